//! When bodies fall asleep: a constant push keeps them awake, small bodies need a speed their
//! size makes still.

mod common;

use common::{add_ground, run, world, DT, G};
use rebond::{BodyDesc, LockedAxes, Shape, Vec3, World};

/// A 1 kg box 20 cm on a side resting on a frictionless floor.
fn box_on_ice(world: &mut World) -> BodyDesc {
    add_ground(world, 0.0);
    BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.1)).unwrap())
        .mass(1.0)
        .friction(0.0)
        .position(Vec3::new(0.0, 0.1, 0.0))
}

#[test]
fn a_small_constant_push_on_ice_never_lets_the_box_sleep() {
    // 0.02 N on 1 kg with nothing to hold it: a = 0.02 m/s², so v = a t = 0.2 m/s after 10 s.
    // Semi-implicit Euler gains exactly a·dt a step, and a frictionless floor takes nothing along
    // x, so the bound is f32 rounding of 600 additions of 3.3e-4 (about 1e-5) with margin.
    // The box stays slower than the 5 cm/s sleep speed for its first 2.5 s: by speed alone it
    // would have slept at 0.5 s and kept v = 0.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let desc = box_on_ice(&mut world).constant_force(Vec3::new(0.02, 0.0, 0.0));
    let body = world.add_body(desc).unwrap();
    for _ in 0..600 {
        world.step(DT).unwrap();
        assert!(!world.body(body).unwrap().is_sleeping());
    }
    let speed = world.body(body).unwrap().linear_velocity().x;
    assert!((speed - 0.2).abs() < 1e-4, "{speed} m/s after 10 s");
}

#[test]
fn a_small_constant_torque_spins_a_floating_box_up_from_rest() {
    // 1e-4 N·m about y on the same box in zero gravity: I = m (2 · 0.2²) / 12 = 6.67e-3 kg m², so
    // ω = τ t / I = 0.15 rad/s after 10 s (its corners at 0.026 m/s, under the sleep speed for
    // all ten seconds). Rounding as above.
    let mut world = world(Vec3::ZERO);
    let body = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.1)).unwrap())
                .mass(1.0)
                .constant_torque(Vec3::new(0.0, 1e-4, 0.0)),
        )
        .unwrap();
    run(&mut world, 600);
    let spin = world.body(body).unwrap().angular_velocity().y;
    let inertia = 1.0 * (0.2f32 * 0.2 + 0.2 * 0.2) / 12.0;
    let expected = 1e-4 * 10.0 / inertia;
    assert!((spin - expected).abs() < 1e-4, "{spin} rad/s, {expected}");
}

#[test]
fn a_push_held_by_friction_keeps_the_box_awake_until_it_is_cleared() {
    // 1 N on a 1 kg box with friction 0.5 (holding up to 4.9 N): the box never moves, and the
    // engine cannot tell before the solve that the floor holds the push, so it stays awake (as
    // documented on `WorldSettings::sleep_speed`); cleared, the box sleeps after the sleep time.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, 0.5);
    let body = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.1)).unwrap())
                .mass(1.0)
                .position(Vec3::new(0.0, 0.1, 0.0))
                .constant_force(Vec3::new(1.0, 0.0, 0.0)),
        )
        .unwrap();
    run(&mut world, 300);
    assert!(!world.body(body).unwrap().is_sleeping());
    world
        .body_mut(body)
        .unwrap()
        .set_constant_force(Vec3::ZERO)
        .unwrap();
    run(&mut world, 60);
    assert!(world.body(body).unwrap().is_sleeping());
}

#[test]
fn a_push_along_a_locked_axis_lets_the_body_sleep() {
    // The push along x cannot move a box locked along x: it sleeps as a box without a push.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let desc = box_on_ice(&mut world)
        .constant_force(Vec3::new(0.02, 0.0, 0.0))
        .locked_axes(LockedAxes {
            translation: [true, false, false],
            rotation: [false; 3],
        });
    let body = world.add_body(desc).unwrap();
    run(&mut world, 60);
    assert!(world.body(body).unwrap().is_sleeping());
}

#[test]
fn a_marble_rolling_a_centimetre_a_second_keeps_rolling() {
    // A marble 1 cm across rolling at 1 cm/s on a level floor keeps its speed (no rolling
    // resistance): it crosses its own size every second, motion anyone sees. Its fastest point
    // moves at 2.7 cm/s, under the world's 5 cm/s sleep speed, above its own still speed
    // (r_max = 0.87 cm per second). Rolling without slipping keeps v; after 10 s the marble is
    // 10 cm on, less what the first steps' slip took (the floor's friction matches ω to v within
    // a step; measured under 0.1 mm), bound 1 mm.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, 0.5);
    let radius = 0.005;
    let speed = 0.01;
    let marble = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(radius).unwrap())
                .position(Vec3::new(0.0, radius, 0.0))
                .linear_velocity(Vec3::new(speed, 0.0, 0.0))
                .angular_velocity(Vec3::new(0.0, 0.0, -speed / radius)),
        )
        .unwrap();
    run(&mut world, 600);
    let body = world.body(marble).unwrap();
    assert!(!body.is_sleeping());
    let travelled = body.position().x;
    assert!((travelled - 0.1).abs() < 1e-3, "{travelled} m in 10 s");
}

#[test]
fn a_large_slow_body_still_sleeps_at_the_world_sleep_speed() {
    // A 2 m box settles on the floor and sleeps within a second of landing: its reach, 1.7 m,
    // leaves the world's 5 cm/s as its still speed.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, 0.5);
    let body = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::splat(1.0)).unwrap())
                .position(Vec3::new(0.0, 1.01, 0.0)),
        )
        .unwrap();
    run(&mut world, 120);
    assert!(world.body(body).unwrap().is_sleeping());
}
