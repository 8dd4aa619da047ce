//! The serde model of a scene file, as written: every field optional where the format allows it,
//! numbers as `f64` (narrowed to `f32` in `convert.rs`, so a value beyond `f32` is refused rather
//! than read as infinity), unknown fields refused.
//!
//! Shapes are read as one flat object whose `type` says which of the other fields it takes; this
//! keeps `deny_unknown_fields` and the error paths of `serde_path_to_error` working inside shapes,
//! which serde's internally tagged enums would lose. Every object of the format is read through
//! [`JsonObject`], since serde's derived structs would also accept a JSON array, by position.

use std::fmt;
use std::marker::PhantomData;
use std::ops::Deref;

use serde::de::value::MapAccessDeserializer;
use serde::de::{Deserializer, MapAccess, Visitor};
use serde::Deserialize;

use crate::body::BodyType;
use crate::joint::{GenericAxis, JointType};
use crate::material::CombineRule;

/// A value that must be written as a JSON object. Derived structs alone would also take a JSON
/// array of their fields in order, which the format does not allow.
#[derive(Debug)]
pub(super) struct JsonObject<T>(pub(super) T);

impl<T> Deref for JsonObject<T> {
    type Target = T;

    fn deref(&self) -> &T {
        &self.0
    }
}

impl<'de, T: Deserialize<'de>> Deserialize<'de> for JsonObject<T> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_map(ObjectVisitor(PhantomData))
    }
}

/// Accepts a JSON object only, and hands its entries to `T`'s own deserialiser.
struct ObjectVisitor<T>(PhantomData<T>);

impl<'de, T: Deserialize<'de>> Visitor<'de> for ObjectVisitor<T> {
    type Value = JsonObject<T>;

    fn expecting(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        formatter.write_str("a JSON object")
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Self::Value, A::Error> {
        T::deserialize(MapAccessDeserializer::new(map)).map(JsonObject)
    }
}

/// The top level of a scene file, as written: the timestep, every world setting under its
/// `WorldSettings` name, the bodies and the joints.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SceneFile {
    pub(super) gravity: Option<[f64; 3]>,
    pub(super) timestep: Option<f64>,
    pub(super) substeps: Option<u32>,
    pub(super) max_linear_speed: Option<f64>,
    pub(super) contact_hertz: Option<f64>,
    pub(super) contact_damping_ratio: Option<f64>,
    pub(super) contact_push_speed: Option<f64>,
    pub(super) restitution_threshold: Option<f64>,
    pub(super) speculative_distance: Option<f64>,
    pub(super) sleep_speed: Option<f64>,
    pub(super) sleep_time: Option<f64>,
    pub(super) joint_hertz: Option<f64>,
    pub(super) joint_damping_ratio: Option<f64>,
    pub(super) friction_combine: Option<CombineEntry>,
    pub(super) restitution_combine: Option<CombineEntry>,
    pub(super) bodies: Vec<JsonObject<BodyEntry>>,
    pub(super) joints: Option<Vec<JsonObject<JointEntry>>>,
    /// Extension of the contract: couplings of joint coordinates, `L = Σ cᵢ qᵢ` (MuJoCo's fixed
    /// tendons, URDF's mimic).
    pub(super) couplings: Option<Vec<JsonObject<CouplingEntry>>>,
    /// Extension of the contract: the body a player drives as a character, and how.
    pub(super) character: Option<JsonObject<CharacterEntry>>,
    /// Extension of the contract: MuJoCo's actuators, one control value each, on joints.
    pub(super) actuators: Option<Vec<JsonObject<ActuatorEntry>>>,
}

/// The kinds of actuator, as written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum ActuatorKindEntry {
    Motor,
    Position,
    Velocity,
}

/// One actuator, as written: `kp` belongs to position actuators, `kv` to position and velocity
/// ones (checked in `convert.rs`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ActuatorEntry {
    pub(super) name: Option<String>,
    pub(super) joint: String,
    #[serde(rename = "type")]
    pub(super) kind: ActuatorKindEntry,
    pub(super) gear: Option<f64>,
    pub(super) ctrl_range: Option<[f64; 2]>,
    pub(super) kp: Option<f64>,
    pub(super) kv: Option<f64>,
}

/// Explicit mass properties, as written: body frame, inertia about the centre of mass as
/// `[ixx, iyy, izz, ixy, ixz, iyz]`; the centre of mass defaults to the body origin.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MassPropertiesEntry {
    pub(super) mass: f64,
    pub(super) center_of_mass: Option<[f64; 3]>,
    pub(super) inertia: [f64; 6],
}

