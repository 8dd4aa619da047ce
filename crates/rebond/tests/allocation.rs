//! No allocation in a steady step (a project rule): a counting global allocator proves that once
//! a scene has run long enough to size every buffer, stepping it again allocates nothing, with
//! events and sensors, in a scene of cylinders, hulls and capsules whose pairs go through GJK
//! and EPA, and on triangle meshes and heightfields.

mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use common::{add_ground, unit_box, world, DT, G};
use rebond::internals::collision::epa;
use rebond::internals::collision::PosedCore;
use rebond::{
    BodyDesc, BodyHandle, CompoundChild, CouplingDesc, JointDesc, Motor, Pose, Quat, Shape, Vec3,
    World,
};

/// Counts the allocations of the calling thread, so a test can prove a step allocates nothing
/// while other tests run on other threads.
struct CountingAllocator;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: forwards every call to the system allocator unchanged; the counter is a const-initialised
// thread-local `Cell`, which never allocates.
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|count| count.set(count.get() + 1));
        // SAFETY: the caller's contract is passed on unchanged.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, pointer: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract is passed on unchanged.
        unsafe { System.dealloc(pointer, layout) }
    }

    unsafe fn realloc(&self, pointer: *mut u8, layout: Layout, size: usize) -> *mut u8 {
        ALLOCATIONS.with(|count| count.set(count.get() + 1));
        // SAFETY: the caller's contract is passed on unchanged.
        unsafe { System.realloc(pointer, layout, size) }
    }
}

#[global_allocator]
static ALLOCATOR: CountingAllocator = CountingAllocator;

fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

/// Runs `work` and checks that it allocated nothing on this thread; returns its result.
fn allocations_of<T>(work: impl FnOnce() -> T) -> T {
    let probe = allocations();
    drop(std::hint::black_box(vec![0u8; 16]));
    assert_eq!(
        allocations(),
        probe + 1,
        "the counter sees this thread's allocations"
    );
    let before = allocations();
    let result = work();
    assert_eq!(allocations(), before, "a steady step allocates nothing");
    result
}

/// Steps `world` 240 times, the kinematic `movers` going along +X at `speed` m/s for the first
/// 120 steps and back for the others, so that the scene repeats; `after_step` sees each step.
fn sweep(world: &mut World, movers: &[BodyHandle], speed: f32, mut after_step: impl FnMut(&World)) {
    for step in 0..240 {
        let velocity = if step < 120 { speed } else { -speed };
        for &mover in movers {
            world
                .body_mut(mover)
                .unwrap()
                .set_linear_velocity(Vec3::new(velocity, 0.0, 0.0))
                .unwrap();
        }
        world.step(DT).unwrap();
        after_step(world);
    }
}

#[test]
fn a_steady_step_with_events_and_sensors_allocates_nothing() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let ground = add_ground(&mut world, 0.5);
    world
        .body_mut(ground)
        .unwrap()
        .set_contact_force_threshold(0.0)
        .unwrap();
    for index in 0..5 {
        world
            .add_body(unit_box(Vec3::new(index as f32 * 1.5, 0.5, 0.0)).can_sleep(false))
            .unwrap();
    }
    // Last in the row, a box resting on the ground with a sensor child (a foot) in it.
    let foot = CompoundChild::new(
        Shape::sphere(0.2).unwrap(),
        Pose::from_position(Vec3::new(0.0, -0.45, 0.0)),
    )
    .sensor(true);
    let torso = CompoundChild::new(Shape::cuboid(Vec3::splat(0.5)).unwrap(), Pose::IDENTITY);
    world
        .add_body(
            BodyDesc::dynamic(Shape::compound(vec![torso, foot]).unwrap())
                .position(Vec3::new(7.5, 0.5, 0.0))
                .can_sleep(false),
        )
        .unwrap();
    let gate = world
        .add_body(
            BodyDesc::kinematic(Shape::cuboid(Vec3::new(0.25, 1.0, 1.0)).unwrap())
                .position(Vec3::new(-1.0, 1.0, 0.0))
                .sensor(true),
        )
        .unwrap();
    // The gate sweeps back and forth over the row of boxes, 2 s each way; counts the sensor and
    // force events it saw.
    let mut events = 0;
    let mut count_events = |world: &World| {
        events += world.sensor_events().len() + world.contact_force_events().len();
    };
    sweep(&mut world, &[gate], 4.0, |_| {});
    sweep(&mut world, &[gate], 4.0, |_| {});
    allocations_of(|| {
        sweep(&mut world, &[gate], 4.0, &mut count_events);
        sweep(&mut world, &[gate], 4.0, &mut count_events);
    });
    assert!(
        events > 2 * 240,
        "every step reports the boxes' weights, and the gate crosses"
    );
}

