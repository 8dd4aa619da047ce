//! Contacts of any convex shape B resting on or sinking into a halfspace A: the points of B's
//! surface deepest below the plane, measured along the plane's normal.

use std::f32::consts::TAU;

use super::manifold::{ContactPoint, Manifold};
use super::reduction::reduce_contacts;
use crate::math::{Pose, Vec3};
use crate::shape::{Halfspace, Shape};

/// Most candidate points read from one shape; a hull with more vertices within the margin keeps
/// the first ones found (a flat face of a hull rarely has more).
const MAX_CANDIDATES: usize = 64;

/// Rim points sampled on each cylinder cap, at fixed angles in the cylinder's frame (a square
/// inscribed in the rim), so a cylinder standing on its cap keeps the same four point ids from step
/// to step. With more samples, more than four would touch and the reduction to four, which starts
/// from the deepest point, would pick a different subset whenever the cylinder tilts a little.
const CYLINDER_RIM_SAMPLES: usize = 4;

/// The rim sample nearest a cap's deepest rim point moves onto that point when it lies deeper by
/// more than this, metres: a cylinder standing flat keeps its square of samples, a tilted or
/// lying one reaches its deepest spot, under the id of the sample it replaces.
const DEEPEST_SNAP_DISTANCE: f32 = 1.0e-3;

/// Candidate points of B below (or within `margin` above) the plane.
struct Candidates {
    normal: Vec3,
    plane_point: Vec3,
    margin: f32,
    points: [ContactPoint; MAX_CANDIDATES],
    len: usize,
}

impl Candidates {
    /// Adds the surface point `point` of B if it lies within the margin of the plane; the contact
    /// point sits midway between it and the plane.
    fn offer(&mut self, point: Vec3, id: u32) {
        let separation = self.normal.dot(point - self.plane_point);
        if separation <= self.margin && self.len < MAX_CANDIDATES {
            self.points[self.len] = ContactPoint {
                position: point - self.normal * (0.5 * separation),
                separation,
                id,
            };
            self.len += 1;
        }
    }
}

/// The contact of halfspace A (at `pose_a`) with the convex shape B (at `pose_b`; never a
/// compound or a halfspace), with the normal from A toward B: the plane's outward normal.
/// Points: a sphere's lowest point; a capsule's two lowest segment ends; a box's or hull's
/// vertices; a cylinder's four fixed samples on each rounded rim (on its core's rim, lowered by
/// the convex radius), the one nearest a cap's deepest rim point moved there when it lies deeper
/// by more than `DEEPEST_SNAP_DISTANCE` (so a cylinder keeps the same ids whether it stands flat,
/// wobbles or lies on its side). More than four are reduced to four by depth and spread.
pub fn collide_halfspace(
    halfspace: &Halfspace,
    pose_a: &Pose,
    shape: &Shape,
    pose_b: &Pose,
    margin: f32,
) -> Option<Manifold> {
    let normal = pose_a.transform_vector(halfspace.normal());
    let mut candidates = Candidates {
        normal,
        plane_point: pose_a.position,
        margin,
        points: [ContactPoint::default(); MAX_CANDIDATES],
        len: 0,
    };
    let down = -normal * shape.core_radius();
    match shape {
        Shape::Sphere(_) => candidates.offer(pose_b.position + down, 0),
        Shape::Capsule(capsule) => {
            for (id, end) in (0..).zip(capsule.segment()) {
                candidates.offer(pose_b.transform_point(end) + down, id);
            }
        }
        Shape::Cuboid(cuboid) => {
            let half = cuboid.half_extents();
            for id in 0..8u32 {
                let corner = Vec3::new(
                    if id & 1 == 0 { -half.x } else { half.x },
                    if id & 2 == 0 { -half.y } else { half.y },
                    if id & 4 == 0 { -half.z } else { half.z },
                );
                candidates.offer(pose_b.transform_point(corner), id);
            }
        }
        Shape::ConvexHull(hull) => {
            for (id, vertex) in (0..).zip(hull.vertices()) {
                candidates.offer(pose_b.transform_point(*vertex), id);
            }
        }
        Shape::Cylinder(cylinder) => {
            // The core's rim, each sample then moved down by the convex radius: the lowest points
            // of the rounded rim.
            let cylinder = cylinder.core();
            let local_normal = pose_b.inverse_transform_vector(normal);
            let downhill = Vec3::new(-local_normal.x, 0.0, -local_normal.z).normalize_or_zero();
            let rim_direction = |sample: u32| {
                let angle = TAU * sample as f32 / CYLINDER_RIM_SAMPLES as f32;
                Vec3::new(angle.cos(), 0.0, angle.sin())
            };
            let samples = 0..CYLINDER_RIM_SAMPLES as u32;
            let nearest = samples.clone().max_by(|&i, &j| {
                rim_direction(i)
                    .dot(downhill)
                    .total_cmp(&rim_direction(j).dot(downhill))
            });
            for (cap, y) in (0u32..).zip([-cylinder.half_height(), cylinder.half_height()]) {
                let center = Vec3::new(0.0, y, 0.0);
                let deepest = center + downhill * cylinder.radius();
                for sample in samples.clone() {
                    let rim = center + rim_direction(sample) * cylinder.radius();
                    let snapped = Some(sample) == nearest
                        && local_normal.dot(rim - deepest) > DEEPEST_SNAP_DISTANCE;
                    let point = if snapped { deepest } else { rim };
                    let id = cap * CYLINDER_RIM_SAMPLES as u32 + sample;
                    candidates.offer(pose_b.transform_point(point) + down, id);
                }
            }
        }
        Shape::Compound(_) | Shape::Halfspace(_) | Shape::TriMesh(_) | Shape::HeightField(_) => {}
    }
    if candidates.len == 0 {
        return None;
    }
    Some(reduce_contacts(
        normal,
        &candidates.points[..candidates.len],
    ))
}
