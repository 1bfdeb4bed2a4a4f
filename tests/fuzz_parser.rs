//! Property tests of the parser.
//!
//! 1. Random token streams (names, Python keywords, numbers in every form
//!    and malformed ones, strings with escapes or unterminated, punctuation,
//!    newlines of every kind, comments, arbitrary UTF-8) never make `parse`
//!    panic; an error always points inside the source and renders; a
//!    success gives a tree whose spans nest inside their parents.
//! 2. Round trip: a random syntax tree printed with random layout (spaces,
//!    newlines inside brackets, comments, continuations, both quotes, every
//!    number form, redundant parentheses, trailing commas, `;`) parses back
//!    to the same tree, and so does the parsed tree printed again. The
//!    printed text, damaged by a few random edits, goes through the checks
//!    of property 1: near-valid files reach error paths that random token
//!    soup rarely does.
//!
//! The number of cases is `ASTER_FUZZ_CASES` (default 100000) for the token
//! streams and a tenth of it for the round trip, whose inputs are larger:
//! `ASTER_FUZZ_CASES=1000000 cargo test --test fuzz_parser` (about 4 minutes).

use aster::diag::{Source, Span};
use aster::lang::ast::{Arg, BinOp, Expr, ExprKind, Ident, Program, Stmt, StmtKind, UnOp};
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
        ExprKind::Tuple(items) => items.iter().for_each(|i| check_expr(text, i, e.span)),
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
        ExprKind::Unary { operand, .. } => check_expr(text, operand, e.span),
        ExprKind::Binary { lhs, rhs, .. } => {
            check_expr(text, lhs, e.span);
            check_expr(text, rhs, e.span);
        }
        _ => {}
    }
}

/// Parses `text` and checks what any result must satisfy.
fn check_no_panic(text: &str) {
    let src = Source::new("fuzz.comm", text);
    match parse(&src) {
        Ok(program) => {
            for stmt in &program.stmts {
                check_span(text, stmt.span, "statement");
                match &stmt.kind {
                    StmtKind::Assign { target, value } => {
                        assert!(inside(target.span, stmt.span));
                        check_expr(text, value, stmt.span);
                    }
                    StmtKind::Expr(e) => check_expr(text, e, stmt.span),
                }
            }
        }
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

fn expr() -> impl Strategy<Value = Expr> {
    let leaf = prop_oneof![
        (0..=i64::MAX).prop_map(|i| e(ExprKind::Int(i))),
        real().prop_map(|r| e(ExprKind::Real(r))),
        "([a-zA-Z0-9 _.#,()=]|'|\"|\\\\|\n|\t|\r|é|€)*".prop_map(|s| e(ExprKind::Str(s))),
        Just(e(ExprKind::NoneLit)),
        ident().prop_map(|i| e(ExprKind::Name(i.name))),
    ];
    leaf.prop_recursive(5, 40, 4, |inner| {
        let op = prop::sample::select(vec![
            BinOp::Add,
            BinOp::Sub,
            BinOp::Mul,
            BinOp::Div,
            BinOp::Pow,
        ]);
        let arg = |named: bool, inner: BoxedStrategy<Expr>| {
            (ident(), inner).prop_map(move |(n, value)| Arg {
                name: named.then_some(n),
                value,
                span: Span::default(),
            })
        };
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..4).prop_map(|v| e(ExprKind::Tuple(v))),
            (
                ident(),
                prop::collection::vec(arg(false, inner.clone().boxed()), 0..3),
                prop::collection::vec(arg(true, inner.clone().boxed()), 0..3),
            )
                .prop_map(|(func, mut args, kw)| {
                    args.extend(kw);
                    e(ExprKind::Call { func, args })
                }),
            (any::<bool>(), inner.clone()).prop_map(|(neg, x)| e(ExprKind::Unary {
                op: if neg { UnOp::Neg } else { UnOp::Pos },
                operand: Box::new(x),
            })),
            (op, inner.clone(), inner).prop_map(|(op, l, r)| e(ExprKind::Binary {
                op,
                lhs: Box::new(l),
                rhs: Box::new(r),
            })),
        ]
    })
}

