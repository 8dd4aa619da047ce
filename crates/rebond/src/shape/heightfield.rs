//! Heightfields: a grid of heights, solid below its surface, shared between clones through an
//! `Arc`. Its triangles are found from the grid directly, with no hierarchy.

use std::sync::Arc;

use super::triangle::{edge_flags, Triangle};
use super::trimesh::placed_bounds;
use crate::error::{check_finite, check_length, check_named, check_size, Error, ErrorKind, Result};
use crate::limits::MAX_SIZE;
use crate::math::{Aabb, Pose, Vec3};

/// How far below its lowest sample a heightfield's bounding box reaches at least, metres: the
/// box reaches down by the height range, or by this, whichever is more, so that bodies pushed
/// below the surface are still found and pushed back up.
pub const MIN_SOLID_DEPTH: f32 = 1.0;

/// A grid of heights in the body frame: `rows × cols` samples, row `i` along +Z and column `j`
/// along +X, sample `(i, j)` at `x = (j / (cols − 1) − ½) · sx`, `z = (i / (rows − 1) − ½) · sz`,
/// `y = heights[i][j] · sy`. Solid below the surface. Cloning shares the heights.
///
/// Cell `(i, j)` (between rows `i`, `i + 1` and columns `j`, `j + 1`) is split along its diagonal
/// from sample `(i, j)` to `(i + 1, j + 1)` into triangles `2 (i (cols − 1) + j)` and the next.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct HeightField {
    #[cfg_attr(feature = "serde", serde(with = "crate::state::shared"))]
    data: Arc<HeightData>,
}

#[derive(Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct HeightData {
    /// Row-major heights, before scaling.
    heights: Vec<f32>,
    rows: usize,
    cols: usize,
    scale: Vec3,
    bounds: Aabb,
    /// Each triangle's edge flags, found once when the heightfield is made: fetching a triangle
    /// is the inner loop of its contacts, and the flags' angles cost more than the rest of it.
    edge_flags: Vec<u8>,
}

