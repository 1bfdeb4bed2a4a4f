//! DYNA_NON_LINE: nonlinear transient dynamics.

use indexmap::IndexMap;

use super::blocks::*;
use super::mesh_args::{check_groups, GroupKind};
use super::post_args::{cell_name, node_name};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::{Concept, ConceptData, ConceptType as C, ElemQuantity};
use crate::diag::{closest, Diagnostic};
use crate::law::TangentKind;
use crate::mesh::Mesh;
use crate::model::{Material, MaterialField, MechLoad, Model};
use crate::nonlinear::loads::{largest_load, LoadPeak};
use crate::nonlinear::observation::Observation;
use crate::nonlinear::{
    self, dyna, fields, ArchivePolicy, Assembler, Controls, ConvergenceSettings, Engine,
    NewtonSettings, Occurrence, PrepareError, Reduce, Suivi, SuiviField, TimeLoop,
};
use crate::result::{Access, EvolNoli, RunData};
use crate::study::Study;
use crate::time::explicit::ExplicitScheme;
use crate::time::list::{Action, AdaptEvent, Event, Subdivision, TimeList, TplusMode};
use crate::time::{Predictor, Scheme};

pub fn def() -> CommandDef {
    let spec = command(
        "DYNA_NON_LINE",
        Produces::Concept(C::EvolNoli),
        vec![
            concept("MODELE", &[C::Modele]).required().kw(),
            concept("CHAM_MATER", &[C::ChamMater]).required().kw(),
            text("MASS_DIAG")
                .into(&["OUI", "NON"])
                .doc("lumped mass (explicit schemes only)")
                .kw(),
            fact(
                "EXCIT",
                vec![
                    text("TYPE_CHARGE")
                        .into(&["FIXE_CSTE", "SUIV", "DIDI"])
                        .not_built(&["SUIV", "DIDI"], "loads are dead, FIXE_CSTE, built on the initial geometry")
                        .default(t("FIXE_CSTE"))
                        .doc("dead load, follower load, or differential imposed displacement")
                        .kw(),
                    concept("CHARGE", &[C::CharMeca, C::CharCineMeca]).required().kw(),
                    concept("FONC_MULT", &[C::Fonction, C::Formule])
                        .doc("time multiplier of the load: a function of INST, a constant, or a FORMULE of INST")
                        .kw(),
                ],
            )
            .many()
            .doc("loads and boundary conditions")
            .kw(),
            concept("CONTACT", &[C::CharContact])
                .doc("contact definition from DEFI_CONTACT (with explicit schemes, an aster extension: DISCRETE against a fixed master or, penalised, a deformable one, or LIAISON_UNIL; MASS_DIAG='OUI')")
                .kw(),
            text("AMOR_RAYL_RIGI")
                .into(&["TANGENTE", "ELASTIQUE"])
                .default(t("TANGENTE"))
                .doc("stiffness used in Rayleigh damping")
                .kw(),
            c_comportement(),
            c_etat_init(),
            c_resultat_reuse(),
            c_increment(),
            schema_temps(),
            text("METHODE")
                .into(&["NEWTON", "NEWTON_KRYLOV"])
                .default(t("NEWTON"))
                .kw(),
            c_newton(),
            c_rech_lineaire(),
            c_convergence(),
            c_solveur(),
            c_suivi_ddl(),
            c_observation(),
            c_energie(),
            c_affichage(),
            c_archivage(),
            info(),
            titre(),
        ],
    )
    // code_aster's 'f:ETAT_INIT:EVOL_NOLI': the continued result is the one
    // given as initial state, as in `R = DYNA_NON_LINE(reuse=R, ETAT_INIT=_F(EVOL_NOLI=R), ...)`.
    .reentrant(Reentrant::Optional("ETAT_INIT/EVOL_NOLI"))
    .doc("Computes the nonlinear dynamic evolution of a structure (evol_noli); with reuse= it continues a result.");
    CommandDef { spec, exec }
}

fn schema_temps() -> Keyword {
    let explicit = ["TCHAMWA", "DIFF_CENT"];
    fact(
        "SCHEMA_TEMPS",
        vec![
            text("SCHEMA")
                .required()
                .into(&[
                    "DIFF_CENT",
                    "TCHAMWA",
                    "NEWMARK",
                    "HHT",
                    "THETA_METHODE",
                    "KRENK",
                ])
                .not_built(
                    &["THETA_METHODE", "KRENK"],
                    "aster builds DIFF_CENT, TCHAMWA, NEWMARK and HHT",
                )
                .doc("time integration scheme (DIFF_CENT, TCHAMWA explicit; NEWMARK, HHT implicit)")
                .kw(),
            real("COEF_MASS_SHIFT").default(r(0.0)).kw(),
            block(
                "b_tchamwa",
                eq("SCHEMA", "TCHAMWA"),
                vec![real("PHI").default(r(1.05)).doc("Tchamwa dissipation").kw()],
            )
            .kw(),
            block(
                "b_newmark",
                eq("SCHEMA", "NEWMARK"),
                vec![
                    real("BETA")
                        .default(r(0.25))
                        .doc("Newmark beta (must be > 0)")
                        .kw(),
                    real("GAMMA").default(r(0.5)).doc("Newmark gamma").kw(),
                ],
            )
            .kw(),
            block(
                "b_hht",
                eq("SCHEMA", "HHT"),
                vec![
                    real("ALPHA")
                        .default(r(-0.1))
                        .doc("HHT alpha, usually in [-1/3, 0]: beta = (1-alpha)^2/4, gamma = 1/2 - alpha; -1 refused, outside ]-1, 0] an alarm")
                        .kw(),
                    oui_non("MODI_EQUI", "OUI")
                        .doc("'OUI': true alpha-method (equilibrium weighted between steps); 'NON': only beta, gamma change")
                        .kw(),
                ],
            )
            .kw(),
            block(
                "b_theta",
                eq("SCHEMA", "THETA_METHODE"),
                vec![real("THETA")
                    .default(r(1.0))
                    .min_val(0.5)
                    .max_val(100.0)
                    .kw()],
            )
            .kw(),
            block(
                "b_krenk",
                eq("SCHEMA", "KRENK"),
                vec![real("KAPPA")
                    .default(r(1.0))
                    .min_val(1.0)
                    .max_val(100.0)
                    .kw()],
            )
            .kw(),
            block(
                "b_explicit",
                is_in("SCHEMA", &explicit),
                vec![
                    oui_non("STOP_CFL", "OUI")
                        .doc("stop when a step exceeds the critical (CFL) step")
                        .kw(),
                    text("FORMULATION")
                        .required()
                        .into(&["ACCELERATION"])
                        .doc("primary unknown: acceleration")
                        .kw(),
                ],
            )
            .kw(),
            block(
                "b_implicit",
                not(is_in("SCHEMA", &explicit)),
                vec![text("FORMULATION")
                    .required()
                    .into(&["DEPLACEMENT", "VITESSE", "ACCELERATION"])
                    .doc("primary unknown (VITESSE is forbidden with NEWMARK/HHT)")
                    .kw()],
            )
            .kw(),
        ],
    )
    .required()
    .doc("time integration scheme")
    .kw()
}

// ------------------------------------------------------------------ executor

/// The model, its mesh, the material field and the materials it names.
pub(crate) struct ModelData {
    pub model: Model,
    pub mesh: Mesh,
    pub matfield: MaterialField,
    pub materials: IndexMap<String, Material>,
    /// PESANTEUR as the lumped mass times g: set for an explicit run with
    /// MASS_DIAG='OUI' and for CALC_CHAMP on its result, so that the
    /// load matches the run's inertia (`element::body_force`).
    pub lumped_gravity: bool,
}

impl ModelData {
    /// The nodal forces of one load (PESANTEUR, FORCE_NODALE, PRES_REP),
    /// full dof numbering, before any FONC_MULT.
    pub fn load_forces(&self, load: &MechLoad) -> Result<Vec<f64>, String> {
        crate::element::body_force::load_forces(
            &self.mesh,
            &self.model,
            &self.matfield,
            &self.materials,
            load,
            self.lumped_gravity,
        )
    }
}

/// Fetches MODELE (`model_name`) and CHAM_MATER (`mat_name`) data;
/// `key_model`/`key_mat` are the keywords to blame.
pub(crate) fn model_data(
    study: &Study,
    args: &Args,
    (key_model, model_name): (&str, &str),
    (key_mat, mat_name): (&str, &str),
) -> Result<ModelData, Diagnostic> {
    let no_data = |key: &str, name: &str| {
        args.error(
            key,
            format!("the concept {name} holds no data (its command did not run)"),
        )
    };
    let model = match study.concepts.data(model_name) {
        Some(ConceptData::Model(m)) => (**m).clone(),
        _ => return Err(no_data(key_model, model_name)),
    };
    let mesh = match study.concepts.data(&model.mesh) {
        Some(ConceptData::Mesh(m)) => (**m).clone(),
        _ => return Err(no_data(key_model, &model.mesh)),
    };
    let matfield = match study.concepts.data(mat_name) {
        Some(ConceptData::MaterialField(m)) => (**m).clone(),
        _ => return Err(no_data(key_mat, mat_name)),
    };
    if matfield.mesh != model.mesh {
        return Err(args.error(
            key_mat,
            format!(
                "the CHAM_MATER {mat_name} is on the mesh {}, the model on {}",
                matfield.mesh, model.mesh
            ),
        ));
    }
    let mut materials = IndexMap::new();
    for name in matfield.cell_material.iter().flatten() {
        if materials.contains_key(name) {
            continue;
        }
        match study.concepts.data(name) {
            Some(ConceptData::Material(m)) => {
                materials.insert(name.clone(), (**m).clone());
            }
            _ => return Err(no_data(key_mat, name)),
        }
    }
    Ok(ModelData {
        model,
        mesh,
        matfield,
        materials,
        lumped_gravity: false,
    })
}

/// F_ext of the loads at the first instant into the engine, and, when a
/// load has a FONC_MULT, the history the engine re-evaluates at each
/// step. A FONC_MULT is a function of INST (or a constant) that can be
/// evaluated at every instant of the list; it scales the load's forces
/// (PESANTEUR, FORCE_NODALE) and its DDL_IMPO values (an imposed
/// displacement value × FONC_MULT(t), set at each step's end instant).
pub(crate) fn set_loads(
    args: &Args,
    md: &ModelData,
    loads: &[MechLoad],
    mults: &[Option<String>],
    study: &Study,
    instants: &[f64],
    engine: &mut crate::nonlinear::Engine,
) -> Result<(), Diagnostic> {
    let history = load_history(
        args,
        md,
        loads,
        mults,
        study,
        instants,
        &engine.asm.numbering,
    )?;
    let t0 = instants.first().copied().unwrap_or(0.0);
    history
        .at(t0, &mut engine.fext)
        .map_err(|m| args.error("EXCIT", m))?;
    history
        .set_imposed(t0, &mut engine.asm.numbering.imposed)
        .map_err(|m| args.error("EXCIT", m))?;
    if history.varies() {
        engine.loads = Some(history);
    }
    Ok(())
}

/// The loads of EXCIT on the numbering `nb` as a history the engine
/// evaluates at each instant: each load's forces with its FONC_MULT, the
/// AFFE_CHAR_MECA_F values and the DDL_IMPO values under a FONC_MULT.
pub(crate) fn load_history(
    args: &Args,
    md: &ModelData,
    loads: &[MechLoad],
    mults: &[Option<String>],
    study: &Study,
    instants: &[f64],
    nb: &crate::nonlinear::dofs::DofNumbering,
) -> Result<crate::nonlinear::loads::LoadHistory, Diagnostic> {
    let excits = args.facts("EXCIT");
    let mut parts = Vec::new();
    let mut mult_fns = Vec::new();
    for (k, load) in loads.iter().enumerate() {
        let forces = md.load_forces(load).map_err(|m| args.error("EXCIT", m))?;
        let mult = match (mults.get(k).and_then(|m| m.as_deref()), excits.get(k)) {
            (Some(name), Some(ex)) => Some(fonc_mult(study, ex, name, instants)?),
            _ => None,
        };
        mult_fns.push(mult.clone());
        parts.push((forces, mult));
    }
    let functions =
        function_parts(md, loads, &mult_fns, nb).map_err(|(k, m)| match excits.get(k) {
            Some(ex) => ex.error("CHARGE", m),
            None => args.error("EXCIT", m),
        })?;
    let mut history = crate::nonlinear::loads::LoadHistory::new(parts)
        .with_functions(functions)
        .with_fields(field_parts(md, loads, &mult_fns));
    let varying = imposed_under_mult(args, md, loads, mults, study, instants, nb)?;
    for (entries, mult) in varying {
        history = history.with_imposed(entries, mult);
    }
    Ok(history)
}

