//! Values that used to pass silently wrong, and messages that used to mislead (issue 30):
//! arrays with extra elements, a byte-order mark in an OBJ, the inclusive minimum length,
//! one thinness rule for every shape with an extent, "did you mean", plain type names with
//! the entry named, and MTL values checked as written.

use std::path::{Path, PathBuf};

const CAMERA: &str = "[camera]\neye = [0, 0, 0]\ndirection = [0, 0, -1]\nfov = 40\n\n";

fn parse(text: &str) -> Result<prism::scene::Scene, String> {
    parse_in(text, Path::new("."))
}

fn parse_in(text: &str, dir: &Path) -> Result<prism::scene::Scene, String> {
    let source = format!("{CAMERA}{text}");
    prism::scene_file::parse_scene(&source, &dir.join("scene.toml"), dir).map_err(|e| e.to_string())
}

fn refused(text: &str, needles: &[&str]) {
    let e = parse(text)
        .err()
        .unwrap_or_else(|| panic!("accepted: {text}"));
    for n in needles {
        assert!(e.contains(n), "expected {n:?} in: {e}");
    }
}

#[test]
fn arrays_with_extra_elements_are_refused_as_short_ones_are() {
    refused(
        "[[spheres]]\ncenter = [0, 0, -5, 99, \"x\", true]\nradius = 1\n",
        &["scene.toml:7", "spheres[0]", "6 values", "exactly 3"],
    );
    refused(
        "[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\nrotate = [1, 2, 3, 4, 5]\n",
        &["5 values", "exactly 3"],
    );
    refused(
        "[[triangles]]\nvertices = [[0, 0, -5], [1, 0, -5], [0, 1, -5], [1, 1, -5]]\n",
        &["triangles[0]", "4 values", "exactly 3"],
    );
    refused(
        "[[spheres]]\ncenter = [0, 0]\nradius = 1\n",
        &["2 values", "exactly 3"],
    );
    // An animation key of five angles for a rotation is refused at load, too.
    refused(
        "[[spheres]]\nname = \"b\"\ncenter = [0, 0, -5]\nradius = 1\n\n[animation]\nframes = 2\n\
         [[animation.track]]\ntarget = \"b\"\nfield = \"rotate\"\nkeys = [{ frame = 0, value = \
         [0, 0, 0, 0, 0] }, { frame = 1, value = [0, 90, 0, 0, 0] }]\n",
        &["exactly 3"],
    );
    parse("[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\n").unwrap();
}

#[test]
fn type_errors_use_the_formats_words_and_name_the_entry() {
    refused(
        "[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\n\n[[spheres]]\nname = \"glass ball\"\n\
         center = [0, 0, -5]\nradius = \"big\"\n",
        &["spheres[1] \"glass ball\"", "expected a number"],
    );
    let e = parse("[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\n").map(|_| ());
    assert!(e.is_ok());
    refused(
        "[render]\nmax_depth = 2.5\n[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\n",
        &["[render]", "a whole number"],
    );
}

#[test]
fn near_names_are_suggested() {
    refused(
        "[[spheres]]\ncenter = [0, 0, -5]\nraduis = 1\n",
        &["unknown field `raduis`", "did you mean \"radius\"?"],
    );
    refused(
        "[materials.glass]\ncolor = [1, 1, 1]\n[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\n\
         material = \"glas\"\n",
        &["no material named \"glas\"", "did you mean \"glass\"?"],
    );
    refused(
        "[[lights]]\ntype = \"spto\"\nposition = [0, 1, 0]\n",
        &["unknown light type", "did you mean \"spot\"?"],
    );
    refused(
        "[textures.wood]\ntype = \"checker\"\nsize = 1\n[materials.m]\ntexture = \"wod\"\n\
         [[spheres]]\ncenter = [0, 0, -5]\nradius = 1\nmaterial = \"m\"\n",
        &["no texture named \"wod\"", "did you mean \"wood\"?"],
    );
    refused(
        "[textures.t]\ntype = \"chequer\"\n",
        &["unknown texture type", "did you mean \"checker\"?"],
    );
    // Nothing close: no guess.
    let e =
        parse("[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\nmaterial = \"zzzz\"\n").unwrap_err();
    assert!(!e.contains("did you mean"), "{e}");
}

