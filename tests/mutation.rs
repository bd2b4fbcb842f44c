//! A bounded mutation test of the scene loader, run with every `cargo test`: thousands of
//! damaged variants of the fuzz corpus (hostile numbers, lost and doubled lines, stray
//! bytes, truncation), each of which must load into a scene that renders to finite colours
//! or fail with a short, printable message. fuzz/ holds the coverage-guided fuzzer that
//! searches far longer.

use prism::render::RenderSettings;
use prism::scene::PreparedScene;
use prism::scene_file::parse_scene;
use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

const SEEDS: [&str; 15] = [
    include_str!("../fuzz/corpus/seed.toml"),
    include_str!("../fuzz/corpus/shapes.toml"),
    include_str!("../fuzz/corpus/sphere.toml"),
    include_str!("../fuzz/corpus/glass-box.toml"),
    include_str!("../fuzz/corpus/lights.toml"),
    include_str!("../fuzz/corpus/environment.toml"),
    include_str!("../fuzz/corpus/solids.toml"),
    include_str!("../fuzz/corpus/effects.toml"),
    include_str!("../fuzz/corpus/animation.toml"),
    include_str!("../fuzz/corpus/left-handed.toml"),
    include_str!("../fuzz/corpus/touching.toml"),
    include_str!("../fuzz/corpus/smooth-mesh-and-brackets.toml"),
    include_str!("../fuzz/corpus/csg.toml"),
    include_str!("../fuzz/corpus/groups.toml"),
    include_str!("../fuzz/corpus/path.toml"),
];

/// Values that have broken renderers: overflow when squared or multiplied, underflow,
/// signed zero, integers where floats go, non-numbers, and the edges of prism's limits.
const HOSTILE: [&str; 24] = [
    "0",
    "-0",
    "-1",
    "1e38",
    "-1e38",
    "3.4028235e38",
    "2e19",
    "5e18",
    "1e12",
    "1.0000001e12",
    "1e-12",
    "1e-45",
    "1e-300",
    "1e300",
    "nan",
    "inf",
    "-inf",
    "0.1",
    "10",
    "64",
    "65",
    "16384",
    "4294967296",
    "1.0000001",
];

/// Text the fuzzer's dictionary also offers: table headers and keys out of place.
const FRAGMENTS: [&str; 30] = [
    "[[spheres]]\ncenter = [0, 0, -5]\nradius = 1\n",
    "[[polygons]]\nvertices = [[0, 0, 0], [1, 0, 0], [1, 1e-7, 0]]\n",
    "[[tetrahedra]]\nvertices = [[0,0,0],[1,0,0],[0,1,0],[0,0,1e-9]]\n",
    "[[cylinders]]\nbase = [0, -1e11, -30]\nradius = 1\nheight = 2e11\n",
    "[[lights]]\nposition = [0, 0, 0]\n",
    "eta = 1e-30\n",
    "max_depth = 64\n",
    "name = \"\u{1b}[31m\n\"\n",
    "\u{0}",
    "[materials.x]\nreflectivity = 1\ntransparency = 1\n",
    "[[tori]]\ncenter = [0, 0, -5]\nmajor_radius = 1e-12\nminor_radius = 9e-13\nrotate = [90, 0, 0]\n",
    "[[planes]]\npoint = [0, 1e12, 0]\nnormal = [1e-45, 1, 0]\n",
    "[[cones]]\nbase = [0, 0, -5]\nradius = 0\ntop_radius = 1e12\nheight = 1e-12\ncaps = false\n",
    "[[boxes]]\nmin = [0, 0, 0]\nmax = [1e-30, 1, 1]\nscale = [1e6, 1e-6, 1]\nrotate = [0, 45, 0]\n",
    "[[lights]]\ntype = \"area\"\ncorner = [0, 1e12, 0]\nedge_u = [1e12, 0, 0]\nedge_v = [0, 1e-12, 1e-12]\n",
    "[[lights]]\ntype = \"sphere\"\nposition = [0, 0, 0]\nradius = 1e12\nfalloff = \"inverse_square\"\nintensity = 1e30\n",
    "[[lights]]\ntype = \"spot\"\nposition = [0, 0, 1]\ndirection = [0, 0, -1]\nangle = 0.01\nsoftness = 1\n",
    "[fog]\ndensity = 1e12\n",
    "[materials.y]\ntransparency = 1\neta = 10\nfresnel = true\nroughness = 1\nabsorption = [1e12, 0, 1e-30]\n",
    // Arrays of the wrong length, a byte-order mark, the camera's handedness, extents at
    // the thinness rule's edge, names that are nearly right.
    "center = [0, 0, -5, 99, \"x\", true]\nrotate = [1, 2, 3, 4, 5]\n",
    "[[triangles]]\nvertices = [[0, 0, -5], [1, 0, -5], [0, 1, -5], [1, 1, -5]]\n",
    "\u{feff}",
    "handedness = \"left\"\n",
    "[[cones]]\nbase = [0, 0, -5]\nradius = 1\nheight = 4.77e-6\ncaps = false\n",
    "[[spheres]]\ncenter = [0, 0, -5]\nraduis = 1\nmaterial = \"glas\"\n",
    // Brackets left open or closed in strings and comments; surfaces that touch.
    "position = [1, 1, 1\n",
    "name = \"[,,]\" # [,,\n",
    "[[boxes]]\nmin = [-1, -1, -6]\nmax = [1, 0, -4]\n[[boxes]]\nmin = [-1, 0, -6]\nmax = [1, 1, -4]\nmaterial = \"x\"\n",
    // A capsule at the thinness rule's edge, far out, turned.
    "[[capsules]]\nbase = [0, 1e11, -30]\nradius = 1e-12\nheight = 4.77e-6\nrotate = [0, 0, 90]\n",
    "[animation]\nframes = 2\n[[animation.track]]\ntarget = \"spheres[0]\"\nfield = \"radius\"\nkeys = [{ frame = 0, value = 1 }, { frame = 1e300, value = 2 }]\n",
];

