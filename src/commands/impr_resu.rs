//! IMPR_RESU: writes meshes and results (MED files, readable listings).

use super::blocks::*;
use super::post_args::{
    alarm, cell_name, cham_no_of, component_index, limitation, mesh_for_field, mesh_named,
    node_name, nodes_of, pad8, result_of, select_steps,
};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;
use crate::diag::Diagnostic;
use crate::medio::{self, ElemField, FieldStep, NodalField as MedNodal};
use crate::mesh::Mesh;
use crate::post::table::RealFormat;
use crate::result::{GaussField, NodalField, Step};
use crate::study::Study;

pub fn def() -> CommandDef {
    let mut acces = vec![
        text("TOUT_CHAM").into(&["OUI", "NON"]).kw(),
        text("NOM_CHAM")
            .many()
            .into(NOM_CHAM_RESU)
            .doc("fields written")
            .kw(),
        text("TOUT_ORDRE").into(&["OUI"]).kw(),
        int("NUME_ORDRE").many().kw(),
        concept("LIST_ORDRE", &[C::Listis])
            .doc("stored indices of a DEFI_LIST_ENTI list")
            .kw(),
        real("INST").many().kw(),
        concept("LIST_INST", &[C::Listr8]).kw(),
    ];
    acces.extend(critere_precision(1e-6));
    let unit = |format: &'static str, unite: i64| {
        block(
            match format {
                "MED" => "b_format_med",
                "RESULTAT" => "b_format_resultat",
                "IDEAS" => "b_format_ideas",
                "ASTER" => "b_format_aster",
                _ => "b_format_gmsh",
            },
            eq("FORMAT", format),
            vec![int("UNITE")
                .default(i(unite))
                .doc("logical unit written")
                .kw()],
        )
        .kw()
    };
    let spec = command(
        "IMPR_RESU",
        Produces::Nothing,
        vec![
            text("FORMAT")
                .into(&["RESULTAT", "IDEAS", "ASTER", "MED", "GMSH"])
                .default(t("MED"))
                .kw(),
            unit("MED", 80),
            unit("RESULTAT", 8),
            unit("IDEAS", 30),
            unit("ASTER", 26),
            unit("GMSH", 37),
            block(
                "b_version_med",
                eq("FORMAT", "MED"),
                vec![text("VERSION_MED")
                    .default(t("3.3.1"))
                    .doc("version of the MED file format written")
                    .kw()],
            )
            .kw(),
            concept("MODELE", &[C::Modele]).kw(),
            fact(
                "RESU",
                vec![
                    concept("MAILLAGE", &[C::Maillage]).doc("mesh written too").kw(),
                    concept("CHAM_GD", &[C::ChamNo]).kw(),
                    concept("RESULTAT", RESULTS).kw(),
                    oui_non("INFO_MAILLAGE", "NON").kw(),
                    block("b_extrac", present("RESULTAT"), acces)
                        .rules(vec![
                            exclus(&["TOUT_CHAM", "NOM_CHAM"]),
                            exclus(&["TOUT_ORDRE", "NUME_ORDRE", "LIST_ORDRE", "INST", "LIST_INST"]),
                        ])
                        .kw(),
                    text("TOUT_CMP").into(&["OUI"]).kw(),
                    text("NOM_CMP").many().kw(),
                    text("NOM_CHAM_MED")
                        .many()
                        .doc("MED field name; default: result name padded with '_' to 8, then the field name")
                        .kw(),
                    text("NOM_RESU_MED").kw(),
                    tout(),
                    group_no(),
                    noeud(),
                    group_ma(),
                    maille(),
                    text("VALE_MAX").into(&["OUI"]).kw(),
                    text("VALE_MIN").into(&["OUI"]).kw(),
                    real("BORNE_SUP").kw(),
                    real("BORNE_INF").kw(),
                    oui_non("IMPR_COOR", "NON").kw(),
                    text("FORMAT_R")
                        .default(t("1PE21.14"))
                        .doc("format of reals (RESULTAT/ASTER formats)")
                        .kw(),
                    text("SOUS_TITRE").many().kw(),
                ],
            )
            .required()
            .many()
            .rules(vec![
                au_moins_un(&["CHAM_GD", "RESULTAT", "MAILLAGE"]),
                exclus(&["CHAM_GD", "RESULTAT"]),
                exclus(&["TOUT_CMP", "NOM_CMP"]),
                exclus(&["NOM_CHAM_MED", "NOM_RESU_MED"]),
            ])
            .doc("what to write")
            .kw(),
            info(),
        ],
    )
    .doc("Writes a mesh and/or results in a file format.");
    CommandDef { spec, exec }
}

fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    match args.text("FORMAT").unwrap_or("MED") {
        "MED" => med(study, args),
        "RESULTAT" => listing(study, args),
        other => Err(args.not_implemented("FORMAT", &format!("FORMAT='{other}'"))),
    }?;
    Ok(None)
}

// ---------------------------------------------------------------- MED

/// Keywords of a RESU occurrence the MED writer does not honour yet; they
/// are refused so that a file is never silently different from the request.
/// Restrictions to part of the mesh: MED would store them with profiles,
/// which the writer does not build. The whole fields are written instead,
/// with an alarm: a superset of what was asked, every number right, where
/// refusing would stop the study at its output after the run.
const MED_WHOLE_MESH: [&str; 4] = ["GROUP_NO", "NOEUD", "GROUP_MA", "MAILLE"];

const MED_UNSUPPORTED: [&str; 4] = ["VALE_MAX", "VALE_MIN", "BORNE_SUP", "BORNE_INF"];

/// What one IMPR_RESU puts in its MED file.
#[derive(Default)]
struct MedContent {
    /// The mesh (named after its concept) and the occurrence that set it.
    mesh: Option<Mesh>,
    nodal: Vec<MedNodal>,
    cells: Vec<ElemField>,
}

/// The marker logged after a MED write.
fn med_marker(unit: i64, path: &std::path::Path) -> String {
    format!(
        "    IMPR_RESU: MED file of unit {unit} written: {}",
        path.display()
    )
}

