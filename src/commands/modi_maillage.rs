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

/// ORIE_PEAU, ORIE_PEAU_2D/3D, TRANSLATION, ROTATION and ECHELLE.
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
    // code_aster's order (op0154): TRANSLATION, ROTATION, ECHELLE; the
    // orientation of skins does not depend on where the mesh is.
    let t = args.reals("TRANSLATION");
    if !t.is_empty() {
        for p in &mut mesh.coords {
            for (k, dx) in t.iter().enumerate() {
                p[k] += dx;
            }
        }
    }
    for occ in args.facts("ROTATION") {
        let rotation = rotation_of(occ)?;
        for p in &mut mesh.coords {
            *p = rotation.apply(*p);
        }
    }
    if let Some(s) = args.real("ECHELLE") {
        for p in &mut mesh.coords {
            p.iter_mut().for_each(|x| *x *= s);
        }
    }
    Ok(Some(ConceptData::Mesh(Box::new(mesh))))
}

/// A rotation of ROTATION: ANGLE degrees about the axis through POIN_1,
/// right-handed about its direction (code_aster's `rotama`). POIN_1 of
/// two values is the 2D case, about the z axis through that point; of
/// three, the axis is DIR or POIN_2 - POIN_1.
#[derive(Debug, Clone, Copy)]
struct Rotation {
    point: [f64; 3],
    /// Unit direction of the axis.
    axis: [f64; 3],
    cos: f64,
    sin: f64,
}

impl Rotation {
    /// Rodrigues' formula: p' = c + cos (p-c) + (1-cos) ((p-c).d) d + sin d x (p-c).
    fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let r = [0, 1, 2].map(|k| p[k] - self.point[k]);
        let d = self.axis;
        let along = r[0] * d[0] + r[1] * d[1] + r[2] * d[2];
        let cross = [
            d[1] * r[2] - d[2] * r[1],
            d[2] * r[0] - d[0] * r[2],
            d[0] * r[1] - d[1] * r[0],
        ];
        [0, 1, 2].map(|k| {
            self.point[k] + self.cos * r[k] + (1.0 - self.cos) * along * d[k] + self.sin * cross[k]
        })
    }
}

fn rotation_of(occ: &Args) -> Result<Rotation, crate::diag::Diagnostic> {
    let p1 = occ.reals("POIN_1");
    let angle = occ.real("ANGLE").unwrap_or(0.0).to_radians();
    let (point, axis) = if p1.len() == 2 {
        if occ.has("DIR") || occ.has("POIN_2") {
            let key = if occ.has("DIR") { "DIR" } else { "POIN_2" };
            return Err(occ.error(
                key,
                "POIN_1 of two values is a rotation in the plane (about the z axis through POIN_1): DIR and POIN_2 are for a 3D axis, give POIN_1 three values",
            ));
        }
        ([p1[0], p1[1], 0.0], [0.0, 0.0, 1.0])
    } else {
        let point = [p1[0], p1[1], p1[2]];
        let (key, d) = if occ.has("DIR") {
            ("DIR", occ.reals("DIR"))
        } else if occ.has("POIN_2") {
            let p2 = occ.reals("POIN_2");
            ("POIN_2", p2.iter().zip(&p1).map(|(b, a)| b - a).collect())
        } else {
            return Err(occ.error(
                "POIN_1",
                "a 3D rotation needs its axis: give DIR (its direction) or POIN_2 (a second point on it)",
            ));
        };
        if d.len() != 3 {
            return Err(occ.error(
                key,
                format!(
                    "{key} takes three values with POIN_1 of three, here {}",
                    d.len()
                ),
            ));
        }
        let norm = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if norm < 1e-14 {
            return Err(occ.error(
                key,
                "the axis of the rotation has a zero direction (ALGORITH10_48)",
            ));
        }
        (point, [d[0] / norm, d[1] / norm, d[2] / norm])
    };
    Ok(Rotation {
        point,
        axis,
        cos: angle.cos(),
        sin: angle.sin(),
    })
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
