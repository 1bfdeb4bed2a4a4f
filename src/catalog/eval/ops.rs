//! Python 3's operators on the values of a command file: arithmetic,
//! comparisons, truth, indexing, slicing and iteration.

use super::pyfmt::{float_repr, percent_format, type_name, MAX_TEXT};
use super::{concept_unknown, PyVal, SpVal, MAX_ITEMS};
use crate::diag::{Diagnostic, Span};
use crate::lang::ast::{BinOp, CmpOp, UnOp};

/// `True` and `False` are the integers 1 and 0 in arithmetic, as in Python.
fn int_of_bool(v: PyVal) -> PyVal {
    match v {
        PyVal::Bool(b) => PyVal::Int(b as i64),
        v => v,
    }
}

fn no_span(message: impl Into<String>) -> Diagnostic {
    Diagnostic::error(message)
}

pub fn unary(op: UnOp, x: PyVal) -> Result<PyVal, String> {
    if x == PyVal::Poison {
        return Ok(PyVal::Poison);
    }
    if op == UnOp::Not {
        return match truth(&x) {
            Ok(t) => Ok(PyVal::Bool(!t)),
            Err(d) => Err(d.message),
        };
    }
    Ok(match (op, int_of_bool(x)) {
        (UnOp::Neg, PyVal::Int(i)) => PyVal::Int(
            i.checked_neg()
                .ok_or_else(|| "integer overflow".to_string())?,
        ),
        (UnOp::Neg, PyVal::Real(r)) => PyVal::Real(-r),
        (UnOp::Pos, v @ (PyVal::Int(_) | PyVal::Real(_))) => v,
        (_, v) => {
            return Err(format!(
                "unary '{}' needs a number, not {}",
                if op == UnOp::Neg { "-" } else { "+" },
                v.describe()
            ))
        }
    })
}

fn repeat(items: &[SpVal], n: i64) -> Result<Vec<SpVal>, String> {
    let n = n.max(0) as usize;
    if items.len().saturating_mul(n) > MAX_ITEMS {
        return Err(format!("a sequence of more than {MAX_ITEMS} items"));
    }
    Ok((0..n).flat_map(|_| items.iter().cloned()).collect())
}

