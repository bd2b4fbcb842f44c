//! Where subsample k of a pixel lies. One function serves the one-shot render, the
//! progressive viewer and the bench, so that every path traces exactly the same rays.

/// How subsamples sit inside their grid cells.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SampleLayout {
    /// Each subsample at a hashed random position inside its own cell of the N×N grid:
    /// stratified, different for every pixel, so no regular aliasing pattern survives.
    #[default]
    Stratified,
    /// Each subsample at the centre of its cell, as the seed's 2×2 supersampling does.
    Grid,
}

/// The N×N subsample pattern for anti-aliasing level N.
#[derive(Clone, Debug, PartialEq)]
pub struct Sampler {
    n: u32,
    layout: SampleLayout,
    /// Cell (column, row) of subsample k, ordered so that every prefix is spread evenly
    /// over the pixel: the progressive image improves evenly pass by pass.
    order: Vec<(u32, u32)>,
}

impl Sampler {
    /// Level `n` must be at least 1.
    pub fn new(n: u32, layout: SampleLayout) -> Self {
        assert!(n >= 1, "anti-aliasing level must be at least 1");
        Self {
            n,
            layout,
            order: if n.is_power_of_two() {
                sobol_order(n)
            } else {
                farthest_point_order(n)
            },
        }
    }

    /// The anti-aliasing level N.
    pub fn level(&self) -> u32 {
        self.n
    }

    /// Where the subsamples lie in their cells.
    pub fn layout(&self) -> SampleLayout {
        self.layout
    }

    /// N²: the number of subsamples a converged pixel holds.
    pub fn samples_per_pixel(&self) -> u32 {
        self.n * self.n
    }

    /// The position of subsample `k` inside pixel (x, y), in [0, 1)². Past N² subsamples
    /// the grid's cells are visited again in the same order, at new random places in them.
    #[inline]
    pub fn offset(&self, x: u32, y: u32, k: u32) -> (f32, f32) {
        self.row(y, k).offset(x)
    }

    /// Subsample `k` of the pixels of row `y`: what depends only on the row and `k` is
    /// hashed once, not once per pixel.
    #[inline]
    pub fn row(&self, y: u32, k: u32) -> RowSampler<'_> {
        RowSampler {
            sampler: self,
            shift_seed: hash(y ^ 0x5bd1_e995),
            jitter_seed: hash(y ^ hash(k)),
            cell: self.order[(k % (self.n * self.n)) as usize],
        }
    }
}

/// `Sampler::row`: subsample k of every pixel of one row.
#[derive(Clone, Copy, Debug)]
pub struct RowSampler<'a> {
    sampler: &'a Sampler,
    shift_seed: u32,
    jitter_seed: u32,
    /// Cell (column, row) of subsample k before the pixel's own shift.
    cell: (u32, u32),
}

impl RowSampler<'_> {
    /// The position of this row's subsample inside pixel `x`, in [0, 1)².
    #[inline]
    pub fn offset(&self, x: u32) -> (f32, f32) {
        // Each pixel walks the same order, moved by its own hashed shift, so that a part-way
        // image is unbiased noise rather than the whole picture shifted by a fraction of a
        // pixel. For power-of-two N the shift is digital (cell bits XOR a random number):
        // it maps every box of the sampler's stratification onto another, so prefixes stay
        // stratified. Otherwise it is a rotation on the torus in whole cells
        // (Cranley–Patterson), which keeps the farthest-point spacing.
        let n = self.sampler.n;
        let shift = hash(x.wrapping_mul(0x9e37_79b1) ^ self.shift_seed);
        let (cx, cy) = self.cell;
        // 16 hash bits per axis mapped onto 0..n by a multiply and a shift (Lemire's
        // reduction); `shift % n` costs an integer division, as much as the rest of this.
        let (sx, sy) = (((shift & 0xffff) * n) >> 16, ((shift >> 16) * n) >> 16);
        let (cx, cy) = if n.is_power_of_two() {
            (cx ^ sx, cy ^ sy)
        } else {
            let wrap = |c: u32| if c >= n { c - n } else { c };
            (wrap(cx + sx), wrap(cy + sy))
        };
        let inv = 1.0 / n as f32;
        let (jx, jy) = match self.sampler.layout {
            SampleLayout::Grid => (0.5, 0.5),
            SampleLayout::Stratified => {
                let h = hash(x ^ self.jitter_seed);
                (unit(h), unit(hash(h)))
            }
        };
        ((cx as f32 + jx) * inv, (cy as f32 + jy) * inv)
    }
}

