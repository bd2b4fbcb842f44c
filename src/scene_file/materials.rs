//! `[materials]`: a colour or a texture, and the fields `Material::check` holds to the one
//! rule every material follows, whether a file or an edit made it.

use super::error::SceneError;
use super::validator::{Item, V3, Validator};
use crate::appearance::Material;
use crate::appearance::Texture;
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
}
