//! Scene files: JSON descriptions of a world (gravity, timestep, bodies with their shapes and
//! materials, joints between them), loaded into a [`World`] ready to step. The format is
//! documented field by field in `docs/scene-format.md`; the `rebond` command line runs such files.
//!
//! ```
//! use rebond::scene::Scene;
//!
//! let json = br#"{
//!     "bodies": [
//!         { "name": "ground", "type": "static",
//!           "shape": { "type": "box", "half_extents": [10, 0.5, 10] }, "position": [0, -0.5, 0] },
//!         { "name": "ball", "shape": { "type": "sphere", "radius": 0.5 }, "position": [0, 3, 0] }
//!     ]
//! }"#;
//! let mut scene = Scene::from_json(json)?;
//! for _ in 0..120 {
//!     scene.step()?;
//! }
//! let ball = scene.body_handle("ball").expect("the scene names it");
//! assert!((scene.world().body(ball)?.position().y - 0.5).abs() < 0.01);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Every value is checked before anything is built: an invalid scene is a [`SceneError`] naming
//! the place of the bad value in the file (`bodies[3].shape.radius`) and what is wrong with it.

mod actuators;
mod builtin;
mod convert;
mod format;
mod meshes;
mod mjcf;
mod urdf;

use std::collections::HashMap;
use std::fmt;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;

use crate::body::{BodyHandle, RigidBody};
use crate::character::CharacterSettings;
use crate::coupling::CouplingHandle;
use crate::error::ErrorKind;
use crate::joint::{Joint, JointHandle, JointType};
use crate::world::World;
pub use actuators::{Actuator, ActuatorKind};
pub use builtin::{builtin, BuiltinScene, BUILTIN_SCENES};
use convert::{
    actuator, body_desc, character, coupling_desc, joint_desc, timestep, world_settings,
};
use format::{BodyEntry, CouplingEntry, JointEntry, JsonObject, SceneFile};
use meshes::MeshFiles;
pub use urdf::UrdfOptions;

/// Default seconds per step when a scene leaves `timestep` out.
pub const DEFAULT_TIMESTEP: f64 = 1.0 / 60.0;

/// Default walking speed of a scene's character, m/s: a brisk walk.
pub const DEFAULT_CHARACTER_WALK_SPEED: f32 = 4.0;

/// Default take-off speed of a scene's character's jump, m/s: under standard gravity it rises
/// `v² / 2g` = 1.27 m.
pub const DEFAULT_CHARACTER_JUMP_SPEED: f32 = 5.0;

/// The fastest a scene's character walks or jumps, m/s.
pub const MAX_CHARACTER_SPEED: f32 = 100.0;

/// An invalid scene: where in the file, and what is wrong.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError {
    /// Path of the bad value, such as `bodies[3].shape.radius`, or `line 3, column 7` for text
    /// that is not JSON; empty for the file as a whole.
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

impl SceneError {
    /// The same error, seen from one level up: a place within a body entry becomes a place within
    /// `bodies[2]`. A line and column in the text stays as it is.
    fn within(mut self, prefix: &str) -> Self {
        if self.place.is_empty() || self.place == "top level" {
            self.place = prefix.to_owned();
        } else if !self.place.starts_with("line ") {
            self.place = join(prefix, &self.place);
        }
        self
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

impl std::error::Error for SceneError {}

impl From<crate::Error> for SceneError {
    fn from(error: crate::Error) -> Self {
        Self::new(error.field, error.kind.to_string())
    }
}

/// Why a scene file could not be loaded.
#[derive(Debug)]
pub enum LoadError {
    /// The file could not be read.
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        error: io::Error,
    },
    /// The file was read but is not a valid scene.
    Invalid(SceneError),
    /// A mesh file the scene names (a `trimesh`'s `file`) could not be read or is not a valid
    /// Wavefront OBJ file.
    Mesh {
        /// Where the scene names it, such as `bodies[0].shape.file`.
        place: String,
        /// The file, as resolved against the scene's folder.
        path: PathBuf,
        /// Why it could not be used.
        message: String,
    },
}

impl From<SceneError> for LoadError {
    fn from(error: SceneError) -> Self {
        Self::Invalid(error)
    }
}

impl fmt::Display for LoadError {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Read { path, error } => {
                write!(formatter, "{}: cannot read scene: {error}", path.display())
            }
            Self::Invalid(error) => error.fmt(formatter),
            Self::Mesh {
                place,
                path,
                message,
            } => write!(
                formatter,
                "{place}: cannot load mesh file {}: {message}",
                path.display()
            ),
        }
    }
}

