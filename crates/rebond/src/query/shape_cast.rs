//! Shape casts: where a shape moving in a straight line first touches another, by conservative
//! advancement on the GJK distance.
//!
//! For a translation `A + t·d` against a fixed B, the distance between the rounded surfaces,
//! `f(t) = dist(A + t·d, B)`, is convex in `t`, and its slope is `−d·n` with `n` the unit
//! direction from A's closest point to B's. Conservative advancement moves A by
//! `f(t) / (d·n)`, which is Newton's step on `f`: from the left of a root of a convex decreasing
//! function it never overshoots, so A never passes through B, and it converges in one step on a
//! flat face and quadratically elsewhere. The distance used is a lower bound (the reach of
//! `A − B` along GJK's direction), which keeps every step short of the contact. A part that
//! reaches a halfspace is solved in closed form from its deepest point.

use super::{convex_parts, world_support, HitPart, PlacedHalfspace};
use crate::collision::gjk::{self, SupportPoint};
use crate::collision::{epa, PosedCore, SupportMap};
use crate::math::{Aabb, Pose, Vec3};
use crate::shape::{Shape, Triangle};

/// Most distance queries per pair of parts. Advancement converges in a handful; this only bounds
/// grazing passes, where it slows down, and reports them as misses.
const MAX_ITERATIONS: usize = 32;

/// The cast stops when the surfaces are closer than this, metres, near the world origin; the
/// bound grows with the coordinates' magnitude like their f32 rounding
/// (`CONTACT_TOLERANCE · (1 + |largest coordinate|)`), since GJK distances carry that rounding.
const CONTACT_TOLERANCE: f32 = 1e-5;

/// A normal is taken from a closest point of the cores only while that point is farther from
/// the origin than this fraction of the problem's size (GJK's scale): closer, f32 rounding turns
/// its direction by more than a milliradian. Rounded parts always qualify; two polytopes in
/// contact are backed off from each other to measure it ([`backed_off_normal`]).
const RELIABLE_DIRECTION: f32 = 1e-3;

/// How many times [`RELIABLE_DIRECTION`] of the problem's size two touching polytopes are
/// backed off for their normal: enough for the distance to qualify even when the estimate is
/// tilted from the true normal by 60°.
const BACK_OFF: f32 = 4.0;

/// Where a swept shape first touches a fixed one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CastHit {
    /// Travel before contact, metres.
    pub distance: f32,
    /// Contact point on the fixed shape, world.
    pub point: Vec3,
    /// Unit normal of the fixed shape at the point, facing the swept one.
    pub normal: Vec3,
}

/// A shape moving from `pose` along the unit `direction` for up to `max_distance` metres
/// (infinity allowed).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Sweep<'a> {
    /// The moving shape.
    pub shape: &'a Shape,
    /// Where it starts, world.
    pub pose: Pose,
    /// Unit world direction of travel.
    pub direction: Vec3,
    /// Longest travel, metres.
    pub max_distance: f32,
}

