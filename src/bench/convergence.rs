//! `prism bench convergence`: run time against image error for each sampling strategy on
//! the seed scene, and the headline speed figures (docs/benchmarks/).

use super::scenes::sphere_field;
use super::timing::median_of;
use anyhow::{Context, Result};
use glam::Vec3;
use plotters::prelude::*;
use prism::accel::AccelOptions;
use prism::camera::Camera;
use prism::integrator::IntegratorKind;
use prism::integrator::RayCounts;
use prism::render::{
    Accumulator, AdaptiveSettings, PassOutcome, ProgressiveRender, RenderSettings,
};
use prism::sampler::SampleLayout;
use prism::scene::{PreparedScene, Scene};
use std::fmt::Write as _;
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

pub struct Config {
    pub quick: bool,
    /// The adaptive strategy's tolerance.
    pub tolerance: f32,
    /// The adaptive strategy's minimum subsamples per pixel.
    pub min_samples: u32,
    /// The adaptive strategies' minimum subsamples beside an edge.
    pub edge_samples: u32,
    /// The adaptive strategies' least contrast of an edge worth refining beside.
    pub edge_contrast: f32,
    pub out_dir: PathBuf,
    pub runs: usize,
}

pub(super) struct Size {
    pub width: u32,
    pub height: u32,
    pub reference_aa: u32,
    /// Subsamples per pixel of the reference when not reference_aa² (`RenderSettings::samples`).
    pub reference_samples: Option<u32>,
    /// The light transport of the reference (and of the strategies compared with it).
    pub integrator: IntegratorKind,
}

/// A way of sampling the seed scene, compared by the bench.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Strategy {
    /// The seed's supersampling: 2×2 subsamples at the cell centres, one finished image.
    SeedGrid,
    /// N×N subsamples at the cell centres, one finished image per N.
    FixedGrid,
    /// The viewer's mode: one jittered subsample of an 8×8 pattern per pass.
    Progressive,
    /// `Progressive` at the cell centres.
    ProgressiveCentres,
    /// `Progressive` with adaptive stopping.
    Adaptive,
    /// `Adaptive` at the cell centres.
    AdaptiveCentres,
}

impl Strategy {
    const ALL: [Strategy; 6] = [
        Strategy::SeedGrid,
        Strategy::FixedGrid,
        Strategy::Progressive,
        Strategy::ProgressiveCentres,
        Strategy::Adaptive,
        Strategy::AdaptiveCentres,
    ];

    /// What the table, the CSV and the plot call it.
    fn name(self) -> &'static str {
        match self {
            Strategy::SeedGrid => "seed 2×2 grid",
            Strategy::FixedGrid => "fixed N×N grid",
            Strategy::Progressive => "progressive",
            Strategy::ProgressiveCentres => "progressive, cell centres",
            Strategy::Adaptive => "adaptive",
            Strategy::AdaptiveCentres => "adaptive, cell centres",
        }
    }

    /// Whether the error is measured after every pass rather than once finished.
    fn every_pass(self) -> bool {
        !matches!(self, Strategy::SeedGrid | Strategy::FixedGrid)
    }

    /// The plot's colour.
    fn color(self) -> RGBColor {
        match self {
            Strategy::SeedGrid => RGBColor(200, 0, 0),
            Strategy::FixedGrid => RGBColor(230, 140, 0),
            Strategy::Progressive => RGBColor(0, 90, 200),
            Strategy::ProgressiveCentres => RGBColor(120, 170, 240),
            Strategy::Adaptive => RGBColor(0, 150, 60),
            Strategy::AdaptiveCentres => RGBColor(130, 210, 130),
        }
    }
}

/// One measurement: a strategy's image after some passes.
#[derive(Clone, Debug)]
pub(super) struct Point {
    /// The strategy's name.
    pub name: &'static str,
    pub passes: u32,
    pub samples_per_pixel: f64,
    pub seconds: f64,
    pub rmse: f64,
    pub flip: f64,
}

