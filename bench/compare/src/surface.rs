//! Piles on a heightfield or a triangle mesh: how far the bodies go below its surface, measured
//! the same way in both engines from the bodies' poses, with rebond's ray casts against the
//! ground alone.

use crate::rebond_engine::rebond_shape;
use crate::scenes::{Scene, ShapeSpec};
use rebond::{BodyDesc, Quat, QueryFilter, Ray, Shape, Vec3, World, WorldSettings};

/// The ground of a pile scene, and the shapes of its dynamic bodies.
pub struct Surface {
    /// A world holding only the ground.
    ground: World,
    /// A height above the whole ground, metres: where the rays down start.
    top: f32,
    /// The dynamic bodies' shapes, in scene order.
    shapes: Vec<Shape>,
}

impl Surface {
    /// The first fixed heightfield or mesh of `scene` with its dynamic bodies' shapes, or `None`
    /// when the scene has neither.
    pub fn of(scene: &Scene) -> Option<Self> {
        let spec = scene.bodies.iter().find(|body| {
            body.fixed
                && matches!(
                    body.shape,
                    ShapeSpec::HeightField { .. } | ShapeSpec::TriMesh { .. }
                )
        })?;
        let mut ground = World::new(WorldSettings::default()).expect("settings");
        let handle = ground
            .add_body(
                BodyDesc::static_body(rebond_shape(&spec.shape))
                    .position(Vec3::from(spec.position))
                    .rotation(Quat::from_scaled_axis(Vec3::from(spec.rotation))),
            )
            .expect("valid ground");
        let body = ground.body(handle).expect("ground");
        let top = body.shape().aabb(&body.pose()).max.y + 1.0;
        let shapes = scene
            .bodies
            .iter()
            .filter(|body| !body.fixed)
            .map(|body| rebond_shape(&body.shape))
            .collect();
        Some(Self {
            ground,
            top,
            shapes,
        })
    }

    /// The height of the ground's top surface over `(x, z)` and its normal there, or `None` off
    /// the ground.
    pub fn under(&self, x: f32, z: f32) -> Option<(f32, Vec3)> {
        let ray = Ray::new(Vec3::new(x, self.top, z), Vec3::NEG_Y);
        let hit = self
            .ground
            .cast_ray(&ray, &QueryFilter::new())
            .expect("valid ray")?;
        Some((hit.point.y, hit.normal))
    }

    /// How far below the surface a point is, straight down, metres (negative above it; 0 off the
    /// ground).
    fn depth(&self, point: Vec3) -> f32 {
        self.under(point.x, point.z)
            .map_or(0.0, |(height, _)| height - point.y)
    }

    /// The deepest any dynamic body reaches below the surface, straight down, metres (0 when none
    /// does). Two points of each body are tested: its lowest point, and its farthest point
    /// against the surface normal under its centre (the point that touches a slope).
    pub fn deepest(&self, positions: &[[f32; 3]], rotations: &[[f32; 4]]) -> f32 {
        let mut deepest = 0.0f32;
        for ((shape, position), rotation) in self.shapes.iter().zip(positions).zip(rotations) {
            let (position, rotation) = (Vec3::from(*position), Quat::from_array(*rotation));
            let normal = self
                .under(position.x, position.z)
                .map_or(Vec3::Y, |(_, normal)| normal);
            for direction in [Vec3::NEG_Y, -normal] {
                let local = rotation.inverse() * direction;
                if let Some(support) = shape.support(local) {
                    deepest = deepest.max(self.depth(position + rotation * support));
                }
            }
        }
        deepest
    }

    /// Dynamic bodies that left the ground: not finite, off its edge, or with their centre below
    /// the surface.
    pub fn escaped(&self, positions: &[[f32; 3]]) -> usize {
        positions
            .iter()
            .filter(|p| {
                !p.iter().all(|c| c.is_finite())
                    || self
                        .under(p[0], p[2])
                        .is_none_or(|(height, _)| p[1] < height)
            })
            .count()
    }
}

#[cfg(test)]
mod tests {
    use crate::rapier_engine::RapierEngine;
    use crate::rebond_engine::RebondEngine;
    use crate::scenes::{build_scene, terrain, ShapeSpec};
    use crate::Engine;

    /// The ground of each pile scene is the same surface in both engines: rays cast straight
    /// down on a grid of points that falls inside cells on both sides of their diagonals, and
    /// slanted rays, meet it at the same distance in both, to 0.1 mm.
    #[test]
    fn grounds_agree() {
        for name in ["terrain_pile", "mesh_pile"] {
            let mut scene = build_scene(name);
            scene.bodies.retain(|body| body.fixed);
            let mut rebond_engine = RebondEngine::new(&scene);
            let mut rapier_engine = RapierEngine::new(&scene);
            rebond_engine.step();
            rapier_engine.step();
            let pipeline = rapier_engine.world.query_pipeline();
            let mut hits = 0;
            for k in 0..4000 {
                let (x, z) = (
                    -30.0 + 0.0153 * k as f32,
                    -29.7 + 0.0271 * (k % 2213) as f32,
                );
                let direction = if k % 2 == 0 {
                    [0.0, -1.0, 0.0]
                } else {
                    [0.3, -1.0, -0.2]
                };
                let origin = [x, 20.0, z];
                let rebond_ray = rebond::Ray::new(origin.into(), direction.into());
                let rebond_distance = rebond_engine
                    .world
                    .cast_ray(&rebond_ray, &rebond::QueryFilter::new())
                    .expect("valid ray")
                    .map(|hit| hit.distance);
                let rapier_ray = {
                    use rapier3d::prelude::{Ray, Vector};
                    Ray::new(Vector::from_array(origin), Vector::from_array(direction))
                };
                let rapier_distance = pipeline
                    .cast_ray(&rapier_ray, f32::MAX, true)
                    .map(|(_, distance)| distance * rapier_ray.dir.length());
                match (rebond_distance, rapier_distance) {
                    (Some(a), Some(b)) => {
                        assert!(
                            (a - b).abs() < 1e-4,
                            "{name}: ray {k} from {origin:?}: rebond {a} m, rapier {b} m"
                        );
                        hits += 1;
                    }
                    (None, None) => {}
                    other => panic!("{name}: ray {k} from {origin:?}: {other:?}"),
                }
            }
            assert!(hits > 3500, "{name}: {hits} hits");
        }
    }

    /// The terrain's heights are those of the built-in `terrain` scene.
    #[test]
    fn terrain_is_the_builtin_one() {
        let ShapeSpec::HeightField { heights, scale } = terrain() else {
            unreachable!()
        };
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/terrain.json");
        let builtin = rebond::scene::Scene::from_file(path).expect("terrain.json");
        let (_, body) = builtin
            .bodies()
            .find(|(name, _)| *name == "terrain")
            .expect("a body named terrain");
        let rebond::Shape::HeightField(field) = body.shape() else {
            panic!("the terrain is not a heightfield");
        };
        assert_eq!(field.scale().to_array(), scale);
        assert_eq!(
            (field.rows(), field.cols()),
            (heights.len(), heights[0].len())
        );
        for (i, row) in heights.iter().enumerate() {
            for (j, &height) in row.iter().enumerate() {
                assert_eq!(
                    field.sample(i, j).expect("inside").y,
                    height,
                    "sample ({i}, {j})"
                );
            }
        }
    }
}
