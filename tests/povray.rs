//! POV-Ray as an independent reference for the shapes and their transforms: the same
//! geometry, each object in a flat colour (lit by ambient light alone, so only what is hit
//! where decides a pixel), one sample at each pixel's centre, must give the same image in
//! both. POV-Ray's `rotate <x, y, z>` turns about x, then y, then z, as prism's does.
//!
//! The soft shadows of area lights are checked against POV-Ray's `area_light` too: prism's
//! light colour is the whole light's, spread over its area, as POV-Ray's is.
//!
//! Needs `povray` (`.ci/run` installs it). Without it the test fails, unless
//! PRISM_SKIP_MISSING_TOOLS is set, when it says it skipped.

mod common;

use common::povray::{povray_available, povray_render, prism_render};

const W: u32 = 320;
const H: u32 = 240;

/// Each object as prism's scene file and POV-Ray's scene language write it.
const OBJECTS: [(&str, &str); 9] = [
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
        "[[capsules]]\nbase = [0, 0, 0]\nradius = 0.35\nheight = 1.0\nrotate = [30, 0, -70]\n\
         translate = [-3.4, 2.4, -2.0]\nmaterial = \"blue\"\n",
        "merge { cylinder { <0, 0, 0>, <0, 1, 0>, 0.35 open } sphere { <0, 0, 0>, 0.35 } \
         sphere { <0, 1, 0>, 0.35 } pigment { rgb <0, 0, 1> } finish { F } \
         rotate <30, 0, -70> translate <-3.4, 2.4, -2.0> }",
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
    if !povray_available() {
        return;
    }
    let reference = povray_render(&povray_scene(), W, H);

    let ours = prism_render(&prism_scene(), W, H, None);

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

/// A POV-Ray scene's numbers render as POV-Ray shows them with `handedness = "left"`: POV-Ray
/// at its own, left-handed camera (`right x`), prism with the same numbers.
#[test]
fn left_handed_scenes_render_as_povray_shows_them() {
    if !povray_available() {
        return;
    }
    let povray = povray_scene().replace("right -x *", "right x *");
    assert_ne!(povray, povray_scene());
    let reference = povray_render(&povray, W, H);
    let prism = prism_scene().replace("fov = 40\n", "fov = 40\nhandedness = \"left\"\n");
    let ours = prism_render(&prism, W, H, None);
    let differing = |a: &image::RgbImage| {
        a.pixels()
            .zip(reference.pixels())
            .filter(|(a, b)| (0..3).any(|c| a[c].abs_diff(b[c]) > 1))
            .count()
    };
    assert!(differing(&ours) <= 8, "{} pixels differ", differing(&ours));
    // The right-handed render is the mirror image, far from POV-Ray's own.
    let mirrored = prism_render(&prism_scene(), W, H, None);
    assert!(differing(&mirrored) > 1000, "{}", differing(&mirrored));
}

/// A white matte floor and a black ball lit by nothing but a soft light, POV-Ray's
/// `pov_light` against prism's `prism_light(size)` (TOML, the light `size` times as large),
/// at 256 samples at each pixel's centre: the penumbra and the light around it must match at
/// size 1 (mean difference under 0.4 levels, under 0.6% of pixels beyond 4), and a light a
/// fifth larger must not (over 2% beyond 4). (The ball is black because at its terminator,
/// where part of the light lies below its horizon, POV-Ray is darker than the exact integral
/// of the light by up to ten 8-bit levels, and prism is within one of it.)
fn soft_shadow_matches_povrays(what: &str, pov_light: &str, prism_light: impl Fn(f32) -> String) {
    if !povray_available() {
        return;
    }
    let (w, h) = (160u32, 120u32);
    let aspect = w as f64 / h as f64;
    let pov = format!(
        "#version 3.7;\nglobal_settings {{ assumed_gamma 1.0 ambient_light 0 }}\n\
         camera {{ perspective location <0, 6, 7> look_at <0, 0.5, 0> right -x * {aspect} up y \
         angle 2 * degrees(atan(tan(radians(20)) * {aspect})) }}\n\
         background {{ rgb 0 }}\n{pov_light}\n\
         #declare F = finish {{ ambient 0 diffuse 1 specular 0 phong 0 }};\n\
         plane {{ y, 0 pigment {{ rgb 1 }} finish {{ F }} }}\n\
         sphere {{ <0.3, 1, 0.2>, 0.7 pigment {{ rgb 0 }} finish {{ F }} }}\n"
    );
    let reference = povray_render(&pov, w, h);
    let differing = |size: f32| {
        let text = format!(
            "[camera]\neye = [0, 6, 7]\nlook_at = [0, 0.5, 0]\nfov = 40\n\
             [render]\nambient = [0, 0, 0]\nbackground = [0, 0, 0]\n\
             [[lights]]\n{}\n\
             [materials.white]\ncolor = [1, 1, 1]\nambient = 0\nspecular = 0\n\
             [materials.black]\ncolor = [0, 0, 0]\nambient = 0\nspecular = 0\n\
             [[planes]]\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\nmaterial = \"white\"\n\
             [[spheres]]\ncenter = [0.3, 1, 0.2]\nradius = 0.7\nmaterial = \"black\"\n",
            prism_light(size)
        );
        let ours = prism_render(&text, w, h, Some(256));
        let diffs: Vec<u8> = ours
            .pixels()
            .zip(reference.pixels())
            .map(|(a, b)| (0..3).map(|c| a[c].abs_diff(b[c])).max().unwrap())
            .collect();
        let mean = diffs.iter().map(|&d| d as f64).sum::<f64>() / diffs.len() as f64;
        let far = diffs.iter().filter(|&&d| d > 4).count() as f64 / diffs.len() as f64;
        (mean, far)
    };
    let (mean, far) = differing(1.0);
    println!(
        "{what}: mean difference {mean:.3} levels, {:.3}% of pixels beyond 4",
        far * 100.0
    );
    assert!(
        mean < 0.4 && far < 0.006,
        "{what}: mean {mean:.3} levels, {:.3}% beyond 4",
        far * 100.0
    );
    let (mean, far) = differing(1.2);
    println!(
        "{what} a fifth larger: mean difference {mean:.3} levels, {:.3}% beyond 4",
        far * 100.0
    );
    assert!(
        far > 0.02,
        "{what} a fifth larger went unnoticed: {:.3}% beyond 4",
        far * 100.0
    );
}

/// A 2 × 2 area light against POV-Ray's `area_light`: a 33 × 33 grid of point lights sharing
/// its colour, each lighting by its own direction (`area_illumination on`).
#[test]
fn area_light_soft_shadows_match_povrays() {
    soft_shadow_matches_povrays(
        "area light",
        "light_source { <0, 4, 0> color rgb 0.9 \
         area_light <2, 0, 0>, <0, 0, 2>, 33, 33 area_illumination on }",
        |size| {
            format!(
                "type = \"area\"\ncorner = [{c}, 4, {c}]\nedge_u = [{e}, 0, 0]\n\
                 edge_v = [0, 0, {e}]\ncolor = [0.9, 0.9, 0.9]\nvisible = false",
                c = -size,
                e = 2.0 * size
            )
        },
    );
}

/// A spotlight whose disc (radius 1, level, facing down its axis) casts the shadow, against
/// POV-Ray's `spotlight` with a circular `area_light` (the 33 × 33 grid mapped onto the
/// disc). The cone is wide enough that all the floor seen is within its full light, so only
/// the shadows are compared.
#[test]
fn spotlight_disc_soft_shadows_match_povrays() {
    soft_shadow_matches_povrays(
        "spotlight disc",
        "light_source { <0, 4, 0> color rgb 0.9 spotlight point_at <0, 0, 0> radius 80 \
         falloff 80 tightness 0 \
         area_light <2, 0, 0>, <0, 0, 2>, 33, 33 circular area_illumination on }",
        |size| {
            format!(
                "type = \"spot\"\nposition = [0, 4, 0]\ndirection = [0, -1, 0]\n\
                 angle = 80\nradius = {size}\ncolor = [0.9, 0.9, 0.9]"
            )
        },
    );
}
