//! The CPU rasteriser of `World.render`: a sky, halfspaces as checkered ground planes, and every
//! bounded body's triangles ([`rebond::shape::tessellation`]) in its colour
//! ([`rebond::palette`]; static bodies grey with one-metre squares), lit by a fixed sun and an
//! ambient light (Lambert), hazed with distance, hidden by a depth buffer, back faces culled.
//! One thread and no randomness: the same world and camera give the same bytes.

use rebond::palette::{body_colour, Rgb, STATIC_BODY};
use rebond::scene::Scene;
use rebond::shape::tessellation::{tessellate, Tessellation};
use rebond::shape::Halfspace;
use rebond::{BodyType, Pose, Quat, Shape, Vec3};

use super::camera::{world_up, Camera, View};

/// Nearest distance drawn in front of the camera, metres: triangles are cut there.
const NEAR: f32 = 0.01;
/// Share of a surface's colour lit whatever its direction.
const AMBIENT: f32 = 0.35;
/// Share lit by the sun, times the cosine between the surface's normal and the sun (Lambert).
const DIFFUSE: f32 = 0.65;
/// The direction toward the sun for +Y up (turned with the world's up): above, in front, to the
/// right, so that the default camera sees three faces of a box lit differently.
const SUN: Vec3 = Vec3::new(0.3, 1.0, 0.55);
/// The sky at the horizon, pale.
const SKY_HORIZON: Rgb = Rgb([205, 222, 236]);
/// The sky straight up, bluer.
const SKY_ZENITH: Rgb = Rgb([96, 148, 212]);
/// Brightness of the ground's darker squares relative to the lighter ones.
const CHECKER_SHADE: f32 = 0.78;
/// Side of a ground square, metres.
const CHECKER_SIZE: f32 = 1.0;
/// Distance over which surfaces fade into the horizon's colour, metres: `e^(-d / this)` of a
/// surface's own colour is left at distance `d`, so that the ground meets the sky smoothly.
const HAZE_DISTANCE: f32 = 400.0;
/// How far inside a static body its squares are sampled, metres: a face lying on a square's
/// border takes the squares behind it, not a speckle of both.
const CHECKER_INSET: f32 = 1e-3;

/// A picture being drawn: colours, and the inverse depth (`1/z`, 0 for nothing yet) of what
/// each pixel shows.
struct Frame {
    width: usize,
    height: usize,
    /// Red, green, blue a pixel, rows from the top.
    pixels: Vec<u8>,
    inverse_depth: Vec<f32>,
}

/// How a surface is coloured.
#[derive(Debug, Clone, Copy)]
enum Paint {
    /// One colour.
    Plain(Rgb),
    /// Squares of [`CHECKER_SIZE`] in the body frame, of the colour and a darker shade of it.
    Checker(Rgb),
}

/// A corner of a triangle being drawn: camera coordinates, brightness, and the body-frame point
/// its squares are sampled at.
#[derive(Debug, Clone, Copy)]
struct Corner {
    camera: Vec3,
    light: f32,
    texture: Vec3,
}

impl Corner {
    /// The point `share` of the way from `self` to `other`.
    fn lerp(self, other: Corner, share: f32) -> Corner {
        Corner {
            camera: self.camera.lerp(other.camera, share),
            light: self.light + (other.light - self.light) * share,
            texture: self.texture.lerp(other.texture, share),
        }
    }
}

/// A corner projected on the picture, with what is interpolated across the triangle, divided by
/// the depth so that it interpolates linearly on the picture (perspective-correct).
#[derive(Debug, Clone, Copy, Default)]
struct Projected {
    column: f64,
    row: f64,
    inverse_depth: f64,
    light: f64,
    texture: [f64; 3],
}

