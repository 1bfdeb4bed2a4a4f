//! DEFI_LIST_ENTI: a strictly increasing list of integers, the list of
//! stored indices that LIST_ORDRE takes in the post-processing commands.
//!
//! code_aster's OPERATION='DEFI' (op0022, dlidef): VALE strictly
//! increasing, or DEBUT followed by INTERVALLE occurrences each reaching
//! its JUSQU_A in whole steps, PAS or NOMBRE having to divide the interval
//! exactly (code_aster stops otherwise, and so do we, naming the
//! occurrence). OPERATION='NUME_ORDRE' (the indices of a result whose
//! parameter lies in an interval) is refused as not implemented.

use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::{ConceptData, ConceptType as C};
use crate::diag::Diagnostic;
use crate::study::Study;

use super::blocks::{eq, info, t, titre, RESULTS};
use super::defi_list_reel::{strictly_increasing, MAX_VALUES};

pub fn def() -> CommandDef {
    let spec = command(
        "DEFI_LIST_ENTI",
        Produces::Concept(C::Listis),
        vec![
            text("OPERATION")
                .into(&["DEFI", "NUME_ORDRE"])
                .default(t("DEFI"))
                .doc("DEFI: the list is given; NUME_ORDRE (indices of a result): not implemented yet")
                .kw(),
            block(
                "b_defi",
                eq("OPERATION", "DEFI"),
                vec![
                    int("VALE").many().doc("explicit, strictly increasing values").kw(),
                    int("DEBUT").doc("first value of a list built by intervals").kw(),
                    fact(
                        "INTERVALLE",
                        vec![
                            int("JUSQU_A")
                                .required()
                                .doc("end of the interval, reached exactly")
                                .kw(),
                            int("NOMBRE")
                                .doc("number of equal steps; must divide the interval")
                                .kw(),
                            int("PAS").doc("step; must divide the interval").kw(),
                        ],
                    )
                    .many()
                    .rules(vec![un_parmi(&["NOMBRE", "PAS"])])
                    .doc("intervals following each other from DEBUT")
                    .kw(),
                ],
            )
            .rules(vec![un_parmi(&["VALE", "DEBUT"]), exclus(&["VALE", "INTERVALLE"])])
            .kw(),
            block(
                "b_extr",
                eq("OPERATION", "NUME_ORDRE"),
                vec![
                    concept("RESULTAT", RESULTS).required().kw(),
                    text("PARAMETRE").required().kw(),
                    real("INTERV_R").required().count(2, 2).kw(),
                ],
            )
            .kw(),
            info(),
            titre(),
        ],
    )
    .doc("Defines a strictly increasing list of integers, explicitly or by intervals (LIST_ORDRE of the post-processing commands).");
    CommandDef { spec, exec }
}

fn exec(_study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    if args.text("OPERATION") == Some("NUME_ORDRE") {
        return Err(args.not_implemented(
            "OPERATION",
            "OPERATION='NUME_ORDRE' (only OPERATION='DEFI': give the indices with VALE or DEBUT/INTERVALLE)",
        ));
    }
    let values = if args.has("VALE") {
        explicit(args)?
    } else {
        let debut = args.int("DEBUT").ok_or_else(|| {
            args.error(
                "DEBUT",
                "OPERATION='DEFI' needs VALE or DEBUT (with INTERVALLE)",
            )
        })?;
        by_intervals(debut, args.facts("INTERVALLE"))?
    };
    Ok(Some(ConceptData::ListInt(values)))
}

fn explicit(args: &Args) -> Result<Vec<i64>, Diagnostic> {
    strictly_increasing(args, args.ints("VALE"), |x| x.to_string())
}

/// DEBUT, then each occurrence's values up to its JUSQU_A in equal whole
/// steps (dlidef): a step that does not divide the interval is an error.
pub fn by_intervals(debut: i64, intervals: &[Args]) -> Result<Vec<i64>, Diagnostic> {
    let mut values = vec![debut];
    let mut prev = debut;
    for (k, occ) in intervals.iter().enumerate() {
        let end = occ
            .int("JUSQU_A")
            .ok_or_else(|| occ.error("JUSQU_A", "JUSQU_A is required"))?;
        let length = end.checked_sub(prev).filter(|&l| l > 0).ok_or_else(|| {
            occ.error(
                "JUSQU_A",
                format!("JUSQU_A = {end} must be greater than the previous value {prev}"),
            )
        })?;
        let (key, steps, step) = if let Some(pas) = occ.int("PAS") {
            if pas < 1 {
                return Err(occ.error("PAS", format!("PAS = {pas} must be at least 1")));
            }
            ("PAS", length / pas, pas)
        } else {
            let n = occ
                .int("NOMBRE")
                .ok_or_else(|| occ.error("", "one of NOMBRE or PAS is required"))?;
            if n < 1 {
                return Err(occ.error("NOMBRE", format!("NOMBRE = {n} must be at least 1")));
            }
            ("NOMBRE", n, length / n)
        };
        if step == 0 || steps * step != length {
            return Err(occ.error(
                key,
                format!(
                    "{key} = {} does not divide the interval [{prev}, {end}] of INTERVALLE occurrence {} (length {length}): the values of a list of integers are whole steps",
                    occ.int(key).unwrap_or_default(),
                    k + 1
                ),
            ));
        }
        if values.len() as u64 + steps as u64 > MAX_VALUES as u64 {
            return Err(occ.error(
                key,
                format!("the intervals give more than the {MAX_VALUES} values a list may hold"),
            ));
        }
        values.extend((1..=steps).map(|i| prev + i * step));
        prev = end;
    }
    Ok(values)
}
