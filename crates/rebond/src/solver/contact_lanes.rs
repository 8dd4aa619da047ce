//! Four contact constraints of one colour solved at once, one per SIMD lane (Box2D v3's wide
//! solver idea; our own code).
//!
//! The four constraints share no moving body (`graph_colour.rs`), so solving them side by side
//! gives each the result solving it alone gives: lane `i` runs exactly the sequential-impulse
//! step of [`ContactConstraint::solve`] on constraint `i`, with each branch turned into a
//! per-lane select. A lane set with fewer than four constraints fills the rest with empty lanes on
//! solver body 0 (no mass, zero Jacobians: their impulses are zero); a manifold with fewer points
//! than the widest one of the set gets empty points the same way.

use super::contact_solver::{
    ContactConstraint, Jacobian, LINEAR_SLOP, MAX_PUSH_SPEED, RESTITUTION_THRESHOLD,
};
use super::softness::Softness;
use super::wide::{F32x4, Mask4, Vec3x4};
use super::BodyState;
use crate::collision::contact_cache::Contact;
use crate::collision::MAX_MANIFOLD_POINTS;
use crate::math::{Vec3, Vec3A};

/// Lanes per set.
pub const LANES: usize = 4;

/// What a lane set reads of its bodies, gathered from the body states.
struct BodyLanes {
    linear_velocity: Vec3x4,
    angular_velocity: Vec3x4,
    delta_position: Vec3x4,
    delta_rotation: Vec3x4,
}

impl BodyLanes {
    fn gather(states: &[BodyState], bodies: &[usize; LANES]) -> Self {
        let [a, b, c, d] = [0, 1, 2, 3].map(|lane| &states[bodies[lane]]);
        let field = |f: fn(&BodyState) -> Vec3A| Vec3x4::from_lanes([f(a), f(b), f(c), f(d)]);
        Self {
            linear_velocity: field(|s| s.linear_velocity),
            angular_velocity: field(|s| s.angular_velocity),
            delta_position: field(|s| s.delta_position),
            delta_rotation: field(|s| s.delta_rotation),
        }
    }

    /// Writes the velocities back; body 0 (fixed, and the empty lanes) never changes.
    fn scatter(&self, states: &mut [BodyState], bodies: &[usize; LANES]) {
        let linear = self.linear_velocity.lanes();
        let angular = self.angular_velocity.lanes();
        for (lane, &body) in bodies.iter().enumerate() {
            if body != 0 {
                let state = &mut states[body];
                state.linear_velocity = linear[lane];
                state.angular_velocity = angular[lane];
            }
        }
    }
}

/// [`Jacobian`] of four constraints.
#[derive(Debug, Clone, Copy)]
struct JacobianLanes {
    arm_a: Vec3x4,
    arm_b: Vec3x4,
    spin_a: Vec3x4,
    spin_b: Vec3x4,
    mass: F32x4,
}

impl JacobianLanes {
    const ZERO: Self = Self {
        arm_a: Vec3x4::ZERO,
        arm_b: Vec3x4::ZERO,
        spin_a: Vec3x4::ZERO,
        spin_b: Vec3x4::ZERO,
        mass: F32x4::ZERO,
    };

    fn set_lane(&mut self, lane: usize, jacobian: &Jacobian) {
        self.arm_a.set_lane(lane, jacobian.arm_a);
        self.arm_b.set_lane(lane, jacobian.arm_b);
        self.spin_a.set_lane(lane, jacobian.spin_a);
        self.spin_b.set_lane(lane, jacobian.spin_b);
        self.mass.set_lane(lane, jacobian.mass);
    }

    /// `d·(v_B − v_A) + ω_B·(r_B × d) − ω_A·(r_A × d)` per lane.
    fn velocity(&self, a: &BodyLanes, b: &BodyLanes, direction: Vec3x4) -> F32x4 {
        direction.dot(b.linear_velocity - a.linear_velocity) + b.angular_velocity.dot(self.arm_b)
            - a.angular_velocity.dot(self.arm_a)
    }

