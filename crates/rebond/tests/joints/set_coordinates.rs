//! `World::set_joint_positions` and `World::set_joint_velocities` against the closed forms of the
//! poses and velocities of chains placed at given angles and slides.

use super::{add, rod, world};
use rebond::{BodyDesc, BodyHandle, ErrorKind, JointDesc, JointHandle, Quat, Shape, Vec3, World};
use std::f32::consts::TAU;

/// The reading of a coordinate that was set: the angle is rebuilt from quaternion components
/// (`2 atan2(d_xyz·a, d_w)`) of products of three or four unit quaternions, each rounded to
/// about 1.2e-7 per component, so a few 1e-7 rad (the worst measured over 1000 random states of
/// a three-joint arm at angles up to ±20 rad: 9.5e-7 rad, rates 1.4e-6 rad/s); 1e-5 leaves ten
/// times that, and 6π itself is resolved to 5e-7.
const ANGLE_TOLERANCE: f32 = 1e-5;

/// Positions a few metres from the origin rounded in `f32` (6e-8 m per metre, a few roundings
/// per link): 1e-5 m holds a 3-link chain ten times over.
const POSITION_TOLERANCE: f32 = 1e-5;

/// A chain of three 1 m rods hanging along −Y from the world at the origin, no gravity:
/// joint 1 (world–rod 1) at y = 0 about Z, joint 2 at y = −1 about X, joint 3 at y = −2 about Z.
fn chain() -> (World, [BodyHandle; 3], [JointHandle; 3]) {
    let mut world = world(Vec3::ZERO);
    let rods: [BodyHandle; 3] = std::array::from_fn(|index| {
        add(
            &mut world,
            rod(1.0, 1.0).position(Vec3::new(0.0, -0.5 - index as f32, 0.0)),
        )
    });
    let axes = [Vec3::Z, Vec3::X, Vec3::Z];
    let joints: [JointHandle; 3] = std::array::from_fn(|index| {
        let parent = (index > 0).then(|| rods[index - 1]);
        let anchor = Vec3::new(0.0, -(index as f32), 0.0);
        world
            .add_joint(JointDesc::revolute(
                parent,
                rods[index],
                anchor,
                axes[index],
            ))
            .unwrap()
    });
    (world, rods, joints)
}

fn assert_near(got: Vec3, expected: Vec3, tolerance: f32, what: &str) {
    assert!(
        (got - expected).length() <= tolerance,
        "{what}: {got} expected {expected}"
    );
}

/// Each revolute joint reads its angle, with its anchors together.
fn assert_placed(world: &World, angles: &[(JointHandle, f32)]) {
    for &(joint, angle) in angles {
        let read = world.joint_position(joint).unwrap();
        assert!(
            (read - angle).abs() <= ANGLE_TOLERANCE,
            "read {read} rad, set {angle}"
        );
        let placement = world.joint_placement(joint).unwrap();
        assert_near(
            placement.anchor_b,
            placement.anchor_a,
            POSITION_TOLERANCE,
            "anchors",
        );
    }
}

#[test]
fn a_chain_set_to_angles_reads_them_back_with_its_anchors_together() {
    let (mut world, rods, joints) = chain();
    let angles = [0.7, -1.2, 2.5];
    world
        .set_joint_positions(&[
            (joints[0], angles[0]),
            (joints[1], angles[1]),
            (joints[2], angles[2]),
        ])
        .unwrap();
    assert_placed(
        &world,
        &[
            (joints[0], angles[0]),
            (joints[1], angles[1]),
            (joints[2], angles[2]),
        ],
    );
    // The closed form: rod 1 turned by θ₁ about Z at the origin, rod 2 by θ₂ about X at rod
    // 1's lower end, rod 3 by θ₃ about Z at rod 2's lower end.
    let q1 = Quat::from_rotation_z(angles[0]);
    let q2 = q1 * Quat::from_rotation_x(angles[1]);
    let q3 = q2 * Quat::from_rotation_z(angles[2]);
    let half = Vec3::new(0.0, -0.5, 0.0);
    let end1 = q1 * (2.0 * half);
    let end2 = end1 + q2 * (2.0 * half);
    for (rod, (center, rotation)) in rods.iter().zip([
        (q1 * half, q1),
        (end1 + q2 * half, q2),
        (end2 + q3 * half, q3),
    ]) {
        let body = world.body(*rod).unwrap();
        assert_near(body.position(), center, POSITION_TOLERANCE, "rod centre");
        // |q · q_expected| = cos(half the angle between), 1 − 1e-10 within 2e-5 rad.
        assert!(
            body.rotation().dot(rotation).abs() >= 1.0 - 1e-10,
            "rod rotation {} expected {rotation}",
            body.rotation()
        );
    }
}

