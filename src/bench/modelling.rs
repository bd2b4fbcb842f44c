//! `prism bench modelling`: what the modelling features cost against what they stand for.
//! Spheres combined by CSG against the same spheres as separate objects (a union at the top
//! of an entry, which prism traces as its members, and a union inside an intersection,
//! traced as one solid through its hierarchies), each the same image; and a
//! million-triangle glTF file read and built (docs/benchmarks/modelling.md).

use super::timing::median;
use anyhow::{Context, Result};
use prism::render::{RenderSettings, render};
use prism::scene::{PreparedScene, Scene};
use prism::scene_file::{Assets, glb_file, parse_scene_with};
use serde_json::json;
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// What to measure and where the table goes.
pub struct Config {
    /// Fewer spheres, a small image and a 100k-triangle file: proves the bench works.
    pub quick: bool,
    /// Timed runs of each figure (the median is reported).
    pub runs: usize,
    /// The folder `modelling.md` is written to.
    pub out_dir: PathBuf,
}

/// How `spheres` are written into a scene.
#[derive(Clone, Copy)]
enum Spheres {
    /// One `[[spheres]]` entry each.
    Separate,
    /// The members of one `[[csg]]` union.
    Union,
    /// The members of a union inside an intersection with a box around them all: the same
    /// solid, traced as a combination.
    UnionInBox,
}

/// A scene of `n` spheres of radius 0.4 on a grid one unit apart (none touching), on a
/// floor, lit by one light, seen from above at an angle, written as `how` says.
fn sphere_scene(n: usize, how: Spheres) -> Result<Scene> {
    let side = (n as f64).sqrt().ceil() as usize;
    let half = side as f64 / 2.0;
    let mut text = format!(
        "[camera]\neye = [0, {}, {}]\nlook_at = [0, 0, 0]\nfov = 45\n\n\
         [[lights]]\nposition = [{half}, {}, {half}]\n\n\
         [materials.paint]\ncolor = [0.8, 0.35, 0.2]\nspecular = 0.4\nshininess = 40\n\n\
         [[planes]]\npoint = [0, -0.4, 0]\nnormal = [0, 1, 0]\n\n",
        half * 1.6,
        half * 2.2,
        half * 3.0
    );
    let centre = |i: usize| {
        let (x, z) = ((i % side) as f64, (i / side) as f64);
        [x - half + 0.5, 0.0, z - half + 0.5]
    };
    let sphere = |i: usize| {
        let [x, y, z] = centre(i);
        format!("center = [{x}, {y}, {z}]\nradius = 0.4\n")
    };
    match how {
        Spheres::Separate => {
            for i in 0..n {
                let _ = writeln!(text, "[[spheres]]\nmaterial = \"paint\"\n{}", sphere(i));
            }
        }
        Spheres::Union => {
            text.push_str("[[csg]]\noperation = \"union\"\nmaterial = \"paint\"\n");
            for i in 0..n {
                let _ = writeln!(text, "[[csg.members]]\ntype = \"sphere\"\n{}", sphere(i));
            }
        }
        Spheres::UnionInBox => {
            text.push_str(
                "[[csg]]\noperation = \"intersection\"\nmaterial = \"paint\"\n\
                 [[csg.members]]\ntype = \"csg\"\noperation = \"union\"\n",
            );
            for i in 0..n {
                let _ = writeln!(
                    text,
                    "[[csg.members.members]]\ntype = \"sphere\"\n{}",
                    sphere(i)
                );
            }
            let _ = writeln!(
                text,
                "[[csg.members]]\ntype = \"box\"\nmin = [{}, -1, {}]\nmax = [{}, 1, {}]",
                -half - 1.0,
                -half - 1.0,
                half + 1.0,
                half + 1.0
            );
        }
    }
    parse_scene_with(&text, Path::new("spheres.toml"), Assets::Embedded(&[]))
        .context("the benchmark's sphere scene")
}

/// Seconds to prepare `scene` and render it (one subsample per pixel, `w` × `h`), median of
/// `runs`, and the image.
fn render_time(scene: &Scene, w: u32, h: u32, runs: usize) -> (f64, image::RgbImage) {
    let settings = RenderSettings::new(w, h, 1);
    let image = || {
        let prepared = Arc::new(PreparedScene::new(scene));
        render(prepared, scene.camera, settings, |_, _| {})
            .accumulator()
            .to_rgb8()
    };
    let seconds = median(runs, || {
        black_box(image());
    });
    (seconds, image())
}

/// How many pixels of `a` and `b` differ.
fn differing(a: &image::RgbImage, b: &image::RgbImage) -> usize {
    a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count()
}

