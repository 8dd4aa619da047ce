//! The continuous pass: after the solver, each fast body (one that moved farther than
//! [`FAST_MOTION_REACHES`] times its reach, so its contacts may have missed what it met) is
//! swept from its pose at the step's start to its pose at the end against every body its path
//! overlaps, static or moving, rotation included ([`time_of_impact`]). One that would end the
//! step deep in or past another is put back where it first met it, a little short of touching,
//! with its velocities kept: the next step's contact (within the margin by then) stops it. Box2D
//! does the same for its bullets; the step loses the rest of that body's motion, and a joint to
//! it stretches until the joint pulls it back.
//!
//! A kinematic body is swept too, with the motion of its velocities over the step, `v dt` and
//! `ω dt` (a pose target or a path moves it by velocity: `body/kinematic.rs`; a teleport,
//! `set_position`, gives it none and is not swept). A fast body meets it where it is at each
//! moment of the step; one that meets a moving kinematic body is not left behind at the pose
//! where they met, but pushed ([`Pusher::push`]): carried on with it to the end of the step. A
//! fast kinematic body (one whose points move farther than [`FAST_MOTION_REACHES`] times its
//! reach, or that turns farther than [`CONTACT_TURN`]) is swept last against the dynamic bodies,
//! each fixed where the step left it, and pushes those it would end deep in or past: it cannot
//! be put back, as it ends the step where it was told to
//! ([`World::push_ahead_of_fast_kinematic_bodies`]).
//!
//! A fast body passes through a one-way body from the side that lets it (`hooks.rs`): an impact
//! whose normal the one-way rule refuses is no impact.

use super::contact_update::pair_interacts;
use super::{World, WorldSettings};
use crate::arena::Arena;
use crate::body::{BodyHandle, BodyType, RigidBody};
use crate::collision::time_of_impact::{time_of_impact, Impact, ImpactTolerances, Motion};
use crate::collision::FAST_MOTION_REACHES;
use crate::filter::{Colliders, IgnoredPairs};
use crate::hooks::one_way_holds;
use crate::joint::JointSet;
use crate::math::{Pose, Vec3};
use crate::solver::FastMotion;

/// How a body that did not move in the step (static, or not fast) is swept: fixed
/// at its pose.
fn fixed_motion(body: &RigidBody) -> Motion {
    moving(body, Vec3::ZERO, Vec3::ZERO)
}

/// How a kinematic body moved over the step `dt`: at its velocities, which the solver does not
/// change.
fn kinematic_motion(body: &RigidBody, dt: f32) -> Motion {
    moving(body, body.linear_velocity * dt, body.angular_velocity * dt)
}

/// How far a kinematic body may turn in a step, rad, and still be left to its contacts: a
/// contact's normal is the one at the step's start, so a bar turning faster strikes a ball with
/// a side the contact points the wrong way, and passes it (measured: a bar turning 0.83 rad a
/// step passes a ball it meets late in the step; at 0.2 rad a step its contact stops the ball,
/// letting it in by 9 mm).
const CONTACT_TURN: f32 = 0.25;

/// Whether a kinematic body moving over the step `dt` at its velocities goes farther than its
/// contacts reach, or turns farther than they follow ([`CONTACT_TURN`]), so that it is swept
/// ([`World::push_ahead_of_fast_kinematic_bodies`]).
fn is_fast_kinematic(body: &RigidBody, dt: f32) -> bool {
    body.body_type == BodyType::Kinematic
        && !body.sensor
        && (dt * body.max_point_speed() > FAST_MOTION_REACHES * body.max_extent
            || dt * body.angular_velocity.length() > CONTACT_TURN)
}

/// How `body`, now at the end of the step, moved over it.
fn moving(body: &RigidBody, delta_position: Vec3, delta_rotation: Vec3) -> Motion {
    Motion {
        end_center: body.center_of_mass,
        end_rotation: body.rotation,
        local_center: body.local_center_of_mass,
        delta_position,
        delta_rotation,
        reach: body.max_extent,
    }
}

