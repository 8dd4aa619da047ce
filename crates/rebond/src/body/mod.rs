//! Rigid bodies: their description, their state, and the user calls that change them.
//!
//! A body keeps the pose of its centre of mass, which is what the engine integrates; the pose of
//! the body origin (what users place and read) is derived from it.

use crate::arena::ArenaIndex;
use crate::collision::broad_phase::ProxyHandle;
use crate::error::{
    check_direction, check_length, check_non_negative, check_non_negative_or_infinite,
    check_position, check_positive, check_range, Error, ErrorKind, Result,
};
use crate::filter::InteractionGroups;
use crate::limits::{
    MAX_ANGULAR_SPEED, MAX_FORCE, MAX_INERTIA_RATIO, MAX_MASS, MAX_SIZE, MAX_SPEED, MIN_MASS,
};
use crate::mass::MassProperties;
use crate::material::Material;
use crate::math::{normalize_rotation, rotate_tensor, skew, Aabb, Mat3, Pose, Quat, Vec3};
use crate::shape::{Shape, TriangleMaterial};

mod desc;
mod forces;
mod kinematic;
mod locked_axes;
mod path;

use kinematic::checked_path;

pub use desc::BodyDesc;
pub use locked_axes::LockedAxes;
pub use path::{KinematicPath, PathPoint};

/// How long a small body's fastest point may take to cross its reach `r_max` and the body still
/// count as still, s: a marble 1 cm across is still below 0.9 cm/s, not at the world's 5 cm/s,
/// five of its diameters a second ([`RigidBody::is_still`]).
const STILL_REACH_TIME: f32 = 1.0;

/// How a body moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum BodyType {
    /// Moved by gravity, forces and contacts.
    Dynamic,
    /// Never moves; infinite mass.
    Static,
    /// Moves only by the velocity, pose target
    /// ([`RigidBody::set_kinematic_target`]) or path ([`KinematicPath`]) the user gives it;
    /// infinite mass, pushes dynamic bodies and carries what rests on it.
    Kinematic,
}

/// Names one body of a [`crate::World`]. A handle to a removed body stays invalid forever, even
/// after another body takes its slot, and a handle of another world is refused
/// ([`crate::ErrorKind::StaleHandle`]), never taken for a body of this one. A world's clones and
/// the worlds restored from its states ([`crate::World::load_state`]) are the same world at
/// other times: its handles name the same bodies in each. Handles of one world order by slot.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BodyHandle(pub(crate) ArenaIndex);

impl BodyHandle {
    /// The storage slot of the body; unique among living bodies.
    pub fn slot(&self) -> usize {
        self.0.slot()
    }
}

/// A rigid body in a world.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RigidBody {
    pub(crate) body_type: BodyType,
    pub(crate) shape: Shape,
    /// World position of the centre of mass.
    pub(crate) center_of_mass: Vec3,
    pub(crate) rotation: Quat,
    /// Centre of mass in the body frame.
    pub(crate) local_center_of_mass: Vec3,
    pub(crate) linear_velocity: Vec3,
    pub(crate) angular_velocity: Vec3,
    pub(crate) mass: f32,
    pub(crate) inverse_mass: f32,
    /// Inertia about the centre of mass, body axes (zero for static and kinematic bodies).
    pub(crate) local_inertia: Mat3,
    pub(crate) local_inverse_inertia: Mat3,
    /// `R · I⁻¹ · Rᵀ`, refreshed whenever the rotation changes.
    pub(crate) world_inverse_inertia: Mat3,
    /// Forces and torques applied by the user since the last step.
    pub(crate) force: Vec3,
    pub(crate) torque: Vec3,
    pub(crate) constant_force: Vec3,
    /// Where the constant force acts, body frame; `None` for the centre of mass.
    pub(crate) constant_force_point: Option<Vec3>,
    pub(crate) constant_torque: Vec3,
    pub(crate) linear_damping: f32,
    pub(crate) angular_damping: f32,
    pub(crate) friction: f32,
    pub(crate) restitution: f32,
    pub(crate) rolling_resistance: f32,
    pub(crate) can_sleep: bool,
    pub(crate) locked_axes: LockedAxes,
    pub(crate) sleeping: bool,
    /// How long the body has been still, seconds (see [`crate::island`]).
    pub(crate) sleep_time: f32,
    /// The island the body fell asleep with (its root slot); the whole group wakes together.
    pub(crate) sleep_group: Option<usize>,
    /// Distance from the centre of mass to the farthest corner of the local bounding box, m.
    pub(crate) max_extent: f32,
    /// Whether the shape has only flat surfaces ([`Shape::is_polyhedral`]): only then can its
    /// contacts be recycled.
    pub(crate) polyhedral: bool,
    /// The body's entry in the broad phase, set when it joins a world.
    pub(crate) proxy: Option<ProxyHandle>,
    pub(crate) sensor: bool,
    pub(crate) collision_groups: InteractionGroups,
    /// Newtons; infinity for no force reports.
    pub(crate) contact_force_threshold: f32,
    pub(crate) user_data: u128,
    /// The pose of the body origin the next step ends at (kinematic bodies only); the step
    /// takes it.
    pub(crate) kinematic_target: Option<Pose>,
    /// The keyframes the body follows (kinematic bodies only), checked.
    pub(crate) path: Option<KinematicPath>,
    /// Seconds along the path: the sum of the steps' `dt` since the path was set, in `f64` so
    /// that it is the exact sum of the `f32` steps for far longer than any run.
    pub(crate) path_time: f64,
    /// Unit direction, body frame, bodies pass through it from; `None` for a solid body.
    pub(crate) one_way: Option<Vec3>,
    /// Velocity of its surface relative to it, m/s, body frame.
    pub(crate) surface_velocity: Vec3,
}

