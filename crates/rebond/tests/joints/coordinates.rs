//! Joint coordinates (angles counted across turns, slides, lengths, and their rates), torque
//! motors, and position targets on the angle counted across turns, against their closed forms.

use super::{add, world, DT};
use rebond::{BodyDesc, BodyHandle, JointDesc, JointHandle, Motor, Shape, Vec3, World};
use std::f32::consts::{PI, TAU};

/// The wheel's mass, kg, and radius, m: a disc 0.2 m thick.
const WHEEL_MASS: f32 = 2.0;
const WHEEL_RADIUS: f32 = 0.5;

/// The wheel's moment of inertia about its axis, `m r² / 2`, kg·m².
const WHEEL_INERTIA: f32 = 0.5 * WHEEL_MASS * WHEEL_RADIUS * WHEEL_RADIUS;

/// A wheel (a cylinder along Y) at the origin on a hinge about Y through its centre of mass,
/// joined to the world, no gravity, spinning at `spin` rad/s: the hinge's point and axis rows
/// carry no load, so only a motor or limit (set by `hinge`) changes the spin.
fn wheel(
    spin: f32,
    hinge: impl FnOnce(JointDesc) -> JointDesc,
) -> (World, BodyHandle, JointHandle) {
    let mut world = world(Vec3::ZERO);
    let wheel = add(
        &mut world,
        BodyDesc::dynamic(Shape::cylinder(WHEEL_RADIUS, 0.1).unwrap())
            .mass(WHEEL_MASS)
            .angular_velocity(Vec3::Y * spin),
    );
    let joint = world
        .add_joint(hinge(JointDesc::revolute(None, wheel, Vec3::ZERO, Vec3::Y)))
        .unwrap();
    (world, wheel, joint)
}

/// The unit cube of `drives.rs` (6 kg, `I_zz = 1 kg·m²`) on a hinge about Z through its centre,
/// no gravity.
fn cube_on_a_hinge(motor: Motor) -> (World, JointHandle) {
    let mut world = world(Vec3::ZERO);
    let cube = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.5)).unwrap()).mass(6.0),
    );
    let hinge = world
        .add_joint(JointDesc::revolute(None, cube, Vec3::ZERO, Vec3::Z).motor(motor))
        .unwrap();
    (world, hinge)
}

#[test]
fn an_angle_read_after_three_turns_is_six_pi() {
    // The free wheel keeps its spin ω and turns by the Cayley rotation `2 atan(h ω / 2)` each
    // substep of `h`; ω is chosen so that the 180 steps of 3 s make exactly three turns, either
    // way. Each substep rounds the quaternion to about 1e-7 rad, so 1440 substeps may drift by
    // 1.5e-4 rad at worst; 6π itself is resolved to 2e-6. 5e-4 rad holds both.
    for sign in [1.0_f32, -1.0] {
        let steps = 180;
        let substeps = world(Vec3::ZERO).settings().substeps as f64;
        let h = f64::from(DT) / substeps;
        let count = steps as f64 * substeps;
        let spin = sign * ((2.0 / h) * (3.0 * std::f64::consts::TAU / (2.0 * count)).tan()) as f32;
        let (mut world, _, hinge) = wheel(spin, |hinge| hinge);
        let mut previous = 0.0_f32;
        for _ in 0..steps {
            world.step(DT).unwrap();
            let angle = world.joint_position(hinge).unwrap();
            // Each step turns the wheel by ω DT (1.7 % of a turn), through ±π and every turn.
            let turned = angle - previous;
            assert!(
                (turned - spin * DT).abs() < 1e-3,
                "the angle went from {previous} to {angle} rad in one step at {spin} rad/s"
            );
            previous = angle;
        }
        let angle = world.joint_position(hinge).unwrap();
        let expected = sign * 3.0 * TAU;
        assert!(
            (angle - expected).abs() < 5e-4,
            "{angle} rad after three turns, expected {expected}"
        );
        // The free wheel's rate is its spin, untouched by the rows.
        let rate = world.joint_velocity(hinge).unwrap();
        assert!(
            (rate - spin).abs() < 1e-5 * spin.abs(),
            "rate {rate} rad/s, spin {spin}"
        );
    }
}

