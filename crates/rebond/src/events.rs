//! Contact, force and sensor events: what changed during the last step.
//!
//! After each [`World::step`](crate::World::step) the world lists
//! - [`ContactEvent`]s: pairs of colliders that started or stopped touching (a body whose shape
//!   is not a compound is one collider, index 0; each child of a compound is one, by its index;
//!   see [`CompoundChild`](crate::CompoundChild)). A pair touches during a step when its surfaces
//!   meet (a manifold point with separation ≤ 0 at the start of the step)
//!   or its contacts pushed (the solver's normal impulse, summed over the pair's manifold points,
//!   is positive). Speculative points that never push (a body passing close by) do not count.
//!   Each start is followed by exactly one stop, reported at the first step the pair no longer
//!   touches, or at the step after one of its bodies was removed (with the removed body's stale
//!   handle).
//! - [`ContactForceEvent`]s: touching collider pairs whose normal force exceeds the smaller of
//!   the two bodies' [`contact_force_threshold`](crate::BodyDesc::contact_force_threshold)s.
//! - [`SensorEvent`]s: colliders that entered or left a sensor collider (a sensor body, see
//!   [`crate::BodyDesc::sensor`], or a sensor child of a compound, see
//!   [`CompoundChild::sensor`](crate::CompoundChild::sensor)). Sensors never report sensors.
//!
//! Events are per collider pair: a compound resting on the floor on two of its children makes two
//! contact events, each naming its child. Every list is sorted by the pair's handles and then its
//! colliders, so it does not depend on anything but the bodies and their history; the buffers
//! are reused from step to step, so a steady scene allocates nothing. Sleeping pairs keep their
//! state: a body asleep on the floor stays touching it, a body asleep inside a sensor stays
//! inside. Their pairs are parked apart while no body of theirs is awake, so that a step's event
//! pass costs what is awake.
//!
//! ```
//! use rebond::{BodyDesc, ContactEventKind, SensorEventKind, Shape, Vec3, World, WorldSettings};
//!
//! let mut world = World::new(WorldSettings::default())?;
//! let floor = world.add_body(
//!     BodyDesc::static_body(Shape::cuboid(Vec3::new(10.0, 0.5, 10.0))?)
//!         .position(Vec3::new(0.0, -0.5, 0.0)),
//! )?;
//! let trigger = world.add_body(
//!     BodyDesc::static_body(Shape::cuboid(Vec3::splat(1.0))?)
//!         .position(Vec3::new(0.0, 3.0, 0.0))
//!         .sensor(true),
//! )?;
//! let ball = world.add_body(
//!     BodyDesc::dynamic(Shape::sphere(0.25)?).position(Vec3::new(0.0, 6.0, 0.0)),
//! )?;
//! let (mut entered, mut exited, mut landed) = (0, 0, 0);
//! for _ in 0..120 {
//!     world.step(1.0 / 60.0)?;
//!     for event in world.sensor_events() {
//!         assert_eq!((event.sensor, event.body), (trigger, ball));
//!         match event.kind {
//!             SensorEventKind::Entered => entered += 1,
//!             SensorEventKind::Exited => exited += 1,
//!         }
//!     }
//!     let starts = world.contact_events().iter();
//!     landed += starts.filter(|e| e.kind == ContactEventKind::Started).count();
//! }
//! // The ball fell through the trigger (in, then out) and landed on the floor once.
//! assert_eq!((entered, exited, landed), (1, 1, 1));
//! assert!(world.touching_pairs().eq([(floor, ball)]));
//! # Ok::<(), rebond::Error>(())
//! ```

use crate::arena::Arena;
use crate::body::{BodyHandle, RigidBody};
use crate::collision::contact_cache::Contact;
use crate::collision::narrow_phase::for_each_part;
use crate::filter::Colliders;
use crate::math::Vec3;
use crate::query::shapes_overlap;
use crate::shape::Shape;
use crate::sorted::{merge_into, merged};

/// Whether a pair started or stopped touching.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ContactEventKind {
    /// The pair touches during this step and did not during the previous one.
    Started,
    /// The pair touched during the previous step and does not any more.
    Stopped,
}

