//! The joints as a constraint kind: every acting joint with a moving body, from the parts of
//! `joint_parts.rs`. `docs/joints.md` gives each joint type's rows.
//!
//! A joint's geometry (anchors, axes, angles and the parts built on them) follows the bodies:
//! it is rebuilt from the poses at the first substep's warm start and for every relax pass,
//! after the poses moved (the next substep's warm start and biased passes see the same poses), so
//! the rows and their position errors are exact for the poses, not only to first order. The relax pass's refresh matters: with the rows of the
//! substep's start, the velocity it leaves is tangent to where the body was, and a pendulum
//! loses its energy at a rate proportional to the substep.
//!
//! The rows that hold bodies together (points, rotation locks, hinge axes, slide lines, rigid
//! lengths) of joints sharing moving bodies are solved together and exactly
//! (`joint_groups.rs`); limits, motors, springs and friction one row at a time.

mod geometry;

use super::joint_groups::{Accumulator, EliminationOrder, GroupRow, GroupSystem};
use super::joint_parts::{
    AxisPart, JointBodies, RotationPart, RowJacobian, RowSoftness, Velocities,
};
use super::softness::Softness;
use super::stages::{ConstraintKind, StepContext, BIASED_ITERATIONS};
use super::{BodyMotion, BodyState, SolverBodies};
use crate::joint::{AxisFreedom, JointFrames, JointImpulses, JointSet, JointType, Motor, Spring};
use crate::limits::MAX_SOLVER_IMPULSE;
use crate::math::{Quat, Vec3};
use geometry::Geometry;

/// Largest joint frequency as a fraction of the substep rate (as for contacts,
/// `CONTACT_HERTZ_PER_SUBSTEP_RATE`): a stiffer spring is unstable in the soft step.
const JOINT_HERTZ_PER_SUBSTEP_RATE: f32 = 0.25;

/// Below this distance between a distance joint's anchors, m, the line between them has no
/// direction and the joint's rows wait until it has one.
const SHORTEST_DIRECTION: f32 = 1.0e-6;

/// Least `1 + a·b` of a ball joint's twist rate `(a + b) / (1 + a·b)`: past a swing of about
/// 160° the twist is hardly defined, and its rate is held at most ten times the unit one.
const TWIST_RATE_FLOOR: f32 = 0.1;

/// What the world's settings say about joints, for one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct JointSettings {
    /// The position correction's frequency, Hz, before the cap.
    pub hertz: f32,
    /// Its damping ratio.
    pub damping_ratio: f32,
}

impl JointSettings {
    pub(super) fn softness(&self, h: f32, inverse_h: f32) -> Softness {
        Softness::new(
            self.hertz.min(JOINT_HERTZ_PER_SUBSTEP_RATE * inverse_h),
            self.damping_ratio,
            h,
        )
    }
}

/// This step's joint constraints, in a buffer reused from step to step.
#[derive(Debug, Clone, Default)]
pub(crate) struct JointConstraints {
    constraints: Vec<JointConstraint>,
    softness: Softness,
    /// The groups of joints linked by moving bodies whose holding rows are solved directly;
    /// only the first `group_count` are this step's (the rest keep their buffers).
    groups: Vec<GroupSystem>,
    group_count: usize,
    /// Scratch for grouping: the group of each root.
    group_of_root: Vec<usize>,
    /// Scratch: how many holding rows each group has.
    rows_of_group: Vec<usize>,
    /// Scratch: each joint's solver bodies if it is in a group.
    grouped_bodies: Vec<Option<[usize; 2]>>,
    /// The order in which the grouped joints' rows go into their groups.
    order: EliminationOrder,
    /// Whether the rows were built at the bodies' current poses: poses move only between the
    /// biased passes and the relax pass, so the rows the relax pass builds serve the next
    /// substep's warm start and biased passes too; only the first substep builds its own.
    rows_current: bool,
    /// Biased passes run so far in this substep: the groups are solved in the last.
    biased_passes: usize,
    /// Group solves this step that asked for impulses past the limit and applied nothing.
    refused_solves: usize,
}

/// What of a joint's description the solve reads.
#[derive(Debug, Clone, Copy)]
struct JointOptions {
    joint_type: JointType,
    limits: Option<[f32; 2]>,
    swing_limit: Option<f32>,
    twist_limits: Option<[f32; 2]>,
    motor: Option<Motor>,
    spring: Option<Spring>,
    /// Most friction torque (force for a prismatic joint), N·m or N.
    friction: f32,
    /// Revolute and prismatic joints: the inertia added to the coordinate, kg·m² or kg.
    armature: f32,
    /// Generic joints: each axis's freedom and motor.
    axes: [AxisFreedom; 6],
    motors: [Option<Motor>; 6],
}

