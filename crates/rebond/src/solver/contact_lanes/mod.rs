//! Four contact constraints of one colour solved at once, one per SIMD lane (Box2D v3's wide
//! solver idea; our own code).
//!
//! The four constraints share no moving body (`graph_colour.rs`), so solving them side by side
//! gives each the result solving it alone gives: lane `i` runs the sequential-impulse step of
//! constraint `i`, with each branch turned into a per-lane select. A lane set with fewer than four
//! constraints fills the rest with empty lanes on solver body 0 (no mass, zero Jacobians: their
//! impulses are zero); a manifold with fewer points than the widest one of the set gets empty
//! points of no mass the same way. The constraints are built straight into their lanes, from the
//! contacts, and their impulses go straight back to the contacts. Each point's normal and the two
//! friction directions are axis parts (`parts.rs`).

use super::contact_model::limit_surface_projection;
use super::normal_block::NormalBlock;
use super::parts::{inverse_or_zero, BodyFrame, BodyLanes, JacobianLanes, LinearMasses};
use super::softness::Softness;
use super::wide::{F32x4, Mask4, Vec3x4, LANES};
use super::{BodyMotion, BodyState};
use crate::collision::contact_cache::Contact;
use crate::collision::MAX_MANIFOLD_POINTS;
use crate::limits::MAX_SOLVER_IMPULSE;
use crate::material::Material;
use crate::math::{Vec3, Vec3A};

mod collisions;

pub(crate) use collisions::Collision;

/// What a solver pass reads of its bodies: both sides' spins and rotations, but of the linear
/// velocities and moves only B's minus A's, since the impulses act on both along one direction
/// and the bodies get the linear impulse of the pass at its end ([`Self::finish`]).
struct PassLanes {
    /// `v_B − v_A`, m/s, at the start of the pass.
    relative_velocity: Vec3x4,
    /// `Δc_B − Δc_A`, m.
    relative_motion: Vec3x4,
    angular_a: Vec3x4,
    angular_b: Vec3x4,
    rotation_a: Vec3x4,
    rotation_b: Vec3x4,
}

impl PassLanes {
    /// Inlined, as is [`Self::finish`]: as calls they would pass their lanes through memory.
    #[inline(always)]
    fn gather(states: &[BodyState], bodies_a: &[usize; LANES], bodies_b: &[usize; LANES]) -> Self {
        let a = bodies_a.map(|body| &states[body]);
        let b = bodies_b.map(|body| &states[body]);
        let field = |side: &[&BodyState; LANES], f: fn(&BodyState) -> Vec3A| {
            Vec3x4::from_lanes(side.map(f))
        };
        let difference = |f: fn(&BodyState) -> Vec3A| {
            Vec3x4::from_lanes(std::array::from_fn(|lane| f(b[lane]) - f(a[lane])))
        };
        Self {
            relative_velocity: difference(|s| s.linear_velocity),
            relative_motion: difference(|s| s.delta_position),
            angular_a: field(&a, |s| s.angular_velocity),
            angular_b: field(&b, |s| s.angular_velocity),
            rotation_a: field(&a, |s| s.delta_rotation),
            rotation_b: field(&b, |s| s.delta_rotation),
        }
    }

    /// Writes the spins back, and the linear velocity changes `Δv_A = −P / m_A`,
    /// `Δv_B = +P / m_B` for the linear impulse `P` of the pass; body 0 (fixed, and the empty
    /// lanes) never changes.
    #[inline(always)]
    fn finish<const LOCKED: bool>(
        &self,
        states: &mut [BodyState],
        lanes: &ContactLanes,
        linear_impulse: Vec3x4,
    ) {
        let (linear_a, linear_b) = lanes.masses.responses::<LOCKED>(linear_impulse);
        let (linear_a, linear_b) = (linear_a.lanes(), linear_b.lanes());
        let (angular_a, angular_b) = (self.angular_a.lanes(), self.angular_b.lanes());
        for lane in 0..LANES {
            let (body_a, body_b) = (lanes.body_a[lane], lanes.body_b[lane]);
            if body_a != 0 {
                let state = &mut states[body_a];
                state.linear_velocity -= linear_a[lane];
                state.angular_velocity = angular_a[lane];
            }
            if body_b != 0 {
                let state = &mut states[body_b];
                state.linear_velocity += linear_b[lane];
                state.angular_velocity = angular_b[lane];
            }
        }
    }
}

/// One contact to put into a lane: the contact, its index in the contact cache, its solver
/// bodies.
#[derive(Clone, Copy)]
pub(crate) struct LaneContact<'a> {
    pub contact: &'a Contact,
    pub index: usize,
    pub body_a: usize,
    pub body_b: usize,
}

/// How far below zero, N·s, a point's total impulse from the block solve may come before its
/// lane falls back to solving the points one after another: rounding, not a pull.
const BLOCK_PULL: f32 = 1.0e-6;

/// Normal speed above which a point's collision counts as an impact, m/s, for the block solve
/// ([`ContactLanes::prepare_biased_passes`]): resting contacts move at millimetres to a few
/// centimetres a second, gravity adds 0.16 m/s a step at 60 Hz, and a box dropped from 1 cm
/// lands at 0.44 m/s.
const IMPACT_SPEED: f32 = 0.25;

/// The separation of a point a manifold does not have, m: far apart at every substep's poses,
/// so a lane's points are all apart when its nearest real point is
/// ([`ContactLanes::prepare_biased_passes`]). Its mass is zero, so it gets no impulse.
const ABSENT_SEPARATION: f32 = 1.0e9;

