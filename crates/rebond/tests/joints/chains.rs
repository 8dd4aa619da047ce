//! Chains and ragdolls: joints that hold under heavy loads and in piles.

use super::{add, world, DT, G};
use rebond::{BodyDesc, BodyHandle, JointDesc, JointHandle, Quat, Shape, Vec3, World};
use std::f32::consts::FRAC_PI_2;

/// How far apart the two anchors of every joint are, summed, and the worst single gap, m.
fn gaps(world: &World, joints: &[JointHandle]) -> (f32, f32) {
    joints.iter().fold((0.0, 0.0), |(sum, worst), &joint| {
        let placement = world.joint_placement(joint).unwrap();
        let gap = (placement.anchor_b - placement.anchor_a).length();
        (sum + gap, worst.max(gap))
    })
}

/// Ten 1 kg links, 0.2 m long, hanging from the world on ball joints, with `weight` kg hung at
/// the end; released from `tilt` (rad about Z). Returns the world, the joints and the weight.
fn chain_with_weight(weight: f32, tilt: f32) -> (World, Vec<JointHandle>, BodyHandle) {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let turn = Quat::from_rotation_z(tilt);
    let down = turn * Vec3::new(0.0, -1.0, 0.0);
    let mut joints = Vec::new();
    let mut previous = None;
    let link = Shape::capsule(0.04, 0.08).unwrap();
    for index in 0..10 {
        let top = down * (0.2 * index as f32);
        let body = add(
            &mut world,
            BodyDesc::dynamic(link.clone())
                .mass(1.0)
                .position(top + down * 0.1)
                .rotation(turn),
        );
        joints.push(
            world
                .add_joint(JointDesc::ball(previous, body, top))
                .unwrap(),
        );
        previous = Some(body);
    }
    let end = down * 2.0;
    let load = add(
        &mut world,
        BodyDesc::dynamic(Shape::sphere(0.15).unwrap())
            .mass(weight)
            .position(end + down * 0.15),
    );
    joints.push(
        world
            .add_joint(JointDesc::ball(previous, load, end))
            .unwrap(),
    );
    (world, joints, load)
}

#[test]
fn a_chain_of_light_links_holds_a_hundred_and_a_thousand_times_heavier_weight() {
    // 1:100 and 1:1000 mass ratios, the classic failure of impulse joints (such a chain
    // stretches by metres under iterative solvers): the chain must not stretch by a centimetre
    // in all, hanging still or swinging from 45°.
    for (weight, tilt) in [0.0, 0.25 * std::f32::consts::PI]
        .into_iter()
        .flat_map(|tilt| [(100.0, tilt), (1000.0, tilt)])
    {
        let (mut world, joints, _) = chain_with_weight(weight, tilt);
        let mut worst_stretch = 0.0_f32;
        for _ in 0..300 {
            world.step(DT).unwrap();
            worst_stretch = worst_stretch.max(gaps(&world, &joints).0);
        }
        assert!(
            worst_stretch < 0.01,
            "{weight} kg released at {tilt} rad: the chain stretched {worst_stretch} m in all"
        );
    }
}

/// Joint friction of the ragdoll's joints, N·m: each is 4–12 % of the torque of the parts it
/// carries held out level (head 6.9 N·m at the neck, arm 12 at the shoulder, forearm 2.6 at the
/// elbow, leg 44 at the hip, shin 8.6 at the knee), as the stiffness of real joints gives. It is
/// what brings a pile to rest: a limb that jointed parts let pass through its own body (an arm
/// over its torso) otherwise swings on as a frictionless pendulum.
const NECK_FRICTION: f32 = 0.5;
const SHOULDER_FRICTION: f32 = 0.5;
const ELBOW_FRICTION: f32 = 0.3;
const HIP_FRICTION: f32 = 2.0;
const KNEE_FRICTION: f32 = 1.0;

