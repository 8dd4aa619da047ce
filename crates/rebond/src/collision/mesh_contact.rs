//! Contacts of convex shapes with triangle meshes and heightfields: the midphase (the mesh's
//! hierarchy, or the heightfield's grid) finds the triangles near the shape, each triangle gives
//! a manifold (`triangle_contact`), and the manifolds that share a normal are merged into one of
//! at most four points.
//!
//! Merging is what makes a mesh behave like one surface for the solver: a box resting on a floor
//! of many triangles gets one manifold of four points (chosen by where they lie on the floor, so
//! the same corners are kept from step to step) instead of a manifold per triangle under it. Each
//! point's id mixes the triangle's index into the id of its features, so warm starting follows a
//! point as long as it stays on its triangle; the one point of a rounded shape (a sphere's lowest
//! point) keeps its id across triangles, so a rolling ball keeps its impulse. Two such points far
//! apart are two places where the shape touches (a cylinder across a ridge, touching with both
//! ends of its rim), and both are kept.
//!
//! Triangles of different materials ([`crate::shape::TriMesh::with_materials`]) never merge, so
//! each manifold has one material: a box across the border of ice and rubber gets a manifold on
//! each. A merged manifold names the triangle of its deepest point.

use super::feature_contact::{is_vertex_of_b_on_face, DEEPEST_POINT_ID};
use super::manifold::{ContactPoint, Manifold};
use super::reduction::{reduce_contacts_on_face, Surface};
use super::triangle_contact::{collide_triangle_from, TriangleSimplex};
use crate::math::{Aabb, Pose, Vec3};
use crate::shape::{Shape, Triangle, ACTIVE_EDGE_ANGLE};

/// Manifolds whose normals are within this cosine (1.8°) merge into one: coplanar triangles, and
/// the gentle bends whose edges are not active (under 5°), give one surface.
const MERGE_COSINE: f32 = 0.9995;

/// Two points of one merged manifold closer than this, metres, are one point (the deeper is kept):
/// a point on an edge shared by two triangles is found by both.
const SAME_POINT_DISTANCE: f32 = 1.0e-3;

/// A mesh or heightfield placed in the world.
pub(crate) struct PlacedMesh<'a> {
    /// The shape: [`Shape::TriMesh`] or [`Shape::HeightField`].
    pub shape: &'a Shape,
    /// Its pose.
    pub pose: &'a Pose,
}

/// One group of manifolds with a shared normal, its points in `MeshScratch::points`.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Group {
    normal: Vec3,
    start: usize,
    len: usize,
    /// The triangle of its deepest point.
    triangle: u32,
}

/// The GJK simplex a query left for one triangle (by index), to start the next from.
pub type KeptSimplex = (u32, TriangleSimplex);

/// Scratch space of mesh contacts, kept from query to query so that a steady step allocates
/// nothing.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MeshScratch {
    triangles: Vec<u32>,
    manifolds: Vec<(u32, Manifold)>,
    groups: Vec<Group>,
    points: Vec<ContactPoint>,
    /// What the last query of the same part left, by triangle index (filled by the caller).
    pub(crate) previous_simplices: Vec<KeptSimplex>,
    /// What this query leaves, by triangle index.
    simplices: Vec<KeptSimplex>,
}

impl MeshScratch {
    /// The manifolds between `mesh` and the convex `part` at `part_pose` (normals from the mesh
    /// toward the part), each handed to `emit(group, manifold, simplices)` with `group` counting
    /// the merged manifolds from 0, in a deterministic order: triangles by index, groups by their
    /// first triangle. Each triangle's GJK query starts from its simplex in `previous_simplices`,
    /// and `simplices` holds those this query leaves, by triangle index (passed with every group).
    /// `reach` (m, within `margin`) is how far the two can close in the step.
    pub(crate) fn collide(
        &mut self,
        mesh: &PlacedMesh,
        part: &Shape,
        part_pose: &Pose,
        margin: f32,
        reach: f32,
        mut emit: impl FnMut(u32, Manifold, &[KeptSimplex]),
    ) {
        self.simplices.clear();
        if part.is_triangulated() || !part.is_bounded() {
            return;
        }
        let local_pose = mesh.pose.inverse().mul_pose(part_pose);
        let bounds = part.aabb(&local_pose);
        let bounds = Aabb::new(
            bounds.min - Vec3::splat(margin),
            bounds.max + Vec3::splat(margin),
        );
        self.triangles.clear();
        mesh.shape
            .triangles_in(&bounds, |index| self.triangles.push(index));
        // A mesh's hierarchy gives its triangles in leaf order.
        self.triangles.sort_unstable();
        let one_sided = matches!(mesh.shape, Shape::HeightField(_));
        self.manifolds.clear();
        // Both lists run by triangle index: the previous simplices are walked alongside.
        let mut previous = self.previous_simplices.iter().peekable();
        for &index in &self.triangles {
            let Some(local) = mesh.shape.triangle(index) else {
                continue;
            };
            while previous.next_if(|(kept, _)| *kept < index).is_some() {}
            let mut simplex = previous
                .next_if(|(kept, _)| *kept == index)
                .map_or_else(TriangleSimplex::default, |(_, simplex)| *simplex);
            let triangle = Triangle {
                vertices: local
                    .vertices
                    .map(|vertex| mesh.pose.transform_point(vertex)),
                edge_flags: local.edge_flags,
            };
            let manifold =
                collide_triangle_from(&triangle, one_sided, part, part_pose, margin, &mut simplex);
            if !simplex.is_empty() {
                self.simplices.push((index, simplex));
            }
            if let Some(manifold) = manifold {
                self.manifolds.push((index, manifold));
            }
        }
        // The one deepest point of a rounded shape, found by two triangles of a merged surface,
        // lies under the shape within the sideways reach of a normal bent by up to
        // `ACTIVE_EDGE_ANGLE` (`triangle_contact::holds_foot`), at most the shape's radius away.
        let same_deepest = part.bounding_radius() * ACTIVE_EDGE_ANGLE.sin() + SAME_POINT_DISTANCE;
        self.merge(same_deepest, |triangle| mesh.shape.material_index(triangle));
        let tangent_axis = mesh.pose.transform_vector(Vec3::X);
        for (group_index, group) in (0u32..).zip(&self.groups) {
            let points = &self.points[group.start..group.start + group.len];
            let normal = group.normal;
            let tangent = (tangent_axis - normal * normal.dot(tangent_axis))
                .try_normalize()
                .unwrap_or_else(|| normal.any_orthonormal_vector());
            let mut manifold =
                reduce_contacts_on_face(normal, tangent, points, Surface::Bent { reach });
            manifold.triangle = Some(group.triangle);
            emit(group_index, manifold, &self.simplices);
        }
    }

