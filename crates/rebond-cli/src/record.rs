//! Records: the state of every body, one JSON line per recorded step.

use std::fs::File;
use std::io::{BufWriter, Write};
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

/// Writes record lines to a file through a buffer.
#[derive(Debug)]
pub struct Recorder {
    path: PathBuf,
    writer: BufWriter<File>,
}

impl Recorder {
    /// Creates (or truncates) the record file.
    pub fn create(path: &Path) -> Result<Self, Failure> {
        let file = File::create(path)
            .map_err(|error| Failure::io(path, "cannot create record file", error))?;
        Ok(Self {
            path: path.to_owned(),
            writer: BufWriter::new(file),
        })
    }

    /// Appends the state of every body after `step` steps, in scene order.
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
        let line = RecordLine {
            step,
            time: step as f64 * scene.timestep().seconds,
            bodies,
        };
        serde_json::to_writer(&mut self.writer, &line)
            .map_err(std::io::Error::from)
            .and_then(|()| self.writer.write_all(b"\n"))
            .map_err(|error| Failure::io(&self.path, "cannot write record", error))
    }

    /// Flushes the buffer to the file.
    pub fn finish(mut self) -> Result<(), Failure> {
        self.writer
            .flush()
            .map_err(|error| Failure::io(&self.path, "cannot write record", error))
    }
}

/// Whether the state after `step` of `last_step` goes into the record: step 0, every `every`-th
/// step, and the last step.
pub fn is_recorded(step: u64, every: u64, last_step: u64) -> bool {
    step % every == 0 || step == last_step
}
