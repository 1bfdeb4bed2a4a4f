//! AFFE_MODELE: assigns finite elements to the cells of a mesh.

use std::collections::BTreeMap;

use super::blocks::*;
use super::mesh_args::mesh_of;
use super::model_args::{groups_containing, select_cells};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::mesh::ops::jacobian_dets;
use crate::mesh::CellType;
use crate::model::spec::{element_spec, unimplemented_element, Formulation};
use crate::model::{CellRole, Dof, Model};
use crate::study::Study;

pub fn def() -> CommandDef {
    let spec = command(
        "AFFE_MODELE",
        Produces::Concept(C::Modele),
        vec![
            concept("MAILLAGE", &[C::Maillage]).required().kw(),
            fact(
                "AFFE",
                vec![
                    tout(),
                    group_ma(),
                    maille(),
                    text("PHENOMENE")
                        .required()
                        .into(&["MECANIQUE"])
                        .doc("physics; only MECANIQUE in aster")
                        .kw(),
                    block(
                        "b_mecanique",
                        eq("PHENOMENE", "MECANIQUE"),
                        vec![text("MODELISATION")
                            .required()
                            .into(MODELISATIONS)
                            .doc("element family; _SI is reduced integration")
                            .kw()],
                    )
                    .kw(),
                ],
            )
            .required()
            .many()
            .rules(vec![un_parmi(&["TOUT", "GROUP_MA", "MAILLE"])])
            .doc("applied in order: a later occurrence replaces the element wherever its modelisation has one for the cell type")
            .kw(),
            oui_non("VERI_JACOBIEN", "OUI")
                .doc("check element Jacobians")
                .kw(),
            info(),
        ],
    )
    .doc("Defines the model: physics and element type per cell.");
    CommandDef { spec, exec }
}

/// The modelisations aster builds, with their formulation. Any other
/// value is refused as not implemented rather than silently giving no
/// element.
fn formulation_of(modelisation: &str) -> Option<Formulation> {
    match modelisation {
        "3D" | "3D_SI" => Some(Formulation::Solid3d),
        "AXIS" | "AXIS_SI" => Some(Formulation::Axis),
        "D_PLAN" | "D_PLAN_SI" => Some(Formulation::PlaneStrain),
        "C_PLAN" | "C_PLAN_SI" => Some(Formulation::PlaneStress),
        _ => None,
    }
}

/// The boundary element a modelisation puts on a cell one dimension below
/// its volume cells (code_aster's MECA_FACE* in 3D, MEAXSE* in AXIS):
/// such cells carry loads and contact, no stiffness.
fn skin_element(formulation: Formulation, cell: CellType) -> Option<&'static str> {
    use CellType::*;
    match (formulation, cell) {
        (Formulation::Solid3d, Tria3) => Some("MECA_FACE3"),
        (Formulation::Solid3d, Tria6) => Some("MECA_FACE6"),
        (Formulation::Solid3d, Quad4) => Some("MECA_FACE4"),
        (Formulation::Solid3d, Quad8) => Some("MECA_FACE8"),
        // edges of a 3D model: they carry FORCE_ARETE only (given by
        // MODELISATION='3D' alone, see `assigns_skin`)
        (Formulation::Solid3d, Seg2) => Some("MECA_ARETE2"),
        (Formulation::Solid3d, Seg3) => Some("MECA_ARETE3"),
        (Formulation::Axis, Seg2) => Some("MEAXSE2"),
        (Formulation::Axis, Seg3) => Some("MEAXSE3"),
        // code_aster's D_PLAN and C_PLAN share their edge elements.
        (Formulation::PlaneStrain | Formulation::PlaneStress, Seg2) => Some("MEPLSE2"),
        (Formulation::PlaneStrain | Formulation::PlaneStress, Seg3) => Some("MEPLSE3"),
        _ => None,
    }
}

/// Whether `modelisation` puts its skin element on `cell`: the edge
/// elements MECA_ARETE2/3 come with '3D' only [mem: code_aster's 3D_SI
/// catalogue is not known here to hold them], so that 3D_SI on SEG cells
/// still assigns nothing.
fn assigns_skin(modelisation: &str, form: Formulation, cell: CellType) -> bool {
    skin_element(form, cell).is_some()
        && (cell.dim() != 1 || form != Formulation::Solid3d || modelisation == "3D")
}

