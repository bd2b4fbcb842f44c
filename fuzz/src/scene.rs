//! Fuzz target: any bytes as a scene file. Whatever the input, loading ends in a scene or
//! in a short, printable message, and a scene that loads prepares and renders a few
//! pixels to finite colours, with no panic, hang or runaway allocation on the way.

mod outcome;

use prism::scene_file::parse_scene;
use std::path::{Path, PathBuf};

/// A folder laid out like the repository's assets/ (scenes/ beside earth.jpg), with a small
/// Earth so that the seed scene and its mutants load their texture quickly.
fn textures_dir() -> PathBuf {
    let root = std::env::temp_dir().join("prism-fuzz-assets");
    let scenes = root.join("scenes");
    if !scenes.is_dir() {
        std::fs::create_dir_all(&scenes).expect("a temporary folder");
        let earth = image::RgbImage::from_fn(32, 16, |x, y| {
            image::Rgb([(x * 8) as u8, (y * 16) as u8, 200])
        });
        earth.save(root.join("earth.jpg")).expect("the small Earth");
        earth.save(root.join("earth.png")).expect("the small Earth");
    }
    scenes
}

fn exercise(bytes: &[u8], base: &Path) {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return; // the file reader turns these into a located message (tested in tests/)
    };
    outcome::check(parse_scene(text, Path::new("fuzz.toml"), base));
}

fn main() {
    let base = textures_dir();
    // One worker, as prism's renders have it (a deep stack), so the same input always takes
    // the same path. Made on first use: AFL forks the process after main starts, and
    // threads do not survive a fork.
    static POOL: std::sync::OnceLock<rayon::ThreadPool> = std::sync::OnceLock::new();
    afl::fuzz!(|data: &[u8]| {
        let pool = POOL.get_or_init(|| prism::render::thread_pool(Some(1)).expect("a worker"));
        pool.install(|| exercise(data, &base));
    });
}