impl JointOptions {
    /// Whether the joint holds its length rigidly (a distance joint without spring or limits).
    fn has_rigid_length(&self) -> bool {
        self.joint_type == JointType::Distance && self.spring.is_none() && self.limits.is_none()
    }

    /// Most rows the joint adds to its group's direct solve.
    fn holding_rows(&self) -> usize {
        match self.joint_type {
            JointType::Fixed => 6,
            JointType::Ball => 3,
            JointType::Revolute | JointType::Prismatic => 5 + usize::from(self.armature > 0.0),
            JointType::Distance => usize::from(self.has_rigid_length()),
            JointType::Generic => self.axes.iter().filter(|axis| !axis.moves()).count(),
        }
    }
}

/// One joint for this step.
#[derive(Debug, Clone)]
struct JointConstraint {
    /// The joint's slot in the [`JointSet`].
    slot: usize,
    options: JointOptions,
    frames: JointFrames,
    /// Solver indices of bodies A and B (0 for a side that does not move this step).
    solver: [usize; 2],
    /// The same for the dynamic sides only, 0 for a kinematic one, for the order of the group's
    /// joints: a kinematic body takes no impulse, so nothing couples through it.
    dynamic: [usize; 2],
    bodies: JointBodies,
    /// Centre of mass and rotation of each side as the step starts (read for a side that does
    /// not move).
    start_poses: [(Vec3, Quat); 2],
    impulses: JointImpulses,
    /// The group whose direct solve holds this joint together: every joint with a holding row
    /// has one.
    group: Option<usize>,
    /// Revolute joints: the angle counted across turns at the last refresh, rad.
    angle: f32,
    /// Joints with an armature: the rotor's speed, the joint's rate as the substep starts (as
    /// the last one ended), rad/s or m/s, and the impulse it has given the joint in this
    /// substep, N·m·s or N·s.
    rotor_speed: f32,
    armature_impulse: f32,
    /// Impulses on B summed over the substeps, N·s and N·m·s.
    step_linear: Vec3,
    step_angular: Vec3,
    geometry: Geometry,
}

impl JointConstraint {
    /// Adds the rows that hold the joint together at this substep's pose to `rows`; `index` is
    /// the joint's index among the step's constraints.
    fn push_holding_rows(&self, index: usize, rows: &mut Vec<GroupRow>) {
        let geometry = &self.geometry;
        let masses = (self.bodies.inverse_mass, self.bodies.inverse_inertia);
        let mut push = |accumulator, jacobian, error| {
            rows.push(GroupRow::new(
                (index, accumulator),
                self.solver,
                masses,
                jacobian,
                error,
            ));
        };
        if let Some(point) = &geometry.point {
            for (k, jacobian) in point.rows().into_iter().enumerate() {
                let axis = Vec3::AXES[k];
                push(
                    Accumulator::Linear(axis),
                    jacobian,
                    geometry.separation.dot(axis),
                );
            }
        }
        if geometry.locks_rotation {
            for (k, jacobian) in RotationPart::rows().into_iter().enumerate() {
                let axis = Vec3::AXES[k];
                push(
                    Accumulator::Angular(axis),
                    jacobian,
                    geometry.rotation_error.dot(axis),
                );
            }
        }
        if let Some(plane) = &geometry.plane {
            for ((jacobian, axis), error) in plane.rows().into_iter().zip(geometry.plane_errors) {
                let accumulator = match self.options.joint_type {
                    JointType::Revolute => Accumulator::Angular(axis),
                    _ => Accumulator::Linear(axis),
                };
                push(accumulator, jacobian, error);
            }
        }
        if self.options.has_rigid_length() {
            // Without a direction the row is all zeros, and gets no impulse; it stays in the
            // group so that the group's rows are the same all through the step.
            let row = geometry.axis_part.map_or(
                RowJacobian {
                    linear: [Vec3::ZERO; 2],
                    angular: [Vec3::ZERO; 2],
                },
                |axis| axis.row(),
            );
            push(
                Accumulator::Axial,
                row,
                geometry.position - self.frames.length,
            );
        }
        if let Some(generic) = &geometry.generic {
            for (k, freedom) in self.options.axes.iter().enumerate() {
                if freedom.moves() {
                    continue;
                }
                let direction = generic.direction(k);
                let accumulator = if k < 3 {
                    Accumulator::Linear(direction)
                } else {
                    Accumulator::Angular(direction)
                };
                push(accumulator, generic.parts[k].row(), generic.positions[k]);
            }
        }
        if let (Some(axis), true) = (&geometry.axis_part, self.options.armature > 0.0) {
            // The rotor: `J v = ω_rotor` with the compliance `1 / a`, so that the joint and
            // rotor share the impulse as one body of inertia `I + a` along the coordinate.
            push(Accumulator::Armature, axis.row(), 0.0);
            if let Some(row) = rows.last_mut() {
                row.compliance = 1.0 / self.options.armature;
            }
        }
    }

