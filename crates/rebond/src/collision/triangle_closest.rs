//! Closest points of a triangle and the core of a capsule (a segment) or of a box, in closed
//! form: what GJK finds for those pairs, for about a fifth of its cost (650 to 850 instructions
//! a query against 3,500) and without its tolerance.
//!
//! Two convex sets are closest along a unique vector, reached (when they do not meet) at a pair
//! of features; it is enough to try the candidates below and keep the nearest:
//!
//! - segment and triangle: an end of the segment against the triangle, or the segment against
//!   one of the triangle's edges. A segment crossing the face meets the triangle.
//! - box and triangle: an edge of the triangle against the box (exact, see [`edge_toward_box`]),
//!   or, when the triangle's plane misses the box, the box's corner nearest the plane against the
//!   triangle. When the plane cuts the box and no edge meets it, the box meets the triangle
//!   exactly when the plane's section of the box lies inside the triangle, which one point of it
//!   tells.
//!
//! Both work in a frame near the pair (the triangle's first corner, the box's own frame), so
//! that the distance's rounding is relative to the pair's size, not to its distance from the
//! world origin; the points are then placed back in the world.

use super::closed_form::closest_segment_parameters;
use super::gjk;
use crate::math::{Pose, Vec3};
use crate::shape::Triangle;

/// The closest points `(on_triangle, on_core)` of `triangle` and the world segment `segment`
/// when they are apart by at most `limit` metres: `Some(Some(..))`; `Some(None)` when they meet
/// (or are apart by less than GJK's overlap tolerance, [`gjk::TOLERANCE`] of their size);
/// `None` when apart by more than `limit`.
pub(crate) fn segment_triangle(
    triangle: &Triangle,
    segment: [Vec3; 2],
    limit: f32,
) -> Option<Option<(Vec3, Vec3)>> {
    let origin = triangle.vertices[0];
    let corners = triangle.vertices.map(|corner| corner - origin);
    let [start, end] = segment.map(|point| point - origin);
    let local = Triangle {
        vertices: corners,
        edge_flags: 0,
    };
    let normal = corners[1].cross(corners[2]);
    let (height_start, height_end) = (normal.dot(start), normal.dot(end));
    let above = height_start > 0.0 && height_end > 0.0;
    let below = height_start < 0.0 && height_end < 0.0;
    // Wholly on one side of the plane by more than the limit (heights are times `|normal|`).
    let lowest = height_start.abs().min(height_end.abs());
    if (above || below) && lowest > limit * normal.length() {
        return None;
    }
    let crosses =
        (height_start > 0.0 && height_end < 0.0) || (height_start < 0.0 && height_end > 0.0);
    if crosses {
        let crossing = start + (end - start) * (height_start / (height_start - height_end));
        if inside(&corners, normal, crossing) {
            return Some(None);
        }
    }
    let mut nearest = Nearest::default();
    for point in [start, end] {
        nearest.offer(local.closest_point(point).0, point);
    }
    for edge in 0..3 {
        let from = corners[edge];
        let along = corners[(edge + 1) % 3] - from;
        let (s, t) = closest_segment_parameters(from, along, start, end - start);
        nearest.offer(from + along * s, start + (end - start) * t);
    }
    let size = corners
        .iter()
        .chain(&[start, end])
        .fold(0.0f32, |size, point| size.max(point.abs().max_element()));
    nearest
        .within(limit, size)
        .map(|points| points.map(|(on_triangle, on_core)| (on_triangle + origin, on_core + origin)))
}

