//! How joints are drawn: a dot at each anchor, a red line between the anchors when a joint has
//! come apart, the axis of a hinge or slider, and the limits: a revolute joint's two limit
//! directions with a spoke fixed to `body_b` that turns between them, a ball joint's swing cone
//! around its twist axis with `body_b`'s twist axis inside it, its twist limits as two spokes at
//! the tip of `body_b`'s axis with a spoke fixed to `body_b` between them, and a prismatic joint's
//! range of slide. Broken joints are not drawn: they no longer hold anything.

use std::f32::consts::TAU;

use rebond::{BodyHandle, Joint, JointHandle, JointPlacement, JointType, Quat, Vec3, World};

use super::debug_draw::{DebugGeometry, Marker, Segment};
use super::palette::{JOINT_ANCHOR, JOINT_AXIS, JOINT_GAP, JOINT_LIMIT, JOINT_LINK};

/// Length of a drawn hinge or slide axis, metres, centred on the anchor.
const AXIS_LENGTH: f32 = 0.4;
/// Length of the spokes that show limits and angles, metres.
const SPOKE_LENGTH: f32 = 0.3;
/// Anchors further apart than this, metres, are joined by a line.
const SHOWN_GAP: f32 = 1.0e-3;
/// Length of the spokes that show a ball joint's twist, metres.
const TWIST_SPOKE_LENGTH: f32 = 0.15;
/// Lines drawn on a ball joint's swing cone.
const CONE_LINES: usize = 8;

/// Adds every joint of `world` to `geometry`. `start` is the world as the scene loaded, when its
/// joints were added: their angles count from the bodies' poses there.
pub fn push_joints(geometry: &mut DebugGeometry, world: &World, start: &World) {
    for (handle, joint) in world.joints() {
        if joint.is_broken() {
            continue;
        }
        let Ok(placement) = world.joint_placement(handle) else {
            continue;
        };
        let mut lines = |from: Vec3, to: Vec3, colour| {
            geometry.segments.push(Segment { from, to, colour });
        };
        let (anchor, axis) = (placement.anchor_a, placement.axis_a);
        let apart = placement.anchor_b - anchor;
        match joint.joint_type() {
            // The anchors are apart by design: the rod, and the slide along the axis.
            JointType::Distance => lines(anchor, placement.anchor_b, JOINT_LINK),
            JointType::Prismatic => {
                lines(anchor, placement.anchor_b, JOINT_LINK);
                let half = 0.5 * AXIS_LENGTH * axis;
                lines(anchor - half, anchor + half, JOINT_AXIS);
                if let Some([low, high]) = joint.desc().limits {
                    lines(anchor + low * axis, anchor + high * axis, JOINT_LIMIT);
                }
            }
            JointType::Fixed | JointType::Ball | JointType::Revolute | JointType::Generic => {
                if apart.length() > SHOWN_GAP {
                    lines(anchor, placement.anchor_b, JOINT_GAP);
                }
            }
        }
        match joint.joint_type() {
            JointType::Revolute => {
                let half = 0.5 * AXIS_LENGTH * axis;
                lines(anchor - half, anchor + half, JOINT_AXIS);
                if let Some(spokes) = HingeSpokes::new(world, start, handle, joint, &placement) {
                    if let Some([low, high]) = joint.desc().limits {
                        for angle in [low, high] {
                            let direction = Quat::from_axis_angle(axis, angle) * spokes.zero;
                            lines(anchor, anchor + SPOKE_LENGTH * direction, JOINT_LIMIT);
                        }
                    }
                    let tip = placement.anchor_b + SPOKE_LENGTH * spokes.body_b;
                    lines(placement.anchor_b, tip, JOINT_ANCHOR);
                }
            }
            JointType::Ball
                if joint.desc().swing_limit.is_some() || joint.desc().axis.is_some() =>
            {
                lines(anchor, anchor + SPOKE_LENGTH * axis, JOINT_AXIS);
                let tip_b = placement.anchor_b + SPOKE_LENGTH * placement.axis_b;
                lines(placement.anchor_b, tip_b, JOINT_ANCHOR);
                if let (Some([low, high]), Some(twist)) = (
                    joint.desc().twist_limits,
                    TwistSpokes::new(world, start, handle, joint, &placement),
                ) {
                    let axis_b = placement.axis_b;
                    for angle in [low, high] {
                        let direction = Quat::from_axis_angle(axis_b, angle) * twist.zero;
                        lines(tip_b, tip_b + TWIST_SPOKE_LENGTH * direction, JOINT_LIMIT);
                    }
                    lines(
                        tip_b,
                        tip_b + TWIST_SPOKE_LENGTH * twist.body_b,
                        JOINT_ANCHOR,
                    );
                }
                if let Some(swing) = joint.desc().swing_limit {
                    let edge = Quat::from_axis_angle(axis.any_orthonormal_vector(), swing) * axis;
                    for line in 0..CONE_LINES {
                        let turn =
                            Quat::from_axis_angle(axis, line as f32 * TAU / CONE_LINES as f32);
                        lines(anchor, anchor + SPOKE_LENGTH * (turn * edge), JOINT_LIMIT);
                    }
                }
            }
            _ => {}
        }
        for position in [placement.anchor_a, placement.anchor_b] {
            geometry.markers.push(Marker {
                position,
                colour: JOINT_ANCHOR,
            });
        }
    }
}

