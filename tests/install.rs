//! An installed prism needs nothing of the source tree: `cargo install --path . --root DIR`
//! from a copy of the tree, the copy deleted, and `DIR/bin/prism render` run from another
//! folder draws the seed scene exactly as the binary under test does.
//!
//! The install builds in a copy of this build's target folder (its dependencies, already
//! compiled), so only prism itself is compiled again and the binary under test is untouched.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The files a package needs to build: the manifest, the lock file and the targets it
/// names (the library, the binary and the bench), and the assets the library embeds.
const PACKAGE: &[&str] = &["Cargo.toml", "Cargo.lock", "src", "assets", "benches"];

fn copy_tree(from: &Path, to: &Path) {
    if from.is_dir() {
        std::fs::create_dir_all(to).unwrap();
        for entry in std::fs::read_dir(from).unwrap() {
            let entry = entry.unwrap();
            copy_tree(&entry.path(), &to.join(entry.file_name()));
        }
    } else {
        std::fs::copy(from, to).unwrap();
    }
}

/// A new target folder at `to` holding the release dependencies compiled so far.
fn seeded_target_dir(to: &Path) -> PathBuf {
    // The binary under test is …/target/<profile>/prism.
    let exe = Path::new(env!("CARGO_BIN_EXE_prism"));
    let target = exe.parent().and_then(Path::parent).unwrap();
    let release = to.join("release");
    std::fs::create_dir_all(&release).unwrap();
    for part in ["deps", "build", ".fingerprint"] {
        let from = target.join("release").join(part);
        if from.is_dir() {
            let status = Command::new("cp")
                .arg("-a")
                .arg(&from)
                .arg(&release)
                .status()
                .expect("cp runs");
            assert!(status.success(), "copying {}", from.display());
        }
    }
    to.to_path_buf()
}

fn render_seed(prism: &Path, cwd: &Path, out: &str) {
    let status = Command::new(prism)
        .args([
            "render", "--width", "96", "--height", "72", "--aa", "2", "--quiet",
        ])
        .args(["--out", out])
        .current_dir(cwd)
        .status()
        .expect("prism runs");
    assert!(status.success(), "{} render failed", prism.display());
}

#[test]
fn an_installed_prism_renders_the_seed_scene_without_the_source_tree() {
    let work = tempfile::tempdir().unwrap();
    let source = work.path().join("source");
    let root = work.path().join("root");
    let elsewhere = work.path().join("elsewhere");
    std::fs::create_dir_all(&elsewhere).unwrap();
    std::fs::create_dir_all(&source).unwrap();
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    for item in PACKAGE {
        copy_tree(&manifest.join(item), &source.join(item));
    }
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let installed = Command::new(cargo)
        .args(["install", "--locked", "--offline", "--quiet", "--path"])
        .arg(&source)
        .arg("--root")
        .arg(&root)
        .arg("--target-dir")
        .arg(seeded_target_dir(&work.path().join("target")))
        .status()
        .expect("cargo runs");
    assert!(installed.success(), "cargo install failed");
    std::fs::remove_dir_all(&source).unwrap();

    let prism = root.join("bin/prism");
    render_seed(&prism, &elsewhere, "installed.png");
    render_seed(
        Path::new(env!("CARGO_BIN_EXE_prism")),
        &elsewhere,
        "tested.png",
    );
    let installed = std::fs::read(elsewhere.join("installed.png")).unwrap();
    let tested = std::fs::read(elsewhere.join("tested.png")).unwrap();
    assert!(installed.len() > 1000);
    assert_eq!(installed, tested, "the installed prism draws another image");
}
