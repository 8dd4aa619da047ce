//! Contact constraints solved by sequential impulses with accumulated clamping, soft position
//! correction, Coulomb friction and restitution.
//!
//! Friction acts on the whole manifold at once, at the centre of its points, as Box3D and Jolt
//! do: two tangent impulses clamped together to the cone `|λ_t| ≤ μ Σλ_n`, and a twist impulse
//! about the normal clamped to `μ Σλ_n r̄` (`r̄` the mean distance of the points from their
//! centre). Measured against friction at each point (which Gauss–Seidel solves one point after
//! another), a box sliding down a 35° incline with μ = 0.5 then decelerates at the closed-form
//! rate instead of 5 % too little, and no longer starts to spin about the normal.

use super::softness::Softness;
use super::{BodyMotion, BodyState};
use crate::body::RigidBody;
use crate::collision::contact_cache::Contact;
use crate::collision::MAX_MANIFOLD_POINTS;
use crate::math::{Mat3, Vec3, Vec3A};

/// Penetration allowed without correction, metres: resting contacts settle this deep instead of
/// jittering in and out of touch. Stacks sink by about this much per layer.
pub const LINEAR_SLOP: f32 = 0.001;

/// Bodies approaching faster than this, m/s, bounce with their restitution; slower ones stay
/// down, so resting bodies do not jitter.
pub const RESTITUTION_THRESHOLD: f32 = 1.0;

/// Fastest a soft contact pushes overlapping bodies apart, m/s.
pub const MAX_PUSH_SPEED: f32 = 3.0;

/// Stiffness of contacts, Hz, capped at [`CONTACT_HERTZ_PER_SUBSTEP_RATE`] of the substep rate so
/// the spring stays stable. A contact's steady sag under a load is `load / (m_eff ω²)`: at 60 Hz
/// a box sags 0.07 mm per box resting on it.
pub const CONTACT_HERTZ: f32 = 60.0;

/// Largest contact frequency as a fraction of the substep rate, `ω h ≤ π / 2` (Box2D's cap): 60 Hz
/// from 4 substeps at 60 Hz up. A 20-box column of unit boxes buckles below about 47 Hz
/// (docs/physics.md); at the former cap of 1/8, 30 Hz, it toppled.
pub const CONTACT_HERTZ_PER_SUBSTEP_RATE: f32 = 0.25;

/// Friction anchors further apart than this along the contact plane, m, are set again where the
/// manifold is now, instead of pulling the bodies back together.
pub const FRICTION_ANCHOR_MAX_SLIP: f32 = 0.005;

/// Damping ratio of contacts: over-damped, so corrections never bounce. At 4 substeps a 20-box
/// column rocked at up to 0.2 m/s with 10 and stays within 0.05 m/s with 5.
pub const CONTACT_DAMPING_RATIO: f32 = 5.0;

/// How two bodies' friction coefficients combine: the geometric mean `√(μ_A μ_B)` (equal values
/// give that value; a frictionless body makes the contact frictionless).
pub fn combine_friction(a: f32, b: f32) -> f32 {
    (a * b).sqrt()
}

/// How two bodies' restitutions combine: the larger one (a bouncy ball bounces on anything).
pub fn combine_restitution(a: f32, b: f32) -> f32 {
    a.max(b)
}

/// The velocity Jacobian of one direction `d` of a contact, for both bodies, with the angular
/// response precomputed from the inverse inertia at the start of the step.
#[derive(Debug, Clone, Copy)]
pub(super) struct Jacobian {
    /// `r_A × d` and `r_B × d`: how each body's spin moves the contact along `d`.
    pub(super) arm_a: Vec3A,
    pub(super) arm_b: Vec3A,
    /// `I_A⁻¹ (r_A × d)` and `I_B⁻¹ (r_B × d)`: the spin a unit impulse along `d` gives.
    pub(super) spin_a: Vec3A,
    pub(super) spin_b: Vec3A,
    /// `1 / (m_A⁻¹ + m_B⁻¹ + (r_A × d)·I_A⁻¹(r_A × d) + (r_B × d)·I_B⁻¹(r_B × d))`, or zero when
    /// nothing can move along `d`.
    pub(super) mass: f32,
}

