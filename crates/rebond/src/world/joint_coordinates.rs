//! Setting joint coordinates: the bodies are placed along each joint tree so that the joints
//! read the positions or rates given (`docs/joints.md`, "Setting joint coordinates").
//!
//! The trees are walked depth first from their roots, each body's joints in slot order (the
//! order they were added), so that a chain as declared is followed to its end before a later
//! joint that closes a loop: first the world and every static or kinematic body (never moved),
//! then, for each group of dynamic bodies not reached, a body no joint places (that is `body_b`
//! of no joint), else the group's first body in slot order. Each acting joint that reaches a
//! body not yet placed places it from the body it comes from (in either direction: a joint may
//! place its `body_a` from its `body_b`); a joint reaching a body already placed closes a loop
//! and is not used.

use super::{stale_joint, World};
use crate::body::{BodyHandle, BodyType, RigidBody};
use crate::error::Result;
use crate::error::{check_finite, check_length, check_position, check_range, Error, ErrorKind};
use crate::joint::{Joint, JointHandle, JointType};
use crate::limits::{MAX_ANGULAR_SPEED, MAX_COORDINATE, MAX_SPEED};
use crate::math::{Pose, Quat, Vec3};

/// One step of the walk: the joint, and whether it places its `body_a` from its `body_b`
/// (`true`) rather than `body_b` from `body_a`.
type Link = (JointHandle, bool);

impl World {
    /// Places bodies so that each joint listed reads the position given (rad for revolute
    /// joints, counted across whole turns: 6π is three turns; m for prismatic slides and
    /// distance lengths), as [`World::joint_position`] measures it; wakes the bodies moved.
    ///
    /// Each joint tree is walked from its root (module documentation of
    /// `world/joint_coordinates.rs`, `docs/joints.md`): a root keeps its own pose, and each
    /// body's centre of mass and rotation are rebuilt from the new pose of the body it hangs
    /// from, so a body's subtree moves rigidly with it. For `A` the parent's pose, `B` the
    /// child's, the relative pose `A⁻¹ B` is
    /// - revolute at `θ`: rotation `R(a, θ) q₀`, with the anchors coinciding;
    /// - prismatic at `s`: rotation `q₀`, anchor `B` at anchor `A` + `s a`;
    /// - distance at `L`: the current relative rotation, anchor `B` at `L` from anchor `A` in the
    ///   current direction between them (the joint's `+X` in `A`'s axes while they coincide);
    /// - a joint not listed: the current relative pose, kept.
    ///
    /// A revolute joint's turns are counted from `θ`, so it reads `θ` exactly as given. A joint
    /// that closes a loop, that is broken, or that joins two static or kinematic bodies places
    /// nothing: it reads what the others' placement gives. A joint listed twice takes the last
    /// value. Velocities are kept.
    ///
    /// Errors name the entry (`positions[2]`): a stale handle, a fixed, ball or generic joint
    /// (they have no one coordinate), a value not finite or beyond ±[`MAX_COORDINATE`]; `positions` when a body
    /// would be placed beyond [`MAX_COORDINATE`]. On error the world is unchanged.
    pub fn set_joint_positions(&mut self, positions: &[(JointHandle, f32)]) -> Result<()> {
        let given = self.given_coordinates(positions, "positions", |_| MAX_COORDINATE)?;
        let tree = self.joint_tree();
        let mut poses: Vec<Option<Pose>> = vec![None; self.bodies.slot_count()];
        for &(handle, reversed) in &tree {
            let joint = self.joints.get(handle).ok_or_else(stale_joint)?;
            let (body_a, body_b) = joint.bodies();
            let old_a = self.center_pose(body_a);
            let old_b = self.center_pose(Some(body_b));
            let relative = match given[handle.slot()] {
                Some(value) => placed_relative(joint, value, old_a, old_b),
                None => old_a.inverse().mul_pose(&old_b),
            };
            let new_pose = |body: Option<BodyHandle>, old: Pose| {
                body.and_then(|body| poses[body.slot()]).unwrap_or(old)
            };
            let (slot, placed) = match (reversed, body_a) {
                (true, Some(body_a)) => (
                    body_a.slot(),
                    new_pose(Some(body_b), old_b).mul_pose(&relative.inverse()),
                ),
                _ => (body_b.slot(), new_pose(body_a, old_a).mul_pose(&relative)),
            };
            poses[slot] = Some(placed);
        }
        for (slot, pose) in poses.iter().enumerate() {
            if let (Some(pose), Some((_, body))) = (pose, self.bodies.at_slot(slot)) {
                check_position("positions", body.origin_of(pose))?;
            }
        }
        for (slot, pose) in poses.into_iter().enumerate() {
            let Some(pose) = pose else { continue };
            if let Some(body) = self.bodies.at_slot_mut(slot) {
                body.center_of_mass = pose.position;
                body.rotation = pose.rotation;
                body.update_world_inverse_inertia();
            }
            self.wake_slot(slot);
        }
        for (handle, _) in tree {
            let value = given[handle.slot()];
            if let (Some(joint), Some(value)) = (self.joints.get_mut(handle), value) {
                if joint.joint_type() == JointType::Revolute {
                    joint.angle = value;
                }
            }
        }
        Ok(())
    }

