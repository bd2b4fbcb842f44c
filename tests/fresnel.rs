//! Fresnel glass: a flat dielectric seen at every angle reflects what the exact Fresnel
//! equations say, the seed's fixed shares are untouched without it, and the option is
//! refused where it means nothing.

mod common;

use prism::render::RenderSettings;
use prism::sampler::SampleLayout;
use prism::scene::Scene;
use prism::scene_file::parse_scene;
use std::path::Path;

/// A white sky over a sheet of glass (eta 1.5, all of its light split by Fresnel), over a
/// black floor: a pixel sees R·white by reflection plus (1 − R)·black through the sheet.
fn sheet(fresnel: bool) -> String {
    format!(
        "[camera]\neye = [0, 1, 0]\nlook_at = [0, 0, -3]\nfov = 60\n\n\
         [render]\nbackground = [1, 1, 1]\nambient = [0, 0, 0]\n\n\
         [materials.glass]\ncolor = [1, 1, 1]\nambient = 0\ndiffuse = 0\nspecular = 0\n\
         transparency = 1\neta = 1.5\nfresnel = {fresnel}\n\n\
         [materials.black]\ncolor = [0, 0, 0]\nambient = 0\ndiffuse = 0\nspecular = 0\n\n\
         [[polygons]]\nmaterial = \"glass\"\n\
         vertices = [[-1000, 0, 1000], [1000, 0, 1000], [1000, 0, -1000], [-1000, 0, -1000]]\n\n\
         [[polygons]]\nmaterial = \"black\"\n\
         vertices = [[-1000, -1, 1000], [1000, -1, 1000], [1000, -1, -1000], [-1000, -1, -1000]]\n"
    )
}

fn load(text: &str) -> Scene {
    parse_scene(text, Path::new("sheet.toml"), Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

/// The linear colour of every pixel, one sample at its centre.
fn render_centres(scene: &Scene, w: u32, h: u32) -> image::RgbImage {
    let mut settings = RenderSettings::new(w, h, 1);
    settings.layout = SampleLayout::Grid;
    common::render_scene(scene, settings)
}

/// The exact unpolarised reflectance from air into eta 1.5 at `theta` from the normal.
fn reflectance(theta: f64) -> f64 {
    let (n1, n2) = (1.0, 1.5);
    let t = (n1 / n2 * theta.sin()).asin();
    let (ci, ct) = (theta.cos(), t.cos());
    let rs = (n1 * ci - n2 * ct) / (n1 * ci + n2 * ct);
    let rp = (n2 * ci - n1 * ct) / (n2 * ci + n1 * ct);
    0.5 * (rs * rs + rp * rp)
}

#[test]
fn a_sheet_of_glass_reflects_what_the_fresnel_equations_say() {
    let scene = load(&sheet(true));
    let (w, h) = (16, 200);
    let image = render_centres(&scene, w, h);
    let rays = scene.camera.rays(w, h);
    let mut seen = Vec::new();
    for y in 0..h {
        let d = rays.ray(w as f32 / 2.0, y as f32 + 0.5).dir;
        if d.y >= -0.02 {
            continue; // the sky, or the sheet too far off for its pixel to be one angle
        }
        let theta = (-d.y as f64).acos();
        let want = reflectance(theta) * 255.0;
        let got = image.get_pixel(w / 2, y)[0] as f64;
        // One 8-bit level, for the rounding of the pixel.
        assert!(
            (got - want).abs() <= 1.0,
            "row {y}, {:.1}° from the normal: {got} vs {want:.2}",
            theta.to_degrees()
        );
        seen.push((theta.to_degrees(), got));
    }
    // The view spans steep to grazing: from about 5% reflected to far more.
    let steepest = seen.iter().map(|s| s.0).fold(90.0, f64::min);
    let flattest = seen.iter().map(|s| s.0).fold(0.0, f64::max);
    assert!(
        steepest < 45.0 && flattest > 85.0,
        "{steepest}° to {flattest}°"
    );
    let most = seen.iter().map(|s| s.1).fold(0.0, f64::max);
    assert!(
        most > 100.0,
        "at grazing angles most of the sky is reflected ({most})"
    );
}

#[test]
fn without_fresnel_the_shares_are_fixed() {
    // The same sheet, transparency 1 and no Fresnel: it reflects nothing at any angle, and
    // through it the black floor shows.
    let scene = load(&sheet(false));
    let image = render_centres(&scene, 16, 200);
    let rays = scene.camera.rays(16, 200);
    for y in 0..200 {
        if rays.ray(8.0, y as f32 + 0.5).dir.y < -0.02 {
            assert_eq!(image.get_pixel(8, y)[0], 0, "row {y}");
        }
    }
}

#[test]
fn fresnel_needs_a_refractive_material() {
    for eta in ["", "eta = 1\n"] {
        let text = format!(
            "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = 40\n\n\
             [materials.x]\ntransparency = 1\n{eta}fresnel = true\n"
        );
        let message = parse_scene(&text, Path::new("s.toml"), Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(
            message.contains("s.toml:") && message.contains("`fresnel = true` needs"),
            "{message}"
        );
    }
}

/// Energy is conserved: the reflectance prism uses plus the transmittance computed on its own
/// from the Fresnel transmission amplitudes, T = (η₂ cos θt / η₁ cos θi)·(t_s² + t_p²)/2, is 1 at
/// every angle below the critical one, from either side; past it, all is reflected.
#[test]
fn reflectance_and_transmittance_sum_to_one() {
    for (n1, n2) in [(1.0f64, 1.5f64), (1.5, 1.0), (1.33, 1.5), (1.0, 2.4)] {
        for step in 0..90 {
            let theta_i = (step as f64).to_radians();
            let (cos_i, sin_i) = (theta_i.cos(), theta_i.sin());
            let sin_t = n1 / n2 * sin_i;
            let r = prism::appearance::fresnel_reflectance(cos_i as f32, (n1 / n2) as f32) as f64;
            if sin_t >= 1.0 {
                assert_eq!(r, 1.0, "{n1} → {n2} at {step}°: total internal reflection");
                continue;
            }
            let cos_t = (1.0 - sin_t * sin_t).sqrt();
            let ts = 2.0 * n1 * cos_i / (n1 * cos_i + n2 * cos_t);
            let tp = 2.0 * n1 * cos_i / (n2 * cos_i + n1 * cos_t);
            let t = n2 * cos_t / (n1 * cos_i) * 0.5 * (ts * ts + tp * tp);
            assert!(
                (r + t - 1.0).abs() < 1e-5,
                "{n1} → {n2} at {step}°: R {r} + T {t}"
            );
        }
    }
}
