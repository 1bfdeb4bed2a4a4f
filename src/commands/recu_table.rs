//! RECU_TABLE: a table attached to a result, as a table concept.
//!
//! Why: code_aster keeps the energy balance of DYNA_NON_LINE in the
//! result's PARA_CALC table; RECU_TABLE(CO=RESU, NOM_TABLE='PARA_CALC')
//! makes it a table TEST_TABLE and IMPR_TABLE read. Only tables of results
//! exist here (CO of another concept type, or NOM_PARA, are refused).

use super::blocks::*;
use super::post_args::{concept_title, result_of};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::{ConceptData, ConceptType as C};
use crate::study::Study;

pub fn def() -> CommandDef {
    let spec = command(
        "RECU_TABLE",
        Produces::Concept(C::Table),
        vec![
            concept("CO", &[C::EvolNoli])
                .required()
                .doc("the result holding the table")
                .kw(),
            text("NOM_TABLE")
                .doc("name of the result's table (PARA_CALC: the energy balance)")
                .kw(),
            text("NOM_PARA").many().kw(),
            titre(),
        ],
    )
    .doc("Extracts a table attached to a result (PARA_CALC: the energy balance of DYNA_NON_LINE).");
    CommandDef { spec, exec }
}

fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    let (name, evol) = result_of(study, args, "CO")?;
    if args.given("NOM_PARA") {
        // The result's parameters as a table are not built; the tables it
        // holds are what a user of these studies usually wants.
        return Err(args.not_implemented(
            "NOM_PARA",
            &format!(
                "a table of the result's parameters; {name}'s own tables are read with NOM_TABLE: {}",
                table_names(evol)
            ),
        ));
    }
    let Some(nom) = args.text("NOM_TABLE") else {
        return Err(args.error(
            "NOM_TABLE",
            format!(
                "NOM_TABLE is required; {name} holds the tables: {}",
                table_names(evol)
            ),
        ));
    };
    let Some(t) = evol.tables.get(nom) else {
        return Err(args.error(
            "NOM_TABLE",
            format!(
                "{name} holds no table '{nom}'; its tables: {}",
                table_names(evol)
            ),
        ));
    };
    let mut t = t.clone();
    t.title = if args.has("TITRE") {
        args.texts("TITRE").iter().map(|s| s.to_string()).collect()
    } else {
        concept_title(result.unwrap_or(""), "table_sdaster")
    };
    Ok(Some(ConceptData::Table(Box::new(t))))
}

fn table_names(evol: &crate::result::EvolNoli) -> String {
    if evol.tables.is_empty() {
        "none".into()
    } else {
        evol.tables.keys().cloned().collect::<Vec<_>>().join(", ")
    }
}
