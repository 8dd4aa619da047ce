//! Contact manifolds between convex polyhedra (boxes and convex hulls) by the separating axis
//! test and clipping.
//!
//! The candidate axes are the face normals of A, those of B, and the cross products of an edge
//! of A with an edge of B, kept only when the two edges' arcs cross on the Gauss map (the pair
//! builds a face of the Minkowski difference; other pairs cannot give the deepest axis). If an
//! axis separates the shapes by more than the margin there is no contact. Otherwise the axis of
//! least overlap, with a bias toward faces and toward A (see [`collide_polyhedra`]), gives either
//! a face contact (the other shape's most anti-parallel face through its deepest vertex clipped
//! against the reference face, see [`crate::collision::clipping`]) or an edge contact (one point
//! between the two edges). Shapes apart whose closest points no axis measures (a vertex near a
//! vertex or an edge) get one point between their closest points, found by GJK.

use crate::collision::clipping::{
    clip_polygon, reduce_contacts_on_face, ClipFeature, MAX_CLIP_VERTICES, MAX_POLYGON_VERTICES,
};
use crate::collision::gjk;
use crate::collision::manifold::{ContactPoint, Manifold};
use crate::collision::SupportMap;
use crate::math::{Mat3, Pose, Vec3};
use crate::shape::{ConvexHull, Cuboid, Shape};

/// B's best face replaces A's as the reference only when its separation is larger by this
/// fraction of A's separation (in absolute value) plus [`ABSOLUTE_TOLERANCE`].
const FACE_RELATIVE_TOLERANCE: f32 = 0.05;

/// An edge pair replaces the chosen reference face only when its separation is larger by this
/// fraction of the face's separation (in absolute value) plus [`ABSOLUTE_TOLERANCE`]: face
/// contacts give several points and rest better.
const EDGE_RELATIVE_TOLERANCE: f32 = 0.1;

/// Absolute part of the axis-choice tolerances, metres.
const ABSOLUTE_TOLERANCE: f32 = 5.0e-4;

/// Edge pairs whose directions make an angle with a sine below this are treated as parallel and
/// skipped: their cross product is too short to be a reliable axis, and the faces around such
/// edges already cover those directions.
const PARALLEL_SINE: f32 = 1.0e-3;

/// How many of B's edges the edge query moves into A's frame at a time (a stack buffer).
const EDGE_CHUNK: usize = 32;

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

/// Box vertex `i` is `(±hx, ±hy, ±hz)` with the sign of x from bit 0 of `i`, y from bit 1 and z
/// from bit 2 (set = positive).
const BOX_VERTEX_COUNT: usize = 8;

/// Box face `f` has normal `+axis` for even `f` and `−axis` for odd `f`, with `axis = f / 2`
/// (0 = x, 1 = y, 2 = z). Vertex loops are counter-clockwise seen from outside.
const BOX_FACE_LOOPS: [[u8; 4]; 6] = [
    [1, 3, 7, 5],
    [0, 4, 6, 2],
    [2, 6, 7, 3],
    [0, 1, 5, 4],
    [4, 5, 7, 6],
    [0, 2, 3, 1],
];

/// Box edges: the two vertices, then the two faces that meet there.
const BOX_EDGES: [([u8; 2], [u8; 2]); 12] = [
    ([0, 1], [3, 5]),
    ([2, 3], [2, 5]),
    ([4, 5], [3, 4]),
    ([6, 7], [2, 4]),
    ([0, 2], [1, 5]),
    ([1, 3], [0, 5]),
    ([4, 6], [1, 4]),
    ([5, 7], [0, 4]),
    ([0, 4], [1, 3]),
    ([1, 5], [0, 3]),
    ([2, 6], [1, 2]),
    ([3, 7], [0, 2]),
];

/// A face plane in the polyhedron's frame: `normal · p = offset` on the face, `normal` unit and
/// pointing out.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacePlane {
    /// Unit outward normal.
    pub normal: Vec3,
    /// Signed distance of the plane from the origin along `normal`.
    pub offset: f32,
}

/// An edge in the polyhedron's frame, with the outward normals of the two faces that meet there
/// (the ends of the edge's arc on the Gauss map).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolyhedronEdge {
    /// First end.
    pub start: Vec3,
    /// Second end.
    pub end: Vec3,
    /// Unit outward normals of the two adjacent faces.
    pub face_normals: [Vec3; 2],
}

impl PolyhedronEdge {
    /// `end − start`.
    pub fn direction(&self) -> Vec3 {
        self.end - self.start
    }
}

/// What a polyhedron's vertices, faces and edges are read from.
#[derive(Debug, Clone, Copy)]
enum Topology<'a> {
    /// A box: fixed topology scaled by the half extents.
    Cuboid(Vec3),
    /// A convex hull, whose indices its builder guarantees.
    Hull(&'a ConvexHull),
}

/// A convex polyhedron in its local frame: vertices, faces (planes and vertex loops) and edges.
/// Borrows a hull's data; a box needs no storage.
#[derive(Debug, Clone, Copy)]
pub struct Polyhedron<'a> {
    topology: Topology<'a>,
}

