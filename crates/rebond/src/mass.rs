//! Mass properties: mass, centre of mass and inertia tensor of a shape or body.

use crate::math::{parallel_axis_shift, rotate_tensor, Mat3, Pose, Vec3};

/// Mass, centre of mass and inertia of a solid, in its own (local) frame.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MassProperties {
    /// Mass, kg.
    pub mass: f32,
    /// Centre of mass in the local frame, metres.
    pub center_of_mass: Vec3,
    /// Inertia tensor about the centre of mass, in local axes, kg·m².
    pub inertia: Mat3,
}

impl MassProperties {
    /// No mass at all: the neutral element of [`MassProperties::combine`].
    pub const ZERO: Self = Self {
        mass: 0.0,
        center_of_mass: Vec3::ZERO,
        inertia: Mat3::ZERO,
    };

    /// The same solid with its density changed so that its mass is `mass`: inertia scales by
    /// `mass / self.mass`, the centre of mass stays.
    pub fn scaled_to_mass(&self, mass: f32) -> Self {
        let scale = mass / self.mass;
        Self {
            mass,
            center_of_mass: self.center_of_mass,
            inertia: self.inertia * scale,
        }
    }

    /// The same solid with its principal moments of inertia at most `ratio` apart (largest over
    /// smallest): where the smallest may lie below `tr I / ratio`, every moment is raised by that
    /// much, `I + (tr I / ratio) 𝟙`. The smallest moment is at least `4 det I / (tr I)²` (the two
    /// largest multiply to at most `(tr I / 2)²`), so a solid within the ratio by that bound is
    /// returned as it is.
    pub fn with_inertia_spread_at_most(&self, ratio: f32) -> Self {
        let inertia = self.inertia.as_dmat3();
        let trace = inertia.x_axis.x + inertia.y_axis.y + inertia.z_axis.z;
        if 4.0 * inertia.determinant() * f64::from(ratio) >= trace.powi(3) {
            return *self;
        }
        Self {
            inertia: self.inertia
                + Mat3::from_diagonal(Vec3::splat((trace / f64::from(ratio)) as f32)),
            ..*self
        }
    }

    /// The same solid seen from a frame in which it sits at `position` rotated by `rotation`:
    /// `c' = p + R c`, `I' = R I Rᵀ` (still about its own centre of mass).
    pub fn transformed(&self, pose: &Pose) -> Self {
        Self {
            mass: self.mass,
            center_of_mass: pose.transform_point(self.center_of_mass),
            inertia: rotate_tensor(pose.rotation, self.inertia),
        }
    }

    /// Inertia tensor about `point` instead of the centre of mass (parallel-axis theorem).
    pub fn inertia_about(&self, point: Vec3) -> Mat3 {
        self.inertia + parallel_axis_shift(self.mass, self.center_of_mass - point)
    }

    /// Two solids taken as one: masses add, the centre of mass is the mass-weighted mean, and each
    /// inertia moves to the common centre by the parallel-axis theorem.
    pub fn combine(&self, other: &MassProperties) -> Self {
        let mass = self.mass + other.mass;
        if mass <= 0.0 {
            return Self::ZERO;
        }
        let center_of_mass =
            (self.center_of_mass * self.mass + other.center_of_mass * other.mass) / mass;
        Self {
            mass,
            center_of_mass,
            inertia: self.inertia_about(center_of_mass) + other.inertia_about(center_of_mass),
        }
    }
}
