//! Joint friction against Coulomb's law: a joint slows its free motion at `friction / I` (or
//! `/ m`), stops it for good, and holds still under a smaller load.

use super::{add, angle_about_z, rod, world, DT, G};
use rebond::{BodyDesc, JointDesc, Quat, Shape, Vec3};
use std::f32::consts::FRAC_PI_2;

/// A 6 kg unit cube about its centre, no gravity: `I = m (1 + 1)/12 = 1 kg·m²` about every
/// axis, so a friction torque `τ` slows it at `τ` rad/s² whatever the axis.
fn spinning_cube(spin: Vec3, joint: impl FnOnce(rebond::BodyHandle) -> JointDesc) -> Vec<Vec3> {
    let mut world = world(Vec3::ZERO);
    let cube = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.5)).unwrap())
            .mass(6.0)
            .angular_velocity(spin),
    );
    world.add_joint(joint(cube)).unwrap();
    (0..300)
        .map(|_| {
            world.step(DT).unwrap();
            world.body(cube).unwrap().angular_velocity()
        })
        .collect()
}

/// Checks a spin that starts at `start` and slows at 0.5 rad/s² along its own direction: 1.5
/// rad/s left after 1 s (the friction impulse is exactly `τ h` each substep, so only f32
/// rounding is off: 1e-3), stopped from 4 s on.
fn assert_slows_and_stops(spins: &[Vec3], start: Vec3) {
    let direction = start.normalize();
    let after_one_second = spins[59];
    let expected = direction * (start.length() - 0.5);
    assert!(
        (after_one_second - expected).length() < 1e-3,
        "spin {after_one_second:?} after 1 s, expected {expected:?}"
    );
    for spin in &spins[245..] {
        assert!(spin.length() < 1e-5, "still spinning at {spin:?} after 4 s");
    }
}

#[test]
fn revolute_friction_slows_a_spin_at_friction_over_inertia_and_stops_it() {
    let start = Vec3::new(0.0, 0.0, 2.0);
    let spins = spinning_cube(start, |cube| {
        JointDesc::revolute(None, cube, Vec3::ZERO, Vec3::Z).friction(0.5)
    });
    assert_slows_and_stops(&spins, start);
}

#[test]
fn ball_friction_slows_a_spin_about_any_axis_along_that_axis() {
    // Coulomb friction on a couple opposes the relative spin's direction: the spin shrinks
    // without turning.
    let start = Vec3::new(2.0, -1.0, 2.0) * (2.0 / 3.0);
    let spins = spinning_cube(start, |cube| {
        JointDesc::ball(None, cube, Vec3::ZERO).friction(0.5)
    });
    assert_slows_and_stops(&spins, start);
}

#[test]
fn prismatic_friction_stops_a_slide_after_v_squared_over_twice_the_deceleration() {
    // 2 kg sliding at 3 m/s against 4 N: a = 2 m/s², it stops at 1.5 s after v²/2a = 2.25 m,
    // less the half substep that semi-implicit Euler's positions lag by, v₀ h / 2 = 3 mm (h =
    // 1/480 s): within 5 mm.
    let mut world = world(Vec3::ZERO);
    let block = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.1)).unwrap())
            .mass(2.0)
            .linear_velocity(Vec3::new(3.0, 0.0, 0.0)),
    );
    world
        .add_joint(JointDesc::prismatic(None, block, Vec3::ZERO, Vec3::X).friction(4.0))
        .unwrap();
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let speed = world.body(block).unwrap().linear_velocity().x;
    assert!(
        (speed - 1.0).abs() < 1e-3,
        "{speed} m/s after 1 s, 1 expected"
    );
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let body = world.body(block).unwrap();
    assert!(body.linear_velocity().length() < 1e-5, "still sliding");
    let travelled = body.position().x;
    assert!(
        (travelled - 2.25).abs() < 5e-3,
        "stopped after {travelled} m, v²/2a = 2.25 m"
    );
}

/// A 1 kg rod of 1 m hinged about Z at one end (the origin), lying along +X; `I = m L²/3` about
/// the hinge.
fn hinged_rod(world: &mut rebond::World, friction: f32) -> rebond::BodyHandle {
    let bar = add(
        world,
        rod(1.0, 1.0)
            .position(Vec3::new(0.5, 0.0, 0.0))
            .rotation(Quat::from_rotation_z(-FRAC_PI_2)),
    );
    world
        .add_joint(JointDesc::revolute(None, bar, Vec3::ZERO, Vec3::Z).friction(friction))
        .unwrap();
    bar
}

#[test]
fn a_rod_hinged_at_its_end_slows_at_friction_over_its_inertia_about_the_hinge() {
    // No gravity; spinning at 2 rad/s against 0.5 N·m: α = τ / I = 1.5 rad/s², so 0.5 rad/s
    // after 1 s, stopped from 4/3 s on. The hinge's point rows carry the rod round, so the
    // couple acts about the hinge, not the centre of mass (where it would be 6 rad/s²). While
    // it slips the friction impulse is exactly τ h a substep, which the hinge's rows pass on to
    // the rod as it turns between the poses they are built at: α within 1 % (0.015 rad/s).
    let mut world = world(Vec3::ZERO);
    let bar = hinged_rod(&mut world, 0.5);
    let body = world.body_mut(bar).unwrap();
    body.set_angular_velocity(Vec3::new(0.0, 0.0, 2.0)).unwrap();
    body.set_linear_velocity(Vec3::new(0.0, 1.0, 0.0)).unwrap();
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let spin = world.body(bar).unwrap().angular_velocity().z;
    assert!(
        (spin - 0.5).abs() < 0.015,
        "{spin} rad/s after 1 s, 0.5 expected"
    );
    for _ in 0..30 {
        world.step(DT).unwrap();
    }
    let spin = world.body(bar).unwrap().angular_velocity();
    assert!(
        spin.length() < 1e-4,
        "still turning at {spin:?} after 1.5 s"
    );
}

#[test]
fn a_rod_held_out_level_stays_put_when_friction_exceeds_its_weight_torque() {
    // The rod's weight pulls with m g L/2 = 4.9 N·m about the hinge; friction of 5 N·m holds it:
    // less than a milliradian of sag in 2 s (the give of the joint's position correction).
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let bar = hinged_rod(&mut world, 5.0);
    let mut sag = 0.0_f32;
    for _ in 0..120 {
        world.step(DT).unwrap();
        sag = sag.max(angle_about_z(world.body(bar).unwrap().rotation()) + FRAC_PI_2);
    }
    assert!(sag.abs() < 1e-3, "the rod sagged {sag} rad");
}
