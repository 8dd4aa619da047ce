//! A body's description: everything needed to create one, with the builder calls that set it.

use super::{BodyType, KinematicPath, LockedAxes};
use crate::filter::InteractionGroups;
use crate::mass::MassProperties;
use crate::math::{Quat, Vec3};
use crate::shape::Shape;

/// Default density, kg/m³ (water).
pub const DEFAULT_DENSITY: f32 = 1000.0;
/// Default Coulomb friction coefficient.
pub const DEFAULT_FRICTION: f32 = 0.5;

/// Everything needed to create a body. Values are checked when the body is added to a world.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BodyDesc {
    /// Dynamic, static or kinematic.
    pub body_type: BodyType,
    /// The collision shape, in the body frame.
    pub shape: Shape,
    /// World position of the body origin, metres.
    pub position: Vec3,
    /// World orientation; normalised when added (a zero quaternion is an error).
    pub rotation: Quat,
    /// Velocity of the centre of mass, m/s (ignored for static bodies).
    pub linear_velocity: Vec3,
    /// Angular velocity, rad/s, world frame (ignored for static bodies).
    pub angular_velocity: Vec3,
    /// Density, kg/m³, default 1000; mass and inertia follow from the shape.
    pub density: f32,
    /// Mass, kg: overrides `density`, the inertia is scaled to match.
    pub mass: Option<f32>,
    /// Explicit mass, centre of mass (body frame, m) and inertia (about the centre of mass, body
    /// axes, kg·m²), default `None`: they replace what the shape and `density` give, for a model
    /// whose inertia is measured or computed elsewhere (an MJCF `inertial`, a URDF link). Dynamic
    /// bodies only; checked when added: mass within the engine's limits, everything finite, the
    /// inertia symmetric and positive definite. Not together with `mass`.
    pub mass_properties: Option<MassProperties>,
    /// Coulomb friction coefficient, ≥ 0, default 0.5.
    pub friction: f32,
    /// Coefficient of restitution, 0 to 1, default 0.
    pub restitution: f32,
    /// Rolling resistance coefficient `c`, ≥ 0, dimensionless, default 0 (none): a contact
    /// resists the rolling of the surfaces over each other with a torque of at most `c R N`, `R`
    /// the radius the body rolls on ([`Shape::rolling_radius`]) and `N` the normal force, so a
    /// ball rolling on flat ground slows at `(5/7) c g` and rests on slopes up to `atan c`
    /// (docs/physics.md, "Rolling resistance"). A pair uses the larger coefficient of its two.
    pub rolling_resistance: f32,
    /// World force applied during every step, newtons, at the centre of mass or at
    /// `constant_force_point`.
    pub constant_force: Vec3,
    /// Where `constant_force` acts: a point in the body frame (it turns with the body), metres
    /// from the body origin; `None` (the default) for the centre of mass. Off the centre of mass
    /// the force also gives the torque `r × F`, `r` from the centre of mass to the point.
    pub constant_force_point: Option<Vec3>,
    /// World torque applied during every step, N·m.
    pub constant_torque: Vec3,
    /// Linear damping, 1/s, ≥ 0: `v ← v / (1 + h·c)` each substep.
    pub linear_damping: f32,
    /// Angular damping, 1/s, ≥ 0: `ω ← ω / (1 + h·c)` each substep.
    pub angular_damping: f32,
    /// Whether the body may fall asleep, default true.
    pub can_sleep: bool,
    /// World axes along which the body never moves and about which it never turns, default
    /// none ([`LockedAxes`]); only dynamic bodies feel them.
    pub locked_axes: LockedAxes,
    /// Whether the body is a sensor, default false: it never pushes anything and nothing pushes
    /// it (no contacts), but it reports the bodies that enter and leave its shape
    /// ([`crate::events::SensorEvent`]). A sensor sees dynamic and kinematic bodies, and static
    /// ones if it moves itself (two static bodies are never paired); not other sensors. A body
    /// asleep inside it stays inside; a sensor never wakes anything.
    pub sensor: bool,
    /// Which bodies it interacts with (contacts and sensors), default [`InteractionGroups::ALL`].
    pub collision_groups: InteractionGroups,
    /// Contacts of this body whose normal force exceeds this, newtons, are reported as
    /// [`crate::events::ContactForceEvent`]s; default infinity (no reports). A pair uses the
    /// smaller threshold of its two bodies.
    pub contact_force_threshold: f32,
    /// Whatever the user wants to keep with the body (an entity id, an index), default 0; the
    /// engine never reads it.
    pub user_data: u128,
    /// Keyframes the body follows, kinematic bodies only, default `None`: the body is placed at
    /// the first point's pose (`position` and `rotation` give way to it) and each step carries
    /// it to the path's pose at the step's end ([`KinematicPath`]).
    pub path: Option<KinematicPath>,
    /// The direction, in the body frame, bodies pass through it from, default `None` (a solid
    /// body): a platform with `one_way = +Y` lets bodies jump through it from below and stand
    /// on top. Normalised when added; a zero or non-finite one is an error. Its contacts count
    /// only where the normal from this body to the other lies within 45° of the direction and
    /// the contact is no deeper than [`ONE_WAY_MAX_DEPTH`](crate::hooks::ONE_WAY_MAX_DEPTH)
    /// (the rule and its limits: [`crate::hooks`]).
    pub one_way: Option<Vec3>,
    /// The velocity of the body's surface relative to the body, m/s, body frame (it turns with
    /// the body), default zero: a conveyor belt. Friction drives what touches the body toward
    /// it along the contact plane (the part along a contact's normal does nothing), so a box
    /// on a static conveyor with `[1, 0, 0]` is carried along +X at 1 m/s once friction
    /// brought it there, in `v / (μ g)` seconds on flat ground ([`crate::hooks`]).
    pub surface_velocity: Vec3,
}

