//! Saving and restoring worlds: a restored world steps bit for bit as the saved one, and bytes
//! that are not a whole state of this version are refused, never decoded.

use rebond::scene::Scene;
use rebond::state::{StateError, STATE_FORMAT_VERSION};
use rebond::World;

/// A scene with every shape and every joint kind, things falling, sliding, rolling, hanging,
/// driven and asleep: a static floor, a sphere, a box, a capsule, a cylinder, a hull and a
/// compound (one child with rolling resistance) dropped on it; a heightfield and a triangle-mesh
/// ramp (of two materials) with bodies rolling on them (one with rolling resistance) and a hull and a lying
/// cylinder on them (whose triangle queries start from last step's simplices); a fixed, a ball (limits,
/// friction), a revolute (limits, motor), a prismatic (limits, motor) and two distance joints
/// (spring, rope); two wheels geared by an equality coupling, a pendulum coupled to them by a
/// limited spring coupling.
const EVERY_KIND: &str = r#"{
  "bodies": [
    {"name": "floor", "type": "static", "shape": {"type": "box", "half_extents": [8, 0.5, 8]},
     "position": [0, -0.5, 0], "friction": 0.6},
    {"name": "plane", "type": "static", "shape": {"type": "halfspace", "normal": [0, 1, 0]},
     "position": [0, -2, 0]},
    {"name": "ball", "shape": {"type": "sphere", "radius": 0.3}, "position": [-3, 1, 0],
     "linear_velocity": [2, 0, 0.5], "restitution": 0.4},
    {"name": "crate", "shape": {"type": "box", "half_extents": [0.3, 0.2, 0.4]},
     "position": [-1.5, 0.8, 1], "rotation": [0.1, 0.2, 0.0, 0.974679], "angular_velocity": [1, 2, 0]},
    {"name": "pill", "shape": {"type": "capsule", "radius": 0.2, "half_height": 0.3},
     "position": [0, 1.5, -1], "rotation": [0.0, 0.0, 0.7071068, 0.7071068]},
    {"name": "drum", "shape": {"type": "cylinder", "radius": 0.3, "half_height": 0.2},
     "position": [1.5, 0.6, -1], "angular_velocity": [0, 0, 3]},
    {"name": "gem", "shape": {"type": "convex_hull", "points": [[-0.3, 0, -0.3], [0.3, 0, -0.3],
     [0.3, 0, 0.3], [-0.3, 0, 0.3], [0, 0.5, 0]]}, "position": [3, 0.2, 1]},
    {"name": "dumbbell", "shape": {"type": "compound", "children": [
       {"shape": {"type": "sphere", "radius": 0.2}, "position": [-0.4, 0, 0],
        "rolling_resistance": 0.1},
       {"shape": {"type": "box", "half_extents": [0.2, 0.2, 0.2]}, "position": [0.4, 0, 0]}]},
     "position": [0, 2.5, 2]},
    {"name": "glued", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]}, "position": [-1.5, 1.2, 1]},
    {"name": "bob", "shape": {"type": "sphere", "radius": 0.2}, "position": [2, 3, 3]},
    {"name": "door", "shape": {"type": "box", "half_extents": [0.5, 0.8, 0.05]}, "position": [-4, 1.5, -3]},
    {"name": "slider", "shape": {"type": "box", "half_extents": [0.2, 0.2, 0.2]}, "position": [4, 2, -3]},
    {"name": "spring_weight", "shape": {"type": "sphere", "radius": 0.15}, "position": [-2, 3, -4]},
    {"name": "rope_end", "shape": {"type": "box", "half_extents": [0.15, 0.15, 0.15]}, "position": [1, 3, -5]},
    {"name": "hill", "type": "static", "shape": {"type": "heightfield", "scale": [6, 1, 6],
     "heights": [[0, 0.2, 0, 0.1], [0.1, 0.8, 0.3, 0], [0, 0.4, 0.6, 0.2], [0.2, 0, 0.1, 0]]},
     "position": [12, 0, 0]},
    {"name": "roller", "shape": {"type": "sphere", "radius": 0.25}, "position": [12, 1.5, 0.3],
     "rolling_resistance": 0.05},
    {"name": "tumbler", "shape": {"type": "box", "half_extents": [0.2, 0.2, 0.2]}, "position": [11, 1.5, -1]},
    {"name": "ramp", "type": "static", "shape": {"type": "trimesh",
     "vertices": [[-2, 0, -2], [2, 1, -2], [2, 1, 2], [-2, 0, 2], [0, 0.5, 0]],
     "indices": [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]],
     "materials": [{"friction": 0.1}, {"restitution": 0.5, "rolling_resistance": 0.02}],
     "triangle_materials": [0, 1, 1, 0]}, "position": [0, 0, 12]},
    {"name": "skid", "shape": {"type": "capsule", "radius": 0.15, "half_height": 0.2},
     "position": [0.5, 1.5, 12]},
    {"name": "nugget", "shape": {"type": "convex_hull", "points": [[-0.2, 0, -0.2], [0.2, 0, -0.2],
     [0.2, 0, 0.2], [-0.2, 0, 0.2], [0, 0.3, 0]]}, "position": [-0.8, 1.2, 12.6]},
    {"name": "can", "shape": {"type": "cylinder", "radius": 0.2, "half_height": 0.15},
     "position": [12.6, 1.6, -0.6], "rotation": [0.0, 0.0, 0.7071068, 0.7071068]},
    {"name": "gear_a", "shape": {"type": "cylinder", "radius": 0.3, "half_height": 0.05},
     "position": [-6, 2, 6], "rotation": [0.7071068, 0.0, 0.0, 0.7071068]},
    {"name": "gear_b", "shape": {"type": "cylinder", "radius": 0.3, "half_height": 0.05},
     "position": [-6, 2, 7], "rotation": [0.7071068, 0.0, 0.0, 0.7071068]},
    {"name": "gear_c", "shape": {"type": "box", "half_extents": [0.1, 0.3, 0.1]},
     "position": [-6, 1.7, 8]}
  ],
  "joints": [
    {"type": "fixed", "body_a": "crate", "body_b": "glued", "anchor": [-1.5, 1.0, 1]},
    {"type": "ball", "body_b": "bob", "anchor": [2, 4, 3], "axis": [0, -1, 0],
     "swing_limit": 0.8, "twist_limits": [-0.5, 0.5], "friction": 0.05},
    {"type": "revolute", "body_b": "door", "anchor": [-4.5, 1.5, -3], "axis": [0, 1, 0],
     "limits": [-1.5, 1.5], "motor": {"target_velocity": 1.0, "max_force": 20}},
    {"type": "prismatic", "body_b": "slider", "anchor": [4, 2, -3], "axis": [1, 0.2, 0],
     "limits": [-0.5, 1.0], "motor": {"target_position": 0.5, "stiffness": 50, "damping": 5}},
    {"type": "distance", "body_b": "spring_weight", "anchor": [-2, 4, -4],
     "spring": {"stiffness": 40, "damping": 0.5}},
    {"type": "distance", "body_b": "rope_end", "anchor": [0, 4, -5], "anchor_b": [1, 3, -5],
     "limits": [0, 1.6]},
    {"name": "gear_a", "type": "revolute", "body_b": "gear_a", "anchor": [-6, 2, 6],
     "axis": [0, 0, 1], "motor": {"torque": 0.5}},
    {"name": "gear_b", "type": "revolute", "body_b": "gear_b", "anchor": [-6, 2, 7],
     "axis": [0, 0, 1]},
    {"name": "gear_c", "type": "revolute", "body_b": "gear_c", "anchor": [-6, 2, 8],
     "axis": [0, 0, 1]}
  ],
  "couplings": [
    {"name": "gear", "joints": [{"joint": "gear_b", "coefficient": 1},
     {"joint": "gear_a", "coefficient": -2}], "limits": [0, 0]},
    {"joints": [{"joint": "gear_c", "coefficient": 1}, {"joint": "gear_b", "coefficient": 0.5}],
     "limits": [-1, 1], "stiffness": 2, "damping": 0.1}
  ]
}"#;

