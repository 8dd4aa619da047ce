//! Penetration of two overlapping convex solids by the Expanding Polytope Algorithm (EPA), and
//! the contact query the narrow phase runs on every pair of shape cores.
//!
//! When A and B overlap, the origin lies inside their Minkowski difference `A − B`, and the
//! shortest translation of B that separates them reaches the point of the boundary of `A − B`
//! closest to the origin. EPA grows a polytope inside `A − B` from GJK's final simplex: it takes
//! the polytope face closest to the origin (a lower bound on the depth), adds the support point
//! along that face's normal (an upper bound along that direction), replaces the faces the new
//! point sees by a fan around it, and stops when the bounds meet.
//!
//! Tolerances are relative to the size of the problem, the largest `|a − b|` among the polytope's
//! vertices (never less than the depth, since the origin is inside), for the same reason as in
//! GJK: every support point carries an f32 rounding of about `6e-8` of its magnitude.

use std::cmp::Ordering;

use crate::collision::gjk::{self, Simplex, SimplexCache, SupportPoint};
use crate::collision::{LocalCore, PosedCore, RelativeCore, SupportMap};
use crate::math::Vec3;

/// Most support points one query adds to the polytope. Polytopes need a few dozen at most;
/// smooth surfaces refine around the answer until the tolerance is met, except on exact ties
/// (a point on a cylinder's axis is as deep in every direction across it), where EPA settles
/// for the shallowest direction found, within about 1e-3 of the size.
pub const MAX_ITERATIONS: usize = 128;

/// Relative precision of the depth: EPA stops once the support point along the closest face's
/// normal lies within `TOLERANCE · scale` of that face (the depth along the normal is then
/// known to that precision). About 150 f32 rounding steps, as in [`gjk::TOLERANCE`]. It is also
/// the slack of the check that the polytope only grows: a new face nearer the origin than the
/// closest one by more than this means rounding has folded the polytope, and the vertex is not
/// added.
pub const TOLERANCE: f32 = 1e-5;

/// How precisely the contact query ([`Polytope::contact_from`]) measures the depth, metres, when
/// the relative [`TOLERANCE`] asks for more: a twentieth of a millimetre, far below a resting
/// contact's depth (a few millimetres). EPA's depth errs on the deep side, by
/// up to this, so it is half of GJK's [`gjk::CONTACT_PRECISION`], which errs on the shallow side:
/// with f32 rounding, within the 0.1 mm the narrow phase's tests allow. `mixed` runs about 1 %
/// fewer instructions than at the relative tolerance alone.
pub const CONTACT_PRECISION: f32 = 5e-5;

/// A new vertex sees a face only when it lies more than `COPLANAR · scale` in front of it.
/// Support points often lie in the plane of existing faces (all of a cylinder's lie on its rims,
/// so its caps fill with coplanar faces), and rounding alone would then decide, face by face,
/// whether they are seen, tearing holes in the region to replace. Ten f32 rounding steps lie
/// below this, and a tenth of [`TOLERANCE`] above it: faces left in place despite being seen by
/// less than that dent the polytope by no more.
const COPLANAR: f32 = 1e-6;

/// A face whose area is below this fraction of `scale · perimeter` has no reliable normal
/// (about ten f32 rounding steps) and is never chosen as the closest face.
const DEGENERACY: f32 = 1e-6;

/// The world axes, probed when there is no better direction to try.
const AXES: [Vec3; 6] = [
    Vec3::X,
    Vec3::NEG_X,
    Vec3::Y,
    Vec3::NEG_Y,
    Vec3::Z,
    Vec3::NEG_Z,
];

/// How deep two overlapping solids A and B are, and along which direction.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Penetration {
    /// Unit world direction from A toward B: translating B by `depth · normal` separates them.
    pub normal: Vec3,
    /// Length of the shortest separating translation, metres; never negative, and zero only
    /// when the solids merely touch or `A − B` is flat (two points, or a point and a segment).
    pub depth: f32,
    /// Point of A deepest inside B (world).
    pub point_a: Vec3,
    /// Point of B deepest inside A (world): `point_a − point_b = depth · normal`.
    pub point_b: Vec3,
}

/// Where two convex shapes touch, or nearly do, measured on their rounded surfaces.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContactInfo {
    /// Unit world normal from A toward B.
    pub normal: Vec3,
    /// Distance between the surfaces along the normal, metres: negative when they overlap.
    pub separation: f32,
    /// Point of A's surface (world).
    pub point_a: Vec3,
    /// Point of B's surface (world): `point_b − point_a = separation · normal`.
    pub point_b: Vec3,
}

