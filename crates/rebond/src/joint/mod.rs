//! Joints: constraints that hold two bodies (or a body and the world) together.
//!
//! A joint is described by a [`JointDesc`] with anchors and axes in world coordinates as the
//! bodies stand when it is added; [`crate::World::add_joint`] fixes them to each body then.
//! Angles and slides are measured from that pose: an angle is `body_b`'s rotation relative to
//! `body_a` about the axis, right-handed, counted on across whole turns; a slide is `body_b`'s
//! displacement relative to `body_a` along the axis. [`crate::World::joint_position`] and
//! [`crate::World::joint_velocity`] read them.
//!
//! | type | holds | leaves free |
//! |---|---|---|
//! | [`JointType::Fixed`] | the whole relative pose | nothing |
//! | [`JointType::Ball`] | the anchor point | rotation (optionally within a swing cone and twist limits) |
//! | [`JointType::Revolute`] | the anchor point and the axis direction | rotation about the axis |
//! | [`JointType::Prismatic`] | the relative rotation and the line of the axis | sliding along the axis |
//! | [`JointType::Distance`] | the distance between two anchors | everything else |
//! | [`JointType::Generic`] | each of six axes of a joint frame chosen locked | the axes chosen free or limited |
//!
//! Joints are solved in the same soft step as contacts (`docs/joints.md` gives each one's
//! equations): their velocity constraints are rigid, and their position errors are corrected by a
//! stiff spring ([`crate::WorldSettings::joint_hertz`]). Springs and position motors are soft by
//! design, with the stiffness and damping given.
//!
//! Revolute and prismatic joints also take a passive [`Spring`] on their coordinate
//! (`−k (q − r) − d q̇`, MuJoCo's joint stiffness and damping) and an
//! [`armature`](JointDesc::armature) (an inertia added to the coordinate, MuJoCo's armature).
//!
//! A [generic joint](JointType::Generic) has a frame ([`JointDesc::frame`]) and six axes
//! ([`GenericAxis`]): `x`, `y`, `z`, the slide of `body_b`'s anchor from `body_a`'s along the
//! frame's axes as fixed in `body_a`, and `rx`, `ry`, `rz`, rotations about them. Each is locked,
//! free or limited ([`AxisFreedom`]) and a free or limited one may have a motor
//! ([`JointDesc::motors`]). [`crate::World::generic_joint_coordinates`] reads the six
//! coordinates: the slides, m, and for the rotation `d` of `body_b` relative to `body_a` since
//! the joint was made, in the joint frame (`w ≥ 0`), the angles `2 atan2(dᵢ, d_w)`, rad: each
//! exact when it is the only rotation left free, and the twist–swing decomposition's
//! components otherwise.

mod generic;
mod set;

pub(crate) use generic::GenericFrame;
pub use generic::{AxisFreedom, GenericAxis, GenericCoordinates};

pub(crate) use set::{JointFrames, JointImpulses, JointSet, SidePose};

use crate::arena::ArenaIndex;
use crate::body::BodyHandle;
use crate::error::{
    check_finite, check_finite_vector, check_non_negative, check_position, Error, ErrorKind,
};
use crate::error::{check_non_negative_or_infinite, check_range, Result};
use crate::limits::{MAX_COORDINATE, MAX_FORCE, MAX_SPEED};
use crate::math::{normalize_rotation, Quat, Vec3};
use std::f32::consts::{PI, TAU};

/// Names one joint of a [`crate::World`]. A handle to a removed joint stays invalid forever, even
/// after another joint takes its slot, and a handle of another world is refused
/// ([`crate::ErrorKind::StaleJointHandle`]), as [`BodyHandle`]s are.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct JointHandle(pub(crate) ArenaIndex);

impl JointHandle {
    /// The storage slot of the joint; unique among living joints.
    pub fn slot(&self) -> usize {
        self.0.slot()
    }
}

