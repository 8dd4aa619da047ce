//! A dynamic AABB tree: a bounding volume hierarchy over boxes that are created, moved and
//! destroyed one at a time.
//!
//! Every leaf is a proxy holding a *fat* box (the caller's tight box grown by [`AABB_MARGIN`]) and
//! a `u32` chosen by the caller; every internal node holds the union of its two children. All
//! nodes live in one vector and link to each other by index; destroyed nodes go on a free list
//! threaded through the same vector, so the tree allocates only when it outgrows its capacity.
//!
//! A new leaf goes next to the sibling that adds the least surface area to the tree (the
//! surface-area heuristic, searched exactly by branch and bound), and the ancestors are then
//! rebalanced on the way up by rotations that keep the two subtrees of every node within one level
//! of each other, so the height stays logarithmic whatever order the boxes arrive in. A moved
//! proxy whose new fat box still fits inside a small ancestor keeps its place instead: only the
//! boxes above it are refit.

use std::ops::ControlFlow;

use glam::{BVec3A, Vec3Swizzles};

use crate::math::{Aabb, Vec3, Vec3A};

/// How far a proxy's fat box reaches beyond its tight box on every side, metres.
///
/// 10 cm: a body moving at 3 m/s under a 60 Hz step crosses it in about two steps, so ordinary
/// motion touches the tree every few steps instead of every step, while the extra pairs the fat
/// boxes produce stay few for bodies of a decimetre or more.
pub const AABB_MARGIN: f32 = 0.1;

/// How much larger (in half area) than a moved proxy's new fat box an ancestor holding that box
/// may be for the proxy to keep its place in the tree instead of being reinserted.
///
/// Keeping the place skips the sibling search, which dominates a reinsertion, and leaves every
/// box above the holding ancestor no larger; what it costs is a looser subtree below it. At 16, a
/// random-motion test (8,000 boxes in straight lines for 1,200 steps) ends with 3.5 % more total
/// node area than with reinsertion every time, and falling-body scenes reinsert far less.
const IN_PLACE_AREA_RATIO: f32 = 16.0;

/// Marks a missing link: no parent (the root), no children (a leaf), the end of the free list.
const NULL_NODE: u32 = u32::MAX;

/// The height stored in nodes that are on the free list.
const FREE_HEIGHT: u32 = u32::MAX;

/// Depth of the query stack kept on the program stack; deeper trees spill into a heap vector. A
/// balanced tree needs one entry per level, so 64 covers far more proxies than memory can hold.
const INLINE_STACK_DEPTH: usize = 64;

/// Names one proxy (one leaf) of a [`DynamicTree`]: the index of its node, stable from
/// [`DynamicTree::create_proxy`] until [`DynamicTree::destroy_proxy`]. A destroyed proxy's index
/// is later reused by a new proxy.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ProxyId(u32);

impl ProxyId {
    /// The node index: dense, below the number of nodes the tree has ever held at once, so it can
    /// index a side table.
    pub fn index(self) -> usize {
        self.0 as usize
    }

    /// The id of node `index`, for callers that pack ids into their own handles.
    pub(crate) fn from_index(index: u32) -> Self {
        Self(index)
    }
}

/// A box as two SIMD vectors, the form in which the tree stores and tests boxes: a union or a
/// comparison is one instruction per corner instead of three. Holds the same values as the
/// [`Aabb`] it comes from, and its arithmetic rounds the same way.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Bounds {
    min: Vec3A,
    max: Vec3A,
}

impl Bounds {
    fn new(aabb: &Aabb) -> Self {
        Self {
            min: aabb.min.into(),
            max: aabb.max.into(),
        }
    }

    fn to_aabb(self) -> Aabb {
        Aabb::new(self.min.into(), self.max.into())
    }

