//! Meshes and heightfields are shared, not copied, refused on dynamic bodies, and checked.

use rebond::{BodyDesc, ErrorKind, Shape, Vec3, World, WorldSettings};

use super::floor_mesh;

#[test]
fn cloning_a_mesh_shape_body_or_world_shares_its_triangles() {
    let mesh = floor_mesh(10.0, 10);
    let Shape::TriMesh(original) = &mesh else {
        panic!("a trimesh")
    };
    let desc = BodyDesc::static_body(mesh.clone());
    let mut world = World::new(WorldSettings::default()).unwrap();
    let handle = world.add_body(desc.clone()).unwrap();
    let copy = world.clone();
    for shape in [
        &mesh.clone(),
        &desc.shape,
        copy.body(handle).unwrap().shape(),
    ] {
        let Shape::TriMesh(shared) = shape else {
            panic!("a trimesh")
        };
        assert!(shared.shares_geometry(original));
    }
}

#[test]
fn meshes_and_heightfields_are_refused_on_dynamic_bodies() {
    let mut world = World::new(WorldSettings::default()).unwrap();
    let heightfield =
        Shape::heightfield(&[vec![0.0, 1.0], vec![0.5, 0.0]], Vec3::splat(2.0)).unwrap();
    for shape in [floor_mesh(1.0, 1), heightfield] {
        let error = world.add_body(BodyDesc::dynamic(shape)).unwrap_err();
        assert_eq!(error.field, "shape");
        assert_eq!(error.kind, ErrorKind::MeshOnDynamicBody);
    }
}

#[test]
fn bad_mesh_and_heightfield_input_names_its_place() {
    let square = vec![Vec3::ZERO, Vec3::X, Vec3::Z];
    let error = Shape::trimesh(square.clone(), &[[0, 1, 2], [0, 2, 3]]).unwrap_err();
    assert_eq!(error.field, "indices[1]");
    let error = Shape::trimesh(square.clone(), &[[0, 1, 1]]).unwrap_err();
    assert_eq!(
        (error.field.as_str(), error.kind),
        ("indices", ErrorKind::EmptyMesh)
    );
    let error = Shape::trimesh(vec![Vec3::ZERO, Vec3::NAN], &[[0, 1, 1]]).unwrap_err();
    assert_eq!(error.field, "vertices[1]");
    // Each coordinate within the size limit, the vertex beyond it: as a hull's point would be.
    let far = Vec3::new(0.9, 0.9, 0.0) * rebond::limits::MAX_SIZE;
    let error = Shape::trimesh(vec![Vec3::ZERO, Vec3::X, far], &[[0, 1, 2]]).unwrap_err();
    assert_eq!(error.field, "vertices[2]");
    assert!(matches!(error.kind, ErrorKind::TooLarge { .. }));
    let error = Shape::heightfield(&[vec![0.0, 1.0], vec![0.5]], Vec3::ONE).unwrap_err();
    assert_eq!(error.field, "heights[1]");
    let error = Shape::heightfield(&[vec![0.0, 1.0]], Vec3::ONE).unwrap_err();
    assert_eq!(error.field, "heights");
    let error = Shape::heightfield(&[vec![0.0, 1.0], vec![f32::NAN, 0.0]], Vec3::ONE).unwrap_err();
    assert_eq!(error.field, "heights[1][0]");
    let error = Shape::heightfield(&[vec![0.0, 1.0], vec![0.0, 0.0]], Vec3::new(1.0, 0.0, 1.0))
        .unwrap_err();
    assert_eq!(error.field, "scale[1]");
}

#[test]
fn zero_area_triangles_are_skipped() {
    let vertices = vec![Vec3::ZERO, Vec3::X, Vec3::Z, Vec3::new(2.0, 0.0, 0.0)];
    let Shape::TriMesh(mesh) = Shape::trimesh(vertices, &[[0, 1, 3], [0, 2, 1]]).unwrap() else {
        panic!("a trimesh")
    };
    assert_eq!(mesh.indices(), &[[0, 2, 1]]);
}
