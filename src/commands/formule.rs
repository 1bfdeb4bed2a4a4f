//! FORMULE: a function given by an expression of its parameters, in the
//! command file's (Python) syntax: arithmetic on reals (+ - * / // % **,
//! unary signs), comparisons, `and`/`or`/`not` and `x if c else y` with
//! Python's booleans as 1 and 0 (Heaviside steps are written
//! `(INST > T1) * F`), the real functions of reals and the constants of
//! code_aster's formula namespace (every name of `math`, and the
//! builtins abs, min, max, float, int, round, pow), NOM_PARA, and numbers given as extra keywords
//! (`H=H`) or defined earlier in the command file (the checker gathers
//! them into CONST_NOMS/CONST_VALE), and functions called by name,
//! DEFI_FONCTION/DEFI_CONSTANTE/RECU_FONCTION results or other formulas
//! given the same two ways (`VALE='GAM(INST) * Z', GAM=GAM`; gathered
//! into FONC_NOMS/FONC_VALE). Only the
//! commands that evaluate code_aster's "function-like" arguments by
//! parameter name take a formula (LIAISON_UNIL's COEF_IMPO and COEF_MULT,
//! AFFE_CHAR_MECA_F's values);
//! the others ask for a fonction_sdaster and refuse it by its type.

use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::{ConceptData, ConceptType as C};
use crate::diag::Source;
use crate::lang::ast::{BinOp, CmpOp, Expr, ExprKind, LogicOp, StmtKind, UnOp};
use crate::post::formula::{Cmp, Coef, Formula, Func, Node, Op, CONSTANTS};
use crate::study::Study;

pub fn def() -> CommandDef {
    let spec = command(
        "FORMULE",
        Produces::Concept(C::Formule),
        vec![
            text("VALE")
                .required()
                .doc("the expression, in Python syntax, of the parameters and math functions")
                .kw(),
            text("NOM_PARA")
                .required()
                .many()
                .doc("the parameters (INST, X, Y, Z...)")
                .kw(),
            // The constants of VALE: extra keywords (H=H) or command-file
            // variables, gathered by the checker.
            text("CONST_NOMS").many().hidden().kw(),
            real("CONST_VALE").many().hidden().kw(),
            // The functions VALE calls, gathered the same way.
            text("FONC_NOMS").many().hidden().kw(),
            concept("FONC_VALE", &[C::Fonction, C::Formule])
                .many()
                .hidden()
                .kw(),
        ],
    )
    .doc("Defines a function by an expression of its parameters (constants of the command file are written as numbers).");
    CommandDef { spec, exec }
}

fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    let vale = args.text("VALE").unwrap_or_default();
    let params: Vec<String> = args
        .texts("NOM_PARA")
        .iter()
        .map(|s| s.to_string())
        .collect();
    let consts: Vec<(String, f64)> = args
        .texts("CONST_NOMS")
        .iter()
        .map(|s| s.to_string())
        .zip(args.reals("CONST_VALE"))
        .collect();
    let mut callees = Vec::new();
    for (name, concept) in args
        .texts("FONC_NOMS")
        .iter()
        .zip(args.concepts("FONC_VALE"))
    {
        let f = match study.concepts.data(concept) {
            Some(ConceptData::Function(f)) => Coef::Function((**f).clone()),
            Some(ConceptData::Formula(g)) => Coef::Formula((**g).clone()),
            _ => {
                return Err(args.error(
                    "VALE",
                    format!("{name} = {concept} holds no function (its command did not run)"),
                ))
            }
        };
        callees.push((name.to_string(), f));
    }
    let f = parse_calling(vale, &params, &consts, callees).map_err(|m| args.error("VALE", m))?;
    Ok(Some(ConceptData::Formula(Box::new(f))))
}

/// VALE → the formula's tree, every name checked; `consts` are the
/// values of the other names (FORMULE's extra keywords, command-file
/// variables).
pub fn parse(text: &str, params: &[String], consts: &[(String, f64)]) -> Result<Formula, String> {
    parse_calling(text, params, consts, Vec::new())
}

/// [`parse`], VALE calling the functions `callees` by their names.
pub fn parse_calling(
    text: &str,
    params: &[String],
    consts: &[(String, f64)],
    callees: Vec<(String, Coef)>,
) -> Result<Formula, String> {
    let src = Source::new("VALE", format!("F__ = ({text})\n"));
    let program = crate::lang::parser::parse(&src)
        .map_err(|d| format!("VALE '{text}' is not an expression: {}", d.message))?;
    let expr = match program.stmts.as_slice() {
        [s] => match &s.kind {
            StmtKind::Assign { value, .. } => value,
            _ => return Err(format!("VALE '{text}' is not an expression")),
        },
        _ => return Err(format!("VALE '{text}' is not one expression")),
    };
    let names = Names {
        text,
        params,
        consts,
        callees: &callees,
    };
    let node = names.tree(expr)?;
    Ok(Formula {
        params: params.to_vec(),
        text: text.to_string(),
        node,
        callees,
    })
}