/// Two colliders of two bodies that started or stopped touching during the last step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContactEvent {
    /// The body with the smaller handle.
    pub body_a: BodyHandle,
    /// The body with the larger handle.
    pub body_b: BodyHandle,
    /// The collider of A: its compound child's index, or 0.
    pub collider_a: u32,
    /// The collider of B: its compound child's index, or 0.
    pub collider_b: u32,
    /// Started or stopped.
    pub kind: ContactEventKind,
    /// The triangle of the body that is a triangle mesh or heightfield (A or B) the pair touches
    /// on ([`crate::Contact::triangle`]): for a start, where it first touched; for a stop, where
    /// it last touched. Of the pair's contacts on several triangles, the one pressed hardest (the
    /// first in contact order when none is pressed yet). `None` between other shapes.
    pub triangle: Option<u32>,
}

/// A touching collider pair whose normal force exceeded its threshold during the last step.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContactForceEvent {
    /// The body with the smaller handle.
    pub body_a: BodyHandle,
    /// The body with the larger handle.
    pub body_b: BodyHandle,
    /// The collider of A: its compound child's index, or 0.
    pub collider_a: u32,
    /// The collider of B: its compound child's index, or 0.
    pub collider_b: u32,
    /// The normal force on B's collider from A's, world, newtons: `Σ λ_n n / h` over the
    /// colliders' manifold points, with `λ_n` the normal impulse of the step's last substep and
    /// `h = dt / substeps` (a body of mass m resting on the floor on one collider gives `m g`).
    pub total_force: Vec3,
    /// `Σ λ_n / h`, newtons: the sum of the points' force magnitudes, at least `|total_force|`.
    pub total_force_magnitude: f32,
}

/// Whether a body entered or left a sensor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SensorEventKind {
    /// The body's shape overlaps the sensor's now and did not at the previous step.
    Entered,
    /// The body's shape overlapped the sensor's at the previous step and does not now.
    Exited,
}

/// A collider of a body that entered or left a sensor collider during the last step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SensorEvent {
    /// The sensor's body: a sensor body, or a body with a sensor child.
    pub sensor: BodyHandle,
    /// The body that entered or left it (never a sensor body).
    pub body: BodyHandle,
    /// Entered or exited.
    pub kind: SensorEventKind,
    /// The sensor collider of `sensor`: its compound child's index, or 0.
    pub sensor_collider: u32,
    /// The collider of `body` that entered or left (never a sensor): its compound child's index,
    /// or 0.
    pub collider: u32,
}

/// Collider `collider_a` of body `a` and collider `collider_b` of body `b`: a touching pair
/// (smaller handle first) or a sensor overlap (sensor first). Ordered and compared by bodies,
/// then colliders: the mesh triangle it carries along names where a touching pair touches, and
/// a pair touching on another triangle than at the step before is the same pair.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct ColliderPair {
    a: BodyHandle,
    b: BodyHandle,
    collider_a: u32,
    collider_b: u32,
    triangle: Option<u32>,
}

impl ColliderPair {
    /// What pairs are compared by.
    fn key(&self) -> (BodyHandle, BodyHandle, u32, u32) {
        (self.a, self.b, self.collider_a, self.collider_b)
    }
}

impl PartialEq for ColliderPair {
    fn eq(&self, other: &Self) -> bool {
        self.key() == other.key()
    }
}

impl Eq for ColliderPair {}

impl PartialOrd for ColliderPair {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for ColliderPair {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.key().cmp(&other.key())
    }
}

/// One collider pair's share of a step's contacts: its normal impulse summed over its manifolds,
/// N·s, the same weighted by their normals, whether its surfaces meet, and the mesh triangle of
/// its manifold of most impulse (the first one's while none has any) with that impulse.
#[derive(Debug, Clone, Copy)]
struct ColliderSum {
    impulse: f32,
    impulse_vector: Vec3,
    surfaces_meet: bool,
    triangle: Option<(u32, f32)>,
}

impl ColliderSum {
    const EMPTY: Self = Self {
        impulse: 0.0,
        impulse_vector: Vec3::ZERO,
        surfaces_meet: false,
        triangle: None,
    };

