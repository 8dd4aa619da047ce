//! Acceptance tests of the narrow phase, pair by pair: every unordered pair of sphere, box,
//! capsule, cylinder, convex hull and halfspace (the halfspace only as A, normal +Y), and a
//! compound of a box and a sphere against a box and against a halfspace.
//!
//! Each scene puts A at the origin and B straight above it on the Y axis, both in their canonical
//! orientation, so the contact normal is exactly +Y and every contact point lies at the same
//! height, midway between A's top and B's bottom. The gaps are 0.5 m (beyond the margin: no
//! contact), 0.01 m (speculative), 0 (touching) and −0.05 m (overlap). The same scenes are then
//! moved as a whole by a fixed rotation and translation, which must move the normal and the points
//! with them and keep the separations.
//!
//! Tolerances (see [`EXACT`] and [`ITERATIVE`]) depend on how the pair is computed: in closed form,
//! by the plane test or by the separating-axis test, a result is a few dozen f32 operations on
//! coordinates below 6 m; by GJK/EPA, it is known to the algorithms' documented tolerance.

use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, TAU};

use rebond::internals::collision::narrow_phase::{collide, collide_convex};
use rebond::internals::collision::{Manifold, SPECULATIVE_DISTANCE};
use rebond::{CompoundChild, Pose, Quat, Shape, Vec3};

/// Closed forms, the plane test and the separating-axis test: every coordinate is below 6 m,
/// whose f32 spacing is 4.8e-7 m, and a result goes through a few dozen roundings (a rotation of
/// the scene, the shapes' frames, one or two dot products), so 1e-5 m (about 20 spacings) holds
/// them all with room to spare. Also the tolerance on normals, which are unit vectors rotated a
/// couple of times.
const EXACT: f32 = 1.0e-5;

/// GJK and EPA stop within `TOLERANCE · scale` of the answer (`gjk::TOLERANCE`, `epa::TOLERANCE`:
/// 1e-5 of the largest support point of A − B, below 3 m here, so 3e-5 m), and a witness point or
/// normal built from the final simplex adds rounding of the same order; 1e-4 m bounds both.
const ITERATIVE: f32 = 1.0e-4;

/// The four gaps of every scene: beyond the margin, within it, touching and overlapping.
const GAPS: [f32; 4] = [0.5, 0.01, 0.0, -0.05];

/// The shapes of the scenes, each about 1 m across.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Sphere,
    Box,
    Capsule,
    Cylinder,
    Hull,
    Halfspace,
}

const BOUNDED_KINDS: [Kind; 5] = [
    Kind::Sphere,
    Kind::Box,
    Kind::Capsule,
    Kind::Cylinder,
    Kind::Hull,
];

/// A hexagonal prism along Y: flat top and bottom faces, circumradius 0.5 m, height 0.7 m.
fn hexagonal_prism() -> Shape {
    let corners: Vec<Vec3> = (0..12)
        .map(|index| {
            let angle = TAU * (index % 6) as f32 / 6.0;
            let y = if index < 6 { -0.35 } else { 0.35 };
            Vec3::new(0.5 * angle.cos(), y, 0.5 * angle.sin())
        })
        .collect();
    Shape::convex_hull(&corners).expect("a hexagonal prism")
}

fn shape(kind: Kind) -> Shape {
    match kind {
        Kind::Sphere => Shape::sphere(0.5),
        Kind::Box => Shape::cuboid(Vec3::new(0.6, 0.4, 0.5)),
        Kind::Capsule => Shape::capsule(0.3, 0.4),
        Kind::Cylinder => Shape::cylinder(0.5, 0.4),
        Kind::Hull => Ok(hexagonal_prism()),
        Kind::Halfspace => Shape::halfspace(Vec3::Y),
    }
    .expect("valid shape")
}

/// Whether the narrow phase solves the pair with GJK/EPA (every pair with a cylinder, a capsule
/// against a polyhedron, a sphere against a hull), rather than exactly.
fn iterative(a: Kind, b: Kind) -> bool {
    let exact = |a: Kind, b: Kind| {
        matches!(
            (a, b),
            (Kind::Halfspace, _)
                | (Kind::Sphere, Kind::Sphere | Kind::Capsule | Kind::Box)
                | (Kind::Capsule, Kind::Capsule)
                | (Kind::Box | Kind::Hull, Kind::Box | Kind::Hull)
        )
    };
    !exact(a, b) && !exact(b, a)
}

