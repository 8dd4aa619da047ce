//! The scene's character under the keyboard: each step the viewer walks it along the direction
//! the keys ask for at the scene's walking speed, adds the vertical speed of a jump or a fall,
//! and moves it with the engine's character controller before the world steps.

use rebond::character::CharacterController;
use rebond::hooks::ONE_WAY_MAX_DEPTH;
use rebond::scene::SceneCharacter;
use rebond::{BodyHandle, QueryFilter, RigidBody, Vec3, World};

/// The character a scene names, and what the keys ask of it.
#[derive(Debug, Clone)]
pub struct Player {
    /// The scene's character: its body, speeds and controller settings.
    character: SceneCharacter,
    /// The controller, which keeps the last move (the ground it stands on).
    controller: CharacterController,
    /// The controller as made, with no last move, for a reset.
    fresh_controller: CharacterController,
    /// The speed along `up`, m/s: a jump's, less what gravity took since; zero on the ground.
    vertical_speed: f32,
    /// Where to walk on the ground plane: a unit vector, or zero to stand.
    walk: Vec3,
    /// Whether a jump was asked for since the last step.
    jump: bool,
}

impl Player {
    /// The scene's character, standing still.
    pub fn new(character: &SceneCharacter) -> rebond::Result<Self> {
        let controller = CharacterController::new(character.settings)?;
        Ok(Self {
            character: *character,
            fresh_controller: controller.clone(),
            controller,
            vertical_speed: 0.0,
            walk: Vec3::ZERO,
            jump: false,
        })
    }

    /// Walks along `direction` (its part across `up`, normalised; zero stands still) from the
    /// next step on.
    pub fn set_walk(&mut self, direction: Vec3) {
        let up = self.controller.settings().up;
        self.walk = (direction - up * direction.dot(up)).normalize_or_zero();
    }

    /// Jumps at the next step, if the character then stands on the ground.
    pub fn jump(&mut self) {
        self.jump = true;
    }

    /// Back to standing still, as loaded; what the keys ask stays.
    pub fn reset(&mut self) {
        self.controller = self.fresh_controller.clone();
        self.vertical_speed = 0.0;
    }

    /// Moves the character over a step of `dt` seconds, to be called before the world steps:
    /// `(walk · walk_speed + up · vertical_speed) · dt`, through the controller. A jump on the
    /// ground sets the vertical speed to `jump_speed`; in the air, gravity's part along `up`
    /// changes it by `g · dt` a step; on the ground it is zero.
    pub fn before_step(&mut self, world: &mut World, dt: f32) -> rebond::Result<()> {
        let up = self.controller.settings().up;
        if std::mem::take(&mut self.jump) && self.controller.last_move().is_grounded() {
            self.vertical_speed = self.character.jump_speed;
        }
        let desired = (self.walk * self.character.walk_speed + up * self.vertical_speed) * dt;
        let feet = lowest_along(world.body(self.character.body)?, up);
        let solid = |_: BodyHandle, body: &RigidBody| stands_on(body, up, feet);
        let filter = QueryFilter {
            predicate: Some(&solid),
            ..QueryFilter::default()
        };
        let moved = self
            .controller
            .move_body(world, self.character.body, desired, dt, &filter)?;
        self.vertical_speed = if moved.is_grounded() {
            0.0
        } else {
            self.vertical_speed + world.settings().gravity.dot(up) * dt
        };
        Ok(())
    }
}

/// The lowest reach of `body` along `up`, metres: the smallest `p·up` over its bounding box.
fn lowest_along(body: &RigidBody, up: Vec3) -> f32 {
    let aabb = body.aabb();
    let (center, half) = (aabb.center(), aabb.half_extents());
    center.dot(up) - half.dot(up.abs())
}

