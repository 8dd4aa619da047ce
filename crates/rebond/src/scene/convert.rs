//! From the file's model to the engine's descriptions: every number narrowed to `f32` and checked,
//! every error placed at the path of the value the user wrote (`bodies[3].shape.radius`).

use crate::body::{BodyDesc, BodyHandle, BodyType, KinematicPath, LockedAxes, PathPoint};
use crate::character::{CharacterController, CharacterSettings};
use crate::coupling::CouplingDesc;
use crate::filter::InteractionGroups;
use crate::joint::{AxisFreedom, JointDesc, JointHandle, JointType, Motor};
use crate::limits::{MAX_TIMESTEP, MIN_TIMESTEP};
use crate::mass::MassProperties;
use crate::math::{Mat3, Pose, Quat, Vec3};
use crate::shape::{CompoundChild, Shape};
use crate::world::WorldSettings;

use super::actuators::{Actuator, ActuatorKind};
use super::format::{
    ActuatorEntry, ActuatorKindEntry, AxisEntry, BodyEntry, CharacterEntry, ChildEntry,
    CouplingEntry, GroupsEntry, JointEntry, MassPropertiesEntry, MotorEntry, PathEntry, SceneFile,
    ShapeEntry, ShapeKind,
};
use super::meshes::{heightfield, trimesh, MeshFiles};
use super::{
    join, LoadError, SceneCharacter, SceneError, Timestep, DEFAULT_CHARACTER_JUMP_SPEED,
    DEFAULT_CHARACTER_WALK_SPEED, DEFAULT_TIMESTEP, MAX_CHARACTER_SPEED,
};