impl BodyDesc {
    /// A body of the given type and shape at the origin, at rest, with the default material.
    pub fn new(body_type: BodyType, shape: Shape) -> Self {
        Self {
            body_type,
            shape,
            position: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            linear_velocity: Vec3::ZERO,
            angular_velocity: Vec3::ZERO,
            density: DEFAULT_DENSITY,
            mass: None,
            mass_properties: None,
            friction: DEFAULT_FRICTION,
            restitution: 0.0,
            rolling_resistance: 0.0,
            constant_force: Vec3::ZERO,
            constant_force_point: None,
            constant_torque: Vec3::ZERO,
            linear_damping: 0.0,
            angular_damping: 0.0,
            can_sleep: true,
            locked_axes: LockedAxes::NONE,
            sensor: false,
            collision_groups: InteractionGroups::ALL,
            contact_force_threshold: f32::INFINITY,
            user_data: 0,
            path: None,
            one_way: None,
            surface_velocity: Vec3::ZERO,
        }
    }

    /// A dynamic body: moved by gravity, forces and contacts.
    pub fn dynamic(shape: Shape) -> Self {
        Self::new(BodyType::Dynamic, shape)
    }

    /// A static body ([`BodyType::Static`], `"static"` in scene files): never moves, infinite
    /// mass.
    pub fn static_body(shape: Shape) -> Self {
        Self::new(BodyType::Static, shape)
    }

    /// A kinematic body: moves at the velocity it is given, or to the pose targets or along the
    /// path it is given, pushes dynamic bodies, is pushed by nothing.
    pub fn kinematic(shape: Shape) -> Self {
        Self::new(BodyType::Kinematic, shape)
    }

    /// Sets the world position of the body origin.
    pub fn position(mut self, position: Vec3) -> Self {
        self.position = position;
        self
    }

    /// Sets the world orientation.
    pub fn rotation(mut self, rotation: Quat) -> Self {
        self.rotation = rotation;
        self
    }