/// Python 3 arithmetic on numbers, `+` and `*` on texts, tuples and lists,
/// and `%` formatting of texts.
pub fn binary(op: BinOp, a: PyVal, b: PyVal) -> Result<PyVal, String> {
    use PyVal::*;
    let overflow = || "integer overflow".to_string();
    if let (Str(fmt), BinOp::Mod) = (&a, op) {
        return percent_format(fmt, &b).map(Str);
    }
    let (a, b) = (int_of_bool(a), int_of_bool(b));
    match (&a, &b) {
        (Int(x), Int(y)) => {
            let (x, y) = (*x, *y);
            Ok(match op {
                BinOp::Add => Int(x.checked_add(y).ok_or_else(overflow)?),
                BinOp::Sub => Int(x.checked_sub(y).ok_or_else(overflow)?),
                BinOp::Mul => Int(x.checked_mul(y).ok_or_else(overflow)?),
                BinOp::Div => {
                    if y == 0 {
                        return Err("division by zero".into());
                    }
                    Real(x as f64 / y as f64)
                }
                BinOp::FloorDiv | BinOp::Mod => {
                    if y == 0 {
                        return Err("integer division or modulo by zero".into());
                    }
                    let r = x.wrapping_rem(y);
                    if op == BinOp::Mod && y == -1 {
                        return Ok(Int(0));
                    }
                    let q = x.checked_div(y).ok_or_else(overflow)?;
                    let adjust = r != 0 && ((r < 0) != (y < 0));
                    if op == BinOp::FloorDiv {
                        Int(if adjust { q - 1 } else { q })
                    } else {
                        Int(if adjust { r + y } else { r })
                    }
                }
                BinOp::Pow => {
                    if y >= 0 {
                        let e = u32::try_from(y).map_err(|_| overflow())?;
                        Int(x.checked_pow(e).ok_or_else(overflow)?)
                    } else if x == 0 {
                        return Err("zero cannot be raised to a negative power".into());
                    } else {
                        Real((x as f64).powf(y as f64))
                    }
                }
            })
        }
        (Int(_) | Real(_), Int(_) | Real(_)) => {
            let f = |v: &PyVal| match v {
                Int(i) => *i as f64,
                Real(r) => *r,
                _ => unreachable!("numbers only"),
            };
            let (x, y) = (f(&a), f(&b));
            let r = match op {
                BinOp::Add => x + y,
                BinOp::Sub => x - y,
                BinOp::Mul => x * y,
                BinOp::Div => {
                    if y == 0.0 {
                        return Err("division by zero".into());
                    }
                    x / y
                }
                BinOp::FloorDiv | BinOp::Mod => {
                    if y == 0.0 {
                        return Err(if op == BinOp::Mod {
                            "float modulo by zero".into()
                        } else {
                            "float floor division by zero".into()
                        });
                    }
                    let (q, m) = crate::post::formula::py_divmod(x, y);
                    if op == BinOp::Mod {
                        m
                    } else {
                        q
                    }
                }
                BinOp::Pow => {
                    if x < 0.0 && y.fract() != 0.0 {
                        return Err(format!(
                            "{} ** {}: a negative number to a fractional power is complex",
                            float_repr(x),
                            float_repr(y)
                        ));
                    }
                    if x == 0.0 && y < 0.0 {
                        return Err("zero cannot be raised to a negative power".into());
                    }
                    x.powf(y)
                }
            };
            if !r.is_finite() {
                return Err(format!(
                    "the result of {} {} {} overflows",
                    float_repr(x),
                    op.symbol(),
                    float_repr(y)
                ));
            }
            Ok(Real(r))
        }
        (Str(x), Str(y)) if op == BinOp::Add => {
            if x.len() + y.len() > MAX_TEXT {
                return Err(format!("a text longer than {MAX_TEXT} bytes"));
            }
            Ok(Str(format!("{x}{y}")))
        }
        (Str(s), Int(n)) | (Int(n), Str(s)) if op == BinOp::Mul => {
            let n = (*n).max(0) as usize;
            if s.len().saturating_mul(n) > MAX_TEXT {
                return Err(format!("a text longer than {MAX_TEXT} bytes"));
            }
            Ok(Str(s.repeat(n)))
        }
        (Tuple(x), Tuple(y)) if op == BinOp::Add => {
            if x.len() + y.len() > MAX_ITEMS {
                return Err(format!("a tuple of more than {MAX_ITEMS} items"));
            }
            Ok(Tuple([x.as_slice(), y.as_slice()].concat()))
        }
        // The caller gives the result list a new identity.
        (List(_, x), List(_, y)) if op == BinOp::Add => {
            if x.len() + y.len() > MAX_ITEMS {
                return Err(format!("a list of more than {MAX_ITEMS} items"));
            }
            Ok(List(0, [x.as_slice(), y.as_slice()].concat()))
        }
        (Tuple(t), Int(n)) | (Int(n), Tuple(t)) if op == BinOp::Mul => Ok(Tuple(repeat(t, *n)?)),
        (List(_, t), Int(n)) | (Int(n), List(_, t)) if op == BinOp::Mul => {
            Ok(List(0, repeat(t, *n)?))
        }
        _ => Err(format!(
            "operator '{}' cannot combine {} and {}",
            op.symbol(),
            a.describe(),
            b.describe()
        )),
    }
}