/// One coupling, as written (extension of the contract): the joints by name with their
/// coefficients; every other field optional.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CouplingEntry {
    pub(super) name: Option<String>,
    pub(super) joints: Vec<JsonObject<CoupledJointEntry>>,
    pub(super) limits: Option<[f64; 2]>,
    pub(super) stiffness: Option<f64>,
    pub(super) damping: Option<f64>,
    pub(super) length: Option<f64>,
}

/// One joint of a coupling, as written: its name and coefficient.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CoupledJointEntry {
    pub(super) joint: String,
    pub(super) coefficient: f64,
}

/// The scene's character, as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CharacterEntry {
    pub(super) body: String,
    pub(super) walk_speed: Option<f64>,
    pub(super) jump_speed: Option<f64>,
    pub(super) max_slope_angle: Option<f64>,
    pub(super) max_step_height: Option<f64>,
}

/// How two surfaces' values combine, as written: one of [`CombineRule`]'s variants in snake case,
/// a JSON string (read as a string first, so that another JSON type is an error at the field
/// rather than serde_json's "expected value" at a line and column).
#[derive(Debug, Clone, Copy)]
pub(super) struct CombineEntry(pub(super) CombineRule);

impl<'de> Deserialize<'de> for CombineEntry {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        const NAMES: &[&str] = &["geometric_mean", "average", "min", "max", "multiply"];
        let name = String::deserialize(deserializer)?;
        let rule = match name.as_str() {
            "geometric_mean" => CombineRule::GeometricMean,
            "average" => CombineRule::Average,
            "min" => CombineRule::Min,
            "max" => CombineRule::Max,
            "multiply" => CombineRule::Multiply,
            _ => return Err(serde::de::Error::unknown_variant(&name, NAMES)),
        };
        Ok(Self(rule))
    }
}

/// How a body moves, as written.
#[derive(Debug, Clone, Copy, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum BodyKind {
    #[default]
    Dynamic,
    Static,
    Kinematic,
}

impl From<BodyKind> for BodyType {
    fn from(kind: BodyKind) -> Self {
        match kind {
            BodyKind::Dynamic => BodyType::Dynamic,
            BodyKind::Static => BodyType::Static,
            BodyKind::Kinematic => BodyType::Kinematic,
        }
    }
}

/// One body, as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BodyEntry {
    pub(super) name: Option<String>,
    #[serde(rename = "type", default)]
    pub(super) kind: BodyKind,
    pub(super) shape: JsonObject<ShapeEntry>,
    pub(super) position: Option<[f64; 3]>,
    pub(super) rotation: Option<[f64; 4]>,
    pub(super) linear_velocity: Option<[f64; 3]>,
    pub(super) angular_velocity: Option<[f64; 3]>,
    pub(super) density: Option<f64>,
    pub(super) mass: Option<f64>,
    /// Extension of the contract: explicit mass, centre of mass and inertia.
    pub(super) mass_properties: Option<JsonObject<MassPropertiesEntry>>,
    pub(super) friction: Option<f64>,
    pub(super) restitution: Option<f64>,
    /// Extension of the contract: the body's rolling resistance coefficient.
    pub(super) rolling_resistance: Option<f64>,
    pub(super) force: Option<[f64; 3]>,
    pub(super) force_point: Option<[f64; 3]>,
    pub(super) torque: Option<[f64; 3]>,
    pub(super) linear_damping: Option<f64>,
    pub(super) angular_damping: Option<f64>,
    pub(super) can_sleep: Option<bool>,
    pub(super) locked_axes: Option<JsonObject<LockedAxesEntry>>,
    /// Extension of the contract: a sensor reports overlaps and pushes nothing.
    pub(super) sensor: Option<bool>,
    /// Extension of the contract: the body's collision groups.
    pub(super) collision_groups: Option<JsonObject<GroupsEntry>>,
    /// Keyframes a kinematic body follows.
    pub(super) path: Option<JsonObject<PathEntry>>,
    /// Extension of the contract: the direction, body frame, bodies pass through it from.
    pub(super) one_way: Option<[f64; 3]>,
    /// Extension of the contract: the velocity of its surface, m/s, body frame (a conveyor).
    pub(super) surface_velocity: Option<[f64; 3]>,
}

