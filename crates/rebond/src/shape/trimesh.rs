//! Triangle meshes: static or kinematic level geometry, shared between clones through an `Arc`.

use std::sync::Arc;

use super::bvh::Bvh;
use super::triangle::{edge_flags, Triangle};
use crate::error::{
    check_length, check_named, check_non_negative, check_range, Error, ErrorKind, Result,
};
use crate::limits::MAX_SIZE;
use crate::math::{Aabb, Pose, Vec3};

/// A triangle mesh in the body frame. Cloning it (or a shape, body description or world holding
/// it) shares the geometry; nothing is copied.
///
/// Both sides of every triangle collide. Each triangle keeps, per edge and side, whether the edge
/// may produce edge contacts (see [`Triangle`]): edges between triangles of a flat or gently bent
/// surface do not, so bodies slide and roll across them as on one surface. Neighbours are found by
/// position: triangles whose corners repeat the same coordinates under other vertex indices (a
/// vertex per triangle corner, as OBJ exports often have) are neighbours as if they shared the
/// vertices, while the vertices and indices stay as given.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TriMesh {
    #[cfg_attr(feature = "serde", serde(with = "crate::state::shared"))]
    data: Arc<TriMeshData>,
}

#[derive(Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct TriMeshData {
    vertices: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    edge_flags: Vec<u8>,
    bvh: Bvh,
    bounds: Aabb,
    /// The mesh's table of surface materials; empty for a mesh of the body's material.
    materials: Vec<TriangleMaterial>,
    /// Each triangle's index into `materials`; empty with them.
    triangle_materials: Vec<u32>,
}

/// The surface of some of a mesh's triangles ([`TriMesh::with_materials`]): each value left
/// `None` (the default) is the body's, as for a compound's child.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TriangleMaterial {
    /// Coulomb friction coefficient, ≥ 0.
    pub friction: Option<f32>,
    /// Coefficient of restitution, 0 to 1.
    pub restitution: Option<f32>,
    /// Rolling resistance coefficient, ≥ 0, dimensionless (as [`crate::BodyDesc`]'s).
    pub rolling_resistance: Option<f32>,
}

impl TriMesh {
    /// A mesh of `vertices` (metres, body frame) and triangles `indices` into them, each
    /// counter-clockwise about what is taken as its front (both sides collide alike). Triangles
    /// of zero area are skipped, so triangle `k` of the mesh is the `k`-th triangle of positive
    /// area. Errors: a non-finite vertex (field `vertices[i]`), an index out of range
    /// (`indices[k]`), or no triangle of positive area (`indices`).
    pub fn new(vertices: Vec<Vec3>, indices: &[[u32; 3]]) -> Result<Self> {
        Self::build(vertices, indices, Vec::new(), &[])
    }

    /// A mesh as [`TriMesh::new`] makes it whose triangle `k` of `indices` has the surface
    /// `materials[triangle_materials[k]]` (one index per given triangle, zero-area ones
    /// included): a contact with the mesh takes the friction, restitution and rolling resistance
    /// of the triangle it touches, each the body's where the material leaves it `None`. Errors,
    /// besides [`TriMesh::new`]'s: `materials[i].friction` or `materials[i].rolling_resistance`
    /// negative or not finite, `materials[i].restitution` outside 0 to 1, `triangle_materials`
    /// not one per triangle, `triangle_materials[k]` out of range.
    pub fn with_materials(
        vertices: Vec<Vec3>,
        indices: &[[u32; 3]],
        materials: Vec<TriangleMaterial>,
        triangle_materials: &[u32],
    ) -> Result<Self> {
        for (index, material) in materials.iter().enumerate() {
            check_material(material)
                .map_err(|error| error.within(&format!("materials[{index}]")))?;
        }
        if triangle_materials.len() != indices.len() {
            let kind = ErrorKind::WrongCount {
                expected: indices.len(),
                got: triangle_materials.len(),
            };
            return Err(Error::new("triangle_materials", kind));
        }
        if let Some((index, &bad)) = (triangle_materials.iter().enumerate())
            .find(|&(_, &material)| material as usize >= materials.len())
        {
            let kind = ErrorKind::MaterialOutOfRange {
                index: bad,
                len: materials.len(),
            };
            return Err(Error::new(format!("triangle_materials[{index}]"), kind));
        }
        Self::build(vertices, indices, materials, triangle_materials)
    }

