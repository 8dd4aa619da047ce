//! The portable snapshot of a state: the world in frozen record types of its own, which every
//! later build reads, whatever has become of the engine's internal structures.
//!
//! The records are versioned by [`Snapshot`]: a build that changes what a snapshot holds adds a
//! variant (`V2`, …) with records of its own and converts every earlier variant into it when
//! reading; a variant, once released, never changes. Vectors are `[x, y, z]`, quaternions
//! `[x, y, z, w]`, matrices three columns, all in SI units; bodies and joints keep their slots
//! and generations, so that every handle, stale ones too, names the same thing after a load.
//!
//! What a snapshot does not hold is rebuilt when it is read: contacts and their warm-start
//! impulses (contacts start cold), the joints' warm-start impulses, the broad phase's tree,
//! islands (from the bodies' sleep groups), and the last step's events and joint forces to
//! report come back as the next step makes them.

mod couplings;
mod joints;

use std::collections::HashMap;

use serde::{Deserialize, Serialize};

use crate::arena::Arena;
use crate::body::RigidBody;
use crate::body::{BodyDesc, BodyHandle, BodyType, KinematicPath, LockedAxes, PathPoint};
use crate::error::check_position;
use crate::filter::InteractionGroups;
use crate::joint::JointSet;
use crate::mass::MassProperties;
use crate::material::CombineRule;
use crate::math::{Mat3, Pose, Quat, Vec3};
use crate::shape::{CompoundChild, Shape, TriMesh, TriangleMaterial};
use crate::{World, WorldSettings};
pub(crate) use couplings::SnapshotV5;
use joints::{JointExtrasV4, JointV1};

/// A portable snapshot, by version. Reading takes any variant this build knows; a snapshot of a
/// later version than [`SNAPSHOT_VERSIONS`] is one this build cannot read.
#[derive(Serialize, Deserialize)]
pub(crate) enum Snapshot {
    /// Version 1 (rebond's state format version 2).
    V1(SnapshotV1),
    /// Version 2: version 1's records and the bodies' contact rules.
    V2(SnapshotV2),
    /// Version 3: version 2's records and the triangle meshes' materials.
    V3(SnapshotV3),
    /// Version 4: version 3's records and the joints' springs' references, armatures and
    /// generic joints.
    V4(SnapshotV4),
    /// Version 5: version 4's records and the couplings (`couplings.rs`).
    V5(SnapshotV5),
}

/// How many versions of [`Snapshot`] this build reads: its variants, numbered from 0 in its
/// encoding.
pub(crate) const SNAPSHOT_VERSIONS: u32 = 5;

/// Version 2 of a snapshot: version 1's, and the contact rules of the bodies that have some.
#[derive(Serialize, Deserialize)]
pub(crate) struct SnapshotV2 {
    pub world: WorldV1,
    pub scene: Option<SceneV1>,
    /// By ascending slot.
    contact_rules: Vec<ContactRulesV2>,
}

/// Version 3 of a snapshot: version 2's, and the materials of the triangle meshes that have
/// some.
#[derive(Serialize, Deserialize)]
pub(crate) struct SnapshotV3 {
    pub world: WorldV1,
    pub scene: Option<SceneV1>,
    /// By ascending slot.
    contact_rules: Vec<ContactRulesV2>,
    /// By ascending shape.
    mesh_materials: Vec<MeshMaterialsV3>,
}

/// Version 4 of a snapshot: version 3's, and what the joints that have some add to their
/// records ([`JointExtrasV4`]).
#[derive(Serialize, Deserialize)]
pub(crate) struct SnapshotV4 {
    pub world: WorldV1,
    pub scene: Option<SceneV1>,
    /// By ascending slot.
    contact_rules: Vec<ContactRulesV2>,
    /// By ascending shape.
    mesh_materials: Vec<MeshMaterialsV3>,
    /// By ascending joint slot.
    joint_extras: Vec<JointExtrasV4>,
}

