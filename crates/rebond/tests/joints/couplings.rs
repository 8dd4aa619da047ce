//! Couplings of joint coordinates (`L = Σ cᵢ qᵢ`) against closed forms: gears that follow, limits
//! that hold, a spring's period, and bad input refused.

use super::{add, mean_period, upward_crossings, world, DT};
use rebond::{
    BodyDesc, BodyHandle, CouplingDesc, ErrorKind, JointDesc, JointHandle, Motor, Shape, Vec3,
    World,
};
use std::f32::consts::PI;

/// Wheel radius, m, and masses, kg: a sphere's inertia about any axis is `2/5 m r²`.
const RADIUS: f32 = 0.5;

/// A sphere "wheel" of mass `mass` at `x` on a hinge about Z to the world through its centre.
fn wheel(world: &mut World, x: f32, mass: f32) -> (BodyHandle, JointHandle) {
    let centre = Vec3::new(x, 0.0, 0.0);
    let body = add(
        world,
        BodyDesc::dynamic(Shape::sphere(RADIUS).unwrap())
            .mass(mass)
            .position(centre),
    );
    let joint = world
        .add_joint(JointDesc::revolute(None, body, centre, Vec3::Z))
        .unwrap();
    (body, joint)
}

fn inertia(mass: f32) -> f32 {
    0.4 * mass * RADIUS * RADIUS
}

/// Two wheels (1 kg and 3 kg) geared `q₂ = m q₁` by an equality coupling, the first driven by a
/// torque motor of 1 N·m from rest, no gravity: returns the worst `|q₂ − m q₁|` over 2 s and
/// `q₁` at the end.
fn geared_wheels(ratio: f32) -> (f32, f32, f32) {
    let mut world = world(Vec3::ZERO);
    let (_, driven) = wheel(&mut world, 0.0, 1.0);
    let (_, follower) = wheel(&mut world, 2.0, 3.0);
    world
        .set_joint_motor(driven, Some(Motor::torque(1.0)))
        .unwrap();
    world
        .add_coupling(CouplingDesc::new([(follower, 1.0), (driven, -ratio)]).limits(0.0, 0.0))
        .unwrap();
    let (steps, seconds) = (120, 120.0 * DT);
    let mut worst: f32 = 0.0;
    for _ in 0..steps {
        world.step(DT).unwrap();
        let (q1, q2) = (
            world.joint_position(driven).unwrap(),
            world.joint_position(follower).unwrap(),
        );
        worst = worst.max((q2 - ratio * q1).abs());
    }
    // One body of inertia `I₁ + m² I₂` turned by the motor: `q₁ = ½ τ t² / (I₁ + m² I₂)`.
    let expected = 0.5 * seconds * seconds / (inertia(1.0) + ratio * ratio * inertia(3.0));
    (worst, world.joint_position(driven).unwrap(), expected)
}

#[test]
fn an_equality_coupling_gears_one_wheel_to_another() {
    for ratio in [1.0, 2.0] {
        let (worst, q1, expected) = geared_wheels(ratio);
        // The equality row is rigid in the relax pass, with the joints' position correction in
        // the biased passes, and the row is exactly `q̇₂ − m q̇₁`: measured 0 and 9.5e-7 rad
        // (rounding of 1.5 to 5 rad); 1e-4 rad leaves room for the rounding of longer runs.
        assert!(
            worst < 1.0e-4,
            "ratio {ratio}: |q₂ − m q₁| reached {worst} rad"
        );
        // The coupled pair turns as one body of the combined inertia (the motor's torque meets
        // the follower's inertia through the gear). Symplectic Euler over the n = 960 substeps
        // runs `(n + 1)/n` ahead (0.1 %; measured 0.10 % both ways): 0.5 % is the bound.
        assert!(
            (q1 / expected - 1.0).abs() < 0.005,
            "ratio {ratio}: q₁ = {q1} rad, ½ τ t² / (I₁ + m² I₂) = {expected} rad"
        );
    }
}

#[test]
fn a_limited_coupling_keeps_its_length_within_the_limits() {
    // Two 1 kg wheels, `L = q₁ + q₂` within [−0.5, 0.5]; motors of 2 N·m drive both the same
    // way, first up, then down: L goes to each bound and is held there.
    let mut world = world(Vec3::ZERO);
    let (_, first) = wheel(&mut world, 0.0, 1.0);
    let (_, second) = wheel(&mut world, 2.0, 1.0);
    let coupling = world
        .add_coupling(CouplingDesc::new([(first, 1.0), (second, 1.0)]).limits(-0.5, 0.5))
        .unwrap();
    for (torque, bound) in [(2.0, 0.5), (-2.0, -0.5)] {
        for joint in [first, second] {
            world
                .set_joint_motor(joint, Some(Motor::torque(torque)))
                .unwrap();
        }
        let mut worst: f32 = 0.0;
        for step in 0..120 {
            world.step(DT).unwrap();
            let length = world.coupling_length(coupling).unwrap();
            assert!(
                length.abs() <= 0.5 + 2.0e-3,
                "L = {length} rad at step {step}"
            );
            if step >= 60 {
                worst = worst.max((length - bound).abs());
            }
        }
        // Over the second second L sits on the bound, pushed by 4 N·m: the soft correction holds
        // the overshoot of about one substep's push, `L̈ h²` (L̈ = 40 rad/s², 1.7e-4 rad), and
        // takes it back: measured 2.8e-4 rad, 2e-3 rad is the bound.
        assert!(
            worst < 2.0e-3,
            "L strays {worst} rad from the bound {bound} it is pushed onto"
        );
    }
}