/// The directions a revolute joint's angle is shown by, world frame, both square to the axis:
/// `zero`, fixed to `body_a`, is where `body_b`'s spoke pointed when the joint was added (angle
/// 0); `body_b` is that spoke now, fixed to `body_b`. The spoke points from the anchor toward
/// `body_b`'s centre of mass as it was then, so that it lies along the part that swings.
struct HingeSpokes {
    zero: Vec3,
    body_b: Vec3,
}

impl HingeSpokes {
    /// The spokes of the revolute `joint` of `world` at `placement`, from its start in `start`;
    /// `None` when `start` lacks the joint or one of its bodies.
    fn new(
        world: &World,
        start: &World,
        handle: JointHandle,
        joint: &Joint,
        placement: &JointPlacement,
    ) -> Option<Self> {
        let (body_a, body_b) = joint.bodies();
        let then = start.joint_placement(handle).ok()?;
        let reach = start.body(body_b).ok()?.center_of_mass() - then.anchor_a;
        let across = reach - then.axis_a * reach.dot(then.axis_a);
        let spoke = if across.length() > SHOWN_GAP {
            across.normalize()
        } else {
            then.axis_a.any_orthonormal_vector()
        };
        // Turning about the axis only: anything else is the joint's error, not its angle.
        let axis = placement.axis_a;
        Some(Self {
            zero: square_to(axis, fixed_in(world, start, body_a, spoke)?),
            body_b: square_to(axis, fixed_in(world, start, Some(body_b), spoke)?),
        })
    }
}

/// The directions a ball joint's twist is shown by, world frame, both square to `body_b`'s twist
/// axis: `zero`, a direction square to the axis fixed to `body_a` when the joint was added,
/// carried onto `body_b`'s axis by the shortest turn (the swing), is zero twist; `body_b` is that
/// direction as fixed to `body_b`, which turns from `zero` by the twist.
struct TwistSpokes {
    zero: Vec3,
    body_b: Vec3,
}

