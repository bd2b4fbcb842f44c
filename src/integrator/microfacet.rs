//! The GGX (Trowbridge–Reitz) microfacet distribution of width α, as rough mirrors and rough
//! glass use it (Walter et al. 2007): its density of normals, Smith's masking, and two ways
//! to draw a microfacet normal: from the whole distribution, and from the part a direction
//! sees (Heitz 2018), whose weights stay at most 1 even at grazing angles.

use crate::numerics::orthonormal_basis;
use glam::Vec3A;
use std::f32::consts::{PI, TAU};

/// GGX's density of microfacet normals at cosine `cos` to the mean normal.
#[inline]
pub(super) fn ggx_d(cos: f32, alpha: f32) -> f32 {
    if cos <= 0.0 {
        return 0.0;
    }
    let c2 = cos * cos;
    let a2 = alpha * alpha;
    let denom = c2 * (a2 - 1.0) + 1.0;
    a2 / (PI * denom * denom)
}

/// Smith's masking for GGX of a direction at cosine `cos` (above 0) to the mean normal.
#[inline]
pub(super) fn ggx_g1(cos: f32, alpha: f32) -> f32 {
    let c2 = cos * cos;
    let tan2 = (1.0 - c2).max(0.0) / c2;
    2.0 / (1.0 + (1.0 + alpha * alpha * tan2).sqrt())
}

/// A microfacet normal about unit `n` drawn with density D(m)·(m·n) by sample `u`:
/// tan²θ = α²·u₁/(1 − u₁), φ = 2π·u₂.
#[inline]
pub(super) fn ggx_normal(n: Vec3A, alpha: f32, u: (f32, f32)) -> Vec3A {
    let tan2 = alpha * alpha * u.0 / (1.0 - u.0);
    let cos = 1.0 / (1.0 + tan2).sqrt();
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let (sp, cp) = (TAU * u.1).sin_cos();
    let (t, b) = orthonormal_basis(n.into());
    (Vec3A::from(t) * (sin * cp) + Vec3A::from(b) * (sin * sp) + n * cos).normalize()
}

