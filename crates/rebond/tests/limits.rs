//! The engine's numeric limits (`rebond::limits`, `docs/limits.md`): past each one a value is
//! refused with its field named and the world left as it was; at each one the simulation is
//! right: huge boxes hold bodies, bodies far from the origin rest, the longest step and the
//! strongest gravity hold a resting box, the smallest shapes rest.

mod common;

use common::{world, DT, G};
use rebond::limits::{
    MAX_ANGULAR_SPEED, MAX_COORDINATE, MAX_FORCE, MAX_GRAVITY, MAX_INERTIA_RATIO, MAX_MASS,
    MAX_SIZE, MAX_SPEED, MAX_TIMESTEP, MIN_MASS, MIN_SIZE, MIN_TIMESTEP,
};
use rebond::shape::{ConvexHull, TriMesh};
use rebond::{
    BodyDesc, CompoundChild, ErrorKind, JointDesc, Pose, Quat, Result, Shape, Vec3, World,
    WorldSettings,
};

fn refused<T: std::fmt::Debug>(result: Result<T>) -> String {
    let error = result.expect_err("a value past a limit must be refused");
    assert!(
        matches!(
            error.kind,
            ErrorKind::TooLarge { .. } | ErrorKind::OutOfRange { .. }
        ),
        "{error}"
    );
    error.field
}

fn unit_box() -> Shape {
    Shape::cuboid(Vec3::splat(0.5)).unwrap()
}

#[test]
fn values_past_the_limits_are_refused_naming_the_field() {
    let (big, small) = (2.0 * MAX_SIZE, 0.5 * MIN_SIZE);
    assert_eq!(refused(Shape::sphere(big)), "radius");
    assert_eq!(refused(Shape::sphere(small)), "radius");
    assert_eq!(refused(Shape::capsule(1.0, big)), "half_height");
    assert_eq!(refused(Shape::cylinder(small, 1.0)), "radius");
    assert_eq!(
        refused(Shape::cuboid(Vec3::new(1.0, 1e20, 1.0))),
        "half_extents[1]"
    );
    let mut corners: Vec<Vec3> = (0..8)
        .map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, (i >> 2) as f32))
        .collect();
    corners[5].x = big;
    assert_eq!(refused(ConvexHull::new(&corners)), "points[5]");
    let vertices = vec![Vec3::ZERO, Vec3::X, Vec3::new(0.0, 0.0, big)];
    assert_eq!(refused(TriMesh::new(vertices, &[[0, 1, 2]])), "vertices[2]");
    let child = CompoundChild::new(unit_box(), Pose::from_position(Vec3::new(0.0, big, 0.0)));
    assert_eq!(
        refused(Shape::compound(vec![child])),
        "children[0].position"
    );
    assert_eq!(
        refused(Shape::heightfield(
            &[vec![0.0, 0.0], vec![0.0, 1e6]],
            Vec3::ONE
        )),
        "heights[1][1]"
    );

    let mut world = World::new(WorldSettings::default()).unwrap();
    let far = Vec3::new(0.0, 0.0, 1.5 * MAX_COORDINATE);
    let past_body = [
        (BodyDesc::dynamic(unit_box()).position(far), "position"),
        (
            BodyDesc::dynamic(unit_box()).linear_velocity(Vec3::splat(1e30)),
            "linear_velocity",
        ),
        (
            BodyDesc::kinematic(unit_box()).linear_velocity(Vec3::X * 2.0 * MAX_SPEED),
            "linear_velocity",
        ),
        (
            BodyDesc::dynamic(unit_box()).angular_velocity(Vec3::Y * 2.0 * MAX_ANGULAR_SPEED),
            "angular_velocity",
        ),
        (BodyDesc::dynamic(unit_box()).mass(2.0 * MAX_MASS), "mass"),
        (BodyDesc::dynamic(unit_box()).mass(0.5 * MIN_MASS), "mass"),
        // A unit cube of 2e9 kg/m³, and a 1 mm cube of 1e-4 kg/m³.
        (BodyDesc::dynamic(unit_box()).density(2e9), "density"),
        (
            BodyDesc::dynamic(Shape::cuboid(Vec3::splat(MIN_SIZE)).unwrap()).density(1e-4),
            "density",
        ),
        (
            BodyDesc::dynamic(unit_box()).constant_force(Vec3::Y * 2.0 * MAX_FORCE),
            "force",
        ),
    ];
    for (desc, field) in past_body {
        assert_eq!(refused(world.add_body(desc)), field);
    }
    assert_eq!(world.bodies().count(), 0);

    let ball = world
        .add_body(BodyDesc::dynamic(Shape::sphere(0.5).unwrap()))
        .unwrap();
    let before = world.clone();
    let body = world.body_mut(ball).unwrap();
    assert_eq!(refused(body.set_position(far)), "position");
    assert_eq!(
        refused(body.set_linear_velocity(Vec3::X * 1e30)),
        "linear_velocity"
    );
    assert_eq!(
        refused(body.apply_impulse(Vec3::X * 2.0 * MAX_FORCE)),
        "impulse"
    );
    assert_eq!(
        refused(body.apply_torque(Vec3::X * 2.0 * MAX_FORCE)),
        "torque"
    );
    assert_eq!(
        refused(world.add_joint(JointDesc::ball(None, ball, far))),
        "anchor"
    );
    assert_eq!(refused(world.step(1e30)), "dt");
    assert_eq!(refused(world.step(0.5 * MIN_TIMESTEP)), "dt");
    assert_eq!(
        world.body(ball).unwrap().pose(),
        before.body(ball).unwrap().pose()
    );

    let settings = |gravity: Vec3, max_linear_speed: f32| WorldSettings {
        gravity,
        max_linear_speed,
        ..WorldSettings::default()
    };
    let past_settings = [
        (settings(Vec3::Y * -1e30, 1000.0), "gravity"),
        (settings(Vec3::Y * -2.0 * MAX_GRAVITY, 1000.0), "gravity"),
        (settings(Vec3::Y * -G, 2.0 * MAX_SPEED), "max_linear_speed"),
    ];
    for (settings, field) in past_settings {
        assert_eq!(refused(World::new(settings)), field);
        assert_eq!(refused(world.set_settings(settings)), field);
    }
}

