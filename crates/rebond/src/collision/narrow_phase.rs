//! The narrow phase: contact manifolds between two shapes placed in the world.
//!
//! Pairs are routed by shape kind to the best routine: closed forms for spheres and capsules
//! (and for either against a cylinder's side), the plane test for halfspaces, the separating-axis test for boxes and hulls (pairs with a hull
//! rejected by GJK first when they are apart beyond the margin, unless they touched at the last
//! query), and GJK/EPA with
//! feature clipping for everything with a cylinder or a capsule against a polyhedron. Before
//! those two, a pair whose bounding balls are apart by the margin is rejected. Compounds collide
//! child by child. A [`NarrowPhase`] keeps the scratch space from pair to pair, so that a
//! steady step allocates nothing.

use super::closed_form::{
    capsule_capsule, rounded_segment_cylinder_side, sphere_box, sphere_capsule, sphere_sphere,
    CylinderSide,
};
use super::epa::Polytope;
use super::feature_contact::collide_features;
use super::gjk::{self, SimplexCache};
use super::halfspace::collide_halfspace;
use super::manifold::Manifold;
use super::mesh_contact::{KeptSimplex, MeshScratch, PlacedMesh};
use super::polyhedron::Polyhedron;
use super::polyhedron_contact::collide_polyhedra;
use super::{LocalCore, PosedCore, RelativeCore};
use crate::math::{Aabb, Pose, Vec3};
use crate::shape::{Cuboid, Shape};

/// Order of shape kinds: each pair is solved with the lower kind as A and flipped if needed.
fn kind_rank(shape: &Shape) -> u8 {
    match shape {
        Shape::Halfspace(_) => 0,
        Shape::Sphere(_) => 1,
        Shape::Capsule(_) => 2,
        Shape::Cuboid(_) => 3,
        Shape::Cylinder(_) => 4,
        Shape::ConvexHull(_) => 5,
        Shape::Compound(_) => 6,
        Shape::TriMesh(_) => 7,
        Shape::HeightField(_) => 8,
    }
}

/// What a query between two convex parts leaves for the next query between the same parts.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum PartCache {
    /// Nothing: the next query starts cold.
    #[default]
    Cold,
    /// The simplex GJK ended with, to start from.
    Simplex(SimplexCache),
    /// Two polyhedra, one a hull, that the separating-axis test found in contact: the next query
    /// skips GJK's pre-test (`apart_beyond`), which would let them through, and goes straight to
    /// the separating-axis test.
    Touching,
    /// A part against a mesh: the simplices its triangles' GJK queries left, `len` of them from
    /// `start` in the contact cache's list of triangle simplices.
    Triangles {
        /// Where the part's simplices start.
        start: u32,
        /// How many there are.
        len: u32,
    },
}

impl PartCache {
    /// The simplex kept, or an empty one.
    fn simplex(&self) -> SimplexCache {
        match self {
            PartCache::Simplex(simplex) => *simplex,
            PartCache::Cold | PartCache::Touching | PartCache::Triangles { .. } => {
                SimplexCache::default()
            }
        }
    }

    /// `simplex` kept, or nothing when it is empty.
    fn of_simplex(simplex: SimplexCache) -> Self {
        if simplex.is_empty() {
            PartCache::Cold
        } else {
            PartCache::Simplex(simplex)
        }
    }
}

/// Where [`NarrowPhase::collide`] finds, for each pair of convex parts, what the last query left
/// ([`PartCache`]), and leaves the manifolds it finds.
pub trait PartContacts {
    /// What the last query left for parts `child_a` and `child_b` (0 for a shape that is not a
    /// compound), or [`PartCache::Cold`] when the pair is new.
    fn previous_cache(&mut self, child_a: u32, child_b: u32) -> PartCache;

    /// A manifold between parts `child_a` and `child_b`, with what the query leaves for the next.
    fn add(&mut self, child_a: u32, child_b: u32, manifold: Manifold, cache: PartCache);

    /// Fills `simplices` with the GJK simplices, by triangle index, that the last query of a
    /// part against a mesh left with its first manifold, between parts `child_a` and `child_b`
    /// (on the mesh's side, that manifold's group: 0). The default: none.
    fn previous_triangle_simplices(
        &mut self,
        _child_a: u32,
        _child_b: u32,
        simplices: &mut Vec<KeptSimplex>,
    ) {
        simplices.clear();
    }

