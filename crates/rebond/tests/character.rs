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

/// The capsule moved from `start` by `desired` each frame for `frames` frames, in a world that
/// does not step.
struct Walk {
    start: Vec3,
    desired: Vec3,
    frames: usize,
}

impl Walk {
    /// Makes the walk with `controller`, calling `check` after each move; the final position.
    fn run(
        self,
        world: &World,
        controller: &mut CharacterController,
        mut check: impl FnMut(usize, Vec3, &CharacterMove),
    ) -> Vec3 {
        let Walk {
            start,
            desired,
            frames,
        } = self;
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
}

/// Checks that the move ends on `body` with a ground normal within `tolerance` of `normal`.
fn assert_standing_on(moved: &CharacterMove, body: BodyHandle, normal: Vec3, tolerance: f32) {
    let ground = moved.ground.expect("grounded");
    assert_eq!(ground.body, body);
    let error = (ground.normal - normal).length();
    assert!(error <= tolerance, "{} vs {normal}", ground.normal);
}

#[test]
fn flat_ground_is_reported_with_its_normal_and_body() {
    let mut world = world(Vec3::ZERO);
    let floor = add_floor(&mut world);
    let mut controller = controller(CharacterSettings::default());
    // Walking at 3 m/s while pushed down at 6 m/s: the floor holds the character up.
    let desired = Vec3::new(3.0, -6.0, 0.0) * DT;
    let start = Vec3::new(-5.0, STANDING, 0.0);
    let end = Walk {
        start,
        desired,
        frames: 60,
    }
    .run(&world, &mut controller, |frame, position, moved| {
        assert_standing_on(moved, floor, Vec3::Y, 1e-6);
        assert!(
            (position.y - STANDING).abs() <= CAST_PRECISION,
            "frame {frame}: {position}"
        );
    });
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
    Walk {
        start,
        desired,
        frames: 60,
    }
    .run(&world, &mut controller, |frame, position, moved| {
        // The normal read from the slope box's rotated face: f32 rounding of the rotation.
        assert_standing_on(moved, slope, normal, 1e-5);
        let rest = *rest.get_or_insert(position);
        // Pushed straight down, the character moves only along y, by no more than the casts'
        // precision (measured: 1e-6 m on the first frame, then nothing): it does not slide.
        assert_eq!((position.x, position.z), (rest.x, rest.z), "frame {frame}");
        assert!(
            (position.y - rest.y).abs() <= CAST_PRECISION,
            "frame {frame}: {position}"
        );
    });
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
    let end = Walk {
        start,
        desired,
        frames: 90,
    }
    .run(&world, &mut controller, |_, position, _| {
        heights.push(position.y)
    });
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
    let end = Walk {
        start,
        desired,
        frames: 120,
    }
    .run(&world, &mut controller, |_, _, moved| {
        last_ground = moved.ground.map(|ground| ground.body);
    });
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
    Walk {
        start: Vec3::new(-1.0, STANDING, 0.0),
        desired,
        frames: 60,
    }
    .run(&world, &mut controller, |frame, position, moved| {
        let touching = moved
            .hits
            .iter()
            .any(|hit| hit.hit.normal.dot(normal) > 0.99);
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
    });
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
        let end = Walk {
            start: Vec3::new(-1.0, STANDING, 0.0),
            desired,
            frames: 60,
        }
        .run(&world, &mut controller, |_, _, moved| {
            if !moved.is_grounded() {
                airborne += 1;
            }
        });
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
    Walk {
        start,
        desired,
        frames: 30,
    }
    .run(&world, &mut controller, |frame, position, moved| {
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
    });
    assert!(sliding > 20);
}

/// A kinematic capsule standing on the floor at `x`.
fn add_character(world: &mut World, x: f32) -> BodyHandle {
    world
        .add_body(BodyDesc::kinematic(capsule()).position(Vec3::new(x, STANDING, 0.0)))
        .unwrap()
}

/// Moves `character` by `desired` then steps the world, `frames` times, calling `check` after
/// each step.
fn run(
    world: &mut World,
    controller: &mut CharacterController,
    character: BodyHandle,
    desired: Vec3,
    frames: usize,
    mut check: impl FnMut(&World, &CharacterMove),
) {
    for _ in 0..frames {
        let moved = controller
            .move_body(world, character, desired, DT, &QueryFilter::default())
            .unwrap()
            .clone();
        world.step(DT).unwrap();
        check(world, &moved);
    }
}

/// Rides `platform` with the kinematic `character` for two seconds, pushed down at 3 m/s, after
/// `set_off` sets the platform moving; the largest change of the character's position relative
/// to the platform.
fn ride(
    world: &mut World,
    character: BodyHandle,
    platform: BodyHandle,
    set_off: impl FnOnce(&mut World),
) -> f32 {
    let mut controller = controller(CharacterSettings::default());
    let fall = Vec3::new(0.0, -0.05, 0.0);
    // A frame to find the ground, then the platform moves.
    run(world, &mut controller, character, fall, 1, |_, moved| {
        assert!(moved.is_grounded())
    });
    set_off(world);
    let relative = |world: &World| {
        world.body(character).unwrap().position() - world.body(platform).unwrap().position()
    };
    let start = relative(world);
    let mut worst = 0.0f32;
    run(
        world,
        &mut controller,
        character,
        fall,
        120,
        |world, moved| {
            assert_eq!(moved.ground.map(|ground| ground.body), Some(platform));
            worst = worst.max((relative(world) - start).length());
        },
    );
    worst
}

#[test]
fn a_kinematic_platform_carries_the_character_without_slipping() {
    let mut world = world(Vec3::new(0.0, -9.81, 0.0));
    let platform = world
        .add_body(
            BodyDesc::kinematic(Shape::cuboid(Vec3::new(3.0, 0.5, 3.0)).unwrap())
                .position(Vec3::new(0.0, -0.5, 0.0)),
        )
        .unwrap();
    let character = add_character(&mut world, 0.5);
    // The platform rises and moves sideways.
    let velocity = Vec3::new(1.0, 0.5, -0.5);
    let worst = ride(&mut world, character, platform, |world| {
        let platform = world.body_mut(platform).unwrap();
        platform.set_linear_velocity(velocity).unwrap();
    });
    println!("kinematic platform: worst slip {worst}");
    // The platform travels 2.4 m; the character keeps its place on it to the casts' precision
    // and the f32 rounding of positions a few metres out (measured: 1.5e-6 m).
    assert!(worst < 1e-4, "slipped {worst}");
}

/// A world with gravity and a frictionless floor y = 0, and on it a frictionless dynamic box of
/// `half_extents` centred at `x`, moving at `velocity`.
fn box_on_ice(half_extents: Vec3, x: f32, velocity: Vec3) -> (World, BodyHandle) {
    let mut world = world(Vec3::new(0.0, -9.81, 0.0));
    let floor = add_floor(&mut world);
    world.body_mut(floor).unwrap().set_friction(0.0).unwrap();
    let body = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(half_extents).unwrap())
                .position(Vec3::new(x, half_extents.y, 0.0))
                .friction(0.0)
                .linear_velocity(velocity),
        )
        .unwrap();
    (world, body)
}

