//! Writes the brick wall of assets/scenes/relief.toml: one repeating tile of running-bond
//! bricks as three pictures, its colour, its height (white: a brick's face, black: the
//! mortar's floor) and the tangent-space normal map of that height (red right, green up the
//! picture, blue out), all from one fixed seed (the same files every run).
//!
//! `cargo run --release --example bricks -- assets/bricks`
//! writes assets/bricks_color.png, assets/bricks_height.png and assets/bricks_normal.png.

const SIZE: usize = 512;
/// Bricks per row, and rows, in one tile.
const ACROSS: usize = 2;
const ROWS: usize = 4;
/// The mortar's half-width and the bevel of a brick's edge, in texels.
const MORTAR: f64 = 5.0;
const BEVEL: f64 = 7.0;
/// How many texels one unit of height spans, for the normal map's slopes (a depth of
/// BEVEL texels over the bevel's width: edges at about 45°).
const TEXELS_PER_HEIGHT: f64 = BEVEL;

/// A hash of integer coordinates to [0, 1): the same everywhere, no dependency.
fn hash(x: i64, y: i64, seed: u64) -> f64 {
    let mut z = (x as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (y as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
        ^ seed.wrapping_mul(0x1656_67B1_9E37_79F9);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
}

/// Smooth value noise with period `period` texels, wrapping at the tile's edge.
fn noise(x: f64, y: f64, period: usize, seed: u64) -> f64 {
    let cells = (SIZE / period) as i64;
    let (fx, fy) = (x / period as f64, y / period as f64);
    let (x0, y0) = (fx.floor(), fy.floor());
    let (tx, ty) = (fx - x0, fy - y0);
    let smooth = |t: f64| t * t * (3.0 - 2.0 * t);
    let at = |i: i64, j: i64| hash(i.rem_euclid(cells), j.rem_euclid(cells), seed);
    let (i, j) = (x0 as i64, y0 as i64);
    let top = at(i, j) + (at(i + 1, j) - at(i, j)) * smooth(tx);
    let bottom = at(i, j + 1) + (at(i + 1, j + 1) - at(i, j + 1)) * smooth(tx);
    top + (bottom - top) * smooth(ty)
}

/// Which brick a texel lies in (row, column, with the row's offset) and how far it is
/// inside that brick's edge, in texels.
fn brick_at(x: f64, y: f64) -> ((i64, i64), f64) {
    let (w, h) = (SIZE as f64 / ACROSS as f64, SIZE as f64 / ROWS as f64);
    let y = y.rem_euclid(SIZE as f64);
    let row = (y / h).floor();
    let shift = if row as i64 % 2 == 1 { w * 0.5 } else { 0.0 };
    let xs = (x + shift).rem_euclid(SIZE as f64);
    let col = (xs / w).floor();
    let (lx, ly) = (xs - col * w, y - row * h);
    let inside = lx.min(w - lx).min(ly).min(h - ly) - MORTAR;
    ((row as i64, col as i64 % ACROSS as i64), inside)
}

fn height(x: f64, y: f64) -> f64 {
    let (_, inside) = brick_at(x, y);
    let grain = 0.06 * noise(x, y, 8, 1) + 0.04 * noise(x, y, 32, 2);
    if inside <= 0.0 {
        0.1 + grain
    } else {
        let t = (inside / BEVEL).min(1.0);
        0.1 + 0.8 * t * t * (3.0 - 2.0 * t) + grain
    }
}

fn color(x: f64, y: f64) -> [f64; 3] {
    let ((row, col), inside) = brick_at(x, y);
    let speckle = noise(x, y, 4, 3) - 0.5;
    if inside <= 0.0 {
        let g = 0.62 + 0.08 * speckle;
        return [g, g * 0.98, g * 0.93];
    }
    // Each brick its own shade of red, mottled.
    let shade = 0.8 + 0.35 * hash(row, col, 4);
    let mottle = 0.85 + 0.3 * noise(x, y, 16, 5) + 0.1 * speckle;
    [
        0.58 * shade * mottle,
        0.24 * shade * mottle,
        0.16 * shade * mottle,
    ]
}

fn save(path: &str, pixels: Vec<u8>) -> Result<(), Box<dyn std::error::Error>> {
    image::RgbImage::from_raw(SIZE as u32, SIZE as u32, pixels)
        .ok_or("image size")?
        .save(path)?;
    println!("wrote {path} ({SIZE}×{SIZE})");
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let stem = std::env::args().nth(1).ok_or("usage: bricks OUT_STEM")?;
    let byte = |v: f64| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    let (mut colors, mut heights, mut normals) = (vec![], vec![], vec![]);
    for j in 0..SIZE {
        for i in 0..SIZE {
            let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
            colors.extend(color(x, y).map(byte));
            let h = byte(height(x, y));
            heights.extend([h, h, h]);
            // Slopes per texel across the wrapping tile; up the picture is −y.
            let dx = (height(x + 1.0, y) - height(x - 1.0, y)) * 0.5 * TEXELS_PER_HEIGHT;
            let dy = (height(x, y + 1.0) - height(x, y - 1.0)) * 0.5 * TEXELS_PER_HEIGHT;
            let (nx, ny, nz) = (-dx, dy, 1.0);
            let length = (nx * nx + ny * ny + nz * nz).sqrt();
            normals.extend([nx, ny, nz].map(|c| byte(0.5 + 0.5 * c / length)));
        }
    }
    save(&format!("{stem}_color.png"), colors)?;
    save(&format!("{stem}_height.png"), heights)?;
    save(&format!("{stem}_normal.png"), normals)
}