/// The random numbers one subsample draws beyond its place in the pixel (a point on the
/// lens, on an area light, in a glossy lobe), one 2-D dimension after another.
///
/// Dimension d of subsample k of a pixel is point k' of the Sobol (0, 2)-sequence, where k'
/// is k with its low 16 bits shuffled by a nested uniform scramble seeded by a hash of the
/// pixel and d (Burley 2020), and the point is then digitally shifted by another such hash.
/// The scramble flips each bit of the index by a hash of the bits above it, so it maps
/// every aligned block of 2^j indices (j ≤ 16) onto another, and each such block of the
/// sequence is a (0, j, 2)-net: every power-of-two prefix of a pixel's subsamples is
/// stratified in each dimension. Within a block the order changes from block to block, so
/// that no dimension pairs with another, or with the pixel's own cell (which k's low bits
/// choose), the same way twice: a plain XOR of the index would pair them for good, and
/// leave each pixel of a penumbra with a bias of its own that no number of samples removes.
#[derive(Clone, Copy, Debug)]
pub struct SampleStream {
    pixel: u32,
    index: u32,
    dimension: u32,
}

impl SampleStream {
    /// The stream of subsample `k` of pixel (x, y). Costs nothing until a number is drawn.
    #[inline]
    pub fn new(x: u32, y: u32, k: u32) -> Self {
        Self {
            pixel: x.wrapping_mul(0x9e37_79b1) ^ y.wrapping_mul(0x85eb_ca77),
            index: k,
            dimension: 0,
        }
    }

    /// The next dimension's point, in [0, 1)².
    // Not inlined: inlined into a loop that draws only for some lights (the Whitted light
    // loop), the compiler hoisted its per-subsample part out and ran it for every hit.
    #[inline(never)]
    pub fn next_2d(&mut self) -> (f32, f32) {
        let seed = hash(self.pixel ^ hash(self.dimension.wrapping_add(0x2545_f491)));
        self.dimension += 1;
        let shuffled = nested_uniform_scramble(self.index, seed);
        let (x, y) = sobol_point((shuffled & 0xffff) | (self.index & !0xffff));
        let (sx, sy) = (hash(seed), hash(seed ^ 0x68e3_1da4));
        (unit(x ^ sx), unit(y ^ sy))
    }
}

/// The point of the disc of `radius` about `center`, facing along unit `normal`, that
/// sample `u` (in [0, 1)²) stands for: stratified samples stay stratified over the disc.
#[inline]
pub fn disc_point(
    center: glam::Vec3A,
    normal: glam::Vec3,
    radius: f32,
    u: (f32, f32),
) -> glam::Vec3A {
    let (t, b) = crate::numerics::orthonormal_basis(normal);
    let (dx, dy) = concentric_disc(u);
    center + (glam::Vec3A::from(t) * dx + glam::Vec3A::from(b) * dy) * radius
}

/// Shirley and Chiu's concentric map of the unit square onto the unit disc: it keeps areas
/// and keeps nearby points nearby, so a stratified square stays stratified on the disc.
#[inline]
pub fn concentric_disc((u, v): (f32, f32)) -> (f32, f32) {
    let (a, b) = (2.0 * u - 1.0, 2.0 * v - 1.0);
    if a == 0.0 && b == 0.0 {
        return (0.0, 0.0);
    }
    let quarter = std::f32::consts::FRAC_PI_4;
    let (r, phi) = if a.abs() > b.abs() {
        (a, quarter * (b / a))
    } else {
        (b, 2.0 * quarter - quarter * (a / b))
    };
    let (s, c) = phi.sin_cos();
    (r * c, r * s)
}

/// Point `i` of the Sobol (0, 2)-sequence, as 32-bit fractions.
#[inline]
fn sobol_point(i: u32) -> (u32, u32) {
    let x = i.reverse_bits(); // van der Corput: the sequence's first dimension
    // The second dimension XORs one direction number per set bit of i: four byte-table
    // lookups in place of a loop over the bits (every path draws several points per bounce).
    let [b0, b1, b2, b3] = i.to_le_bytes();
    let t = &SOBOL_SECOND;
    let y = t[0][b0 as usize] ^ t[1][b1 as usize] ^ t[2][b2 as usize] ^ t[3][b3 as usize];
    (x, y)
}