    /// [`TriMesh::new`] with the checked `materials` and their `triangle_materials`, one per
    /// given triangle (both empty for a mesh of the body's material).
    fn build(
        vertices: Vec<Vec3>,
        indices: &[[u32; 3]],
        materials: Vec<TriangleMaterial>,
        triangle_materials: &[u32],
    ) -> Result<Self> {
        for (index, &vertex) in vertices.iter().enumerate() {
            check_named(
                |field| check_length(field, vertex, MAX_SIZE),
                || format!("vertices[{index}]"),
            )?;
        }
        let mut triangles = Vec::with_capacity(indices.len());
        let mut kept_materials = Vec::with_capacity(triangle_materials.len());
        for (index, triangle) in indices.iter().enumerate() {
            if let Some(&bad) = triangle.iter().find(|&&i| i as usize >= vertices.len()) {
                let kind = ErrorKind::IndexOutOfRange {
                    index: bad,
                    len: vertices.len(),
                };
                return Err(Error::new(format!("indices[{index}]"), kind));
            }
            let corners = triangle.map(|i| vertices[i as usize]);
            let area = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
            if area.try_normalize().is_some() {
                triangles.push(*triangle);
                kept_materials.extend(triangle_materials.get(index));
            }
        }
        if triangles.is_empty() {
            return Err(Error::new("indices", ErrorKind::EmptyMesh));
        }
        let boxes: Vec<Aabb> = triangles
            .iter()
            .map(|triangle| {
                let [a, b, c] = triangle.map(|i| vertices[i as usize]);
                Aabb::new(a.min(b).min(c), a.max(b).max(c))
            })
            .collect();
        let bvh = Bvh::build(&boxes);
        let bounds = bvh.bounds().unwrap_or(Aabb::new(Vec3::ZERO, Vec3::ZERO));
        let edge_flags = mesh_edge_flags(&vertices, &triangles);
        Ok(Self {
            data: Arc::new(TriMeshData {
                vertices,
                triangles,
                edge_flags,
                bvh,
                bounds,
                materials,
                triangle_materials: kept_materials,
            }),
        })
    }

    /// The mesh that its own vertices, triangles and materials build: a decoded mesh is checked
    /// against it.
    #[cfg(feature = "serde")]
    pub(crate) fn rebuilt(&self) -> Result<Self> {
        let data = &self.data;
        if data.materials.is_empty() && data.triangle_materials.is_empty() {
            return Self::new(data.vertices.clone(), &data.triangles);
        }
        Self::with_materials(
            data.vertices.clone(),
            &data.triangles,
            data.materials.clone(),
            &data.triangle_materials,
        )
    }

    /// The vertices, metres, body frame.
    pub fn vertices(&self) -> &[Vec3] {
        &self.data.vertices
    }

    /// The triangles of positive area, as indices into [`TriMesh::vertices`].
    pub fn indices(&self) -> &[[u32; 3]] {
        &self.data.triangles
    }

    /// Triangle `index` in the body frame with its edge flags, or `None` past the end.
    pub fn triangle(&self, index: u32) -> Option<Triangle> {
        let corners = self.data.triangles.get(index as usize)?;
        let vertices = corners.map(|i| self.data.vertices.get(i as usize).copied());
        Some(Triangle {
            vertices: [vertices[0]?, vertices[1]?, vertices[2]?],
            edge_flags: self.data.edge_flags.get(index as usize).copied()?,
        })
    }

    /// The mesh's table of surface materials ([`TriMesh::with_materials`]); empty for a mesh of
    /// the body's material.
    pub fn materials(&self) -> &[TriangleMaterial] {
        &self.data.materials
    }

    /// The index into [`TriMesh::materials`] of triangle `index`'s surface; `None` for a mesh
    /// without materials or past the end.
    pub fn material_index(&self, index: u32) -> Option<u32> {
        self.data.triangle_materials.get(index as usize).copied()
    }

    /// The surface of triangle `index`; `None` for a mesh without materials or past the end.
    pub fn triangle_material(&self, index: u32) -> Option<&TriangleMaterial> {
        let material = self.material_index(index)?;
        self.data.materials.get(material as usize)
    }

    /// The box around the mesh in the body frame.
    pub fn local_bounds(&self) -> Aabb {
        self.data.bounds
    }

    /// The world box of the mesh at `pose`: its body-frame box's corners, placed.
    pub fn aabb(&self, pose: &Pose) -> Aabb {
        placed_bounds(&self.data.bounds, pose)
    }

    /// Calls `visit(k)` for each triangle `k` whose box overlaps `bounds` (body frame), in the
    /// hierarchy's order.
    pub fn triangles_in(&self, bounds: &Aabb, mut visit: impl FnMut(u32)) {
        self.data.bvh.query(bounds, |item| {
            if let Some(triangle) = self.triangle(item) {
                let [a, b, c] = triangle.vertices;
                if Aabb::new(a.min(b).min(c), a.max(b).max(c)).overlaps(bounds) {
                    visit(item);
                }
            }
        });
    }

    /// Calls `visit(k)` for each triangle in a leaf of the hierarchy whose boxes pass `enter`
    /// (for walks along a ray or a sweep).
    pub fn triangles_where(&self, enter: impl FnMut(&Aabb) -> bool, visit: impl FnMut(u32)) {
        self.data.bvh.walk_boxes(enter, visit);
    }