    /// A manifold between a part and a mesh (as [`PartContacts::add`]), the query having left
    /// `simplices` for the mesh's triangles. The default drops them.
    fn add_on_mesh(
        &mut self,
        child_a: u32,
        child_b: u32,
        manifold: Manifold,
        _simplices: &[KeptSimplex],
    ) {
        self.add(child_a, child_b, manifold, PartCache::Cold);
    }

    /// Whether collider `collider_a` of A and `collider_b` of B may touch (a compound's child is
    /// a collider of its own, which may be a sensor or have its own groups; 0 for a shape that is
    /// not a compound). Asked before each pair of parts is tested. The default: always.
    fn colliders_touch(&self, _collider_a: u32, _collider_b: u32) -> bool {
        true
    }
}

/// Parts found with nothing from before, handed to a closure.
struct ColdStart<F>(F);

impl<F: FnMut(u32, u32, Manifold)> PartContacts for ColdStart<F> {
    fn previous_cache(&mut self, _: u32, _: u32) -> PartCache {
        PartCache::Cold
    }

    fn add(&mut self, child_a: u32, child_b: u32, manifold: Manifold, _: PartCache) {
        (self.0)(child_a, child_b, manifold);
    }
}

/// The narrow phase's scratch space, kept from pair to pair and from step to step so that a
/// steady step allocates nothing: the polytope EPA grows, and the triangles and manifolds of mesh
/// contacts.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct NarrowPhase {
    polytope: Polytope,
    mesh: MeshScratch,
    /// The part of every margin that is not motion, m ([`NarrowPhase::set_speculative_distance`]).
    speculative_distance: f32,
}

impl NarrowPhase {
    /// Sets the speculative distance the world adds to every pair's margin (m, default 0): the
    /// rest of a margin is how far the pair can close in the step, which mesh manifolds keep
    /// points for (`reduction::Surface::Bent`). Left at 0, the whole margin counts as motion.
    pub fn set_speculative_distance(&mut self, distance: f32) {
        self.speculative_distance = distance;
    }

    /// The manifold between two convex shapes (neither a compound, a mesh nor a heightfield), with
    /// the normal from A toward B, or `None` when their surfaces are farther apart than `margin`
    /// metres.
    pub fn collide_convex(
        &mut self,
        shape_a: &Shape,
        pose_a: &Pose,
        shape_b: &Shape,
        pose_b: &Pose,
        margin: f32,
    ) -> Option<Manifold> {
        let mut cache = PartCache::Cold;
        self.collide_convex_from(shape_a, pose_a, shape_b, pose_b, margin, &mut cache)
    }

