//! Geoms: each becomes a compound child (or, for a plane, a static halfspace body), and, with
//! `inertial`, gives the body's mass properties, computed with the engine's own shapes.

use std::path::Path;

use glam::{DQuat, DVec3};
use roxmltree::Node;
use serde_json::{json, Value};

use super::super::meshes::MeshFiles;
use super::super::{LoadError, SceneError};
use super::frames::{frame, orientation, Frame};
use super::parse::{attribute_error, element_error};
use super::Importer;
use crate::mass::MassProperties;
use crate::math::{Mat3, Pose, Vec3};
use crate::shape::Shape;

/// MuJoCo's default density, kg/m³.
const DEFAULT_DENSITY: f64 = 1000.0;

/// MuJoCo's default sliding friction.
const DEFAULT_FRICTION: f64 = 1.0;

/// A geom read: its compound child and mass properties.
pub(super) struct Geom {
    /// The compound child entry, body frame (a plane's is a halfspace, for a static body).
    pub(super) child: Value,
    /// The frame of the child's shape in the body's.
    pub(super) frame: Frame,
    /// Whether it is a plane.
    pub(super) plane: bool,
    /// Mass properties in the body frame, `None` for a plane and a static body's mesh.
    pub(super) mass: Option<MassProperties>,
}

/// The collision groups of MuJoCo's `contype` and `conaffinity`. MuJoCo lets two geoms collide
/// when `(contype₁ & conaffinity₂) ≠ 0 or (contype₂ & conaffinity₁) ≠ 0`; rebond when
/// `(memberships₁ & filter₂) ≠ 0 and (memberships₂ & filter₁) ≠ 0`. With the memberships
/// `contype | conaffinity << 16` and the filter `conaffinity | contype << 16`, both of rebond's
/// terms are MuJoCo's condition, so the rule is MuJoCo's exactly for bits 0 to 15 (bits above are
/// refused).
pub(super) fn collision_groups(contype: u32, conaffinity: u32) -> Value {
    json!({
        "memberships": contype | conaffinity << 16,
        "filter": conaffinity | contype << 16,
    })
}

/// The body-frame pose of a shape whose axis rebond puts along Y where MuJoCo puts it along Z:
/// the geom's frame turned +90° about X.
fn y_axis_to_z(frame: &Frame) -> Frame {
    Frame {
        position: frame.position,
        rotation: (frame.rotation * DQuat::from_rotation_x(std::f64::consts::FRAC_PI_2))
            .normalize(),
    }
}

fn pose32(frame: &Frame) -> Pose {
    Pose::new(frame.position.as_vec3(), frame.rotation.as_quat())
}

fn quat_json(rotation: DQuat) -> Value {
    json!([rotation.x, rotation.y, rotation.z, rotation.w])
}