/// The materials of the triangle mesh [`WorldV1::shapes`]`[shape]`
/// ([`crate::shape::TriMesh::with_materials`]).
#[derive(Serialize, Deserialize, PartialEq)]
struct MeshMaterialsV3 {
    shape: u32,
    /// Friction, restitution and rolling resistance; `None` for the body's.
    materials: Vec<[Option<f32>; 3]>,
    /// Each triangle's index into `materials`, one per triangle of the record.
    triangle_materials: Vec<u32>,
}

impl MeshMaterialsV3 {
    /// The materials of `shape` as the record of shape `index`; `None` for a shape without.
    fn of(shape: &Shape, index: u32) -> Option<Self> {
        let Shape::TriMesh(mesh) = shape else {
            return None;
        };
        if mesh.materials().is_empty() {
            return None;
        }
        let materials = (mesh.materials().iter())
            .map(|m| [m.friction, m.restitution, m.rolling_resistance])
            .collect();
        let triangle_materials = (0..mesh.indices().len() as u32)
            .map(|triangle| mesh.material_index(triangle).unwrap_or_default())
            .collect();
        Some(Self {
            shape: index,
            materials,
            triangle_materials,
        })
    }

    /// Gives `shapes[self.shape]`, a triangle mesh, its materials, checked as the constructor
    /// checks them.
    fn apply(&self, shapes: &mut [Shape]) -> Result<(), String> {
        let index = self.shape;
        let place = |error| format!("shape {index}: {error}");
        let Some(Shape::TriMesh(mesh)) = shapes.get(index as usize) else {
            return Err(format!("shape {index} is not a trimesh to give materials"));
        };
        let materials = (self.materials.iter())
            .map(
                |&[friction, restitution, rolling_resistance]| TriangleMaterial {
                    friction,
                    restitution,
                    rolling_resistance,
                },
            )
            .collect();
        let mesh = TriMesh::with_materials(
            mesh.vertices().to_vec(),
            mesh.indices(),
            materials,
            &self.triangle_materials,
        )
        .map_err(place)?;
        shapes[index as usize] = Shape::TriMesh(mesh);
        Ok(())
    }
}

/// A body's contact rules ([`crate::hooks`]), body frame.
#[derive(Serialize, Deserialize)]
struct ContactRulesV2 {
    slot: u32,
    /// Unit direction bodies pass through it from.
    one_way: Option<[f32; 3]>,
    /// m/s.
    surface_velocity: [f32; 3],
}

/// Version 1 of a snapshot: a world, and for a scene's state its names and clock.
#[derive(Serialize, Deserialize)]
pub(crate) struct SnapshotV1 {
    pub world: WorldV1,
    pub scene: Option<SceneV1>,
}

/// A scene's names, timestep and step count ([`crate::scene::Scene::save_state`]).
#[derive(Serialize, Deserialize)]
pub(crate) struct SceneV1 {
    /// The steps taken when the state was saved.
    pub step: u64,
    /// The timestep, s, as the scene gave it.
    pub timestep: f64,
    /// Each scene body's name and handle, in scene order, removed bodies included.
    pub bodies: Vec<NamedV1>,
    /// Each scene joint's name and handle, in scene order.
    pub joints: Vec<NamedV1>,
}

/// A name and the handle it names.
#[derive(Serialize, Deserialize)]
pub(crate) struct NamedV1 {
    pub name: String,
    pub slot: u32,
    pub generation: u32,
}

/// A world: its identity (what its handles carry), settings, shapes, bodies, joints and
/// ignored pairs.
#[derive(Serialize, Deserialize)]
pub(crate) struct WorldV1 {
    identity: u32,
    settings: SettingsV1,
    /// Every distinct shape once: bodies name theirs by index, and share it again when read.
    shapes: Vec<ShapeV1>,
    /// Every body slot in order: its generation and body, if it holds one.
    bodies: Vec<SlotV1<BodyV1>>,
    /// The empty body slots in the order the next bodies added take them (last first).
    free_bodies: Vec<u32>,
    joints: Vec<SlotV1<JointV1>>,
    free_joints: Vec<u32>,
    /// Pairs of body slots told to ignore each other.
    ignored_pairs: Vec<[u32; 2]>,
}

#[derive(Serialize, Deserialize)]
pub(crate) struct SlotV1<T> {
    generation: u32,
    item: Option<T>,
}

