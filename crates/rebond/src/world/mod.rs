//! The world: owns bodies and settings, and advances them in time. Its joint calls are in
//! `joints.rs`, its coupling calls in `couplings.rs`, and the placing of bodies from joint coordinates in `joint_coordinates.rs`.
//!
//! [`World::step`] is the list of the step's stages, in order, each with where it lives:
//!
//! 1. kinematic bodies take the velocity that carries them to their targets (`body/kinematic.rs`);
//! 2. sleeping groups touched or pushed since the last step wake (`island.rs`);
//! 3. contacts: broad phase, narrow phase, the contact cache, and the groups new contacts wake
//!    (`contact_update.rs`, `collision/`);
//! 4. contact hooks: the bodies' own rules (one-way, surface velocity) and the user's hooks
//!    change this step's contacts (`contact_update.rs`, [`crate::hooks`]);
//! 5. islands: one union–find over the awake bodies' joints, couplings and touching contacts, which also
//!    gives the joint groups (`island.rs`, built through `Solver::build_islands`);
//! 6. the solve, island by island: substeps of the soft step over every kind of constraint
//!    (`solver/`: `stages.rs` runs them, `solver/mod.rs` lists them);
//! 7. kinematic bodies land exactly on their targets (`body/kinematic.rs`);
//! 8. the continuous pass puts back fast bodies that went through another, and pushes ahead of
//!    a moving kinematic body what it would pass (`continuous.rs`);
//! 9. joints measure their forces and break (`joint/set.rs`, `joints.rs`);
//! 10. contact, force and sensor events (`events.rs`);
//! 11. sleep: the contacts the hooks changed are put back as found, the same islands fall
//!     asleep or stay awake, and what no awake body uses is parked (`island.rs`).

mod contact_update;
mod continuous;
mod couplings;
#[cfg(feature = "serde")]
mod decoded;
mod joint_coordinates;
mod joints;

use crate::arena::{new_world, Arena};
use crate::body::{BodyDesc, BodyHandle, BodyType, RigidBody};
use crate::collision::broad_phase::BroadPhase;
use crate::collision::contact_cache::{Contact, ContactCache};
use crate::collision::narrow_phase::NarrowPhase;
use crate::collision::SPECULATIVE_DISTANCE;
use crate::coupling::CouplingSet;
use crate::error::{
    check_count, check_direction, check_length, check_non_negative, check_positive, check_range,
    Error, ErrorKind, Result,
};
use crate::events::{ContactEvent, ContactForceEvent, EventTracker, SensorEvent};
use crate::filter::{ordered, Colliders, IgnoredPairs, InteractionGroups};
use crate::hooks::ContactHooks;
use crate::island::Islands;
use crate::joint::{JointHandle, JointSet};
use crate::limits::{MAX_GRAVITY, MAX_SPEED, MAX_TIMESTEP, MIN_TIMESTEP};
use crate::material::CombineRule;
use crate::math::{Aabb, Vec3};
use crate::solver::{ContactSettings, JointSettings, Solver, Sources, StepSettings};
use crate::sorted::merged;

/// Default gravity, m/s²: Earth's, along −Y.
pub const DEFAULT_GRAVITY: Vec3 = Vec3::new(0.0, -9.81, 0.0);
/// Default number of substeps per step: with 8, contacts can be stiff enough (120 Hz) that a
/// 20-row flat pyramid sinks about 2 mm; see docs/physics.md.
pub const DEFAULT_SUBSTEPS: u32 = 8;
/// Largest number of substeps accepted per step.
pub const MAX_SUBSTEPS: u32 = 64;
/// Default speed limit of a body's centre of mass, m/s (about three times the speed of sound):
/// it keeps a runaway body's position finite.
pub const DEFAULT_MAX_LINEAR_SPEED: f32 = 1000.0;

