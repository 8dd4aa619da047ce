//! Physical pendulums on a revolute joint: periods against the closed forms, amplitude kept.

use super::{add, angle_about_z, mean_period, rod, upward_crossings, world, DT, G};
use rebond::{JointDesc, Quat, Vec3};
use std::f32::consts::PI;

const LENGTH: f32 = 1.0;
const MASS: f32 = 2.0;

/// `I_pivot / (m g d)` of the rod hung from one end: `I_pivot = m (L² + w²)/12 + m (L/2)²`
/// (`w` = 0.1 m thick), `d = L/2`; the small-angle period is `2π √` of it.
fn pendulum_time_squared() -> f32 {
    let inertia = MASS * (LENGTH * LENGTH + 0.01) / 12.0 + MASS * 0.25 * LENGTH * LENGTH;
    inertia / (MASS * G * 0.5 * LENGTH)
}

/// Complete elliptic integral of the first kind `K(k)` by the arithmetic–geometric mean:
/// `K = π / (2 AGM(1, √(1 − k²)))`.
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0_f64, (1.0 - k * k).sqrt());
    for _ in 0..20 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// Swings the rod hung from the world at the origin by a hinge about Z, released from rest at
/// `amplitude`, for `steps`; returns its angle after each step.
fn swing(amplitude: f32, steps: usize) -> Vec<f32> {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let turn = Quat::from_rotation_z(amplitude);
    let rod = add(
        &mut world,
        rod(LENGTH, MASS)
            .position(turn * Vec3::new(0.0, -0.5 * LENGTH, 0.0))
            .rotation(turn),
    );
    world
        .add_joint(JointDesc::revolute(None, rod, Vec3::ZERO, Vec3::Z))
        .unwrap();
    (0..steps)
        .map(|_| {
            world.step(DT).unwrap();
            angle_about_z(world.body(rod).unwrap().rotation())
        })
        .collect()
}

#[test]
fn a_small_swing_has_the_small_angle_period() {
    // At 0.05 rad the finite-amplitude correction is θ₀²/16 = 0.016 %, far below the 0.5 %
    // asked; the rest is the step's own error (symplectic Euler: (ω h)²/24 for a 1/480 s substep).
    let angles = swing(0.05, 600);
    let expected = 2.0 * PI * pendulum_time_squared().sqrt();
    let period = mean_period(&upward_crossings(&angles));
    assert!(
        (period / expected - 1.0).abs() < 0.005,
        "period {period} s, closed form {expected} s"
    );
}

#[test]
fn a_large_swing_has_the_elliptic_integral_period_and_keeps_its_amplitude() {
    // T = 4 K(sin(θ₀/2)) √(I/(m g d)); at θ₀ = 1.5 rad it is 14.6 % longer than the small-angle
    // period, so a 1 % tolerance tells the two apart.
    let amplitude = 1.5_f32;
    let angles = swing(amplitude, 1200);
    let expected = 4.0
        * elliptic_k(f64::from((0.5 * amplitude).sin())) as f32
        * pendulum_time_squared().sqrt();
    let crossings = upward_crossings(&angles);
    assert!(crossings.len() >= 10, "{} swings", crossings.len());
    let period = mean_period(&crossings);
    assert!(
        (period / expected - 1.0).abs() < 0.01,
        "period {period} s, elliptic closed form {expected} s"
    );
    // Ten full swings without damping: the largest angle of the last swing within 5 % of the
    // release angle (energy is the only thing that sets it).
    let last_swing = (crossings[crossings.len() - 2] / DT) as usize;
    let last_peak = angles[last_swing..]
        .iter()
        .fold(0.0_f32, |peak, angle| peak.max(angle.abs()));
    assert!(
        (last_peak / amplitude - 1.0).abs() < 0.05,
        "amplitude {last_peak} rad after ten swings, released at {amplitude} rad"
    );
}
