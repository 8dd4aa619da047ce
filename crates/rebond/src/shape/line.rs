//! Where a line crosses a convex shape, in closed form for every kind: the interval
//! `[enter, leave]` of `t` on which `o + t·d` lies inside (possibly unbounded for a halfspace),
//! found in the shape's local frame: quadratics for the round shapes, slabs for boxes and
//! cylinder caps, one plane per face for hulls. Ray casts (`query::ray`) and the contacts of
//! shapes with triangles (`collision::triangle_contact`) read it.

use super::{Capsule, ConvexHull, Cuboid, Cylinder, Shape};
use crate::math::{Pose, Vec3};

/// The interval of the line `o + t·d` inside a convex shape, with the outward normals where it
/// enters and leaves (local frame). An unbounded end is infinite and its normal unused.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Crossing {
    pub enter: f32,
    pub enter_normal: Vec3,
    pub leave: f32,
    pub leave_normal: Vec3,
}

impl Crossing {
    /// The whole line.
    const EVERYWHERE: Crossing = Crossing {
        enter: f32::NEG_INFINITY,
        enter_normal: Vec3::ZERO,
        leave: f32::INFINITY,
        leave_normal: Vec3::ZERO,
    };

    /// The part of the line inside both (`None` when empty).
    fn intersect(self, other: Crossing) -> Option<Crossing> {
        let (enter, enter_normal) = if other.enter > self.enter {
            (other.enter, other.enter_normal)
        } else {
            (self.enter, self.enter_normal)
        };
        let (leave, leave_normal) = if other.leave < self.leave {
            (other.leave, other.leave_normal)
        } else {
            (self.leave, self.leave_normal)
        };
        (enter <= leave).then_some(Crossing {
            enter,
            enter_normal,
            leave,
            leave_normal,
        })
    }

    /// The part of the line inside either, when their union is one interval (parts of one convex
    /// shape).
    fn union(self, other: Crossing) -> Crossing {
        let (enter, enter_normal) = if other.enter < self.enter {
            (other.enter, other.enter_normal)
        } else {
            (self.enter, self.enter_normal)
        };
        let (leave, leave_normal) = if other.leave > self.leave {
            (other.leave, other.leave_normal)
        } else {
            (self.leave, self.leave_normal)
        };
        Crossing {
            enter,
            enter_normal,
            leave,
            leave_normal,
        }
    }
}

/// Where the line `origin + t·direction` (world, unit direction) enters the convex `shape` placed
/// at `pose` (not a compound, mesh or heightfield), as `t`, which is negative where `origin` lies
/// inside; `None` where the line misses it. For the contacts of a shape with a triangle
/// (`collision::triangle_contact`): how deep the shape reaches below a point of the triangle.
pub(crate) fn line_entry(shape: &Shape, pose: &Pose, origin: Vec3, direction: Vec3) -> Option<f32> {
    let local_origin = pose.inverse_transform_point(origin);
    let local_direction = pose.inverse_transform_vector(direction);
    let crossing = line_crossing(shape, local_origin, local_direction)?;
    crossing.enter.is_finite().then_some(crossing.enter)
}

/// Where the line `origin + t·direction` (local frame, unit direction) crosses a convex shape.
pub(crate) fn line_crossing(shape: &Shape, origin: Vec3, direction: Vec3) -> Option<Crossing> {
    match shape {
        Shape::Sphere(sphere) => ball_crossing(origin, direction, sphere.radius()),
        Shape::Cuboid(cuboid) => box_crossing(cuboid, origin, direction),
        Shape::Capsule(capsule) => capsule_crossing(capsule, origin, direction),
        Shape::Cylinder(cylinder) => cylinder_crossing(cylinder, origin, direction),
        Shape::ConvexHull(hull) => hull_crossing(hull, origin, direction),
        Shape::Compound(_) | Shape::TriMesh(_) | Shape::HeightField(_) => None,
        Shape::Halfspace(halfspace) => {
            // Inside where n·(o + t d) ≤ 0.
            let height = halfspace.normal().dot(origin);
            let rate = halfspace.normal().dot(direction);
            if rate == 0.0 {
                return (height <= 0.0).then_some(Crossing::EVERYWHERE);
            }
            let crossing_at = -height / rate;
            let mut crossing = Crossing::EVERYWHERE;
            if rate < 0.0 {
                crossing.enter = crossing_at;
                crossing.enter_normal = halfspace.normal();
            } else {
                crossing.leave = crossing_at;
                crossing.leave_normal = halfspace.normal();
            }
            Some(crossing)
        }
    }
}

/// The roots of `a t² + 2 b t + c = 0`, smaller first, given its reduced discriminant
/// `b² − a c ≥ 0` (which the caller computes without cancellation). The root of larger magnitude
/// is `q / a` with `q = −(b + sign(b) √disc)`, the other `c / q` (their product is `c / a`):
/// neither subtracts nearly equal numbers, unlike `(−b ± √disc) / a`.
fn quadratic_roots(a: f32, b: f32, c: f32, discriminant: f32) -> (f32, f32) {
    let q = -(b + discriminant.sqrt().copysign(b));
    if q == 0.0 {
        return (0.0, 0.0);
    }
    let (first, second) = (q / a, c / q);
    (first.min(second), first.max(second))
}