    /// The smallest box holding both (the boxes are finite, so no NaN reaches `min` or `max`).
    fn union(&self, other: &Self) -> Self {
        Self {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// Whether the two boxes overlap (touching counts).
    fn overlaps(&self, other: &Self) -> bool {
        (self.min.cmple(other.max) & other.min.cmple(self.max)).all()
    }

    /// Whether `inner` lies inside `self` (touching counts).
    fn contains(&self, inner: &Self) -> bool {
        (self.min.cmple(inner.min) & inner.max.cmple(self.max)).all()
    }

    /// Half the surface area, `xy + yz + zx` (m²): the surface-area heuristic's measure of how
    /// likely a random query is to hit the box.
    fn half_area(&self) -> f32 {
        let size = self.max - self.min;
        (size * size.yzx()).element_sum()
    }

    /// The box grown by [`AABB_MARGIN`] on every side: a proxy's fat box around its tight box.
    fn fattened(&self) -> Self {
        let margin = Vec3A::splat(AABB_MARGIN);
        Self {
            min: self.min - margin,
            max: self.max + margin,
        }
    }
}

/// One node of the tree: a leaf (a proxy) or an internal node with exactly two children.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Node {
    /// Fat box for a leaf, union of the children's boxes for an internal node.
    bounds: Bounds,
    /// The parent node, or [`NULL_NODE`] for the root; for a free node, the next free node.
    parent: u32,
    /// Both children of an internal node; both [`NULL_NODE`] for a leaf.
    children: [u32; 2],
    /// The caller's value for a leaf; unused by internal nodes.
    user_data: u32,
    /// Zero for a leaf, one more than the taller child for an internal node, [`FREE_HEIGHT`] for
    /// a free node.
    height: u32,
}

impl Node {
    fn is_leaf(&self) -> bool {
        self.children[0] == NULL_NODE
    }

    fn is_free(&self) -> bool {
        self.height == FREE_HEIGHT
    }
}

/// A dynamic AABB tree; see the [module documentation](self).
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DynamicTree {
    nodes: Vec<Node>,
    root: u32,
    /// First node of the free list, threaded through [`Node::parent`].
    free_list: u32,
    proxy_count: usize,
    /// Scratch stack of the sibling search: (node, growth of its ancestors and itself if the new
    /// leaf goes below it, m²), kept between insertions so inserting does not allocate.
    insertion_stack: Vec<(u32, f32)>,
}

impl Default for DynamicTree {
    fn default() -> Self {
        Self::new()
    }
}

impl DynamicTree {
    /// An empty tree.
    pub fn new() -> Self {
        Self {
            nodes: Vec::new(),
            root: NULL_NODE,
            free_list: NULL_NODE,
            proxy_count: 0,
            insertion_stack: Vec::new(),
        }
    }

    /// Adds a proxy for the tight box `tight_aabb` with the caller's value `user_data`; the tree
    /// stores the box grown by [`AABB_MARGIN`]. Boxes must be finite.
    pub fn create_proxy(&mut self, tight_aabb: Aabb, user_data: u32) -> ProxyId {
        let leaf = self.allocate_node(Node {
            bounds: Bounds::new(&tight_aabb).fattened(),
            parent: NULL_NODE,
            children: [NULL_NODE; 2],
            user_data,
            height: 0,
        });
        self.insert_leaf(leaf);
        self.proxy_count += 1;
        ProxyId(leaf)
    }

    /// Removes a proxy; its id may be handed out again by a later
    /// [`create_proxy`](Self::create_proxy).
    ///
    /// # Panics
    /// If `id` does not name a live proxy of this tree.
    pub fn destroy_proxy(&mut self, id: ProxyId) {
        self.check_proxy(id);
        self.remove_leaf(id.0);
        self.free_node(id.0);
        self.proxy_count -= 1;
    }