#[test]
fn the_angle_is_body_b_relative_to_body_a_right_handed_about_the_axis() {
    // Two free wheels on one axle, no gravity, spinning at +3 and −2 rad/s about Y: B's angle
    // relative to A grows at ω_B − ω_A = −5 rad/s, θ(2 s) = −10 rad, past a whole turn.
    // Each wheel turns by the Cayley rotation per substep, `ω h − (ω h)³/12`: 2e-5 rad over the
    // run; the rounding of 960 substeps adds at most 1e-4.
    let mut world = world(Vec3::ZERO);
    let disc = || BodyDesc::dynamic(Shape::cylinder(WHEEL_RADIUS, 0.1).unwrap()).mass(WHEEL_MASS);
    let a = add(&mut world, disc().angular_velocity(Vec3::Y * 3.0));
    let b = add(
        &mut world,
        disc()
            .position(Vec3::Y * 0.5)
            .angular_velocity(Vec3::Y * -2.0),
    );
    let axle = world
        .add_joint(JointDesc::revolute(a, b, Vec3::Y * 0.25, Vec3::Y))
        .unwrap();
    for _ in 0..120 {
        world.step(DT).unwrap();
    }
    let angle = world.joint_position(axle).unwrap();
    assert!(
        (angle + 10.0).abs() < 2e-4,
        "relative angle {angle} rad, expected −10"
    );
    let rate = world.joint_velocity(axle).unwrap();
    assert!(
        (rate + 5.0).abs() < 1e-4,
        "relative rate {rate} rad/s, expected −5"
    );
}

#[test]
fn a_torque_motor_gives_omega_equal_to_torque_times_time_over_inertia() {
    // A torque τ about the free wheel's axis: ω = τ t / I. The motor's impulse τ h goes through
    // the hinge's axis row each substep, `Δω = τ h / I` exactly but for rounding, and the angle
    // follows the semi-implicit Euler sum `θ = τ h² n (n + 1) / (2 I)` over n substeps (2e-7
    // relative from the Cayley rotation at these speeds).
    let torque = 0.75;
    let (mut world, wheel, hinge) = wheel(0.0, |hinge| hinge.motor(Motor::torque(torque)));
    let steps = 60;
    for _ in 0..steps {
        world.step(DT).unwrap();
    }
    let t = steps as f32 * DT;
    let expected = torque * t / WHEEL_INERTIA;
    let spin = world.body(wheel).unwrap().angular_velocity();
    // 480 substeps of rounding at 1e-7 relative each.
    assert!(
        (spin.y / expected - 1.0).abs() < 1e-4,
        "ω {spin:?}, τ t / I = {expected}"
    );
    assert!(
        spin.x.abs() + spin.z.abs() < 1e-5,
        "spin off the axis {spin:?}"
    );
    let rate = world.joint_velocity(hinge).unwrap();
    assert!(
        (rate / expected - 1.0).abs() < 1e-4,
        "joint velocity {rate} rad/s"
    );
    let n = steps as f32 * world.settings().substeps as f32;
    let h = DT / world.settings().substeps as f32;
    let angle_expected = torque * h * h * n * (n + 1.0) / (2.0 * WHEEL_INERTIA);
    let angle = world.joint_position(hinge).unwrap();
    assert!(
        (angle / angle_expected - 1.0).abs() < 1e-4,
        "angle {angle} rad, expected {angle_expected}"
    );
    // The joint reports the torque it applies to the wheel, about the axis.
    let reported = world.joint(hinge).unwrap().torque();
    assert!(
        (reported - Vec3::Y * torque).length() < 1e-5,
        "reported torque {reported:?} N·m"
    );
}

