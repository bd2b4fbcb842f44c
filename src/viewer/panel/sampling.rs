//! The panel's sampling controls: the light transport, the anti-aliasing level or samples
//! per pixel, and adaptive sampling.

use super::{Changes, PanelState, SLIDERS};
use egui::{DragValue, RichText, Slider, SliderClamping};
use prism::integrator::IntegratorKind;

impl PanelState {
    pub(super) fn sampling(&mut self, ui: &mut egui::Ui, changes: &mut Changes) {
        ui.label(RichText::new("Light transport").strong());
        let transport = ui
            .horizontal(|ui| {
                IntegratorKind::ALL
                    .into_iter()
                    .map(|kind| {
                        let label = match kind {
                            IntegratorKind::Whitted => "Whitted",
                            IntegratorKind::Path => "path traced",
                        };
                        ui.radio_value(&mut self.integrator, kind, label)
                            .on_hover_text(match kind {
                                IntegratorKind::Whitted => {
                                    "direct light, an ambient term, mirrors and glass"
                                }
                                IntegratorKind::Path => {
                                    "light that bounces between surfaces (no ambient term); \
                                     noisy at first, it converges pass by pass"
                                }
                            })
                            .changed()
                    })
                    .fold(false, |a, b| a | b)
            })
            .inner;
        if transport {
            self.integrator_changed();
        }
        ui.label(RichText::new("Anti-aliasing").strong());
        let aa = ui.add(
            Slider::new(&mut self.aa, SLIDERS.aa)
                .clamping(SliderClamping::Always)
                .text("level N (N×N)"),
        );
        // Past the N×N grid for noisy effects (soft shadows, a lens, glossy lobes).
        let mut custom = self.samples.is_some();
        let mut count = self.samples.unwrap_or(self.aa * self.aa);
        let samples = ui
            .horizontal(|ui| {
                let c = ui.checkbox(&mut custom, "samples per pixel");
                let n = ui.add_enabled(
                    custom,
                    DragValue::new(&mut count).range(prism::limits::SAMPLES),
                );
                c.changed() || n.changed()
            })
            .inner;
        if samples {
            self.samples_for_path = false;
        }
        self.samples = custom.then_some(count);
        let adaptive = ui.checkbox(&mut self.adaptive, "adaptive sampling");
        let tol = ui.add_enabled(
            self.adaptive,
            Slider::new(&mut self.tolerance, SLIDERS.tolerance)
                .logarithmic(true)
                .clamping(SliderClamping::Always)
                .text("tolerance"),
        );
        if !self.tolerance.is_finite() || self.tolerance <= 0.0 {
            self.tolerance = prism::render::AdaptiveSettings::default().tolerance;
        }
        changes.settings =
            transport || aa.changed() || samples || adaptive.changed() || tol.changed();
    }
}
