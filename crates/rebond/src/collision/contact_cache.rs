//! The contact cache: this step's contacts, each with the impulses its points carried over from
//! the point with the same feature id in the previous step (warm starting), and the parked
//! contacts of sleeping bodies, which no step touches until one of their bodies wakes.

use std::ops::Range;

use super::manifold::{ContactPoint, Manifold, MAX_MANIFOLD_POINTS};
use super::manifold_frame::{CenterPose, ManifoldFrame, PlacedBody};
use super::mesh_contact::KeptSimplex;
use super::narrow_phase::{PartCache, PartContacts};
use crate::body::BodyHandle;
use crate::filter::Colliders;
use crate::hooks::ContactEdit;
#[cfg(feature = "serde")]
use crate::limits::MAX_SOLVER_IMPULSE;
use crate::material::Material;
use crate::math::{Pose, Vec3};
use crate::sorted::merge_into;

/// Names one contact: the two bodies (A before B) and the compound children involved (0 for a
/// shape that is not a compound). Ordered, so contacts sort deterministically.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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

/// One manifold between two bodies (or two children of compound bodies) with the impulses the
/// solver applied on it in the last step, N·s. Read it through its methods; its layout belongs to
/// the contact cache.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Contact {
    /// Which bodies and children touch.
    pub(crate) key: ContactKey,
    /// The geometry from the narrow phase.
    pub(crate) manifold: Manifold,
    /// `normal_impulses[i]` belongs to `manifold.points()[i]`; never negative.
    pub(crate) normal_impulses: [f32; MAX_MANIFOLD_POINTS],
    /// Friction impulse of the whole manifold, a world vector in the contact plane (kept as a
    /// vector so it survives a change of the solver's tangent basis).
    pub(crate) friction_impulse: Vec3,
    /// Angular friction impulse about the normal, N·m·s.
    pub(crate) twist_impulse: f32,
    /// Rolling resistance impulse, an angular impulse on body B (its opposite on A), a world
    /// vector in the contact plane, N·m·s (`solver/rolling.rs`).
    pub(crate) rolling_impulse: Vec3,
    /// The surfaces' friction and restitution combined by the world's rules; set by the world
    /// each step, once the contact is made.
    pub(crate) material: Material,
    /// The contact patch's mean distance from its centre under a uniform pressure (the lever
    /// arm of the spinning friction) over the points' root mean square distance from their
    /// centre; set by the world each step with the material
    /// (`solver::contact_model::patch_radius_ratio`).
    pub(crate) patch_radius_ratio: f32,
    /// Where the manifold was computed.
    pub(crate) frame: ManifoldFrame,
    /// Where the cache keeps what the query that computed the manifold left for the next one
    /// ([`PartCache`]); `None` when it left nothing. Kept aside, so that contacts without one stay
    /// small to copy and sort.
    part_cache: Option<u32>,
    /// Whether the narrow phase found the manifold this step, so that its impulses are still to
    /// be carried over by feature id; recycled and kept contacts bring theirs along.
    fresh: bool,
}

impl Contact {
    /// The two bodies, A then B (A's handle is the smaller).
    pub fn bodies(&self) -> (BodyHandle, BodyHandle) {
        (self.key.body_a, self.key.body_b)
    }

    /// The compound children of A and B that touch (0 for a body whose shape is not a compound).
    pub fn children(&self) -> (u32, u32) {
        (self.key.child_a, self.key.child_b)
    }

    /// The triangle of the body that is a triangle mesh or heightfield (A or B: two meshes never
    /// touch) the contact is on, as [`crate::shape::Shape::triangle`] numbers them; `None` between
    /// other shapes. A mesh manifold merged from several coplanar triangles of one material names
    /// the triangle of its deepest point. The contact's friction and restitution are that
    /// triangle's material's ([`crate::shape::TriMesh::with_materials`]).
    pub fn triangle(&self) -> Option<u32> {
        self.manifold.triangle
    }

    /// Unit world normal, from A toward B.
    pub fn normal(&self) -> Vec3 {
        self.manifold.normal
    }

