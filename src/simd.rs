//! SIMD lanes for the hot tests: four lanes (`four.rs`) for the four-triangle test, eight
//! (`eight.rs`) for the wide BVH's box test and for two groups of triangles at once, each in
//! every encoding computing bit for bit what the same scalar operations compute. `lanes.rs`
//! names the operations the triangle test needs in any width (`Lanes`).

mod eight;
mod four;
mod lanes;

#[cfg(target_arch = "x86_64")]
pub use eight::Avx;
pub use eight::{Halves, Lanes8};
pub use four::F32x4;
pub use lanes::{Four, Lanes};

/// Values whose lane operations are easy to get wrong (signed zeros, infinities, NaN, the
/// smallest normal), for the tests that compare encodings.
#[cfg(test)]
const SPECIAL: [f32; 8] = [
    0.0,
    -0.0,
    1.5,
    -2.25,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::NAN,
    f32::MIN_POSITIVE,
];
