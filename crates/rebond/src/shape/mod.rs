//! Collision shapes in their local frame: size, mass properties, bounding box and support function.
//!
//! Every convex shape has a support function `support(d)`: the point of the shape farthest along
//! `d`, which the narrow phase's GJK and EPA are built on. [`tessellation`] gives each shape's
//! triangles for drawing.

mod bvh;
mod capsule;
mod compound;
mod convex_hull;
mod cuboid;
mod cylinder;
mod halfspace;
mod heightfield;
pub(crate) mod line;
mod sphere;
pub mod tessellation;
mod triangle;
mod trimesh;

pub use capsule::Capsule;
pub use compound::{Compound, CompoundChild};
pub use convex_hull::{ConvexHull, HullEdge, HullFace};
pub(crate) use convex_hull::{EdgeLanes, FaceLanes};
pub use cuboid::Cuboid;
pub use cylinder::Cylinder;
pub use halfspace::{Halfspace, HALFSPACE_EXTENT};
pub use heightfield::{HeightField, MIN_SOLID_DEPTH};
pub use sphere::Sphere;
pub use triangle::{Triangle, ACTIVE_EDGE_ANGLE};
pub use trimesh::{TriMesh, TriangleMaterial};

use std::sync::Arc;

use crate::error::Result;
use crate::mass::MassProperties;
use crate::math::{Aabb, Pose, Vec3};

/// A collision shape. Built only through validated constructors, so every size is finite and
/// positive.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Shape {
    /// A ball around the origin.
    Sphere(Sphere),
    /// A box centred on the origin.
    Cuboid(Cuboid),
    /// A segment along local Y swept by a sphere.
    Capsule(Capsule),
    /// A circular cylinder along local Y.
    Cylinder(Cylinder),
    /// The convex hull of a point cloud, shared between clones.
    ConvexHull(
        #[cfg_attr(feature = "serde", serde(with = "crate::state::shared"))] Arc<ConvexHull>,
    ),
    /// Several convex shapes with poses in the body frame, shared between clones.
    Compound(#[cfg_attr(feature = "serde", serde(with = "crate::state::shared"))] Arc<Compound>),
    /// Everything below a plane through the origin (static and kinematic bodies only).
    Halfspace(Halfspace),
    /// A triangle mesh, colliding on both sides of each triangle (static and kinematic bodies
    /// only).
    TriMesh(TriMesh),
    /// A grid of heights, solid below its surface (static and kinematic bodies only).
    HeightField(HeightField),
}

impl Shape {
    /// A sphere of `radius` metres.
    pub fn sphere(radius: f32) -> Result<Shape> {
        Sphere::new(radius).map(Shape::Sphere)
    }

    /// A box of the given half extents, metres.
    pub fn cuboid(half_extents: Vec3) -> Result<Shape> {
        Cuboid::new(half_extents).map(Shape::Cuboid)
    }

    /// A capsule along local Y: `half_height` is half the distance between its sphere centres.
    pub fn capsule(radius: f32, half_height: f32) -> Result<Shape> {
        Capsule::new(radius, half_height).map(Shape::Capsule)
    }

    /// A cylinder along local Y of total height `2 · half_height`.
    pub fn cylinder(radius: f32, half_height: f32) -> Result<Shape> {
        Cylinder::new(radius, half_height).map(Shape::Cylinder)
    }

    /// The convex hull of `points` (body frame).
    pub fn convex_hull(points: &[Vec3]) -> Result<Shape> {
        ConvexHull::new(points).map(|hull| Shape::ConvexHull(Arc::new(hull)))
    }

    /// A compound of convex children placed in the body frame.
    pub fn compound(children: Vec<CompoundChild>) -> Result<Shape> {
        Compound::new(children).map(|compound| Shape::Compound(Arc::new(compound)))
    }

    /// The solid below the plane through the origin with outward `normal` (normalised here).
    pub fn halfspace(normal: Vec3) -> Result<Shape> {
        Halfspace::new(normal).map(Shape::Halfspace)
    }

