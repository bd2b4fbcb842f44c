//! `[textures]`: solid colours, checkers, stripes and images with their UV transform, and
//! the budget of texels every image a scene reads counts towards.

use super::error::SceneError;
use super::fixed_array::Fixed;
use super::validator::{Item, V3, Validator};
use crate::appearance::{
    ColorMap, ImageTexture, MAX_OCTAVES, MAX_TURBULENCE, Pattern, PatternKind, Texture, UvTransform,
};
use crate::limits;
use crate::messages::{did_you_mean, number, quoted};
use glam::Vec3;
use serde::Deserialize;
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;
use toml::Spanned;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TextureDef {
    #[serde(rename = "type")]
    pub(super) kind: String,
    pub(super) path: Option<String>,
    pub(super) colors: Option<Fixed<V3, 2>>,
    pub(super) size: Option<f32>,
    pub(super) axes: Option<String>,
    pub(super) width: Option<f32>,
    pub(super) direction: Option<V3>,
    /// A number (both ways) or [u, v].
    pub(super) uv_scale: Option<toml::Value>,
    pub(super) uv_offset: Option<Fixed<f32, 2>>,
    pub(super) uv_rotate: Option<f32>,
    pub(super) scale: Option<f32>,
    pub(super) turbulence: Option<f32>,
    pub(super) octaves: Option<i64>,
    pub(super) color_map: Option<Vec<ColorStopDef>>,
}

/// One stop of a pattern's colour map: `{ at = 0.5, color = [r, g, b] }`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ColorStopDef {
    at: f32,
    color: V3,
}

impl Validator<'_> {
    /// An image texture's `uv_scale`, `uv_offset` and `uv_rotate`.
    pub(super) fn uv_transform(
        &self,
        at: &Item,
        t: &TextureDef,
    ) -> Result<UvTransform, SceneError> {
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

    pub(super) fn texture(
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
            "gradient" => (
                "gradient",
                &["scale", "turbulence", "octaves", "color_map", "direction"],
            ),
            other if PatternKind::NAMES.contains(&other) => {
                (other, &["scale", "turbulence", "octaves", "color_map"])
            }
            other => {
                let known = ["image", "checker", "stripes"]
                    .into_iter()
                    .chain(PatternKind::NAMES);
                return Err(self.field_error(
                    &at,
                    "type",
                    format!(
                        "unknown texture type {} (expected image, checker, stripes, or a \
                         pattern: {}){}",
                        quoted(other),
                        PatternKind::NAMES.join(", "),
                        did_you_mean(other, known)
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
            ("scale", t.scale.is_some()),
            ("turbulence", t.turbulence.is_some()),
            ("octaves", t.octaves.is_some()),
            ("color_map", t.color_map.is_some()),
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
            "stripes" => {
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
            pattern => self.pattern(&at, pattern, t),
        }
    }

    /// A procedural pattern's texture: its `scale`, `turbulence`, `octaves`, `color_map`
    /// and a gradient's `direction`.
    fn pattern(&self, at: &Item, name: &str, t: &TextureDef) -> Result<Texture, SceneError> {
        let direction = match t.direction {
            None => Vec3::X,
            Some(d) => {
                let d = self.point(at, "direction", d)?;
                crate::numerics::try_normalize(d).ok_or_else(|| {
                    self.field_error(at, "direction", "`direction` has zero length")
                })?
            }
        };
        let kind = PatternKind::named(name, direction).expect("the type was matched");
        let scale = self.length(at, "scale", t.scale.unwrap_or(1.0))?;
        let default_turbulence = match kind {
            PatternKind::Marble | PatternKind::Wood | PatternKind::Agate => 1.0,
            _ => 0.0,
        };
        let turbulence = self.in_range(
            at,
            "turbulence",
            t.turbulence.unwrap_or(default_turbulence),
            0.0,
            MAX_TURBULENCE,
        )?;
        let octaves = self.count(at, "octaves", t.octaves.unwrap_or(6), 1, MAX_OCTAVES as i64)?;
        let map = match &t.color_map {
            None => ColorMap::grey(),
            Some(stops) => {
                let mut read = Vec::with_capacity(stops.len());
                for stop in stops {
                    read.push((stop.at, self.reflectance(at, "color_map", stop.color)?));
                }
                ColorMap::new(read)
                    .map_err(|e| self.field_error(at, "color_map", format!("`color_map`: {e}")))?
            }
        };
        Ok(Texture::Pattern(Arc::new(Pattern {
            kind,
            scale,
            turbulence,
            octaves,
            map,
        })))
    }
}

/// The image textures of one scene, each file decoded once, and the one budget all the
/// scene's images share.
#[derive(Default)]
pub(super) struct Images {
    pub(super) loaded: HashMap<PathBuf, Arc<ImageTexture>>,
    /// The images counted against the budget, each file once.
    pub(super) counted: std::collections::HashSet<PathBuf>,
    /// Their texels together.
    pub(super) texels: u64,
}

/// Why an image cannot be counted.
pub(super) enum BudgetError {
    /// Its header cannot be read (said again, better, when it is loaded).
    Unreadable,
    /// It takes the scene past `MAX_SCENE_TEXELS`: the message says so.
    Exceeded(String),
}

impl Images {
    /// Counts image `rel` against the scene's texel budget from its header, once per file,
    /// whatever names it: a texture, the background or an MTL `map_Kd`.
    pub(super) fn count(&mut self, v: &Validator, rel: &str) -> Result<(), BudgetError> {
        let path = v.locate(rel);
        if self.counted.contains(&path) {
            return Ok(());
        }
        let (w, h) = v.assets.probe(rel).map_err(|_| BudgetError::Unreadable)?;
        self.add(path, w, h).map_err(BudgetError::Exceeded)
    }

    /// Counts image `path` of `w` × `h` texels (once per path) against the budget.
    fn add(&mut self, path: PathBuf, w: u32, h: u32) -> Result<(), String> {
        if !self.counted.insert(path.clone()) {
            return Ok(());
        }
        self.texels += w as u64 * h as u64;
        if self.texels > limits::MAX_SCENE_TEXELS {
            return Err(format!(
                "image {} ({w}×{h}) brings the scene's images to {} texels, more than the {} \
                 all of them may have together (textures, background and the meshes' \
                 material images count alike)",
                quoted(&path.display().to_string()),
                self.texels,
                limits::MAX_SCENE_TEXELS
            ));
        }
        Ok(())
    }

    /// An image held in another file (a glTF buffer's bytes), known by `key`: counted
    /// against the budget from its header, then decoded once.
    pub(super) fn load_bytes(
        &mut self,
        key: PathBuf,
        bytes: &[u8],
    ) -> Result<Arc<ImageTexture>, String> {
        if let Some(img) = self.loaded.get(&key) {
            return Ok(img.clone());
        }
        let fail = |e: crate::appearance::TextureError| {
            format!(
                "cannot load image {}: {e}",
                quoted(&key.display().to_string())
            )
        };
        let (w, h) = ImageTexture::probe_bytes(bytes).map_err(fail)?;
        self.add(key.clone(), w, h)?;
        let img = Arc::new(ImageTexture::decode(bytes).map_err(fail)?);
        self.loaded.insert(key, img.clone());
        Ok(img)
    }

    /// Image `rel`, decoded once however many name it, after counting it.
    pub(super) fn load(&mut self, v: &Validator, rel: &str) -> Result<Arc<ImageTexture>, String> {
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
