//! The cube of faces around a point light, divided into cells, through which the light's
//! lists (light_buffer.rs, shadow_listing.rs) see boxes: where a box can be seen through
//! each face, how near it comes in each cell, and which cell a shadow ray's direction falls
//! in. A box is widened, in directions and distances, by more than a computed shadow ray
//! can stray from its exact segment, so a ray that can meet it looks it up in a cell that
//! lists it.

use super::projected_triangle::ProjectedTriangle;
use glam::{DVec3, Vec3};

/// Directions are widened by this much, in units of a face's tangent (a face spans −1..1),
/// on top of the allowance for where a computed shadow ray can stray (`direction_margin`).
const MARGIN: f64 = 1e-4;

/// How far, in f32 roundings of the largest distance in the scene, a point of a computed
/// shadow ray can lie from the exact segment (a generous bound: the ray's origin and
/// direction are each one rounding off, its points a few more).
const STRAY_ULPS: f64 = 16.0;

/// The six faces: +x, −x, +y, −y, +z, −z. Face `2k + s` looks along axis k (s = 1: the
/// negative way); its tangent coordinates are axes k + 1 and k + 2 (cyclically), divided
/// by the distance along k.
pub(super) const FACES: usize = 6;

/// A cell's range of a list that slice `get` refuses (it starts after it ends): the cell
/// is covered by too many boxes and left to a hierarchy.
pub(super) const CROWDED: (u32, u32) = (1, 0);

/// The part of a face that a grid of `cells` × `cells` covers: tangents
/// `lo..lo + cells / scale` on each of its axes, fitted around the boxes seen through the
/// face. A light far from a small scene sees it through a narrow window, and all its cells
/// go to the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Window {
    lo: [f32; 2],
    scale: [f32; 2],
    /// A cell's width in tangents on each axis: 1 / scale, divided once.
    step: [f64; 2],
    /// Cells along each side.
    cells: u32,
}

impl Window {
    /// The window around tangent rectangles (each within −1..1 on both axes), with
    /// `side(n)` cells along each side for n rectangles; for none, a window beyond the face,
    /// so every lookup misses.
    pub(super) fn around(
        rectangles: impl Iterator<Item = [(f64, f64); 2]>,
        side: impl FnOnce(usize) -> u32,
    ) -> Self {
        let mut range = [(f64::INFINITY, f64::NEG_INFINITY); 2];
        let mut count = 0;
        for rectangle in rectangles {
            count += 1;
            for (axis, (lo, hi)) in range.iter_mut().enumerate() {
                *lo = lo.min(rectangle[axis].0);
                *hi = hi.max(rectangle[axis].1);
            }
        }
        let cells = side(count);
        if count == 0 {
            return Window {
                lo: [2.0; 2],
                scale: [1.0; 2],
                step: [1.0; 2],
                cells,
            };
        }
        let fit = |(lo, hi): (f64, f64)| {
            // Widened a little so that the top edge maps inside the last cell, whatever the
            // rounding of lo and scale to f32.
            let width = (hi - lo).max(1e-9) * (1.0 + 1e-5) + 1e-9;
            let lo = lo - 1e-9;
            (lo as f32, (cells as f64 / width) as f32)
        };
        let ((lo_u, scale_u), (lo_v, scale_v)) = (fit(range[0]), fit(range[1]));
        Window {
            lo: [lo_u, lo_v],
            scale: [scale_u, scale_v],
            step: [1.0 / scale_u as f64, 1.0 / scale_v as f64],
            cells,
        }
    }

    /// Cells along each side.
    pub(super) fn side(&self) -> u32 {
        self.cells
    }

    /// The inclusive cells of `axis` that tangents t0..t1 overlap.
    pub(super) fn cells(&self, axis: usize, (t0, t1): (f64, f64)) -> (u32, u32) {
        let cell = |t: f64| {
            let c = ((t - self.lo[axis] as f64) * self.scale[axis] as f64).floor();
            c.clamp(0.0, (self.cells - 1) as f64) as u32
        };
        (cell(t0), cell(t1))
    }