    /// The contact points (at most [`MAX_MANIFOLD_POINTS`]), with their separations (negative
    /// when overlapping, positive for a speculative point still apart).
    pub fn points(&self) -> &[ContactPoint] {
        self.manifold.points()
    }

    /// The normal impulse on each point in the last step, N·s, never negative:
    /// `normal_impulses()[i]` belongs to `points()[i]`.
    pub fn normal_impulses(&self) -> &[f32] {
        &self.normal_impulses[..self.manifold.len()]
    }

    /// The friction impulse on the whole manifold in the last step, a world vector in the
    /// contact plane, N·s.
    pub fn friction_impulse(&self) -> Vec3 {
        self.friction_impulse
    }

    /// The twisting friction impulse about the normal in the last step, N·m·s.
    pub fn twist_impulse(&self) -> f32 {
        self.twist_impulse
    }

    /// The rolling resistance's angular impulse on body B in the last step (the opposite acts
    /// on body A), a world vector in the contact plane, N·m·s; zero without rolling resistance.
    pub fn rolling_impulse(&self) -> Vec3 {
        self.rolling_impulse
    }

    /// The contact's Coulomb friction coefficient: the two surfaces' combined by
    /// [`WorldSettings::friction_combine`](crate::WorldSettings::friction_combine).
    pub fn friction(&self) -> f32 {
        self.material.friction
    }

    /// The contact's restitution: the two surfaces' combined by
    /// [`WorldSettings::restitution_combine`](crate::WorldSettings::restitution_combine).
    pub fn restitution(&self) -> f32 {
        self.material.restitution
    }

    /// Keeps the points `kept[i]` is true for, in order, with their impulses and lever arms; a
    /// contact left with none holds no friction, twist or rolling impulse either, so the warm
    /// start pushes nothing.
    fn keep_points(&mut self, kept: [bool; MAX_MANIFOLD_POINTS]) {
        let mut count = 0;
        for (index, &keeps) in kept.iter().enumerate().take(self.manifold.len()) {
            if keeps {
                self.normal_impulses[count] = self.normal_impulses[index];
                self.frame.solver.arms[count] = self.frame.solver.arms[index];
                count += 1;
            }
        }
        let mut index = 0;
        self.manifold.retain(|_| {
            index += 1;
            kept[index - 1]
        });
        if count == 0 {
            self.friction_impulse = Vec3::ZERO;
            self.twist_impulse = 0.0;
            self.rolling_impulse = Vec3::ZERO;
        }
    }
}

/// A contact parked while its bodies sleep, with what its query left.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct ParkedContact {
    contact: Contact,
    part_cache: PartCache,
}

/// This step's contacts, sorted by key, and last step's, kept to warm-start from; and the parked
/// contacts, of pairs of which no body is awake.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContactCache {
    current: Vec<Contact>,
    /// Contacts of pairs of which no body is awake (asleep, or asleep against static), sorted by
    /// key: moved out of `current` whole when their bodies fall asleep and back when one wakes.
    parked: Vec<ParkedContact>,
    /// Scratch of [`park`](Self::park) and [`unpark`](Self::unpark): the contacts moving.
    moving_parked: Vec<ParkedContact>,
    moving_current: Vec<Contact>,
    previous: Vec<Contact>,
    /// Where in `previous` the last pair asked for ended: the world asks for pairs in key order
    /// (the broad phase's pairs are sorted), so the next one is found by walking on from there.
    previous_cursor: usize,
    /// Where in `previous` the last pair asked for started: the narrow phase asks again for the
    /// pair whose recycling just failed.
    previous_pair_start: usize,
    /// What the queries of this step's contacts left, and of last step's. Simplices' points and
    /// axes are in the shapes' own frames, which a body's shape never leaves: a shape never
    /// changes under its handle.
    part_caches: Vec<PartCache>,
    previous_part_caches: Vec<PartCache>,
    /// The triangle simplices of parts against meshes that [`PartCache::Triangles`] in
    /// `part_caches` and `previous_part_caches` point into, this step's and last step's.
    triangle_simplices: Vec<KeptSimplex>,
    previous_triangle_simplices: Vec<KeptSimplex>,
    /// The surface velocity of each of this step's contacts, by index, m/s (A's surface
    /// relative to B's, `hooks.rs`); empty while no contact of the step has one.
    #[cfg_attr(feature = "serde", serde(skip))]
    surface_velocities: Vec<Vec3>,
    /// The contacts the step's hooks changed, as they were found, until
    /// [`restore_edited`](Self::restore_edited) puts them back; empty between steps.
    #[cfg_attr(feature = "serde", serde(skip))]
    edited: Vec<(usize, Contact)>,
}

