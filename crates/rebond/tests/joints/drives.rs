//! Springs, motors, slides and limits against their closed forms.

use super::{add, angle_about_z, mean_period, rod, upward_crossings, world, DT, G};
use rebond::{BodyDesc, JointDesc, Motor, Quat, Shape, Vec3};
use std::f32::consts::PI;

/// The spring tests' ball, kg, spring, N/m, and how far it starts pulled out, m.
const SPRING_MASS: f32 = 1.0;
const SPRING_STIFFNESS: f32 = 40.0;
const SPRING_PULL: f32 = 0.2;

/// A ball of [`SPRING_MASS`] held to the origin by a distance joint of rest length 1 m, a spring
/// of [`SPRING_STIFFNESS`] and `damping` N·s/m, released at rest [`SPRING_PULL`] past it along
/// X, no gravity.
fn ball_on_a_spring(damping: f32) -> (rebond::World, rebond::BodyHandle) {
    let start = Vec3::new(1.0 + SPRING_PULL, 0.0, 0.0);
    let mut world = world(Vec3::ZERO);
    let ball = add(
        &mut world,
        BodyDesc::dynamic(Shape::sphere(0.1).unwrap())
            .mass(SPRING_MASS)
            .position(start),
    );
    world
        .add_joint(
            JointDesc::distance(None, ball, Vec3::ZERO, start)
                .length(1.0)
                .spring(SPRING_STIFFNESS, damping),
        )
        .unwrap();
    (world, ball)
}

#[test]
fn a_spring_joint_oscillates_at_its_natural_frequency_and_keeps_its_amplitude() {
    // A 1 kg ball on a 40 N/m undamped spring of rest length 1 m, pulled out 0.2 m, no gravity:
    // x(t) = 1 + 0.2 cos(ω t), ω = √(k/m). The substep is 1/480 s, so ω h = 0.013 and the
    // symplectic step's period error (ω h)²/24 is 7e-6; 1 % leaves room for sampling.
    let (mass, stiffness) = (SPRING_MASS, SPRING_STIFFNESS);
    let (mut world, ball) = ball_on_a_spring(0.0);
    let amplitude = SPRING_PULL;
    let expected = 2.0 * PI * (mass / stiffness).sqrt();
    let steps = (5.5 * expected / DT) as usize;
    let stretch: Vec<f32> = (0..steps)
        .map(|_| {
            world.step(DT).unwrap();
            world.body(ball).unwrap().position().x - 1.0
        })
        .collect();
    let period = mean_period(&upward_crossings(&stretch));
    assert!(
        (period / expected - 1.0).abs() < 0.01,
        "period {period} s, 2π√(m/k) = {expected} s"
    );
    // Symplectic Euler keeps an ellipse whose peak lies `(ω h)²/8` (2e-5) above the amplitude;
    // the steps (1/60 s) sample the last peak up to `1 − cos(ω Δt / 2)` (0.14 %) below it.
    // Measured 1.3e-5; 0.5 % is the bound (the relax pass's spring used to take 17 % off).
    let last_period = &stretch[stretch.len() - (expected / DT) as usize..];
    let peak = last_period
        .iter()
        .fold(0.0_f32, |peak, x| peak.max(x.abs()));
    assert!(
        (peak / amplitude - 1.0).abs() < 0.005,
        "amplitude {peak} m after five periods, {amplitude} m at the start"
    );
}

