//! Fuzzing beyond the parser: the checker and the runner on damaged copies
//! of the real studies.
//!
//! Every `comm/*.comm`, `comm/long/*.comm` and `tests/verification/*.comm`
//! is parsed once; its syntax tree gives the places worth damaging
//! (statements, keyword arguments, factor occurrences, values, numbers,
//! concept names). Each case applies one to three edits at those places,
//! either to the tree (whose spans still point into the original text, so
//! that errors keep their line and column) or, one case in twenty and for
//! every run, to the text, which is then parsed again:
//! - a keyword (simple or factor) dropped, or given twice;
//! - a whole command dropped, or written twice (its result defined twice);
//! - a value replaced by one of another type (integer, real, string, tuple,
//!   concept name, `None`, `_F(...)`), or by another value of the file;
//! - a number pushed out of any sensible range (negative, zero, huge,
//!   subnormal, infinite, NaN-producing, beyond the 64-bit integers);
//! - a concept name replaced by an undefined one or by another concept;
//!   a result renamed so that a name is defined twice;
//! - a factor occurrence duplicated;
//! - the file truncated anywhere.
//!
//! 1. Checker: each damaged tree goes through `check_program` (each
//!    damaged text through `parse` first) under `catch_unwind`. It must not panic, and it either checks clean
//!    or every error it reports is located (a span inside the text, so the
//!    rendered message names `file:line:column`).
//! 2. Runner: damaged copies of the cheapest studies that the checker
//!    accepts are run in-process. A run must not panic; it ends either
//!    with an error located in the file or completed, and a completed run
//!    writes no NaN or infinity in its tables or its .resu.
//!
//! Cases are drawn from a splitmix64 generator seeded by the case index,
//! so that a failure names its index and `ASTER_FUZZ_CASE=<index>` replays
//! that case alone. `ASTER_FUZZ_CASES` (default 100000) sets the number of
//! checker cases; the runner does one run per 500 of them (200 by
//! default). The one-million-case command is in docs/language.md:
//! `ASTER_FUZZ_CASES=1000000 cargo test --release --test fuzz_runner -- --nocapture`.

use std::cell::RefCell;
use std::collections::{BTreeMap, HashMap};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

use aster::catalog::checker::check_program;
use aster::commands;
use aster::concepts::ConceptData;
use aster::diag::{Diagnostic, Severity, Source, Span};
use aster::lang::ast::{Arg, Expr, ExprKind, Program, Stmt, StmtKind, UnOp};
use aster::lang::parser::parse;
use aster::post::table::Cell;
use aster::run::driver::{export_files, parse_and_check, RunOptions};
use aster::study::Study;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn cases() -> u64 {
    std::env::var("ASTER_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(100_000)
}

/// `ASTER_FUZZ_CASE=<index>`: replay one case only.
fn only_case() -> Option<u64> {
    std::env::var("ASTER_FUZZ_CASE")
        .ok()
        .and_then(|v| v.parse().ok())
}

// ---------------------------------------------------------------------------
// Deterministic randomness
// ---------------------------------------------------------------------------

/// splitmix64: tiny, fast and good enough to pick edits; seeded by the
/// case index so that every case replays alone.
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x2545_F491_4F6C_DD1D) ^ 0x5DEE_CE66_D1CE_4E5B)
    }
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    fn pick<'a, T>(&mut self, v: &'a [T]) -> Option<&'a T> {
        if v.is_empty() {
            None
        } else {
            Some(&v[self.below(v.len())])
        }
    }
}

// ---------------------------------------------------------------------------
// The places of a file worth damaging
// ---------------------------------------------------------------------------

/// A keyword argument `KEY=value`.
#[derive(Clone, Copy)]
struct KwSite {
    span: Span,
    value: Span,
}

/// A factor occurrence `_F(...)`, alone or inside a tuple.
#[derive(Clone, Copy)]
struct FactorSite {
    span: Span,
    in_tuple: bool,
}

/// A study file parsed once, with its damageable places.
struct Corpus {
    name: String,
    text: String,
    program: Program,
    stmts: Vec<Span>,
    kwargs: Vec<KwSite>,
    factors: Vec<FactorSite>,
    values: Vec<Span>,
    numbers: Vec<Span>,
    names: Vec<Span>,
    targets: Vec<Span>,
    target_names: Vec<String>,
}

impl Corpus {
    fn load(path: &Path) -> Corpus {
        let text = std::fs::read_to_string(path).expect("study readable");
        let name = path
            .strip_prefix(root())
            .unwrap_or(path)
            .display()
            .to_string();
        let src = Source::new(name.clone(), text.clone());
        let program = parse(&src).unwrap_or_else(|d| panic!("{}", d.render(Some(&src))));
        let mut c = Corpus {
            name,
            text,
            program: program.clone(),
            stmts: Vec::new(),
            kwargs: Vec::new(),
            factors: Vec::new(),
            values: Vec::new(),
            numbers: Vec::new(),
            names: Vec::new(),
            targets: Vec::new(),
            target_names: Vec::new(),
        };
        c.collect(&program.stmts);
        c
    }

