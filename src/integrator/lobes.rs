//! A material's scattering at one hit, as the path tracer reads it: its lobes (Lambertian,
//! a normalised Phong highlight, a mirror that is perfect or a GGX microfacet conductor, and
//! transmission, straight on, refracted, or through a rough interface), their values, their
//! densities and how to draw a direction from them.
//!
//! The fields keep their Whitted meaning, shared out so that no surface returns more light
//! than arrives: reflectivity and transparency (split by the Fresnel equations for `fresnel`
//! glass) take their shares first; the highlight (`specular`) and the Lambertian albedo,
//! colour × `diffuse` × (1 − `transparency`), share what is left, both scaled down alike when
//! together they would return more (so a coloured mirror keeps its colour, dimmed).
//!
//! A rough surface that bends light joins its mirror and transmission into one lobe that
//! reflects or refracts about each microfacet drawn (Walter et al. 2007), split there by the
//! Fresnel equations for `fresnel` glass, else by the material's fixed shares.

use super::microfacet::{ggx_d, ggx_g1, ggx_visible_normal};
use crate::appearance::{fresnel_reflectance, reflect, refract, schlick_reflectance};
use crate::numerics::orthonormal_basis;
use glam::Vec3A;
use std::f32::consts::{FRAC_1_PI, TAU};

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
    /// The share transmitted (one direction: refracted or straight on, unless rough).
    transmit: f32,
    /// A rough surface that bends light: the mirror and transmission are one lobe.
    interface: Option<Interface>,
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
    /// Through a rough surface that bends light, along `wi`, with this factor.
    Refract { wi: Vec3A, weight: Vec3A },
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
    /// How the surface bends light, when it does.
    pub interface: Option<Interface>,
}

