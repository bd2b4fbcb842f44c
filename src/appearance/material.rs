//! Phong surface terms and the directions of mirror reflection and refraction.

use super::relief::Relief;
use super::texture::Texture;
use crate::limits;
use crate::messages::FieldProblem;
use glam::{Vec3, Vec3A};

/// A Whitted material, as in the seed: Phong local shading, plus a mirror term and a
/// transmitted term that may bend by Snell's law.
///
/// Colour = (1 − transparency)·local + reflectivity·reflected + transparency·transmitted;
/// with `fresnel`, the reflected and transmitted shares of reflectivity + transparency are
/// instead split by the dielectric's Fresnel reflectance at each hit.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// The surface colour: a solid colour, a pattern or an image.
    pub texture: Texture,
    /// Multiplies the scene's ambient light.
    pub ambient: f32,
    /// Multiplies the light arriving straight from the lights.
    pub diffuse: f32,
    /// Strength of the Phong highlight.
    pub specular: f32,
    /// Phong exponent: the larger, the smaller and sharper the highlight.
    pub shininess: f32,
    /// Fraction of the mirror-reflected light added, 0..1.
    pub reflectivity: f32,
    /// Fraction of light transmitted through the surface, 0..1.
    pub transparency: f32,
    /// Index of refraction of the inside; None for a surface that transmits without bending.
    pub eta: Option<f32>,
    /// Light the surface gives off itself, added unlit (a glowing lamp, a screen); black
    /// for the seed's materials.
    pub emission: Vec3,
    /// Whether reflection and transmission follow the Fresnel equations of a dielectric of
    /// index `eta` (reflection rising to all of it at grazing angles and past the critical
    /// angle) rather than the fixed `reflectivity` and `transparency`; false for the
    /// seed's Whitted materials.
    pub fresnel: bool,
    /// How far mirror reflection and refraction spread into glossy lobes: 0 is a perfect
    /// mirror, 1 nearly diffuse (the GGX microfacet roughness √α, one sampled direction per
    /// subsample).
    pub roughness: f32,
    /// Beer–Lambert absorption of the inside per scene unit, per channel: light that
    /// travels d inside keeps exp(−absorption·d) of itself. Zero for clear media.
    pub absorption: Vec3,
    /// A metal's reflectance at normal incidence, per channel (gold, copper): the mirror
    /// reflection is tinted by Schlick's Fresnel curve from it, rising to white at grazing
    /// angles. None for the seed's untinted mirrors.
    pub conductor: Option<Vec3>,
    /// Bumps or a normal map tilting the shading normal; None for a smooth surface.
    pub relief: Option<Relief>,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            texture: Texture::Solid(Vec3::splat(0.8)),
            ambient: 1.0,
            diffuse: 1.0,
            specular: 0.5,
            shininess: 50.0,
            reflectivity: 0.0,
            transparency: 0.0,
            eta: None,
            emission: Vec3::ZERO,
            fresnel: false,
            roughness: 0.0,
            absorption: Vec3::ZERO,
            conductor: None,
            relief: None,
        }
    }
}

