//! Durable saves: a state read by another build is rebuilt from its portable snapshot. Bodies,
//! joints, handles, settings and sleep are kept; contacts start cold; damaged snapshots are
//! refused, never a panic.

use rebond::scene::Scene;
use rebond::state::StateError;
use rebond::{
    BodyDesc, BodyHandle, CombineRule, CompoundChild, InteractionGroups, JointDesc, JointHandle,
    KinematicPath, LockedAxes, Motor, PathPoint, Pose, Quat, Shape, Vec3, World, WorldSettings,
};

const DT: f32 = 1.0 / 60.0;

fn hull() -> Shape {
    Shape::convex_hull(&[
        Vec3::new(-0.3, 0.0, -0.3),
        Vec3::new(0.3, 0.0, -0.3),
        Vec3::new(0.3, 0.0, 0.3),
        Vec3::new(-0.3, 0.0, 0.3),
        Vec3::new(0.0, 0.5, 0.0),
    ])
    .unwrap()
}

/// A world with every shape kind, every joint kind (limits, motors, a spring, friction, a joint
/// that breaks), a locked body, a kinematic body on a looping path, a body asleep, an ignored
/// pair, a removed body (a stale handle) and a removed joint, stepped some.
struct Everything {
    world: World,
    bodies: Vec<BodyHandle>,
    joints: Vec<JointHandle>,
    removed_body: BodyHandle,
    removed_joint: JointHandle,
    sleeper: BodyHandle,
    ignored: (BodyHandle, BodyHandle),
    wheel_hinge: JointHandle,
    breaking: JointHandle,
}

