//! The panel's camera controls: position, yaw, pitch, field of view, the lens, the step a
//! key moves, and Copy camera.

use super::{Changes, PanelState, SLIDERS};
use egui::{DragValue, RichText, Slider, SliderClamping};
use prism::scene::check_camera;

impl PanelState {
    pub(super) fn camera_controls(&mut self, ui: &mut egui::Ui, changes: &mut Changes) {
        ui.label(RichText::new("Camera").strong());
        let before = self.camera;
        let mut c = self.camera;
        // Shown in world coordinates; the scene stores them relative to its f64 origin.
        let origin = self.scene.origin;
        let mut world = origin + c.eye.as_dvec3();
        let eye_changed = ui
            .horizontal(|ui| {
                ui.label("eye");
                let x = ui.add(DragValue::new(&mut world.x).speed(0.1).prefix("x "));
                let y = ui.add(DragValue::new(&mut world.y).speed(0.1).prefix("y "));
                let z = ui.add(DragValue::new(&mut world.z).speed(0.1).prefix("z "));
                x.changed() || y.changed() || z.changed()
            })
            .inner;
        if eye_changed {
            c.eye = (world - origin).as_vec3();
        }
        ui.add(Slider::new(&mut c.yaw, -180.0..=180.0).text("yaw °"));
        ui.add(
            Slider::new(&mut c.pitch, SLIDERS.pitch)
                .clamping(SliderClamping::Always)
                .text("pitch °"),
        );
        ui.add(
            Slider::new(&mut c.vfov, SLIDERS.vfov)
                .logarithmic(true)
                .clamping(SliderClamping::Always)
                .text("field of view °"),
        );
        let extent = self
            .scene
            .bounds()
            .map_or(1.0, |b| (b.max - b.min).length().max(1e-6));
        ui.horizontal(|ui| {
            ui.add(
                DragValue::new(&mut c.aperture)
                    .speed(extent * 1e-3)
                    .range(0.0..=prism::limits::MAX_COORDINATE as f32)
                    .prefix("aperture "),
            );
            let step = c.focus_distance * 0.01;
            ui.add(
                DragValue::new(&mut c.focus_distance)
                    .speed(step)
                    .range(prism::limits::MIN_LENGTH as f32..=prism::limits::MAX_COORDINATE as f32)
                    .prefix("focus "),
            );
        });
        if c.aperture > 0.0 {
            ui.small("Click the image to focus on what is there.");
        }
        ui.add_enabled(
            self.selected.is_some(),
            egui::Checkbox::new(&mut self.orbit, "drag orbits the selection"),
        );
        let step_speed = self.step * 0.01;
        ui.add(
            DragValue::new(&mut self.step)
                .speed(step_speed)
                .range(prism::limits::MIN_LENGTH as f32..=prism::limits::MAX_COORDINATE as f32)
                .prefix("step (a tap of WASD/QE) "),
        );
        ui.horizontal(|ui| {
            if ui.button("Reset camera").clicked() {
                c = self.initial_camera;
            }
            // The view as the scene file's [camera] table, to paste into a file.
            if ui.button("Copy camera").clicked() {
                let table = prism::scene_file::camera_table(&self.camera, self.scene.origin);
                ui.ctx().copy_text(table.clone());
                eprintln!("prism: copied the camera:\n{table}");
                self.message = Some(("copied the [camera] table".into(), false));
            }
        });
        if c != before {
            match check_camera(&c) {
                Ok(()) => {
                    self.camera = c;
                    changes.camera = true;
                }
                Err(e) => self.message = Some((e.to_string(), true)),
            }
        }
    }
}
