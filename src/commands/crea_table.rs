//! CREA_TABLE: a table from lists of values (LISTE) or from the points
//! of a function (FONCTION).
//!
//! Why: studies write reference values, or the points of a curve, as a
//! table that TEST_TABLE, CALC_TABLE (COMB with a computed table) and
//! IMPR_TABLE then read like any other.
//!
//! LISTE: one column per occurrence, named PARA, typed by the list given
//! (LISTE_I: I, LISTE_R: R, LISTE_K: TYPE_K, K8 by default, a longer text
//! is an error). Without NUME_LIGN the k-th value goes on line k and every
//! list must have the same length (code_aster's rule); with NUME_LIGN the
//! values go on the lines it gives (from 1), the others stay empty.
//! FONCTION: two columns, the abscissas and ordinates, named by PARA or
//! by the function's NOM_PARA and NOM_RESU. RESU and TYPE_TABLE other
//! than 'TABLE' are not implemented.

use super::blocks::*;
use super::post_args::{concept_title, function_of, table_error};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::{ConceptData, ConceptType as C};
use crate::diag::Diagnostic;
use crate::post::table::{Cell, ColumnType, Table};
use crate::study::Study;

pub fn def() -> CommandDef {
    let spec = command(
        "CREA_TABLE",
        Produces::Concept(C::Table),
        vec![
            fact(
                "LISTE",
                vec![
                    text("PARA").required().doc("name of the column").kw(),
                    text("TYPE_K")
                        .into(&["K8", "K16", "K24"])
                        .default(t("K8"))
                        .doc("width of a LISTE_K column")
                        .kw(),
                    int("NUME_LIGN")
                        .many()
                        .doc("lines (from 1) of the values; without it, lines 1 to n")
                        .kw(),
                    int("LISTE_I").many().doc("integer values").kw(),
                    real("LISTE_R").many().doc("real values").kw(),
                    text("LISTE_K").many().doc("text values").kw(),
                ],
            )
            .rules(vec![un_parmi(&["LISTE_I", "LISTE_R", "LISTE_K"])])
            .many()
            .doc("one column per occurrence")
            .kw(),
            fact(
                "FONCTION",
                vec![
                    concept("FONCTION", &[C::Fonction])
                        .required()
                        .doc("the function whose points make the rows")
                        .kw(),
                    text("PARA")
                        .count(2, 2)
                        .doc("names of the two columns (default: NOM_PARA, NOM_RESU)")
                        .kw(),
                ],
            )
            .doc("a table of the points of a function")
            .kw(),
            fact(
                "RESU",
                vec![
                    concept("RESULTAT", &[C::EvolNoli]).kw(),
                    concept("CHAM_GD", &[C::ChamNo]).kw(),
                    text("NOM_CHAM").kw(),
                    text("TOUT_CMP").into(&["OUI"]).kw(),
                    text("NOM_CMP").many().kw(),
                    tout(),
                    group_ma(),
                    group_no(),
                ],
            )
            .doc("not implemented")
            .kw(),
            text("TYPE_TABLE")
                .into(&["TABLE", "TABLE_FONCTION", "TABLE_CONTENEUR"])
                .default(t("TABLE"))
                .doc("only TABLE is implemented")
                .kw(),
            text("TITRE").doc("title of the table").kw(),
        ],
    )
    .rules(vec![exclus(&["FONCTION", "LISTE", "RESU"])])
    .doc(
        "Creates a table from lists of values (LISTE) or from the points of a function (FONCTION).",
    );
    CommandDef { spec, exec }
}

fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    if args.has("RESU") {
        return Err(args.not_implemented("RESU", ""));
    }
    if let Some(ty) = args.text("TYPE_TABLE").filter(|t| *t != "TABLE") {
        return Err(args.not_implemented("TYPE_TABLE", &format!("TYPE_TABLE='{ty}'")));
    }
    let mut table = if let Some(occ) = args.fact("FONCTION") {
        from_function(study, occ)?
    } else {
        from_lists(args)?
    };
    table.title = match args.text("TITRE") {
        Some(t) => vec![t.to_string()],
        None => concept_title(result.unwrap_or(""), "table_sdaster"),
    };
    Ok(Some(ConceptData::Table(Box::new(table))))
}

