//! Eight f32 lanes for the wide BVH's box test and for a mesh leaf's two groups of
//! triangles at once (`GroupPair`), in one of two encodings chosen at run time
//! (`isa.rs`): two four-lane halves (`Halves`, SSE2 on x86-64, plain arrays elsewhere) on
//! any processor, or one AVX register (`Avx`) where the processor has AVX2. Both run, lane
//! by lane, the same IEEE operations as `F32x4`, so a test finds bit for bit the same
//! distances and masks in either: the choice changes the speed, never the image.
//!
//! The lanes are operated on through an engine value (`Lanes8`) rather than methods on the
//! vector: `Avx` can only be had from `Avx::new`, which checks the processor, so holding
//! one is the proof that its instructions may run.

use super::four::F32x4;
use super::lanes::Lanes;

/// Eight lanes' operations (`Lanes`, whose arrays are eight long), and what the box test
/// and the pairs of triangle groups need beyond them. `Self` is the engine (a proof of the
/// instruction set), `Self::V` its vector.
pub trait Lanes8: Lanes<Array = [f32; 8]> {
    fn load(self, a: &[f32; 8]) -> Self::V;
    /// Per lane `if a < b { a } else { b }`.
    fn min_or(self, a: Self::V, b: Self::V) -> Self::V;
    /// Lanes 0..4 from `lo`, 4..8 from `hi`.
    fn join(self, lo: F32x4, hi: F32x4) -> Self::V;
}

/// Eight lanes as two `F32x4`: the baseline, on every processor.
#[derive(Clone, Copy, Debug, Default)]
pub struct Halves;

impl Lanes for Halves {
    type V = [F32x4; 2];
    type Array = [f32; 8];

    #[inline(always)]
    fn splat(self, v: f32) -> Self::V {
        [F32x4::splat(v); 2]
    }

    #[inline(always)]
    fn to_array(self, v: Self::V) -> [f32; 8] {
        let (lo, hi) = (v[0].to_array(), v[1].to_array());
        [lo[0], lo[1], lo[2], lo[3], hi[0], hi[1], hi[2], hi[3]]
    }

    #[inline(always)]
    fn sub(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0] - b[0], a[1] - b[1]]
    }

    #[inline(always)]
    fn mul(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0] * b[0], a[1] * b[1]]
    }

    #[inline(always)]
    fn max_or(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0].max_or(b[0]), a[1].max_or(b[1])]
    }

    #[inline(always)]
    fn le_mask(self, a: Self::V, b: Self::V) -> u32 {
        a[0].le_mask(b[0]) | (a[1].le_mask(b[1]) << 4)
    }

    #[inline(always)]
    fn add(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0] + b[0], a[1] + b[1]]
    }

    #[inline(always)]
    fn div(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0] / b[0], a[1] / b[1]]
    }

    #[inline(always)]
    fn abs(self, a: Self::V) -> Self::V {
        [a[0].abs(), a[1].abs()]
    }

    #[inline(always)]
    fn lt_mask(self, a: Self::V, b: Self::V) -> u32 {
        a[0].lt_mask(b[0]) | (a[1].lt_mask(b[1]) << 4)
    }

    #[inline(always)]
    fn eq_mask(self, a: Self::V, b: Self::V) -> u32 {
        a[0].eq_mask(b[0]) | (a[1].eq_mask(b[1]) << 4)
    }

    #[inline(always)]
    fn nan_mask(self, a: Self::V) -> u32 {
        a[0].nan_mask() | (a[1].nan_mask() << 4)
    }
}

impl Lanes8 for Halves {
    #[inline(always)]
    fn load(self, a: &[f32; 8]) -> Self::V {
        [
            F32x4::from_array([a[0], a[1], a[2], a[3]]),
            F32x4::from_array([a[4], a[5], a[6], a[7]]),
        ]
    }

    #[inline(always)]
    fn min_or(self, a: Self::V, b: Self::V) -> Self::V {
        [a[0].min_or(b[0]), a[1].min_or(b[1])]
    }

    #[inline(always)]
    fn join(self, lo: F32x4, hi: F32x4) -> Self::V {
        [lo, hi]
    }
}

#[cfg(target_arch = "x86_64")]
pub use avx::Avx;

#[cfg(target_arch = "x86_64")]
mod avx {
    use crate::simd::eight::Lanes8;
    use crate::simd::four::F32x4;
    use crate::simd::lanes::Lanes;
    use std::arch::x86_64::*;

    /// Eight lanes in one AVX register. Only `new` makes one, and only on a processor with
    /// AVX2, so every method may use AVX instructions. They are fast only where they are
    /// inlined into a function compiled for AVX2 (`#[target_feature(enable = "avx2")]`).
    #[derive(Clone, Copy, Debug)]
    pub struct Avx(());

    impl Avx {
        /// The engine, where this processor has AVX2.
        pub fn new() -> Option<Avx> {
            std::arch::is_x86_feature_detected!("avx2").then_some(Avx(()))
        }
    }

    // SAFETY (every `unsafe` below): an `Avx` exists only where the processor has AVX2,
    // which includes AVX, all these intrinsics require; the loads and stores name 32
    // readable or writable bytes and are unaligned.
    impl Lanes for Avx {
        type V = __m256;
        type Array = [f32; 8];

        #[inline(always)]
        fn splat(self, v: f32) -> Self::V {
            unsafe { _mm256_set1_ps(v) }
        }

