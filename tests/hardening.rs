//! One test for each defect the hardening review found (issue "Hardening"): hostile input
//! to `prism render` and to the library ends in a located message and exit code 2, or in
//! a bounded render, never in a panic, a hang, runaway memory or a damaged file.

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

mod common;
use common::{Dir, prism, stderr};

const SPHERE: &str = r#"
[camera]
eye = [0, 0, 0]
direction = [0, 0, -1]
fov = 40

[[lights]]
position = [0, 10, 0]

[materials.glass]
color = [0.9, 0.9, 1]
transparency = 0.9
eta = 1.5

[[spheres]]
name = "ball"
center = [0, 0, -5]
radius = 1
material = "glass"
"#;

impl Dir {
    /// `prism render SCENE -o out.png --quiet` at 40×30 plus `extra`.
    fn render(&self, scene: &Path, extra: &[&str]) -> Output {
        render_to(scene, &self.path("out.png"), extra)
    }
    /// Asserts that rendering `text` fails with exit code 2 saying all of `needles`.
    fn refuses(&self, text: &str, extra: &[&str], needles: &[&str]) -> String {
        let scene = self.write("scene.toml", text);
        let _ = std::fs::remove_file(self.path("out.png"));
        let out = self.render(&scene, extra);
        let e = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{e}");
        assert!(!e.contains("panicked"), "{e}");
        for n in needles {
            assert!(e.contains(n), "expected {n:?} in: {e}");
        }
        assert!(!self.path("out.png").exists());
        e
    }
}

/// `prism render SCENE -o OUT --quiet` plus `extra`, at 40×30 unless `extra` sets a size.
fn render_to(scene: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--quiet",
    ];
    for (flag, value) in [("--width", "40"), ("--height", "30")] {
        if !extra.contains(&flag) {
            args.extend_from_slice(&[flag, value]);
        }
    }
    args.extend_from_slice(extra);
    prism(&args)
}

fn with(from: &str, to: &str) -> String {
    assert!(SPHERE.contains(from), "{from}");
    SPHERE.replacen(from, to, 1)
}

// ---- Crashes -----------------------------------------------------------------------

#[test]
fn an_eta_whose_square_overflows_is_refused_with_its_line() {
    let d = Dir::new();
    let e = d.refuses(
        &with("eta = 1.5", "eta = 2e19"),
        &[],
        &["scene.toml:13:", "eta", "2e19"],
    );
    assert!(e.contains("[0.1, 10]"), "{e}");
    // Both ends of the range render.
    for eta in ["0.1", "10"] {
        let scene = d.write("scene.toml", &with("eta = 1.5", &format!("eta = {eta}")));
        let out = d.render(&scene, &[]);
        assert!(out.status.success(), "eta {eta}: {}", stderr(&out));
    }
}

#[test]
fn triangles_too_large_for_f32_products_are_refused_and_large_ones_draw() {
    let d = Dir::new();
    let big = |leg: &str| {
        format!(
            "{SPHERE}\n[[triangles]]\nvertices = [[0, 0, -{leg}], [{leg}, 0, -{leg}], [0, {leg}, -{leg}]]\n"
        )
    };
    d.refuses(
        &big("2e19"),
        &[],
        &["triangles[0]", "within 1e12 of the camera"],
    );
    // At the limit the triangle still draws: seen from a distance that frames it.
    let text = r#"
[camera]
eye = [3e11, 3e11, 1e12]
look_at = [3e11, 3e11, 0]
fov = 60
[[lights]]
position = [0, 0, 1e12]
[[triangles]]
vertices = [[0, 0, 0], [1e12, 0, 0], [0, 1e12, 0]]
"#;
    let scene = d.write("scene.toml", text);
    let out = d.render(&scene, &[]);
    assert!(out.status.success(), "{}", stderr(&out));
    let img = image::open(d.path("out.png")).unwrap().into_rgb8();
    let lit = img.pixels().filter(|p| p.0 != [0, 0, 0]).count();
    let share = lit as f64 / (40.0 * 30.0);
    // The hypotenuse x + y = 1e12 crosses the view: part of the image is triangle.
    assert!(
        (0.2..0.9).contains(&share),
        "{share} of the image is triangle"
    );
}

