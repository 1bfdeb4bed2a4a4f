//! CALC_FONCTION's operations on tabulated real functions.
//!
//! The rules are code_aster's (U4.32.04 and `t_fonction`), because a study
//! moved between the two codes must give the same curves:
//! - operations on one function (INTEGRE, DERIVE, ABS, PUISSANCE, INVERSE)
//!   keep its abscissas;
//! - COMB and MULT fold their functions two by two; each pair lives on the
//!   union of both abscissa lists, cut to the part of the domain where both
//!   can be evaluated (a side extends beyond the other function's end only
//!   if that function may be extended there), and the result takes the
//!   parameters (NOM_PARA, NOM_RESU, INTERPOL, PROL_*) of the first one;
//! - ENVELOPPE evaluates every function on the union of all abscissas, with
//!   no cut: an excluded function evaluated outside its domain is an error;
//! - INTEGRE and DERIVE give results excluded on both sides and turn
//!   NOM_RESU ACCE into VITE into DEPL (and back for DERIVE).
//!
//! Errors are texts naming the function; the command puts them on its
//! keyword.

use super::function::{Extrapolation, Function};
use super::test_report::py_repr;

/// A function with the name of its concept, for messages.
pub type Named<'a> = (&'a str, &'a Function);

/// Refuses DEFI_CONSTANTE's functions: they have no abscissas of their own
/// (one point of parameter TOUTPARA), so that no operation here can say
/// where their result lives.
fn tabulated<'a>(f: Named<'a>) -> Result<&'a Function, String> {
    if f.1.is_constant() {
        return Err(format!(
            "{} is a constant function (DEFI_CONSTANTE, parameter TOUTPARA): CALC_FONCTION \
             works on functions given by points (DEFI_FONCTION, RECU_FONCTION)",
            f.0
        ));
    }
    Ok(f.1)
}

/// A copy of `f` with new ordinates (same abscissas and parameters).
fn with_ordinates(f: &Function, ordinates: Vec<f64>) -> Function {
    Function {
        ordinates,
        ..f.clone()
    }
}

/// INTEGRE METHODE='TRAPEZE': the cumulative trapezoid rule, `coef` at the
/// first abscissa. The error at x against the exact primitive is at most
/// (x - x0) h^2 / 12 max|f''| for a step h.
pub fn integrate_trapezoid(f: Named, coef: f64) -> Result<Function, String> {
    let g = tabulated(f)?;
    let (xs, ys) = (&g.abscissas, &g.ordinates);
    let mut out = Vec::with_capacity(xs.len());
    let mut acc = coef;
    out.push(acc);
    for i in 1..xs.len() {
        acc += 0.5 * (ys[i] + ys[i - 1]) * (xs[i] - xs[i - 1]);
        out.push(acc);
    }
    let mut r = with_ordinates(g, out);
    r.left = Extrapolation::Excluded;
    r.right = Extrapolation::Excluded;
    r.resu = match &r.resu {
        s if s.starts_with("VITE") => "DEPL".to_string(),
        s if s.starts_with("ACCE") => "VITE".to_string(),
        s => s.clone(),
    };
    Ok(r)
}

/// DERIVE METHODE='DIFF_CENTREE': at an interior point the slope of the
/// chord over the two neighbouring segments, (y[i+1] - y[i-1]) / (x[i+1] -
/// x[i-1]) (exact for a quadratic on equal steps), at the ends the slope of
/// the end segment.
pub fn derive(f: Named) -> Result<Function, String> {
    let g = tabulated(f)?;
    let (xs, ys) = (&g.abscissas, &g.ordinates);
    let n = xs.len();
    if n < 2 {
        return Err(format!("{} has {n} point: DERIVE needs at least 2", f.0));
    }
    let slope = |i: usize| (ys[i + 1] - ys[i]) / (xs[i + 1] - xs[i]);
    let mut out = Vec::with_capacity(n);
    out.push(slope(0));
    for i in 1..n - 1 {
        out.push((ys[i + 1] - ys[i - 1]) / (xs[i + 1] - xs[i - 1]));
    }
    out.push(slope(n - 2));
    let mut r = with_ordinates(g, out);
    r.left = Extrapolation::Excluded;
    r.right = Extrapolation::Excluded;
    r.resu = match &r.resu {
        s if s.starts_with("DEPL") => "VITE".to_string(),
        s if s.starts_with("VITE") => "ACCE".to_string(),
        s => s.clone(),
    };
    Ok(r)
}

