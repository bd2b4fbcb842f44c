//! Light sources.

use glam::Vec3;

/// A point light; `color` is its intensity per channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    /// Where the light is, relative to the scene's origin.
    pub position: Vec3,
    /// Its intensity per channel (it does not fall off with distance).
    pub color: Vec3,
}
