//! Denoising with Intel Open Image Denoise 2 (the `denoise` feature): the film's mean
//! colours filtered by OIDN's ray-tracing filter, guided by the first surfaces' colour and
//! normal (guides.rs), which keep edges and textures that the noise would otherwise smear.

use super::accumulator::Accumulator;
use super::guides::GuideImages;
use thiserror::Error;

/// Why a film could not be denoised.
#[derive(Debug, Error)]
pub enum DenoiseError {
    /// The film and the guide images are not of one size.
    #[error("the guide images are {guides:?}, the film {film:?}")]
    Size {
        /// The guide images' width and height.
        guides: (u32, u32),
        /// The film's.
        film: (u32, u32),
    },
    /// Open Image Denoise refused (no device it can run on, or too little memory).
    #[error("Open Image Denoise: {0}")]
    Oidn(String),
}

/// `film` with each pixel's mean replaced by OIDN's estimate (its count kept, so it
/// encodes as the film does), guided by `guides`. `hdr` says the colours may pass 1.
pub fn denoise(
    film: &Accumulator,
    guides: &GuideImages,
    hdr: bool,
) -> Result<Accumulator, DenoiseError> {
    let (width, height) = (film.width, film.height);
    if (guides.width, guides.height) != (width, height) {
        return Err(DenoiseError::Size {
            guides: (guides.width, guides.height),
            film: (width, height),
        });
    }
    let flat = |v: &mut dyn Iterator<Item = glam::Vec3>| -> Vec<f32> {
        v.flat_map(|c| c.to_array()).collect()
    };
    let color = flat(&mut film.pixels.iter().map(|p| p.mean()));
    let albedo = flat(&mut guides.albedo.iter().copied());
    let normal = flat(&mut guides.normal.iter().copied());
    let fail = |e: oidn::Error| DenoiseError::Oidn(e.to_string());
    let device = oidn::Device::new().map_err(fail)?;
    let mut filter = oidn::RayTracing::try_new(&device).map_err(fail)?;
    filter
        .srgb(false)
        .hdr(hdr)
        .image_dimensions(width as usize, height as usize)
        .albedo_normal(&albedo, &normal);
    let mut output = vec![0.0f32; color.len()];
    filter.filter(&color, &mut output).map_err(fail)?;
    device.get_error().map_err(fail)?;
    let mut denoised = film.clone();
    for (p, c) in denoised.pixels.iter_mut().zip(output.chunks_exact(3)) {
        let mean = glam::Vec3::from_slice(c).max(glam::Vec3::ZERO);
        // Clamped as the passes clamp each subsample, unless the film is HDR.
        let mean = if hdr { mean } else { mean.min(glam::Vec3::ONE) };
        p.color = mean * p.count.max(1) as f32;
        p.count = p.count.max(1);
    }
    Ok(denoised)
}
