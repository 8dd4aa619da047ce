//! The couplings as a constraint kind (`crate::coupling`, `docs/joints.md` "Couplings"): one
//! row per coupling on the bodies of its joints, `L̇ = Σ cᵢ q̇ᵢ`, each joint's part the row
//! its own axis has in `joints/`:
//! - revolute: `q̇ = (ω_B − ω_A)·a`, `a` the axis fixed in A;
//! - prismatic: `q̇ = a·(v_B + ω_B × r_B − v_A − ω_A × r_A) + (p_B − p_A)·(ω_A × a)`, so A's
//!   angular part is `−(r_A + p_B − p_A) × a` (the lever of the prismatic row).
//!
//! A body met by several of the joints (the thigh between hip and knee) has one entry with the
//! sum of its parts, so the effective mass `K = Σ_bodies (l·M⁻¹ l + a·I⁻¹ a)` counts the cross
//! terms. The row is solved one at a time, as the joints' limits and springs are: the spring in
//! the biased passes only (`joints/` says why), the limits softly in the biased passes and
//! rigidly in the relax pass. The geometry follows the poses as the joints' does: rebuilt at the
//! first substep's warm start and for every relax pass.

use std::ops::Range;

use super::joint_parts::{limit_impulse, spring_impulse, RowSoftness};
use super::softness::Softness;
use super::stages::{ConstraintKind, StepContext};
use super::{BodyMotion, BodyState, SolverBodies};
use crate::coupling::{CoupledJoint, CouplingImpulses, CouplingSet};
use crate::joint::{relative_rotation, twist_angle, unwrap_angle, JointFrames, JointType};
use crate::math::{Mat3, Quat, Vec3, Vec3A};

/// This step's coupling constraints, in buffers reused from step to step.
#[derive(Debug, Clone, Default)]
pub(crate) struct CouplingConstraints {
    constraints: Vec<CouplingConstraint>,
    /// The coupled joints of every constraint, each constraint's a range.
    joints: Vec<StepJoint>,
    /// The row's entries of every constraint, one per moving body, each constraint's a range.
    entries: Vec<Entry>,
    softness: Softness,
    /// Whether the rows were built at the bodies' current poses (as `joints/` keeps it).
    rows_current: bool,
}

/// One coupling for this step.
#[derive(Debug, Clone)]
struct CouplingConstraint {
    slot: usize,
    joints: Range<usize>,
    entries: Range<usize>,
    limits: Option<[f32; 2]>,
    stiffness: f32,
    damping: f32,
    rest_length: f32,
    /// `L` at the current substep's poses, rad or m.
    length: f32,
    /// `K` of the row and `K⁻¹`, both zero where nothing moves along it.
    k: f32,
    mass: f32,
    impulses: CouplingImpulses,
}

/// A coupled joint for this step.
#[derive(Debug, Clone, Copy)]
struct StepJoint {
    coefficient: f32,
    joint_type: JointType,
    frames: JointFrames,
    /// Solver indices of its sides (0 for a side that does not move this step).
    solver: [usize; 2],
    start_poses: [(Vec3, Quat); 2],
    /// Revolute joints: the angle counted across turns at the last refresh, rad.
    angle: f32,
}

/// One moving body's part of a coupling's row: `L̇ += l·v + a·ω`; an impulse `λ` along the row
/// changes its velocities by `M⁻¹ l λ` and `I⁻¹ a λ`.
#[derive(Debug, Clone, Copy)]
struct Entry {
    index: usize,
    linear: Vec3,
    angular: Vec3,
    inverse_mass: Vec3,
    inverse_inertia: Mat3,
}

impl StepJoint {
    /// The coordinate `q` at this substep's poses and its row's parts on sides A and B
    /// (linear, angular), module documentation.
    fn refresh(&mut self, motions: &[BodyMotion]) -> (f32, [(Vec3, Vec3); 2]) {
        let pose = |side: usize| match self.solver[side] {
            0 => self.start_poses[side],
            index => (motions[index].center_of_mass, motions[index].rotation),
        };
        let ((center_a, rotation_a), (center_b, rotation_b)) = (pose(0), pose(1));
        let frames = &self.frames;
        let axis = rotation_a * frames.local_axis_a;
        if self.joint_type == JointType::Revolute {
            let relative = relative_rotation(frames, rotation_a, rotation_b);
            let twist = twist_angle(relative, frames.local_axis_a);
            self.angle = unwrap_angle(twist, self.angle);
            return (self.angle, [(Vec3::ZERO, -axis), (Vec3::ZERO, axis)]);
        }
        let arm_a = rotation_a * frames.local_anchor_a;
        let arm_b = rotation_b * frames.local_anchor_b;
        let separation = center_b + arm_b - (center_a + arm_a);
        let lever_a = (arm_a + separation).cross(axis);
        (
            separation.dot(axis),
            [(-axis, -lever_a), (axis, arm_b.cross(axis))],
        )
    }
}