/// [`WorldSettings`], field by field.
#[derive(Serialize, Deserialize)]
struct SettingsV1 {
    gravity: [f32; 3],
    substeps: u32,
    max_linear_speed: f32,
    contact_hertz: f32,
    contact_damping_ratio: f32,
    contact_push_speed: f32,
    restitution_threshold: f32,
    speculative_distance: f32,
    sleep_speed: f32,
    sleep_time: f32,
    joint_hertz: f32,
    joint_damping_ratio: f32,
    friction_combine: CombineV1,
    restitution_combine: CombineV1,
}

#[derive(Serialize, Deserialize)]
enum CombineV1 {
    GeometricMean,
    Average,
    Min,
    Max,
    Multiply,
}

/// A shape as its constructor takes it.
#[derive(Serialize, Deserialize, PartialEq)]
enum ShapeV1 {
    Convex(ConvexV1),
    /// Children as [`CompoundChild`] holds them: never compounds, so records do not nest.
    Compound(Vec<ChildV1>),
    Halfspace {
        normal: [f32; 3],
    },
    TriMesh {
        vertices: Vec<[f32; 3]>,
        indices: Vec<[u32; 3]>,
    },
    /// Heights before scaling, row-major, `rows × cols`.
    HeightField {
        cols: u32,
        heights: Vec<f32>,
        scale: [f32; 3],
    },
}

#[derive(Serialize, Deserialize, PartialEq)]
enum ConvexV1 {
    Sphere {
        radius: f32,
    },
    Cuboid {
        half_extents: [f32; 3],
    },
    Capsule {
        radius: f32,
        half_height: f32,
    },
    Cylinder {
        radius: f32,
        half_height: f32,
    },
    /// The hull's vertices: the hull of these points is the same hull.
    ConvexHull {
        points: Vec<[f32; 3]>,
    },
}

#[derive(Serialize, Deserialize, PartialEq)]
struct ChildV1 {
    position: [f32; 3],
    rotation: [f32; 4],
    shape: ConvexV1,
    friction: Option<f32>,
    restitution: Option<f32>,
    rolling_resistance: Option<f32>,
    /// The collider's own sensor flag, groups (memberships, filter), name and user data.
    sensor: Option<bool>,
    collision_groups: Option<(u32, u32)>,
    name: Option<String>,
    user_data: u128,
}

#[derive(Serialize, Deserialize)]
enum BodyTypeV1 {
    Dynamic,
    Static,
    Kinematic,
}

/// A body: what its description gave it and where the steps since have taken it.
#[derive(Serialize, Deserialize)]
struct BodyV1 {
    body_type: BodyTypeV1,
    /// Index in [`WorldV1::shapes`].
    shape: u32,
    /// World position of the centre of mass, m, and the rotation: the origin is derived from
    /// them and the local centre of mass, exactly as the saved world derived it.
    center_of_mass: [f32; 3],
    rotation: [f32; 4],
    linear_velocity: [f32; 3],
    angular_velocity: [f32; 3],
    /// Dynamic bodies: mass (kg), centre of mass (body frame, m) and inertia about it (body
    /// axes, kg·m²) as saved, not recomputed from the shape; zeros otherwise.
    mass: f32,
    local_center_of_mass: [f32; 3],
    inertia: [[f32; 3]; 3],
    friction: f32,
    restitution: f32,
    rolling_resistance: f32,
    linear_damping: f32,
    angular_damping: f32,
    constant_force: [f32; 3],
    constant_force_point: Option<[f32; 3]>,
    constant_torque: [f32; 3],
    /// Force and torque applied since the last step, N and N·m.
    applied_force: [f32; 3],
    applied_torque: [f32; 3],
    can_sleep: bool,
    sleeping: bool,
    /// Seconds the body has been still.
    sleep_time: f32,
    /// The slot of the root of the group it fell asleep with.
    sleep_group: Option<u32>,
    sensor: bool,
    collision_memberships: u32,
    collision_filter: u32,
    contact_force_threshold: f32,
    user_data: u128,
    locked_translation: [bool; 3],
    locked_rotation: [bool; 3],
    /// Kinematic bodies: the pose target of the next step, the path and its clock (s).
    kinematic_target: Option<PoseV1>,
    path: Option<PathV1>,
    path_time: f64,
}

