//! Reload on save: a thread that watches the scene file and every file it reads (textures,
//! meshes, material libraries), and loads the scene again once they have stopped changing.
//! It polls each file's size and modification time: a handful of `stat` calls a tenth of a
//! second, which works on every file system (network mounts and editors that replace the
//! file by renaming included) without a platform notification API.

use prism::scene_file::{SceneLoad, load_scene_file_at};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::time::{Duration, Instant, SystemTime};

/// How often the files are looked at.
const POLL: Duration = Duration::from_millis(100);

/// How long the files must stay unchanged after a change before the scene is loaded: an
/// editor's save (write, then rename, then touch) is one change, not three, and a file is
/// not read half written.
pub const SETTLE: Duration = Duration::from_millis(150);

/// What a file looked like: its size and modification time, or None when it is missing.
type Stamp = Option<(u64, SystemTime)>;

fn stamp(path: &Path) -> Stamp {
    let meta = std::fs::metadata(path).ok()?;
    Some((meta.len(), meta.modified().ok()?))
}

/// Decides when a set of files has changed and settled, from their stamps over time.
pub struct Settle {
    files: Vec<(PathBuf, Stamp)>,
    /// When a change was last seen, while waiting for the files to settle.
    changed_at: Option<Instant>,
}

impl Settle {
    /// Watches `files`, as they are now.
    pub fn new(files: Vec<PathBuf>) -> Self {
        let files = files
            .into_iter()
            .map(|f| {
                let s = stamp(&f);
                (f, s)
            })
            .collect();
        Self {
            files,
            changed_at: None,
        }
    }

    /// Looks at the files at `now`: true once they changed and then stayed unchanged for
    /// `SETTLE`.
    pub fn poll(&mut self, now: Instant) -> bool {
        let mut changed = false;
        for (path, old) in &mut self.files {
            let new = stamp(path);
            if new != *old {
                *old = new;
                changed = true;
            }
        }
        if changed {
            self.changed_at = Some(now);
            return false;
        }
        match self.changed_at {
            Some(at) if now.duration_since(at) >= SETTLE => {
                self.changed_at = None;
                true
            }
            _ => false,
        }
    }
}

/// The watching thread; dropping it stops the thread without waiting for it (it may be in
/// the middle of a long load, which the UI must not wait for).
pub struct Watcher {
    stop: Arc<AtomicBool>,
}

impl Watcher {
    /// Watches `files` (those of `path`'s last load) and calls `loaded` with each new load
    /// of `path`, then watches the files that load read.
    pub fn spawn(
        path: PathBuf,
        files: Vec<PathBuf>,
        frame: Arc<AtomicU32>,
        loaded: impl Fn(SceneLoad) + Send + 'static,
    ) -> std::io::Result<Self> {
        let stop = Arc::new(AtomicBool::new(false));
        let stop_ = stop.clone();
        std::thread::Builder::new()
            .name("prism-watch".into())
            .spawn(move || {
                let mut settle = Settle::new(files);
                while !stop_.load(Ordering::Relaxed) {
                    std::thread::sleep(POLL);
                    if settle.poll(Instant::now()) {
                        let load = load_scene_file_at(&path, frame.load(Ordering::Relaxed));
                        settle = Settle::new(load.files.clone());
                        // A watcher stopped during a long load reports nothing.
                        if !stop_.load(Ordering::Relaxed) {
                            loaded(load);
                        }
                    }
                }
            })?;
        Ok(Self { stop })
    }
}

impl Drop for Watcher {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::mpsc::channel;

    /// A change is reported once, only after the files have been quiet for SETTLE, however
    /// many writes it took; a file that appears counts as a change.
    #[test]
    fn changes_are_reported_once_they_settle() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.toml"), dir.path().join("b.png"));
        std::fs::write(&a, "one").unwrap();
        let mut settle = Settle::new(vec![a.clone(), b.clone()]);
        let t0 = Instant::now();
        assert!(!settle.poll(t0), "nothing changed");
        assert!(!settle.poll(t0 + SETTLE * 2), "still nothing");
        std::fs::write(&a, "two, longer").unwrap();
        let t1 = t0 + SETTLE * 3;
        assert!(!settle.poll(t1), "changed just now: not settled");
        std::fs::write(&a, "three, longer still").unwrap();
        assert!(!settle.poll(t1 + SETTLE / 2), "changed again");
        assert!(!settle.poll(t1 + SETTLE), "quiet for only half of SETTLE");
        assert!(settle.poll(t1 + SETTLE * 2), "settled");
        assert!(!settle.poll(t1 + SETTLE * 3), "reported once");
        std::fs::write(&b, "new").unwrap();
        let t2 = t1 + SETTLE * 4;
        assert!(!settle.poll(t2));
        assert!(settle.poll(t2 + SETTLE), "a file that appeared");
        std::fs::remove_file(&b).unwrap();
        assert!(!settle.poll(t2 + SETTLE * 2));
        assert!(settle.poll(t2 + SETTLE * 3), "a file that went");
    }

    /// The thread loads the scene again after a save, reports a broken file with its error,
    /// and picks up the fix; within half a second of each write.
    #[test]
    fn the_watcher_reloads_after_each_save() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("scene.toml");
        let good = |r: f32| {
            format!(
                "[camera]\neye = [0, 0, 5]\nfov = 40\n[[spheres]]\ncenter = [0, 0, 0]\nradius = {r}\n"
            )
        };
        std::fs::write(&path, good(1.0)).unwrap();
        let first = prism::scene_file::load_scene_file(&path);
        let (tx, rx) = channel();
        let frame = Arc::new(AtomicU32::new(0));
        let _watcher = Watcher::spawn(path.clone(), first.files, frame, move |load| {
            let _ = tx.send(load);
        })
        .unwrap();
        let next = || rx.recv_timeout(Duration::from_secs(5)).expect("a reload");
        // Modification times may be coarse: make each write differ in size as well.
        std::thread::sleep(Duration::from_millis(50));
        std::fs::write(&path, good(2.5)).unwrap();
        let written = Instant::now();
        let load = next();
        assert!(
            written.elapsed() < Duration::from_millis(500),
            "{:?}",
            written.elapsed()
        );
        let scene = load.result.unwrap().scene;
        assert!(matches!(
            scene.objects[0].shape,
            prism::scene::ShapeDesc::Sphere { radius, .. } if radius == 2.5
        ));
        std::fs::write(
            &path,
            "[camera]\neye = [0, 0, 5]\nfov = 40\n[[spheres]]\nradius = 1\n",
        )
        .unwrap();
        let error = next().result.unwrap_err().to_string();
        assert!(
            error.contains("scene.toml") && error.contains("center"),
            "{error}"
        );
        std::fs::write(&path, good(0.75)).unwrap();
        assert!(next().result.is_ok(), "the fix is picked up");
        assert!(rx.try_recv().is_err(), "one load per save");
    }
}