/// World-wide settings: what the step does, with units and defaults. Every value is checked
/// when the world is made or the settings replaced; an error names the field. A scene file sets
/// each at its top level under the field's name (`docs/scene-format.md`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct WorldSettings {
    /// Gravity, m/s², default `[0, −9.81, 0]`, at most [`MAX_GRAVITY`] long.
    pub gravity: Vec3,
    /// Substeps per step, 1 to [`MAX_SUBSTEPS`], default [`DEFAULT_SUBSTEPS`].
    pub substeps: u32,
    /// Speed limit of every body's centre of mass, m/s, default [`DEFAULT_MAX_LINEAR_SPEED`],
    /// at most [`MAX_SPEED`].
    /// Angular speed is limited too, to a quarter turn per substep.
    pub max_linear_speed: f32,
    /// Stiffness of contacts, Hz, > 0, default 120: a contact is a spring of this frequency for
    /// the two bodies' effective mass, `k = m_eff (2π f)²`, so a load sags it by `load / k`.
    /// Capped at a quarter of the substep rate (`ω h ≤ π/2`), where the spring stays stable:
    /// 60 Hz at 4 substeps of a 60 Hz step, 120 Hz from 8.
    pub contact_hertz: f32,
    /// Damping ratio of the contact spring, ≥ 0, default 5 (over-damped: corrections do not
    /// bounce).
    pub contact_damping_ratio: f32,
    /// Fastest a contact pushes overlapping bodies apart, m/s, > 0, default 3.
    pub contact_push_speed: f32,
    /// Bodies approaching slower than this, m/s, ≥ 0, do not bounce, default 1 (so resting
    /// bodies do not jitter); 0 makes every approach with restitution bounce.
    pub restitution_threshold: f32,
    /// Contact points are made while two surfaces are still this far apart, m, ≥ 0, default
    /// 0.02, plus the distance they can close in one step while that is within four times the
    /// sizes of the moving bodies, so the solver stops approaching bodies before they touch. A
    /// body moving farther than that in a step is swept instead, and stopped where it first
    /// meets another (the continuous pass).
    pub speculative_distance: f32,
    /// A body slower than this counts as still, m/s, ≥ 0, default 0.05: the speed of its
    /// fastest point, `|v| + r_max |ω|` (`r_max` its centre of mass's farthest reach), and
    /// below `r_max` per second for a body that small (a 1 cm marble is still below 0.9 cm/s).
    /// A body pushed by a constant force or torque of its own on an axis it is free on never
    /// counts as still, whether or not a contact holds the push: clear the force to let it sleep.
    pub sleep_speed: f32,
    /// How long an island must stay still before it falls asleep, s, ≥ 0, default 0.5.
    pub sleep_time: f32,
    /// How fast joints correct their position errors, Hz, > 0, default 60: a joint pulls its
    /// bodies back together like a spring of this frequency for their effective mass. Its
    /// velocity rows are rigid, so a joint only drifts apart as far as this spring lets a step's
    /// error through. Capped at a quarter of the substep rate, as `contact_hertz`.
    pub joint_hertz: f32,
    /// Damping ratio of the joints' position correction, ≥ 0, default 2 (over-damped).
    pub joint_damping_ratio: f32,
    /// How two surfaces' friction coefficients combine, default [`CombineRule::GeometricMean`].
    pub friction_combine: CombineRule,
    /// How two surfaces' restitutions combine, default [`CombineRule::Max`].
    pub restitution_combine: CombineRule,
}

impl Default for WorldSettings {
    fn default() -> Self {
        Self {
            gravity: DEFAULT_GRAVITY,
            substeps: DEFAULT_SUBSTEPS,
            max_linear_speed: DEFAULT_MAX_LINEAR_SPEED,
            contact_hertz: 120.0,
            contact_damping_ratio: 5.0,
            contact_push_speed: 3.0,
            restitution_threshold: 1.0,
            speculative_distance: SPECULATIVE_DISTANCE,
            sleep_speed: 0.05,
            sleep_time: 0.5,
            joint_hertz: 60.0,
            joint_damping_ratio: 2.0,
            friction_combine: CombineRule::GeometricMean,
            restitution_combine: CombineRule::Max,
        }
    }
}

