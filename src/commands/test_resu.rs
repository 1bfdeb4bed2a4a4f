//! TEST_RESU: checks values of results against recorded and reference values.

use super::blocks::*;
use super::post_args::{
    alarm, cham_no_of, component_index, is_gauss_name, mesh_for_field, mesh_of_result, node_name,
    report_checks, result_of, run_checks, single_cell, single_node, step_gauss, step_nodal,
    test_spec,
};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;
use crate::diag::Diagnostic;
use crate::post::test_report::{format_checks, header_lines, resu_block, Value};
use crate::result::{Access, NodalField};
use crate::study::Study;

pub fn def() -> CommandDef {
    let (refe_kws, refe_rules) = c_test_reference(true, false);
    let mut resu = vec![
        concept("RESULTAT", RESULTS).required().kw(),
        int("NUME_ORDRE").doc("stored index tested").kw(),
        real("INST")
            .doc("instant tested, found with TOLE_MACHINE(2) and CRITERE(2)")
            .kw(),
        text("PARA")
            .doc("test a result parameter instead of a field")
            .kw(),
        text("NOM_CHAM").into(NOM_CHAM_RESU).kw(),
        text("NOM_CMP").kw(),
        text("NOM_VARI").doc("internal variable by name").kw(),
        text("GROUP_MA").kw(),
        text("MAILLE").hidden().kw(),
        text("NOEUD").many().hidden().kw(),
        text("GROUP_NO")
            .many()
            .doc("must hold exactly one node")
            .kw(),
        int("POINT").doc("Gauss point of an ELGA field").kw(),
        int("SOUS_POINT")
            .doc("sub-point of POINT: 1, the volume elements having one")
            .kw(),
    ];
    resu.extend(refe_kws);
    let mut rules = vec![
        un_parmi(&["NUME_ORDRE", "INST"]),
        un_parmi(&["NOM_CHAM", "PARA"]),
        present_absent(
            "PARA",
            &[
                "MAILLE", "GROUP_MA", "NOEUD", "GROUP_NO", "POINT", "NOM_CMP", "NOM_VARI",
            ],
        ),
        exclus(&["NOEUD", "GROUP_NO", "POINT"]),
        exclus(&["MAILLE", "GROUP_MA"]),
        exclus(&["NOM_CMP", "NOM_VARI"]),
    ];
    rules.extend(refe_rules);

    let (refe_kws, refe_rules) = c_test_reference(false, false);
    let mut cham_no = vec![
        concept("CHAM_GD", &[C::ChamNo]).required().kw(),
        text("NOEUD").hidden().kw(),
        text("GROUP_NO").doc("must hold exactly one node").kw(),
        text("NOM_CMP").kw(),
    ];
    cham_no.extend(refe_kws);
    let mut cham_no_rules = vec![
        exclus(&["NOEUD", "GROUP_NO"]),
        present_present("NOEUD", &["NOM_CMP"]),
        present_present("GROUP_NO", &["NOM_CMP"]),
    ];
    cham_no_rules.extend(refe_rules);

    let spec = command(
        "TEST_RESU",
        Produces::Nothing,
        vec![
            fact("RESU", resu)
                .many()
                .rules(rules)
                .doc("one value of a result field at one node, instant and component")
                .kw(),
            fact("CHAM_NO", cham_no)
                .many()
                .rules(cham_no_rules)
                .doc("one value of a nodal field")
                .kw(),
        ],
    )
    .rules(vec![au_moins_un(&["RESU", "CHAM_NO"])])
    .doc("Tests computed values: non-regression against VALE_CALC, and against VALE_REFE when REFERENCE is given; prints OK/NOOK/SKIP lines.");
    CommandDef { spec, exec }
}

