//! Islands and sleeping: which bodies a step moves.
//!
//! After each step, awake dynamic bodies linked by contacts form islands (union–find over the
//! step's contacts, roots the lowest slot, so the result never depends on anything but the input;
//! other links, such as joints, are more edges of the same union–find, [`Islands::link`]).
//! A body is still while `|v| + r_max |ω|` stays below the sleep speed; an island all of whose
//! bodies have been still for the sleep time falls asleep as one group (both are settings,
//! [`crate::WorldSettings::sleep_speed`] and [`crate::WorldSettings::sleep_time`]). A group wakes
//! whole when any member is touched by an awake body, pushed by the user, or loses a body it
//! rested on.
//!
//! Sleeping costs nothing per step (Box3D's solver sets, in the small): the awake bodies are a
//! list of their own, [`Islands::awake`], which every per-body pass of the step walks; a sleeping
//! group is a linked list through its members' slots, so waking it costs its size. When groups
//! fall asleep, the world parks their contacts, broad-phase pairs, touching pairs and sensor
//! overlaps out of the step's lists (those of which no body is awake), and brings them back when
//! one of their bodies wakes: a transition costs a pass over the lists it moves between, a step
//! without one touches nothing asleep.

use crate::arena::Arena;
#[cfg(feature = "serde")]
use crate::body::BodyType;
use crate::body::RigidBody;
use crate::collision::contact_cache::Contact;
use crate::math::Vec3;
use crate::sorted::merge_into;

/// Ends a sleeping group's list of members.
const END_OF_GROUP: usize = usize::MAX;

/// The awake bodies, the sleeping groups, and the reused buffers of the island pass.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Islands {
    /// Slots of the awake dynamic bodies and of every kinematic body, ascending: the bodies a step
    /// moves, in the order the solver takes them.
    awake: Vec<usize>,
    /// The next member of each sleeping body's group, by slot, or [`END_OF_GROUP`]: a group's list
    /// starts at its root slot (the body's `sleep_group`).
    next_in_group: Vec<usize>,
    /// Slots of bodies that may have been woken since the last [`wake_groups`](Self::wake_groups).
    wake_candidates: Vec<usize>,
    /// Slots woken by the last [`wake_groups`](Self::wake_groups), ascending.
    #[cfg_attr(feature = "serde", serde(skip))]
    woken: Vec<usize>,
    /// Slots that fell asleep in the last [`update_sleep`](Self::update_sleep), ascending.
    #[cfg_attr(feature = "serde", serde(skip))]
    fell_asleep: Vec<usize>,
    /// Union–find parent of each arena slot, reset each step for the awake slots only: a static or
    /// sleeping body never joins an island.
    #[cfg_attr(feature = "serde", serde(skip))]
    parent: Vec<usize>,
    /// Shortest sleep time in the island whose root is the slot.
    #[cfg_attr(feature = "serde", serde(skip))]
    island_sleep_time: Vec<f32>,
    /// Slots of bodies touching a moving kinematic body this step.
    #[cfg_attr(feature = "serde", serde(skip))]
    kept_awake: Vec<usize>,
    /// Each awake dynamic body's slot with its island's root slot.
    #[cfg_attr(feature = "serde", serde(skip))]
    members: Vec<(usize, usize)>,
    /// Number of islands of awake dynamic bodies after the last step.
    count: usize,
}

impl Islands {
    /// Islands of awake dynamic bodies after the last step.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Slots of the bodies the step moves (awake dynamic, and kinematic), ascending.
    pub fn awake(&self) -> &[usize] {
        &self.awake
    }

    /// Slots woken by the last [`wake_groups`](Self::wake_groups), ascending.
    pub fn woken(&self) -> &[usize] {
        &self.woken
    }

    /// Slots that fell asleep in the last [`update_sleep`](Self::update_sleep), ascending.
    pub fn fell_asleep(&self) -> &[usize] {
        &self.fell_asleep
    }

    /// A new dynamic or kinematic body, awake, in `slot`.
    pub fn add_body(&mut self, slot: usize) {
        let place = self.awake.partition_point(|&other| other < slot);
        self.awake.insert(place, slot);
    }

    /// The body in `slot`, awake, is removed.
    pub fn remove_body(&mut self, slot: usize) {
        self.awake.retain(|&other| other != slot);
    }

    /// The body in `slot` may have been woken (its `sleeping` flag cleared): the next
    /// [`wake_groups`](Self::wake_groups) wakes its group.
    pub fn note_woken(&mut self, slot: usize) {
        self.wake_candidates.push(slot);
    }

