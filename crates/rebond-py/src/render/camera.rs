//! The pinhole camera of `World.render`: where it is, what it looks at, its vertical field of
//! view and which way is up, and the default that frames the bodies.
//!
//! A point `p` is seen at camera coordinates `x = (p - position)·right`, `y = (p - position)·up'`,
//! `z = (p - position)·forward`, with `forward` the unit vector from `position` to `target`,
//! `right = normalize(forward × up)` and `up' = right × forward`; it lands on the picture at
//! column `width/2 + f x/z` and row `height/2 - f y/z` (pixels from the top-left corner, pixel
//! `(i, j)` covering `[i, i+1) × [j, j+1)`), where `f = (height/2) / tan(fov/2)`.

use rebond::{Aabb, Quat, Vec3, World};

/// Vertical field of view when none is given, degrees.
const DEFAULT_FOV_DEGREES: f32 = 45.0;
/// Angle about the up axis of the default direction from the target to the camera, radians
/// (30°): the camera is on the front (+Z for +Y up) and to the right.
const DEFAULT_YAW: f32 = std::f32::consts::FRAC_PI_6;
/// Angle of that direction above the horizon, radians (25°).
const DEFAULT_PITCH: f32 = 25.0 * std::f32::consts::PI / 180.0;
/// Part of the picture's half size left free around the framed bodies.
const FRAMING_MARGIN: f32 = 0.1;
/// Nearest the default camera comes to its target, metres.
const MIN_DISTANCE: f32 = 0.1;
/// The box framed when the world has no bounded body, metres about the origin.
const EMPTY_WORLD_HALF_EXTENT: f32 = 3.0;
/// Largest distance, metres, between the camera's position and target, and largest coordinate:
/// far enough for any scene, small enough that the picture's arithmetic stays exact to a
/// fraction of a pixel.
const MAX_COORDINATE: f32 = 1.0e5;

/// A camera as asked for: any field left out is the default camera's.
#[derive(Debug, Clone, Copy, Default)]
pub struct CameraRequest {
    /// Where the camera is, world metres.
    pub position: Option<Vec3>,
    /// The point it looks at, world metres.
    pub target: Option<Vec3>,
    /// Vertical field of view, degrees.
    pub fov_degrees: Option<f32>,
    /// The direction that is up on the picture.
    pub up: Option<Vec3>,
}

/// A camera with every field known and checked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Where the camera is, world metres.
    pub position: Vec3,
    /// The point it looks at, world metres.
    pub target: Vec3,
    /// Vertical field of view, degrees, between 0 and 180 exclusive.
    pub fov_degrees: f32,
    /// The direction that is up on the picture (any length, not along the view).
    pub up: Vec3,
}

/// The world's up: against gravity, or +Y in a world without gravity.
pub fn world_up(world: &World) -> Vec3 {
    // Adding zero turns the -0.0 of a negated zero into 0.0, which prints better.
    (-world.settings().gravity).normalize_or(Vec3::Y) + Vec3::ZERO
}

/// The box the default camera frames: that of the moving (dynamic and kinematic) bodies, or of
/// every bounded body when none moves, or a 6 m cube about the origin in a world without bounded
/// bodies. Halfspaces, unbounded, never count.
fn framed_box(world: &World) -> Aabb {
    let mut moving: Option<Aabb> = None;
    let mut fixed: Option<Aabb> = None;
    for (_, body) in world.bodies() {
        if !body.shape().is_bounded() {
            continue;
        }
        let slot = if body.body_type() == rebond::BodyType::Static {
            &mut fixed
        } else {
            &mut moving
        };
        let bounds = body.shape().aabb(&body.pose());
        *slot = Some(slot.map_or(bounds, |union| union.union(&bounds)));
    }
    moving.or(fixed).unwrap_or_else(|| {
        Aabb::from_center_half_extents(Vec3::ZERO, Vec3::splat(EMPTY_WORLD_HALF_EXTENT))
    })
}

/// The distance from `target` along the unit `backward` at which every corner of `bounds` is
/// on a `width` × `height` picture with the margin. A corner at offset `o` from the target,
/// `x` to the right, `y` up and `z` toward the camera, is `d - z` in front of a camera `d`
/// away and stays inside while `|x| ≤ (d - z) tan(half horizontal fov)` and likewise for `y`:
/// `d ≥ z + |x| / tan(...)`; the largest of these over the corners is the distance.
fn framing_distance(
    bounds: &Aabb,
    target: Vec3,
    backward: Vec3,
    up: Vec3,
    fov_degrees: f32,
    width: usize,
    height: usize,
) -> f32 {
    let right = up.cross(backward).normalize_or(Vec3::X);
    let picture_up = backward.cross(right);
    let vertical = (0.5 * fov_degrees.to_radians()).tan() * (1.0 - FRAMING_MARGIN);
    let horizontal = vertical * width as f32 / height as f32;
    let distance = (0..8)
        .map(|corner| {
            let pick = |bit: usize, axis: usize| {
                if corner & bit == 0 {
                    bounds.min[axis]
                } else {
                    bounds.max[axis]
                }
            };
            let offset = Vec3::new(pick(1, 0), pick(2, 1), pick(4, 2)) - target;
            offset.dot(backward)
                + (offset.dot(right).abs() / horizontal)
                    .max(offset.dot(picture_up).abs() / vertical)
        })
        .fold(0.0, f32::max);
    distance.clamp(MIN_DISTANCE, MAX_COORDINATE)
}