/// Every RESU occurrence, then every CHAM_NO occurrence, in order: each
/// prints its block in the .resu. A value that cannot be found is an error
/// (it stops the study), never a NOOK line.
fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    for occ in args.facts("RESU") {
        let spec = test_spec(occ)?;
        if occ.has("TYPE_TEST") {
            if let Some(k) = ["NOEUD", "GROUP_NO", "POINT"]
                .into_iter()
                .find(|k| occ.has(k))
            {
                // code_aster's trresu: an alarm (CALCULEL6_96), and the
                // aggregate still runs over the whole field.
                alarm(
                    study,
                    "TEST_RESU",
                    "CALCULEL6_96",
                    &format!(
                        "RESU with TYPE_TEST ignores {k}: the {} is taken over the whole field, not over {k}",
                        occ.text("TYPE_TEST").unwrap_or_default()
                    ),
                );
            }
        }
        let (name, fields, computed) = resu_value(study, occ)?;
        let lines = run_checks(occ, &spec, &Value::Real(computed))?;
        let fields: Vec<(&str, &str)> = fields.iter().map(|(k, v)| (*k, v.as_str())).collect();
        let block = resu_block(&name, &fields, &lines);
        report_checks(study, occ, &block, &lines);
    }
    for occ in args.facts("CHAM_NO") {
        let spec = test_spec(occ)?;
        let (name, fields, computed) = cham_no_value(study, occ)?;
        let lines = run_checks(occ, &spec, &Value::Real(computed))?;
        let mut block = String::new();
        let fields: Vec<(&str, &str)> = fields.iter().map(|(k, v)| (*k, v.as_str())).collect();
        for l in header_lines("CHAM_NO", &name, &fields) {
            block.push_str(&l);
            block.push('\n');
        }
        for l in format_checks(&lines) {
            block.push_str(&l);
            block.push('\n');
        }
        block.push_str("  \n");
        report_checks(study, occ, &block, &lines);
    }
    Ok(None)
}