        #[inline(always)]
        fn to_array(self, v: Self::V) -> [f32; 8] {
            let mut out = [0.0; 8];
            unsafe { _mm256_storeu_ps(out.as_mut_ptr(), v) };
            out
        }

        #[inline(always)]
        fn sub(self, a: Self::V, b: Self::V) -> Self::V {
            unsafe { _mm256_sub_ps(a, b) }
        }

        #[inline(always)]
        fn mul(self, a: Self::V, b: Self::V) -> Self::V {
            unsafe { _mm256_mul_ps(a, b) }
        }

        // vmaxps/vminps return the second operand where either is NaN, as maxps/minps.
        #[inline(always)]
        fn max_or(self, a: Self::V, b: Self::V) -> Self::V {
            unsafe { _mm256_max_ps(a, b) }
        }

        // Ordered and signalling-free, as SSE's cmpleps: false where either is NaN.
        #[inline(always)]
        fn le_mask(self, a: Self::V, b: Self::V) -> u32 {
            unsafe { _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(a, b)) as u32 }
        }

        #[inline(always)]
        fn add(self, a: Self::V, b: Self::V) -> Self::V {
            unsafe { _mm256_add_ps(a, b) }
        }

        #[inline(always)]
        fn div(self, a: Self::V, b: Self::V) -> Self::V {
            unsafe { _mm256_div_ps(a, b) }
        }

        #[inline(always)]
        fn abs(self, a: Self::V) -> Self::V {
            unsafe { _mm256_andnot_ps(_mm256_set1_ps(-0.0), a) }
        }

        // As SSE's cmpltps, cmpeqps and cmpunordps: ordered comparisons false on NaN.
        #[inline(always)]
        fn lt_mask(self, a: Self::V, b: Self::V) -> u32 {
            unsafe { _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LT_OQ>(a, b)) as u32 }
        }

        #[inline(always)]
        fn eq_mask(self, a: Self::V, b: Self::V) -> u32 {
            unsafe { _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_EQ_OQ>(a, b)) as u32 }
        }

        #[inline(always)]
        fn nan_mask(self, a: Self::V) -> u32 {
            unsafe { _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_UNORD_Q>(a, a)) as u32 }
        }
    }

    impl Lanes8 for Avx {
        #[inline(always)]
        fn load(self, a: &[f32; 8]) -> Self::V {
            unsafe { _mm256_loadu_ps(a.as_ptr()) }
        }

        #[inline(always)]
        fn min_or(self, a: Self::V, b: Self::V) -> Self::V {
            unsafe { _mm256_min_ps(a, b) }
        }

        #[inline(always)]
        fn join(self, lo: F32x4, hi: F32x4) -> Self::V {
            unsafe { _mm256_set_m128(hi.m128(), lo.m128()) }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simd::SPECIAL;

    /// The lanes of one engine's operations on `a` and `b`, as bits (NaN-ness kept, NaN
    /// payloads ignored), and its comparison mask.
    fn results<L: Lanes8>(l: L, a: [f32; 8], b: [f32; 8]) -> (Vec<Option<u32>>, u32) {
        let (va, vb) = (l.load(&a), l.load(&b));
        let half =
            |x: &[f32; 8], k: usize| F32x4::from_array(std::array::from_fn(|i| x[4 * k + i]));
        let lanes = [
            l.sub(va, vb),
            l.mul(va, vb),
            l.max_or(va, vb),
            l.min_or(va, vb),
            l.splat(a[3]),
            l.add(va, vb),
            l.div(va, vb),
            l.abs(va),
            l.join(half(&b, 1), half(&a, 0)),
        ]
        .into_iter()
        .flat_map(|v| l.to_array(v))
        .map(|x| (!x.is_nan()).then_some(x.to_bits()))
        .collect();
        let masks = l.le_mask(va, vb)
            | l.lt_mask(va, vb) << 8
            | l.eq_mask(va, vb) << 16
            | l.nan_mask(va) << 24;
        (lanes, masks)
    }

    /// The AVX engine computes every lane bit for bit as the two halves do, NaN, infinities
    /// and signed zeros included (on a processor without AVX2 there is nothing to compare).
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn avx_lanes_agree_with_the_halves() {
        let Some(avx) = Avx::new() else {
            eprintln!("no AVX2 on this processor: only the halves run here");
            return;
        };
        for i in 0..8 {
            for j in 0..8 {
                let a = std::array::from_fn(|k| SPECIAL[(i + k) % 8]);
                let b = std::array::from_fn(|k| SPECIAL[(j * 3 + k * 5) % 8]);
                assert_eq!(results(avx, a, b), results(Halves, a, b), "{a:?} {b:?}");
            }
        }
    }

    #[test]
    fn halves_keep_lane_order_and_the_nan_rule() {
        let a: [f32; 8] = std::array::from_fn(|k| k as f32);
        let b = [3.0, f32::NAN, 3.0, 3.0, 3.0, 3.0, 9.0, 0.0];
        assert_eq!(Halves.to_array(Halves.load(&a)), a);
        // Lanes 0..=3 hold 0..=3 ≤ 3 except lane 1, against NaN; lane 6 holds 6 ≤ 9.
        assert_eq!(
            Halves.le_mask(Halves.load(&a), Halves.load(&b)),
            0b0100_1101
        );
        let nan = Halves.splat(f32::NAN);
        assert_eq!(Halves.to_array(Halves.max_or(nan, Halves.load(&a))), a);
        assert_eq!(Halves.to_array(Halves.min_or(nan, Halves.load(&a))), a);
    }
}
