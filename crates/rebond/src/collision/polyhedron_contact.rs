//! Contact manifolds between convex polyhedra (boxes and convex hulls) by the separating axis
//! test and clipping.
//!
//! The candidate axes (`separating_axis`) are the face normals of A, those of B, and the cross
//! products of an edge of A with an edge of B whose arcs cross on the Gauss map. If an axis
//! separates the shapes by more than the margin there is no contact. Otherwise the axis of least
//! overlap, with a bias toward faces and toward A (see [`collide_polyhedra`]), gives either a face
//! contact (the other shape's most anti-parallel face through its deepest vertex clipped against
//! the reference face, see [`crate::collision::clipping`]) or an edge contact (one point between
//! the two edges). Shapes apart whose closest points no axis measures (a vertex near a vertex or
//! an edge) get one point between their closest points, found by GJK.
//!
//! Two boxes take shortcuts with the same results up to rounding: bounding spheres apart beyond
//! the margin end the test first, and a face contact is clipped in the reference box's frame
//! (`box_face_contact`).

use crate::collision::clipping::{
    clip_by_sides, clip_polygon_within, ClipFeature, ClipPolygon, MAX_CLIP_VERTICES,
    MAX_POLYGON_VERTICES,
};
use crate::collision::gjk;
use crate::collision::manifold::{ContactPoint, Manifold};
use crate::collision::polyhedron::{
    box_face_against, box_face_loop, box_face_sides, box_vertex, FacePlane, Frame, Polyhedron,
    Topology, BOX_FACE_LOOPS,
};
use crate::collision::reduction::{reduce_contacts_on_face, Surface};
use crate::collision::separating_axis::{
    best_face_axis, edge_query, EdgeAxis, FaceAxis, ABSOLUTE_TOLERANCE,
};
use crate::collision::SupportMap;
use crate::math::{Pose, Vec3};

/// B's best face replaces A's as the reference only when its separation is larger by this
/// fraction of A's separation (in absolute value) plus [`ABSOLUTE_TOLERANCE`].
const FACE_RELATIVE_TOLERANCE: f32 = 0.05;

/// An edge pair replaces the chosen reference face only when its separation is larger by this
/// fraction of the face's separation (in absolute value) plus [`ABSOLUTE_TOLERANCE`]: face
/// contacts give several points and rest better.
const EDGE_RELATIVE_TOLERANCE: f32 = 0.1;

/// Squared length below which an edge counts as a point when closest points are computed, m².
const DEGENERATE_EDGE_SQUARED: f32 = 1.0e-12;

/// A contact built on an axis is kept for overlapping shapes only when its deepest point reaches
/// the penetration depth (the best axis's separation) to within this, metres; and for shapes
/// apart only when its deepest point is their distance to within this. Above the f32 rounding of
/// the clipped points (1e-6 m) and GJK's precision on polyhedra a few metres across (1e-5 of the
/// problem's size), below the 0.1 mm to which contact depths are checked.
const DEPTH_TOLERANCE: f32 = 5.0e-5;

/// The angle, radians, between a reference face's first edge and the direction along which its
/// contact points are first picked ([`reduce_contacts_on_face`]): 15°, away from the symmetry
/// axes of the squares, hexagons and octagons that clipping faces of boxes and prisms makes, where
/// two points would be equally far along it.
const REDUCTION_ANGLE: f32 = 0.261_799_4;

/// The id of the one point of a contact made from the closest points of shapes apart (no edge
/// contact takes it while hulls have fewer than 32 767 edges).
const CLOSEST_POINTS_ID: u32 = u32::MAX;

/// A polyhedron placed in the world, for GJK.
#[derive(Debug, Clone, Copy)]
struct PosedPolyhedron<'p, 'a> {
    polyhedron: &'p Polyhedron<'a>,
    frame: Frame,
}

impl SupportMap for PosedPolyhedron<'_, '_> {
    fn support(&self, direction: Vec3) -> Vec3 {
        let local = self.frame.inverse_vector(direction);
        self.frame.point(self.polyhedron.support(local))
    }
}