fn tolerance(a: Kind, b: Kind) -> f32 {
    if iterative(a, b) {
        ITERATIVE
    } else {
        EXACT
    }
}

/// Height of a shape's highest point above its origin (0 for the halfspace's plane).
fn top(shape: &Shape) -> f32 {
    shape.support(Vec3::Y).map_or(0.0, |point| point.y)
}

/// Depth of a shape's lowest point below its origin.
fn bottom(shape: &Shape) -> f32 {
    -shape.support(Vec3::NEG_Y).map_or(0.0, |point| point.y)
}

/// The fixed motion applied to a whole scene in the moved variants.
fn moved_scene() -> Pose {
    Pose::new(
        Vec3::new(3.0, -1.5, 2.0),
        Quat::from_axis_angle(Vec3::new(1.0, 2.0, -3.0).normalize(), 0.7),
    )
}

/// The identity and [`moved_scene`]: each scene is checked in both.
fn scene_placements() -> [Pose; 2] {
    [Pose::IDENTITY, moved_scene()]
}

/// Depth of a shape's lowest point below its origin once turned by `orientation`.
fn lowest_when_turned(shape: &Shape, orientation: Quat) -> f32 {
    let lowest = shape
        .support(orientation.inverse() * Vec3::NEG_Y)
        .expect("bounded shape");
    -(orientation * lowest).y
}

/// B's pose above A (at the origin) so that B's lowest point is `gap` above A's highest.
fn stacked(shape_a: &Shape, shape_b: &Shape, gap: f32) -> Pose {
    Pose::from_position(Vec3::new(0.0, top(shape_a) + bottom(shape_b) + gap, 0.0))
}

/// How many points a scene must give.
#[derive(Debug, Clone, Copy)]
enum PointCount {
    Exactly(usize),
    AtLeast(usize),
}

impl PointCount {
    fn check(self, manifold: &Manifold, context: &str) {
        let ok = match self {
            PointCount::Exactly(count) => manifold.len() == count,
            PointCount::AtLeast(count) => manifold.len() >= count,
        };
        assert!(ok, "{context}: expected {self:?} points, got {manifold:?}");
    }
}

/// Points in the canonical scenes: one where a rounded end or a sphere touches; a face resting on
/// a face gives four (more candidates are reduced to four); a cylinder's cap, clipped as a
/// polygon, at least three.
fn canonical_count(a: Kind, b: Kind) -> PointCount {
    let flat_bottom_or_top = |kind: Kind| matches!(kind, Kind::Box | Kind::Hull | Kind::Halfspace);
    match (a, b) {
        (Kind::Sphere | Kind::Capsule, _) | (_, Kind::Sphere | Kind::Capsule) => {
            PointCount::Exactly(1)
        }
        (Kind::Cylinder, _) | (_, Kind::Cylinder) => PointCount::AtLeast(3),
        _ if flat_bottom_or_top(a) && flat_bottom_or_top(b) => PointCount::Exactly(4),
        _ => unreachable!("every pair is listed"),
    }
}

/// Whether `point` (scene frame) lies in the horizontal cross-section of `shape` placed upright at
/// the scene's Y axis: on the axis itself for a sphere or a capsule, whose rounded end touches at a
/// single point; inside the flat face's outline for the others (a prism along Y: box, cylinder,
/// hexagonal prism), tested against the support function along 64 horizontal directions.
fn within_footprint(shape: &Shape, point: Vec3, tolerance: f32) -> bool {
    match shape {
        Shape::Halfspace(_) => true,
        Shape::Sphere(_) | Shape::Capsule(_) => {
            Vec3::new(point.x, 0.0, point.z).length() <= tolerance
        }
        _ => (0..64).all(|index| {
            let angle = TAU * index as f32 / 64.0;
            let direction = Vec3::new(angle.cos(), 0.0, angle.sin());
            let reach = shape
                .support(direction)
                .map_or(0.0, |far| far.dot(direction));
            point.dot(direction) <= reach + tolerance
        }),
    }
}

