//! Evaluation of the Python-like expressions of a command file.
//!
//! Command files compute plain values between commands (`NPAS = 30`,
//! `IMPACT = 1.0*IMPACT_THEORIQUE`, `'G_%d' % i`, `[_F(...) for g in L]`);
//! these are evaluated at check time, before anything runs, with Python 3's
//! rules (int/int `/` gives a real, `**` of ints with a negative exponent
//! gives a real, `int()` truncates toward zero, `%` and `//` floor, `and`
//! and `or` give an operand...). Commands themselves are not evaluated
//! here: the checker handles calls of catalogue commands, and the blocks
//! (`if`, `for`) that decide which commands run.
//!
//! Whatever depends on a concept's content (computed only when the study
//! runs) is refused with a message: its truth, its text, its items.

use std::cell::{Cell, RefCell};

use indexmap::IndexMap;

use crate::catalog::concept_type::ConceptType;
use crate::diag::{closest, Diagnostic, Span};
use crate::lang::ast::{Arg, Expr, ExprKind, Ident, LogicOp, Target};

pub mod builtins;
mod ops;
pub mod pyfmt;

pub use builtins::{is_builtin, BUILTINS};
use ops::binary;

/// The longest list, tuple or range a command file may build or loop
/// over: far above any study's needs, far below what fills the memory.
pub const MAX_ITEMS: usize = 1_000_000;

/// Loop iterations and comprehension items a whole file may evaluate:
/// loops are unrolled before the study runs, and a file that asks for more
/// is a mistake (or hostile), not a study.
pub const MAX_STEPS: u64 = 1_000_000;

/// A value of the language, before it is checked against a keyword.
#[derive(Debug, Clone, PartialEq)]
pub enum PyVal {
    Int(i64),
    Real(f64),
    Bool(bool),
    Str(String),
    None,
    Tuple(Vec<SpVal>),
    /// A list, with its identity: `M = L` shares it, as in Python, and
    /// `L.append(x)` is refused when another name shares it (aster's values
    /// are copies, so the other name would not see the change Python makes).
    List(u64, Vec<SpVal>),
    /// `range(start, stop, step)`, kept lazy.
    Range(i64, i64, i64),
    /// `_F(KEY=value, ...)`: one occurrence of a factor keyword.
    Fact(u64, Vec<(Ident, SpVal)>),
    /// A name bound to a concept.
    Concept {
        name: String,
        ty: ConceptType,
    },
    /// An imported module: "math" or "numpy".
    Module(&'static str),
    /// A function of a module, by its full name ("math.sqrt").
    Func(&'static str),
    /// What `zip(...)` and `enumerate(...)` give: items to go through once,
    /// in the `for` or the comprehension that asked for them (a name
    /// cannot keep one: Python's would be empty the second time).
    Iter(&'static str, Vec<SpVal>),
    /// A concept that has been defined again since this value took it
    /// (`L = [R]`, then `R = CMD(...)`): Python keeps the old object,
    /// aster knows concepts by their names, so using it is an error.
    Stale(String),
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
            PyVal::Bool(b) => format!("the boolean {}", if *b { "True" } else { "False" }),
            PyVal::Str(s) => format!("the text '{s}'"),
            PyVal::None => "None".into(),
            PyVal::Tuple(_) => "a tuple".into(),
            PyVal::List(..) => "a list".into(),
            PyVal::Range(..) => "a range".into(),
            PyVal::Fact(..) => "a dict (_F(...))".into(),
            PyVal::Concept { name, ty } => format!("the concept {name} of type {ty}"),
            PyVal::Module(m) => format!("the module {m}"),
            PyVal::Func(f) => format!("the function {f}"),
            PyVal::Iter(kind, _) => format!("{} {kind} object", article(kind)),
            PyVal::Stale(name) => {
                format!("the concept {name} as it was before {name} was defined again")
            }
            PyVal::Poison => "an invalid value".into(),
        }
    }
}

/// "a zip", "an enumerate".
pub fn article(word: &str) -> &'static str {
    if word.starts_with(['a', 'e', 'i', 'o', 'u']) {
        "an"
    } else {
        "a"
    }
}

/// Replaces, inside a value, the concept `name` by [`PyVal::Stale`].
pub fn make_stale(v: &mut PyVal, name: &str) {
    match v {
        PyVal::Concept { name: n, .. } if n == name => *v = PyVal::Stale(name.to_string()),
        PyVal::List(_, items) | PyVal::Tuple(items) => {
            items.iter_mut().for_each(|x| make_stale(&mut x.v, name))
        }
        PyVal::Fact(_, kv) => kv.iter_mut().for_each(|(_, x)| make_stale(&mut x.v, name)),
        _ => {}
    }
}

