//! Scene queries against independent references over thousands of random cases: ray casts
//! against closed forms (sphere, box as three slabs, capsule, cylinder, halfspace) and brute
//! force over triangles (hulls) and over children (compounds); shape casts against the closed-form time of impact of a sphere and
//! a box at a box; overlaps against closed-form containment and distance. Then filters, ties,
//! sleeping bodies and input validation.
//!
//! References run in f64. A random case near a tangency is ill-conditioned (a ray grazing a
//! silhouette hits or misses on rounding), so each reference is also evaluated on the shape grown
//! and shrunk by `GROW`: a hit on the shrunk shape must be found, a miss of the grown shape must
//! not be, and distances are compared where the grown and shrunk answers agree closely.

#[path = "../common/random.rs"]
mod random;

use random::Random;

use std::ops::ControlFlow;

use glam::DVec3;
use rebond::internals::collision::dynamic_tree::DynamicTree;
use rebond::shape::CompoundChild;
use rebond::{
    Aabb, BodyDesc, BodyHandle, BodyType, ErrorKind, Pose, Quat, QueryFilter, Ray, RayHit,
    RigidBody, Shape, Vec3, World, WorldSettings,
};

mod closest;
mod filters;
mod overlaps;
mod ray_casts;
mod shape_casts;

/// How far references grow and shrink shapes to tell clear cases from grazing ones, metres.
const GROW: f64 = 1e-4;

impl Random {
    fn rotation(&mut self) -> Quat {
        Quat::from_axis_angle(self.unit_vector(), self.range(0.0, std::f32::consts::TAU))
    }

    fn pose(&mut self, extent: f32) -> Pose {
        Pose::new(self.vec3(-extent, extent), self.rotation())
    }

    fn convex_shape(&mut self, kind: usize) -> Shape {
        match kind % 5 {
            0 => Shape::sphere(self.range(0.2, 1.0)).unwrap(),
            1 => Shape::cuboid(self.vec3(0.1, 1.0)).unwrap(),
            2 => Shape::capsule(self.range(0.1, 0.6), self.range(0.1, 0.8)).unwrap(),
            3 => Shape::cylinder(self.range(0.1, 0.8), self.range(0.1, 0.8)).unwrap(),
            _ => {
                let points: Vec<Vec3> = (0..12).map(|_| self.vec3(-0.8, 0.8)).collect();
                Shape::convex_hull(&points).unwrap()
            }
        }
    }

    fn compound(&mut self) -> Shape {
        let children = (0..3)
            .map(|kind| {
                let kind = kind * 2 + self.next_u64() as usize % 2;
                CompoundChild::new(self.convex_shape(kind), self.pose(0.8))
            })
            .collect();
        Shape::compound(children).unwrap()
    }
}

fn to_f64(v: Vec3) -> DVec3 {
    v.as_dvec3()
}

/// A convex piece of a reference shape in world coordinates, in f64.
enum Piece {
    Ball {
        centre: DVec3,
        radius: f64,
    },
    /// A box: the intersection of three slabs, one per unit axis.
    Box {
        centre: DVec3,
        axes: [DVec3; 3],
        half_extents: DVec3,
    },
    /// A closed triangle mesh of a convex solid.
    Mesh(Vec<[DVec3; 3]>),
    Capsule {
        centre: DVec3,
        axis: DVec3,
        half_height: f64,
        radius: f64,
    },
    Cylinder {
        centre: DVec3,
        axis: DVec3,
        half_height: f64,
        radius: f64,
    },
    Plane {
        point: DVec3,
        normal: DVec3,
    },
}

/// The interval of a line inside a piece: `[enter, leave]`.
type Interval = (f64, f64);

fn union(a: Option<Interval>, b: Option<Interval>) -> Option<Interval> {
    match (a, b) {
        (Some(a), Some(b)) => Some((a.0.min(b.0), a.1.max(b.1))),
        (a, None) => a,
        (None, b) => b,
    }
}

fn intersection(a: Option<Interval>, b: Option<Interval>) -> Option<Interval> {
    let (a, b) = (a?, b?);
    let interval = (a.0.max(b.0), a.1.min(b.1));
    (interval.0 <= interval.1).then_some(interval)
}

/// `|o + t d − c|² = r²` by the textbook quadratic.
fn line_ball(o: DVec3, d: DVec3, centre: DVec3, radius: f64) -> Option<Interval> {
    let oc = o - centre;
    let (a, b, c) = (d.dot(d), oc.dot(d), oc.dot(oc) - radius * radius);
    let discriminant = b * b - a * c;
    (discriminant >= 0.0).then(|| {
        let root = discriminant.sqrt();
        ((-b - root) / a, (-b + root) / a)
    })
}

