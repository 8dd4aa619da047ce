//! Convex hull of a point cloud: the smallest convex polyhedron that holds every point.
//!
//! Built in four steps:
//! 1. points within the tolerance of an earlier point are welded to it;
//! 2. the rest are snapped onto an integer grid of 2³⁹ cells across the cloud's largest extent
//!    (finer than anything an `f32` can tell apart), and quickhull runs there on exact `i128`
//!    orientation tests, so its triangulated hull is exactly convex and its topology consistent
//!    whatever the input (duplicates, coplanar or collinear subsets);
//! 3. neighbouring triangles within the tolerance of a common plane are merged into one polygon;
//! 4. vertices left in the middle of an edge between two polygons are dropped.
//!
//! Quickhull (step 2) is exact; the other steps use the tolerance. Steps 1–2 live in
//! `convex_hull/quickhull.rs`, steps 3–4 in `convex_hull/faces.rs`.

use std::collections::BTreeMap;

use glam::{DMat3, DVec3, Vec4};

use crate::error::{check_length, check_named, Error, ErrorKind, Result};
use crate::limits::MAX_SIZE;
use crate::mass::MassProperties;
use crate::math::{Aabb, Pose, Vec3};

mod faces;
mod quickhull;

use faces::{drop_edge_vertices, Merger};
use quickhull::{initial_simplex, Cloud, Quickhull};

/// Distance within which points count as on a plane (or a line), as a fraction of the cloud's
/// largest extent. `f32` points carry rounding noise of a few ulps, about 1e-7 of the cloud's size
/// once rotated or scaled; 1e-5 sits two orders of magnitude above that noise, so a rotated box
/// still merges into six quads, and far below any feature modelled on purpose (a 10 µm bevel on a
/// 1 m part).
const RELATIVE_TOLERANCE: f64 = 1e-5;

/// Lower bound of the tolerance in units of the largest coordinate magnitude: a cloud far from its
/// origin carries the rounding of its coordinates (a few `f32` ulps), which may exceed 1e-5 of its
/// size.
const MAGNITUDE_TOLERANCE: f64 = 4.0 * f32::EPSILON as f64;

/// Cosine of the largest angle between the normals of a facet and of the plane it merges into.
/// A facet whose corners all lie within the tolerance of the plane is nearly parallel to it or
/// thin across it; the angle keeps a steep facet of a thin hull (a slab's rim) from folding its top
/// face over onto its sides. Slivers, no higher than the tolerance, merge on distance alone: their
/// normal is rounding noise.
const MERGE_COSINE: f64 = 0.5;

/// Grid cells across the cloud's largest extent. Snapped coordinates lie in `[-2³⁸, 2³⁸]`, so their
/// differences fit in 40 bits, a triangle normal (a cross product) in 82 bits and an orientation
/// test (normal · difference) in 123 bits: exact in `i128`.
const GRID_CELLS: f64 = (1u64 << 39) as f64;

/// A planar face of a hull.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct HullFace {
    /// Unit outward normal.
    pub normal: Vec3,
    /// Plane offset, metres: `normal · p = offset` on the face. The face's vertices lie on the
    /// plane and every input point behind it (`normal · p ≤ offset`), both to within twice the
    /// hull tolerance.
    pub offset: f32,
    /// Indices into [`ConvexHull::vertices`], counter-clockwise seen from outside, starting with the
    /// smallest.
    pub vertices: Vec<u32>,
}

/// An edge of a hull between two faces.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct HullEdge {
    /// Indices into [`ConvexHull::vertices`] of the two ends, smaller first.
    pub vertices: [u32; 2],
    /// Indices into [`ConvexHull::faces`]: `faces[0]` runs along the edge from `vertices[0]` to
    /// `vertices[1]` (counter-clockwise), `faces[1]` the other way.
    pub faces: [u32; 2],
}

