//! The egui side panel: the file (save, open, undo), the objects and what the selected one
//! is made of, the lights, the scene's settings, anti-aliasing, the camera, and status.
//! Every edit goes through `Scene`'s checked setters (the scene file's limits), and comes
//! out as a `Changes` entry with the scene as it was before, for undo.

mod camera;
mod convergence;
mod file;
mod lights;
mod objects;
mod sampling;
mod scene_settings;
mod status;
mod widgets;

use status::status_lines;

use super::history::EditKey;
use super::render_thread::Status;
use egui::RichText;
use prism::camera::Camera;
use prism::integrator::IntegratorKind;
use prism::render::View;
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
    /// Show the image denoised, or raw.
    pub denoise: Option<bool>,
    /// Place an object's entry anew (its `translate`, `rotate`, `scale`), and which of the
    /// three changed.
    pub place: Option<(usize, ObjectPlacement, &'static str)>,
    /// Place a group anew, as `place` an object: its members follow.
    pub place_group: Option<(usize, ObjectPlacement, &'static str)>,
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

/// The samples per pixel the panel sets when path tracing is switched on and none were set.
const PATH_SAMPLES: u32 = 256;

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
    /// Whether the image is shown denoised.
    pub denoise: bool,
    /// The light transport rendered.
    pub integrator: IntegratorKind,
    /// Whether `samples` was set by switching path tracing on (and goes with it).
    samples_for_path: bool,
    /// The accumulation's course since it last restarted: seconds, samples per pixel and
    /// mean error estimate after each pass.
    pub convergence: Vec<[f64; 3]>,
    /// Whether the plot's x axis is samples per pixel (else seconds).
    plot_by_samples: bool,
    /// Whether a drag orbits the selection (else it turns the camera where it stands).
    pub orbit: bool,
    /// Whether an even scale is shown per axis, to make it uneven.
    scale_per_axis: bool,
    /// The group whose placement the transform rows edit, for the selected object (one of
    /// its groups); else the object's own.
    placing_group: Option<(usize, usize)>,
}

impl PanelState {
    pub fn new(scene: Scene, aa: u32) -> Self {
        Self {
            camera: scene.camera,
            initial_camera: scene.camera,
            samples: scene.render.samples,
            integrator: scene.render.integrator,
            samples_for_path: false,
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
            denoise: false,
            convergence: Vec::new(),
            plot_by_samples: false,
            orbit: false,
            scale_per_axis: false,
            placing_group: None,
        }
    }

    /// The panel rendering with `kind` from the start (the command line's choice, or the
    /// scene's).
    pub fn with_integrator(mut self, kind: IntegratorKind) -> Self {
        self.set_integrator(kind);
        self
    }

    /// Renders with `kind` from now on.
    fn set_integrator(&mut self, kind: IntegratorKind) {
        self.integrator = kind;
        self.integrator_changed();
    }

    /// Takes a newly opened file's samples per pixel and light transport.
    pub fn take_sampling(&mut self, render: &prism::scene::RenderDefaults) {
        self.samples = render.samples;
        self.samples_for_path = false;
        self.set_integrator(render.integrator);
    }

    /// Path tracing refines past the N×N grid, which suits Whitted's edges but leaves a lit
    /// room grainy: switched on with no count of samples set, it sets `PATH_SAMPLES` (shown
    /// and editable in the panel); back to Whitted, a count it set goes back.
    fn integrator_changed(&mut self) {
        match (self.integrator, self.samples) {
            (IntegratorKind::Path, None) => {
                self.samples = Some(PATH_SAMPLES);
                self.samples_for_path = true;
            }
            (IntegratorKind::Whitted, Some(PATH_SAMPLES)) if self.samples_for_path => {
                self.samples = None;
                self.samples_for_path = false;
            }
            _ => {}
        }
    }

    /// The panel with the image shown denoised (or not) from the start.
    pub fn denoised(mut self, on: bool) -> Self {
        self.denoise = on;
        self
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
}

#[cfg(test)]
mod tests {
    use super::widgets::scale_text;
    use super::*;
    use prism::render::{AdaptiveSettings, RenderSettings};
    use prism::scene::check_camera;

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
