//! Contact hooks: a callback that sees each contact before the solver does, and may change its
//! friction, restitution, surface velocity and normal, or switch off some of its points or the
//! whole contact for this step (rapier's `PhysicsHooks::modify_solver_contacts`, Box2D's
//! pre-solve).
//!
//! [`World::step_with_hooks`](crate::World::step_with_hooks) calls
//! [`ContactHooks::modify_contact`] once per contact manifold (one per pair of touching
//! colliders, or per pair of convex parts: a body on a mesh may have several), speculative ones
//! (surfaces still apart by less than the contact margin) included, after the narrow phase made
//! the contacts and gave them their combined materials and before the solver builds its
//! constraints. The order is the contacts' (sorted by [`Contact::bodies`], then
//! [`Contact::children`]), so a hook that depends only on what it is shown steps the same bits
//! every run. Contacts of which no body is awake are not shown: they are parked, unchanged.
//!
//! The continuous pass (a body moving more than four times its reach in a step is swept, and
//! put back where it first meets another) does not see the hooks: a fast body whose contact a
//! hook switches off is still stopped where it meets the other. To let such bodies through, make
//! the pair ignore each other ([`World::set_pair_ignored`](crate::World::set_pair_ignored)).
//!
//! A change lasts one step: the contact cache keeps each contact as the narrow phase found it, so
//! the hook is shown it afresh at the next step. The step's events see the contacts as changed
//! (a switched-off contact does not touch, so it starts no [`ContactEvent`](crate::ContactEvent)),
//! and [`World::contacts`](crate::World::contacts) lists them as found, with the impulses the
//! solver gave them (zero on a switched-off point).
//!
//! # Rules of the bodies' own
//!
//! Two body properties are built on the same hook, and apply in [`World::step`] too, before the
//! user's hook, which sees and may change their outcome. [`BodyDesc`] sets them, and
//! [`World::set_one_way`] and [`World::set_surface_velocity`] change them (waking the body and
//! what sleeps on it):
//!
//! - **Surface velocity** ([`BodyDesc::surface_velocity`]): a conveyor belt. A contact's
//!   [`surface_velocity`](ContactModification::surface_velocity) is `R_A u_A − R_B u_B`, each
//!   body's surface velocity `u` (body frame) turned into the world by its rotation `R`: the
//!   velocity of A's surface relative to B's. The solver's friction rows drive the velocity of
//!   B's contact point relative to A's toward its part in the contact plane, instead of toward
//!   zero, with the same Coulomb limit `|λ_t| ≤ μ λ_n`. A box set down on a static belt moving
//!   at `v` so speeds up at `μ g` and rides at `v` after `v / (μ g)`.
//! - **One-way** ([`BodyDesc::one_way`]): a platform that bodies pass through from one side and
//!   stand on from the other. The rule has no memory: a contact of a one-way body P counts only
//!   when the normal from P to the other body lies within 45° of P's one-way direction (turned
//!   by P's rotation) and its deepest point is no deeper than [`ONE_WAY_MAX_DEPTH`]; otherwise
//!   the whole contact is switched off for the step. A body coming from the other side meets P
//!   with a normal pointing away from the direction, so it passes in; once inside, it is deeper
//!   than [`ONE_WAY_MAX_DEPTH`] until it has nearly left on the far side, where the contact
//!   counts again and lifts it out. A body landing on top meets P with the normal along the
//!   direction, its speculative contact stops it before it sinks in, and it stands.
//!
//!   The continuous pass, which sweeps bodies too fast for their contacts, follows the same
//!   normal rule: a fast body thrown up through the platform is not stopped under it.
//!
//!   Limits of a rule without memory: a body that stops inside the platform (it was thrown too
//!   slowly to cross it) is deep and falls back out the side it came from. A body sliding into
//!   the platform's edge meets it with a sideways normal and passes into it; it is lifted onto
//!   the top if it is no deeper than [`ONE_WAY_MAX_DEPTH`] when the normal turns up (a thin
//!   platform, a body sliding along its top surface), else it carries on through. A body whose
//!   half-size plus the platform's half-thickness is under [`ONE_WAY_MAX_DEPTH`] (a marble
//!   crossing a thin sheet) counts again as soon as its centre passes the platform's middle, and
//!   is lifted out on the far side: it still passes, a little sooner. A body that ends a step
//!   less than [`ONE_WAY_MAX_DEPTH`] inside the far side touches the platform for the next step
//!   (a contact event starts and stops), though moving away it is pushed by nothing.
//!
//! ```
//! use rebond::hooks::ContactModification;
//! use rebond::{BodyDesc, Shape, Vec3, World, WorldSettings};
//!
//! let mut world = World::new(WorldSettings::default())?;
//! let ice = world.add_body(
//!     BodyDesc::static_body(Shape::cuboid(Vec3::new(5.0, 0.5, 5.0))?)
//!         .position(Vec3::new(0.0, -0.5, 0.0)),
//! )?;
//! let puck = world.add_body(
//!     BodyDesc::dynamic(Shape::cylinder(0.2, 0.05)?)
//!         .position(Vec3::new(0.0, 0.05, 0.0))
//!         .linear_velocity(Vec3::new(2.0, 0.0, 0.0)),
//! )?;
//! // Every contact with the ice loses its friction.
//! let mut frictionless_ice = |contact: &mut ContactModification| {
//!     let (a, b) = contact.bodies();
//!     if a == ice || b == ice {
//!         contact.set_friction(0.0).expect("zero is a friction coefficient");
//!     }
//! };
//! for _ in 0..60 {
//!     world.step_with_hooks(1.0 / 60.0, &mut frictionless_ice)?;
//! }
//! // Without friction the puck keeps its speed.
//! assert!((world.body(puck)?.linear_velocity().x - 2.0).abs() < 0.01);
//! # Ok::<(), rebond::Error>(())
//! ```
//!
//! [`World::step`]: crate::World::step
//! [`World::set_one_way`]: crate::World::set_one_way
//! [`World::set_surface_velocity`]: crate::World::set_surface_velocity
//! [`BodyDesc`]: crate::BodyDesc
//! [`BodyDesc::surface_velocity`]: crate::BodyDesc#structfield.surface_velocity
//! [`BodyDesc::one_way`]: crate::BodyDesc#structfield.one_way

