//! The solver: one step of the soft-step scheme (Box2D v3 / Box3D "solver2d" soft step).
//!
//! For each of the `n` substeps of length `h = dt / n`: integrate velocities, warm-start the
//! contacts, solve them with soft position correction (the biased pass), integrate poses, then
//! solve them again without position correction (the relax pass, which takes back the energy the
//! correction added). After the substeps, one restitution pass, and the impulses go back to the
//! contact cache for the next step's warm start.

pub mod contact_solver;
mod softness;

use crate::arena::Arena;
use crate::body::{BodyType, RigidBody};
use crate::collision::contact_cache::ContactCache;
use crate::integration::{
    integrate_pose, integrate_velocities, SpeedLimits, MAX_ROTATION_PER_SUBSTEP,
};
use crate::math::{Mat3, Quat, Vec3};
use contact_solver::{
    ContactConstraint, CONTACT_DAMPING_RATIO, CONTACT_HERTZ, CONTACT_HERTZ_PER_SUBSTEP_RATE,
};
use softness::Softness;

/// The moving state and mass of one awake body, copied out of the world for the step.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SolverBody {
    pub linear_velocity: Vec3,
    pub angular_velocity: Vec3,
    pub center_of_mass: Vec3,
    pub rotation: Quat,
    pub inverse_mass: f32,
    pub world_inverse_inertia: Mat3,
    pub local_inverse_inertia: Mat3,
    pub local_inertia: Mat3,
    /// User forces plus the constant force, N; and torques, N·m.
    pub force: Vec3,
    pub torque: Vec3,
    pub linear_damping: f32,
    pub angular_damping: f32,
    /// Only dynamic bodies feel gravity and forces; kinematic ones just move.
    pub is_dynamic: bool,
}

impl SolverBody {
    /// Solver body 0: stands for every static or sleeping body, which the step never moves.
    const FIXED: Self = Self {
        linear_velocity: Vec3::ZERO,
        angular_velocity: Vec3::ZERO,
        center_of_mass: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        inverse_mass: 0.0,
        world_inverse_inertia: Mat3::ZERO,
        local_inverse_inertia: Mat3::ZERO,
        local_inertia: Mat3::ZERO,
        force: Vec3::ZERO,
        torque: Vec3::ZERO,
        linear_damping: 0.0,
        angular_damping: 0.0,
        is_dynamic: false,
    };

    fn from_body(body: &RigidBody) -> Self {
        Self {
            linear_velocity: body.linear_velocity,
            angular_velocity: body.angular_velocity,
            center_of_mass: body.center_of_mass,
            rotation: body.rotation,
            inverse_mass: body.inverse_mass,
            world_inverse_inertia: body.world_inverse_inertia,
            local_inverse_inertia: body.local_inverse_inertia,
            local_inertia: body.local_inertia,
            force: body.force + body.constant_force,
            torque: body.torque + body.constant_torque,
            linear_damping: body.linear_damping,
            angular_damping: body.angular_damping,
            is_dynamic: body.body_type == BodyType::Dynamic,
        }
    }

    /// Velocity of the material point at offset `anchor` from the centre of mass: `v + ω × r`.
    pub fn velocity_at(&self, anchor: Vec3) -> Vec3 {
        self.linear_velocity + self.angular_velocity.cross(anchor)
    }
}

/// Settings of one step.
#[derive(Debug, Clone, Copy)]
pub(crate) struct StepSettings {
    pub dt: f32,
    pub substeps: u32,
    pub gravity: Vec3,
    pub max_linear_speed: f32,
}

/// Buffers reused from step to step, so a steady scene allocates nothing.
#[derive(Debug, Clone, Default)]
pub(crate) struct Solver {
    bodies: Vec<SolverBody>,
    /// Solver index of each arena slot; 0 for static, sleeping and empty slots.
    solver_index_of_slot: Vec<usize>,
    /// Arena slot of each solver body (index 0 unused).
    slot_of_solver_index: Vec<usize>,
    constraints: Vec<ContactConstraint>,
}