#[test]
fn three_turns_read_six_pi_and_keep_counting_from_there() {
    // Rod 1 set three turns round; after 30 still steps (no gravity, no velocity) the counter
    // still reads 6π, and half a turn more reads 7π.
    let (mut world, _, joints) = chain();
    for turns in [3.0_f32, -3.0] {
        let angle = turns * TAU;
        world.set_joint_positions(&[(joints[0], angle)]).unwrap();
        let read = world.joint_position(joints[0]).unwrap();
        assert!(
            (read - angle).abs() <= ANGLE_TOLERANCE,
            "{read} rad after setting {angle}"
        );
        for _ in 0..30 {
            world.step(1.0 / 60.0).unwrap();
        }
        let read = world.joint_position(joints[0]).unwrap();
        assert!(
            (read - angle).abs() <= ANGLE_TOLERANCE,
            "{read} rad 30 steps after setting {angle}"
        );
        let further = angle + 0.5 * TAU;
        world.set_joint_positions(&[(joints[0], further)]).unwrap();
        let read = world.joint_position(joints[0]).unwrap();
        assert!(
            (read - further).abs() <= ANGLE_TOLERANCE,
            "{read} rad after setting {further}"
        );
    }
}

#[test]
fn a_joint_not_listed_carries_its_subtree_rigidly() {
    // Setting joint 1 only turns rods 2 and 3 with rod 1: joints 2 and 3 read what they read
    // before, and rod 3's pose relative to rod 1 is kept.
    let (mut world, rods, joints) = chain();
    world
        .set_joint_positions(&[(joints[1], 0.4), (joints[2], -0.9)])
        .unwrap();
    let relative = |world: &World| {
        let one = world.body(rods[0]).unwrap().pose();
        let three = world.body(rods[2]).unwrap().pose();
        one.inverse().mul_pose(&three)
    };
    let before = relative(&world);
    world.set_joint_positions(&[(joints[0], 1.1)]).unwrap();
    let after = relative(&world);
    assert_near(
        after.position,
        before.position,
        POSITION_TOLERANCE,
        "rod 3 from rod 1",
    );
    for (joint, angle) in [(joints[0], 1.1), (joints[1], 0.4), (joints[2], -0.9)] {
        let read = world.joint_position(joint).unwrap();
        assert!(
            (read - angle).abs() <= ANGLE_TOLERANCE,
            "read {read}, expected {angle}"
        );
    }
}

#[test]
fn a_floating_root_keeps_its_pose_and_a_joint_may_place_its_body_a() {
    // A free torso at (1, 2, 3) turned about Y (body_b of no joint: the root), a thigh hinged to
    // it, and a shin whose knee has the shin as body_a and the thigh as body_b, so the knee
    // places its body_a. The torso keeps its pose to the bit; hip and knee read what was set.
    let mut world = world(Vec3::ZERO);
    let torso = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::new(0.5, 0.2, 0.2)).unwrap())
            .position(Vec3::new(1.0, 2.0, 3.0))
            .rotation(Quat::from_rotation_y(0.3)),
    );
    let thigh = add(&mut world, rod(1.0, 1.0).position(Vec3::new(1.0, 1.3, 3.0)));
    let shin = add(&mut world, rod(1.0, 1.0).position(Vec3::new(1.0, 0.3, 3.0)));
    let hip = world
        .add_joint(JointDesc::revolute(
            torso,
            thigh,
            Vec3::new(1.0, 1.8, 3.0),
            Vec3::X,
        ))
        .unwrap();
    let knee = world
        .add_joint(JointDesc::revolute(
            shin,
            thigh,
            Vec3::new(1.0, 0.8, 3.0),
            Vec3::X,
        ))
        .unwrap();
    let pose = world.body(torso).unwrap().pose();
    world
        .set_joint_positions(&[(hip, -0.8), (knee, 0.5)])
        .unwrap();
    assert_eq!(world.body(torso).unwrap().pose(), pose);
    assert_placed(&world, &[(hip, -0.8), (knee, 0.5)]);
    // Rates set with the torso moving: its motion is kept, each joint reads its rate, and the
    // anchors of each joint move together.
    let motion = (Vec3::new(0.4, 0.0, -1.0), Vec3::new(0.2, -0.1, 0.3));
    let body = world.body_mut(torso).unwrap();
    body.set_linear_velocity(motion.0).unwrap();
    body.set_angular_velocity(motion.1).unwrap();
    world
        .set_joint_velocities(&[(hip, 1.5), (knee, -0.7)])
        .unwrap();
    let body = world.body(torso).unwrap();
    assert_eq!((body.linear_velocity(), body.angular_velocity()), motion);
    for (joint, rate) in [(hip, 1.5), (knee, -0.7)] {
        let read = world.joint_velocity(joint).unwrap();
        // As the chain's rates below: a few 1e-7 rad/s of rounding.
        assert!((read - rate).abs() <= 1e-5, "rate {read}, set {rate}");
        let placement = world.joint_placement(joint).unwrap();
        let (a, b) = world.joint(joint).unwrap().bodies();
        let velocity_a = world
            .body(a.unwrap())
            .unwrap()
            .velocity_at_point(placement.anchor_a);
        let velocity_b = world.body(b).unwrap().velocity_at_point(placement.anchor_b);
        assert_near(velocity_b, velocity_a, 1e-5, "anchor velocities");
    }
}