#[test]
fn a_cylinder_reaching_past_the_limit_is_refused() {
    let d = Dir::new();
    let text =
        format!("{SPHERE}\n[[cylinders]]\nbase = [0, -1e38, -30]\nradius = 1\nheight = 3e38\n");
    d.refuses(&text, &[], &["cylinders[0]", "base"]);
    // The top cap counts as a position too.
    let text =
        format!("{SPHERE}\n[[cylinders]]\nbase = [0, 9e11, -30]\nradius = 1\nheight = 9e11\n");
    d.refuses(&text, &[], &["cylinders[0]", "height", "1e12"]);
}

#[test]
fn max_depth_beyond_the_limit_is_refused_on_the_command_line_too() {
    let d = Dir::new();
    let scene = d.write("scene.toml", SPHERE);
    let out = d.render(&scene, &["--max-depth", "999"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("0..=64"), "{}", stderr(&out));
    assert_eq!(d.others(&["scene.toml"]), Vec::<String>::new());
}

/// The six faces of the closed box from −2 to 2 on every axis, as `vertices` values.
const BOX_FACES: [&str; 6] = [
    "[[-2,-2,-2],[2,-2,-2],[2,2,-2],[-2,2,-2]]",
    "[[-2,-2,2],[-2,2,2],[2,2,2],[2,-2,2]]",
    "[[-2,-2,-2],[-2,2,-2],[-2,2,2],[-2,-2,2]]",
    "[[2,-2,-2],[2,-2,2],[2,2,2],[2,2,-2]]",
    "[[-2,-2,-2],[-2,-2,2],[2,-2,2],[2,-2,-2]]",
    "[[-2,2,-2],[2,2,-2],[2,2,2],[-2,2,2]]",
];

/// A closed box of mirrors, with a clear pane inside that every path crosses again and
/// again: the deepest recursion a sample can have.
fn mirror_box(max_depth: u32) -> String {
    let mut s = format!(
        "[camera]\neye = [0.1, 0.2, 0.3]\ndirection = [0.3, 0.2, -1]\nfov = 60\n\
         [render]\nmax_depth = {max_depth}\n[[lights]]\nposition = [0.5, 0.5, 0.5]\n\
         [materials.mirror]\nreflectivity = 1\n[materials.both]\nreflectivity = 0.5\n\
         transparency = 0.5\neta = 1.5\n[materials.clear]\ntransparency = 1\n"
    );
    for (i, f) in BOX_FACES.iter().enumerate() {
        let m = if i % 2 == 0 { "mirror" } else { "both" };
        s += &format!("[[polygons]]\nvertices = {f}\nmaterial = \"{m}\"\n");
    }
    for z in 0..8 {
        let z = -1.9 + z as f32 * 0.45;
        s += &format!(
            "[[polygons]]\nvertices = [[-1.9,-1.9,{z}],[1.9,-1.9,{z}],[1.9,1.9,{z}],[-1.9,1.9,{z}]]\nmaterial = \"clear\"\n"
        );
    }
    s
}

/// The ray counts a render's `--stats-json` file reports: (primary, secondary).
fn ray_counts(stats: &Path) -> (u64, u64) {
    let text = std::fs::read_to_string(stats).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let count = |kind: &str| json["rays"][kind].as_u64().unwrap();
    (count("primary"), count("secondary"))
}

#[test]
fn exact_rendering_of_surfaces_that_reflect_and_transmit_stays_within_the_ray_budget() {
    let d = Dir::new();
    let scene = d.write("scene.toml", &mirror_box(64));
    let stats = d.path("stats.json");
    let out = d.render(
        &scene,
        &[
            "--exact",
            "--aa",
            "1",
            "--max-depth",
            "64",
            "--stats-json",
            stats.to_str().unwrap(),
        ],
    );
    let e = stderr(&out);
    assert!(out.status.success(), "{e}");
    let (primary, secondary) = ray_counts(&stats);
    assert_eq!(primary, 40 * 30);
    let budget = prism::limits::RAY_BUDGET as u64;
    assert!(secondary <= budget * primary, "{secondary} secondary rays");
    // The budget is what bounds this scene: without it the tree would double per bounce.
    assert!(secondary > 16 * primary, "{secondary} secondary rays");
}

// ---- Hangs and runaway resources ----------------------------------------------------

#[cfg(unix)]
fn mkfifo(path: &Path) {
    let status = Command::new("mkfifo").arg(path).status().unwrap();
    assert!(status.success());
}

#[cfg(unix)]
#[test]
fn fifos_and_devices_as_input_are_refused_at_once() {
    let d = Dir::new();
    let fifo = d.path("pipe.toml");
    mkfifo(&fifo);
    let start = Instant::now();
    for scene in [fifo.to_str().unwrap(), "/dev/zero"] {
        let out = d.render(Path::new(scene), &[]);
        let e = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{e}");
        assert!(e.contains("not a regular file"), "{e}");
    }
    let texture = d.path("pipe.png");
    mkfifo(&texture);
    let text = format!(
        "{SPHERE}\n[textures.t]\ntype = \"image\"\npath = \"pipe.png\"\n[materials.t]\ntexture = \"t\"\n"
    );
    d.refuses(
        &text,
        &[],
        &["textures.t", "pipe.png", "not a regular file"],
    );
    assert!(
        start.elapsed() < Duration::from_secs(20),
        "it waited on a FIFO"
    );
}

#[test]
fn a_scene_file_past_the_size_limit_is_refused() {
    let d = Dir::new();
    let mut text = SPHERE.to_string();
    let padding = "# padding\n".repeat((prism::limits::MAX_SCENE_FILE_BYTES / 10) as usize + 1);
    text.push_str(&padding);
    let scene = d.write("big.toml", &text);
    let out = d.render(&scene, &[]);
    let e = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{e}");
    assert!(e.contains("larger than the 16 MiB"), "{e}");
}

/// A grey PNG declaring `w`×`h` pixels, all zero: a few hundred KB on disk for any size.
fn grey_png(path: &Path, w: u32, h: u32) {
    let file = std::fs::File::create(path).unwrap();
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), w, h);
    encoder.set_color(png::ColorType::Grayscale);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fast);
    let mut writer = encoder.write_header().unwrap();
    let mut stream = writer.stream_writer().unwrap();
    let row = vec![0u8; w as usize];
    for _ in 0..h {
        std::io::Write::write_all(&mut stream, &row).unwrap();
    }
    stream.finish().unwrap();
}