/// The worst over the last second of `seconds` with sleeping off: how far `body`'s height
/// strayed from `rest` and its fastest point speed.
fn settle(
    world: &mut World,
    body: rebond::BodyHandle,
    dt: f32,
    seconds: f32,
    rest: f32,
) -> (f32, f32) {
    let steps = (seconds / dt).round() as usize;
    let window = (1.0 / dt).round() as usize;
    let (mut height_error, mut speed) = (0.0f32, 0.0f32);
    for step in 0..steps {
        world.step(dt).unwrap();
        if step + window >= steps {
            let state = world.body(body).unwrap();
            height_error = height_error.max((state.position().y - rest).abs());
            speed = speed.max(state.max_point_speed());
        }
    }
    (height_error, speed)
}

/// Each convex kind, with the height of its origin when it rests on y = 0 and the rotation it
/// rests in.
fn resting_shapes() -> Vec<(&'static str, Shape, f32, Quat)> {
    let tetrahedron = [
        Vec3::new(-0.5, -0.5, -0.5),
        Vec3::new(0.5, -0.5, -0.5),
        Vec3::new(0.0, -0.5, 0.5),
        Vec3::new(0.0, 0.5, 0.0),
    ];
    vec![
        ("sphere", Shape::sphere(0.5).unwrap(), 0.5, Quat::IDENTITY),
        ("box", unit_box(), 0.5, Quat::IDENTITY),
        (
            "capsule",
            Shape::capsule(0.3, 0.4).unwrap(),
            0.3,
            Quat::from_rotation_z(std::f32::consts::FRAC_PI_2),
        ),
        (
            "cylinder",
            Shape::cylinder(0.5, 0.5).unwrap(),
            0.5,
            Quat::IDENTITY,
        ),
        (
            "hull",
            Shape::convex_hull(&tetrahedron).unwrap(),
            0.5,
            Quat::IDENTITY,
        ),
    ]
}