impl ContactCache {
    /// Starts a new step: this step's contacts become the previous ones and the list empties.
    /// Both buffers are reused, so a steady scene allocates nothing.
    pub fn begin_step(&mut self) {
        std::mem::swap(&mut self.current, &mut self.previous);
        self.current.clear();
        std::mem::swap(&mut self.part_caches, &mut self.previous_part_caches);
        self.part_caches.clear();
        std::mem::swap(
            &mut self.triangle_simplices,
            &mut self.previous_triangle_simplices,
        );
        self.triangle_simplices.clear();
        self.surface_velocities.clear();
        self.previous_cursor = 0;
        self.previous_pair_start = 0;
    }

    /// Adds a contact found this step by the narrow phase with the bodies' centres of mass at
    /// `pose_a` and `pose_b`, the query having left `part_cache`, with zero impulses until
    /// [`ContactCache::finish_step`].
    pub fn push(
        &mut self,
        key: ContactKey,
        manifold: Manifold,
        pose_a: &Pose,
        pose_b: &Pose,
        part_cache: PartCache,
    ) {
        let part_cache = keep_part_cache(&mut self.part_caches, part_cache);
        self.current.push(Contact {
            key,
            manifold,
            normal_impulses: [0.0; MAX_MANIFOLD_POINTS],
            friction_impulse: Vec3::ZERO,
            twist_impulse: 0.0,
            rolling_impulse: Vec3::ZERO,
            material: Material::NONE,
            patch_radius_ratio: 0.0,
            frame: ManifoldFrame::new(&manifold, &CenterPose::of(pose_a), &CenterPose::of(pose_b)),
            part_cache,
            fresh: true,
        });
    }

