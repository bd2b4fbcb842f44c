//! The `prism render` command end to end: a real render, and every kind of bad input
//! answered with a located message and exit code 2, never a panic or a partial file.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

mod common;
use common::prism;

/// A valid minimal scene; tests break it one field at a time.
const GOOD: &str = r#"
[camera]
eye = [0, 0, 0]
direction = [0, 0, -1]
fov = 40

[[lights]]
position = [0, 10, 0]

[materials.red]
color = [1, 0, 0]
transparency = 0.5
reflectivity = 0.2
eta = 1.5

[[spheres]]
name = "ball"
center = [0, 0, -5]
radius = 1
material = "red"

[[polygons]]
name = "ground"
vertices = [[-5, -1, 0], [5, -1, 0], [5, -1, -10], [-5, -1, -10]]
"#;

struct Case {
    dir: tempfile::TempDir,
}

impl Case {
    fn new() -> Self {
        Self {
            dir: tempfile::tempdir().unwrap(),
        }
    }

    fn scene(&self, text: &str) -> PathBuf {
        let p = self.dir.path().join("scene.toml");
        std::fs::write(&p, text).unwrap();
        p
    }

    fn out(&self) -> PathBuf {
        self.dir.path().join("out.png")
    }

    fn render(&self, scene: &Path, extra: &[&str]) -> Output {
        self.run(scene, extra, true)
    }

    /// `render` without `--quiet`: with the summary and statistics on stderr.
    fn render_reporting(&self, scene: &Path, extra: &[&str]) -> Output {
        self.run(scene, extra, false)
    }

    fn run(&self, scene: &Path, extra: &[&str], quiet: bool) -> Output {
        let out = self.out();
        let mut args = vec![
            "render",
            scene.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ];
        if quiet {
            args.push("--quiet");
        }
        for (flag, value) in [("--width", "40"), ("--height", "30")] {
            if !extra.contains(&flag) {
                args.extend_from_slice(&[flag, value]);
            }
        }
        args.extend_from_slice(extra);
        prism(&args)
    }