impl<'a> Polyhedron<'a> {
    /// The polyhedron of a box.
    pub fn cuboid(cuboid: &Cuboid) -> Self {
        Self {
            topology: Topology::Cuboid(cuboid.half_extents()),
        }
    }

    /// The polyhedron of a convex hull.
    pub fn hull(hull: &'a ConvexHull) -> Self {
        Self {
            topology: Topology::Hull(hull),
        }
    }

    /// A box or a hull as a polyhedron; `None` for any other shape.
    pub fn from_shape(shape: &'a Shape) -> Option<Self> {
        match shape {
            Shape::Cuboid(cuboid) => Some(Self::cuboid(cuboid)),
            Shape::ConvexHull(hull) => Some(Self::hull(hull)),
            _ => None,
        }
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        match self.topology {
            Topology::Cuboid(_) => BOX_VERTEX_COUNT,
            Topology::Hull(hull) => hull.vertices().len(),
        }
    }

    /// Vertex `index` (below [`Polyhedron::vertex_count`]).
    pub fn vertex(&self, index: usize) -> Vec3 {
        match self.topology {
            Topology::Cuboid(half_extents) => box_vertex(half_extents, index),
            Topology::Hull(hull) => hull.vertices()[index],
        }
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        match self.topology {
            Topology::Cuboid(_) => BOX_FACE_LOOPS.len(),
            Topology::Hull(hull) => hull.faces().len(),
        }
    }

    /// The plane of face `index` (below [`Polyhedron::face_count`]).
    pub fn face_plane(&self, index: usize) -> FacePlane {
        match self.topology {
            Topology::Cuboid(half_extents) => {
                let axis = index / 2;
                let sign = if index % 2 == 0 { 1.0 } else { -1.0 };
                FacePlane {
                    normal: Vec3::AXES[axis] * sign,
                    offset: half_extents[axis],
                }
            }
            Topology::Hull(hull) => {
                let face = &hull.faces()[index];
                FacePlane {
                    normal: face.normal,
                    offset: face.offset,
                }
            }
        }
    }

    /// Number of vertices around face `face`.
    pub fn face_vertex_count(&self, face: usize) -> usize {
        match self.topology {
            Topology::Cuboid(_) => BOX_FACE_LOOPS[face].len(),
            Topology::Hull(hull) => hull.faces()[face].vertices.len(),
        }
    }

    /// Vertex `corner` of face `face`, counting counter-clockwise seen from outside.
    pub fn face_vertex(&self, face: usize, corner: usize) -> Vec3 {
        match self.topology {
            Topology::Cuboid(half_extents) => {
                box_vertex(half_extents, usize::from(BOX_FACE_LOOPS[face][corner]))
            }
            Topology::Hull(hull) => hull.vertices()[hull.faces()[face].vertices[corner] as usize],
        }
    }

    /// Number of edges.
    pub fn edge_count(&self) -> usize {
        match self.topology {
            Topology::Cuboid(_) => BOX_EDGES.len(),
            Topology::Hull(hull) => hull.edges().len(),
        }
    }

    /// Edge `index` (below [`Polyhedron::edge_count`]).
    pub fn edge(&self, index: usize) -> PolyhedronEdge {
        match self.topology {
            Topology::Cuboid(half_extents) => {
                let ([start, end], [first, second]) = BOX_EDGES[index];
                PolyhedronEdge {
                    start: box_vertex(half_extents, usize::from(start)),
                    end: box_vertex(half_extents, usize::from(end)),
                    face_normals: [
                        self.face_plane(usize::from(first)).normal,
                        self.face_plane(usize::from(second)).normal,
                    ],
                }
            }
            Topology::Hull(hull) => {
                let edge = &hull.edges()[index];
                let vertex = |end: usize| hull.vertices()[edge.vertices[end] as usize];
                let normal = |side: usize| hull.faces()[edge.faces[side] as usize].normal;
                PolyhedronEdge {
                    start: vertex(0),
                    end: vertex(1),
                    face_normals: [normal(0), normal(1)],
                }
            }
        }
    }

    /// The vertex farthest along `direction` (a box picks the positive side on a zero
    /// component; a hull the lowest index among equally far vertices).
    pub fn support(&self, direction: Vec3) -> Vec3 {
        match self.topology {
            Topology::Cuboid(half_extents) => Vec3::ONE.copysign(direction) * half_extents,
            Topology::Hull(hull) => hull.support(direction),
        }
    }

    /// The index of the vertex farthest along `direction` (as [`Polyhedron::support`]).
    fn support_index(&self, direction: Vec3) -> usize {
        match self.topology {
            Topology::Cuboid(_) => [direction.x, direction.y, direction.z]
                .iter()
                .enumerate()
                .filter(|(_, component)| component.is_sign_positive())
                .map(|(axis, _)| 1 << axis)
                .sum(),
            Topology::Hull(hull) => {
                let mut best = (0, f32::NEG_INFINITY);
                for (index, vertex) in hull.vertices().iter().enumerate() {
                    let reach = vertex.dot(direction);
                    if reach > best.1 {
                        best = (index, reach);
                    }
                }
                best.0
            }
        }
    }

