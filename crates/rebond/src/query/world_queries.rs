//! The scene queries as methods of [`World`]: each walks the broad phase's static and moving
//! trees for candidates, lets the [`QueryFilter`] pick among them, and tests their exact shapes.

use std::ops::ControlFlow;

use super::closest::{classify, nearest_between};
use super::overlap::{shape_contains_point, shapes_overlap};
use super::projection::{box_gap, project_on_shape};
use super::ray::{cast_ray_at_shape, ShapeRayHit};
use super::shape_cast::{cast_shape_at_shape, Sweep};
use super::{
    convex_parts, unit_direction, validated_pose, ClosestPoints, PointProjection, QueryFilter, Ray,
    RayHit, ShapeHit,
};
use crate::body::{BodyHandle, RigidBody};
use crate::collision::dynamic_tree::{DynamicTree, ProxyId};
use crate::error::{check_non_negative_or_infinite, Error, ErrorKind, Result};
use crate::filter::Colliders;
use crate::math::{Aabb, Pose, Vec3};
use crate::shape::Shape;
use crate::world::World;

/// Scene queries; see [`crate::query`] for the conventions they share.
impl World {
    /// The nearest body `ray` meets, or `None`.
    ///
    /// ```
    /// use rebond::{BodyDesc, QueryFilter, Ray, Shape, Vec3, World, WorldSettings};
    ///
    /// let mut world = World::new(WorldSettings::default())?;
    /// let ground = world.add_body(BodyDesc::static_body(Shape::cuboid(Vec3::new(10.0, 1.0, 10.0))?))?;
    /// let ray = Ray::new(Vec3::new(0.0, 5.0, 0.0), Vec3::NEG_Y);
    /// let hit = world.cast_ray(&ray, &QueryFilter::default())?.expect("the ground is below");
    /// assert_eq!(hit.body, ground);
    /// assert!((hit.distance - 4.0).abs() < 1e-6);
    /// assert_eq!(hit.normal, Vec3::Y);
    /// # Ok::<(), rebond::Error>(())
    /// ```
    ///
    /// # Errors
    /// A non-finite `origin` or `direction`, a zero `direction`, a NaN or negative
    /// `max_distance`, a body of another world in `filter.excluded_bodies`; the error names the
    /// field.
    pub fn cast_ray(&self, ray: &Ray, filter: &QueryFilter) -> Result<Option<RayHit>> {
        let ray = ray.validated()?;
        let mut nearest: Option<RayHit> = None;
        self.visit_ray(&ray, filter, |handle, body| {
            let Some(hit) = cast_ray_at_body(body, &ray, filter) else {
                return ControlFlow::Continue(f32::INFINITY);
            };
            let is_nearer =
                nearest.is_none_or(|best| (hit.distance, handle) < (best.distance, best.body));
            if is_nearer {
                nearest = Some(ray_hit(&ray, handle, &hit));
            }
            ControlFlow::Continue(nearest.map_or(f32::INFINITY, |best| best.distance))
        })?;
        Ok(nearest)
    }

    /// Every body `ray` meets, one hit each (the nearest on that body), into `hits` (cleared
    /// first), sorted by distance and then by handle.
    ///
    /// # Errors
    /// As [`World::cast_ray`]; `hits` is then left empty.
    pub fn cast_ray_all(
        &self,
        ray: &Ray,
        filter: &QueryFilter,
        hits: &mut Vec<RayHit>,
    ) -> Result<()> {
        hits.clear();
        let ray = ray.validated()?;
        self.visit_ray(&ray, filter, |handle, body| {
            if let Some(hit) = cast_ray_at_body(body, &ray, filter) {
                hits.push(ray_hit(&ray, handle, &hit));
            }
            ControlFlow::Continue(f32::INFINITY)
        })?;
        hits.sort_unstable_by(|a, b| a.distance.total_cmp(&b.distance).then(a.body.cmp(&b.body)));
        Ok(())
    }

    /// Whether `ray` meets any body; stops at the first hit found, which is cheaper than
    /// [`World::cast_ray`].
    ///
    /// # Errors
    /// As [`World::cast_ray`].
    pub fn cast_ray_any(&self, ray: &Ray, filter: &QueryFilter) -> Result<bool> {
        let ray = ray.validated()?;
        let mut found = false;
        self.visit_ray(&ray, filter, |_, body| {
            if cast_ray_at_body(body, &ray, filter).is_some() {
                found = true;
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(f32::INFINITY)
            }
        })?;
        Ok(found)
    }

