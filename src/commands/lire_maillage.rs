//! LIRE_MAILLAGE: reads a mesh from a logical unit.

use super::blocks::*;
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::study::Study;

pub fn def() -> CommandDef {
    let spec = command(
        "LIRE_MAILLAGE",
        Produces::Concept(C::Maillage),
        vec![
            text("FORMAT")
                .into(&["ASTER", "GIBI", "GMSH", "IDEAS", "MED"])
                .default(t("MED"))
                .doc("file format")
                .kw(),
            int("UNITE")
                .default(i(20))
                .doc("logical unit of the mesh file (fort.20 by default)")
                .kw(),
            block(
                "b_format_med",
                eq("FORMAT", "MED"),
                vec![
                    text("NOM_MED")
                        .doc("name of the mesh in the MED file; absent: the first one")
                        .kw(),
                    int("INFO_MED").default(i(1)).into_ints(&[1, 2, 3]).kw(),
                    text("PARTITIONNEUR")
                        .into(&["SANS", "PTSCOTCH"])
                        .default(t("SANS"))
                        .kw(),
                ],
            )
            .kw(),
            fact(
                "VERI_MAIL",
                vec![
                    oui_non("VERIF", "OUI").doc("check the mesh").kw(),
                    real("APLAT")
                        .default(r(1e-3))
                        .doc("flatness threshold of the check")
                        .kw(),
                ],
            )
            .defaulted()
            .doc("mesh checks after reading")
            .kw(),
            info(),
        ],
    )
    .doc("Reads a mesh; MED cell groups become GROUP_MA, node groups GROUP_NO.");
    CommandDef { spec, exec }
}

/// Reads the MED file behind the logical unit (only FORMAT='MED').
fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    if args.text("FORMAT") != Some("MED") {
        return Err(args.not_implemented("FORMAT", "only FORMAT='MED' is read"));
    }
    let unit = args.int("UNITE").unwrap_or(20);
    let path = study.unit_path(unit);
    if !path.is_file() {
        let mapped = study.units.path(unit).is_some();
        let mut d = args.error(
            "UNITE",
            format!(
                "logical unit {unit} {} '{}', which does not exist",
                if mapped {
                    "is mapped to"
                } else {
                    "is not mapped; its default file is"
                },
                path.display()
            ),
        );
        if !mapped {
            d = d.note(format!(
                "map it with a line 'F mmed <path> D {unit}' in the study's .export file, or with --unit {unit}=<path>"
            ));
        }
        return Err(d);
    }
    let mesh = crate::medio::read_mesh(&path, args.text("NOM_MED")).map_err(|e| {
        args.error(
            if args.given("NOM_MED") {
                "NOM_MED"
            } else {
                "UNITE"
            },
            e.to_string(),
        )
    })?;
    study.log(format!(
        "    mesh '{}' read from {}: {} nodes, {} cells",
        mesh.name,
        path.display(),
        mesh.nnodes(),
        mesh.ncells()
    ));
    for (t, n) in mesh.count_by_type() {
        study.log(format!("      {:<8} {n}", t.aster_name()));
    }
    Ok(Some(ConceptData::Mesh(Box::new(mesh))))
}
