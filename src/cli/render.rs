//! `prism render`: a headless render to PNG with a progress bar.

use super::stats::{Rays, RenderStats, Seconds, peak_memory_bytes};
use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use prism::render::ImageFormat;
use prism::render::{AdaptiveSettings, PendingFile, RenderSettings};
use prism::sampler::SampleLayout;
use prism::scene::PreparedScene;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    /// Scene file (TOML); the seed scene when omitted.
    pub scene: Option<PathBuf>,
    /// Image width in pixels, 1..16384 (default: the scene's, else 800).
    #[arg(long, value_parser = super::within(prism::limits::IMAGE_SIDE))]
    pub width: Option<u32>,
    /// Image height in pixels, 1..16384 (default: the scene's, else 600).
    #[arg(long, value_parser = super::within(prism::limits::IMAGE_SIDE))]
    pub height: Option<u32>,
    /// Anti-aliasing level N: N×N subsamples per pixel, 1..8 (default: the scene's).
    #[arg(long, value_parser = super::within(prism::limits::AA))]
    pub aa: Option<u32>,
    /// Subsamples per pixel, 1..65536, when not N×N (default: the scene's `samples`, else
    /// N×N): soft shadows, depth of field and glossy reflection converge with more.
    #[arg(long, value_parser = super::within(prism::limits::SAMPLES))]
    pub samples: Option<u32>,
    /// The lens's diameter in scene units (0: a pinhole; default: the scene's `aperture`).
    #[arg(long, allow_negative_numbers = true)]
    pub aperture: Option<f32>,
    /// The distance in focus, along the view axis (default: the scene's `focus_distance`).
    #[arg(long, allow_negative_numbers = true)]
    pub focus_distance: Option<f32>,
    /// Output PNG file (a symbolic link's target is replaced; a device or FIFO is written
    /// to directly).
    #[arg(long, short, default_value = "render.png")]
    pub out: PathBuf,
    /// Worker threads, 1..256 (default: all cores).
    #[arg(long, value_parser = super::within(prism::limits::THREADS))]
    pub threads: Option<u16>,
    /// Most reflection/refraction bounces, 0..64 (default: the scene's, else 5).
    #[arg(long, value_parser = super::within(prism::limits::DEPTH))]
    pub max_depth: Option<u32>,
    /// Subsample positions: stratified (jittered in each cell) or grid (cell centres).
    #[arg(long, value_enum, default_value = "stratified")]
    pub layout: Layout,
    /// Stop refining pixels whose subsamples agree.
    #[arg(long)]
    pub adaptive: bool,
    /// Adaptive tolerance: estimated error of a pixel's mean luminance, 0..1 scale.
    #[arg(long, default_value_t = AdaptiveSettings::default().tolerance, allow_negative_numbers = true, requires = "adaptive")]
    pub tolerance: f32,
    /// Adaptive: least contrast (0..1, any channel) of an edge worth refining beside.
    #[arg(long, default_value_t = AdaptiveSettings::default().edge_contrast, allow_negative_numbers = true, requires = "adaptive")]
    pub edge_contrast: f32,
    /// Trace every secondary ray, however faint (the unoptimised reference).
    #[arg(long)]
    pub exact: bool,
    /// No progress bar.
    #[arg(long, short)]
    pub quiet: bool,
    /// Also write the statistics (time by stage, rays by kind, samples per pixel, peak
    /// memory) to FILE as JSON.
    #[arg(long, value_name = "FILE")]
    pub stats_json: Option<PathBuf>,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum Layout {
    Stratified,
    Grid,
}

