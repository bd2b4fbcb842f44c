//! `prism bench`: measurements that back the figures in docs/.

mod numerics;

use anyhow::Result;

#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    #[command(subcommand)]
    pub what: BenchKind,
}

#[derive(clap::Subcommand, Debug)]
pub enum BenchKind {
    /// Numerical accuracy tables (docs/numerics.md).
    Numerics {
        /// Timed runs per configuration (the median is reported).
        #[arg(long, default_value_t = 7)]
        runs: usize,
    },
}

pub fn run(args: BenchArgs) -> Result<()> {
    match args.what {
        BenchKind::Numerics { runs } => numerics::run(runs.max(1)),
    }
}
