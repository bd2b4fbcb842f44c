//! Image textures on polygons: upright when the corners run counter-clockwise from the
//! bottom-left, and moved, scaled and turned by `uv_offset`, `uv_scale` and `uv_rotate`.

use glam::Vec3;
use prism::accel::Reach;
use prism::geometry::Ray;
use prism::integrator::Integrator;
use prism::scene::{PreparedScene, Scene};
use prism::scene_file::parse_scene;
use std::path::Path;

/// A 16×16 picture in quadrants: red top-left, green top-right, blue bottom-left, white
/// bottom-right.
fn quadrants(dir: &Path) {
    let img = image::RgbImage::from_fn(16, 16, |x, y| match (x < 8, y < 8) {
        (true, true) => image::Rgb([255, 0, 0]),
        (false, true) => image::Rgb([0, 255, 0]),
        (true, false) => image::Rgb([0, 0, 255]),
        _ => image::Rgb([255, 255, 255]),
    });
    img.save(dir.join("quadrants.png")).unwrap();
}

/// A unit square at z = −5 facing the camera at the origin, corners counter-clockwise from
/// the bottom-left, showing the picture with `fields`; lit by ambient light alone.
fn square(dir: &Path, fields: &str) -> Scene {
    let text = format!(
        "[camera]\neye = [0, 0, 0]\nfov = 40\n\n[render]\nambient = [1, 1, 1]\n\n\
         [textures.q]\ntype = \"image\"\npath = \"quadrants.png\"\n{fields}\n\n\
         [materials.m]\ntexture = \"q\"\ndiffuse = 0\nspecular = 0\n\n\
         [[polygons]]\nmaterial = \"m\"\n\
         vertices = [[-1, -1, -5], [1, -1, -5], [1, 1, -5], [-1, 1, -5]]\n"
    );
    parse_scene(&text, Path::new("square.toml"), dir).unwrap()
}

/// The colour at (x, y) on the square (each in −1..1).
fn at(scene: &Scene, x: f32, y: f32) -> Vec3 {
    let prepared = PreparedScene::new(scene);
    let mut integrator = Integrator::new(&prepared, 0.0);
    let dir = Vec3::new(x, y, -5.0).normalize();
    integrator
        .trace_primary(
            Reach::After(0.0),
            || Ray::new(Vec3::ZERO, dir),
            prism::sampler::SampleStream::new(0, 0, 0),
        )
        .color
}

const RED: Vec3 = Vec3::new(1.0, 0.0, 0.0);
const GREEN: Vec3 = Vec3::new(0.0, 1.0, 0.0);
const BLUE: Vec3 = Vec3::new(0.0, 0.0, 1.0);
const WHITE: Vec3 = Vec3::ONE;

/// The colours near the square's four corners: top-left, top-right, bottom-left,
/// bottom-right (near enough that bilinear filtering gives the corner texel alone).
fn corners(scene: &Scene) -> [Vec3; 4] {
    let c = 0.9;
    [
        at(scene, -c, c),
        at(scene, c, c),
        at(scene, -c, -c),
        at(scene, c, -c),
    ]
}

fn assert_corners(found: [Vec3; 4], expected: [Vec3; 4], what: &str) {
    for (f, e) in found.iter().zip(&expected) {
        assert!((*f - *e).abs().max_element() < 1e-5, "{what}: {found:?}");
    }
}

#[test]
fn a_picture_on_a_counter_clockwise_polygon_is_upright() {
    let dir = tempfile::tempdir().unwrap();
    quadrants(dir.path());
    let scene = square(dir.path(), "");
    assert_corners(corners(&scene), [RED, GREEN, BLUE, WHITE], "upright");
}

#[test]
fn offset_scale_and_rotation_move_the_picture() {
    let dir = tempfile::tempdir().unwrap();
    quadrants(dir.path());
    // Half a picture across: the halves swap (u wraps round).
    let moved = square(dir.path(), "uv_offset = [0.5, 0]");
    assert_corners(corners(&moved), [GREEN, RED, WHITE, BLUE], "offset");
    // A quarter turn counter-clockwise: the top-right quadrant comes to the top-left.
    let turned = square(dir.path(), "uv_rotate = 90");
    assert_corners(corners(&turned), [GREEN, WHITE, RED, BLUE], "rotate");
    // Scale −1 across mirrors the picture left to right.
    let mirrored = square(dir.path(), "uv_scale = [-1, 1]");
    assert_corners(corners(&mirrored), [GREEN, RED, WHITE, BLUE], "mirror");
    // Scale 2 about the centre: the picture twice across and twice down, so the square's
    // corners fall in the far quadrants of the neighbouring repeats.
    let repeated = square(dir.path(), "uv_scale = 2");
    assert_corners(corners(&repeated), [WHITE, BLUE, GREEN, RED], "repeat");
    // Its centre is still the picture's centre: the four quadrants meet there.
    let near = 0.05;
    assert_corners(
        [
            at(&repeated, -near, near),
            at(&repeated, near, near),
            at(&repeated, -near, -near),
            at(&repeated, near, -near),
        ],
        [RED, GREEN, BLUE, WHITE],
        "repeat, centre",
    );
}

#[test]
fn bad_uv_fields_are_refused_with_their_line() {
    let cases = [
        ("uv_scale = 0 # <-", "non-zero"),
        ("uv_scale = [1, 2, 3] # <-", "takes a number or [u, v]"),
        ("uv_offset = [1e9, 0] # <-", "`uv_offset` must lie in"),
        ("uv_rotate = 400 # <-", "`uv_rotate` must lie in"),
    ];
    let dir = tempfile::tempdir().unwrap();
    quadrants(dir.path());
    for (line, message) in cases {
        let text = format!(
            "[camera]\neye = [0, 0, 0]\nfov = 40\n\n[textures.q]\ntype = \"image\"\n\
             path = \"quadrants.png\"\n{line}\n"
        );
        let error = parse_scene(&text, Path::new("bad.toml"), dir.path()).unwrap_err();
        let marked = text.lines().position(|l| l.contains("# <-")).unwrap() + 1;
        assert!(error.to_string().contains(message), "{error}");
        assert_eq!(error.line(), Some(marked), "{error}");
    }
    // Only an image texture takes them.
    let text = "[camera]\neye = [0, 0, 0]\nfov = 40\n\n[textures.c]\ntype = \"checker\"\n\
                size = 1\nuv_rotate = 10\n";
    let error = parse_scene(text, Path::new("bad.toml"), dir.path()).unwrap_err();
    assert!(
        error.to_string().contains("does not apply to a checker"),
        "{error}"
    );
}
