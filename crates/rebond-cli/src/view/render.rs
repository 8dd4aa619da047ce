//! Drawing a frame with three-d: bodies lit and solid (one instanced mesh per distinct shape),
//! halfspaces as ground grids, the debug geometry on top, and the text panels.

use glam::{Mat4 as GlamMat4, Quat, Vec2, Vec3};
use rebond::shape::tessellation::{tessellate, Tessellation};
use rebond::{BodyType, Pose, Shape};
use three_d::{
    degrees, radians, AmbientLight, Camera, ClearState, ColorMaterial, Context, CpuMaterial,
    CpuMesh, CpuTexture, DepthTest, DirectionalLight, Gm, Indices, InstancedMesh, Instances,
    Interpolation, Light, Mat4, Mesh, PhysicalMaterial, Positions, Rectangle, RenderStates,
    RenderTarget, Srgba, TextureData, Viewport,
};

use super::camera::{FAR_PLANE, FIELD_OF_VIEW_Y, NEAR_PLANE};
use super::controls::help_lines;
use super::debug_draw::{debug_geometry, DebugGeometry};
use super::ground::{grid_texture, ground_model, ground_pose};
use super::overlay::{stats_lines, text_panel, Image};
use super::palette::{shown_colour, Rgb, BACKGROUND};
use super::viewer::Viewer;

/// Side of the shadow map, texels.
const SHADOW_MAP_SIZE: u32 = 2048;
/// Radius of drawn debug lines per metre of distance from the eye: about a pixel either side of
/// the line on a 720-pixel-high window, near or far.
const LINE_RADIUS_PER_METRE: f32 = 0.0012;
/// Radius of drawn debug dots per metre of distance from the eye: about 5 pixels across.
const MARKER_RADIUS_PER_METRE: f32 = 0.0032;
/// Bodies larger than this across (metres) cast no shadow: a floor shadows nothing, and leaving
/// it out keeps the shadow map fine-grained where the action is.
const MAX_SHADOW_CASTER_SIZE: f32 = 40.0;
/// Gap between the screen's edge and the text panels, pixels.
const PANEL_MARGIN: f32 = 10.0;

/// Bodies of one shape and kind (static or not), drawn together.
struct ShapeGroup {
    /// Whether they cast shadows (they are not floor-sized).
    casts_shadow: bool,
    /// Their indices in the simulation's body list.
    members: Vec<usize>,
    /// Their mesh, one instance each.
    model: Gm<InstancedMesh, PhysicalMaterial>,
}

/// A halfspace's ground plane.
struct Ground {
    /// Its body's index in the simulation's body list.
    member: usize,
    /// The plane with its grid.
    model: Gm<Mesh, PhysicalMaterial>,
}

/// The GPU side of the viewer: meshes, lights and the debug and text layers.
pub struct Renderer {
    /// The OpenGL context drawn with.
    context: Context,
    /// The bounded bodies, by shape.
    groups: Vec<ShapeGroup>,
    /// The halfspaces.
    grounds: Vec<Ground>,
    /// The simulation's body-set version the groups were built for.
    built_for: Option<u64>,
    /// The directional light, which casts the shadows.
    sun: DirectionalLight,
    /// The ambient light.
    sky: AmbientLight,
    /// Debug lines: a thin cylinder each.
    lines: Gm<InstancedMesh, ColorMaterial>,
    /// Debug dots: a small sphere each.
    markers: Gm<InstancedMesh, ColorMaterial>,
}

impl Renderer {
    /// A renderer drawing with `context`.
    pub fn new(context: &Context) -> Self {
        let on_top = ColorMaterial {
            color: Srgba::WHITE,
            render_states: RenderStates {
                depth_test: DepthTest::Always,
                ..RenderStates::default()
            },
            ..ColorMaterial::default()
        };
        let no_instances = Instances::default();
        Self {
            context: context.clone(),
            groups: Vec::new(),
            grounds: Vec::new(),
            built_for: None,
            sun: DirectionalLight::new(
                context,
                1.6,
                Srgba::WHITE,
                three_d::vec3(-0.35, -1.0, -0.5),
            ),
            sky: AmbientLight::new(context, 0.35, Srgba::WHITE),
            lines: Gm::new(
                InstancedMesh::new(context, &no_instances, &CpuMesh::cylinder(8)),
                on_top.clone(),
            ),
            markers: Gm::new(
                InstancedMesh::new(context, &no_instances, &CpuMesh::sphere(8)),
                on_top,
            ),
        }
    }

