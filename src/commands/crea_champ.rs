//! CREA_CHAMP: creates a nodal field, by assigned values (AFFE) or as a
//! copy of a result's field at one instant (EXTR).

use super::blocks::*;
use super::mesh_args::mesh_of;
use super::model_args::{mesh_of_model, model_of, select_nodes};
use super::post_args::{inst_access, is_gauss_name, result_of, step_nodal};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::diag::{closest, Diagnostic};
use crate::model::{Dof, Model};
use crate::result::Access;
use crate::result::NodalField;
use crate::study::Study;

pub fn def() -> CommandDef {
    let mut extr = vec![
        concept("RESULTAT", RESULTS)
            .required()
            .doc("result to extract from")
            .kw(),
        text("NOM_CHAM").required().into(NOM_CHAM_RESU).kw(),
        int("NUME_ORDRE").doc("stored index extracted").kw(),
        real("INST")
            .doc("instant extracted, found within CRITERE/PRECISION")
            .kw(),
    ];
    extr.extend(critere_precision(1e-6));
    let spec = command(
        "CREA_CHAMP",
        Produces::Concept(C::ChamNo),
        vec![
            text("TYPE_CHAM")
                .required()
                .into(TYPE_CHAM)
                .doc("location and quantity of the field: AFFE builds NOEU_DEPL_R; EXTR copies a nodal field of a result (NOEU_*); the fields by element (ELGA_*, ELNO_*) are not built yet")
                .kw(),
            text("OPERATION")
                .required()
                .into(&["AFFE", "EXTR"])
                .doc("assign values, or extract a field from a result")
                .kw(),
            block(
                "b_affe",
                eq("OPERATION", "AFFE"),
                vec![
                    concept("MAILLAGE", &[C::Maillage]).kw(),
                    concept("MODELE", &[C::Modele])
                        .doc("model: its dofs (including contact LAGS_C, LAGS_F1) define the allowed components")
                        .kw(),
                    fact(
                        "AFFE",
                        vec![
                            tout(),
                            group_ma(),
                            maille(),
                            group_no(),
                            noeud(),
                            text("NOM_CMP").required().many().doc("components").kw(),
                            real("VALE")
                                .many()
                                .doc("values, one per NOM_CMP")
                                .kw(),
                            int("VALE_I").many().kw(),
                            concept("VALE_F", &[C::Fonction]).many().kw(),
                        ],
                    )
                    .required()
                    .many()
                    .rules(vec![
                        au_moins_un(&["TOUT", "GROUP_MA", "MAILLE", "GROUP_NO", "NOEUD"]),
                        un_parmi(&["VALE", "VALE_I", "VALE_F"]),
                    ])
                    .doc("applied in order, later occurrences overwrite earlier ones; unassigned components are absent")
                    .kw(),
                ],
            )
            .rules(vec![un_parmi(&["MAILLAGE", "MODELE"])])
            .kw(),
            block("b_extr", eq("OPERATION", "EXTR"), extr)
                .rules(vec![un_parmi(&["NUME_ORDRE", "INST"])])
                .kw(),
            info(),
            titre(),
        ],
    )
    .doc("Creates a nodal field (cham_no): assigned values (AFFE), e.g. an initial velocity for ETAT_INIT, or a copy of a result's nodal field at one instant (EXTR), e.g. for TEST_RESU CHAM_NO.");
    CommandDef { spec, exec }
}

/// Components of code_aster's DEPL_R quantity that a nodal field of aster
/// may carry: displacements and rotations, and the contact unknowns of the
/// continuous formulation (LAGS_C, LAGS_F1, LAGS_F2), which sdnv103f sets
/// in its initial velocity. The other DEPL_R components (pressures,
/// temperatures of coupled elements...) are outside aster's scope.
pub const DEPL_R: &[&str] = &[
    "DX", "DY", "DZ", "DRX", "DRY", "DRZ", "LAGS_C", "LAGS_F1", "LAGS_F2",
];

/// TYPE_CHAM values of the catalogue: the nodal ones that EXTR copies
/// (and AFFE builds, NOEU_DEPL_R), and code_aster's fields by element,
/// which are refused at run time as not built yet.
const TYPE_CHAM: &[&str] = &[
    "NOEU_DEPL_R",
    "NOEU_SIEF_R",
    "NOEU_EPSI_R",
    "NOEU_VAR2_R",
    "NOEU_INFC_R",
    "NOEU_ENER_R",
    "ELGA_SIEF_R",
    "ELGA_VARI_R",
    "ELGA_EPSI_R",
    "ELNO_SIEF_R",
    "ELNO_VARI_R",
    "ELNO_EPSI_R",
];