/// The first stale concept inside a value, with where it is.
pub fn find_stale(v: &SpVal) -> Option<(&str, Span)> {
    match &v.v {
        PyVal::Stale(name) => Some((name, v.span)),
        PyVal::List(_, items) | PyVal::Tuple(items) => items.iter().find_map(find_stale),
        PyVal::Fact(_, kv) => kv.iter().find_map(|(_, x)| find_stale(x)),
        _ => None,
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
    /// Concepts destroyed by DETRUIRE and not defined again, with where:
    /// the message of a later use says so.
    pub destroyed: IndexMap<String, Span>,
    /// The variables of the comprehensions being evaluated, innermost
    /// last; they hide the file's names, as in Python 3.
    locals: RefCell<Vec<(String, PyVal)>>,
    /// The identity the next new list gets.
    next_list: Cell<u64>,
    /// Loop iterations and comprehension items evaluated so far.
    steps: Cell<u64>,
}

fn err(message: impl Into<String>, span: Span) -> Diagnostic {
    Diagnostic::error(message).at(span)
}

/// A name of `math` that the file did not bind: code_aster's command
/// namespace has them without an import (its official tests sdnv100a and
/// sdnv108a use `sqrt` and `pi` so), and so does aster. A name the file
/// binds, or a concept DETRUIRE removed, is not one.
fn math_fallback(name: &str, destroyed: &IndexMap<String, Span>) -> Option<PyVal> {
    if destroyed.contains_key(name) || !builtins::is_math(name) {
        return None;
    }
    let id = crate::lang::ast::Ident {
        name: name.to_string(),
        span: Span::new(0, 0),
    };
    builtins::module_attr("math", &id).ok()
}

/// The error for anything that needs a concept's content.
pub fn concept_unknown(name: &str, what: &str, span: Span) -> Diagnostic {
    err(
        format!("{what} the concept {name}, whose content is not known before the study runs"),
        span,
    )
    .note("aster evaluates the Python of a command file before running any command: conditions, loops and texts can use numbers, texts, lists and tuples, not the results of commands")
}

impl Env {
    fn lookup(&self, id: &str, span: Span) -> Result<PyVal, Diagnostic> {
        if let Some((_, v)) = self.locals.borrow().iter().rev().find(|(n, _)| n == id) {
            return Ok(v.clone());
        }
        match self.names.get(id) {
            Some(Binding::Var(v)) => Ok(v.clone()),
            Some(Binding::Concept { ty, .. }) => Ok(PyVal::Concept {
                name: id.to_string(),
                ty: *ty,
            }),
            None => {
                if let Some(v) = math_fallback(id, &self.destroyed) {
                    return Ok(v);
                }
                let known: Vec<&str> = self.names.keys().map(String::as_str).collect();
                let mut d = Diagnostic::error(format!("name '{id}' is not defined")).at(span);
                if self.destroyed.contains_key(id) {
                    return Err(d.note(format!(
                        "{id} was destroyed by DETRUIRE above: define it again before using it"
                    )));
                }
                if let Some(s) = closest(id, &known) {
                    d.suggestion = Some(s);
                }
                Err(d)
            }
        }
    }

    /// A new list identity.
    pub fn new_list(&self, items: Vec<SpVal>) -> PyVal {
        PyVal::List(self.new_id(), items)
    }

    /// A new identity for a list or a dict (they share the counter, so
    /// that [`holds_list`] tells any two apart).
    pub fn new_id(&self) -> u64 {
        let id = self.next_list.get();
        self.next_list.set(id + 1);
        id
    }

    /// `_F(...)` and `dict(...)`: a dict of keywords. `KEY=value` and
    /// `**d` items in order, a key given twice is Python's TypeError;
    /// `dict(d)` copies a dict, `dict(pairs)` reads (key, value) pairs.
    fn dict_call(
        &self,
        func: &Ident,
        args: &[Arg],
        is_command: &dyn Fn(&str) -> bool,
    ) -> Result<PyVal, Diagnostic> {
        let what = format!("{}(...)", func.name);
        let mut out: Vec<(Ident, SpVal)> = Vec::new();
        if let Some(second) = args.iter().filter(|a| a.name.is_none() && !a.unpack).nth(1) {
            if func.name == "dict" {
                return Err(err(
                    "dict() takes at most 1 positional argument",
                    second.span,
                ));
            }
        }
        let mut from_positional = 0;
        for a in args {
            let v = self.eval(&a.value, is_command)?;
            if v.v == PyVal::Poison {
                return Ok(PyVal::Poison);
            }
            let items = match (&a.name, a.unpack) {
                (Some(k), _) => vec![(k.clone(), v)],
                (None, true) => match unpack_keywords(v, &what)? {
                    Some(kv) => kv,
                    None => return Ok(PyVal::Poison),
                },
                (None, false) if func.name == "_F" => {
                    return Err(Diagnostic::error(
                        "_F(...) takes keyword arguments only (KEY=value or **dict)",
                    )
                    .at(a.span))
                }
                (None, false) => match v.v {
                    PyVal::Fact(_, kv) => {
                        out.extend(kv);
                        from_positional = out.len();
                        continue;
                    }
                    _ => {
                        for pair in self.iterate(&v)? {
                            let [k, x] = <[SpVal; 2]>::try_from(unpack(pair, 2)?)
                                .expect("unpack gives 2 items");
                            match k.v {
                                PyVal::Str(name) => {
                                    dict_set(&mut out, Ident { name, span: k.span }, x)
                                }
                                other => return Err(dict_key_error(&other, k.span)),
                            }
                        }
                        from_positional = out.len();
                        continue;
                    }
                },
            };
            for (k, v) in items {
                match out.iter().position(|(p, _)| p.name == k.name) {
                    // dict(d, KEY=value): the keywords update the copy.
                    Some(i) if i < from_positional => out[i].1 = v,
                    Some(i) => {
                        let at = if a.unpack { a.span } else { k.span };
                        let mut d =
                            Diagnostic::error(format!("keyword {} is repeated in {what}", k.name))
                                .at(at)
                                .note(format!("first given at byte {}", out[i].0.span.start));
                        if a.unpack {
                            d = d.note("the second time by the dict that ** unpacks");
                        }
                        return Err(d);
                    }
                    None => out.push((k, v)),
                }
            }
        }
        Ok(PyVal::Fact(self.new_id(), out))
    }

    /// Counts one loop iteration or comprehension item against
    /// [`MAX_STEPS`].
    pub fn step(&self, span: Span) -> Result<(), Diagnostic> {
        let n = self.steps.get() + 1;
        self.steps.set(n);
        if n > MAX_STEPS {
            return Err(err(
                format!(
                    "the loops and comprehensions of the file run more than {MAX_STEPS} iterations"
                ),
                span,
            )
            .note("aster unrolls loops before the study runs; a study needs far fewer"));
        }
        Ok(())
    }

    /// Evaluates an expression that is not a command call.
    /// `is_command` tells whether a called name is a catalogue command (an
    /// error here: commands cannot be nested in expressions).
    pub fn eval(&self, e: &Expr, is_command: &dyn Fn(&str) -> bool) -> Result<SpVal, Diagnostic> {
        let sp = |v| SpVal { v, span: e.span };
        let v = match &e.kind {
            ExprKind::Int(i) => PyVal::Int(*i),
            ExprKind::Real(r) => PyVal::Real(*r),
            ExprKind::Str(s) => PyVal::Str(s.clone()),
            ExprKind::Bool(b) => PyVal::Bool(*b),
            ExprKind::NoneLit => PyVal::None,
            ExprKind::Name(n) => self.lookup(n, e.span)?,
            ExprKind::Tuple(items) => PyVal::Tuple(self.eval_all(items, is_command)?),
            ExprKind::List(items) => {
                let items = self.eval_all(items, is_command)?;
                self.new_list(items)
            }
            ExprKind::Dict(items) => {
                let mut out: Vec<(Ident, SpVal)> = Vec::new();
                for (k, v) in items {
                    let val = self.eval(v, is_command)?;
                    let Some(k) = k else {
                        match unpack_keywords(val, "{**...}")? {
                            Some(kv) => kv.into_iter().for_each(|(k, v)| dict_set(&mut out, k, v)),
                            None => return Ok(sp(PyVal::Poison)),
                        }
                        continue;
                    };
                    let key = self.eval(k, is_command)?;
                    match key.v {
                        PyVal::Str(name) => dict_set(
                            &mut out,
                            Ident {
                                name,
                                span: key.span,
                            },
                            val,
                        ),
                        PyVal::Poison => return Ok(sp(PyVal::Poison)),
                        other => return Err(dict_key_error(&other, key.span)),
                    }
                }
                PyVal::Fact(self.new_id(), out)
            }
            ExprKind::ListComp { elt, generators } => {
                let mut out = Vec::new();
                let depth = self.locals.borrow().len();
                let r = self.comprehension(elt, generators, 0, &mut out, is_command);
                self.locals.borrow_mut().truncate(depth);
                r?;
                if out.iter().any(|x| x.v == PyVal::Poison) {
                    PyVal::Poison
                } else {
                    self.new_list(out)
                }
            }
            ExprKind::Unary { op, operand } => {
                let x = self.eval(operand, is_command)?;
                ops::unary(*op, x.v).map_err(|m| err(m, e.span))?
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let a = self.eval(lhs, is_command)?;
                let b = self.eval(rhs, is_command)?;
                if a.v == PyVal::Poison || b.v == PyVal::Poison {
                    return Ok(sp(PyVal::Poison));
                }
                match binary(*op, a.v, b.v).map_err(|m| err(m, e.span))? {
                    PyVal::List(_, items) => self.new_list(items),
                    v => v,
                }
            }
            ExprKind::Compare { first, rest } => {
                let mut a = self.eval(first, is_command)?;
                let mut result = PyVal::Bool(true);
                for (op, rhs) in rest {
                    let b = self.eval(rhs, is_command)?;
                    if a.v == PyVal::Poison || b.v == PyVal::Poison {
                        return Ok(sp(PyVal::Poison));
                    }
                    let t = ops::compare(*op, &a.v, &b.v).map_err(|m| err(m, e.span))?;
                    if !t {
                        result = PyVal::Bool(false);
                        break;
                    }
                    a = b;
                }
                result
            }
            ExprKind::Logic { op, lhs, rhs } => {
                let a = self.eval(lhs, is_command)?;
                if a.v == PyVal::Poison {
                    return Ok(sp(PyVal::Poison));
                }
                let t = self.truth(&a)?;
                let short = match op {
                    LogicOp::And => !t,
                    LogicOp::Or => t,
                };
                if short {
                    a.v
                } else {
                    self.eval(rhs, is_command)?.v
                }
            }
            ExprKind::IfElse { cond, then, orelse } => {
                let c = self.eval(cond, is_command)?;
                if c.v == PyVal::Poison {
                    return Ok(sp(PyVal::Poison));
                }
                let branch = if self.truth(&c)? { then } else { orelse };
                self.eval(branch, is_command)?.v
            }
            ExprKind::Index { value, index } => {
                let a = self.eval(value, is_command)?;
                let i = self.eval(index, is_command)?;
                if a.v == PyVal::Poison || i.v == PyVal::Poison {
                    return Ok(sp(PyVal::Poison));
                }
                ops::index(&a.v, &i).map_err(|d| d.at_if_none(e.span))?
            }
            ExprKind::Slice {
                value,
                lower,
                upper,
                step,
            } => {
                let a = self.eval(value, is_command)?;
                let bound = |b: &Option<Box<Expr>>| -> Result<Option<SpVal>, Diagnostic> {
                    b.as_ref().map(|x| self.eval(x, is_command)).transpose()
                };
                let (l, u, s) = (bound(lower)?, bound(upper)?, bound(step)?);
                let parts = [&Some(a.clone()), &l, &u, &s];
                if parts
                    .iter()
                    .any(|p| p.as_ref().is_some_and(|x| x.v == PyVal::Poison))
                {
                    return Ok(sp(PyVal::Poison));
                }
                match ops::slice(&a.v, [l.as_ref(), u.as_ref(), s.as_ref()])
                    .map_err(|d| d.at_if_none(e.span))?
                {
                    PyVal::List(_, items) => self.new_list(items),
                    v => v,
                }
            }
            ExprKind::Attribute { value, attr } => {
                let m = self.eval(value, is_command)?;
                match m.v {
                    PyVal::Poison => PyVal::Poison,
                    PyVal::Module(module) => builtins::module_attr(module, attr)?,
                    PyVal::Concept { name, .. } => {
                        return Err(concept_unknown(&name, &format!("'.{}' reads", attr.name), e.span))
                    }
                    v => {
                        return Err(err(
                            format!(
                                "attribute access is supported on the modules math and numpy only, not on {}",
                                v.describe()
                            ),
                            attr.span,
                        ))
                    }
                }
            }
            ExprKind::MethodCall {
                value,
                method,
                args,
            } => {
                let m = self.eval(value, is_command)?;
                match m.v {
                    PyVal::Poison => PyVal::Poison,
                    PyVal::Module(module) => {
                        let f = builtins::module_attr(module, method)?;
                        self.call_value(&f, method, args, e.span, is_command)?
                    }
                    // keys(), values(), items(): lists (Python's views go
                    // through the same items in a for, len() and list(); only
                    // their print differs: dict_keys([...])).
                    PyVal::Fact(_, kv)
                        if matches!(method.name.as_str(), "keys" | "values" | "items") =>
                    {
                        let vals = self.positional(&method.name, args, is_command)?;
                        if !vals.is_empty() {
                            return Err(err(
                                format!("{}() takes no argument ({} given)", method.name, vals.len()),
                                e.span,
                            ));
                        }
                        let items = kv
                            .into_iter()
                            .map(|(k, v)| {
                                let key = SpVal {
                                    v: PyVal::Str(k.name.clone()),
                                    span: k.span,
                                };
                                match method.name.as_str() {
                                    "keys" => key,
                                    "values" => v,
                                    _ => SpVal {
                                        span: k.span,
                                        v: PyVal::Tuple(vec![key, v]),
                                    },
                                }
                            })
                            .collect();
                        self.new_list(items)
                    }
                    PyVal::Fact(_, kv) if matches!(method.name.as_str(), "get" | "copy") => {
                        let vals = self.positional(&method.name, args, is_command)?;
                        match (method.name.as_str(), vals.as_slice()) {
                            ("copy", []) => PyVal::Fact(self.new_id(), kv),
                            ("get", [k] | [k, _]) => {
                                let PyVal::Str(key) = &k.v else {
                                    return Err(dict_key_error(&k.v, k.span));
                                };
                                match kv.into_iter().find(|(n, _)| &n.name == key) {
                                    Some((_, v)) => v.v,
                                    None => vals.get(1).map_or(PyVal::None, |d| d.v.clone()),
                                }
                            }
                            _ => {
                                return Err(err(
                                    format!(
                                        "{}() takes {} ({} given)",
                                        method.name,
                                        if method.name == "copy" {
                                            "no argument"
                                        } else {
                                            "1 or 2 arguments"
                                        },
                                        vals.len()
                                    ),
                                    e.span,
                                ))
                            }
                        }
                    }
                    PyVal::List(..) if method.name == "append" => {
                        return Err(err(
                            "append changes its list and gives None: write it as a statement of its own (L.append(x))",
                            method.span,
                        ))
                    }
                    PyVal::Concept { name, .. } => {
                        return Err(concept_unknown(&name, &format!("'.{}()' calls a method of", method.name), e.span))
                    }
                    v => {
                        return Err(err(
                            format!(
                                "method '{}' of {} is not supported",
                                method.name,
                                v.describe()
                            ),
                            method.span,
                        )
                        .note("the methods are the functions of math and numpy (math.sqrt(x)), L.append(x) on a list, d.get(key), d.copy(), d.keys(), d.values() and d.items() on a dict"))
                    }
                }
            }
            ExprKind::Call { func, args } => {
                if func.name == "_F" || func.name == "dict" {
                    self.dict_call(func, args, is_command)?
                } else if let Some(f @ PyVal::Func(_)) = self.bound_value(&func.name) {
                    self.call_value(&f, func, args, e.span, is_command)?
                } else if func.name == "print" {
                    return Err(err(
                        "print() writes to the .mess and gives None: call it as a statement of its own",
                        func.span,
                    ));
                } else if is_builtin(&func.name) {
                    self.builtin(func, args, e.span, is_command)?
                } else if is_command(&func.name) {
                    return Err(Diagnostic::error(format!(
                        "the command {} cannot be called here: its result must be named first",
                        func.name
                    ))
                    .at(func.span)
                    .note("a command runs where a keyword takes its result (ARCHIVAGE=_F(LIST_INST=DEFI_LIST_REEL(...))), but not inside a list comprehension or a branch of `if ... else`, `and`, `or`, which Python may evaluate several times or not at all: write NAME = COMMAND(...) on a line of its own and use NAME"));
                } else {
                    let mut known: Vec<&str> = BUILTINS.to_vec();
                    known.push("_F");
                    let mut d = Diagnostic::error(format!(
                        "'{}' is not a command, a builtin ({}) or _F",
                        func.name,
                        BUILTINS.join(", ")
                    ))
                    .at(func.span);
                    d.suggestion = closest(&func.name, &known);
                    return Err(d);
                }
            }
        };
        Ok(sp(v))
    }

    fn eval_all(
        &self,
        items: &[Expr],
        is_command: &dyn Fn(&str) -> bool,
    ) -> Result<Vec<SpVal>, Diagnostic> {
        let out: Vec<SpVal> = items
            .iter()
            .map(|x| self.eval(x, is_command))
            .collect::<Result<_, _>>()?;
        if out.len() > MAX_ITEMS {
            let span = items.first().map_or(Span::new(0, 0), |x| x.span);
            return Err(err(format!("more than {MAX_ITEMS} items"), span));
        }
        Ok(out)
    }

    /// The value a name is bound to, if it is a plain value.
    pub fn bound_value(&self, name: &str) -> Option<PyVal> {
        if let Some((_, v)) = self.locals.borrow().iter().rev().find(|(n, _)| n == name) {
            return Some(v.clone());
        }
        match self.names.get(name) {
            Some(Binding::Var(v)) => Some(v.clone()),
            Some(Binding::Concept { .. }) => None,
            None => math_fallback(name, &self.destroyed),
        }
    }

    fn comprehension(
        &self,
        elt: &Expr,
        gens: &[crate::lang::ast::Comprehension],
        at: usize,
        out: &mut Vec<SpVal>,
        is_command: &dyn Fn(&str) -> bool,
    ) -> Result<(), Diagnostic> {
        let Some(g) = gens.get(at) else {
            out.push(self.eval(elt, is_command)?);
            if out.len() > MAX_ITEMS {
                return Err(err(
                    format!("a list of more than {MAX_ITEMS} items"),
                    elt.span,
                ));
            }
            return Ok(());
        };
        let it = self.eval(&g.iter, is_command)?;
        if it.v == PyVal::Poison {
            out.push(SpVal {
                v: PyVal::Poison,
                span: g.iter.span,
            });
            return Ok(());
        }
        let depth = self.locals.borrow().len();
        'items: for item in self.iterate(&it)? {
            self.step(g.iter.span)?;
            self.locals.borrow_mut().truncate(depth);
            for (name, v) in unpack_target(&g.target, item)? {
                self.locals.borrow_mut().push((name, v));
            }
            for c in &g.ifs {
                let cv = self.eval(c, is_command)?;
                if cv.v == PyVal::Poison {
                    out.push(cv);
                    continue 'items;
                }
                if !self.truth(&cv)? {
                    continue 'items;
                }
            }
            self.comprehension(elt, gens, at + 1, out, is_command)?;
        }
        self.locals.borrow_mut().truncate(depth);
        Ok(())
    }

    /// Python's truth of a value (`if`, `and`, `or`, `not`).
    pub fn truth(&self, v: &SpVal) -> Result<bool, Diagnostic> {
        ops::truth(&v.v).map_err(|d| d.at_if_none(v.span))
    }

    /// The items a `for` goes through.
    pub fn iterate(&self, v: &SpVal) -> Result<Vec<SpVal>, Diagnostic> {
        ops::iterate(&v.v, v.span)
    }
}

