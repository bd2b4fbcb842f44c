//! Procedural (solid) patterns, POV-Ray's kind: a value from 0 to 1 at each object-local
//! position (from the object's origin, turned and scaled back by its placement), from
//! gradient noise (Perlin's improved noise, 2002) summed over octaves, looked up in a colour
//! map. A pattern is a function of the point alone: the same
//! at any thread count, and the same image at any scale when its `scale` scales with the
//! scene.

use glam::{Vec3, Vec3A};

/// The most stops a colour map may have.
pub const MAX_COLOR_STOPS: usize = 16;

/// The most octaves of noise a pattern sums.
pub const MAX_OCTAVES: u32 = 10;

/// The most turbulence a pattern takes (in units of its scale).
pub const MAX_TURBULENCE: f32 = 16.0;

/// What the value at a point measures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PatternKind {
    /// Gradient noise summed over octaves (POV-Ray's `bozo`/`noise`).
    Noise,
    /// Bands across x, bent by turbulence.
    Marble,
    /// Rings about the y axis (a trunk standing up), bent by turbulence.
    Wood,
    /// Turbulence at four times the frequency (POV-Ray's `granite`).
    Granite,
    /// Fine bands along y, bent strongly by turbulence.
    Agate,
    /// The distance to the nearest of one random point per unit cell (Worley's cells).
    Cells,
    /// A ramp along a unit direction, repeating every unit.
    Gradient {
        /// The unit direction of the ramp.
        direction: Vec3,
    },
}

impl PatternKind {
    /// The kinds' names in the scene file, in the order above.
    pub const NAMES: [&'static str; 7] = [
        "noise", "marble", "wood", "granite", "agate", "cells", "gradient",
    ];

    /// Its name in the scene file.
    pub fn name(&self) -> &'static str {
        let i = match self {
            PatternKind::Noise => 0,
            PatternKind::Marble => 1,
            PatternKind::Wood => 2,
            PatternKind::Granite => 3,
            PatternKind::Agate => 4,
            PatternKind::Cells => 5,
            PatternKind::Gradient { .. } => 6,
        };
        Self::NAMES[i]
    }

    /// The kind named `name`, a gradient along `direction`; None for no such name.
    pub fn named(name: &str, direction: Vec3) -> Option<PatternKind> {
        Some(match name {
            "noise" => PatternKind::Noise,
            "marble" => PatternKind::Marble,
            "wood" => PatternKind::Wood,
            "granite" => PatternKind::Granite,
            "agate" => PatternKind::Agate,
            "cells" => PatternKind::Cells,
            "gradient" => PatternKind::Gradient { direction },
            _ => return None,
        })
    }
}

/// Colours at values from 0 to 1, blended linearly between stops.
#[derive(Clone, Debug, PartialEq)]
pub struct ColorMap {
    /// (value, colour), values in 0..=1 and not decreasing; two or more.
    stops: Vec<(f32, Vec3)>,
}

impl ColorMap {
    /// The map through `stops`, or why they are not one: 2 to `MAX_COLOR_STOPS` stops at
    /// values from 0 to 1, in order (two at one value make a sharp edge).
    pub fn new(stops: Vec<(f32, Vec3)>) -> Result<Self, String> {
        if !(2..=MAX_COLOR_STOPS).contains(&stops.len()) {
            return Err(format!(
                "a colour map has 2 to {MAX_COLOR_STOPS} stops, got {}",
                stops.len()
            ));
        }
        for (i, &(at, _)) in stops.iter().enumerate() {
            if !(0.0..=1.0).contains(&at) {
                return Err(format!("stop {i}: `at` must lie in 0..=1, got {at}"));
            }
            if i > 0 && at < stops[i - 1].0 {
                return Err(format!(
                    "stop {i}: `at` {at} comes before the stop before it ({})",
                    stops[i - 1].0
                ));
            }
        }
        Ok(Self { stops })
    }

    /// Black at 0 to white at 1.
    pub fn grey() -> Self {
        Self {
            stops: vec![(0.0, Vec3::ZERO), (1.0, Vec3::ONE)],
        }
    }

