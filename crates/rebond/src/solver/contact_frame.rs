//! Frozen contact frames: a contact's normal rows keep the normal and the lever arms the narrow
//! phase last computed them with, for as long as the pair is recycled (rapier's anchor freezing).
//!
//! A contact point's normal row (`parts.rs`, the axis part) is
//!
//! ```text
//! J = [−n₀ᵀ, −(r_A₀ × n₀)ᵀ, n₀ᵀ, (r_B₀ × n₀)ᵀ],    r_A₀ = p₀ − c_A₀,  r_B₀ = p₀ − c_B₀,
//! ```
//!
//! with `n₀` the normal, `p₀` the point and `c_A₀`, `c_B₀` the centres of mass, world axes, at
//! the poses the manifold was computed at. The separation the row corrects still follows the
//! bodies: a recycled manifold's points are carried along with them and measured again each
//! step (`collision/contact_cache.rs`), and within a step `s = s₀ + n₀·(Δc_B − Δc_A) +
//! Δθ_B·(r_B₀ × n₀) − Δθ_A·(r_A₀ × n₀)`.
//!
//! Why not the arms at the step's poses: a box tilted by `θ` on a face carries its centre of mass
//! `θ h` past the middle of the patch (`h` its height above the face), so the normal forces'
//! moment about it falls by `m g h θ`. That negative, geometric stiffness is what makes a chain
//! of contact springs buckle (docs/physics.md: 40 unit boxes need 127 Hz springs, the 100-row
//! flat pyramid about 180 Hz, where the springs are 60 Hz at 4 substeps and 120 Hz at 8). With
//! the arms kept, the rows' moment is the springs' alone while the pair stays within the
//! recycling tolerances (1 mm and 1° of relative motion), and a column or a pyramid stands as
//! its springs do. A pair that moves further gets a fresh manifold, and with it arms at that
//! step's poses: a box that really tips over still falls. A fresh manifold's frame is the step's
//! own, so contacts between bodies that move relative to each other are solved as before.

use crate::collision::manifold::Manifold;
use crate::collision::MAX_MANIFOLD_POINTS;
use crate::math::Vec3;

/// A manifold's normal and each point's lever arms from the two centres of mass, world axes, as
/// the narrow phase computed them. B's arms are A's plus `c_A₀ − c_B₀`, kept once: contacts are
/// copied and sorted every step, and each byte of them costs (callgrind, `pyramid`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct ContactFrame {
    /// `n₀`, from A towards B.
    pub normal: Vec3,
    /// `r_A₀` of each point, m.
    pub arms: [Vec3; MAX_MANIFOLD_POINTS],
    /// `c_A₀ − c_B₀`, m: `r_B₀ = r_A₀ + (c_A₀ − c_B₀)`.
    pub centers: Vec3,
}

impl ContactFrame {
    /// The frame of `manifold`, computed with the centres of mass at `center_a` and `center_b`.
    pub fn new(manifold: &Manifold, center_a: Vec3, center_b: Vec3) -> Self {
        let mut arms = [Vec3::ZERO; MAX_MANIFOLD_POINTS];
        for (point, arm) in manifold.points().iter().zip(&mut arms) {
            *arm = point.position - center_a;
        }
        Self {
            normal: manifold.normal,
            arms,
            centers: center_a - center_b,
        }
    }
}
