//! Steps 3 and 4 of building a hull: merge the triangles lying on a common plane into polygons,
//! and drop the vertices left in the middle of an edge.

use glam::DVec3;

use super::quickhull::{Cloud, Facet};
use super::MERGE_COSINE;

/// Groups neighbouring facets lying within the tolerance of a common plane into polygons.
///
/// Largest facets seed first. A group grows across edges to facets whose three corners lie within
/// the tolerance of the group's plane and whose normal is within 60° of the group's
/// ([`MERGE_COSINE`]; slivers, whose normal means nothing, are exempt). The plane is first the
/// seed's, then the area-weighted plane of that first growth, from which the group grows again
/// (when the seed itself lies on it). Every member lies within the tolerance of the plane the
/// group ends with, so merging cannot drift along a curved surface, and that plane is the face's.
/// A group whose outline is not a single simple loop (not a disk) is dropped back to its seed.
pub(super) struct Merger<'a> {
    positions: &'a [DVec3],
    facets: &'a [Facet],
    tolerance: f64,
    /// Whether each facet is a sliver: no higher than the tolerance over its longest edge.
    sliver: Vec<bool>,
    /// The group of each facet, `usize::MAX` while unassigned.
    group: Vec<usize>,
    /// The growth that last reached each facet.
    mark: Vec<usize>,
    growth: usize,
}

impl<'a> Merger<'a> {
    pub(super) fn new(cloud: &'a Cloud, facets: &'a [Facet]) -> Self {
        let sliver = facets
            .iter()
            .map(|facet| {
                let [a, b, c] = facet
                    .vertices
                    .map(|vertex| cloud.positions[vertex as usize]);
                let longest = (b - a).length().max((c - b).length()).max((a - c).length());
                (b - a).cross(c - a).length() <= cloud.tolerance * longest
            })
            .collect();
        Self {
            positions: &cloud.positions,
            facets,
            tolerance: cloud.tolerance,
            sliver,
            group: vec![usize::MAX; facets.len()],
            mark: vec![0; facets.len()],
            growth: 0,
        }
    }

    /// The outline of each polygon (point indices counter-clockwise seen from outside) and the
    /// unit normal of the plane its members lie on.
    pub(super) fn merge(mut self) -> (Vec<Vec<u32>>, Vec<DVec3>) {
        let facets = self.facets;
        let mut order: Vec<usize> = (0..facets.len()).collect();
        order.sort_by(|&a, &b| facets[b].area.total_cmp(&facets[a].area).then(a.cmp(&b)));
        let mut outlines = Vec::new();
        let mut normals = Vec::new();
        for seed in order {
            if self.group[seed] != usize::MAX {
                continue;
            }
            let mut normal = facets[seed].normal;
            let mut members = self.grow(seed, normal, normal.dot(self.centroid(seed)));
            let (fitted, offset) = self.fit(&members, normal);
            if self.on_plane(seed, fitted, offset) {
                normal = fitted;
                members = self.grow(seed, normal, offset);
            }
            let (members, outline, normal) = match self.outline(&members) {
                Some(outline) => (members, outline, normal),
                None => (
                    vec![seed],
                    facets[seed].vertices.to_vec(),
                    facets[seed].normal,
                ),
            };
            for member in members {
                self.group[member] = outlines.len();
            }
            outlines.push(outline);
            normals.push(normal);
        }
        (outlines, normals)
    }

    fn centroid(&self, facet: usize) -> DVec3 {
        let [a, b, c] = self.facets[facet].vertices;
        (self.positions[a as usize] + self.positions[b as usize] + self.positions[c as usize]) / 3.0
    }

    /// The unassigned facets reachable from `seed` within the tolerance of the plane
    /// `normal · p = offset`, marked with a new growth number.
    fn grow(&mut self, seed: usize, normal: DVec3, offset: f64) -> Vec<usize> {
        self.growth += 1;
        self.mark[seed] = self.growth;
        let mut members = vec![seed];
        let mut next = 0;
        while next < members.len() {
            let neighbors = self.facets[members[next]].neighbors;
            next += 1;
            for neighbor in neighbors {
                if self.mark[neighbor] == self.growth || self.group[neighbor] != usize::MAX {
                    continue;
                }
                let steep = self.facets[neighbor].normal.dot(normal) <= MERGE_COSINE;
                if self.on_plane(neighbor, normal, offset) && (self.sliver[neighbor] || !steep) {
                    self.mark[neighbor] = self.growth;
                    members.push(neighbor);
                }
            }
        }
        members
    }

