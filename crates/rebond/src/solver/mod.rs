//! The solver: one step of the soft-step scheme (Box2D v3 / Box3D "solver2d" soft step), run as
//! a pipeline of stages over the kinds of constraint (`stages.rs`): joints (`joints/`),
//! couplings of joint coordinates (`couplings.rs`) and contacts (`contacts.rs`).
//!
//! Where a kind of constraint registers: the one list of kinds, `Kinds::each` in `stages.rs`
//! (with a field of `Kinds` and of `Sources` beside it); a kind's source links its bodies into
//! the islands through `IslandLinks` (`island.rs`).
//!
//! The island is the solver's unit of work: `Solver::build_islands` builds the step's islands
//! (`island.rs`) before the solve, and the solver takes the bodies island by island (each
//! island a range of solver indices, the kinematic bodies after them). The joints' groups,
//! solved directly (`joint_groups.rs`), are the components of the joints' links alone, recorded
//! while the islands are built.
//!
//! The stages of a solve, and what each does to the velocities `v`, `ω` and the positions `c`, `q`
//! of the moving bodies (`h = dt / n` for `n` substeps; `Δc`, `Δθ` the motion since the step
//! began):
//!
//! | stage | runs | velocities | positions |
//! |---|---|---|---|
//! | prepare | once | read: each kind builds its constraints | read, at the start of the step |
//! | integrate velocities | per substep | `v += h (g + F/m)`, `ω += h I⁻¹τ`, damped, limited | — |
//! | warm start | per substep | the accumulated impulses applied again | read: joints follow the poses; `Δc`, `Δθ` set the contacts' targets for the biased passes |
//! | prepare biased passes | per substep | read: which contacts meet an impact as a block | — |
//! | solve (biased, ×2) | per substep | normal impulses, then joint rows (the groups' exact solve in the second pass only), towards the targets (soft push-out) | — |
//! | integrate positions | per substep | — | `c += h v`, `q` turned by `h ω`, `Δc`, `Δθ` |
//! | relax | per substep | normal impulses without push-out, then friction, then rolling resistance (`rolling.rs`); then joint rows, rigid | read: `Δc`, `Δθ` |
//! | restitution | once | the contacts with restitution collide again in sequence (`contacts.rs`) | — |
//! | store impulses | once | — | — |
//!
//! The contacts set their biased passes' targets, which depend on the poses alone, in the warm
//! start's sweep over their lane sets: one sweep over the lane sets instead of two, which keeps
//! large scenes' lane sets from being read from memory twice a substep.
//!
//! The warm start applies last step's impulses in the first substep, the impulses accumulated
//! so far in the others; the impulses stored go back to the contacts for the next step's warm
//! start, and the bodies get their new velocities and poses.
//!
//! The relax pass takes back the energy the position correction added. The contacts are solved
//! four at a time: `graph_colour.rs` groups them into lane sets of up to four that share no
//! moving body, and `contact_lanes.rs` solves a lane set in SIMD lanes (`wide.rs`) from the
//! constraint parts of `parts.rs`. What is left over goes into lane sets of one.
//! Joints are built from the scalar parts of `joint_parts.rs`: the rows holding jointed bodies
//! together are solved exactly per group of joints sharing moving bodies (`joint_groups.rs`),
//! their limits, motors, springs and friction one row at a time.
//! `contact_frame.rs` says why a recycled contact keeps its normal and lever arms.
//! `contact_model.rs` holds the contact model's constants, `softness.rs` the soft constraint,
//! `integration.rs` the time integration of the bodies.

pub(crate) mod contact_frame;
mod contact_lanes;
pub mod contact_model;
mod contacts;
mod couplings;
mod graph_colour;
mod integration;
mod joint_groups;
mod joint_parts;
mod joints;
mod normal_block;
mod parts;
mod rolling;
mod softness;
mod stages;
mod wide;

