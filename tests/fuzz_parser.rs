//! Property tests of the parser.
//!
//! 1. Random token streams (names, Python keywords, numbers in every form
//!    and malformed ones, strings with escapes or unterminated, punctuation,
//!    newlines of every kind, indentation, comments, arbitrary UTF-8, the
//!    operators and keywords of blocks, comprehensions and imports) never make `parse`
//!    panic; an error always points inside the source and renders; a
//!    success gives a tree whose spans nest inside their parents.
//! 2. Round trip: a random syntax tree printed with random layout (spaces,
//!    newlines inside brackets, comments, continuations, both quotes, every
//!    number form, redundant parentheses, trailing commas, `;`, blocks
//!    indented with spaces or tabs, bodies on the header's line) parses back
//!    to the same tree, and so does the parsed tree printed again. The
//!    printed text, damaged by a few random edits, goes through the checks
//!    of property 1: near-valid files reach error paths that random token
//!    soup rarely does.
//!
//! The number of cases is `ASTER_FUZZ_CASES` (default 100000) for the token
//! streams and a tenth of it for the round trip, whose inputs are larger:
//! `ASTER_FUZZ_CASES=1000000 cargo test --test fuzz_parser` (about 4 minutes).

use aster::diag::{Source, Span};
use aster::lang::ast::{
    Arg, BinOp, CmpOp, Comprehension, Expr, ExprKind, Ident, ImportItem, LogicOp, Program, Stmt,
    StmtKind, Target, UnOp,
};
use aster::lang::parser::parse;
use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};

