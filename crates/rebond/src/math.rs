//! Math types on top of glam (f32): poses, bounding boxes and the few helpers the engine shares.

pub use glam::{Mat3, Quat, Vec3, Vec3A};

use crate::error::{Error, ErrorKind, Result};

/// A rigid transform: a rotation followed by a translation. Maps local points to world points as
/// `p_world = position + rotation · p_local`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Pose {
    /// Translation, metres.
    pub position: Vec3,
    /// Orientation, a unit quaternion.
    pub rotation: Quat,
}

impl Default for Pose {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Pose {
    /// No translation, no rotation.
    pub const IDENTITY: Self = Self {
        position: Vec3::ZERO,
        rotation: Quat::IDENTITY,
    };

    /// A pose from a position and a unit rotation.
    pub fn new(position: Vec3, rotation: Quat) -> Self {
        Self { position, rotation }
    }

    /// A pure translation.
    pub fn from_position(position: Vec3) -> Self {
        Self::new(position, Quat::IDENTITY)
    }

    /// Local point to world point.
    pub fn transform_point(&self, point: Vec3) -> Vec3 {
        self.position + self.rotation * point
    }

    /// Local direction to world direction (rotation only).
    pub fn transform_vector(&self, vector: Vec3) -> Vec3 {
        self.rotation * vector
    }

    /// World point to local point.
    pub fn inverse_transform_point(&self, point: Vec3) -> Vec3 {
        self.rotation.inverse() * (point - self.position)
    }

    /// World direction to local direction.
    pub fn inverse_transform_vector(&self, vector: Vec3) -> Vec3 {
        self.rotation.inverse() * vector
    }

    /// The inverse transform: `p_local = inverse.transform_point(p_world)`.
    pub fn inverse(&self) -> Pose {
        let rotation = self.rotation.inverse();
        Pose::new(rotation * -self.position, rotation)
    }

    /// The composition `self · other`: first `other`, then `self`.
    pub fn mul_pose(&self, other: &Pose) -> Pose {
        Pose::new(
            self.transform_point(other.position),
            (self.rotation * other.rotation).normalize(),
        )
    }
}

/// An axis-aligned bounding box.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Aabb {
    /// Smallest corner.
    pub min: Vec3,
    /// Largest corner.
    pub max: Vec3,
}

impl Aabb {
    /// The box with the given corners.
    pub fn new(min: Vec3, max: Vec3) -> Self {
        Self { min, max }
    }

    /// The box of a centre and half extents.
    pub fn from_center_half_extents(center: Vec3, half_extents: Vec3) -> Self {
        Self::new(center - half_extents, center + half_extents)
    }

    /// The smallest box holding both.
    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb::new(self.min.min(other.min), self.max.max(other.max))
    }

    /// Whether the two boxes overlap (touching counts).
    pub fn overlaps(&self, other: &Aabb) -> bool {
        self.min.cmple(other.max).all() && other.min.cmple(self.max).all()
    }

    /// Whether `point` lies inside or on the box.
    pub fn contains_point(&self, point: Vec3) -> bool {
        self.min.cmple(point).all() && point.cmple(self.max).all()
    }

    /// Centre of the box.
    pub fn center(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// Half the size along each axis.
    pub fn half_extents(&self) -> Vec3 {
        0.5 * (self.max - self.min)
    }
}

/// The skew-symmetric matrix `[v]ₓ` with `[v]ₓ · w = v × w`.
pub fn skew(v: Vec3) -> Mat3 {
    Mat3::from_cols(
        Vec3::new(0.0, v.z, -v.y),
        Vec3::new(-v.z, 0.0, v.x),
        Vec3::new(v.y, -v.x, 0.0),
    )
}

/// The inertia-tensor shift of the parallel-axis theorem for a point mass `mass` at offset `d`:
/// `m (|d|² I − d dᵀ)`, added to an inertia about the centre of mass to get it about the origin.
pub fn parallel_axis_shift(mass: f32, d: Vec3) -> Mat3 {
    mass * (Mat3::from_diagonal(Vec3::splat(d.length_squared()))
        - Mat3::from_cols(d * d.x, d * d.y, d * d.z))
}

/// Normalises a user quaternion; a zero or non-finite one is an error. One whose squared length
/// overflows `f32` (a component past about 1.8e19) is scaled by its largest component first, so
/// that it gives its direction rather than zero or NaN.
pub fn normalize_rotation(field: &str, rotation: Quat) -> Result<Quat> {
    if !rotation.is_finite() {
        return Err(Error::new(field, ErrorKind::NotFinite));
    }
    let rotation = if rotation.length_squared().is_finite() {
        rotation
    } else {
        let components = glam::Vec4::from(rotation);
        Quat::from_vec4(components / components.abs().max_element())
    };
    let length = rotation.length();
    if length <= f32::EPSILON {
        return Err(Error::new(field, ErrorKind::ZeroQuaternion));
    }
    Ok(rotation / length)
}

/// Rotates a body-frame tensor into the world frame: `R · M · Rᵀ`.
pub fn rotate_tensor(rotation: Quat, tensor: Mat3) -> Mat3 {
    let r = Mat3::from_quat(rotation);
    r * tensor * r.transpose()
}

/// The rotation vector (axis times angle, rad) of a unit quaternion with `w ≥ 0`.
pub fn rotation_vector(rotation: Quat) -> Vec3 {
    let vector = Vec3::new(rotation.x, rotation.y, rotation.z);
    let sine = vector.length();
    if sine < 1.0e-6 {
        2.0 * vector
    } else {
        vector * (2.0 * sine.atan2(rotation.w) / sine)
    }
}