    /// Draws the viewer's scene on `target`, a screen of `viewport`; `scene` names it in the
    /// statistics panel.
    pub fn render(
        &mut self,
        target: &RenderTarget<'_>,
        viewer: &Viewer,
        viewport: Viewport,
        scene: &str,
    ) {
        self.sync_bodies(viewer);
        self.update_instances(viewer);
        let camera = perspective_camera(viewer, viewport);
        let [red, green, blue] = BACKGROUND.0.map(|channel| f32::from(channel) / 255.0);
        target.clear(ClearState::color_and_depth(red, green, blue, 1.0, 1.0));
        let casts_shadow = |group: &&ShapeGroup| group.casts_shadow && !group.members.is_empty();
        let casters = self
            .groups
            .iter()
            .filter(casts_shadow)
            .map(|group| &group.model.geometry);
        if self.groups.iter().any(|group| casts_shadow(&group)) {
            // Without a shadow map the scene is still drawn, only without shadows.
            let _ = self.sun.generate_shadow_map(SHADOW_MAP_SIZE, casters);
        }
        let lights: [&dyn Light; 2] = [&self.sun, &self.sky];
        target.render(
            &camera,
            self.grounds.iter().map(|ground| &ground.model),
            &lights,
        );
        target.render(
            &camera,
            self.groups
                .iter()
                .filter(|group| !group.members.is_empty())
                .map(|group| &group.model),
            &lights,
        );
        self.draw_debug(
            target,
            &camera,
            viewer.camera.eye(),
            &debug_geometry(viewer),
        );
        self.draw_panels(target, viewer, viewport, scene);
    }

    /// Rebuilds the shape groups and ground planes when bodies were added or removed.
    fn sync_bodies(&mut self, viewer: &Viewer) {
        let simulation = &viewer.simulation;
        if self.built_for == Some(simulation.body_set_version()) {
            return;
        }
        self.built_for = Some(simulation.body_set_version());
        let mut shapes: Vec<(Shape, bool, Vec<usize>)> = Vec::new();
        self.grounds.clear();
        for (index, info) in simulation.bodies().iter().enumerate() {
            let Ok(body) = simulation.world().body(info.handle) else {
                continue;
            };
            if !body.shape().is_bounded() {
                self.grounds.push(Ground {
                    member: index,
                    model: ground_model(&self.context),
                });
                continue;
            }
            let is_static = body.body_type() == BodyType::Static;
            let same = |(shape, static_group, _): &&mut (Shape, bool, Vec<usize>)| {
                *static_group == is_static && shape == body.shape()
            };
            match shapes.iter_mut().find(same) {
                Some((_, _, members)) => members.push(index),
                None => shapes.push((body.shape().clone(), is_static, vec![index])),
            }
        }
        let plain = CpuMaterial {
            albedo: Srgba::WHITE,
            roughness: 0.65,
            metallic: 0.0,
            ..Default::default()
        };
        let gridded = CpuMaterial {
            albedo_texture: Some(grid_texture(Rgb::WHITE)),
            roughness: 0.9,
            ..plain.clone()
        };
        let plain = PhysicalMaterial::new_opaque(&self.context, &plain);
        let gridded = PhysicalMaterial::new_opaque(&self.context, &gridded);
        self.groups = shapes
            .into_iter()
            .filter_map(|(shape, is_static, members)| {
                let mesh = cpu_mesh(&tessellate(&shape)?, is_static);
                let size = shape.aabb(&Pose::IDENTITY).half_extents().max_element() * 2.0;
                let material = if is_static { &gridded } else { &plain };
                let model = Gm::new(
                    InstancedMesh::new(&self.context, &Instances::default(), &mesh),
                    material.clone(),
                );
                Some(ShapeGroup {
                    casts_shadow: size <= MAX_SHADOW_CASTER_SIZE,
                    members,
                    model,
                })
            })
            .collect();
    }

