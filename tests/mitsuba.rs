//! prism's path tracer against Mitsuba 3's (`scalar_rgb`, its `path` integrator), numbers
//! for numbers, on a Lambertian room lit by a glowing sphere, a glowing rectangle and an
//! inverse-square point light, and by glowing objects (a ball, a mesh, a turned box and a
//! capped cylinder: `emission`), on smooth glass and a rough metal under the rectangle, on
//! two rough glass balls (GGX transmission, Mitsuba's `roughdielectric`) under it, and on
//! matte, metal and glass balls lit only by a sky image with a small sun.
//! tests/mitsuba/render.py writes each scene for Mitsuba with the lights in the physical
//! units docs/effects.md gives for prism's.
//!
//! Both images are averaged over 8×8-pixel blocks, taking out most of the noise; then each
//! channel's mean must agree within 2%, and every block within 5% of the image's mean
//! brightness. The same comparison with Mitsuba one bounce short must fail: the tolerance
//! tells a wrong image from a right one.
//!
//! Mitsuba is a Python package: PRISM_MITSUBA_PYTHON names a Python that imports it
//! (`.ci/run` makes one), else `python3` is tried. Without it the test fails, unless
//! PRISM_SKIP_MISSING_TOOLS is set.

mod common;

use glam::Vec3;
use prism::integrator::IntegratorKind;
use prism::render::{RenderSettings, render};
use prism::scene::PreparedScene;
use prism::scene_file::parse_scene;
use std::path::Path;
use std::process::Command;
use std::sync::Arc;

const WIDTH: u32 = 64;
const HEIGHT: u32 = 48;
const BLOCK: u32 = 8;
/// Paths per pixel in both renderers.
const SAMPLES: u32 = 4096;
/// prism's bounces; Mitsuba's `max_depth` is this + 2 (path_tracer.rs).
const MAX_DEPTH: u32 = 2;

/// The room of every scene, as render.py's `room()`: x and z in −1..1, y in 0..2, open at
/// the front.
const ROOM: &str = include_str!("../assets/mitsuba/room.toml");

macro_rules! rectangle {
    () => {
        include_str!("../assets/mitsuba/rectangle_light.toml")
    };
}

/// The scenes by render.py's names: what each adds to the room.
const SCENES: [(&str, &str); 6] = [
    (
        "sphere_light",
        "[[lights]]\ntype = \"sphere\"\nposition = [0, 1.6, 0]\nradius = 0.15\n\
         color = [1, 0.9, 0.8]\nfalloff = \"inverse_square\"\nintensity = 1\n",
    ),
    ("rectangle_light", rectangle!()),
    (
        "point_light",
        "[[lights]]\nposition = [0, 1.7, 0.2]\ncolor = [1, 0.95, 0.9]\n\
         falloff = \"inverse_square\"\nintensity = 2\n",
    ),
    (
        "glass_and_metal",
        concat!(
            rectangle!(),
            "[materials.glass]\ncolor = [1, 1, 1]\ndiffuse = 0\nspecular = 0\ntransparency = 1\n\
         eta = 1.5\nfresnel = true\n\
         [materials.metal]\ncolor = [1, 1, 1]\ndiffuse = 0\nspecular = 0\nreflectivity = 0.9\n\
         roughness = 0.5\n\
         [[spheres]]\ncenter = [0.4, 0.35, 0.3]\nradius = 0.35\nmaterial = \"glass\"\n\
         [[spheres]]\ncenter = [-0.45, 1.1, -0.35]\nradius = 0.3\nmaterial = \"metal\"\n"
        ),
    ),
    (
        "rough_glass",
        concat!(
            rectangle!(),
            "[materials.frosted]\ncolor = [1, 1, 1]\ndiffuse = 0\nspecular = 0\n\
         transparency = 1\neta = 1.5\nfresnel = true\nroughness = 0.5\n\
         [materials.misted]\ncolor = [1, 1, 1]\ndiffuse = 0\nspecular = 0\n\
         transparency = 1\neta = 1.5\nfresnel = true\nroughness = 0.25\n\
         [[spheres]]\ncenter = [0.4, 0.35, 0.3]\nradius = 0.35\nmaterial = \"frosted\"\n\
         [[spheres]]\ncenter = [-0.45, 0.9, -0.35]\nradius = 0.3\nmaterial = \"misted\"\n"
        ),
    ),
    (
        "glowing_objects",
        "[materials.warm]\ncolor = [0, 0, 0]\nspecular = 0\nemission = [6, 5, 3.5]\n\
         [materials.cool]\ncolor = [0, 0, 0]\nspecular = 0\nemission = [2, 4, 6]\n\
         [[spheres]]\ncenter = [0.45, 1.5, -0.3]\nradius = 0.2\nmaterial = \"warm\"\n\
         [[meshes]]\npath = \"cube.obj\"\nsmooth = false\nmaterial = \"cool\"\n\
         translate = [-0.5, 1.6, 0.3]\nscale = 0.15\n\
         [materials.glow_red]\ncolor = [0, 0, 0]\nspecular = 0\nemission = [5, 1.5, 1]\n\
         [materials.glow_green]\ncolor = [0, 0, 0]\nspecular = 0\nemission = [1, 4, 1.5]\n\
         [[boxes]]\nmin = [-0.15, -0.15, -0.15]\nmax = [0.15, 0.15, 0.15]\nrotate = [0, 30, 0]\n\
         translate = [0.35, 0.15, 0.4]\nmaterial = \"glow_red\"\n\
         [[cylinders]]\nbase = [-0.45, 0.7, -0.4]\nradius = 0.1\nheight = 0.4\nmaterial = \"glow_green\"\n",
    ),
];

