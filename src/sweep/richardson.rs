//! Richardson extrapolation and least-squares power laws, for the
//! convergence study.
//!
//! The three solutions of a refinement series need not have a constant
//! refinement ratio (the Taylor meshes go 2 -> 5 -> 10 -> 20 cells across),
//! so the observed order is solved for from the general relation
//! `f(h) = f0 + C h^p` through three points, not from the constant-ratio
//! formula.

/// The result of a three-point Richardson extrapolation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Richardson {
    /// The extrapolated value at h = 0.
    pub value: f64,
    /// The observed order of convergence p.
    pub order: f64,
    /// |finest - extrapolated|: the error bar of the finest solution.
    pub error_bar: f64,
}

/// Why the extrapolation does not apply.
#[derive(Debug, Clone, PartialEq)]
pub enum NotApplicable {
    /// Fewer than three finite solutions.
    TooFew(usize),
    /// The differences change sign (oscillatory convergence) or vanish: no
    /// order can be fitted; `spread` is the largest difference between the
    /// three solutions, a rough error bar.
    NotMonotone { spread: f64 },
    /// The observed order is outside (0.05, 20): the series is not in its
    /// asymptotic range.
    OrderOutOfRange { order: f64, spread: f64 },
}

impl std::fmt::Display for NotApplicable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NotApplicable::TooFew(n) => write!(f, "needs three solutions, {n} available"),
            NotApplicable::NotMonotone { spread } => write!(
                f,
                "the differences change sign (no monotone convergence); spread {spread:.3e}"
            ),
            NotApplicable::OrderOutOfRange { order, spread } => write!(
                f,
                "observed order {order:.2} is not in the asymptotic range; spread {spread:.3e}"
            ),
        }
    }
}

/// Extrapolates `f(h)` to h = 0 from the three finest points of `series`
/// ((h, f) pairs, any order; non-finite values are ignored). The points
/// must have distinct h.
pub fn extrapolate(series: &[(f64, f64)]) -> Result<Richardson, NotApplicable> {
    let mut pts: Vec<(f64, f64)> = series
        .iter()
        .copied()
        .filter(|(h, f)| h.is_finite() && *h > 0.0 && f.is_finite())
        .collect();
    pts.sort_by(|a, b| b.0.total_cmp(&a.0));
    pts.dedup_by(|a, b| a.0 == b.0);
    if pts.len() < 3 {
        return Err(NotApplicable::TooFew(pts.len()));
    }
    let [(h1, f1), (h2, f2), (h3, f3)] =
        [pts[pts.len() - 3], pts[pts.len() - 2], pts[pts.len() - 1]];
    let spread = (f1 - f2).abs().max((f2 - f3).abs()).max((f1 - f3).abs());
    let d12 = f1 - f2;
    let d23 = f2 - f3;
    if d12 == 0.0 || d23 == 0.0 || d12.signum() != d23.signum() {
        return Err(NotApplicable::NotMonotone { spread });
    }
    // (f1 - f2) / (f2 - f3) = (h1^p - h2^p) / (h2^p - h3^p) =: g(p); g is
    // increasing in p for h1 > h2 > h3, so bisection on ln g finds p.
    let target = (d12 / d23).ln();
    let g = |p: f64| ((h1.powf(p) - h2.powf(p)) / (h2.powf(p) - h3.powf(p))).ln() - target;
    let (mut lo, mut hi) = (0.05_f64, 20.0_f64);
    if g(lo) > 0.0 || g(hi) < 0.0 {
        // Solve anyway on a wider range, to report the order.
        let order = if g(lo) > 0.0 { lo } else { hi };
        return Err(NotApplicable::OrderOutOfRange { order, spread });
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let p = 0.5 * (lo + hi);
    let c = d23 / (h2.powf(p) - h3.powf(p));
    let value = f3 - c * h3.powf(p);
    Ok(Richardson {
        value,
        order: p,
        error_bar: (f3 - value).abs(),
    })
}

/// Least-squares fit of `y = a x^b` on log-log axes; returns (a, b).
/// Points with a non-positive or non-finite coordinate are ignored; None
/// with fewer than two distinct x.
pub fn power_law(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| x.is_finite() && y.is_finite() && *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = logs.len() as f64;
    let (lo, hi) = logs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
            (l.min(p.0), h.max(p.0))
        });
    // Equal x (one mesh size run several times) leave the slope undefined;
    // rounding would otherwise make a tiny sxx and a meaningless slope.
    if logs.len() < 2 || hi - lo < 1e-9 * hi.abs().max(1.0) {
        return None;
    }
    let mx = logs.iter().map(|p| p.0).sum::<f64>() / n;
    let my = logs.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx).powi(2)).sum();
    if sxx <= 0.0 {
        return None;
    }
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let b = sxy / sxx;
    Some(((my - b * mx).exp(), b))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// f(h) = 3 + 0.7 h^1.5 sampled at the Taylor mesh sizes 1/5, 1/10,
    /// 1/20 (plus a coarser point that must be ignored): the routine must
    /// recover f0 = 3 and p = 1.5.
    #[test]
    fn recovers_a_known_power_series_with_unequal_ratios() {
        let f = |h: f64| 3.0 + 0.7 * h.powf(1.5);
        let series: Vec<(f64, f64)> = [0.5, 0.2, 0.1, 0.05].iter().map(|&h| (h, f(h))).collect();
        let r = extrapolate(&series).expect("monotone series");
        assert!((r.value - 3.0).abs() < 1e-10, "{r:?}");
        assert!((r.order - 1.5).abs() < 1e-8, "{r:?}");
        assert!((r.error_bar - 0.7 * 0.05_f64.powf(1.5)).abs() < 1e-10);
        // Unequal ratios: 1/2, 1/5, 1/10 with p = 2.
        let g = |h: f64| -13.0 - 2.0 * h * h;
        let r = extrapolate(&[(0.5, g(0.5)), (0.2, g(0.2)), (0.1, g(0.1))]).unwrap();
        assert!(
            (r.value + 13.0).abs() < 1e-10 && (r.order - 2.0).abs() < 1e-8,
            "{r:?}"
        );
    }

    #[test]
    fn refuses_oscillating_or_short_series() {
        assert_eq!(
            extrapolate(&[(1.0, 1.0), (0.5, 2.0)]),
            Err(NotApplicable::TooFew(2))
        );
        assert!(matches!(
            extrapolate(&[(1.0, 1.0), (0.5, 2.0), (0.25, 1.5), (0.1, f64::NAN)]),
            Err(NotApplicable::NotMonotone { .. })
        ));
    }

    #[test]
    fn power_law_fits_an_exact_law() {
        let pts: Vec<(f64, f64)> = [10.0, 100.0, 1000.0]
            .iter()
            .map(|&x: &f64| (x, 2.0 * x.powf(1.3)))
            .collect();
        let (a, b) = power_law(&pts).unwrap();
        assert!((a - 2.0).abs() < 1e-9 && (b - 1.3).abs() < 1e-12);
        assert_eq!(power_law(&[(1.0, 1.0)]), None);
        // Three runs of one size: no slope (not a huge one from rounding).
        assert_eq!(
            power_law(&[(661.0, 0.3), (661.0, 0.35), (661.0, 0.41)]),
            None
        );
    }
}
