//! Where a ray stands in its sample's tree, and what the rays a hit spawns may spend.

/// A straight pass through a clear surface does not bend the ray, so it cannot start a
/// cycle and does not count towards the bounce limit; this many in a row end the path.
pub const MAX_STRAIGHT_CROSSINGS: u32 = 64;

/// What a ray has spent and what it may still spend.
#[derive(Clone, Copy, Debug)]
pub struct Path {
    /// Bounces (reflections, refractions) so far.
    pub depth: u32,
    /// Straight crossings in a row since the last bounce.
    pub straight: u32,
    /// What this ray's colour is multiplied by on its way to the pixel.
    pub weight: f32,
    /// How many more secondary rays this ray's subtree may spawn (limits::RAY_BUDGET for
    /// the whole tree). Every ray spends one, so the recursion is at most this deep.
    pub budget: u32,
}

impl Path {
    /// A camera ray's.
    pub const PRIMARY: Path = Path {
        depth: 0,
        straight: 0,
        weight: 1.0,
        budget: crate::limits::RAY_BUDGET,
    };

    /// The path of a ray that bounces (reflects or refracts) off this one's hit, carrying
    /// `fraction` of its light, with `budget` rays to spend.
    pub fn bounce(self, fraction: f32, budget: u32) -> Path {
        Path {
            depth: self.depth + 1,
            straight: 0,
            weight: self.weight * fraction,
            budget,
        }
    }

    /// The path of this ray going on straight through a clear surface.
    pub fn straight_on(self, fraction: f32, budget: u32) -> Path {
        Path {
            depth: self.depth,
            straight: self.straight + 1,
            weight: self.weight * fraction,
            budget,
        }
    }
}
