//! The Markdown reference of the command catalogue, generated from the
//! declarations so that the documentation cannot drift from what the
//! checker accepts (`docs/commands.md`; `tests/catalog_doc.rs` fails when
//! the committed file is stale).

use std::fmt::Write as _;

use super::schema::*;

/// The whole catalogue as Markdown, commands in registry order (the
/// registry is `commands::all()`, handed down by the caller).
pub fn commands_markdown<D: AsRef<CommandSpec>>(registry: &[D]) -> String {
    let defs: Vec<&CommandSpec> = registry.iter().map(AsRef::as_ref).collect();
    let mut out = String::new();
    out.push_str("# Command reference\n\n");
    out.push_str(
        "Generated from the catalogue (`src/commands/*.rs`) by \
         `aster::catalog::doc::commands_markdown`; do not edit by hand \
         (regenerate with `UPDATE_DOCS=1 cargo test --test catalog_doc`).\n\n",
    );
    out.push_str(
        "Statuses: *required* (code_aster 'o'), *optional* ('f'), *default* \
         ('d': filled in when absent), *hidden* ('c': accepted, deprecated). \
         A block's keywords exist only while its condition holds on the \
         keywords of its level (after defaults are filled).\n\n",
    );
    for d in &defs {
        let _ = writeln!(out, "- [{}](#{})", d.name, d.name.to_lowercase());
    }
    out.push('\n');
    for d in &defs {
        command_section(&mut out, d);
    }
    out
}

fn command_section(out: &mut String, c: &CommandSpec) {
    let _ = writeln!(out, "## {}\n", c.name);
    if !c.doc.is_empty() {
        let _ = writeln!(out, "{}\n", c.doc);
    }
    let produces = match &c.produces {
        Produces::Nothing => "nothing (procedure)".to_string(),
        Produces::Concept(t) => format!("`{}`", t.aster_name()),
        Produces::SameAs(k, _) => format!("the type of the concept given in `{k}`"),
        Produces::ByText(k, table, default) => format!(
            "{}, else `{}`",
            table
                .iter()
                .map(|(p, t)| format!("`{}` when `{k}` starts with {p}", t.aster_name()))
                .collect::<Vec<_>>()
                .join(", "),
            default.aster_name()
        ),
    };
    let _ = writeln!(out, "- Produces: {produces}");
    let reuse = match &c.reentrant {
        Reentrant::No => "not allowed".to_string(),
        Reentrant::Optional(k) => format!("optional, on the concept given in `{k}`"),
        Reentrant::Required(k) => format!("compulsory, on the concept given in `{k}`"),
    };
    let _ = writeln!(out, "- Reuse (`reuse=`): {reuse}");
    for r in &c.rules {
        let _ = writeln!(out, "- Rule: {}", rule_text(r));
    }
    out.push_str("\nKeywords:\n\n");
    keyword_list(out, &c.keywords, 0);
    out.push('\n');
}

fn keyword_list(out: &mut String, kws: &[Keyword], depth: usize) {
    let pad = "  ".repeat(depth);
    for k in kws {
        match k {
            Keyword::Simple(s) => {
                let _ = writeln!(out, "{pad}- {}", simple_line(s));
            }
            Keyword::Factor(f) => {
                let _ = writeln!(out, "{pad}- {}", factor_line(f));
                for r in &f.rules {
                    let _ = writeln!(out, "{pad}  - Rule: {}", rule_text(r));
                }
                keyword_list(out, &f.keywords, depth + 1);
            }
            Keyword::Block(b) => {
                let _ = writeln!(
                    out,
                    "{pad}- Block `{}`, when {}:",
                    b.name,
                    cond_text(&b.condition)
                );
                for r in &b.rules {
                    let _ = writeln!(out, "{pad}  - Rule: {}", rule_text(r));
                }
                keyword_list(out, &b.keywords, depth + 1);
            }
        }
    }
}

fn status_text(s: &Status) -> &'static str {
    match s {
        Status::Required => "**required**",
        Status::Optional => "optional",
        Status::Defaulted => "default",
        Status::Hidden => "hidden (deprecated)",
    }
}