fn everything() -> Everything {
    let settings = WorldSettings {
        substeps: 6,
        friction_combine: CombineRule::Max,
        restitution_combine: CombineRule::Average,
        sleep_time: 0.3,
        ..WorldSettings::default()
    };
    let mut world = World::new(settings).unwrap();
    let mut bodies = Vec::new();
    let mut add = |world: &mut World, desc: BodyDesc| {
        let handle = world.add_body(desc).unwrap();
        bodies.push(handle);
        handle
    };
    let floor = add(
        &mut world,
        BodyDesc::static_body(Shape::cuboid(Vec3::new(20.0, 0.5, 20.0)).unwrap())
            .position(Vec3::new(0.0, -0.5, 0.0))
            .friction(0.7),
    );
    let removed_body = world
        .add_body(BodyDesc::dynamic(Shape::sphere(0.1).unwrap()).position(Vec3::Y * 30.0))
        .unwrap();
    add(
        &mut world,
        BodyDesc::static_body(Shape::halfspace(Vec3::Y).unwrap()).position(Vec3::Y * -3.0),
    );
    let heights = vec![
        vec![0.0, 0.2, 0.1],
        vec![0.1, 0.6, 0.0],
        vec![0.0, 0.3, 0.2],
    ];
    add(
        &mut world,
        BodyDesc::static_body(Shape::heightfield(&heights, Vec3::new(4.0, 1.0, 4.0)).unwrap())
            .position(Vec3::new(30.0, 0.0, 0.0)),
    );
    let mesh = Shape::trimesh(
        vec![
            Vec3::new(-2.0, 0.0, -2.0),
            Vec3::new(2.0, 1.0, -2.0),
            Vec3::new(2.0, 1.0, 2.0),
            Vec3::new(-2.0, 0.0, 2.0),
        ],
        &[[0, 1, 2], [0, 2, 3]],
    )
    .unwrap();
    add(
        &mut world,
        BodyDesc::static_body(mesh).position(Vec3::new(0.0, 0.0, 30.0)),
    );
    let ball = add(
        &mut world,
        BodyDesc::dynamic(Shape::sphere(0.3).unwrap())
            .position(Vec3::new(-3.0, 1.0, 0.0))
            .linear_velocity(Vec3::new(2.0, 0.0, 0.5))
            .restitution(0.4)
            .rolling_resistance(0.02)
            .user_data(0xdead_beef_0000_0001),
    );
    let crate_ = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::new(0.3, 0.2, 0.4)).unwrap())
            .position(Vec3::new(-1.5, 0.8, 1.0))
            .rotation(Quat::from_rotation_y(0.4))
            .mass(7.5)
            .damping(0.1, 0.2)
            .constant_force_at_point(Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.1, 0.0))
            .constant_torque(Vec3::new(0.0, 0.5, 0.0))
            .contact_force_threshold(20.0),
    );
    let pill = add(
        &mut world,
        BodyDesc::dynamic(Shape::capsule(0.2, 0.3).unwrap())
            .position(Vec3::new(0.0, 1.5, -1.0))
            .locked_axes(LockedAxes::ROTATION),
    );
    add(
        &mut world,
        BodyDesc::dynamic(Shape::cylinder(0.3, 0.2).unwrap())
            .position(Vec3::new(1.5, 0.6, -1.0))
            .angular_velocity(Vec3::new(0.0, 0.0, 3.0))
            .collision_groups(InteractionGroups::new(0b011, 0b101)),
    );
    add(
        &mut world,
        BodyDesc::dynamic(hull()).position(Vec3::new(3.0, 0.2, 1.0)),
    );
    let compound = Shape::compound(vec![
        CompoundChild::new(
            Shape::sphere(0.2).unwrap(),
            Pose::from_position(-0.4 * Vec3::X),
        )
        .rolling_resistance(0.1)
        .friction(0.9)
        .name("foot")
        .sensor(true)
        .user_data(7),
        CompoundChild::new(hull(), Pose::from_position(0.4 * Vec3::X))
            .restitution(0.7)
            .collision_groups(InteractionGroups::new(0b10, 0b01)),
    ])
    .unwrap();
    add(
        &mut world,
        BodyDesc::dynamic(compound).position(Vec3::new(0.0, 2.5, 2.0)),
    );
    add(
        &mut world,
        BodyDesc::dynamic(Shape::sphere(1.0).unwrap())
            .position(Vec3::new(6.0, 2.0, 6.0))
            .sensor(true),
    );
    let path = KinematicPath::new(vec![
        PathPoint::new(0.0, Vec3::new(-6.0, 1.0, 6.0), Quat::IDENTITY),
        PathPoint::new(1.0, Vec3::new(-4.0, 1.0, 6.0), Quat::from_rotation_y(1.0)),
        PathPoint::new(2.0, Vec3::new(-6.0, 1.0, 6.0), Quat::IDENTITY),
    ])
    .looping(true);
    add(
        &mut world,
        BodyDesc::kinematic(Shape::cuboid(Vec3::new(1.0, 0.1, 1.0)).unwrap()).path(path),
    );
    let sleeper = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.25)).unwrap())
            .position(Vec3::new(10.0, 0.25, -10.0)),
    );
    // Jointed bodies, hung high above the floor.
    let glued = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.1)).unwrap())
            .position(Vec3::new(-1.5, 1.2, 1.0)),
    );
    let bob = add(
        &mut world,
        BodyDesc::dynamic(Shape::sphere(0.2).unwrap()).position(Vec3::new(2.0, 8.0, 3.0)),
    );
    let wheel = add(
        &mut world,
        BodyDesc::dynamic(Shape::cylinder(0.5, 0.1).unwrap())
            .position(Vec3::new(-4.0, 8.0, -3.0))
            .rotation(Quat::from_rotation_x(std::f32::consts::FRAC_PI_2)),
    );
    let slider = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.2)).unwrap())
            .position(Vec3::new(4.0, 8.0, -3.0)),
    );
    let weight = add(
        &mut world,
        BodyDesc::dynamic(Shape::sphere(0.15).unwrap()).position(Vec3::new(-2.0, 7.0, -4.0)),
    );
    let snapped = add(
        &mut world,
        BodyDesc::dynamic(Shape::sphere(0.15).unwrap()).position(Vec3::new(8.0, 8.0, -4.0)),
    );
    let joints = vec![
        world
            .add_joint(JointDesc::fixed(crate_, glued, Vec3::new(-1.5, 1.0, 1.0)))
            .unwrap(),
        world
            .add_joint(
                JointDesc::ball(None, bob, Vec3::new(2.0, 9.0, 3.0))
                    .axis(-Vec3::Y)
                    .swing_limit(0.8)
                    .twist_limits(-0.5, 0.5)
                    .friction(0.05),
            )
            .unwrap(),
        world
            .add_joint(
                JointDesc::revolute(None, wheel, Vec3::new(-4.0, 8.0, -3.0), Vec3::Z)
                    .motor(Motor::velocity(20.0, 1000.0)),
            )
            .unwrap(),
        world
            .add_joint(
                JointDesc::prismatic(None, slider, Vec3::new(4.0, 8.0, -3.0), Vec3::X)
                    .limits(-0.5, 1.0)
                    .motor(Motor::position(0.5, 50.0, 5.0, f32::INFINITY)),
            )
            .unwrap(),
        world
            .add_joint(
                JointDesc::distance(
                    None,
                    weight,
                    Vec3::new(-2.0, 8.0, -4.0),
                    Vec3::new(-2.0, 7.0, -4.0),
                )
                .spring(40.0, 0.5)
                .limits(0.5, 1.5),
            )
            .unwrap(),
        world
            .add_joint(
                JointDesc::distance(
                    None,
                    snapped,
                    Vec3::new(8.0, 9.0, -4.0),
                    Vec3::new(8.0, 8.0, -4.0),
                )
                .break_force(0.5),
            )
            .unwrap(),
    ];
    let removed_joint = world
        .add_joint(JointDesc::ball(ball, pill, Vec3::new(-1.5, 1.0, -0.5)))
        .unwrap();
    world.remove_joint(removed_joint).unwrap();
    world.remove_body(removed_body).unwrap();
    world.set_pair_ignored(pill, floor, true).unwrap();
    world.set_pair_ignored(pill, floor, false).unwrap();
    world.set_pair_ignored(crate_, pill, true).unwrap();
    for _ in 0..90 {
        world.step(DT).unwrap();
    }
    // Applied since the last step: kept in the snapshot.
    world
        .body_mut(pill)
        .unwrap()
        .apply_force(Vec3::X * 3.0)
        .unwrap();
    Everything {
        wheel_hinge: joints[2],
        breaking: joints[5],
        world,
        bodies,
        joints,
        removed_body,
        removed_joint,
        sleeper,
        ignored: (crate_, pill),
    }
}

