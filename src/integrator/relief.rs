//! Where a material has relief, the shading normal it gives at a hit.

use super::Integrator;
use crate::accel::Hit;
use crate::appearance::Relief;
use crate::geometry::{RayQuery, SurfacePoint};
use glam::Vec3A;

impl Integrator<'_> {
    /// The shading normal of `surface` (the point of `hit` along `q`, on `object`) tilted
    /// by `relief`, on the side the surface's normal faces. (Out of line: most materials
    /// have none, and the shading path stays lean.)
    #[inline(never)]
    pub(super) fn relief_normal(
        &self,
        relief: &Relief,
        q: &RayQuery,
        hit: &Hit,
        object: u32,
        surface: &SurfacePoint,
    ) -> Vec3A {
        let geometry = self.geometry.object(object);
        let p = surface.point;
        relief.shading_normal(
            surface.shading,
            |pattern| {
                let local = pattern.brightness_gradient(geometry.texture_point(p));
                geometry.texture_gradient_to_scene(local)
            },
            || match geometry.planar_uv {
                Some(planar) => planar.uv_frame(surface.point),
                None => self.accel().uv_frame(q, surface, hit),
            },
        )
    }
}
