//! The character controller against analytic expectations: walls, slopes, steps, snapping,
//! platforms, pushes and the checks of its settings.
//!
//! The character is a capsule of radius 0.3 m and half height 0.5 m (1.6 m tall) standing on
//! floors whose top is y = 0, so it stands with its centre at 0.8 m plus the 1 cm offset. The
//! shape casts behind the controller stop within 1e-5 of the shapes' size on the near side
//! (docs/queries.md): with the floors here, 20 m across, 0.2 mm at most, and a cast's error
//! can only shorten a move.

use rebond::character::{CharacterController, CharacterMove, CharacterSettings};
use rebond::{
    BodyDesc, BodyHandle, ErrorKind, Pose, Quat, QueryFilter, Shape, Vec3, World, WorldSettings,
};

const DT: f32 = 1.0 / 60.0;
const RADIUS: f32 = 0.3;
const HALF_HEIGHT: f32 = 0.5;
const OFFSET: f32 = 0.01;
/// The centre's height of the capsule standing on a floor at y = 0.
const STANDING: f32 = RADIUS + HALF_HEIGHT + OFFSET;
/// How far the shape casts may fall short against the 20 m boxes of these scenes: 1e-5 of their
/// size (docs/queries.md), 0.2 mm.
const CAST_PRECISION: f32 = 2e-4;

fn world(gravity: Vec3) -> World {
    World::new(WorldSettings {
        gravity,
        ..WorldSettings::default()
    })
    .unwrap()
}

fn capsule() -> Shape {
    Shape::capsule(RADIUS, HALF_HEIGHT).unwrap()
}

/// A static box from `min` to `max`.
fn add_block(world: &mut World, min: Vec3, max: Vec3) -> BodyHandle {
    world
        .add_body(
            BodyDesc::static_body(Shape::cuboid((max - min) / 2.0).unwrap())
                .position((max + min) / 2.0),
        )
        .unwrap()
}

/// The floor y = 0 over x, z in [−10, 10].
fn add_floor(world: &mut World) -> BodyHandle {
    add_block(
        world,
        Vec3::new(-10.0, -1.0, -10.0),
        Vec3::new(10.0, 0.0, 10.0),
    )
}

/// A static slope through the origin rising toward +x at `angle` (a 20 m box turned about z), its
/// unit normal.
fn add_slope(world: &mut World, angle: f32) -> (BodyHandle, Vec3) {
    let rotation = Quat::from_rotation_z(angle);
    let body = world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(10.0, 0.5, 10.0)).unwrap())
                .position(rotation * Vec3::new(0.0, -0.5, 0.0))
                .rotation(rotation),
        )
        .unwrap();
    (body, rotation * Vec3::Y)
}

fn controller(settings: CharacterSettings) -> CharacterController {
    CharacterController::new(settings).unwrap()
}

/// Moves the capsule from `start` by `desired` each frame for `frames` frames in a world that
/// does not step, calling `check` after each move; the final position.
fn walk(
    world: &World,
    controller: &mut CharacterController,
    start: Vec3,
    desired: Vec3,
    frames: usize,
    mut check: impl FnMut(usize, Vec3, &CharacterMove),
) -> Vec3 {
    let shape = capsule();
    let mut position = start;
    for frame in 0..frames {
        let pose = Pose::from_position(position);
        let moved = controller
            .move_shape(world, &shape, &pose, desired, DT, &QueryFilter::default())
            .unwrap();
        position += moved.translation;
        check(frame, position, moved);
    }
    position
}

#[test]
fn flat_ground_is_reported_with_its_normal_and_body() {
    let mut world = world(Vec3::ZERO);
    let floor = add_floor(&mut world);
    let mut controller = controller(CharacterSettings::default());
    // Walking at 3 m/s while pushed down at 6 m/s: the floor holds the character up.
    let desired = Vec3::new(3.0, -6.0, 0.0) * DT;
    let start = Vec3::new(-5.0, STANDING, 0.0);
    let end = walk(
        &world,
        &mut controller,
        start,
        desired,
        60,
        |frame, position, moved| {
            let ground = moved.ground.expect("on the floor");
            assert_eq!(ground.body, floor, "frame {frame}");
            assert!(
                (ground.normal - Vec3::Y).length() < 1e-6,
                "{:?}",
                ground.normal
            );
            assert!(
                (position.y - STANDING).abs() <= CAST_PRECISION,
                "frame {frame}: {position}"
            );
        },
    );
    println!("flat: end {end}");
    // The lateral motion is never shortened on flat ground: 60 frames of 5 cm.
    assert!((end.x - (start.x + 3.0)).abs() < 1e-4, "{end}");
}

