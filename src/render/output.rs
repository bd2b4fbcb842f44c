//! Writing files (PNGs, the bench's CSV and caches) so that a failed or interrupted write
//! never leaves a broken file: the data goes to a temporary file beside the target, which is
//! renamed over it only when complete. A symbolic link is followed, and its target replaced;
//! a device or FIFO (`/dev/null`, a pipe) is written directly, never replaced.
//!
//! The temporary file exists only while the data is written, not while a render runs, so a
//! process killed mid-render (SIGKILL, out of memory) leaves nothing; one killed in the
//! moment of writing leaves `.NAME.PID-N.tmp`, which the next write of the same file removes
//! once no process of that number runs.

use crate::messages::io_message;
use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};
use thiserror::Error;

/// Why an image cannot be written.
#[derive(Debug, Error)]
pub enum OutputError {
    /// The file cannot be created here.
    #[error("{}: cannot write here: {reason}", crate::messages::shown_path(path))]
    Create {
        /// The file.
        path: PathBuf,
        /// Why, in words.
        reason: String,
    },
    /// Writing it failed part-way (nothing is left behind).
    #[error(
        "{}: failed while writing: {reason}",
        crate::messages::shown_path(path)
    )]
    Write {
        /// The file.
        path: PathBuf,
        /// Why, in words.
        reason: String,
    },
    #[error(
        "{}: the extension names the format: .png, .jpg (or .jpeg), .exr or .pfm (got {})",
        crate::messages::shown_path(path),
        match extension { Some(e) => format!("\".{e}\""), None => "no extension".into() }
    )]
    /// The path's extension names no format prism writes.
    Format {
        /// The file asked for.
        path: PathBuf,
        /// Its extension, if it has one.
        extension: Option<String>,
    },
    /// Options the file's format cannot honour (16 bits in a JPEG, a curve in an EXR).
    #[error("{}: {reason}", crate::messages::shown_path(path))]
    Options {
        /// The file asked for.
        path: PathBuf,
        /// What cannot be done, in words.
        reason: String,
    },
}

/// How a target is written.
enum Target {
    /// A regular file (or none yet): written to a temporary file in `dir` named after
    /// `name`, then renamed onto `real`, the path after following symbolic links.
    Replace {
        real: PathBuf,
        dir: PathBuf,
        name: String,
    },
    /// A device (opened at once, so a refusal comes before the render) or a FIFO (opened
    /// when the data is ready: opening one waits for a reader), written in place.
    Direct(Option<File>),
}

/// A file about to be written: claimed (and so checked for writability) before the render
/// starts, so a bad path fails at once rather than after the work is done.
pub struct PendingFile {
    path: PathBuf,
    target: Target,
}

/// The temporary file of a write in progress: removed when dropped unless renamed.
struct TempFile(PathBuf);