/// Every body's pose, velocities and sleep, and every joint's force and torque, as bits.
fn fingerprint(world: &World) -> Vec<u32> {
    let mut bits = Vec::new();
    for (_, body) in world.bodies() {
        let vectors = [
            body.position(),
            body.linear_velocity(),
            body.angular_velocity(),
        ];
        bits.extend(vectors.iter().flat_map(|v| v.to_array()).map(f32::to_bits));
        bits.extend(body.rotation().to_array().map(f32::to_bits));
        bits.push(u32::from(body.is_sleeping()));
    }
    for (_, joint) in world.joints() {
        bits.extend(joint.force().to_array().map(f32::to_bits));
        bits.extend(joint.torque().to_array().map(f32::to_bits));
    }
    for (handle, _) in world.couplings() {
        bits.push(world.coupling_length(handle).unwrap().to_bits());
    }
    bits.push(world.contact_count() as u32);
    bits
}

fn stepped(mut world: World, steps: usize) -> World {
    for _ in 0..steps {
        world.step(1.0 / 60.0).unwrap();
    }
    world
}

#[test]
fn a_restored_world_steps_bit_for_bit_as_the_saved_one() {
    // N + M steps in one go against N, save, restore, M, at several N: mid-fall, as the hull
    // and the cylinder land on the ramp and the hill (their triangle simplices kept), in the
    // first contacts, and once things have come to rest (bodies asleep, contacts parked).
    let start = Scene::from_json(EVERY_KIND.as_bytes())
        .unwrap()
        .world()
        .clone();
    for (saved_at, then) in [(1, 60), (25, 60), (45, 90), (400, 60)] {
        let straight = stepped(start.clone(), saved_at + then);
        let bytes = stepped(start.clone(), saved_at).save_state();
        let restored = World::load_state(&bytes).unwrap();
        let resumed = stepped(restored, then);
        assert_eq!(
            fingerprint(&resumed),
            fingerprint(&straight),
            "saved after {saved_at} steps, {then} more"
        );
    }
    let rested = stepped(start, 400);
    assert!(rested.sleeping_body_count() > 0, "something asleep to save");
}