fn cases() -> u32 {
    std::env::var("ASTER_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(100_000)
}

// ---------------------------------------------------------------------------
// 1. Token streams
// ---------------------------------------------------------------------------

fn token() -> impl Strategy<Value = String> {
    let fixed = prop::sample::select(vec![
        "DEBUT",
        "FIN",
        "_F",
        "MA",
        "reuse",
        "None",
        "True",
        "for",
        "import",
        "if",
        "lambda",
        "int",
        "min",
        "elif",
        "else",
        "pass",
        "in",
        "not",
        "and",
        "or",
        "from",
        "as",
        "while",
        "def",
        "False",
        "math",
        "np",
        "append",
        "range",
        "%",
        "<",
        ">",
        "<=",
        ">=",
        "!=",
        ":",
        ":",
        "\n    ",
        "\n  ",
        "\n\t",
        "    ",
        "(",
        ")",
        "[",
        "]",
        "(",
        ")",
        ",",
        ",",
        "=",
        "=",
        "==",
        ";",
        "+",
        "-",
        "*",
        "/",
        "**",
        "//",
        ".",
        ":",
        "{",
        "}",
        "@",
        "$",
        "\\",
        "\\\n",
        "\n",
        "\n",
        "\r\n",
        "\r",
        " ",
        "\t",
        "# comment",
        "#",
        "'",
        "\"",
        "'''",
        "1.E",
        "1e",
        "007",
        "1.5.3",
        "\u{FEFF}",
        "é",
        "\0",
    ])
    .prop_map(str::to_string);
    prop_oneof![
        4 => fixed,
        2 => "[A-Za-z_][A-Za-z0-9_]{0,8}",
        1 => "[0-9]{1,5}",
        1 => "[0-9]{0,3}\\.[0-9]{0,3}([eE][+-]?[0-9]{0,3})?",
        1 => "[0-9]{19,25}",
        1 => "[0-9]{1,3}[eE][+-]?[0-9]{1,4}",
        1 => "'([^'\\\\\n]|\\\\[nt'\"\\\\d])*'?",
        1 => "\"([^\"\\\\\n]|\\\\[nt'\"\\\\])*\"?",
        1 => any::<String>().prop_map(|s| s.chars().take(3).collect()),
    ]
}

fn token_stream() -> impl Strategy<Value = String> {
    prop::collection::vec((token(), any::<bool>()), 0..40).prop_map(|tokens| {
        let mut s = String::new();
        for (t, space) in tokens {
            s.push_str(&t);
            if space {
                s.push(' ');
            }
        }
        s
    })
}

fn check_span(text: &str, s: Span, what: &str) {
    assert!(
        s.start <= s.end && s.end <= text.len(),
        "{what} span {s:?} outside a source of {} bytes",
        text.len()
    );
    assert!(
        text.is_char_boundary(s.start) && text.is_char_boundary(s.end),
        "{what} span {s:?} splits a character"
    );
}

fn inside(child: Span, parent: Span) -> bool {
    parent.start <= child.start && child.end <= parent.end
}

fn check_expr(text: &str, e: &Expr, parent: Span) {
    check_span(text, e.span, "expression");
    assert!(inside(e.span, parent), "{:?} not inside {parent:?}", e.span);
    match &e.kind {
        ExprKind::Call { func, args } => {
            assert!(inside(func.span, e.span));
            for a in args {
                assert!(inside(a.span, e.span));
                if let Some(n) = &a.name {
                    assert!(inside(n.span, a.span));
                }
                check_expr(text, &a.value, a.span);
            }
        }
        _ => e
            .children()
            .into_iter()
            .for_each(|c| check_expr(text, c, e.span)),
    }
}

fn check_stmts(text: &str, stmts: &[Stmt], parent: Option<Span>) {
    for stmt in stmts {
        check_span(text, stmt.span, "statement");
        if let Some(p) = parent {
            assert!(inside(stmt.span, p), "{:?} not inside {p:?}", stmt.span);
        }
        match &stmt.kind {
            StmtKind::Assign { target, value } => {
                assert!(inside(target.span, stmt.span));
                check_expr(text, value, stmt.span);
            }
            StmtKind::Unpack { value, .. } => check_expr(text, value, stmt.span),
            StmtKind::AugAssign { target, value, .. } => {
                assert!(inside(target.span, stmt.span));
                check_expr(text, value, stmt.span);
            }
            StmtKind::SetItem {
                target,
                index,
                value,
            } => {
                assert!(inside(target.span, stmt.span));
                check_expr(text, index, stmt.span);
                check_expr(text, value, stmt.span);
            }
            StmtKind::Expr(e) => check_expr(text, e, stmt.span),
            StmtKind::If { branches, orelse } => {
                for (c, b) in branches {
                    check_expr(text, c, stmt.span);
                    check_stmts(text, b, Some(stmt.span));
                }
                check_stmts(text, orelse, Some(stmt.span));
            }
            StmtKind::For { iter, body, .. } => {
                check_expr(text, iter, stmt.span);
                check_stmts(text, body, Some(stmt.span));
            }
            StmtKind::Pass | StmtKind::Import(_) | StmtKind::FromImport { .. } => {}
        }
    }
}

/// Parses `text` and checks what any result must satisfy.
fn check_no_panic(text: &str) {
    let src = Source::new("fuzz.comm", text);
    match parse(&src) {
        Ok(program) => check_stmts(text, &program.stmts, None),
        Err(d) => {
            assert!(d.message.starts_with("syntax error: "), "{}", d.message);
            let span = d.span.expect("a syntax error has a position");
            check_span(text, span, "error");
            let rendered = d.render(Some(&src));
            assert!(rendered.contains("fuzz.comm:"), "{rendered}");
        }
    }
}

#[test]
fn random_token_streams_never_panic() {
    let mut runner = TestRunner::new(Config {
        cases: cases(),
        failure_persistence: None,
        ..Config::default()
    });
    runner
        .run(&token_stream(), |text| {
            check_no_panic(&text);
            Ok(())
        })
        .unwrap();
}

// ---------------------------------------------------------------------------
// 2. Round trip
// ---------------------------------------------------------------------------

const KEYWORDS: &[&str] = &[
    "False", "None", "True", "and", "as", "assert", "async", "await", "break", "class", "continue",
    "def", "del", "elif", "else", "except", "finally", "for", "from", "global", "if", "import",
    "in", "is", "lambda", "nonlocal", "not", "or", "pass", "raise", "return", "try", "while",
    "with", "yield",
];

fn ident() -> impl Strategy<Value = Ident> {
    "[A-Za-z_][A-Za-z0-9_]{0,6}"
        .prop_filter("not a Python keyword", |s| !KEYWORDS.contains(&s.as_str()))
        .prop_map(|name| Ident {
            name,
            span: Span::default(),
        })
}

fn e(kind: ExprKind) -> Expr {
    Expr {
        kind,
        span: Span::default(),
    }
}

fn real() -> impl Strategy<Value = f64> {
    prop_oneof![
        (0u32..1_000_000).prop_map(f64::from),
        (0u32..1000, -12i32..12).prop_map(|(m, x)| f64::from(m) * 10f64.powi(x)),
        (0.0..1e6f64),
        any::<f64>().prop_filter("finite, positive sign", |v| v.is_finite()
            && v.is_sign_positive()),
    ]
}

fn target() -> impl Strategy<Value = Target> {
    prop_oneof![
        3 => ident().prop_map(Target::Name),
        1 => prop::collection::vec(ident(), 2..4)
            .prop_map(|v| Target::Tuple(v.into_iter().map(Target::Name).collect())),
    ]
}

fn expr() -> impl Strategy<Value = Expr> {
    let leaf = prop_oneof![
        (0..=i64::MAX).prop_map(|i| e(ExprKind::Int(i))),
        real().prop_map(|r| e(ExprKind::Real(r))),
        "([a-zA-Z0-9 _.#,()=%:]|'|\"|\\\\|\n|\t|\r|é|€)*".prop_map(|s| e(ExprKind::Str(s))),
        Just(e(ExprKind::NoneLit)),
        any::<bool>().prop_map(|b| e(ExprKind::Bool(b))),
        ident().prop_map(|i| e(ExprKind::Name(i.name))),
    ];
    leaf.prop_recursive(5, 40, 4, |inner| {
        let op = prop::sample::select(vec![
            BinOp::Add,
            BinOp::Sub,
            BinOp::Mul,
            BinOp::Div,
            BinOp::FloorDiv,
            BinOp::Mod,
            BinOp::Pow,
        ]);
        let cmp = prop::sample::select(vec![
            CmpOp::Eq,
            CmpOp::Ne,
            CmpOp::Lt,
            CmpOp::Le,
            CmpOp::Gt,
            CmpOp::Ge,
            CmpOp::In,
            CmpOp::NotIn,
        ]);
        let arg = |named: bool, inner: BoxedStrategy<Expr>| {
            (ident(), inner).prop_map(move |(n, value)| Arg {
                name: named.then_some(n),
                unpack: false,
                value,
                span: Span::default(),
            })
        };
        let b = |x: Expr| Box::new(x);
        let opt = |inner: BoxedStrategy<Expr>| prop::option::of(inner.prop_map(Box::new));
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..4).prop_map(|v| e(ExprKind::Tuple(v))),
            prop::collection::vec(inner.clone(), 0..4).prop_map(|v| e(ExprKind::List(v))),
            prop::collection::vec((prop::option::of(inner.clone()), inner.clone()), 0..3)
                .prop_map(|v| e(ExprKind::Dict(v))),
            (ident(), prop::collection::vec(inner.clone(), 1..3)).prop_map(|(func, v)| {
                let args = v
                    .into_iter()
                    .map(|value| Arg {
                        name: None,
                        unpack: true,
                        value,
                        span: Span::default(),
                    })
                    .collect();
                e(ExprKind::Call { func, args })
            }),
            (
                ident(),
                prop::collection::vec(arg(false, inner.clone().boxed()), 0..3),
                prop::collection::vec(arg(true, inner.clone().boxed()), 0..3),
            )
                .prop_map(|(func, mut args, kw)| {
                    args.extend(kw);
                    e(ExprKind::Call { func, args })
                }),
            (0u8..3, inner.clone()).prop_map(|(k, x)| e(ExprKind::Unary {
                op: [UnOp::Neg, UnOp::Pos, UnOp::Not][k as usize],
                operand: Box::new(x),
            })),
            (op, inner.clone(), inner.clone()).prop_map(move |(op, l, r)| e(ExprKind::Binary {
                op,
                lhs: b(l),
                rhs: b(r),
            })),
            (
                inner.clone(),
                prop::collection::vec((cmp, inner.clone()), 1..3)
            )
                .prop_map(move |(first, rest)| e(ExprKind::Compare {
                    first: b(first),
                    rest
                })),
            (any::<bool>(), inner.clone(), inner.clone()).prop_map(move |(and, l, r)| e(
                ExprKind::Logic {
                    op: if and { LogicOp::And } else { LogicOp::Or },
                    lhs: b(l),
                    rhs: b(r),
                }
            )),
            (inner.clone(), inner.clone(), inner.clone()).prop_map(move |(c, t, o)| e(
                ExprKind::IfElse {
                    cond: b(c),
                    then: b(t),
                    orelse: b(o),
                }
            )),
            (inner.clone(), inner.clone()).prop_map(move |(v, i)| e(ExprKind::Index {
                value: b(v),
                index: b(i),
            })),
            (
                inner.clone(),
                opt(inner.clone().boxed()),
                opt(inner.clone().boxed()),
                opt(inner.clone().boxed())
            )
                .prop_map(|(v, lower, upper, step)| e(ExprKind::Slice {
                    value: Box::new(v),
                    lower,
                    upper,
                    step,
                })),
            (inner.clone(), ident())
                .prop_map(move |(v, attr)| e(ExprKind::Attribute { value: b(v), attr })),
            (
                inner.clone(),
                ident(),
                prop::collection::vec(arg(false, inner.clone().boxed()), 0..2)
            )
                .prop_map(move |(v, method, args)| e(ExprKind::MethodCall {
                    value: b(v),
                    method,
                    args,
                })),
            (
                inner.clone(),
                prop::collection::vec(
                    (
                        target(),
                        inner.clone(),
                        prop::collection::vec(inner.clone(), 0..2)
                    ),
                    1..3
                )
            )
                .prop_map(move |(elt, gens)| e(ExprKind::ListComp {
                    elt: b(elt),
                    generators: gens
                        .into_iter()
                        .map(|(target, iter, ifs)| Comprehension { target, iter, ifs })
                        .collect(),
                })),
        ]
    })
}

