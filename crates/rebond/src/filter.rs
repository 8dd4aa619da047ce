//! Collision filtering: which pairs of bodies interact at all.
//!
//! Each body has [`InteractionGroups`]: the groups it belongs to and the groups it interacts
//! with, as 32-bit masks. Two bodies interact when each one's memberships meet the other's
//! filter. On top of the groups, the world keeps a sorted list of pairs told to ignore each other
//! ([`World::set_pair_ignored`](crate::World::set_pair_ignored)). A pair that does not interact
//! never becomes a broad-phase pair, so the narrow phase never sees it; no contact, no sensor
//! overlap, no event.

use crate::body::BodyHandle;

/// Group masks of a body, as in Rapier: bit `i` of `memberships` says the body is in group `i`,
/// bit `i` of `filter` that it interacts with bodies of group `i`. The default is in every group
/// and interacts with every group.
///
/// ```
/// use rebond::InteractionGroups;
///
/// let player = InteractionGroups::new(0b01, 0b10);
/// let wall = InteractionGroups::new(0b10, 0b01);
/// let ghost = InteractionGroups::new(0b100, 0);
/// assert!(player.interacts_with(wall));
/// assert!(!ghost.interacts_with(player));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct InteractionGroups {
    /// The groups the body is in, one bit each.
    pub memberships: u32,
    /// The groups the body interacts with, one bit each.
    pub filter: u32,
}

impl InteractionGroups {
    /// In every group, interacting with every group (the default).
    pub const ALL: Self = Self::new(u32::MAX, u32::MAX);
    /// In no group, interacting with nothing.
    pub const NONE: Self = Self::new(0, 0);

    /// Groups with the given membership and filter masks.
    pub const fn new(memberships: u32, filter: u32) -> Self {
        Self {
            memberships,
            filter,
        }
    }

    /// Whether two bodies with these groups interact:
    /// `(a.memberships & b.filter) ≠ 0 and (b.memberships & a.filter) ≠ 0`.
    pub const fn interacts_with(self, other: Self) -> bool {
        self.memberships & other.filter != 0 && other.memberships & self.filter != 0
    }
}

impl Default for InteractionGroups {
    fn default() -> Self {
        Self::ALL
    }
}

/// Pairs of bodies told to ignore each other, smaller handle first, sorted, each once.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct IgnoredPairs {
    pairs: Vec<(BodyHandle, BodyHandle)>,
}

impl IgnoredPairs {
    /// Adds or removes the pair `{a, b}`; returns whether the list changed.
    pub fn set(&mut self, a: BodyHandle, b: BodyHandle, ignored: bool) -> bool {
        let pair = ordered(a, b);
        match (self.pairs.binary_search(&pair), ignored) {
            (Err(index), true) => self.pairs.insert(index, pair),
            (Ok(index), false) => {
                self.pairs.remove(index);
            }
            _ => return false,
        }
        true
    }

    /// Whether the pair `{a, b}` is ignored.
    pub fn contains(&self, a: BodyHandle, b: BodyHandle) -> bool {
        !self.pairs.is_empty() && self.pairs.binary_search(&ordered(a, b)).is_ok()
    }

    /// Every pair, smaller handle first, sorted.
    #[cfg(feature = "serde")]
    pub fn pairs(&self) -> &[(BodyHandle, BodyHandle)] {
        &self.pairs
    }

    /// Forgets every pair of `body` (it was removed).
    pub fn remove_body(&mut self, body: BodyHandle) {
        self.pairs.retain(|&(a, b)| a != body && b != body);
    }
}

/// The two handles, smaller first.
pub(crate) fn ordered(a: BodyHandle, b: BodyHandle) -> (BodyHandle, BodyHandle) {
    (a.min(b), a.max(b))
}