/// A kinematic body's keyframes, as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PathEntry {
    pub(super) points: Vec<JsonObject<PathPointEntry>>,
    #[serde(rename = "loop")]
    pub(super) looping: Option<bool>,
}

/// One keyframe, as written. Extension of the contract: a point without `position` or
/// `rotation` takes the body's.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PathPointEntry {
    pub(super) time: f64,
    pub(super) position: Option<[f64; 3]>,
    pub(super) rotation: Option<[f64; 4]>,
}

/// Locked axes, as written: world axes `[x, y, z]`, each list all `false` when left out.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct LockedAxesEntry {
    pub(super) translation: Option<[bool; 3]>,
    pub(super) rotation: Option<[bool; 3]>,
}

/// Collision groups, as written: two 32-bit masks, each all ones when left out.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct GroupsEntry {
    pub(super) memberships: Option<u32>,
    pub(super) filter: Option<u32>,
}

/// The shape types of the format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub(super) enum ShapeKind {
    Sphere,
    Box,
    Capsule,
    Cylinder,
    ConvexHull,
    Compound,
    Halfspace,
    Trimesh,
    Heightfield,
}

impl ShapeKind {
    /// The name used in the file.
    pub(super) fn name(self) -> &'static str {
        match self {
            Self::Sphere => "sphere",
            Self::Box => "box",
            Self::Capsule => "capsule",
            Self::Cylinder => "cylinder",
            Self::ConvexHull => "convex_hull",
            Self::Compound => "compound",
            Self::Halfspace => "halfspace",
            Self::Trimesh => "trimesh",
            Self::Heightfield => "heightfield",
        }
    }

    /// The fields this shape type takes besides `type` (which of them are required is checked
    /// when the shape is built).
    pub(super) fn fields(self) -> &'static [&'static str] {
        match self {
            Self::Sphere => &["radius"],
            Self::Box => &["half_extents"],
            Self::Capsule | Self::Cylinder => &["radius", "half_height"],
            Self::ConvexHull => &["points"],
            Self::Compound => &["children"],
            Self::Halfspace => &["normal"],
            Self::Trimesh => &[
                "vertices",
                "indices",
                "file",
                "scale",
                "materials",
                "triangle_materials",
            ],
            Self::Heightfield => &["heights", "scale"],
        }
    }
}

/// A shape, as written: `type` and the fields of every type, checked against `type` later.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ShapeEntry {
    #[serde(rename = "type")]
    pub(super) kind: ShapeKind,
    pub(super) radius: Option<f64>,
    pub(super) half_extents: Option<[f64; 3]>,
    pub(super) half_height: Option<f64>,
    pub(super) points: Option<Vec<[f64; 3]>>,
    pub(super) children: Option<Vec<JsonObject<ChildEntry>>>,
    pub(super) normal: Option<[f64; 3]>,
    pub(super) vertices: Option<Vec<[f64; 3]>>,
    pub(super) indices: Option<Vec<[u32; 3]>>,
    pub(super) file: Option<String>,
    pub(super) scale: Option<[f64; 3]>,
    pub(super) heights: Option<Vec<Vec<f64>>>,
    /// Extension of the contract: a trimesh's table of surface materials.
    pub(super) materials: Option<Vec<JsonObject<MaterialEntry>>>,
    /// Extension of the contract: each triangle's index into `materials`.
    pub(super) triangle_materials: Option<Vec<u32>>,
}

/// One surface material of a trimesh, as written: each value left out is the body's.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MaterialEntry {
    pub(super) friction: Option<f64>,
    pub(super) restitution: Option<f64>,
    pub(super) rolling_resistance: Option<f64>,
}

impl ShapeEntry {
    /// The names of the type-specific fields present in the file.
    pub(super) fn present_fields(&self) -> impl Iterator<Item = &'static str> {
        [
            ("radius", self.radius.is_some()),
            ("half_extents", self.half_extents.is_some()),
            ("half_height", self.half_height.is_some()),
            ("points", self.points.is_some()),
            ("children", self.children.is_some()),
            ("normal", self.normal.is_some()),
            ("vertices", self.vertices.is_some()),
            ("indices", self.indices.is_some()),
            ("file", self.file.is_some()),
            ("scale", self.scale.is_some()),
            ("heights", self.heights.is_some()),
            ("materials", self.materials.is_some()),
            ("triangle_materials", self.triangle_materials.is_some()),
        ]
        .into_iter()
        .filter_map(|(field, present)| present.then_some(field))
    }
}