/// An axis the contact can be built on.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
enum ContactAxis {
    /// A face of A is the reference.
    FaceOfA(FaceAxis),
    /// A face of B is the reference.
    FaceOfB(FaceAxis),
    /// An edge of A against an edge of B.
    Edges(EdgeAxis),
}

impl ContactAxis {
    fn separation(&self) -> f32 {
        match self {
            ContactAxis::FaceOfA(face) | ContactAxis::FaceOfB(face) => face.separation,
            ContactAxis::Edges(edge) => edge.separation,
        }
    }

    /// The axis in the world, pointing from A to B.
    fn world_normal(
        &self,
        a: &Polyhedron,
        world_a: &Frame,
        b: &Polyhedron,
        world_b: &Frame,
    ) -> Vec3 {
        match self {
            ContactAxis::FaceOfA(face) => world_a.vector(a.face_plane(face.face).normal),
            ContactAxis::FaceOfB(face) => -world_b.vector(b.face_plane(face.face).normal),
            ContactAxis::Edges(edge) => world_a.vector(edge.axis),
        }
    }
}

/// Whether `candidate` beats `incumbent` by more than the tolerance `relative · |incumbent| +`
/// [`ABSOLUTE_TOLERANCE`].
fn clearly_larger(candidate: f32, incumbent: f32, relative: f32) -> bool {
    candidate > incumbent + relative * incumbent.abs() + ABSOLUTE_TOLERANCE
}

/// The contact manifold between polyhedra `a` at `pose_a` and `b` at `pose_b`, with the normal
/// pointing from A to B; `None` when they are apart by more than `margin` metres, when either
/// has no face, or when clipping leaves no point (only for degenerate faces, of zero area or of
/// more than [`MAX_POLYGON_VERTICES`] corners, of which a subset is clipped).
///
/// The axis of least overlap is chosen with a bias so that the choice holds still while bodies
/// jiggle: B's best face is the reference only if its separation beats A's by 5 % (of A's, in
/// absolute value) plus 0.5 mm, and the best edge pair is used instead of that face only if its
/// separation beats the face's by 10 % plus 0.5 mm. The chosen axis thus trails the true
/// least-overlap axis by at most one of these tolerances. While the shapes overlap, the best
/// axis's separation is the penetration depth; should the chosen axis's contact not reach it
/// (within `DEPTH_TOLERANCE`) or give no point, the best axis makes the contact. While they are
/// apart, the axes' separations may fall short of the distance, which GJK then measures: a contact
/// on the chosen or the best axis is kept only if its deepest point is that distance (within
/// `DEPTH_TOLERANCE`), else the contact is one point midway between the closest points, with
/// the direction between them as the normal and the id `CLOSEST_POINTS_ID`.
///
/// Face contact: the reference face's side planes clip the incident face (the face of the other
/// body, among those through its vertex deepest below the reference plane, most anti-parallel to
/// the reference normal); points whose separation from the reference plane is at most `margin`
/// are kept and reduced to four ([`reduce_contacts_on_face`], along a direction fixed to the
/// reference face, `REDUCTION_ANGLE` from its first edge). Each point sits halfway between the
/// incident point and its projection on the reference plane. Its id packs, from the top bit down:
/// 0, whether B holds the reference face, the reference and incident face indices (7 bits each,
/// wrapping) and the [`ClipFeature::key`] of the clipped point.
///
/// Edge contact: one point halfway between the closest points of the two edges; its id is 1 in
/// the top bit, then 15 bits of A's edge index and 16 bits of B's (wrapping).
pub fn collide_polyhedra(
    a: &Polyhedron,
    pose_a: &Pose,
    b: &Polyhedron,
    pose_b: &Pose,
    margin: f32,
) -> Option<Manifold> {
    if a.face_count() == 0 || b.face_count() == 0 {
        return None;
    }
    let b_in_a = Frame::relative(pose_a, pose_b);
    let face_a = best_face_axis(a, b, &b_in_a);
    if face_a.separation > margin {
        return None;
    }
    let a_in_b = b_in_a.inverse();
    let face_b = best_face_axis(b, a, &a_in_b);
    if face_b.separation > margin {
        return None;
    }
    let face = if clearly_larger(
        face_b.separation,
        face_a.separation,
        FACE_RELATIVE_TOLERANCE,
    ) {
        ContactAxis::FaceOfB(face_b)
    } else {
        ContactAxis::FaceOfA(face_a)
    };
    // An edge pair matters only if it beats the kept face (below, an edge pair is chosen or
    // best only then), so edges that cannot are skipped.
    let edge = edge_query(a, b, &b_in_a, &a_in_b, face.separation());
    if edge.is_some_and(|edge| edge.separation > margin) {
        return None;
    }

    let posed_a = PosedPolyhedron {
        polyhedron: a,
        frame: Frame::from_pose(pose_a),
    };
    let posed_b = PosedPolyhedron {
        polyhedron: b,
        frame: Frame::from_pose(pose_b),
    };
    let chosen = match edge {
        Some(edge)
            if clearly_larger(edge.separation, face.separation(), EDGE_RELATIVE_TOLERANCE) =>
        {
            ContactAxis::Edges(edge)
        }
        _ => face,
    };
    let mut best = ContactAxis::FaceOfA(face_a);
    for candidate in
        std::iter::once(ContactAxis::FaceOfB(face_b)).chain(edge.map(ContactAxis::Edges))
    {
        if candidate.separation() > best.separation() {
            best = candidate;
        }
    }

    let contact = |axis: ContactAxis| match axis {
        ContactAxis::FaceOfA(face) => {
            face_contact(&posed_a, face.face, &posed_b, &b_in_a, false, margin)
        }
        ContactAxis::FaceOfB(face) => {
            face_contact(&posed_b, face.face, &posed_a, &a_in_b, true, margin)
        }
        ContactAxis::Edges(edge) => edge_contact(&posed_a, &posed_b, &edge, margin),
    };
    if best.separation() > 0.0 {
        return apart_contact(&posed_a, &posed_b, chosen, best, margin, contact);
    }
    // Overlapping, the best axis's separation is the penetration depth. The axis kept by the
    // bias may fall short of it where it trails the best one (its deepest vertex lies outside the
    // kept face's side planes) or clip to nothing (two edges crossing near a corner): the best
    // axis, whose deepest vertex always lies inside its face, then makes the contact.
    match contact(chosen) {
        Some(manifold)
            if best == chosen
                || manifold.deepest_separation() <= best.separation() + DEPTH_TOLERANCE =>
        {
            Some(manifold)
        }
        kept => contact(best).or(kept),
    }
}