/// Every value of a body a user reads, as bits where they must be equal.
fn body_bits(world: &World, handle: BodyHandle) -> Vec<u64> {
    let body = world.body(handle).unwrap();
    let vectors = [
        body.position(),
        body.center_of_mass(),
        body.local_center_of_mass(),
        body.linear_velocity(),
        body.angular_velocity(),
        body.constant_force(),
        body.constant_force_point().unwrap_or(Vec3::NAN),
        body.constant_torque(),
    ];
    let mut bits: Vec<u64> = vectors
        .iter()
        .flat_map(|v| v.to_array())
        .chain(body.rotation().to_array())
        .chain(body.local_inertia().to_cols_array())
        .chain(body.world_inverse_inertia().to_cols_array())
        .chain([
            body.mass(),
            body.inverse_mass(),
            body.friction(),
            body.restitution(),
            body.rolling_resistance(),
            body.damping().0,
            body.damping().1,
            body.contact_force_threshold(),
        ])
        .map(|value| u64::from(value.to_bits()))
        .collect();
    let groups = body.collision_groups();
    bits.extend([
        u64::from(body.is_sleeping()),
        u64::from(body.can_sleep()),
        u64::from(body.is_sensor()),
        u64::from(groups.memberships),
        u64::from(groups.filter),
        body.user_data() as u64,
        (body.user_data() >> 64) as u64,
        body.path_time().to_bits(),
    ]);
    bits
}

