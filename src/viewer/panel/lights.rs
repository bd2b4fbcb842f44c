//! The panel's Lights section: each light's colour, place, intensity, size and cone.

use super::widgets::{color_row, position_row};
use super::{Changes, PanelState};
use egui::{DragValue, Slider, SliderClamping};
use prism::appearance::{Falloff, LightKind};
use prism::limits::{MAX_RADIANCE, MIN_LENGTH};

impl PanelState {
    /// Each light's colour, place, intensity, size or cone.
    pub(super) fn lights(&mut self, ui: &mut egui::Ui, changes: &mut Changes) {
        let origin = self.scene.origin;
        for i in 0..self.scene.lights.len() {
            let light = self.scene.lights[i];
            let kind = match light.kind {
                LightKind::Point { .. } => "point",
                LightKind::Spot { .. } => "spot",
                LightKind::Directional { .. } => "directional",
                LightKind::Area { .. } => "area",
            };
            // A light in a group is where its group puts it: move the group.
            let group = self.scene.groups.iter().find(|g| g.lights.contains(&i));
            let free = group.is_none();
            match group {
                Some(g) => ui.label(format!("light {i} ({kind}) in group {}", g.name)),
                None => ui.label(format!("light {i} ({kind})")),
            };
            let mut color = light.color;
            let mut center = light.center().map(|c| origin + c.as_dvec3());
            let mut changed = color_row(ui, "colour", &mut color, 0.0..=MAX_RADIANCE, false);
            if let Some(world) = &mut center {
                let moved = ui
                    .add_enabled_ui(free, |ui| position_row(ui, "at", world))
                    .inner;
                changed |= moved;
            }
            if changed {
                let center = center.map(|w| (w - origin).as_vec3());
                self.edit(changes, format!("light {i} place"), |s| {
                    s.set_light_at(i, color, center)
                });
            }
            if let Some(Falloff::InverseSquare { intensity }) =
                self.scene.lights[i].clone().falloff_mut().copied()
            {
                let mut v = intensity;
                let r = ui.add(
                    DragValue::new(&mut v)
                        .speed(intensity.max(1e-3) * 0.01)
                        .range(0.0..=prism::limits::MAX_LIGHT_INTENSITY)
                        .prefix("intensity "),
                );
                if r.changed() {
                    self.edit(changes, format!("light {i} intensity"), |s| {
                        s.set_light_intensity(i, v)
                    });
                }
            }
            match self.scene.lights[i].kind {
                LightKind::Area { shape, .. } => {
                    let mut size = shape.size();
                    let speed = size * 0.01;
                    let r = ui.add_enabled(
                        free,
                        DragValue::new(&mut size)
                            .speed(speed)
                            .range(MIN_LENGTH as f32..=f32::MAX)
                            .prefix("size "),
                    );
                    if r.changed() {
                        self.edit(changes, format!("light {i} size"), |s| {
                            s.set_light_size(i, size)
                        });
                    }
                }
                LightKind::Spot { cone, radius, .. } => {
                    let (mut angle, mut softness) = (cone.angle, cone.softness);
                    let a = ui.add(
                        Slider::new(&mut angle, prism::limits::SPOT_ANGLE)
                            .logarithmic(true)
                            .clamping(SliderClamping::Always)
                            .text("angle °"),
                    );
                    let b = ui.add(
                        Slider::new(&mut softness, 0.0..=1.0)
                            .clamping(SliderClamping::Always)
                            .text("softness"),
                    );
                    if a.changed() || b.changed() {
                        self.edit(changes, format!("light {i} cone"), |s| {
                            s.set_spot(i, angle, softness)
                        });
                    }
                    // 0: a point and hard shadows; above: a disc and soft ones.
                    let mut r = radius;
                    let d = ui.add_enabled(
                        free,
                        DragValue::new(&mut r)
                            .speed((radius * 0.01).max(1e-3))
                            .range(0.0..=prism::limits::MAX_COORDINATE as f32)
                            .prefix("disc radius "),
                    );
                    if d.changed() {
                        self.edit(changes, format!("light {i} disc radius"), |s| {
                            s.set_spot_radius(i, r)
                        });
                    }
                }
                LightKind::Point { .. } | LightKind::Directional { .. } => {}
            }
        }
    }
}
