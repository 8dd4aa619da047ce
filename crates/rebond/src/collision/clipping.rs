//! Clipping shared by the contact builders that rest a polygon or segment on a face: box and hull
//! faces, capsule and cylinder sides.
//!
//! A face contact takes the *incident* feature of one shape (a polygon or a segment), cuts away
//! what lies outside the *reference* face of the other shape (Sutherland–Hodgman against the
//! reference polygon's side planes) and measures what is left against the reference plane; the
//! caller keeps at most four well-spread points of it (`reduction.rs`). Every clipped point
//! carries a [`ClipFeature`] naming how it was made, from which callers build
//! stable contact ids.

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