#[test]
fn a_clone_and_a_restored_state_take_the_world_s_handles_and_no_other_world_does() {
    // Rolling back keeps handles: a clone and a world restored from a state are the same world
    // at another time. A world made afterwards, though built alike, is another world.
    let build = || {
        let scene = Scene::from_json(EVERY_KIND.as_bytes()).unwrap();
        let crate_handle = scene.body_handle("crate").unwrap();
        let (_, joint) = scene.joint_handles().next().unwrap();
        (stepped(scene.world().clone(), 30), crate_handle, joint)
    };
    let (world, crate_handle, joint) = build();
    let bytes = world.save_state();
    let restored = World::load_state(&bytes).unwrap();
    let copy = world.clone();
    for (twin, what) in [(&copy, "clone"), (&restored, "restored world")] {
        let body = twin
            .body(crate_handle)
            .unwrap_or_else(|error| panic!("{what}: {error}"));
        assert_eq!(
            body.position(),
            world.body(crate_handle).unwrap().position()
        );
        assert!(twin.joint(joint).is_ok(), "{what}: the joint");
    }
    let (later, later_crate, later_joint) = build();
    assert_eq!(later_crate.slot(), crate_handle.slot());
    assert!(later.body(crate_handle).is_err() && later.joint(joint).is_err());
    assert!(restored.body(later_crate).is_err() && restored.joint(later_joint).is_err());
    // The restored world's state is the saved one, identity included.
    assert!(restored.save_state() == bytes);
}

#[test]
fn bytes_that_are_not_a_whole_state_of_this_version_are_refused() {
    let world = Scene::from_json(EVERY_KIND.as_bytes())
        .unwrap()
        .world()
        .clone();
    let bytes = stepped(world, 30).save_state();
    let refuse = |bytes: &[u8]| World::load_state(bytes).map(|_| ()).unwrap_err();
    assert_eq!(refuse(b"{\"bodies\": []}"), StateError::NotAState);
    assert_eq!(refuse(b""), StateError::NotAState);
    for cut in [6, 24] {
        let expected = StateError::Truncated {
            expected: 32,
            found: cut as u64,
        };
        assert_eq!(refuse(&bytes[..cut]), expected, "header cut at {cut}");
    }
    for cut in [32, bytes.len() / 2, bytes.len() - 1] {
        match refuse(&bytes[..cut]) {
            StateError::Truncated { expected, found } => {
                assert_eq!((expected, found), (bytes.len() as u64, cut as u64));
            }
            other => panic!("cut at {cut}: {other:?}"),
        }
    }
    let mut longer = bytes.clone();
    longer.push(0);
    assert!(matches!(refuse(&longer), StateError::TrailingBytes { .. }));
    let mut other_version = bytes.clone();
    other_version[8..12].copy_from_slice(&(STATE_FORMAT_VERSION + 1).to_le_bytes());
    assert_eq!(
        refuse(&other_version),
        StateError::OtherVersion {
            found: STATE_FORMAT_VERSION + 1
        }
    );
    // Another build's state is read from its portable snapshot (tests/durable_state.rs).
    let mut other_build = bytes.clone();
    other_build[12] ^= 1;
    assert!(World::load_state(&other_build).is_ok());
    // Any flipped bit in the world's bytes is caught by the checksum.
    for position in [32, 100, bytes.len() / 2, bytes.len() - 1] {
        let mut damaged = bytes.clone();
        damaged[position] ^= 0x10;
        assert_eq!(refuse(&damaged), StateError::Damaged, "byte {position}");
    }
}

