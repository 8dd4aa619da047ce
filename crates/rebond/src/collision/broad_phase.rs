//! The broad phase: keeps the set of body pairs whose fat bounding boxes overlap, updated
//! incrementally from one step to the next.
//!
//! Bodies live in two [`DynamicTree`]s, one for static bodies and one for everything that moves
//! (dynamic and kinematic), so two static bodies are never paired. Each step the caller reports
//! new tight boxes with [`BroadPhase::update`]; a proxy whose tight box left its fat box gets a
//! new fat box and is marked moved. [`BroadPhase::update_pairs`] then drops every pair of a moved
//! or removed proxy and lets each moved proxy query the trees for its current overlaps, so the
//! work is proportional to what moved, not to the number of bodies.
//!
//! A moving proxy can be put to sleep ([`BroadPhase::set_asleep`]): a pair of which neither proxy
//! is awake (two sleeping, or sleeping and static) cannot change, so it is parked in a list of its
//! own that no update walks, and comes back to [`BroadPhase::pairs`] when one of its proxies wakes.
//! An update walks the awake pairs and what changed; the parked list only when a proxy woke or an
//! asleep or static proxy changed. A new pair of which no proxy is awake (a static proxy moved or
//! added next to sleeping ones) is listed for one update, so that the caller sees the meeting (a
//! sensor's overlap), and parked at the next.

use super::dynamic_tree::{DynamicTree, ProxyId};
use crate::math::Aabb;
use crate::sorted::merge_into;

/// Names one body's proxy in a [`BroadPhase`]: which tree it is in and its id there, packed in
/// one `u32` (the top bit set for the static tree) so that a pair of them takes 8 bytes. Ordered
/// as (moving before static, then by id).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ProxyHandle(u32);

/// The bit of [`ProxyHandle`] that says the proxy is in the static tree.
const STATIC_BIT: u32 = 1 << 31;

impl ProxyHandle {
    /// # Panics
    /// If the proxy's index needs the top bit (more than 2³¹ nodes in one tree).
    fn new(is_static: bool, proxy: ProxyId) -> Self {
        let index = u32::try_from(proxy.index())
            .ok()
            .filter(|&index| index < STATIC_BIT)
            .unwrap_or_else(|| panic!("a broad-phase tree holds at most {STATIC_BIT} nodes"));
        Self(if is_static { index | STATIC_BIT } else { index })
    }

    /// Whether the proxy is in the static tree.
    pub fn is_static(self) -> bool {
        self.0 & STATIC_BIT != 0
    }

    /// The proxy's id in its tree.
    pub fn proxy(self) -> ProxyId {
        ProxyId::from_index(self.0 & !STATIC_BIT)
    }
}

/// Where a proxy stands since the last [`BroadPhase::update_pairs`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
enum ProxyState {
    /// Fat box unchanged: its pairs are still right.
    Unchanged,
    /// Inserted or given a new fat box: its pairs are dropped and found again by a query.
    Moved,
    /// Removed: its pairs are dropped.
    Removed,
}

/// One overlapping pair: the two bodies' keys, smaller first, and their proxies in the same order,
/// in 16 bytes. Lists of pairs are sorted by [`Pair::sort_key`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Pair {
    /// The keys packed into one integer, smaller key in the high half: orders pairs as their keys
    /// do, with one comparison instead of two.
    sort_key: u64,
    proxies: (ProxyHandle, ProxyHandle),
}

impl Pair {
    fn new(first: (u32, ProxyHandle), second: (u32, ProxyHandle)) -> Self {
        let (low, high) = if first.0 <= second.0 {
            (first, second)
        } else {
            (second, first)
        };
        Self {
            sort_key: (u64::from(low.0) << 32) | u64::from(high.0),
            proxies: (low.1, high.1),
        }
    }

    /// The two keys, smaller first.
    fn keys(&self) -> (u32, u32) {
        ((self.sort_key >> 32) as u32, self.sort_key as u32)
    }
}