/// Drops each convex kind 0.2 m onto a static box of half extents `ground` whose top face is at
/// height `origin.y`, placed about `origin`; returns the worst height error and speed at rest.
fn rest_on_box(ground: Vec3, origin: Vec3) -> Vec<(&'static str, f32, f32)> {
    resting_shapes()
        .into_iter()
        .map(|(name, shape, rest, rotation)| {
            let mut world = world(Vec3::new(0.0, -G, 0.0));
            world
                .add_body(
                    BodyDesc::static_body(Shape::cuboid(ground).unwrap())
                        .position(origin - Vec3::Y * ground.y),
                )
                .unwrap();
            let body = world
                .add_body(
                    BodyDesc::dynamic(shape)
                        .position(origin + Vec3::new(0.3, rest + 0.2, 0.2))
                        .rotation(rotation)
                        .can_sleep(false),
                )
                .unwrap();
            let (height, speed) = settle(&mut world, body, DT, 5.0, origin.y + rest);
            (name, height, speed)
        })
        .collect()
}

#[test]
fn a_box_of_the_largest_size_holds_every_shape_at_rest() {
    // A resting contact sinks g/ω² = 9.81 / (2π·120 Hz)² = 17 µm; 0.1 mm and 1 mm/s leave room
    // for rounding and nothing for a tipped or jittering body.
    for (name, height, speed) in rest_on_box(Vec3::new(MAX_SIZE, 0.5, MAX_SIZE), Vec3::ZERO) {
        assert!(height < 1e-4, "{name}: height off by {height} m");
        assert!(speed < 1e-3, "{name}: still moving at {speed} m/s");
    }
}

#[test]
fn bodies_at_the_largest_coordinates_rest() {
    // At 1e4 m a coordinate is resolved to 2^-10 m (0.98 mm): heights within two of those, and
    // slower than the engine's own sleep speed (0.05 m/s), which a jump of one unit of rounding
    // per substep (0.47 m/s) would exceed.
    let origin = Vec3::splat(MAX_COORDINATE - 2.0);
    for (name, height, speed) in rest_on_box(Vec3::new(50.0, 0.5, 50.0), origin) {
        assert!(height < 2e-3, "{name}: height off by {height} m");
        assert!(speed < 0.05, "{name}: still moving at {speed} m/s");
    }
}

/// A unit box resting on the ground in `world`: worst height error and speed over the last
/// second of 5 s of steps of `dt`.
fn box_at_rest(mut world: World, dt: f32) -> (f32, f32) {
    common::add_ground(&mut world, 0.5);
    let body = world
        .add_body(common::unit_box(Vec3::new(0.0, 0.5, 0.0)).can_sleep(false))
        .unwrap();
    settle(&mut world, body, dt, 5.0, 0.5)
}

#[test]
fn the_longest_step_and_the_strongest_gravity_hold_a_box_at_rest() {
    // At 0.1 s and 8 substeps the contact stiffness is capped at a quarter of the substep rate,
    // 20 Hz: it sinks g/ω² = 0.6 mm. Under 1,000 m/s² at 120 Hz it sinks 1.8 mm.
    let (height, speed) = box_at_rest(world(Vec3::new(0.0, -G, 0.0)), MAX_TIMESTEP);
    assert!(height < 1e-3 && speed < 1e-3, "{height} m, {speed} m/s");
    let (height, speed) = box_at_rest(world(Vec3::new(0.0, -MAX_GRAVITY, 0.0)), DT);
    assert!(height < 2.5e-3 && speed < 1e-3, "{height} m, {speed} m/s");
}