    /// Sets body velocities so that each joint listed reads the rate given (rad/s for revolute
    /// joints, m/s for prismatic slides and distance lengths), as [`World::joint_velocity`]
    /// measures it; wakes the bodies changed. Poses are kept.
    ///
    /// The trees are walked as [`World::set_joint_positions`] walks them; each child moves as its
    /// parent's rigid motion carried to it plus the joint's relative motion, at `p` the anchor
    /// on the child: `ω_B = ω_A + ω_rel`, `ṗ = v_A + ω_A × (p − c_A) + v_rel`,
    /// `v_B = ṗ − ω_B × (p − c_B)`, with
    /// - revolute at `θ̇`: `ω_rel = θ̇ a`, `v_rel = 0`;
    /// - prismatic at `ṡ`: `ω_rel = 0`, `v_rel = ṡ a` (the transport term `(p_B − p_A)·(ω_A × a)`
    ///   of the rate is carried by `ω_A × (p − c_A)`);
    /// - distance at `L̇`: the current `ω_rel`, and the current `v_rel` with its part along the
    ///   anchors' direction `u` replaced by `L̇ u` (a distance joint whose anchors coincide reads
    ///   0 whatever the rate);
    /// - a joint not listed: the current `ω_rel` and `v_rel`, kept, so it reads the same rate.
    ///
    /// Locked axes hold as [`RigidBody::set_linear_velocity`] holds them. Errors name the entry
    /// (`velocities[2]`) as [`World::set_joint_positions`]' do, with rates within
    /// ±[`MAX_ANGULAR_SPEED`] or ±[`MAX_SPEED`]; `velocities` when a body would move faster than
    /// those. On error the world is unchanged.
    pub fn set_joint_velocities(&mut self, velocities: &[(JointHandle, f32)]) -> Result<()> {
        let given = self.given_coordinates(velocities, "velocities", |joint_type| {
            if joint_type == JointType::Revolute {
                MAX_ANGULAR_SPEED
            } else {
                MAX_SPEED
            }
        })?;
        let mut motions: Vec<Option<(Vec3, Vec3)>> = vec![None; self.bodies.slot_count()];
        for (handle, reversed) in self.joint_tree() {
            let joint = self.joints.get(handle).ok_or_else(stale_joint)?;
            let (body_a, body_b) = joint.bodies();
            let placement = self.joint_placement(handle)?;
            let point = placement.anchor_b;
            let (center_a, center_b) = (
                self.center_pose(body_a).position,
                self.center_pose(Some(body_b)).position,
            );
            let old_a = self.motion(body_a);
            let old_b = self.motion(Some(body_b));
            let carried =
                |(linear, angular): (Vec3, Vec3)| linear + angular.cross(point - center_a);
            let point_b =
                |(linear, angular): (Vec3, Vec3)| linear + angular.cross(point - center_b);
            let old_spin = old_b.1 - old_a.1;
            let old_slide = point_b(old_b) - carried(old_a);
            let axis = placement.axis_a;
            let (spin, slide) = match (given[handle.slot()], joint.joint_type()) {
                (Some(rate), JointType::Revolute) => (axis * rate, Vec3::ZERO),
                (Some(rate), JointType::Prismatic) => (Vec3::ZERO, axis * rate),
                (Some(rate), _) => {
                    let direction = (point - placement.anchor_a).normalize_or_zero();
                    let along = old_slide - direction * old_slide.dot(direction);
                    (old_spin, along + direction * rate)
                }
                (None, _) => (old_spin, old_slide),
            };
            let new_motion = |body: Option<BodyHandle>, old: (Vec3, Vec3)| {
                body.and_then(|body| motions[body.slot()]).unwrap_or(old)
            };
            if let (true, Some(body_a)) = (reversed, body_a) {
                let from = new_motion(Some(body_b), old_b);
                let angular = from.1 - spin;
                let linear = point_b(from) - slide - angular.cross(point - center_a);
                motions[body_a.slot()] = Some((linear, angular));
            } else {
                let from = new_motion(body_a, old_a);
                let angular = from.1 + spin;
                let linear = carried(from) + slide - angular.cross(point - center_b);
                motions[body_b.slot()] = Some((linear, angular));
            }
        }
        for (linear, angular) in motions.iter().flatten() {
            check_length("velocities", *linear, MAX_SPEED)?;
            check_length("velocities", *angular, MAX_ANGULAR_SPEED)?;
        }
        for (slot, motion) in motions.into_iter().enumerate() {
            let Some((linear, angular)) = motion else {
                continue;
            };
            if let Some(body) = self.bodies.at_slot_mut(slot) {
                body.set_linear_velocity(linear)?;
                body.set_angular_velocity(angular)?;
            }
            self.wake_slot(slot);
        }
        Ok(())
    }