/// Pairs of distinct points in a manifold.
const COUPLINGS: usize = MAX_MANIFOLD_POINTS * (MAX_MANIFOLD_POINTS - 1) / 2;

/// Where the coupling of points `i < j` is kept: the pairs ordered by `j`, then `i`, so the
/// couplings of point `j` with the points before it start at `j (j − 1) / 2`.
const fn coupling_index(i: usize, j: usize) -> usize {
    j * (j - 1) / 2 + i
}

/// What one point of four constraints asks of its normal impulse in the biased passes of a
/// substep, from its separation at the substep's poses: `Δλ = mass (v_n + bias) − impulse_scale λ`
/// solved point by point, `K Δλ = −(v_n + bias)` in a block (`normal_block.rs`).
#[derive(Debug, Clone, Copy)]
struct PointTarget {
    /// m/s.
    bias: F32x4,
    /// The effective mass, scaled by the softness where the point penetrates, and negated, kg.
    mass: F32x4,
    impulse_scale: F32x4,
}

/// The normal part of one point of four constraints.
#[derive(Debug, Clone, Copy)]
struct PointLanes {
    normal: JacobianLanes,
    base_separation: F32x4,
    normal_impulse: F32x4,
    max_normal_impulse: F32x4,
    /// 1 where the point took part in the step's impacts (it approached at the start of the
    /// step, or once an impact reached it), else 0: set by [`ContactLanes::collide`].
    impact: F32x4,
    /// Set before the biased passes of each substep ([`ContactLanes::prepare_biased_passes`]).
    target: PointTarget,
}

impl PointLanes {
    /// Adds `impulse` to the accumulated normal impulse, kept `≥ 0`, and returns what was
    /// applied: the change of the accumulated impulse.
    #[inline(always)]
    fn accumulate(&mut self, impulse: F32x4) -> F32x4 {
        let total = (self.normal_impulse + impulse).max(F32x4::ZERO);
        let applied = total - self.normal_impulse;
        self.normal_impulse = total;
        self.max_normal_impulse = self.max_normal_impulse.max(applied);
        applied
    }

    /// The separation at the pass's poses, `s = s₀ + n·(Δc_B − Δc_A) + Δθ_B·(r_B × n) −
    /// Δθ_A·(r_A × n)`, m, given `n·(Δc_B − Δc_A)`.
    fn separation(&self, bodies: &PassLanes, normal_motion: F32x4) -> F32x4 {
        self.base_separation + normal_motion + bodies.rotation_b.dot(self.normal.arm_b)
            - bodies.rotation_a.dot(self.normal.arm_a)
    }

    /// What the pass asks of the point's normal impulse, solved alone, given its normal velocity
    /// `v_n`: with `USE_BIAS`, `Δλ = mass (v_n + bias) − impulse_scale λ` for its target; without
    /// (the relax pass), `Δλ = −m_eff (v_n + closing)` ([`Self::closing`]).
    #[inline(always)]
    fn impulse<const USE_BIAS: bool>(
        &self,
        normal_velocity: F32x4,
        bodies: &PassLanes,
        normal_motion: F32x4,
        inverse_h: F32x4,
    ) -> F32x4 {
        if USE_BIAS {
            let target = &self.target;
            target.mass * (normal_velocity + target.bias)
                - target.impulse_scale * self.normal_impulse
        } else {
            let closing = self.closing(bodies, normal_motion, inverse_h);
            -self.normal.mass * (normal_velocity + closing)
        }
    }

    /// The normal speed, m/s, at which a point still apart by `s > 0` at the pass's poses
    /// closes its gap this substep, `s / h`; 0 where it touches.
    #[inline(always)]
    fn closing(&self, bodies: &PassLanes, normal_motion: F32x4, inverse_h: F32x4) -> F32x4 {
        let separation = self.separation(bodies, normal_motion);
        separation
            .greater_than(F32x4::ZERO)
            .select(separation * inverse_h, F32x4::ZERO)
    }

    const ZERO: Self = Self {
        normal: JacobianLanes::ZERO,
        base_separation: F32x4::splat(ABSENT_SEPARATION),
        normal_impulse: F32x4::ZERO,
        max_normal_impulse: F32x4::ZERO,
        impact: F32x4::ZERO,
        target: PointTarget {
            bias: F32x4::ZERO,
            mass: F32x4::ZERO,
            impulse_scale: F32x4::ZERO,
        },
    };
}