/// A ragdoll, its feet at `base` and turned by `turn` from standing up: torso, head, arms and
/// legs of two parts each, joined by ball joints (neck, shoulders, hips) with swing and twist
/// limits and hinges (elbows, knees) with limits. Returns its joints.
fn ragdoll(world: &mut World, base: Vec3, turn: Quat) -> Vec<JointHandle> {
    let at = |offset: Vec3| base + turn * offset;
    let part = |world: &mut World, shape: Shape, centre: Vec3, mass: f32| {
        add(
            world,
            BodyDesc::dynamic(shape)
                .mass(mass)
                .position(at(centre))
                .rotation(turn),
        )
    };
    let limb = |world: &mut World, radius: f32, half_height: f32, centre: Vec3, mass: f32| {
        part(
            world,
            Shape::capsule(radius, half_height).unwrap(),
            centre,
            mass,
        )
    };
    let torso = part(
        world,
        Shape::cuboid(Vec3::new(0.18, 0.3, 0.1)).unwrap(),
        Vec3::new(0.0, 1.25, 0.0),
        30.0,
    );
    let head = part(
        world,
        Shape::cuboid(Vec3::splat(0.11)).unwrap(),
        Vec3::new(0.0, 1.7, 0.0),
        5.0,
    );
    let mut joints = Vec::new();
    let mut join = |world: &mut World, desc: JointDesc| joints.push(world.add_joint(desc).unwrap());
    join(
        world,
        JointDesc::ball(torso, head, at(Vec3::new(0.0, 1.56, 0.0)))
            .axis(turn * Vec3::Y)
            .swing_limit(0.6)
            .twist_limits(-0.8, 0.8)
            .friction(NECK_FRICTION),
    );
    for side in [-1.0_f32, 1.0] {
        let upper_arm = limb(world, 0.05, 0.12, Vec3::new(side * 0.25, 1.35, 0.0), 2.5);
        let lower_arm = limb(world, 0.045, 0.11, Vec3::new(side * 0.25, 1.0, 0.0), 1.5);
        let thigh = limb(world, 0.07, 0.16, Vec3::new(side * 0.1, 0.7, 0.0), 8.0);
        let shin = limb(world, 0.06, 0.15, Vec3::new(side * 0.1, 0.25, 0.0), 4.0);
        join(
            world,
            JointDesc::ball(torso, upper_arm, at(Vec3::new(side * 0.25, 1.52, 0.0)))
                .axis(turn * Vec3::NEG_Y)
                .swing_limit(FRAC_PI_2)
                .twist_limits(-0.7, 0.7)
                .friction(SHOULDER_FRICTION),
        );
        join(
            world,
            JointDesc::revolute(
                upper_arm,
                lower_arm,
                at(Vec3::new(side * 0.25, 1.18, 0.0)),
                turn * Vec3::X,
            )
            .limits(-2.4, 0.0)
            .friction(ELBOW_FRICTION),
        );
        join(
            world,
            JointDesc::ball(torso, thigh, at(Vec3::new(side * 0.1, 0.92, 0.0)))
                .axis(turn * Vec3::NEG_Y)
                .swing_limit(1.2)
                .twist_limits(-0.5, 0.5)
                .friction(HIP_FRICTION),
        );
        join(
            world,
            JointDesc::revolute(
                thigh,
                shin,
                at(Vec3::new(side * 0.1, 0.47, 0.0)),
                turn * Vec3::X,
            )
            .limits(0.0, 2.4)
            .friction(KNEE_FRICTION),
        );
    }
    joints
}

/// Twelve ragdolls dropped lying down on each other, crossed, from up to 5.2 m (hitting at up to
/// 10 m/s), no damping, each body's sleeping as `can_sleep` says. Returns the world and the joints.
fn ragdoll_pile(can_sleep: bool) -> (World, Vec<JointHandle>) {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(10.0, 0.5, 10.0)).unwrap())
                .position(Vec3::new(0.0, -0.5, 0.0)),
        )
        .unwrap();
    let mut joints = Vec::new();
    for index in 0..12 {
        let height = 0.3 + 0.45 * index as f32;
        let lying =
            Quat::from_rotation_y(FRAC_PI_2 * index as f32) * Quat::from_rotation_x(FRAC_PI_2);
        let base = Vec3::new(0.0, height, 0.0) - lying * Vec3::new(0.0, 0.9, 0.0);
        joints.extend(ragdoll(&mut world, base, lying));
    }
    let bodies: Vec<BodyHandle> = world.bodies().map(|(handle, _)| handle).collect();
    for body in bodies {
        world.body_mut(body).unwrap().set_can_sleep(can_sleep);
    }
    (world, joints)
}

#[test]
fn a_pile_of_ragdolls_keeps_every_joint_closed_and_comes_to_rest() {
    // Sleeping off. Every joint's anchors stay within 1 cm of each other throughout (measured
    // 2.3 mm). The last ragdoll lands after √(2 · 5.2 m / g) = 1.03 s; from 10 s after that, for
    // two seconds, four times the sleep time, every point of every body moves slower than the
    // sleep speed (5 cm/s): the pile is at rest as sleeping would see it, and holds still
    // rather than creeping or jittering (measured: every point under 5 cm/s from 4.6 s on, under
    // 0.4 mm/s from 5 s on). Its energy, from 2 s on, never rises above its lowest value so far
    // by more than 0.2 J: the settled pile still creeps, forearms sliding a fraction of a
    // millimetre over 20 s (measured 0.06 J over 15 s, the same again in the 20 s after); a
    // bounce or a swing fed by contacts and joints would add joules within a second.
    let (mut world, joints) = ragdoll_pile(false);
    let sleep_speed = world.settings().sleep_speed;
    let (mut worst_gap, mut worst_speed) = (0.0_f32, 0.0_f32);
    let (mut lowest, mut worst_rise) = (f32::INFINITY, 0.0_f32);
    for step in 0..780 {
        world.step(DT).unwrap();
        worst_gap = worst_gap.max(gaps(&world, &joints).1);
        if step >= 120 {
            let energy = world.total_energy();
            lowest = lowest.min(energy);
            worst_rise = worst_rise.max(energy - lowest);
        }
        if step >= 660 {
            for (_, body) in world.bodies() {
                worst_speed = worst_speed.max(body.max_point_speed());
            }
        }
    }
    assert!(worst_gap < 0.01, "a joint opened {worst_gap} m");
    assert!(
        worst_speed < sleep_speed,
        "a point still moves at {worst_speed} m/s 10 s after landing"
    );
    assert!(worst_rise < 0.2, "the pile gained {worst_rise} J");
}

#[test]
fn a_pile_of_ragdolls_falls_asleep_within_ten_seconds_of_landing() {
    // The same pile with sleeping on, as a game runs it: every body asleep 10 s after the last
    // ragdoll lands (measured: all asleep at 5.1 s).
    let (mut world, _) = ragdoll_pile(true);
    for _ in 0..660 {
        world.step(DT).unwrap();
    }
    let awake = world
        .bodies()
        .filter(|(_, body)| !body.is_sleeping())
        .count();
    assert_eq!(
        awake, 1,
        "{awake} bodies awake, the static ground among them"
    );
}
