//! Dragging a body with the mouse: a soft spring pulls the grabbed point of the body toward the
//! cursor, as testbeds' mouse joints do. The cursor moves on the plane through the grabbed point
//! facing the camera.
//!
//! The spring is integrated implicitly, as Box2D's mouse joint is: it asks for the velocity of the
//! grabbed point after the step, `v' = (v − h ω² x) / (1 + 2 ζ ω h + ω² h²)` for an offset `x`
//! from the target, and pushes with the force that gives that velocity through the point's
//! effective mass `K⁻¹`, `K = 1/m − [r]× I⁻¹ [r]×`. It behaves alike for any mass and any grab
//! point, and stays stable where an explicit spring on a corner of a box would blow up.

use std::f32::consts::TAU;

use rebond::{BodyHandle, Vec3, World};

use super::picking::Ray;

/// Natural frequency of the spring, Hz.
const SPRING_FREQUENCY: f32 = 5.0;
/// Damping ratio of the spring: a little below critical, so the body follows without wobbling.
const SPRING_DAMPING_RATIO: f32 = 0.7;
/// Strongest pull, as an acceleration of the body, m/s² (about 20 g).
const MAX_ACCELERATION: f32 = 200.0;
/// Damping of the dragged body's spin, 1/s: without it a body held off its centre of mass
/// swings for long.
const ANGULAR_DAMPING: f32 = 2.0;

/// A body held by the mouse.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drag {
    body: BodyHandle,
    /// The grabbed point in the body frame.
    local_anchor: Vec3,
    /// Where the spring pulls the grabbed point, world metres.
    target: Vec3,
    /// Unit normal of the plane the target moves on (the view direction when the drag began).
    plane_normal: Vec3,
}

impl Drag {
    /// Grabs `body` at `local_anchor` (body frame), now at world `point`, seen along
    /// `view_direction`.
    pub fn new(body: BodyHandle, local_anchor: Vec3, point: Vec3, view_direction: Vec3) -> Self {
        Self {
            body,
            local_anchor,
            target: point,
            plane_normal: view_direction.normalize_or(Vec3::Z),
        }
    }

    /// The body held.
    pub fn body(&self) -> BodyHandle {
        self.body
    }

    /// Where the spring pulls, world metres.
    pub fn target(&self) -> Vec3 {
        self.target
    }

    /// Where the grabbed point of the body is now, or `None` if the body is gone.
    pub fn anchor(&self, world: &World) -> Option<Vec3> {
        let body = world.body(self.body).ok()?;
        Some(body.pose().transform_point(self.local_anchor))
    }

    /// Moves the target to where `ray` crosses the drag plane (kept when the ray runs along the
    /// plane or away from it).
    pub fn aim(&mut self, ray: &Ray) {
        let approach = ray.direction.dot(self.plane_normal);
        if approach.abs() < 1e-6 {
            return;
        }
        let distance = (self.target - ray.origin).dot(self.plane_normal) / approach;
        if distance > 0.0 && distance.is_finite() {
            self.target = ray.at(distance);
        }
    }

    /// Applies the spring force (at the grabbed point) and the spin damping for the next step of
    /// `timestep` seconds.
    pub fn apply(&self, world: &mut World, timestep: f32) -> rebond::Result<()> {
        let body = world.body_mut(self.body)?;
        let anchor = body.pose().transform_point(self.local_anchor);
        let velocity = body.velocity_at_point(anchor);
        let omega = TAU * SPRING_FREQUENCY;
        let offset = anchor - self.target;
        let wanted = (velocity - timestep * omega * omega * offset)
            / (1.0 + 2.0 * SPRING_DAMPING_RATIO * omega * timestep + (omega * timestep).powi(2));
        let impulse = body.inverse_mass_at_point(anchor).inverse() * (wanted - velocity);
        let force = (impulse / timestep).clamp_length_max(body.mass() * MAX_ACCELERATION);
        let spin_damping = -ANGULAR_DAMPING * (body.world_inertia() * body.angular_velocity());
        if force.is_finite() {
            body.apply_force_at_point(force, anchor)?;
        }
        body.apply_torque(spin_damping)
    }
}

#[cfg(test)]
mod tests {
    use rebond::{BodyDesc, Shape, WorldSettings};

    use super::*;

    #[test]
    fn the_target_slides_on_the_plane_facing_the_camera() {
        let mut world = World::new(WorldSettings::default()).expect("a world");
        let body = world
            .add_body(BodyDesc::dynamic(Shape::sphere(0.5).expect("a sphere")))
            .expect("added");
        let mut drag = Drag::new(body, Vec3::ZERO, Vec3::new(0.0, 0.0, 0.0), -Vec3::Z);
        drag.aim(&Ray {
            origin: Vec3::new(0.0, 0.0, 10.0),
            direction: Vec3::new(0.6, 0.0, -0.8),
        });
        assert!((drag.target() - Vec3::new(7.5, 0.0, 0.0)).length() < 1e-4);
        drag.aim(&Ray {
            origin: Vec3::new(0.0, 0.0, 10.0),
            direction: Vec3::X,
        });
        assert!(
            (drag.target() - Vec3::new(7.5, 0.0, 0.0)).length() < 1e-4,
            "kept"
        );
        assert_eq!(drag.anchor(&world), Some(Vec3::ZERO));
    }

    #[test]
    fn the_spring_holds_a_box_by_its_corner_against_gravity() {
        let mut world = World::new(WorldSettings::default()).expect("a world");
        let body = world
            .add_body(BodyDesc::dynamic(
                Shape::cuboid(Vec3::splat(0.5)).expect("a box"),
            ))
            .expect("added");
        let corner = Vec3::splat(0.5);
        let mut drag = Drag::new(body, corner, corner, -Vec3::Z);
        drag.target = Vec3::new(0.5, 2.5, 0.5);
        for _ in 0..240 {
            drag.apply(&mut world, 1.0 / 60.0).expect("a force");
            world.step(1.0 / 60.0).expect("a step");
        }
        let anchor = drag.anchor(&world).expect("the body");
        assert!((anchor - drag.target()).length() < 0.1, "{anchor}");
        let state = world.body(body).expect("the body");
        assert!(state.position().is_finite());
        assert!(
            state.center_of_mass().y > 1.0,
            "held up, swinging below the grabbed corner"
        );
    }
}
