//! The one-metre grid texture drawn on static bodies, and a halfspace drawn as a large ground
//! plane with that grid on it.

use rebond::shape::Halfspace;
use rebond::{Pose, Quat, Vec3};
use three_d::{
    vec2, vec3, Context, CpuMaterial, CpuMesh, CpuTexture, Gm, Indices, Interpolation, Mesh,
    Mipmap, PhysicalMaterial, Positions, Srgba, TextureData, Wrapping,
};

use super::palette::{Rgb, GRID_LINE_SHADE, STATIC_BODY};

/// Half the side of the drawn plane, metres: far enough that its edge is lost in the distance.
const HALF_SIZE: f32 = 500.0;
/// Side of the grid texture, pixels: one texture repeat is one metre.
const TEXTURE_SIZE: usize = 64;
/// Width of a grid line, texture pixels.
const LINE_WIDTH: usize = 2;

/// The pixels of one grid cell: `plane` with a line along two edges, [`GRID_LINE_SHADE`] as
/// bright, top row first.
fn grid_cell_pixels(plane: Rgb) -> Vec<[u8; 4]> {
    let line = Rgb::BLACK.mix(plane, GRID_LINE_SHADE);
    let on_line = |coordinate: usize| coordinate < LINE_WIDTH;
    (0..TEXTURE_SIZE * TEXTURE_SIZE)
        .map(|index| {
            let (x, y) = (index % TEXTURE_SIZE, index / TEXTURE_SIZE);
            let Rgb([red, green, blue]) = if on_line(x) || on_line(y) {
                line
            } else {
                plane
            };
            [red, green, blue, 255]
        })
        .collect()
}

/// A repeating texture of one grid cell of `plane` colour: one repeat is one metre when texture
/// coordinates are metres.
pub fn grid_texture(plane: Rgb) -> CpuTexture {
    CpuTexture {
        data: TextureData::RgbaU8(grid_cell_pixels(plane)),
        width: TEXTURE_SIZE as u32,
        height: TEXTURE_SIZE as u32,
        min_filter: Interpolation::Linear,
        mag_filter: Interpolation::Linear,
        mipmap: Some(Mipmap::default()),
        wrap_s: Wrapping::Repeat,
        wrap_t: Wrapping::Repeat,
        ..Default::default()
    }
}

/// The lit plane of a halfspace with the grid on it, in the body frame (the renderer places it).
pub fn ground_model(context: &Context) -> Gm<Mesh, PhysicalMaterial> {
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    let mesh = CpuMesh {
        positions: Positions::F32(
            corners
                .iter()
                .map(|&(x, y)| vec3(x * HALF_SIZE, y * HALF_SIZE, 0.0))
                .collect(),
        ),
        normals: Some(vec![vec3(0.0, 0.0, 1.0); 4]),
        uvs: Some(
            corners
                .iter()
                .map(|&(x, y)| vec2(x * HALF_SIZE, y * HALF_SIZE))
                .collect(),
        ),
        indices: Indices::U32(vec![0, 1, 2, 0, 2, 3]),
        ..Default::default()
    };
    let material = PhysicalMaterial::new_opaque(
        context,
        &CpuMaterial {
            albedo: Srgba::WHITE,
            albedo_texture: Some(grid_texture(STATIC_BODY)),
            roughness: 0.9,
            metallic: 0.0,
            ..Default::default()
        },
    );
    Gm::new(Mesh::new(context, &mesh), material)
}

/// The world pose of a halfspace's plane for a body at `pose`: the plane's local +Z turned onto
/// the halfspace's outward normal.
pub fn ground_pose(halfspace: &Halfspace, pose: &Pose) -> Pose {
    let normal = pose.rotation * halfspace.normal();
    Pose::new(pose.position, Quat::from_rotation_arc(Vec3::Z, normal))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grid_cell_has_darker_lines_on_two_edges() {
        let pixels = grid_cell_pixels(Rgb([200, 100, 50]));
        assert_eq!(pixels.len(), TEXTURE_SIZE * TEXTURE_SIZE);
        let line = [124, 62, 31, 255];
        assert_eq!(pixels[0], line);
        assert_eq!(pixels[TEXTURE_SIZE * 10], line, "left edge");
        assert_eq!(pixels[10], line, "top edge");
        assert_eq!(pixels[TEXTURE_SIZE * 10 + 10], [200, 100, 50, 255]);
    }

    #[test]
    fn the_plane_faces_along_the_normal() {
        let halfspace = Halfspace::new(Vec3::new(0.0, 1.0, 0.0)).expect("a halfspace");
        let pose = ground_pose(&halfspace, &Pose::from_position(Vec3::new(0.0, 2.0, 0.0)));
        assert!((pose.rotation * Vec3::Z - Vec3::Y).length() < 1e-6);
        assert_eq!(pose.position, Vec3::new(0.0, 2.0, 0.0));
    }
}
