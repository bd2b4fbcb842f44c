//! Procedural patterns in scene files: every bad value refused with its line and field, the
//! example scene's patterns drawn the same on any number of threads, and a pattern that
//! moves with its object.

mod common;

use prism::render::RenderSettings;
use prism::scene_file::parse_scene;
use std::path::Path;

const SPHERE: &str = "[camera]\neye = [0, 0, 0]\nfov = 40\n\n\
                      [[spheres]]\ncenter = [0, 0, -5]\nradius = 1\nmaterial = \"m\"\n\n\
                      [materials.m]\ntexture = \"p\"\n\n[textures.p]\n";

#[test]
fn every_bad_pattern_is_refused_with_its_line_and_field() {
    let cases = [
        ("type = \"marbel\" # <-", "did you mean \"marble\"?"),
        ("type = \"marble\"\nscale = 0 # <-", "`scale`"),
        (
            "type = \"marble\"\nturbulence = 20 # <-",
            "`turbulence` must lie in",
        ),
        (
            "type = \"wood\"\nturbulence = -1 # <-",
            "`turbulence` must lie in",
        ),
        (
            "type = \"noise\"\noctaves = 0 # <-",
            "`octaves` must lie in 1..=10",
        ),
        (
            "type = \"noise\"\noctaves = 11 # <-",
            "`octaves` must lie in 1..=10",
        ),
        (
            "type = \"marble\"\nwidth = 2 # <-",
            "`width` does not apply to a marble",
        ),
        (
            "type = \"marble\"\ndirection = [1, 0, 0] # <-",
            "`direction` does not apply to a marble",
        ),
        (
            "type = \"gradient\"\ndirection = [0, 0, 0] # <-",
            "`direction` has zero length",
        ),
        (
            "type = \"cells\"\ncolor_map = [{ at = 0, color = [1, 1, 1] }] # <-",
            "2 to 16 stops, got 1",
        ),
        (
            "type = \"cells\"\ncolor_map = [{ at = 0.5, color = [1, 1, 1] }, { at = 0.2, color = [0, 0, 0] }] # <-",
            "stop 1: `at` 0.2 comes before",
        ),
        (
            "type = \"cells\"\ncolor_map = [{ at = 0, color = [1, 1, 1] }, { at = 1.5, color = [0, 0, 0] }] # <-",
            "stop 1: `at` must lie in 0..=1",
        ),
        (
            "type = \"granite\"\ncolor_map = [{ at = 0, color = [2, 1, 1] }, { at = 1, color = [0, 0, 0] }] # <-",
            "color_map",
        ),
    ];
    for (table, message) in cases {
        let text = format!("{SPHERE}{table}\n");
        let error = parse_scene(&text, Path::new("p.toml"), Path::new(".")).unwrap_err();
        let shown = error.to_string();
        assert!(shown.contains(message), "{table}: {shown}");
        assert!(shown.contains("textures.p"), "{shown}");
        let marked = text.lines().position(|l| l.contains("# <-")).unwrap() + 1;
        assert_eq!(error.line(), Some(marked), "{shown}");
    }
    // A stop with a field of another name is a syntax error at that stop.
    let text =
        format!("{SPHERE}type = \"cells\"\ncolor_map = [{{ at = 0, colour = [1, 1, 1] }}]\n");
    let shown = parse_scene(&text, Path::new("p.toml"), Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(shown.contains("colour"), "{shown}");
}

fn example() -> prism::scene::Scene {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/scenes/patterns.toml");
    prism::scene_file::load_scene(Path::new(path)).unwrap()
}

/// The example's patterns: the objects show many colours (the patterns, not flat ones), and
/// the image is the same on one thread as on two.
#[test]
fn the_example_patterns_are_the_same_on_any_number_of_threads() {
    let scene = example();
    let settings = RenderSettings::new(240, 135, 1);
    let on = |threads: usize| {
        prism::render::thread_pool(Some(threads))
            .unwrap()
            .install(|| common::render_scene(&scene, settings))
    };
    let one = on(1);
    assert_eq!(one, on(2));
    let colours: std::collections::HashSet<[u8; 3]> = one.pixels().map(|p| p.0).collect();
    assert!(colours.len() > 2000, "{} colours", colours.len());
}

/// The colour a ray from `from` (world coordinates) along `dir` brings back in the scene of
/// `text`.
fn colour_along(text: &str, from: glam::Vec3, dir: glam::Vec3) -> glam::Vec3 {
    let scene = parse_scene(text, Path::new("m.toml"), Path::new(".")).unwrap();
    common::colour_along(&scene, from, dir)
}

/// A pattern is fixed to its object: a ball moved sideways, seen at the same point of its
/// surface, shows the same colour there (its marble came along).
#[test]
fn a_pattern_moves_with_its_object() {
    // The colour seen along -z through (x, y), from in front of the ball.
    let seen = |ball: f32, x: f32, y: f32| {
        let text = format!(
            "[camera]\neye = [0, 0, 10]\nlook_at = [0, 0, 0]\nfov = 30\n\
             [render]\nambient = [1, 1, 1]\nbackground = [0, 0, 0]\n\
             [textures.m]\ntype = \"marble\"\nscale = 0.3\nturbulence = 2\n\
             [materials.m]\ntexture = \"m\"\nambient = 1\ndiffuse = 0\nspecular = 0\n\
             [[spheres]]\ncenter = [{ball}, 0, 0]\nradius = 1\nmaterial = \"m\"\n"
        );
        colour_along(&text, glam::Vec3::new(x, y, 5.0), -glam::Vec3::Z)
    };
    let mut colours = Vec::new();
    for (x, y) in [(0.1f32, 0.2f32), (-0.4, 0.3), (0.5, -0.6), (0.0, 0.0)] {
        let here = seen(0.0, x, y);
        let there = seen(3.75, x + 3.75, y);
        assert!(
            (here - there).abs().max_element() < 1e-4,
            "{here} against {there}"
        );
        colours.push(here);
    }
    // Not one flat colour: a pattern left behind (fixed to the scene) would differ.
    assert!(
        colours
            .iter()
            .any(|c| (*c - colours[0]).abs().max_element() > 0.05),
        "{colours:?}"
    );
}

/// A pattern turns and scales with its object (as POV-Ray's do when the object is
/// transformed after its texture): a ball turned a quarter about z shows at (x, y) what the
/// unturned ball shows at (y, −x); a ball scaled twice as large shows at (x, y) what the
/// unscaled one shows at (x/2, y/2).
#[test]
fn a_pattern_turns_and_scales_with_its_object() {
    let seen = |placement: &str, x: f32, y: f32| {
        let text = format!(
            "[camera]\neye = [0, 0, 10]\nlook_at = [0, 0, 0]\nfov = 30\n\
             [render]\nambient = [1, 1, 1]\nbackground = [0, 0, 0]\n\
             [textures.m]\ntype = \"granite\"\nscale = 0.7\n\
             [materials.m]\ntexture = \"m\"\nambient = 1\ndiffuse = 0\nspecular = 0\n\
             [[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n{placement}\n"
        );
        colour_along(&text, glam::Vec3::new(x, y, 5.0), -glam::Vec3::Z)
    };
    let mut colours = Vec::new();
    for (x, y) in [(0.1f32, 0.2f32), (-0.4, 0.3), (0.5, -0.6), (0.3, 0.45)] {
        let plain = seen("", y, -x);
        let turned = seen("rotate = [0, 0, 90]", x, y);
        assert!(
            (plain - turned).abs().max_element() < 1e-3,
            "turned at ({x}, {y}): {plain} against {turned}"
        );
        let half = seen("", x / 2.0, y / 2.0);
        let scaled = seen("scale = 2", x, y);
        assert!(
            (half - scaled).abs().max_element() < 1e-3,
            "scaled at ({x}, {y}): {half} against {scaled}"
        );
        colours.push(plain);
    }
    // Not one flat colour: a pattern that stayed put would differ.
    assert!(
        colours
            .iter()
            .any(|c| (*c - colours[0]).abs().max_element() > 0.05),
        "{colours:?}"
    );
    // Turned, it is not the pattern it was.
    assert!(
        (seen("", 0.3, 0.45) - seen("rotate = [0, 0, 90]", 0.3, 0.45))
            .abs()
            .max_element()
            > 0.01
    );
}

/// A turned object's pattern is fixed to the object, not to the camera: the same surface
/// point shows the same colour seen from two eyes (positions are kept relative to the eye,
/// and the pattern's origin must not follow it).
#[test]
fn a_turned_objects_pattern_does_not_follow_the_camera() {
    let point = glam::Vec3::new(0.3, 0.4, (1.0f32 - 0.25).sqrt());
    let seen_from = |eye: glam::Vec3| {
        let text = format!(
            "[camera]\neye = {:?}\nlook_at = [0, 0, 0]\nfov = 30\n\
             [render]\nambient = [1, 1, 1]\nbackground = [0, 0, 0]\n\
             [textures.m]\ntype = \"marble\"\nscale = 0.3\n\
             [materials.m]\ntexture = \"m\"\nambient = 1\ndiffuse = 0\nspecular = 0\n\
             [[spheres]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\nrotate = [20, 30, 40]\n",
            eye.to_array()
        );
        colour_along(&text, eye, point - eye)
    };
    let a = seen_from(glam::Vec3::new(0.0, 0.0, 10.0));
    let b = seen_from(glam::Vec3::new(4.0, 3.0, 9.0));
    assert!((a - b).abs().max_element() < 1e-3, "{a} against {b}");
}
