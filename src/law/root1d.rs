//! Bracketed scalar root finders for laws whose return mapping reduces to
//! one equation in one unknown (VMIS_JOHN_COOK's Δp), behind code_aster's
//! `ALGO_INTE` = BRENT, DEKKER or SECANTE (`zerofr`, `zerofb`, `zerofo`,
//! `zerofc`; docs/laws-elements.md).
//!
//! All three share one contract, so a law chooses the method by value:
//! a bracket [a, b] with f(a) < 0 < f(b) (widened outward first when it
//! does not hold), a tolerance on |f| (stress units for the laws, because
//! code_aster's stopping test is on the residual, not on x), and an
//! iteration cap (ITER_INTE_MAXI). Failure to converge is a value: the law
//! turns it into an integration failure, so the time step is cut instead of
//! a wrong or NaN state being accepted.
//!
//! Brent's method follows the classic Brent–Dekker scheme (R.P. Brent,
//! *Algorithms for minimization without derivatives*, 1973, ch. 4) with
//! code_aster's stopping test: converged when the half-width of the bracket
//! reaches 2·ε_M·|b| or |f(b)| < tol. It never leaves the bracket, which is
//! what makes it safe on the Johnson–Cook equation: the rate term makes f
//! very concave near Δp = 0, where Newton's tangent overshoots to negative
//! Δp (tests/law_john_cook.rs shows one such case).

use std::fmt;

/// code_aster's `ALGO_INTE` values for scalar equations.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RootMethod {
    Brent,
    Dekker,
    Secante,
}

impl RootMethod {
    pub fn from_aster_name(name: &str) -> Option<RootMethod> {
        match name {
            "BRENT" => Some(RootMethod::Brent),
            "DEKKER" => Some(RootMethod::Dekker),
            "SECANTE" => Some(RootMethod::Secante),
            _ => None,
        }
    }
    pub fn aster_name(self) -> &'static str {
        match self {
            RootMethod::Brent => "BRENT",
            RootMethod::Dekker => "DEKKER",
            RootMethod::Secante => "SECANTE",
        }
    }
}

/// A converged root and the number of iterations it took.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Root {
    pub x: f64,
    pub fx: f64,
    pub iterations: usize,
}

/// Why no root was returned.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RootFailure {
    /// No sign change found, even after widening the bracket.
    NoBracket { a: f64, b: f64 },
    /// The iteration cap was reached; `x` is the best point so far.
    NotConverged { x: f64, fx: f64 },
    /// f returned a non-finite value at `x`.
    NonFinite { x: f64 },
}

impl fmt::Display for RootFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RootFailure::NoBracket { a, b } => {
                write!(f, "no sign change of the residual between {a:e} and {b:e}")
            }
            RootFailure::NotConverged { x, fx } => write!(
                f,
                "the scalar solver did not converge (last point {x:e}, residual {fx:e})"
            ),
            RootFailure::NonFinite { x } => write!(f, "non-finite residual at {x:e}"),
        }
    }
}

fn eval(f: &mut impl FnMut(f64) -> f64, x: f64) -> Result<f64, RootFailure> {
    let y = f(x);
    if y.is_finite() {
        Ok(y)
    } else {
        Err(RootFailure::NonFinite { x })
    }
}

/// Widens [a, b] outward by a factor 10, at most `max_iter` times, until
/// f(a)·f(b) < 0 (code_aster's `encadr`): the end with the smaller |f|
/// moves. Returns the bracket with its values.
pub fn bracket_outward(
    f: &mut impl FnMut(f64) -> f64,
    mut a: f64,
    mut b: f64,
    max_iter: usize,
) -> Result<(f64, f64, f64, f64), RootFailure> {
    let mut fa = eval(f, a)?;
    let mut fb = eval(f, b)?;
    for _ in 0..=max_iter {
        if fa * fb < 0.0 {
            return Ok((a, b, fa, fb));
        }
        if fa.abs() < fb.abs() {
            a += 10.0 * (a - b);
            fa = eval(f, a)?;
        } else {
            b += 10.0 * (b - a);
            fb = eval(f, b)?;
        }
    }
    if fa * fb < 0.0 {
        Ok((a, b, fa, fb))
    } else {
        Err(RootFailure::NoBracket { a, b })
    }
}

/// Solves f(x) = 0 on a bracket with the chosen method.
pub fn solve(
    method: RootMethod,
    f: &mut impl FnMut(f64) -> f64,
    bracket: (f64, f64, f64, f64),
    tol_f: f64,
    max_iter: usize,
) -> Result<Root, RootFailure> {
    match method {
        RootMethod::Brent => brent(f, bracket, tol_f, max_iter),
        RootMethod::Dekker => dekker(f, bracket, tol_f, max_iter),
        RootMethod::Secante => secant(f, bracket, tol_f, max_iter),
    }
}