#[test]
fn a_dynamic_platform_carries_the_character_without_slipping() {
    let (mut world, platform) = box_on_ice(Vec3::new(2.0, 0.1, 2.0), 0.0, Vec3::new(1.0, 0.0, 0.0));
    let character = world
        .add_body(BodyDesc::kinematic(capsule()).position(Vec3::new(0.0, 0.2 + STANDING, 0.0)))
        .unwrap();
    let worst = ride(&mut world, character, platform, |_| {});
    let platform_x = world.body(platform).unwrap().position().x;
    println!("dynamic platform: worst slip {worst}, platform at {platform_x}");
    assert!(platform_x > 1.9, "the platform glided 2 m: {platform_x}");
    assert!(worst < 1e-3, "slipped {worst}");
}

#[test]
fn a_pushed_box_moves_no_faster_than_the_push_force_allows() {
    let (mut world, crate_) = box_on_ice(Vec3::splat(0.5), 0.0, Vec3::ZERO);
    let mass = world.body(crate_).unwrap().mass();
    let character = add_character(&mut world, -1.0);
    // 2,000 N on the 1,000 kg box: 2 m/s² at most, so it takes a second to reach the character's
    // 2 m/s.
    let push_force = 2000.0;
    let mut controller = controller(CharacterSettings {
        push_force,
        ..CharacterSettings::default()
    });
    let speed = 2.0;
    let desired = Vec3::new(speed, -0.05, 0.0) * DT;
    let (mut pushing, mut given) = (0usize, Vec3::ZERO);
    run(
        &mut world,
        &mut controller,
        character,
        desired,
        90,
        |world, moved| {
            for hit in &moved.hits {
                if hit.hit.body == crate_ && hit.impulse != Vec3::ZERO {
                    pushing += 1;
                    given += hit.impulse;
                    assert!(hit.impulse.length() <= push_force * DT * (1.0 + 1e-6));
                }
            }
            let velocity = world.body(crate_).unwrap().linear_velocity().x;
            // Never faster than the cap allows since the first push, nor than the character.
            let bound = (push_force * DT * pushing as f32 / mass).min(speed);
            assert!(velocity <= bound + 1e-3, "{velocity} > {bound}");
        },
    );
    let velocity = world.body(crate_).unwrap().linear_velocity();
    println!("push: mass {mass}, {pushing} pushes, given {given}, box at {velocity}");
    // After a second and a half it has caught up with the character's speed.
    assert!((velocity.x - speed).abs() < 1e-2, "{velocity}");
    // On a frictionless floor the box's momentum is the impulses given: the contacts of the
    // kinematic character, kept 1 cm away, never pushed it.
    assert!(
        (velocity.x * mass - given.x).abs() < 1e-4 * given.x,
        "{velocity} vs {given}"
    );
}