    /// Adds one manifold's impulses.
    fn add(&mut self, contact: &Contact) {
        let impulse: f32 = contact.normal_impulses[..contact.manifold.len()]
            .iter()
            .sum();
        if let Some(triangle) = contact.manifold.triangle {
            self.keep_triangle((triangle, impulse));
        }
        self.impulse += impulse;
        self.impulse_vector += impulse * contact.manifold.normal;
        self.surfaces_meet |= contact
            .manifold
            .points()
            .iter()
            .any(|p| p.separation <= 0.0);
    }

    /// Keeps `triangle` (with the impulse on it) if it is pressed harder than the one kept.
    fn keep_triangle(&mut self, triangle: (u32, f32)) {
        if self.triangle.is_none_or(|(_, kept)| triangle.1 > kept) {
            self.triangle = Some(triangle);
        }
    }

    /// Adds the sum of other manifolds of the same collider pair.
    fn merge(&mut self, other: &Self) {
        if let Some(triangle) = other.triangle {
            self.keep_triangle(triangle);
        }
        self.impulse += other.impulse;
        self.impulse_vector += other.impulse_vector;
        self.surfaces_meet |= other.surfaces_meet;
    }
}

/// The event lists and the state they are computed from, reused from step to step.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct EventTracker {
    /// Collider pairs touching during the last step, sorted; and during the step before.
    touching: Vec<ColliderPair>,
    previous_touching: Vec<ColliderPair>,
    /// (sensor, body) collider pairs overlapping after the last step, sorted; and after the step
    /// before.
    overlaps: Vec<ColliderPair>,
    previous_overlaps: Vec<ColliderPair>,
    /// (sensor, body) pairs of bodies whose colliders are tested for overlap at the end of this
    /// step.
    sensor_candidates: Vec<(BodyHandle, BodyHandle)>,
    /// Touching pairs and overlaps of which no body is awake, sorted: they cannot change while
    /// parked here, so no step walks them.
    parked_touching: Vec<ColliderPair>,
    parked_overlaps: Vec<ColliderPair>,
    /// The force reports of the parked touching pairs, sorted: repeated each step, as their
    /// contacts keep their impulses while asleep.
    parked_forces: Vec<ContactForceEvent>,
    /// Scratch of [`park`](Self::park) and [`unpark`](Self::unpark): the pairs and reports moving.
    moving: Vec<ColliderPair>,
    moving_forces: Vec<ContactForceEvent>,
    /// Scratch of [`update_contacts`](Self::update_contacts): one body pair's sums per collider
    /// pair, with the place of its first contact among the pair's, so sums keep the contacts'
    /// order.
    #[cfg_attr(feature = "serde", serde(skip))]
    sums: Vec<(ColliderPair, u32, ColliderSum)>,
    contact_events: Vec<ContactEvent>,
    force_events: Vec<ContactForceEvent>,
    sensor_events: Vec<SensorEvent>,
}

impl EventTracker {
    /// Starts a step's sensor bookkeeping: last step's overlaps become the previous ones.
    pub fn begin_sensor_step(&mut self) {
        std::mem::swap(&mut self.overlaps, &mut self.previous_overlaps);
        self.overlaps.clear();
        self.sensor_candidates.clear();
    }

    /// A broad-phase pair of `sensor` and `body` whose overlap is tested at the end of the step.
    pub fn add_sensor_candidate(&mut self, sensor: BodyHandle, body: BodyHandle) {
        self.sensor_candidates.push((sensor, body));
    }

    /// Ends the step: tests each sensor candidate's shapes at the bodies' new poses, and lists
    /// the bodies that entered and left sensors. Then parks the overlaps `(sensor, body)` for which
    /// `parks(sensor, body)` is true: a sensor pair of which no body is awake is a candidate only
    /// at the step its bodies meet (a sensor added or moved around a sleeping body).
    pub fn finish_sensor_step(
        &mut self,
        bodies: &Arena<RigidBody>,
        parks: impl Fn(BodyHandle, BodyHandle) -> bool,
    ) {
        for &(sensor, body) in &self.sensor_candidates {
            let (Some(sensor_body), Some(other)) = (bodies.get(sensor.0), bodies.get(body.0))
            else {
                continue;
            };
            push_overlaps((sensor, sensor_body), (body, other), &mut self.overlaps);
        }
        // A pair woken mid-step may be a candidate twice.
        self.overlaps.sort_unstable();
        self.overlaps.dedup();
        self.sensor_events.clear();
        let events = &mut self.sensor_events;
        for_each_change(&self.previous_overlaps, &self.overlaps, |pair, entered| {
            events.push(SensorEvent {
                sensor: pair.a,
                body: pair.b,
                kind: if entered {
                    SensorEventKind::Entered
                } else {
                    SensorEventKind::Exited
                },
                sensor_collider: pair.collider_a,
                collider: pair.collider_b,
            });
        });
        move_pairs(
            &mut self.overlaps,
            &mut self.parked_overlaps,
            &mut self.moving,
            &parks,
        );
    }

