//! The separating-axis queries between two convex polyhedra A and B: the face of one beyond whose
//! plane the other lies farthest, and the edge pair whose cross product separates them most. Only
//! edge pairs whose arcs cross on the Gauss map are candidates (the pair builds a face of the
//! Minkowski difference; other pairs cannot give the deepest axis). Two boxes take closed forms, a
//! box and a hull one candidate per hull edge and box axis, two hulls every pair; edges whose reach
//! on the Gauss map cannot beat a threshold are skipped.

use crate::collision::polyhedron::{box_vertex, Frame, Polyhedron, Topology, BOX_EDGES};
use crate::math::Vec3;
use crate::shape::{EdgeLanes, FaceLanes};
use glam::Vec4;

/// Absolute part of the axis-choice tolerances, metres.
pub(super) const ABSOLUTE_TOLERANCE: f32 = 5.0e-4;

/// Edge pairs whose directions make an angle with a sine below this are treated as parallel and
/// skipped: their cross product is too short to be a reliable axis, and the faces around such
/// edges already cover those directions.
const PARALLEL_SINE: f32 = 1.0e-3;

/// How many groups of four of A's edges the edge query reach-tests at a time (a stack buffer).
const A_GROUP_CHUNK: usize = 64;

/// A face of one polyhedron and how far the other lies beyond its plane (negative: how deep it
/// reaches in), measured at the other's vertex deepest along the face's inward normal.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(super) struct FaceAxis {
    pub(super) face: usize,
    pub(super) separation: f32,
}

/// An edge of A and an edge of B, their axis in A's frame pointing from A to B, and the
/// separation of the two edges along it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(super) struct EdgeAxis {
    pub(super) edge_a: usize,
    pub(super) edge_b: usize,
    pub(super) axis: Vec3,
    pub(super) separation: f32,
}

/// The face of `reference` beyond whose plane `other` (placed in the reference frame by
/// `other_in_reference`) lies farthest, or reaches in least (the first of equals): in closed form
/// for two boxes, by [`best_face_axis_by_vertices`] against a hull, else by
/// [`best_face_axis_by_support`].
pub(super) fn best_face_axis(
    reference: &Polyhedron,
    other: &Polyhedron,
    other_in_reference: &Frame,
) -> FaceAxis {
    match (reference.topology, other.topology) {
        (Topology::Cuboid(half_reference), Topology::Cuboid(half_other)) => {
            best_box_box_face_axis(half_reference, half_other, other_in_reference)
        }
        (_, Topology::Hull(hull)) => {
            best_face_axis_by_vertices(reference, hull.vertices(), other_in_reference)
        }
        _ => best_face_axis_by_support(reference, other, other_in_reference),
    }
}

/// How many groups of four of the reference's faces [`best_face_axis_by_vertices`] measures at
/// a time (a stack buffer of their minima).
const FACE_GROUP_CHUNK: usize = 32;

/// [`best_face_axis`] against the `vertices` of a hull: each vertex is placed in the reference
/// frame once and measured against four face planes per step ([`FaceLanes`]), so that each face's
/// separation, `min over v of n · v − offset` (the vertex deepest along the inward normal),
/// builds up in a lane.
fn best_face_axis_by_vertices(
    reference: &Polyhedron,
    vertices: &[Vec3],
    other_in_reference: &Frame,
) -> FaceAxis {
    let mut best = FaceAxis {
        face: 0,
        separation: f32::NEG_INFINITY,
    };
    let mut box_lanes = [FaceLanes::default(); 2];
    let face_lanes = reference.face_lanes(&mut box_lanes);
    let face_count = reference.face_count();
    for (chunk, planes) in face_lanes.chunks(FACE_GROUP_CHUNK).enumerate() {
        let mut lowest = [Vec4::INFINITY; FACE_GROUP_CHUNK];
        for &vertex in vertices {
            let placed = other_in_reference.point(vertex);
            let [x, y, z] = placed.to_array().map(Vec4::splat);
            for (low, group) in lowest.iter_mut().zip(planes) {
                let [nx, ny, nz] = group.normal;
                *low = low.min(nx * x + ny * y + nz * z);
            }
        }
        for (group, (low, plane)) in lowest.iter().zip(planes).enumerate() {
            let first_face = 4 * (chunk * FACE_GROUP_CHUNK + group);
            let separations = (*low - plane.offset).to_array();
            for (lane, &separation) in separations.iter().enumerate() {
                if first_face + lane < face_count && separation > best.separation {
                    best = FaceAxis {
                        face: first_face + lane,
                        separation,
                    };
                }
            }
        }
    }
    best
}