impl HeightField {
    /// A heightfield of `heights` rows (all of one length, at least 2 × 2, finite) scaled by
    /// `scale` (metres; every component positive). Errors name `heights`, `heights[i]`,
    /// `heights[i][j]` or `scale`.
    pub fn new(heights: &[Vec<f32>], scale: Vec3) -> Result<Self> {
        for (axis, name) in ["scale[0]", "scale[1]", "scale[2]"].iter().enumerate() {
            check_size(name, scale[axis])?;
        }
        if heights.len() < 2 {
            return Err(Error::new("heights", ErrorKind::InvalidHeightField));
        }
        let cols = heights[0].len();
        let mut flat = Vec::with_capacity(heights.len() * cols);
        for (i, row) in heights.iter().enumerate() {
            if row.len() != cols || cols < 2 {
                return Err(Error::new(
                    format!("heights[{i}]"),
                    ErrorKind::InvalidHeightField,
                ));
            }
            for (j, &height) in row.iter().enumerate() {
                check_named(
                    |field| {
                        check_finite(field, height)?;
                        check_length(field, Vec3::new(0.0, height * scale.y, 0.0), MAX_SIZE)
                    },
                    || format!("heights[{i}][{j}]"),
                )?;
                flat.push(height);
            }
        }
        let (low, high) = flat
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(low, high), &h| {
                (low.min(h), high.max(h))
            });
        let half = 0.5 * scale;
        let (low, high) = (low * scale.y, high * scale.y);
        let depth = (high - low).max(MIN_SOLID_DEPTH);
        let bounds = Aabb::new(
            Vec3::new(-half.x, low - depth, -half.z),
            Vec3::new(half.x, high, half.z),
        );
        if !(bounds.min.is_finite() && bounds.max.is_finite()) {
            return Err(Error::new("scale", ErrorKind::UnrepresentableSize));
        }
        let mut data = HeightData {
            heights: flat,
            rows: heights.len(),
            cols,
            scale,
            bounds,
            edge_flags: Vec::new(),
        };
        data.edge_flags = (0..data.triangle_count())
            .map(|index| data.computed_edge_flags(index))
            .collect();
        Ok(Self {
            data: Arc::new(data),
        })
    }

    /// Checks a decoded heightfield: it is the one [`HeightField::new`] builds from its own
    /// heights and scale.
    #[cfg(feature = "serde")]
    pub(crate) fn check_decoded(&self) -> std::result::Result<(), String> {
        let data = &self.data;
        if data.cols < 2 || data.heights.len() != data.rows.saturating_mul(data.cols) {
            return Err("a heightfield's grid does not hold its heights".to_owned());
        }
        let rows: Vec<Vec<f32>> = data
            .heights
            .chunks(data.cols)
            .map(<[f32]>::to_vec)
            .collect();
        match HeightField::new(&rows, data.scale) {
            Ok(rebuilt) if rebuilt == *self => Ok(()),
            Ok(_) => Err("a heightfield differs from the one its heights build".to_owned()),
            Err(error) => Err(error.to_string()),
        }
    }

    /// Number of rows (samples along Z).
    pub fn rows(&self) -> usize {
        self.data.rows
    }

    /// Number of columns (samples along X).
    pub fn cols(&self) -> usize {
        self.data.cols
    }

    /// The scale `[sx, sy, sz]`, metres.
    pub fn scale(&self) -> Vec3 {
        self.data.scale
    }

    /// Sample `(i, j)` in the body frame, or `None` outside the grid.
    pub fn sample(&self, i: usize, j: usize) -> Option<Vec3> {
        self.data.sample(i, j)
    }

    /// The heights before scaling, row-major, `rows × cols`: what [`HeightField::new`] was
    /// given.
    #[cfg(feature = "serde")]
    pub(crate) fn heights(&self) -> &[f32] {
        &self.data.heights
    }

    /// Number of triangles, two a cell.
    pub fn triangle_count(&self) -> u32 {
        self.data.triangle_count()
    }

    /// Triangle `index` in the body frame (front normal up), with edge flags from its
    /// neighbours, or `None` past the end.
    pub fn triangle(&self, index: u32) -> Option<Triangle> {
        let corners = self.data.corners(index)?;
        Some(Triangle {
            vertices: corners,
            edge_flags: self.data.edge_flags.get(index as usize).copied()?,
        })
    }

    /// The surface's height (body frame, metres) above the point `(x, z)` of the body frame, or
    /// `None` outside the grid: the plane of the triangle of the cell holding it.
    pub fn height_at(&self, x: f32, z: f32) -> Option<f32> {
        let data = &self.data;
        let u = (x / data.scale.x + 0.5) * (data.cols - 1) as f32;
        let v = (z / data.scale.z + 0.5) * (data.rows - 1) as f32;
        let inside = |t: f32, samples: usize| (0.0..=(samples - 1) as f32).contains(&t);
        if !(inside(u, data.cols) && inside(v, data.rows)) {
            return None;
        }
        let j = (u as usize).min(data.cols - 2);
        let i = (v as usize).min(data.rows - 2);
        let (fu, fv) = (u - j as f32, v - i as f32);
        let h = |di: usize, dj: usize| data.heights[(i + di) * data.cols + j + dj];
        // Split along the diagonal from (i, j) to (i + 1, j + 1): fv ≥ fu holds triangle 0.
        let height = if fv >= fu {
            h(0, 0) + fv * (h(1, 0) - h(0, 0)) + fu * (h(1, 1) - h(1, 0))
        } else {
            h(0, 0) + fu * (h(0, 1) - h(0, 0)) + fv * (h(1, 1) - h(0, 1))
        };
        Some(height * data.scale.y)
    }

    /// Whether `point` (body frame) lies in the solid: over the grid and on or below the
    /// surface.
    pub fn is_below(&self, point: Vec3) -> bool {
        self.height_at(point.x, point.z)
            .is_some_and(|height| point.y <= height)
    }

    /// The box around the heightfield in the body frame: its samples, and the solid below them
    /// down to the height range (at least [`MIN_SOLID_DEPTH`]) under the lowest sample.
    pub fn local_bounds(&self) -> Aabb {
        self.data.bounds
    }

    /// The world box of the heightfield at `pose`.
    pub fn aabb(&self, pose: &Pose) -> Aabb {
        placed_bounds(&self.data.bounds, pose)
    }

    /// The cells under `bounds` (body frame) as ranges of rows and columns, `None` when none is.
    fn cells_under(&self, bounds: &Aabb) -> Option<([usize; 2], [usize; 2])> {
        let data = &self.data;
        if bounds.min.y > data.bounds.max.y {
            return None;
        }
        let span = |low: f32, high: f32, size: f32, samples: usize| {
            let cells = (samples - 1) as f32;
            let first = ((low / size + 0.5) * cells).floor().max(0.0);
            let last = ((high / size + 0.5) * cells).floor().min(cells - 1.0);
            (first <= last).then_some([first as usize, last as usize])
        };
        let columns = span(bounds.min.x, bounds.max.x, data.scale.x, data.cols)?;
        let rows = span(bounds.min.z, bounds.max.z, data.scale.z, data.rows)?;
        Some((rows, columns))
    }

    /// Calls `visit(k)` for each triangle `k` over the part of `bounds` (body frame) within the
    /// grid, and not wholly below it, row by row, so in increasing order.
    pub fn triangles_in(&self, bounds: &Aabb, mut visit: impl FnMut(u32)) {
        let Some(([first_row, last_row], [first_col, last_col])) = self.cells_under(bounds) else {
            return;
        };
        let cells_per_row = self.data.cols - 1;
        for i in first_row..=last_row {
            for j in first_col..=last_col {
                for half in 0..2 {
                    let index = (2 * (i * cells_per_row + j) + half) as u32;
                    let Some(triangle) = self.triangle(index) else {
                        continue;
                    };
                    let [a, b, c] = triangle.vertices;
                    // Triangles above the box count too: the solid below them holds it.
                    if bounds.min.y <= a.y.max(b.y).max(c.y) {
                        visit(index);
                    }
                }
            }
        }
    }

    /// Bytes of memory the heightfield holds: heights and edge flags.
    pub fn heap_bytes(&self) -> usize {
        self.data.heights.capacity() * std::mem::size_of::<f32>()
            + self.data.edge_flags.capacity()
            + std::mem::size_of::<HeightData>()
    }

    /// Whether `self` and `other` share one grid (a clone of each other).
    pub fn shares_geometry(&self, other: &HeightField) -> bool {
        Arc::ptr_eq(&self.data, &other.data)
    }
}

