//! Manifolds for the convex pairs with no closed form and no separating-axis routine: capsules
//! and cylinders against boxes, hulls, cylinders and capsules, and spheres against cylinders and
//! hulls.
//!
//! GJK (EPA when the cores overlap) gives the deepest point and the normal. Then each shape's
//! supporting feature along that normal (a face polygon, a segment, or a point) is found; when one
//! of them is a face nearly perpendicular to the normal, the other feature is clipped against it,
//! so a capsule or cylinder lying flat rests on two or more points instead of one.

use std::f32::consts::TAU;

use super::clipping::{clip_polygon, clip_segment, ClipFeature, ClipVertex};
use super::closed_form::parallel_capsules;
use super::epa::{ContactInfo, Polytope};
use super::gjk::SimplexCache;
use super::manifold::{ContactPoint, Manifold, MAX_MANIFOLD_POINTS};
use super::polyhedron::Polyhedron;
use super::reduction::reduce_contacts;
use super::PosedCore;
use crate::math::{Pose, Vec3};
use crate::shape::Shape;

/// Rim points of a cylinder cap used as its face polygon when the cap is the reference face, the
/// region the other shape's feature is clipped to.
const CAP_VERTICES: usize = 8;

/// Every other of the [`CAP_VERTICES`] rim points, a square fixed in the cylinder's frame, is what
/// a cap offers as the incident feature (against a shape's face; a triangle clips the whole rim,
/// see [`manifold_from_features`]). A cap resting whole on a face then gives the same four
/// points, and ids, however it wobbles; with all eight, more than four would touch, and the
/// reduction to four, which starts from the deepest point, would pick a different subset whenever
/// the cylinder tilts a little.
const CAP_SQUARE_CORNERS: usize = 4;

/// The corner of a cap's square nearest the rim point farthest along the query direction moves
/// onto that point when the point reaches farther by more than this, metres (the 1 mm of
/// [`DUPLICATE_DISTANCE`]). A cap lying flat keeps its square; a tilted one reaches its deepest
/// spot, under the id of the corner it replaces, so its ids stay the same set.
const CORNER_SNAP_DISTANCE: f32 = 1.0e-3;

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

/// Two side lines (a cylinder's side, a capsule's segment) touch along their length when the sine
/// of the angle between them is at most this (11°, as [`FACE_COSINE`]): each end of their
/// overlap is then a point, with its own separation, so a wheel across a bar is held at both
/// edges of its tread and not at one point GJK happens to pick between them, which a mirrored
/// wheel would get on its other side.
const PARALLEL_LINES_SINE: f32 = 0.2;

/// When both supporting features are faces, the better aligned with the contact normal is the
/// reference only when it is better by more than this cosine difference (as when one face is
/// tilted 0.8° from a normal that the other matches). Faces resting flat on each other are aligned
/// equally but for rounding, which would otherwise pick the reference, and so the contact ids,
/// afresh at every step: the larger face is then the reference (see [`LARGER_FACE_RATIO`]).
const REFERENCE_PREFERENCE: f32 = 1.0e-4;

/// Between two equally aligned faces, B's is the reference only when its area exceeds A's by this
/// factor, so that faces of equal size (up to rounding) always pick A's. The larger face holds the
/// smaller one's corners, which are then kept whole, with their ids, rather than cut into
/// crossings.
const LARGER_FACE_RATIO: f32 = 1.01;

/// The GJK/EPA point joins clipped points only when it is deeper than all of them by more than
/// this, metres: then the clipped feature (a cylinder cap's polygon) missed the deepest spot.
const DUPLICATE_DISTANCE: f32 = 1.0e-3;

/// The id of the deepest point found by GJK/EPA.
pub(crate) const DEEPEST_POINT_ID: u32 = u32::MAX;

/// Whether a point's id (as [`clip_against_face`] writes it) names a vertex of shape B's face
/// lying inside shape A's reference face 0: a point of shape B itself, the same wherever A's
/// face is. A mesh's triangles are each A's face 0, so such a point found by one triangle or by
/// its neighbour is the same point.
pub(crate) fn is_vertex_of_b_on_face(id: u32) -> bool {
    id != DEEPEST_POINT_ID && id >> 23 == 0 && ClipFeature::is_incident_vertex_key(id as u16)
}

