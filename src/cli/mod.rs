//! Command-line parsing and the headless commands.

mod frames;
mod output_paths;
mod render;
mod render_args;
mod stats;
mod stitch;
mod stop;

use anyhow::Result;
use clap::{Parser, Subcommand};
use prism::integrator::IntegratorKind;
use prism::render::{OutputError, SettingsError};
use prism::scene_file::SceneError;
use std::path::PathBuf;

#[derive(Parser, Debug)]
#[command(
    name = "prism",
    version,
    about = "A fast and accurate ray tracer with an interactive progressive viewer",
    long_about = None,
    after_help = EXIT_STATUS_HELP,
    // `prism [VIEW OPTIONS] [SCENE]` is `prism view …`: the viewer is the default command.
    args_conflicts_with_subcommands = true
)]
pub struct Args {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Without a command: the options of `prism view`.
    #[command(flatten)]
    pub view: ViewArgs,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Open the interactive viewer (the default when no command is given).
    View(ViewArgs),
    /// Render a scene to an image file (PNG, JPEG, EXR, PFM), headless: a whole frame, a
    /// region or tile, one frame of an animation or a range of them.
    Render(render_args::RenderArgs),
    /// Assemble tiles rendered with --tile or --region into the whole frame.
    Stitch(stitch::StitchArgs),
    /// Measure speed and accuracy (the figures in docs/).
    Bench(crate::bench::BenchArgs),
}

/// The exit statuses, for `--help` (docs/farm.md says the same): a farm treats any status
/// but 0 as a failed task.
pub const EXIT_STATUS_HELP: &str = "Exit status:
  0    done: every image asked for was written
  1    failure: a write failed part-way, or an internal error
  2    bad input: the scene file, a flag, a path, a tile
  130  stopped by Ctrl+C (SIGINT); 143 by SIGTERM, 129 by SIGHUP (with --write-partial
       the image so far was written; without, nothing)

Environment:
  PRISM_ISA=auto|baseline|avx2
       the instruction set of the BVH's box tests (default auto: AVX2 where the
       processor has it); every choice makes the same image, bit for bit";

/// A parser of flags that take an integer in `range` (a bound from prism::limits), so
/// that the command line refuses exactly what the renderer refuses.
pub fn within<T>(range: std::ops::RangeInclusive<T>) -> clap::builder::RangedI64ValueParser<T>
where
    T: Copy + Into<i64> + TryFrom<i64> + Clone + Send + Sync + 'static,
    <T as TryFrom<i64>>::Error: std::error::Error + Send + Sync + 'static,
{
    clap::builder::RangedI64ValueParser::<T>::new()
        .range((*range.start()).into()..=(*range.end()).into())
}

/// A parser of an integrator's name, offering exactly the names a scene file takes.
pub fn integrator_name() -> impl clap::builder::TypedValueParser<Value = IntegratorKind> {
    use clap::builder::TypedValueParser;
    let names = IntegratorKind::ALL.map(IntegratorKind::name);
    clap::builder::PossibleValuesParser::new(names)
        .map(|name: String| IntegratorKind::from_name(&name).expect("one of the names offered"))
}

#[derive(clap::Args, Debug, Default)]
pub struct ViewArgs {
    /// Scene file (TOML); the seed scene when omitted.
    pub scene: Option<PathBuf>,
    /// Initial window width of the image area, in pixels.
    #[arg(long, value_parser = within(prism::limits::IMAGE_SIDE))]
    pub width: Option<u32>,
    /// Initial window height, in pixels.
    #[arg(long, value_parser = within(prism::limits::IMAGE_SIDE))]
    pub height: Option<u32>,
    /// Anti-aliasing level N (N×N subsamples per pixel, 1..8).
    #[arg(long, value_parser = within(prism::limits::AA))]
    pub aa: Option<u32>,
    /// Where screenshots are saved (default: the working directory).
    #[arg(long, value_name = "DIR")]
    pub screenshot_dir: Option<PathBuf>,
    /// Log each frame's time and each change's latency to its first image on stderr
    /// ("prism-timing:" lines, read by tests/window/responsiveness.sh).
    #[arg(long)]
    pub log_timing: bool,
    /// Show the image denoised by Intel Open Image Denoise 2 from the start (the panel's
    /// "denoised" switch; a build with the `denoise` feature).
    #[arg(long)]
    pub denoise: bool,
    /// The light transport: whitted (direct light, mirrors and glass) or path (light that
    /// bounces); default: the scene's `integrator`, else whitted.
    #[arg(long, value_parser = integrator_name())]
    pub integrator: Option<IntegratorKind>,
}