/// What a joint holds; see the [module documentation](self).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum JointType {
    /// Holds the whole relative pose.
    Fixed,
    /// Holds one point; rotation is free.
    Ball,
    /// Holds one point and an axis; rotation about the axis is free (a hinge).
    Revolute,
    /// Holds the relative rotation and a line; sliding along it is free.
    Prismatic,
    /// Holds the distance between two anchor points.
    Distance,
    /// Holds the axes of a joint frame chosen locked, limits those chosen limited, and leaves
    /// the others free ([`JointDesc::axes`]).
    Generic,
}

impl JointType {
    /// The name the scene format uses: `"fixed"`, `"ball"`, `"revolute"`, `"prismatic"`,
    /// `"distance"`, `"generic"`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Fixed => "fixed",
            Self::Ball => "ball",
            Self::Revolute => "revolute",
            Self::Prismatic => "prismatic",
            Self::Distance => "distance",
            Self::Generic => "generic",
        }
    }
}

/// A motor on a revolute joint's angle or a prismatic joint's slide (the joint's position
/// [`crate::World::joint_position`]; a revolute angle counted across whole turns, so a target of
/// 4π is two turns from where the joint was made).
///
/// Replacing it with [`crate::World::set_joint_motor`] changes only these parameters, so a
/// controller may set it every step.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Motor {
    /// Drives the speed towards `target_velocity` (rad/s or m/s) with at most `max_force`
    /// (N·m or N, ≥ 0; infinity allowed).
    Velocity {
        /// rad/s (revolute) or m/s (prismatic).
        target_velocity: f32,
        /// N·m or N, ≥ 0.
        max_force: f32,
    },
    /// A spring towards `target_position` (rad or m): torque or force
    /// `−stiffness (x − target) − damping ẋ`, at most `max_force`.
    Position {
        /// rad (revolute) or m (prismatic).
        target_position: f32,
        /// N·m/rad or N/m, ≥ 0.
        stiffness: f32,
        /// N·m·s/rad or N·s/m, ≥ 0.
        damping: f32,
        /// N·m or N, ≥ 0; infinity allowed.
        max_force: f32,
    },
    /// An actuator: a torque about the revolute axis (N·m) or a force along the prismatic axis
    /// (N), applied between the two bodies every substep, `+torque` on `body_b` and `−torque` on
    /// `body_a` (right-handed about the axis, or along it), whatever the joint's speed. Alone on
    /// a free joint it gives `θ̈ = torque / I` about the axis.
    Torque {
        /// N·m (revolute) or N (prismatic), either sign, at most [`MAX_FORCE`] in magnitude.
        torque: f32,
    },
}

impl Motor {
    /// A velocity motor: drives the speed to `target_velocity` with at most `max_force`.
    pub fn velocity(target_velocity: f32, max_force: f32) -> Self {
        Self::Velocity {
            target_velocity,
            max_force,
        }
    }

    /// A position motor: a spring of `stiffness` and `damping` towards `target_position`, with at
    /// most `max_force`.
    pub fn position(target_position: f32, stiffness: f32, damping: f32, max_force: f32) -> Self {
        Self::Position {
            target_position,
            stiffness,
            damping,
            max_force,
        }
    }

    /// A torque motor: `torque` (N·m about a revolute axis, N along a prismatic one) between the
    /// two bodies every substep.
    pub fn torque(torque: f32) -> Self {
        Self::Torque { torque }
    }

    fn validate(&self) -> Result<()> {
        match *self {
            Self::Velocity {
                target_velocity,
                max_force,
            } => {
                check_range("target_velocity", target_velocity, -MAX_SPEED, MAX_SPEED)?;
                check_force_limit("max_force", max_force)?;
            }
            Self::Position {
                target_position,
                stiffness,
                damping,
                max_force,
            } => {
                check_range(
                    "target_position",
                    target_position,
                    -MAX_COORDINATE,
                    MAX_COORDINATE,
                )?;
                check_up_to("stiffness", stiffness, MAX_FORCE)?;
                check_up_to("damping", damping, MAX_FORCE)?;
                check_force_limit("max_force", max_force)?;
            }
            Self::Torque { torque } => {
                check_range("torque", torque, -MAX_FORCE, MAX_FORCE)?;
            }
        }
        Ok(())
    }

