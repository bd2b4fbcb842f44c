//! Writes the starry sky of assets/scenes/earth_and_sun.toml: a latitude-longitude image of
//! stars spread evenly over the sphere, a few bright and most faint, from a fixed seed (the
//! same file every run).
//!
//! `cargo run --release --example starfield -- assets/stars_2048x1024.png`

use std::f64::consts::PI;

const WIDTH: u32 = 2048;
const HEIGHT: u32 = 1024;
const STARS: usize = 9000;

/// A small fixed-seed generator (SplitMix64): no dependency, the same sky everywhere.
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args().nth(1).ok_or("usage: starfield OUT.png")?;
    let mut sky = vec![[0f32; 3]; (WIDTH * HEIGHT) as usize];
    let mut rng = SplitMix(363);
    for _ in 0..STARS {
        // Even over the sphere: uniform in longitude and in sin(latitude).
        let longitude = rng.next() * 2.0 * PI;
        let latitude = (rng.next() * 2.0 - 1.0).asin();
        let x = longitude / (2.0 * PI) * WIDTH as f64;
        let y = (0.5 - latitude / PI) * HEIGHT as f64;
        // Most stars faint, a few bright; warm or cool by chance.
        let brightness = (0.08 + 0.92 * rng.next().powi(8)) as f32;
        let warmth = rng.next() as f32 - 0.5;
        let tint = [1.0 + 0.25 * warmth, 1.0, 1.0 - 0.25 * warmth];
        // Wider near the poles, where a pixel of the map covers less of the sky.
        let stretch = 1.0 / latitude.cos().max(0.05);
        let radius = 0.6 + 1.2 * brightness as f64;
        let (rx, ry) = ((radius * stretch).ceil() as i64, radius.ceil() as i64);
        for dy in -ry..=ry {
            for dx in -rx..=rx {
                let px = (x.floor() as i64 + dx).rem_euclid(WIDTH as i64);
                let py = y.floor() as i64 + dy;
                if !(0..HEIGHT as i64).contains(&py) {
                    continue;
                }
                let fx = (px as f64 + 0.5 - x) / stretch;
                let fy = py as f64 + 0.5 - y;
                let fall = (-(fx * fx + fy * fy) / (radius * radius * 0.5)).exp() as f32;
                let pixel = &mut sky[(py as u32 * WIDTH + px as u32) as usize];
                for c in 0..3 {
                    pixel[c] += brightness * tint[c] * fall;
                }
            }
        }
    }
    let bytes: Vec<u8> = sky
        .iter()
        .flat_map(|p| p.map(|c| (c.min(1.0) * 255.0).round() as u8))
        .collect();
    image::RgbImage::from_raw(WIDTH, HEIGHT, bytes)
        .ok_or("image size")?
        .save(&out)?;
    println!("wrote {out} ({WIDTH}×{HEIGHT}, {STARS} stars)");
    Ok(())
}
