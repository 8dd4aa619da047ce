//! Reaction forces: what a joint reports, and breaking.

use super::{add, world, DT, G};
use rebond::{BodyDesc, JointDesc, Shape, Vec3};

#[test]
fn a_body_hanging_still_reports_a_joint_force_equal_to_its_weight() {
    // A 3 kg ball 1 m below a fixed point on a ball joint, at rest: the joint holds it up with
    // m g, and the mean over a step is exact once nothing moves; 1 % is the bound.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let ball = add(
        &mut world,
        BodyDesc::dynamic(Shape::sphere(0.2).unwrap())
            .mass(3.0)
            .position(Vec3::new(0.0, -1.0, 0.0)),
    );
    let joint = world
        .add_joint(JointDesc::ball(None, ball, Vec3::ZERO))
        .unwrap();
    let weight = 3.0 * G;
    for step in 0..120 {
        world.step(DT).unwrap();
        if step >= 60 {
            let force = world.joint(joint).unwrap().force();
            assert!(
                (force - Vec3::new(0.0, weight, 0.0)).length() < 0.01 * weight,
                "force {force:?} N, weight {weight} N"
            );
        }
    }
}

#[test]
fn a_fixed_joint_holding_a_beam_reports_its_weight_and_moment() {
    // A 2 kg beam 1 m long welded at its left end to the world: the weld carries m g up and the
    // moment m g L/2 about +Z (counter-clockwise) that keeps the beam level.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let beam = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::new(0.5, 0.05, 0.05)).unwrap())
            .mass(2.0)
            .position(Vec3::new(0.5, 0.0, 0.0)),
    );
    let joint = world
        .add_joint(JointDesc::fixed(None, beam, Vec3::ZERO))
        .unwrap();
    for _ in 0..120 {
        world.step(DT).unwrap();
    }
    let weight = 2.0 * G;
    let joint = world.joint(joint).unwrap();
    let (force, torque) = (joint.force(), joint.torque());
    assert!(
        (force - Vec3::new(0.0, weight, 0.0)).length() < 0.01 * weight,
        "force {force:?} N"
    );
    let moment = weight * 0.5;
    assert!(
        (torque - Vec3::new(0.0, 0.0, moment)).length() < 0.01 * moment,
        "torque {torque:?} N·m, m g L/2 = {moment}"
    );
    let sag = world.body(beam).unwrap().position().y;
    assert!(sag.abs() < 1e-3, "the beam sags {sag} m");
}

#[test]
fn a_joint_weaker_than_its_load_breaks_in_the_first_step_and_the_body_falls_freely() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let ball = add(
        &mut world,
        BodyDesc::dynamic(Shape::sphere(0.2).unwrap())
            .mass(1.0)
            .position(Vec3::new(0.0, -1.0, 0.0)),
    );
    let joint = world
        .add_joint(JointDesc::ball(None, ball, Vec3::ZERO).break_force(0.5 * G))
        .unwrap();
    world.step(DT).unwrap();
    assert!(world.joint(joint).unwrap().is_broken());
    let events = world.joint_break_events();
    assert_eq!(events.len(), 1);
    assert_eq!(events[0].joint, joint);
    assert!((events[0].force.y - G).abs() < 0.01 * G, "{:?}", events[0]);
    assert_eq!(world.joint(joint).unwrap().force(), Vec3::ZERO);
    // From the pose and velocity after the breaking step, the ball falls as a free body does:
    // semi-implicit Euler, exactly.
    let body = world.body(ball).unwrap();
    let (mut position, mut velocity) = (body.position(), body.linear_velocity());
    let h = DT / world.settings().substeps as f32;
    for _ in 0..60 {
        world.step(DT).unwrap();
        for _ in 0..world.settings().substeps {
            velocity.y -= h * G;
            position += h * velocity;
        }
    }
    let end = world.body(ball).unwrap().position();
    assert!(
        (end - position).length() < 1e-4,
        "{end:?} against {position:?}"
    );
    assert!(world.joint_break_events().is_empty());
}

#[test]
fn once_broken_a_joint_no_longer_keeps_its_bodies_from_colliding() {
    // A box welded on top of a static block breaks its weld in the first step; from then on the
    // two collide, so the box rests on the block instead of falling through it.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let block = world
        .add_body(BodyDesc::static_body(
            Shape::cuboid(Vec3::splat(0.5)).unwrap(),
        ))
        .unwrap();
    let crate_ = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.5)).unwrap())
            .mass(1.0)
            .position(Vec3::new(0.0, 1.0, 0.0)),
    );
    let weld = world
        .add_joint(JointDesc::fixed(block, crate_, Vec3::new(0.0, 0.5, 0.0)).break_force(0.1))
        .unwrap();
    world.step(DT).unwrap();
    assert!(world.joint(weld).unwrap().is_broken());
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let height = world.body(crate_).unwrap().position().y;
    assert!((height - 1.0).abs() < 0.01, "the box is at {height} m");
}
