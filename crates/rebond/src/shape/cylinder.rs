//! Cylinder: the points with `x² + z² ≤ r²` and `|y| ≤ h`, its two rims rounded for contacts by
//! a small convex radius (see [`Cylinder::convex_radius`]).

use std::f32::consts::PI;

use crate::error::{check_size, Result};
use crate::mass::MassProperties;
use crate::math::{Aabb, Mat3, Pose, Vec3};

/// Rims of a cylinder are rounded by this fraction of the smaller of its radius and half height
/// (see [`Cylinder::convex_radius`]).
const CONVEX_RADIUS_FRACTION: f32 = 0.05;

/// Largest convex radius of a cylinder, metres: 1 cm, a bevel the eye barely sees on a body of a
/// metre, and deeper than the millimetre or so resting contacts sink.
const MAX_CONVEX_RADIUS: f32 = 0.01;

/// A solid circular cylinder along local Y.
///
/// For contacts, shape casts and overlap tests its two rims are rounded: the cylinder is a core
/// cylinder, shrunk by the convex radius `r_c` ([`Cylinder::convex_radius`]) in radius and half
/// height, grown by a ball of radius `r_c`. Its outer radius and height, its caps and side stay
/// exactly as given; only the edges between them are rounds of radius `r_c` (at most 1 cm). Ray
/// casts and point tests see the sharp cylinder, which reaches at most `(√2 − 1)·r_c` (4 mm)
/// beyond the rounded one, at a rim. Mass properties are those of the sharp cylinder.
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

    /// Radius of the rounds on the rims, metres: `r_c = min(0.05·min(r, h), 0.01 m)`. Contacts
    /// shallower than `r_c` are measured between the core cylinders (radius `r − r_c`, half height
    /// `h − r_c`) with the radius added back, with no penetration search (EPA).
    pub fn convex_radius(&self) -> f32 {
        (CONVEX_RADIUS_FRACTION * self.radius.min(self.half_height)).min(MAX_CONVEX_RADIUS)
    }

    /// The core cylinder: this one shrunk by [`Cylinder::convex_radius`] in radius and half
    /// height; the cylinder is the core grown by a ball of that radius.
    pub(crate) fn core(&self) -> Self {
        let rounding = self.convex_radius();
        Self {
            radius: self.radius - rounding,
            half_height: self.half_height - rounding,
        }
    }

    /// `m = ρπr²·2h`, `Iyy = m r²/2`, `Ixx = Izz = m (r²/4 + h²/3)`, those of the sharp cylinder
    /// (the rounds take off `(1 − π/4)·r_c²` of cross-section along each rim, at most 0.11 % of
    /// the volume).
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

    /// World bounding box of the rounded cylinder at `pose`: along world axis `i`, the core's
    /// `(h − r_c)·|aᵢ| + (r − r_c)·√(1 − aᵢ²)` plus `r_c`, with `a` the world cylinder axis.
    pub fn aabb(&self, pose: &Pose) -> Aabb {
        let core = self.core();
        let axis = pose.rotation * Vec3::Y;
        let disc = (Vec3::ONE - axis * axis).max(Vec3::ZERO);
        let half_extents = axis.abs() * core.half_height
            + Vec3::new(disc.x.sqrt(), disc.y.sqrt(), disc.z.sqrt()) * core.radius
            + Vec3::splat(self.convex_radius());
        Aabb::from_center_half_extents(pose.position, half_extents)
    }

    /// The point of the rounded cylinder farthest along `d`: the core cylinder's (its cap farther
    /// along `d`, then its rim point farthest along `d`'s XZ part) moved by `r_c` along `d`.
    pub fn support(&self, direction: Vec3) -> Vec3 {
        self.core_support(direction) + self.convex_radius() * direction.normalize_or_zero()
    }

    /// The point of the core cylinder farthest along `d`: its cap farther along `d`, then its rim
    /// point farthest along `d`'s XZ part.
    pub(crate) fn core_support(&self, direction: Vec3) -> Vec3 {
        self.core().sharp_support(direction)
    }

    /// The cap farther along `d`, then the rim point farthest along `d`'s XZ part.
    fn sharp_support(&self, direction: Vec3) -> Vec3 {
        let y = if direction.y >= 0.0 {
            self.half_height
        } else {
            -self.half_height
        };
        let radial = Vec3::new(direction.x, 0.0, direction.z).normalize_or_zero() * self.radius;
        Vec3::new(radial.x, y, radial.z)
    }
}
