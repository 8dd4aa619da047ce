//! Box: the points with `|x| ≤ hx`, `|y| ≤ hy`, `|z| ≤ hz`.

use crate::error::{check_size, Error, Result};
use crate::mass::MassProperties;
use crate::math::{Aabb, Mat3, Pose, Vec3};

/// A box centred on the body origin, aligned with the body axes.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Cuboid {
    half_extents: Vec3,
}

impl Cuboid {
    /// A box; each half extent must be finite and positive (error field `half_extents`).
    pub fn new(half_extents: Vec3) -> Result<Self> {
        for (index, value) in half_extents.to_array().into_iter().enumerate() {
            check_size("half_extents", value)
                .map_err(|error| Error::new(format!("half_extents[{index}]"), error.kind))?;
        }
        Ok(Self { half_extents })
    }

    /// A box of positive `half_extents` built inside the engine, where they may lie below
    /// [`MIN_SIZE`](crate::limits::MIN_SIZE): the part of a larger box near another shape.
    pub(crate) fn part(half_extents: Vec3) -> Self {
        Self { half_extents }
    }

    /// Half the size along each local axis, metres.
    pub fn half_extents(&self) -> Vec3 {
        self.half_extents
    }

    /// `m = ρ·8·hx·hy·hz`, `Ixx = m/3·(hy² + hz²)` and likewise.
    pub fn mass_properties(&self, density: f32) -> MassProperties {
        let h = self.half_extents;
        let mass = density * 8.0 * h.x * h.y * h.z;
        let squared = h * h;
        MassProperties {
            mass,
            center_of_mass: Vec3::ZERO,
            inertia: Mat3::from_diagonal(
                mass / 3.0
                    * Vec3::new(
                        squared.y + squared.z,
                        squared.x + squared.z,
                        squared.x + squared.y,
                    ),
            ),
        }
    }

    /// World bounding box at `pose`: half extents `|R|·h`.
    pub fn aabb(&self, pose: &Pose) -> Aabb {
        let rotation = Mat3::from_quat(pose.rotation);
        let absolute = Mat3::from_cols(
            rotation.x_axis.abs(),
            rotation.y_axis.abs(),
            rotation.z_axis.abs(),
        );
        Aabb::from_center_half_extents(pose.position, absolute * self.half_extents)
    }

    /// The corner `sign(d) · h` (a zero component picks the positive side).
    pub fn support(&self, direction: Vec3) -> Vec3 {
        Vec3::ONE.copysign(direction) * self.half_extents
    }
}
