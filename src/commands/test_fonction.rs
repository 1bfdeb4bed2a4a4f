//! TEST_FONCTION VALEUR: checks the value of a function at a parameter
//! value, the way TEST_RESU checks a field, so that a study can verify
//! the curves of RECU_FONCTION and CALC_FONCTION against a reference.

use super::blocks::*;
use super::post_args::{function_of, report_checks, run_checks, test_spec};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;
use crate::post::test_report::{function_block, Value};
use crate::study::Study;

pub fn def() -> CommandDef {
    let (refe_kws, refe_rules) = c_test_reference(false, false);
    let mut kws = vec![
        concept("FONCTION", &[C::Fonction]).required().kw(),
        real("VALE_PARA")
            .required()
            .doc("the parameter value the function is evaluated at (its interpolation and extensions apply)")
            .kw(),
        text("NOM_PARA").doc("the parameter's name, checked against the function's").kw(),
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
        let (name, f) = function_of(study, occ, "FONCTION")?;
        let x = occ.real("VALE_PARA").unwrap_or(0.0);
        if let Some(p) = occ.text("NOM_PARA") {
            if p != f.para && !f.is_constant() {
                return Err(occ.error(
                    "NOM_PARA",
                    format!("{name} is a function of {}, not of {p}", f.para),
                ));
            }
        }
        let y = f.eval(x).map_err(|m| occ.error("VALE_PARA", m))?;
        let block_name = name.to_string();
        let para = f.para.clone();
        let lines = run_checks(occ, &spec, &Value::Real(y))?;
        let block = function_block(&block_name, &para, x, &lines);
        report_checks(study, occ, &block, &lines);
    }
    Ok(None)
}