    /// Sweeps `shape`, placed at `pose`, along `direction` (normalised here) for up to
    /// `max_distance` metres (infinity allowed), and returns where it first touches a body.
    /// Compounds and halfspaces may be swept too.
    ///
    /// ```
    /// use rebond::{BodyDesc, Pose, QueryFilter, Shape, Vec3, World, WorldSettings};
    ///
    /// let mut world = World::new(WorldSettings::default())?;
    /// let wall = world.add_body(
    ///     BodyDesc::static_body(Shape::cuboid(Vec3::splat(1.0))?).position(Vec3::new(5.0, 0.0, 0.0)),
    /// )?;
    /// let ball = Shape::sphere(0.5)?;
    /// let hit = world
    ///     .cast_shape(&ball, &Pose::IDENTITY, Vec3::X, 10.0, &QueryFilter::default())?
    ///     .expect("the wall is in the way");
    /// assert_eq!(hit.body, wall);
    /// assert!((hit.distance - 3.5).abs() < 1e-4);
    /// # Ok::<(), rebond::Error>(())
    /// ```
    ///
    /// # Errors
    /// A non-finite `pose.position` or `pose.rotation`, a zero `pose.rotation`, a non-finite or
    /// zero `direction`, a NaN or negative `max_distance`, a body of another world in
    /// `filter.excluded_bodies`; the error names the field.
    pub fn cast_shape(
        &self,
        shape: &Shape,
        pose: &Pose,
        direction: Vec3,
        max_distance: f32,
        filter: &QueryFilter,
    ) -> Result<Option<ShapeHit>> {
        let sweep = Sweep {
            shape,
            pose: validated_pose("pose", pose)?,
            direction: unit_direction("direction", direction)?,
            max_distance: check_non_negative_or_infinite("max_distance", max_distance)?,
        };
        let start_aabb = shape.aabb(&sweep.pose);
        let mut nearest: Option<ShapeHit> = None;
        self.visit_candidates(
            filter,
            |tree, bound, visit| tree.box_cast(&start_aabb, sweep.direction, bound, visit),
            sweep.max_distance,
            |handle, body| {
                let reach = nearest.map_or(sweep.max_distance, |best| best.distance);
                let body_sweep = Sweep {
                    max_distance: reach,
                    ..sweep
                };
                let colliders = Colliders::of(body);
                let sees = |collider| filter.sees_collider(&colliders, collider);
                let Some((hit, part)) =
                    cast_shape_at_shape(&body_sweep, &body.shape, &body.pose(), sees)
                else {
                    return ControlFlow::Continue(reach);
                };
                let is_nearer =
                    nearest.is_none_or(|best| (hit.distance, handle) < (best.distance, best.body));
                if is_nearer {
                    nearest = Some(ShapeHit {
                        body: handle,
                        collider: part.collider,
                        triangle: part.triangle,
                        distance: hit.distance,
                        point: hit.point,
                        normal: hit.normal,
                    });
                }
                ControlFlow::Continue(nearest.map_or(reach, |best| best.distance))
            },
        )?;
        Ok(nearest)
    }

    /// The bodies whose shape holds `point` (inside or on the surface), into `bodies` (cleared
    /// first), sorted by handle.
    ///
    /// # Errors
    /// A non-finite `point`, a body of another world in `filter.excluded_bodies`; `bodies` is
    /// then left empty.
    pub fn bodies_containing_point(
        &self,
        point: Vec3,
        filter: &QueryFilter,
        bodies: &mut Vec<BodyHandle>,
    ) -> Result<()> {
        bodies.clear();
        if !point.is_finite() {
            return Err(Error::new("point", ErrorKind::NotFinite));
        }
        self.collect_overlaps(
            &Aabb::new(point, point),
            filter,
            bodies,
            |handle, body, found| {
                if any_collider_seen(body, filter, |part, part_pose| {
                    shape_contains_point(part, part_pose, point)
                }) {
                    found.push(handle);
                }
            },
        )
    }

