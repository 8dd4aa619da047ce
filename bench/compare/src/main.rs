//! Side-by-side benchmark of rebond against rapier3d (issue 7).
//!
//! Run with no arguments, the binary is the driver: for each scene it starts itself once per
//! engine and round (`compare --engine E --scene S --steps N`), alternating which engine goes
//! first from one round to the next, and collects each child's `RESULT` line: median step time,
//! peak memory (VmHWM of the child) and stability figures. It prints a table, then one line per
//! scene in the form `SCENE ratio=R rebond_ms=A rapier_ms=B rebond_mb=C rapier_mb=D`, followed
//! by each engine's `*_drift_m` and `*_sink_m` for the stacks, by `rebond_gap_m=G rapier_gap_m=H`
//! (the largest joint gap over the run) for scenes with joints, and by each engine's
//! `*_surface_depth_m`, `*_end_surface_depth_m` and `*_moving` for the piles.
//!
//! The stacks' figures: *drift*, the largest distance of any dynamic body from its start position
//! after any step; *sink*, the largest drop below its start height after any step of the top body
//! (`column`, `column40`) or of any body (the pyramids) ([`scenes::Sink`]).
//!
//! `COMPARE_REBOND_SUBSTEPS=N` runs rebond at N substeps instead of [`SUBSTEPS`] (rapier keeps
//! [`SUBSTEPS`]); the `RESULT` line gives each engine's `substeps`.
//!
//! Every scene is described once, engine-neutrally ([`scenes::Scene`]), and built from that
//! description in each engine, so shapes, sizes, masses, poses and materials are the same by
//! construction; so are the joints (anchors, axes, limits) of `ragdolls` and `bridge`.
//!
//! `compare --rays` is the scene-query comparison instead: 10,000 static boxes and 10,000 rays,
//! the same in both engines, cast through each engine's query API in one process, alternating
//! engines from one round to the next ([`run_rays`]).
//!
//! `terrain_pile` and `mesh_pile` pour mixed shapes on a heightfield and on a triangle mesh; for
//! them the child also reports how far any body went below the ground's surface and how many
//! bodies still move at the end ([`surface`]).
//!
//! Modules: [`scenes`] (the descriptions and their jitter), [`rebond_engine`] and
//! [`rapier_engine`] (building and stepping each engine, its stability figures), [`surface`]
//! (depth below the ground of the pile scenes), [`rays`] (the `--rays` mode), [`measure`] (CPU
//! clock, peak memory, medians, run order); this file holds the arguments, the child run, the
//! driver and its report.

mod measure;
mod rapier_engine;
mod rays;
mod rebond_engine;
mod scenes;
mod surface;

use std::process::Command;
use std::time::Instant;

use measure::{alternate, median, ms, peak_memory_mib, thread_cpu_ms};
use rapier_engine::RapierEngine;
use rays::{run_rays, RAY_ROUNDS};
use rebond_engine::RebondEngine;
use scenes::{build_scene, rebond_substeps, Sink, FRICTION, RESTITUTION, SUBSTEPS};
use surface::Surface;

/// Steps at the start of each run left out of the timing (still simulated and checked).
const WARMUP_STEPS: usize = 10;

/// The scenes, with their default step and round counts.
const SCENES: &[(&str, usize, usize)] = &[
    ("pyramid", 600, 5),
    ("rain", 300, 5),
    ("column", 600, 5),
    ("column40", 600, 5),
    ("many_pyramids", 300, 5),
    ("large_pyramid", 300, 5),
    ("mixed", 300, 5),
    ("ragdolls", 600, 5),
    ("bridge", 600, 5),
    ("terrain_pile", 600, 5),
    ("mesh_pile", 600, 5),
];

/// Speed above which a body counts as still moving at the end of a pile scene, m/s.
const MOVING_SPEED: f32 = 0.1;

const ENGINES: [&str; 2] = ["rebond", "rapier"];

// ---------------------------------------------------------------------------------------------
// The two engines behind one interface
// ---------------------------------------------------------------------------------------------