/// The infinite cylinder of `radius` around the line through `centre` along `axis`.
fn line_tube(o: DVec3, d: DVec3, centre: DVec3, axis: DVec3, radius: f64) -> Option<Interval> {
    let oc = o - centre;
    let (op, dp) = (oc - oc.dot(axis) * axis, d - d.dot(axis) * axis);
    let (a, b, c) = (dp.dot(dp), op.dot(dp), op.dot(op) - radius * radius);
    if a < 1e-18 {
        return (c <= 0.0).then_some((f64::NEG_INFINITY, f64::INFINITY));
    }
    let discriminant = b * b - a * c;
    (discriminant >= 0.0).then(|| {
        let root = discriminant.sqrt();
        ((-b - root) / a, (-b + root) / a)
    })
}

/// The slab `|(p − centre)·axis| ≤ half_height`.
fn line_slab(o: DVec3, d: DVec3, centre: DVec3, axis: DVec3, half_height: f64) -> Option<Interval> {
    let (height, rate) = ((o - centre).dot(axis), d.dot(axis));
    if rate.abs() < 1e-18 {
        return (height.abs() <= half_height).then_some((f64::NEG_INFINITY, f64::INFINITY));
    }
    let (t1, t2) = (
        (-half_height - height) / rate,
        (half_height - height) / rate,
    );
    Some((t1.min(t2), t1.max(t2)))
}

/// Möller–Trumbore on the whole line.
fn line_triangle(o: DVec3, d: DVec3, [a, b, c]: [DVec3; 3]) -> Option<f64> {
    let (e1, e2) = (b - a, c - a);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-15 {
        return None;
    }
    let s = o - a;
    let u = s.dot(p) / det;
    let q = s.cross(e1);
    let v = d.dot(q) / det;
    let slack = 1e-9;
    (u >= -slack && v >= -slack && u + v <= 1.0 + slack).then(|| e2.dot(q) / det)
}

impl Piece {
    fn line(&self, o: DVec3, d: DVec3) -> Option<Interval> {
        match *self {
            Piece::Ball { centre, radius } => line_ball(o, d, centre, radius),
            Piece::Box {
                centre,
                axes,
                half_extents,
            } => (0..3)
                .map(|k| line_slab(o, d, centre, axes[k], half_extents[k]))
                .fold(Some((f64::NEG_INFINITY, f64::INFINITY)), intersection),
            Piece::Mesh(ref triangles) => triangles
                .iter()
                .filter_map(|&triangle| line_triangle(o, d, triangle))
                .fold(None, |interval, t| union(interval, Some((t, t)))),
            Piece::Capsule {
                centre,
                axis,
                half_height,
                radius,
            } => {
                let body = intersection(
                    line_tube(o, d, centre, axis, radius),
                    line_slab(o, d, centre, axis, half_height),
                );
                let ends = union(
                    line_ball(o, d, centre + half_height * axis, radius),
                    line_ball(o, d, centre - half_height * axis, radius),
                );
                union(body, ends)
            }
            Piece::Cylinder {
                centre,
                axis,
                half_height,
                radius,
            } => intersection(
                line_tube(o, d, centre, axis, radius),
                line_slab(o, d, centre, axis, half_height),
            ),
            Piece::Plane { point, normal } => {
                let (height, rate) = ((o - point).dot(normal), d.dot(normal));
                if rate == 0.0 {
                    (height <= 0.0).then_some((f64::NEG_INFINITY, f64::INFINITY))
                } else if rate < 0.0 {
                    Some((-height / rate, f64::INFINITY))
                } else {
                    Some((f64::NEG_INFINITY, -height / rate))
                }
            }
        }
    }
}

