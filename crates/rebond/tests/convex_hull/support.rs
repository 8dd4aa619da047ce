//! Support points and bounding radii against a plain scan of the vertices.

use super::*;

#[test]
fn support_breaks_ties_by_lowest_index() {
    let hull = ConvexHull::new(&box_corners(Vec3::ONE)).unwrap();
    for direction in [Vec3::X, -Vec3::Y, Vec3::Z, Vec3::ZERO] {
        let best = hull
            .vertices()
            .iter()
            .map(|v| v.dot(direction))
            .fold(f32::NEG_INFINITY, f32::max);
        let first = hull
            .vertices()
            .iter()
            .find(|v| v.dot(direction) == best)
            .unwrap();
        assert_eq!(hull.support(direction), *first);
    }
    assert_eq!(hull.support(Vec3::NAN), hull.vertices()[0]);
    assert_eq!(hull.support(Vec3::new(1.0, 1.0, 1.0)), Vec3::ONE);
}

/// The support point is the vertex of largest `vertex · direction`, the lowest index on ties (a
/// direction along a face normal of a cube ties four corners) and vertex 0 for a NaN direction,
/// exactly as a plain scan finds it; the bounding radius is the farthest vertex's distance.
#[test]
fn support_and_bounding_radius_match_a_plain_scan() {
    let scan = |hull: &ConvexHull, direction: Vec3| {
        let dots = hull.vertices().iter().map(|vertex| vertex.dot(direction));
        let farthest = dots.clone().fold(f32::NEG_INFINITY, f32::max);
        dots.zip(hull.vertices())
            .find(|(dot, _)| *dot == farthest)
            .map_or(hull.vertices()[0], |(_, vertex)| *vertex)
    };
    let mut rng = Rng(7);
    let cube = ConvexHull::new(&box_corners(Vec3::ONE)).unwrap();
    let mut hulls = vec![cube];
    for count in [4, 5, 9, 14, 40] {
        let points: Vec<Vec3> = (0..count).map(|_| rng.in_ball(1.5)).collect();
        if let Ok(hull) = ConvexHull::new(&points) {
            hulls.push(hull);
        }
    }
    for hull in &hulls {
        let axes = [Vec3::X, Vec3::NEG_Y, Vec3::Z, Vec3::ONE];
        let random = (0..200).map(|_| rng.on_sphere());
        for direction in axes.into_iter().chain(random) {
            assert_eq!(
                hull.support(direction),
                scan(hull, direction),
                "{direction}"
            );
        }
        assert_eq!(hull.support(Vec3::NAN), hull.vertices()[0]);
        let farthest = hull.vertices().iter().map(|vertex| vertex.length());
        assert_eq!(hull.bounding_radius(), farthest.fold(0.0, f32::max));
    }
}
