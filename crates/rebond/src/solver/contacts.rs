//! The contacts as a constraint kind: each step's contacts between moving bodies, coloured into
//! lane sets of up to four (`graph_colour.rs`) and solved a lane set at a time
//! (`contact_lanes.rs`), the lane sets in order.

use super::contact_lanes::{Collision, ContactLanes, LaneContact};
use super::graph_colour::GraphColouring;
use super::rolling::RollingConstraints;
use super::softness::Softness;
use super::stages::{ConstraintKind, StepContext};
use super::{BodyMotion, BodyState, SolverBodies};
use crate::collision::contact_cache::{Contact, ContactCache};

/// Most sweeps of the restitution stage's collisions: a row of touching equal balls passes an
/// impact on in one sweep in the row's order; a chain of collisions without restitution shares
/// out the momentum more slowly: the plastic collision of a ball striking a column of three on
/// the ground takes 121 sweeps to stop them all (its settle 97). Cut off at 32, the plastic
/// outcome kept the striker falling at 0.2 m/s, and the striker, given the elastic outcome less
/// the plastic one, left 4 % faster than it came. The sweeps stop as soon as nothing moves, so
/// the cap costs only chains that need it.
const COLLISION_SWEEPS: usize = 256;

/// This step's contact constraints, in buffers reused from step to step.
#[derive(Debug, Clone, Default)]
pub(crate) struct ContactConstraints {
    /// The solver bodies of each contact to solve, for the colouring, and its index in the
    /// contact cache.
    pairs: Vec<(usize, usize)>,
    pair_contacts: Vec<usize>,
    colouring: GraphColouring,
    /// The contacts in lane sets of up to four, in solving order.
    lanes: Vec<ContactLanes>,
    /// The rolling resistance of the contacts that have some (`rolling.rs`).
    rolling: RollingConstraints,
    /// The contacts' spring for this step's substep, the fastest push-out (m/s) and `1/h`.
    softness: Softness,
    push_speed: f32,
    inverse_h: f32,
    /// The lane sets that may solve lanes as a block this step, by index into `lanes`.
    blocking: Vec<usize>,
    /// Approach speed below which nothing bounces, m/s.
    restitution_threshold: f32,
    /// The lane sets with restitution, by index into `lanes`, in solving order.
    bouncing: Vec<usize>,
    /// The bodies' velocities at the start of the step, kept while any lane set bounces, and
    /// the restitution stage's two copies of them: after the step's collisions with
    /// restitution, and without.
    start: Vec<BodyState>,
    elastic: Vec<BodyState>,
    plastic: Vec<BodyState>,
}

impl ContactConstraints {
    /// Colours every contact between two bodies of which at least one moves this step into lane
    /// sets of up to four.
    fn colour(&mut self, contacts: &ContactCache, solver_bodies: &SolverBodies) {
        self.pairs.clear();
        self.pair_contacts.clear();
        for (contact_index, contact) in contacts.contacts().iter().enumerate() {
            if let Some((solver_a, solver_b)) = constraint_bodies(solver_bodies, contact) {
                self.pairs.push((solver_a, solver_b));
                self.pair_contacts.push(contact_index);
            }
        }
        self.colouring
            .colour(&self.pairs, solver_bodies.states.len());
    }
}

/// The collisions `collision` of the lane sets `bouncing` (indices into `lanes`) on the
/// velocities `states` ([`ContactLanes::collide`]), swept forwards and backwards in turn until
/// no point they act on moves, at most [`COLLISION_SWEEPS`] times.
fn sweep_collisions(
    lanes: &mut [ContactLanes],
    bouncing: &[usize],
    states: &mut [BodyState],
    restitution_threshold: f32,
    collision: Collision,
) {
    for sweep in 0..COLLISION_SWEEPS {
        let mut collided = false;
        let mut collide = |&index: &usize| {
            collided |= lanes[index].collide(states, restitution_threshold, collision);
        };
        if sweep % 2 == 0 {
            bouncing.iter().for_each(&mut collide);
        } else {
            bouncing.iter().rev().for_each(&mut collide);
        }
        if !collided {
            break;
        }
    }
}

/// Lists in `list`, by index into `lanes` and in solving order, the lane sets `keep` holds for.
fn list_lane_sets(lanes: &[ContactLanes], keep: fn(&ContactLanes) -> bool, list: &mut Vec<usize>) {
    list.clear();
    let kept = lanes.iter().enumerate().filter(|(_, lanes)| keep(lanes));
    list.extend(kept.map(|(index, _)| index));
}

/// The solver bodies of `contact`, or `None` when neither moves this step. Every contact's
/// bodies are in the world: removing a body removes its contacts.
fn constraint_bodies(solver_bodies: &SolverBodies, contact: &Contact) -> Option<(usize, usize)> {
    let solver_a = solver_bodies.solver_index(contact.key.body_a.slot());
    let solver_b = solver_bodies.solver_index(contact.key.body_b.slot());
    (solver_a != solver_b).then_some((solver_a, solver_b))
}

impl ConstraintKind for ContactConstraints {
    type Source = ContactCache;

