//! `prism bench path-tracing`: the path tracer's error against time on the room that
//! tests/mitsuba.rs compares with Mitsuba 3 (lit by a glowing rectangle), denoised too in a
//! build with the `denoise` feature, and Mitsuba's own time and error at the same samples
//! per pixel where Mitsuba is installed.

use super::convergence::{
    Measure, NEVER, Point, Size, Timed, errors_of_means, measure, reference, to_rgb8, write_csv,
};
use super::timing::median_of;
use anyhow::{Context, Result, bail};
use glam::Vec3;
use prism::camera::Camera;
use prism::integrator::IntegratorKind;
use prism::render::{PassOutcome, ProgressiveRender, RenderSettings};
use prism::scene::PreparedScene;
use prism::scene_file::parse_scene;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;
use std::time::Instant;

pub struct Config {
    pub quick: bool,
    pub out_dir: PathBuf,
    pub runs: usize,
}

const ROOM: &str = include_str!("../../assets/mitsuba/room.toml");
const LIGHT: &str = include_str!("../../assets/mitsuba/rectangle_light.toml");
/// Mitsuba's description of the same scene.
const SCRIPT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/mitsuba/render.py");
/// The scene's `max_depth` (its default), which Mitsuba counts as 2 more.
const MAX_DEPTH: u32 = 5;

const PRISM: &str = "prism, path tracer";
const MITSUBA: &str = "Mitsuba 3, scalar_rgb path";
#[cfg(feature = "denoise")]
const DENOISED: &str = "prism, path tracer, denoised";