/// [`best_face_axis`] for two boxes: along the reference's axis `eᵢ`, the other box (centre `c`,
/// axes `fₖ`, half extents `bₖ`) reaches down to `cᵢ − Σₖ bₖ |eᵢ · fₖ|`, so the face facing its
/// centre (`+eᵢ` when `cᵢ ≥ 0`) has the larger separation, `|cᵢ| − aᵢ − Σₖ bₖ |eᵢ · fₖ|`.
fn best_box_box_face_axis(
    half_reference: Vec3,
    half_other: Vec3,
    other_in_reference: &Frame,
) -> FaceAxis {
    let rows = other_in_reference.rotation.transpose();
    let mut best = FaceAxis {
        face: 0,
        separation: f32::NEG_INFINITY,
    };
    for (axis, row) in [rows.x_axis, rows.y_axis, rows.z_axis]
        .into_iter()
        .enumerate()
    {
        let centre = other_in_reference.translation[axis];
        let separation = centre.abs() - half_reference[axis] - half_other.dot(row.abs());
        if separation > best.separation {
            best = FaceAxis {
                face: 2 * axis + usize::from(centre < 0.0),
                separation,
            };
        }
    }
    best
}

/// [`best_face_axis`] for any two polyhedra, from the other's support point against each face.
fn best_face_axis_by_support(
    reference: &Polyhedron,
    other: &Polyhedron,
    other_in_reference: &Frame,
) -> FaceAxis {
    let mut best = FaceAxis {
        face: 0,
        separation: f32::NEG_INFINITY,
    };
    for face in 0..reference.face_count() {
        let plane = reference.face_plane(face);
        let inward = other_in_reference.inverse_vector(-plane.normal);
        let deepest = other_in_reference.point(other.support(inward));
        let separation = plane.normal.dot(deepest) - plane.offset;
        if separation > best.separation {
            best = FaceAxis { face, separation };
        }
    }
    best
}

/// Replaces `best` by `candidate` when there is none yet or the candidate's separation is larger,
/// or equal with a lower edge of A, then of B.
fn keep_larger(best: &mut Option<EdgeAxis>, candidate: EdgeAxis) {
    let features = |axis: &EdgeAxis| (axis.edge_a, axis.edge_b);
    let kept = best.is_none_or(|best| {
        candidate.separation > best.separation
            || (candidate.separation == best.separation && features(&candidate) < features(&best))
    });
    if kept {
        *best = Some(candidate);
    }
}

/// An edge placed in A's frame: its first end, its direction and its face normals, negated for
/// an edge of B (its arc on the Gauss map of the Minkowski difference A − B).
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct PlacedEdge {
    start: Vec3,
    direction: Vec3,
    normals: [Vec3; 2],
}

impl PlacedEdge {
    /// Lane `lane` of A's `lanes`, already in A's frame.
    fn of_a(lanes: &EdgeLanes, lane: usize) -> Self {
        Self {
            start: lanes.start(lane),
            direction: lanes.direction(lane),
            normals: lanes.normals(lane),
        }
    }

    /// Lane `lane` of B's `lanes`, moved into A's frame by `b_in_a`.
    fn of_b(lanes: &EdgeLanes, lane: usize, b_in_a: &Frame) -> Self {
        Self {
            start: b_in_a.point(lanes.start(lane)),
            direction: b_in_a.vector(lanes.direction(lane)),
            normals: lanes.normals(lane).map(|normal| -b_in_a.vector(normal)),
        }
    }
}