/// One tree and the state of each of its proxies, indexed by [`ProxyId::index`].
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct TreeWithStates {
    tree: DynamicTree,
    states: Vec<ProxyState>,
}

impl TreeWithStates {
    fn state(&self, proxy: ProxyId) -> ProxyState {
        self.states
            .get(proxy.index())
            .copied()
            .unwrap_or(ProxyState::Unchanged)
    }

    fn state_mut(&mut self, proxy: ProxyId) -> &mut ProxyState {
        if proxy.index() >= self.states.len() {
            self.states.resize(proxy.index() + 1, ProxyState::Unchanged);
        }
        &mut self.states[proxy.index()]
    }
}

/// The set of pairs of bodies whose fat boxes overlap, static–static pairs excepted; see the
/// [module documentation](super::broad_phase).
///
/// Bodies are named by a `u32` key the caller chooses (the body's slot); keys must be unique among
/// the live proxies. Buffers are kept from step to step, so a steady-state step does not allocate.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BroadPhase {
    static_side: TreeWithStates,
    moving_side: TreeWithStates,
    /// Proxies moved, inserted or removed since the last [`update_pairs`](Self::update_pairs),
    /// each once.
    changed: Vec<ProxyHandle>,
    /// The current pairs, sorted.
    pairs: Vec<Pair>,
    /// The keys of [`pairs`](Self::pairs), in the same order, for the public view.
    pair_keys: Vec<(u32, u32)>,
    /// Scratch: pairs found by this update's queries.
    found_pairs: Vec<Pair>,
    /// Whether each proxy of the moving tree sleeps, by [`ProxyId::index`].
    asleep: Vec<bool>,
    /// The pairs of which no proxy is awake, sorted: kept without being walked.
    parked: Vec<Pair>,
    /// Scratch: pairs to park at this update.
    parking: Vec<Pair>,
    /// Whether a proxy fell asleep since the last update, so awake pairs may have to be parked.
    park_pending: bool,
    /// Whether a proxy woke, or an asleep or static proxy changed, since the last update, so parked
    /// pairs may have to come back or be dropped.
    sweep_parked: bool,
}

impl BroadPhase {
    /// An empty broad phase.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds the body `key` with the tight box `aabb` (finite), in the static tree if `is_static`
    /// and in the moving tree otherwise. Its pairs appear at the next
    /// [`update_pairs`](Self::update_pairs).
    pub fn insert(&mut self, key: u32, aabb: Aabb, is_static: bool) -> ProxyHandle {
        let side = self.side_mut(is_static);
        let proxy = side.tree.create_proxy(aabb, key);
        let handle = ProxyHandle::new(is_static, proxy);
        if !is_static {
            self.set_asleep_flag(proxy, false);
        }
        self.mark(handle, ProxyState::Moved);
        handle
    }

    /// Removes a body's proxy. Its pairs are dropped at the next
    /// [`update_pairs`](Self::update_pairs).
    ///
    /// # Panics
    /// If `handle` does not name a live proxy of this broad phase.
    pub fn remove(&mut self, handle: ProxyHandle) {
        self.side_mut(handle.is_static())
            .tree
            .destroy_proxy(handle.proxy());
        self.mark_changed(handle, ProxyState::Removed);
        if !handle.is_static() {
            self.set_asleep_flag(handle.proxy(), false);
        }
    }

    /// Puts a moving proxy to sleep or wakes it (static proxies never wake): from the next
    /// [`update_pairs`](Self::update_pairs), the pairs of which neither proxy is awake are parked,
    /// out of [`pairs`](Self::pairs), and a woken proxy's pairs come back.
    ///
    /// # Panics
    /// If `handle` names a static proxy.
    pub fn set_asleep(&mut self, handle: ProxyHandle, asleep: bool) {
        assert!(!handle.is_static(), "a static proxy never wakes");
        if self.is_asleep(handle) == asleep {
            return;
        }
        self.set_asleep_flag(handle.proxy(), asleep);
        if asleep {
            self.park_pending = true;
        } else {
            self.sweep_parked = true;
        }
    }

