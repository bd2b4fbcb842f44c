//! prism: a fast and accurate Whitted-style CPU ray tracer.
//!
//! The library has no window dependency: it loads scenes, traces them pass by pass into an
//! accumulator, and writes images. The `prism` binary adds the command line, the
//! interactive viewer and the bench on top.

pub mod camera;
pub mod first_hit;
pub mod geometry;
pub mod integrator;
pub mod light;
pub mod light_buffer;
pub mod limits;
pub mod material;
pub mod messages;
pub mod numerics;
pub mod render;
pub mod sampler;
pub mod scene;
pub mod simd;
pub mod texture;

/// The seed scene, shipped with the crate.
pub fn seed_scene_path() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/seed.toml")
}
