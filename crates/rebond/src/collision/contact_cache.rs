//! The contact cache: this step's contacts, each with the impulses its points carried over from
//! the point with the same feature id in the previous step (warm starting).

use super::manifold::{Manifold, MAX_MANIFOLD_POINTS};
use crate::body::BodyHandle;
use crate::math::Vec3;

/// Names one contact: the two bodies (A before B) and the compound children involved (0 for a
/// shape that is not a compound). Ordered, so contacts sort deterministically.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ContactKey {
    /// Body A.
    pub body_a: BodyHandle,
    /// Body B.
    pub body_b: BodyHandle,
    /// Child of A's compound, or 0.
    pub child_a: u32,
    /// Child of B's compound, or 0.
    pub child_b: u32,
}

/// One manifold between two bodies with the impulses the solver accumulated on it, N·s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Which bodies and children touch.
    pub key: ContactKey,
    /// The geometry from the narrow phase.
    pub manifold: Manifold,
    /// `normal_impulses[i]` belongs to `manifold.points()[i]`; never negative.
    pub normal_impulses: [f32; MAX_MANIFOLD_POINTS],
    /// Friction impulse of the whole manifold, a world vector in the contact plane (kept as a
    /// vector so it survives a change of the solver's tangent basis).
    pub friction_impulse: Vec3,
    /// Angular friction impulse about the normal, N·m·s.
    pub twist_impulse: f32,
}

/// This step's contacts, sorted by key, and last step's, kept to warm-start from.
#[derive(Debug, Clone, Default)]
pub struct ContactCache {
    current: Vec<Contact>,
    previous: Vec<Contact>,
}

impl ContactCache {
    /// Starts a new step: this step's contacts become the previous ones and the list empties.
    /// Both buffers are reused, so a steady scene allocates nothing.
    pub fn begin_step(&mut self) {
        std::mem::swap(&mut self.current, &mut self.previous);
        self.current.clear();
    }

    /// Adds a contact found this step, with zero impulses until [`ContactCache::finish_step`].
    pub fn push(&mut self, key: ContactKey, manifold: Manifold) {
        self.current.push(Contact {
            key,
            manifold,
            normal_impulses: [0.0; MAX_MANIFOLD_POINTS],
            friction_impulse: Vec3::ZERO,
            twist_impulse: 0.0,
        });
    }

    /// Keeps last step's contacts between `body_a` and `body_b` unchanged, impulses included:
    /// for pairs of bodies that did not move (asleep, or asleep against static), whose contacts
    /// must be ready the moment they wake.
    pub fn keep_previous(&mut self, body_a: BodyHandle, body_b: BodyHandle) {
        let start = self
            .previous
            .partition_point(|contact| (contact.key.body_a, contact.key.body_b) < (body_a, body_b));
        let kept = self.previous[start..]
            .iter()
            .take_while(|contact| contact.key.body_a == body_a && contact.key.body_b == body_b);
        self.current.extend(kept);
    }

    /// Sorts this step's contacts by key and gives each point the normal impulse of the previous
    /// step's point with the same key and feature id (unmatched points start from zero), and
    /// each contact the friction and twist impulses of the previous contact with its key.
    pub fn finish_step(&mut self) {
        self.current.sort_unstable_by_key(|contact| contact.key);
        let mut previous = self.previous.iter().peekable();
        for contact in &mut self.current {
            while previous.next_if(|old| old.key < contact.key).is_some() {}
            let Some(old) = previous.next_if(|old| old.key == contact.key) else {
                continue;
            };
            contact.friction_impulse = old.friction_impulse;
            contact.twist_impulse = old.twist_impulse;
            for (point, impulse) in contact
                .manifold
                .points()
                .iter()
                .zip(contact.normal_impulses.iter_mut())
            {
                if let Some(index) = old.manifold.points().iter().position(|p| p.id == point.id) {
                    *impulse = old.normal_impulses[index];
                }
            }
        }
    }

    /// This step's contacts, sorted by key.
    pub fn contacts(&self) -> &[Contact] {
        &self.current
    }

    /// This step's contacts, for the solver to store its impulses in.
    pub fn contacts_mut(&mut self) -> &mut [Contact] {
        &mut self.current
    }

    /// Forgets every contact of `body` (it was removed), so no impulse reaches a later body.
    pub fn remove_body(&mut self, body: BodyHandle) {
        self.current
            .retain(|contact| contact.key.body_a != body && contact.key.body_b != body);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arena::Arena;
    use crate::collision::manifold::ContactPoint;

    fn handles() -> (BodyHandle, BodyHandle, BodyHandle) {
        let mut arena = Arena::default();
        (
            BodyHandle(arena.insert(())),
            BodyHandle(arena.insert(())),
            BodyHandle(arena.insert(())),
        )
    }

    fn manifold(ids: &[u32]) -> Manifold {
        let mut manifold = Manifold::new(Vec3::Y);
        for &id in ids {
            manifold.push(ContactPoint {
                position: Vec3::ZERO,
                separation: -0.01,
                id,
            });
        }
        manifold
    }

    fn key(body_a: BodyHandle, body_b: BodyHandle) -> ContactKey {
        ContactKey {
            body_a,
            body_b,
            child_a: 0,
            child_b: 0,
        }
    }

    #[test]
    fn impulses_follow_feature_ids_from_step_to_step() {
        let (ground, box_one, box_two) = handles();
        let mut cache = ContactCache::default();
        cache.begin_step();
        cache.push(key(ground, box_two), manifold(&[5]));
        cache.push(key(ground, box_one), manifold(&[1, 2, 3, 4]));
        cache.finish_step();
        assert_eq!(cache.contacts()[0].key, key(ground, box_one));
        for (index, impulse) in cache.contacts_mut()[0]
            .normal_impulses
            .iter_mut()
            .enumerate()
        {
            *impulse = index as f32 + 1.0;
        }
        cache.contacts_mut()[0].friction_impulse = Vec3::new(0.5, 0.0, -0.5);
        cache.contacts_mut()[1].normal_impulses[0] = 9.0;

        cache.begin_step();
        cache.push(key(ground, box_one), manifold(&[4, 2, 7]));
        cache.push(key(box_one, box_two), manifold(&[5]));
        cache.finish_step();
        let contacts = cache.contacts();
        assert_eq!(contacts.len(), 2);
        assert_eq!(contacts[0].normal_impulses[..3], [4.0, 2.0, 0.0]);
        assert_eq!(contacts[0].friction_impulse, Vec3::new(0.5, 0.0, -0.5));
        // The same id between other bodies does not inherit anything.
        assert_eq!(contacts[1].normal_impulses[0], 0.0);
    }

    #[test]
    fn removed_bodies_leave_no_contact_behind() {
        let (ground, box_one, box_two) = handles();
        let mut cache = ContactCache::default();
        cache.begin_step();
        cache.push(key(ground, box_one), manifold(&[1]));
        cache.push(key(ground, box_two), manifold(&[1]));
        cache.finish_step();
        cache.remove_body(box_one);
        assert_eq!(cache.contacts().len(), 1);
        assert_eq!(cache.contacts()[0].key.body_b, box_two);
    }
}