fn simple_stmt() -> impl Strategy<Value = StmtKind> {
    prop_oneof![
        6 => (ident(), expr()).prop_map(|(target, value)| StmtKind::Assign { target, value }),
        4 => expr().prop_map(StmtKind::Expr),
        1 => (ident(), expr(), expr())
            .prop_map(|(target, index, value)| StmtKind::SetItem { target, index, value }),
        1 => (prop::collection::vec(ident(), 2..4), expr())
            .prop_map(|(targets, value)| StmtKind::Unpack { targets, value }),
        1 => Just(StmtKind::Pass),
        1 => prop::collection::vec((ident(), prop::option::of(ident())), 1..3).prop_map(|v| {
            StmtKind::Import(
                v.into_iter()
                    .map(|(module, alias)| ImportItem { module, alias })
                    .collect(),
            )
        }),
        1 => (ident(), prop::option::of(prop::collection::vec((ident(), prop::option::of(ident())), 1..3)))
            .prop_map(|(module, names)| StmtKind::FromImport { module, names }),
    ]
}

fn stmt_of(kind: StmtKind) -> Stmt {
    Stmt {
        kind,
        span: Span::default(),
    }
}

fn program() -> impl Strategy<Value = Program> {
    let simple = simple_stmt().prop_map(stmt_of);
    let stmt = simple.prop_recursive(2, 12, 3, |inner| {
        let body = prop::collection::vec(inner, 1..3);
        prop_oneof![
            (target(), expr(), body.clone())
                .prop_map(|(target, iter, body)| stmt_of(StmtKind::For { target, iter, body })),
            (
                prop::collection::vec((expr(), body.clone()), 1..3),
                prop::collection::vec(simple_stmt().prop_map(stmt_of), 0..2)
            )
                .prop_map(|(branches, orelse)| stmt_of(StmtKind::If { branches, orelse })),
        ]
    });
    prop::collection::vec(stmt, 0..6).prop_map(|stmts| Program { stmts })
}

