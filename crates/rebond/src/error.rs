//! Errors returned for invalid user input. The engine never panics on what a user gives it.

use std::fmt;

use crate::limits::{MAX_COORDINATE, MAX_SIZE, MIN_SIZE};

/// What is wrong with a value.
#[derive(Debug, Clone, PartialEq)]
pub enum ErrorKind {
    /// The value is NaN or infinite.
    NotFinite,
    /// The value must be strictly positive (a size, a mass, a time step).
    NotPositive(f32),
    /// The value must not be negative (friction, damping).
    Negative(f32),
    /// The value lies outside `[min, max]`.
    OutOfRange { value: f32, min: f32, max: f32 },
    /// A rotation quaternion with zero length.
    ZeroQuaternion,
    /// A vector that must have a length (a plane normal) is zero.
    ZeroVector,
    /// A convex hull could not be built: too few points, or all on one plane or line.
    DegenerateHull(&'static str),
    /// A compound shape with no children, or with a child that is itself a compound or a halfspace.
    InvalidCompound(&'static str),
    /// A halfspace on a dynamic body: it has no finite mass.
    HalfspaceOnDynamicBody,
    /// A triangle mesh or heightfield on a dynamic body: it has no volume or mass.
    MeshOnDynamicBody,
    /// A mesh index that names no vertex.
    IndexOutOfRange { index: u32, len: usize },
    /// A triangle mesh with no triangle of positive area.
    EmptyMesh,
    /// A mesh triangle's material index that names no material of the mesh's table.
    MaterialOutOfRange { index: u32, len: usize },
    /// A list that must give one value per item (a material per triangle, a control per actuator)
    /// of another length.
    WrongCount { expected: usize, got: usize },
    /// Heightfield rows that are too few (fewer than 2), too short (fewer than 2 samples) or of
    /// unequal lengths.
    InvalidHeightField,
    /// The body's mass would not be positive and finite.
    InvalidMass,
    /// A shape so small or so large that its mass or inertia cannot be represented in 32-bit
    /// floats, whatever the density.
    UnrepresentableSize,
    /// A handle to a body that was removed, or that never belonged to this world.
    StaleHandle,
    /// A handle to a joint that was removed, or that never belonged to this world.
    StaleJointHandle,
    /// A handle to a coupling that was removed, or that never belonged to this world.
    StaleCouplingHandle,
    /// A required value is absent (a revolute or prismatic joint's axis).
    Missing,
    /// A field set on a joint type it does not belong to (the type's name).
    NotForJointType(&'static str),
    /// A joint joining a body to itself.
    JointToItself,
    /// A motor on a generic joint's axis that is locked.
    LockedAxis,
    /// `[min, max]` limits with `min > max`.
    InvertedLimits { min: f32, max: f32 },
    /// A vector's length, or a scalar's magnitude, past the engine's limit (see
    /// [`limits`](crate::limits)); for positions, the largest coordinate.
    TooLarge { value: f32, max: f32 },
    /// A pose target or path given to a body that is not kinematic.
    NotKinematic,
    /// A value of a sequence (a path's times) not greater than the one before it.
    NotIncreasing { value: f32, previous: f32 },
    /// A shape that must be convex and bounded (a character's) is a halfspace, a triangle mesh
    /// or a heightfield.
    NotConvex,
    /// An inertia tensor that is not symmetric and positive definite (its principal moments
    /// must all be positive).
    NotPositiveDefinite,
    /// A field that cannot be given together with the named one.
    ExcludedBy(&'static str),
}

/// An invalid input, with the place it was found.
///
/// `field` is a path relative to the call that failed, such as `radius` or
/// `shape.children[1].shape.half_extents`; callers prefix their own context with [`Error::within`].
#[derive(Debug, Clone, PartialEq)]
pub struct Error {
    /// Where the bad value is, as a dotted path; empty when the error concerns the whole call.
    pub field: String,
    /// What is wrong with it.
    pub kind: ErrorKind,
}

/// Result type of the engine's fallible calls.
pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// An error about the value at `field`.
    pub fn new(field: impl Into<String>, kind: ErrorKind) -> Self {
        Self {
            field: field.into(),
            kind,
        }
    }

    /// The same error, seen from one level up: `radius` within `shape` becomes `shape.radius`.
    #[must_use]
    pub fn within(mut self, prefix: &str) -> Self {
        self.field = match (prefix.is_empty(), self.field.is_empty()) {
            (true, _) => self.field,
            (false, true) => prefix.to_owned(),
            (false, false) if self.field.starts_with('[') => format!("{prefix}{}", self.field),
            (false, false) => format!("{prefix}.{}", self.field),
        };
        self
    }
}

impl fmt::Display for ErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite => write!(f, "must be finite"),
            Self::NotPositive(value) => write!(f, "must be positive, got {value}"),
            Self::Negative(value) => write!(f, "must not be negative, got {value}"),
            Self::OutOfRange { value, min, max } => {
                write!(f, "must lie between {min} and {max}, got {value}")
            }
            Self::ZeroQuaternion => write!(f, "quaternion has zero length"),
            Self::ZeroVector => write!(f, "vector has zero length"),
            Self::DegenerateHull(reason) => write!(f, "degenerate convex hull: {reason}"),
            Self::InvalidCompound(reason) => write!(f, "invalid compound: {reason}"),
            Self::HalfspaceOnDynamicBody => {
                write!(
                    f,
                    "a halfspace is only allowed on static or kinematic bodies"
                )
            }
            Self::MeshOnDynamicBody => write!(
                f,
                "a trimesh or heightfield is only allowed on static or kinematic bodies"
            ),
            Self::IndexOutOfRange { index, len } => {
                write!(f, "index {index} is out of range for {len} vertices")
            }
            Self::EmptyMesh => write!(f, "the mesh has no triangle of positive area"),
            Self::MaterialOutOfRange { index, len } => {
                write!(f, "material {index} is out of range for {len} materials")
            }
            Self::WrongCount { expected, got } => {
                write!(
                    f,
                    "expected {expected} values (one per item: triangle, actuator), got {got}"
                )
            }
            Self::InvalidHeightField => write!(
                f,
                "heightfield rows must be at least 2, each of the same length, at least 2"
            ),
            Self::InvalidMass => write!(f, "mass of a dynamic body must be positive and finite"),
            Self::UnrepresentableSize => write!(
                f,
                "too small or too large: the mass and inertia of a dynamic body of this size \
                 cannot be represented in 32-bit floats"
            ),
            Self::StaleHandle => write!(f, "body handle is stale or unknown"),
            Self::StaleJointHandle => write!(f, "joint handle is stale or unknown"),
            Self::StaleCouplingHandle => write!(f, "coupling handle is stale or unknown"),
            Self::Missing => write!(f, "required"),
            Self::NotForJointType(name) => write!(f, "does not apply to a {name} joint"),
            Self::JointToItself => write!(f, "a joint cannot join a body to itself"),
            Self::LockedAxis => write!(f, "a motor needs a free or limited axis, not a locked one"),
            Self::InvertedLimits { min, max } => {
                write!(f, "min must not exceed max, got [{min}, {max}]")
            }
            Self::TooLarge { value, max } => {
                write!(
                    f,
                    "must not exceed {max:e} (the engine's limit), got {value:e}"
                )
            }
            Self::NotKinematic => write!(f, "only a kinematic body follows a pose target or path"),
            Self::NotConvex => write!(
                f,
                "must be a convex shape or a compound of them, not a halfspace, trimesh or \
                 heightfield"
            ),
            Self::NotPositiveDefinite => write!(
                f,
                "inertia must be symmetric with positive principal moments (positive definite)"
            ),
            Self::ExcludedBy(other) => write!(f, "cannot be given together with `{other}`"),
            Self::NotIncreasing { value, previous } => {
                write!(
                    f,
                    "must be greater than the one before, {previous}, got {value}"
                )
            }
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.field.is_empty() {
            write!(f, "{}", self.kind)
        } else {
            write!(f, "{}: {}", self.field, self.kind)
        }
    }
}

impl std::error::Error for Error {}

/// Runs `check` with no field name, and again with `field()` only when it fails: the checks of a
/// long list (a mesh's vertices, a heightfield's samples) format no names while the values pass.
pub(crate) fn check_named<T>(
    check: impl Fn(&str) -> Result<T>,
    field: impl FnOnce() -> String,
) -> Result<T> {
    check("").or_else(|_| check(&field()))
}

/// Checks that `value` is finite.
pub(crate) fn check_finite(field: &str, value: f32) -> Result<f32> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::new(field, ErrorKind::NotFinite))
    }
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn check_positive(field: &str, value: f32) -> Result<f32> {
    check_finite(field, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(Error::new(field, ErrorKind::NotPositive(value)))
    }
}