    /// `Δv = ±λ d / m`, `Δω = ±λ I⁻¹ (r × d)` per lane (A gets the minus sign).
    fn apply(
        &self,
        (a, b): (&mut BodyLanes, &mut BodyLanes),
        (inverse_mass_a, inverse_mass_b): (F32x4, F32x4),
        direction: Vec3x4,
        impulse: F32x4,
    ) {
        a.linear_velocity -= direction.scale(inverse_mass_a * impulse);
        a.angular_velocity -= self.spin_a.scale(impulse);
        b.linear_velocity += direction.scale(inverse_mass_b * impulse);
        b.angular_velocity += self.spin_b.scale(impulse);
    }
}

/// The normal part of one point of four constraints.
#[derive(Debug, Clone, Copy)]
struct PointLanes {
    normal: JacobianLanes,
    base_separation: F32x4,
    approach_velocity: F32x4,
    normal_impulse: F32x4,
    max_normal_impulse: F32x4,
}

impl PointLanes {
    const ZERO: Self = Self {
        normal: JacobianLanes::ZERO,
        base_separation: F32x4::ZERO,
        approach_velocity: F32x4::ZERO,
        normal_impulse: F32x4::ZERO,
        max_normal_impulse: F32x4::ZERO,
    };
}

/// Four constraints of one colour, structure of arrays: built from the contacts, solved, and
/// their impulses stored back into the contact cache, with no scalar constraint kept between.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactLanes {
    /// The contact of each lane, as an index into the contact cache; `usize::MAX` in empty lanes.
    contacts: [usize; LANES],
    body_a: [usize; LANES],
    body_b: [usize; LANES],
    inverse_mass_a: F32x4,
    inverse_mass_b: F32x4,
    normal: Vec3x4,
    tangents: [Vec3x4; 2],
    friction: F32x4,
    restitution: F32x4,
    /// Whether any lane bounces (restitution above zero).
    bounces: bool,
    /// The manifold's points in each lane, and the most of any lane.
    point_counts: [usize; LANES],
    point_count: usize,
    points: [PointLanes; MAX_MANIFOLD_POINTS],
    tangent: [JacobianLanes; 2],
    tangent_impulse: [F32x4; 2],
    friction_anchors: [[Vec3; 2]; LANES],
    anchor_offset: [F32x4; 2],
    slid: Mask4,
    twist_spin_a: Vec3x4,
    twist_spin_b: Vec3x4,
    twist_mass: F32x4,
    twist_radius: F32x4,
    twist_impulse: F32x4,
}

impl ContactLanes {
    /// A lane set whose lanes are all empty: on solver body 0, with no contact, no points and no
    /// mass in any direction, so solving them changes nothing. [`Self::set_lane`] fills lanes.
    pub const EMPTY: Self = Self {
        contacts: [usize::MAX; LANES],
        body_a: [0; LANES],
        body_b: [0; LANES],
        inverse_mass_a: F32x4::ZERO,
        inverse_mass_b: F32x4::ZERO,
        normal: Vec3x4::ZERO,
        tangents: [Vec3x4::ZERO; 2],
        friction: F32x4::ZERO,
        restitution: F32x4::ZERO,
        bounces: false,
        point_counts: [0; LANES],
        point_count: 0,
        points: [PointLanes::ZERO; MAX_MANIFOLD_POINTS],
        tangent: [JacobianLanes::ZERO; 2],
        tangent_impulse: [F32x4::ZERO; 2],
        friction_anchors: [[Vec3::ZERO; 2]; LANES],
        anchor_offset: [F32x4::ZERO; 2],
        slid: Mask4::NONE,
        twist_spin_a: Vec3x4::ZERO,
        twist_spin_b: Vec3x4::ZERO,
        twist_mass: F32x4::ZERO,
        twist_radius: F32x4::ZERO,
        twist_impulse: F32x4::ZERO,
    };