    /// Groups `manifolds` by normal into `groups` and `points`, giving each point an id with its
    /// triangle's index mixed in and merging points found twice: points within
    /// [`SAME_POINT_DISTANCE`], and deepest points within `same_deepest`, m (of a rounded shape:
    /// one point, whose id is kept); a deepest point farther from the group's is a point of its
    /// own, with its triangle's index mixed into its id. Only manifolds of triangles of the same
    /// `material` index merge.
    fn merge(&mut self, same_deepest: f32, material: impl Fn(u32) -> Option<u32>) {
        self.groups.clear();
        self.points.clear();
        let Self {
            manifolds,
            groups,
            points,
            ..
        } = self;
        // Each group's points stay together: groups are filled one after the other.
        let mut taken = 0;
        while taken < manifolds.len() {
            let normal = manifolds[taken].1.normal;
            let surface = material(manifolds[taken].0);
            let merges = |(triangle, manifold): &(u32, Manifold)| {
                manifold.normal.dot(normal) >= MERGE_COSINE && material(*triangle) == surface
            };
            let start = points.len();
            let (mut deepest_triangle, mut deepest) = (manifolds[taken].0, f32::INFINITY);
            for entry @ (triangle, manifold) in manifolds.iter() {
                if !merges(entry) || manifold.is_empty() {
                    continue;
                }
                let depth = manifold.deepest_separation();
                if depth < deepest {
                    (deepest_triangle, deepest) = (*triangle, depth);
                }
                for point in manifold.points() {
                    // A vertex of the shape keeps its id whichever triangle finds it, so that a
                    // corner or rim point resting on a triangle's edge keeps its warm start as
                    // it sways from one side to the other.
                    let id = if (point.id == DEEPEST_POINT_ID
                        && keeps_deepest_id(&points[start..], point, same_deepest))
                        || is_vertex_of_b_on_face(point.id)
                    {
                        point.id
                    } else {
                        mix_id(*triangle, point.id)
                    };
                    add_point(points, start, ContactPoint { id, ..*point });
                }
            }
            if points.len() > start {
                groups.push(Group {
                    normal,
                    start,
                    len: points.len() - start,
                    triangle: deepest_triangle,
                });
            }
            // Mark the merged manifolds as used by emptying them, then find the next unused one.
            for entry in manifolds.iter_mut() {
                if merges(entry) {
                    entry.1 = Manifold::new(entry.1.normal);
                }
            }
            while taken < manifolds.len() && manifolds[taken].1.is_empty() {
                taken += 1;
            }
        }
    }
}

/// Whether the deepest point `point` keeps [`DEEPEST_POINT_ID`] in the group of `points`: it is
/// the group's first deepest point, or its deepest point found again (within `same_deepest` of
/// it), which [`add_point`] then merges with it.
fn keeps_deepest_id(points: &[ContactPoint], point: &ContactPoint, same_deepest: f32) -> bool {
    let mut deepest = points.iter().filter(|other| other.id == DEEPEST_POINT_ID);
    deepest
        .all(|other| other.position.distance_squared(point.position) <= same_deepest * same_deepest)
}

/// Adds `point` to the group starting at `start`, or, when the group holds a point within
/// [`SAME_POINT_DISTANCE`] or of the same id, keeps the deeper of the two.
fn add_point(points: &mut Vec<ContactPoint>, start: usize, point: ContactPoint) {
    let twin = points[start..].iter_mut().find(|other| {
        other.id == point.id
            || other.position.distance_squared(point.position)
                < SAME_POINT_DISTANCE * SAME_POINT_DISTANCE
    });
    match twin {
        Some(twin) if point.separation < twin.separation => *twin = point,
        Some(_) => {}
        None => points.push(point),
    }
}

/// A point id made unique across triangles: the feature id and the triangle's index mixed by a
/// multiplicative hash (Knuth's 2654435761), never [`DEEPEST_POINT_ID`]. Two points of one
/// manifold sharing an id would only share a warm start.
fn mix_id(triangle: u32, id: u32) -> u32 {
    let mixed = id ^ triangle.wrapping_add(1).wrapping_mul(2_654_435_761);
    if mixed == DEEPEST_POINT_ID {
        0
    } else {
        mixed
    }
}
