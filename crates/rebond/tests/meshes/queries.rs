//! Ray casts, shape casts and overlaps against meshes and heightfields, against closed forms.

use rebond::{BodyDesc, Pose, Quat, QueryFilter, Ray, Shape, Vec3, World, WorldSettings};

use super::floor_mesh;

/// A world holding a static 20 m floor mesh at `y = 1` and a heightfield plane tilted by 30°
/// about Z (falling along +X) centred 40 m along X.
fn world() -> World {
    let mut world = World::new(WorldSettings::default()).unwrap();
    world
        .add_body(BodyDesc::static_body(floor_mesh(20.0, 20)).position(Vec3::new(0.0, 1.0, 0.0)))
        .unwrap();
    let slope = 30.0f32.to_radians().tan();
    let heights: Vec<Vec<f32>> = (0..11)
        .map(|_| {
            (0..11)
                .map(|j| -(j as f32 / 10.0 - 0.5) * 10.0 * slope)
                .collect()
        })
        .collect();
    let terrain = Shape::heightfield(&heights, Vec3::new(10.0, 1.0, 10.0)).unwrap();
    world
        .add_body(BodyDesc::static_body(terrain).position(Vec3::new(40.0, 0.0, 0.0)))
        .unwrap();
    world
}

#[test]
fn rays_hit_mesh_triangles_from_both_sides_and_heightfields_from_above() {
    let world = world();
    let filter = QueryFilter::default();
    let down = Ray::new(Vec3::new(0.3, 5.0, -2.7), Vec3::NEG_Y);
    let hit = world.cast_ray(&down, &filter).unwrap().expect("the floor");
    // Exact to f32 rounding: the floor is the plane y = 1.
    assert!((hit.distance - 4.0).abs() < 1e-5 && hit.normal.abs_diff_eq(Vec3::Y, 1e-6));
    let up = Ray::new(Vec3::new(0.3, -2.0, -2.7), Vec3::Y);
    let hit = world
        .cast_ray(&up, &filter)
        .unwrap()
        .expect("the floor's underside");
    assert!((hit.distance - 3.0).abs() < 1e-5 && hit.normal.abs_diff_eq(Vec3::NEG_Y, 1e-6));
    // The heightfield at x = 40 + 1.5: height −1.5 tan 30°.
    let x = 1.5;
    let expected = 5.0 + x * 30.0f32.to_radians().tan();
    let onto_slope = Ray::new(Vec3::new(40.0 + x, 5.0, 0.4), Vec3::NEG_Y);
    let hit = world
        .cast_ray(&onto_slope, &filter)
        .unwrap()
        .expect("the slope");
    assert!((hit.distance - expected).abs() < 1e-4, "{}", hit.distance);
    let normal = Quat::from_rotation_z(-30.0f32.to_radians()) * Vec3::Y;
    assert!(hit.normal.abs_diff_eq(normal, 1e-5), "{}", hit.normal);
    // A solid ray starting below the surface is inside the heightfield.
    let buried = Ray::new(Vec3::new(40.0, -3.0, 0.0), Vec3::X);
    assert_eq!(
        world.cast_ray(&buried, &filter).unwrap().unwrap().distance,
        0.0
    );
}

#[test]
fn shapes_cast_at_meshes_stop_at_the_surface() {
    let world = world();
    let filter = QueryFilter::default();
    let ball = Shape::sphere(0.5).unwrap();
    let start = Pose::from_position(Vec3::new(0.2, 4.0, 0.9));
    let hit = world
        .cast_shape(&ball, &start, Vec3::NEG_Y, f32::INFINITY, &filter)
        .unwrap()
        .expect("the floor");
    // The ball's bottom reaches y = 1 after 4 − 0.5 − 1 = 2.5 m; GJK's precision, 1e-5 of the
    // shapes' size, bounds the error.
    assert!((hit.distance - 2.5).abs() < 1e-3, "{}", hit.distance);
    assert!(hit.normal.abs_diff_eq(Vec3::Y, 1e-3), "{}", hit.normal);
    let crate_ = Shape::cuboid(Vec3::splat(0.5)).unwrap();
    let over_slope = Pose::from_position(Vec3::new(40.0, 3.0, 0.0));
    let hit = world
        .cast_shape(&crate_, &over_slope, Vec3::NEG_Y, 10.0, &filter)
        .unwrap()
        .expect("the slope");
    // The uphill bottom edge (x = 39.5) meets the slope at y = 0.5 tan 30°.
    let expected = 3.0 - 0.5 - 0.5 * 30.0f32.to_radians().tan();
    assert!((hit.distance - expected).abs() < 1e-3, "{}", hit.distance);
}

#[test]
fn overlaps_find_shapes_touching_meshes_and_buried_in_heightfields() {
    let world = world();
    let filter = QueryFilter::default();
    let ball = Shape::sphere(0.5).unwrap();
    let mut found = Vec::new();
    for (position, touches) in [
        (Vec3::new(0.0, 1.45, 0.0), true),
        (Vec3::new(0.0, 1.55, 0.0), false),
        (Vec3::new(0.0, 0.6, 0.0), true),
        (Vec3::new(40.0, -2.0, 0.0), true),
        (Vec3::new(40.0, 2.0, 0.0), false),
    ] {
        world
            .bodies_overlapping_shape(&ball, &Pose::from_position(position), &filter, &mut found)
            .unwrap();
        assert_eq!(found.len() == 1, touches, "ball at {position}");
    }
    let mut holding = Vec::new();
    world
        .bodies_containing_point(Vec3::new(40.0, -2.0, 1.0), &filter, &mut holding)
        .unwrap();
    assert_eq!(holding.len(), 1);
    world
        .bodies_containing_point(Vec3::new(0.0, 1.0, 0.0), &filter, &mut holding)
        .unwrap();
    assert!(holding.is_empty(), "a mesh holds no volume");
}
