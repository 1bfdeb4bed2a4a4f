//! FORMULE: a function given by an expression of its parameters, in the
//! command file's (Python) syntax: arithmetic on reals (+ - * / **, unary
//! minus), the math functions and constants code_aster puts in a
//! formula's namespace, NOM_PARA, and numbers given as extra keywords
//! (`H=H`) or defined earlier in the command file (the checker gathers
//! them into CONST_NOMS/CONST_VALE). Only the
//! commands that evaluate code_aster's "function-like" arguments by
//! parameter name take a formula (LIAISON_UNIL's COEF_IMPO and COEF_MULT,
//! AFFE_CHAR_MECA_F's values);
//! the others ask for a fonction_sdaster and refuse it by its type.

use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::{ConceptData, ConceptType as C};
use crate::diag::Source;
use crate::lang::ast::{BinOp, Expr, ExprKind, StmtKind, UnOp};
use crate::post::formula::{Formula, Func, Node, Op, CONSTANTS};
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
        ],
    )
    .doc("Defines a function by an expression of its parameters (constants of the command file are written as numbers).");
    CommandDef { spec, exec }
}

fn exec(_study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
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
    let f = parse(vale, &params, &consts).map_err(|m| args.error("VALE", m))?;
    Ok(Some(ConceptData::Formula(Box::new(f))))
}

/// VALE → the formula's tree, every name checked; `consts` are the
/// values of the other names (FORMULE's extra keywords, command-file
/// variables).
pub fn parse(text: &str, params: &[String], consts: &[(String, f64)]) -> Result<Formula, String> {
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
    let node = tree(expr, text, params, consts)?;
    Ok(Formula {
        params: params.to_vec(),
        text: text.to_string(),
        node,
    })
}

fn tree(e: &Expr, text: &str, params: &[String], consts: &[(String, f64)]) -> Result<Node, String> {
    Ok(match &e.kind {
        ExprKind::Int(i) => Node::Num(*i as f64),
        ExprKind::Real(r) => Node::Num(*r),
        ExprKind::Name(n) => {
            if let Some(i) = params.iter().position(|p| p == n) {
                Node::Param(i)
            } else if let Some(c) = consts.iter().find(|c| &c.0 == n) {
                Node::Num(c.1)
            } else if let Some(c) = CONSTANTS.iter().find(|c| c.0 == n) {
                Node::Num(c.1)
            } else {
                return Err(format!(
                    "name '{n}' in VALE '{text}' is neither a parameter of NOM_PARA ({}), a number of the command file or of FORMULE's keywords, nor a math constant (pi, e)",
                    params.join(", ")
                ));
            }
        }
        ExprKind::Unary { op, operand } => {
            let a = tree(operand, text, params, consts)?;
            match op {
                UnOp::Neg => Node::Neg(Box::new(a)),
                UnOp::Pos => a,
                UnOp::Not => {
                    return Err(format!(
                        "'not' in VALE '{text}': a FORMULE computes a real from reals"
                    ))
                }
            }
        }
        ExprKind::Binary { op, lhs, rhs } => {
            let op = match op {
                BinOp::Add => Op::Add,
                BinOp::Sub => Op::Sub,
                BinOp::Mul => Op::Mul,
                BinOp::Div => Op::Div,
                BinOp::Pow => Op::Pow,
                BinOp::FloorDiv | BinOp::Mod => {
                    return Err(format!(
                        "operator '{}' in VALE '{text}' is not available in a FORMULE (+ - * / **)",
                        op.symbol()
                    ))
                }
            };
            Node::Bin(
                op,
                Box::new(tree(lhs, text, params, consts)?),
                Box::new(tree(rhs, text, params, consts)?),
            )
        }
        ExprKind::Call { func, args } => {
            let n = func.name.as_str();
            let Some((f, arity)) = Func::of_name(n) else {
                return Err(format!(
                    "function '{n}' in VALE '{text}' is not available in a FORMULE (math functions: {})",
                    Func::NAMES
                ));
            };
            let ok = match arity {
                Some(k) => args.len() == k,
                None => !args.is_empty(),
            };
            if !ok || args.iter().any(|a| a.name.is_some()) {
                return Err(format!("wrong arguments for '{n}' in VALE '{text}'"));
            }
            let xs = args
                .iter()
                .map(|a| tree(&a.value, text, params, consts))
                .collect::<Result<_, _>>()?;
            Node::Call(f, xs)
        }
        _ => return Err(format!("VALE '{text}' must compute a real from reals")),
    })
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
}
