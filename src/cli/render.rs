//! `prism render`: a headless render to an image file with a progress bar: the whole frame
//! or a region or tile of it, one frame of an animation or a range of them.

use super::frames::{FrameChoice, OutputTemplate};
use super::output_paths::{FileRoles, create_parent_folders};
use super::render_args::{BadOption, Layout, RenderArgs};
use super::stats::{Rays, RenderStats, Seconds, peak_memory_bytes};
use super::stop::{self, Interrupted};
use anyhow::{Context, Result, bail};
use indicatif::{ProgressBar, ProgressStyle};
use prism::color::Transfer;
use prism::messages::shown_path;
use prism::render::{AdaptiveSettings, PendingFile, RenderMemory, RenderSettings};
use prism::render::{BitDepth, ImageFormat, OutputOptions, PixelRect, Placement};
use prism::render::{available_memory, gib};
use prism::sampler::SampleLayout;
use prism::scene::{PreparedScene, Scene};
use prism::scene_file::SceneFrames;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

/// What the flags and a frame's scene ask of its render and its file.
struct Plan {
    settings: RenderSettings,
    region: PixelRect,
    placement: Option<Placement>,
    options: OutputOptions,
}

pub fn run(args: RenderArgs) -> Result<()> {
    let start = Instant::now();
    let pool = prism::render::thread_pool(args.threads.map(usize::from))
        .context("cannot start the worker threads")?;
    // Everything runs on the pool, reading meshes and building hierarchies too: `--threads`
    // bounds the whole process, as a farm that packs several jobs on one node expects.
    pool.install(|| render_frames(&args, &pool, start))
}

fn render_frames(args: &RenderArgs, pool: &rayon::ThreadPool, start: Instant) -> Result<()> {
    let source = match &args.scene {
        Some(path) => SceneFrames::load(path)?,
        None => SceneFrames::fixed(prism::seed::scene()?),
    };
    for note in source.unread() {
        eprintln!("prism: warning: not read: {note}");
    }
    let frames = FrameChoice::from_args(args)?.frames(source.animation())?;
    let out = OutputTemplate::parse("--out", &args.out)?;
    let stats_out = match &args.stats_json {
        Some(text) => Some(OutputTemplate::parse("--stats-json", text)?),
        None => None,
    };
    out.require_frame("--out", frames.len())?;
    out.require_tile("--out", args.tile.is_some())?;
    if let Some(t) = &stats_out {
        t.require_frame("--stats-json", frames.len())?;
        t.require_tile("--stats-json", args.tile.is_some())?;
    }
    // The tile's index names the files; its rows wait for the frame's size.
    let tile = match &args.tile {
        Some(text) => Some(PixelRect::parse_tile(text)?.0),
        None => None,
    };
    check_outputs(
        args,
        source.files(),
        &frames,
        &out,
        stats_out.as_ref(),
        tile,
    )?;
    let mut load_seconds = Some(start.elapsed().as_secs_f64());
    // The frame before and its prepared geometry: a frame that moves only some of the
    // shapes and lights (or none) builds only what they touch.
    let mut previous: Option<(Scene, Arc<PreparedScene>)> = None;
    for frame in frames {
        let path = out.path(frame, tile);
        // Checked before the frame is loaded: a farm's rerun skips what it has cheaply. Only
        // a file counts: a folder of the name is no image.
        if args.skip_existing && path.is_file() {
            if !args.quiet {
                eprintln!("skipped {} (it exists)", shown_path(&path));
            }
            continue;
        }
        let frame_start = Instant::now();
        let scene = source.frame(frame)?;
        let load = load_seconds.take().unwrap_or(0.0) + frame_start.elapsed().as_secs_f64();
        // Per frame: an animation may key the `[render]` table (its exposure, say).
        let plan = &make_plan(args, &scene)?;
        let stats_path = stats_out.as_ref().map(|t| t.path(frame, tile));
        let label = source.animation().map(|_| frame);
        previous = Some(render_frame(
            args,
            scene,
            plan,
            pool,
            &path,
            stats_path.as_deref(),
            label,
            load,
            previous.take(),
        )?);
    }
    Ok(())
}

