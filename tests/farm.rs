//! Beyond one machine: regions and tiles equal to the same pixels of the full render,
//! `prism stitch` and its refusals, animation frames, output formats and colour, a clean
//! stop, and the GNU parallel recipe of docs/farm.md run for real.

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

mod common;
use common::{Dir, prism, stderr};

/// Runs prism and asserts it succeeded.
fn ok(args: &[&str]) -> String {
    let out = prism(args);
    assert!(out.status.success(), "{args:?}: {}", stderr(&out));
    stderr(&out)
}

/// Runs prism and asserts bad input: exit 2, and each of `needles` in the message.
fn refused(args: &[&str], needles: &[&str]) -> String {
    let out = prism(args);
    let e = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {e}");
    assert!(!e.contains("panicked"), "{e}");
    for n in needles {
        assert!(e.contains(n), "{args:?}: expected {n:?} in: {e}");
    }
    e
}

fn rgb8(path: &Path) -> image::RgbImage {
    image::open(path).unwrap().into_rgb8()
}

fn turntable() -> String {
    concat!(env!("CARGO_MANIFEST_DIR"), "/assets/scenes/turntable.toml").to_string()
}

const SIZE: [&str; 4] = ["--width", "96", "--height", "72"];

/// The PNG text chunk that places a tile, if any.
fn placement_chunk(path: &Path) -> Option<String> {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let reader = decoder.read_info().unwrap();
    reader
        .info()
        .uncompressed_latin1_text
        .iter()
        .find(|t| t.keyword == "prism placement")
        .map(|t| t.text.clone())
}

/// Regions equal the same pixels of the full frame, with adaptive sampling (which looks at
/// neighbours), with a stochastic scene (soft shadows), and at any thread count; their
/// file is the region's size and records its place.
#[test]
fn regions_equal_the_same_pixels_of_the_full_render() {
    let d = Dir::new();
    let soft = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/scenes/soft_shadows.toml"
    );
    for (scene, extra) in [
        (None, vec!["--adaptive"]),
        (None, vec!["--aa", "3"]),
        (Some(soft), vec!["--adaptive", "--samples", "16"]),
    ] {
        let mut base: Vec<&str> = vec!["render", "--quiet"];
        base.extend(scene);
        base.extend(SIZE);
        base.extend(extra.iter().copied());
        let full = d.s("full.png");
        ok(&[&base[..], &["-o", &full]].concat());
        let full = rgb8(Path::new(&full));
        for (region, threads) in [
            ("0,0,96,72", "1"),
            ("13,7,50,33", "1"),
            ("90,60,96,72", "2"),
            ("0,35,96,36", "2"),
        ] {
            let out = d.s("region.png");
            ok(&[
                &base[..],
                &["--region", region, "--threads", threads, "-o", &out],
            ]
            .concat());
            let part = rgb8(Path::new(&out));
            let r: Vec<u32> = region.split(',').map(|n| n.parse().unwrap()).collect();
            assert_eq!(part.dimensions(), (r[2] - r[0], r[3] - r[1]), "{region}");
            for (x, y, px) in part.enumerate_pixels() {
                assert_eq!(
                    px,
                    full.get_pixel(r[0] + x, r[1] + y),
                    "{scene:?} {extra:?} {region}: pixel ({x}, {y})"
                );
            }
            let chunk = placement_chunk(Path::new(&out));
            if region == "0,0,96,72" {
                assert_eq!(chunk, None, "a whole frame is no tile");
            } else {
                assert_eq!(chunk, Some(format!("{region} of 96x72")));
            }
        }
    }
}

