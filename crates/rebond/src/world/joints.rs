//! The world's joint calls: adding, removing and reading joints, and what a joint changes for
//! its bodies (waking, collisions between them). Joints join islands through their
//! `IslandLinks` (`island.rs`).

use super::{stale, stale_joint, World};
use crate::body::{BodyHandle, RigidBody};
use crate::error::{Error, ErrorKind, Result};
use crate::filter::ordered;
use crate::joint::{
    GenericAxis, GenericCoordinates, GenericFrame, Joint, JointBreakEvent, JointDesc, JointHandle,
    JointPlacement, JointType, Motor,
};
use crate::math::{Quat, Vec3};

impl World {
    /// Checks `desc` and adds the joint, fixing its anchors and axes to the bodies as they stand
    /// now; wakes both bodies. Unless `collide_connected`, the two bodies stop colliding with
    /// each other at once (their contacts are dropped). On error the world is unchanged.
    pub fn add_joint(&mut self, desc: JointDesc) -> Result<JointHandle> {
        let axis = desc.validate()?;
        let body_a = match desc.body_a {
            Some(handle) => Some(
                self.bodies
                    .get(handle.0)
                    .ok_or_else(|| stale().within("body_a"))?,
            ),
            None => None,
        };
        let body_b = self
            .bodies
            .get(desc.body_b.0)
            .ok_or_else(|| stale().within("body_b"))?;
        let (body_a_handle, body_b_handle) = (desc.body_a, desc.body_b);
        let excludes = !desc.collide_connected;
        let handle = self.joints.insert(desc, axis, body_a, body_b);
        self.joint_bodies_changed(body_a_handle, body_b_handle, excludes);
        Ok(handle)
    }

    /// Removes the joint and returns it; its handle becomes stale. Wakes both bodies, which
    /// collide with each other again at the next step if the joint kept them apart (as they do
    /// once it breaks). The couplings of the joint go with it (`crate::coupling`).
    pub fn remove_joint(&mut self, handle: JointHandle) -> Result<Joint> {
        for coupling in self.couplings.couplings_of(handle) {
            self.remove_coupling(coupling)?;
        }
        let joint = self.joints.remove(handle).ok_or_else(stale_joint)?;
        let (body_a, body_b) = joint.bodies();
        self.joint_bodies_changed(body_a, body_b, !joint.desc.collide_connected);
        Ok(joint)
    }

    /// The joint behind `handle`.
    pub fn joint(&self, handle: JointHandle) -> Result<&Joint> {
        self.joints.get(handle).ok_or_else(stale_joint)
    }

    /// All joints with their handles, in a deterministic order (storage slots).
    pub fn joints(&self) -> impl Iterator<Item = (JointHandle, &Joint)> {
        self.joints.iter()
    }

    /// Where the joint's anchors and axes stand now, world frame: for drawing it and for
    /// measuring how far it has come apart.
    pub fn joint_placement(&self, handle: JointHandle) -> Result<JointPlacement> {
        self.joint_sides(handle)
            .map(|(_, placement, _, _)| placement)
    }

    /// The joint's position, its coordinate along the motion it leaves free, at the bodies'
    /// current poses: a revolute joint's angle (rad, counted across whole turns: three turns
    /// read 6π, not 0), a prismatic joint's slide (m), a distance joint's length (m). Angles and
    /// slides are measured from the pose when the joint was added (`docs/joints.md`):
    /// `θ = 2 atan2(d_xyz·a, d_w)` of `d = q_A⁻¹ q_B q₀⁻¹` about the axis `a` plus the turns
    /// counted, `s = (p_B − p_A)·a`, `L = |p_B − p_A|`. A broken joint is measured the same way.
    ///
    /// The turns are counted each substep the joint is solved and as each step starts: a
    /// revolute angle read between steps is right while the bodies turn by less than half a turn
    /// relative to each other in a substep (and in a step, when moved by hand or asleep).
    /// Fixed, ball and generic joints have no one such coordinate (a generic joint's six are
    /// [`World::generic_joint_coordinates`]): an error naming `position`.
    pub fn joint_position(&self, handle: JointHandle) -> Result<f32> {
        let (joint, placement, body_a, body_b) = self.joint_sides(handle)?;
        let separation = placement.anchor_b - placement.anchor_a;
        match joint.joint_type() {
            JointType::Revolute => {
                Ok(joint.unwrapped_angle(body_a.map(RigidBody::rotation), body_b.rotation()))
            }
            JointType::Prismatic => Ok(separation.dot(placement.axis_a)),
            JointType::Distance => Ok(separation.length()),
            other => Err(Error::new(
                "position",
                ErrorKind::NotForJointType(other.name()),
            )),
        }
    }