use crate::body::{BodyHandle, RigidBody};
use crate::collision::contact_cache::Contact;
use crate::collision::{ContactPoint, MAX_MANIFOLD_POINTS};
use crate::error::{
    check_direction, check_length, check_non_negative, check_range, Error, ErrorKind, Result,
};
use crate::limits::MAX_SPEED;
use crate::material::Material;
use crate::math::Vec3;

/// A one-way body's contact counts only while its deepest point is no deeper than this, m: a
/// body crossing the platform is deeper, a body resting on it sinks by its contact spring's sag
/// (millimetres: docs/physics.md) and a body landing on it is stopped by its speculative contact
/// before it sinks in.
pub const ONE_WAY_MAX_DEPTH: f32 = 0.05;

/// A one-way body's contact counts only while its normal, from the one-way body to the other,
/// is within this angle's cosine of the one-way direction: 45°, so a body resting on the
/// platform's rounded or bevelled edge still stands, and a body meeting its side passes.
pub const ONE_WAY_MIN_COSINE: f32 = std::f32::consts::FRAC_1_SQRT_2;

/// Whether bodies `a` and `b` meeting with the unit `normal` (from A toward B) hold each other
/// as far as one-way bodies go: the normal from each one-way body of the two toward the other
/// lies within 45° of its one-way direction. The contacts' rule adds a depth; the continuous
/// pass, whose bodies meet touching, reads it alone (`world/continuous.rs`).
pub(crate) fn one_way_holds(a: &RigidBody, b: &RigidBody, normal: Vec3) -> bool {
    let faces = |platform: &RigidBody, outward: Vec3| {
        platform.one_way.is_none_or(|direction| {
            outward.dot(platform.rotation * direction) >= ONE_WAY_MIN_COSINE
        })
    };
    faces(a, normal) && faces(b, -normal)
}

