//! The progressive engine the viewer runs: one subsample per pixel per pass, cancellable at
//! any moment, converging to exactly the one-shot render.

mod common;

use prism::render::{self, AdaptiveSettings, PassOutcome, ProgressiveRender, RenderSettings};
use prism::scene::PreparedScene;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The seed scene prepared, and its camera.
fn seed() -> (Arc<PreparedScene>, prism::camera::Camera) {
    let scene = common::seed();
    (Arc::new(PreparedScene::new(&scene)), scene.camera)
}

const NEVER: fn() -> bool = || false;

#[test]
fn each_pass_adds_one_subsample_to_every_pixel() {
    let (scene, camera) = seed();
    let mut job = ProgressiveRender::new(scene, camera, RenderSettings::new(64, 48, 3));
    for pass in 1..=9 {
        assert!(matches!(job.step(&NEVER), PassOutcome::Finished(_)));
        assert!(job.accumulator().pixels.iter().all(|p| p.count == pass));
        assert_eq!(job.passes_done(), pass);
    }
    assert!(job.is_converged());
}

#[test]
fn stops_when_converged() {
    let (scene, camera) = seed();
    let mut job = ProgressiveRender::new(scene, camera, RenderSettings::new(32, 24, 2));
    for _ in 0..4 {
        job.step(&NEVER);
    }
    let before = job.accumulator().clone();
    for _ in 0..3 {
        assert_eq!(job.step(&NEVER), PassOutcome::Converged);
    }
    assert_eq!(job.accumulator(), &before, "no work after convergence");
}

#[test]
fn progressive_equals_one_shot() {
    let (scene, camera) = seed();
    let settings = RenderSettings::new(80, 60, 4);
    let one_shot = render::render(scene.clone(), camera, settings, |_, _| {});
    let mut job = ProgressiveRender::new(scene, camera, settings);
    while let PassOutcome::Finished(_) = job.step(&NEVER) {}
    assert!(job.accumulator() == one_shot.accumulator());
    assert_eq!(
        job.accumulator().to_rgb8(),
        one_shot.accumulator().to_rgb8()
    );
}

#[test]
fn restart_in_the_middle_of_a_pass_gives_the_same_final_image() {
    let (scene, camera) = seed();
    let settings = RenderSettings::new(80, 60, 2);
    let reference = render::render(scene.clone(), camera, settings, |_, _| {});

    let mut job = ProgressiveRender::new(scene, camera, settings);
    job.step(&NEVER);
    // Cancel the second pass after a few bands of rows.
    let bands = AtomicUsize::new(0);
    let cancel_soon = || bands.fetch_add(1, Ordering::SeqCst) >= 3;
    assert_eq!(job.step(&cancel_soon), PassOutcome::Cancelled);
    let partial: u32 = job
        .accumulator()
        .pixels
        .iter()
        .map(|p| p.count)
        .max()
        .unwrap();
    assert_eq!(
        partial, 2,
        "some rows had their second subsample when cancelled"
    );
    while let PassOutcome::Finished(_) = job.step(&NEVER) {}
    assert!(job.accumulator() == reference.accumulator());
}

#[test]
fn camera_change_restarts_accumulation() {
    let (scene, mut camera) = seed();
    let mut job = ProgressiveRender::new(scene, camera, RenderSettings::new(40, 30, 2));
    job.step(&NEVER);
    job.step(&NEVER);
    camera.yaw += 5.0;
    job.set_camera(camera);
    assert_eq!(job.passes_done(), 0);
    assert_eq!(job.rays_traced().total(), 0);
    // The next pass replaces every sum: one subsample each, of the new view only.
    job.step(&NEVER);
    assert!(job.accumulator().pixels.iter().all(|p| p.count == 1));
    let fresh = render::render(
        job.scene().clone(),
        camera,
        RenderSettings::new(40, 30, 2),
        |_, _| {},
    );
    while let PassOutcome::Finished(_) = job.step(&NEVER) {}
    assert_eq!(
        job.accumulator(),
        fresh.accumulator(),
        "as if it had never been elsewhere"
    );
}