    /// Checks a motor for a joint of `joint_type`: that the type takes one (revolute,
    /// prismatic), then its values; an error names `motor` or the field within it.
    pub(crate) fn check_for(&self, joint_type: JointType) -> Result<()> {
        if !joint_type.takes_motor() {
            return Err(Error::new(
                "motor",
                ErrorKind::NotForJointType(joint_type.name()),
            ));
        }
        self.validate().map_err(|error| error.within("motor"))
    }
}

/// A joint's spring and damper on its coordinate. On a distance joint: force
/// `−stiffness (d − length) − damping ḋ` along the line of the anchors, instead of a rigid
/// length. On a revolute or prismatic joint: a passive torque or force
/// `−stiffness (q − reference) − damping q̇` on the coordinate `q` of
/// [`crate::World::joint_position`] (MuJoCo's joint `stiffness`, `springref` and `damping`),
/// beside any motor; `stiffness` 0 is pure joint damping. It is integrated implicitly, so a
/// stiff spring on a light body stays stable.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Spring {
    /// N/m (distance, prismatic) or N·m/rad (revolute), ≥ 0.
    pub stiffness: f32,
    /// N·s/m or N·m·s/rad, ≥ 0.
    pub damping: f32,
    /// Revolute and prismatic joints: the coordinate the spring rests at, rad or m, within
    /// ±[`MAX_COORDINATE`]; default 0 (the pose the joint was made at). Distance joints rest at
    /// `length` and take 0 here.
    pub reference: f32,
}

/// Everything needed to create a joint. Values are checked when the joint is added to a world;
/// an error names the field (`axis`, `motor.max_force`, ...).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct JointDesc {
    /// What the joint holds.
    pub joint_type: JointType,
    /// The first body, or `None` for a fixed point of the world.
    pub body_a: Option<BodyHandle>,
    /// The second body; forces and torques are reported as applied to it.
    pub body_b: BodyHandle,
    /// World point where the joint holds the bodies together, metres (for a distance joint: the
    /// point on `body_a`).
    pub anchor: Vec3,
    /// Distance joints: the world point on `body_b`, metres; `None` for `anchor`.
    pub anchor_b: Option<Vec3>,
    /// Unit world direction (normalised when added): the hinge axis (revolute), the slide axis
    /// (prismatic), the twist axis (ball with a swing or twist limit).
    pub axis: Option<Vec3>,
    /// `[min, max]`: radians about the axis (revolute: of the angle counted across whole turns,
    /// so `[−2π, 2π]` allows two turns either way), metres along it (prismatic), metres of
    /// length (distance; `[0, L]` is a rope); within ±[`MAX_COORDINATE`].
    pub limits: Option<[f32; 2]>,
    /// Ball joints: largest angle between the twist axis fixed in `body_a` and the one fixed in
    /// `body_b`, radians, 0 to π.
    pub swing_limit: Option<f32>,
    /// Ball joints: `[min, max]` radians of twist about the axis, within ±π.
    pub twist_limits: Option<[f32; 2]>,
    /// Revolute and prismatic joints: a motor on the angle or slide.
    pub motor: Option<Motor>,
    /// Distance joints: rest length, m, ≥ 0; `None` for the anchors' distance when added.
    pub length: Option<f32>,
    /// Distance joints: a spring instead of a rigid length. Revolute and prismatic joints: a
    /// passive spring and damper on the coordinate, towards [`Spring::reference`].
    pub spring: Option<Spring>,
    /// Revolute and prismatic joints: an inertia added to the joint's coordinate, kg·m² about
    /// the hinge or kg along the slide, ≥ 0, default 0 (MuJoCo's `armature`: a rotor geared to
    /// the joint). Each substep the joint's rate keeps the rotor's, which resists a change of it
    /// with this inertia: a torque `τ` on a free hinge gives `θ̈ = τ / (I + armature)`.
    pub armature: f32,
    /// Generic joints: the world rotation of the joint frame when added; `None` for the
    /// identity. Its axes, fixed in `body_a` then, are those of [`GenericAxis`].
    pub frame: Option<Quat>,
    /// Generic joints: each axis locked (the default), free or limited, in the order of
    /// [`GenericAxis::ALL`].
    pub axes: [AxisFreedom; 6],
    /// Generic joints: a motor on each free or limited axis (a torque motor's `torque` is a
    /// force, N, on a slide), in the order of [`GenericAxis::ALL`].
    pub motors: [Option<Motor>; 6],
    /// Ball, revolute and prismatic joints: the most torque (N·m; prismatic: force, N) the
    /// joint's own friction opposes relative motion with, ≥ 0, default 0. Coulomb friction on the
    /// free motion: the joint holds still under a smaller load and slides against this one
    /// under a larger, `|τ| ≤ friction` (ball: the couple's magnitude).
    pub friction: f32,
    /// Whether the two bodies still collide with each other, default false.
    pub collide_connected: bool,
    /// The joint breaks for good in the step its force on `body_b` exceeds this, N, ≥ 0;
    /// default infinity (unbreakable).
    pub break_force: f32,
    /// The same for its torque, N·m.
    pub break_torque: f32,
}

