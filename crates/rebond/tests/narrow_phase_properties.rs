//! Property tests of the narrow phase over random shapes and poses, for every pair of sphere, box,
//! capsule, cylinder and convex hull.
//!
//! Each case places B near A: along a random direction `d` (or a world axis, with shapes turned by
//! quarter turns, so that faces rest flat on faces), B's extent begins `gap` beyond A's, with
//! `gap` between −0.3 m and +0.05 m, and B is shifted sideways by up to 0.25 m. When
//! `collide_convex` returns a manifold:
//!
//! - the normal is a unit vector;
//! - swapping A and B gives the opposite normal and the same deepest separation;
//! - every point with separation `s` lies within `|s|/2` (plus the tolerances below) of both
//!   shapes, measured by an exact point-to-shape distance written here for each kind of shape;
//! - the deepest separation agrees with the signed distance σ between the shapes (the distance
//!   when they are apart, minus the penetration depth when they overlap). σ is estimated
//!   independently of the narrow phase, from below, as the largest gap between the shapes' extents
//!   over many directions (for convex shapes the largest gap is σ), and bounded from above, for
//!   shapes apart, by the distance between GJK's witness points.
//!
//! When it returns `None`, σ exceeds the margin.
//!
//! The separating-axis routine (boxes and hulls) biases its choice of axis for stability, which
//! [`separating_axis_floor`] allows for.

#[path = "common/spiral.rs"]
mod spiral;

use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use rebond::internals::collision::narrow_phase::collide_convex;
use rebond::internals::collision::{gjk, PosedCore, SupportMap, SPECULATIVE_DISTANCE};
use rebond::shape::ConvexHull;
use rebond::{Pose, Quat, Shape, Vec3};
use spiral::spiral_directions;
use std::f32::consts::{FRAC_PI_2, PI};

/// Slack of every comparison made at the scale of the scenes (shapes up to 2 m across, poses within
/// 2 m of the origin, so coordinates below 6 m): 1e-4 m holds the f32 rounding of a few dozen
/// operations on such coordinates (1e-5 m) and the tolerance of GJK and EPA, which stop within
/// 1e-5 of the largest support point of A − B (below 8 m here: 8e-5 m).
const TOLERANCE: f32 = 1.0e-4;

/// Unit normals: one f32 normalisation after a handful of rotations.
const UNIT_TOLERANCE: f32 = 1.0e-4;

/// The slack of a feature contact (GJK/EPA, then clipping against a face): its points may fall
/// short of the deepest spot by up to 1 mm before the GJK/EPA point joins them
/// (`feature_contact::DUPLICATE_DISTANCE`, measured against GJK/EPA's own depth, itself within
/// [`TOLERANCE`]), and a point clipped under a face up to 11° off the contact normal, near the
/// face's rim, has its depth capped at the GJK/EPA depth, which moves it off the midpoint between
/// the surfaces by half the cut (below 1 mm in all the cases seen).
const FEATURE_SLACK: f32 = 1.0e-3 + TOLERANCE;

/// How far apart the normals of a pair and of its swap may be. The separating-axis and closed-form
/// routines agree to rounding; GJK/EPA stops once the depth is known within 1e-5 of the problem's
/// scale `L`, and near a curved contact (radius `R`) the depth varies with the normal's angle `θ`
/// as `R θ²/2`, so each normal is known within `√(2·1e-5·L/R)`: 0.02 for `L/R` up to 20 (shapes of
/// 0.1 m in scenes of 2 m), twice that for the two normals compared.
const SWAPPED_NORMAL_TOLERANCE: f32 = 0.04;

/// The separating-axis routine keeps B's best face only when it beats A's by 5 % (of A's
/// separation, in absolute value) plus 0.5 mm, and an edge pair only when it beats the kept face
/// by 10 % plus 0.5 mm (`polyhedron::collide_polyhedra`). So, when the shapes overlap, the kept
/// axis's separation `s` satisfies `s ≥ σ − 0.1 |s| − 0.5 mm`, that is `s ≥ (σ − 0.5 mm) / 0.9`,
/// and the deepest clipped point is no deeper than `s`.
fn separating_axis_floor(signed_distance: f32) -> f32 {
    (signed_distance - 5.0e-4) / 0.9
}

/// The kinds of bounded convex shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Sphere,
    Box,
    Capsule,
    Cylinder,
    Hull,
}

