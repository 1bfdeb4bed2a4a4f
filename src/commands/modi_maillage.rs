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
                "ORIE_PEAU",
                vec![
                    text("GROUP_MA_PEAU")
                        .required()
                        .many()
                        .doc("skin cells to orient: SEG2/SEG3 of a 2D mesh or TRIA/QUAD of a 3D one")
                        .kw(),
                    text("GROUP_MA_INTERNE")
                        .many()
                        .doc("restricts the support cells searched")
                        .kw(),
                ],
            )
            .many()
            .doc("code_aster 15's merge of ORIE_PEAU_2D and ORIE_PEAU_3D: the dimension is that of the skin cells")
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
        au_moins_un(&[
            "ORIE_PEAU",
            "ORIE_PEAU_2D",
            "ORIE_PEAU_3D",
            "TRANSLATION",
            "ROTATION",
            "ECHELLE",
        ]),
        present_absent("ORIE_PEAU_2D", &["ORIE_PEAU_3D"]),
        present_absent("ORIE_PEAU", &["ORIE_PEAU_2D", "ORIE_PEAU_3D"]),
    ])
    .doc("Modifies a mesh in place (reuse compulsory): skin orientation before contact or pressure, or geometric moves.");
    CommandDef { spec, exec }
}

/// ORIE_PEAU, ORIE_PEAU_2D/3D, TRANSLATION and ECHELLE; ROTATION is not
/// built yet.
fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    let mut mesh = mesh_of(study, args, "MAILLAGE")?.clone();
    for (key, dim, skin, support) in [
        ("ORIE_PEAU", None, "GROUP_MA_PEAU", "GROUP_MA_INTERNE"),
        (
            "ORIE_PEAU_2D",
            Some(OrieDim::D2),
            "GROUP_MA",
            "GROUP_MA_SURF",
        ),
        (
            "ORIE_PEAU_3D",
            Some(OrieDim::D3),
            "GROUP_MA",
            "GROUP_MA_VOLU",
        ),
    ] {
        for occ in args.facts(key) {
            check_groups(&mesh, occ, skin, GroupKind::Cells)?;
            if occ.has(support) {
                check_groups(&mesh, occ, support, GroupKind::Cells)?;
            }
            let groups = occ.texts(skin);
            let dim = match dim {
                Some(d) => d,
                None => skin_dimension(&mesh, &groups).map_err(|m| occ.error(skin, m))?,
            };
            let sup = occ.texts(support);
            let r = ops::orie_peau(
                &mut mesh,
                dim,
                &groups,
                (!sup.is_empty()).then_some(sup.as_slice()),
            )
            .map_err(|e| mesh_error(occ, skin, e))?;
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

/// The dimension of ORIE_PEAU from its skin cells: segments orient as in
/// ORIE_PEAU_2D, faces as in ORIE_PEAU_3D; a mix is refused.
fn skin_dimension(mesh: &crate::mesh::Mesh, groups: &[&str]) -> Result<OrieDim, String> {
    let (mut lines, mut faces) = (0usize, 0usize);
    for g in groups {
        for &c in mesh.cell_groups.get(*g).into_iter().flatten() {
            match mesh.cells[c].kind.dim() {
                1 => lines += 1,
                2 => faces += 1,
                _ => {}
            }
        }
    }
    match (lines, faces) {
        (0, 0) => Err("the skin groups hold no segment or face cell to orient".into()),
        (_, 0) => Ok(OrieDim::D2),
        (0, _) => Ok(OrieDim::D3),
        (l, f) => Err(format!(
            "the skin groups mix {l} segment and {f} face cells: give the 2D and the 3D skins in separate occurrences"
        )),
    }
}