/// Contact between two convex shape cores when their rounded surfaces are less than `margin`
/// apart: [`Polytope::contact`] with a polytope of its own, which allocates when EPA runs.
pub fn contact(a: &PosedCore, b: &PosedCore, margin: f32) -> Option<ContactInfo> {
    Polytope::default().contact(a, b, margin)
}

/// The penetration of A and B, or `None` when they are apart.
pub fn penetration<A, B>(a: &A, b: &B) -> Option<Penetration>
where
    A: SupportMap + ?Sized,
    B: SupportMap + ?Sized,
{
    let distance = gjk::distance(a, b);
    distance
        .overlapping
        .then(|| Polytope::default().penetration(a, b, &distance.simplex))
}

/// A triangle of the polytope, counter-clockwise seen from outside.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Face {
    vertices: [usize; 3],
    /// The face across each edge `vertices[k] → vertices[k + 1]`.
    neighbors: [usize; 3],
    /// Unit outward normal; zero for a degenerate face.
    normal: Vec3,
    /// Signed distance of the face's plane from the origin; infinite for a degenerate face.
    distance: f32,
    /// Replaced by newer faces; kept in place so that indices stay valid.
    removed: bool,
    /// Its support point could not be added (rounding made the polytope inconsistent there):
    /// never again chosen as the closest face.
    stuck: bool,
}

impl Face {
    /// How far `point` lies in front of the face; infinite for a degenerate face, which has no
    /// plane and which any new vertex reaching it replaces.
    fn height_of(&self, point: Vec3) -> f32 {
        if self.distance.is_finite() {
            self.normal.dot(point) - self.distance
        } else {
            f32::INFINITY
        }
    }
}

/// Which edge `vertices[k] → vertices[k + 1]` of a triangle runs `from → to`.
fn edge_index(vertices: [usize; 3], from: usize, to: usize) -> Option<usize> {
    (0..3).find(|&k| vertices[k] == from && vertices[(k + 1) % 3] == to)
}

/// An edge of the rim of the faces a new vertex replaces, as it runs on a replaced face.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct RimEdge {
    from: usize,
    to: usize,
    /// The face across the edge, which stays.
    outside: usize,
    /// The edge's index in `outside`.
    outside_edge: usize,
}

/// The polytope EPA grows, with its scratch space: keep one to run many queries without
/// allocating.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Polytope {
    vertices: Vec<SupportPoint>,
    faces: Vec<Face>,
    /// The rim of the faces the newest vertex replaces, in order around it.
    rim: Vec<RimEdge>,
    /// The faces the newest vertex replaces, to restore them if it cannot be added.
    replaced: Vec<usize>,
    /// Flood fill over the faces the newest vertex sees: each face with the index of the next
    /// of its edges to cross, and how many remain.
    stack: Vec<(usize, usize, usize)>,
}

impl Polytope {
    /// Contact between two convex shape cores when their rounded surfaces are less than `margin`
    /// apart (`margin` may be negative to ask for overlaps only). GJK measures the cores, EPA takes
    /// over when the cores overlap, growing this polytope, and the rounding radii are then
    /// subtracted. Both run in A's frame.
    pub fn contact(&mut self, a: &PosedCore, b: &PosedCore, margin: f32) -> Option<ContactInfo> {
        self.contact_from(a, b, margin, &mut SimplexCache::default())
    }

