//! Fast bodies against walls and planks: the speculative contact (made a step ahead, as far as
//! the bodies can close in a step, up to four times their sizes) stops them at the surface, a
//! face meeting a face stops flat (the manifold's rigid points solved as one block), and a body
//! moving farther than that in a step is swept and put back where it first meets another (the
//! continuous pass), rotation and moving targets included.

mod common;

use common::{world, DT};
use rebond::{BodyDesc, BodyHandle, CompoundChild, Pose, Quat, Shape, Vec3, World};

/// A world without gravity with a static wall of thickness `thickness` whose face toward −x is
/// the plane x = 0, and a dynamic `shape` 20 m before it at `rotation`, flying at `speed`
/// along +x with restitution 0.
fn wall_and_shot(thickness: f32, shape: Shape, rotation: Quat, speed: f32) -> (World, BodyHandle) {
    let mut world = world(Vec3::ZERO);
    world
        .add_body(
            BodyDesc::static_body(Shape::cuboid(Vec3::new(0.5 * thickness, 5.0, 5.0)).unwrap())
                .position(Vec3::new(0.5 * thickness, 0.0, 0.0)),
        )
        .unwrap();
    let shot = world
        .add_body(
            BodyDesc::dynamic(shape)
                .position(Vec3::new(-20.0, 0.0, 0.0))
                .rotation(rotation)
                .linear_velocity(Vec3::new(speed, 0.0, 0.0))
                .can_sleep(false),
        )
        .unwrap();
    (world, shot)
}

#[test]
fn a_box_flying_face_first_into_a_wall_stops_dead() {
    // Restitution 0: the box should stop at the wall, not rebound or turn. Bounds (the
    // issue's): under 0.5 m/s and 0.5 rad/s at every step after the hit (measured: under 3e-4
    // m/s and 3e-4 rad/s), and it never passes the wall's face.
    for speed in [50.0f32, 200.0, 1000.0] {
        let box_shape = Shape::cuboid(Vec3::splat(0.5)).unwrap();
        let (mut world, shot) = wall_and_shot(1.0, box_shape, Quat::IDENTITY, speed);
        let hit_by = (20.0 / (speed * DT)).ceil() as usize;
        for step in 0..hit_by + 60 {
            world.step(DT).unwrap();
            let body = world.body(shot).unwrap();
            assert!(
                body.position().x < -0.49,
                "{speed} m/s: at {}",
                body.position()
            );
            if step >= hit_by {
                let (v, w) = (body.linear_velocity(), body.angular_velocity());
                assert!(v.length() < 0.5 && w.length() < 0.5, "{speed} m/s: {v} {w}");
            }
        }
    }
}

#[test]
fn a_bullet_never_passes_through_a_thin_plank() {
    // A 2 cm plank and a 1 cm sphere at up to 1,000 m/s (16.7 m a step), a turned box bullet,
    // and a compound of two such spheres side by side: each must end on the near side of the
    // plank.
    let pair = Shape::compound(
        [-0.02f32, 0.02]
            .map(|z| {
                CompoundChild::new(
                    Shape::sphere(0.01).unwrap(),
                    Pose::from_position(Vec3::new(0.0, 0.0, z)),
                )
            })
            .to_vec(),
    )
    .unwrap();
    let bullets = [
        (Shape::sphere(0.01).unwrap(), Quat::IDENTITY),
        (
            Shape::cuboid(Vec3::new(0.05, 0.01, 0.01)).unwrap(),
            Quat::from_rotation_z(0.3),
        ),
        (pair, Quat::from_rotation_x(0.5)),
    ];
    for (shape, rotation) in bullets {
        for speed in [100.0f32, 400.0, 1000.0] {
            let (mut world, shot) = wall_and_shot(0.02, shape.clone(), rotation, speed);
            for _ in 0..120 {
                world.step(DT).unwrap();
                let x = world.body(shot).unwrap().position().x;
                assert!(x < 0.0, "{speed} m/s: reached x = {x}");
            }
        }
    }
}

