//! A kinematic character controller: a convex shape moved each frame by a desired translation,
//! corrected by the world's shape casts so that it slides along walls, climbs slopes and steps,
//! snaps to the ground, rides moving platforms and pushes dynamic bodies.
//!
//! The character never touches anything: it keeps a small gap, the `offset` (default 1 cm), to
//! every surface, which keeps each shape cast from starting in contact. Each call to
//! [`CharacterController::move_shape`] runs:
//!
//! 1. **Recovery**: a shape that starts overlapping a body (a platform rose into it, the user
//!    teleported it) is pushed out along the quickest way, plus the offset.
//! 2. **Slide**: the shape is cast along the remaining motion; it travels until its gap along
//!    the hit's normal is the offset, `s = d − offset / (−û·n)` (`d` the cast's distance, `û` the
//!    unit direction), and the rest of the motion is deflected by the surface, up to
//!    `max_iterations` casts:
//!    - a **walkable** surface (its normal within `max_slope_angle` of `up`) is ground: the
//!      motion down into it is dropped (the character stands, it does not slide), and the
//!      lateral motion is lifted along `up` onto the surface, `l' = l − up (l·n)/(n·up)`, so the
//!      character climbs a slope at its full lateral speed;
//!    - a **steep** surface is a wall: the lateral motion loses its part into the wall's
//!      horizontal normal (a wall cannot be climbed by walking into it), and the vertical motion
//!      is projected on the surface, `v' = v − (v·n) n`, so a character pushed down slides down
//!      it; walking into a wall at angle `α` from its normal slides along it at `|l| sin α`;
//!    - motion deflected back into the previous surface follows the crease of the two.
//! 3. **Step**: blocked by a steep surface while grounded, the character tries to step up: it
//!    rises by up to `max_step_height`, needs free space ahead of the larger of the move and
//!    `min_step_width`, walkable ground below that point within the rise, and then drops onto
//!    what is under it. A step too high blocks the forward cast and is refused.
//! 4. **Ground**: when no ground was met and the motion does not go up, a cast down of twice the
//!    offset, plus `snap_distance` when the character was grounded at its last move, finds the
//!    ground it stands on (or snaps down to, walking down a step or a slope).
//! 5. **Platform**: a character grounded at its last move on a moving body is carried by that
//!    body's velocity at the ground point, `v + ω × r`, times `dt`, cast against everything but
//!    that body.
//!
//! Which surface is ground is decided on its normal; a rounded shape resting on an edge touches
//! it along a tilted normal, so for a contact normal steeper than `max_slope_angle` but within
//! 75° of `up`, a short ray cast down beside the contact point, on the side of the surface, reads
//! the normal of the face under the edge: a character stands on a step's edge.
//!
//! Each hit reports the impulse the character gives a dynamic body it walks into (never the
//! body it stands on): the velocity of the motion the body blocked, `J = m b / dt` along the
//! blocked motion `b`, at the hit point, at most `push_force · dt` in one move for one body.
//! [`CharacterController::apply_pushes`] applies them, and [`CharacterController::move_body`]
//! does everything for a kinematic body of the world.

use crate::body::{BodyHandle, BodyType, RigidBody};
use crate::error::{
    check_count, check_length, check_non_negative, check_non_negative_or_infinite, check_range,
    check_size, Error, ErrorKind, Result,
};
use crate::limits::{MAX_COORDINATE, MAX_FORCE, MAX_SIZE, MAX_TIMESTEP, MIN_TIMESTEP};
use crate::math::{Pose, Vec3};
use crate::query::{closest_points, validated_pose, ClosestPoints, QueryFilter, Ray, ShapeHit};
use crate::shape::Shape;
use crate::world::World;

/// The steepest `max_slope_angle`, radians (80°): lifting the lateral motion onto a walkable
/// slope multiplies it by up to `tan` of the angle, 5.7 at 80°.
pub const MAX_SLOPE_ANGLE: f32 = 80.0 * std::f32::consts::PI / 180.0;

/// Most shape casts of one slide, `max_iterations`' upper bound.
pub const MAX_ITERATIONS: u32 = 64;

