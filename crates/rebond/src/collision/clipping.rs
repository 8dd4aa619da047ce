//! Clipping and point reduction shared by the contact builders that rest a polygon or segment on a
//! face: box and hull faces, capsule and cylinder sides.
//!
//! A face contact takes the *incident* feature of one shape (a polygon or a segment), cuts away
//! what lies outside the *reference* face of the other shape (Sutherland–Hodgman against the
//! reference polygon's side planes), measures what is left against the reference plane, and keeps
//! at most [`MAX_MANIFOLD_POINTS`] well-spread points ([`reduce_contacts`] starting from the
//! deepest, [`reduce_contacts_on_face`] by position on the face, which small motions keep). Every
//! clipped point carries a [`ClipFeature`] naming how it was made, from which callers build
//! stable contact ids.

use crate::collision::manifold::{ContactPoint, Manifold, MAX_MANIFOLD_POINTS};
use crate::math::Vec3;

/// Most vertices read from an incident or reference polygon. Longer inputs are cut to their first
/// `MAX_POLYGON_VERTICES` vertices, which still span a convex polygon inside the original one, so
/// the clipped points stay on the true surfaces (callers with larger faces pass an evenly spaced
/// subset instead, which covers the face better).
pub const MAX_POLYGON_VERTICES: usize = 32;

/// Capacity of a clipped polygon: two convex polygons of `n` and `m` vertices intersect in at most
/// `n + m` vertices, so two inputs within [`MAX_POLYGON_VERTICES`] never overflow it.
pub const MAX_CLIP_VERTICES: usize = 2 * MAX_POLYGON_VERTICES;

/// How far outside a side plane (metres) a vertex may lie and still count as inside. A vertex
/// sitting on a side (two equal boxes stacked) then stays that vertex, with its id, instead of
/// flickering between "vertex" and "two crossings" from round-off. Cuts are made on the exact
/// plane, so only such vertices stick out of the reference face, by at most this much.
pub const SIDE_PLANE_SLOP: f32 = 1.0e-4;

/// Below this fraction of the squared distance between the first two chosen points, a triangle's
/// doubled area counts as zero when [`reduce_contacts`] picks the third and fourth points: a point
/// that close to the line through the others adds nothing to the support polygon.
const MIN_AREA_FRACTION: f32 = 1.0e-3;

/// Which features of the incident and reference polygons made a clipped point. Indices are
/// positions in the polygons as passed to [`clip_polygon`] or [`clip_segment`]: incident vertex
/// `i`, incident edge `i` from vertex `i` to vertex `i + 1`, side `j` along the reference edge from
/// reference vertex `j` to vertex `j + 1`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ClipFeature {
    /// An incident vertex that lies inside every side plane.
    IncidentVertex(u8),
    /// Where an incident edge crosses a side plane.
    EdgeCrossing {
        /// Incident edge index.
        edge: u8,
        /// Side plane index.
        side: u8,
    },
    /// Where two side planes meet on the incident polygon: for neighbouring sides, a reference
    /// vertex seen through the incident face. `first` is the side clipped earlier.
    SideCorner {
        /// The side clipped first.
        first: u8,
        /// The side clipped second.
        second: u8,
    },
}

impl ClipFeature {
    /// A 16-bit code of the feature, distinct for distinct features while every index stays below
    /// 128 (always true for polygons within [`MAX_POLYGON_VERTICES`]): two bits of kind, then two
    /// 7-bit indices.
    pub fn key(self) -> u16 {
        let (kind, first, second) = match self {
            ClipFeature::IncidentVertex(vertex) => (0, vertex, 0),
            ClipFeature::EdgeCrossing { edge, side } => (1, edge, side),
            ClipFeature::SideCorner { first, second } => (2, first, second),
        };
        (kind << 14) | (u16::from(first & 0x7F) << 7) | u16::from(second & 0x7F)
    }

    /// Whether `key` (see [`Self::key`]) is an [`ClipFeature::IncidentVertex`]'s.
    pub fn is_incident_vertex_key(key: u16) -> bool {
        key >> 14 == 0
    }
}

/// A point of a clipped polygon or segment and the features that made it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClipVertex {
    /// Position, in the frame the inputs were given in (world, for the narrow phase).
    pub position: Vec3,
    /// How the point was made.
    pub feature: ClipFeature,
}

/// The line a polygon edge runs along, so that a later cut of that edge can be named.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Along {
    /// Part of incident edge `i`.
    IncidentEdge(u8),
    /// Lies on side plane `j` (made when side `j` cut the polygon).
    Side(u8),
}

/// A convex polygon being clipped: up to `CAPACITY` (by default [`MAX_CLIP_VERTICES`]) tagged
/// vertices in order, with the line each edge runs along. Lives on the stack.
#[derive(Debug, Clone, Copy)]
pub struct ClipPolygon<const CAPACITY: usize = MAX_CLIP_VERTICES> {
    vertices: [ClipVertex; CAPACITY],
    /// `incoming[k]`: the line of the edge from vertex `k − 1` to vertex `k`.
    incoming: [Along; CAPACITY],
    len: usize,
}

impl<const CAPACITY: usize> Default for ClipPolygon<CAPACITY> {
    fn default() -> Self {
        Self {
            vertices: [ClipVertex {
                position: Vec3::ZERO,
                feature: ClipFeature::IncidentVertex(0),
            }; CAPACITY],
            incoming: [Along::IncidentEdge(0); CAPACITY],
            len: 0,
        }
    }
}

