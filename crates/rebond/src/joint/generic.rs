//! The generic joint's axes, their freedoms and its coordinates ([`super`] describes it).

use super::{relative_rotation, JointFrames};
use crate::math::{Quat, Vec3};

/// One of a generic joint's six axes, in the joint frame
/// ([`JointDesc::frame`](super::JointDesc::frame)) as fixed in `body_a`: three slides and three
/// rotations.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum GenericAxis {
    /// The slide of `body_b`'s anchor from `body_a`'s along the frame's X axis, m.
    X,
    /// The same along Y, m.
    Y,
    /// The same along Z, m.
    Z,
    /// The rotation about the frame's X axis, rad.
    RotX,
    /// The rotation about Y, rad.
    RotY,
    /// The rotation about Z, rad.
    RotZ,
}

impl GenericAxis {
    /// The six axes, in the order of [`JointDesc::axes`](super::JointDesc::axes) and of the
    /// coordinates.
    pub const ALL: [Self; 6] = [
        Self::X,
        Self::Y,
        Self::Z,
        Self::RotX,
        Self::RotY,
        Self::RotZ,
    ];

    /// The name the scene format uses: `"x"`, `"y"`, `"z"`, `"rx"`, `"ry"`, `"rz"`.
    pub fn name(self) -> &'static str {
        ["x", "y", "z", "rx", "ry", "rz"][self.index()]
    }

    /// The axis of a scene-format name, `None` for a name that is not one of the six.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|axis| axis.name() == name)
    }

    /// Its place in [`Self::ALL`]: 0 to 2 the slides, 3 to 5 the rotations.
    pub fn index(self) -> usize {
        self as usize
    }

    /// Whether it is a rotation (`rx`, `ry`, `rz`).
    pub fn is_rotation(self) -> bool {
        self.index() >= 3
    }
}

/// What a generic joint does with one of its axes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum AxisFreedom {
    /// Held at its value when the joint was made (0), the default.
    #[default]
    Locked,
    /// Free.
    Free,
    /// Free within `[min, max]`: m for a slide, rad for a rotation (within ±π).
    Limited([f32; 2]),
}

impl AxisFreedom {
    /// Whether the axis moves (free or limited), so that it may take a motor.
    pub fn moves(self) -> bool {
        self != Self::Locked
    }
}

/// A generic joint's six coordinates and their rates, in the order of [`GenericAxis::ALL`]:
/// what [`crate::World::generic_joint_coordinates`] returns.
///
/// - Slides `x`, `y`, `z`: `(p_B − p_A)·eᵢ`, m, with `p` the anchors and `eᵢ` the frame's axes
///   as fixed in `body_a`; rates `(ṗ_B − ṗ_A)·eᵢ + (p_B − p_A)·(ω_A × eᵢ)`, m/s.
/// - Rotations `rx`, `ry`, `rz`: with `d` the rotation of `body_b` relative to `body_a` since
///   the joint was made, in the joint frame, `w ≥ 0`: `2 atan2(dᵢ, d_w)` in `(−π, π]`, rad.
///   When exactly one rotation is free or limited, its coordinate is that, the exact angle
///   (the twist `t` about its axis), and the locked ones are those of the swing `s = d t⁻¹`
///   left once the twist is taken out, so that they read 0 at any angle of the free one. Rates
///   `(ω_B − ω_A)·eᵢ`, rad/s.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct GenericCoordinates {
    /// m (slides) and rad (rotations).
    pub positions: [f32; 6],
    /// m/s and rad/s.
    pub velocities: [f32; 6],
}

/// A generic joint's frame at given poses: its axes in the world and its six coordinates.
#[derive(Debug, Clone, Copy)]
pub(crate) struct GenericFrame {
    /// The frame's X, Y, Z axes as fixed in `body_a`, world frame (unit).
    pub axes: [Vec3; 3],
    /// The coordinates of [`GenericCoordinates::positions`].
    pub positions: [f32; 6],
}

impl GenericFrame {
    /// The frame of a joint with `axes` whose anchors are apart by `separation` (`p_B − p_A`,
    /// world), for the sides' rotations.
    pub(crate) fn new(
        frames: &JointFrames,
        axes: &[AxisFreedom; 6],
        (rotation_a, rotation_b): (Quat, Quat),
        separation: Vec3,
    ) -> Self {
        let frame = rotation_a * frames.local_frame_a;
        let world_axes = Vec3::AXES.map(|axis| frame * axis);
        let relative = relative_rotation(frames, rotation_a, rotation_b);
        // `F⁻¹ d F`: the same rotation with its axis in the joint frame; `w` is unchanged.
        let inframe = frames.local_frame_a.inverse() * relative * frames.local_frame_a;
        let half = Vec3::new(inframe.x, inframe.y, inframe.z);
        let mut positions = [0.0; 6];
        for (k, axis) in world_axes.into_iter().enumerate() {
            positions[k] = separation.dot(axis);
            positions[3 + k] = 2.0 * half[k].atan2(inframe.w);
        }
        let mut turning = (3..6).filter(|&k| axes[k].moves());
        if let (Some(free), None) = (turning.next(), turning.next()) {
            // One rotation moves: `d = s t`, its twist `t` about its axis and the swing `s`
            // left, whose components are the locked rotations' coordinates. They stay 0 at any
            // twist, where `2 atan2(dᵢ, d_w)` would turn into ±π as the twist passes a half turn.
            let k = free - 3;
            let mut along = Vec3::ZERO;
            along[k] = half[k];
            let length = (along[k] * along[k] + inframe.w * inframe.w).sqrt();
            // A swing of a half turn leaves no twist to take out (`d_k = d_w = 0`).
            if length > f32::EPSILON {
                let twist = Quat::from_xyzw(along.x, along.y, along.z, inframe.w) / length;
                let swing = inframe * twist.inverse();
                let swing = if swing.w < 0.0 { -swing } else { swing };
                let swing_half = Vec3::new(swing.x, swing.y, swing.z);
                for i in (0..3).filter(|&i| i != k) {
                    positions[3 + i] = 2.0 * swing_half[i].atan2(swing.w);
                }
            }
        }
        Self {
            axes: world_axes,
            positions,
        }
    }
}
