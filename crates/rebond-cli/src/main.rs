//! `rebond`: runs, times and lists physics scenes from the command line.
//!
//! Scene files and records follow the contract in `docs/scene-format.md`. Exit status: 0 on
//! success, 1 when a file cannot be read or written, 2 for an invalid scene or bad arguments.

mod bench;
mod failure;
mod record;
mod run;
mod soak;
mod source;
#[cfg(feature = "viewer")]
mod view;

use std::io::{self, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

use crate::bench::BenchOptions;
#[cfg(not(feature = "viewer"))]
use crate::failure::Failure;
use crate::run::{RunLength, RunOptions};
use crate::soak::SoakOptions;
use crate::source::SceneSource;
#[cfg(feature = "viewer")]
use crate::view::{ViewError, ViewOptions};
use rebond::scene::BUILTIN_SCENES;

/// Why a command failed: a [`Failure`](failure::Failure) of the scene or a file, or for `view` a
/// window that cannot be opened.
#[cfg(feature = "viewer")]
type CommandError = ViewError;
/// Why a command failed: the scene or a file, or `view` in a build without the viewer.
#[cfg(not(feature = "viewer"))]
type CommandError = Failure;

/// What `SCENE` means, shared by the subcommands' help.
const SCENE_HELP: &str =
    "Scene file (JSON; a MuJoCo MJCF model when it ends in .xml, see docs/mjcf.md), or the name \
     of a built-in scene (see `rebond scenes`). \
     A path that exists wins over a built-in name: use ./NAME for a file named like a built-in \
     scene";

/// Default simulated time of `rebond run`, seconds.
const DEFAULT_RUN_SECONDS: f64 = 10.0;

/// Default number of measured steps of `rebond bench`.
const DEFAULT_BENCH_STEPS: u32 = 300;

/// rebond: an impulse-based 3D rigid-body physics engine, from the command line.
#[derive(Debug, Parser)]
#[command(name = "rebond", version)]
#[command(
    after_help = "Exit status: 0 on success, 1 when a file cannot be read or written, \
                  2 for an invalid scene (one `error:` line names the file and the place) or \
                  bad arguments."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
enum Command {
    /// Run a scene headless and print a summary; optionally record every body's state as JSON
    /// Lines.
    ///
    /// Runs 10 s of simulated time unless --steps or --seconds says otherwise. The scene is
    /// checked completely before anything runs. The summary on stdout gives the scene, steps,
    /// simulated time, the counts of bodies, contacts, islands and sleeping bodies at the end, the
    /// mean wall-clock time of a step and the total energy at start and end. A progress bar is
    /// drawn on stderr only when stderr is a terminal.
    ///
    /// A record line is {"step", "time", "bodies"}, each body with its name, position, rotation
    /// [x, y, z, w], linear_velocity, angular_velocity and sleeping, every body in scene order.
    /// "time" is step × the scene's timestep in double precision (the engine steps with the
    /// timestep rounded to 32 bits). Floats are the shortest text that reads back as the same
    /// 32-bit value, so two runs of a scene write byte-identical records; a value that is not
    /// finite, should a simulation blow up, is written as null.
    Run(RunArgs),
    /// Go on from a state saved by `run --save-state` (or `resume --save-state`): exactly as if
    /// the run had not stopped.
    ///
    /// Runs 10 s of simulated time unless --steps or --seconds says otherwise. The record starts
    /// with the saved step and carries on its step numbers and times: its lines are byte for byte
    /// those an uninterrupted run writes for the same steps. A file that is not a state, or is
    /// damaged, cut short or of another format version, is one `error:` line (exit status 2).
    Resume(ResumeArgs),
    /// Time the steps of a scene: 30 warm-up steps, then N timed steps (300 by default).
    ///
    /// Prints the median, min, max and interquartile spread of the wall-clock time of a step in
    /// milliseconds, and at the end the counts of bodies, contacts and islands, and of dynamic
    /// bodies awake and asleep. The step skips sleeping bodies: when every dynamic body is asleep
    /// at the end, a note says that the timings are of a sleeping scene, and --no-sleep keeps the
    /// bodies awake.
    Bench(BenchArgs),
    /// Run a scene for a long time (a million steps by default, the built-in `soak` scene
    /// unless SCENE is given) and print, as CSV on stdout, a line every K steps: the step, the
    /// simulated time, the total energy (J), the resident memory of the process (KiB), the mean
    /// wall-clock time of a step since the last line (ms), the dynamic bodies awake and the
    /// contacts. Energy must stay bounded and memory flat; the lines come as the run goes.
    Soak(SoakArgs),
    /// List the built-in scenes, one per line with a description.
    Scenes,
    /// Open a window that simulates a scene live: orbit camera, pause, step, reset, slow motion,
    /// contacts, bounding boxes, sleeping tint, drag bodies, shoot balls (press H for the keys).
    ///
    /// With --screenshot, takes --steps steps (0 by default), saves the 960x540 frame as PNG,
    /// prints the counts and, for each body, its colour and the pixel its centre of mass is drawn
    /// at, and exits. OpenGL and the X11 or Wayland libraries are loaded at run time; on a machine
    /// without a screen, run under `xvfb-run -s "-screen 0 1280x720x24"`.
    ///
    /// The viewer is the cargo feature `viewer`, on by default; a rebond built with
    /// --no-default-features has no viewer and answers `view` with an error (exit status 2).
    // The headless build keeps the command, so that `rebond view` answers why it cannot run
    // rather than calling `view` an unknown subcommand.
    #[cfg_attr(
        not(feature = "viewer"),
        command(
            about = "Not in this build: open a window that simulates a scene live",
            long_about = "Not in this build: open a window that simulates a scene live.\n\n\
                          This rebond was built without the cargo feature `viewer` \
                          (--no-default-features), so `rebond view` only prints an error and \
                          exits with status 2. Install it with the default features to get the \
                          viewer: cargo install --path crates/rebond-cli"
        )
    )]
    View(ViewArgs),
}

