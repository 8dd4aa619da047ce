//! Distance between two convex solids by the Gilbert–Johnson–Keerthi algorithm (GJK).
//!
//! The solids A and B are apart by the distance from the origin to their Minkowski difference
//! `A − B = {a − b}`, and they overlap exactly when that difference holds the origin. GJK keeps a
//! simplex of up to four support points of `A − B`, replaces it by its smallest face (vertex,
//! edge, triangle) holding the point closest to the origin, found with signed volumes, and adds
//! the support point farthest against that closest point, until the new point brings the
//! distance's lower bound to within tolerance of its upper bound.
//!
//! Tolerances are relative to the size of the problem, the largest of `|a|`, `|b|` and `|a − b|`
//! among the support points, because every support point carries an f32 rounding of about `6e-8`
//! of the coordinates it is computed from: no answer can be better than a few of those. (Two
//! solids nearly touching have a small `|a − b|` but not small coordinates: measured by `|a − b|`
//! alone, the tolerance would shrink to the rounding's own size and the search would refine a
//! curved contact, which converges linearly, for ten more iterations.)

use crate::collision::{RelativeCore, SupportMap};
use crate::math::Vec3;

/// Most support points one query asks for. Polytopes need a handful; smooth surfaces (a
/// cylinder's rim) converge linearly and may need a few dozen at the tightest tolerance.
pub const MAX_ITERATIONS: usize = 64;

/// Relative precision of the distance: GJK stops once its lower and upper bounds on the distance
/// are within `TOLERANCE · scale`, and reports an overlap once the distance is below that,
/// `scale` being the problem's size (see the module comment). About 150 f32 rounding steps: far
/// above the noise of the support points, far below what the solver or a contact cares about.
pub const TOLERANCE: f32 = 1e-5;

/// How precisely a contact query ([`distance_within`]) measures the distance, metres, when the
/// relative [`TOLERANCE`] asks for more: a tenth of a millimetre, far below a resting contact's
/// depth (a few millimetres), and the slack of the narrow phase's tests (0.1 mm).
/// The distance is never underestimated, only overstated by up to this. Near a curved contact
/// (radius `R`), where the search converges linearly (about one halving of the gap an iteration,
/// on a cylinder's rim), the normal is then within `√(2·1e-4/R)` (1.3° for `R` = 0.4 m), and the
/// separation along it within 0.1 mm; the feature clipping takes a face contact's normal and
/// depths from the faces themselves. `mixed` runs about a quarter fewer GJK iterations than at
/// the relative tolerance alone.
pub const CONTACT_PRECISION: f32 = 1e-4;

/// Iterations in a row without progress after which GJK settles for the best simplex so far:
/// near the answer rounding can hide progress for an iteration or two, never for long.
const MAX_STALLS: usize = 3;

/// A simplex whose signed area or volume is below this fraction of its edge lengths (simplex
/// scaled to unit size) is treated as flat: about ten f32 rounding steps, below which the sign of
/// the volume is noise. Its closest point is then sought on its faces instead.
const DEGENERACY: f32 = 1e-6;

/// A point of the Minkowski difference `A − B`, with the points of A and B it was made from.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SupportPoint {
    /// Point of A farthest along the query direction.
    pub a: Vec3,
    /// Point of B farthest against the query direction.
    pub b: Vec3,
    /// `a − b`: the point of `A − B` farthest along the query direction.
    pub w: Vec3,
}

impl SupportPoint {
    /// The support point of `A − B` along `direction`.
    pub fn new<A, B>(a: &A, b: &B, direction: Vec3) -> Self
    where
        A: SupportMap + ?Sized,
        B: SupportMap + ?Sized,
    {
        let a = a.support(direction);
        let b = b.support(-direction);
        Self { a, b, w: a - b }
    }

    /// The larger of `|a|` and `|b|`, metres: the size of the coordinates the point was computed
    /// from, to which its rounding is relative.
    fn coordinate_size(&self) -> f32 {
        self.a.length_squared().max(self.b.length_squared()).sqrt()
    }
}

/// Up to four support points of `A − B`, the simplex point closest to the origin, and its
/// barycentric weights. After GJK every point has a positive weight.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Simplex {
    points: [SupportPoint; 4],
    /// `|w|` of each point, kept so that the scale costs no square root.
    lengths: [f32; 4],
    weights: [f32; 4],
    len: usize,
    closest: Vec3,
}

