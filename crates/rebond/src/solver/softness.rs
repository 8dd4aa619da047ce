//! Soft constraints: a constraint that behaves like a stiff damped spring of a chosen frequency
//! instead of a rigid one, so position errors are fixed over a few substeps without adding energy
//! (Catto, "Solver2D" and Box2D v3's soft step).

use std::f32::consts::TAU;

/// Impulse coefficients of a spring of frequency `hertz` and damping ratio `zeta` solved
/// implicitly over a substep `h`:
/// with `ω = 2π·hertz`, `a₁ = 2ζ + hω`, `a₂ = hω·a₁`, `a₃ = 1 / (1 + a₂)`:
/// `bias_rate = ω / a₁`, `mass_scale = a₂·a₃`, `impulse_scale = a₃`.
/// The impulse is then `−m_eff · mass_scale · (v + bias_rate · C) − impulse_scale · λ_total`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Softness {
    /// Fraction of the position error fed back as velocity, 1/s.
    pub bias_rate: f32,
    /// Scales the effective mass (below 1: softer).
    pub mass_scale: f32,
    /// Scales the accumulated impulse subtracted each iteration (the spring's damping of itself).
    pub impulse_scale: f32,
}

impl Softness {
    /// The coefficients for `hertz` (≥ 0; zero gives a rigid constraint with no bias), damping
    /// ratio `zeta` and substep `h` seconds.
    pub fn new(hertz: f32, zeta: f32, h: f32) -> Self {
        if hertz <= 0.0 {
            return Self {
                bias_rate: 0.0,
                mass_scale: 1.0,
                impulse_scale: 0.0,
            };
        }
        let omega = TAU * hertz;
        let a1 = 2.0 * zeta + h * omega;
        let a2 = h * omega * a1;
        let a3 = 1.0 / (1.0 + a2);
        Self {
            bias_rate: omega / a1,
            mass_scale: a2 * a3,
            impulse_scale: a3,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Softness, TAU};

    /// One soft impulse on a unit mass at rest in the constraint's frame, error `x` and velocity
    /// `v`, nothing accumulated, is one step of implicit Euler for the damped spring
    /// `ẍ = −ω² x − 2ζω ẋ`: `v' = (v − h ω² x) / (1 + 2ζωh + ω²h²)`. That is what makes the
    /// constraint a spring of the asked frequency and damping at any stiffness.
    #[test]
    fn a_soft_impulse_is_one_implicit_euler_step_of_the_spring() {
        for (hertz, zeta, h) in [(30.0f32, 1.0f32, 1.0 / 240.0), (120.0, 5.0, 1.0 / 480.0)] {
            let soft = Softness::new(hertz, zeta, h);
            let omega = TAU * hertz;
            for (x, v) in [(-0.01f32, 0.0f32), (0.02, -1.5), (0.0, 2.0)] {
                let impulse = -soft.mass_scale * (v + soft.bias_rate * x);
                let expected = (v - h * omega * omega * x)
                    / (1.0 + 2.0 * zeta * omega * h + (omega * h).powi(2));
                let got = v + impulse;
                assert!(
                    (got - expected).abs() <= 1.0e-5 * (1.0 + expected.abs()),
                    "{hertz} Hz, ζ {zeta}: v' = {got}, implicit Euler gives {expected}"
                );
            }
            // An accumulated impulse `λ` is the spring's own force so far: the next impulse
            // takes back the share `impulse_scale = 1 − mass_scale` of it.
            assert!((soft.impulse_scale + soft.mass_scale - 1.0).abs() < 1.0e-6);
        }
    }

    #[test]
    fn zero_hertz_is_a_rigid_constraint_without_bias() {
        let rigid = Softness::new(0.0, 5.0, 1.0 / 240.0);
        assert_eq!(
            rigid,
            Softness {
                bias_rate: 0.0,
                mass_scale: 1.0,
                impulse_scale: 0.0
            }
        );
    }
}
