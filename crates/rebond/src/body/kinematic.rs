//! Kinematic control: a body moved to a pose target over the next step, or along a path of
//! keyframes, at the velocities that carry it there (`docs/kinematic.md`).

use super::{BodyType, KinematicPath, RigidBody};
use crate::error::{check_position, Error, ErrorKind, Result};
use crate::limits::{MAX_ANGULAR_SPEED, MAX_SPEED};
use crate::math::{normalize_rotation, rotation_vector, Pose, Vec3};

impl RigidBody {
    /// Gives a kinematic body the pose of its origin at the end of the next step. The step sets
    /// the velocities that carry it there over its `dt`, `v = Δc / dt` for the centre of mass
    /// and `ω = θ / dt` with `θ` the rotation vector of `q_target q⁻¹` by the shortest arc, so
    /// contacts and friction see the motion and carry what rests on the body; the step then
    /// ends with the body exactly at `pose`. Velocities past [`MAX_SPEED`] or
    /// [`MAX_ANGULAR_SPEED`] are held to them, and the body still ends at `pose`.
    ///
    /// The target holds for one step. After a step without a new target the body keeps its
    /// velocity, as any kinematic body does: give a target every step, or set the velocities
    /// to zero to stop it. A target replaces the body's path, if it has one.
    ///
    /// Errors: [`ErrorKind::NotKinematic`] (field `target`) for a body that is not kinematic; a
    /// position that is not finite or past the coordinate limit (`target.position`); a rotation
    /// that is not finite or zero (`target.rotation`; it is normalised).
    ///
    /// ```
    /// use rebond::{BodyDesc, Pose, Quat, Shape, Vec3, World, WorldSettings};
    ///
    /// let mut world = World::new(WorldSettings::default())?;
    /// let platform = world.add_body(BodyDesc::kinematic(Shape::cuboid(Vec3::new(1.0, 0.1, 1.0))?))?;
    /// let target = Pose::new(Vec3::new(0.1, 0.0, 0.0), Quat::IDENTITY);
    /// world.body_mut(platform)?.set_kinematic_target(target)?;
    /// world.step(0.1)?;
    /// assert_eq!(world.body(platform)?.position(), target.position);
    /// // The velocity that carried it there, 0.1 m in 0.1 s, which it keeps.
    /// let velocity = world.body(platform)?.linear_velocity();
    /// assert!((velocity - Vec3::new(1.0, 0.0, 0.0)).length() < 1e-5);
    /// # Ok::<(), rebond::Error>(())
    /// ```
    pub fn set_kinematic_target(&mut self, pose: Pose) -> Result<()> {
        if self.body_type != BodyType::Kinematic {
            return Err(Error::new("target", ErrorKind::NotKinematic));
        }
        let position = check_position("target.position", pose.position)?;
        let rotation = normalize_rotation("target.rotation", pose.rotation)?;
        self.kinematic_target = Some(Pose::new(position, rotation));
        self.path = None;
        self.wake();
        Ok(())
    }

    /// The pose target the next step carries the body to, if any.
    pub fn kinematic_target(&self) -> Option<Pose> {
        self.kinematic_target
    }

    /// The keyframes the body follows, if any, checked and with normalised rotations.
    pub fn path(&self) -> Option<&KinematicPath> {
        self.path.as_ref()
    }

    /// Seconds the body has followed its path: the sum of the steps' `dt` since it was added
    /// with its path or the path was set.
    pub fn path_time(&self) -> f64 {
        self.path_time
    }

    /// Sets the keyframes a kinematic body follows, from time 0 now, and drops its pose target;
    /// `None` stops following (the body keeps its velocity). The next step carries the body
    /// from where it is to the path's pose at that step's end. Errors:
    /// [`ErrorKind::NotKinematic`] (field `path`) for a body that is not kinematic, and those
    /// of [`BodyDesc::path`](super::BodyDesc::path) (`path.points[1].time`, …).
    pub fn set_path(&mut self, path: Option<KinematicPath>) -> Result<()> {
        self.path = match path {
            Some(path) => Some(checked_path(self.body_type, &path)?),
            None => None,
        };
        self.path_time = 0.0;
        self.kinematic_target = None;
        self.wake();
        Ok(())
    }

    /// Sets the velocities that carry a kinematic body to its pose target over the step `dt`,
    /// the target being its path's pose at the step's end when it follows one.
    pub(crate) fn begin_kinematic_step(&mut self, dt: f32) {
        if let Some(path) = &self.path {
            self.kinematic_target = Some(path.pose_at(self.path_time + f64::from(dt)));
        }
        let Some(target) = self.kinematic_target else {
            return;
        };
        let center = target.transform_point(self.local_center_of_mass);
        self.linear_velocity = ((center - self.center_of_mass) / dt).clamp_length_max(MAX_SPEED);
        // An unchanged rotation gives exactly no spin: a body at rest stays a body at rest.
        self.angular_velocity = if target.rotation == self.rotation {
            Vec3::ZERO
        } else {
            let turn = target.rotation * self.rotation.inverse();
            let shortest = if turn.w < 0.0 { -turn } else { turn };
            (rotation_vector(shortest) / dt).clamp_length_max(MAX_ANGULAR_SPEED)
        };
    }

    /// Puts a kinematic body exactly at the pose target the step carried it to (the substeps'
    /// rounding and first-order rotation leave it near), and advances its path's clock.
    pub(crate) fn finish_kinematic_step(&mut self, dt: f32) {
        if let Some(target) = self.kinematic_target.take() {
            self.set_origin_pose(target);
        }
        if self.path.is_some() {
            self.path_time += f64::from(dt);
        }
    }

    /// Checks a decoded body's pose target, path and path clock.
    #[cfg(feature = "serde")]
    pub(crate) fn check_kinematic_decoded(&self) -> std::result::Result<(), String> {
        let controlled = self.kinematic_target.is_some() || self.path.is_some();
        if controlled && self.body_type != BodyType::Kinematic {
            return Err("a body that is not kinematic has a pose target or path".to_owned());
        }
        if let Some(target) = self.kinematic_target {
            check_position("target.position", target.position).map_err(|e| e.to_string())?;
            if !target.rotation.is_normalized() {
                return Err("the pose target's rotation is not normalised".to_owned());
            }
        }
        if let Some(path) = &self.path {
            path.check_decoded()?;
        }
        if self.path_time.is_finite() && self.path_time >= 0.0 {
            Ok(())
        } else {
            Err("the path time is not finite and non-negative".to_owned())
        }
    }
}

/// `path` checked for a body of type `body_type`, errors named under `path`.
pub(super) fn checked_path(body_type: BodyType, path: &KinematicPath) -> Result<KinematicPath> {
    if body_type != BodyType::Kinematic {
        return Err(Error::new("path", ErrorKind::NotKinematic));
    }
    path.checked().map_err(|error| error.within("path"))
}
