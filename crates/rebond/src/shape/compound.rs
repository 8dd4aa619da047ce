//! Compound: several convex shapes rigidly attached to one body, each a collider of its own.
//!
//! A body's colliders are numbered by a collider index: 0 for a body whose shape is not a
//! compound, the child's index in [`Compound::children`] otherwise. A child may be a sensor, have
//! collision groups of its own, a name and user data; events and query hits name it by index.

use crate::error::{check_length, check_non_negative, check_range, Error, ErrorKind, Result};
use crate::filter::InteractionGroups;
use crate::limits::MAX_SIZE;
use crate::mass::MassProperties;
use crate::math::{normalize_rotation, Aabb, Pose, Vec3};

use super::Shape;

/// One child of a compound, a collider of the body: a convex shape, its pose in the body frame,
/// and optionally a surface material, a sensor flag, collision groups, a name and user data of
/// its own.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CompoundChild {
    /// Where the child sits in the body frame.
    pub pose: Pose,
    /// The child's shape; never a compound or a halfspace.
    pub shape: Shape,
    /// The child's Coulomb friction coefficient, ≥ 0; `None` (the default) for the body's.
    pub friction: Option<f32>,
    /// The child's coefficient of restitution, 0 to 1; `None` (the default) for the body's.
    pub restitution: Option<f32>,
    /// The child's rolling resistance coefficient, ≥ 0; `None` (the default) for the body's.
    /// Its lever is the child's own rolling radius ([`Shape::rolling_radius`]).
    pub rolling_resistance: Option<f32>,
    /// Whether the child is a sensor: it reports the colliders of other bodies entering and
    /// leaving it ([`SensorEvent`](crate::SensorEvent)) and pushes nothing. `None` (the default)
    /// for the body's flag; a child of a sensor body is always a sensor.
    pub sensor: Option<bool>,
    /// The child's collision groups; `None` (the default) for the body's. Two bodies whose groups
    /// interact then meet collider by collider: two colliders touch (or a sensor child sees a
    /// collider) when their own groups interact too.
    pub collision_groups: Option<InteractionGroups>,
    /// A label, unique within the body; `None` (the default) for none.
    pub name: Option<String>,
    /// Free for the user (an entity id, say); default 0. The engine never reads it.
    pub user_data: u128,
}

impl CompoundChild {
    /// `shape` placed at `pose` in the body frame, with the body's material
    /// ([`Compound::new`] checks every value).
    pub fn new(shape: Shape, pose: Pose) -> Self {
        Self {
            pose,
            shape,
            friction: None,
            restitution: None,
            rolling_resistance: None,
            sensor: None,
            collision_groups: None,
            name: None,
            user_data: 0,
        }
    }

    /// Gives the child a friction coefficient of its own.
    pub fn friction(mut self, friction: f32) -> Self {
        self.friction = Some(friction);
        self
    }

    /// Gives the child a restitution of its own.
    pub fn restitution(mut self, restitution: f32) -> Self {
        self.restitution = Some(restitution);
        self
    }

    /// Gives the child a rolling resistance coefficient of its own.
    pub fn rolling_resistance(mut self, rolling_resistance: f32) -> Self {
        self.rolling_resistance = Some(rolling_resistance);
        self
    }

    /// Makes the child a sensor (`true`) or a solid collider (`false`), whatever the body's flag
    /// (a child of a sensor body stays a sensor).
    pub fn sensor(mut self, sensor: bool) -> Self {
        self.sensor = Some(sensor);
        self
    }

    /// Gives the child collision groups of its own.
    pub fn collision_groups(mut self, groups: InteractionGroups) -> Self {
        self.collision_groups = Some(groups);
        self
    }

    /// Names the child (unique within the body).
    pub fn name(mut self, name: impl Into<String>) -> Self {
        self.name = Some(name.into());
        self
    }

    /// Sets the child's user data.
    pub fn user_data(mut self, data: u128) -> Self {
        self.user_data = data;
        self
    }
}

/// A rigid union of convex children.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Compound {
    children: Vec<CompoundChild>,
}