impl RigidBody {
    /// Checks every value of `desc` and builds the body. Errors name the field of `desc`.
    pub(crate) fn from_desc(desc: BodyDesc) -> Result<Self> {
        check_position("position", desc.position)?;
        let rotation = normalize_rotation("rotation", desc.rotation)?;
        check_length("linear_velocity", desc.linear_velocity, MAX_SPEED)?;
        check_length("angular_velocity", desc.angular_velocity, MAX_ANGULAR_SPEED)?;
        check_positive("density", desc.density)?;
        if let Some(mass) = desc.mass {
            check_positive("mass", mass)?;
            check_range("mass", mass, MIN_MASS, MAX_MASS)?;
        }
        if let Some(properties) = &desc.mass_properties {
            if desc.mass.is_some() {
                return Err(Error::new("mass", ErrorKind::ExcludedBy("mass_properties")));
            }
            check_mass_properties(properties).map_err(|error| error.within("mass_properties"))?;
        }
        check_non_negative("friction", desc.friction)?;
        check_range("restitution", desc.restitution, 0.0, 1.0)?;
        check_non_negative("rolling_resistance", desc.rolling_resistance)?;
        check_length("force", desc.constant_force, MAX_FORCE)?;
        if let Some(point) = desc.constant_force_point {
            check_length("force_point", point, MAX_SIZE)?;
        }
        check_length("torque", desc.constant_torque, MAX_FORCE)?;
        check_non_negative("linear_damping", desc.linear_damping)?;
        check_non_negative("angular_damping", desc.angular_damping)?;
        check_non_negative_or_infinite("contact_force_threshold", desc.contact_force_threshold)?;
        let one_way = match desc.one_way {
            Some(direction) => Some(check_direction("one_way", direction)?),
            None => None,
        };
        check_length("surface_velocity", desc.surface_velocity, MAX_SPEED)?;
        let path = match &desc.path {
            Some(path) => Some(checked_path(desc.body_type, path)?),
            None => None,
        };

        let mass_properties = match desc.body_type {
            BodyType::Dynamic => Some(dynamic_mass_properties(&desc)?),
            BodyType::Static | BodyType::Kinematic => None,
        };
        let moves = desc.body_type != BodyType::Static;
        let mut body = Self {
            body_type: desc.body_type,
            shape: desc.shape,
            center_of_mass: desc.position,
            rotation,
            local_center_of_mass: Vec3::ZERO,
            linear_velocity: if moves {
                desc.linear_velocity
            } else {
                Vec3::ZERO
            },
            angular_velocity: if moves {
                desc.angular_velocity
            } else {
                Vec3::ZERO
            },
            mass: 0.0,
            inverse_mass: 0.0,
            local_inertia: Mat3::ZERO,
            local_inverse_inertia: Mat3::ZERO,
            world_inverse_inertia: Mat3::ZERO,
            force: Vec3::ZERO,
            torque: Vec3::ZERO,
            constant_force: desc.constant_force,
            constant_force_point: desc.constant_force_point,
            constant_torque: desc.constant_torque,
            linear_damping: desc.linear_damping,
            angular_damping: desc.angular_damping,
            friction: desc.friction,
            restitution: desc.restitution,
            rolling_resistance: desc.rolling_resistance,
            can_sleep: desc.can_sleep,
            locked_axes: desc.locked_axes,
            sleeping: false,
            sleep_time: 0.0,
            sleep_group: None,
            max_extent: 0.0,
            polyhedral: false,
            proxy: None,
            sensor: desc.sensor,
            collision_groups: desc.collision_groups,
            contact_force_threshold: desc.contact_force_threshold,
            user_data: desc.user_data,
            kinematic_target: None,
            path: None,
            path_time: 0.0,
            one_way,
            surface_velocity: desc.surface_velocity,
        };
        if let Some((properties, inverse_inertia)) = mass_properties {
            body.mass = properties.mass;
            body.inverse_mass = 1.0 / properties.mass;
            body.local_center_of_mass = properties.center_of_mass;
            body.local_inertia = properties.inertia;
            body.local_inverse_inertia = inverse_inertia;
        }
        body.polyhedral = body.shape.is_polyhedral();
        body.update_max_extent();
        body.set_origin_pose(match &path {
            Some(path) => path.pose_at(0.0),
            None => Pose::new(desc.position, rotation),
        });
        body.path = path;
        body.hold_to_locked_axes();
        Ok(body)
    }

