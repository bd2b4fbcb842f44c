//! Times reading an OBJ file's text and building its parts' hierarchies, as `prism bench
//! speed` times its loading row: the text is read into memory once, then parsed and built
//! `RUNS` times in one process on a pool of `THREADS`; it prints the medians. Run two
//! builds' copies in turns to compare them (docs/benchmarks/README.md).
//!
//! `cargo run --release --example load_build -- FILE.obj [RUNS] [THREADS]`
//! (5 runs and 2 threads unless given).

#[path = "shared/harness.rs"]
mod harness;

use harness::{Arguments, median};
use prism::accel::Model;
use prism::scene_file::parse_obj;
use std::hint::black_box;
use std::time::Instant;

fn main() {
    harness::run("load_build", run);
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let Arguments {
        path,
        runs,
        threads,
    } = Arguments::read("load_build FILE.obj [RUNS] [THREADS]", 5, 2)?;
    let path = path.as_str();
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
