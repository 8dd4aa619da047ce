//! Four-lane f32 arithmetic for the wide contact solver: one value of each of four constraints.
//!
//! Each operation works lane by lane on a 16-byte aligned `[f32; 4]`, written so the optimiser
//! turns it into a single SSE (or NEON) instruction; no `unsafe`, and the same result on every
//! target. Lane `i` of every operation computes exactly what the scalar operation computes on lane
//! `i` of its inputs, in the same order: no fused multiply-add, so results are bit-identical from
//! run to run.

use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

use crate::math::Vec3A;

/// Four f32 lanes.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[repr(C, align(16))]
pub(crate) struct F32x4(pub [f32; 4]);

/// Four lane masks: all bits set where a comparison held, zero where it did not.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[repr(C, align(16))]
pub(crate) struct Mask4([u32; 4]);

impl F32x4 {
    pub const ZERO: Self = Self([0.0; 4]);
    pub const ONE: Self = Self([1.0; 4]);

    /// The same value in every lane.
    pub const fn splat(value: f32) -> Self {
        Self([value; 4])
    }

    fn map(self, f: impl Fn(f32) -> f32) -> Self {
        Self(self.0.map(f))
    }

    fn zip(self, other: Self, f: impl Fn(f32, f32) -> f32) -> Self {
        let (a, b) = (self.0, other.0);
        Self([f(a[0], b[0]), f(a[1], b[1]), f(a[2], b[2]), f(a[3], b[3])])
    }

    fn compare(self, other: Self, f: impl Fn(f32, f32) -> bool) -> Mask4 {
        let (a, b) = (self.0, other.0);
        let lane = |i: usize| if f(a[i], b[i]) { u32::MAX } else { 0 };
        Mask4([lane(0), lane(1), lane(2), lane(3)])
    }

    /// `max(self, other)` per lane (`other` where either is NaN).
    pub fn max(self, other: Self) -> Self {
        self.zip(other, |a, b| if a > b { a } else { b })
    }

    /// `min(self, other)` per lane (`other` where either is NaN).
    pub fn min(self, other: Self) -> Self {
        self.zip(other, |a, b| if a < b { a } else { b })
    }

    /// Square root per lane.
    pub fn sqrt(self) -> Self {
        self.map(f32::sqrt)
    }

    /// Where `self > other`.
    pub fn greater_than(self, other: Self) -> Mask4 {
        self.compare(other, |a, b| a > b)
    }

    /// Where `self < other`.
    pub fn less_than(self, other: Self) -> Mask4 {
        self.compare(other, |a, b| a < b)
    }
}

impl Mask4 {
    /// No lane set.
    pub const NONE: Self = Self([0; 4]);

    /// `if_set` where the mask is set, `otherwise` elsewhere, per lane.
    pub fn select(self, if_set: F32x4, otherwise: F32x4) -> F32x4 {
        let (m, a, b) = (self.0, if_set.0, otherwise.0);
        let lane = |i: usize| f32::from_bits((a[i].to_bits() & m[i]) | (b[i].to_bits() & !m[i]));
        F32x4([lane(0), lane(1), lane(2), lane(3)])
    }

    /// Lanes set in either mask.
    pub fn or(self, other: Self) -> Self {
        let (a, b) = (self.0, other.0);
        Self([a[0] | b[0], a[1] | b[1], a[2] | b[2], a[3] | b[3]])
    }

    /// Whether lane `lane` is set.
    pub fn lane(self, lane: usize) -> bool {
        self.0[lane] != 0
    }
}

impl Add for F32x4 {
    type Output = Self;
    fn add(self, other: Self) -> Self {
        self.zip(other, |a, b| a + b)
    }
}

impl Sub for F32x4 {
    type Output = Self;
    fn sub(self, other: Self) -> Self {
        self.zip(other, |a, b| a - b)
    }
}