    /// Gives a dynamic body restored from a portable snapshot the mass (kg), centre of mass
    /// (body frame, m) and inertia (kg·m², body axes) it was saved with, rather than those its
    /// shape gives in this build, and puts its centre of mass at `center_of_mass` (world, m)
    /// turned by `rotation`. Errors when the mass is out of range or the inertia not invertible.
    #[cfg(feature = "serde")]
    pub(crate) fn restore_mass_and_pose(
        &mut self,
        properties: Option<MassProperties>,
        center_of_mass: Vec3,
        rotation: Quat,
    ) -> std::result::Result<(), String> {
        if let Some(properties) = properties {
            let inverse = inverse_inertia(&properties)
                .filter(|_| (MIN_MASS..=MAX_MASS).contains(&properties.mass))
                .ok_or("the mass or inertia is out of range")?;
            self.mass = properties.mass;
            self.inverse_mass = 1.0 / properties.mass;
            self.local_center_of_mass = properties.center_of_mass;
            self.local_inertia = properties.inertia;
            self.local_inverse_inertia = inverse;
            self.update_max_extent();
        }
        self.center_of_mass = center_of_mass;
        self.rotation = rotation;
        self.update_world_inverse_inertia();
        Ok(())
    }

    /// Dynamic, static or kinematic.
    pub fn body_type(&self) -> BodyType {
        self.body_type
    }

    /// The collision shape, body frame.
    pub fn shape(&self) -> &Shape {
        &self.shape
    }

    /// Pose of the body origin in the world.
    pub fn pose(&self) -> Pose {
        Pose::new(self.position(), self.rotation)
    }

    /// Pose of the centre of mass in the world.
    pub(crate) fn center_pose(&self) -> Pose {
        Pose::new(self.center_of_mass, self.rotation)
    }

    /// World position of the body origin, metres.
    pub fn position(&self) -> Vec3 {
        self.center_of_mass - self.rotation * self.local_center_of_mass
    }

    /// World orientation.
    pub fn rotation(&self) -> Quat {
        self.rotation
    }

    /// World position of the centre of mass, metres.
    pub fn center_of_mass(&self) -> Vec3 {
        self.center_of_mass
    }

    /// Centre of mass in the body frame, metres.
    pub fn local_center_of_mass(&self) -> Vec3 {
        self.local_center_of_mass
    }

    /// Velocity of the centre of mass, m/s.
    pub fn linear_velocity(&self) -> Vec3 {
        self.linear_velocity
    }

    /// Angular velocity, rad/s, world frame.
    pub fn angular_velocity(&self) -> Vec3 {
        self.angular_velocity
    }

    /// Velocity of the material point at world `point`: `v + ω × (p − c)`.
    pub fn velocity_at_point(&self, point: Vec3) -> Vec3 {
        self.linear_velocity + self.angular_velocity.cross(point - self.center_of_mass)
    }

    /// Mass, kg; zero for static and kinematic bodies.
    pub fn mass(&self) -> f32 {
        self.mass
    }

