//! DEFI_CONSTANTE: a constant function.

use super::blocks::*;
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::{ConceptData, ConceptType as C};
use crate::study::Study;

pub fn def() -> CommandDef {
    let spec = command(
        "DEFI_CONSTANTE",
        Produces::Concept(C::Fonction),
        vec![
            text("NOM_RESU")
                .default(t("TOUTRESU"))
                .doc("name of the function's value")
                .kw(),
            real("VALE")
                .required()
                .doc("the constant, returned whatever the parameters")
                .kw(),
            titre(),
        ],
    )
    .doc("Defines a function returning VALE for any parameter (TOUTPARA), constant extrapolation.");
    CommandDef { spec, exec }
}

fn exec(_study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    let v = args
        .real("VALE")
        .ok_or_else(|| args.error("VALE", "VALE is missing"))?;
    let nom_resu = args.text("NOM_RESU").unwrap_or("TOUTRESU");
    Ok(Some(ConceptData::Function(Box::new(
        crate::post::function::Function::constant(v, nom_resu),
    ))))
}
