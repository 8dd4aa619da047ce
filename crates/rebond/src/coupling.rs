//! Couplings: one linear relation between the coordinates of revolute and prismatic joints
//! (MuJoCo's fixed tendons, URDF's `mimic`), `docs/joints.md` ("Couplings").
//!
//! A coupling reads `L = Σ cᵢ qᵢ`, each `qᵢ` the coordinate [`crate::World::joint_position`]
//! reads (rad for a revolute joint, counted across turns; m for a prismatic one), and acts on it
//! through one row on the joints' bodies, `L̇ = Σ cᵢ q̇ᵢ`:
//! - `limits [min, max]` keep `L` within them (one-sided rows at the bound reached, soft position
//!   correction as joint limits have); `min == max` holds `L` at that value (an equality: URDF's
//!   mimic `q_f = m q_l + o` is `[(f, 1), (l, −m)]` with limits `[o, o]`);
//! - a spring `stiffness` `k` and `damping` `d` pulls with `−k (L − l₀) − d L̇` towards the rest
//!   length `l₀` (default: `L` when the coupling is added), spread over the joints by their
//!   coefficients (joint `i` feels `cᵢ` times it).
//!
//! Removing a coupled joint (by hand, or with its body) removes its couplings with it: a
//! coupling never names a missing joint. A coupling one of whose joints broke does nothing until
//! it is removed.

use crate::arena::{Arena, ArenaIndex};
use crate::body::RigidBody;
use crate::error::{check_finite, check_non_negative, check_range, Error, ErrorKind, Result};
use crate::joint::{JointFrames, JointHandle, JointSet, JointType, SidePose};
use crate::limits::{MAX_COORDINATE, MAX_FORCE, MAX_SOLVER_IMPULSE};

/// Largest coefficient magnitude of a coupled joint: a gear ratio beyond it makes the row's
/// effective mass span more than the solver's 32-bit floats resolve.
pub const MAX_COEFFICIENT: f32 = 1.0e3;

/// Names one coupling of a [`crate::World`]; stale once the coupling is removed (by hand, or
/// with one of its joints), as joint handles are.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CouplingHandle(pub(crate) ArenaIndex);

impl CouplingHandle {
    /// The storage slot of the coupling; unique among living couplings.
    pub fn slot(&self) -> usize {
        self.0.slot()
    }
}

/// One coupled joint: its coordinate counts `coefficient` times in `L` (dimensionless for
/// joints of one kind; m/rad or rad/m between a revolute and a prismatic one).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CouplingTerm {
    pub joint: JointHandle,
    pub coefficient: f32,
}

/// What a coupling is made from ([`crate::World::add_coupling`]); module documentation.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CouplingDesc {
    /// The joints and their coefficients, at least one; revolute or prismatic joints. A joint
    /// listed twice counts with the sum of its coefficients.
    pub joints: Vec<CouplingTerm>,
    /// `[min, max]` for `L` (rad or m, as the coordinates), `min ≤ max`; `None` (default):
    /// unlimited.
    pub limits: Option<[f32; 2]>,
    /// Spring stiffness `k` towards `length`, N·m/rad (N/m for prismatic coordinates), ≥ 0,
    /// default 0.
    pub stiffness: f32,
    /// Damping `d` of `L̇`, N·m·s/rad (N·s/m), ≥ 0, default 0.
    pub damping: f32,
    /// The spring's rest length `l₀`; `None` (default): `L` when the coupling is added.
    pub length: Option<f32>,
}

impl CouplingDesc {
    /// A coupling of `joints` (joint, coefficient) with nothing acting yet.
    pub fn new(joints: impl IntoIterator<Item = (JointHandle, f32)>) -> Self {
        Self {
            joints: joints
                .into_iter()
                .map(|(joint, coefficient)| CouplingTerm { joint, coefficient })
                .collect(),
            limits: None,
            stiffness: 0.0,
            damping: 0.0,
            length: None,
        }
    }

    /// Keeps `L` within `[min, max]`; `min == max` is an equality.
    pub fn limits(mut self, min: f32, max: f32) -> Self {
        self.limits = Some([min, max]);
        self
    }

    /// A spring of stiffness `k` and damping `d` on `L`.
    pub fn spring(mut self, stiffness: f32, damping: f32) -> Self {
        self.stiffness = stiffness;
        self.damping = damping;
        self
    }

    /// The spring's rest length `l₀`.
    pub fn length(mut self, length: f32) -> Self {
        self.length = Some(length);
        self
    }

