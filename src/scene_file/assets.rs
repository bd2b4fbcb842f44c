//! Where a scene's files come from (a folder on disk, files embedded in the program, or a
//! folder whose files one animation's frames share), and reading one: bounded, regular files
//! only, in UTF-8.

use super::error::{SceneError, line_column};
use super::read_cache::ReadCache;
use crate::appearance::{ImageTexture, TextureError};
use std::path::{Path, PathBuf};

/// Where the files a scene names (image textures) are found.
#[derive(Clone, Copy, Debug)]
pub enum Assets<'a> {
    /// Paths are relative to this folder (the scene file's own).
    Folder(&'a Path),
    /// As `Folder`, each mesh and image kept in the cache once read, and taken from it
    /// when another validation of the scene (another frame) names it again.
    Cached(&'a Path, &'a ReadCache),
    /// Built into the program: each path as the scene writes it, and the file's bytes.
    Embedded(&'a [(&'a str, &'a [u8])]),
}

impl<'a> Assets<'a> {
    /// What `rel` names, for messages and to recognise a file named twice.
    pub(super) fn locate(&self, rel: &str) -> PathBuf {
        match self {
            Assets::Folder(dir) | Assets::Cached(dir, _) => dir.join(rel),
            Assets::Embedded(_) => PathBuf::from(rel),
        }
    }

    /// Whether the files are read from disk (and so watched).
    pub(super) fn on_disk(&self) -> bool {
        matches!(self, Assets::Folder(_) | Assets::Cached(..))
    }

    /// The cache files are kept in, if any.
    pub(super) fn cache(&self) -> Option<&'a ReadCache> {
        match self {
            Assets::Cached(_, cache) => Some(cache),
            _ => None,
        }
    }

    /// These assets with files kept in `cache`, where they are read from disk.
    pub(super) fn cached_in(self, cache: &'a ReadCache) -> Assets<'a> {
        match self {
            Assets::Folder(dir) | Assets::Cached(dir, _) => Assets::Cached(dir, cache),
            embedded => embedded,
        }
    }

    pub(super) fn embedded(&self, rel: &str) -> Option<Result<&[u8], TextureError>> {
        match self {
            Assets::Folder(_) | Assets::Cached(..) => None,
            Assets::Embedded(files) => Some(
                files
                    .iter()
                    .find(|(name, _)| *name == rel)
                    .map(|(_, bytes)| *bytes)
                    .ok_or_else(|| TextureError::Io("no such built-in file".into())),
            ),
        }
    }

    /// The size image `rel` declares, from its header.
    pub(super) fn probe(&self, rel: &str) -> Result<(u32, u32), TextureError> {
        match self.embedded(rel) {
            None => ImageTexture::probe(&self.locate(rel)),
            Some(bytes) => ImageTexture::probe_bytes(bytes?),
        }
    }

    /// Image `rel`, decoded.
    pub(super) fn load(&self, rel: &str) -> Result<ImageTexture, TextureError> {
        match self.embedded(rel) {
            None => ImageTexture::load(&self.locate(rel)),
            Some(bytes) => ImageTexture::decode(bytes?),
        }
    }
}

/// `rel`'s folder joined to `name`: how a file the scene names names its own files (an
/// OBJ its MTL, an MTL its images, a glTF file its buffers and images).
pub(super) fn beside(rel: &str, name: &str) -> String {
    match Path::new(rel).parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir.join(name).to_string_lossy().into_owned(),
        _ => name.to_string(),
    }
}

/// The text of the file at `path`, `what` (a scene file, a mesh file): a regular file of at
/// most `max` bytes, in UTF-8.
pub(super) fn read_text_file(path: &Path, max: u64, what: &str) -> Result<String, SceneError> {
    let bytes = read_file(path, max, what)?;
    String::from_utf8(bytes).map_err(|e| {
        let valid = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        let text = std::str::from_utf8(valid).unwrap_or_default();
        let (line, column) = line_column(text, text.len());
        SceneError::Syntax {
            path: path.to_path_buf(),
            line,
            column,
            message: "the text is not valid UTF-8 here".into(),
        }
    })
}

/// The bytes of the file at `path`, `what` (a mesh file, a glTF buffer): a regular file of
/// at most `max` bytes.
pub(super) fn read_file(path: &Path, max: u64, what: &str) -> Result<Vec<u8>, SceneError> {
    use crate::messages::io_message;
    use std::io::Read;
    let fail = |reason: String| SceneError::Read {
        path: path.to_path_buf(),
        reason,
    };
    let meta =
        std::fs::metadata(path).map_err(|e| fail(crate::messages::read_failure(path, &e)))?;
    if meta.is_dir() {
        return Err(fail("it is a directory".into()));
    }
    if !meta.is_file() {
        // A FIFO would block until written to, a device might never end.
        return Err(fail("it is not a regular file".into()));
    }
    let too_large = || {
        fail(format!(
            "it is larger than the {} MiB a {what} may be",
            max >> 20
        ))
    };
    if meta.len() > max {
        return Err(too_large());
    }
    let file = std::fs::File::open(path).map_err(|e| fail(io_message(&e)))?;
    // The file may grow between the check and the read: read no more than the limit.
    // Its size is reserved: `take` gives no size hint, so the buffer would otherwise grow
    // by doubling, copying and touching fresh pages each time.
    let mut bytes = Vec::with_capacity(meta.len() as usize + 1);
    file.take(max + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| fail(io_message(&e)))?;
    if bytes.len() as u64 > max {
        return Err(too_large());
    }
    Ok(bytes)
}
