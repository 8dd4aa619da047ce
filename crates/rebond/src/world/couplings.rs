//! The world's coupling calls (`crate::coupling`): adding, removing and reading couplings of
//! joint coordinates. Couplings join islands through their `IslandLinks` (`island.rs`).

use super::World;
use crate::coupling::{Coupling, CouplingDesc, CouplingHandle};
use crate::error::{check_range, Error, ErrorKind, Result};
use crate::joint::JointType;
use crate::limits::MAX_COORDINATE;

impl World {
    /// Checks `desc` and adds the coupling; wakes the bodies of its joints. Errors name the
    /// field: `joints` (empty), `joints[1].joint` (a stale handle, or a joint that is neither
    /// revolute nor prismatic), `joints[1].coefficient`, `limits`, `stiffness`, `damping`,
    /// `length`; `length` also when `L` now is beyond ±[`MAX_COORDINATE`] and no rest length is
    /// given. On error the world is unchanged.
    pub fn add_coupling(&mut self, desc: CouplingDesc) -> Result<CouplingHandle> {
        desc.validate()?;
        for (index, term) in desc.joints.iter().enumerate() {
            let field = format!("joints[{index}].joint");
            let joint = self
                .joints
                .get(term.joint)
                .ok_or_else(|| Error::new(&field, ErrorKind::StaleJointHandle))?;
            let joint_type = joint.joint_type();
            if !matches!(joint_type, JointType::Revolute | JointType::Prismatic) {
                return Err(Error::new(
                    field,
                    ErrorKind::NotForJointType(joint_type.name()),
                ));
            }
        }
        let length = match desc.length {
            Some(length) => length,
            None => check_range(
                "length",
                self.sum_of_coordinates(&desc)?,
                -MAX_COORDINATE,
                MAX_COORDINATE,
            )?,
        };
        self.wake_coupled(&desc);
        Ok(self.couplings.insert(Coupling { desc, length }))
    }

    /// Removes the coupling and returns it; its handle becomes stale. Wakes the bodies of its
    /// joints.
    pub fn remove_coupling(&mut self, handle: CouplingHandle) -> Result<Coupling> {
        let coupling = self
            .couplings
            .remove(handle)
            .ok_or_else(|| Error::new("", ErrorKind::StaleCouplingHandle))?;
        self.wake_coupled(&coupling.desc);
        Ok(coupling)
    }

    /// The coupling behind `handle`.
    pub fn coupling(&self, handle: CouplingHandle) -> Result<&Coupling> {
        self.couplings
            .get(handle)
            .ok_or_else(|| Error::new("", ErrorKind::StaleCouplingHandle))
    }

    /// The coupling's `L = Σ cᵢ qᵢ` at the bodies' current poses, each `qᵢ` as
    /// [`World::joint_position`] reads it (rad or m).
    pub fn coupling_length(&self, handle: CouplingHandle) -> Result<f32> {
        self.sum_of_coordinates(&self.coupling(handle)?.desc)
    }

    /// All couplings with their handles, in a deterministic order (storage slots).
    pub fn couplings(&self) -> impl Iterator<Item = (CouplingHandle, &Coupling)> {
        self.couplings.iter()
    }

    /// Number of couplings.
    pub fn coupling_count(&self) -> usize {
        self.couplings.len()
    }

    /// `Σ cᵢ qᵢ` of the joints of `desc`, which are live.
    fn sum_of_coordinates(&self, desc: &CouplingDesc) -> Result<f32> {
        desc.joints.iter().try_fold(0.0, |sum, term| {
            Ok(sum + term.coefficient * self.joint_position(term.joint)?)
        })
    }

    /// Wakes the bodies of the joints of `desc` that are live.
    fn wake_coupled(&mut self, desc: &CouplingDesc) {
        for term in &desc.joints {
            let Some(joint) = self.joints.get(term.joint) else {
                continue;
            };
            let (body_a, body_b) = joint.bodies();
            for body in body_a.into_iter().chain([body_b]) {
                self.wake_slot(body.slot());
            }
        }
    }
}