/// A contact normal this far from `up` or closer, radians (75°), that is too steep to walk on
/// may be a rounded shape resting on an edge: the face under the edge is read by a ray.
const EDGE_ANGLE: f32 = 75.0 * std::f32::consts::PI / 180.0;

/// Motion shorter than this, metres, is no motion: a micrometre, below the shape casts'
/// precision (1e-5 of the shapes' size).
const MIN_MOTION: f32 = 1e-6;

/// Slack on the walkable test's cosine, so that a floor read 1 ulp off `up` is walkable with
/// `max_slope_angle = 0`.
const WALKABLE_SLACK: f32 = 1e-6;

/// How a character moves: every length in metres, angles in radians. Checked by
/// [`CharacterController::new`], whose errors name the field.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CharacterSettings {
    /// The character's up direction, any finite non-zero length (normalised), default `+Y`.
    pub up: Vec3,
    /// The steepest slope the character stands on and climbs, 0 to [`MAX_SLOPE_ANGLE`], default
    /// 45° (π/4). Steeper surfaces are walls, down which it slides.
    pub max_slope_angle: f32,
    /// The highest step climbed, ≥ 0, default 0.3; 0 climbs no step.
    pub max_step_height: f32,
    /// The free space needed on top of a step beyond the character, ≥ 0, default 0.1.
    pub min_step_width: f32,
    /// How far down a grounded character follows the ground when it falls away (down a step or
    /// a slope), ≥ 0, default 0.2.
    pub snap_distance: f32,
    /// The gap kept to every surface, 1 mm to 100 km, default 0.01.
    pub offset: f32,
    /// The largest force with which the character pushes a dynamic body, newtons, ≥ 0 (infinity:
    /// no limit), default 1,000 N: in one move a body gets at most `push_force · dt` of impulse.
    pub push_force: f32,
    /// Most shape casts of the slide, 1 to [`MAX_ITERATIONS`], default 6.
    pub max_iterations: u32,
}

impl Default for CharacterSettings {
    fn default() -> Self {
        Self {
            up: Vec3::Y,
            max_slope_angle: std::f32::consts::FRAC_PI_4,
            max_step_height: 0.3,
            min_step_width: 0.1,
            snap_distance: 0.2,
            offset: 0.01,
            push_force: 1000.0,
            max_iterations: 6,
        }
    }
}

impl CharacterSettings {
    /// The settings checked, with `up` normalised.
    fn validated(&self) -> Result<Self> {
        let up = check_length("up", self.up, MAX_SIZE)?
            .try_normalize()
            .ok_or_else(|| Error::new("up", ErrorKind::ZeroVector))?;
        let max_slope_angle = check_range(
            "max_slope_angle",
            self.max_slope_angle,
            0.0,
            MAX_SLOPE_ANGLE,
        )?;
        let lengths = [
            ("max_step_height", self.max_step_height),
            ("min_step_width", self.min_step_width),
            ("snap_distance", self.snap_distance),
        ];
        for (field, value) in lengths {
            check_range(field, check_non_negative(field, value)?, 0.0, MAX_SIZE)?;
        }
        check_count("max_iterations", self.max_iterations, 1, MAX_ITERATIONS)?;
        Ok(Self {
            up,
            max_slope_angle,
            offset: check_size("offset", self.offset)?,
            push_force: check_non_negative_or_infinite("push_force", self.push_force)?,
            ..*self
        })
    }
}

/// What the character stands on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ground {
    /// The body.
    pub body: BodyHandle,
    /// Its collider: a compound child's index, or 0.
    pub collider: u32,
    /// Where the character touches it, world, metres.
    pub point: Vec3,
    /// The ground's unit surface normal there, world: within `max_slope_angle` of `up` (for a
    /// character resting on an edge, the normal of the face under it).
    pub normal: Vec3,
}

/// A surface the character's shape met during a move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CharacterHit {
    /// The cast's hit: the body and collider met, the contact point on the body, the body's
    /// normal there facing the character, and how far the shape had travelled in that cast
    /// (the time of impact at unit speed, metres).
    pub hit: ShapeHit,
    /// The impulse the character gives the body, N·s, at the contact point: zero unless the
    /// body is dynamic and blocked the character's motion (see the [module
    /// documentation](self)).
    pub impulse: Vec3,
}

