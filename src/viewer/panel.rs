//! The egui side panel: the file (save, open, undo), the objects and what the selected one
//! is made of, the lights, the scene's settings, anti-aliasing, the camera, and status.
//! Every edit goes through `Scene`'s checked setters (the scene file's limits), and comes
//! out as a `Changes` entry with the scene as it was before, for undo.

use super::history::EditKey;
use super::render_thread::Status;
use egui::{DragValue, RichText, Slider, SliderClamping};
use glam::{DVec3, Vec3};
use prism::appearance::{Background, Falloff, LightKind, Texture};
use prism::camera::Camera;
use prism::limits::{MAX_COORDINATE, MAX_PHONG_FACTOR, MAX_RADIANCE, MAX_SHININESS, MIN_LENGTH};
use prism::render::{Legend, View};
use prism::scene::check_camera;
use prism::scene::{EditError, ObjectPlacement, Scene};
use std::ops::RangeInclusive;
use std::path::PathBuf;

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

/// What the user changed or asked for this frame.
#[derive(Default)]
pub struct Changes {
    /// Scene edits, each with what it changed and the scene before it.
    pub edits: Vec<(EditKey, Scene)>,
    pub camera: bool,
    pub settings: bool,
    pub screenshot: bool,
    /// A new selection (None inside: none).
    pub select: Option<Option<usize>>,
    pub save: bool,
    pub save_as: Option<PathBuf>,
    pub open: Option<PathBuf>,
    pub reload: bool,
    pub undo: bool,
    pub redo: bool,
    /// Show this frame of the animation.
    pub frame: Option<u32>,
    /// Show the image or a heat map.
    pub view: Option<View>,
    /// Place an object's entry anew (its `translate`, `rotate`, `scale`), and which of the
    /// three changed.
    pub place: Option<(usize, ObjectPlacement, &'static str)>,
}

/// The file the viewer shows, as the panel reports it.
#[derive(Default)]
pub struct FileStatus {
    /// The scene file; None for the built-in seed.
    pub path: Option<PathBuf>,
    /// The last load's error (file, line and what), shown until a load succeeds.
    pub error: Option<String>,
    /// Edits not yet saved.
    pub unsaved: bool,
    /// Whether a load of the file has succeeded (what stays on screen while it is broken).
    pub loaded: bool,
    pub can_undo: bool,
    pub can_redo: bool,
    /// Recently opened scene files, newest first.
    pub recent: Vec<PathBuf>,
    /// An animated file's frame count and rate.
    pub animation: Option<(u32, f64)>,
    /// The frame shown.
    pub frame: u32,
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
    /// The last screenshot, save or input message, and whether it is an error.
    pub message: Option<(String, bool)>,
    /// The selected object.
    pub selected: Option<usize>,
    pub file: FileStatus,
    /// The path typed into the File section, to open or save as.
    path_entry: String,
    /// What the image area shows.
    pub view: View,
    /// The accumulation's course since it last restarted: seconds, samples per pixel and
    /// mean error estimate after each pass.
    pub convergence: Vec<[f64; 3]>,
    /// Whether the plot's x axis is samples per pixel (else seconds).
    plot_by_samples: bool,
    /// Whether a drag orbits the selection (else it turns the camera where it stands).
    pub orbit: bool,
    /// Whether an even scale is shown per axis, to make it uneven.
    scale_per_axis: bool,
}

impl PanelState {
    pub fn new(scene: Scene, aa: u32) -> Self {
        Self {
            camera: scene.camera,
            initial_camera: scene.camera,
            samples: scene.render.samples,
            step: 1.0,
            scene,
            aa,
            adaptive: false,
            tolerance: prism::render::AdaptiveSettings::default().tolerance,
            message: None,
            selected: None,
            file: FileStatus::default(),
            path_entry: String::new(),
            view: View::Image,
            convergence: Vec::new(),
            plot_by_samples: false,
            orbit: false,
            scale_per_axis: false,
        }
    }

    /// Shows a scene loaded anew (a reload, an undo, another file): the selection is kept
    /// while it still names an object.
    pub fn set_scene(&mut self, scene: Scene) {
        if self.selected.is_some_and(|s| s >= scene.objects.len()) {
            self.selected = None;
        }
        self.scene = scene;
    }

