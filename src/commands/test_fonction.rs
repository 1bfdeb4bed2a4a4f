//! TEST_FONCTION VALEUR: checks the value of a function at a parameter
//! value, the way TEST_RESU checks a field, so that a study can verify
//! the curves of RECU_FONCTION and CALC_FONCTION against a reference,
//! and a FORMULE at one or two parameter values (code_aster's catalogue
//! takes both, NOM_PARA and VALE_PARA up to two values).

use super::blocks::*;
use super::post_args::{function_of, report_checks, run_checks, test_spec};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::{ConceptData, ConceptType as C};
use crate::post::test_report::{function_block, Value};
use crate::study::Study;

pub fn def() -> CommandDef {
    let (refe_kws, refe_rules) = c_test_reference(false, false);
    let mut kws = vec![
        concept("FONCTION", &[C::Fonction, C::Formule]).required().kw(),
        real("VALE_PARA")
            .required()
            .many()
            .doc("the parameter value(s) the function is evaluated at (its interpolation and extensions apply); a formula takes one per parameter")
            .kw(),
        text("NOM_PARA")
            .many()
            .doc("the parameter names, checked against the function's; for a formula, the order of VALE_PARA (NOM_PARA of the FORMULE by default)")
            .kw(),
    ];
    // TYPE_TEST aggregates fields and columns; a function value has none.
    kws.extend(refe_kws.into_iter().filter(|k| k.name() != "TYPE_TEST"));
    let valeur = fact("VALEUR", kws)
        .rules(refe_rules)
        .required()
        .many()
        .doc("one value of a function, tested")
        .kw();
    let attribut = fact(
        "ATTRIBUT",
        vec![
            concept("FONCTION", &[C::Fonction]).required().kw(),
            text("ATTR").required().kw(),
            text("ATTR_REFE").required().kw(),
            text("REFERENCE").kw(),
        ],
    )
    .many()
    .doc("not built")
    .kw();
    let spec = command("TEST_FONCTION", Produces::Nothing, vec![valeur, attribut])
        .doc("Tests values of functions against VALE_CALC (non-regression) and VALE_REFE.");
    CommandDef { spec, exec }
}

fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    if args.has("ATTRIBUT") {
        return Err(args.not_implemented("ATTRIBUT", "VALEUR is built"));
    }
    for occ in args.facts("VALEUR") {
        let spec = test_spec(occ)?;
        let xs = occ.reals("VALE_PARA");
        let names = occ.texts("NOM_PARA");
        if xs.len() > 2 || names.len() > 2 {
            return Err(occ.error(
                "VALE_PARA",
                "VALE_PARA and NOM_PARA take at most two values",
            ));
        }
        let fname = occ.concept("FONCTION").unwrap_or_default();
        let (block_name, para, y, at) = match study.concepts.data(fname) {
            Some(ConceptData::Formula(g)) => {
                let para: Vec<&str> = if names.is_empty() {
                    g.params.iter().map(String::as_str).collect()
                } else {
                    names.clone()
                };
                if para.len() != xs.len() {
                    return Err(occ.error(
                        "VALE_PARA",
                        format!(
                            "{} values for the parameters {} of {fname}: one value per parameter",
                            xs.len(),
                            para.join(", ")
                        ),
                    ));
                }
                let values: Vec<(&str, f64)> =
                    para.iter().copied().zip(xs.iter().copied()).collect();
                let y = g.eval(&values).map_err(|m| occ.error("VALE_PARA", m))?;
                (fname.to_string(), para.join(", "), y, xs.clone())
            }
            _ => {
                let (name, f) = function_of(study, occ, "FONCTION")?;
                let [x] = xs[..] else {
                    return Err(occ.error(
                        "VALE_PARA",
                        format!(
                            "{name} is a function of one parameter ({}): one VALE_PARA",
                            f.para
                        ),
                    ));
                };
                if let [p] = names[..] {
                    if p != f.para && !f.is_constant() {
                        return Err(occ.error(
                            "NOM_PARA",
                            format!("{name} is a function of {}, not of {p}", f.para),
                        ));
                    }
                } else if !names.is_empty() {
                    return Err(occ.error(
                        "NOM_PARA",
                        format!("{name} is a function of one parameter ({})", f.para),
                    ));
                }
                let y = f.eval(x).map_err(|m| occ.error("VALE_PARA", m))?;
                (name.to_string(), f.para.clone(), y, vec![x])
            }
        };
        let lines = run_checks(occ, &spec, &Value::Real(y))?;
        let block = function_block(&block_name, &para, &at, &lines);
        report_checks(study, occ, &block, &lines);
    }
    Ok(None)
}
