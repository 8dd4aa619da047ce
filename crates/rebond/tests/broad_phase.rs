//! The broad phase against brute force on randomised scenes: thousands of boxes moving, appearing
//! and disappearing over hundreds of steps.

#[path = "common/random.rs"]
mod random;

use random::Random;

use rebond::internals::collision::broad_phase::{BroadPhase, ProxyHandle};
use rebond::internals::collision::dynamic_tree::AABB_MARGIN;
use rebond::{Aabb, Vec3};

/// Half the side of the cube the boxes live in, metres.
const EXTENT: f32 = 20.0;
const TIME_STEP: f32 = 1.0 / 60.0;

/// What the test knows about one body, kept independently of the broad phase.
struct Body {
    handle: ProxyHandle,
    is_static: bool,
    center: Vec3,
    half_extents: Vec3,
    velocity: Vec3,
    /// The fat box the broad phase should hold: the tight box at the last reinsertion, grown.
    expected_fat: Aabb,
}

impl Body {
    fn tight(&self) -> Aabb {
        Aabb::from_center_half_extents(self.center, self.half_extents)
    }
}

fn fatten(tight: &Aabb) -> Aabb {
    Aabb::new(
        tight.min - Vec3::splat(AABB_MARGIN),
        tight.max + Vec3::splat(AABB_MARGIN),
    )
}

fn contains(outer: &Aabb, inner: &Aabb) -> bool {
    outer.min.cmple(inner.min).all() && inner.max.cmple(outer.max).all()
}

/// A randomised scene: bodies in slots named by their key, with keys reused after removal.
struct Scene {
    random: Random,
    broad_phase: BroadPhase,
    slots: Vec<Option<Body>>,
    free_keys: Vec<u32>,
}

impl Scene {
    fn new(seed: u64) -> Self {
        Self {
            random: Random(seed),
            broad_phase: BroadPhase::new(),
            slots: Vec::new(),
            free_keys: Vec::new(),
        }
    }

    fn live_keys(&self) -> Vec<u32> {
        (0..self.slots.len() as u32)
            .filter(|&key| self.slots[key as usize].is_some())
            .collect()
    }

    fn insert_body(&mut self, key: u32, center: Vec3, half_extents: Vec3, is_static: bool) {
        let velocity = if is_static {
            Vec3::ZERO
        } else {
            self.random.vec3(-4.0, 4.0)
        };
        let tight = Aabb::from_center_half_extents(center, half_extents);
        let handle = self.broad_phase.insert(key, tight, is_static);
        assert_eq!(self.broad_phase.key(handle), key);
        let body = Body {
            handle,
            is_static,
            center,
            half_extents,
            velocity,
            expected_fat: fatten(&tight),
        };
        if self.slots.len() <= key as usize {
            self.slots.resize_with(key as usize + 1, || None);
        }
        assert!(self.slots[key as usize].replace(body).is_none());
    }

    fn insert_random_body(&mut self) {
        let key = self
            .free_keys
            .pop()
            .unwrap_or(u32::try_from(self.slots.len()).unwrap());
        let center = self.random.vec3(-EXTENT, EXTENT);
        let half_extents = if self.random.chance(0.01) {
            self.random.vec3(2.0, 6.0)
        } else {
            self.random.vec3(0.1, 1.2)
        };
        let is_static = self.random.chance(0.15);
        self.insert_body(key, center, half_extents, is_static);
    }

    fn remove_body(&mut self, key: u32) -> Body {
        let body = self.slots[key as usize].take().unwrap();
        self.broad_phase.remove(body.handle);
        body
    }

    /// Moves every moving body (and, rarely, a static one) and reports the new boxes.
    fn move_bodies(&mut self) {
        for slot in &mut self.slots {
            let Some(body) = slot else { continue };
            if body.is_static {
                if !self.random.chance(0.002) {
                    continue;
                }
                body.center = self.random.vec3(-EXTENT, EXTENT);
            } else if self.random.chance(0.003) {
                body.center = self.random.vec3(-EXTENT, EXTENT);
            } else {
                body.velocity += self.random.vec3(-0.5, 0.5);
                body.center += TIME_STEP * body.velocity;
                for axis in 0..3 {
                    if body.center[axis].abs() > EXTENT {
                        body.velocity[axis] = -body.velocity[axis];
                    }
                }
            }
            if self.random.chance(0.005) {
                body.half_extents = self.random.vec3(0.1, 1.2);
            }
            let tight = body.tight();
            let should_move = !contains(&body.expected_fat, &tight);
            if should_move {
                body.expected_fat = fatten(&tight);
            }
            assert_eq!(self.broad_phase.update(body.handle, tight), should_move);
        }
    }

