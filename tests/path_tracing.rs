//! The path tracer against answers known without it: with no bounce it lights a matte
//! scene exactly as Whitted's diffuse term does (the lights' physical units are defined so);
//! a convex object of any lossless material under a uniform sky returns the sky (a white
//! furnace); a closed room that glows returns the sum of its bounces; light that bounces
//! brightens what only bounced light reaches; and nothing but finite colours reach the film.

mod common;

use glam::Vec3;
use prism::integrator::IntegratorKind;
use prism::render::{Accumulator, RenderSettings, render};
use prism::scene::{PreparedScene, Scene};
use prism::scene_file::parse_scene;
use std::path::Path;
use std::sync::Arc;

fn load(text: &str) -> Scene {
    parse_scene(text, Path::new("path.toml"), Path::new(".")).unwrap()
}

/// `scene` rendered in HDR with `kind` at `samples` subsamples per pixel.
fn film(scene: &Scene, kind: IntegratorKind, w: u32, h: u32, samples: u32) -> Accumulator {
    let mut settings = RenderSettings::new(w, h, 1);
    settings.samples = Some(samples);
    settings.high_dynamic_range = true;
    settings.min_weight = 0.0;
    settings.integrator = kind;
    let prepared = Arc::new(PreparedScene::new(scene));
    render(prepared, scene.camera, settings, |_, _| {})
        .accumulator()
        .clone()
}

fn mean_of(acc: &Accumulator) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for y in 0..acc.height {
        for x in 0..acc.width {
            sum += acc.mean(x, y);
        }
    }
    sum / (acc.width * acc.height) as f32
}

/// A matte floor and ball under a point light with falloff, a spotlight and a
/// directional light; no ambient light, a black sky.
const MATTE: &str = "[camera]\neye = [0, 3, 6]\nlook_at = [0, 0.8, 0]\nfov = 50\n\
    [render]\nambient = [0, 0, 0]\nmax_depth = 0\n\
    [[lights]]\nposition = [2, 5, 3]\ncolor = [1, 0.9, 0.8]\nfalloff = \"inverse_square\"\nintensity = 20\n\
    [[lights]]\ntype = \"spot\"\nposition = [-3, 4, 1]\ndirection = [3, -4, -1]\nangle = 30\nsoftness = 0.3\ncolor = [0.2, 0.3, 0.6]\nfalloff = \"inverse_square\"\nintensity = 20\n\
    [[lights]]\ntype = \"directional\"\ndirection = [1, -2, -1]\ncolor = [0.2, 0.2, 0.1]\n\
    [materials.floor]\ncolor = [0.7, 0.6, 0.5]\nspecular = 0\n\
    [materials.ball]\ncolor = [0.2, 0.5, 0.8]\nspecular = 0\n\
    [[planes]]\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\nmaterial = \"floor\"\n\
    [[spheres]]\ncenter = [0, 0.8, 0]\nradius = 0.8\nmaterial = \"ball\"\n";

/// With no bounce and lights that are points or directions, the path tracer's one light
/// sample per light is exact: each pixel equals Whitted's (which, with no ambient and no
/// highlight, is its diffuse term) to rounding.
#[test]
fn direct_light_from_points_equals_whitteds_diffuse_term() {
    let scene = load(MATTE);
    let whitted = film(&scene, IntegratorKind::Whitted, 64, 48, 1);
    let path = film(&scene, IntegratorKind::Path, 64, 48, 1);
    let mut worst = 0.0f32;
    let mut lit = 0;
    for y in 0..48 {
        for x in 0..64 {
            let (a, b) = (whitted.mean(x, y), path.mean(x, y));
            worst = worst.max((a - b).abs().max_element() / a.max_element().max(0.05));
            lit += (a.max_element() > 0.05) as u32;
        }
    }
    assert!(lit > 2000, "{lit} pixels lit");
    assert!(worst < 1e-4, "worst relative difference {worst}");
}

/// A convex object under a uniform sky of radiance 1, seen so that it fills the frame.
fn furnace(material: &str) -> Scene {
    load(&format!(
        "[camera]\neye = [0, 0, 3]\nlook_at = [0, 0, 0]\nfov = 12\n\
         [render]\nbackground = [1, 1, 1]\nambient = [0, 0, 0]\nmax_depth = 64\n\
         [materials.m]\n{material}\n\
         [[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n"
    ))
}

