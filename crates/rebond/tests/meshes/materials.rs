//! Per-triangle materials: a floor whose halves are ice and rubber slows a sliding box at the
//! `μ g` of the half it is on, a ball bounces to `e² h` on the bouncy triangles only, contacts,
//! events and hooks name the triangle, and bad materials are refused by field and JSON path.

use rebond::scene::Scene;
use rebond::shape::{TriMesh, TriangleMaterial};
use rebond::{
    BodyDesc, BodyHandle, CombineRule, ContactEventKind, ContactModification, ErrorKind, Shape,
    Vec3, World, WorldSettings,
};

use super::common::apex_after_bounce;
use super::{floor_triangles, DT, G};

/// Ice (material 0) and rubber (material 1).
const ICE: f32 = 0.05;
const RUBBER: f32 = 0.9;

/// Bouncy (material 0) and dead (material 1) restitutions.
const BOUNCY: f32 = 0.8;

/// A 40 m floor of 0.4 m cells in the plane y = 0 whose triangles left of x = 0 take material
/// 0 and the others material 1, and a world in which a contact takes the lower friction and the
/// higher restitution of its two surfaces (so a body of friction 1 and restitution 0 gets the
/// triangle's values exactly).
fn half_and_half(materials: [TriangleMaterial; 2]) -> (World, Shape) {
    let (vertices, indices) = floor_triangles(40.0, 100, true);
    let halves: Vec<u32> = (indices.iter())
        .map(|triangle| {
            let x: f32 = triangle.iter().map(|&i| vertices[i as usize].x).sum();
            u32::from(x > 0.0)
        })
        .collect();
    let mesh = TriMesh::with_materials(vertices, &indices, materials.to_vec(), &halves).unwrap();
    let floor = Shape::TriMesh(mesh);
    let mut world = World::new(WorldSettings {
        gravity: Vec3::new(0.0, -G, 0.0),
        friction_combine: CombineRule::Min,
        restitution_combine: CombineRule::Max,
        ..WorldSettings::default()
    })
    .unwrap();
    world
        .add_body(BodyDesc::static_body(floor.clone()).friction(0.5))
        .unwrap();
    (world, floor)
}

fn ice_and_rubber() -> (World, Shape) {
    let surface = |friction| TriangleMaterial {
        friction: Some(friction),
        ..TriangleMaterial::default()
    };
    half_and_half([surface(ICE), surface(RUBBER)])
}

/// The deceleration of a unit box launched at `speed` along +Z from `(x, 0.5, -10)`, measured
/// between steps `from` and `to` (while it still slides), m/s²; and the box's last contact.
fn deceleration(x: f32, speed: f32, from: usize, to: usize) -> (f32, rebond::Contact) {
    let (mut world, _) = ice_and_rubber();
    let body = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.5)).unwrap())
                .position(Vec3::new(x, 0.5, -10.0))
                .linear_velocity(Vec3::new(0.0, 0.0, speed))
                .friction(1.0)
                .can_sleep(false),
        )
        .unwrap();
    let mut speeds = Vec::new();
    for _ in 0..=to {
        speeds.push(world.body(body).unwrap().linear_velocity().z);
        world.step(DT).unwrap();
    }
    let contact = *world.contacts().last().unwrap();
    let measured = (speeds[from] - speeds[to]) / ((to - from) as f32 * DT);
    (measured, contact)
}

#[test]
fn a_box_slides_on_ice_and_on_rubber_at_the_mu_g_of_its_half() {
    // On ice from 3 m/s: stops after v / (μ g) = 6.1 s; measured over 0.5–2.5 s. On rubber from
    // 6 m/s: stops after 0.68 s; measured over 0.1–0.5 s. Coulomb friction slows a sliding box
    // at exactly μ g, and the solver's friction impulse per substep is μ times the normal one,
    // m g h: 0.1 % leaves room for rounding over the window (measured: 1.3e-5 and 1.1e-6).
    for (x, friction, speed, from, to) in [(-5.0, ICE, 3.0, 30, 150), (5.0, RUBBER, 6.0, 6, 30)] {
        let (measured, contact) = deceleration(x, speed, from, to);
        let expected = friction * G;
        assert!(
            (measured / expected - 1.0).abs() <= 0.001,
            "μ = {friction}: slowed at {measured} m/s², expected {expected}"
        );
        assert_eq!(contact.friction(), friction);
        assert!(contact.triangle().is_some());
    }
}

/// Drops a ball of radius 0.5 and restitution 0 from `height` (gap below it) at `x` on the
/// floor whose left half bounces (`BOUNCY`) and right half is dead (the body's restitution 0),
/// in steps of `BOUNCE_DT` with no restitution threshold; returns the highest its bottom rises
/// after the first bounce.
fn rebound(x: f32, height: f32) -> f32 {
    let bouncy = TriangleMaterial {
        restitution: Some(BOUNCY),
        ..TriangleMaterial::default()
    };
    let (mut world, _) = half_and_half([bouncy, TriangleMaterial::default()]);
    let mut settings = *world.settings();
    settings.restitution_threshold = 0.0;
    world.set_settings(settings).unwrap();
    let ball = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(0.5).unwrap())
                .position(Vec3::new(x, 0.5 + height, 0.3))
                .can_sleep(false),
        )
        .unwrap();
    apex_after_bounce(4000, || {
        world.step(BOUNCE_DT).unwrap();
        let body = world.body(ball).unwrap();
        (body.position().y - 0.5, body.linear_velocity().y)
    })
}

