//! A bounding-volume hierarchy over a static set of boxes (a mesh's triangles), built once by
//! halving runs of the boxes sorted along a Morton curve, and walked with a fixed stack: the
//! midphase of a triangle mesh.
//!
//! Nodes are 32 bytes, laid out depth first: an inner node's first child follows it, the second
//! sits at `second`. Leaves hold up to [`LEAF_SIZE`] items, so a mesh of `n` triangles has about
//! `n / 2` nodes: 16 bytes a triangle, plus 4 for the order of the items.

use crate::math::{Aabb, Vec3};

/// Most items in a leaf. Four keeps the hierarchy at about 16 bytes an item; fewer would double
/// the nodes for little gain in a query, as a leaf's boxes are tested one by one anyway.
const LEAF_SIZE: usize = 4;

/// Bits of the Morton curve per axis: the curve orders the items to a cell of `1 / 2²¹` of the
/// mesh's largest extent (5 mm over 10 km). With fewer bits, the small triangles of a large mesh
/// share cells, and within a cell the curve keeps their index order, which need not be near.
const MORTON_BITS: u32 = 21;

/// Deepest hierarchy a walk can follow: every level halves the items, so 64 levels hold far more
/// than `u32::MAX` items.
const MAX_DEPTH: usize = 64;

/// One node: its box, and either its second child (inner) or its first item (leaf).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Node {
    min: [f32; 3],
    max: [f32; 3],
    /// Inner node: index of the second child. Leaf: index of the first item in `order`.
    index: u32,
    /// Number of items of a leaf; zero for an inner node.
    count: u32,
}

impl Node {
    fn overlaps(&self, bounds: &Aabb) -> bool {
        (0..3).all(|axis| self.min[axis] <= bounds.max[axis] && bounds.min[axis] <= self.max[axis])
    }

    fn aabb(&self) -> Aabb {
        Aabb::new(Vec3::from_array(self.min), Vec3::from_array(self.max))
    }
}

/// The hierarchy: nodes and the items in leaf order.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

impl Bvh {
    /// The hierarchy over `boxes` (item `i` has box `boxes[i]`). The items are sorted once along
    /// a Morton curve through their centres ([`MORTON_BITS`] per axis, over the cube around the
    /// centres' bounds: with each axis over its own span, a terrain's few metres of height would
    /// get as many bits as its width and split it by height near the root, into nodes that each
    /// span the whole terrain, which a vertical ray or a body's box then all enter), and
    /// each node splits its run of the sorted items in half, so building costs one sort and
    /// `O(n)` more, and the depth is `log₂(n / 4)`. Near items share leaves as in a median split
    /// along the longest axis, give or take the curve's jumps.
    pub fn build(boxes: &[Aabb]) -> Self {
        let mut nodes = Vec::with_capacity(boxes.len().div_ceil(LEAF_SIZE) * 2);
        let Some(first) = boxes.first() else {
            return Self::default();
        };
        let (low, high) = boxes
            .iter()
            .fold((first.center(), first.center()), |(low, high), b| {
                let c = b.center();
                (low.min(c), high.max(c))
            });
        let span = Vec3::splat((high - low).max_element().max(f32::MIN_POSITIVE));
        let last_cell = ((1u32 << MORTON_BITS) - 1) as f32;
        let mut keys: Vec<(u64, u32)> = (0u32..)
            .zip(boxes)
            .map(|(index, b)| {
                let cell = ((b.center() - low) / span * last_cell)
                    .clamp(Vec3::ZERO, Vec3::splat(last_cell));
                let code = spread_bits(cell.x as u32)
                    | (spread_bits(cell.y as u32) << 1)
                    | (spread_bits(cell.z as u32) << 2);
                (code, index)
            })
            .collect();
        keys.sort_unstable();
        let order: Vec<u32> = keys.into_iter().map(|(_, index)| index).collect();
        build_node(boxes, &order, 0, order.len(), &mut nodes);
        // Halving leaves between 2 and 4 items, so the estimate above can fall short.
        nodes.shrink_to_fit();
        Self { nodes, order }
    }

    /// The box around every item, or `None` when there is none.
    pub fn bounds(&self) -> Option<Aabb> {
        self.nodes.first().map(Node::aabb)
    }