#[test]
fn a_damped_spring_joint_follows_the_closed_form() {
    // The same 1 kg ball on a 40 N/m spring, with 0.4 N·s/m of damping: ζ = c / (2 √(k m)) =
    // 0.032, and from rest at 0.2 m, `x − 1 = A e^(−ζωt) (cos ω_d t + ζ/√(1 − ζ²) sin ω_d t)`,
    // `ω_d = ω √(1 − ζ²)`. Symplectic Euler keeps velocities between substeps, its first one
    // (at rest) half a substep before the start: its positions follow the closed form half a
    // substep ahead, `x(t + h/2)` (against `x(t)` they are off by `A ω h / 2` = 1.3 mm). Against
    // that, the damping taken at each substep's end velocity and the second-order terms leave
    // 0.47 mm over five periods; 1 mm of the 20 cm swing is the bound.
    let (mass, stiffness, damping) = (SPRING_MASS, SPRING_STIFFNESS, 0.4_f32);
    let (mut world, ball) = ball_on_a_spring(damping);
    let amplitude = SPRING_PULL;
    let omega = (stiffness / mass).sqrt();
    let zeta = damping / (2.0 * (stiffness * mass).sqrt());
    let omega_d = omega * (1.0 - zeta * zeta).sqrt();
    let steps = (5.0 * 2.0 * PI / omega / DT) as usize;
    let h = DT / world.settings().substeps as f32;
    let mut worst = 0.0_f32;
    for step in 1..=steps {
        world.step(DT).unwrap();
        let t = step as f32 * DT + 0.5 * h;
        let expected = amplitude
            * (-zeta * omega * t).exp()
            * ((omega_d * t).cos() + zeta / (1.0 - zeta * zeta).sqrt() * (omega_d * t).sin());
        let stretch = world.body(ball).unwrap().position().x - 1.0;
        worst = worst.max((stretch - expected).abs());
    }
    assert!(worst < 1.0e-3, "{worst} m from the closed form");
}

/// A 6 kg unit cube on a hinge about Z through its centre, no gravity: `I_zz = m (1 + 1)/12 =
/// 1 kg·m²`, and the hinge's point and axis rows carry no load.
fn motor_on_a_cube(motor: Motor) -> (rebond::World, rebond::BodyHandle) {
    let mut world = world(Vec3::ZERO);
    let cube = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.5)).unwrap()).mass(6.0),
    );
    world
        .add_joint(JointDesc::revolute(None, cube, Vec3::ZERO, Vec3::Z).motor(motor))
        .unwrap();
    (world, cube)
}

#[test]
fn a_velocity_motor_reaches_its_target_speed() {
    let (mut world, cube) = motor_on_a_cube(Motor::velocity(5.0, 1000.0));
    for _ in 0..30 {
        world.step(DT).unwrap();
    }
    let spin = world.body(cube).unwrap().angular_velocity();
    assert!((spin.z - 5.0).abs() < 1e-3, "spin {spin:?} rad/s");
    assert!(
        spin.truncate().length() < 1e-4,
        "spin off the axis {spin:?}"
    );
}

#[test]
fn a_velocity_motor_at_its_force_cap_accelerates_at_cap_over_inertia() {
    // Target far out of reach, cap 0.1 N·m on I = 1 kg·m²: α = 0.1 rad/s², so ω(1 s) = 0.1.
    // The motor's impulse per substep is clamped at h · cap exactly, so only rounding remains.
    let (mut world, cube) = motor_on_a_cube(Motor::velocity(100.0, 0.1));
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let spin = world.body(cube).unwrap().angular_velocity().z;
    assert!((spin - 0.1).abs() < 1e-5, "spin {spin} rad/s after 1 s");
}

#[test]
fn a_position_motor_turns_the_hinge_to_its_target() {
    let (mut world, cube) = motor_on_a_cube(Motor::position(0.8, 50.0, 15.0, f32::INFINITY));
    for _ in 0..300 {
        world.step(DT).unwrap();
    }
    let angle = angle_about_z(world.body(cube).unwrap().rotation());
    assert!((angle - 0.8).abs() < 1e-3, "angle {angle} rad");
}