    /// The colour at `value`: the first stop's below it, the last's above.
    #[inline]
    pub fn at(&self, value: f32) -> Vec3A {
        let stops = &self.stops;
        let i = stops.partition_point(|&(at, _)| at <= value);
        if i == 0 {
            return stops[0].1.into();
        }
        if i == stops.len() {
            return stops[i - 1].1.into();
        }
        let (a, ca) = stops[i - 1];
        let (b, cb) = stops[i];
        let u = (value - a) / (b - a);
        Vec3A::from(ca) + (Vec3A::from(cb) - Vec3A::from(ca)) * u
    }

    /// The mean colour over values spread evenly from 0 to 1.
    pub fn mean(&self) -> Vec3 {
        let n = 256;
        (0..n)
            .map(|i| Vec3::from(self.at((i as f32 + 0.5) / n as f32)))
            .sum::<Vec3>()
            / n as f32
    }
}

/// A procedural pattern and its colours.
#[derive(Clone, Debug, PartialEq)]
pub struct Pattern {
    /// What it measures.
    pub kind: PatternKind,
    /// The size of its features, in scene units.
    pub scale: f32,
    /// How far turbulence moves the lookup, in units of `scale`.
    pub turbulence: f32,
    /// Octaves of noise summed (1 to `MAX_OCTAVES`).
    pub octaves: u32,
    /// The colours of its values.
    pub map: ColorMap,
}

impl Pattern {
    /// The colour at `local`, a position relative to the object's origin.
    #[inline]
    pub fn eval(&self, local: Vec3A) -> Vec3A {
        self.map.at(self.value(local / self.scale))
    }

    /// The pattern's value at `p` (in units of its scale), from 0 to 1.
    pub fn value(&self, p: Vec3A) -> f32 {
        let v = match self.kind {
            PatternKind::Noise => {
                let q = p + self.turbulence * turbulence_vector(p, self.octaves);
                // Summed octaves rarely stray past ±0.5: stretched to fill 0..1.
                0.5 + fbm(q, self.octaves)
            }
            PatternKind::Marble => {
                triangle_wave(p.x + self.turbulence * turbulence(p, self.octaves))
            }
            PatternKind::Wood => {
                let r = (p.x * p.x + p.z * p.z).sqrt();
                triangle_wave(r + self.turbulence * turbulence(p, self.octaves))
            }
            PatternKind::Granite => 1.5 * turbulence(p * 4.0, self.octaves),
            PatternKind::Agate => {
                let t = p.y + 4.0 * self.turbulence * turbulence(p, self.octaves);
                0.5 + 0.5 * (std::f32::consts::TAU * t).sin()
            }
            PatternKind::Cells => cells(p + self.turbulence * turbulence_vector(p, self.octaves)),
            PatternKind::Gradient { direction } => {
                let t = p.dot(direction.into()) + self.turbulence * turbulence(p, self.octaves);
                t - t.floor()
            }
        };
        // NaN (from a point too far for f32) takes the map's first colour.
        if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) }
    }

    /// How fast the brightness of its colour (the mean of red, green and blue) changes at
    /// `local` (relative to the object's origin), per scene unit along each axis: central
    /// differences, a step well inside the finest octave's features but not below the
    /// point's own rounding. The colour map shapes a bump map's height as it does colour.
    pub fn brightness_gradient(&self, local: Vec3A) -> Vec3A {
        let p = local / self.scale;
        // An eighth of the finest octave's wavelength, 2^−(octaves − 1), which granite
        // makes four times finer still.
        let finest = 0.5f32.powi(self.octaves as i32 + 4);
        let step = finest.max(p.abs().max_element() * (1.0 / 4096.0)).min(0.05);
        let brightness = |p: Vec3A| {
            let c = self.map.at(self.value(p));
            (c.x + c.y + c.z) * (1.0 / 3.0)
        };
        let slope = |axis: Vec3A| {
            (brightness(p + axis * step) - brightness(p - axis * step)) / (2.0 * step)
        };
        Vec3A::new(slope(Vec3A::X), slope(Vec3A::Y), slope(Vec3A::Z)) / self.scale
    }

    /// The same pattern in a scene scaled by `factor`.
    pub fn scaled(&self, factor: f32) -> Pattern {
        Pattern {
            scale: self.scale * factor,
            ..self.clone()
        }
    }
}

