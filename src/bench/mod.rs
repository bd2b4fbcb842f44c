//! `prism bench`: measurements that back the figures in docs/.

mod convergence;
mod edit;
mod modelling;
mod numerics;
mod path_tracing;
mod scale;
mod scenes;
mod soft_shadows;
mod speed;
mod timing;

use anyhow::Result;

#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    #[command(subcommand)]
    pub what: BenchKind,
}

#[derive(clap::Subcommand, Debug)]
pub enum BenchKind {
    /// Run time against image error for each sampling strategy, and the headline speed
    /// figures (docs/benchmarks/).
    Convergence {
        /// A small image and few runs: proves the bench works in well under a minute.
        #[arg(long)]
        quick: bool,
        /// Where the CSV, the plot and the table go (default: prism-bench/convergence in
        /// the working directory, or prism-bench/quick with --quick; the figures in the
        /// docs come from `--out docs/benchmarks`).
        #[arg(long)]
        out: Option<std::path::PathBuf>,
        /// Timed runs per figure (the median is reported).
        #[arg(long, default_value_t = 7)]
        runs: usize,
        /// Tolerance of the adaptive strategies.
        #[arg(long, default_value_t = prism::render::AdaptiveSettings::default().tolerance)]
        tolerance: f32,
        /// Minimum subsamples per pixel of the adaptive strategies.
        #[arg(long, default_value_t = prism::render::AdaptiveSettings::default().min_samples)]
        min_samples: u32,
        /// Minimum subsamples of the adaptive strategies' pixels beside an edge.
        #[arg(long, default_value_t = prism::render::AdaptiveSettings::default().edge_samples)]
        edge_samples: u32,
        /// Least contrast (0..1, any channel) of an edge the adaptive strategies search for.
        #[arg(long, default_value_t = prism::render::AdaptiveSettings::default().edge_contrast)]
        edge_contrast: f32,
    },
    /// What an appearance edit costs against preparing the scene again
    /// (docs/benchmarks/edit.md).
    Edit {
        /// 1,000 spheres and a 160×120 render: proves the bench works in a second.
        #[arg(long)]
        quick: bool,
        /// Where edit.md goes (default: prism-bench/edit in the working directory).
        #[arg(long)]
        out: Option<std::path::PathBuf>,
        /// Timed runs per figure (the median is reported).
        #[arg(long, default_value_t = 9)]
        runs: usize,
    },
    /// CSG against the same solids as separate objects, and a million-triangle glTF file
    /// read and built (docs/benchmarks/modelling.md).
    Modelling {
        /// Fewer spheres, a small image and a 100k-triangle file: proves the bench works.
        #[arg(long)]
        quick: bool,
        /// Where modelling.md goes (default: prism-bench/modelling in the working directory).
        #[arg(long)]
        out: Option<std::path::PathBuf>,
        /// Timed runs per figure (the median is reported).
        #[arg(long, default_value_t = 5)]
        runs: usize,
    },
    /// What a million-triangle mesh and 100 instances cost (docs/benchmarks/scale.md).
    Scale {
        /// A 59k-triangle mesh, a small image and 10 instances: proves the bench works.
        #[arg(long)]
        quick: bool,
        /// Where scale.md goes (default: prism-bench/scale in the working directory).
        #[arg(long)]
        out: Option<std::path::PathBuf>,
        /// Timed runs per figure (the median is reported).
        #[arg(long, default_value_t = 5)]
        runs: usize,
    },
    /// prism beside POV-Ray on the seed scene and Embree on meshes, where they are
    /// installed (docs/benchmarks/speed.md).
    Speed {
        /// A 200×150 seed image and a 59k-triangle mesh: proves the bench works.
        #[arg(long)]
        quick: bool,
        /// Where speed.md goes (default: prism-bench/speed in the working directory).
        #[arg(long)]
        out: Option<std::path::PathBuf>,
        /// Timed runs of each whole-process figure (the median is reported).
        #[arg(long, default_value_t = 5)]
        runs: usize,
    },
    /// Numerical accuracy tables (docs/numerics.md).
    Numerics {
        /// Timed runs per configuration (the median is reported).
        #[arg(long, default_value_t = 7)]
        runs: usize,
    },
    /// The path tracer's error against time on the room tests/mitsuba.rs renders, and
    /// Mitsuba 3's at the same samples where it is installed (docs/benchmarks/path_tracing.md).
    PathTracing {
        /// A 64×48 image against a 256-sample reference: proves the bench works.
        #[arg(long)]
        quick: bool,
        /// Where the CSV and the table go (default: prism-bench/path-tracing in the
        /// working directory; the docs' come from `--out docs/benchmarks`).
        #[arg(long)]
        out: Option<std::path::PathBuf>,
        /// Timed runs per figure (the median is reported).
        #[arg(long, default_value_t = 3)]
        runs: usize,
    },
    /// Error against time for the sampling strategies on a scene of soft shadows
    /// (docs/benchmarks/soft_shadows.md).
    SoftShadows {
        /// A 160×100 image against a 1,024-sample reference: proves the bench works.
        #[arg(long)]
        quick: bool,
        /// Where the CSV, the plot and the table go (default: prism-bench/soft-shadows in
        /// the working directory; the docs' come from `--out docs/benchmarks`).
        #[arg(long)]
        out: Option<std::path::PathBuf>,
        /// Timed runs per figure (the median is reported).
        #[arg(long, default_value_t = 5)]
        runs: usize,
    },
}

