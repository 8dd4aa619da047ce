//! Mass properties of every shape against closed forms or an independent integration.
//!
//! Tolerances: the engine computes in f32, whose relative rounding is about 6e-8 per operation;
//! a few dozen operations stay below 1e-5 relative, which is the bound used here unless stated.

use rebond::internals::math::{parallel_axis_shift, rotate_tensor};
use rebond::shape::CompoundChild;
use rebond::{BodyDesc, MassProperties, Mat3, Pose, Quat, Shape, Vec3, World, WorldSettings};

const RELATIVE: f32 = 1.0e-5;

fn assert_close(actual: f32, expected: f32, relative: f32, what: &str) {
    let scale = expected.abs().max(1.0e-6);
    assert!(
        (actual - expected).abs() <= relative * scale,
        "{what}: got {actual}, expected {expected}"
    );
}

fn assert_matrix_close(actual: Mat3, expected: Mat3, relative: f32, what: &str) {
    let scale = expected
        .to_cols_array()
        .iter()
        .fold(0.0f32, |m, v| m.max(v.abs()));
    for (index, (a, e)) in actual
        .to_cols_array()
        .iter()
        .zip(expected.to_cols_array())
        .enumerate()
    {
        assert!(
            (a - e).abs() <= relative * scale,
            "{what}[{index}]: got {actual:?}, expected {expected:?}"
        );
    }
}

/// Integrates a solid of revolution about Y slice by slice (composite Simpson in f64 on pieces
/// where the slice radius is smooth), independently of the engine's closed forms. A slice at
/// height y of radius ρ has area πρ², axial moment πρ⁴/2 and transverse moment y²πρ² + πρ⁴/4.
/// Returns (volume, transverse inertia, axial inertia) for unit density.
fn revolve(pieces: &[(f64, f64)], radius_squared: impl Fn(f64) -> f64) -> (f64, f64, f64) {
    let slices = 2000;
    let mut totals = (0.0, 0.0, 0.0);
    for &(start, end) in pieces {
        let step = (end - start) / slices as f64;
        for index in 0..=slices {
            let y = start + step * index as f64;
            let weight = if index == 0 || index == slices {
                1.0
            } else if index % 2 == 1 {
                4.0
            } else {
                2.0
            } * step
                / 3.0;
            let rho2 = radius_squared(y).max(0.0);
            let area = std::f64::consts::PI * rho2;
            totals.0 += weight * area;
            totals.1 += weight * (y * y * area + area * rho2 / 4.0);
            totals.2 += weight * area * rho2 / 2.0;
        }
    }
    totals
}

fn check_revolved(properties: MassProperties, density: f32, expected: (f64, f64, f64)) {
    let density = density as f64;
    assert_close(
        properties.mass,
        (expected.0 * density) as f32,
        RELATIVE,
        "mass",
    );
    let inertia = properties.inertia;
    assert_close(
        inertia.x_axis.x,
        (expected.1 * density) as f32,
        RELATIVE,
        "Ixx",
    );
    assert_close(
        inertia.z_axis.z,
        (expected.1 * density) as f32,
        RELATIVE,
        "Izz",
    );
    assert_close(
        inertia.y_axis.y,
        (expected.2 * density) as f32,
        RELATIVE,
        "Iyy",
    );
    assert_eq!(properties.center_of_mass, Vec3::ZERO);
}

#[test]
fn sphere_matches_closed_form_and_slice_integration() {
    let properties = Shape::sphere(0.7).unwrap().mass_properties(1200.0).unwrap();
    let mass = 1200.0 * 4.0 / 3.0 * std::f32::consts::PI * 0.343;
    assert_close(properties.mass, mass, RELATIVE, "mass");
    assert_matrix_close(
        properties.inertia,
        Mat3::from_diagonal(Vec3::splat(0.4 * mass * 0.49)),
        RELATIVE,
        "inertia",
    );
    let r = 0.7f64;
    check_revolved(properties, 1200.0, revolve(&[(-r, r)], |y| r * r - y * y));
}

#[test]
fn box_matches_closed_form() {
    let half = Vec3::new(0.5, 1.0, 2.0);
    let properties = Shape::cuboid(half).unwrap().mass_properties(10.0).unwrap();
    let mass = 10.0 * 1.0 * 2.0 * 4.0;
    assert_close(properties.mass, mass, RELATIVE, "mass");
    // Full sides a, b, c: Ixx = m (b² + c²) / 12.
    let (a, b, c) = (1.0, 2.0, 4.0);
    let expected =
        Mat3::from_diagonal(mass / 12.0 * Vec3::new(b * b + c * c, a * a + c * c, a * a + b * b));
    assert_matrix_close(properties.inertia, expected, RELATIVE, "inertia");
}