#[test]
fn tiles_stitch_into_the_full_render_and_bad_sets_are_refused() {
    let d = Dir::new();
    let base = [
        "render",
        "--quiet",
        "--width",
        "64",
        "--height",
        "50",
        "--adaptive",
    ];
    let mut tiles = Vec::new();
    for i in 0..4 {
        let out = d.s(&format!("t{i}.png"));
        ok(&[&base[..], &["--tile", &format!("{i}/4"), "-o", &out]].concat());
        tiles.push(out);
    }
    // The bands: 50 rows in 4 tiles of 12 or 13 rows.
    assert_eq!(rgb8(Path::new(&tiles[0])).dimensions(), (64, 12));
    assert_eq!(rgb8(Path::new(&tiles[3])).dimensions(), (64, 13));
    let full = d.s("full.png");
    ok(&[&base[..], &["-o", &full]].concat());
    let stitched = d.s("stitched.png");
    // In any order.
    let e = ok(&[
        "stitch", &tiles[2], &tiles[0], &tiles[3], &tiles[1], "-o", &stitched,
    ]);
    assert!(e.contains("stitched 4 tiles"), "{e}");
    assert_eq!(rgb8(Path::new(&stitched)), rgb8(Path::new(&full)));

    refused(
        &["stitch", &tiles[0], &tiles[1], &tiles[3], "-o", &stitched],
        &["is a tile missing", "row 25"],
    );
    refused(
        &[
            "stitch", &tiles[0], &tiles[1], &tiles[1], &tiles[2], &tiles[3], "-o", &stitched,
        ],
        &["overlap", "t1.png"],
    );
    refused(
        &["stitch", &tiles[0], &full, "-o", &stitched],
        &["full.png", "records no place"],
    );
    // A tile of another frame size.
    let other = d.s("other.png");
    ok(&[
        "render", "--quiet", "--width", "64", "--height", "60", "--tile", "3/4", "-o", &other,
    ]);
    refused(
        &[
            "stitch", &tiles[0], &tiles[1], &tiles[2], &other, "-o", &stitched,
        ],
        &["64×60", "64×50"],
    );
    // 8-bit tiles cannot become a float image, nor a missing file a tile.
    refused(
        &[
            "stitch",
            &tiles[0],
            &tiles[1],
            &tiles[2],
            &tiles[3],
            "-o",
            &d.s("s.exr"),
        ],
        &["8-bit", ".png or .jpg"],
    );
    refused(
        &["stitch", &d.s("nothing.png"), "-o", &stitched],
        &["nothing.png", "No such file"],
    );
    // Float tiles stitch losslessly too, through their sidecars.
    let mut exr = Vec::new();
    for i in 0..2 {
        let out = d.s(&format!("h{i}.exr"));
        ok(&[
            "render",
            "--quiet",
            "--width",
            "40",
            "--height",
            "30",
            "--tile",
            &format!("{i}/2"),
            "-o",
            &out,
        ]);
        assert!(d.path(&format!("h{i}.exr.placement")).exists());
        exr.push(out);
    }
    let whole = d.s("whole.exr");
    ok(&[
        "render", "--quiet", "--width", "40", "--height", "30", "-o", &whole,
    ]);
    assert!(
        !d.path("whole.exr.placement").exists(),
        "a whole frame has no sidecar"
    );
    let stitched = d.s("stitched.pfm");
    ok(&["stitch", &exr[1], &exr[0], "-o", &stitched]);
    // Two float formats hold the same pixels: the message tells them apart by format.
    let pfm_tile = d.s("h1.pfm");
    ok(&[
        "render", "--quiet", "--width", "40", "--height", "30", "--tile", "1/2", "-o", &pfm_tile,
    ]);
    refused(
        &["stitch", &exr[0], &pfm_tile, "-o", &d.s("mixed.pfm")],
        &[
            "32-bit float RGB pixels in PFM",
            "32-bit float RGB pixels in OpenEXR",
        ],
    );
    let a = image::open(&whole).unwrap().into_rgb32f();
    let b = prism::render::read_image(Path::new(&stitched), 100)
        .unwrap()
        .image
        .into_rgb32f();
    assert_eq!(a, b);
}

#[test]
fn bad_regions_and_tiles_are_refused_before_rendering() {
    let d = Dir::new();
    let out = d.s("out.png");
    let r = |extra: &[&str], needles: &[&str]| {
        refused(
            &[
                &[
                    "render", "--quiet", "--width", "40", "--height", "30", "-o", &out,
                ][..],
                extra,
            ]
            .concat(),
            needles,
        )
    };
    r(&["--region", "30,0,10,30"], &["X0 < X1"]);
    r(&["--region", "0,0,10,10,"], &["X0,Y0,X1,Y1"]);
    r(
        &["--region", "0,0,41,30"],
        &["does not fit in the 40×30 image"],
    );
    r(&["--tile", "4/4"], &["tile 4/4", "from 0 to N−1"]);
    r(&["--tile", "0/31"], &["1 to 30 tiles"]);
    r(&["--tile", "1"], &["expected I/N"]);
    assert!(
        prism(&["render", "--tile", "0/2", "--region", "0,0,1,1"])
            .status
            .code()
            == Some(2)
    );
    assert_eq!(d.files(), Vec::<String>::new(), "nothing written");
}