/// Whether the character, its lowest point at `feet` along `up`, meets `body`. A one-way body
/// whose direction is within 45° of `up` (a ledge jumped onto from below) is met only from above:
/// when the character's feet are no deeper below its top than the engine's one-way depth
/// (`hooks::ONE_WAY_MAX_DEPTH`), as the engine's contacts meet it. Every other body is solid.
fn stands_on(body: &RigidBody, up: Vec3, feet: f32) -> bool {
    let Some(direction) = body.one_way() else {
        return true;
    };
    let direction = body.rotation() * direction;
    if direction.dot(up) < std::f32::consts::FRAC_1_SQRT_2 {
        return true;
    }
    let aabb = body.aabb();
    let top = aabb.center().dot(up) + aabb.half_extents().dot(up.abs());
    feet >= top - ONE_WAY_MAX_DEPTH
}

#[cfg(test)]
mod tests {
    use super::*;
    use rebond::scene::Scene;

    /// A ground, a one-way ledge 1.2 m up (top face), and a character under it.
    const SCENE: &str = r#"{
        "character": {"body": "player", "walk_speed": 4, "jump_speed": 6},
        "bodies": [
        {"name": "ground", "type": "static",
         "shape": {"type": "box", "half_extents": [20, 0.5, 20]}, "position": [0, -0.5, 0]},
        {"name": "ledge", "type": "static", "one_way": [0, 1, 0],
         "shape": {"type": "box", "half_extents": [2, 0.05, 2]}, "position": [0, 1.15, 0]},
        {"name": "player", "type": "kinematic",
         "shape": {"type": "capsule", "radius": 0.3, "half_height": 0.5},
         "position": [0, 0.81, 0]}
    ]}"#;

    /// Steps `scene` `steps` times with the player moved first; returns the highest and the last
    /// height of its centre.
    fn run(scene: &mut Scene, player: &mut Player, steps: usize) -> (f32, f32) {
        let dt = scene.timestep().engine_seconds;
        let mut highest = f32::NEG_INFINITY;
        for _ in 0..steps {
            player.before_step(scene.world_mut(), dt).expect("a move");
            scene.step().expect("a step");
            highest = highest.max(position(scene).y);
        }
        (highest, position(scene).y)
    }

    /// Where the player's centre is.
    fn position(scene: &Scene) -> Vec3 {
        let player = scene.body_handle("player").expect("named");
        scene.world().body(player).expect("the player").position()
    }

    #[test]
    fn a_jump_rises_through_a_one_way_ledge_and_lands_on_it() {
        // Jumping at 6 m/s under g = 9.81 m/s² rises v² / 2g = 1.835 m in continuous time; the
        // steps integrate the speed after each move, so the peak of the centre is within one
        // step's rise (0.1 m) above 0.81 + 1.835 m. It passes up through the ledge (its feet
        // reach 2.34 m, above the top at 1.2 m) and lands on it: the centre ends 0.81 m above
        // the ledge's top, less at most the offset (1 cm).
        let mut scene = Scene::from_json(SCENE.as_bytes()).expect("a valid scene");
        let mut player = Player::new(scene.character().expect("a character")).expect("valid");
        run(&mut scene, &mut player, 2);
        player.jump();
        let (highest, last) = run(&mut scene, &mut player, 120);
        let peak = 0.81 + 6.0f32 * 6.0 / (2.0 * 9.81);
        assert!(highest > peak - 0.1 && highest < peak + 0.1, "{highest}");
        assert!(last > 1.2 + 0.80 && last < 1.2 + 0.811, "{last}");
        // Walking takes the character along the ground plane at the walking speed.
        player.set_walk(Vec3::new(1.0, 5.0, 0.0));
        let start = position(&scene);
        run(&mut scene, &mut player, 15);
        let end = position(&scene);
        assert!(
            ((end - start) - Vec3::new(1.0, 0.0, 0.0)).length() < 1e-3,
            "{end}"
        );
    }

    #[test]
    fn a_jump_in_the_air_is_ignored() {
        let mut scene = Scene::from_json(SCENE.as_bytes()).expect("a valid scene");
        let body = scene.body_handle("player").expect("named");
        scene
            .world_mut()
            .body_mut(body)
            .expect("the player")
            .set_position(Vec3::new(5.0, 3.0, 0.0))
            .expect("a position");
        let mut player = Player::new(scene.character().expect("a character")).expect("valid");
        player.jump();
        // The first move starts the fall at zero speed; the jump never lifts it.
        let (highest, last) = run(&mut scene, &mut player, 2);
        assert!(highest <= 3.0 && last < 3.0, "it falls: {highest}, {last}");
    }

    /// The built-in `platformer` scene with its player moved to `start`, and the player.
    fn platformer_from(start: Vec3) -> (Scene, Player) {
        let json = rebond::scene::builtin("platformer").expect("built in").json;
        let mut scene = Scene::from_json(json.as_bytes()).expect("a valid scene");
        let player = Player::new(scene.character().expect("a character")).expect("valid");
        let body = scene.body_handle("player").expect("named");
        let world = scene.world_mut();
        let body = world.body_mut(body).expect("the player");
        body.set_position(start).expect("a position");
        (scene, player)
    }

    #[test]
    fn the_platformers_character_jumps_up_both_ledges() {
        // From the ground under the first ledge (top 1.2 m) a jump at 6 m/s rises 1.83 m, through
        // it, and lands on it; from there a jump while walking 2.67 m toward -x (40 steps at
        // 4 m/s) clears the second ledge's edge (x = -5) 1.77 m up and lands on its top, 2.2 m
        // up. Each landing puts the centre 0.81 m above the top, less at most the 1 cm offset
        // (measured: 2.01 and 3.01 m, at x = -5.67).
        let (mut scene, mut player) = platformer_from(Vec3::new(-3.0, 0.81, 0.0));
        run(&mut scene, &mut player, 2);
        player.jump();
        let (_, on_first) = run(&mut scene, &mut player, 90);
        assert!(
            on_first > 1.2 + 0.80 && on_first < 1.2 + 0.811,
            "{on_first}"
        );
        player.jump();
        player.set_walk(-Vec3::X);
        run(&mut scene, &mut player, 40);
        player.set_walk(Vec3::ZERO);
        run(&mut scene, &mut player, 90);
        let on_second = position(&scene);
        assert!(
            on_second.y > 2.2 + 0.80 && on_second.y < 2.2 + 0.811,
            "{on_second}"
        );
        assert!(on_second.x > -7.0 && on_second.x < -5.0, "{on_second}");
    }

    #[test]
    fn the_platformers_door_opens_when_pushed_and_closes_again() {
        // The character walks 1 s toward -x into the door, 0.6 m from its hinge: it pushes with
        // up to 1,000 N, 600 N·m, past the motor's 300 N·m, and the door swings open (measured:
        // 1.16 rad). Walked away, the motor's spring (200 N·m/rad, damped) closes it: 3 s later
        // it is within 0.01 rad of shut (measured 0.002 rad, asleep).
        let (mut scene, mut player) = platformer_from(Vec3::new(-1.8, 0.81, -3.3));
        let door = scene.body_handle("door").expect("named");
        let angle = |scene: &Scene| {
            let rotation = scene.world().body(door).expect("the door").rotation();
            rotation.to_axis_angle().1
        };
        let mut widest = 0.0f32;
        player.set_walk(-Vec3::X);
        for _ in 0..60 {
            run(&mut scene, &mut player, 1);
            widest = widest.max(angle(&scene));
        }
        assert!(widest > 0.5, "opened to {widest} rad");
        player.set_walk(Vec3::new(0.0, 0.0, -1.0));
        run(&mut scene, &mut player, 30);
        player.set_walk(Vec3::ZERO);
        run(&mut scene, &mut player, 150);
        assert!(angle(&scene) < 0.01, "{} rad", angle(&scene));
    }
}