    /// Whether the proxy is a moving one and awake.
    fn is_awake(&self, handle: ProxyHandle) -> bool {
        !handle.is_static() && !self.is_asleep(handle)
    }

    fn is_asleep(&self, handle: ProxyHandle) -> bool {
        self.asleep
            .get(handle.proxy().index())
            .copied()
            .unwrap_or(false)
    }

    fn set_asleep_flag(&mut self, proxy: ProxyId, asleep: bool) {
        if proxy.index() >= self.asleep.len() {
            self.asleep.resize(proxy.index() + 1, false);
        }
        self.asleep[proxy.index()] = asleep;
    }

    /// Reports a body's new tight box. Returns whether the box left the fat box, in which case the
    /// proxy gets a new fat box and its pairs are recomputed at the next
    /// [`update_pairs`](Self::update_pairs).
    ///
    /// # Panics
    /// If `handle` does not name a live proxy of this broad phase.
    pub fn update(&mut self, handle: ProxyHandle, tight_aabb: Aabb) -> bool {
        let moved = self
            .side_mut(handle.is_static())
            .tree
            .move_proxy(handle.proxy(), tight_aabb);
        if moved {
            self.mark_changed(handle, ProxyState::Moved);
        }
        moved
    }

    /// Brings [`pairs`](Self::pairs) up to date with every insertion, removal and move since the
    /// last call: drops the pairs of changed proxies, then each moved proxy queries the moving
    /// tree (and, if it moves, the static tree) for its overlaps.
    pub fn update_pairs(&mut self) {
        self.update_pairs_filtered(|_, _| true);
    }

    /// [`update_pairs`](Self::update_pairs), keeping only the new pairs of keys `(a, b)` for
    /// which `accepts(a, b)` (called with either key first) is true. When the filter's answer
    /// for a proxy's pairs changes, [`refilter`](Self::refilter) the proxy.
    pub fn update_pairs_filtered(&mut self, mut accepts: impl FnMut(u32, u32) -> bool) {
        if self.changed.is_empty() && !self.park_pending && !self.sweep_parked {
            return;
        }
        let Self {
            static_side,
            moving_side,
            changed,
            pairs,
            pair_keys,
            found_pairs,
            asleep,
            parked,
            parking,
            park_pending,
            sweep_parked,
        } = self;
        let sides = [&*moving_side, &*static_side];
        let side_of = |handle: ProxyHandle| sides[usize::from(handle.is_static())];
        let is_unchanged =
            |handle: ProxyHandle| side_of(handle).state(handle.proxy()) == ProxyState::Unchanged;
        let is_awake = |handle: ProxyHandle| {
            !handle.is_static() && !asleep.get(handle.proxy().index()).copied().unwrap_or(false)
        };
        found_pairs.clear();
        parking.clear();
        if *sweep_parked {
            parked.retain(|pair| {
                let (a, b) = pair.proxies;
                if !(is_unchanged(a) && is_unchanged(b)) {
                    return false;
                }
                let wakes = is_awake(a) || is_awake(b);
                if wakes {
                    found_pairs.push(*pair);
                }
                !wakes
            });
        }
        if *park_pending {
            pairs.retain(|pair| {
                let (a, b) = pair.proxies;
                if !(is_unchanged(a) && is_unchanged(b)) {
                    return false;
                }
                let parks = !is_awake(a) && !is_awake(b);
                if parks {
                    parking.push(*pair);
                }
                !parks
            });
        } else {
            pairs.retain(|pair| is_unchanged(pair.proxies.0) && is_unchanged(pair.proxies.1));
        }

        for &handle in changed.iter() {
            let side = side_of(handle);
            if side.state(handle.proxy()) != ProxyState::Moved {
                continue;
            }
            let key = side.tree.user_data(handle.proxy());
            let fat_aabb = side.tree.fat_aabb(handle.proxy());
            let searched: &[&TreeWithStates] = if handle.is_static() {
                &sides[..1]
            } else {
                &sides
            };
            for (other_is_static, other_side) in [false, true].into_iter().zip(searched) {
                other_side.tree.query(&fat_aabb, |other_proxy| {
                    let other = ProxyHandle::new(other_is_static, other_proxy);
                    let other_key = other_side.tree.user_data(other_proxy);
                    // Two moved proxies find each other: only the smaller one adds the pair.
                    let found_by_other =
                        other_side.state(other_proxy) == ProxyState::Moved && other < handle;
                    if other_key != key && !found_by_other && accepts(key, other_key) {
                        found_pairs.push(Pair::new((key, handle), (other_key, other)));
                    }
                    true
                });
            }
        }
        // Keys are unique among live proxies, so no two pairs share a sort key.
        found_pairs.sort_unstable_by_key(|pair| pair.sort_key);
        merge_into(pairs, found_pairs, |pair| pair.sort_key);
        pair_keys.clear();
        pair_keys.extend(pairs.iter().map(Pair::keys));
        merge_into(parked, parking, |pair| pair.sort_key);
        // The new pairs of which no proxy is awake are parked at the next update.
        *park_pending = found_pairs
            .iter()
            .any(|pair| !is_awake(pair.proxies.0) && !is_awake(pair.proxies.1));
        *sweep_parked = false;

        for handle in changed.drain(..) {
            let side = if handle.is_static() {
                &mut *static_side
            } else {
                &mut *moving_side
            };
            *side.state_mut(handle.proxy()) = ProxyState::Unchanged;
        }
    }

