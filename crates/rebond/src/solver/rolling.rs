//! Rolling resistance: an angular impulse at each contact whose material has some
//! ([`Material::rolling_lever`](crate::material::Material::rolling_lever)), against the
//! surfaces' relative rolling, Coulomb-like.
//!
//! The law: the relative angular velocity of the bodies, `ω_rel = ω_B − ω_A`, has its two
//! components in the contact plane (rolling; the twist about the normal is the twist friction's)
//! driven to zero by an angular impulse `L` in the plane, `Δω_A = −I_A⁻¹ L`, `Δω_B = +I_B⁻¹ L`,
//! clamped to the disc `|L| ≤ c R Σλ_n`: `c` the rolling resistance coefficient (dimensionless,
//! default 0), `R` the radius the surfaces roll on (m), `Σλ_n` the contact's normal impulse
//! (N·s). As forces, the resisting torque is at most `c R N`: the normal force acting a distance
//! `c R` ahead of the contact point, the classic coefficient of rolling resistance `F = c N`. A
//! solid ball of radius `r` rolling without slip on flat ground then slows at `(5/7) c g`, and
//! rests on a slope up to `atan c` (docs/physics.md, "Rolling resistance").
//!
//! Rolling contacts are few (round bodies given a coefficient), so each is solved alone, scalar,
//! in the relax pass after the contacts' lane sets, with the normal impulse those just found; and
//! warm-started like friction. A step without any pays only for looking at each contact's lever.

use super::contact_lanes::{ContactLanes, LaneContact};
use super::{BodyMotion, BodyState};
use crate::collision::contact_cache::Contact;
use crate::math::Vec3A;

/// The rolling resistance of one contact.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct RollingConstraint {
    /// The contact's index in the contact cache.
    contact: usize,
    /// Where the contact's normal impulses are: its lane set, by index, and its lane.
    lane_set: usize,
    lane: usize,
    body_a: usize,
    body_b: usize,
    /// The contact plane's two directions, along which `ω_rel` is driven to zero.
    tangents: [Vec3A; 2],
    /// `I_A⁻¹ t_k` and `I_B⁻¹ t_k`: how a unit impulse about `t_k` turns each body.
    spin_a: [Vec3A; 2],
    spin_b: [Vec3A; 2],
    /// The inverse of `K_kl = t_k·(I_A⁻¹ + I_B⁻¹) t_l`, symmetric: `[k⁻¹₀₀, k⁻¹₀₁, k⁻¹₁₁]`,
    /// kg·m².
    mass: [f32; 3],
    /// `c R`, m: the most impulse per unit of normal impulse.
    lever: f32,
    /// The accumulated impulse about each tangent, N·m·s.
    impulse: [f32; 2],
}

/// This step's rolling resistance constraints, in a buffer reused from step to step.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct RollingConstraints {
    constraints: Vec<RollingConstraint>,
}

impl RollingConstraints {
    /// Forgets last step's constraints.
    pub fn clear(&mut self) {
        self.constraints.clear();
    }