/// Python's truth of a value.
pub fn truth(v: &PyVal) -> Result<bool, Diagnostic> {
    Ok(match v {
        PyVal::Int(i) => *i != 0,
        PyVal::Real(r) => *r != 0.0,
        PyVal::Bool(b) => *b,
        PyVal::Str(s) => !s.is_empty(),
        PyVal::None => false,
        PyVal::Tuple(t) | PyVal::List(_, t) => !t.is_empty(),
        PyVal::Range(..) => range_len(v) > 0,
        PyVal::Fact(_, kv) => !kv.is_empty(),
        PyVal::Module(_) | PyVal::Func(_) | PyVal::Iter(..) => true,
        PyVal::Concept { name, .. } | PyVal::Stale(name) => {
            return Err(
                concept_unknown(name, "a condition cannot test", Span::new(0, 0)).drop_span(),
            )
        }
        // Already reported where it was defined.
        PyVal::Poison => false,
    })
}

trait DropSpan {
    fn drop_span(self) -> Self;
}
impl DropSpan for Diagnostic {
    /// Lets the caller locate it (`at_if_none`).
    fn drop_span(mut self) -> Self {
        self.span = None;
        self
    }
}

fn num(v: &PyVal) -> Option<f64> {
    match v {
        PyVal::Int(i) => Some(*i as f64),
        PyVal::Real(r) => Some(*r),
        PyVal::Bool(b) => Some(*b as i64 as f64),
        _ => None,
    }
}

/// `a == b` in Python; `Err` for concepts, whose identity aster does not
/// model.
pub fn equal(a: &PyVal, b: &PyVal) -> Result<bool, String> {
    use PyVal::*;
    Ok(match (a, b) {
        (Concept { name, .. }, _) | (_, Concept { name, .. }) => {
            return Err(format!(
                "comparing the concept {name}: concepts are compared by their content, which is not known before the study runs"
            ))
        }
        (Int(x), Int(y)) => x == y,
        _ if num(a).is_some() && num(b).is_some() => {
            // Exact for integers beyond 2**53 compared with reals too.
            match (int_of_bool(a.clone()), int_of_bool(b.clone())) {
                (Int(x), Real(y)) | (Real(y), Int(x)) => (x as f64) == y && (y as i128) == x as i128,
                _ => num(a) == num(b),
            }
        }
        (Str(x), Str(y)) => x == y,
        (None, None) => true,
        (Tuple(x), Tuple(y)) | (List(_, x), List(_, y)) => {
            x.len() == y.len()
                && x.iter()
                    .zip(y)
                    .map(|(p, q)| equal(&p.v, &q.v))
                    .collect::<Result<Vec<bool>, String>>()?
                    .into_iter()
                    .all(|t| t)
        }
        (Range(..), Range(..)) => {
            let (x, y) = (range_items(a)?, range_items(b)?);
            x == y
        }
        (Module(x), Module(y)) => x == y,
        (Func(x), Func(y)) => x == y,
        (Fact(_, x), Fact(_, y)) => {
            x.len() == y.len()
                && x.iter().all(|(k, v)| {
                    y.iter()
                        .find(|(k2, _)| k2.name == k.name)
                        .is_some_and(|(_, v2)| equal(&v.v, &v2.v).unwrap_or(false))
                })
        }
        _ => false,
    })
}

fn range_items(v: &PyVal) -> Result<Vec<i64>, String> {
    let PyVal::Range(a, _, s) = *v else {
        return Ok(Vec::new());
    };
    let n = range_len(v);
    if n > MAX_ITEMS as u128 {
        return Err(format!("a range of more than {MAX_ITEMS} values"));
    }
    Ok((0..n as i64).map(|i| a + i * s).collect())
}

/// The number of values of a range (as Python computes it, without
/// overflow).
pub fn range_len(v: &PyVal) -> u128 {
    let PyVal::Range(a, b, s) = *v else { return 0 };
    let (a, b, s) = (a as i128, b as i128, s as i128);
    if s > 0 && a < b {
        ((b - a - 1) / s + 1) as u128
    } else if s < 0 && a > b {
        ((a - b - 1) / (-s) + 1) as u128
    } else {
        0
    }
}

