//! The egui side panel: material sliders, anti-aliasing, camera, screenshot, and status.

use super::render_thread::Status;
use egui::{DragValue, RichText, Slider, SliderClamping};
use prism::appearance::LightKind;
use prism::camera::Camera;
use prism::scene::Scene;
use prism::scene::check_camera;
use std::ops::RangeInclusive;

/// Panel width in points.
pub const PANEL_WIDTH: f32 = 300.0;

/// The range of each slider: the bounds the scene file and the edits take (limits.rs), so
/// that no slider position is a value they refuse and every value they take is reachable.
pub struct SliderRanges {
    pub eta: RangeInclusive<f32>,
    pub transparency: RangeInclusive<f32>,
    pub aa: RangeInclusive<u32>,
    pub tolerance: RangeInclusive<f32>,
    pub pitch: RangeInclusive<f32>,
    pub vfov: RangeInclusive<f32>,
}

pub const SLIDERS: SliderRanges = SliderRanges {
    eta: prism::limits::ETA,
    transparency: prism::limits::FRACTION,
    aa: prism::limits::AA,
    tolerance: prism::limits::ADAPTIVE_TOLERANCE,
    pitch: prism::limits::PITCH,
    vfov: prism::limits::VFOV,
};

/// What the user changed this frame.
#[derive(Default)]
pub struct Changes {
    /// Objects whose material changed.
    pub materials: Vec<usize>,
    /// Lights that changed.
    pub lights: Vec<usize>,
    pub fog: bool,
    pub camera: bool,
    pub settings: bool,
    pub screenshot: bool,
}

pub struct PanelState {
    pub scene: Scene,
    pub camera: Camera,
    pub initial_camera: Camera,
    pub aa: u32,
    /// How far a tap of a movement key moves (the camera input's, shown and edited here).
    pub step: f32,
    /// Subsamples per pixel when not N×N (the scene's `samples`).
    pub samples: Option<u32>,
    pub adaptive: bool,
    pub tolerance: f32,
    /// The last screenshot or input message, and whether it is an error.
    pub message: Option<(String, bool)>,
    refractive: Vec<usize>,
    transparent: Vec<usize>,
    /// Objects that reflect (a roughness slider each).
    reflective: Vec<usize>,
}