    /// Puts `constraint` into lane `lane`; the lanes of one set must share no moving body.
    pub fn set_lane(&mut self, lane: usize, constraint: &ContactConstraint, states: &[BodyState]) {
        self.contacts[lane] = constraint.contact;
        self.body_a[lane] = constraint.body_a;
        self.body_b[lane] = constraint.body_b;
        let inverse_mass = |body: usize| states[body].inverse_mass;
        self.inverse_mass_a
            .set_lane(lane, inverse_mass(constraint.body_a));
        self.inverse_mass_b
            .set_lane(lane, inverse_mass(constraint.body_b));
        self.normal.set_lane(lane, constraint.normal);
        self.friction.set_lane(lane, constraint.friction);
        self.restitution.set_lane(lane, constraint.restitution);
        self.bounces |= constraint.restitution > 0.0;
        self.point_counts[lane] = constraint.point_count;
        self.point_count = self.point_count.max(constraint.point_count);
        let points = &constraint.points[..constraint.point_count];
        for (point, source) in self.points.iter_mut().zip(points) {
            point.normal.set_lane(lane, &source.normal);
            point.base_separation.set_lane(lane, source.base_separation);
            point
                .approach_velocity
                .set_lane(lane, source.approach_velocity);
            point.normal_impulse.set_lane(lane, source.normal_impulse);
            point
                .max_normal_impulse
                .set_lane(lane, source.max_normal_impulse);
        }
        for axis in 0..2 {
            self.tangents[axis].set_lane(lane, constraint.tangents[axis]);
            self.tangent[axis].set_lane(lane, &constraint.tangent[axis]);
            self.tangent_impulse[axis].set_lane(lane, constraint.tangent_impulse[axis]);
            self.anchor_offset[axis].set_lane(lane, constraint.anchor_offset[axis]);
        }
        self.friction_anchors[lane] = constraint.friction_anchors;
        self.twist_spin_a.set_lane(lane, constraint.twist_spin_a);
        self.twist_spin_b.set_lane(lane, constraint.twist_spin_b);
        self.twist_mass.set_lane(lane, constraint.twist_mass);
        self.twist_radius.set_lane(lane, constraint.twist_radius);
        self.twist_impulse.set_lane(lane, constraint.twist_impulse);
    }

    /// [`ContactConstraint::apply_restitution`] of the four lanes: a point bounces where its
    /// lane's restitution is above zero, it approached faster than [`RESTITUTION_THRESHOLD`] and
    /// it pushed this step; elsewhere the impulse is zero.
    pub fn apply_restitution(&mut self, states: &mut [BodyState]) {
        if !self.bounces {
            return;
        }
        let mut a = BodyLanes::gather(states, &self.body_a);
        let mut b = BodyLanes::gather(states, &self.body_b);
        let masses = self.inverse_masses();
        let normal = self.normal;
        let elastic = self.restitution.greater_than(F32x4::ZERO);
        let slow = F32x4::splat(-RESTITUTION_THRESHOLD);
        for point in &mut self.points[..self.point_count] {
            let bounces = point
                .max_normal_impulse
                .greater_than(F32x4::ZERO)
                .and(elastic)
                .and_not(point.approach_velocity.greater_than(slow));
            let jacobian = &point.normal;
            let normal_velocity = jacobian.velocity(&a, &b, normal);
            let impulse =
                -jacobian.mass * (normal_velocity + self.restitution * point.approach_velocity);
            let total = (point.normal_impulse + impulse).max(F32x4::ZERO);
            let applied = bounces.select(total - point.normal_impulse, F32x4::ZERO);
            point.normal_impulse += applied;
            jacobian.apply((&mut a, &mut b), masses, normal, applied);
        }
        a.scatter(states, &self.body_a);
        b.scatter(states, &self.body_b);
    }