/// Arguments of `rebond run`.
#[derive(Debug, Args)]
struct RunArgs {
    #[arg(value_name = "SCENE", help = SCENE_HELP)]
    scene: PathBuf,
    #[command(flatten)]
    output: RunOutputArgs,
}

/// How long `run` and `resume` go on, and what they write.
#[derive(Debug, Args)]
struct RunOutputArgs {
    /// Number of steps to run [default: 10 s of simulated time, see --seconds]
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    steps: Option<u64>,
    /// Simulated time to run, seconds: T / timestep steps, rounded up [default: 10]
    #[arg(long, value_name = "T", conflicts_with = "steps", value_parser = positive_seconds)]
    seconds: Option<f64>,
    /// Write the state of every body to FILE as JSON Lines: step 0, every K-th step and the last
    /// step. The file is created only once the scene is valid
    #[arg(long, value_name = "FILE")]
    record: Option<PathBuf>,
    /// Record every K-th step (K ≥ 1); needs --record
    #[arg(
        long,
        value_name = "K",
        default_value_t = 1,
        requires = "record",
        value_parser = clap::value_parser!(u64).range(1..)
    )]
    every: u64,
    /// After the last step, save the whole scene (every body, joint, contact, warm-start impulse
    /// and sleep timer, and the step reached) to FILE, for `rebond resume`
    #[arg(long, value_name = "FILE")]
    save_state: Option<PathBuf>,
}

/// Arguments of `rebond resume`.
#[derive(Debug, Args)]
struct ResumeArgs {
    /// State file written by --save-state
    #[arg(value_name = "STATE")]
    state: PathBuf,
    #[command(flatten)]
    output: RunOutputArgs,
}

/// Arguments of `rebond bench`.
#[derive(Debug, Args)]
struct BenchArgs {
    #[arg(value_name = "SCENE", help = SCENE_HELP)]
    scene: PathBuf,
    /// Number of timed steps, after 30 warm-up steps
    #[arg(
        long,
        value_name = "N",
        default_value_t = DEFAULT_BENCH_STEPS,
        value_parser = clap::value_parser!(u32).range(1..)
    )]
    steps: u32,
    /// Turn sleeping off for every body before the warm-up, so that still bodies are stepped
    /// and timed like moving ones
    #[arg(long)]
    no_sleep: bool,
}

