//! Ray casts against bodies, for picking a body under the mouse. The engine has no ray cast, so
//! the viewer keeps its own: a slab test against each body's bounding box, then an exact test
//! against its shape in the body frame.

use rebond::shape::{Capsule, ConvexHull, Cuboid, Cylinder, Halfspace};
use rebond::{Aabb, BodyHandle, Pose, Shape, Vec3, World};

/// A half-line: `origin + t · direction` for `t ≥ 0`, with a unit `direction`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Where the ray starts, world metres.
    pub origin: Vec3,
    /// Unit direction.
    pub direction: Vec3,
}

impl Ray {
    /// The point at distance `distance` along the ray.
    pub fn at(&self, distance: f32) -> Vec3 {
        self.origin + distance * self.direction
    }

    /// The same ray seen in the frame of `pose` (a local ray of a shape placed at `pose`).
    fn to_local(self, pose: &Pose) -> Ray {
        Ray {
            origin: pose.inverse_transform_point(self.origin),
            direction: pose.inverse_transform_vector(self.direction),
        }
    }
}

/// The body a ray meets first.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// The body.
    pub body: BodyHandle,
    /// Distance along the ray to the surface, metres.
    pub distance: f32,
}

/// The first body along `ray`, if any.
pub fn pick(world: &World, ray: &Ray) -> Option<Hit> {
    world
        .bodies()
        .filter(|(_, body)| ray_box(ray, &body.aabb()).is_some())
        .filter_map(|(handle, body)| {
            ray_shape(ray, body.shape(), &body.pose()).map(|distance| Hit {
                body: handle,
                distance,
            })
        })
        .min_by(|a, b| a.distance.total_cmp(&b.distance))
}

/// Distance along `ray` to where it enters `shape` placed at `pose`; zero when it starts inside.
pub fn ray_shape(ray: &Ray, shape: &Shape, pose: &Pose) -> Option<f32> {
    let local = ray.to_local(pose);
    match shape {
        Shape::Sphere(sphere) => ray_sphere(&local, Vec3::ZERO, sphere.radius()),
        Shape::Cuboid(cuboid) => ray_cuboid(&local, cuboid),
        Shape::Capsule(capsule) => ray_capsule(&local, capsule),
        Shape::Cylinder(cylinder) => ray_cylinder(&local, cylinder),
        Shape::ConvexHull(hull) => ray_hull(&local, hull),
        Shape::Compound(compound) => compound
            .children()
            .iter()
            .filter_map(|child| ray_shape(&local, &child.shape, &child.pose))
            .min_by(f32::total_cmp),
        Shape::Halfspace(halfspace) => ray_halfspace(&local, halfspace),
        // Level geometry is static: nothing to pick and drag.
        Shape::TriMesh(_) | Shape::HeightField(_) => None,
    }
}

/// Distance to where the ray enters the box `bounds` (slab test), zero when it starts inside.
fn ray_box(ray: &Ray, bounds: &Aabb) -> Option<f32> {
    let mut enter = 0.0_f32;
    let mut exit = f32::INFINITY;
    for axis in 0..3 {
        let origin = ray.origin[axis];
        let direction = ray.direction[axis];
        if direction.abs() < 1e-12 {
            if origin < bounds.min[axis] || origin > bounds.max[axis] {
                return None;
            }
            continue;
        }
        let near = (bounds.min[axis] - origin) / direction;
        let far = (bounds.max[axis] - origin) / direction;
        enter = enter.max(near.min(far));
        exit = exit.min(near.max(far));
        if enter > exit {
            return None;
        }
    }
    Some(enter)
}

/// The smaller root `t ≥ 0` of `a t² + 2 b t + c = 0` (zero when `c ≤ 0`, the start inside).
fn first_root(a: f32, b: f32, c: f32) -> Option<f32> {
    if c <= 0.0 {
        return Some(0.0);
    }
    let discriminant = b * b - a * c;
    if a <= 0.0 || discriminant < 0.0 {
        return None;
    }
    let root = (-b - discriminant.sqrt()) / a;
    (root >= 0.0).then_some(root)
}

fn ray_sphere(ray: &Ray, center: Vec3, radius: f32) -> Option<f32> {
    let offset = ray.origin - center;
    first_root(
        ray.direction.length_squared(),
        offset.dot(ray.direction),
        offset.length_squared() - radius * radius,
    )
}

