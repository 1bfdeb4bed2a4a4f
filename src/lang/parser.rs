//! The parser of command files: the pest grammar `grammar/comm.pest`, lowered
//! into the spanned syntax tree of [`crate::lang::ast`].
//!
//! Syntax errors are written for someone who writes code_aster files, not for
//! someone who knows the grammar. pest reports the furthest position it
//! reached and the named rules it tried there; those names are turned into
//! words ("expected ',' or ')'"). The mistakes that pest describes badly
//! (unterminated strings, malformed numbers, unclosed brackets, stray
//! characters, Python statements that are not supported) are recognised from
//! the text around the failure instead, by a small scanner that knows only
//! strings, comments and brackets.
//!
//! Inputs that would recurse deeply (thousands of nested brackets or chained
//! operators) are refused with a message rather than allowed to exhaust the
//! stack: bracket depth is bounded before pest runs, and expression depth
//! while lowering.

use crate::diag::{Diagnostic, Source, Span};
use crate::lang::ast::{
    Arg, BinOp, CmpOp, Comprehension, Expr, ExprKind, Ident, ImportItem, LogicOp, Program, Stmt,
    StmtKind, Target, UnOp,
};
use pest::error::{ErrorVariant, InputLocation};
use pest::iterators::Pair;
use pest::Parser as _;

mod grammar {
    // A private module keeps the generated `Rule` enum out of the public API.
    #[derive(pest_derive::Parser)]
    #[grammar = "../grammar/comm.pest"]
    pub(super) struct CommParser;
}
use grammar::{CommParser, Rule};

/// Deepest bracket nesting accepted. Real files nest five or six levels
/// (command, tuple, `_F`, tuple, arithmetic). Each level costs about 16 KiB
/// of stack in an unoptimised build (pest's generated code plus lowering)
/// and a tenth of that when optimised, so 32 levels fit in a 1 MiB stack,
/// half of a test thread's.
pub const MAX_BRACKET_DEPTH: usize = 32;

/// Deepest expression tree accepted (operators, calls, tuples). It protects
/// every later recursive pass over the tree (checker, evaluator, `Drop`)
/// from a file such as `A = 1+1+1+...` with a hundred thousand terms.
pub const MAX_EXPR_DEPTH: usize = 200;

/// Words that Python reserves. None of them can be a name in a command file:
/// `None` is a literal, the others belong to Python syntax that the command
/// language does not have, and saying so is clearer than "expected ','".
const PYTHON_KEYWORDS: &[&str] = &[
    "False", "None", "True", "and", "as", "assert", "async", "await", "break", "class", "continue",
    "def", "del", "elif", "else", "except", "finally", "for", "from", "global", "if", "import",
    "in", "is", "lambda", "nonlocal", "not", "or", "pass", "raise", "return", "try", "while",
    "with", "yield",
];

/// Parses a whole command file.
///
/// The first error stops the parse: after a syntax error the rest of the file
/// cannot be read reliably, and later checking needs a complete tree anyway.
pub fn parse(src: &Source) -> Result<Program, Diagnostic> {
    let text = src.text.as_str();
    let scan = Scan::run(text, text.len());
    if let Some(at) = scan.too_deep {
        return Err(syntax_error(
            format!("brackets nested more than {MAX_BRACKET_DEPTH} levels deep"),
            Span::new(at, at + 1),
        ));
    }
    let mut pairs = match CommParser::parse(Rule::program, text) {
        Ok(pairs) => pairs,
        Err(err) => return Err(explain(text, &scan, &err)),
    };
    let program = pairs
        .next()
        .expect("a successful parse yields the program rule");
    lower_program(program, text)
}

fn syntax_error(message: impl AsRef<str>, span: Span) -> Diagnostic {
    Diagnostic::error(format!("syntax error: {}", message.as_ref())).at(span)
}

fn span_of(pair: &Pair<'_, Rule>) -> Span {
    let s = pair.as_span();
    Span::new(s.start(), s.end())
}

// ---------------------------------------------------------------------------
// Lowering: one function per grammar rule.
// ---------------------------------------------------------------------------

/// An expression with the depth of its tree, so that the depth bound can be
/// enforced while building without a second recursive pass.
struct Node {
    expr: Expr,
    depth: usize,
}

/// Deepest nesting of `if`/`for` blocks, Python's own limit (CO_MAXBLOCKS).
/// It bounds the recursion of the block builder and of the checker.
pub const MAX_BLOCK_DEPTH: usize = 20;

/// One logical line, before blocks are built from indentation.
struct Line<'a> {
    /// The whitespace before the line's first token.
    indent: &'a str,
    /// Offset of the line's first token.
    start: usize,
    kind: LineKind,
}

enum LineKind {
    Simple(Vec<Stmt>),
    Header {
        head: Head,
        /// Span of the header up to its ':'.
        span: Span,
        /// Statements after the ':' on the same line.
        inline: Vec<Stmt>,
    },
}

enum Head {
    If(Expr),
    Elif(Expr),
    Else,
    For(Target, Expr),
}

impl Head {
    fn word(&self) -> &'static str {
        match self {
            Head::If(_) => "if",
            Head::Elif(_) => "elif",
            Head::Else => "else",
            Head::For(..) => "for",
        }
    }
}

fn lower_program(pair: Pair<'_, Rule>, text: &str) -> Result<Program, Diagnostic> {
    let mut lines: Vec<Line<'_>> = Vec::new();
    let mut new_line = true;
    for p in pair.into_inner() {
        match p.as_rule() {
            Rule::eol => new_line = true,
            Rule::stmt => {
                let start = p.as_span().start();
                let stmt = lower_stmt(p)?;
                match lines.last_mut() {
                    Some(Line {
                        kind: LineKind::Simple(v),
                        ..
                    }) if !new_line => v.push(stmt),
                    _ => lines.push(Line {
                        indent: indentation(text, start),
                        start,
                        kind: LineKind::Simple(vec![stmt]),
                    }),
                }
                new_line = false;
            }
            Rule::compound => {
                let start = p.as_span().start();
                lines.push(Line {
                    indent: indentation(text, start),
                    start,
                    kind: lower_compound(p)?,
                });
                new_line = true;
            }
            _ => {}
        }
    }
    let mut at = 0;
    let stmts = block(text, &lines, &mut at, None, 0)?;
    debug_assert_eq!(at, lines.len());
    Ok(Program { stmts })
}

/// The whitespace between the start of the physical line and `start` (a
/// form feed resets it, as in Python; the byte order mark is not part of
/// it).
fn indentation(text: &str, start: usize) -> &str {
    let line_start = text[..start].rfind(['\n', '\r']).map_or(0, |p| p + 1);
    let ws = &text[line_start..start];
    let ws = ws.strip_prefix('\u{FEFF}').unwrap_or(ws);
    match ws.rfind('\x0C') {
        Some(p) => &ws[p + 1..],
        None => ws,
    }
}

/// How two indentations compare, as Python does when it refuses to guess
/// a tab's width: one must be a prefix of the other.
fn compare_indent(a: &str, b: &str) -> Option<std::cmp::Ordering> {
    use std::cmp::Ordering::*;
    if a == b {
        Some(Equal)
    } else if a.starts_with(b) {
        Some(Greater)
    } else if b.starts_with(a) {
        Some(Less)
    } else {
        None
    }
}

fn first_token(text: &str, start: usize) -> Span {
    let len = text[start..].chars().next().map_or(0, char::len_utf8);
    Span::new(start, start + len)
}

fn tabs_error(text: &str, line: &Line<'_>) -> Diagnostic {
    syntax_error(
        "inconsistent use of tabs and spaces in indentation",
        first_token(text, line.start),
    )
    .note("indent the lines of a block with the same characters (spaces are best)")
}

/// Builds the statements of one block from `lines[*at..]`. `level` is the
/// block's indentation, `None` at the top level, where indentation is
/// ignored as it always was in command files (Python refuses it): only
/// the lines after a block header are read by their indentation.
fn block(
    text: &str,
    lines: &[Line<'_>],
    at: &mut usize,
    level: Option<&str>,
    depth: usize,
) -> Result<Vec<Stmt>, Diagnostic> {
    use std::cmp::Ordering::*;
    let mut out = Vec::new();
    let mut after_block = false;
    while let Some(line) = lines.get(*at) {
        if let Some(lv) = level {
            match compare_indent(line.indent, lv) {
                Some(Equal) => {}
                Some(Less) => return Ok(out),
                Some(Greater) if after_block => {
                    return Err(syntax_error(
                        "unindent does not match any outer indentation level",
                        first_token(text, line.start),
                    ))
                }
                Some(Greater) => {
                    return Err(syntax_error(
                        "unexpected indent",
                        first_token(text, line.start),
                    )
                    .note("a line is indented more than the lines before it only at the start of a block (after a line ending with ':')"))
                }
                None => return Err(tabs_error(text, line)),
            }
        }
        *at += 1;
        after_block = false;
        let (head, hspan, inline) = match &line.kind {
            LineKind::Simple(stmts) => {
                out.extend(stmts.iter().cloned());
                continue;
            }
            LineKind::Header { head, span, inline } => (head, *span, inline),
        };
        let body =
            |at: &mut usize, head_line: &Line<'_>, hspan: Span, inline: &[Stmt], word: &str| {
                header_body(text, lines, at, head_line, hspan, inline, word, depth)
            };
        let stmt = match head {
            Head::Elif(_) | Head::Else => {
                return Err(syntax_error(
                    format!(
                        "'{}' does not follow an 'if' block at the same indentation",
                        head.word()
                    ),
                    first_token(text, line.start),
                ))
            }
            Head::For(target, iter) => {
                let b = body(at, line, hspan, inline, "for")?;
                let end = b.last().map_or(hspan.end, |s| s.span.end);
                Stmt {
                    kind: StmtKind::For {
                        target: target.clone(),
                        iter: iter.clone(),
                        body: b,
                    },
                    span: Span::new(hspan.start, end),
                }
            }
            Head::If(cond) => {
                let b = body(at, line, hspan, inline, "if")?;
                let mut end = b.last().map_or(hspan.end, |s| s.span.end);
                let mut branches = vec![(cond.clone(), b)];
                let mut orelse = Vec::new();
                while let Some(next) = lines.get(*at) {
                    let LineKind::Header {
                        head: h @ (Head::Elif(_) | Head::Else),
                        span,
                        inline,
                    } = &next.kind
                    else {
                        break;
                    };
                    match compare_indent(next.indent, line.indent) {
                        Some(Equal) => {}
                        None => return Err(tabs_error(text, next)),
                        // Deeper or shallower: not this `if`'s; the loop
                        // of the right block reports it.
                        Some(_) => break,
                    }
                    *at += 1;
                    let b = body(at, next, *span, inline, h.word())?;
                    end = b.last().map_or(span.end, |s| s.span.end);
                    match h {
                        Head::Elif(c) => branches.push((c.clone(), b)),
                        _ => {
                            orelse = b;
                            break;
                        }
                    }
                }
                Stmt {
                    kind: StmtKind::If { branches, orelse },
                    span: Span::new(hspan.start, end),
                }
            }
        };
        out.push(stmt);
        after_block = true;
        // After a block, a top-level line may not stop between the
        // header's indentation and the body's.
        if level.is_none() {
            if let Some(next) = lines.get(*at) {
                match compare_indent(next.indent, line.indent) {
                    Some(Equal | Less) => {}
                    Some(Greater) => {
                        return Err(syntax_error(
                            "unindent does not match any outer indentation level",
                            first_token(text, next.start),
                        ))
                    }
                    None => return Err(tabs_error(text, next)),
                }
            }
        }
    }
    Ok(out)
}