    /// The tangents that cell `c` of `axis` spans.
    pub(super) fn tangents(&self, axis: usize, c: u32) -> (f64, f64) {
        let (lo, step) = (self.lo[axis] as f64, self.step[axis]);
        (lo + c as f64 * step, lo + (c + 1) as f64 * step)
    }

    /// The cell (u, v) that a direction seen at tangents `tangents` falls in; None outside
    /// the window, where no box is seen.
    #[inline(always)]
    pub(super) fn cell_of(&self, [t_u, t_v]: [f32; 2]) -> Option<(u32, u32)> {
        let u = (t_u - self.lo[0]) * self.scale[0];
        let v = (t_v - self.lo[1]) * self.scale[1];
        let cells = self.cells as f32;
        (u >= 0.0 && u < cells && v >= 0.0 && v < cells).then_some((u as u32, v as u32))
    }
}

/// A direction from a light (toward a shading point) as the cube around the light sees it:
/// the face it leaves through, and its tangents there.
#[derive(Clone, Copy, Debug)]
pub(super) struct Seen {
    pub face: usize,
    pub tangents: [f32; 2],
}

impl Seen {
    /// How the cube sees direction `from_light`; None for the light itself (zero) or a
    /// direction with an infinite or NaN component (or huge finite ones that overflow):
    /// then a hierarchy answers, as for a crowded cell.
    #[inline(always)]
    pub(super) fn new(from_light: Vec3) -> Option<Seen> {
        let Vec3 { x, y, z } = from_light;
        let a = from_light.abs();
        // The major axis picks the face, the other two (in cyclic order) the tangents; ties
        // go to the lower axis, and `FaceView`'s margin covers either choice.
        let (face, major, t_u, t_v) = if a.x >= a.y && a.x >= a.z {
            ((x < 0.0) as usize, a.x, y, z)
        } else if a.y >= a.z {
            (2 + (y < 0.0) as usize, a.y, z, x)
        } else {
            (4 + (z < 0.0) as usize, a.z, x, y)
        };
        if major == 0.0
            || (a.x + a.y + a.z).partial_cmp(&f32::INFINITY) != Some(std::cmp::Ordering::Less)
        {
            return None;
        }
        let inv_major = 1.0 / major;
        Some(Seen {
            face,
            tangents: [t_u * inv_major, t_v * inv_major],
        })
    }
}

/// How far, in tangent units, a computed shadow ray can stray from the direction of a
/// point on it at `distance` from the light. The ray starts at its shading point and runs
/// along the rounded difference (light − origin), so its points near the light stray the
/// most: by about one rounding of a length up to `farthest`, seen from `distance` away.
fn direction_margin(distance: f64, farthest: f64) -> f64 {
    MARGIN + STRAY_ULPS * f32::EPSILON as f64 * farthest / distance
}

/// The farthest that any point of `boxes` (lo, hi) lies from `light`; infinite boxes are
/// skipped. No shading point is farther, and the rounding of a shadow ray's direction grows
/// with its length.
pub(super) fn farthest(light: DVec3, boxes: impl Iterator<Item = (DVec3, DVec3)>) -> f64 {
    boxes
        .filter(|(lo, hi)| lo.is_finite() && hi.is_finite())
        .map(|(lo, hi)| (lo - light).abs().max((hi - light).abs()).length())
        .fold(0.0, f64::max)
}

/// One box as seen from the light through one face, in the face's coordinates relative to
/// the light: depth along the face's axis, then the two tangent axes.
pub(super) struct FaceView {
    /// The box's depth range, and its ranges along the tangent axes; None when the box
    /// reaches round to the light's plane (or is unbounded): then only its distance from the
    /// light bounds how near it starts.
    extent: Option<[(f64, f64); 3]>,
    /// How far a shadow ray's direction may stray, in tangent units (`direction_margin`).
    margin: f64,
    /// The tangents (widened by the margin, within −1..1) of the directions that may meet
    /// the box.
    pub tangents: [(f64, f64); 2],
}

