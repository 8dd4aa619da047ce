//! Contact response against closed forms, part two: spinning (twist) friction from the contact
//! patch, restitution at every speed and through rows of touching bodies.

mod common;

use common::{add_ground, scene_path, world, DT, G};
use rebond::scene::Scene;
use rebond::{BodyDesc, BodyHandle, Shape, Vec3, World, WorldSettings};

/// Friction of the body and of the ground, so the contact's combined value is the same.
const FRICTION: f32 = 0.5;

/// Spin about the vertical given to a body resting on the ground, rad/s.
const SPIN: f32 = 10.0;

/// Lets `body` settle on the ground for half a second, spins it about the vertical at
/// [`SPIN`], and returns its angular deceleration, rad/s², from the spin lost between 5 and 25
/// steps later (while it still spins: the slowest shape here stops after 40 steps).
fn spin_deceleration(desc: BodyDesc) -> f32 {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, FRICTION);
    let body = world
        .add_body(desc.friction(FRICTION).can_sleep(false))
        .unwrap();
    common::run(&mut world, 30);
    world
        .body_mut(body)
        .unwrap()
        .set_angular_velocity(Vec3::new(0.0, SPIN, 0.0))
        .unwrap();
    let spin = |world: &World| world.body(body).unwrap().angular_velocity().y;
    common::run(&mut world, 5);
    let early = spin(&world);
    common::run(&mut world, 20);
    let late = spin(&world);
    assert!(late > 0.0, "stopped within the window");
    (early - late) / (20.0 * DT)
}

/// Checks that `desc` spinning on the ground slows at `expected` rad/s², to 1 %: the twist
/// impulse sits at its limit `μ Σλ_n ⟨r⟩` all through the window and, once settled, the normal
/// impulses carry the weight exactly (measured within 1e-5 of the closed forms); the issue asks
/// for 5 %.
fn assert_spin_slows_at(desc: BodyDesc, expected: f32) {
    let measured = spin_deceleration(desc);
    assert!(
        (measured - expected).abs() < 0.01 * expected,
        "{measured} rad/s², expected {expected}"
    );
}

#[test]
fn a_cube_spinning_flat_slows_as_coulomb_friction_under_uniform_pressure_gives() {
    // Uniform pressure m g / A over the unit face: the friction torque is μ m g ⟨r⟩, with ⟨r⟩
    // the mean distance of the face from its centre, (√2 + ln(1 + √2)) / 6 = 0.3826 m, against
    // the inertia I = m (1² + 1²) / 12 = m / 6 about the vertical: α = 6 μ g ⟨r⟩ = 11.26 rad/s².
    let mean_distance = (2.0f32.sqrt() + (1.0 + 2.0f32.sqrt()).ln()) / 6.0;
    let expected = 6.0 * FRICTION * G * mean_distance;
    let desc = BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.5)).unwrap())
        .position(Vec3::new(0.0, 0.5, 0.0));
    assert_spin_slows_at(desc, expected);
}

#[test]
fn a_disc_spinning_flat_slows_as_coulomb_friction_under_uniform_pressure_gives() {
    // A cylinder of radius R on its cap: ⟨r⟩ = 2R/3 over the disc, I = m R² / 2, so
    // α = μ g (2R/3) / (R²/2) = 4 μ g / (3 R) = 13.08 rad/s² for R = 0.5 m.
    let radius = 0.5;
    let expected = 4.0 * FRICTION * G / (3.0 * radius);
    let desc = BodyDesc::dynamic(Shape::cylinder(radius, 0.25).unwrap())
        .position(Vec3::new(0.0, 0.25, 0.0));
    assert_spin_slows_at(desc, expected);
}

#[test]
fn a_sphere_spinning_on_its_point_of_contact_keeps_its_spin() {
    // A point contact has no lever arm: no friction torque about the normal. The bound, 1 % of
    // the cube's deceleration, allows for rounding only.
    let desc = BodyDesc::dynamic(Shape::sphere(0.5).unwrap()).position(Vec3::new(0.0, 0.5, 0.0));
    let measured = spin_deceleration(desc);
    assert!(measured.abs() < 0.11, "{measured} rad/s²");
}

/// A ball of radius 0.5 m and restitution `restitution` thrown down at `speed` from 1 cm above
/// the ground, with no gravity, with the restitution threshold `threshold`; returns its
/// vertical velocity a second later.
fn rebound_velocity(restitution: f32, speed: f32, threshold: f32) -> f32 {
    let mut world = world(Vec3::ZERO);
    let mut settings = *world.settings();
    settings.restitution_threshold = threshold;
    world.set_settings(settings).unwrap();
    add_ground(&mut world, 0.0);
    let ball = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(0.5).unwrap())
                .position(Vec3::new(0.0, 0.51, 0.0))
                .linear_velocity(Vec3::new(0.0, -speed, 0.0))
                .restitution(restitution)
                .can_sleep(false),
        )
        .unwrap();
    common::run(&mut world, 60);
    world.body(ball).unwrap().linear_velocity().y
}