fn simple_line(s: &Simple) -> String {
    let mut parts = vec![ty_text(&s.ty)];
    if s.default.is_empty() {
        parts.push(status_text(&s.status).to_string());
    } else {
        let d: Vec<String> = s.default.iter().map(lit_text).collect();
        parts.push(format!("default {}", d.join(", ")));
    }
    if let Some(into) = &s.into {
        let v: Vec<String> = into.iter().map(lit_text).collect();
        parts.push(format!("one of {}", v.join(", ")));
    }
    if s.not_built_at_all() {
        parts.push(format!("not implemented yet ({})", s.not_built_why));
    } else if !s.not_built.is_empty() {
        let v: Vec<String> = s.not_built.iter().map(|x| format!("'{x}'")).collect();
        parts.push(format!(
            "not implemented yet: {} ({})",
            v.join(", "),
            s.not_built_why
        ));
    }
    let bound = |v: f64| match s.ty {
        Ty::Int => format!("{}", v as i64),
        _ => num(v),
    };
    match (s.val_min, s.val_max) {
        (Some(a), Some(b)) => parts.push(format!("in [{}, {}]", bound(a), bound(b))),
        (Some(a), None) => parts.push(format!(">= {}", bound(a))),
        (None, Some(b)) => parts.push(format!("<= {}", bound(b))),
        (None, None) => {}
    }
    if let Some(c) = count_text(s.min, s.max) {
        parts.push(c);
    }
    let mut line = format!("`{}`: {}", s.name, parts.join("; "));
    if !s.doc.is_empty() {
        let _ = write!(line, " — {}", s.doc);
    }
    line
}

fn factor_line(f: &Factor) -> String {
    let occ = match f.max {
        None => "any number of occurrences".to_string(),
        Some(1) => "one occurrence".to_string(),
        Some(n) => format!("up to {n} occurrences"),
    };
    let status = match f.status {
        Status::Defaulted => "default (one occurrence of defaults when absent)",
        ref s => status_text(s),
    };
    let mut line = format!("`{}`: factor keyword, {}; {}", f.name, status, occ);
    if !f.doc.is_empty() {
        let _ = write!(line, " — {}", f.doc);
    }
    line
}

fn count_text(min: usize, max: Option<usize>) -> Option<String> {
    match (min, max) {
        (1, Some(1)) => None,
        (1, None) => Some("one or more values".into()),
        (a, None) => Some(format!("at least {a} values")),
        (a, Some(b)) if a == b => Some(format!("exactly {a} values")),
        (a, Some(b)) => Some(format!("{a} to {b} values")),
    }
}

fn ty_text(t: &Ty) -> String {
    match t {
        Ty::Real => "real".into(),
        Ty::Int => "integer".into(),
        Ty::Text => "text".into(),
        Ty::Concept(tys) => {
            let n: Vec<String> = tys
                .iter()
                .map(|t| format!("`{}`", t.aster_name()))
                .collect();
            format!("concept {}", n.join(" or "))
        }
    }
}

/// Reals printed so that `1e-6` and `0.25` read as in a command file.
fn num(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-3..1e5).contains(&a) {
        format!("{v:e}")
    } else {
        format!("{v:?}")
    }
}

fn lit_text(l: &Lit) -> String {
    match l {
        Lit::Int(i) => i.to_string(),
        Lit::Real(r) => num(*r),
        Lit::Text(t) => format!("'{}'", t.escape_default()),
    }
}

fn names(ks: &[&str]) -> String {
    let v: Vec<String> = ks.iter().map(|k| format!("`{k}`")).collect();
    v.join(", ")
}

fn rule_text(r: &Rule) -> String {
    match r {
        Rule::ExactlyOne(k) => format!("exactly one of {}", names(k)),
        Rule::AtLeastOne(k) => format!("at least one of {}", names(k)),
        Rule::Exclusive(k) => format!("at most one of {}", names(k)),
        Rule::Together(k) => format!("all or none of {}", names(k)),
        Rule::IfPresentAllPresent(a, k) => format!("if `{a}` is given, so must be {}", names(k)),
        Rule::IfPresentAllAbsent(a, k) => {
            format!("if `{a}` is given, none of {} may be", names(k))
        }
    }
}

/// A condition in words; sub-conditions of `and`/`or` are parenthesised
/// when compound so that precedence is explicit.
pub fn cond_text(c: &Cond) -> String {
    let inner = |c: &Cond| match c {
        Cond::And(v) | Cond::Or(v) if v.len() > 1 => format!("({})", cond_text(c)),
        _ => cond_text(c),
    };
    match c {
        Cond::Eq(k, v) => format!("`{k}` = {}", lit_text(v)),
        Cond::In(k, vs) => {
            let v: Vec<String> = vs.iter().map(lit_text).collect();
            format!("`{k}` in ({})", v.join(", "))
        }
        Cond::Present(k) => format!("`{k}` is given"),
        Cond::Absent(k) => format!("`{k}` is absent"),
        Cond::And(v) if v.is_empty() => "always".into(),
        Cond::And(v) => v.iter().map(inner).collect::<Vec<_>>().join(" and "),
        Cond::Or(v) => v.iter().map(inner).collect::<Vec<_>>().join(" or "),
        Cond::Not(c) => match c.as_ref() {
            Cond::Eq(k, v) => format!("`{k}` != {}", lit_text(v)),
            Cond::In(k, vs) => {
                let v: Vec<String> = vs.iter().map(lit_text).collect();
                format!("`{k}` not in ({})", v.join(", "))
            }
            other => format!("not ({})", cond_text(other)),
        },
    }
}