/// The flags a report's command names: the quick mode's, or the docs' folder.
fn flags_of_report(quick: bool) -> &'static str {
    if quick {
        " --quick"
    } else {
        " --out docs/benchmarks"
    }
}

/// Writes the table `md` to `name` in folder `dir` (made if missing) and prints it.
fn write_report(dir: &std::path::Path, name: &str, md: &str) -> Result<()> {
    use anyhow::Context;
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let path = dir.join(name);
    std::fs::write(&path, md).with_context(|| format!("writing {}", path.display()))?;
    print!("{md}");
    println!("wrote {}", path.display());
    Ok(())
}

pub fn run(args: BenchArgs) -> Result<()> {
    let pool = prism::render::thread_pool(None)?;
    pool.install(|| run_in_pool(args))
}

fn run_in_pool(args: BenchArgs) -> Result<()> {
    match args.what {
        BenchKind::Numerics { runs } => numerics::run(runs.max(1)),
        BenchKind::SoftShadows { quick, out, runs } => soft_shadows::run(soft_shadows::Config {
            quick,
            runs: if quick { runs.clamp(1, 2) } else { runs.max(1) },
            out_dir: out
                .unwrap_or_else(|| std::path::Path::new("prism-bench").join("soft-shadows")),
        }),
        BenchKind::PathTracing { quick, out, runs } => path_tracing::run(path_tracing::Config {
            quick,
            runs: runs.max(1),
            out_dir: out
                .unwrap_or_else(|| std::path::Path::new("prism-bench").join("path-tracing")),
        }),
        BenchKind::Scale { quick, out, runs } => scale::run(scale::Config {
            quick,
            runs: runs.max(1),
            out_dir: out.unwrap_or_else(|| std::path::Path::new("prism-bench").join("scale")),
        }),
        BenchKind::Modelling { quick, out, runs } => modelling::run(modelling::Config {
            quick,
            runs: runs.max(1),
            out_dir: out.unwrap_or_else(|| std::path::Path::new("prism-bench").join("modelling")),
        }),
        BenchKind::Speed { quick, out, runs } => speed::run(speed::Config {
            quick,
            runs: runs.max(1),
            out_dir: out.unwrap_or_else(|| std::path::Path::new("prism-bench").join("speed")),
        }),
        BenchKind::Edit { quick, out, runs } => edit::run(edit::Config {
            quick,
            runs: runs.max(1),
            out_dir: out.unwrap_or_else(|| std::path::Path::new("prism-bench").join("edit")),
        }),
        BenchKind::Convergence {
            quick,
            out,
            runs,
            tolerance,
            min_samples,
            edge_samples,
            edge_contrast,
        } => {
            let out_dir = out.unwrap_or_else(|| {
                std::path::Path::new("prism-bench").join(if quick {
                    "quick"
                } else {
                    "convergence"
                })
            });
            convergence::run(convergence::Config {
                quick,
                tolerance,
                min_samples: min_samples.max(1),
                edge_samples,
                edge_contrast,
                out_dir,
                runs: if quick { runs.clamp(1, 3) } else { runs.max(1) },
            })
        }
    }
}