    /// Tells the tree the proxy's tight box is now `tight_aabb`. While it stays inside the fat box
    /// nothing changes and this returns false; once it leaves, the proxy gets a new fat box around
    /// `tight_aabb` and this returns true. The leaf keeps its place if an ancestor of at most 16
    /// times the new fat box's half area holds that box (only the boxes above it are refit), and
    /// is reinserted otherwise.
    ///
    /// # Panics
    /// If `id` does not name a live proxy of this tree.
    pub fn move_proxy(&mut self, id: ProxyId, tight_aabb: Aabb) -> bool {
        self.check_proxy(id);
        let leaf = id.0;
        let tight = Bounds::new(&tight_aabb);
        if self.nodes[leaf as usize].bounds.contains(&tight) {
            return false;
        }
        let fat = tight.fattened();
        let parent = self.nodes[leaf as usize].parent;
        if self.has_close_ancestor_holding(parent, &fat) {
            self.nodes[leaf as usize].bounds = fat;
            self.refit_upwards(parent);
            return true;
        }
        self.remove_leaf(leaf);
        self.nodes[leaf as usize].bounds = fat;
        self.insert_leaf(leaf);
        true
    }

    /// The proxy's fat box: the tight box it was last (re)inserted with, grown by [`AABB_MARGIN`].
    ///
    /// # Panics
    /// If `id` does not name a live proxy of this tree.
    pub fn fat_aabb(&self, id: ProxyId) -> Aabb {
        self.check_proxy(id);
        self.nodes[id.index()].bounds.to_aabb()
    }

    /// The value the proxy was created with.
    ///
    /// # Panics
    /// If `id` does not name a live proxy of this tree.
    pub fn user_data(&self, id: ProxyId) -> u32 {
        self.check_proxy(id);
        self.nodes[id.index()].user_data
    }

    /// Calls `callback` with every proxy whose fat box overlaps `aabb` (touching counts), in an
    /// unspecified but deterministic order, until it returns false. Walks the tree with a stack
    /// on the program stack, so a query does not allocate.
    pub fn query<F: FnMut(ProxyId) -> bool>(&self, aabb: &Aabb, mut callback: F) {
        let aabb = &Bounds::new(aabb);
        if self.root == NULL_NODE || !self.nodes[self.root as usize].bounds.overlaps(aabb) {
            return;
        }
        // Only nodes whose boxes overlap are pushed: each child is tested from its parent.
        let mut stack = NodeStack::new();
        stack.push(self.root);
        while let Some(index) = stack.pop() {
            let node = &self.nodes[index as usize];
            if node.is_leaf() {
                if !callback(ProxyId(index)) {
                    return;
                }
                continue;
            }
            for child in node.children {
                if self.nodes[child as usize].bounds.overlaps(aabb) {
                    stack.push(child);
                }
            }
        }
    }

    /// Number of live proxies.
    pub fn proxy_count(&self) -> usize {
        self.proxy_count
    }

    /// Levels below the root: 0 for an empty tree or a single leaf.
    pub fn height(&self) -> u32 {
        if self.root == NULL_NODE {
            0
        } else {
            self.nodes[self.root as usize].height
        }
    }

