//! Islands and sleeping: which bodies a step moves, in what order, and which fall asleep.
//!
//! Each step builds its islands once, before the solve, right after the contacts are updated
//! (`World::step`): a union–find over the awake dynamic bodies, whose links each kind of
//! constraint adds ([`IslandLinks`]), the joints' first, then the touching contacts'. When the
//! joints' links are in, each body's group root is recorded: the joint groups the solver solves
//! directly are the components of the joints alone (a pile of touching ragdolls is one island
//! but one group per ragdoll). Roots are the lowest slot, so the result depends on the input
//! alone. The islands are the solver's unit of work: it takes the bodies island by island
//! ([`Islands::solver_order`], one range per island), and after the solve the same islands fall
//! asleep or stay awake ([`Islands::update_sleep`]).
//!
//! A body is still while `|v| + r_max |ω|` stays below the sleep speed; an island all of whose
//! bodies have been still for the sleep time falls asleep as one group (both are settings,
//! [`crate::WorldSettings::sleep_speed`] and [`crate::WorldSettings::sleep_time`]). A group wakes
//! whole when any member is touched by an awake body, pushed by the user, or loses a body it
//! rested on. A kinematic body never joins an island, and what touches or is jointed to one
//! moving faster than the sleep speed stays awake.
//!
//! Sleeping costs nothing per step (Box3D's solver sets, in the small): the awake bodies are a
//! list of their own, [`Islands::awake`], which every per-body pass of the step walks; a sleeping
//! group is a linked list through its members' slots, so waking it costs its size. When groups
//! fall asleep, the world parks their contacts, broad-phase pairs, touching pairs and sensor
//! overlaps out of the step's lists (those of which no body is awake), and brings them back when
//! one of their bodies wakes: a transition costs a pass over the lists it moves between, a step
//! without one touches nothing asleep.

use std::ops::Range;

use crate::arena::Arena;
#[cfg(feature = "serde")]
use crate::body::BodyType;
use crate::body::RigidBody;
use crate::collision::contact_cache::ContactCache;
use crate::coupling::CouplingSet;
use crate::joint::JointSet;
use crate::math::Vec3;
use crate::sorted::merge_into;

/// Ends a sleeping group's list of members.
const END_OF_GROUP: usize = usize::MAX;

/// The island number of an awake body in no island (a kinematic body).
const NOT_IN_ISLAND: usize = usize::MAX;