trait Engine {
    fn step(&mut self);
    /// Positions of the dynamic bodies, in scene order.
    fn positions(&self, out: &mut Vec<[f32; 3]>);
    /// Most negative contact separation in the current manifolds (0 when none penetrate).
    fn deepest_penetration(&self) -> f32;
    /// Rotations of the dynamic bodies as quaternions `[x, y, z, w]`, in scene order.
    fn rotations(&self, out: &mut Vec<[f32; 4]>);
    /// Speeds of the dynamic bodies, m/s, in scene order.
    fn speeds(&self, out: &mut Vec<f32>);
    /// Largest speed of a dynamic body, m/s.
    fn max_speed(&self) -> f32 {
        let mut speeds = Vec::new();
        self.speeds(&mut speeds);
        speeds.into_iter().fold(0.0, f32::max)
    }
    fn contact_points(&self) -> usize;
    /// Largest distance between the two anchors of a joint, m: how far the joints have come
    /// apart (0 without joints).
    fn max_joint_gap(&self) -> f32;
    /// Most negative separation of the current manifold points re-evaluated at the current
    /// poses, for engines whose reported separations may be stale (rapier); `None` otherwise.
    fn deepest_reevaluated(&self) -> Option<f32> {
        None
    }
}

// ---------------------------------------------------------------------------------------------
// Child: one engine, one scene, one run
// ---------------------------------------------------------------------------------------------

fn run_child(engine_name: &str, scene_name: &str, steps: usize) {
    let scene = build_scene(scene_name);
    let body_count = scene.bodies.iter().filter(|b| !b.fixed).count();
    let build_start = Instant::now();
    let mut engine: Box<dyn Engine> = match engine_name {
        "rebond" => Box::new(RebondEngine::new(&scene)),
        "rapier" => Box::new(RapierEngine::new(&scene)),
        other => panic!("unknown engine {other:?}"),
    };
    let build_ms = build_start.elapsed().as_secs_f64() * 1e3;

    let surface = Surface::of(&scene);
    let mut start = Vec::new();
    engine.positions(&mut start);
    let mut rotations = Vec::new();
    let mut surface_depth = 0.0f32;
    let mut current = Vec::with_capacity(start.len());
    let mut times = Vec::with_capacity(steps);
    let mut wall_times = Vec::with_capacity(steps);
    let mut max_drift = 0.0f32;
    let mut max_sink = 0.0f32;
    let mut deepest = 0.0f32;
    let mut deepest_reeval = 0.0f32;
    let mut max_gap = 0.0f32;
    let mut non_finite = false;
    let is_rapier = engine_name == "rapier";
    // COMPARE_TRACE=K prints the running figures every K steps on stderr.
    let trace: usize = std::env::var("COMPARE_TRACE")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0);

    for step in 0..steps {
        let (wall0, cpu0) = (Instant::now(), thread_cpu_ms());
        engine.step();
        let elapsed = thread_cpu_ms() - cpu0;
        let wall = wall0.elapsed().as_secs_f64() * 1e3;
        if step >= WARMUP_STEPS {
            times.push(elapsed);
            wall_times.push(wall);
        }
        // Checks, outside the timed region.
        deepest = deepest.min(engine.deepest_penetration());
        if let Some(depth) = engine.deepest_reevaluated() {
            deepest_reeval = deepest_reeval.min(depth);
        }
        max_gap = max_gap.max(engine.max_joint_gap());
        engine.positions(&mut current);
        for (now, then) in current.iter().zip(&start) {
            if !now.iter().all(|c| c.is_finite()) {
                non_finite = true;
                continue;
            }
            let d = ((now[0] - then[0]).powi(2)
                + (now[1] - then[1]).powi(2)
                + (now[2] - then[2]).powi(2))
            .sqrt();
            max_drift = max_drift.max(d);
        }
        max_sink = max_sink.max(scene.sink.drop(&start, &current));
        if let Some(surface) = &surface {
            engine.rotations(&mut rotations);
            surface_depth = surface_depth.max(surface.deepest(&current, &rotations));
        }
        if trace > 0 && (step + 1) % trace == 0 {
            let top = current.iter().map(|p| p[1]).fold(f32::MIN, f32::max);
            eprintln!(
                "step {:>5}  {elapsed:>8.3} ms  drift {max_drift:.4} m  sink {max_sink:.4} m  \
                 deepest {:.4} m  highest {top:.3} m  max speed {:.3} m/s  contacts {}  joint gap {:.4} m",
                step + 1,
                -deepest,
                engine.max_speed(),
                engine.contact_points(),
                engine.max_joint_gap()
            );
        }
    }
    let total_ms: f64 = times.iter().sum();
    let mean_ms = total_ms / times.len().max(1) as f64;
    let mut sorted = times.clone();
    let median_ms = median(&mut sorted);
    let p90_ms = sorted
        .get(((sorted.len() as f64) * 0.9) as usize)
        .copied()
        .unwrap_or(f64::NAN);
    let max_ms = sorted.last().copied().unwrap_or(f64::NAN);
    let wall_median_ms = median(&mut wall_times);
    // Bodies that left the scene: below the ground top by more than a box, or far out; on a
    // heightfield or a mesh, off it or with their centre below its surface.
    engine.positions(&mut current);
    let escaped = match &surface {
        Some(surface) => surface.escaped(&current),
        None => current
            .iter()
            .filter(|p| {
                !p.iter().all(|c| c.is_finite())
                    || p[1] < -1.0
                    || p[0].abs() > 80.0
                    || p[2].abs() > 80.0
            })
            .count(),
    };
    let mut speeds = Vec::new();
    engine.speeds(&mut speeds);
    let moving = speeds.iter().filter(|&&speed| speed > MOVING_SPEED).count();
    let end_surface_depth = surface
        .as_ref()
        .map(|surface| surface.deepest(&current, &rotations));
    let max_height = current.iter().map(|p| p[1]).fold(f32::MIN, f32::max);
    let sag = scene.sag_body.map(|i| start[i][1] - current[i][1]);
    let end_speed = engine.max_speed();
    let contacts = engine.contact_points();
    let mb = peak_memory_mib();
    let substeps = if is_rapier {
        SUBSTEPS
    } else {
        rebond_substeps()
    };
    println!(
        "RESULT engine={engine_name} scene={scene_name} bodies={body_count} steps={steps} substeps={substeps} \
         median_ms={median_ms:.4} wall_median_ms={wall_median_ms:.4} mean_ms={mean_ms:.4} p90_ms={p90_ms:.4} max_ms={max_ms:.4} \
         build_ms={build_ms:.1} mb={mb:.1} drift_m={} sink_m={} penetration_m={:.5} reeval_penetration_m={} \
         end_max_speed={end_speed:.3} end_max_height={max_height:.3} escaped={escaped} \
         non_finite={non_finite} contacts={contacts} joints={} joint_gap_m={} sag_m={} \
         surface_depth_m={} end_surface_depth_m={} end_moving={}",
        if scene.is_stack { format!("{max_drift:.5}") } else { "-".to_string() },
        if scene.sink == Sink::None { "-".to_string() } else { format!("{max_sink:.5}") },
        0.0 - deepest,
        if is_rapier { format!("{:.5}", 0.0 - deepest_reeval) } else { "-".to_string() },
        scene.joints.len(),
        if scene.joints.is_empty() { "-".to_string() } else { format!("{max_gap:.5}") },
        sag.map_or("-".to_string(), |sag| format!("{sag:.4}")),
        if surface.is_some() { format!("{surface_depth:.5}") } else { "-".to_string() },
        end_surface_depth.map_or("-".to_string(), |depth| format!("{depth:.5}")),
        if surface.is_some() { moving.to_string() } else { "-".to_string() },
    );
}

