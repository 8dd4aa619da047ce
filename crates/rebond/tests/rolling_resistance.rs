//! Rolling resistance against its closed forms: a ball rolling on flat ground slows and stops
//! where a constant resisting torque says, and a ball at rest on a slope stays or rolls as the
//! slope's angle is below or above `atan c`.
//!
//! The law (`solver/rolling.rs`): a resisting torque of at most `c r N` about the contact. A solid
//! ball (`I = 2/5 m r²`) rolling without slip has angular momentum `(I + m r²) ω = 7/5 m r² ω`
//! about its contact point, where friction and the normal force have no moment; on a slope `θ`
//! gravity's moment there is `m g r sin θ` and the resisting torque's at most
//! `c r m g cos θ`. So it rolls down at `a = 5/7 g (sin θ − c cos θ)` where `tan θ > c`, rests
//! where `tan θ ≤ c`, and on flat ground slows at `5/7 c g`.

mod common;

use common::{add_ground, add_incline, world, DT, G};
use rebond::scene::Scene;
use rebond::{BodyDesc, BodyHandle, CompoundChild, Pose, Quat, Shape, Vec3, World};

const RADIUS: f32 = 0.5;

/// A ball of radius [`RADIUS`] and rolling resistance `resistance` on the ground (friction 0.8,
/// both), moving at `velocity` and turning at `spin`, sleeping off.
fn ball_on_ground(velocity: Vec3, spin: Vec3, resistance: f32) -> (World, BodyHandle) {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, 0.8);
    let ball = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(RADIUS).unwrap())
                .position(Vec3::new(0.0, RADIUS, 0.0))
                .linear_velocity(velocity)
                .angular_velocity(spin)
                .friction(0.8)
                .rolling_resistance(resistance)
                .can_sleep(false),
        )
        .unwrap();
    (world, ball)
}

#[test]
fn a_rolling_ball_slows_at_five_sevenths_c_g_and_stops_where_the_closed_form_says() {
    let (launch, resistance) = (3.0, 0.1);
    // Friction 0.8: rolling with the resistance asks `5/7 c` = 0.07 of the normal force.
    let (mut world, ball) = ball_on_ground(
        Vec3::new(launch, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -launch / RADIUS),
        resistance,
    );
    let deceleration = 5.0 / 7.0 * resistance * G;
    let stop_time = launch / deceleration;
    let stop_distance = launch * launch / (2.0 * deceleration);
    let speed = |world: &rebond::World| world.body(ball).unwrap().linear_velocity().x;
    // Measured from 0.5 s to 2.5 s, past the first contact's settling.
    for _ in 0..30 {
        world.step(DT).unwrap();
    }
    let early = speed(&world);
    for _ in 0..120 {
        world.step(DT).unwrap();
    }
    let measured = (early - speed(&world)) / (120.0 * DT);
    // 1 %: once saturated, the resisting impulse is `c r Σλ_n` in each substep, exact to
    // rounding, and friction restores the roll in the next substep; measured 0.70072 m/s² for
    // 0.70071.
    assert!(
        (measured / deceleration - 1.0).abs() <= 0.01,
        "slows at {measured} m/s², expected {deceleration}"
    );
    // It stops within a step or two of t = v₀ / a (4.28 s), and no later: then under 1 mm/s.
    let mut stopped_at = None;
    for step in 150..400 {
        world.step(DT).unwrap();
        let body = world.body(ball).unwrap();
        let moving = body.linear_velocity().length() + body.angular_velocity().length() * RADIUS;
        if stopped_at.is_none() && moving < 1.0e-3 {
            stopped_at = Some((step + 1) as f32 * DT);
        }
        if stopped_at.is_some() {
            assert!(moving < 1.0e-3, "moves again at {moving} m/s, step {step}");
        }
    }
    let stopped_at = stopped_at.expect("the ball never stopped");
    // 1 % of the time, 0.04 s: the deceleration's bound, plus a step (stops at 4.30 s, the step
    // after 4.28 s).
    assert!(
        (stopped_at - stop_time).abs() <= 0.01 * stop_time + DT,
        "stopped at {stopped_at} s, expected {stop_time} s"
    );
    let travelled = world.body(ball).unwrap().position().x;
    // 1 % of the distance (6 cm): a uniform deceleration off by 1 % moves the stop by 1 %;
    // measured 6.419 m for 6.422.
    assert!(
        (travelled / stop_distance - 1.0).abs() <= 0.01,
        "stopped after {travelled} m, expected {stop_distance} m"
    );
    // Rolling, not skidding: the roll matched the speed until the end.
    let body = world.body(ball).unwrap();
    assert!(body.angular_velocity().length() * RADIUS < 1.0e-3);
}