#[test]
fn textures_past_the_texel_budget_are_refused_from_their_headers() {
    let d = Dir::new();
    grey_png(&d.path("huge.png"), 22000, 22000);
    let text = format!(
        "{SPHERE}\n[textures.t]\ntype = \"image\"\npath = \"huge.png\"\n[materials.t]\ntexture = \"t\"\n"
    );
    let start = Instant::now();
    d.refuses(
        &text,
        &[],
        &["textures.t", "huge.png", "22000×22000", "8192×8192"],
    );
    // Refused from the header: no decode of 484 million texels.
    assert!(start.elapsed() < Duration::from_secs(10));
    // Three textures within the per-image limit, together past the scene's budget: the
    // third is refused, and none is decoded first.
    let mut text = SPHERE.to_string();
    for i in 0..3 {
        grey_png(&d.path(&format!("t{i}.png")), 8192, 8192);
        text += &format!("\n[textures.t{i}]\ntype = \"image\"\npath = \"t{i}.png\"\n");
    }
    d.refuses(
        &text,
        &[],
        &["textures.t2", "t2.png", "all of them may have together"],
    );
}

#[test]
fn thread_counts_are_bounded_and_zero_is_bad_input() {
    let d = Dir::new();
    let scene = d.write("scene.toml", SPHERE);
    for bad in ["0", "257", "18446744073709551615", "many"] {
        let out = d.render(&scene, &["--threads", bad]);
        assert_eq!(
            out.status.code(),
            Some(2),
            "--threads {bad}: {}",
            stderr(&out)
        );
        assert!(stderr(&out).contains("--threads"), "{}", stderr(&out));
    }
    let out = d.render(&scene, &["--threads", "3"]);
    assert!(out.status.success(), "{}", stderr(&out));
}

