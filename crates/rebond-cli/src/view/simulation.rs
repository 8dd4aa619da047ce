//! The live simulation behind the viewer: a copy of the scene's world that steps in real time
//! (or slower, or one step at a time), can be reset, and takes the user's pokes: balls shot from
//! the camera and bodies dragged on a spring.

use std::collections::{HashMap, VecDeque};
use std::time::{Duration, Instant};

use rebond::{BodyDesc, BodyHandle, BodyType, RigidBody, Shape, World};

use super::drag::Drag;
use super::palette::{body_colour, Rgb};
use super::picking::{pick, Ray};
use super::player::Player;
use rebond::scene::Scene;

/// Simulated time per second of wall clock in slow motion.
pub const SLOW_MOTION_RATE: f64 = 0.25;
/// Most steps taken in one frame: when stepping is slower than real time, the simulation slows
/// down rather than falling ever further behind.
const MAX_STEPS_PER_FRAME: u32 = 8;
/// Steps averaged for the "ms per step" figure.
const TIMED_STEPS: usize = 60;
/// Radius of a shot ball, metres.
const BALL_RADIUS: f32 = 0.25;
/// Density of a shot ball, kg/m³ (about that of rubber).
const BALL_DENSITY: f32 = 1500.0;
/// Speed of a shot ball, m/s.
const BALL_SPEED: f32 = 25.0;

/// A body as the viewer knows it: its handle, name and colour.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyInfo {
    /// Its handle in the world.
    pub handle: BodyHandle,
    /// The scene's name for it (`ball1`, … for shot balls).
    pub name: String,
    /// The colour it is drawn in.
    pub colour: Rgb,
}

/// Counts shown in the overlay.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stats {
    /// Mean wall-clock time of the last steps, milliseconds (zero before the first step).
    pub ms_per_step: f64,
    /// Bodies in the world.
    pub bodies: usize,
    /// Contact points, speculative ones included.
    pub contacts: usize,
    /// Islands of awake bodies.
    pub islands: usize,
    /// Bodies asleep.
    pub sleeping: usize,
    /// Steps taken since the start or the last reset.
    pub steps: u64,
    /// Simulated time since the start or the last reset, seconds.
    pub time: f64,
}

/// The scene's world stepping under the viewer's control.
#[derive(Debug, Clone)]
pub struct Simulation {
    /// The world as loaded, to reset to.
    initial_world: World,
    /// The bodies of the scene as loaded.
    initial_bodies: Vec<BodyInfo>,
    /// The world as it is now.
    world: World,
    /// Its bodies, shot balls included.
    bodies: Vec<BodyInfo>,
    /// Seconds per step.
    timestep: f64,
    /// Whether time stands still.
    paused: bool,
    /// Whether time runs at [`SLOW_MOTION_RATE`].
    slow_motion: bool,
    /// Simulated time owed to the world: wall-clock time times the rate, less the steps taken.
    owed: f64,
    /// Steps since the start or the last reset.
    steps: u64,
    /// Wall-clock times of the last [`TIMED_STEPS`] steps.
    step_times: VecDeque<Duration>,
    /// The body held by the mouse, if any.
    drag: Option<Drag>,
    /// Balls shot so far, to name the next one.
    balls_shot: u32,
    /// Goes up whenever bodies are added or removed, so the renderer knows to rebuild.
    body_set_version: u64,
    /// The scene's character, moved by the keys before each step, if the scene names one.
    player: Option<Player>,
}

