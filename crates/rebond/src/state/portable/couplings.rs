//! The coupling records of a portable snapshot ([`super`], version 5): each coupling's
//! description as given, with its rest length; its warm-start impulses start cold, as the
//! joints' do.

use serde::{Deserialize, Serialize};

use super::{NamedV1, SlotV1, SnapshotV4};
use crate::coupling::{Coupling, CouplingDesc, CouplingSet};
use crate::joint::{JointHandle, JointSet};
use crate::World;

/// Version 5 of a snapshot: version 4's, and the couplings with a scene's names for them.
#[derive(Serialize, Deserialize)]
pub(crate) struct SnapshotV5 {
    pub base: SnapshotV4,
    couplings: Vec<SlotV1<CouplingV5>>,
    free_couplings: Vec<u32>,
    /// Each scene coupling's name and handle, in scene order (empty for a world's state).
    pub coupling_names: Vec<NamedV1>,
}

/// A coupling: its joints by slot (the handles take the slots' generations) and coefficient,
/// limits, spring and rest length.
#[derive(Serialize, Deserialize)]
struct CouplingV5 {
    joints: Vec<(u32, f32)>,
    limits: Option<[f32; 2]>,
    stiffness: f32,
    damping: f32,
    length: Option<f32>,
    /// `l₀`, the given length or `L` when added.
    rest_length: f32,
}

impl SnapshotV5 {
    /// Version 4's records with no couplings: what an earlier snapshot reads as.
    pub fn without_couplings(base: SnapshotV4) -> Self {
        Self {
            base,
            couplings: Vec::new(),
            free_couplings: Vec::new(),
            coupling_names: Vec::new(),
        }
    }

    /// The snapshot of `world`, of a scene's `scene` part and its couplings' `coupling_names`.
    pub fn of(world: &World, scene: Option<super::SceneV1>, coupling_names: Vec<NamedV1>) -> Self {
        let (slots, free) = world.portable_couplings().slots();
        let couplings = slots
            .map(|(generation, coupling)| SlotV1 {
                generation,
                item: coupling.map(CouplingV5::of),
            })
            .collect();
        Self {
            base: SnapshotV4::of(world, scene),
            couplings,
            free_couplings: free.to_vec(),
            coupling_names,
        }
    }

    /// The world of the snapshot with its couplings ([`SnapshotV4::restore_world`]).
    pub fn restore_world(self) -> Result<World, String> {
        let mut world = self.base.restore_world()?;
        let identity = world.identity();
        let joints = world.portable_parts().1;
        let slots = (self.couplings.into_iter().enumerate())
            .map(|(slot, entry)| {
                let coupling = entry
                    .item
                    .map(|coupling| coupling.restore(joints))
                    .transpose()
                    .map_err(|error| format!("coupling {slot}: {error}"))?;
                Ok((entry.generation, coupling))
            })
            .collect::<Result<Vec<_>, String>>()?;
        let couplings = CouplingSet::restored(identity, slots, self.free_couplings)?;
        world.restore_couplings(couplings)?;
        Ok(world)
    }
}

impl CouplingV5 {
    fn of(coupling: &Coupling) -> Self {
        let desc = coupling.desc();
        Self {
            joints: (desc.joints.iter())
                .map(|term| (term.joint.slot() as u32, term.coefficient))
                .collect(),
            limits: desc.limits,
            stiffness: desc.stiffness,
            damping: desc.damping,
            length: desc.length,
            rest_length: coupling.rest_length(),
        }
    }

    fn restore(self, joints: &JointSet) -> Result<Coupling, String> {
        let handle_at = |slot: u32| {
            joints
                .handle_at(slot as usize)
                .ok_or_else(|| format!("joint slot {slot} is empty"))
        };
        let terms = (self.joints.iter())
            .map(|&(slot, coefficient)| Ok((handle_at(slot)?, coefficient)))
            .collect::<Result<Vec<(JointHandle, f32)>, String>>()?;
        let mut desc = CouplingDesc::new(terms);
        desc.limits = self.limits;
        desc.stiffness = self.stiffness;
        desc.damping = self.damping;
        desc.length = self.length;
        Ok(Coupling {
            desc,
            length: self.rest_length,
        })
    }
}