// ---- Unsafe or wrong writes -----------------------------------------------------------

#[cfg(unix)]
#[test]
fn signals_remove_the_temporary_file_and_exit_as_shells_expect() {
    let d = Dir::new();
    let scene = d.write("scene.toml", SPHERE);
    for (signal, code) in [("INT", 130), ("TERM", 143), ("HUP", 129)] {
        let child = Command::new(env!("CARGO_BIN_EXE_prism"))
            .args(["render", scene.to_str().unwrap(), "-o"])
            .arg(d.path("out.exr"))
            .args([
                "--quiet", "--width", "3000", "--height", "2000", "--aa", "2",
            ])
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // Wait until the image is being written: its temporary file exists only then (a
        // large image in a format slow to write, float EXR, so that the writing lasts long
        // enough to be caught: some 0.4 s, where a fast-compressed PNG lasts 10 ms). The
        // render before it must finish first, however slow or loaded the machine.
        let start = Instant::now();
        while d.others(&["scene.toml"]).is_empty() {
            assert!(
                start.elapsed() < Duration::from_secs(300),
                "no temporary file"
            );
            std::thread::sleep(Duration::from_millis(20));
        }
        let kill = Command::new("kill")
            .args([&format!("-{signal}"), &child.id().to_string()])
            .status()
            .unwrap();
        assert!(kill.success());
        let out = child.wait_with_output().unwrap();
        assert_eq!(
            out.status.code(),
            Some(code),
            "SIG{signal}: {}",
            stderr(&out)
        );
        assert!(
            stderr(&out).contains(&format!("SIG{signal}")),
            "{}",
            stderr(&out)
        );
        assert_eq!(
            d.others(&["scene.toml"]),
            Vec::<String>::new(),
            "SIG{signal}"
        );
    }
}

#[cfg(unix)]
#[test]
fn devices_fifos_and_symlinks_are_written_through_not_replaced() {
    use std::os::unix::fs::FileTypeExt;
    let d = Dir::new();
    let scene = d.write("scene.toml", SPHERE);
    let run = |out: &Path| render_to(&scene, out, &["--width", "8", "--height", "6"]);
    // A device: written, and still the device afterwards.
    let out = run(Path::new("/dev/null"));
    assert!(out.status.success(), "{}", stderr(&out));
    let meta = std::fs::symlink_metadata("/dev/null").unwrap();
    assert!(meta.file_type().is_char_device());
    // A symbolic link: its target is replaced, the link stays.
    d.write("real.png", "old");
    std::os::unix::fs::symlink("real.png", d.path("link.png")).unwrap();
    let out = run(&d.path("link.png"));
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        std::fs::symlink_metadata(d.path("link.png"))
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(image::open(d.path("real.png")).unwrap().width(), 8);
    // A FIFO: the reader gets the PNG.
    let fifo = d.path("pipe.png");
    mkfifo(&fifo);
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    let out = run(&fifo);
    assert!(out.status.success(), "{}", stderr(&out));
    let bytes = reader.join().unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    assert!(
        std::fs::symlink_metadata(&fifo)
            .unwrap()
            .file_type()
            .is_fifo()
    );
    assert_eq!(
        d.others(&["scene.toml", "real.png", "link.png", "pipe.png"]),
        Vec::<String>::new()
    );
}

