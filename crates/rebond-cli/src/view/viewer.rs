//! The viewer's state apart from drawing: the simulation, the camera, what is shown, and how
//! keys and mouse gestures change them.

use glam::Vec2;
use rebond::{Aabb, BodyType, Vec3};
use three_d::{Event, MouseButton, PhysicalPoint};

use super::camera::OrbitCamera;
use super::controls::{action_for_key, Action, JUMP_KEY, WALK_KEYS};
use super::simulation::Simulation;

/// What is drawn besides the bodies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DisplayOptions {
    /// Contact points and their normals.
    pub contacts: bool,
    /// Each body's bounding box.
    pub bounding_boxes: bool,
    /// Sleeping bodies in another tint.
    pub sleeping_tint: bool,
    /// The help overlay.
    pub help: bool,
    /// Joints: anchors, axes, limits, gaps.
    pub joints: bool,
}

impl Default for DisplayOptions {
    /// Only joints: they are part of how the scene is built, and otherwise invisible.
    fn default() -> Self {
        Self {
            contacts: false,
            bounding_boxes: false,
            sleeping_tint: false,
            help: false,
            joints: true,
        }
    }
}

/// What a held mouse button is doing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Gesture {
    /// Turning the camera about its target.
    Turning,
    /// Sliding the camera.
    Panning,
    /// Pulling a body.
    Dragging,
}

/// Everything the user sees and steers.
#[derive(Debug, Clone)]
pub struct Viewer {
    /// The live simulation.
    pub simulation: Simulation,
    /// The camera.
    pub camera: OrbitCamera,
    /// The view the scene opened with.
    initial_camera: OrbitCamera,
    /// What is drawn.
    pub display: DisplayOptions,
    /// What the held mouse button is doing, if one is held.
    gesture: Option<Gesture>,
    /// The mouse position, physical pixels from the top left, once known.
    cursor: Option<Vec2>,
    /// Whether the user asked to close the viewer.
    quit: bool,
    /// Which of [`WALK_KEYS`] are held down.
    walk_keys_held: [bool; 4],
}

impl Viewer {
    /// A viewer of `simulation` with the camera framing its moving bodies on a screen of
    /// `viewport` pixels.
    pub fn new(simulation: Simulation, viewport: Vec2) -> Self {
        let camera = OrbitCamera::framing(&scene_bounds(&simulation), viewport);
        Self {
            simulation,
            camera,
            initial_camera: camera,
            display: DisplayOptions::default(),
            gesture: None,
            cursor: None,
            quit: false,
            walk_keys_held: [false; 4],
        }
    }

    /// Whether the user asked to close the viewer.
    pub fn should_quit(&self) -> bool {
        self.quit
    }

    /// Does what `action` asks; `viewport` is the screen size in physical pixels.
    pub fn apply(&mut self, action: Action, viewport: Vec2) -> rebond::Result<()> {
        match action {
            Action::TogglePause => self.simulation.toggle_pause(),
            Action::StepOnce => self.simulation.step_once()?,
            Action::Reset => {
                self.simulation.reset();
                if self.gesture == Some(Gesture::Dragging) {
                    self.gesture = None;
                }
            }
            Action::ToggleSlowMotion => self.simulation.toggle_slow_motion(),
            Action::ToggleContacts => self.display.contacts = !self.display.contacts,
            Action::ToggleBoundingBoxes => {
                self.display.bounding_boxes = !self.display.bounding_boxes;
            }
            Action::ToggleJoints => self.display.joints = !self.display.joints,
            Action::ToggleSleepingTint => {
                self.display.sleeping_tint = !self.display.sleeping_tint;
            }
            Action::ShootBall => {
                let aim = self.cursor.unwrap_or(viewport * 0.5);
                self.simulation.shoot(&self.camera.ray(aim, viewport))?;
            }
            Action::ResetCamera => self.camera = self.initial_camera,
            Action::ToggleHelp => self.display.help = !self.display.help,
            Action::Quit => self.quit = true,
        }
        Ok(())
    }