/// What the names of VALE can be.
struct Names<'a> {
    text: &'a str,
    params: &'a [String],
    consts: &'a [(String, f64)],
    callees: &'a [(String, Coef)],
}

impl Names<'_> {
    fn tree(&self, e: &Expr) -> Result<Node, String> {
        let text = self.text;
        Ok(match &e.kind {
            ExprKind::Int(i) => Node::Num(*i as f64),
            ExprKind::Real(r) => Node::Num(*r),
            ExprKind::Name(n) => {
                if let Some(i) = self.params.iter().position(|p| p == n) {
                    Node::Param(i)
                } else if let Some(c) = self.consts.iter().find(|c| &c.0 == n) {
                    Node::Num(c.1)
                } else if let Some(c) = CONSTANTS.iter().find(|c| c.0 == n) {
                    Node::Num(c.1)
                } else if self.callees.iter().any(|c| &c.0 == n) {
                    return Err(format!(
                        "'{n}' in VALE '{text}' is a function: call it with its parameter, as {n}(INST)"
                    ));
                } else {
                    return Err(format!(
                        "name '{n}' in VALE '{text}' is neither a parameter of NOM_PARA ({}), a number of the command file or of FORMULE's keywords, a function passed as a keyword ({n}={n}), nor a math constant (pi, e)",
                        self.params.join(", ")
                    ));
                }
            }
            ExprKind::Unary { op, operand } => {
                let a = self.tree(operand)?;
                match op {
                    UnOp::Neg => Node::Neg(Box::new(a)),
                    UnOp::Pos => a,
                    UnOp::Not => Node::Not(Box::new(a)),
                }
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let op = match op {
                    BinOp::Add => Op::Add,
                    BinOp::Sub => Op::Sub,
                    BinOp::Mul => Op::Mul,
                    BinOp::Div => Op::Div,
                    BinOp::Pow => Op::Pow,
                    BinOp::Mod => Op::Mod,
                    BinOp::FloorDiv => Op::FloorDiv,
                };
                Node::Bin(op, Box::new(self.tree(lhs)?), Box::new(self.tree(rhs)?))
            }
            ExprKind::Call { func, args } => {
                let n = func.name.as_str();
                // A function passed by the user hides a math function of
                // the same name, as a Python keyword argument would.
                let callee = self.callees.iter().position(|c| c.0 == n);
                let arity = match callee {
                    Some(i) => {
                        let k = self.callees[i].1.arity();
                        (k, Some(k))
                    }
                    None => match Func::of_name(n) {
                        Some((_, least, most)) => (least, most),
                        None => {
                            return Err(format!(
                                "function '{n}' in VALE '{text}' is not available in a FORMULE (math functions: {}; a DEFI_FONCTION or FORMULE is called by the name of the keyword that passes it, as {n}={n})",
                                Func::NAMES
                            ))
                        }
                    },
                };
                let ok = args.len() >= arity.0 && arity.1.is_none_or(|most| args.len() <= most);
                if !ok || args.iter().any(|a| a.name.is_some() || a.unpack) {
                    let expected = match arity {
                        (least, Some(most)) if least == most => format!(" ({n} takes {least})"),
                        (least, Some(most)) => format!(" ({n} takes {least} to {most})"),
                        (least, None) => format!(" ({n} takes at least {least})"),
                    };
                    return Err(format!(
                        "wrong arguments for '{n}' in VALE '{text}'{expected}"
                    ));
                }
                let xs = args
                    .iter()
                    .map(|a| self.tree(&a.value))
                    .collect::<Result<_, _>>()?;
                match callee {
                    Some(i) => Node::Apply(i, xs),
                    None => Node::Call(Func::of_name(n).expect("checked above").0, xs),
                }
            }
            ExprKind::Bool(b) => Node::Num(f64::from(u8::from(*b))),
            ExprKind::Compare { first, rest } => {
                let mut links = Vec::with_capacity(rest.len());
                for (op, operand) in rest {
                    let cmp = match op {
                        CmpOp::Eq => Cmp::Eq,
                        CmpOp::Ne => Cmp::Ne,
                        CmpOp::Lt => Cmp::Lt,
                        CmpOp::Le => Cmp::Le,
                        CmpOp::Gt => Cmp::Gt,
                        CmpOp::Ge => Cmp::Ge,
                        CmpOp::In | CmpOp::NotIn => {
                            return Err(format!(
                                "'{}' in VALE '{text}': a FORMULE computes a real from reals (comparisons < <= > >= == != are available)",
                                op.symbol()
                            ))
                        }
                    };
                    links.push((cmp, self.tree(operand)?));
                }
                Node::Compare(Box::new(self.tree(first)?), links)
            }
            ExprKind::Logic { op, lhs, rhs } => {
                let (a, b) = (Box::new(self.tree(lhs)?), Box::new(self.tree(rhs)?));
                match op {
                    LogicOp::And => Node::And(a, b),
                    LogicOp::Or => Node::Or(a, b),
                }
            }
            ExprKind::IfElse { cond, then, orelse } => Node::IfElse(
                Box::new(self.tree(cond)?),
                Box::new(self.tree(then)?),
                Box::new(self.tree(orelse)?),
            ),
            _ => return Err(format!("VALE '{text}' must compute a real from reals (numbers, the parameters, + - * / // % **, comparisons, and/or/not, x if c else y, and the functions {})", Func::NAMES)),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn f(text: &str, params: &[&str]) -> Result<Formula, String> {
        let p: Vec<String> = params.iter().map(|s| s.to_string()).collect();
        parse(text, &p, &[("H".to_string(), 2.0)])
    }

    #[test]
    fn arithmetic_and_math_functions() {
        let g = f("2.27 - 0.1 * X + Y ** 2 / 4", &["X", "Y"]).unwrap();
        let v = g
            .eval(&[("INST", 9.0), ("X", 3.2), ("Y", 2.0), ("Z", 0.0)])
            .unwrap();
        assert!((v - (2.27 - 0.32 + 1.0)).abs() < 1e-15);
        let h = f(
            "sqrt(X) * cos(pi * INST) + max(1, X, 2) - abs(-3) + 1/2",
            &["X", "INST"],
        )
        .unwrap();
        let v = h.eval(&[("X", 4.0), ("INST", 1.0)]).unwrap();
        assert!((v - (-2.0 + 4.0 - 3.0 + 0.5)).abs() < 1e-15, "{v}");
    }

    #[test]
    fn bad_formulas_are_refused_with_the_reason() {
        assert_eq!(f("H - X", &["X"]).unwrap().eval(&[("X", 0.5)]), Ok(1.5));
        let e = f("G - X", &["X"]).unwrap_err();
        assert!(e.contains("name 'G'") && e.contains("NOM_PARA (X)"), "{e}");
        assert!(f("foo(X)", &["X"]).unwrap_err().contains("function 'foo'"));
        assert!(f("atan2(X)", &["X"])
            .unwrap_err()
            .contains("wrong arguments"));
        assert!(f("X +", &["X"]).unwrap_err().contains("not an expression"));
        assert!(f("'a'", &["X"]).unwrap_err().contains("real"));
        let g = f("1 / X", &["X"]).unwrap();
        assert!(g
            .eval(&[("X", 0.0)])
            .unwrap_err()
            .contains("division by zero"));
        assert!(g.eval(&[("INST", 0.0)]).unwrap_err().contains("needs X"));
        let s = f("sqrt(X)", &["X"]).unwrap();
        assert!(s.eval(&[("X", -1.0)]).unwrap_err().contains("not finite"));
    }

    #[test]
    fn calls_of_functions_and_formulas_are_checked_and_evaluated() {
        use crate::post::function::Function;
        let ramp = Function::new("INST", "TOUTRESU", vec![0.0, 1.0], vec![0.0, 2.0]).unwrap();
        let callees = || vec![("RP".to_string(), Coef::Function(ramp.clone()))];
        let p = vec!["INST".to_string()];
        let g = parse_calling("RP(INST) * 3", &p, &[], callees()).unwrap();
        assert_eq!(g.eval(&[("INST", 0.25)]), Ok(1.5));
        // A formula calling that formula, positionally.
        let h = parse_calling(
            "G(INST / 2) + 1",
            &p,
            &[],
            vec![("G".to_string(), Coef::Formula(g.clone()))],
        )
        .unwrap();
        assert_eq!(h.eval(&[("INST", 0.5)]), Ok(2.5));
        let e = parse_calling("RP(INST, 1)", &p, &[], callees()).unwrap_err();
        assert!(
            e.contains("wrong arguments for 'RP'") && e.contains("RP takes 1"),
            "{e}"
        );
        let e = parse_calling("RP + 1", &p, &[], callees()).unwrap_err();
        assert!(e.contains("'RP'") && e.contains("is a function"), "{e}");
        let e = parse_calling("GAM(INST)", &p, &[], callees()).unwrap_err();
        assert!(e.contains("function 'GAM'") && e.contains("GAM=GAM"), "{e}");
        // The ramp is excluded outside [0, 1]: the message names the callee.
        let e = g.eval(&[("INST", 2.0)]).unwrap_err();
        assert!(
            e.starts_with("RP, called by the formula 'RP(INST) * 3'"),
            "{e}"
        );
    }

    /// Each formula against the value CPython 3 gives for the same text
    /// (printed with repr, the values written here as Python printed them).
    #[test]
    fn python_operators_comparisons_and_conditionals() {
        let p = ["INST", "X"];
        let at = |text: &str, inst: f64, x: f64| -> f64 {
            f(text, &p)
                .unwrap_or_else(|e| panic!("{text}: {e}"))
                .eval(&[("INST", inst), ("X", x)])
                .unwrap_or_else(|e| panic!("{text}: {e}"))
        };
        // Heaviside steps, as load ramps are written.
        assert_eq!(at("(INST > 0.5) * 2.", 0.75, 0.0), 2.0);
        assert_eq!(at("(INST > 0.5) * 2.", 0.5, 0.0), 0.0);
        assert_eq!(at("INST if INST < 1. else 1.", 0.25, 0.0), 0.25);
        assert_eq!(at("INST if INST < 1. else 1.", 3.0, 0.0), 1.0);
        // Chained, stopping at the first false link; a bare comparison.
        assert_eq!(at("0. <= X < 1.", 0.0, 1.0), 0.0);
        assert_eq!(at("0. <= X < 1.", 0.0, 0.5), 1.0);
        assert_eq!(at("X == 2", 0.0, 2.0), 1.0);
        assert_eq!(at("(X != 2) + (X >= 2) + (X <= 2)", 0.0, 2.0), 2.0);
        // and / or give an operand; not gives a boolean.
        assert_eq!(at("X and 3.", 0.0, 0.0), 0.0);
        assert_eq!(at("X and 3.", 0.0, 2.0), 3.0);
        assert_eq!(at("X or 3.", 0.0, 2.0), 2.0);
        assert_eq!(at("not X", 0.0, 0.0), 1.0);
        assert_eq!(at("True + False * 2", 0.0, 0.0), 1.0);
        // Only the branch taken is evaluated: no division by zero here.
        assert_eq!(at("1. / X if X != 0. else 0.", 0.0, 0.0), 0.0);
        assert_eq!(at("sqrt(X) if X > 0 else -1.", 0.0, -4.0), -1.0);
        // % and // of reals: the divisor's sign, divmod's floor.
        assert_eq!(at("X % 3", 0.0, -7.0), 2.0);
        assert_eq!(at("X % -3", 0.0, 7.0), -2.0);
        assert_eq!(at("X // 0.1", 0.0, 7.0), 69.0);
        assert_eq!(at("X // 2", 0.0, -7.0), -4.0);
        assert_eq!(at("INST % 1.E-5", 2.5e-5, 0.0), 4.9999999999999996e-06);
        // The rest of math and the builtins.
        assert_eq!(
            at("floor(X) + ceil(X) + trunc(-X) + int(-X)", 0.0, 2.5),
            1.0
        );
        assert_eq!(at("round(X) + round(-X)", 0.0, 2.5), 0.0);
        assert_eq!(at("round(X, 2)", 0.0, 2.675), 2.67);
        assert_eq!(at("round(X, -2)", 0.0, 1250.0), 1200.0);
        assert_eq!(at("fabs(X) + pow(X, 2) + hypot(3, 4)", 0.0, -2.0), 11.0);
        assert_eq!(at("fmod(X, 3)", 0.0, -7.0), -1.0);
        assert_eq!(at("copysign(2., X)", 0.0, -0.0), -2.0);
        assert_eq!(
            at(
                "log(X, 2) + log2(X) + degrees(pi) - radians(180.)",
                0.0,
                8.0
            ),
            6.0 + 180.0 - std::f64::consts::PI
        );
        assert!(
            (at("tau - 2 * pi + cbrt(X) + expm1(0.) + log1p(0.)", 0.0, 27.0) - 3.0).abs() < 1e-15
        );
        // What stays refused says what is available.
        let e = f("X in (1, 2)", &p).unwrap_err();
        assert!(e.contains("'in'") && e.contains("comparisons"), "{e}");
        let e = f("'a' + X", &p).unwrap_err();
        assert!(
            e.contains("must compute a real") && e.contains("floor"),
            "{e}"
        );
        let e = f("round(X, 1, 2)", &p).unwrap_err();
        assert!(e.contains("round takes 1 to 2"), "{e}");
        let g = f("X % 0.", &p).unwrap();
        assert!(g
            .eval(&[("INST", 0.0), ("X", 1.0)])
            .unwrap_err()
            .contains("division by zero"));
        let g = f("fmod(X, 0.)", &p).unwrap();
        assert!(g
            .eval(&[("INST", 0.0), ("X", 1.0)])
            .unwrap_err()
            .contains("not finite"));
    }
}