/// Which routine the narrow phase runs for a pair, which sets how exact its answer is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Routine {
    /// Sphere/sphere, sphere/capsule, capsule/capsule, sphere/box: exact to rounding.
    ClosedForm,
    /// Boxes and hulls: the separating-axis test, whose chosen axis trails the axis of least
    /// overlap by its documented bias (`polyhedron::collide_polyhedra`).
    SeparatingAxes,
    /// Everything else: GJK/EPA, then the supporting features clipped against each other.
    Features,
}

fn routine(a: Kind, b: Kind) -> Routine {
    let closed_form = |a: Kind, b: Kind| {
        matches!(
            (a, b),
            (Kind::Sphere, Kind::Sphere | Kind::Capsule | Kind::Box)
                | (Kind::Capsule, Kind::Capsule)
        )
    };
    let polyhedron = |kind: Kind| matches!(kind, Kind::Box | Kind::Hull);
    if closed_form(a, b) || closed_form(b, a) {
        Routine::ClosedForm
    } else if polyhedron(a) && polyhedron(b) {
        Routine::SeparatingAxes
    } else {
        Routine::Features
    }
}

/// A number drawn uniformly from `[low, high)`, from 32 random bits. (Proptest's own `f32` range
/// sampler trips its debug assertion `self.low - result < initial.step` on some seeds.)
fn uniform(low: f32, high: f32) -> impl Strategy<Value = f32> + Clone {
    any::<u32>().prop_map(move |bits| {
        let fraction = f64::from(bits) / 4_294_967_296.0;
        (f64::from(low) + f64::from(high - low) * fraction) as f32
    })
}

/// A vector with each coordinate drawn uniformly from `[low, high)`.
fn uniform_vector(low: f32, high: f32) -> impl Strategy<Value = Vec3> + Clone {
    (uniform(low, high), uniform(low, high), uniform(low, high))
        .prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// Random shapes of a kind, 0.2 m to 2 m across.
fn shapes(kind: Kind) -> BoxedStrategy<Shape> {
    let size = uniform(0.1, 1.0);
    match kind {
        Kind::Sphere => size
            .prop_map(|radius| Shape::sphere(radius).expect("valid sphere"))
            .boxed(),
        Kind::Box => uniform_vector(0.1, 1.0)
            .prop_map(|half_extents| Shape::cuboid(half_extents).expect("valid box"))
            .boxed(),
        Kind::Capsule => (uniform(0.1, 0.6), size)
            .prop_map(|(radius, half)| Shape::capsule(radius, half).expect("valid capsule"))
            .boxed(),
        Kind::Cylinder => (size.clone(), size)
            .prop_map(|(radius, half)| Shape::cylinder(radius, half).expect("valid cylinder"))
            .boxed(),
        Kind::Hull => (
            uniform_vector(0.2, 1.0),
            prop::collection::vec(uniform_vector(-1.0, 1.0), 6..16),
        )
            .prop_filter_map("a solid hull", |(scale, points)| {
                let points: Vec<Vec3> = points.into_iter().map(|point| point * scale).collect();
                ConvexHull::new(&points)
                    .ok()
                    .map(|hull| Shape::ConvexHull(hull.into()))
            })
            .boxed(),
    }
}

/// A random rotation (from a random rotation vector) or, for a fifth of the cases, a quarter turn
/// about a world axis, which lines faces up with the world axes.
fn rotations() -> impl Strategy<Value = Quat> {
    let free = uniform_vector(-PI, PI).prop_map(|turn| Quat::from_scaled_axis(turn).normalize());
    let aligned = (0usize..3, 0u32..4).prop_map(|(axis, turns)| {
        Quat::from_axis_angle(Vec3::AXES[axis], FRAC_PI_2 * turns as f32)
    });
    prop_oneof![4 => free, 1 => aligned]
}

/// A random unit direction or, for a fifth of the cases, a world axis.
fn directions() -> impl Strategy<Value = Vec3> {
    let free = uniform_vector(-1.0, 1.0).prop_filter_map("not too short", |vector| {
        (vector.length() > 0.1).then(|| vector.normalize())
    });
    let axis = (0usize..3, prop::bool::ANY).prop_map(|(axis, negative)| {
        if negative {
            -Vec3::AXES[axis]
        } else {
            Vec3::AXES[axis]
        }
    });
    prop_oneof![4 => free, 1 => axis]
}

/// A shape placed in the world.
#[derive(Debug, Clone)]
struct Solid {
    shape: Shape,
    pose: Pose,
}

impl SupportMap for Solid {
    fn support(&self, direction: Vec3) -> Vec3 {
        let local = self.pose.inverse_transform_vector(direction);
        let point = self.shape.support(local).expect("bounded shape");
        self.pose.transform_point(point)
    }
}

impl Solid {
    /// `max d·x` over the solid.
    fn extent(&self, direction: Vec3) -> f32 {
        self.support(direction).dot(direction)
    }

    fn core(&self) -> PosedCore<'_> {
        PosedCore {
            shape: &self.shape,
            pose: &self.pose,
        }
    }

    /// Euclidean distance from `point` to the solid (zero inside), in closed form for each kind.
    fn distance_to(&self, point: Vec3) -> f32 {
        let local = self.pose.inverse_transform_point(point);
        match &self.shape {
            Shape::Sphere(sphere) => (local.length() - sphere.radius()).max(0.0),
            Shape::Cuboid(cuboid) => (local.abs() - cuboid.half_extents())
                .max(Vec3::ZERO)
                .length(),
            Shape::Capsule(capsule) => {
                let half = capsule.half_height();
                let axis_point = Vec3::new(0.0, local.y.clamp(-half, half), 0.0);
                (local.distance(axis_point) - capsule.radius()).max(0.0)
            }
            Shape::Cylinder(cylinder) => {
                let radial = Vec3::new(local.x, 0.0, local.z).length() - cylinder.radius();
                let axial = local.y.abs() - cylinder.half_height();
                Vec3::new(radial.max(0.0), axial.max(0.0), 0.0).length()
            }
            Shape::ConvexHull(hull) => distance_to_hull(hull, local),
            Shape::Compound(_)
            | Shape::Halfspace(_)
            | Shape::TriMesh(_)
            | Shape::HeightField(_) => {
                unreachable!("not generated")
            }
        }
    }
}

