//! Scene queries: what a ray meets, where a convex shape swept in a straight line first touches,
//! which bodies hold a point or overlap a box or a shape, how far apart two shapes or bodies are,
//! and the body surface nearest a point.
//!
//! Every query is a method of [`World`](crate::World) (see `world_queries.rs`) that walks the
//! broad phase's two trees, so it costs about the logarithm of the number of bodies, then tests
//! each candidate's exact shape:
//!
//! | method | answers |
//! |---|---|
//! | [`World::cast_ray`](crate::World::cast_ray) | the nearest [`RayHit`] |
//! | [`World::cast_ray_all`](crate::World::cast_ray_all) | one hit per body the ray meets, nearest first |
//! | [`World::cast_ray_any`](crate::World::cast_ray_any) | whether the ray meets anything (stops at the first hit) |
//! | [`World::cast_shape`](crate::World::cast_shape) | the first [`ShapeHit`] of a shape swept along a direction |
//! | [`World::bodies_containing_point`](crate::World::bodies_containing_point) | bodies whose shape holds a point |
//! | [`World::bodies_overlapping_aabb`](crate::World::bodies_overlapping_aabb) | bodies whose bounding box overlaps a box |
//! | [`World::bodies_overlapping_shape`](crate::World::bodies_overlapping_shape) | bodies whose shape overlaps a shape at a pose |
//! | [`World::project_point`](crate::World::project_point) | the body surface point nearest a point, as a [`PointProjection`] |
//! | [`World::closest_points`](crate::World::closest_points) | the [`ClosestPoints`] of two bodies, or their penetration |
//! | [`World::distance`](crate::World::distance) | the signed distance between two bodies' surfaces |
//!
//! [`closest_points`] answers for two shapes at poses, outside any world.
//!
//! Conventions:
//! - Distances are metres along the unit direction (a direction of any length is normalised).
//! - Normals are unit vectors in the world frame that face where the ray or the swept shape came
//!   from: the outward surface normal of the body hit, or, for a hollow ray leaving a shape from
//!   inside, the inward one.
//! - A [`QueryFilter`] decides which bodies count: by handle, by body type, sensor or not, by
//!   collision groups (the rule bodies use between themselves) and by a predicate.
//!   Sleeping bodies are found like any other.
//! - Equally near hits are broken by body handle (the smaller wins), lists come sorted, so
//!   answers do not depend on the history of the broad phase's trees.
//! - Inputs are checked: a non-finite value, a zero direction or a negative maximum distance is
//!   an [`Error`] naming the field, and so is a filter excluding a body of another world (field
//!   `excluded_bodies[i]`, [`ErrorKind::StaleHandle`]); no query panics. None allocates beyond
//!   the output vector the caller passes in, except a shape cast that starts overlapping a body
//!   and closest points of overlapping bodies whose cores overlap (EPA's scratch space).
//! - Closest points and projections: normals point from A toward B, and from a body's surface
//!   outward. A sphere against a sphere, box, capsule or hull, anything against a halfspace, and
//!   a point projected on any shape are closed forms, exact to f32 rounding, but for a hull seen
//!   from outside and every other pair, measured by GJK within 1e-5 of the shapes' size (EPA's
//!   depth when they overlap, as precise). Meshes and heightfields are measured on their
//!   triangles; overlapping one, a shape gets the narrow phase's triangle contact (depth within
//!   0.1 mm), and two meshes are surfaces, touching where they cross. A point projection sees a
//!   cylinder sharp, as rays do; closest points see its rims rounded, as contacts do. A
//!   halfspace has no depth against a halfspace it does not face: infinite.
//! - Ray casts are closed forms, exact to f32 rounding. Shape casts stop within GJK's precision,
//!   about 1e-5 of the size of the two shapes (0.4 mm against a 100 m floor box), always on the
//!   near side of the contact; against a halfspace they are exact.
//! - Bodies are found through their broad-phase boxes: fat boxes set by
//!   [`World::add_body`](crate::World::add_body) and refreshed at the start of each
//!   [`World::step`](crate::World::step) around the body and its expected motion over the step.
//!   A body pushed off that course during the step (a bounce), or moved by the user since, may
//!   be missed where it sticks out of its box, until the next step.

mod closest;
mod mesh;
mod overlap;
mod projection;
mod ray;
mod shape_cast;
mod world_queries;

