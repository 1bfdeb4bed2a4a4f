//! IMPR_TABLE: prints a table.

use super::blocks::*;
use super::post_args::{alarm, filters_of, table_error, table_of};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;
use crate::post::function::GraphOptions;
use crate::post::table::{PrintFormat, PrintOptions};
use crate::study::Study;

pub fn def() -> CommandDef {
    let tableau = ["TABLEAU", "AGRAF"];
    let spec = command(
        "IMPR_TABLE",
        Produces::Nothing,
        vec![
            concept("TABLE", &[C::Table]).required().kw(),
            text("FORMAT")
                .into(&[
                    "TABLEAU",
                    "ASTER",
                    "TABLEAU_CROISE",
                    "AGRAF",
                    "XMGRACE",
                    "NUMPY",
                ])
                .default(t("TABLEAU"))
                .kw(),
            block(
                "b_unite_xmgrace",
                eq("FORMAT", "XMGRACE"),
                vec![
                    int("UNITE").default(i(29)).doc("logical unit written").kw(),
                    text("PILOTE")
                        .default(t(""))
                        .into(&[
                            "",
                            "POSTSCRIPT",
                            "EPS",
                            "MIF",
                            "SVG",
                            "PNM",
                            "PNG",
                            "JPEG",
                            "PDF",
                            "INTERACTIF",
                        ])
                        .doc("'' writes the .agr project text")
                        .kw(),
                ],
            )
            .kw(),
            block(
                "b_unite",
                not(eq("FORMAT", "XMGRACE")),
                vec![int("UNITE")
                    .default(i(8))
                    .doc("logical unit written (8 is the .resu file)")
                    .kw()],
            )
            .kw(),
            text("NOM_PARA")
                .many()
                .doc("columns printed, in this order; columns left empty are dropped")
                .kw(),
            c_filtre(),
            fact(
                "TRI",
                vec![
                    text("NOM_PARA").required().many().kw(),
                    text("ORDRE")
                        .into(&["CROISSANT", "DECROISSANT"])
                        .default(t("CROISSANT"))
                        .kw(),
                ],
            )
            .doc("row sorting")
            .kw(),
            text("FORMAT_R")
                .default(t("E12.5"))
                .doc("Fortran-like format of reals")
                .kw(),
            fact("PAGINATION", vec![text("NOM_PARA").required().many().kw()]).kw(),
            block(
                "b_tableau",
                is_in("FORMAT", &tableau),
                vec![
                    text("SEPARATEUR").default(t(" ")).kw(),
                    text("COMMENTAIRE").default(t("#")).kw(),
                    text("COMM_PARA").default(t("")).kw(),
                    text("DEBUT_LIGNE").default(t("")).kw(),
                    text("FIN_LIGNE").default(t("\n")).kw(),
                    text("DEBUT_TABLE").kw(),
                    text("FIN_TABLE").kw(),
                ],
            )
            .kw(),
            text("TITRE").many().kw(),
            info(),
        ],
    )
    .doc("Prints a table to a logical unit.");
    CommandDef { spec, exec }
}

/// TABLEAU and AGRAF through `Table::impr_table`; XMGRACE through
/// `Table::xmgrace` after the same FILTRE / TRI / NOM_PARA steps. The text
/// goes to the logical unit (8, the .resu, by default).
fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    let (name, table) = table_of(study, args, "TABLE")?;
    let name = name.to_string();
    let format = args.text("FORMAT").unwrap_or("TABLEAU");
    if args.has("PAGINATION") {
        return Err(args.not_implemented("PAGINATION", ""));
    }
    let mut opts = PrintOptions {
        format: match format {
            "TABLEAU" => PrintFormat::Tableau,
            "AGRAF" => PrintFormat::Agraf,
            "XMGRACE" => PrintFormat::Tableau,
            other => {
                return Err(args.not_implemented("FORMAT", &format!("FORMAT='{other}'")));
            }
        },
        format_r: args.text("FORMAT_R").map(str::to_string),
        nom_para: args.has("NOM_PARA").then(|| {
            args.texts("NOM_PARA")
                .iter()
                .map(|s| s.to_string())
                .collect()
        }),
        filters: filters_of(args)?,
        tri: args.fact("TRI").map(|t| {
            (
                t.texts("NOM_PARA").iter().map(|s| s.to_string()).collect(),
                t.text("ORDRE") == Some("DECROISSANT"),
            )
        }),
        titre: args.texts("TITRE").iter().map(|s| s.to_string()).collect(),
        ..PrintOptions::default()
    };
    for (key, field) in [
        ("SEPARATEUR", &mut opts.separator),
        ("COMMENTAIRE", &mut opts.comment),
        ("COMM_PARA", &mut opts.comm_para),
        ("DEBUT_LIGNE", &mut opts.debut_ligne),
        ("FIN_LIGNE", &mut opts.fin_ligne),
        ("FIN_TABLE", &mut opts.fin_table),
    ] {
        if let Some(v) = args.text(key) {
            *field = v.to_string();
        }
    }
    opts.debut_table = args.text("DEBUT_TABLE").map(str::to_string);
    let unit = args.int("UNITE").unwrap_or(8);
    let text = if format == "XMGRACE" {
        if !args.text("PILOTE").unwrap_or("").is_empty() {
            return Err(args.not_implemented("PILOTE", "only the .agr project text (PILOTE='')"));
        }
        let mut t = table.clone();
        for f in &opts.filters {
            t = t.filter(f).map_err(|e| table_error(args, "FILTRE", e))?;
        }
        if let Some((keys, desc)) = &opts.tri {
            let keys: Vec<&str> = keys.iter().map(String::as_str).collect();
            t.sort_by(&keys, *desc)
                .map_err(|e| table_error(args, "TRI", e))?;
        }
        if let Some(names) = &opts.nom_para {
            let names: Vec<&str> = names.iter().map(String::as_str).collect();
            let (sel, missing) = t.select(&names);
            for m in missing {
                alarm(
                    study,
                    "IMPR_TABLE",
                    "TABLE0_7",
                    &format!("the parameter '{m}' is not a column of the table: it is not printed"),
                );
            }
            t = sel;
        }
        let graph = GraphOptions {
            titre: opts.titre.join(" "),
            ..GraphOptions::default()
        };
        t.without_empty_columns()
            .xmgrace(&graph, &name)
            .map_err(|e| table_error(args, "NOM_PARA", e))?
    } else {
        let (text, warnings) = table
            .impr_table(&opts)
            .map_err(|e| table_error(args, "TABLE", e))?;
        for w in warnings {
            let (id, msg) = w.split_once(": ").unwrap_or(("", w.as_str()));
            alarm(study, "IMPR_TABLE", id, msg);
        }
        text
    };
    study.write_unit(unit, &text);
    Ok(None)
}
