//! The direct solve of the rows that hold jointed bodies together.
//!
//! Sequential impulses pass forces along a chain one joint per iteration, and each joint sees
//! only its two bodies: a 100 kg weight on 1 kg links needs hundreds of iterations before the
//! top link feels it, so the chain stretches and bounces. Instead, the equality rows of all the
//! joints that share moving bodies (a group: a chain, a ragdoll, a vehicle) are solved together,
//! exactly: `A λ = −(J v + b C)` with `A = J M⁻¹ Jᵀ`, factored once per pose (`A = L Lᵀ`, Cholesky
//! over each row's profile, so a chain costs what a band matrix does). Only the profiles are
//! stored, so a group of any size is solved exactly: a net of hundreds of joints costs its
//! profiles, not `n²`. A joint's rows share their profile and are factored together, one SIMD
//! lane a row ([`Block`]). Limits, motors and springs stay one row at a time (`joints/`): they are
//! inequalities or soft by design.
//!
//! A row that depends on the ones before it (a bridge fixed at both ends, a four-bar linkage)
//! has no pivot of its own: it gets the one the joints' softness gives it, the compliance
//! `γ = A_ii / a₂` of the soft spring (`softness.rs`), so it shares the load softly with the rows
//! it depends on instead of being dropped.

use super::joint_parts::{RowJacobian, RowSoftness};
use super::wide::{F32x4, LANES};
use super::BodyState;
use crate::limits::MAX_SOLVER_IMPULSE;
use crate::math::{Mat3, Vec3, Vec3A};

/// Where a row's accumulated impulse lives in its joint's `JointImpulses`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Accumulator {
    /// `linear · axis`.
    Linear(Vec3),
    /// `angular · axis`.
    Angular(Vec3),
    /// `axial`.
    Axial,
    /// The armature's rotor (revolute, prismatic): the joint's own sum for the substep, not
    /// warm-started.
    Armature,
}

/// One equality row of a group.
#[derive(Debug, Clone, Copy)]
pub(super) struct GroupRow {
    /// The joint (index among this step's joint constraints) and where its impulse goes.
    pub joint: usize,
    pub accumulator: Accumulator,
    /// Solver indices of the row's bodies (0 for one that does not move).
    pub bodies: [usize; 2],
    /// Whether each side's body takes impulses: not body 0, not a kinematic body (no inverse
    /// mass or inertia). Rows couple only through such bodies.
    takes_impulses: [bool; 2],
    pub jacobian: RowJacobian,
    /// `M⁻¹ Jᵀ` per side: the velocity change a unit impulse gives.
    pub linear_response: [Vec3; 2],
    pub angular_response: [Vec3; 2],
    /// Position error `C` at the pose the row was built for.
    pub error: f32,
    /// A soft row's compliance `γ`, added to its diagonal of `A` (0 for a rigid row), and the
    /// term its solve adds to `J v` (the armature's `γ λ_acc − ω_rotor`), set before each solve.
    pub compliance: f32,
    pub offset: f32,
}

impl GroupRow {
    pub fn new(
        (joint, accumulator): (usize, Accumulator),
        bodies: [usize; 2],
        (inverse_mass, inverse_inertia): ([Vec3; 2], [Mat3; 2]),
        jacobian: RowJacobian,
        error: f32,
    ) -> Self {
        Self {
            joint,
            accumulator,
            bodies,
            takes_impulses: [0, 1].map(|side| {
                bodies[side] != 0
                    && (inverse_mass[side] != Vec3::ZERO || inverse_inertia[side] != Mat3::ZERO)
            }),
            jacobian,
            linear_response: [0, 1].map(|side| inverse_mass[side] * jacobian.linear[side]),
            angular_response: [0, 1].map(|side| inverse_inertia[side] * jacobian.angular[side]),
            error,
            compliance: 0.0,
            offset: 0.0,
        }
    }

    /// `J v` for the bodies' current velocities.
    fn velocity(&self, states: &[BodyState]) -> f32 {
        (0..2)
            .map(|side| {
                let state = &states[self.bodies[side]];
                self.jacobian.linear[side].dot(state.linear_velocity.into())
                    + self.jacobian.angular[side].dot(state.angular_velocity.into())
            })
            .sum()
    }

