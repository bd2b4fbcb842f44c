//! Backgrounds beyond a colour: a vertical gradient and a latitude-longitude image, seen by
//! primary rays (through empty first-hit tiles too) and by reflections; bad ones refused.

mod common;

use glam::Vec3;
use prism::accel::Reach;
use prism::geometry::Ray;
use prism::integrator::Integrator;
use prism::render::RenderSettings;
use prism::scene::{PreparedScene, Scene};
use prism::scene_file::parse_scene;
use std::path::Path;

fn scene_in(
    dir: &Path,
    render: &str,
    objects: &str,
) -> Result<Scene, prism::scene_file::SceneError> {
    let text = format!(
        "[camera]\neye = [0, 0, 0]\nfov = 60\n\n[render]\nambient = [0, 0, 0]\n{render}\n{objects}"
    );
    parse_scene(&text, Path::new("bg.toml"), dir)
}

/// The colour seen from the scene's eye along `dir`.
fn look(scene: &Scene, dir: Vec3) -> Vec3 {
    let prepared = PreparedScene::new(scene);
    let mut integrator = Integrator::new(&prepared, 0.0);
    integrator
        .trace_primary(
            Reach::After(0.0),
            || Ray::new(Vec3::ZERO, dir.normalize()),
            prism::sampler::SampleStream::new(0, 0, 0),
        )
        .color
}

/// An 8×4 image whose top half is red and bottom half blue, in a folder of its own.
fn sky_image() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let img = image::RgbImage::from_fn(8, 4, |_, y| {
        if y < 2 {
            image::Rgb([255, 0, 0])
        } else {
            image::Rgb([0, 0, 255])
        }
    });
    img.save(dir.path().join("sky.png")).unwrap();
    dir
}

#[test]
fn a_gradient_background_runs_from_bottom_to_top_in_every_ray() {
    let background = "background = { bottom = [0, 0, 1], top = [1, 0.5, 0] }";
    let scene = scene_in(Path::new("."), background, "").unwrap();
    assert_eq!(look(&scene, Vec3::Y), Vec3::new(1.0, 0.5, 0.0));
    assert_eq!(look(&scene, Vec3::NEG_Y), Vec3::new(0.0, 0.0, 1.0));
    assert!((look(&scene, Vec3::NEG_Z) - Vec3::new(0.5, 0.25, 0.5)).length() < 1e-6);
    // A render of the empty scene (every first-hit tile empty): rows brighten upwards.
    let image = common::render_scene(&scene, RenderSettings::new(16, 16, 1));
    let red = |y: u32| image.get_pixel(8, y)[0];
    assert!(
        (0..15).all(|y| red(y) >= red(y + 1)),
        "not brighter upwards"
    );
    assert!(red(0) > red(15) + 50);
}

#[test]
fn an_image_background_wraps_the_scene_and_shows_in_reflections() {
    let sky = sky_image();
    let background = "background = { image = \"sky.png\" }";
    let scene = scene_in(sky.path(), background, "").unwrap();
    assert_eq!(
        look(&scene, Vec3::Y),
        Vec3::new(1.0, 0.0, 0.0),
        "the top row straight up"
    );
    assert_eq!(
        look(&scene, Vec3::NEG_Y),
        Vec3::new(0.0, 0.0, 1.0),
        "the bottom row down"
    );
    // A perfect mirror below the eye, seen looking down, shows the sky above: red.
    let mirror = "[materials.mirror]\ncolor = [1, 1, 1]\ndiffuse = 0\nspecular = 0\n\
                  ambient = 0\nreflectivity = 1\n\n[[polygons]]\nmaterial = \"mirror\"\n\
                  vertices = [[-10, -2, 10], [10, -2, 10], [10, -2, -10], [-10, -2, -10]]\n";
    let mirrored = scene_in(sky.path(), background, mirror).unwrap();
    assert_eq!(look(&mirrored, Vec3::NEG_Y), Vec3::new(1.0, 0.0, 0.0));
}

#[test]
fn bad_backgrounds_are_refused_with_their_line() {
    let sky = sky_image();
    let cases = [
        (
            "background = { image = \"nowhere.png\" }",
            "cannot load image",
        ),
        (
            "background = { bottom = [0, 0, 0] }",
            "both `bottom` and `top`",
        ),
        (
            "background = { top = [1, 1, 1], image = \"sky.png\" }",
            "both `bottom` and `top`",
        ),
        (
            "background = { colour = [1, 0, 0] }",
            "unknown key \"colour\"",
        ),
        (
            "background = { bottom = [0, 0], top = [1, 1, 1] }",
            "`bottom` is not a colour",
        ),
        ("background = \"blue\"", "neither a colour nor a table"),
        (
            "background = { bottom = [0, 0, 0], top = [1, -1, 1] }",
            "`background`",
        ),
    ];
    for (line, message) in cases {
        let error = scene_in(sky.path(), line, "").unwrap_err();
        let shown = error.to_string();
        assert!(shown.contains(message), "{line}: {shown}");
        assert_eq!(error.line(), Some(7), "{line}: {shown}");
    }
}