impl JointDesc {
    /// A joint of `joint_type` between `body_a` (a body, or `None` for the world) and `body_b`,
    /// holding at `anchor` (world point, m), with nothing else set.
    pub fn new(
        joint_type: JointType,
        body_a: impl Into<Option<BodyHandle>>,
        body_b: BodyHandle,
        anchor: Vec3,
    ) -> Self {
        Self {
            joint_type,
            body_a: body_a.into(),
            body_b,
            anchor,
            anchor_b: None,
            axis: None,
            limits: None,
            swing_limit: None,
            twist_limits: None,
            motor: None,
            length: None,
            spring: None,
            armature: 0.0,
            frame: None,
            axes: [AxisFreedom::Locked; 6],
            motors: [None; 6],
            friction: 0.0,
            collide_connected: false,
            break_force: f32::INFINITY,
            break_torque: f32::INFINITY,
        }
    }

    /// Holds the whole relative pose of the bodies as it is when added.
    pub fn fixed(body_a: impl Into<Option<BodyHandle>>, body_b: BodyHandle, anchor: Vec3) -> Self {
        Self::new(JointType::Fixed, body_a, body_b, anchor)
    }

    /// Holds the bodies together at `anchor`; rotation is free.
    pub fn ball(body_a: impl Into<Option<BodyHandle>>, body_b: BodyHandle, anchor: Vec3) -> Self {
        Self::new(JointType::Ball, body_a, body_b, anchor)
    }

    /// A hinge at `anchor` about `axis` (world direction).
    pub fn revolute(
        body_a: impl Into<Option<BodyHandle>>,
        body_b: BodyHandle,
        anchor: Vec3,
        axis: Vec3,
    ) -> Self {
        Self::new(JointType::Revolute, body_a, body_b, anchor).axis(axis)
    }

    /// A slider along `axis` (world direction) through `anchor`.
    pub fn prismatic(
        body_a: impl Into<Option<BodyHandle>>,
        body_b: BodyHandle,
        anchor: Vec3,
        axis: Vec3,
    ) -> Self {
        Self::new(JointType::Prismatic, body_a, body_b, anchor).axis(axis)
    }

