//! Motion of free bodies against closed forms and conservation laws.

use std::f32::consts::FRAC_PI_4;

use rebond::{limits, BodyDesc, BodyHandle, Quat, Shape, Vec3, World, WorldSettings};

const DT: f32 = 1.0 / 60.0;

fn world_with_gravity(gravity: Vec3) -> World {
    World::new(WorldSettings {
        gravity,
        ..WorldSettings::default()
    })
    .unwrap()
}

fn add(world: &mut World, desc: BodyDesc) -> BodyHandle {
    world.add_body(desc).unwrap()
}

#[test]
fn free_fall_matches_semi_implicit_euler_exactly() {
    let gravity = Vec3::new(0.0, -9.81, 0.0);
    let mut world = world_with_gravity(gravity);
    let start = Vec3::new(1.0, 10.0, -2.0);
    let ball = add(
        &mut world,
        BodyDesc::dynamic(Shape::sphere(0.5).unwrap()).position(start),
    );
    let substeps = world.settings().substeps;
    let h = DT / substeps as f32;
    let (mut position, mut velocity) = (start, Vec3::ZERO);
    for _ in 0..120 {
        world.step(DT).unwrap();
        for _ in 0..substeps {
            velocity += h * gravity;
            position += h * velocity;
        }
        let body = world.body(ball).unwrap();
        assert_eq!(body.linear_velocity(), velocity);
        assert_eq!(body.position(), position);
        assert_eq!(body.rotation(), Quat::IDENTITY);
    }
}

#[test]
fn constant_force_and_torque_give_f_over_m_t_and_inverse_inertia_torque_t() {
    let mut world = world_with_gravity(Vec3::ZERO);
    let force = Vec3::new(3.0, -1.0, 2.0);
    // A torque along the box's local Z, a principal axis: ω stays along it, so the gyroscopic
    // term ω × Iω is zero and ω = τ t / Izz exactly in exact arithmetic.
    let torque = Vec3::new(0.0, 0.0, 0.5);
    let half = Vec3::new(0.3, 0.5, 0.7);
    let body = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(half).unwrap())
            .mass(2.0)
            .constant_force(force)
            .constant_torque(torque),
    );
    let steps = 120;
    for _ in 0..steps {
        world.step(DT).unwrap();
    }
    let time = steps as f32 * DT;
    let izz = 2.0 / 3.0 * (half.x * half.x + half.y * half.y);
    let state = world.body(body).unwrap();
    // 480 substeps each adding one rounded increment: relative error below 480 × 6e-8 ≈ 3e-5.
    let tolerance = 1.0e-4;
    assert!((state.linear_velocity() - force / 2.0 * time).length() <= tolerance * force.length());
    let expected_spin = torque / izz * time;
    assert!(
        (state.angular_velocity() - expected_spin).length() <= tolerance * expected_spin.length(),
        "spin {} expected {}",
        state.angular_velocity(),
        expected_spin
    );
    // Positions follow the semi-implicit sum: x = a h² n (n + 1) / 2 after n substeps.
    let substeps = (steps * world.settings().substeps) as f32;
    let h = DT / world.settings().substeps as f32;
    let expected_position = force / 2.0 * h * h * substeps * (substeps + 1.0) / 2.0;
    assert!(
        (state.position() - expected_position).length() <= tolerance * expected_position.length()
    );
}

#[test]
fn user_forces_act_for_one_step_and_force_at_a_point_adds_r_cross_f() {
    let mut world = world_with_gravity(Vec3::ZERO);
    let ball = add(
        &mut world,
        BodyDesc::dynamic(Shape::sphere(0.5).unwrap()).mass(4.0),
    );
    let force = Vec3::new(0.0, 0.0, 8.0);
    let point = Vec3::new(0.5, 0.0, 0.0);
    world
        .body_mut(ball)
        .unwrap()
        .apply_force_at_point(force, point)
        .unwrap();
    world.step(DT).unwrap();
    let inertia = 0.4 * 4.0 * 0.25;
    let body = world.body(ball).unwrap();
    assert!((body.linear_velocity() - force / 4.0 * DT).length() < 1.0e-6);
    let expected_spin = point.cross(force) / inertia * DT;
    assert!((body.angular_velocity() - expected_spin).length() < 1.0e-5);
    // The accumulators were cleared: the next step changes nothing.
    let (linear, angular) = (body.linear_velocity(), body.angular_velocity());
    world.step(DT).unwrap();
    let body = world.body(ball).unwrap();
    assert_eq!(body.linear_velocity(), linear);
    assert!((body.angular_velocity() - angular).length() < 1.0e-6);
}