/// When a strategy's error is measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Measure {
    /// Once, on the finished image.
    Finished,
    /// After every pass.
    EveryPass,
}

/// A strategy the bench times: its name, when its error is measured, and its settings.
pub(super) struct Timed {
    pub name: &'static str,
    pub measure: Measure,
    pub settings: RenderSettings,
}

/// Times each strategy's passes on `prepared` (`runs` times, interleaved), then replays
/// each once untimed to measure its error against `reference`: the points, and the rays
/// traced and their seconds over all timed passes.
pub(super) fn measure(
    prepared: &Arc<PreparedScene>,
    camera: Camera,
    strategies: &[Timed],
    reference: &[Vec3],
    runs: usize,
) -> (Vec<Point>, RayCounts, f64) {
    let reference_rgb8 = {
        let s = &strategies[0].settings;
        to_rgb8(reference, s.width, s.height)
    };
    // Time: each strategy's passes back to back with nothing in between, `runs` times,
    // interleaved strategy by strategy so that a slow spell of the shared machine falls on
    // all of them alike. Measuring the error between timed passes would evict the scene and
    // the film from the cache and charge the next pass for it.
    let mut rays = RayCounts::default();
    let mut ray_seconds = 0.0;
    let mut elapsed: Vec<Vec<Vec<f64>>> = vec![Vec::new(); strategies.len()];
    for run in 0..runs {
        eprintln!("timing run {} of {}", run + 1, runs);
        for (timed, runs) in strategies.iter().zip(&mut elapsed) {
            let mut job = ProgressiveRender::new(prepared.clone(), camera, timed.settings);
            let mut seconds = 0.0;
            let mut cumulative = Vec::new();
            loop {
                // The whole step: the pass and, for adaptive sampling, deciding which
                // pixels stop.
                let start = Instant::now();
                let PassOutcome::Finished(stats) = job.step(&NEVER) else {
                    break;
                };
                seconds += start.elapsed().as_secs_f64();
                cumulative.push(seconds);
                rays += stats.rays;
                ray_seconds += stats.seconds;
            }
            runs.push(cumulative);
        }
    }
    // Error: one untimed replay of each strategy. A render depends only on the scene, the
    // settings and the pass index, so the replay's images are the timed runs' images.
    let mut points = Vec::new();
    for (timed, runs) in strategies.iter().zip(&elapsed) {
        let mut job = ProgressiveRender::new(prepared.clone(), camera, timed.settings);
        while let PassOutcome::Finished(_) = job.step(&NEVER) {
            let pass = job.passes_done();
            let wanted = match timed.measure {
                Measure::Finished => job.is_converged(),
                Measure::EveryPass => true,
            };
            if !wanted {
                continue;
            }
            let seconds = median_of(runs.iter().map(|r| r[pass as usize - 1]).collect());
            let (rmse, flip) = errors(job.accumulator(), reference, &reference_rgb8);
            eprintln!(
                "{:>26}: pass {pass:>3}, {seconds:>7.3} s, RMSE {rmse:.5}, FLIP {flip:.5}",
                timed.name
            );
            points.push(Point {
                name: timed.name,
                passes: pass,
                samples_per_pixel: job.samples_per_pixel(),
                seconds,
                rmse,
                flip,
            });
        }
    }
    (points, rays, ray_seconds)
}

pub(super) const NEVER: fn() -> bool = || false;