    /// The rate of [`World::joint_position`] at the bodies' current velocities: rad/s
    /// (`θ̇ = (ω_B − ω_A)·a`) or m/s (`ṡ = (ṗ_B − ṗ_A)·a + (p_B − p_A)·(ω_A × a)`,
    /// `L̇ = u·(ṗ_B − ṗ_A)`, `ṗ` each anchor's velocity, `u` the unit direction A → B; 0 while the
    /// anchors coincide). Fixed, ball and generic joints: an error naming `velocity`.
    pub fn joint_velocity(&self, handle: JointHandle) -> Result<f32> {
        let (joint, placement, body_a, body_b) = self.joint_sides(handle)?;
        let separation = placement.anchor_b - placement.anchor_a;
        let closing = anchor_velocity(Some(body_b), placement.anchor_b)
            - anchor_velocity(body_a, placement.anchor_a);
        let axis = placement.axis_a;
        match joint.joint_type() {
            JointType::Revolute => Ok((spin(Some(body_b)) - spin(body_a)).dot(axis)),
            JointType::Prismatic => {
                Ok(closing.dot(axis) + separation.dot(spin(body_a).cross(axis)))
            }
            JointType::Distance => Ok(closing.dot(separation.normalize_or_zero())),
            other => Err(Error::new(
                "velocity",
                ErrorKind::NotForJointType(other.name()),
            )),
        }
    }

    /// A generic joint's six coordinates and their rates at the bodies' current poses and
    /// velocities ([`GenericCoordinates`] gives their definitions). Other joint types: an error
    /// naming `coordinates`.
    pub fn generic_joint_coordinates(&self, handle: JointHandle) -> Result<GenericCoordinates> {
        let (joint, placement, body_a, body_b) = self.joint_sides(handle)?;
        if joint.joint_type() != JointType::Generic {
            return Err(Error::new(
                "coordinates",
                ErrorKind::NotForJointType(joint.joint_type().name()),
            ));
        }
        let rotation = |body: Option<&RigidBody>| body.map_or(Quat::IDENTITY, RigidBody::rotation);
        let separation = placement.anchor_b - placement.anchor_a;
        let frame = GenericFrame::new(
            &joint.frames,
            &joint.desc.axes,
            (rotation(body_a), rotation(Some(body_b))),
            separation,
        );
        let closing = anchor_velocity(Some(body_b), placement.anchor_b)
            - anchor_velocity(body_a, placement.anchor_a);
        let turning = spin(Some(body_b)) - spin(body_a);
        let mut velocities = [0.0; 6];
        for (k, axis) in frame.axes.into_iter().enumerate() {
            velocities[k] = closing.dot(axis) + separation.dot(spin(body_a).cross(axis));
            velocities[3 + k] = turning.dot(axis);
        }
        Ok(GenericCoordinates {
            positions: frame.positions,
            velocities,
        })
    }

    /// Replaces the motor of one axis of a generic joint (`None` removes it) and wakes its
    /// bodies, as [`World::set_joint_motor`] does for a revolute or prismatic joint; an error
    /// names the field (`motors.rz`, `motors.x.torque`) and leaves the joint as it was.
    pub fn set_generic_joint_motor(
        &mut self,
        handle: JointHandle,
        axis: GenericAxis,
        motor: Option<Motor>,
    ) -> Result<()> {
        let joint = self.joints.get_mut(handle).ok_or_else(stale_joint)?;
        let mut desc = joint.desc.clone();
        desc.motors[axis.index()] = motor;
        desc.validate()?;
        joint.desc = desc;
        let (body_a, body_b) = joint.bodies();
        for body in body_a.into_iter().chain([body_b]) {
            self.wake_slot(body.slot());
        }
        Ok(())
    }