/// The AFFE_CHAR_MECA_F distributed loads of `loads`, each with its
/// load's FONC_MULT (`mults`, one per load).
pub(crate) fn field_parts(
    md: &ModelData,
    loads: &[MechLoad],
    mults: &[Option<crate::post::formula::Coef>],
) -> Vec<crate::nonlinear::loads::FieldPart> {
    loads
        .iter()
        .enumerate()
        .flat_map(|(k, load)| {
            load.fields.iter().map(move |f| {
                crate::nonlinear::loads::FieldPart::new(
                    &md.mesh,
                    &md.model,
                    f,
                    mults.get(k).cloned().flatten(),
                )
            })
        })
        .collect()
}

/// The AFFE_CHAR_MECA_F values of the loads on the numbering `nb`, each
/// with its load's FONC_MULT (`mults`, one per load). A dof such a load
/// imposes is imposed by no other load (its value would not be unique in
/// time); the error gives the index of the load to blame.
pub(crate) fn function_parts(
    md: &ModelData,
    loads: &[MechLoad],
    mults: &[Option<crate::post::formula::Coef>],
    nb: &crate::nonlinear::dofs::DofNumbering,
) -> Result<Vec<crate::nonlinear::loads::FunctionPart>, (usize, String)> {
    use crate::model::FunctionTarget;
    let index = nb.imposed_index();
    let full = |node: usize, dof: crate::model::Dof| {
        md.model
            .dofs
            .iter()
            .position(|d| *d == dof)
            .map(|c| node * nb.ndpn + c)
    };
    let mut claims: std::collections::HashMap<usize, usize> = std::collections::HashMap::new();
    for load in loads {
        for imp in &load.imposed {
            if let Some(f) = full(imp.node, imp.dof) {
                *claims.entry(f).or_default() += 1;
            }
        }
    }
    let mut out = Vec::new();
    for (k, load) in loads.iter().enumerate() {
        for nf in &load.functions {
            let imposed = nf.target == FunctionTarget::Imposed;
            let keyword = if imposed { "DDL_IMPO" } else { "FORCE_NODALE" };
            let cmp = if imposed {
                nf.dof.name().to_string()
            } else {
                format!("F{}", &nf.dof.name()[1..])
            };
            let mut entries = Vec::with_capacity(nf.nodes.len());
            for &n in &nf.nodes {
                let Some(f) = full(n, nf.dof) else {
                    return Err((
                        k,
                        format!("{cmp} of {keyword}: the model has no {}", nf.dof.name()),
                    ));
                };
                let i = if imposed {
                    if claims.get(&f).copied().unwrap_or(0) > 1 {
                        return Err((
                            k,
                            format!(
                                "{} of node N{} is imposed by the function {} of this load (AFFE_CHAR_MECA_F) and by another DDL_IMPO: one value per dof and instant",
                                nf.dof.name(),
                                n + 1,
                                nf.name
                            ),
                        ));
                    }
                    match index.get(&f) {
                        Some(&i) => i,
                        None => continue,
                    }
                } else {
                    f
                };
                entries.push((i, n, md.mesh.coords[n]));
            }
            out.push(crate::nonlinear::loads::FunctionPart {
                label: format!("{keyword} {cmp} = {}", nf.name),
                coef: nf.coef.clone(),
                mult: mults.get(k).cloned().flatten(),
                imposed,
                entries,
            });
        }
    }
    Ok(out)
}

/// (index in the numbering's imposed list, value at multiplier 1) of a
/// load's moving dofs, and its multiplier.
type ImposedUnderMult = (Vec<(usize, f64)>, crate::post::formula::Coef);

/// The non-zero DDL_IMPO values of the loads with a FONC_MULT, as
/// (index in the numbering's imposed list, value) per load with its
/// multiplier. A dof imposed both by such a load and by a load without
/// multiplier has no single value in time: refused, naming the EXCIT.
fn imposed_under_mult(
    args: &Args,
    md: &ModelData,
    loads: &[MechLoad],
    mults: &[Option<String>],
    study: &Study,
    instants: &[f64],
    nb: &crate::nonlinear::dofs::DofNumbering,
) -> Result<Vec<ImposedUnderMult>, Diagnostic> {
    let index = nb.imposed_index();
    let full = |imp: &crate::model::ImposedDof| {
        md.model
            .dofs
            .iter()
            .position(|d| *d == imp.dof)
            .map(|c| imp.node * nb.ndpn + c)
            .and_then(|f| index.get(&f).copied())
    };
    let excits = args.facts("EXCIT");
    let mut fixed = std::collections::HashSet::new();
    for (k, load) in loads.iter().enumerate() {
        if mults.get(k).and_then(|m| m.as_deref()).is_none() {
            fixed.extend(load.imposed.iter().filter_map(full));
        }
    }
    let mut out = Vec::new();
    for (k, load) in loads.iter().enumerate() {
        let (Some(name), Some(ex)) = (mults.get(k).and_then(|m| m.as_deref()), excits.get(k))
        else {
            continue;
        };
        let mut entries = Vec::new();
        for imp in load.imposed.iter().filter(|d| d.value != 0.0) {
            let Some(i) = full(imp) else { continue };
            if fixed.contains(&i) {
                return Err(ex.error(
                    "FONC_MULT",
                    format!(
                        "{} of node N{} is imposed by this load, whose FONC_MULT makes it vary in time, and by a load without FONC_MULT: one value per dof and instant",
                        imp.dof.name(),
                        imp.node + 1
                    ),
                ));
            }
            entries.push((i, imp.value));
        }
        if !entries.is_empty() {
            out.push((entries, fonc_mult(study, ex, name, instants)?));
        }
    }
    Ok(out)
}

/// The largest values of each EXCIT load (DDL_IMPO, FORCE_NODALE, the
/// other dead loads' nodal forces), for the message of a solve whose
/// right-hand side or solution left the range of doubles: such a failure
/// is no singular matrix, and the user must be told which load is too
/// large (a value of 1e308, a unit slip), not to add supports.
pub(crate) fn load_peaks(
    study: &Study,
    md: &ModelData,
    loads: &[MechLoad],
    names: &[String],
    mults: &[Option<String>],
) -> Vec<LoadPeak> {
    let ndpn = md.model.ndof_per_node();
    let mut out = Vec::new();
    for (k, load) in loads.iter().enumerate() {
        let mult = mults
            .get(k)
            .and_then(|m| m.as_deref())
            .and_then(|name| Some((name.to_string(), multiplier(study, name).ok()?)));
        let name = names.get(k).map_or("?", String::as_str);
        let mut push = |what: String, value: f64| {
            out.push(LoadPeak {
                what: format!("{what} of load {name} (EXCIT {})", k + 1),
                value,
                mult: mult.clone(),
            })
        };
        if let Some(imp) = load
            .imposed
            .iter()
            .rev()
            .max_by(|a, b| a.value.abs().total_cmp(&b.value.abs()))
        {
            push(
                format!("DDL_IMPO {} at node N{}", imp.dof.name(), imp.node + 1),
                imp.value,
            );
        }
        if let Some(&(node, dof, f)) = load
            .nodal_forces
            .iter()
            .rev()
            .max_by(|a, b| a.2.abs().total_cmp(&b.2.abs()))
        {
            push(
                format!("FORCE_NODALE F{} at node N{}", &dof.name()[1..], node + 1),
                f,
            );
        }
        if load.gravity.is_some() || !load.pressures.is_empty() || !load.distributed.is_empty() {
            let Ok(forces) = md.load_forces(&MechLoad {
                nodal_forces: Vec::new(),
                ..load.clone()
            }) else {
                continue;
            };
            if let Some((f, v)) = forces
                .iter()
                .enumerate()
                .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
            {
                push(
                    format!(
                        "the nodal force F{} at node N{} of its PESANTEUR, PRES_REP or FORCE_*",
                        ["X", "Y", "Z"].get(f % ndpn).unwrap_or(&"?"),
                        f / ndpn + 1
                    ),
                    *v,
                );
            }
        }
    }
    out
}

/// The FONC_MULT `name` of one EXCIT occurrence, checked at every
/// instant of the time list.
fn fonc_mult(
    study: &Study,
    ex: &Args,
    name: &str,
    instants: &[f64],
) -> Result<crate::post::formula::Coef, Diagnostic> {
    let f = multiplier(study, name).map_err(|m| ex.error("FONC_MULT", m))?;
    for &t in instants {
        f.eval(t).map_err(|e| {
            ex.error(
                "FONC_MULT",
                format!(
                    "{name} cannot be evaluated at INST = {t:e}, an instant of the time list: {e}"
                ),
            )
        })?;
    }
    Ok(f)
}

/// The time multiplier held by the concept `name`: a function of INST or
/// a constant (DEFI_FONCTION, DEFI_CONSTANTE...) or a FORMULE of INST
/// alone, as code_aster's EXCIT/FONC_MULT takes (fonction_sdaster,
/// formule).
pub(crate) fn multiplier(study: &Study, name: &str) -> Result<crate::post::formula::Coef, String> {
    use crate::post::formula::Coef;
    let f = match study.concepts.data(name) {
        Some(ConceptData::Function(f)) => Coef::Function((**f).clone()),
        Some(ConceptData::Formula(g)) => Coef::Formula((**g).clone()),
        _ => {
            return Err(format!(
                "{name} holds no function (its command did not run)"
            ))
        }
    };
    match f.unknown_param(&["INST"]) {
        Some(p) => Err(format!(
            "FONC_MULT multiplies the load by a function of time: {name} is a {} of {p}, not of INST alone",
            f.type_name()
        )),
        None => Ok(f),
    }
}

/// The mechanical loads named in `names`.
pub(crate) fn loads_of(
    study: &Study,
    args: &Args,
    key: &str,
    names: &[String],
) -> Result<Vec<MechLoad>, Diagnostic> {
    names
        .iter()
        .map(|n| match study.concepts.data(n) {
            Some(ConceptData::MechLoad(l)) => Ok((**l).clone()),
            _ => Err(args.error(key, format!("the load {n} holds no data"))),
        })
        .collect()
}

/// The cells of a location: GROUP_MA's then MAILLE's (by name), or None
/// for TOUT / nothing given.
fn location_cells(mesh: &Mesh, occ: &Args) -> Result<Option<Vec<usize>>, Diagnostic> {
    if !occ.has("GROUP_MA") && !occ.has("MAILLE") {
        return Ok(None);
    }
    let mut cells = Vec::new();
    if occ.has("GROUP_MA") {
        check_groups(mesh, occ, "GROUP_MA", GroupKind::Cells)?;
        for g in occ.texts("GROUP_MA") {
            cells.extend(mesh.cell_groups[g].iter().copied());
        }
    }
    for m in occ.texts("MAILLE") {
        cells.push(super::post_args::cell_by_name(mesh, occ, "MAILLE", m)?);
    }
    Ok(Some(cells))
}

/// The COMPORTEMENT occurrences resolved to cells.
pub(crate) fn occurrences(mesh: &Mesh, args: &Args) -> Result<Vec<Occurrence>, Diagnostic> {
    args.facts("COMPORTEMENT")
        .iter()
        .map(|o| {
            Ok(Occurrence {
                cells: location_cells(mesh, o)?,
                relation: o.text("RELATION").unwrap_or("ELAS").to_string(),
                deformation: o.text("DEFORMATION").unwrap_or("PETIT").to_string(),
                controls: Controls {
                    algo_inte: o.text("ALGO_INTE").map(str::to_string),
                    iter_inte_maxi: o.int("ITER_INTE_MAXI"),
                    resi_inte_rela: o.real("RESI_INTE_RELA"),
                },
            })
        })
        .collect()
}

/// (RELATION, DEFORMATION) of each element cell, later occurrence wins,
/// ELAS/PETIT elsewhere: what the result keeps for CALC_CHAMP.
pub(crate) fn cell_comportement(
    model: &Model,
    occs: &[Occurrence],
) -> Vec<Option<(String, String)>> {
    let mut out: Vec<Option<(String, String)>> = model
        .cells
        .iter()
        .map(|r| {
            matches!(r, crate::model::CellRole::Element(_))
                .then(|| ("ELAS".to_string(), "PETIT".to_string()))
        })
        .collect();
    for o in occs {
        let cells: Vec<usize> = match &o.cells {
            Some(c) => c.clone(),
            None => (0..out.len()).collect(),
        };
        for c in cells {
            if let Some(slot) = out.get_mut(c) {
                if slot.is_some() {
                    *slot = Some((o.relation.clone(), o.deformation.clone()));
                }
            }
        }
    }
    out
}

