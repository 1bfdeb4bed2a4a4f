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
use aster::lang::ast::{Expr, ExprKind, LogicOp, Program, Stmt, StmtKind, Target, UnOp};
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
    contract(src, &program.stmts, &mut defined);
}

/// Every name read is assigned before (in the text order, blocks
/// included).
fn contract(src: &Source, stmts: &[Stmt], defined: &mut Vec<String>) {
    let read = |e: &Expr, defined: &Vec<String>| {
        let mut used = Vec::new();
        names(e, &mut used);
        for (name, span) in used {
            assert!(
                defined.contains(&name),
                "{}:{:?}: '{name}' is read before it is assigned",
                src.name,
                src.line_col(span.start)
            );
        }
    };
    let bind = |t: &Target, defined: &mut Vec<String>| {
        defined.extend(t.names().into_iter().map(|n| n.name.clone()))
    };
    for stmt in stmts {
        match &stmt.kind {
            StmtKind::Assign { target, value } => {
                read(value, defined);
                defined.push(target.name.clone());
            }
            StmtKind::Unpack { targets, value } => {
                read(value, defined);
                defined.extend(targets.iter().map(|n| n.name.clone()));
            }
            StmtKind::AugAssign { target, value, .. } => {
                read(value, defined);
                read(
                    &Expr {
                        kind: ExprKind::Name(target.name.clone()),
                        span: target.span,
                    },
                    defined,
                );
            }
            StmtKind::Expr(e) => read(e, defined),
            StmtKind::SetItem {
                target,
                index,
                value,
            } => {
                read(value, defined);
                read(
                    &Expr {
                        kind: ExprKind::Name(target.name.clone()),
                        span: target.span,
                    },
                    defined,
                );
                read(index, defined);
            }
            StmtKind::Pass => {}
            StmtKind::FromImport { names, .. } => defined.extend(
                names
                    .iter()
                    .flatten()
                    .map(|(n, a)| a.as_ref().unwrap_or(n).name.clone()),
            ),
            StmtKind::Import(items) => defined.extend(
                items
                    .iter()
                    .map(|i| i.alias.as_ref().unwrap_or(&i.module).name.clone()),
            ),
            StmtKind::If { branches, orelse } => {
                for (c, b) in branches {
                    read(c, defined);
                    contract(src, b, defined);
                }
                contract(src, orelse, defined);
            }
            StmtKind::For { target, iter, body } => {
                read(iter, defined);
                bind(target, defined);
                contract(src, body, defined);
            }
        }
    }
}

/// The names an expression reads (a comprehension's own variables and the
/// attributes of modules excluded).
fn names(e: &Expr, out: &mut Vec<(String, Span)>) {
    match &e.kind {
        ExprKind::Name(n) => out.push((n.clone(), e.span)),
        ExprKind::ListComp { generators, .. } => {
            let mut inner = Vec::new();
            for c in e.children() {
                names(c, &mut inner);
            }
            let bound: Vec<String> = generators
                .iter()
                .flat_map(|g| {
                    g.target
                        .names()
                        .into_iter()
                        .map(|n| n.name.clone())
                        .collect::<Vec<_>>()
                })
                .collect();
            out.extend(inner.into_iter().filter(|(n, _)| !bound.contains(n)));
        }
        _ => e.children().into_iter().for_each(|c| names(c, out)),
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
                        None if a.unpack => "**".to_string(),
                        None => String::new(),
                    };
                    self.expr(a.span, depth + 1, &p, &a.value);
                }
                self.line(None, depth, ")");
            }
            ExprKind::Tuple(items) | ExprKind::List(items) => {
                let (o, c) = if matches!(e.kind, ExprKind::List(_)) {
                    ("[", "]")
                } else {
                    ("(", ")")
                };
                self.line(Some(at), depth, &format!("{prefix}{o}"));
                for i in items {
                    self.expr(i.span, depth + 1, "", i);
                }
                self.line(None, depth, c);
            }
            _ => self.line(Some(at), depth, &format!("{prefix}{}", long(e))),
        }
    }
}