    /// The contacts between `body_a` and `body_b` (their centres of mass at `pose_a` and `pose_b`)
    /// the narrow phase is about to find, with last step's contacts of the pair to start GJK from.
    pub fn pair<'a>(
        &'a mut self,
        body_a: BodyHandle,
        body_b: BodyHandle,
        pose_a: &'a Pose,
        pose_b: &'a Pose,
    ) -> PairContacts<'a> {
        let previous = self.previous_of_pair(body_a, body_b);
        PairContacts {
            cache: self,
            bodies: (body_a, body_b),
            poses: (pose_a, pose_b),
            previous,
            colliders: None,
        }
    }

    /// Rebuilds last step's contacts between `body_a` and `body_b` (their centres of mass now at
    /// `pose_a` and `pose_b`) instead of running the narrow phase, if there were any and B has
    /// barely moved relative to A since they were computed ([`RECYCLE_MAX_TRANSLATION`], 1°).
    /// Returns whether it did.
    ///
    /// [`RECYCLE_MAX_TRANSLATION`]: super::manifold_frame::RECYCLE_MAX_TRANSLATION
    pub fn recycle(
        &mut self,
        body_a: BodyHandle,
        body_b: BodyHandle,
        pose_a: &Pose,
        pose_b: &Pose,
    ) -> bool {
        let previous = self.previous_of_pair(body_a, body_b);
        let previous = &self.previous[previous];
        if previous.is_empty() {
            return false;
        }
        let (a, b) = (CenterPose::of(pose_a), CenterPose::of(pose_b));
        let relative = a.relative(&b);
        if !previous
            .iter()
            .all(|contact| contact.frame.still_fits(&relative))
        {
            return false;
        }
        let (placed_a, placed_b) = (PlacedBody::new(&a), PlacedBody::new(&b));
        let start = self.current.len();
        self.current.extend_from_slice(previous);
        for contact in &mut self.current[start..] {
            contact
                .frame
                .rebuild(&mut contact.manifold, &placed_a, &placed_b);
            carry_part_cache(
                contact,
                (
                    &self.previous_part_caches,
                    &self.previous_triangle_simplices,
                ),
                (&mut self.part_caches, &mut self.triangle_simplices),
            );
        }
        true
    }

    /// Keeps last step's contacts between `body_a` and `body_b` unchanged, impulses included:
    /// for pairs of bodies that did not move (asleep, or asleep against static), whose contacts
    /// must be ready the moment they wake.
    pub fn keep_previous(&mut self, body_a: BodyHandle, body_b: BodyHandle) {
        let previous = self.previous_of_pair(body_a, body_b);
        let start = self.current.len();
        self.current.extend_from_slice(&self.previous[previous]);
        for contact in &mut self.current[start..] {
            carry_part_cache(
                contact,
                (
                    &self.previous_part_caches,
                    &self.previous_triangle_simplices,
                ),
                (&mut self.part_caches, &mut self.triangle_simplices),
            );
        }
    }

    /// Where last step's contacts between `body_a` and `body_b` lie in `previous`, which is
    /// sorted by key. Walks on from the pair asked for before, which costs a few comparisons when
    /// pairs are asked for in key order; a pair asked for again is remembered, and one asked for
    /// out of order is found by binary search.
    fn previous_of_pair(&mut self, body_a: BodyHandle, body_b: BodyHandle) -> Range<usize> {
        let pair = |contact: &Contact| (contact.key.body_a, contact.key.body_b);
        let wanted = (body_a, body_b);
        let previous = &self.previous;
        let mut start = self.previous_cursor.min(previous.len());
        if start > 0 && pair(&previous[start - 1]) >= wanted {
            // The contact before the cursor ends the range last asked for when it was not empty.
            if self.previous_pair_start < start && pair(&previous[start - 1]) == wanted {
                return self.previous_pair_start..start;
            }
            start = previous.partition_point(|contact| pair(contact) < wanted);
        } else {
            while previous
                .get(start)
                .is_some_and(|contact| pair(contact) < wanted)
            {
                start += 1;
            }
        }
        let mut end = start;
        while previous
            .get(end)
            .is_some_and(|contact| pair(contact) == wanted)
        {
            end += 1;
        }
        self.previous_cursor = end;
        self.previous_pair_start = start;
        start..end
    }

    /// Sorts this step's contacts by key and gives each point the narrow phase found the normal
    /// impulse of the previous step's point with the same key and feature id (unmatched points
    /// start from zero), and each such contact the friction, twist and rolling impulses of the
    /// previous contact with its key.
    pub fn finish_step(&mut self) {
        self.current.sort_unstable_by_key(|contact| contact.key);
        let mut previous = self.previous.iter().peekable();
        for contact in self.current.iter_mut().filter(|contact| contact.fresh) {
            contact.fresh = false;
            while previous.next_if(|old| old.key < contact.key).is_some() {}
            let Some(old) = previous.next_if(|old| old.key == contact.key) else {
                continue;
            };
            contact.friction_impulse = old.friction_impulse;
            contact.twist_impulse = old.twist_impulse;
            contact.rolling_impulse = old.rolling_impulse;
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

    /// Checks decoded contacts: this step's and the parked ones sorted by key, of live bodies
    /// (`is_live`), with at most [`MAX_MANIFOLD_POINTS`] points, finite values and impulses a
    /// step can have accumulated. Describes the first broken invariant.
    #[cfg(feature = "serde")]
    pub(crate) fn check_decoded(&self, is_live: impl Fn(BodyHandle) -> bool) -> Result<(), String> {
        let parked = self.parked.iter().map(|parked| &parked.contact);
        for contacts in [self.current.iter().collect::<Vec<_>>(), parked.collect()] {
            if !contacts.windows(2).all(|two| two[0].key <= two[1].key) {
                return Err("contacts are out of order".to_owned());
            }
            for contact in contacts {
                let manifold = &contact.manifold;
                let finite = manifold.normal.is_finite()
                    && contact
                        .normal_impulses
                        .iter()
                        .all(|impulse| (0.0..=MAX_SOLVER_IMPULSE).contains(impulse))
                    && contact.friction_impulse.abs().max_element() <= 2.0 * MAX_SOLVER_IMPULSE
                    && contact.twist_impulse.abs() <= MAX_SOLVER_IMPULSE
                    && contact.rolling_impulse.length() <= MAX_SOLVER_IMPULSE
                    && contact.patch_radius_ratio.is_finite()
                    && contact.frame.is_finite()
                    && manifold.len() <= MAX_MANIFOLD_POINTS
                    && manifold
                        .points()
                        .iter()
                        .all(|point| point.position.is_finite() && point.separation.is_finite());
                if !(finite && is_live(contact.key.body_a) && is_live(contact.key.body_b)) {
                    return Err("a contact names a missing body or holds a bad value".to_owned());
                }
            }
        }
        Ok(())
    }

    /// This step's contacts, sorted by key.
    pub fn contacts(&self) -> &[Contact] {
        &self.current
    }

    /// This step's contacts, for the solver to store its impulses in.
    pub fn contacts_mut(&mut self) -> &mut [Contact] {
        &mut self.current
    }

    /// The surface velocity of this step's contact `index`, m/s: A's surface relative to B's,
    /// which friction drives B's contact point toward, relative to A's.
    pub fn surface_velocity(&self, index: usize) -> Vec3 {
        self.surface_velocities
            .get(index)
            .copied()
            .unwrap_or_default()
    }

    /// Whether a contact of this step has a surface velocity.
    pub fn has_surface_velocities(&self) -> bool {
        !self.surface_velocities.is_empty()
    }

    /// Gives this step's contact `index` what a hook changed of it: its surface velocity, and
    /// for a changed material or normal or points switched off, a changed copy for the solve and
    /// the events, the contact as found kept aside for [`restore_edited`](Self::restore_edited).
    /// The indices are the solver's: nothing adds or removes a contact from the hooks to the
    /// restore.
    pub(crate) fn apply_edit(&mut self, index: usize, edit: &ContactEdit) {
        let count = self.current.len();
        let Some(contact) = self.current.get_mut(index) else {
            return;
        };
        if edit.surface_velocity != Vec3::ZERO {
            if self.surface_velocities.len() < count {
                self.surface_velocities.resize(count, Vec3::ZERO);
            }
            self.surface_velocities[index] = edit.surface_velocity;
        }
        if edit.material == contact.material && edit.normal.is_none() && edit.kept.is_none() {
            return;
        }
        self.edited.push((index, *contact));
        contact.material = edit.material;
        if let Some(normal) = edit.normal {
            contact.manifold.normal = normal;
            contact.frame.solver.normal = normal;
        }
        if let Some(kept) = edit.kept {
            contact.keep_points(kept);
        }
    }

    /// Puts back the contacts the step's hooks changed, as they were found, with the impulses
    /// the solve gave their changed copies, each point's normal impulse by feature id (zero on a
    /// point switched off). The next step starts from the contacts as found.
    pub fn restore_edited(&mut self) {
        for (index, mut found) in self.edited.drain(..) {
            let solved = &self.current[index];
            let points = found.manifold.points().iter();
            for (point, impulse) in points.zip(&mut found.normal_impulses) {
                let same = solved
                    .manifold
                    .points()
                    .iter()
                    .position(|p| p.id == point.id);
                *impulse = same.map_or(0.0, |same| solved.normal_impulses[same]);
            }
            found.friction_impulse = solved.friction_impulse;
            found.twist_impulse = solved.twist_impulse;
            found.rolling_impulse = solved.rolling_impulse;
            self.current[index] = found;
        }
    }

    /// Parks this step's contacts of the pairs `(a, b)` for which `parks(a, b)` is true: they
    /// leave [`contacts`](Self::contacts), unchanged, impulses and query caches included, until
    /// [`unpark`](Self::unpark) brings them back.
    pub fn park(&mut self, mut parks: impl FnMut(BodyHandle, BodyHandle) -> bool) {
        let Self {
            current,
            parked,
            moving_parked,
            part_caches,
            ..
        } = self;
        moving_parked.clear();
        current.retain(|contact| {
            let moves = parks(contact.key.body_a, contact.key.body_b);
            if moves {
                let part_cache = match contact
                    .part_cache
                    .and_then(|index| part_caches.get(index as usize))
                {
                    // Triangle simplices live in a list rebuilt every step: a parked contact
                    // wakes cold against its mesh.
                    Some(PartCache::Triangles { .. }) | None => PartCache::Cold,
                    Some(part_cache) => *part_cache,
                };
                moving_parked.push(ParkedContact {
                    contact: *contact,
                    part_cache,
                });
            }
            !moves
        });
        merge_into(parked, moving_parked, |parked| parked.contact.key);
    }

    /// Brings the parked contacts of the pairs `(a, b)` for which `wakes(a, b)` is true back into
    /// [`contacts`](Self::contacts), in key order, as they were parked.
    pub fn unpark(&mut self, mut wakes: impl FnMut(BodyHandle, BodyHandle) -> bool) {
        let Self {
            current,
            parked,
            moving_current,
            part_caches,
            ..
        } = self;
        moving_current.clear();
        parked.retain(|parked| {
            let moves = wakes(parked.contact.key.body_a, parked.contact.key.body_b);
            if moves {
                let mut contact = parked.contact;
                contact.part_cache = keep_part_cache(part_caches, parked.part_cache);
                moving_current.push(contact);
            }
            !moves
        });
        merge_into(current, moving_current, |contact| contact.key);
    }

    /// The parked contacts, sorted by key.
    pub fn parked(&self) -> impl ExactSizeIterator<Item = &Contact> {
        self.parked.iter().map(|parked| &parked.contact)
    }

    /// Forgets every contact of `body` (it was removed), so no impulse reaches a later body: those
    /// of this step, as the world brings a removed body's parked contacts back first.
    pub fn remove_body(&mut self, body: BodyHandle) {
        self.retain_pairs(|body_a, body_b| body_a != body && body_b != body);
    }

    /// Keeps only this step's contacts between bodies `(a, b)` for which `keep(a, b)` is true.
    pub fn retain_pairs(&mut self, mut keep: impl FnMut(BodyHandle, BodyHandle) -> bool) {
        self.current
            .retain(|contact| keep(contact.key.body_a, contact.key.body_b));
    }
}

/// Keeps `part_cache` in `part_caches` unless it is cold, and returns where.
fn keep_part_cache(part_caches: &mut Vec<PartCache>, part_cache: PartCache) -> Option<u32> {
    if part_cache == PartCache::Cold {
        return None;
    }
    let index = u32::try_from(part_caches.len()).ok()?;
    part_caches.push(part_cache);
    Some(index)
}

/// Keeps the triangle simplices `kept` at the end of `triangle_simplices`, and returns the
/// part cache naming them (cold when there are none).
fn keep_triangle_simplices(
    triangle_simplices: &mut Vec<KeptSimplex>,
    kept: &[KeptSimplex],
) -> PartCache {
    let (Ok(start), Ok(len)) = (
        u32::try_from(triangle_simplices.len()),
        u32::try_from(kept.len()),
    ) else {
        return PartCache::Cold;
    };
    if len == 0 {
        return PartCache::Cold;
    }
    triangle_simplices.extend_from_slice(kept);
    PartCache::Triangles { start, len }
}

/// The triangle simplices a [`PartCache::Triangles`] names in `triangle_simplices`; none for
/// another cache, or a range out of the list (of a decoded state).
fn triangle_simplices_of(
    part_cache: PartCache,
    triangle_simplices: &[KeptSimplex],
) -> &[KeptSimplex] {
    let PartCache::Triangles { start, len } = part_cache else {
        return &[];
    };
    let start = start as usize;
    triangle_simplices
        .get(start..start.saturating_add(len as usize))
        .unwrap_or_default()
}

/// Moves the part cache of `contact`, carried over from last step, from `previous` (part caches
/// and triangle simplices) to `current`.
fn carry_part_cache(
    contact: &mut Contact,
    previous: (&[PartCache], &[KeptSimplex]),
    current: (&mut Vec<PartCache>, &mut Vec<KeptSimplex>),
) {
    if let Some(index) = contact.part_cache {
        let kept = previous.0.get(index as usize).copied().unwrap_or_default();
        let kept = match kept {
            PartCache::Triangles { .. } => {
                keep_triangle_simplices(current.1, triangle_simplices_of(kept, previous.1))
            }
            _ => kept,
        };
        contact.part_cache = keep_part_cache(current.0, kept);
    }
}

/// The contacts of one pair of bodies as the narrow phase finds them (see [`ContactCache::pair`]).
pub struct PairContacts<'a> {
    cache: &'a mut ContactCache,
    bodies: (BodyHandle, BodyHandle),
    poses: (&'a Pose, &'a Pose),
    /// The pair's contacts of last step not yet passed, sorted by children.
    previous: Range<usize>,
    /// The colliders of A and B, when some have a sensor flag or groups of their own; `None`
    /// when every collider pair of the two bodies touches.
    colliders: Option<(Colliders<'a>, Colliders<'a>)>,
}