impl<const CAPACITY: usize> ClipPolygon<CAPACITY> {
    /// The vertices, in the incident polygon's order.
    pub fn vertices(&self) -> &[ClipVertex] {
        &self.vertices[..self.len]
    }

    /// Number of vertices.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether clipping left nothing.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The incident polygon itself: vertex `i` tagged [`ClipFeature::IncidentVertex`]`(i)`, up to
    /// [`MAX_POLYGON_VERTICES`] and the capacity.
    fn from_incident(points: &[Vec3]) -> Self {
        let points = &points[..points.len().min(MAX_POLYGON_VERTICES).min(CAPACITY)];
        let mut polygon = Self::default();
        for (index, &position) in points.iter().enumerate() {
            let previous = (index + points.len() - 1) % points.len();
            polygon.push(
                ClipVertex {
                    position,
                    feature: ClipFeature::IncidentVertex(index as u8),
                },
                Along::IncidentEdge(previous as u8),
            );
        }
        polygon
    }

    /// Appends a vertex reached along `incoming`; past the capacity the vertex is dropped, which
    /// leaves a convex polygon inside the true one.
    fn push(&mut self, vertex: ClipVertex, incoming: Along) {
        if self.len < CAPACITY {
            self.vertices[self.len] = vertex;
            self.incoming[self.len] = incoming;
            self.len += 1;
        }
    }
}

/// A side plane of the reference polygon: `normal · p − offset` is how far `p` lies outside it.
#[derive(Debug, Clone, Copy)]
struct SidePlane {
    normal: Vec3,
    offset: f32,
}

impl SidePlane {
    /// The plane through reference edge `start → end`, facing out of a polygon that winds
    /// counter-clockwise about `face_normal`. A zero-length edge gives a plane everything is on.
    fn new(start: Vec3, end: Vec3, face_normal: Vec3) -> Self {
        let normal = (end - start).cross(face_normal).normalize_or_zero();
        Self {
            normal,
            offset: normal.dot(start),
        }
    }

    fn distance(&self, point: Vec3) -> f32 {
        self.normal.dot(point) - self.offset
    }
}

/// The side planes of `reference` (its first [`MAX_POLYGON_VERTICES`] vertices), in order.
fn side_planes(reference: &[Vec3], normal: Vec3) -> impl Iterator<Item = (u8, SidePlane)> + '_ {
    let reference = &reference[..reference.len().min(MAX_POLYGON_VERTICES)];
    reference.iter().enumerate().map(move |(index, &start)| {
        let end = reference[(index + 1) % reference.len()];
        (index as u8, SidePlane::new(start, end, normal))
    })
}

/// The point where the segment `from → to` crosses a plane, given their distances to it: one
/// negative, the other above [`SIDE_PLANE_SLOP`], so the denominator is never zero.
fn crossing(from: Vec3, to: Vec3, from_distance: f32, to_distance: f32) -> Vec3 {
    let t = from_distance / (from_distance - to_distance);
    from + (to - from) * t
}

/// Cuts `polygon` by one side plane (Sutherland–Hodgman), writing the part inside to `out`;
/// `distance` is how far a point lies outside the plane. A vertex counts as inside up to
/// [`SIDE_PLANE_SLOP`] out; an edge leaving or entering at such a vertex is not cut, since its
/// crossing of the exact plane would lie behind that vertex.
fn clip_by_plane<const CAPACITY: usize>(
    polygon: &ClipPolygon<CAPACITY>,
    side: u8,
    distance: impl Fn(Vec3) -> f32,
    out: &mut ClipPolygon<CAPACITY>,
) {
    out.len = 0;
    let vertices = &polygon.vertices[..polygon.len];
    let Some(&last) = vertices.last() else {
        return;
    };
    // Each vertex's distance is measured once, as the current vertex, and carried on as the
    // previous one.
    let (mut previous, mut previous_distance) = (last, distance(last.position));
    for (&current, &edge_line) in vertices.iter().zip(&polygon.incoming) {
        let current_distance = distance(current.position);
        let cut = |distance_inside: f32| {
            (distance_inside < 0.0).then(|| ClipVertex {
                position: crossing(
                    previous.position,
                    current.position,
                    previous_distance,
                    current_distance,
                ),
                feature: match edge_line {
                    Along::IncidentEdge(edge) => ClipFeature::EdgeCrossing { edge, side },
                    Along::Side(first) => ClipFeature::SideCorner {
                        first,
                        second: side,
                    },
                },
            })
        };
        match (
            previous_distance <= SIDE_PLANE_SLOP,
            current_distance <= SIDE_PLANE_SLOP,
        ) {
            (true, true) => out.push(current, edge_line),
            // Leaving: the polygon now runs along this side to where it comes back in.
            (true, false) => {
                if let Some(exit) = cut(previous_distance) {
                    out.push(exit, edge_line);
                }
            }
            (false, true) => match cut(current_distance) {
                Some(entry) => {
                    out.push(entry, Along::Side(side));
                    out.push(current, edge_line);
                }
                None => out.push(current, Along::Side(side)),
            },
            (false, false) => {}
        }
        (previous, previous_distance) = (current, current_distance);
    }
}