/// The ball's displacement after 2 s and its acceleration down the slope over the second
/// second, for a ball set at rest on a slope of `degrees` with rolling resistance `resistance`.
fn on_a_slope(degrees: f32, resistance: f32) -> (f32, f32) {
    let angle = degrees.to_radians();
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    add_incline(&mut world, angle, 0.8);
    let rotation = Quat::from_rotation_z(angle);
    let start = rotation * Vec3::new(0.0, RADIUS, 0.0);
    let ball = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(RADIUS).unwrap())
                .position(start)
                .friction(0.8)
                .rolling_resistance(resistance)
                .can_sleep(false),
        )
        .unwrap();
    let down_slope = rotation * Vec3::NEG_X;
    let speed = |world: &rebond::World| world.body(ball).unwrap().linear_velocity().dot(down_slope);
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let early = speed(&world);
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let acceleration = (speed(&world) - early) / (60.0 * DT);
    let moved = (world.body(ball).unwrap().position() - start).length();
    (moved, acceleration)
}

#[test]
fn a_ball_rests_on_slopes_gentler_than_atan_c_and_rolls_down_steeper_ones() {
    // c = 0.2: the steepest slope it rests on is atan 0.2 = 11.3°.
    let resistance = 0.2;
    let (moved, _) = on_a_slope(9.0, resistance);
    // 1 mm in 2 s: it holds (without resistance it would roll 2.2 m in that time); what moves
    // is the contact settling into its spring, 0.03 mm.
    assert!(moved < 1.0e-3, "moved {moved} m on a 9° slope");
    for degrees in [14.0f32, 25.0] {
        let (moved, acceleration) = on_a_slope(degrees, resistance);
        let angle = degrees.to_radians();
        let expected = 5.0 / 7.0 * G * (angle.sin() - resistance * angle.cos());
        // 1 %, as on flat ground: the second second is past the start's settling (measured
        // within 0.01 % at both angles).
        assert!(
            (acceleration / expected - 1.0).abs() <= 0.01,
            "{degrees}°: rolls at {acceleration} m/s², expected {expected} (moved {moved} m)"
        );
    }
}

