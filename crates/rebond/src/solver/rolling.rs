//! Rolling resistance: an angular impulse at each contact whose material has some
//! ([`Material::rolling_lever`](crate::material::Material::rolling_lever)), against the
//! surfaces' relative rolling, Coulomb-like.
//!
//! The law: the relative angular velocity of the bodies, `ω_rel = ω_B − ω_A`, has its two
//! components in the contact plane (rolling) driven to zero by an angular impulse `L` in the
//! plane, `Δω_A = −I_A⁻¹ L`, `Δω_B = +I_B⁻¹ L`, clamped to `|L| ≤ c R Σλ_n`: `c` the rolling
//! resistance coefficient (dimensionless, default 0), `R` the radius the surfaces roll on (m),
//! `Σλ_n` the contact's normal impulse (N·s). As forces, the resisting torque is at most `c R N`:
//! the normal force acting a distance `c R` ahead of the contact point, the classic coefficient
//! of rolling resistance `F = c N`. A solid ball of radius `r` rolling without slip on flat ground
//! then slows at `(5/7) c g`, and rests on a slope up to `atan c` (docs/physics.md, "Rolling
//! resistance"). The spin about the normal is the twist friction's, except at a contact of one
//! point (a ball, a rim), where the twist friction has no lever (`⟨r⟩ = 0`): there `L` takes in
//! the spin about the normal too, within the same bound (as Box3D's does at every contact), so
//! that a ball at rest does not spin on about the vertical for ever.
//!
//! Rolling contacts are few (round bodies given a coefficient), so each is solved alone, scalar,
//! in the relax pass after the contacts' lane sets, with the normal impulse those just found; and
//! warm-started like friction. A step without any pays only for looking at each contact's lever.

use super::contact_lanes::{ContactLanes, LaneContact};
use super::{BodyMotion, BodyState};
use crate::collision::contact_cache::Contact;
use crate::limits::MAX_SOLVER_IMPULSE;
use crate::math::{Mat3, Vec3, Vec3A};

/// The rolling resistance of one contact.
#[derive(Debug, Clone, Copy)]
struct RollingConstraint {
    /// The contact's index in the contact cache.
    contact: usize,
    /// Where the contact's normal impulses are: its lane set, by index, and its lane.
    lane_set: usize,
    lane: usize,
    body_a: usize,
    body_b: usize,
    /// The axes about which `ω_rel` is driven to zero: the contact plane's two directions, and
    /// the normal where the contact has one point (else zero: the twist friction's).
    axes: [Vec3A; 3],
    /// `I_A⁻¹ a_k` and `I_B⁻¹ a_k`: how a unit impulse about axis `a_k` turns each body.
    spin_a: [Vec3A; 3],
    spin_b: [Vec3A; 3],
    /// The inverse of `K_kl = a_k·(I_A⁻¹ + I_B⁻¹) a_l`, kg·m².
    mass: Mat3,
    /// `c R`, m: the most impulse per unit of normal impulse.
    lever: f32,
    /// The accumulated impulse about each axis, N·m·s.
    impulse: Vec3,
}

/// This step's rolling resistance constraints, in a buffer reused from step to step.
#[derive(Debug, Clone, Default)]
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
            let twists = contact.manifold.len() == 1;
            let axes = [
                tangent_1,
                tangent_2,
                if twists { normal } else { Vec3A::ZERO },
            ];
            let inverse_inertia_a = motions[body_a].world_inverse_inertia;
            let inverse_inertia_b = motions[body_b].world_inverse_inertia;
            let spin_a = axes.map(|axis| inverse_inertia_a * axis);
            let spin_b = axes.map(|axis| inverse_inertia_b * axis);
            let components = |vector: Vec3A| {
                Vec3::new(
                    axes[0].dot(vector),
                    axes[1].dot(vector),
                    axes[2].dot(vector),
                )
            };
            let mut stiffness = Mat3::from_cols(
                components(spin_a[0] + spin_b[0]),
                components(spin_a[1] + spin_b[1]),
                components(spin_a[2] + spin_b[2]),
            );
            if !twists {
                // The normal's row is all zero: 1 on the diagonal keeps `K` invertible, and its
                // impulse stays zero, as the row's error always is.
                stiffness.z_axis.z = 1.0;
            }
            // One body at least turns (a contact has a moving body, and moving bodies have
            // inertia), so `K` is positive definite; the guard is for rounding alone.
            let mass = if stiffness.determinant() > f32::MIN_POSITIVE {
                stiffness.inverse()
            } else {
                Mat3::ZERO
            };
            self.constraints.push(RollingConstraint {
                contact: lane_contact.index,
                lane_set,
                lane,
                body_a,
                body_b,
                axes,
                spin_a,
                spin_b,
                mass,
                lever,
                impulse: components(contact.rolling_impulse.into()),
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
                let impulse: Vec3 = constraint
                    .combine(&constraint.axes, constraint.impulse)
                    .into();
                // As for the other impulses (`contact_lanes.rs`): past what bodies within the
                // limits exchange, not kept to warm-start from.
                contact.rolling_impulse = if impulse.length() <= MAX_SOLVER_IMPULSE {
                    impulse
                } else {
                    Vec3::ZERO
                };
            }
        }
    }
}

impl RollingConstraint {
    /// Drives `ω_rel` about the axes to zero, the accumulated impulse clamped to
    /// `|L| ≤ c R Σλ_n`.
    fn solve(&mut self, states: &mut [BodyState], normal_impulse: f32) {
        let relative = states[self.body_b].angular_velocity - states[self.body_a].angular_velocity;
        let [a1, a2, a3] = self.axes;
        let error = Vec3::new(a1.dot(relative), a2.dot(relative), a3.dot(relative));
        let old = self.impulse;
        let total = (old - self.mass * error).clamp_length_max(self.lever * normal_impulse);
        self.impulse = total;
        self.apply(states, total - old);
    }

    /// `Σ impulse_k v_k` for one vector `v_k` per axis.
    fn combine(&self, vectors: &[Vec3A; 3], impulse: Vec3) -> Vec3A {
        vectors[0] * impulse.x + vectors[1] * impulse.y + vectors[2] * impulse.z
    }

    /// Applies the angular impulse of components `impulse` about the axes to body B and its
    /// opposite to body A; solver body 0 (static or asleep) never changes.
    fn apply(&self, states: &mut [BodyState], impulse: Vec3) {
        if self.body_a != 0 {
            states[self.body_a].angular_velocity -= self.combine(&self.spin_a, impulse);
        }
        if self.body_b != 0 {
            states[self.body_b].angular_velocity += self.combine(&self.spin_b, impulse);
        }
    }
}