/// A discretization error as a diagnostic on the keyword at fault.
pub(crate) fn prepare_error(args: &Args, e: PrepareError) -> Diagnostic {
    match e {
        PrepareError::Behaviour(b) => {
            let level = b
                .occurrence
                .and_then(|k| args.facts("COMPORTEMENT").get(k))
                .unwrap_or(args);
            if b.not_implemented {
                let message = match b.message.strip_prefix("not implemented yet: ") {
                    Some(what) => format!("not implemented yet: {}/{what}", args.command),
                    None => b.message,
                };
                // Named in the message, as Args::not_implemented does.
                Diagnostic::error(message).at(level.span_of(b.keyword))
            } else {
                level.error(b.keyword, b.message)
            }
        }
        PrepareError::Load(m) => args.error("EXCIT", m),
        PrepareError::Mesh(m) => args.error("MODELE", m),
        PrepareError::Material(m) => args.error("CHAM_MATER", m),
    }
}

/// Rayleigh damping from the ELAS AMOR_ALPHA and AMOR_BETA of the
/// materials (semantics.md §4.1: their presence switches it on in
/// DYNA_NON_LINE). What aster cannot do yet is refused, never dropped: a
/// study whose damping was ignored would run and be wrong.
fn rayleigh_of(
    args: &Args,
    md: &ModelData,
) -> Result<Option<nonlinear::damping::Rayleigh>, Diagnostic> {
    let pairs: Vec<(&str, f64, f64)> = md
        .materials
        .iter()
        .map(|(n, m)| {
            (
                n.as_str(),
                m.get("ELAS", "AMOR_ALPHA").unwrap_or(0.0),
                m.get("ELAS", "AMOR_BETA").unwrap_or(0.0),
            )
        })
        .collect();
    let Some(&(n0, a0, b0)) = pairs.iter().find(|p| p.1 != 0.0 || p.2 != 0.0) else {
        return Ok(None);
    };
    if let Some(&(n, a, b)) = pairs.iter().find(|p| (p.1, p.2) != (a0, b0)) {
        return Err(args.not_implemented(
            "CHAM_MATER",
            &format!(
                "Rayleigh damping with different coefficients on different materials ({n0}: AMOR_ALPHA={a0}, AMOR_BETA={b0}; {n}: AMOR_ALPHA={a}, AMOR_BETA={b}): one pair for the whole model"
            ),
        ));
    }
    let kind = if args.text("AMOR_RAYL_RIGI") == Some("ELASTIQUE") {
        crate::law::TangentKind::Elastic
    } else {
        crate::law::TangentKind::Consistent
    };
    Ok(Some(nonlinear::damping::Rayleigh {
        stiffness: a0,
        mass: b0,
        kind,
    }))
}

/// The scheme of SCHEMA_TEMPS: implicit (Newmark family) or explicit.
enum SchemeChoice {
    Implicit(Scheme),
    Explicit(ExplicitScheme),
}

fn scheme_of(args: &Args) -> Result<SchemeChoice, Diagnostic> {
    let st = args
        .fact("SCHEMA_TEMPS")
        .ok_or_else(|| args.error("SCHEMA_TEMPS", "SCHEMA_TEMPS is compulsory"))?;
    let schema = st.text("SCHEMA").unwrap_or("");
    let formulation = st.text("FORMULATION").unwrap_or("");
    match schema {
        "DIFF_CENT" | "TCHAMWA" => {
            if formulation != "ACCELERATION" {
                return Err(st.error(
                    "FORMULATION",
                    format!("SCHEMA='{schema}' needs FORMULATION='ACCELERATION' (MECANONLINE5_10)"),
                ));
            }
            return Ok(SchemeChoice::Explicit(if schema == "DIFF_CENT" {
                ExplicitScheme::DiffCent
            } else {
                ExplicitScheme::Tchamwa {
                    phi: st.real("PHI").unwrap_or(1.05),
                }
            }));
        }
        _ => {}
    }
    let scheme = match schema {
        "NEWMARK" => Scheme::newmark(
            st.real("BETA").unwrap_or(0.25),
            st.real("GAMMA").unwrap_or(0.5),
        ),
        "HHT" => Scheme::hht(
            st.real("ALPHA").unwrap_or(-0.1),
            st.text("MODI_EQUI").unwrap_or("OUI") == "OUI",
        ),
        other => {
            return Err(st.not_implemented(
                "SCHEMA",
                &format!("SCHEMA='{other}'; NEWMARK, HHT, DIFF_CENT and TCHAMWA are implemented"),
            ))
        }
    }
    .map_err(|m| st.error("SCHEMA", m))?;
    match formulation {
        "DEPLACEMENT" => Ok(SchemeChoice::Implicit(scheme)),
        "ACCELERATION" => Ok(SchemeChoice::Implicit(Scheme {
            predictor: Predictor::Acceleration,
            ..scheme
        })),
        "VITESSE" => Err(st.error(
            "FORMULATION",
            format!("FORMULATION='VITESSE' is forbidden with SCHEMA='{schema}' (as in code_aster)"),
        )),
        other => Err(st.not_implemented(
            "FORMULATION",
            &format!("FORMULATION='{other}'; 'DEPLACEMENT' and 'ACCELERATION' are implemented"),
        )),
    }
}

/// NEWTON; REAC_ITER defaults to 1 in DYNA_NON_LINE (this project's
/// choice since its first version) and to 0 in STAT_NON_LINE (code_aster).
fn newton_of(args: &Args, inertia: bool) -> Result<NewtonSettings, Diagnostic> {
    let mut n = NewtonSettings {
        reac_iter: usize::from(inertia),
        ..NewtonSettings::default()
    };
    if let Some(o) = args.fact("NEWTON") {
        n.matrix = match o.text("MATRICE").unwrap_or("TANGENTE") {
            "ELASTIQUE" => TangentKind::Elastic,
            _ => TangentKind::Consistent,
        };
        n.prediction = match o.text("PREDICTION") {
            None => n.matrix,
            Some("TANGENTE") => TangentKind::Consistent,
            Some("ELASTIQUE") => TangentKind::Elastic,
            Some(other) => {
                return Err(o.not_implemented(
                    "PREDICTION",
                    &format!("PREDICTION='{other}' (TANGENTE and ELASTIQUE are computed)"),
                ))
            }
        };
        n.reac_incr = o.int("REAC_INCR").unwrap_or(1).max(0) as usize;
        n.reac_iter = o.int("REAC_ITER").unwrap_or(i64::from(inertia)).max(0) as usize;
        n.symmetrize = o.text("MATR_RIGI_SYME") == Some("OUI");
        if o.given("PAS_MINI_ELAS") {
            return Err(o.not_implemented("PAS_MINI_ELAS", ""));
        }
    }
    Ok(n)
}

fn convergence_of(
    args: &Args,
    log: &mut Vec<String>,
    inertia: bool,
) -> Result<ConvergenceSettings, Diagnostic> {
    let mut c = ConvergenceSettings::default();
    if let Some(o) = args.fact("CONVERGENCE") {
        if o.given("RESI_COMP_RELA") && !inertia {
            return Err(o.not_implemented("RESI_COMP_RELA", ""));
        }
        if o.given("RESI_COMP_RELA") {
            return Err(o.error(
                "RESI_COMP_RELA",
                "RESI_COMP_RELA is forbidden in dynamics (as in code_aster)",
            ));
        }
        if o.given("RESI_REFE_RELA") {
            return Err(o.not_implemented("RESI_REFE_RELA", ""));
        }
        let (rela, maxi) = (o.real("RESI_GLOB_RELA"), o.real("RESI_GLOB_MAXI"));
        c.resi_glob_maxi = maxi;
        c.resi_glob_rela = match (rela, maxi) {
            (None, None) => Some(1e-6),
            (r, _) => r,
        };
        if c.resi_glob_rela.is_some_and(|r| r > 1e-4) {
            log.push(format!(
                "alarm: RESI_GLOB_RELA = {:e} > 1e-4 is a loose criterion",
                c.resi_glob_rela.unwrap_or(0.0)
            ));
        }
        // code_aster's nmcvgn stops at row `iterat` when iterat + 1 >=
        // ITER_GLOB_MAXI, so 0 stops at row 0, the prediction, as 1 does
        // (its sdld32a gives 0 for a linear oscillator); the catalogue
        // refuses negative values.
        let it = o.int("ITER_GLOB_MAXI").unwrap_or(10).max(1);
        c.iter_glob_maxi = it as usize;
        c.arret = o.text("ARRET").unwrap_or("OUI") == "OUI";
    }
    Ok(c)
}

pub(crate) fn archive_of(study: &Study, args: &Args) -> Result<ArchivePolicy, Diagnostic> {
    let Some(o) = args.fact("ARCHIVAGE") else {
        return Ok(ArchivePolicy::Every(1));
    };
    instants_of(study, o, "PAS_ARCH")
}

/// The fields aster's time loops archive, which ARCHIVAGE/CHAM_EXCLU may
/// leave out.
const ARCHIVED_FIELDS: &[&str] = &[
    "DEPL",
    "VITE",
    "ACCE",
    "SIEF_ELGA",
    "VARI_ELGA",
    "CONT_NOEU",
];

/// Fields code_aster's DYNA_NON_LINE and STAT_NON_LINE archive and aster
/// does not: excluding them changes nothing.
const UNARCHIVED_FIELDS: &[&str] = &[
    "COMPORTEMENT",
    "STRX_ELGA",
    "EPSI_ELGA",
    "FORC_AMOR",
    "FORC_LIAI",
    "CONT_ELEM",
    "MODE_FLAMB",
    "MODE_STAB",
    "DEPL_VIBR",
    "DEPL_ABSOLU",
    "VITE_ABSOLU",
    "ACCE_ABSOLU",
];

/// ARCHIVAGE/CHAM_EXCLU: the fields to leave out of every archived
/// instant of the call but the last one. A name that is no field the
/// command archives is an error (code_aster ignores it silently, so a
/// misspelt name would exclude nothing).
pub(crate) fn cham_exclu_of(args: &Args) -> Result<Vec<String>, Diagnostic> {
    let Some(o) = args.fact("ARCHIVAGE") else {
        return Ok(Vec::new());
    };
    let mut out: Vec<String> = Vec::new();
    for name in o.texts("CHAM_EXCLU") {
        if !ARCHIVED_FIELDS.contains(&name) && !UNARCHIVED_FIELDS.contains(&name) {
            let all: Vec<&str> = ARCHIVED_FIELDS
                .iter()
                .chain(UNARCHIVED_FIELDS)
                .copied()
                .collect();
            let mut d = o.error(
                "CHAM_EXCLU",
                format!(
                    "{name} is not a field this command archives (it archives {}; code_aster's {} are not archived by aster and may be named too)",
                    ARCHIVED_FIELDS.join(", "),
                    UNARCHIVED_FIELDS.join(", ")
                ),
            );
            d.suggestion = closest(name, &all);
            return Err(d);
        }
        if out.iter().any(|x| x == name) {
            return Err(o.error("CHAM_EXCLU", format!("{name} is given twice in CHAM_EXCLU")));
        }
        out.push(name.to_string());
    }
    Ok(out)
}

/// Which computed steps an occurrence selects (ARCHIVAGE, OBSERVATION):
/// every `step_key` steps, the instants of LIST_INST or INST within
/// CRITERE/PRECISION, or every step.
fn instants_of(study: &Study, o: &Args, step_key: &str) -> Result<ArchivePolicy, Diagnostic> {
    let relative = o.text("CRITERE").unwrap_or("RELATIF") == "RELATIF";
    let precision = o.real("PRECISION").unwrap_or(1e-6);
    if let Some(p) = o.int(step_key) {
        if p < 1 {
            return Err(o.error(step_key, format!("{step_key} must be >= 1")));
        }
        return Ok(ArchivePolicy::Every(p as usize));
    }
    let instants = if let Some(l) = o.concept("LIST_INST") {
        match study.concepts.data(l) {
            Some(ConceptData::ListReal(v)) => v.clone(),
            Some(ConceptData::TimeList(t)) => t.instants.clone(),
            _ => return Err(o.error("LIST_INST", format!("the list {l} holds no data"))),
        }
    } else if o.has("INST") {
        o.reals("INST")
    } else {
        return Ok(ArchivePolicy::Every(1));
    };
    Ok(ArchivePolicy::Instants {
        instants,
        precision,
        relative,
    })
}