    /// [`NarrowPhase::collide_convex`] starting from `cache`, what the last query between the
    /// same two shapes left (GJK's simplex, or that two polyhedra with a hull touched), and
    /// leaving this query's there. The shapes are put in the same order at every
    /// query, so the cache always belongs to the same one of the two.
    pub fn collide_convex_from(
        &mut self,
        shape_a: &Shape,
        pose_a: &Pose,
        shape_b: &Shape,
        pose_b: &Pose,
        margin: f32,
        cache: &mut PartCache,
    ) -> Option<Manifold> {
        if kind_rank(shape_a) > kind_rank(shape_b) {
            return self
                .collide_convex_from(shape_b, pose_b, shape_a, pose_a, margin, cache)
                .map(Manifold::flipped);
        }
        let rounded_segment = match shape_a {
            Shape::Sphere(sphere) => Some(([pose_a.position; 2], sphere.radius())),
            Shape::Capsule(capsule) => Some((
                capsule.segment().map(|end| pose_a.transform_point(end)),
                capsule.radius(),
            )),
            _ => None,
        };
        if let (Some((segment, radius)), Shape::Cylinder(cylinder)) = (rounded_segment, shape_b) {
            if let CylinderSide::Side(manifold) =
                rounded_segment_cylinder_side(segment, radius, cylinder, pose_b, margin)
            {
                *cache = PartCache::Cold;
                return manifold;
            }
        }
        match (shape_a, shape_b) {
            (Shape::Halfspace(_), Shape::Halfspace(_))
            | (_, Shape::Compound(_) | Shape::TriMesh(_) | Shape::HeightField(_)) => None,
            (Shape::Halfspace(halfspace), other) => {
                collide_halfspace(halfspace, pose_a, other, pose_b, margin)
            }
            (Shape::Sphere(a), Shape::Sphere(b)) => sphere_sphere(a, pose_a, b, pose_b, margin),
            (Shape::Sphere(a), Shape::Capsule(b)) => sphere_capsule(a, pose_a, b, pose_b, margin),
            (Shape::Sphere(a), Shape::Cuboid(b)) => sphere_box(a, pose_a, b, pose_b, margin),
            (Shape::Capsule(a), Shape::Capsule(b)) => capsule_capsule(a, pose_a, b, pose_b, margin),
            _ if balls_apart(shape_a, shape_b, pose_b.position - pose_a.position, margin) => None,
            (Shape::Cuboid(_) | Shape::ConvexHull(_), Shape::Cuboid(_) | Shape::ConvexHull(_)) => {
                let a = Polyhedron::from_shape(shape_a)?;
                let b = Polyhedron::from_shape(shape_b)?;
                let has_hull = matches!(shape_a, Shape::ConvexHull(_))
                    || matches!(shape_b, Shape::ConvexHull(_));
                if !has_hull {
                    return collide_polyhedra(&a, pose_a, &b, pose_b, margin);
                }
                if *cache != PartCache::Touching {
                    let mut simplex = cache.simplex();
                    let apart =
                        apart_beyond(shape_a, pose_a, shape_b, pose_b, margin, &mut simplex);
                    *cache = PartCache::of_simplex(simplex);
                    if apart {
                        return None;
                    }
                }
                let manifold = collide_polyhedra(&a, pose_a, &b, pose_b, margin);
                *cache = PartCache::Touching;
                manifold
            }
            (Shape::Cuboid(cuboid), other) | (other, Shape::Cuboid(cuboid))
                if cuboid.half_extents().max_element()
                    > NEAR_PART_RATIO * other.bounding_radius() =>
            {
                let box_is_a = matches!(shape_a, Shape::Cuboid(_));
                let (box_pose, other_pose) = if box_is_a {
                    (pose_a, pose_b)
                } else {
                    (pose_b, pose_a)
                };
                let (part, center) = near_part(cuboid, box_pose, other, other_pose, margin)?;
                let half_extents = part.half_extents();
                let part = Shape::Cuboid(part);
                // Placed about the box's origin, not in the world: the part's faces on the box's
                // faces stay where the box's are, where a world position far from the origin
                // would round them by up to half a millimetre at 10 km.
                let origin = box_pose.position;
                let part_pose = Pose::new(box_pose.rotation * center, box_pose.rotation);
                let other_pose = &Pose::new(other_pose.position - origin, other_pose.rotation);
                let (part_a, part_pose_a, part_b, part_pose_b) = if box_is_a {
                    (&part, &part_pose, other, other_pose)
                } else {
                    (other, other_pose, &part, &part_pose)
                };
                // The simplex is kept with its points of the box in the box's frame, where they
                // stay put while the part moves with `other`; each is taken into this part's
                // frame and clamped to it, a point of the part whether or not the part still
                // holds it.
                let box_side = usize::from(!box_is_a);
                let mut simplex = cache.simplex().with_points(box_side, |point| {
                    (point - center).clamp(-half_extents, half_extents)
                });
                let manifold = collide_features(
                    &mut self.polytope,
                    part_a,
                    part_pose_a,
                    part_b,
                    part_pose_b,
                    margin,
                    &mut simplex,
                );
                *cache =
                    PartCache::of_simplex(simplex.with_points(box_side, |point| point + center));
                manifold.map(|manifold| manifold.translated(origin))
            }
            _ => {
                let mut simplex = cache.simplex();
                let manifold = collide_features(
                    &mut self.polytope,
                    shape_a,
                    pose_a,
                    shape_b,
                    pose_b,
                    margin,
                    &mut simplex,
                );
                *cache = PartCache::of_simplex(simplex);
                manifold
            }
        }
    }

