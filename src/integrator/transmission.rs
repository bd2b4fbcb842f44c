//! Transmission: light through a transparent surface, bent by Snell's law when the
//! material has an index of refraction other than 1 (about a GGX microfacet normal drawn
//! per subsample when it is rough), else going on along the same ray.

use super::microfacet::ggx_normal;
use super::path::{MAX_STRAIGHT_CROSSINGS, Path};
use super::{Integrator, Shading};
use crate::appearance::{Material, reflect, refract};
use crate::geometry::{Ray, RayQuery};
use glam::Vec3A;

impl Integrator<'_> {
    /// Whether a hit on `material` that transmits `transparency` of the light along `path`
    /// spawns a transmitted ray: it is transparent, the ray would weigh enough to matter,
    /// and a bent ray has a bounce left (a straight one, a crossing left).
    #[inline]
    pub(super) fn transmits(
        &self,
        material: &Material,
        transparency: f32,
        path: Path,
        bounces_left: bool,
    ) -> bool {
        transparency > 0.0
            && path.weight * transparency >= self.min_weight
            && if material.bends() {
                bounces_left
            } else {
                path.straight < MAX_STRAIGHT_CROSSINGS
            }
    }

    /// The light the transmitted ray from `at` brings back (before `transparency`, the
    /// share transmitted, scales it); its subtree may spend `budget` rays.
    #[inline]
    pub(super) fn transmission(
        &mut self,
        at: &Shading,
        transparency: f32,
        path: Path,
        budget: u32,
    ) -> Vec3A {
        self.counts.secondary += 1;
        let material = at.material;
        let ray = at.q.ray;
        // Through the surface the ray enters the object's medium, or leaves it, for its
        // subtree; the media are put back after.
        // A touching medium the ray left at this point is left behind too.
        let around = self.media;
        let here = at.leaves.map_or(around, |touching| around.left(touching));
        let beyond = if at.entering {
            here.entered(at.object)
        } else {
            here.left(at.object)
        };
        let color = if material.bends() {
            let ratio = self.eta_ratio(at);
            // Past the critical angle the transmitted light is reflected inside; either
            // way the ray must go where the true surface says.
            let bend = |n: Vec3A| match refract(ray.dir, n, ratio) {
                Some(dir) => (dir, false),
                None => (reflect(ray.dir, n), true),
            };
            let roughness = material.roughness;
            // A rough surface bends each subsample's ray about a microfacet normal, unless
            // that would send it out on the wrong side.
            let rough = (roughness > 0.0).then(|| {
                let m = ggx_normal(at.ns, roughness * roughness, self.stream.next_2d());
                bend(m)
            });
            let dir = match rough {
                Some((dir, outward)) if (dir.dot(at.n) > 0.0) == outward => dir,
                _ => self.turned(at, bend),
            };
            let origin = self.leave(&at.surface, at.n, dir);
            let q = RayQuery::new(Ray::new(origin, dir));
            let inside = self.inside(at, dir);
            // Reflected inside (past the critical angle), the ray stays where it was.
            if dir.dot(at.n) < 0.0 {
                self.media = beyond;
            }
            self.trace(&q, 0.0, inside, path.bounce(transparency, budget))
        } else {
            // Unbent light goes on along the very same ray, past this hit: exact, so an
            // eta-1 clear object leaves the image untouched.
            let inside = self.inside(at, ray.dir);
            let path = path.straight_on(transparency, budget);
            self.media = beyond;
            self.trace(at.q, at.hit.shape.t, inside, path)
        };
        self.media = around;
        color
    }
}
