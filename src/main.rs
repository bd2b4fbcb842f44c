//! The `prism` command: `view` (the default) opens the interactive viewer, `render` renders
//! a PNG headless, `bench` measures run time against image error.

mod bench;
mod cli;
#[cfg(feature = "viewer")]
mod viewer;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = cli::Args::parse();
    match cli::run(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("prism: error: {error:#}");
            ExitCode::from(cli::exit_code(&error))
        }
    }
}