impl Solver {
    /// Advances every awake, non-static body by one step, with its contacts.
    pub fn step(
        &mut self,
        bodies: &mut Arena<RigidBody>,
        contacts: &mut ContactCache,
        settings: StepSettings,
    ) {
        self.gather_bodies(bodies);
        self.prepare_contacts(bodies, contacts);
        let h = settings.dt / settings.substeps as f32;
        let inverse_h = 1.0 / h;
        let softness = Softness::new(
            CONTACT_HERTZ.min(CONTACT_HERTZ_PER_SUBSTEP_RATE * inverse_h),
            CONTACT_DAMPING_RATIO,
            h,
        );
        let limits = SpeedLimits {
            linear: settings.max_linear_speed,
            angular: MAX_ROTATION_PER_SUBSTEP * inverse_h,
        };
        let moving = 1..self.bodies.len();
        for _ in 0..settings.substeps {
            for body in &mut self.bodies[moving.clone()] {
                integrate_velocities(body, settings.gravity, h, limits);
            }
            for constraint in &self.constraints {
                constraint.warm_start(&mut self.bodies);
            }
            for constraint in &mut self.constraints {
                constraint.solve(&mut self.bodies, &softness, inverse_h, true);
            }
            for body in &mut self.bodies[moving.clone()] {
                integrate_pose(body, h);
            }
            for constraint in &mut self.constraints {
                constraint.solve(&mut self.bodies, &softness, inverse_h, false);
            }
        }
        for constraint in &mut self.constraints {
            constraint.apply_restitution(&mut self.bodies);
        }
        for constraint in &self.constraints {
            constraint.store_impulses(contacts.contacts_mut());
        }
        self.scatter_bodies(bodies);
    }

    /// Copies every awake dynamic or kinematic body into the solver array (slot order).
    fn gather_bodies(&mut self, bodies: &Arena<RigidBody>) {
        self.bodies.clear();
        self.bodies.push(SolverBody::FIXED);
        self.slot_of_solver_index.clear();
        self.slot_of_solver_index.push(0);
        self.solver_index_of_slot.clear();
        for (index, body) in bodies.iter() {
            let slot = index.slot();
            if self.solver_index_of_slot.len() <= slot {
                self.solver_index_of_slot.resize(slot + 1, 0);
            }
            if body.body_type != BodyType::Static && !body.sleeping {
                self.solver_index_of_slot[slot] = self.bodies.len();
                self.slot_of_solver_index.push(slot);
                self.bodies.push(SolverBody::from_body(body));
            }
        }
    }

    /// One constraint per contact between two bodies of which at least one moves this step.
    fn prepare_contacts(&mut self, bodies: &Arena<RigidBody>, contacts: &ContactCache) {
        self.constraints.clear();
        for (contact_index, contact) in contacts.contacts().iter().enumerate() {
            let slot_a = contact.key.body_a.slot();
            let slot_b = contact.key.body_b.slot();
            let solver_a = self.solver_index_of_slot.get(slot_a).copied().unwrap_or(0);
            let solver_b = self.solver_index_of_slot.get(slot_b).copied().unwrap_or(0);
            if solver_a == solver_b {
                continue;
            }
            let (Some(body_a), Some(body_b)) = (
                bodies.get(contact.key.body_a.0),
                bodies.get(contact.key.body_b.0),
            ) else {
                continue;
            };
            self.constraints.push(ContactConstraint::new(
                contact,
                contact_index,
                &self.bodies,
                solver_a,
                solver_b,
                (body_a, body_b),
            ));
        }
    }

    /// Copies the solved state back into the bodies and clears their force accumulators.
    fn scatter_bodies(&self, bodies: &mut Arena<RigidBody>) {
        for (solved, &slot) in self.bodies.iter().zip(&self.slot_of_solver_index).skip(1) {
            if let Some(body) = bodies.at_slot_mut(slot) {
                body.linear_velocity = solved.linear_velocity;
                body.angular_velocity = solved.angular_velocity;
                body.center_of_mass = solved.center_of_mass;
                body.rotation = solved.rotation;
                body.world_inverse_inertia = solved.world_inverse_inertia;
            }
        }
        for body in bodies.values_mut() {
            body.force = Vec3::ZERO;
            body.torque = Vec3::ZERO;
        }
    }
}