    /// Moves every instance to its body's pose and paints it its colour.
    fn update_instances(&mut self, viewer: &Viewer) {
        let simulation = &viewer.simulation;
        let bodies = simulation.bodies();
        let world = simulation.world();
        let tint = viewer.display.sleeping_tint;
        for group in &mut self.groups {
            let mut transformations = Vec::with_capacity(group.members.len());
            let mut colours = Vec::with_capacity(group.members.len());
            for &member in &group.members {
                let Some(body) = bodies
                    .get(member)
                    .and_then(|info| world.body(info.handle).ok())
                else {
                    continue;
                };
                transformations.push(pose_matrix(&body.pose()));
                colours.push(srgba(shown_colour(
                    bodies[member].colour,
                    body.is_sleeping(),
                    tint,
                )));
            }
            group.model.geometry.set_instances(&Instances {
                transformations,
                colors: Some(colours),
                ..Default::default()
            });
        }
        for ground in &mut self.grounds {
            let body = bodies
                .get(ground.member)
                .and_then(|info| world.body(info.handle).ok());
            if let Some(body) = body {
                if let Shape::Halfspace(halfspace) = body.shape() {
                    let pose = ground_pose(halfspace, &body.pose());
                    ground.model.set_transformation(pose_matrix(&pose));
                }
            }
        }
    }

    /// Draws debug lines as thin cylinders and dots as small spheres, over everything, sized to
    /// look alike near and far from the `eye`.
    fn draw_debug(
        &mut self,
        target: &RenderTarget<'_>,
        camera: &Camera,
        eye: Vec3,
        geometry: &DebugGeometry,
    ) {
        let lines = Instances {
            transformations: geometry
                .segments
                .iter()
                .map(|segment| {
                    let distance = eye.distance(0.5 * (segment.from + segment.to));
                    segment_matrix(segment.from, segment.to, LINE_RADIUS_PER_METRE * distance)
                })
                .collect(),
            colors: Some(
                geometry
                    .segments
                    .iter()
                    .map(|segment| srgba(segment.colour))
                    .collect(),
            ),
            ..Default::default()
        };
        let markers = Instances {
            transformations: geometry
                .markers
                .iter()
                .map(|marker| {
                    let radius = MARKER_RADIUS_PER_METRE * eye.distance(marker.position);
                    glam_to_three_d(GlamMat4::from_scale_rotation_translation(
                        Vec3::splat(radius),
                        Quat::IDENTITY,
                        marker.position,
                    ))
                })
                .collect(),
            colors: Some(
                geometry
                    .markers
                    .iter()
                    .map(|marker| srgba(marker.colour))
                    .collect(),
            ),
            ..Default::default()
        };
        self.lines.geometry.set_instances(&lines);
        self.markers.geometry.set_instances(&markers);
        if !geometry.segments.is_empty() {
            target.render(camera, &self.lines, &[]);
        }
        if !geometry.markers.is_empty() {
            target.render(camera, &self.markers, &[]);
        }
    }

    /// The statistics panel at the bottom left, where the ground usually is, and, when asked
    /// for, the help at the top right.
    fn draw_panels(
        &self,
        target: &RenderTarget<'_>,
        viewer: &Viewer,
        viewport: Viewport,
        scene: &str,
    ) {
        let simulation = &viewer.simulation;
        let dragged = simulation.drag().and_then(|drag| {
            simulation
                .bodies()
                .iter()
                .find(|info| info.handle == drag.body())
                .map(|info| info.name.as_str())
        });
        let stats = text_panel(&stats_lines(
            scene,
            &simulation.stats(),
            simulation.is_paused(),
            simulation.is_slow_motion(),
            dragged,
        ));
        let camera = Camera::new_2d(viewport);
        let height = viewport.height as f32;
        let mut panels = vec![self.panel(
            &stats,
            Vec2::new(PANEL_MARGIN, PANEL_MARGIN + stats.height as f32),
        )];
        if viewer.display.help {
            let help = text_panel(&help_lines());
            let left = viewport.width as f32 - PANEL_MARGIN - help.width as f32;
            panels.push(self.panel(&help, Vec2::new(left.max(0.0), height - PANEL_MARGIN)));
        }
        target.render(&camera, &panels, &[]);
    }

