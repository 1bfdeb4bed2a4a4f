//! RECU_FONCTION: a function of time extracted from a result or a table.

use super::blocks::*;
use super::post_args::{
    alarm, cell_name, component_index, filters_of, function_overrides, is_gauss_name,
    mesh_of_result, node_name, nodes_of, result_of, select_steps, single_cell, step_gauss,
    step_nodal, table_error, table_of,
};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::diag::Diagnostic;
use crate::post::function::Function;
use crate::study::Study;

pub fn def() -> CommandDef {
    let mut prec = critere_precision(1e-6);
    prec.push(text("INTERP_NUME").into(&["NON", "LIN"]).kw());
    let spec = command(
        "RECU_FONCTION",
        Produces::Concept(C::Fonction),
        vec![
            concept("RESULTAT", RESULTS).kw(),
            concept("TABLE", &[C::Table]).kw(),
            block(
                "b_acces",
                present("RESULTAT"),
                vec![
                    text("TOUT_ORDRE").into(&["OUI"]).kw(),
                    int("NUME_ORDRE").many().kw(),
        concept("LIST_ORDRE", &[C::Listis]).doc("stored indices of a DEFI_LIST_ENTI list").kw(),
                    text("TOUT_INST").into(&["OUI"]).kw(),
                    real("INST").many().kw(),
                    concept("LIST_INST", &[C::Listr8]).kw(),
                    block(
                        "b_prec",
                        or(vec![present("INST"), present("LIST_INST")]),
                        prec,
                    )
                    .kw(),
                ],
            )
            .kw(),
            block(
                "b_resu",
                present("RESULTAT"),
                vec![
                    text("NOM_CHAM").into(NOM_CHAM_RESU).kw(),
                    text("NOM_PARA_RESU")
                        .doc("a result parameter instead of a field")
                        .kw(),
                    block(
                        "b_cham",
                        present("NOM_CHAM"),
                        vec![
                            text("NOM_CMP").required().kw(),
                            text("MAILLE").hidden().kw(),
                            text("GROUP_MA").kw(),
                            text("NOEUD").hidden().kw(),
                            text("GROUP_NO")
                                .doc("with several nodes the first one is used, with an alarm")
                                .kw(),
                            int("POINT").kw(),
                            int("SOUS_POINT").kw(),
                        ],
                    )
                    .rules(vec![
                        au_moins_un(&["MAILLE", "GROUP_MA", "GROUP_NO", "NOEUD"]),
                        present_absent("POINT", &["NOEUD", "GROUP_NO"]),
                        present_absent("SOUS_POINT", &["NOEUD", "GROUP_NO"]),
                        exclus(&["GROUP_MA", "MAILLE"]),
                        exclus(&["GROUP_NO", "NOEUD"]),
                    ])
                    .kw(),
                ],
            )
            .rules(vec![un_parmi(&["NOM_CHAM", "NOM_PARA_RESU"])])
            .kw(),
            block(
                "b_table",
                present("TABLE"),
                vec![
                    text("PARA_X").doc("column of the abscissas").kw(),
                    text("PARA_Y").doc("column of the ordinates").kw(),
                    text("NOM_PARA_TABL").into(&["FONCTION", "FONCTION_C"]).kw(),
                    c_filtre(),
                ],
            )
            .rules(vec![
                un_parmi(&["PARA_X", "NOM_PARA_TABL"]),
                present_present("PARA_X", &["PARA_Y"]),
            ])
            .kw(),
            text("NOM_PARA")
                .into(&["INST", "X", "Y", "Z", "FREQ", "ABSC"])
                .doc("overrides the parameter name (default INST for a result)")
                .kw(),
            text("NOM_RESU").doc("overrides the value name (default: the component)").kw(),
            text("INTERPOL")
                .count(1, 2)
                .into(&["NON", "LIN", "LOG"])
                .doc("interpolation, default 'LIN LIN'")
                .kw(),
            text("PROL_DROITE")
                .into(&["CONSTANT", "LINEAIRE", "EXCLU"])
                .doc("extrapolation on the right, default EXCLU")
                .kw(),
            text("PROL_GAUCHE")
                .into(&["CONSTANT", "LINEAIRE", "EXCLU"])
                .doc("extrapolation on the left, default EXCLU")
                .kw(),
            titre(),
            info(),
        ],
    )
    .rules(vec![un_parmi(&["RESULTAT", "TABLE"])])
    .doc("Extracts the evolution of one component at one node over all stored instants (or columns of a table) as a function.");
    CommandDef { spec, exec }
}