pub(crate) fn suivi_of(
    mesh: &Mesh,
    model: &Model,
    args: &Args,
    inertia: bool,
) -> Result<Vec<Suivi>, Diagnostic> {
    let mut out = Vec::new();
    for o in args.facts("SUIVI_DDL") {
        out.extend(
            monitored(mesh, model, o, inertia)?
                .into_iter()
                .map(|(_, s)| s),
        );
    }
    Ok(out)
}

/// The OBSERVATION occurrences: SUIVI_DDL's selection, with the
/// instants, the initial state and a title.
pub(crate) fn observations_of(
    study: &Study,
    mesh: &Mesh,
    model: &Model,
    args: &Args,
    inertia: bool,
) -> Result<Vec<Observation>, Diagnostic> {
    let mut out = Vec::new();
    for (k, o) in args.facts("OBSERVATION").iter().enumerate() {
        let columns = monitored(mesh, model, o, inertia)?;
        let nodal = columns.first().is_some_and(|(_, s)| {
            matches!(
                s.field,
                SuiviField::Depl | SuiviField::Vite | SuiviField::Acce | SuiviField::ForcNoda
            )
        });
        let entity_names = columns
            .first()
            .map(|(_, s)| {
                s.entities
                    .iter()
                    .map(|&e| if nodal { node_name(e) } else { cell_name(e) })
                    .collect()
            })
            .unwrap_or_default();
        out.push(Observation {
            title: o
                .texts("TITRE")
                .first()
                .map_or(format!("OBSERVATION_{}", k + 1), |t| t.to_string()),
            field_name: o.text("NOM_CHAM").unwrap_or("").to_string(),
            eval_name: o.text("EVAL_CHAM").unwrap_or("VALE").to_string(),
            eval_elga_name: o.text("EVAL_ELGA").unwrap_or("VALE").to_string(),
            columns,
            entity_names,
            when: instants_of(study, o, "PAS_OBSE")?,
            initial: o.text("OBSE_ETAT_INIT").unwrap_or("OUI") == "OUI",
        });
    }
    Ok(out)
}

/// One SUIVI_DDL or OBSERVATION occurrence: a column per NOM_CMP, with
/// its component name.
fn monitored(
    mesh: &Mesh,
    model: &Model,
    o: &Args,
    inertia: bool,
) -> Result<Vec<(String, Suivi)>, Diagnostic> {
    let mut out = Vec::new();
    let name = o.text("NOM_CHAM").unwrap_or("");
    if !inertia && matches!(name, "VITE" | "ACCE") {
        return Err(o.error(
            "NOM_CHAM",
            format!("NOM_CHAM='{name}': STAT_NON_LINE computes no {name} (no inertia); follow DEPL, FORC_NODA, SIEF_ELGA or VARI_ELGA"),
        ));
    }
    let field = match name {
        "DEPL" => SuiviField::Depl,
        "VITE" => SuiviField::Vite,
        "ACCE" => SuiviField::Acce,
        "FORC_NODA" => SuiviField::ForcNoda,
        "SIEF_ELGA" => SuiviField::SiefElga,
        "VARI_ELGA" => SuiviField::VariElga,
        other => return Err(o.not_implemented("NOM_CHAM", &format!("NOM_CHAM='{other}'"))),
    };
    let nodal = matches!(
        field,
        SuiviField::Depl | SuiviField::Vite | SuiviField::Acce | SuiviField::ForcNoda
    );
    let entities: Vec<usize> = if nodal {
        if o.has("GROUP_NO") || o.has("NOEUD") {
            check_groups(mesh, o, "GROUP_NO", GroupKind::Nodes)?;
            let mut nodes: Vec<usize> = o
                .texts("GROUP_NO")
                .iter()
                .flat_map(|g| mesh.node_groups[*g].iter().copied())
                .collect();
            for n in o.texts("NOEUD") {
                nodes.push(super::post_args::node_by_name(mesh, o, "NOEUD", n)?);
            }
            nodes
        } else if let Some(cells) = location_cells(mesh, o)? {
            mesh.nodes_of_cells(&cells)
        } else {
            let cells: Vec<usize> = model.element_cells().map(|(c, _)| c).collect();
            mesh.nodes_of_cells(&cells)
        }
    } else {
        match location_cells(mesh, o)? {
            Some(c) => c,
            None => model.element_cells().map(|(c, _)| c).collect(),
        }
    };
    let eval = Reduce::from_name(o.text("EVAL_CHAM").unwrap_or("VALE")).unwrap_or(Reduce::Vale);
    let eval_elga =
        Reduce::from_name(o.text("EVAL_ELGA").unwrap_or("VALE")).unwrap_or(Reduce::Vale);
    let points: Vec<usize> = o.ints("POINT").iter().map(|&p| p.max(0) as usize).collect();
    for cmp in o.texts("NOM_CMP") {
        let component = match field {
            SuiviField::SiefElga => ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"]
                .iter()
                .position(|c| *c == cmp),
            SuiviField::VariElga => cmp
                .strip_prefix('V')
                .and_then(|k| k.parse::<usize>().ok())
                .filter(|k| *k >= 1)
                .map(|k| k - 1),
            _ => model.dofs.iter().position(|d| d.name() == cmp),
        }
        .ok_or_else(|| {
            o.error(
                "NOM_CMP",
                format!("the field {name} has no component '{cmp}' here"),
            )
        })?;
        out.push((
            cmp.to_string(),
            Suivi {
                label: format!("{name} {cmp}"),
                field,
                component,
                entities: entities.clone(),
                eval,
                eval_elga,
                points: points.clone(),
            },
        ));
    }
    Ok(out)
}

/// An ECHEC rule EVENEMENT='DELTA_GRANDEUR' made checkable: NOM_CHAM one
/// of DEPL, SIEF_ELGA, VARI_ELGA (the catalogue's choices) and NOM_CMP a
/// component of it in this model.
fn delta_grandeur(
    args: &Args,
    (model, vari): (&Model, usize),
    nom_cham: &str,
    nom_cmp: &str,
    vale_ref: f64,
    action: &Action,
) -> Result<dyna::DeltaGrandeur, Diagnostic> {
    delta_measure(
        args,
        (model, vari),
        (nom_cham, nom_cmp, vale_ref),
        action,
        "ECHEC EVENEMENT='DELTA_GRANDEUR'",
    )
}

/// A component of DEPL, SIEF_ELGA or VARI_ELGA whose largest increment
/// over a step is compared with VALE_REF, checked on the model (`vari`:
/// the largest number of internal variables of its behaviours); `what`
/// names the keyword in the messages.
fn delta_measure(
    args: &Args,
    (model, vari): (&Model, usize),
    (nom_cham, nom_cmp, vale_ref): (&str, &str, f64),
    action: &Action,
    what: &str,
) -> Result<dyna::DeltaGrandeur, Diagnostic> {
    let bad = |m: String| args.error("INCREMENT", format!("LIST_INST, {what}: {m}"));
    let (field, component) = match nom_cham {
        "DEPL" => (
            SuiviField::Depl,
            model.dofs.iter().position(|d| d.name() == nom_cmp),
        ),
        "SIEF_ELGA" => (
            SuiviField::SiefElga,
            ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"]
                .iter()
                .position(|c| *c == nom_cmp),
        ),
        "VARI_ELGA" => (
            SuiviField::VariElga,
            nom_cmp
                .strip_prefix('V')
                .and_then(|k| k.parse::<usize>().ok())
                .filter(|k| *k >= 1)
                .map(|k| k - 1),
        ),
        other => {
            return Err(bad(format!(
                "NOM_CHAM='{other}' is not one of DEPL, SIEF_ELGA, VARI_ELGA"
            )))
        }
    };
    let component = component.ok_or_else(|| {
        bad(format!(
            "the field {nom_cham} has no component '{nom_cmp}' in this model"
        ))
    })?;
    // An internal variable no behaviour has would never change: the rule
    // would never act, silently.
    if field == SuiviField::VariElga && component >= vari {
        return Err(bad(if vari == 0 {
            format!("VARI_ELGA '{nom_cmp}': no behaviour of the model has internal variables")
        } else {
            format!("VARI_ELGA '{nom_cmp}': the behaviours of the model have at most {vari} internal variable(s) (V1 to V{vari})")
        }));
    }
    if !(vale_ref.is_finite() && vale_ref > 0.0) {
        return Err(bad(format!(
            "VALE_REF = {vale_ref} must be a positive number"
        )));
    }
    Ok(dyna::DeltaGrandeur {
        label: format!("{nom_cham} {nom_cmp}"),
        field,
        component,
        vale_ref,
        action: action.clone(),
    })
}

/// METHODE='AUTO' of a time list: PAS_MINI, PAS_MAXI and NB_PAS_MAXI, and
/// for the explicit loop the growth factor of the step (1 + PCENT_AUGM/100
/// of the first ADAPTATION with MODE_CALCUL_TPLUS 'FIXE', 100 % by
/// default; 1 when every occurrence is EVENEMENT='AUCUN'); None for
/// METHODE='MANUEL'. The implicit loop applies the occurrences themselves
/// (`adaptation_of`).
pub(crate) fn growth_of(list: &TimeList) -> Option<dyna::Growth> {
    list.auto.then(|| {
        let adapting: Vec<_> = list
            .adaptation
            .iter()
            .filter(|a| a.event != AdaptEvent::Aucun)
            .collect();
        let pcent = if !list.adaptation.is_empty() && adapting.is_empty() {
            0.0
        } else {
            adapting
                .iter()
                .find_map(|a| match a.mode {
                    TplusMode::Fixe { pcent_augm } => Some(pcent_augm),
                    _ => None,
                })
                .unwrap_or(100.0)
        };
        dyna::Growth {
            factor: 1.0 + pcent / 100.0,
            pas_mini: list.pas_mini,
            pas_maxi: list.pas_maxi,
            max_steps: list.nb_pas_maxi,
        }
    })
}

/// One ADAPTATION occurrence in words, for the .mess.
fn describe_adaptation(a: &dyna::StepAdaptation) -> String {
    let when = match &a.trigger {
        dyna::AdaptTrigger::Never => return "EVENEMENT='AUCUN': never".into(),
        dyna::AdaptTrigger::Always => "after every step".to_string(),
        dyna::AdaptTrigger::Threshold {
            count,
            crit,
            or_equal,
            vale,
        } => format!(
            "each time {count} Newton convergences at an iteration {}{} {vale} have been counted (SEUIL)",
            if *crit == std::cmp::Ordering::Less { "<" } else { ">" },
            if *or_equal { "=" } else { "" }
        ),
    };
    let how = match &a.rule {
        dyna::StepRule::Fixe(f) => format!("{f} times the last step (FIXE)"),
        dyna::StepRule::IterNewton(n) => {
            format!("the last step times sqrt({n} / (iteration + 1)) (ITER_NEWTON)")
        }
        dyna::StepRule::DeltaGrandeur(d) => format!(
            "the last step times {:e} / the largest increment of {} over it (DELTA_GRANDEUR)",
            d.vale_ref, d.label
        ),
    };
    format!("{how}, {when}")
}

