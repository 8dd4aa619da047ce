//! The contact model: contact constraints solved by sequential impulses with accumulated
//! clamping, soft position correction, Coulomb friction and restitution (`contact_lanes.rs`
//! builds and solves them), and its constants.
//!
//! Friction acts on the whole manifold at once, at the centre of its points, as Box3D and Jolt
//! do: two tangent impulses clamped together to the cone `|λ_t| ≤ μ Σλ_n`, and a twist impulse
//! about the normal clamped to `μ Σλ_n r̄` (`r̄` the mean distance of the points from their
//! centre). Measured against friction at each point (which Gauss–Seidel solves one point after
//! another), a box sliding down a 35° incline with μ = 0.5 then decelerates at the closed-form
//! rate instead of 5 % too little, and no longer starts to spin about the normal. Friction is
//! solved in the relax pass only: friction reacting to the position correction's velocities
//! feeds the lean of tall stacks (docs/physics.md).

/// Bodies approaching faster than this, m/s, bounce with their restitution; slower ones stay
/// down, so resting bodies do not jitter.
pub const RESTITUTION_THRESHOLD: f32 = 1.0;

/// Fastest a soft contact pushes overlapping bodies apart, m/s.
pub const MAX_PUSH_SPEED: f32 = 3.0;

/// Stiffness of contacts, Hz, capped at [`CONTACT_HERTZ_PER_SUBSTEP_RATE`] of the substep rate so
/// the spring stays stable: 60 Hz at 4 substeps of a 60 Hz step, 120 Hz from 8 (the default).
/// A contact's steady sag under a load is `load / (m_eff ω²)`: between two unit boxes, 0.14 mm
/// per box resting on it at 60 Hz, 0.035 mm at 120 Hz. Stiffer contacts also let taller stacks
/// stand: a stack of soft contacts leans under its own weight and buckles past a height that
/// grows with the stiffness (docs/physics.md, "Soft stacks lean").
pub const CONTACT_HERTZ: f32 = 120.0;

/// Largest contact frequency as a fraction of the substep rate, `ω h ≤ π / 2` (Box2D's cap): 60 Hz
/// at 4 substeps at 60 Hz. A 20-box column of unit boxes buckles below about 47 Hz
/// (docs/physics.md); at the former cap of 1/8, 30 Hz, it toppled.
pub const CONTACT_HERTZ_PER_SUBSTEP_RATE: f32 = 0.25;

/// Damping ratio of contacts: over-damped, so corrections never bounce. At 4 substeps a 20-box
/// column rocked at up to 0.2 m/s with 10 and stayed within 0.05 m/s with 5 (measured with the
/// former rigid zone within a 1 mm slop; without it, both come to rest).
pub const CONTACT_DAMPING_RATIO: f32 = 5.0;

/// How two bodies' friction coefficients combine: the geometric mean `√(μ_A μ_B)` (equal values
/// give that value; a frictionless body makes the contact frictionless).
pub fn combine_friction(a: f32, b: f32) -> f32 {
    (a * b).sqrt()
}

/// How two bodies' restitutions combine: the larger one (a bouncy ball bounces on anything).
pub fn combine_restitution(a: f32, b: f32) -> f32 {
    a.max(b)
}