/// Each format follows its extension and opens in ImageMagick; the float formats hold the
/// linear values unclamped; 16-bit PNG and JPEG quality are honoured; a mismatched option
/// is refused.
#[test]
fn every_output_format_is_written_and_opens() {
    let d = Dir::new();
    let base = ["render", "--quiet", "--width", "48", "--height", "36"];
    let png8 = d.s("a.png");
    ok(&[&base[..], &["-o", &png8]].concat());
    let png16 = d.s("b.png");
    ok(&[&base[..], &["--bits", "16", "-o", &png16]].concat());
    let jpg = d.s("c.jpg");
    ok(&[&base[..], &["--quality", "95", "-o", &jpg]].concat());
    let small_jpg = d.s("c5.jpeg");
    ok(&[&base[..], &["--quality", "5", "-o", &small_jpg]].concat());
    let exr = d.s("d.exr");
    ok(&[&base[..], &["-o", &exr]].concat());
    let pfm = d.s("e.pfm");
    ok(&[&base[..], &["-o", &pfm]].concat());

    let eight = rgb8(Path::new(&png8));
    let sixteen = image::open(&png16).unwrap().into_rgb16();
    for (a, b) in eight.pixels().zip(sixteen.pixels()) {
        for c in 0..3 {
            // The 16-bit value rounds to the 8-bit one.
            assert!(
                (b[c] as f32 / 257.0 - a[c] as f32).abs() <= 0.51,
                "{a:?} {b:?}"
            );
        }
    }
    let jpeg = rgb8(Path::new(&jpg));
    let worst = eight
        .iter()
        .zip(jpeg.iter())
        .map(|(a, b)| a.abs_diff(*b))
        .max()
        .unwrap();
    assert!(worst < 40, "quality 95 stays close: {worst}");
    assert!(std::fs::metadata(&small_jpg).unwrap().len() < std::fs::metadata(&jpg).unwrap().len());
    let float = image::open(&exr).unwrap().into_rgb32f();
    let pf = prism::render::read_image(Path::new(&pfm), 100)
        .unwrap()
        .image
        .into_rgb32f();
    assert_eq!(float, pf, "EXR and PFM hold the same values");
    // The seed's highlights are brighter than white: a float file keeps them.
    assert!(float.iter().any(|&v| v > 1.0), "unclamped values");
    // An unclamped mean is never below the clamped one, and equals it (to 8-bit rounding)
    // wherever no subsample was brighter than white: nearly everywhere.
    let mut agree = 0;
    for (f, e) in float.pixels().zip(eight.pixels()) {
        for c in 0..3 {
            assert!(f[c] * 255.0 >= e[c] as f32 - 0.51, "{f:?} {e:?}");
            agree += ((f[c].min(1.0) * 255.0 - e[c] as f32).abs() <= 0.51) as usize;
        }
    }
    assert!(agree * 100 >= 95 * 3 * 48 * 36, "{agree}");

    // ImageMagick reads every one it has a reader for, at its size and depth (Debian's
    // ImageMagick reads EXR only with the "extra" coders installed; the `image` crate read
    // it above).
    if let Ok(formats) = Command::new("identify").args(["-list", "format"]).output() {
        let formats = String::from_utf8_lossy(&formats.stdout).to_string();
        let reads = |format: &str| {
            formats.lines().any(|line| {
                let mut words = line.split_whitespace();
                words.next().map(|w| w.trim_end_matches('*')) == Some(format)
                    && words.nth(1).is_some_and(|mode| mode.starts_with('r'))
            })
        };
        assert!(reads("PNG") && reads("PFM"), "{formats}");
        for (file, depth) in [
            (&png8, "8"),
            (&png16, "16"),
            (&jpg, "8"),
            (&exr, "16"),
            (&pfm, "32"),
        ] {
            let extension = Path::new(file).extension().unwrap().to_str().unwrap();
            if !reads(&extension.to_uppercase()) {
                eprintln!("ImageMagick has no reader for {extension}: not asked");
                continue;
            }
            let out = Command::new("identify")
                .args(["-format", "%w %h %z", file])
                .output()
                .unwrap();
            let text = String::from_utf8_lossy(&out.stdout);
            assert!(
                out.status.success(),
                "{file}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            assert!(text.starts_with("48 36"), "{file}: {text}");
            // EXR's half floats are reported as 16 bits; what matters is that it is HDR.
            if !file.ends_with(".exr") {
                assert_eq!(
                    text.split_whitespace().nth(2),
                    Some(depth),
                    "{file}: {text}"
                );
            }
        }
    } else {
        eprintln!("skipped the ImageMagick check: no `identify` here");
    }

    let out = d.s("x.jpg");
    refused(
        &[&base[..], &["--bits", "16", "-o", &out]].concat(),
        &["16 bits", "JPEG is not PNG"],
    );
    refused(
        &[&base[..], &["--srgb", "-o", &d.s("x.exr")]].concat(),
        &["OpenEXR holds linear values"],
    );
    refused(
        &[&base[..], &["--quality", "50", "-o", &d.s("x.png")]].concat(),
        &["--quality is a JPEG option"],
    );
    refused(
        &[&base[..], &["--quality", "0", "-o", &out]].concat(),
        &["quality"],
    );
    refused(
        &[&base[..], &["--exposure", "40", "-o", &d.s("x.png")]].concat(),
        &["--exposure 40", "stops"],
    );
}

/// `--srgb` applies the sRGB curve and `--exposure` scales by powers of two, to the
/// linear values the default writes (which stays as it was).
#[test]
fn colour_encoding_and_exposure_do_what_they_say() {
    let d = Dir::new();
    let base = [
        "render", "--quiet", "--width", "48", "--height", "36", "--bits", "16",
    ];
    let run = |extra: &[&str], name: &str| {
        let out = d.s(name);
        ok(&[&base[..], extra, &["-o", &out]].concat());
        image::open(&out).unwrap().into_rgb16()
    };
    let linear = run(&[], "lin.png");
    let srgb = run(&["--srgb"], "srgb.png");
    let darker = run(&["--exposure", "-1"], "dark.png");
    let brighter = run(&["--srgb", "--exposure", "1"], "bright.png");
    let encode = |v: f32| {
        if v <= 0.003_130_8 {
            12.92 * v
        } else {
            1.055 * v.powf(1.0 / 2.4) - 0.055
        }
    };
    // Each file rounds its own value once: the encoded value lies within what the linear
    // file's value, give or take its half step, encodes to (and one step of its own).
    let within = |got: u16, linear: u16, gain: f32, curve: &dyn Fn(f32) -> f32| {
        let at = |v: f32| curve((gain * v / 65535.0).clamp(0.0, 1.0)) * 65535.0;
        let (lo, hi) = (at(linear as f32 - 0.5) - 1.0, at(linear as f32 + 0.5) + 1.0);
        (lo..=hi).contains(&(got as f32))
    };
    let identity = |v: f32| v;
    for (((l, s), dk), b) in linear
        .pixels()
        .zip(srgb.pixels())
        .zip(darker.pixels())
        .zip(brighter.pixels())
    {
        for c in 0..3 {
            assert!(
                within(s[c], l[c], 1.0, &encode),
                "srgb: {} from {}",
                s[c],
                l[c]
            );
            assert!(
                within(dk[c], l[c], 0.5, &identity),
                "half: {} from {}",
                dk[c],
                l[c]
            );
            assert!(
                within(b[c], l[c], 2.0, &encode),
                "bright: {} from {}",
                b[c],
                l[c]
            );
        }
    }
    // The scene file may ask for the curve too; the flag and the table agree.
    let scene = d.path("srgb.toml");
    let seed = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/scenes/seed.toml"
    ))
    .unwrap();
    let text = seed.replacen("[render]", "[render]\nencoding = \"srgb\"", 1);
    assert_ne!(text, seed, "the seed scene file has a [render] table");
    let assets = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/scenes/");
    std::fs::write(
        &scene,
        text.replace("path = \"../", &format!("path = \"{assets}../")),
    )
    .unwrap();
    let from_file = d.s("file.png");
    ok(&[&base[..], &[scene.to_str().unwrap(), "-o", &from_file]].concat());
    let flagged = d.s("flag.png");
    let seed_file = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/scenes/seed.toml");
    ok(&[&base[..], &[seed_file, "--srgb", "-o", &flagged]].concat());
    assert_eq!(
        image::open(&from_file).unwrap().into_rgb16(),
        image::open(&flagged).unwrap().into_rgb16()
    );
    let bad = d.path("bad.toml");
    std::fs::write(
        &bad,
        seed.replacen("[render]", "[render]\nencoding = \"gamma\"", 1),
    )
    .unwrap();
    refused(
        &["render", bad.to_str().unwrap(), "-o", &d.s("x.png")],
        &["bad.toml:", "`encoding` must be \"linear\""],
    );
}