/// The body of a header: its statements on the same line, or the indented
/// lines that follow it.
#[allow(clippy::too_many_arguments)]
fn header_body(
    text: &str,
    lines: &[Line<'_>],
    at: &mut usize,
    head_line: &Line<'_>,
    hspan: Span,
    inline: &[Stmt],
    word: &str,
    depth: usize,
) -> Result<Vec<Stmt>, Diagnostic> {
    if depth + 1 > MAX_BLOCK_DEPTH {
        return Err(syntax_error(
            format!("blocks nested more than {MAX_BLOCK_DEPTH} levels deep"),
            hspan,
        ));
    }
    if !inline.is_empty() {
        return Ok(inline.to_vec());
    }
    let (line, _) = line_col(text, hspan.start);
    let missing = |span: Span| {
        syntax_error(
            format!("expected an indented block after '{word}' statement on line {line}"),
            span,
        )
        .note("indent the lines of the block more than the line that ends with ':' (write 'pass' for an empty block)")
    };
    let Some(next) = lines.get(*at) else {
        return Err(missing(Span::new(text.len(), text.len())));
    };
    match compare_indent(next.indent, head_line.indent) {
        Some(std::cmp::Ordering::Greater) => {}
        Some(_) => return Err(missing(first_token(text, next.start))),
        None => return Err(tabs_error(text, next)),
    }
    let stmts = block(text, lines, at, Some(next.indent), depth + 1)?;
    // The line that ended the block must line up with an enclosing one:
    // checked by the enclosing block (or, at the top level, by `block`).
    let _ = head_line;
    Ok(stmts)
}

fn lower_compound(pair: Pair<'_, Rule>) -> Result<LineKind, Diagnostic> {
    let mut it = pair.into_inner();
    let head_pair = it.next().expect("compound has a header");
    let colon = it.next().expect("compound has a colon");
    let span = Span::new(head_pair.as_span().start(), colon.as_span().end());
    let head = match head_pair.as_rule() {
        Rule::if_head | Rule::elif_head => {
            let mut h = head_pair.into_inner();
            let kw = h.next().expect("keyword");
            let cond = lower_expr(h.next().expect("condition"))?.expr;
            if kw.as_rule() == Rule::kw_if {
                Head::If(cond)
            } else {
                Head::Elif(cond)
            }
        }
        Rule::else_head => Head::Else,
        Rule::for_head => {
            let mut h = head_pair.into_inner();
            let _kw = h.next();
            let target = lower_loop_targets(h.next().expect("targets"))?;
            let _in = h.next();
            let iter = lower_expr_list(h.next().expect("iterable"))?.expr;
            Head::For(target, iter)
        }
        r => unreachable!("unexpected header {r:?}"),
    };
    let mut inline = Vec::new();
    for p in it {
        if p.as_rule() == Rule::stmt {
            inline.push(lower_stmt(p)?);
        }
    }
    Ok(LineKind::Header { head, span, inline })
}

fn lower_targets(pair: Pair<'_, Rule>) -> Result<Target, Diagnostic> {
    let mut names = Vec::new();
    let mut comma = false;
    for p in pair.into_inner() {
        match p.as_rule() {
            Rule::ident => names.push(lower_ident(p)?),
            _ => comma = true,
        }
    }
    Ok(if names.len() == 1 && !comma {
        Target::Name(names.pop().expect("one name"))
    } else {
        Target::Tuple(names.into_iter().map(Target::Name).collect())
    })
}

/// A `for` or comprehension target: Python reads `(a, b)` as `a, b` and
/// `(a)` as `a`, while a bracketed list `[a]` always unpacks (a one-name
/// list target takes a one-item sequence apart); items nest
/// (`for a, (b, c) in ...`).
fn lower_loop_targets(pair: Pair<'_, Rule>) -> Result<Target, Diagnostic> {
    let items = pair
        .into_inner()
        .next()
        .expect("loop_targets holds loop_items");
    lower_loop_items(items)
}

fn lower_loop_items(pair: Pair<'_, Rule>) -> Result<Target, Diagnostic> {
    let mut items = Vec::new();
    let mut comma = false;
    for p in pair.into_inner() {
        match p.as_rule() {
            Rule::loop_item => items.push(lower_loop_item(p)?),
            _ => comma = true,
        }
    }
    Ok(if items.len() == 1 && !comma {
        items.pop().expect("one item")
    } else {
        Target::Tuple(items)
    })
}

fn lower_loop_item(pair: Pair<'_, Rule>) -> Result<Target, Diagnostic> {
    let mut bracket = false;
    let mut inner = None;
    for p in pair.into_inner() {
        match p.as_rule() {
            Rule::ident => return Ok(Target::Name(lower_ident(p)?)),
            Rule::lbrack => bracket = true,
            Rule::loop_items => inner = Some(lower_loop_items(p)?),
            _ => {}
        }
    }
    let inner = inner.expect("a bracketed loop item holds loop_items");
    Ok(match inner {
        Target::Name(n) if bracket => Target::Tuple(vec![Target::Name(n)]),
        t => t,
    })
}

fn lower_stmt(pair: Pair<'_, Rule>) -> Result<Stmt, Diagnostic> {
    let span = span_of(&pair);
    let inner = pair.into_inner().next().expect("stmt has one child");
    let kind = match inner.as_rule() {
        Rule::assign => {
            let mut it = inner.into_inner();
            let target = lower_targets(it.next().expect("assign targets"))?;
            let _eq = it.next();
            let value = lower_expr_list(it.next().expect("assign value"))?.expr;
            match target {
                Target::Name(target) => StmtKind::Assign { target, value },
                Target::Tuple(targets) => StmtKind::Unpack {
                    targets: targets
                        .into_iter()
                        .map(|t| match t {
                            Target::Name(n) => n,
                            Target::Tuple(_) => unreachable!("assignment targets are names"),
                        })
                        .collect(),
                    value,
                },
            }
        }
        Rule::augassign => {
            let mut it = inner.into_inner();
            let target = lower_ident(it.next().expect("augassign name"))?;
            let op = match it.next().expect("augassign operator").as_str() {
                "+=" => BinOp::Add,
                "-=" => BinOp::Sub,
                "*=" => BinOp::Mul,
                "/=" => BinOp::Div,
                "//=" => BinOp::FloorDiv,
                "%=" => BinOp::Mod,
                _ => BinOp::Pow,
            };
            let value = lower_expr_list(it.next().expect("augassign value"))?.expr;
            StmtKind::AugAssign { target, op, value }
        }
        Rule::setitem => {
            let mut it = inner.into_inner();
            let target = lower_ident(it.next().expect("setitem name"))?;
            let sub = it.next().expect("setitem subscript");
            let sub_span = span_of(&sub);
            let slice = sub.into_inner().nth(1).expect("subscript has a slice");
            let mut parts = slice.into_inner();
            let index = match (parts.next(), parts.next()) {
                (Some(e), None) if e.as_rule() != Rule::colon => lower_expr(e)?.expr,
                (None, _) => {
                    return Err(syntax_error(
                        "expected an index or a slice between '[' and ']'",
                        sub_span,
                    ))
                }
                _ => {
                    return Err(syntax_error(
                        "assigning to a slice (L[a:b] = ...) is not supported",
                        sub_span,
                    )
                    .note("assign one item at a time (L[i] = x), or build a new list"))
                }
            };
            let _eq = it.next();
            let value = lower_expr_list(it.next().expect("setitem value"))?.expr;
            StmtKind::SetItem {
                target,
                index,
                value,
            }
        }
        Rule::pass_stmt => StmtKind::Pass,
        Rule::import_stmt => {
            let mut items = Vec::new();
            for p in inner.into_inner() {
                if p.as_rule() == Rule::import_item {
                    let mut it = p.into_inner();
                    let module = lower_module(it.next().expect("module"))?;
                    let alias = match it.nth(1) {
                        Some(a) => Some(lower_ident(a)?),
                        None => None,
                    };
                    items.push(ImportItem { module, alias });
                }
            }
            StmtKind::Import(items)
        }
        Rule::from_stmt => {
            let mut module = None;
            let mut names: Option<Vec<(Ident, Option<Ident>)>> = Some(Vec::new());
            for p in inner.into_inner() {
                match p.as_rule() {
                    Rule::module => module = Some(lower_module(p)?),
                    Rule::star => names = None,
                    Rule::import_list => {
                        for n in p.into_inner() {
                            if n.as_rule() != Rule::name_as {
                                continue;
                            }
                            let mut it = n.into_inner();
                            let name = lower_ident(it.next().expect("name"))?;
                            let alias = match it.nth(1) {
                                Some(a) => Some(lower_ident(a)?),
                                None => None,
                            };
                            if let Some(v) = names.as_mut() {
                                v.push((name, alias));
                            }
                        }
                    }
                    _ => {}
                }
            }
            StmtKind::FromImport {
                module: module.expect("from has a module"),
                names,
            }
        }
        _ => StmtKind::Expr(lower_expr(inner)?.expr),
    };
    Ok(Stmt { kind, span })
}

/// `a.b.c` as one identifier named `a.b.c`.
fn lower_module(pair: Pair<'_, Rule>) -> Result<Ident, Diagnostic> {
    let span = span_of(&pair);
    let mut parts = Vec::new();
    for p in pair.into_inner() {
        if p.as_rule() == Rule::ident {
            parts.push(lower_ident(p)?.name);
        }
    }
    Ok(Ident {
        name: parts.join("."),
        span,
    })
}

fn lower_ident(pair: Pair<'_, Rule>) -> Result<Ident, Diagnostic> {
    let span = span_of(&pair);
    let name = pair.as_str();
    if PYTHON_KEYWORDS.contains(&name) {
        return Err(unsupported_keyword(name, span));
    }
    Ok(Ident {
        name: name.to_string(),
        span,
    })
}

/// `a, b, c` (a tuple without brackets, as in `A = 1, 2`) or one
/// expression.
fn lower_expr_list(pair: Pair<'_, Rule>) -> Result<Node, Diagnostic> {
    let span = span_of(&pair);
    let mut items = Vec::new();
    let mut comma = false;
    for p in pair.into_inner() {
        match p.as_rule() {
            Rule::comma => comma = true,
            _ => items.push(lower_expr(p)?),
        }
    }
    if items.len() == 1 && !comma {
        return Ok(items.pop().expect("one item"));
    }
    let depth = items.iter().map(|n| n.depth).max().unwrap_or(0);
    let items = items.into_iter().map(|n| n.expr).collect();
    deeper(ExprKind::Tuple(items), span, depth)
}

/// Every expression rule, by the rule of the pair.
fn lower_expr(pair: Pair<'_, Rule>) -> Result<Node, Diagnostic> {
    match pair.as_rule() {
        Rule::expr => lower_conditional(pair),
        Rule::disjunction | Rule::conjunction => lower_logic(pair),
        Rule::inversion => lower_inversion(pair),
        Rule::comparison => lower_comparison(pair),
        Rule::sum | Rule::term => lower_arith(pair),
        Rule::factor => lower_factor(pair),
        r => unreachable!("unexpected expression rule {r:?}"),
    }
}

/// `t0 if c0 else t1 if c1 else e`, folded from the right.
fn lower_conditional(pair: Pair<'_, Rule>) -> Result<Node, Diagnostic> {
    let mut parts = Vec::new();
    for p in pair.into_inner() {
        if p.as_rule() == Rule::disjunction {
            parts.push(lower_expr(p)?);
        }
    }
    let mut acc = parts.pop().expect("expr has an operand");
    while parts.len() >= 2 {
        let cond = parts.pop().expect("condition");
        let then = parts.pop().expect("value");
        let span = then.expr.span.to(acc.expr.span);
        let depth = then.depth.max(cond.depth).max(acc.depth);
        acc = deeper(
            ExprKind::IfElse {
                cond: Box::new(cond.expr),
                then: Box::new(then.expr),
                orelse: Box::new(acc.expr),
            },
            span,
            depth,
        )?;
    }
    Ok(acc)
}

fn lower_logic(pair: Pair<'_, Rule>) -> Result<Node, Diagnostic> {
    let mut it = pair.into_inner();
    let mut acc = lower_expr(it.next().expect("logic has an operand"))?;
    while let Some(op) = it.next() {
        let op = if op.as_rule() == Rule::kw_and {
            LogicOp::And
        } else {
            LogicOp::Or
        };
        let rhs = lower_expr(it.next().expect("operator has a right operand"))?;
        let span = acc.expr.span.to(rhs.expr.span);
        let depth = acc.depth.max(rhs.depth);
        acc = deeper(
            ExprKind::Logic {
                op,
                lhs: Box::new(acc.expr),
                rhs: Box::new(rhs.expr),
            },
            span,
            depth,
        )?;
    }
    Ok(acc)
}

fn lower_inversion(pair: Pair<'_, Rule>) -> Result<Node, Diagnostic> {
    let mut nots = Vec::new();
    let mut node = None;
    for p in pair.into_inner() {
        match p.as_rule() {
            Rule::kw_not => nots.push((UnOp::Not, p.as_span().start())),
            _ => node = Some(lower_expr(p)?),
        }
    }
    apply_unary(nots, node.expect("inversion has an operand"))
}

fn lower_comparison(pair: Pair<'_, Rule>) -> Result<Node, Diagnostic> {
    let mut it = pair.into_inner();
    let first = lower_expr(it.next().expect("comparison has an operand"))?;
    let mut rest = Vec::new();
    let mut depth = first.depth;
    let mut span = first.expr.span;
    while let Some(op) = it.next() {
        let words: Vec<&str> = op.as_str().split_whitespace().collect();
        let op = match op.as_str() {
            "==" => CmpOp::Eq,
            "!=" => CmpOp::Ne,
            "<" => CmpOp::Lt,
            "<=" => CmpOp::Le,
            ">" => CmpOp::Gt,
            ">=" => CmpOp::Ge,
            "in" => CmpOp::In,
            _ if words.first() == Some(&"not") => CmpOp::NotIn,
            // `not` and `in` separated by a comment or a continuation.
            _ => CmpOp::NotIn,
        };
        let rhs = lower_expr(it.next().expect("operator has a right operand"))?;
        depth = depth.max(rhs.depth);
        span = span.to(rhs.expr.span);
        rest.push((op, rhs.expr));
    }
    if rest.is_empty() {
        return Ok(first);
    }
    deeper(
        ExprKind::Compare {
            first: Box::new(first.expr),
            rest,
        },
        span,
        depth,
    )
}

/// `sum` and `term` share their shape: operands separated by
/// left-associative operators.
fn lower_arith(pair: Pair<'_, Rule>) -> Result<Node, Diagnostic> {
    let mut it = pair.into_inner();
    let first = it.next().expect("expr has a first operand");
    let mut acc = lower_expr(first)?;
    while let Some(op) = it.next() {
        let op = match op.as_str() {
            "+" => BinOp::Add,
            "-" => BinOp::Sub,
            "*" => BinOp::Mul,
            "//" => BinOp::FloorDiv,
            "%" => BinOp::Mod,
            _ => BinOp::Div,
        };
        let rhs = lower_expr(it.next().expect("operator has a right operand"))?;
        acc = binary(op, acc, rhs)?;
    }
    Ok(acc)
}

fn unary_op(pair: &Pair<'_, Rule>) -> UnOp {
    if pair.as_str() == "-" {
        UnOp::Neg
    } else {
        UnOp::Pos
    }
}

fn lower_factor(pair: Pair<'_, Rule>) -> Result<Node, Diagnostic> {
    let mut ops = Vec::new();
    let mut power = None;
    for p in pair.into_inner() {
        match p.as_rule() {
            Rule::unary_op => ops.push((unary_op(&p), p.as_span().start())),
            _ => power = Some(lower_power(p)?),
        }
    }
    let node = power.expect("factor has a power");
    apply_unary(ops, node)
}

/// Applies prefix operators, innermost (rightmost) first.
fn apply_unary(ops: Vec<(UnOp, usize)>, mut node: Node) -> Result<Node, Diagnostic> {
    for (op, start) in ops.into_iter().rev() {
        let span = Span::new(start, node.expr.span.end);
        node = deeper(
            ExprKind::Unary {
                op,
                operand: Box::new(node.expr),
            },
            span,
            node.depth,
        )?;
    }
    Ok(node)
}

/// `a ** -b ** c` is `a ** (-(b ** c))`: the chain is folded from the right,
/// and the signs in front of an operand apply to the power that starts there.
fn lower_power(pair: Pair<'_, Rule>) -> Result<Node, Diagnostic> {
    let mut segments: Vec<(Vec<(UnOp, usize)>, Node)> = Vec::new();
    let mut signs = Vec::new();
    for p in pair.into_inner() {
        match p.as_rule() {
            Rule::pow_op => {}
            Rule::unary_op => signs.push((unary_op(&p), p.as_span().start())),
            _ => segments.push((std::mem::take(&mut signs), lower_postfix(p)?)),
        }
    }
    let (last_signs, last) = segments.pop().expect("power has an operand");
    let mut acc = apply_unary(last_signs, last)?;
    while let Some((signs, base)) = segments.pop() {
        acc = binary(BinOp::Pow, base, acc)?;
        acc = apply_unary(signs, acc)?;
    }
    Ok(acc)
}

/// A primary followed by `[index]`, `[a:b]`, `.attr` and `.method(...)`.
fn lower_postfix(pair: Pair<'_, Rule>) -> Result<Node, Diagnostic> {
    let start = pair.as_span().start();
    let mut it = pair.into_inner();
    let mut acc = lower_primary(it.next().expect("postfix has a primary"))?;
    for t in it {
        let span = Span::new(start, t.as_span().end());
        let rule = t.as_rule();
        let mut parts = t.into_inner();
        acc = match rule {
            Rule::subscript => {
                let _lb = parts.next();
                let slice = parts.next().expect("subscript has a slice");
                let slice_span = span_of(&slice);
                let mut bounds: Vec<Option<Node>> = vec![None];
                let mut colons = 0;
                for p in slice.into_inner() {
                    if p.as_rule() == Rule::colon {
                        colons += 1;
                        bounds.push(None);
                    } else {
                        *bounds.last_mut().expect("a bound") = Some(lower_expr(p)?);
                    }
                }
                let depth = bounds
                    .iter()
                    .flatten()
                    .map(|n| n.depth)
                    .max()
                    .unwrap_or(0)
                    .max(acc.depth);
                if colons == 0 {
                    let Some(index) = bounds.pop().flatten() else {
                        return Err(syntax_error(
                            "expected an index or a slice between '[' and ']'",
                            Span::new(slice_span.start.saturating_sub(1), slice_span.end + 1),
                        ));
                    };
                    deeper(
                        ExprKind::Index {
                            value: Box::new(acc.expr),
                            index: Box::new(index.expr),
                        },
                        span,
                        depth,
                    )?
                } else {
                    let mut b = bounds.into_iter().map(|n| n.map(|n| Box::new(n.expr)));
                    let lower = b.next().flatten();
                    let upper = b.next().flatten();
                    let step = b.next().flatten();
                    deeper(
                        ExprKind::Slice {
                            value: Box::new(acc.expr),
                            lower,
                            upper,
                            step,
                        },
                        span,
                        depth,
                    )?
                }
            }
            Rule::attribute => {
                let _dot = parts.next();
                let attr = lower_ident(parts.next().expect("attribute name"))?;
                let depth = acc.depth;
                deeper(
                    ExprKind::Attribute {
                        value: Box::new(acc.expr),
                        attr,
                    },
                    span,
                    depth,
                )?
            }
            _ => {
                let _dot = parts.next();
                let method = lower_ident(parts.next().expect("method name"))?;
                let (args, depth) = lower_args(parts)?;
                let depth = depth.max(acc.depth);
                deeper(
                    ExprKind::MethodCall {
                        value: Box::new(acc.expr),
                        method,
                        args,
                    },
                    span,
                    depth,
                )?
            }
        };
    }
    Ok(acc)
}

fn binary(op: BinOp, lhs: Node, rhs: Node) -> Result<Node, Diagnostic> {
    let span = lhs.expr.span.to(rhs.expr.span);
    deeper(
        ExprKind::Binary {
            op,
            lhs: Box::new(lhs.expr),
            rhs: Box::new(rhs.expr),
        },
        span,
        lhs.depth.max(rhs.depth),
    )
}

/// Builds a node one level above its deepest child, refusing trees deeper
/// than [`MAX_EXPR_DEPTH`].
fn deeper(kind: ExprKind, span: Span, child_depth: usize) -> Result<Node, Diagnostic> {
    let depth = child_depth + 1;
    if depth > MAX_EXPR_DEPTH {
        return Err(syntax_error(
            format!("expression too deeply nested (more than {MAX_EXPR_DEPTH} levels of operators, calls and tuples)"),
            span,
        ));
    }
    Ok(Node {
        expr: Expr { kind, span },
        depth,
    })
}

fn leaf(kind: ExprKind, span: Span) -> Node {
    Node {
        expr: Expr { kind, span },
        depth: 1,
    }
}

fn lower_primary(pair: Pair<'_, Rule>) -> Result<Node, Diagnostic> {
    let span = span_of(&pair);
    match pair.as_rule() {
        Rule::number => lower_number(pair.as_str(), span),
        Rule::strings => lower_strings(pair),
        Rule::none => Ok(leaf(ExprKind::NoneLit, span)),
        Rule::boolean => Ok(leaf(ExprKind::Bool(pair.as_str() == "True"), span)),
        Rule::name => {
            let id = lower_ident(pair.into_inner().next().expect("name has an ident"))?;
            Ok(leaf(ExprKind::Name(id.name), span))
        }
        Rule::call => lower_call(pair),
        Rule::paren => lower_sequence(pair, true),
        Rule::list => lower_sequence(pair, false),
        Rule::dict => lower_dict(pair),
        r => unreachable!("unexpected primary rule {r:?}"),
    }
}

fn lower_number(text: &str, span: Span) -> Result<Node, Diagnostic> {
    if text.contains(['.', 'e', 'E']) {
        let value: f64 = text
            .parse()
            .map_err(|_| syntax_error(format!("malformed number '{text}'"), span))?;
        if !value.is_finite() {
            return Err(syntax_error(
                format!("number '{text}' is too large for a 64-bit float"),
                span,
            ));
        }
        Ok(leaf(ExprKind::Real(value), span))
    } else {
        let value: i64 = text.parse().map_err(|_| {
            syntax_error(
                format!(
                    "integer '{text}' is too large (the largest is {})",
                    i64::MAX
                ),
                span,
            )
            .note("write it as a real number, e.g. with a trailing '.'")
        })?;
        Ok(leaf(ExprKind::Int(value), span))
    }
}

fn lower_strings(pair: Pair<'_, Rule>) -> Result<Node, Diagnostic> {
    let span = span_of(&pair);
    let mut value = String::new();
    for s in pair.into_inner() {
        unescape(s.as_str(), s.as_span().start(), &mut value)?;
    }
    Ok(leaf(ExprKind::Str(value), span))
}

/// Decodes one quoted literal (quotes included in `raw`) into `out`.
/// Only the escapes a command file needs are accepted; Python would keep an
/// unknown escape such as `\d` as two characters, which is almost always a
/// mistake in a file path or title, so it is refused here.
fn unescape(raw: &str, start: usize, out: &mut String) -> Result<(), Diagnostic> {
    let body = &raw[1..raw.len() - 1];
    let mut chars = body.char_indices();
    while let Some((i, c)) = chars.next() {
        if c != '\\' {
            out.push(c);
            continue;
        }
        let (_, e) = chars.next().expect("the grammar pairs every backslash");
        out.push(match e {
            '\\' => '\\',
            '\'' => '\'',
            '"' => '"',
            'n' => '\n',
            't' => '\t',
            'r' => '\r',
            _ => {
                let at = start + 1 + i;
                return Err(syntax_error(
                    format!("unknown escape '\\{e}' in string"),
                    Span::new(at, at + 1 + e.len_utf8()),
                )
                .note("the escapes are \\\\ \\' \\\" \\n \\t \\r; write \\\\ for a backslash"));
            }
        });
    }
    Ok(())
}

fn lower_call(pair: Pair<'_, Rule>) -> Result<Node, Diagnostic> {
    let span = span_of(&pair);
    let mut it = pair.into_inner();
    let func = lower_ident(it.next().expect("call has a name"))?;
    let (args, depth) = lower_args(it)?;
    deeper(ExprKind::Call { func, args }, span, depth)
}

/// The arguments among `pairs` (brackets and commas are skipped), with the
/// depth of the deepest.
fn lower_args<'a>(
    pairs: impl Iterator<Item = Pair<'a, Rule>>,
) -> Result<(Vec<Arg>, usize), Diagnostic> {
    let mut args: Vec<Arg> = Vec::new();
    let mut depth = 0;
    for p in pairs {
        if p.as_rule() != Rule::arg {
            continue;
        }
        let arg_span = span_of(&p);
        let inner = p.into_inner().next().expect("arg has one child");
        let arg = if inner.as_rule() == Rule::kwarg {
            let mut kw = inner.into_inner();
            let name = lower_ident(kw.next().expect("kwarg name"))?;
            let _eq = kw.next();
            let value = lower_expr(kw.next().expect("kwarg value"))?;
            depth = depth.max(value.depth);
            Arg {
                name: Some(name),
                unpack: false,
                value: value.expr,
                span: arg_span,
            }
        } else if inner.as_rule() == Rule::star2_arg {
            let value = lower_expr(inner.into_inner().nth(1).expect("** has a value"))?;
            depth = depth.max(value.depth);
            Arg {
                name: None,
                unpack: true,
                value: value.expr,
                span: arg_span,
            }
        } else {
            if args.iter().any(|a| a.name.is_some() || a.unpack) {
                return Err(
                    syntax_error("positional argument after keyword arguments", arg_span).note(
                        "give values without a keyword before the first KEYWORD=value or **dict",
                    ),
                );
            }
            let value = lower_expr(inner)?;
            depth = depth.max(value.depth);
            Arg {
                name: None,
                unpack: false,
                value: value.expr,
                span: arg_span,
            }
        };
        args.push(arg);
    }
    Ok((args, depth))
}