/// Distance from `point` to a hull (zero inside): the distance to the nearest of its face
/// polygons, each fanned into triangles, when `point` lies outside some face plane.
fn distance_to_hull(hull: &ConvexHull, point: Vec3) -> f32 {
    let inside = hull
        .faces()
        .iter()
        .all(|face| face.normal.dot(point) <= face.offset);
    if inside {
        return 0.0;
    }
    let vertices = hull.vertices();
    hull.faces()
        .iter()
        .flat_map(|face| {
            let corner = |index: usize| vertices[face.vertices[index] as usize];
            (1..face.vertices.len() - 1).map(move |index| {
                distance_to_triangle(point, [corner(0), corner(index), corner(index + 1)])
            })
        })
        .fold(f32::INFINITY, f32::min)
}

/// Distance from `point` to a triangle: to its plane when the projection falls inside, else to
/// the nearest edge.
fn distance_to_triangle(point: Vec3, [a, b, c]: [Vec3; 3]) -> f32 {
    let normal = (b - a).cross(c - a);
    let inside = [(a, b), (b, c), (c, a)]
        .iter()
        .all(|&(from, to)| (to - from).cross(point - from).dot(normal) >= 0.0);
    if inside && normal.length_squared() > 0.0 {
        return (point - a).dot(normal).abs() / normal.length();
    }
    [(a, b), (b, c), (c, a)]
        .iter()
        .map(|&(from, to)| {
            let edge = to - from;
            let t = ((point - from).dot(edge) / edge.length_squared().max(f32::MIN_POSITIVE))
                .clamp(0.0, 1.0);
            point.distance(from + edge * t)
        })
        .fold(f32::INFINITY, f32::min)
}

/// How far B lies beyond A along unit `direction`: `min_B d·x − max_A d·x`.
fn gap(a: &Solid, b: &Solid, direction: Vec3) -> f32 {
    -b.extent(-direction) - a.extent(direction)
}