#[test]
fn a_thirty_degree_slope_is_ground_and_the_character_does_not_slide() {
    let mut world = world(Vec3::ZERO);
    let angle = 30f32.to_radians();
    let (slope, normal) = add_slope(&mut world, angle);
    let mut controller = controller(CharacterSettings::default());
    // Dropped 5 cm above the slope, then pushed straight down for a second.
    let start = normal * (RADIUS + OFFSET + 0.05) + Vec3::Y * HALF_HEIGHT;
    let desired = Vec3::new(0.0, -0.1, 0.0);
    let mut rest = None;
    walk(
        &world,
        &mut controller,
        start,
        desired,
        60,
        |frame, position, moved| {
            let ground = moved.ground.expect("on the slope");
            assert_eq!(ground.body, slope);
            assert!(
                (ground.normal - normal).length() < 1e-5,
                "{:?}",
                ground.normal
            );
            let rest = *rest.get_or_insert(position);
            // Pushed straight down, the character moves only along y, by no more than the casts'
            // precision (measured: 1e-6 m on the first frame, then nothing): it does not slide.
            assert_eq!((position.x, position.z), (rest.x, rest.z), "frame {frame}");
            assert!(
                (position.y - rest.y).abs() <= CAST_PRECISION,
                "frame {frame}: {position}"
            );
        },
    );
}

/// Walks from the floor toward a slope of `slope` degrees at 2 m/s, pushed down at 3 m/s, with
/// a 45° limit; returns the heights per frame and the final position.
fn walk_up_slope(slope: f32) -> (Vec<f32>, Vec3) {
    let mut world = world(Vec3::ZERO);
    add_floor(&mut world);
    add_slope(&mut world, slope.to_radians());
    let mut controller = controller(CharacterSettings::default());
    let mut heights = Vec::new();
    let start = Vec3::new(-1.0, STANDING, 0.0);
    let desired = Vec3::new(2.0, -3.0, 0.0) * DT;
    let end = walk(
        &world,
        &mut controller,
        start,
        desired,
        90,
        |_, position, _| heights.push(position.y),
    );
    (heights, end)
}

#[test]
fn a_fifty_degree_slope_is_refused_with_a_forty_five_degree_limit() {
    let (heights, end) = walk_up_slope(50.0);
    let highest = heights.iter().copied().fold(f32::MIN, f32::max);
    println!("slope50: highest {highest}, end {end}");
    assert!(highest <= STANDING + CAST_PRECISION, "climbed to {highest}");
    // The capsule's bottom sphere rests against the slope: its centre 0.31 m from the plane
    // y = x tan 50°, at the sphere centre's height 0.31.
    let angle = 50f32.to_radians();
    let sphere_centre_height = RADIUS + OFFSET;
    let touching_x = sphere_centre_height / angle.tan() - (RADIUS + OFFSET) / angle.sin();
    assert!(
        (end.x - touching_x).abs() < 1e-3,
        "{} vs {touching_x}",
        end.x
    );

    // A 40° slope is climbed at the lateral speed: 2 m/s × tan 40° upward.
    let (heights, _) = walk_up_slope(40.0);
    let rises: Vec<f32> = heights.windows(2).map(|pair| pair[1] - pair[0]).collect();
    let climbing = 2.0 * DT * 40f32.to_radians().tan();
    println!("slope40: last rises {:?}", &rises[rises.len() - 3..]);
    assert!((rises[rises.len() - 1] - climbing).abs() < 1e-4);
}

/// Walks at 2 m/s, pushed down at 3 m/s, for two seconds toward a step of `height` whose face is
/// the plane x = 0, with steps up to 0.35 m; the final position and ground body.
fn walk_to_step(height: f32) -> (Vec3, Option<BodyHandle>, BodyHandle) {
    let mut world = world(Vec3::ZERO);
    add_floor(&mut world);
    let step = add_block(
        &mut world,
        Vec3::new(0.0, -1.0, -10.0),
        Vec3::new(5.0, height, 10.0),
    );
    let mut controller = controller(CharacterSettings {
        max_step_height: 0.35,
        ..CharacterSettings::default()
    });
    let start = Vec3::new(-1.0, STANDING, 0.0);
    let desired = Vec3::new(2.0, -3.0, 0.0) * DT;
    let mut last_ground = None;
    let end = walk(
        &world,
        &mut controller,
        start,
        desired,
        120,
        |_, _, moved| {
            last_ground = moved.ground.map(|ground| ground.body);
        },
    );
    (end, last_ground, step)
}

#[test]
fn a_step_lower_than_the_limit_is_climbed_and_a_higher_one_refused() {
    let (end, ground, step) = walk_to_step(0.3);
    println!("step 0.3: {end}");
    assert_eq!(ground, Some(step));
    assert!(end.x > 2.0, "{end}");
    assert!((end.y - (0.3 + STANDING)).abs() <= CAST_PRECISION, "{end}");

    let (end, ground, step) = walk_to_step(0.5);
    println!("step 0.5: {end}");
    assert_ne!(ground, Some(step));
    assert!((end.y - STANDING).abs() <= CAST_PRECISION, "{end}");
    // Against the face, the offset away.
    assert!((end.x - -(RADIUS + OFFSET)).abs() < 1e-3, "{end}");
}