pub fn run(args: Args) -> Result<()> {
    // Before any work, so that a PRISM_ISA this processor cannot follow is refused at once.
    prism::isa::choose_from_environment()?;
    match args.command {
        Some(Command::Render(a)) => {
            stop::install()?;
            render::run(a)
        }
        Some(Command::Stitch(a)) => {
            stop::install()?;
            stitch::run(a)
        }
        Some(Command::View(a)) => view(a),
        Some(Command::Bench(a)) => {
            stop::install()?;
            crate::bench::run(a)
        }
        None => view(args.view),
    }
}

#[cfg(feature = "viewer")]
fn view(args: ViewArgs) -> Result<()> {
    // A scene file that fails to load is reported here and shown in the window, which
    // opens anyway (the file is watched: a fix loads it).
    let (start, defaults) = match &args.scene {
        None => {
            let scene = prism::seed::scene()?;
            let defaults = scene.render;
            (crate::viewer::Start::Seed(scene), defaults)
        }
        Some(path) => {
            let load = prism::scene_file::load_scene_file(path);
            let defaults = match &load.result {
                Ok(loaded) => loaded.scene.render,
                Err(_) => prism::scene::RenderDefaults::default(),
            };
            let path = path.clone();
            (crate::viewer::Start::File { path, load }, defaults)
        }
    };
    let mut settings =
        prism::render::RenderSettings::for_scene(&defaults, args.width, args.height, args.aa)?;
    if let Some(kind) = args.integrator {
        settings.integrator = kind;
    }
    crate::viewer::run(crate::viewer::Launch {
        start,
        settings,
        screenshot_dir: args.screenshot_dir.unwrap_or_else(|| PathBuf::from(".")),
        log_timing: args.log_timing,
        denoise: args.denoise,
    })
}

#[cfg(not(feature = "viewer"))]
fn view(_: ViewArgs) -> Result<()> {
    anyhow::bail!("this prism was built without the viewer feature; use `prism render`")
}

/// The exit status for `error` (`EXIT_STATUS_HELP`): 128 + the signal's number for a stop,
/// 2 for bad input (scene file, settings, flags, paths, tiles), 1 for anything else.
pub fn exit_code(error: &anyhow::Error) -> u8 {
    use prism::render::{ReadError, RegionError, StitchError};
    if let Some(stop) = error.downcast_ref::<stop::Interrupted>() {
        return stop.exit_code();
    }
    // A write that failed part-way is a failure, not bad input.
    if error.chain().any(|e| {
        matches!(
            e.downcast_ref::<OutputError>(),
            Some(OutputError::Write { .. })
        )
    }) {
        return 1;
    }
    let bad_input = error.chain().any(|e| {
        e.is::<SceneError>()
            || e.is::<SettingsError>()
            || e.is::<OutputError>()
            || e.is::<RegionError>()
            || e.is::<StitchError>()
            || e.is::<ReadError>()
            || e.is::<render_args::BadOption>()
            || e.is::<prism::isa::IsaError>()
    });
    if bad_input { 2 } else { 1 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism::limits::{AA, DEPTH, IMAGE_SIDE, THREADS};

    /// Whether `prism <args>` parses.
    fn parses(args: &[&str]) -> bool {
        Args::try_parse_from(std::iter::once("prism").chain(args.iter().copied())).is_ok()
    }

    /// Every integer flag takes exactly its range from limits.rs: both ends, and nothing
    /// one beyond either.
    #[test]
    fn every_ranged_flag_takes_exactly_its_limit() {
        let side = (*IMAGE_SIDE.start() as i64, *IMAGE_SIDE.end() as i64);
        let aa = (*AA.start() as i64, *AA.end() as i64);
        let threads = (*THREADS.start() as i64, *THREADS.end() as i64);
        let depth = (*DEPTH.start() as i64, *DEPTH.end() as i64);
        let flags = [
            ("render", "--width", side),
            ("render", "--height", side),
            ("render", "--aa", aa),
            ("render", "--threads", threads),
            ("render", "--max-depth", depth),
            ("view", "--width", side),
            ("view", "--height", side),
            ("view", "--aa", aa),
        ];
        for (command, flag, (lo, hi)) in flags {
            for (value, ok) in [(lo, true), (hi, true), (lo - 1, false), (hi + 1, false)] {
                let value = value.to_string();
                assert_eq!(
                    parses(&[command, flag, &value]),
                    ok,
                    "{command} {flag} {value}"
                );
            }
        }
    }

    /// What the flags let through at their ends, the renderer accepts.
    #[test]
    fn the_settings_accept_the_flags_extremes() {
        use prism::render::RenderSettings;
        let defaults = prism::scene::RenderDefaults::default();
        for side in [*IMAGE_SIDE.start(), *IMAGE_SIDE.end()] {
            for aa in [*AA.start(), *AA.end()] {
                let s = RenderSettings::for_scene(&defaults, Some(side), Some(side), Some(aa));
                assert!(s.is_ok(), "{side} {aa}");
            }
        }
        assert!(prism::render::thread_pool(Some(*THREADS.end() as usize)).is_ok());
    }
}