/// Over the edge pairs that build a face of the Minkowski difference A − B, the largest
/// separation along their cross product, in A's frame (`b_in_a` places B there, `a_in_b` A in
/// B's): by [`best_box_box_edge_axis`] for two boxes, by [`best_box_edge_axis`] when A or B is a
/// box (the roles swapped when only B is), else by [`best_edge_axis`] over every pair. Edges
/// whose pairs cannot separate the shapes by more than `threshold` may be skipped
/// ([`edge_reach`]), so a pair at or below it may be missed.
pub(super) fn edge_query(
    a: &Polyhedron,
    b: &Polyhedron,
    b_in_a: &Frame,
    a_in_b: &Frame,
    threshold: f32,
) -> Option<EdgeAxis> {
    match (a.topology, b.topology) {
        (Topology::Cuboid(half_a), Topology::Cuboid(half_b)) => {
            best_box_box_edge_axis(half_a, half_b, b_in_a)
        }
        (Topology::Cuboid(half_extents), _) => {
            best_box_edge_axis(half_extents, b, b_in_a, threshold)
        }
        (_, Topology::Cuboid(half_extents)) => {
            best_box_edge_axis(half_extents, a, a_in_b, threshold).map(|swapped| EdgeAxis {
                edge_a: swapped.edge_b,
                edge_b: swapped.edge_a,
                axis: -b_in_a.vector(swapped.axis),
                separation: swapped.separation,
            })
        }
        _ => best_edge_axis(a, b, b_in_a, threshold),
    }
}

/// A bit per lane of `lanes`, set for the edges whose pairs may separate the shapes by at least
/// `threshold` (less [`ABSOLUTE_TOLERANCE`], against rounding): whose reach from the other shape,
/// which holds the ball of radius `inner_radius` about `inside` (in this shape's frame), is not
/// below it (lanes from `count` edges on are clear). An edge's reach bounds the separation of any
/// pair with it from above: the largest `n · (p − s) − r` over the unit normals `n` on the edge's
/// arc between its face normals `n₁, n₂`, for `s` the edge's first end, `p = inside` and
/// `r = inner_radius`. The pair's separation along its axis `n` is the other shape's extent along
/// `−n` less this shape's, which is reached at the edge; the other shape reaches at least to the
/// ball's far side, `n · p − r`, so the separation is at most `n · (p − s) − r`. The largest
/// `n · (p − s)` is `|v|` for `v` the part of `p − s` in the arc's plane when `v` lies between
/// `n₁` and `n₂` (`v = α n₁ + β n₂`, `α, β ≥ 0`), else at an end; infinite for a degenerate arc
/// (`1 − (n₁ · n₂)² ≤ 10⁻⁶`, or NaN).
fn within_reach(
    lanes: &EdgeLanes,
    count: usize,
    inside: Vec3,
    inner_radius: f32,
    threshold: f32,
) -> u32 {
    let toward: [Vec4; 3] =
        std::array::from_fn(|axis| Vec4::splat(inside[axis]) - lanes.start[axis]);
    let dot =
        |normal: &[Vec4; 3]| normal[0] * toward[0] + normal[1] * toward[1] + normal[2] * toward[2];
    let [first, second] = &lanes.normals;
    let (along_first, along_second) = (dot(first), dot(second));
    let cosine = lanes.cosine;
    let sine_squared = Vec4::ONE - cosine * cosine;
    let proper_arc = sine_squared.cmpgt(Vec4::splat(1.0e-6));
    let alpha = along_first - along_second * cosine;
    let beta = along_second - along_first * cosine;
    let between = alpha.cmpge(Vec4::ZERO) & beta.cmpge(Vec4::ZERO);
    let on_arc = ((alpha * along_first + beta * along_second) / sine_squared)
        .max(Vec4::ZERO)
        .sqrt();
    let reach = Vec4::select(between, on_arc, along_first.max(along_second));
    let least = Vec4::splat(threshold + inner_radius - ABSOLUTE_TOLERANCE);
    let out_of_reach = reach.cmplt(least) & proper_arc;
    let present = (1u32 << count.min(4)) - 1;
    !out_of_reach.bitmask() & present
}