#[test]
fn a_world_rebuilt_from_its_snapshot_keeps_its_bodies_joints_and_handles() {
    let saved = everything();
    let world = &saved.world;
    assert!(
        world.body(saved.sleeper).unwrap().is_sleeping(),
        "the sleeper sleeps"
    );
    assert!(
        world.joint(saved.breaking).unwrap().is_broken(),
        "the weak joint broke"
    );
    let turns = world.joint_position(saved.wheel_hinge).unwrap();
    assert!(
        turns > std::f32::consts::TAU,
        "the wheel turned more than once: {turns}"
    );

    let bytes = world.save_state();
    let restored = World::load_state_as_other_build(&bytes).unwrap();
    assert_eq!(restored.settings(), world.settings());
    assert_eq!(restored.body_count(), world.body_count());
    let mut compounds = 0;
    for &handle in &saved.bodies {
        let (before, after) = (world.body(handle).unwrap(), restored.body(handle).unwrap());
        assert_eq!(
            body_bits(&restored, handle),
            body_bits(world, handle),
            "body {handle:?}"
        );
        assert_eq!(after.body_type(), before.body_type());
        assert_eq!(after.locked_axes(), before.locked_axes());
        assert_eq!(after.path(), before.path());
        assert_eq!(after.kinematic_target(), before.kinematic_target());
        // Hulls are rebuilt from their vertices: the same solid, compared by its support points.
        let directions = [Vec3::X, -Vec3::Y, Vec3::new(1.0, 2.0, -3.0).normalize()];
        for direction in directions {
            assert_eq!(
                after.shape().support(direction),
                before.shape().support(direction)
            );
        }
        assert_eq!(
            after.shape().aabb(&Pose::IDENTITY),
            before.shape().aabb(&Pose::IDENTITY)
        );
        // A compound's colliders keep their own fields.
        if let (Shape::Compound(after), Shape::Compound(before)) = (after.shape(), before.shape()) {
            let fields = |child: &CompoundChild| {
                (
                    child.name.clone(),
                    child.sensor,
                    child.collision_groups,
                    child.user_data,
                    child.friction,
                    child.restitution,
                    child.rolling_resistance,
                )
            };
            let after: Vec<_> = after.children().iter().map(fields).collect();
            let before: Vec<_> = before.children().iter().map(fields).collect();
            assert_eq!(after, before);
            assert_eq!(before[0].0.as_deref(), Some("foot"));
            compounds += 1;
        }
    }
    assert_eq!(compounds, 1);
    assert_eq!(restored.joints().count(), world.joints().count());
    for &handle in &saved.joints {
        let (before, after) = (
            world.joint(handle).unwrap(),
            restored.joint(handle).unwrap(),
        );
        assert_eq!(after.desc(), before.desc());
        assert_eq!(after.is_broken(), before.is_broken());
        assert_eq!(after.force(), before.force());
        assert_eq!(after.torque(), before.torque());
        // The frames in each body: the joints' anchors and axes where the bodies stand now.
        assert_eq!(
            restored.joint_placement(handle).ok(),
            world.joint_placement(handle).ok()
        );
        if let Ok(position) = world.joint_position(handle) {
            assert_eq!(
                restored.joint_position(handle).unwrap().to_bits(),
                position.to_bits()
            );
        }
    }
    // Handles: stale ones stay stale, the world's identity is kept, another world's is refused.
    assert!(restored.body(saved.removed_body).is_err());
    assert!(restored.joint(saved.removed_joint).is_err());
    let other = everything();
    assert!(restored.body(other.bodies[0]).is_err());
    let (a, b) = saved.ignored;
    assert!(restored.is_pair_ignored(a, b));
    assert_eq!(restored.sleeping_body_count(), world.sleeping_body_count());
    // Contacts start cold; the next step makes them again.
    assert_eq!(restored.contact_count(), 0);
    assert!(world.contact_count() > 0);

    let mut restored = restored;
    for _ in 0..120 {
        restored.step(DT).unwrap();
    }
    assert!(restored.contact_count() > 0);
    let mut original = saved.world.clone();
    for _ in 0..120 {
        original.step(DT).unwrap();
    }
    let worst = restored
        .bodies()
        .map(|(handle, body)| {
            let exact = original.body(handle).unwrap();
            (body.position() - exact.position()).length()
        })
        .fold(0.0_f32, f32::max);
    // Only the contacts' warm start differs from the exact world's: a cold contact settles
    // within its sag under load, g / (2π · 120 Hz)² = 0.017 mm, of the warm one's pose; six
    // sags allow for the few steps the impulses take to build up again.
    assert!(
        worst < 1e-4,
        "{worst} m from where the exact world has a body"
    );
    assert!(restored.body(saved.sleeper).unwrap().is_sleeping());
    // A body added after the load takes the slot the saved world would have given it.
    let mut exact = World::load_state(&bytes).unwrap();
    let desc = BodyDesc::dynamic(Shape::sphere(0.1).unwrap());
    let (next_exact, next_restored) = (
        exact.add_body(desc.clone()).unwrap(),
        World::load_state_as_other_build(&bytes)
            .unwrap()
            .add_body(desc)
            .unwrap(),
    );
    assert_eq!(next_exact, next_restored);
}

