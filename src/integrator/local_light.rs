//! The light a surface sends back from the lights directly: ambient, and Phong diffuse and
//! specular terms from every light a shadow ray reaches.

use super::{Integrator, Shading};
use crate::accel::{Hit, Toward};
use crate::appearance::{Falloff, LightKind, Material, Texture, reflect};
use crate::geometry::{RayQuery, SurfacePoint};
use glam::Vec3A;

/// Where the shadow rays from one hit start.
pub(super) struct ShadowStart {
    /// On a smooth mesh seen from the side its normals face, the point lifted off the facet
    /// (the lift is outwards only) and its error bound.
    lifted: Option<(Vec3A, Vec3A)>,
    /// The object a shadow ray leaves and cannot meet again (`Accelerator::light_reaching`).
    pub leaving: Option<u32>,
}

impl ShadowStart {
    /// Whether light from `to_light` (at cosine-times-length `n_dot` to the shading normal)
    /// can reach the hit. A light behind the shading normal sends nothing: no shadow ray
    /// needed. Nor does one behind the true surface, except on a smooth mesh, where the
    /// facet stands in for a curved surface that may still face the light: its shadow ray
    /// starts from the lifted point, above the facet, and decides.
    #[inline(always)]
    pub fn faces(&self, at: &Shading, n_dot: f32, to_light: Vec3A) -> bool {
        !(n_dot <= 0.0 || (at.ns != at.n && self.lifted.is_none() && at.n.dot(to_light) <= 0.0))
    }
}

impl Integrator<'_> {
    /// Where shadow rays from `at` start.
    #[inline(always)]
    pub(super) fn shadow_start(&self, at: &Shading) -> ShadowStart {
        let object = self.geometry.object(at.object);
        ShadowStart {
            lifted: if at.entering && at.ns != at.n {
                self.accel().shadow_point(at.hit)
            } else {
                None
            },
            leaving: ((at.entering && object.convex) || object.flat).then_some(at.object),
        }
    }

    /// The origin of a shadow ray from `at` toward unit direction `l`.
    #[inline(always)]
    pub(super) fn shadow_origin(&self, at: &Shading, start: &ShadowStart, l: Vec3A) -> Vec3A {
        match start.lifted {
            // Off the facet's outer side, where the lifted point lies, whichever side of the
            // facet the light is on.
            Some((point, error)) => self.leave(
                &SurfacePoint {
                    point,
                    error,
                    ..at.surface
                },
                at.n,
                at.n,
            ),
            None => self.leave(&at.surface, at.n, l),
        }
    }

    /// The colour of `material`'s texture at `surface`, the point of `hit` (on object
    /// `object`) along `q`.
    #[inline(always)]
    pub(super) fn texture_color(
        &self,
        q: &RayQuery,
        hit: &Hit,
        object: u32,
        material: &Material,
        surface: &SurfacePoint,
    ) -> Vec3A {
        // One colour needs neither the texture coordinates nor the object's own point.
        match material.texture {
            Texture::Solid(color) => color.into(),
            _ => self.varying_texture_color(q, hit, object, material, surface),
        }
    }

    /// `texture_color` for a texture that varies over the surface.
    #[inline(never)]
    fn varying_texture_color(
        &self,
        q: &RayQuery,
        hit: &Hit,
        object: u32,
        material: &Material,
        surface: &SurfacePoint,
    ) -> Vec3A {
        let object = self.geometry.object(object);
        let p = surface.point;
        let uv = if !material.texture.needs_uv() {
            (0.0, 0.0)
        } else if let Some(planar) = object.planar_uv {
            planar.uv(p)
        } else {
            self.accel().uv(q, surface, hit)
        };
        material.texture.eval(uv, object.texture_point(p))
    }

    /// The ambient, diffuse and specular light at `at`; the diffuse part fades with the
    /// material's opacity, the highlight (light reflected at the surface) does not.
    #[inline]
    pub(super) fn local_light(&mut self, at: &Shading) -> Vec3A {
        let material = at.material;
        let opacity = 1.0 - material.transparency;
        if !(opacity > 0.0 || material.specular > 0.0) {
            return Vec3A::ZERO;
        }
        let p = at.surface.point;
        let base = self.texture_color(at.q, at.hit, at.object, material, &at.surface);
        if !material.texture.needs_uv() {
            self.signature.pattern(base);
        }
        let mut diffuse = base * self.appearance.ambient() * material.ambient;
        let mut specular = Vec3A::ZERO;
        let accel = self.accel();
        let filters = self.appearance.shadow_filters();
        let start = self.shadow_start(at);
        for (light_index, light) in self.appearance.lights().iter().enumerate() {
            // The direction to the light (to a point of it, unnormalised), how it fades, and
            // a spotlight's cone.
            let (to_light, point, falloff, cone) = match light.kind {
                LightKind::Point { position, falloff } => {
                    let position = Vec3A::from(position);
                    (position - p, Some(position), falloff, None)
                }
                LightKind::Spot {
                    position,
                    falloff,
                    cone,
                    radius,
                } => {
                    // A disc: one point of it per subsample, the shadow ray ending there;
                    // its centre is kept to measure the cone from.
                    let position = Vec3A::from(position);
                    let (sampled, disc) = if radius > 0.0 {
                        let u = self.stream.next_2d();
                        let sampled =
                            crate::sampler::disc_point(position, cone.direction, radius, u);
                        (sampled, Some(position))
                    } else {
                        (position, None)
                    };
                    (sampled - p, Some(sampled), falloff, Some((cone, disc)))
                }
                LightKind::Directional { direction } => {
                    (-Vec3A::from(direction), None, Falloff::None, None)
                }
                LightKind::Area { shape, falloff, .. } => {
                    // One point of the surface per subsample: the shadow ray ends there.
                    let sampled = shape.sample(p, self.stream.next_2d());
                    (sampled - p, Some(sampled), falloff, None)
                }
            };
            let n_dot = at.ns.dot(to_light);
            if !start.faces(at, n_dot, to_light) {
                continue;
            }
            let distance = to_light.length();
            let l = to_light / distance;
            // The cone is measured from the light's position, whatever point of its disc
            // the shadow ray goes to: the disc softens shadows, not the cone's edge.
            let spot = match cone {
                Some((cone, None)) => cone.gain(-l),
                Some((cone, Some(center))) => match (p - center).try_normalize() {
                    Some(w) => cone.gain(w),
                    None => 0.0,
                },
                None => 1.0,
            };
            if spot == 0.0 {
                continue;
            }
            let origin = self.shadow_origin(at, &start, l);
            self.counts.shadow += 1;
            let toward = match point {
                Some(position) => Toward::Point(position),
                None => Toward::Direction(l),
            };
            let visible = accel.light_reaching(light_index, toward, origin, start.leaving, filters);
            self.signature.shadow(visible);
            if visible == Vec3A::ZERO {
                continue;
            }
            let mut lit = visible * Vec3A::from(light.color);
            // No falloff multiplies by exactly one: skipped, it costs nothing.
            if falloff != Falloff::None {
                lit *= falloff.gain(distance);
            }
            if cone.is_some() {
                lit *= spot;
            }
            diffuse += lit * base * (material.diffuse * n_dot / distance);
            if material.specular > 0.0 {
                let r = reflect(-l, at.ns);
                let r_dot_v = r.dot(-at.q.ray.dir).max(0.0);
                // Outside the highlight the power is 0 (unless the exponent is 0 too).
                if r_dot_v > 0.0 || material.shininess == 0.0 {
                    specular += lit * (material.specular * r_dot_v.powf(material.shininess));
                }
            }
        }
        diffuse * opacity + specular
    }
}
