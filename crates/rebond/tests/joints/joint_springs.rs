//! Joint springs and damping on revolute and prismatic coordinates (MuJoCo's joint stiffness,
//! `springref` and damping) against their closed forms.

use super::{add, mean_period, upward_crossings, world, DT};
use rebond::{BodyDesc, BodyHandle, JointDesc, JointHandle, Shape, Vec3, World};
use std::f32::consts::PI;

/// The bar's half extents, m, and mass, kg: a bar 1 m long turning about Z through its centre.
const HALF_EXTENTS: Vec3 = Vec3::new(0.5, 0.1, 0.1);
const MASS: f32 = 1.0;

/// The bar's moment of inertia about Z through its centre, `m (w² + h²) / 12`, kg·m².
fn bar_inertia() -> f32 {
    let (w, h) = (2.0 * HALF_EXTENTS.x, 2.0 * HALF_EXTENTS.y);
    MASS * (w * w + h * h) / 12.0
}

/// A bar hinged to the world at its centre about Z with `spring`, spinning at `spin` rad/s,
/// gravity off.
fn hinged_bar(spring: (f32, f32, f32), spin: f32) -> (World, BodyHandle, JointHandle) {
    let mut world = world(Vec3::ZERO);
    let bar = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(HALF_EXTENTS).unwrap())
            .mass(MASS)
            .angular_velocity(Vec3::Z * spin),
    );
    let (stiffness, damping, reference) = spring;
    let joint = world
        .add_joint(
            JointDesc::revolute(None, bar, Vec3::ZERO, Vec3::Z)
                .spring_to(stiffness, damping, reference),
        )
        .unwrap();
    (world, bar, joint)
}

/// The joint's position after each of `steps` steps.
fn positions(world: &mut World, joint: JointHandle, steps: usize) -> Vec<f32> {
    (0..steps)
        .map(|_| {
            world.step(DT).unwrap();
            world.joint_position(joint).unwrap()
        })
        .collect()
}

#[test]
fn a_hinge_spring_swings_at_its_natural_period() {
    // k = 2 N·m/rad on I = 0.0867 kg·m²: T = 2π √(I/k) = 1.308 s. Symplectic Euler at the
    // substep h = 1/480 s (ω h = 0.01) errs on the period by (ω h)²/24, 4e-6; the crossings are
    // interpolated between steps of 1/60 s. Measured 4e-6; 0.5 % is the bound.
    let stiffness = 2.0;
    let (mut world, _, joint) = hinged_bar((stiffness, 0.0, 0.0), 0.2);
    let expected = 2.0 * PI * (bar_inertia() / stiffness).sqrt();
    let angles = positions(&mut world, joint, (6.5 * expected / DT) as usize);
    let period = mean_period(&upward_crossings(&angles));
    assert!(
        (period / expected - 1.0).abs() < 0.005,
        "period {period} s, 2π√(I/k) = {expected} s"
    );
}

#[test]
fn a_slide_spring_swings_at_its_natural_period() {
    // A 2 kg box on a prismatic joint along X, k = 50 N/m: T = 2π √(m/k) = 1.257 s; the same
    // bound as the hinge's (measured 5e-6).
    let (mass, stiffness) = (2.0, 50.0);
    let mut world = world(Vec3::ZERO);
    let block = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.1)).unwrap())
            .mass(mass)
            .linear_velocity(Vec3::X * 0.1),
    );
    let joint = world
        .add_joint(JointDesc::prismatic(None, block, Vec3::ZERO, Vec3::X).spring(stiffness, 0.0))
        .unwrap();
    let expected = 2.0 * PI * (mass / stiffness).sqrt();
    let slides = positions(&mut world, joint, (6.5 * expected / DT) as usize);
    let period = mean_period(&upward_crossings(&slides));
    assert!(
        (period / expected - 1.0).abs() < 0.005,
        "period {period} s, 2π√(m/k) = {expected} s"
    );
}

/// The largest `|value|` of `values`.
fn peak(values: &[f32]) -> f32 {
    values
        .iter()
        .fold(0.0_f32, |peak, value| peak.max(value.abs()))
}