#[test]
fn a_prismatic_slide_is_placed_along_its_turned_axis() {
    // A carriage on a rail along X fixed to a base turned 30° about Z: set to s = 0.35 m it sits
    // 0.35 m along the turned axis from where the joint was made, rotated as the base.
    let mut world = world(Vec3::ZERO);
    let base = add(&mut world, rod(1.0, 2.0));
    let carriage = add(&mut world, rod(0.5, 1.0).position(Vec3::new(0.0, 1.0, 0.0)));
    let hinge = world
        .add_joint(JointDesc::revolute(None, base, Vec3::ZERO, Vec3::Z))
        .unwrap();
    let rail = world
        .add_joint(JointDesc::prismatic(base, carriage, Vec3::Y, Vec3::X))
        .unwrap();
    let turn = 30f32.to_radians();
    world
        .set_joint_positions(&[(hinge, turn), (rail, 0.35)])
        .unwrap();
    let slide = world.joint_position(rail).unwrap();
    assert!((slide - 0.35).abs() <= POSITION_TOLERANCE, "slide {slide}");
    let rotation = Quat::from_rotation_z(turn);
    let expected = rotation * Vec3::new(0.35, 1.0, 0.0);
    let body = world.body(carriage).unwrap();
    assert_near(body.position(), expected, POSITION_TOLERANCE, "carriage");
    assert!(body.rotation().dot(rotation).abs() >= 1.0 - 1e-10);
    // Rates: the hinge turning at 2 rad/s and the slide at −0.5 m/s; the carriage's velocity
    // is ω × r + ṡ a, with a the turned X.
    world
        .set_joint_velocities(&[(hinge, 2.0), (rail, -0.5)])
        .unwrap();
    let rate = world.joint_velocity(rail).unwrap();
    assert!((rate + 0.5).abs() <= 1e-5, "slide rate {rate}");
    let spin = world.joint_velocity(hinge).unwrap();
    assert!((spin - 2.0).abs() <= 1e-5, "hinge rate {spin}");
    let body = world.body(carriage).unwrap();
    assert_near(
        body.angular_velocity(),
        Vec3::Z * 2.0,
        1e-5,
        "carriage spin",
    );
    let expected = (Vec3::Z * 2.0).cross(body.center_of_mass()) + rotation * Vec3::X * -0.5;
    assert_near(body.linear_velocity(), expected, 1e-5, "carriage velocity");
}

#[test]
fn chain_rates_read_back_and_the_anchors_move_together() {
    let (mut world, rods, joints) = chain();
    world
        .set_joint_positions(&[(joints[0], 0.3), (joints[1], 0.6), (joints[2], -0.4)])
        .unwrap();
    let rates = [1.5, -2.0, 0.75];
    world
        .set_joint_velocities(&[
            (joints[0], rates[0]),
            (joints[1], rates[1]),
            (joints[2], rates[2]),
        ])
        .unwrap();
    for (&joint, &rate) in joints.iter().zip(&rates) {
        let read = world.joint_velocity(joint).unwrap();
        // ω differences of sums of a few products of unit vectors and rates ≤ 2 rad/s:
        // a few 1e-7 rad/s; 1e-5 as the angles.
        assert!((read - rate).abs() <= 1e-5, "rate {read}, set {rate}");
    }
    // Rod 1 turns at θ̇₁ about Z through the origin: its centre moves at θ̇₁ ẑ × c₁.
    let one = world.body(rods[0]).unwrap();
    let expected = (Vec3::Z * rates[0]).cross(one.center_of_mass());
    assert_near(one.linear_velocity(), expected, 1e-5, "rod 1 velocity");
    for joint in joints {
        let placement = world.joint_placement(joint).unwrap();
        let (a, b) = world.joint(joint).unwrap().bodies();
        let velocity_a = a.map_or(Vec3::ZERO, |a| {
            world.body(a).unwrap().velocity_at_point(placement.anchor_a)
        });
        let velocity_b = world.body(b).unwrap().velocity_at_point(placement.anchor_b);
        assert_near(velocity_b, velocity_a, 1e-5, "anchor velocities");
    }
}