pub fn run(args: RenderArgs) -> Result<()> {
    let start = Instant::now();
    let mut scene = super::load_scene_or_seed(args.scene.as_deref())?;
    let load_seconds = start.elapsed().as_secs_f64();
    if let Some(depth) = args.max_depth {
        scene.render.max_depth = depth;
    }
    if args.aperture.is_some() || args.focus_distance.is_some() {
        let mut camera = scene.camera;
        camera.aperture = args.aperture.unwrap_or(camera.aperture);
        camera.focus_distance = args.focus_distance.unwrap_or(camera.focus_distance);
        camera.check().map_err(prism::render::SettingsError::Lens)?;
        scene.camera = camera;
    }
    let mut settings = RenderSettings::for_scene(&scene.render, args.width, args.height, args.aa)?;
    if let Some(n) = args.samples {
        settings.samples = Some(n);
    }
    settings.layout = match args.layout {
        Layout::Stratified => SampleLayout::Stratified,
        Layout::Grid => SampleLayout::Grid,
    };
    if args.exact {
        settings.min_weight = 0.0;
    }
    if args.adaptive {
        settings.adaptive = Some(AdaptiveSettings {
            tolerance: args.tolerance,
            edge_contrast: args.edge_contrast,
            ..AdaptiveSettings::default()
        });
    }
    settings.validate()?;
    ImageFormat::from_path(&args.out)?;
    // Claim the output file first: an unwritable path fails now, not after the render.
    let pending = PendingFile::create(&args.out)?;
    let stats_file = match &args.stats_json {
        Some(path) => Some(PendingFile::create(path)?),
        None => None,
    };
    let pool = prism::render::thread_pool(args.threads.map(usize::from))
        .context("cannot start the worker threads")?;

    let build_start = Instant::now();
    let prepared = Arc::new(PreparedScene::new(&scene));
    let build_seconds = build_start.elapsed().as_secs_f64();
    let bar = if args.quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(settings.total_passes() as u64)
    };
    bar.set_style(
        ProgressStyle::with_template("{spinner} pass {pos}/{len} [{bar:30}] {elapsed} {msg}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    let trace_start = Instant::now();
    let job = pool.install(|| {
        rayon::join(crate::fault_injection::injected_panic, || ());
        prism::render::render(prepared, scene.camera, settings, |job, stats| {
            bar.set_position(job.passes_done() as u64);
            bar.set_message(format!(
                "{:.0} ms/pass, {} px active",
                stats.seconds * 1e3,
                job.active_pixels()
            ));
        })
    });
    bar.finish_and_clear();
    let wall = trace_start.elapsed().as_secs_f64();
    let path = pending.finish_png(&job.accumulator().to_rgb8())?;
    let rays = job.rays_traced();
    eprintln!(
        "rendered {} ({}×{}, {} threads) in {:.3} s: {:.2} samples per pixel, {} passes, \
         {:.1} M rays/s ({} primary, {} shadow, {} secondary)",
        path.display(),
        settings.width,
        settings.height,
        pool.current_num_threads(),
        wall,
        job.samples_per_pixel(),
        job.passes_done(),
        rays.total() as f64 / wall / 1e6,
        rays.primary,
        rays.shadow,
        rays.secondary,
    );
    let stats = RenderStats {
        scene: args
            .scene
            .as_ref()
            .map_or_else(|| "seed".into(), |p| p.display().to_string()),
        output: path.display().to_string(),
        width: settings.width,
        height: settings.height,
        threads: pool.current_num_threads(),
        seconds: Seconds {
            load: load_seconds,
            build: build_seconds,
            trace: wall,
            total: start.elapsed().as_secs_f64(),
        },
        samples_per_pixel: job.samples_per_pixel(),
        passes: job.passes_done(),
        rays: Rays {
            primary: rays.primary,
            shadow: rays.shadow,
            secondary: rays.secondary,
            total: rays.total(),
        },
        rays_per_second: rays.total() as f64 / wall.max(1e-9),
        peak_memory_bytes: peak_memory_bytes(),
    };
    eprintln!("{}", stats.lines());
    if let Some(file) = stats_file {
        file.finish_bytes(stats.to_json().as_bytes())?;
    }
    Ok(())
}