impl std::error::Error for LoadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Read { error, .. } => Some(error),
            Self::Invalid(error) => Some(error),
            Self::Mesh { .. } => None,
        }
    }
}

impl World {
    /// The world of the scene file at `path` (see [`Scene::from_file`], which also keeps the
    /// bodies' names and the scene's timestep).
    pub fn from_scene_file(path: impl AsRef<Path>) -> Result<Self, LoadError> {
        Scene::from_file(path).map(Scene::into_world)
    }
}

/// The first eight bytes of a scene's state ([`crate::state`]).
#[cfg(feature = "serde")]
const SCENE_MAGIC: &[u8; 8] = b"REBONDSC";

/// Seconds per step, as written and as the engine steps with it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Timestep {
    /// The scene's value in double precision; record times are `step × seconds`.
    pub seconds: f64,
    /// The same value rounded to `f32`, passed to `World::step`.
    pub engine_seconds: f32,
}

/// A body of a loaded scene.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct SceneBody {
    /// Its unique name, used in records.
    name: String,
    /// Its handle in the scene's world.
    handle: BodyHandle,
}

/// A joint of a loaded scene.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct SceneJoint {
    /// Its unique name among joints, used in records.
    name: String,
    /// Its handle in the scene's world.
    handle: JointHandle,
}

/// A coupling of a loaded scene.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct SceneCoupling {
    /// Its unique name among couplings (`coupling{i}` when the file gives none).
    name: String,
    /// Its handle in the scene's world.
    handle: CouplingHandle,
}

/// The character a scene names (its `character` field): a kinematic body a player drives with a
/// [`crate::character::CharacterController`], walking at `walk_speed` and jumping at
/// `jump_speed`. The scene only names it; the program that reads the scene moves it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SceneCharacter {
    /// The character's body, kinematic.
    pub body: BodyHandle,
    /// Walking speed along the ground, m/s, above 0 and at most [`MAX_CHARACTER_SPEED`]; default
    /// [`DEFAULT_CHARACTER_WALK_SPEED`].
    pub walk_speed: f32,
    /// Upward speed a jump starts with, m/s, 0 to [`MAX_CHARACTER_SPEED`]; default
    /// [`DEFAULT_CHARACTER_JUMP_SPEED`]. Gravity then slows it: a jump rises `v² / 2g`.
    pub jump_speed: f32,
    /// The controller's settings, checked: the scene's `max_slope_angle` and `max_step_height`,
    /// the defaults of [`CharacterSettings`] otherwise.
    pub settings: CharacterSettings,
}

/// A scene checked and loaded into a world, ready to step.
///
/// Stepping never removes a body or a joint (a broken joint stays, broken), so the handle of every
/// scene body and joint stays valid unless removed through [`Scene::world_mut`].
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Scene {
    world: World,
    bodies: Vec<SceneBody>,
    joints: Vec<SceneJoint>,
    couplings: Vec<SceneCoupling>,
    /// Index in `bodies` by name (not saved: rebuilt from `bodies` when a state is loaded).
    #[cfg_attr(feature = "serde", serde(skip))]
    body_indices: HashMap<String, usize>,
    /// Index in `joints` by name (as `body_indices`).
    #[cfg_attr(feature = "serde", serde(skip))]
    joint_indices: HashMap<String, usize>,
    timestep: Timestep,
    character: Option<SceneCharacter>,
    /// The actuators, in file order (a state read from its portable part, by another build,
    /// has none, as it has no character).
    actuators: Vec<Actuator>,
}

