//! CALC_TABLE: a sequence of operations on a table (FILTRE, EXTR,
//! SUPPRIME, RENOMME, TRI, COMB, OPER), each ACTION applied to the result
//! of the previous one.
//!
//! Why: studies reduce the tables of POST_RELEVE_T and RECU_TABLE (a
//! node, an instant, a maximum, a renamed column merged with another
//! table) before TEST_TABLE and IMPR_TABLE. FILTRE and TRI are the very
//! ones of TEST_TABLE and IMPR_TABLE ([`crate::post::table`]); the others
//! are in [`crate::post::calc_table`].

use super::blocks::*;
use super::post_args::{alarm, concept_title, filter_of, table_error, table_of};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::{ConceptData, ConceptType as C};
use crate::diag::Diagnostic;
use crate::post::table::Table;
use crate::study::Study;

const OPERATIONS: &[&str] = &[
    "FILTRE",
    "EXTR",
    "RENOMME",
    "TRI",
    "COMB",
    "AJOUT_LIGNE",
    "OPER",
    "SUPPRIME",
    "AJOUT_COLONNE",
];

pub fn def() -> CommandDef {
    let names = |doc: &'static str| text("NOM_PARA").required().many().doc(doc).kw();
    let action = fact(
        "ACTION",
        vec![
            text("OPERATION")
                .required()
                .into(OPERATIONS)
                .doc("AJOUT_LIGNE and AJOUT_COLONNE are not built")
                .kw(),
            block(
                "b_filtre",
                eq("OPERATION", "FILTRE"),
                vec![
                    text("NOM_PARA").required().doc("column filtered on").kw(),
                    text("CRIT_COMP")
                        .into(&[
                            "EQ", "NE", "GT", "LT", "GE", "LE", "REGEXP", "VIDE", "NON_VIDE",
                            "MAXI", "MAXI_ABS", "MINI", "MINI_ABS",
                        ])
                        .default(t("EQ"))
                        .doc("comparison (REGEXP is not built); MAXI/MINI... keep the first row holding the extreme value")
                        .kw(),
                    block(
                        "b_vale",
                        is_in("CRIT_COMP", &["EQ", "NE", "GT", "LT", "GE", "LE"]),
                        vec![
                            real("VALE").many().doc("values, for real columns").kw(),
                            int("VALE_I").many().doc("values, for integer columns").kw(),
                            text("VALE_K").many().doc("values, for text columns").kw(),
                        ],
                    )
                    .rules(vec![un_parmi(&["VALE", "VALE_I", "VALE_K"])])
                    .kw(),
                    block(
                        "b_regexp",
                        eq("CRIT_COMP", "REGEXP"),
                        vec![text("VALE_K").required().kw()],
                    )
                    .kw(),
                    block(
                        "b_crit",
                        is_in("CRIT_COMP", &["EQ", "NE"]),
                        vec![
                            text("CRITERE")
                                .into(&["RELATIF", "ABSOLU"])
                                .default(t("RELATIF"))
                                .kw(),
                            real("PRECISION")
                                .default(r(1e-3))
                                .doc("tolerance of EQ/NE on reals")
                                .kw(),
                        ],
                    )
                    .kw(),
                ],
            )
            .kw(),
            block(
                "b_extr",
                eq("OPERATION", "EXTR"),
                vec![names("the columns kept, in this order")],
            )
            .kw(),
            block(
                "b_suppr",
                eq("OPERATION", "SUPPRIME"),
                vec![names("the columns removed")],
            )
            .kw(),
            block(
                "b_renomme",
                eq("OPERATION", "RENOMME"),
                vec![text("NOM_PARA")
                    .required()
                    .count(2, 2)
                    .doc("(old name, new name)")
                    .kw()],
            )
            .kw(),
            block(
                "b_tri",
                eq("OPERATION", "TRI"),
                vec![
                    names("sort keys, the first one first"),
                    text("ORDRE")
                        .into(&["CROISSANT", "DECROISSANT"])
                        .default(t("CROISSANT"))
                        .kw(),
                ],
            )
            .kw(),
            block(
                "b_comb",
                eq("OPERATION", "COMB"),
                vec![
                    concept("TABLE", &[C::Table])
                        .required()
                        .doc("the table whose rows are merged in")
                        .kw(),
                    text("NOM_PARA")
                        .many()
                        .doc("columns whose values identify a row in both tables")
                        .kw(),
                    text("RESTREINT")
                        .into(&["OUI", "NON"])
                        .default(t("NON"))
                        .doc("OUI: the rows of TABLE that match none are not added")
                        .kw(),
                    text("FORMAT_R").doc("not built").kw(),
                ],
            )
            .kw(),
            block(
                "b_ajout_lig",
                eq("OPERATION", "AJOUT_LIGNE"),
                vec![text("NOM_PARA").required().many().kw(), real("VALE").required().many().kw()],
            )
            .kw(),
            block(
                "b_ajout_col",
                eq("OPERATION", "AJOUT_COLONNE"),
                vec![text("NOM_PARA").required().many().kw(), real("VALE").required().many().kw()],
            )
            .kw(),
            block(
                "b_oper",
                eq("OPERATION", "OPER"),
                vec![
                    concept("FORMULE", &[C::Formule])
                        .required()
                        .doc("formula of the columns named as its parameters")
                        .kw(),
                    text("NOM_PARA").required().doc("the new column").kw(),
                    text("NOM_COLONNE")
                        .many()
                        .doc("the columns given to the formula's parameters, in order")
                        .kw(),
                ],
            )
            .kw(),
        ],
    )
    .required()
    .many()
    .doc("the operations, applied in order")
    .kw();
    let spec = command(
        "CALC_TABLE",
        Produces::Concept(C::Table),
        vec![
            concept("TABLE", &[C::Table]).required().kw(),
            action,
            text("TITRE").many().kw(),
            info(),
        ],
    )
    .reentrant(Reentrant::Optional("TABLE"))
    .doc("Filters, extracts, sorts, renames, merges or computes columns of a table.");
    CommandDef { spec, exec }
}

fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    let (name, table) = table_of(study, args, "TABLE")?;
    let reused = result == Some(name);
    let mut t = table.clone();
    if !reused {
        t.title = concept_title(result.unwrap_or(""), "table_sdaster");
    }
    let mut warnings = Vec::new();
    for occ in args.facts("ACTION") {
        t = action(study, occ, t, &mut warnings)?;
    }
    for w in warnings {
        alarm(study, "CALC_TABLE", "TABLE0_2", &w);
    }
    if args.has("TITRE") {
        t.title = args.texts("TITRE").iter().map(|s| s.to_string()).collect();
    }
    Ok(Some(ConceptData::Table(Box::new(t))))
}

/// One ACTION occurrence on `t`.
fn action(
    study: &Study,
    occ: &Args,
    mut t: Table,
    warnings: &mut Vec<String>,
) -> Result<Table, Diagnostic> {
    let op = occ.text("OPERATION").unwrap_or_default();
    let err = |e| table_error(occ, "NOM_PARA", e);
    let names = occ.texts("NOM_PARA");
    match op {
        "FILTRE" => {
            if occ.text("CRIT_COMP") == Some("REGEXP") {
                return Err(occ.not_implemented("CRIT_COMP", "CRIT_COMP='REGEXP'"));
            }
            let f = filter_of(occ)?;
            t = t.filter(&f).map_err(|e| filter_error(occ, e))?;
            f.trace_in_title(&mut t.title);
            Ok(t)
        }
        "EXTR" => t.extract(&names).map_err(err),
        "SUPPRIME" => {
            let (out, missing) = t.drop_columns(&names);
            for m in missing {
                warnings.push(format!(
                    "{}: SUPPRIME of '{m}', which is not a column of the table: nothing removed",
                    occ.key_path("NOM_PARA")
                ));
            }
            Ok(out)
        }
        "RENOMME" => {
            let (old, new) = (
                names.first().copied().unwrap_or(""),
                names.get(1).copied().unwrap_or(""),
            );
            t.rename(old, new).map_err(err)?;
            Ok(t)
        }
        "TRI" => {
            let descending = occ.text("ORDRE") == Some("DECROISSANT");
            t.sort_by(&names, descending).map_err(|e| {
                let e = crate::post::table::TableError {
                    keyword: Some("NOM_PARA".into()),
                    ..e
                };
                err(e)
            })?;
            Ok(t)
        }
        "COMB" => {
            if occ.given("FORMAT_R") {
                return Err(occ.not_implemented("FORMAT_R", "labels are compared exactly"));
            }
            let (_, other) = table_of(study, occ, "TABLE")?;
            let restrict = occ.text("RESTREINT") == Some("OUI");
            t.merge(other, &names, restrict).map_err(err)
        }
        "OPER" => {
            let fname = occ.concept("FORMULE").unwrap_or_default();
            let formula = match study.concepts.data(fname) {
                Some(ConceptData::Formula(f)) => f,
                _ => {
                    return Err(occ.error(
                        "FORMULE",
                        format!("{fname} holds no formula (its command did not run)"),
                    ))
                }
            };
            let map = occ.texts("NOM_COLONNE");
            let map = (!map.is_empty()).then_some(map.as_slice());
            let new = occ.text("NOM_PARA").unwrap_or_default();
            t.add_formula_column(new, formula, map).map_err(err)?;
            Ok(t)
        }
        other => Err(occ.not_implemented(
            "OPERATION",
            &format!(
                "OPERATION='{other}'; built: FILTRE, EXTR, SUPPRIME, RENOMME, TRI, COMB, OPER"
            ),
        )),
    }
}

/// A FILTRE error on the keyword of the ACTION occurrence it names
/// (`FILTRE/VALE_I` -> `VALE_I`).
fn filter_error(occ: &Args, e: crate::post::table::TableError) -> Diagnostic {
    let key = e
        .keyword
        .as_deref()
        .and_then(|k| k.strip_prefix("FILTRE/"))
        .unwrap_or("NOM_PARA")
        .to_string();
    occ.error(&key, e.message)
}