/// The outcome of one move.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CharacterMove {
    /// The corrected translation, world, metres: where the character goes instead of the
    /// desired translation.
    pub translation: Vec3,
    /// What the character stands on at the end of the move, `None` in the air.
    pub ground: Option<Ground>,
    /// Every surface met, in the order met.
    pub hits: Vec<CharacterHit>,
}

impl CharacterMove {
    /// Whether the character stands on walkable ground at the end of the move.
    pub fn is_grounded(&self) -> bool {
        self.ground.is_some()
    }
}

/// A character controller: the settings of one character and what its last move found (the
/// ground it snaps to and rides on). See the [module documentation](self) for the rules.
///
/// ```
/// use rebond::character::{CharacterController, CharacterSettings};
/// use rebond::prelude::*;
///
/// let mut world = World::new(WorldSettings::default())?;
/// world.add_body(BodyDesc::static_body(Shape::cuboid(Vec3::new(10.0, 0.5, 10.0))?)
///     .position(Vec3::new(0.0, -0.5, 0.0)))?;
/// let mut controller = CharacterController::new(CharacterSettings::default())?;
/// let capsule = Shape::capsule(0.3, 0.5)?;
/// let pose = Pose::from_position(Vec3::new(0.0, 0.81, 0.0));
/// // Walk along x at 3 m/s and fall at 1 m/s: the ground holds the character up.
/// let dt = 1.0 / 60.0;
/// let moved = controller.move_shape(&world, &capsule, &pose, Vec3::new(3.0, -1.0, 0.0) * dt, dt,
///     &QueryFilter::default())?;
/// assert!(moved.is_grounded());
/// assert!((moved.translation.x - 0.05).abs() < 1e-5);
/// # Ok::<(), rebond::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct CharacterController {
    settings: CharacterSettings,
    /// `cos(max_slope_angle)`, less [`WALKABLE_SLACK`].
    walkable_cos: f32,
    last: CharacterMove,
    /// The hits of the move being made, swapped with `last.hits` once it succeeds.
    spare_hits: Vec<CharacterHit>,
}

impl CharacterController {
    /// A controller with `settings`, never moved yet (not grounded).
    ///
    /// # Errors
    /// A setting out of its range (see [`CharacterSettings`]), naming the field.
    pub fn new(settings: CharacterSettings) -> Result<Self> {
        let settings = settings.validated()?;
        Ok(Self {
            walkable_cos: settings.max_slope_angle.cos() - WALKABLE_SLACK,
            settings,
            last: CharacterMove::default(),
            spare_hits: Vec::new(),
        })
    }

    /// The settings, with `up` normalised.
    pub fn settings(&self) -> &CharacterSettings {
        &self.settings
    }

    /// The last move made, empty before the first.
    pub fn last_move(&self) -> &CharacterMove {
        &self.last
    }

    /// Moves `shape`, placed at `pose`, by `desired_translation` (metres) over a frame of `dt`
    /// seconds against the bodies `filter` sees (sensors never count), and returns the corrected
    /// move. Nothing in the world changes: move the character by the returned translation, and
    /// call [`apply_pushes`](Self::apply_pushes) for the dynamic bodies it pushes.
    ///
    /// # Errors
    /// A shape that is a halfspace, a trimesh, a heightfield ([`ErrorKind::NotConvex`], field
    /// `shape`); a bad `pose` (`pose.position`, `pose.rotation`), a non-finite
    /// `desired_translation` or one longer than the coordinate limit, a `dt` outside
    /// [`MIN_TIMESTEP`] to [`MAX_TIMESTEP`], a filter excluding a body of another world. The
    /// controller is unchanged by a refused call.
    pub fn move_shape(
        &mut self,
        world: &World,
        shape: &Shape,
        pose: &Pose,
        desired_translation: Vec3,
        dt: f32,
        filter: &QueryFilter,
    ) -> Result<&CharacterMove> {
        let mut hits = std::mem::take(&mut self.spare_hits);
        let found = self.compute(
            world,
            shape,
            pose,
            desired_translation,
            dt,
            filter,
            &mut hits,
        );
        self.commit(found, hits)
    }

