//! What the test suites share: running the `prism` binary, a temporary folder, the seed
//! scene, and a scene rendered to 8-bit RGB in memory. Each suite declares `mod common;`
//! and uses the part it needs (so some of it is unused in any one suite).
#![allow(dead_code)]

pub mod gltf;
pub mod povray;

use prism::camera::Camera;
use prism::render::{self, RenderSettings};
use prism::scene::{PreparedScene, Scene};
use std::path::PathBuf;
use std::process::{Command, Output, Stdio};
use std::sync::Arc;

/// Runs the `prism` binary under test with `args` (no input on stdin) to its end.
pub fn prism(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_prism"))
        .args(args)
        .stdin(Stdio::null())
        .output()
        .expect("prism runs")
}

/// The example scenes in assets/scenes, in name order.
pub fn example_scenes() -> Vec<PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
    let mut paths: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    paths.sort();
    assert!(paths.len() >= 20, "{} scenes", paths.len());
    paths
}

/// What a run said on stderr.
pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// The variable that lets a test whose tool is missing skip, saying so.
pub const SKIP_MISSING_TOOLS: &str = "PRISM_SKIP_MISSING_TOOLS";

/// Whether `tool` is a command on PATH.
pub fn on_path(tool: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {tool}")])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Whether every one of `tools` is here for `what` (a check that runs them). A missing
/// one fails the test (`.ci/run` installs them all) unless PRISM_SKIP_MISSING_TOOLS is set:
/// then the test says it skipped and returns. A skip is asked for, never silent.
pub fn tools_present(what: &str, tools: &[&str]) -> bool {
    let missing: Vec<&str> = tools.iter().copied().filter(|t| !on_path(t)).collect();
    if missing.is_empty() {
        return true;
    }
    assert!(
        std::env::var_os(SKIP_MISSING_TOOLS).is_some(),
        "{what} needs {missing:?}, not installed here: run .ci/run, which installs them, \
         or set {SKIP_MISSING_TOOLS}=1 to skip it"
    );
    eprintln!("skipped {what}: {missing:?} not installed ({SKIP_MISSING_TOOLS} is set)");
    false
}

/// The seed scene, as the binary builds it in.
pub fn seed() -> Scene {
    prism::seed::scene().expect("the seed scene loads")
}

/// `prepared` seen from `camera` with `settings`, rendered to convergence, as 8-bit RGB.
pub fn render_prepared(
    prepared: Arc<PreparedScene>,
    camera: Camera,
    settings: RenderSettings,
) -> image::RgbImage {
    render::render(prepared, camera, settings, |_, _| {})
        .accumulator()
        .to_rgb8()
}

/// `scene` from its own camera with `settings`, rendered to convergence, as 8-bit RGB.
pub fn render_scene(scene: &Scene, settings: RenderSettings) -> image::RgbImage {
    render_prepared(Arc::new(PreparedScene::new(scene)), scene.camera, settings)
}

/// The colour one primary ray from `from` (world coordinates) along `dir` brings back in
/// `scene` (subsample 0 of pixel 0).
pub fn colour_along(scene: &Scene, from: glam::Vec3, dir: glam::Vec3) -> glam::Vec3 {
    let prepared = PreparedScene::new(scene);
    let origin = from - scene.origin.as_vec3();
    prism::integrator::Integrator::new(&prepared, 0.0)
        .trace_primary(
            prism::accel::Reach::After(0.0),
            || prism::geometry::Ray::new(origin, dir.normalize()),
            prism::sampler::SampleStream::new(0, 0, 0),
        )
        .color
}

/// A temporary folder, removed with everything in it when dropped.
pub struct Dir(pub tempfile::TempDir);

impl Dir {
    pub fn new() -> Self {
        Self(tempfile::tempdir().expect("a temporary folder"))
    }

    /// The path of `name` in it.
    pub fn path(&self, name: &str) -> PathBuf {
        self.0.path().join(name)
    }

    /// The path of `name` in it, as a string for a command line.
    pub fn s(&self, name: &str) -> String {
        self.path(name).to_str().unwrap().to_string()
    }

    /// Writes `text` to `name` in it; its path.
    pub fn write(&self, name: &str, text: &str) -> PathBuf {
        let p = self.path(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    /// The names in it, sorted.
    pub fn files(&self) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(self.0.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    /// The names in it other than `keep`, sorted.
    pub fn others(&self, keep: &[&str]) -> Vec<String> {
        self.files()
            .into_iter()
            .filter(|n| !keep.contains(&n.as_str()))
            .collect()
    }
}