pub fn run(cfg: Config) -> Result<()> {
    let size = if cfg.quick {
        Size {
            width: 64,
            height: 48,
            reference_aa: 4,
            reference_samples: Some(256),
            integrator: IntegratorKind::Path,
        }
    } else {
        Size {
            width: 320,
            height: 240,
            reference_aa: 4,
            reference_samples: Some(4096),
            integrator: IntegratorKind::Path,
        }
    };
    let counts: &[u32] = if cfg.quick {
        &[4, 16]
    } else {
        &[4, 16, 64, 256]
    };
    std::fs::create_dir_all(&cfg.out_dir)
        .with_context(|| format!("cannot create {}", cfg.out_dir.display()))?;
    let text = format!("{ROOM}{LIGHT}");
    let scene = parse_scene(&text, Path::new("room.toml"), Path::new("."))?;
    assert_eq!(scene.render.max_depth, MAX_DEPTH);
    let prepared = Arc::new(PreparedScene::new(&scene));
    let reference = reference(&text, &prepared, scene.camera, &size)?;
    let reference_rgb8 = to_rgb8(&reference, size.width, size.height);
    // prism also renders the 1,024-sample image that denoised ones are held against.
    let prism_counts: Vec<u32> = if cfg.quick {
        counts.to_vec()
    } else {
        counts.iter().copied().chain([1024]).collect()
    };
    let settings_of = |n: u32| {
        let mut s =
            RenderSettings::for_scene(&scene.render, Some(size.width), Some(size.height), None)
                .expect("the bench's settings are valid");
        s.samples = Some(n);
        s
    };
    let strategies: Vec<Timed> = prism_counts
        .iter()
        .map(|&n| Timed {
            name: PRISM,
            measure: Measure::Finished,
            settings: settings_of(n),
        })
        .collect();
    let (mut points, _, _) = measure(&prepared, scene.camera, &strategies, &reference, cfg.runs);

    let denoised = denoised_points(
        &prepared,
        scene.camera,
        counts.iter().map(|&n| settings_of(n)),
        &reference,
        &reference_rgb8,
        cfg.runs,
    )?;
    let python = mitsuba_python();
    // Mitsuba's time over prism's at each count: each Mitsuba run paired with a prism
    // render of the same samples just before it, so that a slow spell of the shared machine
    // falls on both; the median of the pairs' ratios.
    let mut ratios = Vec::new();
    if let Some(python) = &python {
        let dir = cfg.out_dir.join("mitsuba");
        std::fs::create_dir_all(&dir)?;
        for &n in counts {
            let mut times = Vec::new();
            let mut pairs = Vec::new();
            let mut image = Vec::new();
            for run in 0..cfg.runs {
                eprintln!(
                    "Mitsuba and prism at {n} samples, run {} of {}",
                    run + 1,
                    cfg.runs
                );
                let ours = prism_seconds(&prepared, scene.camera, settings_of(n));
                let (seconds, means) = mitsuba(python, &dir, n, &size)?;
                times.push(seconds);
                pairs.push(seconds / ours);
                image = means;
            }
            let (rmse, flip) =
                errors_of_means(&image, size.width, size.height, &reference, &reference_rgb8);
            points.push(Point {
                name: MITSUBA,
                passes: n,
                samples_per_pixel: n as f64,
                seconds: median_of(times),
                rmse,
                flip,
            });
            ratios.push((n, median_of(pairs)));
        }
    }
    points.extend(denoised.iter().cloned());
    write_csv(&cfg.out_dir.join("path_tracing.csv"), &points)?;

    let mut md = String::new();
    let mode = if cfg.quick { " (quick mode)" } else { "" };
    writeln!(md, "# Path tracing: prism against Mitsuba 3{mode}\n")?;
    writeln!(
        md,
        "The room tests/mitsuba.rs compares with Mitsuba (assets/mitsuba/room.toml lit by \
         assets/mitsuba/rectangle_light.toml; Mitsuba's copy in tests/mitsuba/render.py), \
         {}×{}, `max_depth` {MAX_DEPTH} (Mitsuba's {}), both on every core, against prism's \
         own {}-sample image. Made by `{}cargo run --release{} -- bench path-tracing{}`; medians \
         of {} runs on a shared 2-core machine. Mitsuba's time is its `mi.render` call alone \
         (the scene loaded before); prism's is its passes. At equal samples Mitsuba's image \
         is the noisier: it samples one light per bounce (here one of the two back-to-back \
         rectangles that stand for prism's two-sided one) with independent random numbers, \
         where prism samples every light with stratified ones.\n",
        size.width,
        size.height,
        MAX_DEPTH + 2,
        size.reference_samples.unwrap_or(16),
        if cfg!(feature = "denoise") {
            "OIDN_DIR=… "
        } else {
            ""
        },
        if cfg!(feature = "denoise") {
            " --features denoise"
        } else {
            ""
        },
        super::flags_of_report(cfg.quick),
        cfg.runs
    )?;
    writeln!(
        md,
        "| renderer | samples per pixel | time | mean FLIP | RMSE |\n|---|---|---|---|---|"
    )?;
    for p in &points {
        writeln!(
            md,
            "| {} | {} | {:.3} s | {:.5} | {:.5} |",
            p.name, p.passes, p.seconds, p.flip, p.rmse
        )?;
    }
    denoised_summary(&mut md, &points, &denoised)?;
    match &python {
        Some(_) => {
            writeln!(
                md,
                "\nMitsuba's time over prism's at equal samples: each of Mitsuba's runs paired \
                 with a prism render just before it, the median of the {} pairs' ratios.\n\n\
                 | samples per pixel | Mitsuba's time over prism's |\n|---|---|",
                cfg.runs
            )?;
            for (n, ratio) in &ratios {
                writeln!(md, "| {n} | {ratio:.2}× |")?;
            }
        }
        None => writeln!(
            md,
            "\nMitsuba 3 is not installed here (no Python that imports `mitsuba`, set \
             PRISM_MITSUBA_PYTHON; or no {SCRIPT}): its rows are missing."
        )?,
    }
    super::write_report(&cfg.out_dir, "path_tracing.md", &md)
}

/// The seconds prism's passes take to render `settings` (the scene prepared before).
fn prism_seconds(prepared: &Arc<PreparedScene>, camera: Camera, settings: RenderSettings) -> f64 {
    let mut job = ProgressiveRender::new(prepared.clone(), camera, settings);
    let start = Instant::now();
    while let PassOutcome::Finished(_) = job.step(&NEVER) {}
    start.elapsed().as_secs_f64()
}