impl Simulation {
    /// A simulation of `scene` as loaded, running (not paused), at normal speed; an error when
    /// the settings of the character it names are refused.
    pub fn new(scene: &Scene) -> rebond::Result<Self> {
        let world = scene.world().clone();
        // The scene lists its bodies by name and the world by handle, both as references into
        // the same storage: their addresses pair them up.
        let handles: HashMap<*const RigidBody, BodyHandle> = scene
            .world()
            .bodies()
            .map(|(handle, body)| (body as *const RigidBody, handle))
            .collect();
        let bodies: Vec<BodyInfo> = scene
            .bodies()
            .filter_map(|(name, body)| {
                let handle = *handles.get(&(body as *const RigidBody))?;
                Some(BodyInfo {
                    handle,
                    name: name.to_owned(),
                    colour: body_colour(name, body.body_type()),
                })
            })
            .collect();
        let player = scene.character().map(Player::new).transpose()?;
        Ok(Self {
            initial_world: world.clone(),
            initial_bodies: bodies.clone(),
            world,
            bodies,
            timestep: scene.timestep().seconds,
            paused: false,
            slow_motion: false,
            owed: 0.0,
            steps: 0,
            step_times: VecDeque::with_capacity(TIMED_STEPS),
            drag: None,
            balls_shot: 0,
            body_set_version: 0,
            player,
        })
    }

    /// The world as it is now.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The world as loaded, which a reset goes back to. Scenes add their joints as they load, so
    /// it holds the poses each joint's angles count from.
    pub fn initial_world(&self) -> &World {
        &self.initial_world
    }

    /// Every body with its name and colour, scene bodies first, in scene order.
    pub fn bodies(&self) -> &[BodyInfo] {
        &self.bodies
    }

    /// Changes whenever bodies are added or removed.
    pub fn body_set_version(&self) -> u64 {
        self.body_set_version
    }

    /// Whether time stands still.
    pub fn is_paused(&self) -> bool {
        self.paused
    }

    /// Whether time runs at [`SLOW_MOTION_RATE`].
    pub fn is_slow_motion(&self) -> bool {
        self.slow_motion
    }

    /// The body being dragged and the spring's ends, if any.
    pub fn drag(&self) -> Option<&Drag> {
        self.drag.as_ref()
    }

    /// Pauses, or resumes.
    pub fn toggle_pause(&mut self) {
        self.paused = !self.paused;
        self.owed = 0.0;
    }

    /// Switches slow motion on or off.
    pub fn toggle_slow_motion(&mut self) {
        self.slow_motion = !self.slow_motion;
    }

    /// Pauses (if running) and takes exactly one step.
    pub fn step_once(&mut self) -> rebond::Result<()> {
        self.paused = true;
        self.owed = 0.0;
        self.step()
    }

    /// The scene's character, if it names one.
    pub fn player_mut(&mut self) -> Option<&mut Player> {
        self.player.as_mut()
    }

    /// Back to the scene as loaded: shot balls go, the drag ends, the character stands where it
    /// started; pause and speed stay.
    pub fn reset(&mut self) {
        if let Some(player) = &mut self.player {
            player.reset();
        }
        self.world = self.initial_world.clone();
        self.bodies = self.initial_bodies.clone();
        self.drag = None;
        self.owed = 0.0;
        self.steps = 0;
        self.step_times.clear();
        self.body_set_version += 1;
    }

    /// Lets `elapsed` of wall-clock time pass: takes the steps it is worth at the current rate
    /// (none while paused), at most a few per frame.
    pub fn advance(&mut self, elapsed: Duration) -> rebond::Result<()> {
        if self.paused {
            return Ok(());
        }
        let rate = if self.slow_motion {
            SLOW_MOTION_RATE
        } else {
            1.0
        };
        self.owed += elapsed.as_secs_f64() * rate;
        let mut taken = 0;
        while self.owed >= self.timestep && taken < MAX_STEPS_PER_FRAME {
            self.step()?;
            self.owed -= self.timestep;
            taken += 1;
        }
        self.owed = self.owed.min(self.timestep);
        Ok(())
    }

    /// One step of the world, the character moved first, with the drag spring acting during it.
    pub fn step(&mut self) -> rebond::Result<()> {
        if let Some(player) = &mut self.player {
            player.before_step(&mut self.world, self.timestep as f32)?;
        }
        if let Some(drag) = &self.drag {
            if drag.apply(&mut self.world, self.timestep as f32).is_err() {
                self.drag = None;
            }
        }
        let started = Instant::now();
        self.world.step(self.timestep as f32)?;
        if self.step_times.len() == TIMED_STEPS {
            self.step_times.pop_front();
        }
        self.step_times.push_back(started.elapsed());
        self.steps += 1;
        Ok(())
    }

