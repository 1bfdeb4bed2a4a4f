//! The generic checker: walks a whole command file against the catalogue
//! and reports every error it finds before anything executes.
//!
//! It follows code_aster's supervisor (`SyntaxChecker.py`): per command,
//! defaults are added, `None` values removed, then counts, types, `into`
//! lists, bounds, mandatory keywords, unknown keywords, conditional blocks
//! and rules are checked. Unlike code_aster, which checks a command just
//! before running it, aster checks the whole file first, so that a typo
//! near the end is reported before an hour of computation. Concept types
//! flow from command to command, so a name bound to the wrong kind of
//! result is caught too.

use crate::catalog::args::{Args, Entry, EntryData, Value};
use crate::catalog::concept_type::ConceptType;
use crate::catalog::eval::builtins;
use crate::catalog::eval::{
    find_stale, for_keyword, holds_list, make_stale, unpack, unpack_target, Binding, Env, PyVal,
    SpVal,
};
use crate::catalog::schema::{
    CommandSpec, Cond, Factor, Keyword, Lit, Produces, Reentrant, Rule, Simple, Status, Ty,
};
use crate::diag::{closest, Diagnostic, Span};
use crate::lang::ast::{CmpOp, ExprKind, Ident, Program, Stmt, StmtKind};

/// A module that command files cannot import.
fn unknown_module(module: &Ident) -> Diagnostic {
    Diagnostic::error(format!(
        "module '{}' is not available in command files",
        module.name
    ))
    .at(module.span)
    .note("the modules are math, numpy (a few scalar functions: np.sqrt, np.pi...) and code_aster.Commands")
}

/// One command ready to run.
#[derive(Debug, Clone)]
pub struct CheckedCommand {
    /// Index of the command in the registry given to [`check_program`].
    pub def: usize,
    pub name: String,
    /// The name the result is bound to (`MAIL = LIRE_MAILLAGE(...)`).
    pub result: Option<Ident>,
    /// `reuse=NAME`: the concept modified in place.
    pub reuse: Option<String>,
    pub produces: Option<ConceptType>,
    pub args: Args,
    /// Span of the whole statement.
    pub span: Span,
}

/// A checked file: the commands in order, and the warnings found.
#[derive(Debug, Clone, Default)]
pub struct CheckedProgram {
    pub commands: Vec<CheckedCommand>,
    pub warnings: Vec<Diagnostic>,
    /// What the file's `print(...)` calls write to the .mess, each with the
    /// index of the command it comes before (`commands.len()`: after the
    /// last one). Their text is known now: print() of a value known only
    /// when the study runs is refused.
    pub prints: Vec<(usize, String)>,
}

/// Checks a whole program. On failure, returns every error found (and the
/// warnings, after them).
///
/// The Python around the commands is evaluated here, before anything runs:
/// plain statements, imports, and the `if`/`for` blocks, whose conditions
/// and iterables are values known now (numbers, texts, lists, tuples,
/// ranges). A block's commands are checked where the evaluation reaches
/// them, once per iteration, so the runner receives the flat list of
/// commands the file stands for, each with the span of its own text.
pub fn check_program<D: AsRef<CommandSpec>>(
    program: &Program,
    registry: &[D],
) -> Result<CheckedProgram, Vec<Diagnostic>> {
    let registry: Vec<&CommandSpec> = registry.iter().map(AsRef::as_ref).collect();
    let names: Vec<&str> = registry.iter().map(|d| d.name).collect();
    let program = &super::inline_commands::hoist(program, &is_cmd(&names));
    let mut ck = Checker {
        registry: &registry,
        names: &names,
        env: Env::default(),
        errors: Vec::new(),
        warnings: Vec::new(),
        out: Vec::new(),
        seen_debut: false,
        fin_at: None,
        iterating: Vec::new(),
        cmd_keywords: &[],
        captured: Vec::new(),
        current: Span::default(),
        prints: Vec::new(),
    };
    ck.stmts(&program.stmts);
    if !ck.seen_debut {
        ck.errors.push(
            Diagnostic::error("the study has no DEBUT(): a command file must begin with DEBUT()")
                .at(Span::new(0, 0)),
        );
    }
    if ck.fin_at.is_none() && ck.seen_debut {
        // Located where FIN() would go: after the last statement.
        let end = program.stmts.last().map_or(0, |s| s.span.end);
        ck.warnings.push(
            Diagnostic::warning("the study has no FIN(): it is closed at the end of the file")
                .at(Span::new(end, end)),
        );
    }
    for (_, _, _, pending) in std::mem::take(&mut ck.captured) {
        ck.warnings.extend(pending);
    }
    // A mistake inside a loop is found at every iteration: say it once.
    let dedup = |v: Vec<Diagnostic>| {
        let mut seen = std::collections::HashSet::new();
        v.into_iter()
            .filter(|d| seen.insert((d.message.clone(), d.span.map(|s| (s.start, s.end)))))
            .collect::<Vec<_>>()
    };
    let warnings = dedup(ck.warnings);
    if ck.errors.is_empty() {
        Ok(CheckedProgram {
            commands: ck.out,
            warnings,
            prints: ck.prints,
        })
    } else {
        let mut all = dedup(ck.errors);
        all.extend(warnings);
        Err(all)
    }
}

struct Checker<'a> {
    registry: &'a [&'a CommandSpec],
    /// The names of the commands of the registry.
    names: &'a [&'a str],
    env: Env,
    errors: Vec<Diagnostic>,
    warnings: Vec<Diagnostic>,
    /// The commands to run, in order, loops unrolled.
    out: Vec<CheckedCommand>,
    seen_debut: bool,
    fin_at: Option<Span>,
    /// The identities of the lists the enclosing `for`s go through.
    iterating: Vec<u64>,
    /// The keywords of the command being checked, for the hint on a
    /// keyword of another variant of a factor keyword.
    cmd_keywords: &'a [Keyword],
    /// The command-file variables FORMULEs read without a keyword: (the
    /// variable, the value the formula keeps, the formula's name), and
    /// the warning of a later rebinding, given at the end unless the
    /// formula is defined again first (a FORMULE in a loop over the
    /// variable).
    captured: Vec<(String, PyVal, String, Option<Diagnostic>)>,
    /// The statement being checked (where a rebinding is reported).
    current: Span,
    /// See [`CheckedProgram::prints`].
    prints: Vec<(usize, String)>,
}

/// The values present at one level, for conditions and rules.
type Present<'v> = Vec<(&'v str, Option<&'v PyVal>)>;

