//! TEST_TABLE: checks one cell (or an aggregate) of a table.

use super::blocks::*;
use super::post_args::{filters_of, report_checks, run_checks, table_error, table_of, test_spec};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;
use crate::diag::Diagnostic;
use crate::post::table::{Cell, Table};
use crate::post::test_report::{table_block, Value};
use crate::study::Study;

pub fn def() -> CommandDef {
    let (refe_kws, refe_rules) = c_test_reference(false, true);
    let mut kws = vec![
        concept("TABLE", &[C::Table]).required().kw(),
        c_filtre(),
        text("NOM_PARA")
            .required()
            .doc("column tested; without TYPE_TEST exactly one row must remain after filtering")
            .kw(),
        info(),
    ];
    kws.extend(refe_kws);
    let spec = command("TEST_TABLE", Produces::Nothing, kws)
        .rules(refe_rules)
        .doc("Tests a value of a table against VALE_CALC (non-regression) and VALE_REFE.");
    CommandDef { spec, exec }
}

/// Filters the table, takes the cell (or the TYPE_TEST aggregate of the
/// column) and prints the checks in the .resu.
fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    let spec = test_spec(args)?;
    let (name, table) = table_of(study, args, "TABLE")?;
    let name = name.to_string();
    let filters = filters_of(args)?;
    let kept = table
        .filter_all(&filters)
        .map_err(|e| table_error(args, "FILTRE", e))?;
    let nom_para = args.text("NOM_PARA").unwrap_or_default();
    let type_test = args.text("TYPE_TEST");
    let computed = match type_test {
        None => Value::from(
            kept.single_value(nom_para)
                .map_err(|e| table_error(args, "NOM_PARA", e))?,
        ),
        Some(tt) => aggregate(args, &kept, nom_para, tt)?,
    };
    let lines = run_checks(args, &spec, &computed)?;
    let block = table_block(&name, nom_para, type_test, &lines);
    report_checks(study, args, &block, &lines);
    Ok(None)
}

/// TYPE_TEST over the filtered column: SOMM, SOMM_ABS, MAX or MIN of its
/// cells (empty cells left out), an integer for an I column.
fn aggregate(args: &Args, t: &Table, nom_para: &str, tt: &str) -> Result<Value, Diagnostic> {
    let cells: Vec<&Cell> = t
        .column(nom_para)
        .map_err(|e| table_error(args, "NOM_PARA", e))?
        .into_iter()
        .flatten()
        .collect();
    if cells.is_empty() {
        return Err(args.error(
            "TYPE_TEST",
            format!("column {nom_para} has no value left after filtering"),
        ));
    }
    if cells.iter().all(|c| matches!(c, Cell::Int(_))) {
        let v: Vec<i64> = cells
            .iter()
            .filter_map(|c| match c {
                Cell::Int(i) => Some(*i),
                _ => None,
            })
            .collect();
        let r = match tt {
            "SOMM" => v.iter().sum(),
            "SOMM_ABS" => v.iter().map(|x| x.abs()).sum(),
            "MAX" => *v.iter().max().unwrap_or(&0),
            _ => *v.iter().min().unwrap_or(&0),
        };
        return Ok(Value::Int(r));
    }
    let v: Vec<f64> = cells
        .iter()
        .map(|c| {
            c.as_f64().ok_or_else(|| {
                args.error(
                    "TYPE_TEST",
                    format!("TYPE_TEST needs a numeric column; {nom_para} holds texts"),
                )
            })
        })
        .collect::<Result<_, _>>()?;
    Ok(Value::Real(match tt {
        "SOMM" => v.iter().sum(),
        "SOMM_ABS" => v.iter().map(|x| x.abs()).sum(),
        "MAX" => v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        _ => v.iter().copied().fold(f64::INFINITY, f64::min),
    }))
}