    /// Steps since the start or the last reset.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// The overlay's counts.
    pub fn stats(&self) -> Stats {
        let timed = self.step_times.len().max(1) as f64;
        Stats {
            ms_per_step: self.step_times.iter().sum::<Duration>().as_secs_f64() * 1000.0 / timed,
            bodies: self.world.body_count(),
            contacts: self.world.contact_count(),
            islands: self.world.island_count(),
            sleeping: self.world.sleeping_body_count(),
            steps: self.steps,
            time: self.steps as f64 * self.timestep,
        }
    }

    /// Shoots a ball along `ray` from its origin at [`BALL_SPEED`].
    pub fn shoot(&mut self, ray: &Ray) -> rebond::Result<()> {
        let shape = Shape::sphere(BALL_RADIUS)?;
        let handle = self.world.add_body(
            BodyDesc::dynamic(shape)
                .position(ray.origin + ray.direction * (BALL_RADIUS * 2.0))
                .linear_velocity(ray.direction * BALL_SPEED)
                .density(BALL_DENSITY)
                .restitution(0.3),
        )?;
        self.balls_shot += 1;
        let name = format!("ball{}", self.balls_shot);
        self.bodies.push(BodyInfo {
            handle,
            colour: body_colour(&name, BodyType::Dynamic),
            name,
        });
        self.body_set_version += 1;
        Ok(())
    }

    /// Starts dragging the dynamic body under `ray`, if there is one in front of anything else;
    /// returns whether a drag started.
    pub fn begin_drag(&mut self, ray: &Ray) -> bool {
        self.drag = pick(&self.world, ray).and_then(|hit| {
            let body = self.world.body(hit.body).ok()?;
            (body.body_type() == BodyType::Dynamic).then(|| {
                Drag::new(
                    hit.body,
                    body.pose().inverse_transform_point(ray.at(hit.distance)),
                    ray.at(hit.distance),
                    ray.direction,
                )
            })
        });
        self.drag.is_some()
    }

    /// Moves the dragged point's target to where `ray` crosses the drag plane.
    pub fn move_drag(&mut self, ray: &Ray) {
        if let Some(drag) = &mut self.drag {
            drag.aim(ray);
        }
    }

    /// Lets go of the dragged body.
    pub fn end_drag(&mut self) {
        self.drag = None;
    }
}

#[cfg(test)]
mod tests {
    use rebond::Vec3;

    use super::*;

