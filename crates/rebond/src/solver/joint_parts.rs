//! Joint constraint parts, one joint at a time (joints are few beside contacts, so their parts
//! are scalar), after Jolt's `Constraints/ConstraintPart/`. `parts.rs` gives the notation: a
//! constraint `C = 0` (or `≥ 0`) is solved on `Ċ = J V`, `V = (v_A, ω_A, v_B, ω_B)`, with the
//! effective mass `K⁻¹`, `K = J M⁻¹ Jᵀ`; an impulse `λ` changes the velocities by `M⁻¹ Jᵀ λ`.
//! Every impulse here is the one on body B; body A gets the opposite.
//!
//! Each part is solved softly in the biased passes and rigidly in the relax pass
//! ([`RowSoftness`]): `λ = −s_m K⁻¹ (Ċ + b) − s_i λ_acc`, with `b = bias_rate · C`, the soft
//! constraint's mass scale `s_m` and impulse scale `s_i` (`softness.rs`).

use super::softness::Softness;
use crate::math::{Mat3, Vec3};

/// The two bodies of a joint as its parts see them: inverse masses along the world axes
/// (kg⁻¹; `1/m` but zero along locked axes, `body/locked_axes.rs`) and world inverse inertias at
/// the start of the step.
#[derive(Debug, Clone, Copy)]
pub(super) struct JointBodies {
    pub inverse_mass: [Vec3; 2],
    pub inverse_inertia: [Mat3; 2],
}

impl JointBodies {
    /// `i · (M_A⁻¹ + M_B⁻¹) j`, the linear part of two rows' coupling: `(m_A⁻¹ + m_B⁻¹) i·j`
    /// when the sum is the same along every axis (no locked translation), rounded as that.
    pub fn linear_coupling(&self, i: Vec3, j: Vec3) -> f32 {
        let sum = self.inverse_mass[0] + self.inverse_mass[1];
        if sum.x == sum.y && sum.y == sum.z {
            sum.x * i.dot(j)
        } else {
            i.dot(sum * j)
        }
    }
}

/// The two bodies' velocities while a joint is solved (`[A, B]`), m/s and rad/s.
#[derive(Debug, Clone, Copy)]
pub(super) struct Velocities {
    pub linear: [Vec3; 2],
    pub angular: [Vec3; 2],
}

/// Fastest a joint corrects its position error, m/s or rad/s: a joint whose anchors were set
/// kilometres apart would otherwise ask, through levers as long, for velocities that overflow
/// within a pass (found by fuzzing the scene loader). Ordinary errors, centimetres at tens of
/// hertz, ask for metres a second.
const MAX_CORRECTION_SPEED: f32 = 100.0;

/// How hard one solve of a part pushes towards `C = 0`: the soft spring's coefficients, or
/// rigid and without position correction (the relax pass).
#[derive(Debug, Clone, Copy)]
pub(super) struct RowSoftness {
    pub bias_rate: f32,
    pub mass_scale: f32,
    pub impulse_scale: f32,
}

impl RowSoftness {
    /// Rigid, no position correction.
    pub const RIGID: Self = Self {
        bias_rate: 0.0,
        mass_scale: 1.0,
        impulse_scale: 0.0,
    };

    /// Rigid, with the soft spring's position correction in biased passes: for rows solved
    /// exactly together, where the spring's softness would only let the joints sag.
    pub fn rigid_of_pass(softness: &Softness, use_bias: bool) -> Self {
        Self {
            bias_rate: if use_bias { softness.bias_rate } else { 0.0 },
            ..Self::RIGID
        }
    }

    /// The velocity with which a row corrects the position error `error`: `b C`, at most
    /// [`MAX_CORRECTION_SPEED`] either way.
    pub fn bias(&self, error: f32) -> f32 {
        (self.bias_rate * error).clamp(-MAX_CORRECTION_SPEED, MAX_CORRECTION_SPEED)
    }

    /// The soft spring in biased passes, rigid otherwise.
    pub fn of_pass(softness: &Softness, use_bias: bool) -> Self {
        if use_bias {
            Self {
                bias_rate: softness.bias_rate,
                mass_scale: softness.mass_scale,
                impulse_scale: softness.impulse_scale,
            }
        } else {
            Self::RIGID
        }
    }
}