    /// Holds the distance between `anchor_a` on `body_a` and `anchor_b` on `body_b` (world
    /// points), rigid at their distance when added unless [`length`](Self::length),
    /// [`limits`](Self::limits) or [`spring`](Self::spring) say otherwise.
    pub fn distance(
        body_a: impl Into<Option<BodyHandle>>,
        body_b: BodyHandle,
        anchor_a: Vec3,
        anchor_b: Vec3,
    ) -> Self {
        let mut desc = Self::new(JointType::Distance, body_a, body_b, anchor_a);
        desc.anchor_b = Some(anchor_b);
        desc
    }

    /// A generic joint at `anchor` with the identity frame and every axis locked; see
    /// [`frame`](Self::frame), [`free`](Self::free), [`limit`](Self::limit) and
    /// [`axis_motor`](Self::axis_motor).
    pub fn generic(
        body_a: impl Into<Option<BodyHandle>>,
        body_b: BodyHandle,
        anchor: Vec3,
    ) -> Self {
        Self::new(JointType::Generic, body_a, body_b, anchor)
    }

    /// Sets [`frame`](Self::frame).
    pub fn frame(mut self, frame: Quat) -> Self {
        self.frame = Some(frame);
        self
    }

    /// Frees one axis of a generic joint ([`axes`](Self::axes)).
    pub fn free(mut self, axis: GenericAxis) -> Self {
        self.axes[axis.index()] = AxisFreedom::Free;
        self
    }

    /// Limits one axis of a generic joint to `[min, max]` ([`axes`](Self::axes)).
    pub fn limit(mut self, axis: GenericAxis, min: f32, max: f32) -> Self {
        self.axes[axis.index()] = AxisFreedom::Limited([min, max]);
        self
    }

    /// Sets the motor of one axis of a generic joint ([`motors`](Self::motors)).
    pub fn axis_motor(mut self, axis: GenericAxis, motor: Motor) -> Self {
        self.motors[axis.index()] = Some(motor);
        self
    }

    /// Sets [`axis`](Self::axis).
    pub fn axis(mut self, axis: Vec3) -> Self {
        self.axis = Some(axis);
        self
    }

    /// Sets [`limits`](Self::limits).
    pub fn limits(mut self, min: f32, max: f32) -> Self {
        self.limits = Some([min, max]);
        self
    }

    /// Sets [`swing_limit`](Self::swing_limit).
    pub fn swing_limit(mut self, angle: f32) -> Self {
        self.swing_limit = Some(angle);
        self
    }

    /// Sets [`twist_limits`](Self::twist_limits).
    pub fn twist_limits(mut self, min: f32, max: f32) -> Self {
        self.twist_limits = Some([min, max]);
        self
    }

    /// Sets [`motor`](Self::motor).
    pub fn motor(mut self, motor: Motor) -> Self {
        self.motor = Some(motor);
        self
    }

    /// Sets [`length`](Self::length).
    pub fn length(mut self, length: f32) -> Self {
        self.length = Some(length);
        self
    }

    /// Sets [`spring`](Self::spring).
    pub fn spring(self, stiffness: f32, damping: f32) -> Self {
        self.spring_to(stiffness, damping, 0.0)
    }

    /// Sets [`spring`](Self::spring) with its [`reference`](Spring::reference) (revolute and
    /// prismatic joints).
    pub fn spring_to(mut self, stiffness: f32, damping: f32, reference: f32) -> Self {
        self.spring = Some(Spring {
            stiffness,
            damping,
            reference,
        });
        self
    }

    /// Sets [`armature`](Self::armature).
    pub fn armature(mut self, armature: f32) -> Self {
        self.armature = armature;
        self
    }

    /// Sets [`friction`](Self::friction).
    pub fn friction(mut self, friction: f32) -> Self {
        self.friction = friction;
        self
    }

    /// Sets [`collide_connected`](Self::collide_connected).
    pub fn collide_connected(mut self, collide: bool) -> Self {
        self.collide_connected = collide;
        self
    }

    /// Sets [`break_force`](Self::break_force).
    pub fn break_force(mut self, force: f32) -> Self {
        self.break_force = force;
        self
    }

