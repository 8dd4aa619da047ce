//! Sequences of library calls with arbitrary values, shared by the `world_calls` fuzz target and
//! the property test `crates/rebond/tests/call_sequences.rs`: adding and removing bodies and
//! joints, setters, forces, steps, ray casts and settings. [`run`] checks what the engine
//! promises for any sequence: no call panics, NaN or infinity never enters a body, and the
//! world's saved state restores and steps bit for bit as the world does.

use arbitrary::{Arbitrary, Unstructured};
use rebond::{
    limits, BodyDesc, BodyHandle, JointDesc, JointHandle, JointType, Motor, Quat, QueryFilter, Ray,
    Shape, Vec3, World, WorldSettings,
};

/// A number drawn to reach deep: mostly ordinary values of a scene, often the engine's limits
/// and the values just past them, sometimes any `f32` at all (NaN and infinities included).
#[derive(Debug, Clone, Copy)]
pub struct Num(pub f32);

/// Values at and past the engine's limits, and the special ones.
const EDGES: [f32; 16] = [
    0.0,
    -1.0,
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::MAX,
    f32::MIN_POSITIVE,
    1e30,
    limits::MAX_SIZE,
    limits::MIN_SIZE,
    limits::MAX_COORDINATE,
    limits::MAX_SPEED,
    limits::MAX_MASS,
    limits::MIN_MASS,
    limits::MAX_FORCE,
    limits::MAX_TIMESTEP,
];

impl<'a> Arbitrary<'a> for Num {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<Self> {
        Ok(Num(match u.int_in_range(0u8..=7)? {
            0..=4 => f32::from(u.int_in_range(-80i8..=80)?) / 16.0,
            5 => f32::from(u.int_in_range(-100i8..=100)?) * 10.0,
            6 => *u.choose(&EDGES)?,
            _ => f32::arbitrary(u)?,
        }))
    }
}

fn vector([x, y, z]: [Num; 3]) -> Vec3 {
    Vec3::new(x.0, y.0, z.0)
}

#[derive(Debug, Arbitrary)]
pub enum ShapeKind {
    Sphere(Num),
    Cuboid([Num; 3]),
    Capsule(Num, Num),
    Cylinder(Num, Num),
    Hull([[Num; 3]; 6]),
}

#[derive(Debug, Arbitrary)]
pub enum Op {
    AddBody {
        shape: ShapeKind,
        kind: u8,
        position: [Num; 3],
        rotation: [Num; 4],
        velocity: [Num; 3],
        spin: [Num; 3],
        mass: Option<Num>,
    },
    RemoveBody(u8),
    AddJoint {
        kind: u8,
        a: Option<u8>,
        b: u8,
        anchor: [Num; 3],
        axis: Option<[Num; 3]>,
        limits: Option<[Num; 2]>,
        motor: Option<(Num, Num)>,
        friction: Num,
        break_force: Num,
    },
    RemoveJoint(u8),
    SetVelocity(u8, [Num; 3]),
    SetPosition(u8, [Num; 3]),
    ApplyForce(u8, [Num; 3], [Num; 3]),
    Step(Num),
    CastRay([Num; 3], [Num; 3], Num),
    Settings {
        gravity: [Num; 3],
        substeps: u32,
        max_speed: Num,
    },
}

fn shape(kind: &ShapeKind) -> Option<Shape> {
    match kind {
        ShapeKind::Sphere(r) => Shape::sphere(r.0).ok(),
        ShapeKind::Cuboid(h) => Shape::cuboid(vector(*h)).ok(),
        ShapeKind::Capsule(r, h) => Shape::capsule(r.0, h.0).ok(),
        ShapeKind::Cylinder(r, h) => Shape::cylinder(r.0, h.0).ok(),
        ShapeKind::Hull(points) => {
            let points = points.map(vector);
            Shape::convex_hull(&points).ok()
        }
    }
}

fn pick<T: Copy>(items: &[T], index: u8) -> Option<T> {
    (!items.is_empty()).then(|| items[usize::from(index) % items.len()])
}

/// Whether every body's pose and velocities are finite.
fn all_finite(world: &World) -> bool {
    world.bodies().all(|(_, body)| {
        body.position().is_finite()
            && body.rotation().is_finite()
            && body.linear_velocity().is_finite()
            && body.angular_velocity().is_finite()
    })
}