#[test]
fn adaptive_sampling_stops_flat_pixels_and_refines_edges() {
    let (scene, camera) = seed();
    let mut settings = RenderSettings::new(160, 120, 4);
    let full = render::render(scene.clone(), camera, settings, |_, _| {});
    settings.adaptive = Some(AdaptiveSettings::default());
    let adaptive = render::render(scene, camera, settings, |_, _| {});
    let counts: Vec<u32> = adaptive
        .accumulator()
        .pixels
        .iter()
        .map(|p| p.count)
        .collect();
    let defaults = AdaptiveSettings::default();
    let min = *counts.iter().min().unwrap();
    assert!(min >= defaults.min_samples, "min {min}");
    let stopped_at_min = counts
        .iter()
        .filter(|&&c| c == defaults.min_samples)
        .count();
    assert!(
        stopped_at_min * 2 > counts.len(),
        "only {stopped_at_min} of {} pixels stopped at the minimum",
        counts.len()
    );
    // Every pixel that a strong edge crosses (its subsamples' signatures differ, and a
    // neighbour is far brighter or darker) refined to at least the edge minimum, and some
    // went on to the full grid. Faint edges may stop at the minimum.
    let pixels = &adaptive.accumulator().pixels;
    let (w, h) = (160usize, 120usize);
    let contrast = |x: usize, y: usize| {
        let p = pixels[y * w + x].mean();
        let mut most = 0.0f32;
        for ny in y.saturating_sub(1)..(y + 2).min(h) {
            for nx in x.saturating_sub(1)..(x + 2).min(w) {
                most = most.max((pixels[ny * w + nx].mean() - p).abs().max_element());
            }
        }
        most
    };
    let mut strong = Vec::new();
    let mut faint_stopped = 0;
    for (i, p) in pixels.iter().enumerate() {
        if !p.mixed {
            continue;
        }
        let c = contrast(i % w, i / w);
        if c > 0.25 {
            strong.push(p.count);
        } else if c < 0.5 * defaults.edge_contrast && p.count == defaults.min_samples {
            faint_stopped += 1;
        }
    }
    assert!(
        strong.len() > 100,
        "the seed scene has strong edges: {}",
        strong.len()
    );
    assert!(strong.iter().all(|&c| c >= defaults.edge_samples.min(16)));
    assert!(
        faint_stopped > 0,
        "no pixel on a faint edge stopped at the minimum"
    );
    assert_eq!(*counts.iter().max().unwrap(), 16);
    // And the image stays close to the full render.
    let a = adaptive.accumulator().to_rgb8();
    let b = full.accumulator().to_rgb8();
    let mean_error: f64 = a
        .as_raw()
        .iter()
        .zip(b.as_raw())
        .map(|(&x, &y)| x.abs_diff(y) as f64)
        .sum::<f64>()
        / a.as_raw().len() as f64;
    assert!(mean_error < 1.0, "mean error {mean_error} levels");
}

#[test]
fn an_appearance_edit_keeps_the_geometry_and_draws_what_a_fresh_preparation_draws() {
    // A viewer slider: the glass sphere's eta and the mirror sphere's transparency change
    // in a running render. The geometry (shapes, BVH, light buffers) is the very same
    // object afterwards, and the image equals that of the edited scene prepared anew.
    let mut scene = prism::seed::scene().unwrap();
    let settings = RenderSettings::new(80, 60, 2);
    let mut job =
        ProgressiveRender::new(Arc::new(PreparedScene::new(&scene)), scene.camera, settings);
    job.step(&NEVER);
    let geometry = job.scene().geometry.clone();
    let glass = geometry.find("glass sphere (eta 1.43)").unwrap() as usize;
    let mirror = geometry.find("mirror sphere").unwrap() as usize;
    scene.set_eta(glass, 1.9).unwrap();
    scene.set_transparency(mirror, 0.4).unwrap();
    for object in [glass, mirror] {
        let material = scene.objects[object].material.clone();
        job.edit_appearance(|a| a.set_material(object, material));
    }
    assert_eq!(job.passes_done(), 0, "an edit restarts the accumulation");
    assert!(Arc::ptr_eq(&job.scene().geometry, &geometry));
    while let PassOutcome::Finished(_) = job.step(&NEVER) {}
    let fresh = render::render(
        Arc::new(PreparedScene::new(&scene)),
        scene.camera,
        settings,
        |_, _| {},
    );
    assert_eq!(job.accumulator(), fresh.accumulator());
    let unedited = render::render(
        Arc::new(PreparedScene::new(&prism::seed::scene().unwrap())),
        scene.camera,
        settings,
        |_, _| {},
    );
    assert_ne!(job.accumulator(), unedited.accumulator(), "the edit shows");
}