/// The ADAPTATION occurrences of a METHODE='AUTO' list as the implicit
/// loop applies them (code_aster's `nmadat`, `diadap`, `nmcadt`): a list
/// without one has the catalogue's default occurrence (SEUIL, FIXE 100 %);
/// VALE_I absent or 0 is ITER_GLOB_MAXI/2 (`nmcrsu`). IMPLEX needs
/// STAT_NON_LINE's METHODE='IMPLEX' (MECANONLINE6_4), which aster lacks.
fn adaptation_of(
    args: &Args,
    model: (&Model, usize),
    list: &TimeList,
    iter_glob_maxi: usize,
) -> Result<Vec<dyna::StepAdaptation>, Diagnostic> {
    let default = [crate::time::list::Adaptation {
        event: AdaptEvent::Seuil {
            nb_incr_seuil: 2,
            nom_para: "NB_ITER_NEWTON".into(),
            crit_comp: "LE".into(),
            vale_i: None,
        },
        mode: TplusMode::Fixe { pcent_augm: 100.0 },
    }];
    let occurrences = if list.adaptation.is_empty() {
        &default[..]
    } else {
        &list.adaptation[..]
    };
    let mut out = Vec::new();
    for a in occurrences {
        let trigger = match &a.event {
            AdaptEvent::Aucun => dyna::AdaptTrigger::Never,
            AdaptEvent::ToutInst => dyna::AdaptTrigger::Always,
            AdaptEvent::Seuil {
                nb_incr_seuil,
                crit_comp,
                vale_i,
                ..
            } => {
                use std::cmp::Ordering::{Greater, Less};
                let (crit, or_equal) = match crit_comp.as_str() {
                    "LT" => (Less, false),
                    "GT" => (Greater, false),
                    "GE" => (Greater, true),
                    _ => (Less, true),
                };
                let vale = match vale_i {
                    Some(v) if *v != 0 => (*v).max(0) as usize,
                    _ => iter_glob_maxi / 2,
                };
                dyna::AdaptTrigger::Threshold {
                    count: *nb_incr_seuil,
                    crit,
                    or_equal,
                    vale,
                }
            }
        };
        let rule = match &a.mode {
            TplusMode::Fixe { pcent_augm } => dyna::StepRule::Fixe(1.0 + pcent_augm / 100.0),
            TplusMode::IterNewton { nb_iter_newton_ref } => {
                if *nb_iter_newton_ref < 1 {
                    return Err(args.error(
                        "INCREMENT",
                        format!("LIST_INST, ADAPTATION: NB_ITER_NEWTON_REF = {nb_iter_newton_ref} must be at least 1"),
                    ));
                }
                dyna::StepRule::IterNewton(*nb_iter_newton_ref as usize)
            }
            TplusMode::DeltaGrandeur {
                vale_ref,
                nom_cham,
                nom_cmp,
            } => dyna::StepRule::DeltaGrandeur(delta_measure(
                args,
                model,
                (nom_cham, nom_cmp, *vale_ref),
                &Action::Arret,
                "ADAPTATION MODE_CALCUL_TPLUS='DELTA_GRANDEUR'",
            )?),
            TplusMode::Implex => {
                return Err(args.not_implemented(
                    "INCREMENT",
                    "DEFI_LIST_INST/ADAPTATION/MODE_CALCUL_TPLUS='IMPLEX' (code_aster allows it only with STAT_NON_LINE METHODE='IMPLEX', MECANONLINE6_4, which aster does not have)",
                ));
            }
        };
        out.push(dyna::StepAdaptation { trigger, rule });
    }
    Ok(out)
}

/// The time list and the instants [INST_INIT .. INST_FIN] to compute;
/// `t_etat` is the initial instant of an EVOL_NOLI initial state.
pub(crate) fn time_range(
    study: &Study,
    args: &Args,
    t_etat: Option<f64>,
) -> Result<(TimeList, Vec<f64>), Diagnostic> {
    let inc = args
        .fact("INCREMENT")
        .ok_or_else(|| args.error("INCREMENT", "INCREMENT is compulsory"))?;
    let name = inc.concept("LIST_INST").unwrap_or("");
    let list = match study.concepts.data(name) {
        Some(ConceptData::ListReal(v)) => TimeList::plain(v.clone()),
        Some(ConceptData::TimeList(t)) => (**t).clone(),
        _ => return Err(inc.error("LIST_INST", format!("the list {name} holds no data"))),
    };
    let ins = &list.instants;
    if ins.len() < 2 {
        return Err(inc.error(
            "LIST_INST",
            format!(
                "the list {name} holds {} instant(s): a computation needs at least 2",
                ins.len()
            ),
        ));
    }
    if let Some(k) = ins.windows(2).position(|w| w[1] <= w[0]) {
        return Err(inc.error(
            "LIST_INST",
            format!(
                "the list {name} must be strictly increasing: instant {} ({:e}) follows {:e}",
                k + 2,
                ins[k + 1],
                ins[k]
            ),
        ));
    }
    let min_step = ins
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min);
    let tol = inc.real("PRECISION").unwrap_or(1e-6) * min_step;
    let find = |key: &str, t: f64| {
        ins.iter().position(|&s| (s - t).abs() <= tol).ok_or_else(|| {
            inc.error(
                key,
                format!(
                    "{key} = {t:e} is not an instant of the list {name} (absolute tolerance {tol:e} = PRECISION x smallest step)"
                ),
            )
        })
    };
    let index = |key: &str, k: i64| {
        usize::try_from(k)
            .ok()
            .filter(|&k| k < ins.len())
            .ok_or_else(|| {
                inc.error(
                    key,
                    format!("{key} = {k} is outside the list (0..{})", ins.len() - 1),
                )
            })
    };
    let i0 = if let Some(t) = inc.real("INST_INIT") {
        find("INST_INIT", t)?
    } else if let Some(k) = inc.int("NUME_INST_INIT") {
        index("NUME_INST_INIT", k)?
    } else if let Some(t) = t_etat {
        // The nearest list value not after the initial state's instant.
        ins.iter().rposition(|&s| s <= t + tol).unwrap_or(0)
    } else {
        0
    };
    let i1 = if let Some(t) = inc.real("INST_FIN") {
        find("INST_FIN", t)?
    } else if let Some(k) = inc.int("NUME_INST_FIN") {
        index("NUME_INST_FIN", k)?
    } else {
        ins.len() - 1
    };
    if i1 <= i0 {
        return Err(inc.error(
            "",
            format!(
                "nothing to compute: the final instant {:e} is not after the initial instant {:e}",
                ins[i1], ins[i0]
            ),
        ));
    }
    let instants = ins[i0..=i1].to_vec();
    Ok((list, instants))
}

/// The initial state: (t0 from EVOL_NOLI, u, v, a, Gauss states).
pub(crate) struct Init {
    pub t0: Option<f64>,
    pub u: Option<Vec<f64>>,
    pub v: Option<Vec<f64>>,
    pub a: Option<Vec<f64>>,
    pub points: Option<Vec<crate::element::PointState>>,
    /// The explicit contact history of an EVOL_NOLI step.
    pub contact: Option<crate::result::ContactHistory>,
    /// The initial state carries stresses (EVOL_NOLI): RELATION='ELAS' is
    /// then incremental, as in code_aster (`start_comp_elas`).
    pub stressed: bool,
    /// The energy table's values at the EVOL_NOLI step, which the new
    /// call's balance continues from (zero without EVOL_NOLI).
    pub energy_start: crate::nonlinear::energy::EnergyStart,
    /// Why the balance starts from zero although EVOL_NOLI is given.
    pub energy_note: Option<String>,
}

/// Starts the COMP_ELAS elements (ELAS/PETIT) of an initial state that
/// carries no stresses at σ0 = D ε(u0) (`Assembler::start_comp_elas` says
/// why), with a note naming how many; nothing when ETAT_INIT gives no
/// DEPL or gives EVOL_NOLI, whose stresses ELAS then continues from.
pub(crate) fn start_comp_elas(
    args: &Args,
    stressed: bool,
    asm: &mut Assembler,
    state: &mut nonlinear::State,
    notes: &mut Vec<String>,
) -> Result<(), Diagnostic> {
    if stressed || state.motion.u.iter().all(|&x| x == 0.0) {
        return Ok(());
    }
    let n = asm
        .start_comp_elas(&state.motion.u, &mut state.points)
        .map_err(|f| {
            args.error(
                "ETAT_INIT",
                format!(
                    "the stress of the initial displacement DEPL: cell M{}: {}",
                    f.cell + 1,
                    f.failure
                ),
            )
        })?;
    if n > 0 {
        notes.push(format!(
            "RELATION='ELAS' with DEFORMATION='PETIT' or 'GROT_GDEP' and an initial state without stresses is of type COMP_ELAS (as code_aster): the stress is D eps of the total displacement (its Green-Lagrange strain under GROT_GDEP), so the initial DEPL is stressed, sigma0 = D eps(u0) on {n} element(s)"
        ));
    }
    Ok(())
}

pub(crate) fn etat_init(
    study: &Study,
    args: &Args,
    asm: &Assembler,
    dofs: &[String],
    model: &str,
    mesh: &str,
) -> Result<Init, Diagnostic> {
    let mut init = Init {
        t0: None,
        u: None,
        v: None,
        a: None,
        points: None,
        contact: None,
        stressed: false,
        energy_start: Default::default(),
        energy_note: None,
    };
    let Some(o) = args.fact("ETAT_INIT") else {
        return Ok(init);
    };
    if o.given("NUME_DIDI") {
        return Err(o.not_implemented("NUME_DIDI", ""));
    }
    if let Some(name) = o.concept("EVOL_NOLI") {
        init.stressed = true;
        let Some(ConceptData::Result(r)) = study.concepts.data(name) else {
            return Err(o.error("EVOL_NOLI", format!("the result {name} holds no data")));
        };
        if r.mesh != mesh {
            return Err(o.error(
                "EVOL_NOLI",
                format!(
                    "the result {name} was computed on the mesh {}, not on the mesh {mesh} of the model: its fields would be read on other nodes",
                    r.mesh
                ),
            ));
        }
        let step = if let Some(k) = o.int("NUME_ORDRE") {
            r.find(Access::NumeOrdre(k.max(0) as usize))
        } else if let Some(t) = o.real("INST") {
            r.find(Access::Inst {
                inst: t,
                precision: o.real("PRECISION").unwrap_or(1e-6),
                relative: o.text("CRITERE").unwrap_or("RELATIF") == "RELATIF",
            })
        } else {
            r.steps
                .last()
                .ok_or_else(|| format!("the result {name} holds no step"))
        }
        .map_err(|m| o.error("EVOL_NOLI", m))?;
        // A state lacking a field CHAM_EXCLU took out cannot be continued
        // from (its displacement, velocity or stresses would start at 0);
        // the acceleration alone is solved again from the equilibrium, as
        // without ETAT_INIT.
        if let Some(f) = step.excluded.iter().find(|f| f.as_str() != "ACCE") {
            return Err(o.error(
                "EVOL_NOLI",
                format!(
                    "NUME_ORDRE {} (INST {:e}) of {name} has no {f}{}: continue from the last instant of that call, which keeps every field, or archive {f} at this instant",
                    step.nume_ordre,
                    step.inst,
                    step.exclusion_note(f)
                ),
            ));
        }
        let nodal = |f: &str| {
            step.nodal
                .get(f)
                .map(|fl| fields::from_nodal(asm, dofs, fl))
        };
        init.u = nodal("DEPL");
        init.v = nodal("VITE");
        init.a = nodal("ACCE");
        init.contact = step.contact_history.clone();
        if let (Some(s), Some(v)) = (step.gauss.get("SIEF_ELGA"), step.gauss.get("VARI_ELGA")) {
            init.points =
                Some(fields::states_from_gauss(asm, s, v).map_err(|m| o.error("EVOL_NOLI", m))?);
        }
        init.t0 = Some(o.real("INST_ETAT_INIT").unwrap_or(step.inst));
        // code_aster's nonlinDSEnergyInitValues: the new call's energies
        // start from the initial state's row of the result's table.
        if let Some(t) = r.tables.get(crate::nonlinear::energy::TABLE_NAME) {
            match crate::nonlinear::energy::EnergyStart::from_table(t, step.nume_ordre, step.inst) {
                Some(start) => init.energy_start = start,
                None => {
                    init.energy_note = Some(format!(
                        "ETAT_INIT: the energy table {} of {name} has no row for NUME_ORDRE {} (INST {:e}): the energy balance of this call starts from 0",
                        crate::nonlinear::energy::TABLE_NAME,
                        step.nume_ordre,
                        step.inst
                    ))
                }
            }
        }
    }
    for (key, slot) in [
        ("DEPL", &mut init.u),
        ("VITE", &mut init.v),
        ("ACCE", &mut init.a),
    ] {
        if let Some(name) = o.concept(key) {
            match study.concepts.data(name) {
                Some(ConceptData::Field(f)) if f.mesh != mesh => {
                    return Err(o.error(
                        key,
                        format!(
                            "the field {name} is defined on the mesh {}, not on the mesh {mesh} of the model: its values would be read on other nodes",
                            f.mesh
                        ),
                    ))
                }
                Some(ConceptData::Field(f)) => {
                    *slot = Some(fields::from_nodal(asm, dofs, &f.field))
                }
                _ => return Err(o.error(key, format!("the field {name} holds no data"))),
            }
        }
    }
    let sigm = elem_field(study, o, "SIGM", ElemQuantity::Sief, model, mesh)?;
    let vari = elem_field(study, o, "VARI", ElemQuantity::Vari, model, mesh)?;
    // A CART (one value per cell) goes to every Gauss point of its cell,
    // as code_aster converts it (nmetcv: chpchd, message ETATINIT_51).
    let sigm_points = sigm
        .filter(|f| f.by_cell)
        .map(|f| cart_to_points(asm, &f.field));
    let sigm = sigm_points.as_ref().or(sigm.map(|f| &f.field));
    let vari = vari.map(|f| &f.field);
    if sigm.is_some() || vari.is_some() {
        // Read after EVOL_NOLI's fields, which they replace (code_aster's
        // nmdoet: nmetl1 from the result, then nmetl2 field by field).
        let mut pts = init.points.take().unwrap_or_else(|| asm.initial_states());
        fields::apply_initial_fields(asm, &mut pts, sigm, vari).map_err(|(k, m)| o.error(k, m))?;
        init.points = Some(pts);
        // An initial stress makes RELATION='ELAS' incremental
        // (comp_meca_incr: l_etat_init), as EVOL_NOLI does.
        init.stressed |= sigm.is_some();
    }
    if init.t0.is_none() {
        init.t0 = o.real("INST_ETAT_INIT");
    }
    Ok(init)
}

