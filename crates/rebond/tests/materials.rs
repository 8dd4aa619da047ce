//! Surface materials on contacts: the world's combine rules, a compound child's own friction, the
//! restitution threshold.

mod common;

use common::{add_ground, add_incline, apex_after_bounce, run, unit_box, world, DT, G};
use rebond::scene::Scene;
use rebond::{BodyDesc, CombineRule, CompoundChild, Pose, Quat, Shape, Vec3, World, WorldSettings};

/// A sled on a 20° incline of friction 0.5: a deck of friction 1 riding on two runners, with
/// `runner_friction` their own (`None`: the body's). Returns its acceleration down the slope,
/// m/s², measured over one second after half a second of settling.
fn sled_acceleration(runner_friction: Option<f32>) -> f32 {
    let angle = 20.0f32.to_radians();
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    add_incline(&mut world, angle, 0.5);
    let runner = |z: f32| {
        let child = CompoundChild::new(
            Shape::cuboid(Vec3::new(0.5, 0.05, 0.05)).unwrap(),
            Pose::from_position(Vec3::new(0.0, 0.0, z)),
        );
        match runner_friction {
            Some(friction) => child.friction(friction),
            None => child,
        }
    };
    let deck = CompoundChild::new(
        Shape::cuboid(Vec3::new(0.5, 0.1, 0.3)).unwrap(),
        Pose::from_position(Vec3::new(0.0, 0.2, 0.0)),
    );
    let rotation = Quat::from_rotation_z(angle);
    let sled = world
        .add_body(
            BodyDesc::dynamic(Shape::compound(vec![runner(-0.25), runner(0.25), deck]).unwrap())
                .position(rotation * Vec3::new(0.0, 0.05, 0.0))
                .rotation(rotation)
                .friction(1.0),
        )
        .unwrap();
    run(&mut world, 30);
    let early = world.body(sled).unwrap().linear_velocity();
    run(&mut world, 60);
    let late = world.body(sled).unwrap().linear_velocity();
    (late - early).dot(rotation * Vec3::NEG_X) / (60.0 * DT)
}

#[test]
fn a_sled_on_frictionless_runners_slides_at_g_sin_theta_although_its_body_has_friction_one() {
    // Only the runners touch the incline, and √(0 · 0.5) = 0: no friction at all, so the sled
    // accelerates at g sin θ. Tolerance 2 %, as for the box sliding down an incline: the
    // integration is exact for a constant force; what remains is the contacts settling.
    let expected = G * 20.0f32.to_radians().sin();
    let measured = sled_acceleration(Some(0.0));
    assert!(
        (measured - expected).abs() <= 0.02 * expected,
        "slid at {measured} m/s², expected {expected}"
    );
    // With the body's friction on the runners, μ = √(1 · 0.5) ≈ 0.71 > tan 20° ≈ 0.36: it holds.
    let held = sled_acceleration(None);
    assert!(
        held.abs() < 1.0e-3,
        "the sled with rough runners moved at {held} m/s²"
    );
}

/// Steps of the bounce scenes, s: short, so that the approach speed the bounce reverses (the one
/// at the start of the landing step) is within `g dt` = 0.008 m/s of the impact speed.
const BOUNCE_DT: f32 = 1.0 / 1200.0;

/// Drops a ball of radius 0.5 and restitution 1 on a ground of restitution 0 from `height`
/// (gap below the ball) in a scene with `threshold` as its `restitution_threshold` (`None`: the
/// default), and returns the highest its bottom rises after the first bounce.
fn rebound_height(height: f32, threshold: Option<f32>) -> f32 {
    let threshold = threshold.map_or(String::new(), |value| {
        format!(r#""restitution_threshold": {value},"#)
    });
    let json = format!(
        r#"{{ {threshold} "timestep": {BOUNCE_DT}, "bodies": [
            {{"name": "ground", "type": "static", "position": [0, -0.5, 0],
              "shape": {{"type": "box", "half_extents": [5, 0.5, 5]}}}},
            {{"name": "ball", "position": [0, {y}, 0], "restitution": 1,
              "shape": {{"type": "sphere", "radius": 0.5}}}}
        ]}}"#,
        y = 0.5 + height
    );
    let mut scene = Scene::from_json(json.as_bytes()).unwrap();
    let ball = scene.body_handle("ball").unwrap();
    apex_after_bounce(1200, || {
        scene.step().unwrap();
        let body = scene.world().body(ball).unwrap();
        (body.position().y - 0.5, body.linear_velocity().y)
    })
}

#[test]
fn with_restitution_threshold_zero_a_slow_elastic_ball_bounces_back_to_its_height() {
    let height = 0.04;
    let impact_speed = (2.0 * G * height).sqrt();
    // It lands at 0.89 m/s, below the default threshold of 1 m/s: it stays down.
    let default = rebound_height(height, None);
    assert!(
        default < 1.0e-3,
        "bounced to {default} m past the default threshold"
    );
    // With e = 1 it leaves at the approach speed of the landing step's start, slower than the
    // impact speed by at most g dt: the height falls short by at most 2 g dt / v (1.8 %); the
    // apex is sampled once a step (at most ½ g dt² = 0.014 mm lower).
    let measured = rebound_height(height, Some(0.0));
    let shortfall = 2.0 * G * BOUNCE_DT / impact_speed;
    assert!(
        measured <= height + 1.0e-4 && measured >= height * (1.0 - shortfall) - 1.0e-4,
        "bounced to {measured} m, expected {height} m less at most {shortfall:.3} of it"
    );
}

#[test]
fn contacts_carry_the_material_the_world_rules_combine() {
    for (friction_rule, restitution_rule, friction, restitution) in [
        (CombineRule::GeometricMean, CombineRule::Max, 0.4, 0.6),
        (CombineRule::Average, CombineRule::Min, 0.5, 0.2),
        (CombineRule::Multiply, CombineRule::Average, 0.16, 0.4),
    ] {
        let mut world = World::new(WorldSettings {
            friction_combine: friction_rule,
            restitution_combine: restitution_rule,
            ..WorldSettings::default()
        })
        .unwrap();
        let ground = add_ground(&mut world, 0.8);
        world
            .body_mut(ground)
            .unwrap()
            .set_restitution(0.2)
            .unwrap();
        world
            .add_body(
                unit_box(Vec3::new(0.0, 0.5, 0.0))
                    .friction(0.2)
                    .restitution(0.6),
            )
            .unwrap();
        run(&mut world, 2);
        let contact = &world.contacts()[0];
        assert!(
            (contact.friction() - friction).abs() < 1e-6,
            "{friction_rule:?}"
        );
        assert!(
            (contact.restitution() - restitution).abs() < 1e-6,
            "{restitution_rule:?}"
        );
    }
}
