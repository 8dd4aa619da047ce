//! Ray against one shape, in closed form for every kind.
//!
//! A convex shape meets the line `o + t·d` on one interval `[enter, leave]` of `t`
//! (`shape/line.rs`). The ray's answer follows from the interval: entering ahead (`enter ≥ 0`)
//! it hits at `enter`; starting inside (`enter < 0 ≤ leave`) it hits at zero if solid, at
//! `leave` if hollow.

use super::mesh::cast_ray_at_mesh;
use super::{convex_parts, HitPart, Ray};
use crate::math::{Pose, Vec3};
use crate::shape::line::line_crossing;
use crate::shape::Shape;

/// Where a ray meets a shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ShapeRayHit {
    /// Distance along the ray, metres.
    pub distance: f32,
    /// Unit world normal facing the ray.
    pub normal: Vec3,
    /// The collider and triangle hit.
    pub part: HitPart,
}

/// The first point where `ray` (validated: unit direction) meets `shape` placed at `pose`, within
/// the ray's maximum distance. A compound is hit at the nearest of its children's hits for which
/// `sees(child)` holds (the first child among equals), each child being solid or hollow as the
/// ray says; a mesh or heightfield at its first triangle (see `query::mesh`).
pub(crate) fn cast_ray_at_shape(
    shape: &Shape,
    pose: &Pose,
    ray: &Ray,
    sees: impl Fn(u32) -> bool,
) -> Option<ShapeRayHit> {
    if shape.is_triangulated() {
        return cast_ray_at_mesh(shape, pose, ray);
    }
    convex_parts(shape, *pose)
        .filter(|&(collider, _, _)| sees(collider))
        .filter_map(|(collider, part, part_pose)| {
            cast_ray_at_convex(part, &part_pose, ray).map(|hit| ShapeRayHit {
                part: HitPart {
                    collider,
                    triangle: None,
                },
                ..hit
            })
        })
        .reduce(|best, hit| {
            if hit.distance < best.distance {
                hit
            } else {
                best
            }
        })
}

/// One convex part: its crossing with the ray's line, in its local frame, and the rule of the
/// module documentation.
fn cast_ray_at_convex(shape: &Shape, pose: &Pose, ray: &Ray) -> Option<ShapeRayHit> {
    let origin = pose.inverse_transform_point(ray.origin);
    let direction = pose.inverse_transform_vector(ray.direction);
    let crossing = line_crossing(shape, origin, direction)?;
    let to_world = |local_normal: Vec3| {
        pose.transform_vector(local_normal)
            .normalize_or(-ray.direction)
    };
    let (distance, normal) = if crossing.enter >= 0.0 {
        (crossing.enter, to_world(crossing.enter_normal))
    } else if crossing.leave < 0.0 {
        return None;
    } else if ray.solid {
        (0.0, -ray.direction)
    } else if crossing.leave.is_finite() {
        (crossing.leave, to_world(-crossing.leave_normal))
    } else {
        return None;
    };
    (distance.is_finite() && distance <= ray.max_distance).then_some(ShapeRayHit {
        distance,
        normal,
        part: HitPart::default(),
    })
}