    /// The colliders whose shape holds `point`, as `(body, collider)` pairs into `colliders`
    /// (cleared first), sorted: [`World::bodies_containing_point`] naming each collider (its
    /// compound child's index, 0 for a body of one shape) the point is in.
    ///
    /// # Errors
    /// As [`World::bodies_containing_point`]; `colliders` is then left empty.
    pub fn colliders_containing_point(
        &self,
        point: Vec3,
        filter: &QueryFilter,
        colliders: &mut Vec<(BodyHandle, u32)>,
    ) -> Result<()> {
        colliders.clear();
        if !point.is_finite() {
            return Err(Error::new("point", ErrorKind::NotFinite));
        }
        self.collect_overlaps(
            &Aabb::new(point, point),
            filter,
            colliders,
            |handle, body, found| {
                push_colliders_seen(handle, body, filter, found, |part, part_pose| {
                    shape_contains_point(part, part_pose, point)
                });
            },
        )
    }

    /// The bodies whose bounding box overlaps `aabb` (touching counts), into `bodies` (cleared
    /// first), sorted by handle. A cheap, conservative test: for the exact shapes, query with
    /// [`World::bodies_overlapping_shape`] and a box.
    ///
    /// # Errors
    /// A non-finite corner, field `aabb.min[i]` or `aabb.max[i]`, or a `min` above `max` on an
    /// axis (field `aabb.min[i]`, [`ErrorKind::OutOfRange`]), a body of another world in
    /// `filter.excluded_bodies`; `bodies` is then left empty.
    pub fn bodies_overlapping_aabb(
        &self,
        aabb: &Aabb,
        filter: &QueryFilter,
        bodies: &mut Vec<BodyHandle>,
    ) -> Result<()> {
        bodies.clear();
        for axis in 0..3 {
            let (min, max) = (aabb.min[axis], aabb.max[axis]);
            if !min.is_finite() {
                return Err(Error::new(
                    format!("aabb.min[{axis}]"),
                    ErrorKind::NotFinite,
                ));
            }
            if !max.is_finite() {
                return Err(Error::new(
                    format!("aabb.max[{axis}]"),
                    ErrorKind::NotFinite,
                ));
            }
            if min > max {
                let kind = ErrorKind::OutOfRange {
                    value: min,
                    min: f32::NEG_INFINITY,
                    max,
                };
                return Err(Error::new(format!("aabb.min[{axis}]"), kind));
            }
        }
        self.collect_overlaps(aabb, filter, bodies, |handle, body, found| {
            if body.aabb().overlaps(aabb) {
                found.push(handle);
            }
        })
    }

    /// The bodies whose shape overlaps `shape` placed at `pose` (touching counts), into `bodies`
    /// (cleared first), sorted by handle.
    ///
    /// # Errors
    /// A non-finite `pose.position` or `pose.rotation`, a zero `pose.rotation`, a body of
    /// another world in `filter.excluded_bodies`; `bodies` is then left empty.
    pub fn bodies_overlapping_shape(
        &self,
        shape: &Shape,
        pose: &Pose,
        filter: &QueryFilter,
        bodies: &mut Vec<BodyHandle>,
    ) -> Result<()> {
        bodies.clear();
        let pose = validated_pose("pose", pose)?;
        let bounds = shape.aabb(&pose);
        self.collect_overlaps(&bounds, filter, bodies, |handle, body, found| {
            if body.aabb().overlaps(&bounds)
                && any_collider_seen(body, filter, |part, part_pose| {
                    shapes_overlap(shape, &pose, part, part_pose)
                })
            {
                found.push(handle);
            }
        })
    }

    /// The colliders that overlap `shape` placed at `pose` (touching counts), as
    /// `(body, collider)` pairs into `colliders` (cleared first), sorted:
    /// [`World::bodies_overlapping_shape`] naming each collider (its compound child's index, 0
    /// for a body of one shape) that overlaps. A mesh is one collider; the triangles it overlaps
    /// are not listed.
    ///
    /// # Errors
    /// As [`World::bodies_overlapping_shape`]; `colliders` is then left empty.
    pub fn colliders_overlapping_shape(
        &self,
        shape: &Shape,
        pose: &Pose,
        filter: &QueryFilter,
        colliders: &mut Vec<(BodyHandle, u32)>,
    ) -> Result<()> {
        colliders.clear();
        let pose = validated_pose("pose", pose)?;
        let bounds = shape.aabb(&pose);
        self.collect_overlaps(&bounds, filter, colliders, |handle, body, found| {
            if body.aabb().overlaps(&bounds) {
                push_colliders_seen(handle, body, filter, found, |part, part_pose| {
                    shapes_overlap(shape, &pose, part, part_pose)
                });
            }
        })
    }
}