/// 0 at whole numbers, 1 halfway between, linear in between.
#[inline]
fn triangle_wave(t: f32) -> f32 {
    let f = t - t.floor();
    1.0 - (2.0 * f - 1.0).abs()
}

/// Noise summed over `octaves`, each twice the frequency and half the weight of the one
/// before, divided by the sum of the weights: about −1 to 1.
fn fbm(p: Vec3A, octaves: u32) -> f32 {
    let (mut sum, mut weight, mut total, mut q) = (0.0, 1.0, 0.0, p);
    for _ in 0..octaves {
        sum += weight * noise(q);
        total += weight;
        weight *= 0.5;
        q *= 2.0;
    }
    sum / total
}

/// |noise| summed as `fbm` sums noise: 0 to about 1.
fn turbulence(p: Vec3A, octaves: u32) -> f32 {
    let (mut sum, mut weight, mut total, mut q) = (0.0, 1.0, 0.0, p);
    for _ in 0..octaves {
        sum += weight * noise(q).abs();
        total += weight;
        weight *= 0.5;
        q *= 2.0;
    }
    sum / total
}

/// Three independent turbulent offsets (noise at shifted points), for patterns that are
/// moved by turbulence in every direction.
fn turbulence_vector(p: Vec3A, octaves: u32) -> Vec3A {
    const SHIFT: [Vec3A; 3] = [
        Vec3A::new(31.4, 17.7, 5.3),
        Vec3A::new(-11.2, 43.9, 27.1),
        Vec3A::new(7.6, -23.5, 51.8),
    ];
    Vec3A::new(
        fbm(p + SHIFT[0], octaves),
        fbm(p + SHIFT[1], octaves),
        fbm(p + SHIFT[2], octaves),
    )
}

/// The permutation of 0..256 the noise hashes lattice points with: fixed, so every run
/// and every machine draws the same pattern (a shuffle by a fixed linear congruential
/// sequence).
const PERMUTATION: [u8; 256] = {
    let mut p = [0u8; 256];
    let mut i = 0;
    while i < 256 {
        p[i] = i as u8;
        i += 1;
    }
    let mut state: u32 = 0x2545_f491;
    let mut i = 255;
    while i > 0 {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        let j = ((state >> 8) as usize) % (i + 1);
        let t = p[i];
        p[i] = p[j];
        p[j] = t;
        i -= 1;
    }
    p
};

#[inline]
fn hash(i: i32) -> usize {
    PERMUTATION[(i & 255) as usize] as usize
}

/// The lattice point (x, y, z)'s hash, 0..256.
#[inline]
fn hash3(x: i32, y: i32, z: i32) -> usize {
    hash(hash(hash(x) as i32 + y) as i32 + z)
}

/// The dot product of `(x, y, z)` with one of the twelve edge directions of a cube,
/// chosen by `h` (Perlin 2002).
#[inline]
fn grad(h: usize, x: f32, y: f32, z: f32) -> f32 {
    let h = h & 15;
    let u = if h < 8 { x } else { y };
    let v = if h < 4 {
        y
    } else if h == 12 || h == 14 {
        x
    } else {
        z
    };
    (if h & 1 == 0 { u } else { -u }) + (if h & 2 == 0 { v } else { -v })
}

#[inline]
fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

fn lerp(t: f32, a: f32, b: f32) -> f32 {
    a + t * (b - a)
}