    fn collect(&mut self, stmts: &[Stmt]) {
        for stmt in stmts {
            self.stmts.push(stmt.span);
            let value = match &stmt.kind {
                StmtKind::Assign { target, value } => {
                    self.targets.push(target.span);
                    if !self.target_names.contains(&target.name) {
                        self.target_names.push(target.name.clone());
                    }
                    value
                }
                StmtKind::Expr(e)
                | StmtKind::Unpack { value: e, .. }
                | StmtKind::AugAssign { value: e, .. } => e,
                StmtKind::SetItem { index, value, .. } => {
                    self.value(index, false);
                    value
                }
                StmtKind::Pass | StmtKind::Import(_) | StmtKind::FromImport { .. } => continue,
                StmtKind::If { branches, orelse } => {
                    for (c, b) in branches {
                        self.value(c, false);
                        self.collect(b);
                    }
                    self.collect(orelse);
                    continue;
                }
                StmtKind::For { iter, body, .. } => {
                    self.value(iter, false);
                    self.collect(body);
                    continue;
                }
            };
            match &value.kind {
                ExprKind::Call { args, .. } => args.iter().for_each(|a| self.arg(a)),
                _ => self.value(value, false),
            }
        }
    }

    fn arg(&mut self, a: &Arg) {
        if a.name.is_some() {
            self.kwargs.push(KwSite {
                span: a.span,
                value: a.value.span,
            });
        }
        self.value(&a.value, false);
    }

    fn value(&mut self, e: &Expr, in_tuple: bool) {
        match &e.kind {
            ExprKind::Int(_) | ExprKind::Real(_) => {
                self.numbers.push(e.span);
                self.values.push(e.span);
            }
            ExprKind::Unary { op, operand } => {
                self.values.push(e.span);
                if *op == UnOp::Neg && matches!(operand.kind, ExprKind::Int(_) | ExprKind::Real(_))
                {
                    self.numbers.push(e.span);
                } else {
                    self.value(operand, false);
                }
            }
            ExprKind::Str(_) | ExprKind::NoneLit | ExprKind::Bool(_) => self.values.push(e.span),
            ExprKind::Name(_) => {
                self.names.push(e.span);
                self.values.push(e.span);
            }
            ExprKind::Tuple(items) | ExprKind::List(items) => {
                self.values.push(e.span);
                items.iter().for_each(|i| self.value(i, true));
            }
            ExprKind::Call { func, args } => {
                if func.name == "_F" {
                    self.factors.push(FactorSite {
                        span: e.span,
                        in_tuple,
                    });
                } else {
                    self.values.push(e.span);
                }
                args.iter().for_each(|a| self.arg(a));
            }
            ExprKind::Binary { lhs, rhs, .. } => {
                self.values.push(e.span);
                self.value(lhs, false);
                self.value(rhs, false);
            }
            ExprKind::MethodCall { args, .. } => {
                self.values.push(e.span);
                args.iter().for_each(|a| self.arg(a));
            }
            // The Python around commands: its parts are values too.
            _ => {
                self.values.push(e.span);
                e.children()
                    .into_iter()
                    .for_each(|c| self.value(c, matches!(e.kind, ExprKind::ListComp { .. })));
            }
        }
    }

    fn slice(&self, s: Span) -> &str {
        &self.text[s.start..s.end]
    }
}

fn studies() -> Vec<Corpus> {
    let mut paths = Vec::new();
    for dir in ["comm", "comm/long", "tests/verification"] {
        let mut found: Vec<PathBuf> = std::fs::read_dir(root().join(dir))
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "comm"))
            .collect();
        found.sort();
        paths.extend(found);
    }
    assert!(paths.len() >= 20, "only {} studies found", paths.len());
    paths.iter().map(|p| Corpus::load(p)).collect()
}

// ---------------------------------------------------------------------------
// Damage
// ---------------------------------------------------------------------------

const OUT_OF_RANGE: &[&str] = &[
    "-1",
    "0",
    "-0.",
    "0.",
    "-1.",
    "-1.E-300",
    "1.E-320",
    "1.E308",
    "-1.E308",
    "1.E308*10.",
    "-(1.E308*10.)",
    "(1.E308*10.)-(1.E308*10.)",
    "9223372036854775807",
    "-9223372036854775808",
    "99999999999999999999",
    "2**62",
    "2.**2000",
    "1/0",
    "0./0.",
    "1.E+400",
    "-2147483649",
    "float('nan')",
    "float('inf')",
    "-float('inf')",
    "float('1e999')",
    "int(1.E18)*100",
    "10**6 // 1",
    "-7 % 0",
    "1. // 0.",
    "round(1.E308*10.)",
    "math.exp(1000.)",
    "math.sqrt(-1.)",
    "math.log(0.)",
    "len(range(10**18))",
    "sum(range(10**6))",
];

