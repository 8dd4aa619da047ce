//! `rebond soak`: a long run that reports, every K steps, what must stay bounded over millions
//! of steps: the energy, the process's memory and the time a step takes.

use std::io::Write;
use std::path::Path;
use std::time::Instant;

use crate::failure::Failure;
use crate::source::SceneSource;

/// What `rebond soak` was asked to do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SoakOptions {
    /// Steps to run (≥ 1).
    pub steps: u64,
    /// Report every this many steps (≥ 1).
    pub every: u64,
}

/// The report's header line.
const HEADER: &str = "step,seconds,energy_j,resident_kib,ms_per_step,awake_bodies,contacts";

/// Runs the scene for `options.steps` steps, writing to `out` a CSV header, a line for step 0
/// and one every `options.every` steps (and for the last): the step, the simulated time, the
/// total energy, the resident memory of the process (empty where the system does not say), the
/// mean wall-clock time of the steps since the last line, the dynamic bodies awake and the
/// contacts.
pub fn soak(
    source: &SceneSource,
    options: SoakOptions,
    out: &mut impl Write,
) -> Result<(), Failure> {
    let scene = source.load()?;
    let mut world = scene.world().clone();
    let seconds = scene.timestep().engine_seconds;
    let write_failed =
        |error: std::io::Error| Failure::io(Path::new("standard output"), "cannot write", error);
    writeln!(out, "{HEADER}").map_err(write_failed)?;
    let mut report = |step: u64, world: &rebond::World, ms_per_step: f64| {
        let resident = resident_kib()
            .map(|kib| kib.to_string())
            .unwrap_or_default();
        let awake = world.body_count() - world.sleeping_body_count();
        writeln!(
            out,
            "{step},{:.3},{:.3},{resident},{ms_per_step:.4},{awake},{}",
            step as f64 * f64::from(seconds),
            world.total_energy(),
            world.contact_count()
        )
        .and_then(|()| out.flush())
        .map_err(write_failed)
    };
    report(0, &world, 0.0)?;
    let mut since = (0, Instant::now());
    for step in 1..=options.steps {
        world.step(seconds).map_err(|error| Failure::Step {
            source: source.label(),
            step,
            error,
        })?;
        if step % options.every == 0 || step == options.steps {
            let ms = since.1.elapsed().as_secs_f64() * 1000.0 / (step - since.0) as f64;
            report(step, &world, ms)?;
            since = (step, Instant::now());
        }
    }
    Ok(())
}

/// The resident memory of this process, KiB, from `/proc/self/status` (Linux).
fn resident_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|line| line.starts_with("VmRSS:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}
