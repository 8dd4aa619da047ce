//! Sequences of library calls with arbitrary values: adding and removing bodies and joints,
//! setters, steps, ray casts and settings. No call panics, and NaN or infinity never enters a
//! body: every error is a value.
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use rebond::{
    BodyDesc, BodyHandle, JointDesc, JointHandle, JointType, Motor, Quat, QueryFilter, Ray, Shape,
    Vec3, World, WorldSettings,
};

#[derive(Debug, Arbitrary)]
enum ShapeKind {
    Sphere(f32),
    Cuboid([f32; 3]),
    Capsule(f32, f32),
    Cylinder(f32, f32),
    Hull(Vec<[f32; 3]>),
}

#[derive(Debug, Arbitrary)]
enum Op {
    AddBody {
        shape: ShapeKind,
        kind: u8,
        position: [f32; 3],
        rotation: [f32; 4],
        velocity: [f32; 3],
        spin: [f32; 3],
        mass: Option<f32>,
    },
    RemoveBody(u8),
    AddJoint {
        kind: u8,
        a: Option<u8>,
        b: u8,
        anchor: [f32; 3],
        axis: Option<[f32; 3]>,
        limits: Option<[f32; 2]>,
        motor: Option<(f32, f32)>,
        friction: f32,
        break_force: f32,
    },
    RemoveJoint(u8),
    SetVelocity(u8, [f32; 3]),
    SetPosition(u8, [f32; 3]),
    ApplyForce(u8, [f32; 3], [f32; 3]),
    Step(f32),
    CastRay([f32; 3], [f32; 3], f32),
    Settings {
        gravity: [f32; 3],
        substeps: u32,
        max_speed: f32,
    },
}

fn shape(kind: &ShapeKind) -> Option<Shape> {
    match kind {
        ShapeKind::Sphere(r) => Shape::sphere(*r).ok(),
        ShapeKind::Cuboid(h) => Shape::cuboid(Vec3::from_array(*h)).ok(),
        ShapeKind::Capsule(r, h) => Shape::capsule(*r, *h).ok(),
        ShapeKind::Cylinder(r, h) => Shape::cylinder(*r, *h).ok(),
        ShapeKind::Hull(points) => {
            let points: Vec<Vec3> = points
                .iter()
                .take(16)
                .map(|p| Vec3::from_array(*p))
                .collect();
            Shape::convex_hull(&points).ok()
        }
    }
}

fn pick<T: Copy>(items: &[T], index: u8) -> Option<T> {
    (!items.is_empty()).then(|| items[usize::from(index) % items.len()])
}

fuzz_target!(|ops: Vec<Op>| {
    let Ok(mut world) = World::new(WorldSettings::default()) else {
        return;
    };
    let mut bodies: Vec<BodyHandle> = Vec::new();
    let mut joints: Vec<JointHandle> = Vec::new();
    for op in ops.iter().take(64) {
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
                let mut desc = desc
                    .position(Vec3::from_array(*position))
                    .rotation(Quat::from_array(*rotation))
                    .linear_velocity(Vec3::from_array(*velocity))
                    .angular_velocity(Vec3::from_array(*spin));
                if let Some(mass) = mass {
                    desc = desc.mass(*mass);
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
                let mut desc =
                    JointDesc::new(joint_type, body_a, body_b, Vec3::from_array(*anchor));
                desc.axis = axis.map(Vec3::from_array);
                desc.limits = *limits;
                desc.motor = motor.map(|(target, force)| Motor::velocity(target, force));
                desc.friction = *friction;
                desc.break_force = *break_force;
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
                    let _ = body.set_linear_velocity(Vec3::from_array(*velocity));
                }
            }
            Op::SetPosition(index, position) => {
                if let Some(body) = pick(&bodies, *index).and_then(|h| world.body_mut(h).ok()) {
                    let _ = body.set_position(Vec3::from_array(*position));
                }
            }
            Op::ApplyForce(index, force, point) => {
                if let Some(body) = pick(&bodies, *index).and_then(|h| world.body_mut(h).ok()) {
                    let _ = body
                        .apply_force_at_point(Vec3::from_array(*force), Vec3::from_array(*point));
                }
            }
            Op::Step(dt) => {
                if world.step(*dt).is_ok() {
                    for (_, body) in world.bodies() {
                        let finite = body.position().is_finite()
                            && body.rotation().is_finite()
                            && body.linear_velocity().is_finite()
                            && body.angular_velocity().is_finite();
                        assert!(finite, "a body is not finite after a step");
                    }
                }
            }
            Op::CastRay(origin, direction, max) => {
                let mut ray = Ray::new(Vec3::from_array(*origin), Vec3::from_array(*direction));
                ray.max_distance = *max;
                let _ = world.cast_ray(&ray, &QueryFilter::default());
            }
            Op::Settings {
                gravity,
                substeps,
                max_speed,
            } => {
                let settings = WorldSettings {
                    gravity: Vec3::from_array(*gravity),
                    substeps: *substeps,
                    max_linear_speed: *max_speed,
                    ..WorldSettings::default()
                };
                let _ = world.set_settings(settings);
            }
        }
    }
});