const OTHER_VALUES: &[&str] = &[
    "0",
    "1",
    "-1",
    "3",
    "100",
    "0.",
    "1.",
    "0.5",
    "-227000.",
    "1.E-5",
    "'DX'",
    "'VOL'",
    "'OUI'",
    "'NON'",
    "''",
    "'NOPE'",
    "'ELAS'",
    "'DEPL'",
    "'HHT'",
    "()",
    "(1., 2.)",
    "('DX', 'DY')",
    "(0, 1, 2)",
    "(1.,)",
    "None",
    "_F()",
    "_F(TOUT='OUI')",
    "UNDEFINED_NAME",
    "float('x')",
    "True",
    "[1., 2.]",
    "[]",
    "[_F(TOUT='OUI') for i in range(2)]",
    "[x for x in 'DX']",
    "('DX', 'DY')[1]",
    "(1, 2)[5]",
    "'ABC'[1:]",
    "'%s%d' % ('A', 2)",
    "'%d' % 'x'",
    "1 if 2 > 1 else 'a'",
    "not 0",
    "3 // 2 % 2",
    "1 < 2 < 'a'",
    "min([])",
    "str(0.1)",
    "math.pi",
    "np.sqrt(2.)",
    "list(range(3))",
    "[1] * 3",
];

/// What an edit does to the node at its span.
#[derive(Clone, Debug)]
enum Op {
    /// Drop the statement.
    RemoveStmt,
    /// Drop the keyword argument (and, in the text, its comma).
    RemoveArg,
    /// Write the statement twice.
    DupStmt,
    /// Write the keyword argument twice.
    DupArg,
    /// Write the tuple item (a factor occurrence) twice.
    DupItem,
    /// A lone factor occurrence `_F(...)` becomes `(_F(...), _F(...))`.
    Pair,
    /// The value, name or result name becomes this text.
    Replace(String),
    /// Everything from the start of the span is cut.
    Truncate,
}

#[derive(Clone, Debug)]
struct Edit {
    span: Span,
    op: Op,
    what: &'static str,
}

/// The end of `span` extended over the comma that follows it, so that a
/// dropped argument leaves well-formed Python behind.
fn with_comma(text: &str, span: Span) -> Span {
    let rest = &text[span.end..];
    let skipped = rest.len() - rest.trim_start().len();
    if rest[skipped..].starts_with(',') {
        Span::new(span.start, span.end + skipped + 1)
    } else {
        span
    }
}

/// One random edit of `c`, or None when the file has no place of that kind.
fn edit(c: &Corpus, rng: &mut Rng, numeric_only: bool) -> Option<Edit> {
    let kind = if numeric_only {
        [0, 3, 3, 3, 2, 7][rng.below(6)]
    } else {
        rng.below(10)
    };
    let e = |span: Span, op: Op, what| Some(Edit { span, op, what });
    match kind {
        0 => e(rng.pick(&c.kwargs)?.span, Op::RemoveArg, "keyword dropped"),
        1 => e(*rng.pick(&c.stmts)?, Op::RemoveStmt, "statement dropped"),
        2 => {
            let v = if rng.below(2) == 0 {
                rng.pick(&c.kwargs)?.value
            } else {
                *rng.pick(&c.values)?
            };
            let text = match rng.below(3) {
                0 => c.slice(*rng.pick(&c.values)?).to_string(),
                1 => rng.pick(&c.target_names)?.clone(),
                _ => rng.pick(OTHER_VALUES)?.to_string(),
            };
            e(v, Op::Replace(text), "value swapped")
        }
        3 => {
            let n = *rng.pick(&c.numbers)?;
            let text = rng.pick(OUT_OF_RANGE)?.to_string();
            e(n, Op::Replace(text), "number out of range")
        }
        4 => {
            let n = *rng.pick(&c.names)?;
            let text = if rng.below(2) == 0 {
                "UNDEFINED_CONCEPT".to_string()
            } else {
                rng.pick(&c.target_names)?.clone()
            };
            e(n, Op::Replace(text), "concept renamed")
        }
        5 => {
            let t = *rng.pick(&c.targets)?;
            let text = rng.pick(&c.target_names)?.clone();
            e(t, Op::Replace(text), "result renamed")
        }
        6 => e(*rng.pick(&c.stmts)?, Op::DupStmt, "statement repeated"),
        7 => e(rng.pick(&c.kwargs)?.span, Op::DupArg, "keyword repeated"),
        8 => {
            let f = *rng.pick(&c.factors)?;
            let op = if f.in_tuple { Op::DupItem } else { Op::Pair };
            e(f.span, op, "factor occurrence repeated")
        }
        _ => {
            // Truncation: everything from a character boundary on.
            let mut at = rng.below(c.text.len() + 1);
            while !c.text.is_char_boundary(at) {
                at -= 1;
            }
            e(Span::new(at, c.text.len()), Op::Truncate, "file truncated")
        }
    }
}

/// One to three random edits of `c` at disjoint places.
fn edits(c: &Corpus, rng: &mut Rng, numeric_only: bool) -> Vec<Edit> {
    let n = 1 + rng.below(3);
    let mut edits: Vec<Edit> = Vec::new();
    for _ in 0..n * 4 {
        if edits.len() == n {
            break;
        }
        let Some(ed) = edit(c, rng, numeric_only) else {
            continue;
        };
        // A dropped argument takes its comma along in the text.
        let reach = |e: &Edit| match e.op {
            Op::RemoveArg => with_comma(&c.text, e.span),
            _ => e.span,
        };
        let (a, disjoint) = (reach(&ed), &edits);
        if disjoint.iter().all(|o| {
            let b = reach(o);
            a.end < b.start || b.end < a.start
        }) {
            edits.push(ed);
        }
    }
    edits
}

