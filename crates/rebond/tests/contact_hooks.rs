//! Contact hooks (`rebond::hooks`): a user's hook changing friction, restitution, surface
//! velocity and normal or switching points off, and the bodies' own rules built on it, conveyors
//! (`surface_velocity`) and one-way platforms (`one_way`), measured against their analytic
//! outcomes.

mod common;

use common::{add_ground, run, unit_box, world, DT, G};
use rebond::hooks::ContactModification;
use rebond::scene::Scene;
use rebond::{BodyDesc, BodyHandle, ErrorKind, Quat, Shape, Vec3, World};

/// Steps `world` `steps` times with `hook`.
fn run_hooked(world: &mut World, steps: usize, mut hook: impl FnMut(&mut ContactModification)) {
    for _ in 0..steps {
        world.step_with_hooks(DT, &mut hook).unwrap();
    }
}

/// A static conveyor (the ground box, friction 0.5) with a unit box (friction 0.5, never
/// asleep) settled on it for a second, the belt still.
fn box_on_belt() -> (World, BodyHandle, BodyHandle) {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let belt = add_ground(&mut world, 0.5);
    let crate_ = world
        .add_body(unit_box(Vec3::new(0.0, 0.5, 0.0)).can_sleep(false))
        .unwrap();
    run(&mut world, 60);
    (world, belt, crate_)
}

/// A box set down on a belt moving at 1 m/s speeds up at `μ g` and rides at 1 m/s from
/// `t = v / (μ g)` = 0.204 s on (μ = 0.5, the pair's geometric mean).
#[test]
fn a_conveyor_brings_a_box_to_its_speed_in_the_time_friction_allows() {
    let (mut world, belt, crate_) = box_on_belt();
    let speed = 1.0;
    world
        .set_surface_velocity(belt, Vec3::new(speed, 0.0, 0.0))
        .unwrap();
    let acceleration = 0.5 * G;
    let catch_up = speed / acceleration;
    let mut velocities = Vec::new();
    for _ in 0..240 {
        world.step(DT).unwrap();
        velocities.push(world.body(crate_).unwrap().linear_velocity());
    }
    // While it slides, v = μ g t at each step's end. Measured within 5e-5 m/s of it at every
    // step before the catch-up (sliding friction at the Coulomb limit, the normal force settled
    // by the second at rest); 1 cm/s is the bound, a tenth of what a step's μ g dt adds.
    let sliding_steps = (catch_up / DT) as usize;
    for (step, velocity) in velocities[..sliding_steps].iter().enumerate() {
        let expected = acceleration * DT * (step + 1) as f32;
        assert!(
            (velocity.x - expected).abs() < 0.01,
            "step {step}: {velocity} against {expected}"
        );
    }
    // From the step after the catch-up on (window of 3.7 s), the box rides at the belt's speed:
    // measured within 3e-5 m/s; 1 mm/s is the bound (no slip on a flat belt), with nothing
    // sideways or up.
    for (step, velocity) in velocities.iter().enumerate().skip(sliding_steps + 2) {
        assert!(
            (*velocity - Vec3::new(speed, 0.0, 0.0)).length() < 1.0e-3,
            "step {step}: {velocity}"
        );
    }
    let height = world.body(crate_).unwrap().position().y;
    assert!((height - 0.5).abs() < 5.0e-3, "rides at height {height}");
}

/// A belt switched on under a box asleep on it wakes the box and carries it off.
#[test]
fn a_belt_switched_on_wakes_what_sleeps_on_it() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let belt = add_ground(&mut world, 0.5);
    let crate_ = world.add_body(unit_box(Vec3::new(0.0, 0.5, 0.0))).unwrap();
    run(&mut world, 120);
    assert!(world.body(crate_).unwrap().is_sleeping());
    world.set_surface_velocity(belt, Vec3::X).unwrap();
    run(&mut world, 60);
    let body = world.body(crate_).unwrap();
    assert!(!body.is_sleeping());
    // Caught up after 0.2 s, riding at 1 m/s by the end of the second (measured 1e-5 off).
    assert!((body.linear_velocity().x - 1.0).abs() < 1.0e-3);
}

