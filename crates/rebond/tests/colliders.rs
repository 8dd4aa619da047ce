//! Colliders of their own: the children of a compound as sensors, with collision groups and
//! names, named by events and query hits; against closed forms (rest heights, free fall) and the
//! bookkeeping rules (one event per collider pair, the collider named).

mod common;

use common::{add_ground, world, DT, G};
use rebond::scene::Scene;
use rebond::{
    BodyDesc, BodyHandle, CompoundChild, ContactEventKind, ErrorKind, InteractionGroups, Pose,
    QueryFilter, Ray, SensorEvent, SensorEventKind, Shape, Vec3, World,
};

const TORSO_HALF: f32 = 0.5;
const FOOT_RADIUS: f32 = 0.2;
/// The foot's centre below the body origin: it reaches 0.15 m below the torso's bottom face.
const FOOT_DEPTH: f32 = 0.45;

/// A unit box "torso" (collider 0) with a sensor sphere "foot" (collider 1) under it, origin at
/// `height`, never sleeping.
fn walker(height: f32, foot_is_sensor: bool) -> BodyDesc {
    let torso = CompoundChild::new(
        Shape::cuboid(Vec3::splat(TORSO_HALF)).unwrap(),
        Pose::IDENTITY,
    )
    .name("torso");
    let foot = CompoundChild::new(
        Shape::sphere(FOOT_RADIUS).unwrap(),
        Pose::from_position(Vec3::new(0.0, -FOOT_DEPTH, 0.0)),
    )
    .name("foot")
    .sensor(foot_is_sensor)
    .user_data(7);
    BodyDesc::dynamic(Shape::compound(vec![torso, foot]).unwrap())
        .position(Vec3::new(0.0, height, 0.0))
        .can_sleep(false)
}

/// The worst distance of `body`'s height from `expected` over `steps` steps.
fn worst_height_error(world: &mut World, body: BodyHandle, expected: f32, steps: usize) -> f32 {
    (0..steps)
        .map(|_| {
            world.step(DT).unwrap();
            (world.body(body).unwrap().position().y - expected).abs()
        })
        .fold(0.0, f32::max)
}

#[test]
fn a_foot_sensor_on_one_collider_fires_while_the_bodys_other_collider_rests() {
    // The walker falls from 1 m (its foot 0.35 m above the ground) and lands on its torso: the
    // torso's bottom face rests on the ground plane y = 0, so the origin rests at TORSO_HALF. The
    // foot hangs 0.15 m into the ground and reports it, once, naming itself and the ground; it
    // pushes nothing, or the body would rest on it, FOOT_DEPTH + FOOT_RADIUS − TORSO_HALF =
    // 0.15 m higher.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let ground = add_ground(&mut world, 0.5);
    let body = world.add_body(walker(1.0, true)).unwrap();
    let (mut sensor_events, mut contact_events) = (Vec::new(), Vec::new());
    for _ in 0..60 {
        world.step(DT).unwrap();
        sensor_events.extend_from_slice(world.sensor_events());
        contact_events.extend_from_slice(world.contact_events());
    }
    assert_eq!(
        sensor_events,
        [SensorEvent {
            sensor: body,
            body: ground,
            kind: SensorEventKind::Entered,
            sensor_collider: 1,
            collider: 0,
        }]
    );
    assert!(world.sensor_overlaps().eq([(body, ground)]));
    let torso_contacts: Vec<_> = contact_events
        .iter()
        .map(|event| {
            (
                event.body_a,
                event.collider_a,
                event.body_b,
                event.collider_b,
            )
        })
        .collect();
    assert_eq!(torso_contacts, [(ground, 0, body, 0)], "{contact_events:?}");
    assert_eq!(contact_events[0].kind, ContactEventKind::Started);
    assert!(world
        .contacts()
        .iter()
        .all(|contact| contact.children() == (0, 0)));
    // 0.1 mm: the contact's sag under the body's weight, g/ω² = 0.017 mm at the contact's
    // 120 Hz (measured 0.017 mm), with room for the landing's settling a second after it; far
    // below the 0.15 m a solid foot would hold the body up.
    let error = worst_height_error(&mut world, body, TORSO_HALF, 60);
    assert!(error < 1e-4, "the torso rests {error} m off its height");
    assert!(world.sensor_events().is_empty());

    // The same walker with a solid foot rests on the foot instead.
    let mut world = common::world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, 0.5);
    let body = world.add_body(walker(1.0, false)).unwrap();
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    // 0.1 mm: as above, the sphere's point contact sags g/ω² under the same weight.
    let on_foot = FOOT_DEPTH + FOOT_RADIUS;
    let error = worst_height_error(&mut world, body, on_foot, 60);
    assert!(
        error < 1e-4,
        "the walker rests {error} m off its foot's height"
    );
}

