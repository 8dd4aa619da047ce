//! Locked axes: a body never moves along a locked world axis nor turns about one, whatever
//! pushes it, and along the free axes it answers as the constrained body of mechanics does.

mod common;

use common::{add_ground, world, DT, G};
use rebond::prelude::*;
use rebond::JointDesc;

/// A capsule standing upright on the ground, radius 0.3 m, 1.8 m tall, 70 kg.
fn standing_capsule(locked_axes: LockedAxes) -> BodyDesc {
    BodyDesc::dynamic(Shape::capsule(0.3, 0.6).unwrap())
        .position(Vec3::new(0.0, 0.9, 0.0))
        .mass(70.0)
        .can_sleep(false)
        .locked_axes(locked_axes)
}

/// The angle between a body's local +Y and the world's, radians.
fn tilt(rotation: Quat) -> f32 {
    (rotation * Vec3::Y).dot(Vec3::Y).clamp(-1.0, 1.0).acos()
}

/// A 20 kg box thrown at the capsule's upper part, 1.2 m above the ground.
fn strike_high(world: &mut World) {
    world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.2)).unwrap())
                .position(Vec3::new(1.0, 1.3, 0.0))
                .linear_velocity(Vec3::new(-8.0, 1.0, 0.0))
                .mass(20.0),
        )
        .unwrap();
}

#[test]
fn locked_capsule_struck_high_on_its_side_slides_and_never_turns() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, 0.5);
    let capsule = world
        .add_body(standing_capsule(LockedAxes::ROTATION))
        .unwrap();
    strike_high(&mut world);
    let mut slid = 0.0_f32;
    // Worst over two seconds: the rotation is never touched, to the bit, since every angular
    // velocity change is `I⁻¹ τ` with `I⁻¹` zero on all three locked axes.
    for _ in 0..120 {
        world.step(DT).unwrap();
        let body = world.body(capsule).unwrap();
        assert_eq!(body.rotation(), Quat::IDENTITY);
        assert_eq!(body.angular_velocity(), Vec3::ZERO);
        slid = slid.max(-body.position().x);
    }
    // The 20 kg box at 8 m/s carries 160 N·s; without restitution the 70 kg capsule leaves at
    // about 160 / 90 = 1.8 m/s, as a point mass would, and friction 0.5 stops it in
    // v² / (2 μ g) = 0.32 m. A lock that leaked the blow into a turn would leave it far less.
    assert!(slid > 0.25, "the capsule slid only {slid} m");

    // The same blow tips a free capsule: the test above holds because of the lock.
    let mut free_world = common::world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut free_world, 0.5);
    let free = free_world
        .add_body(standing_capsule(LockedAxes::NONE))
        .unwrap();
    strike_high(&mut free_world);
    let worst = (0..120)
        .map(|_| {
            free_world.step(DT).unwrap();
            tilt(free_world.body(free).unwrap().rotation())
        })
        .fold(0.0, f32::max);
    assert!(worst > 0.2, "an unlocked capsule tilted only {worst} rad");
}

#[test]
fn struck_capsule_with_locked_rotation_takes_a_one_dimensional_elastic_collision() {
    // No gravity; a 1 kg ball at 4 m/s meets a 2 kg capsule side-on, 0.4 m above its centre,
    // both with restitution 1. With rotation locked the capsule answers at the contact with
    // its mass alone, so this is the head-on elastic collision of two point masses:
    // v_capsule = 2 m₁ v / (m₁ + m₂), v_ball = (m₁ − m₂) v / (m₁ + m₂).
    let mut world = world(Vec3::ZERO);
    let (m1, m2, speed) = (1.0_f32, 2.0_f32, 4.0_f32);
    let capsule = world
        .add_body(
            BodyDesc::dynamic(Shape::capsule(0.3, 0.6).unwrap())
                .mass(m2)
                .restitution(1.0)
                .locked_axes(LockedAxes::ROTATION),
        )
        .unwrap();
    let ball = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(0.2).unwrap())
                .position(Vec3::new(1.0, 0.4, 0.0))
                .linear_velocity(Vec3::new(-speed, 0.0, 0.0))
                .mass(m1)
                .restitution(1.0),
        )
        .unwrap();
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let capsule_velocity = world.body(capsule).unwrap().linear_velocity();
    let ball_velocity = world.body(ball).unwrap().linear_velocity();
    let expected_capsule = -2.0 * m1 * speed / (m1 + m2);
    let expected_ball = -(m1 - m2) * speed / (m1 + m2);
    // One contact point along x, solved exactly (Newton's restitution for a single point):
    // what is left is f32 rounding over the substeps (measured 1e-7 of the speed).
    let tolerance = 1e-4 * speed;
    assert!(
        (capsule_velocity.x - expected_capsule).abs() < tolerance,
        "capsule {capsule_velocity}, expected x {expected_capsule}"
    );
    assert!(
        (ball_velocity.x - expected_ball).abs() < tolerance,
        "ball {ball_velocity}, expected x {expected_ball}"
    );
    assert_eq!(world.body(capsule).unwrap().angular_velocity(), Vec3::ZERO);
}

