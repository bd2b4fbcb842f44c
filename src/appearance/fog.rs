//! Fog: light along every ray segment fades towards the fog's colour with the segment's
//! length, as POV-Ray's constant fog does (shadow rays are not fogged: the lights stay as
//! bright, only what the eye sees through the fog fades).

use glam::{Vec3, Vec3A};

/// Fog that fills the whole scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fog {
    /// What a ray sees through fog too deep to see through.
    pub color: Vec3,
    /// How it thickens with distance.
    pub kind: FogKind,
}

/// How fog thickens with distance (a closed set).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FogKind {
    /// The share seen through a length d is `exp(−density·d)`.
    Exponential {
        /// Per scene unit.
        density: f32,
    },
    /// Clear up to `start`, opaque from `end`, linear between.
    Linear {
        /// Where the fog begins, in scene units from a segment's start.
        start: f32,
        /// Where nothing is seen through it any more.
        end: f32,
    },
}

impl Fog {
    /// The share of the light from distance `d` along a segment that comes through.
    #[inline]
    pub fn transmittance(&self, d: f32) -> f32 {
        match self.kind {
            FogKind::Exponential { density } => (-density * d).exp(),
            FogKind::Linear { start, end } => ((end - d) / (end - start)).clamp(0.0, 1.0),
        }
    }

    /// `color`, seen from distance `d` through the fog (d infinite for a ray that leaves
    /// the scene, which then sees the fog's colour alone).
    #[inline]
    pub fn apply(&self, color: Vec3A, d: f32) -> Vec3A {
        let t = self.transmittance(d);
        if t == 1.0 {
            return color;
        }
        color * t + Vec3A::from(self.color) * (1.0 - t)
    }

    /// The same fog in a scene scaled by `scale`: it thins or thickens so that the image
    /// stays the same.
    pub fn scaled(&self, scale: f32) -> Fog {
        let kind = match self.kind {
            FogKind::Exponential { density } => FogKind::Exponential {
                density: density / scale,
            },
            FogKind::Linear { start, end } => FogKind::Linear {
                start: start * scale,
                end: end * scale,
            },
        };
        Fog { kind, ..*self }
    }

    /// The fog's thickness as one number: the exponential density, or 1/(end − start) for
    /// linear fog (what the viewer's density slider edits).
    pub fn density(&self) -> f32 {
        match self.kind {
            FogKind::Exponential { density } => density,
            FogKind::Linear { start, end } => 1.0 / (end - start),
        }
    }

    /// The same fog with thickness `density` (see `density`); linear fog keeps its start.
    pub fn with_density(&self, density: f32) -> Fog {
        let kind = match self.kind {
            FogKind::Exponential { .. } => FogKind::Exponential { density },
            FogKind::Linear { start, .. } => FogKind::Linear {
                start,
                end: start + 1.0 / density,
            },
        };
        Fog { kind, ..*self }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exponential_fog_follows_beer_lambert_and_composes() {
        let fog = Fog {
            color: Vec3::new(0.5, 0.6, 0.7),
            kind: FogKind::Exponential { density: 0.2 },
        };
        for d in [0.0f32, 1.0, 5.0, 20.0] {
            assert!((fog.transmittance(d) - (-0.2 * d).exp()).abs() < 1e-6);
        }
        // Two segments fogged one after the other equal one segment of their total length.
        let c = Vec3A::new(1.0, 0.0, 0.25);
        let two = fog.apply(fog.apply(c, 3.0), 2.0);
        let one = fog.apply(c, 5.0);
        assert!((two - one).abs().max_element() < 1e-6, "{two} {one}");
        assert_eq!(fog.apply(c, f32::INFINITY), Vec3A::new(0.5, 0.6, 0.7));
        assert_eq!(fog.apply(c, 0.0), c);
    }

    #[test]
    fn linear_fog_is_clear_then_ramps_then_opaque() {
        let fog = Fog {
            color: Vec3::ONE,
            kind: FogKind::Linear {
                start: 2.0,
                end: 6.0,
            },
        };
        assert_eq!(fog.transmittance(1.0), 1.0);
        assert_eq!(fog.transmittance(4.0), 0.5);
        assert_eq!(fog.transmittance(7.0), 0.0);
        assert_eq!(fog.transmittance(f32::INFINITY), 0.0);
        let thicker = fog.with_density(0.5);
        assert_eq!(
            thicker.kind,
            FogKind::Linear {
                start: 2.0,
                end: 4.0
            }
        );
        assert_eq!(thicker.density(), 0.5);
        let scaled = fog.scaled(10.0);
        assert_eq!(scaled.transmittance(40.0), 0.5);
    }
}
