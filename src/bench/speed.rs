//! `prism bench speed`: prism beside the renderers people would pick instead, on their own
//! ground. The seed scene against POV-Ray 3.7 (benches/reference/seed.pov, the same scene
//! in its language), both as whole processes that read the scene and write a PNG; a mesh
//! pass against Embree 3 (benches/reference/embree_trace.cpp: the bunny, one primary and
//! one shadow ray per pixel), at 1 and 2 threads; and loading and building a
//! million-triangle mesh (docs/benchmarks/speed.md). A reference that is not installed is
//! named in its row, and the rest is measured.

use super::scale::to_obj;
use super::scenes::BUNNY_OBJ;
use super::timing::{median, median_of, sorted};
use anyhow::{Context, Result, bail};
use prism::accel::Model;
use prism::render::{ProgressiveRender, RenderSettings};
use prism::sampler::SampleLayout;
use prism::scene::{PreparedScene, Scene};
use prism::scene_file::{Assets, parse_obj, parse_scene_with};
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;
use std::time::Instant;

/// The seed scene in POV-Ray's language, and the texture it reads.
const SEED_POV: &str = include_str!("../../benches/reference/seed.pov");
const EARTH_JPG: &[u8] = include_bytes!("../../assets/earth.jpg");
/// The Embree 3 mesh tracer prism's mesh pass is raced against.
const EMBREE_TRACE: &str = include_str!("../../benches/reference/embree_trace.cpp");

/// What to measure and where the table goes.
pub struct Config {
    /// A small seed image and the bunny subdivided twice: proves the bench works.
    pub quick: bool,
    /// Timed runs of each figure.
    pub runs: usize,
    /// The folder `speed.md` is written to.
    pub out_dir: PathBuf,
}

/// One row of the table: what was measured, prism's figure, the reference's (or why there
/// is none), the ratio, and the target.
struct Row {
    what: String,
    prism: String,
    reference: String,
    ratio: String,
    target: String,
}

/// The mesh scene of embree_trace.cpp in prism's terms: its camera, its point light, the
/// mesh flat-shaded in a white that is lit by that light alone, on black.
fn mesh_scene(obj: &str, w: u32, h: u32) -> Result<Scene> {
    let text = format!(
        "[camera]\neye = [0, 5, 22]\ndirection = [0, 0, -1]\nfov = 28.072487\n\n\
         [render]\nwidth = {w}\nheight = {h}\nbackground = [0, 0, 0]\nambient = [0, 0, 0]\n\n\
         [[lights]]\nposition = [20, 40, 30]\n\n\
         [materials.white]\ncolor = [1, 1, 1]\nambient = 0\ndiffuse = 1\nspecular = 0\n\n\
         [[meshes]]\npath = \"mesh.obj\"\nsmooth = false\nmaterial = \"white\"\n"
    );
    let files = [("mesh.obj", obj.as_bytes())];
    parse_scene_with(&text, Path::new("speed.toml"), Assets::Embedded(&files))
        .context("the mesh benchmark's scene")
}

/// One pass over `scene` (a ray through each pixel's centre) on `threads` threads: its
/// fastest and median time over `runs`, and how many pixels it lit. Each run's render job
/// (its pixel sums, allocated and cleared) is made before its clock starts, as Embree's
/// tracer allocates its image before its own: what is timed is the pass, including the
/// camera view it builds on first use.
fn mesh_pass(scene: &Scene, threads: usize, runs: usize) -> Result<(f64, f64, usize)> {
    let pool = prism::render::thread_pool(Some(threads))?;
    let prepared = Arc::new(PreparedScene::new(scene));
    let mut settings = RenderSettings::new(scene.render.width, scene.render.height, 1);
    settings.layout = SampleLayout::Grid;
    let mut times = Vec::with_capacity(runs);
    let mut last = None;
    pool.install(|| {
        for _ in 0..runs.max(1) {
            let mut job = ProgressiveRender::new(prepared.clone(), scene.camera, settings);
            let start = Instant::now();
            black_box(job.step(&|| false));
            times.push(start.elapsed().as_secs_f64());
            last = Some(job);
        }
    });
    let lit = last.map_or(0, |job| {
        let image = job.accumulator().to_rgb8();
        image.pixels().filter(|p| p.0[0] > 0).count()
    });
    let times = sorted(times);
    Ok((times[0], times[times.len() / 2], lit))
}

/// What embree_trace.cpp printed: build seconds, pass milliseconds, lit pixels.
struct EmbreeRun {
    build: f64,
    pass_ms: f64,
    lit: usize,
}

