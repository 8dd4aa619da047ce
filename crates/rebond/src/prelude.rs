//! What most programs need, in one import: `use rebond::prelude::*;`.
//!
//! It brings the world and its settings, body descriptions and handles, shapes, the math types
//! and the query types; `rebond::Result` stays out so that it does not shadow `std`'s.

pub use crate::{
    BodyDesc, BodyHandle, BodyType, ClosestPoints, CompoundChild, Error, InteractionGroups,
    JointDesc, JointHandle, LockedAxes, Motor, Pose, Quat, QueryFilter, Ray, RigidBody, Shape,
    Vec3, World, WorldSettings,
};