impl FaceView {
    /// None when no direction through face `face` meets the box lo..hi.
    pub(super) fn new(
        lo: DVec3,
        hi: DVec3,
        light: DVec3,
        face: usize,
        farthest: f64,
    ) -> Option<Self> {
        let whole_face = Self {
            extent: None,
            margin: 0.0,
            tangents: [(-1.0, 1.0); 2],
        };
        if !(lo.is_finite() && hi.is_finite()) {
            return Some(whole_face);
        }
        let (axis, negative) = (face / 2, face % 2 == 1);
        let (lo, hi) = ((lo - light).to_array(), (hi - light).to_array());
        // The box's extent along the face's axis, measured the way the face looks.
        let depth = if negative {
            (-hi[axis], -lo[axis])
        } else {
            (lo[axis], hi[axis])
        };
        if depth.1 <= 0.0 {
            return None; // wholly behind the face's plane: no direction through it gets there
        }
        let (u_axis, v_axis) = ((axis + 1) % 3, (axis + 2) % 3);
        if depth.0 <= 0.0 {
            // The box reaches round to the light's plane, where t / depth is unbounded, but
            // on each axis the part of it in front of the plane still lies on one side of
            // the light or spans it: t / depth ≥ t_lo / far when t_lo > 0 (less the
            // positions' rounding), and likewise below.
            let stray = STRAY_ULPS * f32::EPSILON as f64 * farthest;
            let far = depth.1 + stray;
            let tangent_range = |k: usize| {
                let low = if lo[k] - stray > 0.0 {
                    (lo[k] - stray) / far - MARGIN
                } else {
                    -1.0
                };
                let high = if hi[k] + stray < 0.0 {
                    (hi[k] + stray) / far + MARGIN
                } else {
                    1.0
                };
                (low.max(-1.0), high.min(1.0))
            };
            let tangents = [tangent_range(u_axis), tangent_range(v_axis)];
            if tangents.iter().any(|(low, high)| low > high) {
                return None;
            }
            return Some(Self {
                extent: None,
                margin: 0.0,
                tangents,
            });
        }
        let margin = direction_margin(depth.0, farthest);
        // t / depth over the box is extreme at its corners: it is monotone in t, and in
        // depth for depth > 0.
        let tangent_range = |k: usize| {
            let quotients = [
                lo[k] / depth.0,
                lo[k] / depth.1,
                hi[k] / depth.0,
                hi[k] / depth.1,
            ];
            let min = quotients.iter().copied().fold(f64::INFINITY, f64::min);
            let max = quotients.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            (min - margin, max + margin)
        };
        let (u_min, u_max) = tangent_range(u_axis);
        let (v_min, v_max) = tangent_range(v_axis);
        if u_max < -1.0 || u_min > 1.0 || v_max < -1.0 || v_min > 1.0 {
            return None;
        }
        Some(Self {
            extent: Some([depth, (lo[u_axis], hi[u_axis]), (lo[v_axis], hi[v_axis])]),
            margin,
            tangents: [
                (u_min.max(-1.0), u_max.min(1.0)),
                (v_min.max(-1.0), v_max.min(1.0)),
            ],
        })
    }

    /// The inclusive cells (u0, v0, u1, v1) of `window` through which the box is seen.
    pub(super) fn cells(&self, window: &Window) -> (u32, u32, u32, u32) {
        let (u0, u1) = window.cells(0, self.tangents[0]);
        let (v0, v1) = window.cells(1, self.tangents[1]);
        (u0, v0, u1, v1)
    }

    /// A lower bound of the squared distance from the light to the part of the box that
    /// directions with tangents in `u_cell` × `v_cell` (widened by the margin) can reach.
    /// Tighter than the distance to the whole box: seen from the light, a floor lies farther
    /// away in each cell than the objects standing on it, so their shadow rays need not test
    /// it.
    pub(super) fn distance_sq_within(&self, u_cell: (f64, f64), v_cell: (f64, f64)) -> f64 {
        let Some([depth, u_extent, v_extent]) = self.extent else {
            return 0.0;
        };
        let widen = |(c0, c1): (f64, f64)| (c0 - self.margin, c1 + self.margin);
        let (u_cell, v_cell) = (widen(u_cell), widen(v_cell));
        // The depth z at which a direction with tangent in c0..c1 can reach a coordinate in
        // lo..hi: c1·z ≥ lo and c0·z ≤ hi, each a lower bound on z when lo > 0 or hi < 0.
        let least_depth = |(c0, c1): (f64, f64), (lo, hi): (f64, f64)| {
            let mut z: f64 = 0.0;
            if lo > 0.0 && c1 > 0.0 {
                z = z.max(lo / c1);
            }
            if hi < 0.0 && c0 < 0.0 {
                z = z.max(hi / c0);
            }
            z
        };
        let z = depth
            .0
            .max(least_depth(u_cell, u_extent))
            .max(least_depth(v_cell, v_extent));
        // Along a direction with tangents (a, b), distance = depth·√(1 + a² + b²).
        let least_tangent_sq = |(c0, c1): (f64, f64)| {
            if c0 <= 0.0 && c1 >= 0.0 {
                0.0
            } else {
                (c0 * c0).min(c1 * c1)
            }
        };
        z * z * (1.0 + least_tangent_sq(u_cell) + least_tangent_sq(v_cell))
    }

