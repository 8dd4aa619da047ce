//! Four contact constraints of one colour solved at once, one per SIMD lane (Box2D v3's wide
//! solver idea; our own code).
//!
//! The four constraints share no moving body (`graph_colour.rs`), so solving them side by side
//! gives each the result solving it alone gives: lane `i` runs exactly the sequential-impulse
//! step of [`ContactConstraint::solve`] on constraint `i`, with each branch turned into a
//! per-lane select. A lane set with fewer than four constraints fills the rest with empty lanes on
//! solver body 0 (no mass, zero Jacobians: their impulses are zero); a manifold with fewer points
//! than the widest one of the set gets empty points the same way.

use super::contact_solver::{ContactConstraint, Jacobian, LINEAR_SLOP, MAX_PUSH_SPEED};
use super::softness::Softness;
use super::wide::{F32x4, Mask4, Vec3x4};
use super::BodyState;
use crate::collision::MAX_MANIFOLD_POINTS;
use crate::math::Vec3A;

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
#[derive(Debug, Clone, Copy, Default)]
struct JacobianLanes {
    arm_a: Vec3x4,
    arm_b: Vec3x4,
    spin_a: Vec3x4,
    spin_b: Vec3x4,
    mass: F32x4,
}

impl JacobianLanes {
    fn from_lanes(jacobians: [&Jacobian; LANES]) -> Self {
        Self {
            arm_a: Vec3x4::from_lanes(jacobians.map(|j| j.arm_a)),
            arm_b: Vec3x4::from_lanes(jacobians.map(|j| j.arm_b)),
            spin_a: Vec3x4::from_lanes(jacobians.map(|j| j.spin_a)),
            spin_b: Vec3x4::from_lanes(jacobians.map(|j| j.spin_b)),
            mass: F32x4::from_array(jacobians.map(|j| j.mass)),
        }
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
#[derive(Debug, Clone, Copy, Default)]
struct PointLanes {
    normal: JacobianLanes,
    base_separation: F32x4,
    normal_impulse: F32x4,
    max_normal_impulse: F32x4,
}

/// Four constraints of one colour, structure of arrays.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactLanes {
    /// The constraint of each lane, as an index into the solver's constraint list; only the first
    /// `constraint_count` lanes hold one.
    constraints: [usize; LANES],
    constraint_count: usize,
    body_a: [usize; LANES],
    body_b: [usize; LANES],
    inverse_mass_a: F32x4,
    inverse_mass_b: F32x4,
    normal: Vec3x4,
    tangents: [Vec3x4; 2],
    friction: F32x4,
    /// The most points of any lane's manifold.
    point_count: usize,
    points: [PointLanes; MAX_MANIFOLD_POINTS],
    tangent: [JacobianLanes; 2],
    tangent_impulse: [F32x4; 2],
    anchor_offset: [F32x4; 2],
    slid: Mask4,
    twist_spin_a: Vec3x4,
    twist_spin_b: Vec3x4,
    twist_mass: F32x4,
    twist_radius: F32x4,
    twist_impulse: F32x4,
}

impl ContactLanes {
    /// Packs the constraints `members` (one to four indices into `constraints`, sharing no
    /// moving body) into one lane set.
    pub fn pack(
        members: &[usize],
        constraints: &[ContactConstraint],
        states: &[BodyState],
    ) -> Self {
        let empty = ContactConstraint::EMPTY;
        let lane = |i: usize| members.get(i).map_or(&empty, |&index| &constraints[index]);
        let lanes = [lane(0), lane(1), lane(2), lane(3)];
        let point_count = lanes.iter().map(|c| c.point_count).max().unwrap_or(0);
        let mut points = [PointLanes::default(); MAX_MANIFOLD_POINTS];
        for (index, point) in points.iter_mut().enumerate().take(point_count) {
            let of_lanes = lanes.map(|c| &c.points[index]);
            *point = PointLanes {
                normal: JacobianLanes::from_lanes(of_lanes.map(|p| &p.normal)),
                base_separation: F32x4::from_array(of_lanes.map(|p| p.base_separation)),
                normal_impulse: F32x4::from_array(of_lanes.map(|p| p.normal_impulse)),
                max_normal_impulse: F32x4::from_array(of_lanes.map(|p| p.max_normal_impulse)),
            };
        }
        let mut constraint_indices = [0; LANES];
        constraint_indices[..members.len()].copy_from_slice(members);
        let body_a = lanes.map(|c| c.body_a);
        let body_b = lanes.map(|c| c.body_b);
        Self {
            constraints: constraint_indices,
            constraint_count: members.len(),
            body_a,
            body_b,
            inverse_mass_a: F32x4::from_array(body_a.map(|body| states[body].inverse_mass)),
            inverse_mass_b: F32x4::from_array(body_b.map(|body| states[body].inverse_mass)),
            normal: Vec3x4::from_lanes(lanes.map(|c| c.normal)),
            tangents: [0, 1].map(|axis| Vec3x4::from_lanes(lanes.map(|c| c.tangents[axis]))),
            friction: F32x4::from_array(lanes.map(|c| c.friction)),
            point_count,
            points,
            tangent: [0, 1].map(|axis| JacobianLanes::from_lanes(lanes.map(|c| &c.tangent[axis]))),
            tangent_impulse: [0, 1]
                .map(|axis| F32x4::from_array(lanes.map(|c| c.tangent_impulse[axis]))),
            anchor_offset: [0, 1]
                .map(|axis| F32x4::from_array(lanes.map(|c| c.anchor_offset[axis]))),
            slid: Mask4::NONE,
            twist_spin_a: Vec3x4::from_lanes(lanes.map(|c| c.twist_spin_a)),
            twist_spin_b: Vec3x4::from_lanes(lanes.map(|c| c.twist_spin_b)),
            twist_mass: F32x4::from_array(lanes.map(|c| c.twist_mass)),
            twist_radius: F32x4::from_array(lanes.map(|c| c.twist_radius)),
            twist_impulse: F32x4::from_array(lanes.map(|c| c.twist_impulse)),
        }
    }

    /// Writes the accumulated impulses and the sliding flag back into the lanes' constraints.
    pub fn unpack(&self, constraints: &mut [ContactConstraint]) {
        for (lane, &index) in self.constraints[..self.constraint_count].iter().enumerate() {
            let constraint = &mut constraints[index];
            let points = constraint.points.iter_mut().take(constraint.point_count);
            for (point, solved) in points.zip(&self.points) {
                point.normal_impulse = solved.normal_impulse.lane(lane);
                point.max_normal_impulse = solved.max_normal_impulse.lane(lane);
            }
            constraint.tangent_impulse = self.tangent_impulse.map(|impulse| impulse.lane(lane));
            constraint.twist_impulse = self.twist_impulse.lane(lane);
            constraint.slid |= self.slid.lane(lane);
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