    /// [`Polytope::contact`] with GJK starting from `simplex`, the simplex of the last query
    /// between the same two shapes (or an empty one), and leaving there the simplex it ends
    /// with.
    pub fn contact_from(
        &mut self,
        a: &PosedCore,
        b: &PosedCore,
        margin: f32,
        simplex: &mut SimplexCache,
    ) -> Option<ContactInfo> {
        let radius_a = a.shape.core_radius();
        let radius_b = b.shape.core_radius();
        let limit = margin + radius_a + radius_b;
        let (local_a, local_b) = (LocalCore(a.shape), RelativeCore::new(b, a.pose));
        let (start, len) = simplex.placed(&local_b);
        let cores =
            gjk::distance_within(&local_a, &local_b, &start[..len], local_b.position, limit)?;
        *simplex = SimplexCache::new(&cores.simplex, &local_b);
        // Overlapping cores are as far apart as EPA's depth says, checked below.
        if !cores.overlapping && cores.distance - radius_a - radius_b >= margin {
            return None;
        }
        let (normal, core_separation, core_a, core_b) = match cores.normal() {
            Some(normal) => (normal, cores.distance, cores.point_a, cores.point_b),
            None => {
                let deepest =
                    self.penetration_within(&local_a, &local_b, &cores.simplex, CONTACT_PRECISION);
                (
                    deepest.normal,
                    -deepest.depth,
                    deepest.point_a,
                    deepest.point_b,
                )
            }
        };
        let separation = core_separation - radius_a - radius_b;
        let normal = a.pose.transform_vector(normal);
        (separation < margin).then(|| ContactInfo {
            normal,
            separation,
            point_a: a.pose.transform_point(core_a) + radius_a * normal,
            point_b: a.pose.transform_point(core_b) - radius_b * normal,
        })
    }

    /// The penetration of A and B, starting from `simplex`, the final simplex of a GJK query that
    /// found them overlapping. Always answers: when rounding or the iteration budget defeats the
    /// algorithm, with the shallowest direction found so far.
    pub fn penetration<A, B>(&mut self, a: &A, b: &B, simplex: &Simplex) -> Penetration
    where
        A: SupportMap + ?Sized,
        B: SupportMap + ?Sized,
    {
        self.penetration_within(a, b, simplex, 0.0)
    }

    /// [`Polytope::penetration`], stopping once the depth is known within [`TOLERANCE`] of the
    /// problem's size or within `precision` metres, whichever is looser.
    fn penetration_within<A, B>(
        &mut self,
        a: &A,
        b: &B,
        simplex: &Simplex,
        precision: f32,
    ) -> Penetration
    where
        A: SupportMap + ?Sized,
        B: SupportMap + ?Sized,
    {
        self.vertices.clear();
        self.faces.clear();
        let mut scale = match self.seed(a, b, simplex) {
            Ok(scale) => scale,
            Err(answer) => return answer,
        };
        // Each support point bounds the depth from above, along its direction, and the closest
        // face bounds it from below. The answer is the direction of least upper bound, once the
        // two bounds meet (or when the iterations run out).
        let mut best: Option<(f32, usize, SupportPoint)> = None;
        for _ in 0..MAX_ITERATIONS {
            let Some(closest) = self.closest_face() else {
                break;
            };
            let face = self.faces[closest];
            let point = SupportPoint::new(a, b, face.normal);
            if !point.w.is_finite() {
                break;
            }
            scale = scale.max(point.w.length());
            let tolerance = TOLERANCE * scale;
            let reach = point.w.dot(face.normal);
            let (least, _, _) = *best.get_or_insert((reach, closest, point));
            if reach < least {
                best = Some((reach, closest, point));
            }
            if reach.min(least) - face.distance <= tolerance.max(precision) {
                break;
            }
            if !self.add_vertex(point, closest, tolerance, scale) {
                self.faces[closest].stuck = true;
            }
        }
        match best {
            Some((_, face, support)) => self.answer(face, support),
            None => Prober::new(a, b, simplex).fallback(),
        }
    }