/// The convex hull of a point cloud, in the body frame: vertices, planar polygon faces and edges.
///
/// Its vertices are the input points that are corners of the hull, in input order (the first of
/// points closer than the tolerance); points inside, on a face or in the middle of an edge are
/// dropped. The topology is a closed polyhedron: `V − E + F = 2`, every edge between exactly two
/// faces, every face a polygon planar to within the tolerance. A corner lies on at least three
/// faces, except where the cloud has features at the scale of the tolerance: two nearly coplanar
/// faces may then meet along a slightly bent edge.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ConvexHull {
    vertices: Vec<Vec3>,
    faces: Vec<HullFace>,
    edges: Vec<HullEdge>,
    /// Mass properties at unit density: the mass equals the volume.
    unit: MassProperties,
    /// Largest `|vertex|`, metres: the radius of the ball about the body origin holding the hull.
    bounding_radius: f32,
    /// The vertices four at a time as x, y and z lanes, the last group padded with vertex 0:
    /// [`ConvexHull::support`] takes four dot products per SIMD step.
    vertex_lanes: Vec<[Vec4; 3]>,
    /// The edges four at a time, in the order of [`ConvexHull::edges`], for the separating-axis
    /// edge query.
    edge_lanes: Vec<EdgeLanes>,
    /// The face planes four at a time, in the order of [`ConvexHull::faces`], for the
    /// separating-axis face query.
    face_lanes: Vec<FaceLanes>,
    /// The mean of the vertices, metres: a point inside the hull.
    mean_vertex: Vec3,
    /// Radius of a ball about the mean vertex inside the hull, metres: its distance to the
    /// nearest face plane less twice the hull tolerance (how far a face's plane may lie off its
    /// points), at least 0.
    inner_radius: f32,
}

/// Four edges of a polyhedron laid out by coordinate, a lane each (zero in lanes past the last
/// edge), as the separating-axis edge query reads them: each edge's first end, its direction
/// (second end less first), the unit outward normals `n₁, n₂` of its two faces (the ends of its
/// arc on the Gauss map) and their dot product `n₁ · n₂`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct EdgeLanes {
    pub(crate) start: [Vec4; 3],
    pub(crate) direction: [Vec4; 3],
    pub(crate) normals: [[Vec4; 3]; 2],
    pub(crate) cosine: Vec4,
}

impl EdgeLanes {
    /// At most four edges, each as `[first end, second end, n₁, n₂]`.
    pub(crate) fn new(edges: &[[Vec3; 4]]) -> Self {
        let by_coordinate = |value: &dyn Fn(&[Vec3; 4]) -> Vec3| {
            let [p, q, r, s] =
                std::array::from_fn(|lane| edges.get(lane).map_or(Vec3::ZERO, value));
            [
                Vec4::new(p.x, q.x, r.x, s.x),
                Vec4::new(p.y, q.y, r.y, s.y),
                Vec4::new(p.z, q.z, r.z, s.z),
            ]
        };
        let cosines: [f32; 4] = std::array::from_fn(|lane| {
            edges
                .get(lane)
                .map_or(0.0, |&[_, _, first, second]| first.dot(second))
        });
        Self {
            start: by_coordinate(&|&[start, ..]| start),
            direction: by_coordinate(&|&[start, end, ..]| end - start),
            normals: [
                by_coordinate(&|&[_, _, first, _]| first),
                by_coordinate(&|&[.., second]| second),
            ],
            cosine: Vec4::from_array(cosines),
        }
    }

    /// Lane `lane`'s first end.
    #[inline]
    pub(crate) fn start(&self, lane: usize) -> Vec3 {
        lane_vector(&self.start, lane)
    }

    /// Lane `lane`'s direction.
    #[inline]
    pub(crate) fn direction(&self, lane: usize) -> Vec3 {
        lane_vector(&self.direction, lane)
    }

    /// Lane `lane`'s face normals.
    #[inline]
    pub(crate) fn normals(&self, lane: usize) -> [Vec3; 2] {
        self.normals.map(|normal| lane_vector(&normal, lane))
    }
}

/// Four face planes laid out by coordinate, a lane each (zero in lanes past the last face): unit
/// outward normals and offsets, `normal · p = offset` on the face.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct FaceLanes {
    pub(crate) normal: [Vec4; 3],
    pub(crate) offset: Vec4,
}