    /// Drops the proxy's pairs and finds them again at the next update, as if it had moved: for
    /// when the pair filter's answer changed. `handle` must name a live proxy.
    pub fn refilter(&mut self, handle: ProxyHandle) {
        self.mark_changed(handle, ProxyState::Moved);
    }

    /// The pairs of keys whose fat boxes overlapped at the last
    /// [`update_pairs`](Self::update_pairs) and of which at least one proxy is awake: smaller key
    /// first, sorted, each pair once, never two static bodies.
    pub fn pairs(&self) -> &[(u32, u32)] {
        &self.pair_keys
    }

    /// The parked pairs: overlapping at the last [`update_pairs`](Self::update_pairs), no proxy
    /// awake; smaller key first, sorted.
    pub fn parked_pairs(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.parked.iter().map(Pair::keys)
    }

    /// Number of live proxies, static and moving.
    pub fn proxy_count(&self) -> usize {
        self.static_side.tree.proxy_count() + self.moving_side.tree.proxy_count()
    }

    /// The proxy's fat box: its tight box at the last reinsertion grown by
    /// [`AABB_MARGIN`](super::dynamic_tree::AABB_MARGIN).
    ///
    /// # Panics
    /// If `handle` does not name a live proxy of this broad phase.
    pub fn fat_aabb(&self, handle: ProxyHandle) -> Aabb {
        self.side(handle.is_static()).tree.fat_aabb(handle.proxy())
    }

    /// The key the proxy was inserted with.
    ///
    /// # Panics
    /// If `handle` does not name a live proxy of this broad phase.
    pub fn key(&self, handle: ProxyHandle) -> u32 {
        self.side(handle.is_static()).tree.user_data(handle.proxy())
    }