#[test]
fn a_constant_force_at_a_body_point_gives_r_cross_f_on_a_turned_anisotropic_box() {
    let mut world = world_with_gravity(Vec3::ZERO);
    let half = Vec3::new(0.3, 0.5, 0.7);
    let rotation = Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalize(), 0.8);
    let force = Vec3::new(0.2, -0.1, 0.3);
    // A corner, in the body frame: the box's centre of mass is its origin, so the lever arm in the
    // world is the corner turned by the body's rotation.
    let point = Vec3::new(0.3, 0.5, -0.7);
    let body = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(half).unwrap())
            .mass(2.0)
            .position(Vec3::new(1.0, 2.0, 3.0))
            .rotation(rotation)
            .constant_force_at_point(force, point),
    );
    let inverse_inertia = world.body(body).unwrap().world_inverse_inertia();
    let expected_spin = inverse_inertia * (rotation * point).cross(force) * DT;
    world.step(DT).unwrap();
    let state = world.body(body).unwrap();
    assert!((state.linear_velocity() - force / 2.0 * DT).length() <= 1.0e-6);
    // The spin reaches about 0.02 rad/s in the step: the gyroscopic term ω × Iω it brings is
    // second order, below 1e-4 of the spin, and the inverse inertia of the turned box is the
    // start-of-step one to first order in the angle turned (3e-4 rad); 1e-3 covers both.
    assert!(
        (state.angular_velocity() - expected_spin).length() <= 1.0e-3 * expected_spin.length(),
        "spin {} expected {}",
        state.angular_velocity(),
        expected_spin
    );
    assert_eq!(state.constant_force_point(), Some(point));
}

#[test]
fn a_body_thrown_faster_than_the_limit_flies_at_the_limit() {
    // Half the largest impulse on the lightest body (5e17 m/s) and the largest angular speed the
    // engine takes: the limits must hold the direction and the speed.
    let mut world = world_with_gravity(Vec3::ZERO);
    let limit = world.settings().max_linear_speed;
    let direction = Vec3::new(3.0, -4.0, 0.0) / 5.0;
    let body = add(
        &mut world,
        BodyDesc::dynamic(Shape::sphere(0.5).unwrap())
            .mass(limits::MIN_MASS)
            .angular_velocity(Vec3::new(0.0, limits::MAX_ANGULAR_SPEED, 0.0)),
    );
    world
        .body_mut(body)
        .unwrap()
        .apply_impulse(0.5 * limits::MAX_FORCE * direction)
        .unwrap();
    world.step(DT).unwrap();
    let state = world.body(body).unwrap();
    let velocity = state.linear_velocity();
    assert!(
        (velocity - limit * direction).length() <= 1.0e-6 * limit,
        "{velocity}"
    );
    assert!((state.position() - limit * DT * direction).length() <= 1.0e-6 * limit * DT);
    // A quarter turn per substep at most, about the axis it was given.
    let substep = DT / world.settings().substeps as f32;
    let spin = state.angular_velocity();
    assert!((spin - Vec3::Y * FRAC_PI_4 / substep).length() <= 1.0e-6 * spin.length());
}

#[test]
fn impulse_at_a_point_changes_velocities_at_once() {
    let mut world = world_with_gravity(Vec3::ZERO);
    let half = Vec3::new(0.5, 0.5, 0.5);
    let cube = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(half).unwrap()).mass(6.0),
    );
    let impulse = Vec3::new(0.0, 3.0, 0.0);
    let point = Vec3::new(0.5, 0.0, 0.5);
    let body = world.body_mut(cube).unwrap();
    body.apply_impulse_at_point(impulse, point).unwrap();
    // A unit cube of 6 kg: I = m (1 + 1) / 12 = 1 kg·m² about every axis.
    assert!((body.linear_velocity() - Vec3::new(0.0, 0.5, 0.0)).length() < 1.0e-6);
    assert!((body.angular_velocity() - point.cross(impulse)).length() < 1.0e-5);
}