impl Importer {
    /// Reads the geom `node`; `fixed` for a geom of a static body, whose mesh is a `trimesh`
    /// rather than a convex hull.
    pub(super) fn geom(&self, node: Node, fixed: bool) -> Result<Geom, LoadError> {
        let defaults = &self.defaults;
        let kind = defaults.get(node, "type").unwrap_or("sphere");
        let size = defaults.numbers(node, "size", None)?.unwrap_or_default();
        let size_at = |index: usize| -> Result<f64, SceneError> {
            match size.get(index) {
                Some(&value) if value > 0.0 => Ok(value),
                Some(&value) => Err(attribute_error(
                    node,
                    "size",
                    format!("must be positive, got {value}"),
                )),
                None => Err(attribute_error(
                    node,
                    "size",
                    format!("a {kind} geom needs at least {} sizes", index + 1),
                )),
            }
        };
        let mut frame = frame(node, defaults, &self.compiler)?;
        let fromto = defaults.numbers(node, "fromto", Some(6))?;
        let mut half_length = None;
        if let Some(ends) = &fromto {
            if !matches!(kind, "capsule" | "cylinder") {
                let message =
                    format!("rebond reads `fromto` on capsules and cylinders, not a {kind}");
                return Err(attribute_error(node, "fromto", message).into());
            }
            let from = DVec3::new(ends[0], ends[1], ends[2]);
            let to = DVec3::new(ends[3], ends[4], ends[5]);
            let direction = (to - from).try_normalize().ok_or_else(|| {
                attribute_error(node, "fromto", "the two ends are the same point")
            })?;
            frame = Frame {
                position: (from + to) / 2.0,
                rotation: DQuat::from_rotation_arc(DVec3::Z, direction),
            };
            half_length = Some((to - from).length() / 2.0);
        }
        let density = defaults.number(node, "density", DEFAULT_DENSITY)?;
        if density < 0.0 {
            let message = format!("must not be negative, got {density}");
            return Err(attribute_error(node, "density", message).into());
        }
        let given_mass = match defaults.numbers(node, "mass", Some(1))? {
            Some(mass) if mass[0] < 0.0 => {
                let message = format!("must not be negative, got {}", mass[0]);
                return Err(attribute_error(node, "mass", message).into());
            }
            Some(mass) => Some(mass[0]),
            None => None,
        };
        let (shape_json, shape, shape_frame): (Value, Shape, Frame) = match kind {
            "plane" => {
                let shape = json!({ "type": "halfspace", "normal": [0, 0, 1] });
                return Ok(Geom {
                    child: self.child(node, shape, &frame)?,
                    frame,
                    plane: true,
                    mass: None,
                });
            }
            "sphere" => {
                let radius = size_at(0)?;
                let shape = Shape::sphere(radius as f32);
                (
                    json!({"type": "sphere", "radius": radius}),
                    shape.map_err(|e| engine(node, e))?,
                    frame,
                )
            }
            "capsule" | "cylinder" => {
                let radius = size_at(0)?;
                let half = match half_length {
                    Some(half) => half,
                    None => size_at(1)?,
                };
                let shape = if kind == "capsule" {
                    Shape::capsule(radius as f32, half as f32)
                } else {
                    Shape::cylinder(radius as f32, half as f32)
                };
                (
                    json!({"type": kind, "radius": radius, "half_height": half}),
                    shape.map_err(|e| engine(node, e))?,
                    y_axis_to_z(&frame),
                )
            }
            "box" => {
                let half = [size_at(0)?, size_at(1)?, size_at(2)?];
                let shape = Shape::cuboid(DVec3::from_array(half).as_vec3());
                (
                    json!({"type": "box", "half_extents": half}),
                    shape.map_err(|e| engine(node, e))?,
                    frame,
                )
            }
            "ellipsoid" => {
                let radii = DVec3::new(size_at(0)?, size_at(1)?, size_at(2)?);
                let points = ellipsoid_points(radii);
                let shape =
                    Shape::convex_hull(&points.iter().map(|p| p.as_vec3()).collect::<Vec<_>>());
                let points: Vec<_> = points.iter().map(|p| p.to_array()).collect();
                (
                    json!({"type": "convex_hull", "points": points}),
                    shape.map_err(|e| engine(node, e))?,
                    frame,
                )
            }
            "mesh" if fixed => {
                let asset = self.mesh_asset(node)?;
                let vertices: Vec<[f64; 3]> = asset
                    .vertices
                    .iter()
                    .map(|vertex| (vertex.as_dvec3() * asset.scale).to_array())
                    .collect();
                let shape =
                    json!({"type": "trimesh", "vertices": vertices, "indices": asset.indices});
                return Ok(Geom {
                    child: self.child(node, shape, &frame)?,
                    frame,
                    plane: false,
                    mass: None,
                });
            }
            "mesh" => {
                let (points, shape) = self.mesh_points(node)?;
                (
                    json!({"type": "convex_hull", "points": points}),
                    shape,
                    frame,
                )
            }
            other => {
                let message = format!(
                    "rebond reads geoms of type sphere, capsule, cylinder, box, plane, ellipsoid \
                     and mesh, not \"{other}\""
                );
                return Err(attribute_error(node, "type", message).into());
            }
        };
        let mut properties = if kind == "ellipsoid" {
            // The hull of points on it is slightly smaller than the solid: MuJoCo's mass is the
            // ellipsoid's own, 4/3 π abc ρ with I = m (b² + c²) / 5 and so on.
            let radii = DVec3::from_array([size_at(0)?, size_at(1)?, size_at(2)?]);
            ellipsoid_mass(radii, density)
        } else {
            shape
                .mass_properties(density as f32)
                .ok_or_else(|| element_error(node, "this geom has no volume to take a mass from"))?
        };
        if let Some(mass) = given_mass {
            properties = if properties.mass > 0.0 {
                properties.scaled_to_mass(mass as f32)
            } else {
                MassProperties {
                    mass: mass as f32,
                    ..properties
                }
            };
        }
        let properties = properties.transformed(&pose32(&shape_frame));
        Ok(Geom {
            child: self.child(node, shape_json, &shape_frame)?,
            frame: shape_frame,
            plane: false,
            mass: Some(properties),
        })
    }