/// The contact of polyhedra `a` and `b` (placed in the world) while they are apart (`best`'s
/// separation positive): built by `contact` on the `chosen` or the `best` axis when it measures
/// their distance, else one point between their closest points. The separations along the axes
/// may fall short of the distance (two edges whose closest points are their ends, a vertex near a
/// vertex), so GJK measures it, starting from the best axis; touching within GJK's tolerance, the
/// best axis's separation is as near the distance as GJK gets. The chosen contact needs no GJK
/// when a pair of points it is built from, one on each shape, is within [`DEPTH_TOLERANCE`] of
/// the best axis's separation: that pair's distance bounds the shapes' distance from above, as
/// any axis's separation bounds it from below. A face contact's deepest point pairs a point of
/// one shape with its projection on the other's face; an edge contact's the closest points of
/// the two edges.
fn apart_contact(
    a: &PosedPolyhedron,
    b: &PosedPolyhedron,
    chosen: ContactAxis,
    best: ContactAxis,
    margin: f32,
    contact: impl Fn(ContactAxis) -> Option<Manifold>,
) -> Option<Manifold> {
    let lower_bound = best.separation();
    let chosen_contact = contact(chosen);
    let upper_bound = |manifold: &Manifold| match chosen {
        ContactAxis::Edges(edge) => {
            let (on_a, on_b) = edge_closest_points(a, b, &edge);
            on_a.distance(on_b)
        }
        ContactAxis::FaceOfA(_) | ContactAxis::FaceOfB(_) => manifold.deepest_separation(),
    };
    if chosen_contact
        .is_some_and(|manifold| upper_bound(&manifold) <= lower_bound + DEPTH_TOLERANCE)
    {
        return chosen_contact;
    }
    let axis_normal = best.world_normal(a.polyhedron, &a.frame, b.polyhedron, &b.frame);
    let closest = gjk::distance_from_direction(a, b, axis_normal);
    let (distance, normal) = if closest.overlapping {
        (lower_bound, axis_normal)
    } else {
        (closest.distance, closest.normal().unwrap_or(axis_normal))
    };
    if distance > margin {
        return None;
    }
    let measures_distance =
        |manifold: &Manifold| (manifold.deepest_separation() - distance).abs() <= DEPTH_TOLERANCE;
    let built = chosen_contact.filter(measures_distance).or_else(|| {
        (best != chosen)
            .then(|| contact(best))
            .flatten()
            .filter(measures_distance)
    });
    Some(built.unwrap_or_else(|| {
        let mut manifold = Manifold::new(normal);
        manifold.push(ContactPoint {
            position: 0.5 * (closest.point_a + closest.point_b),
            separation: distance,
            id: CLOSEST_POINTS_ID,
        });
        manifold
    }))
}

