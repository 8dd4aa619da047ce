//! Steps 1 and 2 of building a hull: weld the points, snap them to the exact grid, and run
//! quickhull there on exact integer orientation tests.

use std::collections::BTreeMap;

use glam::DVec3;

use super::{degenerate, inconsistent, GRID_CELLS, MAGNITUDE_TOLERANCE, RELATIVE_TOLERANCE};
use crate::error::Result;
use crate::math::Vec3;

/// The input points, welded, in `f64` and on the exact grid.
pub(super) struct Cloud {
    /// Coordinates, metres, in input order; each farther than the tolerance from the others.
    pub(super) positions: Vec<DVec3>,
    /// The same points snapped to the grid.
    pub(super) grid: Vec<[i64; 3]>,
    /// Grid cells per metre.
    pub(super) scale: f64,
    /// Distance within which a point counts as on a plane or line, metres.
    pub(super) tolerance: f64,
}

impl Cloud {
    /// Welds finite `points` (drops each point within the tolerance of an earlier kept one) and
    /// snaps the rest to the grid.
    pub(super) fn new(points: &[Vec3]) -> Result<Self> {
        let positions: Vec<DVec3> = points.iter().map(|point| point.as_dvec3()).collect();
        let (min, max) = positions.iter().fold(
            (DVec3::INFINITY, DVec3::NEG_INFINITY),
            |(min, max), point| (min.min(*point), max.max(*point)),
        );
        let extent = (max - min).max_element();
        if extent <= 0.0 {
            return Err(degenerate("all points coincide"));
        }
        let magnitude = min.abs().max(max.abs()).max_element();
        let tolerance = (RELATIVE_TOLERANCE * extent).max(MAGNITUDE_TOLERANCE * magnitude);
        // Kept points go in buckets of side `tolerance` (at most 1e5 across), so a kept point
        // within the tolerance of a new one can only be in the 27 buckets around it.
        let bucket_of = |point: DVec3| {
            let bucket = ((point - min) / tolerance).floor();
            [bucket.x as i64, bucket.y as i64, bucket.z as i64]
        };
        let mut buckets: BTreeMap<[i64; 3], Vec<DVec3>> = BTreeMap::new();
        let mut kept = Vec::new();
        for point in positions {
            let [x, y, z] = bucket_of(point);
            let welded = (x - 1..=x + 1).any(|x| {
                (y - 1..=y + 1).any(|y| {
                    (z - 1..=z + 1).any(|z| {
                        buckets.get(&[x, y, z]).is_some_and(|near| {
                            near.iter().any(|other| other.distance(point) <= tolerance)
                        })
                    })
                })
            });
            if !welded {
                buckets.entry([x, y, z]).or_default().push(point);
                kept.push(point);
            }
        }
        let center = 0.5 * (min + max);
        let scale = GRID_CELLS / extent;
        let grid = kept
            .iter()
            .map(|point| {
                let cell = ((*point - center) * scale).round();
                [cell.x as i64, cell.y as i64, cell.z as i64]
            })
            .collect();
        Ok(Self {
            positions: kept,
            grid,
            scale,
            tolerance,
        })
    }
}

/// An exact vector of grid differences or normals.
type Exact = [i128; 3];

fn difference(a: [i64; 3], b: [i64; 3]) -> Exact {
    [
        i128::from(a[0]) - i128::from(b[0]),
        i128::from(a[1]) - i128::from(b[1]),
        i128::from(a[2]) - i128::from(b[2]),
    ]
}

fn cross(a: Exact, b: Exact) -> Exact {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: Exact, b: Exact) -> i128 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn to_f64(a: Exact) -> DVec3 {
    DVec3::new(a[0] as f64, a[1] as f64, a[2] as f64)
}

/// Four points spanning a tetrahedron: the farthest pair among the axis extremes, the point
/// farthest from their line, the point farthest from the plane of the three. Fails when one of
/// these distances is within the tolerance (coincident, collinear or coplanar cloud).
pub(super) fn initial_simplex(cloud: &Cloud) -> Result<[u32; 4]> {
    let grid = &cloud.grid;
    let tolerance = cloud.tolerance * cloud.scale;
    let mut extremes = [0usize; 6];
    for (index, point) in grid.iter().enumerate() {
        for axis in 0..3 {
            if point[axis] < grid[extremes[2 * axis]][axis] {
                extremes[2 * axis] = index;
            }
            if point[axis] > grid[extremes[2 * axis + 1]][axis] {
                extremes[2 * axis + 1] = index;
            }
        }
    }
    let (mut a, mut b, mut widest) = (extremes[0], extremes[1], 0);
    for (k, &first) in extremes.iter().enumerate() {
        for &second in &extremes[k + 1..] {
            let span = difference(grid[second], grid[first]);
            if dot(span, span) > widest {
                (a, b, widest) = (first, second, dot(span, span));
            }
        }
    }
    if (widest as f64).sqrt() <= tolerance {
        return Err(degenerate("all points coincide"));
    }
    let axis = difference(grid[b], grid[a]);
    let (mut c, mut farthest) = (a, 0.0);
    for (index, point) in grid.iter().enumerate() {
        let area = to_f64(cross(axis, difference(*point, grid[a]))).length();
        if area > farthest {
            (c, farthest) = (index, area);
        }
    }
    if farthest <= tolerance * to_f64(axis).length() {
        return Err(degenerate("all points are collinear"));
    }
    let normal = cross(axis, difference(grid[c], grid[a]));
    let (mut d, mut highest) = (a, 0);
    for (index, point) in grid.iter().enumerate() {
        let height = dot(normal, difference(*point, grid[a])).abs();
        if height > highest {
            (d, highest) = (index, height);
        }
    }
    if highest as f64 <= tolerance * to_f64(normal).length() {
        return Err(degenerate("all points are coplanar"));
    }
    Ok([a as u32, b as u32, c as u32, d as u32])
}

