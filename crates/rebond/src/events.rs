//! Contact, force and sensor events: what changed during the last step.
//!
//! After each [`World::step`](crate::World::step) the world lists
//! - [`ContactEvent`]s: pairs of bodies that started or stopped touching. A pair touches during a
//!   step when its surfaces meet (a manifold point with separation ≤ 0 at the start of the step)
//!   or its contacts pushed (the solver's normal impulse, summed over the pair's manifold points,
//!   is positive). Speculative points that never push (a body passing close by) do not count.
//!   Each start is followed by exactly one stop, reported at the first step the pair no longer
//!   touches, or at the step after one of its bodies was removed (with the removed body's stale
//!   handle).
//! - [`ContactForceEvent`]s: touching pairs whose normal force exceeds the smaller of the two
//!   bodies' [`contact_force_threshold`](crate::BodyDesc::contact_force_threshold)s.
//! - [`SensorEvent`]s: bodies that entered or left a sensor's shape (see
//!   [`crate::BodyDesc::sensor`]).
//!
//! Every list is sorted by the pair's handles, so it does not depend on anything but the bodies
//! and their history; the buffers are reused from step to step, so a steady scene allocates
//! nothing. Sleeping pairs keep their state: a body asleep on the floor stays touching it, a body
//! asleep inside a sensor stays inside.
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
//! assert_eq!(world.touching_pairs(), [(floor, ball)]);
//! # Ok::<(), rebond::Error>(())
//! ```

use crate::arena::Arena;
use crate::body::{BodyHandle, RigidBody};
use crate::collision::contact_cache::Contact;
use crate::math::Vec3;
use crate::query::shapes_overlap;

/// Whether a pair started or stopped touching.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ContactEventKind {
    /// The pair touches during this step and did not during the previous one.
    Started,
    /// The pair touched during the previous step and does not any more.
    Stopped,
}

/// Two bodies that started or stopped touching during the last step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ContactEvent {
    /// The body with the smaller handle.
    pub body_a: BodyHandle,
    /// The body with the larger handle.
    pub body_b: BodyHandle,
    /// Started or stopped.
    pub kind: ContactEventKind,
}

/// A touching pair whose normal force exceeded its threshold during the last step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactForceEvent {
    /// The body with the smaller handle.
    pub body_a: BodyHandle,
    /// The body with the larger handle.
    pub body_b: BodyHandle,
    /// The normal force on B from A, world, newtons: `Σ λ_n n / h` over the pair's manifold
    /// points, with `λ_n` the normal impulse of the step's last substep and `h = dt / substeps`
    /// (a body of mass m resting on the floor gives `m g`).
    pub total_force: Vec3,
    /// `Σ λ_n / h`, newtons: the sum of the points' force magnitudes, at least `|total_force|`.
    pub total_force_magnitude: f32,
}

/// Whether a body entered or left a sensor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum SensorEventKind {
    /// The body's shape overlaps the sensor's now and did not at the previous step.
    Entered,
    /// The body's shape overlapped the sensor's at the previous step and does not now.
    Exited,
}

/// A body that entered or left a sensor during the last step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SensorEvent {
    /// The sensor.
    pub sensor: BodyHandle,
    /// The body that entered or left it (never a sensor).
    pub body: BodyHandle,
    /// Entered or exited.
    pub kind: SensorEventKind,
}

/// The event lists and the state they are computed from, reused from step to step.
#[derive(Debug, Clone, Default)]
pub(crate) struct EventTracker {
    /// Pairs touching during the last step, sorted; and during the step before.
    touching: Vec<(BodyHandle, BodyHandle)>,
    previous_touching: Vec<(BodyHandle, BodyHandle)>,
    /// (sensor, body) pairs overlapping after the last step, sorted; and after the step before.
    overlaps: Vec<(BodyHandle, BodyHandle)>,
    previous_overlaps: Vec<(BodyHandle, BodyHandle)>,
    /// (sensor, body) pairs to test for overlap at the end of this step.
    sensor_candidates: Vec<(BodyHandle, BodyHandle)>,
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
    /// the bodies that entered and left sensors.
    pub fn finish_sensor_step(&mut self, bodies: &Arena<RigidBody>) {
        for &(sensor, body) in &self.sensor_candidates {
            let (Some(sensor_body), Some(other)) = (bodies.get(sensor.0), bodies.get(body.0))
            else {
                continue;
            };
            if shapes_overlap(
                &sensor_body.shape,
                &sensor_body.pose(),
                &other.shape,
                &other.pose(),
            ) {
                self.overlaps.push((sensor, body));
            }
        }
        self.overlaps.sort_unstable();
        self.sensor_events.clear();
        let events = &mut self.sensor_events;
        for_each_change(
            &self.previous_overlaps,
            &self.overlaps,
            |(sensor, body), entered| {
                events.push(SensorEvent {
                    sensor,
                    body,
                    kind: if entered {
                        SensorEventKind::Entered
                    } else {
                        SensorEventKind::Exited
                    },
                });
            },
        );
    }

    /// Lists the pairs that started and stopped touching in this step's solved `contacts`
    /// (sorted by key), and the force reports above threshold; `h` is the substep length, s.
    pub fn update_contacts(&mut self, contacts: &[Contact], bodies: &Arena<RigidBody>, h: f32) {
        std::mem::swap(&mut self.touching, &mut self.previous_touching);
        self.touching.clear();
        self.force_events.clear();
        for pair in contacts.chunk_by(same_pair) {
            let (body_a, body_b) = (pair[0].key.body_a, pair[0].key.body_b);
            let (mut impulse, mut impulse_vector) = (0.0, Vec3::ZERO);
            let mut surfaces_meet = false;
            for contact in pair {
                let manifold_impulse: f32 = contact.normal_impulses[..contact.manifold.len()]
                    .iter()
                    .sum();
                impulse += manifold_impulse;
                impulse_vector += manifold_impulse * contact.manifold.normal;
                surfaces_meet |= contact
                    .manifold
                    .points()
                    .iter()
                    .any(|p| p.separation <= 0.0);
            }
            if impulse <= 0.0 && !surfaces_meet {
                continue;
            }
            self.touching.push((body_a, body_b));
            if impulse <= 0.0 {
                continue;
            }
            let threshold = [body_a, body_b]
                .iter()
                .filter_map(|handle| bodies.get(handle.0))
                .map(|body| body.contact_force_threshold)
                .fold(f32::INFINITY, f32::min);
            let force = impulse / h;
            if force > threshold {
                self.force_events.push(ContactForceEvent {
                    body_a,
                    body_b,
                    total_force: impulse_vector / h,
                    total_force_magnitude: force,
                });
            }
        }
        self.contact_events.clear();
        let events = &mut self.contact_events;
        for_each_change(
            &self.previous_touching,
            &self.touching,
            |(body_a, body_b), started| {
                events.push(ContactEvent {
                    body_a,
                    body_b,
                    kind: if started {
                        ContactEventKind::Started
                    } else {
                        ContactEventKind::Stopped
                    },
                });
            },
        );
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

    /// Pairs touching during the last step, smaller handle first, sorted.
    pub fn touching(&self) -> &[(BodyHandle, BodyHandle)] {
        &self.touching
    }

    /// (sensor, body) pairs overlapping after the last step, sorted.
    pub fn overlaps(&self) -> &[(BodyHandle, BodyHandle)] {
        &self.overlaps
    }
}

fn same_pair(x: &Contact, y: &Contact) -> bool {
    (x.key.body_a, x.key.body_b) == (y.key.body_a, y.key.body_b)
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