/// A canonical scene: `below` upright at the origin, `above` upright over it with its axis at the
/// horizontal offset `above_axis`, its lowest point `gap` above the highest point of `below`; the
/// whole moved by `placement`.
struct Stack<'a> {
    below: &'a Shape,
    above: &'a Shape,
    above_axis: Vec3,
    gap: f32,
    placement: Pose,
}

/// Checks a manifold of a stack: normal `placement · Y` (or its opposite when `flipped`, for the
/// manifold of the swapped pair), every separation `gap`, every point at the height midway between
/// the surfaces and inside both shapes' outlines.
fn check_stacked_manifold(
    manifold: &Manifold,
    stack: &Stack,
    flipped: bool,
    tolerance: f32,
    context: &str,
) {
    let up = stack.placement.transform_vector(Vec3::Y);
    let expected_normal = if flipped { -up } else { up };
    assert!(
        (manifold.normal - expected_normal).length() <= tolerance.max(EXACT),
        "{context}: normal {} expected {expected_normal}",
        manifold.normal
    );
    let contact_height = top(stack.below) + 0.5 * stack.gap;
    for point in manifold.points() {
        assert!(
            (point.separation - stack.gap).abs() <= tolerance,
            "{context}: separation {} expected {} ({manifold:?})",
            point.separation,
            stack.gap
        );
        let local = stack.placement.inverse_transform_point(point.position);
        assert!(
            (local.y - contact_height).abs() <= tolerance,
            "{context}: point {local} (scene frame) not at height {contact_height}"
        );
        assert!(
            within_footprint(stack.below, local, tolerance)
                && within_footprint(stack.above, local - stack.above_axis, tolerance),
            "{context}: point {local} (scene frame) outside the contact patch"
        );
    }
}

fn ids(manifold: &Manifold) -> Vec<u32> {
    let mut ids: Vec<u32> = manifold.points().iter().map(|point| point.id).collect();
    ids.sort_unstable();
    ids
}

/// Runs the four gaps of the pair (A below, B above) in both placements, and each with A and B
/// swapped unless A is the halfspace.
fn check_pair(a: Kind, b: Kind) {
    let (shape_a, shape_b) = (shape(a), shape(b));
    let tolerance = tolerance(a, b);
    for placement in scene_placements() {
        for gap in GAPS {
            let pose_a = placement;
            let pose_b = placement.mul_pose(&stacked(&shape_a, &shape_b, gap));
            let context = format!("{a:?} below {b:?}, gap {gap}, placement {placement:?}");
            let manifold =
                collide_convex(&shape_a, &pose_a, &shape_b, &pose_b, SPECULATIVE_DISTANCE);
            let swapped = (a != Kind::Halfspace).then(|| {
                collide_convex(&shape_b, &pose_b, &shape_a, &pose_a, SPECULATIVE_DISTANCE)
            });
            if gap > SPECULATIVE_DISTANCE {
                assert!(manifold.is_none(), "{context}: {manifold:?}");
                assert!(swapped.flatten().is_none(), "{context}, swapped");
                continue;
            }
            let manifold = manifold.unwrap_or_else(|| panic!("{context}: no contact"));
            let stack = Stack {
                below: &shape_a,
                above: &shape_b,
                above_axis: Vec3::ZERO,
                gap,
                placement,
            };
            check_stacked_manifold(&manifold, &stack, false, tolerance, &context);
            canonical_count(a, b).check(&manifold, &context);
            assert_unique_ids(&manifold, &context);
            if let Some(swapped) = swapped {
                let context = format!("{context}, swapped");
                let swapped = swapped.unwrap_or_else(|| panic!("{context}: no contact"));
                check_stacked_manifold(&swapped, &stack, true, tolerance, &context);
                assert_eq!(swapped.len(), manifold.len(), "{context}: {swapped:?}");
            }
        }
    }
}