pub fn run(cfg: Config) -> Result<()> {
    let size = if cfg.quick {
        Size {
            width: 160,
            height: 120,
            reference_aa: 16,
            reference_samples: None,
            integrator: IntegratorKind::Whitted,
        }
    } else {
        Size {
            width: 800,
            height: 600,
            reference_aa: 16,
            reference_samples: None,
            integrator: IntegratorKind::Whitted,
        }
    };
    std::fs::create_dir_all(&cfg.out_dir)
        .with_context(|| format!("cannot create {}", cfg.out_dir.display()))?;
    let scene = prism::seed::scene()?;
    let prepared = Arc::new(PreparedScene::new(&scene));
    let reference = reference(prism::seed::SCENE_TOML, &prepared, scene.camera, &size)?;

    let settings = |aa: u32, layout: SampleLayout, adaptive: Option<AdaptiveSettings>| {
        let mut s = RenderSettings::new(size.width, size.height, aa);
        s.layout = layout;
        s.adaptive = adaptive;
        s
    };
    let adaptive = Some(AdaptiveSettings {
        tolerance: cfg.tolerance,
        min_samples: cfg.min_samples,
        edge_samples: cfg.edge_samples,
        edge_contrast: cfg.edge_contrast,
    });
    // Each strategy with the settings of each image it makes.
    let timed = |strategy: Strategy, settings| Timed {
        name: strategy.name(),
        measure: if strategy.every_pass() {
            Measure::EveryPass
        } else {
            Measure::Finished
        },
        settings,
    };
    let mut strategies = vec![timed(
        Strategy::SeedGrid,
        settings(2, SampleLayout::Grid, None),
    )];
    for n in [1, 2, 3, 4, 6, 8] {
        strategies.push(timed(
            Strategy::FixedGrid,
            settings(n, SampleLayout::Grid, None),
        ));
    }
    strategies.extend([
        timed(
            Strategy::Progressive,
            settings(8, SampleLayout::Stratified, None),
        ),
        timed(
            Strategy::ProgressiveCentres,
            settings(8, SampleLayout::Grid, None),
        ),
        timed(
            Strategy::Adaptive,
            settings(8, SampleLayout::Stratified, adaptive),
        ),
        timed(
            Strategy::AdaptiveCentres,
            settings(8, SampleLayout::Grid, adaptive),
        ),
    ]);
    let (points, rays, ray_seconds) =
        measure(&prepared, scene.camera, &strategies, &reference, cfg.runs);

    write_csv(&cfg.out_dir.join("convergence.csv"), &points)?;
    let series: Vec<(&str, RGBColor)> = Strategy::ALL
        .iter()
        .map(|s| (s.name(), s.color()))
        .collect();
    plot(&cfg.out_dir.join("convergence.svg"), &points, &series)?;
    let headline = headline(&cfg, &scene, &prepared, &size, &points, rays, ray_seconds)?;
    std::fs::write(cfg.out_dir.join("results.md"), &headline)?;
    println!("{headline}");
    eprintln!(
        "wrote convergence.csv, convergence.svg and results.md in {}",
        cfg.out_dir.display()
    );
    Ok(())
}

/// The converged reference (reference_aa² subsamples, every secondary ray traced), cached
/// under target/ by scene text and size.
pub(super) fn reference(
    text: &str,
    scene: &Arc<PreparedScene>,
    camera: Camera,
    size: &Size,
) -> Result<Vec<Vec3>> {
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    (
        text,
        size.width,
        size.height,
        size.reference_aa,
        size.reference_samples,
        size.integrator,
        env!("CARGO_PKG_VERSION"),
    )
        .hash(&mut hasher);
    let dir = cache_dir();
    std::fs::create_dir_all(&dir)
        .with_context(|| format!("cannot create the cache folder {}", dir.display()))?;
    let cache = dir.join(format!("reference-{:016x}.f32", hasher.finish()));
    let count = (size.width * size.height) as usize;
    if let Ok(bytes) = std::fs::read(&cache)
        && bytes.len() == count * 12
    {
        eprintln!("reference: cached {}", cache.display());
        return Ok(bytes
            .chunks_exact(12)
            .map(|c| {
                let f = |i: usize| f32::from_le_bytes(c[i..i + 4].try_into().unwrap());
                Vec3::new(f(0), f(4), f(8))
            })
            .collect());
    }
    let start = Instant::now();
    let mut settings = RenderSettings::new(size.width, size.height, size.reference_aa);
    settings.samples = size.reference_samples;
    settings.min_weight = 0.0;
    settings.integrator = size.integrator;
    let mut job = ProgressiveRender::new(scene.clone(), camera, settings);
    while let PassOutcome::Finished(_) = job.step(&NEVER) {}
    let means: Vec<Vec3> = job.accumulator().pixels.iter().map(|p| p.mean()).collect();
    let bytes: Vec<u8> = means
        .iter()
        .flat_map(|v| [v.x, v.y, v.z])
        .flat_map(f32::to_le_bytes)
        .collect();
    prism::render::write_bytes(&cache, &bytes)?;
    eprintln!(
        "reference: {} subsamples per pixel in {:.1} s, cached {}",
        settings.total_passes(),
        start.elapsed().as_secs_f64(),
        cache.display()
    );
    Ok(means)
}