/// Climbs to a local maximum of the gap from `start`: tries steps of a given angle toward eight
/// tangent directions and moves on any gain; when none gains, turns the eight directions by the
/// golden angle (a ridge of the gap may run between them) and, after four turns without gain,
/// halves the step.
fn climb_gap(a: &Solid, b: &Solid, start: Vec3) -> f32 {
    let golden_angle = PI * (3.0 - 5.0f32.sqrt());
    let mut direction = start;
    let mut best = gap(a, b, direction);
    let mut step = 0.05f32;
    let mut twist = 0.0f32;
    let mut misses = 0;
    while step > 1.0e-6 {
        let base = direction.any_orthonormal_vector();
        let first = base * twist.cos() + direction.cross(base) * twist.sin();
        let second = direction.cross(first);
        let moves = [
            first,
            -first,
            second,
            -second,
            first + second,
            first - second,
            second - first,
            -first - second,
        ];
        let improved = moves.iter().find_map(|tangent| {
            let candidate = (direction + *tangent * step).normalize();
            let value = gap(a, b, candidate);
            (value > best).then_some((candidate, value))
        });
        match improved {
            Some((candidate, value)) => {
                (direction, best) = (candidate, value);
                misses = 0;
            }
            None => {
                twist += golden_angle;
                misses += 1;
                if misses == 4 {
                    step *= 0.5;
                    misses = 0;
                }
            }
        }
    }
    best
}

/// The signed distance between A and B (negative: minus the penetration depth), from below: the
/// largest gap over 600 spiral directions, the solids' own axes (face normals, and the cross
/// products of an edge direction of A with one of B: for two polyhedra these include the axis of
/// least overlap), and `hints`, then refined by climbing from the best five, from each hint and
/// from GJK's direction between the cores when they are apart (without it, climbs from sampled
/// directions can stop 0.1 mm short on a pair of boxes apart edge to edge). Every gap is a lower
/// bound; for convex solids the largest one is the signed distance.
fn signed_distance_from_below(a: &Solid, b: &Solid, hints: &[Vec3]) -> f32 {
    let (faces_a, edges_a) = axes(a);
    let (faces_b, edges_b) = axes(b);
    let crossed = edges_a.iter().flat_map(|edge_a| {
        edges_b
            .iter()
            .filter_map(move |edge_b| edge_a.cross(*edge_b).try_normalize())
    });
    let candidates: Vec<Vec3> = faces_a
        .into_iter()
        .chain(faces_b)
        .chain(crossed)
        .flat_map(|axis| [axis, -axis])
        .chain(spiral_directions(600))
        .collect();
    let mut sampled: Vec<(f32, Vec3)> = candidates
        .into_iter()
        .map(|direction| (gap(a, b, direction), direction))
        .collect();
    sampled.sort_by(|left, right| right.0.total_cmp(&left.0));
    sampled
        .iter()
        .take(5)
        .map(|&(_, direction)| direction)
        .chain(hints.iter().copied())
        .chain(gjk::distance(&a.core(), &b.core()).normal())
        .map(|direction| climb_gap(a, b, direction))
        .fold(f32::NEG_INFINITY, f32::max)
}

/// A solid's face normals and edge directions, world frame: a box's three axes as both; a hull's
/// faces and edges; a capsule's segment and a cylinder's axis (whose caps are faces and whose side
/// lines run along it); nothing for a sphere.
fn axes(solid: &Solid) -> (Vec<Vec3>, Vec<Vec3>) {
    let world = |vectors: Vec<Vec3>| -> Vec<Vec3> {
        vectors
            .into_iter()
            .map(|vector| solid.pose.transform_vector(vector))
            .collect()
    };
    let (faces, edges) = match &solid.shape {
        Shape::Cuboid(_) => (Vec3::AXES.to_vec(), Vec3::AXES.to_vec()),
        Shape::ConvexHull(hull) => {
            let vertices = hull.vertices();
            let faces = hull.faces().iter().map(|face| face.normal).collect();
            let edges = hull
                .edges()
                .iter()
                .map(|edge| {
                    vertices[edge.vertices[1] as usize] - vertices[edge.vertices[0] as usize]
                })
                .collect();
            (faces, edges)
        }
        Shape::Capsule(_) => (Vec::new(), vec![Vec3::Y]),
        Shape::Cylinder(_) => (vec![Vec3::Y], vec![Vec3::Y]),
        _ => (Vec::new(), Vec::new()),
    };
    (world(faces), world(edges))
}

/// The distance between A and B when GJK finds them apart: its witness points are convex
/// combinations of support points of the cores, so their distance, less the rounding radii,
/// bounds the distance from above.
fn distance_from_above(a: &Solid, b: &Solid) -> Option<f32> {
    let cores = gjk::distance(&a.core(), &b.core());
    (!cores.overlapping).then(|| {
        cores.point_a.distance(cores.point_b) - a.shape.core_radius() - b.shape.core_radius()
    })
}

