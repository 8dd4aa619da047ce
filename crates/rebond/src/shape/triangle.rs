//! One triangle of a mesh or heightfield, with which of its edges may produce edge contacts.
//!
//! A convex body sliding across the edge shared by two triangles of a flat or gently bent surface
//! must see one surface: its contact normal must not tilt toward the edge ("ghost collisions").
//! Each edge is therefore marked active or not, separately for the two sides of the triangle:
//! an edge is active on a side when the surface seen from that side is convex there and bent by
//! more than [`ACTIVE_EDGE_ANGLE`], or when the edge has no neighbour (a rim) or more than one.
//! Contacts on an inactive edge take the face normal instead (see `collision::triangle`); the
//! neighbour across a concave or flat edge holds the body on its own face.

use crate::math::Vec3;

/// An edge whose two triangles bend by less than this, radians (5°), never makes edge contacts:
/// a surface bent that little is treated as flat, and one bent more the other way (concave)
/// holds bodies with its faces. 5° is Jolt's default for the same test.
pub const ACTIVE_EDGE_ANGLE: f32 = 5.0 * std::f32::consts::PI / 180.0;

/// A triangle in some frame: three corners (counter-clockwise about its front normal) and its
/// edge flags: bit `k` says edge `k` (from corner `k` to corner `k + 1`) is active on the front
/// side, bit `k + 3` on the back side.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Triangle {
    /// The corners, metres.
    pub vertices: [Vec3; 3],
    /// Active edges, front in bits 0–2, back in bits 3–5.
    pub edge_flags: u8,
}

impl Triangle {
    /// The unit front normal `(b − a) × (c − a) / |…|`, or `None` for a triangle of zero area.
    pub fn normal(&self) -> Option<Vec3> {
        let [a, b, c] = self.vertices;
        (b - a).cross(c - a).try_normalize()
    }

    /// Whether edge `edge` is active on the front (`front`) or back side.
    pub fn edge_active(&self, edge: usize, front: bool) -> bool {
        let bit = if front { edge } else { edge + 3 };
        self.edge_flags & (1 << bit) != 0
    }

    /// The triangle's point closest to `point`, with its barycentric weights (one per corner).
    /// Zero weights say on which edge or corner the point lies: weight `k` zero puts it on the
    /// edge opposite corner `k`, that is edge `(k + 1) % 3`.
    pub fn closest_point(&self, point: Vec3) -> (Vec3, [f32; 3]) {
        // Voronoi regions of the corners, edges and face, in the order of Ericson's
        // "Real-Time Collision Detection", section 5.1.5.
        let [a, b, c] = self.vertices;
        let (ab, ac, ap) = (b - a, c - a, point - a);
        let (d1, d2) = (ab.dot(ap), ac.dot(ap));
        if d1 <= 0.0 && d2 <= 0.0 {
            return (a, [1.0, 0.0, 0.0]);
        }
        let bp = point - b;
        let (d3, d4) = (ab.dot(bp), ac.dot(bp));
        if d3 >= 0.0 && d4 <= d3 {
            return (b, [0.0, 1.0, 0.0]);
        }
        let vc = d1 * d4 - d3 * d2;
        if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
            let v = d1 / (d1 - d3);
            return (a + ab * v, [1.0 - v, v, 0.0]);
        }
        let cp = point - c;
        let (d5, d6) = (ab.dot(cp), ac.dot(cp));
        if d6 >= 0.0 && d5 <= d6 {
            return (c, [0.0, 0.0, 1.0]);
        }
        let vb = d5 * d2 - d1 * d6;
        if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
            let w = d2 / (d2 - d6);
            return (a + ac * w, [1.0 - w, 0.0, w]);
        }
        let va = d3 * d6 - d5 * d4;
        if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
            let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
            return (b + (c - b) * w, [0.0, 1.0 - w, w]);
        }
        let denominator = 1.0 / (va + vb + vc);
        let (v, w) = (vb * denominator, vc * denominator);
        (a + ab * v + ac * w, [1.0 - v - w, v, w])
    }
}

/// Edge flags of edge `edge` of the triangle `corners` (front normal `normal`) given the corner
/// of the neighbour across it that is not on the edge (`None` for a rim edge): the two bits to
/// set in [`Triangle::edge_flags`].
///
/// The bend is the angle `φ = atan2(−n · u, o · u)` between the triangle's outward in-plane
/// direction `o` at the edge and the neighbour's in-plane direction `u` away from the edge:
/// positive when the neighbour falls away below the front (convex seen from the front), negative
/// when it rises. The edge is active on the front when `φ > ACTIVE_EDGE_ANGLE`, on the back when
/// `φ < −ACTIVE_EDGE_ANGLE`.
pub fn edge_flags(corners: &[Vec3; 3], normal: Vec3, edge: usize, neighbour: Option<Vec3>) -> u8 {
    let both = (1 << edge) | (1 << (edge + 3));
    let Some(far) = neighbour else {
        return both;
    };
    let from = corners[edge];
    let to = corners[(edge + 1) % 3];
    let Some(along) = (to - from).try_normalize() else {
        return both;
    };
    let across = |point: Vec3| {
        let offset = point - from;
        (offset - along * along.dot(offset)).try_normalize()
    };
    let (Some(inward), Some(away)) = (across(corners[(edge + 2) % 3]), across(far)) else {
        return both;
    };
    bend_flags(-inward.dot(away), -normal.dot(away), edge)
}

