//! Python's builtins that command files use (`len`, `range`, `str`, `min`,
//! `round`...), and the modules `math` and a small part of `numpy`.

use super::ops::{self, range_len};
use super::pyfmt::py_str;
use super::{Env, PyVal, SpVal};
use crate::diag::{closest, Diagnostic, Span};
use crate::lang::ast::{Arg, Ident};

pub const BUILTINS: [&str; 16] = [
    "int",
    "float",
    "abs",
    "min",
    "max",
    "len",
    "range",
    "str",
    "sum",
    "round",
    "list",
    "tuple",
    "bool",
    "repr",
    "enumerate",
    "zip",
];

pub fn is_builtin(name: &str) -> bool {
    BUILTINS.contains(&name)
}

/// The functions and constants of `math` that command files may use.
const MATH: &[&str] = &[
    "sqrt", "exp", "log", "log10", "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "pow",
    "fabs", "floor", "ceil", "sinh", "cosh", "tanh", "hypot", "degrees", "radians", "pi", "e",
];

/// A function or constant of `math` that command files may use.
pub fn is_math(name: &str) -> bool {
    MATH.contains(&name)
}

/// The part of numpy that aster has: scalar functions whose result is the
/// same float as Python's math gives. Arrays (np.array, np.linspace...)
/// are refused: their printing and arithmetic differ from lists.
const NUMPY: &[&str] = &[
    "sqrt", "exp", "log", "log10", "sin", "cos", "tan", "arcsin", "arccos", "arctan", "arctan2",
    "abs", "fabs", "floor", "ceil", "sinh", "cosh", "tanh", "hypot", "degrees", "radians", "pi",
    "e",
];

/// The modules a command file may import, by their Python name.
pub fn module(name: &str) -> Option<&'static str> {
    match name {
        "math" => Some("math"),
        "numpy" => Some("numpy"),
        _ => None,
    }
}