/// Frames rendered by one command each build on the frame before (only what moved is
/// prepared again): a frame in which one of two opaque bunnies moves, one in which a light
/// moves, and one in which only the camera does are each the image that frame rendered
/// alone makes.
#[test]
fn frames_built_on_the_frame_before_equal_frames_rendered_alone() {
    let d = Dir::new();
    let bunny = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/meshes/bunny.obj");
    let scene = d.write(
        "moving.toml",
        &format!(
            "[camera]\neye = [0, 5, 22]\nlook_at = [0, 1, 0]\nfov = 40\n\n\
             [[lights]]\nposition = [20, 40, 30]\n\n\
             [[lights]]\nposition = [-20, 30, 10]\ncolor = [0.4, 0.4, 0.5]\n\n\
             [[polygons]]\nname = \"floor\"\n\
             vertices = [[-20, 0, 20], [20, 0, 20], [20, 0, -20], [-20, 0, -20]]\n\n\
             [[meshes]]\nname = \"still\"\npath = \"{bunny}\"\ntranslate = [-4, 0, 0]\n\n\
             [[meshes]]\nname = \"moving\"\npath = \"{bunny}\"\nsmooth = false\n\
             translate = [4, 0, 0]\n\n\
             [animation]\nframes = 4\n\n\
             [[animation.track]]\ntarget = \"moving\"\nfield = \"translate\"\n\
             interpolation = \"step\"\n\
             keys = [{{ frame = 0, value = [4, 0, 0] }}, {{ frame = 1, value = [3, 0, 2] }}]\n\n\
             [[animation.track]]\ntarget = \"lights[1]\"\nfield = \"position\"\n\
             interpolation = \"step\"\n\
             keys = [{{ frame = 0, value = [-20, 30, 10] }}, {{ frame = 2, value = [-10, 20, 25] }}]\n\n\
             [[animation.track]]\ntarget = \"camera\"\nfield = \"eye\"\n\
             interpolation = \"step\"\n\
             keys = [{{ frame = 0, value = [0, 5, 22] }}, {{ frame = 3, value = [3, 6, 21] }}]\n"
        ),
    );
    let scene = scene.to_str().unwrap();
    let base = [
        "render", scene, "--quiet", "--width", "120", "--height", "90",
    ];
    ok(&[&base[..], &["--frames", "all", "-o", &d.s("f_{frame}.png")]].concat());
    let frame = |n: u32| rgb8(&d.path(&format!("f_{n}.png")));
    for n in 1..4 {
        assert_ne!(frame(n), frame(n - 1), "frame {n} moves something");
        let alone = d.s(&format!("alone_{n}.png"));
        ok(&[&base[..], &["--frame", &n.to_string(), "-o", &alone]].concat());
        let (alone, together) = (rgb8(Path::new(&alone)), frame(n));
        let differ = alone
            .pixels()
            .zip(together.pixels())
            .filter(|(a, b)| a != b)
            .count();
        assert_eq!(
            differ, 0,
            "frame {n}: pixels that differ from the frame rendered alone"
        );
    }
}