/// `cos` and `sin` of [`ACTIVE_EDGE_ANGLE`].
const ACTIVE_EDGE_COS: f32 = 0.996_194_7;
const ACTIVE_EDGE_SIN: f32 = 0.087_155_74;

/// The flags of an edge bent by `φ = atan2(y, x)`: `φ > ACTIVE_EDGE_ANGLE` where `(x, y)` lies
/// above the x axis and `y cos A > x sin A` (`sin(φ − A) > 0`), `φ < −A` below it and
/// `−y cos A > x sin A`; folded flat back (`y = ±0`, `x < 0`) as `atan2` has it, `±π`. Building
/// a mesh or heightfield tests every edge, so the test does without `atan2`.
fn bend_flags(x: f32, y: f32, edge: usize) -> u8 {
    let front = if y == 0.0 {
        x < 0.0 && y.is_sign_positive()
    } else {
        y > 0.0 && y * ACTIVE_EDGE_COS > x * ACTIVE_EDGE_SIN
    };
    let back = if y == 0.0 {
        x < 0.0 && y.is_sign_negative()
    } else {
        y < 0.0 && -y * ACTIVE_EDGE_COS > x * ACTIVE_EDGE_SIN
    };
    if front {
        1 << edge
    } else if back {
        1 << (edge + 3)
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Flat and gently bent neighbours leave an edge inactive; a ridge is active on its convex
    /// side only.
    #[test]
    fn edges_are_active_where_the_surface_is_convex() {
        let corners = [Vec3::ZERO, Vec3::Z, Vec3::X];
        let normal = Vec3::Y;
        // Edge 2 runs from X to the origin; the neighbour lies on the −Z side.
        let flat = edge_flags(&corners, normal, 2, Some(Vec3::new(0.5, 0.0, -1.0)));
        let gentle = edge_flags(&corners, normal, 2, Some(Vec3::new(0.5, -0.03, -1.0)));
        let ridge = edge_flags(&corners, normal, 2, Some(Vec3::new(0.5, -0.5, -1.0)));
        let valley = edge_flags(&corners, normal, 2, Some(Vec3::new(0.5, 0.5, -1.0)));
        assert_eq!((flat, gentle), (0, 0));
        assert_eq!(ridge, 1 << 2);
        assert_eq!(valley, 1 << 5);
        assert_eq!(edge_flags(&corners, normal, 1, None), (1 << 1) | (1 << 4));
    }

    /// The bend test without `atan2` flags edges as `atan2` would, all round the circle.
    #[test]
    fn bends_are_flagged_as_their_angles_give() {
        let (sin, cos) = ACTIVE_EDGE_ANGLE.sin_cos();
        assert!((ACTIVE_EDGE_SIN - sin).abs() < 1e-7 && (ACTIVE_EDGE_COS - cos).abs() < 1e-7);
        for k in 0..10_000 {
            let angle =
                -std::f32::consts::PI + 2.0 * std::f32::consts::PI * (k as f32 + 0.37) / 1e4;
            let (y, x) = angle.sin_cos();
            let (x, y) = (3.0 * x, 3.0 * y);
            let bend = y.atan2(x);
            if (bend.abs() - ACTIVE_EDGE_ANGLE).abs() < 1e-5 {
                continue;
            }
            let expected = if bend > ACTIVE_EDGE_ANGLE {
                1 << 1
            } else if bend < -ACTIVE_EDGE_ANGLE {
                1 << 4
            } else {
                0
            };
            assert_eq!(bend_flags(x, y, 1), expected, "angle {angle}");
        }
        assert_eq!(bend_flags(-1.0, 0.0, 0), 1);
        assert_eq!(bend_flags(-1.0, -0.0, 0), 1 << 3);
        assert_eq!(bend_flags(1.0, 0.0, 0), 0);
    }

    #[test]
    fn closest_points_name_their_feature() {
        let triangle = Triangle {
            vertices: [Vec3::ZERO, Vec3::X, Vec3::Z],
            edge_flags: 0,
        };
        let (inside, weights) = triangle.closest_point(Vec3::new(0.2, 1.0, 0.2));
        assert!(inside.distance(Vec3::new(0.2, 0.0, 0.2)) < 1.0e-6);
        assert!(weights.iter().all(|&w| w > 0.0));
        let (on_edge, weights) = triangle.closest_point(Vec3::new(0.5, 1.0, -1.0));
        assert!(on_edge.distance(Vec3::new(0.5, 0.0, 0.0)) < 1.0e-6);
        assert_eq!(weights[2], 0.0);
    }
}
