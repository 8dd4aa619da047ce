//! The contact cache: contacts kept, recycled, parked and woken across steps.

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
    cache.push(
        key(ground, box_two),
        manifold(&[5]),
        &Pose::IDENTITY,
        &Pose::IDENTITY,
        PartCache::Cold,
    );
    cache.push(
        key(ground, box_one),
        manifold(&[1, 2, 3, 4]),
        &Pose::IDENTITY,
        &Pose::IDENTITY,
        PartCache::Cold,
    );
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
    cache.push(
        key(ground, box_one),
        manifold(&[4, 2, 7]),
        &Pose::IDENTITY,
        &Pose::IDENTITY,
        PartCache::Cold,
    );
    cache.push(
        key(box_one, box_two),
        manifold(&[5]),
        &Pose::IDENTITY,
        &Pose::IDENTITY,
        PartCache::Cold,
    );
    cache.finish_step();
    let contacts = cache.contacts();
    assert_eq!(contacts.len(), 2);
    assert_eq!(contacts[0].normal_impulses[..3], [4.0, 2.0, 0.0]);
    assert_eq!(contacts[0].friction_impulse, Vec3::new(0.5, 0.0, -0.5));
    // The same id between other bodies does not inherit anything.
    assert_eq!(contacts[1].normal_impulses[0], 0.0);
}

/// Pairs asked for in key order are found by walking on, a pair asked for again from memory,
/// and out of order by binary search: either way each gets exactly its own contacts.
#[test]
fn previous_contacts_are_found_in_and_out_of_order() {
    let (ground, box_one, box_two) = handles();
    let mut cache = ContactCache::default();
    cache.begin_step();
    for (a, b, ids) in [
        (ground, box_one, &[1, 2][..]),
        (ground, box_two, &[3]),
        (box_one, box_two, &[4, 5, 6]),
    ] {
        cache.push(
            key(a, b),
            manifold(ids),
            &Pose::IDENTITY,
            &Pose::IDENTITY,
            PartCache::Cold,
        );
    }
    cache.finish_step();
    let kept_in_order = |cache: &mut ContactCache, pairs: &[(BodyHandle, BodyHandle)]| {
        cache.begin_step();
        let counts: Vec<usize> = pairs
            .iter()
            .map(|&(a, b)| {
                let before = cache.contacts().len();
                cache.keep_previous(a, b);
                cache.contacts()[before..]
                    .iter()
                    .map(|contact| contact.manifold.points().len())
                    .sum()
            })
            .collect();
        cache.finish_step();
        counts
    };
    let all = [(ground, box_one), (ground, box_two), (box_one, box_two)];
    assert_eq!(kept_in_order(&mut cache, &all), [2, 1, 3]);
    let shuffled = [
        (box_one, box_two),
        (box_one, box_two),
        (ground, box_two),
        (box_two, ground),
        (ground, box_one),
        (ground, box_one),
    ];
    assert_eq!(kept_in_order(&mut cache, &shuffled), [3, 3, 1, 0, 2, 2]);
}

/// Each pair of compound parts gets back the simplex it left, through recycling too, and a
/// pair of parts with none starts cold.
#[test]
fn simplices_come_back_to_their_own_parts() {
    use crate::collision::gjk::{Simplex, SimplexCache, SupportPoint};
    use crate::collision::{PosedCore, RelativeCore};
    use crate::shape::Shape;

    let (ground, body, _) = handles();
    let shape = Shape::sphere(1.0).unwrap();
    let placed = RelativeCore::new(&PosedCore::new(&shape, &Pose::IDENTITY), &Pose::IDENTITY);
    let simplex_at = |x: f32| {
        let w = Vec3::new(x, 0.0, 0.0);
        let (simplex, _) = Simplex::reduced(&[SupportPoint {
            a: w,
            b: Vec3::ZERO,
            w,
        }]);
        PartCache::Simplex(SimplexCache::new(&simplex, &placed))
    };
    let parts = [(0, 1, 1.0), (1, 0, 2.0), (1, 2, 3.0)];
    let mut cache = ContactCache::default();
    cache.begin_step();
    for (child_a, child_b, x) in parts {
        let key = ContactKey {
            child_a,
            child_b,
            ..key(ground, body)
        };
        cache.push(
            key,
            manifold(&[1]),
            &Pose::IDENTITY,
            &Pose::IDENTITY,
            simplex_at(x),
        );
    }
    cache.finish_step();
    let identity = Pose::IDENTITY;
    cache.begin_step();
    assert!(cache.recycle(ground, body, &identity, &identity));
    cache.finish_step();
    cache.begin_step();
    let mut pair = cache.pair(ground, body, &identity, &identity);
    for (child_a, child_b, expected) in [(0, 0, None), (0, 1, Some(1.0)), (1, 2, Some(3.0))] {
        let found = pair.previous_cache(child_a, child_b);
        assert_eq!(found, expected.map_or(PartCache::Cold, simplex_at));
    }
}

