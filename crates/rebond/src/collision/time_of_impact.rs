//! Time of impact: when, over a step, a fast body first comes within a target separation of
//! another, by conservative advancement with rotation (Mirtich's), so the step's continuous pass
//! can stop it there instead of letting it pass through.
//!
//! Over the step's fraction `t ∈ [0, 1]` each body's centre of mass moves in a straight line and
//! its orientation turns at a constant rate about a fixed axis ([`Motion::pose_at`]), so while
//! `t` grows by 1 no point of it moves more than `|Δc| + |Δθ| r`, `r` its reach from the centre
//! of mass. Along a fixed unit direction `n` from A toward B, the separation of two convex parts
//! therefore shrinks by at most `μ = (Δc_A − Δc_B)·n + |Δθ_A| r_A + |Δθ_B| r_B` per unit `t`;
//! measured along the direction of their closest points it is their distance `d`. Advancing `t`
//! by `(d − target) / μ` keeps them apart by at least the target, and repeated, `t` converges on
//! the first approach from below: the answer never lies past a contact.

use super::gjk::{self, SupportPoint};
use super::{epa, PosedCore, SupportMap};
use crate::math::{Aabb, Pose, Quat, Vec3};
use crate::shape::{Shape, Triangle};

/// Most distance queries per pair of parts. Advancement converges in a few on a face; a grazing
/// pass with rotation converges slowly, and stopping early leaves the answer short of the
/// contact, which is safe.
const MAX_ITERATIONS: usize = 24;

/// Halvings of the step that find where a part already touching the target goes too deep:
/// 12 leave the answer within 1/4096 of the step.
const BISECTIONS: usize = 12;

/// How a body moves over the step: from `end − Δ` to `end`, its centre of mass in a straight
/// line, its orientation about the fixed axis of the rotation vector `Δθ`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Motion {
    /// Centre of mass at the end of the step, world.
    pub end_center: Vec3,
    /// Orientation at the end of the step.
    pub end_rotation: Quat,
    /// Centre of mass in the body frame.
    pub local_center: Vec3,
    /// How far the centre of mass moved over the step, m.
    pub delta_position: Vec3,
    /// How far the body turned over the step, a world rotation vector, rad.
    pub delta_rotation: Vec3,
    /// Largest distance of a point of the body from its centre of mass, m.
    pub reach: f32,
}

impl Motion {
    /// The body-frame pose at fraction `t` of the step: `c(t) = c₁ − (1 − t) Δc`,
    /// `q(t) = exp(−(1 − t) Δθ) q₁`.
    pub fn pose_at(&self, t: f32) -> Pose {
        let back = 1.0 - t;
        let rotation =
            (Quat::from_scaled_axis(-back * self.delta_rotation) * self.end_rotation).normalize();
        let center = self.end_center - back * self.delta_position;
        Pose::new(center - rotation * self.local_center, rotation)
    }

    /// Upper bound of how fast a point of the body moves along unit `direction` per unit `t`,
    /// rotation included.
    fn speed_along(&self, direction: Vec3) -> f32 {
        self.delta_position.dot(direction) + self.delta_rotation.length() * self.reach
    }

    /// The box, in the frame of the fixed pose `frame`, that holds `shape` (at `shape_pose` in
    /// the body) over the whole step: its boxes at both ends, grown by how far the rotation can
    /// carry a point away from the straight path.
    pub fn swept_bounds(&self, shape: &Shape, shape_pose: &Pose, frame: &Pose) -> Aabb {
        let to_frame = frame.inverse();
        let [start, end] = [0.0, 1.0]
            .map(|t| shape.aabb(&to_frame.mul_pose(&self.pose_at(t).mul_pose(shape_pose))));
        let turn = Vec3::splat(self.delta_rotation.length() * self.reach);
        let bounds = start.union(&end);
        Aabb::new(bounds.min - turn, bounds.max + turn)
    }
}

/// What the continuous pass asks of a pair.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ImpactTolerances {
    /// The separation the answer leaves between the surfaces, m: within the contact margin, so
    /// the next step's contact sees the pair.
    pub target: f32,
    /// How deep into the other shape a body may end the step and still be left to the contact
    /// solver, m: no impact is reported for a pair that ends the step shallower (a body sliding
    /// from one face onto the next meets the next face's edge on its way, and stopping it there
    /// would stall it).
    pub tolerated_depth: f32,
}

/// Where a fast body is to be put back: the fraction `t` of the step it keeps, and the unit
/// normal from it toward what it met there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Impact {
    pub t: f32,
    pub normal: Vec3,
}

impl Impact {
    /// Keeps in `earliest` whichever of it and `impact` comes first (the one already kept on a
    /// tie).
    pub fn keep_earliest(earliest: &mut Option<Impact>, impact: Option<Impact>) {
        if let Some(impact) = impact {
            if earliest.is_none_or(|kept| impact.t < kept.t) {
                *earliest = Some(impact);
            }
        }
    }
}