/// Clips the convex `incident` polygon against the side planes of the convex `reference` polygon:
/// what is left is the part of `incident` whose projection along `normal` falls inside
/// `reference` (vertices up to [`SIDE_PLANE_SLOP`] outside a side are kept as they are).
///
/// - `incident`: the vertices in order around the polygon, either winding.
/// - `reference`: the vertices counter-clockwise seen from the tip of `normal` (the usual
///   outward-facing order of a face). Three or more vertices; fewer clip nothing useful.
/// - `normal`: the reference face's unit normal.
///
/// Each polygon is read up to [`MAX_POLYGON_VERTICES`] vertices. The points keep the
/// incident order and are tagged with [`ClipFeature`]s indexed by position in the inputs.
pub fn clip_polygon(incident: &[Vec3], reference: &[Vec3], normal: Vec3) -> ClipPolygon {
    clip_polygon_within(incident, reference, normal)
}

/// [`clip_polygon`] into a polygon of `CAPACITY` vertices, for callers whose polygons are known
/// to be small (`CAPACITY` at least the two polygons' vertex counts together): less to clear and
/// copy than [`MAX_CLIP_VERTICES`].
pub fn clip_polygon_within<const CAPACITY: usize>(
    incident: &[Vec3],
    reference: &[Vec3],
    normal: Vec3,
) -> ClipPolygon<CAPACITY> {
    clip_by_sides(
        incident,
        side_planes(reference, normal)
            .map(|(side, plane)| (side, move |point| plane.distance(point))),
    )
}

/// Clips the convex `incident` polygon by side planes in turn, as [`clip_polygon`] does, into a
/// polygon of `CAPACITY` vertices (enough for the incident's vertices plus one per side). Each
/// side comes as its index, which tags the points it makes, and the distance of a point outside
/// it: a reference face whose sides have a simpler form (a box face in the box's frame) skips the
/// general planes.
#[inline]
pub fn clip_by_sides<const CAPACITY: usize, Distance: Fn(Vec3) -> f32>(
    incident: &[Vec3],
    sides: impl Iterator<Item = (u8, Distance)>,
) -> ClipPolygon<CAPACITY> {
    // Two buffers used in turn: each side plane reads one and writes the other.
    let mut buffers = [ClipPolygon::from_incident(incident), ClipPolygon::default()];
    let mut current = 0;
    for (side, distance) in sides {
        if buffers[current].is_empty() {
            break;
        }
        let [first, second] = &mut buffers;
        let (from, to) = if current == 0 {
            (first, second)
        } else {
            (second, first)
        };
        clip_by_plane(from, side, distance, to);
        current = 1 - current;
    }
    let [first, second] = buffers;
    if current == 0 {
        first
    } else {
        second
    }
}

/// Clips the segment `[start, end]` against the side planes of `reference` (same conventions as
/// [`clip_polygon`]): `None` when no part of it projects inside the reference polygon, otherwise
/// its two clipped ends, tagged as incident vertex 0 and 1 or as crossings of incident edge 0.
/// An end up to [`SIDE_PLANE_SLOP`] outside a side counts as inside. A segment lying inside
/// gives its two ends; a point (`start == end`) inside gives it twice.
pub fn clip_segment(
    start: Vec3,
    end: Vec3,
    reference: &[Vec3],
    normal: Vec3,
) -> Option<[ClipVertex; 2]> {
    let (mut enter, mut exit) = (0.0_f32, 1.0_f32);
    let mut enter_feature = ClipFeature::IncidentVertex(0);
    let mut exit_feature = ClipFeature::IncidentVertex(1);
    for (side, plane) in side_planes(reference, normal) {
        let start_distance = plane.distance(start);
        let end_distance = plane.distance(end);
        let crossing_feature = ClipFeature::EdgeCrossing { edge: 0, side };
        // The crossing of the exact plane; clamped, as an end within the slop band is kept.
        let t = || (start_distance / (start_distance - end_distance)).clamp(0.0, 1.0);
        match (
            start_distance <= SIDE_PLANE_SLOP,
            end_distance <= SIDE_PLANE_SLOP,
        ) {
            (true, true) => {}
            (false, false) => return None,
            (false, true) => {
                let t = t();
                if t > enter {
                    enter = t;
                    enter_feature = crossing_feature;
                }
            }
            (true, false) => {
                let t = t();
                if t < exit {
                    exit = t;
                    exit_feature = crossing_feature;
                }
            }
        }
    }
    if enter > exit {
        return None;
    }
    let along = end - start;
    Some([
        ClipVertex {
            position: start + along * enter,
            feature: enter_feature,
        },
        ClipVertex {
            position: start + along * exit,
            feature: exit_feature,
        },
    ])
}

/// Twice the area of triangle `(a, b, c)` projected on the plane of `normal`, positive when it
/// winds counter-clockwise about `normal`.
fn signed_double_area(a: Vec3, b: Vec3, c: Vec3, normal: Vec3) -> f32 {
    (b - a).cross(c - a).dot(normal)
}

/// Builds a manifold with `normal` from `candidates`, keeping all of them when there are at most
/// [`MAX_MANIFOLD_POINTS`], else four that hold the contact best: the deepest point (it must be
/// resolved), then points spread from it (`spread`). Points too close to the line or triangle
/// already chosen are not added, so a manifold of a thin patch may have two or three points. The
/// order is the order of choice.
pub fn reduce_contacts(normal: Vec3, candidates: &[ContactPoint]) -> Manifold {
    if candidates.len() <= MAX_MANIFOLD_POINTS {
        return manifold_of(normal, candidates, 0..candidates.len());
    }
    let mut chosen = Chosen::default();
    chosen.push(deepest_index(candidates));
    spread(normal, candidates, &mut chosen);
    manifold_of(normal, candidates, chosen.indices().iter().copied())
}

