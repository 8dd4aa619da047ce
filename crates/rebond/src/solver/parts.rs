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
//! point's normal and by the manifold's two friction directions, the bodies' inverse masses
//! ([`LinearMasses`]) and the body views the parts read and write ([`BodyLanes`],
//! [`BodyFrame`]). Joints, few beside contacts, have scalar parts of their own
//! (`joint_parts.rs`).

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

/// The inverse masses of the bodies on the two sides of four constraints, per lane, kg⁻¹:
/// `M⁻¹ = m⁻¹ (𝟙 − L)`, `L` the diagonal with 1 on the world axes a body's translation is locked
/// along (`body/locked_axes.rs`). In lane sets without a locked body (`locked` false: all but
/// those of a locked body) the terms of `L` are skipped, so `M⁻¹ = m⁻¹ 𝟙` rounds as it always
/// has and costs nothing more.
#[derive(Debug, Clone, Copy)]
pub(super) struct LinearMasses {
    pub a: F32x4,
    pub b: F32x4,
    pub lock_a: Vec3x4,
    pub lock_b: Vec3x4,
    /// Whether some lane's body has a locked translation axis.
    pub locked: bool,
}

impl LinearMasses {
    pub(super) const ZERO: Self = Self {
        a: F32x4::ZERO,
        b: F32x4::ZERO,
        lock_a: Vec3x4::ZERO,
        lock_b: Vec3x4::ZERO,
        locked: false,
    };

    /// Sets lane `lane` from the bodies' motions.
    #[inline(always)]
    pub(super) fn set_lane(&mut self, lane: usize, a: &BodyMotion, b: &BodyMotion) {
        self.a.set_lane(lane, a.inverse_mass);
        self.b.set_lane(lane, b.inverse_mass);
        self.lock_a.set_lane(lane, a.translation_lock);
        self.lock_b.set_lane(lane, b.translation_lock);
        self.locked |= a.translation_lock != Vec3A::ZERO || b.translation_lock != Vec3A::ZERO;
    }

    /// `i · (M_A⁻¹ + M_B⁻¹) j` per lane: `(m_A⁻¹ + m_B⁻¹) i·j` less the locked axes' part.
    #[inline(always)]
    pub(super) fn coupling(&self, i: Vec3x4, j: Vec3x4) -> F32x4 {
        let free = (self.a + self.b) * i.dot(j);
        if self.locked {
            free - self.a * i.dot(j.masked(self.lock_a)) - self.b * i.dot(j.masked(self.lock_b))
        } else {
            free
        }
    }

    /// `d · (M_A⁻¹ + M_B⁻¹) d` for a unit direction `d`: `m_A⁻¹ + m_B⁻¹` less the locked part.
    #[inline(always)]
    pub(super) fn along(&self, direction: Vec3x4) -> F32x4 {
        let free = self.a + self.b;
        if self.locked {
            free - self.a * direction.dot(direction.masked(self.lock_a))
                - self.b * direction.dot(direction.masked(self.lock_b))
        } else {
            free
        }
    }

    /// The velocity changes `(M_A⁻¹ P, M_B⁻¹ P)` a linear impulse `P` gives (A's to subtract);
    /// `LOCKED` is [`Self::locked`], a constant so that the passes of lane sets without locks
    /// carry no test of it.
    #[inline(always)]
    pub(super) fn responses<const LOCKED: bool>(&self, impulse: Vec3x4) -> (Vec3x4, Vec3x4) {
        if LOCKED {
            (
                (impulse - impulse.masked(self.lock_a)).scale(self.a),
                (impulse - impulse.masked(self.lock_b)).scale(self.b),
            )
        } else {
            (impulse.scale(self.a), impulse.scale(self.b))
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
    #[inline(always)]
    pub(super) fn new(
        (a, b): (&BodyFrame, &BodyFrame),
        masses: &LinearMasses,
        (anchor_a, anchor_b): (Vec3x4, Vec3x4),
        direction: Vec3x4,
    ) -> Self {
        let arm_a = anchor_a.cross(direction);
        let arm_b = anchor_b.cross(direction);
        let spin_a = a.inverse_inertia.mul_vec3(arm_a);
        let spin_b = b.inverse_inertia.mul_vec3(arm_b);
        let k = masses.along(direction) + arm_a.dot(spin_a) + arm_b.dot(spin_b);
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

    /// `ΔV = M⁻¹ Jᵀ λ`: `Δv = ±λ M⁻¹ d`, `Δω = ±λ I⁻¹ (r × d)` per lane (A gets the minus sign).
    pub(super) fn apply(
        &self,
        (a, b): (&mut BodyLanes, &mut BodyLanes),
        masses: &LinearMasses,
        direction: Vec3x4,
        impulse: F32x4,
    ) {
        if masses.locked {
            let (response_a, response_b) = masses.responses::<true>(direction.scale(impulse));
            a.linear_velocity -= response_a;
            b.linear_velocity += response_b;
        } else {
            a.linear_velocity -= direction.scale(masses.a * impulse);
            b.linear_velocity += direction.scale(masses.b * impulse);
        }
        self.apply_spin(&mut a.angular_velocity, &mut b.angular_velocity, impulse);
    }
}
