//! Tests of the `rebond` binary against the contract in `docs/scene-format.md`: they run the
//! built binary on scene files written to a scratch directory.

mod bad_input;
mod bad_joints;
mod commands;
mod common;
mod filtering;
mod joints;
mod kinematic;
mod limits;
mod meshes;
mod mjcf;
mod records;
mod scenes;
mod state;
#[cfg(feature = "viewer")]
mod view;