    /// Checks every invariant of the tree (links, heights, boxes, balance, free list and counts)
    /// in time linear in its size; for tests and debugging. Describes the first broken invariant.
    pub fn validate(&self) -> Result<(), String> {
        let mut reached = vec![false; self.nodes.len()];
        let mut leaves = 0;
        if self.root != NULL_NODE {
            let root = self.node_checked(self.root)?;
            if root.parent != NULL_NODE {
                return Err(format!("root {} has parent {}", self.root, root.parent));
            }
            let mut stack = vec![self.root];
            while let Some(index) = stack.pop() {
                let node = self.node_checked(index)?;
                if std::mem::replace(&mut reached[index as usize], true) {
                    return Err(format!("node {index} is reached twice"));
                }
                if node.is_free() {
                    return Err(format!("free node {index} is in the tree"));
                }
                if node.is_leaf() {
                    if node.children[1] != NULL_NODE || node.height != 0 {
                        return Err(format!("leaf {index} has a child or a height"));
                    }
                    if !(node.bounds.min.is_finite() && node.bounds.max.is_finite()) {
                        return Err(format!("leaf {index}'s box is not finite"));
                    }
                    leaves += 1;
                    continue;
                }
                let [left, right] = node.children;
                let (left_node, right_node) = (self.node_checked(left)?, self.node_checked(right)?);
                if left_node.parent != index || right_node.parent != index {
                    return Err(format!("a child of {index} does not link back to it"));
                }
                if left_node.height.max(right_node.height).checked_add(1) != Some(node.height) {
                    return Err(format!("node {index} has a wrong height"));
                }
                if left_node.height.abs_diff(right_node.height) > 1 {
                    return Err(format!("node {index} is unbalanced"));
                }
                if node.bounds != left_node.bounds.union(&right_node.bounds) {
                    return Err(format!("node {index}'s box is not its children's union"));
                }
                stack.push(left);
                stack.push(right);
            }
        }
        if leaves != self.proxy_count {
            return Err(format!("{leaves} leaves but {} proxies", self.proxy_count));
        }
        let mut free = self.free_list;
        while free != NULL_NODE {
            let node = self.node_checked(free)?;
            if !node.is_free() || std::mem::replace(&mut reached[free as usize], true) {
                return Err(format!("free list reaches node {free} twice or in use"));
            }
            free = node.parent;
        }
        match reached.iter().position(|&was_reached| !was_reached) {
            Some(lost) => Err(format!("node {lost} is neither in the tree nor free")),
            None => Ok(()),
        }
    }

    /// Whether `id` names a live proxy (a leaf in use) of this tree.
    pub(crate) fn is_live_proxy(&self, id: ProxyId) -> bool {
        self.nodes
            .get(id.index())
            .is_some_and(|node| node.is_leaf() && !node.is_free())
    }

    fn node_checked(&self, index: u32) -> Result<&Node, String> {
        self.nodes
            .get(index as usize)
            .ok_or_else(|| format!("link to missing node {index}"))
    }

    fn check_proxy(&self, id: ProxyId) {
        assert!(
            self.is_live_proxy(id),
            "proxy {} is not live in this tree",
            id.0
        );
    }

    fn allocate_node(&mut self, node: Node) -> u32 {
        if self.free_list == NULL_NODE {
            let index = u32::try_from(self.nodes.len())
                .ok()
                .filter(|&index| index != NULL_NODE)
                .unwrap_or_else(|| panic!("a dynamic tree holds at most {NULL_NODE} nodes"));
            self.nodes.push(node);
            index
        } else {
            let index = self.free_list;
            self.free_list = self.nodes[index as usize].parent;
            self.nodes[index as usize] = node;
            index
        }
    }

    fn free_node(&mut self, index: u32) {
        let node = &mut self.nodes[index as usize];
        node.parent = self.free_list;
        node.children = [NULL_NODE; 2];
        node.height = FREE_HEIGHT;
        self.free_list = index;
    }

