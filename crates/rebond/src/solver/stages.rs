//! The step as a pipeline of stages (Box3D's solver stages): the body stages integrate, the
//! constraint stages run over every kind of constraint through one interface,
//! [`ConstraintKind`]: joints (`joints/`, their restitution does nothing), couplings of joint
//! coordinates (`couplings.rs`) and contacts (`contacts.rs`).
//!
//! [`Kinds::each`] is the list of kinds, the one place a kind registers: the islands' links
//! ([`Solver::build_islands`]), `prepare`, every constraint stage and `store_impulses` go
//! through it. A new kind is a field of [`Kinds`] and of [`Sources`], a line there, and an
//! [`IslandLinks`] for its source. The list sets the order of the kinds in a stage: contacts
//! first, then couplings (rows along the joints' free axes, which the joints' holding rows leave
//! alone), then joints, so the joints, solved last, are the most nearly met when a pass ends (with
//! the joints first, a pile of ragdolls opened a joint by 3.7 cm; `docs/design-notes/joints.md`).

use super::contact_model::ContactSettings;
use super::contacts::ContactConstraints;
use super::couplings::CouplingConstraints;
use super::integration::{SpeedLimits, MAX_ROTATION_PER_SUBSTEP};
use super::joints::{JointConstraints, JointSettings};
use super::{BodyMotion, BodyState, Solver, SolverBodies, StepSettings};
use crate::arena::Arena;
use crate::body::RigidBody;
use crate::collision::contact_cache::ContactCache;
use crate::coupling::CouplingSet;
use crate::island::{IslandLinks, Islands};
use crate::joint::JointSet;
use crate::math::Vec3;

/// Biased passes per substep. Lane sets converge more slowly than solving the contacts strictly
/// one after another: with one pass the bench's stacks keep moving instead of coming to rest
/// (`docs/design-notes/contact-model.md`).
pub(super) const BIASED_ITERATIONS: usize = 2;

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
    /// What the constraints are built from and store their impulses in between steps; it
    /// links their bodies into the islands.
    type Source: IslandLinks;

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

/// Where each kind's constraints come from and store their impulses between steps: the
/// world's.
pub(crate) struct Sources<'a> {
    pub joints: &'a mut JointSet,
    pub couplings: &'a mut CouplingSet,
    pub contacts: &'a mut ContactCache,
}

/// The constraints of every kind, in buffers reused from step to step.
#[derive(Debug, Clone, Default)]
pub(crate) struct Kinds {
    joints: JointConstraints,
    couplings: CouplingConstraints,
    contacts: ContactConstraints,
}

/// Work done on every kind of constraint in turn ([`Kinds::each`]): generic over the kind, so
/// each kind's loops compile to code of their own, with nothing dispatched per constraint.
trait KindTask {
    /// Does the work on the constraints of one kind, `kind`, built from `source`.
    fn run<K: ConstraintKind>(&mut self, kind: &mut K, source: &mut K::Source);
}

impl Kinds {
    /// The joints' group solves refused in the last step ([`JointConstraints::refused_solves`]).
    pub fn refused_joint_solves(&self) -> usize {
        self.joints.refused_solves()
    }

    /// Runs `task` on every kind of constraint with its source, in the order the stages take
    /// them: the one list of the kinds (module documentation).
    #[inline(always)]
    fn each(&mut self, sources: &mut Sources, task: &mut impl KindTask) {
        task.run(&mut self.contacts, sources.contacts);
        task.run(&mut self.couplings, sources.couplings);
        task.run(&mut self.joints, sources.joints);
    }
}

/// One [`ConstraintStage`] over the constraints of a kind.
struct StageTask<'a> {
    stage: ConstraintStage,
    bodies: &'a mut SolverBodies,
    context: &'a StepContext,
}