#[test]
fn a_truncated_jpeg_is_refused() {
    let d = Dir::new();
    let earth = std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/earth.jpg")).unwrap();
    std::fs::write(d.path("cut.jpg"), &earth[..20_000]).unwrap();
    let text = format!(
        "{SPHERE}\n[textures.t]\ntype = \"image\"\npath = \"cut.jpg\"\n[materials.t]\ntexture = \"t\"\n"
    );
    d.refuses(&text, &[], &["textures.t", "cut.jpg", "truncated"]);
    // The whole file loads.
    std::fs::write(d.path("cut.jpg"), &earth).unwrap();
    let scene = d.write("scene.toml", &text);
    assert!(d.render(&scene, &[]).status.success());
}

#[test]
fn output_names_must_name_a_format() {
    let d = Dir::new();
    let scene = d.write("scene.toml", SPHERE);
    for name in ["out.tiff", "out", "out.png.bak"] {
        let out = prism(&[
            "render",
            scene.to_str().unwrap(),
            "-o",
            d.path(name).to_str().unwrap(),
            "--quiet",
        ]);
        let e = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{name}: {e}");
        assert!(e.contains(".png, .jpg (or .jpeg), .exr or .pfm"), "{e}");
    }
    let upper = d.path("OUT.PNG");
    let out = prism(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        upper.to_str().unwrap(),
        "--quiet",
        "--width",
        "8",
        "--height",
        "6",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(d.others(&["scene.toml", "OUT.PNG"]), Vec::<String>::new());
}

// ---- Messages ---------------------------------------------------------------------------

#[test]
fn io_errors_name_their_cause_once_and_no_temporary_file() {
    let d = Dir::new();
    let out = prism(&["render", "/no/such/scene.toml", "--quiet"]);
    let e = stderr(&out);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(e.matches("No such file or directory").count(), 1, "{e}");
    let scene = d.write("scene.toml", SPHERE);
    let out = prism(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        // A folder that cannot be made (missing ones are): its parent is a file.
        scene.join("missing/out.png").to_str().unwrap(),
    ]);
    let e = stderr(&out);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(e.matches("Not a directory").count(), 1, "{e}");
    assert!(!e.contains(".out.png."), "{e}");
}

#[test]
fn invalid_utf8_is_reported_with_its_line() {
    let d = Dir::new();
    let mut bytes = SPHERE.as_bytes().to_vec();
    let at = SPHERE.find("fov").unwrap();
    bytes.splice(at..at, *b"# caf\xe9\n");
    std::fs::write(d.path("scene.toml"), bytes).unwrap();
    let out = d.render(&d.path("scene.toml"), &[]);
    let e = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{e}");
    assert!(e.contains("scene.toml:5:6:") && e.contains("UTF-8"), "{e}");
}

#[test]
fn bounds_print_as_written_and_names_are_made_safe() {
    let d = Dir::new();
    let e = d.refuses(
        &with("transparency = 0.9", "transparency = 0.9\nambient = 5000"),
        &[],
        &["ambient", "[0, 1000]"],
    );
    assert!(!e.contains("3402823"), "{e}");
    let hostile = format!("\u{1b}[31mred\nball{}", "x".repeat(5_000_000));
    let text = with(
        "name = \"ball\"",
        &format!(
            "name = \"{}\"",
            hostile.replace('\n', "\\n").replace('\u{1b}', "\\u001b")
        ),
    )
    .replace("radius = 1", "radius = -1");
    let e = d.refuses(&text, &[], &["spheres[0]", "radius"]);
    assert!(e.len() < 1000, "a message of {} bytes", e.len());
    assert!(!e.contains('\u{1b}'), "{e:?}");
    assert_eq!(e.trim_end().lines().count(), 1, "{e:?}");
    // Names of things that do not exist, too.
    let text = with(
        "material = \"glass\"",
        "material = \"\\u001b]0;title\\u0007\"",
    );
    let e = d.refuses(&text, &[], &["no material named"]);
    assert!(!e.contains('\u{1b}') && !e.contains('\u{7}'), "{e:?}");
}