/// A CART's values (one point per cell) repeated at each Gauss point of
/// the cell's element (the family of SIEF_ELGA); cells without an element
/// get no point.
fn cart_to_points(asm: &Assembler, cart: &crate::result::GaussField) -> crate::result::GaussField {
    let ncells = cart.offsets.len().saturating_sub(1);
    let mut npg = vec![0usize; ncells];
    for e in &asm.elements {
        if e.cell < ncells && cart.npg(e.cell) == 1 {
            npg[e.cell] = crate::element::output_points(&e.spec);
        }
    }
    let mut out = crate::result::GaussField {
        components: cart.components.clone(),
        offsets: Vec::with_capacity(ncells + 1),
        values: Vec::new(),
    };
    for (c, &n) in npg.iter().enumerate() {
        out.offsets.push(out.values.len());
        for _ in 0..n {
            out.values.extend_from_slice(cart.cell(c));
        }
    }
    out.offsets.push(out.values.len());
    out
}

/// The field by element of ETAT_INIT's `key` (SIGM or VARI), checked: a
/// field of the quantity the keyword reads, built on the model of the
/// computation (its points are that model's elements'); a CART
/// (`by_cell`) may be on the mesh alone.
fn elem_field<'s>(
    study: &'s Study,
    o: &Args,
    key: &str,
    q: ElemQuantity,
    model: &str,
    mesh: &str,
) -> Result<Option<&'s crate::concepts::ChamElem>, Diagnostic> {
    let Some(name) = o.concept(key) else {
        return Ok(None);
    };
    let Some(ConceptData::ElemField(f)) = study.concepts.data(name) else {
        return Err(o.error(key, format!("the field {name} holds no data")));
    };
    if f.quantity != q {
        return Err(o.error(
            key,
            format!(
                "the field {name} is of type {}; {key} takes a field of type {} (CREA_CHAMP TYPE_CHAM='{}')",
                f.quantity.type_cham(),
                q.type_cham(),
                q.type_cham()
            ),
        ));
    }
    if f.mesh != mesh || (f.model != model && !(f.by_cell && f.model.is_empty())) {
        return Err(o.error(
            key,
            format!(
                "the field {name} was built on {}, not on the model {model} (mesh {mesh}) of this computation: its Gauss points are those of other elements; build it with CREA_CHAMP on MODELE={model}",
                if f.model.is_empty() {
                    format!("the mesh {}", f.mesh)
                } else {
                    format!("the model {} (mesh {})", f.model, f.mesh)
                }
            ),
        ));
    }
    Ok(Some(f))
}

fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    run(study, args, result, Analysis::Dynamic)
}

/// Which of the two nonlinear commands runs: they share this executor, the
/// engine and the time loop; STAT_NON_LINE is the implicit path with the
/// inertia removed ([`Scheme::quasi_static`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Analysis {
    /// DYNA_NON_LINE: SCHEMA_TEMPS chooses the scheme.
    Dynamic,
    /// STAT_NON_LINE: equilibrium at each instant of a pseudo-time.
    Static,
}

