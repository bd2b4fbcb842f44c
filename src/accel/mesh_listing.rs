//! A placed mesh listed group by group in the first-hit tiles: for each tile, the groups
//! of its triangles (`TriangleGroup`, four to a group) that a primary ray through the tile
//! may meet, nearest box first. A ray then tests those groups, two at a time, instead of
//! walking the mesh's hierarchy from its root (mesh_search.rs): on the bunny of `prism
//! bench speed` a tile lists six or seven groups, and most rays stop after the first pair or
//! two. A group is listed where any of its triangles' outlines may fall, so the list holds
//! every triangle a ray through the tile can hit.

use super::instance::{Instance, Model};
use super::mesh_search::ListedGroup;
use super::tile_projection::{
    ImageProjection, ProjectedTriangle, TileRectangle, lower_bound_distance,
};
use crate::geometry::GROUP_WIDTH;
use glam::{DAffine3, DVec3, Vec3};

/// A placed mesh whose groups more than this many of a tile's rays could meet is left to
/// its own hierarchy there.
pub const MAX_LISTED_GROUPS: usize = 16;

/// A placed mesh is listed group by group only when it has at most this many groups per
/// tile of its rectangle: a finer mesh would crowd every tile past `MAX_LISTED_GROUPS`.
const GROUPS_PER_TILE: usize = 4;

/// For each tile of `rectangle` (the instance's box's, row by row), the groups of a placed
/// mesh's triangles that primary rays through it may meet, nearest box first: a group is
/// listed in the tiles its triangles' outlines may cover (all of its box's rectangle when a
/// triangle has no outline). None for a shape, or a mesh too fine for its rectangle.
pub(super) fn mesh_listing(
    instance: &Instance,
    (x0, y0, x1, y1): TileRectangle,
    projection: &ImageProjection,
) -> Option<Vec<Vec<ListedGroup>>> {
    let Model::Mesh { groups, .. } = &**instance.model() else {
        return None;
    };
    let columns = x1 - x0 + 1;
    let area = (columns * (y1 - y0 + 1)) as usize;
    if groups.len() > GROUPS_PER_TILE * area {
        return None;
    }
    let to_scene = instance.transform().to_scene();
    let to_scene = DAffine3::from_cols_array(&to_scene.to_cols_array().map(f64::from));
    let mut listing: Vec<Vec<ListedGroup>> = vec![Vec::new(); area];
    for (index, group) in groups.iter().enumerate() {
        let mut points = [[DVec3::ZERO; 3]; GROUP_WIDTH];
        let count = group.triangles().len();
        for (corners, triangle) in points.iter_mut().zip(group.triangles()) {
            *corners = group
                .corners_of(triangle)
                .map(|c| to_scene.transform_point3(Vec3::from(c).as_dvec3()));
        }
        let points = &points[..count];
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for p in points.iter().flatten() {
            (lo, hi) = (lo.min(*p), hi.max(*p));
        }
        let listed = ListedGroup {
            group: index as u32,
            min_t: lower_bound_distance(projection.eye, lo, hi),
        };
        for (outline, (a0, b0, a1, b1)) in group_outlines(points, lo, hi, projection) {
            for ty in b0.max(y0)..=b1.min(y1) {
                for tx in a0.max(x0)..=a1.min(x1) {
                    let list = &mut listing[((ty - y0) * columns + (tx - x0)) as usize];
                    // Listed once, however many of its triangles cover the tile.
                    let listed_here = list.last().is_some_and(|l| l.group == listed.group);
                    if !listed_here && outline.is_none_or(|o| o.may_cover_tile(tx, ty)) {
                        list.push(listed);
                    }
                }
            }
        }
    }
    for groups in &mut listing {
        // Stable, so equal distances keep the groups' order.
        groups.sort_by(|a, b| a.min_t.total_cmp(&b.min_t));
    }
    Some(listing)
}

/// The outlines of a group's triangles (corners `points`, inside the box lo..hi), each with
/// the tiles it may cover. With every corner of a triangle well in front of the eye, its
/// rectangle is that of its projected corners, and it has an outline unless it is seen
/// edge-on; otherwise the group's box's rectangle stands for it, with no outline. A
/// triangle that no primary ray can reach is left out.
fn group_outlines(
    points: &[[DVec3; 3]],
    lo: DVec3,
    hi: DVec3,
    projection: &ImageProjection,
) -> impl Iterator<Item = (Option<ProjectedTriangle>, TileRectangle)> {
    points.iter().filter_map(move |corners| {
        let mut pixels = [(0.0, 0.0); 3];
        for (pixel, &p) in pixels.iter_mut().zip(corners) {
            let Some(xy) = projection.point(p) else {
                return Some((None, projection.box_tiles(lo, hi)?));
            };
            *pixel = xy;
        }
        let min = pixels.iter().fold((f64::INFINITY, f64::INFINITY), |m, p| {
            (m.0.min(p.0), m.1.min(p.1))
        });
        let max = pixels
            .iter()
            .fold((f64::NEG_INFINITY, f64::NEG_INFINITY), |m, p| {
                (m.0.max(p.0), m.1.max(p.1))
            });
        Some((
            ProjectedTriangle::new(pixels),
            projection.extent_tiles(min, max)?,
        ))
    })
}
