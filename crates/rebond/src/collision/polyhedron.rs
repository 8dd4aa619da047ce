//! Convex polyhedra (boxes and convex hulls) as the separating-axis test and clipping read them:
//! vertices, face planes and counter-clockwise vertex loops, and edges with the outward normals of
//! the two faces that meet there (the ends of the edge's arc on the Gauss map). A box's topology
//! is a fixed table scaled by its half extents; a hull's is borrowed from the hull. `Frame` places
//! one polyhedron in the world or in the other's frame.

use crate::collision::clipping::MAX_POLYGON_VERTICES;
use crate::math::{Mat3, Pose, Vec3};
use crate::shape::{ConvexHull, Cuboid, EdgeLanes, FaceLanes, HullEdge, HullFace, Shape};

/// Box vertex `i` is `(±hx, ±hy, ±hz)` with the sign of x from bit 0 of `i`, y from bit 1 and z
/// from bit 2 (set = positive).
const BOX_VERTEX_COUNT: usize = 8;

/// Box face `f` has normal `+axis` for even `f` and `−axis` for odd `f`, with `axis = f / 2`
/// (0 = x, 1 = y, 2 = z). Vertex loops are counter-clockwise seen from outside.
pub(super) const BOX_FACE_LOOPS: [[u8; 4]; 6] = [
    [1, 3, 7, 5],
    [0, 4, 6, 2],
    [2, 6, 7, 3],
    [0, 1, 5, 4],
    [4, 5, 7, 6],
    [0, 2, 3, 1],
];