/// The picture of `scene` seen by `camera`, `width` × `height` pixels: `height` rows of
/// `width` red, green, blue bytes. Bodies are drawn in scene order, each in the colour of its
/// name.
pub fn render(scene: &Scene, camera: &Camera, width: usize, height: usize) -> Vec<u8> {
    let world = scene.world();
    let view = View::new(camera, width, height);
    let up = world_up(world);
    let sun = Quat::from_rotation_arc(Vec3::Y, up) * SUN.normalize();
    let mut frame = Frame::sky(&view, up, width, height);
    // Tessellations of the shapes drawn so far: bodies of one shape share theirs.
    let mut meshes: Vec<(&Shape, Tessellation)> = Vec::new();
    for (name, handle) in scene.body_handles() {
        let Ok(body) = world.body(handle) else {
            continue;
        };
        let pose = body.pose();
        let shape = body.shape();
        if let Shape::Halfspace(halfspace) = shape {
            frame.ground(&view, halfspace, &pose, sun);
            continue;
        }
        let bounds = shape.aabb(&pose);
        if !view.sees_sphere(bounds.center(), bounds.half_extents().length(), NEAR) {
            continue;
        }
        let mesh = match meshes.iter().position(|(drawn, _)| *drawn == shape) {
            Some(index) => &meshes[index].1,
            None => {
                let Some(mesh) = tessellate(shape) else {
                    continue;
                };
                meshes.push((shape, mesh));
                &meshes[meshes.len() - 1].1
            }
        };
        let paint = match body.body_type() {
            BodyType::Static => Paint::Checker(STATIC_BODY),
            body_type => Paint::Plain(body_colour(name, body_type)),
        };
        frame.shape(&view, mesh, &pose, paint, sun);
    }
    frame.pixels
}

/// Brightness of a surface facing `normal` (unit) under the sun.
fn lighting(normal: Vec3, sun: Vec3) -> f32 {
    AMBIENT + DIFFUSE * normal.dot(sun).max(0.0)
}

/// The colour of a square of `base`: `base` on even squares, [`CHECKER_SHADE`] of it on odd
/// ones, both fading to their mean as the ground under one pixel (`footprint`, metres) grows to
/// a square, where drawing the squares would only alias.
fn square_colour(base: Rgb, odd: bool, footprint: f32) -> [f32; 3] {
    let sharpness = (1.0 - footprint / CHECKER_SIZE).clamp(0.0, 1.0);
    let mean = 0.5 * (1.0 + CHECKER_SHADE);
    let own = if odd { CHECKER_SHADE } else { 1.0 };
    let factor = mean + (own - mean) * sharpness;
    base.0.map(|channel| f32::from(channel) * factor)
}

/// Whether the square holding `point` (a sum of floors of its coordinates in squares) is odd.
fn odd_square(coordinates: impl IntoIterator<Item = f32>) -> bool {
    let sum: f32 = coordinates
        .into_iter()
        .map(|coordinate| (coordinate / CHECKER_SIZE).floor())
        .sum();
    sum.rem_euclid(2.0) >= 1.0
}

/// A surface's `colour` lit at `brightness` and seen `distance` metres away through the haze,
/// as bytes.
fn finish(colour: [f32; 3], brightness: f32, distance: f32) -> [u8; 3] {
    let haze = 1.0 - (-distance / HAZE_DISTANCE).exp();
    let mut lit = [0; 3];
    for (channel, (value, sky)) in lit.iter_mut().zip(colour.iter().zip(SKY_HORIZON.0)) {
        let value = value * brightness;
        *channel = (value + (f32::from(sky) - value) * haze)
            .round()
            .clamp(0.0, 255.0) as u8;
    }
    lit
}

impl Frame {
    /// A frame showing only the sky: the horizon's colour at and below the horizon, the zenith's
    /// straight up, mixed by the sine of the elevation in between.
    fn sky(view: &View, up: Vec3, width: usize, height: usize) -> Self {
        let mut pixels = Vec::with_capacity(width * height * 3);
        for row in 0..height {
            for column in 0..width {
                let ray = view.ray(column as f32 + 0.5, row as f32 + 0.5);
                let elevation = (ray.dot(up) / ray.length()).clamp(0.0, 1.0);
                pixels.extend(SKY_HORIZON.mix(SKY_ZENITH, elevation).0);
            }
        }
        Self {
            width,
            height,
            pixels,
            inverse_depth: vec![0.0; width * height],
        }
    }

