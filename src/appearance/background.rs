//! What a ray that leaves the scene sees: a colour, a vertical gradient, or an environment
//! image wrapped around the scene.

use super::texture::ImageTexture;
use glam::{Vec3, Vec3A};
use std::sync::Arc;

/// The scene's surroundings (a closed set).
#[derive(Clone, Debug, PartialEq)]
pub enum Background {
    /// One colour in every direction (the seed's black).
    Solid(Vec3),
    /// From `bottom` straight down to `top` straight up, blended by the direction's height
    /// (+y): the horizon gets their mean.
    Gradient {
        /// The colour straight down.
        bottom: Vec3,
        /// The colour straight up.
        top: Vec3,
    },
    /// A latitude-longitude (equirectangular) image: its top row straight up, its bottom
    /// row straight down; across, its centre lies along −z (where the default camera
    /// looks), three quarters of the way along +x, a quarter along −x, and its left and
    /// right edges meet behind, along +z.
    Image(Arc<ImageTexture>),
}

impl Background {
    /// The colour, when it is the same in every direction.
    #[inline]
    pub fn solid(&self) -> Option<Vec3A> {
        match self {
            Background::Solid(c) => Some((*c).into()),
            _ => None,
        }
    }

    /// What a ray along `dir` sees.
    #[inline]
    pub fn along(&self, dir: Vec3A) -> Vec3A {
        match self {
            Background::Solid(c) => (*c).into(),
            Background::Gradient { bottom, top } => {
                let up = dir.normalize_or_zero().y;
                let t = (up * 0.5 + 0.5).clamp(0.0, 1.0);
                Vec3A::from(*bottom).lerp(Vec3A::from(*top), t)
            }
            Background::Image(image) => {
                let (u, v) = lat_long(dir);
                image.sample(u, v)
            }
        }
    }
}

/// The (u, v) of direction `dir` in a latitude-longitude image: u = ½ along −z and growing
/// towards +x, v = 0 straight up and 1 straight down.
pub(super) fn lat_long(dir: Vec3A) -> (f32, f32) {
    use std::f32::consts::{PI, TAU};
    let d = dir.normalize_or_zero();
    let u = 0.5 + d.x.atan2(-d.z) / TAU;
    let v = d.y.clamp(-1.0, 1.0).acos() / PI;
    (u, v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lat_long_puts_the_centre_ahead_and_the_poles_at_the_edges() {
        let close = |(u, v): (f32, f32), (eu, ev): (f32, f32)| {
            assert!((u - eu).abs() < 1e-6 && (v - ev).abs() < 1e-6, "({u}, {v})");
        };
        close(lat_long(Vec3A::NEG_Z), (0.5, 0.5));
        close(lat_long(Vec3A::X), (0.75, 0.5));
        close(lat_long(Vec3A::NEG_X), (0.25, 0.5));
        close(lat_long(Vec3A::Y * 3.0), (lat_long(Vec3A::Y).0, 0.0));
        close(lat_long(Vec3A::NEG_Y), (lat_long(Vec3A::NEG_Y).0, 1.0));
    }

    #[test]
    fn a_gradient_runs_from_bottom_to_top_by_height() {
        let g = Background::Gradient {
            bottom: Vec3::new(0.0, 0.0, 1.0),
            top: Vec3::new(1.0, 0.0, 0.0),
        };
        assert_eq!(g.along(Vec3A::Y), Vec3A::new(1.0, 0.0, 0.0));
        assert_eq!(g.along(Vec3A::NEG_Y * 2.0), Vec3A::new(0.0, 0.0, 1.0));
        assert_eq!(g.along(Vec3A::X), Vec3A::new(0.5, 0.0, 0.5));
        assert_eq!(g.solid(), None);
        let solid = Background::Solid(Vec3::splat(0.25));
        assert_eq!(solid.along(Vec3A::Y), Vec3A::splat(0.25));
        assert_eq!(solid.solid(), Some(Vec3A::splat(0.25)));
    }
}