/// A triangle of the hull under construction.
struct Triangle {
    /// Point indices, counter-clockwise seen from outside.
    vertices: [u32; 3],
    /// Outward normal `(v1 − v0) × (v2 − v0)`, grid units².
    normal: Exact,
    /// The triangle across edge `k`, which runs from `vertices[k]` to `vertices[(k + 1) % 3]`.
    neighbors: [usize; 3],
    /// Points strictly above the triangle's plane that no earlier triangle claimed.
    outside: Vec<u32>,
    /// False once the triangle is replaced.
    alive: bool,
    /// The pass that last tested the triangle against an eye point.
    visit: usize,
    /// Whether that pass found the eye strictly above it.
    visible: bool,
}

/// A triangle of the finished exact hull.
pub(super) struct Facet {
    /// Point indices, counter-clockwise seen from outside.
    pub(super) vertices: [u32; 3],
    /// The facet across edge `k` (from `vertices[k]` to `vertices[(k + 1) % 3]`).
    pub(super) neighbors: [usize; 3],
    /// Unit outward normal.
    pub(super) normal: DVec3,
    /// Twice the area in grid units², a weight.
    pub(super) area: f64,
}

/// Quickhull on the grid: repeatedly take the farthest point outside a triangle, remove every
/// triangle that sees it and fan new triangles from it to the horizon.
pub(super) struct Quickhull<'a> {
    grid: &'a [[i64; 3]],
    triangles: Vec<Triangle>,
}

impl<'a> Quickhull<'a> {
    /// The exact triangulated hull of `grid`, starting from a non-degenerate `simplex`.
    pub(super) fn build(grid: &'a [[i64; 3]], simplex: [u32; 4]) -> Result<Vec<Facet>> {
        let mut hull = Self {
            grid,
            triangles: Vec::new(),
        };
        hull.start(simplex)?;
        hull.expand()?;
        Ok(hull.facets())
    }

    /// `normal · (point − v0)`: positive strictly above the triangle's plane, exact.
    fn height(&self, triangle: usize, point: u32) -> i128 {
        let triangle = &self.triangles[triangle];
        dot(
            triangle.normal,
            difference(
                self.grid[point as usize],
                self.grid[triangle.vertices[0] as usize],
            ),
        )
    }

    fn normal(&self, [a, b, c]: [u32; 3]) -> Exact {
        let origin = self.grid[a as usize];
        cross(
            difference(self.grid[b as usize], origin),
            difference(self.grid[c as usize], origin),
        )
    }

    fn push(&mut self, vertices: [u32; 3], neighbors: [usize; 3]) {
        let normal = self.normal(vertices);
        self.triangles.push(Triangle {
            vertices,
            normal,
            neighbors,
            outside: Vec::new(),
            alive: true,
            visit: 0,
            visible: false,
        });
    }

    /// The four faces of the simplex, facing away from its fourth corner, and every other point
    /// handed to the first face it lies strictly above.
    fn start(&mut self, simplex: [u32; 4]) -> Result<()> {
        for [i, j, k, omitted] in [[1, 2, 3, 0], [0, 2, 3, 1], [0, 1, 3, 2], [0, 1, 2, 3]] {
            let mut corners = [simplex[i], simplex[j], simplex[k]];
            let opposite = difference(
                self.grid[simplex[omitted] as usize],
                self.grid[corners[0] as usize],
            );
            if dot(self.normal(corners), opposite) > 0 {
                corners.swap(1, 2);
            }
            self.push(corners, [0; 3]);
        }
        let mut directed = BTreeMap::new();
        for (index, triangle) in self.triangles.iter().enumerate() {
            for k in 0..3 {
                directed.insert(
                    (triangle.vertices[k], triangle.vertices[(k + 1) % 3]),
                    index,
                );
            }
        }
        for triangle in &mut self.triangles {
            for k in 0..3 {
                let reverse = (triangle.vertices[(k + 1) % 3], triangle.vertices[k]);
                triangle.neighbors[k] = *directed.get(&reverse).ok_or_else(inconsistent)?;
            }
        }
        for point in 0..self.grid.len() as u32 {
            if !simplex.contains(&point) {
                if let Some(triangle) = (0..4).find(|&t| self.height(t, point) > 0) {
                    self.triangles[triangle].outside.push(point);
                }
            }
        }
        Ok(())
    }

