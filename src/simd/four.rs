//! Four f32 lanes for the four-triangle test (and, two at a time, the wide BVH's box test:
//! `eight.rs`): SSE2 on x86-64 (part of the baseline, so no `target-cpu` flag), plain arrays
//! elsewhere with the same results. Every lane operation is one IEEE operation, rounded as
//! the scalar one is, so a lane computes bit for bit what scalar code with the same
//! operations in the same order computes.
//!
//! `max_or`/`min_or` fix what happens to NaN, which the slab test relies on: a NaN in `self`
//! yields `other`. SSE2's `maxps`/`minps` do exactly that; glam's `Vec4::max` leaves it to the
//! platform (NEON propagates NaN), hence this small type.

// SAFETY (every `unsafe` below): these SSE/SSE2 intrinsics only require their target
// feature, which every x86-64 processor has.
#[cfg(target_arch = "x86_64")]
mod lanes {
    use std::arch::x86_64::*;

    #[derive(Clone, Copy, Debug)]
    #[repr(transparent)]
    pub struct F32x4(__m128);

    impl F32x4 {
        /// The register, for the eight-lane engines that join two.
        #[inline(always)]
        pub fn m128(self) -> __m128 {
            self.0
        }

        #[inline(always)]
        pub fn splat(v: f32) -> Self {
            Self(unsafe { _mm_set1_ps(v) })
        }

        #[inline(always)]
        pub const fn from_array(a: [f32; 4]) -> Self {
            // SAFETY: __m128 is four f32 lanes, lane 0 first in memory.
            Self(unsafe { std::mem::transmute::<[f32; 4], __m128>(a) })
        }

        #[inline(always)]
        pub fn to_array(self) -> [f32; 4] {
            let mut out = [0.0; 4];
            // SAFETY: `out` is 16 writable bytes; the unaligned store has no other demand.
            unsafe { _mm_storeu_ps(out.as_mut_ptr(), self.0) };
            out
        }

        /// Lane `i & 3`, read where the lanes lie in memory (not through a register).
        #[inline(always)]
        pub fn lane(&self, i: usize) -> f32 {
            // SAFETY: an __m128 is four f32 lanes, lane 0 first in memory (`from_array`), and
            // `i & 3` is one of them.
            unsafe { *(self as *const Self).cast::<f32>().add(i & 3) }
        }

        /// Per lane `if self > other { self } else { other }`.
        #[inline(always)]
        pub fn max_or(self, other: Self) -> Self {
            Self(unsafe { _mm_max_ps(self.0, other.0) })
        }

        /// Per lane `if self < other { self } else { other }`.
        #[inline(always)]
        pub fn min_or(self, other: Self) -> Self {
            Self(unsafe { _mm_min_ps(self.0, other.0) })
        }

        /// Bit i set where lane i of `self` ≤ lane i of `other`.
        #[inline(always)]
        pub fn le_mask(self, other: Self) -> u32 {
            unsafe { _mm_movemask_ps(_mm_cmple_ps(self.0, other.0)) as u32 }
        }

        /// Bit i set where lane i of `self` < lane i of `other`.
        #[inline(always)]
        pub fn lt_mask(self, other: Self) -> u32 {
            unsafe { _mm_movemask_ps(_mm_cmplt_ps(self.0, other.0)) as u32 }
        }

        /// Bit i set where lane i of `self` == lane i of `other`.
        #[inline(always)]
        pub fn eq_mask(self, other: Self) -> u32 {
            unsafe { _mm_movemask_ps(_mm_cmpeq_ps(self.0, other.0)) as u32 }
        }

        /// Bit i set where lane i is NaN.
        #[inline(always)]
        pub fn nan_mask(self) -> u32 {
            unsafe { _mm_movemask_ps(_mm_cmpunord_ps(self.0, self.0)) as u32 }
        }

        /// Each lane's magnitude (its sign bit cleared).
        #[inline(always)]
        pub fn abs(self) -> Self {
            Self(unsafe { _mm_andnot_ps(_mm_set1_ps(-0.0), self.0) })
        }
    }

    impl std::ops::Add for F32x4 {
        type Output = Self;
        #[inline(always)]
        fn add(self, o: Self) -> Self {
            Self(unsafe { _mm_add_ps(self.0, o.0) })
        }
    }

    impl std::ops::Sub for F32x4 {
        type Output = Self;
        #[inline(always)]
        fn sub(self, o: Self) -> Self {
            Self(unsafe { _mm_sub_ps(self.0, o.0) })
        }
    }

    impl std::ops::Mul for F32x4 {
        type Output = Self;
        #[inline(always)]
        fn mul(self, o: Self) -> Self {
            Self(unsafe { _mm_mul_ps(self.0, o.0) })
        }
    }

    impl std::ops::Div for F32x4 {
        type Output = Self;
        #[inline(always)]
        fn div(self, o: Self) -> Self {
            Self(unsafe { _mm_div_ps(self.0, o.0) })
        }
    }
}

#[cfg(not(target_arch = "x86_64"))]
mod lanes {
    pub use crate::simd::four::portable::F32x4;
}

pub use lanes::F32x4;

/// The plain-array lanes: used where SSE2 is not available, and compiled everywhere so the
/// tests can check that both give the same answers.
#[cfg_attr(target_arch = "x86_64", allow(dead_code))]
mod portable {
    #[derive(Clone, Copy, Debug)]
    pub struct F32x4([f32; 4]);