/// The lanes set in `mask`, lowest first.
fn lanes_of(mut mask: u32) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (mask != 0).then(|| {
            let lane = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            lane
        })
    })
}

/// [`best_edge_axis`] for two boxes (half extents `half_a`, `half_b`): one candidate per pair of
/// axes `eᵢ` of A and `fⱼ` of B. Of the two Minkowski faces along `±(eᵢ × fⱼ)`, the one facing B's
/// centre is the larger separation, `|n · c| − Σₖ aₖ |n · eₖ| − Σₖ bₖ |n · fₖ|` (`c` B's centre in
/// A's frame), between A's edge along `eᵢ` supporting `n` and B's edge along `fⱼ` supporting
/// `−n`, read from the signs of the other components. A crossing on a face normal (a zero
/// component) is left to the face axes, as a parallel pair is. Each product is read off B's axes
/// in A's frame: `eᵢ × fⱼ` has two components of `fⱼ`, and `n · eₖ`, `n · fₖ` are components of
/// `n` and 2×2 sums, with `n · fⱼ = 0`.
fn best_box_box_edge_axis(half_a: Vec3, half_b: Vec3, b_in_a: &Frame) -> Option<EdgeAxis> {
    let mut best: Option<EdgeAxis> = None;
    // columns[j][k]: component k, in A's frame, of B's axis fⱼ.
    let columns = [
        b_in_a.rotation.x_axis,
        b_in_a.rotation.y_axis,
        b_in_a.rotation.z_axis,
    ]
    .map(|axis| axis.to_array());
    let centre = b_in_a.translation.to_array();
    let (half_a, half_b) = (half_a.to_array(), half_b.to_array());
    for index_a in 0..3 {
        // eᵢ × f has no eᵢ component, −f[last] along e_next and f[next] along e_last (cyclic).
        let (next, last) = ((index_a + 1) % 3, (index_a + 2) % 3);
        for (index_b, column) in columns.iter().enumerate() {
            let (mut along_next, mut along_last) = (-column[last], column[next]);
            let length_squared = along_next * along_next + along_last * along_last;
            // Written so that a NaN (from overflow on absurdly large shapes) also rejects it.
            let crosses = length_squared > PARALLEL_SINE * PARALLEL_SINE;
            if !crosses {
                continue;
            }
            let mut toward_centre = along_next * centre[next] + along_last * centre[last];
            if toward_centre < 0.0 {
                (along_next, along_last, toward_centre) =
                    (-along_next, -along_last, -toward_centre);
            }
            let inverse_length = length_squared.sqrt().recip();
            let mut axis = [0.0; 3];
            axis[next] = along_next * inverse_length;
            axis[last] = along_last * inverse_length;
            // −fₖ · axis; zero for fⱼ, which the axis is normal to.
            let against_in_b: [f32; 3] = std::array::from_fn(|k| {
                if k == index_b {
                    0.0
                } else {
                    -(axis[next] * columns[k][next] + axis[last] * columns[k][last])
                }
            });
            let reach_b: f32 = (0..3).map(|k| half_b[k] * against_in_b[k].abs()).sum();
            let separation = toward_centre * inverse_length
                - half_a[next] * axis[next].abs()
                - half_a[last] * axis[last].abs()
                - reach_b;
            // The edges are read only for a candidate that would be kept.
            if best.is_some_and(|best| separation <= best.separation) {
                continue;
            }
            let axis = Vec3::from_array(axis);
            if let (Some(edge_a), Some(edge_b)) = (
                box_edge_along(index_a, axis),
                box_edge_along(index_b, Vec3::from_array(against_in_b)),
            ) {
                best = Some(EdgeAxis {
                    edge_a,
                    edge_b,
                    axis,
                    separation,
                });
            }
        }
    }
    best
}