/// Four constraints of one colour, structure of arrays: built from the contacts, solved, and
/// their impulses stored back into the contact cache, with no scalar constraint kept between.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactLanes {
    /// The contact of each lane, as an index into the contact cache; `usize::MAX` in empty lanes.
    contacts: [usize; LANES],
    body_a: [usize; LANES],
    body_b: [usize; LANES],
    masses: LinearMasses,
    normal: Vec3x4,
    tangents: [Vec3x4; 2],
    friction: F32x4,
    restitution: F32x4,
    /// Whether any lane bounces (restitution above zero).
    bounces: bool,
    /// The manifold's points in each lane, and the most of any lane.
    point_counts: [usize; LANES],
    point_count: usize,
    points: [PointLanes; MAX_MANIFOLD_POINTS],
    /// How a unit impulse at point `i` changes the normal velocity at point `j > i`, per lane:
    /// `K_ij = (m_A⁻¹ + m_B⁻¹)(n·n) + (r_Aj × n)·I_A⁻¹(r_Ai × n) + (r_Bj × n)·I_B⁻¹(r_Bi × n)`,
    /// the off-diagonal part of the points' effective-mass matrix, at [`coupling_index`]`(i, j)`.
    coupling: [F32x4; COUPLINGS],
    /// The points' effective-mass matrix, factored for the block solve in the substeps where a
    /// lane is [`Self::apart`].
    block: NormalBlock,
    /// 1 in the lanes whose points were all apart at the substep's poses, one of them meeting an
    /// impact (a speculative contact, where a fast body meets another), else 0: the lanes
    /// solved as a block in the substep's passes ([`Self::prepare_block`]).
    apart: F32x4,
    /// Whether any lane is [`Self::apart`] this substep: the passes take the block solve's path
    /// only then, so the lane sets of resting contacts pay nothing for it.
    any_apart: bool,
    /// Whether a lane of two points or more had them all apart at the start of the step, one of
    /// them about to meet an impact ([`Self::acts_within_step`]): only such lane sets look for
    /// lanes to solve as a block in each substep ([`Self::prepare_block`]). Resting contacts
    /// and the sideways gaps between the boxes of a pyramid (apart but not closing: half of its
    /// lane sets) skip the look.
    may_block: bool,
    tangent: [JacobianLanes; 2],
    /// `t·(M_A⁻¹ + M_B⁻¹) n` per tangent: how the normal impulse moves the contact along the
    /// tangent, zero but where a body's translation is locked ([`LinearMasses`]).
    tangent_coupling: [F32x4; 2],
    tangent_impulse: [F32x4; 2],
    /// `t·u` per tangent, m/s: the velocity of B's contact point relative to A's that friction
    /// drives toward, from the surface velocity `u` (zero but on a conveyor, `hooks.rs`).
    tangent_target: [F32x4; 2],
    /// `n·(I_A⁻¹(r_A × t) + I_B⁻¹(r_B × t))` per tangent: how a tangent impulse at the points'
    /// centre turns the bodies about the normal, which the twist's trial impulse takes in.
    tangent_twist: [F32x4; 2],
    twist_spin_a: Vec3x4,
    twist_spin_b: Vec3x4,
    twist_mass: F32x4,
    twist_radius: F32x4,
    twist_impulse: F32x4,
}

impl ContactLanes {
    /// A lane set whose lanes are all empty: on solver body 0, with no contact, no points and no
    /// mass in any direction, so solving them changes nothing. [`Self::fill`] fills lanes.
    pub const EMPTY: Self = Self {
        contacts: [usize::MAX; LANES],
        body_a: [0; LANES],
        body_b: [0; LANES],
        masses: LinearMasses::ZERO,
        normal: Vec3x4::ZERO,
        tangents: [Vec3x4::ZERO; 2],
        friction: F32x4::ZERO,
        restitution: F32x4::ZERO,
        bounces: false,
        point_counts: [0; LANES],
        point_count: 0,
        points: [PointLanes::ZERO; MAX_MANIFOLD_POINTS],
        coupling: [F32x4::ZERO; COUPLINGS],
        block: NormalBlock::ZERO,
        apart: F32x4::ZERO,
        any_apart: false,
        may_block: false,
        tangent: [JacobianLanes::ZERO; 2],
        tangent_coupling: [F32x4::ZERO; 2],
        tangent_impulse: [F32x4::ZERO; 2],
        tangent_target: [F32x4::ZERO; 2],
        tangent_twist: [F32x4::ZERO; 2],
        twist_spin_a: Vec3x4::ZERO,
        twist_spin_b: Vec3x4::ZERO,
        twist_mass: F32x4::ZERO,
        twist_radius: F32x4::ZERO,
        twist_impulse: F32x4::ZERO,
    };

