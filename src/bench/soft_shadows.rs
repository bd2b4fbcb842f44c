//! `prism bench soft-shadows`: run time against image error for the sampling strategies on
//! three noisy scenes, where the noise is the lights', the lens's or the paths' rather than
//! the edges': area, sphere and spot lights (assets/scenes/soft_shadows.toml), a lens and
//! glossy mirrors under an area light (assets/scenes/materials.toml), and the Cornell room
//! path traced (assets/scenes/cornell.toml).

use super::convergence::{
    Measure, Point, Size, Timed, first_below, measure, plot, reference, write_csv,
};
use anyhow::{Context, Result};
use plotters::style::RGBColor;
use prism::integrator::IntegratorKind;
use prism::render::{AdaptiveSettings, RenderSettings};
use prism::scene::PreparedScene;
use prism::scene_file::parse_scene;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::sync::Arc;

pub struct Config {
    pub quick: bool,
    pub out_dir: PathBuf,
    pub runs: usize,
}

/// A noisy scene the strategies are raced on.
struct NoisyScene {
    /// The section's title, and the stem of its CSV and plot.
    title: &'static str,
    stem: &'static str,
    path: &'static str,
    text: &'static str,
    integrator: IntegratorKind,
    /// The image's width and height (the quick mode's are half).
    size: (u32, u32),
}

const SCENES: [NoisyScene; 3] = [
    NoisyScene {
        title: "Soft shadows",
        stem: "soft_shadows",
        path: "assets/scenes/soft_shadows.toml",
        text: include_str!("../../assets/scenes/soft_shadows.toml"),
        integrator: IntegratorKind::Whitted,
        size: (320, 200),
    },
    NoisyScene {
        title: "A lens, glossy mirrors and an area light",
        stem: "lens",
        path: "assets/scenes/materials.toml",
        text: include_str!("../../assets/scenes/materials.toml"),
        integrator: IntegratorKind::Whitted,
        size: (320, 200),
    },
    NoisyScene {
        title: "The Cornell room, path traced",
        stem: "path_traced",
        path: "assets/scenes/cornell.toml",
        text: include_str!("../../assets/scenes/cornell.toml"),
        integrator: IntegratorKind::Path,
        // A square room, and paths cost several rays each: a smaller image.
        size: (160, 160),
    },
];

const FIXED: &str = "fixed count, one image each";
const PROGRESSIVE: &str = "progressive (256 passes)";
const ADAPTIVE: [(&str, f32); 3] = [
    ("adaptive, tolerance 1/256 (default)", 1.0 / 256.0),
    ("adaptive, tolerance 1e-3", 1e-3),
    ("adaptive, tolerance 3e-4", 3e-4),
];

pub fn run(cfg: Config) -> Result<()> {
    std::fs::create_dir_all(&cfg.out_dir)
        .with_context(|| format!("cannot create {}", cfg.out_dir.display()))?;
    let mut md = String::new();
    let mode = if cfg.quick { " (quick mode)" } else { "" };
    writeln!(md, "# Noise: error against time{mode}\n")?;
    writeln!(
        md,
        "Made by `cargo run --release -- bench soft-shadows{}`; medians of {} runs on a \
         shared 2-core machine. Each scene is measured against a long reference render of \
         the same light transport. How adaptive sampling treats noise: \
         [effects.md](../effects.md#more-samples-and-adaptive-sampling-of-noise).",
        super::flags_of_report(cfg.quick),
        cfg.runs
    )?;
    for scene in &SCENES {
        race(&cfg, scene, &mut md)?;
    }
    std::fs::write(cfg.out_dir.join("soft_shadows.md"), &md)?;
    println!("{md}");
    Ok(())
}