/// The damaged text: the edits applied to the source text.
fn damaged_text(c: &Corpus, edits: &[Edit]) -> String {
    let mut sorted = edits.to_vec();
    sorted.sort_by_key(|e| std::cmp::Reverse((e.span.start, e.span.end)));
    let mut text = c.text.clone();
    for ed in &sorted {
        let s = ed.span;
        let old = c.slice(s);
        let (range, new) = match &ed.op {
            Op::RemoveStmt | Op::Truncate => (s, String::new()),
            Op::RemoveArg => (with_comma(&c.text, s), String::new()),
            Op::DupStmt => (Span::new(s.end, s.end), format!("\n{old}")),
            Op::DupArg | Op::DupItem => (Span::new(s.end, s.end), format!(", {old}")),
            Op::Pair => (s, format!("({old}, {old})")),
            Op::Replace(t) => (s, t.clone()),
        };
        text.replace_range(range.start..range.end, &new);
    }
    text
}

/// Replacement texts parsed once, as expressions.
#[derive(Default)]
struct Pool {
    parsed: HashMap<String, Option<Expr>>,
}

impl Pool {
    /// The expression of `text`, every span set to `at`; None when the
    /// text is not a valid expression (text-mode cases cover those).
    fn expr(&mut self, text: &str, at: Span) -> Option<Expr> {
        if !self.parsed.contains_key(text) {
            let e = (|| {
                let src = Source::new("value", format!("X = {text}\n"));
                let p = parse(&src).ok()?;
                match p.stmts.into_iter().next()?.kind {
                    StmtKind::Assign { value, .. } => Some(value),
                    _ => None,
                }
            })();
            self.parsed.insert(text.to_string(), e);
        }
        let mut e = self.parsed[text].clone()?;
        respan(&mut e, at);
        Some(e)
    }
}

fn respan(e: &mut Expr, at: Span) {
    e.span = at;
    match &mut e.kind {
        ExprKind::Tuple(items) | ExprKind::List(items) => {
            items.iter_mut().for_each(|i| respan(i, at))
        }
        ExprKind::Call { func, args } => {
            func.span = at;
            for a in args {
                a.span = at;
                if let Some(n) = &mut a.name {
                    n.span = at;
                }
                respan(&mut a.value, at);
            }
        }
        ExprKind::Unary { operand, .. } => respan(operand, at),
        ExprKind::Binary { lhs, rhs, .. } => {
            respan(lhs, at);
            respan(rhs, at);
        }
        _ => {}
    }
}

/// The damaged tree: the same edits applied to the syntax tree, whose
/// spans still point into the original text (so that errors can be
/// located there). Parsing is most of the cost of a case; this lets the
/// checker see ten times more damaged files in the same time.
fn damaged_tree(program: &Program, edits: &[Edit], pool: &mut Pool) -> Program {
    let cut = edits
        .iter()
        .find(|e| matches!(e.op, Op::Truncate))
        .map(|e| e.span.start);
    Program {
        stmts: damaged_stmts(&program.stmts, edits, pool, cut),
    }
}

/// The statements of one block, damaged; a block cut in the middle keeps
/// the statements before the cut.
fn damaged_stmts(
    stmts_in: &[Stmt],
    edits: &[Edit],
    pool: &mut Pool,
    cut: Option<usize>,
) -> Vec<Stmt> {
    let find = |s: Span, f: &dyn Fn(&Op) -> bool| edits.iter().find(|e| e.span == s && f(&e.op));
    let mut stmts = Vec::new();
    for stmt in stmts_in {
        if cut.is_some_and(|at| stmt.span.start >= at) {
            break;
        }
        if find(stmt.span, &|o| matches!(o, Op::RemoveStmt)).is_some() {
            continue;
        }
        let mut st = stmt.clone();
        if let StmtKind::Assign { target, .. } = &mut st.kind {
            if let Some(Edit {
                op: Op::Replace(t), ..
            }) = find(target.span, &|o| matches!(o, Op::Replace(_)))
            {
                target.name = t.clone();
            }
        }
        match &mut st.kind {
            StmtKind::Assign { value, .. }
            | StmtKind::Expr(value)
            | StmtKind::AugAssign { value, .. }
            | StmtKind::Unpack { value, .. } => damage_expr(value, edits, pool, cut),
            StmtKind::SetItem { index, value, .. } => {
                damage_expr(index, edits, pool, cut);
                damage_expr(value, edits, pool, cut);
            }
            StmtKind::Pass | StmtKind::Import(_) | StmtKind::FromImport { .. } => {}
            StmtKind::If { branches, orelse } => {
                for (c, b) in branches.iter_mut() {
                    damage_expr(c, edits, pool, cut);
                    *b = damaged_stmts(b, edits, pool, cut);
                }
                *orelse = damaged_stmts(orelse, edits, pool, cut);
            }
            StmtKind::For { iter, body, .. } => {
                damage_expr(iter, edits, pool, cut);
                *body = damaged_stmts(body, edits, pool, cut);
            }
        }
        let twice = find(stmt.span, &|o| matches!(o, Op::DupStmt)).is_some();
        if twice {
            stmts.push(st.clone());
        }
        stmts.push(st);
    }
    stmts
}