    /// Wakes the whole group of every candidate woken since the last call (cleared `sleeping`,
    /// still in a group), and adds the woken bodies to [`awake`](Self::awake), listed in
    /// [`woken`](Self::woken). Costs the candidates and the groups woken. Returns whether any
    /// body woke.
    pub fn wake_groups(&mut self, bodies: &mut Arena<RigidBody>) -> bool {
        self.woken.clear();
        for &slot in &self.wake_candidates {
            let root = match bodies.at_slot(slot) {
                Some((_, body)) if !body.sleeping => body.sleep_group,
                _ => None,
            };
            let mut member = root.unwrap_or(END_OF_GROUP);
            while member != END_OF_GROUP {
                if let Some(body) = bodies.at_slot_mut(member) {
                    body.sleeping = false;
                    body.sleep_time = 0.0;
                    body.sleep_group = None;
                }
                self.woken.push(member);
                member = std::mem::replace(&mut self.next_in_group[member], END_OF_GROUP);
            }
        }
        self.wake_candidates.clear();
        if self.woken.is_empty() {
            return false;
        }
        self.woken.sort_unstable();
        merge_into(&mut self.awake, &self.woken, |&slot| slot);
        true
    }

    /// The islands of bodies restored from a portable snapshot, whose `sleeping` and
    /// `sleep_group` are as saved: the moving bodies that are not asleep are awake; each sleeping
    /// body joins the list of its group's root; a body woken by hand before the save (no longer
    /// asleep, still in a group) wakes its group at the next step, as it would have. Built
    /// without checks: [`check_decoded`](Self::check_decoded) follows.
    #[cfg(feature = "serde")]
    pub fn restored(bodies: &Arena<RigidBody>) -> Self {
        let mut islands = Self {
            next_in_group: vec![END_OF_GROUP; bodies.slot_count()],
            ..Self::default()
        };
        for (index, body) in bodies.iter() {
            let slot = index.slot();
            let Some(root) = body.sleep_group else {
                if !body.sleeping && body.body_type != BodyType::Static {
                    islands.awake.push(slot);
                }
                continue;
            };
            if !body.sleeping {
                islands.wake_candidates.push(slot);
            }
            if root != slot && root < islands.next_in_group.len() {
                islands.next_in_group[slot] = islands.next_in_group[root];
                islands.next_in_group[root] = slot;
            }
        }
        islands
    }