#[test]
fn body_locked_along_y_holds_its_height_under_gravity_and_load() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let height = 2.0;
    let force = Vec3::new(3.0, 5.0, 0.0);
    let mass = 4.0;
    let platform = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::new(1.0, 0.1, 1.0)).unwrap())
                .position(Vec3::new(0.0, height, 0.0))
                .mass(mass)
                .constant_force(force)
                .can_sleep(false)
                .locked_axes(LockedAxes {
                    translation: [false, true, false],
                    rotation: [true, true, true],
                }),
        )
        .unwrap();
    // A ball dropped onto it: the platform carries its weight without sinking a bit.
    let ball = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(0.25).unwrap())
                .position(Vec3::new(0.0, height + 1.0, 0.0))
                .can_sleep(false),
        )
        .unwrap();
    for _ in 0..120 {
        world.step(DT).unwrap();
        let body = world.body(platform).unwrap();
        assert_eq!(body.position().y, height);
        assert_eq!(body.linear_velocity().y, 0.0);
    }
    // Along x it is free: the force drives it, and the ball it carries by friction (rolling, so
    // it takes part of the force) slows it. Its speed lies between sharing the whole force with
    // the ball, F_x t / (m + m_ball), and carrying nothing, F_x t / m.
    let vx = world.body(platform).unwrap().linear_velocity().x;
    let ball_mass = world.body(ball).unwrap().mass();
    let time = 120.0 * DT;
    let (low, high) = (force.x / (mass + ball_mass) * time, force.x / mass * time);
    assert!(
        vx > low * 0.99 && vx < high * 1.01,
        "vx {vx} outside [{low}, {high}]"
    );
    let ball_height = world.body(ball).unwrap().position().y;
    // Resting on the top face at height + 0.1, within the contact's sag and 1 mm of rounding.
    assert!(
        (ball_height - (height + 0.1 + 0.25)).abs() < 5e-3,
        "ball at {ball_height}"
    );
}

#[test]
fn free_axis_turns_with_the_inertia_about_it_not_the_inverse_inertia_entry() {
    // A box tilted 30° about X has world inertia with an off-diagonal y–z term. Locked about X
    // and Z, a torque τ about Y spins it at ω_y = τ t / I_yy (the momentum about Y,
    // `I_yy ω_y`, grows by τ t, and I_yy does not change as it turns about Y). Zeroing the
    // locked rows of I⁻¹ instead would give τ t (I⁻¹)_yy, here about 9 % more.
    let mut world = world(Vec3::ZERO);
    let rotation = Quat::from_rotation_x(30f32.to_radians());
    let torque = 0.5;
    let body = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::new(0.3, 0.5, 0.9)).unwrap())
                .rotation(rotation)
                .mass(3.0)
                .constant_torque(Vec3::new(0.2, torque, -0.4))
                .locked_axes(LockedAxes {
                    translation: [false; 3],
                    rotation: [true, false, true],
                }),
        )
        .unwrap();
    let world_inertia = world.body(body).unwrap().world_inertia();
    let i_yy = world_inertia.y_axis.y;
    let naive = world_inertia.inverse().y_axis.y;
    assert!(
        (naive * i_yy - 1.0).abs() > 0.05,
        "the test needs a tilted inertia"
    );
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let omega = world.body(body).unwrap().angular_velocity();
    let expected = torque * (60.0 * DT) / i_yy;
    assert_eq!((omega.x, omega.z), (0.0, 0.0));
    // The torque adds h τ / I_yy per substep: only f32 rounding of 480 additions remains
    // (measured 3e-6 of ω_y), far from the 9 % of the wrong inverse.
    assert!(
        (omega.y - expected).abs() < 1e-5 * expected,
        "ω_y {} against τt/I_yy {expected}",
        omega.y
    );
}