/// Under a uniform sky, light that leaves a lossless convex object is the sky's: each
/// material that conserves energy returns it (within the noise of 64 paths per pixel),
/// and one that loses some (a GGX mirror's single scattering) returns no more.
#[test]
fn lossless_materials_return_a_uniform_sky() {
    let cases = [
        ("white matte", "color = [1, 1, 1]\nspecular = 0", 1.0, 0.01),
        (
            "mirror",
            "color = [1, 1, 1]\ndiffuse = 0\nspecular = 0\nreflectivity = 1",
            1.0,
            1e-4,
        ),
        (
            "glass",
            "color = [1, 1, 1]\ndiffuse = 0\nspecular = 0\ntransparency = 1\neta = 1.5\nfresnel = true",
            1.0,
            0.01,
        ),
        (
            "clear, unbent",
            "color = [1, 1, 1]\ndiffuse = 0\nspecular = 0\ntransparency = 1",
            1.0,
            1e-4,
        ),
        (
            "half mirror, half matte",
            "color = [1, 1, 1]\nspecular = 0\nreflectivity = 0.5",
            1.0,
            0.01,
        ),
        (
            "matte under a highlight",
            "color = [1, 1, 1]\nspecular = 0.3\nshininess = 40",
            // Of the highlight, what its lobe sends below the horizon is lost.
            0.985,
            0.02,
        ),
        (
            "rough glass",
            "color = [1, 1, 1]\ndiffuse = 0\nspecular = 0\ntransparency = 1\neta = 1.5\n\
             fresnel = true\nroughness = 0.4",
            0.97,
            0.03,
        ),
        (
            "rough gold-free metal",
            "color = [1, 1, 1]\ndiffuse = 0\nspecular = 0\nreflectivity = 1\nroughness = 0.4",
            0.97,
            0.03,
        ),
    ];
    for (name, material, expected, tolerance) in cases {
        let scene = furnace(material);
        let mean = mean_of(&film(&scene, IntegratorKind::Path, 16, 16, 64));
        for c in mean.to_array() {
            assert!(
                (c - expected).abs() <= tolerance && c <= 1.0 + 0.01,
                "{name}: {mean} against {expected} ± {tolerance}"
            );
        }
    }
}

/// Under a sky image of one grey, drawn toward by its own samples as well as by scattered
/// rays, a white matte ball and a mirror return the grey: the image's density is
/// normalised, and the two ways of finding it are weighed to one.
#[test]
fn a_uniform_sky_image_is_returned_too() {
    let dir = tempfile::tempdir().unwrap();
    image::RgbImage::from_pixel(32, 16, image::Rgb([128, 128, 128]))
        .save(dir.path().join("grey.png"))
        .unwrap();
    for material in [
        "color = [1, 1, 1]\nspecular = 0",
        "diffuse = 0\nspecular = 0\nreflectivity = 1",
    ] {
        let text = format!(
            "[camera]\neye = [0, 0, 3]\nlook_at = [0, 0, 0]\nfov = 12\n\
             [render]\nbackground = {{ image = \"grey.png\" }}\nambient = [0, 0, 0]\n\
             max_depth = 64\n[materials.m]\n{material}\n\
             [[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n"
        );
        let scene = parse_scene(&text, &dir.path().join("sky.toml"), dir.path()).unwrap();
        let mean = mean_of(&film(&scene, IntegratorKind::Path, 16, 16, 64));
        let grey = 128.0 / 255.0;
        for c in mean.to_array() {
            assert!(
                (c - grey).abs() < 0.01 * grey,
                "{material}: {mean} against {grey}"
            );
        }
    }
}