fn ray_cuboid(ray: &Ray, cuboid: &Cuboid) -> Option<f32> {
    let half = cuboid.half_extents();
    ray_box(ray, &Aabb::new(-half, half))
}

/// Where the ray enters the infinite cylinder of `radius` about the Y axis, if it does so with
/// `|y| ≤ half_height`; zero when it starts inside that finite cylinder.
fn ray_cylinder_side(ray: &Ray, radius: f32, half_height: f32) -> Option<f32> {
    let (origin, direction) = (ray.origin, ray.direction);
    let distance = first_root(
        direction.x * direction.x + direction.z * direction.z,
        origin.x * direction.x + origin.z * direction.z,
        origin.x * origin.x + origin.z * origin.z - radius * radius,
    )?;
    (ray.at(distance).y.abs() <= half_height).then_some(distance)
}

fn ray_capsule(ray: &Ray, capsule: &Capsule) -> Option<f32> {
    let [bottom, top] = capsule.segment();
    [
        ray_cylinder_side(ray, capsule.radius(), capsule.half_height()),
        ray_sphere(ray, bottom, capsule.radius()),
        ray_sphere(ray, top, capsule.radius()),
    ]
    .into_iter()
    .flatten()
    .min_by(f32::total_cmp)
}

fn ray_cylinder(ray: &Ray, cylinder: &Cylinder) -> Option<f32> {
    let (radius, half_height) = (cylinder.radius(), cylinder.half_height());
    let caps = [-half_height, half_height].into_iter().filter_map(|y| {
        if ray.direction.y.abs() < 1e-12 {
            return None;
        }
        let distance = (y - ray.origin.y) / ray.direction.y;
        let point = ray.at(distance);
        (distance >= 0.0 && point.x * point.x + point.z * point.z <= radius * radius)
            .then_some(distance)
    });
    ray_cylinder_side(ray, radius, half_height)
        .into_iter()
        .chain(caps)
        .min_by(f32::total_cmp)
}

/// Clips the ray by every face plane of the hull (Cyrus–Beck).
fn ray_hull(ray: &Ray, hull: &ConvexHull) -> Option<f32> {
    let mut enter = 0.0_f32;
    let mut exit = f32::INFINITY;
    for face in hull.faces() {
        let height = face.normal.dot(ray.origin) - face.offset;
        let approach = face.normal.dot(ray.direction);
        if approach.abs() < 1e-12 {
            if height > 0.0 {
                return None;
            }
            continue;
        }
        let crossing = -height / approach;
        if approach < 0.0 {
            enter = enter.max(crossing);
        } else {
            exit = exit.min(crossing);
        }
        if enter > exit {
            return None;
        }
    }
    Some(enter)
}

fn ray_halfspace(ray: &Ray, halfspace: &Halfspace) -> Option<f32> {
    let normal = halfspace.normal();
    let height = normal.dot(ray.origin);
    if height <= 0.0 {
        return Some(0.0);
    }
    let approach = normal.dot(ray.direction);
    (approach < 0.0).then(|| -height / approach)
}

#[cfg(test)]
mod tests {
    use rebond::shape::CompoundChild;
    use rebond::{BodyDesc, Quat, WorldSettings};

    use super::*;

    /// A ray from `origin` toward `toward`.
    fn ray(origin: [f32; 3], toward: [f32; 3]) -> Ray {
        let origin = Vec3::from(origin);
        Ray {
            origin,
            direction: (Vec3::from(toward) - origin).normalize(),
        }
    }

    fn cast(shape: &Shape, ray: &Ray) -> Option<f32> {
        ray_shape(ray, shape, &Pose::IDENTITY)
    }

    fn assert_near(actual: Option<f32>, expected: f32) {
        let actual = actual.expect("a hit");
        assert!((actual - expected).abs() < 1e-4, "{actual} vs {expected}");
    }