/// The TYPE_CHAM of a result's nodal field (code_aster's quantities:
/// FORC_NODA and REAC_NODA are DEPL_R, the stresses and their
/// equivalents SIEF_R, the strains and theirs EPSI_R, the internal
/// variables at nodes VAR2_R, the discrete contact's CONT_NOEU INFC_R,
/// the elastic energy ENER_R).
pub fn nodal_type_cham(nom_cham: &str) -> Option<&'static str> {
    Some(match nom_cham {
        "DEPL" | "VITE" | "ACCE" | "FORC_NODA" | "REAC_NODA" => "NOEU_DEPL_R",
        "SIEF_NOEU" | "SIGM_NOEU" | "SIEQ_NOEU" => "NOEU_SIEF_R",
        "EPSI_NOEU" | "EPSG_NOEU" | "EPSL_NOEU" | "EPEQ_NOEU" => "NOEU_EPSI_R",
        "VARI_NOEU" => "NOEU_VAR2_R",
        "CONT_NOEU" => "NOEU_INFC_R",
        "ENEL_NOEU" => "NOEU_ENER_R",
        _ => return None,
    })
}

fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    let type_cham = args.text("TYPE_CHAM").unwrap_or_default();
    if !type_cham.starts_with("NOEU_") {
        return Err(args.not_implemented(
            "TYPE_CHAM",
            "fields by element (ELGA_*, ELNO_*); CREA_CHAMP builds nodal fields: AFFE of NOEU_DEPL_R, EXTR of NOEU_DEPL_R, NOEU_SIEF_R, NOEU_EPSI_R, NOEU_VAR2_R, NOEU_INFC_R, NOEU_ENER_R",
        ));
    }
    match args.text("OPERATION") {
        Some("AFFE") if type_cham != "NOEU_DEPL_R" => Err(args.not_implemented(
            "TYPE_CHAM",
            "OPERATION='AFFE' of a field other than NOEU_DEPL_R",
        )),
        Some("AFFE") => affe(study, args, result),
        _ => extr(study, args, type_cham, result),
    }
}

/// OPERATION='EXTR' from RESULTAT: a copy of the nodal field NOM_CHAM of
/// the step that NUME_ORDRE or INST (within CRITERE/PRECISION) designates,
/// on the result's mesh. The field keeps the result's components and its
/// absent pairs (a CONT_NOEU outside the contact zones stays absent).
fn extr(study: &mut Study, args: &Args, type_cham: &str, result: Option<&str>) -> ExecResult {
    let (rname, res) = result_of(study, args, "RESULTAT")?;
    let nom_cham = args.text("NOM_CHAM").unwrap_or_default();
    let Some(expected) = nodal_type_cham(nom_cham) else {
        let what = if is_gauss_name(nom_cham) || nom_cham.ends_with("_ELNO") {
            "a field by element"
        } else {
            "not a nodal field"
        };
        return Err(args.not_implemented(
            "NOM_CHAM",
            &format!(
                "EXTR of {nom_cham} ({what}); EXTR copies the nodal fields DEPL, VITE, ACCE, FORC_NODA, REAC_NODA (NOEU_DEPL_R), SIEF_NOEU, SIGM_NOEU, SIEQ_NOEU (NOEU_SIEF_R), EPSI_NOEU, EPSG_NOEU, EPSL_NOEU, EPEQ_NOEU (NOEU_EPSI_R), VARI_NOEU (NOEU_VAR2_R), CONT_NOEU (NOEU_INFC_R), ENEL_NOEU (NOEU_ENER_R)"
            ),
        ));
    };
    if expected != type_cham {
        return Err(args.error(
            "TYPE_CHAM",
            format!("{nom_cham} is a field of type {expected}, not {type_cham}: give TYPE_CHAM='{expected}'"),
        ));
    }
    let (step, key) = match args.int("NUME_ORDRE") {
        Some(n) => {
            let n = usize::try_from(n)
                .map_err(|_| args.error("NUME_ORDRE", format!("NUME_ORDRE {n} is negative")))?;
            (res.find(Access::NumeOrdre(n)), "NUME_ORDRE")
        }
        None => {
            let t = args
                .real("INST")
                .ok_or_else(|| args.error("INST", "NUME_ORDRE or INST is needed"))?;
            (res.find(inst_access(args, t, 1e-6)), "INST")
        }
    };
    let step = step.map_err(|e| args.error(key, format!("result {rname}: {e}")))?;
    let field = step_nodal(step, nom_cham, args, "NOM_CHAM", rname)?.clone();
    let absent = field.values.iter().filter(|v| v.is_nan()).count();
    let line = format!(
        "    field {} ({type_cham}) = {nom_cham} of {rname} at NUME_ORDRE {} (INST {:e}): components {}, {} nodes, {absent} absent (node, component) pairs",
        result.unwrap_or("(unnamed)"),
        step.nume_ordre,
        step.inst,
        field.components.join(" "),
        field.nnodes()
    );
    let mesh = res.mesh.clone();
    study.log(line);
    Ok(Some(ConceptData::Field(Box::new(
        crate::concepts::ChamNo { mesh, field },
    ))))
}

