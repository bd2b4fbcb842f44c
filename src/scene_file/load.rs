//! Loading a scene file: reading its text (bounded, regular files only), parsing it (the
//! lexical pass first, then TOML, then the animation), and validating it into a `Scene`,
//! with what the viewer needs to edit and save it (`LoadedScene`).

use super::animation::Animation;
use super::assemble::{ObjectOrigin, SceneFile};
use super::assets::{Assets, read_text_file};
use super::brackets::scan_brackets;
use super::error::SceneError;
use super::error::{line_column, syntax_error};
use super::parse_tree::{Tree, parse_tree};
use super::read_cache::ReadCache;
use super::spans::FieldSpans;
use super::validator::Validator;
use crate::limits;
use crate::scene::Scene;
use serde::Deserialize;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Reads and validates the scene file at `path`; image textures are found relative to it.
pub fn load_scene(path: &Path) -> Result<Scene, SceneError> {
    load_scene_file(path).result.map(|loaded| loaded.scene)
}

/// A scene file as loaded, with what saving it back needs: its text, and where in the text
/// each object comes from.
#[derive(Clone, Debug)]
pub struct LoadedScene {
    /// The validated scene.
    pub scene: Scene,
    /// The file's text as read.
    pub source: String,
    /// For each of `scene.objects`, in order, the table entry it comes from.
    pub origins: Vec<ObjectOrigin>,
    /// The file's animation, if it has an `[animation]` table.
    pub animation: Option<Arc<Animation>>,
    /// The frame `scene` is (0 for a still scene).
    pub frame: u32,
}

impl LoadedScene {
    /// What the files its entries name (glTF scenes) hold that prism does not read, each
    /// entry's once, prefixed by the entry (`meshes[0]: extension KHR_texture_transform`).
    pub fn unread(&self) -> Vec<String> {
        let mut seen = Vec::new();
        let mut out = Vec::new();
        for o in &self.origins {
            if o.unread.is_empty() || seen.contains(&(o.table, o.index)) {
                continue;
            }
            seen.push((o.table, o.index));
            out.extend(
                o.unread
                    .iter()
                    .map(|u| format!("{}[{}]: {u}", o.table, o.index)),
            );
        }
        out
    }
}

/// The outcome of loading a scene file, and every file the attempt read or tried to read
/// (the scene file, textures, meshes, material libraries): what a viewer that reloads on
/// change watches, whether the load succeeded or not.
#[derive(Debug)]
pub struct SceneLoad {
    /// The scene, or why it was refused.
    pub result: Result<LoadedScene, SceneError>,
    /// The files read, the scene file first.
    pub files: Vec<PathBuf>,
}

/// Reads and validates the scene file at `path`, keeping what [`SceneLoad`] describes; an
/// animated file at its first frame.
pub fn load_scene_file(path: &Path) -> SceneLoad {
    load_scene_file_at(path, 0)
}

/// As [`load_scene_file`], at `frame` of the file's animation (the last frame for one past
/// it; a still file has only frame 0).
pub fn load_scene_file_at(path: &Path, frame: u32) -> SceneLoad {
    load_scene_file_cached(path, frame, &ReadCache::default())
}

/// As [`load_scene_file_at`], keeping the meshes and images read in `cache` (and taking
/// those read before from it).
pub(super) fn load_scene_file_cached(path: &Path, frame: u32, cache: &ReadCache) -> SceneLoad {
    let mut files = vec![path.to_path_buf()];
    let result = read_scene_text(path).and_then(|source| {
        let base = path.parent().unwrap_or(Path::new("."));
        let assets = Assets::Cached(base, cache);
        let (mut scene, origins, animation) = parse_recorded(&source, path, assets, &mut files)?;
        let frame = animation.as_ref().map_or(0, |a| frame.min(a.frames - 1));
        if let Some(animation) = &animation
            && frame > 0
        {
            scene = animation.scene_at(frame, path, assets)?;
        }
        Ok(LoadedScene {
            scene,
            source,
            origins,
            animation: animation.map(Arc::new),
            frame,
        })
    });
    SceneLoad { result, files }
}

/// The text of a scene file: a regular file of at most `MAX_SCENE_FILE_BYTES`, in UTF-8.
pub(super) fn read_scene_text(path: &Path) -> Result<String, SceneError> {
    read_text_file(path, limits::MAX_SCENE_FILE_BYTES, "scene file")
}

/// Validates scene text; `path` names it in messages, `base_dir` resolves texture paths.
pub fn parse_scene(source: &str, path: &Path, base_dir: &Path) -> Result<Scene, SceneError> {
    parse_scene_with(source, path, Assets::Folder(base_dir))
}