    /// Checks every value but the joints' handles (the world checks those against its joints):
    /// errors name the field (`joints`, `joints[1].coefficient`, `limits`, `stiffness`).
    pub(crate) fn validate(&self) -> Result<()> {
        if self.joints.is_empty() {
            return Err(Error::new("joints", ErrorKind::Missing));
        }
        for (index, term) in self.joints.iter().enumerate() {
            let field = format!("joints[{index}].coefficient");
            check_finite(&field, term.coefficient)?;
            check_range(&field, term.coefficient, -MAX_COEFFICIENT, MAX_COEFFICIENT)?;
        }
        if let Some([min, max]) = self.limits {
            check_finite("limits[0]", min)?;
            check_finite("limits[1]", max)?;
            check_range("limits[0]", min, -MAX_COORDINATE, MAX_COORDINATE)?;
            check_range("limits[1]", max, -MAX_COORDINATE, MAX_COORDINATE)?;
            if min > max {
                return Err(Error::new("limits", ErrorKind::InvertedLimits { min, max }));
            }
        }
        for (field, value) in [("stiffness", self.stiffness), ("damping", self.damping)] {
            check_finite(field, value)?;
            check_non_negative(field, value)?;
            check_range(field, value, 0.0, MAX_FORCE)?;
        }
        if let Some(length) = self.length {
            check_finite("length", length)?;
            check_range("length", length, -MAX_COORDINATE, MAX_COORDINATE)?;
        }
        Ok(())
    }
}

/// A coupling of a world: its description, with the rest length resolved.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Coupling {
    pub(crate) desc: CouplingDesc,
    /// `l₀`: the description's, or `L` when added.
    pub(crate) length: f32,
}

impl Coupling {
    /// The description it was made from.
    pub fn desc(&self) -> &CouplingDesc {
        &self.desc
    }

    /// The spring's rest length `l₀` (rad or m): the one given, or `L` when added.
    pub fn rest_length(&self) -> f32 {
        self.length
    }
}

/// What the solver keeps of a coupling from one step to the next: the warm-start impulses of
/// its row (spring, lower and upper limit), N·m·s or N·s along `L`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct CouplingImpulses {
    pub spring: f32,
    pub lower: f32,
    pub upper: f32,
}

impl CouplingImpulses {
    /// Whether every impulse is finite and at most [`MAX_SOLVER_IMPULSE`], so that it can
    /// warm-start the next step.
    pub fn is_within_limit(&self) -> bool {
        [self.spring, self.lower, self.upper]
            .iter()
            .all(|impulse| impulse.abs() <= MAX_SOLVER_IMPULSE)
    }
}

/// One coupled joint as the step starts: what the solver reads of it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct CoupledJoint {
    pub coefficient: f32,
    pub joint_type: JointType,
    pub frames: JointFrames,
    pub sides: [SidePose; 2],
    /// Revolute joints: the angle counted across turns, rad.
    pub angle: f32,
}

/// Every coupling of a world, with its solver data.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct CouplingSet {
    couplings: Arena<(Coupling, CouplingImpulses)>,
    /// This step's coupled joints of each acting coupling, by coupling slot (rebuilt by
    /// [`CouplingSet::refresh`] as each step starts).
    #[cfg_attr(feature = "serde", serde(skip))]
    acting: Vec<(usize, Vec<CoupledJoint>)>,
}

impl CouplingSet {
    /// No couplings, in the world with identity `world`.
    pub fn new(world: u32) -> Self {
        Self {
            couplings: Arena::new(world),
            acting: Vec::new(),
        }
    }

    pub fn insert(&mut self, coupling: Coupling) -> CouplingHandle {
        CouplingHandle(
            self.couplings
                .insert((coupling, CouplingImpulses::default())),
        )
    }

    pub fn remove(&mut self, handle: CouplingHandle) -> Option<Coupling> {
        self.couplings
            .remove(handle.0)
            .map(|(coupling, _)| coupling)
    }

    pub fn get(&self, handle: CouplingHandle) -> Option<&Coupling> {
        self.couplings.get(handle.0).map(|(coupling, _)| coupling)
    }

    pub fn len(&self) -> usize {
        self.couplings.len()
    }

    /// Every coupling with its handle, in slot order.
    pub fn iter(&self) -> impl Iterator<Item = (CouplingHandle, &Coupling)> {
        self.couplings
            .iter()
            .map(|(index, (coupling, _))| (CouplingHandle(index), coupling))
    }

    /// The couplings that name `joint`, in slot order.
    pub fn couplings_of(&self, joint: JointHandle) -> Vec<CouplingHandle> {
        self.iter()
            .filter(|(_, coupling)| coupling.desc.joints.iter().any(|t| t.joint == joint))
            .map(|(handle, _)| handle)
            .collect()
    }

