//! Convex hull of a point cloud. PLACEHOLDER: being replaced by a full implementation.

use crate::error::{Error, ErrorKind, Result};
use crate::mass::MassProperties;
use crate::math::{Aabb, Pose, Vec3};

/// A planar face of a hull.
#[derive(Debug, Clone, PartialEq)]
pub struct HullFace {
    /// Unit outward normal.
    pub normal: Vec3,
    /// Plane offset: `normal · p = offset` on the face.
    pub offset: f32,
    /// Vertex indices, counter-clockwise seen from outside.
    pub vertices: Vec<u32>,
}

/// An edge of a hull between two faces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HullEdge {
    /// Vertex indices of the two ends.
    pub vertices: [u32; 2],
    /// The two faces that meet at the edge.
    pub faces: [u32; 2],
}

/// The convex hull of a point cloud.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvexHull {
    vertices: Vec<Vec3>,
    faces: Vec<HullFace>,
    edges: Vec<HullEdge>,
}

impl ConvexHull {
    /// The hull of `points`.
    pub fn new(points: &[Vec3]) -> Result<Self> {
        if points.len() < 4 {
            return Err(Error::new(
                "points",
                ErrorKind::DegenerateHull("fewer than 4 points"),
            ));
        }
        Ok(Self {
            vertices: points.to_vec(),
            faces: Vec::new(),
            edges: Vec::new(),
        })
    }

    /// Hull vertices.
    pub fn vertices(&self) -> &[Vec3] {
        &self.vertices
    }

    /// Hull faces.
    pub fn faces(&self) -> &[HullFace] {
        &self.faces
    }

    /// Hull edges.
    pub fn edges(&self) -> &[HullEdge] {
        &self.edges
    }

    /// Mass properties.
    pub fn mass_properties(&self, _density: f32) -> MassProperties {
        MassProperties::ZERO
    }

    /// World bounding box.
    pub fn aabb(&self, pose: &Pose) -> Aabb {
        let mut bounds = Aabb::new(Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
        for vertex in &self.vertices {
            let point = pose.transform_point(*vertex);
            bounds = bounds.union(&Aabb::new(point, point));
        }
        bounds
    }

    /// Support point.
    pub fn support(&self, direction: Vec3) -> Vec3 {
        self.vertices
            .iter()
            .copied()
            .max_by(|a, b| a.dot(direction).total_cmp(&b.dot(direction)))
            .unwrap_or(Vec3::ZERO)
    }
}
