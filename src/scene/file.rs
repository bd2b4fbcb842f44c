//! The TOML scene format (documented in docs/scene-format.md): parsing, and validation that
//! names the file, the line and the field of every problem.

mod brackets;
mod entry;
mod entry_def;
mod fixed_array;
mod meshes;
mod placement;
mod read_cache;
mod solids;

use super::description::{RenderDefaults, Scene, SceneObject, ShapeDesc};
use super::error::{SceneError, line_column};
use super::spans::FieldSpans;
use crate::appearance::{AreaShape, Background, Falloff, Fog, FogKind, Light, LightKind, SpotCone};
use crate::appearance::{ImageTexture, Texture, TextureError, UvTransform};
use crate::appearance::{Material, RADIANCE_BOUND, REFLECTANCE_BOUND};
use crate::camera::Camera;
use crate::limits;
use crate::messages::{did_you_mean, number, outside_color_range, outside_range, quoted};
use entry::entry_label;
use entry_def::EntryDef;
use fixed_array::Fixed;
use glam::Vec3;
use placement::Placement;
pub use read_cache::ReadCache;
use serde::Deserialize;
use std::collections::{BTreeMap, HashMap};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use toml::Spanned;

type V3 = Fixed<f32, 3>;
/// Positions are read in f64 and stored relative to the scene origin (see `Scene`).
type P3 = Fixed<f64, 3>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    camera: Spanned<CameraDef>,
    render: Option<Spanned<RenderDef>>,
    fog: Option<Spanned<FogDef>>,
    #[serde(default)]
    lights: Vec<Spanned<LightDef>>,
    #[serde(default)]
    textures: BTreeMap<String, Spanned<TextureDef>>,
    #[serde(default)]
    materials: BTreeMap<String, Spanned<MaterialDef>>,
    #[serde(default)]
    spheres: Vec<Spanned<SphereDef>>,
    #[serde(default)]
    cylinders: Vec<Spanned<CylinderDef>>,
    #[serde(default)]
    polygons: Vec<Spanned<PolygonDef>>,
    #[serde(default)]
    triangles: Vec<Spanned<TriangleDef>>,
    #[serde(default)]
    tetrahedra: Vec<Spanned<TetrahedronDef>>,
    #[serde(default)]
    meshes: Vec<Spanned<MeshDef>>,
    #[serde(default)]
    boxes: Vec<Spanned<solids::BoxDef>>,
    #[serde(default)]
    discs: Vec<Spanned<solids::DiscDef>>,
    #[serde(default)]
    planes: Vec<Spanned<solids::PlaneDef>>,
    #[serde(default)]
    cones: Vec<Spanned<solids::ConeDef>>,
    #[serde(default)]
    tori: Vec<Spanned<solids::TorusDef>>,
    /// Read by animation.rs; a still frame's validation passes over it.
    #[allow(dead_code)]
    animation: Option<serde::de::IgnoredAny>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraDef {
    eye: P3,
    look_at: Option<P3>,
    direction: Option<V3>,
    yaw: Option<f32>,
    pitch: Option<f32>,
    up: Option<V3>,
    fov: f32,
    aperture: Option<f32>,
    focus_distance: Option<f32>,
    handedness: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FogDef {
    color: Option<V3>,
    density: Option<f32>,
    start: Option<f32>,
    end: Option<f32>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RenderDef {
    width: Option<i64>,
    height: Option<i64>,
    aa: Option<i64>,
    samples: Option<i64>,
    max_depth: Option<i64>,
    /// `[r, g, b]`, or a table: `{ bottom = …, top = … }` or `{ image = "…" }` (read by
    /// hand, for messages that say which form was meant).
    background: Option<toml::Value>,
    ambient: Option<V3>,
    encoding: Option<String>,
    exposure: Option<f32>,
}

/// A `background` value, by form.
enum BackgroundDef {
    Color(V3),
    Gradient { bottom: V3, top: V3 },
    Image(String),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LightDef {
    #[serde(rename = "type")]
    kind: Option<String>,
    position: Option<P3>,
    direction: Option<V3>,
    color: Option<V3>,
    falloff: Option<String>,
    intensity: Option<f32>,
    corner: Option<P3>,
    edge_u: Option<V3>,
    edge_v: Option<V3>,
    radius: Option<f32>,
    angle: Option<f32>,
    softness: Option<f32>,
    visible: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TextureDef {
    #[serde(rename = "type")]
    kind: String,
    path: Option<String>,
    colors: Option<Fixed<V3, 2>>,
    size: Option<f32>,
    axes: Option<String>,
    width: Option<f32>,
    direction: Option<V3>,
    /// A number (both ways) or [u, v].
    uv_scale: Option<toml::Value>,
    uv_offset: Option<Fixed<f32, 2>>,
    uv_rotate: Option<f32>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialDef {
    color: Option<V3>,
    texture: Option<String>,
    ambient: Option<f32>,
    diffuse: Option<f32>,
    specular: Option<f32>,
    shininess: Option<f32>,
    reflectivity: Option<f32>,
    transparency: Option<f32>,
    eta: Option<f32>,
    emission: Option<V3>,
    fresnel: Option<bool>,
    roughness: Option<f32>,
    absorption: Option<V3>,
    conductor: Option<V3>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SphereDef {
    name: Option<String>,
    center: P3,
    radius: f32,
    material: Option<String>,
    shadow: Option<bool>,
    translate: Option<P3>,
    rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    scale: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CylinderDef {
    name: Option<String>,
    base: P3,
    radius: f32,
    height: f32,
    caps: Option<bool>,
    material: Option<String>,
    shadow: Option<bool>,
    translate: Option<P3>,
    rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    scale: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PolygonDef {
    name: Option<String>,
    vertices: Vec<P3>,
    material: Option<String>,
    shadow: Option<bool>,
    translate: Option<P3>,
    rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    scale: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TriangleDef {
    name: Option<String>,
    vertices: Fixed<P3, 3>,
    material: Option<String>,
    shadow: Option<bool>,
    translate: Option<P3>,
    rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    scale: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TetrahedronDef {
    name: Option<String>,
    vertices: Fixed<P3, 4>,
    material: Option<String>,
    shadow: Option<bool>,
    translate: Option<P3>,
    rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    scale: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MeshDef {
    name: Option<String>,
    path: String,
    material: Option<String>,
    smooth: Option<bool>,
    shadow: Option<bool>,
    translate: Option<P3>,
    rotate: Option<V3>,
    /// A number or [sx, sy, sz].
    scale: Option<toml::Value>,
}

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
    pub animation: Option<Arc<super::animation::Animation>>,
    /// The frame `scene` is (0 for a still scene).
    pub frame: u32,
}

/// The entry of a scene file that made an object.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjectOrigin {
    /// The array of tables it is in: "spheres", "boxes", "meshes", ….
    pub table: &'static str,
    /// Its index in that array.
    pub index: usize,
    /// The name of the `[materials]` entry it uses; None for the default material or for
    /// a mesh part whose material comes from the mesh's own MTL file.
    pub material: Option<String>,
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
fn read_scene_text(path: &Path) -> Result<String, SceneError> {
    read_text_file(path, limits::MAX_SCENE_FILE_BYTES, "scene file")
}

/// The text of the file at `path`, `what` (a scene file, a mesh file): a regular file of at
/// most `max` bytes, in UTF-8.
fn read_text_file(path: &Path, max: u64, what: &str) -> Result<String, SceneError> {
    use crate::messages::io_message;
    use std::io::Read;
    let fail = |reason: String| SceneError::Read {
        path: path.to_path_buf(),
        reason,
    };
    let meta =
        std::fs::metadata(path).map_err(|e| fail(crate::messages::read_failure(path, &e)))?;
    if meta.is_dir() {
        return Err(fail("it is a directory".into()));
    }
    if !meta.is_file() {
        // A FIFO would block until written to, a device might never end.
        return Err(fail("it is not a regular file".into()));
    }
    let too_large = || {
        fail(format!(
            "it is larger than the {} MiB a {what} may be",
            max >> 20
        ))
    };
    if meta.len() > max {
        return Err(too_large());
    }
    let file = std::fs::File::open(path).map_err(|e| fail(io_message(&e)))?;
    // The file may grow between the check and the read: read no more than the limit.
    // Its size is reserved: `take` gives no size hint, so the buffer would otherwise grow
    // by doubling, copying and touching fresh pages each time.
    let mut bytes = Vec::with_capacity(meta.len() as usize + 1);
    file.take(max + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| fail(io_message(&e)))?;
    if bytes.len() as u64 > max {
        return Err(too_large());
    }
    String::from_utf8(bytes).map_err(|e| {
        let valid = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        let text = std::str::from_utf8(valid).unwrap_or_default();
        let (line, column) = line_column(text, text.len());
        SceneError::Syntax {
            path: path.to_path_buf(),
            line,
            column,
            message: "the text is not valid UTF-8 here".into(),
        }
    })
}

/// Where the files a scene names (image textures) are found.
#[derive(Clone, Copy, Debug)]
pub enum Assets<'a> {
    /// Paths are relative to this folder (the scene file's own).
    Folder(&'a Path),
    /// As `Folder`, each mesh and image kept in the cache once read, and taken from it
    /// when another validation of the scene (another frame) names it again.
    Cached(&'a Path, &'a ReadCache),
    /// Built into the program: each path as the scene writes it, and the file's bytes.
    Embedded(&'a [(&'a str, &'a [u8])]),
}

impl<'a> Assets<'a> {
    /// What `rel` names, for messages and to recognise a file named twice.
    fn locate(&self, rel: &str) -> PathBuf {
        match self {
            Assets::Folder(dir) | Assets::Cached(dir, _) => dir.join(rel),
            Assets::Embedded(_) => PathBuf::from(rel),
        }
    }

    /// Whether the files are read from disk (and so watched).
    fn on_disk(&self) -> bool {
        matches!(self, Assets::Folder(_) | Assets::Cached(..))
    }

    /// The cache files are kept in, if any.
    fn cache(&self) -> Option<&'a ReadCache> {
        match self {
            Assets::Cached(_, cache) => Some(cache),
            _ => None,
        }
    }

    /// These assets with files kept in `cache`, where they are read from disk.
    fn cached_in(self, cache: &'a ReadCache) -> Assets<'a> {
        match self {
            Assets::Folder(dir) | Assets::Cached(dir, _) => Assets::Cached(dir, cache),
            embedded => embedded,
        }
    }

    fn embedded(&self, rel: &str) -> Option<Result<&[u8], TextureError>> {
        match self {
            Assets::Folder(_) | Assets::Cached(..) => None,
            Assets::Embedded(files) => Some(
                files
                    .iter()
                    .find(|(name, _)| *name == rel)
                    .map(|(_, bytes)| *bytes)
                    .ok_or_else(|| TextureError::Io("no such built-in file".into())),
            ),
        }
    }

    /// The size image `rel` declares, from its header.
    fn probe(&self, rel: &str) -> Result<(u32, u32), TextureError> {
        match self.embedded(rel) {
            None => ImageTexture::probe(&self.locate(rel)),
            Some(bytes) => ImageTexture::probe_bytes(bytes?),
        }
    }

    /// Image `rel`, decoded.
    fn load(&self, rel: &str) -> Result<ImageTexture, TextureError> {
        match self.embedded(rel) {
            None => ImageTexture::load(&self.locate(rel)),
            Some(bytes) => ImageTexture::decode(bytes?),
        }
    }
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
fn parse_recorded(
    source: &str,
    path: &Path,
    assets: Assets,
    files: &mut Vec<PathBuf>,
) -> Result<
    (
        Scene,
        Vec<ObjectOrigin>,
        Option<super::animation::Animation>,
    ),
    SceneError,
> {
    refuse_overlong_arrays(source, path)?;
    // An animated scene is validated at its first frame, as it renders by default.
    match super::animation::Animation::parse(source, path)? {
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
            parse_still(&animation.written_source(), path, assets, files)?;
            let (scene, origins) = parse_still(&animation.source_at(0), path, assets, files)
                .map_err(|error| SceneError::Frame {
                    frame: 0,
                    error: Box::new(error),
                })?;
            Ok((scene, origins, Some(animation)))
        }
    }
}

/// The parser's error `message` about `source` (the file `path`) at `span`, in the
/// format's words, with the entry it lies in named (`spheres[0] "glass ball": …`). Where a
/// bracket opened before that place is never closed, the error is that bracket's, at its
/// line: the parser stops only where the text no longer fits, often lines later.
pub(super) fn syntax_error(
    source: &str,
    path: &Path,
    span: Option<Range<usize>>,
    message: &str,
) -> SceneError {
    let offset = span.as_ref().map_or(0, |s| s.start);
    let plain = crate::messages::plain_type_words(message.trim());
    // The parser may quote the file (an unknown key of any length, say).
    let text = crate::messages::shown_within(&plain, 400);
    let unclosed = brackets::scan_brackets(source, usize::MAX)
        .unclosed
        .filter(|&at| at < offset && line_column(source, at).0 < line_column(source, offset).0);
    if let Some(at) = unclosed {
        let (line, column) = line_column(source, at);
        let bracket = &source[at..at + 1];
        return SceneError::Syntax {
            path: path.to_path_buf(),
            line,
            column,
            message: format!(
                "this `{bracket}` is never closed (the parser stopped at line {}: {text})",
                line_column(source, offset).0
            ),
        };
    }
    // A field missing from the file as a whole has an empty span at its start (an
    // entry's spans its header): no entry to name.
    let whole = span.as_ref().is_some_and(|s| s.is_empty());
    let entry = span
        .filter(|_| !whole)
        .and_then(|s| super::spans::entry_at(source, s.start));
    let (line, column) = line_column(source, offset);
    SceneError::Syntax {
        path: path.to_path_buf(),
        line,
        column,
        message: match entry {
            Some(entry) => format!("{entry}: {text}"),
            None => text,
        },
    }
}

/// Refuses, before the parser reads it, an array longer than any field of the format takes
/// (the parser's memory for a number is many times its text).
fn refuse_overlong_arrays(source: &str, path: &Path) -> Result<(), SceneError> {
    match brackets::scan_brackets(source, limits::MAX_ARRAY_ELEMENTS).overlong {
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
    let file: SceneFile =
        toml::from_str(source).map_err(|e| syntax_error(source, path, e.span(), e.message()))?;
    let eye = file.camera.get_ref().eye;
    let v = Validator {
        path: path.to_path_buf(),
        source,
        spans: FieldSpans::new(source),
        assets,
        origin: glam::DVec3::from(eye),
        reads: Default::default(),
    };
    let result = v.scene(file);
    for read in v.reads.into_inner() {
        if !files.contains(&read) {
            files.push(read);
        }
    }
    result
}

struct Validator<'a> {
    path: PathBuf,
    source: &'a str,
    /// Where every key and value lies in `source`.
    spans: FieldSpans<'a>,
    assets: Assets<'a>,
    /// The camera's eye, in f64: positions are stored relative to it.
    origin: glam::DVec3,
    /// The files the scene names that have been looked for, in order (from a folder only).
    reads: std::cell::RefCell<Vec<PathBuf>>,
}

/// Where a problem is: the span of the table it is in, and how to name that table.
struct Item<'s> {
    span: Range<usize>,
    name: &'s str,
}

impl Validator<'_> {
    /// An error in table `at`, pointing at the line of `field` (or of the element
    /// `field[i]` names) when the table has it, else at the table.
    fn field_error(&self, at: &Item, field: &str, message: impl Into<String>) -> SceneError {
        match self.spans.field(at.span.start, field) {
            Some(span) => {
                let at = Item {
                    span,
                    name: at.name,
                };
                self.error(&at, message)
            }
            None => self.error(at, message),
        }
    }

    fn error(&self, at: &Item, message: impl Into<String>) -> SceneError {
        let (line, _) = line_column(self.source, at.span.start);
        SceneError::Invalid {
            path: self.path.clone(),
            line,
            item: at.name.to_string(),
            message: message.into(),
        }
    }

    fn number(&self, at: &Item, field: &str, v: f32) -> Result<f32, SceneError> {
        self.in_range(at, field, v, f32::NEG_INFINITY, f32::INFINITY)
    }

    /// A radius, height or pattern size: positive, and within the lengths the tracer's
    /// squares and products keep finite (limits.rs).
    fn length(&self, at: &Item, field: &str, v: f32) -> Result<f32, SceneError> {
        let v = self.number(at, field, v)?;
        let problem = if v <= 0.0 {
            "be greater than zero"
        } else if v < *limits::LENGTH.start() {
            &format!("be at least {:e}", limits::MIN_LENGTH)
        } else if v > *limits::LENGTH.end() {
            &format!("be at most {:e}", limits::MAX_COORDINATE)
        } else {
            return Ok(v);
        };
        Err(self.field_error(
            at,
            field,
            format!("`{field}` must {problem}, got {}", number(v)),
        ))
    }

    fn in_range(
        &self,
        at: &Item,
        field: &str,
        v: f32,
        lo: f32,
        hi: f32,
    ) -> Result<f32, SceneError> {
        match outside_range(field, v, &(lo..=hi)) {
            Some(message) => Err(self.field_error(at, field, message)),
            None => Ok(v),
        }
    }

    fn point(&self, at: &Item, field: &str, v: V3) -> Result<Vec3, SceneError> {
        if v.iter().all(|c| c.is_finite()) {
            Ok(Vec3::from(v))
        } else {
            Err(self.field_error(
                at,
                field,
                format!("`{field}` must hold finite numbers, got {v:?}"),
            ))
        }
    }

    /// A position, relative to the scene origin (the camera), within `MAX_COORDINATE` of it.
    fn position(&self, at: &Item, field: &str, v: P3) -> Result<Vec3, SceneError> {
        let relative = glam::DVec3::from(v) - self.origin;
        if relative.is_finite() && relative.abs().max_element() <= limits::MAX_COORDINATE {
            Ok(relative.as_vec3())
        } else {
            Err(self.field_error(
                at,
                field,
                format!(
                    "`{field}` must hold finite numbers within {:e} of the camera on every \
                     axis, got {v:?}",
                    limits::MAX_COORDINATE
                ),
            ))
        }
    }

    /// A colour whose channels lie in [0, hi]; `why` says why hi is the bound.
    fn color_up_to(
        &self,
        at: &Item,
        field: &str,
        v: V3,
        hi: f32,
        why: &str,
    ) -> Result<Vec3, SceneError> {
        match outside_color_range(field, v.0, hi, why) {
            Some(message) => Err(self.field_error(at, field, message)),
            None => Ok(Vec3::from(v)),
        }
    }

    /// A surface's colour: the fraction of light it reflects, per channel.
    fn reflectance(&self, at: &Item, field: &str, v: V3) -> Result<Vec3, SceneError> {
        let hi = *limits::REFLECTANCE.end();
        self.color_up_to(at, field, v, hi, REFLECTANCE_BOUND)
    }

    /// A light's colour, the background, the ambient light: brighter than white is allowed.
    fn radiance(&self, at: &Item, field: &str, v: V3) -> Result<Vec3, SceneError> {
        self.color_up_to(at, field, v, limits::MAX_RADIANCE, RADIANCE_BOUND)
    }

    fn count(&self, at: &Item, field: &str, v: i64, lo: i64, hi: i64) -> Result<u32, SceneError> {
        if (lo..=hi).contains(&v) {
            Ok(v as u32)
        } else {
            Err(self.field_error(
                at,
                field,
                format!("`{field}` must lie in {lo}..={hi}, got {v}"),
            ))
        }
    }

    fn light(&self, at: &Item, l: &LightDef) -> Result<Light, SceneError> {
        let kind = l.kind.as_deref().unwrap_or("point");
        // The fields each type takes; any other given is refused by name.
        let takes: &[&str] = match kind {
            "point" => &["position", "falloff", "intensity"],
            "spot" => &[
                "position",
                "falloff",
                "intensity",
                "direction",
                "angle",
                "softness",
            ],
            "directional" => &["direction"],
            "area" => &[
                "corner",
                "edge_u",
                "edge_v",
                "falloff",
                "intensity",
                "visible",
            ],
            "sphere" => &["position", "radius", "falloff", "intensity", "visible"],
            other => {
                return Err(self.field_error(
                    at,
                    "type",
                    format!(
                        "unknown light type {} (expected \"point\", \"spot\", \"directional\", \
                         \"area\" or \"sphere\"){}",
                        quoted(other),
                        did_you_mean(other, ["point", "spot", "directional", "area", "sphere"])
                    ),
                ));
            }
        };
        let given = [
            ("position", l.position.is_some()),
            ("direction", l.direction.is_some()),
            ("falloff", l.falloff.is_some()),
            ("intensity", l.intensity.is_some()),
            ("corner", l.corner.is_some()),
            ("edge_u", l.edge_u.is_some()),
            ("edge_v", l.edge_v.is_some()),
            ("radius", l.radius.is_some()),
            ("angle", l.angle.is_some()),
            ("softness", l.softness.is_some()),
            ("visible", l.visible.is_some()),
        ];
        let a = if kind == "area" { "an" } else { "a" };
        if let Some((field, _)) = given.iter().find(|(f, g)| *g && !takes.contains(f)) {
            return Err(self.field_error(
                at,
                field,
                format!("`{field}` does not apply to {a} {kind} light"),
            ));
        }
        let needs = |field: &str| self.error(at, format!("{a} {kind} light needs `{field}`"));
        let position = |field: &str, v: Option<P3>| {
            let v = v.ok_or_else(|| needs(field))?;
            self.position(at, field, v)
        };
        let direction = || -> Result<Vec3, SceneError> {
            let d = l.direction.ok_or_else(|| needs("direction"))?;
            let d = self.point(at, "direction", d)?;
            crate::numerics::try_normalize(d)
                .ok_or_else(|| self.field_error(at, "direction", "`direction` has zero length"))
        };
        let kind = match kind {
            "point" => LightKind::Point {
                position: position("position", l.position)?,
                falloff: self.falloff(at, l)?,
            },
            "spot" => {
                let (lo, hi) = (*limits::SPOT_ANGLE.start(), *limits::SPOT_ANGLE.end());
                let angle = l.angle.ok_or_else(|| needs("angle"))?;
                let angle = self.in_range(at, "angle", angle, lo, hi)?;
                let softness =
                    self.in_range(at, "softness", l.softness.unwrap_or(0.0), 0.0, 1.0)?;
                LightKind::Spot {
                    position: position("position", l.position)?,
                    falloff: self.falloff(at, l)?,
                    cone: SpotCone::new(direction()?, angle, softness),
                }
            }
            "directional" => LightKind::Directional {
                direction: direction()?,
            },
            "area" => {
                let corner = position("corner", l.corner)?;
                let edge = |field: &str, v: Option<V3>| {
                    let v = v.ok_or_else(|| needs(field))?;
                    let e = self.point(at, field, v)?;
                    if e.abs().max_element() as f64 > limits::MAX_COORDINATE {
                        return Err(self.field_error(
                            at,
                            field,
                            format!(
                                "`{field}` must lie within {:e} on every axis",
                                limits::MAX_COORDINATE
                            ),
                        ));
                    }
                    Ok(e)
                };
                let (edge_u, edge_v) = (edge("edge_u", l.edge_u)?, edge("edge_v", l.edge_v)?);
                // The two edges must span a parallelogram: neither may be (nearly) zero
                // or parallel to the other, or its samples would all lie on a line.
                let area = edge_u.as_dvec3().cross(edge_v.as_dvec3()).length();
                let lengths = edge_u.as_dvec3().length() * edge_v.as_dvec3().length();
                if !(area > 1e-6 * lengths && area.sqrt() >= limits::MIN_LENGTH) {
                    return Err(self.field_error(
                        at,
                        "edge_v",
                        "`edge_u` and `edge_v` must span a rectangle: neither zero nor parallel",
                    ));
                }
                LightKind::Area {
                    shape: AreaShape::Rectangle {
                        corner,
                        edge_u,
                        edge_v,
                    },
                    falloff: self.falloff(at, l)?,
                    visible: l.visible.unwrap_or(true),
                }
            }
            _ => {
                let radius = l.radius.ok_or_else(|| needs("radius"))?;
                LightKind::Area {
                    shape: AreaShape::Sphere {
                        center: position("position", l.position)?,
                        radius: self.length(at, "radius", radius)?,
                    },
                    falloff: self.falloff(at, l)?,
                    visible: l.visible.unwrap_or(true),
                }
            }
        };
        Ok(Light {
            kind,
            color: self.radiance(at, "color", l.color.unwrap_or(Fixed([1.0; 3])))?,
        })
    }

    /// A light's `falloff` and `intensity`.
    fn falloff(&self, at: &Item, l: &LightDef) -> Result<Falloff, SceneError> {
        match l.falloff.as_deref().unwrap_or("none") {
            "none" => {
                if l.intensity.is_some() {
                    return Err(self.field_error(
                        at,
                        "intensity",
                        "`intensity` needs `falloff = \"inverse_square\"` (without \
                         falloff, `color` alone sets the brightness)",
                    ));
                }
                Ok(Falloff::None)
            }
            "inverse_square" => Ok(Falloff::InverseSquare {
                intensity: self.in_range(
                    at,
                    "intensity",
                    l.intensity.unwrap_or(1.0),
                    0.0,
                    limits::MAX_LIGHT_INTENSITY,
                )?,
            }),
            other => Err(self.field_error(
                at,
                "falloff",
                format!(
                    "unknown falloff {} (expected \"none\" or \"inverse_square\")",
                    quoted(other)
                ),
            )),
        }
    }

    /// Where asset `rel` is, noted as read.
    fn locate(&self, rel: &str) -> PathBuf {
        let path = self.assets.locate(rel);
        if self.assets.on_disk() {
            self.reads.borrow_mut().push(path.clone());
        }
        path
    }

    fn scene(&self, file: SceneFile) -> Result<(Scene, Vec<ObjectOrigin>), SceneError> {
        let camera = self.camera(&file.camera)?;
        let (render, ambient) = self.render(file.render.as_ref())?;
        let lights = file
            .lights
            .iter()
            .enumerate()
            .map(|(i, l)| {
                let name = format!("lights[{i}]");
                let at = Item {
                    span: l.span(),
                    name: &name,
                };
                self.light(&at, l.get_ref())
            })
            .collect::<Result<Vec<_>, SceneError>>()?;
        let fog = self.fog(file.fog.as_ref())?;
        let mut images = Images::default();
        self.check_texel_budget(&file.textures, file.render.as_ref(), &mut images)?;
        let background = self.background(file.render.as_ref(), &mut images)?;
        let textures = file
            .textures
            .iter()
            .map(|(name, t)| Ok((name.clone(), self.texture(name, t, &mut images)?)))
            .collect::<Result<HashMap<_, _>, SceneError>>()?;
        let materials = file
            .materials
            .iter()
            .map(|(name, m)| Ok((name.clone(), self.material(name, m, &textures)?)))
            .collect::<Result<HashMap<_, _>, SceneError>>()?;

        let mut objects = Vec::new();
        let mut origins = Vec::new();
        let mut add = |kind: &'static str,
                       i: usize,
                       span: Range<usize>,
                       d: &dyn EntryDef,
                       shape: &dyn Fn(&Item, &Placement) -> Result<ShapeDesc, SceneError>|
         -> Result<(), SceneError> {
            let label = entry_label(kind, i, d.name());
            let at = Item { span, name: &label };
            let material = match d.material() {
                None => Material::default(),
                Some(m) => materials.get(m).cloned().ok_or_else(|| {
                    self.field_error(
                        &at,
                        "material",
                        format!(
                            "no material named {} (see [materials]){}",
                            quoted(m),
                            did_you_mean(m, materials.keys().map(String::as_str))
                        ),
                    )
                })?,
            };
            let placement = self.placement(&at, d)?;
            let shape = shape(&at, &placement)?;
            objects.push(SceneObject {
                name: d
                    .name()
                    .map_or_else(|| format!("{kind} {i}"), str::to_string),
                shape,
                material,
                casts_shadow: d.shadow().unwrap_or(true),
                placement: placement.written(),
            });
            origins.push(ObjectOrigin {
                table: kind,
                index: i,
                material: d.material().map(str::to_string),
            });
            Ok(())
        };
        macro_rules! entries {
            ($list:expr, $kind:literal, $read:ident) => {
                for (i, item) in $list.iter().enumerate() {
                    let d = item.get_ref();
                    add($kind, i, item.span(), d, &|at, p| self.$read(at, d, p))?;
                }
            };
        }
        entries!(file.spheres, "spheres", sphere);
        entries!(file.cylinders, "cylinders", cylinder);
        entries!(file.polygons, "polygons", polygon);
        entries!(file.triangles, "triangles", triangle);
        entries!(file.tetrahedra, "tetrahedra", tetrahedron);
        entries!(file.boxes, "boxes", cuboid);
        entries!(file.discs, "discs", disc);
        entries!(file.planes, "planes", plane);
        entries!(file.cones, "cones", cone);
        entries!(file.tori, "tori", torus);
        let mut mesh_files = meshes::MeshFiles::default();
        for (i, m) in file.meshes.iter().enumerate() {
            let d = m.get_ref();
            let label = entry_label("meshes", i, d.name());
            let at = Item {
                span: m.span(),
                name: &label,
            };
            let material = match &d.material {
                None => None,
                Some(name) => Some(materials.get(name).ok_or_else(|| {
                    self.field_error(
                        &at,
                        "material",
                        format!(
                            "no material named {} (see [materials]){}",
                            quoted(name),
                            did_you_mean(name, materials.keys().map(String::as_str))
                        ),
                    )
                })?),
            };
            let placement = self.placement(&at, d)?;
            let parts = self.mesh_objects(&at, d, material, &mut mesh_files, &mut images)?;
            let transform =
                self.mesh_transform(&at, parts.iter().map(|p| p.mesh.as_ref()), &placement)?;
            let name = d.name.clone().unwrap_or_else(|| format!("meshes {i}"));
            for part in parts {
                objects.push(SceneObject {
                    name: match &part.part {
                        Some(p) => format!("{name}/{p}"),
                        None => name.clone(),
                    },
                    shape: ShapeDesc::Mesh {
                        mesh: part.mesh,
                        transform,
                    },
                    material: part.material,
                    casts_shadow: d.shadow.unwrap_or(true),
                    placement: placement.written(),
                });
                origins.push(ObjectOrigin {
                    table: "meshes",
                    index: i,
                    material: d.material.clone(),
                });
            }
        }
        let scene = Scene {
            origin: self.origin,
            camera,
            render,
            background,
            ambient,
            lights,
            fog,
            objects,
        };
        Ok((scene, origins))
    }

    /// A `[[spheres]]` entry, placed.
    fn sphere(
        &self,
        at: &Item,
        d: &SphereDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        match placement.uniform_scale() {
            Some(s) => Ok(ShapeDesc::Sphere {
                center: self.position(at, "center", placement.point(d.center))?,
                radius: self.length(at, "radius", (d.radius as f64 * s) as f32)?,
            }),
            None => {
                let sphere = ShapeDesc::Sphere {
                    center: self.position(at, "center", d.center)?,
                    radius: self.length(at, "radius", d.radius)?,
                };
                self.transformed(at, sphere, placement)
            }
        }
    }

    /// A `[[cylinders]]` entry, placed.
    fn cylinder(
        &self,
        at: &Item,
        d: &CylinderDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        let upright = placement.upright_scale();
        let (a, b) = upright.unwrap_or((1.0, 1.0));
        let base = if upright.is_some() {
            placement.point(d.base)
        } else {
            d.base
        };
        let relative_base = self.position(at, "base", base)?;
        let height = self.length(at, "height", (d.height as f64 * b) as f32)?;
        // The top cap is a position too.
        let mut top = base;
        top[1] += height as f64;
        let top = self.position(at, "height", top)?;
        let distance = relative_base.abs().max(top.abs()).max_element();
        let extent = top.y - relative_base.y;
        self.resolvable(at, "height", "the cylinder's height", extent, distance)?;
        let cylinder = ShapeDesc::Cylinder {
            base: relative_base,
            radius: self.length(at, "radius", (d.radius as f64 * a) as f32)?,
            height,
            caps: d.caps.unwrap_or(true),
        };
        match upright {
            Some(_) => Ok(cylinder),
            None => self.transformed(at, cylinder, placement),
        }
    }

    /// A `[[polygons]]` entry, placed.
    fn polygon(
        &self,
        at: &Item,
        d: &PolygonDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        let placed: Vec<P3> = d.vertices.iter().map(|&v| placement.point(v)).collect();
        let vertices = self.flat_corners(at, &placed)?;
        Ok(ShapeDesc::Polygon { vertices })
    }

    /// A `[[triangles]]` entry, placed.
    fn triangle(
        &self,
        at: &Item,
        d: &TriangleDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        let v = self.flat_corners(at, &d.vertices.map(|v| placement.point(v)))?;
        Ok(ShapeDesc::Triangle {
            vertices: [v[0], v[1], v[2]],
        })
    }

    /// A `[[tetrahedra]]` entry, placed.
    fn tetrahedron(
        &self,
        at: &Item,
        d: &TetrahedronDef,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        let v = self.vertices(at, &d.vertices.map(|v| placement.point(v)))?;
        if !has_volume(&v) {
            return Err(self.field_error(
                at,
                "vertices",
                "the four vertices lie in one plane (no volume)",
            ));
        }
        let faces = [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]];
        if !faces
            .iter()
            .all(|&[a, b, c]| representable(v[a], v[b], v[c]))
        {
            return Err(self.field_error(at, "vertices", TOO_SMALL));
        }
        Ok(ShapeDesc::Tetrahedron {
            vertices: [v[0], v[1], v[2], v[3]],
        })
    }

    /// `shape` (relative to the scene's origin) under `placement`, when its own parameters
    /// cannot express it; it must stay within `MAX_COORDINATE` of the camera.
    fn transformed(
        &self,
        at: &Item,
        shape: ShapeDesc,
        placement: &Placement,
    ) -> Result<ShapeDesc, SceneError> {
        let Some(transform) = placement.relative(self.origin) else {
            return Err(self.field_error(at, "scale", "the placement cannot be inverted"));
        };
        let b = transform.bounds_to_scene(&shape.bounds());
        let reach = b.min.abs().max(b.max.abs()).max_element() as f64;
        if reach.is_nan() || reach > limits::MAX_COORDINATE {
            return Err(self.field_error(
                at,
                "scale",
                format!(
                    "the shape, placed, reaches {reach:e} from the camera, more than {:e}",
                    limits::MAX_COORDINATE
                ),
            ));
        }
        Ok(ShapeDesc::Transformed {
            shape: Box::new(shape),
            transform,
        })
    }

    /// Counts the images of `[textures]` and the background against the scene's texel
    /// budget from their headers, before any is decoded, refusing the one that passes it
    /// with its field. (A file that cannot be read is reported when it is loaded.)
    fn check_texel_budget(
        &self,
        textures: &BTreeMap<String, Spanned<TextureDef>>,
        render: Option<&Spanned<RenderDef>>,
        budget: &mut Images,
    ) -> Result<(), SceneError> {
        // Every image the scene names: (where, the field, the path).
        let mut images: Vec<(String, Range<usize>, &str, &str)> = textures
            .iter()
            .filter_map(|(name, t)| {
                let label = format!("textures.{}", crate::messages::shown(name));
                match (&t.get_ref().path, t.get_ref().kind.as_str()) {
                    (Some(rel), "image") => Some((label, t.span(), "path", rel.as_str())),
                    _ => None,
                }
            })
            .collect();
        if let Some(r) = render
            && let Some(toml::Value::Table(t)) = &r.get_ref().background
            && let Some(toml::Value::String(rel)) = t.get("image")
        {
            images.push(("render".into(), r.span(), "background", rel.as_str()));
        }
        for (label, span, field, rel) in images {
            if let Err(BudgetError::Exceeded(message)) = budget.count(self, rel) {
                let at = Item { span, name: &label };
                return Err(self.field_error(&at, field, message));
            }
        }
        Ok(())
    }

    /// The corners of a flat convex shape (a polygon or a triangle), checked as one.
    fn flat_corners(&self, at: &Item, vs: &[P3]) -> Result<Vec<Vec3>, SceneError> {
        let vertices = self.vertices(at, vs)?;
        check_polygon(&vertices).map_err(|m| self.field_error(at, "vertices", m))?;
        Ok(vertices)
    }

    fn vertices(&self, at: &Item, vs: &[P3]) -> Result<Vec<Vec3>, SceneError> {
        vs.iter()
            .enumerate()
            .map(|(i, &v)| self.position(at, &format!("vertices[{i}]"), v))
            .collect()
    }

    fn camera(&self, c: &Spanned<CameraDef>) -> Result<Camera, SceneError> {
        let at = Item {
            span: c.span(),
            name: "camera",
        };
        let c = c.get_ref();
        let eye = self.position(&at, "eye", c.eye)?;
        let (lo, hi) = (*limits::VFOV.start(), *limits::VFOV.end());
        let vfov = self.in_range(&at, "fov", c.fov, lo, hi)?;
        let ways = [
            c.look_at.is_some(),
            c.direction.is_some(),
            c.yaw.is_some() || c.pitch.is_some(),
        ];
        if ways.iter().filter(|&&w| w).count() > 1 {
            return Err(self.error(
                &at,
                "give only one of `look_at`, `direction`, or `yaw`/`pitch`",
            ));
        }
        let up = self.point(&at, "up", c.up.unwrap_or(Fixed([0.0, 1.0, 0.0])))?;
        let up = crate::numerics::try_normalize(up)
            .ok_or_else(|| self.field_error(&at, "up", "`up` has zero length"))?;
        let direction = if let Some(target) = c.look_at {
            let target = self.position(&at, "look_at", target)?;
            if target == eye {
                return Err(self.field_error(
                    &at,
                    "look_at",
                    "`look_at` equals `eye`: the camera has no direction",
                ));
            }
            target - eye
        } else if let Some(d) = c.direction {
            self.point(&at, "direction", d)?
        } else {
            let yaw = self.number(&at, "yaw", c.yaw.unwrap_or(0.0))?;
            let pitch = self.in_range(
                &at,
                "pitch",
                c.pitch.unwrap_or(0.0),
                *limits::PITCH.start(),
                *limits::PITCH.end(),
            )?;
            let camera = Camera {
                eye,
                yaw,
                pitch,
                vfov,
                up,
                aperture: 0.0,
                focus_distance: 1.0,
                handedness: crate::camera::Handedness::Right,
            };
            return self.lens(&at, c, camera, None);
        };
        // The view is given by `look_at` or by `direction`: point at the one given.
        let view = if c.look_at.is_some() {
            "look_at"
        } else {
            "direction"
        };
        if crate::numerics::try_normalize(direction).is_none() {
            return Err(self.field_error(
                &at,
                view,
                format!("the view direction {direction} has zero length"),
            ));
        }
        let camera = Camera::looking_along_up(eye, direction, up, vfov).ok_or_else(|| {
            self.field_error(
                &at,
                view,
                format!(
                    "the view direction {direction} is within 1° of `up` {up}: choose another `up`"
                ),
            )
        })?;
        // A `look_at` target is in focus unless `focus_distance` says otherwise.
        let target = c
            .look_at
            .map(|_| direction.dot(camera.forward()))
            .filter(|d| d.is_finite() && *d > 0.0);
        self.lens(&at, c, camera, target)
    }

    /// `camera` with the lens `c` gives (`aperture`, `focus_distance`, which defaults to
    /// `target`), checked by the rule every camera follows. (The fields are checked one by
    /// one before it, for messages on their own lines.)
    fn lens(
        &self,
        at: &Item,
        c: &CameraDef,
        mut camera: Camera,
        target: Option<f32>,
    ) -> Result<Camera, SceneError> {
        camera.handedness = match c.handedness.as_deref() {
            None | Some("right") => crate::camera::Handedness::Right,
            Some("left") => crate::camera::Handedness::Left,
            Some(other) => {
                return Err(self.field_error(
                    at,
                    "handedness",
                    format!(
                        "`handedness` is \"right\" (prism's coordinates) or \"left\" \
                         (POV-Ray's), got {}{}",
                        quoted(other),
                        did_you_mean(other, ["right", "left"])
                    ),
                ));
            }
        };
        let max = limits::MAX_COORDINATE as f32;
        camera.aperture = self.in_range(at, "aperture", c.aperture.unwrap_or(0.0), 0.0, max)?;
        camera.focus_distance = match (c.focus_distance, target) {
            (Some(d), _) => self.length(at, "focus_distance", d)?,
            (None, Some(d)) => d.max(limits::MIN_LENGTH as f32),
            (None, None) if camera.aperture > 0.0 => {
                return Err(self.field_error(
                    at,
                    "aperture",
                    "an `aperture` needs a `focus_distance` (or a `look_at` to focus on)",
                ));
            }
            (None, None) => 1.0,
        };
        camera
            .check()
            .map(|()| camera)
            .map_err(|m| self.error(at, m))
    }

    fn render(&self, r: Option<&Spanned<RenderDef>>) -> Result<(RenderDefaults, Vec3), SceneError> {
        let defaults = RenderDefaults::default();
        let Some(r) = r else {
            return Ok((defaults, Vec3::splat(0.2)));
        };
        let at = Item {
            span: r.span(),
            name: "render",
        };
        let r = r.get_ref();
        let opt = |v: Option<i64>, d: u32| v.unwrap_or(d as i64);
        let render = RenderDefaults {
            width: self.count(
                &at,
                "width",
                opt(r.width, defaults.width),
                1,
                *limits::IMAGE_SIDE.end() as i64,
            )?,
            height: self.count(
                &at,
                "height",
                opt(r.height, defaults.height),
                1,
                *limits::IMAGE_SIDE.end() as i64,
            )?,
            aa: self.count(
                &at,
                "aa",
                opt(r.aa, defaults.aa),
                *limits::AA.start() as i64,
                *limits::AA.end() as i64,
            )?,
            max_depth: self.count(
                &at,
                "max_depth",
                opt(r.max_depth, defaults.max_depth),
                0,
                *limits::DEPTH.end() as i64,
            )?,
            samples: match r.samples {
                None => None,
                Some(n) => Some(self.count(
                    &at,
                    "samples",
                    n,
                    *limits::SAMPLES.start() as i64,
                    *limits::SAMPLES.end() as i64,
                )?),
            },
            encoding: self.encoding(&at, r)?,
        };
        let ambient = self.radiance(&at, "ambient", r.ambient.unwrap_or(Fixed([0.2; 3])))?;
        Ok((render, ambient))
    }

    /// The `[render]` table's `encoding` (a curve's name) and `exposure` (stops).
    fn encoding(&self, at: &Item, r: &RenderDef) -> Result<crate::color::Encoding, SceneError> {
        use crate::color::{Encoding, Transfer};
        let transfer = match r.encoding.as_deref() {
            None => Transfer::Linear,
            Some(name) => Transfer::from_name(name).ok_or_else(|| {
                self.field_error(
                    at,
                    "encoding",
                    format!(
                        "`encoding` must be \"linear\" (the default) or \"srgb\", got {}",
                        quoted(name)
                    ),
                )
            })?,
        };
        let exposure = self.number(at, "exposure", r.exposure.unwrap_or(0.0))?;
        if !limits::EXPOSURE.contains(&exposure) {
            return Err(self.field_error(
                at,
                "exposure",
                format!(
                    "`exposure` must be {} to {} stops, got {}",
                    limits::EXPOSURE.start(),
                    limits::EXPOSURE.end(),
                    number(exposure)
                ),
            ));
        }
        Ok(Encoding { transfer, exposure })
    }

    /// The `[render]` table's `background`: black when it has none.
    fn background(
        &self,
        r: Option<&Spanned<RenderDef>>,
        images: &mut Images,
    ) -> Result<Background, SceneError> {
        let Some(r) = r else {
            return Ok(Background::Solid(Vec3::ZERO));
        };
        let at = Item {
            span: r.span(),
            name: "render",
        };
        match self.background_def(&at, r.get_ref())? {
            None => Ok(Background::Solid(Vec3::ZERO)),
            Some(BackgroundDef::Color(c)) => {
                Ok(Background::Solid(self.radiance(&at, "background", c)?))
            }
            Some(BackgroundDef::Gradient { bottom, top }) => Ok(Background::Gradient {
                bottom: self.radiance(&at, "background", bottom)?,
                top: self.radiance(&at, "background", top)?,
            }),
            Some(BackgroundDef::Image(rel)) => images
                .load(self, &rel)
                .map(Background::Image)
                .map_err(|e| self.field_error(&at, "background", e)),
        }
    }

    /// Which form of `background` the table gives, refusing any other.
    fn background_def(
        &self,
        at: &Item,
        r: &RenderDef,
    ) -> Result<Option<BackgroundDef>, SceneError> {
        const FORMS: &str = "`background` takes a colour [r, g, b], \
                             { bottom = [r, g, b], top = [r, g, b] } (a vertical gradient) or \
                             { image = \"file\" } (a latitude-longitude image)";
        let bad = |what: String| self.field_error(at, "background", format!("{what}; {FORMS}"));
        let colour = |v: &toml::Value, key: &str| -> Result<V3, SceneError> {
            v.clone()
                .try_into::<V3>()
                .map_err(|_| bad(format!("`{key}` is not a colour of three numbers")))
        };
        let Some(value) = &r.background else {
            return Ok(None);
        };
        match value {
            toml::Value::Array(_) => {
                colour(value, "background").map(|c| Some(BackgroundDef::Color(c)))
            }
            toml::Value::Table(t) => {
                if let Some(key) = t
                    .keys()
                    .find(|k| !["bottom", "top", "image"].contains(&k.as_str()))
                {
                    return Err(bad(format!("unknown key {}", quoted(key))));
                }
                match (t.get("image"), t.get("bottom"), t.get("top")) {
                    (Some(toml::Value::String(rel)), None, None) => {
                        Ok(Some(BackgroundDef::Image(rel.clone())))
                    }
                    (Some(_), None, None) => Err(bad("`image` is not a file name".into())),
                    (None, Some(bottom), Some(top)) => Ok(Some(BackgroundDef::Gradient {
                        bottom: colour(bottom, "bottom")?,
                        top: colour(top, "top")?,
                    })),
                    _ => Err(bad(
                        "a background table takes `image`, or both `bottom` and `top`".into(),
                    )),
                }
            }
            _ => Err(bad("it is neither a colour nor a table".into())),
        }
    }

    /// An image texture's `uv_scale`, `uv_offset` and `uv_rotate`.
    fn uv_transform(&self, at: &Item, t: &TextureDef) -> Result<UvTransform, SceneError> {
        let most = limits::MAX_UV_TRANSFORM;
        let scale = match &t.uv_scale {
            None => [1.0, 1.0],
            Some(value) => {
                let pair = match value {
                    toml::Value::Float(_) | toml::Value::Integer(_) => {
                        value.clone().try_into::<f32>().ok().map(|s| [s, s])
                    }
                    toml::Value::Array(_) => value.clone().try_into::<[f32; 2]>().ok(),
                    _ => None,
                };
                let pair = pair.ok_or_else(|| {
                    self.field_error(at, "uv_scale", "`uv_scale` takes a number or [u, v]")
                })?;
                for s in pair {
                    if !(s.is_finite() && s != 0.0 && s.abs() <= most) {
                        return Err(self.field_error(
                            at,
                            "uv_scale",
                            format!(
                                "`uv_scale` must be non-zero and within ±{}, got {}",
                                number(most),
                                number(s)
                            ),
                        ));
                    }
                }
                pair
            }
        };
        let offset = match t.uv_offset {
            None => [0.0, 0.0],
            Some(Fixed([u, v])) => [
                self.in_range(at, "uv_offset", u, -most, most)?,
                self.in_range(at, "uv_offset", v, -most, most)?,
            ],
        };
        let rotate = self.in_range(at, "uv_rotate", t.uv_rotate.unwrap_or(0.0), -360.0, 360.0)?;
        Ok(UvTransform::new(scale, offset, rotate))
    }

    fn texture(
        &self,
        name: &str,
        t: &Spanned<TextureDef>,
        images: &mut Images,
    ) -> Result<Texture, SceneError> {
        let label = format!("textures.{}", crate::messages::shown(name));
        let at = Item {
            span: t.span(),
            name: &label,
        };
        let t = t.get_ref();
        // Which fields each type reads; any other given is a mistake worth saying.
        let (kind, takes): (&str, &[&str]) = match t.kind.as_str() {
            "image" => ("image", &["path", "uv_scale", "uv_offset", "uv_rotate"]),
            "checker" => ("checker", &["colors", "size", "axes"]),
            "stripes" => ("stripes", &["colors", "width", "direction"]),
            other => {
                return Err(self.field_error(
                    &at,
                    "type",
                    format!(
                        "unknown texture type {} (expected image, checker or stripes){}",
                        quoted(other),
                        did_you_mean(other, ["image", "checker", "stripes"])
                    ),
                ));
            }
        };
        let given = [
            ("path", t.path.is_some()),
            ("colors", t.colors.is_some()),
            ("size", t.size.is_some()),
            ("axes", t.axes.is_some()),
            ("width", t.width.is_some()),
            ("direction", t.direction.is_some()),
            ("uv_scale", t.uv_scale.is_some()),
            ("uv_offset", t.uv_offset.is_some()),
            ("uv_rotate", t.uv_rotate.is_some()),
        ];
        if let Some((field, _)) = given.iter().find(|(f, g)| *g && !takes.contains(f)) {
            return Err(self.field_error(
                &at,
                field,
                format!(
                    "`{field}` does not apply to a {kind} texture (it takes {})",
                    takes.join(", ")
                ),
            ));
        }
        let colors = |default: [V3; 2]| -> Result<[Vec3; 2], SceneError> {
            let [a, b] = t.colors.map_or(default, |c| c.0);
            Ok([
                self.reflectance(&at, "colors", a)?,
                self.reflectance(&at, "colors", b)?,
            ])
        };
        let require = |field: &str, v: Option<f32>| {
            v.ok_or_else(|| self.error(&at, format!("a {kind} texture needs `{field}`")))
        };
        match kind {
            "image" => {
                let Some(rel) = &t.path else {
                    return Err(self.error(&at, "an image texture needs `path`"));
                };
                let uv = self.uv_transform(&at, t)?;
                images
                    .load(self, rel)
                    .map(|image| Texture::Image { image, uv })
                    .map_err(|e| self.field_error(&at, "path", e))
            }
            "checker" => {
                let size = self.length(&at, "size", require("size", t.size)?)?;
                let axes_text = t.axes.as_deref().unwrap_or("xyz");
                let mut axes = Vec3::ZERO;
                for ch in axes_text.chars() {
                    match ch {
                        'x' => axes.x = 1.0,
                        'y' => axes.y = 1.0,
                        'z' => axes.z = 1.0,
                        _ => {
                            return Err(self.field_error(
                                &at,
                                "axes",
                                format!(
                                    "`axes` takes letters from \"xyz\", got {}",
                                    quoted(axes_text)
                                ),
                            ));
                        }
                    }
                }
                if axes == Vec3::ZERO {
                    return Err(self.field_error(&at, "axes", "`axes` names no axis"));
                }
                Ok(Texture::Checker {
                    colors: colors([Fixed([1.0; 3]), Fixed([0.0; 3])])?,
                    size,
                    axes,
                })
            }
            _ => {
                let width = self.length(&at, "width", require("width", t.width)?)?;
                let d = self.point(
                    &at,
                    "direction",
                    t.direction.unwrap_or(Fixed([1.0, 0.0, 0.0])),
                )?;
                let direction = crate::numerics::try_normalize(d).ok_or_else(|| {
                    self.field_error(&at, "direction", "`direction` has zero length")
                })?;
                Ok(Texture::Stripes {
                    colors: colors([Fixed([1.0; 3]), Fixed([0.0; 3])])?,
                    width,
                    direction,
                })
            }
        }
    }

    fn material(
        &self,
        name: &str,
        m: &Spanned<MaterialDef>,
        textures: &HashMap<String, Texture>,
    ) -> Result<Material, SceneError> {
        let label = format!("materials.{name}");
        let at = Item {
            span: m.span(),
            name: &label,
        };
        let m = m.get_ref();
        let d = Material::default();
        let texture = match (&m.texture, m.color) {
            (Some(_), Some(_)) => {
                return Err(self.field_error(
                    &at,
                    "texture",
                    "give either `color` or `texture`, not both",
                ));
            }
            (Some(t), None) => textures.get(t).cloned().ok_or_else(|| {
                let hint = did_you_mean(t, textures.keys().map(String::as_str));
                self.field_error(
                    &at,
                    "texture",
                    format!("no texture named {}{hint}", quoted(t)),
                )
            })?,
            (None, Some(c)) => Texture::Solid(c.into()),
            (None, None) => d.texture.clone(),
        };
        let material = Material {
            texture,
            ambient: m.ambient.unwrap_or(d.ambient),
            diffuse: m.diffuse.unwrap_or(d.diffuse),
            specular: m.specular.unwrap_or(d.specular),
            shininess: m.shininess.unwrap_or(d.shininess),
            reflectivity: m.reflectivity.unwrap_or(d.reflectivity),
            transparency: m.transparency.unwrap_or(d.transparency),
            eta: m.eta,
            emission: m.emission.map_or(d.emission, Vec3::from),
            fresnel: m.fresnel.unwrap_or(d.fresnel),
            roughness: m.roughness.unwrap_or(d.roughness),
            absorption: m.absorption.map_or(d.absorption, Vec3::from),
            conductor: m.conductor.map(Vec3::from),
        };
        material
            .check()
            .map_err(|p| self.field_error(&at, p.field, p.message))?;
        Ok(material)
    }

    /// The `[fog]` table: exponential with `density`, or linear from `start` to `end`.
    fn fog(&self, f: Option<&Spanned<FogDef>>) -> Result<Option<Fog>, SceneError> {
        let Some(f) = f else {
            return Ok(None);
        };
        let at = Item {
            span: f.span(),
            name: "fog",
        };
        let f = f.get_ref();
        let color = self.radiance(&at, "color", f.color.unwrap_or(Fixed([0.5; 3])))?;
        let max = limits::MAX_COORDINATE as f32;
        let kind = match (f.density, f.start, f.end) {
            (Some(density), None, None) => FogKind::Exponential {
                density: self.in_range(&at, "density", density, 0.0, limits::MAX_EXTINCTION)?,
            },
            (None, start, Some(end)) => {
                let start = self.in_range(&at, "start", start.unwrap_or(0.0), 0.0, max)?;
                let end = self.in_range(&at, "end", end, 0.0, max)?;
                if end <= start {
                    return Err(self.field_error(
                        &at,
                        "end",
                        format!(
                            "`end` ({}) must lie beyond `start` ({})",
                            number(end),
                            number(start)
                        ),
                    ));
                }
                FogKind::Linear { start, end }
            }
            (Some(_), _, _) => {
                return Err(self.error(
                    &at,
                    "give either `density` (exponential fog) or `start` and `end` (linear), not both",
                ));
            }
            (None, _, None) => {
                return Err(self.error(
                    &at,
                    "fog needs `density` (exponential) or `end` (linear, with an optional `start`)",
                ));
            }
        };
        Ok(Some(Fog { color, kind }))
    }
}

/// The image textures of one scene, each file decoded once, and the one budget all the
/// scene's images share.
#[derive(Default)]
struct Images {
    loaded: HashMap<PathBuf, Arc<ImageTexture>>,
    /// The images counted against the budget, each file once.
    counted: std::collections::HashSet<PathBuf>,
    /// Their texels together.
    texels: u64,
}

/// Why an image cannot be counted.
enum BudgetError {
    /// Its header cannot be read (said again, better, when it is loaded).
    Unreadable,
    /// It takes the scene past `MAX_SCENE_TEXELS`: the message says so.
    Exceeded(String),
}

impl Images {
    /// Counts image `rel` against the scene's texel budget from its header, once per file,
    /// whatever names it: a texture, the background or an MTL `map_Kd`.
    fn count(&mut self, v: &Validator, rel: &str) -> Result<(), BudgetError> {
        let path = v.locate(rel);
        if self.counted.contains(&path) {
            return Ok(());
        }
        let (w, h) = v.assets.probe(rel).map_err(|_| BudgetError::Unreadable)?;
        self.counted.insert(path.clone());
        self.texels += w as u64 * h as u64;
        if self.texels > limits::MAX_SCENE_TEXELS {
            return Err(BudgetError::Exceeded(format!(
                "image {} ({w}×{h}) brings the scene's images to {} texels, more than the {} \
                 all of them may have together (textures, background and the meshes' \
                 material images count alike)",
                quoted(&path.display().to_string()),
                self.texels,
                limits::MAX_SCENE_TEXELS
            )));
        }
        Ok(())
    }

    /// Image `rel`, decoded once however many name it, after counting it.
    fn load(&mut self, v: &Validator, rel: &str) -> Result<Arc<ImageTexture>, String> {
        let (path, assets) = (v.locate(rel), &v.assets);
        if let Some(img) = self.loaded.get(&path) {
            return Ok(img.clone());
        }
        if let Err(BudgetError::Exceeded(message)) = self.count(v, rel) {
            return Err(message);
        }
        let cached = assets.cache().and_then(|cache| cache.image(&path));
        let img = match cached {
            Some(img) => img,
            None => {
                let img = assets.load(rel).map_err(|e| {
                    format!(
                        "cannot load image {}: {e}",
                        quoted(&path.display().to_string())
                    )
                })?;
                let img = Arc::new(img);
                if let Some(cache) = assets.cache() {
                    cache.keep_image(path.clone(), img.clone());
                }
                img
            }
        };
        self.loaded.insert(path.to_path_buf(), img.clone());
        Ok(img)
    }
}

/// The points moved to their first and scaled by their largest extent along any axis, in
/// f64: the checks below then use tolerances relative to the shape's own size, whatever its
/// scale or distance.
fn normalized(v: &[Vec3]) -> Vec<glam::DVec3> {
    let b = crate::geometry::Aabb::from_points(v);
    let extent = (b.max.as_dvec3() - b.min.as_dvec3()).max_element();
    let scale = if extent > 0.0 { 1.0 / extent } else { 0.0 };
    v.iter()
        .map(|p| (p.as_dvec3() - v[0].as_dvec3()) * scale)
        .collect()
}

/// Whether four corners enclose a volume: beyond the rounding of f32 vertices (relative to
/// the tetrahedron's extent, so at any scale).
fn has_volume(v: &[Vec3]) -> bool {
    let p = normalized(v);
    let volume6 = (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]).abs();
    volume6 > 1e-5
}

/// Why these corners do not make a planar convex polygon, if they do not. Tolerances are
/// relative to the polygon's extent, and a corner counts as straight when its vertex lies
/// within that tolerance of its neighbours' line, so a regular polygon of many sides passes
/// at any scale.
pub fn check_polygon(vertices: &[Vec3]) -> Result<(), String> {
    if vertices.len() < 3 {
        return Err(format!(
            "a polygon needs at least 3 vertices, got {}",
            vertices.len()
        ));
    }
    let v = normalized(vertices);
    let n = v.len();
    // f32 vertices are rounded to about 6e-8 of their extent; these are well beyond that.
    const COINCIDENT: f64 = 1e-6;
    for i in 0..n {
        let j = (i + 1) % n;
        if (v[j] - v[i]).length() <= COINCIDENT {
            return Err(format!("vertices {i} and {j} coincide"));
        }
    }
    // Newell's normal: robust for any planar polygon, and its length is twice the area.
    let mut normal = glam::DVec3::ZERO;
    for i in 0..n {
        let (a, b) = (v[i], v[(i + 1) % n]);
        normal += glam::DVec3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        );
    }
    let area2 = normal.length();
    if area2.is_nan() || area2 <= 1e-6 {
        return Err("the vertices are collinear (the polygon has no area)".into());
    }
    let normal = normal / area2;
    for (i, p) in v.iter().enumerate() {
        if (*p - v[0]).dot(normal).abs() > 1e-4 {
            return Err(format!("vertex {i} is not in the plane of the others"));
        }
    }
    for i in 0..n {
        let (a, b, c) = (v[i], v[(i + 1) % n], v[(i + 2) % n]);
        let (e1, e2) = (b - a, c - b);
        let turn = e1.cross(e2);
        // About the distance of the middle vertex from the line through the other two.
        if turn.length() <= COINCIDENT * e1.length().max(e2.length()) {
            return Err(format!(
                "vertices {i}, {}, {} are collinear",
                (i + 1) % n,
                (i + 2) % n
            ));
        }
        if turn.dot(normal) < 0.0 {
            return Err(format!(
                "the polygon is not convex at vertex {}",
                (i + 1) % n
            ));
        }
    }
    // What the tracer builds from it, in f32: the fan of triangles and the plane's normal.
    let fan_ok = (1..n - 1).all(|i| representable(vertices[0], vertices[i], vertices[i + 1]));
    let normal_ok = crate::numerics::try_normalize(
        (vertices[1] - vertices[0]).cross(vertices[2] - vertices[1]),
    )
    .is_some();
    if !(fan_ok && normal_ok) {
        return Err(TOO_SMALL.into());
    }
    Ok(())
}

const TOO_SMALL: &str = "the shape is too small for f32: its edges' cross products underflow \
                         (scale the scene up)";

/// Whether f32 can hold the triangle the tracer builds from these corners (a normal of
/// non-zero length).
fn representable(a: Vec3, b: Vec3, c: Vec3) -> bool {
    crate::geometry::Triangle::new(a, b, c).is_some()
}