/// Brent's method on (a, b, f(a), f(b)).
pub fn brent(
    f: &mut impl FnMut(f64) -> f64,
    (mut a, mut b, mut fa, mut fb): (f64, f64, f64, f64),
    tol_f: f64,
    max_iter: usize,
) -> Result<Root, RootFailure> {
    if (fa > 0.0 && fb > 0.0) || (fa < 0.0 && fb < 0.0) {
        return Err(RootFailure::NoBracket { a, b });
    }
    let eps = f64::EPSILON;
    let (mut c, mut fc) = (b, fb);
    let (mut d, mut e) = (b - a, b - a);
    for k in 1..=max_iter {
        if (fb > 0.0 && fc > 0.0) || (fb < 0.0 && fc < 0.0) {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol1 = 2.0 * eps * b.abs();
        let xm = 0.5 * (c - b);
        if xm.abs() <= tol1 || fb.abs() < tol_f {
            return Ok(Root {
                x: b,
                fx: fb,
                iterations: k,
            });
        }
        if e.abs() >= tol1 && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * xm * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * xm * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            }
            p = p.abs();
            let min1 = 3.0 * xm * q - (tol1 * q).abs();
            let min2 = (e * q).abs();
            if 2.0 * p < min1.min(min2) {
                e = d;
                d = p / q;
            } else {
                d = xm;
                e = d;
            }
        } else {
            d = xm;
            e = d;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol1 {
            d
        } else {
            tol1.max(f64::MIN_POSITIVE).copysign(xm)
        };
        fb = eval(f, b)?;
    }
    Err(RootFailure::NotConverged { x: b, fx: fb })
}

/// The secant method safeguarded by the bracket (regula falsi when the
/// secant point leaves it), as code_aster's `zerofc`.
pub fn secant(
    f: &mut impl FnMut(f64) -> f64,
    (a, b, fa, fb): (f64, f64, f64, f64),
    tol_f: f64,
    max_iter: usize,
) -> Result<Root, RootFailure> {
    // Bracket (lo: f < 0, hi: f > 0).
    let ((mut lo, mut flo), (mut hi, mut fhi)) = if fa < 0.0 && fb > 0.0 {
        ((a, fa), (b, fb))
    } else if fb < 0.0 && fa > 0.0 {
        ((b, fb), (a, fa))
    } else {
        if fa == 0.0 {
            return Ok(Root {
                x: a,
                fx: fa,
                iterations: 0,
            });
        }
        if fb == 0.0 {
            return Ok(Root {
                x: b,
                fx: fb,
                iterations: 0,
            });
        }
        return Err(RootFailure::NoBracket { a, b });
    };
    let (mut x3, mut f3) = (lo, flo);
    let (mut x4, mut f4) = (hi, fhi);
    for i in 1..=max_iter {
        if f4.abs() < tol_f {
            return Ok(Root {
                x: x4,
                fx: f4,
                iterations: i,
            });
        }
        if f4 < 0.0 {
            lo = x4;
            flo = f4;
        } else {
            hi = x4;
            fhi = f4;
        }
        let slope = (f4 - f3) / (x4 - x3);
        let mut x = if slope != 0.0 && slope.is_finite() {
            x4 - f4 / slope
        } else {
            f64::NAN
        };
        let (xa, xb) = (lo.min(hi), lo.max(hi));
        if !(x > xa && x < xb) {
            x = lo - flo * (hi - lo) / (fhi - flo);
        }
        x3 = x4;
        f3 = f4;
        x4 = x;
        f4 = eval(f, x4)?;
    }
    Err(RootFailure::NotConverged { x: x4, fx: f4 })
}

/// Dekker's method: secant steps, replaced by bisection when they leave
/// the current bracket or shrink it too slowly (`zerofo`).
pub fn dekker(
    f: &mut impl FnMut(f64) -> f64,
    (a, b, fa, fb): (f64, f64, f64, f64),
    tol_f: f64,
    max_iter: usize,
) -> Result<Root, RootFailure> {
    let ((mut lo, mut flo), (mut hi, mut fhi)) = if fa <= 0.0 && fb >= 0.0 {
        ((a, fa), (b, fb))
    } else if fb <= 0.0 && fa >= 0.0 {
        ((b, fb), (a, fa))
    } else {
        return Err(RootFailure::NoBracket { a, b });
    };
    // The best point so far and the previous one (for the secant).
    let (mut xp, mut fp) = (lo, flo);
    let (mut x, mut fx) = if fhi.abs() < flo.abs() {
        (hi, fhi)
    } else {
        (lo, flo)
    };
    for k in 1..=max_iter {
        if fx.abs() < tol_f {
            return Ok(Root {
                x,
                fx,
                iterations: k,
            });
        }
        let mid = 0.5 * (lo + hi);
        let slope = (fx - fp) / (x - xp);
        let mut cand = if slope != 0.0 && slope.is_finite() {
            x - fx / slope
        } else {
            mid
        };
        let (xa, xb) = (lo.min(hi), lo.max(hi));
        // Bisection when the secant leaves the bracket or lands beyond
        // the midpoint (a step longer than half the bracket).
        if !(cand > xa && cand < xb) || (cand - x).abs() > (mid - x).abs() {
            cand = mid;
        }
        xp = x;
        fp = fx;
        x = cand;
        fx = eval(f, x)?;
        if fx < 0.0 {
            lo = x;
            flo = fx;
        } else {
            hi = x;
            fhi = fx;
        }
        if (hi - lo).abs() <= 2.0 * f64::EPSILON * x.abs() {
            return Ok(Root {
                x,
                fx,
                iterations: k,
            });
        }
    }
    let _ = (flo, fhi);
    Err(RootFailure::NotConverged { x, fx })
}

