//! What a denoiser is guided by at one subsample: the first surface a primary ray meets
//! (first_surface.rs finds it; render/guides.rs gathers a frame's).

use glam::Vec3;

/// The first surface along a ray, as a denoiser's guide images hold it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Guide {
    /// The surface's own colour (its texture there, or a glowing light's), each channel in
    /// [0, 1]; the background's where the ray meets nothing.
    pub albedo: Vec3,
    /// The shading normal, turned to face the ray; zero where the ray meets nothing.
    pub normal: Vec3,
}