#[test]
fn the_documented_minimum_length_is_accepted() {
    parse("[[spheres]]\ncenter = [0, 0, -5]\nradius = 1e-12\n").unwrap();
    parse("[[cones]]\nbase = [0, 0, -5]\nradius = 1e-12\nheight = 1\n").unwrap();
    parse("[[tori]]\ncenter = [0, 0, -5]\nmajor_radius = 1\nminor_radius = 1e-12\n").unwrap();
    let source = "[camera]\neye = [0, 0, 0]\ndirection = [0, 0, -1]\nfov = 40\naperture = 0.1\n\
                  focus_distance = 1e-12\n";
    prism::scene_file::parse_scene(source, Path::new("s.toml"), Path::new(".")).unwrap();
    refused(
        "[[spheres]]\ncenter = [0, 0, -5]\nradius = 9e-13\n",
        &["at least 1e-12", "got 9e-13"],
    );
}

#[test]
fn one_thinness_rule_for_boxes_cylinders_and_cones() {
    for thin in [
        "[[boxes]]\nmin = [-1, -1, -5]\nmax = [1, -0.9999999, -4]\n",
        "[[cones]]\nbase = [0, 0, -5]\nradius = 1\nheight = 1e-9\ncaps = false\n",
        "[[cones]]\nbase = [0, 0, -5]\nradius = 1\nheight = 1e-6\ncaps = false\n",
        "[[cylinders]]\nbase = [0, 0, -5]\nradius = 1\nheight = 1e-9\ncaps = false\n",
    ] {
        refused(
            thin,
            &["too thin to hold in single precision", "make it at least"],
        );
    }
    // At 2^-20 of the distance and above, each is accepted.
    for ok in [
        "[[boxes]]\nmin = [-1, -1, -5]\nmax = [1, -0.99999, -4]\n",
        "[[cones]]\nbase = [0, 0, -5]\nradius = 1\nheight = 1e-5\ncaps = false\n",
        "[[cylinders]]\nbase = [0, 0, -5]\nradius = 1\nheight = 1e-5\n",
    ] {
        parse(ok).unwrap_or_else(|e| panic!("{ok}: {e}"));
    }
    // The rule is relative: the same thin cone near the camera is fine.
    parse("[[cones]]\nbase = [0, 0, -0.001]\nradius = 1e-4\nheight = 1e-8\ncaps = false\n")
        .unwrap();
}

fn dir_with(files: &[(&str, &str)]) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    let path = dir.path().to_path_buf();
    (dir, path)
}

#[test]
fn a_byte_order_mark_in_an_obj_or_mtl_hides_nothing() {
    let obj = "v -1 -1 -5\nv 1 -1 -5\nv 0 1 -5\nv 9 9 9\nmtllib m.mtl\nusemtl red\nf 1 2 3\n";
    let mtl = "newmtl red\nKd 1 0 0\n";
    let mesh = "[[meshes]]\npath = \"tri.obj\"\n";
    let (_a, plain) = dir_with(&[("tri.obj", obj), ("m.mtl", mtl)]);
    let (_b, marked) = dir_with(&[
        ("tri.obj", &format!("\u{feff}{obj}")),
        ("m.mtl", &format!("\u{feff}{mtl}")),
    ]);
    let a = parse_in(mesh, &plain).unwrap();
    let b = parse_in(mesh, &marked).unwrap();
    assert_eq!(format!("{:?}", a.objects), format!("{:?}", b.objects));
}

#[test]
fn mtl_values_are_checked_as_written() {
    let obj = "mtllib m.mtl\nv -1 -1 -5\nv 1 -1 -5\nv 0 1 -5\nusemtl a\nf 1 2 3\n";
    let (_d, dir) = dir_with(&[("tri.obj", obj), ("m.mtl", "newmtl a\nd -5\n")]);
    let e = parse_in("[[meshes]]\npath = \"tri.obj\"\n", &dir).unwrap_err();
    assert!(e.contains("m.mtl:2") && e.contains("got -5"), "{e}");
    assert!(!e.contains("got 6"), "{e}");
}

/// A PNG whose header says `side`² and whose pixels are missing: enough for a header
/// probe, refused if ever decoded.
fn header_only_png(path: &Path, side: u32) {
    let file = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
    let mut encoder = png::Encoder::new(file, side, side);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().unwrap();
    writer.write_chunk(png::chunk::IDAT, &[]).unwrap();
}

