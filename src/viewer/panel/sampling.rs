//! The panel's sampling controls: the anti-aliasing level or samples per pixel, and
//! adaptive sampling.

use super::{Changes, PanelState, SLIDERS};
use egui::{DragValue, RichText, Slider, SliderClamping};

impl PanelState {
    pub(super) fn sampling(&mut self, ui: &mut egui::Ui, changes: &mut Changes) {
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
        changes.settings = aa.changed() || samples || adaptive.changed() || tol.changed();
    }
}
