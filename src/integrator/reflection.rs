//! Mirror reflection: one ray in the mirror direction.

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
        let dir = self.turned(at, |n| (reflect(at.q.ray.dir, n), true));
        let origin = self.leave(&at.surface, at.n, dir);
        self.counts.secondary += 1;
        let reflected = RayQuery::new(Ray::new(origin, dir));
        let inside = self.inside(at, dir);
        self.trace(&reflected, 0.0, inside, path)
    }
}
