//! Triangles approximating a shape, for drawing: the viewer (`rebond view`) and the Python
//! module's pictures (`World.render`) both draw these.
//!
//! [`tessellate`] gives a shape's triangles in its body frame, with a unit normal at every
//! vertex for lighting. Round shapes (sphere, capsule, cylinder) are lathed about the Y axis from
//! a profile, [`SEGMENTS_AROUND`] segments around and [`SEGMENTS_POLE_TO_POLE`] from pole to
//! pole, so a sphere's triangles lie inside it by at most `r (1 - cos(π / 16))` (1.9 % of the
//! radius); boxes and hulls are flat-shaded, one set of vertices per face, and so are triangle
//! meshes and heightfields, one set a triangle, each drawn from both sides. Compounds gather
//! their children's triangles at the children's poses. A halfspace, unbounded, has none: a
//! drawing shows it as a ground plane.

use std::f32::consts::{FRAC_PI_2, TAU};

use super::{Capsule, ConvexHull, Cuboid, Cylinder, Shape, Sphere, Triangle};
use crate::math::{Pose, Vec3};

/// Segments around the Y axis of lathed shapes.
pub const SEGMENTS_AROUND: usize = 32;
/// Segments from pole to pole of a sphere (a capsule's caps take half each).
pub const SEGMENTS_POLE_TO_POLE: usize = 16;

/// Triangles with a normal at every vertex; triangles wind counter-clockwise seen from outside.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Tessellation {
    /// Vertex positions, metres.
    pub positions: Vec<Vec3>,
    /// Unit vertex normals, one per position.
    pub normals: Vec<Vec3>,
    /// Three indices into `positions` per triangle.
    pub indices: Vec<u32>,
}

impl Tessellation {
    /// Appends `other` moved by `pose`.
    fn append(&mut self, other: &Tessellation, pose: &Pose) {
        let base = self.positions.len() as u32;
        self.positions.extend(
            other
                .positions
                .iter()
                .map(|&position| pose.transform_point(position)),
        );
        self.normals.extend(
            other
                .normals
                .iter()
                .map(|&normal| pose.transform_vector(normal)),
        );
        self.indices
            .extend(other.indices.iter().map(|&index| base + index));
    }

    /// Adds a vertex and returns its index.
    fn vertex(&mut self, position: Vec3, normal: Vec3) -> u32 {
        self.positions.push(position);
        self.normals.push(normal);
        self.positions.len() as u32 - 1
    }
}

/// The triangles of `shape` in its body frame (metres), or `None` for a halfspace.
pub fn tessellate(shape: &Shape) -> Option<Tessellation> {
    Some(match shape {
        Shape::Sphere(sphere) => sphere_mesh(sphere),
        Shape::Cuboid(cuboid) => cuboid_mesh(cuboid),
        Shape::Capsule(capsule) => capsule_mesh(capsule),
        Shape::Cylinder(cylinder) => cylinder_mesh(cylinder),
        Shape::ConvexHull(hull) => hull_mesh(hull),
        Shape::Compound(compound) => {
            let mut mesh = Tessellation::default();
            for child in compound.children() {
                if let Some(child_mesh) = tessellate(&child.shape) {
                    mesh.append(&child_mesh, &child.pose);
                }
            }
            mesh
        }
        Shape::Halfspace(_) => return None,
        Shape::TriMesh(trimesh) => flat_triangles(
            (0..trimesh.indices().len() as u32).filter_map(|index| trimesh.triangle(index)),
        ),
        Shape::HeightField(heightfield) => flat_triangles(
            (0..heightfield.triangle_count()).filter_map(|index| heightfield.triangle(index)),
        ),
    })
}

/// Flat-shaded triangles, each drawn from both sides (a mesh collides on both; a heightfield is
/// seen from above).
fn flat_triangles(triangles: impl Iterator<Item = Triangle>) -> Tessellation {
    let mut mesh = Tessellation::default();
    for triangle in triangles {
        let Some(normal) = triangle.normal() else {
            continue;
        };
        let [a, b, c] = triangle.vertices;
        for (corners, facing) in [([a, b, c], normal), ([a, c, b], -normal)] {
            let first = mesh.vertex(corners[0], facing);
            mesh.vertex(corners[1], facing);
            mesh.vertex(corners[2], facing);
            mesh.indices.extend([first, first + 1, first + 2]);
        }
    }
    mesh
}

/// One point of a lathe profile: distance from the Y axis, height, and the outward normal in
/// the (radial, Y) plane.
#[derive(Debug, Clone, Copy)]
struct ProfilePoint {
    radius: f32,
    height: f32,
    normal_radial: f32,
    normal_y: f32,
}

