//! POST_RELEVE_T: extracts field values into a table.

use super::blocks::*;
use super::post_args::{
    cham_no_of, concept_title, is_gauss_name, mesh_for_field, mesh_of_result, node_name, nodes_of,
    result_of, select_steps, step_nodal, table_error,
};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::diag::Diagnostic;
use crate::mesh::Mesh;
use crate::post::table::{Cell, ColumnType, Table};
use crate::result::NodalField;
use crate::study::Study;

pub fn def() -> CommandDef {
    let mut extrac = vec![
        text("NOM_CHAM").required().into(NOM_CHAM_RESU).kw(),
        text("TOUT_ORDRE").into(&["OUI"]).kw(),
        int("NUME_ORDRE").many().kw(),
        concept("LIST_ORDRE", &[C::Listis])
            .doc("stored indices of a DEFI_LIST_ENTI list")
            .kw(),
        real("INST").many().kw(),
        concept("LIST_INST", &[C::Listr8]).kw(),
    ];
    extrac.extend(critere_precision(1e-6));
    let other = ["EXTREMA", "MOYENNE_ARITH"];
    let spec = command(
        "POST_RELEVE_T",
        Produces::Concept(C::Table),
        vec![
            fact(
                "ACTION",
                vec![
                    text("OPERATION")
                        .required()
                        .count(1, 2)
                        .into(&["EXTRACTION", "MOYENNE", "MOYENNE_ARITH", "EXTREMA"])
                        .doc("one, or the pair ('EXTRACTION', 'MOYENNE')")
                        .kw(),
                    text("INTITULE")
                        .required()
                        .doc("label of the rows, first column of the table")
                        .kw(),
                    concept("CHAM_GD", &[C::ChamNo]).kw(),
                    concept("RESULTAT", RESULTS)
                        .doc("all stored indices unless restricted")
                        .kw(),
                    block("b_extrac", present("RESULTAT"), extrac)
                        .rules(vec![exclus(&["TOUT_ORDRE", "NUME_ORDRE", "LIST_ORDRE", "INST", "LIST_INST"])])
                        .kw(),
                    tout(),
                    group_ma(),
                    maille(),
                    group_no(),
                    noeud(),
                    text("TOUT_CMP").into(&["OUI"]).doc("every component").kw(),
                    text("NOM_CMP").many().kw(),
                    text("INVARIANT").into(&["OUI"]).kw(),
                    text("ELEM_PRINCIPAUX").into(&["OUI"]).kw(),
                    text("RESULTANTE")
                        .many()
                        .into(&["DX", "DY", "DZ"])
                        .doc("sum of these components over the nodes: one row per field, a column per component")
                        .kw(),
                    text("MOMENT").many().into(&["DRX", "DRY", "DRZ"]).kw(),
                    real("POINT").many().kw(),
                    text("REPERE")
                        .into(&["GLOBAL", "LOCAL", "POLAIRE", "UTILISATEUR", "CYLINDRIQUE"])
                        .default(t("GLOBAL"))
                        .not_built(
                            &["LOCAL", "POLAIRE"],
                            "REPERE='GLOBAL', 'UTILISATEUR' (ANGL_NAUT) and 'CYLINDRIQUE' (ORIGINE, AXE_Z) are built",
                        )
                        .doc("UTILISATEUR and CYLINDRIQUE turn the DX, DY, DZ (and DRX, DRY, DRZ) of a displacement-type field (DEPL, VITE, ACCE, FORC_NODA, REAC_NODA), names kept; in the cylindrical frame DX is radial, DY axial, DZ tangential, code_aster's order")
                        .kw(),
                    real("ANGL_NAUT")
                        .count(3, 3)
                        .doc("REPERE='UTILISATEUR': nautical angles (alpha, beta, gamma) of the frame, in degrees")
                        .kw(),
                    real("ORIGINE")
                        .count(3, 3)
                        .doc("REPERE='CYLINDRIQUE': a point of the axis")
                        .kw(),
                    real("AXE_Z")
                        .count(3, 3)
                        .doc("REPERE='CYLINDRIQUE': direction of the axis")
                        .kw(),
                    text("TRAC_NOR").into(&["OUI"]).kw(),
                    text("TRAC_DIR").into(&["OUI"]).kw(),
                    real("DIRECTION").many().kw(),
                    real("VECT_Y").many().kw(),
                    oui_non("MOYE_NOEUD", "OUI")
                        .doc("a field by element at nodes (*_ELNO) in EXTRACTION: 'OUI' one row per node, the mean over the cells holding it; 'NON' one row per (node, cell), with the column MAILLE")
                        .kw(),
                    text("FORMAT_C")
                        .into(&["MODULE", "REEL", "IMAG"])
                        .default(t("MODULE"))
                        .kw(),
                    block("b_autre", not(is_in("OPERATION", &other)), vec![])
                        .rules(vec![
                            // code_aster's rule is AU_MOINS_UN('GROUP_NO',
                            // 'NOEUD'); cells and TOUT alone pass here to
                            // be refused when run with that rule and the
                            // way to the nodes of cells (DEFI_GROUP).
                            au_moins_un(&["TOUT", "GROUP_NO", "NOEUD", "GROUP_MA", "MAILLE"]),
                            un_parmi(&[
                                "TOUT_CMP",
                                "NOM_CMP",
                                "INVARIANT",
                                "ELEM_PRINCIPAUX",
                                "RESULTANTE",
                            ]),
                            present_present("TRAC_DIR", &["DIRECTION"]),
                            ensemble(&["MOMENT", "POINT"]),
                            present_present("MOMENT", &["RESULTANTE"]),
                            present_absent("TOUT_CMP", &["TRAC_DIR", "TRAC_NOR"]),
                            exclus(&["TRAC_DIR", "TRAC_NOR"]),
                            present_present("ORIGINE", &["AXE_Z"]),
                        ])
                        .kw(),
                    block("b_extrema", is_in("OPERATION", &other), vec![])
                        .rules(vec![exclus(&["TOUT_CMP", "NOM_CMP"])])
                        .kw(),
                ],
            )
            .required()
            .many()
            .rules(vec![un_parmi(&["RESULTAT", "CHAM_GD"])])
            .doc("one extraction per occurrence; one row per (stored index, node)")
            .kw(),
            info(),
            titre(),
        ],
    )
    .doc("Extracts values of fields into a table (columns INTITULE, RESU, NOM_CHAM, NUME_ORDRE, INST, NOEUD, MAILLE for a *_ELNO field with MOYE_NOEUD='NON', COOR_*, components), or their mean along a line of nodes (MOYENNE: six QUANTITE rows).");
    CommandDef { spec, exec }
}

/// The leading columns of an extraction table, in code_aster's order
/// (`rvtec0`): label, concept, field, access parameters, node, coordinates.
/// Component columns follow, in order of first appearance.
const LEADING: [(&str, ColumnType); 14] = [
    ("INTITULE", ColumnType::Text(16)),
    ("RESU", ColumnType::Text(8)),
    ("CHAM_GD", ColumnType::Text(8)),
    ("NOM_CHAM", ColumnType::Text(16)),
    ("NUME_ORDRE", ColumnType::Int),
    ("INST", ColumnType::Real),
    // EXTREMA (code_aster's `rvmima`): which extremum, then where.
    ("EXTREMA", ColumnType::Text(8)),
    ("NOEUD", ColumnType::Text(8)),
    // A field by element at nodes with MOYE_NOEUD='NON' (code_aster's
    // `rvtec0`): the cell of the row, right after its node (before it in
    // EXTREMA of such a field, where the table is built).
    ("MAILLE", ColumnType::Text(8)),
    ("CMP", ColumnType::Text(8)),
    ("VALE", ColumnType::Real),
    ("COOR_X", ColumnType::Real),
    ("COOR_Y", ColumnType::Real),
    ("COOR_Z", ColumnType::Real),
];

