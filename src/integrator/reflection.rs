//! Mirror reflection: one ray in the mirror direction, or for a rough (glossy) material,
//! one ray per subsample about a microfacet normal drawn from the GGX distribution.

use super::microfacet::ggx_normal;
use super::path::Path;
use super::{Integrator, Shading};
use crate::appearance::reflect;
use crate::geometry::{Ray, RayQuery};
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