/// Narrows a file number to `f32`, refusing one beyond the `f32` range.
pub(super) fn scalar(place: &str, value: f64) -> Result<f32, SceneError> {
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

/// The world settings a scene file gives, each under its `WorldSettings` name, the engine's
/// default where it gives none; values are narrowed here and checked by [`crate::World::new`],
/// whose errors name the same fields.
pub(super) fn world_settings(file: &SceneFile) -> Result<WorldSettings, SceneError> {
    let defaults = WorldSettings::default();
    let setting = |place: &str, value: Option<f64>, default: f32| match value {
        Some(value) => scalar(place, value),
        None => Ok(default),
    };
    Ok(WorldSettings {
        gravity: match file.gravity {
            Some(gravity) => vector("gravity", gravity)?,
            None => defaults.gravity,
        },
        substeps: file.substeps.unwrap_or(defaults.substeps),
        max_linear_speed: setting(
            "max_linear_speed",
            file.max_linear_speed,
            defaults.max_linear_speed,
        )?,
        contact_hertz: setting("contact_hertz", file.contact_hertz, defaults.contact_hertz)?,
        contact_damping_ratio: setting(
            "contact_damping_ratio",
            file.contact_damping_ratio,
            defaults.contact_damping_ratio,
        )?,
        contact_push_speed: setting(
            "contact_push_speed",
            file.contact_push_speed,
            defaults.contact_push_speed,
        )?,
        restitution_threshold: setting(
            "restitution_threshold",
            file.restitution_threshold,
            defaults.restitution_threshold,
        )?,
        speculative_distance: setting(
            "speculative_distance",
            file.speculative_distance,
            defaults.speculative_distance,
        )?,
        sleep_speed: setting("sleep_speed", file.sleep_speed, defaults.sleep_speed)?,
        sleep_time: setting("sleep_time", file.sleep_time, defaults.sleep_time)?,
        joint_hertz: setting("joint_hertz", file.joint_hertz, defaults.joint_hertz)?,
        joint_damping_ratio: setting(
            "joint_damping_ratio",
            file.joint_damping_ratio,
            defaults.joint_damping_ratio,
        )?,
        friction_combine: file
            .friction_combine
            .map_or(defaults.friction_combine, |entry| entry.0),
        restitution_combine: file
            .restitution_combine
            .map_or(defaults.restitution_combine, |entry| entry.0),
    })
}

/// Narrows a file vector to a [`Vec3`], naming the bad component.
pub(super) fn vector(place: &str, value: [f64; 3]) -> Result<Vec3, SceneError> {
    let mut narrowed = [0.0; 3];
    for (index, component) in value.into_iter().enumerate() {
        narrowed[index] = scalar(&format!("{place}[{index}]"), component)?;
    }
    Ok(Vec3::from_array(narrowed))
}

/// Narrows a file quaternion `[x, y, z, w]` to a [`Quat`] (not normalised: the engine does it).
pub(super) fn rotation(place: &str, value: [f64; 4]) -> Result<Quat, SceneError> {
    let mut narrowed = [0.0; 4];
    for (index, component) in value.into_iter().enumerate() {
        narrowed[index] = scalar(&format!("{place}[{index}]"), component)?;
    }
    Ok(Quat::from_array(narrowed))
}

/// Narrows a file pair `[min, max]`, naming the bad element.
fn pair(place: &str, value: [f64; 2]) -> Result<[f32; 2], SceneError> {
    Ok([
        scalar(&format!("{place}[0]"), value[0])?,
        scalar(&format!("{place}[1]"), value[1])?,
    ])
}

/// The time step: finite and positive, also once rounded to `f32`, and within the engine's
/// limits.
pub(super) fn timestep(value: Option<f64>) -> Result<Timestep, SceneError> {
    let seconds = value.unwrap_or(DEFAULT_TIMESTEP);
    let engine_seconds = scalar("timestep", seconds)?;
    if engine_seconds > 0.0 && !(MIN_TIMESTEP..=MAX_TIMESTEP).contains(&engine_seconds) {
        Err(SceneError::new(
            "timestep",
            format!(
                "must lie between {MIN_TIMESTEP} and {MAX_TIMESTEP} (the engine's limits), got {}",
                number(seconds)
            ),
        ))
    } else if engine_seconds > 0.0 {
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

/// The scene's character: `find_body` gives the handle and type of a body by name. Errors are
/// placed under `character`; the controller's settings are checked by
/// [`CharacterController::new`], whose errors name the same fields.
pub(super) fn character(
    entry: &CharacterEntry,
    find_body: impl Fn(&str) -> Option<(BodyHandle, BodyType)>,
) -> Result<SceneCharacter, SceneError> {
    let body = match find_body(&entry.body) {
        Some((handle, BodyType::Kinematic)) => handle,
        Some(_) => {
            let message = format!("\"{}\" must be a kinematic body", entry.body);
            return Err(SceneError::new("character.body", message));
        }
        None => {
            let message = format!("no body is named \"{}\"", entry.body);
            return Err(SceneError::new("character.body", message));
        }
    };
    let speed = |name: &str, value: Option<f64>, default: f32, zero_allowed: bool| {
        let place = format!("character.{name}");
        let speed = match value {
            Some(value) => scalar(&place, value)?,
            None => default,
        };
        if speed <= MAX_CHARACTER_SPEED && (speed > 0.0 || zero_allowed && speed == 0.0) {
            return Ok(speed);
        }
        let lowest = if zero_allowed { "from 0" } else { "above 0" };
        let message = format!(
            "must lie {lowest} to {MAX_CHARACTER_SPEED} m/s, got {}",
            number(f64::from(speed))
        );
        Err(SceneError::new(place, message))
    };
    let mut settings = CharacterSettings::default();
    if let Some(value) = entry.max_slope_angle {
        settings.max_slope_angle = scalar("character.max_slope_angle", value)?;
    }
    if let Some(value) = entry.max_step_height {
        settings.max_step_height = scalar("character.max_step_height", value)?;
    }
    CharacterController::new(settings)
        .map_err(|error| SceneError::from(error.within("character")))?;
    Ok(SceneCharacter {
        body,
        walk_speed: speed(
            "walk_speed",
            entry.walk_speed,
            DEFAULT_CHARACTER_WALK_SPEED,
            false,
        )?,
        jump_speed: speed(
            "jump_speed",
            entry.jump_speed,
            DEFAULT_CHARACTER_JUMP_SPEED,
            true,
        )?,
        settings,
    })
}

/// A file number for a message: plain notation for ordinary magnitudes, scientific otherwise.
fn number(value: f64) -> String {
    if value == 0.0 || (1e-4..1e16).contains(&value.abs()) {
        value.to_string()
    } else {
        format!("{value:e}")
    }
}

/// The engine description of one body; errors are placed under `place` (`bodies[i]`). Mesh files
/// are read through `files`.
pub(super) fn body_desc(
    entry: &BodyEntry,
    place: &str,
    files: &MeshFiles,
) -> Result<BodyDesc, LoadError> {
    let field = |name: &str| format!("{place}.{name}");
    let shape = shape(&entry.shape, &field("shape"), files)?;
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
    if let Some(properties) = &entry.mass_properties {
        desc.mass_properties = Some(mass_properties(properties, &field("mass_properties"))?);
    }
    if let Some(value) = entry.friction {
        desc.friction = scalar(&field("friction"), value)?;
    }
    if let Some(value) = entry.restitution {
        desc.restitution = scalar(&field("restitution"), value)?;
    }
    if let Some(value) = entry.rolling_resistance {
        desc.rolling_resistance = scalar(&field("rolling_resistance"), value)?;
    }
    if let Some(value) = entry.force {
        desc.constant_force = vector(&field("force"), value)?;
    }
    if let Some(value) = entry.force_point {
        desc.constant_force_point = Some(vector(&field("force_point"), value)?);
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
    if let Some(locks) = &entry.locked_axes {
        desc.locked_axes = LockedAxes {
            translation: locks.translation.unwrap_or_default(),
            rotation: locks.rotation.unwrap_or_default(),
        };
    }
    if let Some(value) = entry.sensor {
        desc.sensor = value;
    }
    if let Some(groups) = &entry.collision_groups {
        desc.collision_groups = interaction_groups(groups);
    }
    if let Some(entry) = &entry.path {
        desc.path = Some(path(entry, &field("path"), desc.position, desc.rotation)?);
    }
    if let Some(value) = entry.one_way {
        desc.one_way = Some(vector(&field("one_way"), value)?);
    }
    if let Some(value) = entry.surface_velocity {
        desc.surface_velocity = vector(&field("surface_velocity"), value)?;
    }
    Ok(desc)
}

/// Explicit mass properties, narrowed; errors are placed under `place`
/// (`bodies[i].mass_properties`). The checks (positive mass, positive definite inertia) are the
/// world's, when the body is added.
fn mass_properties(entry: &MassPropertiesEntry, place: &str) -> Result<MassProperties, SceneError> {
    let field = |name: &str| join(place, name);
    let center_of_mass = match entry.center_of_mass {
        Some(value) => vector(&field("center_of_mass"), value)?,
        None => Vec3::ZERO,
    };
    let mut inertia = [0.0; 6];
    for (index, value) in entry.inertia.into_iter().enumerate() {
        inertia[index] = scalar(&format!("{place}.inertia[{index}]"), value)?;
    }
    let [xx, yy, zz, xy, xz, yz] = inertia;
    Ok(MassProperties {
        mass: scalar(&field("mass"), entry.mass)?,
        center_of_mass,
        inertia: Mat3::from_cols(
            Vec3::new(xx, xy, xz),
            Vec3::new(xy, yy, yz),
            Vec3::new(xz, yz, zz),
        ),
    })
}

/// The actuator of an `actuators` entry; errors are placed under `place` (`actuators[i]`).
/// `find_joint` gives the handle and type of a joint by name.
pub(super) fn actuator(
    entry: &ActuatorEntry,
    place: &str,
    name: String,
    find_joint: impl Fn(&str) -> Option<(JointHandle, JointType)>,
) -> Result<Actuator, SceneError> {
    let field = |name: &str| join(place, name);
    let joint = match find_joint(&entry.joint) {
        Some((handle, JointType::Revolute | JointType::Prismatic)) => handle,
        Some((_, other)) => {
            let message = format!(
                "\"{}\" is a {} joint; an actuator drives a revolute or prismatic one",
                entry.joint,
                other.name()
            );
            return Err(SceneError::new(field("joint"), message));
        }
        None => {
            let message = format!("no joint is named \"{}\"", entry.joint);
            return Err(SceneError::new(field("joint"), message));
        }
    };
    let gain = |name: &str, value: Option<f64>, default: f32| match value {
        Some(value) => {
            let gain = scalar(&field(name), value)?;
            if gain >= 0.0 {
                Ok(gain)
            } else {
                Err(SceneError::new(
                    field(name),
                    format!("must not be negative, got {gain}"),
                ))
            }
        }
        None => Ok(default),
    };
    let stray = |name: &str| {
        let message = format!(
            "unknown field `{name}` for a {} actuator",
            entry_kind_name(entry.kind)
        );
        SceneError::new(field(name), message)
    };
    let kind = match entry.kind {
        ActuatorKindEntry::Motor if entry.kp.is_some() => return Err(stray("kp")),
        ActuatorKindEntry::Motor if entry.kv.is_some() => return Err(stray("kv")),
        ActuatorKindEntry::Velocity if entry.kp.is_some() => return Err(stray("kp")),
        ActuatorKindEntry::Motor => ActuatorKind::Motor,
        ActuatorKindEntry::Position => ActuatorKind::Position {
            kp: gain("kp", entry.kp, 1.0)?,
            kv: gain("kv", entry.kv, 0.0)?,
        },
        ActuatorKindEntry::Velocity => ActuatorKind::Velocity {
            kv: gain("kv", entry.kv, 1.0)?,
        },
    };
    let gear = match entry.gear {
        Some(value) => scalar(&field("gear"), value)?,
        None => 1.0,
    };
    if gear == 0.0 {
        return Err(SceneError::new(field("gear"), "must not be 0"));
    }
    let ctrl_range = match entry.ctrl_range {
        Some(value) => {
            let [lo, hi] = pair(&field("ctrl_range"), value)?;
            if lo > hi {
                let message = format!("min must not exceed max, got [{lo}, {hi}]");
                return Err(SceneError::new(field("ctrl_range"), message));
            }
            Some([lo, hi])
        }
        None => None,
    };
    Ok(Actuator {
        name,
        joint,
        kind,
        gear,
        ctrl_range,
    })
}

/// The name of an actuator kind as written.
fn entry_kind_name(kind: ActuatorKindEntry) -> &'static str {
    match kind {
        ActuatorKindEntry::Motor => "motor",
        ActuatorKindEntry::Position => "position",
        ActuatorKindEntry::Velocity => "velocity",
    }
}

/// The engine path of a path entry; errors are placed under `place` (`bodies[i].path`). A point
/// without a position or rotation takes the body's, `body_position` and `body_rotation`. Times
/// are narrowed here; that they start at 0 and increase is checked when the body is added.
fn path(
    entry: &PathEntry,
    place: &str,
    body_position: Vec3,
    body_rotation: Quat,
) -> Result<KinematicPath, SceneError> {
    let mut points = Vec::with_capacity(entry.points.len());
    for (index, point) in entry.points.iter().enumerate() {
        let field = |name: &str| format!("{place}.points[{index}].{name}");
        let time = scalar(&field("time"), point.time)?;
        let position = match point.position {
            Some(value) => vector(&field("position"), value)?,
            None => body_position,
        };
        let rotation = match point.rotation {
            Some(value) => rotation(&field("rotation"), value)?,
            None => body_rotation,
        };
        points.push(PathPoint::new(time, position, rotation));
    }
    Ok(KinematicPath::new(points).looping(entry.looping.unwrap_or(false)))
}

/// The groups of a `collision_groups` entry: each mask all ones when left out.
fn interaction_groups(entry: &GroupsEntry) -> InteractionGroups {
    InteractionGroups::new(
        entry.memberships.unwrap_or(u32::MAX),
        entry.filter.unwrap_or(u32::MAX),
    )
}

/// The engine shape of a shape entry; errors are placed under `place` (`bodies[i].shape`).
fn shape(entry: &ShapeEntry, place: &str, files: &MeshFiles) -> Result<Shape, LoadError> {
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
        )
        .into());
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
                .map(|(index, child)| {
                    compound_child(child, &format!("{place}.children[{index}]"), files)
                })
                .collect::<Result<Vec<_>, _>>()?;
            Shape::compound(children)
        }
        ShapeKind::Halfspace => {
            let normal = entry.normal.ok_or_else(|| required("normal"))?;
            Shape::halfspace(vector(&field("normal"), normal)?)
        }
        ShapeKind::Trimesh => return trimesh(entry, place, files),
        ShapeKind::Heightfield => {
            let heights = entry.heights.as_ref().ok_or_else(|| required("heights"))?;
            let scale = entry.scale.ok_or_else(|| required("scale"))?;
            return Ok(heightfield(heights, scale, place)?);
        }
    };
    shape.map_err(|error| SceneError::from(error.within(place)).into())
}

