//! Fuzz target: any bytes as the glTF file (`.glb`, or a `.gltf` whose buffers are data
//! URIs) that a mesh entry names. Whatever the input, loading ends in a scene or in a short,
//! printable message, and a scene that loads prepares and renders a few pixels to finite
//! colours, with no panic, hang or runaway allocation on the way.

mod outcome;

use prism::scene_file::{Assets, parse_scene_with};
use std::path::Path;

const SCENE: &str = "[camera]\neye = [0, 2, 6]\nlook_at = [0, 0, 0]\nfov = 45\n\
                     [[lights]]\nposition = [3, 5, 4]\n\
                     [[meshes]]\nname = \"fuzzed\"\npath = \"fuzzed.glb\"\n";

fn exercise(bytes: &[u8]) {
    let files = [("fuzzed.glb", bytes)];
    outcome::check(parse_scene_with(
        SCENE,
        Path::new("fuzz.toml"),
        Assets::Embedded(&files),
    ));
}

fn main() {
    // One worker, as in the scene target (see there).
    static POOL: std::sync::OnceLock<rayon::ThreadPool> = std::sync::OnceLock::new();
    afl::fuzz!(|data: &[u8]| {
        let pool = POOL.get_or_init(|| prism::render::thread_pool(Some(1)).expect("a worker"));
        pool.install(|| exercise(data));
    });
}
