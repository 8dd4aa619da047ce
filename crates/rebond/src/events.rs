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
//! asleep inside a sensor stays inside. Their pairs are parked apart while no body of theirs is
//! awake, so that a step's event pass costs what is awake.
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
use crate::math::Vec3;
use crate::query::shapes_overlap;
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

/// Two bodies that started or stopped touching during the last step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SensorEventKind {
    /// The body's shape overlaps the sensor's now and did not at the previous step.
    Entered,
    /// The body's shape overlapped the sensor's at the previous step and does not now.
    Exited,
}

/// A body that entered or left a sensor during the last step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct EventTracker {
    /// Pairs touching during the last step, sorted; and during the step before.
    touching: Vec<(BodyHandle, BodyHandle)>,
    previous_touching: Vec<(BodyHandle, BodyHandle)>,
    /// (sensor, body) pairs overlapping after the last step, sorted; and after the step before.
    overlaps: Vec<(BodyHandle, BodyHandle)>,
    previous_overlaps: Vec<(BodyHandle, BodyHandle)>,
    /// (sensor, body) pairs to test for overlap at the end of this step.
    sensor_candidates: Vec<(BodyHandle, BodyHandle)>,
    /// Touching pairs and overlaps of which no body is awake, sorted: they cannot change while
    /// parked here, so no step walks them.
    parked_touching: Vec<(BodyHandle, BodyHandle)>,
    parked_overlaps: Vec<(BodyHandle, BodyHandle)>,
    /// The force reports of the parked touching pairs, sorted: repeated each step, as their
    /// contacts keep their impulses while asleep.
    parked_forces: Vec<ContactForceEvent>,
    /// Scratch of [`park`](Self::park) and [`unpark`](Self::unpark): the pairs and reports moving.
    moving: Vec<(BodyHandle, BodyHandle)>,
    moving_forces: Vec<ContactForceEvent>,
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
        move_pairs(
            &mut self.overlaps,
            &mut self.parked_overlaps,
            &mut self.moving,
            &parks,
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
        merge_into(&mut self.force_events, &self.parked_forces, |event| {
            (event.body_a, event.body_b)
        });
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
        let pair_of = |event: &ContactForceEvent| (event.body_a, event.body_b);
        let parked_forces = &self.parked_forces;
        self.moving_forces.clear();
        self.moving_forces
            .extend(self.force_events.iter().filter(|event| {
                parks(event.body_a, event.body_b)
                    && parked_forces
                        .binary_search_by_key(&pair_of(event), pair_of)
                        .is_err()
            }));
        merge_into(&mut self.parked_forces, &self.moving_forces, |event| {
            (event.body_a, event.body_b)
        });
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
            self.sensor_candidates.extend_from_slice(&self.moving);
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

    /// Pairs touching during the last step, sleeping ones included, smaller handle first, sorted.
    pub fn touching(&self) -> impl Iterator<Item = (BodyHandle, BodyHandle)> + '_ {
        merged(
            self.touching.iter().copied(),
            self.parked_touching.iter().copied(),
        )
    }

    /// (sensor, body) pairs overlapping after the last step, sleeping ones included, sorted.
    pub fn overlaps(&self) -> impl Iterator<Item = (BodyHandle, BodyHandle)> + '_ {
        merged(
            self.overlaps.iter().copied(),
            self.parked_overlaps.iter().copied(),
        )
    }
}

/// Moves the pairs of the sorted `from` for which `moves` is true into the sorted `to`, through
/// the scratch `moving`, which keeps them.
fn move_pairs(
    from: &mut Vec<(BodyHandle, BodyHandle)>,
    to: &mut Vec<(BodyHandle, BodyHandle)>,
    moving: &mut Vec<(BodyHandle, BodyHandle)>,
    moves: &impl Fn(BodyHandle, BodyHandle) -> bool,
) {
    moving.clear();
    from.retain(|&(a, b)| {
        let leaves = moves(a, b);
        if leaves {
            moving.push((a, b));
        }
        !leaves
    });
    merge_into(to, moving, |&pair| pair);
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