    /// A triangle mesh of `vertices` (metres) and counter-clockwise `indices`; see
    /// [`TriMesh::new`].
    pub fn trimesh(vertices: Vec<Vec3>, indices: &[[u32; 3]]) -> Result<Shape> {
        TriMesh::new(vertices, indices).map(Shape::TriMesh)
    }

    /// A heightfield of `heights` rows scaled by `scale`; see [`HeightField::new`].
    pub fn heightfield(heights: &[Vec<f32>], scale: Vec3) -> Result<Shape> {
        HeightField::new(heights, scale).map(Shape::HeightField)
    }

    /// Checks a decoded shape: it is the one its constructor builds from its own defining
    /// values (a compound's children each so), or an error saying what differs.
    #[cfg(feature = "serde")]
    pub(crate) fn check_decoded(&self) -> std::result::Result<(), String> {
        let rebuilt = match self {
            Shape::Sphere(sphere) => Shape::sphere(sphere.radius()),
            Shape::Cuboid(cuboid) => Shape::cuboid(cuboid.half_extents()),
            Shape::Capsule(capsule) => Shape::capsule(capsule.radius(), capsule.half_height()),
            Shape::Cylinder(cylinder) => Shape::cylinder(cylinder.radius(), cylinder.half_height()),
            Shape::ConvexHull(hull) => return hull.check_decoded(),
            Shape::TriMesh(mesh) => mesh.rebuilt().map(Shape::TriMesh),
            Shape::HeightField(heightfield) => return heightfield.check_decoded(),
            // Both normalise rotations or normals, which may move a last bit: checked, not
            // compared.
            Shape::Halfspace(halfspace) => {
                let normal = halfspace.normal();
                return match Shape::halfspace(normal) {
                    Ok(_) if (normal.length() - 1.0).abs() <= 1e-5 => Ok(()),
                    _ => Err("a halfspace's normal is not a unit vector".to_owned()),
                };
            }
            Shape::Compound(compound) => {
                Compound::new(compound.children().to_vec()).map_err(|error| error.to_string())?;
                return compound
                    .children()
                    .iter()
                    .try_for_each(|child| child.shape.check_decoded());
            }
        };
        match rebuilt {
            Ok(shape) if shape == *self => Ok(()),
            Ok(_) => Err("a shape differs from the one its own values build".to_owned()),
            Err(error) => Err(error.to_string()),
        }
    }

    /// Whether the shape is a triangle mesh or a heightfield: made of triangles, collided
    /// triangle by triangle.
    pub fn is_triangulated(&self) -> bool {
        matches!(self, Shape::TriMesh(_) | Shape::HeightField(_))
    }

    /// Triangle `index` of a mesh or heightfield in its body frame, with its edge flags; `None`
    /// past the end or for any other shape.
    pub fn triangle(&self, index: u32) -> Option<Triangle> {
        match self {
            Shape::TriMesh(mesh) => mesh.triangle(index),
            Shape::HeightField(heightfield) => heightfield.triangle(index),
            _ => None,
        }
    }

    /// The index into its mesh's [`TriMesh::materials`] of triangle `index`'s surface; `None`
    /// for a mesh without materials, a heightfield or any other shape.
    pub(crate) fn material_index(&self, index: u32) -> Option<u32> {
        match self {
            Shape::TriMesh(mesh) => mesh.material_index(index),
            _ => None,
        }
    }

    /// Calls `visit(k)` for the triangles `k` of a mesh or heightfield near `bounds` (body frame;
    /// see [`TriMesh::triangles_in`] and [`HeightField::triangles_in`]); nothing for any other
    /// shape.
    pub fn triangles_in(&self, bounds: &Aabb, visit: impl FnMut(u32)) {
        match self {
            Shape::TriMesh(mesh) => mesh.triangles_in(bounds, visit),
            Shape::HeightField(heightfield) => heightfield.triangles_in(bounds, visit),
            _ => {}
        }
    }

