//! CREA_MAILLAGE: builds a new mesh from an existing one.

use super::blocks::*;
use super::mesh_args::{check_groups, mesh_error, mesh_of, GroupKind};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::mesh::ops;
use crate::study::Study;

pub fn def() -> CommandDef {
    let selection = || vec![tout(), maille(), group_ma()];
    let rule = || vec![au_moins_un(&["TOUT", "MAILLE", "GROUP_MA"])];
    let spec = command(
        "CREA_MAILLAGE",
        Produces::Concept(C::Maillage),
        vec![
            concept("MAILLAGE", &[C::Maillage])
                .required()
                .doc("the source mesh (left unchanged)")
                .kw(),
            fact("QUAD_LINE", selection())
                .rules(rule())
                .doc("quadratic to linear cells; mid-nodes used only by converted cells are deleted, empty node groups vanish")
                .kw(),
            fact(
                "LINE_QUAD",
                [
                    selection(),
                    vec![
                        text("PREF_NOEUD").default(t("NS")).kw(),
                        int("PREF_NUME").default(i(1)).kw(),
                    ],
                ]
                .concat(),
            )
            .rules(rule())
            .doc("linear to quadratic cells: a node at the middle of each edge of the selected cells (QUAD4 gives QUAD8, HEXA8 HEXA20, TETRA4 TETRA10); groups kept, the new nodes in none")
            .kw(),
            fact(
                "RESTREINT",
                vec![
                    group_ma(),
                    maille(),
                    oui_non("TOUT_GROUP_MA", "NON").kw(),
                    group_no(),
                    oui_non("TOUT_GROUP_NO", "NON").kw(),
                ],
            )
            .rules(vec![au_moins_un(&["GROUP_MA", "MAILLE"])])
            .doc("restricts the mesh to some cell groups")
            .kw(),
            titre(),
            info(),
        ],
    )
    .rules(vec![un_parmi(&["QUAD_LINE", "LINE_QUAD", "RESTREINT"])])
    .doc("Creates a new mesh from MAILLAGE (never in place).");
    CommandDef { spec, exec }
}

/// QUAD_LINE or LINE_QUAD: a new mesh, the source left unchanged.
fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    let (occ, name) = match (args.fact("QUAD_LINE"), args.fact("LINE_QUAD")) {
        (Some(o), _) => (o, "QUAD_LINE"),
        (None, Some(o)) => (o, "LINE_QUAD"),
        (None, None) => {
            return Err(args.not_implemented("RESTREINT", "only QUAD_LINE and LINE_QUAD"))
        }
    };
    let src = mesh_of(study, args, "MAILLAGE")?;
    let cells: Option<Vec<usize>> = if occ.has("TOUT") {
        None
    } else if occ.has("GROUP_MA") {
        check_groups(src, occ, "GROUP_MA", GroupKind::Cells)?;
        let mut c: Vec<usize> = occ
            .texts("GROUP_MA")
            .iter()
            .flat_map(|g| src.cell_groups[*g].iter().copied())
            .collect();
        c.sort_unstable();
        c.dedup();
        Some(c)
    } else {
        return Err(occ.not_implemented("MAILLE", "cells by name"));
    };
    let key = if occ.has("TOUT") { "TOUT" } else { "GROUP_MA" };
    let mesh = if name == "QUAD_LINE" {
        ops::quad_line(src, cells.as_deref())
    } else {
        ops::line_quad(src, cells.as_deref())
    }
    .map_err(|e| mesh_error(occ, key, e))?;
    study.log(format!(
        "    {name}: {} nodes, {} cells",
        mesh.nnodes(),
        mesh.ncells()
    ));
    Ok(Some(ConceptData::Mesh(Box::new(mesh))))
}