/// A random scene: A at a random pose; B turned at random and placed so that its extent along
/// `direction` begins `gap` beyond A's, shifted sideways by up to 0.25 m.
fn scenes(kind_a: Kind, kind_b: Kind) -> impl Strategy<Value = (Solid, Solid)> {
    (
        shapes(kind_a),
        shapes(kind_b),
        uniform_vector(-2.0, 2.0),
        rotations(),
        rotations(),
        directions(),
        uniform(-0.3, 0.05),
        (uniform(-0.25, 0.25), uniform(-0.25, 0.25)),
    )
        .prop_map(
            |(shape_a, shape_b, position_a, rotation_a, rotation_b, direction, gap, (u, v))| {
                let a = Solid {
                    shape: shape_a,
                    pose: Pose::new(position_a, rotation_a),
                };
                let first = direction.any_orthonormal_vector();
                let sideways = first * u + direction.cross(first) * v;
                let unplaced = Solid {
                    shape: shape_b,
                    pose: Pose::new(Vec3::ZERO, rotation_b),
                };
                let along = a.extent(direction) + gap + unplaced.extent(-direction)
                    - direction.dot(a.pose.position + sideways);
                let b = Solid {
                    pose: Pose::new(a.pose.position + sideways + direction * along, rotation_b),
                    ..unplaced
                };
                (a, b)
            },
        )
}

/// Checks every property of one scene.
fn check_scene(kind_a: Kind, kind_b: Kind, a: &Solid, b: &Solid) -> Result<(), TestCaseError> {
    let margin = SPECULATIVE_DISTANCE;
    let routine = routine(kind_a, kind_b);
    let manifold = collide_convex(&a.shape, &a.pose, &b.shape, &b.pose, margin);
    let swapped = collide_convex(&b.shape, &b.pose, &a.shape, &a.pose, margin);
    let hints: Vec<Vec3> = manifold.iter().map(|manifold| manifold.normal).collect();
    let signed_distance = signed_distance_from_below(a, b, &hints);
    let apart = signed_distance > 0.0;
    let Some(manifold) = manifold else {
        prop_assert!(
            signed_distance > margin - TOLERANCE,
            "no contact, yet the signed distance is {signed_distance} m"
        );
        if let Some(swapped) = swapped {
            prop_assert!(
                swapped.deepest_separation() > margin - TOLERANCE,
                "only the swapped pair touches: {swapped:?}"
            );
        }
        return Ok(());
    };
    prop_assert!(
        (manifold.normal.length() - 1.0).abs() <= UNIT_TOLERANCE,
        "normal {}",
        manifold.normal
    );
    let deepest = manifold.deepest_separation();
    let slack = match routine {
        Routine::ClosedForm | Routine::SeparatingAxes => TOLERANCE,
        Routine::Features => FEATURE_SLACK + TOLERANCE,
    };
    if let Some(distance) = distance_from_above(a, b) {
        prop_assert!(
            deepest <= distance + slack,
            "deepest separation {deepest} beyond the distance {distance}\n{manifold:?}"
        );
    }
    for point in manifold.points() {
        let allowed = 0.5 * point.separation.abs() + slack;
        let (to_a, to_b) = (a.distance_to(point.position), b.distance_to(point.position));
        prop_assert!(
            to_a <= allowed && to_b <= allowed,
            "{point:?} lies {to_a} m from A and {to_b} m from B\n{manifold:?}"
        );
    }
    let floor = match routine {
        Routine::SeparatingAxes if !apart => separating_axis_floor(signed_distance),
        _ => signed_distance,
    };
    prop_assert!(
        deepest >= floor - TOLERANCE,
        "deepest separation {deepest} deeper than the shapes allow (signed distance at least \
         {signed_distance}, {routine:?})\n{manifold:?}"
    );
    prop_assert!(
        deepest <= signed_distance + slack,
        "deepest separation {deepest} short of the signed distance {signed_distance} \
         ({routine:?})\n{manifold:?}"
    );

    let Some(swapped) = swapped else {
        prop_assert!(
            deepest > margin - TOLERANCE,
            "the swapped pair does not touch"
        );
        return Ok(());
    };
    let swapped_deepest = swapped.deepest_separation();
    let flipped = (swapped.normal + manifold.normal).length();
    match routine {
        Routine::SeparatingAxes => {
            // Its bias toward A's faces may keep another axis once A and B trade places, when the
            // two are within the bias of each other: then each manifold is within the bias of σ.
            let floor = separating_axis_floor(signed_distance.min(0.0));
            prop_assert!(
                flipped <= UNIT_TOLERANCE
                    || (deepest >= floor - TOLERANCE && swapped_deepest >= floor - TOLERANCE),
                "swapped: normal {} and deepest separation {swapped_deepest}, for {} and \
                 {deepest}\n{manifold:?}\n{swapped:?}",
                swapped.normal,
                -manifold.normal
            );
        }
        Routine::ClosedForm | Routine::Features => {
            prop_assert!(
                flipped <= SWAPPED_NORMAL_TOLERANCE,
                "swapped: normal {} instead of {}",
                swapped.normal,
                -manifold.normal
            );
            prop_assert!(
                (swapped_deepest - deepest).abs() <= slack,
                "swapped: deepest separation {swapped_deepest} instead of {deepest}"
            );
        }
    }
    Ok(())
}