fn assert_unique_ids(manifold: &Manifold, context: &str) {
    let mut unique = ids(manifold);
    unique.dedup();
    assert_eq!(
        unique.len(),
        manifold.len(),
        "{context}: ids repeat in {manifold:?}"
    );
}

/// The bounding radius the narrow phase rejects pairs with is each shape's farthest point from its
/// origin: the sphere's radius, the box's half diagonal, the capsule's half height plus radius,
/// the cylinder's rim corner, the prism's corner (circumradius 0.5 m, half height 0.35 m).
#[test]
fn bounding_radii_reach_the_farthest_point() {
    let expected = [
        (Kind::Sphere, 0.5),
        (Kind::Box, Vec3::new(0.6, 0.4, 0.5).length()),
        (Kind::Capsule, 0.7),
        (Kind::Cylinder, 0.5f32.hypot(0.4)),
        (Kind::Hull, 0.5f32.hypot(0.35)),
    ];
    for (kind, radius) in expected {
        let found = shape(kind).bounding_radius();
        assert!(
            (found - radius).abs() <= EXACT,
            "{kind:?}: {found} against {radius}"
        );
    }
    assert_eq!(shape(Kind::Halfspace).bounding_radius(), f32::INFINITY);
}

#[test]
fn every_pair_separated_speculative_touching_and_overlapping() {
    for (index, &a) in BOUNDED_KINDS.iter().enumerate() {
        for &b in &BOUNDED_KINDS[index..] {
            check_pair(a, b);
        }
    }
}

#[test]
fn halfspace_against_every_shape() {
    for b in BOUNDED_KINDS {
        check_pair(Kind::Halfspace, b);
    }
}

/// A box of half extents (0.5, 0.3, 0.5) at the body origin and a ball of radius 0.3 beside it,
/// centred at (0.9, 0, 0): both bottoms at y = −0.3, so both rest on the ground together.
fn box_and_ball() -> Shape {
    Shape::compound(vec![
        CompoundChild::new(
            Shape::cuboid(Vec3::new(0.5, 0.3, 0.5)).expect("box"),
            Pose::IDENTITY,
        ),
        CompoundChild::new(
            Shape::sphere(0.3).expect("ball"),
            Pose::from_position(Vec3::new(0.9, 0.0, 0.0)),
        ),
    ])
    .expect("compound")
}

/// Every `(child_a, child_b, manifold)` between two shapes.
fn all_manifolds(
    shape_a: &Shape,
    pose_a: &Pose,
    shape_b: &Shape,
    pose_b: &Pose,
) -> Vec<(u32, u32, Manifold)> {
    let mut manifolds = Vec::new();
    collide(
        shape_a,
        pose_a,
        shape_b,
        pose_b,
        SPECULATIVE_DISTANCE,
        |child_a, child_b, manifold| {
            manifolds.push((child_a, child_b, manifold));
        },
    );
    manifolds
}

/// The compound resting on `ground` (a wide box or the halfspace): one manifold per child, the box
/// child on four points and the ball on one, all at the scene's gap; with the compound as A (not
/// for the halfspace, which is only A), the same manifolds flipped.
fn check_compound_on(ground: &Shape) {
    let compound = box_and_ball();
    let Shape::Compound(parts) = &compound else {
        unreachable!("box_and_ball is a compound");
    };
    let children = parts.children();
    for placement in scene_placements() {
        for gap in GAPS {
            let pose_ground = placement;
            let pose_compound = placement.mul_pose(&Pose::from_position(Vec3::new(
                0.0,
                top(ground) + 0.3 + gap,
                0.0,
            )));
            let context = format!("compound on {ground:?}, gap {gap}, placement {placement:?}");
            let below = all_manifolds(ground, &pose_ground, &compound, &pose_compound);
            let above = ground
                .is_bounded()
                .then(|| all_manifolds(&compound, &pose_compound, ground, &pose_ground));
            if gap > SPECULATIVE_DISTANCE {
                assert!(below.is_empty(), "{context}: {below:?}");
                assert!(
                    above.is_none_or(|above| above.is_empty()),
                    "{context}, compound as A"
                );
                continue;
            }
            let children_b: Vec<u32> = below
                .iter()
                .map(|(child_a, child_b, _)| {
                    assert_eq!(*child_a, 0);
                    *child_b
                })
                .collect();
            assert_eq!(children_b, [0, 1], "{context}");
            for ((_, child, manifold), count) in below.iter().zip([4, 1]) {
                let CompoundChild { pose, shape, .. } = &children[*child as usize];
                let stack = Stack {
                    below: ground,
                    above: shape,
                    above_axis: pose.position,
                    gap,
                    placement,
                };
                let context = format!("{context}, child {child}");
                check_stacked_manifold(manifold, &stack, false, EXACT, &context);
                PointCount::Exactly(count).check(manifold, &context);
            }
            if let Some(above) = above {
                assert_eq!(above.len(), below.len(), "{context}, compound as A");
                for ((child_a, child_b, flipped), (_, child, manifold)) in above.iter().zip(&below)
                {
                    assert_eq!(
                        (*child_a, *child_b),
                        (*child, 0),
                        "{context}, compound as A"
                    );
                    assert!(
                        (flipped.normal + manifold.normal).length() <= EXACT,
                        "{context}, compound as A"
                    );
                    assert_same_points(flipped, manifold, EXACT, &context);
                }
            }
        }
    }
}

