//! IMPR_FONCTION: prints curves.

use super::blocks::*;
use super::post_args::{alarm, function_of};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;
use crate::post::function::{write_tableau, write_xmgrace, FunctionCurve, GraphOptions, Scale};
use crate::post::table::PrintOptions;
use crate::study::Study;

pub fn def() -> CommandDef {
    let echelle = |n: &'static str| text(n).into(&["LIN", "LOG"]).default(t("LIN")).kw();
    let spec = command(
        "IMPR_FONCTION",
        Produces::Nothing,
        vec![
            text("FORMAT")
                .into(&["TABLEAU", "AGRAF", "XMGRACE", "LISS_ENVELOP"])
                .default(t("TABLEAU"))
                .kw(),
            block(
                "b_xmgrace",
                eq("FORMAT", "XMGRACE"),
                vec![
                    int("UNITE")
                        .default(i(29))
                        .doc("logical unit of the .agr file")
                        .kw(),
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
                        .doc("'' writes the Grace project text; the others need xmgrace")
                        .kw(),
                ],
            )
            .kw(),
            block(
                "b_unite",
                not(eq("FORMAT", "XMGRACE")),
                vec![int("UNITE").default(i(8)).doc("logical unit written").kw()],
            )
            .kw(),
            fact(
                "COURBE",
                vec![
                    concept("FONCTION", &[C::Fonction])
                        .required()
                        .doc("function plotted")
                        .kw(),
                    text("LEGENDE").doc("curve legend").kw(),
                    int("STYLE").kw(),
                    int("COULEUR").kw(),
                    int("MARQUEUR").kw(),
                    int("FREQ_MARQUEUR").default(i(0)).kw(),
                    text("TRI")
                        .into(&["N", "X", "Y", "XY", "YX"])
                        .default(t("N"))
                        .doc("sorting of the points")
                        .kw(),
                ],
            )
            .required()
            .many()
            .doc("one curve per occurrence")
            .kw(),
            text("TITRE").doc("graph title").kw(),
            text("SOUS_TITRE").kw(),
            real("BORNE_X").count(2, 2).kw(),
            real("BORNE_Y").count(2, 2).kw(),
            echelle("ECHELLE_X"),
            echelle("ECHELLE_Y"),
            real("GRILLE_X").kw(),
            real("GRILLE_Y").kw(),
            text("LEGENDE_X").kw(),
            text("LEGENDE_Y").kw(),
            info(),
        ],
    )
    .doc("Prints functions as curves (table, Agraf or Grace project).");
    CommandDef { spec, exec }
}

/// XMGRACE (the .agr project text, unit 29 by default) or TABLEAU (unit 8)
/// through the writers of `post::function`.
fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    let format = args.text("FORMAT").unwrap_or("TABLEAU");
    if !matches!(format, "XMGRACE" | "TABLEAU") {
        return Err(args.not_implemented("FORMAT", &format!("FORMAT='{format}'")));
    }
    if !args.text("PILOTE").unwrap_or("").is_empty() {
        return Err(args.not_implemented("PILOTE", "only the .agr project text (PILOTE='')"));
    }
    let mut curves = Vec::new();
    for occ in args.facts("COURBE") {
        let (name, f) = function_of(study, occ, "FONCTION")?;
        let tri = occ.text("TRI").unwrap_or("N");
        // A function's abscissas are increasing already: TRI='X' changes
        // nothing; sorting on Y would break the curve into a new one.
        if !matches!(tri, "N" | "X") {
            return Err(occ.not_implemented("TRI", &format!("TRI='{tri}'")));
        }
        let mut c = FunctionCurve::new(f, occ.text("LEGENDE").unwrap_or(name));
        c.style = occ.int("STYLE");
        c.color = occ.int("COULEUR");
        c.marker = occ.int("MARQUEUR");
        c.marker_freq = occ.int("FREQ_MARQUEUR");
        curves.push(c);
    }
    let scale = |k: &str| {
        if args.text(k) == Some("LOG") {
            Scale::Log
        } else {
            Scale::Lin
        }
    };
    let pair = |k: &str| {
        let v = args.reals(k);
        (v.len() == 2).then(|| (v[0], v[1]))
    };
    let graph = GraphOptions {
        titre: args.text("TITRE").unwrap_or_default().to_string(),
        sous_titre: args.text("SOUS_TITRE").unwrap_or_default().to_string(),
        legende_x: args.text("LEGENDE_X").unwrap_or_default().to_string(),
        legende_y: args.text("LEGENDE_Y").unwrap_or_default().to_string(),
        borne_x: pair("BORNE_X"),
        borne_y: pair("BORNE_Y"),
        echelle_x: scale("ECHELLE_X"),
        echelle_y: scale("ECHELLE_Y"),
        grille_x: args.real("GRILLE_X"),
        grille_y: args.real("GRILLE_Y"),
    };
    let (text, warnings) = if format == "XMGRACE" {
        (write_xmgrace(&curves, &graph), Vec::new())
    } else {
        write_tableau(&curves, &graph, None, &PrintOptions::default())
            .map_err(|e| args.error("COURBE", e))?
    };
    let unit = args
        .int("UNITE")
        .unwrap_or(if format == "XMGRACE" { 29 } else { 8 });
    for w in warnings {
        alarm(study, "IMPR_FONCTION", "", &w);
    }
    study.write_unit(unit, &text);
    Ok(None)
}