    /// Checks a decoded broad phase against the bodies' keys (`slot_count` arena slots): both
    /// trees whole, every proxy to be queried live, every pair sorted and naming keys below
    /// `slot_count`. Describes the first broken invariant.
    #[cfg(feature = "serde")]
    pub(crate) fn check_decoded(&self, slot_count: usize) -> Result<(), String> {
        for side in [&self.static_side, &self.moving_side] {
            side.tree.validate()?;
        }
        for &handle in &self.changed {
            let side = self.side(handle.is_static());
            if side.state(handle.proxy()) == ProxyState::Moved
                && !side.tree.is_live_proxy(handle.proxy())
            {
                return Err(format!("moved proxy {} is not live", handle.0));
            }
        }
        for pairs in [&self.pairs, &self.parked] {
            let sorted = pairs
                .windows(2)
                .all(|two| two[0].sort_key < two[1].sort_key);
            let keys_known = pairs.iter().all(|pair| {
                let (a, b) = pair.keys();
                (a as usize) < slot_count && (b as usize) < slot_count
            });
            if !(sorted && keys_known) {
                return Err("a pair list is out of order or names an unknown body".to_owned());
            }
        }
        if !self
            .pair_keys
            .iter()
            .copied()
            .eq(self.pairs.iter().map(Pair::keys))
        {
            return Err("the pairs' keys do not match the pairs".to_owned());
        }
        Ok(())
    }

    /// Whether `handle` names a live proxy.
    #[cfg(feature = "serde")]
    pub(crate) fn is_live(&self, handle: ProxyHandle) -> bool {
        self.side(handle.is_static())
            .tree
            .is_live_proxy(handle.proxy())
    }

    /// The tree of static bodies.
    pub fn static_tree(&self) -> &DynamicTree {
        &self.static_side.tree
    }

    /// The tree of dynamic and kinematic bodies.
    pub fn moving_tree(&self) -> &DynamicTree {
        &self.moving_side.tree
    }

    fn side(&self, is_static: bool) -> &TreeWithStates {
        if is_static {
            &self.static_side
        } else {
            &self.moving_side
        }
    }

    fn side_mut(&mut self, is_static: bool) -> &mut TreeWithStates {
        if is_static {
            &mut self.static_side
        } else {
            &mut self.moving_side
        }
    }

    /// Records a change to a proxy that may have pairs: one that is not awake may have parked
    /// pairs, which the next update then looks through.
    fn mark_changed(&mut self, handle: ProxyHandle, state: ProxyState) {
        if !self.is_awake(handle) {
            self.sweep_parked = true;
        }
        self.mark(handle, state);
    }