impl CouplingConstraint {
    fn velocity(&self, entries: &[Entry], states: &[BodyState]) -> f32 {
        entries[self.entries.clone()]
            .iter()
            .map(|entry| {
                let state = &states[entry.index];
                entry.linear.dot(state.linear_velocity.into())
                    + entry.angular.dot(state.angular_velocity.into())
            })
            .sum()
    }

    fn apply(&self, entries: &[Entry], states: &mut [BodyState], impulse: f32) {
        for entry in &entries[self.entries.clone()] {
            let state = &mut states[entry.index];
            state.linear_velocity += Vec3A::from(entry.inverse_mass * entry.linear * impulse);
            state.angular_velocity += Vec3A::from(entry.inverse_inertia * entry.angular * impulse);
        }
    }

    /// One pass over the row: the spring (biased passes only), then the limits, with the soft
    /// row's coefficients of the pass and the rigid ones.
    fn solve(
        &mut self,
        entries: &[Entry],
        states: &mut [BodyState],
        (softness, rigid): (RowSoftness, RowSoftness),
        (h, inverse_h): (f32, f32),
        biased: bool,
    ) {
        if biased && (self.stiffness > 0.0 || self.damping > 0.0) {
            let velocity = self.velocity(entries, states);
            let applied = spring_impulse(
                (self.k, velocity),
                self.length - self.rest_length,
                (self.stiffness, self.damping, h),
                f32::INFINITY,
                &mut self.impulses.spring,
            );
            self.apply(entries, states, applied);
        }
        match self.limits {
            Some([min, max]) if min == max => {
                // An equality is one two-sided row, rigid with the soft position correction as
                // the joints' holding rows are (`RowSoftness::rigid_of_pass`): solved softly, the
                // spring's give let a geared pair lose 1.6 % of its motion in 2 s.
                let velocity = self.velocity(entries, states);
                let impulse = -self.mass * (velocity + rigid.bias(self.length - min));
                self.impulses.lower += impulse;
                self.apply(entries, states, impulse);
            }
            Some([min, max]) => self.solve_limits([min, max], entries, states, softness, inverse_h),
            None => {}
        }
    }

    /// The limits as two one-sided rows (`AxisPart::solve_limit`).
    fn solve_limits(
        &mut self,
        [min, max]: [f32; 2],
        entries: &[Entry],
        states: &mut [BodyState],
        softness: RowSoftness,
        inverse_h: f32,
    ) {
        {
            let pass = (softness, inverse_h);
            for (gap, sign) in [(self.length - min, 1.0), (max - self.length, -1.0)] {
                let velocity = self.velocity(entries, states);
                let accumulated = if sign > 0.0 {
                    &mut self.impulses.lower
                } else {
                    &mut self.impulses.upper
                };
                let applied = limit_impulse(velocity, self.mass, (gap, sign), pass, accumulated);
                self.apply(entries, states, sign * applied);
            }
        }
    }
}

