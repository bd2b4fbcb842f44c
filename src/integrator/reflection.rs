//! Mirror reflection: one ray in the mirror direction, or for a rough (glossy) material,
//! one ray per subsample about a microfacet normal drawn from the GGX distribution.

use super::path::Path;
use super::{Integrator, Shading};
use crate::appearance::reflect;
use crate::geometry::{Ray, RayQuery};
use crate::numerics::orthonormal_basis;
use glam::Vec3A;

impl Integrator<'_> {
    /// Whether a hit that reflects `reflectivity` of the light along `path` spawns a
    /// reflected ray: it reflects, a bounce is left, and the ray would weigh enough to
    /// matter.
    #[inline]
    pub(super) fn reflects(&self, reflectivity: f32, path: Path, bounces_left: bool) -> bool {
        bounces_left && reflectivity > 0.0 && path.weight * reflectivity >= self.min_weight
    }

    /// The light the mirror ray from `at` brings back (before the reflectivity scales it).
    #[inline]
    pub(super) fn reflection(&mut self, at: &Shading, path: Path) -> Vec3A {
        let d = at.q.ray.dir;
        let roughness = at.material.roughness;
        let dir = if roughness > 0.0 {
            let m = ggx_normal(at.ns, roughness * roughness, self.stream.next_2d());
            let glossy = reflect(d, m);
            // A direction the microfacet sends below the surface is replaced by the mirror's.
            if glossy.dot(at.n) > 0.0 {
                glossy
            } else {
                self.turned(at, |n| (reflect(d, n), true))
            }
        } else {
            self.turned(at, |n| (reflect(d, n), true))
        };
        let origin = self.leave(&at.surface, at.n, dir);
        self.counts.secondary += 1;
        let reflected = RayQuery::new(Ray::new(origin, dir));
        let inside = self.inside(at, dir);
        self.trace(&reflected, 0.0, inside, path)
    }
}

/// A microfacet normal about unit `n` drawn from the GGX (Trowbridge–Reitz) distribution of
/// width `alpha` by sample `u` (Walter et al. 2007): tan²θ = α²·u₁/(1 − u₁), φ = 2π·u₂.
#[inline]
fn ggx_normal(n: Vec3A, alpha: f32, u: (f32, f32)) -> Vec3A {
    let tan2 = alpha * alpha * u.0 / (1.0 - u.0);
    let cos = 1.0 / (1.0 + tan2).sqrt();
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let (sp, cp) = (std::f32::consts::TAU * u.1).sin_cos();
    let (t, b) = orthonormal_basis(n.into());
    (Vec3A::from(t) * (sin * cp) + Vec3A::from(b) * (sin * sp) + n * cos).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The GGX normals' cosines follow the distribution's CDF: P(tan²θ ≤ x) = x / (α² + x).
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
}