    /// `1/m`; zero for static and kinematic bodies.
    pub fn inverse_mass(&self) -> f32 {
        self.inverse_mass
    }

    /// The inverse mass along each world axis, kg⁻¹: `1/m` on the free axes, zero on the
    /// locked ones ([`LockedAxes`]) and for static and kinematic bodies. `Δv = M⁻¹ J` for an
    /// impulse `J` at the centre of mass.
    pub fn inverse_mass_diagonal(&self) -> Vec3 {
        self.locked_axes.free_linear(Vec3::splat(self.inverse_mass))
    }

    /// The world axes the body does not move along or turn about.
    pub fn locked_axes(&self) -> LockedAxes {
        self.locked_axes
    }

    /// Locks world axes ([`LockedAxes`]); the velocities along and about the newly locked axes
    /// become zero. Only dynamic bodies feel locks.
    pub fn set_locked_axes(&mut self, locked_axes: LockedAxes) {
        self.locked_axes = locked_axes;
        self.update_world_inverse_inertia();
        self.hold_to_locked_axes();
        self.wake();
    }

    /// Inertia tensor about the centre of mass in body axes, kg·m²; zero unless dynamic.
    pub fn local_inertia(&self) -> Mat3 {
        self.local_inertia
    }

    /// Inverse inertia in world axes, `R · I⁻¹ · Rᵀ`, restricted to the free rotation axes when
    /// some are locked ([`LockedAxes`]); zero unless dynamic.
    pub fn world_inverse_inertia(&self) -> Mat3 {
        self.world_inverse_inertia
    }

    /// How the velocity of the material point at world `point` answers an impulse there, s/kg:
    /// `Δv = K J` with `K = M⁻¹ − [r]ₓ I⁻¹ [r]ₓ`, `r = p − c`, `M⁻¹` and `I⁻¹` without their
    /// locked axes (zero unless dynamic). Its inverse is the point's effective mass, what a
    /// mouse spring or a point constraint needs.
    pub fn inverse_mass_at_point(&self, point: Vec3) -> Mat3 {
        let arm = skew(point - self.center_of_mass);
        Mat3::from_diagonal(self.inverse_mass_diagonal()) - arm * self.world_inverse_inertia * arm
    }

    /// Inertia in world axes, `R · I · Rᵀ`; zero unless dynamic.
    pub fn world_inertia(&self) -> Mat3 {
        rotate_tensor(self.rotation, self.local_inertia)
    }

    /// Linear momentum `m v`, kg·m/s.
    pub fn linear_momentum(&self) -> Vec3 {
        self.mass * self.linear_velocity
    }

    /// Angular momentum about the centre of mass, `R I Rᵀ ω`, kg·m²/s.
    pub fn angular_momentum(&self) -> Vec3 {
        self.world_inertia() * self.angular_velocity
    }

    /// Kinetic energy `½ m v² + ½ ωᵀ I ω`, joules.
    pub fn kinetic_energy(&self) -> f32 {
        0.5 * self.mass * self.linear_velocity.length_squared()
            + 0.5 * self.angular_velocity.dot(self.angular_momentum())
    }

    /// Coulomb friction coefficient.
    pub fn friction(&self) -> f32 {
        self.friction
    }

    /// Coefficient of restitution.
    pub fn restitution(&self) -> f32 {
        self.restitution
    }

    /// Rolling resistance coefficient.
    pub fn rolling_resistance(&self) -> f32 {
        self.rolling_resistance
    }

    /// Linear and angular damping, 1/s.
    pub fn damping(&self) -> (f32, f32) {
        (self.linear_damping, self.angular_damping)
    }

    /// The force applied at the centre of mass during every step, N.
    pub fn constant_force(&self) -> Vec3 {
        self.constant_force
    }

    /// Where the constant force acts, a point in the body frame; `None` for the centre of mass.
    pub fn constant_force_point(&self) -> Option<Vec3> {
        self.constant_force_point
    }

    /// The torque applied during every step, N·m.
    pub fn constant_torque(&self) -> Vec3 {
        self.constant_torque
    }

    /// Whether the body may fall asleep.
    pub fn can_sleep(&self) -> bool {
        self.can_sleep
    }

    /// Lets the body fall asleep or not; `false` also wakes it (and, at the next step, the rest
    /// of its sleeping group).
    pub fn set_can_sleep(&mut self, can_sleep: bool) {
        self.can_sleep = can_sleep;
        if !can_sleep {
            self.wake();
        }
    }

