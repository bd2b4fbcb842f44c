//! Every real root of a polynomial of degree at most four inside an interval, in f64.
//!
//! Closed forms for the quartic (Ferrari's) lose most of their digits to cancellation near
//! double roots, which on a torus are the silhouette and the inner rim: the speckles of a
//! naive torus. Instead the roots of the derivative split the interval into pieces on which
//! the polynomial is monotone; each piece whose ends differ in sign holds exactly one root,
//! found by Newton steps kept inside a shrinking bracket. Only a root that touches zero
//! without crossing (an exact tangency, a set of rays of measure zero) can be missed.

/// The most roots returned (the most a quartic has).
pub const MAX_ROOTS: usize = 4;

/// Real roots, ascending.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Roots {
    values: [f64; MAX_ROOTS],
    len: usize,
}

impl Roots {
    const NONE: Roots = Roots {
        values: [0.0; MAX_ROOTS],
        len: 0,
    };

    fn push(&mut self, x: f64) {
        if self.len < MAX_ROOTS {
            self.values[self.len] = x;
            self.len += 1;
        }
    }

    /// The roots, ascending.
    pub fn as_slice(&self) -> &[f64] {
        &self.values[..self.len]
    }
}

/// The value of the polynomial with coefficients `c` (c[i] multiplies xⁱ) at `x`.
#[inline]
pub fn evaluate(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ci| acc * x + ci)
}

/// Every root of the polynomial `c` (c[i] multiplies xⁱ, at most five coefficients) in
/// [lo, hi], ascending; a root at an end counts once.
pub fn roots_in(c: &[f64], lo: f64, hi: f64) -> Roots {
    debug_assert!(c.len() <= MAX_ROOTS + 1);
    let mut degree = c.len();
    while degree > 0 && c[degree - 1] == 0.0 {
        degree -= 1;
    }
    let c = &c[..degree];
    let mut out = Roots::NONE;
    if lo.is_nan() || hi.is_nan() || lo > hi || degree < 2 {
        return out;
    }
    if degree == 2 {
        let x = -c[0] / c[1];
        if x >= lo && x <= hi {
            out.push(x);
        }
        return out;
    }
    // The derivative's roots bound the monotone pieces.
    let mut derivative = [0.0; MAX_ROOTS];
    for i in 1..degree {
        derivative[i - 1] = c[i] * i as f64;
    }
    let critical = roots_in(&derivative[..degree - 1], lo, hi);
    let mut ends = [lo; MAX_ROOTS + 1];
    let mut count = 1;
    for &x in critical.as_slice() {
        if x > ends[count - 1] && x < hi {
            ends[count] = x;
            count += 1;
        }
    }
    ends[count] = hi;
    let mut a = lo;
    let mut fa = evaluate(c, a);
    if fa == 0.0 {
        out.push(a);
    }
    for &b in &ends[1..=count] {
        let fb = evaluate(c, b);
        if fb == 0.0 {
            out.push(b);
        } else if fa != 0.0 && (fa < 0.0) != (fb < 0.0) {
            out.push(bracketed_root(c, &derivative[..degree - 1], a, b, fa));
        }
        a = b;
        fa = fb;
    }
    out
}

/// The one root of the monotone polynomial `c` between `a` and `b` (where it takes the
/// value `fa` at `a`, and the opposite sign at `b`): Newton steps, with a bisection whenever
/// a step would leave the bracket, until the bracket stops shrinking.
fn bracketed_root(c: &[f64], derivative: &[f64], mut a: f64, mut b: f64, fa: f64) -> f64 {
    let rising = fa < 0.0;
    let mut x = 0.5 * (a + b);
    for _ in 0..100 {
        let fx = evaluate(c, x);
        if fx == 0.0 {
            return x;
        }
        if (fx < 0.0) == rising {
            a = x;
        } else {
            b = x;
        }
        let slope = evaluate(derivative, x);
        let newton = x - fx / slope;
        let next = if newton > a.min(b) && newton < a.max(b) {
            newton
        } else {
            0.5 * (a + b)
        };
        if next == x || (b - a).abs() <= f64::EPSILON * a.abs().max(b.abs()) {
            return next;
        }
        x = next;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    fn from_roots(roots: &[f64]) -> Vec<f64> {
        // (x − r0)(x − r1)… expanded, lowest power first.
        let mut c = vec![1.0];
        for &r in roots {
            let mut next = vec![0.0; c.len() + 1];
            for (i, &ci) in c.iter().enumerate() {
                next[i + 1] += ci;
                next[i] -= r * ci;
            }
            c = next;
        }
        c
    }

    #[test]
    fn finds_four_distinct_roots_in_order() {
        let c = from_roots(&[-1.5, -0.25, 0.125, 2.0]);
        let r = roots_in(&c, -10.0, 10.0);
        let expected = [-1.5, -0.25, 0.125, 2.0];
        assert_eq!(r.as_slice().len(), 4);
        for (got, want) in r.as_slice().iter().zip(expected) {
            assert!((got - want).abs() < 1e-14, "{got} vs {want}");
        }
    }

    #[test]
    fn keeps_to_the_interval() {
        let c = from_roots(&[-1.5, -0.25, 0.125, 2.0]);
        let r = roots_in(&c, -0.3, 1.0);
        assert_eq!(r.as_slice().len(), 2);
        assert!((r.as_slice()[0] + 0.25).abs() < 1e-14);
        assert!((r.as_slice()[1] - 0.125).abs() < 1e-14);
        assert!(roots_in(&c, 3.0, 4.0).as_slice().is_empty());
        assert!(roots_in(&c, 1.0, -1.0).as_slice().is_empty());
    }

    #[test]
    fn separates_roots_far_closer_than_closed_forms_can() {
        // Two roots 1e-6 apart, as a ray grazing a torus's inner rim has. (Between roots
        // closer than about 1e-7 the polynomial dips less than f64's rounding of its value:
        // a chord that thin, of a shape scaled to [−1, 1], is far below a pixel.)
        let c = from_roots(&[0.3, 0.3 + 1e-6, -0.7, 0.9]);
        let r = roots_in(&c, -1.0, 1.0);
        assert_eq!(r.as_slice().len(), 4, "{r:?}");
        assert!((r.as_slice()[1] - 0.3).abs() < 1e-10);
        assert!((r.as_slice()[2] - (0.3 + 1e-6)).abs() < 1e-10);
    }

    #[test]
    fn no_real_roots_gives_none() {
        // (x² + 1)(x² + 4)
        let c = [4.0, 0.0, 5.0, 0.0, 1.0];
        assert!(roots_in(&c, -100.0, 100.0).as_slice().is_empty());
    }

    #[test]
    fn lower_degrees_and_zero_leading_terms() {
        assert_eq!(
            roots_in(&[-2.0, 4.0, 0.0, 0.0], -1.0, 1.0).as_slice(),
            &[0.5]
        );
        let q = roots_in(&[-1.0, 0.0, 1.0], -2.0, 2.0);
        assert_eq!(q.as_slice(), &[-1.0, 1.0]);
        assert!(roots_in(&[3.0], -1.0, 1.0).as_slice().is_empty());
        assert!(roots_in(&[], -1.0, 1.0).as_slice().is_empty());
    }
}
