//! Capsule: the segment from `(0, −h, 0)` to `(0, h, 0)` swept by a sphere of radius `r`.

use std::f32::consts::PI;

use crate::error::{check_size, Result};
use crate::mass::MassProperties;
use crate::math::{Aabb, Mat3, Pose, Vec3};

/// A capsule along local Y.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Capsule {
    radius: f32,
    half_height: f32,
}

impl Capsule {
    /// A capsule; `radius` and `half_height` (half the distance between the sphere centres) must
    /// be finite and positive.
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

    /// Half the distance between the two sphere centres, metres.
    pub fn half_height(&self) -> f32 {
        self.half_height
    }

    /// The two sphere centres, local frame.
    pub fn segment(&self) -> [Vec3; 2] {
        [
            Vec3::new(0.0, -self.half_height, 0.0),
            Vec3::new(0.0, self.half_height, 0.0),
        ]
    }

    /// Cylinder of mass `m_c = ρπr²·2h` plus two hemispheres of total mass `m_s = ρ·4/3·πr³`:
    /// `Iyy = m_c r²/2 + 2/5 m_s r²`,
    /// `Ixx = m_c (r²/4 + h²/3) + m_s (2/5 r² + h² + 3/4 h r)` (hemisphere centroids at `3r/8`).
    pub fn mass_properties(&self, density: f32) -> MassProperties {
        let (r, h) = (self.radius, self.half_height);
        let cylinder_mass = density * PI * r * r * 2.0 * h;
        let spheres_mass = density * 4.0 / 3.0 * PI * r * r * r;
        let axial = 0.5 * cylinder_mass * r * r + 0.4 * spheres_mass * r * r;
        let transverse = cylinder_mass * (r * r / 4.0 + h * h / 3.0)
            + spheres_mass * (0.4 * r * r + h * h + 0.75 * h * r);
        MassProperties {
            mass: cylinder_mass + spheres_mass,
            center_of_mass: Vec3::ZERO,
            inertia: Mat3::from_diagonal(Vec3::new(transverse, axial, transverse)),
        }
    }

    /// World bounding box at `pose`: the box of the world segment, grown by the radius.
    pub fn aabb(&self, pose: &Pose) -> Aabb {
        let axis = (pose.rotation * Vec3::Y * self.half_height).abs();
        Aabb::from_center_half_extents(pose.position, axis + Vec3::splat(self.radius))
    }

    /// The segment end farther along `d`, plus `r · d / |d|`.
    pub fn support(&self, direction: Vec3) -> Vec3 {
        let end = if direction.y >= 0.0 {
            self.half_height
        } else {
            -self.half_height
        };
        Vec3::new(0.0, end, 0.0) + direction.normalize_or(Vec3::Y) * self.radius
    }
}