    /// Checks decoded islands against `bodies`: the awake list ascending, of live moving bodies
    /// that are not asleep; every sleeping group a list without loops through slots of the arena,
    /// starting at its members' root. Describes the first broken invariant.
    #[cfg(feature = "serde")]
    pub fn check_decoded(&self, bodies: &Arena<RigidBody>) -> Result<(), String> {
        let moving_and_awake = |slot: usize| {
            bodies
                .at_slot(slot)
                .is_some_and(|(_, body)| body.body_type != BodyType::Static && !body.sleeping)
        };
        let ascending = self.awake.windows(2).all(|two| two[0] < two[1]);
        if !(ascending && self.awake.iter().all(|&slot| moving_and_awake(slot))) {
            return Err("the awake list is out of order or names a body not awake".to_owned());
        }
        let slots = bodies.slot_count();
        if self.next_in_group.len() > slots || self.wake_candidates.iter().any(|&s| s >= slots) {
            return Err("sleeping groups name slots past the arena".to_owned());
        }
        // Each slot follows at most one other and each root heads its group: walking from the
        // roots then reaches every listed slot once, unless a list loops.
        let mut followed = vec![false; self.next_in_group.len()];
        for &next in &self.next_in_group {
            if next != END_OF_GROUP && followed.get(next).is_none_or(|&seen| seen) {
                return Err(format!(
                    "slot {next} follows two slots or none of the arena"
                ));
            }
            if let Some(seen) = followed.get_mut(next) {
                *seen = true;
            }
        }
        let mut reached = 0;
        for (slot, body) in (0..slots).filter_map(|slot| Some((slot, bodies.at_slot(slot)?.1))) {
            let Some(root) = body.sleep_group else {
                continue;
            };
            if root >= self.next_in_group.len() || followed[root] {
                return Err(format!(
                    "body {slot}'s sleeping group {root} is not a group"
                ));
            }
            if root == slot {
                let mut member = self.next_in_group[root];
                while member != END_OF_GROUP {
                    reached += 1;
                    member = self.next_in_group[member];
                }
            }
        }
        if reached != followed.iter().filter(|&&seen| seen).count() {
            return Err("a sleeping group's list loops".to_owned());
        }
        Ok(())
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

    /// Puts the bodies in slots `a` and `b` in one island if both are awake and dynamic: called
    /// for each edge of this step (touching contacts, and any other link between two bodies)
    /// between [`begin_islands`](Self::begin_islands) and [`update_sleep`](Self::update_sleep).
    pub fn link(&mut self, bodies: &Arena<RigidBody>, a: usize, b: usize) {
        let awake_dynamic = |slot: usize| {
            bodies
                .at_slot(slot)
                .is_some_and(|(_, body)| body.is_dynamic() && !body.sleeping)
        };
        if awake_dynamic(a) && awake_dynamic(b) {
            self.union(a, b);
        }
    }

    /// Keeps the body in slot `slot` from counting as still this step (it is jointed to a moving
    /// kinematic body); called between [`begin_islands`](Self::begin_islands) and
    /// [`update_sleep`](Self::update_sleep).
    pub fn keep_awake(&mut self, slot: usize) {
        self.kept_awake.push(slot);
    }

    /// Starts this step's islands: each awake body alone.
    pub fn begin_islands(&mut self, bodies: &Arena<RigidBody>) {
        self.kept_awake.clear();
        let slots = bodies.slot_count();
        self.parent.resize(slots, 0);
        self.island_sleep_time.resize(slots, f32::INFINITY);
        self.next_in_group.resize(slots, END_OF_GROUP);
        for &slot in &self.awake {
            self.parent[slot] = slot;
            self.island_sleep_time[slot] = f32::INFINITY;
        }
    }

    /// Links the bodies of each of `contacts` with a manifold ([`link`](Self::link)).
    pub fn link_contacts(&mut self, bodies: &Arena<RigidBody>, contacts: &[Contact]) {
        for contact in contacts {
            if !contact.manifold.is_empty() {
                let (slot_a, slot_b) = (contact.key.body_a.slot(), contact.key.body_b.slot());
                self.link(bodies, slot_a, slot_b);
            }
        }
    }

    /// Ends this step's islands, linked since [`begin_islands`](Self::begin_islands): advances by
    /// `dt` the still time of every awake dynamic body slower than `sleep_speed` (m/s,
    /// `|v| + r_max |ω|` with `r_max` the distance from its centre of mass to the farthest point of
    /// its bounding box) and not touching a moving kinematic body in `contacts`, and puts to sleep
    /// each island still for `sleep_time` seconds, listed in [`fell_asleep`](Self::fell_asleep).
    /// Returns whether any body fell asleep.
    pub fn update_sleep(
        &mut self,
        bodies: &mut Arena<RigidBody>,
        contacts: &[Contact],
        dt: f32,
        sleep_speed: f32,
        sleep_time: f32,
    ) -> bool {
        let moving_kinematic_contacts = contacts.iter().filter(|contact| {
            [contact.key.body_a, contact.key.body_b]
                .iter()
                .any(|handle| {
                    bodies
                        .get(handle.0)
                        .is_some_and(|body| body.is_kinematic_moving_faster_than(sleep_speed))
                })
        });
        for contact in moving_kinematic_contacts {
            self.kept_awake.push(contact.key.body_a.slot());
            self.kept_awake.push(contact.key.body_b.slot());
        }
        for &slot in &self.awake {
            let Some(body) = bodies.at_slot_mut(slot) else {
                continue;
            };
            if !body.is_dynamic() {
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
        for index in 0..self.awake.len() {
            let slot = self.awake[index];
            let Some((_, body)) = bodies.at_slot(slot) else {
                continue;
            };
            if body.is_dynamic() {
                let body_sleep_time = body.sleep_time;
                let root = self.find(slot);
                self.members.push((slot, root));
                let time = &mut self.island_sleep_time[root];
                *time = time.min(body_sleep_time);
            }
        }
        self.count = 0;
        self.fell_asleep.clear();
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
                // The root comes first among its island's members (slot order), so each member
                // joins a list that starts at the root.
                if slot != root {
                    self.next_in_group[slot] = self.next_in_group[root];
                    self.next_in_group[root] = slot;
                }
                self.fell_asleep.push(slot);
            }
        }
        if self.fell_asleep.is_empty() {
            return false;
        }
        let fell_asleep = &self.fell_asleep;
        self.awake
            .retain(|slot| fell_asleep.binary_search(slot).is_err());
        true
    }
}
