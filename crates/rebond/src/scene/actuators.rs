//! A scene's actuators (MuJoCo's `motor`, `position` and `velocity`): one control value each,
//! turned into the motor of the joint it drives.

use crate::error::{check_finite, Error, ErrorKind};
use crate::joint::{JointHandle, Motor};
use crate::world::World;

/// How an actuator turns its control `u` (clamped to its range) into its joint's motor, with
/// `g` the actuator's gear (its length is `g·q` for the joint coordinate `q`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ActuatorKind {
    /// A torque (N·m) or force (N) `g·u` on the joint.
    Motor,
    /// A position motor towards `q = u / g` with stiffness `kp·g²` and damping `kv·g²`: the
    /// torque `−g (kp (g q − u) + kv g q̇)`.
    Position {
        /// Stiffness, N·m/rad or N/m, ≥ 0.
        kp: f32,
        /// Damping, N·m·s/rad or N·s/m, ≥ 0.
        kv: f32,
    },
    /// A velocity motor towards `q̇ = u / g`, without force limit. MuJoCo's velocity actuator
    /// is the damper `g kv (u − g q̇)` instead; rebond's motor reaches the speed within a step.
    Velocity {
        /// MuJoCo's velocity gain, N·m·s/rad or N·s/m, ≥ 0, kept for the record.
        kv: f32,
    },
}

impl ActuatorKind {
    /// The name used in scene files: `"motor"`, `"position"` or `"velocity"`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Motor => "motor",
            Self::Position { .. } => "position",
            Self::Velocity { .. } => "velocity",
        }
    }
}

/// One actuator of a scene (its `actuators` entry, checked).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Actuator {
    /// Its unique name among actuators.
    pub name: String,
    /// The revolute or prismatic joint it drives.
    pub joint: JointHandle,
    /// How its control drives the joint.
    pub kind: ActuatorKind,
    /// The transmission `g`, finite and non-zero, default 1.
    pub gear: f32,
    /// `[lo, hi]` the control is clamped to; `None` for no clamping.
    pub ctrl_range: Option<[f32; 2]>,
}

impl Actuator {
    /// The joint motor for the control `u`.
    pub fn motor(&self, control: f32) -> Motor {
        let u = match self.ctrl_range {
            Some([lo, hi]) => control.clamp(lo, hi),
            None => control,
        };
        let gear = self.gear;
        match self.kind {
            ActuatorKind::Motor => Motor::torque(gear * u),
            ActuatorKind::Position { kp, kv } => {
                Motor::position(u / gear, kp * gear * gear, kv * gear * gear, f32::INFINITY)
            }
            ActuatorKind::Velocity { .. } => Motor::velocity(u / gear, f32::INFINITY),
        }
    }
}

/// Sets the motors of `actuators` in `world` from `controls`, one per actuator in order; every
/// control and every motor is checked before any joint changes, and an error names
/// `controls[i]` (or the motor's field within it).
pub(super) fn apply(
    world: &mut World,
    actuators: &[Actuator],
    controls: &[f32],
) -> crate::Result<()> {
    if controls.len() != actuators.len() {
        let kind = ErrorKind::WrongCount {
            expected: actuators.len(),
            got: controls.len(),
        };
        return Err(Error::new("controls", kind));
    }
    let mut motors = Vec::with_capacity(actuators.len());
    for (index, (actuator, &control)) in actuators.iter().zip(controls).enumerate() {
        let place = format!("controls[{index}]");
        check_finite(&place, control)?;
        let motor = actuator.motor(control);
        let joint = world.joint(actuator.joint)?;
        motor
            .check_for(joint.joint_type())
            .map_err(|error| error.within(&place))?;
        motors.push(motor);
    }
    for (actuator, motor) in actuators.iter().zip(motors) {
        world.set_joint_motor(actuator.joint, Some(motor))?;
    }
    Ok(())
}
