//! The `prism` command: `view` (the default) opens the interactive viewer, `render` renders
//! a PNG headless, `bench` measures run time against image error.

mod bench;
mod cli;
mod fault_injection;
#[cfg(feature = "viewer")]
mod viewer;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = cli::Args::parse();
    // A panic is a bug, but it still ends with a message and exit code 1, not 101, and
    // unwinding removes any half-written output on the way.
    match std::panic::catch_unwind(|| cli::run(args)) {
        Ok(Ok(())) => ExitCode::SUCCESS,
        Ok(Err(error)) => {
            eprintln!("prism: error: {error:#}");
            ExitCode::from(cli::exit_code(&error))
        }
        Err(_) => {
            eprintln!(
                "prism: error: internal error (the message above says where); nothing was \
                 written. Please report it with the scene file"
            );
            ExitCode::FAILURE
        }
    }
}
