//! Frames: the compiler settings that read angles and orientations, the orientation forms of
//! MJCF (`quat`, `euler`, `axisangle`, `xyaxes`, `zaxis`), and the turn from MuJoCo's Z-up to
//! rebond's Y-up.

use glam::{DQuat, DVec3};
use roxmltree::Node;

use super::super::SceneError;
use super::parse::{attribute_error, Defaults};

/// The rotation `C` that turns the whole model from Z-up to Y-up: −90° about X, so a point
/// `(x, y, z)` becomes `(x, z, −y)`.
pub(in crate::scene) fn z_up_to_y_up() -> DQuat {
    DQuat::from_rotation_x(-std::f64::consts::FRAC_PI_2)
}

/// A pose: position and rotation of a frame in its parent's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(in crate::scene) struct Frame {
    pub(in crate::scene) position: DVec3,
    pub(in crate::scene) rotation: DQuat,
}

impl Frame {
    pub(in crate::scene) const IDENTITY: Self = Self {
        position: DVec3::ZERO,
        rotation: DQuat::IDENTITY,
    };

    /// This frame followed by `local` (a frame given in this one).
    pub(in crate::scene) fn then(&self, local: &Frame) -> Frame {
        Frame {
            position: self.position + self.rotation * local.position,
            rotation: (self.rotation * local.rotation).normalize(),
        }
    }

    /// A point given in this frame, in the parent's.
    pub(super) fn point(&self, point: DVec3) -> DVec3 {
        self.position + self.rotation * point
    }
}

/// Whether the body's inertia comes from its geoms (`compiler inertiafromgeom`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum InertiaFromGeom {
    /// From the geoms where the body has no `inertial` (MuJoCo's default).
    Auto,
    /// Always from the geoms: `inertial` is ignored.
    Always,
    /// Never: only `inertial`.
    Never,
}

/// The `compiler` settings rebond reads.
#[derive(Debug, Clone)]
pub(super) struct Compiler {
    /// Angles in degrees (`angle="degree"`, MuJoCo's default) rather than radians.
    pub(super) degrees: bool,
    /// `eulerseq`: each axis, lower case turning with the frame (intrinsic), upper case fixed
    /// in the parent (extrinsic).
    pub(super) euler_sequence: [u8; 3],
    pub(super) inertia_from_geom: InertiaFromGeom,
    /// `settotalmass`: the bodies' masses and inertias are scaled to this total, kg.
    pub(super) total_mass: Option<f64>,
    /// `meshdir`, relative to the model's folder.
    pub(super) mesh_dir: Option<String>,
}

impl Compiler {
    /// The settings of `<compiler>` (MuJoCo's defaults where it gives none or is absent).
    pub(super) fn read(node: Option<Node>, defaults: &Defaults) -> Result<Self, SceneError> {
        let mut compiler = Self {
            degrees: true,
            euler_sequence: *b"xyz",
            inertia_from_geom: InertiaFromGeom::Auto,
            total_mass: None,
            mesh_dir: None,
        };
        let Some(node) = node else {
            return Ok(compiler);
        };
        let text = |name: &str| node.attribute(name);
        if let Some(angle) = text("angle") {
            compiler.degrees = match angle {
                "degree" => true,
                "radian" => false,
                other => {
                    let message = format!("expected \"degree\" or \"radian\", got \"{other}\"");
                    return Err(attribute_error(node, "angle", message));
                }
            };
        }
        if let Some(coordinate) = text("coordinate") {
            if coordinate != "local" {
                let message = format!(
                    "only local coordinates are read, got \"{coordinate}\" (MuJoCo 2.3.3 \
                     removed global ones)"
                );
                return Err(attribute_error(node, "coordinate", message));
            }
        }
        if let Some(sequence) = text("eulerseq") {
            let bytes = sequence.as_bytes();
            if bytes.len() != 3 || !bytes.iter().all(|byte| b"xyzXYZ".contains(byte)) {
                let message = format!("expected 3 of x, y, z, X, Y, Z, got \"{sequence}\"");
                return Err(attribute_error(node, "eulerseq", message));
            }
            compiler.euler_sequence = [bytes[0], bytes[1], bytes[2]];
        }
        if let Some(mode) = text("inertiafromgeom") {
            compiler.inertia_from_geom = match mode {
                "auto" => InertiaFromGeom::Auto,
                "true" => InertiaFromGeom::Always,
                "false" => InertiaFromGeom::Never,
                other => {
                    let message =
                        format!("expected \"true\", \"false\" or \"auto\", got \"{other}\"");
                    return Err(attribute_error(node, "inertiafromgeom", message));
                }
            };
        }
        if text("settotalmass").is_some() {
            let mass = defaults.number(node, "settotalmass", -1.0)?;
            // MuJoCo's rule: a value that is not positive leaves the masses as they are.
            compiler.total_mass = (mass > 0.0).then_some(mass);
        }
        compiler.mesh_dir = text("meshdir").map(str::to_owned);
        Ok(compiler)
    }