/// The surface velocity is in the belt's frame: a belt turned a quarter turn about +Y carries
/// along its own +X, the world's −Z.
#[test]
fn a_surface_velocity_turns_with_its_body() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(50.0, 0.5, 50.0)).unwrap())
                .position(Vec3::new(0.0, -0.5, 0.0))
                .rotation(Quat::from_rotation_y(std::f32::consts::FRAC_PI_2))
                .surface_velocity(Vec3::new(2.0, 0.0, 0.0)),
        )
        .unwrap();
    let crate_ = world.add_body(unit_box(Vec3::new(0.0, 0.5, 0.0))).unwrap();
    run(&mut world, 120);
    // Caught up after 2 / (0.5 g) = 0.41 s; measured within 1e-4 m/s after 2 s.
    let velocity = world.body(crate_).unwrap().linear_velocity();
    assert!(
        (velocity - Vec3::new(0.0, 0.0, -2.0)).length() < 1.0e-3,
        "{velocity}"
    );
}

/// The bodies' surface velocities are a hook's: a hook setting the same surface velocity on a
/// still belt steps the same bits, and a hook sees the rule's value before it.
#[test]
fn a_hooks_surface_velocity_is_the_conveyors() {
    let belt_velocity = Vec3::new(1.0, 0.0, 0.5);
    let (mut by_rule, belt, crate_) = box_on_belt();
    let (mut by_hook, _, hooked_crate) = box_on_belt();
    by_rule.set_surface_velocity(belt, belt_velocity).unwrap();
    let mut seen = Vec::new();
    for _ in 0..90 {
        by_rule
            .step_with_hooks(DT, &mut |contact: &mut ContactModification| {
                seen.push(contact.surface_velocity());
            })
            .unwrap();
        by_hook
            .step_with_hooks(DT, &mut |contact: &mut ContactModification| {
                contact.set_surface_velocity(belt_velocity).unwrap();
            })
            .unwrap();
    }
    // The belt is body A (added first): A's surface relative to B's is the belt's velocity.
    assert!(seen.iter().all(|&velocity| velocity == belt_velocity));
    let (a, b) = (
        by_rule.body(crate_).unwrap(),
        by_hook.body(hooked_crate).unwrap(),
    );
    assert_eq!(a.position(), b.position());
    assert_eq!(a.linear_velocity(), b.linear_velocity());
}

/// A one-way platform of `half_thickness` with its top at y = 2.1, turned by `rotation`, over a
/// ground at y = 0; its one-way direction is +Y in its own frame.
fn platform_world(rotation: Quat) -> (World, BodyHandle) {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, 0.5);
    let platform = world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(2.0, 0.1, 2.0)).unwrap())
                .position(Vec3::new(0.0, 2.0, 0.0))
                .rotation(rotation)
                .one_way(Vec3::new(0.0, 3.0, 0.0)),
        )
        .unwrap();
    (world, platform)
}

/// What a ball thrown up through the one-way platform of [`platform_world`] did.
struct Throw {
    /// Its highest centre, and the free flight's, m.
    apex: f32,
    free_apex: f32,
    /// Its fastest while its centre was within 0.5 m of the platform's, m/s.
    fastest_at_platform: f32,
    /// The worst of its distance from resting on the platform plus its speed, over the steps
    /// from `rest_from` on.
    worst_rest: f32,
    /// How many contact events with the platform started.
    platform_starts: usize,
}