/// What the denoised rows show: the samples and time at which a denoised image reaches
/// the 1,024-sample image's error (or, without the `denoise` feature, how to get them).
fn denoised_summary(md: &mut String, points: &[Point], denoised: &[Point]) -> Result<()> {
    if !cfg!(feature = "denoise") {
        writeln!(md, "\nDenoised rows: {}.", prism::render::DENOISE_NOT_BUILT)?;
        return Ok(());
    }
    let Some(target) = points.iter().find(|p| p.name == PRISM && p.passes == 1024) else {
        return Ok(());
    };
    for (metric, value) in [
        ("mean FLIP", (|p: &Point| p.flip) as fn(&Point) -> f64),
        ("RMSE", |p: &Point| p.rmse),
    ] {
        match denoised.iter().find(|p| value(p) <= value(target)) {
            Some(p) => writeln!(
                md,
                "\nDenoised, {} samples per pixel reach the 1,024-sample image's {metric} \
                 ({:.5}, in {:.2} s): {:.5} in {:.2} s, {:.0}% of its time.",
                p.passes,
                value(target),
                target.seconds,
                value(p),
                p.seconds,
                p.seconds / target.seconds * 100.0
            )?,
            None => writeln!(
                md,
                "\nNo denoised image here reaches the 1,024-sample image's {metric} ({:.5}).",
                value(target)
            )?,
        }
    }
    Ok(())
}

/// prism's image at each of `settings` denoised by Open Image Denoise (`--denoise`): the
/// median time of the passes, the guide images and the filter together, and the error.
#[cfg(feature = "denoise")]
fn denoised_points(
    prepared: &Arc<PreparedScene>,
    camera: prism::camera::Camera,
    settings: impl Iterator<Item = RenderSettings>,
    reference: &[Vec3],
    reference_rgb8: &[u8],
    runs: usize,
) -> Result<Vec<Point>> {
    let mut points = Vec::new();
    for s in settings {
        let mut times = Vec::new();
        let mut image = Vec::new();
        for _ in 0..runs {
            let start = std::time::Instant::now();
            let job = prism::render::render(prepared.clone(), camera, s, |_, _| {});
            let guides = prism::render::guide_images(prepared, camera, &s, job.passes_done());
            let film = prism::render::denoise(job.accumulator(), &guides, s.high_dynamic_range)?;
            times.push(start.elapsed().as_secs_f64());
            image = film.pixels.iter().map(|p| p.mean()).collect();
        }
        let (rmse, flip) = errors_of_means(&image, s.width, s.height, reference, reference_rgb8);
        let n = s.samples.unwrap_or(1);
        points.push(Point {
            name: DENOISED,
            passes: n,
            samples_per_pixel: n as f64,
            seconds: median_of(times),
            rmse,
            flip,
        });
    }
    Ok(points)
}

/// Without the `denoise` feature there is nothing to measure.
#[cfg(not(feature = "denoise"))]
fn denoised_points(
    _: &Arc<PreparedScene>,
    _: prism::camera::Camera,
    _: impl Iterator<Item = RenderSettings>,
    _: &[Vec3],
    _: &[u8],
    _: usize,
) -> Result<Vec<Point>> {
    Ok(Vec::new())
}

/// The Python that runs Mitsuba: PRISM_MITSUBA_PYTHON, else `python3`, if it imports it
/// and Mitsuba's copy of the scene is here (a source tree's tests/, not an installed prism).
fn mitsuba_python() -> Option<String> {
    if !Path::new(SCRIPT).is_file() {
        return None;
    }
    let python = std::env::var("PRISM_MITSUBA_PYTHON").unwrap_or_else(|_| "python3".into());
    Command::new(&python)
        .args(["-c", "import mitsuba"])
        .output()
        .is_ok_and(|o| o.status.success())
        .then_some(python)
}

/// Mitsuba's render of the room at `samples` per pixel: the seconds it took and its pixels.
fn mitsuba(python: &str, dir: &Path, samples: u32, size: &Size) -> Result<(f64, Vec<Vec3>)> {
    let out = dir.join("mitsuba.exr");
    let run = Command::new(python)
        .arg(SCRIPT)
        .args([
            "rectangle_light",
            &samples.to_string(),
            &(MAX_DEPTH + 2).to_string(),
        ])
        .arg(&out)
        .arg(dir.join("sky.exr"))
        .args([size.width.to_string(), size.height.to_string()])
        .output()
        .context("cannot run Mitsuba's script")?;
    if !run.status.success() {
        bail!(
            "Mitsuba failed: {}",
            String::from_utf8_lossy(&run.stderr).trim()
        );
    }
    let seconds: f64 = String::from_utf8_lossy(&run.stdout)
        .trim()
        .parse()
        .context("Mitsuba's script did not print its time")?;
    let image = image::open(&out)
        .context("cannot read Mitsuba's image")?
        .into_rgb32f();
    Ok((seconds, image.pixels().map(|p| Vec3::from(p.0)).collect()))
}
