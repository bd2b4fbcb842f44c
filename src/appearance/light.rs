//! Light sources: what kind of light, how bright, and how it falls off.

use glam::Vec3;

/// A light: its kind and where it shines from, and its colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// Where the light comes from.
    pub kind: LightKind,
    /// Its intensity per channel. A point light without falloff lights a surface facing it
    /// with this at any distance (as the seed's does); with inverse-square falloff, with
    /// this times `intensity / distance²`.
    pub color: Vec3,
}

/// The kinds of light (a closed set).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind {
    /// Light from one point, in every direction.
    Point {
        /// Where the light is, relative to the scene's origin.
        position: Vec3,
        /// How it fades with distance.
        falloff: Falloff,
    },
    /// Parallel light from infinitely far away, like the sun's.
    Directional {
        /// The unit direction the light travels in (from the sky towards the scene).
        direction: Vec3,
    },
}

/// How a point light's light fades with distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Falloff {
    /// It does not: the seed's lights, and Whitted's.
    None,
    /// As physical light does: `intensity / distance²` times the light's colour.
    InverseSquare {
        /// The colour's multiplier at a distance of one scene unit.
        intensity: f32,
    },
}

/// The most an inverse-square light may multiply its colour by, however near a surface
/// comes to it: keeps every product finite where a surface touches the light.
pub const MAX_FALLOFF_GAIN: f32 = 1.0e20;

impl Falloff {
    /// What the light's colour is multiplied by at `distance`.
    #[inline]
    pub fn gain(&self, distance: f32) -> f32 {
        match *self {
            Falloff::None => 1.0,
            Falloff::InverseSquare { intensity } => {
                (intensity / (distance * distance)).min(MAX_FALLOFF_GAIN)
            }
        }
    }
}

impl Light {
    /// A point light at `position` of colour `color`, without falloff.
    pub fn point(position: Vec3, color: Vec3) -> Light {
        Light {
            kind: LightKind::Point {
                position,
                falloff: Falloff::None,
            },
            color,
        }
    }

    /// A point light's position; None for a directional light.
    pub fn position(&self) -> Option<Vec3> {
        match self.kind {
            LightKind::Point { position, .. } => Some(position),
            LightKind::Directional { .. } => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_square_falls_off_with_the_square_and_stays_finite_at_the_light() {
        let f = Falloff::InverseSquare { intensity: 50.0 };
        assert_eq!(f.gain(1.0), 50.0);
        assert_eq!(f.gain(5.0), 2.0);
        assert_eq!(f.gain(10.0), 0.5);
        assert_eq!(f.gain(0.0), MAX_FALLOFF_GAIN);
        assert_eq!(Falloff::None.gain(1e6), 1.0);
    }
}
