//! Closest points and distance between two shapes, or their penetration when they overlap.
//!
//! Two bounded convex parts are measured on their cores by GJK, the rounding radii added back
//! afterwards ([`Shape::core_radius`]); when the cores overlap, EPA gives the depth. A sphere
//! against a sphere, box, capsule or hull is the projection of its centre onto the other shape
//! ([`project_on_convex`]) less its radius, in closed form (a hull seen from outside still asks
//! GJK, a point against a polytope). A halfspace against anything is closed-form: the other
//! shape's deepest point along the inward normal. A mesh or heightfield is taken triangle by
//! triangle near the other shape: overlapping triangles give the contact the narrow phase would
//! make (its normal and deepest point, a heightfield solid below its surface), otherwise the
//! nearest triangle by GJK. Compounds are taken part by part.

use super::projection::{box_gap, near_triangles, project_on_convex};
use super::{convex_parts, validated_pose, world_support, PlacedHalfspace};
use crate::collision::epa::Polytope;
use crate::collision::triangle_contact::collide_triangle;
use crate::collision::{gjk, PosedCore, SupportMap};
use crate::error::{check_non_negative_or_infinite, Result};
use crate::math::{Aabb, Pose, Vec3};
use crate::shape::{Shape, Triangle};

/// How two shapes lie relative to each other: their closest points, or how deep they overlap.
///
/// Normals point from A toward B: moving B along `normal` takes it away from A.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ClosestPoints {
    /// The shapes are apart, by no more than the maximum distance asked.
    Separated {
        /// A's point nearest B, world, metres.
        point_a: Vec3,
        /// B's point nearest A, world, metres: `point_a + distance · normal`.
        point_b: Vec3,
        /// Unit world direction from A toward B.
        normal: Vec3,
        /// Distance between the surfaces, metres, positive.
        distance: f32,
    },
    /// The shapes overlap or touch.
    Overlapping {
        /// A's point deepest inside B, world, metres.
        point_a: Vec3,
        /// B's point deepest inside A, world, metres: `point_a − depth · normal`.
        point_b: Vec3,
        /// Unit world direction from A toward B along which B leaves A the quickest.
        normal: Vec3,
        /// Penetration depth, metres, zero or more: translating B by `depth · normal` separates
        /// them. Infinite for two halfspaces that do not face each other.
        depth: f32,
    },
    /// The shapes are farther apart than the maximum distance asked.
    Beyond,
}

impl ClosestPoints {
    /// The signed distance between the surfaces, metres: the distance when separated, minus the
    /// depth when overlapping, `None` beyond the maximum distance.
    pub fn distance(&self) -> Option<f32> {
        match *self {
            ClosestPoints::Separated { distance, .. } => Some(distance),
            ClosestPoints::Overlapping { depth, .. } => Some(-depth),
            ClosestPoints::Beyond => None,
        }
    }
}

/// The closest points of `shape_a` at `pose_a` and `shape_b` at `pose_b`, or their penetration,
/// or [`ClosestPoints::Beyond`] when they are more than `max_distance` metres apart (zero or
/// more; infinity for no limit).
///
/// Any two shapes may be measured: compounds by their nearest pair of children (the first pair
/// among equally near ones), meshes and heightfields by their nearest triangle (see the
/// [module conventions](crate::query) for the precision).
///
/// ```
/// use rebond::query::{closest_points, ClosestPoints};
/// use rebond::{Pose, Shape, Vec3};
///
/// let ball = Shape::sphere(0.5)?;
/// let crate_ = Shape::cuboid(Vec3::splat(1.0))?;
/// let at = |x: f32| Pose::from_position(Vec3::new(x, 0.0, 0.0));
/// let found = closest_points(&ball, &at(-3.0), &crate_, &at(0.0), f32::INFINITY)?;
/// let ClosestPoints::Separated { distance, normal, .. } = found else { panic!() };
/// assert!((distance - 1.5).abs() < 1e-6);
/// assert_eq!(normal, Vec3::X);
/// # Ok::<(), rebond::Error>(())
/// ```
///
/// # Errors
/// A non-finite `pose_a.position` or `pose_b.position`, a non-finite or zero rotation
/// (`pose_a.rotation`, `pose_b.rotation`), a NaN or negative `max_distance`.
pub fn closest_points(
    shape_a: &Shape,
    pose_a: &Pose,
    shape_b: &Shape,
    pose_b: &Pose,
    max_distance: f32,
) -> Result<ClosestPoints> {
    let pose_a = validated_pose("pose_a", pose_a)?;
    let pose_b = validated_pose("pose_b", pose_b)?;
    let max_distance = check_non_negative_or_infinite("max_distance", max_distance)?;
    let nearest = nearest_between(shape_a, &pose_a, shape_b, &pose_b, max_distance);
    Ok(classify(nearest, max_distance))
}