/// What a step calls on each contact before the solve ([`crate::hooks`]). A closure
/// `FnMut(&mut ContactModification)` is one.
pub trait ContactHooks {
    /// Looks at one contact and changes what the solver does with it this step.
    fn modify_contact(&mut self, contact: &mut ContactModification<'_>);
}

impl<F: FnMut(&mut ContactModification<'_>)> ContactHooks for F {
    fn modify_contact(&mut self, contact: &mut ContactModification<'_>) {
        self(contact);
    }
}

/// One contact as a hook sees it: its bodies, colliders, normal and points, and what the solver
/// will do with it this step, which the hook may change. Every setter checks its value; on error
/// nothing changes.
#[derive(Debug)]
pub struct ContactModification<'a> {
    contact: &'a Contact,
    body_a: &'a RigidBody,
    body_b: &'a RigidBody,
    normal: Vec3,
    normal_changed: bool,
    enabled: [bool; MAX_MANIFOLD_POINTS],
    friction: f32,
    restitution: f32,
    surface_velocity: Vec3,
}

/// What a hook changed of one contact, for the contact cache to apply
/// ([`ContactCache::apply_edit`](crate::collision::contact_cache::ContactCache::apply_edit)).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactEdit {
    /// The material with the hook's friction and restitution.
    pub material: Material,
    /// m/s, world frame: A's surface relative to B's.
    pub surface_velocity: Vec3,
    /// The normal the hook set, unit, from A toward B.
    pub normal: Option<Vec3>,
    /// Which points stay, when the hook switched some off.
    pub kept: Option<[bool; MAX_MANIFOLD_POINTS]>,
}

impl<'a> ContactModification<'a> {
    /// `contact` between `body_a` and `body_b`, unchanged.
    pub(crate) fn new(contact: &'a Contact, body_a: &'a RigidBody, body_b: &'a RigidBody) -> Self {
        Self {
            contact,
            body_a,
            body_b,
            normal: contact.normal(),
            normal_changed: false,
            enabled: [true; MAX_MANIFOLD_POINTS],
            friction: contact.friction(),
            restitution: contact.restitution(),
            surface_velocity: Vec3::ZERO,
        }
    }

    /// The two bodies, A then B (A's handle is the smaller).
    pub fn bodies(&self) -> (BodyHandle, BodyHandle) {
        self.contact.bodies()
    }

    /// The colliders of A and B that touch: the compound child, or the mesh's manifold, as in
    /// [`Contact::children`] (0 for a body whose shape is one convex shape).
    pub fn colliders(&self) -> (u32, u32) {
        self.contact.children()
    }

    /// The triangle of the mesh body (A or B) the contact is on, as [`Contact::triangle`]:
    /// `None` unless one body is a triangle mesh or heightfield. A hook may pick a sound or a
    /// rule by it; the friction and restitution it starts from are already the triangle's.
    pub fn triangle(&self) -> Option<u32> {
        self.contact.triangle()
    }

    /// Body A.
    pub fn body_a(&self) -> &RigidBody {
        self.body_a
    }

    /// Body B.
    pub fn body_b(&self) -> &RigidBody {
        self.body_b
    }

    /// The unit world normal the solver pushes along, from A toward B.
    pub fn normal(&self) -> Vec3 {
        self.normal
    }

    /// Sets the normal the solver pushes along, from A toward B, normalised here (zero or not
    /// finite is an error for `normal`). The points' separations stay as measured along the
    /// narrow phase's normal.
    pub fn set_normal(&mut self, normal: Vec3) -> Result<()> {
        self.normal = check_direction("normal", normal)?;
        self.normal_changed = true;
        Ok(())
    }

    /// The contact points, with their world positions and separations (negative where the
    /// surfaces overlap, positive for a speculative point still apart), m.
    pub fn points(&self) -> &[ContactPoint] {
        self.contact.points()
    }

