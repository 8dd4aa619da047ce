//! The contact model: contact constraints solved by sequential impulses with accumulated
//! clamping, soft position correction, Coulomb friction and restitution (`contact_lanes.rs`
//! builds and solves them), and what sets them (the world's settings, the stability cap).
//!
//! Friction acts on the whole manifold at once, at the centre of its points (rapier's simplified
//! friction model): two tangent impulses and a twist impulse about the normal kept together
//! within the ellipsoid `(|λ_t| / μΣλ_n)² + (λ_tw / μΣλ_n⟨r⟩)² ≤ 1`
//! (`limit_surface_projection`), with `⟨r⟩` the mean distance of the contact patch from its
//! centre under a uniform pressure (`patch_radius_ratio`). Against friction at each point,
//! solved by Gauss–Seidel one point after another, a box sliding down an incline decelerates at
//! the closed-form rate and does not start to spin about the normal.
//! Friction is solved in the relax pass only: friction reacting to the position correction's
//! velocities feeds the lean of tall stacks (docs/physics.md). Each contact carries its combined
//! friction and restitution (`Contact::material`).

use super::parts::inverse_or_zero;
use super::softness::Softness;
use super::wide::F32x4;

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
/// lever arm of the patch's spinning (Coulomb) friction (the twist impulse alone is bounded by
/// `μ Σλ_n ⟨r⟩`, [`limit_surface_projection`]), as a multiple of the root mean square distance
/// `ρ` of the manifold's `count` points from their centre, which the solver measures
/// (`ContactLanes::fill`, four manifolds at once). The patch is the polygon whose corners are the points (a manifold keeps the corners of
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

/// Newton steps of the friction projection ([`limit_surface_projection`]): the first is exact
/// where the tangents and the twist weigh alike, `m_t ⟨r⟩² / I_n` = 1; two leave the nearest
/// point exact to rounding at 0.88 (a square box or a disc flat on the ground is near 0.9) and
/// 1.3e-4 off at 0.25 (the unit tests). The result is scaled onto the surface after them, so it
/// always lies on it.
const LIMIT_SURFACE_NEWTON_STEPS: usize = 2;

/// Largest trial friction impulse kept, as a multiple of its bound: a trial this far out stops a
/// body whose load has all but vanished, and the bound keeps the projection's squares finite
/// however small the load.
const MAX_TRIAL_OVER_BOUND: f32 = 1.0e6;