fn damage_expr(e: &mut Expr, edits: &[Edit], pool: &mut Pool, cut: Option<usize>) {
    let find = |s: Span, f: &dyn Fn(&Op) -> bool| edits.iter().find(|e| e.span == s && f(&e.op));
    if let Some(Edit {
        op: Op::Replace(t), ..
    }) = find(e.span, &|o| matches!(o, Op::Replace(_)))
    {
        if let Some(new) = pool.expr(t, e.span) {
            *e = new;
            return;
        }
    }
    if find(e.span, &|o| matches!(o, Op::Pair)).is_some() {
        let one = e.clone();
        *e = Expr {
            kind: ExprKind::Tuple(vec![one.clone(), one]),
            span: e.span,
        };
        return;
    }
    match &mut e.kind {
        ExprKind::Call { args, .. } => {
            let mut out: Vec<Arg> = Vec::with_capacity(args.len() + 1);
            for mut a in std::mem::take(args) {
                // A command cut in the middle keeps the arguments before the cut.
                if cut.is_some_and(|at| a.span.end > at) {
                    break;
                }
                if find(a.span, &|o| matches!(o, Op::RemoveArg)).is_some() {
                    continue;
                }
                damage_expr(&mut a.value, edits, pool, cut);
                if find(a.span, &|o| matches!(o, Op::DupArg)).is_some() {
                    out.push(a.clone());
                }
                out.push(a);
            }
            *args = out;
        }
        ExprKind::Tuple(items) | ExprKind::List(items) => {
            let mut out = Vec::with_capacity(items.len() + 1);
            for mut it in std::mem::take(items) {
                if cut.is_some_and(|at| it.span.end > at) {
                    break;
                }
                let span = it.span;
                damage_expr(&mut it, edits, pool, cut);
                if find(span, &|o| matches!(o, Op::DupItem)).is_some() {
                    out.push(it.clone());
                }
                out.push(it);
            }
            *items = out;
        }
        ExprKind::Unary { operand, .. } => damage_expr(operand, edits, pool, cut),
        ExprKind::Binary { lhs, rhs, .. } | ExprKind::Logic { lhs, rhs, .. } => {
            damage_expr(lhs, edits, pool, cut);
            damage_expr(rhs, edits, pool, cut);
        }
        ExprKind::MethodCall { value, args, .. } => {
            damage_expr(value, edits, pool, cut);
            for a in args {
                damage_expr(&mut a.value, edits, pool, cut);
            }
        }
        ExprKind::Attribute { value, .. } => damage_expr(value, edits, pool, cut),
        ExprKind::Index { value, index } => {
            damage_expr(value, edits, pool, cut);
            damage_expr(index, edits, pool, cut);
        }
        ExprKind::Slice {
            value,
            lower,
            upper,
            step,
        } => {
            damage_expr(value, edits, pool, cut);
            for b in [lower, upper, step].into_iter().flatten() {
                damage_expr(b, edits, pool, cut);
            }
        }
        ExprKind::Compare { first, rest } => {
            damage_expr(first, edits, pool, cut);
            for (_, x) in rest {
                damage_expr(x, edits, pool, cut);
            }
        }
        ExprKind::IfElse { cond, then, orelse } => {
            damage_expr(cond, edits, pool, cut);
            damage_expr(then, edits, pool, cut);
            damage_expr(orelse, edits, pool, cut);
        }
        ExprKind::ListComp { elt, generators } => {
            damage_expr(elt, edits, pool, cut);
            for g in generators {
                damage_expr(&mut g.iter, edits, pool, cut);
                for c in &mut g.ifs {
                    damage_expr(c, edits, pool, cut);
                }
            }
        }
        ExprKind::Dict(items) => {
            for (k, v) in items {
                if let Some(k) = k {
                    damage_expr(k, edits, pool, cut);
                }
                damage_expr(v, edits, pool, cut);
            }
        }
        _ => {}
    }
}

fn describe(c: &Corpus, edits: &[Edit]) -> String {
    let src = Source::new(c.name.clone(), c.text.clone());
    edits
        .iter()
        .map(|e| {
            let (l, col) = src.line_col(e.span.start);
            let old: String = c.slice(e.span).chars().take(60).collect();
            let new = match &e.op {
                Op::Replace(t) => format!(" -> {:?}", t.chars().take(60).collect::<String>()),
                _ => String::new(),
            };
            format!("  {}:{l}:{col}: {}: {old:?}{new}", c.name, e.what)
        })
        .collect::<Vec<_>>()
        .join("\n")
}

// ---------------------------------------------------------------------------
// Panics: recorded per thread instead of printed
// ---------------------------------------------------------------------------

thread_local! {
    /// Set while a fuzz case runs: the panic hook records the panic here
    /// (message and place) instead of printing it.
    static CAUGHT: RefCell<Option<Option<String>>> = const { RefCell::new(None) };
}

