//! Floating-point error bounds and the small numerical kernels every shape shares.
//!
//! prism traces in f32. Rather than hiding rounding error behind a fixed epsilon, each
//! intersection reports a conservative bound on the error of its hit point, and secondary
//! rays leave the surface by exactly as much as that bound requires (pbrt-v4, section 6.8;
//! the same idea as Wächter and Binder, Ray Tracing Gems chapter 6).

use glam::{Vec3, Vec3A};

/// Half the distance between 1.0 and the next f32: the unit roundoff of one operation.
pub const MACHINE_EPSILON: f32 = f32::EPSILON * 0.5;

/// The bound γ(n) = nε / (1 − nε) on the relative error of n chained roundings.
#[inline]
pub const fn gamma(n: u32) -> f32 {
    let ne = n as f32 * MACHINE_EPSILON;
    ne / (1.0 - ne)
}

/// The smallest f32 greater than `v` (for finite v).
#[inline]
pub fn next_float_up(v: f32) -> f32 {
    if v.is_infinite() && v > 0.0 {
        return v;
    }
    let v = if v == -0.0 { 0.0 } else { v };
    let bits = v.to_bits();
    let bits = if v >= 0.0 { bits + 1 } else { bits - 1 };
    f32::from_bits(bits)
}

/// The largest f32 less than `v` (for finite v).
#[inline]
pub fn next_float_down(v: f32) -> f32 {
    if v.is_infinite() && v < 0.0 {
        return v;
    }
    let v = if v == 0.0 { -0.0 } else { v };
    let bits = v.to_bits();
    let bits = if v > 0.0 { bits - 1 } else { bits + 1 };
    f32::from_bits(bits)
}

/// The largest f32 not above `v` (f64 → f32 rounds to nearest, which may round up): for
/// lower bounds computed in f64 and compared in f32.
#[inline]
pub fn f32_at_most(v: f64) -> f32 {
    let d = v as f32;
    if d as f64 > v { d.next_down() } else { d }
}

/// Moves a hit point `p`, whose every coordinate is within `error` of the true surface point,
/// off the surface with normal `n` to the side that direction `w` leaves towards, so that a
/// ray from the returned origin cannot intersect the surface it starts on.
#[inline]
pub fn offset_ray_origin(p: Vec3A, error: Vec3A, n: Vec3A, w: Vec3A) -> Vec3A {
    // The addition p + offset rounds each coordinate by up to half a step of p; adding one
    // full relative step per coordinate to the bound keeps the result outside without
    // pbrt's per-axis next-float stepping (cheaper, and branch-free).
    let bound = error + p.abs() * f32::EPSILON;
    let distance = n.abs().dot(bound);
    let offset = if w.dot(n) < 0.0 { -n } else { n } * distance;
    p + offset
}

/// The two real roots t0 ≤ t1 of a·t² − 2·β·t + c = 0 given the discriminant
/// `disc` = β² − a·c, computed without subtracting nearly equal numbers (Ray Tracing Gems
/// chapter 7): the root of larger magnitude is (β + sign(β)·√disc) / a and the other is
/// c / (β + sign(β)·√disc).
#[inline]
pub fn stable_quadratic_roots(a: f32, beta: f32, c: f32, disc: f32) -> Option<(f32, f32)> {
    if disc.is_nan() || disc < 0.0 || a == 0.0 {
        return None;
    }
    let q = beta + disc.sqrt().copysign(beta);
    if q == 0.0 {
        // β = 0 and disc = 0: a double root at zero.
        return Some((0.0, 0.0));
    }
    let t_a = c / q;
    let t_b = q / a;
    Some(if t_a <= t_b { (t_a, t_b) } else { (t_b, t_a) })
}