    /// Bytes held by the hierarchy.
    pub fn heap_bytes(&self) -> usize {
        self.nodes.capacity() * std::mem::size_of::<Node>()
            + self.order.capacity() * std::mem::size_of::<u32>()
    }

    /// Calls `visit(item)` for every item of every leaf reached through nodes whose boxes
    /// overlap `bounds`: a superset of the items whose own boxes do, which the caller tests.
    pub fn query(&self, bounds: &Aabb, visit: impl FnMut(u32)) {
        self.walk(|node| node.overlaps(bounds), visit);
    }

    /// Calls `visit(item)` for every item in a leaf whose node boxes all pass `enter`.
    pub fn walk_boxes(&self, mut enter: impl FnMut(&Aabb) -> bool, visit: impl FnMut(u32)) {
        self.walk(|node| enter(&node.aabb()), visit);
    }

    fn walk(&self, mut enter: impl FnMut(&Node) -> bool, mut visit: impl FnMut(u32)) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = [0u32; MAX_DEPTH];
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let index = stack[len] as usize;
            let Some(node) = self.nodes.get(index) else {
                continue;
            };
            if !enter(node) {
                continue;
            }
            if node.count > 0 {
                let start = node.index as usize;
                for &item in self
                    .order
                    .get(start..start + node.count as usize)
                    .unwrap_or(&[])
                {
                    visit(item);
                }
            } else if len + 2 <= MAX_DEPTH {
                stack[len] = node.index;
                stack[len + 1] = index as u32 + 1;
                len += 2;
            }
        }
    }
}

/// The [`MORTON_BITS`] low bits of `value` spread to every third bit (bit `k` to bit `3k`).
fn spread_bits(value: u32) -> u64 {
    let mut x = u64::from(value) & 0x1F_FFFF;
    x = (x | (x << 32)) & 0x001F_0000_0000_FFFF;
    x = (x | (x << 16)) & 0x001F_0000_FF00_00FF;
    x = (x | (x << 8)) & 0x100F_00F0_0F00_F00F;
    x = (x | (x << 4)) & 0x10C3_0C30_C30C_30C3;
    (x | (x << 2)) & 0x1249_2492_4924_9249
}