/// One child of a compound; errors are placed under `place` (`...children[i]`).
fn compound_child(
    entry: &ChildEntry,
    place: &str,
    files: &MeshFiles,
) -> Result<CompoundChild, LoadError> {
    let position = match entry.position {
        Some(value) => vector(&format!("{place}.position"), value)?,
        None => Vec3::ZERO,
    };
    let rotation = match entry.rotation {
        Some(value) => rotation(&format!("{place}.rotation"), value)?,
        None => Quat::IDENTITY,
    };
    let mut child = CompoundChild::new(
        shape(&entry.shape, &format!("{place}.shape"), files)?,
        Pose::new(position, rotation),
    );
    if let Some(value) = entry.friction {
        child.friction = Some(scalar(&format!("{place}.friction"), value)?);
    }
    if let Some(value) = entry.restitution {
        child.restitution = Some(scalar(&format!("{place}.restitution"), value)?);
    }
    if let Some(value) = entry.rolling_resistance {
        child.rolling_resistance = Some(scalar(&format!("{place}.rolling_resistance"), value)?);
    }
    child.name.clone_from(&entry.name);
    child.sensor = entry.sensor;
    child.collision_groups = entry.collision_groups.as_deref().map(interaction_groups);
    Ok(child)
}

/// The engine description of one coupling; errors are placed under `place` (`couplings[i]`).
/// `find_joint` gives the handle of the joint of a name. Values are narrowed and the joints
/// looked up here; the rest (ranges, joint types, `min ≤ max`) is checked by the world when the
/// coupling is added.
pub(super) fn coupling_desc(
    entry: &CouplingEntry,
    place: &str,
    find_joint: impl Fn(&str) -> Option<JointHandle>,
) -> Result<CouplingDesc, SceneError> {
    let mut joints = Vec::with_capacity(entry.joints.len());
    for (index, term) in entry.joints.iter().enumerate() {
        let term_place = format!("{place}.joints[{index}]");
        let joint = find_joint(&term.joint).ok_or_else(|| {
            SceneError::new(
                format!("{term_place}.joint"),
                format!("no joint is named \"{}\"", term.joint),
            )
        })?;
        let coefficient = scalar(&format!("{term_place}.coefficient"), term.coefficient)?;
        joints.push((joint, coefficient));
    }
    let mut desc = CouplingDesc::new(joints);
    if let Some(limits) = entry.limits {
        desc.limits = Some(pair(&format!("{place}.limits"), limits)?);
    }
    if let Some(stiffness) = entry.stiffness {
        desc.stiffness = scalar(&format!("{place}.stiffness"), stiffness)?;
    }
    if let Some(damping) = entry.damping {
        desc.damping = scalar(&format!("{place}.damping"), damping)?;
    }
    if let Some(length) = entry.length {
        desc.length = Some(scalar(&format!("{place}.length"), length)?);
    }
    Ok(desc)
}

