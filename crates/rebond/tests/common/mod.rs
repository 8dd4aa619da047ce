//! Scene helpers shared by the solver tests.
#![allow(dead_code)]

use rebond::{BodyDesc, BodyHandle, Quat, Shape, Vec3, World, WorldSettings};

/// One step at 60 Hz, the engine's intended rate.
pub const DT: f32 = 1.0 / 60.0;
/// Standard gravity used by the tests, m/s².
pub const G: f32 = 9.81;

/// A world with the default settings and the given gravity.
pub fn world(gravity: Vec3) -> World {
    World::new(WorldSettings {
        gravity,
        ..WorldSettings::default()
    })
    .unwrap()
}

/// A static ground box whose top face is the plane y = 0, with friction `friction`.
pub fn add_ground(world: &mut World, friction: f32) -> BodyHandle {
    world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(50.0, 0.5, 50.0)).unwrap())
                .position(Vec3::new(0.0, -0.5, 0.0))
                .friction(friction),
        )
        .unwrap()
}

/// A unit box (1 m sides) at `position`, dynamic, default material.
pub fn unit_box(position: Vec3) -> BodyDesc {
    BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.5)).unwrap()).position(position)
}

/// A static incline: a large box rotated by `angle` about Z, its top face through the origin.
pub fn add_incline(world: &mut World, angle: f32, friction: f32) -> BodyHandle {
    let rotation = Quat::from_rotation_z(angle);
    world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(50.0, 0.5, 50.0)).unwrap())
                .position(rotation * Vec3::new(0.0, -0.5, 0.0))
                .rotation(rotation)
                .friction(friction),
        )
        .unwrap()
}

/// The highest a bouncing body rises after it first moves up, stopping as it comes down again:
/// `step` advances its world by one step and returns the body's height and vertical velocity.
/// At most `steps` steps.
pub fn apex_after_bounce(steps: usize, mut step: impl FnMut() -> (f32, f32)) -> f32 {
    let (mut bounced, mut highest) = (false, 0.0f32);
    for _ in 0..steps {
        let (height, vertical_velocity) = step();
        bounced |= vertical_velocity > 0.0;
        if bounced {
            highest = highest.max(height);
            if vertical_velocity < 0.0 {
                break;
            }
        }
    }
    highest
}

/// Steps the world `steps` times.
pub fn run(world: &mut World, steps: usize) {
    for _ in 0..steps {
        world.step(DT).unwrap();
    }
}

/// The path of the built-in scene file `name` (`scenes/NAME.json`).
pub fn scene_path(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(format!("{name}.json"))
}