#[test]
fn a_fast_box_meeting_a_resting_one_face_first_shares_its_momentum_without_turning() {
    // Equal unit boxes, restitution 0, no gravity: a perfectly inelastic collision leaves both
    // at half the speed, v/2, with no spin. Bounds: 0.1 % of v and 1e-3 rad/s (rounding; the
    // two are not pushed apart, so they stay in contact, speculative points holding them).
    for speed in [50.0f32, 400.0] {
        let mut world = world(Vec3::ZERO);
        let cube = || Shape::cuboid(Vec3::splat(0.5)).unwrap();
        let target = world
            .add_body(BodyDesc::dynamic(cube()).can_sleep(false))
            .unwrap();
        let shot = world
            .add_body(
                BodyDesc::dynamic(cube())
                    .position(Vec3::new(-20.0, 0.0, 0.0))
                    .linear_velocity(Vec3::new(speed, 0.0, 0.0))
                    .can_sleep(false),
            )
            .unwrap();
        let hit_by = (20.0 / (speed * DT)).ceil() as usize;
        common::run(&mut world, hit_by + 30);
        for body in [shot, target] {
            let body = world.body(body).unwrap();
            let (v, w) = (body.linear_velocity(), body.angular_velocity());
            assert!(
                (v - Vec3::new(0.5 * speed, 0.0, 0.0)).length() < 1e-3 * speed,
                "{speed} m/s: {v}"
            );
            assert!(w.length() < 1e-3, "{speed} m/s: {w}");
        }
    }
}

/// The largest x of any corner of a box with half extents `half` at the pose of `body`.
fn largest_corner_x(world: &World, body: BodyHandle, half: Vec3) -> f32 {
    let body = world.body(body).unwrap();
    let (position, rotation) = (body.position(), body.rotation());
    (0..8)
        .map(|k| {
            let sign = |bit: u32| if k & (1 << bit) == 0 { -1.0 } else { 1.0 };
            let corner = Vec3::new(sign(0) * half.x, sign(1) * half.y, sign(2) * half.z);
            (position + rotation * corner).x
        })
        .fold(f32::NEG_INFINITY, f32::max)
}

#[test]
fn a_rod_spinning_into_a_thin_plank_never_passes_through() {
    // A 2 m rod flying at 240 m/s and turning at 90 to 150 rad/s about z moves up to 6.5 m a
    // step, more than four times its reach (1 m): its contacts reach no farther, so the
    // continuous pass sweeps it, rotation included. Against a 2 cm plank it must end every step
    // with no corner past the plank's far face (x = 0.02) and its centre on the near side, and
    // the plank must have stopped it.
    let half = Vec3::new(1.0, 0.05, 0.05);
    for spin in [90.0f32, -90.0, 150.0] {
        let mut world = world(Vec3::ZERO);
        world
            .add_body(
                BodyDesc::static_body(Shape::cuboid(Vec3::new(0.01, 5.0, 5.0)).unwrap())
                    .position(Vec3::new(0.01, 0.0, 0.0)),
            )
            .unwrap();
        let rod = world
            .add_body(
                BodyDesc::dynamic(Shape::cuboid(half).unwrap())
                    .position(Vec3::new(-20.0, 0.0, 0.0))
                    .linear_velocity(Vec3::new(240.0, 0.0, 0.0))
                    .angular_velocity(Vec3::new(0.0, 0.0, spin))
                    .can_sleep(false),
            )
            .unwrap();
        for step in 0..60 {
            world.step(DT).unwrap();
            let far = largest_corner_x(&world, rod, half);
            let centre = world.body(rod).unwrap().position().x;
            assert!(
                far < 0.02 && centre < 0.0,
                "{spin} rad/s, step {step}: corner at x = {far}, centre at {centre}"
            );
        }
        let v = world.body(rod).unwrap().linear_velocity();
        assert!(v.x < 1.0, "{spin} rad/s: still at {v}");
    }
}

#[test]
fn a_bullet_into_a_floating_plank_stays_in_front_and_keeps_the_momentum() {
    // A 1 cm sphere at 1,000 m/s into a free 2 cm plank, no gravity, restitution 0: the sweep
    // meets a moving body. The bullet must never end a step past the plank's far face, and the
    // momentum along x must stay m v (to 1e-4: the impulses are solved in f32); once stuck the
    // two move together at m v / (m + M).
    let mut world = world(Vec3::ZERO);
    let plank = world
        .add_body(
            BodyDesc::dynamic(Shape::cuboid(Vec3::new(0.01, 1.0, 1.0)).unwrap())
                .position(Vec3::new(0.01, 0.0, 0.0))
                .can_sleep(false),
        )
        .unwrap();
    let bullet = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(0.01).unwrap())
                .position(Vec3::new(-20.0, 0.0, 0.0))
                .linear_velocity(Vec3::new(1000.0, 0.0, 0.0))
                .can_sleep(false),
        )
        .unwrap();
    let mass = |body| world.body(body).unwrap().mass();
    let (m, big_m) = (mass(bullet), mass(plank));
    let momentum = m * 1000.0;
    for step in 0..30 {
        world.step(DT).unwrap();
        let (b, p) = (world.body(bullet).unwrap(), world.body(plank).unwrap());
        assert!(
            b.position().x < p.position().x + 0.01,
            "step {step}: bullet at {}, plank at {}",
            b.position().x,
            p.position().x
        );
        let total = m * b.linear_velocity().x + big_m * p.linear_velocity().x;
        assert!(
            (total - momentum).abs() < 1e-4 * momentum,
            "step {step}: momentum {total}, was {momentum}"
        );
    }
    let shared = momentum / (m + big_m);
    for body in [bullet, plank] {
        let v = world.body(body).unwrap().linear_velocity().x;
        assert!(
            (v - shared).abs() < 0.01 * shared,
            "{v} m/s, expected {shared}"
        );
    }
}

