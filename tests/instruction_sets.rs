//! The instruction sets prism chooses at run time (src/isa.rs) make the same images: every
//! example scene rendered with `PRISM_ISA=baseline` and with `PRISM_ISA=avx2` gives the
//! same file, byte for byte. docs/farm.md promises this to farms of mixed machines.

mod common;

use common::{Dir, example_scenes, stderr};
use std::path::Path;
use std::process::{Command, Output, Stdio};

fn render_with(isa: &str, scene: &Path, out: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_prism"))
        .env("PRISM_ISA", isa)
        .args([
            "render",
            "--width",
            "96",
            "--height",
            "72",
            "--samples",
            "4",
        ])
        .arg(scene)
        .arg("-o")
        .arg(out)
        .stdin(Stdio::null())
        .output()
        .expect("prism runs")
}

#[test]
fn every_example_scene_is_the_same_with_each_instruction_set() {
    if !prism::isa::InstructionSet::Avx2.is_supported() {
        // The baseline is then the only path this processor runs: nothing to compare.
        eprintln!("skipped: this processor has no AVX2, so only the baseline path runs here");
        return;
    }
    let dir = Dir::new();
    for scene in example_scenes() {
        let name = scene.file_stem().unwrap().to_string_lossy().into_owned();
        let mut files = Vec::new();
        for isa in ["baseline", "avx2"] {
            let out = dir.path(&format!("{name}-{isa}.png"));
            let run = render_with(isa, &scene, &out);
            assert!(run.status.success(), "{name} with {isa}: {}", stderr(&run));
            files.push(std::fs::read(&out).unwrap());
        }
        assert!(
            files[0] == files[1],
            "{name}: the baseline and AVX2 paths made different images"
        );
    }
}

#[test]
fn a_name_prism_does_not_know_is_refused_before_any_work() {
    let dir = Dir::new();
    let out = dir.path("never.png");
    let seed = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/seed.toml");
    let run = render_with("avx512", &seed, &out);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        stderr(&run).contains(
            "PRISM_ISA=\"avx512\" is not an instruction set prism knows: use auto, baseline or avx2"
        ),
        "{}",
        stderr(&run)
    );
    assert!(!out.exists());
}

#[test]
fn a_set_the_processor_lacks_is_refused_and_one_it_has_is_used() {
    let dir = Dir::new();
    let out = dir.path("seed.png");
    let seed = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/seed.toml");
    let run = render_with("avx2", &seed, &out);
    if prism::isa::InstructionSet::Avx2.is_supported() {
        assert!(run.status.success(), "{}", stderr(&run));
    } else {
        assert_eq!(run.status.code(), Some(2));
        assert!(
            stderr(&run).contains("PRISM_ISA=avx2 asks for an instruction set this processor"),
            "{}",
            stderr(&run)
        );
        assert!(!out.exists());
    }
    assert!(render_with("baseline", &seed, &out).status.success());
}
