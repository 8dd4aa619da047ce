//! The joints of a world: storage, the frames each joint fixes to its bodies, and what the
//! solver keeps of a joint from one step to the next.

use super::{Joint, JointBreakEvent, JointDesc, JointHandle, JointType};
use crate::arena::Arena;
use crate::body::{BodyHandle, RigidBody};
use crate::filter::ordered;
#[cfg(feature = "serde")]
use crate::limits::MAX_SOLVER_IMPULSE;
use crate::math::{normalize_rotation, Quat, Vec3};

/// What a joint fixes to each body when it is added: anchors and axes in each body's frame, and
/// the relative rotation the angles are measured from. The world side (no `body_a`) has the
/// identity pose, so its local values are world values.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct JointFrames {
    /// Anchor on `body_a` from its centre of mass, in its axes, m.
    pub local_anchor_a: Vec3,
    /// Anchor on `body_b` from its centre of mass, in its axes, m.
    pub local_anchor_b: Vec3,
    /// The joint axis in `body_a`'s and in `body_b`'s axes (unit; +X when the joint has none).
    pub local_axis_a: Vec3,
    pub local_axis_b: Vec3,
    /// `q_A⁻¹ q_B` when added: the relative rotation of zero angle.
    pub reference_rotation: Quat,
    /// Generic joints: the joint frame in `body_a`'s axes (identity for the other types).
    pub local_frame_a: Quat,
    /// Distance joints: the rest length, m.
    pub length: f32,
}

/// What the solver keeps of a joint between steps to warm-start it: the impulses of the last
/// substep, world frame, on `body_b` (`body_a` gets the opposite).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct JointImpulses {
    /// Point constraint (fixed, ball, revolute) or the prismatic's perpendicular one, N·s.
    pub linear: Vec3,
    /// Rotation lock (fixed, prismatic) or the hinge's axis alignment, N·m·s.
    pub angular: Vec3,
    /// The distance joint's rigid length or spring, N·s.
    pub axial: f32,
    /// Lower and upper limit (revolute angle, prismatic slide, distance length), N·s or N·m·s.
    pub lower: f32,
    pub upper: f32,
    pub motor: f32,
    /// Ball joints: swing cone and twist limits, N·m·s.
    pub swing: f32,
    pub twist_lower: f32,
    pub twist_upper: f32,
    /// Joint friction: the ball joint's couple, N·m·s.
    pub friction_couple: Vec3,
    /// Joint friction along the revolute or prismatic axis, N·m·s or N·s.
    pub friction: f32,
    /// Generic joints: each axis's lower and upper limit and motor, N·s or N·m·s.
    pub axis_lower: [f32; 6],
    pub axis_upper: [f32; 6],
    pub axis_motor: [f32; 6],
}

impl JointImpulses {
    /// What the rows along a revolute or prismatic axis (spring, limits, motor, friction) give
    /// together, N·m·s or N·s.
    pub fn along_axis(&self) -> f32 {
        self.axial + self.lower - self.upper + self.motor + self.friction
    }

    /// Whether every impulse is at most `limit` long (N·s or N·m·s; NaN is not), so that it can
    /// warm-start the next substep or step.
    pub fn is_within(&self, limit: f32) -> bool {
        [self.linear, self.angular, self.friction_couple]
            .iter()
            .all(|impulse| impulse.abs().max_element() <= limit)
            && [
                self.axial,
                self.lower,
                self.upper,
                self.motor,
                self.swing,
                self.twist_lower,
                self.twist_upper,
                self.friction,
            ]
            .iter()
            .chain(self.axis_lower.iter().chain(&self.axis_upper))
            .chain(&self.axis_motor)
            .all(|impulse| impulse.abs() <= limit)
    }
}

/// A body side of a joint as the step starts: its handle, and its centre of mass and rotation
/// (what the solver uses for a side that does not move this step).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct SidePose {
    pub slot: Option<usize>,
    pub center_of_mass: Vec3,
    pub rotation: Quat,
}

impl SidePose {
    const WORLD: Self = Self {
        slot: None,
        center_of_mass: Vec3::ZERO,
        rotation: Quat::IDENTITY,
    };

    /// The side `handle` (`None` for the world) as it stands now in `bodies`.
    pub fn of(handle: Option<BodyHandle>, bodies: &Arena<RigidBody>) -> Self {
        handle
            .and_then(|handle| bodies.get(handle.0))
            .map_or(Self::WORLD, |body| Self {
                slot: handle.map(|handle| handle.slot()),
                center_of_mass: body.center_of_mass(),
                rotation: body.rotation(),
            })
    }
}