fn is_cmd<'n>(names: &'n [&'n str]) -> impl Fn(&str) -> bool + 'n {
    move |n| names.contains(&n)
}

impl Checker<'_> {
    fn stmts(&mut self, stmts: &[Stmt]) {
        for s in stmts {
            self.stmt(s);
        }
    }

    fn bind(&mut self, name: &str, v: PyVal) {
        self.rebinding_captured(name, &v);
        if v == PyVal::None {
            self.env.names.shift_remove(name);
        }
        self.env.names.insert(name.to_string(), Binding::Var(v));
    }

    /// A FORMULE that reads a command-file variable keeps the value it had
    /// then; older code_aster read the variable when the formula was
    /// evaluated, and 14+ gives VALE only FORMULE's keywords. A later
    /// rebinding makes the versions disagree.
    fn rebinding_captured(&mut self, name: &str, v: &PyVal) {
        let current = self.current;
        for (var, kept, formula, pending) in self.captured.iter_mut() {
            if var != name || pending.is_some() || kept == v {
                continue;
            }
            *pending = Some(
                Diagnostic::warning(format!(
                    "{name} is bound again after the FORMULE {formula} read it: {formula} keeps {}",
                    kept.describe()
                ))
                .at(current)
                .note(format!(
                    "code_aster up to 13 reads {name} when {formula} is evaluated (the new value), 14 and later give VALE only FORMULE's keywords: write {name}={name} in FORMULE to pass the value explicitly"
                )),
            );
        }
    }

    fn stmt(&mut self, stmt: &Stmt) {
        self.current = stmt.span;
        if let Some(fin) = self.fin_at {
            self.warnings.push(
                Diagnostic::warning("statement after FIN() is ignored, as code_aster does")
                    .at(stmt.span)
                    .note(format!("FIN() is at byte {}", fin.start)),
            );
            return;
        }
        match &stmt.kind {
            StmtKind::Assign { target, value } => self.statement(Some(target), value, stmt.span),
            StmtKind::Expr(e) => match &e.kind {
                ExprKind::MethodCall {
                    value,
                    method,
                    args,
                } if method.name == "append" && matches!(value.kind, ExprKind::Name(_)) => {
                    if let Err(d) = self.append(value, args, e.span) {
                        self.errors.push(d);
                    }
                }
                _ => self.statement(None, e, stmt.span),
            },
            StmtKind::Unpack { targets, value } => {
                let r = self
                    .env
                    .eval(value, &is_cmd(self.names))
                    .and_then(|v| unpack(v, targets.len()));
                match r {
                    Ok(vals) => {
                        for (t, v) in targets.iter().zip(vals) {
                            self.bind(&t.name, v.v);
                        }
                    }
                    Err(d) => {
                        self.errors.push(d);
                        for t in targets {
                            self.bind(&t.name, PyVal::Poison);
                        }
                    }
                }
            }
            StmtKind::SetItem {
                target,
                index,
                value,
            } => {
                if let Err(d) = self.set_item(target, index, value) {
                    self.errors.push(d);
                }
            }
            StmtKind::AugAssign { target, op, value } => {
                if let Err(d) = self.aug_assign(target, *op, value, stmt.span) {
                    self.errors.push(d);
                }
            }
            StmtKind::Pass => {}
            StmtKind::Import(items) => {
                for it in items {
                    match builtins::module(&it.module.name) {
                        Some(m) => {
                            let name = it.alias.as_ref().unwrap_or(&it.module);
                            self.bind(&name.name, PyVal::Module(m));
                        }
                        None => self.errors.push(unknown_module(&it.module)),
                    }
                }
            }
            StmtKind::FromImport { module, names } => self.import_names(module, names.as_deref()),
            StmtKind::If { branches, orelse } => {
                for (cond, body) in branches {
                    let c = match self.env.eval(cond, &is_cmd(self.names)) {
                        Ok(c) => c,
                        Err(d) => return self.errors.push(d),
                    };
                    if c.v == PyVal::Poison {
                        return;
                    }
                    match self.env.truth(&c) {
                        Ok(true) => return self.stmts(body),
                        Ok(false) => {}
                        Err(d) => return self.errors.push(d.at_if_none(cond.span)),
                    }
                }
                self.stmts(orelse);
            }
            StmtKind::For { target, iter, body } => {
                let v = match self.env.eval(iter, &is_cmd(self.names)) {
                    Ok(v) => v,
                    Err(d) => return self.errors.push(d),
                };
                if v.v == PyVal::Poison {
                    return;
                }
                let items = match self.env.iterate(&v) {
                    Ok(items) => items,
                    Err(d) => return self.errors.push(d),
                };
                let id = match v.v {
                    PyVal::List(id, _) => Some(id),
                    _ => None,
                };
                self.iterating.extend(id);
                for item in items {
                    // The loop variable is bound by the `for` itself.
                    self.current = stmt.span;
                    if let Err(d) = self.env.step(iter.span) {
                        self.errors.push(d);
                        break;
                    }
                    match unpack_target(target, item) {
                        Ok(binds) => {
                            for (n, v) in binds {
                                self.bind(&n, v);
                            }
                        }
                        Err(d) => {
                            self.errors.push(d);
                            break;
                        }
                    }
                    self.stmts(body);
                    if self.fin_at.is_some() {
                        break;
                    }
                }
                if id.is_some() {
                    self.iterating.pop();
                }
            }
        }
    }

    /// `L.append(x)` on a list variable. aster's values are copies, so the
    /// cases where Python's shared list would make a difference are refused.
    fn append(
        &mut self,
        value: &crate::lang::ast::Expr,
        args: &[crate::lang::ast::Arg],
        span: Span,
    ) -> Result<(), Diagnostic> {
        let ExprKind::Name(name) = &value.kind else {
            unreachable!("append on a name")
        };
        // The list's identity, read in place: evaluating the name would
        // copy the whole list at every append, quadratic in a loop (a
        // fuzzed study with range(1000000) ran for an hour).
        let id = match self.env.names.get(name.as_str()) {
            Some(Binding::Var(PyVal::List(id, _))) => *id,
            _ => {
                let list = self.env.eval(value, &is_cmd(self.names))?;
                match list.v {
                    PyVal::List(id, _) => id,
                    PyVal::Poison => return Ok(()),
                    v => {
                        return Err(Diagnostic::error(format!(
                            "append needs a list, and {name} is {}",
                            v.describe()
                        ))
                        .at(value.span))
                    }
                }
            }
        };
        let [arg] = args else {
            return Err(Diagnostic::error(format!(
                "append takes exactly one argument ({} given)",
                args.len()
            ))
            .at(span));
        };
        if arg.name.is_some() {
            return Err(Diagnostic::error("append takes no keyword argument").at(arg.span));
        }
        let x = self.env.eval(&arg.value, &is_cmd(self.names))?;
        if let Some(other) = self.other_holder(name, id) {
            return Err(Diagnostic::error(format!(
                "{name} is the same list as {other}: Python's append would change both, aster's values are copies"
            ))
            .at(value.span)
            .note(format!("build {other} after the appends, or copy the list with list({name})")));
        }
        if holds_list(&x.v, id) || self.iterating.contains(&id) {
            return Err(Diagnostic::error(format!(
                "appending to {name} while it is being looped over, or to itself, is not supported"
            ))
            .at(span));
        }
        if let Some(Binding::Var(PyVal::List(_, items))) = self.env.names.get_mut(name.as_str()) {
            if items.len() >= crate::catalog::eval::MAX_ITEMS {
                return Err(Diagnostic::error(format!(
                    "the list {name} would have more than {} items",
                    crate::catalog::eval::MAX_ITEMS
                ))
                .at(span));
            }
            items.push(x);
        }
        Ok(())
    }

    /// `A op= x`. On a list, Python's `+=` extends the list in place (by
    /// any iterable) and `*=` repeats it in place, so another name holding
    /// the same list would change too: refused, as for append, since
    /// aster's values are copies. Everything else is `A = A op x`.
    fn aug_assign(
        &mut self,
        target: &Ident,
        op: crate::lang::ast::BinOp,
        value: &crate::lang::ast::Expr,
        span: Span,
    ) -> Result<(), Diagnostic> {
        use crate::lang::ast::{BinOp, Expr};
        let name = target.name.as_str();
        if let Some(Binding::Var(PyVal::List(id, _))) = self.env.names.get(name) {
            let id = *id;
            if matches!(op, BinOp::Add | BinOp::Mul) {
                if let Some(other) = self.other_holder(name, id) {
                    return Err(Diagnostic::error(format!(
                        "{name} is the same list as {other}: Python's {}= would change both, aster's values are copies",
                        op.symbol()
                    ))
                    .at(target.span)
                    .note(format!("build {other} after this, or copy the list first: {name} = list({name})")));
                }
                if self.iterating.contains(&id) {
                    return Err(Diagnostic::error(format!(
                        "changing {name} with {}= while it is being looped over is not supported",
                        op.symbol()
                    ))
                    .at(span));
                }
            }
            if op == BinOp::Add {
                let x = self.env.eval(value, &is_cmd(self.names))?;
                if x.v == PyVal::Poison {
                    self.bind(name, PyVal::Poison);
                    return Ok(());
                }
                let more = self.env.iterate(&x)?;
                if let Some(Binding::Var(PyVal::List(_, items))) = self.env.names.get_mut(name) {
                    if items.len() + more.len() > crate::catalog::eval::MAX_ITEMS {
                        return Err(Diagnostic::error(format!(
                            "the list {name} would have more than {} items",
                            crate::catalog::eval::MAX_ITEMS
                        ))
                        .at(span));
                    }
                    items.extend(more);
                }
                return Ok(());
            }
        }
        let expr = Expr {
            kind: ExprKind::Binary {
                op,
                lhs: Box::new(Expr {
                    kind: ExprKind::Name(name.to_string()),
                    span: target.span,
                }),
                rhs: Box::new(value.clone()),
            },
            span: target.span.to(value.span),
        };
        self.statement(Some(target), &expr, span);
        Ok(())
    }

    /// `L[i] = x` and `d['KEY'] = x` on a list or a dict held in a name.
    /// As for append, aster's values are copies: the cases where Python's
    /// shared object would make a difference are refused.
    /// Another name whose value holds the list or dict `id` (Python's
    /// in-place change would reach it too; aster's values are copies).
    fn other_holder(&self, name: &str, id: u64) -> Option<String> {
        self.env
            .names
            .iter()
            .find(|(n, b)| *n != name && matches!(b, Binding::Var(v) if holds_list(v, id)))
            .map(|(n, _)| n.clone())
    }

    fn set_item(
        &mut self,
        target: &Ident,
        index: &crate::lang::ast::Expr,
        value: &crate::lang::ast::Expr,
    ) -> Result<(), Diagnostic> {
        let name = target.name.as_str();
        if let ExprKind::Call { func, .. } = &value.kind {
            if self.names.contains(&func.name.as_str()) {
                return Err(Diagnostic::error(format!(
                    "the result of {} cannot be stored in an item of {name}: aster knows concepts by their names",
                    func.name
                ))
                .at(value.span)
                .in_command(func.name.clone())
                .note("name the result (RESU_1 = COMMAND(...)), one name per result, and use the names"));
            }
        }
        let x = self.env.eval(value, &is_cmd(self.names))?;
        let id = match self.env.names.get(name) {
            Some(Binding::Var(PyVal::List(id, _) | PyVal::Fact(id, _))) => *id,
            Some(Binding::Var(PyVal::Poison)) => return Ok(()),
            Some(Binding::Var(v)) => {
                return Err(Diagnostic::error(format!(
                "{name} is {}, which does not support item assignment (only a list or a dict does)",
                v.describe()
            ))
                .at(target.span))
            }
            Some(Binding::Concept { .. }) => {
                return Err(crate::catalog::eval::concept_unknown(
                    name,
                    "item assignment changes",
                    target.span,
                ))
            }
            None => {
                // The message of an undefined name.
                self.env.eval(
                    &crate::lang::ast::Expr {
                        kind: ExprKind::Name(name.to_string()),
                        span: target.span,
                    },
                    &is_cmd(self.names),
                )?;
                return Ok(());
            }
        };
        let i = self.env.eval(index, &is_cmd(self.names))?;
        if i.v == PyVal::Poison {
            return Ok(());
        }
        if let Some(other) = self.other_holder(name, id) {
            return Err(Diagnostic::error(format!(
                "{name} is the same object as {other}: Python's item assignment would change both, aster's values are copies"
            ))
            .at(target.span)
            .note(format!("build {other} after the assignments, or copy first: {name} = list({name}) or dict({name})")));
        }
        if holds_list(&x.v, id) || self.iterating.contains(&id) {
            return Err(Diagnostic::error(format!(
                "assigning an item of {name} while it is being looped over, or {name} into itself, is not supported"
            ))
            .at(target.span.to(value.span)));
        }
        let Some(Binding::Var(slot)) = self.env.names.get_mut(name) else {
            unreachable!("checked above")
        };
        match slot {
            PyVal::List(_, items) => {
                let n = items.len();
                let k = match i.v {
                    PyVal::Int(k) => k,
                    PyVal::Bool(b) => b as i64,
                    ref v => {
                        return Err(Diagnostic::error(format!(
                            "list indices must be integers, not {}",
                            v.describe()
                        ))
                        .at(i.span))
                    }
                };
                let at = if k < 0 {
                    k as i128 + n as i128
                } else {
                    k as i128
                };
                if !(0..n as i128).contains(&at) {
                    return Err(Diagnostic::error(format!(
                        "list assignment index {k} out of range: {name} has {n} item{}",
                        if n == 1 { "" } else { "s" }
                    ))
                    .at(i.span)
                    .note(
                        "an item is added with append; [None] * n makes a list of n items to fill",
                    ));
                }
                items[at as usize] = x;
            }
            PyVal::Fact(_, kv) => {
                let PyVal::Str(key) = i.v else {
                    return Err(crate::catalog::eval::dict_key_error(&i.v, i.span));
                };
                match kv.iter_mut().find(|(k, _)| k.name == key) {
                    Some(slot) => slot.1 = x,
                    None => kv.push((
                        Ident {
                            name: key,
                            span: i.span,
                        },
                        x,
                    )),
                }
            }
            _ => unreachable!("a list or a dict"),
        }
        Ok(())
    }

    /// `print(...)` as a statement: its text is made now (Python's str of
    /// each argument, `sep` between them, `end` after) and written to the
    /// .mess when the study runs, in its place among the commands.
    fn print(&mut self, args: &[crate::lang::ast::Arg], span: Span) -> Result<(), Diagnostic> {
        let mut parts = Vec::new();
        let mut sep = " ".to_string();
        let mut end = "\n".to_string();
        for a in args {
            if a.unpack {
                return Err(Diagnostic::error("print(**...) is not supported").at(a.span));
            }
            let v = self.env.eval(&a.value, &is_cmd(self.names))?;
            if v.v == PyVal::Poison {
                return Ok(());
            }
            let text = |v: &SpVal| -> Result<String, Diagnostic> {
                match &v.v {
                    PyVal::Concept { name, .. } => Err(crate::catalog::eval::concept_unknown(
                        name,
                        "print() writes",
                        v.span,
                    )),
                    other => crate::catalog::eval::pyfmt::py_str(other)
                        .map_err(|m| Diagnostic::error(m).at(v.span)),
                }
            };
            match a.name.as_ref().map(|k| k.name.as_str()) {
                None => parts.push(text(&v)?),
                Some(k @ ("sep" | "end")) => {
                    let s = match &v.v {
                        PyVal::Str(s) => s.clone(),
                        PyVal::None if k == "sep" => " ".into(),
                        PyVal::None => "\n".into(),
                        other => {
                            return Err(Diagnostic::error(format!(
                                "print(): {k} must be None or a text, not {}",
                                other.describe()
                            ))
                            .at(v.span))
                        }
                    };
                    if k == "sep" {
                        sep = s;
                    } else {
                        end = s;
                    }
                }
                Some("flush") => {}
                Some(k) => {
                    return Err(Diagnostic::error(format!(
                        "print() keyword {k} is not supported (only sep, end and flush)"
                    ))
                    .at(a.span)
                    .note("print() writes to the .mess file"))
                }
            }
        }
        let mut line = parts.join(&sep);
        line.push_str(&end);
        if line.len() > crate::catalog::eval::pyfmt::MAX_TEXT {
            return Err(Diagnostic::error("print() of a text longer than 10^7 bytes").at(span));
        }
        self.prints.push((self.out.len(), line));
        Ok(())
    }

    fn import_names(&mut self, module: &Ident, names: Option<&[(Ident, Option<Ident>)]>) {
        if module.name == "code_aster.Commands" {
            // The commands are always there.
            for (n, _) in names.unwrap_or_default() {
                if !self.names.contains(&n.name.as_str()) {
                    let mut d =
                        Diagnostic::error(format!("code_aster.Commands has no command {}", n.name))
                            .at(n.span);
                    d.suggestion = closest(&n.name, self.names);
                    self.errors.push(d);
                }
            }
            return;
        }
        if module.name == "code_aster" {
            // code_aster 16+ headers: `from code_aster import CA` is
            // accepted (CA is then refused where it is used, with the
            // reason); other names are not there.
            for (n, alias) in names.unwrap_or_default() {
                if n.name == "CA" {
                    self.bind(
                        &alias.as_ref().unwrap_or(n).name,
                        PyVal::Module(builtins::CODE_ASTER_CA),
                    );
                } else {
                    self.errors.push(
                        Diagnostic::error(format!("code_aster.{} is not available in command files", n.name))
                            .at(n.span)
                            .note("from code_aster import CA and from code_aster.Commands import * are accepted"),
                    );
                }
            }
            if names.is_none() {
                self.errors.push(
                    Diagnostic::error("'from code_aster import *' is not supported")
                        .at(module.span)
                        .note("write from code_aster.Commands import * (the commands are always there anyway)"),
                );
            }
            return;
        }
        let Some(m) = builtins::module(&module.name) else {
            return self.errors.push(unknown_module(module));
        };
        let Some(names) = names else {
            if m == "numpy" {
                return self.errors.push(
                    Diagnostic::error("'from numpy import *' is not supported")
                        .at(module.span)
                        .note("import numpy as np and write np.sqrt(...), or import the few functions needed by name"),
                );
            }
            for n in builtins::star_names(m) {
                let id = Ident {
                    name: n.to_string(),
                    span: module.span,
                };
                if let Ok(v) = builtins::module_attr(m, &id) {
                    self.bind(n, v);
                }
            }
            return;
        };
        for (n, alias) in names {
            match builtins::module_attr(m, n) {
                Ok(v) => self.bind(&alias.as_ref().unwrap_or(n).name, v),
                Err(d) => self.errors.push(d),
            }
        }
    }

    /// An assignment or an expression statement: a command call, or plain
    /// Python evaluated now.
    fn statement(&mut self, target: Option<&Ident>, expr: &crate::lang::ast::Expr, span: Span) {
        let call = match &expr.kind {
            ExprKind::Call { func, args } if self.names.contains(&func.name.as_str()) => {
                Some((func, args))
            }
            _ => None,
        };
        let Some((func, args)) = call else {
            if let ExprKind::Call { func, args } = &expr.kind {
                let shadowed = self.env.names.contains_key(func.name.as_str());
                if func.name == "print" && target.is_none() && !shadowed {
                    if let Err(d) = self.print(args, span) {
                        self.errors.push(d);
                    }
                    return;
                }
            }
            // A plain Python statement: evaluate it now. A call of an
            // unknown name at statement level is most likely a misspelt
            // command.
            if let ExprKind::Call { func, .. } = &expr.kind {
                let known = func.name == "_F"
                    || func.name == "dict"
                    || func.name == "print"
                    || crate::catalog::eval::is_builtin(&func.name)
                    || matches!(self.env.bound_value(&func.name), Some(PyVal::Func(_)));
                if !known {
                    self.unknown_call(func, self.names);
                    if let Some(t) = target {
                        self.bind(&t.name, PyVal::Poison);
                    }
                    return;
                }
            }
            match self.env.eval(expr, &is_cmd(self.names)) {
                Ok(SpVal {
                    v: PyVal::Iter(kind, _),
                    span: at,
                }) if target.is_some() => {
                    self.errors.push(
                        Diagnostic::error(format!(
                            "{} {kind} object cannot be kept in a name: write list({kind}(...)), or use it directly in the for",
                            crate::catalog::eval::article(kind)
                        ))
                        .at(at)
                        .note("Python's would be empty the second time it is gone through"),
                    );
                    if let Some(t) = target {
                        self.bind(&t.name, PyVal::Poison);
                    }
                }
                Ok(v) => match target {
                    Some(t) => self.bind(&t.name, v.v),
                    None => self
                        .warnings
                        .push(Diagnostic::warning("this statement has no effect").at(span)),
                },
                Err(d) => {
                    self.errors.push(d);
                    if let Some(t) = target {
                        self.bind(&t.name, PyVal::Poison);
                    }
                }
            }
            return;
        };
        let name = func.name.as_str();
        if !self.seen_debut && name != "DEBUT" {
            self.errors.push(
                Diagnostic::error(format!(
                    "the study must begin with DEBUT(); {name} comes before it"
                ))
                .at(func.span)
                .in_command(name),
            );
            self.seen_debut = true; // report it once
        } else if name == "DEBUT" {
            if self.seen_debut {
                self.errors.push(
                    Diagnostic::error("DEBUT() may appear only once, at the start")
                        .at(func.span)
                        .in_command(name),
                );
            }
            self.seen_debut = true;
        }
        if name == "FIN" {
            self.fin_at = Some(span);
        }
        if let Some(c) = self.command(target, func, args, span) {
            self.out.push(c);
        }
    }

    fn unknown_call(&mut self, func: &Ident, names: &[&str]) {
        let mut d = Diagnostic::error(format!("unknown command {}", func.name)).at(func.span);
        match func.name.as_str() {
            "POURSUITE" => {
                // It stands where DEBUT would: no second error for that.
                self.seen_debut = true;
                d = d.note("POURSUITE continues a study saved by an earlier run, which aster does not save: put the commands of both files in one, after DEBUT()");
            }
            "INCLUDE" => {
                d = d.note("aster reads one command file: copy the included commands into it");
            }
            other => match super::absent::describe(other) {
                Some(what) => d = d.note(what),
                None => d.suggestion = closest(&func.name, names),
            },
        }
        self.errors.push(d);
    }

    fn command(
        &mut self,
        target: Option<&Ident>,
        func: &Ident,
        args: &[crate::lang::ast::Arg],
        span: Span,
    ) -> Option<CheckedCommand> {
        let def_idx = self.registry.iter().position(|d| d.name == func.name)?;
        let spec = self.registry[def_idx];
        let cmd = spec.name;
        let nerr = self.errors.len();

        // Evaluate the arguments; positional ones are errors. `**d` gives
        // the dict's items as keywords, each keeping the span where the
        // dict got it, so a wrong one is reported at the dict's entry
        // (with a note naming the `**`).
        let mut given: Vec<(Ident, SpVal)> = Vec::new();
        let mut reuse: Option<(String, Span)> = None;
        // (span of a keyword or value that came from a dict, the `**` argument)
        let mut from_dict: Vec<(Span, Span)> = Vec::new();
        for a in args {
            let items: Vec<(Ident, Result<SpVal, Diagnostic>, Option<Span>)> = if a.unpack {
                let registry = self.registry;
                let is_c = |n: &str| registry.iter().any(|d| d.name == n);
                let v = match self.env.eval(&a.value, &is_c) {
                    Ok(v) => v,
                    Err(d) => {
                        self.errors.push(d.in_command(cmd));
                        continue;
                    }
                };
                match crate::catalog::eval::unpack_keywords(v, cmd) {
                    Ok(Some(kv)) => kv
                        .into_iter()
                        .map(|(k, v)| (k, Ok(v), Some(a.span)))
                        .collect(),
                    Ok(None) => continue,
                    Err(d) => {
                        self.errors.push(d.in_command(cmd));
                        continue;
                    }
                }
            } else if let Some(k) = &a.name {
                vec![(k.clone(), Err(Diagnostic::error("")), None)]
            } else {
                let mut d =
                    Diagnostic::error(format!("{cmd} takes keyword arguments only (KEY=value)"))
                        .at(a.span)
                        .in_command(cmd);
                if let ExprKind::Compare { first, rest } = &a.value.kind {
                    if let (ExprKind::Name(k), [(CmpOp::Eq, _)]) = (&first.kind, rest.as_slice()) {
                        d = d.note(format!("write {k}=... with a single '=' ('==' compares)"));
                    }
                }
                self.errors.push(d);
                continue;
            };
            for (k, pre, star) in items {
                if given.iter().any(|(p, _)| p.name == k.name)
                    || (k.name == "reuse" && reuse.is_some())
                {
                    let mut d = Diagnostic::error(format!("keyword {} is given twice", k.name))
                        .at(star.unwrap_or(k.span))
                        .in_command(cmd)
                        .keyword(k.name.clone());
                    if star.is_some() {
                        d = d.note(format!(
                            "the dict that ** unpacks holds {} (at byte {}), already given to {cmd}",
                            k.name, k.span.start
                        ));
                    }
                    self.errors.push(d);
                    continue;
                }
                if let Some(star) = star {
                    from_dict.push((k.span, star));
                }
                if k.name == "reuse" {
                    match (&a.value.kind, &pre) {
                        (ExprKind::Name(n), Err(_)) if star.is_none() => {
                            reuse = Some((n.clone(), a.value.span))
                        }
                        (
                            _,
                            Ok(SpVal {
                                v: PyVal::Concept { name, .. },
                                span,
                            }),
                        ) => reuse = Some((name.clone(), *span)),
                        _ => self.errors.push(
                            Diagnostic::error("reuse= takes the name of an existing concept")
                                .at(pre.as_ref().map_or(a.value.span, |v| v.span))
                                .in_command(cmd),
                        ),
                    }
                    continue;
                }
                let registry = self.registry;
                let evaluated = match pre {
                    Ok(v) => Ok(v),
                    Err(_) => self
                        .env
                        .eval(&a.value, &|n| registry.iter().any(|d| d.name == n)),
                };
                match evaluated {
                    Ok(v) => {
                        if star.is_some() {
                            from_dict.push((v.span, a.span));
                        }
                        if let Some((name, at)) = find_stale(&v) {
                            self.errors.push(
                                Diagnostic::error(format!(
                                    "this value holds the concept {name} as it was before {name} was defined again"
                                ))
                                .at(at)
                                .in_command(cmd)
                                .keyword(k.name.clone())
                                .note("aster knows concepts by their names: give each concept its own name"),
                            );
                        }
                        given.push((k.clone(), for_keyword(v)))
                    }
                    Err(d) => {
                        self.errors.push(with_ctx(d, cmd, &k.name));
                        given.push((
                            k.clone(),
                            SpVal {
                                v: PyVal::Poison,
                                span: a.value.span,
                            },
                        ));
                    }
                }
            }
        }
        if let Some(compat) = spec.compat {
            self.errors.extend(compat(&mut given));
        }

        // `for R in (RN, RL): R = CALC_CHAMP(reuse=R, RESULTAT=R, ...)`: R
        // is a name holding the concept RN, and Python modifies RN in place
        // and binds R to it again. aster knows concepts by their names, so
        // the command is the one on RN, and R keeps holding RN.
        let mut alias_target = None;
        if let Some((n, sp)) = reuse.clone() {
            if let Some(Binding::Var(PyVal::Concept { name: real, .. })) = self.env.names.get(&n) {
                let real = real.clone();
                alias_target = target.filter(|t| t.name == n).map(|t| Ident {
                    name: real.clone(),
                    span: t.span,
                });
                reuse = Some((real, sp));
            }
        }
        // `CMD(reuse=X, ...)` without `X =`: code_aster modifies X in place
        // all the same (ssnp170a's CALC_CHAMP, sdnl112a's MODI_MAILLAGE):
        // the result goes to X, as `X = CMD(reuse=X, ...)`.
        let implied_target = match (alias_target.as_ref().or(target), &reuse) {
            (None, Some((n, sp))) => Some(Ident {
                name: n.clone(),
                span: *sp,
            }),
            _ => None,
        };
        let target = alias_target.as_ref().or(target).or(implied_target.as_ref());
        if cmd == "FORMULE" {
            let formula = target.map_or("the formula".to_string(), |t| t.name.clone());
            // The formula defined again: what the old one read is moot.
            self.captured.retain(|c| c.2 != formula);
            for (var, v) in formula_constants(&mut given, &self.env) {
                self.captured.push((var, v, formula.clone(), None));
            }
        }
        let mut top = Args::new(cmd, "", span);
        let before_level = self.errors.len();
        self.cmd_keywords = &spec.keywords;
        self.level(cmd, "", &spec.keywords, &spec.rules, given, &mut top);
        if !from_dict.is_empty() {
            for d in &mut self.errors[before_level..] {
                let star = d.span.and_then(|s| {
                    from_dict
                        .iter()
                        .find(|(inner, _)| inner.start <= s.start && s.end <= inner.end)
                });
                if let Some((_, star)) = star {
                    d.notes.push(format!(
                        "the keyword comes from the dict that ** unpacks in {cmd} (at byte {})",
                        star.start
                    ));
                }
            }
        }

        // Result binding and reuse.
        let produces = match &spec.produces {
            Produces::Nothing => None,
            Produces::Concept(t) => Some(*t),
            Produces::SameAs(key, default) => Some(
                top.concept(key)
                    .and_then(|n| match self.env.names.get(n) {
                        Some(Binding::Concept { ty, .. }) => Some(*ty),
                        _ => None,
                    })
                    .unwrap_or(*default),
            ),
            Produces::ByText(key, table, default) => Some(
                top.text(key)
                    .and_then(|v| {
                        table
                            .iter()
                            .find(|(prefix, _)| v.starts_with(prefix))
                            .map(|(_, t)| *t)
                    })
                    .unwrap_or(*default),
            ),
        };
        match (target, produces) {
            (Some(t), None) => self.errors.push(
                Diagnostic::error(format!("{cmd} produces no result; remove '{} ='", t.name))
                    .at(t.span)
                    .in_command(cmd),
            ),
            (None, Some(ty)) => self.warnings.push(
                Diagnostic::warning(format!(
                    "the result of {cmd} ({ty}) is not assigned to a name and will be lost"
                ))
                .at(func.span)
                .in_command(cmd),
            ),
            _ => {}
        }
        let reuse_name = reuse.as_ref().map(|(n, _)| n.clone());
        top.reuse = reuse_name.clone();
        self.check_reuse(
            cmd,
            &spec.reentrant,
            target,
            reuse,
            produces,
            &top,
            func.span,
        );

        if spec.destroys && self.errors.len() == nerr {
            let mut gone = Vec::new();
            concept_names(&top, &mut gone);
            for name in gone {
                for (n, b) in self.env.names.iter_mut() {
                    if let (true, Binding::Var(v)) = (*n != name, b) {
                        make_stale(v, &name);
                    }
                }
                self.env.names.shift_remove(&name);
                self.env.destroyed.insert(name, span);
            }
        }
        if let (Some(t), Some(ty)) = (target, produces) {
            self.env.destroyed.shift_remove(&t.name);
            // The runner finds concepts by name: values still holding the
            // previous concept of this name would see the new one, where
            // Python keeps the old object; they become stale (an error
            // where they are used).
            if reuse_name.is_none() {
                for (n, b) in self.env.names.iter_mut() {
                    if let (true, Binding::Var(v)) = (*n != t.name, b) {
                        make_stale(v, &t.name);
                    }
                }
            }
            self.env.names.insert(
                t.name.clone(),
                Binding::Concept {
                    ty,
                    defined_at: t.span,
                },
            );
        }
        if self.errors.len() > nerr {
            return None;
        }
        Some(CheckedCommand {
            def: def_idx,
            name: cmd.to_string(),
            result: target.cloned(),
            reuse: reuse_name,
            produces,
            args: top,
            span,
        })
    }

    #[allow(clippy::too_many_arguments)]
    fn check_reuse(
        &mut self,
        cmd: &str,
        reentrant: &Reentrant,
        target: Option<&Ident>,
        reuse: Option<(String, Span)>,
        produces: Option<ConceptType>,
        top: &Args,
        cmd_span: Span,
    ) {
        let key = match reentrant {
            Reentrant::No => {
                if let Some((_, sp)) = reuse {
                    self.errors.push(
                        Diagnostic::error(format!(
                            "reuse is not allowed: {cmd} always creates a new concept"
                        ))
                        .at(sp)
                        .in_command(cmd)
                        .keyword("reuse"),
                    );
                }
                return;
            }
            Reentrant::Optional(k) | Reentrant::Required(k) => *k,
        };
        // A reentrant command whose reentrance is not RESULTAT but which
        // has RESULTAT at its top (STAT_NON_LINE, DYNA_NON_LINE): there
        // code_aster ≥ 15 names the result continued in place.
        let resultat = (key != "RESULTAT")
            .then(|| {
                top.concept("RESULTAT")
                    .map(|g| (g.to_string(), top.span_of("RESULTAT")))
            })
            .flatten();
        let Some((name, sp)) = reuse else {
            if let Some((given, at)) = &resultat {
                self.errors.push(
                    Diagnostic::error(format!(
                        "RESULTAT={given} names the result {cmd} continues in place: write {given} = {cmd}(reuse={given}, RESULTAT={given}, ...), or leave RESULTAT out for a new result"
                    ))
                    .at(*at)
                    .in_command(cmd)
                    .keyword("RESULTAT"),
                );
            }
            if let (Reentrant::Required(_), Some(t)) = (reentrant, target) {
                self.errors.push(
                    Diagnostic::error(format!(
                        "{cmd} modifies the concept given in {key} in place: write {} = {cmd}(reuse={}, {key}={}, ...)",
                        t.name, t.name, t.name
                    ))
                    .at(cmd_span)
                    .in_command(cmd)
                    .keyword("reuse"),
                );
            }
            return;
        };
        match self.env.names.get(&name) {
            None => {
                let known: Vec<&str> = self.env.names.keys().map(String::as_str).collect();
                let mut d = Diagnostic::error(format!("reuse={name}: '{name}' is not defined"))
                    .at(sp)
                    .in_command(cmd)
                    .keyword("reuse");
                d.suggestion = closest(&name, &known);
                self.errors.push(d);
                return;
            }
            Some(Binding::Var(v)) => {
                self.errors.push(
                    Diagnostic::error(format!(
                        "reuse={name}: '{name}' is {}, not a concept",
                        v.describe()
                    ))
                    .at(sp)
                    .in_command(cmd)
                    .keyword("reuse"),
                );
                return;
            }
            Some(Binding::Concept { ty, .. }) => {
                if Some(*ty) != produces {
                    self.errors.push(
                        Diagnostic::error(format!(
                            "reuse={name}: '{name}' is a {ty} but {cmd} produces a {}",
                            produces.map(|t| t.aster_name()).unwrap_or("nothing")
                        ))
                        .at(sp)
                        .in_command(cmd)
                        .keyword("reuse"),
                    );
                    return;
                }
            }
        }
        if let Some(t) = target {
            if t.name != name {
                self.errors.push(
                    Diagnostic::error(format!(
                        "reuse={name} modifies '{name}' in place, so the result must be assigned to '{name}', not '{}'",
                        t.name
                    ))
                    .at(t.span)
                    .in_command(cmd)
                    .keyword("reuse"),
                );
            }
        }
        if let Some((given, at)) = resultat.filter(|(g, _)| *g != name) {
            self.errors.push(
                Diagnostic::error(format!(
                    "reuse={name} but RESULTAT={given}: RESULTAT names the result continued in place, the one of reuse="
                ))
                .at(at)
                .in_command(cmd)
                .keyword("RESULTAT"),
            );
        }
        // The reused concept must be the one passed in the reentrance keyword
        // (e.g. MAILLAGE for DEFI_GROUP, ETAT_INIT/EVOL_NOLI for DYNA_NON_LINE).
        let mut level = top;
        let mut parts: Vec<&str> = key.split('/').collect();
        let last = parts.pop().unwrap_or(key);
        for p in parts {
            match level.fact(p) {
                Some(a) => level = a,
                None => return,
            }
        }
        if let Some(given) = level.concept(last) {
            if given != name {
                self.errors.push(
                    Diagnostic::error(format!(
                        "reuse={name} but {key}={given}: the concept modified in place must be the one given in {key}"
                    ))
                    .at(level.span_of(last))
                    .in_command(cmd)
                    .keyword(key),
                );
            }
        } else if matches!(reentrant, Reentrant::Required(_)) {
            self.errors.push(
                Diagnostic::error(format!("reuse={name} needs {key}={name}"))
                    .at(sp)
                    .in_command(cmd)
                    .keyword(key),
            );
        }
    }

    /// Checks the keywords of one level (a command or one `_F` occurrence)
    /// and fills `out`.
    fn level(
        &mut self,
        cmd: &str,
        path: &str,
        keywords: &[Keyword],
        rules: &[Rule],
        given: Vec<(Ident, SpVal)>,
        out: &mut Args,
    ) {
        // None means "absent", as in code_aster.
        let given: Vec<(Ident, SpVal)> = given
            .into_iter()
            .filter(|(_, v)| v.v != PyVal::None)
            .collect();

        // Resolve blocks to a fixpoint: conditions see given values and the
        // defaults of keywords visible so far.
        let mut active: Vec<&Keyword> = Vec::new();
        let mut block_rules: Vec<&Rule> = Vec::new();
        for _ in 0..8 {
            let mut defaults: Vec<(&str, PyVal)> = Vec::new();
            for k in &active {
                if let Keyword::Simple(s) = k {
                    if s.status == Status::Defaulted && !given.iter().any(|(g, _)| g.name == s.name)
                    {
                        defaults.push((s.name, lit_default(s)));
                    }
                }
            }
            let mut present: Present = given
                .iter()
                .map(|(k, v)| (k.name.as_str(), Some(&v.v)))
                .collect();
            for (n, v) in &defaults {
                present.push((n, Some(v)));
            }
            let mut next = Vec::new();
            let mut next_rules = Vec::new();
            flatten(keywords, &present, &mut next, &mut next_rules);
            let same = next.len() == active.len()
                && next.iter().zip(&active).all(|(a, b)| std::ptr::eq(*a, *b));
            active = next;
            block_rules = next_rules;
            if same {
                break;
            }
        }

        // Unknown keywords.
        let mut unknown_given = false;
        for (k, _) in &given {
            if active.iter().any(|a| a.name() == k.name) {
                continue;
            }
            let kp = join(path, &k.name);
            // A keyword of the same factor keyword under another block
            // (GROUP_MA_MAIT in a ZONE of DEFI_CONTACT's LIAISON_UNIL:
            // a ZONE of DISCRETE or CONTINUE has it).
            let fact = path.rsplit('/').next().unwrap_or("");
            let mut variants = Vec::new();
            if !fact.is_empty() {
                find_fact_variants(self.cmd_keywords, fact, &k.name, None, &mut variants);
            }
            let mut conds: Vec<String> = Vec::new();
            for c in variants {
                let d = describe_cond(c);
                if !conds.contains(&d) {
                    conds.push(d);
                }
            }
            if let Some(cond) = find_in_blocks(keywords, &k.name) {
                self.errors.push(
                    Diagnostic::error(format!(
                        "keyword {} is not allowed here: it exists only when {}",
                        k.name,
                        describe_cond(cond)
                    ))
                    .at(k.span)
                    .in_command(cmd)
                    .keyword(kp),
                );
            } else if !conds.is_empty() {
                self.errors.push(
                    Diagnostic::error(format!(
                        "keyword {} of {fact} is not allowed here: {fact} has it only when {}",
                        k.name,
                        conds.join(", or when ")
                    ))
                    .at(k.span)
                    .in_command(cmd)
                    .keyword(kp),
                );
                unknown_given = true;
            } else {
                let valid: Vec<&str> = active.iter().map(|a| a.name()).collect();
                let mut d = Diagnostic::error(format!(
                    "unknown keyword {}{}",
                    k.name,
                    if path.is_empty() {
                        format!(" for {cmd}")
                    } else {
                        format!(" in {path}")
                    }
                ))
                .at(k.span)
                .in_command(cmd)
                .keyword(kp);
                match super::absent::removed_keyword(cmd, &k.name) {
                    Some(note) => d.notes.push(note),
                    None => {
                        d.suggestion = closest(&k.name, &valid);
                        d.choices = valid.iter().map(|s| s.to_string()).collect();
                    }
                }
                self.errors.push(d);
                unknown_given = true;
            }
        }

        // Each visible keyword, in catalogue order.
        for kw in &active {
            let g = given.iter().find(|(k, _)| k.name == kw.name());
            match kw {
                Keyword::Simple(s) => self.simple(cmd, path, s, g, out),
                Keyword::Factor(f) => self.factor(cmd, path, f, g, out),
                Keyword::Block(_) => {}
            }
        }

        // Rules, on the keywords present after defaults (as code_aster). A
        // keyword the user gave counts as present even if its value was
        // wrong: that error is already reported.
        let mut present: Vec<&str> = out.entries.keys().map(String::as_str).collect();
        for (k, _) in &given {
            if !present.contains(&k.name.as_str()) {
                present.push(k.name.as_str());
            }
        }
        for r in rules.iter().chain(block_rules.iter().copied()) {
            // "At least one of ... must be given" after an unknown keyword
            // is the same mistake again (LIAISON_DDL in AFFE_CHAR_MECA,
            // which the user meant as the load): reported once.
            let none_of = |ks: &[&str]| !ks.iter().any(|k| present.contains(k));
            let nothing_given = match r {
                Rule::AtLeastOne(ks) | Rule::ExactlyOne(ks) => none_of(ks),
                _ => false,
            };
            if unknown_given && nothing_given {
                continue;
            }
            if let Some(msg) = rule_violation(r, &present) {
                let mut d = Diagnostic::error(msg).at(out.span).in_command(cmd);
                if !path.is_empty() {
                    d = d.keyword(path.to_string());
                }
                self.errors.push(d);
            }
        }
    }

    fn simple(
        &mut self,
        cmd: &str,
        path: &str,
        s: &Simple,
        given: Option<&(Ident, SpVal)>,
        out: &mut Args,
    ) {
        let kp = join(path, s.name);
        let Some((k, v)) = given else {
            match s.status {
                Status::Required => self.errors.push(
                    Diagnostic::error(format!(
                        "missing compulsory keyword {} ({} expected)",
                        s.name,
                        s.ty.describe()
                    ))
                    .at(out.span)
                    .in_command(cmd)
                    .keyword(kp),
                ),
                Status::Defaulted => {
                    let vals = s.default.iter().map(lit_value).collect();
                    out.entries.insert(
                        s.name.to_string(),
                        Entry {
                            span: out.span,
                            defaulted: true,
                            data: EntryData::Simple(vals),
                        },
                    );
                }
                _ => {}
            }
            return;
        };
        let span = k.span.to(v.span);
        let err = |msg: String| {
            Diagnostic::error(msg)
                .at(v.span)
                .in_command(cmd)
                .keyword(kp.clone())
        };
        // Flatten tuples; a one-element tuple on a single-valued keyword is
        // unwrapped, as code_aster does.
        let items: Vec<&SpVal> = match &v.v {
            PyVal::Tuple(items) => items.iter().collect(),
            _ => vec![v],
        };
        if items.iter().any(|it| it.v == PyVal::Poison) {
            // Already reported where the value was defined; keep the
            // keyword present so that rules do not report it again.
            out.entries.insert(
                s.name.to_string(),
                Entry {
                    span,
                    defaulted: false,
                    data: EntryData::Simple(Vec::new()),
                },
            );
            return;
        }
        if let Some(max) = s.max {
            if items.len() > max {
                self.errors.push(err(format!(
                    "{} takes at most {max} value{}, {} given",
                    s.name,
                    if max > 1 { "s" } else { "" },
                    items.len()
                )));
                return;
            }
        }
        if items.len() < s.min {
            self.errors.push(err(format!(
                "{} needs at least {} values, {} given",
                s.name,
                s.min,
                items.len()
            )));
            return;
        }
        let mut vals = Vec::new();
        for it in items {
            match self.convert(cmd, &kp, s, it) {
                Ok(x) => vals.push(x),
                Err(d) => self.errors.push(d),
            }
        }
        out.entries.insert(
            s.name.to_string(),
            Entry {
                span,
                defaulted: false,
                data: EntryData::Simple(vals),
            },
        );
    }

    /// Type, `into` and bounds of one value.
    fn convert(&self, cmd: &str, kp: &str, s: &Simple, it: &SpVal) -> Result<Value, Diagnostic> {
        let err = |msg: String| {
            Diagnostic::error(msg)
                .at(it.span)
                .in_command(cmd)
                .keyword(kp.to_string())
        };
        let wrong = || {
            let mut d = err(format!(
                "expected {}, found {}",
                s.ty.describe(),
                it.v.describe()
            ));
            if let (PyVal::Concept { name, .. }, Some(Binding::Concept { defined_at, .. })) = (
                &it.v,
                self.env.names.get(match &it.v {
                    PyVal::Concept { name, .. } => name.as_str(),
                    _ => "",
                }),
            ) {
                d = d.note(format!("{name} is defined at byte {}", defined_at.start));
            }
            d
        };
        let value = match (&s.ty, &it.v) {
            (Ty::Real, PyVal::Real(r)) => Value::Real(*r),
            (Ty::Real, PyVal::Int(i)) => Value::Real(*i as f64),
            (Ty::Int, PyVal::Int(i)) => Value::Int(*i),
            (Ty::Int, PyVal::Real(r)) if r.fract() == 0.0 && r.abs() < 9.0e15 => {
                Value::Int(*r as i64)
            }
            (Ty::Text, PyVal::Str(t)) => Value::Text(t.clone()),
            (Ty::Concept(tys), PyVal::Concept { name, ty }) => {
                if !tys.contains(ty) {
                    let names: Vec<&str> = tys.iter().map(|t| t.aster_name()).collect();
                    return Err(err(format!(
                        "{name} is a {ty}, but a concept of type {} is expected",
                        names.join(" or ")
                    )));
                }
                Value::Concept {
                    name: name.clone(),
                    ty: *ty,
                }
            }
            (Ty::Text, PyVal::Concept { name, .. }) => {
                return Err(err(format!(
                "expected a text, found the concept {name}; did you forget the quotes ('{name}')?"
            )))
            }
            _ => return Err(wrong()),
        };
        if let Some(into) = &s.into {
            let ok = into.iter().any(|l| lit_matches(l, &value));
            if !ok {
                let choices: Vec<String> = into.iter().map(lit_display).collect();
                let given = match &value {
                    Value::Text(t) => t.clone(),
                    v => v.to_string(),
                };
                let mut d = err(format!("{value} is not an allowed value of {}", s.name));
                d.choices = choices.clone();
                match super::absent::removed_value(cmd, s.name, &given) {
                    Some(note) => d.notes.push(note),
                    None => d.suggestion = closest(&given, &choices),
                }
                return Err(d);
            }
        }
        if s.not_built_at_all() {
            return Err(err(format!(
                "not implemented yet: {cmd}/{kp} ({})",
                s.not_built_why
            )));
        }
        if let Value::Text(t) = &value {
            if s.not_built.contains(&t.as_str()) {
                return Err(err(format!(
                    "not implemented yet: {cmd}/{kp}='{t}' ({})",
                    s.not_built_why
                )));
            }
        }
        if let Some(x) = value.as_real() {
            if let Some(lo) = s.val_min {
                if x < lo {
                    return Err(err(format!("{} = {x} is below its minimum {lo}", s.name)));
                }
            }
            if let Some(hi) = s.val_max {
                if x > hi {
                    return Err(err(format!("{} = {x} is above its maximum {hi}", s.name)));
                }
            }
        }
        Ok(value)
    }

    fn factor(
        &mut self,
        cmd: &str,
        path: &str,
        f: &Factor,
        given: Option<&(Ident, SpVal)>,
        out: &mut Args,
    ) {
        let kp = join(path, f.name);
        let Some((k, v)) = given else {
            match f.status {
                Status::Required => self.errors.push(
                    Diagnostic::error(format!(
                        "missing compulsory factor keyword {} (expected {}=_F(...))",
                        f.name, f.name
                    ))
                    .at(out.span)
                    .in_command(cmd)
                    .keyword(kp),
                ),
                Status::Defaulted => {
                    let mut occ = Args::new(cmd, kp.clone(), out.span);
                    self.level(cmd, &kp, &f.keywords, &f.rules, Vec::new(), &mut occ);
                    out.entries.insert(
                        f.name.to_string(),
                        Entry {
                            span: out.span,
                            defaulted: true,
                            data: EntryData::Factor(vec![occ]),
                        },
                    );
                }
                _ => {}
            }
            return;
        };
        let occs: Vec<&SpVal> = match &v.v {
            PyVal::Tuple(items) => items.iter().collect(),
            _ => vec![v],
        };
        if let Some(o) = occs
            .iter()
            .find(|o| !matches!(o.v, PyVal::Fact(..) | PyVal::Poison))
        {
            self.errors.push(
                Diagnostic::error(format!(
                    "{} is a factor keyword: expected _F(...) or a tuple of _F(...), found {}",
                    f.name,
                    o.v.describe()
                ))
                .at(o.span)
                .in_command(cmd)
                .keyword(kp),
            );
            return;
        }
        if occs.len() < f.min {
            // `KEY=()`: given, but with no occurrence; code_aster's
            // supervisor refuses it as it refuses a required keyword left
            // out.
            self.errors.push(
                Diagnostic::error(format!(
                    "{} needs at least {} occurrence{} _F(...), {} given",
                    f.name,
                    f.min,
                    if f.min > 1 { "s" } else { "" },
                    occs.len()
                ))
                .at(v.span)
                .in_command(cmd)
                .keyword(kp),
            );
            return;
        }
        if let Some(max) = f.max {
            if occs.len() > max {
                self.errors.push(
                    Diagnostic::error(format!(
                        "{} takes at most {max} occurrence{}, {} given",
                        f.name,
                        if max > 1 { "s" } else { "" },
                        occs.len()
                    ))
                    .at(v.span)
                    .in_command(cmd)
                    .keyword(kp),
                );
                return;
            }
        }
        let mut checked = Vec::new();
        for o in occs {
            if o.v == PyVal::Poison {
                continue;
            }
            let PyVal::Fact(_, items) = &o.v else {
                self.errors.push(
                    Diagnostic::error(format!(
                        "{} is a factor keyword: expected _F(...) or a tuple of _F(...), found {}",
                        f.name,
                        o.v.describe()
                    ))
                    .at(o.span)
                    .in_command(cmd)
                    .keyword(kp.clone()),
                );
                continue;
            };
            let mut occ = Args::new(cmd, kp.clone(), o.span);
            self.level(cmd, &kp, &f.keywords, &f.rules, items.clone(), &mut occ);
            checked.push(occ);
        }
        out.entries.insert(
            f.name.to_string(),
            Entry {
                span: k.span.to(v.span),
                defaulted: false,
                data: EntryData::Factor(checked),
            },
        );
    }
}

