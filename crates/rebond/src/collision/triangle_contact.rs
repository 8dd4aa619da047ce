//! Contacts of a convex shape with one triangle of a mesh or heightfield.
//!
//! A triangle is flat, so EPA would degenerate on it, and its edges are shared with neighbours, so
//! an edge normal is often a "ghost" of a surface that goes on flat. The contact is therefore
//! built in three steps:
//!
//! 1. The closest points of the triangle and of the shape's core: in closed form for a sphere, a
//!    capsule and a box (`triangle_closest`), by GJK for cylinders and hulls. When the cores
//!    overlap, or the shape lies behind a heightfield's surface, the normal is the face normal
//!    and the depth is the shape's deepest point below the triangle's plane.
//! 2. Internal edges: when the closest point of the triangle is on an edge or corner that is not
//!    active on that side (see [`Triangle`]) and the normal is not the face normal, the normal
//!    becomes the face normal, with the separation measured along it from the triangle's closest
//!    point: the neighbour across a flat or concave edge holds the shape on its own face, so the
//!    edge must not push sideways (Jolt's internal-edge removal and Box3D's triangle manifolds
//!    rest on the same idea). The deepest point then sits under the shape's closest point, and is
//!    left out when that foot lies off the triangle (the neighbour under it makes that point);
//!    a shape beside or behind the plane there gets no contact.
//!    Where the shape overlaps the triangle's plane and no point is left, the triangle still
//!    holds the shape at the point of it nearest the foot (`nearest_hold`): on a ridge too
//!    gentle for an active edge, each of its two triangles finds the shape's deepest point over
//!    the other, and without it neither would hold the shape up.
//! 3. Points: the triangle's supporting feature (its face, an edge or a corner) and the shape's
//!    are clipped against each other as for any convex pair
//!    (`feature_contact::manifold_from_features`).

use super::epa::ContactInfo;
use super::feature_contact::{
    manifold_from_features, supporting_feature, Feature, DEEPEST_POINT_ID,
};
use super::gjk::{self, Search};
use super::manifold::{ContactPoint, Manifold};
use super::triangle_closest;
use super::{LocalCore, PosedCore, SupportMap};
use crate::math::{Pose, Vec3};
use crate::shape::line::line_entry;
use crate::shape::{Shape, Triangle, ACTIVE_EDGE_ANGLE};

/// A normal within this cosine of the face normal (0.8°) is taken as the face normal: closer
/// than GJK's precision on a shape resting flat.
const FACE_NORMAL_COSINE: f32 = 0.9999;

/// A barycentric weight below this puts the closest point on the edge or corner it names:
/// relative to the triangle, so a millimetre on a 10 m triangle.
const FEATURE_WEIGHT: f32 = 1.0e-4;

/// A contact snapped to the face normal is kept when the point under the shape lies this close to
/// the triangle, metres, besides the reach of a bent normal: f32 rounding of a point on an edge.
const FOOT_TOLERANCE: f32 = 1.0e-5;

/// A triangle (in world space, for GJK) as a support map: its corner farthest along the direction.
impl SupportMap for Triangle {
    fn support(&self, direction: Vec3) -> Vec3 {
        let [a, b, c] = self.vertices;
        let (da, db, dc) = (a.dot(direction), b.dot(direction), c.dot(direction));
        if da >= db && da >= dc {
            a
        } else if db >= dc {
            b
        } else {
            c
        }
    }
}

/// The simplex a GJK query between a triangle and a shape's core (cylinders and hulls) ended
/// with, kept to start the next query between the same two from (as [`gjk::SimplexCache`] does
/// for two shapes). Each vertex is kept as the corner of the triangle and the point of the core,
/// in the shape's frame, it was made from: the triangle's supports are its corners, so placed
/// again they are points of the triangle and the core wherever the shape has moved. Resting on a
/// mesh, a shape meets the same triangles step after step: in `mesh_pile` a hull's query on a
/// triangle within reach (mostly near an edge) takes 4.3 iterations cold and 1.3 warm, a query on
/// one out of reach 2.3 cold and 1.1 warm. Empty: start cold.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TriangleSimplex {
    /// Each vertex's corner of the triangle, 0 to 2.
    corners: [u8; 4],
    /// Each vertex's point of the core, in the shape's frame.
    core_points: [Vec3; 4],
    len: u8,
}

