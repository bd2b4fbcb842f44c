//! How the benches reduce repeated timings to one figure: runs timed back to back, and the
//! median (of an even count, the upper of the two middle values).

use std::time::Instant;

/// `values` sorted, smallest first.
pub(super) fn sorted(mut values: Vec<f64>) -> Vec<f64> {
    values.sort_by(f64::total_cmp);
    values
}

/// The median of `values` (at least one).
pub(super) fn median_of(values: Vec<f64>) -> f64 {
    let values = sorted(values);
    values[values.len() / 2]
}

/// Seconds of each of `runs` calls of `f` (at least one), fastest first.
pub(super) fn sorted_times(runs: usize, mut f: impl FnMut()) -> Vec<f64> {
    sorted(
        (0..runs.max(1))
            .map(|_| {
                let start = Instant::now();
                f();
                start.elapsed().as_secs_f64()
            })
            .collect(),
    )
}

/// Median seconds of `runs` calls of `f`.
pub(super) fn median(runs: usize, f: impl FnMut()) -> f64 {
    let times = sorted_times(runs, f);
    times[times.len() / 2]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_median_is_the_middle_value_or_the_upper_of_two() {
        assert_eq!(median_of(vec![3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median_of(vec![4.0, 1.0, 3.0, 2.0]), 3.0);
        assert_eq!(median_of(vec![5.0]), 5.0);
        assert_eq!(sorted(vec![2.0, -1.0, 0.5]), vec![-1.0, 0.5, 2.0]);
    }
}