    /// Whether the body is a sensor (reports overlaps, never pushes).
    pub fn is_sensor(&self) -> bool {
        self.sensor
    }

    /// Which bodies it interacts with; change them with
    /// [`World::set_collision_groups`](crate::World::set_collision_groups).
    pub fn collision_groups(&self) -> InteractionGroups {
        self.collision_groups
    }

    /// Contact force above which its contacts are reported, newtons (infinity: never).
    pub fn contact_force_threshold(&self) -> f32 {
        self.contact_force_threshold
    }

    /// Sets the contact force above which its contacts are reported, newtons, not negative
    /// (infinity: never).
    pub fn set_contact_force_threshold(&mut self, threshold: f32) -> Result<()> {
        self.contact_force_threshold =
            check_non_negative_or_infinite("contact_force_threshold", threshold)?;
        Ok(())
    }

    /// The direction, body frame, unit, bodies pass through it from; `None` for a solid body
    /// ([`BodyDesc::one_way`](BodyDesc#structfield.one_way)); set it with
    /// [`World::set_one_way`](crate::World::set_one_way).
    pub fn one_way(&self) -> Option<Vec3> {
        self.one_way
    }

    /// The velocity of the body's surface relative to the body, m/s, body frame
    /// ([`BodyDesc::surface_velocity`](BodyDesc#structfield.surface_velocity)); set it with
    /// [`World::set_surface_velocity`](crate::World::set_surface_velocity).
    pub fn surface_velocity(&self) -> Vec3 {
        self.surface_velocity
    }

    /// Whether the contact rules of its own apply to its contacts: it is one-way or its
    /// surface moves ([`crate::hooks`]).
    pub(crate) fn has_contact_rules(&self) -> bool {
        self.one_way.is_some() || self.surface_velocity != Vec3::ZERO
    }

    /// Whether the body is asleep (skipped by the step until something wakes it).
    pub fn is_sleeping(&self) -> bool {
        self.sleeping
    }

    /// World bounding box of the shape.
    pub fn aabb(&self) -> Aabb {
        self.shape.aabb(&self.pose())
    }

    /// The bounding box grown to hold the body wherever its current velocities carry it within
    /// `dt` seconds: shifted along `v dt`, and grown by `|ω| r_max dt` for the turning.
    pub fn swept_aabb(&self, dt: f32) -> Aabb {
        self.sweep_aabb(self.aabb(), dt)
    }

    /// [`swept_aabb`](Self::swept_aabb) from the body's bounding box `bounds`, already computed.
    pub(crate) fn sweep_aabb(&self, bounds: Aabb, dt: f32) -> Aabb {
        let travel = self.linear_velocity * dt;
        let turn = Vec3::splat(self.angular_velocity.length() * self.max_extent * dt);
        Aabb::new(
            bounds.min.min(bounds.min + travel) - turn,
            bounds.max.max(bounds.max + travel) + turn,
        )
    }

    /// Upper bound of how fast any point of the body moves, m/s: `|v| + |ω| r_max`.
    pub fn max_point_speed(&self) -> f32 {
        self.linear_velocity.length() + self.max_extent * self.angular_velocity.length()
    }

    /// Whether the body counts as still this step, with `sleep_speed` the world's
    /// [`sleep_speed`](crate::world::WorldSettings::sleep_speed), m/s: its fastest point moves
    /// slower than `min(sleep_speed, r_max / 1 s)` ([`STILL_REACH_TIME`]), and no constant force or torque of
    /// its own pushes it along or about an axis it is free on: the engine cannot tell before the
    /// solve whether a contact holds such a push, and a push nothing holds starts from rest too
    /// slowly for speed alone to tell it from rest (0.02 N on a 1 kg box on ice reaches the
    /// default 5 cm/s after 2.5 s, long after half a second of stillness).
    pub(crate) fn is_still(&self, sleep_speed: f32) -> bool {
        let (force, torque) = self.applied_constant_force_and_torque();
        let pushed = self.locked_axes.free_linear(force) != Vec3::ZERO
            || self.locked_axes.free_angular(torque) != Vec3::ZERO;
        !pushed && self.max_point_speed() <= sleep_speed.min(self.max_extent / STILL_REACH_TIME)
    }

