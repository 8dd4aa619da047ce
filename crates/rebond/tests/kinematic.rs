//! Kinematic control: pose targets reached exactly in one step with the matching velocity, and
//! keyframe paths that carry what rests on them.

mod common;

use common::G;
use rebond::{
    BodyDesc, BodyHandle, KinematicPath, PathPoint, Pose, Quat, Shape, Vec3, World, WorldSettings,
};

/// 64 Hz: a power of two, so that the path clock (the sum of the steps) lands exactly on the
/// keyframe times, and each keyframe's pose can be compared bit for bit.
const DT: f32 = 1.0 / 64.0;

fn world() -> World {
    World::new(WorldSettings {
        gravity: Vec3::new(0.0, -G, 0.0),
        ..WorldSettings::default()
    })
    .unwrap()
}

fn stepped(world: &mut World, steps: usize) {
    for _ in 0..steps {
        world.step(DT).unwrap();
    }
}

fn point(time: f32, x: f32) -> PathPoint {
    PathPoint::new(time, Vec3::new(x, 0.0, 0.0), Quat::IDENTITY)
}

fn kinematic_box() -> BodyDesc {
    BodyDesc::kinematic(Shape::cuboid(Vec3::new(2.0, 0.1, 2.0)).unwrap())
}

/// A 4 m × 0.2 m × 4 m kinematic platform, top face at y = 0.1, following `path`, and a unit
/// box resting on it, both with the default friction 0.5.
fn platform_with_box(world: &mut World, path: KinematicPath) -> [BodyHandle; 2] {
    let platform = world.add_body(kinematic_box().path(path)).unwrap();
    let cube = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.5)).unwrap())
                .position(Vec3::new(0.0, 0.6, 0.0))
                .can_sleep(false),
        )
        .unwrap();
    [platform, cube]
}

/// The box's position along x relative to the platform's, m.
fn offset(world: &World, [platform, cube]: [BodyHandle; 2]) -> f32 {
    world.body(cube).unwrap().position().x - world.body(platform).unwrap().position().x
}

#[test]
fn a_kinematic_platform_following_keyframes_carries_a_box() {
    // At rest for 0.5 s, 2 m along x in 2 s (1 m/s), then stopped.
    let mut world = world();
    let path = KinematicPath::new(vec![point(0.0, 0.0), point(0.5, 0.0), point(2.5, 2.0)]);
    let bodies = platform_with_box(&mut world, path);
    let [platform, cube] = bodies;
    let position = |world: &World| world.body(platform).unwrap().position();

    stepped(&mut world, 32);
    // Each keyframe's pose exactly: the clock is exactly 0.5 s, and a point's time gives its pose.
    assert_eq!(position(&world), Vec3::ZERO);
    let at_rest = offset(&world, bodies);

    // Friction accelerates the box at μg until it moves with the platform. Over substeps of
    // h = dt/8 (velocity first, then position) the box gains μgh per substep, so it trails by
    // Σₖ (v − kμgh) h = v²/(2μg) − vh/2 once it has caught up: 0.10194 − 0.00098 m.
    let (speed, friction, h) = (1.0, 0.5, DT / 8.0);
    let slip = speed * speed / (2.0 * friction * G) - speed * h / 2.0;
    stepped(&mut world, 64);
    assert_eq!(
        position(&world),
        Vec3::new(1.0, 0.0, 0.0),
        "at 1.5 s, halfway"
    );
    let carried = offset(&world, bodies) - at_rest;
    // The sum's last substep is a partial one, off by at most μgh² = 1.9e-5 m; the contact's
    // soft push adds nothing along x. 1e-4 m is five times that.
    assert!(
        (carried + slip).abs() < 1.0e-4,
        "slipped {carried}, expected {}",
        -slip
    );
    // Carried: moving with the platform, no longer slipping.
    let velocity = world.body(cube).unwrap().linear_velocity();
    // Friction holds the relative speed to the solver's rounding of a 1 m/s velocity.
    assert!(
        (velocity - Vec3::X).length() < 1.0e-4,
        "box velocity {velocity}"
    );

    stepped(&mut world, 64);
    assert_eq!(
        position(&world),
        Vec3::new(2.0, 0.0, 0.0),
        "at 2.5 s, the last point"
    );
    assert_eq!(world.body(platform).unwrap().linear_velocity(), Vec3::X);
    // After the stop the box slides on by the same sum, Σₖ (v − kμgh) h, and comes back to where
    // it stood: the two slips cancel up to their partial substeps, 2μgh² = 3.7e-5 m.
    stepped(&mut world, 64);
    assert_eq!(position(&world), Vec3::new(2.0, 0.0, 0.0));
    assert_eq!(world.body(platform).unwrap().linear_velocity(), Vec3::ZERO);
    let change = offset(&world, bodies) - at_rest;
    assert!(change.abs() < 1.0e-4, "offset changed by {change} m");
    assert!(world.body(cube).unwrap().linear_velocity().length() < 1.0e-4);
}