#[test]
fn a_resting_box_restored_cold_stays_at_rest() {
    let mut world = World::new(WorldSettings::default()).unwrap();
    world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(5.0, 0.5, 5.0)).unwrap())
                .position(Vec3::Y * -0.5),
        )
        .unwrap();
    let cube = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.5)).unwrap())
                .position(Vec3::Y * 0.5)
                .can_sleep(false),
        )
        .unwrap();
    for _ in 0..120 {
        world.step(DT).unwrap();
    }
    let rest = world.body(cube).unwrap().position();
    let mut restored = World::load_state_as_other_build(&world.save_state()).unwrap();
    let (mut drift, mut speed) = (0.0_f32, 0.0_f32);
    for _ in 0..120 {
        restored.step(DT).unwrap();
        let body = restored.body(cube).unwrap();
        drift = drift.max((body.position() - rest).length());
        speed = speed.max(body.linear_velocity().length());
    }
    // A cold contact takes the box's weight from its first substep: the box neither sinks nor
    // jumps. 10 µm is below the contact's sag under the box's weight, g / (2π · 120 Hz)² =
    // 17 µm, so the box does not settle to another rest; 1 mm/s is a 160th of the speed one
    // step of free fall gives (g dt = 0.16 m/s).
    assert!(drift < 1e-5, "worst drift {drift} m");
    assert!(speed < 1e-3, "worst speed {speed} m/s");
}

/// A small world's state and where its snapshot starts.
fn small_state() -> (Vec<u8>, usize) {
    let json = r#"{"bodies": [
      {"type": "static", "shape": {"type": "box", "half_extents": [4, 0.5, 4]}, "position": [0, -0.5, 0]},
      {"shape": {"type": "box", "half_extents": [0.3, 0.3, 0.3]}, "position": [0, 0.3, 0]},
      {"shape": {"type": "sphere", "radius": 0.2}, "position": [1, 1, 0]},
      {"name": "bob", "shape": {"type": "sphere", "radius": 0.1}, "position": [-1, 1, 0]}],
      "joints": [{"type": "revolute", "body_b": "bob", "anchor": [-1, 1.5, 0], "axis": [0, 0, 1],
                  "limits": [-1, 1]}]}"#;
    let mut world = Scene::from_json(json.as_bytes()).unwrap().world().clone();
    for _ in 0..40 {
        world.step(DT).unwrap();
    }
    let bytes = world.save_state();
    let exact_length = u64::from_le_bytes(bytes[32..40].try_into().unwrap()) as usize;
    (bytes, 40 + exact_length)
}

/// `bytes` with the checksum made to match.
fn with_checksum(mut bytes: Vec<u8>) -> Vec<u8> {
    let checksum = crc32fast::hash(&bytes[32..]);
    bytes[28..32].copy_from_slice(&checksum.to_le_bytes());
    bytes
}

#[test]
fn a_snapshot_changed_to_match_its_checksum_is_refused_or_restores_a_world_that_steps() {
    // Every byte of a small world's snapshot, changed three ways, the checksum made to match:
    // refused as undecodable or inconsistent (or, its version byte, as a later build's), or
    // restored to a world whose bodies stay finite. Never a panic.
    let (bytes, start) = small_state();
    let (mut refused, mut restored) = (0, 0);
    for position in start..bytes.len() {
        for change in [0x01, 0x80, 0xff] {
            let mut changed = bytes.clone();
            changed[position] ^= change;
            match World::load_state_as_other_build(&with_checksum(changed)) {
                Ok(mut world) => {
                    restored += 1;
                    if world.step(DT).is_ok() {
                        let finite = world.bodies().all(|(_, body)| {
                            body.position().is_finite() && body.linear_velocity().is_finite()
                        });
                        assert!(
                            finite,
                            "byte {position} ^ {change:#x}: a body is not finite"
                        );
                    }
                }
                Err(StateError::Undecodable(_) | StateError::Inconsistent(_)) => refused += 1,
                Err(StateError::OtherBuild) if position == start => refused += 1,
                Err(other) => panic!("byte {position} ^ {change:#x}: {other:?}"),
            }
        }
    }
    assert!(
        refused > 0 && restored > 0,
        "{refused} refused, {restored} restored"
    );
}