#[test]
fn two_bullets_meeting_head_on_stop_each_other() {
    // Two 10 cm spheres at ±500 m/s (8.3 m a step each, 80 times their reach), restitution 0,
    // no gravity: both are swept, each against the other's motion. They must never pass each
    // other, and equal momenta cancel: both at rest (under 0.5 m/s, the bound).
    let mut world = world(Vec3::ZERO);
    let ball = |x: f32, v: f32| {
        BodyDesc::dynamic(Shape::sphere(0.1).unwrap())
            .position(Vec3::new(x, 0.0, 0.0))
            .linear_velocity(Vec3::new(v, 0.0, 0.0))
            .can_sleep(false)
    };
    let left = world.add_body(ball(-20.0, 500.0)).unwrap();
    let right = world.add_body(ball(20.0, -500.0)).unwrap();
    for step in 0..30 {
        world.step(DT).unwrap();
        let x = |body| world.body(body).unwrap().position().x;
        assert!(
            x(right) - x(left) > 0.19,
            "step {step}: {} and {}",
            x(left),
            x(right)
        );
    }
    for body in [left, right] {
        let v = world.body(body).unwrap().linear_velocity();
        assert!(v.length() < 0.5, "{v}");
    }
}

#[test]
fn a_ball_passing_a_box_at_a_kilometre_a_second_keeps_its_velocity() {
    // A ball flying past a box at 1,000 m/s (16.7 m a step), its lowest point `clear` above the
    // box's top: its path comes nearer the box than the contacts' margin (within a step of
    // it), and the sweep follows it past the box's edge. Nothing it passes may touch it: it
    // must fly on with its velocity and height unchanged, to the bit.
    for clear in [0.5f32, 0.1, 0.01] {
        let mut world = world(Vec3::ZERO);
        world
            .add_body(BodyDesc::static_body(
                Shape::cuboid(Vec3::splat(0.5)).unwrap(),
            ))
            .unwrap();
        let (speed, height) = (1000.0, 1.0 + clear);
        let ball = world
            .add_body(
                BodyDesc::dynamic(Shape::sphere(0.5).unwrap())
                    .position(Vec3::new(-1.2 - speed * DT, height, 0.0))
                    .linear_velocity(Vec3::new(speed, 0.0, 0.0))
                    .can_sleep(false),
            )
            .unwrap();
        for _ in 0..4 {
            world.step(DT).unwrap();
            let body = world.body(ball).unwrap();
            assert_eq!(
                body.linear_velocity(),
                Vec3::new(speed, 0.0, 0.0),
                "{clear}"
            );
            assert_eq!(body.angular_velocity(), Vec3::ZERO, "{clear}");
            assert_eq!(body.position().y, height, "{clear}");
        }
    }
}