impl TriangleSimplex {
    /// Whether no simplex is kept: the query starts cold.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Keeps `simplex`, found between `triangle` and a core in the core's frame; empty if one of
    /// its points of the triangle is not a corner.
    fn new(simplex: &gjk::Simplex, triangle: &Triangle) -> Self {
        let mut kept = Self::default();
        for (slot, point) in simplex.points().iter().enumerate() {
            let Some(corner) = triangle
                .vertices
                .iter()
                .position(|&vertex| vertex == point.a)
            else {
                return Self::default();
            };
            kept.corners[slot] = corner as u8;
            kept.core_points[slot] = point.b;
        }
        kept.len = simplex.points().len() as u8;
        kept
    }

    /// The kept vertices between `triangle` and the core now, both in the core's frame: the
    /// first `len` of the array (none when a corner index is out of range).
    fn placed(&self, triangle: &Triangle) -> ([gjk::SupportPoint; 4], usize) {
        let mut points = [gjk::SupportPoint::default(); 4];
        for (slot, point) in points.iter_mut().enumerate().take(usize::from(self.len)) {
            let Some(&a) = triangle.vertices.get(usize::from(self.corners[slot])) else {
                return (points, 0);
            };
            let b = self.core_points[slot];
            *point = gjk::SupportPoint { a, b, w: a - b };
        }
        (points, usize::from(self.len).min(4))
    }
}

/// The manifold between `triangle` (world space) and the convex `shape` at `pose` (not a
/// compound, halfspace, mesh or heightfield), with the normal from the triangle toward the shape,
/// or `None` beyond `margin`. A `one_sided` triangle (of a heightfield) is solid behind its front;
/// otherwise the side facing the shape's origin is the face that collides.
pub fn collide_triangle(
    triangle: &Triangle,
    one_sided: bool,
    shape: &Shape,
    pose: &Pose,
    margin: f32,
) -> Option<Manifold> {
    let mut simplex = TriangleSimplex::default();
    collide_triangle_from(triangle, one_sided, shape, pose, margin, &mut simplex)
}

/// [`collide_triangle`] with GJK (for a cylinder or a hull) starting from `simplex`, what the
/// last query between the same triangle and shape left, and leaving its own there (empty when
/// GJK did not run).
pub fn collide_triangle_from(
    triangle: &Triangle,
    one_sided: bool,
    shape: &Shape,
    pose: &Pose,
    margin: f32,
    simplex: &mut TriangleSimplex,
) -> Option<Manifold> {
    let front_normal = triangle.normal()?;
    let [a, _, _] = triangle.vertices;
    let front = one_sided || front_normal.dot(pose.position - a) >= 0.0;
    let face = if front { front_normal } else { -front_normal };
    let radius = shape.core_radius();
    let core = PosedCore::new(shape, pose);
    // A shape whose origin lies behind a heightfield's surface is in its solid, however deep.
    let buried = one_sided && front_normal.dot(pose.position - a) < 0.0;
    let closest = if buried {
        *simplex = TriangleSimplex::default();
        None
    } else {
        closest_cores(triangle, shape, &core, face, margin + radius, simplex)?
    };
    // Whether the deepest point lies on this triangle, so that the manifold may hold it.
    let mut deepest_here = true;
    let deepest = match closest {
        Some((on_triangle, on_shape)) => {
            let offset = on_shape - on_triangle;
            let distance = offset.length();
            let normal = offset / distance;
            let (_, weights) = triangle.closest_point(on_triangle);
            if normal.dot(face) >= FACE_NORMAL_COSINE || on_active_feature(triangle, weights, front)
            {
                ContactInfo {
                    normal,
                    separation: distance - radius,
                    point_a: on_triangle,
                    point_b: on_shape - normal * radius,
                }
            } else {
                // Snapped to the face: the deepest point sits under the shape's closest point.
                let height = face.dot(offset);
                if height <= 0.0 {
                    return None;
                }
                let surface = on_shape - face * radius;
                let foot = surface - face * face.dot(surface - a);
                deepest_here = holds_foot(triangle, foot, distance);
                ContactInfo {
                    normal: face,
                    separation: height - radius,
                    point_a: foot,
                    point_b: surface,
                }
            }
        }
        None => {
            let lowest = core.support(-face) - face * radius;
            let separation = face.dot(lowest - a);
            let foot = lowest - face * separation;
            deepest_here = holds_foot(triangle, foot, 0.0);
            ContactInfo {
                normal: face,
                separation,
                point_a: foot,
                point_b: lowest,
            }
        }
    };
    if deepest.separation > margin {
        return None;
    }
    let feature_a = triangle_feature(triangle, face, deepest.normal, deepest.point_a);
    let feature_b = supporting_feature(shape, pose, -deepest.normal);
    let mut manifold = manifold_from_features(
        &deepest,
        &feature_a,
        &feature_b,
        [0.0, radius],
        margin,
        Some(inactive_sides(triangle, face, front)),
    );
    if !deepest_here {
        manifold.retain(|point| point.id != DEEPEST_POINT_ID);
        if manifold.is_empty() && closest.is_none() {
            if let Some(point) = nearest_hold(triangle, face, shape, pose, deepest.point_a, margin)
            {
                manifold.push(point);
            }
        }
    }
    (!manifold.is_empty()).then_some(manifold)
}