    /// A screen-space rectangle showing `image` with its top-left corner at `top_left` (pixels
    /// from the bottom left).
    fn panel(&self, image: &Image, top_left: Vec2) -> Gm<Rectangle, ColorMaterial> {
        let (width, height) = (image.width as f32, image.height as f32);
        let texture = CpuTexture {
            data: TextureData::RgbaU8(image.pixels.clone()),
            width: image.width as u32,
            height: image.height as u32,
            min_filter: Interpolation::Nearest,
            mag_filter: Interpolation::Nearest,
            mipmap: None,
            ..Default::default()
        };
        let material = ColorMaterial::new_transparent(
            &self.context,
            &CpuMaterial {
                albedo: Srgba::WHITE,
                albedo_texture: Some(texture),
                ..Default::default()
            },
        );
        let centre = three_d::PhysicalPoint {
            x: top_left.x + width * 0.5,
            y: top_left.y - height * 0.5,
        };
        Gm::new(
            Rectangle::new(&self.context, centre, degrees(0.0), width, height),
            material,
        )
    }
}

/// three-d's camera for the viewer's orbit camera.
fn perspective_camera(viewer: &Viewer, viewport: Viewport) -> Camera {
    let eye = viewer.camera.eye();
    let target = viewer.camera.target;
    Camera::new_perspective(
        viewport,
        three_d::vec3(eye.x, eye.y, eye.z),
        three_d::vec3(target.x, target.y, target.z),
        three_d::vec3(0.0, 1.0, 0.0),
        radians(FIELD_OF_VIEW_Y),
        NEAR_PLANE,
        FAR_PLANE,
    )
}

/// three-d's mesh of a triangle mesh, with texture coordinates for the grid when `gridded`.
fn cpu_mesh(mesh: &Tessellation, gridded: bool) -> CpuMesh {
    let convert = |v: &Vec3| three_d::vec3(v.x, v.y, v.z);
    let uvs = gridded.then(|| {
        mesh.positions
            .iter()
            .zip(&mesh.normals)
            .map(|(&position, &normal)| {
                let [u, v] = grid_coordinates(position, normal);
                three_d::vec2(u, v)
            })
            .collect()
    });
    CpuMesh {
        positions: Positions::F32(mesh.positions.iter().map(convert).collect()),
        normals: Some(mesh.normals.iter().map(convert).collect()),
        uvs,
        indices: Indices::U32(mesh.indices.clone()),
        ..Default::default()
    }
}

/// Texture coordinates in metres for the grid: the position projected along the normal's
/// largest axis, so that each face of a box shows square one-metre cells.
fn grid_coordinates(position: Vec3, normal: Vec3) -> [f32; 2] {
    let magnitude = normal.abs();
    if magnitude.y >= magnitude.x && magnitude.y >= magnitude.z {
        [position.x, position.z]
    } else if magnitude.x >= magnitude.z {
        [position.z, position.y]
    } else {
        [position.x, position.y]
    }
}

/// The matrix of a pose, for three-d.
fn pose_matrix(pose: &Pose) -> Mat4 {
    glam_to_three_d(GlamMat4::from_rotation_translation(
        pose.rotation,
        pose.position,
    ))
}

/// The matrix taking three-d's unit cylinder (along +X from 0 to 1, radius 1) onto the line from
/// `from` to `to` of `radius` metres.
fn segment_matrix(from: Vec3, to: Vec3, radius: f32) -> Mat4 {
    let along = to - from;
    let length = along.length();
    let rotation = Quat::from_rotation_arc(Vec3::X, along.normalize_or(Vec3::X));
    glam_to_three_d(GlamMat4::from_scale_rotation_translation(
        Vec3::new(length, radius, radius),
        rotation,
        from,
    ))
}

/// A glam matrix as three-d's (cgmath, also column-major).
fn glam_to_three_d(matrix: GlamMat4) -> Mat4 {
    Mat4::from(matrix.to_cols_array_2d())
}

/// A palette colour for three-d.
fn srgba(colour: Rgb) -> Srgba {
    let [red, green, blue] = colour.0;
    Srgba::new(red, green, blue, 255)
}