/// Throws a ball of `radius` up at `launch` m/s from the ground under the platform, for
/// `steps` steps.
fn throw_through_platform(radius: f32, launch: f32, steps: usize, rest_from: usize) -> Throw {
    let (mut world, platform) = platform_world(Quat::IDENTITY);
    let ball = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(radius).unwrap())
                .position(Vec3::new(0.0, radius + 0.01, 0.0))
                .linear_velocity(Vec3::new(0.0, launch, 0.0))
                .can_sleep(false),
        )
        .unwrap();
    let mut throw = Throw {
        apex: 0.0,
        free_apex: radius + 0.01 + launch * launch / (2.0 * G),
        fastest_at_platform: 0.0,
        worst_rest: 0.0,
        platform_starts: 0,
    };
    for step in 0..steps {
        world.step(DT).unwrap();
        let body = world.body(ball).unwrap();
        throw.apex = throw.apex.max(body.position().y);
        if (1.5..2.5).contains(&body.position().y) {
            let speed = body.linear_velocity().length();
            throw.fastest_at_platform = throw.fastest_at_platform.max(speed);
        }
        throw.platform_starts += world
            .contact_events()
            .iter()
            .filter(|event| event.body_a == platform || event.body_b == platform)
            .filter(|event| event.kind == rebond::ContactEventKind::Started)
            .count();
        if step >= rest_from {
            let error = (body.position() - Vec3::new(0.0, 2.1 + radius, 0.0)).length();
            throw.worst_rest = throw
                .worst_rest
                .max(error + body.linear_velocity().length());
        }
    }
    throw
}

/// A ball thrown up from under a one-way platform passes through it at its own speed, then lands
/// on it and rests there.
#[test]
fn a_ball_thrown_up_through_a_one_way_platform_lands_and_rests_on_it() {
    let (world, platform) = platform_world(Quat::IDENTITY);
    assert_eq!(
        world.body(platform).unwrap().one_way(),
        Some(Vec3::Y),
        "normalised"
    );
    // It lands about 1.3 s after the throw (0.82 s up, 0.49 s down from the apex); from 2.5 s
    // on it rests on the platform.
    let throw = throw_through_platform(0.25, 8.0, 300, 150);
    // Passing costs it nothing: the apex is the free flight's, 3.52 m, less the integration's
    // g h t / 2 = 8.3 mm at t = 0.82 s (symplectic Euler, substeps h = dt / 8): measured 8.4 mm
    // below. 2 cm is the bound, below the 0.1 m that a push at the platform's underside for a
    // single step would cost.
    assert!(
        (throw.apex - throw.free_apex).abs() < 0.02,
        "apex {} against {}",
        throw.apex,
        throw.free_apex
    );
    // It starts touching the platform once: when it lands on top.
    assert_eq!(throw.platform_starts, 1);
    // At rest on top: the contact spring's sag under a 65 kg ball is well under a millimetre;
    // measured worst position error plus speed 2e-5 over the 2.5 s window, bound 2 mm.
    assert!(throw.worst_rest < 2.0e-3, "worst {}", throw.worst_rest);
}

/// A marble too fast for its contacts (more than four radii a step: the continuous pass sweeps
/// it) passes up through a one-way platform all the same, and the sweep stops it on top when it
/// comes down.
#[test]
fn a_fast_marble_passes_up_through_a_one_way_platform_and_lands_on_it() {
    // Up 2.55 s, down 2.46 s from the apex to the platform: at rest from 6 s on.
    let throw = throw_through_platform(0.05, 25.0, 420, 360);
    // It crossed at 24.3 m/s, 0.41 m a step: more than its four radii (0.2 m), and more than
    // the platform's thickness and its diameter (0.3 m), so the sweep sees it pass.
    assert!(throw.fastest_at_platform * DT > 0.3);
    // The free flight's apex, 31.92 m, less g h t / 2 = 26 mm (t = 2.55 s, h = dt / 8):
    // measured 25.7 mm below; bound 5 cm. Stopped under the platform for a step, as the sweep
    // without the one-way rule does, it lost 5 m.
    assert!(
        (throw.apex - throw.free_apex).abs() < 0.05,
        "apex {} against {}",
        throw.apex,
        throw.free_apex
    );
    // It touches the platform twice: for one step as it leaves the top (a step ended with it
    // less than 5 cm inside, where the contact counts again; moving away, it is pushed
    // by nothing), and when it lands.
    assert_eq!(throw.platform_starts, 2);
    // Measured worst position error plus speed 2e-5 over the last second; bound 2 mm.
    assert!(throw.worst_rest < 2.0e-3, "worst {}", throw.worst_rest);
}