use crate::arena::Arena;
use crate::body::{BodyType, RigidBody};
use crate::collision::FAST_MOTION_REACHES;
use crate::island::Islands;
use crate::math::{Mat3, Quat, Vec3, Vec3A};
pub(crate) use contact_model::ContactSettings;
use integration::{integrate_pose, integrate_velocities, SpeedLimits};
pub(crate) use joints::JointSettings;
pub(crate) use stages::Sources;
use stages::{Kinds, StepContext};

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
    /// 1 on the world axes a dynamic body may not move along, else 0 (`body/locked_axes.rs`):
    /// its inverse mass is `m⁻¹ (𝟙 − L)`.
    pub translation_lock: Vec3A,
    pub center_of_mass: Vec3,
    pub rotation: Quat,
    /// `R I⁻¹ Rᵀ` at the start of the step; the contact solver uses it for the whole step.
    pub world_inverse_inertia: Mat3,
    pub local_inertia: Mat3,
    /// Whether the gyroscopic step is skipped: where `local_inertia` is `s·1` (spheres, cubes),
    /// `ω × Iω = 0` and it changes nothing; a body with a locked rotation axis turns without
    /// it (`body/locked_axes.rs`).
    pub skips_gyroscopic_step: bool,
    /// User forces plus the constant force, N; and torques, N·m.
    pub force: Vec3,
    pub torque: Vec3,
    pub linear_damping: f32,
    pub angular_damping: f32,
    /// Only dynamic bodies feel gravity and forces; kinematic ones just move.
    pub is_dynamic: bool,
}

impl BodyMotion {
    /// The inverse mass along each world axis, `m⁻¹ (𝟙 − L)`, kg⁻¹.
    pub fn inverse_mass_diagonal(&self) -> Vec3 {
        let inverse_mass = Vec3A::splat(self.inverse_mass);
        (inverse_mass - inverse_mass * self.translation_lock).into()
    }

    /// Solver body 0: stands for every static or sleeping body, which the step never moves.
    const FIXED: Self = Self {
        inverse_mass: 0.0,
        translation_lock: Vec3A::ZERO,
        center_of_mass: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        world_inverse_inertia: Mat3::ZERO,
        local_inertia: Mat3::ZERO,
        skips_gyroscopic_step: true,
        force: Vec3::ZERO,
        torque: Vec3::ZERO,
        linear_damping: 0.0,
        angular_damping: 0.0,
        is_dynamic: false,
    };