/// FORMULE's constants: code_aster evaluates VALE with the values passed
/// as extra keywords (`FORMULE(VALE='H - X', NOM_PARA='X', H=H)`) and, in
/// older versions, with the command file's variables. Both become the
/// hidden keywords CONST_NOMS/CONST_VALE (numbers), the functions it
/// calls (`VALE='GAM(INST) * Z', GAM=GAM`) FONC_NOMS/FONC_VALE; anything
/// else is left to be reported as an unknown keyword.
fn formula_constants(given: &mut Vec<(Ident, SpVal)>, env: &Env) -> Vec<(String, PyVal)> {
    // The hidden keywords written by hand are checked as they are.
    if given.iter().any(|(k, _)| {
        matches!(
            k.name.as_str(),
            "CONST_NOMS" | "CONST_VALE" | "FONC_NOMS" | "FONC_VALE"
        )
    }) {
        return Vec::new();
    }
    let mut captured: Vec<(String, PyVal)> = Vec::new();
    let is_function = |ty: &ConceptType| matches!(ty, ConceptType::Fonction | ConceptType::Formule);
    let mut names: Vec<String> = Vec::new();
    let mut values: Vec<f64> = Vec::new();
    let mut fnames: Vec<String> = Vec::new();
    let mut fvalues: Vec<SpVal> = Vec::new();
    let mut span = None;
    given.retain(|(k, v)| {
        if matches!(k.name.as_str(), "VALE" | "NOM_PARA") {
            if k.name == "VALE" {
                span = Some(v.span);
            }
            return true;
        }
        let x = match &v.v {
            PyVal::Int(i) => *i as f64,
            PyVal::Real(r) => *r,
            PyVal::Concept { ty, .. } if is_function(ty) => {
                span.get_or_insert(v.span);
                fnames.push(k.name.clone());
                fvalues.push(v.clone());
                return false;
            }
            _ => return true,
        };
        span.get_or_insert(v.span);
        names.push(k.name.clone());
        values.push(x);
        false
    });
    let text = given.iter().find_map(|(k, v)| match (&*k.name, &v.v) {
        ("VALE", PyVal::Str(s)) => Some(s.clone()),
        _ => None,
    });
    let params: Vec<String> = given
        .iter()
        .filter(|(k, _)| k.name == "NOM_PARA")
        .flat_map(|(_, v)| match &v.v {
            PyVal::Str(s) => vec![s.clone()],
            PyVal::Tuple(t) => t
                .iter()
                .filter_map(|x| match &x.v {
                    PyVal::Str(s) => Some(s.clone()),
                    _ => None,
                })
                .collect(),
            _ => vec![],
        })
        .collect();
    if let Some(text) = text {
        let src = crate::diag::Source::new("VALE", format!("F__ = ({text})\n"));
        if let Ok(program) = crate::lang::parser::parse(&src) {
            let mut used = Vec::new();
            for s in &program.stmts {
                if let StmtKind::Assign { value, .. } = &s.kind {
                    collect_names(value, &mut used);
                }
            }
            for n in used {
                if params.contains(&n) || names.contains(&n) || fnames.contains(&n) {
                    continue;
                }
                let x = match env.names.get(&n) {
                    Some(Binding::Var(v @ PyVal::Int(i))) => {
                        captured.push((n.clone(), v.clone()));
                        *i as f64
                    }
                    Some(Binding::Var(v @ PyVal::Real(r))) => {
                        captured.push((n.clone(), v.clone()));
                        *r
                    }
                    Some(Binding::Concept { ty, .. }) if is_function(ty) => {
                        if let Some(span) = span {
                            fvalues.push(SpVal {
                                v: PyVal::Concept {
                                    name: n.clone(),
                                    ty: *ty,
                                },
                                span,
                            });
                            fnames.push(n);
                        }
                        continue;
                    }
                    Some(Binding::Var(v @ PyVal::Concept { ty, .. })) if is_function(ty) => {
                        if let Some(span) = span {
                            fvalues.push(SpVal { v: v.clone(), span });
                            fnames.push(n);
                        }
                        continue;
                    }
                    _ => continue,
                };
                names.push(n);
                values.push(x);
            }
        }
    }
    let Some(span) = span else {
        return captured;
    };
    let ident = |n: &str| Ident {
        name: n.to_string(),
        span,
    };
    let sp = |v: PyVal| SpVal { v, span };
    if !fnames.is_empty() {
        given.push((
            ident("FONC_NOMS"),
            sp(PyVal::Tuple(
                fnames.into_iter().map(|n| sp(PyVal::Str(n))).collect(),
            )),
        ));
        given.push((ident("FONC_VALE"), sp(PyVal::Tuple(fvalues))));
    }
    if names.is_empty() {
        return captured;
    }
    given.push((
        ident("CONST_NOMS"),
        sp(PyVal::Tuple(
            names.into_iter().map(|n| sp(PyVal::Str(n))).collect(),
        )),
    ));
    given.push((
        ident("CONST_VALE"),
        sp(PyVal::Tuple(
            values.into_iter().map(|x| sp(PyVal::Real(x))).collect(),
        )),
    ));
    captured
}