impl Simplex {
    /// The smallest face of the simplex of (up to four) `points` holding its point closest to
    /// the origin, and whether the simplex is a solid tetrahedron holding the origin.
    pub(crate) fn reduced(points: &[SupportPoint]) -> (Self, bool) {
        let mut simplex = Self::default();
        for point in points.iter().take(4) {
            simplex.push(*point);
        }
        let enclosed = simplex.reduce();
        (simplex, enclosed)
    }

    /// The support points.
    pub fn points(&self) -> &[SupportPoint] {
        &self.points[..self.len]
    }

    /// Barycentric weight of each point in the closest point; they sum to one.
    pub fn weights(&self) -> &[f32] {
        &self.weights[..self.len]
    }

    /// The point of the simplex closest to the origin, `Σ weightᵢ · wᵢ` (computed more directly
    /// where that is more precise: as the projection on the plane of a triangle).
    pub fn closest_point(&self) -> Vec3 {
        self.closest
    }

    /// The points of A and of B whose difference is [`Simplex::closest_point`].
    pub fn witness_points(&self) -> (Vec3, Vec3) {
        let combine = |coordinate: fn(&SupportPoint) -> Vec3| {
            self.points()
                .iter()
                .zip(self.weights())
                .fold(Vec3::ZERO, |sum, (point, weight)| {
                    sum + *weight * coordinate(point)
                })
        };
        (combine(|point| point.a), combine(|point| point.b))
    }

    /// Largest `|w|` among the points: the length scale of the problem.
    pub fn scale(&self) -> f32 {
        self.lengths[..self.len]
            .iter()
            .fold(0.0, |largest, &length| largest.max(length))
    }

    /// Appends a point; a full simplex is left unchanged.
    fn push(&mut self, point: SupportPoint) {
        if let Some(slot) = self.points.get_mut(self.len) {
            *slot = point;
            self.lengths[self.len] = point.w.length();
            self.weights[self.len] = 0.0;
            self.len += 1;
        }
    }

    /// Keeps only the points spanning the closest point to the origin, and sets it and their
    /// weights. Returns true when the simplex is a solid tetrahedron holding the origin.
    fn reduce(&mut self) -> bool {
        let scale = self.scale();
        if !(scale > 0.0 && scale.is_finite()) {
            // Every point is the origin (or the input is not finite): keep one, weight one.
            self.len = self.len.min(1);
            self.weights[0] = 1.0;
            self.closest = self.points[0].w;
            return false;
        }
        // Solved at unit size so that areas and volumes neither underflow nor overflow.
        let unit = self.points.map(|point| point.w / scale);
        let found = match self.len {
            1 => Barycentric::vertex(&unit, 0),
            2 => Barycentric::segment(&unit, 0, 1),
            3 => Barycentric::triangle(&unit, [0, 1, 2]),
            _ => Barycentric::tetrahedron(&unit),
        };
        let kept = &found.indices[..found.len];
        if kept.iter().enumerate().any(|(slot, &index)| slot != index) {
            let (points, lengths) = (self.points, self.lengths);
            for (slot, &index) in kept.iter().enumerate() {
                self.points[slot] = points[index];
                self.lengths[slot] = lengths[index];
            }
        }
        self.weights = found.weights;
        self.len = found.len;
        self.closest = found.point * scale;
        found.len == 4
    }
}

/// A query's final simplex kept to start the next query between the same two shapes (warm
/// starting, as Box2D's simplex cache does). Each vertex is kept as its point of A in A's frame,
/// the frame the query runs in, and its point of B in B's frame: points of the shapes, which stay
/// on them however the shapes move, so that placed at the new poses they are again points of
/// `A − B`, a simplex from which GJK goes on. When the shapes have barely moved, it is within
/// tolerance of the answer, and the first support point confirms it. Empty: start cold.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SimplexCache {
    /// Each vertex's point of A (A's frame) and of B (B's frame).
    local_points: [[Vec3; 2]; 4],
    len: u8,
}

impl SimplexCache {
    /// Whether no simplex is kept: the query starts cold.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Keeps `simplex`, found in A's frame with B placed there as `b`.
    pub(crate) fn new(simplex: &Simplex, b: &RelativeCore) -> Self {
        let mut local_points = [[Vec3::ZERO; 2]; 4];
        for (local, point) in local_points.iter_mut().zip(simplex.points()) {
            *local = [point.a, b.local_point(point.b)];
        }
        Self {
            local_points,
            len: simplex.len as u8,
        }
    }