impl Compound {
    /// A compound of at least one child. Child poses must be finite (their rotations are
    /// normalised here), their materials in range; a child may not be a compound or a
    /// halfspace; names are not empty and unique. Errors name the field as `children[i].position`,
    /// `children[i].rotation`, `children[i].friction`, `children[i].restitution`,
    /// `children[i].rolling_resistance`, `children[i].shape` or `children[i].name`.
    pub fn new(mut children: Vec<CompoundChild>) -> Result<Self> {
        if children.is_empty() {
            return Err(Error::new(
                "children",
                ErrorKind::InvalidCompound("a compound needs at least one child"),
            ));
        }
        for (index, child) in children.iter_mut().enumerate() {
            let place = format!("children[{index}]");
            check_length("position", child.pose.position, MAX_SIZE)
                .map_err(|error| error.within(&place))?;
            child.pose.rotation = normalize_rotation("rotation", child.pose.rotation)
                .map_err(|error| error.within(&place))?;
            if let Some(friction) = child.friction {
                check_non_negative("friction", friction).map_err(|error| error.within(&place))?;
            }
            if let Some(restitution) = child.restitution {
                check_range("restitution", restitution, 0.0, 1.0)
                    .map_err(|error| error.within(&place))?;
            }
            if let Some(resistance) = child.rolling_resistance {
                check_non_negative("rolling_resistance", resistance)
                    .map_err(|error| error.within(&place))?;
            }
            let reason = match child.shape {
                Shape::Compound(_) => Some("a child may not be a compound"),
                Shape::Halfspace(_) => Some("a child may not be a halfspace"),
                Shape::TriMesh(_) | Shape::HeightField(_) => {
                    Some("a child may not be a trimesh or heightfield")
                }
                _ => None,
            };
            if let Some(reason) = reason {
                return Err(Error::new(
                    format!("{place}.shape"),
                    ErrorKind::InvalidCompound(reason),
                ));
            }
        }
        for (index, child) in children.iter().enumerate() {
            let Some(name) = &child.name else {
                continue;
            };
            let reason = if name.is_empty() {
                "a child's name may not be empty"
            } else if children[..index]
                .iter()
                .any(|earlier| earlier.name.as_ref() == Some(name))
            {
                "two children of a compound share a name"
            } else {
                continue;
            };
            return Err(Error::new(
                format!("children[{index}].name"),
                ErrorKind::InvalidCompound(reason),
            ));
        }
        Ok(Self { children })
    }

    /// The children, in the order given.
    pub fn children(&self) -> &[CompoundChild] {
        &self.children
    }

    /// The index of the child named `name`, if any.
    pub fn child_index(&self, name: &str) -> Option<u32> {
        (0..)
            .zip(&self.children)
            .find_map(|(index, child)| (child.name.as_deref() == Some(name)).then_some(index))
    }

    /// The children's mass properties moved into the body frame and combined by the
    /// parallel-axis theorem.
    pub fn mass_properties(&self, density: f32) -> MassProperties {
        self.children
            .iter()
            .filter_map(|child| {
                child
                    .shape
                    .mass_properties(density)
                    .map(|properties| properties.transformed(&child.pose))
            })
            .fold(MassProperties::ZERO, |total, part| total.combine(&part))
    }

    /// Union of the children's bounding boxes.
    pub fn aabb(&self, pose: &Pose) -> Aabb {
        let mut children = self.children.iter();
        let first = children
            .next()
            .map(|child| child.shape.aabb(&pose.mul_pose(&child.pose)));
        children.fold(
            first.unwrap_or(Aabb::new(pose.position, pose.position)),
            |bounds, child| bounds.union(&child.shape.aabb(&pose.mul_pose(&child.pose))),
        )
    }

    /// The farthest of the children's support points along `d`.
    pub fn support(&self, direction: Vec3) -> Vec3 {
        let mut best = Vec3::ZERO;
        let mut best_distance = f32::NEG_INFINITY;
        for child in &self.children {
            let local_direction = child.pose.inverse_transform_vector(direction);
            if let Some(point) = child.shape.support(local_direction) {
                let point = child.pose.transform_point(point);
                let distance = point.dot(direction);
                if distance > best_distance {
                    best_distance = distance;
                    best = point;
                }
            }
        }
        best
    }
}