    /// The coordinate given for each joint slot, checked: live handles of joints with a
    /// coordinate, finite values within `±limit(type)`. Errors name `name[index]`.
    fn given_coordinates(
        &self,
        entries: &[(JointHandle, f32)],
        name: &str,
        limit: impl Fn(JointType) -> f32,
    ) -> Result<Vec<Option<f32>>> {
        let slots = self.joints.iter().map(|(handle, _)| handle.slot() + 1);
        let mut given = vec![None; slots.max().unwrap_or(0)];
        for (index, &(handle, value)) in entries.iter().enumerate() {
            let field = format!("{name}[{index}]");
            let joint = self
                .joints
                .get(handle)
                .ok_or_else(|| stale_joint().within(&field))?;
            let joint_type = joint.joint_type();
            // A generic joint has six coordinates, not one (`World::generic_joint_coordinates`).
            if matches!(
                joint_type,
                JointType::Fixed | JointType::Ball | JointType::Generic
            ) {
                return Err(Error::new(
                    field,
                    ErrorKind::NotForJointType(joint_type.name()),
                ));
            }
            check_finite(&field, value)?;
            let limit = limit(joint_type);
            check_range(&field, value, -limit, limit)?;
            given[handle.slot()] = Some(value);
        }
        Ok(given)
    }

