//! Building and stepping the scenes in rebond, and its stability figures.

use crate::scenes::{
    rebond_substeps, JointKind, Scene, ShapeSpec, DT, FRICTION, GRAVITY, RESTITUTION,
};
use crate::Engine;

pub fn rebond_shape(shape: &ShapeSpec) -> rebond::Shape {
    use rebond::{Shape, Vec3};
    match shape {
        ShapeSpec::Cuboid(h) => Shape::cuboid(Vec3::from(*h)),
        ShapeSpec::Sphere(r) => Shape::sphere(*r),
        ShapeSpec::Capsule {
            radius,
            half_height,
        } => Shape::capsule(*radius, *half_height),
        ShapeSpec::Cylinder {
            radius,
            half_height,
        } => Shape::cylinder(*radius, *half_height),
        ShapeSpec::Hull(points) => {
            let points: Vec<Vec3> = points.iter().map(|p| Vec3::from(*p)).collect();
            Shape::convex_hull(&points)
        }
        ShapeSpec::HeightField { heights, scale } => {
            Shape::heightfield(heights, Vec3::from(*scale))
        }
        ShapeSpec::TriMesh { vertices, indices } => {
            Shape::trimesh(vertices.iter().map(|p| Vec3::from(*p)).collect(), indices)
        }
    }
    .expect("valid shape")
}

pub struct RebondEngine {
    pub world: rebond::World,
    dynamic: Vec<rebond::BodyHandle>,
    joints: Vec<rebond::JointHandle>,
}

impl RebondEngine {
    pub fn new(scene: &Scene) -> Self {
        use rebond::{BodyDesc, JointDesc, Quat, Vec3, World, WorldSettings};
        let mut world = World::new(WorldSettings {
            gravity: Vec3::new(0.0, GRAVITY, 0.0),
            substeps: rebond_substeps(),
            ..WorldSettings::default()
        })
        .expect("settings");
        let mut dynamic = Vec::new();
        let mut handles = Vec::with_capacity(scene.bodies.len());
        for spec in &scene.bodies {
            let shape = rebond_shape(&spec.shape);
            let desc = if spec.fixed {
                BodyDesc::static_body(shape)
            } else {
                BodyDesc::dynamic(shape).mass(spec.mass).can_sleep(false)
            };
            let desc = desc
                .position(Vec3::from(spec.position))
                .rotation(Quat::from_scaled_axis(Vec3::from(spec.rotation)))
                .friction(FRICTION)
                .restitution(RESTITUTION);
            let handle = world.add_body(desc).expect("valid body");
            handles.push(handle);
            if !spec.fixed {
                dynamic.push(handle);
            }
        }
        let joints = scene
            .joints
            .iter()
            .map(|spec| {
                let (a, b) = (handles[spec.body_a], handles[spec.body_b]);
                let (anchor, axis) = (Vec3::from(spec.anchor), Vec3::from(spec.axis));
                let desc = match spec.kind {
                    JointKind::Ball { swing, twist } => JointDesc::ball(a, b, anchor)
                        .axis(axis)
                        .swing_limit(swing)
                        .twist_limits(twist[0], twist[1]),
                    JointKind::Revolute { limits } => {
                        let desc = JointDesc::revolute(a, b, anchor, axis);
                        match limits {
                            Some([min, max]) => desc.limits(min, max),
                            None => desc,
                        }
                    }
                };
                world.add_joint(desc).expect("valid joint")
            })
            .collect();
        Self {
            world,
            dynamic,
            joints,
        }
    }
}

impl Engine for RebondEngine {
    fn step(&mut self) {
        self.world.step(DT).expect("step");
    }

    fn positions(&self, out: &mut Vec<[f32; 3]>) {
        out.clear();
        for &handle in &self.dynamic {
            out.push(self.world.body(handle).expect("body").position().to_array());
        }
    }

    fn deepest_penetration(&self) -> f32 {
        let mut deepest = 0.0f32;
        for contact in self.world.contacts() {
            for point in contact.points() {
                deepest = deepest.min(point.separation);
            }
        }
        deepest
    }

    fn rotations(&self, out: &mut Vec<[f32; 4]>) {
        out.clear();
        for &handle in &self.dynamic {
            out.push(self.world.body(handle).expect("body").rotation().to_array());
        }
    }

    fn speeds(&self, out: &mut Vec<f32>) {
        out.clear();
        for &handle in &self.dynamic {
            out.push(
                self.world
                    .body(handle)
                    .expect("body")
                    .linear_velocity()
                    .length(),
            );
        }
    }

    fn contact_points(&self) -> usize {
        self.world.contact_count()
    }

    fn max_joint_gap(&self) -> f32 {
        self.joints
            .iter()
            .map(|&h| {
                let placement = self.world.joint_placement(h).expect("joint");
                (placement.anchor_b - placement.anchor_a).length()
            })
            .fold(0.0, f32::max)
    }
}