    /// Answers one input event; `viewport` is the screen size in physical pixels.
    pub fn handle_event(&mut self, event: &Event, viewport: Vec2) -> rebond::Result<()> {
        match event {
            // The guard hands the character its keys; any other key does its action.
            Event::KeyPress { kind, .. } if !self.drive_character(*kind, true) => {
                if let Some(action) = action_for_key(*kind) {
                    self.apply(action, viewport)?;
                }
            }
            Event::KeyRelease { kind, .. } => {
                self.drive_character(*kind, false);
            }
            Event::MousePress {
                button,
                position,
                modifiers,
                ..
            } => {
                let cursor = from_bottom_left(*position, viewport);
                self.cursor = Some(cursor);
                self.gesture = Some(match button {
                    MouseButton::Left if !modifiers.shift => {
                        let ray = self.camera.ray(cursor, viewport);
                        if self.simulation.begin_drag(&ray) {
                            Gesture::Dragging
                        } else {
                            Gesture::Turning
                        }
                    }
                    _ => Gesture::Panning,
                });
            }
            Event::MouseRelease { .. } => {
                if self.gesture == Some(Gesture::Dragging) {
                    self.simulation.end_drag();
                }
                self.gesture = None;
            }
            Event::MouseMotion { position, .. } => {
                let cursor = from_bottom_left(*position, viewport);
                let delta = self.cursor.map_or(Vec2::ZERO, |last| cursor - last);
                self.cursor = Some(cursor);
                match self.gesture {
                    Some(Gesture::Turning) => self.camera.turn(delta),
                    Some(Gesture::Panning) => self.camera.pan(delta, viewport.y),
                    Some(Gesture::Dragging) => {
                        self.simulation
                            .move_drag(&self.camera.ray(cursor, viewport));
                    }
                    None => {}
                }
            }
            Event::MouseWheel { delta, .. } => {
                self.camera.zoom(delta.1);
                if self.gesture == Some(Gesture::Dragging) {
                    if let Some(cursor) = self.cursor {
                        self.simulation
                            .move_drag(&self.camera.ray(cursor, viewport));
                    }
                }
            }
            _ => {}
        }
        self.steer_character();
        Ok(())
    }

    /// Passes a key going down (`pressed`) or up to the scene's character; returns whether the
    /// key is one of the character's (none are without a character).
    fn drive_character(&mut self, key: three_d::Key, pressed: bool) -> bool {
        let Some(player) = self.simulation.player_mut() else {
            return false;
        };
        if key == JUMP_KEY {
            if pressed {
                player.jump();
            }
            return true;
        }
        match WALK_KEYS
            .iter()
            .position(|(walk_key, _, _)| *walk_key == key)
        {
            Some(index) => {
                self.walk_keys_held[index] = pressed;
                true
            }
            None => false,
        }
    }

    /// Points the character's walk where the held keys ask, as the camera now faces.
    fn steer_character(&mut self) {
        let (heading, right) = self.camera.ground_heading_and_right();
        let Some(player) = self.simulation.player_mut() else {
            return;
        };
        let direction = (WALK_KEYS.iter().zip(self.walk_keys_held))
            .filter(|(_, held)| *held)
            .fold(Vec3::ZERO, |sum, ((_, forward, across), _)| {
                sum + heading * *forward + right * *across
            });
        player.set_walk(direction);
    }
}

/// A point from the bottom-left origin of three-d's events to the top-left one used here.
fn from_bottom_left(position: PhysicalPoint, viewport: Vec2) -> Vec2 {
    Vec2::new(position.x, viewport.y - position.y)
}

/// The boxes the camera frames at the start: the moving bodies', or every bounded body's when
/// nothing moves, or a few metres around the origin when there is nothing at all.
fn scene_bounds(simulation: &Simulation) -> Vec<Aabb> {
    let world = simulation.world();
    let bounded = || world.bodies().filter(|(_, body)| body.shape().is_bounded());
    let moving: Vec<Aabb> = bounded()
        .filter(|(_, body)| body.body_type() != BodyType::Static)
        .map(|(_, body)| body.aabb())
        .collect();
    if !moving.is_empty() {
        return moving;
    }
    let all: Vec<Aabb> = bounded().map(|(_, body)| body.aabb()).collect();
    if !all.is_empty() {
        return all;
    }
    vec![Aabb::from_center_half_extents(Vec3::ZERO, Vec3::splat(3.0))]
}

#[cfg(test)]
mod tests {
    use three_d::{Key, Modifiers};

    use super::*;
    use rebond::scene::Scene;

    const VIEWPORT: Vec2 = Vec2::new(960.0, 540.0);