impl FaceLanes {
    /// At most four planes, each as its normal and offset.
    pub(crate) fn new(planes: &[(Vec3, f32)]) -> Self {
        let lane = |value: &dyn Fn(&(Vec3, f32)) -> f32| {
            Vec4::from_array(std::array::from_fn(|lane| {
                planes.get(lane).map_or(0.0, value)
            }))
        };
        Self {
            normal: [
                lane(&|(normal, _)| normal.x),
                lane(&|(normal, _)| normal.y),
                lane(&|(normal, _)| normal.z),
            ],
            offset: lane(&|&(_, offset)| offset),
        }
    }
}

/// The vector in lane `lane` of x, y and z lanes.
#[inline]
fn lane_vector(coordinates: &[Vec4; 3], lane: usize) -> Vec3 {
    let [x, y, z] = coordinates.each_ref().map(|column| column.as_ref()[lane]);
    Vec3::new(x, y, z)
}

impl ConvexHull {
    /// The hull of `points` (metres, body frame).
    ///
    /// The tolerance is `1e-5` of the cloud's largest extent, and at least four `f32` ulps of its
    /// largest coordinate. Points closer than that to each other count as one, and to a plane of
    /// the hull as on it: nearly coplanar faces merge and the points inside them drop.
    ///
    /// # Errors
    /// A non-finite coordinate, field `points[i]` ([`ErrorKind::NotFinite`]); fewer than 4 points,
    /// points all coincident, collinear or coplanar (the hull no thicker than twice the tolerance),
    /// or a volume or inertia that an `f32` cannot hold, field `points`
    /// ([`ErrorKind::DegenerateHull`]). Building takes `O(n log n)` time for typical clouds.
    pub fn new(points: &[Vec3]) -> Result<Self> {
        for (index, &point) in points.iter().enumerate() {
            check_named(
                |field| check_length(field, point, MAX_SIZE),
                || format!("points[{index}]"),
            )?;
        }
        if points.len() < 4 {
            return Err(degenerate("fewer than 4 points"));
        }
        if u32::try_from(points.len()).is_err() {
            return Err(degenerate("more than u32::MAX points"));
        }
        let cloud = Cloud::new(points)?;
        let simplex = initial_simplex(&cloud)?;
        let facets = Quickhull::build(&cloud.grid, simplex)?;
        let (outlines, normals) = Merger::new(&cloud, &facets).merge();
        let outlines = drop_edge_vertices(outlines, &cloud.positions, cloud.tolerance);
        assemble(&cloud.positions, &outlines, &normals, cloud.tolerance)
    }

    /// Checks a decoded hull: at least four vertices within the size limit and four faces,
    /// every face and edge naming vertices and faces of the hull, the groups of four built from
    /// them, values finite. (Building the hull again from its vertices may not give the same
    /// faces for a sliver, so the hull is checked, not rebuilt.)
    #[cfg(feature = "serde")]
    pub(crate) fn check_decoded(&self) -> std::result::Result<(), String> {
        let (vertex_count, face_count) = (self.vertices.len(), self.faces.len());
        let names_vertices = |indices: &[u32]| indices.iter().all(|&i| (i as usize) < vertex_count);
        let indices_fit = vertex_count >= 4
            && face_count >= 4
            && u32::try_from(vertex_count).is_ok()
            && self.faces.iter().all(|face| {
                face.vertices.len() >= 3
                    && names_vertices(&face.vertices)
                    && face.normal.is_finite()
                    && face.offset.is_finite()
            })
            && self.edges.iter().all(|edge| {
                names_vertices(&edge.vertices)
                    && edge.faces.iter().all(|&face| (face as usize) < face_count)
            });
        if !indices_fit {
            return Err("a hull's faces or edges name vertices or faces it lacks".to_owned());
        }
        let (edge_lanes, face_lanes) =
            edge_and_face_lanes(&self.vertices, &self.faces, &self.edges);
        let unit = &self.unit;
        let consistent = edge_lanes == self.edge_lanes
            && face_lanes == self.face_lanes
            && vertex_lanes(&self.vertices) == self.vertex_lanes
            && self
                .vertices
                .iter()
                .all(|vertex| vertex.abs().max_element() <= MAX_SIZE)
            && unit.mass.is_finite()
            && unit.mass > 0.0
            && unit.center_of_mass.is_finite()
            && unit.inertia.is_finite()
            && [self.bounding_radius, self.inner_radius]
                .iter()
                .all(|r| r.is_finite())
            && self.mean_vertex.is_finite();
        if consistent {
            Ok(())
        } else {
            Err("a hull's derived values do not follow from its vertices and faces".to_owned())
        }
    }