/// A microfacet normal about unit `n` drawn from those that unit `wo` (above the surface)
/// sees, with density G₁(wo)·max(0, wo·m)·D(m) / (wo·n), by sample `u`: the hemisphere of
/// the stretched configuration, projected onto the disc that `wo` sees (Heitz 2018).
#[inline]
pub(super) fn ggx_visible_normal(n: Vec3A, alpha: f32, wo: Vec3A, u: (f32, f32)) -> Vec3A {
    let (t, b) = orthonormal_basis(n.into());
    let (t, b) = (Vec3A::from(t), Vec3A::from(b));
    // wo in the frame, stretched to the unit-roughness configuration.
    let v = Vec3A::new(alpha * wo.dot(t), alpha * wo.dot(b), wo.dot(n)).normalize();
    let across = v.x * v.x + v.y * v.y;
    let t1 = if across > 0.0 {
        Vec3A::new(-v.y, v.x, 0.0) / across.sqrt()
    } else {
        Vec3A::X
    };
    let t2 = v.cross(t1);
    // A point of the unit disc, squeezed onto the part of it the tilted hemisphere covers.
    let r = u.0.sqrt();
    let (sp, cp) = (TAU * u.1).sin_cos();
    let p1 = r * cp;
    let s = 0.5 * (1.0 + v.z);
    let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * (r * sp);
    let h = t1 * p1 + t2 * p2 + v * (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt();
    // Back to the surface's roughness, and into world space.
    let m = Vec3A::new(alpha * h.x, alpha * h.y, h.z.max(0.0)).normalize();
    t * m.x + b * m.y + n * m.z
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The normals drawn over the whole distribution follow its CDF:
    /// P(tan²θ ≤ x) = x / (α² + x).
    #[test]
    fn ggx_normals_follow_their_distribution() {
        let n = Vec3A::new(0.0, 0.6, 0.8);
        let alpha = 0.3f32;
        let mut below = 0;
        let count = 4096;
        for i in 0..count {
            let u = (
                (i as f32 + 0.5) / count as f32,
                ((i * 37) % count) as f32 / count as f32,
            );
            let m = ggx_normal(n, alpha, u);
            assert!((m.length() - 1.0).abs() < 1e-5 && m.dot(n) > 0.0);
            let cos = m.dot(n);
            let tan2 = (1.0 - cos * cos) / (cos * cos);
            below += (tan2 <= alpha * alpha) as u32;
        }
        // At x = α² the CDF is 1/2.
        let share = below as f32 / count as f32;
        assert!((share - 0.5).abs() < 0.01, "{share}");
        assert!((ggx_normal(n, 0.0, (0.7, 0.2)) - n).length() < 1e-6);
    }

    /// D integrates to 1 over projected solid angle, and the visible normals' density
    /// G₁·(wo·m)·D/(wo·n) to 1 over the sphere: a midpoint rule in (cos θ, φ) for both.
    #[test]
    fn densities_integrate_to_one() {
        let alpha = 0.4f32;
        let wo = Vec3A::new(0.8, 0.1, 0.3).normalize();
        let (mut d_total, mut visible_total) = (0.0f64, 0.0f64);
        let k = 1024;
        for a in 0..k {
            let cos = (a as f32 + 0.5) / k as f32;
            let sin = (1.0 - cos * cos).sqrt();
            for b in 0..k {
                let (s, c) = (TAU * (b as f32 + 0.5) / k as f32).sin_cos();
                let m = Vec3A::new(sin * c, sin * s, cos);
                let cell = (1.0 / k as f64) * (TAU as f64 / k as f64);
                let d = ggx_d(cos, alpha);
                d_total += (d * cos) as f64 * cell;
                let seen = wo.dot(m).max(0.0);
                visible_total += (ggx_g1(wo.z, alpha) * seen * d / wo.z) as f64 * cell;
            }
        }
        assert!((d_total - 1.0).abs() < 1e-3, "{d_total}");
        assert!((visible_total - 1.0).abs() < 1e-2, "{visible_total}");
    }

    /// The visible normals' distribution: the share drawn within a cone about the normal
    /// matches the integral of their density over that cone, for a steep and a grazing
    /// direction; and every normal drawn faces `wo`.
    #[test]
    fn visible_normals_follow_their_density() {
        let alpha = 0.5f32;
        for wo in [
            Vec3A::new(0.2, 0.0, 0.98).normalize(),
            Vec3A::new(0.95, 0.2, 0.1).normalize(),
        ] {
            let cone = 0.9f32;
            let count = 512;
            let mut within = 0u32;
            for i in 0..count {
                for j in 0..count {
                    let u = (
                        (i as f32 + 0.5) / count as f32,
                        (j as f32 + 0.5) / count as f32,
                    );
                    let m = ggx_visible_normal(Vec3A::Z, alpha, wo, u);
                    assert!((m.length() - 1.0).abs() < 1e-4);
                    assert!(m.dot(wo) >= -1e-4, "{m} does not face {wo}");
                    within += (m.z >= cone) as u32;
                }
            }
            let drawn = within as f64 / (count * count) as f64;
            let k = 1024;
            let mut expected = 0.0f64;
            for a in 0..k {
                let cos = cone + (1.0 - cone) * (a as f32 + 0.5) / k as f32;
                let sin = (1.0 - cos * cos).sqrt();
                for b in 0..k {
                    let (s, c) = (TAU * (b as f32 + 0.5) / k as f32).sin_cos();
                    let m = Vec3A::new(sin * c, sin * s, cos);
                    let density =
                        ggx_g1(wo.z, alpha) * wo.dot(m).max(0.0) * ggx_d(cos, alpha) / wo.z;
                    expected +=
                        density as f64 * ((1.0 - cone) as f64 / k as f64) * (TAU as f64 / k as f64);
                }
            }
            assert!(
                (drawn - expected).abs() < 3e-3,
                "{drawn} against {expected} for {wo}"
            );
        }
    }
}
