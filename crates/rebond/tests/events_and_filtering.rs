//! Contact events, force reports, sensors and collision filtering, against closed forms where
//! there is one (bounce times, crossing times, a resting body's weight) and against the
//! bookkeeping rules otherwise (each start stopped once, sorted lists); `tests/allocation.rs`
//! checks that a steady step with events and sensors allocates nothing.

mod common;

use common::{add_ground, run, unit_box, world, DT, G};
use rebond::{
    BodyDesc, BodyHandle, ContactEvent, ContactEventKind, ErrorKind, InteractionGroups,
    QueryFilter, Ray, SensorEvent, SensorEventKind, Shape, Vec3, World,
};

fn zero_gravity() -> World {
    world(Vec3::ZERO)
}

fn ball(radius: f32, position: Vec3) -> BodyDesc {
    BodyDesc::dynamic(Shape::sphere(radius).unwrap()).position(position)
}

/// The events of the pair `{a, b}` in the last step.
fn pair_events(world: &World, a: BodyHandle, b: BodyHandle) -> Vec<ContactEventKind> {
    world
        .contact_events()
        .iter()
        .filter(|event| (event.body_a, event.body_b) == (a.min(b), a.max(b)))
        .map(|event| event.kind)
        .collect()
}

#[test]
fn a_ball_bouncing_three_times_starts_and_stops_touching_three_times() {
    // A ball of restitution e dropped with its bottom h above the floor lands at
    // t₁ = √(2h/g) with speed v₀ = √(2gh), and after the i-th bounce flies for 2 eⁱ v₀ / g.
    // We run until the top of the third rebound, halfway to a fourth landing.
    let (height, e, radius) = (1.0f32, 0.7f32, 0.25f32);
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let ground = add_ground(&mut world, 0.5);
    let ball = world
        .add_body(ball(radius, Vec3::new(0.0, radius + height, 0.0)).restitution(e))
        .unwrap();
    let v0 = (2.0 * G * height).sqrt();
    let mut landings = vec![(2.0 * height / G).sqrt()];
    for bounce in 1..3 {
        let last = landings[bounce - 1];
        landings.push(last + 2.0 * e.powi(bounce as i32) * v0 / G);
    }
    let end = landings[2] + e.powi(3) * v0 / G;

    let mut starts = Vec::new();
    let mut stops = Vec::new();
    let mut touching = false;
    for step in 0..(end / DT) as usize {
        world.step(DT).unwrap();
        let time = (step + 1) as f32 * DT;
        for kind in pair_events(&world, ground, ball) {
            match kind {
                ContactEventKind::Started => {
                    assert!(!touching, "started twice without a stop at t = {time}");
                    starts.push(time);
                }
                ContactEventKind::Stopped => {
                    assert!(touching, "stopped without a start at t = {time}");
                    stops.push(time);
                }
            }
            touching = kind == ContactEventKind::Started;
        }
        assert_eq!(
            world.contact_events().len(),
            pair_events(&world, ground, ball).len(),
            "only the ball and the floor can touch"
        );
    }
    assert_eq!(
        starts.len(),
        3,
        "starts at {starts:?}, expected near {landings:?}"
    );
    assert_eq!(stops.len(), 3, "stops at {stops:?}");
    // Tolerance: a landing is reported at the end of the step that solves it, within a step of
    // the closed form either way (the semi-implicit substeps fall ahead of the parabola by
    // ½ g h t, 5 mm at the first landing, and the speculative contact pushes in the substep
    // before the touch). The bounce itself uses the approach speed at the start of the landing
    // step, up to g dt below the impact speed, so each rebound flight 2v/g is up to 2 dt
    // shorter: landing i may come up to (1 + 2i) dt early.
    for (index, (&start, &landing)) in starts.iter().zip(&landings).enumerate() {
        let early = (1.0 + 2.0 * index as f32) * DT + 1e-4;
        assert!(
            start >= landing - early && start <= landing + DT + 1e-4,
            "landing {index}: started at {start} s, expected at {landing} s"
        );
    }
    // A bounce is over within a few steps: the ball leaves the floor during the bounce step.
    for (start, stop) in starts.iter().zip(&stops) {
        assert!(
            stop - start <= 3.0 * DT + 1e-4,
            "touched from {start} s to {stop} s"
        );
    }
}

