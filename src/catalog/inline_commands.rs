//! Commands called inside another command's keywords.
//!
//! Python lets a command file write `ARCHIVAGE=_F(LIST_INST=DEFI_LIST_REEL(
//! VALE=(0., 1.)))` or `FONC_MULT=DEFI_FONCTION(...)`: the inner command runs
//! first and its concept, which has no name of its own, is what the keyword
//! receives. code_aster's test files do this often, so users' studies do
//! too. The checker works on statements that bind one command's result to a
//! name, so such a file is first rewritten into that form: each inner call
//! becomes a statement of its own, just before the statement it was in,
//! binding a name the file cannot use (it is not an identifier a user would
//! write, and is checked against every name the file binds), and the call is
//! replaced by that name. Inner calls are hoisted innermost first, in source
//! order, which is the order Python evaluates them in.
//!
//! Two places are left alone, because hoisting would change what runs: a
//! call inside a list comprehension (it may read the comprehension's
//! variable, and runs once per item) and one in a branch that Python may
//! not evaluate (`x if c else y`, `a and b`, `a or b`). The evaluator refuses
//! those with a located error that says to name the result first.

use std::collections::HashSet;

use crate::lang::ast::{Expr, ExprKind, Ident, Program, Stmt, StmtKind};

/// The program with every hoistable inner command call moved into a
/// statement of its own. `is_command` says which called names are commands.
pub fn hoist(program: &Program, is_command: &dyn Fn(&str) -> bool) -> Program {
    let mut taken = HashSet::new();
    bound_names(&program.stmts, &mut taken);
    let mut h = Hoister {
        is_command,
        taken,
        count: 0,
    };
    Program {
        stmts: h.block(&program.stmts),
    }
}

struct Hoister<'a> {
    is_command: &'a dyn Fn(&str) -> bool,
    /// Every name the file binds, so a generated name never shadows one.
    taken: HashSet<String>,
    count: usize,
}