/// The first contact of the sweep (a shape that is not a mesh) with the mesh or heightfield
/// `target` at `target_pose`: each convex part against each triangle near its path; with the
/// triangle touched.
fn cast_shape_at_mesh(
    sweep: &Sweep,
    target: &Shape,
    target_pose: &Pose,
) -> Option<(CastHit, HitPart)> {
    let mut best: Option<CastHit> = None;
    let mut best_triangle = 0;
    let to_local = target_pose.inverse();
    for (_, part, part_pose) in convex_parts(sweep.shape, sweep.pose) {
        let local_pose = to_local.mul_pose(&part_pose);
        let local_direction = to_local.transform_vector(sweep.direction);
        let reach = best.map_or(sweep.max_distance, |hit| hit.distance);
        let path = swept_aabb(part, &local_pose, local_direction, reach);
        let bounds = match target {
            Shape::TriMesh(mesh) => mesh.local_bounds(),
            Shape::HeightField(heightfield) => heightfield.local_bounds(),
            _ => return None,
        };
        let path = Aabb::new(path.min.max(bounds.min), path.max.min(bounds.max));
        let mut triangles = Vec::new();
        target.triangles_in(&path, |index| triangles.push(index));
        triangles.sort_unstable();
        for index in triangles {
            let Some(local) = target.triangle(index) else {
                continue;
            };
            let triangle = Triangle {
                vertices: local.vertices.map(|v| target_pose.transform_point(v)),
                edge_flags: local.edge_flags,
            };
            let part_sweep = Sweep {
                shape: part,
                pose: part_pose,
                direction: sweep.direction,
                max_distance: best.map_or(sweep.max_distance, |hit| hit.distance),
            };
            let overlap = |moving: &PosedCore| CastHit {
                distance: 0.0,
                point: moving.pose.position,
                normal: -sweep.direction,
            };
            let centre = triangle.vertices.iter().sum::<Vec3>() / 3.0;
            let start = centre - part_pose.position;
            let Some(hit) = advance(&part_sweep, &triangle, 0.0, start, overlap) else {
                continue;
            };
            if hit.distance <= part_sweep.max_distance
                && best.is_none_or(|best| hit.distance < best.distance)
            {
                best = Some(hit);
                best_triangle = index;
            }
        }
    }
    best.map(|hit| {
        let part = HitPart {
            collider: 0,
            triangle: Some(best_triangle),
        };
        (hit, part)
    })
}

/// The box holding `shape` along its whole path from `pose`, `distance` metres along `direction`.
fn swept_aabb(shape: &Shape, pose: &Pose, direction: Vec3, distance: f32) -> Aabb {
    let start = shape.aabb(pose);
    // A zero component stays zero even for an infinite distance.
    let travel = Vec3::select(
        direction.cmpeq(Vec3::ZERO),
        Vec3::ZERO,
        direction * distance,
    );
    Aabb::new(
        start.min.min(start.min + travel),
        start.max.max(start.max + travel),
    )
}

/// The first contact of the sweep with `target` at `target_pose`, within the sweep's distance,
/// with the target's collider and triangle touched. Compounds on either side are taken part by
/// part (the first pair among equally near ones), a target's children only where
/// `sees(child)` holds; a mesh or heightfield target triangle by triangle (`query::mesh`). A
/// swept mesh or heightfield meets nothing.
pub(crate) fn cast_shape_at_shape(
    sweep: &Sweep,
    target: &Shape,
    target_pose: &Pose,
    sees: impl Fn(u32) -> bool,
) -> Option<(CastHit, HitPart)> {
    if sweep.shape.is_triangulated() {
        return None;
    }
    if target.is_triangulated() {
        return cast_shape_at_mesh(sweep, target, target_pose);
    }
    let mut best: Option<(CastHit, HitPart)> = None;
    for (_, part, part_pose) in convex_parts(sweep.shape, sweep.pose) {
        for (collider, target_part, target_part_pose) in convex_parts(target, *target_pose) {
            if !sees(collider) {
                continue;
            }
            let best_distance = best.map(|(hit, _)| hit.distance);
            let part_sweep = Sweep {
                shape: part,
                pose: part_pose,
                direction: sweep.direction,
                max_distance: best_distance.unwrap_or(sweep.max_distance),
            };
            let path = swept_aabb(part, &part_pose, sweep.direction, part_sweep.max_distance);
            if !path.overlaps(&target_part.aabb(&target_part_pose)) {
                continue;
            }
            if let Some(hit) = cast_convex(&part_sweep, target_part, &target_part_pose) {
                if best_distance.is_none_or(|distance| hit.distance < distance) {
                    let part = HitPart {
                        collider,
                        triangle: None,
                    };
                    best = Some((hit, part));
                }
            }
        }
    }
    best
}