/// Perlin's improved gradient noise at `p`: 0 at every lattice point, smooth, about −1 to 1.
pub fn noise(p: Vec3A) -> f32 {
    let cell = p.floor();
    let (xi, yi, zi) = (cell.x as i32, cell.y as i32, cell.z as i32);
    let f = p - cell;
    let (u, v, w) = (fade(f.x), fade(f.y), fade(f.z));
    let corner = |dx: i32, dy: i32, dz: i32| {
        grad(
            hash3(xi + dx, yi + dy, zi + dz),
            f.x - dx as f32,
            f.y - dy as f32,
            f.z - dz as f32,
        )
    };
    lerp(
        w,
        lerp(
            v,
            lerp(u, corner(0, 0, 0), corner(1, 0, 0)),
            lerp(u, corner(0, 1, 0), corner(1, 1, 0)),
        ),
        lerp(
            v,
            lerp(u, corner(0, 0, 1), corner(1, 0, 1)),
            lerp(u, corner(0, 1, 1), corner(1, 1, 1)),
        ),
    )
}

/// The feature point of the unit cell at (x, y, z): a fixed pseudo-random point inside it.
fn feature_point(x: i32, y: i32, z: i32) -> Vec3A {
    let h = hash3(x, y, z);
    let a = hash(h as i32 + 1);
    let b = hash(a as i32 + 2);
    let c = hash(b as i32 + 3);
    Vec3A::new(x as f32, y as f32, z as f32)
        + Vec3A::new(a as f32, b as f32, c as f32) * (1.0 / 256.0)
        + Vec3A::splat(0.5 / 256.0)
}