    /// Every manifold between two shapes, compounds, meshes and heightfields included, added to
    /// `contacts` for each pair of convex parts in contact (child indices are 0 for a shape that
    /// is not a compound; on a mesh or heightfield, the index of the merged manifold, see
    /// `mesh_contact`), in a deterministic order, each query starting from what `contacts` kept
    /// for the parts. Parts whose bounding boxes, grown by `margin`, do not overlap are skipped.
    pub fn collide(
        &mut self,
        shape_a: &Shape,
        pose_a: &Pose,
        shape_b: &Shape,
        pose_b: &Pose,
        margin: f32,
        contacts: &mut impl PartContacts,
    ) {
        if shape_a.is_triangulated() || shape_b.is_triangulated() {
            self.collide_mesh(shape_a, pose_a, shape_b, pose_b, margin, contacts);
            return;
        }
        let mut collide_parts = |child_a: u32,
                                 part_a: &Shape,
                                 part_pose_a: &Pose,
                                 child_b: u32,
                                 part_b: &Shape,
                                 part_pose_b: &Pose| {
            if !contacts.colliders_touch(child_a, child_b) {
                return;
            }
            let mut cache = contacts.previous_cache(child_a, child_b);
            if let Some(manifold) = self.collide_convex_from(
                part_a,
                part_pose_a,
                part_b,
                part_pose_b,
                margin,
                &mut cache,
            ) {
                contacts.add(child_a, child_b, manifold, cache);
            }
        };
        let grow = |aabb: Aabb| {
            Aabb::new(
                aabb.min - Vec3::splat(margin),
                aabb.max + Vec3::splat(margin),
            )
        };
        let compound = |shape: &Shape| matches!(shape, Shape::Compound(_));
        if !compound(shape_a) && !compound(shape_b) {
            collide_parts(0, shape_a, pose_a, 0, shape_b, pose_b);
            return;
        }
        for_each_part(shape_a, pose_a, |child_a, part_a, part_pose_a| {
            let bounds_a = grow(part_a.aabb(&part_pose_a));
            for_each_part(shape_b, pose_b, |child_b, part_b, part_pose_b| {
                if bounds_a.overlaps(&part_b.aabb(&part_pose_b)) {
                    collide_parts(child_a, part_a, &part_pose_a, child_b, part_b, &part_pose_b);
                }
            });
        });
    }
}

impl NarrowPhase {
    /// [`NarrowPhase::collide`] when A or B is a mesh or heightfield: each convex part of the
    /// other shape against the mesh. Two meshes, or a mesh and a halfspace, never touch (both are
    /// static or kinematic).
    fn collide_mesh(
        &mut self,
        shape_a: &Shape,
        pose_a: &Pose,
        shape_b: &Shape,
        pose_b: &Pose,
        margin: f32,
        contacts: &mut impl PartContacts,
    ) {
        let mesh_is_a = shape_a.is_triangulated();
        let (mesh, other, other_pose) = if mesh_is_a {
            (
                PlacedMesh {
                    shape: shape_a,
                    pose: pose_a,
                },
                shape_b,
                pose_b,
            )
        } else {
            (
                PlacedMesh {
                    shape: shape_b,
                    pose: pose_b,
                },
                shape_a,
                pose_a,
            )
        };
        let reach = (margin - self.speculative_distance).max(0.0);
        let scratch = &mut self.mesh;
        for_each_part(other, other_pose, |child, part, part_pose| {
            let touch = if mesh_is_a {
                contacts.colliders_touch(0, child)
            } else {
                contacts.colliders_touch(child, 0)
            };
            if !touch {
                return;
            }
            // The simplices ride with the part's first manifold (group 0), which exists whenever
            // any does.
            let (first_a, first_b) = if mesh_is_a { (0, child) } else { (child, 0) };
            contacts.previous_triangle_simplices(first_a, first_b, &mut scratch.previous_simplices);
            scratch.collide(
                &mesh,
                part,
                &part_pose,
                margin,
                reach,
                |group, manifold, simplices| {
                    let manifold = if mesh_is_a {
                        manifold
                    } else {
                        manifold.flipped()
                    };
                    let (child_a, child_b) = if mesh_is_a {
                        (group, child)
                    } else {
                        (child, group)
                    };
                    if group == 0 {
                        contacts.add_on_mesh(child_a, child_b, manifold, simplices);
                    } else {
                        contacts.add(child_a, child_b, manifold, PartCache::Cold);
                    }
                },
            );
        });
    }
}

/// [`NarrowPhase::collide_convex`] with scratch space of its own, which allocates when EPA runs.
pub fn collide_convex(
    shape_a: &Shape,
    pose_a: &Pose,
    shape_b: &Shape,
    pose_b: &Pose,
    margin: f32,
) -> Option<Manifold> {
    NarrowPhase::default().collide_convex(shape_a, pose_a, shape_b, pose_b, margin)
}