/// Clips the incident face of `incident` (through its vertex deepest below the reference plane,
/// the most anti-parallel) against face `reference_face` of `reference` (both placed in the world;
/// `incident_in_reference` places the incident in the reference's frame): two boxes by
/// [`box_face_contact`], else by [`polygon_face_contact`]. `reference_is_b` says which side of
/// the manifold the reference is on.
fn face_contact(
    reference: &PosedPolyhedron,
    reference_face: usize,
    incident: &PosedPolyhedron,
    incident_in_reference: &Frame,
    reference_is_b: bool,
    margin: f32,
) -> Option<Manifold> {
    if let (Topology::Cuboid(reference_half), Topology::Cuboid(incident_half)) =
        (reference.polyhedron.topology, incident.polyhedron.topology)
    {
        return box_face_contact(
            &BoxFace {
                half_extents: reference_half,
                face: reference_face,
                frame: reference.frame,
            },
            incident_half,
            incident_in_reference,
            reference_is_b,
            margin,
        );
    }
    polygon_face_contact(reference, reference_face, incident, reference_is_b, margin)
}

/// [`face_contact`] for any two polyhedra, worked in the world: the faces' loops are placed there
/// and clipped by [`clip_polygon`].
fn polygon_face_contact(
    reference: &PosedPolyhedron,
    reference_face: usize,
    incident: &PosedPolyhedron,
    reference_is_b: bool,
    margin: f32,
) -> Option<Manifold> {
    let (reference_frame, incident_frame) = (&reference.frame, &incident.frame);
    let (reference, incident) = (reference.polyhedron, incident.polyhedron);
    let plane = reference.face_plane(reference_face);
    let normal = reference_frame.vector(plane.normal);
    let world_plane = FacePlane {
        normal,
        offset: plane.offset + normal.dot(reference_frame.translation),
    };

    let toward_incident = incident_frame.inverse_vector(normal);
    let deepest_vertex = incident.support_index(-toward_incident);
    let mut incident_face = 0;
    let mut most_opposed = f32::INFINITY;
    // The alignment is measured first: a face's loop is searched for the vertex only when the
    // face would be kept.
    for face in 0..incident.face_count() {
        let alignment = incident.face_plane(face).normal.dot(toward_incident);
        if alignment < most_opposed && incident.face_has_vertex(face, deepest_vertex) {
            most_opposed = alignment;
            incident_face = face;
        }
    }

    let mut incident_loop = [Vec3::ZERO; MAX_POLYGON_VERTICES];
    let incident_count = incident.face_loop(incident_face, incident_frame, &mut incident_loop);
    let mut reference_loop = [Vec3::ZERO; MAX_POLYGON_VERTICES];
    let reference_count = reference.face_loop(reference_face, reference_frame, &mut reference_loop);
    let (incident_loop, reference_loop) = (
        &incident_loop[..incident_count],
        &reference_loop[..reference_count],
    );
    let faces = FacePair {
        reference_is_b,
        reference_face,
        incident_face,
    };
    if incident_count + reference_count <= SMALL_CLIP_VERTICES {
        clip_loops::<SMALL_CLIP_VERTICES>(
            incident_loop,
            reference_loop,
            &world_plane,
            faces,
            margin,
        )
    } else {
        clip_loops::<MAX_CLIP_VERTICES>(incident_loop, reference_loop, &world_plane, faces, margin)
    }
}

