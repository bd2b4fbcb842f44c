//! The viewer's denoised image (a build with the `denoise` feature): the film filtered by
//! Open Image Denoise after each pass that doubles its samples and after the last, shown in
//! place of the raw image while the passes go on (render/denoise.rs).

use prism::render::{Accumulator, ProgressiveRender};

/// What the image shows when denoising is on, and why it could not be.
#[derive(Default)]
pub struct Denoised {
    /// Whether the image is shown denoised.
    pub on: bool,
    /// The guide images, and the subsamples they average.
    #[cfg(feature = "denoise")]
    guides: Option<(u32, prism::render::GuideImages)>,
    /// The last film denoised, and the passes it held.
    film: Option<(u32, Accumulator)>,
    /// Why the last try failed.
    pub error: Option<String>,
}

impl Denoised {
    /// Forgets the images of the render before a restart.
    pub fn restart(&mut self) {
        #[cfg(feature = "denoise")]
        {
            self.guides = None;
        }
        self.film = None;
    }

    /// The film to show for `job` when denoising is on: filtered anew when its pass count
    /// is a power of two or it has converged, else the last one filtered (None: show the
    /// raw film).
    pub fn film(&mut self, job: &ProgressiveRender) -> Option<&Accumulator> {
        if !self.on || job.passes_done() == 0 {
            return None;
        }
        let passes = job.passes_done();
        let due = passes.is_power_of_two() || job.is_converged();
        if due && self.film.as_ref().is_none_or(|(n, _)| *n != passes) {
            match self.filter(job) {
                Ok(film) => {
                    self.film = Some((passes, film));
                    self.error = None;
                }
                Err(e) => self.error = Some(e),
            }
        }
        self.film.as_ref().map(|(_, film)| film)
    }

    #[cfg(feature = "denoise")]
    fn filter(&mut self, job: &ProgressiveRender) -> Result<Accumulator, String> {
        use prism::render::{MAX_GUIDE_SUBSAMPLES, denoise, guide_images};
        let settings = job.settings();
        let n = job.passes_done().min(MAX_GUIDE_SUBSAMPLES);
        if self.guides.as_ref().is_none_or(|(m, _)| *m != n) {
            let guides = guide_images(job.scene(), *job.camera(), settings, n);
            self.guides = Some((n, guides));
        }
        let (_, guides) = self.guides.as_ref().expect("made above");
        denoise(job.accumulator(), guides, settings.high_dynamic_range).map_err(|e| e.to_string())
    }

    #[cfg(not(feature = "denoise"))]
    fn filter(&mut self, _: &ProgressiveRender) -> Result<Accumulator, String> {
        Err(prism::render::DENOISE_NOT_BUILT.into())
    }
}