    /// Writes `colour` at pixel `index` if `inverse_depth` is nearer than what it shows.
    fn plot(&mut self, index: usize, inverse_depth: f32, colour: [u8; 3]) {
        if inverse_depth > self.inverse_depth[index] {
            self.inverse_depth[index] = inverse_depth;
            self.pixels[3 * index..3 * index + 3].copy_from_slice(&colour);
        }
    }

    /// The plane of a halfspace at `pose`, seen from its outside, checkered along the plane's
    /// axes (the world's X and Z for a +Y normal). Each pixel's ray is met with the plane
    /// exactly, so the plane reaches the horizon.
    fn ground(&mut self, view: &View, halfspace: &Halfspace, pose: &Pose, sun: Vec3) {
        let normal = pose.rotation * halfspace.normal();
        let height = normal.dot(view.eye - pose.position);
        if height <= 0.0 {
            return;
        }
        let turn = Quat::from_rotation_arc(Vec3::Y, normal);
        let (across, along) = (turn * Vec3::X, turn * Vec3::Z);
        let brightness = lighting(normal, sun);
        for row in 0..self.height {
            for column in 0..self.width {
                let ray = view.ray(column as f32 + 0.5, row as f32 + 0.5);
                let approach = -normal.dot(ray);
                if approach <= 0.0 {
                    continue;
                }
                // `ray` is one metre long along the view, so `depth` is the hit's z.
                let depth = height / approach;
                if depth < NEAR {
                    continue;
                }
                let hit = view.eye + depth * ray - pose.position;
                let length = ray.length();
                // The plane under one pixel: its width at that distance over the cosine of the
                // incidence, `approach / length`.
                let footprint = depth * length * length / (view.focal * approach);
                let odd = odd_square([hit.dot(across), hit.dot(along)]);
                let colour = square_colour(STATIC_BODY, odd, footprint);
                let colour = finish(colour, brightness, depth * length);
                self.plot(row * self.width + column, 1.0 / depth, colour);
            }
        }
    }

    /// The triangles `mesh` of a body at `pose`, painted `paint`, lit at their corners.
    fn shape(&mut self, view: &View, mesh: &Tessellation, pose: &Pose, paint: Paint, sun: Vec3) {
        let world_points: Vec<Vec3> = mesh
            .positions
            .iter()
            .map(|&point| pose.transform_point(point))
            .collect();
        let cameras: Vec<Vec3> = world_points
            .iter()
            .map(|&point| view.camera_point(point))
            .collect();
        let lights: Vec<f32> = mesh
            .normals
            .iter()
            .map(|&normal| lighting(pose.transform_vector(normal), sun))
            .collect();
        for triangle in mesh.indices.chunks_exact(3) {
            let indices = [0, 1, 2].map(|corner| triangle[corner] as usize);
            let [a, b, c] = indices.map(|index| world_points[index]);
            let face = (b - a).cross(c - a);
            if face.dot(a - view.eye) >= 0.0 {
                continue;
            }
            let (inset, footprint_per_metre) = match paint {
                Paint::Plain(_) => (Vec3::ZERO, 0.0),
                Paint::Checker(_) => {
                    // The surface under one pixel per metre of distance, from the incidence at
                    // the triangle's centre.
                    let centre = (a + b + c) / 3.0 - view.eye;
                    let incidence = face.normalize_or_zero().dot(centre).abs() / centre.length();
                    (
                        CHECKER_INSET * (pose.rotation.inverse() * face.normalize_or_zero()),
                        1.0 / (view.focal * incidence.max(1e-3)),
                    )
                }
            };
            let corners = indices.map(|index| Corner {
                camera: cameras[index],
                light: lights[index],
                texture: mesh.positions[index] - inset,
            });
            self.triangle(view, corners, paint, footprint_per_metre);
        }
    }