/// The engine description of one joint; errors are placed under `place` (`joints[i]`).
/// `find_body` gives the handle and the position of the body of a name. Values are narrowed and
/// the bodies looked up here; the rest (ranges, which fields the joint type takes, a body joined
/// to itself) is checked by the world when the joint is added.
pub(super) fn joint_desc(
    entry: &JointEntry,
    place: &str,
    find_body: impl Fn(&str) -> Option<(BodyHandle, Vec3)>,
) -> Result<JointDesc, SceneError> {
    let field = |name: &str| format!("{place}.{name}");
    let body = |name: &str, side: &str| {
        find_body(name)
            .ok_or_else(|| SceneError::new(field(side), format!("no body is named \"{name}\"")))
    };
    let body_a = match &entry.body_a {
        Some(name) => Some(body(name, "body_a")?.0),
        None => None,
    };
    let (body_b, position_b) = body(&entry.body_b, "body_b")?;
    let anchor = match entry.anchor {
        Some(value) => vector(&field("anchor"), value)?,
        None => position_b,
    };
    let mut desc = JointDesc::new(entry.kind.into(), body_a, body_b, anchor);
    if let Some(value) = entry.anchor_b {
        desc.anchor_b = Some(vector(&field("anchor_b"), value)?);
    }
    if let Some(value) = entry.axis {
        desc.axis = Some(vector(&field("axis"), value)?);
    }
    if let Some(value) = entry.limits {
        desc.limits = Some(pair(&field("limits"), value)?);
    }
    if let Some(value) = entry.swing_limit {
        desc.swing_limit = Some(scalar(&field("swing_limit"), value)?);
    }
    if let Some(value) = entry.twist_limits {
        desc.twist_limits = Some(pair(&field("twist_limits"), value)?);
    }
    if let Some(entry) = &entry.motor {
        desc.motor = Some(motor(entry, &field("motor"))?);
    }
    if let Some(value) = entry.length {
        desc.length = Some(scalar(&field("length"), value)?);
    }
    if let Some(spring) = &entry.spring {
        let optional = |name: &str, value: Option<f64>| match value {
            Some(value) => scalar(&field(name), value),
            None => Ok(0.0),
        };
        desc = desc.spring_to(
            scalar(&field("spring.stiffness"), spring.stiffness)?,
            optional("spring.damping", spring.damping)?,
            optional("spring.reference", spring.reference)?,
        );
    }
    if let Some(value) = entry.armature {
        desc.armature = scalar(&field("armature"), value)?;
    }
    if let Some(value) = entry.frame {
        desc.frame = Some(rotation(&field("frame"), value)?);
    }
    if let Some(axes) = &entry.axes {
        for (axis, value) in axes.given() {
            let place = field(&format!("axes.{}", axis.name()));
            desc.axes[axis.index()] = axis_freedom(value, &place)?;
        }
    }
    if let Some(motors) = &entry.motors {
        for (axis, value) in motors.given() {
            let place = field(&format!("motors.{}", axis.name()));
            desc.motors[axis.index()] = Some(motor(value, &place)?);
        }
    }
    if let Some(value) = entry.friction {
        desc.friction = scalar(&field("friction"), value)?;
    }
    if let Some(value) = entry.collide_connected {
        desc.collide_connected = value;
    }
    if let Some(value) = entry.break_force {
        desc.break_force = scalar(&field("break_force"), value)?;
    }
    if let Some(value) = entry.break_torque {
        desc.break_torque = scalar(&field("break_torque"), value)?;
    }
    Ok(desc)
}