#[test]
fn a_sensor_reports_each_enter_and_exit_once_and_changes_no_velocity() {
    // A ball of radius r at speed v crosses a static sensor box of half extent a centred on the
    // origin: it starts at x₀ = −5 and overlaps the box while |x| ≤ a + r, from
    // t_in = (−a − r − x₀) / v to t_out = (a + r − x₀) / v. The overlap is tested at the end of
    // each step, so each event comes at the first step end past the crossing time.
    let (half, radius, speed, start) = (1.0f32, 0.3f32, 2.0f32, -5.0f32);
    let mut world = zero_gravity();
    let sensor = world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::splat(half)).unwrap())
                .sensor(true)
                .restitution(1.0),
        )
        .unwrap();
    let velocity = Vec3::new(speed, 0.0, 0.0);
    let ball = world
        .add_body(ball(radius, Vec3::new(start, 0.0, 0.0)).linear_velocity(velocity))
        .unwrap();
    let t_in = (-half - radius - start) / speed;
    let t_out = (half + radius - start) / speed;
    let mut events: Vec<(f32, SensorEvent)> = Vec::new();
    let steps = 360;
    for step in 0..steps {
        world.step(DT).unwrap();
        let time = (step + 1) as f32 * DT;
        events.extend(world.sensor_events().iter().map(|&event| (time, event)));
        assert_eq!(world.body(ball).unwrap().linear_velocity(), velocity);
        assert!(world.contacts().is_empty(), "a sensor makes no contacts");
        assert!(world.touching_pairs().next().is_none());
        let inside = world.sensor_overlaps().eq([(sensor, ball)]);
        // Tolerance: the ball moves v dt = 3.3 cm a step; 1e-4 s covers f32 rounding of times.
        if time > t_in + 1e-4 && time < t_out - 1e-4 {
            assert!(inside, "the ball is inside at t = {time}");
        }
        if time < t_in - 1e-4 || time > t_out + 1e-4 {
            assert!(!inside, "the ball is outside at t = {time}");
        }
    }
    assert_eq!(events.len(), 2, "{events:?}");
    let [(entered_at, entered), (exited_at, exited)] = [events[0], events[1]];
    assert_eq!(
        (entered.sensor, entered.body, entered.kind),
        (sensor, ball, SensorEventKind::Entered)
    );
    assert_eq!(
        (exited.sensor, exited.body, exited.kind),
        (sensor, ball, SensorEventKind::Exited)
    );
    assert!(entered_at >= t_in - 1e-4 && entered_at <= t_in + DT + 1e-4);
    assert!(exited_at >= t_out - 1e-4 && exited_at <= t_out + DT + 1e-4);
    // x(t) = x₀ + v t exactly: nothing pushed the ball. f32 sums of v dt drift by about
    // 360 steps × 2⁻²³ × 5 m ≈ 0.2 mm.
    let x = world.body(ball).unwrap().position().x;
    let expected = start + speed * steps as f32 * DT;
    assert!((x - expected).abs() < 1e-3, "x = {x}, expected {expected}");
}

