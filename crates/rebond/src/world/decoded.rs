//! Checks of a world decoded from a state ([`World::load_state`]): a state whose checksum
//! matches is still only bytes (the checksum guards against damage, not against bytes made to
//! match it), so before a decoded world is handed out every index it stores is checked to be in
//! range and every value the step reads to be finite and within the limits.

use super::{World, WorldSettings};
use crate::arena::{restore_world, Arena};
use crate::body::{BodyHandle, BodyType, RigidBody};
use crate::error::{check_direction, check_length};
use crate::filter::IgnoredPairs;
use crate::island::Islands;
use crate::joint::JointSet;
use crate::limits::{MAX_ANGULAR_SPEED, MAX_MASS, MAX_SPEED, MIN_MASS};
use crate::math::Vec3;

/// How far past a speed limit a decoded velocity may lie: the step holds velocities to the limits
/// in `f32`, which may land a rounding above them.
const LIMIT_ROUNDING: f32 = 1.0 + 1e-5;

impl World {
    /// Checks the invariants a decoded world must hold for the step to be safe to run: storage,
    /// handles and indices in range, every body's values finite and in range, derived lists
    /// consistent with what they derive from. Describes the first broken invariant.
    pub(crate) fn check_decoded(&self) -> Result<(), String> {
        self.settings
            .validate()
            .map_err(|error| error.to_string())?;
        self.bodies.check_decoded()?;
        let slots = self.bodies.slot_count();
        for (index, body) in self.bodies.iter() {
            let slot = index.slot();
            check_body(body).map_err(|error| format!("body {slot}: {error}"))?;
            let is_static = body.body_type == BodyType::Static;
            let proxy_fits = body.proxy.is_some_and(|proxy| {
                self.broad_phase.is_live(proxy)
                    && proxy.is_static() == is_static
                    && self.broad_phase.key(proxy) as usize == slot
            });
            if !proxy_fits {
                return Err(format!("body {slot}'s broad-phase proxy is not its own"));
            }
        }
        if self.broad_phase.proxy_count() != self.bodies.len() {
            return Err("the broad phase holds proxies of no body".to_owned());
        }
        let ruled = self
            .bodies
            .iter()
            .filter(|(_, body)| body.has_contact_rules());
        if ruled.count() != self.contact_rule_bodies {
            return Err("the count of bodies with contact rules is wrong".to_owned());
        }
        self.broad_phase.check_decoded(slots)?;
        self.islands.check_decoded(&self.bodies)?;
        let is_live = |handle: BodyHandle| self.bodies.get(handle.0).is_some();
        self.contacts.check_decoded(is_live)?;
        self.joints.check_decoded(is_live)?;
        self.couplings.check_decoded(&self.joints)?;
        if self.bounds_of_slot.len() < slots
            || self.touched_static_slots.iter().any(|&slot| slot >= slots)
        {
            return Err("bounding boxes are missing for some slots".to_owned());
        }
        Ok(())
    }
}

/// A world rebuilt from a portable snapshot ([`crate::state`]), and what such a snapshot reads of
/// a world.
impl World {
    /// The world of `settings`, `bodies` and `joints` (built with their saved slots, generations
    /// and identity) and the `ignored` pairs, with no contacts: the broad phase, islands and
    /// bounding boxes are made from the bodies, sleeping ones parked as they were. Checked as a
    /// decoded world is; describes the first broken invariant.
    pub(crate) fn restored(
        settings: WorldSettings,
        bodies: Arena<RigidBody>,
        joints: JointSet,
        ignored: &[(BodyHandle, BodyHandle)],
    ) -> Result<World, String> {
        let mut world = World::new(settings).map_err(|error| error.to_string())?;
        restore_world(bodies.world());
        world.islands = Islands::restored(&bodies);
        world.bodies = bodies;
        world.joints = joints;
        world.contact_rule_bodies = (world.bodies.iter())
            .filter(|(_, body)| body.has_contact_rules())
            .count();
        let slots = world.bodies.slot_count();
        for slot in 0..slots {
            let Some(body) = world.bodies.at_slot_mut(slot) else {
                continue;
            };
            let (aabb, is_static) = (body.aabb(), body.body_type == BodyType::Static);
            let proxy = world.broad_phase.insert(slot as u32, aabb, is_static);
            body.proxy = Some(proxy);
            if body.sleeping && !is_static {
                world.broad_phase.set_asleep(proxy, true);
            }
            if world.bounds_of_slot.len() <= slot {
                world.bounds_of_slot.resize(slot + 1, aabb);
            }
            world.bounds_of_slot[slot] = aabb;
        }
        for &(a, b) in ignored {
            if world.bodies.get(a.0).is_none() || world.bodies.get(b.0).is_none() {
                return Err("an ignored pair names a missing body".to_owned());
            }
            world.ignored_pairs.set(a, b, true);
        }
        world.check_decoded()?;
        Ok(world)
    }

