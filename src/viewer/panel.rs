//! The egui side panel: material sliders, anti-aliasing, camera, screenshot, and status.

use super::render_thread::Status;
use egui::{DragValue, RichText, Slider, SliderClamping};
use prism::camera::Camera;
use prism::limits::{ETA, MAX_PITCH, VFOV};
use prism::scene::Scene;
use prism::scene::edit::check_camera;

/// Panel width in points.
pub const PANEL_WIDTH: f32 = 300.0;

/// What the user changed this frame.
#[derive(Default)]
pub struct Changes {
    /// Objects whose material changed.
    pub materials: Vec<usize>,
    pub camera: bool,
    pub settings: bool,
    pub screenshot: bool,
}

pub struct PanelState {
    pub scene: Scene,
    pub camera: Camera,
    pub initial_camera: Camera,
    pub aa: u32,
    pub adaptive: bool,
    pub tolerance: f32,
    /// The last screenshot or input message, and whether it is an error.
    pub message: Option<(String, bool)>,
    refractive: Vec<usize>,
    transparent: Vec<usize>,
}

impl PanelState {
    pub fn new(scene: Scene, aa: u32) -> Self {
        let refractive = (0..scene.objects.len())
            .filter(|&i| scene.objects[i].material.eta.is_some())
            .collect();
        let transparent = (0..scene.objects.len())
            .filter(|&i| scene.objects[i].material.transparency > 0.0)
            .collect();
        Self {
            camera: scene.camera,
            initial_camera: scene.camera,
            scene,
            aa,
            adaptive: false,
            tolerance: prism::render::AdaptiveSettings::default().tolerance,
            message: None,
            refractive,
            transparent,
        }
    }

    pub fn show(&mut self, ui: &mut egui::Ui, status: &Status) -> Changes {
        let mut changes = Changes::default();
        egui::ScrollArea::vertical().show(ui, |ui| {
            ui.heading("prism");
            // A failed render matters more than any control: it goes first.
            if let Some(e) = &status.error {
                let text = format!("The render failed: {e}. Change anything to try again.");
                ui.label(RichText::new(text).color(ui.visuals().error_fg_color));
                ui.separator();
            }
            self.materials(ui, &mut changes);
            ui.separator();
            ui.label(RichText::new("Anti-aliasing").strong());
            let aa = ui.add(
                Slider::new(&mut self.aa, 1..=prism::limits::MAX_AA)
                    .clamping(SliderClamping::Always)
                    .text("level N (N×N)"),
            );
            let adaptive = ui.checkbox(&mut self.adaptive, "adaptive sampling");
            let tol = ui.add_enabled(
                self.adaptive,
                Slider::new(&mut self.tolerance, 0.0005..=0.05)
                    .logarithmic(true)
                    .clamping(SliderClamping::Always)
                    .text("tolerance"),
            );
            if !self.tolerance.is_finite() || self.tolerance <= 0.0 {
                self.tolerance = prism::render::AdaptiveSettings::default().tolerance;
            }
            changes.settings = aa.changed() || adaptive.changed() || tol.changed();
            ui.separator();
            self.camera_controls(ui, &mut changes);
            ui.separator();
            if ui.button("Save screenshot (F12 or P)").clicked() {
                changes.screenshot = true;
            }
            if let Some((text, error)) = &self.message {
                let color = if *error {
                    ui.visuals().error_fg_color
                } else {
                    ui.visuals().text_color()
                };
                ui.label(RichText::new(text).color(color));
            }
            ui.separator();
            status_lines(ui, status);
            ui.separator();
            ui.small("Drag: look · WASD: move · Q/E: down/up · scroll: zoom · Ctrl+Q: quit");
        });
        changes
    }

    fn materials(&mut self, ui: &mut egui::Ui, changes: &mut Changes) {
        if !self.refractive.is_empty() {
            ui.label(RichText::new("Refraction (eta)").strong());
        }
        for &i in &self.refractive.clone() {
            let name = self.scene.objects[i].name.clone();
            let mut eta = self.scene.objects[i].material.eta.unwrap_or(1.0);
            let r = ui.add(
                // The whole range a file may give, on a log scale centred on 1.
                Slider::new(&mut eta, ETA)
                    .logarithmic(true)
                    .clamping(SliderClamping::Always)
                    .max_decimals(4)
                    .text(&name),
            );
            if r.changed() {
                match self.scene.set_eta(i, eta) {
                    Ok(()) => changes.materials.push(i),
                    Err(e) => self.message = Some((e.to_string(), true)),
                }
            }
        }
        if !self.transparent.is_empty() {
            ui.label(RichText::new("Transparency").strong());
        }
        for &i in &self.transparent.clone() {
            let name = self.scene.objects[i].name.clone();
            let mut t = self.scene.objects[i].material.transparency;
            let r = ui.add(
                Slider::new(&mut t, 0.0..=1.0)
                    .clamping(SliderClamping::Always)
                    .text(&name),
            );
            if r.changed() {
                match self.scene.set_transparency(i, t) {
                    Ok(()) => changes.materials.push(i),
                    Err(e) => self.message = Some((e.to_string(), true)),
                }
            }
        }
    }

    fn camera_controls(&mut self, ui: &mut egui::Ui, changes: &mut Changes) {
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
            Slider::new(&mut c.pitch, -MAX_PITCH..=MAX_PITCH)
                .clamping(SliderClamping::Always)
                .text("pitch °"),
        );
        ui.add(
            Slider::new(&mut c.vfov, VFOV)
                .logarithmic(true)
                .clamping(SliderClamping::Always)
                .text("field of view °"),
        );
        if ui.button("Reset camera").clicked() {
            c = self.initial_camera;
        }
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

fn status_lines(ui: &mut egui::Ui, s: &Status) {
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