#[test]
fn compound_on_a_box_and_on_a_halfspace() {
    check_compound_on(&Shape::cuboid(Vec3::new(1.5, 0.5, 1.0)).expect("ground box"));
    check_compound_on(&Shape::halfspace(Vec3::Y).expect("ground plane"));
}

/// Whether two manifolds have the same points (in any order): same positions and separations.
fn assert_same_points(left: &Manifold, right: &Manifold, tolerance: f32, context: &str) {
    assert_eq!(left.len(), right.len(), "{context}: {left:?} vs {right:?}");
    for point in left.points() {
        assert!(
            right.points().iter().any(|other| {
                (other.position - point.position).length() <= tolerance
                    && (other.separation - point.separation).abs() <= tolerance
            }),
            "{context}: {point:?} has no match in {right:?}"
        );
    }
}

/// Depth of the resting scenes below.
const RESTING_GAP: f32 = -0.05;

/// The box every resting scene below lies on, its top face at y = 0.4.
fn ground_box() -> Shape {
    Shape::cuboid(Vec3::new(1.0, 0.4, 1.0)).expect("ground box")
}

/// B in `orientation` resting on [`ground_box`] at [`RESTING_GAP`], its axis at x = 0.1, z = −0.05,
/// in both placements: each placement with its manifold.
fn resting_on_ground(shape_b: &Shape, orientation: Quat) -> Vec<(Pose, Manifold)> {
    let ground = ground_box();
    let height = top(&ground) + lowest_when_turned(shape_b, orientation) + RESTING_GAP;
    let local_b = Pose::new(Vec3::new(0.1, height, -0.05), orientation);
    scene_placements()
        .into_iter()
        .map(|placement| {
            let manifold = collide_convex(
                &ground,
                &placement,
                shape_b,
                &placement.mul_pose(&local_b),
                SPECULATIVE_DISTANCE,
            )
            .unwrap_or_else(|| panic!("{shape_b:?} on the ground box: no contact"));
            (placement, manifold)
        })
        .collect()
}

/// Checks the normal (up in the scene), the count, and that every point is at the resting depth,
/// midway between the surfaces, and returns the scene-frame positions.
fn check_resting(
    shape_b: &Shape,
    orientation: Quat,
    count: PointCount,
    tolerance: f32,
) -> Vec<Vec<Vec3>> {
    let top_height = top(&ground_box());
    resting_on_ground(shape_b, orientation)
        .into_iter()
        .map(|(placement, manifold)| {
            let context = format!("{shape_b:?} at {orientation} on a box, placement {placement:?}");
            count.check(&manifold, &context);
            let up = placement.transform_vector(Vec3::Y);
            assert!(
                (manifold.normal - up).length() <= tolerance,
                "{context}: normal {}",
                manifold.normal
            );
            manifold
                .points()
                .iter()
                .map(|point| {
                    assert!(
                        (point.separation - RESTING_GAP).abs() <= tolerance,
                        "{context}: separation {}",
                        point.separation
                    );
                    let local = placement.inverse_transform_point(point.position);
                    assert!(
                        (local.y - (top_height + 0.5 * RESTING_GAP)).abs() <= tolerance,
                        "{context}: {local}"
                    );
                    local
                })
                .collect()
        })
        .collect()
}