    /// Whether every surface of the shape is flat (boxes, hulls, halfspaces, and compounds of
    /// them): its contact points are corners, edges and faces that turn with it. On a curved
    /// surface the point in contact changes as the body rolls.
    pub(crate) fn is_polyhedral(&self) -> bool {
        match self {
            Shape::Cuboid(_)
            | Shape::ConvexHull(_)
            | Shape::Halfspace(_)
            | Shape::TriMesh(_)
            | Shape::HeightField(_) => true,
            Shape::Sphere(_) | Shape::Capsule(_) | Shape::Cylinder(_) => false,
            Shape::Compound(compound) => compound
                .children()
                .iter()
                .all(|child| child.shape.is_polyhedral()),
        }
    }

    /// Whether the shape has a finite volume (everything but a halfspace).
    pub fn is_bounded(&self) -> bool {
        !matches!(self, Shape::Halfspace(_))
    }

    /// Mass properties for a uniform `density` (kg/m³), or `None` for a halfspace, a triangle
    /// mesh or a heightfield.
    pub fn mass_properties(&self, density: f32) -> Option<MassProperties> {
        match self {
            Shape::Sphere(sphere) => Some(sphere.mass_properties(density)),
            Shape::Cuboid(cuboid) => Some(cuboid.mass_properties(density)),
            Shape::Capsule(capsule) => Some(capsule.mass_properties(density)),
            Shape::Cylinder(cylinder) => Some(cylinder.mass_properties(density)),
            Shape::ConvexHull(hull) => Some(hull.mass_properties(density)),
            Shape::Compound(compound) => Some(compound.mass_properties(density)),
            Shape::Halfspace(_) | Shape::TriMesh(_) | Shape::HeightField(_) => None,
        }
    }

