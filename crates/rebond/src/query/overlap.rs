//! Overlap tests against one shape: does it hold a point, does it overlap another shape.
//! Touching counts as overlapping.

use super::mesh::part_overlaps_mesh;
use super::{convex_parts, world_support, PlacedHalfspace};
use crate::collision::gjk;
use crate::collision::PosedCore;
use crate::math::{Pose, Vec3};
use crate::shape::Shape;

/// Whether `point` (world) lies inside or on `shape` placed at `pose`.
pub(crate) fn shape_contains_point(shape: &Shape, pose: &Pose, point: Vec3) -> bool {
    convex_parts(shape, *pose).any(|(_, part, part_pose)| {
        let local = part_pose.inverse_transform_point(point);
        match part {
            Shape::Sphere(sphere) => local.length_squared() <= sphere.radius() * sphere.radius(),
            Shape::Cuboid(cuboid) => local.abs().cmple(cuboid.half_extents()).all(),
            Shape::Capsule(capsule) => {
                let height = capsule.half_height();
                let axis_point = Vec3::new(0.0, local.y.clamp(-height, height), 0.0);
                (local - axis_point).length_squared() <= capsule.radius() * capsule.radius()
            }
            Shape::Cylinder(cylinder) => {
                local.x * local.x + local.z * local.z <= cylinder.radius() * cylinder.radius()
                    && local.y.abs() <= cylinder.half_height()
            }
            Shape::ConvexHull(hull) => hull
                .faces()
                .iter()
                .all(|face| face.normal.dot(local) <= face.offset),
            Shape::Halfspace(halfspace) => halfspace.normal().dot(local) <= 0.0,
            Shape::HeightField(heightfield) => heightfield.is_below(local),
            Shape::Compound(_) | Shape::TriMesh(_) => false,
        }
    })
}

/// Whether `shape_a` at `pose_a` and `shape_b` at `pose_b` overlap or touch: for compounds,
/// whether any two of their parts do; for a mesh or heightfield, whether a triangle touches a part
/// of the other (two meshes never do: they are surfaces of static or kinematic bodies).
pub(crate) fn shapes_overlap(
    shape_a: &Shape,
    pose_a: &Pose,
    shape_b: &Shape,
    pose_b: &Pose,
) -> bool {
    match (shape_a.is_triangulated(), shape_b.is_triangulated()) {
        (true, true) => return false,
        (true, false) => {
            return convex_parts(shape_b, *pose_b)
                .any(|(_, part, part_pose)| part_overlaps_mesh(shape_a, pose_a, part, &part_pose))
        }
        (false, true) => {
            return convex_parts(shape_a, *pose_a)
                .any(|(_, part, part_pose)| part_overlaps_mesh(shape_b, pose_b, part, &part_pose))
        }
        (false, false) => {}
    }
    convex_parts(shape_a, *pose_a).any(|(_, part_a, part_pose_a)| {
        let bounds_a = part_a.aabb(&part_pose_a);
        convex_parts(shape_b, *pose_b).any(|(_, part_b, part_pose_b)| {
            bounds_a.overlaps(&part_b.aabb(&part_pose_b))
                && convex_parts_overlap(part_a, &part_pose_a, part_b, &part_pose_b)
        })
    })
}

/// Two convex parts. Against a halfspace, the other part's deepest point along the inward
/// normal decides; two bounded parts overlap when GJK finds their cores within the sum of their
/// rounding radii.
fn convex_parts_overlap(shape_a: &Shape, pose_a: &Pose, shape_b: &Shape, pose_b: &Pose) -> bool {
    match (shape_a, shape_b) {
        (Shape::Halfspace(a), Shape::Halfspace(b)) => {
            let (a, b) = (
                PlacedHalfspace::new(a, pose_a),
                PlacedHalfspace::new(b, pose_b),
            );
            // Facing halfspaces overlap when each one's plane is inside the other.
            !a.faces(&b) || a.height_of(b.point) <= 0.0
        }
        (Shape::Halfspace(halfspace), other) => {
            reaches_halfspace(other, pose_b, &PlacedHalfspace::new(halfspace, pose_a))
        }
        (other, Shape::Halfspace(halfspace)) => {
            reaches_halfspace(other, pose_a, &PlacedHalfspace::new(halfspace, pose_b))
        }
        _ => {
            let core_a = PosedCore {
                shape: shape_a,
                pose: pose_a,
            };
            let core_b = PosedCore {
                shape: shape_b,
                pose: pose_b,
            };
            let cores =
                gjk::distance_from_direction(&core_a, &core_b, pose_b.position - pose_a.position);
            cores.overlapping || cores.distance <= shape_a.core_radius() + shape_b.core_radius()
        }
    }
}

/// Whether a bounded convex shape reaches into the halfspace: its deepest point along
/// `−normal` is inside or on the plane.
fn reaches_halfspace(shape: &Shape, pose: &Pose, halfspace: &PlacedHalfspace) -> bool {
    world_support(shape, pose, -halfspace.normal)
        .is_some_and(|deepest| halfspace.height_of(deepest) <= 0.0)
}