/// Where the triangle holds a shape overlapping its plane whose deepest point's `foot` lies off
/// it, when nothing else does: at the triangle's point `q` nearest the foot (on its rim), the
/// shape's surface straight above or below it along the face normal, as the deepest point, or
/// `None` where the shape does not reach over `q` or is apart by more than `margin`. Across a
/// ridge (a convex bend of under `ACTIVE_EDGE_ANGLE`, whose edge is not active), the two planes
/// meet at the edge, so the depth there is the surface's: a cylinder lying across the ridge is
/// held where it crosses it. A foot off a flat or concave edge is held by the neighbour under it,
/// and this point, no deeper than that one, only joins it.
fn nearest_hold(
    triangle: &Triangle,
    face: Vec3,
    shape: &Shape,
    pose: &Pose,
    foot: Vec3,
    margin: f32,
) -> Option<ContactPoint> {
    let (nearest, _) = triangle.closest_point(foot);
    let separation = line_entry(shape, pose, nearest, face)?;
    (separation <= margin).then(|| ContactPoint {
        position: nearest + face * (0.5 * separation),
        separation,
        id: DEEPEST_POINT_ID,
    })
}

/// Whether the point `foot` of the triangle's plane, under a point of the shape `distance` from
/// the triangle, belongs to the triangle: on it, or within the sideways reach of a normal bent by
/// up to `ACTIVE_EDGE_ANGLE` (past a convex edge bent that little, neither triangle would
/// otherwise hold the shape). Off it, the neighbour under the foot makes that point.
fn holds_foot(triangle: &Triangle, foot: Vec3, distance: f32) -> bool {
    let (nearest, _) = triangle.closest_point(foot);
    let reach = distance * ACTIVE_EDGE_ANGLE.sin() + FOOT_TOLERANCE;
    nearest.distance_squared(foot) <= reach * reach
}