    /// Removes and inserts a few bodies; now and then a body changes between static and moving,
    /// which removes and reinserts it under the same key.
    fn churn(&mut self, removals: usize, insertions: usize) {
        for _ in 0..removals {
            let live = self.live_keys();
            let key = live[self.random.below(live.len())];
            let body = self.remove_body(key);
            if self.random.chance(0.2) {
                self.insert_body(key, body.center, body.half_extents, !body.is_static);
            } else {
                self.free_keys.push(key);
            }
        }
        for _ in 0..insertions {
            self.insert_random_body();
        }
    }

    /// Checks the broad phase against brute force over every pair of live bodies.
    fn check_against_brute_force(&self) {
        let bodies: Vec<(u32, bool, Aabb, Aabb)> = self
            .slots
            .iter()
            .enumerate()
            .filter_map(|(key, slot)| {
                let body = slot.as_ref()?;
                assert_eq!(self.broad_phase.fat_aabb(body.handle), body.expected_fat);
                assert!(contains(&body.expected_fat, &body.tight()));
                Some((key as u32, body.is_static, body.expected_fat, body.tight()))
            })
            .collect();
        assert_eq!(self.broad_phase.proxy_count(), bodies.len());
        let mut expected = Vec::new();
        let mut touching = Vec::new();
        for (index, &(key, is_static, fat, tight)) in bodies.iter().enumerate() {
            for &(other_key, other_is_static, other_fat, other_tight) in &bodies[index + 1..] {
                if is_static && other_is_static {
                    continue;
                }
                if fat.overlaps(&other_fat) {
                    expected.push((key, other_key));
                }
                if tight.overlaps(&other_tight) {
                    touching.push((key, other_key));
                }
            }
        }
        let pairs = self.broad_phase.pairs();
        assert_eq!(pairs.len(), expected.len());
        assert_eq!(pairs, expected.as_slice());
        for pair in touching {
            assert!(
                pairs.binary_search(&pair).is_ok(),
                "missing touching pair {pair:?}"
            );
        }
    }
}

#[test]
fn pairs_equal_brute_force_over_thousands_of_moving_boxes() {
    let mut scene = Scene::new(0x00b1_0c5e);
    let ground = Aabb::new(
        Vec3::new(-EXTENT, -EXTENT - 1.0, -EXTENT),
        Vec3::new(EXTENT, -EXTENT + 0.5, EXTENT),
    );
    scene.insert_body(0, ground.center(), ground.half_extents(), true);
    for _ in 0..2000 {
        scene.insert_random_body();
    }
    scene.broad_phase.update_pairs();
    scene.check_against_brute_force();

    let mut total_pairs = 0;
    for step in 0..200 {
        scene.move_bodies();
        let (removals, insertions) = match step % 50 {
            25 => (300, 50),
            49 => (0, 250),
            _ => (8, 8),
        };
        scene.churn(removals, insertions);
        scene.broad_phase.update_pairs();
        scene.check_against_brute_force();
        total_pairs += scene.broad_phase.pairs().len();
        if step % 20 == 0 {
            assert_eq!(scene.broad_phase.moving_tree().validate(), Ok(()));
            assert_eq!(scene.broad_phase.static_tree().validate(), Ok(()));
        }
    }
    // The scene is dense enough for the comparison to mean something.
    assert!(total_pairs > 200 * 1000, "only {total_pairs} pairs in all");
}

#[test]
fn a_second_update_without_changes_keeps_the_pairs() {
    let mut scene = Scene::new(7);
    for _ in 0..500 {
        scene.insert_random_body();
    }
    scene.broad_phase.update_pairs();
    let before = scene.broad_phase.pairs().to_vec();
    scene.broad_phase.update_pairs();
    assert_eq!(scene.broad_phase.pairs(), before.as_slice());
    scene.check_against_brute_force();
}

#[test]
fn removing_every_body_empties_the_pairs_and_the_trees() {
    let mut scene = Scene::new(11);
    for _ in 0..300 {
        scene.insert_random_body();
    }
    scene.broad_phase.update_pairs();
    assert!(!scene.broad_phase.pairs().is_empty());
    for key in scene.live_keys() {
        scene.remove_body(key);
    }
    scene.broad_phase.update_pairs();
    assert!(scene.broad_phase.pairs().is_empty());
    assert_eq!(scene.broad_phase.proxy_count(), 0);
    assert_eq!(scene.broad_phase.moving_tree().height(), 0);
    assert_eq!(scene.broad_phase.static_tree().validate(), Ok(()));
}