    /// The same vertices with each point of A (`side` 0) or of B (`side` 1) replaced by
    /// `map(point)`: to carry the simplex into another frame of that shape, or onto another
    /// shape that holds those points.
    pub(crate) fn with_points(&self, side: usize, map: impl Fn(Vec3) -> Vec3) -> Self {
        let mut moved = *self;
        for vertex in &mut moved.local_points[..usize::from(self.len)] {
            vertex[side] = map(vertex[side]);
        }
        moved
    }

    /// The kept vertices with B placed as `b` now (A's frame): the first `len` of the array.
    pub(crate) fn placed(&self, b: &RelativeCore) -> ([SupportPoint; 4], usize) {
        let points = self.local_points.map(|[on_a, on_b]| {
            let on_b = b.place(on_b);
            SupportPoint {
                a: on_a,
                b: on_b,
                w: on_a - on_b,
            }
        });
        (points, usize::from(self.len))
    }
}

/// A point of a simplex (scaled to unit size) as weights on some of its vertices.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Barycentric {
    indices: [usize; 4],
    weights: [f32; 4],
    len: usize,
    point: Vec3,
}

impl Barycentric {
    fn vertex(unit: &[Vec3; 4], index: usize) -> Self {
        Self {
            indices: [index, 0, 0, 0],
            weights: [1.0, 0.0, 0.0, 0.0],
            len: 1,
            point: unit[index],
        }
    }

    /// The candidate nearer the origin.
    fn nearer(self, other: Self) -> Self {
        if other.point.length_squared() < self.point.length_squared() {
            other
        } else {
            self
        }
    }

    /// Closest point of segment `[i, j]`: the origin's projection on the line, clamped. The
    /// projection is taken as the part of the ends across the line, `e × (pᵢ × pⱼ) / |e|²`, which
    /// keeps its direction precise when it is much shorter than the ends themselves.
    fn segment(unit: &[Vec3; 4], i: usize, j: usize) -> Self {
        let edge = unit[j] - unit[i];
        let along = -unit[i].dot(edge);
        let length_squared = edge.length_squared();
        if along <= 0.0 {
            Self::vertex(unit, i)
        } else if along >= length_squared {
            Self::vertex(unit, j)
        } else {
            let t = along / length_squared;
            Self {
                indices: [i, j, 0, 0],
                weights: [1.0 - t, t, 0.0, 0.0],
                len: 2,
                point: edge.cross(unit[i].cross(unit[j])) / length_squared,
            }
        }
    }

    /// Closest point of a triangle. When the barycentric weights of the origin's projection on
    /// the plane are all positive, that projection; otherwise the closest point lies on an edge
    /// facing a vertex whose weight is not, so only those edges are searched. The projection
    /// itself is taken along the normal, whose direction is less sensitive to rounding than
    /// the weights.
    fn triangle(unit: &[Vec3; 4], vertices: [usize; 3]) -> Self {
        let [a, b, c] = vertices.map(|index| unit[index]);
        let (ab, bc, ca) = (b - a, c - b, a - c);
        let normal = ab.cross(c - a);
        let edges = [
            (vertices[1], vertices[2]),
            (vertices[2], vertices[0]),
            (vertices[0], vertices[1]),
        ];
        // With the projection p = a + wb·(b − a) + wc·(c − a), crossing with an edge isolates
        // each weight. Built from edges rather than from the vertices' own cross products, the
        // weights stay precise for a small triangle far from the origin.
        let area = normal.length_squared();
        let weight_b = (c - a).cross(a).dot(normal) / area;
        let weight_c = a.cross(b - a).dot(normal) / area;
        let weights = [1.0 - weight_b - weight_c, weight_b, weight_c];
        // Flat when `|normal| ≤ DEGENERACY · perimeter`. As `perimeter² ≤ 3 Σ |edge|²`, a larger
        // area rules that out without a square root, which spares the roots for most triangles.
        let edge_squares = ab.length_squared() + bc.length_squared() + ca.length_squared();
        let flat = area <= DEGENERACY * DEGENERACY * 3.0 * edge_squares
            && normal.length() <= DEGENERACY * (ab.length() + bc.length() + ca.length());
        if !flat && weights.iter().all(|&weight| weight > 0.0) {
            let height = (a + b + c).dot(normal) / 3.0;
            return Self {
                indices: [vertices[0], vertices[1], vertices[2], 0],
                weights: [weights[0], weights[1], weights[2], 0.0],
                len: 3,
                point: normal * (height / area),
            };
        }
        edges
            .iter()
            .zip(weights)
            .filter(|(_, weight)| flat || *weight <= 0.0)
            .map(|(&(i, j), _)| Self::segment(unit, i, j))
            .reduce(Self::nearer)
            .unwrap_or(Self::vertex(unit, vertices[0]))
    }