    /// Asserts the render failed with exit code 2, left no file, and said all of `needles`.
    fn fails_with(&self, text: &str, extra: &[&str], needles: &[&str]) {
        let scene = self.scene(text);
        let out = self.render(&scene, extra);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "stderr: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
        for n in needles {
            assert!(stderr.contains(n), "expected {n:?} in: {stderr}");
        }
        let leftovers: Vec<_> = std::fs::read_dir(self.dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .filter(|n| n != "scene.toml")
            .collect();
        assert!(leftovers.is_empty(), "left behind: {leftovers:?}");
    }
}

fn replace(from: &str, to: &str) -> String {
    assert!(GOOD.contains(from), "{from}");
    GOOD.replacen(from, to, 1)
}

#[test]
fn renders_a_png_and_reports_speed() {
    let case = Case::new();
    let scene = case.scene(GOOD);
    let out = case.render_reporting(&scene, &["--aa", "2", "--threads", "2"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("4.00 samples per pixel"), "{stderr}");
    assert!(stderr.contains(" 4 passes,"), "{stderr}");
    // Quiet means nothing on stderr when all goes well.
    let out = case.render(&scene, &["--aa", "1", "--threads", "2"]);
    assert!(out.status.success());
    assert_eq!(String::from_utf8_lossy(&out.stderr), "");
    let out = case.render_reporting(&scene, &["--aa", "1"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains(" 1 pass,"), "{stderr}");
    assert!(stderr.contains("M rays/s"), "{stderr}");
    let img = image::open(case.out()).unwrap().into_rgb8();
    assert_eq!(img.dimensions(), (40, 30));
    // The ball is red in the middle of the image.
    let c = img.get_pixel(20, 15);
    assert!(c[0] > c[1] && c[0] > c[2], "{c:?}");
}

#[test]
fn seed_scene_is_the_default() {
    let case = Case::new();
    let out_path = case.out();
    let out = prism(&[
        "render",
        "--width",
        "32",
        "--height",
        "24",
        "--aa",
        "1",
        "--quiet",
        "--out",
        out_path.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out_path.exists());
}

#[test]
fn toml_syntax_error_names_line_and_column() {
    Case::new().fails_with(&replace("fov = 40", "fov = = 40"), &[], &["scene.toml:5:"]);
}

#[test]
fn unknown_field_is_named() {
    Case::new().fails_with(
        &replace("radius = 1", "radius = 1\nradiuss = 2"),
        &[],
        &["scene.toml:", "radiuss"],
    );
}

#[test]
fn missing_field_is_named() {
    Case::new().fails_with(&replace("radius = 1\n", ""), &[], &["radius"]);
}

#[test]
fn missing_texture_image_is_named() {
    let text = format!("{GOOD}\n[textures.pic]\ntype = \"image\"\npath = \"nope.jpg\"\n");
    Case::new().fails_with(&text, &[], &["textures.pic", "nope.jpg"]);
}

#[test]
fn unreadable_texture_image_is_named() {
    let case = Case::new();
    std::fs::write(case.dir.path().join("bad.jpg"), b"not a jpeg").unwrap();
    let text = format!("{GOOD}\n[textures.pic]\ntype = \"image\"\npath = \"bad.jpg\"\n");
    let scene = case.scene(&text);
    let out = case.render(&scene, &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("bad.jpg"), "{stderr}");
}

#[test]
fn non_positive_radius_is_rejected_with_its_line() {
    let case = Case::new();
    case.fails_with(
        &replace("radius = 1", "radius = -1"),
        &[],
        &["scene.toml:19:", "spheres[0] \"ball\"", "radius", "-1"],
    );
    case.fails_with(&replace("radius = 1", "radius = 0"), &[], &["radius"]);
}

#[test]
fn bad_eta_is_rejected() {
    let case = Case::new();
    case.fails_with(
        &replace("eta = 1.5", "eta = 0"),
        &[],
        &["materials.red", "eta"],
    );
    case.fails_with(&replace("eta = 1.5", "eta = -2"), &[], &["eta"]);
    case.fails_with(&replace("eta = 1.5", "eta = nan"), &[], &["eta"]);
    case.fails_with(&replace("eta = 1.5", "eta = inf"), &[], &["eta"]);
}

#[test]
fn fractions_outside_zero_one_are_rejected() {
    let case = Case::new();
    case.fails_with(
        &replace("transparency = 0.5", "transparency = 1.5"),
        &[],
        &["materials.red", "transparency", "[0, 1]"],
    );
    case.fails_with(
        &replace("reflectivity = 0.2", "reflectivity = -0.1"),
        &[],
        &["reflectivity"],
    );
}

#[test]
fn degenerate_polygons_are_rejected() {
    let case = Case::new();
    case.fails_with(
        &replace(
            "[[-5, -1, 0], [5, -1, 0], [5, -1, -10], [-5, -1, -10]]",
            "[[0, 0, 0], [1, 1, 1], [2, 2, 2]]",
        ),
        &[],
        &["polygons[0] \"ground\"", "collinear"],
    );
    case.fails_with(
        &replace(
            "[[-5, -1, 0], [5, -1, 0], [5, -1, -10], [-5, -1, -10]]",
            "[[-5, -1, 0], [5, -1, 0], [5, -1, 0], [-5, -1, -10]]",
        ),
        &[],
        &["coincide"],
    );
}

#[test]
fn zero_length_camera_direction_is_rejected() {
    let case = Case::new();
    case.fails_with(
        &replace("direction = [0, 0, -1]", "direction = [0, 0, 0]"),
        &[],
        &["camera", "zero length"],
    );
    case.fails_with(
        &replace("direction = [0, 0, -1]", "look_at = [0, 0, 0]"),
        &[],
        &["look_at"],
    );
}

#[test]
fn bad_image_settings_are_rejected() {
    let case = Case::new();
    // The flags take their ranges from limits.rs, and say them.
    case.fails_with(GOOD, &["--width", "0"], &["--width", "1..=16384"]);
    case.fails_with(GOOD, &["--aa", "9"], &["--aa", "9 is not in 1..=8"]);
    case.fails_with(GOOD, &["--aa", "0"], &["--aa", "0 is not in 1..=8"]);
    // The scene file's suggestion is checked by the same rule.
    let large = GOOD.replace("[[lights]]", "[render]\nwidth = 40\naa = 8\n\n[[lights]]");
    case.fails_with(&large.replace("aa = 8", "aa = 9"), &[], &["`aa`", "1..=8"]);
}

#[test]
fn unwritable_output_fails_before_rendering() {
    let case = Case::new();
    let scene = case.scene(GOOD);
    // A folder that cannot be made: its parent is a file.
    let bad = scene.join("missing-dir/out.png");
    let out = prism(&[
        "render",
        scene.to_str().unwrap(),
        "--out",
        bad.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("missing-dir/out.png"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(
        !stderr.contains("rendered"),
        "it should not have rendered: {stderr}"
    );
}

#[test]
fn missing_scene_file_is_named() {
    let out = prism(&["render", "/no/such/scene.toml", "--quiet"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr.contains("/no/such/scene.toml"), "{stderr}");
}

#[test]
fn non_finite_and_extreme_numbers_are_rejected() {
    let case = Case::new();
    case.fails_with(
        &replace("radius = 1", "radius = nan"),
        &[],
        &["radius", "finite"],
    );
    case.fails_with(
        &replace("eye = [0, 0, 0]", "eye = [0, inf, 0]"),
        &[],
        &["camera", "eye"],
    );
    case.fails_with(&replace("fov = 40", "fov = -40"), &[], &["fov"]);
    case.fails_with(&replace("fov = 40", "fov = 1e30"), &[], &["fov"]);
    case.fails_with(
        &replace("center = [0, 0, -5]", "center = [0, 0, -1e300]"),
        &[],
        &["center", "finite"],
    );
    case.fails_with(
        GOOD,
        &["--width", "100000"],
        &["100000 is not in 1..=16384"],
    );
    case.fails_with(GOOD, &["--adaptive", "--tolerance", "nan"], &["tolerance"]);
    case.fails_with(GOOD, &["--adaptive", "--tolerance", "-1"], &["tolerance"]);
    case.fails_with(
        GOOD,
        &["--adaptive", "--edge-contrast", "-0.5"],
        &["edge contrast"],
    );
    case.fails_with(
        GOOD,
        &["--adaptive", "--edge-contrast", "inf"],
        &["edge contrast"],
    );
    // Adaptive settings without --adaptive would be silently ignored: refuse them.
    case.fails_with(GOOD, &["--edge-contrast", "0.1"], &["--adaptive"]);
    case.fails_with(GOOD, &["--tolerance", "0.01"], &["--adaptive"]);
}

/// `prism ARGS` with no display to open a window on.
#[cfg(feature = "viewer")]
fn prism_without_display(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_prism"))
        .args(args)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap()
}

#[cfg(feature = "viewer")]
#[test]
fn viewer_reports_a_bad_scene_before_opening_a_window() {
    let case = Case::new();
    let scene = case.scene(&replace("radius = 1", "radius = -1"));
    let out = prism_without_display(&["view", scene.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("scene.toml:19") && stderr.contains("radius"),
        "{stderr}"
    );
}

#[cfg(feature = "viewer")]
#[test]
fn viewer_without_a_display_points_to_render() {
    let out = prism_without_display(&["view"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("prism render"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// Plain `prism` takes the options of `prism view` (and its scene), checked as `view`
/// checks them, before any window opens.
#[cfg(feature = "viewer")]
#[test]
fn plain_prism_takes_the_viewers_options() {
    let case = Case::new();
    let missing = case.dir.path().join("no-such-folder");
    for args in [
        vec!["--screenshot-dir", missing.to_str().unwrap()],
        vec!["view", "--screenshot-dir", missing.to_str().unwrap()],
    ] {
        let out = prism_without_display(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains("screenshots cannot be saved here"),
            "{stderr}"
        );
    }
    let out = prism_without_display(&["--aa", "9"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("1..=8"));
    let scene = case.scene(&replace("radius = 1", "radius = -1"));
    let out = prism_without_display(&["--width", "200", scene.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("scene.toml:19"), "{stderr}");
    // A good scene gets as far as the window, which this test's environment cannot open.
    let good = case.scene(GOOD);
    let out = prism_without_display(&["--width", "200", good.to_str().unwrap()]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot open a window"));
}

#[test]
fn bad_up_vectors_are_rejected() {
    let case = Case::new();
    case.fails_with(
        &replace("fov = 40", "fov = 40\nup = [0, 0, 0]"),
        &[],
        &["camera", "`up` has zero length"],
    );
    case.fails_with(
        &replace("fov = 40", "fov = 40\nup = [0, 0, 1]"),
        &[],
        &["camera", "choose another `up`"],
    );
}

/// A whole frame is encoded from the render's own pixel sums, as the memory check before a
/// render assumes (`RenderMemory`): the peak stays within its figure plus what the process
/// holds anyway (code, the earth texture, thread stacks). A copy of the film, 148 MiB here,
/// would go past it.
#[test]
fn a_whole_frame_peaks_within_the_memory_the_check_assumes() {
    use prism::render::{BitDepth, ImageFormat, PixelRect, RenderMemory};
    let dir = tempfile::tempdir().unwrap();
    let (out, json) = (dir.path().join("out.png"), dir.path().join("stats.json"));
    let (w, h) = (2400, 1800);
    let run = prism(&[
        "render",
        "-o",
        out.to_str().unwrap(),
        "--width",
        &w.to_string(),
        "--height",
        &h.to_string(),
        "--aa",
        "1",
        "--quiet",
        "--stats-json",
        json.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", common::stderr(&run));
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let peak = stats["peak_memory_bytes"].as_u64().unwrap();
    let frame = PixelRect::full(w, h);
    let model = RenderMemory::of(frame, frame, ImageFormat::Png, BitDepth::Eight).total();
    let process = 64 << 20;
    assert!(
        peak < model + process,
        "peak {} MiB against {} MiB assumed for the render",
        peak >> 20,
        model >> 20
    );
}

/// The statistics at the end: time by stage and peak memory on stderr, and with
/// `--stats-json` the same figures as JSON, consistent with each other; an unwritable
/// statistics path fails before the render.
#[test]
fn statistics_are_reported_and_written_as_json() {
    let case = Case::new();
    let scene = case.scene(GOOD);
    let json_path = case.dir.path().join("stats.json");
    let out = case.render_reporting(&scene, &["--stats-json", json_path.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("s loading,") && stderr.contains("s tracing"),
        "{stderr}"
    );
    assert!(stderr.contains("peak memory: "), "{stderr}");
    let text = std::fs::read_to_string(&json_path).unwrap();
    let stats: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(stats["width"], 40);
    assert_eq!(stats["height"], 30);
    let rays = &stats["rays"];
    let sum = ["primary", "shadow", "secondary"]
        .iter()
        .map(|k| rays[k].as_u64().unwrap())
        .sum::<u64>();
    assert_eq!(rays["total"].as_u64(), Some(sum));
    // 40×30 pixels at the scene's 2×2 subsamples: 4,800 primary rays.
    assert_eq!(rays["primary"], 4800);
    assert_eq!(stats["samples_per_pixel"], 4.0);
    let s = &stats["seconds"];
    let part = |k: &str| s[k].as_f64().unwrap();
    assert!(part("load") + part("build") + part("trace") <= part("total") + 1e-6);
    assert!(stats["peak_memory_bytes"].as_u64().unwrap_or(u64::MAX) > 1 << 20);

    std::fs::remove_file(case.out()).unwrap();
    // A folder that cannot be made: its parent is a file.
    let bad = scene.join("stats.json");
    let out = case.render(&scene, &["--stats-json", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        !case.out().exists(),
        "no image after a refused statistics path"
    );
}

/// No output may land on what the render reads or on another of its outputs: refused with
/// exit 2 before anything is rendered, and the file is unchanged.
#[test]
fn outputs_never_overwrite_inputs_or_each_other() {
    let case = Case::new();
    let dir = case.dir.path();
    let obj = dir.join("tri.obj");
    std::fs::write(&obj, "v 0 0 -4\nv 1 0 -4\nv 0 1 -4\nf 1 2 3\n").unwrap();
    let scene = case.scene(&format!("{GOOD}\n[[meshes]]\npath = \"tri.obj\"\n"));
    let before = std::fs::read(&scene).unwrap();
    let out = case.out();
    let s = |p: &Path| p.to_str().unwrap().to_string();
    for (args, needle) in [
        (
            vec!["--stats-json".to_string(), s(&scene)],
            "the scene file",
        ),
        (vec!["--stats-json".to_string(), s(&out)], "the image"),
        (
            vec!["--stats-json".to_string(), s(&obj)],
            "which the scene reads",
        ),
        (
            vec!["--stats-json".to_string(), s(&dir.join("./x/../out.png"))],
            "the image",
        ),
    ] {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = case.render(&scene, &args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(needle), "{args:?}: {stderr}");
    }
    assert_eq!(std::fs::read(&scene).unwrap(), before);
    assert!(!out.exists());
    // An image on a mesh or the scene, and frames through templates.
    let o = prism(&["render", &s(&scene), "-q", "-o", &s(&obj)]);
    assert_eq!(o.status.code(), Some(2));
    let tex = dir.join("tex.png");
    image::RgbImage::from_pixel(2, 2, image::Rgb([9, 9, 9]))
        .save(&tex)
        .unwrap();
    let textured = case.scene(&format!(
        "{GOOD}\n[textures.t]\ntype = \"image\"\npath = \"tex.png\"\n[materials.t]\ntexture = \"t\"\n"
    ));
    let o = prism(&["render", &s(&textured), "-q", "-o", &s(&tex)]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("which the scene reads"), "{stderr}");
    assert_eq!(
        image::open(&tex).unwrap().into_rgb8().get_pixel(0, 0).0,
        [9, 9, 9]
    );
    let o = prism(&[
        "render",
        &s(&textured),
        "-q",
        "--width",
        "8",
        "--height",
        "6",
        "-o",
        &s(&dir.join("same_{tile}.png")),
        "--stats-json",
        &s(&dir.join("same_{tile}.png")),
        "--tile",
        "1/2",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!dir.join("same_1.png").exists());
}

/// Outputs go where a user expects: missing folders are made (and said), `{tile}` needs a
/// tile, and `--skip-existing` skips only a file, not a folder of the name.
#[test]
fn output_paths_behave_as_a_user_expects() {
    let case = Case::new();
    let scene = case.scene(GOOD);
    let dir = case.dir.path();
    let nested = dir.join("frames/a/shot_0000.png");
    let o = prism(&[
        "render",
        scene.to_str().unwrap(),
        "--width",
        "8",
        "--height",
        "6",
        "-o",
        dir.join("frames/a/shot_{frame:04}.png").to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(stderr.contains("made the folder"), "{stderr}");
    assert!(nested.is_file());

    let o = prism(&[
        "render",
        scene.to_str().unwrap(),
        "-q",
        "-o",
        dir.join("x_{tile}.png").to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("{tile}") && stderr.contains("--tile"),
        "{stderr}"
    );
    assert!(!dir.join("x_.png").exists());

    let folder = dir.join("done.png");
    std::fs::create_dir(&folder).unwrap();
    let o = prism(&[
        "render",
        scene.to_str().unwrap(),
        "-q",
        "--skip-existing",
        "-o",
        folder.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(
        o.status.code(),
        Some(2),
        "a folder is not a finished image: {stderr}"
    );
    assert!(stderr.contains("directory"), "{stderr}");

    // A terminal escape in a path is shown escaped, never sent to the terminal.
    let o = prism(&[
        "render",
        scene.to_str().unwrap(),
        "--width",
        "4",
        "--height",
        "3",
        "-o",
        dir.join("esc\u{1b}[31m.png").to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(
        !stderr.contains('\u{1b}') && stderr.contains("\\u{1b}"),
        "{stderr}"
    );
}

/// The largest frame is worked out before anything is allocated: under a memory limit it
/// is refused with the figures and the way out (tiles), leaving nothing, and a tile of it
/// that fits renders.
#[test]
fn a_frame_too_large_for_memory_is_refused_up_front() {
    let case = Case::new();
    let out = case.out();
    let run = |extra: &str| {
        let command = format!(
            "ulimit -v 3000000; exec \"$0\" render -q --aa 1 --width 16384 --height 16384 {extra} -o {}",
            out.display()
        );
        Command::new("bash")
            .args(["-c", &command, env!("CARGO_BIN_EXE_prism")])
            .output()
            .unwrap()
    };
    let o = run("");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    for needle in ["16384×16384", "GiB", "address-space limit", "--tile I/"] {
        assert!(stderr.contains(needle), "{needle:?} in {stderr}");
    }
    assert_eq!(std::fs::read_dir(case.dir.path()).unwrap().count(), 0);
    let o = run("--tile 63/64");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(image::open(&out).unwrap().height(), 256);
}