/// Validates scene text; `path` names it in messages, `assets` finds the files it names.
pub fn parse_scene_with(source: &str, path: &Path, assets: Assets) -> Result<Scene, SceneError> {
    parse_recorded(source, path, assets, &mut Vec::new()).map(|(scene, ..)| scene)
}

/// Validates scene text, keeping what saving it back needs (as [`load_scene_file`] does for
/// a file): for a scene that was not read from a file, such as the built-in seed.
pub fn parse_loaded(source: &str, path: &Path, assets: Assets) -> Result<LoadedScene, SceneError> {
    let (scene, origins, animation) = parse_recorded(source, path, assets, &mut Vec::new())?;
    Ok(LoadedScene {
        scene,
        source: source.to_string(),
        origins,
        animation: animation.map(Arc::new),
        frame: 0,
    })
}

/// Validates scene text, adding each file it reads to `files` (once) and returning each
/// object's origin with the scene.
#[allow(clippy::type_complexity)]
pub(super) fn parse_recorded(
    source: &str,
    path: &Path,
    assets: Assets,
    files: &mut Vec<PathBuf>,
) -> Result<(Scene, Vec<ObjectOrigin>, Option<Animation>), SceneError> {
    refuse_overlong_arrays(source, path)?;
    // An animated scene is validated at its first frame, as it renders by default.
    match Animation::parse(source, path)? {
        None => {
            let (scene, origins) = parse_still(source, path, assets, files)?;
            Ok((scene, origins, None))
        }
        Some(animation) => {
            // The file as written is a scene too (what it is with the animation taken
            // out): a value a track overwrites is checked as the file has it. Its files,
            // read once, serve the first frame.
            let cache = ReadCache::default();
            let assets = match assets.cache() {
                Some(_) => assets,
                None => assets.cached_in(&cache),
            };
            animation.validate_as_written(path, assets, files)?;
            let (scene, origins) = animation.frame_scene(0, path, assets, files)?;
            Ok((scene, origins, Some(animation)))
        }
    }
}

/// Refuses, before the parser reads it, an array longer than any field of the format takes
/// (the parser's memory for a number is many times its text).
pub(super) fn refuse_overlong_arrays(source: &str, path: &Path) -> Result<(), SceneError> {
    match scan_brackets(source, limits::MAX_ARRAY_ELEMENTS).overlong {
        Some(at) => {
            let (line, column) = line_column(source, at);
            Err(SceneError::Syntax {
                path: path.to_path_buf(),
                line,
                column,
                message: format!(
                    "an array of more than {} elements: no field takes that many",
                    limits::MAX_ARRAY_ELEMENTS
                ),
            })
        }
        None => Ok(()),
    }
}

/// Validates scene text as a still, its values as written (an `[animation]` table is
/// passed over: see `parse_recorded`).
pub(super) fn parse_still(
    source: &str,
    path: &Path,
    assets: Assets,
    files: &mut Vec<PathBuf>,
) -> Result<(Scene, Vec<ObjectOrigin>), SceneError> {
    validate_tree(&parse_tree(source, path)?, source, path, assets, files)
}

/// Validates the scene file whose text is `source` and whose parse tree is `tree` (which
/// may hold values the text does not: an animation's frame), adding each file it reads to
/// `files` (once).
pub(super) fn validate_tree(
    tree: &Tree,
    source: &str,
    path: &Path,
    assets: Assets,
    files: &mut Vec<PathBuf>,
) -> Result<(Scene, Vec<ObjectOrigin>), SceneError> {
    let file = read_tables(tree, source, path)?;
    let eye = file.camera.get_ref().eye;
    let v = Validator {
        path: path.to_path_buf(),
        source,
        spans: FieldSpans::of(tree),
        assets,
        origin: glam::DVec3::from(eye),
        reads: Default::default(),
        materials: Default::default(),
        groups: Default::default(),
    };
    let result = v.scene(file);
    for read in v.reads.into_inner() {
        if !files.contains(&read) {
            files.push(read);
        }
    }
    result
}

/// The file's tables, as written in the parse tree `tree` of `source`: the types and
/// names of fields, not yet their values.
pub(super) fn read_tables(tree: &Tree, source: &str, path: &Path) -> Result<SceneFile, SceneError> {
    SceneFile::deserialize(toml::de::Deserializer::from(tree.clone()))
        .map_err(|e| syntax_error(source, path, e.span(), e.message()))
}