/// Builds the subtree of the items `order[start..end]` at the end of `nodes` (its root is the
/// node pushed first) and returns its bounds.
fn build_node(
    boxes: &[Aabb],
    order: &[u32],
    start: usize,
    end: usize,
    nodes: &mut Vec<Node>,
) -> Aabb {
    let here = nodes.len();
    nodes.push(Node {
        min: [0.0; 3],
        max: [0.0; 3],
        index: start as u32,
        count: (end - start) as u32,
    });
    let bounds = if end - start <= LEAF_SIZE {
        let items = &order[start..end];
        items
            .iter()
            .skip(1)
            .fold(boxes[items[0] as usize], |bounds, &item| {
                bounds.union(&boxes[item as usize])
            })
    } else {
        let middle = start + (end - start) / 2;
        let first = build_node(boxes, order, start, middle, nodes);
        let second_index = nodes.len() as u32;
        let second = build_node(boxes, order, middle, end, nodes);
        nodes[here].index = second_index;
        nodes[here].count = 0;
        first.union(&second)
    };
    nodes[here].min = bounds.min.to_array();
    nodes[here].max = bounds.max.to_array();
    bounds
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A walk finds exactly the items whose boxes overlap the query (a leaf may give more, which
    /// the caller filters; here every item's own box is checked too).
    #[test]
    fn a_query_finds_every_overlapping_box() {
        let boxes: Vec<Aabb> = (0..1000)
            .map(|i| {
                let x = (i % 10) as f32;
                let y = ((i / 10) % 10) as f32;
                let z = (i / 100) as f32;
                Aabb::new(Vec3::new(x, y, z), Vec3::new(x + 0.5, y + 0.5, z + 0.5))
            })
            .collect();
        let bvh = Bvh::build(&boxes);
        let query = Aabb::new(Vec3::new(2.2, 3.2, 4.2), Vec3::new(5.1, 4.1, 4.3));
        let mut found = Vec::new();
        bvh.query(&query, |item| {
            if boxes[item as usize].overlaps(&query) {
                found.push(item);
            }
        });
        found.sort_unstable();
        let expected: Vec<u32> = (0..1000u32)
            .filter(|&i| boxes[i as usize].overlaps(&query))
            .collect();
        assert_eq!(found, expected);
        assert_eq!(expected.len(), 4 * 2);
    }

    /// Each vertical line `(x, z)` enters at most two nodes a level of `bvh`, built over `count`
    /// items: the nodes whose boxes it crosses.
    fn assert_vertical_lines_enter_two_nodes_a_level(
        bvh: &Bvh,
        count: usize,
        lines: impl Iterator<Item = (f32, f32)>,
    ) {
        let levels = (count / LEAF_SIZE).ilog2() as usize + 1;
        for (x, z) in lines {
            let mut entered = 0;
            bvh.walk_boxes(
                |bounds| {
                    let inside = (bounds.min.x..=bounds.max.x).contains(&x)
                        && (bounds.min.z..=bounds.max.z).contains(&z);
                    entered += usize::from(inside);
                    inside
                },
                |_| {},
            );
            assert!(
                entered <= 2 * levels,
                "the line at ({x}, {z}) entered {entered} nodes of a {levels}-level hierarchy"
            );
        }
    }

    /// A 4 km strip of 1 m triangles in a scrambled order: the curve's cells must be finer than
    /// the triangles, or the triangles sharing one go into leaves in their index order, leaves
    /// that span the cell, and a vertical line enters several of them (with 10 bits, 4 m cells:
    /// 44 nodes of a 15-level hierarchy).
    #[test]
    fn a_long_scrambled_strip_keeps_its_leaves_small() {
        let (along, across) = (4096, 8);
        let count = along * across * 2;
        let boxes: Vec<Aabb> = (0..count)
            .map(|k| {
                let cell = (k * 7919) % count / 2;
                let (x, z) = ((cell % along) as f32, (cell / along) as f32);
                let y = 0.3 * (0.05 * x).sin();
                Aabb::new(
                    Vec3::new(x, y - 0.01, z),
                    Vec3::new(x + 1.0, y + 0.01, z + 1.0),
                )
            })
            .collect();
        let bvh = Bvh::build(&boxes);
        let lines = (0..200).map(|k| (3.3 + 20.37 * k as f32, 0.5 + (k % 7) as f32));
        assert_vertical_lines_enter_two_nodes_a_level(&bvh, count, lines);
    }

    #[test]
    fn spreading_puts_bit_k_at_bit_3k() {
        for value in [0u32, 1, 2, 0x15_5555, 0x1F_FFFF, 0x12_3456, 0xFFFF_FFFF] {
            let expected = (0..MORTON_BITS)
                .filter(|k| value >> k & 1 == 1)
                .fold(0u64, |code, k| code | 1 << (3 * k));
            assert_eq!(spread_bits(value), expected, "{value:#x}");
        }
    }

    /// A vertical line through a bumpy terrain of 8,192 triangles (64 m square, heights within
    /// ±0.5 m) enters at most two nodes a level, as through a flat one: the curve follows the
    /// terrain's width, not its height.
    #[test]
    fn a_vertical_line_through_a_terrain_enters_few_nodes() {
        let height = |x: f32, z: f32| 0.5 * (0.7 * x).sin() * (0.9 * z).cos();
        let mut boxes = Vec::new();
        for i in 0..64 {
            for j in 0..64 {
                let corner = |di: i32, dj: i32| {
                    let (x, z) = ((i + di) as f32, (j + dj) as f32);
                    Vec3::new(x, height(x, z), z)
                };
                for [a, b, c] in [
                    [corner(0, 0), corner(1, 0), corner(1, 1)],
                    [corner(0, 0), corner(1, 1), corner(0, 1)],
                ] {
                    boxes.push(Aabb::new(a.min(b).min(c), a.max(b).max(c)));
                }
            }
        }
        let bvh = Bvh::build(&boxes);
        let lines = (0..100).map(|k| (0.3 + 0.637 * k as f32, 63.7 - 0.611 * k as f32));
        assert_vertical_lines_enter_two_nodes_a_level(&bvh, boxes.len(), lines);
    }
}