    /// An angle of the file in radians.
    pub(super) fn angle(&self, value: f64) -> f64 {
        if self.degrees {
            value.to_radians()
        } else {
            value
        }
    }
}

/// The frame of `node` in its parent's: `pos` and one of the orientation forms.
pub(super) fn frame(
    node: Node,
    defaults: &Defaults,
    compiler: &Compiler,
) -> Result<Frame, SceneError> {
    let position = defaults
        .triple(node, "pos")?
        .map_or(DVec3::ZERO, DVec3::from_array);
    Ok(Frame {
        position,
        rotation: orientation(node, defaults, compiler)?,
    })
}

/// The orientation of `node`: at most one of `quat` (w x y z), `axisangle`, `euler`, `xyaxes`,
/// `zaxis`; identity without any.
pub(super) fn orientation(
    node: Node,
    defaults: &Defaults,
    compiler: &Compiler,
) -> Result<DQuat, SceneError> {
    let forms = ["quat", "axisangle", "euler", "xyaxes", "zaxis"];
    let given: Vec<_> = forms
        .iter()
        .filter(|form| node.attribute(**form).is_some())
        .collect();
    if given.len() > 1 {
        let message = format!("`{}` and `{}` both orient it: give one", given[0], given[1]);
        return Err(attribute_error(node, given[1], message));
    }
    let Some(&&form) = given.first() else {
        return Ok(DQuat::IDENTITY);
    };
    let zero = || attribute_error(node, form, "has zero length");
    let rotation = match form {
        "quat" => {
            let q = defaults.numbers(node, form, Some(4))?.unwrap_or_default();
            let quat = DQuat::from_xyzw(q[1], q[2], q[3], q[0]);
            if quat.length() == 0.0 {
                return Err(zero());
            }
            quat.normalize()
        }
        "axisangle" => {
            let v = defaults.numbers(node, form, Some(4))?.unwrap_or_default();
            let axis = DVec3::new(v[0], v[1], v[2])
                .try_normalize()
                .ok_or_else(zero)?;
            DQuat::from_axis_angle(axis, compiler.angle(v[3]))
        }
        "euler" => {
            let angles = defaults.triple(node, form)?.unwrap_or_default();
            let mut rotation = DQuat::IDENTITY;
            for (axis, angle) in compiler.euler_sequence.iter().zip(angles) {
                let unit = match axis.to_ascii_lowercase() {
                    b'x' => DVec3::X,
                    b'y' => DVec3::Y,
                    _ => DVec3::Z,
                };
                let turn = DQuat::from_axis_angle(unit, compiler.angle(angle));
                rotation = if axis.is_ascii_lowercase() {
                    rotation * turn
                } else {
                    turn * rotation
                };
            }
            rotation.normalize()
        }
        "xyaxes" => {
            let v = defaults.numbers(node, form, Some(6))?.unwrap_or_default();
            let x = DVec3::new(v[0], v[1], v[2])
                .try_normalize()
                .ok_or_else(zero)?;
            let y = DVec3::new(v[3], v[4], v[5]);
            let y = (y - x * x.dot(y)).try_normalize().ok_or_else(zero)?;
            let z = x.cross(y);
            DQuat::from_mat3(&glam::DMat3::from_cols(x, y, z)).normalize()
        }
        _ => {
            let z = defaults.triple(node, form)?.unwrap_or_default();
            let z = DVec3::from_array(z).try_normalize().ok_or_else(zero)?;
            DQuat::from_rotation_arc(DVec3::Z, z)
        }
    };
    Ok(rotation)
}