/// Solver data of one joint, beside the joint.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct JointSolverData {
    pub impulses: JointImpulses,
    pub poses: [SidePose; 2],
    /// Impulse on `body_b` summed over the substeps of the last step (linear at its anchor, and
    /// the pure couple), N·s and N·m·s.
    pub step_linear: Vec3,
    pub step_angular: Vec3,
    /// Whether the solver took the joint in the last step (a joint whose bodies are asleep or
    /// static is left out, and keeps reporting its last force).
    pub solved: bool,
}

impl JointSolverData {
    /// A joint's solver data before its first step: nothing to warm-start from.
    const COLD: Self = Self {
        impulses: JointImpulses {
            linear: Vec3::ZERO,
            angular: Vec3::ZERO,
            axial: 0.0,
            lower: 0.0,
            upper: 0.0,
            motor: 0.0,
            swing: 0.0,
            twist_lower: 0.0,
            twist_upper: 0.0,
            friction_couple: Vec3::ZERO,
            friction: 0.0,
            axis_lower: [0.0; 6],
            axis_upper: [0.0; 6],
            axis_motor: [0.0; 6],
        },
        poses: [SidePose::WORLD; 2],
        step_linear: Vec3::ZERO,
        step_angular: Vec3::ZERO,
        solved: false,
    };
}

/// Every joint of a world, with the pairs of bodies that joints keep from colliding.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct JointSet {
    joints: Arena<(Joint, JointSolverData)>,
    /// Pairs of bodies joined by at least one joint without `collide_connected`, smaller handle
    /// first, sorted, with how many such joints join them.
    excluded: Vec<((BodyHandle, BodyHandle), u32)>,
    break_events: Vec<JointBreakEvent>,
}

impl JointSet {
    /// No joints, in the world with identity `world`.
    pub fn new(world: u32) -> Self {
        Self {
            joints: Arena::new(world),
            ..Self::default()
        }
    }

    /// Adds a checked joint whose bodies stand at `pose_a` (`None` for the world) and `pose_b`
    /// (origin position, rotation, centre of mass); `axis` is the unit axis.
    pub fn insert(
        &mut self,
        desc: JointDesc,
        axis: Option<Vec3>,
        body_a: Option<&RigidBody>,
        body_b: &RigidBody,
    ) -> JointHandle {
        let frame = |body: Option<&RigidBody>| match body {
            Some(body) => (body.center_of_mass(), body.rotation()),
            None => (Vec3::ZERO, Quat::IDENTITY),
        };
        let (com_a, rotation_a) = frame(body_a);
        let (com_b, rotation_b) = frame(Some(body_b));
        let anchor_b = desc.anchor_b.unwrap_or(desc.anchor);
        let axis = axis.unwrap_or(Vec3::X);
        let frame = desc
            .frame
            .and_then(|frame| normalize_rotation("frame", frame).ok())
            .unwrap_or(Quat::IDENTITY);
        let frames = JointFrames {
            local_frame_a: (rotation_a.inverse() * frame).normalize(),
            local_anchor_a: rotation_a.inverse() * (desc.anchor - com_a),
            local_anchor_b: rotation_b.inverse() * (anchor_b - com_b),
            local_axis_a: rotation_a.inverse() * axis,
            local_axis_b: rotation_b.inverse() * axis,
            reference_rotation: rotation_a.inverse() * rotation_b,
            length: desc
                .length
                .unwrap_or_else(|| (anchor_b - desc.anchor).length()),
        };
        add_exclusion(&mut self.excluded, &desc);
        let data = JointSolverData::COLD;
        let joint = Joint {
            desc,
            frames,
            force: Vec3::ZERO,
            torque: Vec3::ZERO,
            broken: false,
            angle: 0.0,
        };
        JointHandle(self.joints.insert((joint, data)))
    }

    /// The joints of a portable snapshot in the world with identity `world`: each slot's
    /// generation and joint, in slot order, and the free list ([`Arena::from_slots`]). Their
    /// solver data starts cold; the pairs they keep apart follow from the joints.
    #[cfg(feature = "serde")]
    pub fn restored(
        world: u32,
        slots: Vec<(u32, Option<Joint>)>,
        free_slots: Vec<u32>,
    ) -> Result<Self, String> {
        let slots = slots
            .into_iter()
            .map(|(generation, joint)| {
                (
                    generation,
                    joint.map(|joint| (joint, JointSolverData::COLD)),
                )
            })
            .collect();
        let joints = Arena::from_slots(world, slots, free_slots)?;
        let mut excluded = Vec::new();
        for (_, (joint, _)) in joints.iter() {
            if !joint.broken {
                add_exclusion(&mut excluded, &joint.desc);
            }
        }
        Ok(Self {
            joints,
            excluded,
            break_events: Vec::new(),
        })
    }