#[test]
fn bad_entries_are_refused_by_place_and_leave_the_world_unchanged() {
    let (mut world, rods, joints) = chain();
    let ball_body = add(
        &mut world,
        rod(1.0, 1.0).position(Vec3::new(0.0, -3.5, 0.0)),
    );
    let ball = world
        .add_joint(JointDesc::ball(
            rods[2],
            ball_body,
            Vec3::new(0.0, -3.0, 0.0),
        ))
        .unwrap();
    let (mut other, _, other_joints) = chain();
    world.remove_joint(joints[2]).unwrap();
    other.step(1.0 / 60.0).unwrap();
    let poses: Vec<_> = rods
        .iter()
        .map(|&rod| world.body(rod).unwrap().pose())
        .collect();
    let cases = [
        ((joints[0], f32::NAN), "positions[1]", ErrorKind::NotFinite),
        (
            (joints[0], 2e4),
            "positions[1]",
            ErrorKind::OutOfRange {
                value: 2e4,
                min: -1e4,
                max: 1e4,
            },
        ),
        (
            (ball, 0.5),
            "positions[1]",
            ErrorKind::NotForJointType("ball"),
        ),
        (
            (joints[2], 0.5),
            "positions[1]",
            ErrorKind::StaleJointHandle,
        ),
        (
            (other_joints[0], 0.5),
            "positions[1]",
            ErrorKind::StaleJointHandle,
        ),
    ];
    for (entry, field, kind) in cases {
        let error = world
            .set_joint_positions(&[(joints[1], 0.2), entry])
            .unwrap_err();
        assert_eq!((error.field.as_str(), &error.kind), (field, &kind));
        let error = world
            .set_joint_velocities(&[(joints[1], 0.2), entry])
            .unwrap_err();
        let field = field.replace("positions", "velocities");
        assert_eq!((error.field.as_str(), &error.kind), (field.as_str(), &kind));
    }
    for (&rod, pose) in rods.iter().zip(&poses) {
        assert_eq!(world.body(rod).unwrap().pose(), *pose);
        assert_eq!(world.body(rod).unwrap().angular_velocity(), Vec3::ZERO);
    }
}

#[test]
fn a_joint_closing_a_loop_places_nothing() {
    // The chain's rod 3 also tied to the world by a distance joint from (2, −3, 0) to its lower
    // end: the walk reaches rod 3 through the chain first, so the distance joint closes a loop.
    // Its value is ignored, and it reads the distance the chain's placement gives.
    let (mut world, rods, joints) = chain();
    let tie = world
        .add_joint(JointDesc::distance(
            None,
            rods[2],
            Vec3::new(2.0, -3.0, 0.0),
            Vec3::new(0.0, -3.0, 0.0),
        ))
        .unwrap();
    let mut ignored = world.clone();
    world.set_joint_positions(&[(joints[0], 0.6)]).unwrap();
    ignored
        .set_joint_positions(&[(joints[0], 0.6), (tie, 9.0)])
        .unwrap();
    assert_eq!(
        world.body(rods[2]).unwrap().pose(),
        ignored.body(rods[2]).unwrap().pose()
    );
    // Rod 3's lower end, 3 m from the pivot, turned 0.6 rad about Z: its distance to (2, −3, 0).
    let end = Quat::from_rotation_z(0.6) * Vec3::new(0.0, -3.0, 0.0);
    let expected = (end - Vec3::new(2.0, -3.0, 0.0)).length();
    let read = world.joint_position(tie).unwrap();
    assert!(
        (read - expected).abs() <= POSITION_TOLERANCE,
        "the tie reads {read} m, the chain puts it at {expected}"
    );
}