impl Hoister<'_> {
    fn block(&mut self, stmts: &[Stmt]) -> Vec<Stmt> {
        let mut out = Vec::with_capacity(stmts.len());
        for s in stmts {
            let mut before = Vec::new();
            let kind = match &s.kind {
                StmtKind::Assign { target, value } => StmtKind::Assign {
                    target: target.clone(),
                    value: self.top(value, &mut before),
                },
                StmtKind::Expr(e) => StmtKind::Expr(self.top(e, &mut before)),
                // A command's result stored in an item is refused by the
                // checker (its concept would have no name): kept as written.
                StmtKind::SetItem {
                    target,
                    index,
                    value,
                } => StmtKind::SetItem {
                    target: target.clone(),
                    index: self.inner(index, &mut before),
                    value: self.top(value, &mut before),
                },
                StmtKind::Unpack { targets, value } => StmtKind::Unpack {
                    targets: targets.clone(),
                    value: self.inner(value, &mut before),
                },
                StmtKind::AugAssign { target, op, value } => StmtKind::AugAssign {
                    target: target.clone(),
                    op: *op,
                    value: self.inner(value, &mut before),
                },
                StmtKind::If { branches, orelse } => {
                    // Only the first condition is always evaluated; later
                    // ones keep their calls (refused if they are commands).
                    let branches = branches
                        .iter()
                        .enumerate()
                        .map(|(i, (c, body))| {
                            let c = if i == 0 {
                                self.inner(c, &mut before)
                            } else {
                                c.clone()
                            };
                            (c, self.block(body))
                        })
                        .collect();
                    StmtKind::If {
                        branches,
                        orelse: self.block(orelse),
                    }
                }
                StmtKind::For { target, iter, body } => StmtKind::For {
                    target: target.clone(),
                    iter: self.inner(iter, &mut before),
                    body: self.block(body),
                },
                k @ (StmtKind::Pass | StmtKind::Import(_) | StmtKind::FromImport { .. }) => {
                    k.clone()
                }
            };
            out.extend(before);
            out.push(Stmt { kind, span: s.span });
        }
        out
    }

    /// A statement's own expression: a command call here is the statement's
    /// command (kept), only its arguments are searched.
    fn top(&mut self, e: &Expr, before: &mut Vec<Stmt>) -> Expr {
        match &e.kind {
            ExprKind::Call { func, args } if (self.is_command)(&func.name) => Expr {
                kind: ExprKind::Call {
                    func: func.clone(),
                    args: self.args(args, before),
                },
                span: e.span,
            },
            _ => self.inner(e, before),
        }
    }

    fn args(
        &mut self,
        args: &[crate::lang::ast::Arg],
        before: &mut Vec<Stmt>,
    ) -> Vec<crate::lang::ast::Arg> {
        args.iter()
            .map(|a| crate::lang::ast::Arg {
                name: a.name.clone(),
                unpack: a.unpack,
                value: self.inner(&a.value, before),
                span: a.span,
            })
            .collect()
    }

    /// An expression inside a statement: command calls in it are hoisted.
    fn inner(&mut self, e: &Expr, before: &mut Vec<Stmt>) -> Expr {
        let kind = match &e.kind {
            ExprKind::Call { func, args } => {
                let args = self.args(args, before);
                if (self.is_command)(&func.name) {
                    let name = self.fresh(&func.name);
                    let target = Ident {
                        name: name.clone(),
                        span: func.span,
                    };
                    before.push(Stmt {
                        kind: StmtKind::Assign {
                            target,
                            value: Expr {
                                kind: ExprKind::Call {
                                    func: func.clone(),
                                    args,
                                },
                                span: e.span,
                            },
                        },
                        span: e.span,
                    });
                    ExprKind::Name(name)
                } else {
                    ExprKind::Call {
                        func: func.clone(),
                        args,
                    }
                }
            }
            ExprKind::Tuple(items) => ExprKind::Tuple(self.all(items, before)),
            ExprKind::List(items) => ExprKind::List(self.all(items, before)),
            ExprKind::Dict(items) => ExprKind::Dict(
                items
                    .iter()
                    .map(|(k, v)| {
                        let k = k.as_ref().map(|k| self.inner(k, before));
                        (k, self.inner(v, before))
                    })
                    .collect(),
            ),
            ExprKind::MethodCall {
                value,
                method,
                args,
            } => ExprKind::MethodCall {
                value: Box::new(self.inner(value, before)),
                method: method.clone(),
                args: self.args(args, before),
            },
            ExprKind::Attribute { value, attr } => ExprKind::Attribute {
                value: Box::new(self.inner(value, before)),
                attr: attr.clone(),
            },
            ExprKind::Index { value, index } => ExprKind::Index {
                value: Box::new(self.inner(value, before)),
                index: Box::new(self.inner(index, before)),
            },
            ExprKind::Slice {
                value,
                lower,
                upper,
                step,
            } => {
                let value = Box::new(self.inner(value, before));
                let lower = self.opt(lower, before);
                let upper = self.opt(upper, before);
                let step = self.opt(step, before);
                ExprKind::Slice {
                    value,
                    lower,
                    upper,
                    step,
                }
            }
            ExprKind::Unary { op, operand } => ExprKind::Unary {
                op: *op,
                operand: Box::new(self.inner(operand, before)),
            },
            ExprKind::Binary { op, lhs, rhs } => ExprKind::Binary {
                op: *op,
                lhs: Box::new(self.inner(lhs, before)),
                rhs: Box::new(self.inner(rhs, before)),
            },
            ExprKind::Compare { first, rest } => ExprKind::Compare {
                first: Box::new(self.inner(first, before)),
                rest: rest
                    .iter()
                    .map(|(op, x)| (*op, self.inner(x, before)))
                    .collect(),
            },
            // Evaluated conditionally or once per item: left as written.
            ExprKind::Logic { .. } | ExprKind::IfElse { .. } | ExprKind::ListComp { .. } => {
                e.kind.clone()
            }
            ExprKind::Int(_)
            | ExprKind::Real(_)
            | ExprKind::Str(_)
            | ExprKind::Bool(_)
            | ExprKind::NoneLit
            | ExprKind::Name(_) => e.kind.clone(),
        };
        Expr { kind, span: e.span }
    }

    fn opt(&mut self, e: &Option<Box<Expr>>, before: &mut Vec<Stmt>) -> Option<Box<Expr>> {
        e.as_ref().map(|b| Box::new(self.inner(b, before)))
    }

    fn all(&mut self, items: &[Expr], before: &mut Vec<Stmt>) -> Vec<Expr> {
        items.iter().map(|x| self.inner(x, before)).collect()
    }

    /// A name no statement of the file binds: `_DEFI_LIST_REEL_1`, ... (the
    /// command's name makes the .mess readable where the concept is named).
    fn fresh(&mut self, command: &str) -> String {
        loop {
            self.count += 1;
            let name = format!("_{command}_{}", self.count);
            if self.taken.insert(name.clone()) {
                return name;
            }
        }
    }
}

/// Every name a statement of `stmts` binds, blocks included.
fn bound_names(stmts: &[Stmt], out: &mut HashSet<String>) {
    for s in stmts {
        match &s.kind {
            StmtKind::Assign { target, .. } | StmtKind::AugAssign { target, .. } => {
                out.insert(target.name.clone());
            }
            StmtKind::Unpack { targets, .. } => {
                out.extend(targets.iter().map(|t| t.name.clone()));
            }
            StmtKind::For { target, body, .. } => {
                out.extend(target.names().into_iter().map(|t| t.name.clone()));
                bound_names(body, out);
            }
            StmtKind::If { branches, orelse } => {
                for (_, b) in branches {
                    bound_names(b, out);
                }
                bound_names(orelse, out);
            }
            StmtKind::Import(items) => {
                out.extend(
                    items
                        .iter()
                        .map(|i| i.alias.as_ref().unwrap_or(&i.module).name.clone()),
                );
            }
            StmtKind::FromImport { names, .. } => {
                for (n, a) in names.iter().flatten() {
                    out.insert(a.as_ref().unwrap_or(n).name.clone());
                }
            }
            StmtKind::Expr(_) | StmtKind::Pass | StmtKind::SetItem { .. } => {}
        }
    }
}