/// Cases per test: about 40 % of the scenes touch; the 15 pairs at this count run in a few
/// seconds.
const CASES: u32 = 1024;

/// The seed of every test's cases: each run checks the same scenes, so a failure is reproducible
/// and a passing run does not depend on luck. Another seed explores other scenes.
const SEED: u64 = 0x7265_626f_6e64;

/// A box pair a random run found, edge to edge, 4 µm beyond the speculative margin: no contact
/// is right. Climbing only from sampled directions, the signed distance came out 0.0198999 m,
/// 0.1 mm short of the distance and past the tolerance.
#[test]
fn a_box_pair_just_beyond_the_margin_gets_no_contact() {
    let solid = |half: [f32; 3], position: [f32; 3], rotation: [f32; 4]| Solid {
        shape: Shape::cuboid(Vec3::from_array(half)).unwrap(),
        pose: Pose::new(Vec3::from_array(position), Quat::from_array(rotation)),
    };
    let a = solid(
        [0.86799264, 0.18138078, 0.47163215],
        [-0.24394642, 0.6401286, 0.69612145],
        [0.33051303, 0.41376764, 0.39475563, -0.7508165],
    );
    let b = solid(
        [0.7597986, 0.76942015, 0.5288288],
        [0.9238077, 0.9141486, 1.9937879],
        [0.7621652, 0.4165244, -0.39195195, 0.30329084],
    );
    // A lower bound on the distance, beyond the margin.
    let distance = signed_distance_from_below(&a, &b, &[]);
    assert!(distance > SPECULATIVE_DISTANCE, "{distance}");
    assert!(collide_convex(&a.shape, &a.pose, &b.shape, &b.pose, SPECULATIVE_DISTANCE).is_none());
    check_scene(Kind::Box, Kind::Box, &a, &b).unwrap();
}

macro_rules! pair_properties {
    ($($name:ident: $a:expr, $b:expr;)*) => {
        proptest! {
            #![proptest_config(ProptestConfig {
                cases: CASES,
                failure_persistence: None,
                rng_seed: RngSeed::Fixed(SEED),
                ..ProptestConfig::default()
            })]
            $(
                #[test]
                fn $name((a, b) in scenes($a, $b)) {
                    check_scene($a, $b, &a, &b)?;
                }
            )*
        }
    };
}

pair_properties! {
    sphere_sphere: Kind::Sphere, Kind::Sphere;
    sphere_box: Kind::Sphere, Kind::Box;
    sphere_capsule: Kind::Sphere, Kind::Capsule;
    sphere_cylinder: Kind::Sphere, Kind::Cylinder;
    sphere_hull: Kind::Sphere, Kind::Hull;
    box_capsule: Kind::Box, Kind::Capsule;
    box_cylinder: Kind::Box, Kind::Cylinder;
    capsule_capsule: Kind::Capsule, Kind::Capsule;
    capsule_cylinder: Kind::Capsule, Kind::Cylinder;
    capsule_hull: Kind::Capsule, Kind::Hull;
    cylinder_cylinder: Kind::Cylinder, Kind::Cylinder;
    cylinder_hull: Kind::Cylinder, Kind::Hull;
    box_box: Kind::Box, Kind::Box;
    box_hull: Kind::Box, Kind::Hull;
    hull_hull: Kind::Hull, Kind::Hull;
}