    /// Moves the body origin to `position` (finite), keeping its rotation and velocities.
    ///
    /// On a kinematic body this is a teleport: the pose jumps, and contacts see no velocity, so
    /// what rests on it is left behind (or pushed out of the overlap). To move a kinematic body
    /// with its contacts, give it a pose target ([`RigidBody::set_kinematic_target`]).
    pub fn set_position(&mut self, position: Vec3) -> Result<()> {
        check_position("position", position)?;
        self.set_origin_pose(Pose::new(position, self.rotation));
        self.wake();
        Ok(())
    }

    /// Turns the body about its origin to `rotation` (normalised; zero is an error). On a
    /// kinematic body this is a teleport, as [`RigidBody::set_position`] says.
    pub fn set_rotation(&mut self, rotation: Quat) -> Result<()> {
        let rotation = normalize_rotation("rotation", rotation)?;
        self.set_origin_pose(Pose::new(self.position(), rotation));
        self.wake();
        Ok(())
    }

    /// Sets the velocity of the centre of mass (ignored for static bodies; without its parts
    /// along locked axes).
    pub fn set_linear_velocity(&mut self, velocity: Vec3) -> Result<()> {
        check_length("linear_velocity", velocity, MAX_SPEED)?;
        if self.body_type != BodyType::Static {
            self.linear_velocity = velocity;
            self.hold_to_locked_axes();
            self.wake();
        }
        Ok(())
    }

    /// Sets the world angular velocity (ignored for static bodies; without its parts about
    /// locked axes).
    pub fn set_angular_velocity(&mut self, velocity: Vec3) -> Result<()> {
        check_length("angular_velocity", velocity, MAX_ANGULAR_SPEED)?;
        if self.body_type != BodyType::Static {
            self.angular_velocity = velocity;
            self.hold_to_locked_axes();
            self.wake();
        }
        Ok(())
    }

    /// The user data (default 0; the engine never reads it).
    pub fn user_data(&self) -> u128 {
        self.user_data
    }

    /// Sets the user data.
    pub fn set_user_data(&mut self, data: u128) {
        self.user_data = data;
    }

    /// The surface material of compound child `child` (its own where it has one, else the
    /// body's), or of mesh triangle `triangle` (its material's values where it has one, else the
    /// body's), or the body's for any other shape; the rolling radius is the child's shape's,
    /// or the body's shape's.
    pub(crate) fn material_of_child(&self, child: u32, triangle: Option<u32>) -> Material {
        let (own, rolling_radius) = match &self.shape {
            Shape::Compound(compound) => match compound.children().get(child as usize) {
                Some(child) => (
                    TriangleMaterial {
                        friction: child.friction,
                        restitution: child.restitution,
                        rolling_resistance: child.rolling_resistance,
                    },
                    child.shape.rolling_radius(),
                ),
                None => (TriangleMaterial::default(), self.shape.rolling_radius()),
            },
            Shape::TriMesh(mesh) => (
                triangle
                    .and_then(|triangle| mesh.triangle_material(triangle))
                    .copied()
                    .unwrap_or_default(),
                self.shape.rolling_radius(),
            ),
            _ => (TriangleMaterial::default(), self.shape.rolling_radius()),
        };
        Material {
            rolling_resistance: own.rolling_resistance.unwrap_or(self.rolling_resistance),
            rolling_radius,
            friction: own.friction.unwrap_or(self.friction),
            restitution: own.restitution.unwrap_or(self.restitution),
        }
    }

    /// Sets linear and angular damping, 1/s, both ≥ 0.
    pub fn set_damping(&mut self, linear: f32, angular: f32) -> Result<()> {
        check_non_negative("linear_damping", linear)?;
        check_non_negative("angular_damping", angular)?;
        self.linear_damping = linear;
        self.angular_damping = angular;
        Ok(())
    }

    /// Sets the mass of a dynamic body, kg, from [`MIN_MASS`] to [`MAX_MASS`], as if its shape
    /// were made of a denser or lighter material: the centre of mass stays, and the inertia keeps
    /// its distribution, `I_new = (m_new / m_old) · I_old` (so `I⁻¹_new = (m_old / m_new) · I⁻¹_old`).
    /// Static and kinematic bodies have no mass to set (they move as if infinitely heavy): the
    /// call leaves them as they are once `mass` is checked. Wakes the body.
    pub fn set_mass(&mut self, mass: f32) -> Result<()> {
        check_positive("mass", mass)?;
        check_range("mass", mass, MIN_MASS, MAX_MASS)?;
        if self.is_dynamic() {
            let scale = mass / self.mass;
            self.local_inertia *= scale;
            self.local_inverse_inertia *= self.mass / mass;
            self.mass = mass;
            self.inverse_mass = 1.0 / mass;
            self.update_world_inverse_inertia();
            self.wake();
        }
        Ok(())
    }