#[derive(Serialize, Deserialize)]
struct PoseV1 {
    position: [f32; 3],
    rotation: [f32; 4],
}

#[derive(Serialize, Deserialize)]
struct PathV1 {
    /// Each keyframe's time (s) and pose.
    points: Vec<(f32, PoseV1)>,
    looping: bool,
}

impl SnapshotV4 {
    /// The snapshot of `world`, and of a scene's `scene` part.
    pub fn of(world: &World, scene: Option<SceneV1>) -> Self {
        let (bodies, _, _) = world.portable_parts();
        let contact_rules = (bodies.slots().enumerate())
            .filter_map(|(slot, (_, body))| {
                let body = body.filter(|body| body.has_contact_rules())?;
                Some(ContactRulesV2 {
                    slot: slot as u32,
                    one_way: body.one_way.map(|direction| direction.to_array()),
                    surface_velocity: body.surface_velocity.to_array(),
                })
            })
            .collect();
        let (world_record, shapes) = WorldV1::of(world);
        let mesh_materials = (0..)
            .zip(&shapes)
            .filter_map(|(index, shape)| MeshMaterialsV3::of(shape, index))
            .collect();
        let (joint_slots, _) = world.portable_parts().1.slots();
        let joint_extras = (0..)
            .zip(joint_slots)
            .filter_map(|(slot, (_, joint))| JointExtrasV4::of(slot, joint?))
            .collect();
        Self {
            world: world_record,
            scene,
            contact_rules,
            mesh_materials,
            joint_extras,
        }
    }

    /// The world of the snapshot, with its meshes' materials and its bodies' contact rules
    /// ([`WorldV1::restore`]).
    pub fn restore_world(self) -> Result<World, String> {
        let mut world = self
            .world
            .restore(&self.mesh_materials, self.joint_extras)?;
        for rules in self.contact_rules {
            let slot = rules.slot as usize;
            world
                .restore_contact_rules(
                    slot,
                    rules.one_way.map(Vec3::from_array),
                    Vec3::from_array(rules.surface_velocity),
                )
                .map_err(|error| format!("body {slot}: {error}"))?;
        }
        Ok(world)
    }
}

impl Snapshot {
    /// The latest version of the snapshot, whatever version it was written in: a version 1
    /// snapshot has no contact rules, neither it nor a version 2 one mesh materials, and none
    /// before version 4 joint extras, or before version 5 couplings.
    pub fn into_latest(self) -> SnapshotV5 {
        let base = match self {
            Self::V1(snapshot) => SnapshotV4 {
                world: snapshot.world,
                scene: snapshot.scene,
                contact_rules: Vec::new(),
                mesh_materials: Vec::new(),
                joint_extras: Vec::new(),
            },
            Self::V2(snapshot) => SnapshotV4 {
                world: snapshot.world,
                scene: snapshot.scene,
                contact_rules: snapshot.contact_rules,
                mesh_materials: Vec::new(),
                joint_extras: Vec::new(),
            },
            Self::V3(snapshot) => SnapshotV4 {
                world: snapshot.world,
                scene: snapshot.scene,
                contact_rules: snapshot.contact_rules,
                mesh_materials: snapshot.mesh_materials,
                joint_extras: Vec::new(),
            },
            Self::V4(snapshot) => snapshot,
            Self::V5(snapshot) => return snapshot,
        };
        SnapshotV5::without_couplings(base)
    }
}

