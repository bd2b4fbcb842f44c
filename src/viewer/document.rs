//! The scene file the viewer shows: its path, the last good load (what a save writes into),
//! the error of a load that failed, and the watcher that reloads it on change. Loads run on
//! threads of their own (the watcher's, or a one-off for Open and F5), never on the UI
//! thread; each ends as a message on a channel.

use super::watch::Watcher;
use prism::camera::Camera;
use prism::scene::Scene;
use prism::scene_file::{LoadedScene, SceneLoad, load_scene_file_at};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::mpsc::Sender;

/// A finished load of `path`, and whether it was asked for (Open, F5, Save as) rather than
/// seen by the watcher.
pub struct LoadMessage {
    pub path: PathBuf,
    pub load: SceneLoad,
    pub asked: bool,
}

pub struct Document {
    /// The scene file; None for the built-in seed.
    pub path: Option<PathBuf>,
    /// The last good load: what Save writes into.
    pub loaded: Option<LoadedScene>,
    /// The scene as last loaded or saved, to tell whether edits are unsaved.
    pub saved: Option<Scene>,
    /// Why the last load failed, until one succeeds.
    pub error: Option<String>,
    /// The frame of an animated file that loads show (shared with the watcher, so that a
    /// reload on save stays at it).
    frame: Arc<AtomicU32>,
    watcher: Option<Watcher>,
    sender: Sender<LoadMessage>,
    wake: std::sync::Arc<dyn Fn() + Send + Sync>,
}

impl Document {
    /// A document that sends its loads to `sender`, calling `wake` after each.
    pub fn new(sender: Sender<LoadMessage>, wake: impl Fn() + Send + Sync + 'static) -> Self {
        Self {
            path: None,
            loaded: None,
            saved: None,
            error: None,
            frame: Arc::new(AtomicU32::new(0)),
            watcher: None,
            sender,
            wake: std::sync::Arc::new(wake),
        }
    }

    /// Watches `path`'s `files` (those its last load read) from now on.
    pub fn watch(&mut self, path: &Path, files: Vec<PathBuf>) {
        let (sender, wake) = (self.sender.clone(), self.wake.clone());
        let p = path.to_path_buf();
        self.watcher = None;
        let watcher = Watcher::spawn(p.clone(), files, self.frame.clone(), move |load| {
            let _ = sender.send(LoadMessage {
                path: p.clone(),
                load,
                asked: false,
            });
            wake();
        });
        match watcher {
            Ok(w) => self.watcher = Some(w),
            Err(e) => eprintln!(
                "prism: error: cannot watch {} for changes (F5 reloads it): {e}",
                path.display()
            ),
        }
    }

    /// Loads `path` on a thread of its own; the result comes as a message.
    pub fn load_in_background(&self, path: PathBuf) {
        let (sender, wake) = (self.sender.clone(), self.wake.clone());
        let frame = self.frame.load(Ordering::Relaxed);
        let spawned = std::thread::Builder::new()
            .name("prism-load".into())
            .spawn(move || {
                let load = load_scene_file_at(&path, frame);
                let _ = sender.send(LoadMessage {
                    path,
                    load,
                    asked: true,
                });
                wake();
            });
        if let Err(e) = spawned {
            eprintln!("prism: error: cannot start a thread to load the scene: {e}");
        }
    }

    /// Shows `frame` of an animated file from the next load on (0 for another file).
    pub fn set_frame(&self, frame: u32) {
        self.frame.store(frame, Ordering::Relaxed);
    }

    /// The frame loads show.
    pub fn frame(&self) -> u32 {
        self.frame.load(Ordering::Relaxed)
    }

    /// Whether `scene` differs from the scene as last loaded or saved.
    pub fn unsaved(&self, scene: &Scene) -> bool {
        self.saved.as_ref().is_some_and(|s| s != scene)
    }
}

/// The camera to show after the file is loaded again: the file's own when the file's
/// `[camera]` changed (the user edited it), else the view the user had, kept in place in
/// the world although the scene's origin (the file's eye) may have moved.
pub fn camera_after_reload(before: &Scene, after: &Scene, current: Camera) -> Camera {
    let world = |s: &Scene, c: &Camera| s.origin + c.eye.as_dvec3();
    let file_camera_changed = world(before, &before.camera) != world(after, &after.camera)
        || Camera {
            eye: glam::Vec3::ZERO,
            ..before.camera
        } != Camera {
            eye: glam::Vec3::ZERO,
            ..after.camera
        };
    if file_camera_changed {
        return after.camera;
    }
    let mut kept = current;
    kept.eye = (world(before, &current) - after.origin).as_vec3();
    if kept.check().is_ok() {
        kept
    } else {
        after.camera
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism::scene_file::parse_scene;

    fn scene(text: &str) -> Scene {
        parse_scene(text, Path::new("s.toml"), Path::new(".")).unwrap()
    }

    const FILE: &str = "[camera]\neye = [1, 2, 10]\nfov = 40\n\
                        [[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n";

    /// An edit elsewhere in the file keeps the user's view where it was in the world; an
    /// edit of the file's camera takes the new camera.
    #[test]
    fn a_reload_keeps_the_view_unless_the_files_camera_changed() {
        let before = scene(FILE);
        let mut flown = before.camera;
        flown.eye += glam::Vec3::new(3.0, 0.0, -2.0);
        flown.yaw = 25.0;
        let after = scene(&FILE.replace("radius = 1", "radius = 2"));
        let kept = camera_after_reload(&before, &after, flown);
        assert_eq!(kept.yaw, 25.0);
        let world = after.origin + kept.eye.as_dvec3();
        assert_eq!(world, glam::DVec3::new(4.0, 2.0, 8.0));
        let moved = scene(&FILE.replace("eye = [1, 2, 10]", "eye = [0, 0, 20]"));
        assert_eq!(camera_after_reload(&before, &moved, flown), moved.camera);
        let wider = scene(&FILE.replace("fov = 40", "fov = 60"));
        assert_eq!(camera_after_reload(&before, &wider, flown), wider.camera);
    }
}
