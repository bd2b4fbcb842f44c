//! The `[render]` table (size, anti-aliasing, depth, ambient light, the colour encoding and
//! the background: a colour, a gradient or an image) and the `[fog]` table.

use super::error::SceneError;
use super::fixed_array::Fixed;
use super::textures::Images;
use super::validator::{Item, V3, Validator};
use crate::appearance::{Background, Fog, FogKind};
use crate::integrator::IntegratorKind;
use crate::limits;
use crate::messages::{number, quoted};
use crate::scene::RenderDefaults;
use glam::Vec3;
use serde::Deserialize;
use toml::Spanned;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FogDef {
    pub(super) color: Option<V3>,
    pub(super) density: Option<f32>,
    pub(super) start: Option<f32>,
    pub(super) end: Option<f32>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RenderDef {
    pub(super) width: Option<i64>,
    pub(super) height: Option<i64>,
    pub(super) aa: Option<i64>,
    pub(super) samples: Option<i64>,
    pub(super) max_depth: Option<i64>,
    /// `[r, g, b]`, or a table: `{ bottom = …, top = … }` or `{ image = "…" }` (read by
    /// hand, for messages that say which form was meant).
    pub(super) background: Option<toml::Value>,
    pub(super) ambient: Option<V3>,
    pub(super) encoding: Option<String>,
    pub(super) exposure: Option<f32>,
    pub(super) integrator: Option<String>,
}

/// A `background` value, by form.
pub(super) enum BackgroundDef {
    Color(V3),
    Gradient { bottom: V3, top: V3 },
    Image(String),
}

impl Validator<'_> {
    pub(super) fn render(
        &self,
        r: Option<&Spanned<RenderDef>>,
    ) -> Result<(RenderDefaults, Vec3), SceneError> {
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
            integrator: self.integrator(&at, r)?,
        };
        let ambient = self.radiance(&at, "ambient", r.ambient.unwrap_or(Fixed([0.2; 3])))?;
        Ok((render, ambient))
    }

    /// The `[render]` table's `encoding` (a curve's name) and `exposure` (stops).
    pub(super) fn encoding(
        &self,
        at: &Item,
        r: &RenderDef,
    ) -> Result<crate::color::Encoding, SceneError> {
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

    /// The `[render]` table's `integrator`: "whitted" (the default) or "path".
    fn integrator(&self, at: &Item, r: &RenderDef) -> Result<IntegratorKind, SceneError> {
        match r.integrator.as_deref() {
            None => Ok(IntegratorKind::default()),
            Some(name) => IntegratorKind::from_name(name).ok_or_else(|| {
                self.field_error(
                    at,
                    "integrator",
                    format!(
                        "`integrator` must be \"whitted\" (the default) or \"path\", got {}",
                        quoted(name)
                    ),
                )
            }),
        }
    }

    /// The `[render]` table's `background`: black when it has none.
    pub(super) fn background(
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
    pub(super) fn background_def(
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

    /// The `[fog]` table: exponential with `density`, or linear from `start` to `end`.
    pub(super) fn fog(&self, f: Option<&Spanned<FogDef>>) -> Result<Option<Fog>, SceneError> {
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
