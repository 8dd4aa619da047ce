//! The joint records of a portable snapshot ([`super`]): a joint's description as given, the
//! frames it holds fixed in each body, and its state.

use serde::{Deserialize, Serialize};

use crate::body::BodyHandle;
use crate::joint::{AxisFreedom, Joint, JointDesc, JointFrames, JointType, Motor, Spring};
use crate::math::{Quat, Vec3};

#[derive(Serialize, Deserialize)]
enum JointTypeV1 {
    Fixed,
    Ball,
    Revolute,
    Prismatic,
    Distance,
}

#[derive(Serialize, Deserialize)]
enum MotorV1 {
    Velocity {
        target_velocity: f32,
        max_force: f32,
    },
    Position {
        target_position: f32,
        stiffness: f32,
        damping: f32,
        max_force: f32,
    },
    Torque {
        torque: f32,
    },
}

/// A joint: its description as given (world anchors of the moment it was added), the frames it
/// holds fixed in each body (what it acts on), and its state.
#[derive(Serialize, Deserialize)]
pub(super) struct JointV1 {
    joint_type: JointTypeV1,
    /// Body slots; the handles take the slots' generations.
    body_a: Option<u32>,
    body_b: u32,
    anchor: [f32; 3],
    anchor_b: Option<[f32; 3]>,
    axis: Option<[f32; 3]>,
    limits: Option<[f32; 2]>,
    swing_limit: Option<f32>,
    twist_limits: Option<[f32; 2]>,
    motor: Option<MotorV1>,
    length: Option<f32>,
    /// Stiffness (N/m) and damping (N·s/m).
    spring: Option<[f32; 2]>,
    friction: f32,
    collide_connected: bool,
    break_force: f32,
    break_torque: f32,
    /// Anchors from each body's centre of mass and axes, in its axes; `q_A⁻¹ q_B` of zero angle;
    /// the distance joint's rest length, m.
    local_anchor_a: [f32; 3],
    local_anchor_b: [f32; 3],
    local_axis_a: [f32; 3],
    local_axis_b: [f32; 3],
    reference_rotation: [f32; 4],
    rest_length: f32,
    /// The last step's mean force (N) and torque (N·m) on `body_b`.
    force: [f32; 3],
    torque: [f32; 3],
    broken: bool,
    /// Revolute joints: the angle counted across whole turns, rad.
    angle: f32,
}

impl JointV1 {
    pub(super) fn of(joint: &Joint) -> Self {
        let desc = &joint.desc;
        let frames = &joint.frames;
        Self {
            joint_type: match desc.joint_type {
                JointType::Fixed => JointTypeV1::Fixed,
                JointType::Ball => JointTypeV1::Ball,
                JointType::Revolute => JointTypeV1::Revolute,
                JointType::Prismatic => JointTypeV1::Prismatic,
                JointType::Distance => JointTypeV1::Distance,
                // Version 1 has no generic joint: its record says fixed, and the joint's
                // extras ([`JointExtrasV4`]) make it generic again.
                JointType::Generic => JointTypeV1::Fixed,
            },
            body_a: desc.body_a.map(|body| body.slot() as u32),
            body_b: desc.body_b.slot() as u32,
            anchor: desc.anchor.to_array(),
            anchor_b: desc.anchor_b.map(|anchor| anchor.to_array()),
            axis: desc.axis.map(|axis| axis.to_array()),
            limits: desc.limits,
            swing_limit: desc.swing_limit,
            twist_limits: desc.twist_limits,
            motor: desc.motor.map(MotorV1::of),
            length: desc.length,
            spring: desc.spring.map(|spring| [spring.stiffness, spring.damping]),
            friction: desc.friction,
            collide_connected: desc.collide_connected,
            break_force: desc.break_force,
            break_torque: desc.break_torque,
            local_anchor_a: frames.local_anchor_a.to_array(),
            local_anchor_b: frames.local_anchor_b.to_array(),
            local_axis_a: frames.local_axis_a.to_array(),
            local_axis_b: frames.local_axis_b.to_array(),
            reference_rotation: frames.reference_rotation.to_array(),
            rest_length: frames.length,
            force: joint.force.to_array(),
            torque: joint.torque.to_array(),
            broken: joint.broken,
            angle: joint.angle,
        }
    }