/// The names `from <module> import *` brings (numpy's star import is
/// refused: it would bring hundreds of names aster does not have).
pub fn star_names(module: &'static str) -> &'static [&'static str] {
    match module {
        "math" => MATH,
        _ => &[],
    }
}

fn qualified(module: &'static str, name: &str) -> Option<&'static str> {
    let list = if module == "math" { MATH } else { NUMPY };
    let n = list.iter().find(|n| **n == name)?;
    // The full names are built once per name; leaking them gives the
    // 'static the value needs (a few dozen bytes, bounded by the list).
    static NAMES: std::sync::OnceLock<Vec<String>> = std::sync::OnceLock::new();
    let all = NAMES.get_or_init(|| {
        MATH.iter()
            .map(|n| format!("math.{n}"))
            .chain(NUMPY.iter().map(|n| format!("numpy.{n}")))
            .collect()
    });
    let full = format!("{module}.{n}");
    all.iter().find(|s| **s == full).map(|s| s.as_str())
}

/// What `from code_aster import CA` binds: code_aster 16+'s object
/// interface, none of whose parts aster has.
pub const CODE_ASTER_CA: &str = "code_aster.CA";

/// `module.name`: a constant or a function value.
pub fn module_attr(module: &'static str, attr: &Ident) -> Result<PyVal, Diagnostic> {
    if module == CODE_ASTER_CA {
        let d = Diagnostic::error(format!(
            "CA.{} (code_aster's object interface) is not available in command files",
            attr.name
        ))
        .at(attr.span);
        return Err(match attr.name.as_str() {
            "init" => d.note("CA.init(...) starts a study in code_aster 17: write DEBUT(...) instead, e.g. DEBUT(CODE='OUI', ERREUR=_F(ALARME='EXCEPTION')) for a test"),
            "TestCase" => d.note("CA.TestCase checks values that exist only when the study runs: use TEST_RESU, TEST_TABLE or TEST_FONCTION"),
            _ => d.note("aster runs the commands of the file; code_aster's Python objects (CA.Mesh, CA.TestCase...) are not there"),
        });
    }
    match (attr.name.as_str(), qualified(module, &attr.name)) {
        ("pi", Some(_)) => Ok(PyVal::Real(std::f64::consts::PI)),
        ("e", Some(_)) => Ok(PyVal::Real(std::f64::consts::E)),
        (_, Some(f)) => Ok(PyVal::Func(f)),
        (name, None) => {
            let list = if module == "math" { MATH } else { NUMPY };
            let mut d =
                Diagnostic::error(format!("{module}.{name} is not available in command files"))
                    .at(attr.span)
                    .note(format!("{module} offers here: {}", list.join(", ")));
            if module == "numpy" {
                d = d.note("numpy arrays are not supported; use lists and list comprehensions");
            }
            d.suggestion = closest(name, list);
            Err(d)
        }
    }
}

fn err(message: impl Into<String>, span: Span) -> Diagnostic {
    Diagnostic::error(message).at(span)
}

fn number(f: &str, v: &SpVal) -> Result<f64, Diagnostic> {
    match v.v {
        PyVal::Int(i) => Ok(i as f64),
        PyVal::Real(r) => Ok(r),
        PyVal::Bool(b) => Ok(b as i64 as f64),
        ref o => Err(err(
            format!("{f}() needs a number, not {}", o.describe()),
            v.span,
        )),
    }
}

/// A float result of a math function: Python raises where it would not
/// be finite ("math domain error", "math range error").
fn finite(f: &str, x: f64, span: Span) -> Result<PyVal, Diagnostic> {
    if x.is_finite() {
        Ok(PyVal::Real(x))
    } else {
        Err(err(
            format!("{f}(): math domain or range error (the result is not a finite number)"),
            span,
        ))
    }
}

fn to_int(f: &str, x: f64, span: Span) -> Result<PyVal, Diagnostic> {
    if !x.is_finite() || x.abs() >= 9.2e18 {
        return Err(err(format!("{f}() of {x} does not fit an integer"), span));
    }
    Ok(PyVal::Int(x as i64))
}

impl Env {
    /// Evaluates positional arguments (builtins take no keywords).
    pub(super) fn positional(
        &self,
        f: &str,
        args: &[Arg],
        is_command: &dyn Fn(&str) -> bool,
    ) -> Result<Vec<SpVal>, Diagnostic> {
        let mut vals = Vec::new();
        for a in args {
            if a.name.is_some() || a.unpack {
                return Err(
                    Diagnostic::error(format!("{f}() takes positional arguments only")).at(a.span),
                );
            }
            vals.push(self.eval(&a.value, is_command)?);
        }
        Ok(vals)
    }

    /// Calls a function value of a module (`math.sqrt`, or `sqrt` after
    /// `from math import sqrt`).
    pub(super) fn call_value(
        &self,
        f: &PyVal,
        name: &Ident,
        args: &[Arg],
        span: Span,
        is_command: &dyn Fn(&str) -> bool,
    ) -> Result<PyVal, Diagnostic> {
        let PyVal::Func(full) = f else {
            return Err(err(format!("{} is not callable", f.describe()), name.span));
        };
        let vals = self.positional(full, args, is_command)?;
        if vals.iter().any(|v| v.v == PyVal::Poison) {
            return Ok(PyVal::Poison);
        }
        let (module, fname) = full.split_once('.').expect("qualified name");
        let two = matches!(fname, "atan2" | "arctan2" | "pow" | "hypot");
        let arity_ok = match fname {
            "log" if module == "math" => (1..=2).contains(&vals.len()),
            _ if two => vals.len() == 2,
            _ => vals.len() == 1,
        };
        if !arity_ok {
            return Err(err(
                format!(
                    "{full}() takes {} argument{} ({} given)",
                    if two { "2" } else { "1" },
                    if two { "s" } else { "" },
                    vals.len()
                ),
                span,
            ));
        }
        let x = number(full, &vals[0])?;
        let y = match vals.get(1) {
            Some(v) => Some(number(full, v)?),
            None => None,
        };
        let y2 = y.unwrap_or(0.0);
        let domain = |ok: bool| -> Result<(), Diagnostic> {
            if ok {
                Ok(())
            } else {
                Err(err(
                    format!("{full}(): math domain error"),
                    span,
                )
                .note(if module == "numpy" {
                    "numpy would give nan with a warning; aster refuses values that are not finite"
                } else {
                    "as in Python, the argument is outside the function's domain"
                }))
            }
        };
        let r = match fname {
            "sqrt" => {
                domain(x >= 0.0)?;
                x.sqrt()
            }
            "exp" => x.exp(),
            "log" => {
                domain(x > 0.0)?;
                match y {
                    Some(b) => {
                        domain(b > 0.0 && b != 1.0)?;
                        x.ln() / b.ln()
                    }
                    None => x.ln(),
                }
            }
            "log10" => {
                domain(x > 0.0)?;
                x.log10()
            }
            "sin" => x.sin(),
            "cos" => x.cos(),
            "tan" => x.tan(),
            "asin" | "arcsin" => {
                domain((-1.0..=1.0).contains(&x))?;
                x.asin()
            }
            "acos" | "arccos" => {
                domain((-1.0..=1.0).contains(&x))?;
                x.acos()
            }
            "atan" | "arctan" => x.atan(),
            "atan2" | "arctan2" => x.atan2(y2),
            "pow" => {
                domain(!(x < 0.0 && y2.fract() != 0.0 || x == 0.0 && y2 < 0.0))?;
                x.powf(y2)
            }
            "hypot" => x.hypot(y2),
            "sinh" => x.sinh(),
            "cosh" => x.cosh(),
            "tanh" => x.tanh(),
            "degrees" => x.to_degrees(),
            "radians" => x.to_radians(),
            "fabs" => x.abs(),
            "abs" => {
                // np.abs keeps integers integers.
                if let PyVal::Int(i) = vals[0].v {
                    return i
                        .checked_abs()
                        .map(PyVal::Int)
                        .ok_or_else(|| err("integer overflow", span));
                }
                x.abs()
            }
            // math.floor/ceil give integers (Python 3); numpy's give floats.
            "floor" if module == "math" => return to_int(full, x.floor(), span),
            "ceil" if module == "math" => return to_int(full, x.ceil(), span),
            "floor" => x.floor(),
            "ceil" => x.ceil(),
            _ => unreachable!("every function of MATH and NUMPY is handled: {full}"),
        };
        finite(full, r, span)
    }

    pub(super) fn builtin(
        &self,
        func: &Ident,
        args: &[Arg],
        span: Span,
        is_command: &dyn Fn(&str) -> bool,
    ) -> Result<PyVal, Diagnostic> {
        let f = func.name.as_str();
        let mut vals = self.positional(f, args, is_command)?;
        if vals.iter().any(|v| v.v == PyVal::Poison) {
            return Ok(PyVal::Poison);
        }
        let arity = |lo: usize, hi: usize| -> Result<(), Diagnostic> {
            if (lo..=hi).contains(&vals.len()) {
                return Ok(());
            }
            let want = if lo == hi {
                format!("exactly {lo} argument{}", if lo == 1 { "" } else { "s" })
            } else {
                format!("{lo} to {hi} arguments")
            };
            Err(err(
                format!("{f}() takes {want} ({} given)", vals.len()),
                span,
            ))
        };
        let num = |v: &SpVal| number(f, v);
        match f {
            "int" | "float" | "abs" => {
                if vals.len() != 1 {
                    return Err(Diagnostic::error(format!(
                        "{f}() takes exactly one argument ({} given)",
                        vals.len()
                    ))
                    .at(span));
                }
                let x = &vals[0];
                Ok(match (f, &x.v) {
                    ("int", PyVal::Int(i)) => PyVal::Int(*i),
                    ("int", PyVal::Bool(b)) => PyVal::Int(*b as i64),
                    ("int", PyVal::Real(r)) => {
                        if !r.is_finite() || r.abs() >= 9.2e18 {
                            return Err(Diagnostic::error(format!(
                                "int() of {r} does not fit an integer"
                            ))
                            .at(span));
                        }
                        PyVal::Int(r.trunc() as i64)
                    }
                    ("int", PyVal::Str(s)) => PyVal::Int(s.trim().parse().map_err(|_| {
                        Diagnostic::error(format!("int() cannot convert '{s}'")).at(x.span)
                    })?),
                    ("float", PyVal::Str(s)) => {
                        let r: f64 = s.trim().parse().map_err(|_| {
                            Diagnostic::error(format!("float() cannot convert '{s}'")).at(x.span)
                        })?;
                        // Python accepts 'nan' and 'inf'; no keyword of a
                        // study means anything with them, and a NaN would
                        // pass every bound check (comparisons are false).
                        if !r.is_finite() {
                            return Err(Diagnostic::error(format!(
                                "float('{s}') is not a finite number"
                            ))
                            .at(x.span));
                        }
                        PyVal::Real(r)
                    }
                    ("float", _) => PyVal::Real(num(x)?),
                    ("abs", PyVal::Int(i)) => PyVal::Int(
                        i.checked_abs()
                            .ok_or_else(|| Diagnostic::error("integer overflow").at(span))?,
                    ),
                    ("abs", PyVal::Bool(b)) => PyVal::Int(*b as i64),
                    ("abs", _) => PyVal::Real(num(x)?.abs()),
                    _ => return Err(num(x).unwrap_err()),
                })
            }
            "len" => {
                arity(1, 1)?;
                let n = match &vals[0].v {
                    PyVal::Str(s) => s.chars().count(),
                    PyVal::Tuple(t) | PyVal::List(_, t) => t.len(),
                    PyVal::Fact(_, kv) => kv.len(),
                    r @ PyVal::Range(..) => range_len(r).min(i64::MAX as u128) as usize,
                    PyVal::Concept { name, .. } => {
                        return Err(super::concept_unknown(name, "len() reads", vals[0].span))
                    }
                    v => return Err(err(format!("{} has no len()", v.describe()), vals[0].span)),
                };
                Ok(PyVal::Int(n as i64))
            }
            "range" => {
                arity(1, 3)?;
                let mut ints = Vec::new();
                for v in &vals {
                    match v.v {
                        PyVal::Int(i) => ints.push(i),
                        PyVal::Bool(b) => ints.push(b as i64),
                        ref o => {
                            return Err(err(
                                format!("range() takes integers, not {}", o.describe()),
                                v.span,
                            ))
                        }
                    }
                }
                let (a, b, s) = match ints[..] {
                    [b] => (0, b, 1),
                    [a, b] => (a, b, 1),
                    [a, b, s] => (a, b, s),
                    _ => unreachable!("arity checked"),
                };
                if s == 0 {
                    return Err(err("range() step must not be zero", vals[2].span));
                }
                Ok(PyVal::Range(a, b, s))
            }
            "str" | "repr" => {
                arity(1, 1)?;
                let s = if f == "str" {
                    py_str(&vals[0].v)
                } else {
                    super::pyfmt::py_repr(&vals[0].v)
                };
                s.map(PyVal::Str).map_err(|m| err(m, vals[0].span))
            }
            "enumerate" => {
                arity(1, 2)?;
                let start = match vals.get(1).map(|v| &v.v) {
                    None => 0,
                    Some(PyVal::Int(i)) => *i,
                    Some(o) => {
                        return Err(err(
                            format!("enumerate() starts at an integer, not {}", o.describe()),
                            vals[1].span,
                        ))
                    }
                };
                let items = self.iterate(&vals[0])?;
                let mut out = Vec::with_capacity(items.len());
                for (k, x) in items.into_iter().enumerate() {
                    let i = start
                        .checked_add(k as i64)
                        .ok_or_else(|| err("integer overflow", span))?;
                    let span = x.span;
                    out.push(SpVal {
                        v: PyVal::Tuple(vec![
                            SpVal {
                                v: PyVal::Int(i),
                                span,
                            },
                            x,
                        ]),
                        span,
                    });
                }
                Ok(PyVal::Iter("enumerate", out))
            }
            "zip" => {
                let mut columns = Vec::with_capacity(vals.len());
                for v in &vals {
                    columns.push(self.iterate(v)?);
                }
                let n = columns.iter().map(Vec::len).min().unwrap_or(0);
                let out = (0..n)
                    .map(|k| SpVal {
                        v: PyVal::Tuple(columns.iter().map(|c| c[k].clone()).collect()),
                        span,
                    })
                    .collect();
                Ok(PyVal::Iter("zip", out))
            }
            "bool" => {
                arity(1, 1)?;
                Ok(PyVal::Bool(self.truth(&vals[0])?))
            }
            "list" | "tuple" => {
                arity(0, 1)?;
                let items = match vals.first() {
                    Some(v) => self.iterate(v)?,
                    None => Vec::new(),
                };
                Ok(if f == "list" {
                    self.new_list(items)
                } else {
                    PyVal::Tuple(items)
                })
            }
            "sum" => {
                arity(1, 2)?;
                let mut acc = vals.get(1).map_or(PyVal::Int(0), |v| v.v.clone());
                if matches!(acc, PyVal::Str(_)) {
                    return Err(err("sum() can't sum texts: use ''.join(...) or +", span));
                }
                for x in self.iterate(&vals[0])? {
                    if matches!(x.v, PyVal::Str(_)) {
                        return Err(err("sum() can't sum texts", x.span));
                    }
                    acc = ops::binary(crate::lang::ast::BinOp::Add, acc, x.v)
                        .map_err(|m| err(format!("sum(): {m}"), span))?;
                }
                Ok(acc)
            }
            "round" => {
                arity(1, 2)?;
                let nd = match vals.get(1).map(|v| &v.v) {
                    None | Some(PyVal::None) => None,
                    Some(PyVal::Int(n)) => Some(*n),
                    Some(o) => {
                        return Err(err(
                            format!(
                                "round() takes an integer number of digits, not {}",
                                o.describe()
                            ),
                            vals[1].span,
                        ))
                    }
                };
                match (&vals[0].v, nd) {
                    (PyVal::Int(i), None) => Ok(PyVal::Int(*i)),
                    (PyVal::Bool(b), None) => Ok(PyVal::Int(*b as i64)),
                    (PyVal::Int(i), Some(n)) if n >= 0 => Ok(PyVal::Int(*i)),
                    (PyVal::Int(i), Some(n)) => {
                        // Half to even on the integer, as Python.
                        let Some(p) = 10i64.checked_pow((-n).min(19) as u32) else {
                            return Ok(PyVal::Int(0));
                        };
                        let (q, r) = (i.div_euclid(p), i.rem_euclid(p));
                        let up = 2 * (r as i128) > p as i128
                            || (2 * (r as i128) == p as i128 && q % 2 != 0);
                        let q = if up { q + 1 } else { q };
                        q.checked_mul(p)
                            .map(PyVal::Int)
                            .ok_or_else(|| err("integer overflow", span))
                    }
                    (_, None) => {
                        let x = num(&vals[0])?;
                        to_int("round", x.round_ties_even(), span)
                    }
                    (_, Some(n)) => {
                        let x = num(&vals[0])?;
                        let r = if n >= 0 {
                            // Formatting rounds the exact binary value half
                            // to even, as Python's round() does.
                            format!("{:.*}", n.min(400) as usize, x)
                                .parse::<f64>()
                                .unwrap_or(x)
                        } else {
                            let p = 10f64.powi((-n).min(400) as i32);
                            (x / p).round_ties_even() * p
                        };
                        finite("round", r, span)
                    }
                }
            }
            // min and max
            _ => {
                if vals.is_empty() {
                    return Err(
                        Diagnostic::error(format!("{f}() needs at least one argument")).at(span),
                    );
                }
                // min/max of a single sequence work on its items, as in
                // Python.
                if vals.len() == 1
                    && matches!(
                        vals[0].v,
                        PyVal::Tuple(_) | PyVal::List(..) | PyVal::Range(..)
                    )
                {
                    let one = vals.pop().expect("one value");
                    vals = self.iterate(&one)?;
                    if vals.is_empty() {
                        return Err(err(format!("{f}() of an empty sequence"), one.span));
                    }
                }
                let texts = vals.iter().all(|v| matches!(v.v, PyVal::Str(_)));
                if !texts {
                    for v in &vals {
                        num(v)?;
                    }
                }
                let mut best = vals[0].clone();
                for v in &vals[1..] {
                    let op = if f == "min" {
                        crate::lang::ast::CmpOp::Lt
                    } else {
                        crate::lang::ast::CmpOp::Gt
                    };
                    if ops::compare(op, &v.v, &best.v).map_err(|m| err(m, v.span))? {
                        best = v.clone();
                    }
                }
                Ok(best.v)
            }
        }
    }
}