/// Two convex parts.
fn cast_convex(sweep: &Sweep, target: &Shape, target_pose: &Pose) -> Option<CastHit> {
    let hit = match (sweep.shape, target) {
        (Shape::Halfspace(moving), Shape::Halfspace(fixed)) => cast_halfspace_at_halfspace(
            sweep,
            &PlacedHalfspace::new(moving, &sweep.pose),
            &PlacedHalfspace::new(fixed, target_pose),
        ),
        (Shape::Halfspace(moving), _) => cast_halfspace_at_shape(
            sweep,
            &PlacedHalfspace::new(moving, &sweep.pose),
            target,
            target_pose,
        ),
        (_, Shape::Halfspace(fixed)) => {
            cast_shape_at_halfspace(sweep, &PlacedHalfspace::new(fixed, target_pose))
        }
        _ => {
            let target_core = PosedCore {
                shape: target,
                pose: target_pose,
            };
            let overlap = |moving: &PosedCore| start_overlap(moving, &target_core);
            let start = target_pose.position - sweep.pose.position;
            advance(sweep, &target_core, target.core_radius(), start, overlap)
        }
    }?;
    (hit.distance <= sweep.max_distance).then_some(hit)
}

/// Conservative advancement of a bounded part towards a bounded target (module documentation):
/// the target's core `target_core` (a shape's, or a triangle) with rounding `target_radius`,
/// searched for first along `start_direction`; `overlap(moving)` answers when they overlap before
/// moving.
pub(super) fn advance<T: SupportMap>(
    sweep: &Sweep,
    target_core: &T,
    target_radius: f32,
    start_direction: Vec3,
    overlap: impl Fn(&PosedCore) -> CastHit,
) -> Option<CastHit> {
    let rounding = sweep.shape.core_radius() + target_radius;
    let magnitude = sweep
        .pose
        .position
        .abs()
        .max((sweep.pose.position + start_direction).abs())
        .max_element();
    let tolerance = CONTACT_TOLERANCE * (1.0 + magnitude);
    let mut travelled = 0.0;
    let mut search_direction = start_direction;
    let mut reliable_normal: Option<Vec3> = None;
    for _ in 0..MAX_ITERATIONS {
        let pose = Pose::new(
            sweep.pose.position + travelled * sweep.direction,
            sweep.pose.rotation,
        );
        let moving_core = PosedCore {
            shape: sweep.shape,
            pose: &pose,
        };
        let cores = gjk::distance_from_direction(&moving_core, target_core, search_direction);
        // `closest` is the point of A − B nearest the origin: the cores are apart by its length,
        // along `normal` from A toward B.
        let closest = cores.simplex.closest_point();
        let scale = cores.simplex.scale();
        let Some(normal) = (-closest).try_normalize() else {
            return Some(match reliable_normal {
                Some(estimate) => CastHit {
                    distance: travelled,
                    point: cores.point_b,
                    normal: backed_off_normal(&moving_core, target_core, estimate, scale),
                },
                None => overlap(&moving_core),
            });
        };
        let is_reliable = closest.length() >= RELIABLE_DIRECTION * scale;
        if is_reliable {
            reliable_normal = Some(-normal);
        }
        // GJK's distance is an upper bound, precise only to its tolerance of the problem's size
        // (a large floor makes that large); the support point along `normal` gives a lower
        // bound, and advancing by a lower bound never overshoots.
        let farthest = SupportPoint::new(&moving_core, target_core, normal).w;
        let separation = -normal.dot(farthest) - rounding;
        let closing_speed = sweep.direction.dot(normal);
        if separation <= tolerance {
            if travelled == 0.0 && separation < 0.0 {
                return Some(overlap(&moving_core));
            }
            // One last step, unchecked: like every step it cannot overshoot, and it takes the
            // remaining separation out of the answer.
            let last_step = if closing_speed > 0.0 {
                separation.max(0.0) / closing_speed
            } else {
                0.0
            };
            let contact_normal = if is_reliable {
                -normal
            } else {
                let estimate = reliable_normal.unwrap_or(-sweep.direction);
                backed_off_normal(&moving_core, target_core, estimate, scale)
            };
            return Some(CastHit {
                distance: travelled + last_step,
                point: cores.point_b - target_radius * normal,
                normal: contact_normal,
            });
        }
        if closing_speed <= 0.0 {
            return None;
        }
        travelled += separation / closing_speed;
        if travelled > sweep.max_distance {
            return None;
        }
        search_direction = normal;
    }
    None
}

