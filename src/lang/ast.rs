//! The spanned syntax tree of a command file.
//!
//! The language is the part of Python that code_aster command files use:
//! assignments, calls with keyword arguments, tuples and lists, numbers,
//! strings, arithmetic, comparisons and logic, indexing, list
//! comprehensions, `import math`, and `if`/`for` blocks. `_F(...)`, builtins
//! and commands are all [`ExprKind::Call`]; telling them apart is the
//! checker's job, not the parser's.

use crate::diag::Span;

#[derive(Debug, Clone, PartialEq)]
pub struct Program {
    pub stmts: Vec<Stmt>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Ident {
    pub name: String,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Stmt {
    pub kind: StmtKind,
    pub span: Span,
}

/// What a `for` (or a comprehension's `for`) binds: `x` or `x, y`.
#[derive(Debug, Clone, PartialEq)]
pub enum Target {
    Name(Ident),
    /// `a, b` (also `a,`): the item is unpacked; a loop's items may
    /// themselves be tuples (`for a, (b, c) in ...`).
    Tuple(Vec<Target>),
}

impl Target {
    /// The names the target binds, in order (nested tuples flattened).
    pub fn names(&self) -> Vec<&Ident> {
        match self {
            Target::Name(n) => vec![n],
            Target::Tuple(v) => v.iter().flat_map(|t| t.names()).collect(),
        }
    }
}

/// One `import` item: `math`, `numpy as np`, `code_aster.Commands`.
#[derive(Debug, Clone, PartialEq)]
pub struct ImportItem {
    /// The dotted module name, as written (`code_aster.Commands`).
    pub module: Ident,
    pub alias: Option<Ident>,
}

#[derive(Debug, Clone, PartialEq)]
pub enum StmtKind {
    /// `NAME = expr`
    Assign {
        target: Ident,
        value: Expr,
    },
    /// `a, b = expr`: the value is unpacked into the names.
    Unpack {
        targets: Vec<Ident>,
        value: Expr,
    },
    /// `NAME op= value` (`+=`, `-=`, `*=`, `/=`, `//=`, `%=`, `**=`):
    /// `NAME = NAME op value`, except that a list is changed in place by
    /// `+=` (extended by any iterable) and `*=`, as Python does.
    AugAssign {
        target: Ident,
        op: BinOp,
        value: Expr,
    },
    /// `NAME[index] = value`: one item of a list or a dict.
    SetItem {
        target: Ident,
        index: Expr,
        value: Expr,
    },
    /// A bare expression, in practice a command call such as `FIN()` or
    /// `L.append(x)`.
    Expr(Expr),
    Pass,
    /// `import math`, `import numpy as np`
    Import(Vec<ImportItem>),
    /// `from math import sqrt, pi as PI`; `names` is `None` for `import *`.
    FromImport {
        module: Ident,
        names: Option<Vec<(Ident, Option<Ident>)>>,
    },
    /// `if c1: ... elif c2: ... else: ...`; `orelse` is empty without `else`.
    If {
        branches: Vec<(Expr, Vec<Stmt>)>,
        orelse: Vec<Stmt>,
    },
    /// `for target in iter: body`
    For {
        target: Target,
        iter: Expr,
        body: Vec<Stmt>,
    },
}

#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    FloorDiv,
    Mod,
    Pow,
}

impl BinOp {
    pub fn symbol(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::FloorDiv => "//",
            BinOp::Mod => "%",
            BinOp::Pow => "**",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnOp {
    Neg,
    Pos,
    Not,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CmpOp {
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    In,
    NotIn,
}

impl CmpOp {
    pub fn symbol(self) -> &'static str {
        match self {
            CmpOp::Eq => "==",
            CmpOp::Ne => "!=",
            CmpOp::Lt => "<",
            CmpOp::Le => "<=",
            CmpOp::Gt => ">",
            CmpOp::Ge => ">=",
            CmpOp::In => "in",
            CmpOp::NotIn => "not in",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LogicOp {
    And,
    Or,
}

/// One `for target in iter if cond ...` of a list comprehension.
#[derive(Debug, Clone, PartialEq)]
pub struct Comprehension {
    pub target: Target,
    pub iter: Expr,
    pub ifs: Vec<Expr>,
}

#[derive(Debug, Clone, PartialEq)]
pub enum ExprKind {
    Int(i64),
    Real(f64),
    Str(String),
    Bool(bool),
    /// `None`, accepted as "keyword absent" as in Python command files.
    NoneLit,
    Name(String),
    /// `(a, b,)`; a parenthesised single expression is not a tuple.
    Tuple(Vec<Expr>),
    /// `[a, b]`
    List(Vec<Expr>),
    /// `{key: value, **d, ...}`: a `None` key is a `**d` item.
    Dict(Vec<(Option<Expr>, Expr)>),
    /// `[elt for x in L if c ...]`
    ListComp {
        elt: Box<Expr>,
        generators: Vec<Comprehension>,
    },
    Call {
        func: Ident,
        args: Vec<Arg>,
    },
    /// `value.method(args)`: `math.sqrt(x)`, `L.append(x)`.
    MethodCall {
        value: Box<Expr>,
        method: Ident,
        args: Vec<Arg>,
    },
    /// `value.attr`: `math.pi`.
    Attribute {
        value: Box<Expr>,
        attr: Ident,
    },
    /// `value[index]`
    Index {
        value: Box<Expr>,
        index: Box<Expr>,
    },
    /// `value[lower:upper:step]`, each part optional.
    Slice {
        value: Box<Expr>,
        lower: Option<Box<Expr>>,
        upper: Option<Box<Expr>>,
        step: Option<Box<Expr>>,
    },
    Unary {
        op: UnOp,
        operand: Box<Expr>,
    },
    Binary {
        op: BinOp,
        lhs: Box<Expr>,
        rhs: Box<Expr>,
    },
    /// `a < b <= c`: Python's chained comparison, each operand evaluated
    /// once.
    Compare {
        first: Box<Expr>,
        rest: Vec<(CmpOp, Expr)>,
    },
    /// `a and b`, `a or b`, short-circuiting and giving an operand, as in
    /// Python.
    Logic {
        op: LogicOp,
        lhs: Box<Expr>,
        rhs: Box<Expr>,
    },
    /// `then if cond else orelse`
    IfElse {
        cond: Box<Expr>,
        then: Box<Expr>,
        orelse: Box<Expr>,
    },
}

impl Expr {
    /// The direct sub-expressions, in source order, for passes that only
    /// look for something inside a tree (the names it reads...).
    pub fn children(&self) -> Vec<&Expr> {
        match &self.kind {
            ExprKind::Int(_)
            | ExprKind::Real(_)
            | ExprKind::Str(_)
            | ExprKind::Bool(_)
            | ExprKind::NoneLit
            | ExprKind::Name(_) => Vec::new(),
            ExprKind::Tuple(items) | ExprKind::List(items) => items.iter().collect(),
            ExprKind::Dict(items) => items
                .iter()
                .flat_map(|(k, v)| k.iter().chain(std::iter::once(v)))
                .collect(),
            ExprKind::ListComp { elt, generators } => {
                let mut v = vec![elt.as_ref()];
                for g in generators {
                    v.push(&g.iter);
                    v.extend(g.ifs.iter());
                }
                v
            }
            ExprKind::Call { args, .. } => args.iter().map(|a| &a.value).collect(),
            ExprKind::MethodCall { value, args, .. } => {
                let mut v = vec![value.as_ref()];
                v.extend(args.iter().map(|a| &a.value));
                v
            }
            ExprKind::Attribute { value, .. } => vec![value],
            ExprKind::Index { value, index } => vec![value, index],
            ExprKind::Slice {
                value,
                lower,
                upper,
                step,
            } => {
                let mut v = vec![value.as_ref()];
                v.extend(
                    [lower, upper, step]
                        .into_iter()
                        .flatten()
                        .map(|b| b.as_ref()),
                );
                v
            }
            ExprKind::Unary { operand, .. } => vec![operand],
            ExprKind::Binary { lhs, rhs, .. } | ExprKind::Logic { lhs, rhs, .. } => {
                vec![lhs, rhs]
            }
            ExprKind::Compare { first, rest } => {
                let mut v = vec![first.as_ref()];
                v.extend(rest.iter().map(|(_, e)| e));
                v
            }
            ExprKind::IfElse { cond, then, orelse } => vec![then, cond, orelse],
        }
    }
}

/// One argument of a call: `KEY=value`, a positional `value`, or
/// `**value` (`unpack`, without a name): the items of a dict as keywords.
#[derive(Debug, Clone, PartialEq)]
pub struct Arg {
    pub name: Option<Ident>,
    pub unpack: bool,
    pub value: Expr,
    pub span: Span,
}