    /// One front-facing triangle: cut at the near distance, projected, and filled.
    fn triangle(&mut self, view: &View, corners: [Corner; 3], paint: Paint, footprint: f32) {
        // Cutting a triangle by a plane leaves at most four corners.
        let mut kept = [Projected::default(); 4];
        let mut count = 0;
        let mut keep = |corner: Corner| {
            let inverse_depth = 1.0 / f64::from(corner.camera.z);
            kept[count] = Projected {
                column: f64::from(view.half_width)
                    + f64::from(view.focal) * f64::from(corner.camera.x) * inverse_depth,
                row: f64::from(view.half_height)
                    - f64::from(view.focal) * f64::from(corner.camera.y) * inverse_depth,
                inverse_depth,
                light: f64::from(corner.light) * inverse_depth,
                texture: corner
                    .texture
                    .to_array()
                    .map(|value| f64::from(value) * inverse_depth),
            };
            count += 1;
        };
        for index in 0..3 {
            let (from, to) = (corners[index], corners[(index + 1) % 3]);
            if from.camera.z >= NEAR {
                keep(from);
            }
            if (from.camera.z >= NEAR) != (to.camera.z >= NEAR) {
                keep(from.lerp(to, (NEAR - from.camera.z) / (to.camera.z - from.camera.z)));
            }
        }
        for fan in 1..count.saturating_sub(1) {
            self.fill(view, [kept[0], kept[fan], kept[fan + 1]], paint, footprint);
        }
    }

    /// Fills the pixels whose centres lie in the projected triangle (edges included) and nearer
    /// than what they show.
    fn fill(&mut self, view: &View, corners: [Projected; 3], paint: Paint, footprint: f32) {
        let edge = |from: &Projected, to: &Projected, column: f64, row: f64| {
            (to.column - from.column) * (row - from.row)
                - (to.row - from.row) * (column - from.column)
        };
        let [a, b, c] = corners;
        let area = edge(&a, &b, c.column, c.row);
        if area.abs() < 1e-12 {
            return;
        }
        // The pixels whose centres, at half-integers, the triangle's box holds.
        let span = |values: [f64; 3], size: usize| {
            let low = values.iter().copied().fold(f64::INFINITY, f64::min);
            let high = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let first = (low - 0.5).ceil().max(0.0);
            let last = (high - 0.5).floor().min(size as f64 - 1.0);
            (first, last)
        };
        let (first_column, last_column) = span([a.column, b.column, c.column], self.width);
        let (first_row, last_row) = span([a.row, b.row, c.row], self.height);
        if last_column < first_column || last_row < first_row {
            return;
        }
        for row in first_row as usize..=last_row as usize {
            let y = row as f64 + 0.5;
            for column in first_column as usize..=last_column as usize {
                let x = column as f64 + 0.5;
                let weights = [edge(&b, &c, x, y) / area, edge(&c, &a, x, y) / area];
                let weights = [weights[0], weights[1], 1.0 - weights[0] - weights[1]];
                if weights.iter().any(|&weight| weight < 0.0) {
                    continue;
                }
                let blend = |value: fn(&Projected) -> f64| {
                    weights[0] * value(&a) + weights[1] * value(&b) + weights[2] * value(&c)
                };
                let inverse_depth = blend(|corner| corner.inverse_depth);
                let index = row * self.width + column;
                if inverse_depth as f32 <= self.inverse_depth[index] {
                    continue;
                }
                let depth = 1.0 / inverse_depth;
                let distance = depth as f32 * view.ray(x as f32, y as f32).length();
                let colour = match paint {
                    Paint::Plain(colour) => colour.0.map(f32::from),
                    Paint::Checker(colour) => {
                        let texture = [
                            blend(|corner| corner.texture[0]),
                            blend(|corner| corner.texture[1]),
                            blend(|corner| corner.texture[2]),
                        ];
                        let odd = odd_square(texture.map(|value| (value * depth) as f32));
                        square_colour(colour, odd, distance * footprint)
                    }
                };
                let light = (blend(|corner| corner.light) * depth) as f32;
                self.plot(index, inverse_depth as f32, finish(colour, light, distance));
            }
        }
    }
}