/// FORMAT='MED': the mesh and the fields of every occurrence in one file
/// (all occurrences must be on the same mesh).
fn med(study: &mut Study, args: &Args) -> Result<(), Diagnostic> {
    let unit = args.int("UNITE").unwrap_or(80);
    let path = study.unit_path(unit);
    let mut out = MedContent::default();
    let mut notes: Vec<String> = Vec::new();
    let mut limits: Vec<String> = Vec::new();
    for occ in args.facts("RESU") {
        for k in MED_UNSUPPORTED {
            if occ.has(k) {
                return Err(occ.not_implemented(k, "MED output of part of a mesh"));
            }
        }
        for k in MED_WHOLE_MESH.into_iter().filter(|k| occ.has(k)) {
            limits.push(format!(
                "{k}={}: the fields are written on the whole mesh (MED profiles, which \
                 would store part of a mesh, are not built)",
                occ.texts(k).join(", ")
            ));
        }
        if occ.has("NOM_RESU_MED") {
            return Err(occ.not_implemented("NOM_RESU_MED", ""));
        }
        if let Some(m) = occ.concept("MAILLAGE") {
            let mesh = mesh_named(study, m)
                .ok_or_else(|| occ.error("MAILLAGE", format!("{m} holds no mesh")))?;
            set_mesh(&mut out, occ, "MAILLAGE", m, mesh)?;
        }
        if occ.has("RESULTAT") {
            let (rname, res) = result_of(study, occ, "RESULTAT")?;
            let mesh = mesh_named(study, &res.mesh).ok_or_else(|| {
                occ.error(
                    "RESULTAT",
                    format!("the mesh '{}' of result {rname} is not available", res.mesh),
                )
            })?;
            set_mesh(&mut out, occ, "RESULTAT", &res.mesh, mesh)?;
            check_restriction(mesh, occ)?;
            let steps = select_steps(study, res, occ)?;
            result_fields(occ, rname, &steps, mesh, &mut out, &mut notes, &mut limits)?;
        } else if occ.has("CHAM_GD") {
            let (fname, field) = cham_no_of(study, occ, "CHAM_GD")?;
            let mesh = mesh_for_field(study, occ, "CHAM_GD", fname, field, &[])?;
            let mname = study
                .concepts
                .iter()
                .find(|c| matches!(&c.data, crate::concepts::ConceptData::Mesh(m) if **m == *mesh))
                .map(|c| c.name.clone())
                .unwrap_or_else(|| "MAILLAGE".to_string());
            set_mesh(&mut out, occ, "CHAM_GD", &mname, mesh)?;
            check_restriction(mesh, occ)?;
            let name = occ
                .texts("NOM_CHAM_MED")
                .first()
                .map(|s| s.to_string())
                .unwrap_or_else(|| fname.to_string());
            let (components, values) = pick_components(occ, field, fname)?;
            out.nodal.push(MedNodal {
                name,
                components,
                steps: vec![FieldStep {
                    numdt: -1,
                    time: 0.0,
                    values,
                }],
            });
        }
    }
    let Some(mesh) = out.mesh.take() else {
        return Err(args.error(
            "RESU",
            "nothing to write: give MAILLAGE, RESULTAT or CHAM_GD",
        ));
    };
    let marker = med_marker(unit, &path);
    let (nodal, cells) = match study.med_files.get(&unit) {
        // A later IMPR_RESU on the unit: its fields join the file's.
        Some(prev) if prev.mesh.coords == mesh.coords && prev.mesh.cells == mesh.cells => {
            let nodal = merge_fields(prev.nodal.clone(), &out.nodal);
            let cells = merge_fields(prev.cells.clone(), &out.cells);
            let added = out.nodal.len() + out.cells.len();
            study.log(format!(
                "    IMPR_RESU: {added} field(s) added to the MED file of unit {unit} (written by an earlier IMPR_RESU)"
            ));
            (nodal, cells)
        }
        Some(prev) => {
            return Err(args.not_implemented(
                "UNITE",
                &format!(
                    "a second mesh ({}) in the MED file of unit {unit}, which holds mesh {}: \
                     write it with another UNITE",
                    mesh.name, prev.mesh.name
                ),
            ))
        }
        None => (out.nodal, out.cells),
    };
    let out = MedContent {
        mesh: None,
        nodal,
        cells,
    };
    medio::write_result_fields(&path, &mesh, &out.nodal, &out.cells)
        .map_err(|e| args.error("UNITE", e.to_string()))?;
    for n in notes {
        alarm(study, "IMPR_RESU", "", &n);
    }
    for n in limits {
        limitation(study, "IMPR_RESU", &n);
    }
    study.log(marker);
    study.log(format!(
        "    mesh {} ({} nodes, {} cells); fields: {}",
        mesh.name,
        mesh.nnodes(),
        mesh.ncells(),
        out.nodal
            .iter()
            .map(|f| format!("{} ({} steps)", f.name, f.steps.len()))
            .chain(out.cells.iter().map(|f| format!(
                "{} (cell means, {} steps)",
                f.name,
                f.steps.len()
            )))
            .collect::<Vec<_>>()
            .join(", ")
    ));
    let written = crate::study::MedWritten {
        mesh,
        nodal: out.nodal,
        cells: out.cells,
    };
    study.med_files.insert(unit, written);
    Ok(())
}

/// A MED field as the merge of two writes sees it.
trait Stepped: Clone {
    fn name(&self) -> &str;
    fn steps_mut(&mut self) -> &mut Vec<FieldStep>;
}

impl Stepped for MedNodal {
    fn name(&self) -> &str {
        &self.name
    }
    fn steps_mut(&mut self) -> &mut Vec<FieldStep> {
        &mut self.steps
    }
}

impl Stepped for ElemField {
    fn name(&self) -> &str {
        &self.name
    }
    fn steps_mut(&mut self) -> &mut Vec<FieldStep> {
        &mut self.steps
    }
}