    /// The world's identity, which its handles carry.
    pub(crate) fn identity(&self) -> u32 {
        self.bodies.world()
    }

    /// Gives the body in arena slot `slot` its contact rules, checked as [`World::set_one_way`]
    /// and [`World::set_surface_velocity`] check them, without waking anything: a portable
    /// snapshot's last part.
    pub(crate) fn restore_contact_rules(
        &mut self,
        slot: usize,
        one_way: Option<Vec3>,
        surface_velocity: Vec3,
    ) -> crate::Result<()> {
        let one_way = one_way
            .map(|direction| check_direction("one_way", direction))
            .transpose()?;
        check_length("surface_velocity", surface_velocity, MAX_SPEED)?;
        let body = self
            .bodies
            .at_slot_mut(slot)
            .ok_or_else(|| crate::Error::new("", crate::ErrorKind::StaleHandle))?;
        let had_rules = body.has_contact_rules();
        body.one_way = one_way;
        body.surface_velocity = surface_velocity;
        let has_rules = body.has_contact_rules();
        self.count_contact_rules(had_rules, has_rules);
        Ok(())
    }

    /// The parts a portable snapshot reads: bodies, joints and ignored pairs.
    pub(crate) fn portable_parts(&self) -> (&Arena<RigidBody>, &JointSet, &IgnoredPairs) {
        (&self.bodies, &self.joints, &self.ignored_pairs)
    }
}

/// Checks a decoded body: its shape, finite values, its mass and `1/m`, materials and speeds in
/// range, sleep for dynamic bodies only.
fn check_body(body: &RigidBody) -> Result<(), String> {
    body.shape.check_decoded()?;
    body.check_kinematic_decoded()?;
    let vectors = [
        body.center_of_mass,
        body.local_center_of_mass,
        body.linear_velocity,
        body.angular_velocity,
        body.force,
        body.torque,
        body.constant_force,
        body.constant_torque,
        body.constant_force_point.unwrap_or_default(),
    ];
    let matrices = [
        body.local_inertia,
        body.local_inverse_inertia,
        body.world_inverse_inertia,
    ];
    let mass_fits = match body.body_type {
        BodyType::Dynamic => {
            (MIN_MASS..=MAX_MASS).contains(&body.mass)
                && (body.inverse_mass * body.mass - 1.0).abs() <= 1e-5
        }
        BodyType::Static | BodyType::Kinematic => {
            // Only dynamic bodies fall asleep: waking another's group would park or unpark a
            // proxy that never sleeps.
            body.inverse_mass == 0.0 && !body.sleeping && body.sleep_group.is_none()
        }
    };
    let finite = mass_fits
        && vectors.iter().all(|vector| vector.is_finite())
        && matrices.iter().all(|matrix| matrix.is_finite())
        && body.rotation.is_normalized()
        && [
            body.mass,
            body.inverse_mass,
            body.sleep_time,
            body.max_extent,
        ]
        .iter()
        .all(|value| value.is_finite() && *value >= 0.0);
    let in_range = [
        body.linear_damping,
        body.angular_damping,
        body.friction,
        body.rolling_resistance,
    ]
    .iter()
    .all(|value| value.is_finite() && *value >= 0.0)
        && (0.0..=1.0).contains(&body.restitution)
        && body.contact_force_threshold >= 0.0
        && body
            .one_way
            .is_none_or(|direction| direction.is_finite() && direction.is_normalized())
        && body.surface_velocity.length() <= MAX_SPEED
        && body.linear_velocity.length() <= MAX_SPEED * LIMIT_ROUNDING
        && body.angular_velocity.length() <= MAX_ANGULAR_SPEED * LIMIT_ROUNDING;
    if finite && in_range {
        Ok(())
    } else {
        Err("a value is not finite or out of its range".to_owned())
    }
}