/// One child of a compound shape, as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ChildEntry {
    pub(super) shape: JsonObject<ShapeEntry>,
    pub(super) position: Option<[f64; 3]>,
    pub(super) rotation: Option<[f64; 4]>,
    pub(super) friction: Option<f64>,
    pub(super) restitution: Option<f64>,
    /// Extension of the contract: the child's rolling resistance coefficient.
    pub(super) rolling_resistance: Option<f64>,
    pub(super) name: Option<String>,
    pub(super) sensor: Option<bool>,
    pub(super) collision_groups: Option<JsonObject<GroupsEntry>>,
}

/// The joint types of the format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum JointKind {
    Fixed,
    Ball,
    Revolute,
    Prismatic,
    Distance,
    /// Extension of the contract: the generic joint.
    Generic,
}

impl From<JointKind> for JointType {
    fn from(kind: JointKind) -> Self {
        match kind {
            JointKind::Fixed => JointType::Fixed,
            JointKind::Ball => JointType::Ball,
            JointKind::Revolute => JointType::Revolute,
            JointKind::Prismatic => JointType::Prismatic,
            JointKind::Distance => JointType::Distance,
            JointKind::Generic => JointType::Generic,
        }
    }
}

/// One joint, as written. Which fields belong to which joint type is the engine's rule
/// (`JointDesc` refuses the others, naming the field).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct JointEntry {
    pub(super) name: Option<String>,
    #[serde(rename = "type")]
    pub(super) kind: JointKind,
    pub(super) body_a: Option<String>,
    pub(super) body_b: String,
    pub(super) anchor: Option<[f64; 3]>,
    pub(super) anchor_b: Option<[f64; 3]>,
    pub(super) axis: Option<[f64; 3]>,
    pub(super) limits: Option<[f64; 2]>,
    pub(super) swing_limit: Option<f64>,
    pub(super) twist_limits: Option<[f64; 2]>,
    pub(super) motor: Option<JsonObject<MotorEntry>>,
    pub(super) length: Option<f64>,
    pub(super) spring: Option<JsonObject<SpringEntry>>,
    /// Extension of the contract: the inertia added to a revolute or prismatic coordinate.
    pub(super) armature: Option<f64>,
    /// Extension of the contract: a generic joint's frame, `[x, y, z, w]`.
    pub(super) frame: Option<[f64; 4]>,
    /// Extension of the contract: a generic joint's axes.
    pub(super) axes: Option<JsonObject<AxesEntry<AxisEntry>>>,
    /// Extension of the contract: a generic joint's motors, by axis.
    pub(super) motors: Option<JsonObject<AxesEntry<JsonObject<MotorEntry>>>>,
    pub(super) friction: Option<f64>,
    pub(super) collide_connected: Option<bool>,
    pub(super) break_force: Option<f64>,
    pub(super) break_torque: Option<f64>,
}

/// A motor, as written: the fields of every kind, the kind told by which of `target_velocity`,
/// `target_position` and `torque` is present and the other kinds' fields refused later, as for
/// shapes.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MotorEntry {
    pub(super) target_velocity: Option<f64>,
    pub(super) target_position: Option<f64>,
    pub(super) stiffness: Option<f64>,
    pub(super) damping: Option<f64>,
    pub(super) max_force: Option<f64>,
    pub(super) torque: Option<f64>,
}

impl MotorEntry {
    /// The names of the fields present in the file.
    pub(super) fn present_fields(&self) -> impl Iterator<Item = &'static str> {
        [
            ("target_velocity", self.target_velocity.is_some()),
            ("target_position", self.target_position.is_some()),
            ("stiffness", self.stiffness.is_some()),
            ("damping", self.damping.is_some()),
            ("max_force", self.max_force.is_some()),
            ("torque", self.torque.is_some()),
        ]
        .into_iter()
        .filter_map(|(field, present)| present.then_some(field))
    }
}

/// A joint's spring, as written; `damping` and `reference` default to 0.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SpringEntry {
    pub(super) stiffness: f64,
    pub(super) damping: Option<f64>,
    /// Extension of the contract: the revolute or prismatic coordinate the spring rests at.
    pub(super) reference: Option<f64>,
}

/// One value per axis of a generic joint, as written: an unknown axis name is refused.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct AxesEntry<T> {
    pub(super) x: Option<T>,
    pub(super) y: Option<T>,
    pub(super) z: Option<T>,
    pub(super) rx: Option<T>,
    pub(super) ry: Option<T>,
    pub(super) rz: Option<T>,
}

