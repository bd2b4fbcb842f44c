//! A scene to render frame by frame: a still scene, or an animated file whose frames are
//! the file with the tracks' values written in, each validated as any file is, the meshes
//! and images read once for all of them.

use super::animation::Animation;
use super::assets::Assets;
use super::error::SceneError;
use super::load::{load_scene_file_cached, parse_still};
use super::read_cache::ReadCache;
use crate::scene::Scene;
use std::path::{Path, PathBuf};

impl Animation {
    /// The scene at `frame`: the file `path` at that frame, validated, its files found by
    /// `assets`. A value out of bounds there is refused as `SceneError::Frame`.
    pub fn scene_at(&self, frame: u32, path: &Path, assets: Assets) -> Result<Scene, SceneError> {
        parse_still(&self.source_at(frame), path, assets, &mut Vec::new())
            .map(|(scene, _)| scene)
            .map_err(|error| SceneError::Frame {
                frame,
                error: Box::new(error),
            })
    }
}

/// A scene to render frame by frame: an animated scene file, or a still scene (whose only
/// frame is 0).
pub struct SceneFrames {
    kind: FramesKind,
    /// The files the first frame read, the scene file first.
    files: Vec<PathBuf>,
    /// The meshes and images the frames read, each once for all of them.
    cache: ReadCache,
}

enum FramesKind {
    Still(Scene),
    Animated {
        path: PathBuf,
        animation: std::sync::Arc<Animation>,
    },
}

impl SceneFrames {
    /// The scene file at `path`, animated or not, with its first frame validated (as
    /// `load_scene` does).
    pub fn load(path: &Path) -> Result<Self, SceneError> {
        let cache = ReadCache::default();
        let load = load_scene_file_cached(path, 0, &cache);
        let loaded = load.result?;
        let kind = match loaded.animation {
            None => FramesKind::Still(loaded.scene),
            Some(animation) => FramesKind::Animated {
                path: path.to_path_buf(),
                animation,
            },
        };
        Ok(Self {
            kind,
            files: load.files,
            cache,
        })
    }

    /// A still scene.
    pub fn fixed(scene: Scene) -> Self {
        Self {
            kind: FramesKind::Still(scene),
            files: Vec::new(),
            cache: ReadCache::default(),
        }
    }

    /// The files the scene reads (its first frame), the scene file first; none for a
    /// scene built in memory.
    pub fn files(&self) -> &[PathBuf] {
        &self.files
    }

    /// The animation, if the scene has one.
    pub fn animation(&self) -> Option<&Animation> {
        match &self.kind {
            FramesKind::Still(_) => None,
            FramesKind::Animated { animation, .. } => Some(animation),
        }
    }

    /// The scene at `frame` (a still scene is the same at every frame).
    pub fn frame(&self, frame: u32) -> Result<Scene, SceneError> {
        match &self.kind {
            FramesKind::Still(scene) => Ok(scene.clone()),
            FramesKind::Animated { path, animation } => {
                let base = path.parent().unwrap_or(Path::new("."));
                animation.scene_at(frame, path, Assets::Cached(base, &self.cache))
            }
        }
    }
}