#[test]
fn with_a_zero_threshold_every_approach_bounces_and_below_the_threshold_none_does() {
    // Without gravity the approach speed is the impact speed, so the rebound is e v exactly, up
    // to rounding (1e-3 relative).
    for speed in [0.05f32, 0.3, 2.0] {
        let rebound = rebound_velocity(0.8, speed, 0.0);
        assert!(
            (rebound - 0.8 * speed).abs() < 1e-3 * speed,
            "{speed} m/s came back at {rebound} m/s"
        );
    }
    assert!(
        rebound_velocity(0.8, 0.3, 0.5).abs() < 1e-3,
        "0.3 m/s is under a 0.5 m/s threshold"
    );
}

#[test]
fn a_box_landing_flat_bounces_straight_up_at_e_times_its_speed() {
    // Its four corners hit together: the restitution stage stops them together and bounces
    // them by e, so the box leaves at e v without turning. No gravity, so the impact speed is
    // the speed thrown; bounds for rounding (1e-3 relative, 1e-3 rad/s).
    let mut world = world(Vec3::ZERO);
    add_ground(&mut world, 0.5);
    let speed = 3.0;
    let crate_box = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.5)).unwrap())
                .position(Vec3::new(0.0, 0.55, 0.0))
                .linear_velocity(Vec3::new(0.0, -speed, 0.0))
                .restitution(0.5),
        )
        .unwrap();
    common::run(&mut world, 30);
    let body = world.body(crate_box).unwrap();
    let velocity = body.linear_velocity();
    assert!(
        (velocity.y - 0.5 * speed).abs() < 1e-3 * speed,
        "{velocity}"
    );
    assert!(
        body.angular_velocity().length() < 1e-3,
        "{}",
        body.angular_velocity()
    );
}

/// The velocities along x of a built-in cradle's five balls, `ball_0` to `ball_4`.
fn ball_velocities(scene: &Scene) -> [f32; 5] {
    std::array::from_fn(|index| {
        let ball = scene.body_handle(&format!("ball_{index}")).unwrap();
        scene.world().body(ball).unwrap().linear_velocity().x
    })
}

/// Checks a cradle's balls after the impact against the textbook answer for equal elastic balls,
/// which pass the impact on whole: `0, …, 0, v` for the incoming speed `v` along the row, all
/// the energy kept. Bounds (the issue's): last ≥ 95 % of `v`, others ≤ 5 %, energy ≥ 95 %; and
/// no energy made (0.1 % for rounding).
fn check_cradle(velocities: &[f32], incoming: f32) {
    let energy: f32 = velocities.iter().map(|v| v * v).sum::<f32>() / (incoming * incoming);
    let (last, others) = velocities.split_last().unwrap();
    assert!(*last >= 0.95 * incoming, "{velocities:?} from {incoming}");
    assert!(
        others.iter().all(|v| v.abs() <= 0.05 * incoming),
        "{velocities:?} from {incoming}"
    );
    assert!(
        (0.95..=1.001).contains(&energy),
        "kept {energy} of the energy: {velocities:?}"
    );
}

#[test]
fn an_impact_travels_down_a_row_of_touching_balls() {
    // The built-in `cradle`: five touching balls of restitution 1 in zero gravity, the first
    // moving at 1 m/s. Nothing but the contacts acts, so the answer holds at any later step.
    let mut scene = Scene::from_file(scene_path("cradle")).unwrap();
    for _ in 0..30 {
        scene.step().unwrap();
    }
    check_cradle(&ball_velocities(&scene), 1.0);
}

#[test]
fn rows_of_two_three_and_five_touching_balls_pass_the_push_through() {
    // As the built-in cradle, built here: touching balls of restitution 1, no friction, no
    // gravity, every approach bouncing (threshold 0), the first pushed at 1 m/s along the row
    // (measured: the last leaves at 1.0, 1.00004 and 1.0004 m/s, the others at 0).
    for count in [2, 3, 5] {
        let mut world = World::new(WorldSettings {
            gravity: Vec3::ZERO,
            restitution_threshold: 0.0,
            ..WorldSettings::default()
        })
        .unwrap();
        let balls: Vec<BodyHandle> = (0..count)
            .map(|index| {
                let speed = if index == 0 { 1.0 } else { 0.0 };
                let ball = BodyDesc::dynamic(Shape::sphere(0.5).unwrap())
                    .position(Vec3::new(index as f32, 0.0, 0.0))
                    .linear_velocity(Vec3::new(speed, 0.0, 0.0))
                    .restitution(1.0)
                    .friction(0.0);
                world.add_body(ball).unwrap()
            })
            .collect();
        common::run(&mut world, 30);
        let velocities: Vec<f32> = balls
            .iter()
            .map(|&ball| world.body(ball).unwrap().linear_velocity().x)
            .collect();
        check_cradle(&velocities, 1.0);
    }
}

