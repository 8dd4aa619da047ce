//! The orbit camera: it looks at a target point from a distance along a direction given by yaw
//! and pitch. Dragging turns it, the wheel zooms and panning slides the target.
//!
//! Screen positions are in physical pixels from the top-left corner, `y` down, as in a PNG.

use glam::camera::rh::proj::opengl::perspective;
use glam::camera::rh::view::look_at_mat4;
use glam::{Mat4, Vec2, Vec3, Vec4Swizzles};
use rebond::Aabb;

use super::picking::Ray;

/// Vertical field of view, radians (45°).
pub const FIELD_OF_VIEW_Y: f32 = std::f32::consts::FRAC_PI_4;
/// Distance of the near clipping plane, metres.
pub const NEAR_PLANE: f32 = 0.05;
/// Distance of the far clipping plane, metres.
pub const FAR_PLANE: f32 = 2000.0;
/// Radians of turn per pixel of drag.
const TURN_PER_PIXEL: f32 = 0.006;
/// Largest pitch above or below the horizon, radians: just short of straight up or down.
const MAX_PITCH: f32 = 1.5;
/// Zoom factor per unit of wheel delta (one wheel notch is about 24 units): about 10 % a notch.
const ZOOM_PER_WHEEL_UNIT: f32 = 0.0045;
/// Closest and farthest orbit distances, metres.
const DISTANCE_RANGE: (f32, f32) = (0.5, 1000.0);
/// Part of the screen's width and height left free around a framed scene.
const FRAMING_MARGIN: f32 = 0.06;
/// Initial yaw and pitch, radians: looking from the front right, somewhat above.
const INITIAL_YAW: f32 = 0.2;
const INITIAL_PITCH: f32 = 0.4;

/// A camera orbiting a target point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrbitCamera {
    /// The point looked at, world metres.
    pub target: Vec3,
    /// Angle about +Y of the direction from the target to the eye, radians (0: the eye on +Z).
    pub yaw: f32,
    /// Angle of that direction above the horizon, radians.
    pub pitch: f32,
    /// Distance from the target to the eye, metres.
    pub distance: f32,
}

impl OrbitCamera {
    /// A camera looking at the centre of the boxes `bounds` from the front right and somewhat
    /// above, as close as it can while every box stays on a screen of `viewport` pixels with a
    /// margin.
    pub fn framing(bounds: &[Aabb], viewport: Vec2) -> Self {
        let union = bounds
            .iter()
            .copied()
            .reduce(|a, b| a.union(&b))
            .unwrap_or_else(|| Aabb::new(Vec3::ZERO, Vec3::ZERO));
        let corners: Vec<Vec3> = bounds
            .iter()
            .flat_map(|bounds| (0..8).map(|index| corner(bounds, index)))
            .collect();
        let mut camera = Self {
            target: union.center(),
            yaw: INITIAL_YAW,
            pitch: INITIAL_PITCH,
            distance: DISTANCE_RANGE.1,
        };
        let inside_margin = |camera: &OrbitCamera| {
            corners.iter().all(|&point| {
                camera.project(point, viewport).is_some_and(|pixel| {
                    let margin = FRAMING_MARGIN * viewport;
                    pixel.cmpge(margin).all() && pixel.cmple(viewport - margin).all()
                })
            })
        };
        let (mut near, mut far) = DISTANCE_RANGE;
        for _ in 0..40 {
            camera.distance = 0.5 * (near + far);
            if inside_margin(&camera) {
                far = camera.distance;
            } else {
                near = camera.distance;
            }
        }
        camera.distance = far;
        camera
    }

    /// Unit vector from the target toward the eye.
    fn backward(&self) -> Vec3 {
        Vec3::new(
            self.pitch.cos() * self.yaw.sin(),
            self.pitch.sin(),
            self.pitch.cos() * self.yaw.cos(),
        )
    }

    /// Where the camera is, world metres.
    pub fn eye(&self) -> Vec3 {
        self.target + self.distance * self.backward()
    }

    /// The camera's heading on the ground (the horizontal part of its view direction) and the
    /// screen's right, both horizontal unit vectors.
    pub fn ground_heading_and_right(&self) -> (Vec3, Vec3) {
        let (sin, cos) = self.yaw.sin_cos();
        (Vec3::new(-sin, 0.0, -cos), Vec3::new(cos, 0.0, -sin))
    }

    /// The screen's right and up directions in the world.
    fn right_and_up(&self) -> (Vec3, Vec3) {
        let backward = self.backward();
        let right = Vec3::Y.cross(backward).normalize_or(Vec3::X);
        (right, backward.cross(right))
    }