#[test]
fn a_moving_sensor_sees_static_and_sleeping_bodies_without_waking_them() {
    // A kinematic sensor slab sweeps along x over a static box and a box asleep on the floor;
    // each is entered and left once, the sleeper sleeps on, and nothing moves but the sensor.
    // A static sensor over the same static box never sees it: two static bodies are never paired.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let ground = add_ground(&mut world, 0.5);
    let post = world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::splat(0.5)).unwrap())
                .position(Vec3::new(3.0, 0.5, 0.0)),
        )
        .unwrap();
    let sleeper = world.add_body(unit_box(Vec3::new(6.0, 0.5, 0.0))).unwrap();
    let static_sensor = world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::splat(1.0)).unwrap())
                .position(Vec3::new(3.0, 0.5, 0.0))
                .sensor(true),
        )
        .unwrap();
    run(&mut world, 120);
    assert!(world.body(sleeper).unwrap().is_sleeping());
    let sleeper_pose = world.body(sleeper).unwrap().pose();

    let sweep = world
        .add_body(
            BodyDesc::kinematic(Shape::cuboid(Vec3::new(0.25, 1.0, 1.0)).unwrap())
                .position(Vec3::new(0.0, 1.0, 0.0))
                .linear_velocity(Vec3::new(3.0, 0.0, 0.0))
                .sensor(true),
        )
        .unwrap();
    let mut events = Vec::new();
    for _ in 0..(3.0 / DT) as usize {
        world.step(DT).unwrap();
        events.extend(
            world
                .sensor_events()
                .iter()
                .map(|e| (e.sensor, e.body, e.kind)),
        );
        assert!(world
            .contacts()
            .iter()
            .all(|c| c.bodies().0 != sweep && c.bodies().1 != sweep));
    }
    use SensorEventKind::{Entered, Exited};
    // The slab sits 1 m up with half height 1: it overlaps the floor's top face from the start.
    let expected = [
        (sweep, ground, Entered),
        (sweep, post, Entered),
        (sweep, post, Exited),
        (sweep, sleeper, Entered),
        (sweep, sleeper, Exited),
    ];
    assert_eq!(events, expected);
    assert!(
        world.body(sleeper).unwrap().is_sleeping(),
        "a sensor wakes nobody"
    );
    assert_eq!(world.body(sleeper).unwrap().pose(), sleeper_pose);
    assert!(world
        .sensor_overlaps()
        .all(|(sensor, _)| sensor != static_sensor));
}

#[test]
fn a_body_asleep_inside_a_sensor_stays_inside() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, 0.5);
    let zone = world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(2.0, 1.0, 2.0)).unwrap())
                .position(Vec3::new(0.0, 1.0, 0.0))
                .sensor(true),
        )
        .unwrap();
    let crate_box = world.add_body(unit_box(Vec3::new(0.0, 3.0, 0.0))).unwrap();
    let mut events = Vec::new();
    for _ in 0..300 {
        world.step(DT).unwrap();
        events.extend_from_slice(world.sensor_events());
    }
    assert!(world.body(crate_box).unwrap().is_sleeping());
    assert!(world.sensor_overlaps().eq([(zone, crate_box)]));
    assert_eq!(events.len(), 1, "entered once, never left: {events:?}");
    assert_eq!(events[0].kind, SensorEventKind::Entered);

    // A sensor added around the sleeping box sees it at the next step, and lets it sleep.
    let late = world
        .add_body(
            BodyDesc::static_body(Shape::sphere(1.0).unwrap())
                .position(Vec3::new(0.0, 0.5, 0.0))
                .sensor(true),
        )
        .unwrap();
    world.step(DT).unwrap();
    assert_eq!(
        world.sensor_events(),
        [SensorEvent {
            sensor: late,
            body: crate_box,
            kind: SensorEventKind::Entered,
            sensor_collider: 0,
            collider: 0,
        }]
    );
    assert!(world.body(crate_box).unwrap().is_sleeping());
}

/// Two boxes flying head-on at each other along x in zero gravity, 4 m apart, at 2 m/s each.
fn head_on(world: &mut World, groups: [InteractionGroups; 2]) -> [BodyHandle; 2] {
    [(-2.0f32, 2.0f32, groups[0]), (2.0, -2.0, groups[1])].map(|(x, v, groups)| {
        world
            .add_body(
                unit_box(Vec3::new(x, 0.0, 0.0))
                    .linear_velocity(Vec3::new(v, 0.0, 0.0))
                    .collision_groups(groups),
            )
            .unwrap()
    })
}