#[test]
fn a_coupling_spring_on_one_hinge_swings_at_its_natural_frequency() {
    // `L = q` of one 2 kg wheel (I = 0.2 kg·m²), stiffness 5 N·m/rad, rest length 0.3 rad,
    // released at q = 0: q(t) = 0.3 (1 − cos ω t), ω = √(k/I) = 5 rad/s. As for the joints'
    // springs (`drives.rs`), the symplectic substep's period error (ω h)²/24 is 5e-6; 1 % leaves
    // room for the crossings' sampling
    // (measured 4e-6).
    let (mass, stiffness, rest) = (2.0, 5.0, 0.3);
    let mut world = world(Vec3::ZERO);
    let (_, hinge) = wheel(&mut world, 0.0, mass);
    world
        .add_coupling(
            CouplingDesc::new([(hinge, 1.0)])
                .spring(stiffness, 0.0)
                .length(rest),
        )
        .unwrap();
    let expected = 2.0 * PI * (inertia(mass) / stiffness).sqrt();
    let swing: Vec<f32> = (0..(5.5 * expected / DT) as usize)
        .map(|_| {
            world.step(DT).unwrap();
            world.joint_position(hinge).unwrap() - rest
        })
        .collect();
    let period = mean_period(&upward_crossings(&swing));
    assert!(
        (period / expected - 1.0).abs() < 0.01,
        "period {period} s, 2π√(I/k) = {expected} s"
    );
    // Undamped: the swing keeps its amplitude (symplectic Euler's peak lies (ω h)²/8 above it;
    // measured 0.30001 rad against 0.3).
    let peak = swing.iter().fold(0.0f32, |most, q| most.max(q.abs()));
    assert!((peak / rest - 1.0).abs() < 0.01, "amplitude {peak} rad");
}

#[test]
fn bad_couplings_are_refused_naming_the_field() {
    let mut world = world(Vec3::ZERO);
    let (body, hinge) = wheel(&mut world, 0.0, 1.0);
    let other = add(
        &mut world,
        BodyDesc::dynamic(Shape::sphere(0.1).unwrap()).position(Vec3::new(3.0, 0.0, 0.0)),
    );
    let ball = world
        .add_joint(JointDesc::ball(body, other, Vec3::new(3.0, 0.0, 0.0)))
        .unwrap();
    let removed = world
        .add_joint(JointDesc::revolute(None, other, Vec3::ZERO, Vec3::Y))
        .unwrap();
    world.remove_joint(removed).unwrap();
    let cases = [
        (CouplingDesc::new([]), "joints", ErrorKind::Missing),
        (
            CouplingDesc::new([(hinge, 1.0), (removed, 1.0)]),
            "joints[1].joint",
            ErrorKind::StaleJointHandle,
        ),
        (
            CouplingDesc::new([(hinge, 1.0), (ball, 1.0)]),
            "joints[1].joint",
            ErrorKind::NotForJointType("ball"),
        ),
        (
            CouplingDesc::new([(hinge, f32::NAN)]),
            "joints[0].coefficient",
            ErrorKind::NotFinite,
        ),
        (
            CouplingDesc::new([(hinge, 1.0)]).limits(1.0, -1.0),
            "limits",
            ErrorKind::InvertedLimits {
                min: 1.0,
                max: -1.0,
            },
        ),
        (
            CouplingDesc::new([(hinge, 1.0)]).spring(-1.0, 0.0),
            "stiffness",
            ErrorKind::Negative(-1.0),
        ),
        (
            CouplingDesc::new([(hinge, 1.0)]).length(f32::INFINITY),
            "length",
            ErrorKind::NotFinite,
        ),
    ];
    for (desc, field, kind) in cases {
        let error = world.add_coupling(desc).unwrap_err();
        assert_eq!((error.field.as_str(), error.kind), (field, kind));
    }
    assert_eq!(world.coupling_count(), 0, "a refused coupling is not added");
}

#[test]
fn removing_a_coupled_joint_removes_its_couplings() {
    let mut world = world(Vec3::ZERO);
    let (_, first) = wheel(&mut world, 0.0, 1.0);
    let (_, second) = wheel(&mut world, 2.0, 1.0);
    let coupling = world
        .add_coupling(CouplingDesc::new([(first, 1.0), (second, -1.0)]).limits(0.0, 0.0))
        .unwrap();
    world.remove_joint(second).unwrap();
    assert_eq!(world.coupling_count(), 0);
    assert_eq!(
        world.coupling(coupling).unwrap_err().kind,
        ErrorKind::StaleCouplingHandle
    );
    world.step(DT).unwrap();
}

#[test]
fn coupled_bodies_share_one_island() {
    // Two wheels on hinges to the world touch nothing: two islands, until a coupling ties them.
    let mut world = world(Vec3::ZERO);
    let (_, first) = wheel(&mut world, 0.0, 1.0);
    let (_, second) = wheel(&mut world, 2.0, 1.0);
    world.step(DT).unwrap();
    assert_eq!(world.island_count(), 2);
    world
        .add_coupling(CouplingDesc::new([(first, 1.0), (second, -1.0)]))
        .unwrap();
    world.step(DT).unwrap();
    assert_eq!(world.island_count(), 1);
}
