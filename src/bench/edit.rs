//! `prism bench edit`: what an appearance edit costs in a running render, against preparing
//! the scene again (what every edit cost before geometry and appearance were kept apart);
//! and what a geometry edit in a mesh scene costs, prepared afresh and from the scene before.

use super::scenes::{herd, sphere_field};
use super::timing::median;
use anyhow::{Context, Result};
use glam::{Affine3A, Vec3};
use prism::render::{ProgressiveRender, RenderSettings};
use prism::scene::{PreparedScene, Scene, ShapeDesc};
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::PathBuf;
use std::sync::Arc;

/// What to measure and where the table goes.
pub struct Config {
    /// 1,000 spheres and a small image rather than 10,000 and 800×600.
    pub quick: bool,
    /// Timed runs of each edit (the median is reported).
    pub runs: usize,
    /// The folder `edit.md` is written to.
    pub out_dir: PathBuf,
}

/// Times an edit that makes one sphere of a `sphere_field` glass, as a viewer slider does,
/// three ways, and writes the table to `edit.md`.
pub fn run(cfg: Config) -> Result<()> {
    let (spheres, w, h) = if cfg.quick {
        (1000, 160, 120)
    } else {
        (10_000, 800, 600)
    };
    let scene = sphere_field(spheres);
    let mut edited = scene.clone();
    edited.objects[0].material.transparency = 0.5;
    edited.objects[0].material.eta = Some(1.5);
    let material = edited.objects[0].material.clone();

    let rebuild = median(cfg.runs, || {
        black_box(PreparedScene::new(&edited));
    });
    // Far shorter than a clock tick is precise to: timed a thousand at a time, alternating
    // with the opposite edit (back to opaque, which checks every material for transparency).
    const BATCH: usize = 1000;
    let mut prepared = PreparedScene::new(&scene);
    let opaque = scene.objects[0].material.clone();
    let table = median(cfg.runs, || {
        for i in 0..BATCH {
            let m = if i % 2 == 0 { &material } else { &opaque };
            prepared.appearance.set_material(0, m.clone());
            black_box(&prepared);
        }
    }) / BATCH as f64;
    let mut job = ProgressiveRender::new(
        Arc::new(PreparedScene::new(&scene)),
        scene.camera,
        RenderSettings::new(w, h, 1),
    );
    let restart = median(cfg.runs, || {
        job.edit_appearance(|a| a.set_material(0, material.clone()));
    });
    let geometry = geometry_edits(cfg.runs)?;

    let mut md = String::new();
    writeln!(
        md,
        "# An appearance edit{}\n\n\
         `sphere_field({spheres})`, a {w}×{h} render; medians of {} runs on a shared 2-core \
         machine. Made by `cargo run --release -- bench edit{}`.\n\n\
         One sphere becomes glass (transparency 0.5, eta 1.5), as a viewer slider does. \
         Preparing the scene again builds the shapes, the BVH and the light buffers; the \
         edit changes the material table in place (timed as the mean of a thousand edits, \
         alternating glass and opaque), and a running render then restarts its \
         accumulation, keeping the geometry and the view's first-hit tiles.\n\n\
         | edit | time |\n|---|---|\n\
         | prepare the scene again | {:.2} ms |\n\
         | change the material table in place | {:.1} µs |\n\
         | change it in a running render (and restart the accumulation) | {:.3} ms |",
        if cfg.quick { " (quick mode)" } else { "" },
        cfg.runs,
        super::flags_of_report(cfg.quick),
        rebuild * 1e3,
        table * 1e6,
        restart * 1e3,
    )?;
    writeln!(
        md,
        "\n## A geometry edit in a mesh scene\n\n\
         Five placed bunnies under two point lights (`herd` in src/bench/scenes.rs), one light or \
         one bunny moved by one unit along x, as dragging it in the viewer does. Prepared \
         afresh, every mesh's hierarchy and every placed mesh's lists around every light are \
         made again; prepared from the scene before (`PreparedScene::updated`), only the \
         lists of what moved are. Medians of {} runs.\n\n\
         | moved | prepared afresh | from the scene before |\n|---|---|---|",
        cfg.runs
    )?;
    for (what, fresh, kept) in geometry {
        writeln!(
            md,
            "| {what} | {:.1} ms | {:.1} ms |",
            fresh * 1e3,
            kept * 1e3
        )?;
    }
    print!("{md}");
    std::fs::create_dir_all(&cfg.out_dir)
        .with_context(|| format!("cannot create {}", cfg.out_dir.display()))?;
    let path = cfg.out_dir.join("edit.md");
    prism::render::write_bytes(&path, md.as_bytes())?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

/// The herd with one light, then one bunny, moved by a unit along x: for each, the median
/// seconds of preparing it afresh and from the herd prepared.
fn geometry_edits(runs: usize) -> Result<Vec<(&'static str, f64, f64)>> {
    let scene = herd().context("the herd scene")?;
    let prepared = PreparedScene::new(&scene);
    let mut lit = scene.clone();
    lit.lights[0] = lit.lights[0].moved_by(Vec3::X);
    let mut moved = scene.clone();
    let bunny = moved
        .objects
        .iter_mut()
        .find_map(|o| match &mut o.shape {
            ShapeDesc::Mesh { transform, .. } => Some(transform),
            _ => None,
        })
        .context("the herd has bunnies")?;
    *bunny = bunny
        .then(Affine3A::from_translation(Vec3::X))
        .context("a bunny moved by a unit")?;
    let edits: [(&'static str, &Scene); 2] = [("light 0", &lit), ("the first bunny", &moved)];
    Ok(edits
        .into_iter()
        .map(|(what, edited)| {
            let fresh = median(runs, || {
                black_box(PreparedScene::new(edited));
            });
            let kept = median(runs, || {
                black_box(prepared.updated(&scene, edited));
            });
            (what, fresh, kept)
        })
        .collect())
}
