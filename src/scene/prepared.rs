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

/// A scene that no render can finish in bounded time: more than
/// `limits::MAX_COINCIDENT` surfaces at one place (copies of one triangle, objects placed at
/// one spot). No hierarchy can part them, so every ray that comes near tests each.
#[derive(Debug, thiserror::Error)]
#[error(
    "{count} surfaces share one centre{}: at most {} may, as a ray near them tests every one \
     (copies of one triangle, or objects placed at one spot?)",
    object.as_ref().map_or_else(String::new, |o| format!(" (in {})", crate::messages::quoted(o))),
    crate::limits::MAX_COINCIDENT
)]
pub struct CoincidentSurfaces {
    /// How many share the centre.
    pub count: u32,
    /// The name of the object they are in (the first of them).
    pub object: Option<String>,
}

impl PreparedScene {
    /// Refuses the scene when more than `limits::MAX_COINCIDENT` of its surfaces share one
    /// centre; `scene` is the scene it was prepared from (to name the object).
    pub fn check_coincident(&self, scene: &Scene) -> Result<(), CoincidentSurfaces> {
        let (count, object) = self.geometry.accel().largest_coincident();
        if count as usize <= crate::limits::MAX_COINCIDENT {
            return Ok(());
        }
        Err(CoincidentSurfaces {
            count,
            object: scene.objects.get(object as usize).map(|o| o.name.clone()),
        })
    }

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

    /// The object seen through image point (x, y), in pixels: what a click picks; None
    /// where the ray meets nothing.
    pub fn object_at(&self, rays: &crate::camera::CameraRays, x: f32, y: f32) -> Option<usize> {
        let q = crate::geometry::RayQuery::new(rays.ray(x, y));
        let accel = self.geometry.accel();
        let hit = accel.nearest_hit(&q, crate::accel::Reach::After(0.0))?;
        Some(accel.primitive(hit.primitive).object as usize)
    }

    /// Which pixels of a `width` × `height` image show object `object` (through each
    /// pixel's centre), row by row: where the viewer outlines a selection.
    pub fn coverage(
        &self,
        rays: &crate::camera::CameraRays,
        width: u32,
        height: u32,
        object: usize,
    ) -> Vec<bool> {
        use rayon::prelude::*;
        let mut covered = vec![false; width as usize * height as usize];
        covered
            .par_chunks_mut(width.max(1) as usize)
            .enumerate()
            .for_each(|(y, row)| {
                for (x, c) in row.iter_mut().enumerate() {
                    let at = self.object_at(rays, x as f32 + 0.5, y as f32 + 0.5);
                    *c = at == Some(object);
                }
            });
        covered
    }

    /// Prepares `scene` with every shortcut on.
    pub fn new(scene: &Scene) -> Self {
        Self::with_options(scene, AccelOptions::ALL)
    }

    /// Prepares `scene` with the shortcuts `options` names.
    pub fn with_options(scene: &Scene, options: AccelOptions) -> Self {
        Self {
            geometry: Arc::new(Geometry::new(scene, options)),
            appearance: Self::appearance_of(scene),
        }
    }

    /// `edited` prepared, where `self` is `before` prepared: the geometry is shared when
    /// the edit left it unchanged (a material, a light's colour, the background), so only
    /// the appearance tables are made again; otherwise it is built again with the same
    /// shortcuts, reusing what the edit did not touch (`Geometry::rebuilt`).
    pub fn updated(&self, before: &Scene, edited: &Scene) -> Self {
        let geometry = if Geometry::same_for(before, edited) {
            self.geometry.clone()
        } else {
            Arc::new(Geometry::rebuilt(edited, &self.geometry))
        };
        Self {
            geometry,
            appearance: Self::appearance_of(edited),
        }
    }

    /// The appearance tables of `scene`: materials, shadow flags, lights, ambient light,
    /// background, depth and fog.
    fn appearance_of(scene: &Scene) -> Appearance {
        Appearance::new(
            scene.objects.iter().map(|o| o.material.clone()).collect(),
            scene.objects.iter().map(|o| o.casts_shadow).collect(),
            scene.lights.clone(),
            scene.ambient,
            scene.background.clone(),
            scene.render.max_depth,
        )
        .with_member_materials(scene.member_materials())
        .with_fog(scene.fog)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// A material or light-colour edit keeps the geometry (the same allocation); moving a
    /// light or a shape does not, since the light buffers and the BVH depend on them.
    #[test]
    fn only_edits_of_geometry_rebuild_it() {
        let scene = crate::seed::scene().unwrap();
        let prepared = PreparedScene::new(&scene);
        let mut recoloured = scene.clone();
        let mut m = recoloured.objects[0].material.clone();
        m.specular = 0.1;
        recoloured.set_material(0, m).unwrap();
        recoloured.set_light_at(0, Vec3::splat(0.3), None).unwrap();
        recoloured.set_ambient(Vec3::splat(0.3)).unwrap();
        let updated = prepared.updated(&scene, &recoloured);
        assert!(Arc::ptr_eq(&updated.geometry, &prepared.geometry));
        assert_eq!(updated.appearance.material(0).specular, 0.1);
        let mut moved = scene.clone();
        let at = moved.lights[0].center().unwrap() + Vec3::Y;
        moved.set_light_at(0, Vec3::ONE, Some(at)).unwrap();
        assert!(!Arc::ptr_eq(
            &prepared.updated(&scene, &moved).geometry,
            &prepared.geometry
        ));
    }
}
