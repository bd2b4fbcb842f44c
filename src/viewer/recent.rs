//! The scene files opened lately, newest first, kept between runs in the user's
//! configuration folder (`$XDG_CONFIG_HOME/prism/recent`, else `~/.config/prism/recent`),
//! one path per line. The list is a convenience: a folder that cannot be written leaves it
//! to this run.

use std::path::{Path, PathBuf};

/// The most files the list keeps.
pub const MAX_RECENT: usize = 8;

/// Where the list is kept, if the environment names a home.
pub fn list_path() -> Option<PathBuf> {
    let config = std::env::var_os("XDG_CONFIG_HOME")
        .filter(|v| !v.is_empty())
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".config")))?;
    Some(config.join("prism").join("recent"))
}

/// The list kept at `at` (empty when there is none); files that no longer exist are left out.
pub fn read(at: &Path) -> Vec<PathBuf> {
    let text = std::fs::read_to_string(at).unwrap_or_default();
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(PathBuf::from)
        .filter(|p| p.is_file())
        .take(MAX_RECENT)
        .collect()
}

/// `list` with `opened` first (once), at most `MAX_RECENT` long.
pub fn with_opened(list: &[PathBuf], opened: &Path) -> Vec<PathBuf> {
    let opened = std::fs::canonicalize(opened).unwrap_or_else(|_| opened.to_path_buf());
    std::iter::once(opened.clone())
        .chain(list.iter().filter(|p| **p != opened).cloned())
        .take(MAX_RECENT)
        .collect()
}

/// `list` with `opened` first, kept for the next run where `list_path` says (a folder that
/// cannot be written leaves the list to this run).
pub fn remember(list: &[PathBuf], opened: &Path) -> Vec<PathBuf> {
    let list = with_opened(list, opened);
    if let Some(at) = list_path() {
        let _ = write(&at, &list);
    }
    list
}

/// Keeps `list` at `at`, through a temporary file renamed over the old list.
pub fn write(at: &Path, list: &[PathBuf]) -> std::io::Result<()> {
    if let Some(dir) = at.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let text: String = list.iter().map(|p| format!("{}\n", p.display())).collect();
    prism::render::write_bytes(at, text.as_bytes())
        .map(|_| ())
        .map_err(|e| std::io::Error::other(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_list_keeps_the_newest_first_once_and_survives_a_restart() {
        let dir = tempfile::tempdir().unwrap();
        let files: Vec<PathBuf> = (0..MAX_RECENT + 2)
            .map(|i| {
                let p = dir.path().join(format!("s{i}.toml"));
                std::fs::write(&p, "").unwrap();
                p.canonicalize().unwrap()
            })
            .collect();
        let mut list = Vec::new();
        for f in &files {
            list = with_opened(&list, f);
        }
        assert_eq!(list.len(), MAX_RECENT);
        assert_eq!(list[0], files[MAX_RECENT + 1]);
        list = with_opened(&list, &files[5]);
        assert_eq!(list[0], files[5]);
        assert_eq!(list.iter().filter(|p| **p == files[5]).count(), 1);
        let at = dir.path().join("config/prism/recent");
        write(&at, &list).unwrap();
        assert_eq!(read(&at), list);
        std::fs::remove_file(&files[5]).unwrap();
        assert!(
            !read(&at).contains(&files[5]),
            "a file that went is left out"
        );
        assert!(read(&dir.path().join("none")).is_empty());
    }
}