    /// Closest point of a tetrahedron: the origin itself when its four signed-volume weights are
    /// positive, otherwise on a face opposite a vertex whose weight is not.
    fn tetrahedron(unit: &[Vec3; 4]) -> Self {
        let [a, b, c, d] = *unit;
        let faces = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];
        let (ab, ac, ad) = (b - a, c - a, d - a);
        let volume = ab.dot(ac.cross(ad));
        // Solid when `|volume| > DEGENERACY · (|ab||ac| + |ac||ad| + |ad||ab|)`; that sum is at
        // most `|ab|² + |ac|² + |ad|²`, so a volume above the bound needs no square roots.
        let edge_squares = ab.length_squared() + ac.length_squared() + ad.length_squared();
        let solid = volume.abs() > DEGENERACY * edge_squares
            || volume.abs()
                > DEGENERACY
                    * (ab.length() * ac.length()
                        + ac.length() * ad.length()
                        + ad.length() * ab.length());
        // The origin is a + wb·ab + wc·ac + wd·ad: Cramer's rule on the edges, the first weight
        // making the sum one. A thin tetrahedron loses precision there, which one round of
        // refinement (solving again for what the weights miss) wins back.
        let solve = |target: Vec3| {
            let weight_b = -target.dot(ac.cross(ad)) / volume;
            let weight_c = -ab.dot(target.cross(ad)) / volume;
            let weight_d = -ab.dot(ac.cross(target)) / volume;
            [weight_b, weight_c, weight_d]
        };
        let [weight_b, weight_c, weight_d] = solve(a);
        let residual = weight_b * ab + weight_c * ac + weight_d * ad + a;
        let [fix_b, fix_c, fix_d] = solve(residual);
        let (weight_b, weight_c, weight_d) = (weight_b + fix_b, weight_c + fix_c, weight_d + fix_d);
        let weights = [
            1.0 - weight_b - weight_c - weight_d,
            weight_b,
            weight_c,
            weight_d,
        ];
        if solid && weights.iter().all(|&weight| weight > 0.0) {
            return Self {
                indices: [0, 1, 2, 3],
                weights,
                len: 4,
                point: Vec3::ZERO,
            };
        }
        faces
            .iter()
            .zip(weights)
            .filter(|(_, weight)| !solid || *weight <= 0.0)
            .map(|(&face, _)| Self::triangle(unit, face))
            .reduce(Self::nearer)
            .unwrap_or(Self::vertex(unit, 0))
    }
}

/// The result of a GJK distance query.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Distance {
    /// Distance between the two solids, metres; zero when they overlap.
    pub distance: f32,
    /// Point of A closest to B (world). When overlapping, a point common to both.
    pub point_a: Vec3,
    /// Point of B closest to A (world). When overlapping, a point common to both.
    pub point_b: Vec3,
    /// Whether the solids overlap or touch (distance below [`TOLERANCE`] of the problem's size).
    pub overlapping: bool,
    /// The final simplex, from which EPA starts when the solids overlap.
    pub simplex: Simplex,
}

impl Distance {
    /// Unit direction from A toward B along which they are closest, or `None` when they
    /// overlap. Taken from the simplex's closest point rather than from the witness points,
    /// whose difference loses its direction to rounding when the solids nearly touch.
    pub fn normal(&self) -> Option<Vec3> {
        if self.overlapping {
            None
        } else {
            (-self.simplex.closest_point()).try_normalize()
        }
    }

    fn from_simplex(simplex: Simplex, overlapping: bool) -> Self {
        let (point_a, point_b) = simplex.witness_points();
        Self {
            distance: if overlapping {
                0.0
            } else {
                simplex.closest_point().length()
            },
            point_a,
            point_b,
            overlapping,
            simplex,
        }
    }
}

/// Distance between convex solids A and B, their closest points, and whether they overlap.
pub fn distance<A, B>(a: &A, b: &B) -> Distance
where
    A: SupportMap + ?Sized,
    B: SupportMap + ?Sized,
{
    distance_from_direction(a, b, Vec3::X)
}

