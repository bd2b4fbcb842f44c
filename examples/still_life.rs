//! Writes assets/meshes/still_life.glb, the glTF scene of assets/scenes/gltf.toml: a table
//! (a node whose children stand on it) holding the Stanford bunny in red paint, a gold
//! ball and a glass ball, over a checkered cloth (a texture in the file's own bytes), lit by
//! a `KHR_lights_punctual` point light and a spotlight. Built the way an exporter writes
//! one: a node tree with translations, rotations and scales, one binary buffer.
//!
//! `cargo run --release --example still_life -- assets/meshes/still_life.glb`

use serde_json::{Value, json};
use std::f32::consts::PI;

/// The bytes of a GLB file and what its JSON lists, built up piece by piece.
#[derive(Default)]
struct Builder {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Builder {
    /// A buffer view over `bytes`, 4-byte aligned.
    fn view(&mut self, bytes: &[u8]) -> usize {
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        self.views
            .push(json!({ "buffer": 0, "byteOffset": offset, "byteLength": bytes.len() }));
        self.views.len() - 1
    }

    fn floats(&mut self, items: &[[f32; 3]], kind: &str, bounds: bool) -> usize {
        let bytes: Vec<u8> = items
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let view = self.view(&bytes);
        let mut a = json!({ "bufferView": view, "componentType": 5126, "count": items.len(), "type": kind });
        if bounds {
            let lo = (0..3).map(|c| items.iter().map(|p| p[c]).fold(f32::MAX, f32::min));
            let hi = (0..3).map(|c| items.iter().map(|p| p[c]).fold(f32::MIN, f32::max));
            a["min"] = json!(lo.collect::<Vec<_>>());
            a["max"] = json!(hi.collect::<Vec<_>>());
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    fn uvs(&mut self, items: &[[f32; 2]]) -> usize {
        let bytes: Vec<u8> = items
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let view = self.view(&bytes);
        self.accessors.push(json!({ "bufferView": view, "componentType": 5126, "count": items.len(), "type": "VEC2" }));
        self.accessors.len() - 1
    }

    fn indices(&mut self, items: &[u32]) -> usize {
        let bytes: Vec<u8> = items.iter().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.view(&bytes);
        self.accessors.push(json!({ "bufferView": view, "componentType": 5125, "count": items.len(), "type": "SCALAR" }));
        self.accessors.len() - 1
    }

    /// A mesh primitive of `positions`, `normals`, optional `uvs` and `triangles`.
    fn primitive(
        &mut self,
        positions: &[[f32; 3]],
        normals: &[[f32; 3]],
        uvs: Option<&[[f32; 2]]>,
        triangles: &[u32],
        material: usize,
    ) -> Value {
        let mut attributes = json!({
            "POSITION": self.floats(positions, "VEC3", true),
            "NORMAL": self.floats(normals, "VEC3", false),
        });
        if let Some(uvs) = uvs {
            attributes["TEXCOORD_0"] = json!(self.uvs(uvs));
        }
        json!({ "attributes": attributes, "indices": self.indices(triangles), "material": material })
    }
}

/// A unit sphere, `n` bands by 2n segments.
fn sphere(n: u32) -> (Vec<[f32; 3]>, Vec<u32>) {
    let mut p = Vec::new();
    for i in 0..=n {
        let theta = PI * i as f32 / n as f32;
        for j in 0..=2 * n {
            let phi = PI * j as f32 / n as f32;
            p.push([
                theta.sin() * phi.cos(),
                theta.cos(),
                -theta.sin() * phi.sin(),
            ]);
        }
    }
    let row = 2 * n + 1;
    let mut t = Vec::new();
    for i in 0..n {
        for j in 0..2 * n {
            let (a, b) = (i * row + j, (i + 1) * row + j);
            t.extend([a, b, b + 1, a, b + 1, a + 1]);
        }
    }
    (p, t)
}

/// An 8 × 8 checker of two colours, `texels` on a side, as PNG bytes.
fn checker(texels: u32) -> Vec<u8> {
    let img = image::RgbImage::from_fn(texels, texels, |x, y| {
        if (x * 8 / texels + y * 8 / texels).is_multiple_of(2) {
            image::Rgb([225, 215, 190])
        } else {
            image::Rgb([60, 80, 110])
        }
    });
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}

fn main() {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "assets/meshes/still_life.glb".into());
    let mut b = Builder::default();
    // The cloth: a square on the table top, its texture from the file's own bytes.
    let cloth = b.primitive(
        &[
            [-2.0, 0.0, -1.5],
            [2.0, 0.0, -1.5],
            [2.0, 0.0, 1.5],
            [-2.0, 0.0, 1.5],
        ],
        &[[0.0, 1.0, 0.0]; 4],
        Some(&[[0.0, 0.0], [1.0, 0.0], [1.0, 0.75], [0.0, 0.75]]),
        &[0, 2, 1, 0, 3, 2],
        0,
    );
    let picture = b.view(&checker(256));
    // The bunny, from the repository's OBJ.
    let text = std::fs::read_to_string("assets/meshes/bunny.obj").expect("run from the repository");
    let obj = prism::scene_file::parse_obj(&text, 1 << 24, true).expect("the bunny parses");
    let (mut bp, mut bn, mut bt) = (Vec::new(), Vec::new(), Vec::new());
    for part in &obj.parts {
        let mesh = &part.mesh;
        let base = bp.len() as u32;
        bp.extend(mesh.positions().iter().map(|p| p.to_array()));
        bn.extend((0..mesh.vertex_count()).map(|_| [0.0f32, 0.0, 0.0]));
        bt.extend(mesh.triangles().iter().flatten().map(|i| i + base));
    }
    // Normals: each vertex's faces' area-weighted mean.
    for t in bt.chunks(3) {
        let [a, b2, c] = [t[0], t[1], t[2]].map(|i| glam::Vec3::from(bp[i as usize]));
        let n = (b2 - a).cross(c - a);
        for &i in t {
            let m = &mut bn[i as usize];
            *m = (glam::Vec3::from(*m) + n).to_array();
        }
    }
    let bunny = b.primitive(&bp, &bn, None, &bt, 1);
    let (sp, st) = sphere(24);
    let gold = b.primitive(&sp, &sp, None, &st, 2);
    let glass = b.primitive(&sp, &sp, None, &st, 3);
    let doc = json!({
        "asset": { "version": "2.0", "generator": "prism examples/still_life.rs" },
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior"],
        "extensions": { "KHR_lights_punctual": { "lights": [
            { "name": "lamp", "type": "point", "color": [1.0, 0.95, 0.85], "intensity": 60000.0 },
            { "name": "spot", "type": "spot", "color": [0.8, 0.85, 1.0], "intensity": 60000.0,
              "spot": { "innerConeAngle": 0.25, "outerConeAngle": 0.45 } }
        ] } },
        "scene": 0,
        "scenes": [{ "name": "still life", "nodes": [0, 5, 6] }],
        "nodes": [
            { "name": "table", "translation": [0.0, 0.0, 0.0], "rotation": [0.0, 0.13, 0.0, 0.9915],
              "mesh": 0, "children": [1, 2, 3] },
            { "name": "bunny", "mesh": 1, "translation": [-0.6, 0.0005, 0.1], "scale": [0.12, 0.12, 0.12],
              "rotation": [0.0, 0.2588, 0.0, 0.9659] },
            { "name": "gold ball", "mesh": 2, "translation": [0.9, 0.35, -0.3], "scale": [0.35, 0.35, 0.35] },
            { "name": "stand", "translation": [0.6, 0.0, 0.8], "children": [4] },
            { "name": "glass ball", "mesh": 3, "translation": [0.0, 0.3, 0.0], "scale": [0.3, 0.3, 0.3] },
            { "name": "lamp", "translation": [-2.0, 4.0, 3.0], "extensions": { "KHR_lights_punctual": { "light": 0 } } },
            { "name": "spot", "translation": [3.0, 4.0, 1.0], "rotation": [-0.5, 0.3, 0.1, 0.8062],
              "extensions": { "KHR_lights_punctual": { "light": 1 } } }
        ],
        "meshes": [
            { "name": "cloth", "primitives": [cloth] },
            { "name": "bunny", "primitives": [bunny] },
            { "name": "gold ball", "primitives": [gold] },
            { "name": "glass ball", "primitives": [glass] }
        ],
        "materials": [
            { "name": "cloth", "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 }, "metallicFactor": 0.0, "roughnessFactor": 0.9 } },
            { "name": "paint", "pbrMetallicRoughness": { "baseColorFactor": [0.75, 0.12, 0.08, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.35 } },
            { "name": "gold", "pbrMetallicRoughness": { "baseColorFactor": [1.0, 0.77, 0.34, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.15 } },
            { "name": "glass", "pbrMetallicRoughness": { "baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.0 },
              "extensions": { "KHR_materials_transmission": { "transmissionFactor": 1.0 }, "KHR_materials_ior": { "ior": 1.5 } } }
        ],
        "textures": [{ "source": 0 }],
        "images": [{ "bufferView": picture, "mimeType": "image/png" }],
        "buffers": [{ "byteLength": b.bin.len() }],
        "bufferViews": b.views,
        "accessors": b.accessors
    });
    let file = prism::scene_file::glb_file(&serde_json::to_vec(&doc).unwrap(), &b.bin);
    std::fs::write(&out, file).unwrap();
    println!("wrote {out}");
}