/// Where the candidates of [`reduce_contacts_on_face`] lie.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Surface {
    /// On one flat face of each shape.
    Flat,
    /// On triangles of a mesh merged into one manifold, not quite coplanar, of a pair that closes
    /// by at most `reach` metres in the step.
    Bent {
        /// How far the pair can close in the step, metres.
        reach: f32,
    },
}

/// As [`reduce_contacts`], but choosing the four points by where they lie on the face rather than
/// by depth, so that small motions, which shift depths more than positions, keep the same ids: the
/// points farthest along `tangent`, along `normal × tangent`, against `tangent` and against
/// `normal × tangent` (counter-clockwise about `normal`), any still missing added by `spread`.
/// `tangent` is a unit direction in the face's plane fixed to the reference body.
///
/// On a [`Surface::Bent`], a dropped point that touches and lies outside the kept points' polygon
/// then takes the place of the nearest kept point apart by more than the pair's reach
/// (`hold_touching_points_outside`).
///
/// When a dropped point is deeper than every kept one by more than [`DEEPEST_SLACK`], the kept
/// point nearest it moves onto it (position and separation), keeping its id: the manifold reaches
/// the full depth and its set of ids stays the same. On a [`Surface::Bent`], so do, after it, the dropped points that
/// penetrate deeper than every kept point not yet moved (`reach_deepest`).
pub fn reduce_contacts_on_face(
    normal: Vec3,
    tangent: Vec3,
    candidates: &[ContactPoint],
    surface: Surface,
) -> Manifold {
    let bent = matches!(surface, Surface::Bent { .. });
    if candidates.len() <= MAX_MANIFOLD_POINTS {
        return manifold_of(normal, candidates, 0..candidates.len());
    }
    let bitangent = normal.cross(tangent);
    let directions = [tangent, bitangent, -tangent, -bitangent];
    let mut chosen = Chosen::default();
    for (turn, direction) in directions.iter().enumerate() {
        let farthest = candidates
            .iter()
            .map(|candidate| candidate.position.dot(*direction))
            .fold(f32::NEG_INFINITY, f32::max);
        // Of the points equally far (along one edge of the patch), the corner that comes next
        // counter-clockwise: a merged mesh manifold holds points of an edge found by several
        // triangles (some where the edge only grazes a triangle's side), and the four corners
        // hold the patch where a point in between would leave one corner out.
        let next = directions[(turn + 1) % directions.len()];
        let extreme = candidates
            .iter()
            .enumerate()
            .filter(|(_, candidate)| candidate.position.dot(*direction) >= farthest - EXTREME_TIE)
            .max_by(|(_, a), (_, b)| a.position.dot(next).total_cmp(&b.position.dot(next)))
            .map_or(0, |(index, _)| index);
        if !chosen.indices().contains(&extreme) {
            chosen.push(extreme);
        }
    }
    spread(normal, candidates, &mut chosen);
    let mut manifold = manifold_of(normal, candidates, chosen.indices().iter().copied());
    if let Surface::Bent { reach } = surface {
        hold_touching_points_outside(&mut manifold, candidates, chosen.indices(), reach);
    }
    reach_deepest(&mut manifold, candidates, chosen.indices(), bent);
    manifold
}

/// On a bent surface, gives each dropped candidate that touches (deepest first) and lies outside
/// the polygon of the kept points the place of the kept point nearest it among those apart by
/// more than [`HELD_REACH_FRACTION`] of `reach` (how far the pair can close in the step, metres),
/// with its own id, while any is. A cap resting across a crease touches at rim points between
/// the extremes along the tangents, which may all be apart: held at two of its four touching
/// points, it rocked on for ever. A point the pair may reach within the step stays: a body
/// landing tilted needs its far side's points to catch it. A touching point inside the polygon
/// (a box's face across a ridge touching along its middle) adds no support, and the corners
/// apart are what catch the face when it tips.
fn hold_touching_points_outside(
    manifold: &mut Manifold,
    candidates: &[ContactPoint],
    kept: &[usize],
    reach: f32,
) {
    let normal = manifold.normal;
    let held = HELD_REACH_FRACTION * reach;
    let mut touching: [usize; 2 * MAX_CLIP_VERTICES] = [0; 2 * MAX_CLIP_VERTICES];
    let mut count = 0;
    for (index, candidate) in candidates.iter().enumerate() {
        if candidate.separation < 0.0 && !kept.contains(&index) && count < touching.len() {
            touching[count] = index;
            count += 1;
        }
    }
    let touching = &mut touching[..count];
    touching.sort_by(|&a, &b| {
        candidates[a]
            .separation
            .total_cmp(&candidates[b].separation)
            .then(a.cmp(&b))
    });
    for &index in touching.iter() {
        let candidate = candidates[index];
        let points = manifold.points();
        if points.len() < 3 || !points.iter().any(|point| point.separation > held) {
            return;
        }
        if inside_polygon(points, candidate.position, normal) {
            continue;
        }
        let distance = |point: &ContactPoint| point.position.distance_squared(candidate.position);
        let nearest_apart = points
            .iter()
            .enumerate()
            .filter(|(_, point)| point.separation > held)
            .min_by(|(_, a), (_, b)| distance(a).total_cmp(&distance(b)))
            .map(|(slot, _)| slot);
        if let Some(slot) = nearest_apart {
            manifold.points_mut()[slot] = candidate;
        }
    }
}