/// [`distance`], starting the search along `direction` (a guess of the direction from A toward
/// B, such as the difference of their centres, or last step's normal). A zero or non-finite
/// direction falls back to +X.
pub fn distance_from_direction<A, B>(a: &A, b: &B, direction: Vec3) -> Distance
where
    A: SupportMap + ?Sized,
    B: SupportMap + ?Sized,
{
    match search(a, b, &[], direction, f32::INFINITY, 0.0) {
        Search::Done(found) | Search::Beyond(found) => found,
    }
}

/// [`distance_from_direction`] to the precision of a contact, [`CONTACT_PRECISION`], or `None` as
/// soon as the solids are known to be more than `limit` metres apart: a support point whose reach along the search direction leaves a lower
/// bound on the distance above `limit` ends the search (contact queries, where most pairs of
/// overlapping boxes are farther apart than the margin, stop there after a few iterations).
/// The search starts from the simplex of the points `start` (up to four points of `A − B`, such
/// as last query's simplex placed anew, see [`SimplexCache`]), or when it is empty from the
/// support point along `direction`.
pub fn distance_within<A, B>(
    a: &A,
    b: &B,
    start: &[SupportPoint],
    direction: Vec3,
    limit: f32,
) -> Option<Distance>
where
    A: SupportMap + ?Sized,
    B: SupportMap + ?Sized,
{
    match search(a, b, start, direction, limit, CONTACT_PRECISION) {
        Search::Done(found) => Some(found),
        Search::Beyond(_) => None,
    }
}

/// [`distance_within`], ending with [`Search::Beyond`] and the simplex reached so far, rather
/// than `None`, when the solids are more than `limit` apart: a start for the next query between
/// the same two, which then most often rejects them again with its first support point.
pub(crate) fn search_within<A, B>(
    a: &A,
    b: &B,
    start: &[SupportPoint],
    direction: Vec3,
    limit: f32,
) -> Search
where
    A: SupportMap + ?Sized,
    B: SupportMap + ?Sized,
{
    search(a, b, start, direction, limit, CONTACT_PRECISION)
}

/// How a GJK search ended.
pub(crate) enum Search {
    /// With the distance, to tolerance.
    Done(Distance),
    /// Early, with the simplex so far, once a lower bound on the distance exceeded the limit.
    Beyond(Distance),
}