#[test]
fn light_ambient_background_and_depth_edits_draw_what_a_fresh_preparation_draws() {
    // Each edit in place in a running render, against the edited description prepared anew.
    let settings = RenderSettings::new(64, 48, 1);
    let base = prism::seed::scene().unwrap();
    let mut edited = base.clone();
    edited.lights[0].color = glam::Vec3::new(1.0, 0.6, 0.3);
    edited.ambient = glam::Vec3::new(0.05, 0.1, 0.3);
    edited.background = prism::appearance::Background::Gradient {
        bottom: glam::Vec3::new(0.2, 0.3, 0.5),
        top: glam::Vec3::new(0.6, 0.7, 0.9),
    };
    edited.render.max_depth = 1;
    let mut job =
        ProgressiveRender::new(Arc::new(PreparedScene::new(&base)), base.camera, settings);
    job.step(&NEVER);
    job.edit_appearance(|a| {
        a.set_light_color(0, edited.lights[0].color);
        a.set_ambient(edited.ambient);
        a.set_background(edited.background.clone());
        a.set_max_depth(edited.render.max_depth);
    });
    while let PassOutcome::Finished(_) = job.step(&NEVER) {}
    let fresh = render::render(
        Arc::new(PreparedScene::new(&edited)),
        edited.camera,
        settings,
        |_, _| {},
    );
    assert_eq!(job.accumulator(), fresh.accumulator());
}

/// Soft shadows are noise, not edges: with `samples` past the grid, the passes go on to the
/// count asked for, and adaptive sampling (which in a noisy render pools each pixel's noise
/// with its neighbours' and spends subsamples in proportion to it) comes closer to the full
/// render than a fixed render of as many subsamples.
#[test]
fn adaptive_sampling_of_soft_shadows_beats_as_many_fixed_subsamples() {
    let text = include_str!("../assets/scenes/soft_shadows.toml");
    let scene = prism::scene_file::parse_scene(
        text,
        std::path::Path::new("soft_shadows.toml"),
        std::path::Path::new("."),
    )
    .unwrap();
    let prepared = Arc::new(PreparedScene::new(&scene));
    let mut settings = RenderSettings::new(160, 100, 4);
    settings.samples = Some(256);
    let full = render::render(prepared.clone(), scene.camera, settings, |_, _| {});
    assert_eq!(full.passes_done(), 256);
    assert!(full.is_stochastic());
    let adaptive = render::render(
        prepared.clone(),
        scene.camera,
        RenderSettings {
            adaptive: Some(AdaptiveSettings::default()),
            ..settings
        },
        |_, _| {},
    );
    let rmse = |a: &render::Accumulator, b: &render::Accumulator| {
        let sum: f64 = a
            .pixels
            .iter()
            .zip(&b.pixels)
            .map(|(p, q)| {
                (p.mean().min(glam::Vec3::ONE) - q.mean().min(glam::Vec3::ONE)).length_squared()
                    as f64
            })
            .sum();
        (sum / (a.pixels.len() * 3) as f64).sqrt()
    };
    let spp = adaptive.samples_per_pixel();
    let error = rmse(adaptive.accumulator(), full.accumulator());
    let fixed = render::render(
        prepared.clone(),
        scene.camera,
        RenderSettings {
            samples: Some(spp.ceil() as u32),
            ..settings
        },
        |_, _| {},
    );
    let fixed_error = rmse(fixed.accumulator(), full.accumulator());
    println!(
        "adaptive: {spp:.1} samples per pixel, RMSE {error:.5} against 256; \
         fixed {}: {fixed_error:.5}",
        spp.ceil()
    );
    assert!(spp < 96.0, "{spp} samples per pixel");
    assert!(
        error < 0.75 * fixed_error,
        "adaptive RMSE {error} against fixed {fixed_error}"
    );
    // The seed scene has no random numbers beyond the pixel positions.
    let (seed, camera) = seed();
    assert!(!ProgressiveRender::new(seed, camera, RenderSettings::new(8, 8, 2)).is_stochastic());
}