#[test]
fn a_pose_target_is_reached_exactly_in_one_step_with_the_matching_velocity() {
    let mut world = world();
    let body = world.add_body(kinematic_box()).unwrap();
    let axis = Vec3::new(1.0, 2.0, 3.0).normalize();
    let (angle, travel) = (0.4, Vec3::new(0.3, -0.2, 0.1));
    let target = Pose::new(travel, Quat::from_axis_angle(axis, angle));
    world
        .body_mut(body)
        .unwrap()
        .set_kinematic_target(target)
        .unwrap();
    world.step(DT).unwrap();
    let moved = world.body(body).unwrap();
    assert_eq!(moved.pose(), target);
    assert_eq!(
        moved.kinematic_target(),
        None,
        "a target holds for one step"
    );
    // v = Δx/dt, rounded once in the difference and once in the division: 2 ulp of 19 m/s.
    let velocity = moved.linear_velocity();
    assert!((velocity - travel / DT).length() < 4.0e-6, "{velocity}");
    // ω = θ/dt, θ from the f32 quaternion through atan2: a few ulp of the 25.6 rad/s, 1e-5
    // relative at most.
    let spin = moved.angular_velocity();
    assert!(
        (spin - axis * angle / DT).length() < 25.6 * 1.0e-5,
        "{spin}"
    );

    // Without a new target it keeps its velocity, as any kinematic body.
    world.step(DT).unwrap();
    let coasted = world.body(body).unwrap();
    assert_eq!(coasted.linear_velocity(), velocity);
    assert_eq!(coasted.angular_velocity(), spin);
    // Another Δx, by substeps: 8 roundings of a 0.3 m sum, a few ulp.
    assert!((coasted.position() - 2.0 * travel).length() < 1.0e-6);
}

#[test]
fn a_pose_target_turns_by_the_shortest_arc() {
    let mut world = world();
    let body = world.add_body(kinematic_box()).unwrap();
    // 350° about y is −10°; and −q is the same orientation as q, no turn at all.
    let long_way = Quat::from_rotation_y(350f32.to_radians());
    world
        .body_mut(body)
        .unwrap()
        .set_kinematic_target(Pose::new(Vec3::ZERO, long_way))
        .unwrap();
    world.step(DT).unwrap();
    let spin = world.body(body).unwrap().angular_velocity();
    let expected = -10f32.to_radians() / DT;
    // The f32 quaternion of 350° carries an angle error of about 1e-7 rad: 1e-5 rad/s here.
    assert!(
        (spin - Vec3::Y * expected).length() < 1.0e-4,
        "{spin}, expected {expected}"
    );

    let rotation = world.body(body).unwrap().rotation();
    let negated = Pose::new(Vec3::ZERO, -rotation);
    world
        .body_mut(body)
        .unwrap()
        .set_kinematic_target(negated)
        .unwrap();
    world.step(DT).unwrap();
    let spin = world.body(body).unwrap().angular_velocity();
    // q·(−q)⁻¹ = −1, the identity by the shortest arc: no turn, to f32 rounding.
    assert!(spin.length() < 1.0e-4, "{spin}");
}

#[test]
fn rotation_keyframes_turn_by_the_shortest_arc() {
    // Identity, then 350° about y at 1 s: the body turns −10° over the second, at −10°/s.
    let mut world = world();
    let end = Quat::from_rotation_y(350f32.to_radians());
    let path = KinematicPath::new(vec![
        PathPoint::new(0.0, Vec3::ZERO, Quat::IDENTITY),
        PathPoint::new(1.0, Vec3::ZERO, end),
    ]);
    let body = world.add_body(kinematic_box().path(path)).unwrap();
    stepped(&mut world, 32);
    let halfway = world.body(body).unwrap();
    let expected = Quat::from_rotation_y(-5f32.to_radians());
    // Same orientation up to the quaternion's sign: |q·q'| = cos(error/2), and slerp in f32 is
    // good to a few ulp, so within 1e-6 of 1 (an error under 3e-3 rad, as f32 resolves it).
    assert!(halfway.rotation().dot(expected).abs() > 1.0 - 1.0e-6);
    let spin = halfway.angular_velocity();
    // A 1/64 s slice of the turn, θ/dt: the slerp's few ulp over dt, 1e-4 rad/s.
    assert!(
        (spin - Vec3::Y * -10f32.to_radians()).length() < 1.0e-4,
        "{spin}"
    );
    stepped(&mut world, 32);
    // At the last point exactly, and stopped.
    let stopped = world.body(body).unwrap();
    assert_eq!(stopped.rotation(), end.normalize());
    stepped(&mut world, 1);
    assert_eq!(world.body(body).unwrap().angular_velocity(), Vec3::ZERO);
}