    /// Whether point `index` takes part in the solve (false also for an index past the points).
    pub fn is_point_enabled(&self, index: usize) -> bool {
        index < self.points().len() && self.enabled[index]
    }

    /// Switches point `index` on or off for this step; an index past the points is an error
    /// for `point`.
    pub fn set_point_enabled(&mut self, index: usize, enabled: bool) -> Result<()> {
        let len = self.points().len();
        if index >= len {
            let index = u32::try_from(index).unwrap_or(u32::MAX);
            return Err(Error::new(
                "point",
                ErrorKind::IndexOutOfRange { index, len },
            ));
        }
        self.enabled[index] = enabled;
        Ok(())
    }

    /// Whether any point takes part in the solve.
    pub fn is_enabled(&self) -> bool {
        (0..self.points().len()).any(|index| self.enabled[index])
    }

    /// Switches every point on or off for this step: off, the bodies pass through each other.
    pub fn set_enabled(&mut self, enabled: bool) {
        self.enabled = [enabled; MAX_MANIFOLD_POINTS];
    }

    /// The Coulomb friction coefficient, the surfaces' combined by the world's rule unless a
    /// hook changed it.
    pub fn friction(&self) -> f32 {
        self.friction
    }

    /// Sets the friction coefficient, finite and ≥ 0 (else an error for `friction`).
    pub fn set_friction(&mut self, friction: f32) -> Result<()> {
        self.friction = check_non_negative("friction", friction)?;
        Ok(())
    }

    /// The coefficient of restitution, the surfaces' combined unless a hook changed it.
    pub fn restitution(&self) -> f32 {
        self.restitution
    }

    /// Sets the coefficient of restitution, 0 to 1 (else an error for `restitution`).
    pub fn set_restitution(&mut self, restitution: f32) -> Result<()> {
        self.restitution = check_range("restitution", restitution, 0.0, 1.0)?;
        Ok(())
    }

    /// The velocity of A's surface relative to B's at the contact, m/s, world frame: friction
    /// drives the velocity of B's contact point relative to A's toward its part in the contact
    /// plane (the part along the normal does nothing). Zero for plain friction; the bodies'
    /// own surface velocities give `R_A u_A − R_B u_B` ([`crate::hooks`]).
    pub fn surface_velocity(&self) -> Vec3 {
        self.surface_velocity
    }

    /// Sets the velocity of A's surface relative to B's, m/s, world frame, at most
    /// [`MAX_SPEED`] long (else an error for `surface_velocity`).
    pub fn set_surface_velocity(&mut self, velocity: Vec3) -> Result<()> {
        self.surface_velocity = check_length("surface_velocity", velocity, MAX_SPEED)?;
        Ok(())
    }

    /// Applies the rules of the bodies' own ([`crate::hooks`]): their surface velocities, and
    /// a one-way body's contact switched off unless its normal and depth say the other body is
    /// on the side it stands on.
    pub(crate) fn apply_body_rules(&mut self) {
        let (a, b) = (self.body_a, self.body_b);
        self.surface_velocity = a.rotation * a.surface_velocity - b.rotation * b.surface_velocity;
        if a.one_way.is_some() || b.one_way.is_some() {
            let shallow = self.contact.manifold.deepest_separation() >= -ONE_WAY_MAX_DEPTH;
            if !(shallow && one_way_holds(a, b, self.normal)) {
                self.set_enabled(false);
            }
        }
    }

    /// What the hooks changed.
    pub(crate) fn edit(&self) -> ContactEdit {
        let count = self.points().len();
        let kept = self.enabled[..count]
            .contains(&false)
            .then_some(self.enabled);
        ContactEdit {
            material: Material {
                friction: self.friction,
                restitution: self.restitution,
                ..self.contact.material
            },
            surface_velocity: self.surface_velocity,
            normal: self.normal_changed.then_some(self.normal),
            kept,
        }
    }
}