    /// A point inside the polyhedron: a box's centre, the mean of a hull's vertices.
    fn interior_point(&self) -> Vec3 {
        match self.topology {
            Topology::Cuboid(_) => Vec3::ZERO,
            Topology::Hull(hull) => {
                let vertices = hull.vertices();
                vertices.iter().copied().sum::<Vec3>() / vertices.len().max(1) as f32
            }
        }
    }

    /// Whether vertex `vertex` is a corner of face `face`.
    fn face_has_vertex(&self, face: usize, vertex: usize) -> bool {
        match self.topology {
            Topology::Cuboid(_) => BOX_FACE_LOOPS[face].contains(&(vertex as u8)),
            Topology::Hull(hull) => hull.faces()[face].vertices.contains(&(vertex as u32)),
        }
    }

    /// The loop of face `face` mapped by `frame` into `out`, returning how many vertices were
    /// written. A loop longer than [`MAX_POLYGON_VERTICES`] is read at evenly spaced corners,
    /// which spans a convex polygon inside the face.
    fn face_loop(
        &self,
        face: usize,
        frame: &Frame,
        out: &mut [Vec3; MAX_POLYGON_VERTICES],
    ) -> usize {
        let total = self.face_vertex_count(face);
        let count = total.min(MAX_POLYGON_VERTICES);
        for (slot, corner) in out.iter_mut().zip(0..count) {
            *slot = frame.point(self.face_vertex(face, corner * total / count));
        }
        count
    }
}

/// Box vertex `index` as laid out in [`BOX_VERTEX_COUNT`].
fn box_vertex(half_extents: Vec3, index: usize) -> Vec3 {
    let sign = |bit: usize| if index & bit != 0 { 1.0 } else { -1.0 };
    Vec3::new(sign(1), sign(2), sign(4)) * half_extents
}

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

/// A rigid transform as a rotation matrix and a translation: `rotation · p + translation`.
#[derive(Debug, Clone, Copy)]
struct Frame {
    rotation: Mat3,
    translation: Vec3,
}

impl Frame {
    fn from_pose(pose: &Pose) -> Self {
        Self {
            rotation: Mat3::from_quat(pose.rotation),
            translation: pose.position,
        }
    }

    /// The pose of `inner`'s frame seen from `outer`'s frame.
    fn relative(outer: &Pose, inner: &Pose) -> Self {
        let inverse = outer.rotation.inverse();
        Self {
            rotation: Mat3::from_quat(inverse * inner.rotation),
            translation: inverse * (inner.position - outer.position),
        }
    }

    fn point(&self, point: Vec3) -> Vec3 {
        self.rotation * point + self.translation
    }

    fn vector(&self, vector: Vec3) -> Vec3 {
        self.rotation * vector
    }

    /// The inverse rotation applied to `vector` (`Rᵀ · v`).
    fn inverse_vector(&self, vector: Vec3) -> Vec3 {
        Vec3::new(
            self.rotation.x_axis.dot(vector),
            self.rotation.y_axis.dot(vector),
            self.rotation.z_axis.dot(vector),
        )
    }
}

/// A face of one polyhedron and how far the other lies beyond its plane (negative: how deep it
/// reaches in), measured at the other's vertex deepest along the face's inward normal.
#[derive(Debug, Clone, Copy, PartialEq)]
struct FaceAxis {
    face: usize,
    separation: f32,
}

/// An edge of A and an edge of B, their axis in A's frame pointing from A to B, and the
/// separation of the two edges along it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct EdgeAxis {
    edge_a: usize,
    edge_b: usize,
    axis: Vec3,
    separation: f32,
}

/// The face of `reference` beyond whose plane `other` (placed in the reference frame by
/// `other_in_reference`) lies farthest, or reaches in least (the first of equals): in closed form
/// for two boxes, else by [`best_face_axis_by_support`].
fn best_face_axis(
    reference: &Polyhedron,
    other: &Polyhedron,
    other_in_reference: &Frame,
) -> FaceAxis {
    match (reference.topology, other.topology) {
        (Topology::Cuboid(half_reference), Topology::Cuboid(half_other)) => {
            best_box_box_face_axis(half_reference, half_other, other_in_reference)
        }
        _ => best_face_axis_by_support(reference, other, other_in_reference),
    }
}

/// [`best_face_axis`] for two boxes: along the reference's axis `eᵢ`, the other box (centre `c`,
/// axes `fₖ`, half extents `bₖ`) reaches down to `cᵢ − Σₖ bₖ |eᵢ · fₖ|`, so the face facing its
/// centre (`+eᵢ` when `cᵢ ≥ 0`) has the larger separation, `|cᵢ| − aᵢ − Σₖ bₖ |eᵢ · fₖ|`.
fn best_box_box_face_axis(
    half_reference: Vec3,
    half_other: Vec3,
    other_in_reference: &Frame,
) -> FaceAxis {
    let rows = other_in_reference.rotation.transpose();
    let mut best = FaceAxis {
        face: 0,
        separation: f32::NEG_INFINITY,
    };
    for (axis, row) in [rows.x_axis, rows.y_axis, rows.z_axis]
        .into_iter()
        .enumerate()
    {
        let centre = other_in_reference.translation[axis];
        let separation = centre.abs() - half_reference[axis] - half_other.dot(row.abs());
        if separation > best.separation {
            best = FaceAxis {
                face: 2 * axis + usize::from(centre < 0.0),
                separation,
            };
        }
    }
    best
}