// ---------------------------------------------------------------------------------------------
// Driver
// ---------------------------------------------------------------------------------------------

#[derive(Default, Clone)]
struct Run {
    fields: Vec<(String, String)>,
}

impl Run {
    fn parse(line: &str) -> Self {
        let fields = line
            .split_whitespace()
            .skip(1)
            .filter_map(|kv| kv.split_once('='))
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        Self { fields }
    }

    fn get(&self, key: &str) -> &str {
        self.fields
            .iter()
            .find(|(k, _)| k == key)
            .map_or("?", |(_, v)| v.as_str())
    }

    fn num(&self, key: &str) -> f64 {
        self.get(key).parse().unwrap_or(f64::NAN)
    }
}

fn run_driver(only: &[String], rounds_override: Option<usize>, steps_override: Option<usize>) {
    let exe = std::env::current_exe().expect("own path");
    let started = Instant::now();
    let substeps = match rebond_substeps() {
        SUBSTEPS => format!("{SUBSTEPS} substeps"),
        other => format!("{SUBSTEPS} substeps (rebond {other})"),
    };
    println!(
        "rebond vs rapier3d {}: dt = 1/60 s, {substeps}, sleeping off, one thread, \
         friction {FRICTION}, restitution {RESTITUTION}; ms/step = median thread CPU time per step \
         (wall-clock median alongside), first {WARMUP_STEPS} steps not timed",
        rapier3d::VERSION
    );
    let mut summary = Vec::new();
    for &(scene, default_steps, default_rounds) in SCENES {
        if !only.is_empty() && !only.iter().any(|s| s == scene) {
            continue;
        }
        let steps = steps_override.unwrap_or(default_steps);
        let rounds = rounds_override.unwrap_or(default_rounds);
        let mut runs: [Vec<Run>; 2] = [Vec::new(), Vec::new()];
        alternate(rounds, |round, e| {
            let output = Command::new(&exe)
                .args([
                    "--engine",
                    ENGINES[e],
                    "--scene",
                    scene,
                    "--steps",
                    &steps.to_string(),
                ])
                .output()
                .expect("start child");
            let stdout = String::from_utf8_lossy(&output.stdout);
            let Some(line) = stdout.lines().find(|l| l.starts_with("RESULT ")) else {
                eprintln!(
                    "{} on {scene} failed: {}\n{}",
                    ENGINES[e],
                    output.status,
                    String::from_utf8_lossy(&output.stderr)
                );
                std::process::exit(1);
            };
            let run = Run::parse(line);
            eprintln!(
                    "[{:>5.0} s] {scene:<14} round {}/{rounds} {:<6} median {:>9.3} ms cpu {:>9.3} ms wall {:>7.1} MiB",
                    started.elapsed().as_secs_f64(),
                    round + 1,
                    ENGINES[e],
                    run.num("median_ms"),
                    run.num("wall_median_ms"),
                    run.num("mb")
                );
            runs[e].push(run);
        });
        summary.push((scene, steps, rounds, runs));
    }

    let med = |runs: &[Run], key: &str| {
        let mut v: Vec<f64> = runs.iter().map(|r| r.num(key)).collect();
        median(&mut v)
    };
    let spread = |runs: &[Run], key: &str| {
        let v: Vec<f64> = runs.iter().map(|r| r.num(key)).collect();
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        (lo, hi)
    };

    println!();
    println!(
        "| scene | bodies | steps × rounds | rebond ms/step (range) | rapier ms/step (range) | ratio | wall ms rebond / rapier | rebond MiB | rapier MiB |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for (scene, steps, rounds, runs) in &summary {
        let (a, b) = (med(&runs[0], "median_ms"), med(&runs[1], "median_ms"));
        let (alo, ahi) = spread(&runs[0], "median_ms");
        let (blo, bhi) = spread(&runs[1], "median_ms");
        println!(
            "| {scene} | {} | {steps} × {rounds} | {} ({}–{}) | {} ({}–{}) | {:.2} | {} / {} | {:.1} | {:.1} |",
            runs[0][0].get("bodies"),
            ms(a),
            ms(alo),
            ms(ahi),
            ms(b),
            ms(blo),
            ms(bhi),
            a / b,
            ms(med(&runs[0], "wall_median_ms")),
            ms(med(&runs[1], "wall_median_ms")),
            med(&runs[0], "mb"),
            med(&runs[1], "mb"),
        );
    }
    println!();
    println!(
        "| scene | engine | max drift m | max sink m | deepest penetration m | rapier re-evaluated m | below surface, deepest / at end m | end max speed m/s | moving at end | end max height m | escaped | max joint gap m | middle plank sag m | cpu mean / p90 / max ms | build ms | contact points at end |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (scene, _, _, runs) in &summary {
        for (e, engine_runs) in runs.iter().enumerate() {
            // Stability figures come from the first round; every round runs the same scene and
            // both engines are deterministic on one thread (a difference is flagged).
            let r = &engine_runs[0];
            let same = engine_runs.iter().all(|o| {
                o.get("drift_m") == r.get("drift_m")
                    && o.get("sink_m") == r.get("sink_m")
                    && o.get("penetration_m") == r.get("penetration_m")
                    && o.get("joint_gap_m") == r.get("joint_gap_m")
                    && o.get("surface_depth_m") == r.get("surface_depth_m")
            });
            println!(
                "| {scene} | {} | {} | {} | {} | {} | {} / {} | {} | {} | {} | {}{} | {} | {} | {} / {} / {} | {:.0} | {} |",
                ENGINES[e],
                r.get("drift_m"),
                r.get("sink_m"),
                r.get("penetration_m"),
                r.get("reeval_penetration_m"),
                r.get("surface_depth_m"),
                r.get("end_surface_depth_m"),
                r.get("end_max_speed"),
                r.get("end_moving"),
                r.get("end_max_height"),
                r.get("escaped"),
                if r.get("non_finite") == "true" {
                    " (non-finite!)"
                } else {
                    ""
                },
                r.get("joint_gap_m"),
                r.get("sag_m"),
                ms(med(engine_runs, "mean_ms")),
                ms(med(engine_runs, "p90_ms")),
                ms(med(engine_runs, "max_ms")),
                med(engine_runs, "build_ms"),
                r.get("contacts"),
            );
            if !same {
                println!(
                    "|   | {} | (stability figures differ between rounds) | | | | | | | | | | | | | |",
                    ENGINES[e]
                );
            }
        }
    }
    println!();
    println!("total {:.0} s", started.elapsed().as_secs_f64());
    println!();
    for (scene, _, _, runs) in &summary {
        let (a, b) = (med(&runs[0], "median_ms"), med(&runs[1], "median_ms"));
        let stack = match runs[0][0].get("drift_m") {
            "-" => String::new(),
            drift => format!(
                " rebond_drift_m={drift} rapier_drift_m={} rebond_sink_m={} rapier_sink_m={}",
                runs[1][0].get("drift_m"),
                runs[0][0].get("sink_m"),
                runs[1][0].get("sink_m"),
            ),
        };
        let gaps = match runs[0][0].get("joint_gap_m") {
            "-" => String::new(),
            gap => format!(
                " rebond_gap_m={gap} rapier_gap_m={}",
                runs[1][0].get("joint_gap_m")
            ),
        };
        let surface = match runs[0][0].get("surface_depth_m") {
            "-" => String::new(),
            depth => format!(
                " rebond_surface_depth_m={depth} rapier_surface_depth_m={} \
                 rebond_end_surface_depth_m={} rapier_end_surface_depth_m={} rebond_moving={} \
                 rapier_moving={}",
                runs[1][0].get("surface_depth_m"),
                runs[0][0].get("end_surface_depth_m"),
                runs[1][0].get("end_surface_depth_m"),
                runs[0][0].get("end_moving"),
                runs[1][0].get("end_moving"),
            ),
        };
        println!(
            "{scene} ratio={:.3} rebond_ms={a:.3} rapier_ms={b:.3} rebond_mb={:.1} rapier_mb={:.1}{stack}{gaps}{surface}",
            a / b,
            med(&runs[0], "mb"),
            med(&runs[1], "mb"),
        );
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut engine = None;
    let mut scenes = Vec::new();
    let mut steps = None;
    let mut rounds = None;
    let mut rays = false;
    let mut i = 0;
    while i < args.len() {
        let value = args.get(i + 1).cloned();
        match args[i].as_str() {
            "--rays" => {
                rays = true;
                i += 1;
                continue;
            }
            "--engine" => engine = value,
            "--scene" => scenes.extend(value),
            "--steps" => steps = value.and_then(|v| v.parse().ok()),
            "--rounds" => rounds = value.and_then(|v| v.parse().ok()),
            "-h" | "--help" => {
                println!(
                    "compare [--scene S]... [--steps N] [--rounds K]   run the comparison\n\
                     compare --engine rebond|rapier --scene S [--steps N]   one run (child)\n\
                     compare --rays [--rounds K]   10,000 rays against 10,000 boxes in both \
                     engines (default {RAY_ROUNDS} rounds)\n\
                     scenes: {}",
                    SCENES.iter().map(|s| s.0).collect::<Vec<_>>().join(", ")
                );
                return;
            }
            other => {
                eprintln!("unknown argument {other:?} (try --help)");
                std::process::exit(2);
            }
        }
        i += 2;
    }
    if rays {
        run_rays(rounds.unwrap_or(RAY_ROUNDS));
        return;
    }
    match engine {
        Some(engine) => {
            let scene = scenes.first().expect("--scene with --engine");
            let default_steps = SCENES.iter().find(|s| s.0 == scene).map_or(300, |s| s.1);
            run_child(&engine, scene, steps.unwrap_or(default_steps));
        }
        None => run_driver(&scenes, rounds, steps),
    }
}
