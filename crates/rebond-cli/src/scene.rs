//! Scene files: the serde model of the JSON format (see `shared/scene-format.md`) and its
//! conversion, with every value checked, into an engine [`World`] ready to step.
//!
//! Numbers are read as `f64` and narrowed to the engine's `f32` here, so that a value too large
//! for `f32` (such as `1e39`) is refused as not finite instead of silently becoming infinity.
//! Shapes are read as one flat object whose `type` says which of the other fields it takes; this
//! keeps `deny_unknown_fields` and the error paths of `serde_path_to_error` working inside shapes,
//! which serde's internally tagged enums would lose. Every object of the format is read through
//! [`JsonObject`], since serde's derived structs would also accept a JSON array, by position.

use std::collections::HashMap;
use std::fmt;
use std::marker::PhantomData;
use std::ops::Deref;

use rebond::{
    BodyDesc, BodyHandle, BodyType, CompoundChild, InteractionGroups, Pose, Quat, RigidBody, Shape,
    Vec3, World, WorldSettings,
};
use serde::de::value::MapAccessDeserializer;
use serde::de::{Deserializer, MapAccess, Visitor};
use serde::Deserialize;

/// Default seconds per step when a scene leaves `timestep` out.
pub const DEFAULT_TIMESTEP: f64 = 1.0 / 60.0;

/// An invalid scene: where in the file, and what is wrong.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError {
    /// Path of the bad value, such as `bodies[3].shape.radius`; empty for the file as a whole.
    pub place: String,
    /// What is wrong with it.
    pub message: String,
}

impl SceneError {
    /// An error about the value at `place`.
    fn new(place: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            place: place.into(),
            message: message.into(),
        }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.place.is_empty() {
            write!(formatter, "{}", self.message)
        } else {
            write!(formatter, "{}: {}", self.place, self.message)
        }
    }
}

impl From<rebond::Error> for SceneError {
    fn from(error: rebond::Error) -> Self {
        Self::new(error.field, error.kind.to_string())
    }
}

/// A value that must be written as a JSON object. Derived structs alone would also take a JSON
/// array of their fields in order, which the format does not allow.
#[derive(Debug)]
struct JsonObject<T>(T);

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

/// The top level of a scene file, as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    gravity: Option<[f64; 3]>,
    timestep: Option<f64>,
    substeps: Option<u32>,
    bodies: Vec<JsonObject<BodyEntry>>,
}

/// How a body moves, as written.
#[derive(Debug, Clone, Copy, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
enum BodyKind {
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
struct BodyEntry {
    name: Option<String>,
    #[serde(rename = "type", default)]
    kind: BodyKind,
    shape: JsonObject<ShapeEntry>,
    position: Option<[f64; 3]>,
    rotation: Option<[f64; 4]>,
    linear_velocity: Option<[f64; 3]>,
    angular_velocity: Option<[f64; 3]>,
    density: Option<f64>,
    mass: Option<f64>,
    friction: Option<f64>,
    restitution: Option<f64>,
    force: Option<[f64; 3]>,
    torque: Option<[f64; 3]>,
    linear_damping: Option<f64>,
    angular_damping: Option<f64>,
    can_sleep: Option<bool>,
    /// Extension of the contract: a sensor reports overlaps and pushes nothing.
    sensor: Option<bool>,
    /// Extension of the contract: the body's collision groups.
    collision_groups: Option<JsonObject<GroupsEntry>>,
}

/// Collision groups, as written: two 32-bit masks, each all ones when left out.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct GroupsEntry {
    memberships: Option<u32>,
    filter: Option<u32>,
}

/// The shape types of the format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
enum ShapeKind {
    Sphere,
    Box,
    Capsule,
    Cylinder,
    ConvexHull,
    Compound,
    Halfspace,
}

impl ShapeKind {
    /// The name used in the file.
    fn name(self) -> &'static str {
        match self {
            Self::Sphere => "sphere",
            Self::Box => "box",
            Self::Capsule => "capsule",
            Self::Cylinder => "cylinder",
            Self::ConvexHull => "convex_hull",
            Self::Compound => "compound",
            Self::Halfspace => "halfspace",
        }
    }

    /// The fields this shape type takes besides `type`; all of them are required.
    fn fields(self) -> &'static [&'static str] {
        match self {
            Self::Sphere => &["radius"],
            Self::Box => &["half_extents"],
            Self::Capsule | Self::Cylinder => &["radius", "half_height"],
            Self::ConvexHull => &["points"],
            Self::Compound => &["children"],
            Self::Halfspace => &["normal"],
        }
    }
}

