//! Four-lane f32 arithmetic for the wide contact solver: one value of each of four constraints.
//!
//! [`F32x4`] wraps glam's `Vec4`, which is one SSE register on x86-64 (NEON on aarch64, plain
//! arrays elsewhere), so each operation is one vector instruction, with no `unsafe` here. Lane `i`
//! of every operation computes what the scalar operation computes on lane `i` of its inputs: no
//! fused multiply-add, so results are bit-identical from run to run.

use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

use glam::{BVec4A, Mat4, Vec4};

use crate::math::{Mat3, Vec3, Vec3A};

/// Lanes in a wide value: constraints solved at once, one per lane.
pub const LANES: usize = 4;

/// Four f32 lanes.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct F32x4(Vec4);

/// Four lane masks: set where a comparison held.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct Mask4(BVec4A);

impl F32x4 {
    pub const ZERO: Self = Self(Vec4::ZERO);
    pub const ONE: Self = Self(Vec4::ONE);

    /// The same value in every lane.
    pub const fn splat(value: f32) -> Self {
        Self(Vec4::splat(value))
    }

    /// Lane `i` holds `values[i]`.
    pub fn from_array(values: [f32; LANES]) -> Self {
        Self(Vec4::from_array(values))
    }

    /// The lanes as an array.
    pub fn to_array(self) -> [f32; LANES] {
        self.0.to_array()
    }

    /// The value of lane `lane`.
    pub fn lane(self, lane: usize) -> f32 {
        self.0[lane]
    }

    /// The sum of the four lanes, `(l₀ + l₁) + (l₂ + l₃)`.
    pub fn sum(self) -> f32 {
        (self.0.x + self.0.y) + (self.0.z + self.0.w)
    }

    /// `max(self, other)` per lane.
    pub fn max(self, other: Self) -> Self {
        Self(self.0.max(other.0))
    }

    /// `min(self, other)` per lane.
    pub fn min(self, other: Self) -> Self {
        Self(self.0.min(other.0))
    }

    /// Square root per lane.
    pub fn sqrt(self) -> Self {
        Self(self.0.sqrt())
    }

    /// Where `self > other`.
    pub fn greater_than(self, other: Self) -> Mask4 {
        Mask4(self.0.cmpgt(other.0))
    }

    /// Sets lane `lane` to `value`.
    pub fn set_lane(&mut self, lane: usize, value: f32) {
        self.0[lane] = value;
    }
}

impl Mask4 {
    /// No lane set.
    pub const NONE: Self = Self(BVec4A::FALSE);

    /// `if_set` where the mask is set, `otherwise` elsewhere, per lane.
    pub fn select(self, if_set: F32x4, otherwise: F32x4) -> F32x4 {
        F32x4(Vec4::select(self.0, if_set.0, otherwise.0))
    }

    /// Lanes set in both masks.
    pub fn and(self, other: Self) -> Self {
        Self(self.0 & other.0)
    }

    /// Lanes set in either mask.
    pub fn or(self, other: Self) -> Self {
        Self(self.0 | other.0)
    }

    /// Whether any lane is set.
    pub fn any(self) -> bool {
        self.0.any()
    }
}

impl Add for F32x4 {
    type Output = Self;
    fn add(self, other: Self) -> Self {
        Self(self.0 + other.0)
    }
}

impl Sub for F32x4 {
    type Output = Self;
    fn sub(self, other: Self) -> Self {
        Self(self.0 - other.0)
    }
}

impl Mul for F32x4 {
    type Output = Self;
    fn mul(self, other: Self) -> Self {
        Self(self.0 * other.0)
    }
}

impl Div for F32x4 {
    type Output = Self;
    fn div(self, other: Self) -> Self {
        Self(self.0 / other.0)
    }
}

