//! The lane operations that the triangle test needs, in any width: four lanes (`Four`,
//! one group of triangles) or eight (`Halves` and `Avx` of `eight.rs`, two groups at once).
//! One generic test then serves every width, and each lane runs the same IEEE operations.

use super::four::F32x4;

/// Lane operations, on the vectors of an engine (`Self`, a proof of the instruction set its
/// vectors need). Every one acts lane by lane as the scalar operation does.
pub trait Lanes: Copy {
    type V: Copy;
    /// The lanes as an array.
    type Array: Copy + std::ops::Index<usize, Output = f32>;
    fn splat(self, v: f32) -> Self::V;
    fn to_array(self, v: Self::V) -> Self::Array;
    fn add(self, a: Self::V, b: Self::V) -> Self::V;
    fn sub(self, a: Self::V, b: Self::V) -> Self::V;
    fn mul(self, a: Self::V, b: Self::V) -> Self::V;
    fn div(self, a: Self::V, b: Self::V) -> Self::V;
    /// Each lane with its sign bit cleared.
    fn abs(self, a: Self::V) -> Self::V;
    /// Per lane `if a > b { a } else { b }` (a NaN in `a` yields `b`, as `F32x4::max_or`).
    fn max_or(self, a: Self::V, b: Self::V) -> Self::V;
    /// Bit i set where lane i of `a` ≤ lane i of `b` (false where either is NaN).
    fn le_mask(self, a: Self::V, b: Self::V) -> u32;
    /// Bit i set where lane i of `a` < lane i of `b` (false where either is NaN).
    fn lt_mask(self, a: Self::V, b: Self::V) -> u32;
    /// Bit i set where lane i of `a` = lane i of `b` (false where either is NaN).
    fn eq_mask(self, a: Self::V, b: Self::V) -> u32;
    /// Bit i set where lane i of `a` is NaN.
    fn nan_mask(self, a: Self::V) -> u32;
}

/// Four lanes as one `F32x4`: SSE2 on x86-64, on every processor.
#[derive(Clone, Copy, Debug, Default)]
pub struct Four;

impl Lanes for Four {
    type V = F32x4;
    type Array = [f32; 4];

    #[inline(always)]
    fn splat(self, v: f32) -> F32x4 {
        F32x4::splat(v)
    }

    #[inline(always)]
    fn to_array(self, v: F32x4) -> [f32; 4] {
        v.to_array()
    }

    #[inline(always)]
    fn add(self, a: F32x4, b: F32x4) -> F32x4 {
        a + b
    }

    #[inline(always)]
    fn sub(self, a: F32x4, b: F32x4) -> F32x4 {
        a - b
    }

    #[inline(always)]
    fn mul(self, a: F32x4, b: F32x4) -> F32x4 {
        a * b
    }

    #[inline(always)]
    fn div(self, a: F32x4, b: F32x4) -> F32x4 {
        a / b
    }

    #[inline(always)]
    fn abs(self, a: F32x4) -> F32x4 {
        a.abs()
    }

    #[inline(always)]
    fn max_or(self, a: F32x4, b: F32x4) -> F32x4 {
        a.max_or(b)
    }

    #[inline(always)]
    fn le_mask(self, a: F32x4, b: F32x4) -> u32 {
        a.le_mask(b)
    }

    #[inline(always)]
    fn lt_mask(self, a: F32x4, b: F32x4) -> u32 {
        a.lt_mask(b)
    }

    #[inline(always)]
    fn eq_mask(self, a: F32x4, b: F32x4) -> u32 {
        a.eq_mask(b)
    }

    #[inline(always)]
    fn nan_mask(self, a: F32x4) -> u32 {
        a.nan_mask()
    }
}