/// The reference pieces of `shape` at `pose`, grown by `grow` metres (negative shrinks).
fn pieces(shape: &Shape, pose: &Pose, grow: f64) -> Vec<Piece> {
    let centre = to_f64(pose.position);
    let axis = to_f64(pose.rotation * Vec3::Y);
    match shape {
        Shape::Sphere(sphere) => vec![Piece::Ball {
            centre,
            radius: f64::from(sphere.radius()) + grow,
        }],
        Shape::Cuboid(cuboid) => vec![Piece::Box {
            centre,
            axes: [Vec3::X, Vec3::Y, Vec3::Z].map(|local| to_f64(pose.rotation * local)),
            half_extents: to_f64(cuboid.half_extents()) + grow,
        }],
        Shape::Capsule(capsule) => vec![Piece::Capsule {
            centre,
            axis,
            half_height: f64::from(capsule.half_height()),
            radius: f64::from(capsule.radius()) + grow,
        }],
        Shape::Cylinder(cylinder) => vec![Piece::Cylinder {
            centre,
            axis,
            half_height: f64::from(cylinder.half_height()) + grow,
            radius: f64::from(cylinder.radius()) + grow,
        }],
        Shape::ConvexHull(hull) => {
            let vertices: Vec<DVec3> = hull.vertices().iter().map(|v| to_f64(*v)).collect();
            let middle = vertices.iter().sum::<DVec3>() / vertices.len() as f64;
            let size = vertices
                .iter()
                .map(|v| (*v - middle).length())
                .fold(0.0, f64::max);
            let scale = 1.0 + grow / size;
            let place = |index: u32| {
                let local = middle + (vertices[index as usize] - middle) * scale;
                centre + pose.rotation.as_dquat() * local
            };
            let mut triangles = Vec::new();
            for face in hull.faces() {
                for k in 1..face.vertices.len() - 1 {
                    triangles.push([
                        place(face.vertices[0]),
                        place(face.vertices[k]),
                        place(face.vertices[k + 1]),
                    ]);
                }
            }
            vec![Piece::Mesh(triangles)]
        }
        Shape::Halfspace(halfspace) => {
            let normal = to_f64(pose.rotation * halfspace.normal());
            vec![Piece::Plane {
                point: centre + grow * normal,
                normal,
            }]
        }
        Shape::Compound(compound) => compound
            .children()
            .iter()
            .flat_map(|child| pieces(&child.shape, &pose.mul_pose(&child.pose), grow))
            .collect(),
        // Surfaces: their own triangles, which growing does not change.
        Shape::TriMesh(mesh) => {
            let place = |index: u32| to_f64(pose.transform_point(mesh.vertices()[index as usize]));
            vec![Piece::Mesh(
                mesh.indices()
                    .iter()
                    .map(|triangle| triangle.map(place))
                    .collect(),
            )]
        }
        Shape::HeightField(heightfield) => vec![Piece::Mesh(
            (0..heightfield.triangle_count())
                .filter_map(|index| heightfield.triangle(index))
                .map(|triangle| triangle.vertices.map(|v| to_f64(pose.transform_point(v))))
                .collect(),
        )],
    }
}

/// The distance at which a ray meets a piece: entering ahead, or starting inside (zero if
/// solid, where it leaves if hollow).
fn ray_answer(interval: Option<Interval>, solid: bool) -> Option<f64> {
    let (enter, leave) = interval?;
    if enter >= 0.0 {
        Some(enter)
    } else if leave < 0.0 {
        None
    } else if solid {
        Some(0.0)
    } else {
        leave.is_finite().then_some(leave)
    }
}

/// The reference answer of a ray against a shape grown by `grow`: the nearest piece's answer.
fn reference_ray(shape: &Shape, pose: &Pose, ray: &Ray, grow: f64) -> Option<f64> {
    let (o, d) = (to_f64(ray.origin), to_f64(ray.direction).normalize());
    pieces(shape, pose, grow)
        .iter()
        .filter_map(|piece| ray_answer(piece.line(o, d), ray.solid))
        .filter(|&t| t <= f64::from(ray.max_distance))
        .reduce(f64::min)
}

/// What a reference says about one ray and one shape.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Expected {
    /// Even the grown shape is missed.
    Miss,
    /// Even the shrunk shape is hit, at about the same distance: the distance to match.
    Hit(f64),
    /// Anything in between: a grazing ray, either answer is right.
    Either,
}

fn expected_ray(shape: &Shape, pose: &Pose, ray: &Ray) -> Expected {
    let grown = reference_ray(shape, pose, ray, GROW);
    let shrunk = reference_ray(shape, pose, ray, -GROW);
    match (grown, shrunk) {
        (None, _) => Expected::Miss,
        (Some(outer), Some(inner)) if (outer - inner).abs() < 1e-2 => {
            Expected::Hit(reference_ray(shape, pose, ray, 0.0).unwrap_or(inner))
        }
        _ => Expected::Either,
    }
}

/// The world point of `shape` at `pose` farthest along `direction`.
fn world_support(shape: &Shape, pose: &Pose, direction: Vec3) -> Option<Vec3> {
    shape
        .support(pose.inverse_transform_vector(direction))
        .map(|local| pose.transform_point(local))
}

/// Whether `normal` is an outward normal of the convex `shape` at `point`: the plane through
/// the point with that normal has the whole shape behind it.
fn is_outward_normal(shape: &Shape, pose: &Pose, point: Vec3, normal: Vec3) -> bool {
    outward_normal_gap(shape, pose, point, normal) <= 2e-4
}

/// How far `shape` reaches beyond the plane through `point` with `normal`, metres: zero for an
/// outward normal at a point of the surface.
fn outward_normal_gap(shape: &Shape, pose: &Pose, point: Vec3, normal: Vec3) -> f32 {
    match shape {
        Shape::Halfspace(halfspace) => 1.0 - (pose.rotation * halfspace.normal()).dot(normal),
        _ => world_support(shape, pose, normal)
            .map_or(f32::INFINITY, |support| (support - point).dot(normal)),
    }
}

