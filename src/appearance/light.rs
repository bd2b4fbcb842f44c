//! Light sources.

use glam::Vec3;

/// A point light; `color` is its intensity per channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    pub position: Vec3,
    pub color: Vec3,
}