/// A function of INST from a result (one component at one node, or at one
/// Gauss point), or of a column of a table; then the NOM_PARA, NOM_RESU,
/// INTERPOL and PROL_* overrides.
fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    let mut f = if args.has("RESULTAT") {
        from_result(study, args)?
    } else {
        from_table(study, args)?
    };
    function_overrides(args, &mut f)?;
    Ok(Some(ConceptData::Function(Box::new(f))))
}

fn from_result(study: &mut Study, args: &Args) -> Result<Function, Diagnostic> {
    for k in ["NOM_PARA_RESU", "SOUS_POINT", "INTERP_NUME"] {
        if args.has(k) {
            return Err(args.not_implemented(k, ""));
        }
    }
    let (rname, res) = result_of(study, args, "RESULTAT")?;
    let mesh = mesh_of_result(study, args, "RESULTAT", rname, res)?;
    let nom_cham = args.text("NOM_CHAM").unwrap_or_default();
    let cmp = args.text("NOM_CMP").unwrap_or_default();
    let steps = select_steps(study, res, args)?;
    let mut xs = Vec::with_capacity(steps.len());
    let mut ys = Vec::with_capacity(steps.len());
    let mut alarms = Vec::new();
    if nom_cham.ends_with("_ELNO") {
        return Err(args.not_implemented(
            "NOM_CHAM",
            &format!("a function of the field by element at nodes {nom_cham}; the nodal field {}_NOEU of CALC_CHAMP averages it at the nodes", nom_cham.trim_end_matches("_ELNO")),
        ));
    }
    if is_gauss_name(nom_cham) {
        let (cell, _, _) = single_cell(mesh, args)?;
        let point = args
            .int("POINT")
            .ok_or_else(|| args.error("POINT", format!("POINT is needed for {nom_cham}")))?;
        for s in &steps {
            let f = step_gauss(s, nom_cham, args, "NOM_CHAM", rname)?;
            let c = component_index(&f.components, cmp, args, "NOM_CMP", nom_cham)?;
            let npg = f.npg(cell);
            if point < 1 || point as usize > npg {
                return Err(args.error(
                    "POINT",
                    format!(
                        "cell {} has {npg} Gauss point(s) in {nom_cham} at NUME_ORDRE {}",
                        cell_name(cell),
                        s.nume_ordre
                    ),
                ));
            }
            xs.push(s.inst);
            ys.push(f.cell(cell)[(point as usize - 1) * f.ncmp() + c]);
        }
    } else {
        let nodes = nodes_of(mesh, args)?;
        let Some(&node) = nodes.first() else {
            return Err(args.error("GROUP_NO", "the node group is empty"));
        };
        if nodes.len() > 1 {
            alarms.push(format!(
                "GROUP_NO holds {} nodes: the first one, {}, is used",
                nodes.len(),
                node_name(node)
            ));
        }
        for s in &steps {
            let f = step_nodal(s, nom_cham, args, "NOM_CHAM", rname)?;
            component_index(&f.components, cmp, args, "NOM_CMP", nom_cham)?;
            let v = f.get(node, cmp).ok_or_else(|| {
                args.error(
                    "NOM_CMP",
                    format!(
                        "component {cmp} of {nom_cham} is absent at node {} at NUME_ORDRE {}",
                        node_name(node),
                        s.nume_ordre
                    ),
                )
            })?;
            xs.push(s.inst);
            ys.push(v);
        }
    }
    for a in alarms {
        alarm(study, "RECU_FONCTION", "", &a);
    }
    Function::new("INST", cmp, xs, ys).map_err(|e| args.error("RESULTAT", e))
}

/// PARA_X / PARA_Y of a table after FILTRE; rows missing either cell are
/// left out.
fn from_table(study: &Study, args: &Args) -> Result<Function, Diagnostic> {
    if args.has("NOM_PARA_TABL") {
        return Err(args.not_implemented("NOM_PARA_TABL", ""));
    }
    let (_, table) = table_of(study, args, "TABLE")?;
    let t = table
        .filter_all(&filters_of(args)?)
        .map_err(|e| table_error(args, "FILTRE", e))?;
    let px = args.text("PARA_X").unwrap_or_default();
    let py = args.text("PARA_Y").unwrap_or_default();
    let xs = t.column(px).map_err(|e| table_error(args, "PARA_X", e))?;
    let ys = t.column(py).map_err(|e| table_error(args, "PARA_Y", e))?;
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for (a, b) in xs.into_iter().zip(ys) {
        if let (Some(a), Some(b)) = (a.and_then(|c| c.as_f64()), b.and_then(|c| c.as_f64())) {
            x.push(a);
            y.push(b);
        }
    }
    Function::new(px, py, x, y).map_err(|e| args.error("TABLE", e))
}