#[test]
fn box_flat_on_a_box_rests_on_its_four_corners() {
    let block = Shape::cuboid(Vec3::new(0.3, 0.2, 0.25)).expect("box");
    for corners in check_resting(&block, Quat::IDENTITY, PointCount::Exactly(4), EXACT) {
        for corner in corners {
            let offset = corner - Vec3::new(0.1, 0.0, -0.05);
            assert!(
                (offset.x.abs() - 0.3).abs() <= EXACT && (offset.z.abs() - 0.25).abs() <= EXACT,
                "{corner}"
            );
        }
    }
}

#[test]
fn box_on_its_edge_rests_on_two_points() {
    let block = Shape::cuboid(Vec3::splat(0.3)).expect("box");
    for ends in check_resting(
        &block,
        Quat::from_rotation_z(FRAC_PI_4),
        PointCount::Exactly(2),
        EXACT,
    ) {
        for end in ends {
            assert!(
                (end.x - 0.1).abs() <= EXACT && ((end.z + 0.05).abs() - 0.3).abs() <= EXACT,
                "{end}"
            );
        }
    }
}

#[test]
fn capsule_lying_on_a_box_rests_on_two_points() {
    let capsule = shape(Kind::Capsule);
    for ends in check_resting(
        &capsule,
        Quat::from_rotation_z(FRAC_PI_2),
        PointCount::Exactly(2),
        ITERATIVE,
    ) {
        let mut along: Vec<f32> = ends.iter().map(|end| end.x - 0.1).collect();
        along.sort_by(f32::total_cmp);
        assert!(
            (along[0] + 0.4).abs() <= ITERATIVE && (along[1] - 0.4).abs() <= ITERATIVE,
            "{ends:?}"
        );
    }
}

#[test]
fn cylinder_lying_on_a_box_rests_on_its_side() {
    let cylinder = shape(Kind::Cylinder);
    for line in check_resting(
        &cylinder,
        Quat::from_rotation_x(FRAC_PI_2),
        PointCount::AtLeast(2),
        ITERATIVE,
    ) {
        let span = line
            .iter()
            .map(|point| point.z)
            .fold(f32::NEG_INFINITY, f32::max)
            - line
                .iter()
                .map(|point| point.z)
                .fold(f32::INFINITY, f32::min);
        assert!((span - 0.8).abs() <= ITERATIVE, "{line:?}");
        for point in line {
            assert!((point.x - 0.1).abs() <= ITERATIVE, "{point}");
        }
    }
}

#[test]
fn cylinder_standing_on_a_box_rests_on_its_cap() {
    let cylinder = shape(Kind::Cylinder);
    for rim in check_resting(&cylinder, Quat::IDENTITY, PointCount::AtLeast(3), ITERATIVE) {
        for point in rim {
            let radial = Vec3::new(point.x - 0.1, 0.0, point.z + 0.05).length();
            assert!(
                (radial - 0.5).abs() <= ITERATIVE,
                "{point} is not on the rim"
            );
        }
    }
}

/// The small motions B makes between two steps while resting: 1 mm, 0.5°, and both.
fn nudges() -> [Pose; 4] {
    let turn = 0.5_f32.to_radians();
    [
        Pose::from_position(Vec3::new(0.6e-3, 0.0, 0.8e-3)),
        Pose::from_position(Vec3::new(0.0, -1.0e-3, 0.0)),
        Pose::new(
            Vec3::ZERO,
            Quat::from_axis_angle(Vec3::new(1.0, 0.0, 1.0).normalize(), turn),
        ),
        Pose::new(
            Vec3::new(-0.48e-3, 0.6e-3, 0.64e-3),
            Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalize(), turn),
        ),
    ]
}