/// The executor of DYNA_NON_LINE and STAT_NON_LINE.
pub(crate) fn run(
    study: &mut Study,
    args: &Args,
    result: Option<&str>,
    analysis: Analysis,
) -> ExecResult {
    // ENERGIE is accepted: the balance is computed for every run
    // (nonlinear::energy) and kept as the result's PARA_CALC table.
    if args.given("PILOTAGE") {
        return Err(args.not_implemented("PILOTAGE", ""));
    }
    let inertia = analysis == Analysis::Dynamic;
    let choice = match analysis {
        Analysis::Dynamic => scheme_of(args)?,
        Analysis::Static => SchemeChoice::Implicit(Scheme::quasi_static()),
    };
    // An explicit step calls no line search, and code_aster accepts the
    // keyword there without effect (the explicit path's note says so).
    if args.given("RECH_LINEAIRE") && matches!(choice, SchemeChoice::Implicit(_)) {
        return Err(args.not_implemented("RECH_LINEAIRE", ""));
    }
    if let Some(st) = args.fact("SCHEMA_TEMPS") {
        if st.real("COEF_MASS_SHIFT").is_some_and(|c| c != 0.0) {
            return Err(st.not_implemented(
                "COEF_MASS_SHIFT",
                "the mass M + COEF_MASS_SHIFT K of the first step kept for the run; leave the default 0",
            ));
        }
    }
    if !inertia && !args.given("CHAM_MATER") {
        return Err(args.error(
            "CHAM_MATER",
            "CHAM_MATER is needed: the elements of the model need a material",
        ));
    }
    if args.text("MASS_DIAG") == Some("OUI") && matches!(choice, SchemeChoice::Implicit(_)) {
        return Err(args.error(
            "MASS_DIAG",
            "MASS_DIAG='OUI' is only allowed with explicit schemes (MECANONLINE5_13)",
        ));
    }
    let unilateral = args.concept("CONTACT").is_some_and(|name| {
        matches!(study.concepts.data(name), Some(ConceptData::Contact(c)) if c.text("FORMULATION") == Some("LIAISON_UNIL"))
    });
    if unilateral {
        if let Some(s) = args.fact("SOLVEUR") {
            if let Some(m @ ("GCPC" | "PETSC")) = s.text("METHODE") {
                return Err(s.error(
                    "METHODE",
                    format!("LIAISON_UNIL cannot be used with the iterative solver METHODE='{m}': its active set solves with the factorised matrix (MECANONLINE3_96); use a direct solver (MUMPS, MULT_FRONT, LDLT)"),
                ));
            }
        }
    }
    // LIAISON_UNIL with DIFF_CENT/TCHAMWA (code_aster: MECANONLINE5_23)
    // is an aster extension, checked by the explicit path.
    if let (true, SchemeChoice::Implicit(s)) = (unilateral, &choice) {
        if s.predictor == Predictor::Acceleration {
            return Err(args
                .fact("SCHEMA_TEMPS")
                .unwrap_or(args)
                .error(
                    "FORMULATION",
                    "LIAISON_UNIL needs FORMULATION='DEPLACEMENT' with an implicit scheme: code_aster's active set corrects the displacement increment (nmsolm stops otherwise)",
                ));
        }
    }
    let mut notes: Vec<String> = Vec::new();
    if let Some(a) = match &choice {
        SchemeChoice::Implicit(s) => s.hht_alarm(),
        _ => None,
    } {
        notes.push(a);
    }
    if let (SchemeChoice::Implicit(s), true) = (&choice, args.given("CONTACT")) {
        if s.hht_full && s.alpha != 0.0 {
            notes.push(hht_contact_note(s.alpha));
        }
    }
    let model_name = args.concept("MODELE").unwrap_or("").to_string();
    let mat_name = args.concept("CHAM_MATER").unwrap_or("").to_string();
    let md = model_data(
        study,
        args,
        ("MODELE", &model_name),
        ("CHAM_MATER", &mat_name),
    )?;
    let mut load_names = Vec::new();
    let mut load_mults = Vec::new();
    for ex in args.facts("EXCIT") {
        if ex.text("TYPE_CHARGE").unwrap_or("FIXE_CSTE") != "FIXE_CSTE" {
            return Err(ex.not_implemented(
                "TYPE_CHARGE",
                "only FIXE_CSTE: loads are dead, built on the initial geometry (a SUIV follower pressure is not)",
            ));
        }
        load_names.push(ex.concept("CHARGE").unwrap_or("").to_string());
        load_mults.push(ex.concept("FONC_MULT").map(str::to_string));
    }
    let loads = loads_of(study, args, "EXCIT", &load_names)?;
    let occs = occurrences(&md.mesh, args)?;
    let load_refs: Vec<&MechLoad> = loads.iter().collect();
    let initial_state = args
        .fact("ETAT_INIT")
        .is_some_and(|o| o.given("SIGM") || o.given("EVOL_NOLI"));
    nonlinear::behaviour::check_hexs8(&md.model, &occs, initial_state)
        .map_err(|e| prepare_error(args, PrepareError::Behaviour(e)))?;
    let (mut asm, alarms) = nonlinear::discretize_for(
        &md.mesh,
        &md.model,
        &md.matfield,
        &md.materials,
        &occs,
        &load_refs,
        inertia,
    )
    .map_err(|e| prepare_error(args, e))?;
    notes.extend(alarms);
    let mut hint = None;
    let free = if inertia {
        Vec::new()
    } else {
        nonlinear::rigid::unheld_modes(&md.mesh, &md.model, &asm.numbering)
    };
    if !free.is_empty() && args.concept("CONTACT").is_some() {
        let modes = free
            .iter()
            .map(|m| format!("({m})"))
            .collect::<Vec<_>>()
            .join(", ");
        notes.push(format!(
            "alarm: the rigid-body mode(s) {modes} are held by no DDL_IMPO, only by the contact, if at all (without inertia nothing else holds them)"
        ));
        // With Coulomb friction the other way to fail is a load that the
        // friction cannot hold: then no static equilibrium exists at all
        // (probe of 2026-11-28: a block pulled beyond mu N was told only
        // about DDL_IMPO).
        let coulomb = args
            .concept("CONTACT")
            .and_then(|c| study.concepts.data(c))
            .is_some_and(|d| {
                matches!(d, crate::concepts::ConceptData::Contact(a) if a.text("FROTTEMENT") == Some("COULOMB"))
            });
        hint = Some(format!(
            "the rigid-body mode(s) {modes} are held by no DDL_IMPO: if the contact does not hold them (a frictionless contact holds no tangential motion), the stiffness of STAT_NON_LINE is singular; add the missing DDL_IMPO{}",
            if coulomb {
                "; with Coulomb friction, a tangential load larger than the friction can hold (COULOMB times the normal force) has no static equilibrium either: the body slides, which only DYNA_NON_LINE follows"
            } else {
                ""
            }
        ));
    }
    if args.concept("CONTACT").is_none() && !free.is_empty() {
        return Err(args.error(
            "EXCIT",
            format!(
                "the stiffness is singular: the rigid-body mode(s) {} of the model are held by no DDL_IMPO of the loads (without inertia only the supports hold the structure); add the missing DDL_IMPO",
                free.iter().map(|m| format!("({m})")).collect::<Vec<_>>().join(", ")
            ),
        ));
    }
    let damping = if inertia {
        rayleigh_of(args, &md)?
    } else {
        // STAT_NON_LINE has no velocity: code_aster ignores the coefficients.
        None
    };
    if let Some(d) = damping {
        notes.push(format!(
            "Rayleigh damping C = {:e} K + {:e} M (ELAS AMOR_ALPHA, AMOR_BETA; K {})",
            d.stiffness,
            d.mass,
            if d.kind == crate::law::TangentKind::Elastic {
                "elastic, AMOR_RAYL_RIGI='ELASTIQUE'"
            } else {
                "tangent at the start of each step, AMOR_RAYL_RIGI='TANGENTE'"
            }
        ));
    }
    let scheme = match choice {
        SchemeChoice::Implicit(s) => s,
        SchemeChoice::Explicit(es) => {
            return super::dyna_explicit::exec(
                study,
                args,
                result,
                super::dyna_explicit::Prepared {
                    scheme: es,
                    damping,
                    md,
                    occs,
                    loads,
                    load_names,
                    load_mults,
                    asm,
                    notes,
                    model_name,
                    mat_name,
                },
            )
        }
    };
    let mut newton = newton_of(args, inertia)?;
    let mut unil_def = None;
    let contact_def = match args.concept("CONTACT") {
        Some(name) => {
            let Some(ConceptData::Contact(cargs)) = study.concepts.data(name) else {
                return Err(args.error(
                    "CONTACT",
                    format!("the contact {name} holds no data (its command did not run)"),
                ));
            };
            if let Some(m) = cargs.concept("MODELE") {
                if m != model_name {
                    return Err(args.error(
                        "CONTACT",
                        format!(
                            "the contact {name} is defined on the model {m}, not on {model_name}"
                        ),
                    ));
                }
            }
            if unilateral {
                let def =
                    crate::commands::liaison_unil::unil_def(study, cargs, &md.mesh, &md.model)?;
                let o = args.fact("NEWTON").unwrap_or(args);
                match def.algo {
                    crate::contact::unilateral::UnilAlgo::ActiveSet => {
                        if !newton.symmetrize {
                            notes.push("LIAISON_UNIL 'CONTRAINTE': the stiffness is symmetrised (MATR_RIGI_SYME='OUI' implied, as code_aster)".into());
                        }
                        newton.symmetrize = true;
                    }
                    crate::contact::unilateral::UnilAlgo::Penalty => {
                        if newton.reac_incr == 0 {
                            return Err(o.error(
                                "REAC_INCR",
                                "REAC_INCR=0 is forbidden with penalised LIAISON_UNIL: the penalty matrix changes at every iteration (CONTACT_88)",
                            ));
                        }
                        if newton.reac_incr != 1 || newton.reac_iter != 1 {
                            notes.push("alarm: penalised LIAISON_UNIL reassembles the matrix at every prediction and correction, whatever REAC_INCR and REAC_ITER say (MECANONLINE5_5)".into());
                            newton.reac_incr = 1;
                            newton.reac_iter = 1;
                        }
                    }
                }
                notes.push(format!(
                    "LIAISON_UNIL: {} link(s) in {} zone(s), ALGO_CONT='{}'",
                    def.links.len(),
                    def.zones.len(),
                    match def.algo {
                        crate::contact::unilateral::UnilAlgo::ActiveSet => "CONTRAINTE",
                        crate::contact::unilateral::UnilAlgo::Penalty => "PENALISATION",
                    }
                ));
                unil_def = Some(def);
                None
            } else {
                let mut def = crate::contact::ContactDef::from_args(cargs, &md.mesh)?;
                super::contact_def::set_user_gaps(study, cargs, &mut def, &md.mesh)?;
                if newton.reac_incr == 0 {
                    let o = args.fact("NEWTON").unwrap_or(args);
                    return Err(o.error(
                    "REAC_INCR",
                    "REAC_INCR=0 is forbidden with penalised discrete contact or friction: the contact stiffness changes with the pairing (CONTACT_88)",
                ));
                }
                if def.continuous.is_none() {
                    if !newton.symmetrize {
                        notes.push("discrete contact: the stiffness is symmetrised (MATR_RIGI_SYME='OUI' implied, as code_aster)".into());
                    }
                    newton.symmetrize = true;
                } else if newton.symmetrize {
                    return Err(args.not_implemented(
                        "NEWTON",
                        "MATR_RIGI_SYME='OUI' with continuous contact (its multipliers make the system a saddle point, solved unsymmetrised by LU)",
                    ));
                }
                Some(def)
            }
        }
        None => None,
    };
    let mut conv = convergence_of(args, &mut notes, inertia)?;
    let archive = archive_of(study, args)?;
    let suivi = suivi_of(&md.mesh, &md.model, args, inertia)?;
    let observations = observations_of(study, &md.mesh, &md.model, args, inertia)?;
    let dof_names: Vec<String> = md.model.dofs.iter().map(|d| d.name().to_string()).collect();
    let mut init = etat_init(study, args, &asm, &dof_names, &model_name, &md.model.mesh)?;
    if !inertia {
        // A dynamic result continued statically: its motion is dropped.
        init.v = None;
        init.a = None;
    }
    let (list, instants) = time_range(study, args, init.t0)?;
    let on_error = list.on_error().clone();
    if let Some(name) = match on_error {
        Action::IterSuppl { .. } => Some("ITER_SUPPL"),
        Action::AdaptCoefPena { .. } => Some("ADAPT_COEF_PENA"),
        _ => None,
    } {
        let list_name = args
            .fact("INCREMENT")
            .and_then(|i| i.concept("LIST_INST"))
            .unwrap_or("");
        return Err(args.not_implemented(
            "INCREMENT",
            &format!(
                "DEFI_LIST_INST/ECHEC/ACTION='{name}' of the ERREUR event of the time list {list_name}; use ACTION='DECOUPE'"
            ),
        ));
    }
    // The largest number of internal variables of the model's behaviours
    // (DELTA_GRANDEUR on VARI_ELGA).
    let vari = asm
        .laws
        .iter()
        .map(|l| l.law_ref().initial_internal().as_slice().len())
        .max()
        .unwrap_or(0);
    let mut events = dyna::ContactEvents::default();
    let mut ignored: Vec<String> = Vec::new();
    let mut deltas = Vec::new();
    let mut event_actions = Vec::new();
    for r in list.rules.iter().filter(|r| r.event != Event::Erreur) {
        match (&r.event, &r.action) {
            (
                Event::DeltaGrandeur {
                    vale_ref,
                    nom_cham,
                    nom_cmp,
                },
                Action::Decoupe(_) | Action::Arret,
            ) => deltas.push(delta_grandeur(
                args,
                (&md.model, vari),
                nom_cham,
                nom_cmp,
                *vale_ref,
                &r.action,
            )?),
            (Event::ResiMaxi { resi_glob_maxi }, Action::Decoupe(_) | Action::Arret) => {
                conv.events.resi_maxi = Some(*resi_glob_maxi);
                event_actions.push(("RESI_MAXI", r.action.clone()));
            }
            (Event::Other(n), Action::Decoupe(_) | Action::Arret) if n == "DIVE_RESI" => {
                conv.events.dive_resi = true;
                event_actions.push(("DIVE_RESI", r.action.clone()));
            }
            (
                Event::Collision,
                Action::Decoupe(Subdivision::AutoCollision {
                    subd_inst,
                    subd_duree,
                }),
            ) if contact_def.is_some() => events.collision = Some((*subd_inst, *subd_duree)),
            (Event::Interpenetration { pene_maxi }, Action::AdaptCoefPena { coef_maxi })
                if contact_def.is_some() =>
            {
                events.interpenetration = Some((*pene_maxi, *coef_maxi))
            }
            (e, a) => ignored.push(format!("{} with ACTION {a}", e.name())),
        }
    }
    if !ignored.is_empty() && contact_def.is_some() {
        return Err(args.not_implemented(
            "INCREMENT",
            &format!(
                "the time list's events {} with CONTACT (only ERREUR, COLLISION with SUBD_METHODE='AUTO' and INTERPENETRATION with ADAPT_COEF_PENA are handled)",
                ignored.join(", ")
            ),
        ));
    }
    if !ignored.is_empty() {
        notes.push(format!(
            "the time list's events {} are ignored (acted upon: ERREUR, DELTA_GRANDEUR, RESI_MAXI, DIVE_RESI, and with a DISCRETE or CONTINUE contact, not LIAISON_UNIL, COLLISION and INTERPENETRATION)",
            ignored.join(", ")
        ));
    }
    let growth = growth_of(&list);
    let adaptation = if growth.is_some() {
        adaptation_of(args, (&md.model, vari), &list, conv.iter_glob_maxi)?
    } else {
        Vec::new()
    };
    if let Some(g) = &growth {
        let bounds = format!(
            "{}{}",
            g.pas_maxi
                .map_or(String::new(), |m| format!(" and PAS_MAXI = {m:e}")),
            g.pas_mini.map_or(String::new(), |m| format!(
                "; a step chosen below PAS_MINI = {m:e} stops the run"
            ))
        );
        let rules: Vec<String> = adaptation.iter().map(describe_adaptation).collect();
        notes.push(format!(
            "METHODE='AUTO': after each successful step the next one is the smallest that the ADAPTATION occurrences propose ({}), the last step when none does, up to the next instant of the list{bounds}",
            rules.join("; ")
        ));
    }
    if args.has("SOLVEUR") {
        notes.push(super::blocks::SOLVEUR_NOTE.into());
    }
    let info = args.int("INFO").unwrap_or(1);
    let progress = study.verbose && std::io::IsTerminal::is_terminal(&std::io::stderr());
    let tl = TimeLoop {
        instants,
        on_error,
        archive,
        cham_exclu: cham_exclu_of(args)?,
        newton_table: info >= 2 || !suivi.is_empty(),
        suivi,
        observations,
        progress,
        dof_names,
        ncells: md.mesh.ncells(),
        events,
        deltas,
        event_actions,
        growth,
        adaptation,
        subd_niveau: list.max_subd_niveau(),
        hint,
        load_peaks: load_peaks(study, &md, &loads, &load_names, &load_mults),
        energy_start: init.energy_start,
    };
    let mut evol = result_to_fill(
        study,
        args.reuse.as_deref(),
        &md.model,
        &model_name,
        &mat_name,
        RunData {
            loads: load_names.clone(),
            load_mults: load_mults.clone(),
            mass_diag: false,
        },
        &occs,
    );

    let t_start = tl.instants[0];
    let has_acce = init.a.is_some();
    let mut state = nonlinear::initial_state(&asm, t_start, init.u, init.v, init.a);
    start_comp_elas(args, init.stressed, &mut asm, &mut state, &mut notes)?;
    notes.extend(init.energy_note.take());
    if let Some(p) = init.points {
        state.points = p;
    }
    let mut engine = Engine::new(asm, scheme, newton, conv, state);
    engine.damping = damping;
    engine.lu.check = super::blocks::singularity_check(args);
    // PESANTEUR and FORCE_NODALE: dead loads, scaled by their FONC_MULT.
    set_loads(
        args,
        &md,
        &loads,
        &load_mults,
        study,
        &tl.instants,
        &mut engine,
    )?;
    for n in &notes {
        study.log(format!("  {n}"));
    }
    study.log(format!(
        "  {}: {} equations ({} imposed dofs), {} elements, matrix pattern {} entries; {} steps from {:e} to {:e}",
        args.command,
        engine.asm.numbering.neq(),
        engine.asm.numbering.imposed.len(),
        engine.asm.elements.len(),
        engine.asm.pattern.nnz(),
        tl.instants.len() - 1,
        tl.instants[0],
        tl.instants[tl.instants.len() - 1]
    ));
    match engine.initialize(inertia && !has_acce) {
        Ok(Some(alarm)) if alarm.contains(crate::solver::OVERFLOW) => {
            let why = largest_load(&tl.load_peaks, engine.committed.t);
            study.log(format!(
                "  {alarm}{}",
                why.map_or(String::new(), |w| format!("; {w}"))
            ))
        }
        Ok(Some(alarm)) => study.log(format!("  {alarm}")),
        Ok(None) => {
            if inertia && !has_acce {
                study.log("  initial acceleration solved from M a0 = F_ext - F_int(u0)");
            }
        }
        Err(f) => return Err(args.error("", format!("initial state: {f}"))),
    }
    let verbose = study.verbose && !progress;
    let mess = &mut study.mess;
    let mut log = |line: &str| {
        if verbose {
            eprintln!("{line}");
        }
        mess.push_str(line);
        mess.push('\n');
    };
    let axis = md
        .model
        .element_cells()
        .any(|(_, s)| s.formulation == crate::model::spec::Formulation::Axis);
    let mut contact = match contact_def {
        None => None,
        Some(def) => Some(
            nonlinear::DiscreteContact::build(
                def,
                &md.mesh,
                &engine.asm.numbering,
                &engine.committed.motion.u,
                axis,
            )
            .map_err(|m| args.error("CONTACT", m))?,
        ),
    };
    if let Some(a) = contact.as_ref().and_then(|c| c.initial_penetration_alarm()) {
        log(&format!("  {a}"));
    }
    let mut unil = match unil_def {
        Some(def) => {
            let term = nonlinear::UnilateralContact::new(def, &engine.asm.numbering);
            // Coefficients that cannot be evaluated at the step ends of
            // the list (code_aster evaluates them at t+, never at the
            // initial instant) are refused before the first step, not
            // found as a step failure that DEFI_LIST_INST would cut. A
            // function's domain is an interval: the first and the last
            // step ends cover the others.
            let nb = &engine.asm.numbering;
            let eq = |f: usize| (nb.eq[f] != nonlinear::dofs::NONE).then(|| nb.eq[f]);
            let imposed = nonlinear::unilateral::imposed_value(nb);
            let ends = &tl.instants[1.min(tl.instants.len() - 1)..];
            let checked = [ends[0], ends[ends.len() - 1]];
            for &t in &checked {
                term.def.rows(t, nb.ndpn, eq, &imposed).map_err(|m| {
                    args.error("CONTACT", format!("LIAISON_UNIL at INST = {t:e}: {m}"))
                })?;
            }
            Some(term)
        }
        None => None,
    };
    let outcome = dyna::run(
        &mut engine,
        contact.as_mut(),
        unil.as_mut(),
        &tl,
        &mut evol,
        &mut log,
    );
    if let Some(a) = contact.as_ref().and_then(|c| c.active.as_ref()) {
        let s = a.stats;
        log(&format!(
            "  contact ALGO_CONT='CONTRAINTE': {} active-set calls, {} passes (at most {} in one call); {} link(s) active at the last solve",
            s.calls,
            s.passes,
            s.max_passes,
            a.active_links()
        ));
    }
    if let Some(w) = engine.lu.tolerated {
        log(&format!(
            "  {}",
            crate::nonlinear::linear::singularity_alarm(&engine.asm.numbering, w, engine.lu.check)
        ));
    }
    if let Some(u) = &unil {
        let s = u.stats;
        match u.def.algo {
            crate::contact::unilateral::UnilAlgo::ActiveSet => log(&format!(
                "  LIAISON_UNIL: {} active-set calls, {} passes (at most {} in one call); {} link(s) active at the last step",
                s.calls, s.passes, s.max_passes, s.active
            )),
            crate::contact::unilateral::UnilAlgo::Penalty => log(&format!(
                "  LIAISON_UNIL: {} link(s) penetrating at the last step",
                s.active
            )),
        }
        if let Some(a) = u.unheld_alarm() {
            log(&format!("  {a}"));
        }
    }
    result_of_run(study, args, result, evol, init.energy_start, outcome)
}