    /// Colours the contacts and builds the lane sets straight from them, lane by lane; sets the
    /// contacts' spring, at most [`CONTACT_HERTZ_PER_SUBSTEP_RATE`](super::contact_model::CONTACT_HERTZ_PER_SUBSTEP_RATE) of the substep rate.
    fn prepare(
        &mut self,
        contacts: &ContactCache,
        solver_bodies: &SolverBodies,
        context: &StepContext,
    ) {
        self.colour(contacts, solver_bodies);
        self.lanes.clear();
        self.rolling.clear();
        // A step and a substep: how far ahead a contact's gap may close in this step's passes.
        let inverse_reach = context.inverse_h / (context.substeps + 1) as f32;
        for lane_set in self.colouring.lane_sets() {
            let lane_contacts = lane_set.iter().filter_map(|&pair| {
                let index = self.pair_contacts[pair];
                let contact = &contacts.contacts()[index];
                let (body_a, body_b) = constraint_bodies(solver_bodies, contact)?;
                Some(LaneContact {
                    contact,
                    index,
                    body_a,
                    body_b,
                })
            });
            let index = self.lanes.len();
            self.lanes.push(ContactLanes::EMPTY);
            let rolls = self.lanes[index].fill(
                lane_contacts.clone(),
                &solver_bodies.states,
                &solver_bodies.motions,
                inverse_reach,
            );
            if rolls {
                self.rolling
                    .add(index, lane_contacts, &solver_bodies.motions);
            }
            if contacts.has_surface_velocities() {
                self.lanes[index].set_surface_velocities(|index| contacts.surface_velocity(index));
            }
        }
        self.softness = context.contact.softness(context.h, context.inverse_h);
        self.push_speed = context.contact.push_speed;
        self.inverse_h = context.inverse_h;
        list_lane_sets(&self.lanes, ContactLanes::may_block, &mut self.blocking);
        self.restitution_threshold = context.contact.restitution_threshold;
        list_lane_sets(&self.lanes, ContactLanes::bounces, &mut self.bouncing);
        if !self.bouncing.is_empty() {
            self.start.clone_from(&solver_bodies.states);
        }
    }

    /// The warm start, and each point's target for the substep's biased passes, from the
    /// poses, in one sweep ([`ContactLanes::set_targets`]).
    fn warm_start(&mut self, states: &mut [BodyState], _motions: &[BodyMotion]) {
        for lanes in &mut self.lanes {
            lanes.warm_start(states);
            lanes.set_targets(states, &self.softness, self.push_speed, self.inverse_h);
        }
        self.rolling.warm_start(states);
    }

    /// Which lanes solve as a block, from the velocities after every warm start (the targets
    /// are set with the warm start).
    fn prepare_biased_passes(&mut self, states: &[BodyState], _context: &StepContext) {
        for &index in &self.blocking {
            self.lanes[index].prepare_block(states);
        }
    }

    fn solve<const USE_BIAS: bool>(
        &mut self,
        states: &mut [BodyState],
        _motions: &[BodyMotion],
        context: &StepContext,
    ) {
        for lanes in &mut self.lanes {
            lanes.solve::<USE_BIAS>(states, context.inverse_h);
        }
        // Like friction, in the relax pass only.
        if !USE_BIAS {
            self.rolling.solve(&self.lanes, states);
        }
    }

    /// Restitution as a sequence of collisions, so an impact travels down a row of touching
    /// bodies (Newton's cradle). The contacts that bounce and pushed during the step collide
    /// again, one after another, from the velocities at the start of the step, once without
    /// restitution and once with it ([`sweep_collisions`]). The points that collided are the
    /// step's impacts: on the bodies' velocities after the substeps they are brought to rest
    /// along their normals (the outcome without restitution, whatever approach or push-out the
    /// substeps left), and each body then gets the difference of the two collisions' outcomes.
    fn apply_restitution(&mut self, states: &mut [BodyState]) {
        if self.bouncing.is_empty() {
            return;
        }
        let (lanes, bouncing) = (&mut self.lanes, &self.bouncing);
        let threshold = self.restitution_threshold;
        self.plastic.clone_from(&self.start);
        sweep_collisions(
            lanes,
            bouncing,
            &mut self.plastic,
            threshold,
            Collision::Plastic,
        );
        self.elastic.clone_from(&self.start);
        sweep_collisions(
            lanes,
            bouncing,
            &mut self.elastic,
            threshold,
            Collision::Elastic,
        );
        sweep_collisions(lanes, bouncing, states, threshold, Collision::Settle);
        let outcomes = self.elastic.iter().zip(&self.plastic);
        for (state, (elastic, plastic)) in states.iter_mut().zip(outcomes).skip(1) {
            state.linear_velocity += elastic.linear_velocity - plastic.linear_velocity;
            state.angular_velocity += elastic.angular_velocity - plastic.angular_velocity;
        }
    }

    fn store_impulses(&self, contacts: &mut ContactCache) {
        for lanes in &self.lanes {
            lanes.store_impulses(contacts.contacts_mut());
        }
        self.rolling.store_impulses(contacts.contacts_mut());
    }
}