    fn from_body(body: &RigidBody) -> Self {
        let (force, torque) = body.applied_force_and_torque();
        let locks = body.locked_axes;
        Self {
            inverse_mass: body.inverse_mass,
            translation_lock: locks.translation_mask().into(),
            center_of_mass: body.center_of_mass,
            rotation: body.rotation,
            world_inverse_inertia: body.world_inverse_inertia,
            local_inertia: body.local_inertia,
            skips_gyroscopic_step: locks.locks_rotation()
                || body.local_inertia
                    == Mat3::from_diagonal(Vec3::splat(body.local_inertia.x_axis.x)),
            force,
            torque,
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
    pub contact: ContactSettings,
    pub joint: JointSettings,
}

/// The awake dynamic and kinematic bodies of a step, in solver order (island by island, then the
/// kinematic bodies: [`Islands::solver_order`]), in buffers reused from step to step. Solver
/// body 0 stands for every static or sleeping body; the body at place `i` of the order is solver
/// body `i + 1`, so each island's range of places, shifted by one, is its range of solver
/// indices.
#[derive(Debug, Clone, Default)]
pub(crate) struct SolverBodies {
    states: Vec<BodyState>,
    motions: Vec<BodyMotion>,
    /// Solver index of each arena slot; 0 for static, sleeping and empty slots.
    solver_index_of_slot: Vec<usize>,
    /// Arena slot of each solver body (index 0 unused).
    slot_of_solver_index: Vec<usize>,
    /// Each solver body's orientation at the start of the step, for the continuous pass.
    start_rotations: Vec<Quat>,
    /// The solver index of each solver body's group root ([`Islands::group_root`]): the joints
    /// whose dynamic bodies share a root are solved as one group.
    group_roots: Vec<usize>,
}

impl SolverBodies {
    /// Copies the bodies the step moves into the solver array, in the islands' order
    /// ([`Islands::solver_order`]), with their group roots.
    fn gather(&mut self, bodies: &Arena<RigidBody>, islands: &Islands) {
        for &slot in self.slot_of_solver_index.iter().skip(1) {
            self.solver_index_of_slot[slot] = 0;
        }
        self.solver_index_of_slot.resize(bodies.slot_count(), 0);
        self.states.clear();
        self.states.push(BodyState::default());
        self.motions.clear();
        self.motions.push(BodyMotion::FIXED);
        self.slot_of_solver_index.clear();
        self.slot_of_solver_index.push(0);
        self.start_rotations.clear();
        self.start_rotations.push(Quat::IDENTITY);
        self.group_roots.clear();
        self.group_roots.push(0);
        for &slot in islands.solver_order() {
            let Some((_, body)) = bodies.at_slot(slot) else {
                continue;
            };
            let index = self.states.len();
            self.solver_index_of_slot[slot] = index;
            self.slot_of_solver_index.push(slot);
            self.states.push(BodyState {
                linear_velocity: body.linear_velocity.into(),
                angular_velocity: body.angular_velocity.into(),
                delta_position: Vec3A::ZERO,
                delta_rotation: Vec3A::ZERO,
            });
            self.motions.push(BodyMotion::from_body(body));
            self.start_rotations.push(body.rotation);
            // The root is the lowest slot of its group, all in this body's island, which comes
            // before it in the order: its solver index is set.
            let root = self.solver_index_of_slot[islands.group_root(slot)];
            self.group_roots.push(root);
        }
    }

    /// The group of a constraint between solver bodies `a` and `b`, named by a solver index: its
    /// dynamic body's group root (both dynamic bodies have the same one when it joins them),
    /// else that of its moving body. A kinematic body joins no group: its infinite mass leaves
    /// the groups on either side of it independent.
    fn group_root(&self, [a, b]: [usize; 2]) -> usize {
        let body = match (self.motions[a].is_dynamic, self.motions[b].is_dynamic) {
            (true, _) => a,
            (false, true) => b,
            (false, false) => a.max(b),
        };
        self.group_roots[body]
    }

    /// The solver index of the body in arena slot `slot`: 0 when it does not move this step.
    fn solver_index(&self, slot: usize) -> usize {
        self.solver_index_of_slot.get(slot).copied().unwrap_or(0)
    }

    /// One substep `h` of velocity integration for every moving body.
    fn integrate_velocities(&mut self, context: &StepContext) {
        for (state, motion) in self.states[1..].iter_mut().zip(&self.motions[1..]) {
            integrate_velocities(state, motion, context.gravity, context.h, context.limits);
        }
    }

    /// One substep `h` of pose integration for every moving body.
    fn integrate_positions(&mut self, context: &StepContext) {
        for (state, motion) in self.states[1..].iter_mut().zip(&mut self.motions[1..]) {
            integrate_pose(state, motion, context.h);
        }
    }

    /// Copies the solved state back into the bodies and clears their force accumulators. A
    /// dynamic body's velocities are held to the speed limits first: the solver can leave them
    /// far past the limits (a joint pulling together bodies placed metres apart, a motor of
    /// unlimited force), and from step to step such velocities feed on themselves until they
    /// overflow.
    ///
    /// Lists in `fast` (ascending slots) the dynamic bodies that moved, or at the start of the
    /// step of length `dt` were moving fast enough to move, farther than [`FAST_MOTION_REACHES`]
    /// times their reach ([`FastMotion`]): either way their contacts were made no farther ahead.
    fn scatter(
        &mut self,
        bodies: &mut Arena<RigidBody>,
        limits: SpeedLimits,
        dt: f32,
        fast: &mut Vec<FastMotion>,
    ) {
        fast.clear();
        let solved = self.states.iter_mut().zip(&self.motions);
        let bodies_of = solved
            .zip(&self.slot_of_solver_index)
            .zip(&self.start_rotations);
        for (((state, motion), &slot), &start_rotation) in bodies_of.skip(1) {
            if motion.is_dynamic {
                limits.hold(state);
            }
            if let Some(body) = bodies.at_slot_mut(slot) {
                let (delta_position, delta_rotation) =
                    (state.delta_position.into(), state.delta_rotation.into());
                let fast_enough = |reach: f32| {
                    FastMotion::travel(delta_position, delta_rotation, reach)
                        .max(dt * body.max_point_speed())
                        > FAST_MOTION_REACHES * reach
                };
                if motion.is_dynamic && fast_enough(body.max_extent) {
                    fast.push(FastMotion {
                        slot,
                        delta_position,
                        delta_rotation: FastMotion::path_rotation(
                            start_rotation,
                            motion.rotation,
                            delta_rotation,
                        ),
                    });
                }
                body.linear_velocity = state.linear_velocity.into();
                body.angular_velocity = state.angular_velocity.into();
                body.center_of_mass = motion.center_of_mass;
                body.rotation = motion.rotation;
                body.update_world_inverse_inertia();
                body.force = Vec3::ZERO;
                body.torque = Vec3::ZERO;
            }
        }
    }
}

/// A dynamic body that moved, or was moving fast enough to move, farther over the step than
/// [`FAST_MOTION_REACHES`] times its reach (its largest distance from its centre of mass): the
/// contacts, made for motions up to that many times the reaches of the pair
/// (`World::update_contacts`), may have missed what it met, so the continuous pass sweeps it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FastMotion {
    /// Arena slot of the body.
    pub slot: usize,
    /// How far its centre of mass moved over the step, m.
    pub delta_position: Vec3,
    /// How it turned, a world rotation vector, rad: one that takes its orientation at the start
    /// of the step exactly to the one at the end, of the turns about that axis the one nearest
    /// `Σ h ω` ([`FastMotion::path_rotation`]).
    pub delta_rotation: Vec3,
}

impl FastMotion {
    /// The rotation vector `θ` with `exp(θ) start = end` nearest `turned` (the substeps' `Σ h ω`,
    /// which does not compose to `end` exactly when `ω` changed its axis): the shortest arc's axis
    /// `u` and angle `φ`, plus the whole turns `θ = u (φ + 2πk)` that bring it closest.
    fn path_rotation(start: Quat, end: Quat, turned: Vec3) -> Vec3 {
        let (axis, angle) = (end * start.inverse()).normalize().to_axis_angle();
        let turns = ((turned.dot(axis) - angle) / std::f32::consts::TAU).round();
        axis * (angle + turns * std::f32::consts::TAU)
    }

