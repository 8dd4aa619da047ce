//! The contact cache: this step's contacts, each with the impulses its points carried over from
//! the point with the same feature id in the previous step (warm starting).

use super::manifold::{Manifold, MAX_MANIFOLD_POINTS};
use crate::body::BodyHandle;

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

/// Impulses accumulated at one contact point over a step, N·s.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PointImpulse {
    /// Along the manifold normal; never negative (a contact only pushes).
    pub normal: f32,
    /// Along the two tangent directions.
    pub tangent: [f32; 2],
}

/// One manifold between two bodies with the impulses of its points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Which bodies and children touch.
    pub key: ContactKey,
    /// The geometry from the narrow phase.
    pub manifold: Manifold,
    /// `impulses[i]` belongs to `manifold.points()[i]`.
    pub impulses: [PointImpulse; MAX_MANIFOLD_POINTS],
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
            impulses: [PointImpulse::default(); MAX_MANIFOLD_POINTS],
        });
    }

    /// Sorts this step's contacts by key and gives each point the impulses of the previous
    /// step's point with the same key and feature id; unmatched points start from zero.
    pub fn finish_step(&mut self) {
        self.current.sort_unstable_by_key(|contact| contact.key);
        let mut previous = self.previous.iter().peekable();
        for contact in &mut self.current {
            while previous.next_if(|old| old.key < contact.key).is_some() {}
            let Some(old) = previous.next_if(|old| old.key == contact.key) else {
                continue;
            };
            for (point, impulse) in contact
                .manifold
                .points()
                .iter()
                .zip(contact.impulses.iter_mut())
            {
                if let Some(index) = old.manifold.points().iter().position(|p| p.id == point.id) {
                    *impulse = old.impulses[index];
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
    use crate::math::Vec3;

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
        for (index, impulse) in cache.contacts_mut()[0].impulses.iter_mut().enumerate() {
            impulse.normal = index as f32 + 1.0;
            impulse.tangent = [0.5, -0.5];
        }
        cache.contacts_mut()[1].impulses[0].normal = 9.0;

        cache.begin_step();
        cache.push(key(ground, box_one), manifold(&[4, 2, 7]));
        cache.push(key(box_one, box_two), manifold(&[5]));
        cache.finish_step();
        let contacts = cache.contacts();
        assert_eq!(contacts.len(), 2);
        let normals: Vec<f32> = contacts[0].impulses[..3].iter().map(|i| i.normal).collect();
        assert_eq!(normals, [4.0, 2.0, 0.0]);
        assert_eq!(contacts[0].impulses[0].tangent, [0.5, -0.5]);
        // The same id between other bodies does not inherit anything.
        assert_eq!(contacts[1].impulses[0], PointImpulse::default());
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