/// Frames of an animation: a template names each file, `--skip-existing` renders only what
/// is missing, the frame may come from the environment, and every frame is the same image
/// however many threads render it.
#[test]
fn animation_frames_render_to_a_template() {
    let d = Dir::new();
    let scene = turntable();
    let template = d.s("f_{frame:03}.png");
    let base = [
        "render", &scene, "--quiet", "--width", "64", "--height", "48",
    ];
    ok(&[&base[..], &["--frames", "0..3", "-o", &template]].concat());
    assert_eq!(d.files(), ["f_000.png", "f_001.png", "f_002.png"]);
    let frame = |n: u32| rgb8(&d.path(&format!("f_{n:03}.png")));
    assert_ne!(frame(0), frame(1), "the frames move");
    // One frame alone, on one thread, from the environment as a Slurm array task would.
    let alone = d.s("alone.png");
    let out = Command::new(env!("CARGO_BIN_EXE_prism"))
        .args(base)
        .args(["--threads", "1", "--frame-from-env", "TASK", "-o", &alone])
        .env("TASK", "2")
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(rgb8(Path::new(&alone)), frame(2));
    // A rerun skips what exists (and says so, without --quiet).
    std::fs::remove_file(d.path("f_001.png")).unwrap();
    let loud: Vec<&str> = base.iter().copied().filter(|&a| a != "--quiet").collect();
    let e = ok(&[
        &loud[..],
        &["--frames", "0..=2", "--skip-existing", "-o", &template],
    ]
    .concat());
    assert_eq!(e.matches("skipped").count(), 2, "{e}");
    assert_eq!(e.matches("rendered").count(), 1, "{e}");
    assert_eq!(frame(1), {
        let one = d.s("one.png");
        ok(&[&base[..], &["--frame", "1", "-o", &one]].concat());
        rgb8(Path::new(&one))
    });

    refused(
        &[&base[..], &["--frames", "0..3", "-o", &d.s("same.png")]].concat(),
        &["3 frames would all be written to one file"],
    );
    refused(
        &[&base[..], &["--frame", "48", "-o", &d.s("x.png")]].concat(),
        &["frame 48", "48 frames, 0 to 47"],
    );
    refused(
        &[&base[..], &["--frames", "all", "-o", &d.s("{frames}.png")]].concat(),
        &["unknown placeholder {frames}"],
    );
    refused(
        &["render", "--frame", "1", "-o", &d.s("x.png")],
        &["no [animation]"],
    );
    let out = Command::new(env!("CARGO_BIN_EXE_prism"))
        .args(base)
        .args([
            "--frame-from-env",
            "NO_SUCH_VARIABLE_HERE",
            "-o",
            &d.s("x.png"),
        ])
        .env_remove("NO_SUCH_VARIABLE_HERE")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("the environment has no NO_SUCH_VARIABLE_HERE"),
        "{}",
        stderr(&out)
    );
    // A variable that is there but not text is called that, not missing.
    use std::os::unix::ffi::OsStrExt;
    let out = Command::new(env!("CARGO_BIN_EXE_prism"))
        .args(base)
        .args(["--frame-from-env", "TASK", "-o", &d.s("x.png")])
        .env("TASK", std::ffi::OsStr::from_bytes(b"\xff\xfe"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("is not text"), "{}", stderr(&out));
    // A frame past any animation's is called that, not a range of the wrong form.
    refused(
        &[&base[..], &["--frames", "0..=4294967295", "-o", &template]].concat(),
        &["at most 1000000 frames, 0 to 999999"],
    );
}