/// One row of a joint's Jacobian, `Ċ = l_A·v_A + a_A·ω_A + l_B·v_B + a_B·ω_B` (signs included),
/// as the direct solve of `joint_groups.rs` takes it.
#[derive(Debug, Clone, Copy)]
pub(super) struct RowJacobian {
    pub linear: [Vec3; 2],
    pub angular: [Vec3; 2],
}

/// The world axes, the directions of the point and rotation parts' rows.
const WORLD_AXES: [Vec3; 3] = [Vec3::X, Vec3::Y, Vec3::Z];

/// `K⁻¹` of a symmetric 3×3 `K`, or zero where `K` is singular (nothing can move).
fn inverse_or_zero(k: Mat3) -> Mat3 {
    let determinant = k.determinant();
    if determinant.is_finite() && determinant.abs() > f32::MIN_POSITIVE {
        k.inverse()
    } else {
        Mat3::ZERO
    }
}

/// The point part: three rows holding the anchor `p_B` on the anchor `p_A`, `C = p_B − p_A`,
/// solved with the rest of its group (`joint_groups.rs`).
///
/// - Jacobian: `Ċ = v_B + ω_B × r_B − v_A − ω_A × r_A` (`r` from each centre of mass to its
///   anchor).
/// - Impulse `λ` (a vector, N·s, at the anchor): `Δv_B = λ / m_B`, `Δω_B = I_B⁻¹ (r_B × λ)`, and
///   the opposite on A.
#[derive(Debug, Clone, Copy)]
pub(super) struct PointPart {
    arm_a: Vec3,
    arm_b: Vec3,
}

impl PointPart {
    pub fn new(arm_a: Vec3, arm_b: Vec3) -> Self {
        Self { arm_a, arm_b }
    }

    /// Its three rows, along the world axes (`ω × r · e = ω · (r × e)`).
    pub fn rows(&self) -> [RowJacobian; 3] {
        WORLD_AXES.map(|axis| RowJacobian {
            linear: [-axis, axis],
            angular: [-self.arm_a.cross(axis), self.arm_b.cross(axis)],
        })
    }

    pub fn apply(&self, bodies: &JointBodies, v: &mut Velocities, impulse: Vec3) {
        v.linear[0] -= bodies.inverse_mass[0] * impulse;
        v.angular[0] -= bodies.inverse_inertia[0] * self.arm_a.cross(impulse);
        v.linear[1] += bodies.inverse_mass[1] * impulse;
        v.angular[1] += bodies.inverse_inertia[1] * self.arm_b.cross(impulse);
    }
}

/// The rotation part: three rows on the relative rotation, `Ċ = ω_B − ω_A`. Locking it (`C` =
/// the rotation vector of B's rotation relative to A since the joint was made, world axes), its
/// rows are solved with the rest of their group (`joint_groups.rs`); as a ball joint's friction,
/// on their own with the effective mass.
///
/// - Effective mass: `K = I_A⁻¹ + I_B⁻¹`, kept inverted.
/// - Impulse `λ` (a couple, N·m·s): `Δω_B = I_B⁻¹ λ`, `Δω_A = −I_A⁻¹ λ`.
#[derive(Debug, Clone, Copy)]
pub(super) struct RotationPart {
    mass: Mat3,
}

impl RotationPart {
    pub fn new(bodies: &JointBodies) -> Self {
        let [inertia_a, inertia_b] = bodies.inverse_inertia;
        Self {
            mass: inverse_or_zero(inertia_a + inertia_b),
        }
    }

    /// Its three rows, about the world axes.
    pub fn rows() -> [RowJacobian; 3] {
        WORLD_AXES.map(|axis| RowJacobian {
            linear: [Vec3::ZERO; 2],
            angular: [-axis, axis],
        })
    }

    pub fn apply(bodies: &JointBodies, v: &mut Velocities, impulse: Vec3) {
        v.angular[0] -= bodies.inverse_inertia[0] * impulse;
        v.angular[1] += bodies.inverse_inertia[1] * impulse;
    }