    /// The node that, made the sibling of `leaf_aabb`, grows the total half area of the tree the
    /// least: the new parent's area plus the growth of every ancestor. Branch and bound, depth
    /// first with the more promising child first: a subtree is entered only when even a perfect
    /// fit inside it (the leaf's own area plus the growth its ancestors, the subtree's root
    /// included, must pay) could beat the best cost found so far; leaves are priced, never pushed.
    fn find_best_sibling(&mut self, leaf_bounds: &Bounds) -> u32 {
        let leaf_area = leaf_bounds.half_area();
        let root_bounds = &self.nodes[self.root as usize].bounds;
        let root_cost = root_bounds.union(leaf_bounds).half_area();
        let (mut best, mut best_cost) = (self.root, root_cost);
        let nodes = &self.nodes;
        let stack = &mut self.insertion_stack;
        stack.clear();
        stack.push((self.root, root_cost - root_bounds.half_area()));
        while let Some((index, growth_above)) = stack.pop() {
            let node = &nodes[index as usize];
            if node.is_leaf() || leaf_area + growth_above >= best_cost {
                continue;
            }
            // (cost as the sibling, growth of it and its ancestors if the leaf goes below it) of
            // one child; the growth is infinite for a leaf, below which nothing can go.
            let price = |child: u32| {
                let child_node = &nodes[child as usize];
                let child_cost = child_node.bounds.union(leaf_bounds).half_area() + growth_above;
                let growth_below = if child_node.is_leaf() {
                    f32::INFINITY
                } else {
                    child_cost - child_node.bounds.half_area()
                };
                (child_cost, growth_below)
            };
            let [mut first, mut second] = node.children;
            let (first_cost, mut first_growth) = price(first);
            let (second_cost, mut second_growth) = price(second);
            if first_cost < best_cost {
                best = first;
                best_cost = first_cost;
            }
            if second_cost < best_cost {
                best = second;
                best_cost = second_cost;
            }
            // The more promising child goes on top, so it is searched first and tightens the bound.
            if first_growth < second_growth {
                std::mem::swap(&mut first, &mut second);
                std::mem::swap(&mut first_growth, &mut second_growth);
            }
            if leaf_area + first_growth < best_cost {
                stack.push((first, first_growth));
            }
            if leaf_area + second_growth < best_cost {
                stack.push((second, second_growth));
            }
        }
        best
    }

    fn insert_leaf(&mut self, leaf: u32) {
        if self.root == NULL_NODE {
            self.root = leaf;
            self.nodes[leaf as usize].parent = NULL_NODE;
            return;
        }
        let leaf_bounds = self.nodes[leaf as usize].bounds;
        let sibling = self.find_best_sibling(&leaf_bounds);
        let sibling_node = self.nodes[sibling as usize];
        let old_parent = sibling_node.parent;
        let new_parent = self.allocate_node(Node {
            bounds: sibling_node.bounds.union(&leaf_bounds),
            parent: old_parent,
            children: [sibling, leaf],
            user_data: 0,
            height: sibling_node.height + 1,
        });
        self.nodes[sibling as usize].parent = new_parent;
        self.nodes[leaf as usize].parent = new_parent;
        if old_parent == NULL_NODE {
            self.root = new_parent;
        } else {
            self.replace_child(old_parent, sibling, new_parent);
        }
        // The new parent's box and height are already right, but a tall sibling leaves it
        // unbalanced.
        self.balance(new_parent);
        self.refit_upwards(old_parent);
    }

    /// Whether `index` or one of its ancestors holds `fat` while its half area is at most
    /// [`IN_PLACE_AREA_RATIO`] times `fat`'s. Areas only grow on the way up, so the walk stops at
    /// the first ancestor too large.
    fn has_close_ancestor_holding(&self, mut index: u32, fat: &Bounds) -> bool {
        let largest_area = IN_PLACE_AREA_RATIO * fat.half_area();
        while index != NULL_NODE {
            let node = &self.nodes[index as usize];
            if node.bounds.half_area() > largest_area {
                return false;
            }
            if node.bounds.contains(fat) {
                return true;
            }
            index = node.parent;
        }
        false
    }

    /// Unlinks a leaf: its sibling takes the parent's place and the parent node is freed. The
    /// leaf's own node stays allocated.
    fn remove_leaf(&mut self, leaf: u32) {
        if leaf == self.root {
            self.root = NULL_NODE;
            return;
        }
        let parent = self.nodes[leaf as usize].parent;
        let parent_node = self.nodes[parent as usize];
        let sibling = if parent_node.children[0] == leaf {
            parent_node.children[1]
        } else {
            parent_node.children[0]
        };
        let grandparent = parent_node.parent;
        self.nodes[sibling as usize].parent = grandparent;
        self.free_node(parent);
        if grandparent == NULL_NODE {
            self.root = sibling;
        } else {
            self.replace_child(grandparent, parent, sibling);
            self.refit_upwards(grandparent);
        }
    }