pub use closest::{closest_points, ClosestPoints};
pub(crate) use overlap::shapes_overlap;

use std::fmt;

use crate::body::{BodyHandle, BodyType, RigidBody};
use crate::error::{check_non_negative_or_infinite, Error, ErrorKind, Result};
use crate::filter::{Colliders, InteractionGroups};
use crate::math::{normalize_rotation, Pose, Vec3};
use crate::shape::{Halfspace, Shape};

/// A ray: a half-line from `origin` along `direction`, up to `max_distance`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Where the ray starts, world, metres.
    pub origin: Vec3,
    /// Where it goes, world: any finite, non-zero length (queries normalise it).
    pub direction: Vec3,
    /// How far it reaches, metres: zero or more, infinity for no limit (the default).
    pub max_distance: f32,
    /// What a ray starting inside a shape hits. Solid (the default): the shape itself, at distance
    /// zero, with the normal `−direction`. Hollow: the inside of its surface, where the ray
    /// leaves it (a halfspace is never left along a ray going deeper).
    pub solid: bool,
}

impl Ray {
    /// A solid ray from `origin` along `direction`, without a distance limit.
    pub fn new(origin: Vec3, direction: Vec3) -> Self {
        Self {
            origin,
            direction,
            max_distance: f32::INFINITY,
            solid: true,
        }
    }

    /// The same ray reaching only `max_distance` metres.
    pub fn max_distance(mut self, max_distance: f32) -> Self {
        self.max_distance = max_distance;
        self
    }

    /// The same ray, hollow: starting inside a shape, it hits the surface where it leaves.
    pub fn hollow(mut self) -> Self {
        self.solid = false;
        self
    }

    /// The ray with its values checked and its direction normalised; errors name the field
    /// (`origin`, `direction`, `max_distance`).
    pub(crate) fn validated(&self) -> Result<Ray> {
        if !self.origin.is_finite() {
            return Err(Error::new("origin", ErrorKind::NotFinite));
        }
        Ok(Ray {
            origin: self.origin,
            direction: unit_direction("direction", self.direction)?,
            max_distance: check_non_negative_or_infinite("max_distance", self.max_distance)?,
            solid: self.solid,
        })
    }

    /// The point `distance` metres along the ray (validated: unit direction).
    fn point_at(&self, distance: f32) -> Vec3 {
        self.origin + distance * self.direction
    }
}

/// Where a ray meets a body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayHit {
    /// The body hit.
    pub body: BodyHandle,
    /// The body's collider hit: its compound child's index, or 0 (see
    /// [`CompoundChild`](crate::CompoundChild)).
    pub collider: u32,
    /// On a trimesh or heightfield, the triangle hit ([`Shape::triangle`]'s index); `None` on
    /// any other shape, and for a solid ray starting below a heightfield.
    pub triangle: Option<u32>,
    /// The point hit, world, metres: `origin + distance · direction`.
    pub point: Vec3,
    /// Unit world normal facing the ray (see the [module conventions](self)).
    pub normal: Vec3,
    /// Distance from the ray's origin, metres (zero for a solid ray starting inside).
    pub distance: f32,
}

/// Where a shape swept along a direction first touches a body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeHit {
    /// The body touched.
    pub body: BodyHandle,
    /// The body's collider touched: its compound child's index, or 0.
    pub collider: u32,
    /// On a trimesh or heightfield, the triangle touched ([`Shape::triangle`]'s index); `None`
    /// on any other shape.
    pub triangle: Option<u32>,
    /// How far the shape travels before it touches, metres along the unit direction: the time of
    /// impact at unit speed. Zero when it overlaps the body from the start.
    pub distance: f32,
    /// Where they touch, on the body's surface, world, metres. When they overlap from the start,
    /// the body's point deepest inside the shape.
    pub point: Vec3,
    /// Unit world normal of the body's surface at `point`, facing the swept shape. When they
    /// overlap from the start, the direction in which the shape separates from the body the
    /// quickest.
    pub normal: Vec3,
}