#[test]
fn capsule_matches_slice_integration() {
    let (r, h) = (0.3f64, 0.8f64);
    let properties = Shape::capsule(r as f32, h as f32)
        .unwrap()
        .mass_properties(500.0)
        .unwrap();
    let cap = |y: f64| r * r - (y.abs() - h).powi(2);
    let expected = revolve(&[(-h - r, -h), (-h, h), (h, h + r)], |y| {
        if y.abs() <= h {
            r * r
        } else {
            cap(y)
        }
    });
    check_revolved(properties, 500.0, expected);
}

#[test]
fn cylinder_matches_closed_form_and_slice_integration() {
    let (r, h) = (0.4f32, 1.1f32);
    let properties = Shape::cylinder(r, h).unwrap().mass_properties(2.0).unwrap();
    let mass = 2.0 * std::f32::consts::PI * r * r * 2.0 * h;
    assert_close(properties.mass, mass, RELATIVE, "mass");
    // Height L = 2h: Ixx = m (3r² + L²) / 12, Iyy = m r² / 2.
    let length = 2.0 * h;
    assert_close(
        properties.inertia.x_axis.x,
        mass * (3.0 * r * r + length * length) / 12.0,
        RELATIVE,
        "Ixx",
    );
    assert_close(
        properties.inertia.y_axis.y,
        0.5 * mass * r * r,
        RELATIVE,
        "Iyy",
    );
    let (r, h) = (r as f64, h as f64);
    check_revolved(properties, 2.0, revolve(&[(-h, h)], |_| r * r));
}

#[test]
fn compound_of_two_boxes_follows_the_parallel_axis_theorem() {
    let half = Vec3::new(0.5, 0.25, 0.5);
    let density = 300.0;
    let offset = Vec3::new(1.0, 2.0, -0.5);
    let compound = Shape::compound(vec![
        CompoundChild::new(Shape::cuboid(half).unwrap(), Pose::from_position(offset)),
        CompoundChild::new(Shape::cuboid(half).unwrap(), Pose::from_position(-offset)),
    ])
    .unwrap();
    let single = Shape::cuboid(half)
        .unwrap()
        .mass_properties(density)
        .unwrap();
    let properties = compound.mass_properties(density).unwrap();
    assert_close(properties.mass, 2.0 * single.mass, RELATIVE, "mass");
    assert!(properties.center_of_mass.length() < 1.0e-6);
    // Each box sits at distance d from the common centre: I = Σ (I_c + m (|d|² 1 − d dᵀ)).
    let expected = 2.0 * single.inertia + 2.0 * parallel_axis_shift(single.mass, offset);
    assert_matrix_close(properties.inertia, expected, RELATIVE, "inertia");
    // The product of inertia −m Σ dx·dy must appear off the diagonal.
    assert_close(
        properties.inertia.x_axis.y,
        -2.0 * single.mass * offset.x * offset.y,
        RELATIVE,
        "Ixy",
    );
}

#[test]
fn rotated_compound_child_rotates_its_inertia() {
    let half = Vec3::new(0.2, 0.6, 1.0);
    let rotation = Quat::from_axis_angle(Vec3::new(1.0, 1.0, 0.0).normalize(), 0.7);
    let compound = Shape::compound(vec![CompoundChild::new(
        Shape::cuboid(half).unwrap(),
        Pose::new(Vec3::new(0.0, 3.0, 0.0), rotation),
    )])
    .unwrap();
    let properties = compound.mass_properties(1.0).unwrap();
    let single = Shape::cuboid(half).unwrap().mass_properties(1.0).unwrap();
    assert_close(properties.center_of_mass.y, 3.0, RELATIVE, "centre");
    assert_matrix_close(
        properties.inertia,
        rotate_tensor(rotation, single.inertia),
        RELATIVE,
        "inertia",
    );
}

#[test]
fn given_mass_scales_inertia() {
    let shape = Shape::capsule(0.25, 0.5).unwrap();
    let by_density = shape.mass_properties(1000.0).unwrap();
    let mut world = World::new(WorldSettings::default()).unwrap();
    let handle = world.add_body(BodyDesc::dynamic(shape).mass(3.0)).unwrap();
    let body = world.body(handle).unwrap();
    assert_close(body.mass(), 3.0, RELATIVE, "mass");
    let scale = 3.0 / by_density.mass;
    assert_matrix_close(
        body.local_inertia(),
        by_density.inertia * scale,
        RELATIVE,
        "inertia",
    );
}