#[test]
fn bodies_in_groups_that_exclude_each_other_pass_through_without_reaching_the_narrow_phase() {
    let player = InteractionGroups::new(0b001, 0b110);
    let ghost = InteractionGroups::new(0b010, 0b100);
    assert!(!player.interacts_with(ghost));

    let mut world = zero_gravity();
    let [a, b] = head_on(&mut world, [player, ghost]);
    for _ in 0..120 {
        world.step(DT).unwrap();
        assert_eq!(world.broad_phase_pairs().count(), 0);
        assert_eq!(world.narrow_phase_pair_tests(), 0);
        assert!(world.contacts().is_empty());
        assert!(world.contact_events().is_empty());
    }
    // After 2 s each has travelled 4 m, unhindered (f32 sums of 120 steps: well under 1 mm).
    assert!((world.body(a).unwrap().position().x - 2.0).abs() < 1e-3);
    assert!((world.body(b).unwrap().position().x + 2.0).abs() < 1e-3);

    // The control: in groups that interact, the same boxes collide.
    let mut world = zero_gravity();
    let [a, b] = head_on(&mut world, [player, InteractionGroups::new(0b010, 0b001)]);
    let mut tested = 0;
    for _ in 0..120 {
        world.step(DT).unwrap();
        tested += world.narrow_phase_pair_tests();
    }
    assert!(tested > 0);
    assert!(world.body(a).unwrap().position().x < world.body(b).unwrap().position().x);
}

#[test]
fn ignoring_a_pair_or_changing_groups_at_runtime_drops_its_contacts() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let ground = add_ground(&mut world, 0.5);
    let bottom = world.add_body(unit_box(Vec3::new(0.0, 0.5, 0.0))).unwrap();
    let top = world.add_body(unit_box(Vec3::new(0.0, 1.5, 0.0))).unwrap();
    run(&mut world, 60);
    let touching = |world: &World, a: BodyHandle, b: BodyHandle| {
        world
            .touching_pairs()
            .any(|pair| pair == (a.min(b), a.max(b)))
    };
    assert!(touching(&world, bottom, top));

    world.set_pair_ignored(top, bottom, true).unwrap();
    assert!(world.is_pair_ignored(bottom, top));
    let in_contacts = |world: &World, a: BodyHandle, b: BodyHandle| {
        world
            .contacts()
            .iter()
            .any(|contact| contact.bodies() == (a.min(b), a.max(b)))
    };
    assert!(!in_contacts(&world, bottom, top), "dropped at once");
    world.step(DT).unwrap();
    assert_eq!(
        pair_events(&world, bottom, top),
        [ContactEventKind::Stopped]
    );
    let pair = (bottom.min(top), bottom.max(top));
    for _ in 0..120 {
        world.step(DT).unwrap();
        assert!(!world.broad_phase_pairs().any(|p| p == pair));
        assert!(!in_contacts(&world, bottom, top));
    }
    // The top box fell through the bottom one onto the floor: both rest at y = 0.5 (to the
    // floor's few-millimetre soft-contact sink).
    let y = world.body(top).unwrap().position().y;
    assert!((y - 0.5).abs() < 0.01, "top box at y = {y}");
    assert!(touching(&world, ground, top));

    world.set_pair_ignored(top, bottom, false).unwrap();
    world.step(DT).unwrap();
    assert!(world.broad_phase_pairs().any(|p| p == pair));

    world
        .set_collision_groups(top, InteractionGroups::NONE)
        .unwrap();
    assert!(!in_contacts(&world, ground, top));
    run(&mut world, 60);
    assert!(
        world.body(top).unwrap().position().y < -1.0,
        "fell through the floor"
    );
    assert!(world.broad_phase_pairs().all(|(a, b)| a != top && b != top));
}