    /// A ground box, a crate in the middle and a ball beside it.
    const SCENE: &str = r#"{"bodies": [
        {"name": "ground", "type": "static",
         "shape": {"type": "box", "half_extents": [20, 0.5, 20]}, "position": [0, -0.5, 0]},
        {"name": "crate", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]},
         "position": [0, 0.5, 0]},
        {"name": "ball", "shape": {"type": "sphere", "radius": 0.5}, "position": [3, 0.5, 0]}
    ]}"#;

    fn viewer() -> Viewer {
        let scene = Scene::from_json(SCENE.as_bytes()).expect("a valid scene");
        Viewer::new(Simulation::new(&scene).expect("no character"), VIEWPORT)
    }

    fn press(viewer: &mut Viewer, key: Key) {
        send_key(viewer, key, true);
    }

    fn release_key(viewer: &mut Viewer, key: Key) {
        send_key(viewer, key, false);
    }

    /// Sends `key` going down, or up.
    fn send_key(viewer: &mut Viewer, kind: Key, down: bool) {
        let modifiers = Modifiers::default();
        let event = if down {
            Event::KeyPress {
                kind,
                modifiers,
                handled: false,
            }
        } else {
            Event::KeyRelease {
                kind,
                modifiers,
                handled: false,
            }
        };
        viewer.handle_event(&event, VIEWPORT).expect("handled");
    }

    /// three-d's position of the top-left-based `pixel`.
    fn position(pixel: Vec2) -> PhysicalPoint {
        PhysicalPoint {
            x: pixel.x,
            y: VIEWPORT.y - pixel.y,
        }
    }

    fn mouse(viewer: &mut Viewer, button: MouseButton, from: Vec2, to: Vec2, shift: bool) {
        let modifiers = Modifiers {
            shift,
            ..Modifiers::default()
        };
        let events = [
            Event::MousePress {
                button,
                position: position(from),
                modifiers,
                handled: false,
            },
            Event::MouseMotion {
                button: Some(button),
                delta: (to - from).into(),
                position: position(to),
                modifiers,
                handled: false,
            },
        ];
        for event in &events {
            viewer.handle_event(event, VIEWPORT).expect("handled");
        }
    }

    fn release(viewer: &mut Viewer, at: Vec2) {
        let event = Event::MouseRelease {
            button: MouseButton::Left,
            position: position(at),
            modifiers: Modifiers::default(),
            handled: false,
        };
        viewer.handle_event(&event, VIEWPORT).expect("handled");
    }

    #[test]
    fn keys_toggle_what_is_shown_and_quit() {
        let mut viewer = viewer();
        assert_eq!(viewer.display, DisplayOptions::default());
        for key in [Key::C, Key::B, Key::Z, Key::H, Key::J] {
            press(&mut viewer, key);
        }
        let all_but_joints = DisplayOptions {
            contacts: true,
            bounding_boxes: true,
            sleeping_tint: true,
            help: true,
            joints: false,
        };
        assert_eq!(viewer.display, all_but_joints);
        press(&mut viewer, Key::F1);
        assert!(!viewer.display.help);
        assert!(!viewer.should_quit());
        press(&mut viewer, Key::Q);
        assert!(viewer.should_quit());
        let mut other = self::viewer();
        press(&mut other, Key::Escape);
        assert!(other.should_quit());
    }

    #[test]
    fn keys_pause_step_slow_down_and_reset() {
        let mut viewer = viewer();
        press(&mut viewer, Key::Space);
        assert!(viewer.simulation.is_paused());
        press(&mut viewer, Key::Space);
        assert!(!viewer.simulation.is_paused());
        press(&mut viewer, Key::N);
        assert!(viewer.simulation.is_paused());
        assert_eq!(viewer.simulation.steps(), 1);
        press(&mut viewer, Key::S);
        assert!(viewer.simulation.is_slow_motion());
        press(&mut viewer, Key::F);
        assert_eq!(viewer.simulation.world().body_count(), 4, "a ball was shot");
        press(&mut viewer, Key::R);
        assert_eq!(viewer.simulation.world().body_count(), 3);
        assert_eq!(viewer.simulation.steps(), 0);
    }

    #[test]
    fn wasd_walks_the_character_as_the_camera_faces_and_space_jumps() {
        let scene = Scene::from_json(
            br#"{"character": {"body": "player", "walk_speed": 3},
            "bodies": [
            {"name": "ground", "type": "static",
             "shape": {"type": "box", "half_extents": [20, 0.5, 20]}, "position": [0, -0.5, 0]},
            {"name": "player", "type": "kinematic",
             "shape": {"type": "capsule", "radius": 0.3, "half_height": 0.5},
             "position": [0, 0.81, 0]}
        ]}"#,
        )
        .expect("a valid scene");
        let mut viewer = Viewer::new(Simulation::new(&scene).expect("valid"), VIEWPORT);
        let player = scene.body_handle("player").expect("named");
        let position = |viewer: &Viewer| {
            let body = viewer.simulation.world().body(player).expect("the player");
            body.position()
        };
        let (heading, right) = viewer.camera.ground_heading_and_right();
        // W and D held for 20 steps at 3 m/s: 1 m along the heading plus the right, halved.
        press(&mut viewer, Key::W);
        press(&mut viewer, Key::D);
        for _ in 0..20 {
            viewer.simulation.step().expect("a step");
        }
        let walked = position(&viewer) - Vec3::new(0.0, 0.81, 0.0);
        let expected = (heading + right).normalize();
        assert!(
            (walked - expected).length() < 1e-3,
            "{walked} not {expected}"
        );
        release_key(&mut viewer, Key::W);
        release_key(&mut viewer, Key::D);
        // Space jumps rather than pausing; S walks rather than slowing down; P and M do those.
        press(&mut viewer, Key::Space);
        press(&mut viewer, Key::S);
        assert!(!viewer.simulation.is_paused() && !viewer.simulation.is_slow_motion());
        for _ in 0..10 {
            viewer.simulation.step().expect("a step");
        }
        assert!(position(&viewer).y > 1.2, "jumped to {}", position(&viewer));
        release_key(&mut viewer, Key::S);
        press(&mut viewer, Key::P);
        press(&mut viewer, Key::M);
        assert!(viewer.simulation.is_paused() && viewer.simulation.is_slow_motion());
        // A reset puts the character back where it started.
        press(&mut viewer, Key::R);
        assert_eq!(position(&viewer), Vec3::new(0.0, 0.81, 0.0));
    }

    #[test]
    fn a_shot_ball_flies_toward_the_cursor() {
        let mut viewer = viewer();
        let crate_pixel = viewer
            .camera
            .project(Vec3::new(0.0, 0.5, 0.0), VIEWPORT)
            .expect("the crate is on screen");
        let motion = Event::MouseMotion {
            button: None,
            delta: (0.0, 0.0),
            position: position(crate_pixel),
            modifiers: Modifiers::default(),
            handled: false,
        };
        viewer.handle_event(&motion, VIEWPORT).expect("handled");
        press(&mut viewer, Key::F);
        let ball = viewer.simulation.bodies()[3].handle;
        let ball = viewer.simulation.world().body(ball).expect("the ball");
        let toward_crate = (Vec3::new(0.0, 0.5, 0.0) - ball.position()).normalize();
        assert!(ball.linear_velocity().normalize().dot(toward_crate) > 0.999);
    }

    #[test]
    fn the_mouse_turns_pans_zooms_and_the_view_resets() {
        let mut viewer = viewer();
        let start = viewer.camera;
        let corner = Vec2::new(20.0, 20.0);
        mouse(
            &mut viewer,
            MouseButton::Left,
            corner,
            corner + Vec2::new(50.0, 0.0),
            false,
        );
        release(&mut viewer, corner);
        assert_ne!(viewer.camera.yaw, start.yaw, "left drag on nothing turns");
        assert_eq!(viewer.camera.target, start.target);
        press(&mut viewer, Key::V);
        assert_eq!(viewer.camera, start);
        for (button, shift) in [
            (MouseButton::Right, false),
            (MouseButton::Middle, false),
            (MouseButton::Left, true),
        ] {
            mouse(
                &mut viewer,
                button,
                corner,
                corner + Vec2::new(0.0, 30.0),
                shift,
            );
            release(&mut viewer, corner);
            assert_ne!(viewer.camera.target, start.target, "{button:?} pans");
            assert_eq!(viewer.camera.yaw, start.yaw);
            press(&mut viewer, Key::V);
        }
        let wheel = Event::MouseWheel {
            delta: (0.0, 24.0),
            position: position(corner),
            modifiers: Modifiers::default(),
            handled: false,
        };
        viewer.handle_event(&wheel, VIEWPORT).expect("handled");
        assert!(viewer.camera.distance < start.distance);
    }

    #[test]
    fn left_drag_on_a_body_pulls_it_and_leaves_the_camera() {
        let mut viewer = viewer();
        let start = viewer.camera;
        let ball_pixel = viewer
            .camera
            .project(Vec3::new(3.0, 0.5, 0.0), VIEWPORT)
            .expect("the ball is on screen");
        let above = ball_pixel - Vec2::new(0.0, 100.0);
        mouse(&mut viewer, MouseButton::Left, ball_pixel, above, false);
        assert_eq!(viewer.camera, start);
        let drag = *viewer.simulation.drag().expect("dragging");
        assert_eq!(drag.body(), viewer.simulation.bodies()[2].handle);
        for _ in 0..60 {
            viewer.simulation.step().expect("a step");
        }
        assert!(drag.target().y > 1.0, "the cursor is well above the ball");
        let anchor = drag.anchor(viewer.simulation.world()).expect("the ball");
        assert!(
            (anchor - drag.target()).length() < 0.1,
            "{anchor} follows {}",
            drag.target()
        );
        release(&mut viewer, above);
        assert!(viewer.simulation.drag().is_none());
    }
}