    /// `v += M⁻¹ Jᵀ λ`; body 0 never moves.
    fn apply(&self, states: &mut [BodyState], impulse: f32) {
        for side in 0..2 {
            let body = self.bodies[side];
            if body != 0 {
                let state = &mut states[body];
                state.linear_velocity += Vec3A::from(impulse * self.linear_response[side]);
                state.angular_velocity += Vec3A::from(impulse * self.angular_response[side]);
            }
        }
    }
}

/// One body side of a row: its Jacobian and response on that body.
#[derive(Debug, Clone, Copy)]
struct SideTerms {
    linear: Vec3A,
    angular: Vec3A,
    linear_response: Vec3A,
    angular_response: Vec3A,
}

impl SideTerms {
    fn of(row: &GroupRow, side: usize) -> Self {
        Self {
            linear: row.jacobian.linear[side].into(),
            angular: row.jacobian.angular[side].into(),
            linear_response: row.linear_response[side].into(),
            angular_response: row.angular_response[side].into(),
        }
    }

    /// The part of `J_i M⁻¹ J_jᵀ` that this side and `other` (on the same body) give.
    fn coupling(&self, other: &Self) -> f32 {
        self.linear.dot(other.linear_response) + self.angular.dot(other.angular_response)
    }
}

/// Up to [`LANES`] consecutive rows whose profiles start at the same column, factored
/// together: column `k` of the block (`first ≤ k < start + len`) holds `L_ik` of each of its
/// rows `i`, one lane a row, so one pass over an earlier row's profile serves every row of the
/// block. A joint's rows share their bodies, so they share their profile and make a block.
#[derive(Debug, Clone, Copy)]
struct Block {
    /// The block's rows: `start..start + len`.
    start: usize,
    len: usize,
    /// The first column of the rows' profiles: `A_ij = 0` for `j < first`.
    first: usize,
    /// Where column `first` of the block lies in the factor.
    columns: usize,
}

impl Block {
    /// Where column `k` of the block lies in the factor.
    fn column(&self, k: usize) -> usize {
        self.columns + k - self.first
    }
}

/// A group's rows and the Cholesky factor of its `A`, in buffers the caller reuses.
#[derive(Debug, Clone, Default)]
pub(super) struct GroupSystem {
    pub rows: Vec<GroupRow>,
    /// `L` below the diagonal, by blocks of rows ([`Block`]), a column's lanes an array (read
    /// and written lane by lane, loaded into [`F32x4`] for the arithmetic); zero on and above
    /// the diagonal.
    factor: Vec<[f32; LANES]>,
    /// `1 / L_ii`.
    inverse_diagonal: Vec<f32>,
    blocks: Vec<Block>,
    /// The block of each row.
    block_of_row: Vec<usize>,
    /// Scratch: right-hand side, then solution, then the rows' impulses.
    work: Vec<f32>,
    /// Scratch: each moving body side of each row, `(body, row, side)`, sorted, so the rows
    /// sharing a body are neighbours: `A` is assembled from them alone.
    sides: Vec<(usize, usize, usize)>,
    /// Scratch: each of `sides`' Jacobian and response (linear, angular) in SIMD vectors, in
    /// the same order, so a body's run is one contiguous block when `A` is assembled.
    side_terms: Vec<SideTerms>,
    /// Scratch: the first column of each row's profile.
    first: Vec<usize>,
    /// Whether `sides` and `blocks` describe `rows`: which rows there are and which bodies
    /// they join stays the same through a step, only their Jacobians change.
    structure_known: bool,
}

/// Relative size below which a pivot is taken for zero: the row depends on the ones before it,
/// and gets the joints' compliance as its pivot.
const DEPENDENT_PIVOT: f32 = 1.0e-5;