/// Box edges: the two vertices, then the two faces that meet there.
pub(super) const BOX_EDGES: [([u8; 2], [u8; 2]); 12] = [
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
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FacePlane {
    /// Unit outward normal.
    pub normal: Vec3,
    /// Signed distance of the plane from the origin along `normal`.
    pub offset: f32,
}

/// An edge in the polyhedron's frame, with the outward normals of the two faces that meet there
/// (the ends of the edge's arc on the Gauss map).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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
pub(super) enum Topology<'a> {
    /// A box: fixed topology scaled by the half extents.
    Cuboid(Vec3),
    /// A convex hull, whose indices its builder guarantees.
    Hull(&'a ConvexHull),
}

/// A convex polyhedron in its local frame: vertices, faces (planes and vertex loops) and edges.
/// Borrows a hull's data; a box needs no storage.
#[derive(Debug, Clone, Copy)]
pub struct Polyhedron<'a> {
    pub(super) topology: Topology<'a>,
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
            Topology::Hull(hull) => hull_edge(hull.vertices(), hull.faces(), &hull.edges()[index]),
        }
    }

    /// The face planes four to a group in index order, as [`Polyhedron::face_plane`] gives them:
    /// a hull's as it stores them, a box's built in `box_lanes`.
    pub(super) fn face_lanes<'s>(&'s self, box_lanes: &'s mut [FaceLanes; 2]) -> &'s [FaceLanes] {
        match self.topology {
            Topology::Cuboid(_) => {
                let planes: [(Vec3, f32); BOX_FACE_LOOPS.len()] = std::array::from_fn(|face| {
                    let plane = self.face_plane(face);
                    (plane.normal, plane.offset)
                });
                for (lanes, group) in box_lanes.iter_mut().zip(planes.chunks(4)) {
                    *lanes = FaceLanes::new(group);
                }
                box_lanes
            }
            Topology::Hull(hull) => hull.face_lanes(),
        }
    }

    /// The edges four to a group in index order, as [`Polyhedron::edge`] gives them: a hull's as
    /// it stores them, a box's built in `box_lanes`.
    pub(super) fn edge_lanes<'s>(&'s self, box_lanes: &'s mut [EdgeLanes; 3]) -> &'s [EdgeLanes] {
        match self.topology {
            Topology::Cuboid(_) => {
                for (group, lanes) in box_lanes.iter_mut().enumerate() {
                    let edges: [[Vec3; 4]; 4] = std::array::from_fn(|lane| {
                        let edge = self.edge(4 * group + lane);
                        let [first, second] = edge.face_normals;
                        [edge.start, edge.end, first, second]
                    });
                    *lanes = EdgeLanes::new(&edges);
                }
                box_lanes
            }
            Topology::Hull(hull) => hull.edge_lanes(),
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
    pub(super) fn support_index(&self, direction: Vec3) -> usize {
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
    pub(super) fn interior_point(&self) -> Vec3 {
        match self.topology {
            Topology::Cuboid(_) => Vec3::ZERO,
            Topology::Hull(hull) => hull.mean_vertex(),
        }
    }

    /// Radius of a ball about [`Polyhedron::interior_point`] that the polyhedron holds, metres: a
    /// box's smallest half extent, [`ConvexHull::inner_radius`] for a hull.
    pub(super) fn inner_radius(&self) -> f32 {
        match self.topology {
            Topology::Cuboid(half_extents) => half_extents.min_element(),
            Topology::Hull(hull) => hull.inner_radius(),
        }
    }

    /// Whether vertex `vertex` is a corner of face `face`.
    pub(super) fn face_has_vertex(&self, face: usize, vertex: usize) -> bool {
        match self.topology {
            Topology::Cuboid(_) => BOX_FACE_LOOPS[face].contains(&(vertex as u8)),
            Topology::Hull(hull) => hull.faces()[face].vertices.contains(&(vertex as u32)),
        }
    }

    /// The loop of face `face` mapped by `frame` into `out`, returning how many vertices were
    /// written. A loop longer than [`MAX_POLYGON_VERTICES`] is read at evenly spaced corners,
    /// which spans a convex polygon inside the face.
    pub(super) fn face_loop(
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

/// Hull edge `edge` with its ends among `vertices` and its faces' normals among `faces`.
fn hull_edge(vertices: &[Vec3], faces: &[HullFace], edge: &HullEdge) -> PolyhedronEdge {
    let vertex = |end: usize| vertices[edge.vertices[end] as usize];
    let normal = |side: usize| faces[edge.faces[side] as usize].normal;
    PolyhedronEdge {
        start: vertex(0),
        end: vertex(1),
        face_normals: [normal(0), normal(1)],
    }
}

/// Box vertex `index` as laid out in [`BOX_VERTEX_COUNT`].
pub(super) fn box_vertex(half_extents: Vec3, index: usize) -> Vec3 {
    let sign = |bit: usize| if index & bit != 0 { 1.0 } else { -1.0 };
    Vec3::new(sign(1), sign(2), sign(4)) * half_extents
}

/// The box face most anti-parallel to `direction` (in the box's frame): the face across the axis
/// of `direction`'s largest component (the first of equals), on the side that component points
/// away from (a `+0.0` component counting as positive). It holds the box's support vertex
/// against `direction`, so it is the incident face the general search finds.
pub(super) fn box_face_against(direction: Vec3) -> usize {
    let magnitude = direction.abs();
    let axis = if magnitude.y > magnitude.x {
        if magnitude.z > magnitude.y {
            2
        } else {
            1
        }
    } else if magnitude.z > magnitude.x {
        2
    } else {
        0
    };
    2 * axis + usize::from(direction[axis].is_sign_positive())
}

/// The loop of box face `face` (as [`Polyhedron::face_loop`]) mapped by `frame`.
pub(super) fn box_face_loop(half_extents: Vec3, face: usize, frame: &Frame) -> [Vec3; 4] {
    BOX_FACE_LOOPS[face].map(|corner| frame.point(box_vertex(half_extents, usize::from(corner))))
}

/// A side plane of a box face in the box's frame: `sign · p[axis] = offset`, facing out of the
/// face, so that clipping against it needs one coordinate instead of a dot product.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(super) struct BoxFaceSide {
    axis: usize,
    sign: f32,
    offset: f32,
}

impl BoxFaceSide {
    /// How far `point` (box frame) lies outside this side, metres.
    pub(super) fn distance(&self, point: Vec3) -> f32 {
        self.sign * point[self.axis] - self.offset
    }
}

/// The sides of box face `face` in the order of its loop: side `j` runs from corner `j` to corner
/// `j + 1`, along the one axis in which they differ, and lies across the axis that is neither
/// that one nor the face's, on the corners' side of it.
pub(super) fn box_face_sides(half_extents: Vec3, face: usize) -> [BoxFaceSide; 4] {
    let corners = BOX_FACE_LOOPS[face];
    std::array::from_fn(|side| {
        let (start, end) = (corners[side], corners[(side + 1) % corners.len()]);
        let along = (start ^ end).trailing_zeros() as usize;
        let axis = 3 - face / 2 - along;
        BoxFaceSide {
            axis,
            sign: if start & (1 << axis) != 0 { 1.0 } else { -1.0 },
            offset: half_extents[axis],
        }
    })
}

/// A rigid transform as a rotation matrix and a translation: `rotation · p + translation`.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(super) struct Frame {
    pub(super) rotation: Mat3,
    pub(super) translation: Vec3,
}

impl Frame {
    pub(super) fn from_pose(pose: &Pose) -> Self {
        Self {
            rotation: Mat3::from_quat(pose.rotation),
            translation: pose.position,
        }
    }

    /// The pose of `inner`'s frame seen from `outer`'s frame.
    pub(super) fn relative(outer: &Pose, inner: &Pose) -> Self {
        let inverse = outer.rotation.inverse();
        Self {
            rotation: Mat3::from_quat(inverse * inner.rotation),
            translation: inverse * (inner.position - outer.position),
        }
    }

    /// The inverse transform, `p ↦ Rᵀ · (p − t)`: `inner`'s frame seen from `outer`'s turned into
    /// `outer`'s seen from `inner`'s without a second quaternion product.
    pub(super) fn inverse(&self) -> Self {
        let rotation = self.rotation.transpose();
        Self {
            rotation,
            translation: -(rotation * self.translation),
        }
    }

    pub(super) fn point(&self, point: Vec3) -> Vec3 {
        self.rotation * point + self.translation
    }

    pub(super) fn vector(&self, vector: Vec3) -> Vec3 {
        self.rotation * vector
    }

    /// The inverse rotation applied to `vector` (`Rᵀ · v`).
    pub(super) fn inverse_vector(&self, vector: Vec3) -> Vec3 {
        Vec3::new(
            self.rotation.x_axis.dot(vector),
            self.rotation.y_axis.dot(vector),
            self.rotation.z_axis.dot(vector),
        )
    }
}

/// The poses at time `t` of two shapes turning and sliding through each other (for the tests that
/// compare one route with another over many relative poses).
#[cfg(test)]
pub(super) fn crossing_poses(t: f32) -> (Pose, Pose) {
    use crate::math::Quat;
    let pose_a = Pose::new(
        Vec3::new(0.1 * t.sin(), 0.2, -0.1),
        Quat::from_scaled_axis(Vec3::new(0.3 * t, 0.7 * t.cos(), 0.11 * t)),
    );
    let pose_b = Pose::new(
        Vec3::new(
            0.9 * (0.37 * t).cos(),
            1.1 * (0.53 * t).sin(),
            0.8 * (0.29 * t).cos(),
        ),
        Quat::from_scaled_axis(Vec3::new(0.05 * t, -0.2 * t, 0.4 * t.sin())),
    );
    (pose_a, pose_b)
}

/// A box of half extents (0.5, 1, 1.5) m, for the tests.
#[cfg(test)]
pub(super) fn unit_box() -> Cuboid {
    Cuboid::new(Vec3::new(0.5, 1.0, 1.5)).expect("valid box")
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