fn install_hook() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let default = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            let fuzzing = CAUGHT.with(|c| c.borrow().is_some());
            if fuzzing {
                let place = info
                    .location()
                    .map(|l| format!("{}:{}", l.file(), l.line()))
                    .unwrap_or_default();
                let msg = info
                    .payload()
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| info.payload().downcast_ref::<String>().cloned())
                    .unwrap_or_default();
                CAUGHT.with(|c| *c.borrow_mut() = Some(Some(format!("{place}: {msg}"))));
            } else {
                default(info);
            }
        }));
    });
}

/// Runs `f`, turning a panic into its message and place.
fn guarded<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    install_hook();
    CAUGHT.with(|c| *c.borrow_mut() = Some(None));
    let r = catch_unwind(AssertUnwindSafe(f));
    let caught = CAUGHT.with(|c| c.borrow_mut().take()).flatten();
    r.map_err(|_| format!("panic at {}", caught.unwrap_or_default()))
}

/// The problems found, by kind (the panic place or the kind of defect),
/// each with the first case that showed it and how many did.
#[derive(Default)]
struct Findings {
    by_kind: BTreeMap<String, (usize, String)>,
}

impl Findings {
    fn add(&mut self, kind: String, case: String) {
        let entry = self.by_kind.entry(kind).or_insert((0, case));
        entry.0 += 1;
    }
    fn assert_none(&self, what: &str) {
        if self.by_kind.is_empty() {
            return;
        }
        let mut report = format!("{} distinct problems {what}:\n", self.by_kind.len());
        for (kind, (n, case)) in &self.by_kind {
            report.push_str(&format!("\n=== {kind} ({n} cases), first:\n{case}\n"));
        }
        panic!("{report}");
    }
}

/// An error is located when it has a span inside the text and renders
/// with `file:line:column`.
fn unlocated(d: &Diagnostic, src: &Source) -> Option<String> {
    match d.span {
        Some(s) if s.start <= s.end && s.end <= src.text.len() => {
            let rendered = d.render(Some(src));
            (!rendered.contains(&format!("--> {}:", src.name)))
                .then(|| format!("rendered without a position:\n{rendered}"))
        }
        Some(s) => Some(format!("span {s:?} outside a text of {}", src.text.len())),
        None => Some(format!(
            "error without a position: {}",
            d.render(Some(src)).trim_end()
        )),
    }
}

// ---------------------------------------------------------------------------
// 1. Checker
// ---------------------------------------------------------------------------

/// Parses and checks; Ok(true) when the file checks clean, Ok(false) when
/// it is refused with located errors, Err(problem) otherwise.
fn check_case(name: &str, text: &str, registry: &[commands::CommandDef]) -> Result<bool, String> {
    let src = Source::new(name, text);
    guarded(|| match parse(&src) {
        Err(d) => unlocated(&d, &src).map_or(Ok(false), Err),
        Ok(program) => check_located(&src, &program, registry),
    })?
}

/// Checks a tree whose spans point into `src`, with the outcomes of
/// [`check_case`].
fn check_located(
    src: &Source,
    program: &Program,
    registry: &[commands::CommandDef],
) -> Result<bool, String> {
    {
        match check_program(program, registry) {
            Ok(checked) => {
                for w in &checked.warnings {
                    if let Some(p) = unlocated(w, src) {
                        return Err(format!("warning: {p}"));
                    }
                }
                Ok(true)
            }
            Err(ds) => {
                if !ds.iter().any(|d| d.severity == Severity::Error) {
                    return Err("refused without an error".into());
                }
                for d in &ds {
                    if let Some(p) = unlocated(d, src) {
                        return Err(p);
                    }
                }
                Ok(false)
            }
        }
    }
}

/// The kind of a problem: the panic place, or the first line of the message.
fn kind_of(problem: &str) -> String {
    problem
        .lines()
        .next()
        .unwrap_or("")
        .chars()
        .take(160)
        .collect()
}