/// Turns a profile, listed from bottom to top, about the Y axis.
fn lathe(profile: &[ProfilePoint]) -> Tessellation {
    let mut mesh = Tessellation::default();
    for point in profile {
        for segment in 0..=SEGMENTS_AROUND {
            let angle = TAU * segment as f32 / SEGMENTS_AROUND as f32;
            let (sin, cos) = angle.sin_cos();
            mesh.vertex(
                Vec3::new(point.radius * cos, point.height, -point.radius * sin),
                Vec3::new(
                    point.normal_radial * cos,
                    point.normal_y,
                    -point.normal_radial * sin,
                ),
            );
        }
    }
    let ring = SEGMENTS_AROUND as u32 + 1;
    for level in 0..profile.len().saturating_sub(1) as u32 {
        for segment in 0..SEGMENTS_AROUND as u32 {
            let lower = level * ring + segment;
            let upper = lower + ring;
            mesh.indices
                .extend([lower, lower + 1, upper + 1, lower, upper + 1, upper]);
        }
    }
    mesh
}

/// Points of a circular arc of `radius` centred at height `center`, from `from` to `to` radians
/// above the horizon, in `segments` steps.
fn arc(radius: f32, center: f32, from: f32, to: f32, segments: usize) -> Vec<ProfilePoint> {
    (0..=segments)
        .map(|step| {
            let angle = from + (to - from) * step as f32 / segments as f32;
            let (sin, cos) = angle.sin_cos();
            ProfilePoint {
                radius: radius * cos,
                height: center + radius * sin,
                normal_radial: cos,
                normal_y: sin,
            }
        })
        .collect()
}

fn sphere_mesh(sphere: &Sphere) -> Tessellation {
    lathe(&arc(
        sphere.radius(),
        0.0,
        -FRAC_PI_2,
        FRAC_PI_2,
        SEGMENTS_POLE_TO_POLE,
    ))
}

fn capsule_mesh(capsule: &Capsule) -> Tessellation {
    let half_segments = SEGMENTS_POLE_TO_POLE / 2;
    let (radius, half_height) = (capsule.radius(), capsule.half_height());
    let mut profile = arc(radius, -half_height, -FRAC_PI_2, 0.0, half_segments);
    profile.extend(arc(radius, half_height, 0.0, FRAC_PI_2, half_segments));
    lathe(&profile)
}

fn cylinder_mesh(cylinder: &Cylinder) -> Tessellation {
    let (radius, half_height) = (cylinder.radius(), cylinder.half_height());
    let point = |radius, height, normal_radial, normal_y| ProfilePoint {
        radius,
        height,
        normal_radial,
        normal_y,
    };
    lathe(&[
        point(0.0, -half_height, 0.0, -1.0),
        point(radius, -half_height, 0.0, -1.0),
        point(radius, -half_height, 1.0, 0.0),
        point(radius, half_height, 1.0, 0.0),
        point(radius, half_height, 0.0, 1.0),
        point(0.0, half_height, 0.0, 1.0),
    ])
}

fn cuboid_mesh(cuboid: &Cuboid) -> Tessellation {
    let half = cuboid.half_extents();
    let mut mesh = Tessellation::default();
    for axis in 0..3 {
        for sign in [-1.0_f32, 1.0] {
            let normal = Vec3::AXES[axis] * sign;
            let tangent = Vec3::AXES[(axis + 1) % 3];
            let bitangent = normal.cross(tangent);
            let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .map(|(u, v)| mesh.vertex(half * (normal + u * tangent + v * bitangent), normal));
            push_fan(&mut mesh, &corners);
        }
    }
    mesh
}

fn hull_mesh(hull: &ConvexHull) -> Tessellation {
    let vertices = hull.vertices();
    let mut mesh = Tessellation::default();
    for face in hull.faces() {
        let corners: Vec<u32> = face
            .vertices
            .iter()
            .filter_map(|&index| vertices.get(index as usize))
            .map(|&position| mesh.vertex(position, face.normal))
            .collect();
        push_fan(&mut mesh, &corners);
    }
    mesh
}

/// Triangulates a convex polygon, counter-clockwise seen from outside, as a fan.
fn push_fan(mesh: &mut Tessellation, corners: &[u32]) {
    for pair in corners.windows(2).skip(1) {
        mesh.indices.extend([corners[0], pair[0], pair[1]]);
    }
}

#[cfg(test)]
mod tests {
    use crate::math::Quat;
    use crate::shape::CompoundChild;

    use super::*;

    /// The largest gap between a lathed sphere and its mesh, as a fraction of the radius.
    fn lathe_sag() -> f32 {
        1.0 - (std::f32::consts::PI / SEGMENTS_POLE_TO_POLE as f32).cos()
    }

