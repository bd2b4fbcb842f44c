//! What every fuzz target requires of a load, whatever its input: a scene, or a short,
//! printable message; and a scene that loads prepares and renders a few pixels to finite
//! colours.

use prism::render::RenderSettings;
use prism::scene::{PreparedScene, Scene};
use prism::scene_file::SceneError;
use std::sync::Arc;

pub fn check(result: Result<Scene, SceneError>) {
    match result {
        Err(e) => {
            let message = e.to_string();
            assert!(!message.is_empty());
            assert!(
                message.chars().count() < 2000,
                "a message of {} chars",
                message.len()
            );
            assert!(
                !message.chars().any(|c| c.is_control()),
                "a control character in {message:?}"
            );
        }
        Ok(scene) => {
            let prepared = Arc::new(PreparedScene::new(&scene));
            let settings = RenderSettings::new(6, 4, 1);
            let job = prism::render::render(prepared, scene.camera, settings, |_, _| {});
            for (i, p) in job.accumulator().pixels.iter().enumerate() {
                assert!(p.mean().is_finite(), "pixel {i} is {}", p.mean());
            }
        }
    }
}