/// Binding strength, Python's: conditional < or < and < not < comparisons
/// < sums < products < signs < powers < postfix and atoms.
fn prec(e: &Expr) -> u8 {
    match &e.kind {
        ExprKind::IfElse { .. } => 0,
        ExprKind::Logic { op, .. } => match op {
            LogicOp::Or => 1,
            LogicOp::And => 2,
        },
        ExprKind::Unary { op: UnOp::Not, .. } => 3,
        ExprKind::Compare { .. } => 4,
        ExprKind::Binary { op, .. } => match op {
            BinOp::Add | BinOp::Sub => 5,
            BinOp::Mul | BinOp::Div | BinOp::FloorDiv | BinOp::Mod => 6,
            BinOp::Pow => 8,
        },
        ExprKind::Unary { .. } => 7,
        _ => 9,
    }
}

/// Prints source text for a tree; `noise` chooses among equivalent
/// layouts so the parser sees many spellings of the same tree.
struct Printer<'a> {
    out: String,
    noise: std::iter::Cycle<std::slice::Iter<'a, u8>>,
}

impl Printer<'_> {
    fn pick(&mut self, n: u8) -> u8 {
        self.noise.next().map_or(0, |b| b % n)
    }

    /// Space between tokens inside brackets, where newlines are free.
    fn gap_in(&mut self) {
        match self.pick(8) {
            0 => self.out.push_str("\n    "),
            1 => self.out.push_str("  # note (')\n  "),
            2 => self.out.push_str("\r\n\t"),
            3 | 4 => self.out.push(' '),
            _ => {}
        }
    }

    /// Space between tokens outside brackets.
    fn gap_out(&mut self, in_brackets: bool) {
        if in_brackets {
            return self.gap_in();
        }
        match self.pick(8) {
            0 => self.out.push_str(" \\\n  "),
            1 | 2 => self.out.push(' '),
            3 => self.out.push('\t'),
            _ => {}
        }
    }

    fn real(&mut self, v: f64) {
        let dbg = format!("{v:?}");
        let text = match self.pick(5) {
            0 => format!("{v:e}"),
            1 => format!("{v:E}"),
            2 if v.fract() == 0.0 && v < 1e15 => format!("{}.", v as i64),
            3 if dbg.starts_with("0.") => dbg[1..].to_string(),
            _ => dbg,
        };
        // `{:e}` of an integral value has no point ("3e0"): still a float.
        self.out.push_str(&text);
    }

    fn string(&mut self, s: &str) {
        let q = if self.pick(2) == 0 { '\'' } else { '"' };
        let split = if s.is_empty() {
            0
        } else {
            self.pick(4) as usize
        };
        self.out.push(q);
        for (i, c) in s.chars().enumerate() {
            if split != 0 && i == split && s.chars().count() > split {
                self.out.push(q);
                self.out.push(' ');
                self.out.push(q);
            }
            match c {
                '\\' => self.out.push_str("\\\\"),
                '\n' => self.out.push_str("\\n"),
                '\t' => self.out.push_str("\\t"),
                '\r' => self.out.push_str("\\r"),
                c if c == q => {
                    self.out.push('\\');
                    self.out.push(c);
                }
                c => self.out.push(c),
            }
        }
        self.out.push(q);
    }

    fn expr(&mut self, e: &Expr, br: bool) {
        let redundant = self.pick(10) == 0;
        if redundant {
            self.out.push('(');
            self.gap_in();
            self.bare(e, true);
            self.gap_in();
            self.out.push(')');
        } else {
            self.bare(e, br);
        }
    }

    fn wrapped(&mut self, e: &Expr, need: bool, br: bool) {
        if need {
            self.out.push('(');
            self.bare(e, true);
            self.out.push(')');
        } else {
            self.expr(e, br);
        }
    }

    fn sequence(&mut self, items: &[Expr], open: char, close: char, one_needs_comma: bool) {
        self.out.push(open);
        for (i, it) in items.iter().enumerate() {
            self.gap_in();
            self.expr(it, true);
            self.gap_in();
            let last = i + 1 == items.len();
            if !last || (one_needs_comma && items.len() == 1) || self.pick(3) == 0 {
                self.out.push(',');
            }
        }
        self.gap_in();
        self.out.push(close);
    }

    fn bare(&mut self, e: &Expr, br: bool) {
        match &e.kind {
            ExprKind::Int(i) => self.out.push_str(&i.to_string()),
            ExprKind::Real(r) => self.real(*r),
            ExprKind::Str(s) => self.string(s),
            ExprKind::NoneLit => self.out.push_str("None"),
            ExprKind::Name(n) => self.out.push_str(n),
            ExprKind::Tuple(items) => self.sequence(items, '(', ')', true),
            ExprKind::Call { func, args } => {
                self.out.push_str(&func.name);
                self.out.push('(');
                for (i, a) in args.iter().enumerate() {
                    self.gap_in();
                    if let Some(n) = &a.name {
                        self.out.push_str(&n.name);
                        self.gap_in();
                        self.out.push('=');
                        self.gap_in();
                    } else if a.unpack {
                        self.out.push_str("**");
                        self.gap_in();
                    }
                    self.expr(&a.value, true);
                    if i + 1 < args.len() || self.pick(3) == 0 {
                        self.out.push(',');
                    }
                }
                self.gap_in();
                self.out.push(')');
            }
            ExprKind::Bool(b) => self.out.push_str(if *b { "True" } else { "False" }),
            ExprKind::List(items) => self.sequence(items, '[', ']', false),
            ExprKind::Dict(items) => {
                self.out.push('{');
                for (i, (k, v)) in items.iter().enumerate() {
                    self.gap_in();
                    match k {
                        Some(k) => {
                            self.expr(k, true);
                            self.gap_in();
                            self.out.push(':');
                            self.gap_in();
                            self.expr(v, true);
                        }
                        None => {
                            self.out.push_str("**");
                            // `**` takes a sum: anything looser in brackets.
                            self.wrapped(v, prec(v) < 5, true);
                        }
                    }
                    self.gap_in();
                    if i + 1 < items.len() || self.pick(3) == 0 {
                        self.out.push(',');
                    }
                }
                self.gap_in();
                self.out.push('}');
            }
            ExprKind::Unary {
                op: UnOp::Not,
                operand,
            } => {
                self.out.push_str("not ");
                self.gap_out(br);
                self.wrapped(operand, prec(operand) < 3, br);
            }
            ExprKind::Unary { op, operand } => {
                self.out.push(if *op == UnOp::Neg { '-' } else { '+' });
                self.gap_out(br);
                self.wrapped(operand, prec(operand) < 7, br);
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let p = prec(e);
                let (need_l, need_r) = if *op == BinOp::Pow {
                    (prec(lhs) <= 8, prec(rhs) < 7)
                } else {
                    (prec(lhs) < p, prec(rhs) <= p)
                };
                self.wrapped(lhs, need_l, br);
                self.gap_out(br);
                self.out.push_str(op.symbol());
                self.gap_out(br);
                self.wrapped(rhs, need_r, br);
            }
            ExprKind::Compare { first, rest } => {
                self.wrapped(first, prec(first) <= 4, br);
                for (op, x) in rest {
                    self.out.push(' ');
                    self.out.push_str(op.symbol());
                    self.out.push(' ');
                    self.wrapped(x, prec(x) <= 4, br);
                }
            }
            ExprKind::Logic { op, lhs, rhs } => {
                let p = prec(e);
                self.wrapped(lhs, prec(lhs) < p, br);
                self.out
                    .push_str(if *op == LogicOp::And { " and " } else { " or " });
                self.wrapped(rhs, prec(rhs) <= p, br);
            }
            ExprKind::IfElse { cond, then, orelse } => {
                self.wrapped(then, prec(then) == 0, br);
                self.out.push_str(" if ");
                self.wrapped(cond, prec(cond) == 0, br);
                self.out.push_str(" else ");
                self.expr(orelse, br);
            }
            ExprKind::Index { value, index } => {
                self.postfix_base(value, br);
                self.out.push('[');
                self.gap_in();
                self.expr(index, true);
                self.out.push(']');
            }
            ExprKind::Slice {
                value,
                lower,
                upper,
                step,
            } => {
                self.postfix_base(value, br);
                self.out.push('[');
                if let Some(l) = lower {
                    self.expr(l, true);
                }
                self.out.push(':');
                if let Some(u) = upper {
                    self.expr(u, true);
                }
                if step.is_some() || self.pick(2) == 0 {
                    self.out.push(':');
                }
                if let Some(s) = step {
                    self.expr(s, true);
                }
                self.out.push(']');
            }
            ExprKind::Attribute { value, attr } => {
                self.postfix_base(value, br);
                self.out.push('.');
                self.out.push_str(&attr.name);
            }
            ExprKind::MethodCall {
                value,
                method,
                args,
            } => {
                self.postfix_base(value, br);
                self.out.push('.');
                self.out.push_str(&method.name);
                self.out.push('(');
                for (i, a) in args.iter().enumerate() {
                    self.gap_in();
                    self.expr(&a.value, true);
                    if i + 1 < args.len() {
                        self.out.push(',');
                    }
                }
                self.out.push(')');
            }
            ExprKind::ListComp { elt, generators } => {
                self.out.push('[');
                self.gap_in();
                self.expr(elt, true);
                for g in generators {
                    self.out.push_str(" for ");
                    self.target(&g.target);
                    self.out.push_str(" in ");
                    self.wrapped(&g.iter, prec(&g.iter) == 0, true);
                    for c in &g.ifs {
                        self.out.push_str(" if ");
                        self.wrapped(c, prec(c) == 0, true);
                    }
                }
                self.gap_in();
                self.out.push(']');
            }
        }
    }

    /// The value before `[`, `.attr` or `.method(`: an atom, a call or
    /// another postfix; a number is wrapped (`1.real` would read `1.`).
    fn postfix_base(&mut self, v: &Expr, br: bool) {
        let need = prec(v) < 9 || matches!(v.kind, ExprKind::Int(_) | ExprKind::Real(_));
        self.wrapped(v, need, br);
    }

    fn target(&mut self, t: &Target) {
        match t {
            Target::Name(n) => self.out.push_str(&n.name),
            Target::Tuple(v) => {
                for (k, item) in v.iter().enumerate() {
                    if k > 0 {
                        self.out.push_str(", ");
                    }
                    if matches!(item, Target::Tuple(_)) {
                        self.out.push('(');
                        self.target(item);
                        self.out.push(')');
                    } else {
                        self.target(item);
                    }
                }
                if v.len() == 1 {
                    self.out.push(',');
                }
            }
        }
    }

    /// One simple statement, without its end.
    fn simple(&mut self, s: &Stmt) {
        match &s.kind {
            StmtKind::Assign { target, value } => {
                self.out.push_str(&target.name);
                self.gap_out(false);
                self.out.push('=');
                self.gap_out(false);
                self.expr(value, false);
            }
            StmtKind::Unpack { targets, value } => {
                self.target(&Target::Tuple(
                    targets.iter().cloned().map(Target::Name).collect(),
                ));
                self.out.push_str(" = ");
                self.expr(value, false);
            }
            StmtKind::AugAssign { target, op, value } => {
                self.out.push_str(&target.name);
                self.gap_out(false);
                self.out.push_str(op.symbol());
                self.out.push('=');
                self.gap_out(false);
                self.expr(value, false);
            }
            StmtKind::Expr(e) => self.expr(e, false),
            StmtKind::SetItem {
                target,
                index,
                value,
            } => {
                self.out.push_str(&target.name);
                self.out.push('[');
                self.gap_in();
                self.expr(index, true);
                self.out.push_str("] = ");
                self.expr(value, false);
            }
            StmtKind::Pass => self.out.push_str("pass"),
            StmtKind::Import(items) => {
                self.out.push_str("import ");
                for (i, it) in items.iter().enumerate() {
                    if i > 0 {
                        self.out.push_str(", ");
                    }
                    self.out.push_str(&it.module.name);
                    if let Some(a) = &it.alias {
                        self.out.push_str(" as ");
                        self.out.push_str(&a.name);
                    }
                }
            }
            StmtKind::FromImport { module, names } => {
                self.out.push_str("from ");
                self.out.push_str(&module.name);
                self.out.push_str(" import ");
                match names {
                    None => self.out.push('*'),
                    Some(v) => {
                        let paren = self.pick(3) == 0;
                        if paren {
                            self.out.push('(');
                        }
                        for (i, (n, a)) in v.iter().enumerate() {
                            if i > 0 {
                                self.out.push_str(", ");
                            }
                            self.out.push_str(&n.name);
                            if let Some(a) = a {
                                self.out.push_str(" as ");
                                self.out.push_str(&a.name);
                            }
                        }
                        if paren {
                            self.out.push(')');
                        }
                    }
                }
            }
            StmtKind::If { .. } | StmtKind::For { .. } => unreachable!("blocks are not simple"),
        }
    }

    fn is_block(s: &Stmt) -> bool {
        matches!(s.kind, StmtKind::If { .. } | StmtKind::For { .. })
    }

    /// The body of a header, after its ':': on the same line when it is
    /// simple statements and the noise says so, else indented below.
    fn body(&mut self, stmts: &[Stmt], indent: &str) {
        if !stmts.iter().any(Self::is_block) && self.pick(4) == 0 {
            self.out.push(' ');
            for (i, s) in stmts.iter().enumerate() {
                if i > 0 {
                    self.out.push_str("; ");
                }
                self.simple(s);
            }
            self.out.push('\n');
            return;
        }
        self.out.push('\n');
        let step = match self.pick(3) {
            0 => "\t",
            1 => "  ",
            _ => "    ",
        };
        self.block(stmts, &format!("{indent}{step}"));
    }

    fn block(&mut self, stmts: &[Stmt], indent: &str) {
        let mut at_line_start = true;
        for (k, s) in stmts.iter().enumerate() {
            if at_line_start {
                match self.pick(6) {
                    0 => self.out.push_str("# a comment line\n"),
                    1 => self.out.push_str("\n  \t\n"),
                    _ => {}
                }
                self.out.push_str(indent);
            }
            match &s.kind {
                StmtKind::For { target, iter, body } => {
                    self.out.push_str("for ");
                    self.target(target);
                    self.out.push_str(" in ");
                    self.expr(iter, false);
                    self.out.push(':');
                    self.body(body, indent);
                    at_line_start = true;
                    continue;
                }
                StmtKind::If { branches, orelse } => {
                    for (i, (c, b)) in branches.iter().enumerate() {
                        if i > 0 {
                            self.out.push_str(indent);
                        }
                        self.out.push_str(if i == 0 { "if " } else { "elif " });
                        self.expr(c, false);
                        self.out.push(':');
                        self.body(b, indent);
                    }
                    if !orelse.is_empty() {
                        self.out.push_str(indent);
                        self.out.push_str("else:");
                        self.body(orelse, indent);
                    }
                    at_line_start = true;
                    continue;
                }
                _ => self.simple(s),
            }
            // `;` only between simple statements of one line.
            let next_simple = stmts.get(k + 1).is_some_and(|n| !Self::is_block(n));
            at_line_start = true;
            match self.pick(6) {
                0 if next_simple => {
                    self.out.push_str("; ");
                    at_line_start = false;
                }
                1 => self.out.push_str(";\n"),
                2 => self.out.push_str("\r\n"),
                3 => self.out.push_str("  # end\n"),
                _ => self.out.push('\n'),
            }
        }
    }

    fn program(&mut self, p: &Program) {
        self.block(&p.stmts, "");
    }
}

