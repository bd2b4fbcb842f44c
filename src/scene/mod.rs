//! Scenes: the description a file yields, and the prepared form the tracer runs on.
//!
//! ```text
//! scene file (TOML) ──parse──▶ SceneFile ──validate──▶ Scene ──prepare──▶ PreparedScene
//!                                                                      = Geometry + Appearance
//! ```

mod animation;
mod camera_table;
mod description;
mod edit;
mod error;
mod file;
mod geometry;
mod obj;
mod prepared;
mod save;
mod spans;

pub use animation::{Animation, Interpolation, Key, OBJECT_TABLES, SceneFrames, Track};
pub use camera_table::camera_table;
pub use description::{ObjectPlacement, RenderDefaults, Scene, SceneObject, ShapeDesc};
pub use edit::{EditError, check_camera};
pub use error::SceneError;
pub use file::{
    Assets, LoadedScene, ObjectOrigin, ReadCache, SceneLoad, load_scene, load_scene_file,
    load_scene_file_at, parse_loaded, parse_scene, parse_scene_with,
};
pub use geometry::{Geometry, ObjectGeometry, PlanarUv};
pub use obj::{LineError, ObjFile, ObjPart, parse_obj};
pub use prepared::{CoincidentSurfaces, PreparedScene};
pub use save::{SaveError, SavedText, saved_text};