    /// The order in which the joints place bodies (module documentation).
    fn joint_tree(&self) -> Vec<Link> {
        let slots = self.bodies.slot_count();
        // Node `slots` is the world; each node lists the acting joints that touch it.
        let world = slots;
        let mut touching: Vec<Vec<JointHandle>> = vec![Vec::new(); slots + 1];
        let mut is_child = vec![false; slots];
        for (handle, joint) in self.joints.iter() {
            if joint.is_broken() {
                continue;
            }
            let (body_a, body_b) = joint.bodies();
            touching[body_a.map_or(world, |body| body.slot())].push(handle);
            touching[body_b.slot()].push(handle);
            is_child[body_b.slot()] = true;
        }
        let mut placed = vec![false; slots + 1];
        let mut links = Vec::new();
        // The walk's path: each node with the index of its next joint to follow.
        let mut path: Vec<(usize, usize)> = Vec::new();
        let mut walk = |root: usize, placed: &mut Vec<bool>| {
            placed[root] = true;
            path.push((root, 0));
            while let Some((node, next)) = path.last_mut() {
                let Some(&handle) = touching[*node].get(*next) else {
                    path.pop();
                    continue;
                };
                *next += 1;
                let node = *node;
                let Some(joint) = self.joints.get(handle) else {
                    continue;
                };
                let (body_a, body_b) = joint.bodies();
                let slot_a = body_a.map_or(world, |body| body.slot());
                let (other, reversed) = if node == body_b.slot() {
                    (slot_a, true)
                } else {
                    (body_b.slot(), false)
                };
                if !placed[other] {
                    placed[other] = true;
                    links.push((handle, reversed));
                    path.push((other, 0));
                }
            }
        };
        let fixed: Vec<usize> = self
            .bodies
            .iter()
            .filter(|(_, body)| body.body_type != BodyType::Dynamic)
            .map(|(index, _)| index.slot())
            .collect();
        for slot in fixed.iter().copied() {
            placed[slot] = true;
        }
        for root in std::iter::once(world).chain(fixed) {
            placed[root] = false;
            walk(root, &mut placed);
        }
        let dynamic: Vec<usize> = self
            .bodies
            .iter()
            .filter(|(_, body)| body.body_type == BodyType::Dynamic)
            .map(|(index, _)| index.slot())
            .collect();
        for free_root in [true, false] {
            for &slot in &dynamic {
                if !placed[slot] && (is_child[slot] != free_root) {
                    walk(slot, &mut placed);
                }
            }
        }
        links
    }

    /// The pose of a joint side's centre of mass (the world's is the identity).
    fn center_pose(&self, body: Option<BodyHandle>) -> Pose {
        body.and_then(|body| self.bodies.get(body.0))
            .map_or(Pose::IDENTITY, |body| {
                Pose::new(body.center_of_mass(), body.rotation())
            })
    }

    /// A joint side's linear and angular velocity (the world's are zero).
    fn motion(&self, body: Option<BodyHandle>) -> (Vec3, Vec3) {
        body.and_then(|body| self.bodies.get(body.0))
            .map_or((Vec3::ZERO, Vec3::ZERO), |body| {
                (body.linear_velocity(), body.angular_velocity())
            })
    }
}

impl RigidBody {
    /// The body origin for a centre-of-mass pose `pose`, m.
    fn origin_of(&self, pose: &Pose) -> Vec3 {
        pose.position - pose.rotation * self.local_center_of_mass
    }
}

/// `A⁻¹ B` for the joint at coordinate `value`, from the sides' current centre-of-mass poses
/// `old_a`, `old_b` ([`World::set_joint_positions`] lists the cases).
fn placed_relative(joint: &Joint, value: f32, old_a: Pose, old_b: Pose) -> Pose {
    let frames = &joint.frames;
    let (rotation, anchor) = match joint.joint_type() {
        JointType::Revolute => (
            Quat::from_axis_angle(frames.local_axis_a, value) * frames.reference_rotation,
            frames.local_anchor_a,
        ),
        JointType::Prismatic => (
            frames.reference_rotation,
            frames.local_anchor_a + frames.local_axis_a * value,
        ),
        _ => {
            let relative = old_a.inverse().mul_pose(&old_b);
            let separation =
                relative.transform_point(frames.local_anchor_b) - frames.local_anchor_a;
            let direction = separation.try_normalize().unwrap_or(frames.local_axis_a);
            (relative.rotation, frames.local_anchor_a + direction * value)
        }
    };
    let rotation = rotation.normalize();
    Pose::new(anchor - rotation * frames.local_anchor_b, rotation)
}