/// Ctrl+C stops a render within a pass: without --write-partial nothing is left; with it,
/// the image so far is written (some pixels with one subsample more than others) and the
/// statistics say it is incomplete. Either way the exit status is 130.
#[cfg(unix)]
#[test]
fn a_signal_stops_the_render_within_a_pass() {
    let d = Dir::new();
    // (the statistics, the stderr) of a render stopped by SIGINT about 1.5 s into it.
    let stopped = |partial: bool| {
        let out = d.s("big.png");
        let stats = d.s("stats.json");
        let mut args = vec![
            "render",
            "--width",
            "4000",
            "--height",
            "3000",
            "--aa",
            "2",
            "--quiet",
            "--stats-json",
            &stats,
            "-o",
            &out,
        ];
        if partial {
            args.push("--write-partial");
        }
        let child = Command::new(env!("CARGO_BIN_EXE_prism"))
            .args(&args)
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // Wait until the worker threads run, then a while: the passes are running (each
        // takes more than a second here). Nothing is on disk while they do.
        let start = Instant::now();
        let tasks = format!("/proc/{}/task", child.id());
        while std::fs::read_dir(&tasks).map_or(0, |t| t.count()) < 3 {
            assert!(
                start.elapsed() < Duration::from_secs(30),
                "the workers never started"
            );
            std::thread::sleep(Duration::from_millis(20));
        }
        std::thread::sleep(Duration::from_millis(1500));
        assert!(
            d.files().is_empty(),
            "nothing on disk mid-render: {:?}",
            d.files()
        );
        let sent = Instant::now();
        assert!(
            Command::new("kill")
                .args(["-INT", &child.id().to_string()])
                .status()
                .unwrap()
                .success()
        );
        let result = child.wait_with_output().unwrap();
        assert!(
            sent.elapsed() < Duration::from_secs(10),
            "{:?}",
            sent.elapsed()
        );
        let e = stderr(&result);
        assert_eq!(result.status.code(), Some(130), "{e}");
        let json: Option<serde_json::Value> = std::fs::read_to_string(&stats)
            .ok()
            .map(|t| serde_json::from_str(&t).unwrap());
        let files = d.files();
        for f in &files {
            std::fs::remove_file(d.path(f)).unwrap();
        }
        (json, e, files)
    };
    let (json, e, files) = stopped(false);
    assert!(e.contains("no output was written"), "{e}");
    assert_eq!(files, Vec::<String>::new(), "no file, no temporary file");
    assert!(json.is_none());

    // A signal that lands just between two passes stops before the next band: try again
    // then, to see a stop inside a pass.
    for attempt in 0.. {
        let (json, e, files) = stopped(true);
        assert!(e.contains("the image so far was written"), "{e}");
        assert_eq!(files, ["big.png", "stats.json"]);
        let json = json.unwrap();
        assert_eq!(json["complete"], false);
        let passes = json["passes"].as_f64().unwrap();
        let spp = json["samples_per_pixel"].as_f64().unwrap();
        assert!(passes < 4.0, "{json}");
        if spp > passes && spp < passes + 1.0 || attempt == 2 {
            assert!(
                spp > passes && spp < passes + 1.0,
                "stopped inside a pass: {json}"
            );
            break;
        }
    }
}