/// Runs the calls on a new world; panics if a call panics, a step leaves a body that is not
/// finite, or the world's saved state does not restore to step exactly as the world.
pub fn run(ops: &[Op]) {
    let Ok(mut world) = World::new(WorldSettings::default()) else {
        return;
    };
    let mut bodies: Vec<BodyHandle> = Vec::new();
    let mut joints: Vec<JointHandle> = Vec::new();
    for op in ops {
        match op {
            Op::AddBody {
                shape: kind,
                kind: body_type,
                position,
                rotation,
                velocity,
                spin,
                mass,
            } => {
                let Some(shape) = shape(kind) else { continue };
                let desc = match body_type % 3 {
                    0 => BodyDesc::dynamic(shape),
                    1 => BodyDesc::static_body(shape),
                    _ => BodyDesc::kinematic(shape),
                };
                let [x, y, z, w] = rotation.map(|n| n.0);
                let mut desc = desc
                    .position(vector(*position))
                    .rotation(Quat::from_xyzw(x, y, z, w))
                    .linear_velocity(vector(*velocity))
                    .angular_velocity(vector(*spin));
                if let Some(mass) = mass {
                    desc = desc.mass(mass.0);
                }
                if let Ok(handle) = world.add_body(desc) {
                    bodies.push(handle);
                }
            }
            Op::RemoveBody(index) => {
                if let Some(handle) = pick(&bodies, *index) {
                    let _ = world.remove_body(handle);
                }
            }
            Op::AddJoint {
                kind,
                a,
                b,
                anchor,
                axis,
                limits,
                motor,
                friction,
                break_force,
            } => {
                let Some(body_b) = pick(&bodies, *b) else {
                    continue;
                };
                let body_a = a.and_then(|a| pick(&bodies, a));
                let joint_type = [
                    JointType::Fixed,
                    JointType::Ball,
                    JointType::Revolute,
                    JointType::Prismatic,
                    JointType::Distance,
                ][usize::from(*kind) % 5];
                let mut desc = JointDesc::new(joint_type, body_a, body_b, vector(*anchor));
                desc.axis = axis.map(vector);
                desc.limits = limits.map(|[min, max]| [min.0, max.0]);
                desc.motor = motor.map(|(target, force)| Motor::velocity(target.0, force.0));
                desc.friction = friction.0;
                desc.break_force = break_force.0;
                if let Ok(handle) = world.add_joint(desc) {
                    joints.push(handle);
                }
            }
            Op::RemoveJoint(index) => {
                if let Some(handle) = pick(&joints, *index) {
                    let _ = world.remove_joint(handle);
                }
            }
            Op::SetVelocity(index, velocity) => {
                if let Some(body) = pick(&bodies, *index).and_then(|h| world.body_mut(h).ok()) {
                    let _ = body.set_linear_velocity(vector(*velocity));
                }
            }
            Op::SetPosition(index, position) => {
                if let Some(body) = pick(&bodies, *index).and_then(|h| world.body_mut(h).ok()) {
                    let _ = body.set_position(vector(*position));
                }
            }
            Op::ApplyForce(index, force, point) => {
                if let Some(body) = pick(&bodies, *index).and_then(|h| world.body_mut(h).ok()) {
                    let _ = body.apply_force_at_point(vector(*force), vector(*point));
                }
            }
            Op::Step(dt) => {
                // Mostly a step of the usual length, or the number drawn.
                let dt = if dt.0 >= 0.0 && dt.0 < 1.0 {
                    1.0 / 60.0
                } else {
                    dt.0
                };
                if world.step(dt).is_ok() {
                    assert!(all_finite(&world), "a body is not finite after a step");
                }
            }
            Op::CastRay(origin, direction, max) => {
                let mut ray = Ray::new(vector(*origin), vector(*direction));
                ray.max_distance = max.0;
                let _ = world.cast_ray(&ray, &QueryFilter::default());
            }
            Op::Settings {
                gravity,
                substeps,
                max_speed,
            } => {
                let settings = WorldSettings {
                    gravity: vector(*gravity),
                    substeps: *substeps,
                    max_linear_speed: max_speed.0,
                    ..WorldSettings::default()
                };
                let _ = world.set_settings(settings);
            }
        }
    }
    // Whatever the calls made of the world, its state restores and steps as the world does.
    let mut restored = World::load_state(&world.save_state())
        .unwrap_or_else(|error| panic!("a saved world is refused: {error}"));
    if world.step(1.0 / 60.0).is_ok() {
        assert!(
            restored.step(1.0 / 60.0).is_ok(),
            "a restored world does not step"
        );
        let poses = |world: &World| -> Vec<[u32; 7]> {
            let bits = |body: &rebond::RigidBody| {
                let [x, y, z] = body.position().to_array();
                let [i, j, k, w] = body.rotation().to_array();
                [x, y, z, i, j, k, w].map(f32::to_bits)
            };
            world.bodies().map(|(_, body)| bits(body)).collect()
        };
        assert!(
            poses(&world) == poses(&restored),
            "a restored world steps otherwise"
        );
    }
}

/// Runs the calls that `data` encodes, one [`Op`] after another while the bytes last (64 at
/// most).
pub fn run_bytes(data: &[u8]) {
    let mut bytes = Unstructured::new(data);
    let mut ops = Vec::new();
    while ops.len() < 64 && !bytes.is_empty() {
        match Op::arbitrary(&mut bytes) {
            Ok(op) => ops.push(op),
            Err(_) => break,
        }
    }
    run(&ops);
}
