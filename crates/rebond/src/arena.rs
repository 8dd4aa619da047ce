//! A generational arena: items in one contiguous vector, named by (index, generation, world)
//! handles so a handle to a removed item never reaches the item that later takes its slot, and a
//! handle of another world's arena never reaches this one's items.
//!
//! A world's identity is a number from a process-wide counter, given by [`new_world`] when the
//! world is made; its arenas stamp it on every handle they give out and refuse handles that carry
//! another. A clone of a world is the same world at another time and keeps the identity, and so
//! does a world restored from a state: the state holds the identity, and the handles it holds
//! take it as they are read ([`reading_state`]), whatever the bytes say.

#[cfg(feature = "serde")]
use std::cell::Cell;
use std::sync::atomic::{AtomicU32, Ordering};

/// The identity the next world made takes. Identity 0 is given to no world: it is the arenas'
/// own outside a world (`Arena::default`).
static NEXT_WORLD: AtomicU32 = AtomicU32::new(1);

#[cfg(feature = "serde")]
thread_local! {
    /// While a state is read: `Some(None)` until the first identity is read, then `Some(that
    /// identity)`, which every later handle and arena of the state takes.
    static READING_WORLD: Cell<Option<Option<u32>>> = const { Cell::new(None) };
}

/// A new world identity, unique among the worlds this process made or restored, until 2³² worlds
/// have been made and the counter wraps.
pub(crate) fn new_world() -> u32 {
    NEXT_WORLD.fetch_add(1, Ordering::Relaxed)
}

/// Runs `read`, the reading of a state, with every handle and arena it reads taking the first
/// world identity read, so that a state made to disagree with itself still decodes one
/// consistent world. The identity read is never given to a world made later.
#[cfg(feature = "serde")]
pub(crate) fn reading_state<R>(read: impl FnOnce() -> R) -> R {
    let outer = READING_WORLD.replace(Some(None));
    let result = read();
    if let Some(Some(world)) = READING_WORLD.replace(outer) {
        NEXT_WORLD.fetch_max(world.saturating_add(1), Ordering::Relaxed);
    }
    result
}

/// Takes `world`, the identity of a world rebuilt from a portable snapshot, so that no world made
/// later is given it (as [`reading_state`] does for the identities it reads).
#[cfg(feature = "serde")]
pub(crate) fn restore_world(world: u32) {
    NEXT_WORLD.fetch_max(world.saturating_add(1), Ordering::Relaxed);
}

/// Reads a world identity: the state's within [`reading_state`], the one written elsewhere.
#[cfg(feature = "serde")]
fn deserialize_world<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<u32, D::Error> {
    let written = <u32 as serde::Deserialize>::deserialize(deserializer)?;
    Ok(READING_WORLD.with(|reading| match reading.get() {
        None => written,
        Some(Some(first)) => first,
        Some(None) => {
            reading.set(Some(Some(written)));
            written
        }
    }))
}

/// A slot index, the generation the slot had when the item was inserted, and the identity of the
/// world whose arena holds it. Handles of one world order by slot, then generation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ArenaIndex {
    index: u32,
    generation: u32,
    #[cfg_attr(feature = "serde", serde(deserialize_with = "deserialize_world"))]
    world: u32,
}

impl ArenaIndex {
    /// Position of the slot in the arena's storage; stable for the item's lifetime.
    pub fn slot(&self) -> usize {
        self.index as usize
    }

    /// The generation of the slot the handle names.
    #[cfg(feature = "serde")]
    pub(crate) fn generation(&self) -> u32 {
        self.generation
    }

    /// The handle of `slot` at `generation` in the world with identity `world`, as a portable
    /// snapshot names it.
    #[cfg(feature = "serde")]
    pub(crate) fn from_parts(slot: u32, generation: u32, world: u32) -> Self {
        Self {
            index: slot,
            generation,
            world,
        }
    }
}

#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Slot<T> {
    generation: u32,
    item: Option<T>,
}

/// Items of type `T` in slots; iteration runs in slot order, so it is deterministic.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Arena<T> {
    /// Identity of the world the arena belongs to, stamped on its handles.
    #[cfg_attr(feature = "serde", serde(deserialize_with = "deserialize_world"))]
    world: u32,
    slots: Vec<Slot<T>>,
    free_slots: Vec<u32>,
    len: usize,
}