/// `--threads N` bounds the whole process, reading the mesh and building its hierarchy
/// as well as tracing: a farm that packs N-thread jobs onto a node gets no more threads
/// than it asked for. Threads once started stay until the process ends, so sampling the
/// process's thread count as it runs sees every one.
#[test]
fn threads_bound_loading_and_building_too() {
    let d = Dir::new();
    // A grid of 2 × 200² triangles: enough text that it is read in parallel pieces.
    let n = 200;
    let mut obj = String::new();
    for j in 0..=n {
        for i in 0..=n {
            obj += &format!("v {} {} 0\n", i as f32 / n as f32, j as f32 / n as f32);
        }
    }
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i + 1;
            obj += &format!(
                "f {a} {} {}\nf {a} {} {}\n",
                a + 1,
                a + n + 2,
                a + n + 2,
                a + n + 1
            );
        }
    }
    d.write("grid.obj", &obj);
    let scene = d.write(
        "grid.toml",
        "[camera]\neye = [0.5, 0.5, 2]\ndirection = [0, 0, -1]\nfov = 50\n\n\
         [[lights]]\nposition = [0, 0, 5]\n\n\
         [[meshes]]\npath = \"grid.obj\"\n",
    );
    let most_threads = |threads: &str| {
        let out = d.s(&format!("grid-{threads}.png"));
        let mut child = Command::new(env!("CARGO_BIN_EXE_prism"))
            .args([
                "render",
                scene.to_str().unwrap(),
                "--width",
                "64",
                "--height",
                "48",
            ])
            .args(["--quiet", "--threads", threads, "-o", &out])
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let tasks = format!("/proc/{}/task", child.id());
        let mut most = 0;
        while child.try_wait().unwrap().is_none() {
            most = most.max(std::fs::read_dir(&tasks).map_or(0, |t| t.count()));
            std::thread::sleep(Duration::from_millis(1));
        }
        let result = child.wait_with_output().unwrap();
        assert!(result.status.success(), "{}", stderr(&result));
        most
    };
    // The main thread, the one that watches for signals, and the workers.
    for (threads, expected) in [("1", 3), ("2", 4)] {
        let most = most_threads(threads);
        assert!(
            (1..=expected).contains(&most),
            "--threads {threads}: the process ran {most} threads, at most {expected} expected"
        );
    }
}

/// A black 8-bit PNG of `side`², placed as `placement` says.
fn placed_png(path: &Path, side: u32, placement: &str) {
    let file = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
    let mut encoder = png::Encoder::new(file, side, side);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder
        .add_text_chunk("prism placement".into(), placement.into())
        .unwrap();
    let mut writer = encoder.write_header().unwrap();
    writer
        .write_image_data(&vec![0; (side * side * 3) as usize])
        .unwrap();
    writer.finish().unwrap();
}