/// The alarm for ARCHIVAGE instants (LIST_INST or INST) inside the run's
/// span that no computed step ended on: nothing is archived there, as in
/// code_aster, but silently a later TEST_RESU or POST_RELEVE_T at that
/// instant only finds "no stored instant".
fn unarchived_instants(study: &Study, args: &Args, evol: &EvolNoli) -> Option<String> {
    let Ok(ArchivePolicy::Instants {
        instants,
        precision,
        relative,
    }) = archive_of(study, args)
    else {
        return None;
    };
    let (first, last) = (evol.steps.first()?.inst, evol.steps.last()?.inst);
    let near = |s: f64, t: f64| {
        let tol = if relative {
            precision * s.abs()
        } else {
            precision
        };
        (s - t).abs() <= tol
    };
    let missing: Vec<String> = instants
        .iter()
        .filter(|&&s| (first..=last).contains(&s) || near(s, first) || near(s, last))
        .filter(|&&s| !evol.steps.iter().any(|st| near(s, st.inst)))
        .map(|s| format!("{s:e}"))
        .collect();
    if missing.is_empty() {
        return None;
    }
    Some(format!(
        "  alarm: ARCHIVAGE: {} instant(s) asked for within the run's span are not instants the run computed ({}; CRITERE='{}', PRECISION={precision:e}): nothing is archived there (as code_aster). Ask for instants of the time list, or use PAS_ARCH",
        missing.len(),
        missing.join(", "),
        if relative { "RELATIF" } else { "ABSOLU" }
    ))
}

/// Full HHT weights the internal and external forces of the step's end by
/// 1 and of its start by −α/(1 + α) (the equation divided by 1 + α), but
/// keeps no contact force of the step's start, as code_aster's `nmchht`,
/// whose previous-step vectors hold none: the contact force enters at the
/// step's end with weight 1. Its multipliers (CONT_NOEU RN, R, the
/// LIAISON_UNIL forces) are then those of the weighted equation: the force
/// the contact exerts on the bodies is (1 + α) times them (a body at rest
/// on its support shows RN = weight / (1 + α)), while REAC_NODA (from the
/// stresses) gives the force itself. A probe study read impacts 1.43 times
/// too strong at α = −0.3; the .mess says it.
fn hht_contact_note(alpha: f64) -> String {
    format!(
        "alarm: HHT with MODI_EQUI='OUI' and contact: the contact forces enter the step's end with weight 1 and none of the step's start, as code_aster keeps no contact force among HHT's previous-step vectors, so CONT_NOEU (RN, R) and the contact reactions are the multipliers of the equation divided by 1 + ALPHA: the force on the bodies is (1 + ALPHA) = {:.4} times them (a body at rest shows RN = its weight / {:.4}); REAC_NODA gives the force itself",
        1.0 + alpha,
        1.0 + alpha
    )
}

/// The result concept of a run, implicit or explicit. A run stopped by a
/// failed step or a signal still binds what it archived to the result's
/// name before the stop is reported, so that what was computed stays
/// available (docs/dynamics.md §2b).
pub(crate) fn result_of_run<T>(
    study: &mut Study,
    args: &Args,
    result: Option<&str>,
    evol: EvolNoli,
    energy_start: crate::nonlinear::energy::EnergyStart,
    outcome: Result<T, crate::nonlinear::dyna::Stopped>,
) -> ExecResult {
    let mut evol = evol;
    split_internal_energy(
        study,
        args,
        result.unwrap_or_default(),
        &mut evol,
        energy_start,
    );
    if outcome.is_ok() {
        if let Some(alarm) = unarchived_instants(study, args, &evol) {
            study.log(&alarm);
        }
    }
    match outcome {
        Ok(_) => Ok(Some(ConceptData::Result(Box::new(evol)))),
        Err(stopped) => {
            if let Some(name) = result {
                study.concepts.insert(Concept {
                    name: name.to_string(),
                    ty: C::EvolNoli,
                    defined_at: args.span,
                    command: args.command.clone(),
                    data: ConceptData::Result(Box::new(evol)),
                });
            }
            Err(Diagnostic::error(stopped.message)
                .at(args.span)
                .in_command(args.command.clone()))
        }
    }
}

/// The result a run fills, implicit or explicit. With reuse= the result is
/// still in the table: new steps are appended to it (instants not after
/// its last one are not stored again); otherwise a new one, even when the
/// name is already bound (`R = DYNA_NON_LINE(...)` twice without reuse=
/// makes a new R, as Python rebinds the name). Either way it takes the
/// run's model, material field and behaviours, and records the run's
/// loads and mass for the steps it will archive (those already stored
/// keep their own).
pub(crate) fn result_to_fill(
    study: &Study,
    reuse: Option<&str>,
    model: &Model,
    model_name: &str,
    mat_name: &str,
    run: RunData,
    occs: &[Occurrence],
) -> EvolNoli {
    let mut evol = match reuse.and_then(|r| study.concepts.data(r)) {
        Some(ConceptData::Result(r)) => (**r).clone(),
        _ => EvolNoli::default(),
    };
    evol.mesh = model.mesh.clone();
    evol.model = model_name.to_string();
    evol.cham_mater = mat_name.to_string();
    evol.start_run(run);
    evol.comportement = cell_comportement(model, occs);
    evol
}

/// Splits the internal energy of the energy balance (PARA_CALC, whose
/// ENER_TOT is the work of the internal forces, code_aster's column) into
/// two aster columns at each archived instant: ENER_ELAS, the elastic
/// strain energy of the stress (POST_ELEM's ENER_ELAS over every element),
/// and TRAV_PLAS = ENER_TOT − (ENER_ELAS − ENER_ELAS₀), the internal work not stored
/// elastically: the plastic work (dissipation and the energy stored by
/// hardening), plus, in 3D_SI elements, the hourglass stabilisation's
/// energy, and the trapezoidal rule's error in ENER_TOT. Where a cell's
/// law has no elastic energy built (GDEF_LOG, VMIS_JOHN_COOK...), or a
/// step holds no stress, the columns are left out and the .mess says why.
fn split_internal_energy(
    study: &mut Study,
    args: &Args,
    name: &str,
    evol: &mut EvolNoli,
    start: crate::nonlinear::energy::EnergyStart,
) {
    use crate::post::table::{Cell, ColumnType};
    let table_name = crate::nonlinear::energy::TABLE_NAME;
    if !evol.tables.contains_key(table_name) {
        return;
    }
    // The call continues a balance whose ENER_TOT its start's row split:
    // TRAV_PLAS goes on from that row's. A start whose ENER_TOT was not
    // split (a law without elastic energy in the call before) cannot be.
    let tot0 = start.values[2];
    let plas0 = match start.trav_plas {
        Some(p) => p,
        None if tot0 == 0.0 => 0.0,
        None => {
            study.log(format!(
                "  energy balance: ENER_TOT not split into ENER_ELAS and TRAV_PLAS (the initial state's row of the energy table has ENER_TOT {tot0:e} and no TRAV_PLAS: the call that computed it could not split it)"
            ));
            return;
        }
    };
    let Some(ConceptData::Model(model)) = study.concepts.data(&evol.model) else {
        return;
    };
    let Ok(mesh) = super::model_args::mesh_of_model(study, args, "MODELE", model) else {
        return;
    };
    let values =
        super::post_elem::total_elastic_energy(study, args, "ENERGIE", name, evol, mesh, model);
    let values = match values {
        Ok(v) => v
            .into_iter()
            .collect::<std::collections::HashMap<usize, f64>>(),
        Err(d) => {
            study.log(format!(
                "  energy balance: ENER_TOT not split into ENER_ELAS and TRAV_PLAS ({})",
                d.message
            ));
            return;
        }
    };
    let Some(table) = evol.tables.get_mut(table_name) else {
        return;
    };
    let (Some(nume), Some(tot), Some(reuse)) = (
        table.column_index("NUME_ORDRE"),
        table.column_index("ENER_TOT"),
        table.column_index(crate::nonlinear::result_table::NUME_REUSE),
    ) else {
        return;
    };
    // A continuation finds the columns in the table (its previous calls
    // had them), or adds them (the earlier rows stay without).
    let column = |table: &mut crate::post::table::Table, name: &str| match table.column_index(name)
    {
        Some(i) => Some(i),
        None => table.add_column(name, ColumnType::Real).ok(),
    };
    let (Some(elas), Some(plas)) = (column(table, "ENER_ELAS"), column(table, "TRAV_PLAS")) else {
        return;
    };
    // This call's rows: those of the largest NUME_REUSE (the earlier
    // calls' rows were split by their own call, from their own start).
    let int = |c: &Option<Cell>| match c {
        Some(Cell::Int(n)) => Some(*n),
        _ => None,
    };
    let this_call = table.rows.iter().filter_map(|r| int(&r[reuse])).max();
    let ours = |row: &Vec<Option<Cell>>| int(&row[reuse]) == this_call;
    // ENER_TOT is cumulated from the initial state, whose stresses may
    // already hold elastic energy (a continuation, or an ELAS initial DEPL
    // of type COMP_ELAS): TRAV_PLAS is the internal work not stored since
    // then, ENER_TOT - (ENER_ELAS - ENER_ELAS of the initial state). A
    // fresh run's rows start at its initial state, NUME_ORDRE 0; a
    // continuation's start at its first new step, right after the stored
    // step it continues from.
    let first = table
        .rows
        .iter()
        .filter(|r| ours(r))
        .find_map(|row| int(&row[nume]).map(|n| n as usize));
    let initial = first.and_then(|f| {
        if f == 0 {
            values.get(&0).copied()
        } else {
            values
                .iter()
                .filter(|(&n, _)| n < f)
                .max_by_key(|(&n, _)| n)
                .map(|(_, &w)| w)
        }
    });
    let w0 = initial.unwrap_or(0.0);
    let mut last = None;
    for row in table.rows.iter_mut().filter(|r| ours(r)) {
        let n = match &row[nume] {
            Some(Cell::Int(n)) => *n as usize,
            _ => continue,
        };
        let (Some(&w), Some(total)) = (values.get(&n), row[tot].as_ref().and_then(|c| c.as_f64()))
        else {
            continue;
        };
        let p = plas0 + (total - tot0) - (w - w0);
        row[elas] = Some(Cell::Real(w));
        row[plas] = Some(Cell::Real(p));
        last = Some((n, w, p, w0));
    }
    if let Some((n, w, p, w0)) = last {
        study.log(if tot0 != 0.0 || plas0 != 0.0 {
            format!(
                "  energy balance split at NUME_ORDRE {n}: ENER_ELAS {w:e}  TRAV_PLAS {p:e} ({plas0:e} + (ENER_TOT - {tot0:e}) - (ENER_ELAS - {w0:e}): TRAV_PLAS, ENER_TOT and the elastic energy of the initial state)"
            )
        } else if w0 == 0.0 {
            format!(
                "  energy balance split at NUME_ORDRE {n}: ENER_ELAS {w:e}  TRAV_PLAS {p:e} (ENER_TOT - ENER_ELAS)"
            )
        } else {
            format!(
                "  energy balance split at NUME_ORDRE {n}: ENER_ELAS {w:e}  TRAV_PLAS {p:e} (ENER_TOT - (ENER_ELAS - {w0:e}, the elastic energy of the initial state))"
            )
        });
    }
}
