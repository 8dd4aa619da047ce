//! What the debug toggles add to the picture, as plain geometry: contact points with their
//! normals, bounding boxes, joints ([`super::joint_draw`]), and the spring of a dragged body.

use rebond::{Aabb, Vec3};

use super::camera::corner;
use super::joint_draw::push_joints;
use super::palette::{
    Rgb, BOUNDING_BOX, CONTACT_NORMAL, CONTACT_POINT, DRAG_SPRING, SPECULATIVE_POINT,
};
use super::viewer::Viewer;

/// Length of a drawn contact normal, metres.
const NORMAL_LENGTH: f32 = 0.35;

/// A straight line between two world points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// One end, world metres.
    pub from: Vec3,
    /// The other end.
    pub to: Vec3,
    /// Its colour.
    pub colour: Rgb,
}

/// A dot at a world point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Marker {
    /// Where, world metres.
    pub position: Vec3,
    /// Its colour.
    pub colour: Rgb,
}

/// Everything the debug drawing shows this frame.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DebugGeometry {
    /// Lines: normals, box edges, joints, the drag spring.
    pub segments: Vec<Segment>,
    /// Dots: contact points, joint anchors, the drag target.
    pub markers: Vec<Marker>,
}

/// The debug geometry for the viewer's current toggles.
pub fn debug_geometry(viewer: &Viewer) -> DebugGeometry {
    let world = viewer.simulation.world();
    let mut geometry = DebugGeometry::default();
    if viewer.display.contacts {
        for contact in world.contacts().iter().chain(world.sleeping_contacts()) {
            let normal = contact.normal();
            for point in contact.points() {
                let colour = if point.separation < 0.0 {
                    CONTACT_POINT
                } else {
                    SPECULATIVE_POINT
                };
                geometry.markers.push(Marker {
                    position: point.position,
                    colour,
                });
                geometry.segments.push(Segment {
                    from: point.position,
                    to: point.position + NORMAL_LENGTH * normal,
                    colour: CONTACT_NORMAL,
                });
            }
        }
    }
    if viewer.display.bounding_boxes {
        for (_, body) in world.bodies() {
            if body.shape().is_bounded() {
                push_box_edges(&mut geometry.segments, &body.aabb());
            }
        }
    }
    if viewer.display.joints {
        let simulation = &viewer.simulation;
        push_joints(&mut geometry, world, simulation.initial_world());
    }
    if let Some(drag) = viewer.simulation.drag() {
        if let Some(anchor) = drag.anchor(world) {
            geometry.segments.push(Segment {
                from: anchor,
                to: drag.target(),
                colour: DRAG_SPRING,
            });
            geometry.markers.push(Marker {
                position: drag.target(),
                colour: DRAG_SPRING,
            });
        }
    }
    geometry
}

/// The 12 edges of `bounds`.
fn push_box_edges(segments: &mut Vec<Segment>, bounds: &Aabb) {
    for from in 0..8 {
        for axis_bit in [1, 2, 4] {
            if from & axis_bit == 0 {
                segments.push(Segment {
                    from: corner(bounds, from),
                    to: corner(bounds, from | axis_bit),
                    colour: BOUNDING_BOX,
                });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec2;
    use three_d::Key;

    use super::*;
    use crate::view::controls::action_for_key;
    use crate::view::simulation::Simulation;
    use rebond::scene::Scene;

    /// A box resting on a ground box, and a ball in the air.
    const SCENE: &str = r#"{"bodies": [
        {"name": "ground", "type": "static",
         "shape": {"type": "box", "half_extents": [20, 0.5, 20]}, "position": [0, -0.5, 0]},
        {"name": "crate", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]},
         "position": [0, 0.5, 0]},
        {"name": "ball", "shape": {"type": "sphere", "radius": 0.5}, "position": [3, 5, 0]}
    ]}"#;

    fn viewer_after_steps(steps: usize) -> Viewer {
        let scene = Scene::from_json(SCENE.as_bytes()).expect("a valid scene");
        let mut simulation = Simulation::new(&scene).expect("no character");
        for _ in 0..steps {
            simulation.step().expect("a step");
        }
        Viewer::new(simulation, Vec2::new(960.0, 540.0))
    }

    fn press(viewer: &mut Viewer, key: Key) {
        let action = action_for_key(key).expect("a bound key");
        viewer
            .apply(action, Vec2::new(960.0, 540.0))
            .expect("applied");
    }

    #[test]
    fn nothing_is_drawn_with_the_toggles_off() {
        assert_eq!(
            debug_geometry(&viewer_after_steps(5)),
            DebugGeometry::default()
        );
    }

    #[test]
    fn the_contacts_key_draws_points_with_upward_normals() {
        let mut viewer = viewer_after_steps(5);
        press(&mut viewer, Key::C);
        let geometry = debug_geometry(&viewer);
        assert!(geometry.markers.len() >= 4, "the crate's four corners");
        assert_eq!(geometry.markers.len(), geometry.segments.len());
        for segment in &geometry.segments {
            let direction = (segment.to - segment.from).normalize();
            assert!(direction.y.abs() > 0.99, "{direction}");
            assert!(
                segment.from.y.abs() < 0.05,
                "on the ground: {}",
                segment.from
            );
        }
    }

    #[test]
    fn the_bounding_box_key_draws_twelve_edges_a_body() {
        let mut viewer = viewer_after_steps(0);
        press(&mut viewer, Key::B);
        let geometry = debug_geometry(&viewer);
        assert_eq!(geometry.segments.len(), 3 * 12);
        assert!(geometry
            .segments
            .iter()
            .all(|segment| segment.colour == BOUNDING_BOX));
        let crate_edges = &geometry.segments[12..24];
        let length: f32 = crate_edges
            .iter()
            .map(|segment| (segment.to - segment.from).length())
            .sum();
        assert!(
            (length - 12.0).abs() < 1e-4,
            "a unit cube's edges: {length}"
        );
    }
}