/// B resting on A at 1 cm depth keeps the same set of point ids after each nudge (B moved about
/// its own centre), in both placements.
fn check_ids_hold_still(shape_a: &Shape, shape_b: &Shape, orientation_b: Quat) {
    let height = top(shape_a) + lowest_when_turned(shape_b, orientation_b) - 0.01;
    let local_b = Pose::new(Vec3::new(0.05, height, 0.02), orientation_b);
    for placement in scene_placements() {
        let pose_b = placement.mul_pose(&local_b);
        let context =
            format!("{shape_b:?} at {orientation_b} on {shape_a:?}, placement {placement:?}");
        let resting = collide_convex(shape_a, &placement, shape_b, &pose_b, SPECULATIVE_DISTANCE)
            .unwrap_or_else(|| panic!("{context}: no contact"));
        for nudge in nudges() {
            let nudged_b = Pose::new(
                pose_b.position + placement.transform_vector(nudge.position),
                (placement.rotation
                    * nudge.rotation
                    * placement.rotation.inverse()
                    * pose_b.rotation)
                    .normalize(),
            );
            let nudged = collide_convex(
                shape_a,
                &placement,
                shape_b,
                &nudged_b,
                SPECULATIVE_DISTANCE,
            )
            .unwrap_or_else(|| panic!("{context}, nudged by {nudge:?}: no contact"));
            assert_eq!(
                ids(&nudged),
                ids(&resting),
                "{context}, nudged by {nudge:?}:\n{resting:?}\n{nudged:?}"
            );
        }
    }
}

#[test]
fn box_on_a_box_keeps_its_ids() {
    let block = Shape::cuboid(Vec3::new(0.3, 0.2, 0.25)).expect("box");
    check_ids_hold_still(&ground_box(), &block, Quat::IDENTITY);
    check_ids_hold_still(&ground_box(), &block, Quat::from_rotation_z(FRAC_PI_4));
}

#[test]
fn box_on_a_hull_keeps_its_ids() {
    let block = Shape::cuboid(Vec3::new(0.3, 0.2, 0.25)).expect("box");
    check_ids_hold_still(&shape(Kind::Hull), &block, Quat::IDENTITY);
}

/// The hexagonal face gives six points, which `reduction::reduce_contacts_on_face` cuts to four by
/// their place on the face, not by their depth, which a 0.5° tilt changes.
#[test]
fn hull_on_a_box_keeps_its_ids() {
    check_ids_hold_still(&ground_box(), &shape(Kind::Hull), Quat::IDENTITY);
}

#[test]
fn capsule_on_a_box_keeps_its_ids() {
    check_ids_hold_still(
        &ground_box(),
        &shape(Kind::Capsule),
        Quat::from_rotation_z(FRAC_PI_2),
    );
}

#[test]
fn standing_cylinder_on_a_box_keeps_its_ids() {
    check_ids_hold_still(&ground_box(), &shape(Kind::Cylinder), Quat::IDENTITY);
}

#[test]
fn lying_cylinder_on_a_box_keeps_its_ids() {
    check_ids_hold_still(
        &ground_box(),
        &shape(Kind::Cylinder),
        Quat::from_rotation_x(FRAC_PI_2),
    );
}

#[test]
fn box_on_a_halfspace_keeps_its_ids() {
    let block = Shape::cuboid(Vec3::new(0.3, 0.2, 0.25)).expect("box");
    check_ids_hold_still(&shape(Kind::Halfspace), &block, Quat::IDENTITY);
}

#[test]
fn standing_cylinder_on_a_halfspace_keeps_its_ids() {
    check_ids_hold_still(
        &shape(Kind::Halfspace),
        &shape(Kind::Cylinder),
        Quat::IDENTITY,
    );
}

#[test]
fn lying_cylinder_on_a_halfspace_keeps_its_ids() {
    check_ids_hold_still(
        &shape(Kind::Halfspace),
        &shape(Kind::Cylinder),
        Quat::from_rotation_x(FRAC_PI_2),
    );
}

#[test]
fn box_on_a_standing_cylinder_keeps_its_ids() {
    let block = Shape::cuboid(Vec3::new(0.3, 0.2, 0.25)).expect("box");
    check_ids_hold_still(&shape(Kind::Cylinder), &block, Quat::IDENTITY);
}
