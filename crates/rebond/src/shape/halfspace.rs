//! Halfspace: the solid below a plane through the body origin.

use crate::error::{check_finite_vector, Error, ErrorKind, Result};
use crate::math::{Aabb, Pose, Vec3};

/// Half size of the bounding box given to a halfspace, metres: bounding boxes stay finite so the
/// broad phase can do arithmetic on them.
pub const HALFSPACE_EXTENT: f32 = 1.0e6;

/// The points `p` with `n · p ≤ 0` in the body frame, with `n` the unit outward normal.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Halfspace {
    normal: Vec3,
}

impl Halfspace {
    /// A halfspace with outward `normal` (normalised here; a zero or non-finite one is an error
    /// for field `normal`).
    pub fn new(normal: Vec3) -> Result<Self> {
        check_finite_vector("normal", normal)?;
        let normal = normal
            .try_normalize()
            .ok_or_else(|| Error::new("normal", ErrorKind::ZeroVector))?;
        Ok(Self { normal })
    }

    /// Unit outward normal in the body frame.
    pub fn normal(&self) -> Vec3 {
        self.normal
    }

    /// A cube of half size [`HALFSPACE_EXTENT`] around the plane's origin, cut at the plane on
    /// the axis a world normal is aligned with.
    pub fn aabb(&self, pose: &Pose) -> Aabb {
        let mut bounds =
            Aabb::from_center_half_extents(pose.position, Vec3::splat(HALFSPACE_EXTENT));
        let normal = pose.rotation * self.normal;
        for axis in 0..3 {
            if normal[axis] >= 1.0 - 1.0e-6 {
                bounds.max[axis] = pose.position[axis];
            } else if normal[axis] <= -1.0 + 1.0e-6 {
                bounds.min[axis] = pose.position[axis];
            }
        }
        bounds
    }
}
