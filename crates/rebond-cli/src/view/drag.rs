//! Dragging a body with the mouse: a soft spring pulls the grabbed point of the body toward the
//! cursor, as testbeds' mouse joints do. The cursor moves on the plane through the grabbed point
//! facing the camera.
//!
//! The spring is integrated implicitly, as Box2D's mouse joint is: it asks for the velocity of the
//! grabbed point after the step, `v' = (v − h ω² x) / (1 + 2 ζ ω h + ω² h²)` for an offset `x`
//! from the target, and pushes with the force that gives that velocity through the point's
//! effective mass `K⁻¹`, `K = 1/m − [r]× I⁻¹ [r]×`. It behaves alike for any mass and any grab
//! point, and stays stable where an explicit spring on a corner of a box would blow up.
//!
//! A body held by joints is pulled the same way: the joints pass the pull on to what the body is
//! joined to, and hold it back where they must. The spring's stiffness stays that of the body
//! alone (counting the bodies behind the joints would make it far too stiff when only the held
//! part swings, as a forearm about its elbow), but the strongest pull counts them, so that a
//! light part can lift what hangs from it, and they are damped as the held body's spin is, so
//! that they do not swing on for long.

use std::collections::{HashMap, HashSet};
use std::f32::consts::TAU;

use rebond::{BodyHandle, BodyType, Vec3, World};

use super::picking::Ray;

/// Natural frequency of the spring, Hz.
const SPRING_FREQUENCY: f32 = 5.0;
/// Damping ratio of the spring: a little below critical, so the body follows without wobbling.
const SPRING_DAMPING_RATIO: f32 = 0.7;
/// Strongest pull, as an acceleration of the body and the moving bodies jointed to it, m/s²
/// (about 20 g).
const MAX_ACCELERATION: f32 = 200.0;
/// Damping of the dragged body's spin, 1/s: without it a body held off its centre of mass
/// swings for long.
const ANGULAR_DAMPING: f32 = 2.0;
/// Damping of the motion of the bodies jointed to the dragged one, 1/s: the spring, tuned for the
/// dragged body alone, hardly damps them.
const JOINTED_DAMPING: f32 = 2.0;

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
        let jointed = jointed_bodies(world, self.body);
        let mut pulled_mass = 0.0;
        for &handle in &jointed {
            let body = world.body_mut(handle)?;
            pulled_mass += body.mass();
            if handle != self.body {
                let force = -JOINTED_DAMPING * body.mass() * body.linear_velocity();
                let torque = -JOINTED_DAMPING * (body.world_inertia() * body.angular_velocity());
                body.apply_force(force)?;
                body.apply_torque(torque)?;
            }
        }
        let body = world.body_mut(self.body)?;
        let anchor = body.pose().transform_point(self.local_anchor);
        let velocity = body.velocity_at_point(anchor);
        let omega = TAU * SPRING_FREQUENCY;
        let offset = anchor - self.target;
        let wanted = (velocity - timestep * omega * omega * offset)
            / (1.0 + 2.0 * SPRING_DAMPING_RATIO * omega * timestep + (omega * timestep).powi(2));
        let impulse = body.inverse_mass_at_point(anchor).inverse() * (wanted - velocity);
        let force = (impulse / timestep).clamp_length_max(pulled_mass * MAX_ACCELERATION);
        let spin_damping = -ANGULAR_DAMPING * (body.world_inertia() * body.angular_velocity());
        if force.is_finite() {
            body.apply_force_at_point(force, anchor)?;
        }
        body.apply_torque(spin_damping)
    }
}