/// ABS: |y| at the same points; a linear extension would not be the
/// absolute value of anything, so it becomes excluded.
pub fn abs(f: Named) -> Result<Function, String> {
    let g = tabulated(f)?;
    let mut r = with_ordinates(g, g.ordinates.iter().map(|y| y.abs()).collect());
    for side in [&mut r.left, &mut r.right] {
        if *side == Extrapolation::Linear {
            *side = Extrapolation::Excluded;
        }
    }
    Ok(r)
}

/// PUISSANCE: y^n at the same points.
pub fn power(f: Named, n: i64) -> Result<Function, String> {
    let g = tabulated(f)?;
    if n < 1 {
        return Err(format!(
            "EXPOSANT={n}: the exponent must be a positive integer (code_aster returns the \
             function itself for EXPOSANT < 1, which aster refuses)"
        ));
    }
    let e = i32::try_from(n).map_err(|_| format!("EXPOSANT={n} is too large"))?;
    let ys: Vec<f64> = g.ordinates.iter().map(|y| y.powi(e)).collect();
    if let Some(i) = ys.iter().position(|y| !y.is_finite()) {
        return Err(format!(
            "{}^{n} is not finite at {}={}",
            f.0,
            g.para,
            py_repr(g.abscissas[i])
        ));
    }
    Ok(with_ordinates(g, ys))
}

/// INVERSE: x(y), the points swapped (and reversed for a decreasing
/// function); NOM_RESU becomes TOUTRESU, NOM_PARA stays, the interpolation
/// of the two axes is swapped, a constant extension becomes excluded.
pub fn inverse(f: Named) -> Result<Function, String> {
    let g = tabulated(f)?;
    let mut xs = g.ordinates.clone();
    let mut ys = g.abscissas.clone();
    if xs.windows(2).any(|w| w[1] < w[0]) {
        xs.reverse();
        ys.reverse();
    }
    let mut r = Function::new(&g.para, "TOUTRESU", xs, ys).map_err(|e| {
        format!(
            "{} cannot be inverted, it is not strictly monotonic: {e}",
            f.0
        )
    })?;
    r.interpolation = (g.interpolation.1, g.interpolation.0);
    let drop_constant = |e: Extrapolation| match e {
        Extrapolation::Constant => Extrapolation::Excluded,
        e => e,
    };
    r.left = drop_constant(g.left);
    r.right = drop_constant(g.right);
    Ok(r)
}

/// The support of `a op b`: the union of both abscissa lists cut to the
/// common domain, where a side extends beyond the other function's end
/// only if that function may be extended there; with the extensions of
/// the functions that set the bounds. None when the cut is empty.
fn common_support(a: &Function, b: &Function) -> Option<(Vec<f64>, Extrapolation, Extrapolation)> {
    let first = |f: &Function| f.abscissas[0];
    let last = |f: &Function| *f.abscissas.last().unwrap_or(&f.abscissas[0]);
    let left_from = if first(b) > first(a) {
        if b.left != Extrapolation::Excluded {
            a
        } else {
            b
        }
    } else if a.left != Extrapolation::Excluded {
        b
    } else {
        a
    };
    let right_from = if last(a) > last(b) {
        if b.right != Extrapolation::Excluded {
            a
        } else {
            b
        }
    } else if a.right != Extrapolation::Excluded {
        b
    } else {
        a
    };
    let (lo, hi) = (first(left_from), last(right_from));
    if lo > hi {
        return None;
    }
    let mut xs: Vec<f64> = a
        .abscissas
        .iter()
        .chain(&b.abscissas)
        .map(|x| x.clamp(lo, hi))
        .collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    Some((xs, left_from.left, right_from.right))
}

/// `f` evaluated at `xs`, errors naming the function.
fn values_at(f: Named, xs: &[f64]) -> Result<Vec<f64>, String> {
    xs.iter()
        .map(|&x| f.1.eval(x).map_err(|e| format!("{}: {e}", f.0)))
        .collect()
}

