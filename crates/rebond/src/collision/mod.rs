//! Collision detection: the broad phase finds pairs of bodies whose bounding boxes overlap, the
//! narrow phase turns each pair into contact manifolds, and the contact cache carries impulses
//! from one step to the next.

pub mod broad_phase;
pub mod clipping;
pub mod closed_form;
pub mod contact_cache;
pub mod dynamic_tree;
pub mod epa;
pub mod feature_contact;
pub mod gjk;
pub mod halfspace;
pub mod manifold;
mod manifold_frame;
mod mesh_contact;
pub mod narrow_phase;
pub mod polyhedron;
pub mod polyhedron_contact;
pub mod reduction;
mod separating_axis;
pub(crate) mod time_of_impact;
mod triangle_closest;
pub mod triangle_contact;

pub use manifold::{ContactPoint, Manifold, MAX_MANIFOLD_POINTS};

use crate::math::{Mat3, Pose, Vec3};
use crate::shape::Shape;

/// Contact points are made while two shapes are still apart by less than this, metres, so the
/// solver can stop approaching bodies before they touch.
pub const SPECULATIVE_DISTANCE: f32 = 0.02;

/// How many times its reach (its largest distance from its centre of mass) a body may move in a
/// step and still have its contacts made ahead of it, as far as it can close in the step.
/// Farther, the continuous pass sweeps it: a contact made that far ahead, with the normal of
/// where the body is now, would stop it against a corner it is about to fly past. Four reaches
/// keep a body crossing twice its own length a step (a ragdoll's forearm falling at 15 m/s, a
/// box at 50 m/s) in the solver, where its joints and other contacts are solved with it.
pub const FAST_MOTION_REACHES: f32 = 4.0;

/// A convex solid given by its support function in world coordinates.
pub trait SupportMap {
    /// The point of the solid farthest along world `direction` (any length, not zero).
    fn support(&self, direction: Vec3) -> Vec3;
}

/// The core of a convex shape placed in the world: the shape without its rounding radius (a
/// sphere's centre point, a capsule's segment, a cylinder shrunk by its convex radius; boxes and
/// hulls are their own core).
/// Distance algorithms run on cores; the radius is added back afterwards, which keeps rounded
/// shapes exact and the algorithms away from curved surfaces.
#[derive(Debug, Clone, Copy)]
pub struct PosedCore<'a> {
    /// A convex shape: not a compound, not a halfspace.
    pub shape: &'a Shape,
    /// Where it sits in the world.
    pub pose: &'a Pose,
}

impl<'a> PosedCore<'a> {
    /// The core of `shape` (convex: not a compound, not a halfspace) placed at `pose`.
    pub fn new(shape: &'a Shape, pose: &'a Pose) -> Self {
        Self { shape, pose }
    }
}

impl SupportMap for PosedCore<'_> {
    fn support(&self, direction: Vec3) -> Vec3 {
        let local = self.pose.inverse_transform_vector(direction);
        self.pose.transform_point(self.shape.core_support(local))
    }
}

/// The core of a convex shape in its own frame: [`Shape::core_support`] as a support map.
#[derive(Debug, Clone, Copy)]
pub struct LocalCore<'a>(pub &'a Shape);

impl SupportMap for LocalCore<'_> {
    fn support(&self, direction: Vec3) -> Vec3 {
        self.0.core_support(direction)
    }
}

/// The core of a convex shape placed in another's frame, `p = rotation · p_local + position`:
/// running GJK and EPA in A's frame leaves A's supports untransformed and costs B's two
/// matrix products, where world supports cost four quaternion rotations.
#[derive(Debug, Clone, Copy)]
pub struct RelativeCore<'a> {
    shape: &'a Shape,
    rotation: Mat3,
    /// Origin of the shape in the frame, metres.
    pub position: Vec3,
}

impl<'a> RelativeCore<'a> {
    /// `core` seen from `frame`: its pose composed with the inverse of `frame`.
    pub fn new(core: &PosedCore<'a>, frame: &Pose) -> Self {
        let inverse = frame.rotation.inverse();
        Self {
            shape: core.shape,
            rotation: Mat3::from_quat(inverse * core.pose.rotation),
            position: inverse * (core.pose.position - frame.position),
        }
    }

    /// A point given in the shape's own frame, placed in the frame: `rotation · p + position`.
    pub fn place(&self, local: Vec3) -> Vec3 {
        self.rotation * local + self.position
    }

    /// A point of the frame in the shape's own frame: the inverse of [`RelativeCore::place`].
    pub fn local_point(&self, point: Vec3) -> Vec3 {
        self.local_vector(point - self.position)
    }

    /// A vector of the frame in the shape's axes, `rotationᵀ · v`: one dot product per axis.
    fn local_vector(&self, vector: Vec3) -> Vec3 {
        let columns = [
            self.rotation.x_axis,
            self.rotation.y_axis,
            self.rotation.z_axis,
        ];
        Vec3::from_array(columns.map(|column| column.dot(vector)))
    }
}

impl SupportMap for RelativeCore<'_> {
    fn support(&self, direction: Vec3) -> Vec3 {
        self.place(self.shape.core_support(self.local_vector(direction)))
    }
}