    /// Adds `impulse` to one of its holding rows' accumulated impulses.
    fn accumulate(&mut self, accumulator: Accumulator, impulse: f32) {
        match accumulator {
            Accumulator::Linear(axis) => self.impulses.linear += impulse * axis,
            Accumulator::Angular(axis) => self.impulses.angular += impulse * axis,
            Accumulator::Axial => self.impulses.axial += impulse,
            Accumulator::Armature => self.armature_impulse += impulse,
        }
    }

    /// The joint's rate along its coordinate at `v`, for the armature's rotor (0 without an
    /// axis).
    fn coordinate_rate(&self, v: &Velocities) -> f32 {
        self.geometry.axis_part.map_or(0.0, |axis| axis.velocity(v))
    }

    /// The impulse on B these accumulated impulses make: linear at B's anchor, and the couple.
    fn impulse_on_b(&self) -> (Vec3, Vec3) {
        let impulses = &self.impulses;
        let axis = self.geometry.axis;
        let along_axis = impulses.along_axis() + self.armature_impulse;
        match self.options.joint_type {
            JointType::Fixed => (impulses.linear, impulses.angular),
            JointType::Generic => {
                let (mut linear, mut angular) = (impulses.linear, impulses.angular);
                if let Some(generic) = &self.geometry.generic {
                    for k in 0..6 {
                        let along = impulses.axis_lower[k] - impulses.axis_upper[k]
                            + impulses.axis_motor[k];
                        if k < 3 {
                            linear += generic.direction(k) * along;
                        } else {
                            angular += generic.direction(k) * along;
                        }
                    }
                }
                (linear, angular)
            }
            JointType::Ball => (
                impulses.linear,
                axis * (impulses.twist_lower - impulses.twist_upper)
                    - self.geometry.swing_axis * impulses.swing
                    + impulses.friction_couple,
            ),
            JointType::Revolute => (impulses.linear, impulses.angular + axis * along_axis),
            JointType::Prismatic => (impulses.linear + axis * along_axis, impulses.angular),
            JointType::Distance => (
                axis * (impulses.axial + impulses.lower - impulses.upper),
                Vec3::ZERO,
            ),
        }
    }

    /// Applies the accumulated impulses again.
    fn warm_start(&mut self, v: &mut Velocities) {
        // The speed limits take momentum out between substeps; a joint that drags a body faster
        // than they allow (round a fast kinematic body, say) answers with more impulse each
        // substep, growing without bound until it overflows. Past what bodies within the limits
        // exchange, it starts the substep again from nothing.
        if !self.impulses.is_within(MAX_SOLVER_IMPULSE) {
            self.impulses = JointImpulses::default();
        }
        self.armature_impulse = 0.0;
        let (geometry, impulses, bodies) = (&self.geometry, &self.impulses, &self.bodies);
        if let Some(point) = &geometry.point {
            point.apply(bodies, v, impulses.linear);
        }
        if geometry.locks_rotation {
            RotationPart::apply(bodies, v, impulses.angular);
        }
        if let Some(plane) = &geometry.plane {
            let vector = match self.options.joint_type {
                JointType::Revolute => impulses.angular,
                _ => impulses.linear,
            };
            plane.apply(bodies, v, vector);
        }
        if let Some(axis) = &geometry.axis_part {
            let scalar = match self.options.joint_type {
                JointType::Ball => impulses.twist_lower - impulses.twist_upper,
                _ => impulses.along_axis(),
            };
            axis.apply(bodies, v, scalar);
        }
        if geometry.friction.is_some() {
            RotationPart::apply(bodies, v, impulses.friction_couple);
        }
        if let Some(generic) = &geometry.generic {
            // A locked axis's share of the linear or angular impulse kept as a world vector
            // (the frame has turned since), and a moving axis's limits and motor.
            for (k, freedom) in self.options.axes.iter().enumerate() {
                let scalar = if freedom.moves() {
                    impulses.axis_lower[k] - impulses.axis_upper[k] + impulses.axis_motor[k]
                } else if k < 3 {
                    impulses.linear.dot(generic.direction(k))
                } else {
                    impulses.angular.dot(generic.direction(k))
                };
                generic.parts[k].apply(bodies, v, scalar);
            }
        }
        if let Some(swing) = &geometry.swing {
            swing.apply(bodies, v, -impulses.swing);
        }
    }