    /// The compound child of the geom `node`: `shape` at `frame` (body frame), with the geom's
    /// friction, collision groups and name.
    fn child(&self, node: Node, shape: Value, frame: &Frame) -> Result<Value, SceneError> {
        let friction = match self.defaults.numbers(node, "friction", None)? {
            Some(values) if values.is_empty() || values.len() > 3 => {
                let message = format!("expected 1 to 3 numbers, got {}", values.len());
                return Err(attribute_error(node, "friction", message));
            }
            Some(values) if values[0] < 0.0 => {
                let message = format!("must not be negative, got {}", values[0]);
                return Err(attribute_error(node, "friction", message));
            }
            Some(values) => values[0],
            None => DEFAULT_FRICTION,
        };
        let contype = self.bits(node, "contype")?;
        let conaffinity = self.bits(node, "conaffinity")?;
        let mut child = json!({
            "shape": shape,
            "position": frame.position.to_array(),
            "rotation": quat_json(frame.rotation),
            "friction": friction,
            "collision_groups": collision_groups(contype, conaffinity),
        });
        if let Some(name) = node.attribute("name") {
            child["name"] = json!(name);
        }
        Ok(child)
    }
    /// `contype` or `conaffinity`: MuJoCo's default 1, bits 0 to 15 only (see
    /// [`collision_groups`]).
    fn bits(&self, node: Node, name: &str) -> Result<u32, SceneError> {
        let value = self.defaults.number(node, name, 1.0)?;
        if (0.0..65536.0).contains(&value) && value.fract() == 0.0 {
            Ok(value as u32)
        } else {
            let message = format!("rebond reads the bits 0 to 15 (0 to 65535), got {value}");
            Err(attribute_error(node, name, message))
        }
    }

    /// The mesh asset a mesh geom names.
    fn mesh_asset(&self, node: Node) -> Result<&MeshAsset, SceneError> {
        let name = self
            .defaults
            .get(node, "mesh")
            .ok_or_else(|| attribute_error(node, "mesh", "required for a mesh geom"))?;
        self.meshes.get(name).ok_or_else(|| {
            attribute_error(node, "mesh", format!("no mesh asset is named \"{name}\""))
        })
    }

    /// The points of a mesh geom's file, scaled, and their convex hull.
    fn mesh_points(&self, node: Node) -> Result<(Vec<[f64; 3]>, Shape), LoadError> {
        let asset = self.mesh_asset(node)?;
        let points: Vec<[f64; 3]> = asset
            .vertices
            .iter()
            .map(|vertex| (vertex.as_dvec3() * asset.scale).to_array())
            .collect();
        let points32: Vec<Vec3> = points
            .iter()
            .map(|p| DVec3::from_array(*p).as_vec3())
            .collect();
        let shape = Shape::convex_hull(&points32).map_err(|error| engine(node, error))?;
        Ok((points, shape))
    }