/// `( ... )` and `[ ... ]`. A parenthesised single expression without a
/// comma is that expression (Python's rule, which makes `('CYLBAS')` a
/// string); its span is widened to the parentheses so that the spans of
/// enclosing nodes cover the text that produced them.
fn lower_sequence(pair: Pair<'_, Rule>, is_paren: bool) -> Result<Node, Diagnostic> {
    let span = span_of(&pair);
    let mut items = Vec::new();
    let mut generators = Vec::new();
    let mut depth = 0;
    let mut comma = false;
    for p in pair.into_inner() {
        match p.as_rule() {
            Rule::comma => comma = true,
            Rule::expr => items.push(lower_expr(p)?),
            Rule::comp_for => {
                let mut it = p.into_inner();
                let _for = it.next();
                let target = lower_loop_targets(it.next().expect("targets"))?;
                let _in = it.next();
                let iter = lower_expr(it.next().expect("iterable"))?;
                depth = depth.max(iter.depth);
                let mut ifs = Vec::new();
                for c in it {
                    let cond = lower_expr(c.into_inner().nth(1).expect("condition"))?;
                    depth = depth.max(cond.depth);
                    ifs.push(cond.expr);
                }
                generators.push(Comprehension {
                    target,
                    iter: iter.expr,
                    ifs,
                });
            }
            _ => {}
        }
    }
    if is_paren && items.len() == 1 && !comma {
        let mut node = items.pop().expect("one item");
        node.expr.span = span;
        return Ok(node);
    }
    let depth = items.iter().map(|n| n.depth).max().unwrap_or(0).max(depth);
    let mut items: Vec<Expr> = items.into_iter().map(|n| n.expr).collect();
    let kind = if !generators.is_empty() {
        ExprKind::ListComp {
            elt: Box::new(items.pop().expect("a comprehension has an element")),
            generators,
        }
    } else if is_paren {
        ExprKind::Tuple(items)
    } else {
        ExprKind::List(items)
    };
    deeper(kind, span, depth)
}