/// Distances: between two bodies, and from a point to the nearest body.
impl World {
    /// The closest points of bodies `body_a` and `body_b` at their current poses, or their
    /// penetration, or [`ClosestPoints::Beyond`] when they are more than `max_distance` metres
    /// apart (zero or more; infinity for no limit): [`closest_points`](super::closest_points) on
    /// the two bodies' shapes, every collider counted (sensors too).
    ///
    /// ```
    /// use rebond::{BodyDesc, ClosestPoints, Shape, Vec3, World, WorldSettings};
    ///
    /// let mut world = World::new(WorldSettings::default())?;
    /// let a = world.add_body(BodyDesc::static_body(Shape::sphere(1.0)?))?;
    /// let b = world.add_body(
    ///     BodyDesc::static_body(Shape::sphere(1.0)?).position(Vec3::new(0.0, 5.0, 0.0)),
    /// )?;
    /// let found = world.closest_points(a, b, 10.0)?;
    /// assert_eq!(found.distance(), Some(3.0));
    /// assert!(matches!(found, ClosestPoints::Separated { normal: Vec3::Y, .. }));
    /// assert_eq!(world.closest_points(a, b, 2.0)?, ClosestPoints::Beyond);
    /// # Ok::<(), rebond::Error>(())
    /// ```
    ///
    /// # Errors
    /// A removed body or one of another world ([`ErrorKind::StaleHandle`], field `body_a` or
    /// `body_b`), a NaN or negative `max_distance`.
    pub fn closest_points(
        &self,
        body_a: BodyHandle,
        body_b: BodyHandle,
        max_distance: f32,
    ) -> Result<ClosestPoints> {
        let a = self.body(body_a).map_err(|error| error.within("body_a"))?;
        let b = self.body(body_b).map_err(|error| error.within("body_b"))?;
        let max_distance = check_non_negative_or_infinite("max_distance", max_distance)?;
        let nearest = nearest_between(&a.shape, &a.pose(), &b.shape, &b.pose(), max_distance);
        Ok(classify(nearest, max_distance))
    }

    /// The signed distance between the surfaces of bodies `body_a` and `body_b`, metres:
    /// negative by the penetration depth when they overlap. [`World::closest_points`] without a
    /// limit.
    ///
    /// # Errors
    /// As [`World::closest_points`].
    pub fn distance(&self, body_a: BodyHandle, body_b: BodyHandle) -> Result<f32> {
        let found = self.closest_points(body_a, body_b, f32::INFINITY)?;
        Ok(found.distance().unwrap_or(f32::INFINITY))
    }