/// Steps of the bounce scenes, s: the approach speed the bounce reverses (at the start of the
/// landing step) is within `g dt` = 0.008 m/s of the impact speed.
const BOUNCE_DT: f32 = 1.0 / 1200.0;

#[test]
fn a_ball_rebounds_to_e_squared_h_on_the_bouncy_triangles_only() {
    let height = 1.0;
    let impact_speed = (2.0 * G * height).sqrt();
    // It leaves at e times the approach speed of the landing step's start, slower than the
    // impact speed by at most g dt: the height falls short of e² h by at most 2 g dt / v
    // (0.37 %; measured 0.34 %); the apex is sampled once a step (at most ½ g dt² = 0.003 mm
    // lower).
    let expected = BOUNCY * BOUNCY * height;
    let shortfall = 2.0 * G * BOUNCE_DT / impact_speed;
    let measured = rebound(-3.0, height);
    assert!(
        measured <= expected + 1.0e-4 && measured >= expected * (1.0 - shortfall) - 1.0e-4,
        "bounced to {measured} m, expected {expected} m less at most {shortfall:.4} of it"
    );
    // The dead half keeps the body's restitution, 0: under 1 mm.
    let dead = rebound(3.0, height);
    assert!(dead < 1.0e-3, "bounced to {dead} m on the dead half");
}

/// The triangle of `floor` under the point `(x, z)`.
fn triangle_under(floor: &Shape, x: f32, z: f32) -> u32 {
    let Shape::TriMesh(mesh) = floor else {
        unreachable!()
    };
    (0..mesh.indices().len() as u32)
        .find(|&index| {
            let [a, b, c] = mesh.triangle(index).unwrap().vertices;
            let side = |p: Vec3, q: Vec3| (q.x - p.x) * (z - p.z) - (q.z - p.z) * (x - p.x);
            let sides = [side(a, b), side(b, c), side(c, a)];
            sides.iter().all(|&s| s >= 0.0) || sides.iter().all(|&s| s <= 0.0)
        })
        .unwrap()
}

#[test]
fn contacts_events_and_hooks_name_the_triangle_under_a_landing_ball() {
    let (mut world, floor) = ice_and_rubber();
    let (x, z) = (5.13, -2.27);
    let under = triangle_under(&floor, x, z);
    let ball: BodyHandle = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(0.25).unwrap())
                .position(Vec3::new(x, 1.0, z))
                .friction(1.0)
                .can_sleep(false),
        )
        .unwrap();
    let mut hooked = Vec::new();
    let mut started = None;
    for _ in 0..60 {
        world
            .step_with_hooks(DT, &mut |contact: &mut ContactModification<'_>| {
                hooked.push(contact.triangle());
            })
            .unwrap();
        if let Some(event) = (world.contact_events().iter())
            .find(|event| event.kind == ContactEventKind::Started && event.body_b == ball)
        {
            started = Some(event.triangle);
        }
    }
    assert_eq!(started, Some(Some(under)), "the start event's triangle");
    assert!(!hooked.is_empty() && hooked.iter().all(|&seen| seen == Some(under)));
    let contact = world.contacts().last().unwrap();
    assert_eq!(contact.triangle(), Some(under));
    assert_eq!(contact.friction(), RUBBER);
    // The ball lifted off: the stop event names where it last touched.
    world
        .body_mut(ball)
        .unwrap()
        .set_linear_velocity(Vec3::Y * 5.0)
        .unwrap();
    let mut stopped = None;
    for _ in 0..10 {
        world.step(DT).unwrap();
        if let Some(event) = (world.contact_events().iter())
            .find(|event| event.kind == ContactEventKind::Stopped && event.body_b == ball)
        {
            stopped = Some(event.triangle);
        }
    }
    assert_eq!(stopped, Some(Some(under)), "the stop event's triangle");
}

