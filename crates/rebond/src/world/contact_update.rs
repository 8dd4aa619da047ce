//! The step's collision detection: the broad-phase pairs of the awake bodies, their narrow
//! phase into contacts (with the speculative margin of each pair), and the removal of the
//! contacts of pairs that no longer interact.

use super::World;
use crate::arena::Arena;
use crate::body::{BodyHandle, BodyType, RigidBody};
use crate::collision::FAST_MOTION_REACHES;
use crate::filter::{Colliders, IgnoredPairs};
use crate::hooks::{ContactHooks, ContactModification};
use crate::joint::JointSet;
use crate::material::Material;
use crate::math::{Aabb, Vec3};
use crate::shape::Shape;
use crate::solver::contact_model::patch_radius_ratio;

impl World {
    /// Collision detection: refreshes the boxes of the awake bodies (and of static bodies lent
    /// out), updates the broad-phase pairs (only pairs that interact: groups, ignored pairs, not
    /// two sensors), and runs the narrow phase on each pair with a moving body, carrying impulses
    /// over by feature id. Pairs of which no body is awake are parked and not walked. Pairs with
    /// a sensor get no contacts; they are listed for the overlap test at the end of the step.
    /// A pair whose bodies barely moved relative to each other since its manifolds were computed
    /// rebuilds them instead ([`ContactCache::recycle`]).
    ///
    /// The contact margin of a pair grows with how fast its bodies move, so that two bodies
    /// closing in within this step already have speculative points:
    /// [`WorldSettings::speculative_distance`] plus [`speculative_reach`].
    pub(super) fn update_contacts(&mut self, dt: f32) {
        self.update_pairs(dt);
        self.collide_pairs(dt);
        self.finish_contacts();
    }

    /// Refreshes the boxes of the awake bodies and of the static bodies lent out (swept over
    /// the step in the broad phase), then the broad phase's pairs, keeping only pairs that
    /// interact.
    fn update_pairs(&mut self, dt: f32) {
        let Self {
            bodies,
            joints,
            broad_phase,
            ignored_pairs,
            bounds_of_slot,
            islands,
            touched_static_slots,
            ..
        } = self;
        for &slot in islands.awake().iter().chain(touched_static_slots.iter()) {
            let Some((_, body)) = bodies.at_slot(slot) else {
                continue;
            };
            let bounds = body.aabb();
            bounds_of_slot[slot] = bounds;
            if let Some(proxy) = body.proxy {
                broad_phase.update(proxy, body.sweep_aabb(bounds, dt));
            }
        }
        touched_static_slots.clear();
        broad_phase.update_pairs_filtered(|key_a, key_b| {
            let (Some((index_a, body_a)), Some((index_b, body_b))) = (
                bodies.at_slot(key_a as usize),
                bodies.at_slot(key_b as usize),
            ) else {
                return false;
            };
            !(body_a.sensor && body_b.sensor)
                && pair_interacts(
                    (BodyHandle(index_a), body_a),
                    (BodyHandle(index_b), body_b),
                    ignored_pairs,
                    joints,
                )
        });
    }