    /// Fills this lane set, empty before ([`Self::EMPTY`]), in place with up to four contacts,
    /// which must share no moving body, warm-started from their cached impulses. What differs
    /// from contact to contact (normal, tangents, materials) is set lane by lane; the Jacobians
    /// of every point and of the friction and twist are then computed for the four lanes at once.
    /// Returns whether one of the contacts has rolling resistance, so the caller walks them
    /// again for it only then.
    pub fn fill<'a>(
        &mut self,
        lane_contacts: impl IntoIterator<Item = LaneContact<'a>>,
        states: &[BodyState],
        motions: &[BodyMotion],
        inverse_reach: f32,
    ) -> bool {
        let lanes = self;
        // Each point's lever arm from A's centre of mass and the offset from B's to A's, as the
        // contact's frame keeps them (`contact_frame.rs`).
        let mut arms = [[Vec3A::ZERO; LANES]; MAX_MANIFOLD_POINTS];
        let mut centers = [Vec3A::ZERO; LANES];
        let mut point_counts = F32x4::ZERO;
        let mut radius_ratios = F32x4::ZERO;
        let mut rolls = false;
        for (lane, lane_contact) in lane_contacts.into_iter().enumerate() {
            lanes.set_contact(lane, &lane_contact, motions);
            let contact = lane_contact.contact;
            rolls |= contact.material.rolling_lever() > 0.0;
            let frame = &contact.frame.solver;
            let count = contact.manifold.len();
            for (slot, &arm) in arms.iter_mut().zip(&frame.arms[..count]) {
                slot[lane] = arm.into();
            }
            centers[lane] = frame.centers.into();
            point_counts.set_lane(lane, count as f32);
            radius_ratios.set_lane(lane, contact.patch_radius_ratio);
        }
        let centers = Vec3x4::from_lanes(centers);
        let a = BodyFrame::gather(motions, &lanes.body_a);
        let b = BodyFrame::gather(motions, &lanes.body_b);
        let masses = lanes.masses;
        let normal = lanes.normal;
        let mut center_a = Vec3x4::ZERO;
        for (index, point) in lanes.points[..lanes.point_count].iter_mut().enumerate() {
            let anchor_a = Vec3x4::from_lanes(arms[index]);
            let anchor_b = anchor_a + centers;
            let in_manifold = point_counts.greater_than(F32x4::splat(index as f32));
            let jacobian = JacobianLanes::new((&a, &b), &masses, (anchor_a, anchor_b), normal);
            point.normal = JacobianLanes {
                mass: in_manifold.select(jacobian.mass, F32x4::ZERO),
                ..jacobian
            };
            center_a += anchor_a;
        }
        let counts = point_counts.max(F32x4::ONE);
        // The points' centre, as arms from A's and B's centres of mass.
        let center_a = Vec3x4 {
            x: center_a.x / counts,
            y: center_a.y / counts,
            z: center_a.z / counts,
        };
        let center_b = center_a + centers;
        let mut square_distances = F32x4::ZERO;
        for (index, point_arms) in arms[..lanes.point_count].iter().enumerate() {
            let offset = Vec3x4::from_lanes(*point_arms) - center_a;
            let in_manifold = point_counts.greater_than(F32x4::splat(index as f32));
            square_distances += in_manifold.select(offset.dot(offset), F32x4::ZERO);
        }
        // `⟨r⟩`, the patch's mean distance from its centre: a multiple of the points' root mean
        // square distance `ρ` from their centre (`contact_model::patch_radius_ratio`).
        lanes.twist_radius = radius_ratios * (square_distances / counts).sqrt();
        for axis in 0..2 {
            let direction = lanes.tangents[axis];
            let jacobian = JacobianLanes::new((&a, &b), &masses, (center_a, center_b), direction);
            lanes.tangent_twist[axis] = normal.dot(jacobian.spin_a + jacobian.spin_b);
            lanes.tangent[axis] = jacobian;
            if masses.locked {
                lanes.tangent_coupling[axis] = masses.coupling(direction, normal);
            }
        }
        let linear_coupling = masses.coupling(normal, normal);
        for j in 1..lanes.point_count {
            for i in 0..j {
                let (earlier, later) = (&lanes.points[i].normal, &lanes.points[j].normal);
                lanes.coupling[coupling_index(i, j)] = linear_coupling
                    + later.arm_a.dot(earlier.spin_a)
                    + later.arm_b.dot(earlier.spin_b);
            }
        }
        lanes.twist_spin_a = a.inverse_inertia.mul_vec3(normal);
        lanes.twist_spin_b = b.inverse_inertia.mul_vec3(normal);
        lanes.twist_mass =
            inverse_or_zero(normal.dot(lanes.twist_spin_a) + normal.dot(lanes.twist_spin_b));
        let mut nearest = F32x4::splat(ABSENT_SEPARATION);
        for point in &lanes.points[..lanes.point_count] {
            nearest = nearest.min(point.base_separation);
        }
        // A manifold of one point is solved the same alone or as a block.
        let speculative = nearest
            .greater_than(F32x4::ZERO)
            .and(point_counts.greater_than(F32x4::ONE));
        if speculative.any() {
            lanes.may_block = lanes.acts_within_step(speculative, states, inverse_reach);
        }
        rolls
    }

    /// Whether, in some lane of `speculative` (its points all apart), a point may meet an impact
    /// in the step ([`Self::prepare_block`]): it approaches faster than [`IMPACT_SPEED`] and
    /// closes its gap `s` within the step and one substep at the velocities at its start,
    /// `v_n + s / reach < 0` with `inverse_reach = 1 / (dt + h)` (the relax pass of the step's
    /// last substep closes what is left after its positions moved), or it holds an impulse from
    /// the last step that alone would move it faster than [`IMPACT_SPEED`], `λ K_jj`, which the
    /// warm start applies. A point a lane does not have is far apart and holds none.
    #[inline(never)]
    fn acts_within_step(
        &self,
        speculative: Mask4,
        states: &[BodyState],
        inverse_reach: f32,
    ) -> bool {
        let a = BodyLanes::gather(states, &self.body_a);
        let b = BodyLanes::gather(states, &self.body_b);
        let inverse_reach = F32x4::splat(inverse_reach);
        let mut acts = Mask4::NONE;
        for point in &self.points[..self.point_count] {
            let velocity = point.normal.velocity(&a, &b, self.normal);
            let gap_speed = point.base_separation * inverse_reach;
            let closes = F32x4::ZERO
                .greater_than(velocity + gap_speed)
                .and(F32x4::splat(-IMPACT_SPEED).greater_than(velocity));
            let held = point
                .normal_impulse
                .greater_than(F32x4::splat(IMPACT_SPEED) * point.normal.mass);
            acts = acts.or(closes.or(held));
        }
        speculative.and(acts).any()
    }

    /// Sets what lane `lane` takes straight from its contact: the bodies, the normal its frame
    /// keeps (`contact_frame.rs`) and its tangents, the materials, the points' separations and
    /// the cached impulses.
    fn set_contact(&mut self, lane: usize, lane_contact: &LaneContact, motions: &[BodyMotion]) {
        let LaneContact {
            contact,
            index,
            body_a,
            body_b,
        } = *lane_contact;
        self.contacts[lane] = index;
        self.body_a[lane] = body_a;
        self.body_b[lane] = body_b;
        self.masses
            .set_lane(lane, &motions[body_a], &motions[body_b]);
        let normal = Vec3A::from(contact.frame.solver.normal);
        let (tangent_1, tangent_2) = normal.any_orthonormal_pair();
        self.normal.set_lane(lane, normal);
        self.tangents[0].set_lane(lane, tangent_1);
        self.tangents[1].set_lane(lane, tangent_2);
        let Material {
            friction,
            restitution,
            ..
        } = contact.material;
        self.friction.set_lane(lane, friction);
        self.restitution.set_lane(lane, restitution);
        self.bounces |= restitution > 0.0;
        let points = contact.manifold.points();
        self.point_counts[lane] = points.len();
        self.point_count = self.point_count.max(points.len());
        let cached = points.iter().zip(&contact.normal_impulses);
        for (point, (source, &impulse)) in self.points.iter_mut().zip(cached) {
            point.base_separation.set_lane(lane, source.separation);
            point.normal_impulse.set_lane(lane, impulse);
        }
        let friction_impulse = Vec3A::from(contact.friction_impulse);
        self.tangent_impulse[0].set_lane(lane, friction_impulse.dot(tangent_1));
        self.tangent_impulse[1].set_lane(lane, friction_impulse.dot(tangent_2));
        self.twist_impulse.set_lane(lane, contact.twist_impulse);
    }

    /// Gives each lane the target of its friction from its contact's surface velocity
    /// (`surface_velocity(index)`, m/s, A's surface relative to B's: `hooks.rs`), `t·u` along
    /// each tangent; after [`Self::fill`], in the steps where some contact has one.
    pub fn set_surface_velocities(&mut self, surface_velocity: impl Fn(usize) -> Vec3) {
        for (lane, &index) in self.contacts.iter().enumerate() {
            if index == usize::MAX {
                continue;
            }
            let velocity = Vec3A::from(surface_velocity(index));
            for (target, tangent) in self.tangent_target.iter_mut().zip(&self.tangents) {
                target.set_lane(lane, velocity.dot(tangent.lanes()[lane]));
            }
        }
    }

    /// Whether any lane bounces (has a restitution above zero).
    pub fn bounces(&self) -> bool {
        self.bounces
    }

    /// The accumulated normal impulse of lane `lane`'s points, N·s (`rolling.rs` bounds its
    /// impulse by it).
    pub fn normal_impulse_sum(&self, lane: usize) -> f32 {
        let points = &self.points[..self.point_counts[lane]];
        points
            .iter()
            .map(|point| point.normal_impulse.lane(lane))
            .sum()
    }

    /// Writes the accumulated impulses back to the lanes' contacts for the next step's warm
    /// start.
    pub fn store_impulses(&self, contacts: &mut [Contact]) {
        let tangents = self.tangents.map(|tangent| tangent.lanes());
        for (lane, &index) in self.contacts.iter().enumerate() {
            let Some(contact) = contacts.get_mut(index) else {
                continue;
            };
            let points = self.points[..self.point_counts[lane]].iter();
            for (point, impulse) in points.zip(&mut contact.normal_impulses) {
                *impulse = point.normal_impulse.lane(lane);
            }
            let [tangent_1, tangent_2] = self.tangent_impulse.map(|impulse| impulse.lane(lane));
            contact.friction_impulse =
                (tangent_1 * tangents[0][lane] + tangent_2 * tangents[1][lane]).into();
            contact.twist_impulse = self.twist_impulse.lane(lane);
            // As for joints (`joints/`): impulses past what bodies within the limits exchange
            // are not kept to warm-start from.
            let impulses = [tangent_1, tangent_2, contact.twist_impulse].into_iter();
            if !impulses
                .chain(contact.normal_impulses)
                .all(|impulse| impulse.abs() <= MAX_SOLVER_IMPULSE)
            {
                contact.normal_impulses = [0.0; MAX_MANIFOLD_POINTS];
                contact.friction_impulse = Vec3::ZERO;
                contact.twist_impulse = 0.0;
            }
        }
    }

    fn masses(&self) -> &LinearMasses {
        &self.masses
    }

    /// Twist impulse about the normal: `Δω_A = −λ I_A⁻¹ n`, `Δω_B = +λ I_B⁻¹ n` per lane.
    fn apply_twist(&self, bodies: &mut PassLanes, impulse: F32x4) {
        bodies.angular_a -= self.twist_spin_a.scale(impulse);
        bodies.angular_b += self.twist_spin_b.scale(impulse);
    }

    /// Applies last step's accumulated impulses again (warm starting). The impulses only add up,
    /// so they are summed first, `P = Σλ_i n + Σλ_t t + …` and `L_A = Σλ I_A⁻¹(r_A × d)`, and each body
    /// gets `Δv = ±P / m`, `Δω = ∓L_A` or `±L_B` once.
    pub fn warm_start(&self, states: &mut [BodyState]) {
        let mut linear = Vec3x4::default();
        let mut spin_a = self.twist_spin_a.scale(self.twist_impulse);
        let mut spin_b = self.twist_spin_b.scale(self.twist_impulse);
        for point in &self.points[..self.point_count] {
            let impulse = point.normal_impulse;
            linear += self.normal.scale(impulse);
            spin_a += point.normal.spin_a.scale(impulse);
            spin_b += point.normal.spin_b.scale(impulse);
        }
        for axis in 0..2 {
            let (jacobian, impulse) = (&self.tangent[axis], self.tangent_impulse[axis]);
            linear += self.tangents[axis].scale(impulse);
            spin_a += jacobian.spin_a.scale(impulse);
            spin_b += jacobian.spin_b.scale(impulse);
        }
        let (linear_a, linear_b) = if self.masses.locked {
            self.masses.responses::<true>(linear)
        } else {
            self.masses.responses::<false>(linear)
        };
        let (linear_a, linear_b) = (linear_a.lanes(), linear_b.lanes());
        let (spin_a, spin_b) = (spin_a.lanes(), spin_b.lanes());
        for lane in 0..LANES {
            let (body_a, body_b) = (self.body_a[lane], self.body_b[lane]);
            if body_a != 0 {
                let state = &mut states[body_a];
                state.linear_velocity -= linear_a[lane];
                state.angular_velocity -= spin_a[lane];
            }
            if body_b != 0 {
                let state = &mut states[body_b];
                state.linear_velocity += linear_b[lane];
                state.angular_velocity += spin_b[lane];
            }
        }
    }

    /// Before the biased passes of a substep, whose poses they share: what each point's
    /// separation at those poses, `s = s₀ + n·(Δc_B − Δc_A) + Δθ_B·(r_B × n) − Δθ_A·(r_A × n)`,
    /// asks of its normal impulse. Apart (`s > 0`), the point is rigid and may close by `s` this
    /// substep (speculative contact), so a touchdown is perfectly inelastic. Penetrating, it is
    /// a soft constraint pushing out at `bias_rate · s`, at most `push_speed`, at every
    /// depth: no dead zone, in which a resting contact would hold no position and stacks would
    /// wander (docs/physics.md, "Position correction"). It reads the poses alone, so it runs
    /// with the warm start, which changes only velocities, in one sweep over the lane sets
    /// (`contacts.rs`); which lanes the substep solves as a block is found after the warm start
    /// ([`Self::prepare_block`]).
    pub fn set_targets(
        &mut self,
        states: &[BodyState],
        softness: &Softness,
        push_speed: f32,
        inverse_h: f32,
    ) {
        let bodies = PassLanes::gather(states, &self.body_a, &self.body_b);
        let normal_motion = self.normal.dot(bodies.relative_motion);
        let inverse_h = F32x4::splat(inverse_h);
        for point in &mut self.points[..self.point_count] {
            let separation = point.separation(&bodies, normal_motion);
            let apart = separation.greater_than(F32x4::ZERO);
            let push =
                (F32x4::splat(softness.bias_rate) * separation).max(F32x4::splat(-push_speed));
            let mass_scale = apart.select(F32x4::ONE, F32x4::splat(softness.mass_scale));
            point.target = PointTarget {
                bias: apart.select(separation * inverse_h, push),
                mass: -point.normal.mass * mass_scale,
                impulse_scale: apart.select(F32x4::ZERO, F32x4::splat(softness.impulse_scale)),
            };
        }
    }

    /// Whether the lane set may solve lanes as a block this step ([`Self::prepare_block`]).
    pub fn may_block(&self) -> bool {
        self.may_block
    }

    /// In a lane set that [`Self::may_block`]: marks as [`Self::apart`] the lanes whose points
    /// are all apart at the substep's poses and one of them meets an impact in the substep's
    /// passes, and factors their block. A point meets one where it approaches faster than
    /// [`IMPACT_SPEED`] and closes its gap `s` within two substeps, `2 h v_n + s < 0` at the
    /// substep's start (the biased passes close what closes in one, `v_n + s / h < 0`, and the
    /// relax pass what the move of the positions leaves, `v_n + (s + h v_n) / h < 0`), or where
    /// it holds an impulse and recedes faster than [`IMPACT_SPEED`] (the warm start's push after
    /// an impact, which the passes take back). Elsewhere the points are solved one after
    /// another: resting contacts that flicker apart keep their springs (without the speed, 6 %
    /// of the 100-row pyramid's passes took the block).
    #[inline(never)]
    pub fn prepare_block(&mut self, states: &[BodyState]) {
        let a = BodyLanes::gather(states, &self.body_a);
        let b = BodyLanes::gather(states, &self.body_b);
        // A point is apart where its bias is above zero (a push's never is), and a lane is all
        // apart where its nearest point is. A point a lane does not have is far apart, closes
        // no gap and holds no impulse.
        let mut nearest = F32x4::splat(ABSENT_SEPARATION);
        let mut acts = Mask4::NONE;
        for point in &self.points[..self.point_count] {
            let bias = point.target.bias;
            nearest = nearest.min(bias);
            let velocity = point.normal.velocity(&a, &b, self.normal);
            let closes = F32x4::ZERO
                .greater_than(velocity + velocity + bias)
                .and(F32x4::splat(-IMPACT_SPEED).greater_than(velocity));
            let pushed_back = velocity
                .greater_than(F32x4::splat(IMPACT_SPEED))
                .and(point.normal_impulse.greater_than(F32x4::ZERO));
            acts = acts.or(closes.or(pushed_back));
        }
        // A lane set that may block has a lane of two points or more; a lane of one point is
        // solved the same alone or as a block.
        let several = self.points[1].normal.mass.greater_than(F32x4::ZERO);
        let apart = nearest.greater_than(F32x4::ZERO).and(acts).and(several);
        self.apart = apart.select(F32x4::ONE, F32x4::ZERO);
        self.any_apart = apart.any();
        if self.any_apart {
            self.factor_block();
        }
    }

    /// Factors the points' effective-mass matrix for the block solve: the diagonal `1 / m_eff`
    /// (1 for a point a lane does not have) and the couplings between the lane's points.
    fn factor_block(&mut self) {
        let mut diagonal = [F32x4::ONE; MAX_MANIFOLD_POINTS];
        for (entry, point) in diagonal.iter_mut().zip(&self.points[..self.point_count]) {
            let mass = point.normal.mass;
            *entry = mass
                .greater_than(F32x4::ZERO)
                .select(F32x4::ONE / mass, F32x4::ONE);
        }
        let points = &self.points;
        let coupling = |i: usize, j: usize| {
            let both = points[i].normal.mass.greater_than(F32x4::ZERO);
            let both = both.and(points[j].normal.mass.greater_than(F32x4::ZERO));
            both.select(self.coupling[coupling_index(j, i)], F32x4::ZERO)
        };
        self.block = NormalBlock::factor(&diagonal, coupling, self.point_count);
    }

    /// One sequential-impulse pass of the four lanes: the normal impulse of each point with
    /// accumulated clamping (the total never pulls). With `USE_BIAS`, each point's impulse aims
    /// at its target from [`Self::prepare_biased_passes`], and friction is left alone. Without
    /// `USE_BIAS` (the relax pass, after the poses moved) only velocities are solved, which
    /// removes the energy the push added (a point still apart by `s > 0` may close by `s` this
    /// substep), and then friction ([`Self::solve_friction`]). Friction that reacts to the
    /// push's velocities feeds the lean of tall stacks until they topple (rapier's "no friction
    /// when applying bias" rule; BENCHMARKS.md measures both).
    #[inline(always)]
    pub fn solve<const USE_BIAS: bool>(&mut self, states: &mut [BodyState], inverse_h: f32) {
        match (self.any_apart, self.masses.locked) {
            (false, false) => self.solve_pass::<USE_BIAS, false, false>(states, inverse_h),
            (true, false) => self.solve_pass::<USE_BIAS, true, false>(states, inverse_h),
            (false, true) => self.solve_pass::<USE_BIAS, false, true>(states, inverse_h),
            (true, true) => self.solve_pass::<USE_BIAS, true, true>(states, inverse_h),
        }
    }

    /// [`Self::solve`], with `BLOCK` where some lane is [`Self::apart`]: two functions, so
    /// that the lane sets of resting contacts run without the block solve's code, which as a
    /// branch inside would slow them all.
    fn solve_pass<const USE_BIAS: bool, const BLOCK: bool, const LOCKED: bool>(
        &mut self,
        states: &mut [BodyState],
        inverse_h: f32,
    ) {
        let mut bodies = PassLanes::gather(states, &self.body_a, &self.body_b);
        let normal = self.normal;
        let inverse_h = F32x4::splat(inverse_h);
        let normal_motion = normal.dot(bodies.relative_motion);
        let linear_speed = normal.dot(bodies.relative_velocity);
        let (applied, total_normal_impulse) = if BLOCK {
            self.solve_normal_block::<USE_BIAS>(&bodies, linear_speed, normal_motion, inverse_h)
        } else {
            // Each point's normal velocity is its velocity at the start of the pass plus what
            // the points before it applied, through the couplings; the impulses reach the
            // bodies after.
            let mut applied = [F32x4::ZERO; MAX_MANIFOLD_POINTS];
            let mut total_normal_impulse = F32x4::ZERO;
            for (j, point) in self.points[..self.point_count].iter_mut().enumerate() {
                let mut normal_velocity = linear_speed
                    + point
                        .normal
                        .spin_velocity(bodies.angular_a, bodies.angular_b);
                let couplings = &self.coupling[coupling_index(0, j.max(1))..];
                for (&coupling, &earlier) in couplings.iter().zip(&applied[..j]) {
                    normal_velocity += coupling * earlier;
                }
                let impulse =
                    point.impulse::<USE_BIAS>(normal_velocity, &bodies, normal_motion, inverse_h);
                applied[j] = point.accumulate(impulse);
                total_normal_impulse += point.normal_impulse;
            }
            (applied, total_normal_impulse)
        };
        let mut normal_impulse = F32x4::ZERO;
        for (point, &impulse) in self.points[..self.point_count].iter().zip(&applied) {
            normal_impulse += impulse;
            point
                .normal
                .apply_spin(&mut bodies.angular_a, &mut bodies.angular_b, impulse);
        }
        // The normal impulses change the velocities along the tangents through the spins only
        // (n·t = 0), so the bodies get the linear impulse of the whole pass at its end.
        let mut linear_impulse = normal.scale(normal_impulse);
        if !USE_BIAS {
            linear_impulse +=
                self.solve_friction::<LOCKED>(&mut bodies, total_normal_impulse, normal_impulse);
        }
        bodies.finish::<LOCKED>(states, self, linear_impulse);
    }

    /// The normal impulses of a pass ([`Self::solve`]) where some lane is [`Self::apart`]: the
    /// manifold's points solved as one block in those lanes (rigid, in the biased and the relax
    /// passes), `K Δλ = −(v_n + bias)`, `bias` the target's or the closing of a gap. A face
    /// meeting a face at speed then stops flat instead of starting to turn, as one point solved
    /// before the others would make it. Resting points keep a spring each, `k = m_eff ω²` (a
    /// soft block would be 2/3 as stiff against a tilt), and where a lane's block solution
    /// would pull at a point, that lane's points are solved one after another as in the other
    /// lanes. Returns each point's applied impulse and the lanes' total normal impulse.
    #[inline(always)]
    fn solve_normal_block<const USE_BIAS: bool>(
        &mut self,
        bodies: &PassLanes,
        linear_speed: F32x4,
        normal_motion: F32x4,
        inverse_h: F32x4,
    ) -> ([F32x4; MAX_MANIFOLD_POINTS], F32x4) {
        let count = self.point_count;
        let mut velocities = [F32x4::ZERO; MAX_MANIFOLD_POINTS];
        let mut rhs = [F32x4::ZERO; MAX_MANIFOLD_POINTS];
        for ((point, velocity), rhs) in self.points[..count]
            .iter()
            .zip(&mut velocities)
            .zip(&mut rhs)
        {
            *velocity = linear_speed
                + point
                    .normal
                    .spin_velocity(bodies.angular_a, bodies.angular_b);
            let bias = if USE_BIAS {
                point.target.bias
            } else {
                point.closing(bodies, normal_motion, inverse_h)
            };
            let in_manifold = point.normal.mass.greater_than(F32x4::ZERO);
            *rhs = in_manifold.select(-(*velocity + bias), F32x4::ZERO);
        }
        let block = self.block.solve(rhs, count);
        let mut pushes = self.apart.greater_than(F32x4::ZERO);
        for (point, &impulse) in self.points[..count].iter().zip(&block) {
            let total = point.normal_impulse + impulse;
            pushes = pushes.and(total.greater_than(F32x4::splat(-BLOCK_PULL)));
        }
        let mut applied = [F32x4::ZERO; MAX_MANIFOLD_POINTS];
        let mut total_normal_impulse = F32x4::ZERO;
        for (j, point) in self.points[..count].iter_mut().enumerate() {
            let mut normal_velocity = velocities[j];
            let couplings = &self.coupling[coupling_index(0, j.max(1))..];
            for (&coupling, &earlier) in couplings.iter().zip(&applied[..j]) {
                normal_velocity += coupling * earlier;
            }
            let impulse =
                point.impulse::<USE_BIAS>(normal_velocity, bodies, normal_motion, inverse_h);
            let impulse = pushes.select(block[j], impulse);
            applied[j] = point.accumulate(impulse);
            total_normal_impulse += point.normal_impulse;
        }
        (applied, total_normal_impulse)
    }

    /// The manifold's friction: two tangent impulses at the centre of its points, driving the
    /// relative tangential velocity there toward the surface velocity's (`tangent_target`), and a
    /// twist impulse about the normal, kept together within the limit surface
    /// `(|λ_t| / μΣλ_n)² + (λ_tw / μΣλ_n⟨r⟩)² ≤ 1` (`contact_model::limit_surface_projection`;
    /// `⟨r⟩` the patch's mean distance from its centre, `contact_model::patch_radius_ratio`),
    /// given `Σλ_n`, and the pass's normal impulse `applied_normal`, which reaches the tangents'
    /// linear velocities only through a locked body (`t·M⁻¹n ≠ 0`). The tangents' trial impulses
    /// are solved from the same velocities, the twist's after them (through
    /// [`Self::tangent_twist`]), then the three are projected together. Applies the spins to
    /// `bodies` and returns the linear impulse, for [`PassLanes::finish`].
    #[inline(always)]
    fn solve_friction<const LOCKED: bool>(
        &mut self,
        bodies: &mut PassLanes,
        total_normal_impulse: F32x4,
        applied_normal: F32x4,
    ) -> Vec3x4 {
        let old = self.tangent_impulse;
        let old_twist = self.twist_impulse;
        let mut spin = (bodies.angular_b - bodies.angular_a).dot(self.normal);
        let mut trial = [F32x4::ZERO; 2];
        for axis in 0..2 {
            let jacobian = &self.tangent[axis];
            let mut velocity = self.tangents[axis].dot(bodies.relative_velocity)
                + jacobian.spin_velocity(bodies.angular_a, bodies.angular_b)
                - self.tangent_target[axis];
            if LOCKED {
                velocity += self.tangent_coupling[axis] * applied_normal;
            }
            trial[axis] = old[axis] - jacobian.mass * velocity;
            spin += self.tangent_twist[axis] * (trial[axis] - old[axis]);
        }
        let [tangent_1, tangent_2, twist] = limit_surface_projection(
            [trial[0], trial[1], old_twist - self.twist_mass * spin],
            [self.tangent[0].mass, self.tangent[1].mass, self.twist_mass],
            self.friction * total_normal_impulse,
            self.twist_radius,
        );
        self.tangent_impulse = [tangent_1, tangent_2];
        let mut linear_impulse = Vec3x4::ZERO;
        for (axis, previous) in old.into_iter().enumerate() {
            let applied = self.tangent_impulse[axis] - previous;
            linear_impulse += self.tangents[axis].scale(applied);
            self.tangent[axis].apply_spin(&mut bodies.angular_a, &mut bodies.angular_b, applied);
        }
        self.twist_impulse = twist;
        self.apply_twist(bodies, twist - old_twist);
        linear_impulse
    }
}
