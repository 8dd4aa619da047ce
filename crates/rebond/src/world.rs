//! The world: owns bodies and settings, and advances them in time.

use crate::arena::Arena;
use crate::body::{BodyDesc, BodyHandle, RigidBody};
use crate::error::{check_finite_vector, check_positive, Error, ErrorKind, Result};
use crate::integration::{
    integrate_pose, integrate_velocities, SpeedLimits, MAX_ROTATION_PER_SUBSTEP,
};
use crate::math::Vec3;

/// Default gravity, m/s²: Earth's, along −Y.
pub const DEFAULT_GRAVITY: Vec3 = Vec3::new(0.0, -9.81, 0.0);
/// Default number of substeps per step.
pub const DEFAULT_SUBSTEPS: u32 = 4;
/// Largest number of substeps accepted per step.
pub const MAX_SUBSTEPS: u32 = 64;
/// Default speed limit of a body's centre of mass, m/s (about three times the speed of sound):
/// it keeps a runaway body's position finite.
pub const DEFAULT_MAX_LINEAR_SPEED: f32 = 1000.0;

/// World-wide settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldSettings {
    /// Gravity, m/s², default `[0, −9.81, 0]`.
    pub gravity: Vec3,
    /// Substeps per step, 1 to [`MAX_SUBSTEPS`], default 4.
    pub substeps: u32,
    /// Speed limit of every body's centre of mass, m/s, default [`DEFAULT_MAX_LINEAR_SPEED`].
    /// Angular speed is limited too, to a quarter turn per substep.
    pub max_linear_speed: f32,
}

impl Default for WorldSettings {
    fn default() -> Self {
        Self {
            gravity: DEFAULT_GRAVITY,
            substeps: DEFAULT_SUBSTEPS,
            max_linear_speed: DEFAULT_MAX_LINEAR_SPEED,
        }
    }
}

impl WorldSettings {
    fn validate(&self) -> Result<()> {
        check_finite_vector("gravity", self.gravity)?;
        check_positive("max_linear_speed", self.max_linear_speed)?;
        if !(1..=MAX_SUBSTEPS).contains(&self.substeps) {
            return Err(Error::new(
                "substeps",
                ErrorKind::OutOfRange {
                    value: self.substeps as f32,
                    min: 1.0,
                    max: MAX_SUBSTEPS as f32,
                },
            ));
        }
        Ok(())
    }
}

/// A physics world: bodies, settings and the step that moves them.
///
/// ```
/// use rebond::{BodyDesc, Shape, Vec3, World, WorldSettings};
///
/// let mut world = World::new(WorldSettings::default())?;
/// let ball = world.add_body(
///     BodyDesc::dynamic(Shape::sphere(0.5)?).position(Vec3::new(0.0, 10.0, 0.0)),
/// )?;
/// for _ in 0..60 {
///     world.step(1.0 / 60.0)?;
/// }
/// assert!(world.body(ball)?.position().y < 10.0);
/// # Ok::<(), rebond::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct World {
    settings: WorldSettings,
    bodies: Arena<RigidBody>,
}

impl World {
    /// An empty world; settings must be finite and in range.
    pub fn new(settings: WorldSettings) -> Result<Self> {
        settings.validate()?;
        Ok(Self {
            settings,
            bodies: Arena::default(),
        })
    }

    /// The current settings.
    pub fn settings(&self) -> &WorldSettings {
        &self.settings
    }

    /// Replaces the settings; on error the world keeps the old ones.
    pub fn set_settings(&mut self, settings: WorldSettings) -> Result<()> {
        settings.validate()?;
        self.settings = settings;
        Ok(())
    }

    /// Checks `desc` and adds the body; on error the world is unchanged.
    pub fn add_body(&mut self, desc: BodyDesc) -> Result<BodyHandle> {
        let body = RigidBody::from_desc(desc)?;
        Ok(BodyHandle(self.bodies.insert(body)))
    }

    /// Removes the body and returns it; its handle becomes stale.
    pub fn remove_body(&mut self, handle: BodyHandle) -> Result<RigidBody> {
        self.bodies.remove(handle.0).ok_or_else(stale)
    }

    /// The body behind `handle`.
    pub fn body(&self, handle: BodyHandle) -> Result<&RigidBody> {
        self.bodies.get(handle.0).ok_or_else(stale)
    }

    /// The body behind `handle`, to change through its validating setters.
    pub fn body_mut(&mut self, handle: BodyHandle) -> Result<&mut RigidBody> {
        self.bodies.get_mut(handle.0).ok_or_else(stale)
    }

    /// All bodies with their handles, in a deterministic order (storage slots).
    pub fn bodies(&self) -> impl Iterator<Item = (BodyHandle, &RigidBody)> {
        self.bodies
            .iter()
            .map(|(index, body)| (BodyHandle(index), body))
    }

    /// Number of bodies.
    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// Number of bodies asleep.
    pub fn sleeping_body_count(&self) -> usize {
        self.bodies.iter().filter(|(_, body)| body.sleeping).count()
    }

    /// Number of contact points between touching shapes. Collision detection has not landed yet,
    /// so no body touches another and this is zero.
    pub fn contact_count(&self) -> usize {
        0
    }

    /// Number of islands (groups of awake dynamic bodies linked by contacts). Without contacts
    /// every awake dynamic body is an island of its own.
    pub fn island_count(&self) -> usize {
        self.bodies
            .iter()
            .filter(|(_, body)| body.is_dynamic() && !body.sleeping)
            .count()
    }

    /// Kinetic plus gravitational potential energy of the dynamic bodies, joules:
    /// `Σ ½ m v² + ½ ωᵀ I ω − m g · c`.
    pub fn total_energy(&self) -> f32 {
        self.bodies
            .iter()
            .map(|(_, body)| {
                body.kinetic_energy() - body.mass * self.settings.gravity.dot(body.center_of_mass)
            })
            .sum()
    }

    /// Advances the world by `dt` seconds (finite and positive) in `settings.substeps` substeps.
    /// Forces and torques applied since the last step act during the whole step, then are cleared.
    pub fn step(&mut self, dt: f32) -> Result<()> {
        check_positive("dt", dt)?;
        let h = dt / self.settings.substeps as f32;
        let limits = SpeedLimits {
            linear: self.settings.max_linear_speed,
            angular: MAX_ROTATION_PER_SUBSTEP / h,
        };
        let gravity = self.settings.gravity;
        for _ in 0..self.settings.substeps {
            for body in self.bodies.values_mut() {
                integrate_velocities(body, gravity, h, limits);
            }
            for body in self.bodies.values_mut() {
                integrate_pose(body, h);
            }
        }
        for body in self.bodies.values_mut() {
            body.force = Vec3::ZERO;
            body.torque = Vec3::ZERO;
        }
        Ok(())
    }
}

fn stale() -> Error {
    Error::new("", ErrorKind::StaleHandle)
}