#[test]
fn a_sensor_child_leaves_as_it_entered_and_sees_only_the_groups_it_interacts_with() {
    // A static compound: a solid pad (collider 0) and a sensor box (collider 1) 2 m to its
    // side; a ball falls through the sensor box. A second sensor child whose groups exclude the
    // ball's never reports it.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let pad = CompoundChild::new(
        Shape::cuboid(Vec3::new(0.5, 0.1, 0.5)).unwrap(),
        Pose::IDENTITY,
    );
    let trigger = |x: f32| {
        CompoundChild::new(
            Shape::cuboid(Vec3::splat(0.5)).unwrap(),
            Pose::from_position(Vec3::new(x, 0.0, 0.0)),
        )
        .sensor(true)
    };
    let blind = trigger(-2.0).collision_groups(InteractionGroups::new(0b10, 0b10));
    let station = world
        .add_body(BodyDesc::static_body(
            Shape::compound(vec![pad, trigger(2.0), blind]).unwrap(),
        ))
        .unwrap();
    let ball = |x: f32| {
        BodyDesc::dynamic(Shape::sphere(0.1).unwrap())
            .position(Vec3::new(x, 2.0, 0.0))
            .collision_groups(InteractionGroups::new(0b01, u32::MAX))
    };
    let falling = world.add_body(ball(2.0)).unwrap();
    let unseen = world.add_body(ball(-2.0)).unwrap();
    let mut events = Vec::new();
    for _ in 0..90 {
        world.step(DT).unwrap();
        events.extend_from_slice(world.sensor_events());
    }
    let kinds: Vec<_> = events
        .iter()
        .map(|event| (event.sensor, event.sensor_collider, event.body, event.kind))
        .collect();
    assert_eq!(
        kinds,
        [
            (station, 1, falling, SensorEventKind::Entered),
            (station, 1, falling, SensorEventKind::Exited),
        ]
    );
    // Neither ball touched the sensors: both fell freely, `y = 2 − g t²/2`, to within the
    // integrator's `g t h / 2` (h ≤ DT) and 0.1 mm of rounding.
    let time = 90.0 * DT;
    for handle in [falling, unseen] {
        let y = world.body(handle).unwrap().position().y;
        let expected = 2.0 - 0.5 * G * time * time;
        assert!(
            (y - expected).abs() < 0.5 * G * time * DT + 1e-4,
            "{y} against {expected}"
        );
    }
    assert!(world.contacts().is_empty());
}

