//! rebond: an impulse-based 3D rigid-body physics engine.

pub mod error;
pub mod mass;
pub mod math;
pub mod shape;

pub use error::{Error, ErrorKind, Result};
pub use mass::MassProperties;
pub use math::{Aabb, Mat3, Pose, Quat, Vec3};
pub use shape::Shape;
