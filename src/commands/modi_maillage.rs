//! MODI_MAILLAGE: modifies a mesh in place (skin orientation, moves).

use super::blocks::*;
use super::mesh_args::{check_groups, log_report, mesh_error, mesh_of, GroupKind};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::mesh::ops::{self, OrieDim};
use crate::study::Study;

pub fn def() -> CommandDef {
    let spec = command(
        "MODI_MAILLAGE",
        Produces::Concept(C::Maillage),
        vec![
            concept("MAILLAGE", &[C::Maillage])
                .required()
                .doc("the mesh to modify (also the reused concept)")
                .kw(),
            fact(
                "ORIE_PEAU_2D",
                vec![
                    text("GROUP_MA")
                        .required()
                        .many()
                        .doc("SEG2/SEG3 skin cells to orient")
                        .kw(),
                    text("GROUP_MA_SURF")
                        .many()
                        .doc("restricts the support cells searched")
                        .kw(),
                ],
            )
            .many()
            .doc("orients 2D skin cells so that their normal points out of their support cell")
            .kw(),
            fact(
                "ORIE_PEAU_3D",
                vec![
                    text("GROUP_MA")
                        .required()
                        .many()
                        .doc("TRIA/QUAD skin cells to orient")
                        .kw(),
                    text("GROUP_MA_VOLU")
                        .many()
                        .doc("restricts the support cells searched")
                        .kw(),
                ],
            )
            .many()
            .doc("orients 3D skin cells so that their normal points out of their support cell")
            .kw(),
            real("TRANSLATION").count(2, 3).doc("translation vector").kw(),
            fact(
                "ROTATION",
                vec![
                    real("POIN_1").required().count(2, 3).kw(),
                    real("ANGLE").default(r(0.0)).doc("in degrees").kw(),
                    real("POIN_2").count(2, 3).kw(),
                    real("DIR").count(2, 3).kw(),
                ],
            )
            .many()
            .rules(vec![exclus(&["DIR", "POIN_2"])])
            .doc("rotation about the axis through POIN_1")
            .kw(),
            real("ECHELLE").doc("scale factor on coordinates").kw(),
            info(),
        ],
    )
    .reentrant(Reentrant::Required("MAILLAGE"))
    .rules(vec![
        au_moins_un(&["ORIE_PEAU_2D", "ORIE_PEAU_3D", "TRANSLATION", "ROTATION", "ECHELLE"]),
        present_absent("ORIE_PEAU_2D", &["ORIE_PEAU_3D"]),
    ])
    .doc("Modifies a mesh in place (reuse compulsory): skin orientation before contact or pressure, or geometric moves.");
    CommandDef { spec, exec }
}

/// ORIE_PEAU_2D/3D, TRANSLATION and ECHELLE; ROTATION is not built yet.
fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    let mut mesh = mesh_of(study, args, "MAILLAGE")?.clone();
    for (key, dim, support) in [
        ("ORIE_PEAU_2D", OrieDim::D2, "GROUP_MA_SURF"),
        ("ORIE_PEAU_3D", OrieDim::D3, "GROUP_MA_VOLU"),
    ] {
        for occ in args.facts(key) {
            check_groups(&mesh, occ, "GROUP_MA", GroupKind::Cells)?;
            if occ.has(support) {
                check_groups(&mesh, occ, support, GroupKind::Cells)?;
            }
            let sup = occ.texts(support);
            let r = ops::orie_peau(
                &mut mesh,
                dim,
                &occ.texts("GROUP_MA"),
                (!sup.is_empty()).then_some(sup.as_slice()),
            )
            .map_err(|e| mesh_error(occ, "GROUP_MA", e))?;
            study.log(format!(
                "    {key}: {} cells reoriented, {} without support cell",
                r.reoriented, r.not_processed
            ));
            log_report(study, "MODI_MAILLAGE", &r.report);
        }
    }
    if args.has("ROTATION") {
        return Err(args.not_implemented("ROTATION", ""));
    }
    let t = args.reals("TRANSLATION");
    if !t.is_empty() {
        for p in &mut mesh.coords {
            for (k, dx) in t.iter().enumerate() {
                p[k] += dx;
            }
        }
    }
    if let Some(s) = args.real("ECHELLE") {
        for p in &mut mesh.coords {
            p.iter_mut().for_each(|x| *x *= s);
        }
    }
    Ok(Some(ConceptData::Mesh(Box::new(mesh))))
}
