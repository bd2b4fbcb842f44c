//! Lights beyond the seed's: inverse-square falloff and directional (sun) light, against
//! analytic values, under scaling, and every bad light refused with its line.

mod common;

use glam::Vec3;
use prism::accel::Reach;
use prism::geometry::Ray;
use prism::integrator::Integrator;
use prism::sampler::SampleStream;
use prism::scene::{PreparedScene, Scene};
use prism::scene_file::parse_scene;
use std::path::Path;

/// A white matte floor (y = 0), no ambient light, and `lights` (TOML) above it, with an
/// optional sphere.
fn floor_scene(lights: &str, sphere: &str) -> Scene {
    let text = format!(
        "[camera]\neye = [0, 10, 10]\nlook_at = [0, 0, 0]\nfov = 40\n\n\
         [render]\nambient = [0, 0, 0]\n\n{lights}\n\n\
         [materials.matte]\ncolor = [1, 1, 1]\nspecular = 0\n\n\
         [[polygons]]\nname = \"floor\"\nmaterial = \"matte\"\n\
         vertices = [[-50, 0, 50], [50, 0, 50], [50, 0, -50], [-50, 0, -50]]\n{sphere}"
    );
    parse_scene(&text, Path::new("lights.toml"), Path::new(".")).unwrap()
}

/// The colour of the floor at world position `p`, seen from straight above.
fn floor_at(scene: &Scene, p: Vec3) -> Vec3 {
    let prepared = PreparedScene::new(scene);
    let mut integrator = Integrator::new(&prepared, 0.0);
    // The scene's positions are relative to its origin (the camera's eye).
    let p = p - scene.origin.as_vec3();
    let eye = p + Vec3::new(0.0, 0.5, 0.0);
    integrator
        .trace_primary(
            Reach::After(0.0),
            || Ray::new(eye, Vec3::NEG_Y),
            SampleStream::new(0, 0, 0),
        )
        .color
}

fn assert_close(found: Vec3, expected: f32, what: &str) {
    for c in found.to_array() {
        assert!(
            (c - expected).abs() <= 1e-5 * expected.abs().max(1.0),
            "{what}: {found} against {expected}"
        );
    }
}

#[test]
fn inverse_square_light_falls_off_with_distance_and_angle() {
    // A light 2 above the origin, intensity 8: I·cosθ / d² = I·h / d³ on the floor.
    let scene = floor_scene(
        "[[lights]]\nposition = [0, 2, 0]\nfalloff = \"inverse_square\"\nintensity = 8",
        "",
    );
    assert_close(floor_at(&scene, Vec3::ZERO), 8.0 / 4.0, "below the light");
    for x in [1.0f32, 2.0, 5.0] {
        let d = (4.0 + x * x).sqrt();
        let expected = 8.0 * 2.0 / (d * d * d);
        assert_close(floor_at(&scene, Vec3::new(x, 0.0, 0.0)), expected, "aside");
    }
    // Without falloff the same light is cosθ at any distance (the seed's lights).
    let flat = floor_scene("[[lights]]\nposition = [0, 2, 0]", "");
    let d = (4.0f32 + 25.0).sqrt();
    assert_close(
        floor_at(&flat, Vec3::new(5.0, 0.0, 0.0)),
        2.0 / d,
        "no falloff",
    );
}

#[test]
fn a_directional_light_lights_by_angle_and_casts_parallel_shadows() {
    // Sunlight at 45° (travelling along −y and −z): cos 45° everywhere on the floor, except
    // in the shadow of a sphere, which falls 3 units towards −z of the point below it.
    let sun = "[[lights]]\ntype = \"directional\"\ndirection = [0, -1, -1]\ncolor = [1, 1, 1]";
    let sphere = "\n[[spheres]]\ncenter = [0, 3, 0]\nradius = 1\nmaterial = \"matte\"\n";
    let scene = floor_scene(sun, sphere);
    let cos = std::f32::consts::FRAC_1_SQRT_2;
    assert_close(
        floor_at(&scene, Vec3::new(10.0, 0.0, 0.0)),
        cos,
        "in the sun",
    );
    assert_close(
        floor_at(&scene, Vec3::new(0.0, 0.0, -3.0)),
        0.0,
        "in the shadow",
    );
    // Far from the sphere the shadow's direction does not matter: lit again.
    assert_close(
        floor_at(&scene, Vec3::new(0.0, 0.0, 3.0)),
        cos,
        "behind the sphere",
    );
}

#[test]
fn an_inverse_square_scene_scaled_draws_the_same_image() {
    // `Scene::transformed` scales the intensity with the square of the scale.
    use prism::render::{RenderSettings, fraction_differing};
    let scene = floor_scene(
        "[[lights]]\nposition = [2, 4, 1]\nfalloff = \"inverse_square\"\nintensity = 30",
        "\n[[spheres]]\ncenter = [0, 1, 0]\nradius = 1\nmaterial = \"matte\"\n",
    );
    let image = |s: &Scene| common::render_scene(s, RenderSettings::new(80, 60, 1));
    let base = image(&scene);
    for scale in [1e-3f32, 1e4] {
        let scaled = scene.transformed(scale, glam::DVec3::new(1e3, 0.0, -2e3));
        let d = fraction_differing(&base, &image(&scaled), 1);
        assert!(d < 1e-3, "scale {scale}: {d}");
    }
}