    /// Points `parent`'s link to `old_child` at `new_child` instead.
    fn replace_child(&mut self, parent: u32, old_child: u32, new_child: u32) {
        let children = &mut self.nodes[parent as usize].children;
        let side = usize::from(children[1] == old_child);
        children[side] = new_child;
    }

    /// Rebalances and refits `index` and each of its ancestors, from the bottom up, stopping at
    /// the first node whose box and height come out unchanged: nothing above it depends on more.
    fn refit_upwards(&mut self, mut index: u32) {
        while index != NULL_NODE {
            let node = &self.nodes[index as usize];
            let (old_bounds, old_height) = (node.bounds, node.height);
            index = self.balance(index);
            self.refit(index);
            let node = &self.nodes[index as usize];
            if node.bounds == old_bounds && node.height == old_height {
                return;
            }
            index = node.parent;
        }
    }

    /// Recomputes an internal node's box and height from its children.
    fn refit(&mut self, index: u32) {
        let [left, right] = self.nodes[index as usize].children;
        let (left_node, right_node) = (self.nodes[left as usize], self.nodes[right as usize]);
        let node = &mut self.nodes[index as usize];
        node.bounds = left_node.bounds.union(&right_node.bounds);
        node.height = 1 + left_node.height.max(right_node.height);
    }

    /// If one child of the internal node `index` is two or more levels taller than the other,
    /// rotates the taller child up into `index`'s place, then rebalances `index` (now one level
    /// down) the same way, which sifts the short side down until every node is within one level;
    /// returns the node now at `index`'s old place. The subtree's height never grows.
    fn balance(&mut self, index: u32) -> u32 {
        let [left, right] = self.nodes[index as usize].children;
        let left_height = self.nodes[left as usize].height;
        let right_height = self.nodes[right as usize].height;
        let tall_side = if right_height > left_height + 1 {
            1
        } else if left_height > right_height + 1 {
            0
        } else {
            return index;
        };
        let new_top = self.rotate_up(index, tall_side);
        self.balance(index);
        self.refit(new_top);
        new_top
    }

    /// Rotation at `top` whose child on side `tall_side` is the taller by at least two levels: that
    /// child takes `top`'s place and keeps its taller child, while `top` becomes its other child
    /// and adopts its shorter child. With equally tall grandchildren, `top` adopts the one that
    /// makes its box smaller. Returns the tall child, now in `top`'s place.
    fn rotate_up(&mut self, top: u32, tall_side: usize) -> u32 {
        let short_side = 1 - tall_side;
        let top_node = self.nodes[top as usize];
        let tall = top_node.children[tall_side];
        let short_bounds = self.nodes[top_node.children[short_side] as usize].bounds;
        let [first, second] = self.nodes[tall as usize].children;
        let (first_node, second_node) = (self.nodes[first as usize], self.nodes[second as usize]);
        let first_moves_down = match first_node.height.cmp(&second_node.height) {
            std::cmp::Ordering::Less => true,
            std::cmp::Ordering::Greater => false,
            std::cmp::Ordering::Equal => {
                short_bounds.union(&first_node.bounds).half_area()
                    < short_bounds.union(&second_node.bounds).half_area()
            }
        };
        let (kept, adopted) = if first_moves_down {
            (second, first)
        } else {
            (first, second)
        };

        let parent = top_node.parent;
        self.nodes[tall as usize].parent = parent;
        if parent == NULL_NODE {
            self.root = tall;
        } else {
            self.replace_child(parent, top, tall);
        }
        self.nodes[tall as usize].children = [top, kept];
        self.nodes[top as usize].parent = tall;
        self.nodes[top as usize].children[tall_side] = adopted;
        self.nodes[adopted as usize].parent = top;
        self.refit(top);
        self.refit(tall);
        tall
    }
}

/// The traversal stack of a query: [`INLINE_STACK_DEPTH`] entries on the program stack, then a
/// heap vector that is only allocated by trees too deep for them.
struct NodeStack {
    inline: [u32; INLINE_STACK_DEPTH],
    inline_len: usize,
    spill: Vec<u32>,
}

impl NodeStack {
    fn new() -> Self {
        Self {
            inline: [NULL_NODE; INLINE_STACK_DEPTH],
            inline_len: 0,
            spill: Vec::new(),
        }
    }