impl HeightData {
    fn sample(&self, i: usize, j: usize) -> Option<Vec3> {
        if i >= self.rows || j >= self.cols {
            return None;
        }
        let height = self.heights[i * self.cols + j];
        Some(Vec3::new(
            (j as f32 / (self.cols - 1) as f32 - 0.5) * self.scale.x,
            height * self.scale.y,
            (i as f32 / (self.rows - 1) as f32 - 0.5) * self.scale.z,
        ))
    }

    fn triangle_count(&self) -> u32 {
        ((self.rows - 1) * (self.cols - 1) * 2) as u32
    }

    /// Sample `(i + di, j + dj)` for the cell `(i, j)` holding triangle `index`, or `None` outside
    /// the grid.
    fn offset_sample(&self, index: u32, di: isize, dj: isize) -> Option<Vec3> {
        let cell = index as usize / 2;
        let cells_per_row = self.cols - 1;
        let (i, j) = (
            (cell / cells_per_row) as isize + di,
            (cell % cells_per_row) as isize + dj,
        );
        (i >= 0 && j >= 0)
            .then(|| self.sample(i as usize, j as usize))
            .flatten()
    }

    /// The corners of triangle `index`, counter-clockwise about +Y: (i, j) → (i + 1, j) →
    /// (i + 1, j + 1) for even indices, (i, j) → (i + 1, j + 1) → (i, j + 1) for odd ones; `None`
    /// past the end.
    fn corners(&self, index: u32) -> Option<[Vec3; 3]> {
        let s = |di, dj| self.offset_sample(index, di, dj);
        if index % 2 == 0 {
            Some([s(0, 0)?, s(1, 0)?, s(1, 1)?])
        } else {
            Some([s(0, 0)?, s(1, 1)?, s(0, 1)?])
        }
    }

    /// The edge flags of triangle `index` from the corners of its neighbours across its edges
    /// (0 past the end).
    fn computed_edge_flags(&self, index: u32) -> u8 {
        let Some(corners) = self.corners(index) else {
            return 0;
        };
        let s = |di, dj| self.offset_sample(index, di, dj);
        let across = if index % 2 == 0 {
            [s(0, -1), s(2, 1), s(0, 1)]
        } else {
            [s(1, 0), s(1, 2), s(-1, 0)]
        };
        let normal = (corners[1] - corners[0])
            .cross(corners[2] - corners[0])
            .normalize_or_zero();
        (0..3).zip(across).fold(0, |flags, (edge, neighbour)| {
            flags | edge_flags(&corners, normal, edge, neighbour)
        })
    }
}