#[test]
fn child_collision_groups_stop_one_childs_contacts_but_not_the_others() {
    // A static compound of two slabs, tops at y = 0: the left one solid to everything, the right
    // one in a group the balls do not interact with. The left ball rests on its slab, at the
    // radius; the right ball falls through its slab freely.
    let radius = 0.25;
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let slab = |x: f32| {
        CompoundChild::new(
            Shape::cuboid(Vec3::new(1.0, 0.5, 1.0)).unwrap(),
            Pose::from_position(Vec3::new(x, -0.5, 0.0)),
        )
    };
    let ghost = slab(3.0).collision_groups(InteractionGroups::new(0b10, 0b10));
    let floor = world
        .add_body(BodyDesc::static_body(
            Shape::compound(vec![slab(-3.0).name("solid"), ghost.name("ghost")]).unwrap(),
        ))
        .unwrap();
    let ball = |x: f32| {
        BodyDesc::dynamic(Shape::sphere(radius).unwrap())
            .position(Vec3::new(x, 1.0, 0.0))
            .collision_groups(InteractionGroups::new(0b01, 0b01))
            .can_sleep(false)
    };
    let resting = world.add_body(ball(-3.0)).unwrap();
    let falling = world.add_body(ball(3.0)).unwrap();
    let starts = started_contacts(&mut world, 60);
    assert_eq!(starts, [(floor, 0, resting, 0)]);
    let time = 60.0 * DT;
    let y = world.body(falling).unwrap().position().y;
    let expected = 1.0 - 0.5 * G * time * time;
    // Free fall to within the integrator's `g t h / 2` (h ≤ DT) and 0.1 mm of rounding.
    assert!(
        (y - expected).abs() < 0.5 * G * time * DT + 1e-4,
        "{y} against {expected}"
    );
    // 0.1 mm: a sphere's point contact sags g/ω² = 0.017 mm at 120 Hz (measured 0.017 mm); the
    // landing settled a second before.
    let error = worst_height_error(&mut world, resting, radius, 60);
    assert!(error < 1e-4, "the ball rests {error} m off its radius");
    let Shape::Compound(compound) = world.body(floor).unwrap().shape() else {
        panic!("the floor is a compound");
    };
    assert_eq!(compound.child_index("ghost"), Some(1));
    assert_eq!(compound.child_index("nobody"), None);
}

#[test]
fn ray_and_shape_cast_hits_name_the_child_and_the_triangle() {
    let mut world = world(Vec3::ZERO);
    let pillar = |x: f32| {
        CompoundChild::new(
            Shape::cuboid(Vec3::splat(0.5)).unwrap(),
            Pose::from_position(Vec3::new(x, 0.0, 0.0)),
        )
    };
    let pillars = world
        .add_body(BodyDesc::static_body(
            Shape::compound(vec![pillar(0.0), pillar(2.0), pillar(4.0).sensor(true)]).unwrap(),
        ))
        .unwrap();
    // A quad of two triangles in the plane y = 0 around z = 10: triangle 0 where x < z − 9,
    // triangle 1 where x > z − 9.
    let quad = Shape::trimesh(
        vec![
            Vec3::new(0.0, 0.0, 9.0),
            Vec3::new(0.0, 0.0, 11.0),
            Vec3::new(2.0, 0.0, 11.0),
            Vec3::new(2.0, 0.0, 9.0),
        ],
        &[[0, 1, 2], [0, 2, 3]],
    )
    .unwrap();
    let mesh = world.add_body(BodyDesc::static_body(quad)).unwrap();
    let down = |x: f32, z: f32| Ray::new(Vec3::new(x, 5.0, z), Vec3::NEG_Y);
    let filter = QueryFilter::default();
    let hit = world.cast_ray(&down(2.0, 0.0), &filter).unwrap().unwrap();
    assert_eq!((hit.body, hit.collider, hit.triangle), (pillars, 1, None));
    for (x, z, triangle) in [(0.5, 10.5, 0), (1.5, 9.5, 1)] {
        let hit = world.cast_ray(&down(x, z), &filter).unwrap().unwrap();
        assert_eq!(
            (hit.body, hit.collider, hit.triangle),
            (mesh, 0, Some(triangle))
        );
        assert!((hit.distance - 5.0).abs() < 1e-6);
    }
    // The sensor child is hit like a sensor body, and left out with the sensors.
    let hit = world.cast_ray(&down(4.0, 0.0), &filter).unwrap().unwrap();
    assert_eq!((hit.body, hit.collider), (pillars, 2));
    let solid_only = QueryFilter::new().exclude_sensors();
    assert_eq!(world.cast_ray(&down(4.0, 0.0), &solid_only).unwrap(), None);
    let mut hits = Vec::new();
    world
        .bodies_containing_point(Vec3::new(4.0, 0.0, 0.0), &solid_only, &mut hits)
        .unwrap();
    assert!(hits.is_empty());
    world
        .bodies_containing_point(Vec3::new(4.0, 0.0, 0.0), &filter, &mut hits)
        .unwrap();
    assert_eq!(hits, [pillars]);

    let ball = Shape::sphere(0.25).unwrap();
    let start = |x: f32, z: f32| Pose::from_position(Vec3::new(x, 5.0, z));
    let hit = world
        .cast_shape(&ball, &start(2.0, 0.0), Vec3::NEG_Y, 10.0, &filter)
        .unwrap()
        .unwrap();
    assert_eq!((hit.body, hit.collider, hit.triangle), (pillars, 1, None));
    // The ball touches the pillar's top at 5 − 0.5 − 0.25, within the cast's precision.
    assert!((hit.distance - 4.25).abs() < 1e-4, "{}", hit.distance);
    let hit = world
        .cast_shape(&ball, &start(1.5, 9.5), Vec3::NEG_Y, 10.0, &filter)
        .unwrap()
        .unwrap();
    assert_eq!((hit.body, hit.collider, hit.triangle), (mesh, 0, Some(1)));
    assert_eq!(
        world
            .cast_shape(&ball, &start(4.0, 0.0), Vec3::NEG_Y, 10.0, &solid_only)
            .unwrap(),
        None
    );
}

