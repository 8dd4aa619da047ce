//! Where a scene comes from: a file, or a built-in scene named on the command line.

use std::path::{Path, PathBuf};

use crate::failure::Failure;
use rebond::scene::{BuiltinScene, LoadError, Scene};

/// The scene a command was given.
#[derive(Debug, Clone)]
pub enum SceneSource {
    /// A scene file.
    File(PathBuf),
    /// A scene embedded in the binary.
    Builtin(&'static BuiltinScene),
}

impl SceneSource {
    /// Resolves the `SCENE` argument: a path that exists wins, then a built-in scene name.
    pub fn resolve(argument: &Path) -> Result<Self, Failure> {
        if argument.exists() {
            return Ok(Self::File(argument.to_owned()));
        }
        argument
            .to_str()
            .and_then(rebond::scene::builtin)
            .map(Self::Builtin)
            .ok_or_else(|| Failure::UnknownScene {
                argument: argument.display().to_string(),
            })
    }

    /// How errors and summaries name the scene: the path, or `NAME (built-in)`.
    pub fn label(&self) -> String {
        match self {
            Self::File(path) => path.display().to_string(),
            Self::Builtin(scene) => format!("{} (built-in)", scene.name),
        }
    }

    /// Reads, checks and loads the scene.
    pub fn load(&self) -> Result<Scene, Failure> {
        let loaded = match self {
            Self::File(path) => Scene::from_file(path),
            Self::Builtin(scene) => scene.load(),
        };
        loaded.map_err(|error| match error {
            LoadError::Read { path, error } => Failure::io(&path, "cannot read scene", error),
            LoadError::Invalid(error) => Failure::InvalidScene {
                source: self.label(),
                error,
            },
            error @ LoadError::Mesh { .. } => Failure::MeshFile {
                source: self.label(),
                error,
            },
        })
    }
}
