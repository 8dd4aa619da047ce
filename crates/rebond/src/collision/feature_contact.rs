//! Manifolds for the convex pairs with no closed form and no separating-axis routine: capsules
//! and cylinders against boxes, hulls, cylinders and capsules, and spheres against cylinders and
//! hulls.
//!
//! GJK (EPA when the cores overlap) gives the deepest point and the normal. Then each shape's
//! supporting feature along that normal (a face polygon, a segment, or a point) is found; when one
//! of them is a face nearly perpendicular to the normal, the other feature is clipped against it,
//! so a capsule or cylinder lying flat rests on two or more points instead of one.

use std::f32::consts::TAU;

use super::clipping::{clip_polygon, clip_segment, reduce_contacts, ClipVertex};
use super::epa::{contact, ContactInfo};
use super::manifold::{ContactPoint, Manifold, MAX_MANIFOLD_POINTS};
use super::polyhedron::Polyhedron;
use super::PosedCore;
use crate::math::{Pose, Vec3};
use crate::shape::Shape;

/// Rim points of a cylinder cap used as its face polygon.
const CAP_VERTICES: usize = 8;

/// Most vertices of a supporting face used for clipping (larger hull faces keep their first ones,
/// a convex polygon inside the face).
const MAX_FEATURE_VERTICES: usize = 16;

/// A cylinder offers its cap as a face when the cosine between its axis and the direction is at
/// least this (10°).
const CAP_COSINE: f32 = 0.985;

/// A cylinder offers its side line, or a capsule its segment, when the sine between the axis and
/// the direction's normal plane is at most this (30°); steeper, only the end point touches.
const SIDE_SINE: f32 = 0.5;

/// A face is used as the reference for clipping only when its normal is within this cosine (11°)
/// of the contact normal: otherwise the contact is on an edge or vertex and one point is right.
const FACE_COSINE: f32 = 0.98;

/// The GJK/EPA point joins clipped points only when it is deeper than all of them by more than
/// this, metres: then the clipped feature (a cylinder cap's polygon) missed the deepest spot.
const DUPLICATE_DISTANCE: f32 = 1.0e-3;

/// The id of the deepest point found by GJK/EPA.
const DEEPEST_POINT_ID: u32 = u32::MAX;

/// A shape's supporting feature along a direction, in world space, on the shape's core.
struct Feature {
    points: [Vec3; MAX_FEATURE_VERTICES],
    len: usize,
    /// Outward unit normal when the feature is a face (three or more points).
    face_normal: Vec3,
    /// Which face or segment of the shape it is; part of the contact ids.
    index: u32,
}

impl Feature {
    fn new(index: u32) -> Self {
        Self {
            points: [Vec3::ZERO; MAX_FEATURE_VERTICES],
            len: 0,
            face_normal: Vec3::ZERO,
            index,
        }
    }

    fn push(&mut self, point: Vec3) {
        if self.len < MAX_FEATURE_VERTICES {
            self.points[self.len] = point;
            self.len += 1;
        }
    }

    fn points(&self) -> &[Vec3] {
        &self.points[..self.len]
    }

    fn is_face(&self) -> bool {
        self.len >= 3
    }
}

/// The supporting feature of `shape` at `pose` along world `direction` (unit).
fn supporting_feature(shape: &Shape, pose: &Pose, direction: Vec3) -> Feature {
    let local = pose.inverse_transform_vector(direction);
    match shape {
        Shape::Capsule(capsule) => {
            let [bottom, top] = capsule.segment();
            if local.y.abs() <= SIDE_SINE {
                let mut feature = Feature::new(0);
                feature.push(pose.transform_point(bottom));
                feature.push(pose.transform_point(top));
                feature
            } else {
                let (index, end) = if local.y > 0.0 { (2, top) } else { (1, bottom) };
                let mut feature = Feature::new(index);
                feature.push(pose.transform_point(end));
                feature
            }
        }
        Shape::Cylinder(cylinder) => {
            let (radius, half_height) = (cylinder.radius(), cylinder.half_height());
            let cap_y = if local.y >= 0.0 {
                half_height
            } else {
                -half_height
            };
            let radial = Vec3::new(local.x, 0.0, local.z).normalize_or_zero() * radius;
            if local.y.abs() >= CAP_COSINE {
                // Counter-clockwise about the cap's outward normal ±Y.
                let winding = if local.y >= 0.0 { -1.0 } else { 1.0 };
                let mut feature = Feature::new(if local.y >= 0.0 { 2 } else { 1 });
                for corner in 0..CAP_VERTICES {
                    let angle = TAU * corner as f32 / CAP_VERTICES as f32;
                    let rim =
                        Vec3::new(radius * angle.cos(), cap_y, winding * radius * angle.sin());
                    feature.push(pose.transform_point(rim));
                }
                feature.face_normal = pose.transform_vector(Vec3::new(0.0, cap_y.signum(), 0.0));
                feature
            } else if local.y.abs() <= SIDE_SINE {
                let mut feature = Feature::new(0);
                feature.push(pose.transform_point(radial - Vec3::new(0.0, half_height, 0.0)));
                feature.push(pose.transform_point(radial + Vec3::new(0.0, half_height, 0.0)));
                feature
            } else {
                let mut feature = Feature::new(3);
                feature.push(pose.transform_point(radial + Vec3::new(0.0, cap_y, 0.0)));
                feature
            }
        }
        Shape::Cuboid(_) | Shape::ConvexHull(_) => match Polyhedron::from_shape(shape) {
            Some(polyhedron) => polyhedron_face(&polyhedron, pose, local),
            None => Feature::new(0),
        },
        Shape::Sphere(_) | Shape::Compound(_) | Shape::Halfspace(_) => {
            let mut feature = Feature::new(0);
            feature.push(pose.position);
            feature
        }
    }
}

