//! Penetration of two overlapping convex solids by the Expanding Polytope Algorithm (EPA), and
//! the contact query the narrow phase runs on every pair of shape cores.
//!
//! When A and B overlap, the origin lies inside their Minkowski difference `A − B`, and the
//! shortest translation of B that separates them reaches the point of the boundary of `A − B`
//! closest to the origin. EPA grows a polytope inside `A − B` from GJK's final simplex: it takes
//! the polytope face closest to the origin, adds the support point along that face's normal,
//! replaces the faces the new point sees by a fan around it, and stops when the support point is
//! no farther out than the face.
//!
//! Tolerances are relative to the size of the problem, the largest `|a − b|` among the polytope's
//! vertices (never less than the depth, since the origin is inside), for the same reason as in
//! GJK: every support point carries an f32 rounding of about `6e-8` of its magnitude.

use std::cmp::Ordering;

use crate::collision::gjk::{self, Simplex, SupportPoint};
use crate::collision::{PosedCore, SupportMap};
use crate::math::Vec3;

/// Most support points one query adds to the polytope. Polytopes need a few dozen at most;
/// smooth surfaces refine around the answer until the tolerance is met.
pub const MAX_ITERATIONS: usize = 128;

/// Relative precision of the depth: EPA stops once the support point along the closest face's
/// normal lies within `TOLERANCE · scale` of that face (the depth along the normal is then
/// known to that precision). About 150 f32 rounding steps, as in [`gjk::TOLERANCE`]. It is also
/// the slack of the check that the polytope only grows: a new face nearer the origin than the
/// closest one by more than this means rounding has folded the polytope, and the vertex is not
/// added.
pub const TOLERANCE: f32 = 1e-5;

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
/// apart (`margin` may be negative to ask for overlaps only). GJK measures the cores, EPA takes
/// over when the cores overlap, and the rounding radii are then subtracted.
pub fn contact(a: &PosedCore, b: &PosedCore, margin: f32) -> Option<ContactInfo> {
    let radius_a = a.shape.core_radius();
    let radius_b = b.shape.core_radius();
    let cores = gjk::distance_from_direction(a, b, b.pose.position - a.pose.position);
    if cores.distance - radius_a - radius_b >= margin {
        return None;
    }
    let (normal, core_separation, core_a, core_b) = match cores.normal() {
        Some(normal) => (normal, cores.distance, cores.point_a, cores.point_b),
        None => {
            let deepest = Polytope::default().penetration(a, b, &cores.simplex);
            (
                deepest.normal,
                -deepest.depth,
                deepest.point_a,
                deepest.point_b,
            )
        }
    };
    let separation = core_separation - radius_a - radius_b;
    (separation < margin).then_some(ContactInfo {
        normal,
        separation,
        point_a: core_a + radius_a * normal,
        point_b: core_b - radius_b * normal,
    })
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

    /// Which edge of this face runs `from → to`.
    fn edge_from(&self, from: usize, to: usize) -> Option<usize> {
        (0..3).find(|&k| self.vertices[k] == from && self.vertices[(k + 1) % 3] == to)
    }
}

/// An edge of the rim of the faces a new vertex replaces, as it runs on a replaced face.
#[derive(Debug, Clone, Copy)]
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
    /// The penetration of A and B, starting from `simplex`, the final simplex of a GJK query that
    /// found them overlapping. Always answers: when rounding defeats the algorithm, the best
    /// face found so far (or the shallowest world axis) is returned.
    pub fn penetration<A, B>(&mut self, a: &A, b: &B, simplex: &Simplex) -> Penetration
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
        // Every support point bounds the depth along its direction from above; the closest face
        // bounds it from below. The answer is the direction with the least bound, the closest
        // face's own distance once the two bounds meet.
        let mut best: Option<(f32, usize)> = None;
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
            let converged = reach - face.distance <= tolerance;
            let depth = if converged { face.distance } else { reach };
            if best.is_none_or(|(least, _)| depth < least) {
                best = Some((depth, closest));
            }
            if converged {
                break;
            }
            if !self.add_vertex(point, closest, tolerance, scale) {
                self.faces[closest].stuck = true;
            }
        }
        match best {
            Some((depth, face)) => self.answer(face, depth),
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
                    .position(|other| (0..3).any(|j| other[j] == to && other[(j + 1) % 3] == from))
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
            let Some(back) = neighbor.edge_from(to, from) else {
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
        let chained =
            (0..self.rim.len()).all(|i| self.rim[i].to == self.rim[(i + 1) % self.rim.len()].from);
        let simple =
            (0..self.rim.len()).all(|i| (0..i).all(|j| self.rim[i].from != self.rim[j].from));
        self.rim.len() >= 3 && chained && simple
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

    /// The penetration along a face's normal, `depth` deep, with the points of A and B whose
    /// difference is where the ray from the origin along that normal leaves the polytope. That
    /// is usually the origin's projection on the face itself, but may lie in a neighbour of the
    /// same plane (a box face or a cylinder cap is split into several triangles), or elsewhere
    /// when the face is a sliver whose normal, though it does measure the depth, is not quite
    /// its own. The ray leaves through the face it meets inside its triangle (found as the face
    /// whose triangle misses the ray's crossing of its plane the least, which rounding or a
    /// slightly dented polytope cannot fool the way the nearest crossing could).
    fn answer(&self, face: usize, depth: f32) -> Penetration {
        let face = self.faces[face];
        let normal = face.normal;
        let mut exit = (f32::INFINITY, Simplex::default());
        for candidate in &self.faces {
            let facing = candidate.normal.dot(normal);
            if candidate.removed || !candidate.distance.is_finite() || facing <= 0.0 {
                continue;
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
            let miss = nearest.closest_point().length_squared();
            if miss < exit.0 {
                exit = (miss, nearest);
            }
        }
        let (point_a, point_b) = exit.1.witness_points();
        Penetration {
            normal,
            depth: depth.max(0.0),
            point_a,
            point_b,
        }
    }
}

/// A penetration of (almost) zero depth along `normal`, with the GJK simplex's common point of A
/// and B as the contact.
fn touching(simplex: &Simplex, normal: Vec3, overlap: f32) -> Penetration {
    let (point_a, point_b) = simplex.witness_points();
    Penetration {
        normal,
        depth: overlap.max(0.0),
        point_a,
        point_b,
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
    shallowest: Option<Penetration>,
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
        let candidate = touching(self.simplex, direction, overlap);
        if self
            .shallowest
            .is_none_or(|shallowest| candidate.depth < shallowest.depth)
        {
            self.shallowest = Some(candidate);
        }
        if overlap <= TOLERANCE * self.scale {
            Err(candidate)
        } else {
            Ok(point)
        }
    }

    /// Last resort when no polytope can be built: the direction of least overlap probed so far,
    /// or, with none probed, the world axis of least overlap.
    fn fallback(&mut self) -> Penetration {
        if let Some(shallowest) = self.shallowest {
            return shallowest;
        }
        for direction in AXES {
            if let Err(answer) = self.probe(direction) {
                return answer;
            }
        }
        self.shallowest
            .unwrap_or_else(|| touching(self.simplex, Vec3::X, 0.0))
    }
}