#[test]
fn centre_of_mass_off_the_origin_is_integrated_and_the_origin_reported() {
    // A compound whose mass sits 1 m along +X of the body origin, spinning about its centre of
    // mass: the centre stays put while the origin circles it at 1 m.
    let compound = Shape::compound(vec![CompoundChild::new(
        Shape::sphere(0.5).unwrap(),
        Pose::from_position(Vec3::new(1.0, 0.0, 0.0)),
    )])
    .unwrap();
    let settings = WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    };
    let mut world = World::new(settings).unwrap();
    let handle = world
        .add_body(
            BodyDesc::dynamic(compound)
                .position(Vec3::new(5.0, 0.0, 0.0))
                .angular_velocity(Vec3::new(0.0, std::f32::consts::PI, 0.0)),
        )
        .unwrap();
    assert_eq!(
        world.body(handle).unwrap().center_of_mass(),
        Vec3::new(6.0, 0.0, 0.0)
    );
    for _ in 0..60 {
        world.step(1.0 / 60.0).unwrap();
    }
    let body = world.body(handle).unwrap();
    // Half a turn in one second: the centre is unchanged, the origin is now on its +X side.
    assert!((body.center_of_mass() - Vec3::new(6.0, 0.0, 0.0)).length() < 1.0e-4);
    assert!(
        (body.position() - Vec3::new(7.0, 0.0, 0.0)).length() < 1.0e-3,
        "origin at {}",
        body.position()
    );
}

#[test]
fn set_mass_scales_inertia_and_the_response_to_forces() {
    // A box made 4 times heavier: its inertia scales by 4 (I = m (b² + c²) / 12 keeps its
    // shape), so one step of the same force and torque changes its velocities a quarter as much.
    let settings = WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    };
    let mut world = World::new(settings).unwrap();
    let shape = Shape::cuboid(Vec3::new(0.5, 0.25, 0.125)).unwrap();
    let handle = world.add_body(BodyDesc::dynamic(shape).mass(2.0)).unwrap();
    let before = world.body(handle).unwrap().local_inertia();
    world.body_mut(handle).unwrap().set_mass(8.0).unwrap();
    let body = world.body(handle).unwrap();
    assert_close(body.mass(), 8.0, RELATIVE, "mass");
    assert_matrix_close(body.local_inertia(), before * 4.0, RELATIVE, "inertia");
    assert_matrix_close(
        body.world_inverse_inertia(),
        before.inverse() * 0.25,
        RELATIVE,
        "inverse inertia",
    );
    let dt = 1.0 / 60.0;
    let body = world.body_mut(handle).unwrap();
    body.apply_force(Vec3::new(16.0, 0.0, 0.0)).unwrap();
    body.apply_torque(Vec3::new(0.0, 0.0, 1.0)).unwrap();
    world.step(dt).unwrap();
    let body = world.body(handle).unwrap();
    // Δv = F dt / m and Δω = τ dt / I_zz with I_zz = m (1² + 0.5²) / 12 for the 1 × 0.5 × 0.25
    // box: a few f32 roundings over 8 substeps, within RELATIVE.
    assert_close(body.linear_velocity().x, 16.0 * dt / 8.0, RELATIVE, "vx");
    let inertia_z = 8.0 * (1.0 + 0.25) / 12.0;
    assert_close(body.angular_velocity().z, dt / inertia_z, RELATIVE, "wz");
}

#[test]
fn set_mass_refuses_bad_masses_and_leaves_static_bodies() {
    let mut world = World::new(WorldSettings::default()).unwrap();
    let shape = Shape::sphere(0.5).unwrap();
    let ball = world
        .add_body(BodyDesc::dynamic(shape.clone()).mass(1.0))
        .unwrap();
    let wall = world.add_body(BodyDesc::static_body(shape)).unwrap();
    for bad in [0.0, -1.0, f32::NAN, 1.0e10] {
        let error = world.body_mut(ball).unwrap().set_mass(bad).unwrap_err();
        assert!(error.to_string().starts_with("mass"), "{error}");
        assert_eq!(world.body(ball).unwrap().mass(), 1.0);
    }
    world.body_mut(wall).unwrap().set_mass(5.0).unwrap();
    assert_eq!(world.body(wall).unwrap().mass(), 0.0);
    assert_eq!(world.body(wall).unwrap().inverse_mass(), 0.0);
}