#[test]
fn a_torque_set_every_step_is_applied_in_that_step() {
    // A controller sets a new torque each step, τ_k = 0.2 k N·m for step k: the wheel's spin is
    // the sum, ω = Σ τ_k DT / I, and each step's joint torque is that step's τ. Rounding as in
    // the constant torque test.
    let (mut world, _, hinge) = wheel(0.0, |hinge| hinge.motor(Motor::torque(0.0)));
    let mut sum = 0.0_f32;
    for k in 0..60 {
        let torque = 0.2 * k as f32;
        world
            .set_joint_motor(hinge, Some(Motor::torque(torque)))
            .unwrap();
        world.step(DT).unwrap();
        sum += torque * DT / WHEEL_INERTIA;
        let reported = world.joint(hinge).unwrap().torque().y;
        assert!(
            (reported - torque).abs() < 1e-5 * torque.max(1.0),
            "step {k}: {reported}"
        );
    }
    let rate = world.joint_velocity(hinge).unwrap();
    assert!(
        (rate / sum - 1.0).abs() < 1e-4,
        "ω {rate} rad/s, Σ τ_k DT / I = {sum}"
    );
}

#[test]
fn a_removed_torque_motor_stops_driving() {
    // Spun up by 0.5 N·m for 0.5 s (ω = τ t / I = 1 rad/s), the free wheel keeps its spin once
    // the motor is removed: nothing of the motor's impulse is applied after. Rounding only.
    let (mut world, _, hinge) = wheel(0.0, |hinge| hinge.motor(Motor::torque(0.5)));
    for _ in 0..30 {
        world.step(DT).unwrap();
    }
    world.set_joint_motor(hinge, None).unwrap();
    let spun_up = world.joint_velocity(hinge).unwrap();
    assert!((spun_up - 1.0).abs() < 1e-4, "spin {spun_up} rad/s");
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let spin = world.joint_velocity(hinge).unwrap();
    assert!(
        (spin - spun_up).abs() < 1e-5,
        "spin {spin} rad/s, {spun_up} before"
    );
    assert!(world.joint(hinge).unwrap().torque().length() < 1e-5);
}

#[test]
fn a_prismatic_force_motor_gives_v_equal_to_force_times_time_over_mass() {
    // A 3 kg box on a slide along X through its centre, no gravity, pushed by F = 4.5 N:
    // v = F t / m and s = F h² n (n + 1) / (2 m), semi-implicit Euler, rounding only.
    let (mass, force) = (3.0_f32, 4.5_f32);
    let mut world = world(Vec3::ZERO);
    let slider = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::new(0.3, 0.1, 0.2)).unwrap()).mass(mass),
    );
    let slide = world
        .add_joint(
            JointDesc::prismatic(None, slider, Vec3::ZERO, Vec3::X).motor(Motor::torque(force)),
        )
        .unwrap();
    let steps = 60;
    for _ in 0..steps {
        world.step(DT).unwrap();
    }
    let expected = force * steps as f32 * DT / mass;
    let velocity = world.body(slider).unwrap().linear_velocity();
    assert!(
        (velocity.x / expected - 1.0).abs() < 1e-4,
        "v {velocity:?}, F t / m = {expected}"
    );
    let rate = world.joint_velocity(slide).unwrap();
    assert!(
        (rate / expected - 1.0).abs() < 1e-4,
        "joint velocity {rate} m/s"
    );
    let substeps = world.settings().substeps as f32;
    let (n, h) = (steps as f32 * substeps, DT / substeps);
    let slide_expected = force * h * h * n * (n + 1.0) / (2.0 * mass);
    let slid = world.joint_position(slide).unwrap();
    assert!(
        (slid / slide_expected - 1.0).abs() < 1e-4,
        "slide {slid} m, expected {slide_expected}"
    );
}

