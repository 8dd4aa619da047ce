//! Joints against closed forms: pendulum periods, springs, motors, limits, reaction forces,
//! breaking, and chains under heavy loads.

mod armature;
mod chains;
#[path = "../common/mod.rs"]
mod common;
mod coordinates;
mod couplings;
mod drives;
mod friction;
mod friction_threshold;
mod generic;
mod joint_springs;
mod large_groups;
mod pendulums;
mod reactions;
mod set_coordinates;

pub use common::{world, DT, G};
use rebond::{BodyDesc, BodyHandle, Quat, Shape, Vec3, World};

/// A dynamic body that never sleeps, so every sample below is of a moving simulation.
pub fn add(world: &mut World, desc: BodyDesc) -> BodyHandle {
    world.add_body(desc.can_sleep(false)).unwrap()
}

/// A rod of length `length` and mass `mass`, 0.1 m thick, its long axis along Y.
pub fn rod(length: f32, mass: f32) -> BodyDesc {
    BodyDesc::dynamic(Shape::cuboid(Vec3::new(0.05, 0.5 * length, 0.05)).unwrap()).mass(mass)
}

/// The angle of `rotation` about Z, rad (for rotations about Z only).
pub fn angle_about_z(rotation: Quat) -> f32 {
    2.0 * rotation.z.atan2(rotation.w)
}

/// The times at which `samples` (value per step, the first at `t = DT`) cross zero upwards,
/// interpolated linearly between steps.
pub fn upward_crossings(samples: &[f32]) -> Vec<f32> {
    samples
        .windows(2)
        .enumerate()
        .filter(|(_, pair)| pair[0] < 0.0 && pair[1] >= 0.0)
        .map(|(index, pair)| {
            let fraction = -pair[0] / (pair[1] - pair[0]);
            (index as f32 + 1.0 + fraction) * DT
        })
        .collect()
}

/// The mean period between the first and last of `crossings`.
pub fn mean_period(crossings: &[f32]) -> f32 {
    (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f32
}
