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

#[path = "common/random.rs"]
mod random;

use random::Random;

use std::ops::ControlFlow;

use glam::DVec3;
use rebond::collision::dynamic_tree::DynamicTree;
use rebond::shape::CompoundChild;
use rebond::{
    Aabb, BodyDesc, BodyHandle, BodyType, ErrorKind, Pose, Quat, QueryFilter, Ray, RayHit,
    RigidBody, Shape, Vec3, World, WorldSettings,
};

/// How far references grow and shrink shapes to tell clear cases from grazing ones, metres.
const GROW: f64 = 1e-4;

impl Random {
    fn unit_vector(&mut self) -> Vec3 {
        loop {
            let v = self.vec3(-1.0, 1.0);
            if (0.01..=1.0).contains(&v.length_squared()) {
                return v.normalize();
            }
        }
    }

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
                CompoundChild {
                    pose: self.pose(0.8),
                    shape: self.convex_shape(kind),
                }
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

#[test]
fn ray_casts_match_closed_forms_and_brute_force_for_every_shape() {
    let mut random = Random(0xa11ce);
    let kinds = [
        "sphere",
        "box",
        "capsule",
        "cylinder",
        "hull",
        "compound",
        "halfspace",
    ];
    for (kind, label) in kinds.iter().enumerate() {
        let mut clear_hits = 0;
        let mut rays = 0;
        for _ in 0..10 {
            let shape = match kind {
                0..=4 => random.convex_shape(kind),
                5 => random.compound(),
                _ => Shape::halfspace(random.unit_vector()).unwrap(),
            };
            let pose = random.pose(3.0);
            let mut world = world();
            let body = world
                .add_body(
                    BodyDesc::fixed(shape.clone())
                        .position(pose.position)
                        .rotation(pose.rotation),
                )
                .unwrap();
            let pose = world.body(body).unwrap().pose();
            for _ in 0..500 {
                let size = shape.aabb(&pose).half_extents().max_element().min(1.5);
                let ray = random_ray(&mut random, pose.position, size);
                let hit = world.cast_ray(&ray, &QueryFilter::new()).unwrap();
                if let Some(hit) = hit {
                    assert_eq!(hit.body, body);
                }
                rays += 1;
                if matches!(expected_ray(&shape, &pose, &ray), Expected::Hit(_)) {
                    clear_hits += 1;
                }
                if let Shape::Compound(compound) = &shape {
                    check_compound_hit(compound.children(), &pose, &ray, hit, label);
                } else {
                    check_convex_hit(&shape, &pose, &ray, hit, label);
                }
            }
        }
        assert!(
            clear_hits * 4 > rays,
            "{label}: only {clear_hits} of {rays} rays hit clearly"
        );
    }
}

/// A compound: the distance against the brute-force reference; the normal against the child
/// hit when one child is clearly nearer than the others.
fn check_compound_hit(
    children: &[CompoundChild],
    pose: &Pose,
    ray: &Ray,
    hit: Option<RayHit>,
    label: &str,
) {
    let compound = Shape::compound(children.to_vec()).unwrap();
    let direction = ray.direction.normalize();
    match (expected_ray(&compound, pose, ray), hit) {
        (Expected::Miss, Some(hit)) => panic!("{label}: {ray:?} should miss, got {hit:?}"),
        (Expected::Hit(t), None) => panic!("{label}: {ray:?} should hit at {t}"),
        (Expected::Hit(t), Some(hit)) => {
            assert!(
                (f64::from(hit.distance) - t).abs() <= 1e-4 * (1.0 + t),
                "{label}: {ray:?} hit at {} instead of {t}",
                hit.distance
            );
            let mut by_child: Vec<(f64, usize)> = children
                .iter()
                .enumerate()
                .filter_map(|(index, child)| {
                    reference_ray(&child.shape, &pose.mul_pose(&child.pose), ray, 0.0)
                        .map(|t| (t, index))
                })
                .collect();
            by_child.sort_by(|a, b| a.0.total_cmp(&b.0));
            let clearly_first = by_child.len() == 1 || by_child[1].0 - by_child[0].0 > 1e-3;
            if clearly_first && !(hit.distance == 0.0 && ray.solid) {
                let child = &children[by_child[0].1];
                let child_pose = pose.mul_pose(&child.pose);
                let entering = hit.normal.dot(direction) <= 0.0
                    && is_outward_normal(&child.shape, &child_pose, hit.point, hit.normal);
                let leaving = !ray.solid
                    && is_outward_normal(&child.shape, &child_pose, hit.point, -hit.normal);
                assert!(
                    entering || leaving,
                    "{label}: {ray:?} got normal {} at {}",
                    hit.normal,
                    hit.point
                );
            }
        }
        _ => {}
    }
}

#[test]
fn scene_ray_casts_find_every_body_brute_force_finds() {
    let mut random = Random(0x5ce4e);
    let mut world = world();
    let mut bodies: Vec<(BodyHandle, Shape, Pose)> = Vec::new();
    let ground = Shape::halfspace(Vec3::Y).unwrap();
    let handle = world
        .add_body(BodyDesc::fixed(ground.clone()).position(Vec3::new(0.0, -12.0, 0.0)))
        .unwrap();
    bodies.push((handle, ground, world.body(handle).unwrap().pose()));
    for index in 0..400 {
        let shape = if index % 6 == 5 {
            random.compound()
        } else {
            random.convex_shape(index)
        };
        let body_type = [BodyType::Static, BodyType::Dynamic, BodyType::Kinematic][index % 3];
        let pose = random.pose(10.0);
        let handle = world
            .add_body(
                BodyDesc::new(body_type, shape.clone())
                    .position(pose.position)
                    .rotation(pose.rotation),
            )
            .unwrap();
        bodies.push((handle, shape, world.body(handle).unwrap().pose()));
    }
    let (mut all, mut total_hits) = (Vec::new(), 0);
    for _ in 0..2000 {
        let origin = random.vec3(-14.0, 14.0);
        let mut ray = Ray::new(origin, random.unit_vector());
        ray.solid = random.chance(0.5);
        if random.chance(0.5) {
            ray.max_distance = random.range(2.0, 30.0);
        }
        let filter = QueryFilter::new();
        world.cast_ray_all(&ray, &filter, &mut all).unwrap();
        let nearest = world.cast_ray(&ray, &filter).unwrap();
        assert_eq!(nearest, all.first().copied(), "{ray:?}");
        assert_eq!(world.cast_ray_any(&ray, &filter).unwrap(), !all.is_empty());
        for pair in all.windows(2) {
            assert!((pair[0].distance, pair[0].body) < (pair[1].distance, pair[1].body));
        }
        total_hits += all.len();
        for (handle, shape, pose) in &bodies {
            let found = all.iter().find(|hit| hit.body == *handle);
            match (expected_ray(shape, pose, &ray), found) {
                (Expected::Miss, Some(hit)) => panic!("{ray:?} should miss {shape:?}: {hit:?}"),
                (Expected::Hit(t), None) => panic!("{ray:?} should hit {shape:?} at {t}"),
                (Expected::Hit(t), Some(hit)) => {
                    assert!((f64::from(hit.distance) - t).abs() <= 1e-4 * (1.0 + t));
                }
                _ => {}
            }
        }
    }
    assert!(total_hits > 1000, "only {total_hits} hits");
}

#[test]
fn ray_distance_limit_solid_and_hollow_rays() {
    let mut world = world();
    let wall = world
        .add_body(
            BodyDesc::fixed(Shape::cuboid(Vec3::splat(1.0)).unwrap())
                .position(Vec3::new(6.0, 0.0, 0.0)),
        )
        .unwrap();
    let ball = world
        .add_body(BodyDesc::fixed(Shape::sphere(1.0).unwrap()))
        .unwrap();
    let ground = world
        .add_body(
            BodyDesc::fixed(Shape::halfspace(Vec3::Y).unwrap()).position(Vec3::new(0.0, -5.0, 0.0)),
        )
        .unwrap();
    let filter = QueryFilter::new();
    let toward_wall = Ray::new(Vec3::new(2.0, 0.0, 0.0), Vec3::X * 3.0);
    assert_eq!(
        world
            .cast_ray(&toward_wall.max_distance(2.9), &filter)
            .unwrap(),
        None
    );
    for limit in [3.0, 3.1, f32::INFINITY] {
        let hit = world
            .cast_ray(&toward_wall.max_distance(limit), &filter)
            .unwrap()
            .unwrap();
        assert_eq!(
            (hit.body, hit.distance, hit.normal),
            (wall, 3.0, Vec3::NEG_X)
        );
        assert_eq!(hit.point, Vec3::new(5.0, 0.0, 0.0));
    }

    // From the ball's centre: solid hits the ball at once, hollow where it leaves it.
    let from_inside = Ray::new(Vec3::ZERO, Vec3::X);
    let solid = world.cast_ray(&from_inside, &filter).unwrap().unwrap();
    assert_eq!(
        (solid.body, solid.distance, solid.point, solid.normal),
        (ball, 0.0, Vec3::ZERO, Vec3::NEG_X)
    );
    let hollow = world
        .cast_ray(&from_inside.hollow(), &filter)
        .unwrap()
        .unwrap();
    assert_eq!(
        (hollow.body, hollow.distance, hollow.normal),
        (ball, 1.0, Vec3::NEG_X)
    );
    let mut hits = Vec::new();
    world
        .cast_ray_all(&from_inside.hollow(), &filter, &mut hits)
        .unwrap();
    let bodies: Vec<_> = hits.iter().map(|hit| (hit.body, hit.distance)).collect();
    assert_eq!(bodies, [(ball, 1.0), (wall, 5.0)]);

    // Below the ground: a hollow ray going deeper never leaves it, one going up leaves it.
    let under = Vec3::new(0.0, -7.0, 0.0);
    let down = Ray::new(under, Vec3::NEG_Y);
    assert_eq!(
        world.cast_ray(&down, &filter).unwrap().unwrap().distance,
        0.0
    );
    assert_eq!(world.cast_ray(&down.hollow(), &filter).unwrap(), None);
    let up = world
        .cast_ray(&Ray::new(under, Vec3::Y).hollow(), &filter)
        .unwrap()
        .unwrap();
    assert_eq!(
        (up.body, up.distance, up.normal),
        (ground, 2.0, Vec3::NEG_Y)
    );
}

#[test]
fn tree_casts_visit_exactly_the_boxes_on_the_path_nearest_first() {
    let mut random = Random(0x7ee);
    let mut tree = DynamicTree::new();
    let proxies: Vec<_> = (0..600)
        .map(|index| {
            let centre = random.vec3(-20.0, 20.0);
            tree.create_proxy(
                Aabb::from_center_half_extents(centre, random.vec3(0.1, 1.5)),
                index,
            )
        })
        .collect();
    // The entry of a ray into a box in f64, for a box grown by `grow` on every side.
    let entry = |origin: Vec3, direction: Vec3, max: f32, aabb: &Aabb, grow: f64| {
        let (o, d) = (to_f64(origin), to_f64(direction));
        let (min, max_corner) = (to_f64(aabb.min) - grow, to_f64(aabb.max) + grow);
        let (mut enter, mut leave) = (0.0_f64, f64::from(max));
        for axis in 0..3 {
            if d[axis] == 0.0 {
                if o[axis] < min[axis] || o[axis] > max_corner[axis] {
                    return None;
                }
                continue;
            }
            let (t1, t2) = (
                (min[axis] - o[axis]) / d[axis],
                (max_corner[axis] - o[axis]) / d[axis],
            );
            enter = enter.max(t1.min(t2));
            leave = leave.min(t1.max(t2));
        }
        (enter <= leave).then_some(enter)
    };
    for round in 0..600 {
        let origin = random.vec3(-25.0, 25.0);
        let mut direction = random.unit_vector();
        if round % 10 == 0 {
            direction[round / 10 % 3] = 0.0;
            direction = direction.normalize();
        }
        let max = if round % 2 == 0 {
            f32::INFINITY
        } else {
            random.range(0.0, 40.0)
        };
        let swept = Aabb::from_center_half_extents(origin, random.vec3(0.0, 1.0));
        let is_box_cast = round % 3 == 0;
        let mut visited = Vec::new();
        let record = |proxy, entry_distance| {
            visited.push((proxy, entry_distance));
            ControlFlow::Continue(f32::INFINITY)
        };
        if is_box_cast {
            tree.box_cast(&swept, direction, max, record);
        } else {
            tree.ray_cast(origin, direction, max, record);
        }
        let grown_by = if is_box_cast {
            swept.half_extents()
        } else {
            Vec3::ZERO
        };
        for &proxy in &proxies {
            let fat = tree.fat_aabb(proxy);
            let fat = Aabb::new(fat.min - grown_by, fat.max + grown_by);
            let start = swept.center();
            let found = visited.iter().find(|(visited, _)| *visited == proxy);
            let inner = entry(start, direction, max, &fat, -1e-4);
            let outer = entry(start, direction, max, &fat, 1e-4);
            match (found, inner, outer) {
                (Some(_), _, None) => panic!("visited a box off the path"),
                (None, Some(_), _) => panic!("missed a box on the path"),
                (Some(&(_, distance)), Some(_), _) => {
                    let exact = entry(start, direction, max, &fat, 0.0).unwrap();
                    assert!((f64::from(distance) - exact).abs() < 1e-4 * (1.0 + exact));
                }
                _ => {}
            }
        }
        let nearest = visited
            .iter()
            .map(|&(_, distance)| distance)
            .reduce(f32::min);
        let mut closest = None;
        let mut first_calls = 0;
        tree.ray_cast(swept.center(), direction, max, |_, distance| {
            first_calls += 1;
            if !is_box_cast {
                closest = Some(closest.map_or(distance, |best: f32| best.min(distance)));
            }
            ControlFlow::Continue(distance)
        });
        if !is_box_cast {
            assert_eq!(closest, nearest);
        }
        let mut calls = 0;
        tree.ray_cast(swept.center(), direction, max, |_, _| {
            calls += 1;
            ControlFlow::Break(())
        });
        assert!(calls <= 1 && first_calls >= calls);
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

/// When a ball of `radius` whose centre moves along `o + t d` (box frame, unit `d`) first
/// touches the box of half extents `half`: the ray against the box rounded by the radius, the
/// union of the box grown along each axis, a cylinder on each edge and a ball on each corner.
fn ball_box_time_of_impact(o: DVec3, d: DVec3, half: DVec3, radius: f64) -> Option<f64> {
    let mut crossing = None;
    for axis in 0..3 {
        let mut grown = half;
        grown[axis] += radius;
        let slabs = (0..3).try_fold((f64::NEG_INFINITY, f64::INFINITY), |slabs, k| {
            intersection(
                Some(slabs),
                line_slab(o, d, DVec3::ZERO, DVec3::AXES[k], grown[k]),
            )
        });
        crossing = union(crossing, slabs);
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        for (su, sv) in [(-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)] {
            let mut centre = DVec3::ZERO;
            centre[u] = su * half[u];
            centre[v] = sv * half[v];
            let edge = intersection(
                line_tube(o, d, centre, DVec3::AXES[axis], radius),
                line_slab(o, d, centre, DVec3::AXES[axis], half[axis]),
            );
            crossing = union(crossing, edge);
        }
    }
    for corner in 0..8 {
        let signs = DVec3::new(
            if corner & 1 == 0 { -1.0 } else { 1.0 },
            if corner & 2 == 0 { -1.0 } else { 1.0 },
            if corner & 4 == 0 { -1.0 } else { 1.0 },
        );
        crossing = union(crossing, line_ball(o, d, signs * half, radius));
    }
    ray_answer(crossing, true)
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

/// Classifies a shape cast from references evaluated on a target grown and shrunk by `GROW`.
fn expected_cast(grown: Option<f64>, shrunk: Option<f64>, exact: Option<f64>) -> Expected {
    match (grown, shrunk) {
        (None, _) => Expected::Miss,
        (Some(outer), Some(inner)) if (outer - inner).abs() < 1e-2 => {
            Expected::Hit(exact.unwrap_or(inner))
        }
        _ => Expected::Either,
    }
}

#[test]
fn a_sphere_swept_at_a_box_finds_the_closed_form_time_of_impact_within_1e_4() {
    let mut random = Random(0xba11);
    let mut compared = 0;
    for _ in 0..3000 {
        let half = random.vec3(0.2, 1.5);
        let mut world = world();
        let target = world
            .add_body(
                BodyDesc::fixed(Shape::cuboid(half).unwrap())
                    .position(random.vec3(-5.0, 5.0))
                    .rotation(random.rotation()),
            )
            .unwrap();
        let box_pose = world.body(target).unwrap().pose();
        let radius = random.range(0.1, 1.0);
        let start = box_pose.position + random.unit_vector() * random.range(4.0, 7.0);
        let aim = box_pose.position + random.vec3(-1.5, 1.5);
        let direction = (aim - start).normalize();
        let ball = Shape::sphere(radius).unwrap();
        let hit = world
            .cast_shape(
                &ball,
                &Pose::from_position(start),
                direction,
                f32::INFINITY,
                &QueryFilter::new(),
            )
            .unwrap();
        let (o, d) = to_local(&box_pose, start, direction);
        let half64 = to_f64(half);
        let reference = |grow: f64| ball_box_time_of_impact(o, d, half64, f64::from(radius) + grow);
        match (
            expected_cast(reference(GROW), reference(-GROW), reference(0.0)),
            hit,
        ) {
            (Expected::Miss, Some(hit)) => panic!("should miss, got {hit:?}"),
            (Expected::Hit(t), None) => panic!("should hit at {t}"),
            (Expected::Hit(t), Some(hit)) => {
                let error = f64::from(hit.distance) - t;
                assert!(
                    error.abs() <= 1e-4,
                    "time of impact {} instead of {t}",
                    hit.distance
                );
                assert!(error <= 1e-5, "the ball passes the contact by {error}");
                compared += 1;
                assert_eq!(hit.body, target);
                // The point is on the box, the normal points from it to the ball's centre.
                let centre = start + hit.distance * direction;
                let (local, _) = to_local(&box_pose, hit.point, Vec3::ZERO);
                let outside = (local.abs() - half64).max_element();
                assert!(outside.abs() < 1e-3, "point {local} off the box surface");
                let towards_centre = (centre - hit.point) / radius;
                assert!(
                    hit.normal.dot(towards_centre) > 0.999,
                    "normal {}",
                    hit.normal
                );
            }
            _ => {}
        }
    }
    assert!(compared > 1500, "only {compared} clear hits");
}

#[test]
fn a_box_swept_at_a_box_finds_the_closed_form_time_of_impact_within_1e_3() {
    let mut random = Random(0xb0b0);
    let mut compared = 0;
    for _ in 0..3000 {
        let (half_a, half_b) = (random.vec3(0.1, 1.2), random.vec3(0.2, 1.5));
        let mut world = world();
        let target = world
            .add_body(
                BodyDesc::fixed(Shape::cuboid(half_b).unwrap())
                    .position(random.vec3(-5.0, 5.0))
                    .rotation(random.rotation()),
            )
            .unwrap();
        let pose_b = world.body(target).unwrap().pose();
        let pose_a = Pose::new(
            pose_b.position + random.unit_vector() * random.range(4.5, 8.0),
            random.rotation().normalize(),
        );
        let direction = (pose_b.position + random.vec3(-1.5, 1.5) - pose_a.position).normalize();
        let moving = Shape::cuboid(half_a).unwrap();
        let hit = world
            .cast_shape(
                &moving,
                &pose_a,
                direction,
                f32::INFINITY,
                &QueryFilter::new(),
            )
            .unwrap();
        let reference = |grow: f64| {
            box_box_time_of_impact(
                &pose_a,
                to_f64(half_a),
                &pose_b,
                to_f64(half_b) + grow,
                to_f64(direction),
            )
        };
        match (
            expected_cast(reference(GROW), reference(-GROW), reference(0.0)),
            hit,
        ) {
            (Expected::Miss, Some(hit)) => panic!("should miss, got {hit:?}"),
            (Expected::Hit(t), None) => panic!("should hit at {t}"),
            (Expected::Hit(t), Some(hit)) => {
                let error = f64::from(hit.distance) - t;
                assert!(
                    error.abs() <= 1e-3,
                    "time of impact {} instead of {t}",
                    hit.distance
                );
                assert!(error <= 1e-5, "the box passes the contact by {error}");
                assert!(
                    hit.normal.dot(direction) < 0.0,
                    "normal {} faces away",
                    hit.normal
                );
                let moved = Pose::new(pose_a.position + hit.distance * direction, pose_a.rotation);
                // The contact plane separates the boxes, to within a few milliradians (GJK's
                // precision at the distance the normal is measured from).
                let target = Shape::cuboid(half_b).unwrap();
                let gaps = [
                    outward_normal_gap(&target, &pose_b, hit.point, hit.normal),
                    outward_normal_gap(&moving, &moved, hit.point, -hit.normal),
                ];
                assert!(
                    gaps.iter().all(|&gap| gap <= 2.5e-3),
                    "normal {hit:?}: {gaps:?}"
                );
                compared += 1;
            }
            _ => {}
        }
    }
    assert!(compared > 1500, "only {compared} clear hits");
}

#[test]
fn every_shape_dropped_on_a_floor_lands_on_its_lowest_point() {
    let mut random = Random(0xf100);
    let mut world = world();
    let floor = world
        .add_body(
            BodyDesc::fixed(Shape::cuboid(Vec3::new(50.0, 1.0, 50.0)).unwrap())
                .position(Vec3::new(0.0, -1.0, 0.0)),
        )
        .unwrap();
    let ground = world
        .add_body(
            BodyDesc::fixed(Shape::halfspace(Vec3::Y).unwrap()).position(Vec3::new(0.0, -4.0, 0.0)),
        )
        .unwrap();
    let floor_only = [ground];
    let ground_only = [floor];
    for round in 0..300 {
        let shape = if round % 6 == 5 {
            random.compound()
        } else {
            random.convex_shape(round)
        };
        let pose = Pose::new(
            random.vec3(-5.0, 5.0) + Vec3::Y * 8.0,
            random.rotation().normalize(),
        );
        // Bounding boxes are exact for every shape kind: the box's floor is the lowest point.
        let lowest_y = shape.aabb(&pose).min.y;
        // Straight down onto the floor's top at y = 0, and through it (excluded) onto the ground.
        let down = Vec3::NEG_Y;
        let onto_floor = QueryFilter::new().exclude_bodies(&floor_only);
        let hit = world
            .cast_shape(&shape, &pose, down, 100.0, &onto_floor)
            .unwrap()
            .unwrap();
        assert_eq!(hit.body, floor);
        // GJK measures to 1e-5 of the problem's size, here the floor's 71 m half diagonal, and
        // the cast stays on the near side: it never sinks the shape into the floor.
        let error = hit.distance - lowest_y;
        assert!(
            error.abs() < 1e-5 * 71.0 && error < 1e-5,
            "{shape:?}: {error}"
        );
        assert!((hit.normal - Vec3::Y).length() < 3e-3, "{hit:?}");
        assert!(hit.point.y.abs() < 1e-3, "{hit:?}");
        let onto_ground = QueryFilter::new().exclude_bodies(&ground_only);
        let hit = world
            .cast_shape(&shape, &pose, down, 100.0, &onto_ground)
            .unwrap()
            .unwrap();
        assert_eq!((hit.body, hit.normal), (ground, Vec3::Y));
        assert!((hit.distance - lowest_y - 4.0).abs() < 1e-4);
        // Not far enough.
        assert_eq!(
            world
                .cast_shape(&shape, &pose, down, lowest_y - 0.01, &onto_floor)
                .unwrap(),
            None
        );
        // Sideways, nothing is in the way.
        assert_eq!(
            world
                .cast_shape(&shape, &pose, Vec3::X, 100.0, &onto_floor)
                .unwrap(),
            None
        );
    }
}

#[test]
fn shape_casts_starting_in_contact_halfspaces_and_the_nearest_body() {
    let mut world = world();
    let block = world
        .add_body(BodyDesc::fixed(Shape::cuboid(Vec3::splat(1.0)).unwrap()))
        .unwrap();
    let far_block = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::splat(1.0)).unwrap())
                .position(Vec3::new(10.0, 0.0, 0.0)),
        )
        .unwrap();
    let filter = QueryFilter::new();

    // Overlapping from the start: distance zero, the normal pushing the ball out of the block.
    let ball = Shape::sphere(0.5).unwrap();
    let inside = Pose::from_position(Vec3::new(0.8, 0.1, 0.0));
    let hit = world
        .cast_shape(&ball, &inside, Vec3::X, 5.0, &filter)
        .unwrap()
        .unwrap();
    assert_eq!((hit.body, hit.distance), (block, 0.0));
    assert!(hit.normal.x > 0.99, "{hit:?}");
    let deep = Shape::cuboid(Vec3::splat(0.2)).unwrap();
    let hit = world
        .cast_shape(
            &deep,
            &Pose::from_position(Vec3::new(0.0, 0.7, 0.0)),
            Vec3::X,
            5.0,
            &filter,
        )
        .unwrap()
        .unwrap();
    assert_eq!((hit.body, hit.distance), (block, 0.0));
    assert!(hit.normal.y > 0.99, "{hit:?}");

    // The nearest of two bodies in the way, then the far one once the near one is excluded.
    let start = Pose::from_position(Vec3::new(-5.0, 0.0, 0.0));
    let hit = world
        .cast_shape(&ball, &start, Vec3::X, f32::INFINITY, &filter)
        .unwrap()
        .unwrap();
    assert_eq!(hit.body, block);
    assert!(
        (hit.distance - 3.5).abs() < 1e-4
            && (hit.point - Vec3::new(-1.0, 0.0, 0.0)).length() < 1e-3
    );
    let skip = [block];
    let hit = world
        .cast_shape(
            &ball,
            &start,
            Vec3::X,
            f32::INFINITY,
            &QueryFilter::new().exclude_bodies(&skip),
        )
        .unwrap()
        .unwrap();
    assert_eq!(hit.body, far_block);
    assert!((hit.distance - 13.5).abs() < 1e-4);
    assert_eq!(
        world
            .cast_shape(
                &ball,
                &start,
                Vec3::X,
                13.0,
                &QueryFilter::new().exclude_bodies(&skip)
            )
            .unwrap(),
        None
    );

    // A halfspace swept down onto the block, and a halfspace swept at a facing one.
    let ceiling = Shape::halfspace(Vec3::NEG_Y).unwrap();
    let above = Pose::from_position(Vec3::new(0.0, 4.0, 0.0));
    let hit = world
        .cast_shape(&ceiling, &above, Vec3::NEG_Y, 10.0, &filter)
        .unwrap()
        .unwrap();
    assert_eq!(hit.body, block);
    assert!((hit.distance - 3.0).abs() < 1e-5 && hit.normal == Vec3::Y && hit.point.y == 1.0);
    let floor = world
        .add_body(
            BodyDesc::fixed(Shape::halfspace(Vec3::Y).unwrap())
                .position(Vec3::new(0.0, -20.0, 0.0)),
        )
        .unwrap();
    let only_floor = QueryFilter::new()
        .only_type(BodyType::Static)
        .exclude_bodies(&skip);
    let hit = world
        .cast_shape(&ceiling, &above, Vec3::NEG_Y, 100.0, &only_floor)
        .unwrap()
        .unwrap();
    assert_eq!((hit.body, hit.normal), (floor, Vec3::Y));
    assert!((hit.distance - 24.0).abs() < 1e-4);
    let tilted = Shape::halfspace(Vec3::new(1.0, -1.0, 0.0)).unwrap();
    let hit = world
        .cast_shape(&tilted, &above, Vec3::Y, 100.0, &only_floor)
        .unwrap()
        .unwrap();
    assert_eq!((hit.body, hit.distance), (floor, 0.0));

    // A compound of two balls: its lower ball lands first.
    let dumbbell = Shape::compound(vec![
        CompoundChild {
            pose: Pose::from_position(Vec3::new(0.0, -1.0, 0.0)),
            shape: Shape::sphere(0.25).unwrap(),
        },
        CompoundChild {
            pose: Pose::from_position(Vec3::new(0.0, 1.0, 0.0)),
            shape: Shape::sphere(0.5).unwrap(),
        },
    ])
    .unwrap();
    let hit = world
        .cast_shape(&dumbbell, &above, Vec3::NEG_Y, 100.0, &filter)
        .unwrap()
        .unwrap();
    assert_eq!(hit.body, block);
    assert!((hit.distance - 1.75).abs() < 1e-4, "{hit:?}");
}

/// Signed distance from `point` to a shape the overlap test has a closed form for (negative
/// inside), or `None`.
fn signed_distance(shape: &Shape, pose: &Pose, point: Vec3) -> Option<f64> {
    let (local, _) = to_local(pose, point, Vec3::ZERO);
    match shape {
        Shape::Sphere(sphere) => Some(local.length() - f64::from(sphere.radius())),
        Shape::Cuboid(cuboid) => {
            let outside = local.abs() - to_f64(cuboid.half_extents());
            Some(outside.max(DVec3::ZERO).length() + outside.max_element().min(0.0))
        }
        Shape::Capsule(capsule) => {
            let height = f64::from(capsule.half_height());
            let axis_point = DVec3::new(0.0, local.y.clamp(-height, height), 0.0);
            Some((local - axis_point).length() - f64::from(capsule.radius()))
        }
        Shape::Cylinder(cylinder) => {
            let radial = local.x.hypot(local.z) - f64::from(cylinder.radius());
            let axial = local.y.abs() - f64::from(cylinder.half_height());
            Some(radial.max(0.0).hypot(axial.max(0.0)) + radial.max(axial).min(0.0))
        }
        Shape::Halfspace(halfspace) => Some(local.dot(to_f64(halfspace.normal()))),
        Shape::ConvexHull(_) | Shape::Compound(_) => None,
    }
}

/// The hull's own faces as a containment reference, with the face planes pushed out by `grow`.
fn hull_contains(shape: &Shape, pose: &Pose, point: Vec3, grow: f64) -> Option<bool> {
    let Shape::ConvexHull(hull) = shape else {
        return None;
    };
    let (local, _) = to_local(pose, point, Vec3::ZERO);
    Some(
        hull.faces()
            .iter()
            .all(|face| to_f64(face.normal).dot(local) <= f64::from(face.offset) + grow),
    )
}

/// The answer a reference gives for a yes-or-no test: sure yes, sure no, or too close to call.
fn classify(inside_shrunk: bool, inside_grown: bool) -> Option<bool> {
    match (inside_shrunk, inside_grown) {
        (true, _) => Some(true),
        (false, false) => Some(false),
        _ => None,
    }
}

fn random_scene(random: &mut Random, count: usize) -> (World, Vec<(BodyHandle, Shape, Pose)>) {
    let mut world = world();
    let mut bodies = Vec::new();
    for index in 0..count {
        let shape = match index % 7 {
            5 => random.compound(),
            6 if index % 21 == 6 => Shape::halfspace(random.unit_vector()).unwrap(),
            _ => random.convex_shape(index),
        };
        let pose = random.pose(6.0);
        let handle = world
            .add_body(
                BodyDesc::fixed(shape.clone())
                    .position(pose.position)
                    .rotation(pose.rotation),
            )
            .unwrap();
        bodies.push((handle, shape, world.body(handle).unwrap().pose()));
    }
    (world, bodies)
}

#[test]
fn point_box_and_shape_overlaps_match_closed_forms() {
    let mut random = Random(0x0e1a);
    let (world, bodies) = random_scene(&mut random, 120);
    let filter = QueryFilter::new();
    let mut found = Vec::new();
    let mut decided = 0;
    for _ in 0..3000 {
        let point = random.vec3(-8.0, 8.0);
        world
            .bodies_containing_point(point, &filter, &mut found)
            .unwrap();
        for (handle, shape, pose) in &bodies {
            let expected = match shape {
                Shape::ConvexHull(_) => classify(
                    hull_contains(shape, pose, point, -GROW).unwrap(),
                    hull_contains(shape, pose, point, GROW).unwrap(),
                ),
                Shape::Compound(compound) => {
                    let parts: Vec<_> = compound
                        .children()
                        .iter()
                        .map(|child| {
                            let child_pose = pose.mul_pose(&child.pose);
                            signed_distance(&child.shape, &child_pose, point).map_or_else(
                                || {
                                    let shrunk =
                                        hull_contains(&child.shape, &child_pose, point, -GROW);
                                    let grown =
                                        hull_contains(&child.shape, &child_pose, point, GROW);
                                    (shrunk.unwrap(), grown.unwrap())
                                },
                                |distance| (distance < -GROW, distance <= GROW),
                            )
                        })
                        .collect();
                    classify(
                        parts.iter().any(|part| part.0),
                        parts.iter().any(|part| part.1),
                    )
                }
                _ => {
                    let distance = signed_distance(shape, pose, point).unwrap();
                    classify(distance < -GROW, distance <= GROW)
                }
            };
            if let Some(inside) = expected {
                decided += 1;
                assert_eq!(found.contains(handle), inside, "{point} in {shape:?}");
            }
        }
    }
    assert!(decided > 3000 * 100);

    for _ in 0..500 {
        let aabb = Aabb::from_center_half_extents(random.vec3(-8.0, 8.0), random.vec3(0.0, 2.0));
        world
            .bodies_overlapping_aabb(&aabb, &filter, &mut found)
            .unwrap();
        let expected: Vec<_> = world
            .bodies()
            .filter(|(_, body)| body.aabb().overlaps(&aabb))
            .map(|(handle, _)| handle)
            .collect();
        assert_eq!(found, expected);
    }

    // A ball overlaps a body when its centre is within its radius of the body.
    let mut overlapping = 0;
    for _ in 0..2000 {
        let radius = random.range(0.05, 1.5);
        let centre = random.vec3(-8.0, 8.0);
        let ball = Shape::sphere(radius).unwrap();
        world
            .bodies_overlapping_shape(&ball, &Pose::from_position(centre), &filter, &mut found)
            .unwrap();
        overlapping += found.len();
        for (handle, shape, pose) in &bodies {
            let Some(distance) = signed_distance(shape, pose, centre) else {
                continue;
            };
            let gap = distance - f64::from(radius);
            if let Some(overlaps) = classify(gap < -GROW, gap <= GROW) {
                assert_eq!(
                    found.contains(handle),
                    overlaps,
                    "ball {centre} r {radius} vs {shape:?}"
                );
            }
        }
    }
    assert!(overlapping > 1000, "only {overlapping} overlaps");
}

#[test]
fn boxes_overlapping_boxes_match_the_separating_axis_test() {
    let mut random = Random(0x5a7);
    let mut world = world();
    let mut boxes = Vec::new();
    for _ in 0..150 {
        let half = random.vec3(0.1, 1.2);
        let handle = world
            .add_body(
                BodyDesc::dynamic(Shape::cuboid(half).unwrap())
                    .position(random.vec3(-6.0, 6.0))
                    .rotation(random.rotation()),
            )
            .unwrap();
        boxes.push((handle, half, world.body(handle).unwrap().pose()));
    }
    let mut found = Vec::new();
    let mut overlapping = 0;
    for _ in 0..1000 {
        let half = random.vec3(0.1, 1.5);
        let pose = Pose::new(random.vec3(-6.0, 6.0), random.rotation());
        let query = Shape::cuboid(half).unwrap();
        world
            .bodies_overlapping_shape(&query, &pose, &QueryFilter::new(), &mut found)
            .unwrap();
        overlapping += found.len();
        for &(handle, body_half, body_pose) in &boxes {
            // Travel zero along any direction: the boxes overlap where every axis says so.
            let reference = |grow: f64| {
                box_box_time_of_impact(
                    &pose,
                    to_f64(half),
                    &body_pose,
                    to_f64(body_half) + grow,
                    DVec3::X,
                )
                .is_some_and(|t| t == 0.0)
            };
            if let Some(overlaps) = classify(reference(-GROW), reference(GROW)) {
                assert_eq!(found.contains(&handle), overlaps);
            }
        }
    }
    assert!(overlapping > 500, "only {overlapping} overlaps");
}

#[test]
fn filters_pick_bodies_by_handle_type_and_predicate() {
    let mut world = world();
    let cube = || Shape::cuboid(Vec3::splat(0.5)).unwrap();
    let at = |x: f32| Vec3::new(x, 0.0, 0.0);
    let fixed = world
        .add_body(BodyDesc::fixed(cube()).position(at(2.0)))
        .unwrap();
    let moving = world
        .add_body(BodyDesc::dynamic(cube()).position(at(4.0)))
        .unwrap();
    let pushed = world
        .add_body(BodyDesc::kinematic(cube()).position(at(6.0)))
        .unwrap();
    let ray = Ray::new(Vec3::ZERO, Vec3::X);
    let first = |filter: &QueryFilter| world.cast_ray(&ray, filter).unwrap().map(|hit| hit.body);
    assert_eq!(first(&QueryFilter::new()), Some(fixed));
    assert_eq!(
        first(&QueryFilter::new().exclude_bodies(&[fixed])),
        Some(moving)
    );
    assert_eq!(
        first(&QueryFilter::new().exclude_bodies(&[fixed, moving])),
        Some(pushed)
    );
    assert_eq!(
        first(&QueryFilter::new().exclude_bodies(&[fixed, moving, pushed])),
        None
    );
    assert_eq!(
        first(&QueryFilter::new().exclude_type(BodyType::Static)),
        Some(moving)
    );
    assert_eq!(
        first(&QueryFilter::new().only_type(BodyType::Kinematic)),
        Some(pushed)
    );
    assert_eq!(
        first(&QueryFilter::new().only_type(BodyType::Static)),
        Some(fixed)
    );
    let heavy = |_: BodyHandle, body: &RigidBody| body.mass() > 0.0;
    assert_eq!(first(&QueryFilter::new().predicate(&heavy)), Some(moving));
    let last = |handle: BodyHandle, _: &RigidBody| handle == pushed;
    assert_eq!(first(&QueryFilter::new().predicate(&last)), Some(pushed));

    let mut hits = Vec::new();
    world
        .cast_ray_all(
            &ray,
            &QueryFilter::new().exclude_type(BodyType::Dynamic),
            &mut hits,
        )
        .unwrap();
    assert_eq!(
        hits.iter().map(|hit| hit.body).collect::<Vec<_>>(),
        [fixed, pushed]
    );
    assert!(!world
        .cast_ray_any(
            &ray,
            &QueryFilter::new().exclude_bodies(&[fixed, moving, pushed])
        )
        .unwrap());
    let mut found = Vec::new();
    let everything = Aabb::new(Vec3::splat(-10.0), Vec3::splat(10.0));
    world
        .bodies_overlapping_aabb(
            &everything,
            &QueryFilter::new().predicate(&heavy),
            &mut found,
        )
        .unwrap();
    assert_eq!(found, [moving]);
    world
        .bodies_containing_point(
            at(6.0),
            &QueryFilter::new().exclude_type(BodyType::Kinematic),
            &mut found,
        )
        .unwrap();
    assert!(found.is_empty());
    let sweep = world
        .cast_shape(
            &cube(),
            &Pose::IDENTITY,
            Vec3::X,
            10.0,
            &QueryFilter::new().only_type(BodyType::Dynamic),
        )
        .unwrap()
        .unwrap();
    assert_eq!(sweep.body, moving);
}

#[test]
fn equally_near_hits_go_to_the_smaller_handle_and_sleeping_bodies_count() {
    let mut world = world();
    let cube = || Shape::cuboid(Vec3::splat(0.5)).unwrap();
    let handles: Vec<_> = (0..4)
        .map(|_| {
            world
                .add_body(BodyDesc::fixed(cube()).position(Vec3::new(3.0, 0.0, 0.0)))
                .unwrap()
        })
        .collect();
    world.remove_body(handles[0]).unwrap();
    let reused = world
        .add_body(BodyDesc::fixed(cube()).position(Vec3::new(3.0, 0.0, 0.0)))
        .unwrap();
    let ray = Ray::new(Vec3::ZERO, Vec3::X);
    let hit = world.cast_ray(&ray, &QueryFilter::new()).unwrap().unwrap();
    let smallest = *[handles[1], handles[2], handles[3], reused]
        .iter()
        .min()
        .unwrap();
    assert_eq!(hit.body, smallest);
    let mut hits = Vec::new();
    world
        .cast_ray_all(&ray, &QueryFilter::new(), &mut hits)
        .unwrap();
    let mut expected = vec![handles[1], handles[2], handles[3], reused];
    expected.sort();
    assert_eq!(
        hits.iter().map(|hit| hit.body).collect::<Vec<_>>(),
        expected
    );
    let sweep = world
        .cast_shape(
            &Shape::sphere(0.25).unwrap(),
            &Pose::IDENTITY,
            Vec3::X,
            10.0,
            &QueryFilter::new(),
        )
        .unwrap()
        .unwrap();
    assert_eq!(sweep.body, smallest);

    // A box resting on the ground falls asleep and is still found.
    let mut world = self::world();
    world
        .add_body(
            BodyDesc::fixed(Shape::cuboid(Vec3::new(10.0, 0.5, 10.0)).unwrap())
                .position(Vec3::new(0.0, -0.5, 0.0)),
        )
        .unwrap();
    let sleeper = world
        .add_body(BodyDesc::dynamic(cube()).position(Vec3::new(0.0, 0.5, 0.0)))
        .unwrap();
    for _ in 0..120 {
        world.step(1.0 / 60.0).unwrap();
    }
    assert!(world.body(sleeper).unwrap().is_sleeping());
    let down = Ray::new(Vec3::new(0.0, 5.0, 0.0), Vec3::NEG_Y);
    let hit = world.cast_ray(&down, &QueryFilter::new()).unwrap().unwrap();
    assert_eq!(hit.body, sleeper);
    assert!((hit.distance - 4.0).abs() < 0.01);
    let mut found = Vec::new();
    world
        .bodies_containing_point(Vec3::new(0.0, 0.5, 0.0), &QueryFilter::new(), &mut found)
        .unwrap();
    assert_eq!(found, [sleeper]);
}

#[test]
fn bad_inputs_are_errors_naming_the_field() {
    let mut world = world();
    world
        .add_body(BodyDesc::fixed(Shape::sphere(1.0).unwrap()))
        .unwrap();
    let filter = QueryFilter::new();
    let ray = Ray::new(Vec3::new(0.0, 5.0, 0.0), Vec3::NEG_Y);
    let error = |ray: Ray| {
        let error = world.cast_ray(&ray, &filter).unwrap_err();
        assert_eq!(world.cast_ray_any(&ray, &filter).unwrap_err(), error);
        let mut hits = vec![RayHit {
            body: world.bodies().next().unwrap().0,
            point: Vec3::ZERO,
            normal: Vec3::X,
            distance: 0.0,
        }];
        assert_eq!(
            world.cast_ray_all(&ray, &filter, &mut hits).unwrap_err(),
            error
        );
        assert!(hits.is_empty());
        (error.field, error.kind)
    };
    let nan = Vec3::new(f32::NAN, 0.0, 0.0);
    assert_eq!(
        error(Ray { origin: nan, ..ray }),
        ("origin".into(), ErrorKind::NotFinite)
    );
    assert_eq!(
        error(Ray {
            direction: Vec3::ZERO,
            ..ray
        }),
        ("direction".into(), ErrorKind::ZeroVector)
    );
    assert_eq!(
        error(Ray {
            direction: Vec3::splat(1e-30),
            ..ray
        }),
        ("direction".into(), ErrorKind::ZeroVector)
    );
    assert_eq!(
        error(Ray {
            direction: Vec3::INFINITY,
            ..ray
        }),
        ("direction".into(), ErrorKind::NotFinite)
    );
    assert_eq!(
        error(ray.max_distance(-1.0)),
        ("max_distance".into(), ErrorKind::Negative(-1.0))
    );
    assert_eq!(
        error(ray.max_distance(f32::NAN)),
        ("max_distance".into(), ErrorKind::NotFinite)
    );
    assert!(world
        .cast_ray(&ray.max_distance(0.0), &filter)
        .unwrap()
        .is_none());
    assert!(world
        .cast_ray(
            &Ray {
                direction: Vec3::NEG_Y * 1e-20,
                ..ray
            },
            &filter
        )
        .unwrap()
        .is_some());

    let ball = Shape::sphere(0.5).unwrap();
    let cast_error = |pose: Pose, direction: Vec3, max: f32| {
        let error = world
            .cast_shape(&ball, &pose, direction, max, &filter)
            .unwrap_err();
        (error.field, error.kind)
    };
    let above = Pose::from_position(Vec3::new(0.0, 5.0, 0.0));
    assert_eq!(
        cast_error(
            Pose {
                position: nan,
                ..above
            },
            Vec3::Y,
            1.0
        )
        .0,
        "pose.position"
    );
    let zero_rotation = Pose {
        rotation: Quat::from_xyzw(0.0, 0.0, 0.0, 0.0),
        ..above
    };
    assert_eq!(
        cast_error(zero_rotation, Vec3::Y, 1.0),
        ("pose.rotation".into(), ErrorKind::ZeroQuaternion)
    );
    let nan_rotation = Pose {
        rotation: Quat::from_xyzw(f32::NAN, 0.0, 0.0, 1.0),
        ..above
    };
    assert_eq!(
        cast_error(nan_rotation, Vec3::Y, 1.0),
        ("pose.rotation".into(), ErrorKind::NotFinite)
    );
    assert_eq!(
        cast_error(above, Vec3::ZERO, 1.0),
        ("direction".into(), ErrorKind::ZeroVector)
    );
    assert_eq!(
        cast_error(above, Vec3::Y, -2.0),
        ("max_distance".into(), ErrorKind::Negative(-2.0))
    );
    // An unnormalised rotation is normalised, an unnormalised direction too.
    let scaled = Pose {
        rotation: Quat::from_xyzw(0.0, 0.0, 0.0, 3.0),
        ..above
    };
    let hit = world
        .cast_shape(&ball, &scaled, Vec3::NEG_Y * 7.0, f32::INFINITY, &filter)
        .unwrap()
        .unwrap();
    assert!((hit.distance - 3.5).abs() < 1e-4);

    let mut found = vec![world.bodies().next().unwrap().0];
    let point_error = world
        .bodies_containing_point(nan, &filter, &mut found)
        .unwrap_err();
    assert_eq!((point_error.field.as_str(), found.len()), ("point", 0));
    let inverted = Aabb::new(Vec3::new(0.0, 2.0, 0.0), Vec3::new(1.0, 1.0, 1.0));
    let aabb_error = world
        .bodies_overlapping_aabb(&inverted, &filter, &mut found)
        .unwrap_err();
    assert_eq!(aabb_error.field, "aabb.min[1]");
    assert!(
        matches!(aabb_error.kind, ErrorKind::OutOfRange { value, max, .. } if value == 2.0 && max == 1.0)
    );
    let open = Aabb::new(Vec3::ZERO, Vec3::new(f32::INFINITY, 1.0, 1.0));
    assert_eq!(
        world
            .bodies_overlapping_aabb(&open, &filter, &mut found)
            .unwrap_err()
            .field,
        "aabb.max[0]"
    );
    let shape_error = world
        .bodies_overlapping_shape(&ball, &zero_rotation, &filter, &mut found)
        .unwrap_err();
    assert_eq!(shape_error.field, "pose.rotation");
}