/// A box dropped on a one-way platform stands on it, as on a solid one; turned upside down, its
/// one-way direction points down and the box falls through onto the ground.
#[test]
fn a_box_dropped_on_a_one_way_platform_stands_and_one_upside_down_lets_it_through() {
    for (rotation, stands) in [
        (Quat::IDENTITY, true),
        (Quat::from_rotation_x(std::f32::consts::PI), false),
    ] {
        let (mut world, _) = platform_world(rotation);
        let crate_ = world
            .add_body(unit_box(Vec3::new(0.5, 4.0, 0.0)).can_sleep(false))
            .unwrap();
        run(&mut world, 120);
        let expected = if stands { 2.6 } else { 0.5 };
        let mut worst = 0.0f32;
        for _ in 0..120 {
            world.step(DT).unwrap();
            let body = world.body(crate_).unwrap();
            let error = (body.position().y - expected).abs() + body.linear_velocity().length();
            worst = worst.max(error);
        }
        // Measured 2e-5 (position error plus speed: the contact spring's sag) on the platform
        // and on the ground; 5 mm is the bound, far below the 2.1 m between the two.
        assert!(worst < 5.0e-3, "stands {stands}: worst {worst}");
    }
}

/// A box sliding on the ground into the edge of a low one-way platform meets its side with a
/// sideways normal, so it passes into it; inside, the contact's normal points down from the
/// platform (the box's centre is below the platform's), so it passes through it and slides on.
#[test]
fn a_box_sliding_into_a_one_way_platforms_edge_passes_through() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, 0.0);
    world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(1.0, 0.1, 1.0)).unwrap())
                .position(Vec3::new(3.0, 0.35, 0.0))
                .one_way(Vec3::Y),
        )
        .unwrap();
    let crate_ = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.25)).unwrap())
                .position(Vec3::new(0.0, 0.25, 0.0))
                .linear_velocity(Vec3::new(4.0, 0.0, 0.0))
                .friction(0.0),
        )
        .unwrap();
    run(&mut world, 120);
    // Frictionless: 2 s at 4 m/s is 8 m, past the platform's far edge at 4 m. Measured 8 m and
    // 4 m/s to 4e-5; 1 % is the bound (nothing along x acts on it).
    let body = world.body(crate_).unwrap();
    assert!(
        (body.position().x - 8.0).abs() < 0.08,
        "{}",
        body.position()
    );
    assert!((body.linear_velocity().x - 4.0).abs() < 0.04);
}