#[test]
fn a_character_starting_inside_the_floor_is_pushed_out() {
    let mut world = world(Vec3::ZERO);
    add_floor(&mut world);
    let mut controller = controller(CharacterSettings::default());
    let start = Vec3::new(0.0, STANDING - 0.2, 0.0);
    let end = Walk {
        start,
        desired: Vec3::ZERO,
        frames: 1,
    }
    .run(&world, &mut controller, |_, _, moved| {
        assert!(moved.is_grounded());
    });
    println!("recovered to {end}");
    assert!((end.y - STANDING).abs() <= CAST_PRECISION, "{end}");
}

#[test]
fn bad_settings_and_inputs_are_refused_naming_the_field() {
    let refused = |settings: CharacterSettings| CharacterController::new(settings).unwrap_err();
    let base = CharacterSettings::default();
    let cases = [
        (
            CharacterSettings {
                up: Vec3::ZERO,
                ..base
            },
            "up",
        ),
        (
            CharacterSettings {
                up: Vec3::NAN,
                ..base
            },
            "up",
        ),
        (
            CharacterSettings {
                max_slope_angle: -0.1,
                ..base
            },
            "max_slope_angle",
        ),
        (
            CharacterSettings {
                max_slope_angle: 1.5,
                ..base
            },
            "max_slope_angle",
        ),
        (
            CharacterSettings {
                max_step_height: -1.0,
                ..base
            },
            "max_step_height",
        ),
        (
            CharacterSettings {
                min_step_width: f32::NAN,
                ..base
            },
            "min_step_width",
        ),
        (
            CharacterSettings {
                snap_distance: f32::INFINITY,
                ..base
            },
            "snap_distance",
        ),
        (
            CharacterSettings {
                offset: 0.0,
                ..base
            },
            "offset",
        ),
        (
            CharacterSettings {
                push_force: -5.0,
                ..base
            },
            "push_force",
        ),
        (
            CharacterSettings {
                max_iterations: 0,
                ..base
            },
            "max_iterations",
        ),
    ];
    for (settings, field) in cases {
        assert_eq!(refused(settings).field, field);
    }
    assert!(CharacterController::new(CharacterSettings {
        push_force: f32::INFINITY,
        ..base
    })
    .is_ok());

    let mut world = world(Vec3::ZERO);
    add_floor(&mut world);
    let mut controller = controller(base);
    let pose = Pose::from_position(Vec3::new(0.0, STANDING, 0.0));
    let filter = QueryFilter::default();
    let mut attempt = |shape: &Shape, pose: &Pose, desired: Vec3, dt: f32| {
        controller
            .move_shape(&world, shape, pose, desired, dt, &filter)
            .unwrap_err()
    };
    let plane = Shape::halfspace(Vec3::Y).unwrap();
    assert_eq!(
        attempt(&plane, &pose, Vec3::ZERO, DT).kind,
        ErrorKind::NotConvex
    );
    assert_eq!(
        attempt(&capsule(), &pose, Vec3::NAN, DT).field,
        "desired_translation"
    );
    assert_eq!(attempt(&capsule(), &pose, Vec3::X, 0.0).field, "dt");
    let bad_pose = Pose::new(Vec3::new(f32::NAN, 0.0, 0.0), Quat::IDENTITY);
    assert_eq!(
        attempt(&capsule(), &bad_pose, Vec3::X, DT).field,
        "pose.position"
    );
    // A refused call leaves the controller as it was: never moved.
    assert_eq!(controller.last_move(), &CharacterMove::default());

    let dynamic = world
        .add_body(BodyDesc::dynamic(capsule()).position(Vec3::new(3.0, 2.0, 0.0)))
        .unwrap();
    let error = controller
        .move_body(&mut world, dynamic, Vec3::X, DT, &filter)
        .unwrap_err();
    assert_eq!(
        (error.field.as_str(), error.kind),
        ("body", ErrorKind::NotKinematic)
    );
}