#[test]
fn a_prismatic_joint_on_a_tilted_axis_slides_at_g_sin_theta_and_stays_on_its_axis() {
    // The axis falls 30° below the horizontal. Along it the body accelerates at g sin 30°;
    // semi-implicit Euler over n substeps of h gives exactly s = a h² n (n + 1) / 2.
    let theta = PI / 6.0;
    let axis = Vec3::new(theta.cos(), -theta.sin(), 0.0);
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let slider = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::new(0.3, 0.1, 0.2)).unwrap()),
    );
    world
        .add_joint(JointDesc::prismatic(None, slider, Vec3::ZERO, axis))
        .unwrap();
    let substeps = world.settings().substeps as f32;
    let h = DT / substeps;
    let mut worst_off_axis = 0.0_f32;
    let mut worst_turn = 0.0_f32;
    for _ in 0..60 {
        world.step(DT).unwrap();
        let body = world.body(slider).unwrap();
        let position = body.position();
        worst_off_axis = worst_off_axis.max((position - position.dot(axis) * axis).length());
        worst_turn = worst_turn.max(body.rotation().angle_between(Quat::IDENTITY));
    }
    let n = 60.0 * substeps;
    let expected = G * theta.sin() * h * h * n * (n + 1.0) / 2.0;
    let slide = world.body(slider).unwrap().position().dot(axis);
    assert!(
        (slide / expected - 1.0).abs() < 0.005,
        "slid {slide} m in 1 s, g sinθ gives {expected} m"
    );
    assert!(worst_off_axis < 1e-3, "{worst_off_axis} m off the axis");
    assert!(worst_turn < 1e-3, "turned {worst_turn} rad");
}

#[test]
fn a_revolute_limit_stops_the_swing() {
    // A rod released horizontal swings down and would pass -π/2; the limit holds it at -1 rad
    // (angles from the release pose), within 2°.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let turn = Quat::from_rotation_z(PI / 2.0);
    let rod = add(
        &mut world,
        rod(1.0, 2.0)
            .position(turn * Vec3::new(0.0, -0.5, 0.0))
            .rotation(turn),
    );
    world
        .add_joint(JointDesc::revolute(None, rod, Vec3::ZERO, Vec3::Z).limits(-1.0, 0.5))
        .unwrap();
    let mut lowest = 0.0_f32;
    for _ in 0..240 {
        world.step(DT).unwrap();
        let angle = angle_about_z(world.body(rod).unwrap().rotation()) - PI / 2.0;
        lowest = lowest.min(angle);
    }
    assert!(lowest > -1.0 - 2.0_f32.to_radians(), "reached {lowest} rad");
    assert!(
        lowest < -1.0 + 2.0_f32.to_radians(),
        "stopped at {lowest} rad"
    );
}

#[test]
fn a_prismatic_limit_stops_the_slide() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let slider = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.2)).unwrap()),
    );
    world
        .add_joint(JointDesc::prismatic(None, slider, Vec3::ZERO, Vec3::Y).limits(-0.5, 0.5))
        .unwrap();
    let mut lowest = 0.0_f32;
    for _ in 0..180 {
        world.step(DT).unwrap();
        lowest = lowest.min(world.body(slider).unwrap().position().y);
    }
    assert!(lowest > -0.51, "slid to {lowest} m, limit -0.5 m");
    let end = world.body(slider).unwrap().position().y;
    assert!((end + 0.5).abs() < 0.01, "rests at {end} m");
}

#[test]
fn a_rope_never_gets_longer_than_its_length() {
    // A ball 0.5 m from the rope's fixed end falls, is caught at 1 m and swings: the distance
    // never exceeds the rope by more than 1 cm, and the rope goes slack when the ball is closer.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let start = Vec3::new(0.5, 0.0, 0.0);
    let ball = add(
        &mut world,
        BodyDesc::dynamic(Shape::sphere(0.1).unwrap()).position(start),
    );
    world
        .add_joint(JointDesc::distance(None, ball, Vec3::ZERO, start).limits(0.0, 1.0))
        .unwrap();
    let mut longest = 0.0_f32;
    for _ in 0..300 {
        world.step(DT).unwrap();
        longest = longest.max(world.body(ball).unwrap().position().length());
    }
    assert!(longest < 1.01, "rope stretched to {longest} m");
    assert!(longest > 0.99, "rope never tightened: {longest} m");
}