#[test]
fn every_bad_light_is_refused_with_its_line() {
    let cases = [
        (
            "type = \"laser\" # <-\nposition = [0, 5, 0]",
            "unknown light type",
        ),
        (
            "type = \"spot\" # <-\nposition = [0, 5, 0]\ndirection = [0, -1, 0]",
            "needs `angle`",
        ),
        (
            "type = \"spot\"\nposition = [0, 5, 0]\ndirection = [0, -1, 0]\nangle = 200 # <-",
            "`angle` must lie in",
        ),
        (
            "type = \"spot\"\nposition = [0, 5, 0]\ndirection = [0, -1, 0]\nangle = 20\nsoftness = 2 # <-",
            "`softness` must lie in",
        ),
        (
            "type = \"spot\"\nposition = [0, 5, 0]\ndirection = [0, -1, 0]\nangle = 20\nradius = -1 # <-",
            "`radius` must be",
        ),
        (
            "type = \"point\"\nposition = [0, 5, 0]\nradius = 1 # <-",
            "`radius` does not apply to a point light",
        ),
        (
            "type = \"area\"\ncorner = [0, 5, 0]\nedge_u = [1, 0, 0]\nedge_v = [2, 0, 0] # <-",
            "must span a rectangle",
        ),
        (
            "type = \"area\" # <-\ncorner = [0, 5, 0]\nedge_u = [1, 0, 0]",
            "needs `edge_v`",
        ),
        (
            "type = \"area\"\ncorner = [0, 5, 0]\nedge_u = [1, 0, 0]\nedge_v = [0, 0, 1]\nradius = 1 # <-",
            "`radius` does not apply to an area light",
        ),
        (
            "type = \"sphere\"\nposition = [0, 5, 0]\nradius = 0 # <-",
            "`radius` must be greater than zero",
        ),
        (
            "type = \"sphere\"\nposition = [0, 5, 0]\nradius = 1\nangle = 3 # <-",
            "`angle` does not apply to a sphere light",
        ),
        ("color = [1, 1, 1] # <-", "needs `position`"),
        (
            "position = [0, 5, 0]\nintensity = 3 # <-",
            "`intensity` needs `falloff",
        ),
        (
            "position = [0, 5, 0]\nfalloff = \"linear\" # <-",
            "unknown falloff",
        ),
        (
            "position = [0, 5, 0]\nfalloff = \"inverse_square\"\nintensity = -1 # <-",
            "`intensity` must lie in",
        ),
        (
            "type = \"directional\"\ndirection = [0, 0, 0] # <-",
            "`direction` has zero length",
        ),
        (
            "type = \"directional\"\ndirection = [0, -1, 0]\nposition = [0, 5, 0] # <-",
            "`position` does not apply to a directional light",
        ),
        (
            "type = \"directional\"\ndirection = [0, -1, 0]\nfalloff = \"none\" # <-",
            "`falloff` does not apply",
        ),
        (
            "position = [0, 5, 0]\ndirection = [0, -1, 0] # <-",
            "does not apply to a point",
        ),
    ];
    for (light, message) in cases {
        let text = format!("[camera]\neye = [0, 0, 0]\nfov = 40\n\n[[lights]]\n{light}\n");
        let error = parse_scene(&text, Path::new("bad.toml"), Path::new(".")).unwrap_err();
        let marked = text.lines().position(|l| l.contains("# <-")).unwrap() + 1;
        let shown = error.to_string();
        assert!(shown.contains(message), "{shown}");
        assert!(shown.contains("lights[0]"), "{shown}");
        // A missing field is the table's fault: its header's line; else the field's own.
        let line = if message.starts_with("needs") {
            5
        } else {
            marked
        };
        assert_eq!(error.line(), Some(line), "{shown}");
    }
}

#[test]
fn an_emitting_surface_glows_unlit_and_a_shadowless_bulb_does_not_block_its_light() {
    // A bulb (an emitting sphere with `shadow = false`) around a point light 2 above the
    // floor: the floor below is lit exactly as by the bare light, and the bulb, seen from
    // above, shows its emission on top of what the light and the floor's ambient give it.
    let lamp = "[[lights]]\nposition = [0, 2, 0]\nfalloff = \"inverse_square\"\nintensity = 8";
    let bulb = "\n[materials.bulb]\ncolor = [1, 1, 1]\nspecular = 0\ndiffuse = 0\n\
                emission = [0.9, 0.8, 0.5]\n\n\
                [[spheres]]\ncenter = [0, 2, 0]\nradius = 0.3\nmaterial = \"bulb\"\n";
    let bare = floor_scene(lamp, "");
    let shadowless = floor_scene(lamp, &format!("{bulb}shadow = false\n"));
    let shadowing = floor_scene(lamp, bulb);
    let below = Vec3::ZERO;
    assert_eq!(floor_at(&shadowless, below), floor_at(&bare, below));
    assert_close(
        floor_at(&shadowing, below),
        0.0,
        "under a bulb that casts a shadow",
    );
    // The top of the bulb: no diffuse term, no ambient light, so exactly its emission.
    let top = floor_at(&shadowless, Vec3::new(0.0, 2.3, 0.0));
    assert!(
        (top - Vec3::new(0.9, 0.8, 0.5)).abs().max_element() < 1e-6,
        "{top}"
    );
}

#[test]
fn bad_emission_and_shadow_values_are_refused_with_their_line() {
    let base = "[camera]\neye = [0, 0, 0]\nfov = 40\n\n";
    let emission = format!("{base}[materials.m]\nemission = [0, -1, 0] # <-\n");
    let shadow =
        format!("{base}[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\nshadow = \"no\" # <-\n");
    for (text, message) in [(emission, "`emission`"), (shadow, "expected a boolean")] {
        let error = parse_scene(&text, Path::new("bad.toml"), Path::new(".")).unwrap_err();
        let marked = text.lines().position(|l| l.contains("# <-")).unwrap() + 1;
        assert!(error.to_string().contains(message), "{error}");
        assert_eq!(error.line(), Some(marked), "{error}");
    }
}