/// [`best_face_axis`] for any two polyhedra, from the other's support point against each face.
fn best_face_axis_by_support(
    reference: &Polyhedron,
    other: &Polyhedron,
    other_in_reference: &Frame,
) -> FaceAxis {
    let mut best = FaceAxis {
        face: 0,
        separation: f32::NEG_INFINITY,
    };
    for face in 0..reference.face_count() {
        let plane = reference.face_plane(face);
        let inward = other_in_reference.inverse_vector(-plane.normal);
        let deepest = other_in_reference.point(other.support(inward));
        let separation = plane.normal.dot(deepest) - plane.offset;
        if separation > best.separation {
            best = FaceAxis { face, separation };
        }
    }
    best
}

/// Replaces `best` by `candidate` when there is none yet or the candidate's separation is larger.
fn keep_larger(best: &mut Option<EdgeAxis>, candidate: EdgeAxis) {
    if best.is_none_or(|best| candidate.separation > best.separation) {
        *best = Some(candidate);
    }
}

/// An edge of B placed in A's frame, with its face normals negated: its arc on the Gauss map of
/// the Minkowski difference A − B.
#[derive(Debug, Clone, Copy, Default)]
struct MovedEdge {
    index: usize,
    start: Vec3,
    direction: Vec3,
    negated_normals: [Vec3; 2],
}

/// Over the edge pairs that build a face of the Minkowski difference A − B, the largest
/// separation along their cross product, in A's frame (`b_in_a` places B there, `a_in_b` A in
/// B's): by [`best_box_box_edge_axis`] for two boxes, by [`best_box_edge_axis`] when A or B is a
/// box (the roles swapped when only B is), else by [`best_edge_axis`] over every pair. Edges
/// whose pairs cannot separate the shapes by more than `threshold` may be skipped
/// ([`edge_reach`]), so a pair at or below it may be missed.
fn edge_query(
    a: &Polyhedron,
    b: &Polyhedron,
    b_in_a: &Frame,
    a_in_b: &Frame,
    threshold: f32,
) -> Option<EdgeAxis> {
    match (a.topology, b.topology) {
        (Topology::Cuboid(half_a), Topology::Cuboid(half_b)) => {
            best_box_box_edge_axis(half_a, half_b, b_in_a)
        }
        (Topology::Cuboid(half_extents), _) => {
            best_box_edge_axis(half_extents, b, b_in_a, threshold)
        }
        (_, Topology::Cuboid(half_extents)) => {
            best_box_edge_axis(half_extents, a, a_in_b, threshold).map(|swapped| EdgeAxis {
                edge_a: swapped.edge_b,
                edge_b: swapped.edge_a,
                axis: -b_in_a.vector(swapped.axis),
                separation: swapped.separation,
            })
        }
        _ => best_edge_axis(a, b, b_in_a, threshold),
    }
}

/// An upper bound on the separation of any edge pair with this edge: the largest `n · (p − s)`
/// over the unit normals `n` on the edge's arc between its face normals `n₁, n₂`, for `s` a point
/// of the edge and `p` a point inside the other shape (`toward = p − s`). The pair's separation
/// along its axis `n` is the other shape's extent along `∓n` less this shape's, which is reached
/// at the edge, so it is at most `n · (p − s)`. The largest is `|v|` for `v` the part of `toward`
/// in the arc's plane when `v` lies between `n₁` and `n₂` (`v = α n₁ + β n₂`, `α, β ≥ 0`), else
/// at an end; infinite for a degenerate arc.
fn edge_reach(face_normals: [Vec3; 2], toward: Vec3) -> f32 {
    let [first, second] = face_normals;
    let (along_first, along_second) = (first.dot(toward), second.dot(toward));
    let cosine = first.dot(second);
    let sine_squared = 1.0 - cosine * cosine;
    // Written so that a NaN also counts as degenerate.
    let proper_arc = sine_squared > 1.0e-6;
    if !proper_arc {
        return f32::INFINITY;
    }
    let alpha = along_first - along_second * cosine;
    let beta = along_second - along_first * cosine;
    if alpha >= 0.0 && beta >= 0.0 {
        ((alpha * along_first + beta * along_second) / sine_squared)
            .max(0.0)
            .sqrt()
    } else {
        along_first.max(along_second)
    }
}

/// Whether an edge whose [`edge_reach`] is `reach` can be skipped: its pairs cannot beat
/// `threshold` (less [`ABSOLUTE_TOLERANCE`], against the rounding of the two computations).
fn out_of_reach(reach: f32, threshold: f32) -> bool {
    reach < threshold - ABSOLUTE_TOLERANCE
}