fn print(p: &Program, noise: &[u8]) -> String {
    let default = [0u8];
    let noise = if noise.is_empty() {
        &default[..]
    } else {
        noise
    };
    let mut pr = Printer {
        out: String::new(),
        noise: noise.iter().cycle(),
    };
    pr.program(p);
    pr.out
}

fn strip_ident(i: &mut Ident) {
    i.span = Span::default();
}

fn strip_target(t: &mut Target) {
    match t {
        Target::Name(n) => strip_ident(n),
        Target::Tuple(v) => v.iter_mut().for_each(strip_target),
    }
}

fn strip_args(args: &mut [Arg]) {
    for a in args {
        a.span = Span::default();
        if let Some(n) = &mut a.name {
            strip_ident(n);
        }
        strip_expr(&mut a.value);
    }
}

fn strip_expr(e: &mut Expr) {
    e.span = Span::default();
    match &mut e.kind {
        ExprKind::Tuple(items) | ExprKind::List(items) => items.iter_mut().for_each(strip_expr),
        ExprKind::Dict(items) => {
            for (k, v) in items {
                if let Some(k) = k {
                    strip_expr(k);
                }
                strip_expr(v);
            }
        }
        ExprKind::Call { func, args } => {
            strip_ident(func);
            strip_args(args);
        }
        ExprKind::MethodCall {
            value,
            method,
            args,
        } => {
            strip_expr(value);
            strip_ident(method);
            strip_args(args);
        }
        ExprKind::Attribute { value, attr } => {
            strip_expr(value);
            strip_ident(attr);
        }
        ExprKind::Index { value, index } => {
            strip_expr(value);
            strip_expr(index);
        }
        ExprKind::Slice {
            value,
            lower,
            upper,
            step,
        } => {
            strip_expr(value);
            for b in [lower, upper, step].into_iter().flatten() {
                strip_expr(b);
            }
        }
        ExprKind::Unary { operand, .. } => strip_expr(operand),
        ExprKind::Binary { lhs, rhs, .. } | ExprKind::Logic { lhs, rhs, .. } => {
            strip_expr(lhs);
            strip_expr(rhs);
        }
        ExprKind::Compare { first, rest } => {
            strip_expr(first);
            rest.iter_mut().for_each(|(_, x)| strip_expr(x));
        }
        ExprKind::IfElse { cond, then, orelse } => {
            strip_expr(cond);
            strip_expr(then);
            strip_expr(orelse);
        }
        ExprKind::ListComp { elt, generators } => {
            strip_expr(elt);
            for g in generators {
                strip_target(&mut g.target);
                strip_expr(&mut g.iter);
                g.ifs.iter_mut().for_each(strip_expr);
            }
        }
        _ => {}
    }
}