    /// Lists the collider pairs that started and stopped touching in this step's solved
    /// `contacts` (sorted by key), and the force reports above threshold; `h` is the substep
    /// length, s.
    pub fn update_contacts(&mut self, contacts: &[Contact], bodies: &Arena<RigidBody>, h: f32) {
        std::mem::swap(&mut self.touching, &mut self.previous_touching);
        self.touching.clear();
        self.force_events.clear();
        for pair_contacts in
            contacts.chunk_by(|x, y| (x.key.body_a, x.key.body_b) == (y.key.body_a, y.key.body_b))
        {
            let key = pair_contacts[0].key;
            // Most pairs touch with their whole shapes (children 0): one collider pair, summed
            // straight from the contacts.
            if pair_contacts
                .iter()
                .all(|contact| contact.key.child_a == 0 && contact.key.child_b == 0)
            {
                let mut sum = ColliderSum::EMPTY;
                for contact in pair_contacts {
                    sum.add(contact);
                }
                let pair = ColliderPair {
                    a: key.body_a,
                    b: key.body_b,
                    collider_a: 0,
                    collider_b: 0,
                    triangle: None,
                };
                self.add_touching(pair, &sum, bodies, h);
                continue;
            }
            // Compound children and mesh manifolds: sums per collider pair. Contacts come sorted
            // by children; on a mesh, whose children are its manifolds, one collider pair's
            // contacts may come apart: they are brought together, in contact order.
            let mut sums = std::mem::take(&mut self.sums);
            sums.clear();
            for (order, contact) in (0..).zip(pair_contacts) {
                let pair = ColliderPair {
                    a: key.body_a,
                    b: key.body_b,
                    collider_a: collider_of(bodies, key.body_a, contact.key.child_a),
                    collider_b: collider_of(bodies, key.body_b, contact.key.child_b),
                    triangle: None,
                };
                match sums.last_mut() {
                    Some((last, _, sum)) if *last == pair => sum.add(contact),
                    _ => {
                        let mut sum = ColliderSum::EMPTY;
                        sum.add(contact);
                        sums.push((pair, order, sum));
                    }
                }
            }
            if !sums.is_sorted_by_key(|(pair, ..)| *pair) {
                sums.sort_unstable_by_key(|&(pair, order, _)| (pair, order));
            }
            for group in sums.chunk_by(|x, y| x.0 == y.0) {
                let mut total = ColliderSum::EMPTY;
                for (.., sum) in group {
                    total.merge(sum);
                }
                self.add_touching(group[0].0, &total, bodies, h);
            }
            self.sums = sums;
        }
        merge_into(&mut self.force_events, &self.parked_forces, force_pair);
        self.contact_events.clear();
        let events = &mut self.contact_events;
        for_each_change(&self.previous_touching, &self.touching, |pair, started| {
            events.push(ContactEvent {
                body_a: pair.a,
                body_b: pair.b,
                collider_a: pair.collider_a,
                collider_b: pair.collider_b,
                kind: if started {
                    ContactEventKind::Started
                } else {
                    ContactEventKind::Stopped
                },
                triangle: pair.triangle,
            });
        });
    }