impl CameraRequest {
    /// The camera asked for on a picture of `width` × `height` pixels, its missing fields taken
    /// from the default: up against gravity, a 45° field of view, the target at the centre of
    /// the framed box (see [`framed_box`]) and the camera 30° to the right of the front and 25°
    /// above it, as close as it can be while the sphere around that box fits the picture with a
    /// margin. Errors name the field (`camera.fov: ...`).
    pub fn resolve(&self, world: &World, width: usize, height: usize) -> Result<Camera, String> {
        for (name, value) in [("position", self.position), ("target", self.target)] {
            if let Some(value) = value {
                if value.abs().max_element() > MAX_COORDINATE {
                    return Err(format!(
                        "camera.{name}: coordinates must be at most {MAX_COORDINATE} m in size, \
                         got {value}"
                    ));
                }
            }
        }
        let fov_degrees = self.fov_degrees.unwrap_or(DEFAULT_FOV_DEGREES);
        if !(fov_degrees > 0.0 && fov_degrees < 180.0) {
            return Err(format!(
                "camera.fov: must be between 0 and 180 degrees (exclusive), got {fov_degrees}"
            ));
        }
        let up = match self.up {
            Some(up) if up.length() < 1e-6 => {
                return Err(format!("camera.up: must not be zero, got {up}"));
            }
            Some(up) => up,
            None => world_up(world),
        };
        let bounds = framed_box(world);
        let target = self.target.unwrap_or(bounds.center());
        let position = self.position.unwrap_or_else(|| {
            let (sin_yaw, cos_yaw) = DEFAULT_YAW.sin_cos();
            let (sin_pitch, cos_pitch) = DEFAULT_PITCH.sin_cos();
            let backward = Quat::from_rotation_arc(Vec3::Y, world_up(world))
                * Vec3::new(sin_yaw * cos_pitch, sin_pitch, cos_yaw * cos_pitch);
            let distance =
                framing_distance(&bounds, target, backward, up, fov_degrees, width, height);
            target + distance * backward
        });
        let view = target - position;
        if view.length() < 1e-6 {
            return Err(format!(
                "camera.target: must differ from the position {position}, got {target}"
            ));
        }
        if view.normalize().cross(up.normalize()).length() < 1e-6 {
            return Err(format!(
                "camera.up: must not lie along the view direction {}, got {up}",
                view.normalize()
            ));
        }
        Ok(Camera {
            position,
            target,
            fov_degrees,
            up,
        })
    }
}

/// A camera's frame on a picture: its axes and focal length in pixels.
#[derive(Debug, Clone, Copy)]
pub struct View {
    /// Where the camera is, world metres.
    pub eye: Vec3,
    /// Unit vector toward the target.
    pub forward: Vec3,
    /// Unit vector to the picture's right.
    pub right: Vec3,
    /// Unit vector to the picture's top.
    pub up: Vec3,
    /// Focal length, pixels: `(height/2) / tan(fov/2)`.
    pub focal: f32,
    /// Half the picture's width and height, pixels.
    pub half_width: f32,
    /// See `half_width`.
    pub half_height: f32,
}

impl View {
    /// The frame of `camera` on a picture of `width` × `height` pixels.
    pub fn new(camera: &Camera, width: usize, height: usize) -> Self {
        let forward = (camera.target - camera.position).normalize();
        let right = forward.cross(camera.up).normalize();
        let half_height = 0.5 * height as f32;
        Self {
            eye: camera.position,
            forward,
            right,
            up: right.cross(forward),
            focal: half_height / (0.5 * camera.fov_degrees.to_radians()).tan(),
            half_width: 0.5 * width as f32,
            half_height,
        }
    }

    /// Camera coordinates of a world point: along right, up and forward, metres.
    pub fn camera_point(&self, point: Vec3) -> Vec3 {
        let offset = point - self.eye;
        Vec3::new(
            offset.dot(self.right),
            offset.dot(self.up),
            offset.dot(self.forward),
        )
    }

    /// The direction, scaled to one metre along `forward`, through the picture point at
    /// `column`, `row` pixels from the top-left corner.
    pub fn ray(&self, column: f32, row: f32) -> Vec3 {
        self.forward
            + (column - self.half_width) / self.focal * self.right
            + (self.half_height - row) / self.focal * self.up
    }

    /// Whether any of the ball of `radius` about `centre` may be on the picture: it is not wholly
    /// behind the near distance `near`, nor wholly beyond one of the picture's four edges. A
    /// camera point `(x, y, z)` is left of the right edge while `f x ≤ w/2 z`; its distance past
    /// that plane is `(f x - w/2 z) / √(f² + (w/2)²)`, and likewise for the other edges.
    pub fn sees_sphere(&self, centre: Vec3, radius: f32, near: f32) -> bool {
        let point = self.camera_point(centre);
        let beyond = |across: f32, half: f32| {
            (self.focal * across.abs() - half * point.z) / self.focal.hypot(half) > radius
        };
        point.z + radius >= near
            && !beyond(point.x, self.half_width)
            && !beyond(point.y, self.half_height)
    }
}