// Tolerances of the free spinners: the integrator conserves world angular momentum exactly in
// exact arithmetic (see the gyroscopic step in solver/integration.rs), so what remains is f32 rounding
// over 4,800 substeps (10 s at the default 8 substeps), measured at 4.9e-4; 1e-3 leaves room for it
// and is ten times tighter than the 1% and 2% the issue asks. Energy may only fall (measured
// growth: 1e-4, rounding); 1% is the bar.

/// Steps a free body for `seconds` and returns the largest relative change of its world angular
/// momentum and of its kinetic energy, and the body-frame angular velocity at every step.
fn spin_freely(half: Vec3, spin: Vec3, seconds: f32) -> (f32, f32, Vec<Vec3>) {
    let mut world = world_with_gravity(Vec3::ZERO);
    let rotation = Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalize(), 0.4);
    let body = add(
        &mut world,
        BodyDesc::dynamic(Shape::cuboid(half).unwrap())
            .rotation(rotation)
            .angular_velocity(rotation * spin),
    );
    let start = world.body(body).unwrap();
    let momentum = start.angular_momentum();
    let energy = start.kinetic_energy();
    let (mut momentum_error, mut energy_growth) = (0.0f32, 0.0f32);
    let mut body_frame_spins = Vec::new();
    for _ in 0..(seconds / DT).round() as usize {
        world.step(DT).unwrap();
        let state = world.body(body).unwrap();
        momentum_error =
            momentum_error.max((state.angular_momentum() - momentum).length() / momentum.length());
        energy_growth = energy_growth.max((state.kinetic_energy() - energy) / energy);
        body_frame_spins.push(state.rotation().inverse() * state.angular_velocity());
    }
    (momentum_error, energy_growth, body_frame_spins)
}

#[test]
fn asymmetric_box_keeps_its_angular_momentum_for_ten_seconds() {
    let (momentum_error, energy_growth, _) =
        spin_freely(Vec3::new(0.2, 0.5, 0.9), Vec3::new(2.0, 3.0, -4.0), 10.0);
    assert!(
        momentum_error < 1.0e-3,
        "angular momentum drifted by {momentum_error}"
    );
    assert!(
        energy_growth < 0.01,
        "kinetic energy grew by {energy_growth}"
    );
}

#[test]
fn spin_about_the_intermediate_axis_flips_while_momentum_is_kept() {
    // Half extents 0.1, 0.4, 0.8: Ixx ∝ 0.8, Iyy ∝ 0.65, Izz ∝ 0.17, so Y is the intermediate axis
    // and a spin about it with a tiny perturbation is unstable (the Dzhanibekov effect).
    let (momentum_error, energy_growth, spins) =
        spin_freely(Vec3::new(0.1, 0.4, 0.8), Vec3::new(0.01, 6.0, 0.0), 10.0);
    let first_flip = spins.iter().position(|spin| spin.y < -3.0);
    assert!(first_flip.is_some(), "never flipped");
    let flipped_back = spins[first_flip.unwrap_or(0)..]
        .iter()
        .any(|spin| spin.y > 3.0);
    assert!(flipped_back, "flipped once but never back");
    assert!(
        momentum_error < 1.0e-3,
        "angular momentum drifted by {momentum_error}"
    );
    assert!(
        energy_growth < 0.01,
        "kinetic energy grew by {energy_growth}"
    );
}

#[test]
fn kinematic_body_follows_its_velocity_and_ignores_gravity_and_forces() {
    let mut world = world_with_gravity(Vec3::new(0.0, -9.81, 0.0));
    let platform = add(
        &mut world,
        BodyDesc::kinematic(Shape::cuboid(Vec3::ONE).unwrap())
            .linear_velocity(Vec3::new(1.0, 0.0, 0.0))
            .angular_velocity(Vec3::new(0.0, 0.5, 0.0)),
    );
    world
        .body_mut(platform)
        .unwrap()
        .apply_force(Vec3::new(0.0, 1.0e6, 0.0))
        .unwrap();
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    let body = world.body(platform).unwrap();
    assert!((body.position() - Vec3::new(1.0, 0.0, 0.0)).length() < 1.0e-4);
    assert_eq!(body.linear_velocity(), Vec3::new(1.0, 0.0, 0.0));
    let angle = body.rotation().to_axis_angle().1;
    assert!((angle - 0.5).abs() < 1.0e-4);
}