/// A GLB file of a height field: an `n` × `n` grid of quads, two triangles each, gently
/// rolling (positions as f32, corners as u32).
fn height_field_glb(n: usize) -> Vec<u8> {
    let mut bin = Vec::with_capacity((n + 1) * (n + 1) * 12 + n * n * 24);
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for j in 0..=n {
        for i in 0..=n {
            let (x, z) = (i as f32 / n as f32 - 0.5, j as f32 / n as f32 - 0.5);
            let p = [x, 0.05 * (x * 20.0).sin() * (z * 17.0).cos(), z];
            for (k, v) in p.iter().enumerate() {
                lo[k] = lo[k].min(*v);
                hi[k] = hi[k].max(*v);
                bin.extend(v.to_le_bytes());
            }
        }
    }
    let positions = bin.len();
    let corner = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    for j in 0..n {
        for i in 0..n {
            let quad = [corner(i, j), corner(i, j + 1), corner(i + 1, j + 1)];
            let other = [corner(i, j), corner(i + 1, j + 1), corner(i + 1, j)];
            for c in quad.into_iter().chain(other) {
                bin.extend(c.to_le_bytes());
            }
        }
    }
    let corners = 6 * n * n;
    let document = json!({
        "asset": { "version": "2.0" },
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "name": "field", "mesh": 0 }],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "buffers": [{ "byteLength": bin.len() }],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": positions },
            { "buffer": 0, "byteOffset": positions, "byteLength": corners * 4 }
        ],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": (n + 1) * (n + 1),
              "type": "VEC3", "min": lo, "max": hi },
            { "bufferView": 1, "componentType": 5125, "count": corners, "type": "SCALAR" }
        ]
    });
    glb_file(&serde_json::to_vec(&document).expect("a JSON value"), &bin)
}

pub fn run(cfg: Config) -> Result<()> {
    let (union_spheres, nested_spheres, w, h, grid) = if cfg.quick {
        (100, 64, 160, 120, 224)
    } else {
        (1000, prism::limits::MAX_CSG_MEMBERS - 1, 640, 480, 708)
    };
    let mut md = String::new();
    let _ = writeln!(md, "# Modelling: CSG and glTF\n");
    let _ = writeln!(
        md,
        "Measured by `prism bench modelling{}` on {} hardware threads, the median of {} runs \
         each. A render is the scene prepared and rendered at one subsample per pixel; the \
         images are compared pixel for pixel.\n",
        if cfg.quick { " --quick" } else { "" },
        std::thread::available_parallelism().map_or(1, |n| n.get()),
        cfg.runs
    );
    let _ = writeln!(md, "| measured | prism | against | ratio | target |");
    let _ = writeln!(md, "|---|---|---|---|---|");
    for (n, how, what, target) in [
        (
            union_spheres,
            Spheres::Union,
            "a `[[csg]]` union",
            "at most 2×",
        ),
        (
            nested_spheres,
            Spheres::UnionInBox,
            "a union inside an intersection with a box around them",
            "at most 2×",
        ),
    ] {
        let (separate, by_objects) =
            render_time(&sphere_scene(n, Spheres::Separate)?, w, h, cfg.runs);
        let (combined, by_csg) = render_time(&sphere_scene(n, how)?, w, h, cfg.runs);
        let _ = writeln!(
            md,
            "| {w}×{h} render of {n} spheres as {what} | {:.3} s | {:.3} s as separate \
             objects ({} of {} pixels differ) | {:.2}× | {target} |",
            combined,
            separate,
            differing(&by_csg, &by_objects),
            w * h,
            combined / separate
        );
    }

    let field = height_field_glb(grid);
    let triangles = 2 * grid * grid;
    let files = [("field.glb", field.as_slice())];
    let text = "[camera]\neye = [0, 1, 1.5]\nlook_at = [0, 0, 0]\nfov = 40\n\n\
                [[meshes]]\npath = \"field.glb\"\n";
    let pool = prism::render::thread_pool(Some(2))?;
    let load_build = pool.install(|| -> Result<f64> {
        let load = || parse_scene_with(text, Path::new("field.toml"), Assets::Embedded(&files));
        load().context("the benchmark's glTF scene")?;
        Ok(median(cfg.runs, || {
            let scene = load().expect("loaded once already");
            black_box(PreparedScene::new(&scene));
        }))
    })?;
    let per_million = load_build * 1e6 / triangles as f64;
    let _ = writeln!(
        md,
        "| reading a {triangles}-triangle .glb ({:.1} MB) and building its hierarchy, 2 \
         threads | {load_build:.3} s ({per_million:.3} s per million) | | | at most 0.5 s per \
         million |",
        field.len() as f64 / 1e6
    );

    super::write_report(&cfg.out_dir, "modelling.md", &md)?;
    Ok(())
}