/// `a < b` and the others: numbers with numbers, texts with texts,
/// tuples with tuples and lists with lists (item by item), as Python.
fn less(a: &PyVal, b: &PyVal, op: &str) -> Result<std::cmp::Ordering, String> {
    use std::cmp::Ordering;
    use PyVal::*;
    if let (Some(x), Some(y)) = (num(a), num(b)) {
        if let (Int(x), Int(y)) = (int_of_bool(a.clone()), int_of_bool(b.clone())) {
            return Ok(x.cmp(&y));
        }
        return Ok(x.partial_cmp(&y).unwrap_or(Ordering::Equal));
    }
    match (a, b) {
        (Str(x), Str(y)) => Ok(x.cmp(y)),
        (Tuple(x), Tuple(y)) | (List(_, x), List(_, y)) => {
            for (p, q) in x.iter().zip(y) {
                if !equal(&p.v, &q.v)? {
                    return less(&p.v, &q.v, op);
                }
            }
            Ok(x.len().cmp(&y.len()))
        }
        (Concept { name, .. }, _) | (_, Concept { name, .. }) => Err(format!(
            "comparing the concept {name}: its content is not known before the study runs"
        )),
        _ => Err(format!(
            "'{op}' is not supported between {} and {}",
            a.describe(),
            b.describe()
        )),
    }
}

pub fn compare(op: CmpOp, a: &PyVal, b: &PyVal) -> Result<bool, String> {
    use std::cmp::Ordering::*;
    Ok(match op {
        CmpOp::Eq => equal(a, b)?,
        CmpOp::Ne => !equal(a, b)?,
        CmpOp::Lt => less(a, b, "<")? == Less,
        CmpOp::Le => less(a, b, "<=")? != Greater,
        CmpOp::Gt => less(a, b, ">")? == Greater,
        CmpOp::Ge => less(a, b, ">=")? != Less,
        CmpOp::In | CmpOp::NotIn => {
            let found = match b {
                PyVal::Str(s) => match a {
                    PyVal::Str(x) => s.contains(x.as_str()),
                    _ => {
                        return Err(format!(
                            "'in <text>' needs a text on its left, not {}",
                            a.describe()
                        ))
                    }
                },
                PyVal::Tuple(t) | PyVal::List(_, t) => {
                    let mut found = false;
                    for x in t {
                        if equal(a, &x.v)? {
                            found = true;
                            break;
                        }
                    }
                    found
                }
                PyVal::Range(start, _, step) => match int_of_bool(a.clone()) {
                    PyVal::Int(x) => {
                        let (x, start, step) = (x as i128, *start as i128, *step as i128);
                        let k = (x - start) / step;
                        (x - start) % step == 0 && k >= 0 && (k as u128) < range_len(b)
                    }
                    _ => false,
                },
                PyVal::Fact(_, kv) => match a {
                    PyVal::Str(x) => kv.iter().any(|(k, _)| &k.name == x),
                    _ => false,
                },
                PyVal::Concept { name, .. } => {
                    return Err(format!(
                        "'in' reads the concept {name}, whose content is not known before the study runs"
                    ))
                }
                _ => {
                    return Err(format!(
                        "'in' needs a tuple, a list, a range or a text on its right, not {}",
                        b.describe()
                    ))
                }
            };
            found == (op == CmpOp::In)
        }
    })
}

/// The items a `for` or a comprehension goes through.
pub fn iterate(v: &PyVal, span: Span) -> Result<Vec<SpVal>, Diagnostic> {
    let sp = |v| SpVal { v, span };
    Ok(match v {
        PyVal::Tuple(t) | PyVal::List(_, t) | PyVal::Iter(_, t) => t.clone(),
        PyVal::Str(s) => s.chars().map(|c| sp(PyVal::Str(c.to_string()))).collect(),
        PyVal::Range(..) => range_items(v)
            .map_err(|m| no_span(m).at(span))?
            .into_iter()
            .map(|i| sp(PyVal::Int(i)))
            .collect(),
        PyVal::Concept { name, .. } => {
            return Err(concept_unknown(name, "a loop cannot go through", span))
        }
        v => {
            return Err(no_span(format!(
                "cannot loop over {}: it is not a tuple, a list, a range or a text",
                v.describe()
            ))
            .at(span))
        }
    })
}