/// What a generic joint's axis entry says; errors are placed at `place` (`joints[i].axes.x`).
fn axis_freedom(entry: &AxisEntry, place: &str) -> Result<AxisFreedom, SceneError> {
    match entry {
        AxisEntry::Mode(mode) if mode == "locked" => Ok(AxisFreedom::Locked),
        AxisEntry::Mode(mode) if mode == "free" => Ok(AxisFreedom::Free),
        AxisEntry::Mode(mode) => Err(SceneError::new(
            place,
            format!(
                "unknown axis mode \"{mode}\", expected `\"locked\"`, `\"free\"` or [min, max]"
            ),
        )),
        AxisEntry::Limited(limits) => Ok(AxisFreedom::Limited(pair(place, *limits)?)),
    }
}

/// The engine motor of a motor entry; errors are placed under `place` (`joints[i].motor`). The
/// field present says the kind: `target_velocity` a velocity motor, `target_position` a position
/// motor, `torque` a torque motor. A missing `max_force` is unlimited, a missing position motor
/// `damping` is 0.
fn motor(entry: &MotorEntry, place: &str) -> Result<Motor, SceneError> {
    let field = |name: &str| join(place, name);
    let max_force = || match entry.max_force {
        Some(value) => scalar(&field("max_force"), value),
        None => Ok(f32::INFINITY),
    };
    match (entry.target_velocity, entry.target_position) {
        (Some(target_velocity), _) => {
            motor_fields(entry, place, "velocity", &["target_velocity", "max_force"])?;
            Ok(Motor::velocity(
                scalar(&field("target_velocity"), target_velocity)?,
                max_force()?,
            ))
        }
        (None, Some(target_position)) => {
            let fields = ["target_position", "stiffness", "damping", "max_force"];
            motor_fields(entry, place, "position", &fields)?;
            let stiffness = entry.stiffness.ok_or_else(|| {
                SceneError::new(
                    field("stiffness"),
                    "required field is missing (a position motor needs it)",
                )
            })?;
            let damping = match entry.damping {
                Some(value) => scalar(&field("damping"), value)?,
                None => 0.0,
            };
            Ok(Motor::position(
                scalar(&field("target_position"), target_position)?,
                scalar(&field("stiffness"), stiffness)?,
                damping,
                max_force()?,
            ))
        }
        (None, None) => match entry.torque {
            Some(torque) => {
                motor_fields(entry, place, "torque", &["torque"])?;
                Ok(Motor::torque(scalar(&field("torque"), torque)?))
            }
            None => Err(SceneError::new(
                place,
                "required field is missing: `target_velocity` (a velocity motor), \
                 `target_position` (a position motor) or `torque` (a torque motor)",
            )),
        },
    }
}

/// Refuses a field of a motor entry that its `kind` of motor does not take (`fields`).
fn motor_fields(
    entry: &MotorEntry,
    place: &str,
    kind: &str,
    fields: &[&str],
) -> Result<(), SceneError> {
    match entry.present_fields().find(|field| !fields.contains(field)) {
        Some(stray) => {
            let expected = fields
                .iter()
                .map(|field| format!("`{field}`"))
                .collect::<Vec<_>>()
                .join(", ");
            Err(SceneError::new(
                join(place, stray),
                format!("unknown field `{stray}` for a {kind} motor, expected {expected}"),
            ))
        }
        None => Ok(()),
    }
}
