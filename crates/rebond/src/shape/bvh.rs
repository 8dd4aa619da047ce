//! A bounding-volume hierarchy over a static set of boxes (a mesh's triangles), built once by
//! median splits and walked with a fixed stack: the midphase of a triangle mesh.
//!
//! Nodes are 32 bytes, laid out depth first: an inner node's first child follows it, the second
//! sits at `second`. Leaves hold up to [`LEAF_SIZE`] items, so a mesh of `n` triangles has about
//! `n / 2` nodes: 16 bytes a triangle, plus 4 for the order of the items.

use crate::math::{Aabb, Vec3};

/// Most items in a leaf. Four keeps the hierarchy at about 16 bytes an item; fewer would double
/// the nodes for little gain in a query, as a leaf's boxes are tested one by one anyway.
const LEAF_SIZE: usize = 4;

/// Deepest hierarchy a walk can follow: median splits halve the items at every level, so 64
/// levels hold far more than `u32::MAX` items.
const MAX_DEPTH: usize = 64;

/// One node: its box, and either its second child (inner) or its first item (leaf).
#[derive(Debug, Clone, Copy, PartialEq)]
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
pub struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

impl Bvh {
    /// The hierarchy over `boxes` (item `i` has box `boxes[i]`). Each node splits its items at
    /// the median of their centres along the longest axis of the centres' bounds, so building
    /// costs `O(n log n)` and the depth is `log₂(n / 4)`.
    pub fn build(boxes: &[Aabb]) -> Self {
        let mut order: Vec<u32> = (0..boxes.len() as u32).collect();
        let mut nodes = Vec::with_capacity(boxes.len().div_ceil(LEAF_SIZE) * 2);
        if !boxes.is_empty() {
            build_node(boxes, &mut order, 0, &mut nodes);
        }
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

/// Builds the subtree of `order[..]` (a slice of the whole order starting at `offset`) at the
/// end of `nodes`, and returns nothing: its root is the node pushed first.
fn build_node(boxes: &[Aabb], order: &mut [u32], offset: usize, nodes: &mut Vec<Node>) {
    let centre = |item: u32| boxes[item as usize].center();
    let mut bounds = boxes[order[0] as usize];
    let mut centres = Aabb::new(centre(order[0]), centre(order[0]));
    for &item in order.iter().skip(1) {
        bounds = bounds.union(&boxes[item as usize]);
        let c = centre(item);
        centres = Aabb::new(centres.min.min(c), centres.max.max(c));
    }
    let here = nodes.len();
    nodes.push(Node {
        min: bounds.min.to_array(),
        max: bounds.max.to_array(),
        index: offset as u32,
        count: order.len() as u32,
    });
    if order.len() <= LEAF_SIZE {
        return;
    }
    let extent = centres.max - centres.min;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let middle = order.len() / 2;
    order.select_nth_unstable_by(middle, |&a, &b| {
        centre(a)[axis].total_cmp(&centre(b)[axis]).then(a.cmp(&b))
    });
    let (first, second) = order.split_at_mut(middle);
    build_node(boxes, first, offset, nodes);
    let second_index = nodes.len() as u32;
    build_node(boxes, second, offset + middle, nodes);
    nodes[here].index = second_index;
    nodes[here].count = 0;
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
}
