//! A material's scattering at one hit, as the path tracer reads it: its lobes (Lambertian,
//! a normalised Phong highlight, a mirror that is perfect or a GGX microfacet conductor, and
//! transmission), their values, their densities and how to draw a direction from them.
//!
//! The fields keep their Whitted meaning, shared out so that no surface returns more light
//! than arrives: reflectivity and transparency (split by the Fresnel equations for `fresnel`
//! glass) take their shares first; the highlight (`specular`) and the Lambertian albedo,
//! colour × `diffuse` × (1 − `transparency`), share what is left, both scaled down alike when
//! together they would return more (so a coloured mirror keeps its colour, dimmed).

use crate::appearance::{reflect, schlick_reflectance};
use crate::numerics::orthonormal_basis;
use glam::Vec3A;
use std::f32::consts::{FRAC_1_PI, PI, TAU};

/// The lobes of one hit.
#[derive(Clone, Copy, Debug)]
pub(super) struct Lobes {
    /// The Lambertian albedo.
    diffuse: Vec3A,
    /// The normalised Phong lobe's albedo at normal incidence, and its exponent.
    highlight: f32,
    shininess: f32,
    /// The mirror's share, before a conductor's tint.
    mirror: f32,
    /// A conductor's reflectance at normal incidence (Schlick's curve rises from it).
    conductor: Option<Vec3A>,
    /// The GGX width α of a rough mirror; 0 for a perfect one.
    alpha: f32,
    /// The share transmitted (one direction: refracted or straight on).
    transmit: f32,
    /// How often each lobe is drawn: diffuse, highlight, mirror, transmission (summing to
    /// 1, or all 0 for a black surface).
    choose: [f32; 4],
    /// The shading normal and the true surface's normal, on the side the ray arrives from,
    /// and the unit direction back along the arriving ray.
    ns: Vec3A,
    n: Vec3A,
    wo: Vec3A,
}

/// What a draw from the lobes gives.
#[derive(Clone, Copy, Debug)]
pub(super) enum Scatter {
    /// A direction from the lobes that spread light: the throughput's factor
    /// f·cos/density, and the density (for multiple importance sampling).
    Spread { wi: Vec3A, weight: Vec3A, pdf: f32 },
    /// The perfect mirror direction, with this factor.
    Mirror { weight: Vec3A },
    /// Through the surface (refracted, or straight on), with this factor.
    Transmit { weight: Vec3A },
    /// Nothing: the path ends.
    Absorbed,
}

/// What a material gives a hit, before it is shared out (`Lobes::new`).
#[derive(Clone, Copy, Debug)]
pub(super) struct LobeInputs {
    /// Colour × diffuse × (1 − transparency): the Whitted diffuse term's factor.
    pub diffuse: Vec3A,
    pub specular: f32,
    pub shininess: f32,
    /// The shares reflected and transmitted at this angle (`Integrator::split`).
    pub reflected: f32,
    pub transmitted: f32,
    pub conductor: Option<Vec3A>,
    pub roughness: f32,
}

impl Lobes {
    /// The lobes at a hit seen from `wo` (unit, away from the surface) with shading normal
    /// `ns` and true normal `n` facing it.
    pub fn new(m: LobeInputs, ns: Vec3A, n: Vec3A, wo: Vec3A) -> Lobes {
        let (mut mirror, mut transmit) = (m.reflected, m.transmitted);
        let specular_sum = mirror + transmit;
        if specular_sum > 1.0 {
            mirror /= specular_sum;
            transmit /= specular_sum;
        }
        let left = (1.0 - mirror - transmit).max(0.0);
        let mut highlight = m.specular.min(1.0);
        let mut diffuse = m.diffuse.clamp(Vec3A::ZERO, Vec3A::ONE);
        let asked = highlight + diffuse.max_element();
        if asked > left {
            let scale = left / asked;
            highlight *= scale;
            diffuse *= scale;
        }
        let mirror_albedo = match m.conductor {
            Some(f0) => mirror * mean(f0),
            None => mirror,
        };
        let mut choose = [mean(diffuse), highlight, mirror_albedo, transmit];
        let total: f32 = choose.iter().sum();
        if total > 0.0 {
            choose.iter_mut().for_each(|p| *p /= total);
        }
        Lobes {
            diffuse,
            highlight,
            shininess: m.shininess,
            mirror,
            conductor: m.conductor,
            alpha: m.roughness * m.roughness,
            transmit,
            choose,
            ns,
            n,
            wo,
        }
    }

