//! Isolated solids: a closed convex shape (a sphere, a box, a capped cylinder or cone) that no other
//! primitive's box comes near. A ray that starts inside one meets nothing else before it
//! leaves, so its next hit needs no traversal.

use super::bvh::Bvh;
use super::{Primitive, Surface};
use crate::geometry::Aabb;
use glam::Vec3;

/// How far apart (relative to the size and the coordinates of a solid's box) another box
/// must stay for the solid to count as isolated: far beyond the rounding of a hit point or a
/// ray origin (a few ulps), so a rounded hit on another primitive cannot land inside.
const ISOLATION_MARGIN: f32 = 1e-4;

/// For each of `object_count` objects, its primitive when the object is an isolated solid.
pub fn isolated_solids(
    primitives: &[Primitive],
    bvh: &Bvh,
    object_count: usize,
) -> Vec<Option<u32>> {
    let mut sole: Vec<Option<u32>> = vec![None; object_count];
    let mut count = vec![0u32; object_count];
    for (index, primitive) in primitives.iter().enumerate() {
        let object = primitive.object as usize;
        count[object] += 1;
        if let Surface::Shape(shape) = &primitive.surface
            && shape.is_convex_solid()
        {
            sole[object] = Some(index as u32);
        }
    }
    (0..object_count)
        .map(|object| {
            let index = sole[object].filter(|_| count[object] == 1)?;
            alone(primitives, bvh, index).then_some(index)
        })
        .collect()
}

/// Whether no other primitive's box comes within the margin of primitive `index`'s box.
fn alone(primitives: &[Primitive], bvh: &Bvh, index: u32) -> bool {
    let bounds = primitives[index as usize].surface.bounds();
    if !(bounds.min.is_finite() && bounds.max.is_finite()) {
        return false;
    }
    let scale = bounds.min.abs().max(bounds.max.abs()).max_element()
        + (bounds.max - bounds.min).max_element();
    let margin = Vec3::splat(scale * ISOLATION_MARGIN);
    let near = Aabb {
        min: bounds.min - margin,
        max: bounds.max + margin,
    };
    let mut alone = true;
    // Stops at the first neighbour: among many coincident solids the search is short.
    bvh.overlapping(&near, |other| {
        alone &= other == index || !primitives[other as usize].surface.bounds().overlaps(&near);
        alone
    });
    alone
}