    /// One pass over the joint's rows solved one at a time: motor, friction, spring and limits.
    /// What holds the joint together is its group's, solved after every joint's pass
    /// ([`JointConstraints::solve_groups`]), so it is the most nearly met when the pass ends.
    ///
    /// Springs (and position motors, springs towards a target) pull in the biased passes only,
    /// with the force of the substep's starting pose, which makes them symplectic Euler. Solved
    /// again in the relax pass at the pose the substep ended on, the substep's impulse became
    /// `−h k C` at the end pose while the bodies had moved with the one at the start: a drag of
    /// `h² k` times the speed a substep, which took 17 % off an undamped spring's amplitude in
    /// five periods (`tests/joints/drives.rs`).
    fn solve(
        &mut self,
        v: &mut Velocities,
        softness: RowSoftness,
        (h, inverse_h): (f32, f32),
        biased: bool,
    ) {
        let (geometry, impulses, bodies) = (&self.geometry, &mut self.impulses, &self.bodies);
        let options = &self.options;
        if let Some(axis) = &geometry.axis_part {
            let position = geometry.position;
            let armature = options.armature;
            let given_before = impulses.along_axis();
            // With an armature the rows below move the bodies and the rotor together, one
            // inertia `K⁻¹ + a` along the coordinate, as MuJoCo's limits and damping see the
            // armature: a row on the bodies alone, light beside their rotor, is undone by the
            // group's rotor row after it, and lets the rotor carry a limb through its limit
            // (Gymnasium Ant's ankles went 13° past theirs). The rotor first shares its
            // momentum with the bodies (both then turn at `(K⁻¹ Ċ + a ω_rotor) / (K⁻¹ + a)`);
            // each row's impulse then reaches the bodies in the share `1 / (1 + a K)`, the rest
            // turning the rotor.
            let axis = if armature > 0.0 {
                let rotor = self.rotor_speed - self.armature_impulse / armature;
                self.armature_impulse += axis.share_with_rotor(bodies, v, armature, rotor);
                axis.geared(armature)
            } else {
                *axis
            };
            solve_motor(
                &axis,
                options.motor,
                (position, biased, h),
                bodies,
                v,
                &mut impulses.motor,
            );
            if options.friction > 0.0 && options.joint_type != JointType::Ball {
                let most = options.friction * h;
                axis.solve_velocity_motor(bodies, v, 0.0, most, &mut impulses.friction);
            }
            if let (Some(spring), true) = (options.spring, biased) {
                let rest = match options.joint_type {
                    JointType::Distance => self.frames.length,
                    _ => spring.reference,
                };
                axis.solve_spring(
                    bodies,
                    v,
                    position - rest,
                    (spring.stiffness, spring.damping, h),
                    f32::INFINITY,
                    &mut impulses.axial,
                );
            }
            let limits = match options.joint_type {
                JointType::Ball => options.twist_limits,
                _ => options.limits,
            };
            let (lower, upper) = match options.joint_type {
                JointType::Ball => (&mut impulses.twist_lower, &mut impulses.twist_upper),
                _ => (&mut impulses.lower, &mut impulses.upper),
            };
            if let Some([min, max]) = limits {
                let pass = (softness, inverse_h);
                axis.solve_limit(bodies, v, (position - min, 1.0), pass, lower);
                axis.solve_limit(bodies, v, (max - position, -1.0), pass, upper);
            }
            if armature > 0.0 {
                // The rotor's part of what the rows gave, as the impulse it gives the bodies.
                let given = impulses.along_axis() - given_before;
                self.armature_impulse -= given * (1.0 - axis.body_share());
            }
        }
        if let Some(generic) = &geometry.generic {
            for k in 0..6 {
                let (part, position) = (&generic.parts[k], generic.positions[k]);
                let motor = &mut impulses.axis_motor[k];
                let when = (position, biased, h);
                solve_motor(part, options.motors[k], when, bodies, v, motor);
                if let AxisFreedom::Limited([min, max]) = options.axes[k] {
                    let pass = (softness, inverse_h);
                    let lower = &mut impulses.axis_lower[k];
                    part.solve_limit(bodies, v, (position - min, 1.0), pass, lower);
                    let upper = &mut impulses.axis_upper[k];
                    part.solve_limit(bodies, v, (max - position, -1.0), pass, upper);
                }
            }
        }
        if let Some(friction) = &geometry.friction {
            let most = options.friction * h;
            friction.solve_friction(bodies, v, most, &mut impulses.friction_couple);
        }
        if let (Some(swing), Some(limit)) = (&geometry.swing, options.swing_limit) {
            let gap = (limit - geometry.swing_angle, -1.0);
            swing.solve_limit(bodies, v, gap, (softness, inverse_h), &mut impulses.swing);
        }
    }
}