/// The box edge along axis `axis_index` that is the box's support along `direction` (local),
/// read from the signs of `direction`'s other two components; `None` when one is zero (the
/// support is then a face).
fn box_edge_along(axis_index: usize, direction: Vec3) -> Option<usize> {
    let (first, second) = match axis_index {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    };
    (direction[first] != 0.0 && direction[second] != 0.0).then(|| {
        4 * axis_index
            + usize::from(direction[first] > 0.0)
            + 2 * usize::from(direction[second] > 0.0)
    })
}

/// [`best_edge_axis`] for a box A (half extents `half_extents`) and any polyhedron B, with one
/// candidate per edge of B and box axis instead of one per pair of edges. The box's four edges
/// along axis `i` have arcs on the Gauss map that together make the great circle normal to `i`:
/// B's negated arc crosses it when the ends' `i` components differ in sign, at the point
/// `±(eᵢ × e_B)` lying on B's arc, and the box edge whose arc holds that point is the one whose
/// two faces have the signs of the point's other two components. A crossing on a face normal of
/// the box is left to the face axes, as a parallel pair is.
fn best_box_edge_axis(
    half_extents: Vec3,
    b: &Polyhedron,
    b_in_a: &Frame,
    threshold: f32,
) -> Option<EdgeAxis> {
    // Worked in B's frame, where B's edges need no moving: the box axes `eᵢ` are the rows of the
    // rotation, and only a crossing's axis is moved to A's frame.
    let rotation = b_in_a.rotation.transpose();
    let box_axes = [rotation.x_axis, rotation.y_axis, rotation.z_axis];
    let box_centre = b_in_a.inverse_vector(-b_in_a.translation);
    let mut best: Option<EdgeAxis> = None;
    let mut box_lanes = [EdgeLanes::default(); 3];
    let b_lanes = b.edge_lanes(&mut box_lanes);
    let b_count = b.edge_count();
    for (group, lanes) in b_lanes.iter().enumerate() {
        for lane in lanes_of(within_reach(
            lanes,
            b_count - 4 * group,
            box_centre,
            half_extents.min_element(),
            threshold,
        )) {
            let edge_b = 4 * group + lane;
            let local = PlacedEdge::of_a(lanes, lane);
            let direction = local.direction;
            let [m1, m2] = [-local.normals[0], -local.normals[1]];
            let parallel_limit = PARALLEL_SINE * PARALLEL_SINE * direction.length_squared();
            for (axis_index, &box_axis) in box_axes.iter().enumerate() {
                if m1.dot(box_axis) * m2.dot(box_axis) >= 0.0 {
                    continue;
                }
                let mut axis = box_axis.cross(direction);
                let length_squared = axis.length_squared();
                // Written so that a NaN (from overflow on absurdly large shapes) also rejects it.
                let crosses = length_squared > parallel_limit;
                let toward_b_arc = axis.dot(m1 + m2);
                if !crosses || toward_b_arc == 0.0 {
                    continue;
                }
                if toward_b_arc < 0.0 {
                    axis = -axis;
                }
                let axis_in_a = b_in_a.vector(axis);
                let Some(edge_a) = box_edge_along(axis_index, axis_in_a) else {
                    continue;
                };
                let on_edge_a = box_vertex(half_extents, usize::from(BOX_EDGES[edge_a].0[0]));
                let axis = axis_in_a / length_squared.sqrt();
                let separation = axis.dot(b_in_a.point(local.start) - on_edge_a);
                keep_larger(
                    &mut best,
                    EdgeAxis {
                        edge_a,
                        edge_b,
                        axis,
                        separation,
                    },
                );
            }
        }
    }
    best
}