/// `a op b` on their common support, with `a`'s parameters and the
/// extensions of the functions that bound the support.
fn binary(a: Named, b: Named, op: fn(f64, f64) -> f64) -> Result<Function, String> {
    let (fa, fb) = (a.1, b.1);
    let Some((xs, left, right)) = common_support(fa, fb) else {
        let span = |f: &Function| {
            format!(
                "[{}, {}]",
                py_repr(f.abscissas[0]),
                py_repr(*f.abscissas.last().unwrap_or(&f.abscissas[0]))
            )
        };
        return Err(format!(
            "the domains of {} {} and {} {} do not overlap and neither may be extended over \
             the gap (PROL_GAUCHE/PROL_DROITE='EXCLU')",
            a.0,
            span(fa),
            b.0,
            span(fb)
        ));
    };
    let ya = values_at(a, &xs)?;
    let yb = values_at(b, &xs)?;
    let ys: Vec<f64> = ya.iter().zip(&yb).map(|(p, q)| op(*p, *q)).collect();
    let mut r = Function::new(&fa.para, &fa.resu, xs, ys).map_err(|e| format!("{}: {e}", a.0))?;
    r.interpolation = fa.interpolation;
    r.left = left;
    r.right = right;
    Ok(r)
}

/// Gives `r` the parameters of `first` (NOM_PARA, NOM_RESU, INTERPOL,
/// PROL_*), as COMB, MULT and ENVELOPPE do.
fn take_parameters(mut r: Function, first: &Function) -> Function {
    r.para = first.para.clone();
    r.resu = first.resu.clone();
    r.interpolation = first.interpolation;
    r.left = first.left;
    r.right = first.right;
    r
}

/// COMB: Σ coef_i f_i, folded in order (each new term with the sum so
/// far), with the first function's parameters.
pub fn combine(terms: &[(Named, f64)]) -> Result<Function, String> {
    let Some(&(first, _)) = terms.first() else {
        return Err("COMB needs at least one function".to_string());
    };
    let mut acc: Option<Function> = None;
    let mut so_far = String::new();
    for &(f, coef) in terms {
        let g = tabulated(f)?;
        let scaled = with_ordinates(g, g.ordinates.iter().map(|y| coef * y).collect());
        acc = Some(match acc {
            None => scaled,
            Some(sum) => binary(
                (f.0, &scaled),
                (&format!("the sum of {so_far}"), &sum),
                |p, q| p + q,
            )?,
        });
        so_far = if so_far.is_empty() {
            f.0.to_string()
        } else {
            format!("{so_far}, {}", f.0)
        };
    }
    let r = acc.ok_or_else(|| "COMB needs at least one function".to_string())?;
    Ok(take_parameters(r, first.1))
}

/// MULT: Π f_i, folded in order, with the first function's parameters.
pub fn multiply(factors: &[Named]) -> Result<Function, String> {
    let Some(&first) = factors.first() else {
        return Err("MULT needs at least one function".to_string());
    };
    let mut acc: Option<Function> = None;
    let mut so_far = String::new();
    for &f in factors {
        let g = tabulated(f)?;
        acc = Some(match acc {
            None => g.clone(),
            Some(prod) => binary(
                (f.0, g),
                (&format!("the product of {so_far}"), &prod),
                |p, q| p * q,
            )?,
        });
        so_far = if so_far.is_empty() {
            f.0.to_string()
        } else {
            format!("{so_far}, {}", f.0)
        };
    }
    let r = acc.ok_or_else(|| "MULT needs at least one function".to_string())?;
    Ok(take_parameters(r, first.1))
}

/// ENVELOPPE: the pointwise maximum (`upper`, CRITERE='SUP') or minimum
/// of the functions on the union of their abscissas, with the first
/// function's parameters.
pub fn envelope(fs: &[Named], upper: bool) -> Result<Function, String> {
    let Some(&first) = fs.first() else {
        return Err("ENVELOPPE needs at least one function".to_string());
    };
    let mut xs: Vec<f64> = Vec::new();
    for &f in fs {
        xs.extend(&tabulated(f)?.abscissas);
    }
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    let mut ys: Option<Vec<f64>> = None;
    for &f in fs {
        let v = values_at(f, &xs)?;
        ys = Some(match ys {
            None => v,
            Some(e) => e
                .iter()
                .zip(&v)
                .map(|(p, q)| if upper { p.max(*q) } else { p.min(*q) })
                .collect(),
        });
    }
    let r = Function::new(&first.1.para, &first.1.resu, xs, ys.unwrap_or_default())
        .map_err(|e| format!("{}: {e}", first.0))?;
    Ok(take_parameters(r, first.1))
}

