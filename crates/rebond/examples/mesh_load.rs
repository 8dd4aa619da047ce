//! Times building a triangle mesh of about a million triangles (a bumpy grid of 708 × 708
//! squares, two triangles each) and prints its memory per triangle, hierarchy included, as one
//! CSV line: `triangles,vertices,build_ms,bytes,bytes_per_triangle`.
//!
//! `cargo run --release -p rebond --example mesh_load`

use std::time::Instant;

use rebond::shape::TriMesh;
use rebond::Vec3;

fn main() -> Result<(), rebond::Error> {
    let cells: u32 = 708;
    let mut vertices = Vec::with_capacity(((cells + 1) * (cells + 1)) as usize);
    for i in 0..=cells {
        for j in 0..=cells {
            let (x, z) = (j as f32 * 0.5, i as f32 * 0.5);
            vertices.push(Vec3::new(x, (x * 0.3).sin() * (z * 0.2).cos(), z));
        }
    }
    let at = |i: u32, j: u32| i * (cells + 1) + j;
    let mut indices = Vec::with_capacity((2 * cells * cells) as usize);
    for i in 0..cells {
        for j in 0..cells {
            indices.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            indices.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    let vertex_count = vertices.len();
    let start = Instant::now();
    let mesh = TriMesh::new(vertices, &indices)?;
    let build_ms = start.elapsed().as_secs_f64() * 1e3;
    let triangles = mesh.indices().len();
    let bytes = mesh.heap_bytes();
    println!("triangles,vertices,build_ms,bytes,bytes_per_triangle");
    println!(
        "{triangles},{vertex_count},{build_ms:.1},{bytes},{:.1}",
        bytes as f64 / triangles as f64
    );
    Ok(())
}