    /// Gives every dynamic body the last move pushed its [`CharacterHit::impulse`].
    ///
    /// # Errors
    /// A body pushed that was removed since (field `hits[i].body`); the impulses before it
    /// were applied.
    pub fn apply_pushes(&self, world: &mut World) -> Result<()> {
        for (index, hit) in self.last.hits.iter().enumerate() {
            if hit.impulse != Vec3::ZERO {
                world
                    .body_mut(hit.hit.body)
                    .and_then(|body| body.apply_impulse_at_point(hit.impulse, hit.hit.point))
                    .map_err(|error| error.within(&format!("hits[{index}].body")))?;
            }
        }
        Ok(())
    }

    /// Moves the kinematic body `body` as a character with its own shape: the move of
    /// [`move_shape`](Self::move_shape) (the body never meets itself), set as its pose target
    /// ([`RigidBody::set_kinematic_target`]), so the next [`World::step`] carries it there with
    /// the matching velocity and its contacts and events stay right; then the pushes are
    /// applied. Call it once a frame, before the step.
    ///
    /// # Errors
    /// A removed body ([`ErrorKind::StaleHandle`], field `body`), one that is not kinematic
    /// ([`ErrorKind::NotKinematic`], field `body`), the errors of `move_shape`, a target past the
    /// coordinate limit (`target.position`). Nothing changes on a refused call.
    pub fn move_body(
        &mut self,
        world: &mut World,
        body: BodyHandle,
        desired_translation: Vec3,
        dt: f32,
        filter: &QueryFilter,
    ) -> Result<&CharacterMove> {
        let character = world.body(body).map_err(|error| error.within("body"))?;
        if character.body_type() != BodyType::Kinematic {
            return Err(Error::new("body", ErrorKind::NotKinematic));
        }
        let pose = character.pose();
        let user_predicate = filter.predicate;
        let not_itself = move |handle: BodyHandle, other: &RigidBody| {
            handle != body && user_predicate.is_none_or(|predicate| predicate(handle, other))
        };
        let own_filter = QueryFilter {
            predicate: Some(&not_itself),
            ..*filter
        };
        let mut hits = std::mem::take(&mut self.spare_hits);
        let found = self.compute(
            world,
            character.shape(),
            &pose,
            desired_translation,
            dt,
            &own_filter,
            &mut hits,
        );
        let found = found.and_then(|(translation, ground)| {
            let target = Pose::new(pose.position + translation, pose.rotation);
            world.body_mut(body)?.set_kinematic_target(target)?;
            Ok((translation, ground))
        });
        self.commit(found, hits)?;
        self.apply_pushes(world)?;
        Ok(&self.last)
    }

    /// Makes a successful move the last one, keeping both hit lists' storage.
    fn commit(
        &mut self,
        found: Result<(Vec3, Option<Ground>)>,
        mut hits: Vec<CharacterHit>,
    ) -> Result<&CharacterMove> {
        match found {
            Ok((translation, ground)) => {
                std::mem::swap(&mut self.last.hits, &mut hits);
                self.spare_hits = hits;
                self.last.translation = translation;
                self.last.ground = ground;
                Ok(&self.last)
            }
            Err(error) => {
                self.spare_hits = hits;
                Err(error)
            }
        }
    }