/// Arguments of `rebond soak`.
#[derive(Debug, Args)]
struct SoakArgs {
    #[arg(value_name = "SCENE", help = SCENE_HELP, default_value = "soak")]
    scene: PathBuf,
    /// Number of steps
    #[arg(
        long,
        value_name = "N",
        default_value_t = 1_000_000,
        value_parser = clap::value_parser!(u64).range(1..)
    )]
    steps: u64,
    /// Print a line every K steps
    #[arg(
        long,
        value_name = "K",
        default_value_t = 10_000,
        value_parser = clap::value_parser!(u64).range(1..)
    )]
    every: u64,
}

/// Arguments of `rebond view`.
#[derive(Debug, Args)]
struct ViewArgs {
    #[arg(value_name = "SCENE", help = SCENE_HELP)]
    scene: PathBuf,
    /// Save the frame as PNG to FILE after --steps steps and exit, instead of staying open
    #[arg(long, value_name = "FILE")]
    screenshot: Option<PathBuf>,
    /// Steps to take before the screenshot; needs --screenshot
    #[arg(
        long,
        value_name = "N",
        default_value_t = 0,
        requires = "screenshot",
        value_parser = clap::value_parser!(u64)
    )]
    steps: u64,
}

impl From<RunOutputArgs> for RunOptions {
    fn from(arguments: RunOutputArgs) -> Self {
        let length = match (arguments.steps, arguments.seconds) {
            (Some(steps), _) => RunLength::Steps(steps),
            (None, Some(seconds)) => RunLength::Seconds(seconds),
            (None, None) => RunLength::Seconds(DEFAULT_RUN_SECONDS),
        };
        Self {
            length,
            record: arguments.record,
            every: arguments.every,
            save_state: arguments.save_state,
        }
    }
}

/// Parses `--seconds`: a finite, positive number.
fn positive_seconds(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(seconds) if seconds.is_finite() && seconds > 0.0 => Ok(seconds),
        Ok(_) => Err("must be a finite, positive number of seconds".to_owned()),
        Err(error) => Err(error.to_string()),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match execute(cli.command) {
        Ok(output) => {
            let mut stdout = io::stdout().lock();
            // A closed stdout (such as `rebond scenes | head -1`) is not an error worth reporting.
            let _ = stdout
                .write_all(output.as_bytes())
                .and_then(|()| stdout.flush());
            ExitCode::SUCCESS
        }
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::from(error.exit_status())
        }
    }
}

/// Runs one subcommand and returns what it prints on stdout.
fn execute(command: Command) -> Result<String, CommandError> {
    match command {
        Command::Run(arguments) => {
            let source = SceneSource::resolve(&arguments.scene)?;
            Ok(run::run(&source, &arguments.output.into())?.to_string())
        }
        Command::Resume(arguments) => {
            Ok(run::resume(&arguments.state, &arguments.output.into())?.to_string())
        }
        Command::Bench(arguments) => {
            let source = SceneSource::resolve(&arguments.scene)?;
            let options = BenchOptions {
                measured_steps: usize::try_from(arguments.steps).unwrap_or(usize::MAX),
                sleep: !arguments.no_sleep,
            };
            Ok(bench::bench(&source, options)?.to_string())
        }
        Command::Soak(arguments) => {
            let source = SceneSource::resolve(&arguments.scene)?;
            let options = SoakOptions {
                steps: arguments.steps,
                every: arguments.every,
            };
            soak::soak(&source, options, &mut io::stdout().lock())?;
            Ok(String::new())
        }
        #[cfg(feature = "viewer")]
        Command::View(arguments) => {
            let source = SceneSource::resolve(&arguments.scene)?;
            let options = ViewOptions {
                screenshot: arguments.screenshot,
                steps: arguments.steps,
            };
            view::view(&source, &options)
        }
        #[cfg(not(feature = "viewer"))]
        Command::View(_) => Err(Failure::NoViewer),
        Command::Scenes => {
            let width = BUILTIN_SCENES
                .iter()
                .map(|scene| scene.name.len())
                .max()
                .unwrap_or(0);
            Ok(BUILTIN_SCENES
                .iter()
                .map(|scene| format!("{:<width$} {}\n", scene.name, scene.description))
                .collect())
        }
    }
}
