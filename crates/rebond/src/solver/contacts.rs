//! The contacts as a constraint kind: each step's contacts between moving bodies, coloured into
//! lane sets of up to four (`graph_colour.rs`) and solved a lane set at a time
//! (`contact_lanes.rs`), the lane sets in order.

use super::contact_lanes::{ContactLanes, LaneContact};
use super::graph_colour::GraphColouring;
use super::softness::Softness;
use super::stages::{ConstraintKind, StepContext};
use super::{BodyMotion, BodyState, SolverBodies};
use crate::collision::contact_cache::{Contact, ContactCache};

/// This step's contact constraints, in buffers reused from step to step.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct ContactConstraints {
    /// The solver bodies of each contact to solve, for the colouring, and its index in the
    /// contact cache.
    pairs: Vec<(usize, usize)>,
    pair_contacts: Vec<usize>,
    colouring: GraphColouring,
    /// The contacts in lane sets of up to four, in solving order.
    lanes: Vec<ContactLanes>,
    /// The contacts' spring for this step's substep.
    softness: Softness,
    /// Approach speed below which nothing bounces, m/s.
    restitution_threshold: f32,
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
            self.lanes[index].fill(lane_contacts, &solver_bodies.states, &solver_bodies.motions);
        }
        self.softness = context.contact.softness(context.h, context.inverse_h);
        self.restitution_threshold = context.contact.restitution_threshold;
    }

    fn warm_start(&mut self, states: &mut [BodyState], _motions: &[BodyMotion]) {
        for lanes in &self.lanes {
            lanes.warm_start(states);
        }
    }

    fn prepare_biased_passes(&mut self, states: &[BodyState], context: &StepContext) {
        for lanes in &mut self.lanes {
            lanes.prepare_biased_passes(
                states,
                &self.softness,
                context.contact.push_speed,
                context.inverse_h,
            );
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
    }

    fn apply_restitution(&mut self, states: &mut [BodyState]) {
        for lanes in &mut self.lanes {
            lanes.apply_restitution(states, self.restitution_threshold);
        }
    }

    fn store_impulses(&self, contacts: &mut ContactCache) {
        for lanes in &self.lanes {
            lanes.store_impulses(contacts.contacts_mut());
        }
    }
}