/// The closest points of the triangle and the shape's core when they are apart by less than
/// `limit`: `Some(Some((on_triangle, on_core)))`; `Some(None)` when the cores overlap, or the
/// core lies behind a one-sided `face` (a point below the plane); `None` when apart by more. GJK
/// starts from `simplex` and leaves its own there.
fn closest_cores(
    triangle: &Triangle,
    shape: &Shape,
    core: &PosedCore,
    face: Vec3,
    limit: f32,
    simplex: &mut TriangleSimplex,
) -> Option<Option<(Vec3, Vec3)>> {
    let found = match shape {
        Shape::Sphere(_) => {
            let (on_triangle, _) = triangle.closest_point(core.pose.position);
            Some((on_triangle, core.pose.position))
        }
        Shape::Capsule(capsule) => {
            let segment = capsule.segment().map(|end| core.pose.transform_point(end));
            triangle_closest::segment_triangle(triangle, segment, limit)?
        }
        Shape::Cuboid(cuboid) => {
            triangle_closest::box_triangle(triangle, cuboid.half_extents(), core.pose, limit)?
        }
        _ => {
            // In the shape's own frame its supports need no rotation: the triangle is turned
            // once instead of every support point.
            let pose = core.pose;
            let local = Triangle {
                vertices: triangle
                    .vertices
                    .map(|corner| pose.inverse_transform_point(corner)),
                edge_flags: triangle.edge_flags,
            };
            let toward = pose.inverse_transform_vector(face);
            let (start, len) = simplex.placed(&local);
            let searched =
                gjk::search_within(&local, &LocalCore(shape), &start[..len], toward, limit);
            // Kept beyond the limit too: the neighbours of the triangles a shape rests on are
            // mostly out of reach, and started there their next query ends at its first point.
            // A cylinder's answer within reach is not kept: its rim converges linearly, and
            // started on last step's rim points the search stops at once within
            // `gjk::CONTACT_PRECISION` with last step's normal, which lags behind a rocking rim
            // (`tests/meshes` cylinders on bumps sank up to 5.6 mm instead of 4.9 mm).
            *simplex = match (&searched, shape) {
                (Search::Beyond(reached), _) | (Search::Done(reached), Shape::ConvexHull(_)) => {
                    TriangleSimplex::new(&reached.simplex, &local)
                }
                _ => TriangleSimplex::default(),
            };
            let Search::Done(found) = searched else {
                return None;
            };
            (!found.overlapping).then(|| {
                (
                    pose.transform_point(found.point_a),
                    pose.transform_point(found.point_b),
                )
            })
        }
    };
    let Some((on_triangle, on_core)) = found else {
        return Some(None);
    };
    let offset = on_core - on_triangle;
    if offset.length_squared() > limit * limit {
        return None;
    }
    let plane_height = face.dot(on_core - triangle.vertices[0]);
    if offset.length() <= f32::EPSILON * limit.max(1.0) || plane_height < 0.0 {
        return Some(None);
    }
    Some(Some((on_triangle, on_core)))
}

/// Whether the point of the triangle with barycentric `weights` lies on an edge active on that
/// side (`front`), or on a corner one of whose edges is.
fn on_active_feature(triangle: &Triangle, weights: [f32; 3], front: bool) -> bool {
    // Weight k zero: the point is on edge (k + 1) % 3, opposite corner k.
    let on_edge = |edge: usize| weights[(edge + 2) % 3] < FEATURE_WEIGHT;
    (0..3).any(|edge| on_edge(edge) && triangle.edge_active(edge, front))
}

/// The sides of the triangle's face polygon (as [`triangle_feature`] orders it about `face`)
/// whose edges are not active on that side: bit `j` for the side from polygon vertex `j` to
/// `j + 1`.
fn inactive_sides(triangle: &Triangle, face: Vec3, front: bool) -> u8 {
    let [a, b, c] = triangle.vertices;
    // Counter-clockwise about the face, sides follow edges 0, 1, 2; turned over, the polygon
    // a, c, b runs along edges 2, 1, 0.
    let edges = if face.dot((b - a).cross(c - a)) >= 0.0 {
        [0, 1, 2]
    } else {
        [2, 1, 0]
    };
    (0..3)
        .filter(|&side| !triangle.edge_active(edges[side], front))
        .fold(0, |sides, side| sides | (1 << side))
}