impl TwistSpokes {
    /// The spokes of the ball `joint` of `world` at `placement`, from its start in `start`;
    /// `None` when `start` lacks the joint or one of its bodies.
    fn new(
        world: &World,
        start: &World,
        handle: JointHandle,
        joint: &Joint,
        placement: &JointPlacement,
    ) -> Option<Self> {
        let (body_a, body_b) = joint.bodies();
        let spoke = start
            .joint_placement(handle)
            .ok()?
            .axis_a
            .any_orthonormal_vector();
        let swing = Quat::from_rotation_arc(placement.axis_a, placement.axis_b);
        let zero = swing * fixed_in(world, start, body_a, spoke)?;
        let axis = placement.axis_b;
        Some(Self {
            zero: square_to(axis, zero),
            body_b: square_to(axis, fixed_in(world, start, Some(body_b), spoke)?),
        })
    }
}

/// `direction` (world frame in `start`) as fixed to `body`: in its frame as it stood in `start`,
/// then turned as it stands in `world`.
fn fixed_in(
    world: &World,
    start: &World,
    body: Option<BodyHandle>,
    direction: Vec3,
) -> Option<Vec3> {
    let then = rotation(start, body)?;
    let now = rotation(world, body)?;
    Some(now * (then.inverse() * direction))
}

/// `direction` without its part along the unit `axis`, normalised (itself when along the axis).
fn square_to(axis: Vec3, direction: Vec3) -> Vec3 {
    (direction - axis * direction.dot(axis)).normalize_or(direction)
}

/// The rotation of `body` in `world`: the identity for the world itself (`None`).
fn rotation(world: &World, body: Option<BodyHandle>) -> Option<Quat> {
    match body {
        Some(body) => Some(world.body(body).ok()?.rotation()),
        None => Some(Quat::IDENTITY),
    }
}

#[cfg(test)]
mod tests {
    use rebond::{BodyDesc, JointDesc, Shape, WorldSettings};

    use super::super::palette::Rgb;
    use super::*;

    /// A world with a bar hanging from a world hinge about Z at the origin, limited to
    /// [−0.5, 1], and a ball on a ball joint with a swing limit; and the hinge's handle.
    fn world() -> (World, JointHandle) {
        let mut world = World::new(WorldSettings::default()).expect("a world");
        let bar = Shape::cuboid(Vec3::new(0.1, 0.5, 0.1)).expect("a bar");
        let bar = world
            .add_body(BodyDesc::dynamic(bar).position(Vec3::new(0.0, -0.5, 0.0)))
            .expect("added");
        let hinge = world
            .add_joint(JointDesc::revolute(None, bar, Vec3::ZERO, Vec3::Z).limits(-0.5, 1.0))
            .expect("joined");
        let ball = Shape::sphere(0.2).expect("a ball");
        let ball = world
            .add_body(BodyDesc::dynamic(ball).position(Vec3::new(3.0, -0.5, 0.0)))
            .expect("added");
        let swing = JointDesc::ball(None, ball, Vec3::new(3.0, 0.0, 0.0))
            .axis(Vec3::NEG_Y)
            .swing_limit(0.4)
            .twist_limits(-0.3, 0.6);
        world.add_joint(swing).expect("joined");
        (world, hinge)
    }

    fn coloured(geometry: &DebugGeometry, colour: Rgb) -> Vec<Segment> {
        let segments = geometry.segments.iter();
        segments.filter(|s| s.colour == colour).copied().collect()
    }