impl<T> AxesEntry<T> {
    /// The values given, with their axes, in the order of [`GenericAxis::ALL`].
    pub(super) fn given(&self) -> impl Iterator<Item = (GenericAxis, &T)> {
        let values = [&self.x, &self.y, &self.z, &self.rx, &self.ry, &self.rz];
        GenericAxis::ALL
            .into_iter()
            .zip(values)
            .filter_map(|(axis, value)| value.as_ref().map(|value| (axis, value)))
    }
}

/// What a generic joint's axis does, as written: `"locked"`, `"free"` or `[min, max]`.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(super) enum AxisEntry {
    Mode(String),
    Limited([f64; 2]),
}

#[cfg(test)]
mod tests {
    //! The users' reference, `docs/scene-format.md`, names every field and type name the loader
    //! knows: each structure of the model tells its field names to a deserialiser that only
    //! records them, and each must stand in the reference in backticks, as `name` or as the JSON
    //! string `"name"`.

    use serde::de::value::Error;
    use serde::de::{Error as _, Visitor};
    use serde::{forward_to_deserialize_any, Deserialize, Deserializer};

    use super::SpringEntry;
    use super::{ActuatorEntry, ActuatorKindEntry, MassPropertiesEntry};
    use super::{AxesEntry, JointEntry, JointKind, MotorEntry, PathEntry, PathPointEntry};
    use super::{BodyEntry, BodyKind, ChildEntry, GroupsEntry, SceneFile, ShapeEntry, ShapeKind};
    use super::{CoupledJointEntry, CouplingEntry};

    const REFERENCE: &str = include_str!("../../../../docs/scene-format.md");

    /// A deserialiser that records the field names or variant names it is asked for, and fails.
    #[derive(Default)]
    struct NameRecorder(Vec<&'static str>);

    impl<'de> Deserializer<'de> for &mut NameRecorder {
        type Error = Error;

        fn deserialize_any<V: Visitor<'de>>(self, _visitor: V) -> Result<V::Value, Error> {
            Err(Error::custom("names recorded"))
        }

        fn deserialize_struct<V: Visitor<'de>>(
            self,
            _name: &'static str,
            fields: &'static [&'static str],
            _visitor: V,
        ) -> Result<V::Value, Error> {
            self.0.extend(fields);
            Err(Error::custom("names recorded"))
        }

        fn deserialize_enum<V: Visitor<'de>>(
            self,
            _name: &'static str,
            variants: &'static [&'static str],
            _visitor: V,
        ) -> Result<V::Value, Error> {
            self.0.extend(variants);
            Err(Error::custom("names recorded"))
        }

        forward_to_deserialize_any! {
            bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
            option unit unit_struct newtype_struct seq tuple tuple_struct map identifier
            ignored_any
        }
    }

    /// The names `T` asks its deserialiser for.
    fn names_of<'de, T: Deserialize<'de>>() -> Vec<&'static str> {
        let mut recorder = NameRecorder::default();
        assert!(T::deserialize(&mut recorder).is_err());
        recorder.0
    }

    #[test]
    fn the_reference_mentions_every_field_and_type_the_loader_knows() {
        let names = [
            names_of::<SceneFile>(),
            names_of::<BodyEntry>(),
            names_of::<GroupsEntry>(),
            names_of::<ShapeEntry>(),
            names_of::<ChildEntry>(),
            names_of::<ShapeKind>(),
            names_of::<BodyKind>(),
            names_of::<JointEntry>(),
            names_of::<JointKind>(),
            names_of::<MotorEntry>(),
            names_of::<SpringEntry>(),
            names_of::<AxesEntry<f64>>(),
            names_of::<PathEntry>(),
            names_of::<PathPointEntry>(),
            names_of::<ActuatorEntry>(),
            names_of::<ActuatorKindEntry>(),
            names_of::<MassPropertiesEntry>(),
            names_of::<CouplingEntry>(),
            names_of::<CoupledJointEntry>(),
        ]
        .concat();
        assert!(names.len() > 30, "recorded only {names:?}");
        let missing: Vec<_> = names
            .iter()
            .filter(|name| {
                !REFERENCE.contains(&format!("`{name}`"))
                    && !REFERENCE.contains(&format!("`\"{name}\"`"))
            })
            .collect();
        assert!(
            missing.is_empty(),
            "docs/scene-format.md does not mention {missing:?} (in backticks)"
        );
    }
}
