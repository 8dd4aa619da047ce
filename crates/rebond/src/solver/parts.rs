//! Constraint parts: the pieces a constraint between two bodies is built from, each for four
//! constraints at once (one per SIMD lane, `wide.rs`), after Jolt's `Constraints/ConstraintPart/`.
//!
//! A constraint `C(x_A, q_A, x_B, q_B) = 0` (or `≥ 0`) is solved on its velocity
//! `Ċ = J V`, with `V = (v_A, ω_A, v_B, ω_B)` the bodies' velocities and `J` its Jacobian. A part
//! keeps `J`, the spin `M⁻¹ Jᵀ` a unit impulse gives and the effective mass `K⁻¹`,
//! `K = J M⁻¹ Jᵀ`, so an impulse `λ = −K⁻¹ (Ċ + bias)` cancels `Ċ + bias` in one step, and
//! applying it changes the velocities by `ΔV = M⁻¹ Jᵀ λ`.
//!
//! Here: the axis part ([`JacobianLanes`], a direction `d` at two anchors), used by every contact
//! point's normal and by the manifold's two friction directions, and the body views the parts
//! read and write ([`BodyLanes`], [`BodyFrame`]). Joints add their parts here: a point part
//! (three axis parts at one anchor, the ball joint's `K` a 3×3 matrix) and an angle part (a
//! rotation about an axis, `J = [0, −aᵀ, 0, aᵀ]`, the form the contact's twist friction takes
//! inline in `contact_lanes.rs`).

use super::wide::{F32x4, Mat3x4, Vec3x4, LANES};
use super::{BodyMotion, BodyState};
use crate::math::Vec3A;

/// The velocities of four constraints' bodies on one side, gathered from the body states.
pub(super) struct BodyLanes {
    linear_velocity: Vec3x4,
    angular_velocity: Vec3x4,
}

impl BodyLanes {
    pub(super) fn gather(states: &[BodyState], bodies: &[usize; LANES]) -> Self {
        let [a, b, c, d] = *bodies;
        let (a, b, c, d) = (&states[a], &states[b], &states[c], &states[d]);
        let field = |f: fn(&BodyState) -> Vec3A| Vec3x4::from_lanes([f(a), f(b), f(c), f(d)]);
        Self {
            linear_velocity: field(|s| s.linear_velocity),
            angular_velocity: field(|s| s.angular_velocity),
        }
    }

    /// Writes the velocities back; body 0 (fixed, and the empty lanes) never changes.
    pub(super) fn scatter(&self, states: &mut [BodyState], bodies: &[usize; LANES]) {
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

/// What a constraint builder reads of the bodies on one side of four constraints: the inverse
/// inertia at the start of the step. The lever arms come with the constraints
/// (`contact_frame.rs`).
pub(super) struct BodyFrame {
    /// `I⁻¹` in world axes.
    pub inverse_inertia: Mat3x4,
}

impl BodyFrame {
    /// The frames of the solver bodies `bodies`, one per lane. Inlined into the builder: as a
    /// call, its lanes go through memory.
    #[inline(always)]
    pub(super) fn gather(motions: &[BodyMotion], bodies: &[usize; LANES]) -> Self {
        let [a, b, c, d] = *bodies;
        let motions = [&motions[a], &motions[b], &motions[c], &motions[d]];
        Self {
            inverse_inertia: Mat3x4::from_lanes(motions.map(|m| &m.world_inverse_inertia)),
        }
    }
}

/// `1 / k` per lane, or zero where `k` is not above zero: the effective mass `K⁻¹` of a part,
/// zero where nothing can move along it (both bodies fixed, or an empty lane).
pub(super) fn inverse_or_zero(k: F32x4) -> F32x4 {
    k.greater_than(F32x4::ZERO)
        .select(F32x4::ONE / k, F32x4::ZERO)
}

/// The axis part: the relative velocity of two anchors `r_A`, `r_B` (from each centre of mass)
/// along a direction `d`, per lane, with the angular response precomputed from the inverse
/// inertia at the start of the step.
///
/// - Jacobian: `J = [−dᵀ, −(r_A × d)ᵀ, dᵀ, (r_B × d)ᵀ]`, so
///   `Ċ = d·(v_B − v_A) + ω_B·(r_B × d) − ω_A·(r_A × d)`.
/// - Effective mass: `K = J M⁻¹ Jᵀ = m_A⁻¹ + m_B⁻¹ + (r_A × d)·I_A⁻¹(r_A × d) +
///   (r_B × d)·I_B⁻¹(r_B × d)`, kept as `K⁻¹`.
/// - Impulse `λ`: `ΔV = M⁻¹ Jᵀ λ`, i.e. `Δv_A = −λ d / m_A`, `Δω_A = −λ I_A⁻¹(r_A × d)`,
///   `Δv_B = +λ d / m_B`, `Δω_B = +λ I_B⁻¹(r_B × d)`.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(super) struct JacobianLanes {
    /// `r_A × d` and `r_B × d`: how each body's spin moves the anchors along `d`.
    pub arm_a: Vec3x4,
    pub arm_b: Vec3x4,
    /// `I_A⁻¹ (r_A × d)` and `I_B⁻¹ (r_B × d)`: the spin a unit impulse along `d` gives.
    pub spin_a: Vec3x4,
    pub spin_b: Vec3x4,
    /// The effective mass along `d`, `K⁻¹`, kg.
    pub mass: F32x4,
}

impl JacobianLanes {
    pub(super) const ZERO: Self = Self {
        arm_a: Vec3x4::ZERO,
        arm_b: Vec3x4::ZERO,
        spin_a: Vec3x4::ZERO,
        spin_b: Vec3x4::ZERO,
        mass: F32x4::ZERO,
    };