/// The answer for the nearest points found (or none within `max_distance`).
pub(crate) fn classify(nearest: Option<Nearest>, max_distance: f32) -> ClosestPoints {
    match nearest {
        Some(found) if found.separation <= 0.0 => ClosestPoints::Overlapping {
            point_a: found.point_a,
            point_b: found.point_b,
            normal: found.normal,
            depth: -found.separation,
        },
        Some(found) if found.separation <= max_distance => ClosestPoints::Separated {
            point_a: found.point_a,
            point_b: found.point_b,
            normal: found.normal,
            distance: found.separation,
        },
        _ => ClosestPoints::Beyond,
    }
}

/// The nearest points of two shapes A and B: `point_b − point_a = separation · normal`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Nearest {
    /// A's point, world.
    pub point_a: Vec3,
    /// B's point, world.
    pub point_b: Vec3,
    /// Unit world direction from A toward B.
    pub normal: Vec3,
    /// Signed distance between the surfaces, metres: negative when they overlap.
    pub separation: f32,
}

impl Nearest {
    /// The same points seen with A and B swapped.
    fn flipped(self) -> Self {
        Self {
            point_a: self.point_b,
            point_b: self.point_a,
            normal: -self.normal,
            separation: self.separation,
        }
    }
}

/// Keeps `found` in `best` when it is strictly nearer: the first among equals stays.
fn keep_nearer(best: &mut Option<Nearest>, found: Option<Nearest>) {
    if let Some(found) = found {
        if best.is_none_or(|best| found.separation < best.separation) {
            *best = Some(found);
        }
    }
}

/// The nearest points of two shapes, part by part; `None` when no pair of parts is within
/// `reach` metres (pairs whose boxes are farther apart are skipped).
pub(crate) fn nearest_between(
    shape_a: &Shape,
    pose_a: &Pose,
    shape_b: &Shape,
    pose_b: &Pose,
    reach: f32,
) -> Option<Nearest> {
    let mut best: Option<Nearest> = None;
    let bound = |best: &Option<Nearest>| best.map_or(reach, |found| found.separation.min(reach));
    match (shape_a.is_triangulated(), shape_b.is_triangulated()) {
        (true, true) => return mesh_to_mesh(shape_a, pose_a, shape_b, pose_b, reach),
        (false, true) => {
            for (_, part, part_pose) in convex_parts(shape_a, *pose_a) {
                let found = part_to_mesh(part, &part_pose, shape_b, pose_b, bound(&best));
                keep_nearer(&mut best, found);
            }
        }
        (true, false) => {
            for (_, part, part_pose) in convex_parts(shape_b, *pose_b) {
                let found = part_to_mesh(part, &part_pose, shape_a, pose_a, bound(&best));
                keep_nearer(&mut best, found.map(Nearest::flipped));
            }
        }
        (false, false) => {
            for (_, part_a, part_pose_a) in convex_parts(shape_a, *pose_a) {
                let box_a = part_a.aabb(&part_pose_a);
                for (_, part_b, part_pose_b) in convex_parts(shape_b, *pose_b) {
                    if box_gap(&box_a, &part_b.aabb(&part_pose_b)) <= bound(&best) {
                        let found = convex_pair(part_a, &part_pose_a, part_b, &part_pose_b);
                        keep_nearer(&mut best, Some(found));
                    }
                }
            }
        }
    }
    best
}