#[derive(Clone, Debug)]
enum Mutation {
    /// Replaces the n-th number in the text.
    Number(usize, usize),
    DeleteLine(usize),
    DuplicateLine(usize),
    /// Puts a byte (as a char) at a position.
    Byte(usize, u8),
    Insert(usize, usize),
    Truncate(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        12 => (any::<usize>(), 0..HOSTILE.len()).prop_map(|(n, v)| Mutation::Number(n, v)),
        1 => any::<usize>().prop_map(Mutation::DeleteLine),
        1 => any::<usize>().prop_map(Mutation::DuplicateLine),
        1 => (any::<usize>(), any::<u8>()).prop_map(|(p, b)| Mutation::Byte(p, b)),
        1 => (any::<usize>(), 0..FRAGMENTS.len()).prop_map(|(p, f)| Mutation::Insert(p, f)),
        1 => any::<usize>().prop_map(Mutation::Truncate),
    ]
}

/// The char boundary at or before `at % (len + 1)`.
fn boundary(text: &str, at: usize) -> usize {
    let mut i = at % (text.len() + 1);
    while !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn apply(text: &str, m: &Mutation) -> String {
    match *m {
        Mutation::Number(n, v) => {
            let numbers: Vec<(usize, usize)> = number_spans(text);
            if numbers.is_empty() {
                return text.to_string();
            }
            let (a, b) = numbers[n % numbers.len()];
            format!("{}{}{}", &text[..a], HOSTILE[v], &text[b..])
        }
        Mutation::DeleteLine(n) | Mutation::DuplicateLine(n) => {
            let mut lines: Vec<&str> = text.lines().collect();
            if lines.is_empty() {
                return text.to_string();
            }
            let k = n % lines.len();
            if matches!(m, Mutation::DeleteLine(_)) {
                lines.remove(k);
            } else {
                lines.insert(k, lines[k]);
            }
            lines.join("\n")
        }
        Mutation::Byte(p, b) => {
            let i = boundary(text, p);
            let end = text[i..].chars().next().map_or(i, |c| i + c.len_utf8());
            format!("{}{}{}", &text[..i], b as char, &text[end..])
        }
        Mutation::Insert(p, f) => {
            let i = boundary(text, p);
            format!("{}{}{}", &text[..i], FRAGMENTS[f], &text[i..])
        }
        Mutation::Truncate(p) => text[..boundary(text, p)].to_string(),
    }
}

/// Where the numbers are: runs of digits with their sign, point and exponent.
fn number_spans(text: &str) -> Vec<(usize, usize)> {
    let bytes = text.as_bytes();
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i].is_ascii_digit() {
            let mut a = i;
            if a > 0 && bytes[a - 1] == b'-' {
                a -= 1;
            }
            let mut b = i;
            while b < bytes.len() && (bytes[b].is_ascii_digit() || b".eE+-".contains(&bytes[b])) {
                b += 1;
            }
            spans.push((a, b));
            i = b;
        } else {
            i += 1;
        }
    }
    spans
}