    /// Grows the GJK simplex into a tetrahedron of `A − B` around the origin and returns the
    /// problem's scale. Each direction probed on the way bounds the depth from above; when one
    /// shows an overlap within tolerance of zero, `A − B` is flat there or the origin is on its
    /// boundary, and that direction is the answer, returned as the error. So is the shallowest
    /// direction probed when no solid tetrahedron can be built.
    fn seed<A, B>(&mut self, a: &A, b: &B, simplex: &Simplex) -> Result<f32, Penetration>
    where
        A: SupportMap + ?Sized,
        B: SupportMap + ?Sized,
    {
        self.vertices.extend_from_slice(simplex.points());
        let mut prober = Prober::new(a, b, simplex);
        if let [first] = self.vertices[..] {
            // A single point at the origin: any support point along an axis leaves it.
            let mut farthest = first;
            for direction in AXES {
                let point = prober.probe(direction)?;
                if point.w.distance_squared(first.w) > farthest.w.distance_squared(first.w) {
                    farthest = point;
                }
            }
            self.vertices.push(farthest);
        }
        if let [first, second] = self.vertices[..] {
            // A segment through the origin: look across it for the point farthest off its line.
            let axis = (second.w - first.w).normalize_or(Vec3::X);
            let across = axis.any_orthonormal_vector();
            let mut farthest = first;
            let mut farthest_off_line = 0.0;
            for direction in [across, -across, axis.cross(across), -axis.cross(across)] {
                let point = prober.probe(direction)?;
                let offset = point.w - first.w;
                let off_line = (offset - axis * offset.dot(axis)).length_squared();
                if off_line > farthest_off_line {
                    farthest = point;
                    farthest_off_line = off_line;
                }
            }
            self.vertices.push(farthest);
        }
        if let [first, second, third] = self.vertices[..] {
            // A triangle through the origin: the point farther from its plane, on either side,
            // closes the better-shaped tetrahedron holding the origin on its base.
            let Some(normal) = (second.w - first.w)
                .cross(third.w - first.w)
                .try_normalize()
            else {
                return Err(prober.fallback());
            };
            let above = prober.probe(normal)?;
            let below = prober.probe(-normal)?;
            let farther = if above.w.dot(normal) >= -below.w.dot(normal) {
                above
            } else {
                below
            };
            self.vertices.push(farther);
        }
        let [first, second, third, fourth] = self.vertices[..] else {
            return Err(prober.fallback());
        };
        let scale = prober.scale;
        let (u, v, w) = (second.w - first.w, third.w - first.w, fourth.w - first.w);
        let volume = u.dot(v.cross(w));
        let edge_products =
            u.length() * v.length() + v.length() * w.length() + w.length() * u.length();
        if volume.abs() <= DEGENERACY * scale * edge_products {
            return Err(prober.fallback());
        }
        // With a negative volume these four triangles wind counter-clockwise from outside.
        let (one, two) = if volume > 0.0 { (2, 1) } else { (1, 2) };
        let faces = [[0, one, two], [0, 3, one], [0, two, 3], [one, 3, two]];
        for vertices in faces {
            let mut face = self.face(vertices, scale);
            if !face.distance.is_finite() {
                return Err(prober.fallback());
            }
            // Each edge is shared with the one other face holding it reversed.
            for k in 0..3 {
                let (from, to) = (vertices[k], vertices[(k + 1) % 3]);
                face.neighbors[k] = faces
                    .iter()
                    .position(|&other| edge_index(other, to, from).is_some())
                    .unwrap_or(0);
            }
            self.faces.push(face);
        }
        Ok(scale)
    }

    /// The face through three vertices, with its normal and distance; not linked to its
    /// neighbours yet.
    fn face(&self, vertices: [usize; 3], scale: f32) -> Face {
        let [a, b, c] = vertices.map(|index| self.vertices[index].w);
        let cross = (b - a).cross(c - a);
        let perimeter = (b - a).length() + (c - b).length() + (a - c).length();
        let length = cross.length();
        let (normal, distance) = if length > DEGENERACY * scale * perimeter && length.is_finite() {
            let normal = cross / length;
            (normal, normal.dot(a))
        } else {
            (Vec3::ZERO, f32::INFINITY)
        };
        Face {
            vertices,
            neighbors: [0; 3],
            normal,
            distance,
            removed: false,
            stuck: false,
        }
    }

    /// Index of the face nearest the origin, among the current non-degenerate ones.
    fn closest_face(&self) -> Option<usize> {
        self.faces
            .iter()
            .enumerate()
            .filter(|(_, face)| !face.removed && !face.stuck && face.distance.is_finite())
            .min_by(|(_, x), (_, y)| {
                x.distance
                    .partial_cmp(&y.distance)
                    .unwrap_or(Ordering::Equal)
            })
            .map(|(index, _)| index)
    }

    /// Adds `point`, outside the polytope beyond face `closest`: replaces the faces it sees by a
    /// fan of new faces around it. Returns false, leaving the polytope as it was, when rounding
    /// makes that inconsistent.
    ///
    /// The faces seen are found by flood fill from `closest`, which yields the rim of the hole
    /// in order. A face counts as seen when the point lies more than [`COPLANAR`] (relative) in
    /// front of it; if the rim is still not a single loop, faces up to that far behind the point
    /// count as seen instead. Either way the polytope stays convex to within that slack. No new
    /// face may then come nearer the origin than `closest` by more than `tolerance`.
    fn add_vertex(
        &mut self,
        point: SupportPoint,
        closest: usize,
        tolerance: f32,
        scale: f32,
    ) -> bool {
        let nearest = self.faces[closest].distance;
        let index = self.vertices.len();
        self.vertices.push(point);
        let coplanar = COPLANAR * scale;
        for seen_above in [coplanar, -coplanar] {
            if self.find_rim(point.w, closest, seen_above)
                && self.close_rim(index, nearest, tolerance, scale)
            {
                return true;
            }
            for &face in &self.replaced {
                self.faces[face].removed = false;
            }
        }
        self.vertices.pop();
        false
    }

