//! `rebond bench`: times the steps of a scene and reports their spread.

use std::fmt;
use std::time::{Duration, Instant};

use rebond::{BodyType, World};

use crate::failure::Failure;
use crate::source::SceneSource;

/// Steps run before timing starts, so caches and allocations settle.
pub const WARM_UP_STEPS: u64 = 30;

/// What `rebond bench` was asked to do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BenchOptions {
    /// Timed steps after the warm-up (≥ 1).
    pub measured_steps: usize,
    /// Whether bodies may fall asleep; `false` turns sleeping off for every body before the
    /// warm-up.
    pub sleep: bool,
}

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
    sleep: bool,
    /// Dynamic bodies awake at the end (only dynamic bodies sleep).
    awake_bodies: usize,
    sleeping_bodies: usize,
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
        writeln!(formatter, "islands          {}", self.islands)?;
        let sleep = if self.sleep {
            "allowed"
        } else {
            "off (--no-sleep)"
        };
        writeln!(formatter, "sleep            {sleep}")?;
        writeln!(formatter, "awake bodies     {}", self.awake_bodies)?;
        writeln!(formatter, "sleeping bodies  {}", self.sleeping_bodies)?;
        if self.awake_bodies == 0 && self.sleeping_bodies > 0 {
            writeln!(
                formatter,
                "note             every dynamic body is asleep at the end: these timings are of a \
                 sleeping scene (--no-sleep keeps the bodies awake)"
            )?;
        }
        Ok(())
    }
}

/// Loads the scene, turns sleeping off if asked, runs [`WARM_UP_STEPS`], then times each of the
/// measured steps.
pub fn bench(source: &SceneSource, options: BenchOptions) -> Result<BenchReport, Failure> {
    let scene = source.load()?;
    // The scene lends its world only for reading, so the bench steps a copy, by the timestep
    // `Scene::step` uses.
    let mut world = scene.world().clone();
    let seconds = scene.timestep().engine_seconds;
    if !options.sleep {
        turn_sleep_off(&mut world);
    }
    let mut step_world = |step| {
        world.step(seconds).map_err(|error| Failure::Step {
            source: source.label(),
            step,
            error,
        })
    };
    for step in 1..=WARM_UP_STEPS {
        step_world(step)?;
    }
    let mut timings = Vec::new();
    for step in (WARM_UP_STEPS + 1..).take(options.measured_steps) {
        let started = Instant::now();
        step_world(step)?;
        timings.push(started.elapsed());
    }
    timings.sort_unstable();
    let awake_bodies = world
        .bodies()
        .filter(|(_, body)| body.body_type() == BodyType::Dynamic && !body.is_sleeping())
        .count();
    Ok(BenchReport {
        scene: source.label(),
        measured_steps: options.measured_steps,
        median: quantile(&timings, 0.5),
        min: quantile(&timings, 0.0),
        max: quantile(&timings, 1.0),
        first_quartile: quantile(&timings, 0.25),
        third_quartile: quantile(&timings, 0.75),
        bodies: world.body_count(),
        contacts: world.contact_count(),
        islands: world.island_count(),
        sleep: options.sleep,
        awake_bodies,
        sleeping_bodies: world.sleeping_body_count(),
    })
}

/// Keeps every body of `world` awake from now on.
fn turn_sleep_off(world: &mut World) {
    let handles: Vec<_> = world.bodies().map(|(handle, _)| handle).collect();
    for handle in handles {
        if let Ok(body) = world.body_mut(handle) {
            body.set_can_sleep(false);
        }
    }
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