    /// The outline through the face of the triangle with corners `corners`, inside the box
    /// (widened by `pad` on each axis) that this view sees, widened by the margin and by
    /// the directions that the widening can add; None when the box reaches round to the
    /// light's plane (the triangle's projection is then not the triangle of its projected
    /// corners) or the triangle is seen edge-on.
    pub(super) fn outline(
        &self,
        corners: &[DVec3; 3],
        light: DVec3,
        face: usize,
        pad: f64,
    ) -> Option<FaceOutline> {
        let [(near, _), ..] = self.extent?;
        let (axis, negative) = (face / 2, face % 2 == 1);
        let (u_axis, v_axis) = ((axis + 1) % 3, (axis + 2) % 3);
        let seen = corners.map(|c| {
            let p = (c - light).to_array();
            let depth = if negative { -p[axis] } else { p[axis] };
            (p[u_axis] / depth, p[v_axis] / depth)
        });
        let largest = seen
            .iter()
            .fold(0.0f64, |m, &(u, v)| m.max(u.abs()).max(v.abs()));
        // A point within `pad` of the triangle, at depth ≥ `near`, is seen within
        // pad·(1 + largest) / near of the triangle's outline.
        Some(FaceOutline {
            triangle: ProjectedTriangle::new(seen)?,
            widen: self.margin + pad * (1.0 + largest) / near,
        })
    }

    /// The sort key of the box in cell (u, v) of `window`: a lower bound of the squared
    /// distance from the light to any point of it that a shadow ray through the cell can
    /// meet, at least `box_distance_sq` (the whole box's), rounded down (`round_down`).
    pub(super) fn key_within(&self, window: &Window, u: u32, v: u32, box_distance_sq: f64) -> f32 {
        let within = self.distance_sq_within(window.tangents(0, u), window.tangents(1, v));
        round_down(within.max(box_distance_sq))
    }
}

/// A triangle's outline through one face of the cube, widened (`FaceView::outline`).
pub(super) struct FaceOutline {
    triangle: ProjectedTriangle,
    /// How far, in tangent units, the outline is widened on every side.
    widen: f64,
}

impl FaceOutline {
    /// Whether a direction through cell (u, v) of `window` may meet the triangle.
    pub(super) fn may_cover(&self, window: &Window, u: u32, v: u32) -> bool {
        let widened = |(t0, t1): (f64, f64)| (t0 - self.widen, t1 + self.widen);
        self.triangle.may_cover([
            widened(window.tangents(0, u)),
            widened(window.tangents(1, v)),
        ])
    }
}

/// The squared distance from `light` to the box lo..hi (0 for an unbounded box).
pub(super) fn lower_bound_distance_sq(light: DVec3, lo: DVec3, hi: DVec3) -> f64 {
    if !(lo.is_finite() && hi.is_finite()) {
        return 0.0;
    }
    (lo - light)
        .max(light - hi)
        .max(DVec3::ZERO)
        .length_squared()
}

/// A squared distance rounded down by a relative 10⁻⁴ and then to f32, so that no computed
/// squared length of a shadow ray that reaches that far is smaller.
fn round_down(distance_sq: f64) -> f32 {
    crate::numerics::f32_at_most(distance_sq * (1.0 - 1e-4))
}