impl Jacobian {
    const ZERO: Self = Self {
        arm_a: Vec3A::ZERO,
        arm_b: Vec3A::ZERO,
        spin_a: Vec3A::ZERO,
        spin_b: Vec3A::ZERO,
        mass: 0.0,
    };

    fn new(a: &Body, b: &Body, anchor_a: Vec3A, anchor_b: Vec3A, direction: Vec3A) -> Self {
        let arm_a = anchor_a.cross(direction);
        let arm_b = anchor_b.cross(direction);
        let spin_a = a.world_inverse_inertia.mul_vec3a(arm_a);
        let spin_b = b.world_inverse_inertia.mul_vec3a(arm_b);
        let k = a.inverse_mass + b.inverse_mass + arm_a.dot(spin_a) + arm_b.dot(spin_b);
        Self {
            arm_a,
            arm_b,
            spin_a,
            spin_b,
            mass: inverse_or_zero(k),
        }
    }

    /// Relative velocity of B's point with respect to A's along the direction:
    /// `d·(v_B − v_A) + ω_B·(r_B × d) − ω_A·(r_A × d)`.
    fn velocity(&self, a: &BodyState, b: &BodyState, direction: Vec3A) -> f32 {
        direction.dot(b.linear_velocity - a.linear_velocity) + b.angular_velocity.dot(self.arm_b)
            - a.angular_velocity.dot(self.arm_a)
    }

    /// Applies `impulse` along the direction to B and its opposite to A:
    /// `Δv = ±λ d / m`, `Δω = ±λ I⁻¹ (r × d)`.
    fn apply(&self, a: &mut BodyState, b: &mut BodyState, direction: Vec3A, impulse: f32) {
        a.linear_velocity -= (a.inverse_mass * impulse) * direction;
        a.angular_velocity -= impulse * self.spin_a;
        b.linear_velocity += (b.inverse_mass * impulse) * direction;
        b.angular_velocity += impulse * self.spin_b;
    }
}

/// A body as the constraint builder sees it.
struct Body {
    center_of_mass: Vec3A,
    inverse_mass: f32,
    world_inverse_inertia: Mat3,
    linear_velocity: Vec3A,
    angular_velocity: Vec3A,
}

impl Body {
    fn new(state: &BodyState, motion: &BodyMotion) -> Self {
        Self {
            center_of_mass: motion.center_of_mass.into(),
            inverse_mass: state.inverse_mass,
            world_inverse_inertia: motion.world_inverse_inertia,
            linear_velocity: state.linear_velocity,
            angular_velocity: state.angular_velocity,
        }
    }

    fn velocity_at(&self, anchor: Vec3A) -> Vec3A {
        self.linear_velocity + self.angular_velocity.cross(anchor)
    }
}

fn inverse_or_zero(k: f32) -> f32 {
    if k > 0.0 {
        1.0 / k
    } else {
        0.0
    }
}

/// One point of a contact constraint: the normal (non-penetration) part.
#[derive(Debug, Clone, Copy)]
pub(super) struct ConstraintPoint {
    pub(super) normal: Jacobian,
    /// Separation at the start of the step, metres.
    pub(super) base_separation: f32,
    /// Normal relative velocity at the start of the step, m/s (negative when approaching).
    pub(super) approach_velocity: f32,
    /// Accumulated normal impulse, N·s; never negative.
    pub(super) normal_impulse: f32,
    /// Largest normal impulse applied in one iteration this step: zero means the point never
    /// pushed, and restitution must not act on it.
    pub(super) max_normal_impulse: f32,
}

impl ConstraintPoint {
    const ZERO: Self = Self {
        normal: Jacobian::ZERO,
        base_separation: 0.0,
        approach_velocity: 0.0,
        normal_impulse: 0.0,
        max_normal_impulse: 0.0,
    };

    /// The separation now: the start value plus how the bodies moved along the normal since,
    /// `s₀ + n·(Δc_B − Δc_A) + Δθ_B·(r_B × n) − Δθ_A·(r_A × n)` (rotation to first order).
    fn current_separation(&self, a: &BodyState, b: &BodyState, normal: Vec3A) -> f32 {
        self.base_separation
            + normal.dot(b.delta_position - a.delta_position)
            + b.delta_rotation.dot(self.normal.arm_b)
            - a.delta_rotation.dot(self.normal.arm_a)
    }
}