/// The images of an OBJ's material libraries count towards the scene's texel budget, all
/// of them from their headers before any is decoded.
#[test]
fn mesh_material_images_count_towards_the_texel_budget() {
    let (_d, dir) = dir_with(&[(
        "tri.obj",
        "mtllib m.mtl\nv -1 -1 -5\nv 1 -1 -5\nv 0 1 -5\nusemtl a\nf 1 2 3\nusemtl c\nf 1 2 3\n",
    )]);
    let mut mtl = String::new();
    for name in ["a", "b", "c"] {
        header_only_png(&dir.join(format!("{name}.png")), 8192);
        mtl += &format!("newmtl {name}\nmap_Kd {name}.png\n");
    }
    std::fs::write(dir.join("m.mtl"), mtl).unwrap();
    let e = parse_in("[[meshes]]\npath = \"tri.obj\"\n", &dir).unwrap_err();
    assert!(e.contains("m.mtl:6"), "{e}");
    assert!(e.contains("c.png") && e.contains("201326592 texels"), "{e}");
    // The same image named by every material counts once: within the budget, it is then
    // decoded (and this one, having no pixels, is refused as unreadable).
    std::fs::write(
        dir.join("m.mtl"),
        "newmtl a\nmap_Kd a.png\nnewmtl c\nmap_Kd a.png\n",
    )
    .unwrap();
    let e = parse_in("[[meshes]]\npath = \"tri.obj\"\n", &dir).unwrap_err();
    assert!(
        e.contains("cannot load image") && !e.contains("texels"),
        "{e}"
    );
}

/// Scene-file messages that pointed elsewhere: a field missing from the whole file named the
/// first entry; an unclosed `[` was reported lines later as a missing comma; a frame of
/// 1e300 was printed in 301 digits; an OBJ coordinate past any scale's reach was "no area";
/// a missing file did not say where it was looked for; the animation table had no "did you
/// mean".
#[test]
fn scene_messages_point_at_what_is_wrong() {
    let whole = prism::scene_file::parse_scene(
        "[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\n",
        Path::new("s.toml"),
        Path::new("."),
    )
    .unwrap_err()
    .to_string();
    assert!(whole.contains("missing field `camera`"), "{whole}");
    assert!(!whole.contains("spheres[0]"), "{whole}");

    // The bracket opened on line 6 (after the camera's 5) is never closed.
    refused(
        "[[lights]]\nposition = [1, 1, 1\n\n[render]\nwidth = 10\n",
        &[
            "scene.toml:7:12",
            "this `[` is never closed",
            "stopped at line 9",
        ],
    );
    // A bracket closed later is not blamed for a comma missing inside it.
    refused(
        "[[polygons]]\nvertices = [\n  [0, 0, -5],\n  [1, 0, -5]\n  [0, 1, -5],\n]\n",
        &["scene.toml:10", "comma"],
    );
    let e = parse("[[polygons]]\nvertices = [\n  [0, 0, -5],\n  [1, 0, -5]\n  [0, 1, -5],\n]\n")
        .unwrap_err();
    assert!(!e.contains("never closed"), "{e}");

    refused(
        "[[spheres]]\nname = \"b\"\ncenter = [0, 0, -5]\nradius = 1\n[animation]\nframes = 3\n\
         [[animation.track]]\ntarget = \"b\"\nfield = \"radius\"\n\
         keys = [{ frame = 0, value = 1 }, { frame = 1e300, value = 2 }]\n",
        &["got 1e300"],
    );
    // A key's value past the coordinates' bound is named with the bound and the value.
    refused(
        "[[spheres]]\nname = \"b\"\ncenter = [0, 0, -5]\nradius = 1\n[animation]\nframes = 3\n\
         [[animation.track]]\ntarget = \"b\"\nfield = \"center\"\n\
         keys = [{ frame = 0, value = [0, 0, -5] }, { frame = 2, value = [0, 0, -5e13] }]\n",
        &[
            "keys[1]: `value`",
            "at most 1e12",
            "got [0.0, 0.0, -50000000000000.0]",
        ],
    );
    refused(
        "[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\n[animation]\nframes = 3\ntracks = []\n",
        &["[animation]", "did you mean \"track\""],
    );

    // A colour is quoted as the file wrote it, at the line of its field.
    refused(
        "[materials.m]\ncolor = [1.5, 0.5, 0.5]\n\n[[spheres]]\ncenter = [0, 0, -5]\n\
         radius = 1\nmaterial = \"m\"\n",
        &[
            "scene.toml:7: materials.m: `color` must lie in [0, 1] per channel",
            "got [1.5, 0.5, 0.5]",
        ],
    );
    let e = parse("[materials.m]\nemission = [-1, 0, 0]\n[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\nmaterial = \"m\"\n")
        .unwrap_err();
    assert!(!e.contains("Fixed"), "{e}");

    // A light's values are every light's rules (`Light::check`), placed at their field.
    refused(
        "[[lights]]\ntype = \"spot\"\nposition = [0, 5, 0]\ndirection = [0, -1, 0]\nangle = 200\n",
        &["scene.toml:10: lights[0]: `angle` must lie in [0.01, 180], got 200"],
    );
    refused(
        "[[lights]]\ntype = \"area\"\ncorner = [0, 5, 0]\nedge_u = [1, 0, 0]\nedge_v = [2, 0, 0]\n",
        &["scene.toml:10: lights[0]: `edge_u` and `edge_v` must span a rectangle"],
    );
    refused(
        "[[lights]]\nposition = [0, 5, 0]\nfalloff = \"inverse_square\"\nintensity = -1\n",
        &["scene.toml:9: lights[0]: `intensity` must lie in [0, 1e30], got -1"],
    );

    let (_d, dir) = dir_with(&[("far.obj", "v 3e38 0 0\nv 0 3e38 0\nv 0 0 3e38\nf 1 2 3\n")]);
    let e = parse_in("[[meshes]]\npath = \"far.obj\"\n", &dir).unwrap_err();
    assert!(
        e.contains("far.obj:1") && e.contains("3e38") && e.contains("1e18"),
        "{e}"
    );

    let e = parse_in("[[meshes]]\npath = \"sub/../none.obj\"\n", &dir).unwrap_err();
    let resolved = dir.join("none.obj");
    assert!(
        e.contains(&format!("looked for {}", resolved.display())),
        "{e}"
    );
}

