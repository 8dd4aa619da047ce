//! Cylinder: the points with `x² + z² ≤ r²` and `|y| ≤ h`.

use std::f32::consts::PI;

use crate::error::{check_size, Result};
use crate::mass::MassProperties;
use crate::math::{Aabb, Mat3, Pose, Vec3};

/// A solid circular cylinder along local Y.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Cylinder {
    radius: f32,
    half_height: f32,
}

impl Cylinder {
    /// A cylinder; `radius` and `half_height` must be finite and positive.
    pub fn new(radius: f32, half_height: f32) -> Result<Self> {
        Ok(Self {
            radius: check_size("radius", radius)?,
            half_height: check_size("half_height", half_height)?,
        })
    }

    /// Radius, metres.
    pub fn radius(&self) -> f32 {
        self.radius
    }

    /// Half the height, metres.
    pub fn half_height(&self) -> f32 {
        self.half_height
    }

    /// `m = ρπr²·2h`, `Iyy = m r²/2`, `Ixx = Izz = m (r²/4 + h²/3)`.
    pub fn mass_properties(&self, density: f32) -> MassProperties {
        let (r, h) = (self.radius, self.half_height);
        let mass = density * PI * r * r * 2.0 * h;
        let transverse = mass * (r * r / 4.0 + h * h / 3.0);
        MassProperties {
            mass,
            center_of_mass: Vec3::ZERO,
            inertia: Mat3::from_diagonal(Vec3::new(transverse, 0.5 * mass * r * r, transverse)),
        }
    }

    /// World bounding box at `pose`: along world axis `i`, `h·|aᵢ| + r·√(1 − aᵢ²)` with `a` the
    /// world cylinder axis.
    pub fn aabb(&self, pose: &Pose) -> Aabb {
        let axis = pose.rotation * Vec3::Y;
        let disc = (Vec3::ONE - axis * axis).max(Vec3::ZERO);
        let half_extents = axis.abs() * self.half_height
            + Vec3::new(disc.x.sqrt(), disc.y.sqrt(), disc.z.sqrt()) * self.radius;
        Aabb::from_center_half_extents(pose.position, half_extents)
    }

    /// The cap farther along `d`, then the rim point farthest along `d`'s XZ part.
    pub fn support(&self, direction: Vec3) -> Vec3 {
        let y = if direction.y >= 0.0 {
            self.half_height
        } else {
            -self.half_height
        };
        let radial = Vec3::new(direction.x, 0.0, direction.z).normalize_or_zero() * self.radius;
        Vec3::new(radial.x, y, radial.z)
    }
}