#[test]
fn child_names_are_unique_and_not_empty() {
    let child =
        |name: &str| CompoundChild::new(Shape::sphere(1.0).unwrap(), Pose::IDENTITY).name(name);
    let field_of = |children| {
        let error = Shape::compound(children).unwrap_err();
        (error.field, error.kind)
    };
    assert!(matches!(
        field_of(vec![child("a"), child("b"), child("a")]),
        (field, ErrorKind::InvalidCompound(_)) if field == "children[2].name"
    ));
    assert!(matches!(
        field_of(vec![child("a"), child("")]),
        (field, ErrorKind::InvalidCompound(_)) if field == "children[1].name"
    ));
    assert!(Shape::compound(vec![child("a"), child("b")]).is_ok());
}

#[test]
fn scene_files_give_children_names_sensors_and_groups() {
    let scene = Scene::from_json(
        br#"{"bodies": [{"name": "walker", "shape": {"type": "compound", "children": [
            {"shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}, "name": "torso"},
            {"shape": {"type": "sphere", "radius": 0.2}, "position": [0, -0.45, 0],
             "name": "foot", "sensor": true,
             "collision_groups": {"memberships": 2, "filter": 5}}]}}]}"#,
    )
    .unwrap();
    let (_, body) = scene.bodies().next().unwrap();
    let Shape::Compound(compound) = body.shape() else {
        panic!("a compound");
    };
    let [torso, foot] = compound.children() else {
        panic!("two children");
    };
    assert_eq!(
        (torso.name.as_deref(), torso.sensor, torso.collision_groups),
        (Some("torso"), None, None)
    );
    assert_eq!(
        (foot.name.as_deref(), foot.sensor, foot.collision_groups),
        (Some("foot"), Some(true), Some(InteractionGroups::new(2, 5)))
    );

    let refused = |child: &str| {
        let json = format!(
            r#"{{"bodies": [{{"shape": {{"type": "compound", "children": [
                {{"shape": {{"type": "sphere", "radius": 1}}, "name": "a"}}, {child}]}}}}]}}"#
        );
        Scene::from_json(json.as_bytes()).unwrap_err().place
    };
    let sphere = r#""shape": {"type": "sphere", "radius": 1}"#;
    for (child, place) in [
        (format!(r#"{{{sphere}, "name": "a"}}"#), "name"),
        (format!(r#"{{{sphere}, "name": ""}}"#), "name"),
        (format!(r#"{{{sphere}, "name": 3}}"#), "name"),
        (format!(r#"{{{sphere}, "sensor": "yes"}}"#), "sensor"),
        (
            format!(r#"{{{sphere}, "collision_groups": 3}}"#),
            "collision_groups",
        ),
        (
            format!(r#"{{{sphere}, "collision_groups": {{"memberships": -1}}}}"#),
            "collision_groups.memberships",
        ),
        (
            format!(r#"{{{sphere}, "collision_groups": {{"filter": 4294967296}}}}"#),
            "collision_groups.filter",
        ),
        (
            format!(r#"{{{sphere}, "collision_groups": {{"mask": 1}}}}"#),
            "collision_groups.mask",
        ),
    ] {
        assert_eq!(
            refused(&child),
            format!("bodies[0].shape.children[1].{place}"),
            "{child}"
        );
    }
}

#[test]
fn a_fast_body_passes_a_sensor_child_unslowed_and_stops_on_a_solid_one() {
    // A static compound: a thin sensor plate (collider 0) at y = 0 over a solid slab (collider 1)
    // whose top is at y = −3. A ball shot down at 60 m/s moves 1 m a step, ten times its radius,
    // so the continuous pass sweeps it: through the plate it keeps falling freely, and the slab
    // stops it.
    let radius = 0.1;
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let plate = CompoundChild::new(
        Shape::cuboid(Vec3::new(1.0, 0.01, 1.0)).unwrap(),
        Pose::IDENTITY,
    )
    .sensor(true);
    let slab = CompoundChild::new(
        Shape::cuboid(Vec3::new(1.0, 0.05, 1.0)).unwrap(),
        Pose::from_position(Vec3::new(0.0, -3.05, 0.0)),
    );
    world
        .add_body(BodyDesc::static_body(
            Shape::compound(vec![plate, slab]).unwrap(),
        ))
        .unwrap();
    let (height, speed) = (1.5, 60.0);
    let ball = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(radius).unwrap())
                .position(Vec3::new(0.0, height, 0.0))
                .linear_velocity(Vec3::new(0.0, -speed, 0.0)),
        )
        .unwrap();
    for _ in 0..3 {
        world.step(DT).unwrap();
    }
    // Three steps: past the plate, 1.5 m above the slab's top. Free fall,
    // `y = y₀ − v t − g t²/2`, to within the integrator's `g t h / 2` (h ≤ DT) and 0.1 mm.
    let time = 3.0 * DT;
    let expected = height - speed * time - 0.5 * G * time * time;
    let y = world.body(ball).unwrap().position().y;
    assert!(
        (y - expected).abs() < 0.5 * G * time * DT + 1e-4,
        "{y} against {expected}"
    );
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    // Stopped by the slab, resting on its top: 0.1 mm as the resting ball above.
    let y = world.body(ball).unwrap().position().y;
    assert!((y - (-3.0 + radius)).abs() < 1e-4, "the ball ended at {y}");
}

#[test]
fn a_compound_resting_on_two_children_reports_each_childs_contact_and_half_its_weight() {
    // Two unit boxes 2 m apart, joined as one compound, rest on the ground on both. By symmetry
    // each carries half the weight: its collider pair's force report is m g / 2, straight up.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let ground = add_ground(&mut world, 0.5);
    let cube = |x: f32| {
        CompoundChild::new(
            Shape::cuboid(Vec3::splat(0.5)).unwrap(),
            Pose::from_position(Vec3::new(x, 0.0, 0.0)),
        )
    };
    let pair = world
        .add_body(
            BodyDesc::dynamic(Shape::compound(vec![cube(-1.0), cube(1.0)]).unwrap())
                .position(Vec3::new(0.0, 0.6, 0.0))
                .contact_force_threshold(0.0)
                .can_sleep(false),
        )
        .unwrap();
    let mut starts = started_contacts(&mut world, 60);
    // Each box starts touching once (the solver's order may let one push a step before the
    // other).
    starts.sort();
    assert_eq!(starts, [(ground, 0, pair, 0), (ground, 0, pair, 1)]);
    assert!(world.touching_pairs().eq([(ground, pair)]));
    let weight = world.body(pair).unwrap().mass() * G;
    let forces = world.contact_force_events();
    assert_eq!(forces.len(), 2);
    for (event, collider) in forces.iter().zip(0..) {
        assert_eq!(
            (event.body_a, event.body_b, event.collider_b),
            (ground, pair, collider)
        );
        // 1 %: at rest each substep's impulse carries the weight exactly, as for one body on the
        // floor (tests/events_and_filtering.rs); the split between the two boxes is even to
        // within the solver's order and the settling a second after the drop (measured 0.02 %).
        let share = event.total_force.y / (0.5 * weight);
        assert!((share - 1.0).abs() < 0.01, "a box carries {share} of half");
    }
}

#[test]
fn overlap_queries_name_the_colliders_they_find() {
    // A static body of two colliders 2 m apart, a solid box (0) and a sensor ball (1), and a
    // ball of one shape beside them: point and shape overlaps name each collider they find.
    let mut world = World::new(rebond::WorldSettings::default()).unwrap();
    let pair = Shape::compound(vec![
        CompoundChild::new(
            Shape::cuboid(Vec3::splat(0.5)).unwrap(),
            Pose::from_position(-Vec3::X),
        ),
        CompoundChild::new(Shape::sphere(0.5).unwrap(), Pose::from_position(Vec3::X)).sensor(true),
    ])
    .unwrap();
    let compound = world.add_body(BodyDesc::static_body(pair)).unwrap();
    let single = world
        .add_body(BodyDesc::static_body(Shape::sphere(0.5).unwrap()).position(3.0 * Vec3::X))
        .unwrap();
    let mut found = Vec::new();
    let all = QueryFilter::new();
    world
        .colliders_containing_point(-Vec3::X, &all, &mut found)
        .unwrap();
    assert_eq!(found, [(compound, 0)]);
    world
        .colliders_containing_point(Vec3::X, &all, &mut found)
        .unwrap();
    assert_eq!(found, [(compound, 1)]);
    world
        .colliders_containing_point(Vec3::X, &all.exclude_sensors(), &mut found)
        .unwrap();
    assert!(found.is_empty());
    // A box 4.2 m long along x, centred at x = 1, reaches from the solid box to the single ball.
    let probe = Shape::cuboid(Vec3::new(2.1, 0.1, 0.1)).unwrap();
    let at = Pose::from_position(Vec3::X);
    world
        .colliders_overlapping_shape(&probe, &at, &all, &mut found)
        .unwrap();
    assert_eq!(found, [(compound, 0), (compound, 1), (single, 0)]);
    let mut bodies = Vec::new();
    world
        .bodies_overlapping_shape(&probe, &at, &all, &mut bodies)
        .unwrap();
    assert_eq!(bodies, [compound, single]);
    let nan = Vec3::new(f32::NAN, 0.0, 0.0);
    let error = world
        .colliders_containing_point(nan, &all, &mut found)
        .unwrap_err();
    assert_eq!(
        (error.field.as_str(), error.kind),
        ("point", ErrorKind::NotFinite)
    );
    assert!(found.is_empty());
}

/// The collider pairs `(body_a, collider_a, body_b, collider_b)` that start touching over `steps`
/// steps, in event order.
fn started_contacts(world: &mut World, steps: usize) -> Vec<(BodyHandle, u32, BodyHandle, u32)> {
    let mut starts = Vec::new();
    for _ in 0..steps {
        world.step(DT).unwrap();
        starts.extend(
            world
                .contact_events()
                .iter()
                .filter(|event| event.kind == ContactEventKind::Started)
                .map(|event| {
                    (
                        event.body_a,
                        event.collider_a,
                        event.body_b,
                        event.collider_b,
                    )
                }),
        );
    }
    starts
}