impl JointConstraints {
    /// Sorts the joints into the groups the islands found ([`SolverBodies::group_root`], groups
    /// numbered in joint order) and orders their joints for the direct solve
    /// ([`EliminationOrder`]).
    fn group(&mut self, solver_bodies: &SolverBodies) {
        let body_count = solver_bodies.states.len();
        self.group_of_root.clear();
        self.group_of_root.resize(body_count, usize::MAX);
        let rows_of_group = &mut self.rows_of_group;
        rows_of_group.clear();
        self.group_count = 0;
        for constraint in &mut self.constraints {
            let root = solver_bodies.group_root(constraint.solver);
            if self.group_of_root[root] == usize::MAX {
                self.group_of_root[root] = self.group_count;
                self.group_count += 1;
                rows_of_group.push(0);
            }
            let group = self.group_of_root[root];
            rows_of_group[group] += constraint.options.holding_rows();
            constraint.group = Some(group);
        }
        for constraint in &mut self.constraints {
            if let Some(group) = constraint.group {
                if rows_of_group[group] == 0 {
                    constraint.group = None;
                }
            }
        }
        if self.groups.len() < self.group_count {
            self.groups
                .resize_with(self.group_count, GroupSystem::default);
        }
        for group in &mut self.groups[..self.group_count] {
            group.forget_structure();
        }
        self.grouped_bodies.clear();
        self.grouped_bodies.extend(
            self.constraints
                .iter()
                .map(|constraint| constraint.group.map(|_| constraint.dynamic)),
        );
        self.order.find(&self.grouped_bodies, body_count);
    }

    /// Refreshes every joint's geometry for the current poses and builds each group's rows
    /// and factors it.
    fn refresh(&mut self, motions: &[BodyMotion]) {
        for group in &mut self.groups[..self.group_count] {
            group.rows.clear();
        }
        for constraint in &mut self.constraints {
            constraint.refresh(motions);
        }
        for &index in self.order.joints() {
            let constraint = &self.constraints[index];
            if let Some(group) = constraint.group {
                constraint.push_holding_rows(index, &mut self.groups[group].rows);
            }
        }
        // A dependent row's pivot: the soft spring's compliance `γ = A_ii / a₂`, relative to
        // `A_ii` (`softness.rs`: `mass_scale = a₂ / (1 + a₂)`, `impulse_scale = 1 / (1 + a₂)`).
        let regularisation = self.softness.impulse_scale / self.softness.mass_scale;
        for group in &mut self.groups[..self.group_count] {
            group.factor(regularisation);
        }
    }

    /// Group solves this step that asked any row for an impulse past [`MAX_SOLVER_IMPULSE`], or
    /// one not finite, and applied nothing.
    pub fn refused_solves(&self) -> usize {
        self.refused_solves
    }

    /// One direct solve of every group's holding rows.
    fn solve_groups(&mut self, states: &mut [BodyState], softness: RowSoftness) {
        let constraints = &mut self.constraints;
        for group in &mut self.groups[..self.group_count] {
            if group.rows.is_empty() {
                continue;
            }
            for row in &mut group.rows {
                if row.accumulator == Accumulator::Armature {
                    let joint = &constraints[row.joint];
                    row.offset = row.compliance * joint.armature_impulse - joint.rotor_speed;
                }
            }
            if !group.solve(states, softness) {
                self.refused_solves += 1;
            }
            for (row, impulse) in group.impulses() {
                constraints[row.joint].accumulate(row.accumulator, impulse);
            }
        }
    }

