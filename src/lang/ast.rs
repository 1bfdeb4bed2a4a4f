//! The spanned syntax tree of a command file.
//!
//! The language is the small subset of Python that code_aster command files
//! use: assignments, calls with keyword arguments, tuples, numbers, strings
//! and arithmetic. `_F(...)`, builtins and commands are all [`ExprKind::Call`];
//! telling them apart is the checker's job, not the parser's.

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

#[derive(Debug, Clone, PartialEq)]
pub enum StmtKind {
    /// `NAME = expr`
    Assign { target: Ident, value: Expr },
    /// A bare expression, in practice a command call such as `FIN()`.
    Expr(Expr),
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
    Pow,
}

impl BinOp {
    pub fn symbol(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::Pow => "**",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnOp {
    Neg,
    Pos,
}

#[derive(Debug, Clone, PartialEq)]
pub enum ExprKind {
    Int(i64),
    Real(f64),
    Str(String),
    /// `None`, accepted as "keyword absent" as in Python command files.
    NoneLit,
    Name(String),
    /// `(a, b,)` or `[a, b]`; a parenthesised single expression is not a tuple.
    Tuple(Vec<Expr>),
    Call {
        func: Ident,
        args: Vec<Arg>,
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
}

/// One argument of a call: `KEY=value` or a positional `value`.
#[derive(Debug, Clone, PartialEq)]
pub struct Arg {
    pub name: Option<Ident>,
    pub value: Expr,
    pub span: Span,
}