    /// Applies `edit` to the scene; a change is reported with `key` and the scene before
    /// it, a refusal shown as the panel's message.
    fn edit(
        &mut self,
        changes: &mut Changes,
        key: String,
        edit: impl FnOnce(&mut Scene) -> Result<(), EditError>,
    ) {
        let before = self.scene.clone();
        match edit(&mut self.scene) {
            Ok(()) if self.scene != before => changes.edits.push((EditKey(key), before)),
            Ok(()) => {}
            Err(e) => self.message = Some((e.to_string(), true)),
        }
    }

    pub fn show(&mut self, ui: &mut egui::Ui, status: &Status) -> Changes {
        let mut changes = Changes::default();
        egui::ScrollArea::vertical().show(ui, |ui| {
            ui.heading("prism");
            let error_color = ui.visuals().error_fg_color;
            // A failed render or load matters more than any control: it goes first.
            if let Some(e) = &status.error {
                let text = format!("The render failed: {e}. Change anything to try again.");
                ui.label(RichText::new(text).color(error_color));
                ui.separator();
            }
            if let Some(e) = &self.file.error {
                let then = if self.file.loaded {
                    "The last good scene stays on screen until the file is fixed."
                } else {
                    "Fix the file and save it: the viewer loads it then."
                };
                let text = format!("{e}\n{then}");
                ui.label(RichText::new(text).color(error_color));
                ui.separator();
            }
            self.file_section(ui, &mut changes);
            ui.separator();
            self.objects(ui, &mut changes);
            ui.separator();
            egui::CollapsingHeader::new(RichText::new("Lights").strong())
                .default_open(true)
                .show(ui, |ui| self.lights(ui, &mut changes));
            egui::CollapsingHeader::new(RichText::new("Scene").strong())
                .default_open(true)
                .show(ui, |ui| self.scene_settings(ui, &mut changes));
            ui.separator();
            self.sampling(ui, &mut changes);
            ui.separator();
            egui::CollapsingHeader::new(RichText::new("Convergence").strong())
                .default_open(true)
                .show(ui, |ui| self.convergence(ui, status, &mut changes));
            ui.separator();
            self.camera_controls(ui, &mut changes);
            ui.separator();
            if ui.button("Save screenshot (F12 or P)").clicked() {
                changes.screenshot = true;
            }
            if let Some((text, error)) = &self.message {
                let color = if *error {
                    error_color
                } else {
                    ui.visuals().text_color()
                };
                ui.label(RichText::new(text).color(color));
            }
            ui.separator();
            status_lines(ui, status);
            ui.separator();
            ui.small(
                "Click: select · drag: look · WASD: move · Q/E: down/up · scroll: zoom · \
                 Ctrl+S: save · Ctrl+Z / Ctrl+Shift+Z: undo / redo · F5: reload · \
                 Esc: deselect · Ctrl+Q: quit",
            );
        });
        changes
    }

