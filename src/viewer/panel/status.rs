//! The render's status lines at the foot of the panel: passes, samples, rays and time.

use super::super::render_thread::Status;
use egui::RichText;

pub(super) fn status_lines(ui: &mut egui::Ui, s: &Status) {
    ui.label(RichText::new("Status").strong());
    if s.preview {
        ui.label(format!("moving: coarse preview ({:.1} ms)", s.ms_per_pass));
        return;
    }
    ui.label(format!(
        "pass {} of {}{}",
        s.passes_done,
        s.total_passes,
        if s.converged { " (converged)" } else { "" }
    ));
    ui.label(format!("{:.2} samples per pixel", s.samples_per_pixel));
    ui.label(format!("{:.1} ms per pass", s.ms_per_pass));
    ui.label(format!("{:.1} M rays/s", s.rays_per_second / 1e6));
    if s.converged {
        ui.label(format!("converged in {:.2} s", s.seconds));
    } else {
        ui.label(format!("{:.2} s so far", s.seconds));
    }
    ui.label(format!(
        "active pixels: {} of {}",
        s.active_pixels, s.total_pixels
    ));
}
