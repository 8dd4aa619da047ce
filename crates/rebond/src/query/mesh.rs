//! Queries against triangle meshes and heightfields: rays against their triangles (through the
//! mesh's hierarchy or along the heightfield's cells), overlaps and shape casts triangle by
//! triangle near the other shape.
//!
//! A mesh is a surface: a ray hits the first triangle it crosses, from either side, and nothing
//! is inside it. A heightfield is solid below its surface: a solid ray starting below it hits at
//! distance zero, and a shape below it overlaps it.

use super::ray::ShapeRayHit;
use super::{HitPart, Ray};
use crate::collision::triangle_contact::collide_triangle;
use crate::math::{Aabb, Pose, Vec3};
use crate::shape::{Shape, Triangle};

/// Where the segment `origin + t·direction`, `t ∈ [0, reach]`, crosses `triangle` (both sides),
/// as `t` and the triangle's unit normal facing the segment's start (Möller–Trumbore).
fn cross_triangle(
    triangle: &Triangle,
    origin: Vec3,
    direction: Vec3,
    reach: f32,
) -> Option<(f32, Vec3)> {
    let [a, b, c] = triangle.vertices;
    let (ab, ac) = (b - a, c - a);
    let p = direction.cross(ac);
    let determinant = ab.dot(p);
    if determinant == 0.0 {
        return None;
    }
    let inverse = 1.0 / determinant;
    let to_origin = origin - a;
    let u = to_origin.dot(p) * inverse;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = to_origin.cross(ab);
    let v = direction.dot(q) * inverse;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = ac.dot(q) * inverse;
    if !(0.0..=reach).contains(&t) {
        return None;
    }
    let normal = triangle.normal()?;
    let facing = if normal.dot(direction) > 0.0 {
        -normal
    } else {
        normal
    };
    Some((t, facing))
}

/// The part `[enter, leave]` of `t ∈ [0, reach]` on which `origin + t·direction` lies in `bounds`
/// (slab test), or `None`.
fn segment_in_box(bounds: &Aabb, origin: Vec3, direction: Vec3, reach: f32) -> Option<(f32, f32)> {
    let (mut enter, mut leave) = (0.0f32, reach);
    for axis in 0..3 {
        let (o, d) = (origin[axis], direction[axis]);
        if d == 0.0 {
            if o < bounds.min[axis] || o > bounds.max[axis] {
                return None;
            }
            continue;
        }
        let (t0, t1) = ((bounds.min[axis] - o) / d, (bounds.max[axis] - o) / d);
        enter = enter.max(t0.min(t1));
        leave = leave.min(t0.max(t1));
    }
    (enter <= leave).then_some((enter, leave))
}

/// The first point where `ray` (validated: unit direction) meets a mesh or heightfield `shape`
/// at `pose`, within its maximum distance.
pub(crate) fn cast_ray_at_mesh(shape: &Shape, pose: &Pose, ray: &Ray) -> Option<ShapeRayHit> {
    let origin = pose.inverse_transform_point(ray.origin);
    let direction = pose.inverse_transform_vector(ray.direction);
    let mut best: Option<(f32, Vec3, u32)> = None;
    let offer = |index: u32, best: &mut Option<(f32, Vec3, u32)>| {
        let reach = best.map_or(ray.max_distance, |(t, _, _)| t);
        let crossing = shape
            .triangle(index)
            .and_then(|t| cross_triangle(&t, origin, direction, reach));
        if let Some((t, normal)) = crossing {
            if best.is_none_or(|(best_t, _, _)| t < best_t) {
                *best = Some((t, normal, index));
            }
        }
    };
    match shape {
        Shape::TriMesh(mesh) => {
            let walk_reach = std::cell::Cell::new(ray.max_distance);
            mesh.triangles_where(
                |bounds| segment_in_box(bounds, origin, direction, walk_reach.get()).is_some(),
                |index| {
                    offer(index, &mut best);
                    if let Some((t, _, _)) = best {
                        walk_reach.set(t);
                    }
                },
            );
        }
        Shape::HeightField(heightfield) => {
            if ray.solid && heightfield.is_below(origin) {
                return Some(ShapeRayHit {
                    distance: 0.0,
                    normal: -ray.direction,
                    part: HitPart::default(),
                });
            }
            let (enter, leave) = segment_in_box(
                &heightfield.local_bounds(),
                origin,
                direction,
                ray.max_distance,
            )?;
            let (from, to) = (origin + direction * enter, origin + direction * leave);
            let span = Aabb::new(from.min(to), from.max(to));
            shape.triangles_in(&span, |index| offer(index, &mut best));
        }
        _ => return None,
    }
    best.map(|(distance, normal, triangle)| ShapeRayHit {
        distance,
        normal: pose.transform_vector(normal),
        part: HitPart {
            collider: 0,
            triangle: Some(triangle),
        },
    })
}

/// Whether the convex `part` at `part_pose` touches or overlaps a mesh or heightfield `shape` at
/// `pose`: some triangle's contact with it has a point at zero or negative separation.
pub(crate) fn part_overlaps_mesh(
    shape: &Shape,
    pose: &Pose,
    part: &Shape,
    part_pose: &Pose,
) -> bool {
    let one_sided = matches!(shape, Shape::HeightField(_));
    let bounds = part.aabb(&pose.inverse().mul_pose(part_pose));
    let mut overlaps = false;
    let mut test = |triangle: Option<Triangle>| {
        let Some(local) = triangle.filter(|_| !overlaps) else {
            return;
        };
        let triangle = Triangle {
            vertices: local.vertices.map(|vertex| pose.transform_point(vertex)),
            edge_flags: local.edge_flags,
        };
        overlaps = collide_triangle(&triangle, one_sided, part, part_pose, 0.0)
            .is_some_and(|manifold| manifold.deepest_separation() <= 0.0);
    };
    shape.triangles_in(&bounds, |index| test(shape.triangle(index)));
    overlaps
}