#[test]
fn pendulum_locked_out_of_its_plane_stays_in_it() {
    // A ball pendulum on a ball joint, pushed sideways out of its swing plane (z = 0), with
    // translation along z locked: the bob swings in the plane, to the bit, and keeps the joint.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let bob = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(0.1).unwrap())
                .position(Vec3::new(1.0, 0.0, 0.0))
                .constant_force(Vec3::new(0.0, 0.0, 30.0))
                .locked_axes(LockedAxes {
                    translation: [false, false, true],
                    rotation: [false; 3],
                }),
        )
        .unwrap();
    world
        .add_joint(JointDesc::ball(None, bob, Vec3::ZERO))
        .unwrap();
    let mut lowest = 0.0_f32;
    for _ in 0..180 {
        world.step(DT).unwrap();
        let body = world.body(bob).unwrap();
        assert_eq!(body.position().z, 0.0);
        // The joint holds the bob 1 m from the pivot, within its soft correction (1 cm).
        assert!((body.position().length() - 1.0).abs() < 1e-2);
        lowest = lowest.min(body.position().y);
    }
    // Released level, it swings through the bottom of the arc.
    assert!(lowest < -0.99, "lowest {lowest}");
}

#[test]
fn locking_a_moving_body_stops_its_motion_along_the_lock() {
    let mut world = world(Vec3::ZERO);
    let body = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(0.5).unwrap())
                .linear_velocity(Vec3::new(1.0, 2.0, 3.0))
                .angular_velocity(Vec3::new(4.0, 5.0, 6.0)),
        )
        .unwrap();
    world.body_mut(body).unwrap().set_locked_axes(LockedAxes {
        translation: [false, true, false],
        rotation: [true, false, false],
    });
    let body = world.body(body).unwrap();
    assert_eq!(body.linear_velocity(), Vec3::new(1.0, 0.0, 3.0));
    assert_eq!(body.angular_velocity(), Vec3::new(0.0, 5.0, 6.0));
    assert_eq!(body.inverse_mass_diagonal().y, 0.0);
}

#[test]
fn scene_files_lock_axes_by_name() {
    let json = r#"{"gravity": [0, -9.81, 0], "bodies": [
        {"name": "slider", "shape": {"type": "sphere", "radius": 0.5},
         "locked_axes": {"translation": [false, true, false]}},
        {"name": "upright", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]},
         "locked_axes": {"rotation": [true, true, true]}},
        {"name": "free", "shape": {"type": "sphere", "radius": 0.5}, "position": [5, 0, 0]}]}"#;
    let mut scene = rebond::scene::Scene::from_json(json.as_bytes()).unwrap();
    for _ in 0..30 {
        scene.step().unwrap();
    }
    let world = scene.world();
    let locks: Vec<LockedAxes> = world.bodies().map(|(_, body)| body.locked_axes()).collect();
    assert_eq!(
        locks,
        [
            LockedAxes {
                translation: [false, true, false],
                rotation: [false; 3],
            },
            LockedAxes::ROTATION,
            LockedAxes::NONE,
        ]
    );
    let heights: Vec<f32> = world.bodies().map(|(_, body)| body.position().y).collect();
    // The slider holds y = 0 under gravity; the others fall freely for half a second.
    assert_eq!(heights[0], 0.0);
    assert!(heights[1] < -1.0 && heights[2] < -1.0, "{heights:?}");
}
