//! Evaluation of the Python-like expressions of a command file.
//!
//! Command files compute plain values between commands (`NPAS = 30`,
//! `IMPACT = 1.0*IMPACT_THEORIQUE`); these are evaluated at check time,
//! before anything runs, with Python 3's rules for numbers (int/int `/`
//! gives a real, `**` of ints with a negative exponent gives a real,
//! `int()` truncates toward zero). Commands themselves are not evaluated
//! here: the checker handles calls of catalogue commands.

use indexmap::IndexMap;

use crate::catalog::concept_type::ConceptType;
use crate::diag::{closest, Diagnostic, Span};
use crate::lang::ast::{BinOp, Expr, ExprKind, Ident, UnOp};

/// A value of the language, before it is checked against a keyword.
#[derive(Debug, Clone, PartialEq)]
pub enum PyVal {
    Int(i64),
    Real(f64),
    Str(String),
    None,
    Tuple(Vec<SpVal>),
    /// `_F(KEY=value, ...)`: one occurrence of a factor keyword.
    Fact(Vec<(Ident, SpVal)>),
    /// A name bound to a concept.
    Concept {
        name: String,
        ty: ConceptType,
    },
    /// The value of a name whose definition failed (already reported):
    /// it propagates silently so that one mistake gives one error.
    Poison,
}

impl PyVal {
    /// How the value is described in messages ("a real", "a text"...).
    pub fn describe(&self) -> String {
        match self {
            PyVal::Int(i) => format!("the integer {i}"),
            PyVal::Real(r) => format!("the real {r:?}"),
            PyVal::Str(s) => format!("the text '{s}'"),
            PyVal::None => "None".into(),
            PyVal::Tuple(_) => "a tuple".into(),
            PyVal::Fact(_) => "a factor keyword occurrence _F(...)".into(),
            PyVal::Concept { name, ty } => format!("the concept {name} of type {ty}"),
            PyVal::Poison => "an invalid value".into(),
        }
    }
}

/// A value with the span of the expression that produced it.
#[derive(Debug, Clone, PartialEq)]
pub struct SpVal {
    pub v: PyVal,
    pub span: Span,
}

/// What a name is bound to.
#[derive(Debug, Clone, PartialEq)]
pub enum Binding {
    Var(PyVal),
    Concept { ty: ConceptType, defined_at: Span },
}

/// The names of a command file, in definition order.
#[derive(Debug, Clone, Default)]
pub struct Env {
    pub names: IndexMap<String, Binding>,
}

pub const BUILTINS: [&str; 5] = ["int", "float", "abs", "min", "max"];

impl Env {
    fn lookup(&self, id: &str, span: Span) -> Result<PyVal, Diagnostic> {
        match self.names.get(id) {
            Some(Binding::Var(v)) => Ok(v.clone()),
            Some(Binding::Concept { ty, .. }) => Ok(PyVal::Concept {
                name: id.to_string(),
                ty: *ty,
            }),
            None => {
                let known: Vec<&str> = self.names.keys().map(String::as_str).collect();
                let mut d = Diagnostic::error(format!("name '{id}' is not defined")).at(span);
                if let Some(s) = closest(id, &known) {
                    d.suggestion = Some(s);
                }
                Err(d)
            }
        }
    }

