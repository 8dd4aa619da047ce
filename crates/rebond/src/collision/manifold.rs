//! Contact manifolds: what the narrow phase hands the solver for one pair of touching shapes.

use crate::math::Vec3;

/// Most points a manifold keeps: four well-spread points hold a face resting on a face.
pub const MAX_MANIFOLD_POINTS: usize = 4;

/// One contact point between two shapes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContactPoint {
    /// World position midway between the two surfaces, metres.
    pub position: Vec3,
    /// Distance between the two surfaces along the manifold normal, metres: negative when they
    /// overlap, positive (up to the speculative margin) while they are still apart.
    pub separation: f32,
    /// Names the pair of features (vertex, edge, face) that made the point, so that the same
    /// physical point keeps its id from step to step while the bodies barely move. Unique within
    /// a manifold.
    pub id: u32,
}

/// The contact between two convex shapes A and B: one normal and up to
/// [`MAX_MANIFOLD_POINTS`] points.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Manifold {
    /// Unit world normal, pointing from shape A toward shape B.
    pub normal: Vec3,
    points: [ContactPoint; MAX_MANIFOLD_POINTS],
    count: usize,
    /// The triangle of a mesh or heightfield the manifold was found on, on whichever side the
    /// mesh is (two meshes never touch): the triangle of its deepest point, for a manifold merged
    /// from several (`mesh_contact.rs`). `None` between other shapes.
    pub triangle: Option<u32>,
}

impl Manifold {
    /// A manifold with the given normal and no points yet.
    pub fn new(normal: Vec3) -> Self {
        Self {
            normal,
            points: [ContactPoint::default(); MAX_MANIFOLD_POINTS],
            count: 0,
            triangle: None,
        }
    }

    /// Keeps only the points for which `keep` is true, in order.
    pub fn retain(&mut self, mut keep: impl FnMut(&ContactPoint) -> bool) {
        let mut kept = 0;
        for index in 0..self.count {
            let point = self.points[index];
            if keep(&point) {
                self.points[kept] = point;
                kept += 1;
            }
        }
        self.count = kept;
    }

    /// Adds a point; returns false (and drops it) when the manifold is already full.
    pub fn push(&mut self, point: ContactPoint) -> bool {
        if self.count == MAX_MANIFOLD_POINTS {
            return false;
        }
        self.points[self.count] = point;
        self.count += 1;
        true
    }

    /// The points, in the order they were added.
    pub fn points(&self) -> &[ContactPoint] {
        &self.points[..self.count]
    }

    /// The points, mutably.
    pub fn points_mut(&mut self) -> &mut [ContactPoint] {
        &mut self.points[..self.count]
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.count
    }

    /// The smallest separation of its points, metres (how deep the contact reaches); infinity
    /// with no point.
    pub fn deepest_separation(&self) -> f32 {
        self.points()
            .iter()
            .map(|point| point.separation)
            .fold(f32::INFINITY, f32::min)
    }

    /// Whether the manifold has no point.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// The same contact seen from B: the normal turns around; points and ids stay.
    #[must_use]
    pub fn flipped(mut self) -> Self {
        self.normal = -self.normal;
        self
    }

    /// The manifold with every point moved by `offset`: found about a local origin, placed back
    /// in the world.
    pub(crate) fn translated(mut self, offset: Vec3) -> Self {
        for point in self.points_mut() {
            point.position += offset;
        }
        self
    }
}