/// Inside a closed sphere that glows with radiance E and reflects a fraction a diffusely,
/// every bounce adds a times the last: E·(1 + a + … + a^(max_depth+1)).
#[test]
fn a_glowing_room_returns_the_sum_of_its_bounces() {
    let (e, a, depth) = (0.25f32, 0.6f32, 4u32);
    let scene = load(&format!(
        "[camera]\neye = [0, 0, 0]\nlook_at = [0, 0, -1]\nfov = 60\n\
         [render]\nambient = [0, 0, 0]\nmax_depth = {depth}\n\
         [materials.m]\ncolor = [{a}, {a}, {a}]\nspecular = 0\nemission = [{e}, {e}, {e}]\n\
         [[spheres]]\ncenter = [0, 0, 0]\nradius = 5\nmaterial = \"m\"\n"
    ));
    let expected: f32 = (0..=depth + 1).map(|k| e * a.powi(k as i32)).sum();
    let mean = mean_of(&film(&scene, IntegratorKind::Path, 24, 24, 64));
    for c in mean.to_array() {
        assert!(
            (c - expected).abs() < 0.01 * expected,
            "{mean} against {expected}"
        );
    }
    // One bounce fewer is measurably darker: the test tells depths apart.
    let fewer: f32 = (0..=depth).map(|k| e * a.powi(k as i32)).sum();
    assert!((expected - fewer) > 0.03 * expected);
}

/// Inside any closed shape that glows with radiance E and reflects a fraction a, as inside
/// the sphere above, every pixel returns E·(1 + a + … + a^(max_depth+1)). There the shape is
/// the only light its samples can reach, so a wrong area or a point drawn other than
/// uniformly by area would show as a wrong mean. Each shape is turned, moved and evenly
/// scaled, so the sampling goes through its placement; the camera sits inside at its own
/// origin.
#[test]
fn inside_any_glowing_shape_the_sum_of_its_bounces_returns() {
    let (e, a, depth) = (0.25f32, 0.6f32, 4u32);
    let shapes = [
        "[[boxes]]\nmin = [-1, -0.5, -0.8]\nmax = [1, 0.7, 0.6]",
        "[[cylinders]]\nbase = [0, -1, 0]\nradius = 0.8\nheight = 2",
        "[[cones]]\nbase = [0, -0.5, 0]\nradius = 1.2\ntop_radius = 0.4\nheight = 1.5",
        "[[cones]]\nbase = [0, -0.5, 0]\nradius = 1.5\nheight = 2",
        "[[tori]]\ncenter = [-1, 0, 0]\nmajor_radius = 1\nminor_radius = 0.5",
        "[[capsules]]\nbase = [0, -0.6, 0]\nradius = 0.7\nheight = 1.2",
    ];
    let expected: f32 = (0..=depth + 1).map(|k| e * a.powi(k as i32)).sum();
    for shape in shapes {
        let scene = load(&format!(
            "[camera]\neye = [1, 2, 3]\nlook_at = [1.3, 1.8, 2]\nfov = 90\n\
             [render]\nambient = [0, 0, 0]\nmax_depth = {depth}\n\
             [materials.m]\ncolor = [{a}, {a}, {a}]\nspecular = 0\nemission = [{e}, {e}, {e}]\n\
             {shape}\nmaterial = \"m\"\nrotate = [20, 35, -10]\nscale = 1.5\ntranslate = [1, 2, 3]\n"
        ));
        let mean = mean_of(&film(&scene, IntegratorKind::Path, 24, 24, 64));
        for c in mean.to_array() {
            assert!(
                (c - expected).abs() < 0.01 * expected,
                "{shape}: {mean} against {expected}"
            );
        }
    }
}

/// Under a table lit from above, the floor gets only bounced light: black to Whitted
/// without ambient light, lit to the path tracer, and lit more by a white wall beside it
/// than by a black one.
#[test]
fn bounced_light_reaches_what_the_lights_do_not() {
    let room = |wall: &str| {
        load(&format!(
            "[camera]\neye = [0, 0.5, 4]\nlook_at = [0, 0, 0]\nfov = 10\n\
             [render]\nambient = [0, 0, 0]\nmax_depth = 5\n\
             [[lights]]\nposition = [0, 4, 0]\nfalloff = \"inverse_square\"\nintensity = 16\n\
             [materials.white]\ncolor = [0.8, 0.8, 0.8]\nspecular = 0\n\
             [materials.wall]\ncolor = [{wall}]\nspecular = 0\n\
             [[planes]]\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\nmaterial = \"white\"\n\
             [[boxes]]\nmin = [-1.5, 1, -1.5]\nmax = [1.5, 1.1, 1.5]\nmaterial = \"white\"\n\
             [[planes]]\npoint = [-2, 0, 0]\nnormal = [1, 0, 0]\nmaterial = \"wall\"\n"
        ))
    };
    let white = room("0.9, 0.9, 0.9");
    let black = room("0, 0, 0");
    let under = |acc: &Accumulator| acc.mean(8, 8).x;
    assert_eq!(
        under(&film(&white, IntegratorKind::Whitted, 16, 16, 4)),
        0.0
    );
    let lit_white = under(&film(&white, IntegratorKind::Path, 16, 16, 256));
    let lit_black = under(&film(&black, IntegratorKind::Path, 16, 16, 256));
    assert!(lit_black > 0.0, "{lit_black}");
    assert!(
        lit_white > 1.2 * lit_black,
        "{lit_white} against {lit_black}"
    );
}