    /// An `inertial` element's mass properties, body frame.
    pub(super) fn inertial(&self, node: Node) -> Result<MassProperties, SceneError> {
        let defaults = &self.defaults;
        let frame = Frame {
            position: defaults
                .triple(node, "pos")?
                .map(DVec3::from_array)
                .ok_or_else(|| attribute_error(node, "pos", "required for an inertial"))?,
            rotation: orientation(node, defaults, &self.compiler)?,
        };
        let mass = defaults.number(node, "mass", -1.0)?;
        if node.attribute("mass").is_none() {
            return Err(attribute_error(node, "mass", "required for an inertial"));
        }
        if mass <= 0.0 {
            let message = format!("must be positive, got {mass}");
            return Err(attribute_error(node, "mass", message));
        }
        let inertia = match (
            defaults.triple(node, "diaginertia")?,
            defaults.numbers(node, "fullinertia", Some(6))?,
        ) {
            (Some(d), None) => Mat3::from_diagonal(DVec3::from_array(d).as_vec3()),
            (None, Some(f)) => {
                let f: Vec<f32> = f.iter().map(|value| *value as f32).collect();
                // MuJoCo's order: ixx iyy izz ixy ixz iyz.
                Mat3::from_cols(
                    Vec3::new(f[0], f[3], f[4]),
                    Vec3::new(f[3], f[1], f[5]),
                    Vec3::new(f[4], f[5], f[2]),
                )
            }
            (Some(_), Some(_)) => {
                let message = "`diaginertia` and `fullinertia` both given: give one";
                return Err(attribute_error(node, "fullinertia", message));
            }
            (None, None) => {
                let message = "required: `diaginertia` or `fullinertia`";
                return Err(attribute_error(node, "diaginertia", message));
            }
        };
        let diagonal = Vec3::new(inertia.x_axis.x, inertia.y_axis.y, inertia.z_axis.z);
        if diagonal.min_element() <= 0.0 {
            let field = if node.attribute("diaginertia").is_some() {
                "diaginertia"
            } else {
                "fullinertia"
            };
            return Err(attribute_error(node, field, "the moments must be positive"));
        }
        Ok(MassProperties {
            mass: mass as f32,
            center_of_mass: Vec3::ZERO,
            inertia,
        }
        .transformed(&pose32(&frame)))
    }
}

/// A mesh asset: its vertices and triangles as read, and its scale.
pub(super) struct MeshAsset {
    pub(super) vertices: Vec<Vec3>,
    pub(super) indices: Vec<[u32; 3]>,
    pub(super) scale: DVec3,
}

/// Reads the mesh file at `path` (STL, binary or ASCII, or Wavefront OBJ); errors are
/// [`LoadError::Mesh`] at `place`.
pub(in crate::scene) fn read_mesh(
    path: &Path,
    place: &str,
) -> Result<(Vec<Vec3>, Vec<[u32; 3]>), LoadError> {
    let failure = |message: String| LoadError::Mesh {
        place: place.to_owned(),
        path: path.to_owned(),
        message,
    };
    let extension = path
        .extension()
        .and_then(|extension| extension.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("obj") => {
            let folder = path.parent().unwrap_or(Path::new(""));
            let file = path
                .file_name()
                .and_then(|name| name.to_str())
                .unwrap_or_default();
            let files = MeshFiles { folder, given: &[] };
            files.read_obj(file, place)
        }
        Some("stl") => {
            let bytes = std::fs::read(path).map_err(|error| failure(error.to_string()))?;
            let vertices =
                stl_vertices(&bytes).ok_or_else(|| failure("not a valid STL file".to_owned()))?;
            // Each triangle has its own three corners, in order.
            let count = u32::try_from(vertices.len() / 3)
                .map_err(|_| failure("too many triangles".to_owned()))?;
            let indices = (0..count).map(|k| [3 * k, 3 * k + 1, 3 * k + 2]).collect();
            Ok((vertices, indices))
        }
        _ => Err(failure("rebond reads STL and OBJ mesh files".to_owned())),
    }
}