/// A folder laid out like assets/ (scenes/ beside a small earth.jpg and earth.png).
fn base_dir() -> &'static Path {
    static DIR: OnceLock<(tempfile::TempDir, PathBuf)> = OnceLock::new();
    &DIR.get_or_init(|| {
        let root = tempfile::tempdir().unwrap();
        let scenes = root.path().join("scenes");
        std::fs::create_dir(&scenes).unwrap();
        let earth = image::RgbImage::from_fn(32, 16, |x, y| {
            image::Rgb([(x * 8) as u8, (y * 16) as u8, 200])
        });
        earth.save(root.path().join("earth.jpg")).unwrap();
        earth.save(root.path().join("earth.png")).unwrap();
        (root, scenes)
    })
    .1
}

/// What must hold for any text: a scene that renders finite colours, or a short message;
/// for an animated scene, at its first frame (as it loads) and at its last.
fn loads_or_explains(text: &str) -> Result<(), TestCaseError> {
    let path = Path::new("mutant.toml");
    frame_loads_or_explains(parse_scene(text, path, base_dir()))?;
    if let Ok(Some(animation)) = prism::scene_file::Animation::parse(text, path) {
        let assets = prism::scene_file::Assets::Folder(base_dir());
        frame_loads_or_explains(animation.scene_at(animation.frames - 1, path, assets))?;
    }
    Ok(())
}

fn frame_loads_or_explains(
    scene: Result<prism::scene::Scene, prism::scene_file::SceneError>,
) -> Result<(), TestCaseError> {
    match scene {
        Err(e) => {
            let message = e.to_string();
            let located = message
                .strip_prefix("frame ")
                .map_or(message.as_str(), |rest| {
                    rest.split_once(": ").map_or(rest, |(_, after)| after)
                });
            prop_assert!(located.starts_with("mutant.toml"), "{message}");
            prop_assert!(message.chars().count() < 2000, "{} chars", message.len());
            prop_assert!(!message.chars().any(char::is_control), "{message:?}");
        }
        Ok(scene) => {
            let prepared = Arc::new(PreparedScene::new(&scene));
            let mut settings = RenderSettings::new(6, 4, 1);
            settings.integrator = scene.render.integrator;
            let job = prism::render::render(prepared, scene.camera, settings, |_, _| {});
            for p in &job.accumulator().pixels {
                prop_assert!(p.mean().is_finite(), "a pixel of {}", p.mean());
            }
        }
    }
    Ok(())
}

#[test]
fn the_corpus_itself_loads() {
    for (i, seed) in SEEDS.iter().enumerate() {
        parse_scene(seed, Path::new("seed.toml"), base_dir())
            .unwrap_or_else(|e| panic!("corpus scene {i}: {e}"));
    }
}

#[test]
fn the_number_finder_sees_signs_and_exponents() {
    let text = "a = [-1.5e3, 2]\nb = 7";
    let found: Vec<&str> = number_spans(text)
        .iter()
        .map(|&(a, b)| &text[a..b])
        .collect();
    assert_eq!(found, ["-1.5e3", "2", "7"]);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 6000, ..ProptestConfig::default() })]

    #[test]
    fn every_mutant_loads_or_explains(
        seed in 0..SEEDS.len(),
        mutations in proptest::collection::vec(mutation(), 1..4),
    ) {
        let mut text = SEEDS[seed].to_string();
        for m in &mutations {
            text = apply(&text, m);
        }
        loads_or_explains(&text)?;
    }
}