impl Scene {
    /// Reads, checks and loads the scene file at `path`; mesh files it names are found relative
    /// to the scene file's folder. Nothing is stepped. The extension says the format: `.xml` is
    /// a MuJoCo MJCF model ([`Scene::from_mjcf`]), `.urdf` a URDF robot, anything else a JSON
    /// scene.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Self, LoadError> {
        let path = path.as_ref();
        let bytes = fs::read(path).map_err(|error| LoadError::Read {
            path: path.to_owned(),
            error,
        })?;
        let folder = path.parent().unwrap_or(Path::new(""));
        let extension = path.extension().and_then(|extension| extension.to_str());
        match extension.map(str::to_ascii_lowercase).as_deref() {
            Some("xml") => Self::from_mjcf(&bytes, folder),
            Some("urdf") => Self::from_urdf(&bytes, folder),
            _ => Self::from_json_in(&bytes, folder),
        }
    }

    /// Parses and checks a scene given as JSON text and builds its world; mesh files it names
    /// are found relative to the working directory, and one that cannot be loaded is an error
    /// at the place that names it. Nothing is stepped.
    pub fn from_json(bytes: &[u8]) -> Result<Self, SceneError> {
        Self::from_json_in(bytes, Path::new("")).map_err(into_scene_error)
    }

    /// [`Scene::from_json`] with mesh files found relative to `folder`, and a mesh file that
    /// cannot be loaded reported as [`LoadError::Mesh`].
    pub fn from_json_in(bytes: &[u8], folder: &Path) -> Result<Self, LoadError> {
        Self::load(bytes, MeshFiles { folder, given: &[] })
    }

    /// Reads a MuJoCo MJCF model (the XML text `bytes`) as a scene: its bodies, joints,
    /// actuators and fixed tendons, turned from MuJoCo's Z-up to rebond's Y-up
    /// (`docs/mjcf.md`). Mesh files it names are found relative to `folder`. An element or
    /// attribute rebond cannot honour is an error naming its path in the file, such as
    /// `mujoco/worldbody/body[name=torso]/geom[2]@foo`. Nothing is stepped.
    pub fn from_mjcf(bytes: &[u8], folder: &Path) -> Result<Self, LoadError> {
        let json = mjcf_to_json(bytes, folder)?;
        Self::load(json.as_bytes(), MeshFiles { folder, given: &[] })
    }

    /// Reads a URDF robot (the XML text `bytes`) as a scene, its root link fixed to the world:
    /// [`Scene::from_urdf_with`] with the default [`UrdfOptions`].
    pub fn from_urdf(bytes: &[u8], folder: &Path) -> Result<Self, LoadError> {
        Self::from_urdf_with(bytes, folder, UrdfOptions::default())
    }

    /// Reads a URDF robot (the XML text `bytes`) as a scene: a body per link, a joint per
    /// joint, each named as in the file, a torque actuator per joint with an `effort` limit, a
    /// coupling per `mimic`, turned from URDF's Z-up to rebond's Y-up (`docs/urdf.md`). The root
    /// link is fixed to the world unless `options.floating_base`. What rebond cannot honour is
    /// an error naming its path in the file, such as `robot/link[name=base]/inertial/mass`.
    /// Nothing is stepped.
    pub fn from_urdf_with(
        bytes: &[u8],
        folder: &Path,
        options: UrdfOptions,
    ) -> Result<Self, LoadError> {
        let model = urdf::import(bytes, folder, options)?;
        let json = serde_json::to_vec(&model)
            .map_err(|error| SceneError::new("", format!("cannot write the model: {error}")))?;
        Self::load(&json, MeshFiles { folder, given: &[] })
    }

    /// [`Scene::from_json`] with the mesh files it names given as `(name, contents)` pairs, the
    /// name as the scene writes it (for scenes embedded in a program with their OBJ files); a
    /// file not among them is read relative to the working directory.
    pub fn from_json_with_files(bytes: &[u8], files: &[(&str, &[u8])]) -> Result<Self, LoadError> {
        Self::load(
            bytes,
            MeshFiles {
                folder: Path::new(""),
                given: files,
            },
        )
    }

    /// Parses, checks and builds a scene, reading mesh files through `files`.
    fn load(bytes: &[u8], files: MeshFiles) -> Result<Self, LoadError> {
        let JsonObject::<SceneFile>(file) = parse(bytes)?;
        let timestep = timestep(file.timestep)?;
        let settings = world_settings(&file)?;
        let mut scene = Self {
            world: World::new(settings).map_err(SceneError::from)?,
            bodies: Vec::with_capacity(file.bodies.len()),
            joints: Vec::new(),
            couplings: Vec::new(),
            body_indices: HashMap::new(),
            joint_indices: HashMap::new(),
            timestep,
            character: None,
            actuators: Vec::new(),
        };
        for entry in &file.bodies {
            scene.push_body(entry, &files)?;
        }
        for entry in file.joints.as_deref().unwrap_or_default() {
            scene.push_joint(entry)?;
        }
        for entry in file.couplings.iter().flatten() {
            scene.push_coupling(entry)?;
        }
        for (index, pair) in file.ignored_pairs.iter().flatten().enumerate() {
            scene.ignore_pair(pair, &format!("ignored_pairs[{index}]"))?;
        }
        for (index, entry) in file.actuators.iter().flatten().enumerate() {
            let place = format!("actuators[{index}]");
            let name = entry
                .name
                .clone()
                .unwrap_or_else(|| format!("actuator{index}"));
            if let Some(first) = scene.actuators.iter().position(|known| known.name == name) {
                let message = format!(
                    "duplicate name \"{name}\": actuators[{first}] and {place} both have it"
                );
                return Err(SceneError::new(format!("{place}.name"), message).into());
            }
            let find_joint = |name: &str| {
                let handle = scene.joints[*scene.joint_indices.get(name)?].handle;
                Some((handle, scene.world.joint(handle).ok()?.joint_type()))
            };
            let actuator = actuator(entry, &place, name, find_joint)?;
            scene.actuators.push(actuator);
        }
        actuators::add_damping(&mut scene.world, &scene.actuators).map_err(SceneError::from)?;
        let zeros = vec![0.0; scene.actuators.len()];
        actuators::apply(&mut scene.world, &scene.actuators, &zeros).map_err(SceneError::from)?;
        if let Some(entry) = &file.character {
            let find_body = |name: &str| {
                let handle = scene.body_handle(name)?;
                Some((handle, scene.world.body(handle).ok()?.body_type()))
            };
            scene.character = Some(character(entry, find_body)?);
        }
        Ok(scene)
    }

    /// Adds a body given as one entry of a scene's `bodies` (a JSON object), checked exactly as
    /// the loader checks it, after the bodies already there; returns its index in scene order.
    /// An error names the place the body would have in the file (`bodies[2].shape.radius`).
    pub fn add_body_json(&mut self, bytes: &[u8]) -> Result<usize, SceneError> {
        let place = format!("bodies[{}]", self.bodies.len());
        let JsonObject(entry) = parse(bytes).map_err(|error| error.within(&place))?;
        let files = MeshFiles {
            folder: Path::new(""),
            given: &[],
        };
        self.push_body(&entry, &files).map_err(into_scene_error)
    }

    /// Adds a joint given as one entry of a scene's `joints` (a JSON object), checked exactly as
    /// the loader checks it, after the joints already there; returns its index in scene order.
    /// Default anchors are where the bodies stand now.
    pub fn add_joint_json(&mut self, bytes: &[u8]) -> Result<usize, SceneError> {
        let place = format!("joints[{}]", self.joints.len());
        let JsonObject(entry) = parse(bytes).map_err(|error| error.within(&place))?;
        self.push_joint(&entry)
    }

    /// Checks and adds one body entry after the others, reading mesh files through `files`;
    /// returns its index.
    fn push_body(&mut self, entry: &BodyEntry, files: &MeshFiles) -> Result<usize, LoadError> {
        let index = self.bodies.len();
        let place = format!("bodies[{index}]");
        let name = entry.name.clone().unwrap_or_else(|| format!("body{index}"));
        if let Some(&first) = self.body_indices.get(&name) {
            let message =
                format!("duplicate name \"{name}\": bodies[{first}] and {place} both have it");
            return Err(SceneError::new(format!("{place}.name"), message).into());
        }
        let desc = body_desc(entry, &place, files)?;
        let handle = self
            .world
            .add_body(desc)
            .map_err(|error| SceneError::from(error.within(&place)))?;
        self.body_indices.insert(name.clone(), index);
        self.bodies.push(SceneBody { name, handle });
        Ok(index)
    }

    /// Checks and adds one joint entry after the others; returns its index. The bodies' places,
    /// for default anchors, are where they stand now.
    fn push_joint(&mut self, entry: &JointEntry) -> Result<usize, SceneError> {
        let index = self.joints.len();
        let place = format!("joints[{index}]");
        let name = entry
            .name
            .clone()
            .unwrap_or_else(|| format!("joint{index}"));
        if let Some(&first) = self.joint_indices.get(&name) {
            let message =
                format!("duplicate name \"{name}\": joints[{first}] and {place} both have it");
            return Err(SceneError::new(format!("{place}.name"), message));
        }
        let find_body = |name: &str| {
            let handle = self.bodies[*self.body_indices.get(name)?].handle;
            Some((handle, self.world.body(handle).ok()?.position()))
        };
        let desc = joint_desc(entry, &place, find_body)?;
        let joint_type = desc.joint_type;
        let handle = self
            .world
            .add_joint(desc)
            .map_err(|error| joint_error(error.within(&place), joint_type))?;
        self.joint_indices.insert(name.clone(), index);
        self.joints.push(SceneJoint { name, handle });
        Ok(index)
    }

    /// Checks and adds one coupling entry after the others; returns its index.
    fn push_coupling(&mut self, entry: &CouplingEntry) -> Result<usize, SceneError> {
        let index = self.couplings.len();
        let place = format!("couplings[{index}]");
        let name = (entry.name.clone()).unwrap_or_else(|| format!("coupling{index}"));
        if let Some(first) = self.couplings.iter().position(|c| c.name == name) {
            let message =
                format!("duplicate name \"{name}\": couplings[{first}] and {place} both have it");
            return Err(SceneError::new(format!("{place}.name"), message));
        }
        let desc = coupling_desc(entry, &place, |name| self.joint_handle(name))?;
        let handle = (self.world)
            .add_coupling(desc)
            .map_err(|error| SceneError::from(error.within(&place)))?;
        self.couplings.push(SceneCoupling { name, handle });
        Ok(index)
    }

    /// The handle of the coupling of this name, if the scene has one.
    pub fn coupling_handle(&self, name: &str) -> Option<CouplingHandle> {
        let coupling = self.couplings.iter().find(|c| c.name == name)?;
        Some(coupling.handle)
    }

    /// Keeps the two bodies named by `pair` from ever colliding with each other; an unknown
    /// name, or one body named twice, is an error at `place[i]`.
    fn ignore_pair(&mut self, pair: &[String; 2], place: &str) -> Result<(), SceneError> {
        let [a, b] = [0, 1].map(|side| {
            let name = &pair[side];
            (self.body_handle(name)).ok_or_else(|| {
                SceneError::new(
                    format!("{place}[{side}]"),
                    format!("no body is named \"{name}\""),
                )
            })
        });
        let (a, b) = (a?, b?);
        if a == b {
            let message = "a body cannot be paired with itself";
            return Err(SceneError::new(format!("{place}[1]"), message));
        }
        self.world
            .set_pair_ignored(a, b, true)
            .map_err(|error| SceneError::from(error.within(place)))
    }

    /// The world holding every body of the scene.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The character the scene names, if any.
    pub fn character(&self) -> Option<&SceneCharacter> {
        self.character.as_ref()
    }

    /// The scene's actuators (its `actuators`), in file order: the order of
    /// [`Scene::set_controls`]'s values.
    pub fn actuators(&self) -> &[Actuator] {
        &self.actuators
    }

    /// Sets every actuator's control, one value per actuator in the order of
    /// [`Scene::actuators`], as the motor of its joint ([`Actuator::motor`]): a `motor` gives the
    /// torque `gear · clamp(u)`. The controls hold until set again. Every value is checked first:
    /// a wrong count is an error at `controls`, a non-finite value or a resulting motor out of
    /// the engine's range an error at `controls[i]`, and nothing changes then.
    pub fn set_controls(&mut self, controls: &[f32]) -> crate::Result<()> {
        actuators::apply(&mut self.world, &self.actuators, controls)
    }

    /// Seconds per step.
    pub fn timestep(&self) -> Timestep {
        self.timestep
    }

    /// Advances the world by one time step.
    pub fn step(&mut self) -> crate::Result<()> {
        self.world.step(self.timestep.engine_seconds)
    }

    /// Every body with its name, in scene order (a body removed through [`Scene::world_mut`] is
    /// left out).
    pub fn bodies(&self) -> impl Iterator<Item = (&str, &RigidBody)> {
        self.bodies.iter().filter_map(|body| {
            let state = self.world.body(body.handle).ok()?;
            Some((body.name.as_str(), state))
        })
    }

    /// The handle of the body named `name`.
    pub fn body_handle(&self, name: &str) -> Option<BodyHandle> {
        self.bodies
            .iter()
            .find(|body| body.name == name)
            .map(|body| body.handle)
    }

    /// Every joint with its name, in scene order (a joint removed through [`Scene::world_mut`] is
    /// left out; a broken one stays).
    pub fn joints(&self) -> impl Iterator<Item = (&str, &Joint)> {
        self.joints.iter().filter_map(|joint| {
            let state = self.world.joint(joint.handle).ok()?;
            Some((joint.name.as_str(), state))
        })
    }

    /// The handle of the joint named `name`.
    pub fn joint_handle(&self, name: &str) -> Option<JointHandle> {
        self.joints
            .iter()
            .find(|joint| joint.name == name)
            .map(|joint| joint.handle)
    }

    /// Every body's name and handle, in scene order, removed bodies included.
    pub fn body_handles(&self) -> impl Iterator<Item = (&str, BodyHandle)> {
        self.bodies
            .iter()
            .map(|body| (body.name.as_str(), body.handle))
    }

    /// Every joint's name and handle, in scene order, removed joints included.
    pub fn joint_handles(&self) -> impl Iterator<Item = (&str, JointHandle)> {
        self.joints
            .iter()
            .map(|joint| (joint.name.as_str(), joint.handle))
    }

    /// The scene as it stands after `step` steps, as bytes (the format of [`crate::state`], a
    /// scene's header): its world, names and timestep. [`Scene::load_state`] restores it.
    #[cfg(feature = "serde")]
    pub fn save_state(&self, step: u64) -> Vec<u8> {
        let named = |name: &str, handle: crate::arena::ArenaIndex| crate::state::NamedV1 {
            name: name.to_owned(),
            slot: handle.slot() as u32,
            generation: handle.generation(),
        };
        let scene = crate::state::SceneV1 {
            step,
            timestep: self.timestep.seconds,
            bodies: (self.bodies.iter())
                .map(|body| named(&body.name, body.handle.0))
                .collect(),
            joints: (self.joints.iter())
                .map(|joint| named(&joint.name, joint.handle.0))
                .collect(),
        };
        let coupling_names = (self.couplings.iter())
            .map(|coupling| named(&coupling.name, coupling.handle.0))
            .collect();
        let snapshot = crate::state::SnapshotV5::of(&self.world, Some(scene), coupling_names);
        crate::state::encode(SCENE_MAGIC, &(step, self), snapshot)
    }

    /// A scene saved by [`Scene::save_state`] and the step it was saved after; bytes that are not
    /// a scene's state of this format version, or are cut short or damaged, are an error saying
    /// which. A state another build wrote is rebuilt from its portable snapshot, as
    /// [`World::load_state`] does.
    #[cfg(feature = "serde")]
    pub fn load_state(bytes: &[u8]) -> Result<(Scene, u64), crate::state::StateError> {
        Self::load_state_from(bytes, false)
    }

    /// [`Scene::load_state`] as a build of other engine sources reads the bytes: from their
    /// portable snapshot, contacts cold. For tests of the snapshot.
    #[doc(hidden)]
    #[cfg(feature = "serde")]
    pub fn load_state_as_other_build(
        bytes: &[u8],
    ) -> Result<(Scene, u64), crate::state::StateError> {
        Self::load_state_from(bytes, true)
    }

    #[cfg(feature = "serde")]
    fn load_state_from(
        bytes: &[u8],
        portable: bool,
    ) -> Result<(Scene, u64), crate::state::StateError> {
        use crate::state::{Decoded, StateError};
        let decoded = crate::state::decode::<(u64, Scene)>(SCENE_MAGIC, bytes, portable)?;
        let (step, mut scene) = match decoded {
            Decoded::Exact((step, scene)) => {
                scene.check_decoded().map_err(StateError::Inconsistent)?;
                (step, scene)
            }
            Decoded::Portable(snapshot) => {
                let missing = || StateError::Inconsistent("the scene's names are missing".into());
                let mut snapshot = *snapshot;
                let names = snapshot.base.scene.take().ok_or_else(missing)?;
                let coupling_names = std::mem::take(&mut snapshot.coupling_names);
                let world = snapshot.restore_world().map_err(StateError::Inconsistent)?;
                let identity = world.identity();
                let handle = |named: &crate::state::NamedV1| {
                    crate::arena::ArenaIndex::from_parts(named.slot, named.generation, identity)
                };
                let scene = Scene {
                    bodies: (names.bodies.iter())
                        .map(|named| SceneBody {
                            name: named.name.clone(),
                            handle: BodyHandle(handle(named)),
                        })
                        .collect(),
                    joints: (names.joints.iter())
                        .map(|named| SceneJoint {
                            name: named.name.clone(),
                            handle: JointHandle(handle(named)),
                        })
                        .collect(),
                    world,
                    body_indices: HashMap::new(),
                    joint_indices: HashMap::new(),
                    timestep: timestep(Some(names.timestep)).map_err(|error| {
                        StateError::Inconsistent(format!("the timestep: {error}"))
                    })?,
                    couplings: (coupling_names.iter())
                        .map(|named| SceneCoupling {
                            name: named.name.clone(),
                            handle: CouplingHandle(handle(named)),
                        })
                        .collect(),
                    character: None,
                    actuators: Vec::new(),
                };
                (names.step, scene)
            }
        };
        scene.body_indices = (scene.bodies.iter().enumerate())
            .map(|(index, body)| (body.name.clone(), index))
            .collect();
        scene.joint_indices = (scene.joints.iter().enumerate())
            .map(|(index, joint)| (joint.name.clone(), index))
            .collect();
        Ok((scene, step))
    }

    /// Checks a decoded scene: its world ([`World::load_state`]'s checks) and its timestep.
    #[cfg(feature = "serde")]
    fn check_decoded(&self) -> Result<(), String> {
        self.world.check_decoded()?;
        match convert::timestep(Some(self.timestep.seconds)) {
            Ok(timestep) if timestep.engine_seconds == self.timestep.engine_seconds => Ok(()),
            _ => Err("the timestep is out of range".to_owned()),
        }
    }

    /// The world, to change: set velocities, apply forces, add bodies.
    pub fn world_mut(&mut self) -> &mut World {
        &mut self.world
    }

    /// The world alone, without the names and the timestep.
    pub fn into_world(self) -> World {
        self.world
    }
}

