//! rebond: an impulse-based 3D rigid-body physics engine.
//!
//! The pipeline, one module a stage: [`shape`] (geometry and mass), [`body`] (rigid bodies),
//! [`integration`] (semi-implicit Euler), [`world`] (owns everything and steps it), with
//! [`query`] (rays, shape casts, overlaps), [`events`] (contacts, forces, sensors) and [`filter`]
//! (collision groups).

pub mod arena;
pub mod body;
pub mod collision;
pub mod error;
pub mod events;
pub mod filter;
pub mod island;
pub mod mass;
pub mod math;
pub mod query;
pub mod shape;
pub mod solver;
pub mod world;

pub use body::{BodyDesc, BodyHandle, BodyType, RigidBody};
pub use error::{Error, ErrorKind, Result};
pub use events::{ContactEvent, ContactEventKind, ContactForceEvent, SensorEvent, SensorEventKind};
pub use filter::InteractionGroups;
pub use mass::MassProperties;
pub use math::{Aabb, Mat3, Pose, Quat, Vec3};
pub use query::{QueryFilter, Ray, RayHit, ShapeHit};
pub use shape::{CompoundChild, Shape};
pub use world::{World, WorldSettings};

/// The README's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;
