//! Fast bodies against walls and planks: the speculative contact (made a step ahead, as far as
//! the bodies can close in a step) stops them at the surface, and a face meeting a face stops
//! flat (the manifold's rigid points solved as one block).

mod common;

use common::{world, DT};
use rebond::{BodyDesc, BodyHandle, Quat, Shape, Vec3, World};

/// A world without gravity with a static wall of thickness `thickness` whose face toward −x is
/// the plane x = 0, and a dynamic `shape` 20 m before it at `rotation`, flying at `speed`
/// along +x with restitution 0.
fn wall_and_shot(thickness: f32, shape: Shape, rotation: Quat, speed: f32) -> (World, BodyHandle) {
    let mut world = world(Vec3::ZERO);
    world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(0.5 * thickness, 5.0, 5.0)).unwrap())
                .position(Vec3::new(0.5 * thickness, 0.0, 0.0)),
        )
        .unwrap();
    let shot = world
        .add_body(
            BodyDesc::dynamic(shape)
                .position(Vec3::new(-20.0, 0.0, 0.0))
                .rotation(rotation)
                .linear_velocity(Vec3::new(speed, 0.0, 0.0))
                .can_sleep(false),
        )
        .unwrap();
    (world, shot)
}

#[test]
fn a_box_flying_face_first_into_a_wall_stops_dead() {
    // Restitution 0: the box should stop at the wall, not rebound or turn. Bounds (the
    // issue's): under 0.5 m/s and 0.5 rad/s at every step after the hit (measured: under 3e-4
    // m/s and 3e-4 rad/s), and it never passes the wall's face.
    for speed in [50.0f32, 200.0, 1000.0] {
        let box_shape = Shape::cuboid(Vec3::splat(0.5)).unwrap();
        let (mut world, shot) = wall_and_shot(1.0, box_shape, Quat::IDENTITY, speed);
        let hit_by = (20.0 / (speed * DT)).ceil() as usize;
        for step in 0..hit_by + 60 {
            world.step(DT).unwrap();
            let body = world.body(shot).unwrap();
            assert!(
                body.position().x < -0.49,
                "{speed} m/s: at {}",
                body.position()
            );
            if step >= hit_by {
                let (v, w) = (body.linear_velocity(), body.angular_velocity());
                assert!(v.length() < 0.5 && w.length() < 0.5, "{speed} m/s: {v} {w}");
            }
        }
    }
}

#[test]
fn a_bullet_never_passes_through_a_thin_plank() {
    // A 2 cm plank and a 1 cm sphere at up to 1,000 m/s (16.7 m a step), and a turned box
    // bullet: each must end on the near side of the plank.
    let bullets = [
        (Shape::sphere(0.01).unwrap(), Quat::IDENTITY),
        (
            Shape::cuboid(Vec3::new(0.05, 0.01, 0.01)).unwrap(),
            Quat::from_rotation_z(0.3),
        ),
    ];
    for (shape, rotation) in bullets {
        for speed in [100.0f32, 400.0, 1000.0] {
            let (mut world, shot) = wall_and_shot(0.02, shape.clone(), rotation, speed);
            for _ in 0..120 {
                world.step(DT).unwrap();
                let x = world.body(shot).unwrap().position().x;
                assert!(x < 0.0, "{speed} m/s: reached x = {x}");
            }
        }
    }
}

#[test]
fn a_fast_box_meeting_a_resting_one_face_first_shares_its_momentum_without_turning() {
    // Equal unit boxes, restitution 0, no gravity: a perfectly inelastic collision leaves both
    // at half the speed, v/2, with no spin. Bounds: 0.1 % of v and 1e-3 rad/s (rounding; the
    // two are not pushed apart, so they stay in contact, speculative points holding them).
    for speed in [50.0f32, 400.0] {
        let mut world = world(Vec3::ZERO);
        let cube = || Shape::cuboid(Vec3::splat(0.5)).unwrap();
        let target = world
            .add_body(BodyDesc::dynamic(cube()).can_sleep(false))
            .unwrap();
        let shot = world
            .add_body(
                BodyDesc::dynamic(cube())
                    .position(Vec3::new(-20.0, 0.0, 0.0))
                    .linear_velocity(Vec3::new(speed, 0.0, 0.0))
                    .can_sleep(false),
            )
            .unwrap();
        let hit_by = (20.0 / (speed * DT)).ceil() as usize;
        common::run(&mut world, hit_by + 30);
        for body in [shot, target] {
            let body = world.body(body).unwrap();
            let (v, w) = (body.linear_velocity(), body.angular_velocity());
            assert!(
                (v - Vec3::new(0.5 * speed, 0.0, 0.0)).length() < 1e-3 * speed,
                "{speed} m/s: {v}"
            );
            assert!(w.length() < 1e-3, "{speed} m/s: {w}");
        }
    }
}