    /// The point of the bodies' surfaces nearest `point`, among the bodies `filter` sees, within
    /// `max_distance` metres (zero or more; infinity for no limit), or `None`. The body with the
    /// smallest signed distance wins (the usual signed distance of their union): a body holding
    /// the point beats every body outside, the one it is deepest in first; ties go to the
    /// smaller handle, and within a body to its first collider, its smallest triangle.
    ///
    /// ```
    /// use rebond::{BodyDesc, QueryFilter, Shape, Vec3, World, WorldSettings};
    ///
    /// let mut world = World::new(WorldSettings::default())?;
    /// let ground = world.add_body(BodyDesc::static_body(Shape::cuboid(Vec3::new(10.0, 1.0, 10.0))?))?;
    /// let found = world
    ///     .project_point(Vec3::new(2.0, 4.0, 0.0), f32::INFINITY, &QueryFilter::default())?
    ///     .expect("the ground is there");
    /// assert_eq!(found.body, ground);
    /// assert_eq!(found.point, Vec3::new(2.0, 1.0, 0.0));
    /// assert_eq!((found.distance, found.inside), (3.0, false));
    /// # Ok::<(), rebond::Error>(())
    /// ```
    ///
    /// # Errors
    /// A non-finite `point`, a NaN or negative `max_distance`, a body of another world in
    /// `filter.excluded_bodies`; the error names the field.
    pub fn project_point(
        &self,
        point: Vec3,
        max_distance: f32,
        filter: &QueryFilter,
    ) -> Result<Option<PointProjection>> {
        if !point.is_finite() {
            return Err(Error::new("point", ErrorKind::NotFinite));
        }
        let max_distance = check_non_negative_or_infinite("max_distance", max_distance)?;
        self.check_filter(filter)?;
        let arena = self.bodies_arena();
        let broad_phase = self.broad_phase();
        let trees = [broad_phase.static_tree(), broad_phase.moving_tree()];
        let proxies: usize = trees.iter().map(|tree| tree.proxy_count()).sum();
        let at_point = Aabb::new(point, point);
        let mut best: Option<PointProjection> = None;
        let mut searched: Option<Aabb> = None;
        let mut radius = max_distance.min(FIRST_SEARCH_RADIUS);
        loop {
            let search = Aabb::new(point - Vec3::splat(radius), point + Vec3::splat(radius));
            let mut met = 0;
            for tree in trees {
                tree.query(&search, |proxy| {
                    met += 1;
                    if searched.is_some_and(|inner| tree.fat_aabb(proxy).overlaps(&inner)) {
                        return true;
                    }
                    let Some((index, body)) = arena.at_slot(tree.user_data(proxy) as usize) else {
                        return true;
                    };
                    let handle = BodyHandle(index);
                    let reach = best.map_or(max_distance, |best| best.distance.max(0.0));
                    if !filter.accepts(handle, body) || box_gap(&at_point, &body.aabb()) > reach {
                        return true;
                    }
                    let colliders = Colliders::of(body);
                    let sees = |collider| filter.sees_collider(&colliders, collider);
                    let Some(found) =
                        project_on_shape(&body.shape, &body.pose(), point, reach, sees)
                    else {
                        return true;
                    };
                    if best.is_none_or(|best| (found.distance, handle) < (best.distance, best.body))
                    {
                        best = Some(PointProjection {
                            body: handle,
                            collider: found.part.collider,
                            triangle: found.part.triangle,
                            point: found.point,
                            normal: found.normal,
                            distance: found.distance,
                            inside: found.inside,
                        });
                    }
                    true
                });
            }
            // Every body not met lies outside the search cube, farther than `radius`.
            let settled = best.is_some_and(|best| best.distance <= radius);
            if settled || radius >= max_distance || met >= proxies {
                break;
            }
            searched = Some(search);
            radius = (2.0 * radius).min(max_distance);
        }
        Ok(best.filter(|best| best.distance <= max_distance))
    }
}

/// Half the side of the first cube [`World::project_point`] searches without a distance limit,
/// metres: about a body's size, doubled until a body is found within it.
const FIRST_SEARCH_RADIUS: f32 = 1.0;

/// The walks shared by the queries.
impl World {
    /// Refuses a filter that excludes a body of another world, naming it
    /// (`excluded_bodies[i]`); a removed body of this world excludes nothing and is let be.
    fn check_filter(&self, filter: &QueryFilter) -> Result<()> {
        let bodies = self.bodies_arena();
        match (filter.excluded_bodies.iter()).position(|handle| !bodies.owns(handle.0)) {
            Some(index) => Err(Error::new(
                format!("excluded_bodies[{index}]"),
                ErrorKind::StaleHandle,
            )),
            None => Ok(()),
        }
    }

    /// Calls `visit` with every body passing `filter` whose broad-phase box the ray meets within
    /// the current bound, nearer boxes first, static tree then moving tree. `visit` returns the
    /// new bound (the distance of its nearest hit, or infinity to keep the bound) or stops the
    /// walk. A filter [`check_filter`](Self::check_filter) refuses is an error, before any visit.
    fn visit_ray(
        &self,
        ray: &Ray,
        filter: &QueryFilter,
        visit: impl FnMut(BodyHandle, &RigidBody) -> ControlFlow<(), f32>,
    ) -> Result<()> {
        self.visit_candidates(
            filter,
            |tree, bound, tree_visit| tree.ray_cast(ray.origin, ray.direction, bound, tree_visit),
            ray.max_distance,
            visit,
        )
    }