/// The fields of a file with `new` added: a new name is appended, the
/// steps of a name already there join its steps (a step of the same
/// NUME_ORDRE replaced), in NUME_ORDRE order.
fn merge_fields<F: Stepped>(mut fields: Vec<F>, new: &[F]) -> Vec<F> {
    for f in new {
        match fields.iter_mut().find(|g| g.name() == f.name()) {
            Some(g) => {
                let steps = g.steps_mut();
                for st in f.clone().steps_mut().drain(..) {
                    steps.retain(|s| s.numdt != st.numdt);
                    steps.push(st);
                }
                steps.sort_by_key(|s| s.numdt);
            }
            None => fields.push(f.clone()),
        }
    }
    fields
}

/// The groups and names of a whole-mesh restriction (MED_WHOLE_MESH) must
/// still exist in the mesh written: a misspelt group is an error, as in
/// code_aster, even though the fields are written whole.
fn check_restriction(mesh: &Mesh, occ: &Args) -> Result<(), Diagnostic> {
    use super::mesh_args::{check_groups, GroupKind};
    check_groups(mesh, occ, "GROUP_MA", GroupKind::Cells)?;
    check_groups(mesh, occ, "GROUP_NO", GroupKind::Nodes)?;
    for m in occ.texts("MAILLE") {
        super::post_args::cell_by_name(mesh, occ, "MAILLE", m)?;
    }
    for n in occ.texts("NOEUD") {
        super::post_args::node_by_name(mesh, occ, "NOEUD", n)?;
    }
    Ok(())
}

/// Sets the mesh of the file, or checks that an occurrence uses the same.
fn set_mesh(
    out: &mut MedContent,
    occ: &Args,
    key: &str,
    name: &str,
    mesh: &Mesh,
) -> Result<(), Diagnostic> {
    match &out.mesh {
        None => {
            let mut m = mesh.clone();
            m.name = name.to_string();
            out.mesh = Some(m);
            Ok(())
        }
        Some(m) if m.coords == mesh.coords && m.cells == mesh.cells => Ok(()),
        Some(m) => Err(occ.not_implemented(
            key,
            &format!(
                "a second mesh ({name}) in the MED file of mesh {}: write it with another IMPR_RESU and UNITE",
                m.name
            ),
        )),
    }
}

