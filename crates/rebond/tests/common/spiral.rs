//! Roughly uniform unit directions on a Fibonacci spiral, shared by the tests that search every
//! direction for the least overlap of two shapes.

use glam::Vec3;

/// `count` roughly uniform unit directions on a Fibonacci spiral.
pub fn spiral_directions(count: usize) -> Vec<Vec3> {
    let golden_angle = std::f32::consts::PI * (3.0 - 5.0f32.sqrt());
    (0..count)
        .map(|index| {
            let y = 1.0 - 2.0 * (index as f32 + 0.5) / count as f32;
            let ring = (1.0 - y * y).max(0.0).sqrt();
            let angle = golden_angle * index as f32;
            Vec3::new(ring * angle.cos(), y, ring * angle.sin())
        })
        .collect()
}