/// The GJK iteration from the simplex of `start`, or when it is empty from the support point
/// along `direction`, stopping early once the solids are known to be more than `limit` apart,
/// and once the distance is known within [`TOLERANCE`] of the problem's size or within
/// `precision` metres, whichever is looser.
fn search<A, B>(
    a: &A,
    b: &B,
    start: &[SupportPoint],
    direction: Vec3,
    limit: f32,
    precision: f32,
) -> Search
where
    A: SupportMap + ?Sized,
    B: SupportMap + ?Sized,
{
    let (mut simplex, enclosed) = if start.is_empty() {
        let direction = if direction.length_squared() > 0.0 && direction.is_finite() {
            direction
        } else {
            Vec3::X
        };
        // Along A→B the support point of A − B pairs the facing sides of A and B.
        Simplex::reduced(&[SupportPoint::new(a, b, direction)])
    } else {
        Simplex::reduced(start)
    };
    if enclosed {
        return Search::Done(Distance::from_simplex(simplex, true));
    }
    let mut best = (f32::INFINITY, simplex);
    let mut stalls = 0;
    let mut size = simplex
        .points()
        .iter()
        .map(SupportPoint::coordinate_size)
        .fold(0.0, f32::max);
    for _ in 0..MAX_ITERATIONS {
        let closest = simplex.closest_point();
        let upper = closest.length();
        let scale = simplex.scale().max(size);
        if upper <= TOLERANCE * scale {
            return Search::Done(Distance::from_simplex(simplex, true));
        }
        let point = SupportPoint::new(a, b, -closest);
        if !point.w.is_finite() {
            break;
        }
        // `|closest|` is an upper bound on the distance, and the new point's reach along
        // `closest` a lower one: their gap measures how far the simplex is from the answer, in
        // length and in direction.
        let lower = closest.dot(point.w) / upper;
        if lower > limit {
            return Search::Beyond(Distance::from_simplex(simplex, false));
        }
        let gap = upper - lower;
        if gap < best.0 {
            best = (gap, simplex);
        }
        size = size.max(point.coordinate_size());
        if gap <= (TOLERANCE * scale.max(size)).max(precision) {
            break;
        }
        // Grown in place (`best` holds the simplex to fall back on). A simplex of four points
        // holds the origin and has ended the search, so there is room.
        simplex.push(point);
        if simplex.reduce() {
            return Search::Done(Distance::from_simplex(simplex, true));
        }
        // Near the answer the distance improves only at second order, below rounding, while
        // the direction still improves at first order: a simplex no nearer is kept all the same,
        // and the search ends after a few of those in a row.
        if simplex.closest_point().length() >= upper {
            stalls += 1;
            if stalls > MAX_STALLS {
                break;
            }
        } else {
            stalls = 0;
        }
    }
    Search::Done(Distance::from_simplex(best.1, false))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(w: Vec3) -> SupportPoint {
        SupportPoint {
            a: w,
            b: Vec3::ZERO,
            w,
        }
    }

    fn reduced(points: &[Vec3]) -> (Simplex, bool) {
        Simplex::reduced(&points.iter().copied().map(point).collect::<Vec<_>>())
    }

    // Exact binary fractions throughout: 1e-6 only absorbs one or two roundings of values ≤ 4.
    const EXACT: f32 = 1e-6;

    #[test]
    fn segment_keeps_the_projection_or_an_end() {
        let (simplex, _) = reduced(&[Vec3::new(-1.0, 1.0, 0.0), Vec3::new(3.0, 1.0, 0.0)]);
        assert_eq!(simplex.points().len(), 2);
        assert!((simplex.closest_point() - Vec3::Y).length() < EXACT);
        let (simplex, _) = reduced(&[Vec3::new(1.0, 1.0, 0.0), Vec3::new(3.0, 1.0, 0.0)]);
        assert_eq!(simplex.points().len(), 1);
        assert!((simplex.closest_point() - Vec3::new(1.0, 1.0, 0.0)).length() < EXACT);
    }

    #[test]
    fn triangle_face_edge_and_vertex_regions() {
        let face = [
            Vec3::new(-1.0, -1.0, 2.0),
            Vec3::new(2.0, -1.0, 2.0),
            Vec3::new(-1.0, 2.0, 2.0),
        ];
        let (simplex, _) = reduced(&face);
        assert_eq!(simplex.points().len(), 3);
        assert!((simplex.closest_point() - Vec3::new(0.0, 0.0, 2.0)).length() < EXACT);
        let shifted = face.map(|p| p + Vec3::new(0.0, 2.0, 0.0));
        let (simplex, _) = reduced(&shifted);
        assert_eq!(simplex.points().len(), 2);
        assert!((simplex.closest_point() - Vec3::new(0.0, 1.0, 2.0)).length() < EXACT);
        let corner = face.map(|p| p + Vec3::new(2.0, 2.0, 0.0));
        let (simplex, _) = reduced(&corner);
        assert_eq!(simplex.points().len(), 1);
        assert!((simplex.closest_point() - Vec3::new(1.0, 1.0, 2.0)).length() < EXACT);
    }

    #[test]
    fn collinear_triangle_falls_back_to_its_edges() {
        let (simplex, _) = reduced(&[
            Vec3::new(-1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
        ]);
        assert!(simplex.points().len() <= 2);
        assert!((simplex.closest_point() - Vec3::Y).length() < EXACT);
    }

    #[test]
    fn tetrahedron_encloses_or_reduces_to_a_face() {
        let corners = [
            Vec3::new(1.0, 1.0, 1.0),
            Vec3::new(1.0, -1.0, -1.0),
            Vec3::new(-1.0, 1.0, -1.0),
            Vec3::new(-1.0, -1.0, 1.0),
        ];
        let (simplex, enclosed) = reduced(&corners);
        assert!(enclosed);
        assert!(simplex.closest_point().length() < EXACT);
        assert!((simplex.weights().iter().sum::<f32>() - 1.0).abs() < EXACT);
        let moved = corners.map(|p| p + Vec3::new(0.0, 0.0, 3.0));
        let (simplex, enclosed) = reduced(&moved);
        assert!(!enclosed);
        assert!(simplex.closest_point().length() < 3.0);
        let flat = corners.map(|p| Vec3::new(p.x, p.y, 0.0));
        let (simplex, enclosed) = reduced(&flat);
        assert!(!enclosed);
        assert!(simplex.closest_point().length() < EXACT);
    }

    #[test]
    fn all_points_at_the_origin() {
        let (simplex, enclosed) = reduced(&[Vec3::ZERO, Vec3::ZERO, Vec3::ZERO]);
        assert!(!enclosed);
        assert_eq!(simplex.points().len(), 1);
        assert_eq!(simplex.closest_point(), Vec3::ZERO);
    }
}
