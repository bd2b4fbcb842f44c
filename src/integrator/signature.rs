//! The signature of a sample: a hash of what its ray tree met, which the adaptive sampler
//! compares between neighbouring subsamples to find edges (render/progressive.rs).

/// Records, in order, what one primary ray's tree meets: each surface (primitive, and part
/// of a cylinder), whether each light was blocked, each procedural pattern cell, and each
/// miss. Two samples of a pixel with different signatures straddle an edge, however alike
/// their colours.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Signature(u32);

impl Signature {
    /// The hash so far.
    #[inline]
    pub fn value(self) -> u32 {
        self.0
    }

    /// A hit on part `part` of primitive `primitive`.
    #[inline]
    pub fn surface(&mut self, primitive: u32, part: u32) {
        self.mix(primitive ^ (part << 24));
    }

    /// A shadow ray that brought back `visible` of its light: blocked, clear, or through
    /// transparent surfaces.
    #[inline]
    pub fn shadow(&mut self, visible: glam::Vec3A) {
        let class = if visible == glam::Vec3A::ZERO {
            0
        } else if visible == glam::Vec3A::ONE {
            1
        } else {
            2
        };
        self.mix(class);
    }

    /// A procedural pattern's colour, which names its cell (an image varies within cells
    /// instead, and is not recorded).
    #[inline]
    pub fn pattern(&mut self, color: glam::Vec3A) {
        self.mix(color.x.to_bits() ^ color.z.to_bits());
    }

    /// A ray that left the scene.
    #[inline]
    pub fn miss(&mut self) {
        self.mix(u32::MAX);
    }

    /// Folds `value` into the hash (order matters: a reflection of A seen in B differs
    /// from one of B seen in A).
    #[inline]
    fn mix(&mut self, value: u32) {
        self.0 = (self.0 ^ value).wrapping_mul(0x9e37_79b1).rotate_left(15);
    }
}