/// Over the edge pairs that build a face of the Minkowski difference A − B, the largest
/// separation along their cross product, computed in A's frame (`b_in_a` places B there) by
/// trying every pair of edges within reach ([`within_reach`]) ([`keep_larger`] on ties). A's edges are reach-tested four at a time in groups of
/// [`A_GROUP_CHUNK`], B's each moved into A's frame only when within reach and tested against
/// A's four at a time ([`arcs_cross`]).
fn best_edge_axis(
    a: &Polyhedron,
    b: &Polyhedron,
    b_in_a: &Frame,
    threshold: f32,
) -> Option<EdgeAxis> {
    // A's inside point in B's frame, where B's edges are tested before being moved.
    let inside_a = b_in_a.inverse_vector(a.interior_point() - b_in_a.translation);
    let inside_b = b_in_a.point(b.interior_point());
    let (mut box_lanes_a, mut box_lanes_b) = ([EdgeLanes::default(); 3], [EdgeLanes::default(); 3]);
    let (a_lanes, b_lanes) = (
        a.edge_lanes(&mut box_lanes_a),
        b.edge_lanes(&mut box_lanes_b),
    );
    let (a_count, b_count) = (a.edge_count(), b.edge_count());
    let mut best: Option<EdgeAxis> = None;
    let mut reach_a = [0u32; A_GROUP_CHUNK];
    for (chunk, a_chunk) in a_lanes.chunks(A_GROUP_CHUNK).enumerate() {
        let first_group = chunk * A_GROUP_CHUNK;
        let mut any_a = 0;
        for (group, (lanes, reach)) in a_chunk.iter().zip(&mut reach_a).enumerate() {
            let count = a_count - 4 * (first_group + group);
            *reach = within_reach(lanes, count, inside_b, b.inner_radius(), threshold);
            any_a |= *reach;
        }
        if any_a == 0 {
            continue;
        }
        for (group_b, lanes_b) in b_lanes.iter().enumerate() {
            let reach_b = within_reach(
                lanes_b,
                b_count - 4 * group_b,
                inside_a,
                a.inner_radius(),
                threshold,
            );
            for lane_b in lanes_of(reach_b) {
                let edge_b = 4 * group_b + lane_b;
                let moved = PlacedEdge::of_b(lanes_b, lane_b, b_in_a);
                for (group, (lanes, &reach)) in a_chunk.iter().zip(&reach_a).enumerate() {
                    if reach == 0 {
                        continue;
                    }
                    for lane in lanes_of(arcs_cross(lanes, &moved) & reach) {
                        let edge = PlacedEdge::of_a(lanes, lane);
                        let Some((axis, separation)) = crossing_axis(&edge, &moved) else {
                            continue;
                        };
                        let edge_a = 4 * (first_group + group) + lane;
                        keep_larger(
                            &mut best,
                            EdgeAxis {
                                edge_a,
                                edge_b,
                                axis,
                                separation,
                            },
                        );
                    }
                }
            }
        }
    }
    best
}

/// A bit per lane of A's `lanes`, set where the lane's arc and the negated arc of B's `moved`
/// edge cross on the Gauss map: each one's ends lie on opposite sides of the other's great
/// circle, whose plane normal is the edge direction (`(m₁ · eA)(m₂ · eA) < 0` and
/// `(n₁ · eB)(n₂ · eB) < 0`). Empty lanes give zero.
fn arcs_cross(lanes: &EdgeLanes, moved: &PlacedEdge) -> u32 {
    let dot = |lanes: &[Vec4; 3], vector: Vec3| {
        lanes[0] * vector.x + lanes[1] * vector.y + lanes[2] * vector.z
    };
    let [m1, m2] = moved.normals;
    let [n1, n2] = &lanes.normals;
    let across_a = dot(&lanes.direction, m1) * dot(&lanes.direction, m2);
    let across_b = dot(n1, moved.direction) * dot(n2, moved.direction);
    (across_a.cmplt(Vec4::ZERO) & across_b.cmplt(Vec4::ZERO)).bitmask()
}