#[test]
fn a_position_target_past_half_a_turn_is_reached_and_held_without_overshoot() {
    // Target 3.5 rad (past π, where the angle used to wrap), spring k = 50 N·m/rad and
    // c = 15 N·m·s/rad on I = 1 kg·m²: damping ratio c / (2 √(k I)) = 1.06, so the closed form
    // from rest approaches the target without ever passing it. The symplectic spring step is
    // accurate to (ω h)² ≈ 2e-4 of the motion; 1e-3 rad of overshoot allows for it. Held: the
    // worst error over the last second (sleep off), 1e-3 rad.
    let target = 3.5;
    let (mut world, hinge) = cube_on_a_hinge(Motor::position(target, 50.0, 15.0, f32::INFINITY));
    let mut highest = f32::MIN;
    let mut worst_held = 0.0_f32;
    for step in 0..600 {
        world.step(DT).unwrap();
        let angle = world.joint_position(hinge).unwrap();
        highest = highest.max(angle);
        if step >= 540 {
            worst_held = worst_held.max((angle - target).abs());
        }
    }
    assert!(highest <= target + 1e-3, "overshot to {highest} rad");
    assert!(
        worst_held < 1e-3,
        "{worst_held} rad off the target over the last second"
    );
}

#[test]
fn an_underdamped_target_swings_past_pi_and_settles_on_it() {
    // Target 2.5 rad, k = 50, c = 2 on I = 1: damping ratio ζ = 0.141, so from rest the angle
    // peaks at 2.5 (1 + e^(−ζπ/√(1−ζ²))) = 4.10 rad, past π, then rings down onto the target
    // (the angle wrapped at ±π used to send it the wrong way from there). The solver's spring
    // loses a little more than its damping over a swing (the relax pass meets it again at each
    // substep's end pose): the peak comes 0.9 % low at ω h = 0.015, and 2 % allows for it.
    // After 10 s (e^(−ζ ω t) = 5e-5 of the swing) the angle holds within 1e-3 rad.
    let target = 2.5;
    let (mut world, hinge) = cube_on_a_hinge(Motor::position(target, 50.0, 2.0, f32::INFINITY));
    let zeta = 2.0 / (2.0 * 50.0_f32.sqrt());
    let expected_peak = target * (1.0 + (-zeta * PI / (1.0 - zeta * zeta).sqrt()).exp());
    let mut peak = f32::MIN;
    let mut worst_held = 0.0_f32;
    for step in 0..660 {
        world.step(DT).unwrap();
        let angle = world.joint_position(hinge).unwrap();
        peak = peak.max(angle);
        if step >= 600 {
            worst_held = worst_held.max((angle - target).abs());
        }
    }
    assert!(
        peak > PI && (peak / expected_peak - 1.0).abs() < 0.02,
        "peak {peak} rad, closed form {expected_peak}"
    );
    assert!(
        worst_held < 1e-3,
        "{worst_held} rad off the target after 10 s"
    );
}

#[test]
fn a_target_of_four_pi_is_two_whole_turns() {
    // The stiff, over-damped motor of the 3.5 rad test turns the cube two whole turns.
    let (mut world, hinge) = cube_on_a_hinge(Motor::position(2.0 * TAU, 50.0, 15.0, f32::INFINITY));
    for _ in 0..900 {
        world.step(DT).unwrap();
    }
    let angle = world.joint_position(hinge).unwrap();
    assert!(
        (angle - 2.0 * TAU).abs() < 1e-3,
        "angle {angle} rad, expected 4π"
    );
}

#[test]
fn limits_beyond_half_a_turn_stop_the_angle_counted_across_turns() {
    // A torque of 1 N·m winds the free wheel (I = 0.25 kg·m², 4 rad/s²) up against an upper
    // limit of 2π: it reaches it after one whole turn, 1.8 s in at 7 rad/s, and is held there
    // against the torque. The limit stops it within a substep (speculative), and the torque
    // then presses it in only by what its soft correction lets through each substep,
    // τ h² / I ≈ 2e-5 rad; 1e-3 rad holds that with room.
    let (mut world, _, hinge) = wheel(0.0, |hinge| {
        hinge.limits(-2.0 * TAU, TAU).motor(Motor::torque(1.0))
    });
    let mut highest = f32::MIN;
    for _ in 0..600 {
        world.step(DT).unwrap();
        highest = highest.max(world.joint_position(hinge).unwrap());
    }
    let angle = world.joint_position(hinge).unwrap();
    assert!(
        (angle - TAU).abs() < 1e-3,
        "angle {angle} rad at the 2π limit"
    );
    assert!(
        highest < TAU + 1e-3,
        "went to {highest} rad past the 2π limit"
    );
}

