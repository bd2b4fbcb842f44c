//! What the acceleration layer indexes: one intersectable piece of an object.

use crate::geometry::Shape;

/// One intersectable piece of an object (a polygon becomes a fan of triangles, a
/// tetrahedron four), tagged with the object it belongs to.
#[derive(Clone, Copy, Debug)]
pub struct Primitive {
    /// The surface itself.
    pub shape: Shape,
    /// Index of the object it belongs to, into the scene's objects.
    pub object: u32,
}
