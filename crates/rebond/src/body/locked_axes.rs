//! Locked axes: world axes along which a dynamic body never moves or about which it never turns.
//!
//! A lock is a constraint solved exactly by taking the locked directions out of the body's
//! inverse mass and inertia, rather than by resetting velocities after the step: every impulse
//! (contacts, joints, forces) then acts on the body as on one that cannot move that way.
//!
//! - Translation: `M⁻¹ = m⁻¹ (𝟙 − L)`, `L` the diagonal with 1 on the locked world axes.
//! - Rotation: with `P` the projection on the free world axes and `I` the world inertia
//!   `R I_body Rᵀ`, the effective inverse inertia is `P (P I P + (𝟙 − P))⁻¹ P`: the inverse of `I`
//!   restricted to the free axes. A torque `τ` then gives `I_ff ω̇_f = τ_f` on the free axes
//!   `f`, what a body held about the others feels (the holding torque takes the rest), where
//!   zeroing the rows and columns of `I⁻¹` would be exact only for inertia diagonal in world
//!   axes. The gyroscopic term is left out: with one free axis `a` the momentum about it,
//!   `a·I ω = I_aa ω_a`, changes only by the torque about it, which is exact; with two free axes
//!   (one locked) it drops the precession between them.

use crate::math::{Mat3, Vec3};

/// World axes along which a body does not move and about which it does not turn. Only dynamic
/// bodies feel locks: static and kinematic bodies move as they are told.
///
/// ```
/// use rebond::prelude::*;
///
/// // A character capsule that never tips over, and a body kept in the plane z = 0.
/// let upright = LockedAxes::ROTATION;
/// let planar = LockedAxes { translation: [false, false, true], rotation: [true, true, false] };
/// assert!(upright.rotation.iter().all(|&locked| locked));
/// assert!(!planar.is_none());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct LockedAxes {
    /// `[x, y, z]`: whether the centre of mass never moves along that world axis. Default none.
    pub translation: [bool; 3],
    /// `[x, y, z]`: whether the body never turns about that world axis. Default none.
    pub rotation: [bool; 3],
}

impl LockedAxes {
    /// Nothing locked: the default.
    pub const NONE: Self = Self {
        translation: [false; 3],
        rotation: [false; 3],
    };
    /// Every rotation locked, translation free: a character that stays upright.
    pub const ROTATION: Self = Self {
        translation: [false; 3],
        rotation: [true; 3],
    };
    /// Every translation locked, rotation free: a body that only spins in place.
    pub const TRANSLATION: Self = Self {
        translation: [true; 3],
        rotation: [false; 3],
    };

    /// Whether nothing is locked.
    pub fn is_none(&self) -> bool {
        *self == Self::NONE
    }

    /// 1 on the locked translation axes, 0 on the free ones: the `L` of `M⁻¹ = m⁻¹ (𝟙 − L)`.
    pub(crate) fn translation_mask(&self) -> Vec3 {
        mask(self.translation)
    }

    /// 1 on the locked rotation axes, 0 on the free ones.
    fn rotation_mask(&self) -> Vec3 {
        mask(self.rotation)
    }

    /// `v` without its parts along the locked translation axes.
    pub(crate) fn free_linear(&self, velocity: Vec3) -> Vec3 {
        velocity - velocity * self.translation_mask()
    }

    /// `ω` without its parts about the locked rotation axes.
    pub(crate) fn free_angular(&self, velocity: Vec3) -> Vec3 {
        velocity - velocity * self.rotation_mask()
    }

    /// Whether some rotation axis is locked.
    pub(crate) fn locks_rotation(&self) -> bool {
        self.rotation.contains(&true)
    }

    /// The inverse of the world inertia `inertia` restricted to the free rotation axes,
    /// `P (P I P + (𝟙 − P))⁻¹ P`: zero when every rotation is locked.
    pub(crate) fn restrict_inverse_inertia(&self, inertia: Mat3) -> Mat3 {
        let locked = self.rotation_mask();
        let free = Mat3::from_diagonal(Vec3::ONE - locked);
        let restricted = free * inertia * free + Mat3::from_diagonal(locked);
        let determinant = restricted.determinant();
        if !determinant.is_finite() || determinant <= 0.0 {
            return Mat3::ZERO;
        }
        free * restricted.inverse() * free
    }
}

/// 1.0 where `axes` is true, else 0.0.
fn mask(axes: [bool; 3]) -> Vec3 {
    Vec3::from_array(axes.map(|locked| if locked { 1.0 } else { 0.0 }))
}