/// The fields of a result over the selected steps: nodal fields as they
/// are, Gauss-point fields as their mean per cell (the MED layer does not
/// write Gauss points yet), each named `<result padded to 8 with _><field>`
/// unless NOM_CHAM_MED renames it.
fn result_fields(
    occ: &Args,
    rname: &str,
    steps: &[&Step],
    mesh: &Mesh,
    out: &mut MedContent,
    notes: &mut Vec<String>,
    limits: &mut Vec<String>,
) -> Result<(), Diagnostic> {
    let names: Vec<String> = if occ.has("NOM_CHAM") {
        occ.texts("NOM_CHAM")
            .iter()
            .map(|s| s.to_string())
            .collect()
    } else {
        let mut all: Vec<String> = Vec::new();
        let mut elno: Vec<&str> = Vec::new();
        for s in steps {
            for n in s.nodal.keys().chain(s.gauss.keys()) {
                if !all.contains(n) {
                    all.push(n.clone());
                }
            }
            for n in s.elno.keys() {
                if !elno.contains(&n.as_str()) {
                    elno.push(n);
                }
            }
        }
        // Fields by element at nodes would be written as cell means (the
        // writer has no ELNO support): only when asked by name, and said.
        if !elno.is_empty() {
            notes.push(format!(
                "the fields by element at nodes of result {rname} ({}) are not written without NOM_CHAM: name them in NOM_CHAM to write their mean per cell",
                elno.join(", ")
            ));
        }
        all
    };
    let renames = occ.texts("NOM_CHAM_MED");
    if !renames.is_empty() && renames.len() != names.len() {
        return Err(occ.error(
            "NOM_CHAM_MED",
            format!(
                "{} MED names for {} fields: give one per NOM_CHAM",
                renames.len(),
                names.len()
            ),
        ));
    }
    for (i, nom_cham) in names.iter().enumerate() {
        let med_name = renames
            .get(i)
            .map(|s| s.to_string())
            .unwrap_or_else(|| format!("{}{nom_cham}", pad8(rname)));
        let nodal: Vec<(&Step, &NodalField)> = steps
            .iter()
            .filter_map(|s| s.nodal.get(nom_cham).map(|f| (*s, f)))
            .collect();
        // ELNO fields (CALC_CHAMP *_ELNO) go the same way as Gauss ones,
        // their "points" being the cell's nodes.
        let at_nodes = nom_cham.ends_with("_ELNO");
        let gauss: Vec<(&Step, &GaussField)> = steps
            .iter()
            .filter_map(|s| {
                if at_nodes {
                    s.elno.get(nom_cham)
                } else {
                    s.gauss.get(nom_cham)
                }
                .map(|f| (*s, f))
            })
            .collect();
        if !nodal.is_empty() {
            let mut f = MedNodal {
                name: med_name,
                components: Vec::new(),
                steps: Vec::new(),
            };
            for (s, field) in nodal {
                let (components, values) = pick_components(occ, field, nom_cham)?;
                if f.steps.is_empty() {
                    f.components = components;
                } else if f.components != components {
                    return Err(occ.error(
                        "NOM_CHAM",
                        format!(
                            "the components of {nom_cham} change at NUME_ORDRE {}: one MED field cannot hold both",
                            s.nume_ordre
                        ),
                    ));
                }
                f.steps.push(FieldStep {
                    numdt: s.nume_ordre as i32,
                    time: s.inst,
                    values,
                });
            }
            out.nodal.push(f);
        } else if !gauss.is_empty() {
            if occ.has("NOM_CMP") {
                return Err(occ.not_implemented("NOM_CMP", "component selection of Gauss fields"));
            }
            let mut f = ElemField {
                name: med_name.clone(),
                components: gauss[0].1.components.clone(),
                steps: Vec::new(),
            };
            for (s, field) in gauss {
                if field.components != f.components || field.offsets.len() != mesh.ncells() + 1 {
                    return Err(occ.error(
                        "NOM_CHAM",
                        format!(
                            "{nom_cham} at NUME_ORDRE {} does not match the mesh or the other steps",
                            s.nume_ordre
                        ),
                    ));
                }
                f.steps.push(FieldStep {
                    numdt: s.nume_ordre as i32,
                    time: s.inst,
                    values: field.cell_means(mesh.ncells()),
                });
            }
            limits.push(if at_nodes {
                format!(
                    "{med_name}: the MED writer cannot store fields by element at nodes yet; \
                     the mean over the nodes of each cell is written as a cell field"
                )
            } else {
                format!(
                    "{med_name}: the MED writer cannot store Gauss points yet; the mean over \
                     the Gauss points of each cell is written as a cell field"
                )
            });
            out.cells.push(f);
        } else {
            notes.push(format!(
                "field {nom_cham} is not stored in result {rname} at the selected steps: not written"
            ));
        }
    }
    Ok(())
}

/// The components asked (NOM_CMP, or all) and the values node-major.
fn pick_components(
    occ: &Args,
    f: &NodalField,
    field: &str,
) -> Result<(Vec<String>, Vec<f64>), Diagnostic> {
    if !occ.has("NOM_CMP") {
        return Ok((f.components.clone(), f.values.clone()));
    }
    let idx: Vec<usize> = occ
        .texts("NOM_CMP")
        .iter()
        .map(|c| component_index(&f.components, c, occ, "NOM_CMP", field))
        .collect::<Result<_, _>>()?;
    let n = f.nnodes();
    let mut values = Vec::with_capacity(n * idx.len());
    for node in 0..n {
        values.extend(idx.iter().map(|&k| f.values[node * f.ncmp() + k]));
    }
    Ok((
        idx.iter().map(|&k| f.components[k].clone()).collect(),
        values,
    ))
}

// ---------------------------------------------------------------- RESULTAT