fn collect_names(e: &crate::lang::ast::Expr, out: &mut Vec<String>) {
    match &e.kind {
        ExprKind::Name(n) if !out.contains(n) => out.push(n.clone()),
        ExprKind::Unary { operand, .. } => collect_names(operand, out),
        ExprKind::Binary { lhs, rhs, .. } => {
            collect_names(lhs, out);
            collect_names(rhs, out);
        }
        ExprKind::Call { func, args } => {
            if !out.contains(&func.name) {
                out.push(func.name.clone());
            }
            args.iter().for_each(|a| collect_names(&a.value, out))
        }
        ExprKind::Tuple(items) => items.iter().for_each(|x| collect_names(x, out)),
        _ => {}
    }
}

/// The concepts named anywhere in checked arguments (DETRUIRE's).
fn concept_names(args: &Args, out: &mut Vec<String>) {
    for e in args.entries.values() {
        match &e.data {
            EntryData::Simple(vs) => {
                out.extend(vs.iter().filter_map(|v| v.as_concept().map(str::to_string)))
            }
            EntryData::Factor(occs) => occs.iter().for_each(|a| concept_names(a, out)),
        }
    }
}

fn with_ctx(d: Diagnostic, cmd: &str, key: &str) -> Diagnostic {
    let d = if d.command.is_none() {
        d.in_command(cmd)
    } else {
        d
    };
    if d.keyword.is_none() {
        d.keyword(key.to_string())
    } else {
        d
    }
}

fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}/{key}")
    }
}

/// The keywords visible at a level: plain ones and those of blocks whose
/// condition holds (recursively).
fn flatten<'k>(
    keywords: &'k [Keyword],
    present: &Present,
    out: &mut Vec<&'k Keyword>,
    rules: &mut Vec<&'k Rule>,
) {
    for k in keywords {
        match k {
            Keyword::Block(b) => {
                if eval_cond(&b.condition, present) {
                    rules.extend(b.rules.iter());
                    flatten(&b.keywords, present, out, rules);
                }
            }
            _ => out.push(k),
        }
    }
}

/// Finds the condition of the (first) block that declares `name`.
/// The conditions of the blocks under which a factor keyword `fact` of
/// the command declares `name` (searched in `keywords` and their blocks;
/// `within` the condition of the innermost enclosing block so far).
fn find_fact_variants<'k>(
    keywords: &'k [Keyword],
    fact: &str,
    name: &str,
    within: Option<&'k Cond>,
    out: &mut Vec<&'k Cond>,
) {
    for k in keywords {
        match k {
            Keyword::Factor(f) if f.name == fact => {
                let declares = f.keywords.iter().any(|x| x.name() == name)
                    || find_in_blocks(&f.keywords, name).is_some();
                if let (true, Some(c)) = (declares, within) {
                    out.push(c);
                }
            }
            Keyword::Block(b) => {
                find_fact_variants(&b.keywords, fact, name, Some(&b.condition), out)
            }
            _ => {}
        }
    }
}