/// The friction impulses of four manifolds, two tangents and the twist about the normal, kept
/// inside one limit: the ellipsoid `(|λ_t| / μN)² + (λ_tw / μN⟨r⟩)² ≤ 1` (the limit surface of
/// Goyal, Ruina & Papadopoulos, in the ellipsoid form of Howe & Cutkosky), `μN` = `limit`,
/// `⟨r⟩` = `radius`. Coulomb friction under a uniform pressure holds a patch that slides and
/// spins with less force and less torque than it holds one that only slides or only spins, so
/// the two tangents and the twist share one bound where each clamped alone would take both
/// maxima at once.
///
/// A `trial` impulse outside is moved to the point of the ellipsoid nearest it in the metric of
/// the effective `masses`, `Σ (x_i − y_i)² / m_i`: the impulse within the limit that leaves
/// the least kinetic energy, so the bodies' velocity after it is normal to the surface there, the
/// sliding the maximum-dissipation principle gives that friction (force and torque in proportion
/// to `μN v` and `μN⟨r⟩² ω`). A plain scaling of the trial would instead set them in proportion
/// to `m_t v` and `I_n ω`. The nearest point is `x_i = y_i / (1 + κ m_i / a_i²)`, `a_i` the
/// semi-axis, for the `κ ≥ 0` that puts it on the surface; Newton's method on
/// `1 − 1 / ‖x(κ) / a‖`, concave in `κ` (Moré & Sorensen's trust-region step), rises to that
/// `κ` from 0 without passing it. A component whose bound is zero (no load, or no twist lever,
/// `⟨r⟩ = 0`) holds nothing, so the tangents alone then keep to the circle `|λ_t| ≤ μN`; one no
/// impulse moves (no mass) is set to zero when the trial is outside.
#[inline(always)]
pub(crate) fn limit_surface_projection(
    trial: [F32x4; 3],
    masses: [F32x4; 3],
    limit: F32x4,
    radius: F32x4,
) -> [F32x4; 3] {
    let zero = F32x4::ZERO;
    let bounds = [limit, limit, limit * radius];
    // A bound holds where it is a positive normal number, so that its inverse is finite.
    let holds = |bound: F32x4| bound.greater_than(F32x4::splat(f32::MIN_POSITIVE));
    let (tangents_hold, twist_holds) = (holds(limit), holds(bounds[2]));
    let inverse_limit = tangents_hold.select(F32x4::ONE / limit, zero);
    let inverse_twist_limit = twist_holds.select(F32x4::ONE / bounds[2], zero);
    let kept = [
        tangents_hold.select(trial[0], zero),
        tangents_hold.select(trial[1], zero),
        twist_holds.select(trial[2], zero),
    ];
    // The trial over the bounds, `y_i / a_i`, is inside where `Σ (y_i / a_i)² ≤ 1`.
    let inside = [
        kept[0] * inverse_limit,
        kept[1] * inverse_limit,
        kept[2] * inverse_twist_limit,
    ];
    let square_norm = inside[0] * inside[0] + inside[1] * inside[1] + inside[2] * inside[2];
    let outside = square_norm.greater_than(F32x4::ONE);
    if !outside.any() {
        return kept;
    }
    // The metric's weights over the squared bounds, `m_i / a_i²`, all times `(μN)²`: the
    // twist's `m_tw / ⟨r⟩²`, with `1 / ⟨r⟩ = μN / μN⟨r⟩`. A component with no weight (no
    // mass), or none that is finite, holds nothing.
    let inverse_radius = limit * inverse_twist_limit;
    let weights = [
        masses[0],
        masses[1],
        masses[2] * inverse_radius * inverse_radius,
    ];
    let free = |axis: usize| {
        let weight = weights[axis];
        weight
            .greater_than(zero)
            .and(F32x4::splat(f32::MAX).greater_than(weight))
    };
    let free = [free(0), free(1), free(2)];
    let weights = [
        free[0].select(weights[0], zero),
        free[1].select(weights[1], zero),
        free[2].select(weights[2], zero),
    ];
    // Kept finite however far out.
    let bounded = |axis: usize| {
        let ratio = inside[axis]
            .max(F32x4::splat(-MAX_TRIAL_OVER_BOUND))
            .min(F32x4::splat(MAX_TRIAL_OVER_BOUND));
        free[axis].select(ratio, zero)
    };
    let scaled = [bounded(0), bounded(1), bounded(2)];
    // At `κ`: `x_i / a_i`, `‖x / a‖²`, and `Σ (x_i / a_i)² w_i / (1 + κ w_i)`, minus half the
    // slope of `‖x / a‖²` in `κ`; Newton's step on `1 − 1 / ‖x / a‖` is then
    // `‖x / a‖² (‖x / a‖ − 1) / Σ …`.
    let mut square_norm = zero;
    let mut slope = zero;
    for (&ratio, &weight) in scaled.iter().zip(&weights) {
        square_norm += ratio * ratio;
        slope += ratio * ratio * weight;
    }
    let mut kappa = zero;
    let mut shrunk = scaled;
    for _ in 0..LIMIT_SURFACE_NEWTON_STEPS {
        let step = square_norm * (square_norm.sqrt() - F32x4::ONE) * inverse_or_zero(slope);
        kappa += outside.select(step, zero);
        square_norm = zero;
        slope = zero;
        for axis in 0..3 {
            let factor = F32x4::ONE / (F32x4::ONE + kappa * weights[axis]);
            shrunk[axis] = scaled[axis] * factor;
            let square = shrunk[axis] * shrunk[axis];
            square_norm += square;
            slope += square * weights[axis] * factor;
        }
    }
    let onto_surface = inverse_or_zero(square_norm.sqrt());
    let projected =
        |axis: usize| outside.select(shrunk[axis] * onto_surface * bounds[axis], kept[axis]);
    [projected(0), projected(1), projected(2)]
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
    use super::{limit_surface_projection, patch_radius_ratio, PATCH_RADIUS_RATIOS};
    use crate::solver::wide::F32x4;
    use std::f64::consts::PI;

    /// Projects the trials `[t₁, t₂, tw]` of four lanes, given per lane as rows.
    fn project(
        trials: [[f32; 3]; 4],
        masses: [[f32; 3]; 4],
        limits: [f32; 4],
        radii: [f32; 4],
    ) -> [[f32; 3]; 4] {
        let column = |rows: [[f32; 3]; 4], axis: usize| {
            F32x4::from_array(std::array::from_fn(|lane| rows[lane][axis]))
        };
        let result = limit_surface_projection(
            std::array::from_fn(|axis| column(trials, axis)),
            std::array::from_fn(|axis| column(masses, axis)),
            F32x4::from_array(limits),
            F32x4::from_array(radii),
        );
        std::array::from_fn(|lane| std::array::from_fn(|axis| result[axis].lane(lane)))
    }

    #[test]
    fn a_trial_within_the_limit_surface_is_kept() {
        let trial = [0.3, -0.4, 0.2];
        let [kept, ..] = project([trial; 4], [[1.0, 1.0, 0.2]; 4], [1.0; 4], [0.5; 4]);
        assert_eq!(kept, trial);
    }

    #[test]
    fn a_trial_outside_lands_on_the_surface_where_the_sliding_is_normal_to_it() {
        // Tangents and twist weighing differently (`m_t ⟨r⟩² / I_n` from 0.25 to 10), and
        // trials from just outside to a hundred times out.
        let lanes = [
            ([1.5, 0.5, 0.8], [1.0, 1.0, 0.166_7], 1.0, 0.383),
            ([30.0, -80.0, 12.0], [2.0, 1.7, 0.1], 0.5, 0.3),
            ([0.9, 0.0, -0.4], [1.0, 1.0, 2.0], 1.0, 0.7),
            ([-0.2, 0.1, 40.0], [1.0, 0.9, 0.001], 0.2, 0.1),
        ];
        let result = project(
            lanes.map(|lane| lane.0),
            lanes.map(|lane| lane.1),
            lanes.map(|lane| lane.2),
            lanes.map(|lane| lane.3),
        );
        for ((trial, masses, limit, radius), x) in lanes.into_iter().zip(result) {
            let bounds = [limit, limit, limit * radius];
            let surface: f32 = (0..3).map(|i| (x[i] / bounds[i]).powi(2)).sum();
            assert!((surface - 1.0).abs() < 1e-5, "{x:?}: {surface}");
            // The velocity after the impulse, `(x − y) / m`, is along the surface's normal
            // `x / a²` with one positive factor `κ` (the nearest point in the masses' metric):
            // to 1e-3 of it after the two Newton steps, with weights `m_i / a_i²` up to 10×
            // apart (measured: 1.3e-4 at most).
            let kappas: Vec<f32> = (0..3)
                .filter(|&i| trial[i] != 0.0)
                .map(|i| (trial[i] - x[i]) / masses[i] / (x[i] / bounds[i].powi(2)))
                .collect();
            for &kappa in &kappas {
                assert!(kappa > 0.0, "{kappas:?}");
                assert!((kappa - kappas[0]).abs() < 1e-3 * kappas[0], "{kappas:?}");
            }
        }
    }

    #[test]
    fn without_a_load_a_lever_or_a_mass_the_component_holds_nothing() {
        let trial = [3.0, 4.0, 2.0];
        let result = project(
            [trial, trial, trial, [1e30, -1e30, 1e30]],
            [
                [1.0, 1.0, 0.2],
                [1.0, 1.0, 0.2],
                [1.0, 0.0, 0.2],
                [1.0, 1.0, 0.2],
            ],
            [0.0, 1.0, 1.0, 1e-37],
            [0.5, 0.0, 0.5, 0.5],
        );
        assert_eq!(result[0], [0.0; 3], "no load");
        // No twist lever: the tangents keep to the circle `|λ_t| ≤ μN`, in proportion.
        let [t1, t2, twist] = result[1];
        assert!((t1 - 0.6).abs() < 1e-6 && (t2 - 0.8).abs() < 1e-6 && twist == 0.0);
        assert_eq!(result[2][1], 0.0, "a direction nothing moves along");
        // A vanishing load under a huge trial: on the surface, finite.
        let surface: f32 = (0..3)
            .map(|i| (result[3][i] / [1e-37, 1e-37, 0.5e-37][i]).powi(2))
            .sum();
        assert!((surface - 1.0).abs() < 1e-5, "{:?}", result[3]);
    }

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