#[test]
fn prismatic_and_distance_joints_read_their_slide_and_length() {
    // A ball 1.5 m out along X moving at (0.4, 0.3, 0) m/s, no gravity, held by a distance joint
    // of rigid length 1.5 m: length 1.5, rate 0. A box slid 0.3 m along a slide through it reads
    // 0.3 m, at the velocity given along the axis.
    let mut world = world(Vec3::ZERO);
    let ball = add(
        &mut world,
        BodyDesc::dynamic(Shape::sphere(0.1).unwrap())
            .position(Vec3::X * 1.5)
            .linear_velocity(Vec3::new(0.0, 0.3, 0.0)),
    );
    let rope = world
        .add_joint(JointDesc::distance(None, ball, Vec3::ZERO, Vec3::X * 1.5))
        .unwrap();
    let slider = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.2)).unwrap())
            .position(Vec3::new(0.0, 5.0, 0.0))
            .linear_velocity(Vec3::X * 0.4),
    );
    let slide = world
        .add_joint(JointDesc::prismatic(
            None,
            slider,
            Vec3::new(0.0, 5.0, 0.0),
            Vec3::X,
        ))
        .unwrap();
    assert_eq!(world.joint_position(slide).unwrap(), 0.0);
    assert_eq!(world.joint_velocity(slide).unwrap(), 0.4);
    assert_eq!(world.joint_position(rope).unwrap(), 1.5);
    assert_eq!(world.joint_velocity(rope).unwrap(), 0.0);
    for _ in 0..45 {
        world.step(DT).unwrap();
    }
    // 0.75 s at 0.4 m/s: 0.3 m, rounding only. The rope holds its length to its position
    // correction's few micrometres and the ball swings round it.
    let slid = world.joint_position(slide).unwrap();
    assert!((slid - 0.3).abs() < 1e-5, "slide {slid} m");
    let length = world.joint_position(rope).unwrap();
    assert!((length - 1.5).abs() < 1e-4, "length {length} m");
    assert!(world.joint_velocity(rope).unwrap().abs() < 1e-3);
}

#[test]
fn a_world_saved_mid_turn_resumes_counting_the_same_turns() {
    // Saved 1.5 turns in, the restored world reads the same angle and steps on bit for bit.
    let (mut world, _, hinge) = wheel(TAU, |hinge| hinge.motor(Motor::torque(0.3)));
    for _ in 0..90 {
        world.step(DT).unwrap();
    }
    let mut restored = World::load_state(&world.save_state()).unwrap();
    for _ in 0..90 {
        world.step(DT).unwrap();
        restored.step(DT).unwrap();
        for read in [World::joint_position, World::joint_velocity] {
            assert_eq!(
                read(&world, hinge).unwrap().to_bits(),
                read(&restored, hinge).unwrap().to_bits()
            );
        }
    }
    assert!(world.joint_position(hinge).unwrap() > 3.0 * TAU);
}

#[test]
fn setting_the_same_motor_every_step_changes_nothing() {
    // A controller that sets its motor every step, to the same values, leaves the joint's
    // warm start and angle as they were: the run is bit for bit that of a motor set once.
    let motor = Motor::position(2.5, 50.0, 2.0, 30.0);
    let (mut set_once, once) = cube_on_a_hinge(motor);
    let (mut set_always, always) = cube_on_a_hinge(motor);
    for _ in 0..120 {
        set_always.set_joint_motor(always, Some(motor)).unwrap();
        set_once.step(DT).unwrap();
        set_always.step(DT).unwrap();
        assert_eq!(
            set_once.joint_position(once).unwrap().to_bits(),
            set_always.joint_position(always).unwrap().to_bits()
        );
    }
}