    /// Sets the Coulomb friction coefficient, ≥ 0.
    pub fn set_friction(&mut self, friction: f32) -> Result<()> {
        self.friction = check_non_negative("friction", friction)?;
        Ok(())
    }

    /// Sets the coefficient of restitution, 0 to 1.
    pub fn set_restitution(&mut self, restitution: f32) -> Result<()> {
        self.restitution = check_range("restitution", restitution, 0.0, 1.0)?;
        Ok(())
    }

    /// Sets the rolling resistance coefficient, ≥ 0.
    pub fn set_rolling_resistance(&mut self, rolling_resistance: f32) -> Result<()> {
        self.rolling_resistance = check_non_negative("rolling_resistance", rolling_resistance)?;
        Ok(())
    }

    /// Wakes the body if it sleeps; the rest of its sleeping group wakes at the next step.
    pub fn wake(&mut self) {
        self.sleeping = false;
        self.sleep_time = 0.0;
    }

    /// Whether the body is kinematic and moving faster than `speed` (m/s, its fastest point):
    /// what it touches or is jointed to must not fall asleep.
    pub(crate) fn is_kinematic_moving_faster_than(&self, speed: f32) -> bool {
        self.body_type == BodyType::Kinematic && self.max_point_speed() > speed
    }

    /// Whether the body is awake and moves this step: an awake dynamic body, or a kinematic one
    /// with a velocity. Only movers need fresh contacts and can wake sleeping bodies.
    pub(crate) fn is_awake_mover(&self) -> bool {
        match self.body_type {
            BodyType::Dynamic => !self.sleeping,
            BodyType::Kinematic => {
                self.linear_velocity != Vec3::ZERO || self.angular_velocity != Vec3::ZERO
            }
            BodyType::Static => false,
        }
    }

    /// Whether the step moves the body: a kinematic body, or a dynamic one awake.
    pub(crate) fn is_awake(&self) -> bool {
        match self.body_type {
            BodyType::Dynamic => !self.sleeping,
            BodyType::Kinematic => true,
            BodyType::Static => false,
        }
    }

    pub(crate) fn is_dynamic(&self) -> bool {
        self.body_type == BodyType::Dynamic
    }

    /// The distance from the centre of mass to the farthest corner of the shape's local bounding
    /// box, once the shape and centre of mass are set.
    fn update_max_extent(&mut self) {
        let local_bounds = self.shape.aabb(&Pose::IDENTITY);
        self.max_extent = (local_bounds.min - self.local_center_of_mass)
            .abs()
            .max((local_bounds.max - self.local_center_of_mass).abs())
            .length();
    }

    /// Places the body origin at `pose` and refreshes what follows from the rotation.
    fn set_origin_pose(&mut self, pose: Pose) {
        self.rotation = pose.rotation;
        self.center_of_mass = pose.transform_point(self.local_center_of_mass);
        self.update_world_inverse_inertia();
    }

    /// `I_world⁻¹ = R · I⁻¹ · Rᵀ`, restricted to the free rotation axes of a dynamic body with
    /// locked ones ([`LockedAxes::restrict_inverse_inertia`]).
    pub(crate) fn update_world_inverse_inertia(&mut self) {
        self.world_inverse_inertia = if self.is_dynamic() && self.locked_axes.locks_rotation() {
            self.locked_axes
                .restrict_inverse_inertia(self.world_inertia())
        } else {
            rotate_tensor(self.rotation, self.local_inverse_inertia)
        };
    }

    /// Takes a dynamic body's velocities along and about its locked axes away.
    fn hold_to_locked_axes(&mut self) {
        if self.is_dynamic() {
            self.linear_velocity = self.locked_axes.free_linear(self.linear_velocity);
            self.angular_velocity = self.locked_axes.free_angular(self.angular_velocity);
        }
    }
}

