//! glTF's metallic-roughness materials as prism's: base colour (and its texture), metal as a
//! conductor tinted by the base colour, roughness as the mirror's spread and the highlight's
//! size, emission, normal maps, and transmission with its index of refraction as Fresnel
//! glass. What has no counterpart is named among the file's unread parts.

use super::assets::beside;
use super::gltf_file::{data_uri, relative_uri};
use super::gltf_scene::GltfFile;
use super::textures::Images;
use super::validator::Validator;
use crate::appearance::{ImageTexture, Material, Relief, Texture, UvTransform};
use crate::limits;
use crate::messages::quoted;
use glam::Vec3;
use gltf::material::AlphaMode;
use std::path::PathBuf;
use std::sync::Arc;

/// A problem with a glTF file, in words (the reader names the file and the entry).
type Refusal = String;

/// The Phong exponent whose highlight is about as wide as GGX's of `roughness` (α =
/// roughness², exponent 2/α² − 2, Walter et al. 2007), within prism's bounds.
pub fn shininess_of(roughness: f32) -> f32 {
    let alpha = (roughness * roughness).max(1e-3);
    (2.0 / (alpha * alpha) - 2.0).clamp(1.0, limits::MAX_SHININESS)
}

impl Validator<'_> {
    /// Prism's material for each of `file`'s materials, by index (read from `rel`), adding
    /// what it does not map to `unread`.
    pub(super) fn gltf_materials(
        &self,
        rel: &str,
        file: &GltfFile,
        images: &mut Images,
        unread: &mut Vec<String>,
    ) -> Result<Vec<Material>, Refusal> {
        file.document
            .materials()
            .map(|m| {
                let name = m.name().map_or_else(
                    || format!("materials[{}]", m.index().unwrap_or(0)),
                    |n| format!("material {}", quoted(n)),
                );
                self.gltf_material(rel, file, &m, &name, images, unread)
                    .map_err(|e| format!("{name}: {e}"))
            })
            .collect()
    }

    fn gltf_material(
        &self,
        rel: &str,
        file: &GltfFile,
        m: &gltf::Material,
        name: &str,
        images: &mut Images,
        unread: &mut Vec<String>,
    ) -> Result<Material, Refusal> {
        let mut skip = |what: &str| unread.push(format!("{name}: {what}"));
        let pbr = m.pbr_metallic_roughness();
        let [r, g, b, alpha] = pbr.base_color_factor();
        let in_unit = |v: f32| (0.0..=1.0).contains(&v);
        if ![r, g, b, alpha].into_iter().all(in_unit) {
            return Err("baseColorFactor must lie in [0, 1]".into());
        }
        let base = Vec3::new(r, g, b);
        let texture = match pbr.base_color_texture() {
            Some(info) => {
                if base != Vec3::ONE {
                    skip("baseColorFactor over its texture (the texture alone is used)");
                }
                if info.tex_coord() != 0 {
                    skip("a texture on TEXCOORD_1 or later (TEXCOORD_0 is used)");
                }
                let image = self.gltf_image(rel, file, &info.texture(), images)?;
                Texture::Image {
                    image,
                    uv: UvTransform::IDENTITY,
                }
            }
            None => Texture::Solid(base),
        };
        let (metallic, roughness) = (pbr.metallic_factor(), pbr.roughness_factor());
        if !(in_unit(metallic) && in_unit(roughness)) {
            return Err("metallicFactor and roughnessFactor must lie in [0, 1]".into());
        }
        if pbr.metallic_roughness_texture().is_some() {
            skip("metallicRoughnessTexture (the factors are used)");
        }
        if m.occlusion_texture().is_some() {
            skip("occlusionTexture");
        }
        if m.emissive_texture().is_some() {
            skip("emissiveTexture (emissiveFactor is used)");
        }
        let emission = Vec3::from(m.emissive_factor()) * m.emissive_strength().unwrap_or(1.0);
        let relief = match m.normal_texture() {
            None => None,
            Some(normal) => {
                let image = self.gltf_image(rel, file, &normal.texture(), images)?;
                Some(Relief::NormalMap {
                    map: Texture::Image {
                        image,
                        uv: UvTransform::IDENTITY,
                    },
                    strength: normal.scale(),
                })
            }
        };
        let transmission = m.transmission().map_or(0.0, |t| {
            if t.transmission_texture().is_some() {
                skip("transmissionTexture (transmissionFactor is used)");
            }
            t.transmission_factor()
        });
        let transparency = match m.alpha_mode() {
            AlphaMode::Opaque => transmission,
            AlphaMode::Blend => transmission.max(1.0 - alpha),
            AlphaMode::Mask => {
                skip("alphaMode MASK (drawn opaque)");
                transmission
            }
        };
        let metal = metallic >= 0.5;
        let glass = transmission > 0.0 && !metal;
        let d = Material::default();
        let material = Material {
            texture,
            diffuse: if metal { 0.0 } else { 1.0 - transmission },
            specular: 0.5 * (1.0 - roughness),
            shininess: shininess_of(roughness),
            reflectivity: if metal { 1.0 } else { 0.0 },
            roughness: if metal || glass { roughness } else { 0.0 },
            conductor: metal.then_some(base),
            transparency: if metal { 0.0 } else { transparency },
            eta: glass.then(|| m.ior().unwrap_or(1.5)),
            fresnel: glass,
            emission,
            relief,
            ..d
        };
        material
            .check()
            .map_err(|p| format!("maps to `{}`: {}", p.field, p.message))?;
        Ok(material)
    }

    /// The picture `texture` shows: bytes in a buffer view, a data URI, or a file beside
    /// the glTF file; counted against the scene's texel budget before it is decoded.
    fn gltf_image(
        &self,
        rel: &str,
        file: &GltfFile,
        texture: &gltf::Texture,
        images: &mut Images,
    ) -> Result<Arc<ImageTexture>, Refusal> {
        let image = texture.source();
        let key = format!("{}#images[{}]", self.locate(rel).display(), image.index());
        match image.source() {
            gltf::image::Source::View { view, .. } => {
                let buffer = &file.buffers[view.buffer().index()];
                let bytes = view
                    .offset()
                    .checked_add(view.length())
                    .and_then(|end| buffer.get(view.offset()..end))
                    .ok_or_else(|| {
                        format!(
                            "bufferViews[{}] runs past the end of its buffer",
                            view.index()
                        )
                    })?;
                images.load_bytes(PathBuf::from(key), bytes)
            }
            gltf::image::Source::Uri { uri, .. } => match data_uri(uri) {
                Some(bytes) => images.load_bytes(PathBuf::from(key), &bytes?),
                None => images.load(self, &beside(rel, &relative_uri(uri)?)),
            },
        }
    }
}