impl<'a> PairContacts<'a> {
    /// The same pair, whose colliders touch only as `colliders_a` and `colliders_b` say.
    pub(crate) fn filtered(self, colliders_a: Colliders<'a>, colliders_b: Colliders<'a>) -> Self {
        Self {
            colliders: Some((colliders_a, colliders_b)),
            ..self
        }
    }
}

impl PartContacts for PairContacts<'_> {
    /// The parts are asked for in key order, so the search walks on from the last one asked.
    fn previous_cache(&mut self, child_a: u32, child_b: u32) -> PartCache {
        let previous = &self.cache.previous[self.previous.clone()];
        let children = |contact: &Contact| (contact.key.child_a, contact.key.child_b);
        let passed = previous
            .iter()
            .take_while(|contact| children(contact) < (child_a, child_b))
            .count();
        let kept = previous
            .get(passed)
            .filter(|contact| children(contact) == (child_a, child_b))
            .and_then(|contact| contact.part_cache)
            .and_then(|index| self.cache.previous_part_caches.get(index as usize))
            .copied()
            .unwrap_or_default();
        self.previous.start += passed;
        kept
    }

    fn previous_triangle_simplices(
        &mut self,
        child_a: u32,
        child_b: u32,
        simplices: &mut Vec<KeptSimplex>,
    ) {
        let kept = self.previous_cache(child_a, child_b);
        simplices.clear();
        simplices.extend_from_slice(triangle_simplices_of(
            kept,
            &self.cache.previous_triangle_simplices,
        ));
    }

    fn add_on_mesh(
        &mut self,
        child_a: u32,
        child_b: u32,
        manifold: Manifold,
        simplices: &[KeptSimplex],
    ) {
        let part_cache = keep_triangle_simplices(&mut self.cache.triangle_simplices, simplices);
        self.add(child_a, child_b, manifold, part_cache);
    }

    fn add(&mut self, child_a: u32, child_b: u32, manifold: Manifold, part_cache: PartCache) {
        let key = ContactKey {
            body_a: self.bodies.0,
            body_b: self.bodies.1,
            child_a,
            child_b,
        };
        let (pose_a, pose_b) = self.poses;
        self.cache.push(key, manifold, pose_a, pose_b, part_cache);
    }

    fn colliders_touch(&self, collider_a: u32, collider_b: u32) -> bool {
        self.colliders
            .is_none_or(|(a, b)| a.touch(collider_a, &b, collider_b))
    }
}

#[cfg(test)]
mod tests;