impl WorldSettings {
    fn validate(&self) -> Result<()> {
        check_length("gravity", self.gravity, MAX_GRAVITY)?;
        check_positive("max_linear_speed", self.max_linear_speed)?;
        check_range("max_linear_speed", self.max_linear_speed, 0.0, MAX_SPEED)?;
        check_count("substeps", self.substeps, 1, MAX_SUBSTEPS)?;
        check_positive("contact_hertz", self.contact_hertz)?;
        check_non_negative("contact_damping_ratio", self.contact_damping_ratio)?;
        check_positive("contact_push_speed", self.contact_push_speed)?;
        check_non_negative("restitution_threshold", self.restitution_threshold)?;
        check_non_negative("speculative_distance", self.speculative_distance)?;
        check_non_negative("sleep_speed", self.sleep_speed)?;
        check_non_negative("sleep_time", self.sleep_time)?;
        check_positive("joint_hertz", self.joint_hertz)?;
        check_non_negative("joint_damping_ratio", self.joint_damping_ratio)?;
        Ok(())
    }
}

/// What the last step walked over, for tests that a step's work follows what is awake:
/// diagnostics, not part of the stable API.
#[doc(hidden)]
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct StepWork {
    /// Bodies the step moved: awake dynamic and kinematic ones.
    pub bodies: usize,
    /// Broad-phase pairs the step walked.
    pub pairs: usize,
    /// Contacts the step solved.
    pub contacts: usize,
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
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct World {
    settings: WorldSettings,
    bodies: Arena<RigidBody>,
    joints: JointSet,
    couplings: CouplingSet,
    broad_phase: BroadPhase,
    contacts: ContactCache,
    #[cfg_attr(feature = "serde", serde(skip))]
    narrow_phase: NarrowPhase,
    #[cfg_attr(feature = "serde", serde(skip))]
    solver: Solver,
    islands: Islands,
    ignored_pairs: IgnoredPairs,
    events: EventTracker,
    /// Pairs the narrow phase ran on in the last step (recycled and sleeping pairs excepted).
    narrow_phase_pair_tests: usize,
    /// What the last step walked over.
    step_work: StepWork,
    /// Each body's bounding box, by arena slot, refreshed at the start of each step for the bodies
    /// that may have moved.
    bounds_of_slot: Vec<Aabb>,
    /// Arena slots of static bodies lent out by [`World::body_mut`] since the last step, whose
    /// bounding boxes the next step refreshes in case they were moved.
    touched_static_slots: Vec<usize>,
    /// How many bodies are one-way or have a surface velocity: while none, and without a hook,
    /// the step shows no contact to the hooks' pass.
    contact_rule_bodies: usize,
    /// The continuous pass's bodies to put back or push, by slot, with where and against what.
    #[cfg_attr(feature = "serde", serde(skip))]
    impacts: Vec<continuous::Stop>,
}

/// Marks the broad-phase proxies of the bodies in arena `slots` asleep or awake.
fn set_proxies_asleep(
    bodies: &Arena<RigidBody>,
    broad_phase: &mut BroadPhase,
    slots: &[usize],
    asleep: bool,
) {
    for &slot in slots {
        if let Some(proxy) = bodies.at_slot(slot).and_then(|(_, body)| body.proxy) {
            broad_phase.set_asleep(proxy, asleep);
        }
    }
}

impl World {
    /// An empty world; settings must be finite and in range. The world has an identity of its
    /// own, which its handles carry (see [`BodyHandle`]).
    pub fn new(settings: WorldSettings) -> Result<Self> {
        settings.validate()?;
        let world = new_world();
        Ok(Self {
            settings,
            bodies: Arena::new(world),
            joints: JointSet::new(world),
            couplings: CouplingSet::new(world),
            broad_phase: BroadPhase::new(),
            contacts: ContactCache::default(),
            narrow_phase: NarrowPhase::default(),
            solver: Solver::default(),
            islands: Islands::default(),
            ignored_pairs: IgnoredPairs::default(),
            events: EventTracker::default(),
            narrow_phase_pair_tests: 0,
            step_work: StepWork::default(),
            bounds_of_slot: Vec::new(),
            touched_static_slots: Vec::new(),
            contact_rule_bodies: 0,
            impacts: Vec::new(),
        })
    }

    /// The current settings.
    pub fn settings(&self) -> &WorldSettings {
        &self.settings
    }

    /// Replaces the settings; on error the world keeps the old ones. A change of gravity wakes
    /// every body, since a body resting under the old gravity may not rest under the new one.
    pub fn set_settings(&mut self, settings: WorldSettings) -> Result<()> {
        settings.validate()?;
        if settings.gravity != self.settings.gravity {
            self.wake_all();
        }
        self.settings = settings;
        Ok(())
    }

    /// Wakes every sleeping body.
    pub fn wake_all(&mut self) {
        for slot in 0..self.bodies.slot_count() {
            if self
                .bodies
                .at_slot(slot)
                .is_some_and(|(_, body)| body.sleeping)
            {
                self.wake_slot(slot);
            }
        }
    }

    /// Wakes the body in `slot`; its group wakes at the next [`World::wake_groups`].
    fn wake_slot(&mut self, slot: usize) {
        if let Some(body) = self.bodies.at_slot_mut(slot) {
            body.wake();
            self.islands.note_woken(slot);
        }
    }

    /// Wakes the group of each body woken since the last call, whole, and brings back the
    /// contacts, broad-phase pairs, touching pairs and sensor overlaps parked while no body of
    /// theirs was awake (`mid_step`: after the step listed its sensor pairs). Costs the groups
    /// woken and, when any woke, a pass over the parked lists.
    fn wake_groups(&mut self, mid_step: bool) {
        let Self {
            bodies,
            broad_phase,
            contacts,
            islands,
            events,
            ..
        } = self;
        if !islands.wake_groups(bodies) {
            return;
        }
        set_proxies_asleep(bodies, broad_phase, islands.woken(), false);
        let awake = |handle: BodyHandle| bodies.get(handle.0).is_some_and(RigidBody::is_awake);
        let wakes = |a: BodyHandle, b: BodyHandle| awake(a) || awake(b);
        contacts.unpark(wakes);
        events.unpark(wakes, mid_step);
    }

    /// Parks the contacts, broad-phase pairs, touching pairs and sensor overlaps of which no body
    /// is awake any more, once bodies fell asleep: no step walks them until one of their bodies
    /// wakes.
    fn park_sleeping(&mut self) {
        let Self {
            bodies,
            broad_phase,
            contacts,
            islands,
            events,
            ..
        } = self;
        set_proxies_asleep(bodies, broad_phase, islands.fell_asleep(), true);
        let awake = |handle: BodyHandle| bodies.get(handle.0).is_some_and(RigidBody::is_awake);
        let parks = |a: BodyHandle, b: BodyHandle| !awake(a) && !awake(b);
        contacts.park(parks);
        events.park(parks);
    }

    /// Checks `desc` and adds the body; on error the world is unchanged.
    pub fn add_body(&mut self, desc: BodyDesc) -> Result<BodyHandle> {
        let body = RigidBody::from_desc(desc)?;
        let is_static = body.body_type == BodyType::Static;
        self.count_contact_rules(false, body.has_contact_rules());
        let aabb = body.aabb();
        let index = self.bodies.insert(body);
        let proxy = self
            .broad_phase
            .insert(index.slot() as u32, aabb, is_static);
        if let Some(body) = self.bodies.get_mut(index) {
            body.proxy = Some(proxy);
        }
        let slot = index.slot();
        if self.bounds_of_slot.len() <= slot {
            self.bounds_of_slot.resize(slot + 1, aabb);
        }
        self.bounds_of_slot[slot] = aabb;
        if !is_static {
            self.islands.add_body(slot);
        }
        Ok(BodyHandle(index))
    }

    /// Removes the body and returns it; its handle becomes stale, and its joints and contacts go
    /// with it.
    /// Its touching pairs and sensor overlaps end at the next step (a stop or exit event naming
    /// the stale handle).
    pub fn remove_body(&mut self, handle: BodyHandle) -> Result<RigidBody> {
        let joints: Vec<JointHandle> = self.joints.joints_of(handle).collect();
        for joint in joints {
            self.remove_joint(joint)?;
        }
        if !self.bodies.get(handle.0).ok_or_else(stale)?.is_awake() {
            // A sleeping or static body may have parked contacts: its group and the groups resting
            // on it wake now, so that the contacts come back to be dropped below.
            self.wake_with_resting(handle);
            self.wake_groups(false);
            // Its parked touching pairs and overlaps (a sensor around a sleeping body) end at the
            // next step, as an awake body's do.
            self.events.unpark(|a, b| a == handle || b == handle, false);
        }
        let mut body = self.bodies.remove(handle.0).ok_or_else(stale)?;
        if let Some(proxy) = body.proxy.take() {
            self.broad_phase.remove(proxy);
        }
        if body.body_type != BodyType::Static {
            self.islands.remove_body(handle.slot());
        }
        self.touched_static_slots
            .retain(|&slot| slot != handle.slot());
        for index in 0..self.contacts.contacts().len() {
            let key = self.contacts.contacts()[index].key;
            let other = match (key.body_a == handle, key.body_b == handle) {
                (true, _) => key.body_b,
                (_, true) => key.body_a,
                _ => continue,
            };
            if self.bodies.get(other.0).is_some() {
                self.wake_slot(other.slot());
            }
        }
        self.contacts.remove_body(handle);
        self.ignored_pairs.remove_body(handle);
        self.count_contact_rules(body.has_contact_rules(), false);
        Ok(body)
    }

    /// Makes body `handle` one-way from `direction` (body frame, normalised here; zero or not
    /// finite is an error for `one_way`), or solid again with `None`
    /// ([`BodyDesc::one_way`](BodyDesc#structfield.one_way), [`crate::hooks`]). Wakes it and the
    /// bodies asleep on it.
    pub fn set_one_way(&mut self, handle: BodyHandle, direction: Option<Vec3>) -> Result<()> {
        let one_way = direction
            .map(|direction| check_direction("one_way", direction))
            .transpose()?;
        self.change_contact_rules(handle, |body| body.one_way = one_way)
    }

    /// Sets the velocity of body `handle`'s surface relative to it, m/s, body frame, at most
    /// [`MAX_SPEED`](crate::limits::MAX_SPEED) long (else an error for `surface_velocity`): a
    /// conveyor belt ([`BodyDesc::surface_velocity`](BodyDesc#structfield.surface_velocity),
    /// [`crate::hooks`]). Wakes it and the bodies asleep on it.
    pub fn set_surface_velocity(&mut self, handle: BodyHandle, velocity: Vec3) -> Result<()> {
        let velocity = check_length("surface_velocity", velocity, MAX_SPEED)?;
        self.change_contact_rules(handle, |body| body.surface_velocity = velocity)
    }

    /// Changes body `handle`'s contact rules with `change`, keeps the count of bodies with
    /// rules, and wakes the body and the bodies asleep against it, which the change may set
    /// moving.
    fn change_contact_rules(
        &mut self,
        handle: BodyHandle,
        change: impl FnOnce(&mut RigidBody),
    ) -> Result<()> {
        let body = self.bodies.get_mut(handle.0).ok_or_else(stale)?;
        let had_rules = body.has_contact_rules();
        change(body);
        let has_rules = body.has_contact_rules();
        self.count_contact_rules(had_rules, has_rules);
        self.wake_with_resting(handle);
        Ok(())
    }

    /// Wakes body `handle` and the bodies of its parked contacts (asleep on it, or under it);
    /// their groups wake at the next [`World::wake_groups`].
    fn wake_with_resting(&mut self, handle: BodyHandle) {
        let resting: Vec<BodyHandle> = self
            .contacts
            .parked()
            .filter(|contact| contact.key.body_a == handle || contact.key.body_b == handle)
            .flat_map(|contact| [contact.key.body_a, contact.key.body_b])
            .collect();
        for body in resting {
            self.wake_slot(body.slot());
        }
        self.wake_slot(handle.slot());
    }

    /// Keeps the count of bodies with contact rules as a body goes from having them or not
    /// (`had`) to having them or not (`has`).
    fn count_contact_rules(&mut self, had: bool, has: bool) {
        match (had, has) {
            (false, true) => self.contact_rule_bodies += 1,
            (true, false) => self.contact_rule_bodies -= 1,
            _ => {}
        }
    }

    /// The body behind `handle`.
    pub fn body(&self, handle: BodyHandle) -> Result<&RigidBody> {
        self.bodies.get(handle.0).ok_or_else(stale)
    }

    /// The body behind `handle`, to change through its validating setters.
    pub fn body_mut(&mut self, handle: BodyHandle) -> Result<&mut RigidBody> {
        let body = self.bodies.get_mut(handle.0).ok_or_else(stale)?;
        if body.body_type == BodyType::Static {
            self.touched_static_slots.push(handle.slot());
        } else {
            // The caller may wake it: its group wakes at the next step.
            self.islands.note_woken(handle.slot());
        }
        Ok(body)
    }

    /// Changes which bodies `handle` interacts with, and wakes it. Pairs that no longer interact
    /// lose their contacts now (their bodies wake, so nothing sleeps on a support that is gone)
    /// and their broad-phase pair at the next step (their events end then); pairs that now
    /// interact are found at the next step.
    pub fn set_collision_groups(
        &mut self,
        handle: BodyHandle,
        groups: InteractionGroups,
    ) -> Result<()> {
        let body = self.bodies.get_mut(handle.0).ok_or_else(stale)?;
        body.collision_groups = groups;
        self.wake_slot(handle.slot());
        if let Some(proxy) = self.bodies.get(handle.0).and_then(|body| body.proxy) {
            self.broad_phase.refilter(proxy);
        }
        // A pair whose compounds filter their children is rebuilt: a child may take the new
        // groups.
        self.drop_contacts(|bodies, a, b| match (bodies.get(a.0), bodies.get(b.0)) {
            (Some(body_a), Some(body_b)) => {
                !body_a
                    .collision_groups
                    .interacts_with(body_b.collision_groups)
                    || ((a == handle || b == handle)
                        && Colliders::of(body_a).need_filtering(&Colliders::of(body_b)))
            }
            _ => true,
        });
        Ok(())
    }

    /// Makes bodies `a` and `b` ignore each other (or interact again), whatever their groups
    /// say, and wakes both. An ignored pair loses its contacts now and its broad-phase pair at
    /// the next step.
    pub fn set_pair_ignored(&mut self, a: BodyHandle, b: BodyHandle, ignored: bool) -> Result<()> {
        let proxies = [a, b].map(|handle| self.bodies.get(handle.0).map(|body| body.proxy));
        let [Some(proxy_a), Some(_)] = proxies else {
            return Err(stale());
        };
        if !self.ignored_pairs.set(a, b, ignored) {
            return Ok(());
        }
        for handle in [a, b] {
            self.wake_slot(handle.slot());
        }
        if let Some(proxy) = proxy_a {
            self.broad_phase.refilter(proxy);
        }
        self.drop_contacts(|_, body_a, body_b| ignored && (body_a, body_b) == ordered(a, b));
        Ok(())
    }

    /// Whether bodies `a` and `b` were told to ignore each other; never for a handle of another
    /// world.
    pub fn is_pair_ignored(&self, a: BodyHandle, b: BodyHandle) -> bool {
        self.ignored_pairs.contains(a, b)
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

    /// This step's contacts (one manifold per pair of touching convex parts), sorted by key: the
    /// contacts the step solved, each with at least one awake body. The contacts of sleeping
    /// bodies (asleep together, or asleep on a static body) are kept apart, unchanged, in
    /// [`World::sleeping_contacts`] until one of their bodies wakes. Each is as the narrow phase
    /// found it, with the impulses the solve gave it: a contact hook's changes
    /// ([`crate::hooks`]) last for the step's solve and events alone.
    pub fn contacts(&self) -> &[Contact] {
        self.contacts.contacts()
    }

    /// The contacts of which no body is awake (asleep, or asleep against a static body), sorted by
    /// key, as they were when their bodies fell asleep.
    pub fn sleeping_contacts(&self) -> impl ExactSizeIterator<Item = &Contact> {
        self.contacts.parked()
    }

    /// Number of contact points in all manifolds, sleeping ones included, speculative ones
    /// (bodies still apart by less than [`WorldSettings::speculative_distance`]) too.
    pub fn contact_count(&self) -> usize {
        self.contacts
            .contacts()
            .iter()
            .chain(self.contacts.parked())
            .map(|contact| contact.manifold.len())
            .sum()
    }

    /// Pairs of bodies that started or stopped touching during the last step, sorted by handles;
    /// see [`crate::events`]. Valid until the next step.
    pub fn contact_events(&self) -> &[ContactEvent] {
        self.events.contact_events()
    }

    /// Touching pairs whose normal force exceeded the smaller of their bodies' thresholds during
    /// the last step, sorted by handles.
    pub fn contact_force_events(&self) -> &[ContactForceEvent] {
        self.events.force_events()
    }

    /// Bodies that entered or left a sensor during the last step, sorted by (sensor, body).
    pub fn sensor_events(&self) -> &[SensorEvent] {
        self.events.sensor_events()
    }

    /// Pairs of bodies touching (surfaces meeting or contacts pushing) during the last step,
    /// sleeping pairs included, smaller handle first, sorted.
    pub fn touching_pairs(&self) -> impl Iterator<Item = (BodyHandle, BodyHandle)> + '_ {
        self.events.touching()
    }

    /// (sensor, body) pairs overlapping after the last step, sleeping bodies included, sorted.
    pub fn sensor_overlaps(&self) -> impl Iterator<Item = (BodyHandle, BodyHandle)> + '_ {
        self.events.overlaps()
    }

    /// The broad phase's pairs of bodies after the last step, smaller handle first, sorted: the
    /// pairs whose fat boxes overlap and that interact (groups, ignored pairs, never two
    /// sensors). Diagnostics.
    pub fn broad_phase_pairs(&self) -> impl Iterator<Item = (BodyHandle, BodyHandle)> + '_ {
        let pairs = self.broad_phase.pairs().iter().copied();
        merged(pairs, self.broad_phase.parked_pairs()).filter_map(|(key_a, key_b)| {
            let (index_a, _) = self.bodies.at_slot(key_a as usize)?;
            let (index_b, _) = self.bodies.at_slot(key_b as usize)?;
            Some(ordered(BodyHandle(index_a), BodyHandle(index_b)))
        })
    }

    /// How many pairs of bodies the narrow phase tested in the last step: broad-phase pairs with
    /// a moving body whose contacts were not recycled; sensor pairs are not counted.
    /// Diagnostics.
    pub fn narrow_phase_pair_tests(&self) -> usize {
        self.narrow_phase_pair_tests
    }

    /// How many times in the last step the exact solve of a group of joints (the rows that hold
    /// jointed bodies together, `docs/joints.md`) was refused, because it asked some row for an
    /// impulse past what bodies within the limits can exchange (`docs/limits.md`) or for one that
    /// is not finite: such a pass applies nothing to the group, whose joints then hold by their
    /// warm start alone. Zero in a world within the documented limits; above zero, its joints are
    /// likely anchored far outside their bodies or its masses far apart. Diagnostics.
    pub fn refused_joint_solves(&self) -> usize {
        self.solver.refused_joint_solves()
    }

    /// What the last step walked over. Diagnostics, for tests that a step's work follows what is
    /// awake.
    #[doc(hidden)]
    pub fn step_work(&self) -> StepWork {
        self.step_work
    }

    /// Number of islands (groups of awake dynamic bodies linked by contacts and joints) awake
    /// after the last step.
    pub fn island_count(&self) -> usize {
        self.islands.count()
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

    /// Advances the world by `dt` seconds ([`MIN_TIMESTEP`] to [`MAX_TIMESTEP`]) in
    /// `settings.substeps` substeps. Forces and torques applied since the last step act during
    /// the whole step, then are cleared. Kinematic bodies with a pose target or a path move to
    /// it at the velocity that carries them there and end the step exactly on it
    /// ([`RigidBody::set_kinematic_target`]). The bodies' own contact rules (one-way bodies,
    /// surface velocities: [`crate::hooks`]) apply.
    pub fn step(&mut self, dt: f32) -> Result<()> {
        self.step_hooked(dt, None)
    }

    /// [`World::step`], with `hooks` shown each contact before the solve, after the bodies'
    /// own contact rules, to change what the solver does with it this step ([`crate::hooks`]).
    pub fn step_with_hooks(&mut self, dt: f32, hooks: &mut dyn ContactHooks) -> Result<()> {
        self.step_hooked(dt, Some(hooks))
    }

    fn step_hooked(&mut self, dt: f32, hooks: Option<&mut dyn ContactHooks>) -> Result<()> {
        check_range("dt", dt, MIN_TIMESTEP, MAX_TIMESTEP)?;
        // The stages in order (module documentation). Kinematic velocities come first: the
        // contacts and the broad phase's sweep read them.
        self.for_each_kinematic(|body| body.begin_kinematic_step(dt));
        self.wake_groups(false);
        self.update_contacts(dt);
        self.wake_groups(true);
        // After the contacts woken with their groups came back, so the hooks see every contact
        // the solver will; no pass while no body has rules and there is no hook.
        if self.contact_rule_bodies > 0 || hooks.is_some() {
            self.modify_contacts(hooks);
        }
        self.solve(dt);
        // Before anything reads the poses the step ended with.
        self.for_each_kinematic(|body| body.finish_kinematic_step(dt));
        self.stop_fast_bodies(dt);
        self.joints.finish_step(dt);
        self.refilter_broken_joints();
        self.update_events(dt);
        // Before contacts are parked: what sleeps or comes to the next step is as found.
        self.contacts.restore_edited();
        self.update_sleep(dt);
        Ok(())
    }

    /// Builds this step's islands from its joints and contacts, and solves them: the bodies'
    /// new velocities and poses.
    fn solve(&mut self, dt: f32) {
        self.step_work = StepWork {
            bodies: self.islands.awake().len(),
            pairs: self.broad_phase.pairs().len(),
            contacts: self.contacts.contacts().len(),
        };
        self.joints.refresh_poses(&self.bodies);
        self.couplings.refresh(&self.joints, &self.bodies);
        let settings = &self.settings;
        let mut sources = Sources {
            joints: &mut self.joints,
            couplings: &mut self.couplings,
            contacts: &mut self.contacts,
        };
        self.solver.build_islands(
            &self.bodies,
            &mut self.islands,
            &mut sources,
            settings.sleep_speed,
        );
        self.solver.step(
            &mut self.bodies,
            &self.islands,
            &mut sources,
            StepSettings {
                dt,
                substeps: settings.substeps,
                gravity: settings.gravity,
                max_linear_speed: settings.max_linear_speed,
                contact: ContactSettings {
                    hertz: settings.contact_hertz,
                    damping_ratio: settings.contact_damping_ratio,
                    push_speed: settings.contact_push_speed,
                    restitution_threshold: settings.restitution_threshold,
                },
                joint: JointSettings {
                    hertz: settings.joint_hertz,
                    damping_ratio: settings.joint_damping_ratio,
                },
            },
        );
    }

    /// The step's contact, force and sensor events, from its contacts as solved.
    fn update_events(&mut self, dt: f32) {
        let substep_length = dt / self.settings.substeps as f32;
        self.events
            .update_contacts(self.contacts.contacts(), &self.bodies, substep_length);
        let bodies = &self.bodies;
        let awake = |handle: BodyHandle| bodies.get(handle.0).is_some_and(RigidBody::is_awake);
        self.events
            .finish_sensor_step(bodies, |a, b| !awake(a) && !awake(b));
    }

    /// Puts to sleep the islands still for long enough (the islands this step solved), and parks
    /// what no awake body uses any more.
    fn update_sleep(&mut self, dt: f32) {
        let fell_asleep = self.islands.update_sleep(
            &mut self.bodies,
            dt,
            self.settings.sleep_speed,
            self.settings.sleep_time,
        );
        if fell_asleep {
            self.park_sleeping();
        }
    }
}

impl World {
    /// Runs `visit` on every kinematic body: they are all among the bodies the step moves.
    fn for_each_kinematic(&mut self, mut visit: impl FnMut(&mut RigidBody)) {
        for &slot in self.islands.awake() {
            if let Some(body) = self.bodies.at_slot_mut(slot) {
                if body.body_type == BodyType::Kinematic {
                    visit(body);
                }
            }
        }
    }
}

fn stale() -> Error {
    Error::new("", ErrorKind::StaleHandle)
}

fn stale_joint() -> Error {
    Error::new("", ErrorKind::StaleJointHandle)
}

/// Read access for the scene queries in [`crate::query`].
impl World {
    pub(crate) fn bodies_arena(&self) -> &Arena<RigidBody> {
        &self.bodies
    }

    pub(crate) fn broad_phase(&self) -> &BroadPhase {
        &self.broad_phase
    }
}