impl WorldV1 {
    /// The record of `world`, and its distinct shapes in the order of its shape records.
    fn of(world: &World) -> (Self, Vec<Shape>) {
        let (bodies, joints, ignored) = world.portable_parts();
        let mut shapes = Vec::new();
        let mut distinct = Vec::new();
        let mut shape_index: HashMap<Vec<u8>, u32> = HashMap::new();
        let body_slots = bodies
            .slots()
            .map(|(generation, body)| SlotV1 {
                generation,
                item: body.map(|body| {
                    let record = shape_record(&body.shape);
                    // Shapes compare by their encoding, a mesh's materials included: equal
                    // records are one shape.
                    let materials = MeshMaterialsV3::of(&body.shape, 0);
                    let key = postcard::to_stdvec(&(&record, materials)).unwrap_or_default();
                    let shape = *shape_index.entry(key).or_insert_with(|| {
                        shapes.push(record);
                        distinct.push(body.shape.clone());
                        shapes.len() as u32 - 1
                    });
                    BodyV1::of(body, shape)
                }),
            })
            .collect();
        let (joint_slots, free_joints) = joints.slots();
        let record = Self {
            identity: bodies.world(),
            settings: SettingsV1::of(world.settings()),
            shapes,
            bodies: body_slots,
            free_bodies: bodies.free_slots().to_vec(),
            joints: joint_slots
                .map(|(generation, joint)| SlotV1 {
                    generation,
                    item: joint.map(JointV1::of),
                })
                .collect(),
            free_joints: free_joints.to_vec(),
            ignored_pairs: ignored
                .pairs()
                .iter()
                .map(|(a, b)| [a.slot() as u32, b.slot() as u32])
                .collect(),
        };
        (record, distinct)
    }

    /// The world of the snapshot, its meshes given `mesh_materials`, its joints
    /// `joint_extras`, its handles those of the saved world; contacts start cold. Describes the
    /// first value refused.
    fn restore(
        self,
        mesh_materials: &[MeshMaterialsV3],
        joint_extras: Vec<JointExtrasV4>,
    ) -> Result<World, String> {
        let mut shapes = (self.shapes.iter().enumerate())
            .map(|(index, shape)| build_shape(shape).map_err(|e| format!("shape {index}: {e}")))
            .collect::<Result<Vec<Shape>, String>>()?;
        for materials in mesh_materials {
            materials.apply(&mut shapes)?;
        }
        let body_slots = (self.bodies.into_iter().enumerate())
            .map(|(slot, entry)| {
                let body = entry
                    .item
                    .map(|body| body.restore(slot, &shapes))
                    .transpose()
                    .map_err(|error| format!("body {slot}: {error}"))?;
                Ok((entry.generation, body))
            })
            .collect::<Result<Vec<_>, String>>()?;
        let bodies = Arena::from_slots(self.identity, body_slots, self.free_bodies)?;
        let handle_at = |slot: u32| {
            bodies
                .at_slot(slot as usize)
                .map(|(index, _)| BodyHandle(index))
                .ok_or_else(|| format!("body slot {slot} is empty"))
        };
        let joint_slots = (self.joints.into_iter().enumerate())
            .map(|(slot, entry)| {
                let joint = entry
                    .item
                    .map(|joint| joint.restore(handle_at))
                    .transpose()
                    .map_err(|error| format!("joint {slot}: {error}"))?;
                Ok((entry.generation, joint))
            })
            .collect::<Result<Vec<_>, String>>()?;
        let mut joint_slots = joint_slots;
        for extras in joint_extras {
            let slot = extras.slot;
            match joint_slots.get_mut(slot as usize) {
                Some((_, Some(joint))) => extras.apply(joint),
                _ => return Err(format!("joint slot {slot} is empty")),
            }
        }
        let joints = JointSet::restored(self.identity, joint_slots, self.free_joints)?;
        let ignored = (self.ignored_pairs.iter())
            .map(|&[a, b]| Ok((handle_at(a)?, handle_at(b)?)))
            .collect::<Result<Vec<_>, String>>()?;
        World::restored(self.settings.restore(), bodies, joints, &ignored)
    }
}

impl SettingsV1 {
    fn of(settings: &WorldSettings) -> Self {
        Self {
            gravity: settings.gravity.to_array(),
            substeps: settings.substeps,
            max_linear_speed: settings.max_linear_speed,
            contact_hertz: settings.contact_hertz,
            contact_damping_ratio: settings.contact_damping_ratio,
            contact_push_speed: settings.contact_push_speed,
            restitution_threshold: settings.restitution_threshold,
            speculative_distance: settings.speculative_distance,
            sleep_speed: settings.sleep_speed,
            sleep_time: settings.sleep_time,
            joint_hertz: settings.joint_hertz,
            joint_damping_ratio: settings.joint_damping_ratio,
            friction_combine: CombineV1::of(settings.friction_combine),
            restitution_combine: CombineV1::of(settings.restitution_combine),
        }
    }