/// A surface between two media that bends light.
#[derive(Clone, Copy, Debug)]
pub(super) struct Interface {
    /// η(incident side) / η(other side).
    pub eta: f32,
    /// Whether each microfacet splits light by the Fresnel equations (`fresnel` glass),
    /// rather than in the material's fixed shares.
    pub fresnel: bool,
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
        let alpha = m.roughness * m.roughness;
        // Fresnel glass's shares are split again at each facet, so that light the mean
        // surface would reflect whole may still be refracted by a tilted facet.
        let interface = m
            .interface
            .filter(|i| alpha > 0.0 && (transmit > 0.0 || i.fresnel));
        let mut choose = match (interface, m.conductor) {
            (Some(_), _) => [mean(diffuse), highlight, mirror + transmit, 0.0],
            (None, Some(f0)) => [mean(diffuse), highlight, mirror * mean(f0), transmit],
            (None, None) => [mean(diffuse), highlight, mirror, transmit],
        };
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
            alpha,
            transmit,
            interface,
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
        match (self.interface, self.conductor) {
            (Some(interface), _) => {
                Vec3A::splat((self.mirror + self.transmit) * self.reflected_share(interface, cos))
            }
            (None, Some(f0)) => schlick_reflectance(cos, f0) * self.mirror,
            (None, None) => Vec3A::splat(self.mirror),
        }
    }

    /// The share of a rough interface's light that a microfacet at cosine `cos` to the
    /// arriving direction reflects: all of it past the critical angle.
    #[inline]
    fn reflected_share(&self, interface: Interface, cos: f32) -> f32 {
        if interface.fresnel {
            return fresnel_reflectance(cos, interface.eta);
        }
        let sin2_t = interface.eta * interface.eta * (1.0 - cos * cos).max(0.0);
        if sin2_t >= 1.0 {
            1.0
        } else {
            self.mirror / (self.mirror + self.transmit)
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
                let wo_h = wo.dot(h);
                if wo_h > 0.0 {
                    let d = ggx_d(h.dot(ns), self.alpha);
                    let g_o = ggx_g1(cos_o, self.alpha);
                    let g = g_o * ggx_g1(cos_i, self.alpha);
                    let tint = self.mirror_tint(wo_h);
                    f += tint * (d * g / (4.0 * cos_o * cos_i));
                    // Visible normals drawn, reflected by the interface in its share.
                    let reflected = match self.interface {
                        Some(interface) => self.reflected_share(interface, wo_h),
                        None => 1.0,
                    };
                    pdf += self.choose[2] * reflected * g_o * d / (4.0 * cos_o);
                }
            }
        }
        (f, pdf)
    }

    /// A direction drawn from the lobes with sample `u`; a rough interface also asks
    /// `decide` for one number, to reflect or refract.
    pub fn sample(&self, u: (f32, f32), decide: impl FnOnce() -> f32) -> Scatter {
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
                if self.wo.dot(self.ns) <= 0.0 {
                    return Scatter::Absorbed;
                }
                let m = ggx_visible_normal(self.ns, self.alpha, self.wo, u);
                let cos_m = self.wo.dot(m);
                match self.interface {
                    Some(interface) if decide() >= self.reflected_share(interface, cos_m) => {
                        return self.refracted(interface, m, p);
                    }
                    _ => reflect(-self.wo, m),
                }
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

impl Lobes {
    /// The light a rough interface refracts through microfacet `m` (drawn among those `wo`
    /// sees), with the lobe drawn with probability `p`: the weight is the masking of the
    /// way out, as the other factors cancel against the density.
    fn refracted(&self, interface: Interface, m: Vec3A, p: f32) -> Scatter {
        let Some(wi) = refract(-self.wo, m, interface.eta) else {
            return Scatter::Absorbed;
        };
        let cos_i = -wi.dot(self.ns);
        if cos_i <= 0.0 || wi.dot(self.n) >= 0.0 {
            return Scatter::Absorbed;
        }
        let share = self.mirror + self.transmit;
        Scatter::Refract {
            wi,
            weight: Vec3A::splat(share * ggx_g1(cos_i, self.alpha) / p),
        }
    }
}

/// The mean of three channels.
#[inline]
fn mean(c: Vec3A) -> f32 {
    (c.x + c.y + c.z) / 3.0
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
            interface: None,
        }
    }

    /// The lobes' draws over a `count` × `count` grid of sample points, each with a third,
    /// independent number for a rough interface's choice.
    fn draws(lobes: &Lobes, count: u32) -> impl Iterator<Item = Scatter> + '_ {
        (0..count * count).map(move |k| {
            let (i, j) = (k / count, k % count);
            let u = (
                (i as f32 + 0.5) / count as f32,
                (j as f32 + 0.5) / count as f32,
            );
            let decide = ((i * 7919 + j * 104_729) % 1009) as f32 / 1009.0;
            lobes.sample(u, || decide)
        })
    }

    /// The albedo ∫ f·cos dω, estimated from the lobes' own samples, against its value;
    /// and the densities `sample` reports against a numerical integral of `eval`'s density
    /// over the sphere, which must equal the share of samples that spread light.
    fn check(inputs: LobeInputs, wo: Vec3A, expected_albedo: Vec3A, tolerance: f32) {
        let n = Vec3A::Z;
        let lobes = Lobes::new(inputs, n, n, wo);
        let count = 256u32;
        let mut albedo = Vec3A::ZERO;
        let mut spread = 0u32;
        for scatter in draws(&lobes, count) {
            match scatter {
                Scatter::Spread { wi, weight, pdf } => {
                    let (f, p) = lobes.eval(wi);
                    assert!((p - pdf).abs() <= 1e-4 * pdf, "{p} {pdf}");
                    assert!((f * wi.z / pdf - weight).abs().max_element() < 1e-3);
                    albedo += weight;
                    spread += 1;
                }
                Scatter::Refract { wi, weight } => {
                    assert!(wi.z < 0.0 && (wi.length() - 1.0).abs() < 1e-4);
                    albedo += weight;
                }
                Scatter::Mirror { weight } | Scatter::Transmit { weight } => albedo += weight,
                Scatter::Absorbed => {}
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
        let spreading = spread as f64 / (count * count) as f64;
        assert!(
            (total - spreading).abs() < 0.02,
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
            matches!(smooth.sample((0.5, 0.5), || 0.0), Scatter::Mirror { weight } if weight == Vec3A::ONE)
        );
    }

    /// Rough glass: at normal incidence light splits by the Fresnel equations (4% reflected
    /// for η = 1.5) and what masking hides is lost; the fixed shares of a non-Fresnel
    /// material are kept; from inside past the critical angle everything is reflected.
    #[test]
    fn rough_interface_shares_light_like_the_smooth_one() {
        let glass = |fresnel: bool, eta: f32, reflected: f32, transmitted: f32| LobeInputs {
            diffuse: Vec3A::ZERO,
            reflected,
            transmitted,
            roughness: 0.3,
            interface: Some(Interface { eta, fresnel }),
            ..inputs()
        };
        let wo = Vec3A::Z;
        let lobes = Lobes::new(glass(true, 1.0 / 1.5, 0.04, 0.96), Vec3A::Z, Vec3A::Z, wo);
        assert!(lobes.spreads());
        check(
            glass(true, 1.0 / 1.5, 0.04, 0.96),
            wo,
            Vec3A::splat(0.985),
            0.015,
        );
        // Reflected and refracted apart: the reflected share is Fresnel's at the facets.
        let count = 200u32;
        let (mut up, mut down) = (0.0f32, 0.0f32);
        for scatter in draws(&lobes, count) {
            match scatter {
                Scatter::Spread { weight, .. } => up += weight.x,
                Scatter::Refract { weight, .. } => down += weight.x,
                _ => {}
            }
        }
        let n = (count * count) as f32;
        assert!((up / n - 0.04).abs() < 0.01, "reflected {}", up / n);
        assert!((down / n - 0.95).abs() < 0.02, "refracted {}", down / n);
        // Fixed shares, 0.3 and 0.6, at a slant.
        let slant = Vec3A::new(0.5, 0.0, 0.8).normalize();
        check(
            glass(false, 1.0 / 1.5, 0.3, 0.6),
            slant,
            Vec3A::splat(0.88),
            0.025,
        );
        // From inside glass at 60° to the normal, past the critical angle (41.8°): the
        // facets near the mean normal reflect it all, and nothing is refracted.
        let inside = Vec3A::new(0.866, 0.0, 0.5);
        let lobes = Lobes::new(
            LobeInputs {
                roughness: 0.05,
                ..glass(true, 1.5, 1.0, 0.0)
            },
            Vec3A::Z,
            Vec3A::Z,
            inside,
        );
        assert!(lobes.interface.is_some());
        for i in 0..64 {
            let u = ((i as f32 + 0.5) / 64.0, 0.37);
            assert!(!matches!(
                lobes.sample(u, || 0.999),
                Scatter::Refract { .. }
            ));
        }
    }
}