/// A shape, as written: `type` and the fields of every type, checked against `type` later.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ShapeEntry {
    #[serde(rename = "type")]
    kind: ShapeKind,
    radius: Option<f64>,
    half_extents: Option<[f64; 3]>,
    half_height: Option<f64>,
    points: Option<Vec<[f64; 3]>>,
    children: Option<Vec<JsonObject<ChildEntry>>>,
    normal: Option<[f64; 3]>,
}

impl ShapeEntry {
    /// The names of the type-specific fields present in the file.
    fn present_fields(&self) -> impl Iterator<Item = &'static str> {
        [
            ("radius", self.radius.is_some()),
            ("half_extents", self.half_extents.is_some()),
            ("half_height", self.half_height.is_some()),
            ("points", self.points.is_some()),
            ("children", self.children.is_some()),
            ("normal", self.normal.is_some()),
        ]
        .into_iter()
        .filter_map(|(field, present)| present.then_some(field))
    }
}

/// One child of a compound shape, as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ChildEntry {
    shape: JsonObject<ShapeEntry>,
    position: Option<[f64; 3]>,
    rotation: Option<[f64; 4]>,
}

/// Seconds per step, as written and as the engine steps with it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timestep {
    /// The scene's value in double precision; record times are `step × seconds`.
    pub seconds: f64,
    /// The same value rounded to `f32`, passed to `World::step`.
    pub engine_seconds: f32,
}

/// A body of a loaded scene.
#[derive(Debug, Clone)]
struct SceneBody {
    /// Its unique name, used in records.
    name: String,
    /// Its handle in the scene's world.
    handle: BodyHandle,
}

/// A scene checked and loaded into a world, ready to step.
///
/// Bodies are never removed from the world, so the handle of every scene body stays valid.
#[derive(Debug, Clone)]
pub struct Scene {
    world: World,
    bodies: Vec<SceneBody>,
    timestep: Timestep,
}

impl Scene {
    /// Parses and checks a scene file and builds its world. Nothing is stepped.
    pub fn from_json(bytes: &[u8]) -> Result<Self, SceneError> {
        let file = parse(bytes)?;
        let timestep = timestep(file.timestep)?;
        let gravity = match file.gravity {
            Some(gravity) => vector("gravity", gravity)?,
            None => rebond::world::DEFAULT_GRAVITY,
        };
        let settings = WorldSettings {
            gravity,
            substeps: file.substeps.unwrap_or(rebond::world::DEFAULT_SUBSTEPS),
            ..WorldSettings::default()
        };
        let mut world = World::new(settings)?;
        let mut bodies = Vec::with_capacity(file.bodies.len());
        let mut indices_by_name: HashMap<String, usize> = HashMap::new();
        for (index, entry) in file.bodies.iter().enumerate() {
            let place = format!("bodies[{index}]");
            let name = entry.name.clone().unwrap_or_else(|| format!("body{index}"));
            if let Some(first) = indices_by_name.insert(name.clone(), index) {
                let message =
                    format!("duplicate name \"{name}\": bodies[{first}] and {place} both have it");
                return Err(SceneError::new(format!("{place}.name"), message));
            }
            let desc = body_desc(entry, &place)?;
            let handle = world
                .add_body(desc)
                .map_err(|error| SceneError::from(error.within(&place)))?;
            bodies.push(SceneBody { name, handle });
        }
        Ok(Self {
            world,
            bodies,
            timestep,
        })
    }

    /// The world holding every body of the scene.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// Seconds per step.
    pub fn timestep(&self) -> Timestep {
        self.timestep
    }

    /// Advances the world by one time step.
    pub fn step(&mut self) -> rebond::Result<()> {
        self.world.step(self.timestep.engine_seconds)
    }

    /// Every body with its name, in scene order.
    pub fn bodies(&self) -> impl Iterator<Item = (&str, &RigidBody)> {
        self.bodies.iter().map(|body| {
            let state = self
                .world
                .body(body.handle)
                .expect("scene bodies are never removed from their world");
            (body.name.as_str(), state)
        })
    }
}

/// Deserialises the file, turning serde errors into a place and a message.
fn parse(bytes: &[u8]) -> Result<SceneFile, SceneError> {
    let mut deserializer = serde_json::Deserializer::from_slice(bytes);
    let JsonObject(file) = serde_path_to_error::deserialize(&mut deserializer)
        .map_err(|error| serde_error(error.path().to_string(), error.inner()))?;
    deserializer
        .end()
        .map_err(|error| serde_error(String::new(), &error))?;
    Ok(file)
}