    /// Every joint in slot order, empty slots included, with its slot's generation
    /// ([`Arena::slots`]), and the free list: what a portable snapshot keeps.
    #[cfg(feature = "serde")]
    pub fn slots(&self) -> (impl Iterator<Item = (u32, Option<&Joint>)>, &[u32]) {
        let slots = self
            .joints
            .slots()
            .map(|(generation, item)| (generation, item.map(|(joint, _)| joint)));
        (slots, self.joints.free_slots())
    }

    /// Removes a joint and returns it.
    pub fn remove(&mut self, handle: JointHandle) -> Option<Joint> {
        let (joint, _) = self.joints.remove(handle.0)?;
        if !joint.broken {
            release_exclusion(&mut self.excluded, &joint.desc);
        }
        Some(joint)
    }

    /// The handles of the joints of `body`, in slot order.
    pub fn joints_of(&self, body: BodyHandle) -> impl Iterator<Item = JointHandle> + '_ {
        self.joints.iter().filter_map(move |(index, (joint, _))| {
            let (a, b) = (joint.desc.body_a, joint.desc.body_b);
            (a == Some(body) || b == body).then_some(JointHandle(index))
        })
    }

    /// The handle of the live joint in slot `slot`.
    #[cfg(feature = "serde")]
    pub fn handle_at(&self, slot: usize) -> Option<JointHandle> {
        self.joints
            .at_slot(slot)
            .map(|(index, _)| JointHandle(index))
    }

    pub fn get(&self, handle: JointHandle) -> Option<&Joint> {
        self.joints.get(handle.0).map(|(joint, _)| joint)
    }

    pub fn get_mut(&mut self, handle: JointHandle) -> Option<&mut Joint> {
        self.joints.get_mut(handle.0).map(|(joint, _)| joint)
    }

    /// Every joint with its handle, in slot order.
    pub fn iter(&self) -> impl Iterator<Item = (JointHandle, &Joint)> {
        self.joints
            .iter()
            .map(|(index, (joint, _))| (JointHandle(index), joint))
    }

    pub fn len(&self) -> usize {
        self.joints.len()
    }

    /// Whether a joint keeps bodies `a` and `b` from colliding.
    pub fn excludes(&self, a: BodyHandle, b: BodyHandle) -> bool {
        !self.excluded.is_empty()
            && self
                .excluded
                .binary_search_by_key(&ordered(a, b), |&(pair, _)| pair)
                .is_ok()
    }

    /// The pairs of body slots each joint that still acts links (both sides bodies), for the
    /// islands.
    pub fn body_links(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.joints.iter().filter_map(|(_, (joint, _))| {
            let body_a = joint.desc.body_a?;
            (!joint.broken).then(|| (body_a.slot(), joint.desc.body_b.slot()))
        })
    }

    /// Reads the pose of each side of every joint that still acts, for the sides the solver
    /// does not move, and measures every revolute angle across turns (broken joints too, and
    /// joints the solver leaves out: bodies moved by hand, asleep, or kinematic against the
    /// world), so that it is counted on from where the bodies now stand.
    pub fn refresh_poses(&mut self, bodies: &Arena<RigidBody>) {
        for (_, (joint, data)) in self.joints.iter_mut() {
            if joint.desc.joint_type == JointType::Revolute {
                let rotation = |handle: BodyHandle| bodies.get(handle.0).map(RigidBody::rotation);
                if let Some(rotation_b) = rotation(joint.desc.body_b) {
                    let rotation_a = joint.desc.body_a.and_then(rotation);
                    joint.angle = joint.unwrapped_angle(rotation_a, rotation_b);
                }
            }
            if joint.broken {
                continue;
            }
            data.poses = [
                SidePose::of(joint.desc.body_a, bodies),
                SidePose::of(Some(joint.desc.body_b), bodies),
            ];
        }
    }

    /// The joints that still act, with their slots and solver data, in slot order.
    pub fn acting(&self) -> impl Iterator<Item = (usize, &Joint, &JointSolverData)> {
        self.joints
            .iter()
            .filter(|(_, (joint, _))| !joint.broken)
            .map(|(index, (joint, data))| (index.slot(), joint, data))
    }

    /// Checks decoded joints: the arena whole, each joint's description valid, its bodies live
    /// (`is_live`), its frames and solver data finite, and the excluded pairs those of the
    /// joints. Describes the first broken invariant.
    #[cfg(feature = "serde")]
    pub fn check_decoded(&self, is_live: impl Fn(BodyHandle) -> bool) -> Result<(), String> {
        self.joints.check_decoded()?;
        let mut excluded = Vec::new();
        for (index, (joint, data)) in self.joints.iter() {
            let desc = &joint.desc;
            desc.validate()
                .map_err(|error| format!("joint {}: {error}", index.slot()))?;
            let frames = &joint.frames;
            let finite = data.impulses.is_within(MAX_SOLVER_IMPULSE)
                && [
                    data.step_linear,
                    data.step_angular,
                    joint.force,
                    joint.torque,
                ]
                .iter()
                .chain(&[frames.local_anchor_a, frames.local_anchor_b])
                .chain(&[frames.local_axis_a, frames.local_axis_b])
                .all(|vector| vector.is_finite())
                && frames.reference_rotation.is_finite()
                && frames.local_frame_a.is_normalized()
                && frames.length.is_finite()
                && joint.angle.is_finite()
                && data
                    .poses
                    .iter()
                    .all(|pose| pose.center_of_mass.is_finite() && pose.rotation.is_finite());
            if !(finite && desc.body_a.is_none_or(&is_live) && is_live(desc.body_b)) {
                return Err(format!(
                    "joint {} names a missing body or holds a bad value",
                    index.slot()
                ));
            }
            if let (false, false, Some(body_a)) =
                (joint.broken, desc.collide_connected, desc.body_a)
            {
                excluded.push(ordered(body_a, desc.body_b));
            }
        }
        excluded.sort_unstable();
        let counted = excluded
            .chunk_by(|a, b| a == b)
            .map(|run| (run[0], run.len() as u32));
        if !counted.eq(self.excluded.iter().copied()) {
            return Err("the pairs joints keep apart are not those of the joints".to_owned());
        }
        Ok(())
    }

    /// The joint in slot `slot` and its solver data.
    pub fn at_slot_mut(&mut self, slot: usize) -> Option<(&mut Joint, &mut JointSolverData)> {
        self.joints
            .at_slot_mut(slot)
            .map(|(joint, data)| (joint, data))
    }

    /// After the solve: each acting joint's mean force and torque over the step `dt`, and the
    /// joints that break under them.
    pub fn finish_step(&mut self, dt: f32) {
        self.break_events.clear();
        for (index, (joint, data)) in self.joints.iter_mut() {
            if joint.broken || !data.solved {
                continue;
            }
            data.solved = false;
            joint.force = data.step_linear / dt;
            joint.torque = data.step_angular / dt;
            data.step_linear = Vec3::ZERO;
            data.step_angular = Vec3::ZERO;
            if joint.force.length() > joint.desc.break_force
                || joint.torque.length() > joint.desc.break_torque
            {
                self.break_events.push(JointBreakEvent {
                    joint: JointHandle(index),
                    force: joint.force,
                    torque: joint.torque,
                });
                joint.broken = true;
                release_exclusion(&mut self.excluded, &joint.desc);
                joint.force = Vec3::ZERO;
                joint.torque = Vec3::ZERO;
                data.impulses = JointImpulses::default();
            }
        }
    }

    /// The joints that broke in the last step.
    pub fn break_events(&self) -> &[JointBreakEvent] {
        &self.break_events
    }
}