/// A light inside a glowing sphere that touches a mirror, a lamp on a surface, a camera
/// inside glass: whatever the geometry gives, each pixel is finite and not negative.
#[test]
fn only_finite_colours_reach_the_film() {
    let scene = load(
        "[camera]\neye = [0, 0, 0]\nlook_at = [0, 0, -1]\nfov = 90\n\
         [render]\nmax_depth = 16\nbackground = [0.2, 0.3, 0.4]\n\
         [[lights]]\nposition = [0, 0, -1]\nfalloff = \"inverse_square\"\nintensity = 1e6\n\
         [[lights]]\ntype = \"sphere\"\nposition = [0.5, 0, -1]\nradius = 0.5\n\
         [materials.glass]\ncolor = [1, 1, 1]\ntransparency = 1\neta = 1.5\nfresnel = true\n\
         [materials.mirror]\nreflectivity = 1\nroughness = 0.9\n\
         [[spheres]]\ncenter = [0, 0, 0]\nradius = 2\nmaterial = \"glass\"\n\
         [[planes]]\npoint = [0, -1, 0]\nnormal = [0, 1, 0]\nmaterial = \"mirror\"\n",
    );
    let acc = film(&scene, IntegratorKind::Path, 24, 24, 16);
    for y in 0..24 {
        for x in 0..24 {
            let c = acc.mean(x, y);
            assert!(c.is_finite() && c.min_element() >= 0.0, "{c} at {x}, {y}");
        }
    }
}

/// The seed scene (point lights without falloff, mirrors, glass, textures) and the Cornell
/// room (an inverse-square light, a glowing disc, a mirror), path traced with the same random
/// numbers at 10⁻³, 1 and 10³ times their size and moved 10⁵ away, draw the same images: the
/// lights' physical units, the emitters' areas and the offsets of every bounce scale with
/// the scene. A path that rounding sends
/// another way at one bounce changes its pixel, so a few pixels may differ: at most 1% by
/// more than 4 levels.
#[test]
fn path_tracing_renders_the_same_at_every_scale_and_far_away() {
    let cornell = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/cornell.toml");
    for scene in [
        prism::seed::scene().unwrap(),
        prism::scene_file::load_scene(&cornell).unwrap(),
    ] {
        same_at_every_scale(&scene);
    }
}

fn same_at_every_scale(scene: &Scene) {
    let image = |scene: &Scene| {
        let mut settings = RenderSettings::new(80, 60, 1);
        settings.samples = Some(8);
        settings.integrator = IntegratorKind::Path;
        render(
            Arc::new(PreparedScene::new(scene)),
            scene.camera,
            settings,
            |_, _| {},
        )
        .accumulator()
        .to_rgb8()
    };
    let reference = image(scene);
    for (scale, offset) in [
        (1e-3, glam::DVec3::ZERO),
        (1e3, glam::DVec3::ZERO),
        (1.0, glam::DVec3::new(1e5, -1e5, 1e5)),
    ] {
        let moved = image(&scene.transformed(scale, offset));
        let differing = moved
            .pixels()
            .zip(reference.pixels())
            .filter(|(a, b)| a.0.iter().zip(b.0).any(|(x, y)| x.abs_diff(y) > 4))
            .count();
        let share = differing as f64 / (80.0 * 60.0);
        eprintln!(
            "scale {scale}, offset {offset}: {:.2}% differ",
            share * 100.0
        );
        assert!(
            share <= 0.01,
            "scale {scale}, offset {offset}: {:.2}% differ",
            share * 100.0
        );
    }
}
