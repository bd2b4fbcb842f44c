//! Scenes: the description a file yields, and the prepared form the tracer runs on.
//!
//! ```text
//! scene file (TOML) ──parse──▶ SceneFile ──validate──▶ Scene ──prepare──▶ PreparedScene
//!                                                                      = Geometry + Appearance
//! ```

pub mod description;
pub mod edit;
pub mod error;
pub mod file;
mod geometry;
mod prepared;

pub use description::{RenderDefaults, Scene, SceneObject, ShapeDesc};
pub use error::SceneError;
pub use file::{load_scene, parse_scene};
pub use geometry::{Geometry, ObjectGeometry, PlanarUv};
pub use prepared::PreparedScene;