/// Refuses a render that would need more memory than this process can take, with the
/// figures and the way out, before anything is allocated.
fn check_memory(settings: &RenderSettings, plan: &Plan, format: ImageFormat) -> Result<()> {
    let (width, height) = (settings.width, settings.height);
    // The widest margin, a noisy render's: memory is checked before the scene is prepared.
    let margin = prism::render::adaptive_margin(settings, true);
    let window = plan.region.grown(margin, width, height);
    let need = RenderMemory::of(window, plan.region, format, plan.options.depth);
    let Some((available, source)) = available_memory() else {
        return Ok(());
    };
    if need.total() <= available {
        return Ok(());
    }
    let what = match plan.placement {
        Some(p) => format!("region {} of a {width}×{height} frame", p.rect),
        None => format!("a {width}×{height} frame"),
    };
    let tiles = need.total().div_ceil(available / 2).clamp(2, 4096);
    bail!(BadOption(format!(
        "{what} needs about {} of memory (pixel sums {}, the image {}), but {} is {}: \
         render it in tiles (--tile I/{tiles} for I from 0 to {}, then prism stitch) or \
         at a smaller size",
        gib(need.total()),
        gib(need.film + need.flags + need.crop),
        gib(need.image),
        gib(available),
        source.name(),
        tiles - 1
    )));
}

/// Refuses, before any frame is rendered, an image, sidecar or statistics file that would
/// land on a file the scene reads or on another output of this command.
fn check_outputs(
    args: &RenderArgs,
    inputs: &[PathBuf],
    frames: &[u32],
    out: &OutputTemplate,
    stats_out: Option<&OutputTemplate>,
    tile: Option<u32>,
) -> Result<()> {
    let mut roles = FileRoles::with_inputs(inputs);
    let placed = args.region.is_some() || args.tile.is_some();
    let frame_name = |frame: u32| match frames.len() {
        1 => String::new(),
        _ => format!(" of frame {frame}"),
    };
    for &frame in frames {
        let image = out.path(frame, tile);
        roles.claim("--out", &image, format!("the image{}", frame_name(frame)))?;
        if placed && ImageFormat::from_path(&image)? != ImageFormat::Png {
            let sidecar = prism::render::sidecar_path(&image);
            let what = format!("the placement sidecar{}", frame_name(frame));
            roles.claim("--out", &sidecar, what)?;
        }
    }
    if let Some(stats) = stats_out {
        for &frame in frames {
            let what = format!("the statistics{}", frame_name(frame));
            roles.claim("--stats-json", &stats.path(frame, tile), what)?;
        }
    }
    Ok(())
}

/// The finished film `film` of `job` (of `scene`, the whole frame) denoised.
fn denoised(
    film: &prism::render::Accumulator,
    scene: &Scene,
    job: &prism::render::ProgressiveRender,
    pool: &rayon::ThreadPool,
) -> Result<prism::render::Accumulator> {
    #[cfg(feature = "denoise")]
    {
        let settings = job.settings();
        let guides = pool.install(|| {
            prism::render::guide_images(job.scene(), scene.camera, settings, job.passes_done())
        });
        Ok(prism::render::denoise(
            film,
            &guides,
            settings.high_dynamic_range,
        )?)
    }
    #[cfg(not(feature = "denoise"))]
    {
        let _ = (film, scene, job, pool);
        bail!(BadOption(denoise_missing()))
    }
}

/// What `--denoise` says in a build without the `denoise` feature.
fn denoise_missing() -> String {
    format!("--denoise: {}", prism::render::DENOISE_NOT_BUILT)
}

