//! The scene model: what a scene is, whatever file it came from, and the prepared form the
//! tracer runs on. The file format that yields it is `scene_file`, which depends on this
//! module, never the reverse.
//!
//! ```text
//! scene file (TOML) ──scene_file──▶ Scene ──prepare──▶ PreparedScene
//!                                     ▲ edits            = Geometry + Appearance
//! ```

mod description;
mod edit;
mod geometry;
mod group;
mod placement;
mod prepared;

pub use description::{CsgMember, RenderDefaults, Scene, SceneObject, ShapeDesc};
pub use edit::{EditError, check_camera};
pub use geometry::{Geometry, ObjectGeometry, PlanarUv};
pub use group::{GroupKind, SceneGroup, group_chain, group_frame};
pub use placement::ObjectPlacement;
pub use prepared::{CoincidentSurfaces, PreparedScene};
