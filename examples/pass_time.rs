//! Times one pass of a scene (a ray through each pixel's centre), as `prism bench speed`
//! times its mesh rows: the scene is loaded and prepared once, then each run's render job is
//! made before its clock starts and one pass is timed, `RUNS` times in one process on a pool
//! of `THREADS`; it prints the fastest and the median. Run two builds' copies in turns to
//! compare them (docs/benchmarks/README.md).
//!
//! `cargo run --release --example pass_time -- SCENE.toml [RUNS] [THREADS]`
//! (7 runs and 2 threads unless given).

use prism::render::{ProgressiveRender, RenderSettings};
use prism::sampler::SampleLayout;
use prism::scene::PreparedScene;
use prism::scene_file::load_scene;
use std::hint::black_box;
use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

fn main() {
    if let Err(message) = run() {
        eprintln!("pass_time: {message}");
        std::process::exit(2);
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(path) = args.first() else {
        return Err("usage: pass_time SCENE.toml [RUNS] [THREADS]".into());
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
    let runs = number(1, 7, "RUNS")?;
    let threads = number(2, 2, "THREADS")?;
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
    times.sort_by(f64::total_cmp);
    println!(
        "{path}: one pass, {threads} threads, {runs} runs: fastest {:.1} ms, median {:.1} ms",
        times[0],
        times[runs / 2]
    );
    Ok(())
}