/// The normal of the target, facing the moving shape, where two polytopes touch: their closest
/// points there are too near for a reliable direction, so GJK runs again with the moving shape
/// backed off along `estimate` (a unit vector away from the target) until it is reliable.
fn backed_off_normal<T: SupportMap>(
    moving: &PosedCore,
    target: &T,
    estimate: Vec3,
    scale: f32,
) -> Vec3 {
    let backed_off = Pose::new(
        moving.pose.position + BACK_OFF * RELIABLE_DIRECTION * scale * estimate,
        moving.pose.rotation,
    );
    let moving = PosedCore {
        shape: moving.shape,
        pose: &backed_off,
    };
    gjk::distance_from_direction(&moving, target, -estimate)
        .simplex
        .closest_point()
        .try_normalize()
        .unwrap_or(estimate)
}

/// The answer for shapes that overlap before moving: the target's point deepest inside the
/// moving shape and the direction that separates them the quickest, from GJK or, when the cores
/// overlap, EPA.
fn start_overlap(moving: &PosedCore, target: &PosedCore) -> CastHit {
    let contact = epa::contact(moving, target, f32::INFINITY);
    CastHit {
        distance: 0.0,
        point: contact.map_or(target.pose.position, |contact| contact.point_b),
        normal: contact.map_or(Vec3::Y, |contact| -contact.normal),
    }
}

/// A bounded part against a fixed halfspace: its deepest point along `−n` reaches the plane
/// after `height / (−d·n)`.
fn cast_shape_at_halfspace(sweep: &Sweep, fixed: &PlacedHalfspace) -> Option<CastHit> {
    let deepest = world_support(sweep.shape, &sweep.pose, -fixed.normal)?;
    let height = fixed.height_of(deepest);
    if height <= 0.0 {
        return Some(CastHit {
            distance: 0.0,
            point: deepest - height * fixed.normal,
            normal: fixed.normal,
        });
    }
    let closing_speed = -sweep.direction.dot(fixed.normal);
    (closing_speed > 0.0).then(|| {
        let distance = height / closing_speed;
        CastHit {
            distance,
            point: deepest + distance * sweep.direction,
            normal: fixed.normal,
        }
    })
}

/// A moving halfspace against a bounded part: the plane reaches the part's point deepest along
/// its inward normal after `height / (d·n)`.
fn cast_halfspace_at_shape(
    sweep: &Sweep,
    moving: &PlacedHalfspace,
    target: &Shape,
    target_pose: &Pose,
) -> Option<CastHit> {
    let deepest = world_support(target, target_pose, -moving.normal)?;
    let height = moving.height_of(deepest);
    let closing_speed = sweep.direction.dot(moving.normal);
    let distance = if height <= 0.0 {
        0.0
    } else if closing_speed > 0.0 {
        height / closing_speed
    } else {
        return None;
    };
    Some(CastHit {
        distance,
        point: deepest,
        normal: -moving.normal,
    })
}

/// Two halfspaces: unless they face each other they overlap from the start; facing ones meet
/// when the moving plane reaches the fixed one.
fn cast_halfspace_at_halfspace(
    sweep: &Sweep,
    moving: &PlacedHalfspace,
    fixed: &PlacedHalfspace,
) -> Option<CastHit> {
    let gap = moving.height_of(fixed.point);
    let distance = if !moving.faces(fixed) || gap <= 0.0 {
        0.0
    } else if sweep.direction.dot(moving.normal) > 0.0 {
        gap / sweep.direction.dot(moving.normal)
    } else {
        return None;
    };
    let moved_point = moving.point + distance * sweep.direction;
    Some(CastHit {
        distance,
        point: moved_point - fixed.height_of(moved_point) * fixed.normal,
        normal: fixed.normal,
    })
}