/// Header columns of the .resu block, in order.
type Header = Vec<(&'static str, String)>;

/// The value a RESU occurrence tests, with the result name and the header
/// columns.
fn resu_value(study: &Study, occ: &Args) -> Result<(String, Header, f64), Diagnostic> {
    if occ.has("PARA") {
        return Err(occ.not_implemented("PARA", ""));
    }
    let (rname, res) = result_of(study, occ, "RESULTAT")?;
    let (access, key) = match occ.int("NUME_ORDRE") {
        Some(n) => (
            Access::NumeOrdre(
                usize::try_from(n)
                    .map_err(|_| occ.error("NUME_ORDRE", format!("NUME_ORDRE {n} is negative")))?,
            ),
            "NUME_ORDRE",
        ),
        None => {
            // The instant is searched with TOLE_MACHINE(2) and CRITERE(2).
            let inst = occ
                .real("INST")
                .ok_or_else(|| occ.error("", "NUME_ORDRE or INST is needed"))?;
            let tole = occ.reals("TOLE_MACHINE").get(1).copied().unwrap_or(1e-6);
            let crit = occ.texts("CRITERE").get(1).copied().unwrap_or("RELATIF");
            (
                Access::Inst {
                    inst,
                    precision: tole,
                    relative: crit != "ABSOLU",
                },
                "INST",
            )
        }
    };
    let step = res.find(access).map_err(|e| occ.error(key, e))?;
    let nom_cham = occ.text("NOM_CHAM").unwrap_or_default();
    let mut header: Header = vec![
        ("NUME_ORDRE", step.nume_ordre.to_string()),
        ("NOM_CHAM", nom_cham.to_string()),
    ];
    let gauss = is_gauss_name(nom_cham);
    if occ.has("SOUS_POINT") && (!gauss || occ.has("TYPE_TEST")) {
        return Err(occ.error(
            "SOUS_POINT",
            format!("SOUS_POINT selects a sub-point of one Gauss point (with POINT) of an ELGA field, not of {nom_cham}{}", if occ.has("TYPE_TEST") { " with TYPE_TEST" } else { "" }),
        ));
    }
    if nom_cham.ends_with("_ELNO") {
        let (v, more) = elno_value(study, occ, rname, res, step, nom_cham)?;
        header.extend(more);
        return Ok((rname.to_string(), header, v));
    }
    if let Some(tt) = occ.text("TYPE_TEST") {
        // The rank of a named variable depends on each cell's law: a
        // TYPE_TEST over the field would have to pick it cell by cell;
        // it used to aggregate every component instead.
        if occ.has("NOM_VARI") {
            return Err(occ.not_implemented(
                "NOM_VARI",
                "NOM_VARI with TYPE_TEST (give NOM_CMP='V1', 'V2'...)",
            ));
        }
        let v = if gauss {
            let f = step_gauss(step, nom_cham, occ, "NOM_CHAM", rname)?;
            aggregate(occ, &f.components, &f.values, nom_cham, tt)?
        } else {
            let f = step_nodal(step, nom_cham, occ, "NOM_CHAM", rname)?;
            aggregate(occ, &f.components, &f.values, nom_cham, tt)?
        };
        if let Some(c) = occ.text("NOM_CMP") {
            header.push(("NOM_CMP", c.to_string()));
        }
        header.push(("TYPE_TEST", tt.to_string()));
        return Ok((rname.to_string(), header, v));
    }
    let (nom_vari, cmp) = component_to_test(occ, &mut header)?;
    let mesh = mesh_of_result(study, occ, "RESULTAT", rname, res)?;
    if gauss {
        if occ.has("GROUP_NO") || occ.has("NOEUD") {
            return Err(occ.error(
                if occ.has("GROUP_NO") {
                    "GROUP_NO"
                } else {
                    "NOEUD"
                },
                format!("{nom_cham} is a Gauss-point field: give GROUP_MA (or MAILLE) and POINT"),
            ));
        }
        let (cell, ckey, clabel) = single_cell(mesh, occ)?;
        let point = occ
            .int("POINT")
            .ok_or_else(|| occ.error("POINT", format!("POINT is needed to test {nom_cham}")))?;
        let f = step_gauss(step, nom_cham, occ, "NOM_CHAM", rname)?;
        let c = match nom_vari {
            Some(v) => vari_index(res, cell, v, occ, nom_cham)?,
            None => component_index(&f.components, cmp, occ, "NOM_CMP", nom_cham)?,
        };
        let npg = f.npg(cell);
        if npg == 0 {
            // A cell of the mesh without an element (a skin cell, or one
            // outside AFFE_MODELE) has no Gauss points: "POINT must be in
            // 1..0" said nothing of why.
            return Err(occ.error(
                ckey,
                format!(
                    "the cell {} ({ckey}={clabel}) has no Gauss point in {nom_cham}: it carries no element of the model (a skin cell, or a cell outside AFFE_MODELE)",
                    super::post_args::cell_name(cell)
                ),
            ));
        }
        if point < 1 || point as usize > npg {
            return Err(occ.error(
                "POINT",
                format!(
                    "cell {} has {npg} Gauss point(s) in {nom_cham}: POINT must be in 1..{npg}",
                    super::post_args::cell_name(cell)
                ),
            ));
        }
        let v = f.cell(cell)[(point as usize - 1) * f.ncmp() + c];
        if v.is_nan() {
            return Err(occ.error(
                "NOM_CMP",
                format!(
                    "{cmp} is absent at point {point} of cell {}",
                    super::post_args::cell_name(cell)
                ),
            ));
        }
        header.push((ckey, clabel));
        header.push(("POINT", point.to_string()));
        // The volume elements have one sub-point per Gauss point (sub-
        // points are the layers and fibres of shells, pipes and beams).
        if let Some(sp) = occ.int("SOUS_POINT") {
            if sp != 1 {
                return Err(occ.error(
                    "SOUS_POINT",
                    format!(
                        "the points of cell {} in {nom_cham} have one sub-point each: SOUS_POINT must be 1",
                        super::post_args::cell_name(cell)
                    ),
                ));
            }
            header.push(("SOUS_POINT", "1".to_string()));
        }
        return Ok((rname.to_string(), header, v));
    }
    if occ.has("GROUP_MA") || occ.has("MAILLE") {
        return Err(occ.error(
            if occ.has("GROUP_MA") {
                "GROUP_MA"
            } else {
                "MAILLE"
            },
            format!("{nom_cham} is a nodal field: give GROUP_NO (or NOEUD)"),
        ));
    }
    let (node, nkey, nlabel) = single_node(mesh, occ)?;
    let f = step_nodal(step, nom_cham, occ, "NOM_CHAM", rname)?;
    let v = match nom_vari {
        Some(name) => {
            let k = node_vari_index(res, mesh, node, name, occ, nom_cham)?;
            let Some(c) = f.components.get(k) else {
                return Err(occ.error(
                    "NOM_VARI",
                    format!(
                        "{nom_cham} has {} components, {name} is V{}",
                        f.ncmp(),
                        k + 1
                    ),
                ));
            };
            node_value(occ, f, nom_cham, node, c)?
        }
        None => node_value(occ, f, nom_cham, node, cmp)?,
    };
    header.push((nkey, nlabel));
    Ok((rname.to_string(), header, v))
}

/// The CALC_CHAMP keyword whose option computes the field `nom_cham`
/// (for the message of a field a result does not hold).
fn calc_champ_keyword(nom_cham: &str) -> &'static str {
    match nom_cham.split('_').next().unwrap_or("") {
        "SIEQ" | "EPEQ" => "CRITERES",
        "VARI" => "VARI_INTERNE",
        "ENEL" => "ENERGIE",
        "EPSI" | "EPSG" | "EPSL" | "EPSP" => "DEFORMATION",
        _ => "CONTRAINTE",
    }
}

