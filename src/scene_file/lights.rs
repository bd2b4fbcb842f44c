//! `[[lights]]`: point, spot, directional, rectangle and sphere lights, their colour and
//! how their light falls off with distance.

use super::error::SceneError;
use super::fixed_array::Fixed;
use super::gltf_scene::{GltfLight, GltfLightKind};
use super::placement::Placement;
use super::validator::{Item, P3, V3, Validator};
use crate::appearance::{AreaShape, Falloff, Light, LightKind, SpotCone};
use crate::messages::{did_you_mean, quoted};
use crate::scene::ObjectPlacement;

/// prism's intensity for one candela of a glTF light (and its colour for one lux of a
/// directional one): a candela is 1/683 W/sr, and prism's diffuse shading leaves out the
/// 1/π of a Lambertian surface's radiance, so that a glTF light lights a white surface as
/// a physically based renderer would show it.
pub const PRISM_PER_CANDELA: f32 = 1.0 / (683.0 * std::f32::consts::PI);
use glam::Vec3;
use serde::Deserialize;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct LightDef {
    #[serde(rename = "type")]
    pub(super) kind: Option<String>,
    pub(super) position: Option<P3>,
    pub(super) direction: Option<V3>,
    pub(super) color: Option<V3>,
    pub(super) falloff: Option<String>,
    pub(super) intensity: Option<f32>,
    pub(super) corner: Option<P3>,
    pub(super) edge_u: Option<V3>,
    pub(super) edge_v: Option<V3>,
    pub(super) radius: Option<f32>,
    pub(super) angle: Option<f32>,
    pub(super) softness: Option<f32>,
    pub(super) visible: Option<bool>,
    /// The group it is placed in.
    pub(super) group: Option<String>,
}

impl Validator<'_> {
    /// A `[[lights]]` entry, placed in its group (if it names one), and that group.
    pub(super) fn light(
        &self,
        at: &Item,
        l: &LightDef,
    ) -> Result<(Light, Option<usize>), SceneError> {
        let (group, frame) = self.group_frame(at, l.group.as_deref())?;
        if group.is_none() {
            return Ok((self.light_in_frame(at, l)?, None));
        }
        // The entry's points and directions carried into the world's frame, and its radii
        // scaled with them (which needs the same scale in every direction).
        let frame = Placement::new(ObjectPlacement::IDENTITY, frame, group);
        let radius_scale = match (l.radius, frame.even_scale()) {
            (None, _) => 1.0,
            (Some(_), Some(s)) => s,
            (Some(_), None) => {
                return Err(self.field_error(
                    at,
                    "group",
                    "the group stretches space unevenly, which would make this light's \
                     round emitter an ellipse: give its groups the same scale on every axis",
                ));
            }
        };
        let vector = |v: Option<V3>| {
            v.map(|v| Fixed(frame.vector(Vec3::from(v).as_dvec3()).as_vec3().to_array()))
        };
        let placed = LightDef {
            position: l.position.map(|p| frame.point(p)),
            corner: l.corner.map(|p| frame.point(p)),
            direction: vector(l.direction),
            edge_u: vector(l.edge_u),
            edge_v: vector(l.edge_v),
            radius: l.radius.map(|r| (r as f64 * radius_scale) as f32),
            group: None,
            kind: l.kind.clone(),
            falloff: l.falloff.clone(),
            ..*l
        };
        Ok((self.light_in_frame(at, &placed)?, group))
    }

    /// A glTF file's light, placed by its mesh entry `at`'s `placement`: its candela (or a
    /// directional light's lux) as prism's intensity (or colour) by the rule in
    /// `PRISM_PER_CANDELA`, and held to every light's rules.
    pub(super) fn gltf_light(
        &self,
        at: &Item,
        light: &GltfLight,
        placement: &Placement,
    ) -> Result<Light, SceneError> {
        let scale = light.intensity * PRISM_PER_CANDELA;
        let point = Some(placement.point(Fixed(light.position.to_array())));
        let direction = Some(Fixed(
            placement.vector(light.direction).as_vec3().to_array(),
        ));
        let color = light.color;
        let (kind, angle, softness) = match light.kind {
            GltfLightKind::Point => ("point", None, None),
            GltfLightKind::Spot { inner, outer } => {
                let softness = if outer > 0.0 {
                    1.0 - inner / outer
                } else {
                    0.0
                };
                (
                    "spot",
                    Some(outer.to_degrees()),
                    Some(softness.clamp(0.0, 1.0)),
                )
            }
            GltfLightKind::Directional => ("directional", None, None),
        };
        let directional = light.kind == GltfLightKind::Directional;
        let def = LightDef {
            kind: Some(kind.into()),
            position: (!directional).then_some(point).flatten(),
            direction: (light.kind != GltfLightKind::Point)
                .then_some(direction)
                .flatten(),
            color: Some(Fixed(
                (if directional { color * scale } else { color }).to_array(),
            )),
            falloff: (!directional).then(|| "inverse_square".into()),
            intensity: (!directional).then_some(scale),
            corner: None,
            edge_u: None,
            edge_v: None,
            radius: None,
            angle,
            softness,
            visible: None,
            group: None,
        };
        self.light_in_frame(at, &def)
    }

    /// A `[[lights]]` entry whose values are in the world's frame.
    fn light_in_frame(&self, at: &Item, l: &LightDef) -> Result<Light, SceneError> {
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
                "radius",
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
                let angle = l.angle.ok_or_else(|| needs("angle"))?;
                let softness = l.softness.unwrap_or(0.0);
                LightKind::Spot {
                    position: position("position", l.position)?,
                    falloff: self.falloff(at, l)?,
                    cone: SpotCone::new(direction()?, angle, softness),
                    radius: l.radius.unwrap_or(0.0),
                }
            }
            "directional" => LightKind::Directional {
                direction: direction()?,
            },
            "area" => {
                let corner = position("corner", l.corner)?;
                let edge = |field: &str, v: Option<V3>| {
                    let v = v.ok_or_else(|| needs(field))?;
                    self.point(at, field, v)
                };
                let (edge_u, edge_v) = (edge("edge_u", l.edge_u)?, edge("edge_v", l.edge_v)?);
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
                        radius,
                    },
                    falloff: self.falloff(at, l)?,
                    visible: l.visible.unwrap_or(true),
                }
            }
        };
        // The values' rules are every light's (`Light::check`), edits' too.
        let light = Light {
            kind,
            color: l.color.map_or(Vec3::ONE, Vec3::from),
        };
        light
            .check()
            .map_err(|p| self.field_error(at, p.field, p.message))?;
        Ok(light)
    }

    /// A light's `falloff` and `intensity` (whose value `Falloff::check` holds).
    pub(super) fn falloff(&self, at: &Item, l: &LightDef) -> Result<Falloff, SceneError> {
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
                intensity: l.intensity.unwrap_or(1.0),
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
}