/// The scene file (JSON text) of a MuJoCo MJCF model: what [`Scene::from_mjcf`] loads, for a
/// user to read, keep or edit. Mesh files the model names are read relative to `folder` (their
/// points are written into the scene).
pub fn mjcf_to_json(bytes: &[u8], folder: &Path) -> Result<String, LoadError> {
    let model = mjcf::import(bytes, folder)?;
    serde_json::to_string_pretty(&model)
        .map_err(|error| SceneError::new("", format!("cannot write the model: {error}")).into())
}

/// The scene error for a joint the world refused: a missing axis is told the way the loader
/// tells every missing field, with the reason it is needed.
fn joint_error(error: crate::Error, joint_type: JointType) -> SceneError {
    if error.kind != ErrorKind::Missing {
        return error.into();
    }
    let needing = match joint_type {
        JointType::Ball => "a ball joint with `swing_limit` or `twist_limits`".to_owned(),
        other => format!("a {} joint", other.name()),
    };
    SceneError::new(
        error.field,
        format!("required field is missing ({needing} needs it)"),
    )
}

/// A load error as a scene error at its place: a mesh file that cannot be loaded or read is
/// reported where the scene names it.
fn into_scene_error(error: LoadError) -> SceneError {
    match error {
        LoadError::Invalid(error) => error,
        LoadError::Mesh {
            place,
            path,
            message,
        } => SceneError::new(
            place,
            format!("cannot load mesh file {}: {message}", path.display()),
        ),
        LoadError::Read { path, error } => {
            SceneError::new("", format!("cannot read {}: {error}", path.display()))
        }
    }
}