#[test]
fn the_shortest_step_falls_as_semi_implicit_euler_says() {
    // v_n = −g n h and y_n = y_0 − g h² n(n+1)/2 after n substeps h: 1,000 steps of 1e-4 s
    // from y = 1, a fall of 4.9 cm. Each substep rounds v and y by at most half a unit of their
    // last place (3e-8 below 1), so 8,000 substeps stray by at most 2.4e-4 m or m/s.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let ball = world
        .add_body(BodyDesc::dynamic(Shape::sphere(0.5).unwrap()).position(Vec3::Y))
        .unwrap();
    for _ in 0..1000 {
        world.step(MIN_TIMESTEP).unwrap();
    }
    let n = 1000.0 * world.settings().substeps as f64;
    let h = f64::from(MIN_TIMESTEP) / world.settings().substeps as f64;
    let g = f64::from(G);
    let bound = n * 0.5 * f64::from(f32::EPSILON) * 0.5;
    let state = world.body(ball).unwrap();
    let velocity_error = (f64::from(state.linear_velocity().y) + g * n * h).abs();
    let height_error =
        (f64::from(state.position().y) - (1.0 - g * h * h * n * (n + 1.0) / 2.0)).abs();
    assert!(velocity_error < bound, "velocity off by {velocity_error}");
    assert!(height_error < bound, "height off by {height_error}");
}

#[test]
fn the_smallest_shapes_and_the_extreme_masses_rest() {
    // 1 mm bodies of 1 mg... 8 mg, and a 1e9 kg box with a 1 mg ball on it.
    for shape in [
        Shape::sphere(MIN_SIZE).unwrap(),
        Shape::cuboid(Vec3::splat(MIN_SIZE)).unwrap(),
    ] {
        let mut world = world(Vec3::new(0.0, -G, 0.0));
        common::add_ground(&mut world, 0.5);
        let body = world
            .add_body(
                BodyDesc::dynamic(shape)
                    .position(Vec3::Y * 3.0 * MIN_SIZE)
                    .can_sleep(false),
            )
            .unwrap();
        let (height, speed) = settle(&mut world, body, DT, 3.0, MIN_SIZE);
        assert!(height < 1e-4 && speed < 1e-3, "{height} m, {speed} m/s");
    }
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    common::add_ground(&mut world, 0.5);
    let heavy = world
        .add_body(
            common::unit_box(Vec3::Y * 0.5)
                .mass(MAX_MASS)
                .can_sleep(false),
        )
        .unwrap();
    let light = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(0.1).unwrap())
                .mass(MIN_MASS)
                .position(Vec3::Y * 1.1)
                .can_sleep(false),
        )
        .unwrap();
    let (height, speed) = settle(&mut world, light, DT, 3.0, 1.1);
    assert!(
        height < 1e-3 && speed < 1e-3,
        "light: {height} m, {speed} m/s"
    );
    let state = world.body(heavy).unwrap();
    assert!((state.position().y - 0.5).abs() < 1e-3 && state.max_point_speed() < 1e-3);
}

#[test]
fn a_body_thinner_than_the_inertia_spread_allows_has_its_moments_raised() {
    // Principal moments of a solid cylinder of radius r and length L: m r²/2 about its axis,
    // m (3r² + L²)/12 across it. A 4 m rod 2 cm thick spreads them 2.7e4 apart and keeps them;
    // the fuzzer's 1,820 m rod 12.5 cm thick spreads them 1.4e8 apart, and has each raised by
    // ε = tr I / MAX_INERTIA_RATIO: (λ + ε)/ε with tr I ≈ 2λ brings the spread to about half the
    // ratio.
    let moments = |radius: f32, half_height: f32| {
        let mut world = World::new(WorldSettings::default()).unwrap();
        let rod = Shape::cylinder(radius, half_height).unwrap();
        let body = world.add_body(BodyDesc::dynamic(rod).mass(3.0)).unwrap();
        let inertia = world.body(body).unwrap().local_inertia();
        Vec3::new(inertia.x_axis.x, inertia.y_axis.y, inertia.z_axis.z)
    };
    let (radius, length) = (0.01_f32, 4.0_f32);
    let kept = moments(radius, length / 2.0);
    let (axial, across) = (
        3.0 * radius * radius / 2.0,
        3.0 * (3.0 * radius * radius + length * length) / 12.0,
    );
    assert!((kept.y / axial - 1.0).abs() < 1e-5, "{kept}");
    assert!((kept.x / across - 1.0).abs() < 1e-5, "{kept}");
    let raised = moments(0.0625, 910.0);
    let spread = raised.max_element() / raised.min_element();
    assert!(
        (spread / (0.5 * MAX_INERTIA_RATIO) - 1.0).abs() < 1e-3,
        "{raised}: {spread}"
    );
}