/// Compiles embree_trace.cpp in `dir` with its own build line; the reason when it cannot.
fn build_embree(dir: &Path) -> Result<PathBuf, String> {
    let source = dir.join("embree_trace.cpp");
    std::fs::write(&source, EMBREE_TRACE).map_err(|e| e.to_string())?;
    let exe = dir.join("embree_trace");
    let mut cmd = Command::new("g++");
    cmd.arg("-O3");
    if cfg!(target_arch = "x86_64") {
        cmd.arg("-march=x86-64-v2");
    }
    cmd.arg(&source)
        .args(["-lembree3", "-lpthread", "-o"])
        .arg(&exe);
    match cmd.output() {
        Err(e) => Err(format!(
            "g++ is not installed ({e}): Embree's tracer cannot be built"
        )),
        Ok(out) if !out.status.success() => {
            let err = String::from_utf8_lossy(&out.stderr);
            let first = err.lines().find(|l| l.contains("error")).unwrap_or("");
            Err(format!(
                "Embree 3 is not installed (apt-get install libembree-dev): {}",
                first.trim()
            ))
        }
        Ok(_) => Ok(exe),
    }
}

/// Runs the Embree tracer on `obj` (a file) subdivided `levels` times on `threads`.
fn run_embree(exe: &Path, obj: &Path, levels: u32, threads: usize) -> Result<EmbreeRun> {
    let out = Command::new(exe)
        .arg(obj)
        .arg(levels.to_string())
        .arg(threads.to_string())
        .current_dir(obj.parent().unwrap_or(Path::new(".")))
        .output()
        .context("running the Embree tracer")?;
    if !out.status.success() {
        bail!(
            "the Embree tracer failed: {}",
            String::from_utf8_lossy(&out.stderr).trim()
        );
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let number_after = |key: &str| -> Option<f64> {
        let rest = &text[text.find(key)? + key.len()..];
        rest.split_whitespace().next()?.parse().ok()
    };
    let parsed = (|| {
        Some(EmbreeRun {
            build: number_after("build ")?,
            pass_ms: number_after("pass ")?,
            lit: text
                .split(", ")
                .find(|s| s.ends_with("lit pixels\n") || s.ends_with("lit pixels"))?
                .split_whitespace()
                .next()?
                .parse()
                .ok()?,
        })
    })();
    parsed.with_context(|| format!("the Embree tracer printed {:?}", text.trim()))
}

/// Wall-clock seconds of `cmd`, which must succeed.
fn process_seconds(cmd: &mut Command) -> Result<f64> {
    let start = Instant::now();
    let out = cmd
        .output()
        .with_context(|| format!("running {:?}", cmd.get_program()))?;
    let seconds = start.elapsed().as_secs_f64();
    if !out.status.success() {
        bail!(
            "{:?} failed: {}",
            cmd.get_program(),
            String::from_utf8_lossy(&out.stderr).trim()
        );
    }
    Ok(seconds)
}

fn povray_available() -> bool {
    Command::new("povray")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success() || !o.stderr.is_empty())
}

/// The seed scene at `w` × `h` with `aa`² subsamples on 2 threads: prism's and POV-Ray's
/// whole processes, alternated, `runs` each; the median of each.
fn seed_rows(cfg: &Config, dir: &Path, rows: &mut Vec<Row>) -> Result<()> {
    let (w, h, aa) = if cfg.quick {
        (200, 150, 2)
    } else {
        (800, 600, 4)
    };
    let what = format!(
        "seed scene, {w}×{h}, {} subsamples per pixel, 2 threads, whole process",
        aa * aa
    );
    let exe = std::env::current_exe().context("finding prism's own executable")?;
    let mut prism = Command::new(&exe);
    prism
        .args(["render", "--quiet", "--threads", "2"])
        .args(["--width", &w.to_string(), "--height", &h.to_string()])
        .args(["--aa", &aa.to_string(), "--out"])
        .arg(dir.join("prism_seed.png"));
    let mut times = Vec::new();
    let mut pov_times = Vec::new();
    let pov = povray_available();
    if pov {
        std::fs::write(dir.join("seed.pov"), SEED_POV)?;
        std::fs::write(dir.join("earth.jpg"), EARTH_JPG)?;
    }
    for _ in 0..cfg.runs {
        times.push(process_seconds(&mut prism)?);
        if pov {
            let mut povray = Command::new("povray");
            povray
                .current_dir(dir)
                .args(["+Iseed.pov", "+Opov_seed.png", "-D", "-V", "-GA"])
                .args([format!("+W{w}"), format!("+H{h}")])
                .args(["+A0.0", "+AM1", &format!("+R{aa}"), "+WT2"])
                .args(["File_Gamma=1.0"]);
            pov_times.push(process_seconds(&mut povray)?);
        }
    }
    let prism_s = median_of(times);
    let (reference, ratio) = if pov {
        let pov_s = median_of(pov_times);
        (
            format!("POV-Ray 3.7: {pov_s:.3} s"),
            format!("{:.2}× faster", pov_s / prism_s),
        )
    } else {
        (
            "POV-Ray is not installed (apt-get install povray)".into(),
            String::new(),
        )
    };
    rows.push(Row {
        what,
        prism: format!("{prism_s:.3} s"),
        reference,
        ratio,
        target: "at least 10× faster".into(),
    });
    Ok(())
}

