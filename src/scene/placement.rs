//! Where an entry is put: its own `translate`, `rotate` and `scale` as the scene file writes
//! them, and the affine map they make, in f64 so that a far-off scene keeps its precision.

use glam::{DAffine3, DMat3, DVec3, Vec3};

/// An entry's `translate`, `rotate` and `scale` as the scene file writes them: scale, then
/// turn about x, then y, then z (degrees, right-handed, as POV-Ray's `rotate`), then move,
/// in the frame the entry is in (the world's, or its group's). Identity where the entry
/// gives none.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObjectPlacement {
    /// The move, in world units.
    pub translate: DVec3,
    /// The turns about x, y and z, in degrees (f32, as the file reads them).
    pub rotate: Vec3,
    /// The factor along each axis.
    pub scale: DVec3,
}

impl ObjectPlacement {
    /// No scale, turn or move.
    pub const IDENTITY: ObjectPlacement = ObjectPlacement {
        translate: DVec3::ZERO,
        rotate: Vec3::ZERO,
        scale: DVec3::ONE,
    };

    /// The turn: about x, then y, then z. Whole turns are exact (no turn at all is the
    /// identity, bit for bit); the rest is taken in [0°, 360°) for precision.
    pub fn rotation(&self) -> DMat3 {
        let turned = self
            .rotate
            .as_dvec3()
            .to_array()
            .map(|d| d.rem_euclid(360.0));
        let [x, y, z] = turned.map(f64::to_radians);
        DMat3::from_rotation_z(z) * DMat3::from_rotation_y(y) * DMat3::from_rotation_x(x)
    }

    /// The scale and the turn together: what a direction is carried by.
    pub fn linear(&self) -> DMat3 {
        self.rotation() * DMat3::from_diagonal(self.scale)
    }

    /// The whole map: scale, turn, then move.
    pub fn affine(&self) -> DAffine3 {
        DAffine3 {
            matrix3: self.linear(),
            translation: self.translate,
        }
    }
}

impl Default for ObjectPlacement {
    fn default() -> Self {
        Self::IDENTITY
    }
}