/// A place and message for a serde error found at `path` (`.` for the top level).
///
/// Syntax errors get the line and column; data errors get the path, and a missing field is
/// reported at the field's own path (`bodies[0].shape` rather than `bodies[0]`).
fn serde_error(path: String, error: &serde_json::Error) -> SceneError {
    let full_message = error.to_string();
    let position = format!(" at line {} column {}", error.line(), error.column());
    let message = full_message
        .strip_suffix(&position)
        .unwrap_or(&full_message);
    let location = format!("line {}, column {}", error.line(), error.column());
    if error.is_syntax() || error.is_eof() || error.is_io() {
        return SceneError::new(location, format!("invalid JSON: {message}"));
    }
    let parent = if path == "." { String::new() } else { path };
    if let Some(field) = missing_field(message) {
        return SceneError::new(
            join(&parent, field),
            format!("required field is missing ({location})"),
        );
    }
    let place = if parent.is_empty() {
        "top level".to_owned()
    } else {
        parent
    };
    SceneError::new(place, format!("{message} ({location})"))
}

/// The field named by serde's "missing field `name`" message.
fn missing_field(message: &str) -> Option<&str> {
    message
        .strip_prefix("missing field `")
        .and_then(|rest| rest.strip_suffix('`'))
}

/// `parent.field`, or `field` at the top level.
fn join(parent: &str, field: &str) -> String {
    if parent.is_empty() {
        field.to_owned()
    } else {
        format!("{parent}.{field}")
    }
}

/// Narrows a file number to `f32`, refusing one beyond the `f32` range.
fn scalar(place: &str, value: f64) -> Result<f32, SceneError> {
    let narrowed = value as f32;
    if narrowed.is_finite() {
        Ok(narrowed)
    } else {
        Err(SceneError::new(
            place,
            format!(
                "must be finite, got {}, which is beyond the 32-bit float range",
                number(value)
            ),
        ))
    }
}

/// Narrows a file vector to a [`Vec3`], naming the bad component.
fn vector(place: &str, value: [f64; 3]) -> Result<Vec3, SceneError> {
    let mut narrowed = [0.0; 3];
    for (index, component) in value.into_iter().enumerate() {
        narrowed[index] = scalar(&format!("{place}[{index}]"), component)?;
    }
    Ok(Vec3::from_array(narrowed))
}

/// Narrows a file quaternion `[x, y, z, w]` to a [`Quat`] (not normalised: the engine does it).
fn rotation(place: &str, value: [f64; 4]) -> Result<Quat, SceneError> {
    let mut narrowed = [0.0; 4];
    for (index, component) in value.into_iter().enumerate() {
        narrowed[index] = scalar(&format!("{place}[{index}]"), component)?;
    }
    Ok(Quat::from_array(narrowed))
}

/// The time step: finite and positive, also once rounded to `f32`.
fn timestep(value: Option<f64>) -> Result<Timestep, SceneError> {
    let seconds = value.unwrap_or(DEFAULT_TIMESTEP);
    let engine_seconds = scalar("timestep", seconds)?;
    if engine_seconds > 0.0 {
        Ok(Timestep {
            seconds,
            engine_seconds,
        })
    } else if seconds > 0.0 {
        Err(SceneError::new(
            "timestep",
            format!(
                "must be positive, got {}, which rounds to 0 as a 32-bit float",
                number(seconds)
            ),
        ))
    } else {
        Err(SceneError::new(
            "timestep",
            format!("must be positive, got {}", number(seconds)),
        ))
    }
}

/// A file number for a message: plain notation for ordinary magnitudes, scientific otherwise.
fn number(value: f64) -> String {
    if value == 0.0 || (1e-4..1e16).contains(&value.abs()) {
        value.to_string()
    } else {
        format!("{value:e}")
    }
}