#[test]
fn bodies_asleep_on_a_floor_that_stops_interacting_wake_and_fall() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let ground = add_ground(&mut world, 0.5);
    let bottom = world.add_body(unit_box(Vec3::new(0.0, 0.5, 0.0))).unwrap();
    let top = world.add_body(unit_box(Vec3::new(0.0, 1.5, 0.0))).unwrap();
    run(&mut world, 120);
    assert!(world.body(top).unwrap().is_sleeping());
    world
        .set_collision_groups(ground, InteractionGroups::new(0b10, 0))
        .unwrap();
    run(&mut world, 60);
    // 1 s of free fall: 4.9 m down; the pair of boxes still interacts and falls as a stack.
    for (body, start) in [(bottom, 0.5), (top, 1.5)] {
        let y = world.body(body).unwrap().position().y;
        assert!(y < start - 4.0, "fell through the floor: y = {y}");
    }
    // In free fall the top box rides on the bottom one without weight, still stacked and in
    // contact. The soft contact's sag under the top box's weight (0.035 mm at 120 Hz) springs
    // back once the weight is gone, so the surfaces may part by a hair: the pair keeps its
    // (speculative) contact instead of touching.
    let gap = world.body(top).unwrap().position().y - world.body(bottom).unwrap().position().y;
    assert!((gap - 1.0).abs() < 0.01, "stacked 1 m apart: {gap}");
    let pair = (bottom.min(top), bottom.max(top));
    assert!(world
        .contacts()
        .iter()
        .any(|contact| contact.bodies() == pair));
    // Nothing touches: the floor no longer interacts with the boxes, and the boxes, which
    // carry no load in free fall, part by a hair (measured 0.86 mm, their contact's impulses
    // all 0).
    let touching: Vec<_> = world.touching_pairs().collect();
    assert_eq!(touching, [], "the floor or the falling boxes still touch");
}

#[test]
fn a_resting_box_reports_its_weight_above_the_threshold_and_nothing_below() {
    // At rest the floor carries the box's weight: the normal impulse of each substep is m g h,
    // so the reported force Σλ/h is m g. Tolerance 1 %: the soft contact settles to rest within
    // the first second, leaving the solver's residual velocity of a few mm/s changing by far
    // less than 1 % of g h per substep.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let ground = add_ground(&mut world, 0.5);
    let mass = 3.0;
    let heavy = world
        .add_body(
            unit_box(Vec3::new(0.0, 0.5, 0.0))
                .mass(mass)
                .contact_force_threshold(mass * G * 0.9),
        )
        .unwrap();
    let light = world
        .add_body(
            unit_box(Vec3::new(3.0, 0.5, 0.0))
                .mass(mass)
                .contact_force_threshold(mass * G * 1.1),
        )
        .unwrap();
    run(&mut world, 60);
    let events = world.contact_force_events();
    assert_eq!(events.len(), 1, "{events:?}");
    let event = events[0];
    assert_eq!((event.body_a, event.body_b), (ground, heavy));
    let weight = mass * G;
    assert!(
        (event.total_force_magnitude - weight).abs() < 0.01 * weight,
        "force {} N, weight {weight} N",
        event.total_force_magnitude
    );
    assert!((event.total_force - Vec3::new(0.0, weight, 0.0)).length() < 0.01 * weight);
    assert!(world.touching_pairs().any(|pair| pair == (ground, light)));

    assert!(matches!(
        world
            .body_mut(light)
            .unwrap()
            .set_contact_force_threshold(-1.0)
            .unwrap_err()
            .kind,
        ErrorKind::Negative(_)
    ));
    let error = world
        .add_body(unit_box(Vec3::ZERO).contact_force_threshold(f32::NAN))
        .unwrap_err();
    assert_eq!(error.field, "contact_force_threshold");
}

/// Starts and stops of every pair over a run of a falling pile, checked against the touching
/// lists: a start only for a pair that was not touching, a stop only for one that was. Pairs are
/// logged by their bodies' slots, which two runs share, not by handles, which carry each world's
/// own identity.
fn event_log(seed: u32) -> Vec<Vec<(usize, usize, ContactEventKind)>> {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, 0.5);
    for index in 0..40u32 {
        let spread = ((index * 7 + seed) % 11) as f32 * 0.13;
        let position = Vec3::new(
            (index % 4) as f32 * 1.1 - 1.6 + spread,
            1.0 + index as f32 * 0.7,
            ((index / 4) % 3) as f32 * 1.1 + spread,
        );
        let desc = if index % 2 == 0 {
            unit_box(position)
        } else {
            ball(0.45, position).restitution(0.5)
        };
        world.add_body(desc).unwrap();
    }
    let mut touching: Vec<(BodyHandle, BodyHandle)> = Vec::new();
    let mut log = Vec::new();
    for _ in 0..240 {
        world.step(DT).unwrap();
        let events = world.contact_events();
        assert!(events
            .windows(2)
            .all(|w| (w[0].body_a, w[0].body_b) < (w[1].body_a, w[1].body_b)));
        for event in events {
            let pair = (event.body_a, event.body_b);
            let was_touching = touching.contains(&pair);
            match event.kind {
                ContactEventKind::Started => assert!(!was_touching),
                ContactEventKind::Stopped => assert!(was_touching),
            }
        }
        touching = world.touching_pairs().collect();
        let slots = |event: &ContactEvent| (event.body_a.slot(), event.body_b.slot(), event.kind);
        log.push(events.iter().map(slots).collect());
    }
    assert!(log.iter().flatten().count() > 40, "the pile touched");
    log
}