/// An irregular pebble about 1 m across, the hull of the `mixed` benchmark scene: a hexagonal
/// bipyramid with a flattened, twisted top ring.
fn pebble() -> Shape {
    let mut points = Vec::new();
    for i in 0..6 {
        let angle = i as f32 * std::f32::consts::TAU / 6.0;
        points.push(Vec3::new(0.5 * angle.cos(), -0.15, 0.45 * angle.sin()));
        let angle = angle + 0.4;
        points.push(Vec3::new(0.35 * angle.cos(), 0.25, 0.3 * angle.sin()));
    }
    points.push(Vec3::new(0.05, -0.4, 0.0));
    points.push(Vec3::new(-0.05, 0.4, 0.05));
    Shape::convex_hull(&points).unwrap()
}

/// Cylinders, capsules, hulls and spheres resting on the ground and on each other, kept awake,
/// and, 5 m above them, a kinematic cylinder, capsule and hull sweeping back and forth through a
/// row of fixed cylinders and hulls, cores deep in each other: the narrow phase runs GJK and EPA
/// on those pairs at every step, and on the resting pairs whenever they move by more than the
/// recycling tolerance.
#[test]
fn a_steady_step_of_cylinders_hulls_and_capsules_allocates_nothing() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, 0.5);
    let cylinder = Shape::cylinder(0.4, 0.35).unwrap();
    let capsule = Shape::capsule(0.3, 0.35).unwrap();
    let sphere = Shape::sphere(0.4).unwrap();
    let lying = Quat::from_rotation_z(std::f32::consts::FRAC_PI_2);
    for row in 0..3 {
        let z = row as f32 * 1.2;
        let resting = [
            (cylinder.clone(), Vec3::new(0.0, 0.35, z), Quat::IDENTITY),
            (cylinder.clone(), Vec3::new(0.8, 0.4, z), lying),
            (capsule.clone(), Vec3::new(1.9, 0.3, z), lying),
            (pebble(), Vec3::new(3.0, 0.4, z), Quat::IDENTITY),
            (sphere.clone(), Vec3::new(3.9, 0.4, z), Quat::IDENTITY),
            (cylinder.clone(), Vec3::new(0.0, 1.1, z), Quat::IDENTITY),
            (pebble(), Vec3::new(3.0, 1.2, z), Quat::from_rotation_y(0.7)),
        ];
        for (shape, position, rotation) in resting {
            world
                .add_body(
                    BodyDesc::dynamic(shape)
                        .position(position)
                        .rotation(rotation)
                        .can_sleep(false),
                )
                .unwrap();
        }
    }
    for index in 0..4 {
        let x = index as f32 * 1.5;
        let shape = if index % 2 == 0 {
            cylinder.clone()
        } else {
            pebble()
        };
        world
            .add_body(BodyDesc::static_body(shape).position(Vec3::new(x, 5.0, 0.0)))
            .unwrap();
    }
    let sweepers = [
        (cylinder.clone(), Quat::from_rotation_x(0.3)),
        (capsule.clone(), lying),
        (pebble(), Quat::from_rotation_y(0.5)),
    ]
    .map(|(shape, rotation)| {
        world
            .add_body(
                BodyDesc::kinematic(shape)
                    .position(Vec3::new(-1.0, 5.2, 0.0))
                    .rotation(rotation),
            )
            .unwrap()
    });
    // The sweepers cross the row, 6 m in 2 s, and come back.
    sweep(&mut world, &sweepers, 3.0, |_| {});
    sweep(&mut world, &sweepers, 3.0, |_| {});
    // EPA does run in this scene: a sweeper inside a fixed cylinder, as the step meets them, needs
    // it, and on a polytope of its own it allocates.
    let (inside, fixed) = (
        Pose::from_position(Vec3::new(0.1, 5.2, 0.0)),
        Pose::from_position(Vec3::new(0.0, 5.0, 0.0)),
    );
    let core = |shape, pose| PosedCore { shape, pose };
    let before = allocations();
    let found = epa::contact(&core(&cylinder, &inside), &core(&cylinder, &fixed), 0.0);
    assert!(
        found.is_some_and(|contact| contact.separation < -0.1),
        "{found:?}"
    );
    assert!(allocations() > before, "EPA ran");
    allocations_of(|| {
        sweep(&mut world, &sweepers, 3.0, |_| {});
        sweep(&mut world, &sweepers, 3.0, |_| {});
    });
}

