//! Every kind of object entry a scene file has, listed once. The file's tables
//! (`SceneFile`), the entry interface (`EntryDef`), the reading of every entry, placing one
//! entry again for an edit, and the tables an animation track may name are all made from
//! this list, so a new kind of shape is one line here (docs/architecture.md has the recipe).

/// Calls the macro `$then` with every kind of object entry, in the file's order: its
/// table's name, its definition, and how its objects are made: `shape READER`, one object
/// whose shape the validator's method `READER` makes from the entry and its placement; or
/// `mesh`, one object for each part of the file the entry names (meshes.rs).
macro_rules! object_kinds {
    ($then:ident) => {
        $then! {
            spheres: $crate::scene_file::shapes::SphereDef, shape sphere;
            cylinders: $crate::scene_file::shapes::CylinderDef, shape cylinder;
            polygons: $crate::scene_file::shapes::PolygonDef, shape polygon;
            triangles: $crate::scene_file::shapes::TriangleDef, shape triangle;
            tetrahedra: $crate::scene_file::shapes::TetrahedronDef, shape tetrahedron;
            meshes: $crate::scene_file::meshes::MeshDef, mesh;
            boxes: $crate::scene_file::shapes::BoxDef, shape cuboid;
            discs: $crate::scene_file::shapes::DiscDef, shape disc;
            planes: $crate::scene_file::shapes::PlaneDef, shape plane;
            cones: $crate::scene_file::shapes::ConeDef, shape cone;
            tori: $crate::scene_file::shapes::TorusDef, shape torus;
            capsules: $crate::scene_file::shapes::CapsuleDef, shape capsule;
            csg: $crate::scene_file::csg::CsgDef, shape csg;
        }
    };
}
pub(super) use object_kinds;