impl TempFile {
    /// A new, empty temporary file for `name` in `dir`, `.NAME.PID-N.tmp`.
    fn create(dir: &Path, name: &str) -> std::io::Result<(Self, File)> {
        static SERIAL: AtomicU64 = AtomicU64::new(0);
        loop {
            let serial = SERIAL.fetch_add(1, Ordering::Relaxed);
            let temp = dir.join(format!(".{name}.{}-{serial}.tmp", std::process::id()));
            let mut options = OpenOptions::new();
            options.write(true).create_new(true);
            // The finished image is an ordinary file, readable like any other.
            #[cfg(unix)]
            std::os::unix::fs::OpenOptionsExt::mode(&mut options, 0o644);
            match options.open(&temp) {
                Ok(file) => {
                    register(&temp);
                    return Ok((Self(temp), file));
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
                Err(e) => return Err(e),
            }
        }
    }

    /// Renames it onto `target`; nothing is left to remove.
    fn rename_onto(self, target: &Path) -> std::io::Result<()> {
        std::fs::rename(&self.0, target)?;
        unregister(&self.0);
        std::mem::forget(self);
        Ok(())
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
        unregister(&self.0);
    }
}

/// The process number in a temporary file's name for `name`, `.NAME.PID-N.tmp`, if it is
/// one.
fn temp_owner(file_name: &str, name: &str) -> Option<u32> {
    let rest = file_name
        .strip_prefix('.')?
        .strip_prefix(name)?
        .strip_prefix('.')?
        .strip_suffix(".tmp")?;
    let (pid, serial) = rest.split_once('-')?;
    let digits = |t: &str| !t.is_empty() && t.bytes().all(|b| b.is_ascii_digit());
    (digits(pid) && digits(serial)).then(|| pid.parse().ok())?
}

/// Removes the temporary files for `name` in `dir` that writers killed mid-write left: those
/// of prism's naming whose process no longer runs. Where a process's liveness cannot be
/// read (no /proc), nothing is removed.
fn remove_stale_temps(dir: &Path, name: &str) {
    if !Path::new("/proc/self").exists() {
        return;
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let file_name = entry.file_name();
        let Some(pid) = file_name.to_str().and_then(|f| temp_owner(f, name)) else {
            continue;
        };
        let is_file = entry.file_type().is_ok_and(|t| t.is_file());
        if is_file && pid != std::process::id() && !Path::new(&format!("/proc/{pid}")).exists() {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// Temporary files not yet renamed into place, for `remove_pending_files`.
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Removes every temporary file a `PendingFile` holds: for a process about to exit on a
/// signal, which runs no destructors.
pub fn remove_pending_files() {
    let pending = PENDING.lock().unwrap_or_else(|e| e.into_inner());
    for temp in pending.iter() {
        let _ = std::fs::remove_file(temp);
    }
}

fn register(temp: &Path) {
    PENDING
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .push(temp.to_path_buf());
}

fn unregister(temp: &Path) {
    PENDING
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .retain(|p| p != temp);
}

/// The path a chain of symbolic links ends at (the path itself when it is none). A link
/// that dangles names the file to create.
fn resolve_links(path: &Path) -> Result<PathBuf, String> {
    let mut current = path.to_path_buf();
    // As many hops as Linux follows before it reports a loop.
    for _ in 0..40 {
        match std::fs::symlink_metadata(&current) {
            Ok(meta) if meta.file_type().is_symlink() => {
                let link = std::fs::read_link(&current).map_err(|e| io_message(&e))?;
                current = match current.parent() {
                    Some(dir) if link.is_relative() => dir.join(link),
                    _ => link,
                };
            }
            _ => return Ok(current),
        }
    }
    Err("too many levels of symbolic links".into())
}

impl PendingFile {
    /// Claims `path`: a temporary file beside it, renamed onto it when finished and removed if the render stops first.
    pub fn create(path: &Path) -> Result<Self, OutputError> {
        let err = |reason: String| OutputError::Create {
            path: path.to_path_buf(),
            reason,
        };
        // Followed through any links, as the kernel will when the file is opened.
        match std::fs::metadata(path) {
            Ok(meta) if meta.is_dir() => return Err(err("the path is a directory".into())),
            Ok(meta) if !meta.is_file() => {
                #[cfg(unix)]
                let fifo = std::os::unix::fs::FileTypeExt::is_fifo(&meta.file_type());
                #[cfg(not(unix))]
                let fifo = false;
                let file = if fifo {
                    None
                } else {
                    let file = OpenOptions::new()
                        .write(true)
                        .open(path)
                        .map_err(|e| err(io_message(&e)))?;
                    Some(file)
                };
                return Ok(Self {
                    path: path.to_path_buf(),
                    target: Target::Direct(file),
                });
            }
            _ => {}
        }
        // A regular file, or none yet: the temporary file goes beside the link's target.
        let real = resolve_links(path).map_err(err)?;
        let Some(name) = real.file_name().map(|n| n.to_string_lossy().into_owned()) else {
            return Err(err("the path names no file".into()));
        };
        let dir = match real.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        match std::fs::metadata(&dir) {
            Ok(meta) if meta.is_dir() => {}
            Ok(_) => {
                return Err(err(format!(
                    "{} is not a directory",
                    crate::messages::shown_path(&dir)
                )));
            }
            Err(e) => {
                return Err(err(format!(
                    "{}: {}",
                    crate::messages::shown_path(&dir),
                    io_message(&e)
                )));
            }
        }
        // A probe, removed at once: the directory must take a new file now, but the one
        // written waits until the data is ready.
        TempFile::create(&dir, &name).map_err(|e| err(io_message(&e)))?;
        Ok(Self {
            path: path.to_path_buf(),
            target: Target::Replace { real, dir, name },
        })
    }

    /// The path that will be written.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Encodes `image` as PNG, then puts the finished file in place.
    pub fn finish_png(self, image: &image::RgbImage) -> Result<PathBuf, OutputError> {
        self.commit(|file| {
            let mut writer = BufWriter::new(file);
            image
                .write_to(&mut writer, image::ImageFormat::Png)
                .map_err(|e| match e {
                    image::ImageError::IoError(e) => io_message(&e),
                    other => other.to_string(),
                })?;
            writer.flush().map_err(|e| io_message(&e))
        })
    }

    /// Writes `bytes`, then puts the finished file in place.
    pub fn finish_bytes(self, bytes: &[u8]) -> Result<PathBuf, OutputError> {
        self.commit(|mut file| file.write_all(bytes).map_err(|e| io_message(&e)))
    }

    /// Fills the file; a temporary one is made durable and renamed over the target.
    pub(super) fn commit(
        self,
        fill: impl FnOnce(&File) -> Result<(), String>,
    ) -> Result<PathBuf, OutputError> {
        let path = self.path.clone();
        let fail = |reason: String| OutputError::Write {
            path: path.clone(),
            reason,
        };
        match &self.target {
            Target::Direct(Some(file)) => fill(file).map_err(fail)?,
            Target::Direct(None) => {
                let file = OpenOptions::new()
                    .write(true)
                    .open(&path)
                    .map_err(|e| fail(io_message(&e)))?;
                fill(&file).map_err(fail)?;
            }
            Target::Replace { real, dir, name } => {
                remove_stale_temps(dir, name);
                let (temp, file) = TempFile::create(dir, name).map_err(|e| fail(io_message(&e)))?;
                fill(&file).map_err(fail)?;
                file.sync_all().map_err(|e| fail(io_message(&e)))?;
                temp.rename_onto(real).map_err(|e| fail(io_message(&e)))?;
            }
        }
        Ok(path)
    }
}

/// Writes `bytes` to `path`, atomically.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<PathBuf, OutputError> {
    PendingFile::create(path)?.finish_bytes(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_and_leaves_no_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.png");
        let img = image::RgbImage::from_pixel(3, 2, image::Rgb([10, 20, 30]));
        PendingFile::create(&path)
            .unwrap()
            .finish_png(&img)
            .unwrap();
        let back = image::open(&path).unwrap().into_rgb8();
        assert_eq!(back, img);
        let files: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(files.len(), 1);
        assert!(
            PENDING
                .lock()
                .unwrap()
                .iter()
                .all(|p| !p.starts_with(dir.path()))
        );
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(&path).unwrap().permissions().mode();
            assert_eq!(mode & 0o777, 0o644, "readable like any other image");
        }
    }

    #[test]
    fn unwritable_paths_fail_before_rendering() {
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("no/such/dir/out.png");
        let e = PendingFile::create(&missing).err().unwrap();
        assert!(e.to_string().contains("no/such/dir/out.png"), "{e}");
        assert!(PendingFile::create(dir.path()).is_err());
    }

    #[test]
    fn bytes_are_written_whole() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("data.csv");
        write_bytes(&path, b"a,b\n1,2\n").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"a,b\n1,2\n");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn nothing_is_on_disk_while_the_render_runs() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.png");
        let pending = PendingFile::create(&path).unwrap();
        // A process killed now (SIGKILL runs no destructor) would leave nothing.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        pending.finish_bytes(b"x").unwrap();
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn stale_temporary_files_of_dead_writers_are_removed() {
        let dir = tempfile::tempdir().unwrap();
        // Above Linux's largest process number: no such process runs.
        let dead = "4294967295";
        let names = [
            format!(".out.png.{dead}-0.tmp"),
            format!(".out.png.{}-77.tmp", std::process::id()),
            format!(".other.png.{dead}-0.tmp"),
            format!(".out.png.{dead}-x.tmp"),
            "out.png.tmp".to_string(),
        ];
        for n in &names {
            std::fs::write(dir.path().join(n), b"left").unwrap();
        }
        write_bytes(&dir.path().join("out.png"), b"new").unwrap();
        let left = |n: &str| dir.path().join(n).exists();
        assert_eq!(left(&names[0]), !Path::new("/proc/self").exists());
        for kept in &names[1..] {
            assert!(left(kept), "{kept} is not a stale file of out.png");
        }
        assert_eq!(temp_owner(".a.png.12-3.tmp", "a.png"), Some(12));
        for not_ours in [
            ".a.png.12.tmp",
            ".a.png.-3.tmp",
            ".b.png.12-3.tmp",
            "a.png.12-3.tmp",
        ] {
            assert_eq!(temp_owner(not_ours, "a.png"), None, "{not_ours}");
        }
    }

    #[test]
    fn abandoned_write_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.png");
        drop(PendingFile::create(&path).unwrap());
        assert!(!path.exists());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }
}