/// Two convex parts (no compound, mesh or heightfield).
fn convex_pair(shape_a: &Shape, pose_a: &Pose, shape_b: &Shape, pose_b: &Pose) -> Nearest {
    match (shape_a, shape_b) {
        (Shape::Halfspace(a), Shape::Halfspace(b)) => halfspace_pair(
            &PlacedHalfspace::new(a, pose_a),
            &PlacedHalfspace::new(b, pose_b),
        ),
        (Shape::Halfspace(a), _) => {
            halfspace_to_bounded(&PlacedHalfspace::new(a, pose_a), shape_b, pose_b)
        }
        (_, Shape::Halfspace(b)) => {
            halfspace_to_bounded(&PlacedHalfspace::new(b, pose_b), shape_a, pose_a).flipped()
        }
        (Shape::Sphere(sphere), other) if has_closed_form(other) => {
            sphere_to_convex(pose_a.position, sphere.radius(), other, pose_b)
        }
        (other, Shape::Sphere(sphere)) if has_closed_form(other) => {
            sphere_to_convex(pose_b.position, sphere.radius(), other, pose_a).flipped()
        }
        _ => cores_pair(shape_a, pose_a, shape_b, pose_b),
    }
}

/// Whether a sphere's distance to the shape is its centre's projection less its radius: every
/// bounded convex kind but the cylinder, which contacts (and so this query) see with rims
/// rounded by its convex radius, where the projection sees it sharp.
fn has_closed_form(shape: &Shape) -> bool {
    matches!(
        shape,
        Shape::Sphere(_) | Shape::Cuboid(_) | Shape::Capsule(_) | Shape::ConvexHull(_)
    )
}

/// A sphere (A) of `radius` around `centre` against a convex shape B: B's surface point nearest
/// the centre, `m` the outward normal there and `d` the centre's signed distance, gives the
/// separation `d − radius` along `−m`.
fn sphere_to_convex(centre: Vec3, radius: f32, shape: &Shape, pose: &Pose) -> Nearest {
    let surface = project_on_convex(shape, pose, centre);
    Nearest {
        point_a: centre - radius * surface.normal,
        point_b: surface.point,
        normal: -surface.normal,
        separation: surface.distance - radius,
    }
}

/// Two bounded convex parts by GJK on their cores, EPA when the cores overlap.
fn cores_pair(shape_a: &Shape, pose_a: &Pose, shape_b: &Shape, pose_b: &Pose) -> Nearest {
    let (core_a, core_b) = (
        PosedCore::new(shape_a, pose_a),
        PosedCore::new(shape_b, pose_b),
    );
    let (radius_a, radius_b) = (shape_a.core_radius(), shape_b.core_radius());
    let cores = gjk::distance_from_direction(&core_a, &core_b, pose_b.position - pose_a.position);
    let (normal, separation, point_a, point_b) = match cores.normal() {
        Some(normal) => (normal, cores.distance, cores.point_a, cores.point_b),
        None => {
            let deepest = Polytope::default().penetration(&core_a, &core_b, &cores.simplex);
            (
                deepest.normal,
                -deepest.depth,
                deepest.point_a,
                deepest.point_b,
            )
        }
    };
    Nearest {
        point_a: point_a + radius_a * normal,
        point_b: point_b - radius_b * normal,
        normal,
        separation: separation - radius_a - radius_b,
    }
}

/// A halfspace (A) against a bounded part B: B's deepest point along the inward normal, at its
/// height above the plane.
fn halfspace_to_bounded(halfspace: &PlacedHalfspace, shape: &Shape, pose: &Pose) -> Nearest {
    let deepest = world_support(shape, pose, -halfspace.normal).unwrap_or(pose.position);
    let height = halfspace.height_of(deepest);
    Nearest {
        point_a: deepest - height * halfspace.normal,
        point_b: deepest,
        normal: halfspace.normal,
        separation: height,
    }
}