impl Mul for F32x4 {
    type Output = Self;
    fn mul(self, other: Self) -> Self {
        self.zip(other, |a, b| a * b)
    }
}

impl Div for F32x4 {
    type Output = Self;
    fn div(self, other: Self) -> Self {
        self.zip(other, |a, b| a / b)
    }
}

impl Neg for F32x4 {
    type Output = Self;
    fn neg(self) -> Self {
        self.map(|a| -a)
    }
}

impl AddAssign for F32x4 {
    fn add_assign(&mut self, other: Self) {
        *self = *self + other;
    }
}

impl SubAssign for F32x4 {
    fn sub_assign(&mut self, other: Self) {
        *self = *self - other;
    }
}

/// Four 3-vectors, one per lane, stored as a structure of arrays.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Vec3x4 {
    pub x: F32x4,
    pub y: F32x4,
    pub z: F32x4,
}

impl Vec3x4 {
    /// Lane `i` holds `vectors[i]`.
    pub fn from_lanes(vectors: [Vec3A; 4]) -> Self {
        let [a, b, c, d] = vectors;
        Self {
            x: F32x4([a.x, b.x, c.x, d.x]),
            y: F32x4([a.y, b.y, c.y, d.y]),
            z: F32x4([a.z, b.z, c.z, d.z]),
        }
    }

    /// The vector of lane `lane`.
    pub fn lane(&self, lane: usize) -> Vec3A {
        Vec3A::new(self.x.0[lane], self.y.0[lane], self.z.0[lane])
    }

    /// `x·x' + y·y' + z·z'` per lane.
    pub fn dot(self, other: Self) -> F32x4 {
        self.x * other.x + self.y * other.y + self.z * other.z
    }

    /// Each lane's vector times that lane's scalar.
    pub fn scale(self, factor: F32x4) -> Self {
        Self {
            x: self.x * factor,
            y: self.y * factor,
            z: self.z * factor,
        }
    }
}

impl Add for Vec3x4 {
    type Output = Self;
    fn add(self, other: Self) -> Self {
        Self {
            x: self.x + other.x,
            y: self.y + other.y,
            z: self.z + other.z,
        }
    }
}

impl Sub for Vec3x4 {
    type Output = Self;
    fn sub(self, other: Self) -> Self {
        Self {
            x: self.x - other.x,
            y: self.y - other.y,
            z: self.z - other.z,
        }
    }
}

impl AddAssign for Vec3x4 {
    fn add_assign(&mut self, other: Self) {
        *self = *self + other;
    }
}

impl SubAssign for Vec3x4 {
    fn sub_assign(&mut self, other: Self) {
        *self = *self - other;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_compute_what_scalars_compute() {
        let a = F32x4([1.0, -2.0, 3.5, 0.0]);
        let b = F32x4([0.5, 4.0, -1.0, 0.0]);
        assert_eq!((a + b).0, [1.5, 2.0, 2.5, 0.0]);
        assert_eq!((a * b - a / F32x4::splat(2.0)).0, [0.0, -7.0, -5.25, 0.0]);
        assert_eq!(a.max(b).0, [1.0, 4.0, 3.5, 0.0]);
        assert_eq!(a.min(b).0, [0.5, -2.0, -1.0, 0.0]);
        let mask = a.greater_than(b);
        assert_eq!(mask.select(a, -b).0, [1.0, -4.0, 3.5, -0.0]);
        assert!(mask.lane(0) && !mask.lane(1) && !a.less_than(b).or(mask).lane(3));
    }

    #[test]
    fn vectors_round_trip_through_lanes() {
        let vectors = [0, 1, 2, 3].map(|i| Vec3A::new(i as f32, 2.0 * i as f32, -1.0));
        let lanes = Vec3x4::from_lanes(vectors);
        assert_eq!([0, 1, 2, 3].map(|i| lanes.lane(i)), vectors);
        assert_eq!(lanes.dot(lanes).0, [1.0, 6.0, 21.0, 46.0]);
    }
}