impl KindTask for StageTask<'_> {
    /// Inlined, as is [`Kinds::each`], so the `match` folds away where the stage is a constant.
    #[inline(always)]
    fn run<K: ConstraintKind>(&mut self, kind: &mut K, _source: &mut K::Source) {
        let (bodies, context) = (&mut *self.bodies, self.context);
        let states = &mut bodies.states;
        match self.stage {
            ConstraintStage::WarmStart => kind.warm_start(states, &bodies.motions),
            ConstraintStage::PrepareBiasedPasses => kind.prepare_biased_passes(states, context),
            ConstraintStage::Solve => kind.solve::<true>(states, &bodies.motions, context),
            ConstraintStage::Relax => kind.solve::<false>(states, &bodies.motions, context),
            ConstraintStage::Restitution => kind.apply_restitution(states),
        }
    }
}

/// Builds each kind's constraints ([`ConstraintKind::prepare`]).
struct PrepareTask<'a> {
    bodies: &'a SolverBodies,
    context: &'a StepContext,
}

impl KindTask for PrepareTask<'_> {
    fn run<K: ConstraintKind>(&mut self, kind: &mut K, source: &mut K::Source) {
        kind.prepare(source, self.bodies, self.context);
    }
}

/// Stores each kind's impulses ([`ConstraintKind::store_impulses`]).
struct StoreTask;

impl KindTask for StoreTask {
    fn run<K: ConstraintKind>(&mut self, kind: &mut K, source: &mut K::Source) {
        kind.store_impulses(source);
    }
}

/// Links the bodies of the kinds solved in groups, or of the others ([`IslandLinks::GROUPED`]).
struct LinkTask<'a> {
    grouped: bool,
    bodies: &'a Arena<RigidBody>,
    islands: &'a mut Islands,
}

impl KindTask for LinkTask<'_> {
    fn run<K: ConstraintKind>(&mut self, _kind: &mut K, source: &mut K::Source) {
        if K::Source::GROUPED == self.grouped {
            source.link(self.bodies, self.islands);
        }
    }
}

impl Solver {
    /// Builds this step's islands (`island.rs`) from every kind's links, before the solve: first
    /// the kinds solved in groups (joints), whose groups are recorded then, then the others
    /// (contacts, couplings). A kinematic body faster than `sleep_speed` (m/s) keeps what it touches awake.
    pub fn build_islands(
        &mut self,
        bodies: &Arena<RigidBody>,
        islands: &mut Islands,
        sources: &mut Sources,
        sleep_speed: f32,
    ) {
        islands.begin_islands(bodies, sleep_speed);
        for grouped in [true, false] {
            let mut task = LinkTask {
                grouped,
                bodies,
                islands,
            };
            self.kinds.each(sources, &mut task);
            if grouped {
                islands.end_group_links();
            }
        }
        islands.end_islands(bodies);
    }

    /// Advances the bodies of `islands` ([`Islands::solver_order`], built by
    /// [`build_islands`](Self::build_islands) this step) by one step, with their constraints: the
    /// stages in order (`solver/mod.rs` lists what each does).
    pub fn step(
        &mut self,
        bodies: &mut Arena<RigidBody>,
        islands: &Islands,
        sources: &mut Sources,
        settings: StepSettings,
    ) {
        let context = StepContext::new(&settings);
        self.bodies.gather(bodies, islands);
        let mut prepare = PrepareTask {
            bodies: &self.bodies,
            context: &context,
        };
        self.kinds.each(sources, &mut prepare);
        for _ in 0..context.substeps {
            self.bodies.integrate_velocities(&context);
            self.run(ConstraintStage::WarmStart, sources, &context);
            self.run(ConstraintStage::PrepareBiasedPasses, sources, &context);
            for _ in 0..BIASED_ITERATIONS {
                self.run(ConstraintStage::Solve, sources, &context);
            }
            self.bodies.integrate_positions(&context);
            self.run(ConstraintStage::Relax, sources, &context);
        }
        self.run(ConstraintStage::Restitution, sources, &context);
        self.kinds.each(sources, &mut StoreTask);
        self.bodies
            .scatter(bodies, context.limits, settings.dt, &mut self.fast);
    }

    /// Runs `stage` over every kind of constraint, one kind after another.
    #[inline(always)]
    fn run(&mut self, stage: ConstraintStage, sources: &mut Sources, context: &StepContext) {
        let mut task = StageTask {
            stage,
            bodies: &mut self.bodies,
            context,
        };
        self.kinds.each(sources, &mut task);
    }
}
