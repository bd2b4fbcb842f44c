//! Preparing a scene stays near linear in memory however its primitives crowd together:
//! thousands of spheres at one point once cost memory that grew with their square (the
//! light buffer listed every sphere in every cell it covered). A counting allocator
//! measures the peak, so the bound is on bytes, not on time.

use prism::scene::PreparedScene;
use prism::scene_file::parse_scene;
use std::alloc::{GlobalAlloc, Layout, System};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static IN_USE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = IN_USE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        unsafe { System.dealloc(p, layout) };
        IN_USE.fetch_sub(layout.size(), Ordering::Relaxed);
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The peak heap use while preparing `n` unit spheres, all at the same point, lit by a
/// light just above them (so that they fill much of the light's view).
fn peak_bytes(n: usize) -> usize {
    let mut text = String::from(
        "[camera]\neye = [0, 0, 0]\ndirection = [0, 0, -1]\nfov = 40\n\
         [[lights]]\nposition = [0, 2, -5]\n",
    );
    text += &"[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\n".repeat(n);
    let scene = parse_scene(&text, Path::new("many.toml"), Path::new(".")).unwrap();
    drop(text);
    let before = IN_USE.load(Ordering::Relaxed);
    PEAK.store(before, Ordering::Relaxed);
    let prepared = PreparedScene::new(&scene);
    let accel = prepared.geometry.accel();
    assert!((0..n as u32).all(|o| accel.isolated_solid(o).is_none()));
    // The first-hit tiles of a 640×480 view, in which the spheres cover many tiles.
    let (w, h) = (640, 480);
    let view = accel.camera_view(&scene.camera.rays(w, h), w, h);
    assert!(view.tiles().unwrap().census().crowded > 0);
    PEAK.load(Ordering::Relaxed) - before
}

#[test]
fn coincident_spheres_prepare_in_linear_memory() {
    let small = peak_bytes(2_000);
    let large = peak_bytes(20_000);
    // Ten times the spheres: about ten times the memory (plus the fixed cells), where the
    // quadratic build took a hundred times (gigabytes at this size).
    let per_sphere = large / 20_000;
    assert!(
        large < 12 * small.max(1 << 20),
        "{small} B for 2k, {large} B for 20k"
    );
    assert!(per_sphere < 4096, "{per_sphere} B per sphere");
}