/// One convex piece of the other body: a convex part that moves with it, a triangle of a fixed
/// mesh or heightfield, or a fixed halfspace (unit outward normal, a point of its plane).
enum Target<'a> {
    Part(&'a Shape, Pose, &'a Motion),
    Triangle(Triangle),
    Halfspace(Vec3, Vec3),
}

/// The earliest fraction of the step at which the fast body `a` (a convex shape or a compound of
/// them, moving as `motion_a`) meets `b` (any shape, moving as `motion_b`) in a way the contact
/// solver cannot undo: the pair ends the step deeper than [`ImpactTolerances::tolerated_depth`],
/// or on the other side of the part it met. A part that already touches the other at the step's
/// start and ends deep in it or past it all the same (it turned into it with a side its contact
/// did not see) meets it at `t = 0`. Only the colliders `i` of A and `j` of B (compound
/// children, or 0) for which `touch(i, j)` holds are looked at: the others make no contact. `None`
/// when nothing needs stopping.
pub(crate) fn time_of_impact(
    a: &Shape,
    motion_a: &Motion,
    b: &Shape,
    motion_b: &Motion,
    tolerances: ImpactTolerances,
    touch: impl Fn(u32, u32) -> bool,
) -> Option<Impact> {
    if a.is_triangulated() || !a.is_bounded() {
        return None;
    }
    let mut earliest: Option<Impact> = None;
    let mut consider = |part: &Shape, part_pose: Pose, target: &Target| {
        let impact = part_impact(part, &part_pose, motion_a, target, tolerances);
        Impact::keep_earliest(&mut earliest, impact);
    };
    let pose_b = motion_b.pose_at(1.0);
    for (collider, part, part_pose) in local_parts(a) {
        // A shape that is not a compound is the other body's collider 0.
        if !matches!(b, Shape::Compound(_)) && !touch(collider, 0) {
            continue;
        }
        match b {
            Shape::Halfspace(halfspace) => consider(
                part,
                part_pose,
                &Target::Halfspace(pose_b.transform_vector(halfspace.normal()), pose_b.position),
            ),
            Shape::TriMesh(_) | Shape::HeightField(_) => {
                let swept = motion_a.swept_bounds(part, &part_pose, &pose_b);
                b.triangles_in(&swept, |index| {
                    if let Some(local) = b.triangle(index) {
                        let triangle = Triangle {
                            vertices: local.vertices.map(|v| pose_b.transform_point(v)),
                            edge_flags: local.edge_flags,
                        };
                        consider(part, part_pose, &Target::Triangle(triangle));
                    }
                });
            }
            _ => {
                let path = motion_a.swept_bounds(part, &part_pose, &Pose::IDENTITY);
                for (target_collider, target, target_pose) in local_parts(b) {
                    if !touch(collider, target_collider) {
                        continue;
                    }
                    let target_path = motion_b.swept_bounds(target, &target_pose, &Pose::IDENTITY);
                    if !path.overlaps(&target_path) {
                        continue;
                    }
                    consider(
                        part,
                        part_pose,
                        &Target::Part(target, target_pose, motion_b),
                    );
                }
            }
        }
    }
    earliest
}

/// The convex parts of a bounded shape with their collider indices and poses in its body frame.
fn local_parts(shape: &Shape) -> impl Iterator<Item = (u32, &Shape, Pose)> {
    let (whole, children) = match shape {
        Shape::Compound(compound) => (None, compound.children()),
        _ => (Some((0, shape, Pose::IDENTITY)), &[][..]),
    };
    whole.into_iter().chain(
        (0..)
            .zip(children)
            .map(|(index, child)| (index, &child.shape, child.pose)),
    )
}

/// The separation of part A (world pose `pose_a`) from `target` at fraction `t`, m (a lower
/// bound of their distance while apart; minus their depth when they overlap), and the unit
/// direction from A toward the target along which it is measured (`None` only for degenerate
/// overlaps).
fn separation(part: &Shape, pose_a: &Pose, target: &Target, t: f32) -> (f32, Option<Vec3>) {
    let core_a = PosedCore::new(part, pose_a);
    match target {
        Target::Halfspace(normal, point) => {
            let deepest = lowest_point(part, pose_a, *normal);
            (normal.dot(deepest - *point), Some(-*normal))
        }
        Target::Triangle(triangle) => core_separation(&core_a, triangle, part.core_radius()),
        Target::Part(shape, local, motion) => {
            let pose_b = motion.pose_at(t).mul_pose(local);
            let core_b = PosedCore::new(shape, &pose_b);
            core_separation(&core_a, &core_b, part.core_radius() + shape.core_radius())
        }
    }
}

/// The point of `part` at `pose` farthest along `−up`, world.
fn lowest_point(part: &Shape, pose: &Pose, up: Vec3) -> Vec3 {
    part.support(pose.inverse_transform_vector(-up))
        .map_or(pose.position, |point| pose.transform_point(point))
}