pub(super) fn to_rgb8(means: &[Vec3], width: u32, height: u32) -> Vec<u8> {
    let mut v = Vec::with_capacity(means.len() * 3);
    for m in means {
        v.extend_from_slice(&prism::render::to_8bit(*m));
    }
    debug_assert_eq!(v.len(), (width * height * 3) as usize);
    v
}

/// RMSE of the pixel means (clamped to the display range) and mean FLIP of the 8-bit images.
fn errors(acc: &Accumulator, reference: &[Vec3], reference_rgb8: &[u8]) -> (f64, f64) {
    let means: Vec<Vec3> = acc.pixels.iter().map(|p| p.mean()).collect();
    errors_of_means(&means, acc.width, acc.height, reference, reference_rgb8)
}

/// `errors` of an image given as its pixels' colours, row by row.
pub(super) fn errors_of_means(
    means: &[Vec3],
    width: u32,
    height: u32,
    reference: &[Vec3],
    reference_rgb8: &[u8],
) -> (f64, f64) {
    let mut sum = 0.0f64;
    for (p, r) in means.iter().zip(reference) {
        let d = p.clamp(Vec3::ZERO, Vec3::ONE) - r.clamp(Vec3::ZERO, Vec3::ONE);
        sum += d.length_squared() as f64;
    }
    let rmse = (sum / (reference.len() * 3) as f64).sqrt();
    let test = nv_flip::FlipImageRgb8::with_data(width, height, &to_rgb8(means, width, height));
    let refi = nv_flip::FlipImageRgb8::with_data(width, height, reference_rgb8);
    let map = nv_flip::flip(refi, test, nv_flip::DEFAULT_PIXELS_PER_DEGREE);
    let flip = nv_flip::FlipPool::from_image(&map).mean() as f64;
    (rmse, flip)
}

pub(super) fn write_csv(path: &Path, points: &[Point]) -> Result<()> {
    let mut csv = String::from("strategy,passes,samples_per_pixel,seconds,rmse,mean_flip\n");
    for p in points {
        writeln!(
            csv,
            "{},{},{:.4},{:.6},{:.6},{:.6}",
            p.name, p.passes, p.samples_per_pixel, p.seconds, p.rmse, p.flip
        )?;
    }
    prism::render::write_bytes(path, csv.as_bytes())?;
    Ok(())
}