/// The column of internal variable `name` at a node of a VARI_NOEU field:
/// the nodal mean mixes the cells holding the node, so their laws must
/// agree on the variable's rank.
fn node_vari_index(
    res: &crate::result::EvolNoli,
    mesh: &crate::mesh::Mesh,
    node: usize,
    name: &str,
    occ: &Args,
    nom_cham: &str,
) -> Result<usize, Diagnostic> {
    let mut rank: Option<usize> = None;
    for (c, cell) in mesh.cells.iter().enumerate() {
        if !cell.nodes.contains(&node) || !matches!(res.comportement.get(c), Some(Some(_))) {
            continue;
        }
        let k = vari_index(res, c, name, occ, nom_cham)?;
        if rank.is_some_and(|r| r != k) {
            return Err(occ.error(
                "NOM_VARI",
                format!(
                    "the cells around node {} give {name} different ranks in their laws: test NOM_CMP='V..' instead",
                    node_name(node)
                ),
            ));
        }
        rank = Some(k);
    }
    rank.ok_or_else(|| {
        occ.error(
            "NOM_VARI",
            format!("node {} is on no cell with a behaviour", node_name(node)),
        )
    })
}

/// The column of the internal variable named `name` (NOM_VARI) in the
/// VARI_* field of `cell`: its rank in the cell's law (RELATION and
/// DEFORMATION the result kept), V1 first.
fn vari_index(
    res: &crate::result::EvolNoli,
    cell: usize,
    name: &str,
    occ: &Args,
    nom_cham: &str,
) -> Result<usize, Diagnostic> {
    if !nom_cham.starts_with("VARI_") {
        return Err(occ.error(
            "NOM_VARI",
            format!("NOM_VARI names an internal variable: NOM_CHAM must be VARI_ELGA (or VARI_ELNO/VARI_NOEU), not {nom_cham}"),
        ));
    }
    let Some(Some((relation, deformation))) = res.comportement.get(cell) else {
        return Err(occ.error(
            "NOM_VARI",
            format!(
                "cell {} has no behaviour in this result",
                super::post_args::cell_name(cell)
            ),
        ));
    };
    let names = crate::law::internal_variable_names(relation, deformation).unwrap_or(&[]);
    names.iter().position(|n| *n == name).ok_or_else(|| {
        occ.error(
            "NOM_VARI",
            format!(
                "{relation} with DEFORMATION='{deformation}' has no internal variable {name}; its variables: {}",
                if names.is_empty() { "none".to_string() } else { names.join(", ") }
            ),
        )
    })
}

/// The value a CHAM_NO occurrence tests.
fn cham_no_value(study: &Study, occ: &Args) -> Result<(String, Header, f64), Diagnostic> {
    let (fname, field) = cham_no_of(study, occ, "CHAM_GD")?;
    let mut header: Header = Vec::new();
    if let Some(tt) = occ.text("TYPE_TEST") {
        let v = aggregate(occ, &field.components, &field.values, fname, tt)?;
        if let Some(c) = occ.text("NOM_CMP") {
            header.push(("NOM_CMP", c.to_string()));
        }
        header.push(("TYPE_TEST", tt.to_string()));
        return Ok((fname.to_string(), header, v));
    }
    if !(occ.has("GROUP_NO") || occ.has("NOEUD")) {
        return Err(occ.error("", "give GROUP_NO (or NOEUD) and NOM_CMP, or TYPE_TEST"));
    }
    let cmp = occ.text("NOM_CMP").unwrap_or_default();
    let groups = occ.texts("GROUP_NO");
    let mesh = mesh_for_field(study, occ, "CHAM_GD", fname, field, &groups)?;
    let (node, nkey, nlabel) = single_node(mesh, occ)?;
    let v = node_value(occ, field, fname, node, cmp)?;
    header.push(("NOM_CMP", cmp.to_string()));
    header.push((nkey, nlabel));
    Ok((fname.to_string(), header, v))
}

/// One component at one node; absent is an error on NOM_CMP.
fn node_value(
    occ: &Args,
    f: &NodalField,
    field: &str,
    node: usize,
    cmp: &str,
) -> Result<f64, Diagnostic> {
    component_index(&f.components, cmp, occ, "NOM_CMP", field)?;
    f.get(node, cmp).ok_or_else(|| {
        occ.error(
            "NOM_CMP",
            format!(
                "component {cmp} of {field} is absent at node {}",
                node_name(node)
            ),
        )
    })
}