#[test]
fn events_are_sorted_balanced_and_the_same_on_every_run() {
    assert_eq!(event_log(3), event_log(3));
}

#[test]
fn query_filters_use_collision_groups_and_can_skip_sensors() {
    let mut world = zero_gravity();
    let shape = || Shape::cuboid(Vec3::splat(0.5)).unwrap();
    let near = world
        .add_body(
            BodyDesc::static_body(shape())
                .position(Vec3::new(2.0, 0.0, 0.0))
                .sensor(true)
                .collision_groups(InteractionGroups::new(0b100, u32::MAX)),
        )
        .unwrap();
    let middle = world
        .add_body(
            BodyDesc::static_body(shape())
                .position(Vec3::new(4.0, 0.0, 0.0))
                .collision_groups(InteractionGroups::new(0b10, u32::MAX)),
        )
        .unwrap();
    let far = world
        .add_body(
            BodyDesc::static_body(shape())
                .position(Vec3::new(6.0, 0.0, 0.0))
                .collision_groups(InteractionGroups::new(0b01, u32::MAX)),
        )
        .unwrap();
    let ray = Ray::new(Vec3::ZERO, Vec3::X);
    let first = |filter: &QueryFilter| world.cast_ray(&ray, filter).unwrap().map(|hit| hit.body);
    assert_eq!(first(&QueryFilter::new()), Some(near));
    assert_eq!(first(&QueryFilter::new().exclude_sensors()), Some(middle));
    let only_group_one = InteractionGroups::new(u32::MAX, 0b01);
    assert_eq!(first(&QueryFilter::new().groups(only_group_one)), Some(far));
    assert_eq!(
        first(&QueryFilter::new().groups(InteractionGroups::NONE)),
        None
    );
}

#[test]
fn filter_calls_name_stale_handles() {
    let mut world = zero_gravity();
    let a = world.add_body(ball(0.5, Vec3::ZERO)).unwrap();
    let b = world.add_body(ball(0.5, Vec3::X)).unwrap();
    world.set_pair_ignored(a, b, true).unwrap();
    world.remove_body(b).unwrap();
    assert_eq!(
        world.set_pair_ignored(a, b, false).unwrap_err().kind,
        ErrorKind::StaleHandle
    );
    assert_eq!(
        world
            .set_collision_groups(b, InteractionGroups::NONE)
            .unwrap_err()
            .kind,
        ErrorKind::StaleHandle
    );
    assert!(
        !world.is_pair_ignored(a, b),
        "removing a body forgets its pairs"
    );
}

