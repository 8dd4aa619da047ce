//! What can make a command fail, and the exit status each failure gives.

use std::fmt;
use std::io;
use std::path::{Path, PathBuf};

use rebond::scene::{LoadError, SceneError};

/// Exit status for a scene that is not valid (the contract's "bad input").
pub const EXIT_INVALID_SCENE: u8 = 2;
/// Exit status for a file that cannot be read or written.
pub const EXIT_IO: u8 = 1;
/// Exit status for bad arguments, which is also clap's for usage errors.
pub const EXIT_USAGE: u8 = 2;

/// A failed command; printed as one `error:` line on stderr.
#[derive(Debug)]
pub enum Failure {
    /// The scene was read but is not valid.
    InvalidScene {
        /// The file path, or the built-in scene's label.
        source: String,
        /// What is wrong, and where.
        error: SceneError,
    },
    /// A file could not be read or written.
    Io {
        /// The file concerned.
        path: PathBuf,
        /// What was being done, such as `cannot read scene`.
        action: &'static str,
        /// Why it failed.
        error: io::Error,
    },
    /// A mesh file the scene names could not be read or is not a valid OBJ file.
    MeshFile {
        /// The file path, or the built-in scene's label.
        source: String,
        /// Where the scene names the file, which file, and why it could not be used.
        error: LoadError,
    },
    /// The scene argument is neither an existing file nor a built-in scene.
    UnknownScene {
        /// The argument as given.
        argument: String,
    },
    /// The engine refused to step a loaded scene.
    Step {
        /// The file path, or the built-in scene's label.
        source: String,
        /// The step that failed, counting from 1.
        step: u64,
        /// The engine's reason.
        error: rebond::Error,
    },
    /// An output option (`--record`, `--save-state`) names the command's input file (the scene,
    /// or the state resumed from), which writing it would overwrite.
    OverwritesInput {
        /// The option, such as `--record`.
        option: &'static str,
        /// What the input is: `scene file` or `state file`.
        input: &'static str,
        /// The file as given.
        path: PathBuf,
    },
    /// A state file was read but is not a whole scene state of this version.
    InvalidState {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        error: rebond::state::StateError,
    },
    /// `rebond view` in a build without the cargo feature `viewer`.
    #[cfg(not(feature = "viewer"))]
    NoViewer,
}

impl Failure {
    /// A failed read or write of `path`.
    pub fn io(path: &Path, action: &'static str, error: io::Error) -> Self {
        Self::Io {
            path: path.to_owned(),
            action,
            error,
        }
    }

    /// The process exit status for this failure.
    pub fn exit_status(&self) -> u8 {
        match self {
            Self::InvalidScene { .. } | Self::InvalidState { .. } => EXIT_INVALID_SCENE,
            Self::Io { .. }
            | Self::MeshFile { .. }
            | Self::UnknownScene { .. }
            | Self::Step { .. } => EXIT_IO,
            Self::OverwritesInput { .. } => EXIT_USAGE,
            #[cfg(not(feature = "viewer"))]
            Self::NoViewer => EXIT_USAGE,
        }
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidScene { source, error } => write!(formatter, "{source}: {error}"),
            Self::Io {
                path,
                action,
                error,
            } => write!(formatter, "{}: {action}: {error}", path.display()),
            Self::MeshFile { source, error } => write!(formatter, "{source}: {error}"),
            Self::UnknownScene { argument } => write!(
                formatter,
                "{argument}: cannot read scene: no such file, and no built-in scene of that name \
                 (`rebond scenes` lists them)"
            ),
            Self::Step {
                source,
                step,
                error,
            } => write!(formatter, "{source}: step {step} failed: {error}"),
            Self::OverwritesInput {
                option,
                input,
                path,
            } => write!(
                formatter,
                "{}: {option} names the {input} itself, which it would overwrite; choose another \
                 file",
                path.display()
            ),
            Self::InvalidState { path, error } => write!(formatter, "{}: {error}", path.display()),
            #[cfg(not(feature = "viewer"))]
            Self::NoViewer => write!(
                formatter,
                "this rebond was built without the viewer (cargo feature `viewer`); reinstall it \
                 with the default features for `rebond view`: cargo install --path crates/rebond-cli"
            ),
        }
    }
}
