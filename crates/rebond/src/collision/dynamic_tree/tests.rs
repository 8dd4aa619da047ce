//! Unit tests of the dynamic tree: balance, fat boxes, reinsertion, and random edits checked against brute force.

use super::*;

use super::random::Random;

impl Random {
    fn aabb(&mut self, extent: f32) -> Aabb {
        Aabb::from_center_half_extents(self.vec3(-extent, extent), self.vec3(0.05, 1.0))
    }
}

fn fatten(tight: &Aabb) -> Aabb {
    Bounds::new(tight).fattened().to_aabb()
}

/// The AVL bound on height, `1.44 log2(n + 2)`, with one level of slack.
fn max_balanced_height(count: usize) -> u32 {
    (1.45 * ((count + 2) as f32).log2()).ceil() as u32 + 1
}

fn query_all(tree: &DynamicTree, aabb: &Aabb) -> Vec<ProxyId> {
    let mut found = Vec::new();
    tree.query(aabb, |id| {
        found.push(id);
        true
    });
    found.sort();
    found
}

#[test]
fn empty_tree_has_no_height_and_answers_no_query() {
    let tree = DynamicTree::new();
    assert_eq!(tree.height(), 0);
    assert_eq!(tree.proxy_count(), 0);
    assert!(query_all(&tree, &Aabb::new(Vec3::splat(-1e9), Vec3::splat(1e9))).is_empty());
    assert_eq!(tree.validate(), Ok(()));
}

/// Total half area of the internal nodes: the surface-area heuristic's cost of the tree.
fn internal_area(tree: &DynamicTree) -> f32 {
    let internal = tree
        .nodes
        .iter()
        .filter(|node| !node.is_free() && !node.is_leaf());
    internal.map(|node| node.bounds.half_area()).sum()
}

#[test]
fn leaves_kept_in_place_leave_the_tree_nearly_as_tight_as_a_fresh_build() {
    let mut random = Random(0xf1e5);
    let mut tree = DynamicTree::new();
    let extent = 12.0;
    let mut boxes: Vec<(ProxyId, Vec3, Vec3, Vec3)> = (0..2000)
        .map(|value| {
            let (center, half_extents) = (random.vec3(-extent, extent), random.vec3(0.25, 0.75));
            let aabb = Aabb::from_center_half_extents(center, half_extents);
            let velocity = random.vec3(-4.0, 4.0);
            (
                tree.create_proxy(aabb, value),
                center,
                half_extents,
                velocity,
            )
        })
        .collect();
    for _ in 0..300 {
        for (id, center, half_extents, velocity) in &mut boxes {
            *center += *velocity / 60.0;
            let outside = center.abs().cmpgt(Vec3::splat(extent));
            *velocity = Vec3::select(outside, -*velocity, *velocity);
            tree.move_proxy(*id, Aabb::from_center_half_extents(*center, *half_extents));
        }
    }
    assert_eq!(tree.validate(), Ok(()));
    let mut fresh = DynamicTree::new();
    for &(id, ..) in &boxes {
        let fat = tree.fat_aabb(id);
        let margin = Vec3::splat(AABB_MARGIN);
        fresh.create_proxy(Aabb::new(fat.min + margin, fat.max - margin), 0);
    }
    let (kept, built) = (internal_area(&tree), internal_area(&fresh));
    assert!(
        kept < 1.1 * built,
        "{kept} m² against {built} m² built afresh"
    );
}

#[test]
fn simd_bounds_agree_bit_for_bit_with_the_scalar_box_arithmetic() {
    let mut random = Random(0xb0c5);
    for _ in 0..1000 {
        let (a, b) = (random.aabb(3.0), random.aabb(3.0));
        let (bounds_a, bounds_b) = (Bounds::new(&a), Bounds::new(&b));
        assert_eq!(bounds_a.union(&bounds_b).to_aabb(), a.union(&b));
        assert_eq!(bounds_a.overlaps(&bounds_b), a.overlaps(&b));
        let size = a.max - a.min;
        let scalar_area = size.x * size.y + size.y * size.z + size.z * size.x;
        assert_eq!(bounds_a.half_area().to_bits(), scalar_area.to_bits());
    }
}

#[test]
fn fat_box_is_the_tight_box_grown_by_the_margin() {
    let mut tree = DynamicTree::new();
    let tight = Aabb::new(Vec3::new(1.0, 2.0, 3.0), Vec3::new(2.0, 4.0, 6.0));
    let id = tree.create_proxy(tight, 42);
    assert_eq!(tree.user_data(id), 42);
    assert_eq!(tree.fat_aabb(id), fatten(&tight));
    assert_eq!(tree.fat_aabb(id).min, tight.min - Vec3::splat(AABB_MARGIN));
}

