//! `[materials]`: a colour or a texture, and the fields `Material::check` holds to the one
//! rule every material follows, whether a file or an edit made it.

use super::error::SceneError;
use super::validator::{Item, V3, Validator};
use crate::appearance::Material;
use crate::appearance::{Relief, Texture};
use crate::messages::{did_you_mean, quoted};
use glam::Vec3;
use serde::Deserialize;
use std::collections::HashMap;
use toml::Spanned;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MaterialDef {
    pub(super) color: Option<V3>,
    pub(super) texture: Option<String>,
    pub(super) ambient: Option<f32>,
    pub(super) diffuse: Option<f32>,
    pub(super) specular: Option<f32>,
    pub(super) shininess: Option<f32>,
    pub(super) reflectivity: Option<f32>,
    pub(super) transparency: Option<f32>,
    pub(super) eta: Option<f32>,
    pub(super) emission: Option<V3>,
    pub(super) fresnel: Option<bool>,
    pub(super) roughness: Option<f32>,
    pub(super) absorption: Option<V3>,
    pub(super) conductor: Option<V3>,
    pub(super) bump: Option<String>,
    pub(super) bump_depth: Option<f32>,
    pub(super) normal_map: Option<String>,
    pub(super) normal_strength: Option<f32>,
}

impl Validator<'_> {
    pub(super) fn material(
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
        let named = |field: &str, t: &String| {
            textures.get(t).cloned().ok_or_else(|| {
                let hint = did_you_mean(t, textures.keys().map(String::as_str));
                self.field_error(&at, field, format!("no texture named {}{hint}", quoted(t)))
            })
        };
        let texture = match (&m.texture, m.color) {
            (Some(_), Some(_)) => {
                return Err(self.field_error(
                    &at,
                    "texture",
                    "give either `color` or `texture`, not both",
                ));
            }
            (Some(t), None) => named("texture", t)?,
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
            relief: self.relief(&at, m, named)?,
        };
        material
            .check()
            .map_err(|p| self.field_error(&at, p.field, p.message))?;
        Ok(material)
    }

    /// A material's `bump` and `bump_depth`, or its `normal_map` and `normal_strength`;
    /// `named` finds a texture by name for the field that names it.
    fn relief(
        &self,
        at: &Item,
        m: &MaterialDef,
        named: impl Fn(&str, &String) -> Result<Texture, SceneError>,
    ) -> Result<Option<Relief>, SceneError> {
        let needs = |field: &str, what: &str| {
            self.field_error(at, field, format!("`{field}` needs {what}"))
        };
        match (&m.bump, &m.normal_map) {
            (Some(_), Some(_)) => Err(self.field_error(
                at,
                "normal_map",
                "give either `bump` or `normal_map`, not both",
            )),
            (Some(name), None) => {
                if m.normal_strength.is_some() {
                    return Err(needs("normal_strength", "a `normal_map`"));
                }
                let depth = m.bump_depth.ok_or_else(|| {
                    needs(
                        "bump",
                        "a `bump_depth`: how far the texture's white stands above its black, \
                         in scene units",
                    )
                })?;
                Ok(Some(Relief::Bump {
                    height: named("bump", name)?,
                    depth,
                }))
            }
            (None, Some(name)) => {
                if m.bump_depth.is_some() {
                    return Err(needs("bump_depth", "a `bump` texture"));
                }
                Ok(Some(Relief::NormalMap {
                    map: named("normal_map", name)?,
                    strength: m.normal_strength.unwrap_or(1.0),
                }))
            }
            (None, None) => match (m.bump_depth, m.normal_strength) {
                (Some(_), _) => Err(needs("bump_depth", "a `bump` texture")),
                (_, Some(_)) => Err(needs("normal_strength", "a `normal_map`")),
                (None, None) => Ok(None),
            },
        }
    }
}