    /// Whether some lobe spreads light over directions, so that light sampled toward a
    /// light can be scattered toward the viewer.
    pub fn spreads(&self) -> bool {
        self.choose[0] > 0.0 || self.choose[1] > 0.0 || (self.choose[2] > 0.0 && self.alpha > 0.0)
    }

    /// The mirror's reflectance seen at cosine `cos` to the (micro)facet's normal.
    #[inline]
    fn mirror_tint(&self, cos: f32) -> Vec3A {
        match self.conductor {
            Some(f0) => schlick_reflectance(cos, f0) * self.mirror,
            None => Vec3A::splat(self.mirror),
        }
    }

    /// The lobes that spread light, for light arriving along unit `wi`: their value f
    /// (without the cosine) and the density with which `sample` draws `wi`.
    pub fn eval(&self, wi: Vec3A) -> (Vec3A, f32) {
        let (ns, wo) = (self.ns, self.wo);
        let cos_i = wi.dot(ns);
        // Light from below the true surface, or below the shading normal, is not reflected.
        if cos_i <= 0.0 || wi.dot(self.n) <= 0.0 {
            return (Vec3A::ZERO, 0.0);
        }
        let mut f = Vec3A::ZERO;
        let mut pdf = 0.0;
        if self.choose[0] > 0.0 {
            f += self.diffuse * FRAC_1_PI;
            pdf += self.choose[0] * cos_i * FRAC_1_PI;
        }
        if self.choose[1] > 0.0 {
            let c = reflect(-wo, ns).dot(wi);
            if c > 0.0 {
                let lobe = c.powf(self.shininess);
                f += Vec3A::splat(self.highlight * (self.shininess + 2.0) / TAU * lobe);
                pdf += self.choose[1] * (self.shininess + 1.0) / TAU * lobe;
            }
        }
        if self.choose[2] > 0.0 && self.alpha > 0.0 {
            let cos_o = wo.dot(ns);
            if let (true, Some(h)) = (cos_o > 0.0, (wo + wi).try_normalize()) {
                let cos_h = h.dot(ns);
                let d = ggx_d(cos_h, self.alpha);
                let g = ggx_g1(cos_o, self.alpha) * ggx_g1(cos_i, self.alpha);
                let wo_h = wo.dot(h).max(1e-8);
                f += self.mirror_tint(wo_h) * (d * g / (4.0 * cos_o * cos_i));
                pdf += self.choose[2] * d * cos_h / (4.0 * wo_h);
            }
        }
        (f, pdf)
    }

    /// A direction drawn from the lobes with sample `u`.
    pub fn sample(&self, u: (f32, f32)) -> Scatter {
        // The first number picks the lobe, then is stretched back over [0, 1): a stratified
        // sample stays stratified within each lobe.
        let mut x = u.0;
        let mut lobe = 0;
        while lobe < 3 && (x >= self.choose[lobe] || self.choose[lobe] == 0.0) {
            x -= self.choose[lobe];
            lobe += 1;
        }
        let p = self.choose[lobe];
        if p <= 0.0 {
            return Scatter::Absorbed;
        }
        let u = ((x / p).clamp(0.0, 1.0 - f32::EPSILON / 2.0), u.1);
        let wi = match lobe {
            0 => around(self.ns, cosine_hemisphere(u)),
            1 => {
                let cos = u.0.powf(1.0 / (self.shininess + 1.0));
                around(reflect(-self.wo, self.ns), cone_point(cos, u.1))
            }
            2 if self.alpha == 0.0 => {
                return Scatter::Mirror {
                    weight: self.mirror_tint(self.wo.dot(self.ns)) / p,
                };
            }
            2 => {
                let cos = (1.0 / (1.0 + self.alpha * self.alpha * u.0 / (1.0 - u.0))).sqrt();
                let m = around(self.ns, cone_point(cos, u.1));
                reflect(-self.wo, m)
            }
            _ => {
                return Scatter::Transmit {
                    weight: Vec3A::splat(self.transmit / p),
                };
            }
        };
        let (f, pdf) = self.eval(wi);
        if pdf > 0.0 && f != Vec3A::ZERO {
            Scatter::Spread {
                wi,
                weight: f * (wi.dot(self.ns) / pdf),
                pdf,
            }
        } else {
            Scatter::Absorbed
        }
    }
}