fn strip_stmts(stmts: &mut [Stmt]) {
    for s in stmts {
        s.span = Span::default();
        match &mut s.kind {
            StmtKind::Assign { target, value } => {
                strip_ident(target);
                strip_expr(value);
            }
            StmtKind::Unpack { targets, value } => {
                targets.iter_mut().for_each(strip_ident);
                strip_expr(value);
            }
            StmtKind::AugAssign { target, value, .. } => {
                strip_ident(target);
                strip_expr(value);
            }
            StmtKind::Expr(e) => strip_expr(e),
            StmtKind::SetItem {
                target,
                index,
                value,
            } => {
                strip_ident(target);
                strip_expr(index);
                strip_expr(value);
            }
            StmtKind::Pass => {}
            StmtKind::Import(items) => {
                for it in items {
                    strip_ident(&mut it.module);
                    if let Some(a) = &mut it.alias {
                        strip_ident(a);
                    }
                }
            }
            StmtKind::FromImport { module, names } => {
                strip_ident(module);
                for (n, a) in names.iter_mut().flatten() {
                    strip_ident(n);
                    if let Some(a) = a {
                        strip_ident(a);
                    }
                }
            }
            StmtKind::If { branches, orelse } => {
                for (c, b) in branches {
                    strip_expr(c);
                    strip_stmts(b);
                }
                strip_stmts(orelse);
            }
            StmtKind::For { target, iter, body } => {
                strip_target(target);
                strip_expr(iter);
                strip_stmts(body);
            }
        }
    }
}