#[test]
fn a_box_sliding_fast_over_a_mesh_keeps_its_speed() {
    // A unit box sliding without friction at 300 m/s (5 m a step, more than four times its
    // reach) over a flat triangle mesh of 1 m cells: the sweep meets triangle edges on its way,
    // but the box ends every step resting on the floor, so nothing may stop it. Bound: its speed
    // along x stays within 0.1 % of 300 m/s and it covers 5 m a step (only rounding changes
    // them).
    let speed = 300.0f32;
    let cells = 160u32;
    let vertices = (0..=cells)
        .flat_map(|i| [-2.0f32, 2.0].map(|z| Vec3::new(i as f32 - 2.0, 0.0, z)))
        .collect();
    let indices: Vec<[u32; 3]> = (0..cells)
        .flat_map(|i| {
            let (a, b, c, d) = (2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3);
            [[a, b, d], [a, d, c]]
        })
        .collect();
    let mut world = world(Vec3::new(0.0, -common::G, 0.0));
    world
        .add_body(BodyDesc::static_body(Shape::trimesh(vertices, &indices).unwrap()).friction(0.0))
        .unwrap();
    let slider = world
        .add_body(
            common::unit_box(Vec3::new(0.0, 0.5, 0.0))
                .friction(0.0)
                .can_sleep(false),
        )
        .unwrap();
    common::run(&mut world, 10);
    world
        .body_mut(slider)
        .unwrap()
        .set_linear_velocity(Vec3::new(speed, 0.0, 0.0))
        .unwrap();
    for step in 0..30 {
        let before = world.body(slider).unwrap().position().x;
        world.step(DT).unwrap();
        let body = world.body(slider).unwrap();
        let (v, moved) = (body.linear_velocity().x, body.position().x - before);
        assert!(
            (v - speed).abs() < 1e-3 * speed && (moved - speed * DT).abs() < 1e-3 * speed * DT,
            "step {step}: {v} m/s, moved {moved} m"
        );
    }
}

#[test]
fn shapes_shot_down_stop_on_a_plane_and_a_mesh() {
    // A 10 cm ball and a unit box face down at 1,000 m/s, and a turned unit box at 250 m/s
    // (4.2 m a step, past four reaches), shot straight down from 20 m, restitution 0, onto a
    // halfspace and onto a flat two-triangle mesh: swept against a static halfspace and
    // against triangles. (A turned box much faster would spin past the engine's angular speed
    // limit, 377 rad/s at 8 substeps, on its corner.) The lowest point must never end a step
    // more than the pass leaves a body below the floor: a quarter of the reach for the ball
    // (2.5 cm), 2 cm for the boxes (measured: under 0.03 mm, and 5 mm for the turned box on
    // the plane). The ball and the face-down box must come to rest (under 0.5 m/s and 0.5 rad/s
    // after 2 s, the bound); the turned box tumbles away over the 2 km floor.
    let floors = [
        Shape::halfspace(Vec3::Y).unwrap(),
        Shape::trimesh(
            vec![
                Vec3::new(-1000.0, 0.0, -1000.0),
                Vec3::new(-1000.0, 0.0, 1000.0),
                Vec3::new(1000.0, 0.0, 1000.0),
                Vec3::new(1000.0, 0.0, -1000.0),
            ],
            &[[0, 1, 2], [0, 2, 3]],
        )
        .unwrap(),
    ];
    let cube = || Shape::cuboid(Vec3::splat(0.5)).unwrap();
    let turned = Quat::from_rotation_x(0.4) * Quat::from_rotation_z(0.3);
    let shots = [
        (
            Shape::sphere(0.1).unwrap(),
            Quat::IDENTITY,
            1000.0f32,
            0.025f32,
        ),
        (cube(), Quat::IDENTITY, 1000.0, 0.02),
        (cube(), turned, 250.0, 0.02),
    ];
    for (floor_index, floor) in floors.iter().enumerate() {
        for (shape, rotation, speed, depth) in &shots {
            let mut world = world(Vec3::new(0.0, -common::G, 0.0));
            world
                .add_body(BodyDesc::static_body(floor.clone()))
                .unwrap();
            let shot = world
                .add_body(
                    BodyDesc::dynamic(shape.clone())
                        .position(Vec3::new(0.0, 20.0, 0.0))
                        .rotation(*rotation)
                        .linear_velocity(Vec3::new(0.0, -speed, 0.0))
                        .can_sleep(false),
                )
                .unwrap();
            for step in 0..120 {
                world.step(DT).unwrap();
                let body = world.body(shot).unwrap();
                let lowest = (0..8)
                    .map(|k| {
                        let corner = Vec3::new(
                            if k & 1 == 0 { -1.0 } else { 1.0 },
                            if k & 2 == 0 { -1.0 } else { 1.0 },
                            if k & 4 == 0 { -1.0 } else { 1.0 },
                        );
                        match shape {
                            Shape::Sphere(_) => body.position().y - 0.1,
                            _ => (body.position() + body.rotation() * (0.5 * corner)).y,
                        }
                    })
                    .fold(f32::INFINITY, f32::min);
                assert!(
                    lowest > -depth,
                    "floor {floor_index}, {speed} m/s, step {step}: lowest point at {lowest}"
                );
            }
            let body = world.body(shot).unwrap();
            let (v, w) = (body.linear_velocity(), body.angular_velocity());
            assert!(
                *rotation != Quat::IDENTITY || (v.length() < 0.5 && w.length() < 0.5),
                "floor {floor_index}, {speed} m/s: {v} {w}"
            );
        }
    }
}

