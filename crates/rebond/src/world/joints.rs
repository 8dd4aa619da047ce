//! The world's joint calls: adding, removing and reading joints, and what a joint changes for
//! its bodies (waking, islands, collisions between them).

use super::{stale, stale_joint, World};
use crate::arena::Arena;
use crate::body::{BodyHandle, RigidBody};
use crate::error::Result;
use crate::filter::ordered;
use crate::joint::{Joint, JointBreakEvent, JointDesc, JointHandle, JointPlacement, Motor};

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
    /// once it breaks).
    pub fn remove_joint(&mut self, handle: JointHandle) -> Result<Joint> {
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
        let joint = self.joints.get(handle).ok_or_else(stale_joint)?;
        let pose = |handle: BodyHandle| {
            self.bodies
                .get(handle.0)
                .map(|body| (body.center_of_mass(), body.rotation()))
                .ok_or_else(stale)
        };
        let (body_a, body_b) = joint.bodies();
        let pose_a = body_a.map(pose).transpose()?;
        Ok(joint.world_frames(pose_a, pose(body_b)?))
    }

    /// Number of joints, broken ones included.
    pub fn joint_count(&self) -> usize {
        self.joints.len()
    }

    /// Replaces a revolute or prismatic joint's motor (`None` removes it) and wakes its bodies.
    pub fn set_joint_motor(&mut self, handle: JointHandle, motor: Option<Motor>) -> Result<()> {
        let joint = self.joints.get_mut(handle).ok_or_else(stale_joint)?;
        let mut desc = joint.desc.clone();
        desc.motor = motor;
        desc.validate()?;
        joint.desc = desc;
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

    /// Adds the joints to this step's islands, and keeps what is jointed to a moving kinematic
    /// body from counting as still.
    pub(super) fn link_joints(&mut self) {
        let sleep_speed = self.settings.sleep_speed;
        let moving_kinematic = |bodies: &Arena<RigidBody>, slot: usize| {
            bodies
                .at_slot(slot)
                .is_some_and(|(_, body)| body.is_kinematic_moving_faster_than(sleep_speed))
        };
        for (slot_a, slot_b) in self.joints.body_links() {
            self.islands.link(&self.bodies, slot_a, slot_b);
            if moving_kinematic(&self.bodies, slot_a) || moving_kinematic(&self.bodies, slot_b) {
                self.islands.keep_awake(slot_a);
                self.islands.keep_awake(slot_b);
            }
        }
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