    /// Bytes of memory the mesh holds: vertices, triangles, edge flags and hierarchy.
    pub fn heap_bytes(&self) -> usize {
        let data = &self.data;
        data.vertices.capacity() * std::mem::size_of::<Vec3>()
            + data.triangles.capacity() * std::mem::size_of::<[u32; 3]>()
            + data.edge_flags.capacity()
            + data.materials.capacity() * std::mem::size_of::<TriangleMaterial>()
            + data.triangle_materials.capacity() * std::mem::size_of::<u32>()
            + data.bvh.heap_bytes()
            + std::mem::size_of::<TriMeshData>()
    }

    /// Whether `self` and `other` share one geometry (a clone of each other).
    pub fn shares_geometry(&self, other: &TriMesh) -> bool {
        Arc::ptr_eq(&self.data, &other.data)
    }
}

/// Checks a triangle material's values, naming the field.
fn check_material(material: &TriangleMaterial) -> Result<()> {
    if let Some(friction) = material.friction {
        check_non_negative("friction", friction)?;
    }
    if let Some(restitution) = material.restitution {
        check_range("restitution", restitution, 0.0, 1.0)?;
    }
    if let Some(resistance) = material.rolling_resistance {
        check_non_negative("rolling_resistance", resistance)?;
    }
    Ok(())
}

/// The box around `bounds` (body frame) placed at `pose`, from its eight corners.
pub(crate) fn placed_bounds(bounds: &Aabb, pose: &Pose) -> Aabb {
    let centre = pose.transform_point(bounds.center());
    let half = bounds.half_extents();
    let axes = [Vec3::X, Vec3::Y, Vec3::Z].map(|axis| pose.transform_vector(axis).abs());
    let reach = axes[0] * half.x + axes[1] * half.y + axes[2] * half.z;
    Aabb::new(centre - reach, centre + reach)
}

/// For each vertex, the lowest index of a vertex at exactly the same position: meshes exported
/// with a vertex per triangle corner (OBJ files often are) repeat each position bit for bit, and
/// their neighbours are found through the repeats. Exact equality (with −0 equal to +0) welds no
/// two distinct points, so no tolerance has to be chosen for the mesh's scale.
fn welded_vertices(vertices: &[Vec3]) -> Vec<u32> {
    // The coordinates' bits above the vertex index, so that one sort of plain integers groups
    // equal positions, lowest index first.
    let mut keys: Vec<u128> = (0u32..)
        .zip(vertices)
        .map(|(index, &vertex)| {
            let [x, y, z] = (vertex + Vec3::ZERO).to_array().map(f32::to_bits);
            (u128::from(x) << 96)
                | (u128::from(y) << 64)
                | (u128::from(z) << 32)
                | u128::from(index)
        })
        .collect();
    keys.sort_unstable();
    let mut welded = vec![0u32; vertices.len()];
    let mut first = 0u128;
    for (rank, &key) in keys.iter().enumerate() {
        if rank == 0 || key >> 32 != first >> 32 {
            first = key;
        }
        welded[key as u32 as usize] = first as u32;
    }
    welded
}

/// The edge flags of every triangle: edges are matched with their neighbours by sorting the
/// edges' welded vertex pairs (see [`welded_vertices`]), so building costs `O(n log n)` for `n`
/// triangles and vertices.
fn mesh_edge_flags(vertices: &[Vec3], triangles: &[[u32; 3]]) -> Vec<u8> {
    let welded = welded_vertices(vertices);
    let mut edges: Vec<(u64, u32)> = Vec::with_capacity(3 * triangles.len());
    for (index, triangle) in (0u32..).zip(triangles) {
        for edge in 0..3u32 {
            let (from, to) = (triangle[edge as usize], triangle[(edge as usize + 1) % 3]);
            let (from, to) = (welded[from as usize], welded[to as usize]);
            let key = (u64::from(from.min(to)) << 32) | u64::from(from.max(to));
            edges.push((key, index * 3 + edge));
        }
    }
    // Only the key orders: runs of equal keys give the same flags in any order.
    edges.sort_unstable_by_key(|&(key, _)| key);
    let mut flags = vec![0u8; triangles.len()];
    let corners = |triangle: usize| triangles[triangle].map(|i| vertices[i as usize]);
    let mut start = 0;
    while start < edges.len() {
        let mut end = start + 1;
        while end < edges.len() && edges[end].0 == edges[start].0 {
            end += 1;
        }
        let run = &edges[start..end];
        for &(_, side) in run {
            let (triangle, edge) = ((side / 3) as usize, (side % 3) as usize);
            let own = corners(triangle);
            let neighbour = match run {
                [first, second] => {
                    let other = if first.1 == side { second.1 } else { first.1 };
                    let (other_triangle, other_edge) = ((other / 3) as usize, other % 3);
                    Some(corners(other_triangle)[(other_edge as usize + 2) % 3])
                }
                _ => None,
            };
            let normal = (own[1] - own[0]).cross(own[2] - own[0]).normalize_or_zero();
            flags[triangle] |= edge_flags(&own, normal, edge, neighbour);
        }
        start = end;
    }
    flags
}