#[test]
fn a_looping_path_starts_again_from_its_first_point() {
    // There and back in 2 s.
    let points = vec![point(0.0, 0.0), point(1.0, 1.0), point(2.0, 0.0)];
    let mut world = world();
    let looping = world
        .add_body(kinematic_box().path(KinematicPath::new(points.clone()).looping(true)))
        .unwrap();
    let once = world
        .add_body(
            kinematic_box()
                .path(KinematicPath::new(points))
                .collision_groups(rebond::InteractionGroups::NONE),
        )
        .unwrap();
    let x = |world: &World, body| world.body(body).unwrap().position().x;
    stepped(&mut world, 160);
    // 2.5 s: the loop is at 0.5 s again, the other stays at its last point.
    assert_eq!(x(&world, looping), 0.5);
    assert_eq!(world.body(looping).unwrap().linear_velocity(), Vec3::X);
    assert_eq!(x(&world, once), 0.0);
    assert_eq!(world.body(once).unwrap().linear_velocity(), Vec3::ZERO);
    stepped(&mut world, 32);
    assert_eq!(x(&world, looping), 1.0);
    assert_eq!(world.body(looping).unwrap().path_time(), 3.0);
}

#[test]
fn a_body_with_a_path_starts_at_its_first_point_and_a_target_replaces_the_path() {
    let mut world = world();
    let path = KinematicPath::new(vec![point(0.0, 3.0), point(1.0, 4.0)]);
    let body = world
        .add_body(
            kinematic_box()
                .position(Vec3::new(-7.0, 1.0, 0.0))
                .path(path),
        )
        .unwrap();
    assert_eq!(
        world.body(body).unwrap().position(),
        Vec3::new(3.0, 0.0, 0.0)
    );
    stepped(&mut world, 32);
    assert_eq!(
        world.body(body).unwrap().position(),
        Vec3::new(3.5, 0.0, 0.0)
    );
    let target = Pose::from_position(Vec3::new(3.0, 0.0, 0.0));
    world
        .body_mut(body)
        .unwrap()
        .set_kinematic_target(target)
        .unwrap();
    assert!(world.body(body).unwrap().path().is_none());
    stepped(&mut world, 1);
    assert_eq!(world.body(body).unwrap().position(), target.position);
    // Coasting back at the velocity of the target's step, 0.5 m per step.
    stepped(&mut world, 1);
    assert_eq!(
        world.body(body).unwrap().position(),
        Vec3::new(2.5, 0.0, 0.0)
    );
}

#[test]
fn set_position_teleports_a_kinematic_body_and_leaves_what_rests_on_it() {
    // The documented contrast with a pose target: moved by set_position, the platform has no
    // velocity, so friction does not carry the box.
    let mut world = world();
    let bodies = platform_with_box(&mut world, KinematicPath::new(vec![point(0.0, 0.0)]));
    let [platform, cube] = bodies;
    world.body_mut(platform).unwrap().set_path(None).unwrap();
    stepped(&mut world, 8);
    for step in 1..=32 {
        let to = Vec3::new(step as f32 / 64.0, 0.0, 0.0);
        world.body_mut(platform).unwrap().set_position(to).unwrap();
        stepped(&mut world, 1);
    }
    assert_eq!(world.body(platform).unwrap().position().x, 0.5);
    // The box stays where it stood: friction sees no relative velocity to act on, to within
    // the contact solver's rounding.
    assert!(world.body(cube).unwrap().position().x.abs() < 1.0e-4);
}