impl CouplingConstraints {
    /// Rebuilds every coupling's `L` and row at the current poses.
    fn refresh(&mut self, motions: &[BodyMotion]) {
        self.entries.clear();
        for constraint in &mut self.constraints {
            let start = self.entries.len();
            let mut length = 0.0;
            for joint in &mut self.joints[constraint.joints.clone()] {
                let (position, sides) = joint.refresh(motions);
                let c = joint.coefficient;
                length += c * position;
                for (index, (linear, angular)) in joint.solver.into_iter().zip(sides) {
                    if index == 0 {
                        continue;
                    }
                    let entries = &mut self.entries[start..];
                    match entries.iter_mut().find(|entry| entry.index == index) {
                        Some(entry) => {
                            entry.linear += c * linear;
                            entry.angular += c * angular;
                        }
                        None => self.entries.push(Entry {
                            index,
                            linear: c * linear,
                            angular: c * angular,
                            inverse_mass: motions[index].inverse_mass_diagonal(),
                            inverse_inertia: motions[index].world_inverse_inertia,
                        }),
                    }
                }
            }
            constraint.entries = start..self.entries.len();
            constraint.length = length;
            let k: f32 = self.entries[start..]
                .iter()
                .map(|entry| {
                    entry.linear.dot(entry.inverse_mass * entry.linear)
                        + entry.angular.dot(entry.inverse_inertia * entry.angular)
                })
                .sum();
            (constraint.k, constraint.mass) = if k > 0.0 && k.is_finite() {
                (k, 1.0 / k)
            } else {
                (0.0, 0.0)
            };
        }
    }
}

impl ConstraintKind for CouplingConstraints {
    type Source = CouplingSet;

    /// Takes every acting coupling with a body that moves this step, with last step's impulses.
    fn prepare(
        &mut self,
        couplings: &CouplingSet,
        solver_bodies: &SolverBodies,
        context: &StepContext,
    ) {
        self.constraints.clear();
        self.joints.clear();
        self.softness = context.joint.softness(context.h, context.inverse_h);
        for (slot, coupling, coupled, impulses) in couplings.acting() {
            let start = self.joints.len();
            let solver_index = |joint: &CoupledJoint, side: usize| {
                joint.sides[side]
                    .slot
                    .map_or(0, |slot| solver_bodies.solver_index(slot))
            };
            self.joints.extend(coupled.iter().map(|joint| StepJoint {
                coefficient: joint.coefficient,
                joint_type: joint.joint_type,
                frames: joint.frames,
                solver: [0, 1].map(|side| solver_index(joint, side)),
                start_poses: joint.sides.map(|side| (side.center_of_mass, side.rotation)),
                angle: joint.angle,
            }));
            if self.joints[start..]
                .iter()
                .all(|joint| joint.solver == [0, 0])
            {
                self.joints.truncate(start);
                continue;
            }
            let desc = &coupling.desc;
            self.constraints.push(CouplingConstraint {
                slot,
                joints: start..self.joints.len(),
                entries: 0..0,
                limits: desc.limits,
                stiffness: desc.stiffness,
                damping: desc.damping,
                rest_length: coupling.length,
                length: 0.0,
                k: 0.0,
                mass: 0.0,
                impulses,
            });
        }
        self.rows_current = false;
    }

    /// Applies each coupling's accumulated impulses along its row at the substep's poses.
    fn warm_start(&mut self, states: &mut [BodyState], motions: &[BodyMotion]) {
        if !self.rows_current {
            self.refresh(motions);
            self.rows_current = true;
        }
        for constraint in &self.constraints {
            let impulses = &constraint.impulses;
            let impulse = impulses.spring + impulses.lower - impulses.upper;
            constraint.apply(&self.entries, states, impulse);
        }
    }

    fn prepare_biased_passes(&mut self, _states: &[BodyState], _context: &StepContext) {}

    fn solve<const USE_BIAS: bool>(
        &mut self,
        states: &mut [BodyState],
        motions: &[BodyMotion],
        context: &StepContext,
    ) {
        if !USE_BIAS {
            self.refresh(motions);
        }
        let softness = (
            RowSoftness::of_pass(&self.softness, USE_BIAS),
            RowSoftness::rigid_of_pass(&self.softness, USE_BIAS),
        );
        let times = (context.h, context.inverse_h);
        for constraint in &mut self.constraints {
            constraint.solve(&self.entries, states, softness, times, USE_BIAS);
        }
    }

    fn apply_restitution(&mut self, _states: &mut [BodyState]) {}

    /// Keeps the impulses for the next step's warm start; impulses past what bodies within the
    /// limits exchange (or not finite) start it cold instead, as the joints' do.
    fn store_impulses(&self, couplings: &mut CouplingSet) {
        for constraint in &self.constraints {
            if let Some((_, impulses)) = couplings.at_slot_mut(constraint.slot) {
                *impulses = if constraint.impulses.is_within_limit() {
                    constraint.impulses
                } else {
                    CouplingImpulses::default()
                };
            }
        }
    }
}
