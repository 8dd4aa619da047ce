//! SplitMix64: a tiny deterministic generator, so every run of a test or benchmark sees the same
//! cases. Shared by the integration tests, the benchmarks (through `#[path]`) and the unit tests
//! of the collision module (through the dynamic tree's).
#![allow(dead_code)]

use glam::Vec3;

/// The generator's state; seed it with any value.
pub struct Random(pub u64);

impl Random {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `[low, high)`.
    pub fn range(&mut self, low: f32, high: f32) -> f32 {
        let unit = (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32;
        low + (high - low) * unit
    }

    /// True with the given probability.
    pub fn chance(&mut self, probability: f32) -> bool {
        self.range(0.0, 1.0) < probability
    }

    /// Uniform in `0..bound`.
    pub fn below(&mut self, bound: usize) -> usize {
        (self.next_u64() % bound as u64) as usize
    }

    /// Each coordinate uniform in `[low, high)`.
    pub fn vec3(&mut self, low: f32, high: f32) -> Vec3 {
        Vec3::new(
            self.range(low, high),
            self.range(low, high),
            self.range(low, high),
        )
    }

    /// A unit vector, uniform on the sphere (rejection from the cube, then normalised).
    pub fn unit_vector(&mut self) -> Vec3 {
        loop {
            let v = self.vec3(-1.0, 1.0);
            if (0.01..=1.0).contains(&v.length_squared()) {
                return v.normalize();
            }
        }
    }
}