    #[test]
    fn every_shape_is_hit_at_its_surface_and_missed_beside_it() {
        let down = ray([0.0, 10.0, 0.0], [0.0, 0.0, 0.0]);
        let beside = ray([5.0, 10.0, 0.0], [5.0, 0.0, 0.0]);
        let hull = Shape::convex_hull(&[
            Vec3::new(-1.0, -1.0, -1.0),
            Vec3::new(1.0, -1.0, -1.0),
            Vec3::new(0.0, -1.0, 1.0),
            Vec3::new(0.0, 2.0, 0.0),
        ])
        .expect("a tetrahedron");
        let compound = Shape::compound(vec![CompoundChild::new(
            Shape::sphere(0.5).expect("a sphere"),
            Pose::from_position(Vec3::new(0.0, 1.0, 0.0)),
        )])
        .expect("a compound");
        let cases = [
            (Shape::sphere(1.0), 9.0),
            (Shape::cuboid(Vec3::new(1.0, 2.0, 1.0)), 8.0),
            (Shape::capsule(0.5, 1.0), 8.5),
            (Shape::cylinder(0.5, 1.0), 9.0),
            (Ok(hull), 8.0),
            (Ok(compound), 8.5),
        ];
        for (shape, distance) in cases {
            let shape = shape.expect("a valid shape");
            assert_near(cast(&shape, &down), distance);
            assert_eq!(cast(&shape, &beside), None, "{shape:?}");
        }
    }

    #[test]
    fn sideways_rays_meet_the_sides_of_round_shapes() {
        let side = ray([10.0, 0.2, 0.0], [0.0, 0.2, 0.0]);
        for shape in [Shape::capsule(0.5, 1.0), Shape::cylinder(0.5, 1.0)] {
            assert_near(cast(&shape.expect("a valid shape"), &side), 9.5);
        }
        let above_cylinder = ray([10.0, 1.2, 0.0], [0.0, 1.2, 0.0]);
        let cylinder = Shape::cylinder(0.5, 1.0).expect("a cylinder");
        assert_eq!(cast(&cylinder, &above_cylinder), None);
        let capsule = Shape::capsule(0.5, 1.0).expect("a capsule");
        assert!(
            cast(&capsule, &above_cylinder).is_some(),
            "the capsule's cap"
        );
    }

    #[test]
    fn rays_starting_inside_hit_at_zero_and_halfspaces_hit_from_above_only() {
        let inside = ray([0.1, 0.0, 0.0], [1.0, 1.0, 1.0]);
        assert_near(cast(&Shape::sphere(1.0).expect("a sphere"), &inside), 0.0);
        let ground = Shape::halfspace(Vec3::Y).expect("a halfspace");
        assert_near(cast(&ground, &ray([0.0, 3.0, 0.0], [3.0, -1.0, 0.0])), 3.75);
        assert_eq!(cast(&ground, &ray([0.0, 3.0, 0.0], [0.0, 4.0, 0.0])), None);
    }

    #[test]
    fn posed_shapes_are_hit_where_they_are() {
        let pose = Pose::new(
            Vec3::new(3.0, 0.0, 0.0),
            Quat::from_rotation_z(std::f32::consts::FRAC_PI_2),
        );
        let capsule = Shape::capsule(0.5, 2.0).expect("a capsule");
        let down = ray([4.5, 10.0, 0.0], [4.5, 0.0, 0.0]);
        assert_near(ray_shape(&down, &capsule, &pose), 9.5);
    }

    #[test]
    fn pick_finds_the_nearest_body() {
        let mut world = World::new(WorldSettings::default()).expect("a world");
        let far = world
            .add_body(BodyDesc::static_body(Shape::sphere(1.0).expect("a sphere")))
            .expect("added");
        let near = world
            .add_body(
                BodyDesc::dynamic(Shape::sphere(1.0).expect("a sphere"))
                    .position(Vec3::new(0.0, 5.0, 0.0)),
            )
            .expect("added");
        let down = ray([0.0, 10.0, 0.0], [0.0, 0.0, 0.0]);
        let hit = pick(&world, &down).expect("a hit");
        assert_eq!(hit.body, near);
        assert!((hit.distance - 4.0).abs() < 1e-4);
        let up = ray([0.0, -10.0, 0.0], [0.0, 0.0, 0.0]);
        assert_eq!(pick(&world, &up).map(|hit| hit.body), Some(far));
        assert_eq!(pick(&world, &ray([9.0, 10.0, 0.0], [9.0, 0.0, 0.0])), None);
    }
}
