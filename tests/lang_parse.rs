//! Golden tests of the parser over the corpus in `tests/lang/`.
//!
//! `ok/*.comm` are well-formed files written the way code_aster users write
//! them; each is snapshotted as a compact tree (positions on the left, values
//! inline) so that a change in the parse shows up as a readable diff.
//! `err/syntax_*.comm` hold one syntax error each; the snapshot is the
//! message exactly as a user sees it.
//!
//! Accept new snapshots with `INSTA_UPDATE=always cargo test --test lang_parse`
//! and read them before committing.

use aster::diag::{Source, Span};
use aster::lang::ast::{Expr, ExprKind, Program, StmtKind, UnOp};
use aster::lang::parser::parse;
use std::path::Path;

/// The file as a Source named relative to the crate root, so snapshots do
/// not depend on where the repository is checked out.
fn load(path: &Path) -> Source {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let name = path
        .strip_prefix(root)
        .unwrap_or(path)
        .to_string_lossy()
        .replace('\\', "/");
    let bytes = std::fs::read(path).expect("corpus file is readable");
    Source::from_bytes(name, bytes).expect("corpus file is UTF-8 text")
}

#[test]
fn well_formed_files() {
    insta::glob!("lang/ok/*.comm", |path| {
        let src = load(path);
        let program = match parse(&src) {
            Ok(p) => p,
            Err(d) => panic!("{}", d.render(Some(&src))),
        };
        check_corpus_contract(&src, &program);
        insta::assert_snapshot!(dump(&src, &program));
    });
}

#[test]
fn syntax_errors() {
    insta::glob!("lang/err/syntax_*.comm", |path| {
        let src = load(path);
        let diag = match parse(&src) {
            Ok(_) => panic!("{} parsed without error", src.name),
            Err(d) => d,
        };
        assert!(
            diag.message.starts_with("syntax error: "),
            "{}",
            diag.message
        );
        let span = diag.span.expect("a syntax error has a position");
        assert!(span.start <= span.end && span.end <= src.text.len());
        insta::assert_snapshot!(diag.render(Some(&src)));
    });
}

/// The corpus promises files that the keyword checker can later run on:
/// DEBUT first, FIN last, and every variable assigned before it is read.
fn check_corpus_contract(src: &Source, program: &Program) {
    let call_name = |i: usize| match &program.stmts[i].kind {
        StmtKind::Expr(Expr {
            kind: ExprKind::Call { func, .. },
            ..
        }) => func.name.clone(),
        _ => String::new(),
    };
    assert_eq!(call_name(0), "DEBUT", "{}: first statement", src.name);
    assert_eq!(
        call_name(program.stmts.len() - 1),
        "FIN",
        "{}: last statement",
        src.name
    );
    let mut defined: Vec<String> = Vec::new();
    for stmt in &program.stmts {
        let (value, target) = match &stmt.kind {
            StmtKind::Assign { target, value } => (value, Some(&target.name)),
            StmtKind::Expr(e) => (e, None),
        };
        let mut used = Vec::new();
        names(value, &mut used);
        for (name, span) in used {
            assert!(
                defined.contains(&name),
                "{}:{:?}: '{name}' is read before it is assigned",
                src.name,
                src.line_col(span.start)
            );
        }
        if let Some(t) = target {
            defined.push(t.clone());
        }
    }
}

fn names(e: &Expr, out: &mut Vec<(String, Span)>) {
    match &e.kind {
        ExprKind::Name(n) => out.push((n.clone(), e.span)),
        ExprKind::Tuple(items) => items.iter().for_each(|i| names(i, out)),
        ExprKind::Call { args, .. } => args.iter().for_each(|a| names(&a.value, out)),
        ExprKind::Unary { operand, .. } => names(operand, out),
        ExprKind::Binary { lhs, rhs, .. } => {
            names(lhs, out);
            names(rhs, out);
        }
        ExprKind::Int(_) | ExprKind::Real(_) | ExprKind::Str(_) | ExprKind::NoneLit => {}
    }
}

// ---------------------------------------------------------------------------
// The dump: one line per statement, argument or tuple item that does not fit
// inline; `line:col` of the node that starts the line in the left column.
// Arithmetic is printed fully parenthesised so precedence is visible; reals
// always show a '.' or an exponent, integers never do.
// ---------------------------------------------------------------------------

struct Dump<'a> {
    src: &'a Source,
    out: String,
}

impl Dump<'_> {
    fn line(&mut self, at: Option<Span>, depth: usize, text: &str) {
        let pos = match at {
            Some(s) => {
                let (l, c) = self.src.line_col(s.start);
                format!("{l}:{c}")
            }
            None => String::new(),
        };
        self.out
            .push_str(&format!("{pos:<7} {}{text}\n", "  ".repeat(depth)));
    }

    /// Writes `prefix` followed by `e`, expanding calls with keyword
    /// arguments and long tuples over several lines.
    fn expr(&mut self, at: Span, depth: usize, prefix: &str, e: &Expr) {
        if let Some(s) = inline(e) {
            self.line(Some(at), depth, &format!("{prefix}{s}"));
            return;
        }
        match &e.kind {
            ExprKind::Call { func, args } => {
                self.line(Some(at), depth, &format!("{prefix}{}(", func.name));
                for a in args {
                    let p = match &a.name {
                        Some(n) => format!("{} = ", n.name),
                        None => String::new(),
                    };
                    self.expr(a.span, depth + 1, &p, &a.value);
                }
                self.line(None, depth, ")");
            }
            ExprKind::Tuple(items) => {
                self.line(Some(at), depth, &format!("{prefix}("));
                for i in items {
                    self.expr(i.span, depth + 1, "", i);
                }
                self.line(None, depth, ")");
            }
            _ => unreachable!("every other expression is inline"),
        }
    }
}

fn inline(e: &Expr) -> Option<String> {
    let s = match &e.kind {
        ExprKind::Int(i) => i.to_string(),
        ExprKind::Real(r) => format!("{r:?}"),
        ExprKind::Str(s) => format!("{s:?}"),
        ExprKind::NoneLit => "None".into(),
        ExprKind::Name(n) => n.clone(),
        ExprKind::Tuple(items) => {
            let v: Option<Vec<String>> = items.iter().map(inline).collect();
            let v = v?;
            match v.len() {
                1 => format!("({},)", v[0]),
                _ => format!("({})", v.join(", ")),
            }
        }
        ExprKind::Call { func, args } => {
            if args.iter().any(|a| a.name.is_some()) {
                return None;
            }
            let v: Option<Vec<String>> = args.iter().map(|a| inline(&a.value)).collect();
            format!("{}({})", func.name, v?.join(", "))
        }
        ExprKind::Unary { op, operand } => {
            let o = if *op == UnOp::Neg { "-" } else { "+" };
            format!("({o}{})", inline(operand)?)
        }
        ExprKind::Binary { op, lhs, rhs } => {
            format!("({} {} {})", inline(lhs)?, op.symbol(), inline(rhs)?)
        }
    };
    (s.len() <= 70).then_some(s)
}

fn dump(src: &Source, program: &Program) -> String {
    let mut d = Dump {
        src,
        out: String::new(),
    };
    for stmt in &program.stmts {
        match &stmt.kind {
            StmtKind::Assign { target, value } => {
                d.expr(stmt.span, 0, &format!("{} = ", target.name), value)
            }
            StmtKind::Expr(e) => d.expr(stmt.span, 0, "", e),
        }
    }
    d.out
}
