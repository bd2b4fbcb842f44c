//! Triangle meshes: shared corners, per-corner normals for smooth shading and texture
//! coordinates. The hierarchy over a mesh's triangles belongs to the acceleration layer
//! (accel/instance.rs); this is the data and the per-triangle tests.

use super::aabb::Aabb;
use super::ray::RayQuery;
use super::shape::SurfacePoint;
use super::triangle::{TriangleHit, barycentric_point, watertight};
use super::uv_frame::UvFrame;
use glam::{Vec2, Vec3, Vec3A};
use std::collections::HashMap;

/// Meshes of fewer vertices sum their normals on one thread (`Mesh::area_weighted_normals`):
/// each further thread passes over all the faces.
const PARALLEL_NORMALS_MIN: usize = 1 << 15;

/// A triangle mesh. Every triangle has area (degenerate ones are dropped when the mesh is
/// made), and every index is in range.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    positions: Vec<Vec3A>,
    /// One per position, unit length; empty for a faceted mesh.
    normals: Vec<Vec3A>,
    /// One per position; empty when the mesh has none.
    uvs: Vec<Vec2>,
    triangles: Vec<[u32; 3]>,
}

/// Why a mesh could not be made.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum MeshError {
    /// No triangle with area is left.
    #[error("the mesh has no triangle with area")]
    NoTriangles,
    /// A position that is NaN or infinite.
    #[error("vertex {0} is not a finite point")]
    NotFinite(usize),
    /// A corner names a vertex that does not exist.
    #[error("a triangle names vertex {0}, which does not exist")]
    IndexOutOfRange(u32),
    /// Normal or texture coordinate arrays that are not one per position.
    #[error("the normals or texture coordinates are not one per vertex")]
    Mismatched,
}