    fn file_section(&mut self, ui: &mut egui::Ui, changes: &mut Changes) {
        ui.label(RichText::new("File").strong());
        let name = match &self.file.path {
            Some(p) => p.display().to_string(),
            None => prism::seed::NAME.to_string(),
        };
        let unsaved = if self.file.unsaved { " (edited)" } else { "" };
        ui.label(format!("{name}{unsaved}"));
        ui.horizontal(|ui| {
            let saveable = self.file.path.is_some() && self.file.error.is_none();
            if ui
                .add_enabled(saveable, egui::Button::new("Save"))
                .on_hover_text("Ctrl+S: write the edits and the camera into the file")
                .clicked()
            {
                changes.save = true;
            }
            if ui
                .add_enabled(self.file.can_undo, egui::Button::new("Undo"))
                .clicked()
            {
                changes.undo = true;
            }
            if ui
                .add_enabled(self.file.can_redo, egui::Button::new("Redo"))
                .clicked()
            {
                changes.redo = true;
            }
            if ui
                .add_enabled(self.file.path.is_some(), egui::Button::new("Reload"))
                .clicked()
            {
                changes.reload = true;
            }
        });
        if let Some((frames, fps)) = self.file.animation {
            ui.horizontal(|ui| {
                let last = frames - 1;
                let mut frame = self.file.frame.min(last);
                ui.label("frame");
                if ui
                    .add_enabled(frame > 0, egui::Button::new("<").small())
                    .on_hover_text("the frame before")
                    .clicked()
                {
                    frame -= 1;
                }
                ui.add(egui::DragValue::new(&mut frame).range(0..=last));
                if ui
                    .add_enabled(frame < last, egui::Button::new(">").small())
                    .on_hover_text("the next frame")
                    .clicked()
                {
                    frame += 1;
                }
                ui.label(format!("of 0–{last}, {fps} fps"));
                if frame != self.file.frame {
                    changes.frame = Some(frame);
                }
            });
        }
        ui.horizontal(|ui| {
            ui.add(
                egui::TextEdit::singleline(&mut self.path_entry)
                    .hint_text("path/to/scene.toml")
                    .desired_width(150.0),
            );
            let path = || PathBuf::from(self.path_entry.trim());
            let typed = !self.path_entry.trim().is_empty();
            if ui.add_enabled(typed, egui::Button::new("Open")).clicked() {
                changes.open = Some(path());
            }
            if ui
                .add_enabled(typed, egui::Button::new("Save as"))
                .clicked()
            {
                changes.save_as = Some(path());
            }
        });
        // Collapsed, so that the panel's layout does not shift with the list's length.
        egui::CollapsingHeader::new("Recent files (or drop a file on the window)")
            .default_open(false)
            .show(ui, |ui| {
                for p in self.file.recent.clone() {
                    if ui.small_button(p.display().to_string()).clicked() {
                        changes.open = Some(p);
                    }
                }
            });
    }