/// The names a loop target binds for one item (`for a, b in ...` unpacks).
pub fn unpack_target(target: &Target, item: SpVal) -> Result<Vec<(String, PyVal)>, Diagnostic> {
    match target {
        Target::Name(n) => Ok(vec![(n.name.clone(), item.v)]),
        Target::Tuple(targets) => {
            let vals = unpack(item, targets.len())?;
            let mut out = Vec::new();
            for (t, v) in targets.iter().zip(vals) {
                out.extend(unpack_target(t, v)?);
            }
            Ok(out)
        }
    }
}

/// The `n` items of a value unpacked into `n` names (`a, b = 1, 2`); a
/// poisoned value gives poisoned names.
pub fn unpack(item: SpVal, n: usize) -> Result<Vec<SpVal>, Diagnostic> {
    if item.v == PyVal::Poison {
        return Ok(vec![item; n]);
    }
    let span = item.span;
    let items = ops::iterate(&item.v, span)?;
    if items.len() != n {
        return Err(err(
            format!(
                "cannot unpack {} into {n} names: it has {} item{}",
                item.v.describe(),
                items.len(),
                if items.len() == 1 { "" } else { "s" }
            ),
            span,
        ));
    }
    Ok(items)
}

/// The items a `**value` gives (a dict's keys and values, each key with
/// the span where the dict got it); `None` for a value whose error is
/// already reported.
pub fn unpack_keywords(v: SpVal, what: &str) -> Result<Option<Vec<(Ident, SpVal)>>, Diagnostic> {
    match v.v {
        PyVal::Fact(_, kv) => Ok(Some(kv)),
        PyVal::Poison => Ok(None),
        PyVal::Concept { name, .. } => Err(concept_unknown(&name, "'**' unpacks", v.span)),
        other => Err(err(
            format!(
                "the argument after ** in {what} must be a dict (dict(...), {{...}} or _F(...)), not {}",
                other.describe()
            ),
            v.span,
        )),
    }
}