impl GroupSystem {
    /// Builds `A = J M⁻¹ Jᵀ` for `rows` and factors it. `A_ij` is non-zero only where rows `i`
    /// and `j` share a moving body, so it is assembled body by body from the rows on each, and
    /// only each row's profile (from its first non-zero column) is stored and factored. A pivot
    /// that is not there (below [`DEPENDENT_PIVOT`] of `A_ii`) becomes `regularisation · A_ii`:
    /// the joints' compliance relative to `A_ii`.
    pub fn factor(&mut self, regularisation: f32) {
        if !self.structure_known {
            self.find_structure();
        }
        self.factor.fill([0.0; LANES]);
        self.side_terms.clear();
        self.side_terms.extend(
            self.sides
                .iter()
                .map(|&(_, row, side)| SideTerms::of(&self.rows[row], side)),
        );
        // `sides` is sorted by body, then row: within a body's run a side's row is at least
        // that of every side before it, so each pair lands in the lower triangle as it comes.
        let mut run_start = 0;
        for run in self.sides.chunk_by(|a, b| a.0 == b.0) {
            let terms = &self.side_terms[run_start..run_start + run.len()];
            for (position, &(_, i, _)) in run.iter().enumerate() {
                let block = &self.blocks[self.block_of_row[i]];
                let lane = i - block.start;
                let term_i = &terms[position];
                for (&(_, j, _), term_j) in run[..=position].iter().zip(terms) {
                    self.factor[block.column(j)][lane] += term_i.coupling(term_j);
                }
            }
            run_start += run.len();
        }
        // Only soft rows (an armature's) have a compliance: rigid rows skip the block lookup.
        for (i, row) in self.rows.iter().enumerate() {
            if row.compliance == 0.0 {
                continue;
            }
            let block = &self.blocks[self.block_of_row[i]];
            self.factor[block.column(i)][i - block.start] += row.compliance;
        }
        self.inverse_diagonal.clear();
        for block in &self.blocks {
            let end = block.start + block.len;
            for j in block.first..end {
                // Row `j`'s `L_jk` for `k < j` lie in lane `j − start` of the columns of its
                // own block: this block, or an earlier one already factored.
                let (source, from) = if j >= block.start {
                    (block, block.first)
                } else {
                    let source = &self.blocks[self.block_of_row[j]];
                    (source, block.first.max(source.first))
                };
                let lane_j = j - source.start;
                let mut column = F32x4::from_array(self.factor[block.column(j)]);
                let assembled = column;
                for k in from..j {
                    let l_jk = self.factor[source.column(k)][lane_j];
                    column -= F32x4::from_array(self.factor[block.column(k)]) * F32x4::splat(l_jk);
                }
                self.factor[block.column(j)] = if j < block.start {
                    (column * F32x4::splat(self.inverse_diagonal[j])).to_array()
                } else {
                    let lane = j - block.start;
                    let diagonal = assembled.lane(lane);
                    let mut sum = column.lane(lane);
                    if sum <= DEPENDENT_PIVOT * diagonal {
                        sum = sum.max(0.0) + regularisation * diagonal;
                    }
                    // `L_jj = √sum`, kept as its inverse; a row with nothing to move gets no
                    // impulse. The column keeps the rows below `j` only, the others exactly
                    // zero: the back substitution multiplies whole columns, and what the sums
                    // left there can be large enough to make `0 · ∞`.
                    let pivot = if sum > 0.0 { sum.sqrt().recip() } else { 0.0 };
                    self.inverse_diagonal.push(pivot);
                    let mut below = (column * F32x4::splat(pivot)).to_array();
                    below[..=lane].fill(0.0);
                    below
                };
            }
        }
    }

    /// The group's rows changed (a new step): [`Self::factor`] finds again which rows share bodies.
    pub fn forget_structure(&mut self) {
        self.structure_known = false;
    }