    /// Sets [`break_torque`](Self::break_torque).
    pub fn break_torque(mut self, torque: f32) -> Self {
        self.break_torque = torque;
        self
    }

    /// Checks every value and that each field set belongs to the joint type; returns the unit
    /// axis.
    pub(crate) fn validate(&self) -> Result<Option<Vec3>> {
        let kind = self.joint_type;
        let only = |field: &str, set: bool, allowed: &[JointType]| {
            if set && !allowed.contains(&kind) {
                Err(Error::new(field, ErrorKind::NotForJointType(kind.name())))
            } else {
                Ok(())
            }
        };
        use JointType::{Ball, Distance, Generic, Prismatic, Revolute};
        only("anchor_b", self.anchor_b.is_some(), &[Distance])?;
        only("armature", self.armature != 0.0, &[Revolute, Prismatic])?;
        only("frame", self.frame.is_some(), &[Generic])?;
        let axes_set = self.axes.iter().any(|freedom| freedom.moves());
        only("axes", axes_set, &[Generic])?;
        only(
            "motors",
            self.motors.iter().any(Option::is_some),
            &[Generic],
        )?;
        only("axis", self.axis.is_some(), &[Ball, Revolute, Prismatic])?;
        only(
            "limits",
            self.limits.is_some(),
            &[Revolute, Prismatic, Distance],
        )?;
        only("swing_limit", self.swing_limit.is_some(), &[Ball])?;
        only("twist_limits", self.twist_limits.is_some(), &[Ball])?;
        only("length", self.length.is_some(), &[Distance])?;
        only(
            "spring",
            self.spring.is_some(),
            &[Distance, Revolute, Prismatic],
        )?;
        only(
            "friction",
            self.friction != 0.0,
            &[Ball, Revolute, Prismatic],
        )?;
        check_position("anchor", self.anchor)?;
        if let Some(anchor_b) = self.anchor_b {
            check_position("anchor_b", anchor_b)?;
        }
        let needs_axis = matches!(kind, Revolute | Prismatic)
            || self.swing_limit.is_some()
            || self.twist_limits.is_some();
        let axis = match self.axis {
            Some(axis) => {
                check_finite_vector("axis", axis)?;
                let unit = axis.normalize_or_zero();
                if unit == Vec3::ZERO || !unit.is_finite() {
                    return Err(Error::new("axis", ErrorKind::ZeroVector));
                }
                Some(unit)
            }
            None if needs_axis => return Err(Error::new("axis", ErrorKind::Missing)),
            None => None,
        };
        if let Some(limits) = self.limits {
            match kind {
                Distance => {
                    check_non_negative("limits[0]", limits[0])?;
                    check_interval("limits", limits, Some((0.0, MAX_COORDINATE)))?;
                }
                _ => check_interval("limits", limits, Some((-MAX_COORDINATE, MAX_COORDINATE)))?,
            }
        }
        if let Some(angle) = self.swing_limit {
            check_range("swing_limit", angle, 0.0, PI)?;
        }
        if let Some(limits) = self.twist_limits {
            check_interval("twist_limits", limits, Some((-PI, PI)))?;
        }
        if let Some(motor) = &self.motor {
            motor.check_for(kind)?;
        }
        if let Some(length) = self.length {
            check_up_to("length", length, MAX_COORDINATE)?;
        }
        if let Some(spring) = &self.spring {
            check_up_to("spring.stiffness", spring.stiffness, MAX_FORCE)?;
            check_up_to("spring.damping", spring.damping, MAX_FORCE)?;
            if kind == Distance && spring.reference != 0.0 {
                return Err(Error::new(
                    "spring.reference",
                    ErrorKind::NotForJointType(kind.name()),
                ));
            }
            check_range(
                "spring.reference",
                spring.reference,
                -MAX_COORDINATE,
                MAX_COORDINATE,
            )?;
        }
        check_up_to("armature", self.armature, MAX_FORCE)?;
        if let Some(frame) = self.frame {
            normalize_rotation("frame", frame)?;
        }
        for axis in GenericAxis::ALL {
            let (freedom, motor) = (self.axes[axis.index()], self.motors[axis.index()]);
            if let AxisFreedom::Limited(limits) = freedom {
                let most = if axis.is_rotation() {
                    PI
                } else {
                    MAX_COORDINATE
                };
                check_interval(
                    &format!("axes.{}", axis.name()),
                    limits,
                    Some((-most, most)),
                )?;
            }
            if let Some(motor) = motor {
                let field = format!("motors.{}", axis.name());
                if !freedom.moves() {
                    return Err(Error::new(field, ErrorKind::LockedAxis));
                }
                motor.validate().map_err(|error| error.within(&field))?;
            }
        }
        check_up_to("friction", self.friction, MAX_FORCE)?;
        check_non_negative_or_infinite("break_force", self.break_force)?;
        check_non_negative_or_infinite("break_torque", self.break_torque)?;
        if self.body_a == Some(self.body_b) {
            return Err(Error::new("body_b", ErrorKind::JointToItself));
        }
        Ok(axis)
    }
}

