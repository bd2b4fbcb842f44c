//! Writing files (PNGs, the bench's CSV and caches) so that a failed or interrupted write
//! never leaves a broken file: the data goes to a temporary file beside the target, which is
//! renamed over it only when complete.

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use thiserror::Error;

#[derive(Debug, Error)]
pub enum OutputError {
    #[error("{}: cannot write here: {source}", path.display())]
    Create {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("{}: failed while writing: {reason}", path.display())]
    Write { path: PathBuf, reason: String },
}

/// A file about to be written: created (and so checked for writability) before the render
/// starts, so a bad path fails at once rather than after the work is done.
pub struct PendingFile {
    path: PathBuf,
    temp: tempfile::NamedTempFile,
}

impl PendingFile {
    pub fn create(path: &Path) -> Result<Self, OutputError> {
        let dir = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
        let err = |source| OutputError::Create {
            path: path.to_path_buf(),
            source,
        };
        let Some(name) = name else {
            return Err(err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "the path names no file",
            )));
        };
        if path.is_dir() {
            return Err(err(std::io::Error::new(
                std::io::ErrorKind::IsADirectory,
                "the path is a directory",
            )));
        }
        let prefix = format!(".{name}.");
        let mut builder = tempfile::Builder::new();
        builder.prefix(&prefix).suffix(".tmp");
        // Temporary files are private by default; the finished image is an ordinary file.
        #[cfg(unix)]
        builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o644));
        let temp = builder.tempfile_in(dir).map_err(err)?;
        Ok(Self {
            path: path.to_path_buf(),
            temp,
        })
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Encodes `image` as PNG, then renames the finished file into place.
    pub fn finish_png(self, image: &image::RgbImage) -> Result<PathBuf, OutputError> {
        self.commit(|file| {
            let mut writer = BufWriter::new(file);
            image
                .write_to(&mut writer, image::ImageFormat::Png)
                .map_err(|e| e.to_string())?;
            writer.flush().map_err(|e| e.to_string())
        })
    }

    /// Writes `bytes`, then renames the finished file into place.
    pub fn finish_bytes(self, bytes: &[u8]) -> Result<PathBuf, OutputError> {
        self.commit(|mut file| file.write_all(bytes).map_err(|e| e.to_string()))
    }

    /// Fills the temporary file, makes it durable, and renames it over the target.
    fn commit(
        self,
        fill: impl FnOnce(&std::fs::File) -> Result<(), String>,
    ) -> Result<PathBuf, OutputError> {
        let path = self.path;
        let fail = |reason: String| OutputError::Write {
            path: path.clone(),
            reason,
        };
        fill(self.temp.as_file()).map_err(fail)?;
        self.temp
            .as_file()
            .sync_all()
            .map_err(|e| fail(e.to_string()))?;
        self.temp
            .persist(&path)
            .map_err(|e| fail(e.error.to_string()))?;
        Ok(path)
    }
}

/// Writes `image` to `path` as a PNG, atomically.
pub fn write_png(path: &Path, image: &image::RgbImage) -> Result<PathBuf, OutputError> {
    PendingFile::create(path)?.finish_png(image)
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
        write_png(&path, &img).unwrap();
        let back = image::open(&path).unwrap().into_rgb8();
        assert_eq!(back, img);
        let files: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(files.len(), 1);
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
    fn abandoned_write_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.png");
        drop(PendingFile::create(&path).unwrap());
        assert!(!path.exists());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }
}