    /// Lists each row's moving bodies, sorted by body, finds each row's first non-zero column
    /// and puts the rows into blocks.
    fn find_structure(&mut self) {
        self.sides.clear();
        for (index, row) in self.rows.iter().enumerate() {
            for side in 0..2 {
                if row.takes_impulses[side] {
                    self.sides.push((row.bodies[side], index, side));
                }
            }
        }
        self.sides.sort_unstable();
        self.first.clear();
        self.first.extend(0..self.rows.len());
        for run in self.sides.chunk_by(|a, b| a.0 == b.0) {
            let lowest = run[0].1;
            for &(_, row, _) in run {
                self.first[row] = self.first[row].min(lowest);
            }
        }
        self.blocks.clear();
        self.block_of_row.clear();
        let mut size = 0;
        for (row, &first) in self.first.iter().enumerate() {
            match self.blocks.last_mut() {
                Some(block) if block.first == first && block.len < LANES => block.len += 1,
                _ => {
                    if let Some(block) = self.blocks.last() {
                        size += block.start + block.len - block.first;
                    }
                    self.blocks.push(Block {
                        start: row,
                        len: 1,
                        first,
                        columns: size,
                    });
                }
            }
            self.block_of_row.push(self.blocks.len() - 1);
        }
        if let Some(block) = self.blocks.last() {
            size += block.start + block.len - block.first;
        }
        self.factor.resize(size, [0.0; LANES]);
        self.structure_known = true;
    }

    /// One solve of the group: `λ = −(A + Γ)⁻¹ (J v + b C + o)` per row (`softness` gives the
    /// bias `b C`; the soft rows' compliances `Γ` and offsets `o` are the rows' own), applied to `states`. [`Self::impulses`] then gives the impulse of
    /// each row, for the caller's accumulators. A solve that asks any row for more than
    /// [`MAX_SOLVER_IMPULSE`], or for an impulse that is not finite, applies nothing, gives
    /// every row zero and returns `false`.
    pub fn solve(&mut self, states: &mut [BodyState], softness: RowSoftness) -> bool {
        self.work.clear();
        self.work.extend(
            self.rows
                .iter()
                .map(|row| -(row.velocity(states) + softness.bias(row.error) + row.offset)),
        );
        // `L y = r`, a block at a time: the block's rows less what the earlier rows give them,
        // then its own rows in order.
        for block in &self.blocks {
            let mut rest = [0.0; LANES];
            rest[..block.len].copy_from_slice(&self.work[block.start..block.start + block.len]);
            let mut rest = F32x4::from_array(rest);
            for k in block.first..block.start {
                rest -=
                    F32x4::from_array(self.factor[block.column(k)]) * F32x4::splat(self.work[k]);
            }
            for lane in 0..block.len {
                let j = block.start + lane;
                let y = rest.lane(lane) * self.inverse_diagonal[j];
                self.work[j] = y;
                rest -= F32x4::from_array(self.factor[block.column(j)]) * F32x4::splat(y);
            }
        }
        // `Lᵀ x = y`, blocks in reverse: its own rows last to first, then what they take
        // from the earlier rows.
        for block in self.blocks.iter().rev() {
            let mut solved = [0.0; LANES];
            for lane in (0..block.len).rev() {
                let j = block.start + lane;
                let column = &self.factor[block.column(j)];
                let below: f32 = (lane + 1..block.len).map(|i| column[i] * solved[i]).sum();
                solved[lane] = (self.work[j] - below) * self.inverse_diagonal[j];
                self.work[j] = solved[lane];
            }
            let solved = F32x4::from_array(solved);
            for k in block.first..block.start {
                self.work[k] -= (F32x4::from_array(self.factor[block.column(k)]) * solved).sum();
            }
        }
        // `A` squares the rows' lever arms: a joint anchored kilometres from its bodies has
        // entries 1e8 times its neighbours', its rows nearly dependent on each other, and in `f32`
        // their rounding swamps the pivots of the rows factored after them. The factor is then
        // wrong and its answer unbounded: speeds of 1e3 m/s asked for impulses of 1e27, which
        // overflowed within the pass (a car's axle anchored 9 km away, `tests/validation.rs`).
        // An impulse past what bodies within the limits can exchange is no answer; the pass
        // leaves the group's velocities as they are, as the warm start drops such impulses.
        let answered = self
            .work
            .iter()
            .all(|impulse| impulse.abs() <= MAX_SOLVER_IMPULSE);
        if !answered {
            self.work.fill(0.0);
        }
        for (row, &impulse) in self.rows.iter().zip(&self.work) {
            row.apply(states, impulse);
        }
        answered
    }

    /// Each row with the impulse the last [`Self::solve`] gave it.
    pub fn impulses(&self) -> impl Iterator<Item = (&GroupRow, f32)> {
        self.rows.iter().zip(self.work.iter().copied())
    }
}

