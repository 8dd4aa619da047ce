//! A ball and a box launched across a floor of many triangles, in several directions, on
//! triangles that share their vertices and on squares that share only positions; and across the
//! tile seams of the built-in `level` room.

use std::path::Path;

use rebond::scene::Scene;
use rebond::{BodyDesc, Shape, Vec3, World};

use super::{floor_mesh, floor_quads, heading, world, DT, G};

/// Launch directions, radians about +Y: along the cells' edges, along their diagonals, and across
/// both at odd angles.
const HEADINGS: [f32; 5] = [0.0, 0.3, std::f32::consts::FRAC_PI_4, 1.1, 2.4];

/// The two floors: triangles sharing their vertices, and squares sharing none.
const FLOORS: [fn(f32, u32) -> Shape; 2] = [floor_mesh, floor_quads];

fn floor_world(floor: fn(f32, u32) -> Shape, friction: f32, cell: f32) -> World {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let size = 40.0;
    world
        .add_body(BodyDesc::static_body(floor(size, (size / cell) as u32)).friction(friction))
        .unwrap();
    world
}

/// The built-in `level` room (`scenes/level.obj`, 2 m floor tiles written a face at a time, no
/// vertex shared between tiles) alone, friction `friction`.
fn level_world(friction: f32) -> World {
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let json = format!(
        r#"{{"gravity": [0, {}, 0], "bodies": [{{"name": "level", "type": "static",
            "friction": {friction}, "shape": {{"type": "trimesh", "file": "level.obj"}}}}]}}"#,
        -G
    );
    Scene::from_json_in(json.as_bytes(), &scenes)
        .unwrap()
        .into_world()
}

#[test]
fn a_ball_launched_sliding_rolls_at_five_sevenths_across_triangle_edges() {
    for floor in FLOORS {
        for angle in HEADINGS {
            let mut world = floor_world(floor, 0.4, 1.0);
            ball_rolls_at_five_sevenths(&mut world, Vec3::ZERO, angle);
        }
    }
}

#[test]
fn a_ball_rolls_across_the_level_tiles_as_on_one_floor() {
    // Between the walls, clear of the stairs (z < −7): 7 m of travel crosses 3 to 5 seams.
    for angle in HEADINGS {
        let mut world = level_world(0.4);
        ball_rolls_at_five_sevenths(&mut world, Vec3::new(0.3, 0.0, 0.3), angle);
    }
}

/// Launches a ball of radius 0.5 m sliding at 5 m/s from `start` (on the floor y = 0) along
/// `heading(angle)` on the floor of `world` (friction 0.4) and checks its rolling speed after 2 s
/// and its vertical speed on the way.
fn ball_rolls_at_five_sevenths(world: &mut World, start: Vec3, angle: f32) {
    let (radius, launch, friction) = (0.5, 5.0, 0.4);
    let direction = heading(angle);
    let ball = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(radius).unwrap())
                .position(start + Vec3::new(0.0, radius, 0.0))
                .linear_velocity(direction * launch)
                .friction(friction)
                .can_sleep(false),
        )
        .unwrap();
    // Sliding ends after t = 2 v₀ / (7 μ g) = 0.36 s; run 2 s, about 7 m and 14 edges.
    let mut worst_vertical = 0.0f32;
    for _ in 0..120 {
        world.step(DT).unwrap();
        let velocity = world.body(ball).unwrap().linear_velocity();
        worst_vertical = worst_vertical.max(velocity.y.abs());
    }
    let body = world.body(ball).unwrap();
    let speed = body.linear_velocity().dot(direction);
    let expected = 5.0 / 7.0 * launch;
    // 2 %: the issue's bound. On a single box floor the same ball lands within 1 % (friction
    // acts once per substep, μ g h = 0.008 m/s); the rest is room for the edges.
    assert!(
        (speed / expected - 1.0).abs() <= 0.02,
        "heading {angle}: rolls at {speed}, expected {expected}"
    );
    // 1 cm/s: the issue's bound; a hop off an edge normal tilted by only 1° would reach
    // 5 m/s · sin 1° = 9 cm/s.
    assert!(
        worst_vertical <= 0.01,
        "heading {angle}: vertical speed reached {worst_vertical} m/s"
    );
}

#[test]
fn a_sliding_box_stops_after_v_squared_over_two_mu_g_across_triangle_edges() {
    for floor in FLOORS {
        for angle in HEADINGS {
            // Cells of 0.4 m: the 1 m box always rests on several triangles at once.
            let mut world = floor_world(floor, 0.5, 0.4);
            box_slides_v_squared_over_two_mu_g(&mut world, Vec3::ZERO, angle);
        }
    }
}

#[test]
fn a_box_slides_across_the_level_tiles_as_on_one_floor() {
    // Starting 0.1–0.4 m from a tile corner (2, 0, 2), every heading crosses a seam under the box.
    for angle in HEADINGS {
        let mut world = level_world(0.5);
        box_slides_v_squared_over_two_mu_g(&mut world, Vec3::new(1.7, 0.0, 1.9), angle);
    }
}

/// Launches a unit box sliding at 3 m/s from `start` (on the floor y = 0) along `heading(angle)`
/// on the floor of `world` (friction 0.5) and checks where it stops and that it neither turns nor
/// drifts.
fn box_slides_v_squared_over_two_mu_g(world: &mut World, start: Vec3, angle: f32) {
    let (launch, friction) = (3.0, 0.5);
    let direction = heading(angle);
    let start = start + Vec3::new(0.0, 0.5, 0.0);
    let crate_ = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.5)).unwrap())
                .position(start)
                .linear_velocity(direction * launch)
                .friction(friction)
                .can_sleep(false),
        )
        .unwrap();
    // Stops after v / (μ g) = 0.61 s; run 1.5 s.
    for _ in 0..90 {
        world.step(DT).unwrap();
    }
    let body = world.body(crate_).unwrap();
    let travelled = (body.position() - start).dot(direction);
    let expected = launch * launch / (2.0 * friction * G);
    // 3 %: the issue's bound. Friction acts per substep (h = 1/240 s), so the stop is
    // resolved to v h / 2 ≈ 6 mm (0.7 %).
    assert!(
        (travelled / expected - 1.0).abs() <= 0.03,
        "heading {angle}: slid {travelled} m, expected {expected} m"
    );
    let sideways = (body.position() - start).cross(direction).length();
    let (axis, turn) = body.rotation().to_axis_angle();
    // Without turning: 0.5° and 1 cm sideways are far below what a catching corner does (it
    // turns the box by tens of degrees).
    assert!(
        turn.abs() < 0.5f32.to_radians(),
        "heading {angle}: turned by {turn} rad about {axis}"
    );
    assert!(
        sideways < 0.01,
        "heading {angle}: drifted {sideways} m sideways"
    );
    assert!(body.linear_velocity().length() < 1.0e-3);
}