/// Checks that `value` is finite and not negative.
pub(crate) fn check_non_negative(field: &str, value: f32) -> Result<f32> {
    check_finite(field, value)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::new(field, ErrorKind::Negative(value)))
    }
}

/// Checks that `value` is zero or more, infinity allowed (for limits that may be absent), NaN not.
pub(crate) fn check_non_negative_or_infinite(field: &str, value: f32) -> Result<f32> {
    if value.is_nan() {
        Err(Error::new(field, ErrorKind::NotFinite))
    } else if value < 0.0 {
        Err(Error::new(field, ErrorKind::Negative(value)))
    } else {
        Ok(value)
    }
}

/// Checks that `value` is finite and lies in `[min, max]`.
pub(crate) fn check_range(field: &str, value: f32, min: f32, max: f32) -> Result<f32> {
    check_finite(field, value)?;
    if (min..=max).contains(&value) {
        Ok(value)
    } else {
        Err(Error::new(field, ErrorKind::OutOfRange { value, min, max }))
    }
}

/// Checks that a count lies in `[min, max]`.
pub(crate) fn check_count(field: &str, value: u32, min: u32, max: u32) -> Result<u32> {
    if (min..=max).contains(&value) {
        Ok(value)
    } else {
        Err(Error::new(
            field,
            ErrorKind::OutOfRange {
                value: value as f32,
                min: min as f32,
                max: max as f32,
            },
        ))
    }
}