/// Checks that `value` is not negative, then that it is at most `max`.
fn check_up_to(field: &str, value: f32, max: f32) -> Result<f32> {
    check_non_negative(field, value)?;
    check_range(field, value, 0.0, max)
}

/// Checks a force limit: infinite (no limit), or from 0 to [`MAX_FORCE`].
fn check_force_limit(field: &str, value: f32) -> Result<f32> {
    check_non_negative_or_infinite(field, value)?;
    if value == f32::INFINITY {
        Ok(value)
    } else {
        check_range(field, value, 0.0, MAX_FORCE)
    }
}

/// Checks a `[min, max]` pair: both finite, within `range` when one is given, and `min ≤ max`.
fn check_interval(field: &str, [min, max]: [f32; 2], range: Option<(f32, f32)>) -> Result<()> {
    for (index, value) in [min, max].into_iter().enumerate() {
        let field = format!("{field}[{index}]");
        match range {
            Some((low, high)) => check_range(&field, value, low, high)?,
            None => check_finite(&field, value)?,
        };
    }
    if min > max {
        return Err(Error::new(field, ErrorKind::InvertedLimits { min, max }));
    }
    Ok(())
}

/// A joint in a world: its description, the frames it holds fixed to each body, and what it did
/// in the last step.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Joint {
    pub(crate) desc: JointDesc,
    pub(crate) frames: JointFrames,
    /// Mean force and torque (about the anchor on `body_b`) on `body_b` over the last step,
    /// world frame, N and N·m.
    pub(crate) force: Vec3,
    pub(crate) torque: Vec3,
    pub(crate) broken: bool,
    /// Revolute joints: the angle counted across whole turns where it was last measured (each
    /// substep the joint is solved, and as each step starts), rad; the next measure is the wrapped
    /// angle plus the whole turns that bring it nearest to this one.
    pub(crate) angle: f32,
}

impl Joint {
    /// What the joint holds.
    pub fn joint_type(&self) -> JointType {
        self.desc.joint_type
    }

    /// The joined bodies: `body_a` (`None` for the world) and `body_b`.
    pub fn bodies(&self) -> (Option<BodyHandle>, BodyHandle) {
        (self.desc.body_a, self.desc.body_b)
    }

    /// The description the joint was made from (anchors and axes in the world frame of the
    /// moment it was added), with its current motor.
    pub fn desc(&self) -> &JointDesc {
        &self.desc
    }

    /// Mean force the joint applied to `body_b` over the last step, world frame, N; zero once
    /// broken.
    pub fn force(&self) -> Vec3 {
        self.force
    }

    /// Mean torque the joint applied to `body_b` over the last step about its anchor on
    /// `body_b`, world frame, N·m; zero once broken.
    pub fn torque(&self) -> Vec3 {
        self.torque
    }