#[test]
fn a_box_character_walks_and_climbs_a_step_too() {
    let mut world = world(Vec3::ZERO);
    add_floor(&mut world);
    let step = add_block(
        &mut world,
        Vec3::new(0.0, -1.0, -10.0),
        Vec3::new(5.0, 0.3, 10.0),
    );
    let mut controller = controller(CharacterSettings {
        max_step_height: 0.35,
        ..CharacterSettings::default()
    });
    // A 0.6 m × 1.6 m × 0.6 m box standing on the floor: its flat bottom meets the step's edge
    // face on, without the capsule's rolling over it.
    let shape = Shape::cuboid(Vec3::new(0.3, 0.8, 0.3)).unwrap();
    let desired = Vec3::new(2.0, -3.0, 0.0) * DT;
    let mut position = Vec3::new(-1.0, 0.8 + OFFSET, 0.0);
    for _ in 0..120 {
        let pose = Pose::from_position(position);
        let filter = QueryFilter::default();
        let moved = controller
            .move_shape(&world, &shape, &pose, desired, DT, &filter)
            .unwrap();
        assert!(moved.is_grounded());
        position += moved.translation;
    }
    println!("box character: {position}");
    assert_eq!(controller.last_move().ground.map(|g| g.body), Some(step));
    assert!(
        (position.y - (0.3 + 0.8 + OFFSET)).abs() <= CAST_PRECISION,
        "{position}"
    );
    assert!(position.x > 2.0, "{position}");
}

/// A scene file names its character with the top-level `character`: the body, its speeds and
/// the controller's settings; bad values are refused at their JSON path.
#[test]
fn a_scene_names_its_character_and_bad_values_are_refused_at_their_path() {
    use rebond::scene::{Scene, DEFAULT_CHARACTER_JUMP_SPEED, DEFAULT_CHARACTER_WALK_SPEED};

    let scene_with = |character: &str| {
        format!(
            r#"{{ "character": {character}, "bodies": [
                {{ "name": "player", "type": "kinematic",
                   "shape": {{ "type": "capsule", "radius": 0.3, "half_height": 0.5 }} }},
                {{ "name": "crate", "shape": {{ "type": "box", "half_extents": [1, 1, 1] }} }} ] }}"#
        )
    };
    let scene = Scene::from_json(
        scene_with(
            r#"{ "body": "player", "walk_speed": 3, "jump_speed": 0,
                 "max_slope_angle": 0.5, "max_step_height": 0.2 }"#,
        )
        .as_bytes(),
    )
    .unwrap();
    let character = scene.character().unwrap();
    assert_eq!(character.body, scene.body_handle("player").unwrap());
    assert_eq!((character.walk_speed, character.jump_speed), (3.0, 0.0));
    let expected = CharacterSettings {
        max_slope_angle: 0.5,
        max_step_height: 0.2,
        ..CharacterSettings::default()
    };
    assert_eq!(character.settings, expected);

    let defaults = Scene::from_json(scene_with(r#"{ "body": "player" }"#).as_bytes()).unwrap();
    let character = defaults.character().unwrap();
    assert_eq!(character.walk_speed, DEFAULT_CHARACTER_WALK_SPEED);
    assert_eq!(character.jump_speed, DEFAULT_CHARACTER_JUMP_SPEED);
    assert_eq!(character.settings, CharacterSettings::default());
    let none = Scene::from_json(br#"{ "bodies": [] }"#).unwrap();
    assert!(none.character().is_none());

    for (character, place) in [
        (r#"{ "body": "nobody" }"#, "character.body"),
        (r#"{ "body": "crate" }"#, "character.body"),
        (r#"{ }"#, "character.body"),
        (
            r#"{ "body": "player", "walk_speed": 0 }"#,
            "character.walk_speed",
        ),
        (
            r#"{ "body": "player", "walk_speed": 101 }"#,
            "character.walk_speed",
        ),
        (
            r#"{ "body": "player", "walk_speed": 1e39 }"#,
            "character.walk_speed",
        ),
        (
            r#"{ "body": "player", "jump_speed": -1 }"#,
            "character.jump_speed",
        ),
        (
            r#"{ "body": "player", "max_slope_angle": 1.5 }"#,
            "character.max_slope_angle",
        ),
        (
            r#"{ "body": "player", "max_step_height": -0.1 }"#,
            "character.max_step_height",
        ),
        (
            r#"{ "body": "player", "run_speed": 8 }"#,
            "character.run_speed",
        ),
        (r#"[ "player" ]"#, "character"),
    ] {
        let error = Scene::from_json(scene_with(character).as_bytes()).unwrap_err();
        assert_eq!(error.place, place, "{character}: {}", error.message);
    }
}