/// Capacity of the clipped polygon for faces of at most this many corners together (two
/// triangles, a triangle and a hexagon, two octagons), which most hull faces are.
const SMALL_CLIP_VERTICES: usize = 16;

/// The face contact of the `incident` loop clipped by the sides of the `reference` loop (both in
/// the world, the reference face on `plane`) into a polygon of `CAPACITY` points (at least the
/// two loops' lengths together), by [`clipped_face_manifold`].
fn clip_loops<const CAPACITY: usize>(
    incident: &[Vec3],
    reference: &[Vec3],
    plane: &FacePlane,
    faces: FacePair,
    margin: f32,
) -> Option<Manifold> {
    let clipped: ClipPolygon<CAPACITY> = clip_polygon_within(incident, reference, plane.normal);
    clipped_face_manifold(&clipped, plane, reference[1] - reference[0], faces, margin)
}

/// Most vertices of a box face clipped by another box face: the quads' 4 + 4 corners.
const BOX_CLIP_VERTICES: usize = 8;

/// A face of a box placed in the world.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct BoxFace {
    half_extents: Vec3,
    face: usize,
    /// Places the box in the world.
    frame: Frame,
}

/// [`face_contact`] between two boxes, worked in the reference box's frame: there the reference
/// face's sides are coordinate planes ([`box_face_sides`]), the incident face (most anti-parallel
/// to the reference normal, [`box_face_against`]) a quad placed by one relative frame, and the
/// clipped polygon has at most [`BOX_CLIP_VERTICES`] points; only the kept points are moved to
/// the world. Points and ids are those of the general route, up to rounding.
fn box_face_contact(
    reference: &BoxFace,
    incident_half: Vec3,
    incident_in_reference: &Frame,
    reference_is_b: bool,
    margin: f32,
) -> Option<Manifold> {
    let axis = reference.face / 2;
    let sign = if reference.face % 2 == 0 { 1.0 } else { -1.0 };
    let plane = FacePlane {
        normal: Vec3::AXES[axis] * sign,
        offset: reference.half_extents[axis],
    };
    let incident_face = box_face_against(incident_in_reference.inverse_vector(plane.normal));
    let incident_loop = box_face_loop(incident_half, incident_face, incident_in_reference);
    let sides = box_face_sides(reference.half_extents, reference.face);
    let clipped: ClipPolygon<BOX_CLIP_VERTICES> = clip_by_sides(
        &incident_loop,
        (0..)
            .zip(sides)
            .map(|(index, side)| (index, move |point| side.distance(point))),
    );
    let corner = |slot: usize| {
        box_vertex(
            reference.half_extents,
            BOX_FACE_LOOPS[reference.face][slot].into(),
        )
    };
    let mut manifold = clipped_face_manifold(
        &clipped,
        &plane,
        corner(1) - corner(0),
        FacePair {
            reference_is_b,
            reference_face: reference.face,
            incident_face,
        },
        margin,
    )?;
    manifold.normal = reference.frame.vector(manifold.normal);
    for point in manifold.points_mut() {
        point.position = reference.frame.point(point.position);
    }
    Some(manifold)
}

/// The faces a face contact is made of, for its ids.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct FacePair {
    reference_is_b: bool,
    reference_face: usize,
    incident_face: usize,
}

