//! A point projected onto one shape: the nearest point of its surface, with the signed distance
//! (negative inside) and the outward normal there.
//!
//! Every convex kind has a closed form in its own frame: outside, the point clamped onto the
//! shape; inside, the nearest face (a box's, a hull's, a cylinder's side or cap) or, for the
//! round shapes, the radial direction. Only a hull seen from outside needs GJK (a point against
//! a polytope: exact after a few support points, within `gjk::TOLERANCE` of the size). Meshes
//! and heightfields take their nearest triangle ([`near_triangles`]). Cylinders are projected
//! onto their sharp surface, as rays and point tests see them.

use std::cell::Cell;

use super::HitPart;
use crate::collision::{gjk, LocalCore, SupportMap};
use crate::math::{Aabb, Pose, Vec3};
use crate::shape::{Shape, Triangle};

/// The nearest surface point of a shape to a query point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SurfacePoint {
    /// The surface point, world, metres.
    pub point: Vec3,
    /// Unit outward normal of the surface there, world; on a mesh, the triangle's side facing
    /// the query point.
    pub normal: Vec3,
    /// Signed distance of the query point from the surface, metres: negative inside.
    pub distance: f32,
    /// Whether the query point lies in the shape (inside or on its surface).
    pub inside: bool,
    /// The collider and triangle the surface point is on.
    pub part: HitPart,
}

/// A single point as a support map, for GJK.
struct Point(Vec3);

impl SupportMap for Point {
    fn support(&self, _direction: Vec3) -> Vec3 {
        self.0
    }
}

/// The projection of `point` (world) onto `shape` at `pose`. A compound answers with its child of
/// the smallest signed distance for which `sees(child)` holds (the first among equals), the usual
/// signed distance of a union; a mesh or heightfield with its nearest triangle, or `None` when no
/// triangle lies within `reach` metres (zero or more).
pub(crate) fn project_on_shape(
    shape: &Shape,
    pose: &Pose,
    point: Vec3,
    reach: f32,
    sees: impl Fn(u32) -> bool,
) -> Option<SurfacePoint> {
    if shape.is_triangulated() {
        return project_on_mesh(shape, pose, point, reach);
    }
    super::convex_parts(shape, *pose)
        .filter(|&(collider, _, _)| sees(collider))
        .map(|(collider, part, part_pose)| SurfacePoint {
            part: HitPart {
                collider,
                triangle: None,
            },
            ..project_on_convex(part, &part_pose, point)
        })
        .reduce(|best, found| {
            if found.distance < best.distance {
                found
            } else {
                best
            }
        })
}

/// One convex part (not a compound), in closed form in its frame.
pub(crate) fn project_on_convex(shape: &Shape, pose: &Pose, point: Vec3) -> SurfacePoint {
    let local = pose.inverse_transform_point(point);
    let (surface, normal, distance) = match shape {
        Shape::Sphere(sphere) => round(local, Vec3::ZERO, sphere.radius()),
        Shape::Capsule(capsule) => {
            let height = capsule.half_height();
            let axis_point = Vec3::new(0.0, local.y.clamp(-height, height), 0.0);
            round(local, axis_point, capsule.radius())
        }
        Shape::Cuboid(cuboid) => project_on_box(local, cuboid.half_extents()),
        Shape::Cylinder(cylinder) => {
            project_on_cylinder(local, cylinder.radius(), cylinder.half_height())
        }
        Shape::ConvexHull(hull) => {
            let (height, normal) = hull
                .faces()
                .iter()
                .map(|face| (face.normal.dot(local) - face.offset, face.normal))
                .fold((f32::NEG_INFINITY, Vec3::Y), |best, face| {
                    if face.0 > best.0 {
                        face
                    } else {
                        best
                    }
                });
            if height <= 0.0 {
                (local - height * normal, normal, height)
            } else {
                let found = gjk::distance_from_direction(&Point(local), &LocalCore(shape), -local);
                let normal = (local - found.point_b).try_normalize().unwrap_or(normal);
                (found.point_b, normal, found.distance)
            }
        }
        Shape::Halfspace(halfspace) => {
            let normal = halfspace.normal();
            let height = normal.dot(local);
            (local - height * normal, normal, height)
        }
        // Not convex parts: answered by `project_on_shape`.
        Shape::Compound(_) | Shape::TriMesh(_) | Shape::HeightField(_) => {
            (local, Vec3::Y, f32::INFINITY)
        }
    };
    SurfacePoint {
        point: pose.transform_point(surface),
        normal: pose.transform_vector(normal),
        distance,
        inside: distance <= 0.0,
        part: HitPart::default(),
    }
}

/// A ball of `radius` around `centre` (a sphere's centre, the nearest point of a capsule's
/// segment): along the radial direction, or local X for the centre itself.
fn round(local: Vec3, centre: Vec3, radius: f32) -> (Vec3, Vec3, f32) {
    let offset = local - centre;
    let length = offset.length();
    let normal = offset.normalize_or(Vec3::X);
    (centre + radius * normal, normal, length - radius)
}