    /// Joint friction on the relative rotation: drives `ω_B − ω_A` to zero with an accumulated
    /// couple of at most `max_impulse` (N·m·s) in magnitude, Coulomb's law for a couple.
    pub fn solve_friction(
        &self,
        bodies: &JointBodies,
        v: &mut Velocities,
        max_impulse: f32,
        accumulated: &mut Vec3,
    ) {
        let velocity = v.angular[1] - v.angular[0];
        let total = (*accumulated - self.mass * velocity).clamp_length_max(max_impulse);
        let applied = total - *accumulated;
        *accumulated = total;
        Self::apply(bodies, v, applied);
    }
}

/// The axis part: one row, the relative velocity along a direction `d` of two anchors, plus
/// turning: `Ċ = d·(v_B − v_A) + ω_B·a_B − ω_A·a_A`.
///
/// - A linear row (a slide, a distance) has `a_A = r_A × d`, `a_B = r_B × d`; an angular row
///   (an angle about `e`) has `d = 0`, `a_A = a_B = e`.
/// - Effective mass: `K = (m_A⁻¹ + m_B⁻¹) |d|² + a_A·I_A⁻¹ a_A + a_B·I_B⁻¹ a_B`, kept as `K⁻¹`.
/// - Impulse `λ`: `Δv_B = λ d / m_B`, `Δω_B = λ I_B⁻¹ a_B`, the opposite on A.
/// - Geared to a rotor of inertia `a` ([`AxisPart::geared`]): `K⁻¹ + a` is the row's effective
///   mass, and the bodies take the share `s = 1 / (1 + a K)` of an impulse, so `Ċ` changes by
///   `λ / (K⁻¹ + a)`, the rotor's speed with it.
#[derive(Debug, Clone, Copy)]
pub(super) struct AxisPart {
    direction: Vec3,
    arm_a: Vec3,
    arm_b: Vec3,
    spin_a: Vec3,
    spin_b: Vec3,
    /// `K`, kg (or kg·m²), and `K⁻¹`; both zero where nothing can move along the row.
    k: f32,
    mass: f32,
    /// The share `s` of an impulse the bodies take: 1, or less when geared to a rotor.
    share: f32,
}

impl AxisPart {
    pub fn linear(bodies: &JointBodies, arms: (Vec3, Vec3), direction: Vec3) -> Self {
        Self::new(
            bodies,
            direction,
            arms.0.cross(direction),
            arms.1.cross(direction),
        )
    }

    pub fn angular(bodies: &JointBodies, axis: Vec3) -> Self {
        Self::new(bodies, Vec3::ZERO, axis, axis)
    }

    fn new(bodies: &JointBodies, direction: Vec3, arm_a: Vec3, arm_b: Vec3) -> Self {
        let spin_a = bodies.inverse_inertia[0] * arm_a;
        let spin_b = bodies.inverse_inertia[1] * arm_b;
        let k =
            bodies.linear_coupling(direction, direction) + arm_a.dot(spin_a) + arm_b.dot(spin_b);
        let (k, mass) = if k > 0.0 && k.is_finite() {
            (k, 1.0 / k)
        } else {
            (0.0, 0.0)
        };
        Self {
            direction,
            arm_a,
            arm_b,
            spin_a,
            spin_b,
            k,
            mass,
            share: 1.0,
        }
    }

    /// The row geared to a rotor of inertia `armature` (kg·m² or kg) turning with it: effective
    /// mass `K⁻¹ + a`, the bodies' share `1 / (1 + a K)` of each impulse. Unchanged where
    /// nothing moves along the row.
    pub fn geared(&self, armature: f32) -> Self {
        if self.k == 0.0 {
            return *self;
        }
        let share = 1.0 / (1.0 + armature * self.k);
        Self {
            k: self.k * share,
            mass: self.mass + armature,
            share,
            ..*self
        }
    }

    /// The share of an impulse the bodies take ([`AxisPart::geared`]).
    pub fn body_share(&self) -> f32 {
        self.share
    }