    /// Writes the accumulated impulses back to the lanes' contacts for the next step's warm
    /// start, as [`ContactConstraint::store_impulses`] does for one constraint.
    pub fn store_impulses(&self, contacts: &mut [Contact]) {
        let tangents = self.tangents.map(|tangent| tangent.lanes());
        for (lane, &index) in self.contacts.iter().enumerate() {
            let Some(contact) = contacts.get_mut(index) else {
                continue;
            };
            let points = self.points[..self.point_counts[lane]].iter();
            for (point, impulse) in points.zip(&mut contact.normal_impulses) {
                *impulse = point.normal_impulse.lane(lane);
            }
            let [tangent_1, tangent_2] = self.tangent_impulse.map(|impulse| impulse.lane(lane));
            contact.friction_impulse =
                (tangent_1 * tangents[0][lane] + tangent_2 * tangents[1][lane]).into();
            contact.twist_impulse = self.twist_impulse.lane(lane);
            contact.friction_anchors =
                (!self.slid.lane(lane)).then_some(self.friction_anchors[lane]);
        }
    }

    fn inverse_masses(&self) -> (F32x4, F32x4) {
        (self.inverse_mass_a, self.inverse_mass_b)
    }

    /// Twist impulse about the normal: `Δω_A = −λ I_A⁻¹ n`, `Δω_B = +λ I_B⁻¹ n` per lane.
    fn apply_twist(&self, a: &mut BodyLanes, b: &mut BodyLanes, impulse: F32x4) {
        a.angular_velocity -= self.twist_spin_a.scale(impulse);
        b.angular_velocity += self.twist_spin_b.scale(impulse);
    }

    /// [`ContactConstraint::warm_start`] of the four lanes. The impulses only add up, so they
    /// are summed first, `P = Σλ_i n + Σλ_t t + …` and `L_A = Σλ I_A⁻¹(r_A × d)`, and each body
    /// gets `Δv = ±P / m`, `Δω = ∓L_A` or `±L_B` once.
    pub fn warm_start(&self, states: &mut [BodyState]) {
        let mut linear = Vec3x4::default();
        let mut spin_a = self.twist_spin_a.scale(self.twist_impulse);
        let mut spin_b = self.twist_spin_b.scale(self.twist_impulse);
        let directions = [self.tangents[0], self.tangents[1]];
        let tangents = self
            .tangent
            .iter()
            .zip(directions)
            .zip(self.tangent_impulse);
        let normals = self.points[..self.point_count]
            .iter()
            .map(|point| ((&point.normal, self.normal), point.normal_impulse));
        for ((jacobian, direction), impulse) in normals.chain(tangents) {
            linear += direction.scale(impulse);
            spin_a += jacobian.spin_a.scale(impulse);
            spin_b += jacobian.spin_b.scale(impulse);
        }
        let linear_a = linear.scale(self.inverse_mass_a).lanes();
        let linear_b = linear.scale(self.inverse_mass_b).lanes();
        let (spin_a, spin_b) = (spin_a.lanes(), spin_b.lanes());
        for lane in 0..LANES {
            let (body_a, body_b) = (self.body_a[lane], self.body_b[lane]);
            if body_a != 0 {
                let state = &mut states[body_a];
                state.linear_velocity -= linear_a[lane];
                state.angular_velocity -= spin_a[lane];
            }
            if body_b != 0 {
                let state = &mut states[body_b];
                state.linear_velocity += linear_b[lane];
                state.angular_velocity += spin_b[lane];
            }
        }
    }