/// An array longer than any field takes is refused before the parser spends memory on it:
/// a key of four million numbers, a 12 MB file, under a 300 MB address-space limit.
#[test]
fn an_overlong_array_is_refused_before_it_is_parsed() {
    let numbers = vec!["1"; 4_000_000].join(", ");
    let text = format!(
        "{CAMERA}[[spheres]]\nname = \"b\"\ncenter = [0, 0, -5]\nradius = 1\n[animation]\n\
         frames = 3\n[[animation.track]]\ntarget = \"b\"\nfield = \"center\"\n\
         keys = [{{ frame = 0, value = [{numbers}] }}, {{ frame = 2, value = [0, 0, 0] }}]\n"
    );
    let (_d, dir) = dir_with(&[("long.toml", &text)]);
    let out = std::process::Command::new("bash")
        .args([
            "-c",
            "ulimit -v 300000; exec \"$0\" render --quiet \"$1\" -o \"$2\"",
            env!("CARGO_BIN_EXE_prism"),
            dir.join("long.toml").to_str().unwrap(),
            dir.join("out.png").to_str().unwrap(),
        ])
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{e}");
    assert!(
        e.contains("long.toml:15:") && e.contains("more than 100000 elements"),
        "{e}"
    );
    // Every key counts towards one limit, however the keys are split among tracks.
    let keys = |n: usize| {
        (0..n)
            .map(|k| format!("{{ frame = {k}, value = 1 }}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let tracks: String = (0..3)
        .map(|_| {
            format!(
                "[[animation.track]]\ntarget = \"b\"\nfield = \"radius\"\nkeys = [{}]\n",
                keys(40_000)
            )
        })
        .collect();
    let e = parse(&format!(
        "[[spheres]]\nname = \"b\"\ncenter = [0, 0, -5]\nradius = 1\n[animation]\nframes = 100000\n{tracks}"
    ))
    .unwrap_err();
    assert!(e.contains("at most 100000 keys in all"), "{e}");
}