    /// Hull vertices, metres, in the order of the input points.
    pub fn vertices(&self) -> &[Vec3] {
        &self.vertices
    }

    /// Hull faces: convex polygons (to within the tolerance), one per plane.
    pub fn faces(&self) -> &[HullFace] {
        &self.faces
    }

    /// Hull edges, each once, sorted by their vertex indices.
    pub fn edges(&self) -> &[HullEdge] {
        &self.edges
    }

    /// The edges four to a group, in the order of [`ConvexHull::edges`].
    pub(crate) fn edge_lanes(&self) -> &[EdgeLanes] {
        &self.edge_lanes
    }

    /// The face planes four to a group, in the order of [`ConvexHull::faces`].
    pub(crate) fn face_lanes(&self) -> &[FaceLanes] {
        &self.face_lanes
    }

    /// The mean of the vertices, metres: a point inside the hull.
    pub(crate) fn mean_vertex(&self) -> Vec3 {
        self.mean_vertex
    }

    /// Radius of a ball about [`ConvexHull::mean_vertex`] that the hull holds, metres.
    pub(crate) fn inner_radius(&self) -> f32 {
        self.inner_radius
    }

    /// Radius of the ball about the body origin that holds the hull (its farthest vertex), metres.
    pub fn bounding_radius(&self) -> f32 {
        self.bounding_radius
    }

    /// Mass properties of the solid hull at uniform `density` (kg/m³), exact for the polyhedron.
    ///
    /// Each face is fanned into triangles `(a, b, c)`, taken relative to the mean vertex `r`; each
    /// makes a tetrahedron with apex `r` of signed volume `det[a b c]/6`. Summed over all of them:
    /// `V = Σ det/6`, `∫x dV = Σ det·s/24` and `∫x xᵀ dV = Σ det/120·(aaᵀ + bbᵀ + ccᵀ + ssᵀ)` with
    /// `s = a + b + c`. With `g = ∫x dV / V`, the centre of mass is `r + g`, the central second
    /// moment `C = ∫x xᵀ dV − V g gᵀ`, and the inertia about the centre of mass `I = ρ (tr C·𝟙 − C)`,
    /// a full symmetric tensor (kg·m²); the mass is `ρ V` (kg). Evaluated once, in `f64`, when the
    /// hull is built.
    pub fn mass_properties(&self, density: f32) -> MassProperties {
        MassProperties {
            mass: density * self.unit.mass,
            center_of_mass: self.unit.center_of_mass,
            inertia: self.unit.inertia * density,
        }
    }

    /// World bounding box at `pose`: the box of the transformed vertices.
    pub fn aabb(&self, pose: &Pose) -> Aabb {
        let (min, max) = self.vertices.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(min, max), vertex| {
                let point = pose.transform_point(*vertex);
                (min.min(point), max.max(point))
            },
        );
        Aabb::new(min, max)
    }

    /// The vertex with the largest `vertex · direction`; ties (and a NaN direction) go to the
    /// lowest index.
    pub fn support(&self, direction: Vec3) -> Vec3 {
        let [x, y, z] = direction.to_array().map(Vec4::splat);
        let dots = |[xs, ys, zs]: &[Vec4; 3]| xs * x + ys * y + zs * z;
        let Some(first) = self.vertex_lanes.first() else {
            return Vec3::ZERO;
        };
        // Each lane keeps its farthest vertex (the earliest on ties, the first on NaN).
        let (mut best_dot, mut best_index) = (dots(first), Vec4::new(0.0, 1.0, 2.0, 3.0));
        let mut index = best_index;
        for group in &self.vertex_lanes[1..] {
            index += Vec4::splat(4.0);
            let dot = dots(group);
            let farther = dot.cmpgt(best_dot);
            best_dot = Vec4::select(farther, dot, best_dot);
            best_index = Vec4::select(farther, index, best_index);
        }
        let (dots, indices) = (best_dot.to_array(), best_index.to_array());
        let mut best = 0;
        for lane in 1..4 {
            let (dot, current) = (dots[lane], dots[best]);
            if dot > current || (dot == current && indices[lane] < indices[best]) {
                best = lane;
            }
        }
        // A padding lane (past the last vertex) holds vertex 0.
        let vertex = self.vertices.get(indices[best] as usize);
        vertex
            .or(self.vertices.first())
            .copied()
            .unwrap_or(Vec3::ZERO)
    }
}