/// A box of `half` extents: outside, the point clamped onto it; inside, the nearest face (the
/// first axis among equally near ones, the positive side at the centre plane).
fn project_on_box(local: Vec3, half: Vec3) -> (Vec3, Vec3, f32) {
    let clamped = local.clamp(-half, half);
    let outside = local - clamped;
    if let Some(normal) = outside.try_normalize() {
        return (clamped, normal, outside.length());
    }
    let heights = local.abs() - half;
    let axis = if heights.x >= heights.y && heights.x >= heights.z {
        0
    } else if heights.y >= heights.z {
        1
    } else {
        2
    };
    let mut normal = Vec3::ZERO;
    normal[axis] = if local[axis] < 0.0 { -1.0 } else { 1.0 };
    let mut surface = local;
    surface[axis] = normal[axis] * half[axis];
    (surface, normal, heights[axis])
}

/// A sharp cylinder along local Y: outside, the point clamped radially and axially; inside, the
/// nearer of the side and the cap.
fn project_on_cylinder(local: Vec3, radius: f32, half_height: f32) -> (Vec3, Vec3, f32) {
    let radial = Vec3::new(local.x, 0.0, local.z);
    let radial_length = radial.length();
    let across = radial.normalize_or(Vec3::X);
    let side = radial_length - radius;
    let cap = local.y.abs() - half_height;
    let up = if local.y < 0.0 { Vec3::NEG_Y } else { Vec3::Y };
    if side > 0.0 || cap > 0.0 {
        let clamped =
            across * radial_length.min(radius) + Vec3::Y * local.y.clamp(-half_height, half_height);
        let offset = local - clamped;
        let normal = offset
            .try_normalize()
            .unwrap_or(if side > 0.0 { across } else { up });
        (clamped, normal, offset.length())
    } else if side >= cap {
        (across * radius + Vec3::Y * local.y, across, side)
    } else {
        (Vec3::new(local.x, up.y * half_height, local.z), up, cap)
    }
}

/// A mesh or heightfield: its nearest triangle within `reach`. A point below a heightfield is
/// inside (negative distance) and always answered, from the triangle nearest it.
fn project_on_mesh(shape: &Shape, pose: &Pose, point: Vec3, reach: f32) -> Option<SurfacePoint> {
    let local = pose.inverse_transform_point(point);
    let inside = matches!(shape, Shape::HeightField(heightfield) if heightfield.is_below(local));
    let reach = if inside { f32::INFINITY } else { reach };
    let mut best: Option<(f32, u32, Vec3, Triangle)> = None;
    near_triangles(shape, &Aabb::new(local, local), reach, |index, triangle| {
        let (surface, _) = triangle.closest_point(local);
        let distance = (local - surface).length();
        if best.is_none_or(|(d, i, _, _)| (distance, index) < (d, i)) {
            best = Some((distance, index, surface, *triangle));
        }
        distance
    });
    let (distance, index, surface, triangle) = best.filter(|&(d, ..)| d <= reach)?;
    let front = triangle.normal().unwrap_or(Vec3::Y);
    let facing = if front.dot(local - surface) < 0.0 {
        -front
    } else {
        front
    };
    // Outward: toward the query point outside, away from it inside (a heightfield's solid).
    let away = (local - surface) / distance;
    let normal = match (inside, away.is_finite()) {
        (false, true) => away,
        (true, true) => -away,
        (false, false) => facing,
        (true, false) => front,
    };
    Some(SurfacePoint {
        point: pose.transform_point(surface),
        normal: pose.transform_vector(normal),
        distance: if inside { -distance } else { distance },
        inside,
        part: HitPart {
            collider: 0,
            triangle: Some(index),
        },
    })
}

/// Euclidean distance between two boxes, metres: zero when they overlap.
pub(crate) fn box_gap(a: &Aabb, b: &Aabb) -> f32 {
    (a.min - b.max).max(b.min - a.max).max(Vec3::ZERO).length()
}

/// Calls `measure(index, triangle)` (the triangle in the shape's frame) for the triangles of a
/// mesh or heightfield that may lie within `reach` metres of `bounds` (shape frame; infinity
/// for no limit). `measure` returns the distance it found, and each triangle after it is
/// measured only if its box lies within the least distance so far: a mesh prunes its hierarchy
/// so, a heightfield first measures the cell under the centre of `bounds` (clamped onto the
/// grid) when `reach` is infinite, then the cells within the least distance of `bounds`.
pub(crate) fn near_triangles(
    shape: &Shape,
    bounds: &Aabb,
    reach: f32,
    mut measure: impl FnMut(u32, &Triangle) -> f32,
) {
    let least = Cell::new(reach);
    let mut offer = |index: u32| {
        let Some(triangle) = shape.triangle(index) else {
            return;
        };
        let [a, b, c] = triangle.vertices;
        let triangle_box = Aabb::new(a.min(b).min(c), a.max(b).max(c));
        if box_gap(&triangle_box, bounds) <= least.get() {
            least.set(least.get().min(measure(index, &triangle)));
        }
    };
    match shape {
        Shape::TriMesh(mesh) => {
            mesh.triangles_where(|node| box_gap(node, bounds) <= least.get(), offer);
        }
        Shape::HeightField(heightfield) => {
            let grid = heightfield.local_bounds();
            if !least.get().is_finite() {
                let centre = bounds.center().clamp(grid.min, grid.max);
                let column = Aabb::new(Vec3::new(centre.x, grid.min.y, centre.z), centre);
                heightfield.triangles_in(&column, &mut offer);
            }
            let search = if least.get().is_finite() {
                Aabb::new(bounds.min - least.get(), bounds.max + least.get())
            } else {
                grid
            };
            heightfield.triangles_in(&search, offer);
        }
        _ => {}
    }
}
