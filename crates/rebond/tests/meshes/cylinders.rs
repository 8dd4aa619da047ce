//! A cylinder lying on its cap across triangles bent against each other (a V-shaped dip, a bowl,
//! the bumps of the bench's `mesh_pile`): its rim must stay on the surface between the points
//! its contacts are made of.

use rebond::{BodyDesc, BodyHandle, Quat, QueryFilter, Ray, Shape, Vec3, World};

use super::random::Random;
use super::{world, DT, G};

/// How deep a rim may go below the surface, metres, at any step after landing. Clipped as the
/// square of four rim points, a cap sank up to 3.2 cm into these surfaces (1.6 cm on `mesh_pile`);
/// clipped whole, the worst cases here are 4.2 mm on the bumps and 3.8 mm on the jittered bowl,
/// at most 1.8 mm on the V-shaped dip and the smooth bowl. 5 mm keeps that margin while failing
/// the square by six times.
const RIM_DEPTH: f32 = 5.0e-3;

/// A surface `y = height(x, z)` over 8 m × 8 m, of squares `cell` metres a side, each split in
/// two triangles, with every inner vertex moved sideways by up to `jitter` metres.
fn surface_mesh(height: impl Fn(f32, f32) -> f32, cell: f32, jitter: f32) -> Shape {
    let cells = (8.0 / cell) as u32;
    let mut random = Random(53);
    let mut vertices = Vec::new();
    for i in 0..=cells {
        for j in 0..=cells {
            let inner = (1..cells).contains(&i) && (1..cells).contains(&j);
            let (dx, dz) = if inner {
                (random.range(-jitter, jitter), random.range(-jitter, jitter))
            } else {
                (0.0, 0.0)
            };
            let (x, z) = (j as f32 * cell - 4.0 + dx, i as f32 * cell - 4.0 + dz);
            vertices.push(Vec3::new(x, height(x, z), z));
        }
    }
    let at = |i: u32, j: u32| i * (cells + 1) + j;
    let mut indices = Vec::new();
    for i in 0..cells {
        for j in 0..cells {
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            if (i + j) % 2 == 0 {
                indices.extend([[a, d, c], [a, c, b]]);
            } else {
                indices.extend([[a, d, b], [b, d, c]]);
            }
        }
    }
    Shape::trimesh(vertices, &indices).unwrap()
}

/// How far the cylinder's rims go below the mesh (straight down, by ray casts), at 64 points each.
fn deepest_rim(world: &World, body: BodyHandle, radius: f32, half_height: f32) -> f32 {
    let pose = world.body(body).unwrap().pose();
    let filter = QueryFilter {
        include_dynamic: false,
        ..QueryFilter::default()
    };
    (0..128)
        .map(|k| {
            let angle = std::f32::consts::TAU * (k % 64) as f32 / 64.0;
            let y = if k < 64 { -half_height } else { half_height };
            let point =
                pose.transform_point(Vec3::new(radius * angle.cos(), y, radius * angle.sin()));
            let down = Ray::new(Vec3::new(point.x, 10.0, point.z), Vec3::NEG_Y);
            let hit = world.cast_ray(&down, &filter).unwrap().unwrap();
            hit.point.y - point.y
        })
        .fold(f32::NEG_INFINITY, f32::max)
}

/// Drops a cylinder of radius 0.3 m and half height 0.2 m (the bench's) at `rotation` with its
/// centre over `(x, z)`, 2 cm above its resting height there, onto `mesh`; the deepest its rims
/// go over the 2.5 s after the first half second (landed), sleeping off.
fn worst_rim_depth(mesh: Shape, x: f32, z: f32, rotation: Quat) -> f32 {
    let (radius, half_height) = (0.3, 0.2);
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    world
        .add_body(BodyDesc::static_body(mesh).friction(0.6))
        .unwrap();
    let filter = QueryFilter::default();
    let ground = world
        .cast_ray(&Ray::new(Vec3::new(x, 10.0, z), Vec3::NEG_Y), &filter)
        .unwrap()
        .unwrap()
        .point
        .y;
    // High enough for a rim over a rise of 27° (tan 27° · 0.3 m = 15 cm).
    let start = Vec3::new(x, ground + half_height + 0.17, z);
    let cylinder = world
        .add_body(
            BodyDesc::dynamic(Shape::cylinder(radius, half_height).unwrap())
                .position(start)
                .rotation(rotation)
                .friction(0.6)
                .can_sleep(false),
        )
        .unwrap();
    let mut worst = f32::NEG_INFINITY;
    for step in 0..180 {
        world.step(DT).unwrap();
        if step >= 30 {
            worst = worst.max(deepest_rim(&world, cylinder, radius, half_height));
        }
    }
    worst
}

/// The bench's bumps (`bump_height` in `bench/compare/src/scenes.rs`): 7 m apart, slopes up to
/// about 27°.
fn bumps(x: f32, z: f32) -> f32 {
    0.35 * (0.9 * x).sin() * (0.7 * z).cos() + 0.2 * (0.5 * x + 1.3 * z).sin()
}

#[test]
fn a_cylinder_lying_in_dips_and_on_bumps_keeps_its_rim_out_of_the_mesh() {
    let v_dip = |x: f32, _: f32| x.abs() * 4.0f32.to_radians().tan();
    let bowl = |x: f32, z: f32| 0.14 * (x * x + z * z);
    let cases: [(&str, Shape); 4] = [
        ("V-shaped dip", surface_mesh(v_dip, 0.25, 0.0)),
        ("bowl", surface_mesh(bowl, 0.5, 0.0)),
        ("jittered bowl", surface_mesh(bowl, 0.5, 0.1)),
        ("bumps", surface_mesh(bumps, 0.5, 0.1)),
    ];
    for (name, mesh) in cases {
        for (k, yaw) in [0.0f32, 0.4, 0.785, 1.3].into_iter().enumerate() {
            let shift = 0.13 * k as f32;
            let tilt = Quat::from_rotation_x(0.05 * k as f32);
            for (x, z) in [
                (0.03 + shift, 0.1 + 0.5 * shift),
                (1.1 - shift, -0.7 + shift),
            ] {
                let worst = worst_rim_depth(mesh.clone(), x, z, Quat::from_rotation_y(yaw) * tilt);
                assert!(
                    worst <= RIM_DEPTH,
                    "{name}, yaw {yaw}, at ({x}, {z}): a rim went {worst} m deep"
                );
            }
        }
    }
}