    /// Records a change to a proxy, listing it for the next update if it was not listed yet.
    fn mark(&mut self, handle: ProxyHandle, state: ProxyState) {
        let slot = self.side_mut(handle.is_static()).state_mut(handle.proxy());
        let already_listed = *slot != ProxyState::Unchanged;
        *slot = state;
        if !already_listed {
            self.changed.push(handle);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Vec3;

    fn unit_box_at(x: f32) -> Aabb {
        Aabb::from_center_half_extents(Vec3::new(x, 0.0, 0.0), Vec3::splat(0.5))
    }

    #[test]
    fn pairs_list_the_smaller_key_first_and_skip_static_static() {
        let mut broad_phase = BroadPhase::new();
        broad_phase.insert(9, unit_box_at(0.0), true);
        broad_phase.insert(4, unit_box_at(0.5), true);
        broad_phase.insert(7, unit_box_at(0.9), false);
        broad_phase.insert(2, unit_box_at(1.5), false);
        broad_phase.update_pairs();
        assert_eq!(broad_phase.pairs(), &[(2, 4), (2, 7), (4, 7), (7, 9)]);
        assert_eq!(broad_phase.proxy_count(), 4);
    }

    #[test]
    fn moving_inside_the_fat_box_changes_nothing_and_leaving_it_updates_the_pairs() {
        let mut broad_phase = BroadPhase::new();
        let ground = broad_phase.insert(0, unit_box_at(0.0), true);
        let ball = broad_phase.insert(1, unit_box_at(1.1), false);
        broad_phase.update_pairs();
        assert_eq!(broad_phase.pairs(), &[(0, 1)]);

        assert!(!broad_phase.update(ball, unit_box_at(1.15)));
        assert!(broad_phase.update(ball, unit_box_at(3.0)));
        assert_eq!(
            broad_phase.pairs(),
            &[(0, 1)],
            "pairs change at update_pairs"
        );
        broad_phase.update_pairs();
        assert!(broad_phase.pairs().is_empty());

        assert!(broad_phase.update(ground, unit_box_at(2.5)));
        broad_phase.update_pairs();
        assert_eq!(broad_phase.pairs(), &[(0, 1)]);
        assert_eq!(broad_phase.key(ground), 0);
    }

    #[test]
    fn filtered_pairs_are_never_made_and_refiltering_asks_again() {
        let mut broad_phase = BroadPhase::new();
        broad_phase.insert(1, unit_box_at(0.0), false);
        let second = broad_phase.insert(2, unit_box_at(0.5), false);
        broad_phase.insert(3, unit_box_at(0.9), false);
        let mut refused = (1, 2);
        let filter = |refused: (u32, u32)| move |a: u32, b: u32| (a.min(b), a.max(b)) != refused;
        broad_phase.update_pairs_filtered(filter(refused));
        assert_eq!(broad_phase.pairs(), &[(1, 3), (2, 3)]);

        // Unchanged proxies keep their pairs whatever the filter says now...
        refused = (2, 3);
        broad_phase.update_pairs_filtered(filter(refused));
        assert_eq!(broad_phase.pairs(), &[(1, 3), (2, 3)]);
        // ...until one of them is refiltered.
        broad_phase.refilter(second);
        broad_phase.update_pairs_filtered(filter(refused));
        assert_eq!(broad_phase.pairs(), &[(1, 2), (1, 3)]);
    }

    #[test]
    fn removing_a_proxy_drops_its_pairs_even_when_its_slot_is_reused() {
        let mut broad_phase = BroadPhase::new();
        let first = broad_phase.insert(1, unit_box_at(0.0), false);
        broad_phase.insert(2, unit_box_at(0.5), false);
        broad_phase.insert(3, unit_box_at(10.0), false);
        broad_phase.update_pairs();
        assert_eq!(broad_phase.pairs(), &[(1, 2)]);

        broad_phase.remove(first);
        broad_phase.insert(4, unit_box_at(10.5), false);
        broad_phase.update_pairs();
        assert_eq!(broad_phase.pairs(), &[(3, 4)]);
        assert_eq!(broad_phase.proxy_count(), 3);
    }

    #[test]
    fn pairs_of_sleeping_proxies_are_parked_until_one_wakes() {
        let mut broad_phase = BroadPhase::new();
        broad_phase.insert(0, unit_box_at(0.0), true);
        let first = broad_phase.insert(1, unit_box_at(0.5), false);
        let second = broad_phase.insert(2, unit_box_at(1.0), false);
        broad_phase.insert(3, unit_box_at(10.0), false);
        broad_phase.update_pairs();
        assert_eq!(broad_phase.pairs(), &[(0, 1), (0, 2), (1, 2)]);

        broad_phase.set_asleep(first, true);
        broad_phase.update_pairs();
        assert_eq!(
            broad_phase.pairs(),
            &[(0, 2), (1, 2)],
            "a pair with an awake proxy stays"
        );
        broad_phase.set_asleep(second, true);
        broad_phase.update_pairs();
        assert!(broad_phase.pairs().is_empty());
        let parked: Vec<_> = broad_phase.parked_pairs().collect();
        assert_eq!(parked, [(0, 1), (0, 2), (1, 2)]);

        broad_phase.set_asleep(second, false);
        broad_phase.update_pairs();
        assert_eq!(broad_phase.pairs(), &[(0, 2), (1, 2)]);
        assert!(broad_phase.parked_pairs().eq([(0, 1)]));
        broad_phase.remove(first);
        broad_phase.update_pairs();
        assert_eq!(broad_phase.pairs(), &[(0, 2)]);
        assert_eq!(
            broad_phase.parked_pairs().count(),
            0,
            "a removed proxy's parked pairs go"
        );
    }
}