/// Where the line crosses the ball of `radius` around the origin: `|o + t d|² = r²`. The reduced
/// discriminant is `r² − |o − (o·d) d|²`, the squared half chord, from the line's closest point.
fn ball_crossing(origin: Vec3, direction: Vec3, radius: f32) -> Option<Crossing> {
    let along = origin.dot(direction);
    let half_chord_squared = radius * radius - (origin - along * direction).length_squared();
    if half_chord_squared < 0.0 {
        return None;
    }
    let offset = origin.length_squared() - radius * radius;
    let (enter, leave) = quadratic_roots(1.0, along, offset, half_chord_squared);
    let normal_at = |t: f32| (origin + t * direction).normalize_or(-direction);
    Some(Crossing {
        enter,
        enter_normal: normal_at(enter),
        leave,
        leave_normal: normal_at(leave),
    })
}

/// Where the line crosses the infinite cylinder `x² + z² ≤ r²` around local Y: the ball test in
/// the XZ plane, with `a = dx² + dz²`. A line along Y is inside everywhere or nowhere.
fn side_crossing(origin: Vec3, direction: Vec3, radius: f32) -> Option<Crossing> {
    let flat_origin = Vec3::new(origin.x, 0.0, origin.z);
    let flat_direction = Vec3::new(direction.x, 0.0, direction.z);
    let a = flat_direction.length_squared();
    let offset = flat_origin.length_squared() - radius * radius;
    if a < f32::MIN_POSITIVE {
        return (offset <= 0.0).then_some(Crossing::EVERYWHERE);
    }
    let along = flat_origin.dot(flat_direction);
    let closest = flat_origin - (along / a) * flat_direction;
    let discriminant = a * (radius * radius - closest.length_squared());
    if discriminant < 0.0 {
        return None;
    }
    let (enter, leave) = quadratic_roots(a, along, offset, discriminant);
    let normal_at = |t: f32| {
        let point = flat_origin + t * flat_direction;
        point.normalize_or(-flat_direction.normalize_or(Vec3::X))
    };
    Some(Crossing {
        enter,
        enter_normal: normal_at(enter),
        leave,
        leave_normal: normal_at(leave),
    })
}

/// Where the line crosses the slab `|p[axis]| ≤ half_width`, with the slab's face normals.
fn slab_crossing(origin: Vec3, direction: Vec3, axis: usize, half_width: f32) -> Option<Crossing> {
    let inverse = direction[axis].recip();
    if !inverse.is_finite() {
        return (origin[axis].abs() <= half_width).then_some(Crossing::EVERYWHERE);
    }
    let to_low = (-half_width - origin[axis]) * inverse;
    let to_high = (half_width - origin[axis]) * inverse;
    let mut outward = Vec3::ZERO;
    outward[axis] = 1.0;
    // Moving up the axis, the line enters through the low face and leaves through the high one.
    let (enter, leave, enter_normal) = if inverse > 0.0 {
        (to_low, to_high, -outward)
    } else {
        (to_high, to_low, outward)
    };
    Some(Crossing {
        enter,
        enter_normal,
        leave,
        leave_normal: -enter_normal,
    })
}

/// A box is three slabs.
fn box_crossing(cuboid: &Cuboid, origin: Vec3, direction: Vec3) -> Option<Crossing> {
    let half = cuboid.half_extents();
    (0..3).try_fold(Crossing::EVERYWHERE, |crossing, axis| {
        crossing.intersect(slab_crossing(origin, direction, axis, half[axis])?)
    })
}

/// A cylinder is its infinite side cut by the slab between its caps.
fn cylinder_crossing(cylinder: &Cylinder, origin: Vec3, direction: Vec3) -> Option<Crossing> {
    side_crossing(origin, direction, cylinder.radius())?.intersect(slab_crossing(
        origin,
        direction,
        1,
        cylinder.half_height(),
    )?)
}

/// A capsule is the union of its two end balls and the cylinder between their centres; the
/// parts' intervals overlap, so the capsule's runs from the earliest entry to the latest exit.
/// Normals are taken from the capsule's own geometry at the crossing points.
fn capsule_crossing(capsule: &Capsule, origin: Vec3, direction: Vec3) -> Option<Crossing> {
    let (radius, half_height) = (capsule.radius(), capsule.half_height());
    let ball_at = |height: f32| {
        let centre = Vec3::new(0.0, height, 0.0);
        ball_crossing(origin - centre, direction, radius)
    };
    let body = side_crossing(origin, direction, radius)
        .and_then(|side| side.intersect(slab_crossing(origin, direction, 1, half_height)?));
    let crossing = [ball_at(-half_height), ball_at(half_height), body]
        .into_iter()
        .flatten()
        .reduce(Crossing::union)?;
    let normal_at = |t: f32| {
        let point = origin + t * direction;
        let axis_point = Vec3::new(0.0, point.y.clamp(-half_height, half_height), 0.0);
        (point - axis_point).normalize_or(-direction)
    };
    Some(Crossing {
        enter_normal: normal_at(crossing.enter),
        leave_normal: normal_at(crossing.leave),
        ..crossing
    })
}

/// A hull is the intersection of its faces' halfspaces `n·p ≤ offset`.
fn hull_crossing(hull: &ConvexHull, origin: Vec3, direction: Vec3) -> Option<Crossing> {
    hull.faces()
        .iter()
        .try_fold(Crossing::EVERYWHERE, |crossing, face| {
            let height = face.normal.dot(origin) - face.offset;
            let rate = face.normal.dot(direction);
            if rate == 0.0 {
                return (height <= 0.0).then_some(crossing);
            }
            let crossing_at = -height / rate;
            let mut plane = Crossing::EVERYWHERE;
            if rate < 0.0 {
                plane.enter = crossing_at;
                plane.enter_normal = face.normal;
            } else {
                plane.leave = crossing_at;
                plane.leave_normal = face.normal;
            }
            crossing.intersect(plane)
        })
}