/// `{key: value, **d}`.
fn lower_dict(pair: Pair<'_, Rule>) -> Result<Node, Diagnostic> {
    let span = span_of(&pair);
    let mut items = Vec::new();
    let mut depth = 0;
    for p in pair.into_inner() {
        if p.as_rule() != Rule::dict_item {
            continue;
        }
        let mut it = p.into_inner();
        let first = it.next().expect("dict item");
        if first.as_rule() == Rule::pow_op {
            let v = lower_expr(it.next().expect("** has a value"))?;
            depth = depth.max(v.depth);
            items.push((None, v.expr));
        } else {
            let k = lower_expr(first)?;
            let _colon = it.next();
            let v = lower_expr(it.next().expect("dict value"))?;
            depth = depth.max(k.depth).max(v.depth);
            items.push((Some(k.expr), v.expr));
        }
    }
    deeper(ExprKind::Dict(items), span, depth)
}

/// Python's reserved words that command files use (in their Python
/// meaning); the others belong to syntax that command files lack.
const SUPPORTED_KEYWORDS: &[&str] = &[
    "False", "None", "True", "and", "as", "elif", "else", "for", "from", "if", "import", "in",
    "not", "or", "pass",
];

fn unsupported_keyword(word: &str, span: Span) -> Diagnostic {
    match word {
        "None" => syntax_error("'None' cannot be used as a name", span),
        _ if SUPPORTED_KEYWORDS.contains(&word) => syntax_error(
            format!("'{word}' is a reserved word of Python and cannot be used as a name"),
            span,
        ),
        "is" => syntax_error("'is' is not supported", span)
            .note("compare values with == and !="),
        _ => syntax_error(format!("'{word}' is Python syntax that command files do not support"), span)
            .note("a command file is a sequence of assignments, command calls, imports of math, and if/for blocks (no def, class, while, try, with, ...)"),
    }
}

// ---------------------------------------------------------------------------
// Scanner: strings, comments and brackets only, for the checks pest cannot
// phrase well.
// ---------------------------------------------------------------------------

struct Scan {
    /// Opening brackets still open at the stop position: (offset, char).
    open: Vec<(usize, char)>,
    /// First string without its closing quote on the same line: (start, end).
    unterminated: Option<(usize, usize)>,
    /// First bracket beyond [`MAX_BRACKET_DEPTH`].
    too_deep: Option<usize>,
}

impl Scan {
    /// Scans the tokens that start before `stop`.
    fn run(text: &str, stop: usize) -> Scan {
        let b = text.as_bytes();
        let mut scan = Scan {
            open: Vec::new(),
            unterminated: None,
            too_deep: None,
        };
        let mut i = 0;
        while i < b.len() && i < stop {
            match b[i] {
                b'#' => {
                    while i < b.len() && b[i] != b'\n' && b[i] != b'\r' {
                        i += 1;
                    }
                }
                q @ (b'\'' | b'"') => {
                    let start = i;
                    i += 1;
                    loop {
                        if i >= b.len() || b[i] == b'\n' || b[i] == b'\r' {
                            if scan.unterminated.is_none() {
                                scan.unterminated = Some((start, i));
                            }
                            break;
                        }
                        if b[i] == b'\\'
                            && i + 1 < b.len()
                            && b[i + 1] != b'\n'
                            && b[i + 1] != b'\r'
                        {
                            i += 2;
                            continue;
                        }
                        i += 1;
                        if b[i - 1] == q {
                            break;
                        }
                    }
                    continue;
                }
                c @ (b'(' | b'[' | b'{') => {
                    scan.open.push((i, c as char));
                    if scan.open.len() > MAX_BRACKET_DEPTH && scan.too_deep.is_none() {
                        scan.too_deep = Some(i);
                    }
                }
                b')' | b']' | b'}' => {
                    scan.open.pop();
                }
                _ => {}
            }
            i += 1;
        }
        scan
    }
}