/// The face contact from the incident face clipped by the reference face's sides, all in one
/// frame, in which the reference face lies on `plane` and its loop starts along `first_edge`: the
/// points at most `margin` beyond the plane, each moved halfway to it, reduced to four
/// ([`reduce_contacts_on_face`]); `None` when there is none.
fn clipped_face_manifold<const CAPACITY: usize>(
    clipped: &ClipPolygon<CAPACITY>,
    plane: &FacePlane,
    first_edge: Vec3,
    faces: FacePair,
    margin: f32,
) -> Option<Manifold> {
    let normal = plane.normal;
    let mut candidates = [ContactPoint::default(); CAPACITY];
    let mut count = 0;
    for vertex in clipped.vertices() {
        let separation = normal.dot(vertex.position) - plane.offset;
        if separation <= margin {
            candidates[count] = ContactPoint {
                position: vertex.position - normal * (0.5 * separation),
                separation,
                id: face_contact_id(faces, vertex.feature),
            };
            count += 1;
        }
    }
    if count == 0 {
        return None;
    }
    let manifold_normal = if faces.reference_is_b {
        -normal
    } else {
        normal
    };
    let edge = first_edge.normalize_or_zero();
    let tangent = edge * REDUCTION_ANGLE.cos() + normal.cross(edge) * REDUCTION_ANGLE.sin();
    Some(reduce_contacts_on_face(
        manifold_normal,
        tangent,
        &candidates[..count],
        Surface::Flat,
    ))
}

/// The id of a face-contact point; layout in [`collide_polyhedra`].
fn face_contact_id(faces: FacePair, feature: ClipFeature) -> u32 {
    (u32::from(faces.reference_is_b) << 30)
        | ((faces.reference_face as u32 & 0x7F) << 23)
        | ((faces.incident_face as u32 & 0x7F) << 16)
        | u32::from(feature.key())
}

/// One point between edge `edge.edge_a` of A and `edge.edge_b` of B.
fn edge_contact(
    a: &PosedPolyhedron,
    b: &PosedPolyhedron,
    edge: &EdgeAxis,
    margin: f32,
) -> Option<Manifold> {
    let (on_a, on_b) = edge_closest_points(a, b, edge);
    let normal = a.frame.vector(edge.axis);
    let separation = normal.dot(on_b - on_a);
    let within_margin = separation <= margin;
    if !within_margin {
        return None;
    }
    let mut manifold = Manifold::new(normal);
    manifold.push(ContactPoint {
        position: 0.5 * (on_a + on_b),
        separation,
        id: (1 << 31) | ((edge.edge_a as u32 & 0x7FFF) << 16) | (edge.edge_b as u32 & 0xFFFF),
    });
    Some(manifold)
}

/// The closest points, in the world, of edge `edge.edge_a` of A and edge `edge.edge_b` of B.
fn edge_closest_points(a: &PosedPolyhedron, b: &PosedPolyhedron, edge: &EdgeAxis) -> (Vec3, Vec3) {
    let edge_a = a.polyhedron.edge(edge.edge_a);
    let edge_b = b.polyhedron.edge(edge.edge_b);
    closest_points_between_segments(
        a.frame.point(edge_a.start),
        a.frame.point(edge_a.end),
        b.frame.point(edge_b.start),
        b.frame.point(edge_b.end),
    )
}