/// For each byte k of an index and each value of it, the XOR of the second Sobol dimension's
/// direction numbers v(8k) … v(8k + 7) its set bits select: v(0) = 2³¹, v(j + 1) = v(j) ^
/// (v(j) >> 1).
const SOBOL_SECOND: [[u32; 256]; 4] = {
    let mut directions = [0u32; 32];
    let mut v = 1u32 << 31;
    let mut j = 0;
    while j < 32 {
        directions[j] = v;
        v ^= v >> 1;
        j += 1;
    }
    let mut table = [[0u32; 256]; 4];
    let mut k = 0;
    while k < 4 {
        let mut value = 0;
        while value < 256 {
            let mut y = 0u32;
            let mut bit = 0;
            while bit < 8 {
                if value & (1 << bit) != 0 {
                    y ^= directions[8 * k + bit];
                }
                bit += 1;
            }
            table[k][value] = y;
            value += 1;
        }
        k += 1;
    }
    table
};

/// For N a power of two: the cells in the order of the first N² points of the Sobol
/// (0, 2)-sequence, which visits each cell once. Every prefix of 2^k subsamples then has
/// one subsample in each of the 2^k equal boxes of any shape 2^-a × 2^-b (a + b = k) that are
/// no finer than a cell: stratified for edges of every orientation at every power of two.
/// The first half of a power-of-two prefix is such a prefix too, which the adaptive
/// sampler's error estimate relies on (accumulator.rs).
fn sobol_order(n: u32) -> Vec<(u32, u32)> {
    let bits = n.trailing_zeros();
    (0..n * n)
        .map(|i| {
            let (x, y) = sobol_point(i);
            if bits == 0 {
                (0, 0)
            } else {
                (x >> (32 - bits), y >> (32 - bits))
            }
        })
        .collect()
}

/// For other N: a greedy farthest-point order of the cells of the N×N grid, on the torus
/// (neighbouring pixels continue the pattern): each next cell is the one farthest from all
/// chosen ones, ties broken by the lowest index so the order is fixed.
fn farthest_point_order(n: u32) -> Vec<(u32, u32)> {
    let cells: Vec<(u32, u32)> = (0..n * n).map(|i| (i % n, i / n)).collect();
    let torus = |a: (u32, u32), b: (u32, u32)| {
        let dx = a.0.abs_diff(b.0).min(n - a.0.abs_diff(b.0));
        let dy = a.1.abs_diff(b.1).min(n - a.1.abs_diff(b.1));
        dx * dx + dy * dy
    };
    let mut order = Vec::with_capacity(cells.len());
    let mut nearest = vec![u32::MAX; cells.len()];
    let mut chosen = vec![false; cells.len()];
    let mut next = ((n / 2) * n + n / 2) as usize;
    for _ in 0..cells.len() {
        chosen[next] = true;
        order.push(cells[next]);
        for (i, &c) in cells.iter().enumerate() {
            nearest[i] = nearest[i].min(torus(c, cells[next]));
        }
        next = (0..cells.len())
            .filter(|&i| !chosen[i])
            .max_by(|&a, &b| nearest[a].cmp(&nearest[b]).then(b.cmp(&a)))
            .unwrap_or(0);
    }
    order
}

/// A 32-bit integer hash with good avalanche ("lowbias32", C. Wellons).
#[inline]
fn hash(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^= x >> 16;
    x
}

/// A nested uniform (Owen) scramble of `i` seeded by `seed`: each bit flipped by a hash of
/// the bits above it. It is Laine and Karras's hash-based permutation, in which each bit
/// depends on the bits below it, applied to the bits reversed.
#[inline]
fn nested_uniform_scramble(i: u32, seed: u32) -> u32 {
    let mut x = i.reverse_bits().wrapping_add(seed);
    x ^= x.wrapping_mul(0x6c50_b47c);
    x ^= x.wrapping_mul(0xb82f_1e52);
    x ^= x.wrapping_mul(0xc7af_e638);
    x ^= x.wrapping_mul(0x8d22_f6e6);
    x.reverse_bits()
}