#[test]
fn removed_bodies_leave_no_contact_behind() {
    let (ground, box_one, box_two) = handles();
    let mut cache = ContactCache::default();
    cache.begin_step();
    cache.push(
        key(ground, box_one),
        manifold(&[1]),
        &Pose::IDENTITY,
        &Pose::IDENTITY,
        PartCache::Cold,
    );
    cache.push(
        key(ground, box_two),
        manifold(&[1]),
        &Pose::IDENTITY,
        &Pose::IDENTITY,
        PartCache::Cold,
    );
    cache.finish_step();
    cache.remove_body(box_one);
    assert_eq!(cache.contacts().len(), 1);
    assert_eq!(cache.contacts()[0].key.body_b, box_two);
}

#[test]
fn a_recycled_manifold_follows_small_motions_like_a_fresh_one() {
    use crate::collision::narrow_phase::collide_convex;
    use crate::math::Quat;
    use crate::shape::Shape;

    let (ground, box_one, _) = handles();
    let ground_shape = Shape::cuboid(Vec3::new(5.0, 0.5, 5.0)).unwrap();
    let box_shape = Shape::cuboid(Vec3::splat(0.5)).unwrap();
    let ground_pose = Pose::from_position(Vec3::new(0.0, -0.5, 0.0));
    let collide =
        |pose: &Pose| collide_convex(&ground_shape, &ground_pose, &box_shape, pose, 0.02).unwrap();
    let start = Pose::from_position(Vec3::new(0.0, 0.495, 0.0));
    let mut cache = ContactCache::default();
    cache.begin_step();
    cache.push(
        key(ground, box_one),
        collide(&start),
        &ground_pose,
        &start,
        PartCache::Cold,
    );
    cache.finish_step();

    // Moved by 0.6 mm and turned by 0.5°: within the tolerances, rebuilt.
    let nudged = Pose::new(
        start.position + Vec3::new(0.0003, 0.0004, -0.0003),
        Quat::from_rotation_x(0.5f32.to_radians()),
    );
    cache.begin_step();
    assert!(cache.recycle(ground, box_one, &ground_pose, &nudged));
    cache.finish_step();
    let rebuilt = cache.contacts()[0].manifold;
    let fresh = collide(&nudged);
    assert_eq!(rebuilt.len(), fresh.len());
    // Separations agree to 0.1 mm: the rebuilt points follow the box's corners exactly. The
    // positions agree to 4 mm: the turn moves a corner (0.87 m from the centre) sideways by
    // up to 0.87 · 0.0087 rad ≈ 7.6 mm, and the rebuilt midpoint keeps the ground-side point
    // where it was, so it moves half of that.
    for fresh_point in fresh.points() {
        let twin = rebuilt
            .points()
            .iter()
            .find(|point| point.id == fresh_point.id)
            .unwrap();
        assert!((twin.separation - fresh_point.separation).abs() < 1.0e-4);
        assert!(twin.position.distance(fresh_point.position) < 4.0e-3);
    }

    // Moved by 2 mm: beyond the tolerance, the narrow phase must run again.
    cache.begin_step();
    let moved = Pose::from_position(start.position + Vec3::new(0.002, 0.0, 0.0));
    assert!(!cache.recycle(ground, box_one, &ground_pose, &moved));
}