fn find_in_blocks<'k>(keywords: &'k [Keyword], name: &str) -> Option<&'k Cond> {
    for k in keywords {
        if let Keyword::Block(b) = k {
            if b.keywords.iter().any(|x| x.name() == name) {
                return Some(&b.condition);
            }
            if let Some(c) = find_in_blocks(&b.keywords, name) {
                return Some(c);
            }
        }
    }
    None
}

fn first_scalar(v: &PyVal) -> Option<&PyVal> {
    match v {
        PyVal::Tuple(items) => items.first().map(|x| &x.v),
        v => Some(v),
    }
}

fn lit_eq_py(l: &Lit, v: &PyVal) -> bool {
    match (l, v) {
        (Lit::Text(a), PyVal::Str(b)) => a == b,
        (Lit::Int(a), PyVal::Int(b)) => a == b,
        (Lit::Int(a), PyVal::Real(b)) => *a as f64 == *b,
        (Lit::Real(a), PyVal::Real(b)) => a == b,
        (Lit::Real(a), PyVal::Int(b)) => *a == *b as f64,
        _ => false,
    }
}

fn eval_cond(c: &Cond, present: &Present) -> bool {
    let get = |k: &str| present.iter().find(|(n, _)| *n == k).and_then(|(_, v)| *v);
    match c {
        Cond::Eq(k, l) => get(k)
            .and_then(first_scalar)
            .is_some_and(|v| lit_eq_py(l, v)),
        Cond::In(k, ls) => get(k)
            .and_then(first_scalar)
            .is_some_and(|v| ls.iter().any(|l| lit_eq_py(l, v))),
        Cond::Present(k) => get(k).is_some(),
        Cond::Absent(k) => get(k).is_none(),
        Cond::And(cs) => cs.iter().all(|c| eval_cond(c, present)),
        Cond::Or(cs) => cs.iter().any(|c| eval_cond(c, present)),
        Cond::Not(c) => !eval_cond(c, present),
    }
}

