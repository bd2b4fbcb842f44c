//! The files a render reads and writes, checked before any work: no output may land on an
//! input (the scene, a mesh, a material library, a texture) or on another output of the
//! same command (`-o img.png --stats-json img.png`), and an output's missing folders are
//! made, as a user who names `frames/shot_{frame:04}.png` in a fresh folder expects.

use super::render_args::BadOption;
use anyhow::{Result, bail};
use prism::messages::{io_message, shown_path};
use prism::render::OutputError;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// What makes two paths one file: for a file that exists, its device and inode (so a link
/// or a `./` finds it); for one to be made, the path with its folders resolved.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum Identity {
    #[cfg(unix)]
    Inode(u64, u64),
    Path(PathBuf),
}

fn identity(path: &Path) -> Identity {
    #[cfg(unix)]
    if let Ok(meta) = std::fs::metadata(path) {
        use std::os::unix::fs::MetadataExt;
        return Identity::Inode(meta.dev(), meta.ino());
    }
    Identity::Path(resolved(path))
}

/// `path` made absolute, its deepest existing folder resolved through links and the rest
/// taken as written, without `.` and with `..` applied.
fn resolved(path: &Path) -> PathBuf {
    let clean = prism::messages::absolute_as_written(path);
    let mut existing = clean.as_path();
    let mut rest = Vec::new();
    while !existing.exists() {
        match (existing.parent(), existing.file_name()) {
            (Some(parent), Some(name)) => {
                rest.push(name.to_os_string());
                existing = parent;
            }
            _ => break,
        }
    }
    let mut out = existing
        .canonicalize()
        .unwrap_or_else(|_| existing.to_path_buf());
    out.extend(rest.iter().rev());
    out
}

/// The files of one command, each with what it is, in words.
#[derive(Default)]
pub struct FileRoles {
    known: HashMap<Identity, String>,
}

impl FileRoles {
    /// The files the scene reads (the scene file first).
    pub fn with_inputs(files: &[PathBuf]) -> Self {
        let mut roles = Self::default();
        for (i, file) in files.iter().enumerate() {
            let what = match i {
                0 => format!("the scene file {}", shown_path(file)),
                _ => format!("{}, which the scene reads", shown_path(file)),
            };
            roles.known.entry(identity(file)).or_insert(what);
        }
        roles
    }

    /// Records `path`, which `flag` writes as `what`, refusing it when it is an input or
    /// another output.
    pub fn claim(&mut self, flag: &str, path: &Path, what: String) -> Result<()> {
        let id = identity(path);
        if let Some(other) = self.known.get(&id) {
            bail!(BadOption(format!(
                "{flag} {}: that is {other}; writing {what} there would overwrite it (give \
                 the output a name of its own)",
                shown_path(path)
            )));
        }
        self.known.insert(id, what);
        Ok(())
    }
}

/// Makes the missing folders of `path`'s parent, saying so on stderr unless `quiet`.
pub fn create_parent_folders(path: &Path, quiet: bool) -> Result<()> {
    let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) else {
        return Ok(());
    };
    if parent.is_dir() {
        return Ok(());
    }
    std::fs::create_dir_all(parent).map_err(|e| OutputError::Create {
        path: path.to_path_buf(),
        reason: format!(
            "cannot make its folder {}: {}",
            shown_path(parent),
            io_message(&e)
        ),
    })?;
    if !quiet {
        eprintln!("made the folder {}", shown_path(parent));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_output_on_an_input_or_on_another_output_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let scene = dir.path().join("scene.toml");
        let mesh = dir.path().join("mesh.obj");
        std::fs::write(&scene, "").unwrap();
        std::fs::write(&mesh, "").unwrap();
        let mut roles = FileRoles::with_inputs(&[scene.clone(), mesh.clone()]);
        let e = roles
            .claim("--stats-json", &scene, "the statistics".into())
            .unwrap_err();
        assert!(e.to_string().contains("the scene file"), "{e}");
        // The same file by another spelling.
        let other = dir.path().join("sub/../mesh.obj");
        std::fs::create_dir(dir.path().join("sub")).unwrap();
        let e = roles.claim("-o", &other, "the image".into()).unwrap_err();
        assert!(e.to_string().contains("which the scene reads"), "{e}");
        #[cfg(unix)]
        {
            let link = dir.path().join("link.toml");
            std::os::unix::fs::symlink(&scene, &link).unwrap();
            assert!(roles.claim("-o", &link, "the image".into()).is_err());
        }
        // Files that do not exist yet collide by their resolved path.
        let image = dir.path().join("img.png");
        roles.claim("-o", &image, "the image".into()).unwrap();
        let e = roles
            .claim(
                "--stats-json",
                &dir.path().join("./sub/../img.png"),
                "s".into(),
            )
            .unwrap_err();
        assert!(e.to_string().contains("the image"), "{e}");
        roles
            .claim("--stats-json", &dir.path().join("img.json"), "s".into())
            .unwrap();
    }

    #[test]
    fn missing_folders_are_made() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("frames/a/shot_0001.png");
        create_parent_folders(&path, true).unwrap();
        assert!(dir.path().join("frames/a").is_dir());
        create_parent_folders(Path::new("plain.png"), true).unwrap();
        let file = dir.path().join("file");
        std::fs::write(&file, "").unwrap();
        assert!(create_parent_folders(&file.join("x/y.png"), true).is_err());
    }
}
