//! Joint friction's stick and slip (MuJoCo's `frictionloss`): a hinge under a load torque
//! below `friction` holds still, one above turns at `(τ − friction) / I`.

use super::{add, world, DT};
use rebond::{BodyDesc, JointDesc, Motor, Shape, Vec3, World};

/// A bar hinged at its centre about Z with `friction` N·m, driven by a torque motor of `torque`
/// N·m, gravity off; its joint's position and rate after each of 60 steps (1 s).
fn driven(friction: f32, torque: f32) -> (Vec<(f32, f32)>, f32) {
    let mut world: World = world(Vec3::ZERO);
    let half = Vec3::new(0.5, 0.1, 0.1);
    let bar = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(half).unwrap()).mass(1.0),
    );
    let joint = world
        .add_joint(
            JointDesc::revolute(None, bar, Vec3::ZERO, Vec3::Z)
                .friction(friction)
                .motor(Motor::torque(torque)),
        )
        .unwrap();
    let samples = (0..60)
        .map(|_| {
            world.step(DT).unwrap();
            (
                world.joint_position(joint).unwrap(),
                world.joint_velocity(joint).unwrap(),
            )
        })
        .collect();
    // I = m (w² + h²) / 12 about Z.
    (samples, (1.0 + 0.04) / 12.0)
}

#[test]
fn a_hinge_sticks_under_a_load_below_its_friction() {
    // 0.3 N·m against 0.5 N·m of friction: the friction row's impulse per substep, within
    // ±friction·h, meets the motor's τ h exactly, so the bar stays put to rounding. Over the
    // whole second the worst |θ| and |θ̇| stay below 1e-6 rad and 1e-5 rad/s (measured 0).
    let (samples, _) = driven(0.5, 0.3);
    let (worst_angle, worst_rate) = samples.iter().fold((0.0_f32, 0.0_f32), |worst, &(q, v)| {
        (worst.0.max(q.abs()), worst.1.max(v.abs()))
    });
    assert!(
        worst_angle < 1.0e-6 && worst_rate < 1.0e-5,
        "worst |θ| {worst_angle} rad, |θ̇| {worst_rate} rad/s"
    );
}

#[test]
fn a_hinge_slips_under_a_load_above_its_friction_at_the_difference() {
    // 0.8 N·m against 0.5 N·m: the friction gives its whole impulse each substep, so the bar
    // turns at (τ − friction) / I = 3.46 rad/s² and after 1 s at 3.46 rad/s; the row is solved
    // to its cap, so only rounding is left (measured 4e-6): 0.1 % is the bound.
    let (torque, friction) = (0.8, 0.5);
    let (samples, inertia) = driven(friction, torque);
    let expected = (torque - friction) / inertia * 60.0 * DT;
    let rate = samples[59].1;
    assert!(
        (rate / expected - 1.0).abs() < 0.001,
        "rate {rate} rad/s after 1 s, (τ − f) t / I = {expected} rad/s"
    );
}