fn from_lists(args: &Args) -> Result<Table, Diagnostic> {
    let occs = args.facts("LISTE");
    let mut table = Table::new();
    // (column, line, cell) of every value, lines from 0
    let mut placed: Vec<(usize, usize, Cell)> = Vec::new();
    let mut first_len: Option<(usize, &str)> = None;
    for occ in occs {
        let para = occ.text("PARA").unwrap_or_default();
        let (key, ty, cells): (&str, ColumnType, Vec<Cell>) = if occ.has("LISTE_I") {
            let v = occ.ints("LISTE_I").into_iter().map(Cell::Int).collect();
            ("LISTE_I", ColumnType::Int, v)
        } else if occ.has("LISTE_R") {
            let v = occ.reals("LISTE_R").into_iter().map(Cell::Real).collect();
            ("LISTE_R", ColumnType::Real, v)
        } else {
            let width = match occ.text("TYPE_K").unwrap_or("K8") {
                "K16" => 16,
                "K24" => 24,
                _ => 8,
            };
            let v = occ
                .texts("LISTE_K")
                .into_iter()
                .map(|s| Cell::Text(s.to_string()))
                .collect();
            ("LISTE_K", ColumnType::Text(width), v)
        };
        let col = table
            .add_column(para, ty)
            .map_err(|e| occ.error("PARA", e.message))?;
        let lines: Vec<usize> = if occ.has("NUME_LIGN") {
            let nl = occ.ints("NUME_LIGN");
            if nl.len() != cells.len() {
                return Err(occ.error(
                    "NUME_LIGN",
                    format!(
                        "NUME_LIGN gives {} lines for the {} values of {key}",
                        nl.len(),
                        cells.len()
                    ),
                ));
            }
            let mut lines = Vec::with_capacity(nl.len());
            for n in nl {
                if n < 1 {
                    return Err(occ.error(
                        "NUME_LIGN",
                        format!("line numbers start at 1, {n} is given"),
                    ));
                }
                let l = (n - 1) as usize;
                if lines.contains(&l) {
                    return Err(
                        occ.error("NUME_LIGN", format!("line {n} is given twice for {para}"))
                    );
                }
                lines.push(l);
            }
            lines
        } else {
            match first_len {
                Some((n, other)) if n != cells.len() => {
                    return Err(occ.error(
                        key,
                        format!(
                            "{para} has {} values where {other} has {n}: lists without NUME_LIGN must have the same length",
                            cells.len()
                        ),
                    ))
                }
                None => first_len = Some((cells.len(), para)),
                _ => {}
            }
            (0..cells.len()).collect()
        };
        for (l, c) in lines.into_iter().zip(cells) {
            placed.push((col, l, c));
        }
    }
    let nrows = placed.iter().map(|(_, l, _)| l + 1).max().unwrap_or(0);
    let mut rows = vec![vec![None; table.columns.len()]; nrows];
    for (c, l, cell) in placed {
        rows[l][c] = Some(cell);
    }
    for row in rows {
        table
            .push_row(row)
            .map_err(|e| table_error(args, "LISTE", e))?;
    }
    Ok(table)
}

fn from_function(study: &Study, occ: &Args) -> Result<Table, Diagnostic> {
    let (_, f) = function_of(study, occ, "FONCTION")?;
    let names: Vec<String> = if occ.has("PARA") {
        occ.texts("PARA").iter().map(|s| s.to_string()).collect()
    } else {
        vec![f.para.clone(), f.resu.clone()]
    };
    if names[0] == names[1] {
        return Err(occ.error(
            "PARA",
            format!("the two columns are both named '{}'", names[0]),
        ));
    }
    let mut table = Table::new();
    for n in &names {
        table
            .add_column(n, ColumnType::Real)
            .map_err(|e| occ.error("PARA", e.message))?;
    }
    for (x, y) in f.abscissas.iter().zip(&f.ordinates) {
        table
            .push_row(vec![Some(Cell::Real(*x)), Some(Cell::Real(*y))])
            .map_err(|e| occ.error("FONCTION", e.message))?;
    }
    Ok(table)
}
