//! `rebond run`: steps a scene headless, optionally recording it, and summarises the run.

use std::fmt;
use std::fs;
use std::io::{self, IsTerminal};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};

use crate::failure::Failure;
use crate::record::{is_recorded, Recorder};
use crate::source::SceneSource;

/// How long to run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RunLength {
    /// This many steps.
    Steps(u64),
    /// This much simulated time, seconds.
    Seconds(f64),
}

impl RunLength {
    /// The number of steps: `Seconds(t)` gives `t / timestep` rounded up, at least one. A
    /// quotient within a billionth of a whole number counts as that number, so that 10 s at
    /// 1/60 s is 600 steps despite rounding.
    pub fn steps(self, timestep: f64) -> u64 {
        match self {
            Self::Steps(steps) => steps,
            Self::Seconds(seconds) => {
                let quotient = seconds / timestep;
                let nearest = quotient.round();
                let steps = if (quotient - nearest).abs() <= 1e-9 * nearest.max(1.0) {
                    nearest
                } else {
                    quotient.ceil()
                };
                (steps as u64).max(1)
            }
        }
    }
}

/// What `rebond run` was asked to do.
#[derive(Debug, Clone)]
pub struct RunOptions {
    /// How long to run.
    pub length: RunLength,
    /// Where to write the record, if anywhere.
    pub record: Option<PathBuf>,
    /// Record every this many steps (≥ 1).
    pub every: u64,
}

/// What a run did, printed on stdout.
#[derive(Debug, Clone)]
pub struct RunSummary {
    scene: String,
    steps: u64,
    simulated_seconds: f64,
    bodies: usize,
    contacts: usize,
    islands: usize,
    sleeping_bodies: usize,
    mean_step: Duration,
    energy_start: f32,
    energy_end: f32,
}

impl fmt::Display for RunSummary {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(formatter, "scene            {}", self.scene)?;
        writeln!(formatter, "steps            {}", self.steps)?;
        writeln!(formatter, "simulated time   {} s", self.simulated_seconds)?;
        writeln!(formatter, "bodies           {}", self.bodies)?;
        writeln!(formatter, "contacts         {}", self.contacts)?;
        writeln!(formatter, "islands          {}", self.islands)?;
        writeln!(formatter, "sleeping bodies  {}", self.sleeping_bodies)?;
        writeln!(
            formatter,
            "ms per step      {:.4} (mean wall clock)",
            self.mean_step.as_secs_f64() * 1000.0
        )?;
        writeln!(formatter, "energy at start  {} J", self.energy_start)?;
        writeln!(formatter, "energy at end    {} J", self.energy_end)
    }
}

/// Loads the scene, starts the record once the scene is valid, runs, and summarises. A record
/// that would overwrite the scene file is refused before anything runs.
pub fn run(source: &SceneSource, options: &RunOptions) -> Result<RunSummary, Failure> {
    if let (SceneSource::File(scene_path), Some(record)) = (source, &options.record) {
        if same_file(scene_path, record) {
            return Err(Failure::RecordIsScene {
                path: record.clone(),
            });
        }
    }
    let mut scene = source.load()?;
    let timestep = scene.timestep().seconds;
    let steps = options.length.steps(timestep);
    let mut recorder = options
        .record
        .as_deref()
        .map(Recorder::create)
        .transpose()?;
    if let Some(recorder) = recorder.as_mut() {
        recorder.write_step(0, &scene)?;
    }
    let progress = io::stderr().is_terminal().then(|| progress_bar(steps));
    let energy_start = scene.world().total_energy();
    let mut stepping = Duration::ZERO;
    for step in 1..=steps {
        let started = Instant::now();
        scene.step().map_err(|error| Failure::Step {
            source: source.label(),
            step,
            error,
        })?;
        stepping += started.elapsed();
        if let Some(recorder) = recorder.as_mut() {
            if is_recorded(step, options.every, steps) {
                recorder.write_step(step, &scene)?;
            }
        }
        if let Some(progress) = &progress {
            progress.inc(1);
        }
    }
    if let Some(progress) = progress {
        progress.finish_and_clear();
    }
    if let Some(recorder) = recorder {
        recorder.finish()?;
    }
    let world = scene.world();
    Ok(RunSummary {
        scene: source.label(),
        steps,
        simulated_seconds: steps as f64 * timestep,
        bodies: world.body_count(),
        contacts: world.contact_count(),
        islands: world.island_count(),
        sleeping_bodies: world.sleeping_body_count(),
        mean_step: stepping.div_f64(steps as f64),
        energy_start,
        energy_end: world.total_energy(),
    })
}

/// Whether `a` and `b` name the same existing file, however spelt.
fn same_file(a: &Path, b: &Path) -> bool {
    match (fs::canonicalize(a), fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

/// A progress bar on stderr counting steps.
fn progress_bar(steps: u64) -> ProgressBar {
    let style =
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} steps, eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> ");
    ProgressBar::new(steps).with_style(style)
}
