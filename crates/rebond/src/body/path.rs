//! Keyframe paths for kinematic bodies: poses at given times, passed at constant velocity.

use crate::error::{check_finite, check_position, Error, ErrorKind, Result};
use crate::math::{normalize_rotation, Pose, Quat, Vec3};

/// One keyframe of a [`KinematicPath`]: the pose of the body origin at `time`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PathPoint {
    /// Seconds from the start of the path: 0 for the first point, then strictly increasing.
    pub time: f32,
    /// World position of the body origin, metres.
    pub position: Vec3,
    /// World orientation; normalised when the body is added (a zero quaternion is an error).
    pub rotation: Quat,
}

impl PathPoint {
    /// The pose `(position, rotation)` at `time` seconds.
    pub fn new(time: f32, position: Vec3, rotation: Quat) -> Self {
        Self {
            time,
            position,
            rotation,
        }
    }

    fn pose(&self) -> Pose {
        Pose::new(self.position, self.rotation)
    }
}

/// The keyframes a kinematic body follows ([`crate::BodyDesc::path`]): it passes each point's
/// pose at the point's time, moving at constant velocity between two points (`p = p₀ + s (p₁ −
/// p₀)`, `q = slerp(q₀, q₁, s)` by the shortest arc, `s = (t − t₀)/(t₁ − t₀)`). Without
/// `looping` it stops at the last point; with it, it goes on from the first after the last
/// point's time (`t mod t_last`), so a loop should end where it starts, or the body travels
/// back to the first point in one step. Times count from when the body is added to its world.
///
/// The world moves the body there by a pose target each step
/// ([`crate::RigidBody::set_kinematic_target`]): what rests on it is carried.
///
/// ```
/// use rebond::{KinematicPath, PathPoint, Quat, Vec3};
///
/// let path = KinematicPath::new(vec![
///     PathPoint::new(0.0, Vec3::ZERO, Quat::IDENTITY),
///     PathPoint::new(2.0, Vec3::new(2.0, 0.0, 0.0), Quat::IDENTITY),
/// ]);
/// assert_eq!(path.pose_at(1.0).position, Vec3::new(1.0, 0.0, 0.0));
/// assert_eq!(path.pose_at(5.0).position, Vec3::new(2.0, 0.0, 0.0));
/// assert_eq!(path.looping(true).pose_at(3.0).position, Vec3::new(1.0, 0.0, 0.0));
/// ```
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct KinematicPath {
    /// The keyframes, at least one, the first at time 0, times strictly increasing.
    pub points: Vec<PathPoint>,
    /// Whether the path starts again from the first point after the last one, default false.
    pub looping: bool,
}

impl KinematicPath {
    /// A path through `points` that stops at the last one. Checked when the body is added.
    pub fn new(points: Vec<PathPoint>) -> Self {
        Self {
            points,
            looping: false,
        }
    }

    /// Sets whether the path starts again from the first point after the last one.
    pub fn looping(mut self, looping: bool) -> Self {
        self.looping = looping;
        self
    }

    /// The pose of the body origin at `time` seconds from the start of the path; before the
    /// first point (a negative time) the first point's pose. Exact at each point's time. For a
    /// path as the world checks it ([`crate::BodyDesc::path`]); an empty one gives the
    /// identity.
    pub fn pose_at(&self, time: f64) -> Pose {
        let Some(last) = self.points.last() else {
            return Pose::IDENTITY;
        };
        let duration = f64::from(last.time);
        let time = if self.looping && duration > 0.0 && time > duration {
            time % duration
        } else {
            time
        };
        // The points at or before `time`; the segment runs from the last of them to the next.
        let passed = self
            .points
            .partition_point(|point| f64::from(point.time) <= time);
        if passed == 0 {
            return self.points[0].pose();
        }
        if passed == self.points.len() {
            return last.pose();
        }
        let (start, end) = (&self.points[passed - 1], &self.points[passed]);
        let start_time = f64::from(start.time);
        let fraction = ((time - start_time) / (f64::from(end.time) - start_time)) as f32;
        if fraction == 0.0 {
            return start.pose();
        }
        Pose::new(
            start.position.lerp(end.position, fraction),
            start.rotation.slerp(end.rotation, fraction).normalize(),
        )
    }

    /// Checks the points and normalises their rotations. Errors name `points[i].time`,
    /// `points[i].position` or `points[i].rotation`; `points` when there is none.
    pub(crate) fn checked(&self) -> Result<Self> {
        if self.points.is_empty() {
            return Err(Error::new("points", ErrorKind::Missing));
        }
        let mut points = Vec::with_capacity(self.points.len());
        let mut previous: Option<f32> = None;
        for (index, point) in self.points.iter().enumerate() {
            let field = |name: &str| format!("points[{index}].{name}");
            let time = check_finite(&field("time"), point.time)?;
            match previous {
                None if time != 0.0 => {
                    let kind = ErrorKind::OutOfRange {
                        value: time,
                        min: 0.0,
                        max: 0.0,
                    };
                    return Err(Error::new(field("time"), kind));
                }
                Some(previous) if time <= previous => {
                    let kind = ErrorKind::NotIncreasing {
                        value: time,
                        previous,
                    };
                    return Err(Error::new(field("time"), kind));
                }
                _ => {}
            }
            previous = Some(time);
            points.push(PathPoint {
                time,
                position: check_position(&field("position"), point.position)?,
                rotation: normalize_rotation(&field("rotation"), point.rotation)?,
            });
        }
        Ok(Self {
            points,
            looping: self.looping,
        })
    }

    /// Checks a decoded path: its points as [`KinematicPath::checked`] wants them, and rotations
    /// already normalised.
    #[cfg(feature = "serde")]
    pub(crate) fn check_decoded(&self) -> std::result::Result<(), String> {
        self.checked().map_err(|error| format!("path: {error}"))?;
        if self
            .points
            .iter()
            .all(|point| point.rotation.is_normalized())
        {
            Ok(())
        } else {
            Err("a path rotation is not normalised".to_owned())
        }
    }
}