/// Notes that the joint of `desc` keeps its bodies from colliding, unless it lets them collide
/// or joins a body to the world.
fn add_exclusion(excluded: &mut Vec<((BodyHandle, BodyHandle), u32)>, desc: &JointDesc) {
    if let (false, Some(body_a)) = (desc.collide_connected, desc.body_a) {
        let pair = ordered(body_a, desc.body_b);
        match excluded.binary_search_by_key(&pair, |&(pair, _)| pair) {
            Ok(index) => excluded[index].1 += 1,
            Err(index) => excluded.insert(index, (pair, 1)),
        }
    }
}

/// Forgets that the joint of `desc` keeps its bodies from colliding (it went or broke).
fn release_exclusion(excluded: &mut Vec<((BodyHandle, BodyHandle), u32)>, desc: &JointDesc) {
    if let (false, Some(body_a)) = (desc.collide_connected, desc.body_a) {
        let pair = ordered(body_a, desc.body_b);
        if let Ok(index) = excluded.binary_search_by_key(&pair, |&(pair, _)| pair) {
            excluded[index].1 -= 1;
            if excluded[index].1 == 0 {
                excluded.remove(index);
            }
        }
    }
}

impl JointType {
    /// Whether the joint holds its anchor point together (three linear rows).
    pub(crate) fn holds_point(self) -> bool {
        matches!(self, Self::Fixed | Self::Ball | Self::Revolute)
    }

    /// Whether the joint takes a motor (revolute, prismatic).
    pub(crate) fn takes_motor(self) -> bool {
        matches!(self, Self::Revolute | Self::Prismatic)
    }

    /// Whether the joint locks the relative rotation (three angular rows).
    pub(crate) fn locks_rotation(self) -> bool {
        matches!(self, Self::Fixed | Self::Prismatic)
    }
}