/// `v` scaled to unit length, or None when its length is zero or not finite.
#[inline]
pub fn try_normalize(v: Vec3) -> Option<Vec3> {
    let length = v.length();
    if length > 0.0 && length.is_finite() {
        Some(v / length)
    } else {
        // Very large or very small vectors overflow or underflow the squared length:
        // rescale by the largest component first.
        let largest = v.abs().max_element();
        if largest > 0.0 && largest.is_finite() {
            let scaled = v / largest;
            let length = scaled.length();
            (length > 0.0).then(|| scaled / length)
        } else {
            None
        }
    }
}

/// Two unit vectors that form a right-handed orthonormal frame with unit `n`
/// (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
#[inline]
pub fn orthonormal_basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn next_float_steps_by_one_ulp() {
        assert_eq!(next_float_up(1.0), 1.0 + f32::EPSILON);
        assert_eq!(next_float_down(1.0), 1.0 - f32::EPSILON / 2.0);
        assert!(next_float_up(0.0) > 0.0);
        assert!(next_float_down(0.0) < 0.0);
        assert_eq!(next_float_up(-1.0), -1.0 + f32::EPSILON / 2.0);
    }

    #[test]
    fn f32_at_most_never_rounds_up() {
        for v in [0.1f64, 1.0 / 3.0, 4393.5605, 1e-30, 2.0, 0.0, -0.7] {
            let d = f32_at_most(v);
            assert!(d as f64 <= v, "{v}");
            assert!(d.next_up() as f64 > v, "{v}: not the largest");
        }
    }

    #[test]
    fn gamma_grows_with_operation_count() {
        assert!(gamma(1) > MACHINE_EPSILON);
        assert!(gamma(5) > 5.0 * MACHINE_EPSILON && gamma(5) < 5.01 * MACHINE_EPSILON);
    }

    #[test]
    fn stable_roots_are_accurate_when_one_root_is_tiny() {
        // t² − 2·1e4·t + 1 = 0: roots ≈ 5e−5 and 2e4. The textbook formula loses the small
        // one entirely in f32 (1e4 − √(1e8 − 1) rounds to 0).
        let (a, beta, c) = (1.0f32, 1.0e4f32, 1.0f32);
        let (t0, t1) = stable_quadratic_roots(a, beta, c, beta * beta - a * c).unwrap();
        let exact_small = 1.0e4f64 - (1.0e8f64 - 1.0).sqrt();
        assert!(((t0 as f64 - exact_small) / exact_small).abs() < 1e-6);
        assert!((t1 - 2.0e4).abs() / 2.0e4 < 1e-6);
    }

    #[test]
    fn offset_origin_lands_on_the_side_of_w() {
        let p = Vec3A::new(1.0e5, 3.0, -2.0);
        let n = Vec3A::Y;
        let err = Vec3A::splat(1e-3);
        let above = offset_ray_origin(p, err, n, Vec3A::Y);
        let below = offset_ray_origin(p, err, n, -Vec3A::Y);
        assert!(above.y > p.y + 1e-3 * 0.99);
        assert!(below.y < p.y - 1e-3 * 0.99);
    }

    #[test]
    fn normalize_handles_extreme_magnitudes() {
        let tiny = Vec3::new(1e-30, 0.0, 1e-30);
        let huge = Vec3::new(3e30, 4e30, 0.0);
        assert!((try_normalize(tiny).unwrap().length() - 1.0).abs() < 1e-6);
        assert!((try_normalize(huge).unwrap() - Vec3::new(0.6, 0.8, 0.0)).length() < 1e-6);
        assert!(try_normalize(Vec3::ZERO).is_none());
        assert!(try_normalize(Vec3::new(f32::NAN, 0.0, 0.0)).is_none());
    }

    #[test]
    fn basis_is_orthonormal() {
        for n in [
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            -Vec3::Z,
            Vec3::new(0.3, -0.5, 0.81).normalize(),
        ] {
            let (t, b) = orthonormal_basis(n);
            assert!(t.dot(n).abs() < 1e-6 && b.dot(n).abs() < 1e-6 && t.dot(b).abs() < 1e-6);
            assert!((t.length() - 1.0).abs() < 1e-6 && (b.length() - 1.0).abs() < 1e-6);
        }
    }
}
