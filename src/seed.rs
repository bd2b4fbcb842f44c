//! The seed scene, built into the library with its texture, so that an installed prism
//! opens it from any folder without the source tree.

use crate::scene::Scene;
use crate::scene_file::{Assets, LoadedScene, SceneError, parse_loaded, parse_scene_with};
use std::path::Path;

/// The seed scene's file, as shipped in assets/scenes/seed.toml.
pub const SCENE_TOML: &str = include_str!("../assets/scenes/seed.toml");

/// The name messages give the built-in scene.
pub const NAME: &str = "seed.toml (built in)";

/// The files the seed scene names, by the paths it writes.
const FILES: &[(&str, &[u8])] = &[("../earth.jpg", include_bytes!("../assets/earth.jpg"))];

/// The seed scene, validated as any scene file is.
pub fn scene() -> Result<Scene, SceneError> {
    parse_scene_with(SCENE_TOML, Path::new(NAME), Assets::Embedded(FILES))
}

/// The seed scene with its file's text, to save an edited seed as a file of its own.
pub fn loaded() -> Result<LoadedScene, SceneError> {
    parse_loaded(SCENE_TOML, Path::new(NAME), Assets::Embedded(FILES))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_built_in_seed_is_the_shipped_file() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
        let shipped = crate::scene_file::load_scene(&dir.join("seed.toml")).unwrap();
        assert_eq!(scene().unwrap(), shipped);
    }
}
