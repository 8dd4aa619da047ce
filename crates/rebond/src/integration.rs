//! Time integration of body velocities and poses by semi-implicit (symplectic) Euler:
//! velocities first from forces, then positions from the new velocities.

use crate::body::RigidBody;
use crate::math::{skew, Quat, Vec3};

/// Advances a dynamic body's velocities by one substep `h` (seconds):
/// `v ← (v + h·(g + F/m)) / (1 + h·c_lin)` and `ω ← (ω + h·I⁻¹τ)` followed by the implicit
/// gyroscopic step and `ω ← ω / (1 + h·c_ang)`. Static and kinematic bodies are left alone.
pub(crate) fn integrate_velocities(body: &mut RigidBody, gravity: Vec3, h: f32) {
    if !body.is_dynamic() {
        return;
    }
    let force = body.force + body.constant_force;
    let torque = body.torque + body.constant_torque;
    let linear = body.linear_velocity + h * (gravity + body.inverse_mass * force);
    let angular = body.angular_velocity + h * (body.world_inverse_inertia * torque);
    let angular = implicit_gyroscopic_step(body, angular, h);
    body.linear_velocity = linear / (1.0 + h * body.linear_damping);
    body.angular_velocity = angular / (1.0 + h * body.angular_damping);
}

/// Solves the torque-free Euler equation `I (ω' − ω) + h ω' × I ω' = 0` in body axes with one
/// Newton step from `ω`, as Catto describes for Box2D/Box3D: with `f = h ω × I ω` and Jacobian
/// `J = I + h ([ω]ₓ I − [I ω]ₓ)`, `ω' = ω − J⁻¹ f`. The implicit form keeps a free spinner from
/// gaining energy, which the explicit term `−h I⁻¹ (ω × I ω)` does.
fn implicit_gyroscopic_step(body: &RigidBody, world_angular_velocity: Vec3, h: f32) -> Vec3 {
    let inertia = body.local_inertia;
    let omega = body.rotation.inverse() * world_angular_velocity;
    let momentum = inertia * omega;
    let residual = h * omega.cross(momentum);
    let jacobian = inertia + h * (skew(omega) * inertia - skew(momentum));
    let determinant = jacobian.determinant();
    if !determinant.is_finite() || determinant.abs() <= f32::MIN_POSITIVE {
        return world_angular_velocity;
    }
    body.rotation * (omega - jacobian.inverse() * residual)
}

/// Advances the pose of a dynamic or kinematic body by one substep: `c ← c + h v`,
/// `q ← normalise(q + ½ h (ω, 0) q)`, then refreshes the world inverse inertia.
pub(crate) fn integrate_pose(body: &mut RigidBody, h: f32) {
    if body.body_type == crate::body::BodyType::Static {
        return;
    }
    body.center_of_mass += h * body.linear_velocity;
    let spin = Quat::from_xyzw(
        body.angular_velocity.x,
        body.angular_velocity.y,
        body.angular_velocity.z,
        0.0,
    ) * body.rotation;
    body.rotation = (body.rotation + spin * (0.5 * h)).normalize();
    body.update_world_inverse_inertia();
}