    /// Lists `pair` as touching when its contacts' `sum` holds an impulse or its surfaces meet,
    /// and reports its force when that exceeds the smaller threshold of its two bodies.
    fn add_touching(
        &mut self,
        pair: ColliderPair,
        sum: &ColliderSum,
        bodies: &Arena<RigidBody>,
        h: f32,
    ) {
        if sum.impulse <= 0.0 && !sum.surfaces_meet {
            return;
        }
        let triangle = sum.triangle.map(|(triangle, _)| triangle);
        self.touching.push(ColliderPair { triangle, ..pair });
        if sum.impulse <= 0.0 {
            return;
        }
        let threshold = [pair.a, pair.b]
            .iter()
            .filter_map(|handle| bodies.get(handle.0))
            .map(|body| body.contact_force_threshold)
            .fold(f32::INFINITY, f32::min);
        let force = sum.impulse / h;
        if force > threshold {
            self.force_events.push(ContactForceEvent {
                body_a: pair.a,
                body_b: pair.b,
                collider_a: pair.collider_a,
                collider_b: pair.collider_b,
                total_force: sum.impulse_vector / h,
                total_force_magnitude: force,
            });
        }
    }

    /// Parks the touching pairs and overlaps `(a, b)` for which `parks(a, b)` is true (no body
    /// awake), after the step's lists were made: they stay touching and inside, with no event.
    pub fn park(&mut self, parks: impl Fn(BodyHandle, BodyHandle) -> bool) {
        move_pairs(
            &mut self.touching,
            &mut self.parked_touching,
            &mut self.moving,
            &parks,
        );
        move_pairs(
            &mut self.overlaps,
            &mut self.parked_overlaps,
            &mut self.moving,
            &parks,
        );
        // This step's reports include those parked before, which stay parked once.
        let parked_forces = &self.parked_forces;
        self.moving_forces.clear();
        self.moving_forces
            .extend(self.force_events.iter().filter(|event| {
                parks(event.body_a, event.body_b)
                    && parked_forces
                        .binary_search_by_key(&force_pair(event), force_pair)
                        .is_err()
            }));
        merge_into(&mut self.parked_forces, &self.moving_forces, force_pair);
    }

    /// Brings back the parked pairs `(a, b)` for which `wakes(a, b)` is true, as last step's, so
    /// the step compares its lists with them. `mid_step`: the step's sensor pairs are already
    /// listed, so the woken overlaps join its candidates to be tested again.
    pub fn unpark(&mut self, wakes: impl Fn(BodyHandle, BodyHandle) -> bool, mid_step: bool) {
        move_pairs(
            &mut self.parked_touching,
            &mut self.touching,
            &mut self.moving,
            &wakes,
        );
        self.parked_forces
            .retain(|event| !wakes(event.body_a, event.body_b));
        if mid_step {
            move_pairs(
                &mut self.parked_overlaps,
                &mut self.previous_overlaps,
                &mut self.moving,
                &wakes,
            );
            self.sensor_candidates
                .extend(self.moving.iter().map(|pair| (pair.a, pair.b)));
        } else {
            move_pairs(
                &mut self.parked_overlaps,
                &mut self.overlaps,
                &mut self.moving,
                &wakes,
            );
        }
    }

    pub fn contact_events(&self) -> &[ContactEvent] {
        &self.contact_events
    }

    pub fn force_events(&self) -> &[ContactForceEvent] {
        &self.force_events
    }

    pub fn sensor_events(&self) -> &[SensorEvent] {
        &self.sensor_events
    }

    /// Pairs of bodies some colliders of which touched during the last step, sleeping ones
    /// included, smaller handle first, sorted.
    pub fn touching(&self) -> impl Iterator<Item = (BodyHandle, BodyHandle)> + '_ {
        body_pairs(merged(
            self.touching.iter().copied(),
            self.parked_touching.iter().copied(),
        ))
    }

    /// (sensor, body) pairs of bodies some colliders of which overlap after the last step,
    /// sleeping ones included, sorted.
    pub fn overlaps(&self) -> impl Iterator<Item = (BodyHandle, BodyHandle)> + '_ {
        body_pairs(merged(
            self.overlaps.iter().copied(),
            self.parked_overlaps.iter().copied(),
        ))
    }
}

/// The body pairs of sorted collider pairs, each once.
fn body_pairs(
    pairs: impl Iterator<Item = ColliderPair>,
) -> impl Iterator<Item = (BodyHandle, BodyHandle)> {
    let mut last = None;
    pairs.filter_map(move |pair| {
        let bodies = (pair.a, pair.b);
        (last.replace(bodies) != Some(bodies)).then_some(bodies)
    })
}

