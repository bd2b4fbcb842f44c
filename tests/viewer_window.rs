//! The viewer in a real window under Xvfb, driven by xdotool (tests/window/e2e.sh): the
//! screenshot key saves exactly what `prism render` makes with the same settings, a camera
//! key restarts accumulation, a window narrower than the panel breaks nothing, and Ctrl+Q
//! closes the window (with the keyboard focus in the panel too) and ends the render thread.
//! tests/window/panic.sh checks that a panic in the render thread is shown and reported.
//!
//! Needs xvfb-run, xdotool and ImageMagick (`.ci/run` installs them). Without them the test
//! says so and passes, unless PRISM_REQUIRE_WINDOW_TEST is set, as it is in CI.

use prism::render::fraction_differing as differing;
use std::path::{Path, PathBuf};
use std::process::Command;

fn have(tool: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {tool}")])
        .output()
        .is_ok_and(|o| o.status.success())
}

fn shots(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "png"))
        .collect();
    v.sort();
    v
}

/// Runs tests/window/SCRIPT with prism and the work folder, on a virtual screen.
fn under_xvfb(script: &str, work: &Path) -> std::process::Output {
    let script = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/window")
        .join(script);
    Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x800x24"])
        .arg(&script)
        .arg(env!("CARGO_BIN_EXE_prism"))
        .arg(work)
        .output()
        .unwrap()
}

/// Whether the window tools are here; without them the test is skipped, unless it is
/// required.
fn window_tools() -> bool {
    let required = std::env::var_os("PRISM_REQUIRE_WINDOW_TEST").is_some();
    let missing: Vec<&str> = ["xvfb-run", "xdotool", "import"]
        .into_iter()
        .filter(|t| !have(t))
        .collect();
    if !missing.is_empty() {
        assert!(!required, "the window test needs {missing:?}: run .ci/run");
        eprintln!("skipping the window test: {missing:?} not installed (see docs/testing.md)");
        return false;
    }
    true
}

#[cfg(feature = "viewer")]
#[test]
fn viewer_window_end_to_end() {
    if !window_tools() {
        return;
    }
    let work = tempfile::tempdir().unwrap();
    let out = under_xvfb("e2e.sh", work.path());
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    let log = std::fs::read_to_string(work.path().join("viewer.log")).unwrap_or_default();
    assert!(
        out.status.success(),
        "e2e.sh failed\nstdout: {stdout}\nstderr: {stderr}\nviewer log: {log}"
    );
    assert!(stdout.contains("viewer exited cleanly"), "{stdout}");

    let taken = shots(&work.path().join("shots"));
    assert_eq!(taken.len(), 2, "{taken:?}");
    for shot in &taken {
        let name = shot.file_name().unwrap().to_string_lossy();
        assert!(
            name.starts_with("prism-20") && name.ends_with("-4spp.png"),
            "{name}"
        );
    }
    let first = image::open(&taken[0]).unwrap().into_rgb8();
    let second = image::open(&taken[1]).unwrap().into_rgb8();
    assert_eq!(
        first.dimensions(),
        (320, 240),
        "the image area, without the panel"
    );

    // The same settings headless.
    let reference = work.path().join("reference.png");
    let render = Command::new(env!("CARGO_BIN_EXE_prism"))
        .args([
            "render", "--width", "320", "--height", "240", "--aa", "2", "--quiet",
        ])
        .arg("--out")
        .arg(&reference)
        .output()
        .unwrap();
    assert!(render.status.success());
    let reference = image::open(&reference).unwrap().into_rgb8();
    let off = differing(&first, &reference, 1);
    assert!(
        off < 0.001,
        "{:.4}% of pixels differ from prism render",
        off * 100.0
    );

    // Flying forward restarted accumulation and changed the view.
    let moved = differing(&second, &first, 8);
    assert!(
        moved > 0.05,
        "only {:.2}% of pixels changed after W",
        moved * 100.0
    );

    // The whole screen shows the panel (not black) beside the image.
    let screen = image::open(work.path().join("screen.png"))
        .unwrap()
        .into_rgb8();
    let panel_pixel = screen.get_pixel(150, 120);
    assert!(
        panel_pixel.0.iter().any(|&c| c > 10),
        "panel missing: {panel_pixel:?}"
    );
    assert!(!log.contains("panicked"), "{log}");
}

#[cfg(feature = "viewer")]
#[test]
fn a_panic_in_the_render_thread_is_shown_and_reported() {
    if !window_tools() {
        return;
    }
    let work = tempfile::tempdir().unwrap();
    let out = under_xvfb("panic.sh", work.path());
    let stdout = String::from_utf8_lossy(&out.stdout);
    let log = std::fs::read_to_string(work.path().join("viewer.log")).unwrap_or_default();
    assert!(
        out.status.success(),
        "panic.sh failed\n{stdout}\nviewer log: {log}"
    );
    assert!(stdout.contains("viewer exited with 1"), "{stdout}\n{log}");
    assert!(log.contains("PRISM_INJECT_PANIC"), "{log}");
    // The panel shows the failure in red: some strongly red pixels in the panel.
    let screen = image::open(work.path().join("panic.png"))
        .unwrap()
        .into_rgb8();
    let red = (0..300)
        .flat_map(|x| (0..240).map(move |y| (x, y)))
        .filter(|&(x, y)| {
            let [r, g, b] = screen.get_pixel(x, y).0;
            r > 150 && g < 120 && b < 120
        })
        .count();
    assert!(red > 20, "no red error text in the panel ({red} pixels)");
}