/// Half extents of the paddle: 4 cm thick along x, 30 cm square. Its reach, 0.21 m, is far
/// below the 1.67 m it moves in a step at 100 m/s.
const PADDLE_HALF: Vec3 = Vec3::new(0.02, 0.15, 0.15);

/// A world without gravity with a ball of `radius` and `restitution` at rest at `ball`, and a
/// kinematic paddle ([`PADDLE_HALF`]) centred 2 m before it along −x, moving at `speed` along
/// +x.
fn paddle_and_ball(
    radius: f32,
    restitution: f32,
    ball: Vec3,
    speed: f32,
) -> (World, BodyHandle, BodyHandle) {
    let mut world = world(Vec3::ZERO);
    let paddle = world
        .add_body(
            BodyDesc::kinematic(Shape::cuboid(PADDLE_HALF).unwrap())
                .position(Vec3::new(ball.x - 2.0, 0.0, 0.0))
                .linear_velocity(Vec3::new(speed, 0.0, 0.0)),
        )
        .unwrap();
    let ball = world
        .add_body(
            BodyDesc::dynamic(Shape::sphere(radius).unwrap())
                .position(ball)
                .restitution(restitution)
                .can_sleep(false),
        )
        .unwrap();
    (world, paddle, ball)
}

#[test]
fn a_fast_kinematic_paddle_pushes_a_ball_ahead_and_never_passes_it() {
    // A 4 cm paddle at 100 m/s moves 1.67 m a step, eight times its reach: its contacts reach
    // no farther than four times the pair's reaches, so only the continuous pass sees the ball.
    // Balls of 1, 2.5 and 10 cm radius, on the paddle's axis and 12 cm off it (still in front
    // of the 15 cm half-width), placed so that the paddle meets them early, midway and late in
    // a step. Every step after the paddle's front face reaches the ball, the ball's centre lies
    // ahead of that face by its radius and by no more than the speculative distance (0.02 m; the
    // pass leaves a quarter of it, measured 5.0 mm), and with restitution 0 it rides at the
    // paddle's velocity, as off a body of infinite mass: to 1e-5 of it, f32 rounding (measured
    // 1.5e-7).
    let speed = 100.0f32;
    for radius in [0.01f32, 0.025, 0.1] {
        for offset in [0.0f32, 0.12] {
            for phase in [0.1f32, 0.5, 0.9] {
                let ball_x = phase * speed * DT;
                let start = Vec3::new(ball_x, offset, 0.0);
                let (mut world, paddle, ball) = paddle_and_ball(radius, 0.0, start, speed);
                for step in 0..8 {
                    world.step(DT).unwrap();
                    let front = world.body(paddle).unwrap().position().x + PADDLE_HALF.x;
                    if front < ball_x - radius {
                        continue;
                    }
                    let body = world.body(ball).unwrap();
                    let (ahead, v) = (body.position().x - front, body.linear_velocity());
                    assert!(
                        (0.0..=0.02).contains(&(ahead - radius)),
                        "r {radius}, off {offset}, phase {phase}, step {step}: {ahead} ahead"
                    );
                    assert!(
                        (v - Vec3::new(speed, 0.0, 0.0)).length() <= 1.0e-5 * speed,
                        "r {radius}, off {offset}, phase {phase}, step {step}: v = {v}"
                    );
                }
            }
        }
    }
}

#[test]
fn a_fast_kinematic_paddle_leaves_a_ball_beside_its_path_alone() {
    // A 2.5 cm ball whose surface lies 1 cm beyond the paddle's edge is never met: it keeps its
    // pose and rest exactly, whether it is awake or asleep.
    for can_sleep in [false, true] {
        let start = Vec3::new(0.8, PADDLE_HALF.y + 0.025 + 0.01, 0.0);
        let (mut world, _, ball) = paddle_and_ball(0.025, 0.0, start, 100.0);
        world.body_mut(ball).unwrap().set_can_sleep(can_sleep);
        common::run(&mut world, 4);
        let body = world.body(ball).unwrap();
        assert_eq!(body.position(), start, "can sleep: {can_sleep}");
        assert_eq!(body.linear_velocity(), Vec3::ZERO, "can sleep: {can_sleep}");
    }
}

