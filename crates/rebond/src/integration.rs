//! Time integration of body velocities and poses by semi-implicit (symplectic) Euler:
//! velocities first from forces, then positions from the new velocities.

use crate::math::{rotate_tensor, skew, Quat, Vec3};
use crate::solver::SolverBody;

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

/// Advances a dynamic body's velocities by one substep `h` (seconds):
/// `v ← (v + h·(g + F/m)) / (1 + h·c_lin)` and `ω ← (ω + h·I⁻¹τ)` followed by the implicit
/// gyroscopic step and `ω ← ω / (1 + h·c_ang)`, each then held to its speed limit. Static and
/// kinematic bodies are left alone.
pub(crate) fn integrate_velocities(
    body: &mut SolverBody,
    gravity: Vec3,
    h: f32,
    limits: SpeedLimits,
) {
    if !body.is_dynamic {
        return;
    }
    let (force, torque) = (body.force, body.torque);
    let linear = body.linear_velocity + h * (gravity + body.inverse_mass * force);
    let angular = body.angular_velocity + h * (body.world_inverse_inertia * torque);
    let angular = implicit_gyroscopic_step(body, angular, h);
    body.linear_velocity =
        (linear / (1.0 + h * body.linear_damping)).clamp_length_max(limits.linear);
    body.angular_velocity =
        (angular / (1.0 + h * body.angular_damping)).clamp_length_max(limits.angular);
}

/// Implicit gyroscopic step for the torque-free Euler equation, in body axes.
///
/// The pose update turns the body by the Cayley rotation `cay(h ω')` of the end velocity `ω'`
/// ([`integrate_pose`]). The world angular momentum `R I ω` is then conserved exactly when the
/// body-frame momentum turns back by the same rotation: `I ω' = cay(−h ω') I ω`, i.e.
/// `f(ω') = I (ω' − ω) + ½ h ω' × (I ω + I ω') = 0`. One Newton step from `ω'= ω` solves it to
/// second order, as Box3D does for its (backward-Euler) form: `f = h ω × I ω`,
/// `J = I + ½ h [ω]ₓ I − h [I ω]ₓ`, `ω' = ω − J⁻¹ f`. Unlike the explicit term
/// `−h I⁻¹ (ω × I ω)` it never adds energy, and unlike backward Euler it does not bleed momentum.
fn implicit_gyroscopic_step(body: &SolverBody, world_angular_velocity: Vec3, h: f32) -> Vec3 {
    let inertia = body.local_inertia;
    let omega = body.rotation.inverse() * world_angular_velocity;
    let momentum = inertia * omega;
    let residual = h * omega.cross(momentum);
    let jacobian = inertia + 0.5 * h * (skew(omega) * inertia) - h * skew(momentum);
    let determinant = jacobian.determinant();
    if !determinant.is_finite() || determinant.abs() <= f32::MIN_POSITIVE {
        return world_angular_velocity;
    }
    body.rotation * (omega - jacobian.inverse() * residual)
}

/// Advances the pose of a dynamic or kinematic body by one substep: `c ← c + h v`,
/// `q ← normalise(q + ½ h (ω, 0) q)` (the Cayley rotation by `h ω`), then refreshes the world
/// inverse inertia.
pub(crate) fn integrate_pose(body: &mut SolverBody, h: f32) {
    body.center_of_mass += h * body.linear_velocity;
    let spin = Quat::from_xyzw(
        body.angular_velocity.x,
        body.angular_velocity.y,
        body.angular_velocity.z,
        0.0,
    ) * body.rotation;
    body.rotation = (body.rotation + spin * (0.5 * h)).normalize();
    body.world_inverse_inertia = rotate_tensor(body.rotation, body.local_inverse_inertia);
}