fn index_value(i: &SpVal, len: usize) -> Result<Option<usize>, Diagnostic> {
    let k = match int_of_bool(i.v.clone()) {
        PyVal::Int(k) => k,
        v => {
            return Err(
                no_span(format!("an index must be an integer, not {}", v.describe())).at(i.span),
            )
        }
    };
    let k = if k < 0 {
        k as i128 + len as i128
    } else {
        k as i128
    };
    Ok((0..len as i128).contains(&k).then_some(k as usize))
}

/// `a[i]`
pub fn index(a: &PyVal, i: &SpVal) -> Result<PyVal, Diagnostic> {
    let out_of_range = |len: usize, what: &str| {
        no_span(format!(
            "index {} is out of range: the {what} has {len} item{}",
            match &i.v {
                PyVal::Int(k) => k.to_string(),
                v => v.describe(),
            },
            if len == 1 { "" } else { "s" }
        ))
        .at(i.span)
    };
    match a {
        PyVal::Tuple(t) | PyVal::List(_, t) => {
            let what = type_name(a);
            match index_value(i, t.len())? {
                Some(k) => Ok(t[k].v.clone()),
                None => Err(out_of_range(t.len(), what)),
            }
        }
        PyVal::Str(s) => {
            let n = s.chars().count();
            match index_value(i, n)? {
                Some(k) => Ok(PyVal::Str(
                    s.chars().nth(k).expect("index checked").to_string(),
                )),
                None => Err(out_of_range(n, "text")),
            }
        }
        PyVal::Range(start, _, step) => {
            let n = range_len(a).min(usize::MAX as u128) as usize;
            match index_value(i, n)? {
                Some(k) => Ok(PyVal::Int(start + k as i64 * step)),
                None => Err(out_of_range(n, "range")),
            }
        }
        PyVal::Fact(_, kv) => match &i.v {
            PyVal::Str(key) => kv
                .iter()
                .find(|(k, _)| &k.name == key)
                .map(|(_, v)| v.v.clone())
                .ok_or_else(|| no_span(format!("the dict has no key '{key}'")).at(i.span)),
            v => Err(no_span(format!(
                "a dict's item is read with its key, a text, not {}",
                v.describe()
            ))
            .at(i.span)),
        },
        PyVal::Concept { name, .. } => Err(concept_unknown(name, "indexing reads", i.span)),
        v => Err(no_span(format!("{} cannot be indexed", v.describe()))),
    }
}

/// Python's slice bounds (PySlice_AdjustIndices): the indices taken.
/// Python's adjusted slice (PySlice_AdjustIndices): the first index, the
/// index not reached, and the step.
fn slice_bounds(len: i128, bounds: [Option<&SpVal>; 3]) -> Result<(i128, i128, i128), Diagnostic> {
    let int = |b: Option<&SpVal>| -> Result<Option<i128>, Diagnostic> {
        match b.map(|x| (int_of_bool(x.v.clone()), x.span)) {
            None | Some((PyVal::None, _)) => Ok(None),
            Some((PyVal::Int(k), _)) => Ok(Some(k as i128)),
            Some((v, span)) => Err(no_span(format!(
                "a slice bound must be an integer or None, not {}",
                v.describe()
            ))
            .at(span)),
        }
    };
    let [l, u, s] = bounds;
    let step = int(s)?.unwrap_or(1);
    if step == 0 {
        return Err(no_span("slice step cannot be zero").at(s.map_or(Span::new(0, 0), |x| x.span)));
    }
    let n = len;
    let adjust = |k: Option<i128>, default: i128| -> i128 {
        match k {
            None => default,
            Some(k) => {
                let k = if k < 0 { k + n } else { k };
                if step > 0 {
                    k.clamp(0, n)
                } else {
                    k.clamp(-1, n - 1)
                }
            }
        }
    };
    let (lo, hi) = if step > 0 {
        (adjust(int(l)?, 0), adjust(int(u)?, n))
    } else {
        (adjust(int(l)?, n - 1), adjust(int(u)?, -1))
    };
    Ok((lo, hi, step))
}