#[test]
fn a_world_saved_while_a_path_is_followed_resumes_bit_for_bit() {
    let path = KinematicPath::new(vec![
        PathPoint::new(0.0, Vec3::ZERO, Quat::IDENTITY),
        PathPoint::new(0.7, Vec3::new(1.0, 0.0, 0.0), Quat::from_rotation_y(0.5)),
        PathPoint::new(1.3, Vec3::new(1.0, 0.2, 0.0), Quat::IDENTITY),
    ])
    .looping(true);
    let mut start = world();
    platform_with_box(&mut start, path);
    // Irregular steps, so that the clock is not a round number when saved.
    let run = |world: &mut World, steps: usize| {
        for step in 0..steps {
            world
                .step(if step % 3 == 0 { 0.013 } else { 1.0 / 60.0 })
                .unwrap();
        }
    };
    let mut straight = start.clone();
    run(&mut straight, 150);
    let mut saved = start;
    run(&mut saved, 75);
    let mut resumed = World::load_state(&saved.save_state()).unwrap();
    run(&mut resumed, 75);
    for ((_, a), (_, b)) in straight.bodies().zip(resumed.bodies()) {
        assert_eq!(a.pose(), b.pose());
        assert_eq!(a.linear_velocity(), b.linear_velocity());
        assert_eq!(a.angular_velocity(), b.angular_velocity());
        assert_eq!(a.path_time().to_bits(), b.path_time().to_bits());
    }
}

#[test]
fn a_box_asleep_on_a_waiting_platform_wakes_when_the_path_sets_off() {
    // The platform waits 2 s, long enough for the box to fall asleep on it, then moves 1 m in
    // 1 s.
    let mut world = world();
    let path = KinematicPath::new(vec![point(0.0, 0.0), point(2.0, 0.0), point(3.0, 1.0)]);
    let platform = world.add_body(kinematic_box().path(path)).unwrap();
    let cube = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.5)).unwrap())
                .position(Vec3::new(0.0, 0.6, 0.0)),
        )
        .unwrap();
    stepped(&mut world, 128);
    assert!(
        world.body(cube).unwrap().is_sleeping(),
        "asleep on the waiting platform"
    );
    stepped(&mut world, 64);
    assert_eq!(world.body(platform).unwrap().position(), Vec3::X);
    // Carried along, less the slip of a sudden start, v²/(2μg) − vh/2 = 0.101 m at 1 m/s; the
    // tolerance is the one of the platform test above.
    let cube = world.body(cube).unwrap();
    assert!(!cube.is_sleeping());
    let slip = 1.0 / (2.0 * 0.5 * G) - DT / 16.0;
    assert!(
        (cube.position().x - (1.0 - slip)).abs() < 1.0e-4,
        "{}",
        cube.position().x
    );
}

#[test]
fn a_pose_target_is_swept_and_a_teleport_is_not() {
    // A 4 cm paddle moved 1.6 m a step toward a resting ball, by pose targets (motion at
    // 102 m/s, which the continuous pass sweeps) and by set_position (a teleport: no velocity,
    // nothing swept). The target pushes the ball ahead at its speed; the teleport jumps over
    // it and leaves it where it was, untouched.
    for teleport in [false, true] {
        let mut world = world();
        let paddle = world
            .add_body(BodyDesc::kinematic(
                Shape::cuboid(Vec3::new(0.02, 0.15, 0.15)).unwrap(),
            ))
            .unwrap();
        let ball = world
            .add_body(
                BodyDesc::dynamic(Shape::sphere(0.025).unwrap())
                    .position(Vec3::new(2.5, 0.0, 0.0))
                    .can_sleep(false),
            )
            .unwrap();
        let step_length = 1.6;
        for step in 1..=3 {
            let to = Vec3::new(step as f32 * step_length, 0.0, 0.0);
            let body = world.body_mut(paddle).unwrap();
            if teleport {
                body.set_position(to).unwrap();
            } else {
                body.set_kinematic_target(Pose::from_position(to)).unwrap();
            }
            stepped(&mut world, 1);
        }
        let body = world.body(ball).unwrap();
        let (x, v) = (body.position().x, body.linear_velocity().x);
        if teleport {
            assert!(x == 2.5 && v == 0.0, "teleport: ball at {x} m, {v} m/s");
        } else {
            // Ahead of the paddle's front face (x = 4.82) by its radius, at the paddle's speed,
            // 1.6 m / DT, to 1e-5 of it (f32 rounding).
            assert!(x >= 4.82 + 0.025, "target: ball at {x}");
            assert!((v - 1.6 / DT).abs() < 1.0e-5 * 1.6 / DT, "target: {v} m/s");
        }
    }
}
