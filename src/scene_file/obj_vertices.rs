//! A part's vertices: each distinct corner of its triangles (position, texture coordinate,
//! normal) becomes one vertex, so shared corners stay shared, numbered in the order the
//! triangles first use them.

use super::obj_corner::{Corner, NONE};
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

/// A part's vertices and its triangles over them.
#[derive(Debug, PartialEq)]
pub(super) struct Vertices {
    pub(super) positions: Vec<Vec3>,
    /// One per vertex where every corner has a texture coordinate, else none.
    pub(super) uvs: Vec<Vec2>,
    /// One per vertex where every corner has a normal, else none.
    pub(super) normals: Vec<Vec3>,
    pub(super) triangles: Vec<[u32; 3]>,
}

impl Vertices {
    /// The vertices of `triangles`, whose corners index the file's `positions`, `uvs` and
    /// `normals`. A corner's texture coordinate counts only where every corner has one,
    /// and so does its normal.
    pub(super) fn of(
        triangles: &[[Corner; 3]],
        positions: &[Vec3],
        uvs: &[Vec2],
        normals: &[Vec3],
    ) -> Vertices {
        let every_corner =
            |has: fn(&Corner) -> bool| triangles.par_iter().all(|t| t.iter().all(has));
        let all_uv = every_corner(|c| c[1] != NONE);
        let all_normals = every_corner(|c| c[2] != NONE);
        let corners_fit = 3 * triangles.len() < u32::MAX as usize;
        if !all_uv && !all_normals && corners_fit && rayon::current_num_threads() > 1 {
            Self::by_position(triangles, positions)
        } else {
            Self::in_order(triangles, positions, uvs, normals, all_uv, all_normals)
        }
    }

    /// The vertices found in one pass over the corners in order. Most positions make one
    /// vertex: the first corner at each position is found by a table indexed by position,
    /// and only corners that differ from it there (a seam of texture coordinates or
    /// normals) by a hash map.
    fn in_order(
        triangles: &[[Corner; 3]],
        positions: &[Vec3],
        uvs: &[Vec2],
        normals: &[Vec3],
        all_uv: bool,
        all_normals: bool,
    ) -> Vertices {
        // A key of the position alone is the same as the first corner's there.
        let by_position = !all_uv && !all_normals;
        let key = |c: &Corner| -> Corner {
            [
                c[0],
                if all_uv { c[1] } else { NONE },
                if all_normals { c[2] } else { NONE },
            ]
        };
        let mut first_at: Vec<u32> = vec![u32::MAX; positions.len()];
        let mut keys: Vec<Corner> = Vec::new();
        let mut others: HashMap<Corner, u32> = HashMap::new();
        // At least a vertex per position used, as a rule; seams add a few more.
        let capacity = |all: bool| if all { positions.len() } else { 0 };
        let mut p_out = Vec::with_capacity(positions.len());
        let mut uv_out = Vec::with_capacity(capacity(all_uv));
        let mut n_out = Vec::with_capacity(capacity(all_normals));
        let mut out = Vec::with_capacity(triangles.len());
        for tri in triangles {
            out.push(tri.map(|c| {
                let k = key(&c);
                let first = first_at[k[0] as usize];
                if first != u32::MAX && (by_position || keys[first as usize] == k) {
                    return first;
                }
                let mut add = || {
                    p_out.push(positions[k[0] as usize]);
                    if k[1] != NONE {
                        uv_out.push(uvs[k[1] as usize]);
                    }
                    if k[2] != NONE {
                        n_out.push(normals[k[2] as usize]);
                    }
                    keys.push(k);
                    (p_out.len() - 1) as u32
                };
                if first == u32::MAX {
                    let v = add();
                    first_at[k[0] as usize] = v;
                    v
                } else {
                    *others.entry(k).or_insert_with(add)
                }
            }));
        }
        Vertices {
            positions: p_out,
            uvs: uv_out,
            normals: n_out,
            triangles: out,
        }
    }