/// Checks that every component of `vector` is finite.
pub(crate) fn check_finite_vector(field: &str, vector: glam::Vec3) -> Result<glam::Vec3> {
    if vector.is_finite() {
        Ok(vector)
    } else {
        Err(Error::new(field, ErrorKind::NotFinite))
    }
}

/// `direction` normalised; a non-finite one is [`ErrorKind::NotFinite`], one too short to
/// normalise [`ErrorKind::ZeroVector`].
pub(crate) fn check_direction(field: &str, direction: glam::Vec3) -> Result<glam::Vec3> {
    check_finite_vector(field, direction)?
        .try_normalize()
        .ok_or_else(|| Error::new(field, ErrorKind::ZeroVector))
}

/// Checks that a size (radius, half extent, half height) is finite and within
/// `[MIN_SIZE, MAX_SIZE]`.
pub(crate) fn check_size(field: &str, value: f32) -> Result<f32> {
    check_positive(field, value)?;
    check_range(field, value, MIN_SIZE, MAX_SIZE)
}

/// Checks that `vector` is finite and at most `max` long; the length is taken in `f64`, so a
/// vector too long to square in `f32` is reported, not overflowed.
pub(crate) fn check_length(field: &str, vector: glam::Vec3, max: f32) -> Result<glam::Vec3> {
    check_finite_vector(field, vector)?;
    let length = vector.as_dvec3().length();
    if length <= f64::from(max) {
        Ok(vector)
    } else {
        Err(Error::new(
            field,
            ErrorKind::TooLarge {
                value: length as f32,
                max,
            },
        ))
    }
}

/// Checks that every coordinate of a position is finite and at most [`MAX_COORDINATE`] in
/// magnitude.
pub(crate) fn check_position(field: &str, position: glam::Vec3) -> Result<glam::Vec3> {
    check_finite_vector(field, position)?;
    let largest = position.abs().max_element();
    if largest <= MAX_COORDINATE {
        Ok(position)
    } else {
        Err(Error::new(
            field,
            ErrorKind::TooLarge {
                value: largest,
                max: MAX_COORDINATE,
            },
        ))
    }
}
