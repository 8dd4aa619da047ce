//! Contacts in closed form for the rounded shapes: sphere/sphere, sphere/capsule,
//! capsule/capsule, sphere/box, and a sphere or capsule against a cylinder's side. Every function
//! returns the manifold with the normal from A toward B, or `None` when the surfaces are farther
//! apart than `margin`.

use super::manifold::{ContactPoint, Manifold};
use crate::math::{Pose, Vec3};
use crate::shape::{Capsule, Cuboid, Cylinder, Sphere};

/// Below this squared length, metres², two centres or a segment count as coincident and a
/// fallback direction is used.
const COINCIDENT_SQUARED: f32 = 1.0e-12;

/// Segments whose directions' cross product is shorter than this (sine of the angle between
/// them, for unit directions) count as parallel: capsules lying side by side get two points.
const PARALLEL_SINE: f32 = 0.005;

/// A contact between two balls (centre, radius) as a point id: the single point lies midway
/// between the two surfaces along the line of centres.
fn ball_contact(
    center_a: Vec3,
    radius_a: f32,
    center_b: Vec3,
    radius_b: f32,
    fallback_normal: Vec3,
    id: u32,
) -> (Vec3, ContactPoint) {
    let offset = center_b - center_a;
    let distance_squared = offset.length_squared();
    let (normal, distance) = if distance_squared > COINCIDENT_SQUARED {
        let distance = distance_squared.sqrt();
        (offset / distance, distance)
    } else {
        (fallback_normal, 0.0)
    };
    let separation = distance - radius_a - radius_b;
    let surface_a = center_a + normal * radius_a;
    let surface_b = center_b - normal * radius_b;
    let point = ContactPoint {
        position: 0.5 * (surface_a + surface_b),
        separation,
        id,
    };
    (normal, point)
}

fn single_point(normal: Vec3, point: ContactPoint, margin: f32) -> Option<Manifold> {
    if point.separation > margin {
        return None;
    }
    let mut manifold = Manifold::new(normal);
    manifold.push(point);
    Some(manifold)
}

/// Sphere A against sphere B: `separation = |c_B − c_A| − r_A − r_B`.
pub fn sphere_sphere(
    a: &Sphere,
    pose_a: &Pose,
    b: &Sphere,
    pose_b: &Pose,
    margin: f32,
) -> Option<Manifold> {
    let (normal, point) = ball_contact(
        pose_a.position,
        a.radius(),
        pose_b.position,
        b.radius(),
        Vec3::Y,
        0,
    );
    single_point(normal, point, margin)
}

/// The world segment of a capsule.
fn world_segment(capsule: &Capsule, pose: &Pose) -> [Vec3; 2] {
    capsule.segment().map(|end| pose.transform_point(end))
}

/// The point of segment `[start, end]` closest to `point`.
fn closest_on_segment(start: Vec3, end: Vec3, point: Vec3) -> Vec3 {
    let direction = end - start;
    let length_squared = direction.length_squared();
    if length_squared <= COINCIDENT_SQUARED {
        return start;
    }
    let t = ((point - start).dot(direction) / length_squared).clamp(0.0, 1.0);
    start + direction * t
}

/// Sphere A against capsule B: a sphere against the closest point of B's segment.
pub fn sphere_capsule(
    a: &Sphere,
    pose_a: &Pose,
    b: &Capsule,
    pose_b: &Pose,
    margin: f32,
) -> Option<Manifold> {
    let [start, end] = world_segment(b, pose_b);
    let closest = closest_on_segment(start, end, pose_a.position);
    // `any_orthonormal_vector` needs a unit input to give a unit output.
    let fallback = (end - start).normalize().any_orthonormal_vector();
    let (normal, point) = ball_contact(
        pose_a.position,
        a.radius(),
        closest,
        b.radius(),
        fallback,
        0,
    );
    single_point(normal, point, margin)
}