/// The part of a pair's reach in the step (a bound on its fastest point, `|v| + |ω| r` over the
/// whole body, more than most points close) within which a kept point apart is not given up for
/// a touching one ([`hold_touching_points_outside`]). Measured on the terrain pours (seeds 1–16)
/// and `mesh_pile` (4 substeps, deepest dip below the mesh while landing): the whole reach left
/// three pours rocking for ever, half of it one; a quarter rests all sixteen, and landings dip
/// 4.65 cm (4.04 cm before points were held, 9.1 cm holding them whatever the reach).
const HELD_REACH_FRACTION: f32 = 0.25;

/// Whether `point` lies inside the convex polygon of `points` (in any order) seen along `normal`:
/// the points are ordered counter-clockwise about their centre, by half-plane and then by the
/// cross product (no trigonometry, so the same bits on every platform).
fn inside_polygon(points: &[ContactPoint], point: Vec3, normal: Vec3) -> bool {
    let centre = points.iter().map(|p| p.position).sum::<Vec3>() / points.len() as f32;
    let reference = (points[0].position - centre).normalize_or_zero();
    let side = normal.cross(reference);
    let planar = |slot: usize| {
        let offset = points[slot].position - centre;
        (offset.dot(reference), offset.dot(side))
    };
    let half = |(x, y): (f32, f32)| u8::from(y < 0.0 || (y == 0.0 && x < 0.0));
    let mut order = [0, 1, 2, 3];
    let order = &mut order[..points.len().min(MAX_MANIFOLD_POINTS)];
    order.sort_by(|&a, &b| {
        let ((ax, ay), (bx, by)) = (planar(a), planar(b));
        half((ax, ay))
            .cmp(&half((bx, by)))
            .then_with(|| (ay * bx).total_cmp(&(ax * by)))
    });
    (0..order.len()).all(|k| {
        let from = points[order[k]].position;
        let to = points[order[(k + 1) % order.len()]].position;
        signed_double_area(from, to, point, normal) >= 0.0
    })
}

/// Moves kept points of `manifold` (the candidates at `kept`, in order) onto deeper dropped ones
/// ([`reduce_contacts_on_face`]): the deepest dropped candidate, when it is deeper than every kept
/// point by more than [`DEEPEST_SLACK`], moves the kept point nearest it; then, on a `bent`
/// surface, while a dropped candidate that penetrates is deeper than every kept point not yet
/// moved, it moves the nearest of those (the points of one flat face pair keep the single move
/// they always had). A cylinder's cap resting across triangles bent against each other rests on
/// two or three rim points lower than the rest: reaching only the deepest, the manifold swapped
/// one low point for the other from step to step, and the cap rocked on for ever at 1 to 6 cm/s
/// (the pours of `tests/meshes/terrain.rs`). Speculative points (apart) move nothing past the
/// first: a body landing at an angle keeps its spread of points instead of gathering them on the
/// side that touches first (which let a tumbling cylinder's far rim sink 4.7 cm).
fn reach_deepest(manifold: &mut Manifold, candidates: &[ContactPoint], kept: &[usize], bent: bool) {
    let mut moved = [false; MAX_MANIFOLD_POINTS];
    let mut reached = [usize::MAX; MAX_MANIFOLD_POINTS];
    let rounds = if bent { manifold.len() } else { 1 };
    for round in 0..rounds {
        let unmoved = || {
            manifold
                .points()
                .iter()
                .enumerate()
                .filter(|&(slot, _)| !moved[slot])
        };
        let bound = unmoved()
            .map(|(_, point)| point.separation)
            .fold(f32::INFINITY, f32::min)
            - DEEPEST_SLACK;
        let deepest = candidates
            .iter()
            .enumerate()
            .filter(|(index, candidate)| {
                !kept.contains(index)
                    && !reached.contains(index)
                    && candidate.separation < bound
                    && (round == 0 || candidate.separation < 0.0)
            })
            .min_by(|(_, a), (_, b)| a.separation.total_cmp(&b.separation));
        let Some((index, &deepest)) = deepest else {
            break;
        };
        let distance = |point: &ContactPoint| point.position.distance_squared(deepest.position);
        let nearest = unmoved()
            .min_by(|(_, a), (_, b)| distance(a).total_cmp(&distance(b)))
            .map(|(slot, _)| slot);
        let Some(slot) = nearest else {
            break;
        };
        let point = &mut manifold.points_mut()[slot];
        point.position = deepest.position;
        point.separation = deepest.separation;
        moved[slot] = true;
        reached[round] = index;
    }
}

/// Candidates within this distance, metres, of the farthest along a direction are equally far
/// ([`reduce_contacts_on_face`]): f32 rounding of points on one edge of a 10 m face is 1e-6 m.
const EXTREME_TIE: f32 = 1.0e-5;

/// A dropped point deeper than every kept point by more than this, metres, is reached by moving
/// the nearest kept point onto it ([`reduce_contacts_on_face`]). Well below the 0.1 mm to which
/// contact depths are checked, well above the f32 rounding (1e-6 m) that
/// makes the corners of a face resting flat differ in depth.
pub const DEEPEST_SLACK: f32 = 2.0e-5;

/// Indices of the candidates chosen so far, in order of choice.
#[derive(Debug, Clone, Copy, Default)]
struct Chosen {
    indices: [usize; MAX_MANIFOLD_POINTS],
    len: usize,
}

