//! Sphere: every point within `radius` of the origin.

use std::f32::consts::PI;

use crate::error::{check_size, Result};
use crate::mass::MassProperties;
use crate::math::{Aabb, Mat3, Pose, Vec3};

/// A ball of `radius` metres centred on the body origin.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Sphere {
    radius: f32,
}

impl Sphere {
    /// A sphere; the radius must be finite and positive (error field `radius`).
    pub fn new(radius: f32) -> Result<Self> {
        Ok(Self {
            radius: check_size("radius", radius)?,
        })
    }

    /// Radius, metres.
    pub fn radius(&self) -> f32 {
        self.radius
    }

    /// `m = ρ·4/3·π·r³`, `I = 2/5·m·r²` about every axis.
    pub fn mass_properties(&self, density: f32) -> MassProperties {
        let r = self.radius;
        let mass = density * 4.0 / 3.0 * PI * r * r * r;
        MassProperties {
            mass,
            center_of_mass: Vec3::ZERO,
            inertia: Mat3::from_diagonal(Vec3::splat(0.4 * mass * r * r)),
        }
    }

    /// World bounding box at `pose`.
    pub fn aabb(&self, pose: &Pose) -> Aabb {
        Aabb::from_center_half_extents(pose.position, Vec3::splat(self.radius))
    }

    /// `r · d / |d|`.
    pub fn support(&self, direction: Vec3) -> Vec3 {
        direction.normalize_or(Vec3::X) * self.radius
    }
}
