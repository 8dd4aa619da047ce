//! A joint's geometry at the poses of a substep: its anchors, axes, angles and the parts built
//! on them, rebuilt as the bodies move ([`super`] says when).

use super::{JointConstraint, SHORTEST_DIRECTION, TWIST_RATE_FLOOR};
use crate::joint::{relative_rotation, twist_angle, unwrap_angle, GenericFrame, JointType};
use crate::math::{rotation_vector, Quat, Vec3};
use crate::solver::joint_parts::{AxisPart, PlanePart, PointPart, RotationPart};
use crate::solver::BodyMotion;

/// A joint at the poses of the current substep.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Geometry {
    /// `p_B − p_A`, m.
    pub(super) separation: Vec3,
    /// The rotation vector of B relative to A since the joint was made, world axes, rad.
    pub(super) rotation_error: Vec3,
    /// The joint axis fixed in A (world), the distance joint's direction from A to B, or the
    /// ball joint's twist rate vector (`Ċ_twist = (ω_B − ω_A)·axis`).
    pub(super) axis: Vec3,
    /// Angle (revolute, ball twist, rad), slide (prismatic, m) or length (distance, m).
    pub(super) position: f32,
    /// Ball joints: the angle between the twist axes fixed in A and in B, rad, and the axis it
    /// grows about.
    pub(super) swing_angle: f32,
    pub(super) swing_axis: Vec3,
    /// Errors of the two rows of `plane` (hinge axis misalignment, rad; prismatic offset, m).
    pub(super) plane_errors: [f32; 2],
    pub(super) point: Option<PointPart>,
    /// Whether the joint locks the relative rotation (a fixed joint).
    pub(super) locks_rotation: bool,
    pub(super) plane: Option<PlanePart>,
    pub(super) axis_part: Option<AxisPart>,
    pub(super) swing: Option<AxisPart>,
    /// Ball joints with friction: the relative rotation's effective mass.
    pub(super) friction: Option<RotationPart>,
    /// Generic joints: a part per axis ([`GenericAxis::ALL`]'s order), along the frame's axes
    /// fixed in A, and the coordinates.
    pub(super) generic: Option<GenericGeometry>,
}

/// A generic joint at the poses of the current substep.
#[derive(Debug, Clone, Copy)]
pub(super) struct GenericGeometry {
    pub(super) parts: [AxisPart; 6],
    /// The frame's axes in the world (unit), and the six coordinates (m, rad).
    pub(super) axes: [Vec3; 3],
    pub(super) positions: [f32; 6],
}

impl GenericGeometry {
    /// The unit world direction (slide) or axis (rotation) of axis `k`.
    pub(super) fn direction(&self, k: usize) -> Vec3 {
        self.axes[k % 3]
    }
}

impl JointConstraint {
    /// The pose (centre of mass, rotation) of side `side` in this substep.
    pub(super) fn pose(&self, side: usize, motions: &[BodyMotion]) -> (Vec3, Quat) {
        match self.solver[side] {
            0 => self.start_poses[side],
            index => (motions[index].center_of_mass, motions[index].rotation),
        }
    }

    /// Rebuilds the geometry and parts for this substep's poses.
    pub(super) fn refresh(&mut self, motions: &[BodyMotion]) {
        let (center_a, rotation_a) = self.pose(0, motions);
        let (center_b, rotation_b) = self.pose(1, motions);
        let frames = &self.frames;
        let bodies = &self.bodies;
        let arm_a = rotation_a * frames.local_anchor_a;
        let arm_b = rotation_b * frames.local_anchor_b;
        let separation = center_b + arm_b - (center_a + arm_a);
        let axis = rotation_a * frames.local_axis_a;
        let relative = relative_rotation(frames, rotation_a, rotation_b);
        let twist = twist_angle(relative, frames.local_axis_a);
        let mut geometry = Geometry {
            separation,
            rotation_error: rotation_a * rotation_vector(relative),
            axis,
            position: twist,
            ..Geometry::default()
        };
        let options = &self.options;
        if options.joint_type.holds_point() {
            geometry.point = Some(PointPart::new(arm_a, arm_b));
        }
        if options.joint_type.locks_rotation() {
            geometry.locks_rotation = true;
        }
        match options.joint_type {
            JointType::Fixed => {}
            JointType::Ball => {
                let axis_b = rotation_b * frames.local_axis_b;
                if options.swing_limit.is_some() {
                    let cross = axis.cross(axis_b);
                    let sine = cross.length();
                    geometry.swing_angle = sine.atan2(axis.dot(axis_b));
                    geometry.swing_axis = if sine > 1.0e-6 {
                        cross / sine
                    } else {
                        axis.any_orthonormal_vector()
                    };
                    geometry.swing = Some(AxisPart::angular(bodies, geometry.swing_axis));
                }
                if options.twist_limits.is_some() {
                    // The twist (about the axis, once the swing has taken A's axis onto B's)
                    // grows at `(ω_B − ω_A)·(a + b) / (1 + a·b)`, not along A's axis alone; the
                    // rate is held finite where the swing nears a half turn.
                    geometry.axis =
                        (axis + axis_b) / (1.0 + axis.dot(axis_b)).max(TWIST_RATE_FLOOR);
                    geometry.axis_part = Some(AxisPart::angular(bodies, geometry.axis));
                }
                if options.friction > 0.0 {
                    geometry.friction = Some(RotationPart::new(bodies));
                }
            }
            JointType::Revolute => {
                let axis_b = rotation_b * frames.local_axis_b;
                let misalignment = axis.cross(axis_b);
                let (first, second) = axis.any_orthonormal_pair();
                let rows = [first, second].map(|row| AxisPart::angular(bodies, row));
                geometry.plane = Some(PlanePart::new(rows, [first, second]));
                geometry.plane_errors = [misalignment.dot(first), misalignment.dot(second)];
                geometry.axis_part = Some(AxisPart::angular(bodies, axis));
                // Limits and position targets are on the angle counted across turns: measured
                // every substep, it changes by far less than the half turn its count needs.
                geometry.position = unwrap_angle(twist, self.angle);
                self.angle = geometry.position;
            }
            JointType::Prismatic => {
                let arms = (arm_a + separation, arm_b);
                let (first, second) = axis.any_orthonormal_pair();
                let rows = [first, second].map(|row| AxisPart::linear(bodies, arms, row));
                geometry.plane = Some(PlanePart::new(rows, [first, second]));
                geometry.plane_errors = [separation.dot(first), separation.dot(second)];
                geometry.axis_part = Some(AxisPart::linear(bodies, arms, axis));
                geometry.position = separation.dot(axis);
            }
            JointType::Distance => {
                let length = separation.length();
                geometry.position = length;
                if length > SHORTEST_DIRECTION {
                    geometry.axis = separation / length;
                    geometry.axis_part =
                        Some(AxisPart::linear(bodies, (arm_a, arm_b), geometry.axis));
                }
            }
            JointType::Generic => {
                let frame =
                    GenericFrame::new(frames, &options.axes, (rotation_a, rotation_b), separation);
                let arms = (arm_a + separation, arm_b);
                let parts = [0, 1, 2, 3, 4, 5].map(|k| {
                    let axis = frame.axes[k % 3];
                    if k < 3 {
                        AxisPart::linear(bodies, arms, axis)
                    } else {
                        AxisPart::angular(bodies, axis)
                    }
                });
                geometry.generic = Some(GenericGeometry {
                    parts,
                    axes: frame.axes,
                    positions: frame.positions,
                });
            }
        }
        self.geometry = geometry;
    }
}
