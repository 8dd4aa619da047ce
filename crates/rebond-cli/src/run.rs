//! `rebond run` and `rebond resume`: step a scene headless (from its start, or from a saved
//! state), optionally recording it and saving its state at the end, and summarise the run.

use std::fmt;
use std::fs;
use std::io::{self, IsTerminal};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};

use crate::failure::Failure;
use crate::record::{is_recorded, write_whole, Recorder};
use crate::source::SceneSource;
use rebond::scene::Scene;

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
    /// Where to save the scene's state after the last step, if anywhere.
    pub save_state: Option<PathBuf>,
}

impl RunOptions {
    /// Refuses outputs that name `input` (the scene file, or the state resumed from), which
    /// writing them would overwrite.
    fn refuse_overwriting(&self, input: &Path, what: &'static str) -> Result<(), Failure> {
        let outputs = [
            ("--record", &self.record),
            ("--save-state", &self.save_state),
        ];
        for (option, output) in outputs {
            if let Some(output) = output.as_deref().filter(|output| same_file(input, output)) {
                return Err(Failure::OverwritesInput {
                    option,
                    input: what,
                    path: output.to_owned(),
                });
            }
        }
        Ok(())
    }
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

/// Loads the scene, starts the record once the scene is valid, runs, saves the state if asked,
/// and summarises. Outputs that would overwrite the scene file are refused before anything runs.
pub fn run(source: &SceneSource, options: &RunOptions) -> Result<RunSummary, Failure> {
    if let SceneSource::File(scene_path) = source {
        options.refuse_overwriting(scene_path, "scene file")?;
    }
    let scene = source.load()?;
    drive(source.label(), scene, 0, options)
}

/// Restores the scene saved in `state` (by `--save-state`) and goes on from its step: record
/// lines carry on the step numbers and times, byte for byte as an uninterrupted run writes
/// them. Outputs that would overwrite the state file are refused before anything runs.
pub fn resume(state: &Path, options: &RunOptions) -> Result<RunSummary, Failure> {
    options.refuse_overwriting(state, "state file")?;
    let bytes = fs::read(state).map_err(|error| Failure::io(state, "cannot read state", error))?;
    let (scene, step) = Scene::load_state(&bytes).map_err(|error| Failure::InvalidState {
        path: state.to_owned(),
        error,
    })?;
    drive(state.display().to_string(), scene, step, options)
}

/// Steps `scene` from step `first` for the options' length, recording and saving as asked.
fn drive(
    label: String,
    mut scene: Scene,
    first: u64,
    options: &RunOptions,
) -> Result<RunSummary, Failure> {
    let timestep = scene.timestep().seconds;
    let steps = options.length.steps(timestep);
    let last = first.saturating_add(steps);
    let mut recorder = options
        .record
        .as_deref()
        .map(Recorder::create)
        .transpose()?;
    if let Some(recorder) = recorder.as_mut() {
        recorder.write_step(first, &scene)?;
    }
    let progress = io::stderr().is_terminal().then(|| progress_bar(steps));
    let energy_start = scene.world().total_energy();
    let mut stepping = Duration::ZERO;
    for step in first + 1..=last {
        let started = Instant::now();
        scene.step().map_err(|error| Failure::Step {
            source: label.clone(),
            step,
            error,
        })?;
        stepping += started.elapsed();
        if let Some(recorder) = recorder.as_mut() {
            if is_recorded(step, options.every, last) {
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
    if let Some(path) = &options.save_state {
        write_whole(path, &scene.save_state(last), "cannot write state")?;
    }
    let world = scene.world();
    Ok(RunSummary {
        scene: label,
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