// ---------------------------------------------------------------------------
// Turning a pest failure into a message.
// ---------------------------------------------------------------------------

fn explain(text: &str, scan: &Scan, err: &pest::error::Error<Rule>) -> Diagnostic {
    let pos = match err.location {
        InputLocation::Pos(p) => p,
        InputLocation::Span((s, _)) => s,
    };
    let positives: Vec<Rule> = match &err.variant {
        ErrorVariant::ParsingError { positives, .. } => positives.clone(),
        // pest's own guard: the native stack ran low (a thread much smaller
        // than MAX_BRACKET_DEPTH assumes).
        ErrorVariant::CustomError { message } => {
            return syntax_error(
                format!("the file is nested too deeply to parse here ({message})"),
                Span::new(pos, pos),
            )
        }
    };

    if let Some((start, end)) = scan.unterminated.filter(|&(s, _)| s <= pos) {
        let quote = &text[start..start + 1];
        let mut d = syntax_error("unterminated string", Span::new(start, end.max(start + 1))).note(
            format!("add the closing {quote} before the end of the line"),
        );
        if text[..start].ends_with(&quote.repeat(2)) {
            d = d.note("triple-quoted strings are not supported");
        }
        return d;
    }
    if let Some(span) = malformed_number(text, pos) {
        return syntax_error(
            format!("malformed number '{}'", &text[span.start..span.end]),
            span,
        )
        .note("numbers are written like 12, 0.35, .35, 227000., 1.E-5 or 2e3");
    }
    if let Some((word, span)) = keyword_near(text, pos) {
        return unsupported_keyword(word, span);
    }
    if let Some(d) = stray_character(text, pos) {
        return d;
    }
    let found = found_token(text, pos);
    let open = Scan::run(text, pos).open;
    let at_line_start = text[..pos].ends_with('\n') || pos == 0;
    // A bracket left open swallows the newlines that follow it, so the
    // parse only fails at the end of the file or at the next statement,
    // which starts in the first column: the open bracket is the news.
    if found.len == 0 && text[pos..].trim().is_empty() || at_line_start && found.starts_value {
        if let Some(&(at, c)) = open.last() {
            let mut d = syntax_error(format!("'{c}' was never closed"), Span::new(at, at + 1));
            if !text[pos..].trim().is_empty() {
                d = d.note(format!(
                    "the statement at line {} starts while it is still open",
                    line_of(text, pos)
                ));
            }
            if open.len() > 1 {
                d = d.note(format!(
                    "{} more bracket(s) opened before it are not closed either",
                    open.len() - 1
                ));
            }
            return d;
        }
    }
    let span = Span::new(pos, pos + found.len);
    if let Some(closer) = text[pos..]
        .chars()
        .next()
        .filter(|c| matches!(c, ')' | ']' | '}'))
    {
        let opener = match closer {
            ')' => '(',
            ']' => '[',
            _ => '{',
        };
        match open.last() {
            None => return syntax_error(format!("unmatched '{closer}'"), span),
            Some(&(at, c)) if c != opener => {
                let (line, col) = line_col(text, at);
                return syntax_error(
                    format!(
                        "'{closer}' does not match the '{c}' opened at line {line}, column {col}"
                    ),
                    span,
                );
            }
            Some(_) => {}
        }
    }

    if std::env::var_os("ASTER_DEBUG_PEST").is_some() {
        eprintln!("positives at {pos}: {positives:?}");
    }
    let expected = expectations(&positives);
    let mut d = if expected.is_empty() {
        syntax_error(format!("unexpected {}", found.description), span)
    } else {
        syntax_error(
            format!(
                "expected {}, found {}",
                join_or(&expected),
                found.description
            ),
            span,
        )
    };
    let wants = |rules: &[Rule]| positives.iter().any(|r| rules.contains(r));
    if let Some(note) = hint(
        text,
        pos,
        &found,
        &open,
        wants(&[Rule::semi, Rule::eol, Rule::EOI]),
        wants(&[Rule::eq]),
        wants(&[Rule::comma]),
    ) {
        d = d.note(note);
    }
    d
}

/// A guess at the cause, for the mistakes that the expected-token list
/// alone explains badly. At most one, the most specific.
fn hint(
    text: &str,
    pos: usize,
    found: &Found,
    open: &[(usize, char)],
    wants_end: bool,
    wants_eq: bool,
    wants_comma: bool,
) -> Option<&'static str> {
    let rest = &text[pos..];
    let before = &text[..pos];
    let prev = before.chars().next_back().unwrap_or(' ');
    // Directly after a name or a closing bracket, without space.
    let attached = is_ident_char(prev) || prev == ')' || prev == ']';
    let word_start = rest.starts_with(|c: char| is_ident_char(c) || c == '\'' || c == '"');
    Some(
        if rest.starts_with('=') && before.ends_with(['+', '-', '*', '/', '%']) {
            "augmented assignment (+=, -=, ...) is supported on a name only; write L[i] = L[i] + ..."
        } else if wants_end && rest.starts_with('=') {
            "assign one name per statement (A = B = value is not supported)"
        } else if open.last().is_some_and(|(_, c)| *c == '{') && rest.starts_with([',', '}']) {
            "sets are not supported: braces make a dict, {'KEY': value, ...}"
        } else if rest.starts_with('(') && attached {
            "only a name can be called: NAME(...)"
        } else if rest.starts_with(['\'', '"'])
            && before.ends_with(['r', 'R', 'u', 'U', 'f', 'F', 'b', 'B'])
        {
            "string prefixes (r'', u'', f'', b'') are not supported"
        } else if wants_end && word_start {
            "put each statement on its own line, or separate them with ';'"
        } else if found.starts_value && before.ends_with(['\'', '"']) {
            "is a quote misplaced? the string before it ends just here"
        } else if wants_eq && found.starts_value {
            "write KEYWORD=value, and separate arguments with ','"
        } else if wants_comma && found.starts_value {
            "is a ',' missing before it?"
        } else if found.description == "end of line" && open.is_empty() {
            "a statement continues on the next line only inside brackets or after a '\\'"
        } else {
            return None;
        },
    )
}

/// 1-based line and column (in characters) of a byte offset.
fn line_col(text: &str, at: usize) -> (usize, usize) {
    let line_start = text[..at].rfind('\n').map(|p| p + 1).unwrap_or(0);
    (line_of(text, at), text[line_start..at].chars().count() + 1)
}

fn line_of(text: &str, pos: usize) -> usize {
    text.as_bytes()[..pos]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// The words for what the parser would have accepted, in a stable order.
/// Operators are left out when anything else is possible: after any value an
/// operator could follow, and listing them only hides the useful part.
fn expectations(positives: &[Rule]) -> Vec<&'static str> {
    const VALUE: &str = "a value (number, string, name, tuple or call)";
    const STATEMENT: &str = "a statement (NAME = value or a command call)";
    let mut out: Vec<&'static str> = Vec::new();
    let mut operator = false;
    // After a value, '[' starts an index, as an operator would.
    let after_value = positives.contains(&Rule::add_op);
    for r in positives {
        let word = match r {
            Rule::lbrack if after_value => continue,
            Rule::comma => "','",
            Rule::rparen => "')'",
            Rule::rbrack => "']'",
            Rule::rbrace => "'}'",
            Rule::eq => "'='",
            Rule::colon => "':'",
            Rule::kw_in => "'in'",
            Rule::kw_else => "'else'",
            Rule::kw_import => "'import'",
            Rule::semi | Rule::eol | Rule::EOI => "end of statement (new line or ';')",
            // Tried after every name (it could be a call) and after every
            // string (adjacent strings concatenate): never the useful word.
            Rule::lparen | Rule::string => continue,
            // What may follow any value: listing them hides the useful part.
            Rule::add_op
            | Rule::mul_op
            | Rule::pow_op
            | Rule::cmp_op
            | Rule::cmp_sym
            | Rule::kw_if
            | Rule::kw_and
            | Rule::kw_or
            | Rule::kw_not
            | Rule::kw_for
            | Rule::kw_as
            | Rule::comp_for
            | Rule::comp_if
            | Rule::dot
            | Rule::subscript
            | Rule::method
            | Rule::attribute => {
                operator = true;
                continue;
            }
            Rule::arg | Rule::kwarg => "an argument (KEYWORD=value or a value)",
            Rule::targets
            | Rule::loop_targets
            | Rule::loop_items
            | Rule::loop_item
            | Rule::name_as
            | Rule::import_list => "a name",
            Rule::module | Rule::import_item => "a module name",
            Rule::ident => "a name",
            Rule::program
            | Rule::stmt
            | Rule::assign
            | Rule::augassign
            | Rule::compound
            | Rule::if_head
            | Rule::elif_head
            | Rule::else_head
            | Rule::for_head
            | Rule::kw_elif
            | Rule::kw_pass
            | Rule::kw_from
            | Rule::pass_stmt
            | Rule::import_stmt
            | Rule::from_stmt => STATEMENT,
            _ => VALUE,
        };
        if !out.contains(&word) {
            out.push(word);
        }
    }
    if out.is_empty() && operator {
        out.push("an operator");
    }
    // "a value" already says what an argument can be, and where a
    // statement may start a blank line may too: saying so is noise.
    if out.contains(&VALUE) {
        out.retain(|w| !w.starts_with("an argument"));
    }
    if out.contains(&STATEMENT) {
        out.retain(|w| *w == STATEMENT);
    }
    // A ',' could make a tuple of a statement's value (`A = 1, 2`), which
    // is never what a missing line break or ';' means.
    const END: &str = "end of statement (new line or ';')";
    if out.contains(&END) && !out.contains(&"')'") && !out.contains(&"']'") && !out.contains(&"'}'")
    {
        out.retain(|w| *w != "','");
    }
    let rank = |w: &&str| match *w {
        "'='" => 0,
        "','" => 1,
        "')'" | "']'" | "'}'" => 2,
        _ => 3,
    };
    out.sort_by_key(rank);
    out
}