/// The distance from `p` to the nearest feature point (of its cell and the 26 around it).
fn cells(p: Vec3A) -> f32 {
    let cell = p.floor();
    let (xi, yi, zi) = (cell.x as i32, cell.y as i32, cell.z as i32);
    let mut nearest = f32::INFINITY;
    for dz in -1..=1 {
        for dy in -1..=1 {
            for dx in -1..=1 {
                let d = feature_point(xi + dx, yi + dy, zi + dz).distance_squared(p);
                nearest = nearest.min(d);
            }
        }
    }
    nearest.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points spread over a region, from a fixed sequence.
    fn points(n: usize, extent: f32) -> Vec<Vec3A> {
        let mut state = 12345u32;
        let mut next = || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f32 / (1u32 << 24) as f32
        };
        (0..n)
            .map(|_| (Vec3A::new(next(), next(), next()) * 2.0 - 1.0) * extent)
            .collect()
    }

    #[test]
    fn noise_is_zero_on_the_lattice_bounded_and_smooth() {
        for p in [
            Vec3A::ZERO,
            Vec3A::new(3.0, -7.0, 12.0),
            Vec3A::splat(-100.0),
        ] {
            assert_eq!(noise(p), 0.0);
        }
        let mut low = f32::INFINITY;
        let mut high = f32::NEG_INFINITY;
        for p in points(20_000, 40.0) {
            let n = noise(p);
            low = low.min(n);
            high = high.max(n);
            // A step of 1e-3 moves it by at most its largest slope (under 3) times 1e-3.
            let m = noise(p + Vec3A::new(1e-3, -1e-3, 1e-3));
            assert!((n - m).abs() < 6e-3, "{p}: {n} then {m}");
        }
        assert!(
            low > -1.1 && high < 1.1 && low < -0.5 && high > 0.5,
            "{low} {high}"
        );
        // Not periodic at the scale of a feature: it differs one cell over.
        assert_ne!(noise(Vec3A::splat(0.3)), noise(Vec3A::new(1.3, 0.3, 0.3)));
    }

    fn pattern(kind: PatternKind, turbulence: f32) -> Pattern {
        Pattern {
            kind,
            scale: 1.0,
            turbulence,
            octaves: 6,
            map: ColorMap::grey(),
        }
    }

    #[test]
    fn every_pattern_lies_in_0_to_1_and_varies() {
        for kind in [
            PatternKind::Noise,
            PatternKind::Marble,
            PatternKind::Wood,
            PatternKind::Granite,
            PatternKind::Agate,
            PatternKind::Cells,
            PatternKind::Gradient {
                direction: Vec3::new(0.6, 0.8, 0.0),
            },
        ] {
            let p = pattern(kind, 1.0);
            let values: Vec<f32> = points(4000, 10.0).into_iter().map(|x| p.value(x)).collect();
            assert!(values.iter().all(|v| (0.0..=1.0).contains(v)), "{kind:?}");
            let (low, high) = values
                .iter()
                .fold((1.0f32, 0.0f32), |(l, h), &v| (l.min(v), h.max(v)));
            assert!(high - low > 0.5, "{kind:?} spans only {low}..{high}");
            // A point far beyond f32's reach gives a colour, not NaN.
            assert!(p.eval(Vec3A::splat(f32::MAX)).is_finite(), "{kind:?}");
        }
    }

    #[test]
    fn without_turbulence_the_bands_rings_and_ramps_are_exact() {
        let marble = pattern(PatternKind::Marble, 0.0);
        assert_eq!(marble.value(Vec3A::new(0.25, 5.0, -3.0)), 0.5);
        assert_eq!(marble.value(Vec3A::new(2.5, 0.0, 0.0)), 1.0);
        let wood = pattern(PatternKind::Wood, 0.0);
        assert_eq!(wood.value(Vec3A::new(3.0, 7.0, 4.0)), 0.0); // r = 5
        assert_eq!(wood.value(Vec3A::new(0.0, -2.0, 1.5)), 1.0); // r = 1.5
        let ramp = pattern(PatternKind::Gradient { direction: Vec3::Y }, 0.0);
        assert_eq!(ramp.value(Vec3A::new(9.0, 2.25, -1.0)), 0.25);
        // A feature point is its own nearest.
        let cells = pattern(PatternKind::Cells, 0.0);
        assert_eq!(cells.value(feature_point(4, -2, 7)), 0.0);
    }

    #[test]
    fn a_pattern_scaled_with_its_points_is_the_same() {
        let p = Pattern {
            scale: 0.7,
            ..pattern(PatternKind::Marble, 1.3)
        };
        for x in points(200, 5.0) {
            let a = p.eval(x);
            let b = p.scaled(1024.0).eval(x * 1024.0);
            assert!((a - b).abs().max_element() < 1e-4, "{x}: {a} against {b}");
        }
    }

    #[test]
    fn every_kind_is_named_as_the_file_names_it() {
        for name in PatternKind::NAMES {
            assert_eq!(PatternKind::named(name, Vec3::X).unwrap().name(), name);
        }
        assert_eq!(PatternKind::named("marbel", Vec3::X), None);
    }

    #[test]
    fn a_colour_map_blends_between_its_stops() {
        let map = ColorMap::new(vec![
            (0.2, Vec3::X),
            (0.6, Vec3::Y),
            (0.6, Vec3::Z),
            (1.0, Vec3::ONE),
        ])
        .unwrap();
        let near = |a: Vec3A, b: Vec3A| (a - b).abs().max_element() < 1e-6;
        assert_eq!(map.at(0.0), Vec3A::X);
        assert_eq!(map.at(0.2), Vec3A::X);
        assert!(near(map.at(0.4), Vec3A::new(0.5, 0.5, 0.0)));
        assert_eq!(
            map.at(0.6),
            Vec3A::Z,
            "two stops at one value: a sharp edge"
        );
        assert!(near(map.at(0.8), Vec3A::new(0.5, 0.5, 1.0)));
        assert_eq!(map.at(1.0), Vec3A::ONE);
        // The mean of black to white is mid-grey.
        assert!(
            (ColorMap::grey().mean() - Vec3::splat(0.5))
                .abs()
                .max_element()
                < 1e-6
        );
        for bad in [
            vec![(0.0, Vec3::X)],
            vec![(0.5, Vec3::X), (0.4, Vec3::Y)],
            vec![(0.0, Vec3::X), (1.5, Vec3::Y)],
            vec![(f32::NAN, Vec3::X), (1.0, Vec3::Y)],
            vec![(0.5, Vec3::X); MAX_COLOR_STOPS + 1],
        ] {
            assert!(ColorMap::new(bad.clone()).is_err(), "{bad:?}");
        }
    }
}