/// The top 24 bits of `h` as a float in [0, 1).
#[inline]
fn unit(h: u32) -> f32 {
    (h >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_cell_exactly_once() {
        for n in 1..=8 {
            let s = Sampler::new(n, SampleLayout::Stratified);
            let mut seen = vec![false; (n * n) as usize];
            for k in 0..n * n {
                let (x, y) = s.offset(17, 42, k);
                assert!((0.0..1.0).contains(&x) && (0.0..1.0).contains(&y));
                let cell = ((y * n as f32) as u32 * n + (x * n as f32) as u32) as usize;
                assert!(!seen[cell], "n={n}: cell {cell} twice");
                seen[cell] = true;
            }
        }
    }

    #[test]
    fn grid_layout_uses_cell_centres() {
        let s = Sampler::new(2, SampleLayout::Grid);
        let mut offsets: Vec<(f32, f32)> = (0..4).map(|k| s.offset(3, 4, k)).collect();
        offsets.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(
            offsets,
            vec![(0.25, 0.25), (0.25, 0.75), (0.75, 0.25), (0.75, 0.75)]
        );
    }

    #[test]
    fn second_subsample_is_far_from_the_first_in_every_pixel() {
        let s = Sampler::new(4, SampleLayout::Grid);
        let d = |a: f32, b: f32| (a - b).abs().min(1.0 - (a - b).abs());
        let mut firsts = std::collections::HashSet::new();
        for (px, py) in [(0, 0), (1, 0), (0, 1), (17, 5), (640, 480)] {
            let (x0, y0) = s.offset(px, py, 0);
            let (x1, y1) = s.offset(px, py, 1);
            assert!(d(x0, x1) >= 0.5 && d(y0, y1) >= 0.5, "pixel ({px}, {py})");
            firsts.insert(((x0 * 4.0) as u32, (y0 * 4.0) as u32));
        }
        assert!(firsts.len() > 1, "pixels start in different cells");
    }

    /// For power-of-two N, every prefix of 2^k subsamples puts exactly one subsample in each
    /// box 2^-a × 2^-b (a + b = k) no finer than a cell, in every pixel (whatever its rotation).
    #[test]
    fn power_of_two_prefixes_are_stratified_in_every_box_shape() {
        for n in [2u32, 4, 8] {
            let bits = n.trailing_zeros();
            let s = Sampler::new(n, SampleLayout::Stratified);
            for (px, py) in [(0, 0), (3, 9), (100, 7), (641, 333)] {
                for k in 0..=2 * bits {
                    let points: Vec<(f32, f32)> =
                        (0..1u32 << k).map(|i| s.offset(px, py, i)).collect();
                    for a in k.saturating_sub(bits)..=k.min(bits) {
                        let b = k - a;
                        let mut boxes = vec![0u32; 1 << k];
                        for &(x, y) in &points {
                            let (bx, by) =
                                ((x * (1 << a) as f32) as u32, (y * (1 << b) as f32) as u32);
                            boxes[((by << a) + bx) as usize] += 1;
                        }
                        assert!(
                            boxes.iter().all(|&c| c == 1),
                            "n {n}, pixel ({px}, {py}), prefix {}, boxes 1/{} × 1/{}",
                            1 << k,
                            1 << a,
                            1 << b
                        );
                    }
                }
            }
        }
    }

    /// Every power-of-two prefix of a pixel's draws in one dimension has one point in each
    /// of the 2^k boxes of every shape 2^-a × 2^-b; other pixels and dimensions differ.
    #[test]
    fn stream_prefixes_are_stratified_and_decorrelated() {
        for (px, py) in [(0, 0), (5, 3), (1023, 777)] {
            for dim in 0..3 {
                let draw = |k: u32| {
                    let mut s = SampleStream::new(px, py, k);
                    for _ in 0..dim {
                        s.next_2d();
                    }
                    s.next_2d()
                };
                for k in [0u32, 3, 6, 8] {
                    let points: Vec<(f32, f32)> = (0..1u32 << k).map(draw).collect();
                    for a in 0..=k {
                        let b = k - a;
                        let mut boxes = vec![0u32; 1 << k];
                        for &(x, y) in &points {
                            assert!((0.0..1.0).contains(&x) && (0.0..1.0).contains(&y));
                            let (bx, by) =
                                ((x * (1 << a) as f32) as u32, (y * (1 << b) as f32) as u32);
                            boxes[((by << a) + bx) as usize] += 1;
                        }
                        assert!(
                            boxes.iter().all(|&c| c == 1),
                            "pixel ({px}, {py}) dim {dim} 2^{k}"
                        );
                    }
                }
            }
        }
        let first = |x, y, dims: u32| {
            let mut s = SampleStream::new(x, y, 0);
            (0..dims).map(|_| s.next_2d()).last().unwrap()
        };
        assert_ne!(first(1, 2, 1), first(2, 1, 1));
        assert_ne!(first(1, 2, 1), first(1, 2, 2));
        // The first draws of neighbouring pixels look like uncorrelated noise: their mean
        // over a 64×64 block is near 1/2 and its correlation between dimensions near 0.
        let (mut sum, mut cross) = (0.0f64, 0.0f64);
        for y in 0..64 {
            for x in 0..64 {
                let mut s = SampleStream::new(x, y, 0);
                let (a, _) = s.next_2d();
                let (b, _) = s.next_2d();
                sum += a as f64;
                cross += (a as f64 - 0.5) * (b as f64 - 0.5);
            }
        }
        let n = 4096.0;
        assert!((sum / n - 0.5).abs() < 0.02, "mean {}", sum / n);
        assert!((cross / n).abs() < 0.01, "covariance {}", cross / n);
        // Within one pixel, a dimension's quarter of [0, 1) does not follow k's low bits
        // (which choose the pixel's cell at 2×2 anti-aliasing): over 4,096 subsamples each
        // of the 16 pairings occurs, about equally often.
        let mut pairs = [0u32; 16];
        for k in 0..4096u32 {
            let (x, _) = SampleStream::new(7, 9, k).next_2d();
            pairs[((k % 4) * 4 + (x * 4.0) as u32) as usize] += 1;
        }
        assert!(pairs.iter().all(|&c| (200..312).contains(&c)), "{pairs:?}");
    }

    /// The byte tables give the second dimension exactly as the loop over the index's bits
    /// that defines it.
    #[test]
    fn sobol_tables_equal_the_bit_loop() {
        let by_loop = |i: u32| {
            let mut y = 0u32;
            let (mut v, mut j) = (1u32 << 31, i);
            while j != 0 {
                if j & 1 != 0 {
                    y ^= v;
                }
                j >>= 1;
                v ^= v >> 1;
            }
            y
        };
        let mut h = 1u32;
        for i in (0..70_000u32).chain((0..10_000).map(|_| {
            h = hash(h);
            h
        })) {
            assert_eq!(sobol_point(i).1, by_loop(i), "index {i}");
        }
    }

    #[test]
    fn concentric_map_keeps_area_and_stays_in_the_disc() {
        // Equal areas of the square go to equal areas of the disc: the share of a 64×64
        // grid of cell centres within radius r is r².
        let mut inside_half = 0;
        for i in 0..64 {
            for j in 0..64 {
                let (x, y) = concentric_disc(((i as f32 + 0.5) / 64.0, (j as f32 + 0.5) / 64.0));
                let r2 = x * x + y * y;
                assert!(r2 <= 1.0 + 1e-6);
                inside_half += (r2 < 0.25) as u32;
            }
        }
        let share = inside_half as f32 / 4096.0;
        assert!((share - 0.25).abs() < 0.01, "{share}");
    }

    #[test]
    fn past_the_grid_cells_repeat_with_new_jitter() {
        let s = Sampler::new(2, SampleLayout::Stratified);
        for k in 0..4 {
            let (a, b) = (s.offset(7, 9, k), s.offset(7, 9, k + 4));
            assert_eq!(
                ((a.0 * 2.0) as u32, (a.1 * 2.0) as u32),
                ((b.0 * 2.0) as u32, (b.1 * 2.0) as u32)
            );
            assert_ne!(a, b);
        }
    }

    #[test]
    fn positions_are_deterministic_and_vary_by_pixel() {
        let s = Sampler::new(3, SampleLayout::Stratified);
        assert_eq!(s.offset(5, 6, 2), s.offset(5, 6, 2));
        assert_ne!(s.offset(5, 6, 2), s.offset(6, 5, 2));
    }
}
