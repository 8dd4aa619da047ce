//! The step as a pipeline of stages (Box3D's solver stages): the body stages integrate, the
//! constraint stages run over every kind of constraint through one interface,
//! [`ConstraintKind`]: joints (`joints.rs`, their restitution does nothing) and contacts
//! (`contacts.rs`). [`Solver::run`] is where the order of the kinds in a stage is set: contacts
//! first, then joints, so the joints, solved last, are the most nearly met when a pass ends (with
//! the joints first, a pile of ragdolls opened a joint by 3.7 cm; `docs/design-notes/joints.md`).

use super::contact_model::ContactSettings;
use super::integration::{SpeedLimits, MAX_ROTATION_PER_SUBSTEP};
use super::joints::JointSettings;
use super::{BodyMotion, BodyState, Solver, SolverBodies, StepSettings};
use crate::arena::Arena;
use crate::body::RigidBody;
use crate::collision::contact_cache::ContactCache;
use crate::joint::JointSet;
use crate::math::Vec3;

/// Biased passes per substep. Lane sets converge more slowly than solving the contacts strictly
/// one after another: with one pass the bench's stacks keep moving instead of coming to rest
/// (`docs/design-notes/contact-model.md`).
const BIASED_ITERATIONS: usize = 2;

/// What the stages of one step share.
#[derive(Debug, Clone, Copy)]
pub(crate) struct StepContext {
    pub substeps: u32,
    /// The substep `h = dt / n`, s, and `1 / h`, 1/s.
    pub h: f32,
    pub inverse_h: f32,
    pub gravity: Vec3,
    pub limits: SpeedLimits,
    pub contact: ContactSettings,
    pub joint: JointSettings,
}

impl StepContext {
    fn new(settings: &StepSettings) -> Self {
        let h = settings.dt / settings.substeps as f32;
        let inverse_h = 1.0 / h;
        Self {
            substeps: settings.substeps,
            h,
            inverse_h,
            gravity: settings.gravity,
            limits: SpeedLimits {
                linear: settings.max_linear_speed,
                angular: MAX_ROTATION_PER_SUBSTEP * inverse_h,
            },
            contact: settings.contact,
            joint: settings.joint,
        }
    }
}

/// One kind of constraint between two bodies, as the stages see it: each method is one stage
/// over all the constraints of the kind, in their solving order. The stages call the kinds
/// through generics, not `dyn`, so each kind's loops compile to code of their own in the stage
/// loop, with nothing dispatched per constraint.
pub(crate) trait ConstraintKind {
    /// What the constraints are built from and store their impulses in between steps.
    type Source;

    /// Builds this step's constraints from `source` and the solver bodies at the start of the
    /// step, warm-started from the impulses `source` kept.
    fn prepare(
        &mut self,
        source: &Self::Source,
        solver_bodies: &SolverBodies,
        context: &StepContext,
    );

    /// Applies the accumulated impulses again, at the substep's poses (`motions`); a kind may
    /// also set its biased passes' targets from those poses here, in the same sweep.
    fn warm_start(&mut self, states: &mut [BodyState], motions: &[BodyMotion]);

    /// What the biased passes of the substep need once every kind has warm-started: the
    /// velocities are the substep's then.
    fn prepare_biased_passes(&mut self, states: &[BodyState], context: &StepContext);

    /// One pass over the constraints: with position correction (`USE_BIAS`), or without it
    /// after the poses moved (the relax pass).
    fn solve<const USE_BIAS: bool>(
        &mut self,
        states: &mut [BodyState],
        motions: &[BodyMotion],
        context: &StepContext,
    );

    /// After the substeps: the bounce of the constraints that have one.
    fn apply_restitution(&mut self, states: &mut [BodyState]);

    /// Writes the accumulated impulses back to `source` for the next step's warm start.
    fn store_impulses(&self, source: &mut Self::Source);
}

/// A stage that runs over the constraints of every kind: the [`ConstraintKind`] method of each.
#[derive(Debug, Clone, Copy)]
enum ConstraintStage {
    WarmStart,
    PrepareBiasedPasses,
    /// A biased pass.
    Solve,
    /// The pass without position correction, after the poses moved.
    Relax,
    Restitution,
}

impl ConstraintStage {
    /// Runs this stage over the constraints of one kind. Inlined, as is [`Solver::run`], so the
    /// `match` folds away where the stage is a constant.
    #[inline(always)]
    fn run<K: ConstraintKind>(
        self,
        kind: &mut K,
        bodies: &mut SolverBodies,
        context: &StepContext,
    ) {
        let states = &mut bodies.states;
        match self {
            Self::WarmStart => kind.warm_start(states, &bodies.motions),
            Self::PrepareBiasedPasses => kind.prepare_biased_passes(states, context),
            Self::Solve => kind.solve::<true>(states, &bodies.motions, context),
            Self::Relax => kind.solve::<false>(states, &bodies.motions, context),
            Self::Restitution => kind.apply_restitution(states),
        }
    }
}

impl Solver {
    /// Advances the bodies of `awake` (the slots of the awake dynamic and of the kinematic bodies,
    /// ascending) by one step, with their joints and contacts: the stages in order
    /// (`solver/mod.rs` lists what each does).
    pub fn step(
        &mut self,
        bodies: &mut Arena<RigidBody>,
        awake: &[usize],
        (joints, contacts): (&mut JointSet, &mut ContactCache),
        settings: StepSettings,
    ) {
        let context = StepContext::new(&settings);
        self.bodies.gather(bodies, awake);
        self.joints.prepare(joints, &self.bodies, &context);
        self.contacts.prepare(contacts, &self.bodies, &context);
        for _ in 0..context.substeps {
            self.bodies.integrate_velocities(&context);
            self.run(ConstraintStage::WarmStart, &context);
            self.run(ConstraintStage::PrepareBiasedPasses, &context);
            for _ in 0..BIASED_ITERATIONS {
                self.run(ConstraintStage::Solve, &context);
            }
            self.bodies.integrate_positions(&context);
            self.run(ConstraintStage::Relax, &context);
        }
        self.run(ConstraintStage::Restitution, &context);
        self.joints.store_impulses(joints);
        self.contacts.store_impulses(contacts);
        self.bodies
            .scatter(bodies, context.limits, settings.dt, &mut self.fast);
    }

    /// Runs `stage` over every kind of constraint, one kind after another.
    #[inline(always)]
    fn run(&mut self, stage: ConstraintStage, context: &StepContext) {
        stage.run(&mut self.contacts, &mut self.bodies, context);
        stage.run(&mut self.joints, &mut self.bodies, context);
    }
}