/// Keywords of a RESU occurrence the listing does not honour yet; they are
/// refused so that a listing is never silently different from the request
/// (code_aster's ircnrl/ircerl filter or summarise the values with them).
const LISTING_UNSUPPORTED: [(&str, &str); 4] = [
    (
        "VALE_MAX",
        "the largest value of each component (FORMAT='RESULTAT')",
    ),
    (
        "VALE_MIN",
        "the smallest value of each component (FORMAT='RESULTAT')",
    ),
    (
        "BORNE_SUP",
        "values filtered by a bound (FORMAT='RESULTAT')",
    ),
    (
        "BORNE_INF",
        "values filtered by a bound (FORMAT='RESULTAT')",
    ),
];

/// Keywords that code_aster's catalogue offers with FORMAT='MED' only.
const MED_ONLY: [&str; 2] = ["NOM_CHAM_MED", "NOM_RESU_MED"];

/// FORMAT='RESULTAT': readable listings of the fields, per stored step,
/// one line per node (`1X, name, values` in FORMAT_R, six values per
/// line) or per Gauss point.
fn listing(study: &mut Study, args: &Args) -> Result<(), Diagnostic> {
    let unit = args.int("UNITE").unwrap_or(8);
    let mut text = String::new();
    let mut notes: Vec<String> = Vec::new();
    for occ in args.facts("RESU") {
        for (k, what) in LISTING_UNSUPPORTED {
            if occ.has(k) {
                return Err(occ.not_implemented(k, what));
            }
        }
        if occ.text("IMPR_COOR") == Some("OUI") {
            return Err(occ.not_implemented(
                "IMPR_COOR",
                "the coordinates in the listing (FORMAT='RESULTAT')",
            ));
        }
        for k in MED_ONLY {
            if occ.has(k) {
                return Err(occ.error(
                    k,
                    format!("{k} names a field of a MED file: it is read with FORMAT='MED' only"),
                ));
            }
        }
        let fmt_text = occ.text("FORMAT_R").unwrap_or("1PE21.14");
        let fmt = RealFormat::from_fortran(fmt_text).ok_or_else(|| {
            occ.error(
                "FORMAT_R",
                format!("'{fmt_text}' is not a Fortran real format"),
            )
        })?;
        for title in occ.texts("SOUS_TITRE") {
            text.push_str(&format!("\n {title}\n"));
        }
        if occ.has("RESULTAT") {
            let (rname, res) = result_of(study, occ, "RESULTAT")?;
            let mesh = mesh_named(study, &res.mesh).ok_or_else(|| {
                occ.error(
                    "RESULTAT",
                    format!("the mesh of result {rname} is not available"),
                )
            })?;
            let sel = Selection::of(mesh, occ)?;
            let wanted: Vec<&str> = occ.texts("NOM_CHAM");
            let steps = select_steps(study, res, occ)?;
            for name in &wanted {
                let stored = steps.iter().any(|s| {
                    s.nodal.contains_key(*name)
                        || s.gauss.contains_key(*name)
                        || s.elno.contains_key(*name)
                });
                if !stored {
                    notes.push(format!(
                        "field {name} is not stored in result {rname} at the selected steps: not written"
                    ));
                }
            }
            for s in steps {
                for (name, f) in &s.nodal {
                    if wanted.is_empty() || wanted.contains(&name.as_str()) {
                        let (components, values) = pick_components(occ, f, name)?;
                        let f = NodalField { components, values };
                        text.push_str(&format!(
                            "\n CHAMP AUX NOEUDS DE NOM SYMBOLIQUE  {name}\n NUMERO D'ORDRE: {:>8} INST: {}\n\n",
                            s.nume_ordre,
                            fmt.format(s.inst)
                        ));
                        text.push_str(&node_lines(&f, &sel.nodes, &fmt));
                    }
                }
                for (name, f) in &s.gauss {
                    if wanted.is_empty() || wanted.contains(&name.as_str()) {
                        let f = pick_cell_components(occ, f, name)?;
                        text.push_str(&format!(
                            "\n CHAMP AUX POINTS DE GAUSS DE NOM SYMBOLIQUE  {name}\n NUMERO D'ORDRE: {:>8} INST: {}\n\n",
                            s.nume_ordre,
                            fmt.format(s.inst)
                        ));
                        text.push_str(&cell_lines(&f, &sel.cells, None, &fmt));
                    }
                }
                // Fields by element at nodes are printed when named only,
                // as the MED writer does: TOUT_CHAM means the fields the
                // run stored.
                for (name, f) in &s.elno {
                    if wanted.contains(&name.as_str()) {
                        let f = pick_cell_components(occ, f, name)?;
                        text.push_str(&format!(
                            "\n CHAMP PAR ELEMENT AUX NOEUDS DE NOM SYMBOLIQUE  {name}\n NUMERO D'ORDRE: {:>8} INST: {}\n\n",
                            s.nume_ordre,
                            fmt.format(s.inst)
                        ));
                        text.push_str(&cell_lines(&f, &sel.cells, Some(mesh), &fmt));
                    }
                }
            }
        } else if occ.has("CHAM_GD") {
            let (fname, field) = cham_no_of(study, occ, "CHAM_GD")?;
            let nodes: Vec<usize> = if SELECTION.iter().any(|k| occ.has(k)) && !occ.has("TOUT") {
                let groups = occ.texts("GROUP_NO");
                let mesh = mesh_for_field(study, occ, "CHAM_GD", fname, field, &groups)?;
                Selection::of(mesh, occ)?.nodes
            } else {
                (0..field.nnodes()).collect()
            };
            let (components, values) = pick_components(occ, field, fname)?;
            text.push_str(&format!("\n CHAMP AUX NOEUDS  {fname}\n\n"));
            text.push_str(&node_lines(
                &NodalField { components, values },
                &nodes,
                &fmt,
            ));
        } else if let Some(m) = occ.concept("MAILLAGE") {
            if let Some(k) = SELECTION.iter().find(|k| occ.has(k)) {
                return Err(occ.error(
                    k,
                    format!(
                        "{k} selects the values of a field: with MAILLAGE alone there is none \
                         (give RESULTAT or CHAM_GD)"
                    ),
                ));
            }
            let mesh = mesh_named(study, m)
                .ok_or_else(|| occ.error("MAILLAGE", format!("{m} holds no mesh")))?;
            text.push_str(&format!("\n MAILLAGE {m}\n{}", medio::mesh_info(mesh)));
        }
    }
    for n in notes {
        alarm(study, "IMPR_RESU", "", &n);
    }
    study.write_unit(unit, &text);
    Ok(())
}