    /// Sets the initial linear velocity.
    pub fn linear_velocity(mut self, velocity: Vec3) -> Self {
        self.linear_velocity = velocity;
        self
    }

    /// Sets the initial angular velocity (world frame).
    pub fn angular_velocity(mut self, velocity: Vec3) -> Self {
        self.angular_velocity = velocity;
        self
    }

    /// Sets the density.
    pub fn density(mut self, density: f32) -> Self {
        self.density = density;
        self
    }

    /// Sets the mass, overriding the density.
    pub fn mass(mut self, mass: f32) -> Self {
        self.mass = Some(mass);
        self
    }

    /// Sets explicit mass properties, overriding the shape's and the density's.
    pub fn mass_properties(mut self, properties: MassProperties) -> Self {
        self.mass_properties = Some(properties);
        self
    }

    /// Sets the friction coefficient.
    pub fn friction(mut self, friction: f32) -> Self {
        self.friction = friction;
        self
    }

    /// Sets the coefficient of restitution.
    pub fn restitution(mut self, restitution: f32) -> Self {
        self.restitution = restitution;
        self
    }

    /// Sets the rolling resistance coefficient.
    pub fn rolling_resistance(mut self, rolling_resistance: f32) -> Self {
        self.rolling_resistance = rolling_resistance;
        self
    }

    /// Sets the force applied at the centre of mass during every step.
    pub fn constant_force(mut self, force: Vec3) -> Self {
        self.constant_force = force;
        self.constant_force_point = None;
        self
    }

    /// Sets the world force applied during every step at `point`, a point in the body frame
    /// (it turns with the body).
    pub fn constant_force_at_point(mut self, force: Vec3, point: Vec3) -> Self {
        self.constant_force = force;
        self.constant_force_point = Some(point);
        self
    }

    /// Sets the torque applied during every step.
    pub fn constant_torque(mut self, torque: Vec3) -> Self {
        self.constant_torque = torque;
        self
    }

    /// Locks world axes of translation and rotation ([`LockedAxes`]).
    pub fn locked_axes(mut self, locked_axes: LockedAxes) -> Self {
        self.locked_axes = locked_axes;
        self
    }

    /// Sets the linear and angular damping.
    pub fn damping(mut self, linear: f32, angular: f32) -> Self {
        self.linear_damping = linear;
        self.angular_damping = angular;
        self
    }

    /// Sets whether the body may fall asleep.
    pub fn can_sleep(mut self, can_sleep: bool) -> Self {
        self.can_sleep = can_sleep;
        self
    }

    /// Sets whether the body is a sensor.
    pub fn sensor(mut self, sensor: bool) -> Self {
        self.sensor = sensor;
        self
    }

    /// Sets the collision groups.
    pub fn collision_groups(mut self, groups: InteractionGroups) -> Self {
        self.collision_groups = groups;
        self
    }

    /// Sets the contact force above which contacts are reported, newtons (not negative).
    pub fn contact_force_threshold(mut self, threshold: f32) -> Self {
        self.contact_force_threshold = threshold;
        self
    }

    /// Sets the user data.
    pub fn user_data(mut self, data: u128) -> Self {
        self.user_data = data;
        self
    }

    /// Sets the keyframes a kinematic body follows.
    pub fn path(mut self, path: KinematicPath) -> Self {
        self.path = Some(path);
        self
    }

    /// Makes the body one-way: bodies pass through it from `direction` (body frame), and
    /// stand on it from the other side ([`BodyDesc::one_way`](BodyDesc#structfield.one_way)).
    pub fn one_way(mut self, direction: Vec3) -> Self {
        self.one_way = Some(direction);
        self
    }

    /// Sets the velocity of the body's surface relative to the body, m/s, body frame: a
    /// conveyor belt ([`BodyDesc::surface_velocity`](BodyDesc#structfield.surface_velocity)).
    pub fn surface_velocity(mut self, velocity: Vec3) -> Self {
        self.surface_velocity = velocity;
        self
    }
}