impl PanelState {
    pub fn new(scene: Scene, aa: u32) -> Self {
        let refractive = (0..scene.objects.len())
            .filter(|&i| scene.objects[i].material.eta.is_some())
            .collect();
        let transparent = (0..scene.objects.len())
            .filter(|&i| scene.objects[i].material.transparency > 0.0)
            .collect();
        let reflective = (0..scene.objects.len())
            .filter(|&i| {
                let m = &scene.objects[i].material;
                m.reflectivity > 0.0 || m.fresnel
            })
            .collect();
        Self {
            reflective,
            camera: scene.camera,
            initial_camera: scene.camera,
            samples: scene.render.samples,
            step: 1.0,
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
            self.effects(ui, &mut changes);
            ui.separator();
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
                Slider::new(&mut eta, SLIDERS.eta)
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
                Slider::new(&mut t, SLIDERS.transparency)
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

    /// Lights' sizes and cones, glossy roughness, Fresnel glass and fog: each change
    /// restarts the accumulation.
    fn effects(&mut self, ui: &mut egui::Ui, changes: &mut Changes) {
        ui.label(RichText::new("Lights and effects").strong());
        for i in 0..self.scene.lights.len() {
            match self.scene.lights[i].kind {
                LightKind::Area { shape, .. } => {
                    let mut size = shape.size();
                    let step = size * 0.01;
                    let r = ui.add(
                        DragValue::new(&mut size)
                            .speed(step)
                            .range(prism::limits::MIN_LENGTH as f32..=f32::MAX)
                            .prefix(format!("light {i} size ")),
                    );
                    if r.changed() {
                        match self.scene.set_light_size(i, size) {
                            Ok(()) => changes.lights.push(i),
                            Err(e) => self.message = Some((e.to_string(), true)),
                        }
                    }
                }
                LightKind::Spot { cone, .. } => {
                    let (mut angle, mut softness) = (cone.angle, cone.softness);
                    let a = ui.add(
                        Slider::new(&mut angle, prism::limits::SPOT_ANGLE)
                            .logarithmic(true)
                            .clamping(SliderClamping::Always)
                            .text(format!("spot {i} angle °")),
                    );
                    let s = ui.add(
                        Slider::new(&mut softness, 0.0..=1.0)
                            .clamping(SliderClamping::Always)
                            .text(format!("spot {i} softness")),
                    );
                    if a.changed() || s.changed() {
                        match self.scene.set_spot(i, angle, softness) {
                            Ok(()) => changes.lights.push(i),
                            Err(e) => self.message = Some((e.to_string(), true)),
                        }
                    }
                }
                LightKind::Point { .. } | LightKind::Directional { .. } => {}
            }
        }
        for &i in &self.reflective.clone() {
            let name = self.scene.objects[i].name.clone();
            let mut r = self.scene.objects[i].material.roughness;
            let changed = ui
                .add(
                    Slider::new(&mut r, prism::limits::ROUGHNESS)
                        .clamping(SliderClamping::Always)
                        .text(format!("{name} roughness")),
                )
                .changed();
            if changed {
                match self.scene.set_roughness(i, r) {
                    Ok(()) => changes.materials.push(i),
                    Err(e) => self.message = Some((e.to_string(), true)),
                }
            }
        }
        for &i in &self.refractive.clone() {
            let m = &self.scene.objects[i].material;
            if m.eta == Some(1.0) {
                continue;
            }
            let mut on = m.fresnel;
            let name = self.scene.objects[i].name.clone();
            if ui
                .checkbox(&mut on, format!("{name}: Fresnel glass"))
                .changed()
            {
                match self.scene.set_fresnel(i, on) {
                    Ok(()) => changes.materials.push(i),
                    Err(e) => self.message = Some((e.to_string(), true)),
                }
            }
        }
        if let Some(fog) = self.scene.fog {
            let mut density = fog.density();
            let step = density * 0.01;
            let changed = ui
                .add(
                    DragValue::new(&mut density)
                        .speed(step)
                        .range(f32::MIN_POSITIVE..=prism::limits::MAX_EXTINCTION)
                        .prefix("fog density "),
                )
                .changed();
            if changed {
                match self.scene.set_fog_density(density) {
                    Ok(()) => changes.fog = true,
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
                let table = prism::scene::camera_table(&self.camera, self.scene.origin);
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

#[cfg(test)]
mod tests {
    use super::*;
    use prism::render::{AdaptiveSettings, RenderSettings};

    /// The values just inside and just outside a range's ends.
    fn ends(r: &RangeInclusive<f32>) -> [(f32, bool); 4] {
        let (lo, hi) = (*r.start(), *r.end());
        [
            (lo, true),
            (hi, true),
            (lo.next_down(), false),
            (hi.next_up(), false),
        ]
    }

    #[test]
    fn every_slider_spans_exactly_what_the_edits_and_settings_accept() {
        let mut scene = prism::seed::scene().unwrap();
        let glass = scene
            .objects
            .iter()
            .position(|o| o.material.eta.is_some())
            .unwrap();
        for (eta, ok) in ends(&SLIDERS.eta) {
            assert_eq!(scene.set_eta(glass, eta).is_ok(), ok, "eta {eta}");
        }
        for (t, ok) in ends(&SLIDERS.transparency) {
            assert_eq!(
                scene.set_transparency(glass, t).is_ok(),
                ok,
                "transparency {t}"
            );
        }
        for (pitch, ok) in ends(&SLIDERS.pitch) {
            let c = prism::camera::Camera {
                pitch,
                ..scene.camera
            };
            assert_eq!(check_camera(&c).is_ok(), ok, "pitch {pitch}");
        }
        for (vfov, ok) in ends(&SLIDERS.vfov) {
            let c = prism::camera::Camera {
                vfov,
                ..scene.camera
            };
            assert_eq!(check_camera(&c).is_ok(), ok, "field of view {vfov}");
        }
        let (lo, hi) = (*SLIDERS.aa.start(), *SLIDERS.aa.end());
        for (aa, ok) in [(lo, true), (hi, true), (lo - 1, false), (hi + 1, false)] {
            let s = RenderSettings::new(8, 8, aa);
            assert_eq!(s.validate().is_ok(), ok, "aa {aa}");
        }
        for (tolerance, ok) in ends(&SLIDERS.tolerance) {
            let mut s = RenderSettings::new(8, 8, 2);
            s.adaptive = Some(AdaptiveSettings {
                tolerance,
                ..AdaptiveSettings::default()
            });
            assert_eq!(s.validate().is_ok(), ok, "tolerance {tolerance}");
        }
    }

    #[test]
    fn the_file_takes_what_the_sliders_span() {
        // The scene file's own bounds at the same ends: eta, transparency, pitch, fov, aa.
        let parse = |camera: &str, render: &str, material: &str| {
            let camera = if camera.starts_with("fov") {
                camera.to_string()
            } else {
                format!("fov = 40\n{camera}")
            };
            let text = format!(
                "[camera]\neye = [0, 0, 0]\n{camera}\n[render]\n{render}\n\
                 [materials.m]\n{material}\n[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\n\
                 material = \"m\"\n"
            );
            let path = std::path::Path::new("walk.toml");
            prism::scene::parse_scene(&text, path, std::path::Path::new(".")).is_ok()
        };
        let show = |v: f32| format!("{v:e}");
        for (eta, ok) in ends(&SLIDERS.eta) {
            let m = format!("transparency = 0.5\neta = {}", show(eta));
            assert_eq!(parse("", "", &m), ok, "eta {eta}");
        }
        for (t, ok) in ends(&SLIDERS.transparency) {
            assert_eq!(
                parse("", "", &format!("transparency = {}", show(t))),
                ok,
                "{t}"
            );
        }
        for (pitch, ok) in ends(&SLIDERS.pitch) {
            assert_eq!(
                parse(&format!("pitch = {}", show(pitch)), "", ""),
                ok,
                "{pitch}"
            );
        }
        for (vfov, ok) in ends(&SLIDERS.vfov) {
            assert_eq!(
                parse(&format!("fov = {}", show(vfov)), "", ""),
                ok,
                "{vfov}"
            );
        }
        let (lo, hi) = (*SLIDERS.aa.start(), *SLIDERS.aa.end());
        for (aa, ok) in [(lo, true), (hi, true), (lo - 1, false), (hi + 1, false)] {
            assert_eq!(parse("", &format!("aa = {aa}"), ""), ok, "aa {aa}");
        }
    }
}