    /// Walks the broad phase's pairs: a pair with a sensor becomes a candidate for the overlap
    /// test, a pair of which no body is awake keeps its parked contacts, a recycled pair its
    /// manifolds, and the others within their margin of each other go through the narrow phase,
    /// collider by collider. A body with sensor children is also a candidate with the other.
    fn collide_pairs(&mut self, dt: f32) {
        let Self {
            settings,
            bodies,
            broad_phase,
            contacts,
            narrow_phase,
            events,
            narrow_phase_pair_tests,
            bounds_of_slot,
            ..
        } = self;
        contacts.begin_step();
        events.begin_sensor_step();
        *narrow_phase_pair_tests = 0;
        narrow_phase.set_speculative_distance(settings.speculative_distance);
        for &(key_a, key_b) in broad_phase.pairs() {
            let (Some((index_a, body_a)), Some((index_b, body_b))) = (
                bodies.at_slot(key_a as usize),
                bodies.at_slot(key_b as usize),
            ) else {
                continue;
            };
            let (body_a_handle, body_b_handle) = (BodyHandle(index_a), BodyHandle(index_b));
            if body_a.sensor || body_b.sensor {
                let (sensor, other) = if body_a.sensor {
                    (body_a_handle, body_b_handle)
                } else {
                    (body_b_handle, body_a_handle)
                };
                events.add_sensor_candidate(sensor, other);
                continue;
            }
            let colliders = (Colliders::of(body_a), Colliders::of(body_b));
            if colliders.0.has_sensor_children() {
                events.add_sensor_candidate(body_a_handle, body_b_handle);
            }
            if colliders.1.has_sensor_children() {
                events.add_sensor_candidate(body_b_handle, body_a_handle);
            }
            if !body_a.is_awake_mover() && !body_b.is_awake_mover() {
                if body_a.sleeping || body_b.sleeping {
                    contacts.keep_previous(body_a_handle, body_b_handle);
                }
                continue;
            }
            let (pose_a, pose_b) = (body_a.pose(), body_b.pose());
            // The contact cache keeps its frames at the centres of mass, whose lever arms the
            // solver reads.
            let (center_a, center_b) = (body_a.center_pose(), body_b.center_pose());
            // Only flat surfaces keep their contact features while they turn: a recycled point
            // on a rolling ball would lag behind the true contact, and the normal force there
            // would push the roll on.
            let recyclable = body_a.polyhedral && body_b.polyhedral;
            if recyclable && contacts.recycle(body_a_handle, body_b_handle, &center_a, &center_b) {
                continue;
            }
            let margin = settings.speculative_distance + speculative_reach(body_a, body_b, dt);
            if !bounds_within(
                &bounds_of_slot[key_a as usize],
                &bounds_of_slot[key_b as usize],
                margin,
            ) {
                continue;
            }
            *narrow_phase_pair_tests += 1;
            let mut pair = contacts.pair(body_a_handle, body_b_handle, &center_a, &center_b);
            if colliders.0.need_filtering(&colliders.1) {
                pair = pair.filtered(colliders.0, colliders.1);
            }
            narrow_phase.collide(
                &body_a.shape,
                &pose_a,
                &body_b.shape,
                &pose_b,
                margin,
                &mut pair,
            );
        }
        contacts.finish_step();
    }

    /// Gives each of this step's contacts its combined material and its patch's radius ratio,
    /// and wakes the sleepers an awake mover touches.
    fn finish_contacts(&mut self) {
        let Self {
            settings,
            bodies,
            contacts,
            islands,
            ..
        } = self;
        for contact in contacts.contacts_mut() {
            if contact.manifold.is_empty() {
                continue;
            }
            let (a, b) = (contact.key.body_a, contact.key.body_b);
            let (Some(body_a), Some(body_b)) = (bodies.get(a.0), bodies.get(b.0)) else {
                continue;
            };
            contact.material = Material::combine(
                body_a.material_of_child(contact.key.child_a, contact.manifold.triangle),
                body_b.material_of_child(contact.key.child_b, contact.manifold.triangle),
                settings.friction_combine,
                settings.restitution_combine,
            );
            // A body with only flat surfaces has no cylinder, so a pair of them skips the look.
            let (count, normal) = (contact.manifold.len(), contact.manifold.normal);
            let round = count > 2
                && !(body_a.polyhedral && body_b.polyhedral)
                && (flat_cap(body_a, contact.key.child_a, normal)
                    || flat_cap(body_b, contact.key.child_b, normal));
            contact.patch_radius_ratio = patch_radius_ratio(count, round);
            // A sleeper touched by an awake mover wakes (a body woken here was asleep, so it
            // cannot be the other one's awake toucher).
            let wakes = [
                (a, body_a.sleeping && body_b.is_awake_mover()),
                (b, body_b.sleeping && body_a.is_awake_mover()),
            ];
            for (sleeper, _) in wakes.into_iter().filter(|&(_, wakes)| wakes) {
                if let Some(body) = bodies.get_mut(sleeper.0) {
                    body.wake();
                    islands.note_woken(sleeper.slot());
                }
            }
        }
    }

    /// Shows each of this step's contacts with a body that has contact rules of its own, or
    /// every contact when there are `hooks`, to the rules and then to the hooks, in the
    /// contacts' order, and hands what they changed to the contact cache ([`crate::hooks`]).
    pub(super) fn modify_contacts(&mut self, mut hooks: Option<&mut dyn ContactHooks>) {
        let Self {
            bodies, contacts, ..
        } = self;
        for index in 0..contacts.contacts().len() {
            let contact = &contacts.contacts()[index];
            let (a, b) = contact.bodies();
            let (Some(body_a), Some(body_b)) = (bodies.get(a.0), bodies.get(b.0)) else {
                continue;
            };
            let ruled = body_a.has_contact_rules() || body_b.has_contact_rules();
            if contact.manifold.is_empty() || !(ruled || hooks.is_some()) {
                continue;
            }
            let mut modification = ContactModification::new(contact, body_a, body_b);
            if ruled {
                modification.apply_body_rules();
            }
            if let Some(hooks) = hooks.as_deref_mut() {
                hooks.modify_contact(&mut modification);
            }
            let edit = modification.edit();
            contacts.apply_edit(index, &edit);
        }
    }
}