/// A hook that switches off every contact of one ball lets it fall through the ground; switching
/// off some points of a box's contact tips it over the points left; the contacts after the step
/// are as found, the switched-off points with no impulse.
#[test]
fn switched_off_contacts_and_points_push_nothing() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let ground = add_ground(&mut world, 0.5);
    let ghost = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(0.25).unwrap()).position(Vec3::new(-3.0, 0.25, 0.0)),
        )
        .unwrap();
    let solid = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(0.25).unwrap()).position(Vec3::new(3.0, 0.25, 0.0)),
        )
        .unwrap();
    run_hooked(&mut world, 30, |contact| {
        if contact.bodies().1 == ghost {
            contact.set_enabled(false);
            assert!(!contact.is_enabled());
        }
    });
    // Free fall for 0.5 s: −g t² / 2 = −1.23 m from 0.25 (the ground is no obstacle), less the
    // integration's g h t / 2 = 5.1 mm (substeps h = dt / 8): measured 5 mm below; bound 5 cm.
    let fallen = world.body(ghost).unwrap().position().y;
    let free = 0.25 - 0.5 * G * 0.25;
    assert!((fallen - free).abs() < 0.05, "{fallen} against {free}");
    assert!((world.body(solid).unwrap().position().y - 0.25).abs() < 2.0e-3);
    assert!(!world.touching_pairs().any(|pair| pair == (ground, ghost)));

    // A box on the ground with its two points at −x switched off stands on the +x edge alone,
    // and tips toward −x.
    let mut world = common::world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, 0.5);
    let crate_ = world.add_body(unit_box(Vec3::new(0.0, 0.5, 0.0))).unwrap();
    run(&mut world, 10);
    let mut switched_off = 0;
    run_hooked(&mut world, 1, |contact| {
        for index in 0..contact.points().len() {
            if contact.points()[index].position.x < 0.0 {
                contact.set_point_enabled(index, false).unwrap();
                assert!(!contact.is_point_enabled(index));
                switched_off += 1;
            }
        }
        let error = contact.set_point_enabled(9, false).unwrap_err();
        assert_eq!(error.field, "point");
    });
    assert_eq!(switched_off, 2);
    // As found after the step: four points, the two switched off with no impulse.
    let contact = world.contacts()[0];
    assert_eq!(contact.points().len(), 4);
    for (point, &impulse) in contact.points().iter().zip(contact.normal_impulses()) {
        assert_eq!(
            point.position.x < 0.0,
            impulse == 0.0,
            "{point:?}: {impulse}"
        );
    }
    run_hooked(&mut world, 30, |contact| {
        for index in 0..contact.points().len() {
            if contact.points()[index].position.x < 0.0 {
                contact.set_point_enabled(index, false).unwrap();
            }
        }
    });
    // Held up at its +x edge only, the box turns about z: toward −x is a positive angle.
    let (axis, angle) = world.body(crate_).unwrap().rotation().to_axis_angle();
    assert!(axis.z * angle > 0.1, "turned {angle} about {axis}");
}

/// A hook's friction, restitution and normal: a frictionless hook lets a box slide down a 30°
/// incline at g sin 30°; a restitution of 1 bounces a ball back to its height; a normal turned
/// to +X pushes a resting box sideways.
#[test]
fn a_hooks_friction_restitution_and_normal_reach_the_solver() {
    // Frictionless on a 30° incline whose friction (0.9) would hold the box.
    let angle = 30f32.to_radians();
    let mut world = common::world(Vec3::new(0.0, -G, 0.0));
    common::add_incline(&mut world, angle, 0.9);
    let rotation = Quat::from_rotation_z(angle);
    let crate_ = world
        .add_body(
            unit_box(rotation * Vec3::new(0.0, 0.5, 0.0))
                .rotation(rotation)
                .friction(0.9),
        )
        .unwrap();
    run_hooked(&mut world, 60, |contact| {
        assert!((contact.friction() - 0.9).abs() < 1.0e-6);
        contact.set_friction(0.0).unwrap();
        assert_eq!(contact.set_friction(-1.0).unwrap_err().field, "friction");
        assert_eq!(contact.friction(), 0.0);
    });
    // After 1 s, v = g sin 30° = 4.905 m/s down the slope; measured within 1e-6 relative, bound
    // 2 % (with the incline's friction 0.9 it would not move).
    let speed = world.body(crate_).unwrap().linear_velocity().length();
    assert!(
        (speed - G * angle.sin()).abs() < 0.02 * G * angle.sin(),
        "{speed}"
    );

    // A ball dropped from 2 m with restitution set to 1 by the hook bounces as one whose own
    // restitution is 1: the same bits.
    let apexes = [false, true].map(|hooked| {
        let mut world = common::world(Vec3::new(0.0, -G, 0.0));
        add_ground(&mut world, 0.5);
        let ball = BodyDesc::dynamic(Shape::sphere(0.25).unwrap())
            .position(Vec3::new(0.0, 2.0, 0.0))
            .restitution(if hooked { 0.0 } else { 1.0 });
        let ball = world.add_body(ball).unwrap();
        let mut hook = |contact: &mut ContactModification| {
            if hooked {
                contact.set_restitution(1.0).unwrap();
            }
            assert_eq!(contact.restitution(), 1.0);
            let error = contact.set_restitution(1.5).unwrap_err();
            assert_eq!(error.field, "restitution");
        };
        common::apex_after_bounce(240, || {
            world.step_with_hooks(DT, &mut hook).unwrap();
            let body = world.body(ball).unwrap();
            (body.position().y, body.linear_velocity().y)
        })
    });
    assert_eq!(apexes[0], apexes[1]);
    // Measured 1.91 m, as the ball's own restitution gives; its bounce is elastic at the
    // speed it struck with, and the fall's discretisation and the contact's speculative stop
    // cost the rest. 1.8 m bounds it far above a ball without restitution (0.25 m).
    assert!(apexes[0] > 1.8, "apex {}", apexes[0]);

    // A resting box whose contact normal is turned 45° toward +X is pushed up and along +X.
    let mut world = common::world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, 0.0);
    let crate_ = world
        .add_body(
            unit_box(Vec3::new(0.0, 0.5, 0.0))
                .friction(0.0)
                .can_sleep(false),
        )
        .unwrap();
    run(&mut world, 30);
    run_hooked(&mut world, 30, |contact| {
        assert_eq!(
            contact.set_normal(Vec3::ZERO).unwrap_err().kind,
            ErrorKind::ZeroVector
        );
        contact.set_normal(Vec3::new(1.0, 1.0, 0.0)).unwrap();
        assert!((contact.normal().length() - 1.0).abs() < 1.0e-6);
    });
    // The support now pushes along (1, 1)/√2 only, so the frictionless box slides down the
    // plane across it, along (1, −1)/√2, at g sin 45° t = 3.468 m/s after 0.5 s; measured
    // 3.465 (the push-out, along the normal, is not in it), bound 1 %.
    let velocity = world.body(crate_).unwrap().linear_velocity();
    let along = velocity.dot(Vec3::new(1.0, -1.0, 0.0).normalize());
    let expected = G * std::f32::consts::FRAC_1_SQRT_2 * 0.5;
    assert!((along - expected).abs() < 0.01 * expected, "{velocity}");
}