#[test]
fn joint_damping_takes_the_amplitude_down_exponentially() {
    // Light damping d = 0.01 N·m·s/rad on the 2 N·m/rad hinge (ζ = 0.012): the amplitude decays
    // as exp(−d t / (2I)). The peaks of the first and the sixth period are five periods apart:
    // their ratio is exp(−5 d T / (2I)) = 0.686. Each peak is sampled by steps of 1/60 s, up to
    // 1 − cos(ω Δt / 2) = 0.08 % below it, and implicit damping per substep differs from the
    // exponential by (h d / I)², 6e-8; 1 % is the bound (measured 0.17 %).
    let (stiffness, damping) = (2.0, 0.01);
    let (mut world, _, joint) = hinged_bar((stiffness, damping, 0.0), 0.2);
    let inertia = bar_inertia();
    let period = 2.0 * PI * (inertia / stiffness).sqrt();
    let per_period = (period / DT).round() as usize;
    let angles = positions(&mut world, joint, 6 * per_period);
    let (first, sixth) = (peak(&angles[..per_period]), peak(&angles[5 * per_period..]));
    let expected = (-5.0 * per_period as f32 * DT * damping / (2.0 * inertia)).exp();
    assert!(
        (sixth / first / expected - 1.0).abs() < 0.01,
        "amplitude ratio {} over five periods, exp(−d t / 2I) = {expected}",
        sixth / first
    );
}

#[test]
fn a_stiff_spring_on_a_light_link_rests_at_its_reference() {
    // A 10 g bar (I = 8.7e-4 kg·m²) on a spring of 100 N·m/rad towards 0.3 rad: ω h = 0.7,
    // past symplectic Euler's reach, so the spring is integrated implicitly. Released spinning
    // at 5 rad/s, gravity off, with damping 0.05 N·m·s/rad, it comes to rest at the reference:
    // over the last second of three, the worst |q − 0.3| and |q̇| are below 1e-4 rad and
    // 1e-3 rad/s (measured 0 to rounding; the spring's force at 1e-4 rad is 0.01 N·m).
    let reference = 0.3;
    let mut world = world(Vec3::ZERO);
    let bar = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(HALF_EXTENTS).unwrap())
            .mass(0.01)
            .angular_velocity(Vec3::Z * 5.0),
    );
    let joint = world
        .add_joint(
            JointDesc::revolute(None, bar, Vec3::ZERO, Vec3::Z).spring_to(100.0, 0.05, reference),
        )
        .unwrap();
    for _ in 0..120 {
        world.step(DT).unwrap();
    }
    let (mut worst_offset, mut worst_rate) = (0.0_f32, 0.0_f32);
    for _ in 0..60 {
        world.step(DT).unwrap();
        let position = world.joint_position(joint).unwrap();
        assert!(position.is_finite());
        worst_offset = worst_offset.max((position - reference).abs());
        worst_rate = worst_rate.max(world.joint_velocity(joint).unwrap().abs());
    }
    assert!(
        worst_offset < 1.0e-4 && worst_rate < 1.0e-3,
        "worst |q − r| {worst_offset} rad, |q̇| {worst_rate} rad/s"
    );
}

#[test]
fn a_spring_and_a_torque_motor_share_the_joint() {
    // A torque motor of 0.4 N·m against a 2 N·m/rad spring (HalfCheetah's joints have both):
    // with damping 0.5 N·m·s/rad the bar settles where the spring balances the torque,
    // q = τ / k = 0.2 rad; the last second of four stays within 1e-4 rad of it (measured
    // 1.6e-5).
    let (stiffness, torque) = (2.0, 0.4);
    let (mut world, _, joint) = hinged_bar((stiffness, 0.5, 0.0), 0.0);
    world
        .set_joint_motor(joint, Some(rebond::Motor::torque(torque)))
        .unwrap();
    let angles = positions(&mut world, joint, 240);
    let expected = torque / stiffness;
    let worst = angles[180..]
        .iter()
        .fold(0.0_f32, |worst, angle| worst.max((angle - expected).abs()));
    assert!(worst < 1.0e-4, "worst |q − τ/k| {worst} rad");
}
