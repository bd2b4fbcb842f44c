//! How a pixel's linear value becomes the number a file stores: an exposure (a factor of
//! two per stop) and a transfer function. prism's colours are linear throughout; the seed
//! scene's look comes from writing them linearly (no curve), which stays the default.
//! `Srgb` applies the sRGB curve (IEC 61966-2-1), for an image that displays with the
//! brightness a physically based scene meant.

use glam::Vec3;

/// The curve between linear values and stored numbers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Transfer {
    /// Stored as computed (the seed's look, and what linear HDR files hold).
    #[default]
    Linear,
    /// The sRGB curve, for display.
    Srgb,
}

impl Transfer {
    /// The name the scene file and the command line use.
    pub fn name(self) -> &'static str {
        match self {
            Transfer::Linear => "linear",
            Transfer::Srgb => "srgb",
        }
    }

    /// The transfer a name stands for.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "linear" => Some(Transfer::Linear),
            "srgb" => Some(Transfer::Srgb),
            _ => None,
        }
    }
}

/// An exposure and a transfer function, applied to each pixel's mean before it is stored.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Encoding {
    /// The curve.
    pub transfer: Transfer,
    /// Stops: values are multiplied by 2^exposure first (0 leaves them as they are).
    pub exposure: f32,
}

impl Encoding {
    /// The stored value of linear colour `c` (not clamped: a file's quantiser clamps).
    #[inline]
    pub fn apply(&self, c: Vec3) -> Vec3 {
        // Exposure 0 and the linear curve leave every bit as it was.
        let c = if self.exposure == 0.0 {
            c
        } else {
            c * self.exposure.exp2()
        };
        match self.transfer {
            Transfer::Linear => c,
            Transfer::Srgb => Vec3::new(srgb_encode(c.x), srgb_encode(c.y), srgb_encode(c.z)),
        }
    }

    /// Whether it changes nothing.
    pub fn is_identity(&self) -> bool {
        self.transfer == Transfer::Linear && self.exposure == 0.0
    }
}

/// The sRGB curve from linear light to an encoded value, both on the 0..1 scale (values
/// outside it are clamped first).
#[inline]
pub fn srgb_encode(v: f32) -> f32 {
    let v = v.clamp(0.0, 1.0);
    if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

/// The inverse of `srgb_encode`.
#[inline]
pub fn srgb_decode(v: f32) -> f32 {
    let v = v.clamp(0.0, 1.0);
    if v <= 0.040_45 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_changes_no_bit() {
        let e = Encoding::default();
        assert!(e.is_identity());
        for c in [Vec3::ZERO, Vec3::new(0.1, 0.5, 0.999), Vec3::splat(3.0)] {
            assert_eq!(
                e.apply(c).to_array().map(f32::to_bits),
                c.to_array().map(f32::to_bits)
            );
        }
    }

    #[test]
    fn srgb_matches_the_standard_and_inverts() {
        // Published points of the curve: 18% grey encodes to about 0.4614, 0.5 to 0.7354.
        assert!((srgb_encode(0.18) - 0.4614).abs() < 1e-4);
        assert!((srgb_encode(0.5) - 0.7354).abs() < 1e-4);
        assert_eq!(srgb_encode(0.0), 0.0);
        assert!((srgb_encode(1.0) - 1.0).abs() < 1e-6);
        // The two pieces meet: continuous at the knee.
        assert!((srgb_encode(0.003_130_8) - 0.040_45).abs() < 1e-5);
        for i in 0..=100 {
            let v = i as f32 / 100.0;
            assert!((srgb_decode(srgb_encode(v)) - v).abs() < 1e-5, "{v}");
        }
    }

    #[test]
    fn exposure_is_in_stops() {
        let e = Encoding {
            transfer: Transfer::Linear,
            exposure: 1.0,
        };
        assert_eq!(e.apply(Vec3::splat(0.25)), Vec3::splat(0.5));
        let e = Encoding {
            transfer: Transfer::Srgb,
            exposure: -1.0,
        };
        assert!((e.apply(Vec3::splat(0.36)).x - srgb_encode(0.18)).abs() < 1e-6);
        assert_eq!(Transfer::from_name("srgb"), Some(Transfer::Srgb));
        assert_eq!(
            Transfer::from_name(Transfer::Linear.name()),
            Some(Transfer::Linear)
        );
        assert_eq!(Transfer::from_name("gamma"), None);
    }
}