/// The closest points `(on_triangle, on_box)` of `triangle` and the box of `half_extents` at
/// `pose`, as [`segment_triangle`] gives them for a segment; `None` for a triangle of zero area
/// (which `collide_triangle` never passes).
pub(crate) fn box_triangle(
    triangle: &Triangle,
    half_extents: Vec3,
    pose: &Pose,
    limit: f32,
) -> Option<Option<(Vec3, Vec3)>> {
    let corners = triangle
        .vertices
        .map(|corner| pose.inverse_transform_point(corner));
    // The box's three axes as separating axes: lower bounds of the distance.
    let low = corners[0].min(corners[1]).min(corners[2]);
    let high = corners[0].max(corners[1]).max(corners[2]);
    if (low - half_extents).max(-half_extents - high).max_element() > limit {
        return None;
    }
    let normal = (corners[1] - corners[0])
        .cross(corners[2] - corners[0])
        .try_normalize()?;
    // The centre's height over the plane and the box's reach along the normal: the box spans
    // heights `centre ± reach`, its lowest corner `−sign(normal) ∘ half_extents`.
    let centre = -normal.dot(corners[0]);
    let reach = half_extents.dot(normal.abs());
    if centre.abs() - reach > limit {
        return None;
    }
    let toward_plane = half_extents * normal.signum();
    let mut nearest = Nearest::default();
    if centre.abs() <= reach {
        // The point of the corner-to-corner diagonal across the plane lies in the box's section.
        let section = toward_plane * (-centre / reach.max(f32::MIN_POSITIVE));
        if inside(&corners, normal, section) {
            return Some(None);
        }
    } else {
        let corner = if centre > 0.0 {
            -toward_plane
        } else {
            toward_plane
        };
        let local = Triangle {
            vertices: corners,
            edge_flags: 0,
        };
        nearest.offer(local.closest_point(corner).0, corner);
    }
    for edge in 0..3 {
        let from = corners[edge];
        let along = corners[(edge + 1) % 3] - from;
        let on_edge = edge_toward_box(from, along, half_extents);
        nearest.offer(on_edge, on_edge.clamp(-half_extents, half_extents));
    }
    let size = corners
        .iter()
        .fold(half_extents.max_element(), |size, point| {
            size.max(point.abs().max_element())
        });
    nearest.within(limit, size).map(|points| {
        points.map(|(on_triangle, on_box)| {
            (
                pose.transform_point(on_triangle),
                pose.transform_point(on_box),
            )
        })
    })
}

/// The point of the segment `from + t · along` (`t` in `[0, 1]`) closest to the box
/// `[−half_extents, half_extents]`. The squared distance `f(t) = |x − clamp(x)|²` of the point
/// `x(t)` is convex and piecewise quadratic, its pieces split where `x` crosses a face's plane, so
/// its slope `g(t) = along · (x − clamp(x))` is nondecreasing and linear between those crossings:
/// the minimum is an end where `g` does not change sign, otherwise the root of `g`, found by
/// narrowing a bracket to the two crossings around it and interpolating there, exactly.
fn edge_toward_box(from: Vec3, along: Vec3, half_extents: Vec3) -> Vec3 {
    let slope = |t: f32| {
        let point = from + along * t;
        along.dot(point - point.clamp(-half_extents, half_extents))
    };
    let slope_low = slope(0.0);
    if slope_low >= 0.0 {
        return from;
    }
    let slope_high = slope(1.0);
    if slope_high <= 0.0 {
        return from + along;
    }
    let (mut low, mut high, mut slope_low, mut slope_high) = (0.0, 1.0, slope_low, slope_high);
    for axis in 0..3 {
        if along[axis] == 0.0 {
            continue;
        }
        for bound in [-half_extents[axis], half_extents[axis]] {
            let t = (bound - from[axis]) / along[axis];
            if t > low && t < high {
                let slope_t = slope(t);
                if slope_t < 0.0 {
                    (low, slope_low) = (t, slope_t);
                } else {
                    (high, slope_high) = (t, slope_t);
                }
            }
        }
    }
    let t = low + (high - low) * (slope_low / (slope_low - slope_high));
    from + along * t
}

/// Whether `point` of the plane of `corners` (normal `normal`, any length) lies inside the
/// triangle or on its rim: on the inner side of each edge.
fn inside(corners: &[Vec3; 3], normal: Vec3, point: Vec3) -> bool {
    (0..3).all(|edge| {
        let from = corners[edge];
        let along = corners[(edge + 1) % 3] - from;
        normal.dot(along.cross(point - from)) >= 0.0
    })
}

/// The nearest pair of candidate points so far: a point of the triangle and one of the core.
#[derive(Debug, Clone, Copy)]
struct Nearest {
    distance_squared: f32,
    points: (Vec3, Vec3),
}

impl Default for Nearest {
    fn default() -> Self {
        Self {
            distance_squared: f32::INFINITY,
            points: (Vec3::ZERO, Vec3::ZERO),
        }
    }
}

impl Nearest {
    /// Keeps the pair when it is nearer than the nearest so far.
    fn offer(&mut self, on_triangle: Vec3, on_core: Vec3) {
        let distance_squared = on_triangle.distance_squared(on_core);
        if distance_squared < self.distance_squared {
            *self = Self {
                distance_squared,
                points: (on_triangle, on_core),
            };
        }
    }

    /// The pair when apart by at most `limit`, `Some(None)` when they touch, as GJK reports an
    /// overlap: closer than [`gjk::TOLERANCE`] of the problem's `size` (its largest coordinate),
    /// where the direction between them is lost to rounding.
    fn within(&self, limit: f32, size: f32) -> Option<Option<(Vec3, Vec3)>> {
        if self.distance_squared > limit * limit {
            return None;
        }
        let touching = gjk::TOLERANCE * size;
        Some((self.distance_squared > touching * touching).then_some(self.points))
    }
}

#[cfg(test)]
mod tests;
