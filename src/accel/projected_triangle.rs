//! A triangle's outline seen from one point, projected onto a plane (the image seen from
//! the eye, a face of the cube around a light), as three edge functions: what lets a list
//! of cells hold a triangle only in the cells its outline may cover, not in every cell of
//! its box's rectangle.

/// A triangle's outline on a plane, as three edge functions that are ≥ 0 inside it.
#[derive(Clone, Copy, Debug)]
pub(super) struct ProjectedTriangle {
    /// Edge i: (a, b, c) with a·x + b·y + c ≥ 0 on the triangle's side of the edge.
    edges: [(f64, f64, f64); 3],
}

impl ProjectedTriangle {
    /// The outline of the triangle whose corners fall on the plane at `corners`, or None
    /// when it is seen edge-on, or nearly: the edge functions' signs would then mean
    /// nothing.
    pub(super) fn new(corners: [(f64, f64); 3]) -> Option<Self> {
        let [(ax, ay), (bx, by), (cx, cy)] = corners;
        let area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
        let extent = [bx - ax, cx - ax, by - ay, cy - ay]
            .iter()
            .fold(0.0f64, |m, d| m.max(d.abs()));
        if area.is_nan() || area.abs() <= 1e-9 * extent * extent {
            return None;
        }
        let sign = area.signum();
        let edge = |(px, py): (f64, f64), (qx, qy): (f64, f64)| {
            // (q − p) × (r − p) ≥ 0 for r on the inside (counter-clockwise when sign > 0).
            let (a, b) = (-(qy - py) * sign, (qx - px) * sign);
            (a, b, -(a * px + b * py))
        };
        Some(Self {
            edges: [
                edge(corners[0], corners[1]),
                edge(corners[1], corners[2]),
                edge(corners[2], corners[0]),
            ],
        })
    }

    /// Whether any point of the rectangle x0..x1 × y0..y1 may lie inside: false only when
    /// the whole rectangle lies outside one edge.
    pub(super) fn may_cover(&self, [(x0, x1), (y0, y1)]: [(f64, f64); 2]) -> bool {
        self.edges.iter().all(|&(a, b, c)| {
            // The corner farthest along the edge's inward normal.
            let x = if a > 0.0 { x1 } else { x0 };
            let y = if b > 0.0 { y1 } else { y0 };
            a * x + b * y + c >= 0.0
        })
    }
}