/// The settings, region and output options, from the flags and the frame's scene.
fn make_plan(args: &RenderArgs, scene: &Scene) -> Result<Plan> {
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
    if let Some(kind) = args.integrator {
        settings.integrator = kind;
    }
    if args.adaptive {
        settings.adaptive = Some(AdaptiveSettings {
            tolerance: args.tolerance,
            edge_contrast: args.edge_contrast,
            ..AdaptiveSettings::default()
        });
    }
    settings.validate()?;
    let (width, height) = (settings.width, settings.height);
    let region = match (&args.region, &args.tile) {
        (Some(text), _) => PixelRect::parse(text)?,
        (None, Some(text)) => {
            let (index, count) = PixelRect::parse_tile(text)?;
            PixelRect::tile(index, count, width, height)?
        }
        (None, None) => PixelRect::full(width, height),
    };
    region.check_within(width, height)?;
    if args.denoise {
        if !region.is_full(width, height) {
            bail!(BadOption(
                "--denoise filters the whole frame: not with --region or --tile (denoise \
                 the stitched image's render instead)"
                    .into()
            ));
        }
        if !cfg!(feature = "denoise") {
            bail!(BadOption(denoise_missing()));
        }
    }
    let placement = (!region.is_full(width, height)).then_some(Placement {
        rect: region,
        frame_width: width,
        frame_height: height,
    });

    let mut encoding = scene.render.encoding;
    if args.srgb {
        encoding.transfer = Transfer::Srgb;
    }
    if let Some(stops) = args.exposure {
        if !prism::limits::EXPOSURE.contains(&stops) {
            bail!(BadOption(format!(
                "--exposure {stops}: must be {} to {} stops",
                prism::limits::EXPOSURE.start(),
                prism::limits::EXPOSURE.end()
            )));
        }
        encoding.exposure = stops;
    }
    let options = OutputOptions {
        encoding,
        depth: if args.bits == 16 {
            BitDepth::Sixteen
        } else {
            BitDepth::Eight
        },
        jpeg_quality: args
            .quality
            .unwrap_or(OutputOptions::default().jpeg_quality),
    };
    // The format is the same for every frame: the template's extension.
    let format = ImageFormat::from_path(Path::new(&args.out))?;
    if args.quality.is_some() && format != ImageFormat::Jpeg {
        bail!(BadOption(format!(
            "--quality is a JPEG option; {} names a {} file",
            args.out,
            format.name()
        )));
    }
    format.check(Path::new(&args.out), &options)?;
    settings.high_dynamic_range = format.is_hdr();
    Ok(Plan {
        settings,
        region,
        placement,
        options,
    })
}