#[test]
fn a_snapshot_cut_damaged_or_of_a_later_version_is_refused() {
    let (bytes, start) = small_state();
    let cut = &bytes[..bytes.len() - 3];
    assert!(matches!(
        World::load_state_as_other_build(cut),
        Err(StateError::Truncated { .. })
    ));
    let mut damaged = bytes.clone();
    damaged[bytes.len() - 1] ^= 0x04;
    assert_eq!(
        World::load_state_as_other_build(&damaged).unwrap_err(),
        StateError::Damaged
    );
    // A later build's snapshot version (the first byte of the snapshot) is another build's:
    // this build writes version 5 (byte 4) and reads versions 1 to 5.
    assert_eq!(bytes[start], 4);
    let mut later = bytes.clone();
    later[start] = 5;
    assert_eq!(
        World::load_state_as_other_build(&with_checksum(later)).unwrap_err(),
        StateError::OtherBuild
    );
    // Version-1 states, tied to the build that wrote them, are refused.
    let mut version_1 = bytes.clone();
    version_1[8..12].copy_from_slice(&1_u32.to_le_bytes());
    assert_eq!(
        World::load_state(&version_1).unwrap_err(),
        StateError::OtherVersion { found: 1 }
    );
}

/// Version-1 to 4 snapshots (earlier builds': no contact rules, no mesh materials, no joint
/// extras, no couplings) still read. Version 2 is version 1's records followed by the bodies'
/// contact rules, version 3 version 2's followed by the meshes' materials, version 4 version 3's
/// followed by the joints' extras, and version 5 version 4's followed by the couplings (two
/// lists) and their names, so a version-5 snapshot with none of them, its version byte set back
/// and the empty lists (its last bytes) cut, is the earlier version's snapshot of the same world.
#[test]
fn version_1_to_4_snapshots_still_read() {
    let (bytes, start) = small_state();
    let saved = World::load_state_as_other_build(&bytes).unwrap();
    assert_eq!(
        bytes[bytes.len() - 6..],
        [0; 6],
        "empty lists of rules, materials, joint extras, couplings and their names"
    );
    for version in [0, 1, 2, 3] {
        let mut earlier = bytes[..bytes.len() - 6 + usize::from(version)].to_vec();
        earlier[start] = version;
        let payload = (earlier.len() - 32) as u64;
        earlier[20..28].copy_from_slice(&payload.to_le_bytes());
        let restored = World::load_state_as_other_build(&with_checksum(earlier)).unwrap();
        for ((_, a), (_, b)) in saved.bodies().zip(restored.bodies()) {
            assert_eq!(a.position(), b.position(), "version {version}");
            assert_eq!((b.one_way(), b.surface_velocity()), (None, Vec3::ZERO));
        }
    }
}

#[test]
fn a_mesh_rebuilt_from_its_snapshot_keeps_its_materials_and_shares_them_with_no_other() {
    // Two meshes of the same triangles, one of two materials and one without: two shapes in
    // the snapshot, each rebuilt as it was.
    let mesh = r#""type": "trimesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 0, 1], [1, 0, 1]],
        "indices": [[0, 2, 1], [1, 2, 3]]"#;
    let json = format!(
        r#"{{"bodies": [
          {{"type": "static", "shape": {{{mesh}, "materials": [{{"friction": 0.05}},
            {{"restitution": 0.5}}], "triangle_materials": [1, 0]}}}},
          {{"type": "static", "shape": {{{mesh}}}, "position": [3, 0, 0]}}]}}"#
    );
    let world = Scene::from_json(json.as_bytes()).unwrap().world().clone();
    let rebuilt = World::load_state_as_other_build(&world.save_state()).unwrap();
    let meshes: Vec<_> = (rebuilt.bodies())
        .map(|(_, body)| match body.shape() {
            Shape::TriMesh(mesh) => mesh.clone(),
            _ => panic!("not a mesh"),
        })
        .collect();
    assert_eq!(meshes[0].material_index(0), Some(1));
    assert_eq!(meshes[0].triangle_material(1).unwrap().friction, Some(0.05));
    assert_eq!(
        meshes[0].triangle_material(0).unwrap().restitution,
        Some(0.5)
    );
    assert!(meshes[1].materials().is_empty());
}

