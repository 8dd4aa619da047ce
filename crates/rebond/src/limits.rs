//! The engine's numeric limits. A value past one is refused where it enters the engine (an
//! [`Error`](crate::Error) naming the field, [`ErrorKind::TooLarge`](crate::ErrorKind::TooLarge)
//! or [`ErrorKind::OutOfRange`](crate::ErrorKind::OutOfRange)); a value within them is simulated
//! with every quantity finite and within the 32-bit float precision each limit states. The
//! engine's own tests run at the limits (`tests/limits.rs`). `docs/limits.md` explains each one.

/// Largest size of a shape, m: a radius, half extent or half height, the distance of a hull
/// point, mesh vertex or compound child from its body's origin, a heightfield's scaled height or
/// extent. A static box this large still holds a ball, box, capsule, cylinder or hull at rest.
pub const MAX_SIZE: f32 = 1.0e5;

/// Smallest radius, half extent or half height of a shape, m.
pub const MIN_SIZE: f32 = 1.0e-3;

/// Largest coordinate of a body's position or a joint's anchor, m. Positions are resolved to
/// about 6e-8 of their distance from the origin: 0.6 mm at this distance.
pub const MAX_COORDINATE: f32 = 1.0e4;

/// Largest speed of a body's centre of mass given to the engine, m/s, and largest
/// [`WorldSettings::max_linear_speed`](crate::WorldSettings::max_linear_speed).
pub const MAX_SPEED: f32 = 1.0e4;

/// Largest angular speed given to the engine, rad/s. The step holds every body to a quarter
/// turn per substep on top of this.
pub const MAX_ANGULAR_SPEED: f32 = 1.0e4;

/// Smallest mass of a dynamic body, kg, given or from its density.
pub const MIN_MASS: f32 = 1.0e-6;

/// Largest mass of a dynamic body, kg, given or from its density. With [`MIN_MASS`] it bounds
/// the mass ratio of any two bodies to 1e15; past about 1e7 the lighter body's `1/m` swallows
/// the heavier one's in 32-bit floats, which then moves as if it were static.
pub const MAX_MASS: f32 = 1.0e9;

/// Largest spread of a dynamic body's principal moments of inertia, largest over smallest. A
/// rod 4 m long and 2 cm thick is within it; a longer or thinner body has its moments raised
/// (each by `tr I / 100,000`) until it is: with a wider spread the world inverse inertia
/// `R I⁻¹ Rᵀ` is lost to `f32` rounding in its smallest direction, and contacts on the body feed
/// on themselves until they overflow. Such a body turns about its long axis a little more slowly
/// than its shape says.
pub const MAX_INERTIA_RATIO: f32 = 1.0e5;

/// Largest force, N, torque, N·m, or impulse, N·s, applied to a body.
pub const MAX_FORCE: f32 = 1.0e12;

/// Largest impulse the solver can have accumulated on one constraint in a step, N·s: twice the
/// momentum of the heaviest body at the top speed, the most two bodies within the limits
/// exchange. A saved world holding more was not written by a step ([`crate::state`]).
pub(crate) const MAX_SOLVER_IMPULSE: f32 = 2.0 * MAX_MASS * MAX_SPEED;

/// Largest gravity, m/s² (about 100 g).
pub const MAX_GRAVITY: f32 = 1.0e3;

/// Shortest step, s. A substep moves a body by `h v`, which is lost to rounding where it is
/// under half the resolution of its position: shorter steps would freeze slow bodies.
pub const MIN_TIMESTEP: f32 = 1.0e-4;

/// Longest step, s: 10 steps per second.
pub const MAX_TIMESTEP: f32 = 0.1;