/// The hook is called once per contact with points, in the order of the contacts, seeing both
/// bodies.
#[test]
fn the_hook_sees_each_contact_once_in_contact_order() {
    let mut world = common::world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, 0.5);
    for index in 0..5 {
        world
            .add_body(unit_box(Vec3::new(2.0 * index as f32, 0.5, 0.0)))
            .unwrap();
    }
    run(&mut world, 5);
    let mut seen = Vec::new();
    run_hooked(&mut world, 1, |contact| {
        // The ground (static, added first) is A, a box B.
        assert!(contact.body_a().mass() == 0.0 && contact.body_b().mass() > 0.0);
        seen.push((contact.bodies(), contact.colliders()));
    });
    let contacts: Vec<_> = world
        .contacts()
        .iter()
        .filter(|contact| !contact.points().is_empty())
        .map(|contact| (contact.bodies(), contact.children()))
        .collect();
    assert_eq!(seen, contacts);
    assert_eq!(seen.len(), 5);
}

/// Bad one-way directions and surface velocities are refused naming the field, by the library
/// and at their JSON path by a scene file.
#[test]
fn bad_one_way_directions_and_surface_velocities_are_refused() {
    let mut world = common::world(Vec3::new(0.0, -G, 0.0));
    let platform = || BodyDesc::static_body(Shape::cuboid(Vec3::splat(1.0)).unwrap());
    for (desc, field, kind) in [
        (
            platform().one_way(Vec3::ZERO),
            "one_way",
            ErrorKind::ZeroVector,
        ),
        (
            platform().one_way(Vec3::new(f32::NAN, 1.0, 0.0)),
            "one_way",
            ErrorKind::NotFinite,
        ),
        (
            platform().surface_velocity(Vec3::new(0.0, f32::INFINITY, 0.0)),
            "surface_velocity",
            ErrorKind::NotFinite,
        ),
    ] {
        let error = world.add_body(desc).unwrap_err();
        assert_eq!((error.field.as_str(), error.kind), (field, kind));
    }
    let too_fast = world.add_body(platform().surface_velocity(Vec3::new(2.0e4, 0.0, 0.0)));
    assert_eq!(too_fast.unwrap_err().field, "surface_velocity");
    assert_eq!(world.body_count(), 0);

    let body = world.add_body(platform().one_way(Vec3::Y)).unwrap();
    let error = world.set_one_way(body, Some(Vec3::ZERO)).unwrap_err();
    assert_eq!(error.field, "one_way");
    assert_eq!(
        world.body(body).unwrap().one_way(),
        Some(Vec3::Y),
        "kept on error"
    );
    let error = world.set_surface_velocity(body, Vec3::splat(f32::NAN));
    assert_eq!(error.unwrap_err().field, "surface_velocity");
    world
        .set_one_way(body, Some(Vec3::new(0.0, 0.0, -2.0)))
        .unwrap();
    assert_eq!(world.body(body).unwrap().one_way(), Some(-Vec3::Z));
    world.set_one_way(body, None).unwrap();
    assert_eq!(world.body(body).unwrap().one_way(), None);

    for (field, value, place) in [
        ("one_way", "[0, 0, 0]", "bodies[0].one_way"),
        ("one_way", "[0, 1e39, 0]", "bodies[0].one_way[1]"),
        (
            "surface_velocity",
            "[1e5, 0, 0]",
            "bodies[0].surface_velocity",
        ),
        (
            "surface_velocity",
            "[0, 0, -1e40]",
            "bodies[0].surface_velocity[2]",
        ),
    ] {
        let json = format!(
            r#"{{ "bodies": [ {{ "type": "static", "{field}": {value},
                "shape": {{ "type": "box", "half_extents": [1, 1, 1] }} }} ] }}"#
        );
        let error = Scene::from_json(json.as_bytes()).unwrap_err();
        assert_eq!(error.place, place, "{field}: {value}: {}", error.message);
    }
    let json = r#"{ "bodies": [ { "type": "static", "one_way": [0, 2, 0],
        "surface_velocity": [1, 0, 0], "shape": { "type": "box", "half_extents": [1, 1, 1] } } ] }"#;
    let scene = Scene::from_json(json.as_bytes()).unwrap();
    let (_, body) = scene.bodies().next().unwrap();
    assert_eq!(body.one_way(), Some(Vec3::Y));
    assert_eq!(body.surface_velocity(), Vec3::X);
}