/// The vertices of an STL file: binary (an 80-byte header, a triangle count, 50 bytes a
/// triangle) or ASCII (`vertex x y z` lines).
fn stl_vertices(bytes: &[u8]) -> Option<Vec<Vec3>> {
    if bytes.len() >= 84 {
        let count = u32::from_le_bytes(bytes[80..84].try_into().ok()?) as usize;
        if count.checked_mul(50)?.checked_add(84) == Some(bytes.len()) {
            let float =
                |at: usize| f32::from_le_bytes(bytes[at..at + 4].try_into().unwrap_or_default());
            let mut vertices = Vec::with_capacity(count * 3);
            for triangle in 0..count {
                for corner in 0..3 {
                    let at = 84 + triangle * 50 + 12 + corner * 12;
                    vertices.push(Vec3::new(float(at), float(at + 4), float(at + 8)));
                }
            }
            return vertices.iter().all(|v| v.is_finite()).then_some(vertices);
        }
    }
    let text = std::str::from_utf8(bytes).ok()?;
    if !text.trim_start().starts_with("solid") {
        return None;
    }
    let mut vertices = Vec::new();
    for line in text.lines() {
        let mut words = line.split_ascii_whitespace();
        if words.next() == Some("vertex") {
            let numbers: Vec<f32> = words.map(str::parse).collect::<Result<_, _>>().ok()?;
            let [x, y, z] = numbers[..] else { return None };
            vertices.push(Vec3::new(x, y, z));
        }
    }
    (!vertices.is_empty() && vertices.iter().all(|v| v.is_finite())).then_some(vertices)
}

/// Points on an ellipsoid of `radii`: 8 rings of 16, and the two poles.
fn ellipsoid_points(radii: DVec3) -> Vec<DVec3> {
    let mut points = vec![
        DVec3::new(0.0, 0.0, radii.z),
        DVec3::new(0.0, 0.0, -radii.z),
    ];
    for ring in 1..9 {
        let polar = std::f64::consts::PI * f64::from(ring) / 9.0;
        for step in 0..16 {
            let azimuth = std::f64::consts::TAU * f64::from(step) / 16.0;
            let unit = DVec3::new(
                polar.sin() * azimuth.cos(),
                polar.sin() * azimuth.sin(),
                polar.cos(),
            );
            points.push(unit * radii);
        }
    }
    points
}

/// A solid ellipsoid's mass properties: `m = 4/3 π abc ρ`, `Ixx = m (b² + c²) / 5`.
fn ellipsoid_mass(radii: DVec3, density: f64) -> MassProperties {
    let mass = 4.0 / 3.0 * std::f64::consts::PI * radii.x * radii.y * radii.z * density;
    let squares = radii * radii;
    let moments = DVec3::new(
        squares.y + squares.z,
        squares.x + squares.z,
        squares.x + squares.y,
    ) * (mass / 5.0);
    MassProperties {
        mass: mass as f32,
        center_of_mass: Vec3::ZERO,
        inertia: Mat3::from_diagonal(moments.as_vec3()),
    }
}

/// An engine error about a geom's shape, at the geom.
fn engine(node: Node, error: crate::Error) -> SceneError {
    element_error(node, format!("invalid shape: {error}"))
}

/// The quaternion of a frame as JSON `[x, y, z, w]`, for the other modules.
pub(in crate::scene) fn rotation_json(rotation: DQuat) -> Value {
    quat_json(rotation)
}
