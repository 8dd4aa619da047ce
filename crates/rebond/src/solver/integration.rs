//! Time integration of body velocities and poses by semi-implicit (symplectic) Euler:
//! velocities first from forces, then positions from the new velocities.

use super::{BodyMotion, BodyState};
use crate::math::{skew, Quat, Vec3, Vec3A};

/// Largest rotation of a body in one substep, radians: a quarter turn.
pub(crate) const MAX_ROTATION_PER_SUBSTEP: f32 = 0.25 * std::f32::consts::PI;

/// Speed limits that keep every pose finite whatever a user throws at the world.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SpeedLimits {
    /// m/s.
    pub linear: f32,
    /// rad/s.
    pub angular: f32,
}

impl SpeedLimits {
    /// Holds a body's velocities to the limits; a non-finite velocity becomes zero.
    #[inline(always)]
    pub(crate) fn hold(&self, state: &mut BodyState) {
        state.linear_velocity = clamp_length(state.linear_velocity, self.linear);
        state.angular_velocity = clamp_length(state.angular_velocity, self.angular);
    }
}

/// Advances a dynamic body's velocities by one substep `h` (seconds):
/// `v ← (v + h·(𝟙 − L)(g + F/m)) / (1 + h·c_lin)`, `L` the locked translation axes, and
/// `ω ← (ω + h·I⁻¹τ)` followed by the implicit gyroscopic step (skipped for isotropic inertia,
/// where `ω × Iω = 0`, and for a body with a locked rotation axis) and
/// `ω ← ω / (1 + h·c_ang)`, each then held to its speed limit. Static and kinematic bodies are
/// left alone.
pub(crate) fn integrate_velocities(
    state: &mut BodyState,
    motion: &BodyMotion,
    gravity: Vec3,
    h: f32,
    limits: SpeedLimits,
) {
    if !motion.is_dynamic {
        return;
    }
    let acceleration = Vec3A::from(gravity) + motion.inverse_mass * Vec3A::from(motion.force);
    // Along a locked axis (`body/locked_axes.rs`) the body feels no acceleration: 0 · a there.
    let acceleration = acceleration - acceleration * motion.translation_lock;
    let linear = state.linear_velocity + h * acceleration;
    let torque = Vec3A::from(motion.torque);
    let angular = state.angular_velocity + h * motion.world_inverse_inertia.mul_vec3a(torque);
    let angular = if motion.skips_gyroscopic_step {
        angular
    } else {
        implicit_gyroscopic_step(motion, angular.into(), h).into()
    };
    state.linear_velocity = clamp_length(linear / (1.0 + h * motion.linear_damping), limits.linear);
    state.angular_velocity =
        clamp_length(angular / (1.0 + h * motion.angular_damping), limits.angular);
}

/// `v` held to length `max`. A finite vector longer than about 1.8e19 has a squared length that
/// overflows `f32`, where `clamp_length_max` would return zero: it is scaled down first, so a
/// body thrown at 1e30 m/s flies at the speed limit instead of stopping dead. A vector with an
/// infinite or NaN component has no direction and becomes zero.
#[inline(always)]
fn clamp_length(v: Vec3A, max: f32) -> Vec3A {
    // NaN fails the comparison too, and takes the slow path.
    if v.length_squared() <= max * max {
        v
    } else {
        clamp_long(v, max)
    }
}

/// [`clamp_length`] of a vector longer than `max`, or not finite.
#[cold]
#[inline(never)]
fn clamp_long(v: Vec3A, max: f32) -> Vec3A {
    if v.length_squared().is_finite() {
        v.clamp_length_max(max)
    } else {
        (v / v.abs().max_element()).normalize_or_zero() * max
    }
}

/// Below this relative size the gyroscopic change `h ω × I ω` is lost in f32 rounding of `I ω`
/// (spheres, cubes, slow spins) and the Newton step is skipped.
const GYROSCOPIC_NEGLIGIBLE: f32 = 1.0e-7;

/// Implicit gyroscopic step for the torque-free Euler equation, in body axes.
///
/// The pose update turns the body by the Cayley rotation `cay(h ω')` of the end velocity `ω'`
/// ([`integrate_pose`]). The world angular momentum `R I ω` is then conserved exactly when the
/// body-frame momentum turns back by the same rotation: `I ω' = cay(−h ω') I ω`, i.e.
/// `f(ω') = I (ω' − ω) + ½ h ω' × (I ω + I ω') = 0`. One Newton step from `ω'= ω` solves it to
/// second order, as Box3D does for its (backward-Euler) form: `f = h ω × I ω`,
/// `J = I + ½ h [ω]ₓ I − h [I ω]ₓ`, `ω' = ω − J⁻¹ f`. Unlike the explicit term
/// `−h I⁻¹ (ω × I ω)` it never adds energy, and unlike backward Euler it does not bleed momentum.
fn implicit_gyroscopic_step(motion: &BodyMotion, world_angular_velocity: Vec3, h: f32) -> Vec3 {
    let inertia = motion.local_inertia;
    let omega = motion.rotation.inverse() * world_angular_velocity;
    let momentum = inertia * omega;
    let residual = h * omega.cross(momentum);
    if residual.length_squared()
        <= GYROSCOPIC_NEGLIGIBLE * GYROSCOPIC_NEGLIGIBLE * momentum.length_squared()
    {
        return world_angular_velocity;
    }
    let jacobian = inertia + 0.5 * h * (skew(omega) * inertia) - h * skew(momentum);
    let determinant = jacobian.determinant();
    if !determinant.is_finite() || determinant.abs() <= f32::MIN_POSITIVE {
        return world_angular_velocity;
    }
    motion.rotation * (omega - jacobian.inverse() * residual)
}

/// Advances the pose of a dynamic or kinematic body by one substep: `c ← c + h v`,
/// `q ← normalise(q + ½ h (ω, 0) q)` (the Cayley rotation by `h ω`), and accumulates the motion
/// since the step began (`Δc += h v`, `Δθ += h ω`) for the contact solver. The world inverse
/// inertia is refreshed once, at the end of the step.
pub(crate) fn integrate_pose(state: &mut BodyState, motion: &mut BodyMotion, h: f32) {
    let step = h * state.linear_velocity;
    motion.center_of_mass += Vec3::from(step);
    state.delta_position += step;
    state.delta_rotation += h * state.angular_velocity;
    let spin = Quat::from_xyzw(
        state.angular_velocity.x,
        state.angular_velocity.y,
        state.angular_velocity.z,
        0.0,
    ) * motion.rotation;
    motion.rotation = (motion.rotation + spin * (0.5 * h)).normalize();
}