    fn push(&mut self, index: u32) {
        if self.inline_len < INLINE_STACK_DEPTH {
            self.inline[self.inline_len] = index;
            self.inline_len += 1;
        } else {
            self.spill.push(index);
        }
    }

    fn pop(&mut self) -> Option<u32> {
        if let Some(index) = self.spill.pop() {
            return Some(index);
        }
        self.inline_len = self.inline_len.checked_sub(1)?;
        Some(self.inline[self.inline_len])
    }
}

/// Ray casts through the tree: boxes met along a ray, nearest first, or along the path of a box
/// swept in a straight line.
impl DynamicTree {
    /// Calls `callback(proxy, entry)` for every proxy whose fat box the ray from `origin` along
    /// `direction` (unit) meets within `max_distance` metres (infinity allowed), `entry` being the
    /// distance at which the ray enters the box (zero when `origin` is inside it).
    ///
    /// The callback steers the search: `ControlFlow::Continue(distance)` goes on looking only up
    /// to `distance` (a closest-hit search returns the distance of the hit it just found; a
    /// bound larger than the current one is ignored), `ControlFlow::Break(())` stops. Boxes
    /// entered exactly at the bound are still visited, so equally near hits can be told apart by
    /// the caller. Subtrees are searched in the order the ray enters them; the order is
    /// deterministic. Does not allocate below about three million proxies (past 31 levels, the
    /// traversal stack spills to the heap).
    pub fn ray_cast<F>(&self, origin: Vec3, direction: Vec3, max_distance: f32, callback: F)
    where
        F: FnMut(ProxyId, f32) -> ControlFlow<(), f32>,
    {
        self.sweep(origin, Vec3::ZERO, direction, max_distance, callback);
    }

    /// [`ray_cast`](Self::ray_cast) for the box `aabb` translated along `direction` (unit): calls
    /// `callback(proxy, entry)` for every proxy whose fat box the moving box touches within
    /// `max_distance` metres of travel, `entry` being the travel at which they first touch (zero
    /// when they already overlap). The same as a ray from the box's centre against every fat box
    /// grown by the box's half extents.
    pub fn box_cast<F>(&self, aabb: &Aabb, direction: Vec3, max_distance: f32, callback: F)
    where
        F: FnMut(ProxyId, f32) -> ControlFlow<(), f32>,
    {
        self.sweep(
            aabb.center(),
            aabb.half_extents(),
            direction,
            max_distance,
            callback,
        );
    }

