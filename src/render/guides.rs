//! A denoiser's guide images: each pixel's first surface, its colour and which way it
//! faces (integrator/guides.rs), averaged over the subsamples its colour was, so that
//! their edges are smoothed as the colour's are.

use super::settings::RenderSettings;
use crate::camera::Camera;
use crate::geometry::RayQuery;
use crate::integrator::{Guide, Integrator};
use crate::sampler::{SampleStream, Sampler};
use crate::scene::PreparedScene;
use glam::Vec3;
use rayon::prelude::*;

/// The most subsamples a guide averages: past this its edges no longer change to see.
pub const MAX_GUIDE_SUBSAMPLES: u32 = 16;

/// The guide images of a whole frame, row by row from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct GuideImages {
    /// Pixels across.
    pub width: u32,
    /// Pixels down.
    pub height: u32,
    /// Each pixel's mean first-surface colour, in [0, 1].
    pub albedo: Vec<Vec3>,
    /// Each pixel's mean shading normal (not of unit length where the surfaces disagree).
    pub normal: Vec<Vec3>,
}

/// The guide images of `scene` seen from `camera` at `settings`' size, over the first
/// `subsamples` subsamples (at most `MAX_GUIDE_SUBSAMPLES`), placed as the passes place
/// them. Call it inside `thread_pool(..).install`.
pub fn guide_images(
    scene: &PreparedScene,
    camera: Camera,
    settings: &RenderSettings,
    subsamples: u32,
) -> GuideImages {
    let (width, height) = (settings.width, settings.height);
    let n = subsamples.clamp(1, MAX_GUIDE_SUBSAMPLES);
    let sampler = Sampler::new(settings.aa, settings.layout);
    let rays = camera.rays(width, height);
    let rows: Vec<Vec<Guide>> = (0..height)
        .into_par_iter()
        .map(|y| {
            let mut integrator = Integrator::new(scene, settings.min_weight);
            let mut sums = vec![Guide::default(); width as usize];
            for k in 0..n {
                let subsamples = sampler.row(y, k);
                for (x, sum) in (0..width).zip(&mut sums) {
                    let (dx, dy) = subsamples.offset(x);
                    let (px, py) = (x as f32 + dx, y as f32 + dy);
                    let ray = if rays.has_lens() {
                        let u = SampleStream::new(x, y, k).next_2d();
                        rays.ray_through_lens(px, py, u)
                    } else {
                        rays.ray(px, py)
                    };
                    let guide = integrator.first_surface(&RayQuery::new(ray));
                    sum.albedo += guide.albedo;
                    sum.normal += guide.normal;
                }
            }
            for sum in &mut sums {
                sum.albedo /= n as f32;
                sum.normal /= n as f32;
            }
            sums
        })
        .collect();
    let guides = rows.into_iter().flatten();
    let (albedo, normal) = guides.map(|g| (g.albedo, g.normal)).unzip();
    GuideImages {
        width,
        height,
        albedo,
        normal,
    }
}