fn program() -> impl Strategy<Value = Program> {
    let stmt = prop_oneof![
        (ident(), expr()).prop_map(|(target, value)| StmtKind::Assign { target, value }),
        expr().prop_map(StmtKind::Expr),
    ]
    .prop_map(|kind| Stmt {
        kind,
        span: Span::default(),
    });
    prop::collection::vec(stmt, 0..6).prop_map(|stmts| Program { stmts })
}

/// Binding strength, Python's: sums < products < signs < powers < atoms.
fn prec(e: &Expr) -> u8 {
    match &e.kind {
        ExprKind::Binary { op, .. } => match op {
            BinOp::Add | BinOp::Sub => 1,
            BinOp::Mul | BinOp::Div => 2,
            BinOp::Pow => 4,
        },
        ExprKind::Unary { .. } => 3,
        _ => 5,
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
            ExprKind::Tuple(items) => {
                if self.pick(3) == 0 {
                    self.sequence(items, '[', ']', false)
                } else {
                    self.sequence(items, '(', ')', true)
                }
            }
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
                    }
                    self.expr(&a.value, true);
                    if i + 1 < args.len() || self.pick(3) == 0 {
                        self.out.push(',');
                    }
                }
                self.gap_in();
                self.out.push(')');
            }
            ExprKind::Unary { op, operand } => {
                self.out.push(if *op == UnOp::Neg { '-' } else { '+' });
                self.gap_out(br);
                self.wrapped(operand, prec(operand) < 3, br);
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let p = prec(e);
                let (need_l, need_r) = if *op == BinOp::Pow {
                    (prec(lhs) <= 4, prec(rhs) < 3)
                } else {
                    (prec(lhs) < p, prec(rhs) <= p)
                };
                self.wrapped(lhs, need_l, br);
                self.gap_out(br);
                self.out.push_str(op.symbol());
                self.gap_out(br);
                self.wrapped(rhs, need_r, br);
            }
        }
    }

    fn program(&mut self, p: &Program) {
        for s in &p.stmts {
            match self.pick(6) {
                0 => self.out.push_str("# a comment line\n"),
                1 => self.out.push_str("\n  \t\n"),
                _ => {}
            }
            match &s.kind {
                StmtKind::Assign { target, value } => {
                    self.out.push_str(&target.name);
                    self.gap_out(false);
                    self.out.push('=');
                    self.gap_out(false);
                    self.expr(value, false);
                }
                StmtKind::Expr(e) => self.expr(e, false),
            }
            match self.pick(6) {
                0 => self.out.push_str(";\n"),
                1 => self.out.push_str("; "),
                2 => self.out.push_str("\r\n"),
                3 => self.out.push_str("  # end\n"),
                _ => self.out.push('\n'),
            }
        }
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

fn strip_expr(e: &mut Expr) {
    e.span = Span::default();
    match &mut e.kind {
        ExprKind::Tuple(items) => items.iter_mut().for_each(strip_expr),
        ExprKind::Call { func, args } => {
            func.span = Span::default();
            for a in args {
                a.span = Span::default();
                if let Some(n) = &mut a.name {
                    n.span = Span::default();
                }
                strip_expr(&mut a.value);
            }
        }
        ExprKind::Unary { operand, .. } => strip_expr(operand),
        ExprKind::Binary { lhs, rhs, .. } => {
            strip_expr(lhs);
            strip_expr(rhs);
        }
        _ => {}
    }
}

fn strip(mut p: Program) -> Program {
    for s in &mut p.stmts {
        s.span = Span::default();
        match &mut s.kind {
            StmtKind::Assign { target, value } => {
                target.span = Span::default();
                strip_expr(value);
            }
            StmtKind::Expr(e) => strip_expr(e),
        }
    }
    p
}

/// One to three edits chosen by `noise`: delete a few characters, insert
/// a token, or duplicate a slice.
fn mutate(text: &str, noise: &[u8]) -> String {
    const INSERTS: &[&str] = &[
        "(", ")", ",", "=", "'", "\"", "\n", "#", "\\", "1.E", "]", ";", "**",
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
