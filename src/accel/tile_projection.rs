//! Where boxes and triangles of the scene fall on the image, in tiles: projected from the
//! eye in f64 and widened by a margin far beyond the rounding of a camera ray, so that a
//! primary ray through a tile can meet only what is listed there (first_hit.rs,
//! mesh_listing.rs).

use super::outline::CellRectangle;
use super::projected_triangle::ProjectedTriangle;
use crate::camera::CameraRays;
use glam::DVec3;

/// Tile side, in pixels.
pub const TILE: u32 = 8;

/// Image positions are projected in f64 and each box's extent is widened by this many
/// pixels, far more than the f32 rounding of a camera ray (about 10⁻⁶ of the field of
/// view), so no subsample position in a pixel can reach a box that was not listed.
pub(super) const MARGIN_PIXELS: f64 = 1.0;

/// A box corner this close to the eye's plane (as a fraction of its distance from the
/// eye) projects unstably; a box with one counts as covering the whole image.
pub(super) const NEAR_PLANE: f64 = 1e-3;

/// How the image of `width` × `height` pixels seen from the eye maps points of the scene to
/// pixels and tiles.
pub(super) struct ImageProjection<'a> {
    pub eye: DVec3,
    pub forward: DVec3,
    rays: &'a CameraRays,
    width: u32,
    height: u32,
}

impl<'a> ImageProjection<'a> {
    /// The projection of the image of `width` × `height` pixels through `rays`.
    pub(super) fn new(rays: &'a CameraRays, width: u32, height: u32) -> Self {
        Self {
            eye: rays.eye().as_dvec3(),
            forward: rays.forward().as_dvec3(),
            rays,
            width,
            height,
        }
    }

    /// Where point `p` falls on the image, in pixels; None unless it lies well in front of
    /// the eye (a point near the eye's plane projects unstably).
    pub(super) fn point(&self, p: DVec3) -> Option<(f64, f64)> {
        let v = p - self.eye;
        if v.dot(self.forward) <= NEAR_PLANE * v.length() {
            return None;
        }
        self.rays.project(p, self.width, self.height)
    }

    /// The inclusive tile rectangle that the box lo..hi covers as seen from the eye, or None
    /// when no primary ray can reach it.
    pub(super) fn box_tiles(&self, lo: DVec3, hi: DVec3) -> Option<CellRectangle> {
        let corners = (0..8).map(|i| {
            DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        });
        // A primary ray only moves forward (its direction has a positive component along
        // the view axis), so a box wholly behind the eye's plane is never hit.
        let mut behind = 0;
        let (mut x_min, mut y_min) = (f64::INFINITY, f64::INFINITY);
        let (mut x_max, mut y_max) = (f64::NEG_INFINITY, f64::NEG_INFINITY);
        for corner in corners {
            if (corner - self.eye).dot(self.forward) < 0.0 {
                behind += 1;
            }
            let Some((x, y)) = self.point(corner) else {
                x_min = f64::NEG_INFINITY;
                x_max = f64::INFINITY;
                y_min = f64::NEG_INFINITY;
                y_max = f64::INFINITY;
                continue;
            };
            x_min = x_min.min(x);
            x_max = x_max.max(x);
            y_min = y_min.min(y);
            y_max = y_max.max(y);
        }
        if behind == 8 {
            return None;
        }
        self.extent_tiles((x_min, y_min), (x_max, y_max))
    }

    /// The inclusive tile rectangle of the pixel extent from `min` to `max`, widened by
    /// `MARGIN_PIXELS`; None when it lies wholly off the image.
    pub(super) fn extent_tiles(
        &self,
        (x_min, y_min): (f64, f64),
        (x_max, y_max): (f64, f64),
    ) -> Option<CellRectangle> {
        let tiles_x = self.width.div_ceil(TILE);
        let tiles_y = self.height.div_ceil(TILE);
        // Pixel p holds subsample positions in [p, p + 1).
        let tile_of = |position: f64, tiles: u32| -> Option<u32> {
            let pixel = position.floor();
            if pixel < 0.0 {
                return Some(0);
            }
            let tile = (pixel / TILE as f64).floor();
            (tile < tiles as f64).then_some(tile as u32)
        };
        let x0 = tile_of(x_min - MARGIN_PIXELS, tiles_x)?;
        let y0 = tile_of(y_min - MARGIN_PIXELS, tiles_y)?;
        let x1 = tile_of(x_max + MARGIN_PIXELS, tiles_x).unwrap_or(tiles_x - 1);
        let y1 = tile_of(y_max + MARGIN_PIXELS, tiles_y).unwrap_or(tiles_y - 1);
        // An extent wholly left of or above the image ends before tile 0.
        if x_max + MARGIN_PIXELS < 0.0 || y_max + MARGIN_PIXELS < 0.0 {
            return None;
        }
        Some((x0, y0, x1, y1))
    }

    /// The outline of the triangle with corners `points` (in the scene's space), or None
    /// when it cannot be used: a corner is not well in front of the eye (the projection of
    /// the triangle is then not the triangle of the projected corners), or the triangle is
    /// seen edge-on.
    pub(super) fn triangle(&self, points: &[DVec3; 3]) -> Option<ProjectedTriangle> {
        let [a, b, c] = points;
        ProjectedTriangle::new([self.point(*a)?, self.point(*b)?, self.point(*c)?])
    }
}

/// Tile (tx, ty) in pixels, widened by `MARGIN_PIXELS` (far beyond the rounding of a camera
/// ray or of the triangle test), as the x and y ranges an outline may cover.
pub(super) fn tile_area(tx: u32, ty: u32) -> [(f64, f64); 2] {
    let x0 = (tx * TILE) as f64 - MARGIN_PIXELS;
    let y0 = (ty * TILE) as f64 - MARGIN_PIXELS;
    let side = TILE as f64 + 2.0 * MARGIN_PIXELS;
    [(x0, x0 + side), (y0, y0 + side)]
}

/// The distance from `eye` to the box lo..hi, rounded down so that no computed hit
/// distance on a primitive inside the box is smaller.
pub(super) fn lower_bound_distance(eye: DVec3, lo: DVec3, hi: DVec3) -> f32 {
    let gap = (lo - eye).max(eye - hi).max(DVec3::ZERO);
    crate::numerics::f32_at_most(gap.length() * (1.0 - 1e-4))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lower_bound_distance_never_exceeds_the_true_distance() {
        let eye = DVec3::new(0.1, 0.2, 0.3);
        let (lo, hi) = (DVec3::new(1.0, -1.0, -1.0), DVec3::new(2.0, 1.0, 1.0));
        let d = lower_bound_distance(eye, lo, hi) as f64;
        assert!(d <= 0.9 && d > 0.9 * (1.0 - 2e-4), "{d}");
        // An eye inside the box: zero.
        assert_eq!(lower_bound_distance(DVec3::new(1.5, 0.0, 0.0), lo, hi), 0.0);
    }
}