/// The keywords that select parts of the mesh in a RESU occurrence.
const SELECTION: [&str; 5] = ["TOUT", "GROUP_NO", "NOEUD", "GROUP_MA", "MAILLE"];

/// What a RESU occurrence lists, as code_aster's IMPR_RESU (irdepl,
/// irchml): nodal fields at the nodes of GROUP_NO and NOEUD and at the
/// nodes of the cells of GROUP_MA and MAILLE; element fields on the cells
/// of GROUP_MA and MAILLE or, when only nodes are given, on the cells that
/// hold one of them. Nothing given, or TOUT='OUI': everything.
struct Selection {
    nodes: Vec<usize>,
    cells: Vec<usize>,
}

impl Selection {
    fn of(mesh: &Mesh, occ: &Args) -> Result<Selection, Diagnostic> {
        let by_nodes = occ.has("GROUP_NO") || occ.has("NOEUD");
        let by_cells = occ.has("GROUP_MA") || occ.has("MAILLE");
        if occ.has("TOUT") || !(by_nodes || by_cells) {
            return Ok(Selection {
                nodes: (0..mesh.nnodes()).collect(),
                cells: (0..mesh.ncells()).collect(),
            });
        }
        // GROUP_NO/NOEUD keep the order written (as before cells were
        // selectable), the nodes of the cells follow in increasing order.
        let mut nodes = nodes_of(mesh, occ)?;
        let cells = if by_cells {
            let cells = super::model_args::select_cells(mesh, occ)?;
            let mut seen = vec![false; mesh.nnodes()];
            for &n in &nodes {
                seen[n] = true;
            }
            let mut extra: Vec<usize> = cells
                .iter()
                .flat_map(|&c| mesh.cells[c].nodes.iter().copied())
                .filter(|&n| !seen[n])
                .collect();
            extra.sort_unstable();
            extra.dedup();
            nodes.extend(extra);
            cells
        } else {
            let mut mask = vec![false; mesh.nnodes()];
            for &n in &nodes {
                mask[n] = true;
            }
            (0..mesh.ncells())
                .filter(|&c| mesh.cells[c].nodes.iter().any(|&n| mask[n]))
                .collect()
        };
        Ok(Selection { nodes, cells })
    }
}

