//! The panel's Convergence section: the live plot of the error, and the switch between the
//! image and the heat maps with their legend.

use super::super::render_thread::Status;
use super::{Changes, PanelState};
use prism::render::{Legend, View};

impl PanelState {
    /// The view switch, the heat map's legend, and the plot of the error estimate.
    pub(super) fn convergence(
        &mut self,
        ui: &mut egui::Ui,
        status: &Status,
        changes: &mut Changes,
    ) {
        ui.horizontal(|ui| {
            for (view, name) in [
                (View::Image, "image"),
                (View::Samples, "samples"),
                (View::Error, "error"),
            ] {
                if ui.radio_value(&mut self.view, view, name).changed() {
                    changes.view = Some(view);
                }
            }
            let toggle = egui::Checkbox::new(&mut self.denoise, "denoised");
            let toggled = ui
                .add_enabled(cfg!(feature = "denoise"), toggle)
                .on_hover_text(
                    "Show the image filtered by Intel Open Image Denoise, guided by the first \
                     surfaces' colours and normals: again after each pass that doubles the \
                     samples, and at the end",
                )
                .on_disabled_hover_text(prism::render::DENOISE_NOT_BUILT)
                .changed();
            if toggled {
                changes.denoise = Some(self.denoise);
            }
        });
        if let Some(e) = &status.denoise_error {
            ui.small(format!("not denoised: {e}"));
        } else if status.denoised {
            ui.small("denoised (Intel Open Image Denoise)");
        }
        if let Some(legend) = status.legend {
            legend_bar(ui, &legend, self.view);
        }
        ui.horizontal(|ui| {
            ui.label("error against");
            ui.radio_value(&mut self.plot_by_samples, false, "time");
            ui.radio_value(&mut self.plot_by_samples, true, "samples");
        });
        let x = if self.plot_by_samples { 1 } else { 0 };
        let points: Vec<[f64; 2]> = self
            .convergence
            .iter()
            .filter(|p| p[2] > 0.0)
            .map(|p| [p[x], p[2].log10()])
            .collect();
        egui_plot::Plot::new("convergence")
            .height(110.0)
            .allow_zoom(false)
            .allow_drag(false)
            .allow_scroll(false)
            .x_axis_label(if self.plot_by_samples {
                "samples per pixel"
            } else {
                "seconds"
            })
            .y_axis_formatter(|mark, _| format!("1e{:.0}", mark.value))
            .show(ui, |plot| {
                plot.line(egui_plot::Line::new("mean error estimate", points));
            });
        if let Some(e) = status.mean_error {
            ui.small(format!("mean error estimate {e:.2e} (luminance)"));
        }
    }
}

/// The heat map's colour scale with the values at its ends.
pub(super) fn legend_bar(ui: &mut egui::Ui, legend: &Legend, view: View) {
    let (rect, _) = ui.allocate_exact_size(egui::vec2(200.0, 12.0), egui::Sense::hover());
    let steps = 50;
    for i in 0..steps {
        let t = i as f32 / (steps - 1) as f32;
        let [r, g, b] = prism::render::scale_color(t);
        let x0 = rect.left() + rect.width() * i as f32 / steps as f32;
        let x1 = rect.left() + rect.width() * (i + 1) as f32 / steps as f32;
        let cell =
            egui::Rect::from_min_max(egui::pos2(x0, rect.top()), egui::pos2(x1, rect.bottom()));
        ui.painter()
            .rect_filled(cell, 0.0, egui::Color32::from_rgb(r, g, b));
    }
    let text = match view {
        View::Samples => format!("{} to {} subsamples per pixel", legend.low, legend.high),
        View::Error | View::Image => format!(
            "error {:.0e} to {:.0e}{} (grey: not known yet)",
            legend.low,
            legend.high,
            if legend.logarithmic {
                ", log scale"
            } else {
                ""
            }
        ),
    };
    ui.small(text);
}