#[test]
fn a_scene_rebuilt_from_its_snapshot_keeps_its_names_step_and_timestep() {
    let json = r#"{"timestep": 0.01, "bodies": [
      {"name": "floor", "type": "static", "shape": {"type": "box", "half_extents": [4, 0.5, 4]},
       "position": [0, -0.5, 0]},
      {"name": "crate", "shape": {"type": "box", "half_extents": [0.3, 0.3, 0.3]},
       "position": [0, 1, 0]},
      {"name": "bob", "shape": {"type": "sphere", "radius": 0.1}, "position": [-1, 1, 0]},
      {"name": "wheel", "shape": {"type": "sphere", "radius": 0.2}, "position": [2, 1, 0]},
      {"name": "cog", "shape": {"type": "sphere", "radius": 0.1}, "position": [3, 1, 0]}],
      "joints": [{"name": "rope", "type": "distance", "body_b": "bob", "anchor": [-1, 2, 0]},
      {"name": "axle", "type": "revolute", "body_b": "wheel", "anchor": [2, 1, 0], "axis": [0, 0, 1],
       "motor": {"torque": 0.1}},
      {"name": "pin", "type": "revolute", "body_b": "cog", "anchor": [3, 1, 0], "axis": [0, 0, 1]}],
      "couplings": [{"name": "gear", "joints": [{"joint": "pin", "coefficient": 1},
       {"joint": "axle", "coefficient": 3}], "limits": [-0.5, 0], "stiffness": 1, "length": -0.2}]}"#;
    let mut scene = Scene::from_json(json.as_bytes()).unwrap();
    let dt = scene.timestep().engine_seconds;
    for _ in 0..30 {
        scene.world_mut().step(dt).unwrap();
    }
    let bytes = scene.save_state(30);
    let (restored, step) = Scene::load_state_as_other_build(&bytes).unwrap();
    assert_eq!(step, 30);
    assert_eq!(restored.timestep(), scene.timestep());
    assert!(restored.body_handles().eq(scene.body_handles()));
    assert!(restored.joint_handles().eq(scene.joint_handles()));
    for name in ["floor", "crate", "bob"] {
        let handle = restored.body_handle(name).unwrap();
        assert_eq!(
            restored.world().body(handle).unwrap().position(),
            scene.world().body(handle).unwrap().position()
        );
    }
    assert!(restored
        .world()
        .joint(restored.joint_handle("rope").unwrap())
        .is_ok());
    // The coupling comes back under its name, as it was made.
    let gear = scene.coupling_handle("gear").unwrap();
    assert_eq!(restored.coupling_handle("gear"), Some(gear));
    assert_eq!(
        restored.world().coupling(gear).unwrap(),
        scene.world().coupling(gear).unwrap()
    );
    // A world's state is not a scene's.
    assert_eq!(
        Scene::load_state_as_other_build(&scene.world().save_state()).unwrap_err(),
        StateError::NotAState
    );
}

#[test]
fn a_body_woken_by_hand_before_the_save_wakes_its_group_after_the_load() {
    // Two boxes stacked asleep; the top one woken by hand and pushed, then saved: after the load
    // the next step wakes the whole group and moves the pushed box, as the saved world would.
    let mut world = World::new(WorldSettings::default()).unwrap();
    world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(5.0, 0.5, 5.0)).unwrap())
                .position(Vec3::Y * -0.5),
        )
        .unwrap();
    let cube =
        |y: f32| BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.5)).unwrap()).position(Vec3::Y * y);
    let bottom = world.add_body(cube(0.5)).unwrap();
    let top = world.add_body(cube(1.5)).unwrap();
    for _ in 0..120 {
        world.step(DT).unwrap();
    }
    assert!(world.body(bottom).unwrap().is_sleeping() && world.body(top).unwrap().is_sleeping());
    let pushed = world.body_mut(top).unwrap();
    pushed.wake();
    pushed.set_linear_velocity(Vec3::X).unwrap();
    let mut restored = World::load_state_as_other_build(&world.save_state()).unwrap();
    let before = restored.body(top).unwrap().position();
    restored.step(DT).unwrap();
    assert!(!restored.body(bottom).unwrap().is_sleeping());
    assert!(restored.body(top).unwrap().position().x > before.x);
}
