//! The continuous pass: after the solver, each fast body (one that moved farther than
//! [`FAST_MOTION_REACHES`](crate::collision::FAST_MOTION_REACHES) times its reach, so its
//! contacts may have missed what it met) is swept from its pose at the step's start to
//! its pose at the end against every body its path overlaps, static or moving, rotation
//! included ([`time_of_impact`]). One that would end the step deep in or past another is put
//! back where it first met it, a little short of touching, with its velocities kept: the next
//! step's contact (within the margin by then) stops it. Box2D does the same for its bullets;
//! the step loses the rest of that body's motion, and a joint to it stretches until the joint
//! pulls it back.

use super::contact_update::pair_interacts;
use super::World;
use crate::body::{BodyHandle, RigidBody};
use crate::collision::time_of_impact::{time_of_impact, Impact, ImpactTolerances, Motion};
use crate::filter::Colliders;
use crate::math::{Pose, Vec3};
use crate::solver::FastMotion;

/// How a body that did not move in the step (static, or not fast) is swept: fixed
/// at its pose.
fn fixed_motion(body: &RigidBody) -> Motion {
    moving(body, Vec3::ZERO, Vec3::ZERO)
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
    /// distance and a quarter of its reach is left to the contacts.
    pub(super) fn stop_fast_bodies(&mut self) {
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
            let mut earliest: Option<Impact> = None;
            for tree in [broad_phase.static_tree(), broad_phase.moving_tree()] {
                tree.query(&swept, |proxy| {
                    let other_slot = tree.user_data(proxy) as usize;
                    let Some((other_index, other)) = bodies.at_slot(other_slot) else {
                        return true;
                    };
                    if other_slot == slot
                        || other.sensor
                        || !pair_interacts(
                            (BodyHandle(index), body),
                            (BodyHandle(other_index), other),
                            ignored_pairs,
                            joints,
                        )
                    {
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
                    );
                    Impact::keep_earliest(&mut earliest, impact);
                    true
                });
            }
            if let Some(impact) = earliest {
                impacts.push((slot, impact));
            }
        }
        for &(slot, Impact { t, normal }) in impacts.iter() {
            let Some((_, body)) = bodies.at_slot(slot) else {
                continue;
            };
            let pose = motion_of(slot, body).pose_at(t);
            if let Some(body) = bodies.at_slot_mut(slot) {
                body.rotation = pose.rotation;
                body.center_of_mass = pose.transform_point(body.local_center_of_mass);
                body.update_world_inverse_inertia();
                if t == 0.0 {
                    // Its contact let it through: it turned into the other body with a side the
                    // contact did not see. Kept at its start with this velocity, it would try
                    // again every step; it stops against the other instead.
                    let into = body.linear_velocity.dot(normal).max(0.0);
                    body.linear_velocity -= into * normal;
                    body.angular_velocity = Vec3::ZERO;
                }
            }
        }
    }
}