/// Two halfspaces. Facing ones are apart by the height of B's plane above A's; any others
/// overlap without end (infinite depth) at a point of both planes: B's origin when they are
/// parallel and B's plane is inside A, else A's origin when parallel, else the point of the
/// planes' common line nearest A's origin.
fn halfspace_pair(a: &PlacedHalfspace, b: &PlacedHalfspace) -> Nearest {
    if a.faces(b) {
        let gap = a.height_of(b.point);
        return Nearest {
            point_a: b.point - gap * a.normal,
            point_b: b.point,
            normal: a.normal,
            separation: gap,
        };
    }
    let cosine = a.normal.dot(b.normal);
    let across = 1.0 - cosine * cosine;
    let common = if across <= 1e-6 {
        if a.height_of(b.point) <= 0.0 {
            b.point
        } else {
            a.point
        }
    } else {
        // x = p_a + α n_a + β n_b on both planes: α + β c = 0 and α c + β = n_b · (p_b − p_a).
        let beta = b.normal.dot(b.point - a.point) / across;
        a.point + beta * (b.normal - cosine * a.normal)
    };
    Nearest {
        point_a: common,
        point_b: common,
        normal: a.normal,
        separation: f32::NEG_INFINITY,
    }
}

/// A convex part (A) against a mesh or heightfield B. A halfspace meets the mesh's deepest
/// corner. A bounded part first looks for the triangles it overlaps, by the narrow phase's own
/// triangle contact (a heightfield is solid below its surface), and takes the deepest point
/// among them; apart, the nearest triangle within `reach` by GJK (a sphere's in closed form).
fn part_to_mesh(
    part: &Shape,
    part_pose: &Pose,
    mesh: &Shape,
    mesh_pose: &Pose,
    reach: f32,
) -> Option<Nearest> {
    let mut best: Option<Nearest> = None;
    let place = |local: Triangle| Triangle {
        vertices: local
            .vertices
            .map(|vertex| mesh_pose.transform_point(vertex)),
        edge_flags: local.edge_flags,
    };
    let everything = match mesh {
        Shape::TriMesh(trimesh) => trimesh.local_bounds(),
        Shape::HeightField(heightfield) => heightfield.local_bounds(),
        _ => return None,
    };
    if let Shape::Halfspace(halfspace) = part {
        let halfspace = PlacedHalfspace::new(halfspace, part_pose);
        mesh.triangles_in(&everything, |index| {
            for corner in mesh
                .triangle(index)
                .map(place)
                .into_iter()
                .flat_map(|t| t.vertices)
            {
                let height = halfspace.height_of(corner);
                keep_nearer(
                    &mut best,
                    Some(Nearest {
                        point_a: corner - height * halfspace.normal,
                        point_b: corner,
                        normal: halfspace.normal,
                        separation: height,
                    }),
                );
            }
        });
        return best;
    }
    let one_sided = matches!(mesh, Shape::HeightField(_));
    let bounds = part.aabb(&mesh_pose.inverse().mul_pose(part_pose));
    mesh.triangles_in(&bounds, |index| {
        let Some(triangle) = mesh.triangle(index).map(place) else {
            return;
        };
        let manifold = collide_triangle(&triangle, one_sided, part, part_pose, 0.0);
        let deepest = manifold.and_then(|manifold| {
            let point = manifold.points().iter().copied().reduce(|a, b| {
                if b.separation < a.separation {
                    b
                } else {
                    a
                }
            })?;
            // The manifold's normal points from the triangle to the part, its points lie midway
            // between the surfaces.
            let half = 0.5 * point.separation * manifold.normal;
            Some(Nearest {
                point_a: point.position + half,
                point_b: point.position - half,
                normal: -manifold.normal,
                separation: point.separation,
            })
        });
        keep_nearer(&mut best, deepest.filter(|found| found.separation <= 0.0));
    });
    if best.is_some() {
        return best;
    }
    let core = PosedCore::new(part, part_pose);
    let radius = part.core_radius();
    let mut nearest: Option<(Nearest, u32)> = None;
    near_triangles(mesh, &bounds, reach, |index, local| {
        let triangle = place(*local);
        let found = match part {
            Shape::Sphere(_) => sphere_to_triangle(part_pose.position, radius, &triangle),
            _ => core_to_triangle(&core, radius, part_pose.position, &triangle),
        };
        if nearest.is_none_or(|(best, i)| (found.separation, index) < (best.separation, i)) {
            nearest = Some((found, index));
        }
        found.separation
    });
    nearest
        .map(|(found, _)| found)
        .filter(|found| found.separation <= reach)
}