/// Checks one hit of a ray on a convex shape against the reference and the normal rules.
fn check_convex_hit(shape: &Shape, pose: &Pose, ray: &Ray, hit: Option<RayHit>, label: &str) {
    let direction = ray.direction.normalize();
    match (expected_ray(shape, pose, ray), hit) {
        (Expected::Miss, Some(hit)) => panic!("{label}: {ray:?} should miss, got {hit:?}"),
        (Expected::Hit(t), None) => panic!("{label}: {ray:?} should hit at {t}"),
        (Expected::Hit(t), Some(hit)) => {
            let tolerance = 1e-4 * (1.0 + t);
            assert!(
                (f64::from(hit.distance) - t).abs() <= tolerance,
                "{label}: {ray:?} hit at {} instead of {t}",
                hit.distance
            );
            let on_ray = ray.origin + hit.distance * direction;
            assert!((hit.point - on_ray).length() <= 1e-5 * (1.0 + on_ray.length()));
            assert!(
                (hit.normal.length() - 1.0).abs() < 1e-4,
                "{label}: normal {hit:?}"
            );
            if hit.distance == 0.0 && ray.solid {
                assert!(
                    (hit.normal + direction).length() < 1e-6,
                    "{label}: solid ray inside"
                );
            } else if hit.normal.dot(direction) <= 0.0
                && is_outward_normal(shape, pose, hit.point, hit.normal)
            {
                // Entering: the outward normal.
            } else {
                assert!(
                    !ray.solid && is_outward_normal(shape, pose, hit.point, -hit.normal),
                    "{label}: {ray:?} got normal {} at {}",
                    hit.normal,
                    hit.point
                );
            }
        }
        _ => {}
    }
}

fn world() -> World {
    World::new(WorldSettings::default()).unwrap()
}

/// A ray from around a body of size about `size` at `centre`: mostly from outside aimed at its
/// surroundings, sometimes from inside; solid or hollow; usually unbounded.
fn random_ray(random: &mut Random, centre: Vec3, size: f32) -> Ray {
    let ray = if random.chance(0.7) {
        let origin = centre + random.unit_vector() * size * random.range(1.5, 4.0);
        let target = centre + random.vec3(-size, size) * 0.8;
        Ray::new(origin, target - origin)
    } else {
        Ray::new(
            centre + random.vec3(-size, size),
            random.unit_vector() * random.range(0.5, 2.0),
        )
    };
    let ray = if random.chance(0.5) {
        ray.hollow()
    } else {
        ray
    };
    if random.chance(0.2) {
        ray.max_distance(random.range(0.0, 3.0 * size))
    } else {
        ray
    }
}

/// The box's local frame: world to local for a point and a direction, in f64.
fn to_local(pose: &Pose, point: Vec3, direction: Vec3) -> (DVec3, DVec3) {
    let inverse = pose.rotation.as_dquat().inverse();
    (
        inverse * (to_f64(point) - to_f64(pose.position)),
        inverse * to_f64(direction),
    )
}

/// When box A (centre, axes, half extents) moving along unit `d` first touches the fixed box B:
/// on each of the 15 separating axes of two boxes, the projections overlap on an interval of
/// travel; the boxes overlap on the intersection of the 15 intervals.
fn box_box_time_of_impact(
    a: &Pose,
    half_a: DVec3,
    b: &Pose,
    half_b: DVec3,
    d: DVec3,
) -> Option<f64> {
    let axes_a = [DVec3::X, DVec3::Y, DVec3::Z].map(|axis| a.rotation.as_dquat() * axis);
    let axes_b = [DVec3::X, DVec3::Y, DVec3::Z].map(|axis| b.rotation.as_dquat() * axis);
    let mut axes: Vec<DVec3> = axes_a.iter().chain(&axes_b).copied().collect();
    for edge_a in axes_a {
        for edge_b in axes_b {
            let cross = edge_a.cross(edge_b);
            if cross.length() > 1e-9 {
                axes.push(cross.normalize());
            }
        }
    }
    let gap = to_f64(b.position) - to_f64(a.position);
    let mut travel = Some((f64::NEG_INFINITY, f64::INFINITY));
    for axis in axes {
        let reach = (0..3)
            .map(|k| axes_a[k].dot(axis).abs() * half_a[k] + axes_b[k].dot(axis).abs() * half_b[k])
            .sum::<f64>();
        let (offset, rate) = (gap.dot(axis), d.dot(axis));
        let along = if rate.abs() < 1e-12 {
            (offset.abs() <= reach).then_some((f64::NEG_INFINITY, f64::INFINITY))
        } else {
            let (t1, t2) = ((offset - reach) / rate, (offset + reach) / rate);
            Some((t1.min(t2), t1.max(t2)))
        };
        travel = intersection(travel, along);
    }
    ray_answer(travel, true)
}
