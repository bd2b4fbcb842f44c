//! What the window does with its scene file: open, save (Ctrl+S), save as, reload (F5), and
//! a finished load (the watcher's, Open's, F5's) taken in, keeping the camera and the
//! history where they still apply.

use super::app::App;
use super::camera_input::step_for;
use super::document;
use super::document::LoadMessage;
use super::history::{EditKey, History};
use super::recent;
use std::path::{Path, PathBuf};
use std::time::Instant;

impl App {
    /// Ctrl+S: the edits and the camera written into the scene file, atomically.
    pub(super) fn save(&mut self) {
        match self.document.path.clone() {
            Some(path) => {
                self.write_scene(&path);
            }
            None => self.say(
                "the built-in seed scene has no file: type a path in File and press Save as".into(),
                true,
            ),
        }
    }

    /// Writes the scene to `path` (another file), then shows that file.
    pub(super) fn save_as(&mut self, path: PathBuf) {
        if path.extension().is_none_or(|e| e != "toml") {
            return self.say(
                format!("{}: a scene file's name ends in .toml", path.display()),
                true,
            );
        }
        if self.write_scene(&path) {
            if self.document.path.as_deref() != Some(path.as_path()) {
                self.say(
                    format!(
                        "saved {}; textures and meshes are named relative to the file, so                          copy them beside it if it is in another folder",
                        path.display()
                    ),
                    false,
                );
            }
            self.document.path = Some(path.clone());
            self.recent = recent::remember(&self.recent, &path);
            self.document.load_in_background(path);
        }
    }

    /// The scene and camera written into the last good load's text, at `path`; true when
    /// written.
    pub(super) fn write_scene(&mut self, path: &Path) -> bool {
        if let Some(e) = &self.document.error {
            let text = format!("not saved: the file has an error to fix first ({e})");
            self.say(text, true);
            return false;
        }
        let Some(loaded) = &self.document.loaded else {
            self.say("not saved: no scene file has loaded".into(), true);
            return false;
        };
        let saved =
            match prism::scene_file::saved_text(loaded, &self.panel.scene, &self.panel.camera) {
                Ok(saved) => saved,
                Err(e) => {
                    self.say(format!("not saved: {e}"), true);
                    return false;
                }
            };
        match prism::render::write_bytes(path, saved.text.as_bytes()) {
            Ok(_) => {
                self.document.saved = Some(self.panel.scene.clone());
                let mut text = format!("saved {}", path.display());
                for s in &saved.skipped {
                    text.push_str(&format!("; not saved: {s}"));
                }
                self.say(text, !saved.skipped.is_empty());
                true
            }
            Err(e) => {
                self.say(format!("not saved: {e}"), true);
                false
            }
        }
    }

    /// Opens another scene file (loaded on a thread; the window shows it when it is ready).
    pub(super) fn open(&mut self, path: PathBuf) {
        self.say(format!("opening {}", path.display()), false);
        if self.document.path.as_deref() != Some(path.as_path()) {
            self.document.set_frame(0);
        }
        self.document.load_in_background(path);
    }

    /// F5: loads the scene file again now.
    pub(super) fn reload(&mut self) {
        if let Some(path) = self.document.path.clone() {
            self.document.load_in_background(path);
        }
    }

    /// Takes the finished loads: a good one replaces the scene, a bad one is shown and the
    /// last good scene stays.
    pub(super) fn take_loads(&mut self) {
        while let Ok(message) = self.loads.try_recv() {
            self.on_load(message);
        }
    }

    pub(super) fn on_load(&mut self, LoadMessage { path, load, asked }: LoadMessage) {
        let same_file = self.document.path.as_deref() == Some(path.as_path());
        if asked || !same_file {
            // A load asked for (Open, F5, Save as) watches what it read from now on.
            self.document.watch(&path, load.files);
        }
        if !same_file {
            self.document.path = Some(path.clone());
            self.recent = recent::remember(&self.recent, &path);
        }
        let loaded = match load.result {
            Ok(loaded) => loaded,
            Err(e) => {
                let text = e.to_string();
                self.document.error = Some(text.clone());
                return self.say(format!("the scene did not load: {text}"), true);
            }
        };
        // Frames asked for one after another load in parallel: only the last one asked
        // for is shown.
        if let Some(animation) = &loaded.animation
            && loaded.frame != self.document.frame().min(animation.frames - 1)
        {
            return;
        }
        let scene = loaded.scene.clone();
        let camera = match (&self.document.loaded, same_file) {
            (Some(before), true) => {
                document::camera_after_reload(&before.scene, &scene, self.panel.camera)
            }
            _ => scene.camera,
        };
        if same_file {
            // Unsaved edits are one undo away rather than lost.
            if self.document.unsaved(&self.panel.scene) {
                self.history
                    .record(&self.panel.scene, EditKey("reload".into()), Instant::now());
            }
            self.history.break_run();
        } else {
            self.history = History::new();
            self.panel.initial_camera = scene.camera;
            self.input.step = step_for(&scene);
            self.panel.take_sampling(&scene.render);
        }
        let what = match (&loaded.animation, same_file) {
            (Some(_), true) => format!("frame {} of", loaded.frame),
            (_, true) => "reloaded".into(),
            _ => "opened".into(),
        };
        let unread = loaded.unread();
        self.document.error = None;
        self.document.saved = Some(scene.clone());
        self.document.loaded = Some(loaded);
        self.panel.set_scene(scene);
        self.panel.camera = camera;
        self.send_scene();
        self.send_camera(false);
        let mut message = format!("{what} {}", path.display());
        for note in unread {
            message += &format!("\nnot read: {note}");
        }
        self.say(message, false);
    }
}