/// A sphere (A) against a triangle (B), in closed form: the triangle's point nearest the centre.
fn sphere_to_triangle(centre: Vec3, radius: f32, triangle: &Triangle) -> Nearest {
    let (surface, _) = triangle.closest_point(centre);
    let offset = surface - centre;
    let normal = offset
        .try_normalize()
        .unwrap_or_else(|| facing_away(triangle, centre));
    Nearest {
        point_a: centre + radius * normal,
        point_b: surface,
        normal,
        separation: offset.length() - radius,
    }
}

/// A convex core (A, rounded by `radius`, centred near `centre`) against a triangle (B) by GJK.
/// Cores that touch the triangle (within GJK's tolerance) have its face normal, from A's side.
fn core_to_triangle<C: SupportMap>(
    core: &C,
    radius: f32,
    centre: Vec3,
    triangle: &Triangle,
) -> Nearest {
    let middle = triangle.vertices.iter().sum::<Vec3>() / 3.0;
    let found = gjk::distance_from_direction(core, triangle, middle - centre);
    let normal = found
        .normal()
        .unwrap_or_else(|| facing_away(triangle, centre));
    Nearest {
        point_a: found.point_a + radius * normal,
        point_b: found.point_b,
        normal,
        separation: found.distance - radius,
    }
}

/// The triangle's unit normal pointing away from `point`'s side of it (front normal when on
/// its plane, +Y for a triangle of no area).
fn facing_away(triangle: &Triangle, point: Vec3) -> Vec3 {
    let front = triangle.normal().unwrap_or(Vec3::Y);
    if front.dot(point - triangle.vertices[0]) > 0.0 {
        -front
    } else {
        front
    }
}

/// Two meshes or heightfields: surfaces with no volume between them, each triangle of A against
/// the triangles of B near it; triangles that cross are apart by zero.
fn mesh_to_mesh(
    mesh_a: &Shape,
    pose_a: &Pose,
    mesh_b: &Shape,
    pose_b: &Pose,
    reach: f32,
) -> Option<Nearest> {
    let all_of_a = match mesh_a {
        Shape::TriMesh(trimesh) => trimesh.local_bounds(),
        Shape::HeightField(heightfield) => heightfield.local_bounds(),
        _ => return None,
    };
    let to_b = pose_b.inverse().mul_pose(pose_a);
    let mut best: Option<(Nearest, u32, u32)> = None;
    mesh_a.triangles_in(&all_of_a, |index_a| {
        let Some(local_a) = mesh_a.triangle(index_a) else {
            return;
        };
        let in_b = local_a.vertices.map(|vertex| to_b.transform_point(vertex));
        let bounds = Aabb::new(
            in_b[0].min(in_b[1]).min(in_b[2]),
            in_b[0].max(in_b[1]).max(in_b[2]),
        );
        let triangle_a = Triangle {
            vertices: local_a
                .vertices
                .map(|vertex| pose_a.transform_point(vertex)),
            edge_flags: local_a.edge_flags,
        };
        let middle_a = triangle_a.vertices.iter().sum::<Vec3>() / 3.0;
        let bound = best.map_or(reach, |(found, _, _)| found.separation.min(reach));
        near_triangles(mesh_b, &bounds, bound, |index_b, local_b| {
            let triangle_b = Triangle {
                vertices: local_b
                    .vertices
                    .map(|vertex| pose_b.transform_point(vertex)),
                edge_flags: local_b.edge_flags,
            };
            let crossing = core_to_triangle(&triangle_a, 0.0, middle_a, &triangle_b);
            // Crossing triangles touch: surfaces have no depth.
            let found = Nearest {
                separation: crossing.separation.max(0.0),
                ..crossing
            };
            let key = (found.separation, index_a, index_b);
            if best.is_none_or(|(best, a, b)| key < (best.separation, a, b)) {
                best = Some((found, index_a, index_b));
            }
            found.separation
        });
    });
    best.map(|(found, _, _)| found)
        .filter(|found| found.separation <= reach)
}