    /// Runs `each` on every joint with the velocities of its two bodies, then writes them back
    /// (solver body 0 never changes).
    fn for_each_joint(
        &mut self,
        states: &mut [BodyState],
        mut each: impl FnMut(&mut JointConstraint, &mut Velocities),
    ) {
        for constraint in &mut self.constraints {
            let [a, b] = constraint.solver;
            let mut v = Velocities {
                linear: [
                    states[a].linear_velocity.into(),
                    states[b].linear_velocity.into(),
                ],
                angular: [
                    states[a].angular_velocity.into(),
                    states[b].angular_velocity.into(),
                ],
            };
            each(constraint, &mut v);
            for (side, index) in [a, b].into_iter().enumerate() {
                if index != 0 {
                    states[index].linear_velocity = v.linear[side].into();
                    states[index].angular_velocity = v.angular[side].into();
                }
            }
        }
    }
}

impl ConstraintKind for JointConstraints {
    type Source = JointSet;

    /// Takes every acting joint with a body that moves this step, with last step's impulses.
    fn prepare(&mut self, joints: &JointSet, solver_bodies: &SolverBodies, context: &StepContext) {
        self.constraints.clear();
        self.softness = context.joint.softness(context.h, context.inverse_h);
        for (slot, joint, data) in joints.acting() {
            let solver = data
                .poses
                .map(|pose| pose.slot.map_or(0, |slot| solver_bodies.solver_index(slot)));
            if solver == [0, 0] {
                continue;
            }
            let motions = solver.map(|index| &solver_bodies.motions[index]);
            let desc = &joint.desc;
            let mut impulses = data.impulses;
            match desc.motor {
                // A torque motor's impulse is its torque over a substep, set anew each step
                // (the torque may have changed) and applied by every substep's warm start; the
                // passes leave it alone.
                Some(Motor::Torque { torque }) => impulses.motor = torque * context.h,
                // No pass touches the motor's impulse once the motor is gone: left, the warm
                // start would go on applying it.
                None => impulses.motor = 0.0,
                Some(Motor::Velocity { .. } | Motor::Position { .. }) => {}
            }
            for (impulse, motor) in impulses.axis_motor.iter_mut().zip(&desc.motors) {
                match motor {
                    Some(Motor::Torque { torque }) => *impulse = torque * context.h,
                    None => *impulse = 0.0,
                    Some(Motor::Velocity { .. } | Motor::Position { .. }) => {}
                }
            }
            self.constraints.push(JointConstraint {
                slot,
                options: JointOptions {
                    joint_type: desc.joint_type,
                    limits: desc.limits,
                    swing_limit: desc.swing_limit,
                    twist_limits: desc.twist_limits,
                    motor: desc.motor,
                    spring: desc.spring,
                    friction: desc.friction,
                    armature: desc.armature,
                    axes: desc.axes,
                    motors: desc.motors,
                },
                frames: joint.frames,
                solver,
                dynamic: [0, 1].map(|side| {
                    if motions[side].is_dynamic {
                        solver[side]
                    } else {
                        0
                    }
                }),
                bodies: JointBodies {
                    inverse_mass: motions.map(BodyMotion::inverse_mass_diagonal),
                    inverse_inertia: motions.map(|motion| motion.world_inverse_inertia),
                },
                start_poses: data.poses.map(|pose| (pose.center_of_mass, pose.rotation)),
                impulses,
                group: None,
                angle: joint.angle,
                rotor_speed: 0.0,
                armature_impulse: 0.0,
                step_linear: Vec3::ZERO,
                step_angular: Vec3::ZERO,
                geometry: Geometry::default(),
            });
        }
        // The rotors start the step at their joints' rates: the bodies' velocities as the step
        // starts (before the first substep's forces), which a saved state holds, so a resumed
        // run goes on with the same bits.
        for constraint in &mut self.constraints {
            if constraint.options.armature > 0.0 {
                constraint.refresh(&solver_bodies.motions);
                let [a, b] = constraint.solver;
                let states = &solver_bodies.states;
                let v = Velocities {
                    linear: [a, b].map(|index| states[index].linear_velocity.into()),
                    angular: [a, b].map(|index| states[index].angular_velocity.into()),
                };
                constraint.rotor_speed = constraint.coordinate_rate(&v);
            }
        }
        self.group(solver_bodies);
        self.rows_current = false;
        self.refused_solves = 0;
    }

