//! POV-Ray as a reference: its image of a scene at one ray through each pixel's centre,
//! and prism's image of a scene the same way, for the suites that compare them.

use prism::render::RenderSettings;
use prism::sampler::SampleLayout;
use prism::scene_file::parse_scene;
use std::path::Path;
use std::process::Command;

/// Whether POV-Ray can be run (common::tools_present: without it the test fails, unless
/// skipping is asked for).
pub fn povray_available() -> bool {
    super::tools_present("the POV-Ray comparison", &["povray"])
}

/// POV-Ray's image of `scene` at `w` × `h`, one ray through each pixel's centre, linear.
pub fn povray_render(scene: &str, w: u32, h: u32) -> image::RgbImage {
    let dir = tempfile::tempdir().unwrap();
    let pov = dir.path().join("scene.pov");
    std::fs::write(&pov, scene).unwrap();
    let out = dir.path().join("pov.png");
    let run = Command::new("povray")
        .arg(format!("+I{}", pov.display()))
        .arg(format!("+O{}", out.display()))
        .args([
            &format!("+W{w}"),
            &format!("+H{h}"),
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
    image::open(&out).unwrap().to_rgb8()
}

/// prism's image of scene `text` at `w` × `h`, every subsample at each pixel's centre (as
/// POV-Ray's one ray there), `samples` of them (one without).
pub fn prism_render(text: &str, w: u32, h: u32, samples: Option<u32>) -> image::RgbImage {
    let scene = parse_scene(text, Path::new("povray.toml"), Path::new(".")).unwrap();
    let mut settings = RenderSettings::new(w, h, 1);
    settings.layout = SampleLayout::Grid;
    settings.samples = samples;
    super::render_scene(&scene, settings)
}

/// How many pixels differ by more than `by` levels on some channel, and the mean difference.
pub fn compare(a: &image::RgbImage, b: &image::RgbImage, by: u8) -> (usize, f64) {
    let mut far = 0;
    let mut sum = 0u64;
    for (p, q) in a.pixels().zip(b.pixels()) {
        let d = (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap();
        far += (d > by) as usize;
        sum += d as u64;
    }
    (far, sum as f64 / (a.width() * a.height()) as f64)
}