/// The mean of three channels.
#[inline]
fn mean(c: Vec3A) -> f32 {
    (c.x + c.y + c.z) / 3.0
}

/// GGX's distribution of microfacet normals at cosine `cos` to the normal.
#[inline]
fn ggx_d(cos: f32, alpha: f32) -> f32 {
    if cos <= 0.0 {
        return 0.0;
    }
    let c2 = cos * cos;
    let a2 = alpha * alpha;
    let denom = c2 * (a2 - 1.0) + 1.0;
    a2 / (PI * denom * denom)
}

/// Smith's masking for GGX of a direction at cosine `cos` to the normal.
#[inline]
fn ggx_g1(cos: f32, alpha: f32) -> f32 {
    let c2 = cos * cos;
    let tan2 = (1.0 - c2).max(0.0) / c2;
    2.0 / (1.0 + (1.0 + alpha * alpha * tan2).sqrt())
}

/// A direction at cosine `cos` to the pole, turned `2π·v` about it, in the pole's frame.
#[inline]
fn cone_point(cos: f32, v: f32) -> Vec3A {
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let (s, c) = (TAU * v).sin_cos();
    Vec3A::new(sin * c, sin * s, cos)
}

/// A direction of the hemisphere about the pole drawn with density cos/π (Malley's method).
#[inline]
fn cosine_hemisphere(u: (f32, f32)) -> Vec3A {
    let (x, y) = crate::sampler::concentric_disc(u);
    Vec3A::new(x, y, (1.0 - x * x - y * y).max(0.0).sqrt())
}