#[test]
fn a_fast_kinematic_paddle_wakes_a_sleeping_ball_and_pushes_it_ahead() {
    // The ball falls asleep at rest, then the paddle is set off at 100 m/s toward it. Bounds
    // as for the awake ball: ahead of the face by its radius, at the paddle's velocity.
    let (mut world, paddle, ball) = paddle_and_ball(0.025, 0.0, Vec3::new(0.8, 0.0, 0.0), 0.0);
    world.body_mut(ball).unwrap().set_can_sleep(true);
    common::run(&mut world, 120);
    assert!(world.body(ball).unwrap().is_sleeping());
    world
        .body_mut(paddle)
        .unwrap()
        .set_linear_velocity(Vec3::new(100.0, 0.0, 0.0))
        .unwrap();
    common::run(&mut world, 3);
    let front = world.body(paddle).unwrap().position().x + PADDLE_HALF.x;
    let body = world.body(ball).unwrap();
    let (ahead, v) = (body.position().x - front, body.linear_velocity());
    assert!((0.0..=0.02).contains(&(ahead - 0.025)), "{ahead} ahead");
    assert!(
        (v - Vec3::new(100.0, 0.0, 0.0)).length() <= 1.0e-3,
        "v = {v}"
    );
}

#[test]
fn a_fast_kinematic_paddle_bounces_an_elastic_ball_off_at_twice_its_speed() {
    // Restitution 1 off a body of infinite mass moving at u: the ball leaves at 2u.
    let speed = 100.0f32;
    let (mut world, _, ball) = paddle_and_ball(0.025, 1.0, Vec3::new(0.8, 0.0, 0.0), speed);
    common::run(&mut world, 4);
    // Bound: 1e-5 of the speed, f32 rounding (measured 1.5e-7).
    let v = world.body(ball).unwrap().linear_velocity();
    assert!(
        (v - Vec3::new(2.0 * speed, 0.0, 0.0)).length() <= 1.0e-5 * speed,
        "v = {v}"
    );
}

#[test]
fn a_bar_spinning_at_50_rad_s_strikes_a_ball_and_never_passes_it() {
    // A 2 m bar, 4 cm thick, turning at 50 rad/s about its centre (0.83 rad a step) meets a
    // resting 2.5 cm ball 0.8 m from its axis, where it moves at 40 m/s. (A 1 m bar would not
    // reach 0.8 m.) The ball is placed at angles that the bar reaches early, midway and late in
    // a step. In the bar's frame, the side it turns toward is +y at +x and −y at −x; while the
    // ball is within the bar's reach it stays on that side, its centre off the bar's face by its
    // radius less 1 mm (the swept hits leave 5 mm between the surfaces; measured 5.0 to 5.5 mm).
    // A ball passed lies on the other side.
    let half = Vec3::new(1.0, 0.02, 0.05);
    let (radius, lever) = (0.025f32, 0.8f32);
    let spin = 50.0f32;
    for phase in [0.1f32, 0.5, 0.9] {
        let angle = 0.3 + phase * spin * DT;
        let mut world = world(Vec3::ZERO);
        let bar = world
            .add_body(
                BodyDesc::kinematic(Shape::cuboid(half).unwrap())
                    .rotation(Quat::from_rotation_z(0.3))
                    .angular_velocity(Vec3::new(0.0, 0.0, spin)),
            )
            .unwrap();
        let ball = world
            .add_body(
                BodyDesc::dynamic(Shape::sphere(radius).unwrap())
                    .position(lever * Vec3::new(angle.cos(), angle.sin(), 0.0))
                    .can_sleep(false),
            )
            .unwrap();
        for step in 0..20 {
            world.step(DT).unwrap();
            let rotation = world.body(bar).unwrap().rotation();
            let local = rotation.inverse() * world.body(ball).unwrap().position();
            if local.length() <= half.x + radius {
                let lead = local.y * local.x.signum();
                assert!(
                    lead >= half.y + radius - 1.0e-3,
                    "phase {phase}, step {step}: ball at {local} in the bar's frame"
                );
            }
        }
        // Struck, not missed: the bar's face moves at 0.8 m × ω where it meets the ball, and an
        // inelastic blow leaves the ball at least that fast (measured 0.2 to 0.35 % below it, as
        // a contact's normal is the one at the step's start: this checks the hit, not its speed).
        let v = world.body(ball).unwrap().linear_velocity().length();
        assert!(v >= 0.9 * spin * lever, "phase {phase}: {v} m/s");
    }
}
