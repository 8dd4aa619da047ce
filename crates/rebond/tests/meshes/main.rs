//! Triangle meshes and heightfields against closed forms: balls roll and boxes slide across the
//! edges between triangles as on one plane (shared vertices or not), a cylinder's rim stays out of
//! dips and bumps, a box slides down a tilted heightfield at
//! `g (sin θ − μ cos θ)`, a fast ball stops at a wall of two triangles, shapes poured on a terrain
//! rest on it, and geometry is shared, not copied.

#[path = "../common/mod.rs"]
mod common;
mod cylinders;
mod floors;
mod geometry;
mod materials;
mod queries;
#[path = "../common/random.rs"]
mod random;
mod terrain;

pub use common::{world, DT, G};
use rebond::{Quat, Shape, Vec3};

/// A flat square floor in the plane y = 0, `size` metres a side centred on the origin, of
/// `cells × cells` squares each split in two triangles along a diagonal that alternates from
/// cell to cell (so edges run along X, along Z and along both diagonals), the triangles sharing
/// their vertices.
pub fn floor_mesh(size: f32, cells: u32) -> Shape {
    floor(size, cells, true)
}

/// [`floor_mesh`] with a vertex per square corner: neighbouring squares share no vertex index,
/// only the positions, as in an OBJ file written a face at a time.
pub fn floor_quads(size: f32, cells: u32) -> Shape {
    floor(size, cells, false)
}

fn floor(size: f32, cells: u32, shared: bool) -> Shape {
    let (vertices, indices) = floor_triangles(size, cells, shared);
    Shape::trimesh(vertices, &indices).unwrap()
}

/// The vertices and triangles of [`floor_mesh`] (`shared`) or [`floor_quads`].
pub fn floor_triangles(size: f32, cells: u32, shared: bool) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let corner = |i: u32, j: u32| {
        let x = (j as f32 / cells as f32 - 0.5) * size;
        let z = (i as f32 / cells as f32 - 0.5) * size;
        Vec3::new(x, 0.0, z)
    };
    let mut vertices = Vec::new();
    if shared {
        for i in 0..=cells {
            for j in 0..=cells {
                vertices.push(corner(i, j));
            }
        }
    }
    let mut indices = Vec::new();
    for i in 0..cells {
        for j in 0..cells {
            let corners = [(i, j), (i, j + 1), (i + 1, j + 1), (i + 1, j)];
            let [a, b, c, d] = corners.map(|(i, j)| {
                if shared {
                    i * (cells + 1) + j
                } else {
                    vertices.push(corner(i, j));
                    vertices.len() as u32 - 1
                }
            });
            // Counter-clockwise about +Y: a → d → c → b.
            if (i + j) % 2 == 0 {
                indices.push([a, d, c]);
                indices.push([a, c, b]);
            } else {
                indices.push([a, d, b]);
                indices.push([b, d, c]);
            }
        }
    }
    (vertices, indices)
}

/// The horizontal unit direction at `angle` radians from +X toward −Z (about +Y).
pub fn heading(angle: f32) -> Vec3 {
    Quat::from_rotation_y(angle) * Vec3::X
}