/// The engine description of one body; errors are placed under `place` (`bodies[i]`).
fn body_desc(entry: &BodyEntry, place: &str) -> Result<BodyDesc, SceneError> {
    let field = |name: &str| format!("{place}.{name}");
    let shape = shape(&entry.shape, &field("shape"))?;
    let mut desc = BodyDesc::new(entry.kind.into(), shape);
    if let Some(value) = entry.position {
        desc.position = vector(&field("position"), value)?;
    }
    if let Some(value) = entry.rotation {
        desc.rotation = rotation(&field("rotation"), value)?;
    }
    if let Some(value) = entry.linear_velocity {
        desc.linear_velocity = vector(&field("linear_velocity"), value)?;
    }
    if let Some(value) = entry.angular_velocity {
        desc.angular_velocity = vector(&field("angular_velocity"), value)?;
    }
    if let Some(value) = entry.density {
        desc.density = scalar(&field("density"), value)?;
    }
    if let Some(value) = entry.mass {
        desc.mass = Some(scalar(&field("mass"), value)?);
    }
    if let Some(value) = entry.friction {
        desc.friction = scalar(&field("friction"), value)?;
    }
    if let Some(value) = entry.restitution {
        desc.restitution = scalar(&field("restitution"), value)?;
    }
    if let Some(value) = entry.force {
        desc.constant_force = vector(&field("force"), value)?;
    }
    if let Some(value) = entry.torque {
        desc.constant_torque = vector(&field("torque"), value)?;
    }
    if let Some(value) = entry.linear_damping {
        desc.linear_damping = scalar(&field("linear_damping"), value)?;
    }
    if let Some(value) = entry.angular_damping {
        desc.angular_damping = scalar(&field("angular_damping"), value)?;
    }
    if let Some(value) = entry.can_sleep {
        desc.can_sleep = value;
    }
    if let Some(value) = entry.sensor {
        desc.sensor = value;
    }
    if let Some(groups) = &entry.collision_groups {
        desc.collision_groups = InteractionGroups::new(
            groups.memberships.unwrap_or(u32::MAX),
            groups.filter.unwrap_or(u32::MAX),
        );
    }
    Ok(desc)
}

/// The engine shape of a shape entry; errors are placed under `place` (`bodies[i].shape`).
fn shape(entry: &ShapeEntry, place: &str) -> Result<Shape, SceneError> {
    let kind = entry.kind;
    if let Some(stray) = entry
        .present_fields()
        .find(|field| !kind.fields().contains(field))
    {
        let expected = kind
            .fields()
            .iter()
            .map(|field| format!("`{field}`"))
            .collect::<Vec<_>>()
            .join(", ");
        return Err(SceneError::new(
            join(place, stray),
            format!(
                "unknown field `{stray}` for a {} shape, expected `type`, {expected}",
                kind.name()
            ),
        ));
    }
    let required = |field: &'static str| {
        SceneError::new(
            join(place, field),
            format!(
                "required field is missing (a {} shape needs it)",
                kind.name()
            ),
        )
    };
    let field = |name: &str| join(place, name);
    let shape = match kind {
        ShapeKind::Sphere => {
            let radius = entry.radius.ok_or_else(|| required("radius"))?;
            Shape::sphere(scalar(&field("radius"), radius)?)
        }
        ShapeKind::Box => {
            let half_extents = entry.half_extents.ok_or_else(|| required("half_extents"))?;
            Shape::cuboid(vector(&field("half_extents"), half_extents)?)
        }
        ShapeKind::Capsule | ShapeKind::Cylinder => {
            let radius = entry.radius.ok_or_else(|| required("radius"))?;
            let half_height = entry.half_height.ok_or_else(|| required("half_height"))?;
            let radius = scalar(&field("radius"), radius)?;
            let half_height = scalar(&field("half_height"), half_height)?;
            if kind == ShapeKind::Capsule {
                Shape::capsule(radius, half_height)
            } else {
                Shape::cylinder(radius, half_height)
            }
        }
        ShapeKind::ConvexHull => {
            let points = entry.points.as_ref().ok_or_else(|| required("points"))?;
            let points = points
                .iter()
                .enumerate()
                .map(|(index, point)| vector(&format!("{place}.points[{index}]"), *point))
                .collect::<Result<Vec<_>, _>>()?;
            Shape::convex_hull(&points)
        }
        ShapeKind::Compound => {
            let children = entry
                .children
                .as_ref()
                .ok_or_else(|| required("children"))?;
            let children = children
                .iter()
                .enumerate()
                .map(|(index, child)| compound_child(child, &format!("{place}.children[{index}]")))
                .collect::<Result<Vec<_>, _>>()?;
            Shape::compound(children)
        }
        ShapeKind::Halfspace => {
            let normal = entry.normal.ok_or_else(|| required("normal"))?;
            Shape::halfspace(vector(&field("normal"), normal)?)
        }
    };
    shape.map_err(|error| SceneError::from(error.within(place)))
}

/// One child of a compound; errors are placed under `place` (`...children[i]`).
fn compound_child(entry: &ChildEntry, place: &str) -> Result<CompoundChild, SceneError> {
    let position = match entry.position {
        Some(value) => vector(&format!("{place}.position"), value)?,
        None => Vec3::ZERO,
    };
    let rotation = match entry.rotation {
        Some(value) => rotation(&format!("{place}.rotation"), value)?,
        None => Quat::IDENTITY,
    };
    Ok(CompoundChild {
        pose: Pose::new(position, rotation),
        shape: shape(&entry.shape, &format!("{place}.shape"))?,
    })
}
