//! The normal impulses of a manifold's points solved together, as one block (Box2D v2.4's block
//! solver idea for two points, here for up to four, in lanes): `K Δλ = r` with `K` the points'
//! effective-mass matrix, factored once a step as `K = L D Lᵀ`.
//!
//! Four points of a face are coplanar, so their `K` has rank three (the face has three degrees
//! of freedom along the normal: one push and two tilts) and the split of a load among the
//! corners is not unique. `K` is regularised on its diagonal by [`REGULARISATION`], which picks
//! the split of least norm: the load shared as evenly as the motion allows.

use super::wide::F32x4;
use crate::collision::MAX_MANIFOLD_POINTS;

/// Fraction of each diagonal entry added to it so a face's rank-deficient `K` factors. Small
/// enough to change a solution by about this fraction, large enough that `f32` keeps the last
/// pivot (about this fraction of the others) to three digits.
const REGULARISATION: f32 = 1.0e-3;

/// Entries of the strictly lower triangle, ordered as `contact_lanes::coupling_index`.
const LOWER: usize = MAX_MANIFOLD_POINTS * (MAX_MANIFOLD_POINTS - 1) / 2;

/// Where `L_ij`, `i > j`, is kept.
const fn lower_index(i: usize, j: usize) -> usize {
    i * (i - 1) / 2 + j
}

/// `K = L D Lᵀ` of four manifolds at once, one per lane: `L` unit lower triangular, `D`
/// diagonal, kept as `1 / D`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct NormalBlock {
    lower: [F32x4; LOWER],
    inverse_pivot: [F32x4; MAX_MANIFOLD_POINTS],
}

impl NormalBlock {
    /// No factor yet: [`Self::factor`] makes one.
    pub const ZERO: Self = Self {
        lower: [F32x4::ZERO; LOWER],
        inverse_pivot: [F32x4::ZERO; MAX_MANIFOLD_POINTS],
    };

    /// Factors the first `count` points' matrix: `diagonal[j] = K_jj` (1 for a point a lane does
    /// not have, whose couplings must be 0) and `coupling(j, i) = K_ij` for `i < j`.
    pub fn factor(
        diagonal: &[F32x4; MAX_MANIFOLD_POINTS],
        coupling: impl Fn(usize, usize) -> F32x4,
        count: usize,
    ) -> Self {
        let mut block = Self::ZERO;
        let mut pivot = [F32x4::ZERO; MAX_MANIFOLD_POINTS];
        for j in 0..count {
            let mut d = diagonal[j] * F32x4::splat(1.0 + REGULARISATION);
            for (k, &pivot_k) in pivot[..j].iter().enumerate() {
                let l = block.lower[lower_index(j, k)];
                d -= l * l * pivot_k;
            }
            pivot[j] = d;
            block.inverse_pivot[j] = F32x4::ONE / d;
            for i in j + 1..count {
                let mut value = coupling(i, j);
                for (k, &pivot_k) in pivot[..j].iter().enumerate() {
                    value -=
                        block.lower[lower_index(i, k)] * block.lower[lower_index(j, k)] * pivot_k;
                }
                block.lower[lower_index(i, j)] = value * block.inverse_pivot[j];
            }
        }
        block
    }

    /// `x` with `K x = r` for the first `count` points.
    pub fn solve(
        &self,
        mut x: [F32x4; MAX_MANIFOLD_POINTS],
        count: usize,
    ) -> [F32x4; MAX_MANIFOLD_POINTS] {
        for i in 1..count {
            for k in 0..i {
                x[i] -= self.lower[lower_index(i, k)] * x[k];
            }
        }
        for (value, &inverse) in x[..count].iter_mut().zip(&self.inverse_pivot) {
            *value = *value * inverse;
        }
        for i in (0..count).rev() {
            for k in i + 1..count {
                x[i] -= self.lower[lower_index(k, i)] * x[k];
            }
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_block_solves_a_well_conditioned_system() {
        // K = [[4, 1, 0.5], [1, 3, 0.2], [0.5, 0.2, 2]] (regularised by 1e-3 on the diagonal).
        let k = [[4.0f32, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]];
        let mut diagonal = [F32x4::ONE; MAX_MANIFOLD_POINTS];
        for i in 0..3 {
            diagonal[i] = F32x4::splat(k[i][i]);
        }
        let block = NormalBlock::factor(&diagonal, |i, j| F32x4::splat(k[i][j]), 3);
        let expected = [1.0f32, -2.0, 0.5];
        let mut rhs = [F32x4::ZERO; MAX_MANIFOLD_POINTS];
        for i in 0..3 {
            let value: f32 = (0..3)
                .map(|j| k[i][j] * expected[j] * if i == j { 1.0 + REGULARISATION } else { 1.0 })
                .sum();
            rhs[i] = F32x4::splat(value);
        }
        let x = block.solve(rhs, 3);
        for i in 0..3 {
            assert!(
                (x[i].lane(0) - expected[i]).abs() < 1e-5,
                "{i}: {}",
                x[i].lane(0)
            );
        }
    }
}