impl Neg for F32x4 {
    type Output = Self;
    fn neg(self) -> Self {
        Self(-self.0)
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
    /// Zero in every lane.
    pub const ZERO: Self = Self {
        x: F32x4::ZERO,
        y: F32x4::ZERO,
        z: F32x4::ZERO,
    };

    /// Sets lane `lane` to `vector`.
    pub fn set_lane(&mut self, lane: usize, vector: Vec3A) {
        self.x.set_lane(lane, vector.x);
        self.y.set_lane(lane, vector.y);
        self.z.set_lane(lane, vector.z);
    }

    /// Lane `i` holds `vectors[i]`: a 4×4 transpose (glam's, a few shuffles).
    pub fn from_lanes(vectors: [Vec3A; 4]) -> Self {
        let [a, b, c, d] = vectors;
        let rows =
            Mat4::from_cols(a.extend(0.0), b.extend(0.0), c.extend(0.0), d.extend(0.0)).transpose();
        Self {
            x: F32x4(rows.x_axis),
            y: F32x4(rows.y_axis),
            z: F32x4(rows.z_axis),
        }
    }

    /// The vector of each lane: the transpose back.
    pub fn lanes(&self) -> [Vec3A; 4] {
        let columns = Mat4::from_cols(self.x.0, self.y.0, self.z.0, Vec4::ZERO).transpose();
        [
            Vec3A::from_vec4(columns.x_axis),
            Vec3A::from_vec4(columns.y_axis),
            Vec3A::from_vec4(columns.z_axis),
            Vec3A::from_vec4(columns.w_axis),
        ]
    }

    /// `self × other` per lane.
    pub fn cross(self, other: Self) -> Self {
        Self {
            x: self.y * other.z - self.z * other.y,
            y: self.z * other.x - self.x * other.z,
            z: self.x * other.y - self.y * other.x,
        }
    }

    /// `x·x' + y·y' + z·z'` per lane.
    pub fn dot(self, other: Self) -> F32x4 {
        self.x * other.x + self.y * other.y + self.z * other.z
    }

    /// The parts of each lane's vector along the axes where `mask` is 1 (`mask` 0 or 1 per
    /// axis): `x·m_x, y·m_y, z·m_z`.
    pub fn masked(self, mask: Self) -> Self {
        Self {
            x: self.x * mask.x,
            y: self.y * mask.y,
            z: self.z * mask.z,
        }
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

/// Four 3×3 matrices, one per lane, by columns.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Mat3x4 {
    x_axis: Vec3x4,
    y_axis: Vec3x4,
    z_axis: Vec3x4,
}

impl Mat3x4 {
    /// Lane `i` holds `matrices[i]`.
    pub fn from_lanes(matrices: [&Mat3; 4]) -> Self {
        let column = |axis: fn(&Mat3) -> Vec3| {
            Vec3x4::from_lanes(matrices.map(|matrix| Vec3A::from(axis(matrix))))
        };
        Self {
            x_axis: column(|matrix| matrix.x_axis),
            y_axis: column(|matrix| matrix.y_axis),
            z_axis: column(|matrix| matrix.z_axis),
        }
    }

    /// `M v` per lane, `x_axis·v.x + y_axis·v.y + z_axis·v.z` (glam's order).
    pub fn mul_vec3(&self, vector: Vec3x4) -> Vec3x4 {
        self.x_axis.scale(vector.x) + self.y_axis.scale(vector.y) + self.z_axis.scale(vector.z)
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
        let a = F32x4::from_array([1.0, -2.0, 3.5, 0.0]);
        let b = F32x4::from_array([0.5, 4.0, -1.0, 0.0]);
        assert_eq!((a + b).0.to_array(), [1.5, 2.0, 2.5, 0.0]);
        assert_eq!(
            (a * b - a / F32x4::splat(2.0)).0.to_array(),
            [0.0, -7.0, -5.25, 0.0]
        );
        assert_eq!(a.max(b).0.to_array(), [1.0, 4.0, 3.5, 0.0]);
        assert_eq!(a.min(b).0.to_array(), [0.5, -2.0, -1.0, 0.0]);
        let mask = a.greater_than(b);
        assert_eq!(mask.select(a, -b).0.to_array(), [1.0, -4.0, 3.5, -0.0]);
        assert_eq!(
            mask.and(mask).select(a, b).0.to_array(),
            [1.0, 4.0, 3.5, 0.0]
        );
        assert!(mask.any() && !b.greater_than(b).any());
    }

    #[test]
    fn vectors_round_trip_through_lanes() {
        let vectors = [0, 1, 2, 3].map(|i| Vec3A::new(i as f32, 2.0 * i as f32, -1.0));
        let lanes = Vec3x4::from_lanes(vectors);
        assert_eq!(lanes.lanes(), vectors);
        assert_eq!(lanes.dot(lanes).0.to_array(), [1.0, 6.0, 21.0, 46.0]);
    }
}