#[test]
fn tolerances_are_relative_to_the_shape() {
    let d = Dir::new();
    // A regular 400-gon: every corner turns by less than a degree.
    let vertices: Vec<String> = (0..400)
        .map(|i| {
            let a = i as f64 * std::f64::consts::TAU / 400.0;
            format!("[{}, {}, -10]", 3.0 * a.cos(), 3.0 * a.sin())
        })
        .collect();
    let gon = format!(
        "{SPHERE}\n[[polygons]]\nvertices = [{}]\n",
        vertices.join(", ")
    );
    let scene = d.write("scene.toml", &gon);
    let out = d.render(&scene, &[]);
    assert!(out.status.success(), "{}", stderr(&out));
    // Right-corner tetrahedra at large and small scales.
    for s in [1e11f64, 1e-9] {
        let text = format!(
            "[camera]\neye = [{}, {}, {}]\nlook_at = [0, 0, 0]\nfov = 40\n\
             [[lights]]\nposition = [{}, {}, {}]\n\
             [[tetrahedra]]\nvertices = [[0, 0, 0], [{s:e}, 0, 0], [0, {s:e}, 0], [0, 0, {s:e}]]\n",
            3.0 * s,
            2.0 * s,
            4.0 * s,
            2.0 * s,
            5.0 * s,
            3.0 * s
        );
        let scene = d.write("scene.toml", &text);
        let out = d.render(&scene, &[]);
        assert!(out.status.success(), "size {s}: {}", stderr(&out));
        let img = image::open(d.path("out.png")).unwrap().into_rgb8();
        assert!(
            img.pixels().any(|p| p.0 != [0, 0, 0]),
            "size {s}: nothing drawn"
        );
    }
    // A triangle whose f32 cross products underflow is refused, not drawn as nothing.
    d.refuses(
        &format!("{SPHERE}\n[[triangles]]\nvertices = [[0, 0, -1e-25], [1e-25, 0, -1e-25], [0, 1e-25, -1e-25]]\n"),
        &[],
        &["triangles[0]", "too small for f32"],
    );
    // Truly collinear or flat input is still refused.
    d.refuses(
        &format!("{SPHERE}\n[[polygons]]\nvertices = [[0, 0, -5], [1, 0, -5], [2, 1e-9, -5], [1, 1, -5]]\n"),
        &[],
        &["collinear"],
    );
}

#[test]
fn texture_fields_that_do_not_apply_are_refused() {
    let d = Dir::new();
    let checker =
        |extra: &str| format!("{SPHERE}\n[textures.c]\ntype = \"checker\"\nsize = 1\n{extra}\n");
    d.refuses(
        &checker("width = 2"),
        &[],
        &["textures.c", "`width` does not apply to a checker texture"],
    );
    d.refuses(
        &checker("path = \"missing.png\""),
        &[],
        &["`path` does not apply"],
    );
    d.refuses(
        &format!("{SPHERE}\n[textures.i]\ntype = \"image\"\npath = \"x.png\"\nsize = 3\n"),
        &[],
        &["`size` does not apply to a image texture"],
    );
}

#[test]
fn surface_colours_are_reflectances_and_lights_may_be_bright() {
    let d = Dir::new();
    d.refuses(
        &with("color = [0.9, 0.9, 1]", "color = [50, 0, 0]"),
        &[],
        &["materials.glass", "color", "[0, 1]"],
    );
    d.refuses(&format!("{SPHERE}\n[textures.c]\ntype = \"checker\"\nsize = 1\ncolors = [[1e38, 0, 0], [0, 0, 0]]\n"), &[], &["colors"]);
    // A light of 50 is a bright light; 1e38 is refused.
    let bright = SPHERE.replace(
        "position = [0, 10, 0]",
        "position = [0, 10, 0]\ncolor = [50, 50, 50]",
    );
    let scene = d.write("scene.toml", &bright);
    assert!(d.render(&scene, &[]).status.success());
    let text = SPHERE.replace(
        "position = [0, 10, 0]",
        "position = [0, 10, 0]\ncolor = [1e38, 0, 0]",
    );
    d.refuses(&text, &[], &["lights[0]", "color", "[0, 10000]"]);
}