impl World {
    /// Sweeps the solver's fast bodies and puts back the ones that would pass through or end
    /// deep in another body (module documentation). The answer leaves them a quarter of the
    /// speculative distance apart; a body ending the step less deep than the speculative
    /// distance and a quarter of its reach is left to the contacts. Then the fast kinematic
    /// bodies of the step `dt` push ahead what they would pass.
    pub(super) fn stop_fast_bodies(&mut self, dt: f32) {
        let Self {
            settings,
            bodies,
            joints,
            broad_phase,
            ignored_pairs,
            solver,
            impacts,
            ..
        } = self;
        let fast = solver.fast_bodies();
        impacts.clear();
        let motion_of = |slot: usize, body: &RigidBody| match fast
            .binary_search_by_key(&slot, |fast| fast.slot)
        {
            Ok(at) => moving(body, fast[at].delta_position, fast[at].delta_rotation),
            Err(_) if body.body_type == BodyType::Kinematic => kinematic_motion(body, dt),
            Err(_) => fixed_motion(body),
        };
        for &FastMotion { slot, .. } in fast {
            let Some((index, body)) = bodies.at_slot(slot) else {
                continue;
            };
            if body.sensor {
                continue;
            }
            let motion = motion_of(slot, body);
            let tolerances = ImpactTolerances {
                target: 0.25 * settings.speculative_distance,
                tolerated_depth: settings.speculative_distance.min(0.25 * body.max_extent),
            };
            let swept = motion.swept_bounds(&body.shape, &Pose::IDENTITY, &Pose::IDENTITY);
            let mut earliest: Option<Stop> = None;
            for tree in [broad_phase.static_tree(), broad_phase.moving_tree()] {
                tree.query(&swept, |proxy| {
                    let other_slot = tree.user_data(proxy) as usize;
                    let this = (BodyHandle(index), body);
                    let Some(other) = meets(bodies, other_slot, this, ignored_pairs, joints) else {
                        return true;
                    };
                    if other_slot == slot {
                        return true;
                    }
                    let other_motion = motion_of(other_slot, other);
                    let colliders = (Colliders::of(body), Colliders::of(other));
                    let impact = time_of_impact(
                        &body.shape,
                        &motion,
                        &other.shape,
                        &other_motion,
                        tolerances,
                        |a, b| colliders.0.touch(a, &colliders.1, b),
                    )
                    .filter(|impact| one_way_holds(body, other, impact.normal));
                    if let Some(impact) = impact {
                        if earliest.is_none_or(|kept| impact.t < kept.impact.t) {
                            earliest = Some(Stop {
                                slot,
                                impact,
                                against: other_slot,
                            });
                        }
                    }
                    true
                });
            }
            impacts.extend(earliest);
        }
        for &Stop {
            slot,
            impact,
            against,
        } in impacts.iter()
        {
            let Some((_, body)) = bodies.at_slot(slot) else {
                continue;
            };
            let pose = motion_of(slot, body).pose_at(impact.t);
            let pusher = bodies
                .at_slot(against)
                .and_then(|(_, other)| Pusher::moving(other, dt));
            if let Some(body) = bodies.at_slot_mut(slot) {
                body.rotation = pose.rotation;
                body.center_of_mass = pose.transform_point(body.local_center_of_mass);
                body.update_world_inverse_inertia();
                let Impact { t, normal } = impact;
                if let Some(pusher) = pusher {
                    // Put back where it met a kinematic body, it would be left behind by it:
                    // the kinematic body goes on to the end of the step.
                    pusher.push(body, t, -normal, settings);
                } else if t == 0.0 {
                    // Its contact let it through: it turned into the other body with a side the
                    // contact did not see. Kept at its start with this velocity, it would try
                    // again every step; it stops against the other instead.
                    let into = body.linear_velocity.dot(normal).max(0.0);
                    body.linear_velocity -= into * normal;
                    body.angular_velocity = Vec3::ZERO;
                }
            }
        }
        self.push_ahead_of_fast_kinematic_bodies(dt);
    }

    /// Sweeps each fast kinematic body (ascending slot) over the step `dt` against the dynamic
    /// bodies, each fixed at the pose the step (and the sweep of the fast dynamic bodies) left
    /// it in. A body it would end deep in or past is carried from where they met as if fixed
    /// to it for the rest of the step, so it ends a quarter of the speculative distance ahead
    /// of it, and its velocity along the normal there is made that of the kinematic surface
    /// (plus the bounce of the bodies' restitution, when it approached faster than the
    /// restitution threshold), as a collision with a body of infinite mass leaves it.
    fn push_ahead_of_fast_kinematic_bodies(&mut self, dt: f32) {
        let Self {
            settings,
            bodies,
            joints,
            broad_phase,
            ignored_pairs,
            islands,
            impacts,
            ..
        } = self;
        // By place: a body woken here joins the awake list only at the next step's wake.
        for place in 0..islands.awake().len() {
            let slot = islands.awake()[place];
            let Some((index, kinematic)) = bodies.at_slot(slot) else {
                continue;
            };
            if !is_fast_kinematic(kinematic, dt) {
                continue;
            }
            impacts.clear();
            let motion = kinematic_motion(kinematic, dt);
            let tree = broad_phase.moving_tree();
            let swept = motion.swept_bounds(&kinematic.shape, &Pose::IDENTITY, &Pose::IDENTITY);
            tree.query(&swept, |proxy| {
                let other_slot = tree.user_data(proxy) as usize;
                let this = (BodyHandle(index), kinematic);
                let Some(other) = meets(bodies, other_slot, this, ignored_pairs, joints) else {
                    return true;
                };
                if other.body_type != BodyType::Dynamic {
                    return true;
                }
                let tolerances = ImpactTolerances {
                    target: 0.25 * settings.speculative_distance,
                    tolerated_depth: settings
                        .speculative_distance
                        .min(0.25 * kinematic.max_extent.min(other.max_extent)),
                };
                let colliders = (Colliders::of(kinematic), Colliders::of(other));
                let impact = time_of_impact(
                    &kinematic.shape,
                    &motion,
                    &other.shape,
                    &fixed_motion(other),
                    tolerances,
                    |a, b| colliders.0.touch(a, &colliders.1, b),
                )
                .filter(|impact| one_way_holds(kinematic, other, impact.normal));
                impacts.extend(impact.map(|impact| Stop {
                    slot: other_slot,
                    impact,
                    against: slot,
                }));
                true
            });
            let pusher = Pusher::of(kinematic, dt);
            for &Stop { slot, impact, .. } in impacts.iter() {
                let Some(body) = bodies.at_slot_mut(slot) else {
                    continue;
                };
                pusher.push(body, impact.t, impact.normal, settings);
                if body.sleeping {
                    body.wake();
                    islands.note_woken(slot);
                }
            }
        }
        impacts.clear();
    }
}

