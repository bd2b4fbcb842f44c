//! Opening the window: the scene to start with (the seed, or a file as loaded or refused),
//! the render thread started, and the event loop run until the window closes.

use super::app::{App, Wake};
use super::camera_input::{CameraInput, step_for};
use super::document::Document;
use super::history::History;
use super::panel::{PANEL_WIDTH, PanelState};
use super::recent;
use super::render_thread::Status;
use super::timing;
use anyhow::{Context, Result, anyhow};
use prism::render::RenderSettings;
use prism::scene::Scene;
use prism::scene_file::SceneLoad;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::mpsc::channel;
use std::time::Instant;
use winit::event_loop::{ControlFlow, EventLoop};

/// The scene the viewer opens with.
pub enum Start {
    /// The built-in seed scene.
    Seed(Scene),
    /// A scene file, as loaded (or refused: the window then opens with the error shown).
    File {
        /// The file.
        path: PathBuf,
        /// Its load.
        load: SceneLoad,
    },
}

/// What the viewer opens with, resolved and checked by the command line.
pub struct Launch {
    /// The scene to show.
    pub start: Start,
    /// The image size (beside the panel) and anti-aliasing level to start with.
    pub settings: RenderSettings,
    /// Where screenshots are saved.
    pub screenshot_dir: PathBuf,
    /// Log frame times and change latencies (`timing.rs`).
    pub log_timing: bool,
    /// Show the image denoised from the start.
    pub denoise: bool,
}

/// Opens the window and runs until it closes.
pub fn run(launch: Launch) -> Result<()> {
    let Launch {
        start,
        settings: mut probe,
        screenshot_dir,
        log_timing,
        denoise,
    } = launch;
    let aa = probe.aa;
    let window_width = probe.width as u64 + PANEL_WIDTH.ceil() as u64;
    let largest = prism::limits::MAX_WINDOW_SIDE;
    if window_width > largest as u64 || probe.height > largest {
        return Err(prism::render::SettingsError::Window {
            width: probe.width,
            height: probe.height,
            panel: PANEL_WIDTH.ceil() as u32,
        }
        .into());
    }
    let dir_problem = match std::fs::metadata(&screenshot_dir) {
        Ok(meta) if meta.is_dir() => None,
        Ok(_) => Some("it is not a directory".to_string()),
        Err(e) => Some(prism::messages::io_message(&e)),
    };
    if let Some(reason) = dir_problem {
        return Err(prism::render::OutputError::Create {
            path: screenshot_dir,
            reason: format!("screenshots cannot be saved here: {reason}"),
        }
        .into());
    }
    let event_loop = match EventLoop::<Wake>::with_user_event().build() {
        Ok(event_loop) => event_loop,
        // Without a window, a scene that failed to load is the error to report (after
        // why there is no window).
        Err(e) => {
            if let Start::File { load, .. } = start
                && let Err(scene_error) = load.result
            {
                eprintln!("prism: cannot open a window: {e}");
                return Err(scene_error.into());
            }
            return Err(anyhow!(
                "cannot open a window ({e}); is there a display? \
                 `prism render` renders without one"
            ));
        }
    };
    event_loop.set_control_flow(ControlFlow::Wait);
    let (sender, loads) = channel();
    let proxy = Mutex::new(event_loop.create_proxy());
    let mut document = Document::new(sender, move || {
        let _ = proxy
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .send_event(Wake);
    });
    let scene = match start {
        Start::Seed(scene) => {
            document.loaded = prism::seed::loaded().ok();
            document.saved = Some(scene.clone());
            scene
        }
        Start::File { path, load } => {
            document.path = Some(path.clone());
            document.watch(&path, load.files);
            match load.result {
                Ok(loaded) => {
                    let scene = loaded.scene.clone();
                    document.saved = Some(scene.clone());
                    document.loaded = Some(loaded);
                    scene
                }
                Err(e) => {
                    eprintln!("prism: error: the scene did not load: {e}");
                    document.error = Some(e.to_string());
                    empty_scene()
                }
            }
        }
    };
    let mut recent = recent::list_path()
        .as_deref()
        .map(recent::read)
        .unwrap_or_default();
    if let Some(path) = &document.path {
        recent = recent::remember(&recent, path);
    }
    let step = step_for(&scene);
    probe.width = probe.width.max(1);
    let mut app = App {
        proxy: event_loop.create_proxy(),
        screenshot_dir,
        panel: PanelState::new(scene, aa)
            .denoised(denoise)
            .with_integrator(probe.integrator),
        input: CameraInput::new(step),
        document,
        loads,
        history: History::new(),
        recent,
        seen_picks: 0,
        timing: log_timing.then(timing::Timing::new),
        initial_image: (probe.width, probe.height),
        gfx: None,
        error: None,
        last_frame: Instant::now(),
        shown_serial: 0,
        cursor: None,
        dirty: true,
        last_present: Instant::now(),
        refresh_pending: false,
        holding: false,
        modifiers: Default::default(),
        status: Status::default(),
        render_error: None,
        press: None,
        awaiting_focus: false,
    };
    event_loop
        .run_app(&mut app)
        .context("the window's event loop failed")?;
    match (app.error, app.render_error) {
        (Some(e), _) => Err(e),
        (None, Some(e)) => Err(anyhow!("the render failed while the viewer ran: {e}")),
        (None, None) => Ok(()),
    }
}

/// What the window shows while no scene has loaded: nothing, under the default camera.
pub(super) fn empty_scene() -> Scene {
    prism::scene_file::parse_scene(
        "[camera]\neye = [0, 0, 0]\nfov = 40\n",
        Path::new("(no scene)"),
        Path::new("."),
    )
    .expect("the empty scene is valid")
}