    /// Marks removed the faces connected to `start` that `point` lies more than `seen_above` in
    /// front of, and lists the rim around them in order. Returns whether the rim is one loop.
    fn find_rim(&mut self, point: Vec3, start: usize, seen_above: f32) -> bool {
        self.rim.clear();
        self.replaced.clear();
        self.stack.clear();
        self.faces[start].removed = true;
        self.replaced.push(start);
        self.stack.push((start, 0, 3));
        while let Some(top) = self.stack.last_mut() {
            let (face, edge, remaining) = *top;
            if remaining == 0 {
                self.stack.pop();
                continue;
            }
            *top = (face, (edge + 1) % 3, remaining - 1);
            let [from, to] = [edge, (edge + 1) % 3].map(|k| self.faces[face].vertices[k]);
            let across = self.faces[face].neighbors[edge];
            let neighbor = self.faces[across];
            if neighbor.removed {
                continue;
            }
            let Some(back) = edge_index(neighbor.vertices, to, from) else {
                return false;
            };
            if neighbor.height_of(point) > seen_above {
                self.faces[across].removed = true;
                self.replaced.push(across);
                // Go round the neighbour starting after the edge just crossed.
                self.stack.push((across, (back + 1) % 3, 2));
            } else {
                self.rim.push(RimEdge {
                    from,
                    to,
                    outside: across,
                    outside_edge: back,
                });
            }
        }
        is_single_loop(&self.rim)
    }

    /// Closes the rim with a fan of faces to vertex `apex`, unless one would come nearer the
    /// origin than `nearest − tolerance`.
    fn close_rim(&mut self, apex: usize, nearest: f32, tolerance: f32, scale: f32) -> bool {
        let first = self.faces.len();
        let count = self.rim.len();
        for (i, edge) in self.rim.iter().enumerate() {
            let face = self.face([edge.from, edge.to, apex], scale);
            if face.distance < nearest - tolerance {
                self.faces.truncate(first);
                return false;
            }
            self.faces.push(Face {
                neighbors: [
                    edge.outside,
                    first + (i + 1) % count,
                    first + (i + count - 1) % count,
                ],
                ..face
            });
        }
        for (i, edge) in self.rim.iter().enumerate() {
            self.faces[edge.outside].neighbors[edge.outside_edge] = first + i;
        }
        true
    }

    /// The penetration along the normal of face `face`, whose support point in `A − B` is
    /// `support`: as deep as that point reaches along it. The points of A and B are found where
    /// the ray from the origin along the normal leaves the polytope, in the face it meets inside
    /// its triangle: that face itself when the ray's crossing of its plane lies inside it, as it
    /// does once EPA has converged, else the face the ray passes nearest (a neighbour in the same
    /// plane, as a box face or a cylinder cap is split into several triangles, or another face
    /// when the normal came from a sliver). They are then moved along the normal onto A's and B's
    /// support planes, so that they lie on the surfaces and `point_a − point_b = depth · normal`
    /// exactly. The move is within the tolerance once EPA has converged.
    fn answer(&self, face: usize, support: SupportPoint) -> Penetration {
        let normal = self.faces[face].normal;
        // The face's vertices around the ray's crossing of its plane, reduced to the part
        // nearest the ray, or `None` when the face does not face along the ray.
        let exit_through = |candidate: &Face| {
            let facing = candidate.normal.dot(normal);
            if candidate.removed || !candidate.distance.is_finite() || facing <= 0.0 {
                return None;
            }
            let crossing = candidate.distance / facing * normal;
            let shifted = candidate.vertices.map(|index| {
                let point = self.vertices[index];
                SupportPoint {
                    w: point.w - crossing,
                    ..point
                }
            });
            let (nearest, _) = Simplex::reduced(&shifted);
            Some(nearest)
        };
        let exit = match exit_through(&self.faces[face]) {
            Some(inside) if inside.points().len() == 3 => inside,
            _ => {
                let mut nearest = (f32::INFINITY, Simplex::default());
                for candidate in &self.faces {
                    if let Some(through) = exit_through(candidate) {
                        let miss = through.closest_point().length_squared();
                        if miss < nearest.0 {
                            nearest = (miss, through);
                        }
                    }
                }
                nearest.1
            }
        };
        let (inside_a, inside_b) = exit.witness_points();
        penetration_along(normal, support, inside_a, inside_b)
    }
}

