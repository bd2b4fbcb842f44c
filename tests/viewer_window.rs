//! The viewer in a real window under Xvfb, driven by xdotool (tests/window/e2e.sh): the
//! screenshot key saves exactly what `prism render` makes with the same settings, a camera
//! key restarts accumulation, a window narrower than the panel breaks nothing, and Ctrl+Q
//! closes the window (with the keyboard focus in the panel too) and ends the render thread.
//! tests/window/panic.sh checks that a panic in the render thread is shown and reported, and
//! tests/window/focus.sh that a click focuses the lens, and tests/window/edit.sh picking,
//! editing, saving and reloading, tests/window/broken_start.sh a scene that fails at start,
//! and tests/window/animation.sh stepping through an animation's frames.
//!
//! Needs xvfb-run, xdotool and ImageMagick (`.ci/run` installs them). Without them the test
//! fails, unless PRISM_SKIP_MISSING_TOOLS is set, when it says it skipped.

#![cfg(feature = "viewer")]

mod common;

use prism::render::fraction_differing as differing;
use std::path::{Path, PathBuf};
use std::process::Command;

fn shots(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "png"))
        .collect();
    v.sort();
    v
}

/// Runs tests/window/SCRIPT with prism and the work folder, on a virtual screen. One at a
/// time: two `xvfb-run -a` started together can pick the same display number. A run whose
/// viewer could not reach its X server (a display that was still being torn down) is
/// tried once more.
fn under_xvfb(script: &str, work: &Path) -> std::process::Output {
    static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let script = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/window")
        .join(script);
    let run = || {
        Command::new("xvfb-run")
            .args(["-a", "-s", "-screen 0 1280x800x24"])
            .arg(&script)
            .arg(env!("CARGO_BIN_EXE_prism"))
            .arg(work)
            .output()
            .unwrap()
    };
    let out = run();
    let log = std::fs::read_to_string(work.join("viewer.log")).unwrap_or_default();
    if !out.status.success() && log.contains("Failed to open connection to X server") {
        eprintln!("the viewer found no X server; trying once more");
        let _ = std::fs::remove_dir_all(work.join("shots"));
        return run();
    }
    out
}

/// What a window script left: its standard output and the viewer's log.
struct Ran {
    stdout: String,
    log: String,
}

/// Runs tests/window/SCRIPT under Xvfb (`under_xvfb`) and asserts that it succeeded.
fn run_script(script: &str, work: &Path) -> Ran {
    let out = under_xvfb(script, work);
    let ran = Ran {
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        log: std::fs::read_to_string(work.join("viewer.log")).unwrap_or_default(),
    };
    assert!(
        out.status.success(),
        "{script} failed\nstdout: {}\nstderr: {}\nviewer log: {}",
        ran.stdout,
        String::from_utf8_lossy(&out.stderr),
        ran.log
    );
    ran
}

/// `prism render` of the scene TEXT, written to WORK/NAME, at the edit scripts' window size.
fn render_text(work: &Path, name: &str, text: &str) -> image::RgbImage {
    let path = work.join(name);
    std::fs::write(&path, text).unwrap();
    let path = path.to_string_lossy().into_owned();
    render_headless(work, &[&path, "--width", "320", "--height", "700"])
}

/// How many strongly red pixels (the panel's error text) the screenshot at `path` has in
/// the panel's top `rows` rows.
fn red_pixels(path: &Path, rows: u32) -> usize {
    let screen = image::open(path).unwrap().into_rgb8();
    (0..300)
        .flat_map(|x| (0..rows).map(move |y| (x, y)))
        .filter(|&(x, y)| {
            let [r, g, b] = screen.get_pixel(x, y).0;
            r > 150 && g < 120 && b < 120
        })
        .count()
}