fn join_or(items: &[&str]) -> String {
    match items {
        [] => String::new(),
        [one] => one.to_string(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}

struct Found {
    description: String,
    /// Byte length of the token, for the caret.
    len: usize,
    /// Whether it could start a value (a missing ',' is then likely).
    starts_value: bool,
}

fn is_ident_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

fn found_token(text: &str, pos: usize) -> Found {
    let rest = &text[pos..];
    let Some(c) = rest.chars().next() else {
        return Found {
            description: "end of file".into(),
            len: 0,
            starts_value: false,
        };
    };
    if c == '\n' || c == '\r' {
        return Found {
            description: "end of line".into(),
            len: 0,
            starts_value: false,
        };
    }
    if is_ident_char(c) || c == '.' && rest[1..].starts_with(|d: char| d.is_ascii_digit()) {
        let len = rest
            .find(|d: char| !(is_ident_char(d) || d == '.'))
            .unwrap_or(rest.len());
        return Found {
            description: format!("'{}'", &rest[..len]),
            len,
            starts_value: true,
        };
    }
    if c == '\'' || c == '"' {
        return Found {
            description: "a string".into(),
            len: 1,
            starts_value: true,
        };
    }
    let two = rest.get(..2).filter(|t| matches!(*t, "**" | "==" | "//"));
    let tok = two.unwrap_or(&rest[..c.len_utf8()]);
    Found {
        description: format!("'{tok}'"),
        len: tok.len(),
        starts_value: matches!(c, '(' | '['),
    }
}

/// If the failure is inside or right after a numeric literal (`1.E`, `007`,
/// `1.5.3`, `12abc`), the span of the whole malformed token.
fn malformed_number(text: &str, pos: usize) -> Option<Span> {
    let b = text.as_bytes();
    let numeric = |c: u8| c.is_ascii_alphanumeric() || c == b'_' || c == b'.';
    // A sign belongs to the token only right after an exponent letter that
    // follows a digit or a point (`1e+`, `1.E-`).
    let sign_in_token = |i: usize| {
        i >= 2
            && (b[i - 1] == b'e' || b[i - 1] == b'E')
            && (b[i - 2].is_ascii_digit() || b[i - 2] == b'.')
    };
    let mut start = pos.min(b.len());
    while start > 0
        && (numeric(b[start - 1])
            || (matches!(b[start - 1], b'+' | b'-') && sign_in_token(start - 1)))
    {
        start -= 1;
    }
    let first = *b.get(start)?;
    let starts_number = first.is_ascii_digit()
        || (first == b'.' && b.get(start + 1).is_some_and(|c| c.is_ascii_digit()));
    if !starts_number || start == pos {
        return None;
    }
    let mut end = pos.min(b.len());
    while end < b.len()
        && (numeric(b[end]) || (matches!(b[end], b'+' | b'-') && sign_in_token(end)))
    {
        end += 1;
    }
    // The failure must be inside the token: `(1, 2]` fails after a
    // well-formed `2`.
    if end == pos {
        return None;
    }

    Some(Span::new(start, end))
}

/// A Python keyword that command files do not support, at the failure
/// position or just before it on the same line (`while x:` fails at `x`).
fn keyword_near(text: &str, pos: usize) -> Option<(&'static str, Span)> {
    let word_at = |start: usize| {
        let len = text[start..]
            .find(|c: char| !is_ident_char(c))
            .unwrap_or(text.len() - start);
        &text[start..start + len]
    };
    let kw = |w: &str| {
        PYTHON_KEYWORDS
            .iter()
            .find(|k| **k == w && !SUPPORTED_KEYWORDS.contains(k))
            .copied()
    };
    if pos < text.len() && text[pos..].starts_with(|c: char| is_ident_char(c)) {
        let starts_word =
            pos == 0 || !is_ident_char(text[..pos].chars().next_back().unwrap_or(' '));
        if starts_word {
            if let Some(k) = kw(word_at(pos)) {
                return Some((k, Span::new(pos, pos + k.len())));
            }
        }
    }
    let before = text[..pos].trim_end_matches([' ', '\t']);
    // Name characters are ASCII, so counting bytes stays on a boundary.
    let start = before.len()
        - before
            .bytes()
            .rev()
            .take_while(|&b| is_ident_char(b as char))
            .count();
    let word = &before[start..];
    if word.starts_with(|c: char| c.is_ascii_alphabetic()) {
        if let Some(k) = kw(word) {
            return Some((k, Span::new(start, start + k.len())));
        }
    }
    None
}

/// A character that starts no token of the language.
fn stray_character(text: &str, pos: usize) -> Option<Diagnostic> {
    let c = text[pos..].chars().next()?;
    let span = Span::new(pos, pos + c.len_utf8());
    if c == '\\' {
        return Some(
            syntax_error("unexpected '\\'", span)
                .note("a backslash continues a statement only as the last character of a line"),
        );
    }
    let known =
        is_ident_char(c) || " \t\x0C\r\n'\"()[]{},=+-*/.;#%<>!:".contains(c) || c == '\u{FEFF}';
    if known {
        return None;
    }
    let shown = if c.is_control() {
        format!("U+{:04X}", c as u32)
    } else {
        format!("'{c}'")
    };
    let d = syntax_error(format!("unexpected character {shown}"), span);
    Some(match c {
        '&' | '|' | '^' | '~' => {
            d.note("bitwise operators are not supported; the logical operators are and, or, not")
        }
        _ if c.is_alphabetic() => d.note("names use only ASCII letters, digits and '_'"),
        _ => d,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_str(text: &str) -> Result<Program, Diagnostic> {
        parse(&Source::new("t.comm", text))
    }

    fn ok(text: &str) -> Program {
        match parse_str(text) {
            Ok(p) => p,
            Err(d) => panic!("{}", d.render(Some(&Source::new("t.comm", text)))),
        }
    }

    fn err(text: &str) -> Diagnostic {
        match parse_str(text) {
            Ok(p) => panic!("expected an error for {text:?}, got {p:?}"),
            Err(d) => d,
        }
    }

    /// The value of `A = <text>`.
    fn value(text: &str) -> Expr {
        let p = ok(&format!("A = {text}\n"));
        match p.stmts.into_iter().next().unwrap().kind {
            StmtKind::Assign { value, .. } => value,
            k => panic!("not an assignment: {k:?}"),
        }
    }

    /// A compact s-expression, to state expected trees briefly.
    fn sx(e: &Expr) -> String {
        match &e.kind {
            ExprKind::Int(i) => i.to_string(),
            ExprKind::Real(r) => format!("{r:?}"),
            ExprKind::Str(s) => format!("{s:?}"),
            ExprKind::NoneLit => "None".into(),
            ExprKind::Name(n) => n.clone(),
            ExprKind::Tuple(items) => {
                let v: Vec<String> = items.iter().map(sx).collect();
                format!("(tuple {})", v.join(" "))
            }
            ExprKind::Call { func, args } => {
                let v: Vec<String> = args
                    .iter()
                    .map(|a| match &a.name {
                        Some(n) => format!("{}={}", n.name, sx(&a.value)),
                        None if a.unpack => format!("**{}", sx(&a.value)),
                        None => sx(&a.value),
                    })
                    .collect();
                format!("({} {})", func.name, v.join(" "))
            }
            ExprKind::Dict(items) => {
                let v: Vec<String> = items
                    .iter()
                    .map(|(k, v)| match k {
                        Some(k) => format!("{}:{}", sx(k), sx(v)),
                        None => format!("**{}", sx(v)),
                    })
                    .collect();
                format!("(dict {})", v.join(" "))
            }
            ExprKind::Unary { op, operand } => {
                let o = match op {
                    UnOp::Neg => "neg",
                    UnOp::Pos => "pos",
                    UnOp::Not => "not",
                };
                format!("({o} {})", sx(operand))
            }
            ExprKind::Binary { op, lhs, rhs } => {
                format!("({} {} {})", op.symbol(), sx(lhs), sx(rhs))
            }
            ExprKind::Bool(b) => (if *b { "True" } else { "False" }).to_string(),
            ExprKind::List(items) => {
                let v: Vec<String> = items.iter().map(sx).collect();
                format!("(list {})", v.join(" "))
            }
            ExprKind::ListComp { elt, generators } => {
                let mut out = format!("(listcomp {}", sx(elt));
                for g in generators {
                    out.push_str(&format!(" (for {} {}", tx(&g.target), sx(&g.iter)));
                    for c in &g.ifs {
                        out.push_str(&format!(" (if {})", sx(c)));
                    }
                    out.push(')');
                }
                out + ")"
            }
            ExprKind::MethodCall {
                value,
                method,
                args,
            } => {
                let v: Vec<String> = args.iter().map(|a| sx(&a.value)).collect();
                format!("(.{} {} {})", method.name, sx(value), v.join(" "))
            }
            ExprKind::Attribute { value, attr } => format!("(. {} {})", sx(value), attr.name),
            ExprKind::Index { value, index } => format!("(index {} {})", sx(value), sx(index)),
            ExprKind::Slice {
                value,
                lower,
                upper,
                step,
            } => {
                let b = |x: &Option<Box<Expr>>| x.as_ref().map_or("_".to_string(), |e| sx(e));
                format!(
                    "(slice {} {} {} {})",
                    sx(value),
                    b(lower),
                    b(upper),
                    b(step)
                )
            }
            ExprKind::Compare { first, rest } => {
                let mut out = format!("(cmp {}", sx(first));
                for (op, e) in rest {
                    out.push_str(&format!(" {} {}", op.symbol(), sx(e)));
                }
                out + ")"
            }
            ExprKind::Logic { op, lhs, rhs } => {
                let o = if *op == LogicOp::And { "and" } else { "or" };
                format!("({o} {} {})", sx(lhs), sx(rhs))
            }
            ExprKind::IfElse { cond, then, orelse } => {
                format!("(ifelse {} {} {})", sx(cond), sx(then), sx(orelse))
            }
        }
    }

    fn tx(t: &Target) -> String {
        match t {
            Target::Name(n) => n.name.clone(),
            Target::Tuple(v) => {
                let n: Vec<String> = v.iter().map(tx).collect();
                format!("({})", n.join(","))
            }
        }
    }

    /// A statement list as s-expressions, blocks included.
    fn st(stmts: &[Stmt]) -> String {
        let v: Vec<String> = stmts
            .iter()
            .map(|s| match &s.kind {
                StmtKind::Assign { target, value } => format!("{}={}", target.name, sx(value)),
                StmtKind::Unpack { targets, value } => {
                    let n: Vec<&str> = targets.iter().map(|i| i.name.as_str()).collect();
                    format!("{}={}", n.join(","), sx(value))
                }
                StmtKind::Expr(e) => sx(e),
                StmtKind::SetItem {
                    target,
                    index,
                    value,
                } => format!("{}[{}]={}", target.name, sx(index), sx(value)),
                StmtKind::AugAssign { target, op, value } => {
                    format!("{}{}={}", target.name, op.symbol(), sx(value))
                }
                StmtKind::Pass => "pass".into(),
                StmtKind::Import(items) => {
                    let v: Vec<String> = items
                        .iter()
                        .map(|i| match &i.alias {
                            Some(a) => format!("{} as {}", i.module.name, a.name),
                            None => i.module.name.clone(),
                        })
                        .collect();
                    format!("import {}", v.join(","))
                }
                StmtKind::FromImport { module, names } => match names {
                    None => format!("from {} *", module.name),
                    Some(n) => {
                        let v: Vec<&str> = n.iter().map(|(i, _)| i.name.as_str()).collect();
                        format!("from {} {}", module.name, v.join(","))
                    }
                },
                StmtKind::If { branches, orelse } => {
                    let mut out = String::from("(if");
                    for (c, b) in branches {
                        out.push_str(&format!(" {} [{}]", sx(c), st(b)));
                    }
                    if !orelse.is_empty() {
                        out.push_str(&format!(" else [{}]", st(orelse)));
                    }
                    out + ")"
                }
                StmtKind::For { target, iter, body } => {
                    format!("(for {} {} [{}])", tx(target), sx(iter), st(body))
                }
            })
            .collect();
        v.join("; ")
    }

    fn sv(text: &str) -> String {
        sx(&value(text))
    }

    #[test]
    fn number_forms_and_values() {
        let cases: &[(&str, f64)] = &[
            ("1.E-5", 1e-5),
            ("227000.", 227000.0),
            (".35", 0.35),
            ("1.0E+2", 100.0),
            ("1e5", 1e5),
            ("100.E3", 100e3),
            ("8.930E-9", 8.93e-9),
            ("0.", 0.0),
            ("00.5", 0.5),
            ("1.e5", 1e5),
            ("2.27", 2.27),
        ];
        for &(text, v) in cases {
            match value(text).kind {
                ExprKind::Real(r) => assert_eq!(r, v, "{text}"),
                k => panic!("{text}: {k:?}"),
            }
        }
        assert_eq!(value("30").kind, ExprKind::Int(30));
        assert_eq!(value("0").kind, ExprKind::Int(0));
        assert_eq!(value("9223372036854775807").kind, ExprKind::Int(i64::MAX));
    }

    #[test]
    fn integer_overflow_is_a_diagnostic() {
        let d = err("A = 9223372036854775808\n");
        assert!(d.message.contains("too large"), "{}", d.message);
        assert_eq!(d.span, Some(Span::new(4, 23)));
        let d = err("A = 1e999\n");
        assert!(
            d.message.contains("too large for a 64-bit float"),
            "{}",
            d.message
        );
    }

    #[test]
    fn malformed_numbers() {
        for (text, token) in [
            ("A = 1.E\n", "1.E"),
            ("A = 1e\n", "1e"),
            ("A = 1e+\n", "1e+"),
            ("A = 007\n", "007"),
            ("A = 1.5.3\n", "1.5.3"),
            ("F(X=12abc)\n", "12abc"),
        ] {
            let d = err(text);
            assert_eq!(
                d.message,
                format!("syntax error: malformed number '{token}'"),
                "{text}"
            );
            let s = d.span.unwrap();
            assert_eq!(&text[s.start..s.end], token);
        }
    }

    #[test]
    fn precedence_and_associativity() {
        assert_eq!(sv("1 + 2 * 3"), "(+ 1 (* 2 3))");
        assert_eq!(sv("1 - 2 - 3"), "(- (- 1 2) 3)");
        assert_eq!(sv("8 / 4 / 2"), "(/ (/ 8 4) 2)");
        assert_eq!(sv("2 ** 3 ** 2"), "(** 2 (** 3 2))");
        assert_eq!(sv("-2**2"), "(neg (** 2 2))");
        assert_eq!(sv("2**-1"), "(** 2 (neg 1))");
        assert_eq!(sv("2**-3**2"), "(** 2 (neg (** 3 2)))");
        assert_eq!(sv("-x*y"), "(* (neg x) y)");
        assert_eq!(sv("--+1"), "(neg (neg (pos 1)))");
        assert_eq!(sv("(1 + 2) * 3"), "(* (+ 1 2) 3)");
        assert_eq!(sv("a*b**c"), "(* a (** b c))");
        assert_eq!(sv("1.0*IMPACT_THEORIQUE"), "(* 1.0 IMPACT_THEORIQUE)");
        assert_eq!(sv("int(NPAS/2)+1"), "(+ (int (/ NPAS 2)) 1)");
    }

    #[test]
    fn tuples_lists_and_parentheses() {
        assert_eq!(sv("('CYLBAS')"), "\"CYLBAS\"");
        assert_eq!(sv("('CYLBAS',)"), "(tuple \"CYLBAS\")");
        assert_eq!(sv("(1, 2,)"), "(tuple 1 2)");
        assert_eq!(sv("(1, 2)"), "(tuple 1 2)");
        assert_eq!(sv("()"), "(tuple )");
        assert_eq!(sv("[1]"), "(list 1)");
        assert_eq!(sv("[]"), "(list )");
        assert_eq!(sv("[1, (2,), [3, 4,],]"), "(list 1 (tuple 2) (list 3 4))");
        assert_eq!(sv("1, 2"), "(tuple 1 2)");
        assert_eq!(sv("((1))"), "1");
    }

    #[test]
    fn calls_and_keywords() {
        assert_eq!(
            sv("DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=(_F(TOUT_GROUP_MA='OUI'),),)"),
            "(DEFI_GROUP reuse=MA MAILLAGE=MA CREA_GROUP_NO=(tuple (_F TOUT_GROUP_MA=\"OUI\")))"
        );
        assert_eq!(sv("min(1, 2.)"), "(min 1 2.0)");
        assert_eq!(sv("F()"), "(F )");
        assert_eq!(sv("F (X = None)"), "(F X=None)");
        let d = err("F(A=1, 2)\n");
        assert!(
            d.message.contains("positional argument after keyword"),
            "{}",
            d.message
        );
        // Python refuses a repeated keyword at compile time; here the
        // checker reports it, naming the command, so the parser keeps both.
        assert_eq!(sv("F(A=1, A=2)"), "(F A=1 A=2)");
    }

    #[test]
    fn dicts_unpacking_and_item_assignment() {
        assert_eq!(sv("{}"), "(dict )");
        assert_eq!(
            sv("{'A': 1, \"B\": (2,), **D,}"),
            "(dict \"A\":1 \"B\":(tuple 2) **D)"
        );
        assert_eq!(
            sv("{\n  'A': 1,  # c\n  'B': 2\n}"),
            "(dict \"A\":1 \"B\":2)"
        );
        assert_eq!(
            sv("CMD(**common, A=1, **other)"),
            "(CMD **common A=1 **other)"
        );
        assert_eq!(sv("_F(**kw)"), "(_F **kw)");
        let d = err("F(**kw, 2)\n");
        assert!(d.message.contains("positional argument after keyword"));
        let p = ok("L[0] = 1\nD['A'] = F(X=1)\nL[i + 1] = 2, 3\n");
        assert_eq!(
            st(&p.stmts),
            "L[0]=1; D[\"A\"]=(F X=1); L[(+ i 1)]=(tuple 2 3)"
        );
        let d = err("L[1:2] = 3\n");
        assert!(d.message.contains("assigning to a slice"), "{}", d.message);
        let d = err("L[] = 3\n");
        assert!(d.message.contains("expected an index"), "{}", d.message);
        // Sets are not dicts: the ':' is what is missing.
        let d = err("A = {1, 2}\n");
        assert!(d.message.contains("':'"), "{}", d.message);
        let d = err("A = {'a': 1]\n");
        assert_eq!(
            d.message,
            "syntax error: ']' does not match the '{' opened at line 1, column 5"
        );
        let d = err("A = {'a': 1\nFIN()\n");
        assert_eq!(d.message, "syntax error: '{' was never closed");
    }

    #[test]
    fn strings_and_escapes() {
        assert_eq!(value(r#"'a\'b'"#).kind, ExprKind::Str("a'b".into()));
        assert_eq!(
            value(r#""a\"b\\c\n\t""#).kind,
            ExprKind::Str("a\"b\\c\n\t".into())
        );
        assert_eq!(value(r#""it's""#).kind, ExprKind::Str("it's".into()));
        assert_eq!(value("'ab' \"cd\"").kind, ExprKind::Str("abcd".into()));
        assert_eq!(
            value("'é # not a comment'").kind,
            ExprKind::Str("é # not a comment".into())
        );
        let d = err(r"A = 'C:\data'");
        assert!(d.message.contains("unknown escape '\\d'"), "{}", d.message);
        assert_eq!(d.span, Some(Span::new(7, 9)));
        let d = err("A = 'abc\nB = 1\n");
        assert_eq!(d.message, "syntax error: unterminated string");
        assert_eq!(d.span, Some(Span::new(4, 8)));
    }

    #[test]
    fn statements_separators_and_comments() {
        let p = ok("\u{FEFF}# head\n\nDEBUT();  # c\nNPAS = 30; IMPACT = 1.0*NPAS ;\n   \nFIN()");
        assert_eq!(p.stmts.len(), 4);
        let d = err("A = 1 B = 2\n");
        assert_eq!(
            d.message,
            "syntax error: expected end of statement (new line or ';'), found 'B'"
        );
        assert_eq!(d.span, Some(Span::new(6, 7)));
        assert!(parse_str("A = 1;;\n").is_err());
        assert!(parse_str(";\n").is_err());
        assert_eq!(ok("").stmts.len(), 0);
        assert_eq!(ok("\n\n# only comments\n").stmts.len(), 0);
    }

    #[test]
    fn newlines_inside_brackets_and_continuation() {
        let p = ok("A = F(X=1,\n  # comment inside\n\n  Y=(1,\n 2),\n)\nB = 1 + \\\n  2\n");
        assert_eq!(p.stmts.len(), 2);
        // Outside brackets a newline ends the statement.
        let d = err("A = 1 +\n2\n");
        assert!(d.message.contains("expected a value"), "{}", d.message);
    }

    #[test]
    fn windows_line_endings() {
        let text = "DEBUT()\r\nA = F(X=1,\r\n  Y=2)\r\nFIN()\r\n";
        let p = ok(text);
        assert_eq!(p.stmts.len(), 3);
        let s = p.stmts[2].span;
        assert_eq!(&text[s.start..s.end], "FIN()");
    }

    #[test]
    fn spans_point_at_the_right_bytes() {
        let text = "DEBUT()\nMA = DEFI_GROUP(reuse=MA, CREA=(_F(NOM='A'),),)\nX = -(1 + 2)*3\n";
        let p = ok(text);
        let at = |s: Span| &text[s.start..s.end];
        assert_eq!(at(p.stmts[0].span), "DEBUT()");
        let StmtKind::Assign { target, value } = &p.stmts[1].kind else {
            panic!()
        };
        assert_eq!(at(target.span), "MA");
        assert_eq!(at(value.span), "DEFI_GROUP(reuse=MA, CREA=(_F(NOM='A'),),)");
        let ExprKind::Call { func, args } = &value.kind else {
            panic!()
        };
        assert_eq!(at(func.span), "DEFI_GROUP");
        assert_eq!(at(args[0].span), "reuse=MA");
        assert_eq!(at(args[0].name.as_ref().unwrap().span), "reuse");
        assert_eq!(at(args[0].value.span), "MA");
        assert_eq!(at(args[1].value.span), "(_F(NOM='A'),)");
        let ExprKind::Tuple(items) = &args[1].value.kind else {
            panic!()
        };
        assert_eq!(at(items[0].span), "_F(NOM='A')");
        let StmtKind::Assign { value, .. } = &p.stmts[2].kind else {
            panic!()
        };
        assert_eq!(at(value.span), "-(1 + 2)*3");
        let ExprKind::Binary { lhs, .. } = &value.kind else {
            panic!()
        };
        assert_eq!(at(lhs.span), "-(1 + 2)");
        let ExprKind::Unary { operand, .. } = &lhs.kind else {
            panic!()
        };
        assert_eq!(at(operand.span), "(1 + 2)");
    }

    #[test]
    fn syntax_error_messages() {
        let cases = [
            (
                "F(A=1 B=2)\n",
                "syntax error: expected ',' or ')', found 'B'",
            ),
            (
                "F(A=)\n",
                "syntax error: expected a value (number, string, name, tuple or call), found ')'",
            ),
            ("F(A=1\n", "syntax error: '(' was never closed"),
            (
                "A = (1, 2]\n",
                "syntax error: ']' does not match the '(' opened at line 1, column 5",
            ),
            ("A = 1 @ 2\n", "syntax error: unexpected character '@'"),
            ("A = 1}\n", "syntax error: unmatched '}'"),
            (
                "def f(x):\n    pass\n",
                "syntax error: 'def' is Python syntax that command files do not support",
            ),
            (
                "while N < 3:\n    N = N + 1\n",
                "syntax error: 'while' is Python syntax that command files do not support",
            ),
            (
                "A = if\n",
                "syntax error: expected a value (number, string, name, tuple or call), found 'if'",
            ),
            (
                "for = 3\n",
                "syntax error: 'for' is a reserved word of Python and cannot be used as a name",
            ),
            ("A = 1 \\ 2\n", "syntax error: unexpected '\\'"),
        ];
        for (text, msg) in cases {
            assert_eq!(err(text).message, msg, "{text:?}");
        }
    }

    #[test]
    fn hints_for_python_that_is_not_supported() {
        let cases = [
            ("L[0] += 1\n", "augmented assignment"),
            ("D['A'] %= 1\n", "augmented assignment"),
            ("A = r'x'\n", "string prefixes"),
            ("A = f(x)(y)\n", "only a name can be called"),
            ("A = 1 & 2\n", "bitwise"),
            ("F(MAILLAGE MA)\n", "KEYWORD=value"),
        ];
        for (text, note) in cases {
            let d = err(text);
            assert!(
                d.notes.iter().any(|n| n.contains(note)),
                "{text:?}: {} {:?}",
                d.message,
                d.notes
            );
        }
        assert_eq!(
            err("A = 1;;\n").message,
            "syntax error: expected a statement (NAME = value or a command call), found ';'"
        );
    }

    #[test]
    fn unclosed_brackets() {
        // The next statement, in the first column, shows the '(' is open.
        let d = err("A = F(X=1,\n  Y=2\nFIN()\n");
        assert_eq!(d.message, "syntax error: '(' was never closed");
        assert_eq!(d.span, Some(Span::new(5, 6)));
        assert!(
            d.notes.iter().any(|n| n.contains("line 3")),
            "{:?}",
            d.notes
        );
        // An indented line is read as a continuation: a ',' is missing.
        let d = err("A = F(X=1,\n  Y=2\n  Z=3)\n");
        assert_eq!(d.message, "syntax error: expected ',' or ')', found 'Z'");
        let d = err("FIN())\n");
        assert_eq!(d.message, "syntax error: unmatched ')'");
        let d = err("A = [1, 2)\n");
        assert_eq!(
            d.message,
            "syntax error: ')' does not match the '[' opened at line 1, column 5"
        );
    }

    #[test]
    fn depth_limits_are_errors_not_crashes() {
        let deep = format!("A = {}1{}\n", "(".repeat(33), ")".repeat(33));
        let d = err(&deep);
        assert!(d.message.contains("nested more than 32"), "{}", d.message);
        assert_eq!(d.span, Some(Span::new(36, 37)));
        let deep = format!("A = {}\n", "[".repeat(100_000));
        assert!(err(&deep).message.contains("nested more than 32"));
        let ok_depth = format!("A = {}1{}\n", "(".repeat(32), ")".repeat(32));
        ok(&ok_depth);
        let long = format!("A = 1{}\n", "+1".repeat(10_000));
        assert!(err(&long).message.contains("too deeply nested"));
        let signs = format!("A = {}1\n", "-".repeat(10_000));
        assert!(err(&signs).message.contains("too deeply nested"));
        let pow = format!("A = 2{}\n", "**2".repeat(10_000));
        assert!(err(&pow).message.contains("too deeply nested"));
    }
    #[test]
    fn python_expressions_and_precedence() {
        assert_eq!(sv("L[0]"), "(index L 0)");
        assert_eq!(sv("L[-1]"), "(index L (neg 1))");
        assert_eq!(sv("L[1:3]"), "(slice L 1 3 _)");
        assert_eq!(sv("L[::-1]"), "(slice L _ _ (neg 1))");
        assert_eq!(sv("L[1:]"), "(slice L 1 _ _)");
        assert_eq!(sv("L[0][1]"), "(index (index L 0) 1)");
        assert_eq!(sv("-L[0]**2"), "(neg (** (index L 0) 2))");
        assert_eq!(sv("'G_%d' % i"), "(% \"G_%d\" i)");
        assert_eq!(sv("a % b * c"), "(* (% a b) c)");
        assert_eq!(sv("a + b // c"), "(+ a (// b c))");
        assert_eq!(sv("a + 1 < b * 2"), "(cmp (+ a 1) < (* b 2))");
        assert_eq!(sv("0 < x <= 1"), "(cmp 0 < x <= 1)");
        assert_eq!(sv("x not in L"), "(cmp x not in L)");
        assert_eq!(sv("not a == b"), "(not (cmp a == b))");
        assert_eq!(sv("a or b and not c"), "(or a (and b (not c)))");
        assert_eq!(sv("a and b or c"), "(or (and a b) c)");
        assert_eq!(sv("1 if c else 2"), "(ifelse c 1 2)");
        assert_eq!(
            sv("1 if a else 2 if b else 3"),
            "(ifelse a 1 (ifelse b 2 3))"
        );
        assert_eq!(sv("x or y if c else z"), "(ifelse c (or x y) z)");
        assert_eq!(sv("True"), "True");
        assert_eq!(
            sv("[x*2 for x in L if x > 0]"),
            "(listcomp (* x 2) (for x L (if (cmp x > 0))))"
        );
        assert_eq!(
            sv("[(i, j) for i in range(2) for j in L]"),
            "(listcomp (tuple i j) (for i (range 2)) (for j L))"
        );
        assert_eq!(sv("[a for a, b in P]"), "(listcomp a (for (a,b) P))");
        assert_eq!(sv("math.sqrt(2.)"), "(.sqrt math 2.0)");
        assert_eq!(sv("math.pi*2"), "(* (. math pi) 2)");
        assert_eq!(sv("np.pi"), "(. np pi)");
        let d = err("A = L[]\n");
        assert_eq!(
            d.message,
            "syntax error: expected an index or a slice between '[' and ']'"
        );
        let d = err("A = 1 if c\n");
        assert!(d.message.contains("'else'"), "{}", d.message);
    }

    #[test]
    fn imports_and_simple_statements() {
        let p = ok("import math\nimport numpy as np, math as m\nfrom math import *\nfrom math import sqrt, pi as PI\nfrom code_aster.Commands import *\npass\na, b = 1, 2\n");
        assert_eq!(
            st(&p.stmts),
            "import math; import numpy as np,math as m; from math *; from math sqrt,pi; from code_aster.Commands *; pass; a,b=(tuple 1 2)"
        );
        let p = ok("L = []\nL.append(_F(A=1))\n");
        assert_eq!(st(&p.stmts), "L=(list ); (.append L (_F A=1))");
    }

    #[test]
    fn blocks_follow_indentation() {
        let p = ok("for i in range(3):\n    A = i\n    if i == 1:\n        B = i\n    elif i > 1: C = i\n    else:\n        pass\nD = 1\n");
        assert_eq!(
            st(&p.stmts),
            "(for i (range 3) [A=i; (if (cmp i == 1) [B=i] (cmp i > 1) [C=i] else [pass])]); D=1"
        );
        // Comments and blank lines do not count; brackets join lines.
        let p = ok("if X:\n\n  # c\n  A = F(B=1,\nC=2)\n  D = 2\nE = 3\n");
        assert_eq!(st(&p.stmts), "(if X [A=(F B=1 C=2); D=2]); E=3");
        // A flat file ignores indentation, as before.
        let p = ok("DEBUT()\n   A = 1\n B = 2\nFIN()\n");
        assert_eq!(p.stmts.len(), 4);
        // Tabs, and a header indented at the top level.
        let p = ok("  for a, b in P:\n  \tX = a\n  \tY = b\n  Z = 1\n");
        assert_eq!(st(&p.stmts), "(for (a,b) P [X=a; Y=b]); Z=1");
        // The span of an expanded statement is its own text.
        let text = "for i in L:\n    F(X=i)\n";
        let p = ok(text);
        let StmtKind::For { body, .. } = &p.stmts[0].kind else {
            panic!()
        };
        assert_eq!(&text[body[0].span.start..body[0].span.end], "F(X=i)");
        assert_eq!(
            &text[p.stmts[0].span.start..p.stmts[0].span.end],
            "for i in L:\n    F(X=i)"
        );
    }

    #[test]
    fn block_errors_are_located() {
        let cases: &[(&str, &str, &str)] = &[
            (
                "for i in L:\nA = 1\n",
                "expected an indented block after 'for' statement on line 1",
                "A",
            ),
            (
                "if X:\n",
                "expected an indented block after 'if' statement on line 1",
                "",
            ),
            ("if X:\n    A = 1\n      B = 2\n", "unexpected indent", "B"),
            (
                "if X:\n    A = 1\n  B = 2\n",
                "unindent does not match any outer indentation level",
                "B",
            ),
            (
                "for i in L:\n    if i:\n        A = 1\n      B = 2\n",
                "unindent does not match any outer indentation level",
                "B",
            ),
            (
                "if X:\n    A = 1\n\tB = 2\n",
                "inconsistent use of tabs and spaces in indentation",
                "B",
            ),
            (
                "else:\n    A = 1\n",
                "'else' does not follow an 'if' block at the same indentation",
                "e",
            ),
            (
                "for i in L:\n    A = 1\n    else:\n        B = 2\n",
                "'else' does not follow an 'if' block at the same indentation",
                "e",
            ),
            ("if X\n    A = 1\n", "expected ':'", ""),
            ("for i L:\n    A = 1\n", "'in'", "L"),
        ];
        for (text, msg, at) in cases {
            let d = err(text);
            assert!(d.message.contains(msg), "{text:?}: {}", d.message);
            let s = d.span.unwrap();
            assert!(text[s.start..].starts_with(at), "{text:?}: at {s:?}");
        }
        let deep: String = (0..21)
            .map(|k| format!("{}if X:\n", " ".repeat(k)))
            .collect::<String>()
            + &" ".repeat(21)
            + "pass\n";
        assert!(err(&deep).message.contains("blocks nested more than 20"));
        let ok_deep: String = (0..20)
            .map(|k| format!("{}if X:\n", " ".repeat(k)))
            .collect::<String>()
            + &" ".repeat(20)
            + "pass\n";
        ok(&ok_deep);
    }
}
