//! Reducing a contact's candidate points to the [`MAX_MANIFOLD_POINTS`] that hold it best:
//! [`reduce_contacts`] starting from the deepest, [`reduce_contacts_on_face`] by position on the
//! face, which small motions keep, and which on a mesh's bent surface also holds the points that
//! touch.

use super::clipping::MAX_CLIP_VERTICES;
use crate::collision::manifold::{ContactPoint, Manifold, MAX_MANIFOLD_POINTS};
use crate::math::Vec3;

/// Below this fraction of the squared distance between the first two chosen points, a triangle's
/// doubled area counts as zero when [`reduce_contacts`] picks the third and fourth points: a point
/// that close to the line through the others adds nothing to the support polygon.
const MIN_AREA_FRACTION: f32 = 1.0e-3;

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

    fn contact(x: f32, y: f32, separation: f32, id: u32) -> ContactPoint {
        ContactPoint {
            position: Vec3::new(x, y, 0.0),
            separation,
            id,
        }
    }

    #[test]
    fn degenerate_candidates_do_not_panic() {
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
}