/// A saved world with a conveyor and a one-way platform resumes exactly, bit for bit, and
/// another build's reading keeps the rules.
#[test]
fn a_world_with_contact_rules_resumes_exactly() {
    let (mut world, _) = platform_world(Quat::IDENTITY);
    world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(2.0, 0.25, 1.0)).unwrap())
                .position(Vec3::new(6.0, 0.25, 0.0))
                .surface_velocity(Vec3::X),
        )
        .unwrap();
    world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(0.25).unwrap())
                .position(Vec3::new(0.0, 0.3, 0.0))
                .linear_velocity(Vec3::new(0.0, 8.0, 0.0)),
        )
        .unwrap();
    world.add_body(unit_box(Vec3::new(5.0, 1.5, 0.0))).unwrap();
    run(&mut world, 40);
    let saved = world.save_state();
    // Another build reads the portable snapshot, which keeps the rules.
    let rebuilt = World::load_state_as_other_build(&saved).unwrap();
    for ((_, a), (_, b)) in world.bodies().zip(rebuilt.bodies()) {
        assert_eq!(a.one_way(), b.one_way());
        assert_eq!(a.surface_velocity(), b.surface_velocity());
    }
    let mut resumed = World::load_state(&saved).unwrap();
    run(&mut world, 60);
    run(&mut resumed, 60);
    for ((_, a), (_, b)) in world.bodies().zip(resumed.bodies()) {
        assert_eq!(a.position(), b.position());
        assert_eq!(a.one_way(), b.one_way());
        assert_eq!(a.surface_velocity(), b.surface_velocity());
    }
}