impl<T> Default for Arena<T> {
    fn default() -> Self {
        Self::new(0)
    }
}

impl<T> Arena<T> {
    /// An empty arena of the world with identity `world` (from [`new_world`]).
    pub fn new(world: u32) -> Self {
        Self {
            world,
            slots: Vec::new(),
            free_slots: Vec::new(),
            len: 0,
        }
    }

    /// Whether `handle` was given out by an arena of this world, live or not.
    pub fn owns(&self, handle: ArenaIndex) -> bool {
        handle.world == self.world
    }

    /// The slot `handle` names, if it is of this world.
    fn slot_of(&self, handle: ArenaIndex) -> Option<usize> {
        self.owns(handle).then_some(handle.slot())
    }

    /// The handle of the item in `index` as it is now.
    fn index(&self, index: usize, generation: u32) -> ArenaIndex {
        ArenaIndex {
            index: u32::try_from(index).unwrap_or(u32::MAX),
            generation,
            world: self.world,
        }
    }

    /// Stores `item` in the most recently freed slot, or a new one, and returns its handle.
    pub fn insert(&mut self, item: T) -> ArenaIndex {
        self.len += 1;
        if let Some(index) = self.free_slots.pop() {
            let slot = &mut self.slots[index as usize];
            slot.item = Some(item);
            let generation = slot.generation;
            return self.index(index as usize, generation);
        }
        let index = self.slots.len();
        self.slots.push(Slot {
            generation: 0,
            item: Some(item),
        });
        self.index(index, 0)
    }

    /// Removes and returns the item, or `None` if the handle is stale or of another world.
    pub fn remove(&mut self, handle: ArenaIndex) -> Option<T> {
        let index = self.slot_of(handle)?;
        let slot = self.slots.get_mut(index)?;
        if slot.generation != handle.generation {
            return None;
        }
        let item = slot.item.take()?;
        slot.generation = slot.generation.wrapping_add(1);
        self.free_slots.push(handle.index);
        self.len -= 1;
        Some(item)
    }

    /// The item behind `handle`, unless it was removed or the handle is of another world.
    pub fn get(&self, handle: ArenaIndex) -> Option<&T> {
        self.slots
            .get(self.slot_of(handle)?)
            .filter(|slot| slot.generation == handle.generation)
            .and_then(|slot| slot.item.as_ref())
    }

    /// The item behind `handle`, mutably, unless it was removed or the handle is of another
    /// world.
    pub fn get_mut(&mut self, handle: ArenaIndex) -> Option<&mut T> {
        let slot = self.slot_of(handle)?;
        self.slots
            .get_mut(slot)
            .filter(|slot| slot.generation == handle.generation)
            .and_then(|slot| slot.item.as_mut())
    }

    /// The live item in storage slot `slot`, with its handle.
    pub fn at_slot(&self, slot: usize) -> Option<(ArenaIndex, &T)> {
        let entry = self.slots.get(slot)?;
        let item = entry.item.as_ref()?;
        Some((self.index(slot, entry.generation), item))
    }

    /// The live item in storage slot `slot`, mutably.
    pub fn at_slot_mut(&mut self, slot: usize) -> Option<&mut T> {
        self.slots.get_mut(slot)?.item.as_mut()
    }

    /// Number of slots, live or empty: every live item's slot is below it.
    pub fn slot_count(&self) -> usize {
        self.slots.len()
    }

    /// Number of live items.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Live items with their handles, in slot order.
    pub fn iter(&self) -> impl Iterator<Item = (ArenaIndex, &T)> {
        self.slots.iter().enumerate().filter_map(|(index, slot)| {
            let item = slot.item.as_ref()?;
            Some((self.index(index, slot.generation), item))
        })
    }