/// An order of the grouped joints that keeps each group's factor narrow: a depth-first walk of
/// the group's bodies from its most connected one, each joint after the joints of the bodies
/// below it (post-order). A row's profile reaches back only to the joints that share its
/// bodies, and these now lie just before it: in the order joints are usually made (a ragdoll's
/// hips after its arms) a hip's rows would reach back to the spine's, across every arm row.
#[derive(Debug, Clone, Default)]
pub(super) struct EliminationOrder {
    /// The joints, in the order their rows go into their groups.
    order: Vec<usize>,
    /// The joints on each body: `adjacent[start[b]..start[b + 1]]`.
    start: Vec<usize>,
    adjacent: Vec<usize>,
    /// The bodies with a joint, most joints first, then the later body first: a chain made
    /// from one end is walked from its other end, so its rows keep the order they were made in
    /// (which of a closed loop's rows depends on the others, and gets no impulse, stays the
    /// same).
    roots: Vec<usize>,
    /// Scratch: where the next joint of each body goes in `adjacent`.
    cursor: Vec<usize>,
    visited: Vec<bool>,
    emitted: Vec<bool>,
    /// The walk: a body, the joint it was reached by, the next of its joints to follow.
    stack: Vec<(usize, usize, usize)>,
}

impl EliminationOrder {
    /// Orders the joints whose `bodies` (solver indices, 0 for one that does not move) are given;
    /// `None` leaves a joint out (not in a group).
    pub fn find(&mut self, bodies: &[Option<[usize; 2]>], body_count: usize) {
        self.order.clear();
        if bodies.iter().all(Option::is_none) {
            return;
        }
        self.start.clear();
        self.start.resize(body_count + 1, 0);
        for pair in bodies.iter().flatten() {
            for &body in pair.iter().filter(|&&body| body != 0) {
                self.start[body + 1] += 1;
            }
        }
        for body in 0..body_count {
            self.start[body + 1] += self.start[body];
        }
        self.adjacent.clear();
        self.adjacent.resize(self.start[body_count], 0);
        self.roots.clear();
        self.roots
            .extend((1..body_count).filter(|&b| self.start[b + 1] > self.start[b]));
        self.cursor.clear();
        self.cursor.extend_from_slice(&self.start);
        for (joint, pair) in bodies.iter().enumerate() {
            for &body in pair.iter().flatten().filter(|&&body| body != 0) {
                self.adjacent[self.cursor[body]] = joint;
                self.cursor[body] += 1;
            }
        }
        let degree = |body: usize| self.start[body + 1] - self.start[body];
        let mut roots = std::mem::take(&mut self.roots);
        // Keys are distinct (the body is part of each), so the unstable sort is deterministic;
        // unlike the stable one it needs no buffer.
        roots.sort_unstable_by_key(|&body| std::cmp::Reverse((degree(body), body)));
        self.visited.clear();
        self.visited.resize(body_count, false);
        self.emitted.clear();
        self.emitted.resize(bodies.len(), false);
        for &root in &roots {
            if !self.visited[root] {
                self.walk(root, bodies);
            }
        }
        self.roots = roots;
    }

    /// The joints [`Self::find`] ordered.
    pub fn joints(&self) -> &[usize] {
        &self.order
    }