/// Newton's method safeguarded by the bracket (lo, hi) with f(lo) < 0 <
/// f(hi) on a function that is smooth between its kinks: `f` returns the
/// value and the derivative, a Newton step that leaves the current
/// bracket (or has no finite slope) is replaced by a bisection, and every
/// evaluation shrinks the bracket. It stops when |f| ≤ `tol_f` or when the
/// bracket (or the step) is down to round-off, so a caller may give a
/// tolerance below what the law asks and still get the root to the last
/// bits in a couple of quadratically convergent steps. Used where the
/// derivative is cheap and the equation monotonic (VMIS_ISOT_PUIS's
/// R(p) + 3μΔp = q_tr); the start `x0` is clamped into the bracket.
pub fn newton_bracketed(
    f: &mut impl FnMut(f64) -> (f64, f64),
    (mut lo, mut hi): (f64, f64),
    x0: f64,
    tol_f: f64,
    max_iter: usize,
) -> Result<Root, RootFailure> {
    let mut x = if x0 > lo.min(hi) && x0 < lo.max(hi) {
        x0
    } else {
        0.5 * (lo + hi)
    };
    for k in 1..=max_iter {
        let (fx, dfx) = f(x);
        if !fx.is_finite() {
            return Err(RootFailure::NonFinite { x });
        }
        if fx.abs() <= tol_f {
            return Ok(Root {
                x,
                fx,
                iterations: k,
            });
        }
        if fx < 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        let (xa, xb) = (lo.min(hi), lo.max(hi));
        let step = fx / dfx;
        let mut next = x - step;
        if !(dfx.is_finite() && dfx != 0.0 && next > xa && next < xb) {
            next = 0.5 * (lo + hi);
        }
        let tiny = 2.0 * f64::EPSILON * x.abs().max(f64::MIN_POSITIVE);
        if (next - x).abs() <= tiny || xb - xa <= tiny {
            return Ok(Root {
                x: next,
                fx,
                iterations: k,
            });
        }
        x = next;
    }
    let (fx, _) = f(x);
    Err(RootFailure::NotConverged { x, fx })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A smooth root to the last bits, in a few steps.
    #[test]
    fn newton_reaches_round_off() {
        let mut f = |x: f64| (x * x * x - 2.0, 3.0 * x * x);
        let root = newton_bracketed(&mut f, (0.0, 2.0), 1.9, 0.0, 50).unwrap();
        let want = 2f64.cbrt();
        assert!((root.x - want).abs() <= 4.0 * f64::EPSILON, "{}", root.x);
        assert!(root.iterations < 12, "{}", root.iterations);
    }

    /// atan from far away: plain Newton diverges (|x₀ − r| > 1.39);
    /// the bracket turns the first steps into bisections.
    #[test]
    fn steps_that_leave_the_bracket_are_bisections() {
        let mut f = |x: f64| ((x - 0.3).atan(), 1.0 / (1.0 + (x - 0.3) * (x - 0.3)));
        let root = newton_bracketed(&mut f, (-5.0, 10.0), 5.0, 1e-15, 60).unwrap();
        assert!((root.x - 0.3).abs() < 1e-14, "{}", root.x);
        // plain Newton from 5 leaves for ever larger |x|.
        let (mut x, mut grew) = (5.0f64, 0);
        for _ in 0..5 {
            let (v, d) = f(x);
            let next = x - v / d;
            if (next - 0.3).abs() > (x - 0.3).abs() {
                grew += 1;
            }
            x = next;
        }
        assert!(grew >= 4, "plain Newton was expected to diverge");
    }

    #[test]
    fn failures_are_values() {
        let mut nan = |_: f64| (f64::NAN, 1.0);
        assert!(matches!(
            newton_bracketed(&mut nan, (0.0, 1.0), 0.5, 0.0, 10),
            Err(RootFailure::NonFinite { .. })
        ));
        // a tolerance of 0 with one iteration cannot be met.
        let mut f = |x: f64| (x - 0.123, 1.0 + x);
        assert!(matches!(
            newton_bracketed(&mut f, (0.0, 1.0), 0.9, 0.0, 1),
            Err(RootFailure::NotConverged { .. })
        ));
    }
}