    /// Applies each joint's accumulated impulses, with rows at the substep's poses (built here in
    /// the first substep, by the last relax pass in the others).
    fn warm_start(&mut self, states: &mut [BodyState], motions: &[BodyMotion]) {
        if !self.rows_current {
            self.refresh(motions);
            self.rows_current = true;
        }
        self.for_each_joint(states, |constraint, v| constraint.warm_start(v));
        self.biased_passes = 0;
    }

    fn prepare_biased_passes(&mut self, _states: &[BodyState], _context: &StepContext) {}

    /// One pass; the relax pass (no bias) ends the substep, so it also adds the substep's
    /// impulses to the step's sums.
    fn solve<const USE_BIAS: bool>(
        &mut self,
        states: &mut [BodyState],
        motions: &[BodyMotion],
        context: &StepContext,
    ) {
        let softness = RowSoftness::of_pass(&self.softness, USE_BIAS);
        let times = (context.h, context.inverse_h);
        if !USE_BIAS {
            self.refresh(motions);
        }
        self.for_each_joint(states, |constraint, v| {
            constraint.solve(v, softness, times, USE_BIAS)
        });
        // The groups are solved exactly in the last biased pass only; in the ones before, the
        // contacts meet the joints' warm-started impulses and one-row parts alone. Solving the
        // groups in every biased pass costs half again as many solves and leaves the joints
        // further apart: 8.1 against 7.6 mm in `bench/compare`'s ragdoll pile, 1.46 against
        // 1.09 mm on its bridge (`docs/design-notes/joints.md`).
        if USE_BIAS {
            self.biased_passes += 1;
        }
        if !USE_BIAS || self.biased_passes == BIASED_ITERATIONS {
            self.solve_groups(states, RowSoftness::rigid_of_pass(&self.softness, USE_BIAS));
        }
        if !USE_BIAS {
            for constraint in &mut self.constraints {
                let (linear, angular) = constraint.impulse_on_b();
                constraint.step_linear += linear;
                constraint.step_angular += angular;
            }
            // The rotor ends the substep at the joint's rate: the group's solve, last, met it.
            self.for_each_joint(states, |constraint, v| {
                if constraint.options.armature > 0.0 {
                    constraint.rotor_speed = constraint.coordinate_rate(v);
                }
            });
        }
    }

    fn apply_restitution(&mut self, _states: &mut [BodyState]) {}

    fn store_impulses(&self, joints: &mut JointSet) {
        for constraint in &self.constraints {
            if let Some((joint, data)) = joints.at_slot_mut(constraint.slot) {
                joint.angle = constraint.angle;
                // Impulses past what bodies within the limits can exchange (a motor of unlimited
                // force that cannot reach its target within the speed limits, a joint dragging a
                // body round a fast kinematic one) would grow from step to step until they
                // overflow and poison every later step.
                data.impulses = if constraint.impulses.is_within(MAX_SOLVER_IMPULSE) {
                    constraint.impulses
                } else {
                    JointImpulses::default()
                };
                data.step_linear = constraint.step_linear;
                data.step_angular = constraint.step_angular;
                data.solved = true;
            }
        }
    }
}

/// One pass of `motor` on the coordinate of `part` at `position` (rad or m), substep `h`: a
/// velocity motor in every pass, a position motor in the biased passes only (its spring pulls
/// on the position error, as springs do), a torque motor never (it is a force the integration
/// applies).
fn solve_motor(
    part: &AxisPart,
    motor: Option<Motor>,
    (position, biased, h): (f32, bool, f32),
    bodies: &JointBodies,
    v: &mut Velocities,
    impulse: &mut f32,
) {
    match motor {
        Some(Motor::Velocity {
            target_velocity,
            max_force,
        }) => part.solve_velocity_motor(bodies, v, target_velocity, max_force * h, impulse),
        Some(Motor::Position {
            target_position,
            stiffness,
            damping,
            max_force,
        }) if biased => part.solve_spring(
            bodies,
            v,
            position - target_position,
            (stiffness, damping, h),
            max_force * h,
            impulse,
        ),
        Some(Motor::Position { .. } | Motor::Torque { .. }) | None => {}
    }
}