/// [`best_edge_axis`] for two boxes (half extents `half_a`, `half_b`): one candidate per pair of
/// axes `eᵢ` of A and `fⱼ` of B. Of the two Minkowski faces along `±(eᵢ × fⱼ)`, the one facing B's
/// centre is the larger separation, `|n · c| − Σₖ aₖ |n · eₖ| − Σₖ bₖ |n · fₖ|` (`c` B's centre in
/// A's frame), between A's edge along `eᵢ` supporting `n` and B's edge along `fⱼ` supporting
/// `−n`, read from the signs of the other components. A crossing on a face normal (a zero
/// component) is left to the face axes, as a parallel pair is.
fn best_box_box_edge_axis(half_a: Vec3, half_b: Vec3, b_in_a: &Frame) -> Option<EdgeAxis> {
    let mut best: Option<EdgeAxis> = None;
    let centre = b_in_a.translation;
    let axes_b = [
        b_in_a.rotation.x_axis,
        b_in_a.rotation.y_axis,
        b_in_a.rotation.z_axis,
    ];
    for (index_a, &axis_a) in Vec3::AXES.iter().enumerate() {
        for (index_b, &axis_b) in axes_b.iter().enumerate() {
            let cross = axis_a.cross(axis_b);
            let length_squared = cross.length_squared();
            // Written so that a NaN (from overflow on absurdly large shapes) also rejects it.
            let crosses = length_squared > PARALLEL_SINE * PARALLEL_SINE;
            if !crosses {
                continue;
            }
            let mut axis = cross / length_squared.sqrt();
            if axis.dot(centre) < 0.0 {
                axis = -axis;
            }
            let against_in_b = b_in_a.inverse_vector(-axis);
            let (Some(edge_a), Some(edge_b)) = (
                box_edge_along(index_a, axis),
                box_edge_along(index_b, against_in_b),
            ) else {
                continue;
            };
            let separation =
                axis.dot(centre) - half_a.dot(axis.abs()) - half_b.dot(against_in_b.abs());
            keep_larger(
                &mut best,
                EdgeAxis {
                    edge_a,
                    edge_b,
                    axis,
                    separation,
                },
            );
        }
    }
    best
}

/// The box edge along axis `axis_index` that is the box's support along `direction` (local),
/// read from the signs of `direction`'s other two components; `None` when one is zero (the
/// support is then a face).
fn box_edge_along(axis_index: usize, direction: Vec3) -> Option<usize> {
    let (first, second) = match axis_index {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    };
    (direction[first] != 0.0 && direction[second] != 0.0).then(|| {
        4 * axis_index
            + usize::from(direction[first] > 0.0)
            + 2 * usize::from(direction[second] > 0.0)
    })
}

/// [`best_edge_axis`] for a box A (half extents `half_extents`) and any polyhedron B, with one
/// candidate per edge of B and box axis instead of one per pair of edges. The box's four edges
/// along axis `i` have arcs on the Gauss map that together make the great circle normal to `i`:
/// B's negated arc crosses it when the ends' `i` components differ in sign, at the point
/// `±(eᵢ × e_B)` lying on B's arc, and the box edge whose arc holds that point is the one whose
/// two faces have the signs of the point's other two components. A crossing on a face normal of
/// the box is left to the face axes, as a parallel pair is.
fn best_box_edge_axis(
    half_extents: Vec3,
    b: &Polyhedron,
    b_in_a: &Frame,
    threshold: f32,
) -> Option<EdgeAxis> {
    // Worked in B's frame, where B's edges need no moving: the box axes `eᵢ` are the rows of the
    // rotation, and only a crossing's axis is moved to A's frame.
    let rotation = b_in_a.rotation.transpose();
    let box_axes = [rotation.x_axis, rotation.y_axis, rotation.z_axis];
    let box_centre = b_in_a.inverse_vector(-b_in_a.translation);
    let mut best: Option<EdgeAxis> = None;
    for edge_b in 0..b.edge_count() {
        let local = b.edge(edge_b);
        if out_of_reach(
            edge_reach(local.face_normals, box_centre - local.start),
            threshold,
        ) {
            continue;
        }
        let direction = local.direction();
        let [m1, m2] = [-local.face_normals[0], -local.face_normals[1]];
        let parallel_limit = PARALLEL_SINE * PARALLEL_SINE * direction.length_squared();
        for (axis_index, &box_axis) in box_axes.iter().enumerate() {
            if m1.dot(box_axis) * m2.dot(box_axis) >= 0.0 {
                continue;
            }
            let mut axis = box_axis.cross(direction);
            let length_squared = axis.length_squared();
            // Written so that a NaN (from overflow on absurdly large shapes) also rejects it.
            let crosses = length_squared > parallel_limit;
            let toward_b_arc = axis.dot(m1 + m2);
            if !crosses || toward_b_arc == 0.0 {
                continue;
            }
            if toward_b_arc < 0.0 {
                axis = -axis;
            }
            let axis_in_a = b_in_a.vector(axis);
            let Some(edge_a) = box_edge_along(axis_index, axis_in_a) else {
                continue;
            };
            let on_edge_a = box_vertex(half_extents, usize::from(BOX_EDGES[edge_a].0[0]));
            let axis = axis_in_a / length_squared.sqrt();
            let separation = axis.dot(b_in_a.point(local.start) - on_edge_a);
            keep_larger(
                &mut best,
                EdgeAxis {
                    edge_a,
                    edge_b,
                    axis,
                    separation,
                },
            );
        }
    }
    best
}

