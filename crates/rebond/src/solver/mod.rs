//! The solver: one step of the soft-step scheme (Box2D v3 / Box3D "solver2d" soft step).
//!
//! For each of the `n` substeps of length `h = dt / n`: integrate velocities, warm-start the
//! contacts, solve their normal impulses with soft position correction (the biased pass, twice),
//! integrate poses, then solve them again without position correction, normal impulses and then
//! friction (the relax pass, which takes back the energy the correction added). After the
//! substeps, one restitution pass, and the impulses go back to the contact cache for the next
//! step's warm start.
//!
//! The contacts are solved four at a time: `graph_colour.rs` groups them into lane sets of up to
//! four that share no moving body, and `contact_lanes.rs` solves a lane set in SIMD lanes
//! (`wide.rs`) from the constraint parts of `parts.rs`. What is left over goes into lane sets of
//! one. `contact_model.rs` holds the contact model's constants, `integration.rs` the time
//! integration of the bodies.

mod contact_lanes;
pub mod contact_model;
mod graph_colour;
mod integration;
mod parts;
mod softness;
mod wide;

use crate::arena::Arena;
use crate::body::{BodyType, RigidBody};
use crate::collision::contact_cache::Contact;
use crate::collision::contact_cache::ContactCache;
use crate::math::{Mat3, Quat, Vec3, Vec3A};
use contact_lanes::{ContactLanes, LaneContact};
use contact_model::{CONTACT_DAMPING_RATIO, CONTACT_HERTZ, CONTACT_HERTZ_PER_SUBSTEP_RATE};
use graph_colour::GraphColouring;
use integration::{integrate_pose, integrate_velocities, SpeedLimits, MAX_ROTATION_PER_SUBSTEP};
use softness::Softness;

/// Biased passes per substep. With the contacts solved in lane sets instead of strictly one
/// after another, one pass let the 20-box column of the tests topple at 4 substeps (0.74 m of
/// drift); two keep it standing. With the lane sets, the three passes of a substep cost less
/// than the two did one contact at a time (BENCHMARKS.md).
const BIASED_ITERATIONS: usize = 2;

/// What the contact solver reads and writes of one awake body, kept small and contiguous, in
/// SIMD vectors (`Vec3A`, 16 bytes) so each vector operation of the solver is one instruction.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct BodyState {
    /// m/s.
    pub linear_velocity: Vec3A,
    /// rad/s, world frame.
    pub angular_velocity: Vec3A,
    /// How far the centre of mass moved since the step began, m.
    pub delta_position: Vec3A,
    /// Rotation since the step began, as the sum of `h ω` over the substeps (a rotation vector,
    /// rad): contacts follow the bodies to first order in the angle.
    pub delta_rotation: Vec3A,
}

/// The rest of a body the step needs: pose, inertia and forces for integration.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BodyMotion {
    /// `1/m`; zero for kinematic bodies and for solver body 0, which stands for every static or
    /// sleeping body.
    pub inverse_mass: f32,
    pub center_of_mass: Vec3,
    pub rotation: Quat,
    /// `R I⁻¹ Rᵀ` at the start of the step; the contact solver uses it for the whole step.
    pub world_inverse_inertia: Mat3,
    pub local_inertia: Mat3,
    /// Whether `local_inertia` is `s·1` (spheres, cubes): then `ω × Iω = 0` and the gyroscopic
    /// step changes nothing.
    pub has_isotropic_inertia: bool,
    /// User forces plus the constant force, N; and torques, N·m.
    pub force: Vec3,
    pub torque: Vec3,
    pub linear_damping: f32,
    pub angular_damping: f32,
    /// Only dynamic bodies feel gravity and forces; kinematic ones just move.
    pub is_dynamic: bool,
}

impl BodyMotion {
    /// Solver body 0: stands for every static or sleeping body, which the step never moves.
    const FIXED: Self = Self {
        inverse_mass: 0.0,
        center_of_mass: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        world_inverse_inertia: Mat3::ZERO,
        local_inertia: Mat3::ZERO,
        has_isotropic_inertia: true,
        force: Vec3::ZERO,
        torque: Vec3::ZERO,
        linear_damping: 0.0,
        angular_damping: 0.0,
        is_dynamic: false,
    };

    fn from_body(body: &RigidBody) -> Self {
        Self {
            inverse_mass: body.inverse_mass,
            center_of_mass: body.center_of_mass,
            rotation: body.rotation,
            world_inverse_inertia: body.world_inverse_inertia,
            local_inertia: body.local_inertia,
            has_isotropic_inertia: body.local_inertia
                == Mat3::from_diagonal(Vec3::splat(body.local_inertia.x_axis.x)),
            force: body.force + body.constant_force,
            torque: body.torque + body.constant_torque,
            linear_damping: body.linear_damping,
            angular_damping: body.angular_damping,
            is_dynamic: body.body_type == BodyType::Dynamic,
        }
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
    states: Vec<BodyState>,
    motions: Vec<BodyMotion>,
    /// Solver index of each arena slot; 0 for static, sleeping and empty slots.
    solver_index_of_slot: Vec<usize>,
    /// Arena slot of each solver body (index 0 unused).
    slot_of_solver_index: Vec<usize>,
    /// The solver bodies of each contact to solve, for the colouring, and its index in the
    /// contact cache.
    pairs: Vec<(usize, usize)>,
    pair_contacts: Vec<usize>,
    colouring: GraphColouring,
    /// The contacts in lane sets of up to four, in solving order.
    lanes: Vec<ContactLanes>,
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
        self.colour_contacts(bodies, contacts);
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
        for _ in 0..settings.substeps {
            for (state, motion) in self.states.iter_mut().zip(&self.motions).skip(1) {
                integrate_velocities(state, motion, settings.gravity, h, limits);
            }
            self.warm_start(&softness, inverse_h);
            for _ in 0..BIASED_ITERATIONS {
                self.solve_contacts::<true>(inverse_h);
            }
            for (state, motion) in self.states.iter_mut().zip(&mut self.motions).skip(1) {
                integrate_pose(state, motion, h);
            }
            self.solve_contacts::<false>(inverse_h);
        }
        for lanes in &mut self.lanes {
            lanes.apply_restitution(&mut self.states);
        }
        for lanes in &self.lanes {
            lanes.store_impulses(contacts.contacts_mut());
        }
        self.scatter_bodies(bodies);
    }