/// The collider of `body` that its compound child (or mesh manifold) `child` belongs to: the
/// child itself on a compound, the whole shape (0) otherwise. A shape that is not a compound has
/// only child 0, unless it is a mesh, so only then is the body looked up.
fn collider_of(bodies: &Arena<RigidBody>, body: BodyHandle, child: u32) -> u32 {
    if child == 0 {
        return 0;
    }
    match bodies.get(body.0).map(|body| &body.shape) {
        Some(Shape::Compound(_)) => child,
        _ => 0,
    }
}

/// Pushes the overlaps of `sensor`'s sensor colliders with `body`'s colliders they see, each
/// tested at the bodies' poses.
fn push_overlaps(
    (sensor, sensor_body): (BodyHandle, &RigidBody),
    (body, other): (BodyHandle, &RigidBody),
    overlaps: &mut Vec<ColliderPair>,
) {
    let (sensor_colliders, colliders) = (Colliders::of(sensor_body), Colliders::of(other));
    let several = |shape: &Shape| matches!(shape, Shape::Compound(_));
    let sensor_pose = sensor_body.pose();
    let pose = other.pose();
    if !several(&sensor_body.shape) && !several(&other.shape) {
        // One collider each: the bodies' test said they interact.
        if shapes_overlap(&sensor_body.shape, &sensor_pose, &other.shape, &pose) {
            overlaps.push(ColliderPair {
                a: sensor,
                b: body,
                collider_a: 0,
                collider_b: 0,
                triangle: None,
            });
        }
        return;
    }
    for_each_part(
        &sensor_body.shape,
        &sensor_pose,
        |collider_a, part_a, pose_a| {
            if !sensor_colliders.is_sensor(collider_a) {
                return;
            }
            let bounds = part_a.aabb(&pose_a);
            for_each_part(&other.shape, &pose, |collider_b, part_b, pose_b| {
                if sensor_colliders.sees(collider_a, &colliders, collider_b)
                    && bounds.overlaps(&part_b.aabb(&pose_b))
                    && shapes_overlap(part_a, &pose_a, part_b, &pose_b)
                {
                    overlaps.push(ColliderPair {
                        a: sensor,
                        b: body,
                        collider_a,
                        collider_b,
                        triangle: None,
                    });
                }
            });
        },
    );
}

/// The collider pair a force report belongs to, by which the reports are sorted.
fn force_pair(event: &ContactForceEvent) -> ColliderPair {
    ColliderPair {
        a: event.body_a,
        b: event.body_b,
        collider_a: event.collider_a,
        collider_b: event.collider_b,
        triangle: None,
    }
}

/// Moves the pairs of the sorted `from` for which `moves` is true into the sorted `to`, through
/// the scratch `moving`, which keeps them.
fn move_pairs(
    from: &mut Vec<ColliderPair>,
    to: &mut Vec<ColliderPair>,
    moving: &mut Vec<ColliderPair>,
    moves: &impl Fn(BodyHandle, BodyHandle) -> bool,
) {
    moving.clear();
    from.retain(|&pair| {
        let leaves = moves(pair.a, pair.b);
        if leaves {
            moving.push(pair);
        }
        !leaves
    });
    merge_into(to, moving, |&pair| pair);
}

/// Walks two sorted lists together and calls `on_change(item, true)` for each item only in
/// `current` and `on_change(item, false)` for each item only in `previous`, in sorted order.
fn for_each_change<T: Ord + Copy>(
    previous: &[T],
    current: &[T],
    mut on_change: impl FnMut(T, bool),
) {
    let (mut old, mut new) = (previous.iter().peekable(), current.iter().peekable());
    loop {
        match (old.peek(), new.peek()) {
            (Some(&&a), Some(&&b)) if a == b => {
                old.next();
                new.next();
            }
            (Some(&&a), Some(&&b)) if a < b => {
                on_change(a, false);
                old.next();
            }
            (_, Some(&&b)) => {
                on_change(b, true);
                new.next();
            }
            (Some(&&a), None) => {
                on_change(a, false);
                old.next();
            }
            (None, None) => break,
        }
    }
}