#[test]
fn bad_materials_and_indices_are_refused_naming_the_field() {
    let vertices = vec![Vec3::ZERO, Vec3::X, Vec3::Z, Vec3::new(1.0, 0.0, 1.0)];
    let indices = [[0, 2, 1], [1, 2, 3]];
    let fine = TriangleMaterial::default();
    let cases = [
        (
            vec![
                fine,
                TriangleMaterial {
                    friction: Some(-0.1),
                    ..fine
                },
            ],
            vec![0, 1],
            "materials[1].friction",
        ),
        (
            vec![TriangleMaterial {
                friction: Some(f32::NAN),
                ..fine
            }],
            vec![0, 0],
            "materials[0].friction",
        ),
        (
            vec![TriangleMaterial {
                restitution: Some(1.5),
                ..fine
            }],
            vec![0, 0],
            "materials[0].restitution",
        ),
        (
            vec![TriangleMaterial {
                rolling_resistance: Some(f32::INFINITY),
                ..fine
            }],
            vec![0, 0],
            "materials[0].rolling_resistance",
        ),
        (vec![fine], vec![0, 1], "triangle_materials[1]"),
        (vec![fine], vec![0], "triangle_materials"),
    ];
    for (materials, triangle_materials, field) in cases {
        let error =
            TriMesh::with_materials(vertices.clone(), &indices, materials, &triangle_materials)
                .unwrap_err();
        assert_eq!(error.field, field);
    }
    let error = TriMesh::with_materials(vertices, &indices, vec![fine], &[0, 1]).unwrap_err();
    assert_eq!(
        error.kind,
        ErrorKind::MaterialOutOfRange { index: 1, len: 1 }
    );
}

#[test]
fn a_scene_gives_a_trimesh_its_materials_and_refuses_bad_ones_at_their_path() {
    let scene = |materials: &str| {
        format!(
            r#"{{"bodies": [{{"name": "floor", "type": "static", "shape": {{"type": "trimesh",
                "vertices": [[0, 0, 0], [1, 0, 0], [0, 0, 1], [1, 0, 1]],
                "indices": [[0, 2, 1], [1, 2, 3]] {materials} }}}}]}}"#
        )
    };
    let loaded = Scene::from_json(
        scene(
            r#", "materials": [{"friction": 0.05}, {"restitution": 0.5, "rolling_resistance": 0.1}],
            "triangle_materials": [1, 0]"#,
        )
        .as_bytes(),
    )
    .unwrap();
    let handle = loaded.body_handle("floor").unwrap();
    let Shape::TriMesh(mesh) = loaded.world().body(handle).unwrap().shape() else {
        panic!("not a trimesh")
    };
    assert_eq!(mesh.material_index(0), Some(1));
    assert_eq!(mesh.triangle_material(1).unwrap().friction, Some(0.05));
    assert_eq!(mesh.triangle_material(0).unwrap().restitution, Some(0.5));
    for (materials, place) in [
        (
            r#", "materials": [{"friction": -1}], "triangle_materials": [0, 0]"#,
            "materials[0].friction",
        ),
        (
            r#", "materials": [{}, {"restitution": 2}], "triangle_materials": [0, 1]"#,
            "materials[1].restitution",
        ),
        (
            r#", "materials": [{"friction": 1e39}], "triangle_materials": [0, 0]"#,
            "materials[0].friction",
        ),
        (
            r#", "materials": [{"bounce": 1}], "triangle_materials": [0, 0]"#,
            "materials[0].bounce",
        ),
        (
            r#", "materials": [{}], "triangle_materials": [0, 3]"#,
            "triangle_materials[1]",
        ),
        (
            r#", "materials": [{}], "triangle_materials": [0, -1]"#,
            "triangle_materials[1]",
        ),
        (
            r#", "materials": [{}], "triangle_materials": [0]"#,
            "triangle_materials",
        ),
        (r#", "materials": [{}]"#, "triangle_materials"),
        (r#", "triangle_materials": [0, 0]"#, "materials"),
    ] {
        let error = Scene::from_json(scene(materials).as_bytes()).unwrap_err();
        assert_eq!(
            error.place,
            format!("bodies[0].shape.{place}"),
            "{materials}"
        );
    }
}

#[test]
fn a_box_across_the_border_rests_on_a_manifold_of_each_material() {
    // Triangles of different materials never merge: the box's bottom, half on ice and half on
    // rubber, has a manifold on each half, each with its own friction, carrying half the weight.
    let (mut world, _) = ice_and_rubber();
    let body = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.5)).unwrap())
                .position(Vec3::new(0.0, 0.5, 0.3))
                .friction(1.0)
                .can_sleep(false),
        )
        .unwrap();
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let mut frictions: Vec<f32> = (world.contacts().iter())
        .filter(|contact| contact.bodies().1 == body)
        .map(|contact| contact.friction())
        .collect();
    frictions.sort_by(f32::total_cmp);
    assert_eq!(frictions, [ICE, RUBBER]);
    // Each half carries m g / 2 (the box is centred on the border), an impulse of m g h / 2 in
    // the last substep of length h: 1 % of it, for the settling left after a second at rest
    // (measured: 0.03 %).
    let h = DT / world.settings().substeps as f32;
    let weight = world.body(body).unwrap().mass() * G * h;
    for contact in world.contacts().iter().filter(|c| c.bodies().1 == body) {
        let impulse: f32 = contact.normal_impulses().iter().sum();
        assert!(
            (impulse / (weight / 2.0) - 1.0).abs() <= 0.01,
            "μ = {}: carries {impulse} N·s of {weight} N·s",
            contact.friction()
        );
    }
}
