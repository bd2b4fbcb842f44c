//! Times reading an OBJ file's text and building its parts' hierarchies, as `prism bench
//! speed` times its loading row: the text is read into memory once, then parsed and built
//! `RUNS` times in one process on a pool of `THREADS`; it prints the medians. Run two
//! builds' copies in turns to compare them (docs/benchmarks/README.md).
//!
//! `cargo run --release --example load_build -- FILE.obj [RUNS] [THREADS]`
//! (5 runs and 2 threads unless given).

use prism::accel::Model;
use prism::scene_file::parse_obj;
use std::hint::black_box;
use std::time::Instant;

fn main() {
    if let Err(message) = run() {
        eprintln!("load_build: {message}");
        std::process::exit(2);
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(path) = args.first() else {
        return Err("usage: load_build FILE.obj [RUNS] [THREADS]".into());
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
    let runs = number(1, 5, "RUNS")?;
    let threads = number(2, 2, "THREADS")?;
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {path}: {e}"))?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let (mut load, mut build, mut both) = (Vec::new(), Vec::new(), Vec::new());
    let mut triangles = 0;
    pool.install(|| -> Result<(), String> {
        for _ in 0..runs {
            let start = Instant::now();
            let parsed = parse_obj(&text, usize::MAX, true)
                .map_err(|e| format!("{path}:{}: {}", e.line, e.message))?;
            let loaded = start.elapsed().as_secs_f64();
            let start = Instant::now();
            triangles = 0;
            for part in parsed.parts {
                triangles += part.mesh.triangle_count();
                black_box(Model::mesh(&part.mesh));
            }
            let built = start.elapsed().as_secs_f64();
            load.push(loaded);
            build.push(built);
            both.push(loaded + built);
        }
        Ok(())
    })?;
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let both = median(both);
    println!(
        "{triangles} triangles, {threads} thread(s), medians of {runs}: loading {:.4} s, \
         building {:.4} s, both {both:.4} s ({:.4} s per million)",
        median(load),
        median(build),
        both * 1e6 / triangles.max(1) as f64
    );
    Ok(())
}