/// Deserialises the file, turning serde errors into a place and a message.
fn parse<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, SceneError> {
    let mut deserializer = serde_json::Deserializer::from_slice(bytes);
    let file = serde_path_to_error::deserialize(&mut deserializer).map_err(|error| {
        out_of_range_number::<T>(bytes, error.inner())
            .unwrap_or_else(|| serde_error(error.path().to_string(), error.inner()))
    })?;
    deserializer
        .end()
        .map_err(|error| serde_error(String::new(), &error))?;
    Ok(file)
}

/// The place of a number too large even for `f64` (`1e999`), which stops serde_json's reader
/// before it knows the field: the file is read again with the number replaced by `[]`, which no
/// numeric field takes, so that this second reading fails at the number with its path.
fn out_of_range_number<T: DeserializeOwned>(
    bytes: &[u8],
    error: &serde_json::Error,
) -> Option<SceneError> {
    if !error.to_string().starts_with("number out of range") {
        return None;
    }
    let token = number_token_at(bytes, byte_offset(bytes, error.line(), error.column())?)?;
    let mut patched = Vec::with_capacity(bytes.len());
    patched.extend_from_slice(&bytes[..token.start]);
    patched.extend_from_slice(b"[]");
    patched.extend_from_slice(&bytes[token.end..]);
    let mut deserializer = serde_json::Deserializer::from_slice(&patched);
    let retry = serde_path_to_error::deserialize::<_, T>(&mut deserializer);
    let error = retry.err()?;
    let at = byte_offset(&patched, error.inner().line(), error.inner().column())?;
    if !(token.start..=token.start + 1).contains(&at) {
        return None;
    }
    let text = String::from_utf8_lossy(&bytes[token]);
    Some(SceneError::new(
        error.path().to_string(),
        format!("got {text}, a number beyond the floating-point range"),
    ))
}

/// The byte offset where serde_json's reader stood: `line` is 1-based, `column` counts the bytes
/// it had read of that line.
fn byte_offset(bytes: &[u8], line: usize, column: usize) -> Option<usize> {
    let line_start = if line <= 1 {
        0
    } else {
        bytes
            .iter()
            .enumerate()
            .filter(|&(_, &byte)| byte == b'\n')
            .nth(line - 2)?
            .0
            + 1
    };
    Some((line_start + column).min(bytes.len()))
}

/// The span of the JSON number that ends at or runs through `offset`.
fn number_token_at(bytes: &[u8], offset: usize) -> Option<std::ops::Range<usize>> {
    let in_number = |byte: &u8| byte.is_ascii_digit() || b"+-.eE".contains(byte);
    let offset = offset.min(bytes.len());
    let start = bytes[..offset]
        .iter()
        .rposition(|byte| !in_number(byte))
        .map_or(0, |index| index + 1);
    let end = offset
        + bytes[offset..]
            .iter()
            .position(|byte| !in_number(byte))
            .unwrap_or(bytes.len() - offset);
    (start < end).then_some(start..end)
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