/// LIST_PARA: `f` evaluated at the values of the list, its parameters
/// kept.
pub fn resample(f: Named, list: &[f64]) -> Result<Function, String> {
    let ys = values_at(f, list)?;
    let r = Function::new(&f.1.para, &f.1.resu, list.to_vec(), ys)
        .map_err(|e| format!("LIST_PARA: {e}"))?;
    Ok(take_parameters(r, f.1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::post::function::Interp;

    fn fun(points: &[(f64, f64)], left: Extrapolation, right: Extrapolation) -> Function {
        let mut f = Function::new(
            "INST",
            "DY",
            points.iter().map(|p| p.0).collect(),
            points.iter().map(|p| p.1).collect(),
        )
        .unwrap();
        f.left = left;
        f.right = right;
        f
    }

    const E: Extrapolation = Extrapolation::Excluded;
    const L: Extrapolation = Extrapolation::Linear;
    const C: Extrapolation = Extrapolation::Constant;

    #[test]
    fn trapezoid_sums_by_hand_and_renames_accelerations() {
        let mut f = fun(&[(0.0, 1.0), (1.0, 3.0), (3.0, -1.0)], C, L);
        f.resu = "ACCE".into();
        let g = integrate_trapezoid(("F", &f), 2.0).unwrap();
        // 2, 2 + (1+3)/2*1 = 4, 4 + (3-1)/2*2 = 6
        assert_eq!(g.abscissas, f.abscissas);
        assert_eq!(g.ordinates, vec![2.0, 4.0, 6.0]);
        assert_eq!((g.left, g.right), (E, E));
        assert_eq!(g.resu, "VITE");
        let h = integrate_trapezoid(("G", &g), 0.0).unwrap();
        assert_eq!(h.resu, "DEPL");
        // sin on [0, pi], 20 steps: within pi h^2 / 12 of 2 (and, by
        // Euler-Maclaurin, about h^2/6 below it).
        let n = 20;
        let h = std::f64::consts::PI / n as f64;
        let pts: Vec<(f64, f64)> = (0..=n)
            .map(|i| (i as f64 * h, (i as f64 * h).sin()))
            .collect();
        let s = integrate_trapezoid(("S", &fun(&pts, E, E)), 0.0).unwrap();
        let last = *s.ordinates.last().unwrap();
        let err = (last - 2.0).abs();
        assert!(err <= std::f64::consts::PI * h * h / 12.0, "{err}");
        assert!((err - h * h / 6.0).abs() < 1e-5, "{err}");
    }

    #[test]
    fn centred_differences_are_exact_for_a_quadratic_inside() {
        let pts: Vec<(f64, f64)> = (0..7)
            .map(|i| (0.5 * i as f64, (0.5 * i as f64).powi(2)))
            .collect();
        let mut f = fun(&pts, L, L);
        f.resu = "DEPL".into();
        let d = derive(("F", &f)).unwrap();
        for i in 1..6 {
            assert!((d.ordinates[i] - 2.0 * f.abscissas[i]).abs() < 1e-12);
        }
        // End points: the end segments' slopes.
        assert!((d.ordinates[0] - 0.5).abs() < 1e-15);
        assert!((d.ordinates[6] - 5.5).abs() < 1e-12);
        assert_eq!((d.left, d.right, d.resu.as_str()), (E, E, "VITE"));
        let one = fun(&[(0.0, 1.0)], E, E);
        assert!(derive(("ONE", &one)).unwrap_err().contains("at least 2"));
    }

    #[test]
    fn abs_power_and_inverse() {
        let f = fun(&[(0.0, -1.0), (1.0, 2.0), (2.0, -3.0)], L, C);
        let a = abs(("F", &f)).unwrap();
        assert_eq!(a.ordinates, vec![1.0, 2.0, 3.0]);
        assert_eq!((a.left, a.right), (E, C));
        assert_eq!(a.eval(1.5).unwrap(), 2.5);
        let p = power(("F", &f), 3).unwrap();
        assert_eq!(p.ordinates, vec![-1.0, 8.0, -27.0]);
        assert!(power(("F", &f), 0).unwrap_err().contains("positive"));
        assert!(inverse(("F", &f))
            .unwrap_err()
            .contains("not strictly monotonic"));
        let mut g = fun(&[(1.0, 6.0), (2.0, 4.0), (4.0, 0.0)], C, L);
        g.interpolation = (Interp::Lin, Interp::Log);
        let i = inverse(("G", &g)).unwrap();
        assert_eq!(i.abscissas, vec![0.0, 4.0, 6.0]);
        assert_eq!(i.ordinates, vec![4.0, 2.0, 1.0]);
        assert_eq!((i.left, i.right), (E, L));
        assert_eq!(i.interpolation, (Interp::Log, Interp::Lin));
        assert_eq!((i.para.as_str(), i.resu.as_str()), ("INST", "TOUTRESU"));
    }

    #[test]
    fn comb_lives_where_both_functions_can_be_evaluated() {
        // y = x on [0, 2] excluded; y = 2x on [0.5, 3], linear on the left.
        let f1 = fun(&[(0.0, 0.0), (1.0, 1.0), (2.0, 2.0)], E, E);
        let f2 = fun(&[(0.5, 1.0), (1.5, 3.0), (3.0, 6.0)], L, E);
        let c = combine(&[(("F1", &f1), 3.0), (("F2", &f2), 1.0)]).unwrap();
        assert_eq!(c.abscissas, vec![0.0, 0.5, 1.0, 1.5, 2.0]);
        for (x, y) in c.abscissas.iter().zip(&c.ordinates) {
            assert!((y - 5.0 * x).abs() < 1e-14, "{x} {y}");
        }
        assert_eq!((c.left, c.right), (E, E));
        // F2 first: its parameters (L, E), same support.
        let c2 = combine(&[(("F2", &f2), 1.0), (("F1", &f1), 3.0)]).unwrap();
        assert_eq!(c2.abscissas, c.abscissas);
        assert_eq!((c2.left, c2.right), (L, E));
        let r = resample(("C", &c), &[0.25, 1.75]).unwrap();
        assert_eq!(r.ordinates, vec![1.25, 8.75]);
        assert!(resample(("C", &c), &[2.5]).unwrap_err().contains("outside"));
        let far = fun(&[(5.0, 0.0), (6.0, 1.0)], E, E);
        assert!(combine(&[(("F1", &f1), 1.0), (("FAR", &far), 1.0)])
            .unwrap_err()
            .contains("do not overlap"));
        let k = Function::constant(1.0, "TOUTRESU");
        assert!(combine(&[(("K", &k), 1.0)])
            .unwrap_err()
            .contains("DEFI_CONSTANTE"));
    }

    #[test]
    fn mult_and_envelopes() {
        let f1 = fun(&[(0.0, 0.0), (1.0, 1.0), (2.0, 2.0)], E, E);
        let f2 = fun(&[(0.5, 1.0), (1.5, 3.0), (3.0, 6.0)], L, E);
        let m = multiply(&[("F1", &f1), ("F2", &f2)]).unwrap();
        assert_eq!(m.abscissas, vec![0.0, 0.5, 1.0, 1.5, 2.0]);
        for (x, y) in m.abscissas.iter().zip(&m.ordinates) {
            assert!((y - 2.0 * x * x).abs() < 1e-14);
        }
        let g = fun(&[(0.0, 1.0), (2.0, 1.0)], E, E);
        let sup = envelope(&[("F1", &f1), ("G", &g)], true).unwrap();
        assert_eq!(sup.abscissas, vec![0.0, 1.0, 2.0]);
        assert_eq!(sup.ordinates, vec![1.0, 1.0, 2.0]);
        let inf = envelope(&[("F1", &f1), ("G", &g)], false).unwrap();
        assert_eq!(inf.ordinates, vec![0.0, 1.0, 1.0]);
        // No cut: F2 cannot be evaluated at 3 by F1 (excluded).
        assert!(envelope(&[("F1", &f1), ("F2", &f2)], true)
            .unwrap_err()
            .starts_with("F1:"));
    }
}
