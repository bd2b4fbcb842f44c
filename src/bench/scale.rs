//! `prism bench scale`: what large meshes and many instances cost. The Stanford bunny
//! (3,674 triangles, built in) is subdivided four times into about a million triangles;
//! the figures are the mesh's load and build time and bytes per triangle, one 800×600 pass
//! over each, and the memory of 100 instances against one (docs/benchmarks/scale.md).

use super::scenes::BUNNY_OBJ;
use super::timing::median;
use anyhow::{Context, Result};
use prism::accel::{Model, Surface};
use prism::geometry::Mesh;
use prism::render::{ProgressiveRender, RenderSettings};
use prism::scene::{PreparedScene, Scene};
use prism::scene_file::{Assets, parse_obj, parse_scene_with};
use std::collections::HashSet;
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// What to measure and where the table goes.
pub struct Config {
    /// Two subdivisions (59k triangles), a small image and 10 instances: proves the bench
    /// works in seconds.
    pub quick: bool,
    /// Timed runs of each figure (the median is reported).
    pub runs: usize,
    /// The folder `scale.md` is written to.
    pub out_dir: PathBuf,
}

/// `mesh` as OBJ text.
pub(super) fn to_obj(mesh: &Mesh) -> String {
    let mut out = String::with_capacity(mesh.triangle_count() * 40);
    for p in mesh.positions() {
        let _ = writeln!(out, "v {} {} {}", p.x, p.y, p.z);
    }
    for t in mesh.triangles() {
        let _ = writeln!(out, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    out
}

/// A scene of `instances` bunnies (from OBJ text `obj`) in a row on a floor, lit by one
/// light, seen whole.
fn bunny_scene(obj: &str, instances: usize) -> Result<Scene> {
    let mut text = String::from(
        "[camera]\neye = [0, 8, 30]\nlook_at = [0, 4, 0]\nfov = 40\n\n\
         [[lights]]\nposition = [20, 40, 30]\n\n\
         [materials.clay]\ncolor = [0.85, 0.6, 0.45]\n\n\
         [[polygons]]\nvertices = [[-60, 0, 60], [60, 0, 60], [60, 0, -60], [-60, 0, -60]]\n\n",
    );
    let side = (instances as f64).sqrt().ceil() as usize;
    for i in 0..instances {
        let (x, z) = ((i % side) as f64, (i / side) as f64);
        let spacing = 10.0 / side as f64;
        let scale = 1.0 / side as f64;
        let _ = writeln!(
            text,
            "[[meshes]]\npath = \"bunny.obj\"\nmaterial = \"clay\"\nscale = {scale}\n\
             translate = [{}, 0, {}]\nrotate = [0, {}, 0]\n",
            (x - (side as f64 - 1.0) / 2.0) * spacing,
            -(z * spacing),
            (i * 37) % 360
        );
    }
    let files = [("bunny.obj", obj.as_bytes())];
    parse_scene_with(&text, Path::new("scale.toml"), Assets::Embedded(&files))
        .context("the benchmark's scene")
}

/// The bytes the prepared scene's geometry takes: every distinct model's mesh and
/// hierarchy once, the primitives, the top-level hierarchy and the instances.
fn geometry_bytes(prepared: &PreparedScene) -> usize {
    let accel = prepared.geometry.accel();
    let mut seen = HashSet::new();
    let mut bytes = size_of_val(accel.primitives()) + accel.bvh_nodes() * 128;
    for p in accel.primitives() {
        if let Surface::Instance(instance) = &p.surface {
            bytes += size_of_val(&**instance);
            let model = instance.model();
            if seen.insert(Arc::as_ptr(model)) {
                bytes += model.index_bytes();
                if let Model::Mesh { mesh, .. } = &**model {
                    bytes += mesh.vertex_bytes();
                }
            }
        }
    }
    bytes
}

/// Seconds of one pass (one sample per pixel) over `scene` at `w` × `h`, median of `runs`.
fn pass_time(scene: &Scene, w: u32, h: u32, runs: usize) -> f64 {
    let prepared = Arc::new(PreparedScene::new(scene));
    let settings = RenderSettings::new(w, h, 1);
    median(runs, || {
        let mut job = ProgressiveRender::new(prepared.clone(), scene.camera, settings);
        black_box(job.step(&|| false));
    })
}

pub fn run(cfg: Config) -> Result<()> {
    let (levels, w, h, instances) = if cfg.quick {
        (2, 200, 150, 10)
    } else {
        (4, 800, 600, 100)
    };
    let bunny = parse_obj(BUNNY_OBJ, usize::MAX, true)
        .map_err(|e| anyhow::anyhow!("bunny.obj:{}: {}", e.line, e.message))?
        .parts
        .remove(0)
        .mesh;
    let mut big = bunny.clone();
    for _ in 0..levels {
        big = big.subdivided();
    }
    let triangles = big.triangle_count();
    let big_obj = to_obj(&big);

    let load = median(cfg.runs, || {
        black_box(parse_obj(&big_obj, usize::MAX, true).expect("the subdivided bunny"));
    });
    let build = median(cfg.runs, || {
        black_box(Model::mesh(&big));
    });
    let model = Model::mesh(&big);
    let per_triangle = model.index_bytes() as f64 / triangles as f64;

    let small_scene = bunny_scene(BUNNY_OBJ, 1)?;
    let big_scene = bunny_scene(&big_obj, 1)?;
    let small_pass = pass_time(&small_scene, w, h, cfg.runs);
    let big_pass = pass_time(&big_scene, w, h, cfg.runs);

    let one = geometry_bytes(&PreparedScene::new(&small_scene));
    let many_scene = bunny_scene(BUNNY_OBJ, instances)?;
    let many = geometry_bytes(&PreparedScene::new(&many_scene));

    let mut md = String::new();
    let _ = writeln!(md, "# Large meshes and instances\n");
    let _ = writeln!(
        md,
        "Measured by `prism bench scale{}` ({} runs each, the median).\n",
        if cfg.quick { " --quick" } else { "" },
        cfg.runs
    );
    let _ = writeln!(
        md,
        "The bunny (3,674 triangles) subdivided {levels} times: {triangles} triangles, \
         {} vertices.\n",
        big.vertex_count()
    );
    let _ = writeln!(md, "| figure | measured | target |");
    let _ = writeln!(md, "|---|---|---|");
    let _ = writeln!(
        md,
        "| reading its OBJ text ({:.1} MB) | {:.3} s | |",
        big_obj.len() as f64 / 1e6,
        load
    );
    let _ = writeln!(md, "| building its hierarchy | {build:.3} s | |");
    let _ = writeln!(
        md,
        "| loading and building, together | {:.3} s | at most 1 s per million triangles ({:.3} s here) |",
        load + build,
        triangles as f64 / 1e6
    );
    let _ = writeln!(
        md,
        "| bytes per triangle beyond the vertices (corner lists and hierarchy) | {per_triangle:.1} | at most 100 |"
    );
    let _ = writeln!(
        md,
        "| one {w}×{h} pass, the bunny | {:.1} ms | |",
        small_pass * 1e3
    );
    let _ = writeln!(
        md,
        "| one {w}×{h} pass, the subdivided bunny | {:.1} ms ({:.2}× the bunny's) | at most 2× |",
        big_pass * 1e3,
        big_pass / small_pass
    );
    let _ = writeln!(
        md,
        "| geometry of {instances} bunnies against one | {:.1} KiB against {:.1} KiB ({:.3}×) | at most 1.3× |",
        many as f64 / 1024.0,
        one as f64 / 1024.0,
        many as f64 / one as f64
    );
    super::write_report(&cfg.out_dir, "scale.md", &md)?;
    Ok(())
}
