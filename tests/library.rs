//! The library stands apart from the binary: built without the default features it pulls in
//! none of the command line's, the viewer's or the bench's dependencies.

use std::process::Command;

/// The crates the command line, the bench and the viewer bring, none of which the tracer
/// itself needs. (`serde_json` is not among them: the glTF reader's parser uses it.)
const BINARY_ONLY: &[&str] = &[
    "anyhow",
    "clap",
    "indicatif",
    "signal-hook",
    "nv-flip",
    "plotters",
    "winit",
    "pixels",
    "egui",
    "egui_plot",
    "libc",
    "oidn",
];

/// The names of the normal (not dev or build) dependencies of the library, with `features`.
fn dependencies(features: &[&str]) -> Vec<String> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let output = Command::new(cargo)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args([
            "tree",
            "--offline",
            "--locked",
            "--edges",
            "normal",
            "--prefix",
            "none",
        ])
        .args(["--format", "{p}"])
        .args(features)
        .output()
        .expect("cargo runs");
    // Offline, so that the test never reaches the network: `cargo fetch` (which .ci/run
    // runs first) puts every crate of the lock file in cargo's cache.
    assert!(
        output.status.success(),
        "cargo tree {features:?} failed (has `cargo fetch` been run?):\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout)
        .unwrap()
        .lines()
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .collect()
}

#[test]
fn the_library_builds_without_the_binary_dependencies() {
    let library = dependencies(&["--no-default-features"]);
    assert!(library.iter().any(|d| d == "rayon"), "{library:?}");
    for name in BINARY_ONLY {
        assert!(
            !library.iter().any(|d| d == name),
            "the library needs {name}"
        );
    }
    // With the default features and the denoiser they are all there: the test can tell the
    // difference.
    let everything = dependencies(&["--features", "denoise"]);
    for name in BINARY_ONLY {
        assert!(everything.iter().any(|d| d == name), "{name} is gone");
    }
}
