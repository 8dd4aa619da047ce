//! `rebond bench`: times the steps of a scene and reports their spread.

use std::fmt;
use std::time::{Duration, Instant};

use crate::failure::Failure;
use crate::source::SceneSource;

/// Steps run before timing starts, so caches and allocations settle.
pub const WARM_UP_STEPS: u64 = 30;

/// Per-step timings and the scene's counts at the end.
#[derive(Debug, Clone)]
pub struct BenchReport {
    scene: String,
    measured_steps: usize,
    median: Duration,
    min: Duration,
    max: Duration,
    first_quartile: Duration,
    third_quartile: Duration,
    bodies: usize,
    contacts: usize,
    islands: usize,
}

impl fmt::Display for BenchReport {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        let ms = |duration: Duration| duration.as_secs_f64() * 1000.0;
        writeln!(formatter, "scene            {}", self.scene)?;
        writeln!(formatter, "warm-up steps    {WARM_UP_STEPS}")?;
        writeln!(formatter, "measured steps   {}", self.measured_steps)?;
        writeln!(formatter, "median           {:.4} ms/step", ms(self.median))?;
        writeln!(formatter, "min              {:.4} ms/step", ms(self.min))?;
        writeln!(formatter, "max              {:.4} ms/step", ms(self.max))?;
        writeln!(
            formatter,
            "interquartile    {:.4} ms (q1 {:.4}, q3 {:.4})",
            ms(self.third_quartile) - ms(self.first_quartile),
            ms(self.first_quartile),
            ms(self.third_quartile)
        )?;
        writeln!(formatter, "bodies           {}", self.bodies)?;
        writeln!(formatter, "contacts         {}", self.contacts)?;
        writeln!(formatter, "islands          {}", self.islands)
    }
}

/// Loads the scene, runs [`WARM_UP_STEPS`], then times each of `measured_steps` (≥ 1) steps.
pub fn bench(source: &SceneSource, measured_steps: usize) -> Result<BenchReport, Failure> {
    let mut scene = source.load()?;
    let step_failure = |step, error| Failure::Step {
        source: source.label(),
        step,
        error,
    };
    for step in 1..=WARM_UP_STEPS {
        scene.step().map_err(|error| step_failure(step, error))?;
    }
    let mut timings = Vec::new();
    for step in (WARM_UP_STEPS + 1..).take(measured_steps) {
        let started = Instant::now();
        scene.step().map_err(|error| step_failure(step, error))?;
        timings.push(started.elapsed());
    }
    timings.sort_unstable();
    let world = scene.world();
    Ok(BenchReport {
        scene: source.label(),
        measured_steps,
        median: quantile(&timings, 0.5),
        min: quantile(&timings, 0.0),
        max: quantile(&timings, 1.0),
        first_quartile: quantile(&timings, 0.25),
        third_quartile: quantile(&timings, 0.75),
        bodies: world.body_count(),
        contacts: world.contact_count(),
        islands: world.island_count(),
    })
}

/// The `fraction` quantile of sorted durations, interpolating linearly between neighbours;
/// zero when there are none.
fn quantile(sorted: &[Duration], fraction: f64) -> Duration {
    let Some(last) = sorted.len().checked_sub(1) else {
        return Duration::ZERO;
    };
    let position = fraction * last as f64;
    let lower = position.floor() as usize;
    let upper = position.ceil() as usize;
    let weight = position - lower as f64;
    sorted[lower].mul_f64(1.0 - weight) + sorted[upper].mul_f64(weight)
}