fn strip(mut p: Program) -> Program {
    strip_stmts(&mut p.stmts);
    p
}

/// One to three edits chosen by `noise`: delete a few characters, insert
/// a token, or duplicate a slice.
fn mutate(text: &str, noise: &[u8]) -> String {
    const INSERTS: &[&str] = &[
        "(", ")", ",", "=", "'", "\"", "\n", "#", "\\", "1.E", "]", ";", "**", ":", "    ", "\t",
        " if ", " for ", " not ", "%", "[",
    ];
    let mut chars: Vec<char> = text.chars().collect();
    let mut n = noise.iter().copied().chain(std::iter::repeat(0));
    let edits = 1 + n.next().unwrap_or(0) % 3;
    for _ in 0..edits {
        let at = if chars.is_empty() {
            0
        } else {
            n.next().unwrap_or(0) as usize * 7919 % (chars.len() + 1)
        };
        match n.next().unwrap_or(0) % 3 {
            0 => {
                let len = 1 + n.next().unwrap_or(0) as usize % 4;
                let end = (at + len).min(chars.len());
                chars.drain(at..end);
            }
            1 => {
                let t = INSERTS[n.next().unwrap_or(0) as usize % INSERTS.len()];
                for (k, c) in t.chars().enumerate() {
                    chars.insert(at + k, c);
                }
            }
            _ => {
                let end = (at + 1 + n.next().unwrap_or(0) as usize % 8).min(chars.len());
                let slice: Vec<char> = chars[at..end].to_vec();
                for (k, c) in slice.into_iter().enumerate() {
                    chars.insert(end + k, c);
                }
            }
        }
    }
    chars.into_iter().collect()
}

fn parse_text(text: &str) -> Program {
    let src = Source::new("roundtrip.comm", text);
    match parse(&src) {
        Ok(p) => p,
        Err(d) => panic!("{}\n--- source ---\n{text}", d.render(Some(&src))),
    }
}

#[test]
fn printed_programs_parse_back_to_the_same_tree() {
    let mut runner = TestRunner::new(Config {
        cases: (cases() / 10).max(1),
        failure_persistence: None,
        ..Config::default()
    });
    let strategy = (program(), prop::collection::vec(any::<u8>(), 0..64));
    runner
        .run(&strategy, |(tree, noise)| {
            let text = print(&tree, &noise);
            let parsed = strip(parse_text(&text));
            prop_assert_eq!(&parsed, &tree, "source:\n{}", text);
            let again = print(&parsed, &[7]);
            prop_assert_eq!(strip(parse_text(&again)), parsed, "source:\n{}", again);
            // The same text slightly damaged: near-valid files reach error
            // paths that random token soup rarely does.
            let damaged = mutate(&text, &noise);
            check_no_panic(&damaged);
            Ok(())
        })
        .unwrap();
}
