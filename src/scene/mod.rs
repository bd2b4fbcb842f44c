//! Scenes: the description a file yields, and the prepared form the tracer runs on.
//!
//! ```text
//! scene file (TOML) ──parse──▶ SceneFile ──validate──▶ Scene ──prepare──▶ PreparedScene
//!                                                                      = Geometry + Appearance
//! ```

mod camera_table;
mod description;
mod edit;
mod error;
mod file;
mod geometry;
mod obj;
mod prepared;
mod spans;

pub use camera_table::camera_table;
pub use description::{RenderDefaults, Scene, SceneObject, ShapeDesc};
pub use edit::{EditError, check_camera};
pub use error::SceneError;
pub use file::{Assets, load_scene, parse_scene, parse_scene_with};
pub use geometry::{Geometry, ObjectGeometry, PlanarUv};
pub use obj::{LineError, ObjFile, ObjPart, parse_obj};
pub use prepared::PreparedScene;