#[test]
fn bytes_made_to_match_their_checksum_are_refused_or_restore_a_world_that_steps() {
    // What the checksum cannot catch: bytes changed and the checksum made to match (as a fuzzer
    // learns to). Every byte of a small world's state, changed three ways: the state is refused
    // (undecodable or inconsistent), or the world it restores steps with every body finite.
    let json = r#"{"bodies": [
      {"type": "static", "shape": {"type": "box", "half_extents": [4, 0.5, 4]}, "position": [0, -0.5, 0]},
      {"shape": {"type": "box", "half_extents": [0.3, 0.3, 0.3]}, "position": [0, 0.3, 0]},
      {"shape": {"type": "sphere", "radius": 0.2}, "position": [1, 1, 0]},
      {"name": "bob", "shape": {"type": "sphere", "radius": 0.1}, "position": [-1, 1, 0]}],
      "joints": [{"type": "ball", "body_b": "bob", "anchor": [-1, 1.5, 0]}]}"#;
    let world = Scene::from_json(json.as_bytes()).unwrap().world().clone();
    let bytes = stepped(world, 40).save_state();
    let (mut refused, mut restored) = (0, 0);
    for position in 32..bytes.len() {
        for change in [0x01, 0x80, 0xff] {
            let mut changed = bytes.clone();
            changed[position] ^= change;
            let checksum = crc32fast::hash(&changed[32..]);
            changed[28..32].copy_from_slice(&checksum.to_le_bytes());
            match World::load_state(&changed) {
                Ok(world) => {
                    restored += 1;
                    let mut world = world;
                    if world.step(1.0 / 60.0).is_ok() {
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
fn geometry_shared_by_many_bodies_is_saved_once_and_shared_again() {
    use rebond::{BodyDesc, CompoundChild, Pose, Shape, Vec3, WorldSettings};
    let hull = Shape::convex_hull(&[
        Vec3::new(-0.5, -0.5, -0.5),
        Vec3::new(0.5, -0.5, -0.5),
        Vec3::new(0.0, -0.5, 0.5),
        Vec3::new(0.0, 0.5, 0.0),
    ])
    .unwrap();
    let compound = Shape::compound(vec![
        CompoundChild::new(hull.clone(), Pose::IDENTITY),
        CompoundChild::new(hull.clone(), Pose::from_position(Vec3::X)),
    ])
    .unwrap();
    // A floor of 40 × 40 cells, 3,200 triangles.
    let n = 41u32;
    let vertices: Vec<Vec3> = (0..n * n)
        .map(|k| Vec3::new((k % n) as f32 * 0.05, 0.0, (k / n) as f32 * 0.05))
        .collect();
    let indices: Vec<[u32; 3]> = (0..(n - 1) * (n - 1))
        .flat_map(|c| {
            let k = c / (n - 1) * n + c % (n - 1);
            [[k, k + n, k + 1], [k + 1, k + n, k + n + 1]]
        })
        .collect();
    let mesh = Shape::trimesh(vertices, &indices).unwrap();
    let world_with = |count: usize| {
        let mut world = World::new(WorldSettings::default()).unwrap();
        for i in 0..count {
            let x = Vec3::X * (3.0 * i as f32);
            for (shape, y) in [(&hull, 2.0), (&compound, 4.0)] {
                let desc = BodyDesc::dynamic(shape.clone()).position(x + Vec3::Y * y);
                world.add_body(desc).unwrap();
            }
            let desc = BodyDesc::static_body(mesh.clone()).position(x);
            world.add_body(desc).unwrap();
        }
        world
    };
    // One body of each or 20: the state grows by the bodies, not by their geometry again.
    let (one, many) = (world_with(1).save_state(), world_with(20).save_state());
    let per_extra_set = (many.len() - one.len()) / 19;
    assert!(
        per_extra_set < 2_000,
        "{} bytes per set of bodies",
        per_extra_set
    );
    assert!(
        one.len() > 40 * 40 * 2 * 12,
        "the mesh itself is in the state"
    );

    let restored = World::load_state(&many).unwrap();
    let shapes: Vec<&Shape> = restored.bodies().map(|(_, body)| body.shape()).collect();
    let same = |a: &Shape, b: &Shape| match (a, b) {
        (Shape::ConvexHull(a), Shape::ConvexHull(b)) => std::sync::Arc::ptr_eq(a, b),
        (Shape::Compound(a), Shape::Compound(b)) => std::sync::Arc::ptr_eq(a, b),
        (Shape::TriMesh(a), Shape::TriMesh(b)) => a.shares_geometry(b),
        _ => false,
    };
    for set in shapes.chunks(3).skip(1) {
        for (shape, first) in set.iter().zip(&shapes[..3]) {
            assert!(same(shape, first), "restored as a copy: {shape:?}");
        }
    }
    assert_eq!(
        stepped(restored, 30).save_state(),
        stepped(World::load_state(&many).unwrap(), 30).save_state()
    );
}