    /// The walk of [`visit_ray`](Self::visit_ray) for any cast: `cast(tree, bound, callback)`
    /// runs one tree's cast with the current bound.
    fn visit_candidates<C, V>(
        &self,
        filter: &QueryFilter,
        mut cast: C,
        max_distance: f32,
        mut visit: V,
    ) -> Result<()>
    where
        C: FnMut(&DynamicTree, f32, &mut dyn FnMut(ProxyId, f32) -> ControlFlow<(), f32>),
        V: FnMut(BodyHandle, &RigidBody) -> ControlFlow<(), f32>,
    {
        self.check_filter(filter)?;
        let bodies = self.bodies_arena();
        let broad_phase = self.broad_phase();
        let mut bound = max_distance;
        for tree in [broad_phase.static_tree(), broad_phase.moving_tree()] {
            let mut stopped = false;
            cast(tree, bound, &mut |proxy, _entry| {
                let Some((index, body)) = bodies.at_slot(tree.user_data(proxy) as usize) else {
                    return ControlFlow::Continue(bound);
                };
                let handle = BodyHandle(index);
                if !filter.accepts(handle, body) {
                    return ControlFlow::Continue(bound);
                }
                let flow = visit(handle, body);
                match flow {
                    ControlFlow::Continue(new_bound) => bound = bound.min(new_bound),
                    ControlFlow::Break(()) => stopped = true,
                }
                flow
            });
            if stopped {
                break;
            }
        }
        Ok(())
    }

    /// Pushes into `bodies` every body passing `filter` whose broad-phase box overlaps `aabb`
    /// and for which `test` holds, then sorts them by handle; as [`visit_ray`](Self::visit_ray)
    /// for a filter refused.
    fn collect_overlaps<T: Ord>(
        &self,
        aabb: &Aabb,
        filter: &QueryFilter,
        found: &mut Vec<T>,
        mut visit: impl FnMut(BodyHandle, &RigidBody, &mut Vec<T>),
    ) -> Result<()> {
        self.check_filter(filter)?;
        let arena = self.bodies_arena();
        let broad_phase = self.broad_phase();
        for tree in [broad_phase.static_tree(), broad_phase.moving_tree()] {
            tree.query(aabb, |proxy| {
                if let Some((index, body)) = arena.at_slot(tree.user_data(proxy) as usize) {
                    let handle = BodyHandle(index);
                    if filter.accepts(handle, body) {
                        visit(handle, body, found);
                    }
                }
                true
            });
        }
        found.sort_unstable();
        Ok(())
    }
}

/// The first point where `ray` (validated) meets a collider of `body` that `filter` sees.
fn cast_ray_at_body(body: &RigidBody, ray: &Ray, filter: &QueryFilter) -> Option<ShapeRayHit> {
    let colliders = Colliders::of(body);
    cast_ray_at_shape(&body.shape, &body.pose(), ray, |collider| {
        filter.sees_collider(&colliders, collider)
    })
}

/// Whether `test(part, pose)` holds for some collider of `body` that `filter` sees, at its world
/// pose: the body's shape, or a compound's child.
fn any_collider_seen(
    body: &RigidBody,
    filter: &QueryFilter,
    test: impl Fn(&Shape, &Pose) -> bool,
) -> bool {
    let colliders = Colliders::of(body);
    convex_parts(&body.shape, body.pose()).any(|(collider, part, part_pose)| {
        filter.sees_collider(&colliders, collider) && test(part, &part_pose)
    })
}

/// Pushes `(handle, collider)` for each collider of `body` that `filter` sees and `test` holds
/// for, given its shape and world pose.
fn push_colliders_seen(
    handle: BodyHandle,
    body: &RigidBody,
    filter: &QueryFilter,
    found: &mut Vec<(BodyHandle, u32)>,
    test: impl Fn(&Shape, &Pose) -> bool,
) {
    let colliders = Colliders::of(body);
    for (collider, part, part_pose) in convex_parts(&body.shape, body.pose()) {
        if filter.sees_collider(&colliders, collider) && test(part, &part_pose) {
            found.push((handle, collider));
        }
    }
}

/// A [`RayHit`] on `body` along the (validated) ray.
fn ray_hit(ray: &Ray, body: BodyHandle, hit: &ShapeRayHit) -> RayHit {
    RayHit {
        body,
        collider: hit.part.collider,
        triangle: hit.part.triangle,
        point: ray.point_at(hit.distance),
        normal: hit.normal,
        distance: hit.distance,
    }
}
