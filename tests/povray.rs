//! POV-Ray as an independent reference for the shapes and their transforms: the same
//! geometry, each object in a flat colour (lit by ambient light alone, so only what is hit
//! where decides a pixel), one sample at each pixel's centre, must give the same image in
//! both. POV-Ray's `rotate <x, y, z>` turns about x, then y, then z, as prism's does.
//!
//! Needs `povray` (`.ci/run` installs it). Without it the test says so and passes, unless
//! PRISM_REQUIRE_POVRAY is set, as it is in CI.

use prism::render::{self, RenderSettings};
use prism::sampler::SampleLayout;
use prism::scene::{PreparedScene, parse_scene};
use std::path::Path;
use std::process::Command;
use std::sync::Arc;

const W: u32 = 320;
const H: u32 = 240;

/// Each object as prism's scene file and POV-Ray's scene language write it.
const OBJECTS: [(&str, &str); 8] = [
    (
        "[[tori]]\ncenter = [0, 0, 0]\nmajor_radius = 1.2\nminor_radius = 0.35\n\
         rotate = [60, 0, 30]\ntranslate = [-1.6, 0.9, 0]\nmaterial = \"red\"\n",
        "torus { 1.2, 0.35 pigment { rgb <1, 0, 0> } finish { F } \
         rotate <60, 0, 30> translate <-1.6, 0.9, 0> }",
    ),
    (
        "[[cones]]\nbase = [0, 0, 0]\nradius = 0.8\ntop_radius = 0.2\nheight = 1.8\n\
         rotate = [20, 0, -15]\ntranslate = [1.6, -0.3, 0]\nmaterial = \"green\"\n",
        "cone { <0, 0, 0>, 0.8, <0, 1.8, 0>, 0.2 pigment { rgb <0, 1, 0> } finish { F } \
         rotate <20, 0, -15> translate <1.6, -0.3, 0> }",
    ),
    (
        "[[cones]]\nbase = [-0.4, -1.5, -2.5]\nradius = 0.6\nheight = 1.4\nmaterial = \"red\"\n",
        "cone { <-0.4, -1.5, -2.5>, 0.6, <-0.4, -0.1, -2.5>, 0 pigment { rgb <1, 0, 0> } \
         finish { F } }",
    ),
    (
        "[[boxes]]\nmin = [-0.5, -0.5, -0.5]\nmax = [0.5, 0.5, 0.5]\nrotate = [30, 45, 0]\n\
         translate = [0, -0.9, 1.8]\nmaterial = \"blue\"\n",
        "box { <-0.5, -0.5, -0.5>, <0.5, 0.5, 0.5> pigment { rgb <0, 0, 1> } finish { F } \
         rotate <30, 45, 0> translate <0, -0.9, 1.8> }",
    ),
    (
        "[[discs]]\ncenter = [0, 1.9, -1]\nnormal = [0.3, 1, 0.5]\nradius = 0.7\n\
         material = \"blue\"\n",
        "disc { <0, 1.9, -1>, <0.3, 1, 0.5>, 0.7 pigment { rgb <0, 0, 1> } finish { F } }",
    ),
    (
        "[[cylinders]]\nbase = [0, 0, 0]\nradius = 0.5\nheight = 1.2\ncaps = false\n\
         rotate = [-35, 0, 10]\ntranslate = [3.2, 1.3, -1.5]\nmaterial = \"red\"\n",
        "cylinder { <0, 0, 0>, <0, 1.2, 0>, 0.5 open pigment { rgb <1, 0, 0> } finish { F } \
         rotate <-35, 0, 10> translate <3.2, 1.3, -1.5> }",
    ),
    (
        "[[spheres]]\ncenter = [0, 0, 0]\nradius = 0.5\nscale = [1.6, 0.6, 1]\n\
         rotate = [0, 0, 25]\ntranslate = [-3.0, -1.0, 0.5]\nmaterial = \"green\"\n",
        "sphere { <0, 0, 0>, 0.5 pigment { rgb <0, 1, 0> } finish { F } \
         scale <1.6, 0.6, 1> rotate <0, 0, 25> translate <-3.0, -1.0, 0.5> }",
    ),
    (
        "[[planes]]\npoint = [0, -2.5, 0]\nnormal = [0, 1, 0.05]\nmaterial = \"gray\"\n",
        "plane { <0, 1, 0.05>, -2.5 / vlength(<0, 1, 0.05>) pigment { rgb 0.5 } finish { F } }",
    ),
];

