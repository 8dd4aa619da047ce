//! rebond: an impulse-based 3D rigid-body physics engine.
//!
//! A [`World`] holds rigid bodies, each with one [`Shape`], and advances them in time with
//! [`World::step`]: gravity and forces, collision detection, contacts with friction and
//! restitution and joints solved by a soft step of substeps (docs/physics.md), sleeping. Units
//! are SI (metres, kilograms, seconds), +Y is up by default, rotations are unit quaternions.
//!
//! ```
//! use rebond::prelude::*;
//!
//! let mut world = World::new(WorldSettings::default())?;
//! world.add_body(
//!     BodyDesc::static_body(Shape::cuboid(Vec3::new(10.0, 0.5, 10.0))?)
//!         .position(Vec3::new(0.0, -0.5, 0.0)),
//! )?;
//! let ball = world.add_body(
//!     BodyDesc::dynamic(Shape::sphere(0.5)?)
//!         .position(Vec3::new(0.0, 2.0, 0.0))
//!         .restitution(0.5),
//! )?;
//! for _ in 0..120 {
//!     world.step(1.0 / 60.0)?;
//! }
//! // After two seconds the ball has bounced and rests on the ground.
//! let height = world.body(ball)?.position().y;
//! assert!((height - 0.5).abs() < 0.01);
//! # Ok::<(), rebond::Error>(())
//! ```
//!
//! Every call that takes user values checks them and returns an [`Error`] naming the field;
//! nothing a user passes in makes the engine panic or puts NaN or infinity into a body.
//!
//! The modules, in pipeline order: [`shape`] (geometry and mass), bodies ([`BodyDesc`],
//! [`RigidBody`]), [`joint`]s between them, collision detection, islands and the solver
//! (private: `collision/`, `island.rs`, `solver/`), [`World`] (owns everything and steps it;
//! `world/mod.rs` lists the step's stages in order, with where each lives), with [`query`]
//! (rays, shape casts, overlaps), [`events`] (contacts, forces, sensors), [`scene`] (scene
//! files) and [`state`] (saving and restoring whole worlds, exactly); on top of them,
//! [`character`] moves game characters through the world by its shape casts. For drawing,
//! [`shape::tessellation`] gives each shape's triangles and [`palette`] each body's colour.

mod arena;
mod body;
pub mod character;
mod collision;
pub mod coupling;
mod error;
pub mod events;
mod filter;
pub mod hooks;
mod island;
pub mod joint;
pub mod limits;
mod mass;
mod material;
mod math;
pub mod palette;
pub mod prelude;
pub mod query;
#[cfg(feature = "scene")]
pub mod scene;
pub mod shape;
mod solver;
mod sorted;
#[cfg(feature = "serde")]
pub mod state;
mod world;

pub use body::{BodyDesc, BodyHandle, BodyType, KinematicPath, LockedAxes, PathPoint, RigidBody};
pub use collision::contact_cache::Contact;
pub use collision::{ContactPoint, MAX_MANIFOLD_POINTS};
pub use coupling::{Coupling, CouplingDesc, CouplingHandle, CouplingTerm};
pub use error::{Error, ErrorKind, Result};
pub use events::{ContactEvent, ContactEventKind, ContactForceEvent, SensorEvent, SensorEventKind};
pub use filter::InteractionGroups;
pub use hooks::{ContactHooks, ContactModification};
pub use joint::{
    AxisFreedom, GenericAxis, GenericCoordinates, Joint, JointBreakEvent, JointDesc, JointHandle,
    JointPlacement, JointType, Motor, Spring,
};
pub use mass::MassProperties;
pub use material::CombineRule;
pub use math::{Aabb, Mat3, Pose, Quat, Vec3};
pub use query::{ClosestPoints, PointProjection, QueryFilter, Ray, RayHit, ShapeHit};
pub use shape::{CompoundChild, Shape};
#[doc(hidden)]
pub use world::StepWork;
pub use world::{
    World, WorldSettings, DEFAULT_GRAVITY, DEFAULT_MAX_LINEAR_SPEED, DEFAULT_SUBSTEPS, MAX_SUBSTEPS,
};

/// The engine's internal modules, for its own tests and benchmarks: not part of the public API,
/// and free to change in any release.
#[doc(hidden)]
pub mod internals {
    /// Collision detection internals.
    pub mod collision {
        pub use crate::collision::*;
    }
    /// Math helpers.
    pub mod math {
        pub use crate::math::*;
    }
    /// Solver constants.
    pub mod solver {
        pub use crate::solver::*;
    }
}

/// The README's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;

/// The examples of `docs/bodies.md`, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../../../docs/bodies.md")]
pub struct BodiesDoctests;

/// The examples of `docs/games.md`, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../../../docs/games.md")]
pub struct GamesDoctests;

/// The examples of `docs/kinematic.md`, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../../../docs/kinematic.md")]
pub struct KinematicDoctests;