/// The closest points of segments `[p0, p1]` and `[q0, q1]`: minimise `|p(s) − q(t)|²` over
/// `s, t ∈ [0, 1]`, solving the 2×2 normal equations when the segments are not parallel, then
/// clamping one parameter and re-solving the other. A segment shorter than 1 µm is a point.
fn closest_points_between_segments(p0: Vec3, p1: Vec3, q0: Vec3, q1: Vec3) -> (Vec3, Vec3) {
    let p_direction = p1 - p0;
    let q_direction = q1 - q0;
    let offset = p0 - q0;
    let p_squared = p_direction.length_squared();
    let q_squared = q_direction.length_squared();
    let q_offset = q_direction.dot(offset);
    let p_is_point = p_squared <= DEGENERATE_EDGE_SQUARED;
    let q_is_point = q_squared <= DEGENERATE_EDGE_SQUARED;

    let (s, t) = match (p_is_point, q_is_point) {
        (true, true) => (0.0, 0.0),
        (true, false) => (0.0, (q_offset / q_squared).clamp(0.0, 1.0)),
        (false, true) => (
            0.0_f32.max(-p_direction.dot(offset) / p_squared).min(1.0),
            0.0,
        ),
        (false, false) => {
            let p_offset = p_direction.dot(offset);
            let cross = p_direction.dot(q_direction);
            let determinant = p_squared * q_squared - cross * cross;
            let s = if determinant > 0.0 {
                ((cross * q_offset - p_offset * q_squared) / determinant).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let t = (cross * s + q_offset) / q_squared;
            if t < 0.0 {
                ((-p_offset / p_squared).clamp(0.0, 1.0), 0.0)
            } else if t > 1.0 {
                (((cross - p_offset) / p_squared).clamp(0.0, 1.0), 1.0)
            } else {
                (s, t)
            }
        }
    };
    (p0 + p_direction * s, q0 + q_direction * t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::polyhedron::crossing_poses;
    use crate::shape::Cuboid;

    /// Two boxes turned and overlapping in many ways: the box route gives the general route's
    /// contact on each box's best face, with the same ids, points to rounding and the same normal.
    #[test]
    fn box_face_contact_matches_the_polygon_route() {
        let cuboids = [
            Cuboid::new(Vec3::new(0.5, 0.5, 0.5)).expect("valid box"),
            Cuboid::new(Vec3::new(1.5, 0.2, 0.7)).expect("valid box"),
        ];
        let mut compared = 0;
        for step in 0..400 {
            let t = step as f32;
            let (pose_a, pose_b) = crossing_poses(t);
            let a = Polyhedron::cuboid(&cuboids[step % 2]);
            let b = Polyhedron::cuboid(&cuboids[step / 2 % 2]);
            let posed_a = PosedPolyhedron {
                polyhedron: &a,
                frame: Frame::from_pose(&pose_a),
            };
            let posed_b = PosedPolyhedron {
                polyhedron: &b,
                frame: Frame::from_pose(&pose_b),
            };
            let b_in_a = Frame::relative(&pose_a, &pose_b);
            let a_in_b = b_in_a.inverse();
            for (reference, incident, incident_in_reference, reference_is_b) in [
                (&posed_a, &posed_b, &b_in_a, false),
                (&posed_b, &posed_a, &a_in_b, true),
            ] {
                let face = best_face_axis(
                    reference.polyhedron,
                    incident.polyhedron,
                    incident_in_reference,
                )
                .face;
                let general = polygon_face_contact(reference, face, incident, reference_is_b, 0.05);
                let boxes = face_contact(
                    reference,
                    face,
                    incident,
                    incident_in_reference,
                    reference_is_b,
                    0.05,
                );
                let (Some(general), Some(boxes)) = (general, boxes) else {
                    assert_eq!(general.is_some(), boxes.is_some());
                    continue;
                };
                assert!((general.normal - boxes.normal).length() < 1e-6);
                assert_eq!(general.len(), boxes.len());
                for (expected, actual) in general.points().iter().zip(boxes.points()) {
                    assert_eq!(expected.id, actual.id);
                    assert!((expected.position - actual.position).length() < 1e-5);
                    assert!((expected.separation - actual.separation).abs() < 1e-5);
                }
                compared += 1;
            }
        }
        assert!(compared > 300, "{compared} contacts compared");
    }

    #[test]
    fn closest_points_of_segments() {
        let (p, q) = closest_points_between_segments(
            Vec3::new(-1.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.5, 1.0, -1.0),
            Vec3::new(0.5, 1.0, 1.0),
        );
        assert!((p - Vec3::new(0.5, 0.0, 0.0)).length() < 1e-6);
        assert!((q - Vec3::new(0.5, 1.0, 0.0)).length() < 1e-6);
        // Parallel and degenerate inputs stay finite.
        let (p, q) =
            closest_points_between_segments(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Y + Vec3::X);
        assert!(p.is_finite() && q.is_finite());
        assert!(((q - p).length() - 1.0).abs() < 1e-6);
        let (p, q) = closest_points_between_segments(Vec3::ZERO, Vec3::ZERO, Vec3::Y, Vec3::Y);
        assert_eq!((p, q), (Vec3::ZERO, Vec3::Y));
        let (p, q) = closest_points_between_segments(Vec3::ZERO, Vec3::ZERO, -Vec3::X, Vec3::X);
        assert_eq!((p, q), (Vec3::ZERO, Vec3::ZERO));
    }
}