    /// The Jacobian of direction `direction` at the anchors `r_A`, `r_B` per lane, with
    /// `mass = 1 / K`, or zero where nothing can move along `d`.
    pub(super) fn new(
        (a, b): (&BodyFrame, &BodyFrame),
        (inverse_mass_a, inverse_mass_b): (F32x4, F32x4),
        (anchor_a, anchor_b): (Vec3x4, Vec3x4),
        direction: Vec3x4,
    ) -> Self {
        let arm_a = anchor_a.cross(direction);
        let arm_b = anchor_b.cross(direction);
        let spin_a = a.inverse_inertia.mul_vec3(arm_a);
        let spin_b = b.inverse_inertia.mul_vec3(arm_b);
        let k = inverse_mass_a + inverse_mass_b + arm_a.dot(spin_a) + arm_b.dot(spin_b);
        Self {
            arm_a,
            arm_b,
            spin_a,
            spin_b,
            mass: inverse_or_zero(k),
        }
    }

    /// `Ċ = J V = d·(v_B − v_A) + ω_B·(r_B × d) − ω_A·(r_A × d)` per lane.
    pub(super) fn velocity(&self, a: &BodyLanes, b: &BodyLanes, direction: Vec3x4) -> F32x4 {
        direction.dot(b.linear_velocity - a.linear_velocity)
            + self.spin_velocity(a.angular_velocity, b.angular_velocity)
    }

    /// The part of [`Self::velocity`] the spins `ω_A`, `ω_B` give, `ω_B·(r_B × d) − ω_A·(r_A × d)`.
    pub(super) fn spin_velocity(&self, angular_a: Vec3x4, angular_b: Vec3x4) -> F32x4 {
        angular_b.dot(self.arm_b) - angular_a.dot(self.arm_a)
    }

    /// The spin part of [`Self::apply`]: `Δω_A = −λ I_A⁻¹ (r_A × d)`, `Δω_B = +λ I_B⁻¹ (r_B × d)`.
    pub(super) fn apply_spin(
        &self,
        angular_a: &mut Vec3x4,
        angular_b: &mut Vec3x4,
        impulse: F32x4,
    ) {
        *angular_a -= self.spin_a.scale(impulse);
        *angular_b += self.spin_b.scale(impulse);
    }

    /// `ΔV = M⁻¹ Jᵀ λ`: `Δv = ±λ d / m`, `Δω = ±λ I⁻¹ (r × d)` per lane (A gets the minus sign).
    pub(super) fn apply(
        &self,
        (a, b): (&mut BodyLanes, &mut BodyLanes),
        (inverse_mass_a, inverse_mass_b): (F32x4, F32x4),
        direction: Vec3x4,
        impulse: F32x4,
    ) {
        a.linear_velocity -= direction.scale(inverse_mass_a * impulse);
        b.linear_velocity += direction.scale(inverse_mass_b * impulse);
        self.apply_spin(&mut a.angular_velocity, &mut b.angular_velocity, impulse);
    }
}
