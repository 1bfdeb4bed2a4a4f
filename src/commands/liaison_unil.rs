//! DEFI_CONTACT(FORMULATION='LIAISON_UNIL') keywords → the engine's
//! [`UnilDef`] (code_aster's `caliun`/`caraun`/`elimun`, liaison-unil.md
//! §1): zones in keyword order, nodes ascending, one link per (zone, node).

use super::model_args::select_nodes;
use crate::catalog::args::Args;
use crate::concepts::ConceptData;
use crate::contact::unilateral::{Coef, UnilAlgo, UnilDef, UnilLink, UnilZone};
use crate::diag::Diagnostic;
use crate::mesh::Mesh;
use crate::model::{Dof, Model};
use crate::study::Study;

/// At most this many NOM_CMP entries over all zones (UNILATER_43).
const MAX_COMPONENTS: usize = 30;

fn function(study: &Study, zone: &Args, key: &str, name: &str) -> Result<Coef, Diagnostic> {
    match study.concepts.data(name) {
        Some(ConceptData::Function(f)) => {
            // Messages name the function by its NOM_RESU: the default
            // TOUTRESU says nothing to the user, the concept's name does.
            let mut f = (**f).clone();
            if f.resu == "TOUTRESU" {
                f.resu = name.to_string();
            }
            Ok(Coef::Function(f))
        }
        Some(ConceptData::Formula(f)) => Ok(Coef::Formula((**f).clone())),
        _ => Err(zone.error(
            key,
            format!("{name} holds no function (its command did not run)"),
        )),
    }
}

/// Builds the definition from DEFI_CONTACT's checked keywords (`cargs`)
/// on the model's mesh.
pub fn unil_def(
    study: &Study,
    cargs: &Args,
    mesh: &Mesh,
    model: &Model,
) -> Result<UnilDef, Diagnostic> {
    let zones_args = cargs.facts("ZONE");
    if zones_args.is_empty() {
        return Err(cargs.error("ZONE", "at least one ZONE is required"));
    }
    let in_model = model.node_mask(mesh);
    let mut algo = None;
    let mut total_cmp = 0usize;
    let mut zones = Vec::new();
    let mut links = Vec::new();
    for (k, z) in zones_args.iter().enumerate() {
        let this = match z.text("ALGO_CONT").unwrap_or("CONTRAINTE") {
            "PENALISATION" => UnilAlgo::Penalty,
            _ => UnilAlgo::ActiveSet,
        };
        match algo {
            None => algo = Some(this),
            Some(a) if a != this => {
                return Err(z.error(
                    "ALGO_CONT",
                    format!(
                        "all zones of LIAISON_UNIL must use the same ALGO_CONT: zone {} differs from zone 1 (CONTACT3_4)",
                        k + 1
                    ),
                ))
            }
            _ => {}
        }
        let cmps = z.texts("NOM_CMP");
        let mults = z.concepts("COEF_MULT");
        if cmps.len() != mults.len() {
            return Err(z.error(
                "COEF_MULT",
                format!(
                    "NOM_CMP gives {} component(s) and COEF_MULT {} coefficient(s): they must have the same length (UNILATER_42)",
                    cmps.len(),
                    mults.len()
                ),
            ));
        }
        total_cmp += cmps.len();
        if total_cmp > MAX_COMPONENTS {
            return Err(z.error(
                "NOM_CMP",
                format!("more than {MAX_COMPONENTS} NOM_CMP entries over all zones (UNILATER_43)"),
            ));
        }
        let mut components = Vec::new();
        for (c, m) in cmps.iter().zip(&mults) {
            // A component the model does not carry is dropped from the
            // links (code_aster's creaun, UNILATER_75, info).
            if let Some(idx) =
                Dof::from_name(c).and_then(|d| model.dofs.iter().position(|x| *x == d))
            {
                components.push((idx, function(study, z, "COEF_MULT", m)?));
            }
        }
        if components.is_empty() {
            let names: Vec<&str> = model.dofs.iter().map(|d| d.name()).collect();
            return Err(z
                .error(
                    "NOM_CMP",
                    format!(
                        "none of NOM_CMP ({}) is a displacement component of the model: zone {} keeps no node (UNILATER_48)",
                        cmps.join(", "),
                        k + 1
                    ),
                )
                .choices(cmps.first().copied().unwrap_or(""), &names));
        }
        let impo_name = z.concept("COEF_IMPO").unwrap_or_default();
        let coef_impo = function(study, z, "COEF_IMPO", impo_name)?;
        let coef_pena = match this {
            UnilAlgo::Penalty => {
                let e = z.real("COEF_PENA").ok_or_else(|| {
                    z.error(
                        "COEF_PENA",
                        "COEF_PENA is compulsory with ALGO_CONT='PENALISATION'",
                    )
                })?;
                // Positive: DEFI_CONTACT refuses any other value.
                Some(e)
            }
            UnilAlgo::ActiveSet => None,
        };
        // Nodes carrying none of the components (outside the model) are
        // dropped, as code_aster's elimun does; an empty zone is an error.
        let nodes: Vec<usize> = select_nodes(mesh, z, &[])?
            .into_iter()
            .filter(|&n| in_model[n])
            .collect();
        if nodes.is_empty() {
            return Err(z.error(
                "",
                format!(
                    "zone {} of LIAISON_UNIL keeps no node of the model (UNILATER_48)",
                    k + 1
                ),
            ));
        }
        for &n in &nodes {
            links.push(UnilLink {
                zone: k,
                node: n,
                coords: mesh.coords[n],
            });
        }
        zones.push(UnilZone {
            nodes,
            components,
            coef_impo,
            coef_pena,
        });
    }
    Ok(UnilDef {
        algo: algo.unwrap_or(UnilAlgo::ActiveSet),
        zones,
        links,
    })
}