    /// The joint behind `handle`, where it stands now, and its bodies (`body_a` `None` for the
    /// world).
    fn joint_sides(
        &self,
        handle: JointHandle,
    ) -> Result<(&Joint, JointPlacement, Option<&RigidBody>, &RigidBody)> {
        let joint = self.joints.get(handle).ok_or_else(stale_joint)?;
        let body = |handle: BodyHandle| self.bodies.get(handle.0).ok_or_else(stale);
        let (body_a, body_b) = joint.bodies();
        let body_a = body_a.map(body).transpose()?;
        let body_b = body(body_b)?;
        let pose = |body: &RigidBody| (body.center_of_mass(), body.rotation());
        let placement = joint.world_frames(body_a.map(pose), pose(body_b));
        Ok((joint, placement, body_a, body_b))
    }

    /// Number of joints, broken ones included.
    pub fn joint_count(&self) -> usize {
        self.joints.len()
    }

    /// Adds `damping` (N·m·s/rad or N·s/m, finite, ≥ 0) to a revolute or prismatic joint's
    /// passive damping, a spring of stiffness 0 when it has none: a scene's velocity actuator,
    /// MuJoCo's `gear² kv`, is this damping plus a torque motor.
    #[cfg(feature = "scene")]
    pub(crate) fn add_joint_damping(&mut self, handle: JointHandle, damping: f32) -> Result<()> {
        let joint = self.joints.get_mut(handle).ok_or_else(stale_joint)?;
        let spring = joint.desc.spring.get_or_insert(crate::joint::Spring {
            stiffness: 0.0,
            damping: 0.0,
            reference: 0.0,
        });
        spring.damping += damping;
        Ok(())
    }

    /// Replaces a revolute or prismatic joint's motor (`None` removes it) and wakes its bodies;
    /// an error names the field (`motor.torque`) and leaves the joint as it was.
    ///
    /// Only the motor's parameters change: the joint's frames, its angle counted across turns and
    /// the impulses that warm-start it are kept, so a controller may set a new torque or target
    /// every step (a motor of another kind starts from the last one's impulse).
    pub fn set_joint_motor(&mut self, handle: JointHandle, motor: Option<Motor>) -> Result<()> {
        let joint = self.joints.get_mut(handle).ok_or_else(stale_joint)?;
        if let Some(motor) = &motor {
            motor.check_for(joint.joint_type())?;
        }
        joint.desc.motor = motor;
        let (body_a, body_b) = joint.bodies();
        for body in body_a.into_iter().chain([body_b]) {
            self.wake_slot(body.slot());
        }
        Ok(())
    }

    /// Joints that broke during the last step, in slot order. Valid until the next step.
    pub fn joint_break_events(&self) -> &[JointBreakEvent] {
        self.joints.break_events()
    }

    /// After a joint between `body_a` and `body_b` came or went: wakes both, and when it keeps
    /// them from colliding (`excludes`), drops their contacts and has the broad phase look at
    /// their pair again.
    fn joint_bodies_changed(
        &mut self,
        body_a: Option<BodyHandle>,
        body_b: BodyHandle,
        excludes: bool,
    ) {
        for handle in body_a.into_iter().chain([body_b]) {
            self.wake_slot(handle.slot());
        }
        let Some(body_a) = body_a.filter(|_| excludes) else {
            return;
        };
        if let Some(proxy) = self.bodies.get(body_b.0).and_then(|body| body.proxy) {
            self.broad_phase.refilter(proxy);
        }
        let pair = ordered(body_a, body_b);
        if self.joints.excludes(body_a, body_b) {
            self.drop_contacts(|_, a, b| (a, b) == pair);
        }
    }

    /// A joint that broke this step no longer keeps its bodies apart: the broad phase looks at
    /// them again at the next step.
    pub(super) fn refilter_broken_joints(&mut self) {
        for index in 0..self.joints.break_events().len() {
            let joint = self.joints.break_events()[index].joint;
            let body_b = self.joints.get(joint).map(|joint| joint.desc.body_b);
            if let Some(proxy) = body_b.and_then(|body| self.bodies.get(body.0)?.proxy) {
                self.broad_phase.refilter(proxy);
            }
        }
    }
}

/// A joined body's angular velocity, rad/s (zero for the world).
fn spin(body: Option<&RigidBody>) -> Vec3 {
    body.map_or(Vec3::ZERO, RigidBody::angular_velocity)
}

/// The velocity of the point of a joined body at `anchor` (world point, m), m/s (zero for the
/// world).
fn anchor_velocity(body: Option<&RigidBody>, anchor: Vec3) -> Vec3 {
    body.map_or(Vec3::ZERO, |body| body.velocity_at_point(anchor))
}
