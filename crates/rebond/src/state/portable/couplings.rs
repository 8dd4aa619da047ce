//! The coupling records of a portable snapshot ([`super`], version 4): each coupling's
//! description as given, with its rest length; its warm-start impulses start cold, as the
//! joints' do.

use serde::{Deserialize, Serialize};

use super::SlotV1;
use crate::coupling::{Coupling, CouplingDesc, CouplingSet};
use crate::joint::{JointHandle, JointSet};
use crate::World;

/// A coupling: its joints by slot (the handles take the slots' generations) and coefficient,
/// limits, spring and rest length.
#[derive(Serialize, Deserialize)]
pub(super) struct CouplingV4 {
    joints: Vec<(u32, f32)>,
    limits: Option<[f32; 2]>,
    stiffness: f32,
    damping: f32,
    length: Option<f32>,
    /// `l₀`, the given length or `L` when added.
    rest_length: f32,
}

/// Every coupling slot of `world`, and its free slots.
pub(super) fn records(world: &World) -> (Vec<SlotV1<CouplingV4>>, Vec<u32>) {
    let (slots, free) = world.portable_couplings().slots();
    let couplings = slots
        .map(|(generation, coupling)| SlotV1 {
            generation,
            item: coupling.map(CouplingV4::of),
        })
        .collect();
    (couplings, free.to_vec())
}

/// Gives `world` (its joints restored) the recorded couplings.
pub(super) fn restore(
    world: &mut World,
    couplings: Vec<SlotV1<CouplingV4>>,
    free: Vec<u32>,
) -> Result<(), String> {
    let identity = world.identity();
    let joints = world.portable_parts().1;
    let slots = (couplings.into_iter().enumerate())
        .map(|(slot, entry)| {
            let coupling = entry
                .item
                .map(|coupling| coupling.restore(joints))
                .transpose()
                .map_err(|error| format!("coupling {slot}: {error}"))?;
            Ok((entry.generation, coupling))
        })
        .collect::<Result<Vec<_>, String>>()?;
    let couplings = CouplingSet::restored(identity, slots, free)?;
    world.restore_couplings(couplings)
}

impl CouplingV4 {
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