#[test]
fn move_proxy_reinserts_only_when_the_tight_box_leaves_the_fat_box() {
    let mut tree = DynamicTree::new();
    let tight = Aabb::from_center_half_extents(Vec3::ZERO, Vec3::splat(0.5));
    let id = tree.create_proxy(tight, 7);
    tree.create_proxy(Aabb::from_center_half_extents(Vec3::X * 3.0, Vec3::ONE), 8);
    let fat = tree.fat_aabb(id);

    let inside = Aabb::from_center_half_extents(Vec3::splat(0.05), Vec3::splat(0.5));
    assert!(!tree.move_proxy(id, inside));
    assert_eq!(tree.fat_aabb(id), fat);

    let outside = Aabb::from_center_half_extents(Vec3::new(0.3, 0.0, 0.0), Vec3::splat(0.5));
    assert!(tree.move_proxy(id, outside));
    assert_eq!(tree.fat_aabb(id), fatten(&outside));
    assert_eq!(tree.user_data(id), 7);
    assert_eq!(tree.validate(), Ok(()));
}

#[test]
fn query_stops_when_the_callback_says_so() {
    let mut tree = DynamicTree::new();
    for index in 0..10 {
        tree.create_proxy(Aabb::from_center_half_extents(Vec3::ZERO, Vec3::ONE), index);
    }
    let mut calls = 0;
    tree.query(
        &Aabb::from_center_half_extents(Vec3::ZERO, Vec3::ONE),
        |_| {
            calls += 1;
            calls < 3
        },
    );
    assert_eq!(calls, 3);
}

#[test]
fn sorted_insertions_still_give_a_balanced_tree() {
    let mut tree = DynamicTree::new();
    for index in 0..4096 {
        let center = Vec3::new(index as f32 * 2.0, 0.0, 0.0);
        tree.create_proxy(
            Aabb::from_center_half_extents(center, Vec3::splat(0.5)),
            index,
        );
    }
    assert_eq!(tree.validate(), Ok(()));
    assert!(
        tree.height() <= max_balanced_height(4096),
        "height {}",
        tree.height()
    );
}

#[test]
fn random_creates_moves_and_destroys_keep_the_tree_valid_balanced_and_queries_exact() {
    let mut random = Random(0x5eed);
    let mut tree = DynamicTree::new();
    let mut live: Vec<(ProxyId, u32)> = Vec::new();
    let mut next_value = 0;
    for round in 0..40 {
        for _ in 0..150 {
            let id = tree.create_proxy(random.aabb(30.0), next_value);
            live.push((id, next_value));
            next_value += 1;
        }
        for _ in 0..400 {
            let (id, _) = live[random.below(live.len())];
            let center = tree.fat_aabb(id).center() + random.vec3(-0.3, 0.3);
            let tight = Aabb::from_center_half_extents(center, random.vec3(0.05, 1.0));
            let moved = tree.move_proxy(id, tight);
            assert!(Bounds::new(&tree.fat_aabb(id)).contains(&Bounds::new(&tight)));
            assert_eq!(moved, tree.fat_aabb(id) == fatten(&tight));
        }
        let removals = if round % 4 == 3 { 500 } else { 60 };
        for _ in 0..removals.min(live.len()) {
            let (id, _) = live.swap_remove(random.below(live.len()));
            tree.destroy_proxy(id);
        }
        assert_eq!(tree.validate(), Ok(()));
        assert_eq!(tree.proxy_count(), live.len());
        assert!(
            tree.height() <= max_balanced_height(live.len()),
            "height {} for {} proxies",
            tree.height(),
            live.len()
        );
        for &(id, value) in &live {
            assert_eq!(tree.user_data(id), value);
        }
        for _ in 0..20 {
            let probe = random.aabb(30.0);
            let mut expected: Vec<ProxyId> = live
                .iter()
                .map(|&(id, _)| id)
                .filter(|&id| tree.fat_aabb(id).overlaps(&probe))
                .collect();
            expected.sort();
            assert_eq!(query_all(&tree, &probe), expected);
        }
    }
    for (id, _) in live.drain(..) {
        tree.destroy_proxy(id);
    }
    assert_eq!(tree.validate(), Ok(()));
    assert_eq!(tree.height(), 0);
}

#[test]
fn node_stack_spills_past_its_inline_depth_and_stays_last_in_first_out() {
    let mut stack = NodeStack::new();
    let count = INLINE_STACK_DEPTH as u32 + 10;
    for index in 0..count {
        stack.push(index);
    }
    for index in (0..count).rev() {
        assert_eq!(stack.pop(), Some(index));
    }
    assert_eq!(stack.pop(), None);
}
