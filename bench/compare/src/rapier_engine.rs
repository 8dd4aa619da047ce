//! Building and stepping the scenes in rapier3d, and its stability figures.

use crate::scenes::{JointKind, Scene, ShapeSpec, DT, FRICTION, GRAVITY, RESTITUTION, SUBSTEPS};
use crate::Engine;
use rapier3d::geometry::{Contact, ContactManifold, ContactPair, PairContacts};

pub struct RapierEngine {
    pub world: rapier3d::prelude::PhysicsWorld,
    dynamic: Vec<rapier3d::prelude::RigidBodyHandle>,
}

impl RapierEngine {
    pub fn new(scene: &Scene) -> Self {
        use rapier3d::prelude::*;
        let mut world = PhysicsWorld::new();
        world.gravity = Vector::new(0.0, GRAVITY, 0.0);
        world.integration_parameters.dt = DT;
        // Rapier's "solver iterations" are substeps: each one integrates velocities, runs one
        // biased PGS pass (`num_internal_pgs_iterations` = 1), integrates positions and runs one
        // relax pass (`num_internal_stabilization_iterations` = 1), at dt / iterations.
        world.integration_parameters.num_solver_iterations = SUBSTEPS as usize;
        let mut dynamic = Vec::new();
        let mut handles = Vec::with_capacity(scene.bodies.len());
        for spec in &scene.bodies {
            let v = |a: [f32; 3]| Vector::new(a[0], a[1], a[2]);
            let collider = match &spec.shape {
                ShapeSpec::Cuboid(h) => ColliderBuilder::cuboid(h[0], h[1], h[2]),
                ShapeSpec::Sphere(r) => ColliderBuilder::ball(*r),
                ShapeSpec::Capsule {
                    radius,
                    half_height,
                } => ColliderBuilder::capsule_y(*half_height, *radius),
                ShapeSpec::Cylinder {
                    radius,
                    half_height,
                } => ColliderBuilder::cylinder(*half_height, *radius),
                ShapeSpec::Hull(points) => {
                    let points: Vec<Vector> = points.iter().map(|p| v(*p)).collect();
                    ColliderBuilder::convex_hull(&points).expect("valid hull")
                }
                ShapeSpec::HeightField { heights, scale } => heightfield(heights, *scale),
                // FIX_INTERNAL_EDGES also merges duplicate vertices (there are none).
                ShapeSpec::TriMesh { vertices, indices } => ColliderBuilder::trimesh_with_flags(
                    vertices.iter().map(|p| v(*p)).collect(),
                    indices.clone(),
                    TriMeshFlags::FIX_INTERNAL_EDGES,
                )
                .expect("valid mesh"),
            }
            .friction(FRICTION)
            .restitution(RESTITUTION);
            let (body, collider) = if spec.fixed {
                (RigidBodyBuilder::fixed(), collider)
            } else {
                (
                    RigidBodyBuilder::dynamic().can_sleep(false),
                    collider.mass(spec.mass),
                )
            };
            let body = body
                .translation(v(spec.position))
                .rotation(v(spec.rotation));
            let (handle, _) = world.insert(body, collider);
            handles.push(handle);
            if !spec.fixed {
                dynamic.push(handle);
            }
        }
        for spec in &scene.joints {
            let v = |a: [f32; 3]| Vector::new(a[0], a[1], a[2]);
            let (body1, body2) = (handles[spec.body_a], handles[spec.body_b]);
            // The joint frame's X is the axis; each body's frame is the world joint frame seen
            // from the body's start pose, so the frames coincide at the start (angles 0), as
            // rebond measures them.
            let world_frame = Pose::from_parts(
                v(spec.anchor),
                Rotation::from_rotation_arc(Vector::X, v(spec.axis)),
            );
            let frame1 = world.bodies[body1].position().inverse() * world_frame;
            let frame2 = world.bodies[body2].position().inverse() * world_frame;
            // `contacts_enabled(false)`: rebond keeps joined bodies from colliding by default,
            // rapier does not. rapier's joints keep their defaults otherwise (nearly rigid, no
            // warm start), as rebond's do (`joint_hertz` 60, ζ 2, warm-started).
            let joint: GenericJoint = match spec.kind {
                JointKind::Ball { swing, twist } => SphericalJointBuilder::new()
                    .local_frame1(frame1)
                    .local_frame2(frame2)
                    .limits(JointAxis::AngX, twist)
                    .limits(JointAxis::AngY, [-swing, swing])
                    .limits(JointAxis::AngZ, [-swing, swing])
                    .contacts_enabled(false)
                    .into(),
                JointKind::Revolute { limits } => {
                    let builder = RevoluteJointBuilder::new(Vector::X).contacts_enabled(false);
                    let builder = match limits {
                        Some(limits) => builder.limits(limits),
                        None => builder,
                    };
                    // The builder takes one axis for both bodies; the frames give each its own.
                    let mut joint = builder.build();
                    joint.data.set_local_frame1(frame1).set_local_frame2(frame2);
                    joint.into()
                }
            };
            world.insert_impulse_joint(body1, body2, joint);
        }
        Self { world, dynamic }
    }