/// Bodies resting and sliding on a mesh floor and a heightfield, and a kinematic box sweeping
/// over them: the triangles found, their manifolds and the merged points reuse the narrow phase's
/// buffers.
#[test]
fn a_steady_step_on_meshes_and_heightfields_allocates_nothing() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let (cells, size) = (12u32, 12.0);
    let mut vertices = Vec::new();
    for i in 0..=cells {
        for j in 0..=cells {
            let (x, z) = (j as f32 / cells as f32 - 0.5, i as f32 / cells as f32 - 0.5);
            vertices.push(Vec3::new(x * size, 0.0, z * size));
        }
    }
    let at = |i: u32, j: u32| i * (cells + 1) + j;
    let indices: Vec<[u32; 3]> = (0..cells * cells)
        .flat_map(|cell| {
            let (i, j) = (cell / cells, cell % cells);
            [
                [at(i, j), at(i + 1, j), at(i + 1, j + 1)],
                [at(i, j), at(i + 1, j + 1), at(i, j + 1)],
            ]
        })
        .collect();
    let floor = Shape::trimesh(vertices, &indices).unwrap();
    world.add_body(BodyDesc::static_body(floor)).unwrap();
    let heights: Vec<Vec<f32>> = (0..9)
        .map(|i| (0..9).map(|j| 0.1 * ((i + j) % 3) as f32).collect())
        .collect();
    let terrain = Shape::heightfield(&heights, Vec3::new(8.0, 1.0, 8.0)).unwrap();
    world
        .add_body(BodyDesc::static_body(terrain).position(Vec3::new(0.0, 0.0, 12.0)))
        .unwrap();
    for (index, z) in [0.0f32, 12.0].into_iter().enumerate() {
        for k in 0..4 {
            let shape = if (k + index) % 2 == 0 {
                Shape::cuboid(Vec3::splat(0.4)).unwrap()
            } else {
                pebble()
            };
            world
                .add_body(
                    BodyDesc::dynamic(shape)
                        .position(Vec3::new(k as f32 * 1.3 - 2.0, 0.8, z))
                        .can_sleep(false),
                )
                .unwrap();
        }
    }
    let sweeper = world
        .add_body(
            BodyDesc::kinematic(Shape::cuboid(Vec3::splat(0.3)).unwrap())
                .position(Vec3::new(-3.0, 0.35, 2.0)),
        )
        .unwrap();
    sweep(&mut world, &[sweeper], 3.0, |_| {});
    sweep(&mut world, &[sweeper], 3.0, |_| {});
    allocations_of(|| {
        sweep(&mut world, &[sweeper], 3.0, |_| {});
        sweep(&mut world, &[sweeper], 3.0, |_| {});
    });
}