    /// Whether the corners of `facet` lie within the tolerance of the plane `normal · p = offset`.
    fn on_plane(&self, facet: usize, normal: DVec3, offset: f64) -> bool {
        self.facets[facet].vertices.iter().all(|&vertex| {
            (normal.dot(self.positions[vertex as usize]) - offset).abs() <= self.tolerance
        })
    }

    /// The area-weighted mean plane of `members`: normal and offset.
    fn fit(&self, members: &[usize], fallback: DVec3) -> (DVec3, f64) {
        let mut normal = DVec3::ZERO;
        let mut moment = DVec3::ZERO;
        let mut area = 0.0;
        for &member in members {
            let facet = &self.facets[member];
            normal += facet.area * facet.normal;
            moment += facet.area * self.centroid(member);
            area += facet.area;
        }
        let normal = normal.normalize_or(fallback);
        (normal, normal.dot(moment / area))
    }

    /// The boundary of the last growth `members` as one loop of point indices, or `None` when it
    /// is not a single simple loop.
    fn outline(&self, members: &[usize]) -> Option<Vec<u32>> {
        let mut edges = Vec::new();
        for &member in members {
            let facet = &self.facets[member];
            for k in 0..3 {
                if self.mark[facet.neighbors[k]] != self.growth {
                    edges.push((facet.vertices[k], facet.vertices[(k + 1) % 3]));
                }
            }
        }
        edges.sort_unstable();
        if edges.is_empty() || edges.windows(2).any(|pair| pair[0].0 == pair[1].0) {
            return None;
        }
        let mut outline = vec![edges[0].0];
        let mut to = edges[0].1;
        while to != edges[0].0 {
            if outline.len() == edges.len() {
                return None;
            }
            let next = edges.binary_search_by_key(&to, |edge| edge.0).ok()?;
            outline.push(to);
            to = edges[next].1;
        }
        (outline.len() == edges.len()).then_some(outline)
    }
}

/// Drops every vertex shared by exactly two polygons that lies within `tolerance` of the segment
/// between its two neighbours: it sits in the middle of an edge. The polygons run through such a
/// vertex in opposite directions with the same neighbours, so dropping it from both keeps them
/// consistent. A polygon keeps at least three vertices.
pub(super) fn drop_edge_vertices(
    mut outlines: Vec<Vec<u32>>,
    positions: &[DVec3],
    tolerance: f64,
) -> Vec<Vec<u32>> {
    let mut places = vec![Vec::new(); positions.len()];
    for (polygon, outline) in outlines.iter().enumerate() {
        for (slot, &vertex) in outline.iter().enumerate() {
            places[vertex as usize].push((polygon, slot));
        }
    }
    let ring = |outline: &Vec<u32>, step: usize| -> Vec<usize> {
        (0..outline.len())
            .map(|slot| (slot + step) % outline.len())
            .collect()
    };
    let mut next: Vec<Vec<usize>> = outlines.iter().map(|outline| ring(outline, 1)).collect();
    let mut previous: Vec<Vec<usize>> = outlines
        .iter()
        .map(|outline| ring(outline, outline.len() - 1))
        .collect();
    let mut remaining: Vec<usize> = outlines.iter().map(Vec::len).collect();
    let mut dropped = vec![false; positions.len()];
    for (vertex, place) in places.iter().enumerate() {
        let &[(first, slot), (second, other_slot)] = place.as_slice() else {
            continue;
        };
        if remaining[first] <= 3 || remaining[second] <= 3 {
            continue;
        }
        let before = positions[outlines[first][previous[first][slot]] as usize];
        let after = positions[outlines[first][next[first][slot]] as usize];
        if !near_segment(positions[vertex], before, after, tolerance) {
            continue;
        }
        for (polygon, slot) in [(first, slot), (second, other_slot)] {
            let (back, ahead) = (previous[polygon][slot], next[polygon][slot]);
            next[polygon][back] = ahead;
            previous[polygon][ahead] = back;
            remaining[polygon] -= 1;
        }
        dropped[vertex] = true;
    }
    for outline in &mut outlines {
        outline.retain(|&vertex| !dropped[vertex as usize]);
    }
    outlines
}

/// Whether `point` lies within `tolerance` of the segment from `a` to `b`, between its ends.
fn near_segment(point: DVec3, a: DVec3, b: DVec3, tolerance: f64) -> bool {
    let along = b - a;
    let t = (point - a).dot(along) / along.length_squared();
    (0.0..=1.0).contains(&t) && (point - (a + t * along)).length() <= tolerance
}
