//! Where a placed mesh may lie in a grid of cells seen from one point (the first-hit tiles,
//! seen from the eye). A mesh listed in every cell of its whole box's rectangle is listed,
//! around its silhouette, where no part of it is; listed only in the cells that the boxes of
//! its own hierarchy cover, a ray through one of the others is spared the mesh's hierarchy
//! altogether. Every box holds its triangles, so a ray that meets a triangle passes through
//! a cell that its box, or one around it, covers. (A light buffer's cells are too coarse for
//! this to pay: the bunnies of assets/scenes/bunny.toml each cover some 80 cells of their
//! light's cube, and their boxes cover every one.)

use super::bvh::{Child, WIDTH};
use super::instance::{Instance, Model};
use crate::geometry::Aabb;

/// A rectangle of cells, (x0, y0, x1, y1), ends included.
pub(super) type CellRectangle = (u32, u32, u32, u32);

/// A mesh's box whose rectangle covers at most this many cells marks them all, rather than
/// being looked into: deeper boxes would cost more to project than they could spare.
const SMALL_RECTANGLE: u32 = 16;

/// The most boxes of a mesh's hierarchy projected per cell of its whole rectangle, so that
/// the outline's cost is bounded by the cells it can spare (past it, boxes mark their whole
/// rectangles). The 940,544-triangle bunny of `prism bench speed` needs about 0.75 per tile
/// of the first-hit tiles; with more, its outline hardly tightens.
const BOXES_PER_CELL: u32 = 1;

/// The cells of `rectangle` (the instance's whole box's) that the boxes of a placed mesh's
/// hierarchy cover, row by row; None for a shape, or a rectangle too small to be worth it.
/// `cells_of` gives a box's rectangle (the box in the scene's space, widened as any
/// primitive's), or None where no ray of the grid can reach it. Each box is looked into while
/// its own rectangle is more than `SMALL_RECTANGLE` cells and the budget lasts, then marked
/// whole.
pub(super) fn mesh_coverage(
    instance: &Instance,
    rectangle: CellRectangle,
    cells_of: impl Fn(&Aabb) -> Option<CellRectangle>,
) -> Option<Vec<bool>> {
    let Model::Mesh { bvh, .. } = &**instance.model() else {
        return None;
    };
    let area = |(a0, b0, a1, b1): CellRectangle| (a1 - a0 + 1) * (b1 - b0 + 1);
    if area(rectangle) <= SMALL_RECTANGLE || bvh.nodes.is_empty() {
        return None;
    }
    let mut coverage = Coverage::new(rectangle);
    let mut budget = BOXES_PER_CELL * area(rectangle);
    let mut stack = vec![0u32];
    while let Some(node) = stack.pop() {
        let n = &bvh.nodes[node as usize];
        for lane in 0..WIDTH {
            let child = n.child(lane);
            if child == Child::Empty {
                continue;
            }
            let Some(r) = cells_of(&instance.transform().bounds_to_scene(&n.bounds(lane))) else {
                continue;
            };
            budget = budget.saturating_sub(1);
            match child {
                Child::Node(inner) if area(r) > SMALL_RECTANGLE && budget > 0 => stack.push(inner),
                _ => coverage.add(r),
            }
        }
    }
    Some(coverage.covered())
}

/// The cells of a rectangle that some of a set of smaller rectangles cover. Each rectangle
/// adds to a table of differences (four entries), summed once at the end, so a rectangle
/// costs the same whether it covers one cell or all of them, and a mesh's outline stays
/// linear in its boxes and its cells.
struct Coverage {
    x0: u32,
    y0: u32,
    columns: u32,
    rows: u32,
    /// (columns + 1) × (rows + 1) differences; summed, each cell's count of rectangles.
    differences: Vec<i32>,
}

impl Coverage {
    /// An empty coverage of the cells of `(x0, y0, x1, y1)` (inclusive).
    fn new((x0, y0, x1, y1): CellRectangle) -> Self {
        let (columns, rows) = (x1 - x0 + 1, y1 - y0 + 1);
        Self {
            x0,
            y0,
            columns,
            rows,
            differences: vec![0; ((columns + 1) * (rows + 1)) as usize],
        }
    }

    /// Covers the cells of `(a0, b0, a1, b1)` (inclusive) that lie in the rectangle.
    fn add(&mut self, (a0, b0, a1, b1): CellRectangle) {
        let (x1, y1) = (self.x0 + self.columns - 1, self.y0 + self.rows - 1);
        let (a0, a1, b0, b1) = (a0.max(self.x0), a1.min(x1), b0.max(self.y0), b1.min(y1));
        if a0 > a1 || b0 > b1 {
            return;
        }
        let stride = self.columns + 1;
        let (i0, i1) = (a0 - self.x0, a1 - self.x0 + 1);
        let (j0, j1) = (b0 - self.y0, b1 - self.y0 + 1);
        self.differences[(j0 * stride + i0) as usize] += 1;
        self.differences[(j0 * stride + i1) as usize] -= 1;
        self.differences[(j1 * stride + i0) as usize] -= 1;
        self.differences[(j1 * stride + i1) as usize] += 1;
    }

    /// Whether each cell is covered, row by row.
    fn covered(mut self) -> Vec<bool> {
        let stride = (self.columns + 1) as usize;
        // Summed along each row, then down each column.
        for row in self.differences.chunks_mut(stride) {
            for i in 1..stride {
                row[i] += row[i - 1];
            }
        }
        for j in 1..=self.rows as usize {
            for i in 0..stride {
                self.differences[j * stride + i] += self.differences[(j - 1) * stride + i];
            }
        }
        let columns = self.columns as usize;
        (0..self.rows as usize * columns)
            .map(|k| self.differences[(k / columns) * stride + k % columns] > 0)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coverage_marks_the_tiles_its_rectangles_cover() {
        // Rectangles inside, across the edges of and wholly outside the covered rectangle,
        // against marking each tile one by one.
        let (x0, y0, x1, y1) = (3u32, 5u32, 17u32, 11u32);
        let mut seed = 0x2545_f491_u32;
        let mut next = |n: u32| {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) % n
        };
        for round in 0..200 {
            let mut coverage = Coverage::new((x0, y0, x1, y1));
            let mut naive = vec![false; ((x1 - x0 + 1) * (y1 - y0 + 1)) as usize];
            for _ in 0..round % 7 {
                let (a0, b0) = (next(22), next(16));
                let (a1, b1) = (a0 + next(8), b0 + next(6));
                coverage.add((a0, b0, a1, b1));
                for ty in b0.max(y0)..=b1.min(y1) {
                    for tx in a0.max(x0)..=a1.min(x1) {
                        naive[((ty - y0) * (x1 - x0 + 1) + tx - x0) as usize] = true;
                    }
                }
            }
            assert_eq!(coverage.covered(), naive, "round {round}");
        }
    }
}