/// A readable form of a block condition, for messages and docs.
pub fn describe_cond(c: &Cond) -> String {
    match c {
        Cond::Eq(k, l) => format!("{k}={}", lit_display_q(l)),
        Cond::In(k, ls) => format!(
            "{k} is one of {}",
            ls.iter().map(lit_display_q).collect::<Vec<_>>().join(", ")
        ),
        Cond::Present(k) => format!("{k} is given"),
        Cond::Absent(k) => format!("{k} is absent"),
        Cond::And(cs) => cs
            .iter()
            .map(describe_cond)
            .collect::<Vec<_>>()
            .join(" and "),
        Cond::Or(cs) => format!(
            "({})",
            cs.iter()
                .map(describe_cond)
                .collect::<Vec<_>>()
                .join(" or ")
        ),
        Cond::Not(c) => format!("not ({})", describe_cond(c)),
    }
}

pub fn lit_display(l: &Lit) -> String {
    match l {
        Lit::Int(i) => i.to_string(),
        Lit::Real(r) => format!("{r:?}"),
        Lit::Text(t) => t.to_string(),
    }
}

fn lit_display_q(l: &Lit) -> String {
    match l {
        Lit::Text(t) => format!("'{t}'"),
        l => lit_display(l),
    }
}

fn lit_value(l: &Lit) -> Value {
    match l {
        Lit::Int(i) => Value::Int(*i),
        Lit::Real(r) => Value::Real(*r),
        Lit::Text(t) => Value::Text(t.to_string()),
    }
}