/// The mesh pass at each subdivision level and thread count against Embree, and loading
/// and building the finest mesh.
fn mesh_rows(cfg: &Config, dir: &Path, rows: &mut Vec<Row>) -> Result<()> {
    let (w, h) = (800, 600);
    let fine_levels = if cfg.quick { 2 } else { 4 };
    let bunny = parse_obj(BUNNY_OBJ, usize::MAX, true)
        .map_err(|e| anyhow::anyhow!("bunny.obj:{}: {}", e.line, e.message))?
        .parts
        .remove(0)
        .mesh;
    let bunny_obj = to_obj(&bunny);
    let obj_path = dir.join("bunny.obj");
    std::fs::write(&obj_path, &bunny_obj)?;
    let embree = build_embree(dir);
    // Embree's tracer reports the best of 7 passes: prism's figure is the same statistic.
    let runs = 7;
    let mut fine = bunny.clone();
    for levels in [0, fine_levels] {
        while fine.triangle_count() < bunny.triangle_count() << (2 * levels) {
            fine = fine.subdivided();
        }
        let mesh = if levels == 0 { &bunny } else { &fine };
        let scene = mesh_scene(&to_obj(mesh), w, h)?;
        for threads in [1, 2] {
            let (best, median, lit) = mesh_pass(&scene, threads, runs)?;
            let what = format!(
                "{w}×{h} mesh pass, {} triangles, {threads} thread{}",
                mesh.triangle_count(),
                if threads == 1 { "" } else { "s" }
            );
            let prism_cell = format!(
                "{:.1} ms (median {:.1}), {lit} pixels lit",
                best * 1e3,
                median * 1e3
            );
            let (reference, ratio) = match &embree {
                Ok(exe) => {
                    let e = run_embree(exe, &obj_path, levels, threads)?;
                    (
                        format!("Embree 3: {:.1} ms, {} pixels lit", e.pass_ms, e.lit),
                        format!("{:.2}× Embree's time", best * 1e3 / e.pass_ms),
                    )
                }
                Err(why) => (why.clone(), String::new()),
            };
            rows.push(Row {
                what,
                prism: prism_cell,
                reference,
                ratio,
                target: "at most 1× Embree's time".into(),
            });
        }
    }

    // Loading (reading the OBJ text) and building the finest mesh's hierarchy, 2 threads.
    let fine_obj = to_obj(&fine);
    let triangles = fine.triangle_count();
    let pool = prism::render::thread_pool(Some(2))?;
    let load_build = pool.install(|| {
        median(cfg.runs, || {
            let parsed = parse_obj(&fine_obj, usize::MAX, true).expect("the subdivided bunny");
            for part in parsed.parts {
                black_box(Model::mesh(&part.mesh));
            }
        })
    });
    let per_million = load_build * 1e6 / triangles as f64;
    let reference = match &embree {
        Ok(exe) => {
            let e = run_embree(exe, &obj_path, fine_levels, 2)?;
            format!(
                "Embree 3 builds it in {:.3} s (its reading not counted)",
                e.build
            )
        }
        Err(why) => why.clone(),
    };
    let model = Model::mesh(&fine);
    rows.push(Row {
        what: format!("loading and building {triangles} triangles from OBJ text, 2 threads"),
        prism: format!(
            "{load_build:.3} s ({per_million:.3} s per million; {:.1} bytes per triangle beyond the vertices)",
            model.index_bytes() as f64 / triangles as f64
        ),
        reference,
        ratio: String::new(),
        target: "at most 0.5 s per million, 100 bytes per triangle".into(),
    });
    Ok(())
}

/// A scratch folder for the reference programs and their files, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new() -> Result<Self> {
        let dir = std::env::temp_dir().join(format!("prism-bench-speed-{}", std::process::id()));
        std::fs::create_dir_all(&dir)
            .with_context(|| format!("creating the scratch folder {}", dir.display()))?;
        Ok(Self(dir))
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

pub fn run(cfg: Config) -> Result<()> {
    let work = Scratch::new()?;
    let mut rows = Vec::new();
    seed_rows(&cfg, &work.0, &mut rows)?;
    mesh_rows(&cfg, &work.0, &mut rows)?;

    let mut md = String::new();
    let _ = writeln!(md, "# Speed beside POV-Ray and Embree\n");
    let _ = writeln!(
        md,
        "Measured by `prism bench speed{}` on {} hardware threads. The seed rows are whole \
         processes (reading the scene, rendering, writing a PNG), alternated, the median of \
         {} runs each; the mesh passes are the fastest of 7 in one process, as Embree's \
         tracer reports its own, each timed from a render job made beforehand (as Embree's \
         tracer allocates its image before its clock starts). prism's box tests ran on the \
         {} instruction set (`PRISM_ISA`, docs/farm.md).\n",
        if cfg.quick { " --quick" } else { "" },
        std::thread::available_parallelism().map_or(1, |n| n.get()),
        cfg.runs,
        prism::isa::active().name()
    );
    let _ = writeln!(md, "| measured | prism | reference | ratio | target |");
    let _ = writeln!(md, "|---|---|---|---|---|");
    for r in &rows {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} |",
            r.what, r.prism, r.reference, r.ratio, r.target
        );
    }
    super::write_report(&cfg.out_dir, "speed.md", &md)?;
    Ok(())
}