impl World {
    /// Removes the contacts of the pairs `(a, b)` for which `dropped(bodies, a, b)` is true, and
    /// wakes their bodies: a sleeping pair's groups wake first, so that its contacts come back to
    /// be dropped.
    pub(super) fn drop_contacts(
        &mut self,
        dropped: impl Fn(&Arena<RigidBody>, BodyHandle, BodyHandle) -> bool,
    ) {
        let sleeping: Vec<BodyHandle> = self
            .contacts
            .parked()
            .filter(|contact| dropped(&self.bodies, contact.key.body_a, contact.key.body_b))
            .flat_map(|contact| [contact.key.body_a, contact.key.body_b])
            .collect();
        for handle in sleeping {
            self.wake_slot(handle.slot());
        }
        self.wake_groups(false);
        let Self {
            bodies,
            contacts,
            islands,
            ..
        } = self;
        for contact in contacts.contacts() {
            let (a, b) = (contact.key.body_a, contact.key.body_b);
            if dropped(bodies, a, b) {
                for handle in [a, b] {
                    if let Some(body) = bodies.get_mut(handle.0) {
                        body.wake();
                        islands.note_woken(handle.slot());
                    }
                }
            }
        }
        contacts.retain_pairs(|a, b| !dropped(bodies, a, b));
    }
}

/// Whether two bounding boxes come within `margin` of each other on every axis: a necessary
/// condition for their shapes to come within `margin`, so a pair that fails it has no contact.
fn bounds_within(a: &Aabb, b: &Aabb, margin: f32) -> bool {
    let gap = (a.min - b.max).max(b.min - a.max);
    gap.cmple(Vec3::splat(margin)).all()
}

/// Whether two bodies may touch: their groups interact, and neither an ignored pair nor a joint
/// keeps them apart.
#[inline]
pub(super) fn pair_interacts(
    (handle_a, a): (BodyHandle, &RigidBody),
    (handle_b, b): (BodyHandle, &RigidBody),
    ignored_pairs: &IgnoredPairs,
    joints: &JointSet,
) -> bool {
    a.collision_groups.interacts_with(b.collision_groups)
        && !(ignored_pairs.contains(handle_a, handle_b) || joints.excludes(handle_a, handle_b))
}

/// How far past the speculative distance a pair's contacts are made, m: the distance the two
/// bodies can close in the step, `dt · (|v_A − v_B| + |ω_A| r_A + |ω_B| r_B)`, while it is no
/// more than [`FAST_MOTION_REACHES`] times the sum of the reaches `r` of the bodies that move;
/// past that, nothing, and the continuous pass sweeps the fast body (`continuous.rs`).
fn speculative_reach(a: &RigidBody, b: &RigidBody, dt: f32) -> f32 {
    let reach = |body: &RigidBody| {
        if body.body_type == BodyType::Static {
            0.0
        } else {
            body.max_extent
        }
    };
    let closing = dt * closing_speed_bound(a, b);
    if closing <= FAST_MOTION_REACHES * (reach(a) + reach(b)) {
        closing
    } else {
        0.0
    }
}

/// `|v_A − v_B| + |ω_A| r_A + |ω_B| r_B`: no two points of the bodies close in faster, m/s.
fn closing_speed_bound(a: &RigidBody, b: &RigidBody) -> f32 {
    (a.linear_velocity - b.linear_velocity).length()
        + a.max_extent * a.angular_velocity.length()
        + b.max_extent * b.angular_velocity.length()
}

/// A cylinder's cap counts as lying flat on a face when the cosine between its axis and the
/// contact normal is at least this (5°): its contact patch is then the whole disc.
const FLAT_CAP_COSINE: f32 = 0.996;

/// Whether the part `child` of `body` (the body's shape unless a compound) is a cylinder with a
/// cap flat against the contact `normal`, so its contact patch is a disc.
fn flat_cap(body: &RigidBody, child: u32, normal: Vec3) -> bool {
    let (shape, rotation) = match &body.shape {
        Shape::Compound(compound) => match compound.children().get(child as usize) {
            Some(part) => (&part.shape, body.rotation * part.pose.rotation),
            None => return false,
        },
        shape => (shape, body.rotation),
    };
    matches!(shape, Shape::Cylinder(_)) && (rotation * Vec3::Y).dot(normal).abs() >= FLAT_CAP_COSINE
}