    /// Reads, as the step starts, each coupling's joints whose every joint still acts: their
    /// frames, angles and the poses of their sides.
    pub fn refresh(&mut self, joints: &JointSet, bodies: &Arena<RigidBody>) {
        let mut count = 0;
        for (index, (coupling, _)) in self.couplings.iter() {
            let terms = &coupling.desc.joints;
            // Without collecting the joints: a steady scene's step allocates nothing.
            let acts = |term: &CouplingTerm| joints.get(term.joint).is_some_and(|j| !j.broken);
            if !terms.iter().all(acts) {
                continue;
            }
            if self.acting.len() == count {
                self.acting.push((0, Vec::new()));
            }
            let (slot, coupled) = &mut self.acting[count];
            *slot = index.slot();
            coupled.clear();
            for (term, joint) in terms.iter().filter_map(|t| Some((t, joints.get(t.joint)?))) {
                let (body_a, body_b) = joint.bodies();
                coupled.push(CoupledJoint {
                    coefficient: term.coefficient,
                    joint_type: joint.joint_type(),
                    frames: joint.frames,
                    sides: [
                        SidePose::of(body_a, bodies),
                        SidePose::of(Some(body_b), bodies),
                    ],
                    angle: joint.angle,
                });
            }
            count += 1;
        }
        self.acting.truncate(count);
    }

    /// This step's acting couplings: slot, coupling, coupled joints and warm-start impulses.
    pub fn acting(
        &self,
    ) -> impl Iterator<Item = (usize, &Coupling, &[CoupledJoint], CouplingImpulses)> {
        self.acting.iter().filter_map(|(slot, coupled)| {
            let (coupling, impulses) = self.couplings.at_slot(*slot)?.1;
            Some((*slot, coupling, coupled.as_slice(), *impulses))
        })
    }

    /// The couplings of a portable snapshot in the world with identity `world`: each slot's
    /// generation and coupling, in slot order, and the free list ([`Arena::from_slots`]), their
    /// impulses cold.
    #[cfg(feature = "serde")]
    pub fn restored(
        world: u32,
        slots: Vec<(u32, Option<Coupling>)>,
        free_slots: Vec<u32>,
    ) -> std::result::Result<Self, String> {
        let slots = (slots.into_iter())
            .map(|(generation, coupling)| {
                let cold = |coupling| (coupling, CouplingImpulses::default());
                (generation, coupling.map(cold))
            })
            .collect();
        Ok(Self {
            couplings: Arena::from_slots(world, slots, free_slots)?,
            acting: Vec::new(),
        })
    }

    /// Every coupling in slot order, empty slots included, with its slot's generation, and the
    /// free list: what a portable snapshot keeps.
    #[cfg(feature = "serde")]
    pub fn slots(&self) -> (impl Iterator<Item = (u32, Option<&Coupling>)>, &[u32]) {
        let slots = (self.couplings.slots())
            .map(|(generation, item)| (generation, item.map(|(coupling, _)| coupling)));
        (slots, self.couplings.free_slots())
    }

    /// Checks decoded couplings: the arena whole, each description valid and naming live
    /// revolute or prismatic joints, its rest length and impulses finite. Describes the first
    /// broken invariant.
    #[cfg(feature = "serde")]
    pub fn check_decoded(&self, joints: &JointSet) -> std::result::Result<(), String> {
        self.couplings.check_decoded()?;
        for (index, (coupling, impulses)) in self.couplings.iter() {
            let slot = index.slot();
            coupling
                .desc
                .validate()
                .map_err(|error| format!("coupling {slot}: {error}"))?;
            let coupled = |term: &CouplingTerm| {
                joints.get(term.joint).is_some_and(|joint| {
                    matches!(
                        joint.joint_type(),
                        JointType::Revolute | JointType::Prismatic
                    )
                })
            };
            if !(coupling.desc.joints.iter().all(coupled)
                && coupling.length.is_finite()
                && impulses.is_within_limit())
            {
                return Err(format!(
                    "coupling {slot} names a missing joint or holds a bad value"
                ));
            }
        }
        Ok(())
    }

    /// The coupling in slot `slot`, its rest length and impulses to write.
    pub fn at_slot_mut(&mut self, slot: usize) -> Option<(&Coupling, &mut CouplingImpulses)> {
        self.couplings
            .at_slot_mut(slot)
            .map(|(coupling, impulses)| (&*coupling, impulses))
    }
}