/// `prism stitch` decides from the tiles' headers before it decodes a pixel, so a set that
/// cannot make a frame costs no pixel memory; it opens only regular files (a FIFO tile or
/// a sidecar linked to /dev/zero is refused at once).
#[test]
fn stitch_reads_headers_first_and_only_regular_files() {
    let d = Dir::new();
    // Five copies of one 4096² tile (48 MiB each, decoded) claiming the whole frame: under
    // a 200 MiB address-space limit, only refusing before decoding can answer.
    let mut tiles = Vec::new();
    for i in 0..5 {
        let path = d.path(&format!("big{i}.png"));
        placed_png(&path, 4096, "0,0,4096,4096 of 4096x4096");
        tiles.push(path.to_str().unwrap().to_string());
    }
    let command = format!(
        "ulimit -v 200000; exec \"$0\" stitch {} -o {}",
        tiles.join(" "),
        d.s("out.png")
    );
    let out = Command::new("bash")
        .args(["-c", &command, env!("CARGO_BIN_EXE_prism")])
        .output()
        .unwrap();
    let e = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{e}");
    assert!(e.contains("overlap"), "{e}");
    // A frame larger than any render is refused from the header too.
    placed_png(&d.path("huge.png"), 8, "0,0,8,8 of 100000x8");
    refused(
        &["stitch", &d.s("huge.png"), "-o", &d.s("out.png")],
        &["100000×8", "at most 16384"],
    );

    let fifo = d.path("fifo.png");
    if Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success()
    {
        let start = Instant::now();
        refused(
            &["stitch", fifo.to_str().unwrap(), "-o", &d.s("out.png")],
            &["fifo.png", "not a regular file"],
        );
        assert!(start.elapsed() < Duration::from_secs(10));
    }
    // A float tile whose sidecar is /dev/zero.
    let tile = d.s("t.pfm");
    ok(&[
        "render", "--quiet", "--width", "8", "--height", "6", "--tile", "0/2", "-o", &tile,
    ]);
    std::fs::remove_file(d.path("t.pfm.placement")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", d.path("t.pfm.placement")).unwrap();
    refused(
        &["stitch", &tile, "-o", &d.s("out.pfm")],
        &["t.pfm.placement", "not a regular file"],
    );
    assert!(!d.path("out.png").exists() && !d.path("out.pfm").exists());
}

/// The exit statuses are in --help, as a farm's scripts need them.
#[test]
fn help_lists_the_exit_statuses() {
    for args in [
        &["--help"][..],
        &["render", "--help"],
        &["stitch", "--help"],
    ] {
        let out = prism(args);
        let text = String::from_utf8_lossy(&out.stdout);
        for needle in [
            "Exit status:",
            "0    done",
            "2    bad input",
            "130  stopped by Ctrl+C",
        ] {
            assert!(text.contains(needle), "{args:?}: {needle:?} in {text}");
        }
    }
}

/// Runs tests/farm/NAME with the prism binary and a work folder of its own: its outcome
/// and everything it printed.
fn run_script(name: &str) -> (Output, String) {
    let d = Dir::new();
    let script = format!("{}/tests/farm/{name}", env!("CARGO_MANIFEST_DIR"));
    let out = Command::new("bash")
        .args([&script, env!("CARGO_BIN_EXE_prism"), &d.s("work")])
        .output()
        .unwrap();
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), stderr(&out));
    (out, text)
}

/// The GNU parallel recipe of docs/farm.md (tests/farm/parallel.sh): tiles rendered by
/// `parallel` and stitched, and frames rendered one job each, equal to one process's
/// render bit for bit.
#[test]
fn the_gnu_parallel_recipe_reproduces_one_process_bit_for_bit() {
    if !common::tools_present("the GNU parallel recipe", &["parallel", "compare"]) {
        return;
    }
    let (out, text) = run_script("parallel.sh");
    assert!(out.status.success(), "{text}");
    assert!(text.contains("farm recipe: all images equal"), "{text}");
    assert_eq!(text.matches("same:").count(), 2 + 12, "{text}");
}

/// The Slurm recipe of docs/farm.md (tests/farm/slurm.sh): a one-node Slurm cluster started
/// here, a job array of tiles with a stitch job that waits for it, and a job array of
/// frames, each result equal bit for bit to a render in one process. It needs root, Slurm
/// and munge; where the cluster cannot be started the script says why and the test skips.
#[cfg(unix)]
#[test]
fn the_slurm_recipe_reproduces_one_process_bit_for_bit() {
    let (out, text) = run_script("slurm.sh");
    if out.status.code() == Some(3) {
        eprintln!("skipped: {text}");
        return;
    }
    assert!(out.status.success(), "{text}");
    assert!(text.contains("slurm recipe: all images equal"), "{text}");
    assert_eq!(
        text.matches("COMPLETED exit 0:0").count(),
        4 + 1 + 8,
        "{text}"
    );
}
