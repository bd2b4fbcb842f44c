//! The lights in physical units, for the path tracer: where a shadow ray toward each ends,
//! the light it brings over the density it was drawn with, and a visible area light's
//! radiance and density for multiple importance sampling.
//!
//! A light's `color` C and falloff `intensity` g mean what they mean to Whitted's Lambertian
//! term, so that a matte surface lit by one light alone is equally bright in both
//! integrators:
//! - a point light (or a spotlight along its axis) has radiant intensity π·C·g (W/sr), so
//!   it lights a surface at distance d facing it with irradiance π·C·g/d²;
//! - a directional light gives irradiance π·C on a surface facing it;
//! - a rectangle of area A has radiance π·C·g/A on both sides (a point far off its axis
//!   sees it as a point light of intensity π·C·g times the cosine at the rectangle);
//! - a sphere of radius r has radiance C·g/r² (a point light of intensity π·C·g from any
//!   side).
//!
//! Whitted's light without falloff lights every surface alike at any distance, which no
//! light does; the path tracer reads it as an inverse-square light as bright at the centre
//! of the scene's bounds: g = the squared distance from the light to that centre.

use super::Integrator;
use crate::accel::Toward;
use crate::appearance::{AreaShape, Falloff, Light, LightKind};
use crate::geometry::{Ray, Sphere};
use glam::{Vec3, Vec3A};
use std::f32::consts::{PI, TAU};

/// A shadow ray toward a light, and what it brings if nothing blocks it.
pub(super) struct LightSample {
    /// Where the shadow ray ends.
    pub toward: Toward,
    /// The unit direction from the shaded point toward the light.
    pub wi: Vec3A,
    /// The light arriving along `wi` over the density it was drawn with (radiance over a
    /// solid-angle density for an area light; irradiance at normal incidence for a point
    /// or directional one).
    pub light: Vec3A,
    /// The solid-angle density `wi` was drawn with: 0 for a light that is one point or one
    /// direction, which no scattered ray can hit.
    pub pdf: f32,
}

impl Integrator<'_> {
    /// The multiplier g of light `light`'s colour at unit distance: its falloff's
    /// intensity, or for a light without falloff, the squared distance from `anchor` (its
    /// position or centre) to the scene's centre.
    #[inline]
    fn physical_intensity(&self, falloff: Falloff, anchor: Vec3A) -> f32 {
        match falloff {
            Falloff::InverseSquare { intensity } => intensity,
            Falloff::None => self.scene_center.map_or(1.0, |c| {
                (c - anchor).length_squared().max(f32::MIN_POSITIVE)
            }),
        }
    }

    /// A shadow ray from `p` toward `light`, drawn with `u`; None where the light sends
    /// nothing toward `p` (behind a spotlight's cone, inside a sphere light).
    pub(super) fn sample_light(
        &self,
        light: &Light,
        p: Vec3A,
        u: (f32, f32),
    ) -> Option<LightSample> {
        let color = Vec3A::from(light.color);
        let point_light = |position: Vec3A, g: f32, gain: f32| {
            let to = position - p;
            let d2 = to.length_squared();
            let d = d2.sqrt();
            (d > 0.0).then(|| LightSample {
                toward: Toward::Point(position),
                wi: to / d,
                light: color * (PI * gain * (g / d2).min(crate::appearance::MAX_FALLOFF_GAIN)),
                pdf: 0.0,
            })
        };
        match light.kind {
            LightKind::Point { position, falloff } => {
                let position = Vec3A::from(position);
                point_light(position, self.physical_intensity(falloff, position), 1.0)
            }
            LightKind::Spot {
                position,
                falloff,
                cone,
                radius,
            } => {
                let center = Vec3A::from(position);
                let sampled = if radius > 0.0 {
                    crate::sampler::disc_point(center, cone.direction, radius, u)
                } else {
                    center
                };
                // The cone is measured from the centre, as Whitted's is.
                let gain = cone.gain((p - center).try_normalize()?);
                (gain > 0.0)
                    .then(|| point_light(sampled, self.physical_intensity(falloff, center), gain))
                    .flatten()
            }
            LightKind::Directional { direction } => {
                let wi = -Vec3A::from(direction);
                Some(LightSample {
                    toward: Toward::Direction(wi),
                    wi,
                    light: color * PI,
                    pdf: 0.0,
                })
            }
            LightKind::Area { shape, falloff, .. } => {
                let g = self.physical_intensity(falloff, shape.center().into());
                match shape {
                    AreaShape::Rectangle {
                        corner,
                        edge_u,
                        edge_v,
                    } => {
                        let (eu, ev) = (Vec3A::from(edge_u), Vec3A::from(edge_v));
                        let x = Vec3A::from(corner) + eu * u.0 + ev * u.1;
                        let to = x - p;
                        let d2 = to.length_squared();
                        let wi = to.try_normalize()?;
                        let normal = eu.cross(ev);
                        let area = normal.length();
                        let cos_light = wi.dot(normal).abs() / area;
                        let pdf = d2 / (area * cos_light);
                        (pdf.is_finite() && pdf > 0.0).then(|| LightSample {
                            toward: Toward::Point(x),
                            wi,
                            light: color * (PI * g / area / pdf),
                            pdf,
                        })
                    }
                    AreaShape::Sphere { center, radius } => {
                        let center = Vec3A::from(center);
                        let cone = SphereCone::seen_from(center, radius, p)?;
                        let wi = cone.direction(u);
                        let t = Sphere::new(center.into(), radius)
                            .intersect_after(&Ray::new(p, wi), 0.0, f32::INFINITY)
                            // Rounding may miss the rim the cone's edge grazes.
                            .unwrap_or(cone.distance_to_center * cone.cos_max);
                        Some(LightSample {
                            toward: Toward::Point(p + wi * t),
                            wi,
                            light: color * (g / (radius * radius) / cone.pdf),
                            pdf: cone.pdf,
                        })
                    }
                }
            }
        }
    }

    /// The radiance of light `light`'s visible surface.
    pub(super) fn light_radiance(&self, light: &Light) -> Vec3A {
        let LightKind::Area { shape, falloff, .. } = light.kind else {
            return Vec3A::ZERO;
        };
        let g = self.physical_intensity(falloff, shape.center().into());
        let color = Vec3A::from(light.color);
        match shape {
            AreaShape::Rectangle { edge_u, edge_v, .. } => {
                color * (PI * g / edge_u.cross(edge_v).length())
            }
            AreaShape::Sphere { radius, .. } => color * (g / (radius * radius)),
        }
    }

    /// The solid-angle density with which `sample_light` draws unit direction `wi` from
    /// `p` toward area light `light`, whose surface lies `t` along it.
    pub(super) fn light_pdf(&self, light: &Light, p: Vec3A, wi: Vec3A, t: f32) -> f32 {
        let LightKind::Area { shape, .. } = light.kind else {
            return 0.0;
        };
        match shape {
            AreaShape::Rectangle { edge_u, edge_v, .. } => {
                let normal = Vec3A::from(edge_u.cross(edge_v));
                let area = normal.length();
                let cos_light = wi.dot(normal).abs() / area;
                let pdf = t * t / (area * cos_light);
                if pdf.is_finite() { pdf } else { 0.0 }
            }
            AreaShape::Sphere { center, radius } => {
                SphereCone::seen_from(center.into(), radius, p).map_or(0.0, |c| c.pdf)
            }
        }
    }
}