/// The indices a slice takes, in order.
fn slice_indices(len: usize, bounds: [Option<&SpVal>; 3]) -> Result<Vec<usize>, Diagnostic> {
    let (lo, hi, step) = slice_bounds(len as i128, bounds)?;
    let mut out = Vec::new();
    let mut k = lo;
    while (step > 0 && k < hi) || (step < 0 && k > hi) {
        out.push(k as usize);
        k += step;
    }
    Ok(out)
}

/// `a[l:u:s]`
pub fn slice(a: &PyVal, bounds: [Option<&SpVal>; 3]) -> Result<PyVal, Diagnostic> {
    match a {
        PyVal::Tuple(t) => Ok(PyVal::Tuple(
            slice_indices(t.len(), bounds)?
                .into_iter()
                .map(|k| t[k].clone())
                .collect(),
        )),
        PyVal::List(_, t) => Ok(PyVal::List(
            0,
            slice_indices(t.len(), bounds)?
                .into_iter()
                .map(|k| t[k].clone())
                .collect(),
        )),
        PyVal::Str(s) => {
            let chars: Vec<char> = s.chars().collect();
            Ok(PyVal::Str(
                slice_indices(chars.len(), bounds)?
                    .into_iter()
                    .map(|k| chars[k])
                    .collect(),
            ))
        }
        PyVal::Range(start, _, step) => {
            // range(a, b, s)[i:j:k] is range(a + i s, a + j s, s k), as
            // Python computes it, without listing the values.
            let (lo, hi, k) = slice_bounds(range_len(a) as i128, bounds)?;
            let (start, step) = (*start as i128, *step as i128);
            let fit = |x: i128| {
                i64::try_from(x).map_err(|_| no_span("integer overflow in a range slice"))
            };
            Ok(PyVal::Range(
                fit(start + lo * step)?,
                fit(start + hi * step)?,
                fit(step * k)?,
            ))
        }
        PyVal::Concept { name, .. } => {
            Err(concept_unknown(name, "slicing reads", Span::new(0, 0)).drop_span())
        }
        v => Err(no_span(format!("{} cannot be sliced", v.describe()))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn python_number_rules() {
        assert_eq!(
            binary(BinOp::Div, PyVal::Int(1), PyVal::Int(2)),
            Ok(PyVal::Real(0.5))
        );
        assert_eq!(
            binary(BinOp::Pow, PyVal::Int(2), PyVal::Int(10)),
            Ok(PyVal::Int(1024))
        );
        assert_eq!(
            binary(BinOp::Pow, PyVal::Int(2), PyVal::Int(-1)),
            Ok(PyVal::Real(0.5))
        );
        assert!(binary(BinOp::Div, PyVal::Real(1.0), PyVal::Int(0)).is_err());
        assert!(binary(BinOp::Mul, PyVal::Int(i64::MAX), PyVal::Int(2)).is_err());
        // Large reals are named as Python writes them, not in 300 digits.
        assert_eq!(
            binary(BinOp::Mul, PyVal::Real(1e305), PyVal::Real(1e305)),
            Err("the result of 1e+305 * 1e+305 overflows".to_string())
        );
        assert!(binary(BinOp::Add, PyVal::Str("a".into()), PyVal::Int(1)).is_err());
    }

    /// Expected values are CPython 3's: `//` and `%` floor, the remainder
    /// takes the divisor's sign.
    #[test]
    fn floor_division_and_modulo() {
        let i = |op, a, b| binary(op, PyVal::Int(a), PyVal::Int(b)).unwrap();
        assert_eq!(i(BinOp::FloorDiv, 7, 2), PyVal::Int(3));
        assert_eq!(i(BinOp::FloorDiv, -7, 2), PyVal::Int(-4));
        assert_eq!(i(BinOp::Mod, -7, 2), PyVal::Int(1));
        assert_eq!(i(BinOp::Mod, 7, -2), PyVal::Int(-1));
        assert_eq!(i(BinOp::Mod, i64::MIN, -1), PyVal::Int(0));
        assert!(binary(BinOp::FloorDiv, PyVal::Int(i64::MIN), PyVal::Int(-1)).is_err());
        assert!(binary(BinOp::Mod, PyVal::Int(1), PyVal::Int(0)).is_err());
        let r = |op, a, b| binary(op, PyVal::Real(a), PyVal::Real(b)).unwrap();
        assert_eq!(r(BinOp::FloorDiv, 7.5, 2.0), PyVal::Real(3.0));
        assert_eq!(r(BinOp::Mod, -7.5, 2.0), PyVal::Real(0.5));
        assert_eq!(r(BinOp::Mod, 7.5, -2.0), PyVal::Real(-0.5));
        assert_eq!(r(BinOp::FloorDiv, -0.5, 2.0), PyVal::Real(-1.0));
        assert_eq!(r(BinOp::Mod, 5.5, -2.0), PyVal::Real(-0.5));
        // fmod is exact: 0.1 - 10*0.01 in the binary values.
        assert_eq!(r(BinOp::Mod, 0.1, 0.01), PyVal::Real(3.469446951953614e-18));
    }

    #[test]
    fn slices_follow_python() {
        let span = Span::new(0, 0);
        let list: Vec<SpVal> = (0..5)
            .map(|k| SpVal {
                v: PyVal::Int(k),
                span,
            })
            .collect();
        let t = PyVal::Tuple(list);
        let b = |k: i64| SpVal {
            v: PyVal::Int(k),
            span,
        };
        let got = |l: Option<i64>, u: Option<i64>, s: Option<i64>| -> Vec<i64> {
            let (l, u, s) = (l.map(b), u.map(b), s.map(b));
            match slice(&t, [l.as_ref(), u.as_ref(), s.as_ref()]).unwrap() {
                PyVal::Tuple(items) => items
                    .iter()
                    .map(|x| match x.v {
                        PyVal::Int(k) => k,
                        _ => panic!(),
                    })
                    .collect(),
                _ => panic!(),
            }
        };
        assert_eq!(got(Some(1), Some(3), None), vec![1, 2]);
        assert_eq!(got(None, None, Some(-1)), vec![4, 3, 2, 1, 0]);
        assert_eq!(got(Some(-2), None, None), vec![3, 4]);
        assert_eq!(got(Some(10), None, None), Vec::<i64>::new());
        assert_eq!(got(None, Some(-10), Some(-1)), vec![4, 3, 2, 1, 0]);
        assert_eq!(got(Some(3), Some(0), Some(-2)), vec![3, 1]);
        let r = slice(
            &PyVal::Range(0, 10, 1),
            [Some(&b(2)), Some(&b(8)), Some(&b(3))],
        )
        .unwrap();
        // CPython: range(10)[2:8:3] == range(2, 8, 3), range(0, 20, 2)[::-1]
        // == range(18, -2, -2), range(10**18)[-2:] == range(10**18 - 2, 10**18).
        assert_eq!(r, PyVal::Range(2, 8, 3));
        assert_eq!(range_items(&r).unwrap(), vec![2, 5]);
        let r = slice(&PyVal::Range(0, 20, 2), [None, None, Some(&b(-1))]).unwrap();
        assert_eq!(r, PyVal::Range(18, -2, -2));
        let big = 1_000_000_000_000_000_000;
        let r = slice(&PyVal::Range(0, big, 1), [Some(&b(-2)), None, None]).unwrap();
        assert_eq!(r, PyVal::Range(big - 2, big, 1));
    }
}