#[cfg(feature = "viewer")]
#[test]
fn a_viewer_window_too_large_is_named_as_a_size_limit() {
    let out = Command::new(env!("CARGO_BIN_EXE_prism"))
        .args(["view", "--width", "16384", "--height", "16384"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let e = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{e}");
    assert!(
        e.contains("8192") && e.contains("window") && !e.contains("GPU"),
        "{e}"
    );
}

#[cfg(feature = "viewer")]
#[test]
fn a_missing_screenshot_folder_is_called_missing() {
    let out = Command::new(env!("CARGO_BIN_EXE_prism"))
        .args(["view", "--screenshot-dir", "/no/such/dir"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let e = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{e}");
    assert!(
        e.contains("No such file or directory") && !e.contains("not a directory"),
        "{e}"
    );
}

#[test]
fn a_panic_in_the_render_is_an_error_with_exit_code_1() {
    let d = Dir::new();
    let scene = d.write("scene.toml", SPHERE);
    let out = Command::new(env!("CARGO_BIN_EXE_prism"))
        .args(["render", scene.to_str().unwrap(), "-o"])
        .arg(d.path("out.png"))
        .arg("--quiet")
        .env("PRISM_INJECT_PANIC", "1")
        .output()
        .unwrap();
    let e = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{e}");
    assert!(e.contains("internal error"), "{e}");
    assert_eq!(d.others(&["scene.toml"]), Vec::<String>::new());
}

/// A box of perfect mirrors with 20 clear panes inside: every bounce crosses them all, so
/// one camera ray's path is a single chain as long as the ray budget allows.
fn mirror_chain() -> String {
    let mut s = String::from(
        "[camera]\neye = [0.1, 0.2, 0.3]\ndirection = [0.01, 0.02, -1]\nfov = 40\n\
         [render]\nmax_depth = 64\n[[lights]]\nposition = [0.5, 0.5, 0.5]\n\
         [materials.mirror]\nreflectivity = 1\n[materials.clear]\ntransparency = 1\n",
    );
    for f in BOX_FACES {
        s += &format!("[[polygons]]\nvertices = {f}\nmaterial = \"mirror\"\n");
    }
    for k in 0..20 {
        let z = -1.9 + k as f32 * 0.19;
        s += &format!(
            "[[polygons]]\nvertices = [[-1.9,-1.9,{z}],[1.9,-1.9,{z}],[1.9,1.9,{z}],[-1.9,1.9,{z}]]\n\
             material = \"clear\"\n"
        );
    }
    s
}

#[test]
fn the_longest_ray_chain_spends_the_budget_within_a_small_stack() {
    use prism::geometry::Ray;
    use prism::integrator::Integrator;
    use prism::scene::PreparedScene;
    use prism::scene_file::parse_scene;
    let scene = parse_scene(&mirror_chain(), Path::new("chain.toml"), Path::new(".")).unwrap();
    let prepared = PreparedScene::new(&scene);
    // Renders run on prism::render::thread_pool's threads; the deepest sample fits in half
    // of their stack (in a debug build too).
    let counts = std::thread::Builder::new()
        .stack_size(prism::limits::RENDER_STACK_BYTES / 2)
        .spawn(move || {
            let mut integrator = Integrator::new(&prepared, 0.0);
            let sample = integrator.trace_primary(
                prism::accel::Reach::After(0.0),
                || {
                    Ray::new(
                        glam::Vec3::ZERO,
                        glam::Vec3::new(0.01, 0.02, -1.0).normalize(),
                    )
                },
                prism::sampler::SampleStream::new(0, 0, 0),
            );
            assert!(sample.color.is_finite());
            integrator.counts
        })
        .unwrap()
        .join()
        .expect("the chain fits in the stack");
    assert_eq!(counts.secondary, prism::limits::RAY_BUDGET as u64);
}

#[test]
fn every_field_error_points_at_the_fields_own_line() {
    // Each scene has one bad value; the error names the line that holds it (marked `# <-`),
    // not its table's header. Spans come from the parsed file, not from searching its text.
    use prism::scene_file::parse_scene;
    let cases = [
        "[camera]\neye = [0, 0, 0]\nfov = 40\n\n[[spheres]]\nname = \"a\"\ncenter = [0, 0, -5]\n\
         radius = -1 # <-\n",
        "[camera]\neye = [0, 0, 0]\nfov = 40\n\n[[polygons]]\nvertices = [\n  [0, 0, -5],\n  \
         [1, 0, -5],\n  [1e300, 0, -5], # <-\n]\n",
        "[camera]\neye = [0, 0, 0]\nfov = 40\nup = [0, 1, 0]\nlook_at = [0, 0, 0] # <-\n",
        "[camera]\neye = [0, 0, 0]\nfov = 40\n\ndirection = [0, 1, 0] # <-\n",
        "[camera]\neye = [0, 0, 0]\nfov = 40\n\n[[tetrahedra]]\nname = \"flat\"\n\n\
         vertices = [[0, 0, -5], [1, 0, -5], [0, 1, -5], [1, 1, -5]] # <-\n",
        "[camera]\neye = [0, 0, 0]\nfov = 40\n\n[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\n\
         material = \"nowhere\" # <-\n",
        "[camera]\neye = [0, 0, 0]\nfov = 40\n\n[materials.m]\ncolor = [1, 0, 0]\n\
         texture = \"t\" # <-\n\n[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\nmaterial = \"m\"\n",
        "[camera]\neye = [0, 0, 0]\nfov = 40\n\n[render]\nwidth = 64\n\naa = 99 # <-\n",
    ];
    for text in cases {
        let marked = text.lines().position(|l| l.contains("# <-")).unwrap() + 1;
        let error = parse_scene(text, Path::new("lines.toml"), Path::new(".")).unwrap_err();
        assert_eq!(error.line(), Some(marked), "{error}\n{text}");
    }
}

/// Surfaces at one place cannot be parted by any hierarchy, so a ray near them tests each:
/// more than `limits::MAX_COINCIDENT` of them (copies of one triangle in a mesh, objects
/// placed at one spot) are refused at once, with the count and the object, and no file is
/// left. A few copies, as a careless export makes, still render.
#[test]
fn coincident_surfaces_past_the_limit_are_refused_at_once() {
    let d = Dir::new();
    let copies = |n: usize| format!("v 0 0 -5\nv 1 0 -5\nv 0 1 -5\n{}", "f 1 2 3\n".repeat(n));
    d.write("copies.obj", &copies(5000));
    let camera = "[camera]\neye = [0, 0, 0]\ndirection = [0, 0, -1]\nfov = 40\n\n";
    let start = std::time::Instant::now();
    d.refuses(
        &format!("{camera}[[meshes]]\nname = \"copies\"\npath = \"copies.obj\"\n"),
        &[],
        &[
            "5000 surfaces share one centre",
            "\"copies\"",
            "at most 4096",
        ],
    );
    let spheres = "[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\n".repeat(4097);
    d.refuses(
        &format!("{camera}{spheres}"),
        &[],
        &["4097 surfaces share one centre"],
    );
    assert!(start.elapsed() < std::time::Duration::from_secs(20));
    d.write("few.obj", &copies(50));
    let scene = d.write(
        "few.toml",
        &format!("{camera}[[meshes]]\npath = \"few.obj\"\n"),
    );
    let out = d.render(&scene, &[]);
    assert!(out.status.success(), "{}", stderr(&out));
}