    /// The vertices of triangles keyed by position alone, the same as `in_order` finds,
    /// on all threads: each position's first corner (the least corner number, 3t + c, of
    /// the corners there), then the first corners numbered in order, stretch by stretch
    /// from each stretch's count of them.
    fn by_position(triangles: &[[Corner; 3]], positions: &[Vec3]) -> Vertices {
        const STRETCH: usize = 1 << 15;
        let unset = || AtomicU32::new(u32::MAX);
        let first: Vec<AtomicU32> = (0..positions.len())
            .into_par_iter()
            .map(|_| unset())
            .collect();
        triangles.par_iter().enumerate().for_each(|(t, tri)| {
            for (c, corner) in tri.iter().enumerate() {
                first[corner[0] as usize].fetch_min((3 * t + c) as u32, Relaxed);
            }
        });
        // Calls `f(position)` for each corner of the stretch that is its position's first.
        let firsts_in = |k: usize, stretch: &[[Corner; 3]], mut f: Box<dyn FnMut(u32) + '_>| {
            for (t, tri) in stretch.iter().enumerate() {
                for (c, corner) in tri.iter().enumerate() {
                    let number = (3 * (k * STRETCH + t) + c) as u32;
                    if first[corner[0] as usize].load(Relaxed) == number {
                        f(corner[0]);
                    }
                }
            }
        };
        let counts: Vec<usize> = triangles
            .par_chunks(STRETCH)
            .enumerate()
            .map(|(k, stretch)| {
                let mut n = 0;
                firsts_in(k, stretch, Box::new(|_| n += 1));
                n
            })
            .collect();
        let mut position_of = vec![0u32; counts.iter().sum()];
        let mut pieces = Vec::with_capacity(counts.len());
        let mut rest = &mut position_of[..];
        for &n in &counts {
            let (piece, after) = rest.split_at_mut(n);
            pieces.push(piece);
            rest = after;
        }
        let vertex_of: Vec<AtomicU32> = (0..positions.len())
            .into_par_iter()
            .map(|_| unset())
            .collect();
        let offsets = counts.iter().scan(0, |sum, &n| {
            let before = *sum;
            *sum += n;
            Some(before)
        });
        triangles
            .par_chunks(STRETCH)
            .zip(pieces)
            .zip(offsets.collect::<Vec<_>>())
            .enumerate()
            .for_each(|(k, ((stretch, piece), offset))| {
                let mut next = 0;
                firsts_in(
                    k,
                    stretch,
                    Box::new(|p| {
                        piece[next] = p;
                        vertex_of[p as usize].store((offset + next) as u32, Relaxed);
                        next += 1;
                    }),
                );
            });
        Vertices {
            positions: position_of
                .par_iter()
                .map(|&p| positions[p as usize])
                .collect(),
            uvs: Vec::new(),
            normals: Vec::new(),
            triangles: triangles
                .par_iter()
                .map(|tri| tri.map(|c| vertex_of[c[0] as usize].load(Relaxed)))
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::xorshift::XorShift32;

    /// Found on all threads, the vertices of triangles keyed by position are those of the
    /// pass in order: the same positions in the same order and the same triangles, over
    /// several stretches, with positions unused, used once and shared by many corners.
    #[test]
    fn vertices_by_position_are_those_found_in_order() {
        let mut rng = XorShift32::new(0x1234_5678);
        for (count, spread) in [(1, 3), (10, 4), (3 * (1 << 15) + 17, 20_000), (70_000, 300)] {
            let positions: Vec<Vec3> = (0..spread).map(|i| Vec3::new(i as f32, 0.0, 1.0)).collect();
            let triangles: Vec<[Corner; 3]> = (0..count)
                .map(|_| {
                    // Corners without texture coordinates or normals, or with a few.
                    std::array::from_fn(|_| {
                        let p = rng.next_u32() % spread as u32;
                        [p, if p.is_multiple_of(7) { p } else { NONE }, NONE]
                    })
                })
                .collect();
            let in_order = Vertices::in_order(&triangles, &positions, &[], &[], false, false);
            let by_position = Vertices::by_position(&triangles, &positions);
            assert_eq!(in_order, by_position, "{count} triangles");
            assert!(in_order.positions.len() <= spread);
        }
    }
}