/// A chain of boxes on ball joints hanging from the world, a swinging rod on a hinge with a
/// motor and limits, and an arm on a torque motor that a controller reads and sets every step:
/// the joints' grouping, direct solve and limit rows reuse their buffers, and reading a joint's
/// coordinate or replacing its motor allocates nothing.
#[test]
fn a_steady_step_with_joints_allocates_nothing() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let mut previous = None;
    for index in 0..8 {
        let top = Vec3::new(0.3 * index as f32, 4.0, 0.0);
        let link = world
            .add_body(
                BodyDesc::dynamic(Shape::cuboid(Vec3::new(0.15, 0.05, 0.05)).unwrap())
                    .position(top + Vec3::new(0.15, 0.0, 0.0))
                    .can_sleep(false),
            )
            .unwrap();
        world
            .add_joint(JointDesc::ball(previous, link, top))
            .unwrap();
        previous = Some(link);
    }
    let rod = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::new(0.5, 0.05, 0.05)).unwrap())
                .position(Vec3::new(0.5, 8.0, 0.0))
                .can_sleep(false),
        )
        .unwrap();
    world
        .add_joint(
            JointDesc::revolute(None, rod, Vec3::new(0.0, 8.0, 0.0), Vec3::Z)
                .limits(-1.0, 1.0)
                .motor(Motor::velocity(2.0, 5.0)),
        )
        .unwrap();
    let arm = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::new(0.5, 0.05, 0.05)).unwrap())
                .position(Vec3::new(0.5, 12.0, 0.0))
                .can_sleep(false),
        )
        .unwrap();
    let shoulder = world
        .add_joint(
            JointDesc::revolute(None, arm, Vec3::new(0.0, 12.0, 0.0), Vec3::Z)
                .limits(-1.0, 1.0)
                .motor(Motor::torque(0.0)),
        )
        .unwrap();
    // A proportional–derivative controller on the arm's angle, reading it every step.
    let control = |world: &mut World| {
        let angle = world.joint_position(shoulder).unwrap();
        let rate = world.joint_velocity(shoulder).unwrap();
        let torque = -40.0 * angle - 4.0 * rate;
        world
            .set_joint_motor(shoulder, Some(Motor::torque(torque)))
            .unwrap();
        world.step(DT).unwrap();
    };
    // The hanging links knock together now and then, so the buffers reach their largest only
    // after about 680 steps.
    for _ in 0..720 {
        control(&mut world);
    }
    allocations_of(|| {
        for _ in 0..240 {
            control(&mut world);
        }
    });
}

/// A hip and a knee (a thigh shared by two hinges) under a limited spring coupling, and two
/// wheels geared by an equality coupling, one driven: the couplings' rows and the coupled joints
/// they read each step reuse their buffers, and reading a coupling's length allocates nothing.
#[test]
fn a_steady_step_with_couplings_allocates_nothing() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let limb = |world: &mut World, y: f32| {
        (world.add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::new(0.05, 0.25, 0.05)).unwrap())
                .position(Vec3::new(0.0, y, 0.0))
                .can_sleep(false),
        ))
        .unwrap()
    };
    let (thigh, shin) = (limb(&mut world, 7.75), limb(&mut world, 7.25));
    let hip = (world.add_joint(JointDesc::revolute(
        None,
        thigh,
        Vec3::new(0.0, 8.0, 0.0),
        Vec3::Z,
    )))
    .unwrap();
    let knee = (world.add_joint(JointDesc::revolute(
        thigh,
        shin,
        Vec3::new(0.0, 7.5, 0.0),
        Vec3::Z,
    )))
    .unwrap();
    let limb_coupling = (world.add_coupling(
        CouplingDesc::new([(hip, -1.0), (knee, 1.0)])
            .limits(-0.3, 0.3)
            .spring(5.0, 0.5),
    ))
    .unwrap();
    let wheel = |world: &mut World, x: f32| {
        let centre = Vec3::new(x, 12.0, 0.0);
        let body = (world.add_body(
            BodyDesc::dynamic(Shape::sphere(0.3).unwrap())
                .position(centre)
                .can_sleep(false),
        ))
        .unwrap();
        (world.add_joint(JointDesc::revolute(None, body, centre, Vec3::Z))).unwrap()
    };
    let (driven, follower) = (wheel(&mut world, 0.0), wheel(&mut world, 2.0));
    (world.set_joint_motor(driven, Some(Motor::torque(0.5)))).unwrap();
    let gear = (world
        .add_coupling(CouplingDesc::new([(follower, 1.0), (driven, -2.0)]).limits(0.0, 0.0)))
    .unwrap();
    world.set_joint_velocities(&[(hip, 2.0)]).unwrap();
    let run = |world: &mut World| {
        world.step(DT).unwrap();
        std::hint::black_box(world.coupling_length(limb_coupling).unwrap());
        std::hint::black_box(world.coupling_length(gear).unwrap());
    };
    for _ in 0..60 {
        run(&mut world);
    }
    allocations_of(|| {
        for _ in 0..120 {
            run(&mut world);
        }
    });
}

