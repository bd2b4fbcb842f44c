//! A scene to render frame by frame: a still scene, or an animated file whose frames are
//! the file with the tracks' values written into its parse tree, each validated as any
//! file is. The text is parsed once, and the meshes and images read once, for all frames.

use super::animation::Animation;
use super::assemble::ObjectOrigin;
use super::assets::Assets;
use super::error::SceneError;
use super::load::{load_scene_file_cached, validate_tree};
use super::parse_tree::{Tree, set_field};
use super::read_cache::ReadCache;
use crate::scene::Scene;
use std::path::{Path, PathBuf};
use toml::de::DeValue;

impl Animation {
    /// The scene at `frame`: the file `path` at that frame, validated, its files found by
    /// `assets`. A value out of bounds there is refused as `SceneError::Frame`.
    pub fn scene_at(&self, frame: u32, path: &Path, assets: Assets) -> Result<Scene, SceneError> {
        self.frame_scene(frame, path, assets, &mut Vec::new())
            .map(|(scene, _)| scene)
    }

    /// The scene at `frame` with each object's origin, adding the files it reads to
    /// `files` (once).
    pub(super) fn frame_scene(
        &self,
        frame: u32,
        path: &Path,
        assets: Assets,
        files: &mut Vec<PathBuf>,
    ) -> Result<(Scene, Vec<ObjectOrigin>), SceneError> {
        self.with_frame_tree(frame, |tree, source| {
            validate_tree(tree, source, path, assets, files)
        })
        .map_err(|error| SceneError::Frame {
            frame,
            error: Box::new(error),
        })
    }

    /// Validates the file as written, but for its animation: a value a track overwrites
    /// is checked as the file has it.
    pub(super) fn validate_as_written(
        &self,
        path: &Path,
        assets: Assets,
        files: &mut Vec<PathBuf>,
    ) -> Result<(), SceneError> {
        let written = self.written();
        validate_tree(written.tree(), written.text(), path, assets, files).map(|_| ())
    }

    /// `f` of the file's parse tree at `frame` (every track's value written into its
    /// field) and of the text the tree's spans point into.
    pub(super) fn with_frame_tree<R>(&self, frame: u32, f: impl FnOnce(&Tree, &str) -> R) -> R {
        let values: Vec<String> = self.tracks.iter().map(|t| t.toml_at(frame)).collect();
        let written = self.written();
        let mut tree = written.tree().clone();
        for (track, value) in self.tracks.iter().zip(&values) {
            let value = DeValue::parse(value)
                .expect("a number or an array of numbers is TOML")
                .into_inner();
            // Every place was found when the animation was read, and no track can replace
            // a table that holds another's: tracks write fields of the tables they name.
            let found = set_field(&mut tree, track.place(), &track.field, value);
            assert!(found, "targets were found when the animation was read");
        }
        f(&tree, written.text())
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
    /// What the files its entries name hold that prism does not read (`LoadedScene::unread`).
    unread: Vec<String>,
}

enum FramesKind {
    Still(Box<Scene>),
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
        let unread = loaded.unread();
        let kind = match loaded.animation {
            None => FramesKind::Still(Box::new(loaded.scene)),
            Some(animation) => FramesKind::Animated {
                path: path.to_path_buf(),
                animation,
            },
        };
        Ok(Self {
            kind,
            files: load.files,
            cache,
            unread,
        })
    }

    /// What the files the scene's entries name hold that prism does not read.
    pub fn unread(&self) -> &[String] {
        &self.unread
    }

    /// A still scene.
    pub fn fixed(scene: Scene) -> Self {
        Self {
            kind: FramesKind::Still(Box::new(scene)),
            files: Vec::new(),
            cache: ReadCache::default(),
            unread: Vec::new(),
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
            FramesKind::Still(scene) => Ok(Scene::clone(scene)),
            FramesKind::Animated { path, animation } => {
                let base = path.parent().unwrap_or(Path::new("."));
                animation.scene_at(frame, path, Assets::Cached(base, &self.cache))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene_file::parse_tree::PARSES;

    /// Frames are made from the tree parsed at the load: rendering any number of them
    /// parses no text, and each equals a fresh load of the file at that frame.
    #[test]
    fn an_animation_is_parsed_once_for_all_its_frames() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.toml");
        let spheres: String = (0..200)
            .map(|i| format!("[[spheres]]\ncenter = [{i}, 0, -20]\nradius = 0.4\n"))
            .collect();
        let scene = format!(
            "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 40\n{spheres}\
             [animation]\nframes = 6\n[[animation.track]]\ntarget = \"spheres[3]\"\n\
             field = \"radius\"\n\
             keys = [{{ frame = 0, value = 0.5 }}, {{ frame = 5, value = 2.5 }}]\n"
        );
        std::fs::write(&path, scene).unwrap();
        let frames = SceneFrames::load(&path).unwrap();
        let parsed = PARSES.with(|count| count.get());
        let scenes: Vec<Scene> = (0..6).map(|f| frames.frame(f).unwrap()).collect();
        assert_eq!(
            PARSES.with(|count| count.get()),
            parsed,
            "no frame parsed text"
        );
        for (f, scene) in scenes.iter().enumerate() {
            let fresh = crate::scene_file::load_scene_file_at(&path, f as u32)
                .result
                .unwrap();
            assert_eq!(&fresh.scene, scene, "frame {f}");
        }
        let radius = |scene: &Scene| match scene.objects[3].shape {
            crate::scene::ShapeDesc::Sphere { radius, .. } => radius,
            _ => panic!("a sphere"),
        };
        assert_eq!(radius(&scenes[0]), 0.5);
        assert_eq!(radius(&scenes[5]), 2.5);
    }
}