    /// [`ContactConstraint::solve`] of the four lanes: the normal impulse of each point, then the
    /// friction clamped to the cone `|λ_t| ≤ μ Σλ_n` and the twist to `μ Σλ_n r̄`.
    pub fn solve(
        &mut self,
        states: &mut [BodyState],
        softness: &Softness,
        inverse_h: f32,
        use_bias: bool,
    ) {
        let mut a = BodyLanes::gather(states, &self.body_a);
        let mut b = BodyLanes::gather(states, &self.body_b);
        let masses = self.inverse_masses();
        let normal = self.normal;
        let inverse_h = F32x4::splat(inverse_h);
        let slop = F32x4::splat(LINEAR_SLOP);
        // The bodies' centres move only between passes: Δc_B − Δc_A and n·(Δc_B − Δc_A) hold for
        // every point.
        let relative_motion = b.delta_position - a.delta_position;
        let normal_motion = normal.dot(relative_motion);
        let mut total_normal_impulse = F32x4::ZERO;
        for point in &mut self.points[..self.point_count] {
            let jacobian = &point.normal;
            // s = s₀ + n·(Δc_B − Δc_A) + Δθ_B·(r_B × n) − Δθ_A·(r_A × n)
            let separation =
                point.base_separation + normal_motion + b.delta_rotation.dot(jacobian.arm_b)
                    - a.delta_rotation.dot(jacobian.arm_a);
            // Apart: may close by s this substep. Deeper than the slop (biased pass): soft push
            // out at the bias rate, at most MAX_PUSH_SPEED. Otherwise rigid, no bias.
            let apart = separation.greater_than(F32x4::ZERO);
            let deep = if use_bias {
                separation.less_than(-slop)
            } else {
                Mask4::NONE
            };
            let push = (F32x4::splat(softness.bias_rate) * (separation + slop))
                .max(F32x4::splat(-MAX_PUSH_SPEED));
            let bias = apart.select(separation * inverse_h, deep.select(push, F32x4::ZERO));
            let mass_scale = deep.select(F32x4::splat(softness.mass_scale), F32x4::ONE);
            let impulse_scale = deep.select(F32x4::splat(softness.impulse_scale), F32x4::ZERO);
            let normal_velocity = jacobian.velocity(&a, &b, normal);
            let impulse = -jacobian.mass * mass_scale * (normal_velocity + bias)
                - impulse_scale * point.normal_impulse;
            let total = (point.normal_impulse + impulse).max(F32x4::ZERO);
            let applied = total - point.normal_impulse;
            point.normal_impulse = total;
            point.max_normal_impulse = point.max_normal_impulse.max(applied);
            total_normal_impulse += total;
            jacobian.apply((&mut a, &mut b), masses, normal, applied);
        }

        let limit = self.friction * total_normal_impulse;
        let old = self.tangent_impulse;
        let mut total = [F32x4::ZERO; 2];
        for axis in 0..2 {
            let jacobian = &self.tangent[axis];
            let mut velocity = jacobian.velocity(&a, &b, self.tangents[axis]);
            if use_bias {
                // The anchor offset now: start offset plus the motion since, along the tangent.
                let offset = self.anchor_offset[axis]
                    + self.tangents[axis].dot(relative_motion)
                    + b.delta_rotation.dot(jacobian.arm_b)
                    - a.delta_rotation.dot(jacobian.arm_a);
                velocity += inverse_h * offset;
            }
            total[axis] = old[axis] - jacobian.mass * velocity;
        }
        let length = (total[0] * total[0] + total[1] * total[1]).sqrt();
        let slides = length.greater_than(limit);
        let scale = length
            .greater_than(F32x4::ZERO)
            .select(limit / length, F32x4::ZERO);
        for value in &mut total {
            *value = slides.select(*value * scale, *value);
        }
        self.slid = self.slid.or(slides);
        self.tangent_impulse = total;
        for axis in 0..2 {
            let (jacobian, direction) = (&self.tangent[axis], self.tangents[axis]);
            jacobian.apply((&mut a, &mut b), masses, direction, total[axis] - old[axis]);
        }

        let twist_limit = limit * self.twist_radius;
        let spin = (b.angular_velocity - a.angular_velocity).dot(normal);
        let old_twist = self.twist_impulse;
        self.twist_impulse = (old_twist - self.twist_mass * spin)
            .max(-twist_limit)
            .min(twist_limit);
        self.apply_twist(&mut a, &mut b, self.twist_impulse - old_twist);
        a.scatter(states, &self.body_a);
        b.scatter(states, &self.body_b);
    }
}