    /// A ground box and two balls resting apart on it, the second one named.
    const SCENE: &str = r#"{"bodies": [
        {"name": "ground", "type": "static",
         "shape": {"type": "box", "half_extents": [20, 0.5, 20]}, "position": [0, -0.5, 0]},
        {"shape": {"type": "sphere", "radius": 0.5}, "position": [0, 3, 0]},
        {"name": "crate", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]},
         "position": [3, 0.5, 0]}
    ]}"#;

    fn simulation() -> Simulation {
        Simulation::new(&Scene::from_json(SCENE.as_bytes()).expect("a valid scene"))
            .expect("no character")
    }

    fn ball_height(simulation: &Simulation) -> f32 {
        let ball = simulation.bodies()[1].handle;
        simulation
            .world()
            .body(ball)
            .expect("the ball")
            .position()
            .y
    }

    #[test]
    fn bodies_keep_their_scene_names_and_colours() {
        let simulation = simulation();
        let names: Vec<&str> = simulation
            .bodies()
            .iter()
            .map(|body| body.name.as_str())
            .collect();
        assert_eq!(names, ["ground", "body1", "crate"]);
        assert_eq!(
            simulation.bodies()[0].colour,
            super::super::palette::STATIC_BODY
        );
        assert_eq!(
            simulation.bodies()[2].colour,
            body_colour("crate", BodyType::Dynamic)
        );
    }

    #[test]
    fn advance_follows_the_clock_pause_and_slow_motion() {
        let mut simulation = simulation();
        simulation
            .advance(Duration::from_millis(55))
            .expect("steps");
        assert_eq!(
            simulation.steps(),
            3,
            "55 ms is 3 steps of 1/60 s and a bit"
        );
        simulation.toggle_pause();
        assert!(simulation.is_paused());
        simulation
            .advance(Duration::from_secs(1))
            .expect("no steps");
        assert_eq!(simulation.steps(), 3, "paused");
        simulation.toggle_pause();
        simulation.toggle_slow_motion();
        assert!(simulation.is_slow_motion());
        for _ in 0..9 {
            simulation
                .advance(Duration::from_secs_f64(1.0 / 60.0))
                .expect("steps");
        }
        assert_eq!(simulation.steps(), 3 + 2, "a quarter of 9 frames of 1/60 s");
        simulation.advance(Duration::from_secs(10)).expect("steps");
        assert_eq!(
            simulation.steps(),
            5 + MAX_STEPS_PER_FRAME as u64,
            "capped per frame"
        );
    }

    #[test]
    fn step_once_pauses_and_takes_one_step() {
        let mut simulation = simulation();
        let start = ball_height(&simulation);
        simulation.step_once().expect("a step");
        assert!(simulation.is_paused());
        assert_eq!(simulation.steps(), 1);
        assert!(ball_height(&simulation) < start, "the ball falls");
        simulation.step_once().expect("a step");
        assert_eq!(simulation.steps(), 2);
    }

    #[test]
    fn reset_restores_the_scene_and_removes_shot_balls() {
        let mut simulation = simulation();
        let start = ball_height(&simulation);
        let version = simulation.body_set_version();
        let ray = Ray {
            origin: Vec3::new(0.0, 2.0, 10.0),
            direction: -Vec3::Z,
        };
        simulation.shoot(&ray).expect("a ball");
        assert_eq!(simulation.world().body_count(), 4);
        assert_eq!(simulation.bodies()[3].name, "ball1");
        assert_ne!(simulation.body_set_version(), version);
        for _ in 0..30 {
            simulation.step().expect("a step");
        }
        simulation.reset();
        assert_eq!(simulation.world().body_count(), 3);
        assert_eq!(simulation.bodies().len(), 3);
        assert_eq!(simulation.steps(), 0);
        assert_eq!(ball_height(&simulation), start);
    }

    #[test]
    fn a_shot_ball_flies_along_the_ray() {
        let mut simulation = simulation();
        let ray = Ray {
            origin: Vec3::new(0.0, 2.0, 10.0),
            direction: -Vec3::Z,
        };
        simulation.shoot(&ray).expect("a ball");
        let ball = simulation
            .world()
            .body(simulation.bodies()[3].handle)
            .expect("the ball");
        assert_eq!(ball.linear_velocity(), -Vec3::Z * BALL_SPEED);
        assert!(ball.position().z < 10.0);
    }

    #[test]
    fn dragging_pulls_a_dynamic_body_toward_the_cursor() {
        let mut simulation = simulation();
        let toward_crate = Ray {
            origin: Vec3::new(3.0, 0.5, 10.0),
            direction: -Vec3::Z,
        };
        assert!(simulation.begin_drag(&toward_crate));
        let crate_handle = simulation.bodies()[2].handle;
        assert_eq!(simulation.drag().map(Drag::body), Some(crate_handle));
        let above = Ray {
            origin: Vec3::new(3.0, 2.5, 10.0),
            direction: -Vec3::Z,
        };
        simulation.move_drag(&above);
        for _ in 0..60 {
            simulation.step().expect("a step");
        }
        let lifted = simulation
            .world()
            .body(crate_handle)
            .expect("the crate")
            .position();
        assert!(lifted.y > 1.5, "the crate hangs near the cursor: {lifted}");
        simulation.end_drag();
        assert!(simulation.drag().is_none());
        let toward_ground = Ray {
            origin: Vec3::new(-5.0, 5.0, 0.0),
            direction: -Vec3::Y,
        };
        assert!(
            !simulation.begin_drag(&toward_ground),
            "static bodies stay put"
        );
    }
}
