//! Armature (MuJoCo's `armature`): inertia added to a joint's coordinate, against the closed
//! forms of a pendulum and a driven hinge.

use super::{add, mean_period, rod, upward_crossings, world, DT, G};
use rebond::{BodyDesc, JointDesc, Motor, Shape, Vec3};
use std::f32::consts::PI;

#[test]
fn a_torque_on_a_hinge_with_armature_turns_it_at_torque_over_total_inertia() {
    // A bar hinged at its centre about Z (I = m (w² + h²)/12 = 0.0867 kg·m²) with an armature of
    // 0.1 kg·m², driven by 0.5 N·m, gravity off: θ̈ = τ / (I + a), so after 1 s it turns at
    // 2.678 rad/s (without the armature, 5.77). Each substep the rotor and the bar share the
    // torque's impulse exactly as one inertia, so only rounding is left (measured 8e-6): 0.1 %
    // is the bound.
    let (torque, armature) = (0.5, 0.1);
    let mut world = world(Vec3::ZERO);
    let half = Vec3::new(0.5, 0.1, 0.1);
    let bar = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(half).unwrap()).mass(1.0),
    );
    let joint = world
        .add_joint(
            JointDesc::revolute(None, bar, Vec3::ZERO, Vec3::Z)
                .armature(armature)
                .motor(Motor::torque(torque)),
        )
        .unwrap();
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let inertia = (1.0 * 1.0 + 0.2 * 0.2) / 12.0;
    let expected = torque / (inertia + armature) * 60.0 * DT;
    let rate = world.joint_velocity(joint).unwrap();
    assert!(
        (rate / expected - 1.0).abs() < 0.001,
        "rate {rate} rad/s after 1 s, τ t / (I + a) = {expected} rad/s"
    );
}

#[test]
fn armature_slows_a_pendulum_to_its_closed_form_period() {
    // A 1 m rod of 1 kg hinged at its top end about Z, with an armature of 0.2 kg·m²:
    // T = 2π √((I_pivot + a) / (m g l)), I_pivot = m (L² + w²)/12 + m (L/2)² = 0.334 kg·m²,
    // l = 0.5 m: 1.467 s, against 1.160 s without. Released at 0.05 rad, the finite amplitude
    // lengthens it by θ₀²/16 = 1.6e-4 (measured 1.5e-4); 0.5 % is the bound, as for the
    // pendulums without.
    let (length, mass, armature) = (1.0, 1.0, 0.2);
    let amplitude = 0.05_f32;
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let pivot = Vec3::ZERO;
    let down = Vec3::new(amplitude.sin(), -amplitude.cos(), 0.0);
    let rod_body = add(
        &mut world,
        rod(length, mass)
            .position(pivot + 0.5 * length * down)
            .rotation(rebond::Quat::from_rotation_z(amplitude)),
    );
    let joint = world
        .add_joint(JointDesc::revolute(None, rod_body, pivot, Vec3::Z).armature(armature))
        .unwrap();
    let width = 0.1;
    let inertia = mass * (length * length + width * width) / 12.0 + mass * 0.25 * length * length;
    let expected = 2.0 * PI * ((inertia + armature) / (mass * G * 0.5 * length)).sqrt();
    let angles: Vec<f32> = (0..(6.5 * expected / DT) as usize)
        .map(|_| {
            world.step(DT).unwrap();
            // The coordinate counts from the release pose: hanging straight down is −θ₀.
            world.joint_position(joint).unwrap() + amplitude
        })
        .collect();
    let period = mean_period(&upward_crossings(&angles));
    assert!(
        (period / expected - 1.0).abs() < 0.005,
        "period {period} s, 2π√((I + a)/(m g l)) = {expected} s"
    );
}

#[test]
fn a_run_with_armature_and_springs_resumes_with_the_same_bits() {
    // The rotor's speed is the joint's rate as a step starts, read from the bodies' saved
    // velocities: a state saved mid-swing and loaded goes on exactly as the run that was not
    // stopped. The portable snapshot (another build's reading) keeps the armature and the
    // spring's reference.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let link = add(
        &mut world,
        rod(1.0, 1.0).position(Vec3::new(0.3, -0.4, 0.0)),
    );
    let joint = world
        .add_joint(
            JointDesc::revolute(None, link, Vec3::ZERO, Vec3::Z)
                .armature(0.05)
                .spring_to(3.0, 0.1, 0.4)
                .motor(Motor::torque(0.3)),
        )
        .unwrap();
    for _ in 0..37 {
        world.step(DT).unwrap();
    }
    let bytes = world.save_state();
    let mut resumed = rebond::World::load_state(&bytes).unwrap();
    for _ in 0..50 {
        world.step(DT).unwrap();
        resumed.step(DT).unwrap();
    }
    let (a, b) = (world.body(link).unwrap(), resumed.body(link).unwrap());
    assert_eq!(
        a.position().to_array().map(f32::to_bits),
        b.position().to_array().map(f32::to_bits)
    );
    assert_eq!(
        a.angular_velocity().to_array().map(f32::to_bits),
        b.angular_velocity().to_array().map(f32::to_bits)
    );
    let portable = rebond::World::load_state_as_other_build(&bytes).unwrap();
    let desc = portable.joint(joint).unwrap().desc();
    assert_eq!(desc.armature, 0.05);
    assert_eq!(desc.spring.unwrap().reference, 0.4);
}