    /// Upper bound of how far a point of a body of reach `reach` moved, m:
    /// `|Δc| + |Δθ| reach`.
    fn travel(delta_position: Vec3, delta_rotation: Vec3, reach: f32) -> f32 {
        delta_position.length() + delta_rotation.length() * reach
    }
}

/// Buffers reused from step to step, so a steady scene allocates nothing: the bodies, and the
/// constraints of each kind. [`Solver::step`] (`stages.rs`) runs the stages over them;
/// [`Solver::build_islands`] links the islands through the same list of kinds.
#[derive(Debug, Clone, Default)]
pub(crate) struct Solver {
    bodies: SolverBodies,
    kinds: Kinds,
    /// The fast bodies of the last step, by ascending slot.
    fast: Vec<FastMotion>,
}

impl Solver {
    /// The dynamic bodies that moved farther than [`FAST_MOTION_REACHES`] times their reach in
    /// the last step, by ascending
    /// arena slot.
    pub fn fast_bodies(&self) -> &[FastMotion] {
        &self.fast
    }

    /// The joints' group solves refused in the last step: see
    /// [`World::refused_joint_solves`](crate::World::refused_joint_solves).
    pub fn refused_joint_solves(&self) -> usize {
        self.kinds.refused_joint_solves()
    }
}