/// `d[k] = v` in a dict literal: a key given again keeps its place and
/// takes the new value, as in Python.
fn dict_set(out: &mut Vec<(Ident, SpVal)>, k: Ident, v: SpVal) {
    match out.iter_mut().find(|(p, _)| p.name == k.name) {
        Some(slot) => slot.1 = v,
        None => out.push((k, v)),
    }
}

/// Dicts of command files hold keywords: their keys are texts.
pub fn dict_key_error(key: &PyVal, span: Span) -> Diagnostic {
    err(
        format!(
            "a dict key must be a text (a keyword name), not {}",
            key.describe()
        ),
        span,
    )
    .note("aster's dicts are the keyword sets of commands: {'MODELE': MO}, dict(MODELE=MO), _F(MODELE=MO)")
}

/// A list's identity everywhere inside a value.
pub fn holds_list(v: &PyVal, id: u64) -> bool {
    match v {
        PyVal::List(i, items) => *i == id || items.iter().any(|x| holds_list(&x.v, id)),
        PyVal::Tuple(items) => items.iter().any(|x| holds_list(&x.v, id)),
        PyVal::Fact(i, kv) => *i == id || kv.iter().any(|(_, x)| holds_list(&x.v, id)),
        _ => false,
    }
}

/// A value as a command keyword receives it: lists and ranges become
/// tuples (code_aster takes any sequence), inside `_F` too.
pub fn for_keyword(v: SpVal) -> SpVal {
    let span = v.span;
    let v = match v.v {
        PyVal::List(_, items) | PyVal::Tuple(items) => {
            PyVal::Tuple(items.into_iter().map(for_keyword).collect())
        }
        PyVal::Range(..) => match ops::iterate(&v.v, span) {
            Ok(items) => PyVal::Tuple(items),
            Err(_) => PyVal::Poison,
        },
        PyVal::Fact(i, kv) => PyVal::Fact(
            i,
            kv.into_iter().map(|(k, x)| (k, for_keyword(x))).collect(),
        ),
        v => v,
    };
    SpVal { v, span }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::Source;
    use crate::lang::ast::StmtKind;

    /// Evaluates the assignments of `text` in order, then returns the
    /// value of `expr`, as a command file would see it.
    fn eval_in(text: &str, expr: &str) -> Result<PyVal, String> {
        let src = Source::new("t.comm", format!("{text}\nX__ = {expr}\n"));
        let p = crate::lang::parser::parse(&src).map_err(|d| d.message)?;
        let mut env = Env::default();
        env.names
            .insert("math".into(), Binding::Var(PyVal::Module("math")));
        env.names
            .insert("np".into(), Binding::Var(PyVal::Module("numpy")));
        let mut last = PyVal::None;
        for s in &p.stmts {
            let StmtKind::Assign { target, value } = &s.kind else {
                panic!("assignments only")
            };
            let v = env.eval(value, &|_| false).map_err(|d| d.message)?;
            last = v.v.clone();
            env.names.insert(target.name.clone(), Binding::Var(v.v));
        }
        Ok(last)
    }

    fn ev(expr: &str) -> PyVal {
        eval_in("", expr).unwrap_or_else(|e| panic!("{expr}: {e}"))
    }

    fn text(expr: &str) -> String {
        match ev(expr) {
            PyVal::Str(s) => s,
            v => panic!("{expr}: {v:?}"),
        }
    }

    /// Every expected value is what CPython 3 gives for the same text.
    #[test]
    fn expressions_have_python_values() {
        use PyVal::*;
        assert_eq!(ev("(1, 2, 3)[-1]"), Int(3));
        assert_eq!(ev("[1, 2, 3][0]"), Int(1));
        assert_eq!(text("'abcd'[1:3]"), "bc");
        assert_eq!(text("str([1, 2, 3][1:])"), "[2, 3]");
        assert_eq!(text("str((1, 2, 3)[::-1])"), "(3, 2, 1)");
        assert_eq!(ev("7 // 2"), Int(3));
        assert_eq!(ev("-7 % 3"), Int(2));
        assert_eq!(ev("7.5 // 2"), Real(3.0));
        assert_eq!(text("'G_%d_%s' % (3, 'A')"), "G_3_A");
        assert_eq!(
            text("'%5.2f|%g|%e' % (2.71828, 1e-5, 2.)"),
            " 2.72|1e-05|2.000000e+00"
        );
        assert_eq!(ev("1 < 2 <= 2"), Bool(true));
        assert_eq!(ev("1 < 2 > 3"), Bool(false));
        assert_eq!(ev("1 == 1.0"), Bool(true));
        assert_eq!(ev("'a' != 'b'"), Bool(true));
        assert_eq!(ev("(1, 2) < (1, 3)"), Bool(true));
        assert_eq!(ev("2 in [1, 2]"), Bool(true));
        assert_eq!(ev("'B' not in 'ABC'"), Bool(false));
        assert_eq!(ev("True + 1"), Int(2));
        assert_eq!(ev("0 or 'x'"), Str("x".into()));
        assert_eq!(ev("0 and 1/0"), Int(0));
        assert_eq!(ev("not []"), Bool(true));
        assert_eq!(ev("1 if 0 else 2"), Int(2));
        assert_eq!(
            text("str([x * x for x in range(4) if x % 2 == 1])"),
            "[1, 9]"
        );
        assert_eq!(
            text("str([(i, j) for i in range(2) for j in 'ab'])"),
            "[(0, 'a'), (0, 'b'), (1, 'a'), (1, 'b')]"
        );
        assert_eq!(ev("len('abc') + len((1, 2)) + len(range(10))"), Int(15));
        assert_eq!(text("str(list(range(5, 0, -2)))"), "[5, 3, 1]");
        assert_eq!(text("str(0.1 + 0.2)"), "0.30000000000000004");
        assert_eq!(
            text("str(1e-5) + str(2) + str(None) + str(True)"),
            "1e-052NoneTrue"
        );
        assert_eq!(ev("int('12') + int(2.9) + int(-2.9)"), Int(12));
        assert_eq!(ev("float(3)"), Real(3.0));
        assert_eq!(ev("abs(-2) + abs(-0.5)"), Real(2.5));
        assert_eq!(ev("min(3, 1, 2) + max([4, 5])"), Int(6));
        assert_eq!(text("min('b', 'a')"), "a");
        assert_eq!(ev("sum([1, 2, 3])"), Int(6));
        assert_eq!(ev("sum((0.5, 0.25), 1)"), Real(1.75));
        assert_eq!(ev("round(2.5)"), Int(2));
        assert_eq!(ev("round(3.5)"), Int(4));
        assert_eq!(ev("round(2.675, 2)"), Real(2.67));
        assert_eq!(ev("round(1234, -2)"), Int(1200));
        assert_eq!(text("'ab' * 3 + 'c'"), "abababc");
        assert_eq!(text("str([1] + [2] * 2)"), "[1, 2, 2]");
        assert_eq!(text("str((1,) + (2,))"), "(1, 2)");
        assert_eq!(
            text("str(list(enumerate('ab', 1)))"),
            "[(1, 'a'), (2, 'b')]"
        );
        assert_eq!(
            text("str(list(zip((1, 2, 3), 'ab')))"),
            "[(1, 'a'), (2, 'b')]"
        );
        assert_eq!(text("str([i * x for i, x in enumerate([3, 4])])"), "[0, 4]");
        assert_eq!(text("str(range(10)[2:8:3])"), "range(2, 8, 3)");
        assert_eq!(ev("math.sqrt(16.)"), Real(4.0));
        assert_eq!(ev("math.floor(-2.5)"), Int(-3));
        assert_eq!(ev("math.ceil(2.1)"), Int(3));
        assert_eq!(ev("math.pi"), Real(std::f64::consts::PI));
        assert_eq!(ev("math.atan2(1., 1.)"), Real(std::f64::consts::FRAC_PI_4));
        assert_eq!(ev("math.log(8., 2.)"), Real(3.0));
        assert_eq!(ev("math.pow(2, 3)"), Real(8.0));
        assert_eq!(ev("np.sqrt(4)"), Real(2.0));
        assert_eq!(ev("np.floor(2.5)"), Real(2.0));
        assert_eq!(ev("np.pi"), Real(std::f64::consts::PI));
        // Dicts (code_aster's _F is one).
        assert_eq!(
            text("str({'A': 1, 'B': [2, 'x']})"),
            "{'A': 1, 'B': [2, 'x']}"
        );
        assert_eq!(text("str({})"), "{}");
        assert_eq!(ev("{'A': 1, 'A': 2}['A']"), Int(2));
        assert_eq!(text("str({'A': 1, 'B': 2, 'A': 3})"), "{'A': 3, 'B': 2}");
        assert_eq!(ev("len(dict(A=1, **{'B': 2}))"), Int(2));
        assert_eq!(text("str(_F(**{'A': 1}, B=2))"), "{'A': 1, 'B': 2}");
        assert_eq!(
            text("str({**{'A': 1}, 'A': 0, **dict(C=3)})"),
            "{'A': 0, 'C': 3}"
        );
        assert_eq!(text("str(dict({'A': 1}, A=2, B=3))"), "{'A': 2, 'B': 3}");
        assert_eq!(ev("dict([('A', 1), ('B', 2)])['B']"), Int(2));
        assert_eq!(ev("{'A': 1}.get('B', 5)"), Int(5));
        assert_eq!(ev("{'A': 1}.get('A')"), Int(1));
        assert_eq!(ev("{'A': 1}.get('B')"), None);
        assert_eq!(ev("'A' in {'A': 1}"), Bool(true));
        assert_eq!(ev("{'A': 1, 'B': 2} == dict(B=2, A=1)"), Bool(true));
        assert_eq!(ev("bool({})"), Bool(false));
        // keys(), values(), items() as lists (CPython's views give the same
        // items through list(), len() and a for).
        assert_eq!(text("str(list({'A': 1, 'B': 2}.keys()))"), "['A', 'B']");
        assert_eq!(text("str(list({'A': 1, 'B': [2]}.values()))"), "[1, [2]]");
        assert_eq!(
            text("str(list(dict(A=1, B=2).items()))"),
            "[('A', 1), ('B', 2)]"
        );
        assert_eq!(ev("len({'A': 1, 'B': 2}.items())"), Int(2));
        assert_eq!(ev("sum([v for k, v in {'A': 1, 'B': 2}.items()])"), Int(3));
        assert_eq!(
            ev("[k for k in {'A': 1, 'B': 2}.keys()][1]"),
            Str("B".into())
        );
    }

    #[test]
    fn dict_errors_are_messages() {
        for (expr, msg) in [
            ("{1: 2}", "a dict key must be a text"),
            ("dict(**[1])", "must be a dict"),
            ("_F(A=1, **{'A': 2})", "keyword A is repeated in _F(...)"),
            ("dict(A=1, A=2)", "keyword A is repeated in dict(...)"),
            ("_F(1)", "_F(...) takes keyword arguments only"),
            ("{'A': 1}['B']", "the dict has no key 'B'"),
            ("{'A': 1}[0]", "a dict's item is read with its key"),
            (
                "{'A': 1}.update(B=2)",
                "method 'update' of a dict (_F(...)) is not supported",
            ),
            ("{'A': 1}.keys(1)", "keys() takes no argument (1 given)"),
            ("{'A': 1}.get()", "get() takes 1 or 2 arguments (0 given)"),
            ("dict([1])", "cannot loop over the integer 1"),
            ("print(1)", "call it as a statement of its own"),
        ] {
            let e = eval_in("", expr).expect_err(expr);
            assert!(e.contains(msg), "{expr}: {e}");
        }
    }

    #[test]
    fn python_errors_are_messages() {
        for (expr, msg) in [
            (
                "(1, 2)[2]",
                "index 2 is out of range: the tuple has 2 items",
            ),
            ("'a'[1.0]", "an index must be an integer"),
            ("'%d %d' % 1", "not enough arguments for format string"),
            ("'%d' % (1, 2)", "not all arguments converted"),
            (
                "'%d' % 'x'",
                "%d format: a real number is required, not str",
            ),
            ("1 // 0", "integer division or modulo by zero"),
            ("1. % 0", "float modulo by zero"),
            ("1 < 'a'", "'<' is not supported between"),
            ("1 in 2", "'in' needs a tuple, a list, a range or a text"),
            ("[x for x in 3]", "cannot loop over the integer 3"),
            ("math.sqrt(-1.)", "math.sqrt(): math domain error"),
            ("math.nan", "math.nan is not available"),
            ("np.linspace(0., 1., 3)", "numpy.linspace is not available"),
            ("np.sqrt(-1.)", "numpy.sqrt(): math domain error"),
            ("range(1.5)", "range() takes integers"),
            ("range(1, 2, 0)", "step must not be zero"),
            ("len(3)", "has no len()"),
            (
                "'x'.upper()",
                "method 'upper' of the text 'x' is not supported",
            ),
            (
                "(1).real",
                "attribute access is supported on the modules math and numpy only",
            ),
            ("'ab' * 100000000", "a text longer than"),
            ("list(range(10**7))", "a range of more than 1000000 values"),
            ("[1].append(2)", "write it as a statement of its own"),
            ("str(zip())", "the text of a zip object is its address"),
            ("zip(1)", "cannot loop over the integer 1"),
            ("enumerate([1])[0]", "an enumerate object cannot be indexed"),
            ("y", "name 'y' is not defined"),
        ] {
            let e = eval_in("", expr).expect_err(expr);
            assert!(e.contains(msg), "{expr}: {e}");
        }
        // Comprehension variables do not leak, as in Python 3.
        let e = eval_in("A = [i for i in range(3)]", "i").unwrap_err();
        assert!(e.contains("name 'i' is not defined"), "{e}");
    }
}