    fn restore(&self) -> WorldSettings {
        WorldSettings {
            gravity: Vec3::from_array(self.gravity),
            substeps: self.substeps,
            max_linear_speed: self.max_linear_speed,
            contact_hertz: self.contact_hertz,
            contact_damping_ratio: self.contact_damping_ratio,
            contact_push_speed: self.contact_push_speed,
            restitution_threshold: self.restitution_threshold,
            speculative_distance: self.speculative_distance,
            sleep_speed: self.sleep_speed,
            sleep_time: self.sleep_time,
            joint_hertz: self.joint_hertz,
            joint_damping_ratio: self.joint_damping_ratio,
            friction_combine: self.friction_combine.restore(),
            restitution_combine: self.restitution_combine.restore(),
        }
    }
}

impl CombineV1 {
    fn of(rule: CombineRule) -> Self {
        match rule {
            CombineRule::GeometricMean => Self::GeometricMean,
            CombineRule::Average => Self::Average,
            CombineRule::Min => Self::Min,
            CombineRule::Max => Self::Max,
            CombineRule::Multiply => Self::Multiply,
        }
    }

    fn restore(&self) -> CombineRule {
        match self {
            Self::GeometricMean => CombineRule::GeometricMean,
            Self::Average => CombineRule::Average,
            Self::Min => CombineRule::Min,
            Self::Max => CombineRule::Max,
            Self::Multiply => CombineRule::Multiply,
        }
    }
}

fn shape_record(shape: &Shape) -> ShapeV1 {
    let convex = match shape {
        Shape::Sphere(sphere) => ConvexV1::Sphere {
            radius: sphere.radius(),
        },
        Shape::Cuboid(cuboid) => ConvexV1::Cuboid {
            half_extents: cuboid.half_extents().to_array(),
        },
        Shape::Capsule(capsule) => ConvexV1::Capsule {
            radius: capsule.radius(),
            half_height: capsule.half_height(),
        },
        Shape::Cylinder(cylinder) => ConvexV1::Cylinder {
            radius: cylinder.radius(),
            half_height: cylinder.half_height(),
        },
        Shape::ConvexHull(hull) => ConvexV1::ConvexHull {
            points: hull.vertices().iter().map(|v| v.to_array()).collect(),
        },
        Shape::Compound(compound) => {
            // A compound's children are convex (`Compound::new` refuses others): none is left
            // out.
            let children = (compound.children().iter())
                .filter_map(|child| match shape_record(&child.shape) {
                    ShapeV1::Convex(shape) => Some(ChildV1 {
                        position: child.pose.position.to_array(),
                        rotation: child.pose.rotation.to_array(),
                        shape,
                        friction: child.friction,
                        restitution: child.restitution,
                        rolling_resistance: child.rolling_resistance,
                        sensor: child.sensor,
                        collision_groups: child
                            .collision_groups
                            .map(|groups| (groups.memberships, groups.filter)),
                        name: child.name.clone(),
                        user_data: child.user_data,
                    }),
                    _ => None,
                })
                .collect();
            return ShapeV1::Compound(children);
        }
        Shape::Halfspace(halfspace) => {
            return ShapeV1::Halfspace {
                normal: halfspace.normal().to_array(),
            }
        }
        Shape::TriMesh(mesh) => {
            return ShapeV1::TriMesh {
                vertices: mesh.vertices().iter().map(|v| v.to_array()).collect(),
                indices: mesh.indices().to_vec(),
            }
        }
        Shape::HeightField(field) => {
            return ShapeV1::HeightField {
                cols: field.cols() as u32,
                heights: field.heights().to_vec(),
                scale: field.scale().to_array(),
            }
        }
    };
    ShapeV1::Convex(convex)
}

