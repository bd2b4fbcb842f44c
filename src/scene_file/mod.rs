//! The TOML scene format (documented in docs/scene-format.md), into the scene model
//! (`crate::scene`), which knows nothing of it: loading (load.rs), the whole file's tables in
//! order (assemble.rs), each table's reader by subject (camera, lights, render_table,
//! textures, materials, shapes and solids, meshes with OBJ and MTL), every problem named by
//! its file, line and field (validator.rs, spans.rs, error.rs); entries and their placement;
//! animation; saving edits back into the file.

mod animation;
mod assemble;
mod assets;
mod brackets;
mod camera;
mod camera_table;
mod csg;
mod entry;
mod entry_def;
mod error;
mod fixed_array;
mod frames;
mod glb;
mod gltf_file;
mod gltf_materials;
mod gltf_nodes;
mod gltf_scene;
mod group_edit;
mod groups;
mod kinds;
mod lights;
mod line_error;
mod load;
mod materials;
mod meshes;
mod mtl;
mod obj;
mod obj_corner;
mod obj_join;
mod obj_number;
mod obj_text;
mod obj_vertices;
mod parse_tree;
mod placement;
mod read_cache;
mod render_table;
mod save;
mod shapes;
mod spans;
mod textures;
mod validator;

pub use animation::{Animation, Interpolation, Key, OBJECT_TABLES, Track};
pub use assemble::ObjectOrigin;
pub use assets::Assets;
pub use camera_table::camera_table;
pub use error::SceneError;
pub use frames::SceneFrames;
pub use glb::glb_file;
pub use load::{
    LoadedScene, SceneLoad, load_scene, load_scene_file, load_scene_file_at, parse_loaded,
    parse_scene, parse_scene_with,
};
pub use obj::{LineError, ObjFile, ObjPart, parse_obj};
pub use read_cache::ReadCache;
pub use save::{SaveError, SavedText, saved_text};
pub use shapes::check_polygon;