    /// Checks a decoded arena's bookkeeping: the free list names exactly the empty slots, once
    /// each, and the count is the live items'. Describes the first broken invariant.
    #[cfg(feature = "serde")]
    pub(crate) fn check_decoded(&self) -> Result<(), String> {
        let live = self.slots.iter().filter(|slot| slot.item.is_some()).count();
        if live != self.len || u32::try_from(self.slots.len()).is_err() {
            return Err(format!("{live} items in an arena that counts {}", self.len));
        }
        let mut listed = vec![false; self.slots.len()];
        for &index in &self.free_slots {
            let empty = self
                .slots
                .get(index as usize)
                .is_some_and(|slot| slot.item.is_none());
            if !empty || std::mem::replace(&mut listed[index as usize], true) {
                return Err(format!(
                    "free slot {index} is taken, missing or listed twice"
                ));
            }
        }
        if self.free_slots.len() != self.slots.len() - live {
            return Err("an empty slot is not on the free list".to_owned());
        }
        Ok(())
    }

    /// The identity of the world the arena belongs to.
    #[cfg(feature = "serde")]
    pub(crate) fn world(&self) -> u32 {
        self.world
    }

    /// Every slot's generation and item, in slot order, empty slots included: what a portable
    /// snapshot keeps so that every handle, stale ones too, names the same items after a load.
    #[cfg(feature = "serde")]
    pub(crate) fn slots(&self) -> impl Iterator<Item = (u32, Option<&T>)> {
        self.slots
            .iter()
            .map(|slot| (slot.generation, slot.item.as_ref()))
    }

    /// The empty slots in the order the next inserts take them (last first).
    #[cfg(feature = "serde")]
    pub(crate) fn free_slots(&self) -> &[u32] {
        &self.free_slots
    }

    /// The arena of world `world` with `slots` (each slot's generation and item, in slot order)
    /// and the free list `free_slots`, as [`Arena::slots`] and [`Arena::free_slots`] gave them;
    /// checked as a decoded arena is. Describes the first broken invariant.
    #[cfg(feature = "serde")]
    pub(crate) fn from_slots(
        world: u32,
        slots: Vec<(u32, Option<T>)>,
        free_slots: Vec<u32>,
    ) -> Result<Self, String> {
        let slots: Vec<Slot<T>> = slots
            .into_iter()
            .map(|(generation, item)| Slot { generation, item })
            .collect();
        let len = slots.iter().filter(|slot| slot.item.is_some()).count();
        let arena = Self {
            world,
            slots,
            free_slots,
            len,
        };
        arena.check_decoded()?;
        Ok(arena)
    }

    /// Live items with their handles, mutably, in slot order.
    pub fn iter_mut(&mut self) -> impl Iterator<Item = (ArenaIndex, &mut T)> {
        let world = self.world;
        self.slots
            .iter_mut()
            .enumerate()
            .filter_map(move |(index, slot)| {
                let item = slot.item.as_mut()?;
                let index = ArenaIndex {
                    index: index as u32,
                    generation: slot.generation,
                    world,
                };
                Some((index, item))
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stale_handle_never_reaches_the_new_item_in_its_slot() {
        let mut arena = Arena::default();
        let first = arena.insert("first");
        assert_eq!(arena.remove(first), Some("first"));
        let second = arena.insert("second");
        assert_eq!(first.slot(), second.slot());
        assert_eq!(arena.get(first), None);
        assert_eq!(arena.remove(first), None);
        assert_eq!(arena.get(second), Some(&"second"));
        assert_eq!(arena.len(), 1);
    }

    #[test]
    fn a_handle_of_another_world_never_reaches_an_item() {
        let (mut ours, mut theirs) = (Arena::new(new_world()), Arena::new(new_world()));
        let mine = ours.insert("mine");
        let other = theirs.insert("other");
        assert_eq!(mine.slot(), other.slot());
        assert!(!ours.owns(other) && ours.owns(mine));
        assert_eq!(ours.get(other), None);
        assert_eq!(ours.get_mut(other), None);
        assert_eq!(ours.remove(other), None);
        assert_eq!(ours.get(mine), Some(&"mine"));
        assert_eq!(theirs.get(other), Some(&"other"));
        assert!(
            ours.clone().get(mine).is_some(),
            "a clone is the same world"
        );
    }

    #[test]
    fn iteration_runs_in_slot_order() {
        let mut arena = Arena::default();
        let handles: Vec<_> = (0..5).map(|value| arena.insert(value)).collect();
        arena.remove(handles[1]);
        let values: Vec<_> = arena.iter().map(|(_, value)| *value).collect();
        assert_eq!(values, [0, 2, 3, 4]);
    }
}