/// Matte, rough metal and glass balls on a grey floor under the sky `write_sky` paints, as
/// render.py's `environment`.
const ENVIRONMENT: &str = "[camera]\neye = [0, 1.2, 4]\nlook_at = [0, 0.5, 0]\nfov = 40\n\
    [render]\nintegrator = \"path\"\nambient = [0, 0, 0]\nbackground = { image = \"sky.png\" }\n\
    [materials.floor]\ncolor = [0.5, 0.5, 0.5]\nspecular = 0\n\
    [materials.matte]\ncolor = [0.8, 0.8, 0.8]\nspecular = 0\n\
    [materials.metal]\ncolor = [1, 1, 1]\ndiffuse = 0\nspecular = 0\nreflectivity = 0.9\n\
    roughness = 0.5\n\
    [materials.glass]\ncolor = [1, 1, 1]\ndiffuse = 0\nspecular = 0\ntransparency = 1\n\
    eta = 1.5\nfresnel = true\n\
    [[boxes]]\nmin = [-3, -0.1, -3]\nmax = [3, 0, 3]\nmaterial = \"floor\"\n\
    [[spheres]]\ncenter = [-1.1, 0.5, 0]\nradius = 0.5\nmaterial = \"matte\"\n\
    [[spheres]]\ncenter = [0, 0.5, -0.3]\nradius = 0.5\nmaterial = \"metal\"\n\
    [[spheres]]\ncenter = [1.1, 0.5, 0]\nradius = 0.5\nmaterial = \"glass\"\n";

/// A 256×128 latitude-longitude sky, as sky.png for prism and sky.exr (the same values
/// over 255, linear) for Mitsuba, and cube.obj, a glowing mesh: a blue sky paling to the horizon over brown ground, a
/// small sun four times brighter than the sky's brightest, high to the right, and a red
/// patch low on the other side.
fn write_sky(dir: &common::Dir) {
    let (w, h) = (256u32, 128u32);
    let sky = image::RgbImage::from_fn(w, h, |x, y| {
        let v = (y as f32 + 0.5) / h as f32;
        let sun = (179..185).contains(&x) && (27..32).contains(&y);
        let red = (60..70).contains(&x) && (50..64).contains(&y);
        let c = if sun {
            [255.0, 250.0, 235.0]
        } else if red {
            [200.0, 20.0, 20.0]
        } else if v < 0.5 {
            let t = v / 0.5;
            [20.0 + 40.0 * t, 30.0 + 35.0 * t, 60.0 + 15.0 * t]
        } else {
            [40.0, 33.0, 25.0]
        };
        image::Rgb(c.map(|c| c as u8))
    });
    sky.save(dir.path("sky.png")).unwrap();
    // A cube from −1 to 1, its faces wound outwards (Mitsuba's area lights glow on the side
    // a face's winding faces; prism's on both, the inside hidden).
    let cube = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n\
                f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 5 8\nf 1 8 4\n\
                f 2 3 7\nf 2 7 6\nf 1 2 6\nf 1 6 5\nf 4 8 7\nf 4 7 3\n";
    std::fs::write(dir.path("cube.obj"), cube).unwrap();
    let linear = image::Rgb32FImage::from_fn(w, h, |x, y| {
        image::Rgb(sky.get_pixel(x, y).0.map(|c| c as f32 / 255.0))
    });
    linear.save(dir.path("sky.exr")).unwrap();
}

/// The Python that runs Mitsuba, if one is here.
fn mitsuba_python() -> Option<String> {
    let python = std::env::var("PRISM_MITSUBA_PYTHON").unwrap_or_else(|_| "python3".into());
    let imports = Command::new(&python)
        .args(["-c", "import mitsuba"])
        .output()
        .is_ok_and(|o| o.status.success());
    if imports {
        return Some(python);
    }
    assert!(
        std::env::var_os(common::SKIP_MISSING_TOOLS).is_some(),
        "the Mitsuba comparison needs Mitsuba 3 (`pip install mitsuba`), which {python} does \
         not import: run .ci/run, which installs it, set PRISM_MITSUBA_PYTHON to a Python that \
         does, or set {}=1 to skip it",
        common::SKIP_MISSING_TOOLS
    );
    eprintln!("skipped the Mitsuba comparison: {python} does not import mitsuba");
    None
}