/// A shape's supporting feature along a direction, in world space, on the shape's core.
pub(crate) struct Feature {
    points: [Vec3; MAX_FEATURE_VERTICES],
    len: usize,
    /// Outward unit normal when the feature is a face (three or more points).
    face_normal: Vec3,
    /// Which face or segment of the shape it is; part of the contact ids.
    index: u32,
    /// For a cylinder cap, the polygon clipped when the cap is the incident feature: a square of
    /// every other rim point (see [`CAP_SQUARE_CORNERS`]).
    cap_square: Option<[Vec3; CAP_SQUARE_CORNERS]>,
}

impl Feature {
    fn new(index: u32) -> Self {
        Self {
            points: [Vec3::ZERO; MAX_FEATURE_VERTICES],
            len: 0,
            face_normal: Vec3::ZERO,
            index,
            cap_square: None,
        }
    }

    /// The feature of `points` (one point, a segment, or a convex polygon counter-clockwise about
    /// `face_normal`, which is ignored for fewer than three points), named `index` in ids.
    pub(crate) fn of_points(index: u32, points: &[Vec3], face_normal: Vec3) -> Self {
        let mut feature = Self::new(index);
        for &point in points {
            feature.push(point);
        }
        if feature.is_face() {
            feature.face_normal = face_normal;
        }
        feature
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

    /// The points to clip when the feature is the incident one against a shape's face: a cap's
    /// square, or the feature. Against a triangle the feature is clipped whole (see
    /// [`manifold_from_features`]).
    fn incident_points(&self) -> &[Vec3] {
        self.cap_square
            .as_ref()
            .map_or(self.points(), |square| square.as_slice())
    }

    /// Area of the polygon (zero unless the feature is a face).
    fn area(&self) -> f32 {
        let points = self.points();
        let Some(&first) = points.first() else {
            return 0.0;
        };
        let doubled: f32 = points
            .windows(2)
            .skip(1)
            .map(|edge| {
                (edge[0] - first)
                    .cross(edge[1] - first)
                    .dot(self.face_normal)
            })
            .sum();
        0.5 * doubled.abs()
    }

    fn is_face(&self) -> bool {
        self.len >= 3
    }
}

/// The supporting feature of `shape` at `pose` along world `direction` (unit).
pub(crate) fn supporting_feature(shape: &Shape, pose: &Pose, direction: Vec3) -> Feature {
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
            // The sharp cylinder's feature moved in by the convex radius along the direction:
            // with the radius added back along the normal, its clipped points are the sharp
            // cylinder's. Lying flat, the rounded cylinder touches there too; tilted, the sharp
            // rim reaches a little deeper than the rounded one, and no clipped point is deeper
            // than GJK/EPA's depth (see `SeparationLimits`).
            let inward = -direction * cylinder.convex_radius();
            let place = |point: Vec3| pose.transform_point(point) + inward;
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
                let rim: [Vec3; CAP_VERTICES] = std::array::from_fn(|corner| {
                    let angle = TAU * corner as f32 / CAP_VERTICES as f32;
                    Vec3::new(radius * angle.cos(), cap_y, winding * radius * angle.sin())
                });
                for point in rim {
                    feature.push(place(point));
                }
                let step = CAP_VERTICES / CAP_SQUARE_CORNERS;
                let mut square: [Vec3; CAP_SQUARE_CORNERS] =
                    std::array::from_fn(|corner| rim[corner * step]);
                let farthest = radial + Vec3::new(0.0, cap_y, 0.0);
                let nearest = (0..CAP_SQUARE_CORNERS)
                    .max_by(|&i, &j| square[i].dot(radial).total_cmp(&square[j].dot(radial)));
                if let Some(nearest) = nearest {
                    if (farthest - square[nearest]).dot(local) > CORNER_SNAP_DISTANCE {
                        square[nearest] = farthest;
                    }
                }
                feature.cap_square = Some(square.map(place));
                feature.face_normal = pose.transform_vector(Vec3::new(0.0, cap_y.signum(), 0.0));
                feature
            } else if local.y.abs() <= SIDE_SINE {
                let mut feature = Feature::new(0);
                feature.push(place(radial - Vec3::new(0.0, half_height, 0.0)));
                feature.push(place(radial + Vec3::new(0.0, half_height, 0.0)));
                feature
            } else {
                let mut feature = Feature::new(3);
                feature.push(place(radial + Vec3::new(0.0, cap_y, 0.0)));
                feature
            }
        }
        Shape::Cuboid(_) | Shape::ConvexHull(_) => match Polyhedron::from_shape(shape) {
            Some(polyhedron) => polyhedron_face(&polyhedron, pose, local),
            None => Feature::new(0),
        },
        Shape::Sphere(_)
        | Shape::Compound(_)
        | Shape::Halfspace(_)
        | Shape::TriMesh(_)
        | Shape::HeightField(_) => {
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
///
/// When both supporting features are faces within 11° of the GJK/EPA normal, the better aligned
/// one is the reference, or, when they are aligned alike (within `REFERENCE_PREFERENCE`), the
/// larger one; no clipped point is reported deeper than the GJK/EPA depth. A cylinder's cap is an
/// octagon of rim points as the reference face and a square of every other one as the incident
/// face, its corner nearest the deepest rim point moved there when the cap is tilted (see
/// `CORNER_SNAP_DISTANCE`): a cylinder standing or wobbling on a face keeps the same four ids.
/// EPA grows `polytope`, scratch space reused from call to call; GJK starts from `simplex`, last
/// query's between the same shapes (or an empty one), and leaves its own there.
pub fn collide_features(
    polytope: &mut Polytope,
    shape_a: &Shape,
    pose_a: &Pose,
    shape_b: &Shape,
    pose_b: &Pose,
    margin: f32,
    simplex: &mut SimplexCache,
) -> Option<Manifold> {
    // Solved with A's origin at the world origin, then moved back: far from the origin a world
    // coordinate is rounded to a millimetre (at 10 km), which the heights of clipped points would
    // pick up, a cylinder's moved in by its convex radius most of all.
    let origin = pose_a.position;
    let pose_a = Pose::new(Vec3::ZERO, pose_a.rotation);
    let pose_b = Pose::new(pose_b.position - origin, pose_b.rotation);
    let core_a = PosedCore::new(shape_a, &pose_a);
    let core_b = PosedCore::new(shape_b, &pose_b);
    let deepest = polytope.contact_from(&core_a, &core_b, margin, simplex)?;
    let feature_a = supporting_feature(shape_a, &pose_a, deepest.normal);
    let feature_b = supporting_feature(shape_b, &pose_b, -deepest.normal);
    let radii = [shape_a.core_radius(), shape_b.core_radius()];
    Some(
        manifold_from_features(&deepest, &feature_a, &feature_b, radii, margin, None)
            .translated(origin),
    )
}

/// The manifold of two shapes whose deepest point is `deepest`, from their supporting features
/// along its normal (`feature_a` along `n`, `feature_b` along `−n`) and their rounding radii:
/// the feature clipping of [`collide_features`], for any pair of convex parts, triangles
/// included. `triangle_sides` is `Some(sides)` when A is a triangle: its face, when aligned with
/// the normal, is then always the reference (the larger face of B would make the triangle's
/// corners and edge crossings the points), and the points made by its sides in `sides` (bit `j`
/// for the side from its vertex `j` to `j + 1`: the edges it shares with neighbours on one plane)
/// are dropped, since the surface goes on beyond them. Against a triangle a cylinder's cap is
/// clipped as its whole rim polygon, not its square: the cap often spans several triangles bent
/// against each other (a dip), each triangle keeps only what lies over it, and the rim between
/// the square's corners is then what holds the cap up. The mesh's merged manifold is reduced to
/// four points by their place on the surface (`mesh_contact`), not from the deepest one, so its
/// ids stay steady without the square.
pub(crate) fn manifold_from_features(
    deepest: &ContactInfo,
    feature_a: &Feature,
    feature_b: &Feature,
    radii: [f32; 2],
    margin: f32,
    triangle_sides: Option<u8>,
) -> Manifold {
    let alignment_a = feature_a.face_normal.dot(deepest.normal);
    let alignment_b = -feature_b.face_normal.dot(deepest.normal);
    let use_a = feature_a.is_face() && alignment_a >= FACE_COSINE;
    let use_b = feature_b.is_face() && alignment_b >= FACE_COSINE;
    let limits = SeparationLimits {
        deepest: deepest.separation,
        margin,
    };
    let prefer_b = match (use_a, use_b) {
        (true, _) if triangle_sides.is_some() => false,
        (true, true) if (alignment_a - alignment_b).abs() <= REFERENCE_PREFERENCE => {
            feature_b.area() > LARGER_FACE_RATIO * feature_a.area()
        }
        (true, true) => alignment_b > alignment_a,
        _ => use_b && !use_a,
    };
    let clipped = if use_a && !prefer_b {
        let dropped_sides = triangle_sides.unwrap_or(0);
        let incident = if triangle_sides.is_some() {
            feature_b.points()
        } else {
            feature_b.incident_points()
        };
        clip_against_face(
            feature_a,
            feature_b,
            incident,
            radii,
            0,
            &limits,
            dropped_sides,
        )
    } else if use_b {
        let incident = feature_a.incident_points();
        let radii = [radii[1], radii[0]];
        clip_against_face(feature_b, feature_a, incident, radii, 1, &limits, 0)
            .map(Manifold::flipped)
    } else if triangle_sides.is_none() {
        lines_along_each_other(deepest, feature_a, feature_b, radii, &limits)
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
        add_deepest_point(&mut manifold, deepest);
    }
    manifold
}

/// The two-point manifold of two side lines lying along each other
/// ([`PARALLEL_LINES_SINE`]), on the shapes' cores of roundings `radii`, with the ids of the
/// features and each end; `None` unless both features are lines and overlap along their length.
fn lines_along_each_other(
    deepest: &ContactInfo,
    feature_a: &Feature,
    feature_b: &Feature,
    radii: [f32; 2],
    limits: &SeparationLimits,
) -> Option<Manifold> {
    let (&[start_a, end_a], &[start_b, end_b]) = (feature_a.points(), feature_b.points()) else {
        return None;
    };
    let (axis_a, axis_b) = (
        (end_a - start_a).normalize_or_zero(),
        (end_b - start_b).normalize_or_zero(),
    );
    if axis_a.cross(axis_b).length() > PARALLEL_LINES_SINE {
        return None;
    }
    let mut manifold = parallel_capsules(
        [start_a, end_a],
        radii[0],
        [start_b, end_b],
        radii[1],
        deepest.normal,
        limits.margin,
    )?;
    let features = ((feature_a.index & 0x7F) << 23) | ((feature_b.index & 0x7F) << 16);
    for point in manifold.points_mut() {
        point.separation = point.separation.max(limits.deepest);
        point.id |= features;
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

/// The range of separations a clipped point may take.
struct SeparationLimits {
    /// The separation GJK/EPA measured along the contact normal: no point is deeper.
    deepest: f32,
    /// Points farther apart than this are dropped.
    margin: f32,
}

/// Clips the `incident` feature's polygon `incident_points` against the `reference` face, both on
/// their shapes' cores, of roundings `radii` (reference, incident). The manifold normal is the
/// reference face's normal, pointing from the reference shape toward the incident one; each
/// point's separation is its incident surface point's height above the reference surface (the
/// face's plane moved out by its rounding: a rounded cylinder's flat cap), but never deeper than
/// `limits.deepest`: the reference
/// normal may be up to 11° off the contact normal, along which the shapes overlap least, and
/// would overstate the depth of a point near the reference face's rim. `side` (0: A holds the
/// reference face, 1: B) and the feature indices go into the ids. Points made by the reference's
/// sides in `dropped_sides` (crossings of a side, corners between two such sides) are left out.
fn clip_against_face(
    reference: &Feature,
    incident: &Feature,
    incident_points: &[Vec3],
    radii: [f32; 2],
    side: u32,
    limits: &SeparationLimits,
    dropped_sides: u8,
) -> Option<Manifold> {
    let normal = reference.face_normal;
    let plane_point = reference.points[0];
    let [reference_radius, incident_radius] = radii;
    let mut candidates = [ContactPoint::default(); 2 * MAX_FEATURE_VERTICES];
    let mut count = 0;
    let dropped = |side: u8| side < 8 && dropped_sides & (1 << side) != 0;
    let mut offer = |vertex: &ClipVertex| {
        let made_by_dropped_sides = match vertex.feature {
            ClipFeature::IncidentVertex(_) => false,
            ClipFeature::EdgeCrossing { side, .. } => dropped(side),
            ClipFeature::SideCorner { first, second } => dropped(first) && dropped(second),
        };
        if made_by_dropped_sides {
            return;
        }
        let height = normal.dot(vertex.position - plane_point) - reference_radius - incident_radius;
        let separation = height.max(limits.deepest);
        if separation <= limits.margin && count < candidates.len() {
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
    match *incident_points {
        [] | [_] => return None,
        [start, end] => {
            for vertex in clip_segment(start, end, reference.points(), normal)? {
                offer(&vertex);
            }
        }
        _ => {
            let polygon = clip_polygon(incident_points, reference.points(), normal);
            for vertex in polygon.vertices() {
                offer(vertex);
            }
        }
    }
    (count > 0).then(|| reduce_contacts(normal, &candidates[..count]))
}
