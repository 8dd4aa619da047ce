//! The restitution stage's collisions (`contacts.rs`): a manifold's points brought to a stop,
//! bounced, or settled, on the velocities at the end of the step.

use super::{BodyLanes, BodyState, ContactLanes, F32x4, MAX_MANIFOLD_POINTS};

/// Gauss–Seidel passes over a manifold's points in one collision ([`ContactLanes::collide`]); a
/// collision that leaves a point approaching is swept again. With four, a box landing flat
/// bounces straight, its spin under 1e-3 rad/s (`tests/spin_and_restitution.rs`).
const COLLISION_PASSES: usize = 4;

/// Normal speed below which a point counts as no longer colliding, m/s: the restitution stage
/// sweeps its collisions until no point they act on moves faster along its normal.
const COLLISION_SPEED: f32 = 1.0e-4;

/// What one collision of the restitution stage does ([`ContactLanes::collide`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Collision {
    /// Stops every approach, and marks the points it stops as the step's impacts.
    Plastic,
    /// Stops every approach, then bounces by the restitution.
    Elastic,
    /// Brings the step's impacts to rest along their normals.
    Settle,
}

impl ContactLanes {
    /// One collision of the four lanes' contacts on velocities `states` (the restitution
    /// stage's, `contacts.rs`), at the points that pushed during the step: impulses found by
    /// Gauss–Seidel over the manifold's points ([`COLLISION_PASSES`] passes). A
    /// [`Collision::Plastic`] or [`Collision::Elastic`] collision stops every approach with
    /// impulses `λ ≥ 0`, and an elastic one adds `e λ` at the points that approached faster
    /// than `restitution_threshold` (Poisson's restitution; for one point `v_n' = −e v_n`,
    /// Newton's). A plastic collision marks the points it stops as the step's impacts;
    /// [`Collision::Settle`] brings those to `v_n = 0`, pulling as well as pushing. Returns
    /// whether any point it acts on moved faster than [`COLLISION_SPEED`] along the normal.
    pub fn collide(
        &mut self,
        states: &mut [BodyState],
        restitution_threshold: f32,
        collision: Collision,
    ) -> bool {
        let mut a = BodyLanes::gather(states, &self.body_a);
        let mut b = BodyLanes::gather(states, &self.body_b);
        let masses = *self.masses();
        let normal = self.normal;
        let slow = F32x4::splat(COLLISION_SPEED);
        let mut approach = [F32x4::ZERO; MAX_MANIFOLD_POINTS];
        let mut collided = false;
        for (point, approach) in self.points[..self.point_count]
            .iter_mut()
            .zip(&mut approach)
        {
            let velocity = point.normal.velocity(&a, &b, normal);
            let moving = match collision {
                Collision::Settle => {
                    *approach = point.impact;
                    velocity.max(-velocity).greater_than(slow)
                }
                Collision::Plastic | Collision::Elastic => {
                    let pushed = point.max_normal_impulse.greater_than(F32x4::ZERO);
                    *approach = pushed.select(-velocity, F32x4::ZERO);
                    approach.greater_than(slow)
                }
            };
            let acts = approach.greater_than(F32x4::ZERO);
            collided |= acts.and(moving).any();
            if let Collision::Plastic = collision {
                point.impact = moving.select(F32x4::ONE, point.impact);
            }
        }
        if !collided {
            return false;
        }
        let points = &self.points[..self.point_count];
        let mut stopping = [F32x4::ZERO; MAX_MANIFOLD_POINTS];
        for _ in 0..COLLISION_PASSES {
            for ((point, impulse), approach) in points.iter().zip(&mut stopping).zip(&approach) {
                let jacobian = &point.normal;
                let mut total = *impulse - jacobian.mass * jacobian.velocity(&a, &b, normal);
                if !matches!(collision, Collision::Settle) {
                    total = total.max(F32x4::ZERO);
                }
                let total = approach
                    .greater_than(F32x4::ZERO)
                    .select(total, F32x4::ZERO);
                jacobian.apply((&mut a, &mut b), &masses, normal, total - *impulse);
                *impulse = total;
            }
        }
        if let Collision::Elastic = collision {
            let fast = F32x4::splat(restitution_threshold);
            for ((point, impulse), approach) in points.iter().zip(&stopping).zip(&approach) {
                let bounce = approach
                    .greater_than(fast)
                    .select(self.restitution, F32x4::ZERO);
                point
                    .normal
                    .apply((&mut a, &mut b), &masses, normal, bounce * *impulse);
            }
        }
        a.scatter(states, &self.body_a);
        b.scatter(states, &self.body_b);
        true
    }
}