impl Material {
    /// Checks the rules every material follows, whether a scene file or an edit made it:
    /// each number within its limit (limits.rs), and the rules between fields (`fresnel`
    /// needs an `eta` other than 1, `roughness` a mirror, `absorption` transparency, a
    /// `conductor` a mirror that is not Fresnel glass). The first problem is returned, in
    /// the order of the file's fields.
    pub fn check(&self) -> Result<(), FieldProblem> {
        let reflectance = *limits::REFLECTANCE.end();
        if let Texture::Solid(c) = self.texture {
            FieldProblem::check_color(
                "color",
                c.to_array(),
                reflectance,
                limits::REFLECTANCE_BOUND,
            )?;
        }
        if let Some(eta) = self.eta {
            FieldProblem::check_range("eta", eta, &limits::ETA)?;
        }
        if self.fresnel && !matches!(self.eta, Some(e) if e != 1.0) {
            return Err(FieldProblem::new(
                "fresnel",
                "`fresnel = true` needs a refractive material: an `eta` other than 1",
            ));
        }
        FieldProblem::check_range("roughness", self.roughness, &limits::ROUGHNESS)?;
        FieldProblem::check_range("transparency", self.transparency, &limits::FRACTION)?;
        FieldProblem::check_range("reflectivity", self.reflectivity, &limits::FRACTION)?;
        let refracts = self.transparency > 0.0 && self.bends();
        if self.roughness > 0.0 && self.reflectivity == 0.0 && !self.fresnel && !refracts {
            return Err(FieldProblem::new(
                "roughness",
                "`roughness` spreads mirror reflection and refraction: it needs a \
                 `reflectivity` above 0, `fresnel = true`, or a `transparency` above 0 with an \
                 `eta` other than 1",
            ));
        }
        if self.absorption != Vec3::ZERO {
            if self.transparency == 0.0 {
                return Err(FieldProblem::new(
                    "absorption",
                    "`absorption` tints light travelling inside: it needs a `transparency` \
                     above 0",
                ));
            }
            FieldProblem::check_color(
                "absorption",
                self.absorption.to_array(),
                limits::MAX_EXTINCTION,
                "per scene unit",
            )?;
        }
        if let Some(c) = self.conductor {
            if self.reflectivity == 0.0 {
                return Err(FieldProblem::new(
                    "conductor",
                    "`conductor` tints mirror reflection: it needs a `reflectivity` above 0",
                ));
            }
            if self.fresnel {
                return Err(FieldProblem::new(
                    "conductor",
                    "a material is either a `conductor` (a metal) or `fresnel` glass, not both",
                ));
            }
            FieldProblem::check_color(
                "conductor",
                c.to_array(),
                reflectance,
                limits::REFLECTANCE_BOUND,
            )?;
        }
        let phong = 0.0..=limits::MAX_PHONG_FACTOR;
        FieldProblem::check_range("ambient", self.ambient, &phong)?;
        FieldProblem::check_range("diffuse", self.diffuse, &phong)?;
        FieldProblem::check_range("specular", self.specular, &phong)?;
        FieldProblem::check_range("shininess", self.shininess, &(0.0..=limits::MAX_SHININESS))?;
        FieldProblem::check_color(
            "emission",
            self.emission.to_array(),
            limits::MAX_RADIANCE,
            limits::RADIANCE_BOUND,
        )?;
        match &self.relief {
            None => Ok(()),
            Some(Relief::Bump { height, depth }) => {
                if !matches!(height, Texture::Pattern(_) | Texture::Image { .. }) {
                    return Err(FieldProblem::new(
                        "bump",
                        "a bump map's height comes from a pattern (noise, marble, …) or an \
                         image; a solid colour, a checker or stripes is flat between its edges",
                    ));
                }
                FieldProblem::check_range("bump_depth", *depth, &limits::BUMP_DEPTH)
            }
            Some(Relief::NormalMap { map, strength }) => {
                if !matches!(map, Texture::Image { .. }) {
                    return Err(FieldProblem::new(
                        "normal_map",
                        "a normal map is a picture: a texture of type \"image\"",
                    ));
                }
                FieldProblem::check_range("normal_strength", *strength, &limits::NORMAL_STRENGTH)
            }
        }
    }

    /// Whether light through this surface changes direction (an index of refraction other
    /// than 1).
    #[inline]
    pub fn bends(&self) -> bool {
        matches!(self.eta, Some(eta) if eta != 1.0)
    }

    /// How much of the light crossing this surface once goes on, tinted by its colour:
    /// the clearer the surface, the less tint (a 90% clear green glass casts a pale green
    /// shadow).
    pub fn shadow_filter(&self) -> Vec3 {
        let t = self.transparency;
        (self.texture.mean() * (1.0 - t) + Vec3::splat(t)) * t
    }
}