/// `body`, if dynamic, and every dynamic body joined to it through unbroken joints and other
/// dynamic bodies. Static and kinematic bodies end the chain: pulling does not move them.
fn jointed_bodies(world: &World, body: BodyHandle) -> Vec<BodyHandle> {
    let mut neighbours: HashMap<BodyHandle, Vec<BodyHandle>> = HashMap::new();
    for (_, joint) in world.joints().filter(|(_, joint)| !joint.is_broken()) {
        if let (Some(body_a), body_b) = joint.bodies() {
            neighbours.entry(body_a).or_default().push(body_b);
            neighbours.entry(body_b).or_default().push(body_a);
        }
    }
    let mut seen = HashSet::from([body]);
    let mut waiting = vec![body];
    let mut found = Vec::new();
    while let Some(handle) = waiting.pop() {
        let dynamic = world
            .body(handle)
            .is_ok_and(|body| body.body_type() == BodyType::Dynamic);
        if !dynamic {
            continue;
        }
        found.push(handle);
        for &next in neighbours.get(&handle).into_iter().flatten() {
            if seen.insert(next) {
                waiting.push(next);
            }
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use rebond::{BodyDesc, JointDesc, Shape, WorldSettings};

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

    /// Drags `body` at `local_anchor` toward `target` for `steps` steps of 1/60 s.
    fn drag_for(
        world: &mut World,
        body: BodyHandle,
        local_anchor: Vec3,
        target: Vec3,
        steps: usize,
    ) -> Drag {
        let point = world
            .body(body)
            .expect("the body")
            .pose()
            .transform_point(local_anchor);
        let mut drag = Drag::new(body, local_anchor, point, -Vec3::Z);
        drag.target = target;
        for _ in 0..steps {
            drag.apply(world, 1.0 / 60.0).expect("a force");
            world.step(1.0 / 60.0).expect("a step");
        }
        drag
    }

    /// The largest distance between the two anchors of any joint of `world`.
    fn widest_gap(world: &World) -> f32 {
        world
            .joints()
            .map(|(handle, _)| {
                let placement = world.joint_placement(handle).expect("a placement");
                (placement.anchor_b - placement.anchor_a).length()
            })
            .fold(0.0, f32::max)
    }

    #[test]
    fn a_chain_hung_from_the_world_follows_as_far_as_it_reaches() {
        let mut world = World::new(WorldSettings::default()).expect("a world");
        let link = Shape::cuboid(Vec3::new(0.05, 0.25, 0.05)).expect("a link");
        let mut above = None;
        let mut last = None;
        for index in 0..3 {
            let top = 3.0 - 0.5 * index as f32;
            let body = world
                .add_body(BodyDesc::dynamic(link.clone()).position(Vec3::new(0.0, top - 0.25, 0.0)))
                .expect("added");
            world
                .add_joint(JointDesc::ball(above, body, Vec3::new(0.0, top, 0.0)))
                .expect("joined");
            above = Some(body);
            last = Some(body);
        }
        let end = Vec3::new(0.0, -0.25, 0.0);
        let last = last.expect("three links");
        let drag = drag_for(&mut world, last, end, Vec3::new(4.0, 3.0, 0.0), 240);
        let reached = drag.anchor(&world).expect("the link");
        assert!(
            (reached - Vec3::new(1.5, 3.0, 0.0)).length() < 0.1,
            "stretched toward the cursor as far as the chain goes: {reached}"
        );
        assert!(
            widest_gap(&world) < 0.01,
            "the joints hold: {}",
            widest_gap(&world)
        );
    }

    #[test]
    fn a_light_body_drags_the_heavy_one_it_is_jointed_to() {
        let mut world = World::new(WorldSettings::default()).expect("a world");
        world
            .add_body(
                BodyDesc::static_body(Shape::cuboid(Vec3::new(20.0, 0.5, 20.0)).expect("a box"))
                    .position(Vec3::new(0.0, -0.5, 0.0)),
            )
            .expect("the ground");
        let body = |world: &mut World, x: f32, mass: f32| {
            let shape = Shape::cuboid(Vec3::new(0.25, 0.25, 0.25)).expect("a box");
            world
                .add_body(
                    BodyDesc::dynamic(shape)
                        .mass(mass)
                        .position(Vec3::new(x, 0.25, 0.0)),
                )
                .expect("added")
        };
        let heavy = body(&mut world, 0.0, 60.0);
        let light = body(&mut world, 0.6, 2.0);
        world
            .add_joint(JointDesc::ball(heavy, light, Vec3::new(0.3, 0.25, 0.0)))
            .expect("joined");
        let target = Vec3::new(0.6, 2.0, 0.0);
        let drag = drag_for(&mut world, light, Vec3::ZERO, target, 240);
        // The spring is as stiff as for the light box alone (about 980 N/m): it holds 31 times
        // that weight about 0.6 m below the cursor, the heavy box hanging under it.
        let reached = drag.anchor(&world).expect("the light box");
        assert!(
            (reached.x - target.x).abs() < 0.1 && reached.y > 1.2,
            "lifted under the cursor: {reached}"
        );
        let hanging = world.body(heavy).expect("the heavy box");
        let (centre, speed) = (hanging.center_of_mass(), hanging.linear_velocity());
        assert!(
            centre.y > 0.6 && (centre.x - target.x).abs() < 0.2,
            "the heavy box hangs from it: {centre}"
        );
        assert!(speed.length() < 0.05, "and has stopped swinging: {speed}");
        assert!(
            widest_gap(&world) < 0.01,
            "the joint holds: {}",
            widest_gap(&world)
        );
    }
}