/// A manifold turned into a velocity constraint between two solver bodies.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactConstraint {
    pub(super) body_a: usize,
    pub(super) body_b: usize,
    /// Index of the contact in the contact cache, to store impulses back.
    pub(super) contact: usize,
    pub(super) normal: Vec3A,
    pub(super) tangents: [Vec3A; 2],
    pub(super) friction: f32,
    pub(super) restitution: f32,
    pub(super) points: [ConstraintPoint; MAX_MANIFOLD_POINTS],
    pub(super) point_count: usize,
    /// Friction acts at the centre of the points, along the two tangents.
    pub(super) tangent: [Jacobian; 2],
    /// Accumulated friction impulses along the two tangents, N·s.
    pub(super) tangent_impulse: [f32; 2],
    /// The friction anchors in the bodies' axes (see [`Contact`]), and how far B's anchor was
    /// from A's along each tangent at the start of the step, m.
    pub(super) friction_anchors: [Vec3; 2],
    pub(super) anchor_offset: [f32; 2],
    /// Whether the friction cone clamped the friction impulse this step.
    pub(super) slid: bool,
    /// `I_A⁻¹ n` and `I_B⁻¹ n`: the spin a unit twist impulse gives.
    pub(super) twist_spin_a: Vec3A,
    pub(super) twist_spin_b: Vec3A,
    /// `1 / (n · (I_A⁻¹ + I_B⁻¹) n)`: effective inertia for turning about the normal.
    pub(super) twist_mass: f32,
    /// Mean distance of the points from their centre, m: the lever of twist friction.
    pub(super) twist_radius: f32,
    /// Accumulated twist impulse about the normal, N·m·s.
    pub(super) twist_impulse: f32,
}

impl ContactConstraint {
    /// Builds the constraint of `contact` (index `contact_index`) between solver bodies `body_a`
    /// and `body_b`, warm-started from the contact's cached impulses.
    pub fn new(
        contact: &Contact,
        contact_index: usize,
        (states, motions): (&[BodyState], &[BodyMotion]),
        body_a: usize,
        body_b: usize,
        materials: (&RigidBody, &RigidBody),
    ) -> Self {
        let a = Body::new(&states[body_a], &motions[body_a]);
        let b = Body::new(&states[body_b], &motions[body_b]);
        let normal = Vec3A::from(contact.manifold.normal);
        let (tangent_1, tangent_2) = normal.any_orthonormal_pair();
        let tangents = [tangent_1, tangent_2];
        let manifold_points = contact.manifold.points();
        let mut points = [ConstraintPoint::ZERO; MAX_MANIFOLD_POINTS];
        for ((point, &normal_impulse), constraint_point) in manifold_points
            .iter()
            .zip(&contact.normal_impulses)
            .zip(&mut points)
        {
            let position = Vec3A::from(point.position);
            let anchor_a = position - a.center_of_mass;
            let anchor_b = position - b.center_of_mass;
            let relative_velocity = b.velocity_at(anchor_b) - a.velocity_at(anchor_a);
            *constraint_point = ConstraintPoint {
                normal: Jacobian::new(&a, &b, anchor_a, anchor_b, normal),
                base_separation: point.separation,
                approach_velocity: relative_velocity.dot(normal),
                normal_impulse,
                max_normal_impulse: 0.0,
            };
        }
        let count = manifold_points.len().max(1) as f32;
        let center = manifold_points
            .iter()
            .map(|point| Vec3A::from(point.position))
            .sum::<Vec3A>()
            / count;
        let twist_radius = manifold_points
            .iter()
            .map(|point| Vec3A::from(point.position).distance(center))
            .sum::<f32>()
            / count;
        let (center_a, center_b) = (center - a.center_of_mass, center - b.center_of_mass);
        let (material_a, material_b) = materials;
        let fresh_anchors = || {
            [
                material_a.rotation.inverse() * (Vec3::from(center) - material_a.center_of_mass),
                material_b.rotation.inverse() * (Vec3::from(center) - material_b.center_of_mass),
            ]
        };
        let carried = contact.friction_anchors.map(|[on_a, on_b]| {
            let anchor_a = material_a.center_of_mass + material_a.rotation * on_a;
            let anchor_b = material_b.center_of_mass + material_b.rotation * on_b;
            ([on_a, on_b], Vec3A::from(anchor_b - anchor_a))
        });
        let (friction_anchors, offset) = match carried {
            Some((anchors, offset))
                if (offset - normal * normal.dot(offset)).length_squared()
                    <= FRICTION_ANCHOR_MAX_SLIP * FRICTION_ANCHOR_MAX_SLIP =>
            {
                (anchors, offset)
            }
            _ => (fresh_anchors(), Vec3A::ZERO),
        };
        let twist_spin_a = a.world_inverse_inertia.mul_vec3a(normal);
        let twist_spin_b = b.world_inverse_inertia.mul_vec3a(normal);
        Self {
            body_a,
            body_b,
            contact: contact_index,
            normal,
            tangents,
            friction: combine_friction(materials.0.friction, materials.1.friction),
            restitution: combine_restitution(materials.0.restitution, materials.1.restitution),
            points,
            point_count: manifold_points.len(),
            tangent: [
                Jacobian::new(&a, &b, center_a, center_b, tangent_1),
                Jacobian::new(&a, &b, center_a, center_b, tangent_2),
            ],
            tangent_impulse: tangents
                .map(|tangent| Vec3A::from(contact.friction_impulse).dot(tangent)),
            friction_anchors,
            anchor_offset: tangents.map(|tangent| offset.dot(tangent)),
            slid: false,
            twist_spin_a,
            twist_spin_b,
            twist_mass: inverse_or_zero(normal.dot(twist_spin_a) + normal.dot(twist_spin_b)),
            twist_radius,
            twist_impulse: contact.twist_impulse,
        }
    }