#[test]
fn damaged_studies_check_without_panic_and_with_located_errors() {
    let corpus = studies();
    let n = cases();
    let started = std::time::Instant::now();
    // Two threads, each its own share of the case indices: the cases are
    // independent, and a free core halves the time.
    let threads: u64 = if only_case().is_some() { 1 } else { 2 };
    let results: Vec<(Findings, [u64; 3])> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                let corpus = &corpus;
                scope.spawn(move || {
                    let cases = match only_case() {
                        Some(i) => i..i + 1,
                        None => 0..n,
                    };
                    check_share(corpus, cases.filter(|i| i % threads == t))
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let mut findings = Findings::default();
    let mut counts = [0u64; 3];
    for (f, c) in results {
        for (kind, (k, case)) in f.by_kind {
            let e = findings.by_kind.entry(kind).or_insert((0, case));
            e.0 += k;
        }
        for j in 0..3 {
            counts[j] += c[j];
        }
    }
    let [accepted, refused, as_text] = counts;
    let problems: u64 = findings.by_kind.values().map(|v| v.0 as u64).sum();
    println!(
        "checker fuzz: {} cases ({as_text} of them as text, parsed again) on {} studies in {:.1} s: {accepted} accepted, {refused} refused with located errors, {problems} with a problem",
        accepted + refused + problems,
        corpus.len(),
        started.elapsed().as_secs_f64(),
    );
    findings.assert_none("in the checker");
}

/// Runs the checker cases of `indices`; returns the findings and the
/// counts (accepted, refused, damaged as text).
fn check_share(corpus: &[Corpus], indices: impl Iterator<Item = u64>) -> (Findings, [u64; 3]) {
    let registry = commands::all();
    let sources: Vec<Source> = corpus
        .iter()
        .map(|c| Source::new(c.name.clone(), c.text.clone()))
        .collect();
    let mut pool = Pool::default();
    let mut findings = Findings::default();
    let (mut accepted, mut refused, mut as_text) = (0u64, 0u64, 0u64);
    for i in indices {
        let mut rng = Rng::new(i);
        let k = rng.below(corpus.len());
        let c = &corpus[k];
        let edits = edits(c, &mut rng, false);
        // One case in twenty is damaged as text and parsed again (the
        // whole path of `aster check`; parsing is most of its cost, and
        // tests/fuzz_parser.rs fuzzes the parser); the others are damaged
        // as a tree and checked directly.
        let outcome = if i % 20 == 0 {
            as_text += 1;
            check_case(&c.name, &damaged_text(c, &edits), &registry)
        } else {
            let tree = damaged_tree(&c.program, &edits, &mut pool);
            guarded(|| check_located(&sources[k], &tree, &registry)).and_then(|r| r)
        };
        match outcome {
            Ok(true) => accepted += 1,
            Ok(false) => refused += 1,
            Err(problem) => findings.add(
                kind_of(&problem),
                format!(
                    "case {i} (ASTER_FUZZ_CASE={i}):\n{}\n{problem}",
                    describe(c, &edits)
                ),
            ),
        }
    }
    (findings, [accepted, refused, as_text])
}

// ---------------------------------------------------------------------------
// 2. Runner
// ---------------------------------------------------------------------------

/// The studies that run in milliseconds, damaged for the runner.
const CHEAP: &[&str] = &[
    "tests/verification/free_flight.comm",
    "tests/verification/patch_axis.comm",
    "tests/verification/contact_landing.comm",
    "tests/verification/unil_axis_drop.comm",
    "tests/verification/calc_fonction.comm",
    "tests/verification/calc_table.comm",
];

/// Longer than any damaged cheap study should take (they run in well under
/// a second); a run that goes on is reported with its case.
const RUN_TIMEOUT_S: u64 = 60;

enum RunEnd {
    Completed,
    /// The rendered error.
    LocatedError(String),
}

/// Runs a checked damaged study in-process, as `aster run` does.
fn run_case(comm: &Path, name: &str, text: &str, out: &Path) -> Result<Option<RunEnd>, String> {
    let src = Source::new(name, text);
    let registry = commands::all();
    let mut messages = String::new();
    let Some(program) = parse_and_check(&src, &registry, &mut messages) else {
        return Ok(None);
    };
    let _ = std::fs::remove_dir_all(out);
    std::fs::create_dir_all(out).unwrap();
    let mut study = Study {
        out_dir: out.to_path_buf(),
        stem: "fuzz".into(),
        ..Study::default()
    };
    let opts = RunOptions {
        comm: comm.to_path_buf(),
        ..RunOptions::default()
    };
    for f in export_files(&opts).expect("export readable") {
        study.units.map.insert(f.unit, f.path);
    }
    study.units.map.insert(80, out.join("resu.rmed"));
    match aster::run::execute(&mut study, &program, &registry, &src) {
        Err(d) => match unlocated(&d, &src) {
            Some(p) => Err(format!("run stopped on an {p}")),
            None => Ok(Some(RunEnd::LocatedError(d.render(Some(&src))))),
        },
        Ok(()) => {
            for c in study.concepts.iter() {
                if let ConceptData::Table(t) = &c.data {
                    for row in &t.rows {
                        for cell in row.iter().flatten() {
                            if let Cell::Real(x) = cell {
                                if !x.is_finite() {
                                    return Err(format!(
                                        "completed run with {x} in table {}",
                                        c.name
                                    ));
                                }
                            }
                        }
                    }
                }
            }
            let bad = ["NaN", "nan", "inf"];
            if let Some(l) = study.resu.lines().find(|l| {
                l.split_whitespace()
                    .any(|w| bad.iter().any(|b| w.contains(b)))
            }) {
                return Err(format!("completed run writes a non-finite value: {l}"));
            }
            Ok(Some(RunEnd::Completed))
        }
    }
}

#[test]
fn damaged_cheap_studies_run_to_a_located_error_or_to_the_end() {
    let corpus: Vec<Corpus> = CHEAP
        .iter()
        .map(|p| Corpus::load(&root().join(p)))
        .collect();
    let registry = commands::all();
    let runs = (cases() / 500).max(1);
    let range = match only_case() {
        Some(i) => i..i + 1,
        None => 0..runs,
    };
    let scratch = Path::new(env!("CARGO_TARGET_TMPDIR")).join("fuzz_runner");
    let started = std::time::Instant::now();
    let mut findings = Findings::default();
    let (mut completed, mut stopped, mut refused) = (0u64, 0u64, 0u64);
    for i in range {
        let mut rng = Rng::new(i ^ 0xA5A5_0000_0000);
        let c = &corpus[rng.below(corpus.len())];
        // A damaged copy the checker accepts (refused ones are checker cases).
        let mut accepted = None;
        for _ in 0..20 {
            let edits = edits(c, &mut rng, true);
            let text = damaged_text(c, &edits);
            if matches!(check_case(&c.name, &text, &registry), Ok(true)) {
                accepted = Some((text, edits));
                break;
            }
            refused += 1;
        }
        let Some((text, edits)) = accepted else {
            continue;
        };
        let comm = root().join(&c.name);
        let out = scratch.join(format!("{}", i % 4));
        // A run that does not end is a finding too; the thread is left
        // behind and the test stops there.
        let (tx, rx) = std::sync::mpsc::channel();
        let (name, damaged) = (c.name.clone(), text.clone());
        std::thread::spawn(move || {
            let _ = tx.send(guarded(|| run_case(&comm, &name, &damaged, &out)));
        });
        let outcome = rx
            .recv_timeout(std::time::Duration::from_secs(RUN_TIMEOUT_S))
            .unwrap_or_else(|_| Err(format!("run did not end within {RUN_TIMEOUT_S} s")));
        let hung = matches!(&outcome, Err(p) if p.starts_with("run did not end"));
        match outcome {
            Ok(Ok(Some(RunEnd::Completed))) => completed += 1,
            Ok(Ok(Some(RunEnd::LocatedError(_)))) => stopped += 1,
            Ok(Ok(None)) => unreachable!("checked above"),
            Ok(Err(problem)) | Err(problem) => findings.add(
                kind_of(&problem),
                format!(
                    "run {i} (ASTER_FUZZ_CASE={i}):\n{}\n{problem}",
                    describe(c, &edits)
                ),
            ),
        }
        if hung {
            break;
        }
    }
    println!(
        "runner fuzz: {} runs in {:.1} s: {completed} completed, {stopped} stopped on a located error, {} problems ({refused} damaged copies refused by the checker on the way)",
        completed + stopped + findings.by_kind.values().map(|v| v.0 as u64).sum::<u64>(),
        started.elapsed().as_secs_f64(),
        findings.by_kind.len()
    );
    findings.assert_none("in the runner");
}

// ---------------------------------------------------------------------------
// The problems the fuzzing found, as fixed cases
// ---------------------------------------------------------------------------

/// Each damaged text that once panicked, hung or slipped through, with the
/// located error it must now give.
#[test]
fn fuzz_findings_are_located_errors() {
    let registry = commands::all();
    let cases: &[(&str, &str)] = &[
        // float('nan') passed every bound check (comparisons with NaN are
        // false) and reached the engine.
        ("DEBUT()\nX = float('nan')\nFIN()\n", "not a finite number"),
        ("DEBUT()\nX = -float('inf')\nFIN()\n", "not a finite number"),
    ];
    for (text, expected) in cases {
        let src = Source::new("finding.comm", *text);
        let program = parse(&src).expect("parses");
        let ds = check_program(&program, &registry).expect_err("refused");
        let d = &ds[0];
        assert!(unlocated(d, &src).is_none(), "{}", d.render(Some(&src)));
        assert!(d.message.contains(expected), "{}", d.render(Some(&src)));
    }
}

/// The warning of a file without FIN() had no position.
#[test]
fn missing_fin_is_located_after_the_last_statement() {
    let src = Source::new("finding.comm", "DEBUT()\nX = 1\n");
    let program = parse(&src).expect("parses");
    let checked = check_program(&program, &commands::all()).expect("accepted");
    assert_eq!(checked.warnings.len(), 1);
    let w = &checked.warnings[0];
    assert!(unlocated(w, &src).is_none(), "{}", w.render(Some(&src)));
    assert!(
        w.render(Some(&src)).contains("finding.comm:2:6"),
        "{}",
        w.render(Some(&src))
    );
}

/// Runs found by the fuzzing that must stop on a located error, quickly:
/// (study, original text, damaged text, what the error says).
#[test]
fn fuzz_findings_in_runs_are_located_errors() {
    let cases = [
        // NOMBRE = 2**63 - 1 in DEFI_LIST_REEL filled the memory.
        (
            "tests/verification/contact_landing.comm",
            "NOMBRE=151",
            "NOMBRE=9223372036854775807",
            "values a list may hold",
        ),
        // PRECISION = 1e308 printed a tolerance of "inf%" in the .resu.
        (
            "tests/verification/patch_axis.comm",
            "PRECISION=1.E-9",
            "PRECISION=1.E308",
            "too large",
        ),
    ];
    for (k, (path, from, to, expected)) in cases.into_iter().enumerate() {
        let c = Corpus::load(&root().join(path));
        let text = c.text.replacen(from, to, 1);
        assert_ne!(text, c.text);
        let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("fuzz_finding_{k}"));
        match run_case(&root().join(path), path, &text, &out) {
            Ok(Some(RunEnd::LocatedError(m))) => assert!(m.contains(expected), "{m}"),
            Ok(Some(RunEnd::Completed)) => panic!("{path}: {to} completed"),
            Ok(None) => panic!("{path}: {to} refused by the checker"),
            Err(p) => panic!("{path}: {to}: {p}"),
        }
    }
}
