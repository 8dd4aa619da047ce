//! The contact model: contact constraints solved by sequential impulses with accumulated
//! clamping, soft position correction, Coulomb friction and restitution (`contact_lanes.rs`
//! builds and solves them), and what sets them (the world's settings, the stability cap).
//!
//! Friction acts on the whole manifold at once, at the centre of its points (rapier's simplified
//! friction model): two tangent impulses clamped together to the cone `|λ_t| ≤ μ Σλ_n`, and a
//! twist impulse about the normal clamped to `μ Σλ_n ⟨r⟩`, with `⟨r⟩` the mean distance of the
//! contact patch from its centre under a uniform pressure (`patch_radius_ratio`). Against
//! friction at each point, solved by Gauss–Seidel one point after another, a box sliding down an
//! incline decelerates at the closed-form rate and does not start to spin about the normal.
//! Friction is solved in the relax pass only: friction reacting to the position correction's
//! velocities feeds the lean of tall stacks (docs/physics.md). Each contact carries its combined
//! friction and restitution (`Contact::material`).

use super::softness::Softness;

/// `⟨r⟩ / ρ` of a uniformly pressed patch whose corners are `n` points at the root mean square
/// distance `ρ` from their centre, indexed by `n` (see [`patch_radius_ratio`]). For a regular
/// `n`-gon of circumradius `ρ`, integrating `|x|` over the triangles from its centre to each edge
/// gives `⟨r⟩ = (ρ / 3) [1 + (cos² θ / sin θ) ln((1 + sin θ) / cos θ)]`, `θ = π / n`: 0.460058
/// for a triangle, 0.541075 for a square (0.3826 m for a unit face, whose corners are 0.7071 m
/// out). Two points stand for a line contact, a thin strip whose mean distance is a quarter of
/// its length (`ρ / 2`); one point is a point contact, with no lever arm.
const PATCH_RADIUS_RATIOS: [f32; 5] = [0.0, 0.0, 0.5, 0.460_058, 0.541_075];

/// `⟨r⟩ / ρ` of a round patch, a disc sampled by points on its rim (`ρ` its radius): `2/3`, the
/// limit of the regular polygons' formula as `n` grows.
const ROUND_PATCH_RADIUS_RATIO: f32 = 2.0 / 3.0;

/// The mean distance `⟨r⟩` from its centre of a contact patch under a uniform pressure, the
/// lever arm of the patch's spinning (Coulomb) friction (the twist impulse is clamped to
/// `μ Σλ_n ⟨r⟩`), as a multiple of the root mean square distance `ρ` of the manifold's `count`
/// points from their centre, which the solver measures (`ContactLanes::fill`, four manifolds at
/// once). The patch is the polygon whose corners are the points (a manifold keeps the corners of
/// a face resting on a face), or the disc they sample on its rim when `round` (a cylinder's cap
/// flat on a face, which has more than two points). The ratio is exact for a regular polygon of
/// as many corners (or a disc), so `⟨r⟩` is exact for square and triangular faces, discs, lines
/// and points; a rectangle's is 1.9 % short at sides 2:1, 4.9 % at 4:1.
pub(crate) fn patch_radius_ratio(count: usize, round: bool) -> f32 {
    if round {
        ROUND_PATCH_RADIUS_RATIO
    } else {
        PATCH_RADIUS_RATIOS[count.min(PATCH_RADIUS_RATIOS.len() - 1)]
    }
}

/// Largest contact frequency as a fraction of the substep rate, `ω h ≤ π / 2` (Box2D's cap): a
/// stiffer spring is unstable in the soft step. 60 Hz at 4 substeps of a 60 Hz step, 120 Hz at 8.
pub const CONTACT_HERTZ_PER_SUBSTEP_RATE: f32 = 0.25;

/// What the world's settings say about contacts, for one step.
#[derive(Debug, Clone, Copy, PartialEq)]
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

#[cfg(test)]
mod tests {
    use super::{patch_radius_ratio, PATCH_RADIUS_RATIOS};
    use std::f64::consts::PI;

    #[test]
    fn the_patch_ratios_are_the_regular_polygons_closed_form() {
        for (corners, &ratio) in PATCH_RADIUS_RATIOS.iter().enumerate().skip(3) {
            let angle = PI / corners as f64;
            let (sine, cosine) = angle.sin_cos();
            let exact = (1.0 + cosine * cosine / sine * ((1.0 + sine) / cosine).ln()) / 3.0;
            assert!(
                (f64::from(ratio) - exact).abs() < 1e-6,
                "{corners}: {exact}"
            );
        }
    }

    #[test]
    fn a_unit_square_face_has_the_mean_distance_of_its_area() {
        // ∫|x| dA over the unit square about its centre: (√2 + ln(1 + √2)) / 6; its corners are
        // ρ = √½ m from the centre.
        let exact = (2.0f32.sqrt() + (1.0 + 2.0f32.sqrt()).ln()) / 6.0;
        let rho = 0.5f32.sqrt();
        assert!((patch_radius_ratio(4, false) * rho - exact).abs() < 1e-6);
        // A 1 m line: its two ends are ρ = 0.5 m from the centre, its mean distance 0.25 m.
        assert_eq!(patch_radius_ratio(2, false) * 0.5, 0.25);
        assert_eq!(patch_radius_ratio(1, false), 0.0);
        assert_eq!(patch_radius_ratio(4, true), 2.0 / 3.0);
    }
}