/// `local` (in a frame whose pole is z) turned into the frame whose pole is unit `pole`.
#[inline]
fn around(pole: Vec3A, local: Vec3A) -> Vec3A {
    let (t, b) = orthonormal_basis(pole.into());
    Vec3A::from(t) * local.x + Vec3A::from(b) * local.y + pole * local.z
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inputs() -> LobeInputs {
        LobeInputs {
            diffuse: Vec3A::new(0.7, 0.5, 0.3),
            specular: 0.0,
            shininess: 20.0,
            reflected: 0.0,
            transmitted: 0.0,
            conductor: None,
            roughness: 0.0,
        }
    }

    /// The albedo ∫ f·cos dω, estimated from the lobes' own samples, against its value;
    /// and the densities `sample` reports against a numerical integral of `eval`'s density
    /// over the sphere (it must integrate to the share of lobes that spread light).
    fn check(inputs: LobeInputs, wo: Vec3A, expected_albedo: Vec3A, tolerance: f32) {
        let n = Vec3A::Z;
        let lobes = Lobes::new(inputs, n, n, wo);
        let count = 256u32;
        let mut albedo = Vec3A::ZERO;
        for i in 0..count {
            for j in 0..count {
                let u = (
                    (i as f32 + 0.5) / count as f32,
                    (j as f32 + 0.5) / count as f32,
                );
                match lobes.sample(u) {
                    Scatter::Spread { wi, weight, pdf } => {
                        let (f, p) = lobes.eval(wi);
                        assert!((p - pdf).abs() <= 1e-4 * pdf, "{p} {pdf}");
                        assert!((f * wi.z / pdf - weight).abs().max_element() < 1e-3);
                        albedo += weight;
                    }
                    Scatter::Mirror { weight } | Scatter::Transmit { weight } => albedo += weight,
                    Scatter::Absorbed => {}
                }
            }
        }
        albedo /= (count * count) as f32;
        assert!(
            (albedo - expected_albedo).abs().max_element() < tolerance,
            "{albedo} against {expected_albedo}"
        );
        // ∫ pdf dω over the sphere by a midpoint rule in (cos θ, φ).
        let mut total = 0.0f64;
        let k = 512;
        for a in 0..k {
            for b in 0..k {
                let cos = (a as f32 + 0.5) / k as f32 * 2.0 - 1.0;
                let w = cone_point(cos, (b as f32 + 0.5) / k as f32);
                total += lobes.eval(w).1 as f64 * (2.0 / k as f64) * (TAU as f64 / k as f64);
            }
        }
        let spreading: f32 = lobes.choose[0]
            + lobes.choose[1]
            + if lobes.alpha > 0.0 {
                lobes.choose[2]
            } else {
                0.0
            };
        assert!(
            (total as f32 - spreading).abs() < 0.02,
            "density integrates to {total}, not {spreading}"
        );
    }

    #[test]
    fn lambertian_returns_its_albedo() {
        let wo = Vec3A::new(0.3, 0.1, 0.9).normalize();
        check(inputs(), wo, Vec3A::new(0.7, 0.5, 0.3), 1e-3);
    }

    #[test]
    fn shares_never_return_more_than_arrives() {
        // Colour 0.8 with a 0.5 highlight and a 0.3 mirror: the mirror takes 0.3, and the
        // highlight and the diffuse share the 0.7 left in their proportions, 5 : 8.
        let m = LobeInputs {
            diffuse: Vec3A::splat(0.8),
            specular: 0.5,
            reflected: 0.3,
            ..inputs()
        };
        let lobes = Lobes::new(m, Vec3A::Z, Vec3A::Z, Vec3A::Z);
        assert_eq!(lobes.mirror, 0.3);
        assert!((lobes.highlight - 0.7 * 0.5 / 1.3).abs() < 1e-6);
        assert!(
            (lobes.diffuse - Vec3A::splat(0.7 * 0.8 / 1.3))
                .abs()
                .max_element()
                < 1e-6
        );
        // A material that asks for no more than arrives keeps every share.
        let modest = Lobes::new(
            LobeInputs {
                diffuse: Vec3A::new(0.5, 0.2, 0.1),
                specular: 0.2,
                reflected: 0.3,
                ..inputs()
            },
            Vec3A::Z,
            Vec3A::Z,
            Vec3A::Z,
        );
        assert_eq!(modest.highlight, 0.2);
        assert_eq!(modest.diffuse, Vec3A::new(0.5, 0.2, 0.1));
        let over = LobeInputs {
            reflected: 0.9,
            transmitted: 0.6,
            ..m
        };
        let lobes = Lobes::new(over, Vec3A::Z, Vec3A::Z, Vec3A::Z);
        assert!((lobes.mirror + lobes.transmit - 1.0).abs() < 1e-6);
        assert!(lobes.highlight < 1e-6 && lobes.diffuse.max_element() < 1e-6);
    }

    #[test]
    fn normalised_phong_keeps_its_weight_at_normal_incidence() {
        // At normal incidence the whole lobe lies above the surface: its albedo is
        // ∫ (n+2)/2π cosⁿα cos θ dω = 1 times the weight (α = θ here).
        let m = LobeInputs {
            diffuse: Vec3A::ZERO,
            specular: 0.6,
            shininess: 30.0,
            ..inputs()
        };
        check(m, Vec3A::Z, Vec3A::splat(0.6), 2e-3);
    }

    #[test]
    fn rough_mirror_loses_only_what_masking_hides() {
        // A GGX mirror's albedo is below its reflectance by the energy its single-scattering
        // model loses: a few percent at α = 0.09 and normal incidence.
        let m = LobeInputs {
            diffuse: Vec3A::ZERO,
            reflected: 1.0,
            roughness: 0.3,
            ..inputs()
        };
        let lobes = Lobes::new(m, Vec3A::Z, Vec3A::Z, Vec3A::Z);
        assert!(lobes.spreads());
        check(m, Vec3A::Z, Vec3A::splat(0.99), 0.02);
        let smooth = Lobes::new(
            LobeInputs {
                roughness: 0.0,
                ..m
            },
            Vec3A::Z,
            Vec3A::Z,
            Vec3A::Z,
        );
        assert!(!smooth.spreads());
        assert!(
            matches!(smooth.sample((0.5, 0.5)), Scatter::Mirror { weight } if weight == Vec3A::ONE)
        );
    }
}
