//! Stopping a headless command on a signal. While a render traces, the first SIGINT,
//! SIGTERM or SIGHUP asks it to stop at the next band of rows (so it can remove its
//! temporary file or, with `--write-partial`, save the image so far); a second signal, or
//! one at any other time, removes every unfinished output file and exits at once. The exit
//! status is 128 + the signal's number (130, 143, 129), as shells expect.

use anyhow::{Context, Result};
use std::sync::atomic::{AtomicBool, AtomicI32, Ordering};

/// The signal that asked the render to stop (0: none yet).
static REQUESTED: AtomicI32 = AtomicI32::new(0);
/// Whether a render is tracing and will look at `REQUESTED`.
static TRACING: AtomicBool = AtomicBool::new(false);

/// A render stopped by a signal before it finished.
#[derive(Debug, thiserror::Error)]
#[error("stopped by {}{}", signal_name(*signal), if *saved { "; the image so far was written" } else { "; no output was written" })]
pub struct Interrupted {
    /// The signal's number.
    pub signal: i32,
    /// Whether the partial image was saved (`--write-partial`).
    pub saved: bool,
}

impl Interrupted {
    /// The exit status: 128 + the signal's number.
    pub fn exit_code(&self) -> u8 {
        (128 + self.signal).clamp(0, 255) as u8
    }
}

fn signal_name(signal: i32) -> &'static str {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    match signal {
        SIGINT => "SIGINT",
        SIGTERM => "SIGTERM",
        SIGHUP => "SIGHUP",
        _ => "a signal",
    }
}

/// Installs the handlers (once, before any output file is claimed).
pub fn install() -> Result<()> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])
        .context("cannot install the signal handlers")?;
    std::thread::Builder::new()
        .name("prism-signals".into())
        .spawn(move || {
            for signal in signals.forever() {
                let first = REQUESTED
                    .compare_exchange(0, signal, Ordering::SeqCst, Ordering::SeqCst)
                    .is_ok();
                if first && TRACING.load(Ordering::SeqCst) {
                    eprintln!(
                        "\nprism: {}: stopping the render (send it again to quit at once)",
                        signal_name(signal)
                    );
                    continue;
                }
                prism::render::remove_pending_files();
                eprintln!(
                    "\nprism: stopped by {}; no output was written",
                    signal_name(signal)
                );
                std::process::exit(128 + signal);
            }
        })
        .context("cannot start the signal thread")?;
    Ok(())
}

/// Marks the span of a render's tracing, during which a signal asks it to stop rather than
/// ending the process.
pub struct Tracing;

impl Tracing {
    /// Tracing begins.
    pub fn begin() -> Self {
        TRACING.store(true, Ordering::SeqCst);
        Tracing
    }
}

impl Drop for Tracing {
    fn drop(&mut self) {
        TRACING.store(false, Ordering::SeqCst);
    }
}

/// The signal that asked the render to stop, if one has.
pub fn requested() -> Option<i32> {
    match REQUESTED.load(Ordering::SeqCst) {
        0 => None,
        signal => Some(signal),
    }
}