/// Over the edge pairs that build a face of the Minkowski difference A − B, the largest
/// separation along their cross product, computed in A's frame (`b_in_a` places B there) by
/// trying every pair. B's edges are moved into A's frame [`EDGE_CHUNK`] at a time, on the stack.
fn best_edge_axis(
    a: &Polyhedron,
    b: &Polyhedron,
    b_in_a: &Frame,
    threshold: f32,
) -> Option<EdgeAxis> {
    // A's inside point in B's frame, where B's edges are tested before being moved.
    let inside_a = b_in_a.inverse_vector(a.interior_point() - b_in_a.translation);
    let inside_b = b_in_a.point(b.interior_point());
    let mut best: Option<EdgeAxis> = None;
    let mut chunk = [MovedEdge::default(); EDGE_CHUNK];
    let mut next_b = 0;
    while next_b < b.edge_count() {
        let mut chunk_len = 0;
        while chunk_len < EDGE_CHUNK && next_b < b.edge_count() {
            let local = b.edge(next_b);
            if !out_of_reach(
                edge_reach(local.face_normals, inside_a - local.start),
                threshold,
            ) {
                chunk[chunk_len] = MovedEdge {
                    index: next_b,
                    start: b_in_a.point(local.start),
                    direction: b_in_a.vector(local.direction()),
                    negated_normals: [
                        -b_in_a.vector(local.face_normals[0]),
                        -b_in_a.vector(local.face_normals[1]),
                    ],
                };
                chunk_len += 1;
            }
            next_b += 1;
        }
        for edge_a in 0..a.edge_count() {
            let edge = a.edge(edge_a);
            if out_of_reach(
                edge_reach(edge.face_normals, inside_b - edge.start),
                threshold,
            ) {
                continue;
            }
            for moved in &chunk[..chunk_len] {
                let Some((axis, separation)) = edge_pair_axis(&edge, moved) else {
                    continue;
                };
                keep_larger(
                    &mut best,
                    EdgeAxis {
                        edge_a,
                        edge_b: moved.index,
                        axis,
                        separation,
                    },
                );
            }
        }
    }
    best
}

/// The axis of an edge of A and an edge of B (both in A's frame), pointing from A to B, with the
/// separation along it; `None` unless the pair builds a face of the Minkowski difference.
///
/// Edge A's arc on the Gauss map runs between its face normals `n₁, n₂`; edge B's, negated for
/// the difference, between `−m₁, −m₂`. The arcs cross when each one's ends lie on opposite
/// sides of the other's great circle (whose plane normal is the edge direction), and the two
/// crossings of the great circles are the same point: the axis `±(eA × eB)` that lies on A's arc
/// (positive on `n₁ + n₂`) must also lie on B's (positive on `−m₁ − m₂`). Then A's edge is A's
/// support along the axis and B's edge is B's support against it.
fn edge_pair_axis(edge: &PolyhedronEdge, moved: &MovedEdge) -> Option<(Vec3, f32)> {
    let a_direction = edge.direction();
    let [n1, n2] = edge.face_normals;
    let [m1, m2] = moved.negated_normals;
    if m1.dot(a_direction) * m2.dot(a_direction) >= 0.0
        || n1.dot(moved.direction) * n2.dot(moved.direction) >= 0.0
    {
        return None;
    }
    let mut axis = a_direction.cross(moved.direction);
    let length_squared = axis.length_squared();
    let parallel_limit = PARALLEL_SINE
        * PARALLEL_SINE
        * a_direction.length_squared()
        * moved.direction.length_squared();
    // Written so that a NaN (from overflow on absurdly large shapes) also rejects the pair.
    let crosses = length_squared > parallel_limit;
    if !crosses {
        return None;
    }
    if axis.dot(n1 + n2) < 0.0 {
        axis = -axis;
    }
    if axis.dot(m1 + m2) <= 0.0 {
        return None;
    }
    let axis = axis / length_squared.sqrt();
    Some((axis, axis.dot(moved.start - edge.start)))
}