/// The topological dimension of the volume cells of a formulation (the
/// "main dimension" of code_aster's MODELE1_70 check).
fn main_dim(f: Formulation) -> usize {
    match f {
        Formulation::Solid3d => 3,
        Formulation::Axis | Formulation::PlaneStrain | Formulation::PlaneStress => 2,
    }
}

fn family_name(f: Formulation) -> &'static str {
    match f {
        Formulation::Solid3d => "3D (3D, 3D_SI)",
        Formulation::Axis => "2D axisymmetric (AXIS, AXIS_SI)",
        Formulation::PlaneStrain => "2D plane strain (D_PLAN, D_PLAN_SI)",
        Formulation::PlaneStress => "2D plane stress (C_PLAN, C_PLAN_SI)",
    }
}

/// Applies the AFFE occurrences in order (semantics.md §3.2): wherever an
/// occurrence's modelisation has an element for a cell's type it replaces
/// what the cell had; elsewhere the cell keeps it. An element that exists
/// in code_aster but not here must stop the run, because skipping it would
/// silently keep the earlier (differently integrated) element.
fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    let mesh_name = args.concept("MAILLAGE").unwrap_or_default().to_string();
    let mesh = mesh_of(study, args, "MAILLAGE")?.clone();
    let mut roles = vec![CellRole::None; mesh.ncells()];
    // The occurrence that gave each cell its element, for the count table.
    let mut given_by: Vec<Option<usize>> = vec![None; mesh.ncells()];
    let mut family: Option<(Formulation, usize, String)> = None;
    let mut alarms = Vec::new();
    // The cells some occurrence selected, to say why nothing got an element.
    let mut selected = vec![false; mesh.ncells()];
    let occs = args.facts("AFFE");
    for (k, occ) in occs.iter().enumerate() {
        let modelisation = occ.text("MODELISATION").unwrap_or_default();
        let Some(form) = formulation_of(modelisation) else {
            return Err(occ.not_implemented(
                "MODELISATION",
                &format!("MODELISATION='{modelisation}'; aster builds 3D, 3D_SI, AXIS, AXIS_SI, D_PLAN, D_PLAN_SI, C_PLAN and C_PLAN_SI models"),
            ));
        };
        match &family {
            Some((f, first, m)) if *f != form => {
                return Err(occ.error(
                    "MODELISATION",
                    format!(
                        "a model cannot mix {} and {} modelisations: occurrence {} of AFFE uses {m}, occurrence {} uses {modelisation}",
                        family_name(*f),
                        family_name(form),
                        first + 1,
                        k + 1
                    ),
                ));
            }
            Some(_) => {}
            None => family = Some((form, k, modelisation.to_string())),
        }
        let cells = select_cells(&mesh, occ)?;
        for &c in &cells {
            selected[c] = true;
        }
        let blocked: Vec<usize> = cells
            .iter()
            .copied()
            .filter(|&c| unimplemented_element(modelisation, mesh.cells[c].kind).is_some())
            .collect();
        if let Some(&c0) = blocked.first() {
            let kind = mesh.cells[c0].kind;
            let element = unimplemented_element(modelisation, kind).unwrap_or_default();
            let groups = groups_containing(&mesh, &blocked);
            return Err(occ.not_implemented(
                "MODELISATION",
                &format!(
                    "{modelisation} on {} is the element {element}, which aster does not have; \
                     it would be assigned to {} {} cell(s){}; restrict this occurrence with GROUP_MA \
                     to the cells {modelisation} should take",
                    kind.aster_name(),
                    blocked.len(),
                    kind.aster_name(),
                    if groups.is_empty() {
                        String::new()
                    } else {
                        format!(" of group(s) {}", groups.join(", "))
                    }
                ),
            ));
        }
        for &c in &cells {
            let kind = mesh.cells[c].kind;
            if let Some(spec) = element_spec(modelisation, kind) {
                roles[c] = CellRole::Element(spec);
                given_by[c] = Some(k);
            } else if assigns_skin(modelisation, form, kind) {
                roles[c] = CellRole::Skin {
                    modelisation: modelisation.to_string(),
                };
                given_by[c] = Some(k);
            }
        }
        let holes = cells
            .iter()
            .filter(|&&c| mesh.cells[c].kind.dim() == main_dim(form) && roles[c] == CellRole::None)
            .count();
        if holes > 0 {
            alarms.push(format!(
                "<A> <AFFE_MODELE> <MODELE1_70> after occurrence {} of AFFE (MODELISATION='{modelisation}'), \
                 {holes} cell(s) of dimension {} selected by it have no element: the model has holes there",
                k + 1,
                main_dim(form)
            ));
        }
    }
    let Some((form, _, _)) = family else {
        return Err(args.error("AFFE", "no AFFE occurrence"));
    };
    let assigned = roles.iter().filter(|r| **r != CellRole::None).count();
    // What the modelisations given define elements on, "3D_SI on TETRA10,
    // HEXA8, HEXA20; ...".
    let defined: Vec<String> = args
        .facts("AFFE")
        .iter()
        .filter_map(|o| o.text("MODELISATION"))
        .map(|m| {
            let cells: Vec<&str> = crate::model::spec::element_cells(m)
                .iter()
                .map(|c| c.aster_name())
                .collect();
            format!("{m} on {}", cells.join(", "))
        })
        .collect();
    // "5 TETRA4, 2 QUAD4" for the cells in `pick`.
    let kinds_of = |pick: &dyn Fn(usize) -> bool| -> String {
        let mut counts: Vec<(&str, usize)> = Vec::new();
        for (c, cell) in mesh.cells.iter().enumerate() {
            if !pick(c) {
                continue;
            }
            let name = cell.kind.aster_name();
            match counts.iter_mut().find(|(n, _)| *n == name) {
                Some((_, k)) => *k += 1,
                None => counts.push((name, 1)),
            }
        }
        let parts: Vec<String> = counts.iter().map(|(n, k)| format!("{k} {n}")).collect();
        parts.join(", ")
    };
    if assigned == 0 {
        return Err(args.error(
            "AFFE",
            format!(
                "no finite element could be assigned to any cell of the mesh {mesh_name}: the AFFE \
                 occurrences select {}, and the modelisations define elements only on other \
                 types ({}) (MODELE1_6)",
                kinds_of(&|c| selected[c]),
                defined.join("; ")
            ),
        ));
    }
    if !roles.iter().any(|r| matches!(r, CellRole::Element(_))) {
        let dim = main_dim(form);
        let mut present: Vec<&str> = mesh
            .cells
            .iter()
            .filter(|c| c.kind.dim() == dim)
            .map(|c| c.kind.aster_name())
            .collect();
        present.sort_unstable();
        present.dedup();
        let selected_of_dim = mesh
            .cells
            .iter()
            .enumerate()
            .any(|(c, cell)| selected[c] && cell.kind.dim() == dim);
        let why = if present.is_empty() {
            format!("no cell of the mesh {mesh_name} has dimension {dim}")
        } else if !selected_of_dim {
            // The mesh has such cells but the selection left them out
            // (AFFE on a group of faces only).
            format!(
                "the AFFE occurrences select no cell of dimension {dim}, only {} (the mesh {mesh_name} \
                 has {}): select the cells of dimension {dim} too, with TOUT='OUI' or their GROUP_MA",
                kinds_of(&|c| selected[c]),
                kinds_of(&|c| mesh.cells[c].kind.dim() == dim)
            )
        } else {
            // The mesh has cells of the dimension, of types the
            // modelisations given define no element on.
            format!(
                "the cells of dimension {dim} of the mesh {mesh_name} ({}) are of no type the modelisation defines an element on ({})",
                present.join(", "),
                defined.join("; ")
            )
        };
        return Err(args.error(
            "AFFE",
            format!(
                "the model has only boundary elements ({assigned} cells) and no volume element: {why} (MODELE1_6)"
            ),
        ));
    }
    if main_dim(form) == 2 && mesh.coords.iter().any(|x| x[2] != 0.0) {
        alarms.push(format!(
            "<A> <AFFE_MODELE> <MODELE1_3> a {} model needs a mesh in the plane z = 0: \
             the z coordinates are ignored",
            family_name(form)
        ));
    }
    if roles
        .iter()
        .any(|r| matches!(r, CellRole::Element(s) if s.is_hexs8()))
    {
        alarms.push(
            "<A> <AFFE_MODELE> <MODELE1_7> the model contains MECA_HEXS8 elements (3D_SI on HEXA8, \
             one point with hourglass stabilisation): they are reliable on parallelepipeds only \
             and may give wrong results on general shapes"
                .into(),
        );
    }
    if args.text("VERI_JACOBIEN") == Some("OUI") {
        let bad: Vec<usize> = roles
            .iter()
            .enumerate()
            .filter(|(_, r)| matches!(r, CellRole::Element(_)))
            .filter(|(c, _)| {
                let cell = &mesh.cells[*c];
                jacobian_dets(&mesh, cell).is_some_and(|d| d.iter().any(|&j| j <= 0.0))
                    // A cell of (almost) no volume, which the run refuses.
                    || crate::mesh::ops::degeneracy(&mesh, cell)
                        .is_some_and(|(_, r, _)| r < crate::mesh::ops::DEGENERATE_RATIO)
            })
            .map(|(c, _)| c)
            .collect();
        if let Some(&first) = bad.first() {
            // The smallest determinant over the cell's vertices and check
            // points says how far the first cell is from valid.
            let smallest = jacobian_dets(&mesh, &mesh.cells[first])
                .unwrap_or_default()
                .into_iter()
                .fold(f64::INFINITY, f64::min);
            alarms.push(format!(
                "<A> <AFFE_MODELE> {} element(s) have a non-positive or vanishing Jacobian determinant \
                 (inverted or degenerate cells) in group(s) {} (first: cell M{}, smallest det J \
                 {smallest:e} at its vertices and check points)",
                bad.len(),
                groups_containing(&mesh, &bad).join(", "),
                first + 1
            ));
        }
    }
    let dofs = match form {
        Formulation::Axis | Formulation::PlaneStrain | Formulation::PlaneStress => {
            vec![Dof::Dx, Dof::Dy]
        }
        Formulation::Solid3d => vec![Dof::Dx, Dof::Dy, Dof::Dz],
    };

    // The count table code_aster prints after AFFE_MODELE.
    let mut table: BTreeMap<(usize, CellType), (&'static str, usize)> = BTreeMap::new();
    for (c, role) in roles.iter().enumerate() {
        let kind = mesh.cells[c].kind;
        let Some(k) = given_by[c] else { continue };
        let name = match role {
            CellRole::Element(s) => s.name,
            CellRole::Skin { .. } => skin_element(form, kind).unwrap_or("?"),
            CellRole::None => continue,
        };
        table.entry((k, kind)).or_insert((name, 0)).1 += 1;
    }
    study.log(format!(
        "    model {} on mesh {mesh_name}: of the {} cells, {} selected, {assigned} assigned",
        result.unwrap_or("(unnamed)"),
        mesh.ncells(),
        selected_count(&mesh, occs)
    ));
    study.log(format!(
        "      {:<14}{:<16}{:<10}{:>8}",
        "MODELISATION", "ELEMENT", "CELL", "NUMBER"
    ));
    for ((k, kind), (name, n)) in &table {
        study.log(format!(
            "      {:<14}{:<16}{:<10}{:>8}",
            occs[*k].text("MODELISATION").unwrap_or_default(),
            name,
            kind.aster_name(),
            n
        ));
    }
    for a in alarms {
        study.log(a);
    }
    Ok(Some(ConceptData::Model(Box::new(Model {
        mesh: mesh_name,
        dofs,
        cells: roles,
    }))))
}

/// The number of distinct cells selected by any occurrence (code_aster's
/// "ON A DEMANDE L'AFFECTATION DE" line).
fn selected_count(mesh: &crate::mesh::Mesh, occs: &[Args]) -> usize {
    let mut seen = vec![false; mesh.ncells()];
    for occ in occs {
        if let Ok(cells) = select_cells(mesh, occ) {
            for c in cells {
                seen[c] = true;
            }
        }
    }
    seen.iter().filter(|&&s| s).count()
}