    /// Evaluates an expression that is not a command call.
    /// `is_command` tells whether a called name is a catalogue command (an
    /// error here: commands cannot be nested in expressions).
    pub fn eval(&self, e: &Expr, is_command: &dyn Fn(&str) -> bool) -> Result<SpVal, Diagnostic> {
        let v = match &e.kind {
            ExprKind::Int(i) => PyVal::Int(*i),
            ExprKind::Real(r) => PyVal::Real(*r),
            ExprKind::Str(s) => PyVal::Str(s.clone()),
            ExprKind::NoneLit => PyVal::None,
            ExprKind::Name(n) => self.lookup(n, e.span)?,
            ExprKind::Tuple(items) => PyVal::Tuple(
                items
                    .iter()
                    .map(|x| self.eval(x, is_command))
                    .collect::<Result<_, _>>()?,
            ),
            ExprKind::Unary { op, operand } => {
                let x = self.eval(operand, is_command)?;
                match (op, x.v) {
                    (_, PyVal::Poison) => PyVal::Poison,
                    (UnOp::Neg, PyVal::Int(i)) => PyVal::Int(
                        i.checked_neg()
                            .ok_or_else(|| Diagnostic::error("integer overflow").at(e.span))?,
                    ),
                    (UnOp::Neg, PyVal::Real(r)) => PyVal::Real(-r),
                    (UnOp::Pos, v @ (PyVal::Int(_) | PyVal::Real(_))) => v,
                    (_, v) => {
                        return Err(Diagnostic::error(format!(
                            "unary '{}' needs a number, not {}",
                            if *op == UnOp::Neg { "-" } else { "+" },
                            v.describe()
                        ))
                        .at(e.span))
                    }
                }
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let a = self.eval(lhs, is_command)?;
                let b = self.eval(rhs, is_command)?;
                if a.v == PyVal::Poison || b.v == PyVal::Poison {
                    return Ok(SpVal {
                        v: PyVal::Poison,
                        span: e.span,
                    });
                }
                binary(*op, a.v, b.v).map_err(|m| Diagnostic::error(m).at(e.span))?
            }
            ExprKind::Call { func, args } => {
                if func.name == "_F" {
                    let mut occ: Vec<(Ident, SpVal)> = Vec::new();
                    for a in args {
                        let Some(k) = &a.name else {
                            return Err(Diagnostic::error(
                                "_F(...) takes keyword arguments only (KEY=value)",
                            )
                            .at(a.span));
                        };
                        if let Some((prev, _)) = occ.iter().find(|(p, _)| p.name == k.name) {
                            let (l, _) = (prev.span, ());
                            return Err(Diagnostic::error(format!(
                                "keyword {} is repeated in _F(...)",
                                k.name
                            ))
                            .at(k.span)
                            .note(format!("first given at byte {}", l.start)));
                        }
                        occ.push((k.clone(), self.eval(&a.value, is_command)?));
                    }
                    PyVal::Fact(occ)
                } else if BUILTINS.contains(&func.name.as_str()) {
                    self.builtin(func, args, e.span, is_command)?
                } else if is_command(&func.name) {
                    return Err(Diagnostic::error(format!(
                        "the command {} cannot be used inside an expression; assign its result to a name first",
                        func.name
                    ))
                    .at(func.span));
                } else {
                    let mut known: Vec<&str> = BUILTINS.to_vec();
                    known.push("_F");
                    let mut d = Diagnostic::error(format!(
                        "'{}' is not a command, a builtin (int, float, abs, min, max) or _F",
                        func.name
                    ))
                    .at(func.span);
                    d.suggestion = closest(&func.name, &known);
                    return Err(d);
                }
            }
        };
        Ok(SpVal { v, span: e.span })
    }

    fn builtin(
        &self,
        func: &Ident,
        args: &[crate::lang::ast::Arg],
        span: Span,
        is_command: &dyn Fn(&str) -> bool,
    ) -> Result<PyVal, Diagnostic> {
        let f = func.name.as_str();
        let mut vals = Vec::new();
        for a in args {
            if a.name.is_some() {
                return Err(
                    Diagnostic::error(format!("{f}() takes positional arguments only")).at(a.span),
                );
            }
            vals.push(self.eval(&a.value, is_command)?);
        }
        if vals.iter().any(|v| v.v == PyVal::Poison) {
            return Ok(PyVal::Poison);
        }
        // min/max of a single tuple argument work on its items, as in Python.
        if (f == "min" || f == "max") && vals.len() == 1 {
            if let PyVal::Tuple(items) = &vals[0].v {
                vals = items.clone();
            }
        }
        let num = |v: &SpVal| -> Result<f64, Diagnostic> {
            match v.v {
                PyVal::Int(i) => Ok(i as f64),
                PyVal::Real(r) => Ok(r),
                ref o => Err(Diagnostic::error(format!(
                    "{f}() needs a number, not {}",
                    o.describe()
                ))
                .at(v.span)),
            }
        };
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
                    ("abs", _) => PyVal::Real(num(x)?.abs()),
                    _ => return Err(num(x).unwrap_err()),
                })
            }
            _ => {
                if vals.is_empty() {
                    return Err(
                        Diagnostic::error(format!("{f}() needs at least one argument")).at(span),
                    );
                }
                let mut best = vals[0].clone();
                let mut bx = num(&best)?;
                for v in &vals[1..] {
                    let x = num(v)?;
                    if (f == "min" && x < bx) || (f == "max" && x > bx) {
                        best = v.clone();
                        bx = x;
                    }
                }
                Ok(best.v)
            }
        }
    }
}

/// Python 3 arithmetic on numbers (and `+` on texts).
fn binary(op: BinOp, a: PyVal, b: PyVal) -> Result<PyVal, String> {
    use PyVal::*;
    let overflow = || "integer overflow".to_string();
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
                BinOp::Pow => {
                    if x < 0.0 && y.fract() != 0.0 {
                        return Err(format!(
                            "{x} ** {y}: a negative number to a fractional power is complex"
                        ));
                    }
                    if x == 0.0 && y < 0.0 {
                        return Err("zero cannot be raised to a negative power".into());
                    }
                    x.powf(y)
                }
            };
            if !r.is_finite() {
                return Err(format!("the result of {x} {} {y} overflows", op.symbol()));
            }
            Ok(Real(r))
        }
        (Str(x), Str(y)) if op == BinOp::Add => Ok(Str(format!("{x}{y}"))),
        _ => Err(format!(
            "operator '{}' cannot combine {} and {}",
            op.symbol(),
            a.describe(),
            b.describe()
        )),
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
        assert!(binary(BinOp::Add, PyVal::Str("a".into()), PyVal::Int(1)).is_err());
    }
}