#[test]
fn an_impact_travels_down_a_row_of_hanging_balls() {
    // The built-in `cradle_hanging`: the first ball, on strings 2.5 m long, swings down from
    // 40° and hits the row at √(2 g L (1 − cos 40°)) = 3.39 m/s. Read at the step the last
    // ball leaves, when the strings hang straight down and pull along y only; the incoming
    // speed is the first ball's fastest. (The impact may take two steps to cross the row: a
    // contact that did not push in the step of the impact passes it on in the next.)
    let mut scene = Scene::from_file(scene_path("cradle_hanging")).unwrap();
    let mut incoming = 0.0;
    for _ in 0..120 {
        scene.step().unwrap();
        let velocities = ball_velocities(&scene);
        if velocities[4] > 0.5 * incoming && incoming > 1.0 {
            check_cradle(&velocities, incoming);
            return;
        }
        incoming = velocities[0].max(incoming);
    }
    panic!("the last ball never left");
}

/// The largest upward speed of `body` over `steps` steps of `world`, m/s.
fn largest_upward_speed(world: &mut World, body: BodyHandle, steps: usize) -> f32 {
    let mut upward = 0.0f32;
    for _ in 0..steps {
        world.step(DT).unwrap();
        upward = upward.max(world.body(body).unwrap().linear_velocity().y);
    }
    upward
}

#[test]
fn resting_and_landing_contacts_of_restitution_zero_never_bounce() {
    // Restitution 0, the default: a box resting on the ground and one dropped 1 m onto it
    // (landing at 4.4 m/s), sleeping off, over 3 s.
    for drop in [0.0f32, 1.0] {
        let mut world = world(Vec3::new(0.0, -G, 0.0));
        add_ground(&mut world, FRICTION);
        let crate_box = world
            .add_body(
                BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.5)).unwrap())
                    .position(Vec3::new(0.0, 0.5 + drop, 0.0))
                    .can_sleep(false),
            )
            .unwrap();
        let upward = largest_upward_speed(&mut world, crate_box, 180);
        // Below 1 mm/s: a bounce of 2e-4 of the landing speed would show (measured 0 exactly,
        // resting and landing).
        assert!(
            upward < 1.0e-3,
            "dropped {drop} m: the box moved up at {upward} m/s"
        );
    }
}

#[test]
fn a_column_of_elastic_balls_struck_from_above_sends_the_striker_back() {
    // Three balls of restitution 1 rest on each other on the ground, and a fourth falls on the
    // top one. The ground's restitution is 0, but the pair's is the larger, 1. Equal elastic
    // balls pass the blow down the column as a cradle does, the ground sends it back (an
    // immovable body, e = 1) and the column passes it up again: the striker leaves upward at
    // the speed it came in, the column stays at rest.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, FRICTION);
    let ball = |height: f32| {
        BodyDesc::dynamic(Shape::sphere(0.5).unwrap())
            .position(Vec3::new(0.0, height, 0.0))
            .restitution(1.0)
            .friction(0.0)
            .can_sleep(false)
    };
    let column: Vec<BodyHandle> = (0..3)
        .map(|index| world.add_body(ball(0.5 + index as f32)).unwrap())
        .collect();
    common::run(&mut world, 60);
    let striker = world
        .add_body(ball(4.0).linear_velocity(Vec3::new(0.0, -4.0, 0.0)))
        .unwrap();
    // Read at the step the striker first moves up; the incoming speed is its fastest before.
    let mut incoming = 0.0f32;
    for _ in 0..60 {
        world.step(DT).unwrap();
        let striker_velocity = world.body(striker).unwrap().linear_velocity().y;
        if striker_velocity > 0.0 {
            // The cradle's bounds: the striker leaves with at least 95 % of the incoming speed,
            // the column's balls keep under 5 % of it. And no energy is made: the striker
            // leaves no faster than it came, and no column ball moves faster than 1 mm/s, but for
            // what the collisions leave when they stop, under 1e-4 m/s a contact in each of the
            // two outcomes that make the bounce (measured: 4.9813 m/s from 4.9810 m/s, column
            // balls at 0.07 and 0.16 mm/s; with the collisions cut off too early, 5.21 m/s).
            assert!(
                striker_velocity >= 0.95 * incoming && striker_velocity <= incoming + 1e-3,
                "the striker left at {striker_velocity} m/s from {incoming} m/s"
            );
            for &ball in &column {
                let velocity = world.body(ball).unwrap().linear_velocity();
                assert!(
                    velocity.length() <= 1e-3,
                    "a column ball moves at {velocity} after a {incoming} m/s blow"
                );
            }
            return;
        }
        incoming = incoming.max(-striker_velocity);
    }
    panic!("the striker never came back up");
}