/// The shape of a record, through the checking constructors.
fn build_shape(record: &ShapeV1) -> crate::Result<Shape> {
    match record {
        ShapeV1::Convex(convex) => build_convex(convex),
        ShapeV1::Compound(children) => {
            let children = (children.iter())
                .map(|child| {
                    Ok(CompoundChild {
                        pose: Pose::new(
                            Vec3::from_array(child.position),
                            Quat::from_array(child.rotation),
                        ),
                        shape: build_convex(&child.shape)?,
                        friction: child.friction,
                        restitution: child.restitution,
                        rolling_resistance: child.rolling_resistance,
                        sensor: child.sensor,
                        collision_groups: child.collision_groups.map(|(memberships, filter)| {
                            InteractionGroups::new(memberships, filter)
                        }),
                        name: child.name.clone(),
                        user_data: child.user_data,
                    })
                })
                .collect::<crate::Result<Vec<_>>>()?;
            Shape::compound(children)
        }
        ShapeV1::Halfspace { normal } => Shape::halfspace(Vec3::from_array(*normal)),
        ShapeV1::TriMesh { vertices, indices } => Shape::trimesh(
            vertices.iter().copied().map(Vec3::from_array).collect(),
            indices,
        ),
        ShapeV1::HeightField {
            cols,
            heights,
            scale,
        } => {
            // Rows of `cols` heights; a count that does not divide them leaves a short row,
            // which the constructor refuses.
            let rows: Vec<Vec<f32>> = heights
                .chunks((*cols as usize).max(1))
                .map(<[f32]>::to_vec)
                .collect();
            Shape::heightfield(&rows, Vec3::from_array(*scale))
        }
    }
}

fn build_convex(record: &ConvexV1) -> crate::Result<Shape> {
    match *record {
        ConvexV1::Sphere { radius } => Shape::sphere(radius),
        ConvexV1::Cuboid { half_extents } => Shape::cuboid(Vec3::from_array(half_extents)),
        ConvexV1::Capsule {
            radius,
            half_height,
        } => Shape::capsule(radius, half_height),
        ConvexV1::Cylinder {
            radius,
            half_height,
        } => Shape::cylinder(radius, half_height),
        ConvexV1::ConvexHull { ref points } => {
            let points: Vec<Vec3> = points.iter().copied().map(Vec3::from_array).collect();
            Shape::convex_hull(&points)
        }
    }
}

impl PoseV1 {
    fn of(pose: Pose) -> Self {
        Self {
            position: pose.position.to_array(),
            rotation: pose.rotation.to_array(),
        }
    }

    fn restore(&self) -> Pose {
        Pose::new(
            Vec3::from_array(self.position),
            Quat::from_array(self.rotation),
        )
    }
}

impl BodyV1 {
    fn of(body: &RigidBody, shape: u32) -> Self {
        let groups = body.collision_groups;
        Self {
            body_type: match body.body_type {
                BodyType::Dynamic => BodyTypeV1::Dynamic,
                BodyType::Static => BodyTypeV1::Static,
                BodyType::Kinematic => BodyTypeV1::Kinematic,
            },
            shape,
            center_of_mass: body.center_of_mass.to_array(),
            rotation: body.rotation.to_array(),
            linear_velocity: body.linear_velocity.to_array(),
            angular_velocity: body.angular_velocity.to_array(),
            mass: body.mass,
            local_center_of_mass: body.local_center_of_mass.to_array(),
            inertia: body.local_inertia.to_cols_array_2d(),
            friction: body.friction,
            restitution: body.restitution,
            rolling_resistance: body.rolling_resistance,
            linear_damping: body.linear_damping,
            angular_damping: body.angular_damping,
            constant_force: body.constant_force.to_array(),
            constant_force_point: body.constant_force_point.map(|point| point.to_array()),
            constant_torque: body.constant_torque.to_array(),
            applied_force: body.force.to_array(),
            applied_torque: body.torque.to_array(),
            can_sleep: body.can_sleep,
            sleeping: body.sleeping,
            sleep_time: body.sleep_time,
            sleep_group: body.sleep_group.map(|root| root as u32),
            sensor: body.sensor,
            collision_memberships: groups.memberships,
            collision_filter: groups.filter,
            contact_force_threshold: body.contact_force_threshold,
            user_data: body.user_data,
            locked_translation: body.locked_axes.translation,
            locked_rotation: body.locked_axes.rotation,
            kinematic_target: body.kinematic_target.map(PoseV1::of),
            path: body.path.as_ref().map(|path| PathV1 {
                points: (path.points.iter())
                    .map(|point| {
                        let pose = Pose::new(point.position, point.rotation);
                        (point.time, PoseV1::of(pose))
                    })
                    .collect(),
                looping: path.looping,
            }),
            path_time: body.path_time,
        }
    }

