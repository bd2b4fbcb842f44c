//! The scene as the tracer runs it: its geometry (shared, rebuilt only when shapes change)
//! and its appearance (tables that edits change in place).

use super::description::Scene;
use super::geometry::Geometry;
use crate::accel::AccelOptions;
use crate::appearance::Appearance;
use std::sync::Arc;

/// A scene ready to trace.
#[derive(Clone, Debug)]
pub struct PreparedScene {
    /// Shapes and the acceleration layer; shared between copies that differ only in
    /// appearance.
    pub geometry: Arc<Geometry>,
    /// Materials, lights, ambient light and background.
    pub appearance: Appearance,
}

impl PreparedScene {
    /// How far along the view axis the nearest surface seen through image point (x, y)
    /// lies (what a click to focus focuses on); None where the ray meets nothing.
    pub fn depth_at(&self, rays: &crate::camera::CameraRays, x: f32, y: f32) -> Option<f32> {
        let q = crate::geometry::RayQuery::new(rays.ray(x, y));
        let hit = self
            .geometry
            .accel()
            .nearest_hit(&q, crate::accel::Reach::After(0.0))?;
        let depth = hit.shape.t * q.ray.dir.dot(rays.forward().into());
        (depth.is_finite() && depth > 0.0).then_some(depth)
    }

    /// Prepares `scene` with every shortcut on.
    pub fn new(scene: &Scene) -> Self {
        Self::with_options(scene, AccelOptions::ALL)
    }

    /// Prepares `scene` with the shortcuts `options` names.
    pub fn with_options(scene: &Scene, options: AccelOptions) -> Self {
        Self {
            geometry: Arc::new(Geometry::new(scene, options)),
            appearance: Appearance::new(
                scene.objects.iter().map(|o| o.material.clone()).collect(),
                scene.objects.iter().map(|o| o.casts_shadow).collect(),
                scene.lights.clone(),
                scene.ambient,
                scene.background.clone(),
                scene.render.max_depth,
            )
            .with_fog(scene.fog),
        }
    }
}
