//! The statistics of a timed cell: the median of its per-frame samples and their spread, the
//! interquartile range (IQR). A cell whose IQR exceeds [`NOISY_SPREAD`] of its median is
//! flagged in the table: its median is not a number to compare techniques by.

/// A timed cell is flagged when its interquartile range exceeds this share of its median.
pub const NOISY_SPREAD: f64 = 0.10;

/// The finite values of `v`, sorted.
fn sorted(v: &[f64]) -> Vec<f64> {
    let mut s: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    s.sort_by(f64::total_cmp);
    s
}

/// The `p`-quantile (0 ≤ p ≤ 1) of sorted values, interpolating linearly between the two
/// nearest ranks (numpy's default, "type 7"): the median of an even count is the mean of the
/// middle two.
fn quantile_sorted(s: &[f64], p: f64) -> Option<f64> {
    if s.is_empty() {
        return None;
    }
    let h = (s.len() - 1) as f64 * p.clamp(0.0, 1.0);
    let (lo, hi) = (h.floor() as usize, h.ceil() as usize);
    Some(s[lo] + (h - lo as f64) * (s[hi] - s[lo]))
}

/// The median of the finite values of `v`.
pub fn median(v: &[f64]) -> Option<f64> {
    quantile_sorted(&sorted(v), 0.5)
}

/// First quartile, median and third quartile of the finite values of `v`.
pub fn quartiles(v: &[f64]) -> Option<(f64, f64, f64)> {
    let s = sorted(v);
    Some((quantile_sorted(&s, 0.25)?, quantile_sorted(&s, 0.5)?, quantile_sorted(&s, 0.75)?))
}

/// The interquartile range of `samples` as a share of their median (0.12 = 12%); `None` without
/// samples or with a median of zero.
pub fn relative_spread(samples: &[f64]) -> Option<f64> {
    let (q1, m, q3) = quartiles(samples)?;
    (m != 0.0).then(|| (q3 - q1) / m.abs())
}

/// Is a relative spread too large for the median to be trusted?
pub fn is_noisy(spread: f64) -> bool {
    spread > NOISY_SPREAD
}

/// The spread as the table prints it: `±4%`, or `±12%!` when [`is_noisy`].
pub fn format_spread(spread: f64) -> String {
    let pct = (spread * 100.0).round();
    if is_noisy(spread) {
        format!("±{pct:.0}%!")
    } else {
        format!("±{pct:.0}%")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn medians_and_quartiles() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), Some(2.5));
        assert_eq!(median(&[]), None);
        assert_eq!(median(&[f64::NAN, 5.0]), Some(5.0));
        // numpy.percentile([1, 2, 3, 4, 5, 6, 7, 8], [25, 50, 75]) = 2.75, 4.5, 6.25
        assert_eq!(quartiles(&[8.0, 1.0, 7.0, 2.0, 6.0, 3.0, 5.0, 4.0]), Some((2.75, 4.5, 6.25)));
        assert_eq!(quartiles(&[5.0]), Some((5.0, 5.0, 5.0)));
    }

    #[test]
    fn spreads() {
        // IQR 6.25 - 2.75 = 3.5 of a median of 4.5.
        let s = relative_spread(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0]).unwrap();
        assert!((s - 3.5 / 4.5).abs() < 1e-12);
        assert_eq!(relative_spread(&[0.0, 0.0]), None);
        assert_eq!(format_spread(0.04), "±4%");
        assert_eq!(format_spread(0.10), "±10%");
        assert_eq!(format_spread(0.1234), "±12%!");
        assert!(!is_noisy(0.1) && is_noisy(0.1001));
    }
}
