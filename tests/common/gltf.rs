//! glTF files for tests to write: a cube's triangles, buffers with their views and
//! accessors, base64 for data URIs, and the GLB container.

use serde_json::{Value, json};

/// A unit cube about the origin: 8 corners and 12 triangles wound outwards.
pub fn cube() -> (Vec<[f32; 3]>, Vec<u16>) {
    let p = (0..8)
        .map(|i| {
            [
                if i & 1 == 0 { -0.5 } else { 0.5 },
                if i & 2 == 0 { -0.5 } else { 0.5 },
                if i & 4 == 0 { -0.5 } else { 0.5 },
            ]
        })
        .collect();
    let faces: [[u16; 4]; 6] = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let mut t = Vec::new();
    for [a, b, c, d] in faces {
        t.extend([a, b, c, a, c, d]);
    }
    (p, t)
}

/// A buffer of `positions` then `indices`, and the accessors and views over them:
/// (bytes, bufferViews, accessors).
pub fn geometry(positions: &[[f32; 3]], indices: &[u16]) -> (Vec<u8>, Value, Value) {
    let mut bytes: Vec<u8> = positions
        .iter()
        .flatten()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let index_offset = bytes.len();
    bytes.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
    while !bytes.len().is_multiple_of(4) {
        bytes.push(0);
    }
    let (lo, hi) = positions
        .iter()
        .fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
                [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
            )
        });
    let views = json!([
        { "buffer": 0, "byteOffset": 0, "byteLength": index_offset },
        { "buffer": 0, "byteOffset": index_offset, "byteLength": indices.len() * 2 }
    ]);
    let accessors = json!([
        { "bufferView": 0, "componentType": 5126, "count": positions.len(), "type": "VEC3",
          "min": lo, "max": hi },
        { "bufferView": 1, "componentType": 5123, "count": indices.len(), "type": "SCALAR" }
    ]);
    (bytes, views, accessors)
}

/// Base64 of `bytes` (for data URIs).
pub fn base64(bytes: &[u8]) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(A[(n >> (18 - 6 * i) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// A GLB file of `document` with `bin` as its binary chunk.
pub fn glb(document: &Value, bin: &[u8]) -> Vec<u8> {
    prism::scene_file::glb_file(&serde_json::to_vec(document).unwrap(), bin)
}