/// Races the strategies on `noisy` and adds its section to `md`.
fn race(cfg: &Config, noisy: &NoisyScene, md: &mut String) -> Result<()> {
    let (width, height) = noisy.size;
    let (width, height, reference_samples) = if cfg.quick {
        (width / 2, height / 2, 1024)
    } else {
        (width, height, 4096)
    };
    let size = Size {
        width,
        height,
        reference_aa: 4,
        reference_samples: Some(reference_samples),
        integrator: noisy.integrator,
    };
    let scene = parse_scene(
        noisy.text,
        std::path::Path::new(noisy.path),
        std::path::Path::new("."),
    )?;
    let prepared = Arc::new(PreparedScene::new(&scene));
    let reference = reference(noisy.text, &prepared, scene.camera, &size)?;
    let settings = |samples: u32, adaptive: Option<f32>| {
        let mut s = RenderSettings::new(width, height, 4);
        s.integrator = noisy.integrator;
        s.samples = Some(samples);
        s.adaptive = adaptive.map(|tolerance| AdaptiveSettings {
            tolerance,
            ..AdaptiveSettings::default()
        });
        s
    };
    let mut strategies: Vec<Timed> = [4, 16, 64, 256]
        .into_iter()
        .map(|n| Timed {
            name: FIXED,
            measure: Measure::Finished,
            settings: settings(n, None),
        })
        .collect();
    // Measured after every pass, so that the time to reach an error is the pass's that
    // reaches it, between adaptive sampling's power-of-two checks too.
    strategies.push(Timed {
        name: PROGRESSIVE,
        measure: Measure::EveryPass,
        settings: settings(256, None),
    });
    for (name, tolerance) in ADAPTIVE {
        strategies.push(Timed {
            name,
            measure: Measure::EveryPass,
            settings: settings(256, Some(tolerance)),
        });
    }
    let (points, _, _) = measure(&prepared, scene.camera, &strategies, &reference, cfg.runs);

    write_csv(&cfg.out_dir.join(format!("{}.csv", noisy.stem)), &points)?;
    let mut series = vec![
        (FIXED, RGBColor(230, 140, 0)),
        (PROGRESSIVE, RGBColor(0, 90, 200)),
    ];
    series.extend(
        ADAPTIVE
            .iter()
            .zip([
                RGBColor(0, 150, 60),
                RGBColor(110, 190, 60),
                RGBColor(150, 80, 190),
            ])
            .map(|(&(name, _), color)| (name, color)),
    );
    plot(
        &cfg.out_dir.join(format!("{}.svg", noisy.stem)),
        &points,
        &series,
    )?;

    let transport = match noisy.integrator {
        IntegratorKind::Path => ", path traced",
        IntegratorKind::Whitted => "",
    };
    writeln!(
        md,
        "\n## {}\n\n{} at {width}×{height}{transport}, against a reference of \
         {reference_samples} subsamples per pixel.\n",
        noisy.title, noisy.path,
    )?;
    writeln!(
        md,
        "| strategy | subsamples per pixel | time | mean FLIP | RMSE |\n|---|---|---|---|---|"
    )?;
    for p in points.iter().filter(|p| p.name == FIXED) {
        writeln!(
            md,
            "| {} {} | {:.0} | {:.3} s | {:.5} | {:.5} |",
            p.name, p.passes, p.samples_per_pixel, p.seconds, p.flip, p.rmse
        )?;
    }
    for (name, _) in ADAPTIVE {
        if let Some(p) = points.iter().rfind(|p| p.name == name) {
            writeln!(
                md,
                "| {name}, converged | {:.2} | {:.3} s | {:.5} | {:.5} |",
                p.samples_per_pixel, p.seconds, p.flip, p.rmse
            )?;
        }
    }
    let target = points
        .iter()
        .find(|p| p.name == FIXED && p.passes == 64)
        .context("the fixed 64-sample image was measured")?;
    reaching(md, &points, target, "mean FLIP", |p| p.flip)?;
    reaching(md, &points, target, "RMSE", |p| p.rmse)?;
    writeln!(
        md,
        "\n![Error against time]({0}.svg)\n\nThe curves are in `{0}.csv`.",
        noisy.stem
    )?;
    Ok(())
}

/// The table of each strategy's time to reach `target`'s error by `metric` (`name`).
fn reaching(
    md: &mut String,
    points: &[Point],
    target: &Point,
    name: &str,
    metric: impl Fn(&Point) -> f64,
) -> Result<()> {
    writeln!(
        md,
        "\n### Time to reach the 64-sample image's {name} ({:.5})\n\n\
         | strategy | time | subsamples per pixel | share of the fixed image's time |\n\
         |---|---|---|---|",
        metric(target)
    )?;
    writeln!(md, "| fixed 64 | {:.3} s | 64 | 100% |", target.seconds)?;
    for strategy in [PROGRESSIVE]
        .into_iter()
        .chain(ADAPTIVE.iter().map(|a| a.0))
    {
        match first_below(points, strategy, metric(target), &metric) {
            Some(p) => writeln!(
                md,
                "| {strategy} | {:.3} s | {:.2} | {:.0}% |",
                p.seconds,
                p.samples_per_pixel,
                p.seconds / target.seconds * 100.0
            )?,
            None => writeln!(md, "| {strategy} | not reached | | |")?,
        }
    }
    Ok(())
}