/// The point of a body's surface nearest a query point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointProjection {
    /// The body.
    pub body: BodyHandle,
    /// The body's collider the point is on: its compound child's index, or 0.
    pub collider: u32,
    /// On a trimesh or heightfield, the triangle the point is on ([`Shape::triangle`]'s index);
    /// `None` on any other shape.
    pub triangle: Option<u32>,
    /// The surface point nearest the query point, world, metres.
    pub point: Vec3,
    /// Unit world outward normal of the surface at `point`; on a trimesh, which has no inside,
    /// the side of the triangle facing the query point.
    pub normal: Vec3,
    /// Signed distance from the query point to `point`, metres: negative when the query point is
    /// inside the body.
    pub distance: f32,
    /// Whether the query point lies in the body (inside or on its surface); never on a trimesh.
    pub inside: bool,
}

/// A test of one body by its handle and state, such as `|_, body| body.mass() > 10.0`.
pub type BodyPredicate<'a> = &'a dyn Fn(BodyHandle, &RigidBody) -> bool;

/// Which bodies a query sees. The default sees every body.
///
/// ```
/// use rebond::{BodyType, QueryFilter};
///
/// let skip_small = |_, body: &rebond::RigidBody| body.mass() > 10.0;
/// let filter = QueryFilter::new()
///     .exclude_type(BodyType::Static)
///     .predicate(&skip_small);
/// assert!(!filter.include_static);
/// ```
#[derive(Clone, Copy)]
pub struct QueryFilter<'a> {
    /// Bodies never reported, such as the body that casts the ray. A removed body excludes
    /// nothing; a body of another world makes the query an error naming it.
    pub excluded_bodies: &'a [BodyHandle],
    /// Whether dynamic bodies are seen (default true).
    pub include_dynamic: bool,
    /// Whether static bodies are seen (default true).
    pub include_static: bool,
    /// Whether kinematic bodies are seen (default true).
    pub include_kinematic: bool,
    /// Whether sensors are seen (default true): sensor bodies, and the sensor children of
    /// compounds.
    pub include_sensors: bool,
    /// When set, only bodies whose collision groups interact with these are seen, by the rule of
    /// [`InteractionGroups::interacts_with`], and of a compound only the children whose own
    /// groups (the child's, else the body's) interact with them too; default `None` (groups
    /// ignored).
    pub groups: Option<InteractionGroups>,
    /// A last word on each body that passed the other tests: it is seen when this returns true.
    /// Called before the body's shape is tested, so it may be called for bodies the query then
    /// misses.
    pub predicate: Option<BodyPredicate<'a>>,
}

impl Default for QueryFilter<'_> {
    fn default() -> Self {
        Self::new()
    }
}

impl fmt::Debug for QueryFilter<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("QueryFilter")
            .field("excluded_bodies", &self.excluded_bodies)
            .field("include_dynamic", &self.include_dynamic)
            .field("include_static", &self.include_static)
            .field("include_kinematic", &self.include_kinematic)
            .field("include_sensors", &self.include_sensors)
            .field("groups", &self.groups)
            .field("predicate", &self.predicate.map(|_| "Fn(..)"))
            .finish()
    }
}

impl<'a> QueryFilter<'a> {
    /// A filter that sees every body.
    pub fn new() -> Self {
        Self {
            excluded_bodies: &[],
            include_dynamic: true,
            include_static: true,
            include_kinematic: true,
            include_sensors: true,
            groups: None,
            predicate: None,
        }
    }

    /// Never reports `bodies`.
    pub fn exclude_bodies(mut self, bodies: &'a [BodyHandle]) -> Self {
        self.excluded_bodies = bodies;
        self
    }

    /// Leaves out the bodies of type `body_type`.
    pub fn exclude_type(mut self, body_type: BodyType) -> Self {
        *self.includes_mut(body_type) = false;
        self
    }

    /// Sees only the bodies of type `body_type`.
    pub fn only_type(mut self, body_type: BodyType) -> Self {
        self.include_dynamic = false;
        self.include_static = false;
        self.include_kinematic = false;
        *self.includes_mut(body_type) = true;
        self
    }

    /// Leaves out sensors.
    pub fn exclude_sensors(mut self) -> Self {
        self.include_sensors = false;
        self
    }

    /// Sees only the bodies whose collision groups interact with `groups`.
    pub fn groups(mut self, groups: InteractionGroups) -> Self {
        self.groups = Some(groups);
        self
    }

