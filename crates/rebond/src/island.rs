//! Islands and sleeping.
//!
//! After each step, awake dynamic bodies linked by contacts or joints form islands (union–find
//! over the contact list and the joints, roots the lowest slot, so the result never depends on
//! anything but the input).
//! A body is still while `|v| + r_max |ω|` stays below the sleep speed; an island all of whose
//! bodies have been still for the sleep time falls asleep as one group (both are settings,
//! [`crate::WorldSettings::sleep_speed`] and [`crate::WorldSettings::sleep_time`]). Sleeping bodies are
//! left out of the step; a group wakes whole when any member is touched by an awake body, pushed
//! by the user, or loses a body it rested on. A group holds its jointed bodies together, so a
//! ragdoll sleeps and wakes whole.

use crate::arena::Arena;
use crate::body::{BodyType, RigidBody};
use crate::collision::contact_cache::Contact;
use crate::math::Vec3;

/// Reused buffers of the island pass.
#[derive(Debug, Clone, Default)]
pub(crate) struct Islands {
    /// Union–find parent of each arena slot, reset each step for the slots of movable bodies only:
    /// a static body never joins an island.
    parent: Vec<usize>,
    /// Shortest sleep time in the island whose root is the slot.
    island_sleep_time: Vec<f32>,
    /// Groups that have an awake member, indexed by the group's root slot.
    group_awake: Vec<bool>,
    /// Slots of bodies touching or jointed to a moving kinematic body this step.
    kept_awake: Vec<usize>,
    /// Each awake dynamic body's slot with its island's root slot.
    members: Vec<(usize, usize)>,
    /// Number of islands of awake dynamic bodies after the last step.
    count: usize,
}

impl Islands {
    /// Islands of awake dynamic bodies after the last step.
    pub fn count(&self) -> usize {
        self.count
    }

    fn find(&mut self, mut slot: usize) -> usize {
        while self.parent[slot] != slot {
            self.parent[slot] = self.parent[self.parent[slot]];
            slot = self.parent[slot];
        }
        slot
    }

    fn union(&mut self, a: usize, b: usize) {
        let (root_a, root_b) = (self.find(a), self.find(b));
        let (low, high) = (root_a.min(root_b), root_a.max(root_b));
        self.parent[high] = low;
    }

    /// Wakes every sleeping body whose group has an awake member (woken by the user or by a touch
    /// since the group fell asleep), and forgets the group of awake bodies. `movable` lists the
    /// slots of the dynamic and kinematic bodies, the only ones that sleep.
    pub fn wake_touched_groups(&mut self, bodies: &mut Arena<RigidBody>, movable: &[usize]) {
        self.group_awake.clear();
        for body in movable
            .iter()
            .filter_map(|&slot| bodies.at_slot(slot))
            .map(|(_, body)| body)
        {
            if let (false, Some(group)) = (body.sleeping, body.sleep_group) {
                if self.group_awake.len() <= group {
                    self.group_awake.resize(group + 1, false);
                }
                self.group_awake[group] = true;
            }
        }
        for &slot in movable {
            let Some(body) = bodies.at_slot_mut(slot) else {
                continue;
            };
            let Some(group) = body.sleep_group else {
                continue;
            };
            if self.group_awake.get(group).copied().unwrap_or(false) {
                body.sleeping = false;
                body.sleep_time = 0.0;
            }
            if !body.sleeping {
                body.sleep_group = None;
            }
        }
    }

    /// Builds this step's islands from `contacts` and the joints' `links` (pairs of body slots),
    /// advances by `dt` the still time of every
    /// awake dynamic body slower than `sleep_speed` (m/s, `|v| + r_max |ω|` with `r_max` the
    /// distance from its centre of mass to the farthest point of its bounding box), and puts to
    /// sleep each island still for `sleep_time` seconds.
    pub fn update_sleep(
        &mut self,
        bodies: &mut Arena<RigidBody>,
        movable: &[usize],
        (contacts, links): (&[Contact], impl Iterator<Item = (usize, usize)>),
        dt: f32,
        sleep_speed: f32,
        sleep_time: f32,
    ) {
        let slots = bodies.slot_count();
        self.parent.resize(slots, 0);
        self.island_sleep_time.resize(slots, f32::INFINITY);
        for &slot in movable {
            self.parent[slot] = slot;
            self.island_sleep_time[slot] = f32::INFINITY;
        }
        let awake_dynamic = |slot: usize| {
            bodies
                .at_slot(slot)
                .is_some_and(|(_, body)| body.is_dynamic() && !body.sleeping)
        };
        for contact in contacts {
            let (slot_a, slot_b) = (contact.key.body_a.slot(), contact.key.body_b.slot());
            if !contact.manifold.is_empty() && awake_dynamic(slot_a) && awake_dynamic(slot_b) {
                self.union(slot_a, slot_b);
            }
        }
        self.kept_awake.clear();
        let moving_kinematic = |slot: usize| {
            bodies.at_slot(slot).is_some_and(|(_, body)| {
                body.body_type == BodyType::Kinematic && body.max_point_speed() > sleep_speed
            })
        };
        for (slot_a, slot_b) in links {
            if awake_dynamic(slot_a) && awake_dynamic(slot_b) {
                self.union(slot_a, slot_b);
            }
            if moving_kinematic(slot_a) || moving_kinematic(slot_b) {
                self.kept_awake.extend([slot_a, slot_b]);
            }
        }
        let moving_kinematic_contacts = contacts.iter().filter(|contact| {
            moving_kinematic(contact.key.body_a.slot())
                || moving_kinematic(contact.key.body_b.slot())
        });
        for contact in moving_kinematic_contacts {
            self.kept_awake.push(contact.key.body_a.slot());
            self.kept_awake.push(contact.key.body_b.slot());
        }
        for &slot in movable {
            let Some(body) = bodies.at_slot_mut(slot) else {
                continue;
            };
            if !body.is_dynamic() || body.sleeping {
                continue;
            }
            if !body.can_sleep || body.max_point_speed() > sleep_speed {
                body.sleep_time = 0.0;
            } else {
                body.sleep_time += dt;
            }
        }
        for &slot in &self.kept_awake {
            if let Some(body) = bodies.at_slot_mut(slot) {
                body.sleep_time = 0.0;
            }
        }
        self.members.clear();
        for (slot, body) in movable
            .iter()
            .filter_map(|&slot| Some((slot, bodies.at_slot(slot)?.1)))
        {
            if body.is_dynamic() && !body.sleeping {
                let root = self.find(slot);
                self.members.push((slot, root));
                let time = &mut self.island_sleep_time[root];
                *time = time.min(body.sleep_time);
            }
        }
        self.count = 0;
        for &(slot, root) in &self.members {
            let falls_asleep = self.island_sleep_time[root] >= sleep_time;
            if slot == root && !falls_asleep {
                self.count += 1;
            }
            if falls_asleep {
                if let Some(body) = bodies.at_slot_mut(slot) {
                    body.sleeping = true;
                    body.sleep_group = Some(root);
                    body.linear_velocity = Vec3::ZERO;
                    body.angular_velocity = Vec3::ZERO;
                }
            }
        }
    }
}