#[test]
fn a_steady_step_with_kinematic_paths_and_targets_allocates_nothing() {
    use rebond::{KinematicPath, PathPoint};
    // A looping platform path (there and back, with a turn) carrying a box, and a second
    // platform driven by a pose target every step: the path's evaluation and the targets'
    // velocities and end poses run each step.
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let turned = Quat::from_rotation_y(0.3);
    let path = KinematicPath::new(vec![
        PathPoint::new(0.0, Vec3::ZERO, Quat::IDENTITY),
        PathPoint::new(1.0, Vec3::new(1.0, 0.0, 0.0), turned),
        PathPoint::new(2.0, Vec3::ZERO, Quat::IDENTITY),
    ])
    .looping(true);
    let platform = || BodyDesc::kinematic(Shape::cuboid(Vec3::new(2.0, 0.1, 2.0)).unwrap());
    world.add_body(platform().path(path)).unwrap();
    let driven = world
        .add_body(platform().position(Vec3::new(0.0, 0.0, 6.0)))
        .unwrap();
    for z in [0.0, 6.0] {
        world
            .add_body(unit_box(Vec3::new(0.0, 0.6, z)).can_sleep(false))
            .unwrap();
    }
    let run = |world: &mut World, steps: usize| {
        for step in 0..steps {
            let x = (step as f32 * DT).sin();
            let target = Pose::new(Vec3::new(x, 0.0, 6.0), Quat::from_rotation_y(0.2 * x));
            world
                .body_mut(driven)
                .unwrap()
                .set_kinematic_target(target)
                .unwrap();
            world.step(DT).unwrap();
        }
    };
    run(&mut world, 240);
    allocations_of(|| run(&mut world, 240));
}

#[test]
fn a_steady_character_move_allocates_nothing() {
    use rebond::character::{CharacterController, CharacterSettings};
    use rebond::QueryFilter;

    let mut world = world(Vec3::new(0.0, -G, 0.0));
    add_ground(&mut world, 0.5);
    // A wall across the walk, at 30° to it, so every frame slides along it on the ground.
    let turn = Quat::from_rotation_y(std::f32::consts::FRAC_PI_6);
    world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(0.5, 2.0, 20.0)).unwrap())
                .position(turn * Vec3::new(1.5, 2.0, 0.0))
                .rotation(turn),
        )
        .unwrap();
    let character = world
        .add_body(
            BodyDesc::kinematic(Shape::capsule(0.3, 0.5).unwrap())
                .position(Vec3::new(0.0, 0.81, 0.0)),
        )
        .unwrap();
    let mut controller = CharacterController::new(CharacterSettings::default()).unwrap();
    let desired = Vec3::new(2.0, -1.0, 0.0) * DT;
    let filter = QueryFilter::default();
    let mut frame = |world: &mut World| {
        let moved = controller
            .move_body(world, character, desired, DT, &filter)
            .unwrap();
        let touching = moved.hits.len();
        world.step(DT).unwrap();
        touching
    };
    for _ in 0..60 {
        frame(&mut world);
    }
    let hits = allocations_of(|| frame(&mut world));
    assert!(hits >= 2, "on the ground and against the wall: {hits} hits");
}

#[test]
fn a_steady_step_with_contact_hooks_conveyors_and_one_way_bodies_allocates_nothing() {
    let mut world = world(Vec3::new(0.0, -G, 0.0));
    let belt = add_ground(&mut world, 0.5);
    // A one-way slab the boxes ride through sideways, its contacts switched off.
    world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(0.5, 0.1, 3.0)).unwrap())
                .position(Vec3::new(0.0, 0.5, 0.0))
                .one_way(Vec3::Y),
        )
        .unwrap();
    for index in 0..3 {
        world
            .add_body(unit_box(Vec3::new(-1.0, 0.5, index as f32 * 1.5)).can_sleep(false))
            .unwrap();
    }
    // The belt carries the boxes along +X for 2 s and back, through the slab each way, and the
    // hook changes every contact's friction (a changed copy of each for the solve).
    let run_back_and_forth = |world: &mut World| {
        for step in 0..240 {
            let speed = if step < 120 { 1.0 } else { -1.0 };
            world
                .set_surface_velocity(belt, Vec3::new(speed, 0.0, 0.0))
                .unwrap();
            world
                .step_with_hooks(DT, &mut |contact: &mut rebond::ContactModification| {
                    contact.set_friction(0.8).unwrap();
                })
                .unwrap();
        }
    };
    run_back_and_forth(&mut world);
    run_back_and_forth(&mut world);
    allocations_of(|| {
        run_back_and_forth(&mut world);
        run_back_and_forth(&mut world);
    });
}