/// The body in `slot` when a sweep of `this` must test it: not a sensor, and let collide with
/// `this` by their groups, the ignored pairs and the joints ([`pair_interacts`]).
fn meets<'a>(
    bodies: &'a Arena<RigidBody>,
    slot: usize,
    this: (BodyHandle, &RigidBody),
    ignored_pairs: &IgnoredPairs,
    joints: &JointSet,
) -> Option<&'a RigidBody> {
    let (index, other) = bodies.at_slot(slot)?;
    (!other.sensor && pair_interacts(this, (BodyHandle(index), other), ignored_pairs, joints))
        .then_some(other)
}

/// A body the continuous pass puts back or pushes ahead, by slot: where, and the slot of the
/// body it met there.
#[derive(Debug, Clone, Copy)]
pub(super) struct Stop {
    slot: usize,
    impact: Impact,
    against: usize,
}

/// A kinematic body's motion over the step, as it pushes what it meets.
struct Pusher {
    motion: Motion,
    velocity: Vec3,
    spin: Vec3,
    center: Vec3,
    restitution: f32,
}

impl Pusher {
    /// The pusher of kinematic `body` over the step `dt`.
    fn of(body: &RigidBody, dt: f32) -> Self {
        Self {
            motion: kinematic_motion(body, dt),
            velocity: body.linear_velocity,
            spin: body.angular_velocity,
            center: body.center_of_mass,
            restitution: body.restitution,
        }
    }

    /// The pusher of `body` if it is a kinematic body in motion.
    fn moving(body: &RigidBody, dt: f32) -> Option<Self> {
        let moves = body.linear_velocity != Vec3::ZERO || body.angular_velocity != Vec3::ZERO;
        (body.body_type == BodyType::Kinematic && moves).then(|| Self::of(body, dt))
    }

    /// Carries `body`, which met the kinematic body at fraction `t` of the step with unit
    /// `normal` from the kinematic body toward it, from there to the end of the step as if fixed
    /// to it (along and about its free axes only), and gives it the velocity a collision with a
    /// body of infinite mass leaves: along the normal, at least that of the kinematic surface
    /// under it, plus the bounce of the bodies' restitution when it approached faster than the
    /// restitution threshold. Its velocity across the normal, and its spin, are kept.
    fn push(&self, body: &mut RigidBody, t: f32, normal: Vec3, settings: &WorldSettings) {
        let carry = self
            .motion
            .pose_at(1.0)
            .mul_pose(&self.motion.pose_at(t).inverse());
        let carried = carry.mul_pose(&body.center_pose());
        let locks = body.locked_axes;
        body.center_of_mass += locks.free_linear(carried.position - body.center_of_mass);
        if !locks.locks_rotation() {
            body.rotation = carried.rotation;
            body.update_world_inverse_inertia();
        }
        let normal = carry.transform_vector(normal);
        let surface = self.velocity + self.spin.cross(body.center_of_mass - self.center);
        let approach = (body.linear_velocity - surface).dot(normal);
        if approach < 0.0 {
            let restitution = if -approach > settings.restitution_threshold {
                settings
                    .restitution_combine
                    .combine(self.restitution, body.restitution)
            } else {
                0.0
            };
            body.linear_velocity -= locks.free_linear((1.0 + restitution) * approach * normal);
        }
    }
}