/// Error against time, one curve per entry of `series` (a strategy's name and colour).
pub(super) fn plot(path: &Path, points: &[Point], series: &[(&str, RGBColor)]) -> Result<()> {
    let root = SVGBackend::new(path, (1100, 460)).into_drawing_area();
    root.fill(&WHITE)?;
    let (left, right) = root.split_horizontally(550);
    for (area, metric, name) in [(&left, 0, "mean FLIP"), (&right, 1, "RMSE")] {
        let value = |p: &Point| if metric == 0 { p.flip } else { p.rmse };
        let xs = points.iter().map(|p| p.seconds);
        let ys = points.iter().map(value);
        let (x0, x1) = (
            xs.clone().fold(f64::MAX, f64::min) * 0.8,
            xs.fold(0.0, f64::max) * 1.25,
        );
        let (y0, y1) = (
            ys.clone().fold(f64::MAX, f64::min) * 0.8,
            ys.fold(0.0, f64::max) * 1.25,
        );
        let mut chart = ChartBuilder::on(area)
            .caption(format!("{name} against render time"), ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d((x0..x1).log_scale(), (y0.max(1e-6)..y1).log_scale())?;
        chart
            .configure_mesh()
            .bold_line_style(RGBColor(215, 215, 215))
            .light_line_style(RGBColor(240, 240, 240))
            .x_desc("seconds (2 threads, log)")
            .y_desc(format!("{name} against the reference (log)"))
            .draw()?;
        for &(name, color) in series {
            let of_series = points.iter().filter(|p| p.name == name);
            let series: Vec<(f64, f64)> =
                of_series.clone().map(|p| (p.seconds, value(p))).collect();
            // A strategy measured after every pass is a line, dotted at power-of-two passes
            // only.
            let every_pass = series.len() > 16;
            let dots: Vec<(f64, f64)> = of_series
                .filter(|p| !every_pass || p.passes.is_power_of_two())
                .map(|p| (p.seconds, value(p)))
                .collect();
            chart
                .draw_series(LineSeries::new(series.clone(), color.stroke_width(2)))?
                .label(name)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
            // Single-image strategies (the seed's 2×2) are one larger dot.
            let radius = if series.len() == 1 { 6 } else { 3 };
            chart.draw_series(dots.iter().map(|&p| Circle::new(p, radius, color.filled())))?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .border_style(BLACK)
            .background_style(WHITE.mix(0.9))
            .draw()?;
    }
    root.present()?;
    Ok(())
}

/// Median seconds of `runs` first passes of `scene` at the given size.
fn pass_seconds(scene: &Arc<PreparedScene>, camera: Camera, w: u32, h: u32, runs: usize) -> f64 {
    pass_seconds_with(scene, camera, RenderSettings::new(w, h, 1), runs)
}

/// Median seconds of `runs` first passes (which include building the first-hit tiles).
fn pass_seconds_with(
    scene: &Arc<PreparedScene>,
    camera: Camera,
    settings: RenderSettings,
    runs: usize,
) -> f64 {
    median_of(
        (0..runs)
            .map(|_| {
                let mut job = ProgressiveRender::new(scene.clone(), camera, settings);
                match job.step(&NEVER) {
                    PassOutcome::Finished(s) => s.seconds,
                    _ => unreachable!("a first pass always finishes"),
                }
            })
            .collect(),
    )
}

/// Where the reference images are cached between runs: the user's cache folder
/// ($XDG_CACHE_HOME or ~/.cache), else the system's temporary folder.
fn cache_dir() -> PathBuf {
    let base = std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache")))
        .unwrap_or_else(std::env::temp_dir);
    base.join("prism/bench")
}

/// The first point of strategy `name` whose error by `metric` is at most `error`.
pub(super) fn first_below<'p>(
    points: &'p [Point],
    name: &str,
    error: f64,
    metric: impl Fn(&Point) -> f64,
) -> Option<&'p Point> {
    points.iter().find(|p| p.name == name && metric(p) <= error)
}

fn headline(
    cfg: &Config,
    scene: &Scene,
    prepared: &Arc<PreparedScene>,
    size: &Size,
    points: &[Point],
    rays: RayCounts,
    ray_seconds: f64,
) -> Result<String> {
    let runs = cfg.runs;
    let (w, h) = (size.width, size.height);
    let mut md = String::new();
    let mode = if cfg.quick { " (quick mode)" } else { "" };
    writeln!(md, "# Benchmark results{mode}\n")?;
    writeln!(
        md,
        "Seed scene, {w}×{h}, reference {n}×{n} subsamples. Made by `cargo run --release -- bench convergence{}`; \
         medians of {runs} runs on a shared 2-core machine.\n",
        super::flags_of_report(cfg.quick),
        n = size.reference_aa
    )?;
    speed_section(&mut md, cfg, scene, prepared, rays, ray_seconds, size)?;
    shortcuts_section(&mut md, cfg, scene, prepared, size)?;
    grid_error_section(&mut md, points)?;
    resolution_section(&mut md, cfg, scene, prepared)?;
    object_count_section(&mut md, cfg, size)?;
    writeln!(
        md,
        "\n![Error against time](convergence.svg)\n\nThe curves are in `convergence.csv`."
    )?;
    Ok(md)
}