    impl F32x4 {
        #[inline(always)]
        pub fn splat(v: f32) -> Self {
            Self([v; 4])
        }

        #[inline(always)]
        pub const fn from_array(a: [f32; 4]) -> Self {
            Self(a)
        }

        #[inline(always)]
        pub fn to_array(self) -> [f32; 4] {
            self.0
        }

        #[inline(always)]
        pub fn lane(&self, i: usize) -> f32 {
            self.0[i & 3]
        }

        #[inline(always)]
        fn zip(self, o: Self, f: impl Fn(f32, f32) -> f32) -> Self {
            Self(std::array::from_fn(|i| f(self.0[i], o.0[i])))
        }

        #[inline(always)]
        pub fn max_or(self, other: Self) -> Self {
            self.zip(other, |a, b| if a > b { a } else { b })
        }

        #[inline(always)]
        pub fn min_or(self, other: Self) -> Self {
            self.zip(other, |a, b| if a < b { a } else { b })
        }

        #[inline(always)]
        fn mask(self, o: Self, f: impl Fn(f32, f32) -> bool) -> u32 {
            (0..4).fold(0, |m, i| m | ((f(self.0[i], o.0[i]) as u32) << i))
        }

        #[inline(always)]
        pub fn le_mask(self, other: Self) -> u32 {
            self.mask(other, |a, b| a <= b)
        }

        #[inline(always)]
        pub fn lt_mask(self, other: Self) -> u32 {
            self.mask(other, |a, b| a < b)
        }

        #[inline(always)]
        pub fn eq_mask(self, other: Self) -> u32 {
            self.mask(other, |a, b| a == b)
        }

        #[inline(always)]
        pub fn nan_mask(self) -> u32 {
            self.mask(self, |a, _| a.is_nan())
        }

        #[inline(always)]
        pub fn abs(self) -> Self {
            Self(self.0.map(f32::abs))
        }
    }

    impl std::ops::Add for F32x4 {
        type Output = Self;
        #[inline(always)]
        fn add(self, o: Self) -> Self {
            self.zip(o, |a, b| a + b)
        }
    }

    impl std::ops::Sub for F32x4 {
        type Output = Self;
        #[inline(always)]
        fn sub(self, o: Self) -> Self {
            self.zip(o, |a, b| a - b)
        }
    }

    impl std::ops::Mul for F32x4 {
        type Output = Self;
        #[inline(always)]
        fn mul(self, o: Self) -> Self {
            self.zip(o, |a, b| a * b)
        }
    }

    impl std::ops::Div for F32x4 {
        type Output = Self;
        #[inline(always)]
        fn div(self, o: Self) -> Self {
            self.zip(o, |a, b| a / b)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{F32x4, portable};
    use crate::simd::SPECIAL;

    fn same(a: [f32; 4], b: [f32; 4]) -> bool {
        a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
    }

    /// Every operation gives bit-identical lanes in both implementations, NaN and signed
    /// zeros included.
    #[test]
    fn native_and_portable_lanes_agree() {
        for i in 0..SPECIAL.len() {
            for j in 0..SPECIAL.len() {
                let a = [
                    SPECIAL[i],
                    SPECIAL[j],
                    SPECIAL[(i + j) % 8],
                    SPECIAL[(i * 3 + j) % 8],
                ];
                let b = [
                    SPECIAL[j],
                    SPECIAL[i],
                    SPECIAL[(i + 5) % 8],
                    SPECIAL[(j + 3) % 8],
                ];
                let (na, nb) = (F32x4::from_array(a), F32x4::from_array(b));
                let (pa, pb) = (
                    portable::F32x4::from_array(a),
                    portable::F32x4::from_array(b),
                );
                assert!(same(na.max_or(nb).to_array(), pa.max_or(pb).to_array()));
                assert!(same(na.min_or(nb).to_array(), pa.min_or(pb).to_array()));
                assert_eq!(na.le_mask(nb), pa.le_mask(pb));
                assert_eq!(na.lt_mask(nb), pa.lt_mask(pb));
                assert_eq!(na.eq_mask(nb), pa.eq_mask(pb));
                assert_eq!(na.nan_mask(), pa.nan_mask());
                assert!(same(na.abs().to_array(), pa.abs().to_array()));
                let native = [na + nb, na - nb, na * nb, na / nb].map(F32x4::to_array);
                let plain = [pa + pb, pa - pb, pa * pb, pa / pb].map(portable::F32x4::to_array);
                for (n, p) in native.iter().zip(&plain) {
                    for k in 0..4 {
                        // NaN payloads may differ; NaN-ness may not.
                        assert_eq!(n[k].is_nan(), p[k].is_nan());
                        if !n[k].is_nan() {
                            assert_eq!(n[k].to_bits(), p[k].to_bits());
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn nan_in_self_yields_other() {
        let nan = F32x4::splat(f32::NAN);
        let one = F32x4::splat(1.0);
        assert_eq!(nan.max_or(one).to_array(), [1.0; 4]);
        assert_eq!(nan.min_or(one).to_array(), [1.0; 4]);
        assert_eq!(
            F32x4::from_array([1.0, 3.0, 2.0, 0.0]).le_mask(F32x4::splat(2.0)),
            0b1101
        );
    }
}