#[test]
fn static_body_never_moves() {
    let mut world = world_with_gravity(Vec3::new(0.0, -9.81, 0.0));
    let ground = add(
        &mut world,
        BodyDesc::static_body(Shape::cuboid(Vec3::ONE).unwrap()).linear_velocity(Vec3::X),
    );
    world
        .body_mut(ground)
        .unwrap()
        .apply_impulse(Vec3::Y)
        .unwrap();
    world.step(DT).unwrap();
    let body = world.body(ground).unwrap();
    assert_eq!(body.position(), Vec3::ZERO);
    assert_eq!(body.linear_velocity(), Vec3::ZERO);
    assert_eq!(body.inverse_mass(), 0.0);
}

#[test]
fn damping_slows_by_one_over_one_plus_h_c_each_substep() {
    let mut world = world_with_gravity(Vec3::ZERO);
    let ball = add(
        &mut world,
        BodyDesc::dynamic(Shape::sphere(0.5).unwrap())
            .linear_velocity(Vec3::X)
            .damping(2.0, 0.0),
    );
    world.step(DT).unwrap();
    let h = DT / world.settings().substeps as f32;
    let expected = (1.0 / (1.0 + h * 2.0)).powi(world.settings().substeps as i32);
    let speed = world.body(ball).unwrap().linear_velocity().x;
    assert!((speed - expected).abs() < 1.0e-6);
}

#[test]
fn bodies_can_be_added_and_removed_between_steps() {
    let mut world = world_with_gravity(Vec3::ZERO);
    let first = add(&mut world, BodyDesc::dynamic(Shape::sphere(1.0).unwrap()));
    world.step(DT).unwrap();
    let removed = world.remove_body(first).unwrap();
    assert_eq!(removed.mass(), world_sphere_mass(1.0));
    let second = add(&mut world, BodyDesc::dynamic(Shape::sphere(2.0).unwrap()));
    assert_eq!(first.slot(), second.slot());
    assert!(world.body(first).is_err());
    assert!(world.body_mut(first).is_err());
    assert!(world.remove_body(first).is_err());
    assert_eq!(world.body(second).unwrap().mass(), world_sphere_mass(2.0));
    world.step(DT).unwrap();
    assert_eq!(world.body_count(), 1);
}

fn world_sphere_mass(radius: f32) -> f32 {
    Shape::sphere(radius)
        .unwrap()
        .mass_properties(1000.0)
        .unwrap()
        .mass
}

#[test]
fn same_input_gives_bit_identical_trajectories() {
    let run = || {
        let mut world = world_with_gravity(Vec3::new(0.0, -9.81, 0.0));
        let handles: Vec<_> = (0..20)
            .map(|index| {
                let spin = Vec3::new(index as f32, 1.0, -0.5 * index as f32);
                add(
                    &mut world,
                    BodyDesc::dynamic(Shape::cuboid(Vec3::new(0.2, 0.5, 0.9)).unwrap())
                        .position(Vec3::splat(index as f32))
                        .angular_velocity(spin),
                )
            })
            .collect();
        for _ in 0..300 {
            world.step(DT).unwrap();
        }
        handles
            .iter()
            .map(|handle| {
                let body = world.body(*handle).unwrap();
                (body.position(), body.rotation(), body.angular_velocity())
            })
            .collect::<Vec<_>>()
    };
    let (first, second) = (run(), run());
    for (a, b) in first.iter().zip(&second) {
        assert_eq!(
            a.0.to_array().map(f32::to_bits),
            b.0.to_array().map(f32::to_bits)
        );
        assert_eq!(
            a.1.to_array().map(f32::to_bits),
            b.1.to_array().map(f32::to_bits)
        );
        assert_eq!(
            a.2.to_array().map(f32::to_bits),
            b.2.to_array().map(f32::to_bits)
        );
    }
}