    /// Walks the bodies joined to `root`, emitting each body's joints once the bodies below it
    /// are done: first its joints to bodies already reached (to the world, or closing a loop),
    /// then the joint it was reached by.
    fn walk(&mut self, root: usize, bodies: &[Option<[usize; 2]>]) {
        self.visited[root] = true;
        self.stack.push((root, usize::MAX, self.start[root]));
        while let Some(&mut (body, via, ref mut next)) = self.stack.last_mut() {
            if *next < self.start[body + 1] {
                let joint = self.adjacent[*next];
                *next += 1;
                let [a, b] = bodies[joint].unwrap_or_default();
                let other = if a == body { b } else { a };
                if other != 0 && !self.visited[other] {
                    self.visited[other] = true;
                    self.stack.push((other, joint, self.start[other]));
                }
                continue;
            }
            self.stack.pop();
            for &joint in &self.adjacent[self.start[body]..self.start[body + 1]] {
                if joint != via && !self.emitted[joint] {
                    self.emitted[joint] = true;
                    self.order.push(joint);
                }
            }
            if via != usize::MAX {
                self.emitted[via] = true;
                self.order.push(via);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Accumulator, EliminationOrder, GroupRow, GroupSystem};
    use crate::math::{Mat3, Vec3, Vec3A};
    use crate::solver::joint_parts::{RowJacobian, RowSoftness};
    use crate::solver::BodyState;

    /// A group of one row that holds body 1 (1 kg, unit inertia) to the world along X at the
    /// point `arm` from its centre, factored, and the bodies' states with body 1 moving at
    /// `linear` and `angular`.
    fn held_along_x(arm: Vec3, linear: Vec3, angular: Vec3) -> (GroupSystem, [BodyState; 2]) {
        let mut system = GroupSystem::default();
        system.rows.push(GroupRow::new(
            (0, Accumulator::Linear(Vec3::X)),
            [0, 1],
            ([Vec3::ZERO, Vec3::ONE], [Mat3::ZERO, Mat3::IDENTITY]),
            RowJacobian {
                linear: [-Vec3::X, Vec3::X],
                angular: [Vec3::ZERO, arm.cross(Vec3::X)],
            },
            0.0,
        ));
        system.factor(0.25);
        let moving = BodyState {
            linear_velocity: Vec3A::from(linear),
            angular_velocity: Vec3A::from(angular),
            ..BodyState::default()
        };
        (system, [BodyState::default(), moving])
    }

    #[test]
    fn a_group_stops_its_rows_with_the_impulse_they_ask() {
        // At the centre `A = 1/m = 1`: the row moving at 2 m/s takes `λ = −2` N·s and stops.
        let (mut system, mut states) = held_along_x(Vec3::ZERO, Vec3::X * 2.0, Vec3::ZERO);
        assert!(system.solve(&mut states, RowSoftness::RIGID));
        assert_eq!(system.impulses().next().unwrap().1, -2.0);
        assert_eq!(states[1].linear_velocity, Vec3A::ZERO);
    }

    #[test]
    fn a_group_asked_past_the_impulse_limit_applies_nothing() {
        // Speeds no step leaves but a badly rounded factor can make within one (a joint
        // anchored 9 km away asked for 1e27 N·s): 1e30 m/s asks for 1e30 N·s, past the limit;
        // 1e38 rad/s at a 9 km arm overflows `J v` to infinity. Neither solve moves the body,
        // and neither impulse reaches the joint's accumulators.
        let far = Vec3::new(0.0, 9.0e3, 0.0);
        for (arm, linear, angular) in [
            (Vec3::ZERO, Vec3::X * 1.0e30, Vec3::ZERO),
            (far, Vec3::ZERO, Vec3::Z * -1.0e38),
        ] {
            let (mut system, mut states) = held_along_x(arm, linear, angular);
            let before = states[1];
            assert!(!system.solve(&mut states, RowSoftness::RIGID));
            let impulse = system.impulses().next().unwrap().1;
            assert_eq!(impulse, 0.0);
            assert_eq!(states[1].linear_velocity, before.linear_velocity);
            assert_eq!(states[1].angular_velocity, before.angular_velocity);
        }
    }

    #[test]
    fn joints_come_after_the_bodies_below_them_each_once() {
        // Bodies 1–4; body 4 has the most joints (ties go to the later body) and roots the walk.
        // Joint 3 ties body 4 to the world, joint 4 closes the loop 2–3–4, joint 5 is in no
        // group.
        let bodies = [
            Some([1, 2]),
            Some([2, 3]),
            Some([2, 4]),
            Some([0, 4]),
            Some([3, 4]),
            None,
        ];
        let mut order = EliminationOrder::default();
        order.find(&bodies, 5);
        assert_eq!(order.joints(), &[0, 4, 1, 2, 3]);
        // The scratch is reused: a second, smaller scene is ordered from scratch.
        order.find(&[Some([2, 1]), Some([0, 2])], 3);
        assert_eq!(order.joints(), &[0, 1]);
    }
}
