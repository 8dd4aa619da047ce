//! The `trimesh` and `heightfield` shapes of scene files: inline triangles or a Wavefront OBJ
//! file (read with `tobj`, relative to the scene file), and rows of heights.

use std::io::{BufReader, Cursor};
use std::path::Path;

use crate::error::ErrorKind;
use crate::math::Vec3;
use crate::shape::{Shape, TriMesh, TriangleMaterial};

use super::convert::{scalar, vector};
use super::format::{MaterialEntry, ShapeEntry};
use super::{join, LoadError, SceneError};

/// Where the mesh files a scene names are found: among files given with the scene (by the name
/// the scene uses), else in the scene file's folder, or the working directory for a scene given
/// as text.
#[derive(Debug, Clone, Copy)]
pub(super) struct MeshFiles<'a> {
    /// The folder relative paths start from.
    pub(super) folder: &'a Path,
    /// Files given with the scene: name as written in the scene, contents.
    pub(super) given: &'a [(&'a str, &'a [u8])],
}

impl MeshFiles<'_> {
    /// The triangles of the OBJ file `file` (relative to the folder): every object's faces,
    /// triangulated, as one mesh. A file that cannot be read or parsed is a
    /// [`LoadError::Mesh`] at `place`.
    pub(super) fn read_obj(
        &self,
        file: &str,
        place: &str,
    ) -> Result<(Vec<Vec3>, Vec<[u32; 3]>), LoadError> {
        let path = self.folder.join(file);
        let failure = |message: String| LoadError::Mesh {
            place: place.to_owned(),
            path: path.clone(),
            message,
        };
        let bytes = match self.given.iter().find(|(name, _)| *name == file) {
            Some((_, contents)) => contents.to_vec(),
            None => std::fs::read(&path).map_err(|error| failure(error.to_string()))?,
        };
        let options = tobj::LoadOptions {
            triangulate: true,
            single_index: true,
            ..tobj::LoadOptions::default()
        };
        let mut reader = BufReader::new(Cursor::new(bytes));
        // Materials are not used: the material library is not even opened.
        let (models, _) = tobj::load_obj_buf(&mut reader, &options, |_| {
            Err(tobj::LoadError::OpenFileFailed)
        })
        .map_err(|error| failure(format!("not a valid OBJ file: {error}")))?;
        let mut vertices = Vec::new();
        let mut indices = Vec::new();
        for model in &models {
            let offset = u32::try_from(vertices.len())
                .map_err(|_| failure("too many vertices".to_owned()))?;
            let mesh = &model.mesh;
            vertices.extend(
                mesh.positions
                    .chunks_exact(3)
                    .map(|p| Vec3::new(p[0], p[1], p[2])),
            );
            for triangle in mesh.indices.chunks_exact(3) {
                indices.push([0, 1, 2].map(|k| triangle[k].saturating_add(offset)));
            }
        }
        Ok((vertices, indices))
    }
}

/// A `trimesh` entry: inline `vertices` and `indices`, or an OBJ `file`, each vertex multiplied
/// by `scale` component by component. Errors are placed under `place`.
pub(super) fn trimesh(
    entry: &ShapeEntry,
    place: &str,
    files: &MeshFiles,
) -> Result<Shape, LoadError> {
    let field = |name: &str| join(place, name);
    let scale = match entry.scale {
        Some(value) => positive_scale(&field("scale"), value)?,
        None => Vec3::ONE,
    };
    let (vertices, indices) = match (&entry.file, &entry.vertices, &entry.indices) {
        (Some(_), Some(_), _) | (Some(_), _, Some(_)) => {
            let message = "give either `file` or `vertices` and `indices`, not both";
            return Err(SceneError::new(field("file"), message).into());
        }
        (Some(file), None, None) => files.read_obj(file, &field("file"))?,
        (None, Some(vertices), Some(indices)) => {
            let vertices = vertices
                .iter()
                .enumerate()
                .map(|(index, vertex)| vector(&format!("{place}.vertices[{index}]"), *vertex))
                .collect::<Result<Vec<_>, _>>()?;
            (vertices, indices.clone())
        }
        (None, None, _) => return Err(missing(place, "vertices", "trimesh").into()),
        (None, Some(_), None) => return Err(missing(place, "indices", "trimesh").into()),
    };
    let scaled = vertices.into_iter().map(|vertex| vertex * scale).collect();
    let mesh = match (&entry.materials, &entry.triangle_materials) {
        (None, None) => TriMesh::new(scaled, &indices),
        (Some(materials), Some(triangle_materials)) => {
            let materials = (materials.iter().enumerate())
                .map(|(index, entry)| material(entry, &field(&format!("materials[{index}]"))))
                .collect::<Result<Vec<_>, _>>()?;
            TriMesh::with_materials(scaled, &indices, materials, triangle_materials)
        }
        (Some(_), None) => {
            let message = "required field is missing (a trimesh with `materials` needs it)";
            return Err(SceneError::new(field("triangle_materials"), message).into());
        }
        (None, Some(_)) => {
            let message =
                "required field is missing (a trimesh with `triangle_materials` needs it)";
            return Err(SceneError::new(field("materials"), message).into());
        }
    };
    mesh.map(Shape::TriMesh)
        .map_err(|error| SceneError::from(error.within(place)).into())
}

/// One of a trimesh's `materials`, its values narrowed (their ranges are the mesh's to check);
/// errors are placed under `place`.
fn material(entry: &MaterialEntry, place: &str) -> Result<TriangleMaterial, SceneError> {
    let value = |name: &str, value: Option<f64>| {
        value
            .map(|value| scalar(&join(place, name), value))
            .transpose()
    };
    Ok(TriangleMaterial {
        friction: value("friction", entry.friction)?,
        restitution: value("restitution", entry.restitution)?,
        rolling_resistance: value("rolling_resistance", entry.rolling_resistance)?,
    })
}

/// A `heightfield` entry; errors are placed under `place`.
pub(super) fn heightfield(
    heights: &[Vec<f64>],
    scale: [f64; 3],
    place: &str,
) -> Result<Shape, SceneError> {
    let scale = positive_scale(&join(place, "scale"), scale)?;
    let rows = heights
        .iter()
        .enumerate()
        .map(|(i, row)| {
            row.iter()
                .enumerate()
                .map(|(j, &height)| scalar(&format!("{place}.heights[{i}][{j}]"), height))
                .collect::<Result<Vec<_>, _>>()
        })
        .collect::<Result<Vec<_>, _>>()?;
    Shape::heightfield(&rows, scale).map_err(|error| SceneError::from(error.within(place)))
}

/// A `scale`: finite, every component positive.
fn positive_scale(place: &str, value: [f64; 3]) -> Result<Vec3, SceneError> {
    let scale = vector(place, value)?;
    for (index, component) in scale.to_array().into_iter().enumerate() {
        if component <= 0.0 {
            let message = ErrorKind::NotPositive(component).to_string();
            return Err(SceneError::new(format!("{place}[{index}]"), message));
        }
    }
    Ok(scale)
}

/// A required field missing from a shape of type `kind`.
fn missing(place: &str, field: &str, kind: &str) -> SceneError {
    SceneError::new(
        join(place, field),
        format!("required field is missing (a {kind} shape needs it)"),
    )
}