    /// The field that sets the shape's size, as [`Shape`]'s constructors and scene files name
    /// it: where an error about a size the engine cannot handle points.
    pub(crate) fn size_field(&self) -> &'static str {
        match self {
            Shape::Sphere(_) | Shape::Capsule(_) => "radius",
            Shape::Cuboid(_) => "half_extents",
            Shape::Cylinder(cylinder) if cylinder.half_height() < cylinder.radius() => {
                "half_height"
            }
            Shape::Cylinder(_) => "radius",
            Shape::ConvexHull(_) => "points",
            Shape::Compound(_) => "children",
            Shape::Halfspace(_) => "normal",
            Shape::TriMesh(_) => "vertices",
            Shape::HeightField(_) => "heights",
        }
    }

    /// Volume in m³; infinite for a halfspace.
    pub fn volume(&self) -> f32 {
        self.mass_properties(1.0)
            .map_or(f32::INFINITY, |properties| properties.mass)
    }

    /// The world bounding box of the shape placed at `pose`.
    pub fn aabb(&self, pose: &Pose) -> Aabb {
        match self {
            Shape::Sphere(sphere) => sphere.aabb(pose),
            Shape::Cuboid(cuboid) => cuboid.aabb(pose),
            Shape::Capsule(capsule) => capsule.aabb(pose),
            Shape::Cylinder(cylinder) => cylinder.aabb(pose),
            Shape::ConvexHull(hull) => hull.aabb(pose),
            Shape::Compound(compound) => compound.aabb(pose),
            Shape::Halfspace(halfspace) => halfspace.aabb(pose),
            Shape::TriMesh(mesh) => mesh.aabb(pose),
            Shape::HeightField(heightfield) => heightfield.aabb(pose),
        }
    }

    /// Radius of a ball about the shape's origin that holds the whole shape, metres (the
    /// smallest such ball for every shape but a compound, a mesh and a heightfield, which give
    /// the ball around their body-frame box's corners); infinite for a halfspace.
    pub fn bounding_radius(&self) -> f32 {
        match self {
            Shape::Sphere(sphere) => sphere.radius(),
            Shape::Cuboid(cuboid) => cuboid.half_extents().length(),
            Shape::Capsule(capsule) => capsule.half_height() + capsule.radius(),
            Shape::Cylinder(cylinder) => cylinder.radius().hypot(cylinder.half_height()),
            Shape::ConvexHull(hull) => hull.bounding_radius(),
            Shape::Compound(compound) => compound
                .children()
                .iter()
                .map(|child| child.pose.position.length() + child.shape.bounding_radius())
                .fold(0.0, f32::max),
            Shape::Halfspace(_) => f32::INFINITY,
            Shape::TriMesh(mesh) => corner_reach(&mesh.local_bounds()),
            Shape::HeightField(heightfield) => corner_reach(&heightfield.local_bounds()),
        }
    }

    /// The radius the shape rolls on, metres, the lever of its rolling resistance: a sphere's,
    /// capsule's or cylinder's radius; zero for flat-faced shapes, meshes and heightfields, which
    /// rest on faces rather than roll (friction and the spread of their contact points hold them),
    /// and for a compound, whose children each have their own.
    pub fn rolling_radius(&self) -> f32 {
        match self {
            Shape::Sphere(sphere) => sphere.radius(),
            Shape::Capsule(capsule) => capsule.radius(),
            Shape::Cylinder(cylinder) => cylinder.radius(),
            Shape::Cuboid(_)
            | Shape::ConvexHull(_)
            | Shape::Halfspace(_)
            | Shape::TriMesh(_)
            | Shape::HeightField(_)
            | Shape::Compound(_) => 0.0,
        }
    }

    /// Rounding radius around the shape's core, metres: a sphere's or capsule's radius, a
    /// cylinder's convex radius ([`Cylinder::convex_radius`]), zero for every other shape.
    pub fn core_radius(&self) -> f32 {
        match self {
            Shape::Sphere(sphere) => sphere.radius(),
            Shape::Capsule(capsule) => capsule.radius(),
            Shape::Cylinder(cylinder) => cylinder.convex_radius(),
            _ => 0.0,
        }
    }

    /// Support point of the shape's core (the shape shrunk by [`Shape::core_radius`]): a
    /// sphere's centre, an end of a capsule's segment, a point of a cylinder's core cylinder, or
    /// the shape's own support point. A halfspace, mesh or heightfield has no core and gives the
    /// origin.
    pub fn core_support(&self, direction: Vec3) -> Vec3 {
        match self {
            Shape::Sphere(_) => Vec3::ZERO,
            Shape::Cylinder(cylinder) => cylinder.core_support(direction),
            Shape::Capsule(capsule) => {
                let [bottom, top] = capsule.segment();
                if direction.y >= 0.0 {
                    top
                } else {
                    bottom
                }
            }
            _ => self.support(direction).unwrap_or(Vec3::ZERO),
        }
    }

    /// The local point of the shape farthest along local `direction`; `None` for a halfspace, which
    /// is unbounded, and for a mesh or heightfield, which are not convex. For a compound this is
    /// the support of the hull of its children.
    pub fn support(&self, direction: Vec3) -> Option<Vec3> {
        match self {
            Shape::Sphere(sphere) => Some(sphere.support(direction)),
            Shape::Cuboid(cuboid) => Some(cuboid.support(direction)),
            Shape::Capsule(capsule) => Some(capsule.support(direction)),
            Shape::Cylinder(cylinder) => Some(cylinder.support(direction)),
            Shape::ConvexHull(hull) => Some(hull.support(direction)),
            Shape::Compound(compound) => Some(compound.support(direction)),
            Shape::Halfspace(_) | Shape::TriMesh(_) | Shape::HeightField(_) => None,
        }
    }
}

/// Distance from the origin to the farthest corner of `bounds`, metres.
fn corner_reach(bounds: &Aabb) -> f32 {
    bounds.min.abs().max(bounds.max.abs()).length()
}