/// NOM_CMP on a field by element: the components asked, in that order.
fn pick_cell_components(occ: &Args, f: &GaussField, field: &str) -> Result<GaussField, Diagnostic> {
    if !occ.has("NOM_CMP") {
        return Ok(f.clone());
    }
    let idx: Vec<usize> = occ
        .texts("NOM_CMP")
        .iter()
        .map(|c| component_index(&f.components, c, occ, "NOM_CMP", field))
        .collect::<Result<_, _>>()?;
    let nc = f.ncmp();
    let mut out = GaussField {
        components: idx.iter().map(|&k| f.components[k].clone()).collect(),
        offsets: Vec::with_capacity(f.offsets.len()),
        values: Vec::new(),
    };
    for c in 0..f.offsets.len().saturating_sub(1) {
        out.offsets.push(out.values.len());
        for p in 0..f.npg(c) {
            let vals = &f.cell(c)[p * nc..(p + 1) * nc];
            out.values.extend(idx.iter().map(|&k| vals[k]));
        }
    }
    out.offsets.push(out.values.len());
    Ok(out)
}

/// Values in `fmt`, six per line, an absent value printed `-`.
fn value_lines(lead: &str, values: &[f64], fmt: &RealFormat) -> String {
    let w = fmt.format(0.0).len();
    let mut out = String::new();
    for (k, chunk) in values.chunks(6).enumerate() {
        out.push_str(if k == 0 { lead } else { "" });
        if k > 0 {
            out.push_str(&" ".repeat(lead.len()));
        }
        for v in chunk {
            if v.is_nan() {
                out.push_str(&format!("{:>w$}", "-"));
            } else {
                out.push_str(&fmt.format(*v));
            }
        }
        out.push('\n');
    }
    out
}

fn node_lines(f: &NodalField, nodes: &[usize], fmt: &RealFormat) -> String {
    let w = fmt.format(0.0).len();
    let mut out = format!(" {:<8}", "NOEUD");
    for c in &f.components {
        out.push_str(&format!("{c:>w$}"));
    }
    out.push('\n');
    for &n in nodes {
        let vals = &f.values[n * f.ncmp()..(n + 1) * f.ncmp()];
        out.push_str(&value_lines(&format!(" {:<8}", node_name(n)), vals, fmt));
    }
    out
}

/// One line per (cell, point) of `cells`: the point's number for a Gauss
/// field, the node's name for a field by element at nodes (`mesh` given).
fn cell_lines(f: &GaussField, cells: &[usize], mesh: Option<&Mesh>, fmt: &RealFormat) -> String {
    let w = fmt.format(0.0).len();
    let mut out = format!(
        " {:<8} {:>5}",
        "MAILLE",
        if mesh.is_some() { "NOEUD" } else { "POINT" }
    );
    for c in &f.components {
        out.push_str(&format!("{c:>w$}"));
    }
    out.push('\n');
    let nc = f.ncmp();
    let ncells = f.offsets.len().saturating_sub(1);
    for &c in cells.iter().filter(|&&c| c < ncells) {
        for p in 0..f.npg(c) {
            let vals = &f.cell(c)[p * nc..(p + 1) * nc];
            let point = match mesh.and_then(|m| m.cells.get(c)?.nodes.get(p)) {
                Some(&n) => node_name(n),
                None => (p + 1).to_string(),
            };
            out.push_str(&value_lines(
                &format!(" {:<8} {:>5}", cell_name(c), point),
                vals,
                fmt,
            ));
        }
    }
    out
}