/// Parameters `(s, t)` of the closest points `p₁ + s d₁` and `p₂ + t d₂` of two segments, both
/// clamped to `[0, 1]` (the classic clamped solution of the 2×2 normal equations).
pub(super) fn closest_segment_parameters(p1: Vec3, d1: Vec3, p2: Vec3, d2: Vec3) -> (f32, f32) {
    let r = p1 - p2;
    let a = d1.length_squared();
    let e = d2.length_squared();
    let f = d2.dot(r);
    if a <= COINCIDENT_SQUARED && e <= COINCIDENT_SQUARED {
        return (0.0, 0.0);
    }
    if a <= COINCIDENT_SQUARED {
        return (0.0, (f / e).clamp(0.0, 1.0));
    }
    let c = d1.dot(r);
    if e <= COINCIDENT_SQUARED {
        return ((-c / a).clamp(0.0, 1.0), 0.0);
    }
    let b = d1.dot(d2);
    let denominator = a * e - b * b;
    let mut s = if denominator > COINCIDENT_SQUARED * a * e {
        ((b * f - c * e) / denominator).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    (s, t)
}

/// Capsule A against capsule B. In general one point at the closest points of the two segments;
/// when the segments are parallel and overlap along their length, two points at the ends of the
/// overlap, so a capsule lying along another one rests on a line, not a point.
pub fn capsule_capsule(
    a: &Capsule,
    pose_a: &Pose,
    b: &Capsule,
    pose_b: &Pose,
    margin: f32,
) -> Option<Manifold> {
    let [start_a, end_a] = world_segment(a, pose_a);
    let [start_b, end_b] = world_segment(b, pose_b);
    let (direction_a, direction_b) = (end_a - start_a, end_b - start_b);
    let (s, t) = closest_segment_parameters(start_a, direction_a, start_b, direction_b);
    let closest_a = start_a + direction_a * s;
    let closest_b = start_b + direction_b * t;
    let fallback = direction_a.normalize().any_orthonormal_vector();
    let (normal, point) = ball_contact(closest_a, a.radius(), closest_b, b.radius(), fallback, 0);
    if point.separation > margin {
        return None;
    }
    let axis_a = direction_a.normalize_or_zero();
    let axis_b = direction_b.normalize_or_zero();
    if axis_a.cross(axis_b).length() < PARALLEL_SINE {
        if let Some(manifold) = parallel_capsules(
            [start_a, end_a],
            a.radius(),
            [start_b, end_b],
            b.radius(),
            normal,
            margin,
        ) {
            return Some(manifold);
        }
    }
    single_point(normal, point, margin)
}

/// Two points for parallel capsules: B's segment clipped to the stretch of A's, each end paired
/// with the point of A's line across from it. `None` when the overlap is a single point. Also
/// the feature manifold's two rounded lines lying along each other (a cylinder's side on a
/// capsule or another cylinder's side, `feature_contact`).
pub(super) fn parallel_capsules(
    segment_a: [Vec3; 2],
    radius_a: f32,
    segment_b: [Vec3; 2],
    radius_b: f32,
    normal: Vec3,
    margin: f32,
) -> Option<Manifold> {
    let [start_a, end_a] = segment_a;
    let axis = end_a - start_a;
    let length_squared = axis.length_squared();
    if length_squared <= COINCIDENT_SQUARED {
        return None;
    }
    let parameter = |point: Vec3| (point - start_a).dot(axis) / length_squared;
    let (mut t0, mut t1) = (parameter(segment_b[0]), parameter(segment_b[1]));
    let mut ends = segment_b;
    if t0 > t1 {
        std::mem::swap(&mut t0, &mut t1);
        ends.swap(0, 1);
    }
    let low = t0.max(0.0);
    let high = t1.min(1.0);
    if high - low <= 1.0e-3 {
        return None;
    }
    let span = (t1 - t0).max(f32::MIN_POSITIVE);
    let mut manifold = Manifold::new(normal);
    for (id, along_a) in [(0, low), (1, high)] {
        let on_b = ends[0] + (ends[1] - ends[0]) * ((along_a - t0) / span);
        let on_a = start_a + axis * along_a;
        let separation = (on_b - on_a).dot(normal) - radius_a - radius_b;
        if separation <= margin {
            let surface_a = on_a + normal * radius_a;
            let surface_b = on_b - normal * radius_b;
            manifold.push(ContactPoint {
                position: 0.5 * (surface_a + surface_b),
                separation,
                id,
            });
        }
    }
    (!manifold.is_empty()).then_some(manifold)
}

/// Deepest overlap, as a fraction of the cylinder's radius and of the axial room between the
/// contact and the nearer end of the cylinder's side, that [`rounded_segment_cylinder_side`]
/// answers: deeper, the shortest way out may be through a cap, which GJK/EPA finds.
const SIDE_DEPTH_FRACTION: f32 = 0.5;

/// What [`rounded_segment_cylinder_side`] finds.
#[derive(Debug, Clone, PartialEq)]
pub enum CylinderSide {
    /// The contact is on the cylinder's side: its manifold, or `None` beyond the margin.
    Side(Option<Manifold>),
    /// The nearest part of the cylinder is a rim or a cap, or the shapes overlap deeply: the
    /// general routine (GJK/EPA and feature clipping) answers.
    Elsewhere,
}

/// A sphere or capsule A (the segment `segment_a` rounded by `radius_a`; a sphere's segment is
/// its centre twice) against cylinder B, where they meet on B's side. The cylinder lies within
/// the capsule of radius `r` about its core's axis (the side's straight stretch, `±(h − r_c)`),
/// so where the closest points `p_A`, `p_B` of A's segment and that axis fall inside the axis,
/// the side is where they meet, exactly: `n = (p_B − p_A)/|p_B − p_A|`,
/// `separation = |p_B − p_A| − r_A − r`. A capsule lying along the side touches along the
/// stretch both share: two points, as capsules side by side (`parallel_capsules`), at most as
/// far as the sharp cylinder's ends, as the cylinder's other contacts are. The
/// closest points of GJK on a round side are only as good as its tolerance, and its normal
/// leans by about the square root of it (1 % on a car's wheel rolling onto a bump).
pub fn rounded_segment_cylinder_side(
    segment_a: [Vec3; 2],
    radius_a: f32,
    b: &Cylinder,
    pose_b: &Pose,
    margin: f32,
) -> CylinderSide {
    let core_half_height = b.half_height() - b.convex_radius();
    let radius = b.radius();
    let axis = pose_b.transform_vector(Vec3::Y);
    let segment_b = [
        pose_b.position - axis * core_half_height,
        pose_b.position + axis * core_half_height,
    ];
    let [start_a, end_a] = segment_a;
    let [start_b, end_b] = segment_b;
    let (direction_a, direction_b) = (end_a - start_a, end_b - start_b);
    let length_b = 2.0 * core_half_height;
    let parallel = direction_a.normalize_or_zero().cross(axis).length() < PARALLEL_SINE
        && direction_a.length_squared() > COINCIDENT_SQUARED;
    // Where along B's axis the contact lies, metres from its start: the middle of the stretch
    // both share for parallel segments, else the closest point.
    let along = if parallel {
        let low = (start_a - start_b).dot(axis);
        let high = (end_a - start_b).dot(axis);
        let (low, high) = (low.min(high).max(0.0), low.max(high).min(length_b));
        if high - low <= 1.0e-3 * length_b {
            return CylinderSide::Elsewhere;
        }
        0.5 * (low + high)
    } else {
        let (_, t) = closest_segment_parameters(start_a, direction_a, start_b, direction_b);
        t * length_b
    };
    let room = along.min(length_b - along);
    if room <= 0.0 {
        return CylinderSide::Elsewhere;
    }
    let on_b = start_b + axis * along;
    let on_a = closest_on_segment(start_a, end_a, on_b);
    let offset = on_b - on_a;
    let distance_squared = offset.length_squared();
    if distance_squared <= COINCIDENT_SQUARED {
        return CylinderSide::Elsewhere;
    }
    let distance = distance_squared.sqrt();
    let normal = offset / distance;
    let separation = distance - radius_a - radius;
    if -separation > SIDE_DEPTH_FRACTION * radius.min(room) {
        return CylinderSide::Elsewhere;
    }
    if parallel {
        // Held at the sharp cylinder's ends, as its features are (`feature_contact`): a wheel
        // across a bar rests on the full width of its tread.
        let sharp = [
            pose_b.position - axis * b.half_height(),
            pose_b.position + axis * b.half_height(),
        ];
        return CylinderSide::Side(parallel_capsules(
            segment_a, radius_a, sharp, radius, normal, margin,
        ));
    }
    let surface_a = on_a + normal * radius_a;
    let surface_b = on_b - normal * radius;
    let point = ContactPoint {
        position: 0.5 * (surface_a + surface_b),
        separation,
        id: 0,
    };
    CylinderSide::Side(single_point(normal, point, margin))
}

/// Sphere A against box B. With the sphere's centre `c` in the box frame: outside the box, the
/// normal runs from `c` to its clamp onto the box; inside, it leaves through the nearest face.
pub fn sphere_box(
    a: &Sphere,
    pose_a: &Pose,
    b: &Cuboid,
    pose_b: &Pose,
    margin: f32,
) -> Option<Manifold> {
    let half = b.half_extents();
    let center = pose_b.inverse_transform_point(pose_a.position);
    let clamped = center.clamp(-half, half);
    let outside = center - clamped;
    let (local_normal_b_to_a, separation, surface_b) =
        if outside.length_squared() > COINCIDENT_SQUARED {
            let distance = outside.length();
            (outside / distance, distance - a.radius(), clamped)
        } else {
            // Inside: the face with the least depth `h_i − |c_i|` is where the sphere leaves.
            let depth = half - center.abs();
            let axis = if depth.x <= depth.y && depth.x <= depth.z {
                0
            } else if depth.y <= depth.z {
                1
            } else {
                2
            };
            let mut normal = Vec3::ZERO;
            normal[axis] = if center[axis] >= 0.0 { 1.0 } else { -1.0 };
            let mut surface = center;
            surface[axis] = normal[axis] * half[axis];
            (normal, -depth[axis] - a.radius(), surface)
        };
    if separation > margin {
        return None;
    }
    // The normal runs from A (the sphere) toward B (the box).
    let normal = -pose_b.transform_vector(local_normal_b_to_a);
    let surface_b = pose_b.transform_point(surface_b);
    let surface_a = pose_a.position + normal * a.radius();
    let mut manifold = Manifold::new(normal);
    manifold.push(ContactPoint {
        position: 0.5 * (surface_a + surface_b),
        separation,
        id: 0,
    });
    Some(manifold)
}