impl Chosen {
    fn push(&mut self, index: usize) {
        if self.len < MAX_MANIFOLD_POINTS {
            self.indices[self.len] = index;
            self.len += 1;
        }
    }

    fn indices(&self) -> &[usize] {
        &self.indices[..self.len]
    }
}

/// The manifold of the candidates at `indices`, in that order.
fn manifold_of(
    normal: Vec3,
    candidates: &[ContactPoint],
    indices: impl Iterator<Item = usize>,
) -> Manifold {
    let mut manifold = Manifold::new(normal);
    for index in indices {
        manifold.push(candidates[index]);
    }
    manifold
}

/// The index of the deepest candidate (the first among equals); 0 for none.
fn deepest_index(candidates: &[ContactPoint]) -> usize {
    candidates
        .iter()
        .enumerate()
        .min_by(|(_, a), (_, b)| a.separation.total_cmp(&b.separation))
        .map_or(0, |(index, _)| index)
}

/// Adds to the one to three points already chosen (none: nothing is added) until there are four,
/// each time the point adding the most: after one point, the point farthest from it; after two,
/// the point making the largest triangle with them; after three, the point farthest outside that
/// triangle (the largest area added). A point within [`MIN_AREA_FRACTION`] of the line or triangle
/// already chosen adds nothing and ends the choice.
fn spread(normal: Vec3, candidates: &[ContactPoint], chosen: &mut Chosen) {
    if chosen.len == 1 {
        let first = candidates[chosen.indices[0]].position;
        let farthest = candidates
            .iter()
            .map(|candidate| candidate.position.distance_squared(first))
            .enumerate()
            .max_by(|(_, a), (_, b)| a.total_cmp(b));
        match farthest {
            Some((farthest, span_squared)) if span_squared > 0.0 => chosen.push(farthest),
            _ => return,
        }
    }
    if chosen.len == 2 {
        let [first, second] = [0, 1].map(|slot| candidates[chosen.indices[slot]].position);
        let min_double_area = MIN_AREA_FRACTION * first.distance_squared(second);
        let widest = candidates
            .iter()
            .map(|candidate| signed_double_area(first, second, candidate.position, normal))
            .enumerate()
            .max_by(|(_, a), (_, b)| a.abs().total_cmp(&b.abs()));
        match widest {
            Some((widest, area)) if area.abs() > min_double_area => chosen.push(widest),
            _ => return,
        }
    }
    if chosen.len == 3 {
        let triangle = [0, 1, 2].map(|slot| candidates[chosen.indices[slot]].position);
        let area = signed_double_area(triangle[0], triangle[1], triangle[2], normal);
        let span_squared = (0..3)
            .map(|edge| triangle[edge].distance_squared(triangle[(edge + 1) % 3]))
            .fold(0.0, f32::max);
        // With the triangle wound counter-clockwise, a point outside edge (p, q) has a negative
        // area with it; the most negative is the point that adds the most area.
        let winding = area.signum();
        let outside = candidates
            .iter()
            .map(|candidate| {
                (0..3)
                    .map(|edge| {
                        winding
                            * signed_double_area(
                                triangle[edge],
                                triangle[(edge + 1) % 3],
                                candidate.position,
                                normal,
                            )
                    })
                    .fold(f32::INFINITY, f32::min)
            })
            .enumerate()
            .min_by(|(_, a), (_, b)| a.total_cmp(b));
        if let Some((fourth, added)) = outside {
            if added < -MIN_AREA_FRACTION * span_squared {
                chosen.push(fourth);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The square `[-1, 1]²` at height 0, counter-clockwise about +Z.
    const SQUARE: [Vec3; 4] = [
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(-1.0, 1.0, 0.0),
    ];

    fn contact(x: f32, y: f32, separation: f32, id: u32) -> ContactPoint {
        ContactPoint {
            position: Vec3::new(x, y, 0.0),
            separation,
            id,
        }
    }

    #[test]
    fn polygon_inside_is_unchanged() {
        let incident: Vec<Vec3> = SQUARE.iter().map(|p| *p * 0.5 + Vec3::Z).collect();
        let clipped = clip_polygon(&incident, &SQUARE, Vec3::Z);
        assert_eq!(clipped.len(), 4);
        for (index, vertex) in clipped.vertices().iter().enumerate() {
            assert_eq!(vertex.position, incident[index]);
            assert_eq!(vertex.feature, ClipFeature::IncidentVertex(index as u8));
        }
    }

    #[test]
    fn rotated_square_is_cut_to_an_octagon() {
        // A square rotated 45° whose corners stick out past each side of the reference.
        let radius = 1.3;
        let incident: Vec<Vec3> = (0..4)
            .map(|k| {
                let angle = std::f32::consts::FRAC_PI_2 * k as f32;
                Vec3::new(radius * angle.cos(), radius * angle.sin(), -0.2)
            })
            .collect();
        let clipped = clip_polygon(&incident, &SQUARE, Vec3::Z);
        assert_eq!(clipped.len(), 8);
        let mut keys: Vec<u16> = clipped.vertices().iter().map(|v| v.feature.key()).collect();
        for vertex in clipped.vertices() {
            assert!(matches!(vertex.feature, ClipFeature::EdgeCrossing { .. }));
            let p = vertex.position;
            assert!(p.x.abs() <= 1.0 + 1e-6);
            assert!(p.y.abs() <= 1.0 + 1e-6);
            assert!((p.x.abs() + p.y.abs() - radius).abs() < 1e-5);
        }
        keys.sort_unstable();
        keys.dedup();
        assert_eq!(keys.len(), 8, "ids must be distinct");
    }

    #[test]
    fn big_polygon_keeps_the_reference_corners() {
        let incident: Vec<Vec3> = SQUARE.iter().map(|p| *p * 3.0).collect();
        let clipped = clip_polygon(&incident, &SQUARE, Vec3::Z);
        assert_eq!(clipped.len(), 4);
        for vertex in clipped.vertices() {
            assert!(matches!(vertex.feature, ClipFeature::SideCorner { .. }));
            let corner = vertex.position.abs();
            assert!((corner - Vec3::new(1.0, 1.0, 0.0)).abs().max_element() <= 1e-6);
        }
    }

    #[test]
    fn disjoint_polygon_vanishes_and_clockwise_reference_clips_everything() {
        let incident: Vec<Vec3> = SQUARE.iter().map(|p| *p + Vec3::X * 5.0).collect();
        assert!(clip_polygon(&incident, &SQUARE, Vec3::Z).is_empty());
        let inside: Vec<Vec3> = SQUARE.iter().map(|p| *p * 0.5).collect();
        assert!(clip_polygon(&inside, &SQUARE, -Vec3::Z).is_empty());
    }

    #[test]
    fn vertices_on_the_sides_keep_their_ids_through_round_off() {
        for nudge in [Vec3::ZERO, Vec3::X * 5e-5, Vec3::new(-3e-5, 8e-5, 0.0)] {
            let incident: Vec<Vec3> = SQUARE.iter().map(|p| *p + nudge - Vec3::Z).collect();
            let clipped = clip_polygon(&incident, &SQUARE, Vec3::Z);
            let features: Vec<ClipFeature> = clipped.vertices().iter().map(|v| v.feature).collect();
            assert_eq!(
                features,
                (0..4).map(ClipFeature::IncidentVertex).collect::<Vec<_>>()
            );
        }
        // Past the slop, the overhanging corners are cut exactly at the sides.
        let incident: Vec<Vec3> = SQUARE.iter().map(|p| *p + Vec3::X * 1e-3).collect();
        let clipped = clip_polygon(&incident, &SQUARE, Vec3::Z);
        assert_eq!(clipped.len(), 4);
        for vertex in clipped.vertices() {
            assert!(vertex.position.x <= 1.0 + 1e-6);
        }
    }

    #[test]
    fn segment_is_cut_at_the_sides() {
        let clipped = clip_segment(
            Vec3::new(-3.0, 0.5, 1.0),
            Vec3::new(0.5, 0.5, 1.0),
            &SQUARE,
            Vec3::Z,
        );
        let [enter, exit] = clipped.expect("the segment crosses the square");
        assert!((enter.position - Vec3::new(-1.0, 0.5, 1.0)).length() < 1e-6);
        assert_eq!(
            enter.feature,
            ClipFeature::EdgeCrossing { edge: 0, side: 3 }
        );
        assert_eq!(exit.position, Vec3::new(0.5, 0.5, 1.0));
        assert_eq!(exit.feature, ClipFeature::IncidentVertex(1));
        assert!(clip_segment(
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
            &SQUARE,
            Vec3::Z
        )
        .is_none());
        // Crosses two sides' outer regions without entering the square.
        assert!(clip_segment(
            Vec3::new(0.0, 3.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
            &SQUARE,
            Vec3::Z
        )
        .is_none());
    }

    #[test]
    fn degenerate_inputs_do_not_panic() {
        let point = [Vec3::new(0.2, 0.1, 0.0)];
        assert_eq!(clip_polygon(&point, &SQUARE, Vec3::Z).len(), 1);
        assert!(clip_polygon(&[], &SQUARE, Vec3::Z).is_empty());
        let same = [Vec3::ONE; 3];
        let clipped = clip_polygon(&SQUARE, &same, Vec3::Z);
        assert_eq!(clipped.len(), 4);
        assert!(clip_segment(Vec3::ZERO, Vec3::ZERO, &SQUARE, Vec3::Z).is_some());
        assert!(reduce_contacts(Vec3::Z, &[]).is_empty());
        let coincident = [contact(0.0, 0.0, -0.1, 1); 6];
        assert_eq!(reduce_contacts(Vec3::Z, &coincident).len(), 1);
    }

    #[test]
    fn reduction_keeps_the_deepest_and_the_widest() {
        // An octagon of points with one deep point; the reduction keeps four spread points,
        // the deepest first.
        let candidates: Vec<ContactPoint> = (0..8)
            .map(|k| {
                let angle = std::f32::consts::FRAC_PI_4 * k as f32;
                let separation = if k == 3 { -0.05 } else { -0.01 };
                contact(angle.cos(), angle.sin(), separation, k)
            })
            .collect();
        let manifold = reduce_contacts(Vec3::Z, &candidates);
        assert_eq!(manifold.len(), 4);
        let ids: Vec<u32> = manifold.points().iter().map(|p| p.id).collect();
        assert_eq!(ids[0], 3);
        assert_eq!(ids[1], 7, "the opposite point is farthest");
        // The other two are on either side of the diameter 3–7, one each.
        let sides: Vec<f32> = ids[2..]
            .iter()
            .map(|&id| {
                let p = candidates[id as usize].position;
                signed_double_area(candidates[3].position, candidates[7].position, p, Vec3::Z)
            })
            .collect();
        assert!(sides[0] * sides[1] < 0.0);
    }

    #[test]
    fn face_reduction_keeps_its_ids_and_reaches_the_deepest() {
        // A regular hexagon, first flat, then tilted so that each corner in turn is the deepest
        // by 4 mm: the same four ids every time, and the deepest depth always in the manifold.
        let tangent = Vec3::new(15f32.to_radians().cos(), 15f32.to_radians().sin(), 0.0);
        let hexagon = |tilt: Option<usize>| -> Vec<ContactPoint> {
            (0..6)
                .map(|k| {
                    let angle = std::f32::consts::FRAC_PI_3 * k as f32;
                    let depth = tilt.map_or(0.0, |deepest| {
                        0.004 * (angle - std::f32::consts::FRAC_PI_3 * deepest as f32).cos()
                    });
                    contact(0.5 * angle.cos(), 0.5 * angle.sin(), -0.01 - depth, k)
                })
                .collect()
        };
        let ids = |manifold: &Manifold| {
            let mut ids: Vec<u32> = manifold.points().iter().map(|point| point.id).collect();
            ids.sort_unstable();
            ids
        };
        let flat = reduce_contacts_on_face(Vec3::Z, tangent, &hexagon(None), Surface::Flat);
        assert_eq!(flat.len(), 4);
        for deepest in 0..6 {
            let tilted =
                reduce_contacts_on_face(Vec3::Z, tangent, &hexagon(Some(deepest)), Surface::Flat);
            assert_eq!(ids(&tilted), ids(&flat));
            assert_eq!(tilted.deepest_separation(), -0.014);
        }
    }

    #[test]
    fn face_reduction_keeps_the_corners_of_an_edge_found_many_times() {
        // A unit square resting 26 µm deep, as a box's face on a floor of triangles: besides the
        // corners, the triangles under its front edge (x = 1) find points on that edge, one of
        // them where the edge only grazes a triangle's side, 3.5 mm apart. Picking that one as
        // the farthest along +X left the corner (1, 0) out and the box spun on three points.
        let mut candidates = vec![
            contact(1.0, 0.0, -2.6e-5, 0),
            contact(1.0, 0.4, 3.5e-3, 1),
            contact(1.0, 0.5, -2.6e-5, 2),
            contact(1.0, 1.0, -2.6e-5, 3),
            contact(0.0, 1.0, -0.9e-5, 4),
            contact(0.0, 0.0, -0.9e-5, 5),
        ];
        for _ in 0..candidates.len() {
            let manifold = reduce_contacts_on_face(
                Vec3::Z,
                Vec3::X,
                &candidates,
                Surface::Bent { reach: 0.0 },
            );
            let mut ids: Vec<u32> = manifold.points().iter().map(|point| point.id).collect();
            ids.sort_unstable();
            assert_eq!(ids, [0, 3, 4, 5], "from {candidates:?}");
            candidates.rotate_left(1);
        }
    }

    #[test]
    fn bent_face_reduction_keeps_the_points_that_touch() {
        // A cylinder's cap (radius 0.3 m) resting on a terrain across a crease: its rim points
        // found by the triangles, four touching and four up to 1.4 mm apart, the extremes along
        // the tangents among the ones apart. Kept by place, the extremes held the cap on two of
        // its four touching points (the other two moved in), and it rocked at 5 cm/s for ever.
        let candidates = [
            contact(-0.2709, -0.1306, 1.167e-3, 0),
            contact(-0.1056, -0.2828, 1.399e-3, 1),
            contact(0.1204, -0.2703, -1.66e-4, 2),
            contact(0.2745, -0.1003, -3.7e-5, 3),
            contact(-0.1245, 0.2671, -3.6e-5, 4),
            contact(-0.2786, 0.0971, -1.12e-4, 5),
            contact(0.1013, 0.2797, 8.66e-4, 6),
            contact(0.2665, 0.1276, 7.95e-4, 7),
        ];
        let manifold =
            reduce_contacts_on_face(Vec3::Z, Vec3::X, &candidates, Surface::Bent { reach: 0.0 });
        let mut ids: Vec<u32> = manifold.points().iter().map(|point| point.id).collect();
        ids.sort_unstable();
        assert_eq!(ids, [2, 3, 4, 5]);
        for point in manifold.points() {
            assert_eq!(point.position, candidates[point.id as usize].position);
        }
    }

    #[test]
    fn reduction_of_collinear_points_keeps_two() {
        let candidates: Vec<ContactPoint> = (0..6)
            .map(|k| contact(k as f32 * 0.1, 0.0, -0.01, k))
            .collect();
        let manifold = reduce_contacts(Vec3::Z, &candidates);
        assert_eq!(manifold.len(), 2);
    }

    #[test]
    fn keys_are_distinct() {
        let mut keys = Vec::new();
        for a in 0..MAX_POLYGON_VERTICES as u8 {
            keys.push(ClipFeature::IncidentVertex(a).key());
            for b in 0..MAX_POLYGON_VERTICES as u8 {
                keys.push(ClipFeature::EdgeCrossing { edge: a, side: b }.key());
                keys.push(
                    ClipFeature::SideCorner {
                        first: a,
                        second: b,
                    }
                    .key(),
                );
            }
        }
        let total = keys.len();
        keys.sort_unstable();
        keys.dedup();
        assert_eq!(keys.len(), total);
    }
}