/// The headline table: one pass, rays per second, the two-thread speed-up.
fn speed_section(
    md: &mut String,
    cfg: &Config,
    scene: &Scene,
    prepared: &Arc<PreparedScene>,
    rays: RayCounts,
    ray_seconds: f64,
    size: &Size,
) -> Result<()> {
    let runs = cfg.runs;
    let (w, h) = (size.width, size.height);
    let pass = pass_seconds(prepared, scene.camera, w, h, runs);
    writeln!(md, "| measure | value |\n|---|---|")?;
    writeln!(
        md,
        "| one progressive pass (1 subsample per pixel), median | {:.1} ms |",
        pass * 1e3
    )?;
    writeln!(
        md,
        "| rays per second, all kinds (over every pass above) | {:.1} M/s ({:.1} M/s per core) |",
        rays.total() as f64 / ray_seconds / 1e6,
        rays.total() as f64 / ray_seconds / 2e6
    )?;
    writeln!(
        md,
        "| rays traced: primary / shadow / secondary | {} / {} / {} |",
        rays.primary, rays.shadow, rays.secondary
    )?;
    let one = prism::render::thread_pool(Some(1))?;
    let single = one.install(|| pass_seconds(prepared, scene.camera, w, h, runs));
    writeln!(
        md,
        "| speed-up from 1 to 2 threads | {:.2}× ({:.1} ms → {:.1} ms) |",
        single / pass,
        single * 1e3,
        pass * 1e3
    )?;

    Ok(())
}

/// What each shortcut buys: the same pass with one of them turned off.
fn shortcuts_section(
    md: &mut String,
    cfg: &Config,
    scene: &Scene,
    prepared: &Arc<PreparedScene>,
    size: &Size,
) -> Result<()> {
    let runs = cfg.runs;
    let (w, h) = (size.width, size.height);
    // What each shortcut buys: the same pass with one of them turned off.
    writeln!(
        md,
        "\n## What each shortcut buys (one pass, {w}×{h}, median)\n\n\
         Each row turns one shortcut off. The tiles, the light buffer and the BVH leave the \
         image unchanged; \
         the faint-ray cutoff moves no pixel by more than one 8-bit level \
         (`tests/optimizations.rs`).\n"
    )?;
    writeln!(md, "| turned off | pass | against all on |\n|---|---|---|")?;
    let all_on = RenderSettings::new(w, h, 1);
    let without = |options: AccelOptions| Arc::new(PreparedScene::with_options(scene, options));
    let all = AccelOptions::ALL;
    let rows: [(&str, Arc<PreparedScene>, RenderSettings); 5] = [
        ("nothing", prepared.clone(), all_on),
        (
            "first-hit tiles (primary rays traverse the BVH)",
            without(AccelOptions {
                first_hit_tiles: false,
                ..all
            }),
            all_on,
        ),
        (
            "light buffer (shadow rays traverse the BVH)",
            without(AccelOptions {
                light_buffers: false,
                ..all
            }),
            all_on,
        ),
        (
            "faint-ray cutoff (every secondary ray traced)",
            prepared.clone(),
            RenderSettings {
                min_weight: 0.0,
                ..all_on
            },
        ),
        (
            "BVH (secondary rays test every primitive; shadow rays keep the light buffer)",
            without(AccelOptions { bvh: false, ..all }),
            all_on,
        ),
    ];
    // Interleaved run by run, so that a slow spell of the shared machine falls on every
    // row alike rather than on one.
    let mut times = vec![Vec::with_capacity(runs); rows.len()];
    for _ in 0..runs {
        for (row, (_, scene_variant, settings)) in rows.iter().enumerate() {
            times[row].push(pass_seconds_with(scene_variant, scene.camera, *settings, 1));
        }
    }
    let medians: Vec<f64> = times.into_iter().map(median_of).collect();
    for ((what, _, _), t) in rows.iter().zip(&medians) {
        writeln!(
            md,
            "| {what} | {:.1} ms | {:.2}× |",
            t * 1e3,
            t / medians[0]
        )?;
    }

    Ok(())
}