/// The vertices as groups of four x, y and z lanes, the last group padded with vertex 0.
fn vertex_lanes(vertices: &[Vec3]) -> Vec<[Vec4; 3]> {
    vertices
        .chunks(4)
        .map(|group| {
            let lane = |coordinate: fn(&Vec3) -> f32| {
                let mut values = [coordinate(&vertices[0]); 4];
                for (value, vertex) in values.iter_mut().zip(group) {
                    *value = coordinate(vertex);
                }
                Vec4::from_array(values)
            };
            [lane(|v| v.x), lane(|v| v.y), lane(|v| v.z)]
        })
        .collect()
}

/// A [`ErrorKind::DegenerateHull`] error on field `points`.
fn degenerate(reason: &'static str) -> Error {
    Error::new("points", ErrorKind::DegenerateHull(reason))
}

/// The error for a hull whose exact construction contradicts itself; exact arithmetic rules it
/// out, so it stands guard instead of a panic.
fn inconsistent() -> Error {
    degenerate("inconsistent hull topology")
}

/// The hull of polygon `outlines` over `positions`: vertices renumbered in input order, face planes
/// (the `normals` the polygons were merged on, offset of the farthest face vertex), edges and mass
/// properties.
///
/// Fails as coplanar when the hull is no thicker than twice `tolerance` across its largest face:
/// it then fits in the band of ±`tolerance` that faces merge within, so its top and bottom are not
/// told apart. (The initial simplex only catches a cloud thinner than about one tolerance.)
fn assemble(
    positions: &[DVec3],
    outlines: &[Vec<u32>],
    normals: &[DVec3],
    tolerance: f64,
) -> Result<ConvexHull> {
    let mut used = vec![false; positions.len()];
    for &vertex in outlines.iter().flatten() {
        used[vertex as usize] = true;
    }
    let mut renumber = vec![0u32; positions.len()];
    let mut corners = Vec::new();
    for (point, position) in positions.iter().enumerate() {
        if used[point] {
            renumber[point] = corners.len() as u32;
            corners.push(*position);
        }
    }
    let mut faces = Vec::with_capacity(outlines.len());
    let mut largest = (0.0, DVec3::ZERO, 0.0);
    for (outline, &normal) in outlines.iter().zip(normals) {
        let mut vertices: Vec<u32> = outline
            .iter()
            .map(|&vertex| renumber[vertex as usize])
            .collect();
        let smallest = (0..vertices.len())
            .min_by_key(|&k| vertices[k])
            .unwrap_or(0);
        vertices.rotate_left(smallest);
        let origin = corners[vertices[0] as usize];
        let area = vertices
            .iter()
            .zip(vertices.iter().cycle().skip(1))
            .map(|(&a, &b)| (corners[a as usize] - origin).cross(corners[b as usize] - origin))
            .sum::<DVec3>()
            .dot(normal);
        let offset = vertices
            .iter()
            .map(|&vertex| normal.dot(corners[vertex as usize]))
            .fold(f64::NEG_INFINITY, f64::max);
        if area > largest.0 {
            largest = (area, normal, offset);
        }
        faces.push(HullFace {
            normal: normal.as_vec3(),
            offset: offset as f32,
            vertices,
        });
    }
    let (_, normal, offset) = largest;
    let thickness = corners
        .iter()
        .map(|corner| offset - normal.dot(*corner))
        .fold(0.0, f64::max);
    if thickness <= 2.0 * tolerance {
        return Err(degenerate("all points are coplanar"));
    }
    let mut directed = BTreeMap::new();
    for (index, face) in faces.iter().enumerate() {
        let ring = face
            .vertices
            .iter()
            .zip(face.vertices.iter().cycle().skip(1));
        for (&from, &to) in ring {
            if directed.insert((from, to), index as u32).is_some() {
                return Err(inconsistent());
            }
        }
    }
    let mut edges = Vec::with_capacity(directed.len() / 2);
    for (&(from, to), &face) in &directed {
        if from < to {
            let twin = *directed.get(&(to, from)).ok_or_else(inconsistent)?;
            edges.push(HullEdge {
                vertices: [from, to],
                faces: [face, twin],
            });
        }
    }
    if 2 * edges.len() != directed.len() {
        return Err(inconsistent());
    }
    let unit = unit_mass_properties(&corners, &faces)?;
    let vertices: Vec<Vec3> = corners.iter().map(|corner| corner.as_vec3()).collect();
    let bounding_radius = vertices
        .iter()
        .fold(0.0, |largest: f32, vertex| largest.max(vertex.length()));
    let (edge_lanes, face_lanes) = edge_and_face_lanes(&vertices, &faces, &edges);
    let mean_vertex = vertices.iter().copied().sum::<Vec3>() / vertices.len().max(1) as f32;
    let nearest_face = faces
        .iter()
        .map(|face| face.offset - face.normal.dot(mean_vertex))
        .fold(f32::INFINITY, f32::min);
    Ok(ConvexHull {
        edge_lanes,
        face_lanes,
        mean_vertex,
        inner_radius: (nearest_face - 2.0 * tolerance as f32).max(0.0),
        faces,
        edges,
        unit,
        bounding_radius,
        vertex_lanes: vertex_lanes(&vertices),
        vertices,
    })
}

