//! The contact model: contact constraints solved by sequential impulses with accumulated
//! clamping, soft position correction, Coulomb friction and restitution (`contact_lanes.rs`
//! builds and solves them), and what sets them (the world's settings, the stability cap).
//!
//! Friction acts on the whole manifold at once, at the centre of its points (rapier's simplified
//! friction model): two tangent impulses clamped together to the cone `|λ_t| ≤ μ Σλ_n`, and a
//! twist impulse about the normal clamped to `μ Σλ_n r̄` (`r̄` the mean distance of the points
//! from their centre, an approximation that overstates the spinning friction of a uniformly
//! pressed patch). Against friction at each point, solved by Gauss–Seidel one point after
//! another, a box sliding down an incline decelerates at the closed-form rate and does not start
//! to spin about the normal. Friction is solved in the relax pass only: friction reacting to the
//! position correction's velocities feeds the lean of tall stacks (docs/physics.md). Each
//! contact carries its combined friction and restitution (`Contact::material`).

use super::softness::Softness;

/// Largest contact frequency as a fraction of the substep rate, `ω h ≤ π / 2` (Box2D's cap): a
/// stiffer spring is unstable in the soft step. 60 Hz at 4 substeps of a 60 Hz step, 120 Hz at 8.
pub const CONTACT_HERTZ_PER_SUBSTEP_RATE: f32 = 0.25;

/// What the world's settings say about contacts, for one step.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct ContactSettings {
    /// The contact spring's frequency, Hz, before the cap.
    pub hertz: f32,
    /// The spring's damping ratio.
    pub damping_ratio: f32,
    /// Fastest push-out of overlapping bodies, m/s.
    pub push_speed: f32,
    /// Approach speed below which nothing bounces, m/s.
    pub restitution_threshold: f32,
}

impl ContactSettings {
    /// The contact spring for substep `h` (`1/h` = `inverse_h`), at most
    /// [`CONTACT_HERTZ_PER_SUBSTEP_RATE`] of the substep rate.
    pub fn softness(&self, h: f32, inverse_h: f32) -> Softness {
        Softness::new(
            self.hertz.min(CONTACT_HERTZ_PER_SUBSTEP_RATE * inverse_h),
            self.damping_ratio,
            h,
        )
    }
}