/// The fraction of unpolarised light a smooth dielectric boundary reflects, for light
/// arriving at `cos_i` from the normal, with `eta_ratio` = η(incident side) / η(other side):
/// the mean of the s- and p-polarised Fresnel reflectances; 1 past the critical angle (the
/// rest, 1 − R, is transmitted).
#[inline]
pub fn fresnel_reflectance(cos_i: f32, eta_ratio: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = eta_ratio * eta_ratio * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let rs = (eta_ratio * cos_i - cos_t) / (eta_ratio * cos_i + cos_t);
    let rp = (cos_i - eta_ratio * cos_t) / (cos_i + eta_ratio * cos_t);
    (0.5 * (rs * rs + rp * rp)).clamp(0.0, 1.0)
}

/// Schlick's approximation of a conductor's Fresnel reflectance at `cos_i` from the normal,
/// from its reflectance `f0` at normal incidence.
#[inline]
pub fn schlick_reflectance(cos_i: f32, f0: Vec3A) -> Vec3A {
    let m = (1.0 - cos_i.clamp(0.0, 1.0)).powi(5);
    f0 + (Vec3A::ONE - f0) * m
}

/// Mirror reflection of direction `d` about unit normal `n`.
#[inline]
pub fn reflect(d: Vec3A, n: Vec3A) -> Vec3A {
    d - n * (2.0 * d.dot(n))
}

