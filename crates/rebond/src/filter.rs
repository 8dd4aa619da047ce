//! Collision filtering: which pairs of bodies interact at all.
//!
//! Each body has [`InteractionGroups`]: the groups it belongs to and the groups it interacts
//! with, as 32-bit masks. Two bodies interact when each one's memberships meet the other's
//! filter. On top of the groups, the world keeps a sorted list of pairs told to ignore each other
//! ([`World::set_pair_ignored`](crate::World::set_pair_ignored)). A pair that does not interact
//! never becomes a broad-phase pair, so the narrow phase never sees it; no contact, no sensor
//! overlap, no event.
//!
//! The children of a compound are colliders of their own ([`CompoundChild`]): within a pair of
//! bodies that interact, two colliders touch when neither is a sensor and their own groups (the
//! child's, else the body's) interact too.

use crate::body::{BodyHandle, RigidBody};
use crate::shape::{CompoundChild, Shape};

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

/// A body's colliders as the narrow phase and the sensor pass see them: which are sensors and
/// which groups each has. Collider `i` is child `i` of a compound, or the whole shape (0).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Colliders<'a> {
    children: &'a [CompoundChild],
    sensor: bool,
    groups: InteractionGroups,
}

impl<'a> Colliders<'a> {
    pub fn of(body: &'a RigidBody) -> Self {
        Self {
            children: match &body.shape {
                Shape::Compound(compound) => compound.children(),
                _ => &[],
            },
            sensor: body.sensor,
            groups: body.collision_groups,
        }
    }

    /// Whether collider `index` is a sensor: the body is, or the child says so.
    pub fn is_sensor(&self, index: u32) -> bool {
        self.sensor
            || self
                .children
                .get(index as usize)
                .is_some_and(|child| child.sensor == Some(true))
    }

    /// The groups of collider `index`: the child's own, else the body's.
    pub fn groups(&self, index: u32) -> InteractionGroups {
        self.children
            .get(index as usize)
            .and_then(|child| child.collision_groups)
            .unwrap_or(self.groups)
    }

    /// Whether the body is no sensor but some of its children are: its pairs then also go to the
    /// sensor pass.
    pub fn has_sensor_children(&self) -> bool {
        !self.sensor && self.children.iter().any(|child| child.sensor == Some(true))
    }

    /// Whether the pair needs the colliders' own flags looked at: some child of either has a
    /// sensor flag or groups of its own. Otherwise the bodies' test said it all.
    pub fn need_filtering(&self, other: &Colliders) -> bool {
        let own =
            |child: &CompoundChild| child.sensor.is_some() || child.collision_groups.is_some();
        self.children.iter().any(own) || other.children.iter().any(own)
    }

    /// Whether this body's collider `index` and `other`'s collider `other_index` make contacts:
    /// neither is a sensor and their groups interact.
    pub fn touch(&self, index: u32, other: &Colliders, other_index: u32) -> bool {
        !self.is_sensor(index)
            && !other.is_sensor(other_index)
            && self.sees(index, other, other_index)
    }

    /// Whether this body's sensor collider `index` reports `other`'s collider `other_index`: it
    /// is not a sensor and their groups interact.
    pub fn sees(&self, index: u32, other: &Colliders, other_index: u32) -> bool {
        !other.is_sensor(other_index)
            && self.groups(index).interacts_with(other.groups(other_index))
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