    /// The body of the record in `slot`, with its shape from `shapes`: every value checked as
    /// [`BodyDesc`] checks it, then the state the steps gave it put back.
    fn restore(self, slot: usize, shapes: &[Shape]) -> Result<RigidBody, String> {
        let shape = shapes
            .get(self.shape as usize)
            .cloned()
            .ok_or("its shape is missing")?;
        let body_type = match self.body_type {
            BodyTypeV1::Dynamic => BodyType::Dynamic,
            BodyTypeV1::Static => BodyType::Static,
            BodyTypeV1::Kinematic => BodyType::Kinematic,
        };
        let center_of_mass = Vec3::from_array(self.center_of_mass);
        let rotation = Quat::from_array(self.rotation);
        let linear_velocity = Vec3::from_array(self.linear_velocity);
        let angular_velocity = Vec3::from_array(self.angular_velocity);
        let mut desc = BodyDesc::new(body_type, shape)
            .rotation(rotation)
            .friction(self.friction)
            .restitution(self.restitution)
            .rolling_resistance(self.rolling_resistance)
            .constant_torque(Vec3::from_array(self.constant_torque))
            .damping(self.linear_damping, self.angular_damping)
            .can_sleep(self.can_sleep)
            .locked_axes(LockedAxes {
                translation: self.locked_translation,
                rotation: self.locked_rotation,
            })
            .sensor(self.sensor)
            .collision_groups(InteractionGroups::new(
                self.collision_memberships,
                self.collision_filter,
            ))
            .contact_force_threshold(self.contact_force_threshold)
            .user_data(self.user_data);
        desc.constant_force = Vec3::from_array(self.constant_force);
        desc.constant_force_point = self.constant_force_point.map(Vec3::from_array);
        let properties = (body_type == BodyType::Dynamic).then(|| MassProperties {
            mass: self.mass,
            center_of_mass: Vec3::from_array(self.local_center_of_mass),
            inertia: Mat3::from_cols_array_2d(&self.inertia),
        });
        desc.mass = properties.map(|properties| properties.mass);
        check_position("center_of_mass", center_of_mass).map_err(|error| error.to_string())?;
        if !rotation.is_normalized() {
            return Err("its rotation is not normalised".to_owned());
        }
        let mut body = RigidBody::from_desc(desc).map_err(|error| error.to_string())?;
        body.restore_mass_and_pose(properties, center_of_mass, rotation)?;
        if body_type != BodyType::Static {
            // As saved, locked axes held then; checked with the world, which allows the rounding
            // by which the step's speed limits may leave a velocity above them.
            body.linear_velocity = linear_velocity;
            body.angular_velocity = angular_velocity;
        }
        body.force = Vec3::from_array(self.applied_force);
        body.torque = Vec3::from_array(self.applied_torque);
        body.sleeping = self.sleeping;
        body.sleep_time = self.sleep_time;
        // A body asleep is in a group; one without is a group of its own.
        body.sleep_group = match (self.sleep_group, self.sleeping) {
            (Some(root), _) => Some(root as usize),
            (None, true) => Some(slot),
            (None, false) => None,
        };
        body.kinematic_target = self.kinematic_target.as_ref().map(PoseV1::restore);
        body.path = match self.path {
            Some(path) => {
                let points = (path.points.iter())
                    .map(|(time, pose)| {
                        let pose = pose.restore();
                        PathPoint::new(*time, pose.position, pose.rotation)
                    })
                    .collect();
                let path = KinematicPath::new(points).looping(path.looping);
                Some(path.checked().map_err(|error| error.to_string())?)
            }
            None => None,
        };
        body.path_time = self.path_time;
        Ok(body)
    }
}