/// Linear RGB, row by row.
type Image = Vec<Vec3>;

fn mitsuba(python: &str, dir: &common::Dir, name: &str, samples: u32, depth: u32) -> Image {
    let out = dir.path(&format!("{name}_{depth}.exr"));
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mitsuba/render.py");
    let run = Command::new(python)
        .arg(&script)
        .args([name, &samples.to_string(), &(depth + 2).to_string()])
        .arg(&out)
        .arg(dir.path("sky.exr"))
        .output()
        .expect("python runs");
    assert!(
        run.status.success(),
        "Mitsuba failed on {name}: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    let image = image::open(&out)
        .expect("Mitsuba's EXR reads")
        .into_rgb32f();
    assert_eq!(image.dimensions(), (WIDTH, HEIGHT));
    image.pixels().map(|p| Vec3::from(p.0)).collect()
}

fn prism(dir: &common::Dir, name: &str, text: &str, samples: u32) -> Image {
    let scene = parse_scene(
        &text.replace(
            "[render]\n",
            &format!("[render]\nmax_depth = {MAX_DEPTH}\n"),
        ),
        &dir.path(&format!("{name}.toml")),
        dir.0.path(),
    )
    .unwrap();
    assert_eq!(scene.render.integrator, IntegratorKind::Path);
    let mut settings =
        RenderSettings::for_scene(&scene.render, Some(WIDTH), Some(HEIGHT), None).unwrap();
    settings.samples = Some(samples);
    settings.high_dynamic_range = true;
    settings.min_weight = 0.0;
    let prepared = Arc::new(PreparedScene::new(&scene));
    let job = render(prepared, scene.camera, settings, |_, _| {});
    let acc = job.accumulator();
    (0..HEIGHT)
        .flat_map(|y| (0..WIDTH).map(move |x| (x, y)))
        .map(|(x, y)| acc.mean(x, y))
        .collect()
}

/// The image averaged over BLOCK × BLOCK blocks.
fn blocks(image: &Image) -> Vec<Vec3> {
    let (bw, bh) = (WIDTH / BLOCK, HEIGHT / BLOCK);
    let mut out = vec![Vec3::ZERO; (bw * bh) as usize];
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            out[((y / BLOCK) * bw + x / BLOCK) as usize] += image[(y * WIDTH + x) as usize];
        }
    }
    out.iter().map(|c| *c / (BLOCK * BLOCK) as f32).collect()
}

/// How far `a` is from the reference `b`: the worst channel's relative difference of the
/// means, and the worst block's difference relative to the reference's mean brightness.
fn difference(a: &Image, b: &Image) -> (f32, f32) {
    let mean = |i: &Image| i.iter().copied().sum::<Vec3>() / i.len() as f32;
    let (ma, mb) = (mean(a), mean(b));
    let means = ((ma - mb).abs() / mb).max_element();
    let level = (mb.x + mb.y + mb.z) / 3.0;
    let worst_block = blocks(a)
        .iter()
        .zip(blocks(b))
        .map(|(x, y)| (*x - y).abs().max_element())
        .fold(0.0f32, f32::max);
    (means, worst_block / level)
}

#[test]
fn path_tracer_matches_mitsuba() {
    let Some(python) = mitsuba_python() else {
        return;
    };
    let dir = common::Dir::new();
    write_sky(&dir);
    let scenes = SCENES
        .iter()
        .map(|&(name, additions)| (name, format!("{ROOM}{additions}")))
        .chain([("environment", ENVIRONMENT.to_string())]);
    let mut report = Vec::new();
    for (name, text) in scenes {
        let ours = prism(&dir, name, &text, SAMPLES);
        let reference = mitsuba(&python, &dir, name, SAMPLES, MAX_DEPTH);
        let (means, blocks) = difference(&ours, &reference);
        report.push(format!("{name}: means {means:.4}, blocks {blocks:.4}"));
        assert!(
            means < 0.02 && blocks < 0.05,
            "{name} differs from Mitsuba: {report:?}"
        );
        // One bounce short, Mitsuba's image is told apart.
        let short = mitsuba(&python, &dir, name, SAMPLES, MAX_DEPTH.saturating_sub(1));
        let (means, blocks) = difference(&ours, &short);
        report.push(format!(
            "{name} one short: means {means:.4}, blocks {blocks:.4}"
        ));
        assert!(
            means >= 0.02 || blocks >= 0.05,
            "{name}: one bounce fewer passes too (means {means:.4}, blocks {blocks:.4})"
        );
    }
    eprintln!("{report:#?}");
}
