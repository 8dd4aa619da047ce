//! `rebond view`: a window that simulates a scene live, testbed style. Every shape is drawn lit
//! and solid, a halfspace as a ground grid; an orbit camera turns, pans and zooms; keys pause,
//! step, reset and slow the simulation and toggle debug drawing; the mouse drags bodies on a
//! spring and shoots balls; W, A, S, D and Space walk and jump the character a scene names.
//! `--screenshot FILE --steps N` saves one frame as PNG and exits.
//!
//! The module splits by concept: [`simulation`] (the stepping world and the user's pokes),
//! [`drag`] (the mouse spring), [`player`] (the scene's character under the keyboard),
//! [`picking`] (ray casts, which the engine lacks), [`camera`], [`controls`] (the key table and
//! help), [`viewer`] (input to actions), [`ground`], [`palette`], [`debug_draw`] with [`joint_draw`], [`overlay`] (text panels), [`render`]
//! (three-d drawing), [`screenshot`] and [`window`] (winit's event loop).

mod camera;
mod controls;
mod debug_draw;
mod drag;
mod ground;
mod joint_draw;
mod overlay;
mod palette;
mod picking;
mod player;
mod render;
mod screenshot;
mod simulation;
mod viewer;
mod window;

use std::fmt;
use std::path::PathBuf;

use crate::failure::{Failure, EXIT_IO};
use crate::source::SceneSource;
use simulation::Simulation;
use window::Mode;

/// What `rebond view` was asked to do.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ViewOptions {
    /// Save the frame to this PNG after `steps` steps and exit, instead of staying open.
    pub screenshot: Option<PathBuf>,
    /// Steps before the screenshot.
    pub steps: u64,
}

/// Why the viewer could not run.
#[derive(Debug)]
pub enum ViewError {
    /// The scene, a step or the screenshot file failed, as for the other commands.
    Failure(Failure),
    /// No window could be opened or drawn into.
    Window(String),
}

impl ViewError {
    /// The process exit status: the failure's own, or 1 when there is no window.
    pub fn exit_status(&self) -> u8 {
        match self {
            Self::Failure(failure) => failure.exit_status(),
            Self::Window(_) => EXIT_IO,
        }
    }
}

impl From<Failure> for ViewError {
    fn from(failure: Failure) -> Self {
        Self::Failure(failure)
    }
}

impl fmt::Display for ViewError {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Failure(failure) => failure.fmt(formatter),
            Self::Window(reason) => write!(formatter, "cannot open the viewer: {reason}"),
        }
    }
}

/// Loads the scene and opens the viewer on it; returns what to print on stdout (the screenshot
/// report, or nothing).
pub fn view(source: &SceneSource, options: &ViewOptions) -> Result<String, ViewError> {
    let scene = source.load()?;
    // The scene checked its character's settings as it loaded; the controller checks them again.
    let simulation = Simulation::new(&scene).map_err(|error| Failure::InvalidScene {
        source: source.label(),
        error: error.within("character").into(),
    })?;
    let mode = match &options.screenshot {
        Some(path) => Mode::Screenshot {
            path: path.clone(),
            steps: options.steps,
        },
        None => Mode::Interactive,
    };
    window::run(simulation, source.label(), mode)
}
