//! Where a ray stands in its sample's tree, what the rays a hit spawns may spend, and the
//! media it travels through.

use crate::limits::MAX_NESTED_MEDIA;

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

/// The transparent objects a ray is inside, innermost last: it travels in the innermost,
/// and returns to the one around it on leaving. Empty is air (or vacuum): index 1, no
/// absorption, and fog.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Media {
    objects: [u32; MAX_NESTED_MEDIA],
    len: u8,
}

impl Media {
    /// Air: inside nothing.
    pub const AIR: Media = Media {
        objects: [0; MAX_NESTED_MEDIA],
        len: 0,
    };

    /// The object the ray travels inside, if any.
    #[inline]
    pub fn current(&self) -> Option<u32> {
        self.len.checked_sub(1).map(|i| self.objects[i as usize])
    }

    /// The medium a ray in these media is in after leaving `object`.
    #[inline]
    pub fn outside(&self, object: u32) -> Option<u32> {
        match self.current() {
            Some(top) if top == object => self.len.checked_sub(2).map(|i| self.objects[i as usize]),
            top => top,
        }
    }

    /// These media after entering `object` (unchanged when already as deep as can be kept).
    #[inline]
    pub fn entered(mut self, object: u32) -> Media {
        if (self.len as usize) < MAX_NESTED_MEDIA {
            self.objects[self.len as usize] = object;
            self.len += 1;
        }
        self
    }

    /// These media after leaving `object` (unchanged when the ray was not known to be in it).
    #[inline]
    pub fn left(mut self, object: u32) -> Media {
        let len = self.len as usize;
        if let Some(i) = self.objects[..len].iter().rposition(|&o| o == object) {
            self.objects.copy_within(i + 1..len, i);
            self.objects[len - 1] = 0;
            self.len -= 1;
        }
        self
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn media_nest_and_unnest_in_any_order() {
        let air = Media::AIR;
        assert_eq!(air.current(), None);
        let glass = air.entered(3);
        let water = glass.entered(7);
        assert_eq!(water.current(), Some(7));
        assert_eq!(
            water.outside(7),
            Some(3),
            "leaving the water returns to the glass"
        );
        assert_eq!(
            water.outside(3),
            Some(7),
            "leaving the glass first keeps the water"
        );
        assert_eq!(water.left(7), glass);
        assert_eq!(water.left(3).current(), Some(7));
        assert_eq!(water.left(3).left(7), air);
        assert_eq!(
            air.left(5),
            air,
            "leaving what it was not in changes nothing"
        );
        assert_eq!(air.outside(5), None);
        let mut deep = air;
        for o in 0..10 {
            deep = deep.entered(o);
        }
        assert_eq!(deep.current(), Some(MAX_NESTED_MEDIA as u32 - 1));
    }
}