    /// The joint of the record, its bodies' handles from `handle_at` (by slot). Its values are
    /// checked with the world's ([`crate::World::restored`]).
    pub(super) fn restore(
        self,
        handle_at: impl Fn(u32) -> Result<BodyHandle, String>,
    ) -> Result<Joint, String> {
        let desc = JointDesc {
            joint_type: match self.joint_type {
                JointTypeV1::Fixed => JointType::Fixed,
                JointTypeV1::Ball => JointType::Ball,
                JointTypeV1::Revolute => JointType::Revolute,
                JointTypeV1::Prismatic => JointType::Prismatic,
                JointTypeV1::Distance => JointType::Distance,
            },
            body_a: self.body_a.map(&handle_at).transpose()?,
            body_b: handle_at(self.body_b)?,
            anchor: Vec3::from_array(self.anchor),
            anchor_b: self.anchor_b.map(Vec3::from_array),
            axis: self.axis.map(Vec3::from_array),
            limits: self.limits,
            swing_limit: self.swing_limit,
            twist_limits: self.twist_limits,
            motor: self.motor.map(MotorV1::restore),
            length: self.length,
            spring: self.spring.map(|[stiffness, damping]| Spring {
                stiffness,
                damping,
                reference: 0.0,
            }),
            friction: self.friction,
            collide_connected: self.collide_connected,
            break_force: self.break_force,
            break_torque: self.break_torque,
            armature: 0.0,
            frame: None,
            axes: [AxisFreedom::Locked; 6],
            motors: [None; 6],
        };
        Ok(Joint {
            desc,
            frames: JointFrames {
                local_anchor_a: Vec3::from_array(self.local_anchor_a),
                local_anchor_b: Vec3::from_array(self.local_anchor_b),
                local_axis_a: Vec3::from_array(self.local_axis_a),
                local_axis_b: Vec3::from_array(self.local_axis_b),
                reference_rotation: Quat::from_array(self.reference_rotation),
                local_frame_a: Quat::IDENTITY,
                length: self.rest_length,
            },
            force: Vec3::from_array(self.force),
            torque: Vec3::from_array(self.torque),
            broken: self.broken,
            angle: self.angle,
        })
    }
}

impl MotorV1 {
    fn of(motor: Motor) -> Self {
        match motor {
            Motor::Velocity {
                target_velocity,
                max_force,
            } => Self::Velocity {
                target_velocity,
                max_force,
            },
            Motor::Position {
                target_position,
                stiffness,
                damping,
                max_force,
            } => Self::Position {
                target_position,
                stiffness,
                damping,
                max_force,
            },
            Motor::Torque { torque } => Self::Torque { torque },
        }
    }

    fn restore(self) -> Motor {
        match self {
            Self::Velocity {
                target_velocity,
                max_force,
            } => Motor::Velocity {
                target_velocity,
                max_force,
            },
            Self::Position {
                target_position,
                stiffness,
                damping,
                max_force,
            } => Motor::Position {
                target_position,
                stiffness,
                damping,
                max_force,
            },
            Self::Torque { torque } => Motor::Torque { torque },
        }
    }
}

/// What version 4 adds to a joint's record ([`JointV1`]): the spring's reference and the
/// armature (revolute, prismatic), and a generic joint's frame, axes and motors.
#[derive(Serialize, Deserialize)]
pub(super) struct JointExtrasV4 {
    /// The joint's slot.
    pub(super) slot: u32,
    /// rad or m.
    spring_reference: f32,
    /// kg·m² or kg.
    armature: f32,
    generic: Option<GenericV4>,
}

/// A generic joint's own fields.
#[derive(Serialize, Deserialize)]
struct GenericV4 {
    /// The frame as given, world rotation of the moment it was added.
    frame: Option<[f32; 4]>,
    /// The frame in `body_a`'s axes.
    local_frame_a: [f32; 4],
    /// In the order x, y, z, rx, ry, rz.
    axes: [AxisV4; 6],
    motors: [Option<MotorV1>; 6],
}

#[derive(Serialize, Deserialize)]
enum AxisV4 {
    Locked,
    Free,
    Limited([f32; 2]),
}

impl JointExtrasV4 {
    /// The extras of the joint in `slot`; `None` for a joint with none.
    pub(super) fn of(slot: u32, joint: &Joint) -> Option<Self> {
        let desc = &joint.desc;
        let spring_reference = desc.spring.map_or(0.0, |spring| spring.reference);
        let generic = (desc.joint_type == JointType::Generic).then(|| GenericV4 {
            frame: desc.frame.map(|frame| frame.to_array()),
            local_frame_a: joint.frames.local_frame_a.to_array(),
            axes: desc.axes.map(|freedom| match freedom {
                AxisFreedom::Locked => AxisV4::Locked,
                AxisFreedom::Free => AxisV4::Free,
                AxisFreedom::Limited(limits) => AxisV4::Limited(limits),
            }),
            motors: desc.motors.map(|motor| motor.map(MotorV1::of)),
        });
        (spring_reference != 0.0 || desc.armature != 0.0 || generic.is_some()).then_some(Self {
            slot,
            spring_reference,
            armature: desc.armature,
            generic,
        })
    }

    /// Gives `joint`, restored from its version 1 record, its extras; its values are checked
    /// with the world's.
    pub(super) fn apply(self, joint: &mut Joint) {
        let desc = &mut joint.desc;
        if let Some(spring) = &mut desc.spring {
            spring.reference = self.spring_reference;
        }
        desc.armature = self.armature;
        if let Some(generic) = self.generic {
            desc.joint_type = JointType::Generic;
            desc.frame = generic.frame.map(Quat::from_array);
            joint.frames.local_frame_a = Quat::from_array(generic.local_frame_a);
            desc.axes = generic.axes.map(|axis| match axis {
                AxisV4::Locked => AxisFreedom::Locked,
                AxisV4::Free => AxisFreedom::Free,
                AxisV4::Limited(limits) => AxisFreedom::Limited(limits),
            });
            desc.motors = generic.motors.map(|motor| motor.map(MotorV1::restore));
        }
    }
}
