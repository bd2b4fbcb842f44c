//! The panel's Scene section: the background, ambient light, depth and fog.

use super::widgets::color_row;
use super::{Changes, PanelState};
use egui::DragValue;
use glam::Vec3;
use prism::appearance::Background;
use prism::limits::MAX_RADIANCE;

impl PanelState {
    /// Background, ambient light, depth and fog.
    pub(super) fn scene_settings(&mut self, ui: &mut egui::Ui, changes: &mut Changes) {
        match &self.scene.background {
            Background::Solid(c) => {
                let mut c = *c;
                if color_row(ui, "background", &mut c, 0.0..=MAX_RADIANCE, false) {
                    self.edit(changes, "background".into(), |s| s.set_background_color(c));
                }
            }
            other => {
                let kind = match other {
                    Background::Gradient { .. } => "a gradient",
                    _ => "an image",
                };
                ui.horizontal(|ui| {
                    ui.label(format!("background: {kind}"));
                    if ui.small_button("make it black").clicked() {
                        self.edit(changes, "background".into(), |s| {
                            s.set_background_color(Vec3::ZERO)
                        });
                    }
                });
            }
        }
        let mut ambient = self.scene.ambient;
        if color_row(ui, "ambient", &mut ambient, 0.0..=MAX_RADIANCE, false) {
            self.edit(changes, "ambient".into(), |s| s.set_ambient(ambient));
        }
        let mut depth = self.scene.render.max_depth;
        if ui
            .add(
                DragValue::new(&mut depth)
                    .range(prism::limits::DEPTH)
                    .prefix("maximum depth "),
            )
            .changed()
        {
            self.edit(changes, "max_depth".into(), |s| s.set_max_depth(depth));
        }
        if let Some(fog) = self.scene.fog {
            let mut density = fog.density();
            let speed = density * 0.01;
            let changed = ui
                .add(
                    DragValue::new(&mut density)
                        .speed(speed)
                        .range(f32::MIN_POSITIVE..=prism::limits::MAX_EXTINCTION)
                        .prefix("fog density "),
                )
                .changed();
            if changed {
                self.edit(changes, "fog".into(), |s| s.set_fog_density(density));
            }
        }
    }
}