/// How soon each progressive strategy reaches the 4×4 grid's error.
fn grid_error_section(md: &mut String, points: &[Point]) -> Result<()> {
    // Time to reach the error of the full 4×4 grid.
    let grid4 = points
        .iter()
        .find(|p| p.name == Strategy::FixedGrid.name() && p.passes == 16)
        .context("the 4×4 grid was measured")?;
    writeln!(
        md,
        "\n## Time to reach the 4×4 grid's error (mean FLIP {:.5})\n",
        grid4.flip
    )?;
    writeln!(
        md,
        "| strategy | time | subsamples per pixel | share of the grid's time |\n|---|---|---|---|"
    )?;
    writeln!(
        md,
        "| fixed 4×4 grid | {:.3} s | 16 | 100% |",
        grid4.seconds
    )?;
    for strategy in Strategy::ALL.into_iter().filter(|s| s.every_pass()) {
        let name = strategy.name();
        match first_below(points, name, grid4.flip, |p| p.flip) {
            Some(p) => writeln!(
                md,
                "| {name} | {:.3} s | {:.2} | {:.0}% |",
                p.seconds,
                p.samples_per_pixel,
                p.seconds / grid4.seconds * 100.0
            )?,
            None => writeln!(md, "| {name} | not reached | | |")?,
        }
    }

    Ok(())
}

/// The cost of a pass against the image size.
fn resolution_section(
    md: &mut String,
    cfg: &Config,
    scene: &Scene,
    prepared: &Arc<PreparedScene>,
) -> Result<()> {
    let runs = cfg.runs;
    writeln!(
        md,
        "\n## Cost against resolution (one pass)\n\n| image | time | per pixel |\n|---|---|---|"
    )?;
    let sizes: &[(u32, u32)] = if cfg.quick {
        &[(80, 60), (160, 120)]
    } else {
        &[(200, 150), (400, 300), (800, 600), (1600, 1200)]
    };
    for &(sw, sh) in sizes {
        let t = pass_seconds(prepared, scene.camera, sw, sh, runs);
        writeln!(
            md,
            "| {sw}×{sh} | {:.1} ms | {:.0} ns |",
            t * 1e3,
            t * 1e9 / (sw * sh) as f64
        )?;
    }

    Ok(())
}

/// The cost of a pass against the number of objects.
fn object_count_section(md: &mut String, cfg: &Config, size: &Size) -> Result<()> {
    let runs = cfg.runs;
    let (w, h) = (size.width, size.height);
    writeln!(
        md,
        "\n## Cost against object count (one pass, {w}×{h}, `sphere_field` scenes)\n\n\
         | spheres | BVH nodes | build | pass | against 10 spheres |\n|---|---|---|---|---|"
    )?;
    let counts: &[usize] = if cfg.quick {
        &[10, 1000]
    } else {
        &[10, 100, 1000, 10_000]
    };
    let mut base = None;
    for &n in counts {
        let field = sphere_field(n);
        let start = Instant::now();
        let prepared = Arc::new(PreparedScene::new(&field));
        let build = start.elapsed().as_secs_f64();
        let t = pass_seconds(&prepared, field.camera, w, h, runs);
        let base = *base.get_or_insert(t);
        writeln!(
            md,
            "| {n} | {} | {:.1} ms | {:.1} ms | {:.2}× |",
            prepared.geometry.accel().bvh_nodes(),
            build * 1e3,
            t * 1e3,
            t / base
        )?;
    }
    Ok(())
}