    /// Adds a constraint for each contact of lane set `lane_set` (its lanes in order) that has
    /// rolling resistance, warm-started from the contact's cached impulse.
    pub fn add<'a>(
        &mut self,
        lane_set: usize,
        lane_contacts: impl IntoIterator<Item = LaneContact<'a>>,
        motions: &[BodyMotion],
    ) {
        for (lane, lane_contact) in lane_contacts.into_iter().enumerate() {
            let contact = lane_contact.contact;
            let lever = contact.material.rolling_lever();
            if lever <= 0.0 {
                continue;
            }
            let (body_a, body_b) = (lane_contact.body_a, lane_contact.body_b);
            let normal = Vec3A::from(contact.manifold.normal);
            let (tangent_1, tangent_2) = normal.any_orthonormal_pair();
            let tangents = [tangent_1, tangent_2];
            let inverse_inertia_a = motions[body_a].world_inverse_inertia;
            let inverse_inertia_b = motions[body_b].world_inverse_inertia;
            let spin_a = tangents.map(|tangent| inverse_inertia_a * tangent);
            let spin_b = tangents.map(|tangent| inverse_inertia_b * tangent);
            let k = |i: usize, j: usize| tangents[i].dot(spin_a[j] + spin_b[j]);
            let (k00, k01, k11) = (k(0, 0), k(0, 1), k(1, 1));
            let determinant = k00 * k11 - k01 * k01;
            // One body at least turns (a contact has a moving body, and moving bodies have
            // inertia), so `K` is positive definite; the guard is for rounding alone.
            let mass = if determinant > f32::MIN_POSITIVE {
                [k11 / determinant, -k01 / determinant, k00 / determinant]
            } else {
                [0.0; 3]
            };
            let cached = Vec3A::from(contact.rolling_impulse);
            self.constraints.push(RollingConstraint {
                contact: lane_contact.index,
                lane_set,
                lane,
                body_a,
                body_b,
                tangents,
                spin_a,
                spin_b,
                mass,
                lever,
                impulse: tangents.map(|tangent| cached.dot(tangent)),
            });
        }
    }

    /// Applies the accumulated impulses again (warm starting).
    pub fn warm_start(&self, states: &mut [BodyState]) {
        for constraint in &self.constraints {
            constraint.apply(states, constraint.impulse);
        }
    }

    /// One pass, in the relax pass after the lane sets `lanes`, whose normal impulses bound the
    /// rolling ones.
    pub fn solve(&mut self, lanes: &[ContactLanes], states: &mut [BodyState]) {
        for constraint in &mut self.constraints {
            let normal_impulse = lanes[constraint.lane_set].normal_impulse_sum(constraint.lane);
            constraint.solve(states, normal_impulse);
        }
    }

    /// Writes the accumulated impulses back to the contacts, as world vectors, for the next
    /// step's warm start.
    pub fn store_impulses(&self, contacts: &mut [Contact]) {
        for constraint in &self.constraints {
            if let Some(contact) = contacts.get_mut(constraint.contact) {
                let [t1, t2] = constraint.tangents;
                let [i1, i2] = constraint.impulse;
                contact.rolling_impulse = (t1 * i1 + t2 * i2).into();
            }
        }
    }
}

impl RollingConstraint {
    /// Drives `ω_rel` in the contact plane to zero, the accumulated impulse clamped to
    /// `|L| ≤ c R Σλ_n`.
    fn solve(&mut self, states: &mut [BodyState], normal_impulse: f32) {
        let relative = states[self.body_b].angular_velocity - states[self.body_a].angular_velocity;
        let [t1, t2] = self.tangents;
        let (w1, w2) = (t1.dot(relative), t2.dot(relative));
        let [m00, m01, m11] = self.mass;
        let old = self.impulse;
        let mut total = [
            old[0] - (m00 * w1 + m01 * w2),
            old[1] - (m01 * w1 + m11 * w2),
        ];
        let limit = self.lever * normal_impulse;
        let length = total[0].hypot(total[1]);
        if length > limit {
            let scale = if length > 0.0 { limit / length } else { 0.0 };
            total = total.map(|value| value * scale);
        }
        self.impulse = total;
        self.apply(states, [total[0] - old[0], total[1] - old[1]]);
    }

    /// Applies the angular impulse `L = Σ impulse_k t_k` to body B and its opposite to body A;
    /// solver body 0 (static or asleep) never changes.
    fn apply(&self, states: &mut [BodyState], impulse: [f32; 2]) {
        if self.body_a != 0 {
            states[self.body_a].angular_velocity -=
                self.spin_a[0] * impulse[0] + self.spin_a[1] * impulse[1];
        }
        if self.body_b != 0 {
            states[self.body_b].angular_velocity +=
                self.spin_b[0] * impulse[0] + self.spin_b[1] * impulse[1];
        }
    }
}
