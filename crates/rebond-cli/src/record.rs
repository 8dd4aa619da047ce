//! Records: the state of every body, and of every joint when the scene has some, one JSON line
//! per recorded step.

use std::ffi::OsString;
use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::failure::Failure;
use rebond::scene::Scene;

/// One line of a record.
#[derive(Debug, Serialize)]
struct RecordLine<'a> {
    step: u64,
    time: f64,
    bodies: Vec<BodyState<'a>>,
    /// Left out of the line when the scene has no joints, so that such records read as before
    /// joints existed.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    joints: Vec<JointState<'a>>,
}

/// The state of one body in a record line.
#[derive(Debug, Serialize)]
struct BodyState<'a> {
    name: &'a str,
    position: [f32; 3],
    rotation: [f32; 4],
    linear_velocity: [f32; 3],
    angular_velocity: [f32; 3],
    sleeping: bool,
}

/// What one joint did over the last step, in a record line, and where it stands.
#[derive(Debug, Serialize)]
struct JointState<'a> {
    name: &'a str,
    force: [f32; 3],
    torque: [f32; 3],
    broken: bool,
    /// Revolute, prismatic and distance joints (left out for the others): the angle counted
    /// across turns, rad, or the slide or length, m, and its rate, rad/s or m/s; a broken joint
    /// is measured the same way ([`rebond::World::joint_position`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    position: Option<f32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    velocity: Option<f32>,
}

/// Writes record lines through a buffer to a hidden file beside the record's path, renamed to
/// that path when the run ends well: a run that fails or is killed never leaves a partial record
/// under the name the user gave (one that fails removes its hidden file too).
#[derive(Debug)]
pub struct Recorder {
    path: PathBuf,
    partial: PathBuf,
    writer: BufWriter<File>,
}

impl Recorder {
    /// Starts a record to be written to `path` (an existing file there is replaced at the end).
    pub fn create(path: &Path) -> Result<Self, Failure> {
        let cannot_create = |error| Failure::io(path, "cannot create record file", error);
        let partial = partial_path(path).map_err(cannot_create)?;
        let file = File::create(&partial).map_err(cannot_create)?;
        Ok(Self {
            path: path.to_owned(),
            partial,
            writer: BufWriter::new(file),
        })
    }

    /// Appends the state of every body after `step` steps, and what every joint did in that step,
    /// in scene order.
    ///
    /// Floats are written by serde_json's shortest round-trip formatting of the engine's `f32`
    /// values; `time` is `step × timestep` in double precision. The output is byte-for-byte
    /// deterministic for a given scene and step.
    pub fn write_step(&mut self, step: u64, scene: &Scene) -> Result<(), Failure> {
        let bodies = scene
            .bodies()
            .map(|(name, body)| BodyState {
                name,
                position: body.position().to_array(),
                rotation: body.rotation().to_array(),
                linear_velocity: body.linear_velocity().to_array(),
                angular_velocity: body.angular_velocity().to_array(),
                sleeping: body.is_sleeping(),
            })
            .collect();
        let world = scene.world();
        let joints = scene
            .joint_handles()
            .filter_map(|(name, handle)| {
                let joint = world.joint(handle).ok()?;
                Some(JointState {
                    name,
                    force: joint.force().to_array(),
                    torque: joint.torque().to_array(),
                    broken: joint.is_broken(),
                    position: world.joint_position(handle).ok(),
                    velocity: world.joint_velocity(handle).ok(),
                })
            })
            .collect();
        let line = RecordLine {
            step,
            time: step as f64 * scene.timestep().seconds,
            bodies,
            joints,
        };
        serde_json::to_writer(&mut self.writer, &line)
            .map_err(std::io::Error::from)
            .and_then(|()| self.writer.write_all(b"\n"))
            .map_err(|error| Failure::io(&self.path, "cannot write record", error))
    }

    /// Flushes the buffer and gives the record its name.
    pub fn finish(mut self) -> Result<(), Failure> {
        self.writer
            .flush()
            .and_then(|()| fs::rename(&self.partial, &self.path))
            .map_err(|error| Failure::io(&self.path, "cannot write record", error))
    }
}

impl Drop for Recorder {
    /// Removes the hidden file of a record that did not finish (after [`Recorder::finish`] it
    /// has been renamed, and there is nothing to remove).
    fn drop(&mut self) {
        let _ = fs::remove_file(&self.partial);
    }
}

/// The hidden file beside `path` that an output is written to before it takes `path`'s name.
fn partial_path(path: &Path) -> io::Result<PathBuf> {
    if path.is_dir() {
        return Err(io::Error::from(io::ErrorKind::IsADirectory));
    }
    let Some(name) = path.file_name() else {
        return Err(io::Error::from(io::ErrorKind::InvalidInput));
    };
    let mut partial_name = OsString::from(".");
    partial_name.push(name);
    partial_name.push(format!(".partial-{}", std::process::id()));
    Ok(path.with_file_name(partial_name))
}

/// Writes `bytes` to `path` whole or not at all: to a hidden file beside it, renamed to `path`
/// once written (a failed write removes the hidden file). `action` names the failure.
pub fn write_whole(path: &Path, bytes: &[u8], action: &'static str) -> Result<(), Failure> {
    let partial = partial_path(path).map_err(|error| Failure::io(path, action, error))?;
    fs::write(&partial, bytes)
        .and_then(|()| fs::rename(&partial, path))
        .map_err(|error| {
            let _ = fs::remove_file(&partial);
            Failure::io(path, action, error)
        })
}

/// Whether the state after `step` of `last_step` goes into the record: step 0, every `every`-th
/// step, and the last step.
pub fn is_recorded(step: u64, every: u64, last_step: u64) -> bool {
    step % every == 0 || step == last_step
}