/// An axis the contact can be built on.
#[derive(Debug, Clone, Copy, PartialEq)]
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
/// (within [`DEPTH_TOLERANCE`]) or give no point, the best axis makes the contact. While they are
/// apart, the axes' separations may fall short of the distance, which GJK then measures: a contact
/// on the chosen or the best axis is kept only if its deepest point is that distance (within
/// [`DEPTH_TOLERANCE`]), else the contact is one point midway between the closest points, with
/// the direction between them as the normal and the id [`CLOSEST_POINTS_ID`].
///
/// Face contact: the reference face's side planes clip the incident face (the face of the other
/// body, among those through its vertex deepest below the reference plane, most anti-parallel to
/// the reference normal); points whose separation from the reference plane is at most `margin`
/// are kept and reduced to four ([`reduce_contacts_on_face`], along a direction fixed to the
/// reference face, [`REDUCTION_ANGLE`] from its first edge). Each point sits halfway between the
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
    let a_in_b = Frame::relative(pose_b, pose_a);

    let face_a = best_face_axis(a, b, &b_in_a);
    if face_a.separation > margin {
        return None;
    }
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

    let world_a = Frame::from_pose(pose_a);
    let world_b = Frame::from_pose(pose_b);
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
            face_contact(a, &world_a, face.face, b, &world_b, false, margin)
        }
        ContactAxis::FaceOfB(face) => {
            face_contact(b, &world_b, face.face, a, &world_a, true, margin)
        }
        ContactAxis::Edges(edge) => edge_contact(a, &world_a, b, &world_b, &edge, margin),
    };
    if best.separation() > 0.0 {
        let posed_a = PosedPolyhedron {
            polyhedron: a,
            frame: world_a,
        };
        let posed_b = PosedPolyhedron {
            polyhedron: b,
            frame: world_b,
        };
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
/// best axis's separation is as near the distance as GJK gets. A face contact needs no GJK when
/// its deepest point is within [`DEPTH_TOLERANCE`] of the best axis's separation: each of its
/// points pairs a point of one shape with its projection on the other's face, a distance that
/// bounds the shapes' distance from above, as any axis's separation bounds it from below.
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
    let is_face = matches!(chosen, ContactAxis::FaceOfA(_) | ContactAxis::FaceOfB(_));
    if is_face
        && chosen_contact
            .is_some_and(|manifold| manifold.deepest_separation() <= lower_bound + DEPTH_TOLERANCE)
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
/// the most anti-parallel) against face `reference_face` of `reference` (both placed in the world
/// by their frames). `reference_is_b` says which side of the manifold the reference is on.
fn face_contact(
    reference: &Polyhedron,
    reference_frame: &Frame,
    reference_face: usize,
    incident: &Polyhedron,
    incident_frame: &Frame,
    reference_is_b: bool,
    margin: f32,
) -> Option<Manifold> {
    let plane = reference.face_plane(reference_face);
    let normal = reference_frame.vector(plane.normal);
    let offset = plane.offset + normal.dot(reference_frame.translation);

    let toward_incident = incident_frame.inverse_vector(normal);
    let deepest_vertex = incident.support_index(-toward_incident);
    let mut incident_face = 0;
    let mut most_opposed = f32::INFINITY;
    for face in 0..incident.face_count() {
        if !incident.face_has_vertex(face, deepest_vertex) {
            continue;
        }
        let alignment = incident.face_plane(face).normal.dot(toward_incident);
        if alignment < most_opposed {
            most_opposed = alignment;
            incident_face = face;
        }
    }

    let mut incident_loop = [Vec3::ZERO; MAX_POLYGON_VERTICES];
    let incident_count = incident.face_loop(incident_face, incident_frame, &mut incident_loop);
    let mut reference_loop = [Vec3::ZERO; MAX_POLYGON_VERTICES];
    let reference_count = reference.face_loop(reference_face, reference_frame, &mut reference_loop);
    let clipped = clip_polygon(
        &incident_loop[..incident_count],
        &reference_loop[..reference_count],
        normal,
    );

    let mut candidates = [ContactPoint::default(); MAX_CLIP_VERTICES];
    let mut count = 0;
    for vertex in clipped.vertices() {
        let separation = normal.dot(vertex.position) - offset;
        if separation <= margin {
            candidates[count] = ContactPoint {
                position: vertex.position - normal * (0.5 * separation),
                separation,
                id: face_contact_id(
                    reference_is_b,
                    reference_face,
                    incident_face,
                    vertex.feature,
                ),
            };
            count += 1;
        }
    }
    if count == 0 {
        return None;
    }
    let manifold_normal = if reference_is_b { -normal } else { normal };
    let edge = (reference_loop[1] - reference_loop[0]).normalize_or_zero();
    let tangent = edge * REDUCTION_ANGLE.cos() + normal.cross(edge) * REDUCTION_ANGLE.sin();
    Some(reduce_contacts_on_face(
        manifold_normal,
        tangent,
        &candidates[..count],
    ))
}

/// The id of a face-contact point; layout in [`collide_polyhedra`].
fn face_contact_id(
    reference_is_b: bool,
    reference_face: usize,
    incident_face: usize,
    feature: ClipFeature,
) -> u32 {
    (u32::from(reference_is_b) << 30)
        | ((reference_face as u32 & 0x7F) << 23)
        | ((incident_face as u32 & 0x7F) << 16)
        | u32::from(feature.key())
}

/// One point between edge `edge.edge_a` of A and `edge.edge_b` of B.
fn edge_contact(
    a: &Polyhedron,
    world_a: &Frame,
    b: &Polyhedron,
    world_b: &Frame,
    edge: &EdgeAxis,
    margin: f32,
) -> Option<Manifold> {
    let edge_a = a.edge(edge.edge_a);
    let edge_b = b.edge(edge.edge_b);
    let (on_a, on_b) = closest_points_between_segments(
        world_a.point(edge_a.start),
        world_a.point(edge_a.end),
        world_b.point(edge_b.start),
        world_b.point(edge_b.end),
    );
    let normal = world_a.vector(edge.axis);
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

    fn unit_box() -> Cuboid {
        Cuboid::new(Vec3::new(0.5, 1.0, 1.5)).expect("valid box")
    }

    #[test]
    fn box_topology_is_consistent() {
        let cuboid = unit_box();
        let polyhedron = Polyhedron::cuboid(&cuboid);
        for face in 0..polyhedron.face_count() {
            let plane = polyhedron.face_plane(face);
            let count = polyhedron.face_vertex_count(face);
            for corner in 0..count {
                let here = polyhedron.face_vertex(face, corner);
                let next = polyhedron.face_vertex(face, (corner + 1) % count);
                let after = polyhedron.face_vertex(face, (corner + 2) % count);
                assert!((plane.normal.dot(here) - plane.offset).abs() < 1e-6);
                assert!(
                    (next - here).cross(after - next).dot(plane.normal) > 0.0,
                    "CCW loop"
                );
            }
        }
        for index in 0..polyhedron.edge_count() {
            let edge = polyhedron.edge(index);
            for normal in edge.face_normals {
                assert!(normal.dot(edge.direction()).abs() < 1e-6);
                let offset = normal.dot(edge.start);
                assert!((normal.dot(edge.end) - offset).abs() < 1e-6);
                assert!((offset - cuboid.support(normal).dot(normal)).abs() < 1e-6);
            }
            assert!(edge.face_normals[0].dot(edge.face_normals[1]).abs() < 1e-6);
        }
        for index in 0..polyhedron.vertex_count() {
            let vertex = polyhedron.vertex(index);
            assert_eq!(cuboid.support(vertex), vertex);
        }
    }

    /// The box routes find the same face as every support point, and the box routes and the
    /// skipping of edges out of reach the same edge pair, axis and separation as trying every
    /// pair, for boxes and a hull, either way round.
    #[test]
    fn box_queries_match_the_general_ones() {
        let other = unit_box();
        let points: Vec<Vec3> = (0..12)
            .map(|index| {
                let angle = index as f32 * std::f32::consts::TAU / 6.0;
                let y = if index < 6 { -0.4 } else { 0.3 };
                Vec3::new(0.5 * angle.cos(), y, 0.6 * angle.sin())
            })
            .collect();
        let hull = ConvexHull::new(&points).expect("a prism");
        let cuboid = Cuboid::new(Vec3::new(0.4, 0.3, 0.7)).expect("valid box");
        let shapes = [
            Polyhedron::cuboid(&cuboid),
            Polyhedron::cuboid(&other),
            Polyhedron::hull(&hull),
        ];
        let (mut compared, mut same_pair) = (0, 0);
        for step in 0..200 {
            let t = step as f32;
            let pose_a = Pose::new(
                Vec3::new(0.1 * t.sin(), 0.2, -0.1),
                crate::math::Quat::from_scaled_axis(Vec3::new(0.3 * t, 0.7 * t.cos(), 0.11 * t)),
            );
            let pose_b = Pose::new(
                Vec3::new(
                    0.9 * (0.37 * t).cos(),
                    1.1 * (0.53 * t).sin(),
                    0.8 * (0.29 * t).cos(),
                ),
                crate::math::Quat::from_scaled_axis(Vec3::new(0.05 * t, -0.2 * t, 0.4 * t.sin())),
            );
            for a in &shapes {
                for b in &shapes {
                    for (a, b, pose_a, pose_b) in [(a, b, pose_a, pose_b), (b, a, pose_b, pose_a)] {
                        let b_in_a = Frame::relative(&pose_a, &pose_b);
                        let a_in_b = Frame::relative(&pose_b, &pose_a);
                        let face = best_face_axis(a, b, &b_in_a);
                        let by_support = best_face_axis_by_support(a, b, &b_in_a);
                        assert_eq!(face.face, by_support.face);
                        assert!((face.separation - by_support.separation).abs() < 1e-5);
                        let slow = best_edge_axis(a, b, &b_in_a, f32::NEG_INFINITY);
                        let Some(slow) = slow else {
                            assert!(edge_query(a, b, &b_in_a, &a_in_b, f32::NEG_INFINITY).is_none());
                            continue;
                        };
                        for threshold in [f32::NEG_INFINITY, slow.separation - 0.01] {
                            let fast = edge_query(a, b, &b_in_a, &a_in_b, threshold)
                                .expect("the best pair beats the threshold");
                            assert!((fast.separation - slow.separation).abs() < 1e-5);
                            if (fast.edge_a, fast.edge_b) == (slow.edge_a, slow.edge_b) {
                                assert!((fast.axis - slow.axis).length() < 1e-5);
                                same_pair += 1;
                            }
                            compared += 1;
                        }
                        // Above the best pair, whatever is found is no better.
                        let above = edge_query(a, b, &b_in_a, &a_in_b, slow.separation + 0.01);
                        assert!(above.is_none_or(|fast| fast.separation <= slow.separation + 1e-5));
                    }
                }
            }
        }
        // Only exact ties between pairs (boxes turned alike) may pick another pair.
        assert!(
            same_pair * 100 >= compared * 95,
            "{same_pair} of {compared}"
        );
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