#[test]
fn a_chain_with_mujoco_like_springs_armature_and_torques_stays_together() {
    // HalfCheetah's joints: stiffness 240 N·m/rad, damping 6 N·m·s/rad, armature 0.1 kg·m² and a
    // torque motor each. Three 0.3 m rods of 1 kg hinged end to end about Z under gravity, the
    // top one to the world, driven by ±60 N·m switching every quarter second for 5 s. The
    // springs hold each joint near τ/k = 0.25 rad: every angle stays within 1 rad; the rows
    // solved with the armature's keep each hinge's anchors within 1 mm; no group solve is
    // refused, and every value stays finite (measured: 0.62 rad, 0.2 mm).
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let mut joints = Vec::new();
    let mut above = None;
    for link in 0..3 {
        let top = Vec3::new(0.0, -0.3 * link as f32, 0.0);
        let body = add(&mut world, rod(0.3, 1.0).position(top - Vec3::Y * 0.15));
        let joint = world
            .add_joint(
                JointDesc::revolute(above, body, top, Vec3::Z)
                    .spring(240.0, 6.0)
                    .armature(0.1)
                    .motor(Motor::torque(0.0)),
            )
            .unwrap();
        joints.push(joint);
        above = Some(body);
    }
    let (mut worst_angle, mut worst_gap) = (0.0_f32, 0.0_f32);
    for step in 0..300 {
        let sign = if (step / 15) % 2 == 0 { 1.0 } else { -1.0 };
        for (index, &joint) in joints.iter().enumerate() {
            let torque = if index % 2 == 0 { 60.0 } else { -60.0 } * sign;
            world
                .set_joint_motor(joint, Some(Motor::torque(torque)))
                .unwrap();
        }
        world.step(DT).unwrap();
        assert_eq!(world.refused_joint_solves(), 0, "step {step}");
        for &joint in &joints {
            let angle = world.joint_position(joint).unwrap();
            let placement = world.joint_placement(joint).unwrap();
            assert!(angle.is_finite());
            worst_angle = worst_angle.max(angle.abs());
            worst_gap = worst_gap.max((placement.anchor_b - placement.anchor_a).length());
        }
    }
    assert!(
        worst_angle < 1.0 && worst_gap < 1.0e-3,
        "worst angle {worst_angle} rad, worst gap {worst_gap} m"
    );
}

/// A light bar (0.1 kg, 1 m × 0.2 m, hinged at its centre about Z: I = 0.00867 kg·m²) with a
/// heavy armature (1 kg·m², Gymnasium Ant's), gravity off, limited to `[min, max]`, turning at
/// `rate` as it starts; the worst excess beyond the range over 2 s, rad, and the joint's
/// position then.
fn light_bar_against_its_limits(min: f32, max: f32, rate: f32) -> (f32, f32) {
    let mut world = world(Vec3::ZERO);
    let bar = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::new(0.5, 0.1, 0.1)).unwrap())
            .mass(0.1)
            .angular_velocity(Vec3::Z * rate),
    );
    let joint = world
        .add_joint(
            JointDesc::revolute(None, bar, Vec3::ZERO, Vec3::Z)
                .armature(1.0)
                .limits(min, max),
        )
        .unwrap();
    let mut worst = 0.0_f32;
    for step in 0..120 {
        world.step(DT).unwrap();
        let position = world.joint_position(joint).unwrap();
        // A limit that starts violated has a few steps to push the joint back in.
        let lower = if step < 30 { 0.0 } else { min - position };
        worst = worst.max(position - max).max(lower);
    }
    (worst, world.joint_position(joint).unwrap())
}

#[test]
fn a_limit_stops_a_hinge_with_armature_at_its_range() {
    // The bar and its rotor turn at 2 rad/s into the limit at 0.5 rad: the limit's row stops
    // the two together, the rotor's momentum (1 kg·m² × 2 rad/s) with the bar's, as one inertia
    // `I + a` along the coordinate; a limit pushing on the bar alone stops a hundredth of it per
    // pass, and the rotor carries the bar through. The approach is stopped speculatively at the
    // limit; 0.01 rad bounds what the soft correction lets through (measured 6e-8 rad, at rest
    // at 0.5 rad; 0.09 rad past it while the limit pushed on the bar alone).
    let (excess, position) = light_bar_against_its_limits(-0.5, 0.5, 2.0);
    assert!(excess < 0.01, "{excess} rad past the limit");
    assert!((position - 0.5).abs() < 0.01, "rests at {position} rad");
}

#[test]
fn a_hinge_with_armature_starting_outside_its_range_comes_back_into_it() {
    // Gymnasium's Ant starts its ankles at 0, outside their range [30°, 70°]. The limit pushes
    // the joint back, a spring of `joint_hertz` (60 Hz, over-damped) on the bar and its rotor
    // together: in within half a second, and never past the other end (measured: no excess
    // after 0.5 s, resting at 0.5 rad; 0.26 rad short of the range after 0.5 s while the limit
    // pushed on the bar alone).
    let (excess, position) = light_bar_against_its_limits(0.5, 1.2, 0.0);
    assert!(excess < 0.01, "{excess} rad outside the range after 0.5 s");
    assert!((0.49..0.6).contains(&position), "ends at {position} rad");
}