/// OPERATION='AFFE' (code_aster's `cnoaff`): the components are the union
/// of all NOM_CMP in order of first appearance; occurrences are applied in
/// order, later ones overwriting earlier ones node by node and component
/// by component; a pair never assigned stays absent (NaN), which is not
/// zero: ETAT_INIT reads it as 0 but a field operation must not.
fn affe(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    let (support, model, mesh, mesh_name) = if args.has("MODELE") {
        let (name, m) = model_of(study, args, "MODELE")?;
        let mesh = mesh_of_model(study, args, "MODELE", m)?;
        let mesh_name = m.mesh.clone();
        (
            format!("model {name}"),
            Some((name, m.clone())),
            mesh,
            mesh_name,
        )
    } else {
        let name = args.concept("MAILLAGE").unwrap_or_default();
        (
            format!("mesh {name}"),
            None,
            mesh_of(study, args, "MAILLAGE")?,
            name.to_string(),
        )
    };
    let occs = args.facts("AFFE");
    let mut components: Vec<String> = Vec::new();
    for occ in occs {
        if !occ.has("VALE") {
            let key = if occ.has("VALE_F") {
                "VALE_F"
            } else {
                "VALE_I"
            };
            return Err(occ.error(
                key,
                "a field of type NOEU_DEPL_R takes real values: use VALE",
            ));
        }
        let cmps = occ.texts("NOM_CMP");
        let vale = occ.reals("VALE");
        if cmps.len() != vale.len() {
            return Err(occ.error(
                "VALE",
                format!(
                    "NOM_CMP gives {} component(s) and VALE {} value(s): they must have the same length",
                    cmps.len(),
                    vale.len()
                ),
            ));
        }
        for (i, c) in cmps.iter().enumerate() {
            check_component(occ, c, model.as_ref())?;
            if cmps[..i].contains(c) {
                return Err(occ.error(
                    "NOM_CMP",
                    format!("the component {c} is given twice in NOM_CMP"),
                ));
            }
            if !components.iter().any(|x| x == c) {
                components.push(c.to_string());
            }
        }
    }
    let tout: Vec<usize> = match &model {
        Some((_, m)) => {
            let mask = m.node_mask(mesh);
            (0..mesh.nnodes()).filter(|&n| mask[n]).collect()
        }
        None => (0..mesh.nnodes()).collect(),
    };
    let mut field = NodalField::absent(components, mesh.nnodes());
    let mut lines = Vec::new();
    for (k, occ) in occs.iter().enumerate() {
        let nodes = select_nodes(mesh, occ, &tout)?;
        let cmps = occ.texts("NOM_CMP");
        let vale = occ.reals("VALE");
        let idx: Vec<usize> = cmps
            .iter()
            .filter_map(|c| field.component_index(c))
            .collect();
        for &n in &nodes {
            for (&c, &v) in idx.iter().zip(&vale) {
                field.set(n, c, v);
            }
        }
        lines.push(format!(
            "      AFFE {}: {} nodes, {}",
            k + 1,
            nodes.len(),
            cmps.iter()
                .zip(&vale)
                .map(|(c, v)| format!("{c}={v}"))
                .collect::<Vec<_>>()
                .join(" ")
        ));
    }
    let absent = field.values.iter().filter(|v| v.is_nan()).count();
    let header = format!(
        "    field {} (NOEU_DEPL_R) on {support}: components {}, {} nodes, {absent} absent (node, component) pairs",
        result.unwrap_or("(unnamed)"),
        field.components.join(" "),
        mesh.nnodes()
    );
    study.log(header);
    for l in lines {
        study.log(l);
    }
    Ok(Some(ConceptData::Field(Box::new(
        crate::concepts::ChamNo {
            mesh: mesh_name,
            field,
        },
    ))))
}

/// A component must belong to DEPL_R; on a model, a displacement or
/// rotation must also be one of its dofs (DZ on an AXIS model is an error).
/// The contact multipliers are accepted on any model: they are unknowns
/// DEFI_CONTACT adds later, not dofs of the model itself.
fn check_component(occ: &Args, c: &str, model: Option<&(String, Model)>) -> Result<(), Diagnostic> {
    if !DEPL_R.contains(&c) {
        let mut d = occ.error(
            "NOM_CMP",
            format!("{c} is not a component of the quantity DEPL_R"),
        );
        d.suggestion = closest(c, DEPL_R);
        d.choices = DEPL_R.iter().map(|s| s.to_string()).collect();
        return Err(d);
    }
    if let Some((name, m)) = model {
        let is_lagrange = c.starts_with("LAGS_");
        if !is_lagrange && !Dof::from_name(c).is_some_and(|d| m.has_dof(d)) {
            return Err(occ.error(
                "NOM_CMP",
                format!(
                    "{c} is not a degree of freedom of the model {name}, whose nodes carry {}",
                    m.dofs
                        .iter()
                        .map(|d| d.name())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ));
        }
    }
    Ok(())
}