impl Mesh {
    /// The mesh of `triangles` (corners indexing `positions`), with optional per-vertex
    /// `normals` and `uvs` (empty, or one per position). Triangles without area are left
    /// out; normals are normalised (a zero normal is replaced by the faces' own).
    pub fn new(
        positions: Vec<Vec3>,
        normals: Vec<Vec3>,
        uvs: Vec<Vec2>,
        triangles: Vec<[u32; 3]>,
    ) -> Result<Self, MeshError> {
        if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NotFinite(i));
        }
        if (!normals.is_empty() && normals.len() != positions.len())
            || (!uvs.is_empty() && uvs.len() != positions.len())
        {
            return Err(MeshError::Mismatched);
        }
        if let Some(&bad) = triangles
            .iter()
            .flatten()
            .find(|&&i| i as usize >= positions.len())
        {
            return Err(MeshError::IndexOutOfRange(bad));
        }
        let positions: Vec<Vec3A> = positions.into_iter().map(Vec3A::from).collect();
        let has_area = |t: &[u32; 3]| {
            let [a, b, c] = t.map(|i| Vec3::from(positions[i as usize]));
            crate::numerics::try_normalize((b - a).cross(c - a)).is_some()
        };
        // The test on all threads; the list copied without the triangles that fail it only
        // where there are such (rayon's order-keeping filter would collect through lists).
        let kept: Vec<bool> = {
            use rayon::prelude::*;
            triangles.par_iter().map(has_area).collect()
        };
        let triangles: Vec<[u32; 3]> = if kept.iter().all(|&k| k) {
            triangles
        } else {
            triangles
                .into_iter()
                .zip(kept)
                .filter_map(|(t, keep)| keep.then_some(t))
                .collect()
        };
        if triangles.is_empty() {
            return Err(MeshError::NoTriangles);
        }
        let uvs = if uvs.iter().all(|uv| uv.is_finite()) {
            uvs
        } else {
            Vec::new()
        };
        let mut mesh = Self {
            positions,
            normals: Vec::new(),
            uvs,
            triangles,
        };
        if !normals.is_empty() {
            let faces = mesh.area_weighted_normals();
            mesh.normals = normals
                .into_iter()
                .zip(faces)
                .map(|(n, face)| match crate::numerics::try_normalize(n) {
                    Some(n) => n.into(),
                    None => face,
                })
                .collect();
        }
        Ok(mesh)
    }

    /// The same mesh shaded smoothly: its normals, or where it has none, each vertex's
    /// normal the area-weighted mean of its faces'.
    pub fn smooth(mut self) -> Self {
        if self.normals.is_empty() {
            self.normals = self.area_weighted_normals();
        }
        self
    }

    /// The same mesh with flat facets: no vertex normals.
    pub fn faceted(mut self) -> Self {
        self.normals = Vec::new();
        self
    }

    /// Each vertex's normal as the sum of its faces' cross products (each as long as twice
    /// the face's area), normalised; a vertex of no face gets +y.
    fn area_weighted_normals(&self) -> Vec<Vec3A> {
        use rayon::prelude::*;
        let mut sums = vec![Vec3A::ZERO; self.positions.len()];
        // The vertices are cut into one range per thread, and each thread passes over all
        // the faces, adding only to its own range: each vertex sums its faces in the
        // faces' order, as one pass would, so the sums are the same bit for bit.
        let range_len = sums
            .len()
            .div_ceil(rayon::current_num_threads())
            .max(PARALLEL_NORMALS_MIN);
        sums.par_chunks_mut(range_len)
            .enumerate()
            .for_each(|(k, sums)| {
                let start = (k * range_len) as u32;
                let len = sums.len() as u32;
                for t in &self.triangles {
                    if t.iter().all(|&i| i.wrapping_sub(start) >= len) {
                        continue;
                    }
                    let [a, b, c] = t.map(|i| self.positions[i as usize]);
                    let n = (b - a).cross(c - a);
                    for &i in t {
                        if let Some(sum) = sums.get_mut(i.wrapping_sub(start) as usize) {
                            *sum += n;
                        }
                    }
                }
            });
        sums.par_iter_mut()
            .for_each(|n| *n = n.try_normalize().unwrap_or(Vec3A::Y));
        sums
    }

    /// The number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Whether it has vertex normals (is shaded smoothly).
    pub fn is_smooth(&self) -> bool {
        !self.normals.is_empty()
    }

    /// Whether it has texture coordinates.
    pub fn has_uvs(&self) -> bool {
        !self.uvs.is_empty()
    }

    /// The bytes its vertex data takes (positions, normals, texture coordinates).
    pub fn vertex_bytes(&self) -> usize {
        self.positions.len() * size_of::<Vec3A>()
            + self.normals.len() * size_of::<Vec3A>()
            + self.uvs.len() * size_of::<Vec2>()
    }

    /// The bytes its triangles' corner lists take.
    pub fn triangle_bytes(&self) -> usize {
        self.triangles.len() * size_of::<[u32; 3]>()
    }

    /// The vertices' positions.
    pub fn positions(&self) -> &[Vec3A] {
        &self.positions
    }

    /// Each triangle's corners, as indices into `positions`.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// Triangle `i`'s corners.
    #[inline(always)]
    pub fn corners(&self, i: u32) -> [Vec3A; 3] {
        self.triangles[i as usize].map(|v| self.positions[v as usize])
    }

    /// The box around triangle `i`.
    pub fn triangle_bounds(&self, i: u32) -> Aabb {
        Aabb::from_points(&self.corners(i).map(Vec3::from))
    }

    /// The box around the whole mesh.
    pub fn bounds(&self) -> Aabb {
        self.positions
            .iter()
            .fold(Aabb::EMPTY, |b, &p| b.grow(p.into()))
    }

    /// A copy with the triangles in `order` (a permutation of their indices): the order
    /// of the hierarchy's leaves. Gathered straight from this mesh, not copied first.
    pub fn reordered(&self, order: &[u32]) -> Mesh {
        use rayon::prelude::*;
        debug_assert_eq!(order.len(), self.triangles.len());
        Mesh {
            positions: self.positions.clone(),
            normals: self.normals.clone(),
            uvs: self.uvs.clone(),
            triangles: order
                .par_iter()
                .map(|&i| self.triangles[i as usize])
                .collect(),
        }
    }

    /// The watertight test of triangle `i`: its hit with t in (t_min, t_max).
    #[inline(always)]
    pub fn intersect(&self, i: u32, q: &RayQuery, t_min: f32, t_max: f32) -> Option<TriangleHit> {
        watertight(&self.corners(i), q, t_min, t_max)
    }

    /// The surface point at barycentric weights `b` of triangle `i`. The geometric normal
    /// follows the winding (turned to agree with the shading normal of a smooth mesh, whose
    /// normals say which side is out); the shading normal is the corners' normals
    /// interpolated.
    #[inline]
    pub fn surface(&self, i: u32, b: [f32; 3]) -> SurfacePoint {
        self.surface_of(i, &self.corners(i), b)
    }

    /// `surface`, for triangle `i` whose corners `p` the caller has at hand (bit for bit
    /// `corners(i)`).
    #[inline(always)]
    pub fn surface_of(&self, i: u32, p: &[Vec3A; 3], b: [f32; 3]) -> SurfacePoint {
        debug_assert_eq!(*p, self.corners(i));
        let (point, error) = barycentric_point(p, b);
        let mut normal = (p[1] - p[0]).cross(p[2] - p[0]).normalize();
        let shading = if self.normals.is_empty() {
            normal
        } else {
            let [n0, n1, n2] = self.triangles[i as usize].map(|v| self.normals[v as usize]);
            let n = (n0 * b[0] + n1 * b[1] + n2 * b[2])
                .try_normalize()
                .unwrap_or(normal);
            if n.dot(normal) < 0.0 {
                normal = -normal;
            }
            n
        };
        SurfacePoint {
            point,
            error,
            normal,
            shading,
        }
    }

    /// On a smooth mesh, where shadow rays from the point at weights `b` of triangle `i`
    /// start, with its error bound: the point lifted onto its corners' tangent planes
    /// ([`lifted_point`]), so that a flat facet standing in for a curved surface shadows as
    /// the surface would. None on a flat mesh.
    #[inline]
    pub fn shadow_point(&self, i: u32, b: [f32; 3]) -> Option<(Vec3A, Vec3A)> {
        self.shadow_point_of(i, &self.corners(i), b)
    }

    /// `shadow_point`, for triangle `i` whose corners `p` the caller has at hand (bit for
    /// bit `corners(i)`).
    #[inline]
    pub fn shadow_point_of(&self, i: u32, p: &[Vec3A; 3], b: [f32; 3]) -> Option<(Vec3A, Vec3A)> {
        if self.normals.is_empty() {
            return None;
        }
        debug_assert_eq!(*p, self.corners(i));
        let (point, error) = barycentric_point(p, b);
        let normals = self.triangles[i as usize].map(|v| self.normals[v as usize]);
        Some(lifted_point(p, &normals, b, point, error))
    }

    /// Texture coordinates at barycentric weights `b` of triangle `i`: the corners'
    /// interpolated, or without them the weights of the second and third corners.
    #[inline]
    pub fn uv(&self, i: u32, b: [f32; 3]) -> (f32, f32) {
        if self.uvs.is_empty() {
            return (b[1], b[2]);
        }
        let [t0, t1, t2] = self.triangles[i as usize].map(|v| self.uvs[v as usize]);
        let uv = t0 * b[0] + t1 * b[1] + t2 * b[2];
        (uv.x, uv.y)
    }

    /// The texture coordinates at weights `b` of triangle `i` and their tangents, constant
    /// over the triangle. Where its corners' coordinates do not span an area (a seam
    /// squeezed to a line), any frame about the normal stands in.
    pub fn uv_frame(&self, i: u32, b: [f32; 3]) -> UvFrame {
        let p = self.corners(i);
        let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
        if self.uvs.is_empty() {
            return UvFrame {
                uv: (b[1], b[2]),
                dpdu: e1,
                dpdv: e2,
            };
        }
        let [t0, t1, t2] = self.triangles[i as usize].map(|v| self.uvs[v as usize]);
        let (d1, d2) = (t1 - t0, t2 - t0);
        let det = d1.x * d2.y - d1.y * d2.x;
        let (dpdu, dpdv) = if det != 0.0 && det.is_finite() {
            let r = det.recip();
            ((e1 * d2.y - e2 * d1.y) * r, (e2 * d1.x - e1 * d2.x) * r)
        } else {
            let (t, b) =
                crate::numerics::orthonormal_basis(e1.cross(e2).normalize_or_zero().into());
            (t.into(), b.into())
        };
        UvFrame {
            uv: self.uv(i, b),
            dpdu,
            dpdv,
        }
    }

    /// The mesh with every triangle split into four at its edges' midpoints (shared edges
    /// share their midpoint, so the result is as closed as the original); normals and
    /// texture coordinates are interpolated. For making large meshes for benchmarks.
    pub fn subdivided(&self) -> Mesh {
        let mut positions: Vec<Vec3A> = self.positions.clone();
        let mut normals = self.normals.clone();
        let mut uvs = self.uvs.clone();
        let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
        let mut midpoint = |a: u32, b: u32| -> u32 {
            let key = (a.min(b), a.max(b));
            *midpoints.entry(key).or_insert_with(|| {
                let (a, b) = (a as usize, b as usize);
                positions.push((positions[a] + positions[b]) * 0.5);
                if !normals.is_empty() {
                    normals.push(
                        (normals[a] + normals[b])
                            .try_normalize()
                            .unwrap_or(normals[a]),
                    );
                }
                if !uvs.is_empty() {
                    uvs.push((uvs[a] + uvs[b]) * 0.5);
                }
                (positions.len() - 1) as u32
            })
        };
        let mut triangles = Vec::with_capacity(self.triangles.len() * 4);
        for &[a, b, c] in &self.triangles {
            let (ab, bc, ca) = (midpoint(a, b), midpoint(b, c), midpoint(c, a));
            triangles.extend_from_slice(&[[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
        }
        Mesh {
            positions,
            normals,
            uvs,
            triangles,
        }
    }
}

/// The point at weights `b` of a smooth triangle lifted onto the tangent planes of its
/// corners (Hanika 2021): for each corner, the point projected onto that corner's plane
/// when it lies below it, blended by the weights. The lift is the height of the curved
/// surface the normals describe above the flat facet, so shadow rays leaving from it are
/// not caught by the facet's own neighbours at the terminator. Returned with its error
/// bound: the hit's, and the rounding of the lift.
#[inline]
fn lifted_point(
    corners: &[Vec3A; 3],
    normals: &[Vec3A; 3],
    b: [f32; 3],
    point: Vec3A,
    error: Vec3A,
) -> (Vec3A, Vec3A) {
    let mut lift = Vec3A::ZERO;
    for k in 0..3 {
        let n = normals[k];
        let below = (point - corners[k]).dot(n).min(0.0);
        lift -= n * (below * b[k]);
    }
    let lifted = point + lift;
    let rounding =
        (lifted.abs() + lift.abs() + corners[0].abs().max(corners[1].abs()).max(corners[2].abs()))
            * (4.0 * f32::EPSILON);
    (lifted, error + rounding)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Ray;

    /// A triangle's texture tangents carry its corners' coordinates: the point at
    /// weights b moved by Δu·∂p/∂u + Δv·∂p/∂v is the point whose coordinates are (u, v) +
    /// (Δu, Δv), checked at every corner of a triangle with a sheared, turned map.
    #[test]
    fn a_triangle_frame_follows_its_corner_coordinates() {
        let positions = vec![
            Vec3::new(0.2, 0.1, -3.0),
            Vec3::new(2.0, 0.4, -2.5),
            Vec3::new(0.7, 1.9, -3.2),
        ];
        let uvs = vec![
            Vec2::new(0.1, 0.9),
            Vec2::new(0.6, 0.7),
            Vec2::new(0.3, 0.2),
        ];
        let mesh = Mesh::new(positions.clone(), vec![], uvs.clone(), vec![[0, 1, 2]]).unwrap();
        let frame = mesh.uv_frame(0, [1.0 / 3.0; 3]);
        for k in 0..3 {
            let (from, to) = (k, (k + 1) % 3);
            let duv = uvs[to] - uvs[from];
            let moved = Vec3A::from(positions[from]) + frame.dpdu * duv.x + frame.dpdv * duv.y;
            assert!(
                (moved - Vec3A::from(positions[to])).length() < 1e-5,
                "{k}: {moved}"
            );
        }
        // Without coordinates, (u, v) are the second and third corners' weights.
        let plain = Mesh::new(positions.clone(), vec![], vec![], vec![[0, 1, 2]]).unwrap();
        let f = plain.uv_frame(0, [0.2, 0.3, 0.5]);
        assert_eq!(f.uv, (0.3, 0.5));
        assert_eq!(f.dpdu, Vec3A::from(positions[1] - positions[0]));
        // Coordinates squeezed to a line still give a frame in the triangle's plane.
        let line = vec![Vec2::ZERO, Vec2::new(0.5, 0.5), Vec2::new(1.0, 1.0)];
        let squeezed = Mesh::new(positions, vec![], line, vec![[0, 1, 2]]).unwrap();
        let f = squeezed.uv_frame(0, [1.0 / 3.0; 3]);
        let n = squeezed.surface(0, [1.0 / 3.0; 3]).normal;
        assert!(f.dpdu.dot(n).abs() < 1e-6 && f.dpdv.dot(n).abs() < 1e-6);
        assert!((f.dpdu.cross(f.dpdv).length() - 1.0).abs() < 1e-5);
    }

    /// A unit square in z = 0 of two triangles, corners counter-clockwise from (0, 0).
    fn square() -> Mesh {
        Mesh::new(
            vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::new(0.0, 1.0, 0.0),
            ],
            Vec::new(),
            vec![
                Vec2::new(0.0, 0.0),
                Vec2::new(1.0, 0.0),
                Vec2::new(1.0, 1.0),
                Vec2::new(0.0, 1.0),
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        )
        .unwrap()
    }

    #[test]
    fn hits_report_point_normal_and_interpolated_uv() {
        let mesh = square();
        let q = RayQuery::new(Ray::new(Vec3::new(0.25, 0.75, 2.0), -Vec3::Z));
        let (i, hit) = (0..2)
            .find_map(|i| mesh.intersect(i, &q, 0.0, f32::INFINITY).map(|h| (i, h)))
            .unwrap();
        assert_eq!(i, 1);
        assert!((hit.t - 2.0).abs() < 1e-6);
        let s = mesh.surface(i, hit.b);
        assert!((s.point - Vec3A::new(0.25, 0.75, 0.0)).length() < 1e-6);
        assert_eq!(s.normal, Vec3A::Z);
        assert_eq!(s.shading, Vec3A::Z);
        let (u, v) = mesh.uv(i, hit.b);
        assert!((u - 0.25).abs() < 1e-6 && (v - 0.75).abs() < 1e-6);
    }

    /// Normals summed on several threads are those of one thread, bit for bit, on a mesh
    /// large enough to be summed in ranges, with its faces in scattered order so that
    /// faces cross the ranges.
    #[test]
    fn normals_on_several_threads_are_those_of_one() {
        let side = 260u32;
        assert!((side * side) as usize > 2 * PARALLEL_NORMALS_MIN);
        let positions: Vec<Vec3> = (0..side * side)
            .map(|k| {
                let (x, z) = ((k % side) as f32, (k / side) as f32);
                Vec3::new(x * 0.1, (x * 0.37).sin() * (z * 0.23).cos(), z * 0.1)
            })
            .collect();
        let mut triangles = Vec::new();
        for z in 0..side - 1 {
            for x in 0..side - 1 {
                let k = z * side + x;
                triangles.push([k, k + side, k + 1]);
                triangles.push([k + 1, k + side, k + side + 1]);
            }
        }
        // A fixed scattering of the faces (a multiplicative step prime to their number).
        let n = triangles.len();
        let triangles: Vec<[u32; 3]> = (0..n).map(|k| triangles[k * 7919 % n]).collect();
        let normals_on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mesh = Mesh::new(positions.clone(), Vec::new(), Vec::new(), triangles.clone());
            pool.install(|| mesh.unwrap().smooth().normals)
        };
        let bits = |v: Vec<Vec3A>| -> Vec<[u32; 3]> {
            v.iter().map(|n| n.to_array().map(f32::to_bits)).collect()
        };
        let one = bits(normals_on(1));
        assert_eq!(one, bits(normals_on(2)));
        assert_eq!(one, bits(normals_on(3)));
    }

    /// The area-weighted normal at a vertex shared by faces at right angles bisects them;
    /// at a face's middle a smooth mesh's shading normal is the corners' blend.
    #[test]
    fn smooth_normals_are_area_weighted() {
        // Two faces meeting along the z axis: one in the plane x = 0 (normal +x, area 1),
        // one in y = 0 (normal +y, area 2).
        let mesh = Mesh::new(
            vec![
                Vec3::ZERO,
                Vec3::Z,
                Vec3::new(0.0, 2.0, 0.0),
                Vec3::new(4.0, 0.0, 0.0),
            ],
            Vec::new(),
            Vec::new(),
            vec![[0, 2, 1], [0, 1, 3]],
        )
        .unwrap()
        .smooth();
        assert!(mesh.is_smooth());
        let n0 = mesh.normals[0];
        assert!(
            (n0 - Vec3A::new(2.0, 4.0, 0.0).normalize()).length() < 1e-6,
            "{n0}"
        );
        assert_eq!(mesh.normals[2], Vec3A::X);
        assert_eq!(mesh.normals[3], Vec3A::Y);
        // The geometric normal stays the face's own.
        let s = mesh.surface(0, [1.0 / 3.0; 3]);
        assert_eq!(s.normal, Vec3A::X);
        assert!(s.shading.dot(Vec3A::Y) > 0.0 && (s.shading.length() - 1.0).abs() < 1e-6);
        assert!(!mesh.clone().faceted().is_smooth());
    }

    #[test]
    fn bad_meshes_are_refused() {
        let p = vec![Vec3::ZERO, Vec3::X, Vec3::Y];
        assert_eq!(
            Mesh::new(p.clone(), vec![], vec![], vec![[0, 1, 3]]),
            Err(MeshError::IndexOutOfRange(3))
        );
        assert_eq!(
            Mesh::new(p.clone(), vec![], vec![], vec![[0, 1, 1]]),
            Err(MeshError::NoTriangles)
        );
        assert_eq!(
            Mesh::new(
                vec![Vec3::ZERO, Vec3::X, Vec3::NAN],
                vec![],
                vec![],
                vec![[0, 1, 2]]
            ),
            Err(MeshError::NotFinite(2))
        );
        assert_eq!(
            Mesh::new(p, vec![Vec3::Z], vec![], vec![[0, 1, 2]]),
            Err(MeshError::Mismatched)
        );
    }

    /// Subdivision quadruples the triangles, keeps the surface and shares edge midpoints.
    #[test]
    fn subdivision_keeps_the_surface() {
        let mesh = square();
        let fine = mesh.subdivided();
        assert_eq!(fine.triangle_count(), 8);
        // 4 corners + 5 edges (4 sides and the diagonal).
        assert_eq!(fine.vertex_count(), 9);
        let area = |m: &Mesh| -> f32 {
            (0..m.triangle_count() as u32)
                .map(|i| {
                    let [a, b, c] = m.corners(i);
                    (b - a).cross(c - a).length() / 2.0
                })
                .sum()
        };
        assert!((area(&fine) - 1.0).abs() < 1e-6);
        assert_eq!(fine.bounds(), mesh.bounds());
    }
}
