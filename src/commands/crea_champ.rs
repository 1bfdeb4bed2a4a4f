//! CREA_CHAMP: creates a field (here nodal fields).

use super::blocks::*;
use super::mesh_args::mesh_of;
use super::model_args::{mesh_of_model, model_of, select_nodes};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::diag::{closest, Diagnostic};
use crate::model::{Dof, Model};
use crate::result::NodalField;
use crate::study::Study;

pub fn def() -> CommandDef {
    let mut extr = vec![
        concept("RESULTAT", RESULTS)
            .required()
            .doc("result to extract from")
            .kw(),
        text("NOM_CHAM").required().into(NOM_CHAM_RESU).kw(),
        int("NUME_ORDRE").kw(),
        real("INST").kw(),
    ];
    extr.extend(critere_precision(1e-6));
    let spec = command(
        "CREA_CHAMP",
        Produces::Concept(C::ChamNo),
        vec![
            text("TYPE_CHAM")
                .required()
                .into(&["NOEU_DEPL_R"])
                .doc("location and quantity of the field (nodal real displacement-like)")
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
                .rules(vec![exclus(&["NUME_ORDRE", "INST"])])
                .kw(),
            info(),
            titre(),
        ],
    )
    .doc("Creates a nodal field, e.g. an initial velocity for ETAT_INIT.");
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

fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    if args.text("OPERATION") != Some("AFFE") {
        return Err(args.not_implemented("OPERATION", "only OPERATION='AFFE'"));
    }
    affe(study, args, result)
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