/// Keywords of ACTION whose operation is not built: refused rather than
/// ignored, since ignoring them would change the numbers.
const UNSUPPORTED: [&str; 9] = [
    "MOMENT",
    "INVARIANT",
    "ELEM_PRINCIPAUX",
    "TRAC_NOR",
    "TRAC_DIR",
    "TOUT",
    "GROUP_MA",
    "MAILLE",
    "POINT",
];

/// What is not built about an [`UNSUPPORTED`] keyword, and what gives
/// the same numbers when something does.
fn unsupported_why(k: &str) -> &'static str {
    match k {
        "TOUT" | "GROUP_MA" | "MAILLE" => {
            "GROUP_MA, MAILLE or TOUT next to GROUP_NO/NOEUD in EXTRACTION or MOYENNE of a nodal field is not built (code_aster reads them for fields by element only, *_ELNO, where aster restricts the cells to them): the nodes are those of GROUP_NO/NOEUD, give them alone"
        }
        "INVARIANT" => {
            "INVARIANT='OUI' (the invariants VMIS, TRESCA, TRACE, DETER of a tensor field) is not built; CALC_CHAMP CRITERES='SIEQ_NOEU' gives VMIS, TRESCA and TRSIG (the trace) at the nodes, to extract with NOM_CMP"
        }
        "ELEM_PRINCIPAUX" => {
            "ELEM_PRINCIPAUX='OUI' (principal values and directions of a tensor field) is not built; CALC_CHAMP CRITERES='SIEQ_NOEU' gives PRIN_1, PRIN_2, PRIN_3 and VECT_i_X..Z at the nodes, to extract with NOM_CMP"
        }
        "MOMENT" => "MOMENT (the moment of RESULTANTE about POINT) is not built",
        "POINT" => "POINT (the point of MOMENT) is not built",
        _ => {
            "the traction of a stress field on a normal (TRAC_NOR) or a direction (TRAC_DIR) is not built"
        }
    }
}

type Row = Vec<(String, Cell)>;

/// The column naming MOYENNE's six rows.
const QUANTITE: &str = "QUANTITE";

/// Builds one table from every ACTION occurrence, rows appended in order.
fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    let mut rows: Vec<Row> = Vec::new();
    let mut alarms: Vec<(&str, String)> = Vec::new();
    for occ in args.facts("ACTION") {
        let given = occ.text("INTITULE").unwrap_or_default();
        let kept = intitule(occ);
        if kept.len() < given.len() {
            study.log(format!(
                "  POST_RELEVE_T: INTITULE '{given}' is kept as '{kept}' (16 characters, as code_aster's INTITULE column)"
            ));
        }
        extract(study, occ, &mut rows, &mut alarms)?;
        for (id, text) in alarms.drain(..) {
            super::post_args::alarm(study, "POST_RELEVE_T", id, &text);
        }
    }
    let mut table = Table::new();
    table.title = if args.has("TITRE") {
        args.texts("TITRE").iter().map(|s| s.to_string()).collect()
    } else {
        concept_title(result.unwrap_or(""), "table_sdaster")
    };
    // EXTREMA of a field by element at nodes puts the cell before the node
    // (`rvmima`), an extraction with MOYE_NOEUD='NON' after it (`rvtec0`):
    // the first row holding both decides, as the first row written fixes
    // code_aster's columns.
    let mut leading = LEADING;
    let first_of = |r: &Row, a: &str, b: &str| {
        let pa = r.iter().position(|(n, _)| n == a)?;
        let pb = r.iter().position(|(n, _)| n == b)?;
        Some(pa < pb)
    };
    if rows.iter().find_map(|r| first_of(r, "MAILLE", "NOEUD")) == Some(true) {
        let node = leading.iter().position(|(n, _)| *n == "NOEUD").unwrap_or(0);
        let cell = leading
            .iter()
            .position(|(n, _)| *n == "MAILLE")
            .unwrap_or(0);
        leading.swap(node, cell);
    }
    for (name, ty) in leading {
        if rows.iter().any(|r| r.iter().any(|(n, _)| n == name)) {
            table
                .add_column(name, ty)
                .map_err(|e| table_error(args, "ACTION", e))?;
        }
    }
    for r in &rows {
        for (name, _) in r {
            if name != QUANTITE && table.column_index(name).is_none() {
                table
                    .add_column(name, ColumnType::Real)
                    .map_err(|e| table_error(args, "ACTION", e))?;
            }
        }
    }
    // MOYENNE's QUANTITE comes after the components, where code_aster's
    // `rvpara` puts it.
    if rows.iter().any(|r| r.iter().any(|(n, _)| n == QUANTITE)) {
        table
            .add_column(QUANTITE, ColumnType::Text(16))
            .map_err(|e| table_error(args, "ACTION", e))?;
    }
    for r in rows {
        let mut cells = vec![None; table.columns.len()];
        for (name, cell) in r {
            if let Some(i) = table.column_index(&name) {
                cells[i] = Some(cell);
            }
        }
        table
            .push_row(cells)
            .map_err(|e| table_error(args, "ACTION", e))?;
    }
    Ok(Some(ConceptData::Table(Box::new(table))))
}

/// The INTITULE of an occurrence as the table holds it: code_aster reads
/// it into 16 characters (its K16 column) and so cuts a longer title,
/// silently (its own zzzz237a titles a table 'Forces nodales ABCD').
fn intitule(occ: &Args) -> String {
    occ.text("INTITULE")
        .unwrap_or_default()
        .chars()
        .take(16)
        .collect()
}

/// What an ACTION occurrence computes from each nodal field.
#[derive(Clone, Copy, PartialEq)]
enum Operation {
    /// The values at the nodes (or their RESULTANTE).
    Extraction,
    /// MAX, MIN, MAXI_ABS, MINI_ABS over the nodes and components.
    Extrema,
    /// The arithmetic mean of each component over the nodes.
    MeanArith,
    /// MOYENNE: the mean, first moment and extrema along the line of the
    /// nodes (code_aster's `rvpstm`).
    Mean,
    /// OPERATION=('EXTRACTION', 'MOYENNE'): the node rows, then the six
    /// MOYENNE rows, field by field (code_aster's `rvpost`).
    ExtractionMean,
}

impl Operation {
    /// The operations of code_aster's catalogue block `b_autre`, whose
    /// rule AU_MOINS_UN('GROUP_NO', 'NOEUD') takes nodes only.
    fn on_nodes(self) -> bool {
        !matches!(self, Operation::Extrema | Operation::MeanArith)
    }
}