    /// Brings the bodies and a rotor of inertia `armature` turning at `rotor_speed` to their
    /// common rate `(K⁻¹ Ċ + a ω) / (K⁻¹ + a)`, momentum kept: applies to the bodies, and
    /// returns, the impulse `K⁻¹ a (ω − Ċ) / (K⁻¹ + a)` the rotor gives them.
    pub fn share_with_rotor(
        &self,
        bodies: &JointBodies,
        v: &mut Velocities,
        armature: f32,
        rotor_speed: f32,
    ) -> f32 {
        let impulse =
            self.mass * armature * (rotor_speed - self.velocity(v)) / (self.mass + armature);
        self.apply(bodies, v, impulse);
        impulse
    }

    pub fn velocity(&self, v: &Velocities) -> f32 {
        self.direction.dot(v.linear[1] - v.linear[0]) + v.angular[1].dot(self.arm_b)
            - v.angular[0].dot(self.arm_a)
    }

    pub fn row(&self) -> RowJacobian {
        RowJacobian {
            linear: [-self.direction, self.direction],
            angular: [-self.arm_a, self.arm_b],
        }
    }

    pub fn apply(&self, bodies: &JointBodies, v: &mut Velocities, impulse: f32) {
        let impulse = self.share * impulse;
        v.linear[0] -= bodies.inverse_mass[0] * impulse * self.direction;
        v.linear[1] += bodies.inverse_mass[1] * impulse * self.direction;
        v.angular[0] -= impulse * self.spin_a;
        v.angular[1] += impulse * self.spin_b;
    }

    /// A one-sided row keeping `gap ≥ 0`, where the gap grows along `sign · J` (`sign` is +1
    /// for a lower limit, −1 for an upper one): the accumulated impulse only pushes
    /// (`λ_acc ≥ 0`, applied along `sign · J`). A limit not yet reached (`gap > 0`)
    /// lets the bodies close the gap within the substep `1/inverse_h` and no faster
    /// (speculative); a violated one is pushed back softly.
    pub fn solve_limit(
        &self,
        bodies: &JointBodies,
        v: &mut Velocities,
        (gap, sign): (f32, f32),
        (softness, inverse_h): (RowSoftness, f32),
        accumulated: &mut f32,
    ) {
        let applied = limit_impulse(
            self.velocity(v),
            self.mass,
            (gap, sign),
            (softness, inverse_h),
            accumulated,
        );
        self.apply(bodies, v, sign * applied);
    }

    /// A velocity motor: drives `Ċ` to `target_velocity` with an accumulated impulse within
    /// `±max_impulse` (the force cap times the substep).
    pub fn solve_velocity_motor(
        &self,
        bodies: &JointBodies,
        v: &mut Velocities,
        target_velocity: f32,
        max_impulse: f32,
        accumulated: &mut f32,
    ) {
        let impulse = -self.mass * (self.velocity(v) - target_velocity);
        let total = (*accumulated + impulse).clamp(-max_impulse, max_impulse);
        let applied = total - *accumulated;
        *accumulated = total;
        self.apply(bodies, v, applied);
    }

    /// A spring and damper on `C` (`F = −k C − c Ċ`) over the substep `h`, its accumulated
    /// impulse kept within `±max_impulse`.
    ///
    /// A spring slow for the substep (`ω h ≤ ½`, `ω² = k K`) pulls with the force of the
    /// substep's starting position, damping taken at the end velocity: the impulse of the
    /// substep is `λ = −h (k C + c Ċ')`, `Ċ' = Ċ + K (λ − λ_acc)`, so
    /// `Δλ = −(h k C + h c Ċ + λ_acc) / (1 + h c K)`. With the position update after it this is
    /// symplectic Euler: an undamped spring keeps its energy and swings at `ω` to `(ω h)²/24`.
    /// A stiffer spring would go unstable that way (`ω h ≥ 2`), so it is integrated implicitly,
    /// which is stable at any stiffness but damps it:
    /// `Δλ = −(Ċ + β C + γ λ_acc) / (K + γ)`, `β = k / (c + h k)`, `γ = 1 / (h (c + h k))`.
    #[allow(clippy::too_many_arguments)]
    pub fn solve_spring(
        &self,
        bodies: &JointBodies,
        v: &mut Velocities,
        error: f32,
        (stiffness, damping, h): (f32, f32, f32),
        max_impulse: f32,
        accumulated: &mut f32,
    ) {
        let applied = spring_impulse(
            (self.k, self.velocity(v)),
            error,
            (stiffness, damping, h),
            max_impulse,
            accumulated,
        );
        self.apply(bodies, v, applied);
    }
}