/// Whether the rim, as listed, runs once round a single loop: each edge ends where the next
/// begins, and no vertex is left twice.
fn is_single_loop(rim: &[RimEdge]) -> bool {
    let chained = (0..rim.len()).all(|i| rim[i].to == rim[(i + 1) % rim.len()].from);
    let simple = (0..rim.len()).all(|i| (0..i).all(|j| rim[i].from != rim[j].from));
    rim.len() >= 3 && chained && simple
}

/// The penetration along unit `normal`, as deep as `support`, the support point of `A − B`
/// along it, reaches. `inside_a` and `inside_b`, points of A and B whose difference lies along
/// the normal (or is negligible), are moved along it onto A's and B's support planes, so that
/// they lie on the surfaces and `point_a − point_b = depth · normal`.
fn penetration_along(
    normal: Vec3,
    support: SupportPoint,
    inside_a: Vec3,
    inside_b: Vec3,
) -> Penetration {
    Penetration {
        normal,
        depth: support.w.dot(normal).max(0.0),
        point_a: inside_a + (support.a - inside_a).dot(normal) * normal,
        point_b: inside_b + (support.b - inside_b).dot(normal) * normal,
    }
}

/// Support points of `A − B` along the directions tried while seeding the polytope, keeping
/// the direction of least overlap as a fallback answer.
struct Prober<'q, A: ?Sized, B: ?Sized> {
    a: &'q A,
    b: &'q B,
    simplex: &'q Simplex,
    /// Largest `|w|` seen so far.
    scale: f32,
    /// The direction of least overlap so far, with its support point.
    shallowest: Option<(Vec3, SupportPoint)>,
}