/// Refraction of unit direction `d` through a surface with unit normal `n` facing against
/// `d`, where `eta_ratio` = η(incident side) / η(transmitted side). None on total internal
/// reflection. At a ratio of exactly 1 the direction is returned unchanged, so an eta-1
/// object bends nothing; near 1 the result varies continuously with the ratio.
#[inline]
pub fn refract(d: Vec3A, n: Vec3A, eta_ratio: f32) -> Option<Vec3A> {
    if eta_ratio == 1.0 {
        return Some(d);
    }
    let cos_i = (-d.dot(n)).clamp(0.0, 1.0);
    let sin2_i = (1.0 - cos_i * cos_i).max(0.0);
    let sin2_t = eta_ratio * eta_ratio * sin2_i;
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some(d * eta_ratio + n * (eta_ratio * cos_i - cos_t))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each rule of `Material::check`, at its limit and just past it, and the rules between
    /// fields: the field named is the one at fault.
    #[test]
    fn check_holds_each_rule_at_its_limit() {
        let d = Material::default();
        assert_eq!(d.check(), Ok(()));
        let accepted = [
            Material {
                ambient: 1000.0,
                shininess: 10000.0,
                emission: Vec3::splat(1.0e4),
                ..d.clone()
            },
            Material {
                roughness: 1.0,
                reflectivity: 1.0,
                conductor: Some(Vec3::ONE),
                ..d.clone()
            },
            Material {
                transparency: 1.0,
                eta: Some(10.0),
                fresnel: true,
                roughness: 0.5,
                absorption: Vec3::splat(1.0e12),
                ..d.clone()
            },
            Material {
                transparency: 0.8,
                eta: Some(1.33),
                roughness: 0.2,
                ..d.clone()
            },
        ];
        for m in accepted {
            assert_eq!(m.check(), Ok(()), "{m:?}");
        }
        let refused = [
            (
                "color",
                Material {
                    texture: Texture::Solid(Vec3::new(1.01, 0.0, 0.0)),
                    ..d.clone()
                },
            ),
            (
                "ambient",
                Material {
                    ambient: 1000.5,
                    ..d.clone()
                },
            ),
            (
                "diffuse",
                Material {
                    diffuse: -0.01,
                    ..d.clone()
                },
            ),
            (
                "specular",
                Material {
                    specular: f32::INFINITY,
                    ..d.clone()
                },
            ),
            (
                "shininess",
                Material {
                    shininess: 10001.0,
                    ..d.clone()
                },
            ),
            (
                "reflectivity",
                Material {
                    reflectivity: 1.01,
                    ..d.clone()
                },
            ),
            (
                "transparency",
                Material {
                    transparency: -0.01,
                    ..d.clone()
                },
            ),
            (
                "eta",
                Material {
                    eta: Some(10.5),
                    ..d.clone()
                },
            ),
            (
                "eta",
                Material {
                    eta: Some(f32::NAN),
                    ..d.clone()
                },
            ),
            (
                "emission",
                Material {
                    emission: Vec3::new(0.0, 1.0e5, 0.0),
                    ..d.clone()
                },
            ),
            (
                "roughness",
                Material {
                    roughness: 0.5,
                    ..d.clone()
                },
            ),
            (
                "roughness",
                Material {
                    roughness: 0.5,
                    transparency: 0.5,
                    eta: Some(1.0),
                    ..d.clone()
                },
            ),
            (
                "roughness",
                Material {
                    roughness: 1.5,
                    reflectivity: 1.0,
                    ..d.clone()
                },
            ),
            (
                "fresnel",
                Material {
                    fresnel: true,
                    ..d.clone()
                },
            ),
            (
                "fresnel",
                Material {
                    fresnel: true,
                    eta: Some(1.0),
                    ..d.clone()
                },
            ),
            (
                "absorption",
                Material {
                    absorption: Vec3::X,
                    ..d.clone()
                },
            ),
            (
                "absorption",
                Material {
                    absorption: Vec3::NAN,
                    transparency: 0.5,
                    ..d.clone()
                },
            ),
            (
                "conductor",
                Material {
                    conductor: Some(Vec3::ONE),
                    ..d.clone()
                },
            ),
            (
                "conductor",
                Material {
                    conductor: Some(Vec3::ONE),
                    reflectivity: 1.0,
                    fresnel: true,
                    eta: Some(1.5),
                    ..d.clone()
                },
            ),
            (
                "conductor",
                Material {
                    conductor: Some(Vec3::splat(2.0)),
                    reflectivity: 1.0,
                    ..d.clone()
                },
            ),
        ];
        for (field, m) in refused {
            let problem = m.check().unwrap_err();
            assert_eq!(problem.field, field, "{m:?}");
            assert!(
                problem.message.contains(&format!("`{field}")),
                "{problem:?}"
            );
        }
    }

    fn dir_at(angle_deg: f32) -> Vec3A {
        // Travelling down onto the plane y = 0 at `angle` from the normal, in the xy plane.
        let a = angle_deg.to_radians();
        Vec3A::new(a.sin(), -a.cos(), 0.0)
    }

    #[test]
    fn reflection_flips_the_normal_component() {
        let r = reflect(dir_at(30.0), Vec3A::Y);
        assert!((r - Vec3A::new(0.5, 3f32.sqrt() / 2.0, 0.0)).length() < 1e-6);
    }

    #[test]
    fn snell_law_at_a_plane() {
        for (eta, angle) in [(1.5f32, 30.0f32), (1.43, 60.0), (1.002, 45.0), (2.4, 10.0)] {
            let t = refract(dir_at(angle), Vec3A::Y, 1.0 / eta).unwrap();
            assert!((t.length() - 1.0).abs() < 1e-6);
            let sin_t = t.x;
            let expected = angle.to_radians().sin() / eta;
            assert!((sin_t - expected).abs() < 1e-6, "eta {eta} angle {angle}");
            assert!(t.y < 0.0, "the refracted ray continues into the surface");
        }
    }

    #[test]
    fn eta_one_is_the_identity() {
        for angle in [0.0, 10.0, 45.0, 89.9] {
            let d = dir_at(angle);
            assert_eq!(refract(d, Vec3A::Y, 1.0), Some(d));
        }
    }

    #[test]
    fn total_internal_reflection_past_the_critical_angle() {
        // From glass (1.5) into air: critical angle asin(1/1.5) ≈ 41.81°.
        let critical = (1.0f32 / 1.5).asin().to_degrees();
        assert!(refract(dir_at(critical - 0.5), Vec3A::Y, 1.5).is_some());
        assert!(refract(dir_at(critical + 0.5), Vec3A::Y, 1.5).is_none());
        assert!(refract(dir_at(89.999), Vec3A::Y, 1.5).is_none());
    }

    #[test]
    fn refraction_is_continuous_near_eta_one() {
        let d = dir_at(60.0);
        let exact = refract(d, Vec3A::Y, 1.0).unwrap();
        let near = refract(d, Vec3A::Y, 1.0 / 1.002).unwrap();
        let angle = exact.dot(near).clamp(-1.0, 1.0).acos().to_degrees();
        // d(θt)/d(η) = tan θ at η = 1, so 0.002 bends by about 0.002·tan 60° rad ≈ 0.2°.
        assert!(angle > 0.1 && angle < 0.3, "bent by {angle}°");
    }

    /// The textbook Fresnel reflectance in f64, from the angles themselves.
    fn fresnel_f64(theta_i: f64, n1: f64, n2: f64) -> f64 {
        let sin_t = n1 / n2 * theta_i.sin();
        if sin_t >= 1.0 {
            return 1.0;
        }
        let theta_t = sin_t.asin();
        let (ci, ct) = (theta_i.cos(), theta_t.cos());
        let rs = (n1 * ci - n2 * ct) / (n1 * ci + n2 * ct);
        let rp = (n2 * ci - n1 * ct) / (n2 * ci + n1 * ct);
        0.5 * (rs * rs + rp * rp)
    }

    #[test]
    fn fresnel_reflectance_matches_the_exact_formula() {
        for (n1, n2) in [(1.0, 1.5), (1.5, 1.0), (1.0, 1.33), (1.33, 1.5), (1.0, 2.4)] {
            for k in 0..=90 {
                let theta = (k as f64).to_radians();
                let got = fresnel_reflectance(theta.cos() as f32, (n1 / n2) as f32) as f64;
                let want = fresnel_f64(theta, n1, n2);
                assert!(
                    (got - want).abs() < 1e-5,
                    "{n1}→{n2} at {k}°: {got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn fresnel_at_normal_incidence_brewster_grazing_and_past_the_critical_angle() {
        // Normal incidence: ((n1 − n2) / (n1 + n2))² = 0.04 for glass.
        assert!((fresnel_reflectance(1.0, 1.0 / 1.5) - 0.04).abs() < 1e-6);
        // At Brewster's angle, atan(1.5), only the s-polarised half reflects.
        let brewster = 1.5f64.atan();
        let rs = {
            let t = (brewster.sin() / 1.5).asin();
            let (ci, ct) = (brewster.cos(), t.cos());
            (ci - 1.5 * ct) / (ci + 1.5 * ct)
        };
        let r = fresnel_reflectance(brewster.cos() as f32, 1.0 / 1.5) as f64;
        assert!((r - 0.5 * rs * rs).abs() < 1e-6, "{r}");
        // Grazing: everything.
        assert!(fresnel_reflectance(0.0, 1.0 / 1.5) > 0.999);
        // From glass to air past asin(1/1.5) ≈ 41.8°: total internal reflection.
        let past = 42.0f32.to_radians().cos();
        assert_eq!(fresnel_reflectance(past, 1.5), 1.0);
        assert!(fresnel_reflectance(41.5f32.to_radians().cos(), 1.5) < 1.0);
        // The same boundary crossed either way reflects the same (reciprocity).
        let theta_i = 30f32.to_radians();
        let theta_t = (theta_i.sin() / 1.5).asin();
        let there = fresnel_reflectance(theta_i.cos(), 1.0 / 1.5);
        let back = fresnel_reflectance(theta_t.cos(), 1.5);
        assert!((there - back).abs() < 1e-6);
    }

    #[test]
    fn clear_glass_casts_a_pale_shadow_and_opaque_none() {
        let green = Material {
            texture: Texture::Solid(Vec3::new(0.0, 1.0, 0.0)),
            transparency: 0.9,
            ..Material::default()
        };
        let f = green.shadow_filter();
        assert!((f - Vec3::new(0.81, 0.9, 0.81)).length() < 1e-6);
        let opaque = Material::default();
        assert_eq!(opaque.shadow_filter(), Vec3::ZERO);
    }
}