/// One ACTION occurrence: OPERATION='EXTRACTION', 'MOYENNE', 'EXTREMA'
/// or 'MOYENNE_ARITH' of nodal values, or the pair ('EXTRACTION',
/// 'MOYENNE'). Alarms for the .mess are pushed on `alarms` (id, text).
fn extract(
    study: &Study,
    occ: &Args,
    rows: &mut Vec<Row>,
    alarms: &mut Vec<(&'static str, String)>,
) -> Result<(), Diagnostic> {
    let ops = occ.texts("OPERATION");
    let op = match ops.as_slice() {
        ["EXTRACTION"] => Operation::Extraction,
        ["EXTREMA"] => Operation::Extrema,
        ["MOYENNE_ARITH"] => Operation::MeanArith,
        ["MOYENNE"] => Operation::Mean,
        ["EXTRACTION", "MOYENNE"] | ["MOYENNE", "EXTRACTION"] => Operation::ExtractionMean,
        _ => {
            return Err(occ.not_implemented(
                "OPERATION",
                &format!(
                "OPERATION={}; aster builds EXTRACTION, MOYENNE, EXTREMA and MOYENNE_ARITH, one at a time, and the pair ('EXTRACTION', 'MOYENNE')",
                ops.iter()
                    .map(|o| format!("'{o}'"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            ))
        }
    };
    let frame = frame_of(occ, op)?;
    // RESULTANTE sums over the nodes: code_aster refuses it with MOYENNE
    // (POSTRELE_67), and with the pair it would sum and drop the mean.
    if matches!(op, Operation::Mean | Operation::ExtractionMean) && occ.has("RESULTANTE") {
        return Err(occ.error(
            "RESULTANTE",
            "RESULTANTE goes with OPERATION='EXTRACTION' alone (code_aster's POSTRELE_67): give NOM_CMP or TOUT_CMP for the MOYENNE, and the sum in an occurrence of its own",
        ));
    }
    // code_aster's EXTRACTION and MOYENNE take their nodes from
    // GROUP_NO/NOEUD only: the rule of their catalogue block (b_autre)
    // is AU_MOINS_UN('GROUP_NO', 'NOEUD'), and a
    // GROUP_MA (or MAILLE, TOUT) alone is refused there. aster's
    // catalogue lets them through to say so here, with the way to the
    // nodes of cells (it advised extracting "a nodal field on the cells'
    // nodes" of fields that were nodal already, probe s7a M1).
    if op.on_nodes() && !occ.has("GROUP_NO") && !occ.has("NOEUD") {
        if let Some(k) = ["GROUP_MA", "MAILLE", "TOUT"]
            .into_iter()
            .find(|k| occ.has(k))
        {
            let cells = occ.texts(k).join("', '");
            let mut remedy = if k == "GROUP_MA" {
                format!(
                    "DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=_F(GROUP_MA='{cells}')) makes the node group of its cells' nodes, to give as GROUP_NO='{cells}'"
                )
            } else {
                "DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=_F(...)) makes a node group of the nodes wanted, to give as GROUP_NO".to_string()
            };
            if op != Operation::Extraction {
                remedy.push_str(
                    "; MOYENNE follows the nodes in the group's order (such a group is ordered by node number), or in the order NOEUD lists them",
                );
            }
            let named = ops
                .iter()
                .map(|o| format!("'{o}'"))
                .collect::<Vec<_>>()
                .join(", ");
            return Err(occ.error(
                k,
                format!(
                    "OPERATION={named} takes its nodes from GROUP_NO or NOEUD: code_aster's catalogue rule AU_MOINS_UN('GROUP_NO', 'NOEUD') refuses {k} alone; {remedy} (EXTREMA and MOYENNE_ARITH take GROUP_MA directly)"
                ),
            ));
        }
    }
    // A field by element at nodes takes GROUP_MA/MAILLE (and TOUT) next
    // to GROUP_NO/NOEUD: they restrict the cells whose values are read
    // (code_aster's `rvouex`).
    let elno = occ.has("RESULTAT") && occ.text("NOM_CHAM").is_some_and(|n| n.ends_with("_ELNO"));
    for k in UNSUPPORTED {
        // EXTREMA and MOYENNE_ARITH select nodes by cells too.
        let selection = matches!(k, "TOUT" | "GROUP_MA" | "MAILLE");
        if occ.has(k) && (!selection || (op.on_nodes() && !elno)) {
            return Err(occ.not_implemented(k, unsupported_why(k)));
        }
    }
    let intitule = intitule(occ);
    if occ.has("RESULTAT") {
        let (rname, res) = result_of(study, occ, "RESULTAT")?;
        let mesh = mesh_of_result(study, occ, "RESULTAT", rname, res)?;
        let nom_cham = occ.text("NOM_CHAM").unwrap_or_default();
        if is_gauss_name(nom_cham) {
            return Err(occ.not_implemented(
                "NOM_CHAM",
                "extraction of Gauss-point fields (project them to the nodes first)",
            ));
        }
        if elno {
            return elno_extraction(study, occ, op, &frame, rname, res, mesh, &intitule, rows);
        }
        let nodes = selected_nodes(mesh, occ, op)?;
        for step in select_steps(study, res, occ)? {
            let field = step_nodal(step, nom_cham, occ, "NOM_CHAM", rname)?;
            let lead = vec![
                ("INTITULE".to_string(), Cell::Text(intitule.clone())),
                ("RESU".to_string(), Cell::Text(rname.to_string())),
                ("NOM_CHAM".to_string(), Cell::Text(nom_cham.to_string())),
                ("NUME_ORDRE".to_string(), Cell::Int(step.nume_ordre as i64)),
                ("INST".to_string(), Cell::Real(step.inst)),
            ];
            let turned;
            let field = match &frame {
                Frame::Global => field,
                f => {
                    turned = in_frame(occ, f, mesh, field, nom_cham, &nodes, {
                        super::crea_champ::nodal_type_cham(nom_cham) == Some("NOEU_DEPL_R")
                    })?;
                    &turned
                }
            };
            field_rows(occ, op, mesh, field, nom_cham, &nodes, lead, rows, alarms)?;
        }
    } else {
        let (fname, field) = cham_no_of(study, occ, "CHAM_GD")?;
        let groups = occ.texts("GROUP_NO");
        let mesh = mesh_for_field(study, occ, "CHAM_GD", fname, field, &groups)?;
        let nodes = selected_nodes(mesh, occ, op)?;
        let lead = vec![
            ("INTITULE".to_string(), Cell::Text(intitule.clone())),
            ("CHAM_GD".to_string(), Cell::Text(fname.to_string())),
        ];
        // A cham_no does not record its quantity: it is DEPL_R when every
        // component is one of DEPL_R's.
        let turned;
        let field = match &frame {
            Frame::Global => field,
            f => {
                let depl = field
                    .components
                    .iter()
                    .all(|c| super::crea_champ::DEPL_R.contains(&c.as_str()));
                turned = in_frame(occ, f, mesh, field, fname, &nodes, depl)?;
                &turned
            }
        };
        field_rows(occ, op, mesh, field, fname, &nodes, lead, rows, alarms)?;
    }
    Ok(())
}

/// OPERATION='EXTRACTION' of a field by element at nodes (SIEF_ELNO,
/// SIGM_ELNO, SIEQ_ELNO, EPSI_ELNO, VARI_ELNO...), as code_aster's
/// `rvouex`, `rveche`/`rvechn`, `rvaffe` and `rvtec0`/`rvtecn` build it:
/// the cells read at a node of GROUP_NO/NOEUD are those of the mesh that
/// contain it and hold values of the field, in increasing cell number
/// (`cncinv`, `tremno`), restricted to GROUP_MA/MAILLE when given; a node
/// on no such cell is an error (code_aster's POSTRELE_40).
/// MOYE_NOEUD='OUI' (the default) gives one row per node, each component
/// the arithmetic mean of the values those cells give there (`rvaffe`,
/// absent values left out), in the columns of a nodal extraction;
/// MOYE_NOEUD='NON' one row per (node, cell), node by node, with the
/// column MAILLE after NOEUD (`rvtec0`).
#[allow(clippy::too_many_arguments)]
fn elno_extraction(
    study: &Study,
    occ: &Args,
    op: Operation,
    frame: &Frame,
    rname: &str,
    res: &crate::result::EvolNoli,
    mesh: &Mesh,
    intitule: &str,
    rows: &mut Vec<Row>,
) -> Result<(), Diagnostic> {
    let nom_cham = occ.text("NOM_CHAM").unwrap_or_default();
    let noeu = format!("{}_NOEU", nom_cham.trim_end_matches("_ELNO"));
    if op == Operation::Extrema {
        return elno_extrema(study, occ, rname, res, mesh, intitule, rows);
    }
    if op != Operation::Extraction {
        let what = match op {
            Operation::MeanArith => format!(
                "MOYENNE_ARITH of the field by element at nodes {nom_cham} is not built; MOYENNE_ARITH of the nodal field {noeu} (CALC_CHAMP) averages its means at the nodes"
            ),
            _ => format!(
                "MOYENNE along a path of the field by element at nodes {nom_cham} is not built; MOYENNE of the nodal field {noeu} (CALC_CHAMP) gives it from the means at the nodes"
            ),
        };
        return Err(occ.not_implemented("OPERATION", &what));
    }
    if occ.has("RESULTANTE") {
        return Err(occ.not_implemented(
            "RESULTANTE",
            &format!("RESULTANTE of the field by element at nodes {nom_cham} is not built; it sums the components of a nodal field (REAC_NODA, FORC_NODA, or {noeu})"),
        ));
    }
    if !matches!(frame, Frame::Global) {
        return Err(occ.not_implemented(
            "REPERE",
            &format!("REPERE other than 'GLOBAL' on the field by element at nodes {nom_cham} is not built (the frames turn DX, DY, DZ of a displacement-type nodal field only)"),
        ));
    }
    let nodes = ordered_nodes(mesh, occ)?;
    let keep: Option<Vec<bool>> = if occ.has("GROUP_MA") || occ.has("MAILLE") {
        let mut keep = vec![false; mesh.ncells()];
        for c in super::model_args::select_cells(mesh, occ)? {
            keep[c] = true;
        }
        Some(keep)
    } else {
        None
    };
    // The cells at each selected node, increasing, with the node's place
    // in the cell.
    let mut place = vec![usize::MAX; mesh.nnodes()];
    for (k, &n) in nodes.iter().enumerate() {
        place[n] = k;
    }
    let mut cells_at: Vec<Vec<(usize, usize)>> = vec![Vec::new(); nodes.len()];
    for (c, cell) in mesh.cells.iter().enumerate() {
        if keep.as_ref().is_some_and(|k| !k[c]) {
            continue;
        }
        for (a, &n) in cell.nodes.iter().enumerate() {
            if place[n] != usize::MAX {
                cells_at[place[n]].push((c, a));
            }
        }
    }
    let per_cell = occ.text("MOYE_NOEUD") == Some("NON");
    let coords = ["COOR_X", "COOR_Y", "COOR_Z"];
    let ndim = if mesh.dim == 3 { 3 } else { 2 };
    for step in select_steps(study, res, occ)? {
        let field = super::post_args::step_elno(step, nom_cham, occ, "NOM_CHAM", rname)?;
        let cmps = components_of(occ, &field.components, nom_cham)?;
        let ncmp = field.ncmp();
        let lead = vec![
            ("INTITULE".to_string(), Cell::Text(intitule.to_string())),
            ("RESU".to_string(), Cell::Text(rname.to_string())),
            ("NOM_CHAM".to_string(), Cell::Text(nom_cham.to_string())),
            ("NUME_ORDRE".to_string(), Cell::Int(step.nume_ordre as i64)),
            ("INST".to_string(), Cell::Real(step.inst)),
        ];
        for (k, &n) in nodes.iter().enumerate() {
            let active: Vec<(usize, usize)> = cells_at[k]
                .iter()
                .copied()
                .filter(|&(c, _)| field.npg(c) == mesh.cells[c].nodes.len())
                .collect();
            if active.is_empty() {
                // The keyword that brought the node (NOEUD comes first,
                // `ordered_nodes`): a GROUP_NO member is not NOEUD's fault.
                let by_name = occ.texts("NOEUD").iter().any(|t| *t == node_name(n));
                let key = if by_name { "NOEUD" } else { "GROUP_NO" };
                return Err(occ.error(
                    key,
                    format!(
                        "node {} is on no cell{} where {nom_cham} has values at NUME_ORDRE {} (code_aster's POSTRELE_40): leave it out of GROUP_NO/NOEUD{}",
                        node_name(n),
                        if keep.is_some() { " of GROUP_MA/MAILLE" } else { "" },
                        step.nume_ordre,
                        if keep.is_some() { ", or give GROUP_MA/MAILLE cells that contain it" } else { "" }
                    ),
                ));
            }
            let head = |row: &mut Row| {
                for (d, name) in coords.iter().take(ndim).enumerate() {
                    row.push((name.to_string(), Cell::Real(mesh.coords[n][d])));
                }
            };
            if per_cell {
                for &(c, a) in &active {
                    let mut row = lead.clone();
                    row.push(("NOEUD".to_string(), Cell::Text(node_name(n))));
                    row.push((
                        "MAILLE".to_string(),
                        Cell::Text(super::post_args::cell_name(c)),
                    ));
                    head(&mut row);
                    let vals = field.cell(c);
                    for (name, i) in &cmps {
                        let v = vals[a * ncmp + i];
                        if !v.is_nan() {
                            row.push((name.clone(), Cell::Real(v)));
                        }
                    }
                    rows.push(row);
                }
            } else {
                let mut row = lead.clone();
                row.push(("NOEUD".to_string(), Cell::Text(node_name(n))));
                head(&mut row);
                for (name, i) in &cmps {
                    let values: Vec<f64> = active
                        .iter()
                        .map(|&(c, a)| field.cell(c)[a * ncmp + i])
                        .filter(|v| !v.is_nan())
                        .collect();
                    if !values.is_empty() {
                        row.push((
                            name.clone(),
                            Cell::Real(values.iter().sum::<f64>() / values.len() as f64),
                        ));
                    }
                }
                rows.push(row);
            }
        }
    }
    Ok(())
}

/// The four extrema of OPERATION='EXTREMA' (code_aster's `prexno` on
/// nodes, `prexel` on cells): MAX, MIN, MAXI_ABS, MINI_ABS of the values
/// offered in order, with where each was met. The comparisons are strict,
/// so the first value met keeps a tie.
struct Extrema<W> {
    best: [Option<(f64, W)>; 4],
}

impl<W: Copy> Extrema<W> {
    const NAMES: [&'static str; 4] = ["MAX", "MIN", "MAXI_ABS", "MINI_ABS"];
    /// Per extremum: the absolute value is compared, a larger one wins.
    const RULES: [(bool, bool); 4] = [(false, true), (false, false), (true, true), (true, false)];

    fn new() -> Self {
        Extrema { best: [None; 4] }
    }

    /// Offers `v` met at `at`; a NaN (an absent value) is not a candidate.
    fn offer(&mut self, v: f64, at: W) {
        if v.is_nan() {
            return;
        }
        for (slot, &(abs, larger)) in self.best.iter_mut().zip(&Self::RULES) {
            let x = if abs { v.abs() } else { v };
            let better = match slot {
                None => true,
                Some((b, _)) => (larger && x > *b) || (!larger && x < *b),
            };
            if better {
                *slot = Some((x, at));
            }
        }
    }

    /// The four (name, value, where), or None when no value was offered.
    fn found(self) -> Option<Vec<(&'static str, f64, W)>> {
        Self::NAMES
            .iter()
            .zip(self.best)
            .map(|(name, b)| b.map(|(v, at)| (*name, v, at)))
            .collect()
    }
}

/// OPERATION='EXTREMA' of a field by element at nodes, as code_aster's
/// `rvmima`/`prexel`: per step, the largest and smallest value and the
/// largest and smallest absolute value over the components (NOM_CMP's, in
/// their order, else the field's), the cells (GROUP_MA/MAILLE, else every
/// cell with values) and each cell's nodes, the first met winning a tie;
/// four rows MAX, MIN, MAXI_ABS, MINI_ABS with the cell, the node and the
/// component. It reads cells, not nodes: GROUP_NO/NOEUD is an error
/// (POSTRELE_66), and so is a selection with no value (POSTRELE_19).
fn elno_extrema(
    study: &Study,
    occ: &Args,
    rname: &str,
    res: &crate::result::EvolNoli,
    mesh: &Mesh,
    intitule: &str,
    rows: &mut Vec<Row>,
) -> Result<(), Diagnostic> {
    let nom_cham = occ.text("NOM_CHAM").unwrap_or_default();
    if let Some(k) = ["GROUP_NO", "NOEUD"].into_iter().find(|k| occ.has(k)) {
        return Err(occ.error(
            k,
            format!("EXTREMA of the field by element at nodes {nom_cham} reads cells: give GROUP_MA, MAILLE or TOUT, not {k} (code_aster's POSTRELE_66)"),
        ));
    }
    let cells: Vec<usize> = if occ.has("GROUP_MA") || occ.has("MAILLE") {
        super::model_args::select_cells(mesh, occ)?
    } else {
        (0..mesh.ncells()).collect()
    };

    for step in select_steps(study, res, occ)? {
        let field = super::post_args::step_elno(step, nom_cham, occ, "NOM_CHAM", rname)?;
        let cmps = components_of(occ, &field.components, nom_cham)?;
        let ncmp = field.ncmp();
        let mut extrema = Extrema::new();
        for (k, (_, i)) in cmps.iter().enumerate() {
            for &c in &cells {
                let nodes = &mesh.cells[c].nodes;
                if field.npg(c) != nodes.len() {
                    continue;
                }
                let vals = field.cell(c);
                for (a, &n) in nodes.iter().enumerate() {
                    extrema.offer(vals[a * ncmp + i], (c, n, k));
                }
            }
        }
        let Some(found) = extrema.found() else {
            return Err(occ.error(
                "NOM_CHAM",
                format!(
                    "EXTREMA of {nom_cham} at NUME_ORDRE {}: no value on the {} selected cell(s) (code_aster's POSTRELE_19)",
                    step.nume_ordre,
                    cells.len()
                ),
            ));
        };
        for (name, value, (cell, node, cmp)) in found {
            rows.push(vec![
                ("INTITULE".to_string(), Cell::Text(intitule.to_string())),
                ("RESU".to_string(), Cell::Text(rname.to_string())),
                ("NOM_CHAM".to_string(), Cell::Text(nom_cham.to_string())),
                ("NUME_ORDRE".to_string(), Cell::Int(step.nume_ordre as i64)),
                ("INST".to_string(), Cell::Real(step.inst)),
                ("EXTREMA".to_string(), Cell::Text(name.to_string())),
                (
                    "MAILLE".to_string(),
                    Cell::Text(super::post_args::cell_name(cell)),
                ),
                ("NOEUD".to_string(), Cell::Text(node_name(node))),
                ("CMP".to_string(), Cell::Text(cmps[cmp].0.clone())),
                ("VALE".to_string(), Cell::Real(value)),
            ]);
        }
    }
    Ok(())
}

/// The frame of the components (REPERE).
enum Frame {
    Global,
    /// UTILISATEUR: the rows of the matrix are the axes of the frame in
    /// the global one (code_aster's `matrot` of ANGL_NAUT).
    User([[f64; 3]; 3]),
    /// CYLINDRIQUE: a point of the axis and its unit direction.
    Cylinder {
        origin: [f64; 3],
        axis: [f64; 3],
    },
}

/// code_aster's `matrot`: the matrix from the global frame to the frame
/// of the nautical angles (alpha, beta, gamma), in radians: the global
/// frame turned by alpha about z, then by beta about the new y, then by
/// gamma about the newest x, i.e. (Rz(alpha) Ry(beta) Rx(gamma))^T. Its
/// rows are the local axes in global components, the first x' = (cos b
/// cos a, cos b sin a, -sin b), DEFI_GROUP's normal of ANGL_NAUT.
pub(crate) fn nautical_matrix(a: f64, b: f64, g: f64) -> [[f64; 3]; 3] {
    let (sa, ca) = a.sin_cos();
    let (sb, cb) = b.sin_cos();
    let (sg, cg) = g.sin_cos();
    [
        [cb * ca, cb * sa, -sb],
        [sg * sb * ca - cg * sa, cg * ca + sg * sb * sa, sg * cb],
        [sg * sa + cg * sb * ca, cg * sb * sa - ca * sg, cg * cb],
    ]
}

/// The frame of an occurrence. code_aster's catalogue puts REPERE,
/// ANGL_NAUT, ORIGINE and AXE_Z in the block of EXTRACTION and MOYENNE
/// (`b_autre`), and its `extchn` reads ANGL_NAUT with UTILISATEUR and
/// ORIGINE, AXE_Z with CYLINDRIQUE; the other combinations, which
/// code_aster would ignore or read as garbage, are refused here at their
/// keyword.
fn frame_of(occ: &Args, op: Operation) -> Result<Frame, Diagnostic> {
    let repere = occ.text("REPERE").unwrap_or("GLOBAL");
    let wants: &[&str] = match repere {
        "UTILISATEUR" => &["ANGL_NAUT"],
        "CYLINDRIQUE" => &["ORIGINE", "AXE_Z"],
        "GLOBAL" => &[],
        // LOCAL and POLAIRE are refused by the catalogue (`not_built`);
        // this guards a program built another way.
        other => {
            return Err(occ.not_implemented(
                "REPERE",
                &format!("REPERE='{other}'; GLOBAL, UTILISATEUR and CYLINDRIQUE are built"),
            ))
        }
    };
    if !op.on_nodes()
        && (repere != "GLOBAL" || occ.has("ANGL_NAUT") || occ.has("ORIGINE") || occ.has("AXE_Z"))
    {
        let k = ["ANGL_NAUT", "ORIGINE", "AXE_Z"]
            .into_iter()
            .find(|k| occ.has(k))
            .unwrap_or("REPERE");
        return Err(occ.error(
            k,
            "EXTREMA and MOYENNE_ARITH read the components in the global frame: code_aster's catalogue gives REPERE, ANGL_NAUT, ORIGINE and AXE_Z to EXTRACTION and MOYENNE only; extract the nodes with OPERATION='EXTRACTION' and REPERE to read them in another frame",
        ));
    }
    for k in ["ANGL_NAUT", "ORIGINE", "AXE_Z"] {
        if occ.has(k) && !wants.contains(&k) {
            let with = if k == "ANGL_NAUT" {
                "REPERE='UTILISATEUR'"
            } else {
                "REPERE='CYLINDRIQUE'"
            };
            return Err(occ.error(
                k,
                format!("{k} goes with {with}, and REPERE is '{repere}': give {with} to read the components in that frame, or remove {k}"),
            ));
        }
    }
    if let Some(k) = wants.iter().find(|k| !occ.has(k)) {
        return Err(occ.error(
            "REPERE",
            format!(
                "REPERE='{repere}' needs {}: {k} is missing",
                wants.join(" and ")
            ),
        ));
    }
    let three = |k: &str| {
        let v = occ.reals(k);
        [v[0], v[1], v[2]]
    };
    Ok(match repere {
        "UTILISATEUR" => {
            let d = three("ANGL_NAUT").map(f64::to_radians);
            Frame::User(nautical_matrix(d[0], d[1], d[2]))
        }
        "CYLINDRIQUE" => {
            let z = three("AXE_Z");
            let n2 = z.iter().map(|c| c * c).sum::<f64>();
            // code_aster's extchn: PREPOST_38 below 1e-6 (of the square).
            if n2 < 1e-6 {
                return Err(occ.error(
                    "AXE_Z",
                    format!(
                        "AXE_Z = ({}, {}, {}) is (nearly) zero: it gives the direction of the axis of REPERE='CYLINDRIQUE' (code_aster's PREPOST_38)",
                        z[0], z[1], z[2]
                    ),
                ));
            }
            let n = n2.sqrt();
            Frame::Cylinder {
                origin: three("ORIGINE"),
                axis: z.map(|c| c / n),
            }
        }
        _ => Frame::Global,
    })
}

/// The field with the vectors (DX, DY, DZ) and (DRX, DRY, DRZ) of the
/// selected nodes in the frame, as code_aster's `extchn` does before any
/// operation (`rvchn1` for UTILISATEUR, `rvchn2` for CYLINDRIQUE): the
/// components keep their names, each local value v' = P v, an absent
/// component counting as 0 and staying absent. In the cylindrical frame
/// the rows of P are, in this order, e_r (the node's direction from the
/// axis), e_z (the axis) and e_theta = e_z x e_r: so DX holds the radial
/// component, DY the axial one and DZ the tangential one (`rvchn2`'s
/// order, not r, theta, z). A node on the axis has no e_r (code_aster's
/// POSTRELE_30). code_aster turns DEPL_R fields only (POSTRELE_17
/// otherwise: a stress tensor is not turned), so does aster.
fn in_frame(
    occ: &Args,
    frame: &Frame,
    mesh: &Mesh,
    field: &NodalField,
    field_name: &str,
    nodes: &[usize],
    depl_r: bool,
) -> Result<NodalField, Diagnostic> {
    let repere = occ.text("REPERE").unwrap_or("GLOBAL");
    if !depl_r {
        return Err(occ.error(
            "REPERE",
            format!(
                "REPERE='{repere}' turns displacement-type fields only (code_aster's DEPL_R: DEPL, VITE, ACCE, FORC_NODA, REAC_NODA, whose DX, DY, DZ and DRX, DRY, DRZ it turns); {field_name} is not one, and code_aster stops on it (POSTRELE_17): extract it with REPERE='GLOBAL'"
            ),
        ));
    }
    let mut out = field.clone();
    let triples = [["DX", "DY", "DZ"], ["DRX", "DRY", "DRZ"]];
    for &n in nodes {
        let p = match frame {
            Frame::Global => return Ok(out),
            Frame::User(p) => *p,
            Frame::Cylinder { origin, axis } => {
                let x = mesh.coords[n];
                let mut r = [x[0] - origin[0], x[1] - origin[1], x[2] - origin[2]];
                let along: f64 = (0..3).map(|i| r[i] * axis[i]).sum();
                for i in 0..3 {
                    r[i] -= along * axis[i];
                }
                let n2: f64 = r.iter().map(|c| c * c).sum();
                // code_aster's rvchn2: POSTRELE_30 below 1e-6 (of the square).
                if n2 < 1e-6 {
                    return Err(occ.error(
                        "ORIGINE",
                        format!(
                            "node {} is on the axis of REPERE='CYLINDRIQUE' (ORIGINE, AXE_Z): it has no radial direction (code_aster's POSTRELE_30); leave it out of GROUP_NO/NOEUD",
                            node_name(n)
                        ),
                    ));
                }
                let r = r.map(|c| c / n2.sqrt());
                let z = *axis;
                let t = [
                    z[1] * r[2] - z[2] * r[1],
                    z[2] * r[0] - z[0] * r[2],
                    z[0] * r[1] - z[1] * r[0],
                ];
                [r, z, t]
            }
        };
        for names in &triples {
            let idx: Vec<Option<usize>> = names.iter().map(|c| field.component_index(c)).collect();
            let at = |c: Option<usize>| {
                c.map(|c| field.values[n * field.ncmp() + c])
                    .filter(|v| !v.is_nan())
            };
            if idx.iter().all(|&c| at(c).is_none()) {
                continue;
            }
            let v: Vec<f64> = idx.iter().map(|&c| at(c).unwrap_or(0.0)).collect();
            for (i, &c) in idx.iter().enumerate() {
                if let Some(c) = c {
                    if at(Some(c)).is_some() {
                        out.set(n, c, (0..3).map(|j| p[i][j] * v[j]).sum());
                    }
                }
            }
        }
    }
    Ok(out)
}

/// The rows of one field for the occurrence's operation.
#[allow(clippy::too_many_arguments)]
fn field_rows(
    occ: &Args,
    op: Operation,
    mesh: &Mesh,
    field: &NodalField,
    field_name: &str,
    nodes: &[usize],
    lead: Row,
    rows: &mut Vec<Row>,
    alarms: &mut Vec<(&'static str, String)>,
) -> Result<(), Diagnostic> {
    match op {
        Operation::Extraction if occ.has("RESULTANTE") => {
            resultant_row(occ, field, field_name, nodes, lead, rows)
        }
        Operation::Extraction => node_rows(occ, mesh, field, field_name, nodes, &lead, rows),
        Operation::Extrema => extrema_rows(occ, field, field_name, nodes, lead, rows),
        Operation::MeanArith => mean_rows(occ, field, field_name, nodes, lead, rows),
        Operation::Mean => path_rows(occ, mesh, field, field_name, nodes, lead, rows, alarms),
        Operation::ExtractionMean => {
            node_rows(occ, mesh, field, field_name, nodes, &lead, rows)?;
            path_rows(occ, mesh, field, field_name, nodes, lead, rows, alarms)
        }
    }
}

/// The nodes of the occurrence. EXTRACTION needs GROUP_NO/NOEUD (the
/// catalogue's rule), MOYENNE too, both in code_aster's order (see
/// [`ordered_nodes`]); EXTREMA and MOYENNE_ARITH also take the nodes of
/// GROUP_MA/MAILLE cells and default to every node of the mesh, as
/// code_aster's `prexno`/`prmono` do.
fn selected_nodes(mesh: &Mesh, occ: &Args, op: Operation) -> Result<Vec<usize>, Diagnostic> {
    let mut nodes = nodes_of(mesh, occ)?;
    match op {
        Operation::Extraction | Operation::Mean | Operation::ExtractionMean => {
            return ordered_nodes(mesh, occ)
        }
        Operation::Extrema | Operation::MeanArith => {}
    }
    let cells = if occ.has("GROUP_MA") || occ.has("MAILLE") {
        super::model_args::select_cells(mesh, occ)?
    } else {
        Vec::new()
    };
    let mut seen = vec![false; mesh.nnodes()];
    for &n in &nodes {
        seen[n] = true;
    }
    for c in cells {
        for &n in &mesh.cells[c].nodes {
            if !std::mem::replace(&mut seen[n], true) {
                nodes.push(n);
            }
        }
    }
    let by_selection = ["GROUP_NO", "NOEUD", "GROUP_MA", "MAILLE"]
        .iter()
        .any(|k| occ.has(k));
    if !by_selection {
        nodes = (0..mesh.nnodes()).collect();
    }
    Ok(nodes)
}

/// The components an EXTREMA or MOYENNE_ARITH occurrence reads: NOM_CMP,
/// or every component of the field.
fn components_of(
    occ: &Args,
    components: &[String],
    field_name: &str,
) -> Result<Vec<(String, usize)>, Diagnostic> {
    if !occ.has("NOM_CMP") {
        return Ok(components
            .iter()
            .enumerate()
            .map(|(i, c)| (c.clone(), i))
            .collect());
    }
    occ.texts("NOM_CMP")
        .into_iter()
        .map(|c| {
            super::post_args::component_index(components, c, occ, "NOM_CMP", field_name)
                .map(|i| (c.to_string(), i))
        })
        .collect()
}

/// EXTREMA (code_aster's `rvmima`/`prexno`): over the components (outer
/// loop) and the nodes (inner loop), the largest and smallest value and
/// the largest and smallest absolute value, the first one met winning a
/// tie; four rows MAX, MIN, MAXI_ABS, MINI_ABS with the node, the
/// component and the value (|value| for the *_ABS rows). Nodes where the
/// component is absent are skipped; a selection where it is absent
/// everywhere is an error rather than a row of sentinels.
fn extrema_rows(
    occ: &Args,
    field: &NodalField,
    field_name: &str,
    nodes: &[usize],
    lead: Row,
    rows: &mut Vec<Row>,
) -> Result<(), Diagnostic> {
    let cmps = components_of(occ, &field.components, field_name)?;
    let mut extrema = Extrema::new();
    for (k, (_, i)) in cmps.iter().enumerate() {
        for &n in nodes {
            extrema.offer(field.values[n * field.ncmp() + i], (n, k));
        }
    }
    let Some(found) = extrema.found() else {
        return Err(occ.error(
            "NOM_CMP",
            format!(
                "EXTREMA of {field_name}: no value of {} at the {} selected node(s)",
                cmps.iter()
                    .map(|(c, _)| c.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
                nodes.len()
            ),
        ));
    };
    for (name, value, (node, cmp)) in found {
        let mut row = lead.clone();
        row.push(("EXTREMA".to_string(), Cell::Text(name.to_string())));
        row.push(("NOEUD".to_string(), Cell::Text(node_name(node))));
        row.push(("CMP".to_string(), Cell::Text(cmps[cmp].0.clone())));
        row.push(("VALE".to_string(), Cell::Real(value)));
        rows.push(row);
    }
    Ok(())
}

/// MOYENNE_ARITH (code_aster's `rvmoye`/`prmono`): one row per component,
/// the arithmetic mean of its values at the selected nodes where it is
/// defined, in columns CMP and MOYENNE.
fn mean_rows(
    occ: &Args,
    field: &NodalField,
    field_name: &str,
    nodes: &[usize],
    lead: Row,
    rows: &mut Vec<Row>,
) -> Result<(), Diagnostic> {
    for (c, i) in components_of(occ, &field.components, field_name)? {
        let values: Vec<f64> = nodes
            .iter()
            .map(|&n| field.values[n * field.ncmp() + i])
            .filter(|v| !v.is_nan())
            .collect();
        if values.is_empty() {
            return Err(occ.error(
                "NOM_CMP",
                format!(
                    "MOYENNE_ARITH of {field_name}: no value of {c} at the {} selected node(s)",
                    nodes.len()
                ),
            ));
        }
        let mut row = lead.clone();
        row.push(("CMP".to_string(), Cell::Text(c)));
        row.push((
            "MOYENNE".to_string(),
            Cell::Real(values.iter().sum::<f64>() / values.len() as f64),
        ));
        rows.push(row);
    }
    Ok(())
}

/// RESULTANTE: one row per field, each component asked summed over the
/// selected nodes (the total force of REAC_NODA or FORC_NODA on a
/// support, for instance), in a column named after the component, as
/// code_aster's table has it; nodes where the component is absent add
/// nothing.
fn resultant_row(
    occ: &Args,
    field: &NodalField,
    field_name: &str,
    nodes: &[usize],
    lead: Row,
    rows: &mut Vec<Row>,
) -> Result<(), Diagnostic> {
    let mut row = lead;
    for c in occ.texts("RESULTANTE") {
        let i =
            super::post_args::component_index(&field.components, c, occ, "RESULTANTE", field_name)?;
        let sum: f64 = nodes
            .iter()
            .map(|&n| field.values[n * field.ncmp() + i])
            .filter(|v| !v.is_nan())
            .sum();
        row.push((c.to_string(), Cell::Real(sum)));
    }
    rows.push(row);
    Ok(())
}

/// The rows of one field at the selected nodes: coordinates (COOR_Z only
/// for a 3D mesh) and the components asked. A component of the field that
/// is absent at a node leaves its cell empty, as code_aster does.
fn node_rows(
    occ: &Args,
    mesh: &Mesh,
    field: &NodalField,
    field_name: &str,
    nodes: &[usize],
    lead: &Row,
    rows: &mut Vec<Row>,
) -> Result<(), Diagnostic> {
    let cmps = components_of(occ, &field.components, field_name)?;
    let coords = ["COOR_X", "COOR_Y", "COOR_Z"];
    let ndim = if mesh.dim == 3 { 3 } else { 2 };
    for &n in nodes {
        let mut row = lead.clone();
        row.push(("NOEUD".to_string(), Cell::Text(node_name(n))));
        for (k, name) in coords.iter().take(ndim).enumerate() {
            row.push((name.to_string(), Cell::Real(mesh.coords[n][k])));
        }
        for (c, i) in &cmps {
            let v = field.values[n * field.ncmp() + i];
            if !v.is_nan() {
                row.push((c.clone(), Cell::Real(v)));
            }
        }
        rows.push(row);
    }
    Ok(())
}

/// The nodes of GROUP_NO / NOEUD in code_aster's order (`rvgnoe`): the
/// nodes of NOEUD as listed, then those of each GROUP_NO in turn, in the
/// group's own order; a node met again is kept at its first place. It is
/// the row order of an EXTRACTION (probe elnop: GROUP_NO's nodes came
/// first) and the path of a MOYENNE, which integrates along the polyline
/// through them.
fn ordered_nodes(mesh: &Mesh, occ: &Args) -> Result<Vec<usize>, Diagnostic> {
    // The unknown group or node names are reported as everywhere else.
    nodes_of(mesh, occ)?;
    let mut out = Vec::new();
    let mut seen = vec![false; mesh.nnodes()];
    let names = occ.texts("NOEUD");
    let named = names
        .iter()
        .map(|name| super::post_args::node_by_name(mesh, occ, "NOEUD", name))
        .collect::<Result<Vec<_>, _>>()?;
    let grouped = occ
        .texts("GROUP_NO")
        .into_iter()
        .flat_map(|g| mesh.node_groups.get(g).into_iter().flatten().copied());
    for n in named.into_iter().chain(grouped) {
        if !std::mem::replace(&mut seen[n], true) {
            out.push(n);
        }
    }
    Ok(out)
}

/// The components of a MOYENNE: NOM_CMP, or every component of the field
/// (TOUT_CMP), at most six as code_aster's `rvpstm` allows (POSTRELE_7).
fn path_components(
    occ: &Args,
    field: &NodalField,
    field_name: &str,
) -> Result<Vec<(String, usize)>, Diagnostic> {
    let cmps = components_of(occ, &field.components, field_name)?;
    if cmps.len() > 6 {
        let key = if occ.has("NOM_CMP") {
            "NOM_CMP"
        } else {
            "TOUT_CMP"
        };
        return Err(occ.error(
            key,
            format!(
                "MOYENNE of {field_name} on {} components ({}): code_aster's MOYENNE takes at most 6 (POSTRELE_7); name at most 6 in NOM_CMP, in more occurrences if needed",
                cmps.len(),
                cmps.iter()
                    .map(|(c, _)| c.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ));
    }
    Ok(cmps)
}

/// The six quantities of a MOYENNE of one component along a path, as
/// code_aster's `rvpstm` computes them from the nodal values f_i at the
/// curvilinear abscissae s_i (sums of the chords from the first node), f
/// linear on each segment. Segments with an end where the component is
/// absent are left out of the sums (their length too).
#[derive(Debug, Clone, Copy, PartialEq)]
struct PathMean {
    /// MOMENT_0 = (1/L) ∫ f ds, the mean along the path.
    moment_0: f64,
    /// MOMENT_1 = (12/L²) ∫ f (s − L/2) ds: the difference between the
    /// ends of the linear part of f (its "bending" part).
    moment_1: f64,
    /// MINIMUM and MAXIMUM of the nodal values on the kept segments.
    minimum: f64,
    maximum: f64,
    /// The length L of the kept segments.
    length: f64,
}

impl PathMean {
    fn of(s: &[f64], f: &[f64]) -> PathMean {
        let (mut m1, mut m2, mut xl) = (0.0, 0.0, 0.0);
        let (mut mi, mut ma) = (f64::INFINITY, f64::NEG_INFINITY);
        for k in 0..s.len().saturating_sub(1) {
            let (t1, t2) = (f[k], f[k + 1]);
            if t1.is_nan() || t2.is_nan() {
                continue;
            }
            let (s1, s2) = (s[k], s[k + 1]);
            let h = s2 - s1;
            xl += h;
            m1 += h * (t1 + t2);
            // Simpson's rule, exact for the quadratic f·s of a segment.
            m2 += h / 3.0 * (t1 * s1 + (t1 + t2) * (s1 + s2) + t2 * s2);
            mi = mi.min(t1).min(t2);
            ma = ma.max(t1).max(t2);
        }
        let moment_0 = 0.5 * m1 / xl;
        PathMean {
            moment_0,
            moment_1: 6.0 * (m2 / (xl * xl) - moment_0),
            minimum: mi,
            maximum: ma,
            length: xl,
        }
    }

    /// The six rows' values in code_aster's order (`rvtamo`): MOMENT_0,
    /// MOMENT_1, MINIMUM, MAXIMUM, MOYE_INT, MOYE_EXT (the linear part at
    /// the first and at the last node: MOMENT_0 ∓ MOMENT_1/2).
    fn values(&self) -> [f64; 6] {
        [
            self.moment_0,
            self.moment_1,
            self.minimum,
            self.maximum,
            self.moment_0 - 0.5 * self.moment_1,
            self.moment_0 + 0.5 * self.moment_1,
        ]
    }
}

/// MOYENNE (code_aster's `rvpstm`/`rvtamo`): along the path of the nodes
/// (see [`ordered_nodes`]) without those where none of the components is
/// defined (`rvouex`/`utmach`), six rows QUANTITE = MOMENT_0, MOMENT_1,
/// MINIMUM, MAXIMUM, MOYE_INT, MOYE_EXT with a column per component. A
/// node where some components are absent cuts the segments it ends for
/// those: code_aster's alarm POSTRELE_62/63 ("hors de la matière").
#[allow(clippy::too_many_arguments)]
fn path_rows(
    occ: &Args,
    mesh: &Mesh,
    field: &NodalField,
    field_name: &str,
    nodes: &[usize],
    lead: Row,
    rows: &mut Vec<Row>,
    alarms: &mut Vec<(&'static str, String)>,
) -> Result<(), Diagnostic> {
    let cmps = path_components(occ, field, field_name)?;
    let value = |n: usize, i: usize| field.values[n * field.ncmp() + i];
    let path: Vec<usize> = nodes
        .iter()
        .copied()
        .filter(|&n| cmps.iter().any(|&(_, i)| !value(n, i).is_nan()))
        .collect();
    let key = if occ.has("GROUP_NO") {
        "GROUP_NO"
    } else {
        "NOEUD"
    };
    let cmp_list = cmps
        .iter()
        .map(|(c, _)| c.as_str())
        .collect::<Vec<_>>()
        .join(", ");
    if path.len() < 2 {
        return Err(occ.error(
            key,
            format!(
                "MOYENNE of {field_name} needs a path of at least 2 nodes where {cmp_list} is defined; {} of the {} selected node(s) has it (code_aster: POSTRELE_6, path of zero length or of one node)",
                path.len(),
                nodes.len()
            ),
        ));
    }
    let mut s = vec![0.0; path.len()];
    for k in 1..path.len() {
        let (a, b) = (mesh.coords[path[k - 1]], mesh.coords[path[k]]);
        let chord = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2) + (b[2] - a[2]).powi(2)).sqrt();
        s[k] = s[k - 1] + chord;
    }
    let mut means = Vec::new();
    let mut warned = false;
    for (c, i) in &cmps {
        let f: Vec<f64> = path.iter().map(|&n| value(n, *i)).collect();
        let mean = PathMean::of(&s, &f);
        // Zero, or NaN where no segment has the component at both ends.
        if mean.length.is_nan() || mean.length <= 0.0 {
            return Err(occ.error(
                key,
                format!(
                    "MOYENNE of {c} of {field_name}: the path through {} has no length where {c} is defined at both ends of a segment (code_aster would divide by zero)",
                    path.iter()
                        .map(|&n| node_name(n))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ));
        }
        let missing = f.iter().filter(|v| v.is_nan()).count();
        if missing > 0 && !warned {
            warned = true;
            let (id, what) = if missing == 1 {
                ("POSTRELE_62", "node is".to_string())
            } else {
                ("POSTRELE_63", "nodes are".to_string())
            };
            alarms.push((
                id,
                format!(
                    "MOYENNE of {field_name}: {missing} {what} out of the material for {c} (the component is absent there); the segments they end are left out of the mean"
                ),
            ));
        }
        means.push(mean.values());
    }
    for (q, name) in [
        "MOMENT_0", "MOMENT_1", "MINIMUM", "MAXIMUM", "MOYE_INT", "MOYE_EXT",
    ]
    .iter()
    .enumerate()
    {
        let mut row = lead.clone();
        for ((c, _), v) in cmps.iter().zip(&means) {
            row.push((c.clone(), Cell::Real(v[q])));
        }
        row.push((QUANTITE.to_string(), Cell::Text(name.to_string())));
        rows.push(row);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::PathMean;

    /// f = 2 + 3 s on [0, 6] with uneven nodes: the mean is f(3) = 11, the
    /// linear part is f itself: MOMENT_1 = f(6) − f(0) = 18.
    #[test]
    fn linear_field_gives_its_midpoint_and_end_difference() {
        let s = [0.0, 0.5, 2.0, 3.0, 6.0];
        let f: Vec<f64> = s.iter().map(|x| 2.0 + 3.0 * x).collect();
        let v = PathMean::of(&s, &f).values();
        let want = [11.0, 18.0, 2.0, 20.0, 2.0, 20.0];
        for (a, b) in v.iter().zip(want) {
            assert!((a - b).abs() < 1e-12, "{v:?}");
        }
    }
}