/// An expression on one line, however long.
fn long(e: &Expr) -> String {
    let l = |x: &Expr| long(x);
    match &e.kind {
        ExprKind::Int(i) => i.to_string(),
        ExprKind::Real(r) => format!("{r:?}"),
        ExprKind::Str(s) => format!("{s:?}"),
        ExprKind::Bool(b) => (if *b { "True" } else { "False" }).to_string(),
        ExprKind::NoneLit => "None".into(),
        ExprKind::Name(n) => n.clone(),
        ExprKind::Tuple(items) => {
            let v: Vec<String> = items.iter().map(l).collect();
            match v.len() {
                1 => format!("({},)", v[0]),
                _ => format!("({})", v.join(", ")),
            }
        }
        ExprKind::List(items) => {
            let v: Vec<String> = items.iter().map(l).collect();
            format!("[{}]", v.join(", "))
        }
        ExprKind::Dict(items) => {
            let v: Vec<String> = items
                .iter()
                .map(|(k, v)| match k {
                    Some(k) => format!("{}: {}", l(k), l(v)),
                    None => format!("**{}", l(v)),
                })
                .collect();
            format!("{{{}}}", v.join(", "))
        }
        ExprKind::ListComp { elt, generators } => {
            let mut s = format!("[{}", l(elt));
            for g in generators {
                s.push_str(&format!(" for {} in {}", target(&g.target), l(&g.iter)));
                for c in &g.ifs {
                    s.push_str(&format!(" if {}", l(c)));
                }
            }
            s + "]"
        }
        ExprKind::Call { func, args } => format!("{}({})", func.name, arg_list(args)),
        ExprKind::MethodCall {
            value,
            method,
            args,
        } => format!("{}.{}({})", l(value), method.name, arg_list(args)),
        ExprKind::Attribute { value, attr } => format!("{}.{}", l(value), attr.name),
        ExprKind::Index { value, index } => format!("{}[{}]", l(value), l(index)),
        ExprKind::Slice {
            value,
            lower,
            upper,
            step,
        } => {
            let b = |x: &Option<Box<Expr>>| x.as_ref().map_or(String::new(), |e| long(e));
            format!("{}[{}:{}:{}]", l(value), b(lower), b(upper), b(step))
        }
        ExprKind::Unary { op, operand } => {
            let o = match op {
                UnOp::Neg => "-",
                UnOp::Pos => "+",
                UnOp::Not => "not ",
            };
            format!("({o}{})", l(operand))
        }
        ExprKind::Binary { op, lhs, rhs } => format!("({} {} {})", l(lhs), op.symbol(), l(rhs)),
        ExprKind::Compare { first, rest } => {
            let mut s = format!("({}", l(first));
            for (op, x) in rest {
                s.push_str(&format!(" {} {}", op.symbol(), l(x)));
            }
            s + ")"
        }
        ExprKind::Logic { op, lhs, rhs } => {
            let o = if *op == LogicOp::And { "and" } else { "or" };
            format!("({} {o} {})", l(lhs), l(rhs))
        }
        ExprKind::IfElse { cond, then, orelse } => {
            format!("({} if {} else {})", l(then), l(cond), l(orelse))
        }
    }
}

fn arg_list(args: &[aster::lang::ast::Arg]) -> String {
    let v: Vec<String> = args
        .iter()
        .map(|a| match &a.name {
            Some(n) => format!("{}={}", n.name, long(&a.value)),
            None if a.unpack => format!("**{}", long(&a.value)),
            None => long(&a.value),
        })
        .collect();
    v.join(", ")
}

fn target(t: &Target) -> String {
    match t {
        Target::Name(n) => n.name.clone(),
        // A one-name tuple shows its comma (`for f, in L`), as Python
        // writes the target that unpacks one-item sequences.
        Target::Tuple(v) if v.len() == 1 => format!("{},", target_item(&v[0])),
        Target::Tuple(v) => v.iter().map(target_item).collect::<Vec<_>>().join(", "),
    }
}