/// `prism render ARGS` into a file in `work`, read back.
fn render_headless(work: &Path, args: &[&str]) -> image::RgbImage {
    let out = work.join("headless.png");
    let render = Command::new(env!("CARGO_BIN_EXE_prism"))
        .arg("render")
        .args(args)
        .args(["--quiet", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        render.status.success(),
        "{}",
        String::from_utf8_lossy(&render.stderr)
    );
    image::open(&out).unwrap().into_rgb8()
}

/// Whether the window tools are here (common::tools_present: without them the test
/// fails, unless skipping is asked for).
fn window_tools() -> bool {
    common::tools_present("the window test", &["xvfb-run", "xdotool", "import"])
}

#[test]
fn viewer_window_end_to_end() {
    if !window_tools() {
        return;
    }
    let work = tempfile::tempdir().unwrap();
    let Ran { stdout, log } = run_script("e2e.sh", work.path());
    assert!(stdout.contains("viewer exited cleanly"), "{stdout}");

    let taken = shots(&work.path().join("shots"));
    assert_eq!(taken.len(), 3, "{taken:?}");
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
    let reference = render_headless(
        work.path(),
        &["--width", "320", "--height", "240", "--aa", "2"],
    );
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

    // A tap of D (shorter than a frame) moved the camera a step.
    let third = image::open(&taken[2]).unwrap().into_rgb8();
    let tapped = differing(&third, &second, 8);
    assert!(
        tapped > 0.01,
        "only {:.2}% of pixels changed after a tap of D",
        tapped * 100.0
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

#[test]
fn a_panic_in_the_render_thread_is_shown_and_reported() {
    if !window_tools() {
        return;
    }
    let work = tempfile::tempdir().unwrap();
    let Ran { stdout, log } = run_script("panic.sh", work.path());
    assert!(stdout.contains("viewer exited with 1"), "{stdout}\n{log}");
    assert!(log.contains("PRISM_INJECT_PANIC"), "{log}");
    // The panel shows the failure in red: some strongly red pixels in the panel.
    let red = red_pixels(&work.path().join("panic.png"), 240);
    assert!(red > 20, "no red error text in the panel ({red} pixels)");
}

/// tests/window/coincident.sh: a scene of more surfaces at one place than any render can
/// finish opens with the reason in red in the panel, rather than tracing without end.
#[test]
fn a_scene_no_render_can_finish_shows_why() {
    if !window_tools() {
        return;
    }
    let work = tempfile::tempdir().unwrap();
    let spheres = "[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\n".repeat(4100);
    std::fs::write(
        work.path().join("coincident.toml"),
        format!("[camera]\neye = [0, 0, 0]\ndirection = [0, 0, -1]\nfov = 40\n{spheres}"),
    )
    .unwrap();
    let Ran { stdout, log } = run_script("coincident.sh", work.path());
    assert!(stdout.contains("the viewer quit"), "{stdout}\n{log}");
    assert!(log.contains("4100 surfaces share one centre"), "{log}");
    let red = red_pixels(&work.path().join("coincident.png"), 240);
    assert!(red > 20, "no red text in the panel ({red} pixels)");
}

/// A near red sphere and a far checked floor, through a lens focused far away.
const LENS_SCENE: &str = "[camera]\neye = [0, 0, 0]\ndirection = [0, 0, -1]\nfov = 40\n\
    aperture = 0.3\nfocus_distance = 20\n\
    [render]\naa = 2\nsamples = 16\n\
    [[lights]]\nposition = [5, 10, 5]\n\
    [textures.check]\ntype = \"checker\"\ncolors = [[0.9, 0.9, 0.9], [0.1, 0.1, 0.1]]\nsize = 1\naxes = \"xz\"\n\
    [materials.red]\ncolor = [0.8, 0.1, 0.1]\n[materials.floor]\ntexture = \"check\"\nspecular = 0\n\
    [[spheres]]\ncenter = [0, 0, -5]\nradius = 1\nmaterial = \"red\"\n\
    [[planes]]\npoint = [0, -1, 0]\nnormal = [0, 1, 0]\nmaterial = \"floor\"\n";

/// tests/window/focus.sh: with an aperture, a click on the image focuses the lens on what
/// lies under the cursor. The viewer reports the distance (the near sphere's front, 4 units
/// along the axis), and the refocused image is what `prism render --focus-distance 4` draws.
#[test]
fn a_click_focuses_the_lens_on_what_is_under_the_cursor() {
    if !window_tools() {
        return;
    }
    let work = tempfile::tempdir().unwrap();
    let scene = work.path().join("lens.toml");
    std::fs::write(&scene, LENS_SCENE).unwrap();
    let log = run_script("focus.sh", work.path()).log;
    let focused: f32 = log
        .lines()
        .find_map(|l| l.strip_prefix("prism: focused at "))
        .expect("the viewer reports the focus")
        .trim()
        .parse()
        .unwrap();
    println!("focused at {focused}");
    assert!((focused - 4.0).abs() < 1e-4, "focused at {focused}");
    let taken = shots(&work.path().join("shots"));
    assert_eq!(taken.len(), 2, "{taken:?}");
    let before = image::open(&taken[0]).unwrap().into_rgb8();
    let after = image::open(&taken[1]).unwrap().into_rgb8();
    let changed = differing(&before, &after, 8);
    assert!(
        changed > 0.02,
        "refocusing changed {:.2}% of pixels",
        changed * 100.0
    );
    let scene = scene.to_string_lossy();
    let reference = render_headless(
        work.path(),
        &[
            &scene,
            "--width",
            "200",
            "--height",
            "200",
            "--focus-distance",
            "4",
        ],
    );
    let off = differing(&after, &reference, 2);
    println!(
        "refocusing changed {:.2}% of pixels; {:.3}% differ from prism render",
        changed * 100.0,
        off * 100.0
    );
    assert!(
        off < 0.01,
        "{:.3}% of pixels differ from prism render --focus-distance 4",
        off * 100.0
    );
}

/// Two matte spheres on a floor, for tests/window/edit.sh: the right sphere's radius line
/// carries a comment the script's edits find it by.
const EDIT_SCENE: &str = "\
# Two spheres on a floor: the window test picks the left one and edits it.
[camera]
eye = [0, 1.5, 8]
look_at = [0, 0.5, 0]
fov = 40

[render]
ambient = [0.1, 0.1, 0.1]

[[lights]]
position = [5, 8, 6]   # the only light

[materials.red]
color = [0.8, 0.15, 0.1]

[materials.blue]
color = [0.1, 0.2, 0.8]

[materials.floor]
color = [0.6, 0.6, 0.6]
specular = 0

[[spheres]]
name = \"left\"
center = [-1.5, 0.5, 0]
radius = 1
material = \"red\"

[[spheres]]
name = \"right\"
center = [1.5, 0.5, 0]
radius = 1  # right
material = \"blue\"

[[planes]]
name = \"floor\"
point = [0, -0.5, 0]
normal = [0, 1, 0]
material = \"floor\"
";

/// tests/window/edit.sh: a click selects the sphere under it (the viewer names it); an edit
/// of its colour changes the image there and nowhere else; Ctrl+S writes a file that loads
/// and renders to the same image, keeping the file's comments; an edit of the file on disk
/// is picked up without a key press; a broken edit shows the error, keeps the last good
/// image and the window; the fix brings the scene back. Each screenshot equals `prism
/// render` of the file it should show.
#[test]
fn picking_editing_saving_and_reloading_in_the_window() {
    if !window_tools() {
        return;
    }
    let work = tempfile::tempdir().unwrap();
    let scene = work.path().join("scene.toml");
    std::fs::write(&scene, EDIT_SCENE).unwrap();
    let log = run_script("edit.sh", work.path()).log;
    assert!(log.contains("prism: selected left"), "{log}");
    assert!(
        log.contains("scene.toml:32") && log.contains("`radius` must be greater than zero"),
        "the error names the file, the line and the field:\n{log}"
    );
    assert!(!log.contains("panicked"), "{log}");
    let taken = shots(&work.path().join("shots"));
    assert_eq!(taken.len(), 6, "{taken:?}");
    let shot = |i: usize| image::open(&taken[i]).unwrap().into_rgb8();
    // `prism render` of a variant of the scene, at the window's size.
    let render = |name: &str, text: &str| render_text(work.path(), name, text);
    let original = render("original.toml", EDIT_SCENE);
    let green = EDIT_SCENE.replace("[0.8, 0.15, 0.1]", "[0.8, 0.9, 0.1]");
    let edited = render("edited.toml", &green);
    assert_eq!(differing(&shot(0), &original, 0), 0.0, "the opened scene");
    assert_eq!(differing(&shot(1), &edited, 0), 0.0, "the edited colour");
    // Where the edit changed the image: the left sphere's pixels, and no other. They are
    // those a scene lit by nothing but the sphere's own glow shows not black.
    let glowing = EDIT_SCENE
        .replace(
            "color = [0.8, 0.15, 0.1]",
            "color = [0, 0, 0]\nemission = [1, 1, 1]",
        )
        .replace("ambient = [0.1, 0.1, 0.1]", "ambient = [0, 0, 0]")
        .replace("   # the only light", "\ncolor = [0, 0, 0]");
    let sphere = render("mask.toml", &glowing);
    let mut changed = 0;
    for ((a, b), m) in shot(0).pixels().zip(shot(1).pixels()).zip(sphere.pixels()) {
        if a != b {
            changed += 1;
            assert!(m.0 != [0, 0, 0], "a pixel changed outside the left sphere");
        }
    }
    assert!(changed > 2000, "only {changed} pixels changed");
    // The saved file: the new colour, the comments kept, and the same image.
    let saved = std::fs::read_to_string(work.path().join("saved.toml")).unwrap();
    assert!(saved.contains("color = [0.8, 0.9, 0.1]"), "{saved}");
    assert!(
        saved.contains("position = [5, 8, 6]   # the only light"),
        "{saved}"
    );
    let saved_image = render("saved.toml", &saved);
    assert_eq!(differing(&saved_image, &edited, 0), 0.0, "the saved file");
    assert_eq!(differing(&shot(2), &edited, 0), 0.0, "after the reload");
    let smaller = render(
        "smaller.toml",
        &green.replace("radius = 1  # right", "radius = 0.6"),
    );
    assert_eq!(differing(&shot(3), &smaller, 0), 0.0, "the edit on disk");
    assert_eq!(
        differing(&shot(4), &smaller, 0),
        0.0,
        "the last good scene stays"
    );
    let fixed = render(
        "fixed.toml",
        &green.replace("radius = 1  # right", "radius = 0.8"),
    );
    assert_eq!(differing(&shot(5), &fixed, 0), 0.0, "the fix");
    // The broken state on screen: red error text at the top of the panel.
    let red = red_pixels(&work.path().join("broken.png"), 90);
    assert!(
        red > 50,
        "no error text at the top of the panel ({red} pixels)"
    );
}

/// tests/window/transform.sh: the selection's translate, rotate and scale rows place it as
/// the file with those values does; the save writes them and nothing else of the entry,
/// and three undos bring the scene back.
#[test]
fn the_transform_rows_place_the_selection() {
    if !window_tools() {
        return;
    }
    let work = tempfile::tempdir().unwrap();
    std::fs::write(work.path().join("scene.toml"), EDIT_SCENE).unwrap();
    let log = run_script("transform.sh", work.path()).log;
    assert!(!log.contains("panicked"), "{log}");
    let taken = shots(&work.path().join("shots"));
    assert_eq!(taken.len(), 2, "{taken:?}");
    let shot = |i: usize| image::open(&taken[i]).unwrap().into_rgb8();
    let render = |name: &str, text: &str| render_text(work.path(), name, text);
    // The right sphere's entry with the values typed, written by hand.
    let right = "radius = 1  # right\nmaterial = \"blue\"\n";
    let placed = EDIT_SCENE.replace(
        right,
        &format!("{right}translate = [0.5, 0, 0]\nrotate = [0, 0, 20]\nscale = [1, 0.5, 1]\n"),
    );
    assert_ne!(placed, EDIT_SCENE);
    let expected = render("placed.toml", &placed);
    let original = render("original.toml", EDIT_SCENE);
    assert!(differing(&expected, &original, 0) > 0.01, "the edits show");
    assert_eq!(differing(&shot(0), &expected, 0), 0.0, "the placed sphere");
    let saved = std::fs::read_to_string(work.path().join("saved.toml")).unwrap();
    for line in [
        "translate = [0.5, 0.0, 0.0]",
        "rotate = [0.0, 0.0, 20.0]",
        "scale = [1.0, 0.5, 1.0]",
        "radius = 1  # right",
        "position = [5, 8, 6]   # the only light",
    ] {
        assert!(saved.contains(line), "{line} not in\n{saved}");
    }
    assert_eq!(saved.matches("translate").count(), 1, "{saved}");
    assert_eq!(differing(&render("saved.toml", &saved), &expected, 0), 0.0);
    assert_eq!(differing(&shot(1), &original, 0), 0.0, "after three undos");
}

/// tests/window/broken_start.sh: a scene with an error at start opens the window anyway,
/// with the error (file, line, field) in red in the panel; fixing the file shows the scene,
/// as `prism render` draws it.
#[test]
fn a_scene_that_fails_at_start_opens_the_window_with_its_error() {
    if !window_tools() {
        return;
    }
    let work = tempfile::tempdir().unwrap();
    let scene = work.path().join("scene.toml");
    let good = EDIT_SCENE.replace("radius = 1  # right", "radius = 1");
    std::fs::write(&scene, good.replacen("radius = 1\n", "radius = -1\n", 1)).unwrap();
    let log = run_script("broken_start.sh", work.path()).log;
    assert!(
        log.contains("scene.toml:26") && log.contains("`radius` must be greater than zero"),
        "{log}"
    );
    let red = red_pixels(&work.path().join("broken.png"), 90);
    assert!(
        red > 50,
        "no error text at the top of the panel ({red} pixels)"
    );
    let taken = shots(&work.path().join("shots"));
    assert_eq!(taken.len(), 1, "{taken:?}");
    let shot = image::open(&taken[0]).unwrap().into_rgb8();
    let fixed = work.path().join("fixed.toml");
    std::fs::write(&fixed, &good).unwrap();
    let fixed = fixed.to_string_lossy().into_owned();
    let reference = render_headless(work.path(), &[&fixed, "--width", "320", "--height", "240"]);
    assert_eq!(differing(&shot, &reference, 0), 0.0, "the fixed scene");
}

/// tests/window/animation.sh: the panel's frame row steps through an animated scene (the
/// turntable): three clicks of ">" show frame 3, a typed 40 shows frame 40, each as
/// `prism render --frame N` draws it.
#[test]
fn the_frame_row_steps_through_an_animation() {
    if !window_tools() {
        return;
    }
    let work = tempfile::tempdir().unwrap();
    let assets = concat!(env!("CARGO_MANIFEST_DIR"), "/assets");
    let text = std::fs::read_to_string(format!("{assets}/scenes/turntable.toml")).unwrap();
    let text = text.replace(
        "\"../meshes/bunny.obj\"",
        &format!("\"{assets}/meshes/bunny.obj\""),
    );
    let scene = work.path().join("scene.toml");
    std::fs::write(&scene, text).unwrap();
    let log = run_script("animation.sh", work.path()).log;
    assert!(!log.contains("panicked"), "{log}");
    let taken = shots(&work.path().join("shots"));
    assert_eq!(taken.len(), 2, "{taken:?}");
    let scene = scene.to_string_lossy().into_owned();
    for (shot, frame) in taken.iter().zip(["3", "40"]) {
        let shot = image::open(shot).unwrap().into_rgb8();
        let reference = render_headless(
            work.path(),
            &[
                &scene, "--width", "320", "--height", "240", "--frame", frame,
            ],
        );
        assert_eq!(differing(&shot, &reference, 0), 0.0, "frame {frame}");
    }
    // The frames differ: the stepping was seen.
    let first = image::open(&taken[0]).unwrap().into_rgb8();
    let second = image::open(&taken[1]).unwrap().into_rgb8();
    assert!(differing(&first, &second, 0) > 0.05);
}

/// The image is uploaded to the window only when a new one arrives, and then only the
/// image's pixels: the frames the panel's hover redraws after the render converged upload
/// nothing, and every upload is the 320×240 image, not the window.
#[test]
fn frames_for_the_panel_alone_upload_no_image() {
    if !window_tools() {
        return;
    }
    let work = tempfile::tempdir().unwrap();
    let log = run_script("uploads.sh", work.path()).log;
    // Each frame's line: `prism-timing: frame AT SINCE_LAST TO_DRAW BYTES`.
    let frames: Vec<(usize, u64)> = log
        .lines()
        .enumerate()
        .filter_map(|(i, line)| {
            let bytes = line.strip_prefix("prism-timing: frame ")?;
            Some((i, bytes.split_whitespace().nth(3)?.parse().ok()?))
        })
        .collect();
    let uploads: Vec<u64> = frames.iter().map(|f| f.1).filter(|&b| b > 0).collect();
    assert!(!uploads.is_empty(), "no image was uploaded: {log}");
    assert!(
        uploads.iter().all(|&b| b == 320 * 240 * 4),
        "uploads of other sizes: {uploads:?}"
    );
    // After the converged image (drawn in the frame that reports it, or the one after).
    let converged = log.lines().position(|l| l.contains("converged")).unwrap();
    let after: Vec<u64> = frames
        .iter()
        .filter(|f| f.0 > converged)
        .skip(1)
        .map(|f| f.1)
        .collect();
    assert!(
        after.len() >= 3,
        "only {} frames for the hover: {log}",
        after.len()
    );
    assert!(
        after.iter().all(|&b| b == 0),
        "frames with no new image uploaded {after:?}"
    );
}