    /// Turns the camera about the target for a drag of `delta` pixels (x right, y down).
    pub fn turn(&mut self, delta: Vec2) {
        self.yaw -= delta.x * TURN_PER_PIXEL;
        self.pitch = (self.pitch + delta.y * TURN_PER_PIXEL).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// Moves the camera closer for a positive wheel `delta`, farther for a negative one.
    pub fn zoom(&mut self, delta: f32) {
        self.distance = (self.distance * (-delta * ZOOM_PER_WHEEL_UNIT).exp())
            .clamp(DISTANCE_RANGE.0, DISTANCE_RANGE.1);
    }

    /// Slides the camera and its target so that the scene follows a drag of `delta` pixels
    /// (x right, y down) on a screen `viewport_height` pixels high.
    pub fn pan(&mut self, delta: Vec2, viewport_height: f32) {
        let metres_per_pixel =
            2.0 * self.distance * (FIELD_OF_VIEW_Y * 0.5).tan() / viewport_height.max(1.0);
        let (right, up) = self.right_and_up();
        self.target += metres_per_pixel * (up * delta.y - right * delta.x);
    }

    /// World to clip space for a screen of `viewport` pixels (width, height).
    pub fn view_projection(&self, viewport: Vec2) -> Mat4 {
        let aspect = viewport.x.max(1.0) / viewport.y.max(1.0);
        let projection = perspective(FIELD_OF_VIEW_Y, aspect, NEAR_PLANE, FAR_PLANE);
        let view = look_at_mat4(self.eye(), self.target, Vec3::Y);
        projection * view
    }

    /// The ray from the eye through `pixel` of a screen of `viewport` pixels.
    pub fn ray(&self, pixel: Vec2, viewport: Vec2) -> Ray {
        let inverse = self.view_projection(viewport).inverse();
        let ndc = Vec2::new(
            2.0 * pixel.x / viewport.x.max(1.0) - 1.0,
            1.0 - 2.0 * pixel.y / viewport.y.max(1.0),
        );
        let far = inverse * ndc.extend(1.0).extend(1.0);
        let far = far.xyz() / far.w;
        let eye = self.eye();
        Ray {
            origin: eye,
            direction: (far - eye).normalize_or(-self.backward()),
        }
    }

    /// The pixel `point` is drawn at on a screen of `viewport` pixels, or `None` when it is
    /// behind the camera or outside the screen.
    pub fn project(&self, point: Vec3, viewport: Vec2) -> Option<Vec2> {
        let clip = self.view_projection(viewport) * point.extend(1.0);
        if clip.w <= NEAR_PLANE {
            return None;
        }
        let ndc = clip.xyz() / clip.w;
        let pixel = Vec2::new(
            (ndc.x + 1.0) * 0.5 * viewport.x,
            (1.0 - ndc.y) * 0.5 * viewport.y,
        );
        let inside =
            pixel.x >= 0.0 && pixel.y >= 0.0 && pixel.x < viewport.x && pixel.y < viewport.y;
        inside.then_some(pixel)
    }
}

/// Corner `index` (0 to 7, one bit an axis) of `bounds`.
pub fn corner(bounds: &Aabb, index: usize) -> Vec3 {
    Vec3::new(
        if index & 1 == 0 {
            bounds.min.x
        } else {
            bounds.max.x
        },
        if index & 2 == 0 {
            bounds.min.y
        } else {
            bounds.max.y
        },
        if index & 4 == 0 {
            bounds.min.z
        } else {
            bounds.max.z
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> OrbitCamera {
        OrbitCamera::framing(
            &[Aabb::new(
                Vec3::new(-2.0, 0.0, -1.0),
                Vec3::new(4.0, 3.0, 1.0),
            )],
            Vec2::new(960.0, 540.0),
        )
    }

    #[test]
    fn the_target_projects_to_the_centre_and_its_ray_goes_through_it() {
        let camera = camera();
        let viewport = Vec2::new(960.0, 540.0);
        let centre = camera.project(camera.target, viewport).expect("on screen");
        assert!((centre - viewport * 0.5).length() < 0.5, "{centre}");
        let ray = camera.ray(viewport * 0.5, viewport);
        let to_target = (camera.target - ray.origin).normalize();
        assert!(ray.direction.dot(to_target) > 0.99999);
    }

    #[test]
    fn ray_and_projection_agree() {
        let mut camera = camera();
        camera.turn(Vec2::new(40.0, -25.0));
        let viewport = Vec2::new(800.0, 600.0);
        let point = Vec3::new(1.0, 2.0, 0.5);
        let pixel = camera.project(point, viewport).expect("on screen");
        let ray = camera.ray(pixel, viewport);
        let along = (point - ray.origin).dot(ray.direction);
        let closest = ray.origin + along * ray.direction;
        assert!((closest - point).length() < 1e-3, "{closest} vs {point}");
    }

    #[test]
    fn framing_shows_every_corner_of_the_bounds_and_fills_the_screen() {
        let bounds = Aabb::new(Vec3::new(-12.0, 0.0, -6.0), Vec3::new(13.0, 6.0, 6.0));
        let viewport = Vec2::new(960.0, 540.0);
        let camera = OrbitCamera::framing(&[bounds], viewport);
        let pixels: Vec<Vec2> = (0..8)
            .map(|index| {
                camera
                    .project(corner(&bounds, index), viewport)
                    .expect("on screen")
            })
            .collect();
        let low = pixels.iter().copied().reduce(Vec2::min).expect("corners");
        let high = pixels.iter().copied().reduce(Vec2::max).expect("corners");
        let margin = viewport * FRAMING_MARGIN;
        assert!(low.cmpge(margin * 0.99).all() && high.cmple(viewport - margin * 0.99).all());
        let filled = (high - low) / (viewport - 2.0 * margin);
        assert!(
            filled.max_element() > 0.95,
            "about as close as the margin allows: {filled}"
        );
    }

    #[test]
    fn zoom_turn_and_pan_move_the_camera_as_expected() {
        let mut camera = camera();
        let start = camera;
        camera.zoom(24.0);
        assert!(camera.distance < start.distance);
        camera.zoom(-1.0e6);
        assert_eq!(camera.distance, DISTANCE_RANGE.1);
        camera.turn(Vec2::new(0.0, 1.0e6));
        assert_eq!(camera.pitch, MAX_PITCH);
        let mut panned = start;
        panned.pan(Vec2::new(100.0, 0.0), 540.0);
        let (right, _) = start.right_and_up();
        assert!(
            (panned.target - start.target).dot(right) < 0.0,
            "drag right moves the view left"
        );
        assert_eq!(panned.distance, start.distance);
    }

    #[test]
    fn points_behind_the_camera_do_not_project() {
        let camera = camera();
        let behind = camera.eye() + (camera.eye() - camera.target);
        assert_eq!(camera.project(behind, Vec2::new(960.0, 540.0)), None);
    }
}