    fn points(&self) -> &[ConstraintPoint] {
        &self.points[..self.point_count]
    }

    fn friction_impulse(&self) -> Vec3 {
        (self.tangent_impulse[0] * self.tangents[0] + self.tangent_impulse[1] * self.tangents[1])
            .into()
    }

    /// How far B's friction anchor is from A's along tangent `axis` now, m: the offset at the
    /// start of the step plus the motion since, to first order in the rotation.
    fn tangent_offset(&self, axis: usize, a: &BodyState, b: &BodyState) -> f32 {
        let jacobian = &self.tangent[axis];
        self.anchor_offset[axis]
            + self.tangents[axis].dot(b.delta_position - a.delta_position)
            + b.delta_rotation.dot(jacobian.arm_b)
            - a.delta_rotation.dot(jacobian.arm_a)
    }

    fn apply_twist(&self, a: &mut BodyState, b: &mut BodyState, impulse: f32) {
        a.angular_velocity -= impulse * self.twist_spin_a;
        b.angular_velocity += impulse * self.twist_spin_b;
    }

    /// Applies last step's accumulated impulses again (warm starting).
    pub fn warm_start(&self, states: &mut [BodyState]) {
        let (mut a, mut b) = (states[self.body_a], states[self.body_b]);
        let (a, b) = (&mut a, &mut b);
        for point in self.points() {
            point.normal.apply(a, b, self.normal, point.normal_impulse);
        }
        for axis in 0..2 {
            self.tangent[axis].apply(a, b, self.tangents[axis], self.tangent_impulse[axis]);
        }
        self.apply_twist(a, b, self.twist_impulse);
        store_velocities(states, self.body_a, a);
        store_velocities(states, self.body_b, b);
    }

