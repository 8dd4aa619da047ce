//! A generational arena: items in one contiguous vector, named by (index, generation) handles so a
//! handle to a removed item never reaches the item that later takes its slot.

/// A slot index plus the generation the slot had when the item was inserted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ArenaIndex {
    index: u32,
    generation: u32,
}

impl ArenaIndex {
    /// Position of the slot in the arena's storage; stable for the item's lifetime.
    pub fn slot(&self) -> usize {
        self.index as usize
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
    slots: Vec<Slot<T>>,
    free_slots: Vec<u32>,
    len: usize,
}

impl<T> Default for Arena<T> {
    fn default() -> Self {
        Self {
            slots: Vec::new(),
            free_slots: Vec::new(),
            len: 0,
        }
    }
}

impl<T> Arena<T> {
    /// Stores `item` in the most recently freed slot, or a new one, and returns its handle.
    pub fn insert(&mut self, item: T) -> ArenaIndex {
        self.len += 1;
        if let Some(index) = self.free_slots.pop() {
            let slot = &mut self.slots[index as usize];
            slot.item = Some(item);
            return ArenaIndex {
                index,
                generation: slot.generation,
            };
        }
        let index = u32::try_from(self.slots.len()).unwrap_or(u32::MAX);
        self.slots.push(Slot {
            generation: 0,
            item: Some(item),
        });
        ArenaIndex {
            index,
            generation: 0,
        }
    }

    /// Removes and returns the item, or `None` if the handle is stale.
    pub fn remove(&mut self, handle: ArenaIndex) -> Option<T> {
        let slot = self.slots.get_mut(handle.slot())?;
        if slot.generation != handle.generation {
            return None;
        }
        let item = slot.item.take()?;
        slot.generation = slot.generation.wrapping_add(1);
        self.free_slots.push(handle.index);
        self.len -= 1;
        Some(item)
    }

    /// The item behind `handle`, unless it was removed.
    pub fn get(&self, handle: ArenaIndex) -> Option<&T> {
        self.slots
            .get(handle.slot())
            .filter(|slot| slot.generation == handle.generation)
            .and_then(|slot| slot.item.as_ref())
    }

    /// The item behind `handle`, mutably, unless it was removed.
    pub fn get_mut(&mut self, handle: ArenaIndex) -> Option<&mut T> {
        self.slots
            .get_mut(handle.slot())
            .filter(|slot| slot.generation == handle.generation)
            .and_then(|slot| slot.item.as_mut())
    }

    /// The live item in storage slot `slot`, with its handle.
    pub fn at_slot(&self, slot: usize) -> Option<(ArenaIndex, &T)> {
        let entry = self.slots.get(slot)?;
        let item = entry.item.as_ref()?;
        let index = ArenaIndex {
            index: slot as u32,
            generation: entry.generation,
        };
        Some((index, item))
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
            slot.item.as_ref().map(|item| {
                (
                    ArenaIndex {
                        index: index as u32,
                        generation: slot.generation,
                    },
                    item,
                )
            })
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

    /// Live items with their handles, mutably, in slot order.
    pub fn iter_mut(&mut self) -> impl Iterator<Item = (ArenaIndex, &mut T)> {
        self.slots
            .iter_mut()
            .enumerate()
            .filter_map(|(index, slot)| {
                let generation = slot.generation;
                slot.item.as_mut().map(|item| {
                    (
                        ArenaIndex {
                            index: index as u32,
                            generation,
                        },
                        item,
                    )
                })
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
    fn iteration_runs_in_slot_order() {
        let mut arena = Arena::default();
        let handles: Vec<_> = (0..5).map(|value| arena.insert(value)).collect();
        arena.remove(handles[1]);
        let values: Vec<_> = arena.iter().map(|(_, value)| *value).collect();
        assert_eq!(values, [0, 2, 3, 4]);
    }
}
