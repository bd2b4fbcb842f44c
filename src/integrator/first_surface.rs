//! The first surface a primary ray meets, its colour and which way it faces: what a
//! denoiser is guided by (render/guides.rs gathers them over a frame's subsamples).

use super::Integrator;
use super::guide::Guide;
use crate::accel::Reach;
use crate::geometry::RayQuery;
use glam::{Vec3, Vec3A};

impl Integrator<'_> {
    /// The guide along `q` (a primary ray).
    pub fn first_surface(&mut self, q: &RayQuery) -> Guide {
        let unit = |c: Vec3A| Vec3::from(c).clamp(Vec3::ZERO, Vec3::ONE);
        let Some(hit) = self.accel().nearest_hit(q, Reach::After(0.0)) else {
            return Guide {
                albedo: unit(self.appearance.background().along(q.ray.dir)),
                normal: Vec3::ZERO,
            };
        };
        let (object, slot) = self.accel().object_and_material(&hit);
        let material = self.appearance.material(slot);
        let mut surface = self.accel().surface(q, &hit);
        if let Some(relief) = &material.relief {
            surface.shading = self.relief_normal(relief, q, &hit, object, &surface);
        }
        let facing = if q.ray.dir.dot(surface.normal) < 0.0 {
            surface.shading
        } else {
            -surface.shading
        };
        let color = self.texture_color(q, &hit, object, material, &surface);
        Guide {
            albedo: unit(color + Vec3A::from(material.emission)),
            normal: Vec3::from(facing.normalize_or_zero()),
        }
    }
}