    /// The point of a live triangle's outside set farthest above it (lowest index on ties).
    fn eye(&self, triangle: usize) -> Option<u32> {
        if !self.triangles[triangle].alive {
            return None;
        }
        let mut best: Option<(u32, i128)> = None;
        for &point in &self.triangles[triangle].outside {
            let height = self.height(triangle, point);
            if best.is_none_or(|(_, highest)| height > highest) {
                best = Some((point, height));
            }
        }
        best.map(|(point, _)| point)
    }

    /// Adds outside points one by one until no triangle has any.
    fn expand(&mut self) -> Result<()> {
        let mut pending: Vec<usize> = (0..self.triangles.len()).collect();
        let mut pass = 0;
        while let Some(start) = pending.pop() {
            let Some(eye) = self.eye(start) else {
                continue;
            };
            pass += 1;
            let visible = self.visible_from(start, eye, pass);
            let horizon = self.horizon(&visible, pass)?;
            let first = self.triangles.len();
            let count = horizon.len();
            for (k, &(from, to, outer)) in horizon.iter().enumerate() {
                self.push(
                    [from, to, eye],
                    [
                        outer,
                        first + (k + 1) % count,
                        first + (k + count - 1) % count,
                    ],
                );
                let vertices = self.triangles[outer].vertices;
                let slot = (0..3)
                    .find(|&j| vertices[j] == to && vertices[(j + 1) % 3] == from)
                    .ok_or_else(inconsistent)?;
                self.triangles[outer].neighbors[slot] = first + k;
            }
            let mut orphans = Vec::new();
            for &triangle in &visible {
                self.triangles[triangle].alive = false;
                orphans.append(&mut self.triangles[triangle].outside);
            }
            for point in orphans {
                if point == eye {
                    continue;
                }
                if let Some(triangle) = (first..first + count).find(|&t| self.height(t, point) > 0)
                {
                    self.triangles[triangle].outside.push(point);
                }
            }
            pending
                .extend((first..first + count).filter(|&t| !self.triangles[t].outside.is_empty()));
        }
        Ok(())
    }

    /// The triangles that see `eye` strictly above their plane, found by flooding from `start`.
    fn visible_from(&mut self, start: usize, eye: u32, pass: usize) -> Vec<usize> {
        self.triangles[start].visit = pass;
        self.triangles[start].visible = true;
        let mut visible = vec![start];
        let mut next = 0;
        while next < visible.len() {
            let neighbors = self.triangles[visible[next]].neighbors;
            next += 1;
            for neighbor in neighbors {
                if self.triangles[neighbor].visit == pass {
                    continue;
                }
                let sees = self.height(neighbor, eye) > 0;
                self.triangles[neighbor].visit = pass;
                self.triangles[neighbor].visible = sees;
                if sees {
                    visible.push(neighbor);
                }
            }
        }
        visible
    }

    /// The edges `(from, to, outer triangle)` between visible and hidden triangles, in order around
    /// the visible region. Exact tests make that region a disk, so the edges form one cycle.
    fn horizon(&self, visible: &[usize], pass: usize) -> Result<Vec<(u32, u32, usize)>> {
        let mut edges = Vec::new();
        for &triangle in visible {
            let triangle = &self.triangles[triangle];
            for k in 0..3 {
                let neighbor = &self.triangles[triangle.neighbors[k]];
                if !(neighbor.visit == pass && neighbor.visible) {
                    edges.push((
                        triangle.vertices[k],
                        triangle.vertices[(k + 1) % 3],
                        triangle.neighbors[k],
                    ));
                }
            }
        }
        edges.sort_unstable();
        if edges.is_empty() || edges.windows(2).any(|pair| pair[0].0 == pair[1].0) {
            return Err(inconsistent());
        }
        let mut ordered = vec![edges[0]];
        loop {
            let to = ordered[ordered.len() - 1].1;
            let next = edges
                .binary_search_by_key(&to, |edge| edge.0)
                .map_err(|_| inconsistent())?;
            if next == 0 {
                break;
            }
            if ordered.len() == edges.len() {
                return Err(inconsistent());
            }
            ordered.push(edges[next]);
        }
        if ordered.len() == edges.len() {
            Ok(ordered)
        } else {
            Err(inconsistent())
        }
    }

    /// The live triangles, renumbered.
    fn facets(self) -> Vec<Facet> {
        let alive: Vec<usize> = (0..self.triangles.len())
            .filter(|&t| self.triangles[t].alive)
            .collect();
        let mut renumber = vec![0; self.triangles.len()];
        for (index, &triangle) in alive.iter().enumerate() {
            renumber[triangle] = index;
        }
        alive
            .iter()
            .map(|&triangle| {
                let triangle = &self.triangles[triangle];
                let normal = to_f64(triangle.normal);
                Facet {
                    vertices: triangle.vertices,
                    neighbors: triangle.neighbors.map(|neighbor| renumber[neighbor]),
                    normal: normal.normalize(),
                    area: normal.length(),
                }
            })
            .collect()
    }
}