/// The edges and the face planes four to a group; every index in `faces` and `edges` must name
/// one of `vertices` and `faces`.
fn edge_and_face_lanes(
    vertices: &[Vec3],
    faces: &[HullFace],
    edges: &[HullEdge],
) -> (Vec<EdgeLanes>, Vec<FaceLanes>) {
    let edge_ends: Vec<[Vec3; 4]> = edges
        .iter()
        .map(|edge| {
            let [start, end] = edge.vertices.map(|vertex| vertices[vertex as usize]);
            let [first, second] = edge.faces.map(|face| faces[face as usize].normal);
            [start, end, first, second]
        })
        .collect();
    let planes: Vec<(Vec3, f32)> = faces
        .iter()
        .map(|face| (face.normal, face.offset))
        .collect();
    (
        edge_ends.chunks(4).map(EdgeLanes::new).collect(),
        planes.chunks(4).map(FaceLanes::new).collect(),
    )
}

/// `a aᵀ`.
fn outer(a: DVec3) -> DMat3 {
    DMat3::from_cols(a * a.x, a * a.y, a * a.z)
}

/// Volume, centroid and central inertia at unit density, by the tetrahedron fan described on
/// [`ConvexHull::mass_properties`].
fn unit_mass_properties(corners: &[DVec3], faces: &[HullFace]) -> Result<MassProperties> {
    let reference = corners.iter().sum::<DVec3>() / corners.len() as f64;
    let mut six_volume = 0.0;
    let mut first_moment = DVec3::ZERO;
    let mut second_moment = DMat3::ZERO;
    for face in faces {
        let corner = |vertex: u32| corners[vertex as usize] - reference;
        let a = corner(face.vertices[0]);
        for pair in face.vertices[1..].windows(2) {
            let (b, c) = (corner(pair[0]), corner(pair[1]));
            let det = a.dot(b.cross(c));
            let s = a + b + c;
            six_volume += det;
            first_moment += det * s;
            second_moment += det * (outer(a) + outer(b) + outer(c) + outer(s));
        }
    }
    let volume = six_volume / 6.0;
    let offset = first_moment / (24.0 * volume);
    let central = second_moment * (1.0 / 120.0) - volume * outer(offset);
    let trace = central.x_axis.x + central.y_axis.y + central.z_axis.z;
    let inertia = DMat3::from_diagonal(DVec3::splat(trace)) - central;
    let properties = MassProperties {
        mass: volume as f32,
        center_of_mass: (reference + offset).as_vec3(),
        inertia: inertia.as_mat3(),
    };
    if !(properties.mass.is_normal() && properties.mass > 0.0) {
        return Err(degenerate("volume does not fit in an f32"));
    }
    if !properties.center_of_mass.is_finite() || !properties.inertia.is_finite() {
        return Err(degenerate("inertia does not fit in an f32"));
    }
    Ok(properties)
}