/// The face of `polyhedron` whose outward normal is most aligned with local `direction`.
fn polyhedron_face(polyhedron: &Polyhedron, pose: &Pose, direction: Vec3) -> Feature {
    let best = (0..polyhedron.face_count())
        .map(|face| (face, polyhedron.face_plane(face).normal.dot(direction)))
        .fold(None, |best: Option<(usize, f32)>, candidate| match best {
            Some(current) if current.1 >= candidate.1 => Some(current),
            _ => Some(candidate),
        });
    let Some((face, _)) = best else {
        return Feature::new(0);
    };
    let mut feature = Feature::new(face as u32);
    for corner in 0..polyhedron.face_vertex_count(face) {
        feature.push(pose.transform_point(polyhedron.face_vertex(face, corner)));
    }
    feature.face_normal = pose.transform_vector(polyhedron.face_plane(face).normal);
    feature
}

/// The contact of convex shapes A and B (capsules, cylinders, spheres, boxes or hulls; never
/// compounds or halfspaces) with the normal from A toward B, or `None` beyond `margin`.
pub fn collide_features(
    shape_a: &Shape,
    pose_a: &Pose,
    shape_b: &Shape,
    pose_b: &Pose,
    margin: f32,
) -> Option<Manifold> {
    let core_a = PosedCore {
        shape: shape_a,
        pose: pose_a,
    };
    let core_b = PosedCore {
        shape: shape_b,
        pose: pose_b,
    };
    let deepest = contact(&core_a, &core_b, margin)?;
    let feature_a = supporting_feature(shape_a, pose_a, deepest.normal);
    let feature_b = supporting_feature(shape_b, pose_b, -deepest.normal);
    let alignment_a = feature_a.face_normal.dot(deepest.normal);
    let alignment_b = -feature_b.face_normal.dot(deepest.normal);
    let use_a = feature_a.is_face() && alignment_a >= FACE_COSINE;
    let use_b = feature_b.is_face() && alignment_b >= FACE_COSINE;
    let clipped = if use_a && (!use_b || alignment_a >= alignment_b) {
        clip_against_face(&feature_a, &feature_b, shape_b.core_radius(), 0, margin)
    } else if use_b {
        clip_against_face(&feature_b, &feature_a, shape_a.core_radius(), 1, margin)
            .map(Manifold::flipped)
    } else {
        None
    };
    let mut manifold = clipped.unwrap_or_else(|| Manifold::new(deepest.normal));
    let deepest_clipped_separation = manifold
        .points()
        .iter()
        .map(|point| point.separation)
        .fold(f32::INFINITY, f32::min);
    if deepest.separation < deepest_clipped_separation - DUPLICATE_DISTANCE {
        add_deepest_point(&mut manifold, &deepest);
    }
    Some(manifold)
}

fn midpoint(deepest: &ContactInfo) -> Vec3 {
    0.5 * (deepest.point_a + deepest.point_b)
}

/// Adds the GJK/EPA point, replacing the shallowest point when the manifold is full.
fn add_deepest_point(manifold: &mut Manifold, deepest: &ContactInfo) {
    let point = ContactPoint {
        position: midpoint(deepest),
        separation: deepest.separation,
        id: DEEPEST_POINT_ID,
    };
    if manifold.len() < MAX_MANIFOLD_POINTS {
        manifold.push(point);
        return;
    }
    let shallowest = manifold
        .points_mut()
        .iter_mut()
        .max_by(|a, b| a.separation.total_cmp(&b.separation));
    if let Some(shallowest) = shallowest {
        if shallowest.separation > point.separation {
            *shallowest = point;
        }
    }
}

/// Clips the `incident` feature (on a shape of rounding `incident_radius`) against the
/// `reference` face. The manifold normal is the reference face's normal, pointing from the
/// reference shape toward the incident one; each point's separation is its incident surface
/// point's height above the reference plane. `side` (0: A holds the reference face, 1: B) and
/// the feature indices go into the ids.
fn clip_against_face(
    reference: &Feature,
    incident: &Feature,
    incident_radius: f32,
    side: u32,
    margin: f32,
) -> Option<Manifold> {
    let normal = reference.face_normal;
    let plane_point = reference.points[0];
    let mut candidates = [ContactPoint::default(); 2 * MAX_FEATURE_VERTICES];
    let mut count = 0;
    let mut offer = |vertex: &ClipVertex| {
        let separation = normal.dot(vertex.position - plane_point) - incident_radius;
        if separation <= margin && count < candidates.len() {
            candidates[count] = ContactPoint {
                position: vertex.position - normal * (incident_radius + 0.5 * separation),
                separation,
                id: (side << 30)
                    | ((reference.index & 0x7F) << 23)
                    | ((incident.index & 0x7F) << 16)
                    | u32::from(vertex.feature.key()),
            };
            count += 1;
        }
    };
    match incident.len {
        0 | 1 => return None,
        2 => {
            let [start, end] = [incident.points[0], incident.points[1]];
            for vertex in clip_segment(start, end, reference.points(), normal)? {
                offer(&vertex);
            }
        }
        _ => {
            let polygon = clip_polygon(incident.points(), reference.points(), normal);
            for vertex in polygon.vertices() {
                offer(vertex);
            }
        }
    }
    (count > 0).then(|| reduce_contacts(normal, &candidates[..count]))
}