/// The separation of two cores with `rounding` of radii between them: apart, a lower bound (the
/// reach of `A − B` along GJK's direction) and that direction from A toward B; overlapping,
/// minus their depth (EPA) and its direction.
fn core_separation<A: SupportMap, B: SupportMap>(
    a: &A,
    b: &B,
    rounding: f32,
) -> (f32, Option<Vec3>) {
    let distance = gjk::distance(a, b);
    match distance.normal() {
        Some(normal) => {
            let farthest = SupportPoint::new(a, b, normal).w;
            (-normal.dot(farthest) - rounding, Some(normal))
        }
        None => epa::penetration(a, b).map_or((-rounding, None), |penetration| {
            (-penetration.depth - rounding, Some(penetration.normal))
        }),
    }
}

/// Conservative advancement of `part` of the fast body (pose `part_pose` in its body) toward
/// `target`, then the check of how the step ends ([`time_of_impact`]). A part that already
/// touches the target at the start had its contact in the step; it goes back to the start only
/// if it ended deep in or past the target all the same.
fn part_impact(
    part: &Shape,
    part_pose: &Pose,
    motion: &Motion,
    target: &Target,
    tolerances: ImpactTolerances,
) -> Option<Impact> {
    let pose_at = |t: f32| motion.pose_at(t).mul_pose(part_pose);
    let target_speed = |normal: Vec3| match target {
        Target::Part(_, _, other) => other.speed_along(-normal),
        Target::Triangle(_) | Target::Halfspace(..) => 0.0,
    };
    let touching = tolerances.target * 1.25;
    let ends = Ends {
        start: pose_at(0.0),
        end: pose_at(1.0),
    };
    let (start, start_normal) = separation(part, &ends.start, target, 0.0);
    let mut hit_normal = start_normal?;
    if start <= touching {
        if !ends.too_deep(part, target, hit_normal, tolerances) {
            return None;
        }
        // The last fraction of the step at which the part is no deeper in the target than it
        // started (by more than the target separation) nor past it: there its other side, the
        // one its contact did not see, reaches the target, and the next contact sees both.
        let start_depth = (-start).max(0.0);
        let deeper = |t: f32| {
            let (gap, normal) = separation(part, &pose_at(t), target, t);
            if gap > 0.0 {
                normal.is_some_and(|normal| normal.dot(hit_normal) < -0.5)
            } else {
                -gap > start_depth + tolerances.target
            }
        };
        let (mut safe, mut deep) = (0.0, 1.0);
        for _ in 0..BISECTIONS {
            let middle = 0.5 * (safe + deep);
            if deeper(middle) {
                deep = middle;
            } else {
                safe = middle;
            }
        }
        return Some(Impact {
            t: safe,
            normal: hit_normal,
        });
    }
    let mut t = 0.0;
    for _ in 0..MAX_ITERATIONS {
        let (gap, normal) = separation(part, &pose_at(t), target, t);
        let Some(normal) = normal else {
            break;
        };
        hit_normal = normal;
        if gap <= touching {
            break;
        }
        let closing = motion.speed_along(normal) + target_speed(normal);
        if closing <= 0.0 {
            return None;
        }
        t += (gap - tolerances.target) / closing;
        if t >= 1.0 {
            return None;
        }
    }
    ends.too_deep(part, target, hit_normal, tolerances)
        .then_some(Impact {
            t,
            normal: hit_normal,
        })
}

/// A part's poses at the start and the end of the step, world.
struct Ends {
    start: Pose,
    end: Pose,
}

impl Ends {
    /// Whether the part, ending the step at `end`, lies deeper in `target` than the contact
    /// solver is left to handle, or has passed to its far side from where it met it along
    /// `hit_normal` (from the part toward the target). Against a triangle the depth is measured
    /// below its plane, on the side the part's centre starts from: a body sliding over a flat
    /// mesh crosses triangle edges without going under the surface.
    fn too_deep(
        &self,
        part: &Shape,
        target: &Target,
        hit_normal: Vec3,
        tolerances: ImpactTolerances,
    ) -> bool {
        if let Target::Triangle(triangle) = target {
            let Some(face) = triangle.normal() else {
                return false;
            };
            let corner = triangle.vertices[0];
            let up = if face.dot(self.start.position - corner) >= 0.0 {
                face
            } else {
                -face
            };
            let lowest = lowest_point(part, &self.end, up);
            return -up.dot(lowest - corner) > tolerances.tolerated_depth;
        }
        let (gap, normal) = separation(part, &self.end, target, 1.0);
        if gap > 0.0 {
            // Apart at the end: through the target if it now lies behind the part.
            normal.is_some_and(|normal| normal.dot(hit_normal) < -0.5)
        } else {
            -gap > tolerances.tolerated_depth
        }
    }
}