    fn every_shape() -> Vec<Shape> {
        let hull = Shape::convex_hull(&[
            Vec3::new(-1.0, 0.0, -1.0),
            Vec3::new(1.0, 0.0, -1.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(-1.0, 0.0, 1.0),
            Vec3::new(0.0, 1.5, 0.0),
        ])
        .expect("a pyramid");
        let compound = Shape::compound(vec![
            CompoundChild::new(
                Shape::sphere(0.4).expect("a sphere"),
                Pose::from_position(Vec3::new(-1.0, 0.0, 0.0)),
            ),
            CompoundChild::new(
                Shape::cylinder(0.1, 1.0).expect("a cylinder"),
                Pose::new(Vec3::ZERO, Quat::from_rotation_z(FRAC_PI_2)),
            ),
        ])
        .expect("a compound");
        vec![
            Shape::sphere(0.7).expect("a sphere"),
            Shape::cuboid(Vec3::new(0.5, 1.0, 1.5)).expect("a box"),
            Shape::capsule(0.3, 0.8).expect("a capsule"),
            Shape::cylinder(0.6, 0.4).expect("a cylinder"),
            hull,
            compound,
        ]
    }

    #[test]
    fn meshes_are_well_formed_and_lie_on_their_shapes() {
        for shape in every_shape() {
            let mesh = tessellate(&shape).expect("a bounded shape has a mesh");
            assert!(!mesh.indices.is_empty(), "{shape:?}");
            assert_eq!(mesh.indices.len() % 3, 0);
            assert_eq!(mesh.positions.len(), mesh.normals.len());
            assert!(mesh
                .indices
                .iter()
                .all(|&index| (index as usize) < mesh.positions.len()));
            assert!(mesh
                .normals
                .iter()
                .all(|normal| (normal.length() - 1.0).abs() < 1e-4));
            let bounds = shape.aabb(&Pose::IDENTITY);
            let slack = Vec3::splat(1e-4);
            assert!(mesh.positions.iter().all(|&position| {
                position.cmpge(bounds.min - slack).all() && position.cmple(bounds.max + slack).all()
            }));
            let reach = |direction: Vec3| {
                mesh.positions
                    .iter()
                    .map(|position| position.dot(direction))
                    .fold(f32::MIN, f32::max)
            };
            for direction in [Vec3::X, Vec3::Y, Vec3::Z, -Vec3::X, -Vec3::Y, -Vec3::Z] {
                let support = shape.support(direction).expect("bounded").dot(direction);
                assert!(
                    reach(direction) >= support * (1.0 - lathe_sag()) - 1e-4,
                    "{shape:?} along {direction}"
                );
            }
        }
    }

    #[test]
    fn triangles_face_outward() {
        for shape in every_shape() {
            let mesh = tessellate(&shape).expect("a mesh");
            for triangle in mesh.indices.chunks_exact(3) {
                let [a, b, c] = [0, 1, 2].map(|corner| mesh.positions[triangle[corner] as usize]);
                let face_normal = (b - a).cross(c - a);
                if face_normal.length() < 1e-7 {
                    continue;
                }
                let vertex_normals: Vec3 = triangle
                    .iter()
                    .map(|&index| mesh.normals[index as usize])
                    .sum();
                assert!(face_normal.dot(vertex_normals) > 0.0, "{shape:?}");
            }
        }
    }

    #[test]
    fn meshes_and_heightfields_are_drawn_from_both_sides() {
        let trimesh = Shape::trimesh(
            vec![Vec3::ZERO, Vec3::X, Vec3::Z, Vec3::new(1.0, 0.5, 1.0)],
            &[[0, 2, 1], [1, 2, 3]],
        )
        .expect("a mesh");
        let heightfield = Shape::heightfield(
            &[vec![0.0, 0.5, 0.0], vec![0.25, 1.0, 0.0]],
            Vec3::new(2.0, 1.0, 3.0),
        )
        .expect("a heightfield");
        // 2 triangles of the mesh; 2 × 1 cells of 2 triangles each in the heightfield.
        for (shape, triangles) in [(trimesh, 2), (heightfield, 4)] {
            let mesh = tessellate(&shape).expect("a mesh");
            assert_eq!(mesh.indices.len(), 3 * 2 * triangles, "{shape:?}");
            let bounds = shape.aabb(&Pose::IDENTITY);
            for pair in mesh.indices.chunks_exact(6) {
                let front = &pair[..3];
                let back = &pair[3..];
                let corner = |index: u32| mesh.positions[index as usize];
                assert_eq!(corner(front[0]), corner(back[0]));
                assert_eq!(corner(front[1]), corner(back[2]));
                assert_eq!(corner(front[2]), corner(back[1]));
                assert_eq!(
                    mesh.normals[front[0] as usize],
                    -mesh.normals[back[0] as usize]
                );
            }
            let slack = Vec3::splat(1e-4);
            assert!(mesh.positions.iter().all(|&position| {
                position.cmpge(bounds.min - slack).all() && position.cmple(bounds.max + slack).all()
            }));
        }
    }

    #[test]
    fn halfspaces_have_no_mesh() {
        assert_eq!(
            tessellate(&Shape::halfspace(Vec3::Y).expect("a halfspace")),
            None
        );
    }
}