/// The axis of an edge of A and an edge of B (both in A's frame) whose arcs cross
/// ([`arcs_cross`]), pointing from A to B, with the separation along it; `None` unless the pair
/// builds a face of the Minkowski difference.
///
/// Edge A's arc on the Gauss map runs between its face normals `n₁, n₂`; edge B's, negated for
/// the difference, between `−m₁, −m₂`. With the ends of each on opposite sides of the other's
/// great circle, the two crossings of the great circles are the same point: the axis
/// `±(eA × eB)` that lies on A's arc (positive on `n₁ + n₂`) must also lie on B's (positive on
/// `−m₁ − m₂`). Then A's edge is A's support along the axis and B's edge is B's support against
/// it.
fn crossing_axis(edge: &PlacedEdge, moved: &PlacedEdge) -> Option<(Vec3, f32)> {
    let a_direction = edge.direction;
    let [n1, n2] = edge.normals;
    let [m1, m2] = moved.normals;
    let mut axis = a_direction.cross(moved.direction);
    let length_squared = axis.length_squared();
    let parallel_limit = PARALLEL_SINE
        * PARALLEL_SINE
        * a_direction.length_squared()
        * moved.direction.length_squared();
    // Written so that a NaN (from overflow on absurdly large shapes) also rejects the pair.
    let crosses = length_squared > parallel_limit;
    if !crosses {
        return None;
    }
    if axis.dot(n1 + n2) < 0.0 {
        axis = -axis;
    }
    if axis.dot(m1 + m2) <= 0.0 {
        return None;
    }
    let axis = axis / length_squared.sqrt();
    Some((axis, axis.dot(moved.start - edge.start)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::polyhedron::{crossing_poses, unit_box};
    use crate::shape::{ConvexHull, Cuboid};

    /// The box routes and the vertex lanes find the same face as every support point, and the
    /// box routes and the skipping of edges out of reach the same edge pair, axis and separation
    /// as trying every pair, for boxes and a hull, either way round.
    #[test]
    fn box_queries_match_the_general_ones() {
        let other = unit_box();
        let points: Vec<Vec3> = (0..12)
            .map(|index| {
                let angle = index as f32 * std::f32::consts::TAU / 6.0;
                let y = if index < 6 { -0.4 } else { 0.3 };
                Vec3::new(0.5 * angle.cos(), y, 0.6 * angle.sin())
            })
            .collect();
        let hull = ConvexHull::new(&points).expect("a prism");
        let cuboid = Cuboid::new(Vec3::new(0.4, 0.3, 0.7)).expect("valid box");
        let shapes = [
            Polyhedron::cuboid(&cuboid),
            Polyhedron::cuboid(&other),
            Polyhedron::hull(&hull),
        ];
        let (mut compared, mut same_pair) = (0, 0);
        for step in 0..200 {
            let t = step as f32;
            let (pose_a, pose_b) = crossing_poses(t);
            for a in &shapes {
                for b in &shapes {
                    for (a, b, pose_a, pose_b) in [(a, b, pose_a, pose_b), (b, a, pose_b, pose_a)] {
                        let b_in_a = Frame::relative(&pose_a, &pose_b);
                        let a_in_b = Frame::relative(&pose_b, &pose_a);
                        let face = best_face_axis(a, b, &b_in_a);
                        let by_support = best_face_axis_by_support(a, b, &b_in_a);
                        assert_eq!(face.face, by_support.face);
                        assert!((face.separation - by_support.separation).abs() < 1e-5);
                        let slow = best_edge_axis(a, b, &b_in_a, f32::NEG_INFINITY);
                        let Some(slow) = slow else {
                            assert!(edge_query(a, b, &b_in_a, &a_in_b, f32::NEG_INFINITY).is_none());
                            continue;
                        };
                        for threshold in [f32::NEG_INFINITY, slow.separation - 0.01] {
                            let fast = edge_query(a, b, &b_in_a, &a_in_b, threshold)
                                .expect("the best pair beats the threshold");
                            assert!((fast.separation - slow.separation).abs() < 1e-5);
                            if (fast.edge_a, fast.edge_b) == (slow.edge_a, slow.edge_b) {
                                assert!((fast.axis - slow.axis).length() < 1e-5);
                                same_pair += 1;
                            }
                            compared += 1;
                        }
                        // Above the best pair, whatever is found is no better.
                        let above = edge_query(a, b, &b_in_a, &a_in_b, slow.separation + 0.01);
                        assert!(above.is_none_or(|fast| fast.separation <= slow.separation + 1e-5));
                    }
                }
            }
        }
        // Only exact ties between pairs (boxes turned alike) may pick another pair.
        assert!(
            same_pair * 100 >= compared * 95,
            "{same_pair} of {compared}"
        );
    }
}