    /// Sees only the bodies for which `predicate(handle, body)` returns true (among those the
    /// other tests let through).
    pub fn predicate(mut self, predicate: BodyPredicate<'a>) -> Self {
        self.predicate = Some(predicate);
        self
    }

    /// Whether the query sees this body.
    pub fn accepts(&self, handle: BodyHandle, body: &RigidBody) -> bool {
        let type_included = match body.body_type() {
            BodyType::Dynamic => self.include_dynamic,
            BodyType::Static => self.include_static,
            BodyType::Kinematic => self.include_kinematic,
        };
        type_included
            && (self.include_sensors || !body.is_sensor())
            && self
                .groups
                .is_none_or(|groups| groups.interacts_with(body.collision_groups()))
            && !self.excluded_bodies.contains(&handle)
            && self
                .predicate
                .is_none_or(|predicate| predicate(handle, body))
    }

    /// Whether the query sees collider `index` of a body it accepts: a compound's child that is
    /// a sensor or whose own groups do not interact with the filter's is left out as a body
    /// would be.
    pub(crate) fn sees_collider(&self, colliders: &Colliders, index: u32) -> bool {
        (self.include_sensors || !colliders.is_sensor(index))
            && self
                .groups
                .is_none_or(|groups| groups.interacts_with(colliders.groups(index)))
    }

    fn includes_mut(&mut self, body_type: BodyType) -> &mut bool {
        match body_type {
            BodyType::Dynamic => &mut self.include_dynamic,
            BodyType::Static => &mut self.include_static,
            BodyType::Kinematic => &mut self.include_kinematic,
        }
    }
}

// A query's direction is normalised and checked as every direction the engine takes.
use crate::error::check_direction as unit_direction;

/// A user pose with a finite position and a normalised rotation; errors name `position` or
/// `rotation` within `field` (`pose.position`).
pub(crate) fn validated_pose(field: &str, pose: &Pose) -> Result<Pose> {
    if !pose.position.is_finite() {
        return Err(Error::new("position", ErrorKind::NotFinite).within(field));
    }
    let rotation = normalize_rotation("rotation", pose.rotation).map_err(|e| e.within(field))?;
    Ok(Pose::new(pose.position, rotation))
}

/// The convex parts of a shape with their collider indices and world poses: the shape itself
/// (0), or each child of a compound.
fn convex_parts(shape: &Shape, pose: Pose) -> impl Iterator<Item = (u32, &Shape, Pose)> {
    let (whole, children) = match shape {
        Shape::Compound(compound) => (None, compound.children()),
        _ => (Some((0, shape, pose)), &[][..]),
    };
    whole.into_iter().chain(
        (0..)
            .zip(children)
            .map(move |(index, child)| (index, &child.shape, pose.mul_pose(&child.pose))),
    )
}

/// Which part of a body a query met: its collider, and on a mesh or heightfield the triangle.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct HitPart {
    pub collider: u32,
    pub triangle: Option<u32>,
}

/// The point of a bounded convex shape at `pose` farthest along world `direction`; `None` for a
/// halfspace.
fn world_support(shape: &Shape, pose: &Pose, direction: Vec3) -> Option<Vec3> {
    shape
        .support(pose.inverse_transform_vector(direction))
        .map(|point| pose.transform_point(point))
}

/// A halfspace placed in the world: the points `p` with `normal · (p − point) ≤ 0`.
#[derive(Debug, Clone, Copy)]
struct PlacedHalfspace {
    /// Unit outward normal, world.
    normal: Vec3,
    /// A point of the boundary plane, world (the body origin).
    point: Vec3,
}

impl PlacedHalfspace {
    fn new(halfspace: &Halfspace, pose: &Pose) -> Self {
        Self {
            normal: pose.transform_vector(halfspace.normal()),
            point: pose.position,
        }
    }

    /// Signed distance of `point` above the plane, metres (negative inside).
    fn height_of(&self, point: Vec3) -> f32 {
        self.normal.dot(point - self.point)
    }

    /// Whether the two outward normals are opposite to within f32 rounding
    /// (`1 + n_a · n_b ≤ 10⁻⁶`, about 0.08°). Any other two halfspaces overlap somewhere.
    fn faces(&self, other: &PlacedHalfspace) -> bool {
        1.0 + self.normal.dot(other.normal) <= 1e-6
    }
}