    /// Copies every awake dynamic or kinematic body into the solver array (slot order).
    fn gather_bodies(&mut self, bodies: &Arena<RigidBody>) {
        self.states.clear();
        self.states.push(BodyState::default());
        self.motions.clear();
        self.motions.push(BodyMotion::FIXED);
        self.slot_of_solver_index.clear();
        self.slot_of_solver_index.push(0);
        self.solver_index_of_slot.clear();
        for (index, body) in bodies.iter() {
            let slot = index.slot();
            if self.solver_index_of_slot.len() <= slot {
                self.solver_index_of_slot.resize(slot + 1, 0);
            }
            if body.body_type != BodyType::Static && !body.sleeping {
                self.solver_index_of_slot[slot] = self.states.len();
                self.slot_of_solver_index.push(slot);
                self.states.push(BodyState {
                    linear_velocity: body.linear_velocity.into(),
                    angular_velocity: body.angular_velocity.into(),
                    delta_position: Vec3A::ZERO,
                    delta_rotation: Vec3A::ZERO,
                });
                self.motions.push(BodyMotion::from_body(body));
            }
        }
    }

    /// Colours every contact between two bodies of which at least one moves this step into lane
    /// sets of up to four.
    fn colour_contacts(&mut self, bodies: &Arena<RigidBody>, contacts: &ContactCache) {
        self.pairs.clear();
        self.pair_contacts.clear();
        for (contact_index, contact) in contacts.contacts().iter().enumerate() {
            if let Some((solver_a, solver_b, _)) = self.constraint_bodies(bodies, contact) {
                self.pairs.push((solver_a, solver_b));
                self.pair_contacts.push(contact_index);
            }
        }
        self.colouring.colour(&self.pairs, self.states.len());
    }

    /// The solver bodies of `contact` and its two bodies, or `None` when neither moves this step
    /// (or a body is gone).
    fn constraint_bodies<'a>(
        &self,
        bodies: &'a Arena<RigidBody>,
        contact: &Contact,
    ) -> Option<(usize, usize, (&'a RigidBody, &'a RigidBody))> {
        let solver_of = |slot: usize| self.solver_index_of_slot.get(slot).copied().unwrap_or(0);
        let solver_a = solver_of(contact.key.body_a.slot());
        let solver_b = solver_of(contact.key.body_b.slot());
        if solver_a == solver_b {
            return None;
        }
        let body_a = bodies.get(contact.key.body_a.0)?;
        let body_b = bodies.get(contact.key.body_b.0)?;
        Some((solver_a, solver_b, (body_a, body_b)))
    }

    /// Builds the lane sets straight from the contacts, lane by lane.
    fn prepare_contacts(&mut self, bodies: &Arena<RigidBody>, contacts: &ContactCache) {
        let mut lane_sets = std::mem::take(&mut self.lanes);
        lane_sets.clear();
        for lane_set in self.colouring.lane_sets() {
            let lane_contacts = lane_set.iter().filter_map(|&pair| {
                let index = self.pair_contacts[pair];
                let contact = &contacts.contacts()[index];
                let (body_a, body_b, materials) = self.constraint_bodies(bodies, contact)?;
                Some(LaneContact {
                    contact,
                    index,
                    body_a,
                    body_b,
                    materials,
                })
            });
            let index = lane_sets.len();
            lane_sets.push(ContactLanes::EMPTY);
            lane_sets[index].fill(lane_contacts, &self.states, &self.motions);
        }
        self.lanes = lane_sets;
    }

    /// Applies last step's impulses again, and sets what the biased passes of the substep aim
    /// at (its poses).
    fn warm_start(&mut self, softness: &Softness, inverse_h: f32) {
        for lanes in &mut self.lanes {
            lanes.warm_start(&mut self.states);
            lanes.prepare_biased_passes(&self.states, softness, inverse_h);
        }
    }

    /// One pass over every contact (biased with `USE_BIAS`, else relax): the lane sets in order.
    fn solve_contacts<const USE_BIAS: bool>(&mut self, inverse_h: f32) {
        for lanes in &mut self.lanes {
            lanes.solve::<USE_BIAS>(&mut self.states, inverse_h);
        }
    }

    /// Copies the solved state back into the bodies and clears their force accumulators.
    fn scatter_bodies(&self, bodies: &mut Arena<RigidBody>) {
        let solved = self.states.iter().zip(&self.motions);
        for ((state, motion), &slot) in solved.zip(&self.slot_of_solver_index).skip(1) {
            if let Some(body) = bodies.at_slot_mut(slot) {
                body.linear_velocity = state.linear_velocity.into();
                body.angular_velocity = state.angular_velocity.into();
                body.center_of_mass = motion.center_of_mass;
                body.rotation = motion.rotation;
                body.update_world_inverse_inertia();
            }
        }
        for body in bodies.values_mut() {
            body.force = Vec3::ZERO;
            body.torque = Vec3::ZERO;
        }
    }
}