/// The triangle's supporting feature along the contact `normal`: its face (index 0,
/// counter-clockwise about `face`) when the normal is the face normal, otherwise the feature
/// holding `point`, its closest point to the shape: an edge (1 + edge) or a corner (4 + corner).
fn triangle_feature(triangle: &Triangle, face: Vec3, normal: Vec3, point: Vec3) -> Feature {
    let [a, b, c] = triangle.vertices;
    let (_, weights) = triangle.closest_point(point);
    let small = weights.map(|weight| weight < FEATURE_WEIGHT);
    let on_face = normal.dot(face) >= FACE_NORMAL_COSINE;
    match small {
        _ if on_face => {
            let corners = if face.dot((b - a).cross(c - a)) >= 0.0 {
                [a, b, c]
            } else {
                [a, c, b]
            };
            Feature::of_points(0, &corners, face)
        }
        [true, true, _] => Feature::of_points(6, &[c], face),
        [true, _, true] => Feature::of_points(5, &[b], face),
        [_, true, true] => Feature::of_points(4, &[a], face),
        // Weight k zero: edge (k + 1) % 3.
        [true, false, false] => Feature::of_points(2, &[b, c], face),
        [false, true, false] => Feature::of_points(3, &[c, a], face),
        [false, false, true] => Feature::of_points(1, &[a, b], face),
        [false, false, false] => Feature::of_points(0, &[point], face),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::dynamic_tree::random::Random;
    use crate::collision::SPECULATIVE_DISTANCE;
    use crate::math::Quat;

    /// How far the two manifolds' normals may differ (as unit vectors). GJK settles on a
    /// polytope's closest features, and both paths then take the normal from the same features
    /// (or from the face), to f32 rounding: 5e-5 is the most seen, 1e-3 (0.06°) leaves room.
    const NORMAL_TOLERANCE: f32 = 1e-3;

    /// How far a point's position plus its separation may differ, metres: GJK's contact queries
    /// stop within `gjk::CONTACT_PRECISION` (1e-4 m) of the distance, and the clipped points
    /// follow the features, not the distance (4e-7 m is the most seen).
    const POINT_TOLERANCE: f32 = 1e-4;

    /// A pose within 0.6 m along each axis of a random point of the triangle `vertices`,
    /// turned any way.
    fn random_pose_near(random: &mut Random, vertices: [Vec3; 3]) -> Pose {
        let (u, v) = (random.range(0.0, 1.0), random.range(0.0, 1.0));
        let (u, v) = if u + v > 1.0 {
            (1.0 - u, 1.0 - v)
        } else {
            (u, v)
        };
        let [a, b, c] = vertices;
        let centre = a + (b - a) * u + (c - a) * v + random.vec3(-0.6, 0.6);
        Pose::new(centre, Quat::from_scaled_axis(random.vec3(-1.8, 1.8)))
    }

    /// A box's manifold with a triangle, found with the closed form, against the same box as a
    /// hull of its eight corners, which goes through GJK: random triangles (half with active
    /// edges), boxes within 0.6 m along each axis, turned any way, some against one-sided
    /// triangles.
    #[test]
    fn box_manifolds_match_gjk_on_a_hull_of_its_corners() {
        let mut random = Random(0x6d61_6e69);
        let mut compared = 0;
        for case in 0..4000 {
            let vertices = [0; 3].map(|_| random.vec3(-1.0, 1.0));
            let triangle = Triangle {
                vertices,
                edge_flags: if random.chance(0.5) { 0b11_1111 } else { 0 },
            };
            let half = random.vec3(0.05, 0.6);
            let cuboid = Shape::cuboid(half).unwrap();
            let corners = [0, 1, 2, 3, 4, 5, 6, 7].map(|i: u32| {
                half * Vec3::new(
                    if i & 1 == 0 { -1.0 } else { 1.0 },
                    if i & 2 == 0 { -1.0 } else { 1.0 },
                    if i & 4 == 0 { -1.0 } else { 1.0 },
                )
            });
            let hull = Shape::convex_hull(&corners).unwrap();
            let pose = random_pose_near(&mut random, vertices);
            let one_sided = random.chance(0.3);
            let margin = SPECULATIVE_DISTANCE;
            let closed = collide_triangle(&triangle, one_sided, &cuboid, &pose, margin);
            let through_gjk = collide_triangle(&triangle, one_sided, &hull, &pose, margin);
            let (closed, through_gjk) = match (closed, through_gjk) {
                (Some(closed), Some(through_gjk)) => (closed, through_gjk),
                (None, None) => continue,
                (closed, through_gjk) => panic!("case {case}: {closed:?} against {through_gjk:?}"),
            };
            compared += 1;
            assert!(
                closed.normal.distance(through_gjk.normal) <= NORMAL_TOLERANCE,
                "case {case}: {closed:?} against {through_gjk:?}"
            );
            assert_eq!(closed.len(), through_gjk.len(), "case {case}");
            for point in closed.points() {
                let nearest = through_gjk
                    .points()
                    .iter()
                    .map(|other| {
                        point.position.distance(other.position)
                            + (point.separation - other.separation).abs()
                    })
                    .fold(f32::INFINITY, f32::min);
                assert!(nearest <= POINT_TOLERANCE, "case {case}: {point:?}");
            }
        }
        assert!(compared >= 1000, "{compared} manifolds compared");
    }

    /// A query warm-started from the simplex the last one left against the same query cold:
    /// random triangles, cylinders (warm only from a simplex out of reach) and hulls of 12 random
    /// points turned any way within 0.6 m of them, queried again after a step's motion (up to
    /// 2 cm and 0.03 rad). Both searches stop within `gjk::CONTACT_PRECISION` of the distance, so
    /// the manifolds agree to the tolerances of the box test, but at a cylinder's rim, of radius
    /// `R`: there the normal is within `θ = √(2·1e-4/R)` of the true one (see
    /// `gjk::CONTACT_PRECISION`), so two answers within `2θ`, and the deepest point, under the
    /// normal on the rim, moves sideways by up to `R·2θ`. A pair near the margin may fall on
    /// either side of it.
    #[test]
    fn warm_started_manifolds_match_cold_ones() {
        let mut random = Random(0x7761_726d);
        let (mut compared, mut warm) = (0, 0);
        for case in 0..4000 {
            let vertices = [0; 3].map(|_| random.vec3(-1.0, 1.0));
            let triangle = Triangle {
                vertices,
                edge_flags: if random.chance(0.5) { 0b11_1111 } else { 0 },
            };
            let (shape, normal_tolerance, position_tolerance) = if random.chance(0.5) {
                let radius = random.range(0.05, 0.5);
                let rim = 2.0 * (2.0 * gjk::CONTACT_PRECISION / radius).sqrt();
                let shape = Shape::cylinder(radius, random.range(0.05, 0.5)).unwrap();
                (shape, rim, radius * rim + POINT_TOLERANCE)
            } else {
                let points: Vec<Vec3> = (0..12).map(|_| random.vec3(-0.4, 0.4)).collect();
                let shape = Shape::convex_hull(&points).unwrap();
                (shape, NORMAL_TOLERANCE, POINT_TOLERANCE)
            };
            let pose = random_pose_near(&mut random, vertices);
            let (centre, rotation) = (pose.position, pose.rotation);
            let one_sided = random.chance(0.3);
            let margin = SPECULATIVE_DISTANCE;
            let mut simplex = TriangleSimplex::default();
            collide_triangle_from(&triangle, one_sided, &shape, &pose, margin, &mut simplex);
            warm += usize::from(!simplex.is_empty());
            let moved = Pose::new(
                centre + random.vec3(-0.02, 0.02),
                Quat::from_scaled_axis(random.vec3(-0.03, 0.03)) * rotation,
            );
            let from_warm =
                collide_triangle_from(&triangle, one_sided, &shape, &moved, margin, &mut simplex);
            let from_cold = collide_triangle(&triangle, one_sided, &shape, &moved, margin);
            let near_margin =
                |manifold: &Manifold| manifold.deepest_separation() >= margin - POINT_TOLERANCE;
            let (from_warm, from_cold) = match (from_warm, from_cold) {
                (Some(from_warm), Some(from_cold)) => (from_warm, from_cold),
                (None, None) => continue,
                (Some(found), None) | (None, Some(found)) if near_margin(&found) => continue,
                (from_warm, from_cold) => {
                    panic!("case {case}: {from_warm:?} against {from_cold:?}")
                }
            };
            compared += 1;
            assert!(
                from_warm.normal.distance(from_cold.normal) <= normal_tolerance,
                "case {case}: {from_warm:?} against {from_cold:?}"
            );
            assert_eq!(from_warm.len(), from_cold.len(), "case {case}");
            for point in from_warm.points() {
                let matched = from_cold.points().iter().any(|other| {
                    point.position.distance(other.position) <= position_tolerance
                        && (point.separation - other.separation).abs() <= POINT_TOLERANCE
                });
                assert!(matched, "case {case}: {point:?} against {from_cold:?}");
            }
        }
        assert!(compared >= 1000, "{compared} manifolds compared");
        assert!(warm >= 1000, "{warm} queries left a simplex");
    }
}
