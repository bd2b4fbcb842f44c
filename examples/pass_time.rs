//! Times one pass of a scene (a ray through each pixel's centre), as `prism bench speed`
//! times its mesh rows: the scene is loaded and prepared once, then each run's render job is
//! made before its clock starts and one pass is timed, `RUNS` times in one process on a pool
//! of `THREADS`; it prints the fastest and the median. Run two builds' copies in turns to
//! compare them (docs/benchmarks/README.md).
//!
//! `cargo run --release --example pass_time -- SCENE.toml [RUNS] [THREADS]`
//! (7 runs and 2 threads unless given).

#[path = "shared/harness.rs"]
mod harness;

use harness::{Arguments, median};
use prism::render::{ProgressiveRender, RenderSettings};
use prism::sampler::SampleLayout;
use prism::scene::PreparedScene;
use prism::scene_file::load_scene;
use std::hint::black_box;
use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

fn main() {
    harness::run("pass_time", run);
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let Arguments {
        path,
        runs,
        threads,
    } = Arguments::read("pass_time SCENE.toml [RUNS] [THREADS]", 7, 2)?;
    let path = path.as_str();
    let scene = load_scene(Path::new(path)).map_err(|e| format!("{path}: {e}"))?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let prepared = Arc::new(PreparedScene::new(&scene));
    let mut settings = RenderSettings::new(scene.render.width, scene.render.height, 1);
    settings.layout = SampleLayout::Grid;
    let mut times = Vec::with_capacity(runs);
    pool.install(|| {
        for _ in 0..runs {
            let mut job = ProgressiveRender::new(prepared.clone(), scene.camera, settings);
            let start = Instant::now();
            black_box(job.step(&|| false));
            times.push(start.elapsed().as_secs_f64() * 1e3);
        }
    });
    let fastest = times.iter().copied().fold(f64::INFINITY, f64::min);
    println!(
        "{path}: one pass, {threads} threads, {runs} runs: fastest {fastest:.1} ms, median {:.1} ms",
        median(times)
    );
    Ok(())
}