impl<'q, A, B> Prober<'q, A, B>
where
    A: SupportMap + ?Sized,
    B: SupportMap + ?Sized,
{
    fn new(a: &'q A, b: &'q B, simplex: &'q Simplex) -> Self {
        Self {
            a,
            b,
            simplex,
            scale: simplex.scale(),
            shallowest: None,
        }
    }

    /// The support point along unit `direction`, or, when A and B overlap along it by no more
    /// than the tolerance, the answer.
    fn probe(&mut self, direction: Vec3) -> Result<SupportPoint, Penetration> {
        let point = SupportPoint::new(self.a, self.b, direction);
        let overlap = point.w.dot(direction);
        self.scale = self.scale.max(point.w.length());
        if self
            .shallowest
            .is_none_or(|(least, support)| overlap < support.w.dot(least))
        {
            self.shallowest = Some((direction, point));
        }
        if overlap <= TOLERANCE * self.scale {
            Err(self.along(direction, point))
        } else {
            Ok(point)
        }
    }

    /// Last resort when no polytope can be built: the direction of least overlap probed so far,
    /// or, with none probed, the world axis of least overlap.
    fn fallback(&mut self) -> Penetration {
        if self.shallowest.is_none() {
            for direction in AXES {
                if let Err(answer) = self.probe(direction) {
                    return answer;
                }
            }
        }
        let (direction, point) = self
            .shallowest
            .unwrap_or_else(|| (Vec3::X, SupportPoint::new(self.a, self.b, Vec3::X)));
        self.along(direction, point)
    }

    /// The penetration along `direction`, with the GJK simplex's point common to A and B as the
    /// contact.
    fn along(&self, direction: Vec3, point: SupportPoint) -> Penetration {
        let (inside_a, inside_b) = self.simplex.witness_points();
        penetration_along(direction, point, inside_a, inside_b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Pose, Quat};
    use crate::shape::Shape;

    // Values of order one from exact inputs; 1e-4 covers TOLERANCE (1e-5 relative) with margin.
    const CLOSE: f32 = 1e-4;

    /// GJK may stop with 1, 2 or 3 points around the origin; EPA must build a tetrahedron from
    /// any of them. A is a bipyramid on the triangle (2, −1, 0), (−1, 2, 0), (−1, −1, 0) with
    /// apexes (0, 0, ±1), B a point at the origin (a sphere's core), so A − B = A: its faces
    /// nearest the origin are x + y ± z = 1, at 1/√3.
    #[test]
    fn blows_up_small_simplices() {
        let equator = [
            Vec3::new(2.0, -1.0, 0.0),
            Vec3::new(-1.0, 2.0, 0.0),
            Vec3::new(-1.0, -1.0, 0.0),
        ];
        let apexes = [Vec3::Z, Vec3::NEG_Z];
        let bipyramid = Shape::convex_hull(&[equator.as_slice(), &apexes].concat()).unwrap();
        let ball = Shape::sphere(0.5).unwrap();
        let pose = Pose::IDENTITY;
        let a = PosedCore {
            shape: &bipyramid,
            pose: &pose,
        };
        let b = PosedCore {
            shape: &ball,
            pose: &pose,
        };
        let of_a = |point: Vec3| SupportPoint {
            a: point,
            b: Vec3::ZERO,
            w: point,
        };
        let simplices = [
            vec![of_a(Vec3::ZERO)],
            apexes.map(of_a).to_vec(),
            equator.map(of_a).to_vec(),
        ];
        for points in simplices {
            let (simplex, _) = Simplex::reduced(&points);
            assert_eq!(simplex.points().len(), points.len());
            let found = Polytope::default().penetration(&a, &b, &simplex);
            assert!(
                (found.depth - 3.0f32.sqrt().recip()).abs() < CLOSE,
                "{found:?}"
            );
            let expected = Vec3::new(1.0, 1.0, found.normal.z.signum()) / 3.0f32.sqrt();
            assert!((found.normal - expected).length() < CLOSE, "{found:?}");
            let gap = found.point_a - found.point_b - found.depth * found.normal;
            assert!(gap.length() < CLOSE, "{found:?}");
        }
    }

    /// Sphere and capsule cores are points and segments: when they meet, `A − B` is a point, a
    /// segment or a parallelogram holding the origin, and the depth is zero along some unit
    /// normal.
    #[test]
    fn flat_differences_have_zero_depth() {
        let ball = Shape::sphere(1.0).unwrap();
        let stick = Shape::capsule(0.5, 1.0).unwrap();
        let here = Pose::from_position(Vec3::new(0.5, -0.25, 2.0));
        let across = Pose::new(here.position, Quat::from_rotation_z(1.0));
        for (a, b) in [(&ball, &ball), (&ball, &stick), (&stick, &stick)] {
            let core_a = PosedCore {
                shape: a,
                pose: &here,
            };
            let core_b = PosedCore {
                shape: b,
                pose: &across,
            };
            let found = penetration(&core_a, &core_b).expect("the cores meet");
            assert!(found.depth.abs() < CLOSE, "{found:?}");
            assert!((found.normal.length() - 1.0).abs() < CLOSE, "{found:?}");
        }
    }

    /// Cores that overlap are in contact whatever the margin: a margin of zero or below asks for
    /// overlaps only, and these cylinders (no rounding) overlap by 0.5 m.
    #[test]
    fn overlapping_cores_report_with_margins_down_to_zero_and_below() {
        let cylinder = Shape::cylinder(0.4, 0.35).unwrap();
        let (low, high) = (
            Pose::IDENTITY,
            Pose::from_position(Vec3::new(0.1, 0.2, 0.0)),
        );
        let core = |pose| PosedCore {
            shape: &cylinder,
            pose,
        };
        for margin in [0.0, -0.4] {
            let found = contact(&core(&low), &core(&high), margin).expect("they overlap");
            assert!((found.separation + 0.5).abs() < CLOSE, "{found:?}");
        }
        assert!(contact(&core(&low), &core(&high), -0.6).is_none());
    }

    #[test]
    fn single_loop_rims() {
        let edge = |from, to| RimEdge {
            from,
            to,
            outside: 0,
            outside_edge: 0,
        };
        assert!(is_single_loop(&[edge(1, 2), edge(2, 3), edge(3, 1)]));
        assert!(!is_single_loop(&[edge(1, 2), edge(2, 1)]));
        assert!(!is_single_loop(&[edge(1, 2), edge(3, 1), edge(2, 3)]));
        let figure_eight = [
            edge(1, 2),
            edge(2, 3),
            edge(3, 1),
            edge(1, 4),
            edge(4, 5),
            edge(5, 1),
        ];
        assert!(!is_single_loop(&figure_eight));
    }
}
