//! The flags of `prism render`, and the error of a flag that does not fit the output asked
//! for: below the command's files (render.rs, frames.rs, output_paths.rs, stitch.rs), which
//! all read them.

use prism::integrator::IntegratorKind;
use prism::render::AdaptiveSettings;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
#[command(after_help = super::EXIT_STATUS_HELP)]
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
    /// Output image; its extension names the format: .png, .jpg, .exr (linear float) or
    /// .pfm (linear float). May hold {frame} or {frame:04} (the frame's number) and {tile}.
    /// A symbolic link's target is replaced; a device or FIFO is written to directly.
    #[arg(long, short, default_value = "render.png")]
    pub out: String,
    /// Render only these pixels, X0,Y0,X1,Y1 (ends excluded): an image of the region's
    /// size, equal to the same pixels of the full render, its place recorded in the file.
    #[arg(long, value_name = "X0,Y0,X1,Y1", conflicts_with = "tile")]
    pub region: Option<String>,
    /// Render tile I (from 0) of the frame split into N bands of rows, as --region does.
    #[arg(long, value_name = "I/N")]
    pub tile: Option<String>,
    /// Render frame N of the scene's [animation] (from 0).
    #[arg(long, value_name = "N", conflicts_with_all = ["frames", "frame_from_env"])]
    pub frame: Option<u32>,
    /// Render frames A..B of the animation (B excluded; A..=B includes it; `all`: every
    /// frame), each to --out with its {frame} filled in.
    #[arg(long, value_name = "A..B", conflicts_with = "frame_from_env")]
    pub frames: Option<String>,
    /// Render the frame whose number the environment variable VAR holds (for a farm's job
    /// arrays: SLURM_ARRAY_TASK_ID, or $(Process) passed by HTCondor).
    #[arg(long, value_name = "VAR")]
    pub frame_from_env: Option<String>,
    /// Skip a frame or tile whose output file already exists (a farm job's rerun renders
    /// only what is missing).
    #[arg(long)]
    pub skip_existing: bool,
    /// Store colours with the sRGB curve, for display (default: linear, the seed's look;
    /// also `[render] encoding = "srgb"`). Not for .exr or .pfm, which are linear.
    #[arg(long)]
    pub srgb: bool,
    /// Multiply colours by 2^STOPS before they are stored (default: the scene's
    /// `exposure`, else 0).
    #[arg(long, value_name = "STOPS", allow_negative_numbers = true)]
    pub exposure: Option<f32>,
    /// Bits per channel of a PNG: 8 or 16.
    #[arg(long, default_value_t = 8, value_parser = clap::builder::TypedValueParser::map(clap::builder::PossibleValuesParser::new(["8", "16"]), |s: String| s.parse::<u8>().expect("8 or 16")))]
    pub bits: u8,
    /// JPEG quality, 1..100.
    #[arg(long, value_parser = super::within(prism::limits::JPEG_QUALITY))]
    pub quality: Option<u8>,
    /// On Ctrl+C or SIGTERM, write the image as far as it got (then exit 130 or 143)
    /// instead of leaving no file.
    #[arg(long)]
    pub write_partial: bool,
    /// Worker threads, 1..256, for loading and building as well as tracing (default: all
    /// cores). The image is the same for any number.
    #[arg(long, value_parser = super::within(prism::limits::THREADS))]
    pub threads: Option<u16>,
    /// Most reflection/refraction bounces, 0..64 (default: the scene's, else 5).
    #[arg(long, value_parser = super::within(prism::limits::DEPTH))]
    pub max_depth: Option<u32>,
    /// Subsample positions: stratified (jittered in each cell) or grid (cell centres).
    #[arg(long, value_enum, default_value = "stratified")]
    pub layout: Layout,
    /// The light transport: whitted (direct light, mirrors and glass) or path (light that
    /// bounces); default: the scene's `integrator`, else whitted.
    #[arg(long, value_parser = super::integrator_name())]
    pub integrator: Option<IntegratorKind>,
    /// Stop refining pixels whose subsamples agree.
    #[arg(long)]
    pub adaptive: bool,
    /// Adaptive tolerance: estimated error of a pixel's mean luminance, 0..1 scale (in a
    /// noisy render, at 16 subsamples: a pixel that needs n stops at this × √(n/16)).
    #[arg(long, default_value_t = AdaptiveSettings::default().tolerance, allow_negative_numbers = true, requires = "adaptive")]
    pub tolerance: f32,
    /// Adaptive: least contrast (0..1, any channel) of an edge worth refining beside.
    #[arg(long, default_value_t = AdaptiveSettings::default().edge_contrast, allow_negative_numbers = true, requires = "adaptive")]
    pub edge_contrast: f32,
    /// Trace every secondary ray, however faint (the unoptimised reference).
    #[arg(long)]
    pub exact: bool,
    /// Denoise the finished image with Intel Open Image Denoise 2, guided by the first
    /// surfaces' colours and normals (a build with the `denoise` feature; the whole frame).
    #[arg(long)]
    pub denoise: bool,
    /// No progress bar.
    #[arg(long, short)]
    pub quiet: bool,
    /// Also write the statistics (time by stage, rays by kind, samples per pixel, peak
    /// memory) to FILE as JSON (may hold {frame} and {tile} as --out does).
    #[arg(long, value_name = "FILE")]
    pub stats_json: Option<String>,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum Layout {
    Stratified,
    Grid,
}

/// An option that does not fit the output asked for.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct BadOption(pub String);