/// TYPE_TEST over a whole field (one component with NOM_CMP, else all);
/// absent values are left out.
fn aggregate(
    occ: &Args,
    components: &[String],
    values: &[f64],
    field: &str,
    type_test: &str,
) -> Result<f64, Diagnostic> {
    let n = components.len().max(1);
    let only = match occ.text("NOM_CMP") {
        Some(c) => Some(component_index(components, c, occ, "NOM_CMP", field)?),
        None => None,
    };
    let vals = values
        .iter()
        .enumerate()
        .filter(|(i, v)| !v.is_nan() && only.is_none_or(|c| i % n == c))
        .map(|(_, v)| *v);
    let mut count = 0usize;
    let mut acc: Option<f64> = None;
    for v in vals {
        count += 1;
        acc = Some(match (type_test, acc) {
            ("SOMM", a) => a.unwrap_or(0.0) + v,
            ("SOMM_ABS", a) => a.unwrap_or(0.0) + v.abs(),
            ("MAX", Some(a)) => a.max(v),
            ("MIN", Some(a)) => a.min(v),
            (_, _) => v,
        });
    }
    match acc {
        Some(v) if count > 0 => Ok(v),
        _ => Err(occ.error(
            "TYPE_TEST",
            format!("field {field} has no value to aggregate"),
        )),
    }
}

/// An ELNO field's value (CALC_CHAMP SIEF_ELNO, SIGM_ELNO): the value of
/// NOM_CMP that the cell of GROUP_MA/MAILLE gives at the node of
/// GROUP_NO/NOEUD, or TYPE_TEST over the whole field.
fn elno_value(
    study: &Study,
    occ: &Args,
    rname: &str,
    res: &crate::result::EvolNoli,
    step: &crate::result::Step,
    nom_cham: &str,
) -> Result<(f64, Header), Diagnostic> {
    let f = step.elno.get(nom_cham).ok_or_else(|| {
        occ.error(
            "NOM_CHAM",
            format!(
                "result {rname} has no field {nom_cham} at NUME_ORDRE {} (compute it with CALC_CHAMP {}='{nom_cham}')",
                step.nume_ordre,
                calc_champ_keyword(nom_cham)
            ),
        )
    })?;
    let mut header: Header = Vec::new();
    if let Some(tt) = occ.text("TYPE_TEST") {
        let v = aggregate(occ, &f.components, &f.values, nom_cham, tt)?;
        if let Some(c) = occ.text("NOM_CMP") {
            header.push(("NOM_CMP", c.to_string()));
        }
        header.push(("TYPE_TEST", tt.to_string()));
        return Ok((v, header));
    }
    let (nom_vari, cmp) = component_to_test(occ, &mut header)?;
    let mesh = mesh_of_result(study, occ, "RESULTAT", rname, res)?;
    if !(occ.has("GROUP_MA") || occ.has("MAILLE")) || !(occ.has("GROUP_NO") || occ.has("NOEUD")) {
        return Err(occ.error(
            "NOM_CHAM",
            format!("{nom_cham} is a field by element at nodes: give the cell (GROUP_MA or MAILLE) and the node (GROUP_NO or NOEUD)"),
        ));
    }
    let (cell, ckey, clabel) = single_cell(mesh, occ)?;
    let (node, nkey, nlabel) = single_node(mesh, occ)?;
    let c = match nom_vari {
        Some(v) => vari_index(res, cell, v, occ, nom_cham)?,
        None => component_index(&f.components, cmp, occ, "NOM_CMP", nom_cham)?,
    };
    let Some(a) = mesh.cells[cell].nodes.iter().position(|&n| n == node) else {
        return Err(occ.error(
            nkey,
            format!(
                "node {} is not a node of cell {}",
                node_name(node),
                super::post_args::cell_name(cell)
            ),
        ));
    };
    if f.npg(cell) != mesh.cells[cell].nodes.len() {
        return Err(occ.error(
            ckey,
            format!(
                "cell {} has no value in {nom_cham} (not an element of the model)",
                super::post_args::cell_name(cell)
            ),
        ));
    }
    header.push((ckey, clabel));
    header.push((nkey, nlabel));
    Ok((f.cell(cell)[a * f.ncmp() + c], header))
}

/// The NOM_VARI or NOM_CMP of a one-value test, added to the report's
/// header; NOM_VARI comes back as `Some` when it was the one given.
fn component_to_test<'a>(
    occ: &'a Args,
    header: &mut Vec<(&'static str, String)>,
) -> Result<(Option<&'a str>, &'a str), Diagnostic> {
    let nom_vari = occ.text("NOM_VARI");
    let cmp = match nom_vari {
        Some(v) => v,
        None => occ.text("NOM_CMP").ok_or_else(|| {
            occ.error(
                "NOM_CMP",
                "NOM_CMP is needed to test one value (or give TYPE_TEST)",
            )
        })?,
    };
    header.push((
        if nom_vari.is_some() {
            "NOM_VARI"
        } else {
            "NOM_CMP"
        },
        cmp.to_string(),
    ));
    Ok((nom_vari, cmp))
}