    #[test]
    fn a_hinge_shows_its_axis_its_limits_and_its_angle() {
        let (mut world, hinge) = world();
        let bar = world.joint(hinge).expect("the hinge").bodies().1;
        let start = world.clone();
        let mut geometry = DebugGeometry::default();
        push_joints(&mut geometry, &world, &start);
        assert_eq!(geometry.markers.len(), 4, "two anchors a joint");
        assert!(coloured(&geometry, JOINT_GAP).is_empty(), "nothing apart");
        let limits = coloured(&geometry, JOINT_LIMIT);
        assert_eq!(limits.len(), 2 + 2 + CONE_LINES);
        // The hinge's limits turn the downward spoke by −0.5 and 1 rad about Z.
        for (segment, angle) in limits[..2].iter().zip([-0.5f32, 1.0]) {
            let direction = (segment.to - segment.from) / SPOKE_LENGTH;
            let expected = Vec3::new(angle.sin(), -angle.cos(), 0.0);
            assert!(
                (direction - expected).length() < 1e-4,
                "{direction} at {angle}"
            );
        }
        // The ball's twist limits: two spokes square to its downward axis, at its tip, 0.9 rad
        // apart, with the ball's own spoke at zero twist between them.
        let spokes = &limits[2..4];
        let tip = Vec3::new(3.0, -SPOKE_LENGTH, 0.0);
        let [low, high] = [0, 1].map(|k| (spokes[k].to - spokes[k].from).normalize());
        for (segment, direction) in spokes.iter().zip([low, high]) {
            assert!(
                (segment.from - tip).length() < 1e-5,
                "from {}",
                segment.from
            );
            assert!(
                direction.dot(Vec3::Y).abs() < 1e-5,
                "{direction} not square"
            );
        }
        assert!((low.dot(high) - 0.9f32.cos()).abs() < 1e-4);
        let own = coloured(&geometry, JOINT_ANCHOR)[2];
        let own = (own.to - own.from).normalize();
        assert!((own.dot(low) - 0.3f32.cos()).abs() < 1e-4, "{own}");
        // The ball's cone lines are 0.4 rad off its downward twist axis.
        for segment in &limits[4..] {
            let direction = (segment.to - segment.from).normalize();
            assert!((direction.dot(Vec3::NEG_Y) - 0.4f32.cos()).abs() < 1e-4);
        }
        // The bar swings: its spoke turns with it, between the limits.
        for _ in 0..20 {
            world
                .body_mut(bar)
                .expect("the bar")
                .apply_force(Vec3::new(200.0, 0.0, 0.0))
                .expect("pushed");
            world.step(1.0 / 60.0).expect("a step");
        }
        let mut geometry = DebugGeometry::default();
        push_joints(&mut geometry, &world, &start);
        let spoke = coloured(&geometry, JOINT_ANCHOR)[0];
        let direction = (spoke.to - spoke.from) / SPOKE_LENGTH;
        let along_bar = -(world.body(bar).expect("the bar").rotation() * Vec3::Y);
        assert!(
            (direction - along_bar).length() < 1e-3,
            "{direction} along {along_bar}"
        );
        assert!(direction.x > 0.1, "pushed toward +X: {direction}");
    }

    #[test]
    fn broken_joints_are_not_drawn_and_gaps_are_red() {
        let (mut world, hinge) = world();
        let start = world.clone();
        let bar = world.joint(hinge).expect("the hinge").bodies().1;
        world.remove_joint(hinge).expect("removed");
        let stretched = JointDesc::ball(None, bar, Vec3::new(0.0, 0.5, 0.0));
        let stretched = world.add_joint(stretched).expect("joined");
        world
            .body_mut(bar)
            .expect("the bar")
            .set_position(Vec3::new(0.0, -1.0, 0.0))
            .expect("moved");
        let mut geometry = DebugGeometry::default();
        push_joints(&mut geometry, &world, &start);
        let gaps = coloured(&geometry, JOINT_GAP);
        assert_eq!(gaps.len(), 1);
        assert!(((gaps[0].to - gaps[0].from).length() - 0.5).abs() < 1e-4);
        let broken = JointDesc::ball(None, bar, Vec3::ZERO).break_force(0.0);
        world.remove_joint(stretched).expect("removed");
        let broken = world.add_joint(broken).expect("joined");
        for _ in 0..2 {
            world.step(1.0 / 60.0).expect("a step");
        }
        assert!(world.joint(broken).expect("the joint").is_broken());
        let mut geometry = DebugGeometry::default();
        push_joints(&mut geometry, &world, &start);
        assert_eq!(geometry.markers.len(), 2, "only the ball joint's anchors");
    }
}