    /// Separations of the current manifold points re-evaluated at the bodies' current poses:
    /// rapier recycles a pair's manifold (and its `dist`) while the pair barely moves, so `dist`
    /// can be a few steps old.
    fn reevaluated(&self) -> f32 {
        let mut deepest = 0.0f32;
        for (pair, manifolds) in self.rigid_pairs() {
            let (Some(c1), Some(c2)) = (
                self.world.colliders.get(pair.collider1),
                self.world.colliders.get(pair.collider2),
            ) else {
                continue;
            };
            let (pos1, pos2) = (c1.position(), c2.position());
            for manifold in manifolds {
                if manifold.subshape_poses.is_some() {
                    continue; // Composite shapes only; none in these scenes.
                }
                let normal = pos1.rotation * manifold.local_n1;
                for point in &manifold.points {
                    let p1 = pos1.transform_point(point.local_p1);
                    let p2 = pos2.transform_point(point.local_p2);
                    deepest = deepest.min((p2 - p1).dot(normal));
                }
            }
        }
        deepest
    }

    /// Every rigid contact pair with its manifolds; pairs of two soft surfaces (none in these
    /// scenes) are left out.
    fn rigid_pairs(&self) -> impl Iterator<Item = (&ContactPair, &[ContactManifold])> {
        self.world
            .narrow_phase
            .contact_pairs()
            .filter_map(|pair| match &pair.contacts {
                PairContacts::Rigid(rigid) => Some((pair, rigid.manifolds.as_slice())),
                _ => None,
            })
    }

    /// Every point of every rigid manifold.
    fn manifold_points(&self) -> impl Iterator<Item = &Contact> {
        self.rigid_pairs()
            .flat_map(|(_, manifolds)| manifolds)
            .flat_map(|manifold| &manifold.points)
    }
}

/// rebond's heightfield (`ShapeSpec::HeightField`) as a parry heightfield with internal-edge
/// fixing. parry splits its cells along the other diagonal, from sample `(i + 1, j)` to
/// `(i, j + 1)` (its zigzag cells take rebond's diagonal, but their edge pseudo-normals look up
/// the neighbours of the default split), so the collider is the grid turned by 90° about +Y,
/// which maps one diagonal onto the other: parry's sample `(i', j')` is rebond's
/// `(rows − 1 − j', i')`, and the scales along X and Z trade places.
fn heightfield(heights: &[Vec<f32>], scale: [f32; 3]) -> rapier3d::prelude::ColliderBuilder {
    use rapier3d::prelude::*;
    let rows = heights.len();
    let turned = Array2::from_fn(heights[0].len(), rows, |i, j| heights[rows - 1 - j][i]);
    ColliderBuilder::heightfield_with_flags(
        turned,
        Vector::new(scale[2], scale[1], scale[0]),
        HeightFieldFlags::FIX_INTERNAL_EDGES,
    )
    .rotation(Vector::new(0.0, std::f32::consts::FRAC_PI_2, 0.0))
}

impl Engine for RapierEngine {
    fn step(&mut self) {
        self.world.step();
    }

    fn positions(&self, out: &mut Vec<[f32; 3]>) {
        out.clear();
        for &handle in &self.dynamic {
            let t = self.world.bodies[handle].translation();
            out.push([t.x, t.y, t.z]);
        }
    }

    fn deepest_penetration(&self) -> f32 {
        self.manifold_points()
            .fold(0.0f32, |deepest, point| deepest.min(point.dist))
    }

    fn rotations(&self, out: &mut Vec<[f32; 4]>) {
        out.clear();
        for &handle in &self.dynamic {
            let q = self.world.bodies[handle].rotation();
            out.push([q.x, q.y, q.z, q.w]);
        }
    }

    fn speeds(&self, out: &mut Vec<f32>) {
        out.clear();
        for &handle in &self.dynamic {
            out.push(self.world.bodies[handle].linvel().length());
        }
    }

    fn deepest_reevaluated(&self) -> Option<f32> {
        Some(self.reevaluated())
    }

    fn contact_points(&self) -> usize {
        self.manifold_points().count()
    }

    fn max_joint_gap(&self) -> f32 {
        let bodies = &self.world.bodies;
        self.world
            .impulse_joints()
            .map(|(_, joint)| {
                let anchor1 =
                    bodies[joint.body1()].position() * joint.data.local_frame1.translation;
                let anchor2 =
                    bodies[joint.body2()].position() * joint.data.local_frame2.translation;
                (anchor2 - anchor1).length()
            })
            .fold(0.0, f32::max)
    }
}