/// The impulse one solve of a one-sided row applies along `sign · J`
/// ([`AxisPart::solve_limit`]), from the row's velocity `Ċ` and effective mass `K⁻¹`; adds it to
/// `accumulated`. Couplings' limits (`couplings.rs`) take it too.
pub(super) fn limit_impulse(
    velocity: f32,
    mass: f32,
    (gap, sign): (f32, f32),
    (softness, inverse_h): (RowSoftness, f32),
    accumulated: &mut f32,
) -> f32 {
    let (bias, mass_scale, impulse_scale) = if gap > 0.0 {
        (gap * inverse_h, 1.0, 0.0)
    } else {
        (
            softness.bias(gap),
            softness.mass_scale,
            softness.impulse_scale,
        )
    };
    let target = sign * velocity + bias;
    let impulse = -mass_scale * mass * target - impulse_scale * *accumulated;
    let total = (*accumulated + impulse).max(0.0);
    let applied = total - *accumulated;
    *accumulated = total;
    applied
}

/// The impulse one solve of a spring and damper applies along its row
/// ([`AxisPart::solve_spring`]), from the row's `K` and velocity `Ċ`; adds it to `accumulated`.
/// Nothing where `K` is zero (nothing moves along the row). Couplings' springs
/// (`couplings.rs`) take it too.
pub(super) fn spring_impulse(
    (k, velocity): (f32, f32),
    error: f32,
    (stiffness, damping, h): (f32, f32, f32),
    max_impulse: f32,
    accumulated: &mut f32,
) -> f32 {
    if k == 0.0 {
        return 0.0;
    }
    let impulse = if h * h * stiffness * k <= SYMPLECTIC_SPRING_LIMIT {
        -(h * stiffness * error + h * damping * velocity + *accumulated) / (1.0 + h * damping * k)
    } else {
        let softness = damping + h * stiffness;
        let bias_rate = stiffness / softness;
        let gamma = 1.0 / (h * softness);
        -(velocity + bias_rate * error + gamma * *accumulated) / (k + gamma)
    };
    let total = (*accumulated + impulse).clamp(-max_impulse, max_impulse);
    let applied = total - *accumulated;
    *accumulated = total;
    applied
}

/// Largest `(ω h)²` of a spring integrated symplectically ([`AxisPart::solve_spring`]): well
/// inside symplectic Euler's stability bound `ω h < 2`.
const SYMPLECTIC_SPRING_LIMIT: f32 = 0.25;

/// Two axis parts held together (the hinge's axis alignment, the prismatic's perpendicular
/// slide), solved with the rest of their group (`joint_groups.rs`). The accumulated impulse is
/// kept as the world vector `λ₁ d₁ + λ₂ d₂` (its rows' unit directions or axes), so it survives
/// the rows turning from one substep to the next.
#[derive(Debug, Clone, Copy)]
pub(super) struct PlanePart {
    rows: [AxisPart; 2],
    /// The rows' unit directions (linear rows) or axes (angular rows).
    axes: [Vec3; 2],
}

impl PlanePart {
    pub fn new(rows: [AxisPart; 2], axes: [Vec3; 2]) -> Self {
        Self { rows, axes }
    }

    /// Its two rows and their unit directions or axes.
    pub fn rows(&self) -> [(RowJacobian, Vec3); 2] {
        [0, 1].map(|i| (self.rows[i].row(), self.axes[i]))
    }

    pub fn apply(&self, bodies: &JointBodies, v: &mut Velocities, impulse: Vec3) {
        for (row, axis) in self.rows.iter().zip(self.axes) {
            row.apply(bodies, v, impulse.dot(axis));
        }
    }
}
