//! Surfaces that touch: a glass standing on a table has its base and the table top at the
//! same place. A ray inside the glass meets both there, and which of the two rounding puts
//! first is chance; if the glass's own surface wins, the ray leaves it from a point already
//! inside the table and sees the table from within (salt-and-pepper speckle); if the
//! table's wins, nothing says the ray left the glass. The rule here makes it deterministic
//! and what the touching implies: a ray leaving the medium it travels in passes straight
//! into another object whose surface lies at the same place, within the hit point's error
//! bounds. The integrator shades that object's surface, with the ray arriving from the
//! medium it leaves, and what the surface transmits is no longer in that medium.

use super::Integrator;
use crate::accel::Hit;
use crate::geometry::RayQuery;

/// How many of a hit point's error bounds (along its normal) apart two surfaces may be and
/// still count as one place: each hit point is within one bound of its true surface, and
/// the other's bound may be larger than this one's.
const TOUCHING_BOUNDS: f32 = 4.0;

/// Below this cosine between the ray and the surface, the band of touching is measured as
/// if the ray crossed at this angle: a grazing ray would otherwise count far-off surfaces.
const MIN_COSINE: f32 = 1.0 / 32.0;

/// The widest band of touching, relative to the distance (and the origin's distance from 0):
/// the traversal looks this far past the nearest hit for the other kind. It exceeds what
/// the two bounds above allow for any hit point whose error is within a few hundred ulps.
const MAX_BAND: f32 = 1.0 / 1024.0;

impl Integrator<'_> {
    /// The nearest hit along `q` beyond `t_min` of a ray travelling in `medium` (an object),
    /// and whether the ray leaves `medium` there too: where the nearest hits on `medium`'s
    /// surface and on another object's lie within the band of touching, the other's, and
    /// it does.
    pub(super) fn nearest_in_medium(
        &self,
        q: &RayQuery,
        t_min: f32,
        medium: u32,
    ) -> (Option<Hit>, Option<u32>) {
        match self
            .accel()
            .nearest_hits_in_medium(q, t_min, medium, MAX_BAND)
        {
            (Some(other), Some(own)) => {
                let first = if own.shape.t <= other.shape.t {
                    own
                } else {
                    other
                };
                if (own.shape.t - other.shape.t).abs() <= self.touching_band(q, &first) {
                    (Some(other), Some(medium))
                } else {
                    (Some(first), None)
                }
            }
            (other, own) => (other.or(own), None),
        }
    }

    /// How far along `q` (in units of its direction) from `hit` another surface may lie
    /// and still touch `hit`'s: a few of the hit point's error bounds along its normal.
    fn touching_band(&self, q: &RayQuery, hit: &Hit) -> f32 {
        let surface = self.accel().surface(q, hit);
        let n = surface.normal;
        let band = TOUCHING_BOUNDS
            * n.abs()
                .dot(surface.error + surface.point.abs() * f32::EPSILON);
        let dir = q.ray.dir;
        let cosine = (dir.dot(n).abs() / dir.length()).max(MIN_COSINE);
        // No wider than the traversal looked past the nearest hit.
        (band / (cosine * dir.length())).min((hit.shape.t + q.ray.origin_scale()) * MAX_BAND)
    }
}