/// [`NarrowPhase::collide`] with scratch space of its own, which allocates when EPA runs, and no
/// simplex from before: `on_manifold(child_a, child_b, manifold)` is called for each pair of
/// convex parts in contact.
pub fn collide(
    shape_a: &Shape,
    pose_a: &Pose,
    shape_b: &Shape,
    pose_b: &Pose,
    margin: f32,
    on_manifold: impl FnMut(u32, u32, Manifold),
) {
    NarrowPhase::default().collide(
        shape_a,
        pose_a,
        shape_b,
        pose_b,
        margin,
        &mut ColdStart(on_manifold),
    );
}

/// The convex parts of a shape with their world poses: the shape itself, or each child of a
/// compound with its index (the collider index).
pub(crate) fn for_each_part(shape: &Shape, pose: &Pose, mut visit: impl FnMut(u32, &Shape, Pose)) {
    match shape {
        Shape::Compound(compound) => {
            for (index, child) in (0..).zip(compound.children()) {
                visit(index, &child.shape, pose.mul_pose(&child.pose));
            }
        }
        _ => visit(0, shape, *pose),
    }
}

/// A box whose largest half extent is more than this many times the bounding radius of the
/// shape it meets in GJK and EPA is replaced there by its part near that shape ([`near_part`]).
const NEAR_PART_RATIO: f32 = 8.0;

/// The part of a box near `other`: the box cut to `other`'s bounding box in the box's frame,
/// grown by `margin` and by `other`'s bounding radius, as a smaller box with its centre in the
/// box's frame (its axes are the box's); `None` when nothing of the box lies that near, so the
/// two are more than `margin` apart.
///
/// GJK and EPA work with differences of support points, which for a large box are its far
/// corners: their rounding, about 1e-7 of their distance, unsettles a cylinder resting on a box
/// a kilometre wide. The part's corners lie a few of `other`'s sizes away instead. Its cut faces
/// are farther from `other` than `margin` plus its size, so the nearest or shallowest way out
/// found is always through one of the box's own faces, edges or corners.
fn near_part(
    cuboid: &Cuboid,
    pose: &Pose,
    other: &Shape,
    other_pose: &Pose,
    margin: f32,
) -> Option<(Cuboid, Vec3)> {
    let half_extents = cuboid.half_extents();
    let other_in_box = pose.inverse().mul_pose(other_pose);
    let reach = Vec3::splat(margin + other.bounding_radius());
    let bounds = other.aabb(&other_in_box);
    let min = (bounds.min - reach).max(-half_extents);
    let max = (bounds.max + reach).min(half_extents);
    if min.cmpge(max).any() {
        return None;
    }
    Some((Cuboid::part((max - min) * 0.5), (min + max) * 0.5))
}

/// Whether the balls about the shapes' origins that hold them (see [`Shape::bounding_radius`]),
/// the origins `offset` apart, are at least `margin` apart, `|offset| − R_A − R_B ≥ margin`: then
/// so are the shapes, since a translation that separates the balls separates what they hold. A
/// dozen instructions that spare GJK many pairs whose bounding boxes merely overlap.
fn balls_apart(shape_a: &Shape, shape_b: &Shape, offset: Vec3, margin: f32) -> bool {
    let reach = shape_a.bounding_radius() + shape_b.bounding_radius() + margin;
    reach <= 0.0 || offset.length_squared() >= reach * reach
}

/// Whether GJK finds two convex shapes more than `margin` apart. For pairs with a hull it rejects
/// most pairs whose boxes merely overlap for about a third of what the separating-axis test
/// costs. GJK
/// starts from `simplex` and leaves its own there, as in [`Polytope::contact_from`].
fn apart_beyond(
    shape_a: &Shape,
    pose_a: &Pose,
    shape_b: &Shape,
    pose_b: &Pose,
    margin: f32,
    simplex: &mut SimplexCache,
) -> bool {
    let radii = shape_a.core_radius() + shape_b.core_radius();
    let b = RelativeCore::new(&PosedCore::new(shape_b, pose_b), pose_a);
    let (start, len) = simplex.placed(&b);
    let found = gjk::distance_within(
        &LocalCore(shape_a),
        &b,
        &start[..len],
        b.position,
        margin + radii,
    );
    found.is_none_or(|cores| {
        *simplex = SimplexCache::new(&cores.simplex, &b);
        cores.distance - radii >= margin
    })
}