    /// Whether the joint broke (its force or torque went past its break value); a broken joint
    /// no longer acts.
    pub fn is_broken(&self) -> bool {
        self.broken
    }

    /// The anchors on `body_a` and `body_b` and the joint axis as fixed in each, world frame, for
    /// the bodies' poses `(centre of mass, rotation)` (`None` for the world).
    pub(crate) fn world_frames(
        &self,
        pose_a: Option<(Vec3, Quat)>,
        (center_b, rotation_b): (Vec3, Quat),
    ) -> JointPlacement {
        let (center_a, rotation_a) = pose_a.unwrap_or((Vec3::ZERO, Quat::IDENTITY));
        let frames = &self.frames;
        JointPlacement {
            anchor_a: center_a + rotation_a * frames.local_anchor_a,
            anchor_b: center_b + rotation_b * frames.local_anchor_b,
            axis_a: rotation_a * frames.local_axis_a,
            axis_b: rotation_b * frames.local_axis_b,
        }
    }

    /// The revolute angle counted across whole turns at the bodies' rotations (`None` for the
    /// world), rad: the wrapped angle brought within half a turn of the last measure.
    pub(crate) fn unwrapped_angle(&self, rotation_a: Option<Quat>, rotation_b: Quat) -> f32 {
        let relative = relative_rotation(
            &self.frames,
            rotation_a.unwrap_or(Quat::IDENTITY),
            rotation_b,
        );
        unwrap_angle(twist_angle(relative, self.frames.local_axis_a), self.angle)
    }
}

/// `d = q_A⁻¹ q_B q₀⁻¹`, the rotation of B relative to A since the joint was made, in A's frame,
/// taken with `w ≥ 0`.
pub(crate) fn relative_rotation(frames: &JointFrames, rotation_a: Quat, rotation_b: Quat) -> Quat {
    let relative = rotation_a.inverse() * rotation_b * frames.reference_rotation.inverse();
    if relative.w < 0.0 {
        -relative
    } else {
        relative
    }
}

/// The angle of `relative` (`w ≥ 0`) about the unit `axis` of its frame,
/// `2 atan2(d_xyz·a, d_w)`, in `(−π, π]`, rad.
pub(crate) fn twist_angle(relative: Quat, axis: Vec3) -> f32 {
    2.0 * Vec3::new(relative.x, relative.y, relative.z)
        .dot(axis)
        .atan2(relative.w)
}

/// `angle + 2πk`, the whole number of turns `k` that brings it nearest to `previous`, rad: the
/// angle counted across turns, exact while it changes by less than half a turn between measures.
pub(crate) fn unwrap_angle(angle: f32, previous: f32) -> f32 {
    angle + TAU * ((previous - angle) / TAU).round()
}

/// Where a joint stands now, world frame: what [`crate::World::joint_placement`] returns.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct JointPlacement {
    /// The anchor fixed to `body_a` (or the world point), m.
    pub anchor_a: Vec3,
    /// The anchor fixed to `body_b`, m; for every joint type but distance, the joint holds it on
    /// `anchor_a`, so `|anchor_b − anchor_a|` is how far the joint has come apart.
    pub anchor_b: Vec3,
    /// The joint axis as fixed to `body_a` and to `body_b` (unit; +X for a joint without an
    /// axis). A revolute joint keeps them equal.
    pub axis_a: Vec3,
    pub axis_b: Vec3,
}

/// A joint that broke during the last step, with the force and torque that broke it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct JointBreakEvent {
    /// The joint; it stays in the world, broken, until removed.
    pub joint: JointHandle,
    /// Mean force on `body_b` over the step it broke in, N.
    pub force: Vec3,
    /// Mean torque on `body_b` about its anchor over that step, N·m.
    pub torque: Vec3,
}

/// `docs/joints.md`'s examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../../../../docs/joints.md")]
pub struct JointsDocDoctests;
