//! A placed mesh listed triangle by triangle in the first-hit tiles: for each tile, the
//! triangles that a primary ray through the tile may meet, nearest box first, eight to an
//! octet (`TriangleOctet`, their corners side by side in eight lanes). A ray then tests
//! those octets instead of walking the mesh's hierarchy from its root (mesh_search.rs), and
//! stops at the first octet that starts beyond its nearest hit. A triangle is listed where
//! its projected outline may fall, so the list holds every triangle a ray through the tile
//! can hit.

use super::instance::{Instance, Model};
use super::outline::CellRectangle;
use super::projected_triangle::ProjectedTriangle;
use super::tile_projection::{ImageProjection, lower_bound_distance, tile_area};
use crate::geometry::{GROUP_WIDTH, ListedTriangle, OCTET_WIDTH, TriangleGroup, TriangleOctet};
use glam::{DAffine3, DVec3, Vec3};

/// A placed mesh whose triangles that a tile's rays may meet fill more than this many
/// octets is left to its own hierarchy there.
const MAX_LISTED_OCTETS: usize = 4;

/// A placed mesh is listed triangle by triangle only when it has at most this many groups
/// of four triangles per tile of its rectangle: a finer mesh would crowd every tile past
/// `MAX_LISTED_OCTETS`, and listing it would cost more than it spares.
const GROUPS_PER_TILE: usize = 4;

/// A placed mesh's triangles listed by tile.
pub(super) struct MeshListing<'m> {
    /// The mesh's groups, which hold the triangles' corners.
    groups: &'m [TriangleGroup],
    /// The rectangle's first tile, and its width in tiles.
    x0: u32,
    y0: u32,
    columns: u32,
    /// For each tile of the rectangle, row by row, its triangles nearest box first; None
    /// where they would fill more than `MAX_LISTED_OCTETS`.
    tiles: Vec<Option<Vec<ListedTriangle>>>,
}

impl<'m> MeshListing<'m> {
    /// The triangles of the mesh placed by `instance` that primary rays through each tile of
    /// `rectangle` (the instance's box's) may meet: a triangle is listed in the tiles its
    /// outline may cover (all of its box's rectangle when it has no outline). None for a
    /// shape, or a mesh too fine for its rectangle.
    pub(super) fn new(
        instance: &'m Instance,
        (x0, y0, x1, y1): CellRectangle,
        projection: &ImageProjection,
    ) -> Option<Self> {
        let Model::Mesh { mesh, groups, .. } = &**instance.model() else {
            return None;
        };
        let columns = x1 - x0 + 1;
        let area = (columns * (y1 - y0 + 1)) as usize;
        if groups.len() > GROUPS_PER_TILE * area {
            return None;
        }
        let to_scene = instance.transform().to_scene();
        let to_scene = DAffine3::from_cols_array(&to_scene.to_cols_array().map(f64::from));
        // Every triangle a primary ray can reach, with its outline and tiles, nearest box
        // first (stable: equal distances keep the mesh's order), so that each tile's list,
        // filled in this order, comes out sorted.
        // Each vertex in the scene's space and on the image, once for the triangles that
        // share it (the groups' copies of the corners are the same bits).
        let vertices: Vec<(DVec3, Option<(f64, f64)>)> = mesh
            .positions()
            .iter()
            .map(|&p| {
                let p = to_scene.transform_point3(Vec3::from(p).as_dvec3());
                (p, projection.point(p))
            })
            .collect();
        let mut reached = Vec::with_capacity(groups.len() * GROUP_WIDTH);
        for (index, group) in groups.iter().enumerate() {
            for triangle in group.triangles() {
                let corners = mesh.triangles()[triangle as usize].map(|v| vertices[v as usize]);
                let points = corners.map(|(p, _)| p);
                let lo = points[0].min(points[1]).min(points[2]);
                let hi = points[0].max(points[1]).max(points[2]);
                let pixels = corners.map(|(_, pixel)| pixel);
                if let Some((outline, rectangle)) = triangle_outline(pixels, lo, hi, projection) {
                    let listed = (
                        lower_bound_distance(projection.eye, lo, hi),
                        index as u32,
                        triangle,
                    );
                    reached.push((listed, outline, rectangle));
                }
            }
        }
        let mut order: Vec<u32> = (0..reached.len() as u32).collect();
        order.sort_by(|&a, &b| reached[a as usize].0.0.total_cmp(&reached[b as usize].0.0));
        let mut tiles: Vec<Vec<ListedTriangle>> = vec![Vec::new(); area];
        for &i in &order {
            let (listed, outline, (a0, b0, a1, b1)) = &reached[i as usize];
            for ty in (*b0).max(y0)..=(*b1).min(y1) {
                for tx in (*a0).max(x0)..=(*a1).min(x1) {
                    if outline.is_none_or(|o| o.may_cover(tile_area(tx, ty))) {
                        tiles[((ty - y0) * columns + (tx - x0)) as usize].push(*listed);
                    }
                }
            }
        }
        let tiles = tiles
            .into_iter()
            .map(|triangles| {
                (triangles.len() <= MAX_LISTED_OCTETS * OCTET_WIDTH).then_some(triangles)
            })
            .collect();
        Some(Self {
            groups,
            x0,
            y0,
            columns,
            tiles,
        })
    }

    /// The triangles listed in tile (tx, ty) of the rectangle, nearest box first; None
    /// where too many are, and the mesh's hierarchy must be walked.
    pub(super) fn at(&self, tx: u32, ty: u32) -> Option<&[ListedTriangle]> {
        self.tiles[((ty - self.y0) * self.columns + (tx - self.x0)) as usize].as_deref()
    }

    /// How many octets all the tiles' lists fill.
    pub(super) fn octet_count(&self) -> usize {
        self.tiles
            .iter()
            .flatten()
            .map(|t| t.len().div_ceil(OCTET_WIDTH))
            .sum()
    }

    /// The octets of `triangles` (one tile's, nearest box first), in order, onto `octets`.
    pub(super) fn push_octets(
        &self,
        triangles: &[ListedTriangle],
        octets: &mut Vec<TriangleOctet>,
    ) {
        TriangleOctet::pack(self.groups, triangles, octets);
    }
}

/// The outline of a triangle (inside the box lo..hi, its corners on the image at
/// `pixels`, None for a corner not well in front of the eye) and the tiles it may cover, or
/// None when no primary ray can reach it. With every corner well in front of the eye the
/// rectangle is that of its projected corners, and it has an outline unless it is seen
/// edge-on; otherwise the rectangle is the box's, with no outline.
fn triangle_outline(
    pixels: [Option<(f64, f64)>; 3],
    lo: DVec3,
    hi: DVec3,
    projection: &ImageProjection,
) -> Option<(Option<ProjectedTriangle>, CellRectangle)> {
    let [Some(a), Some(b), Some(c)] = pixels else {
        return Some((None, projection.box_tiles(lo, hi)?));
    };
    let pixels = [a, b, c];
    let (xs, ys) = (pixels.map(|p| p.0), pixels.map(|p| p.1));
    let min = (
        xs.into_iter().fold(f64::INFINITY, f64::min),
        ys.into_iter().fold(f64::INFINITY, f64::min),
    );
    let max = (
        xs.into_iter().fold(f64::NEG_INFINITY, f64::max),
        ys.into_iter().fold(f64::NEG_INFINITY, f64::max),
    );
    Some((
        ProjectedTriangle::new(pixels),
        projection.extent_tiles(min, max)?,
    ))
}