    /// The corrected translation and the ground of a move, its hits into `hits`.
    #[allow(clippy::too_many_arguments)]
    fn compute(
        &self,
        world: &World,
        shape: &Shape,
        pose: &Pose,
        desired: Vec3,
        dt: f32,
        filter: &QueryFilter,
        hits: &mut Vec<CharacterHit>,
    ) -> Result<(Vec3, Option<Ground>)> {
        hits.clear();
        if shape.is_triangulated() || !shape.is_bounded() {
            return Err(Error::new("shape", ErrorKind::NotConvex));
        }
        let pose = validated_pose("pose", pose)?;
        check_length("desired_translation", desired, MAX_COORDINATE)?;
        check_range("dt", dt, MIN_TIMESTEP, MAX_TIMESTEP)?;
        let solid_filter = QueryFilter {
            include_sensors: false,
            ..*filter
        };
        let mover = Mover {
            settings: &self.settings,
            walkable_cos: self.walkable_cos,
            world,
            shape,
            pose,
            filter: &solid_filter,
            dt,
        };
        let mut position = mover.recover(pose.position)?;
        let last_ground = self.last.ground;
        let mut ground = None;
        let mut slide = Slide {
            position: &mut position,
            ground: &mut ground,
            hits,
            may_step: last_ground.is_some(),
        };
        mover.slide(&mut slide, desired)?;
        if ground.is_none() && desired.dot(self.settings.up) <= 0.0 {
            let reach = if last_ground.is_some() {
                self.settings.snap_distance
            } else {
                0.0
            };
            if let Some((drop, found)) = mover.ground_below(position, reach)? {
                position -= self.settings.up * drop;
                ground = Some(found);
            }
        }
        if let Some(carried) = last_ground.and_then(|below| mover.carried(below)) {
            let (motion, platform) = carried;
            let filter_predicate = solid_filter.predicate;
            let not_platform = move |handle: BodyHandle, other: &RigidBody| {
                handle != platform
                    && filter_predicate.is_none_or(|predicate| predicate(handle, other))
            };
            let off_platform = QueryFilter {
                predicate: Some(&not_platform),
                ..solid_filter
            };
            let carrier = Mover {
                filter: &off_platform,
                ..mover
            };
            let mut ignored_ground = None;
            let mut slide = Slide {
                position: &mut position,
                ground: &mut ignored_ground,
                hits,
                may_step: false,
            };
            carrier.slide(&mut slide, motion)?;
        }
        Ok((position - pose.position, ground))
    }
}

/// One move's fixed inputs.
#[derive(Clone, Copy)]
struct Mover<'a> {
    settings: &'a CharacterSettings,
    walkable_cos: f32,
    world: &'a World,
    shape: &'a Shape,
    pose: Pose,
    filter: &'a QueryFilter<'a>,
    dt: f32,
}

/// The state a slide updates.
struct Slide<'a> {
    position: &'a mut Vec3,
    ground: &'a mut Option<Ground>,
    hits: &'a mut Vec<CharacterHit>,
    /// Whether the character may step up (it was grounded at its last move or met ground).
    may_step: bool,
}

/// A surface met, classified.
struct Surface {
    walkable: bool,
    /// The surface normal: the contact normal, or the face's under an edge.
    normal: Vec3,
}

