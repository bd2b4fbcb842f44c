//! Marsaglia's xorshift32 (shifts 13, 17, 5): a small deterministic generator for made-up
//! data in tests and in benchmark scenes. Not for sampling an image: the sampler's
//! sequences (sampler.rs) are chosen for that.

/// The generator's state, never 0 (which it would never leave).
#[derive(Clone, Debug)]
pub struct XorShift32(u32);

impl XorShift32 {
    /// Starts from `seed` (from 1 for a seed of 0).
    pub fn new(seed: u32) -> Self {
        Self(seed.max(1))
    }

    /// The next 32 bits.
    pub fn next_u32(&mut self) -> u32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 17;
        self.0 ^= self.0 << 5;
        self.0
    }

    /// The next number in [0, 1].
    pub fn next_f32(&mut self) -> f32 {
        self.next_u32() as f32 / u32::MAX as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first outputs from 1 are Marsaglia's; a zero seed does not stick at zero.
    #[test]
    fn follows_the_published_sequence() {
        let mut rng = XorShift32::new(1);
        let first: Vec<u32> = (0..3).map(|_| rng.next_u32()).collect();
        assert_eq!(first, [270369, 67634689, 2647435461]);
        assert_eq!(XorShift32::new(0).next_u32(), 270369);
        let mut rng = XorShift32::new(7);
        assert!(
            (0..1000)
                .map(|_| rng.next_f32())
                .all(|x| (0.0..=1.0).contains(&x))
        );
    }
}