#[test]
fn walking_into_a_wall_at_thirty_degrees_slides_along_it_at_v_sin_30() {
    let mut world = world(Vec3::ZERO);
    add_floor(&mut world);
    // A wall whose face normal is 30° from −x (the walking direction reversed), face through x = 0.
    let rotation = Quat::from_rotation_y(30f32.to_radians());
    let normal = rotation * -Vec3::X;
    world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(0.5, 5.0, 10.0)).unwrap())
                .position(rotation * Vec3::new(0.5, 0.0, 0.0))
                .rotation(rotation),
        )
        .unwrap();
    let mut controller = controller(CharacterSettings::default());
    let speed = 2.0;
    let desired = Vec3::new(speed, 0.0, 0.0) * DT;
    let along = (desired - normal * desired.dot(normal)).normalize();
    let mut previous: Option<Vec3> = None;
    let mut sliding = 0;
    walk(
        &world,
        &mut controller,
        Vec3::new(-1.0, STANDING, 0.0),
        desired,
        60,
        |frame, position, moved| {
            let touching = moved.hits.iter().any(|hit| hit.normal.dot(normal) > 0.99);
            if let (Some(before), true) = (previous, touching) {
                let step = position - before;
                if (step.dot(normal)).abs() < 1e-6 {
                    sliding += 1;
                    let speed_along = step.dot(along) / DT;
                    println!("wall frame {frame}: {speed_along}");
                    assert!((speed_along - speed * 0.5).abs() < 1e-4, "{speed_along}");
                }
            }
            previous = Some(position);
        },
    );
    // It reaches the wall after about 20 of the 60 frames (0.69 m at 3.3 cm a frame).
    assert!(sliding >= 35, "{sliding} frames sliding");
}

#[test]
fn walking_down_a_step_snaps_to_the_lower_floor() {
    for snap in [0.3, 0.0] {
        let mut world = world(Vec3::ZERO);
        add_block(
            &mut world,
            Vec3::new(-10.0, -1.0, -10.0),
            Vec3::new(0.0, 0.0, 10.0),
        );
        let lower = add_block(
            &mut world,
            Vec3::new(0.0, -1.0, -10.0),
            Vec3::new(10.0, -0.2, 10.0),
        );
        let mut controller = controller(CharacterSettings {
            snap_distance: snap,
            ..CharacterSettings::default()
        });
        let desired = Vec3::new(2.0, 0.0, 0.0) * DT;
        let mut airborne = 0;
        let end = walk(
            &world,
            &mut controller,
            Vec3::new(-1.0, STANDING, 0.0),
            desired,
            60,
            |_, _, moved| {
                if !moved.is_grounded() {
                    airborne += 1;
                }
            },
        );
        println!("snap {snap}: end {end}, airborne {airborne}");
        if snap > 0.0 {
            assert_eq!(airborne, 0);
            assert!((end.y - (STANDING - 0.2)).abs() <= CAST_PRECISION, "{end}");
            assert_eq!(controller.last_move().ground.map(|g| g.body), Some(lower));
        } else {
            assert!(airborne > 0);
            assert_eq!(end.y, STANDING);
        }
    }
}

#[test]
fn a_sixty_degree_slope_is_slid_down() {
    let mut world = world(Vec3::ZERO);
    let angle = 60f32.to_radians();
    let (_, normal) = add_slope(&mut world, angle);
    let mut controller = controller(CharacterSettings::default());
    let start = Vec3::new(2.0, 0.0, 0.0)
        + normal * (RADIUS + OFFSET + 0.05)
        + Vec3::Y * HALF_HEIGHT
        + Vec3::new(0.0, 2.0 * 60f32.to_radians().tan(), 0.0);
    let fall = 0.05;
    let desired = Vec3::new(0.0, -fall, 0.0);
    let mut previous: Option<Vec3> = None;
    let mut sliding = 0;
    walk(
        &world,
        &mut controller,
        start,
        desired,
        30,
        |frame, position, moved| {
            assert!(!moved.is_grounded());
            if let Some(before) = previous {
                let step = position - before;
                if step.dot(normal).abs() < 1e-6 {
                    sliding += 1;
                    // The fall projected on the slope: down by s sin² 60°, back by s sin 60° cos 60°.
                    let expected = Vec3::new(
                        -fall * angle.sin() * angle.cos(),
                        -fall * angle.sin().powi(2),
                        0.0,
                    );
                    println!("slide frame {frame}: {step} vs {expected}");
                    assert!((step - expected).length() < 1e-5, "{step} vs {expected}");
                }
            }
            previous = Some(position);
        },
    );
    assert!(sliding > 20);
}