    /// One sequential-impulse pass: the normal impulse of each point with accumulated clamping
    /// (the total never pulls), then the manifold's friction clamped to the friction cone and its
    /// twist. A point still apart by `s > 0` may close by `s` this substep (speculative contact).
    /// With `use_bias`, a point deeper than [`LINEAR_SLOP`] is pushed out by a soft constraint;
    /// within the slop the contact is rigid, so a resting contact carries its load without the
    /// sag a soft spring has under load (docs/physics.md compares the variants). Without
    /// `use_bias` (the relax pass) only velocities are solved, which removes the energy the push
    /// added.
    pub fn solve(
        &mut self,
        states: &mut [BodyState],
        softness: &Softness,
        inverse_h: f32,
        use_bias: bool,
    ) {
        let (mut a, mut b) = (states[self.body_a], states[self.body_b]);
        let (a, b) = (&mut a, &mut b);
        let normal = self.normal;
        let mut total_normal_impulse = 0.0;
        for point in &mut self.points[..self.point_count] {
            let separation = point.current_separation(a, b, normal);
            let (bias, mass_scale, impulse_scale) = if separation > 0.0 {
                (separation * inverse_h, 1.0, 0.0)
            } else if use_bias && separation < -LINEAR_SLOP {
                let bias = (softness.bias_rate * (separation + LINEAR_SLOP)).max(-MAX_PUSH_SPEED);
                (bias, softness.mass_scale, softness.impulse_scale)
            } else {
                (0.0, 1.0, 0.0)
            };
            let normal_velocity = point.normal.velocity(a, b, normal);
            let impulse = -point.normal.mass * mass_scale * (normal_velocity + bias)
                - impulse_scale * point.normal_impulse;
            let total = (point.normal_impulse + impulse).max(0.0);
            let applied = total - point.normal_impulse;
            point.normal_impulse = total;
            point.max_normal_impulse = point.max_normal_impulse.max(applied);
            total_normal_impulse += total;
            point.normal.apply(a, b, normal, applied);
        }

        let limit = self.friction * total_normal_impulse;
        let old = self.tangent_impulse;
        let mut total = [0.0; 2];
        for axis in 0..2 {
            let mut velocity = self.tangent[axis].velocity(a, b, self.tangents[axis]);
            if use_bias {
                velocity += inverse_h * self.tangent_offset(axis, a, b);
            }
            total[axis] = old[axis] - self.tangent[axis].mass * velocity;
        }
        let length = (total[0] * total[0] + total[1] * total[1]).sqrt();
        if length > limit {
            let scale = if length > 0.0 { limit / length } else { 0.0 };
            total = total.map(|value| value * scale);
            self.slid = true;
        }
        self.tangent_impulse = total;
        for axis in 0..2 {
            self.tangent[axis].apply(a, b, self.tangents[axis], total[axis] - old[axis]);
        }

        let twist_limit = limit * self.twist_radius;
        let spin = (b.angular_velocity - a.angular_velocity).dot(normal);
        let old_twist = self.twist_impulse;
        self.twist_impulse = (old_twist - self.twist_mass * spin).clamp(-twist_limit, twist_limit);
        self.apply_twist(a, b, self.twist_impulse - old_twist);
        store_velocities(states, self.body_a, a);
        store_velocities(states, self.body_b, b);
    }

    /// After the substeps: points that were approaching faster than [`RESTITUTION_THRESHOLD`] and
    /// pushed this step leave with `v_n = −e · v_n,start`.
    pub fn apply_restitution(&mut self, states: &mut [BodyState]) {
        if self.restitution == 0.0 {
            return;
        }
        let (mut a, mut b) = (states[self.body_a], states[self.body_b]);
        let (a, b) = (&mut a, &mut b);
        let normal = self.normal;
        for point in &mut self.points[..self.point_count] {
            if point.approach_velocity > -RESTITUTION_THRESHOLD || point.max_normal_impulse == 0.0 {
                continue;
            }
            let normal_velocity = point.normal.velocity(a, b, normal);
            let impulse =
                -point.normal.mass * (normal_velocity + self.restitution * point.approach_velocity);
            let total = (point.normal_impulse + impulse).max(0.0);
            let applied = total - point.normal_impulse;
            point.normal_impulse = total;
            point.normal.apply(a, b, normal, applied);
        }
        store_velocities(states, self.body_a, a);
        store_velocities(states, self.body_b, b);
    }

    /// Writes the accumulated impulses back to the contact cache for the next step's warm start.
    pub fn store_impulses(&self, contacts: &mut [Contact]) {
        let Some(contact) = contacts.get_mut(self.contact) else {
            return;
        };
        for (point, impulse) in self.points().iter().zip(&mut contact.normal_impulses) {
            *impulse = point.normal_impulse;
        }
        contact.friction_impulse = self.friction_impulse();
        contact.twist_impulse = self.twist_impulse;
        contact.friction_anchors = (!self.slid).then_some(self.friction_anchors);
    }
}

/// Writes back what solving a contact changes of a body: its velocities.
fn store_velocities(states: &mut [BodyState], index: usize, solved: &BodyState) {
    let state = &mut states[index];
    state.linear_velocity = solved.linear_velocity;
    state.angular_velocity = solved.angular_velocity;
}