fn prism_scene() -> String {
    let mut s = String::from(
        "[camera]\neye = [0, 3, 8]\nlook_at = [0, 1, 0]\nfov = 40\n\n\
         [render]\nbackground = [0, 0, 0]\nambient = [1, 1, 1]\n\n",
    );
    for (name, rgb) in [
        ("red", "[1, 0, 0]"),
        ("green", "[0, 1, 0]"),
        ("blue", "[0, 0, 1]"),
        ("gray", "[0.5, 0.5, 0.5]"),
    ] {
        s += &format!(
            "[materials.{name}]\ncolor = {rgb}\nambient = 1\ndiffuse = 0\nspecular = 0\n\n"
        );
    }
    for (toml, _) in OBJECTS {
        s += toml;
        s += "\n";
    }
    s
}

fn povray_scene() -> String {
    // POV-Ray's coordinates are left-handed: a right vector of −x gives prism's view.
    let aspect = W as f64 / H as f64;
    let mut s = format!(
        "#version 3.7;\nglobal_settings {{ assumed_gamma 1.0 ambient_light 1 }}\n\
         camera {{ perspective location <0, 3, 8> look_at <0, 1, 0> right -x * {aspect} up y \
         angle 2 * degrees(atan(tan(radians(20)) * {aspect})) }}\n\
         background {{ rgb 0 }}\n\
         #declare F = finish {{ ambient 1 diffuse 0 specular 0 }};\n"
    );
    for (_, pov) in OBJECTS {
        s += pov;
        s += "\n";
    }
    s
}

#[test]
fn every_shape_draws_as_povray_draws_it() {
    let available = Command::new("sh")
        .args(["-c", "command -v povray"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !available {
        assert!(
            std::env::var_os("PRISM_REQUIRE_POVRAY").is_none(),
            "the POV-Ray comparison needs povray: run .ci/run"
        );
        eprintln!("skipping the POV-Ray comparison: povray is not installed");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let pov = dir.path().join("shapes.pov");
    std::fs::write(&pov, povray_scene()).unwrap();
    let out = dir.path().join("pov.png");
    let run = Command::new("povray")
        .arg(format!("+I{}", pov.display()))
        .arg(format!("+O{}", out.display()))
        .args([
            &format!("+W{W}"),
            &format!("+H{H}"),
            "-A",
            "-D",
            "File_Gamma=1.0",
        ])
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "povray failed: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    let reference = image::open(&out).unwrap().to_rgb8();

    let scene = parse_scene(&prism_scene(), Path::new("shapes.toml"), Path::new(".")).unwrap();
    let mut settings = RenderSettings::new(W, H, 1);
    settings.layout = SampleLayout::Grid;
    let ours = render::render(
        Arc::new(PreparedScene::new(&scene)),
        scene.camera,
        settings,
        |_, _| {},
    )
    .accumulator()
    .to_rgb8();

    // Every shape is in the picture, in its own colour.
    for colour in [[255, 0, 0], [0, 255, 0], [0, 0, 255], [128, 128, 128]] {
        let n = ours.pixels().filter(|p| p.0 == colour).count();
        assert!(n > 500, "{colour:?}: {n} pixels");
    }
    let differing = ours
        .pixels()
        .zip(reference.pixels())
        .filter(|(a, b)| (0..3).any(|c| a[c].abs_diff(b[c]) > 1))
        .count();
    // Pixels whose centre lies within rounding of an edge may go either way.
    assert!(
        differing <= 8,
        "{differing} of {} pixels differ from POV-Ray's",
        W * H
    );
}