    fn sweep<F>(
        &self,
        origin: Vec3,
        half_extents: Vec3,
        direction: Vec3,
        max_distance: f32,
        mut callback: F,
    ) where
        F: FnMut(ProxyId, f32) -> ControlFlow<(), f32>,
    {
        if self.root == NULL_NODE {
            return;
        }
        let slabs = SweepSlabs::new(origin, half_extents, direction);
        let mut bound = max_distance;
        let mut stack = SweepStack(NodeStack::new());
        if let Some(entry) = slabs.entry(&self.nodes[self.root as usize].bounds, bound) {
            stack.push(self.root, entry);
        }
        while let Some((index, entry)) = stack.pop() {
            // The bound may have shrunk since the node was pushed.
            if entry > bound {
                continue;
            }
            let node = &self.nodes[index as usize];
            if node.is_leaf() {
                match callback(ProxyId(index), entry) {
                    ControlFlow::Continue(new_bound) => bound = bound.min(new_bound),
                    ControlFlow::Break(()) => return,
                }
                continue;
            }
            let mut children = node.children.map(|child| {
                (
                    child,
                    slabs.entry(&self.nodes[child as usize].bounds, bound),
                )
            });
            // Last pushed, first searched: the child the ray enters first.
            let entry_of = |met: Option<f32>| met.unwrap_or(f32::INFINITY);
            if entry_of(children[0].1) < entry_of(children[1].1) {
                children.swap(0, 1);
            }
            for (child, met) in children {
                if let Some(child_entry) = met {
                    stack.push(child, child_entry);
                }
            }
        }
    }
}

/// The traversal stack of a cast: nodes with the distance at which the cast enters them, kept on
/// a [`NodeStack`] as two entries each (the distance as its bits).
struct SweepStack(NodeStack);

impl SweepStack {
    fn push(&mut self, node: u32, entry: f32) {
        self.0.push(node);
        self.0.push(entry.to_bits());
    }

    fn pop(&mut self) -> Option<(u32, f32)> {
        let entry = f32::from_bits(self.0.pop()?);
        let node = self.0.pop()?;
        Some((node, entry))
    }
}

/// A ray, or the centre of a box swept along one, set up for the slab test against many boxes.
struct SweepSlabs {
    /// The ray's origin plus the swept box's half extents: a tested box's `min` minus this is
    /// its grown lower corner relative to the origin.
    lower_offset: Vec3A,
    /// The ray's origin minus the half extents, likewise for the upper corner.
    upper_offset: Vec3A,
    /// `1 / direction` per axis; `+∞` on the axes the ray runs parallel to.
    inverse_direction: Vec3A,
    /// The axes along which the ray runs towards `+∞` (or not at all): it crosses the lower
    /// plane first.
    rising: BVec3A,
}

impl SweepSlabs {
    fn new(origin: Vec3, half_extents: Vec3, direction: Vec3) -> Self {
        let parallel = direction.cmpeq(Vec3::ZERO);
        let inverse_direction = Vec3::select(parallel, Vec3::INFINITY, direction.recip());
        let rising = parallel | direction.cmpgt(Vec3::ZERO);
        Self {
            lower_offset: (origin + half_extents).into(),
            upper_offset: (origin - half_extents).into(),
            inverse_direction: inverse_direction.into(),
            rising: BVec3A::new(rising.x, rising.y, rising.z),
        }
    }

    /// The distance at which the ray enters `bounds` (grown by the half extents), if it does so
    /// within `[0, bound]`. On each axis the ray is between the box's two planes for
    /// `t ∈ [(near − o)/d, (far − o)/d]`; it is inside the box where all three overlap.
    ///
    /// On a parallel axis the two ends are `∓∞` when the origin lies between the planes and the
    /// interval is empty otherwise; an origin exactly on a plane gives `0 · ∞ = NaN`, which
    /// `f32::max` and `f32::min` skip, so the axis does not constrain: touching counts.
    #[inline]
    fn entry(&self, bounds: &Bounds, bound: f32) -> Option<f32> {
        let low = bounds.min - self.lower_offset;
        let high = bounds.max - self.upper_offset;
        let near = Vec3A::select(self.rising, low, high) * self.inverse_direction;
        let far = Vec3A::select(self.rising, high, low) * self.inverse_direction;
        let enter = near.x.max(near.y).max(near.z).max(0.0);
        let leave = far.x.min(far.y).min(far.z).min(bound);
        (enter <= leave).then_some(enter)
    }
}

#[cfg(test)]
#[path = "../../tests/common/random.rs"]
pub(super) mod random;

#[cfg(test)]
mod tests;