#[test]
fn a_compound_child_rolls_with_its_own_resistance_and_radius() {
    // A dumbbell: two balls 2 m apart, the body's resistance 0 and one child's its own. Only
    // that child's contact resists, on its radius: without it the dumbbell rolls on at 2 m/s,
    // with it the one contact slows it (to 1.65 m/s after 1 s).
    let rolled = |child_resistance: Option<f32>| {
        let mut world = world(Vec3::new(0.0, -G, 0.0));
        add_ground(&mut world, 0.8);
        let ball = |z: f32| {
            CompoundChild::new(
                Shape::sphere(RADIUS).unwrap(),
                Pose::new(Vec3::new(0.0, 0.0, z), Quat::IDENTITY),
            )
        };
        let mut resisting = ball(-1.0);
        if let Some(resistance) = child_resistance {
            resisting = resisting.rolling_resistance(resistance);
        }
        let shape = Shape::compound(vec![resisting, ball(1.0)]).unwrap();
        let body = world
            .add_body(
                BodyDesc::dynamic(shape)
                    .position(Vec3::new(0.0, RADIUS, 0.0))
                    .linear_velocity(Vec3::new(2.0, 0.0, 0.0))
                    .angular_velocity(Vec3::new(0.0, 0.0, -2.0 / RADIUS))
                    .friction(0.8)
                    .can_sleep(false),
            )
            .unwrap();
        for _ in 0..60 {
            world.step(DT).unwrap();
        }
        let contacts = world.contacts();
        let impulses: Vec<f32> = contacts
            .iter()
            .map(|contact| contact.rolling_impulse().length())
            .collect();
        (world.body(body).unwrap().linear_velocity().x, impulses)
    };
    let (free, impulses) = rolled(None);
    assert!(impulses.iter().all(|&impulse| impulse == 0.0));
    // Rolls on at its launch speed, to rounding.
    assert!((free - 2.0).abs() < 1.0e-3, "rolls at {free} m/s");
    let (resisted, impulses) = rolled(Some(0.1));
    assert_eq!(impulses.iter().filter(|&&impulse| impulse > 0.0).count(), 1);
    assert!(resisted < free - 0.1, "rolls at {resisted} m/s");
}

#[test]
fn scene_files_take_rolling_resistance_and_name_a_bad_one() {
    let scene = |body: &str| {
        Scene::from_json(format!(r#"{{"bodies": [{body}]}}"#).as_bytes()).map(|scene| {
            let (_, body) = scene.bodies().next().unwrap();
            body.rolling_resistance()
        })
    };
    let ball = r#""shape": {"type": "sphere", "radius": 0.5}"#;
    assert_eq!(
        scene(&format!(r#"{{{ball}, "rolling_resistance": 0.05}}"#)).unwrap(),
        0.05
    );
    assert_eq!(scene(&format!("{{{ball}}}")).unwrap(), 0.0);
    let error = scene(&format!(r#"{{{ball}, "rolling_resistance": -1}}"#)).unwrap_err();
    assert_eq!(error.place, "bodies[0].rolling_resistance", "{error}");
    let compound = r#""shape": {"type": "compound", "children": [
        {"shape": {"type": "sphere", "radius": 0.5}},
        {"shape": {"type": "sphere", "radius": 0.5}, "rolling_resistance": -0.5}]}"#;
    let error = scene(&format!("{{{compound}}}")).unwrap_err();
    assert_eq!(
        error.place, "bodies[0].shape.children[1].rolling_resistance",
        "{error}"
    );
}

#[test]
fn a_ball_spinning_in_place_about_the_vertical_stops_at_the_same_bound() {
    // A ball touches at one point, where the twist friction has no lever; the rolling resistance
    // resists that spin too, with the torque `c r m g`: `I ω̇ = −c r m g`, `I = 2/5 m r²`, so
    // `ω̇ = −(5/2) c g / r` = 4.9 rad/s² for c = 0.1, r = 0.5 m, and 5 rad/s stops at 1.02 s.
    let (spin, resistance) = (5.0, 0.1);
    let (mut world, ball) = ball_on_ground(Vec3::ZERO, Vec3::new(0.0, spin, 0.0), resistance);
    let rate = 2.5 * resistance * G / RADIUS;
    for _ in 0..30 {
        world.step(DT).unwrap();
    }
    let measured = world.body(ball).unwrap().angular_velocity().y;
    let expected = spin - rate * 30.0 * DT;
    // 1 % of the spin lost, as for the rolling ball.
    assert!(
        (measured - expected).abs() <= 0.01 * (spin - expected),
        "spins at {measured} rad/s after 0.5 s, expected {expected}"
    );
    for _ in 30..66 {
        world.step(DT).unwrap();
    }
    // Stopped a step after 1.02 s, and stays so.
    let body = world.body(ball).unwrap();
    assert!(
        body.angular_velocity().length() < 1.0e-3,
        "still spins at {}",
        body.angular_velocity()
    );
}
