//! `prism bench soft-shadows`: run time against image error for the sampling strategies on
//! a scene of area, sphere and spot lights (assets/scenes/soft_shadows.toml), where the
//! noise is the lights' rather than the edges'.

use super::convergence::{Measure, Size, Timed, first_below, measure, plot, reference, write_csv};
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

const SCENE: &str = include_str!("../../assets/scenes/soft_shadows.toml");

const FIXED: &str = "fixed count, one image each";
const PROGRESSIVE: &str = "progressive (256 passes)";
const ADAPTIVE: [(&str, f32); 3] = [
    ("adaptive, tolerance 1/256 (default)", 1.0 / 256.0),
    ("adaptive, tolerance 1e-3", 1e-3),
    ("adaptive, tolerance 3e-4", 3e-4),
];

pub fn run(cfg: Config) -> Result<()> {
    let size = if cfg.quick {
        Size {
            width: 160,
            height: 100,
            reference_aa: 4,
            reference_samples: Some(1024),
            integrator: IntegratorKind::Whitted,
        }
    } else {
        Size {
            width: 320,
            height: 200,
            reference_aa: 4,
            reference_samples: Some(4096),
            integrator: IntegratorKind::Whitted,
        }
    };
    std::fs::create_dir_all(&cfg.out_dir)
        .with_context(|| format!("cannot create {}", cfg.out_dir.display()))?;
    let scene = parse_scene(
        SCENE,
        std::path::Path::new("assets/scenes/soft_shadows.toml"),
        std::path::Path::new("."),
    )?;
    let prepared = Arc::new(PreparedScene::new(&scene));
    let reference = reference(SCENE, &prepared, scene.camera, &size)?;
    let settings = |samples: u32, adaptive: Option<f32>| {
        let mut s = RenderSettings::new(size.width, size.height, 4);
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
    strategies.push(Timed {
        name: PROGRESSIVE,
        measure: Measure::PowersOfTwo,
        settings: settings(256, None),
    });
    for (name, tolerance) in ADAPTIVE {
        strategies.push(Timed {
            name,
            measure: Measure::PowersOfTwo,
            settings: settings(256, Some(tolerance)),
        });
    }
    let (points, _, _) = measure(&prepared, scene.camera, &strategies, &reference, cfg.runs);

    write_csv(&cfg.out_dir.join("soft_shadows.csv"), &points)?;
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
    plot(&cfg.out_dir.join("soft_shadows.svg"), &points, &series)?;

    let mut md = String::new();
    let mode = if cfg.quick { " (quick mode)" } else { "" };
    writeln!(md, "# Soft shadows: error against time{mode}\n")?;
    writeln!(
        md,
        "assets/scenes/soft_shadows.toml at {}×{}, against a reference of {} subsamples per \
         pixel. Made by `cargo run --release -- bench soft-shadows{}`; medians of {} runs on a \
         shared 2-core machine.\n",
        size.width,
        size.height,
        size.reference_samples.unwrap_or(16),
        super::flags_of_report(cfg.quick),
        cfg.runs
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
    writeln!(
        md,
        "\n## Time to reach the 64-sample image's error (mean FLIP {:.5})\n\n\
         | strategy | time | subsamples per pixel | share of the fixed image's time |\n|---|---|---|---|",
        target.flip
    )?;
    writeln!(md, "| fixed 64 | {:.3} s | 64 | 100% |", target.seconds)?;
    for name in [PROGRESSIVE]
        .into_iter()
        .chain(ADAPTIVE.iter().map(|a| a.0))
    {
        match first_below(&points, name, target.flip) {
            Some(p) => writeln!(
                md,
                "| {name} | {:.3} s | {:.2} | {:.0}% |",
                p.seconds,
                p.samples_per_pixel,
                p.seconds / target.seconds * 100.0
            )?,
            None => writeln!(md, "| {name} | not reached | | |")?,
        }
    }
    writeln!(
        md,
        "\n![Error against time](soft_shadows.svg)\n\nThe curves are in `soft_shadows.csv`."
    )?;
    std::fs::write(cfg.out_dir.join("soft_shadows.md"), &md)?;
    println!("{md}");
    Ok(())
}
