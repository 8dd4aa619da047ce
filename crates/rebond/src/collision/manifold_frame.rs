//! Where a manifold was computed, and how it is rebuilt while its two bodies barely move relative
//! to each other (the contact cache's recycling, `contact_cache.rs`).

use super::manifold::{Manifold, MAX_MANIFOLD_POINTS};
use crate::math::{Pose, Quat, Vec3, Vec3A};
use crate::solver::contact_frame::ContactFrame;
use glam::Mat3A;

/// A manifold is rebuilt from its stored points instead of running the narrow phase again while
/// B has moved less than this relative to A since the manifold was computed, metres. The solver
/// keeps a recycled manifold's normal and lever arms (`solver/contact_frame.rs`), so this is also
/// how far a pair moves before its contacts feel their bodies' lean. More would hold tall stacks
/// better (a 40-box column at 4 substeps swayed 17 cm at its top in 1,000 steps with 1 mm, 5.0 cm
/// with 5 mm, 1.9 cm with 1 cm), but at 1e4 m from the origin, where a coordinate is rounded to
/// 1 mm, a resting box then jitters at 0.17 m/s, and with 1 cm shapes poured on a heightfield
/// sink 3.9 cm below it: carried points lag behind the surface they stand on.
pub const RECYCLE_MAX_TRANSLATION: f32 = 1.0e-3;

/// ... and turned less than this, radians (1°), measured as `cos(angle / 2)`.
const RECYCLE_MIN_HALF_ANGLE_COSINE: f32 = 0.999_961_9;

/// Where a manifold was computed, so it can be rebuilt while the two bodies barely move relative
/// to each other (as Jolt's body-pair cache does): every point follows the bodies' surfaces. The
/// bodies' frames here are their centres of mass' (position and rotation).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ManifoldFrame {
    /// Pose of body B in body A's frame when the manifold was computed.
    relative_position: Vec3A,
    relative_rotation: Quat,
    /// The normal in A's frame.
    local_normal: Vec3,
    /// Each point's surface point on A in A's frame, and on B in B's frame.
    local_points: [[Vec3; 2]; MAX_MANIFOLD_POINTS],
    /// The normal and lever arms the solver keeps while the manifold is recycled.
    pub(crate) solver: ContactFrame,
}

impl ManifoldFrame {
    /// Records `manifold`, computed with the centres of mass at `a` and `b`. A point at `position`
    /// with separation `s` has its surface points at `position ∓ n s / 2`.
    pub(super) fn new(manifold: &Manifold, a: &CenterPose, b: &CenterPose) -> Self {
        let mut local_points = [[Vec3::ZERO; 2]; MAX_MANIFOLD_POINTS];
        let normal = CenterPose::lanes(manifold.normal);
        for (point, local) in manifold.points().iter().zip(&mut local_points) {
            let position = CenterPose::lanes(point.position);
            let half_gap = 0.5 * point.separation * normal;
            *local = [
                a.local_point(position - half_gap).into(),
                b.local_point(position + half_gap).into(),
            ];
        }
        let relative = a.relative(b);
        Self {
            relative_position: relative.position,
            relative_rotation: relative.rotation,
            local_normal: (a.rotation.inverse() * normal).into(),
            local_points,
            solver: ContactFrame::new(manifold, a.position.into(), b.position.into()),
        }
    }

    /// Whether every value is finite.
    #[cfg(feature = "serde")]
    pub(super) fn is_finite(&self) -> bool {
        let solver = &self.solver;
        let points = self.local_points.iter().flatten();
        [self.local_normal, solver.normal, solver.centers]
            .iter()
            .chain(points)
            .chain(&solver.arms)
            .all(|vector| vector.is_finite())
            && self.relative_position.is_finite()
            && self.relative_rotation.is_finite()
    }

    /// Whether B's pose relative to A is still within the recycling tolerances.
    pub(super) fn still_fits(&self, relative: &CenterPose) -> bool {
        let moved = relative.position.distance_squared(self.relative_position);
        let half_angle_cosine = relative.rotation.dot(self.relative_rotation).abs();
        moved <= RECYCLE_MAX_TRANSLATION * RECYCLE_MAX_TRANSLATION
            && half_angle_cosine >= RECYCLE_MIN_HALF_ANGLE_COSINE
    }

    /// Carries `manifold`'s points along with the bodies now placed at `a` and `b`: same ids,
    /// separations measured again along the carried normal. In place: contacts are large, and
    /// each copy of one costs (callgrind, `pyramid`).
    pub(super) fn rebuild(&self, manifold: &mut Manifold, a: &PlacedBody, b: &PlacedBody) {
        let normal = a.rotation * Vec3A::from(self.local_normal);
        manifold.normal = normal.into();
        for (point, [on_a, on_b]) in manifold.points_mut().iter_mut().zip(&self.local_points) {
            let surface_a = a.place(*on_a);
            let surface_b = b.place(*on_b);
            point.separation = normal.dot(surface_b - surface_a);
            point.position = (0.5 * (surface_a + surface_b)).into();
        }
    }
}

/// A body's pose with its rotation as a SIMD matrix, to place several body points cheaply.
pub(super) struct PlacedBody {
    position: Vec3A,
    rotation: Mat3A,
}

impl PlacedBody {
    pub(super) fn new(pose: &CenterPose) -> Self {
        Self {
            position: pose.position,
            rotation: Mat3A::from_quat(pose.rotation),
        }
    }

    /// Body point to world point.
    fn place(&self, point: Vec3) -> Vec3A {
        self.position + self.rotation * Vec3A::from(point)
    }
}

/// A centre of mass's pose for the cache's arithmetic, its position in a `Vec3A` whose fourth lane
/// is a copy of `z`. Loaded from a [`Pose`], a position brings the padding after it into the
/// fourth SIMD lane, which the arithmetic computes on though nothing reads it; stale bytes there
/// (a pointer's upper half) are denormal floats, and on Intel cores every multiply with one takes
/// a microcode assist (`docs/design-notes/performance.md`).
#[derive(Debug, Clone, Copy)]
pub(super) struct CenterPose {
    position: Vec3A,
    rotation: Quat,
}

impl CenterPose {
    pub(super) fn of(pose: &Pose) -> Self {
        Self {
            position: Self::lanes(pose.position),
            rotation: pose.rotation,
        }
    }

    /// `v` in four lanes, the fourth a copy of `z`: kept out of reach of the optimiser, which
    /// would otherwise load the four bytes after `v` instead, as the lane is never read.
    fn lanes(v: Vec3) -> Vec3A {
        std::hint::black_box(Vec3A::from(v))
    }

    /// This pose's inverse times `other`: `other` seen from this one, rounded as
    /// `Pose::inverse` and `Pose::mul_pose` round it.
    pub(super) fn relative(&self, other: &CenterPose) -> CenterPose {
        let inverse = self.rotation.inverse();
        CenterPose {
            position: inverse * -self.position + inverse * other.position,
            rotation: inverse * other.rotation,
        }
    }

    /// World point to local point.
    fn local_point(&self, point: Vec3A) -> Vec3A {
        self.rotation.inverse() * (point - self.position)
    }
}