impl Mover<'_> {
    /// The first hit of the shape at `position` cast along unit `direction` for `distance`.
    fn cast(&self, position: Vec3, direction: Vec3, distance: f32) -> Result<Option<ShapeHit>> {
        let pose = Pose::new(position, self.pose.rotation);
        self.world
            .cast_shape(self.shape, &pose, direction, distance, self.filter)
    }

    /// How far the shape may travel along unit `direction`, at most `length`, toward `hit` and
    /// keep the offset to it along its normal.
    fn travel(&self, hit: &ShapeHit, direction: Vec3, length: f32) -> f32 {
        let into = -direction.dot(hit.normal);
        let keep = if into > MIN_MOTION {
            self.settings.offset / into
        } else {
            0.0
        };
        (hit.distance - keep).clamp(0.0, length)
    }

    /// Pushes the shape out of the bodies it starts in, along the quickest way plus the offset.
    fn recover(&self, mut position: Vec3) -> Result<Vec3> {
        for _ in 0..self.settings.max_iterations {
            let Some(hit) = self.cast(position, self.settings.up, 0.0)? else {
                break;
            };
            let body = self.world.body(hit.body)?;
            let pose = Pose::new(position, self.pose.rotation);
            match closest_points(body.shape(), &body.pose(), self.shape, &pose, 0.0)? {
                ClosestPoints::Overlapping { normal, depth, .. } if depth.is_finite() => {
                    position += normal * (depth + self.settings.offset);
                }
                _ => break,
            }
        }
        Ok(position)
    }

    /// Whether the surface `hit` is walkable, and its normal.
    fn surface(&self, hit: &ShapeHit) -> Result<Surface> {
        let up = self.settings.up;
        let rise = hit.normal.dot(up);
        if rise >= self.walkable_cos {
            return Ok(Surface {
                walkable: true,
                normal: hit.normal,
            });
        }
        let steep = Surface {
            walkable: false,
            normal: hit.normal,
        };
        if rise < EDGE_ANGLE.cos() {
            return Ok(steep);
        }
        // Beside the contact, a step inward over the surface and up: a solid ray from there
        // starts inside a slope steeper than 45°, and meets the face under an edge.
        let Some(inward) = (up * rise - hit.normal).try_normalize() else {
            return Ok(steep);
        };
        let probe = self.settings.offset;
        let ray = Ray::new(hit.point + (inward + up) * probe, -up).max_distance(2.0 * probe);
        Ok(match self.world.cast_ray(&ray, self.filter)? {
            Some(face) if face.distance > 0.0 && face.normal.dot(up) >= self.walkable_cos => {
                Surface {
                    walkable: true,
                    normal: face.normal,
                }
            }
            _ => steep,
        })
    }

    /// Moves the shape along `motion`, deflected by what it meets (module documentation).
    fn slide(&self, slide: &mut Slide, motion: Vec3) -> Result<()> {
        let mut remaining = motion;
        let mut previous_normal: Option<Vec3> = None;
        for _ in 0..self.settings.max_iterations {
            let length = remaining.length();
            if length <= MIN_MOTION {
                break;
            }
            let direction = remaining / length;
            let cast = self.cast(*slide.position, direction, length + self.settings.offset)?;
            let Some(hit) = cast else {
                *slide.position += remaining;
                break;
            };
            let travel = self.travel(&hit, direction, length);
            *slide.position += direction * travel;
            remaining -= direction * travel;
            let surface = self.surface(&hit)?;
            if surface.walkable {
                *slide.ground = Some(ground_of(&hit, surface.normal));
                slide.may_step = true;
            }
            let mut deflected = self.deflect(remaining, hit.normal, surface.walkable);
            if let Some(previous) = previous_normal {
                if deflected.dot(previous) < 0.0 {
                    deflected = crease(deflected, previous, hit.normal);
                }
            }
            let impulse = self.push(&hit, remaining - deflected, surface.walkable, slide.hits)?;
            slide.hits.push(CharacterHit { hit, impulse });
            if !surface.walkable && slide.may_step {
                if let Some((position, ground)) = self.step_up(*slide.position, remaining)? {
                    *slide.position = position;
                    *slide.ground = Some(ground);
                    remaining = self.settings.up * remaining.dot(self.settings.up).max(0.0);
                    previous_normal = None;
                    continue;
                }
            }
            remaining = deflected;
            previous_normal = Some(hit.normal);
        }
        Ok(())
    }

    /// The rest of a motion `r` after meeting a surface of contact normal `n`: walked on (ground)
    /// or a wall (module documentation).
    fn deflect(&self, r: Vec3, n: Vec3, walk_on: bool) -> Vec3 {
        let up = self.settings.up;
        let vertical = up * r.dot(up);
        let lateral = r - vertical;
        if walk_on {
            let rise = if r.dot(up) > 0.0 {
                slide_along(vertical, n)
            } else {
                Vec3::ZERO
            };
            let into = lateral.dot(n);
            let lifted = if into < 0.0 {
                lateral - up * (into / n.dot(up))
            } else {
                lateral
            };
            rise + lifted
        } else {
            let wall = (n - up * n.dot(up)).try_normalize();
            let lateral = wall.map_or(lateral, |wall| slide_along(lateral, wall));
            lateral + slide_along(vertical, n)
        }
    }

    /// The impulse the character gives the body of `hit` for the `blocked` motion: zero unless
    /// dynamic and not stood on; at most `push_force · dt` over the move's hits of the body.
    fn push(
        &self,
        hit: &ShapeHit,
        blocked: Vec3,
        walkable: bool,
        earlier: &[CharacterHit],
    ) -> Result<Vec3> {
        let body = self.world.body(hit.body)?;
        if walkable || body.body_type() != BodyType::Dynamic || blocked.length() <= MIN_MOTION {
            return Ok(Vec3::ZERO);
        }
        let given: f32 = earlier
            .iter()
            .filter(|other| other.hit.body == hit.body)
            .map(|other| other.impulse.length())
            .sum();
        // An infinite push force is held to the engine's impulse limit, which bodies accept.
        let cap = (self.settings.push_force * self.dt).min(MAX_FORCE);
        let cap = (cap - given).max(0.0);
        let wanted = blocked * (body.mass() / self.dt);
        Ok(wanted.clamp_length_max(cap))
    }

    /// The position after stepping up onto what blocks the lateral part of `remaining` at
    /// `position`, and the ground there; `None` when there is no step to climb.
    fn step_up(&self, position: Vec3, remaining: Vec3) -> Result<Option<(Vec3, Ground)>> {
        let up = self.settings.up;
        if remaining.dot(up) > MIN_MOTION || self.settings.max_step_height <= 0.0 {
            return Ok(None);
        }
        let lateral = remaining - up * remaining.dot(up);
        let length = lateral.length();
        if length <= MIN_MOTION {
            return Ok(None);
        }
        let direction = lateral / length;
        let height = self.settings.max_step_height;
        let rise = match self.cast(position, up, height + self.settings.offset)? {
            Some(hit) => self.travel(&hit, up, height),
            None => height,
        };
        if rise <= MIN_MOTION {
            return Ok(None);
        }
        let raised = position + up * rise;
        let ahead = length.max(self.settings.min_step_width);
        if self
            .cast(raised, direction, ahead + self.settings.offset)?
            .is_some()
        {
            return Ok(None);
        }
        let Some((_, probe)) = self.landing(raised + direction * ahead, rise)? else {
            return Ok(None);
        };
        let moved = raised + direction * length;
        let landing = self.landing(moved, rise)?;
        let (drop, ground) = landing.unwrap_or((rise, probe));
        Ok(Some((moved - up * drop, ground)))
    }

    /// The walkable ground under `position` within `reach` (keeping the offset): how far down it
    /// is and what it is.
    fn landing(&self, position: Vec3, reach: f32) -> Result<Option<(f32, Ground)>> {
        let down = -self.settings.up;
        let Some(hit) = self.cast(position, down, reach + self.settings.offset)? else {
            return Ok(None);
        };
        let surface = self.surface(&hit)?;
        Ok(surface.walkable.then(|| {
            (
                self.travel(&hit, down, reach),
                ground_of(&hit, surface.normal),
            )
        }))
    }

    /// The ground the character at `position` stands on, within twice the offset plus `reach`:
    /// how far down it is (keeping the offset) and what it is.
    fn ground_below(&self, position: Vec3, reach: f32) -> Result<Option<(f32, Ground)>> {
        self.landing(position, reach + self.settings.offset)
            .map(|found| found.map(|(drop, ground)| (drop.min(reach), ground)))
    }

    /// The motion over the frame of the point of the last move's ground the character stands
    /// on, and that body; `None` on a static or still body, or one removed since.
    fn carried(&self, ground: Ground) -> Option<(Vec3, BodyHandle)> {
        let body = self.world.body(ground.body).ok()?;
        let motion = body.velocity_at_point(ground.point) * self.dt;
        (body.body_type() != BodyType::Static && motion.length() > MIN_MOTION)
            .then_some((motion, ground.body))
    }
}

/// `motion` less its part into a surface of unit normal `normal`.
fn slide_along(motion: Vec3, normal: Vec3) -> Vec3 {
    motion - normal * motion.dot(normal).min(0.0)
}

/// `motion` along the crease of two surfaces of normals `a` and `b` (none when they are
/// parallel: then the motion stops).
fn crease(motion: Vec3, a: Vec3, b: Vec3) -> Vec3 {
    a.cross(b)
        .try_normalize()
        .map_or(Vec3::ZERO, |along| along * motion.dot(along))
}

fn ground_of(hit: &ShapeHit, normal: Vec3) -> Ground {
    Ground {
        body: hit.body,
        collider: hit.collider,
        point: hit.point,
        normal,
    }
}