/// The cone of directions in which a sphere is seen from a point outside it, sampled
/// uniformly by solid angle.
struct SphereCone {
    /// The unit direction to the centre.
    axis: Vec3A,
    distance_to_center: f32,
    /// The cosine of the cone's half-angle.
    cos_max: f32,
    /// The uniform density over the cone's solid angle.
    pdf: f32,
}

impl SphereCone {
    /// None from inside (or on) the sphere.
    fn seen_from(center: Vec3A, radius: f32, p: Vec3A) -> Option<SphereCone> {
        let to = center - p;
        let d2 = to.length_squared();
        let sin2 = radius * radius / d2;
        // NaN (a point at the centre) refuses too.
        if sin2.is_nan() || sin2 >= 1.0 {
            return None;
        }
        let distance_to_center = d2.sqrt();
        // 1 − cos θ by the half-angle form, exact for small spheres far away.
        let cos_max = (1.0 - sin2).sqrt();
        let one_minus_cos = sin2 / (1.0 + cos_max);
        let pdf = 1.0 / (TAU * one_minus_cos);
        pdf.is_finite().then_some(SphereCone {
            axis: to / distance_to_center,
            distance_to_center,
            cos_max,
            pdf,
        })
    }

    /// The direction sample `u` stands for.
    fn direction(&self, u: (f32, f32)) -> Vec3A {
        let one_minus_cos_max = 1.0 - self.cos_max;
        let cos = 1.0 - u.0 * one_minus_cos_max;
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let (s, c) = (TAU * u.1).sin_cos();
        let (t, b) = crate::numerics::orthonormal_basis(Vec3::from(self.axis));
        (Vec3A::from(t) * (sin * c) + Vec3A::from(b) * (sin * s) + self.axis * cos).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Directions drawn in the cone hit the sphere, and the cone's solid angle is what the
    /// density says: 2π(1 − cos θ).
    #[test]
    fn sphere_cone_directions_hit_the_sphere() {
        let center = Vec3A::new(1.0, 2.0, -5.0);
        let p = Vec3A::new(0.5, -1.0, 3.0);
        let cone = SphereCone::seen_from(center, 1.5, p).unwrap();
        let sphere = Sphere::new(center.into(), 1.5);
        for i in 0..64 {
            let u = ((i as f32 + 0.5) / 64.0, ((i * 29) % 64) as f32 / 64.0);
            let wi = cone.direction(u);
            assert!(
                sphere
                    .intersect_after(&Ray::new(p, wi), 0.0, f32::INFINITY)
                    .is_some()
                    || wi.dot(cone.axis) > cone.cos_max - 1e-6,
                "{wi}"
            );
        }
        let d = (center - p).length() as f64;
        let solid = std::f64::consts::TAU * (1.0 - (1.0 - (1.5 / d).powi(2)).sqrt());
        assert!((1.0 / cone.pdf as f64 - solid).abs() < 1e-5 * solid);
        assert!(SphereCone::seen_from(center, 1.5, center + Vec3A::X).is_none());
    }
}