/// The awake bodies, the sleeping groups, and the reused buffers of the island pass.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Islands {
    /// Slots of the awake dynamic bodies and of every kinematic body, ascending: the bodies a step
    /// moves.
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
    /// Each awake body's group root by slot ([`group_root`](Self::group_root)).
    #[cfg_attr(feature = "serde", serde(skip))]
    group_root: Vec<usize>,
    /// This step's sleep speed, m/s, for the links' kinematic check.
    #[cfg_attr(feature = "serde", serde(skip))]
    sleep_speed: f32,
    /// Slots of bodies beside a moving kinematic body this step.
    #[cfg_attr(feature = "serde", serde(skip))]
    kept_awake: Vec<usize>,
    /// Each island's number, by its root's slot, while the order is made.
    #[cfg_attr(feature = "serde", serde(skip))]
    island_of_root: Vec<usize>,
    /// Each awake body's island number ([`NOT_IN_ISLAND`] for a kinematic body) with its slot,
    /// by ascending slot.
    #[cfg_attr(feature = "serde", serde(skip))]
    members: Vec<(usize, usize)>,
    /// The bodies the step moves, in the solver's order ([`solver_order`](Self::solver_order)).
    #[cfg_attr(feature = "serde", serde(skip))]
    order: Vec<usize>,
    /// Each island's place in `order`.
    #[cfg_attr(feature = "serde", serde(skip))]
    ranges: Vec<Range<usize>>,
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

    /// Starts this step's islands, before the solve: each awake body alone. A body linked to a
    /// kinematic body faster than `sleep_speed` (m/s) is kept awake ([`link`](Self::link)).
    pub fn begin_islands(&mut self, bodies: &Arena<RigidBody>, sleep_speed: f32) {
        self.sleep_speed = sleep_speed;
        self.kept_awake.clear();
        let slots = bodies.slot_count();
        self.parent.resize(slots, 0);
        self.group_root.resize(slots, 0);
        self.island_of_root.resize(slots, 0);
        self.next_in_group.resize(slots, END_OF_GROUP);
        for &slot in &self.awake {
            self.parent[slot] = slot;
        }
    }

    /// A link between the bodies in slots `a` and `b`, called by each kind's
    /// [`IslandLinks::link`] between [`begin_islands`](Self::begin_islands) and
    /// [`end_islands`](Self::end_islands). When `joined` (a joint, a touching contact), puts both
    /// in one island if both are awake and dynamic: a kinematic, static or sleeping body never
    /// joins an island. Roots are the lowest slot, so the islands depend on the links alone, not
    /// on their order. Either way, when either body is a kinematic body faster than the sleep
    /// speed, keeps both from counting as still this step: a body it carries, drags or is about
    /// to touch stays awake.
    #[inline]
    pub fn link(&mut self, bodies: &Arena<RigidBody>, a: usize, b: usize, joined: bool) {
        let (Some((_, body_a)), Some((_, body_b))) = (bodies.at_slot(a), bodies.at_slot(b)) else {
            return;
        };
        let awake_dynamic = |body: &RigidBody| body.is_dynamic() && !body.sleeping;
        if joined && awake_dynamic(body_a) && awake_dynamic(body_b) {
            let (root_a, root_b) = (self.find(a), self.find(b));
            let (low, high) = (root_a.min(root_b), root_a.max(root_b));
            self.parent[high] = low;
        }
        let sleep_speed = self.sleep_speed;
        let moving_kinematic = |body: &RigidBody| body.is_kinematic_moving_faster_than(sleep_speed);
        if moving_kinematic(body_a) || moving_kinematic(body_b) {
            self.kept_awake.extend([a, b]);
        }
    }

    /// Ends the links of the kinds solved in groups (joints): records each awake body's group
    /// root, the lowest slot of the bodies those links alone join, before the other kinds'
    /// links join groups into islands.
    pub fn end_group_links(&mut self) {
        for index in 0..self.awake.len() {
            let slot = self.awake[index];
            self.group_root[slot] = self.find(slot);
        }
    }

    /// The root slot of the group of the awake body in `slot`, recorded by
    /// [`end_group_links`](Self::end_group_links): the bodies of one root are joined by
    /// constraints solved in groups, through dynamic bodies. A kinematic body is its own root.
    pub fn group_root(&self, slot: usize) -> usize {
        self.group_root[slot]
    }

    /// Ends this step's links: lists the awake bodies in [`solver_order`](Self::solver_order),
    /// island by island with each island's range in it, then the kinematic bodies. Costs two
    /// passes over the awake bodies (a counting sort by island).
    pub fn end_islands(&mut self, bodies: &Arena<RigidBody>) {
        // Each island's root, its lowest slot, comes first in the ascending awake list: islands
        // are numbered by it, and counted in their ranges' ends.
        self.members.clear();
        self.ranges.clear();
        let mut kinematic_count = 0;
        for index in 0..self.awake.len() {
            let slot = self.awake[index];
            if !bodies
                .at_slot(slot)
                .is_some_and(|(_, body)| body.is_dynamic())
            {
                self.members.push((NOT_IN_ISLAND, slot));
                kinematic_count += 1;
                continue;
            }
            let root = self.find(slot);
            if root == slot {
                self.island_of_root[slot] = self.ranges.len();
                self.ranges.push(0..0);
            }
            let island = self.island_of_root[root];
            self.ranges[island].end += 1;
            self.members.push((island, slot));
        }
        let mut start = 0;
        for range in &mut self.ranges {
            let size = range.end;
            *range = start..start;
            start += size;
        }
        self.order.clear();
        self.order.resize(start + kinematic_count, 0);
        let mut next_kinematic = start;
        for &(island, slot) in &self.members {
            let place = match self.ranges.get_mut(island) {
                Some(range) => {
                    range.end += 1;
                    range.end - 1
                }
                None => {
                    next_kinematic += 1;
                    next_kinematic - 1
                }
            };
            self.order[place] = slot;
        }
    }

    /// The bodies the step moves, in the solver's order: each island's awake dynamic bodies
    /// together (islands by their lowest slot, bodies by ascending slot), then the kinematic
    /// bodies by ascending slot. Valid from [`end_islands`](Self::end_islands) to the next
    /// [`begin_islands`](Self::begin_islands).
    pub fn solver_order(&self) -> &[usize] {
        &self.order
    }

    /// After the solve, with this step's islands: advances by `dt` the still time of every awake
    /// dynamic body that is still (`RigidBody::is_still`: slower than `sleep_speed`, m/s, and
    /// pushed by no constant force or torque) and not kept awake by a moving kinematic body, and puts to sleep each island still for `sleep_time` seconds,
    /// listed in [`fell_asleep`](Self::fell_asleep). Returns whether any body fell asleep.
    pub fn update_sleep(
        &mut self,
        bodies: &mut Arena<RigidBody>,
        dt: f32,
        sleep_speed: f32,
        sleep_time: f32,
    ) -> bool {
        for &slot in &self.awake {
            let Some(body) = bodies.at_slot_mut(slot) else {
                continue;
            };
            if !body.is_dynamic() {
                continue;
            }
            if !body.can_sleep || !body.is_still(sleep_speed) {
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
        self.count = 0;
        self.fell_asleep.clear();
        for range in &self.ranges {
            let island = &self.order[range.clone()];
            let still_for = island
                .iter()
                .filter_map(|&slot| Some(bodies.at_slot(slot)?.1.sleep_time))
                .fold(f32::INFINITY, f32::min);
            if still_for < sleep_time {
                self.count += 1;
                continue;
            }
            // The root, the island's lowest slot, comes first: each member joins a list that
            // starts at the root.
            let root = island[0];
            for &slot in island {
                if let Some(body) = bodies.at_slot_mut(slot) {
                    body.sleeping = true;
                    body.sleep_group = Some(root);
                    body.linear_velocity = Vec3::ZERO;
                    body.angular_velocity = Vec3::ZERO;
                }
                if slot != root {
                    self.next_in_group[slot] = self.next_in_group[root];
                    self.next_in_group[root] = slot;
                }
            }
            self.fell_asleep.extend_from_slice(island);
        }
        if self.fell_asleep.is_empty() {
            return false;
        }
        self.fell_asleep.sort_unstable();
        let fell_asleep = &self.fell_asleep;
        self.awake
            .retain(|slot| fell_asleep.binary_search(slot).is_err());
        true
    }
}

/// A source of constraints that links bodies into islands: what each kind of constraint keeps
/// between steps (its `ConstraintKind::Source`, `solver/stages.rs`).
pub(crate) trait IslandLinks {
    /// Whether the solver solves these constraints in groups of the bodies they join (the
    /// joints' direct solve): such kinds link first, and
    /// [`end_group_links`](Islands::end_group_links) records the groups before the other kinds
    /// join them into islands.
    const GROUPED: bool;

    /// Links the bodies of each constraint this step ([`Islands::link`]).
    fn link(&self, bodies: &Arena<RigidBody>, islands: &mut Islands);
}

/// A coupling ties the bodies of all its joints: coupled bodies sleep and wake as one.
impl IslandLinks for CouplingSet {
    const GROUPED: bool = false;

    fn link(&self, bodies: &Arena<RigidBody>, islands: &mut Islands) {
        for (_, _, coupled, _) in self.acting() {
            let mut slots = coupled
                .iter()
                .flat_map(|joint| joint.sides.iter().filter_map(|side| side.slot));
            if let Some(first) = slots.next() {
                for slot in slots {
                    islands.link(bodies, first, slot, true);
                }
            }
        }
    }
}

/// Every joint that still acts between two bodies ties them: a jointed pile sleeps and wakes
/// as one.
impl IslandLinks for JointSet {
    const GROUPED: bool = true;

    fn link(&self, bodies: &Arena<RigidBody>, islands: &mut Islands) {
        for (slot_a, slot_b) in self.body_links() {
            islands.link(bodies, slot_a, slot_b, true);
        }
    }
}

/// A contact ties its bodies once it has a manifold; a kinematic body keeps awake what it is
/// about to touch, too.
impl IslandLinks for ContactCache {
    const GROUPED: bool = false;

    fn link(&self, bodies: &Arena<RigidBody>, islands: &mut Islands) {
        for contact in self.contacts() {
            let (slot_a, slot_b) = (contact.key.body_a.slot(), contact.key.body_b.slot());
            islands.link(bodies, slot_a, slot_b, !contact.manifold.is_empty());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arena::new_world;
    use crate::body::{BodyDesc, BodyType};
    use crate::shape::Shape;

    /// Bodies of `types` in slots 0, 1, … (spheres at rest), with islands that have them awake.
    fn bodies_of(types: &[BodyType]) -> (Arena<RigidBody>, Islands) {
        let mut bodies = Arena::new(new_world());
        let mut islands = Islands::default();
        for &body_type in types {
            let shape = Shape::sphere(0.5).expect("valid sphere");
            let desc = match body_type {
                BodyType::Dynamic => BodyDesc::dynamic(shape),
                BodyType::Kinematic => BodyDesc::kinematic(shape),
                BodyType::Static => BodyDesc::static_body(shape),
            };
            let body = RigidBody::from_desc(desc).expect("valid body");
            let slot = bodies.insert(body).slot();
            if body_type != BodyType::Static {
                islands.add_body(slot);
            }
        }
        (bodies, islands)
    }

    #[test]
    fn joints_make_the_groups_and_contacts_join_them_into_islands() {
        use BodyType::{Dynamic as D, Kinematic as K, Static as S};
        // Two jointed pairs, 1–3 and 0–4, touching at 3–4; body 2 touches the kinematic body 5
        // and the static body 6, which join nothing; 7 is near 2 without touching it.
        let (bodies, mut islands) = bodies_of(&[D, D, D, D, D, K, S, D]);
        islands.begin_islands(&bodies, 0.05);
        islands.link(&bodies, 3, 1, true);
        islands.link(&bodies, 0, 4, true);
        islands.end_group_links();
        islands.link(&bodies, 3, 4, true);
        islands.link(&bodies, 2, 5, true);
        islands.link(&bodies, 6, 2, true);
        islands.link(&bodies, 2, 7, false);
        islands.end_islands(&bodies);
        let group_roots: Vec<usize> = [0, 1, 2, 3, 4, 5, 7]
            .map(|slot| islands.group_root(slot))
            .to_vec();
        assert_eq!(group_roots, [0, 1, 2, 1, 0, 5, 7]);
        // Islands by lowest slot, bodies ascending within each, the kinematic body last.
        assert_eq!(islands.solver_order(), [0, 1, 3, 4, 2, 7, 5]);
        assert_eq!(islands.ranges, [0..4, 4..5, 5..6]);
        // The kinematic body is at rest: it keeps nothing awake.
        assert!(islands.kept_awake.is_empty());
    }
}