/// A box that lands on the floor inside a static sensor, falls asleep there and is woken keeps
/// touching the floor and stays inside the sensor throughout: one start, one entry, no stop, no
/// exit, and the sleeping pair is still listed.
#[test]
fn touching_pairs_and_overlaps_last_through_sleep_and_waking() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let ground = add_ground(&mut world, 0.6);
    let zone = world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::splat(2.0)).unwrap())
                .position(Vec3::new(0.0, 1.0, 0.0))
                .sensor(true),
        )
        .unwrap();
    let crate_box = world.add_body(unit_box(Vec3::new(0.0, 1.0, 0.0))).unwrap();
    let (mut contact_events, mut sensor_events) = (Vec::new(), Vec::new());
    let mut record = |world: &World| {
        contact_events.extend(world.contact_events().iter().map(|e| e.kind));
        sensor_events.extend(world.sensor_events().iter().map(|e| e.kind));
        assert!(world.touching_pairs().eq([(ground, crate_box)]) || world.contacts().is_empty());
    };
    for _ in 0..120 {
        world.step(DT).unwrap();
        record(&world);
    }
    assert!(world.body(crate_box).unwrap().is_sleeping());
    assert!(
        world.contacts().is_empty(),
        "the sleeping contact is parked"
    );
    assert!(world.touching_pairs().eq([(ground, crate_box)]));
    assert!(world.sensor_overlaps().eq([(zone, crate_box)]));
    world.body_mut(crate_box).unwrap().wake();
    for _ in 0..5 {
        world.step(DT).unwrap();
        record(&world);
        assert!(!world.body(crate_box).unwrap().is_sleeping());
        assert!(world.touching_pairs().eq([(ground, crate_box)]));
        assert!(world.sensor_overlaps().eq([(zone, crate_box)]));
    }
    assert_eq!(contact_events, [ContactEventKind::Started]);
    assert_eq!(sensor_events, [SensorEventKind::Entered]);
}

/// Removing a floor and a sensor from under sleeping boxes ends their touching pairs and overlaps
/// at the next step, with the removed bodies' handles, and the boxes wake and fall.
#[test]
fn removing_a_floor_and_a_sensor_under_sleeping_boxes_ends_their_pairs() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let ground = add_ground(&mut world, 0.6);
    let zone = world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(5.0, 1.0, 5.0)).unwrap())
                .position(Vec3::new(0.0, 1.0, 0.0))
                .sensor(true),
        )
        .unwrap();
    let boxes: Vec<BodyHandle> = (0..3)
        .map(|i| {
            world
                .add_body(unit_box(Vec3::new(2.0 * i as f32, 0.5, 0.0)))
                .unwrap()
        })
        .collect();
    run(&mut world, 120);
    assert!(boxes
        .iter()
        .all(|&handle| world.body(handle).unwrap().is_sleeping()));
    assert_eq!(world.touching_pairs().count(), 3);
    assert_eq!(world.sensor_overlaps().count(), 3);

    world.remove_body(zone).unwrap();
    world.step(DT).unwrap();
    let exits: Vec<_> = world
        .sensor_events()
        .iter()
        .map(|e| (e.sensor, e.kind))
        .collect();
    assert_eq!(exits, [(zone, SensorEventKind::Exited); 3]);
    assert_eq!(world.sensor_overlaps().count(), 0);
    assert!(
        boxes
            .iter()
            .all(|&handle| world.body(handle).unwrap().is_sleeping()),
        "a sensor wakes nobody"
    );

    world.remove_body(ground).unwrap();
    world.step(DT).unwrap();
    let stops: Vec<_> = world
        .contact_events()
        .iter()
        .map(|e| (e.body_a, e.kind))
        .collect();
    assert_eq!(stops, [(ground, ContactEventKind::Stopped); 3]);
    assert_eq!(world.touching_pairs().count(), 0);
    run(&mut world, 30);
    for &handle in &boxes {
        assert!(world.body(handle).unwrap().position().y < 0.0, "fell");
    }
}

/// A sleeping box's force report goes on each step, once, while other bodies fall asleep later.
#[test]
fn a_sleeping_box_keeps_reporting_its_weight_once() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let ground = add_ground(&mut world, 0.5);
    let heavy = world
        .add_body(unit_box(Vec3::new(0.0, 0.5, 0.0)).contact_force_threshold(G * 0.5))
        .unwrap();
    run(&mut world, 60);
    assert!(world.body(heavy).unwrap().is_sleeping());
    let late = world.add_body(unit_box(Vec3::new(5.0, 2.0, 0.0))).unwrap();
    for _ in 0..120 {
        world.step(DT).unwrap();
        let reported: Vec<_> = world
            .contact_force_events()
            .iter()
            .map(|event| (event.body_a, event.body_b))
            .collect();
        assert_eq!(reported, [(ground, heavy)]);
    }
    assert!(world.body(late).unwrap().is_sleeping());
}