/// An item of a tuple target: a nested tuple in parentheses.
fn target_item(t: &Target) -> String {
    match t {
        Target::Name(n) => n.name.clone(),
        Target::Tuple(_) => format!("({})", target(t)),
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
            if args.iter().any(|a| a.name.is_some() || a.unpack) {
                return None;
            }
            let v: Option<Vec<String>> = args.iter().map(|a| inline(&a.value)).collect();
            format!("{}({})", func.name, v?.join(", "))
        }
        ExprKind::List(items) => {
            let v: Option<Vec<String>> = items.iter().map(inline).collect();
            format!("[{}]", v?.join(", "))
        }
        ExprKind::Unary { op, operand } => {
            let o = match op {
                UnOp::Neg => "-",
                UnOp::Pos => "+",
                UnOp::Not => "not ",
            };
            format!("({o}{})", inline(operand)?)
        }
        ExprKind::Binary { op, lhs, rhs } => {
            format!("({} {} {})", inline(lhs)?, op.symbol(), inline(rhs)?)
        }
        _ => long(e),
    };
    (s.len() <= 70).then_some(s)
}

fn dump(src: &Source, program: &Program) -> String {
    let mut d = Dump {
        src,
        out: String::new(),
    };
    dump_block(&mut d, &program.stmts, 0);
    d.out
}

fn dump_block(d: &mut Dump<'_>, stmts: &[Stmt], depth: usize) {
    for stmt in stmts {
        let at = Some(stmt.span);
        match &stmt.kind {
            StmtKind::Assign { target, value } => {
                d.expr(stmt.span, depth, &format!("{} = ", target.name), value)
            }
            StmtKind::Unpack { targets, value } => {
                let n: Vec<&str> = targets.iter().map(|t| t.name.as_str()).collect();
                d.expr(stmt.span, depth, &format!("{} = ", n.join(", ")), value)
            }
            StmtKind::AugAssign { target, op, value } => d.expr(
                stmt.span,
                depth,
                &format!("{} {}= ", target.name, op.symbol()),
                value,
            ),
            StmtKind::Expr(e) => d.expr(stmt.span, depth, "", e),
            StmtKind::SetItem {
                target,
                index,
                value,
            } => d.expr(
                stmt.span,
                depth,
                &format!("{}[{}] = ", target.name, long(index)),
                value,
            ),
            StmtKind::Pass => d.line(at, depth, "pass"),
            StmtKind::Import(items) => {
                let v: Vec<String> = items
                    .iter()
                    .map(|i| match &i.alias {
                        Some(a) => format!("{} as {}", i.module.name, a.name),
                        None => i.module.name.clone(),
                    })
                    .collect();
                d.line(at, depth, &format!("import {}", v.join(", ")))
            }
            StmtKind::FromImport { module, names } => {
                let n = match names {
                    None => "*".to_string(),
                    Some(v) => v
                        .iter()
                        .map(|(n, a)| match a {
                            Some(a) => format!("{} as {}", n.name, a.name),
                            None => n.name.clone(),
                        })
                        .collect::<Vec<_>>()
                        .join(", "),
                };
                d.line(at, depth, &format!("from {} import {n}", module.name))
            }
            StmtKind::If { branches, orelse } => {
                for (i, (c, b)) in branches.iter().enumerate() {
                    let kw = if i == 0 { "if" } else { "elif" };
                    d.line(Some(c.span), depth, &format!("{kw} {}:", long(c)));
                    dump_block(d, b, depth + 1);
                }
                if !orelse.is_empty() {
                    d.line(None, depth, "else:");
                    dump_block(d, orelse, depth + 1);
                }
            }
            StmtKind::For {
                target: t,
                iter,
                body,
            } => {
                d.line(at, depth, &format!("for {} in {}:", target(t), long(iter)));
                dump_block(d, body, depth + 1);
            }
        }
    }
}