    /// The list of objects, and the selected one's material.
    fn objects(&mut self, ui: &mut egui::Ui, changes: &mut Changes) {
        ui.label(RichText::new("Objects").strong());
        egui::ScrollArea::vertical()
            .id_salt("objects")
            .max_height(110.0)
            .show(ui, |ui| {
                for (i, o) in self.scene.objects.iter().enumerate() {
                    let picked = self.selected == Some(i);
                    if ui.selectable_label(picked, &o.name).clicked() {
                        let new = if picked { None } else { Some(i) };
                        self.selected = new;
                        changes.select = Some(new);
                    }
                }
            });
        let Some(i) = self.selected else {
            ui.small("Click an object in the image or the list to edit it.");
            return;
        };
        ui.label(RichText::new(format!("Selected: {}", self.scene.objects[i].name)).strong());
        // Its entry's `translate`, `rotate` and `scale`, as the file has them.
        let mut p = self.scene.objects[i].placement;
        let before = p;
        position_row(ui, "translate", &mut p.translate);
        ui.horizontal(|ui| {
            ui.label("rotate °").on_hover_text(
                "The file's `rotate`: degrees about x, then y, then z, about the world's \
                 origin, after the scale and before the move",
            );
            let r = &mut p.rotate;
            // Any finite angle, as in the file: place_object refuses the rest.
            xyz(ui, [&mut r.x, &mut r.y, &mut r.z], |d| d.speed(0.5));
        });
        ui.horizontal(|ui| {
            ui.label("scale").on_hover_text(
                "The file's `scale`: about the world's origin, before the turn and the move",
            );
            fn factor(d: DragValue<'_>) -> DragValue<'_> {
                d.range(prism::limits::SCALE)
                    .speed(0.01)
                    .custom_formatter(|v, _| scale_text(v))
            }
            let even = p.scale.x == p.scale.y && p.scale.y == p.scale.z;
            if even && !self.scale_per_axis {
                let mut k = p.scale.x;
                if ui.add(factor(DragValue::new(&mut k))).changed() {
                    p.scale = DVec3::splat(k);
                }
            } else {
                let s = &mut p.scale;
                xyz(ui, [&mut s.x, &mut s.y, &mut s.z], factor);
            }
            let mut per_axis = self.scale_per_axis || !even;
            if ui
                .add_enabled(even, egui::Checkbox::new(&mut per_axis, "per axis"))
                .changed()
            {
                self.scale_per_axis = per_axis;
            }
        });
        let field = if p.translate != before.translate {
            "translate"
        } else if p.rotate != before.rotate {
            "rotate"
        } else {
            "scale"
        };
        if p != before {
            changes.place = Some((i, p, field));
        }
        let mut m = self.scene.objects[i].material.clone();
        let before = m.clone();
        let mut field = "";
        match &mut m.texture {
            Texture::Solid(c) => {
                if color_row(ui, "colour", c, 0.0..=1.0, true) {
                    field = "color";
                }
            }
            other => {
                ui.label(format!("colour: {} texture", texture_kind(other)));
            }
        }
        let factors: [(&str, &mut f32, f32, f32); 4] = [
            ("ambient", &mut m.ambient, MAX_PHONG_FACTOR, 0.01),
            ("diffuse", &mut m.diffuse, MAX_PHONG_FACTOR, 0.01),
            ("specular", &mut m.specular, MAX_PHONG_FACTOR, 0.01),
            ("shininess", &mut m.shininess, MAX_SHININESS, 1.0),
        ];
        ui.horizontal_wrapped(|ui| {
            for (name, v, hi, speed) in factors {
                let r = ui.add(
                    DragValue::new(v)
                        .range(0.0..=hi)
                        .speed(speed)
                        .prefix(format!("{name} ")),
                );
                if r.changed() {
                    field = name;
                }
            }
        });
        for (name, v) in [
            ("reflectivity", &mut m.reflectivity),
            ("transparency", &mut m.transparency),
        ] {
            let r = ui.add(
                Slider::new(v, SLIDERS.transparency)
                    .clamping(SliderClamping::Always)
                    .text(name),
            );
            if r.changed() {
                field = name;
            }
        }
        let mut refracts = m.eta.is_some();
        let mut eta = m.eta.unwrap_or(1.5);
        ui.horizontal(|ui| {
            let c = ui.checkbox(&mut refracts, "");
            let r = ui.add_enabled(
                refracts,
                // The whole range a file may give, on a log scale centred on 1.
                Slider::new(&mut eta, SLIDERS.eta)
                    .logarithmic(true)
                    .clamping(SliderClamping::Always)
                    .max_decimals(4)
                    .text("eta"),
            );
            if c.changed() || r.changed() {
                field = "eta";
            }
        });
        m.eta = refracts.then_some(eta);
        if !refracts {
            m.fresnel = false;
        }
        let reflects = m.reflectivity > 0.0 || m.fresnel;
        let r = ui.add_enabled(
            reflects,
            Slider::new(&mut m.roughness, prism::limits::ROUGHNESS)
                .clamping(SliderClamping::Always)
                .text("roughness"),
        );
        if r.changed() {
            field = "roughness";
        }
        if !reflects {
            m.roughness = 0.0;
        }
        let glass = matches!(m.eta, Some(e) if e != 1.0) && m.conductor.is_none();
        let r = ui.add_enabled(glass, egui::Checkbox::new(&mut m.fresnel, "Fresnel glass"));
        if r.changed() {
            field = "fresnel";
        }
        if color_row(ui, "emission", &mut m.emission, 0.0..=MAX_RADIANCE, false) {
            field = "emission";
        }
        if m != before {
            self.edit(changes, format!("object {i} {field}"), |s| {
                s.set_material(i, m)
            });
        }
    }

    /// Each light's colour, place, intensity, size or cone.
    fn lights(&mut self, ui: &mut egui::Ui, changes: &mut Changes) {
        let origin = self.scene.origin;
        for i in 0..self.scene.lights.len() {
            let light = self.scene.lights[i];
            let kind = match light.kind {
                LightKind::Point { .. } => "point",
                LightKind::Spot { .. } => "spot",
                LightKind::Directional { .. } => "directional",
                LightKind::Area { .. } => "area",
            };
            ui.label(format!("light {i} ({kind})"));
            let mut color = light.color;
            let mut center = light.center().map(|c| origin + c.as_dvec3());
            let mut changed = color_row(ui, "colour", &mut color, 0.0..=MAX_RADIANCE, false);
            if let Some(world) = &mut center {
                changed |= position_row(ui, "at", world);
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
                    let r = ui.add(
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
                LightKind::Spot { cone, .. } => {
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
                }
                LightKind::Point { .. } | LightKind::Directional { .. } => {}
            }
        }
    }

    /// Background, ambient light, depth and fog.
    fn scene_settings(&mut self, ui: &mut egui::Ui, changes: &mut Changes) {
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

    /// The view switch, the heat map's legend, and the plot of the error estimate.
    fn convergence(&mut self, ui: &mut egui::Ui, status: &Status, changes: &mut Changes) {
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
        });
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

    fn sampling(&mut self, ui: &mut egui::Ui, changes: &mut Changes) {
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

/// Three numbers for a colour (within `range` per channel) with, for a reflectance
/// (`picker`), egui's colour picker beside them; true when any changed.
fn color_row(
    ui: &mut egui::Ui,
    label: &str,
    c: &mut Vec3,
    range: RangeInclusive<f32>,
    picker: bool,
) -> bool {
    ui.horizontal(|ui| {
        ui.label(label);
        let mut changed = false;
        if picker {
            let mut rgb = c.to_array();
            if ui.color_edit_button_rgb(&mut rgb).changed() {
                *c = Vec3::from_array(rgb)
                    .clamp(Vec3::splat(*range.start()), Vec3::splat(*range.end()));
                changed = true;
            }
        }
        for (v, name) in [(&mut c.x, "r "), (&mut c.y, "g "), (&mut c.z, "b ")] {
            let r = ui.add(
                DragValue::new(v)
                    .range(range.clone())
                    .speed(0.005)
                    .max_decimals(4)
                    .prefix(name),
            );
            changed |= r.changed();
        }
        changed
    })
    .inner
}

/// The heat map's colour scale with the values at its ends.
fn legend_bar(ui: &mut egui::Ui, legend: &Legend, view: View) {
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

/// A scale factor as the panel shows it: three decimals, and tiny factors (which a typed 0
/// is clamped to) in exponent form rather than as "0.000".
fn scale_text(v: f64) -> String {
    if v != 0.0 && v.abs() < 0.01 {
        format!("{v:.2e}")
    } else {
        let text = format!("{v:.3}");
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// Three numbers named x, y and z, each styled by `style`; true when one changed.
fn xyz<N: egui::emath::Numeric>(
    ui: &mut egui::Ui,
    values: [&mut N; 3],
    style: impl Fn(DragValue<'_>) -> DragValue<'_>,
) -> bool {
    let mut changed = false;
    for (v, name) in values.into_iter().zip(["x ", "y ", "z "]) {
        changed |= ui.add(style(DragValue::new(v)).prefix(name)).changed();
    }
    changed
}

/// A position in world coordinates; true when it changed.
fn position_row(ui: &mut egui::Ui, label: &str, p: &mut DVec3) -> bool {
    ui.horizontal(|ui| {
        ui.label(label);
        xyz(ui, [&mut p.x, &mut p.y, &mut p.z], |d| {
            d.range(-MAX_COORDINATE..=MAX_COORDINATE).speed(0.05)
        })
    })
    .inner
}

fn texture_kind(t: &Texture) -> &'static str {
    match t {
        Texture::Solid(_) => "solid",
        Texture::Checker { .. } => "checker",
        Texture::Stripes { .. } => "stripes",
        Texture::Image { .. } => "image",
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

    /// A scale shows as few digits as it needs, and the smallest one a file may give
    /// does not read as zero.
    #[test]
    fn scale_factors_read_as_what_they_are() {
        for (v, text) in [
            (1.0, "1"),
            (1.5, "1.5"),
            (0.25, "0.25"),
            (10.0, "10"),
            (1.0e6, "1000000"),
            (0.0123, "0.012"),
            (1.0e-6, "1.00e-6"),
            (0.005, "5.00e-3"),
        ] {
            assert_eq!(scale_text(v), text, "{v}");
            if v >= 0.01 {
                let back: f64 = text.parse().unwrap();
                assert!((back - v).abs() <= 5e-4 * v.max(1.0), "{v}");
            }
        }
    }

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
            prism::scene_file::parse_scene(&text, path, std::path::Path::new(".")).is_ok()
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