/// Mass properties of a dynamic body and its inverse inertia, with every failure named: a
/// halfspace, triangle mesh or heightfield (field `shape`); a shape whose mass or inertia is out of `f32`'s reach even at unit
/// density (`shape.radius`, `shape.half_extents`, …); otherwise a mass or inertia that is not
/// positive and finite (field `mass` when given, `density` otherwise).
fn dynamic_mass_properties(desc: &BodyDesc) -> Result<(MassProperties, Mat3)> {
    if let Some(properties) = desc.mass_properties {
        // Checked positive definite by `check_mass_properties`; the spread is bounded as for
        // every body so that the solver keeps its conditioning.
        let properties = properties.with_inertia_spread_at_most(MAX_INERTIA_RATIO);
        let inverse = inverse_inertia(&properties)
            .ok_or_else(|| Error::new("mass_properties.inertia", ErrorKind::NotPositiveDefinite))?;
        return Ok((properties, inverse));
    }
    let properties = desc.shape.mass_properties(desc.density).ok_or_else(|| {
        let kind = if desc.shape.is_triangulated() {
            ErrorKind::MeshOnDynamicBody
        } else {
            ErrorKind::HalfspaceOnDynamicBody
        };
        Error::new("shape", kind)
    })?;
    let properties = match desc.mass {
        Some(mass) => properties.scaled_to_mass(mass),
        None => properties,
    }
    .with_inertia_spread_at_most(MAX_INERTIA_RATIO);
    if let Some(inverse_inertia) = inverse_inertia(&properties) {
        let mass_out_of_range = !(MIN_MASS..=MAX_MASS).contains(&properties.mass);
        if desc.mass.is_none() && mass_out_of_range {
            // The densities that give the mass limits, so that the message says what to pass.
            let volume = properties.mass / desc.density;
            let kind = ErrorKind::OutOfRange {
                value: desc.density,
                min: MIN_MASS / volume,
                max: MAX_MASS / volume,
            };
            return Err(Error::new("density", kind));
        }
        return Ok((properties, inverse_inertia));
    }
    let unit_density = desc.shape.mass_properties(1.0);
    if unit_density.as_ref().and_then(inverse_inertia).is_none() {
        let field = format!("shape.{}", desc.shape.size_field());
        return Err(Error::new(field, ErrorKind::UnrepresentableSize));
    }
    let field = if desc.mass.is_some() {
        "mass"
    } else {
        "density"
    };
    Err(Error::new(field, ErrorKind::InvalidMass))
}

/// Checks explicit mass properties: a mass within the engine's limits, a finite centre of mass
/// within [`MAX_SIZE`] of the origin, a finite symmetric inertia with positive principal moments
/// (Sylvester's criterion on the leading minors, in `f64`).
fn check_mass_properties(properties: &MassProperties) -> Result<()> {
    check_positive("mass", properties.mass)?;
    check_range("mass", properties.mass, MIN_MASS, MAX_MASS)?;
    check_length("center_of_mass", properties.center_of_mass, MAX_SIZE)?;
    let inertia = properties.inertia.as_dmat3();
    if !properties.inertia.is_finite() {
        return Err(Error::new("inertia", ErrorKind::NotFinite));
    }
    let symmetric = inertia.x_axis.y == inertia.y_axis.x
        && inertia.x_axis.z == inertia.z_axis.x
        && inertia.y_axis.z == inertia.z_axis.y;
    let minor = inertia.x_axis.x * inertia.y_axis.y - inertia.x_axis.y * inertia.y_axis.x;
    if !(symmetric && inertia.x_axis.x > 0.0 && minor > 0.0 && inertia.determinant() > 0.0) {
        return Err(Error::new("inertia", ErrorKind::NotPositiveDefinite));
    }
    Ok(())
}

/// The inverse inertia, when the mass and the inertia are positive, finite and invertible. Where
/// the `f32` determinant overflows (a large body) or underflows (a small one) while the inertia
/// and its inverse are both fine in `f32`, the inverse is taken in `f64`.
fn inverse_inertia(properties: &MassProperties) -> Option<Mat3> {
    if !(properties.mass.is_finite() && properties.mass > 0.0 && properties.inertia.is_finite()) {
        return None;
    }
    let usable = |inverse: &Mat3| {
        let diagonal = Vec3::new(inverse.x_axis.x, inverse.y_axis.y, inverse.z_axis.z);
        inverse.is_finite() && diagonal.min_element() > 0.0
    };
    let determinant = properties.inertia.determinant();
    if determinant.is_finite() && determinant > 0.0 {
        let inverse = properties.inertia.inverse();
        if usable(&inverse) {
            return Some(inverse);
        }
    }
    let inertia = properties.inertia.as_dmat3();
    if inertia.determinant() <= 0.0 {
        return None;
    }
    Some(inertia.inverse().as_mat3()).filter(usable)
}
