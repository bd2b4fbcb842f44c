//! What the timing harnesses among the examples share: their command line (a file, then
//! optional counts of runs and threads) and their way of failing.

/// A harness's command line: the file it times and how.
pub struct Arguments {
    pub path: String,
    pub runs: usize,
    pub threads: usize,
}

impl Arguments {
    /// Reads `FILE [RUNS] [THREADS]`, with the given defaults; `usage` is the message for
    /// a missing file.
    pub fn read(usage: &str, runs: usize, threads: usize) -> Result<Self, String> {
        let args: Vec<String> = std::env::args().skip(1).collect();
        let Some(path) = args.first() else {
            return Err(format!("usage: {usage}"));
        };
        let number = |k: usize, default: usize, what: &str| -> Result<usize, String> {
            match args.get(k) {
                None => Ok(default),
                Some(text) => match text.parse::<usize>() {
                    Ok(n) if n > 0 => Ok(n),
                    _ => Err(format!(
                        "{what} must be a whole number above 0, not {text:?}"
                    )),
                },
            }
        };
        Ok(Self {
            path: path.clone(),
            runs: number(1, runs, "RUNS")?,
            threads: number(2, threads, "THREADS")?,
        })
    }
}

/// Runs a harness, printing its error and exiting with status 2 when it fails.
pub fn run(name: &str, harness: impl FnOnce() -> Result<(), Box<dyn std::error::Error>>) {
    if let Err(message) = harness() {
        eprintln!("{name}: {message}");
        std::process::exit(2);
    }
}

/// The median of `values` (the upper one of an even count).
pub fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}
