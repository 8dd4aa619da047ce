//! Forces, torques and impulses on a body: applied for the next step, or held for every step
//! (the constant ones), and what a step applies of them.

use super::RigidBody;
use crate::error::{check_length, check_position, Result};
use crate::limits::{MAX_FORCE, MAX_SIZE};
use crate::math::Vec3;

impl RigidBody {
    /// Adds a force at the centre of mass for the next step, N (no effect unless dynamic).
    pub fn apply_force(&mut self, force: Vec3) -> Result<()> {
        check_length("force", force, MAX_FORCE)?;
        if self.is_dynamic() {
            self.force += force;
            self.wake();
        }
        Ok(())
    }

    /// Adds a force at world `point` for the next step: the force, and the torque `r × F` with
    /// `r = point − c` (no effect unless dynamic).
    pub fn apply_force_at_point(&mut self, force: Vec3, point: Vec3) -> Result<()> {
        check_length("force", force, MAX_FORCE)?;
        check_position("point", point)?;
        if self.is_dynamic() {
            self.force += force;
            self.torque += (point - self.center_of_mass).cross(force);
            self.wake();
        }
        Ok(())
    }

    /// Adds a torque for the next step, N·m (no effect unless dynamic).
    pub fn apply_torque(&mut self, torque: Vec3) -> Result<()> {
        check_length("torque", torque, MAX_FORCE)?;
        if self.is_dynamic() {
            self.torque += torque;
            self.wake();
        }
        Ok(())
    }

    /// Changes the velocity at once by an impulse at the centre of mass: `Δv = M⁻¹ J`, N·s
    /// (`J/m` on the axes that are not locked).
    pub fn apply_impulse(&mut self, impulse: Vec3) -> Result<()> {
        check_length("impulse", impulse, MAX_FORCE)?;
        if self.is_dynamic() {
            self.linear_velocity += self.inverse_mass_diagonal() * impulse;
            self.wake();
        }
        Ok(())
    }

    /// An impulse at world `point`: `Δv = M⁻¹ J`, `Δω = I⁻¹ (r × J)` with `r = point − c`.
    pub fn apply_impulse_at_point(&mut self, impulse: Vec3, point: Vec3) -> Result<()> {
        check_length("impulse", impulse, MAX_FORCE)?;
        check_position("point", point)?;
        if self.is_dynamic() {
            self.linear_velocity += self.inverse_mass_diagonal() * impulse;
            self.angular_velocity +=
                self.world_inverse_inertia * (point - self.center_of_mass).cross(impulse);
            self.wake();
        }
        Ok(())
    }

    /// Sets the force applied at the centre of mass during every step.
    pub fn set_constant_force(&mut self, force: Vec3) -> Result<()> {
        self.constant_force = check_length("force", force, MAX_FORCE)?;
        self.constant_force_point = None;
        self.wake();
        Ok(())
    }

    /// Sets the world force applied during every step at `point`, a point in the body frame
    /// (it turns with the body): the force, and the torque `r × F` about the centre of mass.
    pub fn set_constant_force_at_point(&mut self, force: Vec3, point: Vec3) -> Result<()> {
        check_length("force", force, MAX_FORCE)?;
        check_length("point", point, MAX_SIZE)?;
        self.constant_force = force;
        self.constant_force_point = Some(point);
        self.wake();
        Ok(())
    }

    /// The force and torque this step applies: what the user applied since the last step plus
    /// the constant ones, with `r × F` of a constant force off the centre of mass
    /// (`r = R (p − c_local)`), N and N·m.
    pub(crate) fn applied_force_and_torque(&self) -> (Vec3, Vec3) {
        let (force, torque) = self.applied_constant_force_and_torque();
        (self.force + force, self.torque + torque)
    }

    /// The constant force and torque alone, as [`applied_force_and_torque`] counts them.
    ///
    /// [`applied_force_and_torque`]: Self::applied_force_and_torque
    pub(super) fn applied_constant_force_and_torque(&self) -> (Vec3, Vec3) {
        let mut torque = self.constant_torque;
        if let Some(point) = self.constant_force_point {
            let arm = self.rotation * (point - self.local_center_of_mass);
            torque += arm.cross(self.constant_force);
        }
        (self.constant_force, torque)
    }

    /// Sets the torque applied during every step.
    pub fn set_constant_torque(&mut self, torque: Vec3) -> Result<()> {
        self.constant_torque = check_length("torque", torque, MAX_FORCE)?;
        self.wake();
        Ok(())
    }
}