/// Renders one frame (or the region of it) to `path`, prepared from `previous` (the frame
/// before and its preparation) where it can be (`PreparedScene::updated`), which is let go
/// once this frame is prepared; returns the frame's scene and preparation, for the next.
#[allow(clippy::too_many_arguments)]
fn render_frame(
    args: &RenderArgs,
    mut scene: Scene,
    plan: &Plan,
    pool: &rayon::ThreadPool,
    path: &Path,
    stats_path: Option<&Path>,
    frame: Option<u32>,
    load_seconds: f64,
    previous: Option<(Scene, Arc<PreparedScene>)>,
) -> Result<(Scene, Arc<PreparedScene>)> {
    let start = Instant::now();
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
    let settings = plan.settings;
    let format = ImageFormat::from_path(path)?;
    check_memory(&settings, plan, format)?;
    // Claim the output file first: an unwritable path fails now, not after the render.
    create_parent_folders(path, args.quiet)?;
    let pending = PendingFile::create(path)?;
    let stats_file = match stats_path {
        Some(path) => {
            create_parent_folders(path, args.quiet)?;
            Some(PendingFile::create(path)?)
        }
        None => None,
    };

    let build_start = Instant::now();
    let prepared = Arc::new(match previous {
        // Dropped here: the frame before's geometry is not held through this one's render.
        Some((before, prepared)) => prepared.updated(&before, &scene),
        None => PreparedScene::new(&scene),
    });
    let build_seconds = build_start.elapsed().as_secs_f64();
    prepared
        .check_coincident(&scene)
        .map_err(|e| BadOption(e.to_string()))?;
    let bar = if args.quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(settings.total_passes() as u64)
    };
    let prefix = frame.map_or_else(String::new, |f| format!("frame {f} "));
    bar.set_style(
        ProgressStyle::with_template(&format!(
            "{{spinner}} {prefix}pass {{pos}}/{{len}} [{{bar:30}}] {{elapsed}} {{msg}}"
        ))
        .expect("valid template")
        .progress_chars("=> "),
    );
    let trace_start = Instant::now();
    let tracing = stop::Tracing::begin();
    let stopped = || stop::requested().is_some();
    let job = pool.install(|| {
        rayon::join(crate::fault_injection::injected_panic, || ());
        prism::render::render_region(
            prepared.clone(),
            scene.camera,
            settings,
            plan.region,
            &stopped,
            |job, stats| {
                bar.set_position(job.passes_done() as u64);
                bar.set_message(format!(
                    "{:.0} ms/pass, {} px active",
                    stats.seconds * 1e3,
                    job.active_pixels()
                ));
            },
        )
    });
    drop(tracing);
    bar.finish_and_clear();
    let wall = trace_start.elapsed().as_secs_f64();
    let interrupted = stop::requested();
    if let Some(signal) = interrupted
        && !args.write_partial
    {
        // Dropping the claimed files removes their temporary files.
        bail!(Interrupted {
            signal,
            saved: false
        });
    }
    // The job's own sums are encoded where they are: a copy would hold a second film, which
    // the memory check (`RenderMemory`) does not count, and take longer than the encoding.
    let mut sums = job.sums_of(plan.region);
    if args.denoise {
        sums = std::borrow::Cow::Owned(denoised(&sums, &scene, &job, pool)?);
    }
    let image = prism::render::encode(&sums, format, &plan.options);
    let path = pending.finish_image(&image, format, &plan.options, plan.placement)?;
    let rays = job.rays_traced();
    let what = match plan.placement {
        Some(p) => format!("{} of {}×{}", p.rect, settings.width, settings.height),
        None => format!("{}×{}", settings.width, settings.height),
    };
    if !args.quiet {
        let threads = pool.current_num_threads();
        let passes = job.passes_done();
        eprintln!(
            "rendered {} ({what}, {threads} thread{}) in {:.3} s: {:.2} samples per pixel, \
             {passes} pass{}, {:.1} M rays/s ({} primary, {} shadow, {} secondary)",
            shown_path(&path),
            if threads == 1 { "" } else { "s" },
            wall,
            job.samples_per_pixel(),
            if passes == 1 { "" } else { "es" },
            rays.total() as f64 / wall / 1e6,
            rays.primary,
            rays.shadow,
            rays.secondary,
        );
    }
    let stats = RenderStats {
        scene: args
            .scene
            .as_ref()
            .map_or_else(|| "seed".into(), |p| p.display().to_string()),
        output: path.display().to_string(),
        frame,
        region: plan.placement.map(|p| p.rect.to_string()),
        width: settings.width,
        height: settings.height,
        threads: pool.current_num_threads(),
        seconds: Seconds {
            load: load_seconds,
            build: build_seconds,
            trace: wall,
            total: load_seconds + start.elapsed().as_secs_f64(),
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
        complete: interrupted.is_none(),
    };
    if !args.quiet {
        eprintln!("{}", stats.lines());
    }
    if let Some(file) = stats_file {
        file.finish_bytes(stats.to_json().as_bytes())?;
    }
    if let Some(signal) = interrupted {
        bail!(Interrupted {
            signal,
            saved: true
        });
    }
    Ok((scene, prepared))
}