fn lit_default(s: &Simple) -> PyVal {
    match s.default.as_slice() {
        [one] => lit_py(one),
        many => PyVal::Tuple(
            many.iter()
                .map(|l| SpVal {
                    v: lit_py(l),
                    span: Span::default(),
                })
                .collect(),
        ),
    }
}

fn lit_py(l: &Lit) -> PyVal {
    match l {
        Lit::Int(i) => PyVal::Int(*i),
        Lit::Real(r) => PyVal::Real(*r),
        Lit::Text(t) => PyVal::Str(t.to_string()),
    }
}

fn lit_matches(l: &Lit, v: &Value) -> bool {
    match (l, v) {
        (Lit::Text(a), Value::Text(b)) => a == b,
        (Lit::Int(a), Value::Int(b)) => a == b,
        (Lit::Int(a), Value::Real(b)) => *a as f64 == *b,
        (Lit::Real(a), Value::Real(b)) => a == b,
        (Lit::Real(a), Value::Int(b)) => *a == *b as f64,
        _ => false,
    }
}

/// The message of a violated rule, or None.
pub fn rule_violation(r: &Rule, present: &[&str]) -> Option<String> {
    let has = |k: &&str| present.contains(k);
    let count = |ks: &[&str]| ks.iter().filter(|k| present.contains(k)).count();
    let list = |ks: &[&str]| ks.join(", ");
    match r {
        Rule::ExactlyOne(ks) => {
            let n = count(ks);
            (n != 1).then(|| {
                if n == 0 {
                    format!("exactly one of {} must be given, none is", list(ks))
                } else {
                    let g: Vec<&str> = ks.iter().copied().filter(|k| has(k)).collect();
                    format!(
                        "exactly one of {} must be given, but {} are",
                        list(ks),
                        g.join(" and ")
                    )
                }
            })
        }
        Rule::AtLeastOne(ks) => {
            (!ks.iter().any(has)).then(|| format!("at least one of {} must be given", list(ks)))
        }
        Rule::Exclusive(ks) => {
            let g: Vec<&str> = ks.iter().copied().filter(|k| has(k)).collect();
            (g.len() > 1).then(|| {
                format!(
                    "{} exclude each other (at most one of {} may be given)",
                    g.join(" and "),
                    list(ks)
                )
            })
        }
        Rule::Together(ks) => {
            let n = count(ks);
            (n != 0 && n != ks.len()).then(|| {
                let missing: Vec<&str> = ks.iter().copied().filter(|k| !has(k)).collect();
                format!("{} go together: missing {}", list(ks), missing.join(", "))
            })
        }
        Rule::IfPresentAllPresent(first, others) => {
            if !has(first) {
                return None;
            }
            let missing: Vec<&str> = others.iter().copied().filter(|k| !has(k)).collect();
            (!missing.is_empty())
                .then(|| format!("{first} requires {} as well", missing.join(", ")))
        }
        Rule::IfPresentAllAbsent(first, others) => {
            if !has(first) {
                return None;
            }
            let bad: Vec<&str> = others.iter().copied().filter(|k| has(k)).collect();
            (!bad.is_empty()).then(|| format!("{first} excludes {}", bad.join(", ")))
        }
    }
}
