//! CALC_CHAMP: derived fields of a result (stresses at nodes, nodal forces...).

use super::blocks::*;
use super::dyna_non_line::{loads_of, model_data, prepare_error, ModelData};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::{ConceptData, ConceptType as C};
use crate::law::TangentKind;
use crate::model::CellRole;
use crate::model::MechLoad;
use crate::nonlinear::{self, fields, Occurrence};
use crate::result::energy::CellEnergy;
use crate::result::{Access, GaussField, NodalField, RunData};
use crate::study::Study;

/// The element options of code_aster's CALC_CHAMP on a nonlinear result
/// (C_NOM_CHAM_INTO, category 'nonlin') by keyword: those computed here,
/// then the others, which the catalogue accepts as code_aster's values and
/// the executor refuses as not implemented (a user's valid option is not
/// an input error).
#[rustfmt::skip]
const OPTIONS: [(&str, &[&str], &[&str]); 5] = [
    (
        "CONTRAINTE",
        &["SIEF_ELNO", "SIGM_ELNO", "SIEF_NOEU", "SIGM_NOEU", "SIGM_ELGA"],
        &[
            "EFGE_ELGA", "EFGE_ELNO", "EFGE_NOEU", "SIPM_ELNO", "SIPO_ELNO", "SIPO_NOEU",
            "SIRO_ELEM",
        ],
    ),
    (
        "DEFORMATION",
        &[
            "EPSI_ELGA", "EPSI_ELNO", "EPSI_NOEU", "EPSG_ELGA", "EPSG_ELNO", "EPSG_NOEU",
            "EPSL_ELGA", "EPSL_ELNO", "EPSL_NOEU", "EPSP_ELGA", "EPSP_ELNO", "EPSP_NOEU",
        ],
        &[
            "DEGE_ELGA", "DEGE_ELNO", "DEGE_NOEU", "EPFD_ELGA", "EPFD_ELNO", "EPFD_NOEU",
            "EPFP_ELGA", "EPFP_ELNO", "EPFP_NOEU", "EPME_ELGA", "EPME_ELNO", "EPME_NOEU",
            "EPMG_ELGA", "EPMG_ELNO", "EPMG_NOEU", "EPVC_ELGA", "EPVC_ELNO", "EPVC_NOEU",
        ],
    ),
    (
        "CRITERES",
        &["SIEQ_ELGA", "SIEQ_ELNO", "SIEQ_NOEU", "EPEQ_ELGA", "EPEQ_ELNO", "EPEQ_NOEU"],
        &[
            "DERA_ELGA", "DERA_ELNO", "DERA_NOEU", "ENDO_ELGA", "ENDO_ELNO", "ENDO_NOEU",
            "EPGQ_ELGA", "EPGQ_ELNO", "EPGQ_NOEU", "EPMQ_ELGA", "EPMQ_ELNO", "EPMQ_NOEU",
            "INDL_ELGA", "PDIL_ELGA",
        ],
    ),
    (
        "VARI_INTERNE",
        &["VARI_ELNO", "VARI_NOEU"],
        &["VAEX_ELGA", "VAEX_ELNO", "VAEX_NOEU", "VARC_ELGA"],
    ),
    (
        "ENERGIE",
        &["ENEL_ELGA", "ENEL_ELNO", "ENEL_NOEU"],
        &[
            "DISS_ELEM", "DISS_ELGA", "DISS_ELNO", "DISS_NOEU", "ENEL_ELEM", "ENTR_ELEM",
            "ETOT_ELEM", "ETOT_ELGA", "ETOT_ELNO", "ETOT_NOEU",
        ],
    ),
];

/// Every value of `key` the catalogue accepts: the built ones first.
fn option_values(key: &str) -> Vec<&'static str> {
    OPTIONS
        .iter()
        .filter(|(k, _, _)| *k == key)
        .flat_map(|(_, built, other)| built.iter().chain(other.iter()).copied())
        .collect()
}

pub fn def() -> CommandDef {
    let mut kws = vec![
        concept("RESULTAT", RESULTS)
            .required()
            .doc("result to enrich (also the reused concept)")
            .kw(),
        concept("MODELE", &[C::Modele])
            .doc("absent: the result's")
            .kw(),
        concept("CHAM_MATER", &[C::ChamMater]).kw(),
        fact(
            "EXCIT",
            vec![
                concept("CHARGE", &[C::CharMeca, C::CharCineMeca])
                    .required()
                    .kw(),
                concept("FONC_MULT", &[C::Fonction, C::Formule]).kw(),
                text("TYPE_CHARGE")
                    .into(&["FIXE_CSTE", "SUIV", "DIDI"])
                    .not_built(&["SUIV", "DIDI"], "only FIXE_CSTE loads")
                    .default(t("FIXE_CSTE"))
                    .kw(),
            ],
        )
        .many()
        .doc("loads for REAC_NODA, replacing those of every step; absent: each step's own (those of the call that computed it)")
        .kw(),
        text("TOUT_ORDRE").into(&["OUI"]).kw(),
        int("NUME_ORDRE").many().kw(),
        concept("LIST_ORDRE", &[C::Listis]).doc("stored indices of a DEFI_LIST_ENTI list").kw(),
        real("INST").many().kw(),
        concept("LIST_INST", &[C::Listr8]).kw(),
    ];
    kws.extend(critere_precision(1e-6));
    kws.extend([
        tout(),
        text("GROUP_MA")
            .many()
            .doc("cells the element options are computed on (*_NOEU: the mean over them); FORCE needs the whole model")
            .kw(),
        maille(),
        text("CONTRAINTE")
            .many()
            .into(&option_values("CONTRAINTE"))
            .doc("stress fields: *_ELNO extrapolated from SIEF_ELGA cell by cell, *_NOEU their mean over the cells at each node; SIGM_* the stress components SIXX..SIYZ only (SIGM_ELGA: those of SIEF_ELGA)")
            .kw(),
        text("DEFORMATION")
            .many()
            .into(&option_values("DEFORMATION"))
            .doc("strains of DEPL on the initial geometry, tensor shears (EPXY = γxy/2): EPSI linearised ½(H + Hᵀ), EPSG Green-Lagrange ½(FᵀF − 1), EPSL logarithmic ½ ln(FᵀF); EPSP the anelastic strain EPSI − S:σ (S the ELAS compliance; PETIT and PETIT_REAC); *_ELGA at the SIEF_ELGA points, *_ELNO extrapolated cell by cell, *_NOEU their mean at each node")
            .kw(),
        text("CRITERES")
            .many()
            .into(&option_values("CRITERES"))
            .doc("equivalent stresses VMIS, TRESCA, PRIN_1..3, VMIS_SG, VECT_1_X..VECT_3_Z, TRSIG, TRIAX: SIEQ_ELGA of SIEF_ELGA, SIEQ_ELNO of SIGM_ELNO, SIEQ_NOEU the mean of SIEQ_ELNO at each node ; EPEQ_ELGA, EPEQ_ELNO, EPEQ_NOEU the equivalent strains INVA_2, PRIN_1..3, INVA_2SG, VECT_1_X..VECT_3_Z of EPSI_ELGA, EPSI_ELNO and the mean of EPEQ_ELNO")
            .kw(),
        text("VARI_INTERNE")
            .many()
            .into(&option_values("VARI_INTERNE"))
            .doc("internal variables V1..Vn at nodes: VARI_ELNO extrapolated from VARI_ELGA cell by cell, VARI_NOEU its mean at each node")
            .kw(),
        text("NOM_VARI")
            .many()
            .doc("the variables VAEX_* extract (VAEX_* not implemented)")
            .kw(),
        text("ENERGIE")
            .many()
            .into(&option_values("ENERGIE"))
            .doc("ENEL_ELGA: the elastic energy density TOTALE, ½ σ:S:σ of SIEF_ELGA (S the ELAS compliance) under PETIT and PETIT_REAC, the stored energy K/2 (½(J² − 1) − ln J) + μ/2 (tr b̄ᵉ − 3) for VMIS_ISOT_LINE, VMIS_ISOT_TRAC and VMIS_ISOT_PUIS in SIMO_MIEHE; ENEL_ELNO extrapolated, ENEL_NOEU averaged (the other code_aster options and GDEF_LOG not implemented)")
            .kw(),
        text("FORCE")
            .many()
            .into(&["FORC_NODA", "REAC_NODA"])
            .doc("FORC_NODA: internal nodal forces; REAC_NODA: minus applied loads, plus M.a, i.e. support and contact reactions")
            .kw(),
        info(),
        titre(),
    ]);
    let spec = command("CALC_CHAMP", Produces::SameAs("RESULTAT", C::EvolNoli), kws)
        .reentrant(Reentrant::Optional("RESULTAT"))
        .rules(vec![
            exclus(&[
                "TOUT_ORDRE",
                "NUME_ORDRE",
                "LIST_ORDRE",
                "INST",
                "LIST_INST",
            ]),
            exclus(&["TOUT", "GROUP_MA", "MAILLE"]),
        ])
        .doc("Adds derived fields to a result, at all stored indices unless restricted.");
    CommandDef { spec, exec }
}

/// FORC_NODA and REAC_NODA (semantics.md §9.1) at the selected steps.
///
/// FORC_NODA is the assembled ∫ Bᵀσ of the stored state: the law is
/// re-evaluated with a zero increment from the stored SIEF_ELGA/VARI_ELGA
/// and the stored DEPL, which returns the stored stress and integrates it
/// on the element's own configuration (current geometry for PETIT_REAC,
/// P = τF⁻ᵀ on the initial one for SIMO_MIEHE). REAC_NODA = FORC_NODA −
/// F_ext + M·ACCE with the loads (and their FONC_MULT) and the mass of
/// the call that computed each step, so at free nodes it is that step's
/// dynamic residual (≈ 0, without contact forces) and at supports the
/// support reaction, also in a result chained through calls (reuse=)
/// with other loads or another mass.
fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    let name = args.concept("RESULTAT").unwrap_or("").to_string();
    let mut evol = match study.concepts.data(&name) {
        Some(ConceptData::Result(r)) => (**r).clone(),
        _ => return Err(args.error("RESULTAT", format!("the result {name} holds no data"))),
    };
    for (key, built, _) in OPTIONS {
        if let Some(o) = args.texts(key).iter().find(|o| !built.contains(o)) {
            return Err(args.not_implemented(
                key,
                &format!("{o}; the {key} options computed are {}", built.join(", ")),
            ));
        }
    }
    // GROUP_MA/MAILLE restrict the element options; FORC_NODA and
    // REAC_NODA are assembled over the whole model.
    if let Some(key) = ["GROUP_MA", "MAILLE"].into_iter().find(|k| args.has(k)) {
        if args.has("FORCE") {
            return Err(args.not_implemented(
                key,
                "FORCE (FORC_NODA, REAC_NODA) on part of the model; the element options (CONTRAINTE, DEFORMATION, CRITERES, VARI_INTERNE) are restricted",
            ));
        }
    }
    let selected = selected_steps(study, args, &evol)?;
    element_fields(study, args, &name, &mut evol, &selected)?;
    let options = args.texts("FORCE");
    if options.is_empty() {
        return Ok(Some(ConceptData::Result(Box::new(evol))));
    }
    let model_name = args.concept("MODELE").unwrap_or(&evol.model).to_string();
    let mat_name = args
        .concept("CHAM_MATER")
        .unwrap_or(&evol.cham_mater)
        .to_string();
    if model_name.is_empty() || mat_name.is_empty() {
        return Err(args.error(
            "RESULTAT",
            format!("the result {name} does not say which model and material field it was computed with: give MODELE and CHAM_MATER"),
        ));
    }
    let mut md = model_data(
        study,
        args,
        ("MODELE", &model_name),
        ("CHAM_MATER", &mat_name),
    )?;
    // CALC_CHAMP's own EXCIT replaces the loads of every step, as in
    // code_aster; the mass stays each step's.
    let given: Option<(Vec<String>, Vec<Option<String>>)> = if args.has("EXCIT") {
        for ex in args.facts("EXCIT") {
            if ex.text("TYPE_CHARGE").unwrap_or("FIXE_CSTE") != "FIXE_CSTE" {
                return Err(ex.not_implemented("TYPE_CHARGE", "only FIXE_CSTE loads"));
            }
        }
        Some(
            args.facts("EXCIT")
                .iter()
                .map(|e| {
                    (
                        e.concept("CHARGE").unwrap_or("").to_string(),
                        e.concept("FONC_MULT").map(str::to_string),
                    )
                })
                .unzip(),
        )
    } else {
        None
    };
    // The behaviour the result was computed with, one occurrence per
    // (RELATION, DEFORMATION) pair.
    let mut occs: Vec<Occurrence> = Vec::new();
    for (c, b) in evol.comportement.iter().enumerate() {
        if let Some((rel, def)) = b {
            match occs
                .iter_mut()
                .find(|o| &o.relation == rel && &o.deformation == def)
            {
                Some(o) => o.cells.get_or_insert_with(Vec::new).push(c),
                None => occs.push(Occurrence {
                    cells: Some(vec![c]),
                    relation: rel.clone(),
                    deformation: def.clone(),
                    controls: Default::default(),
                }),
            }
        }
    }
    // The selected steps grouped by what they were computed with (the
    // calls of a chained result differ in loads and mass), in order.
    let mut groups: Vec<(RunData, Vec<usize>)> = Vec::new();
    for step in evol
        .steps
        .iter()
        .filter(|s| selected.contains(&s.nume_ordre))
    {
        let mut run = evol.run_of(step).cloned().unwrap_or_default();
        run.load_mults.resize(run.loads.len(), None);
        if let Some((loads, mults)) = &given {
            run.loads.clone_from(loads);
            run.load_mults.clone_from(mults);
        }
        match groups.iter_mut().find(|(r, _)| *r == run) {
            Some((_, orders)) => orders.push(step.nume_ordre),
            None => groups.push((run, vec![step.nume_ordre])),
        }
    }
    if groups.len() > 1 {
        for (run, orders) in &groups {
            study.log(format!(
                "  {}: NUME_ORDRE {} with the loads {} and the {} mass of the call that computed them",
                options.join(", "),
                describe_orders(orders),
                describe_loads(run),
                if run.mass_diag { "lumped (MASS_DIAG='OUI')" } else { "consistent" }
            ));
        }
    }
    let is_elas = matches!(study.concepts.get(&name).map(|c| c.ty), Some(C::EvolElas));
    for (run, orders) in &groups {
        forces_of_run(
            study, args, &name, &mut md, &occs, run, is_elas, &options, &mut evol, orders,
        )?;
    }
    Ok(Some(ConceptData::Result(Box::new(evol))))
}

/// "0 to 20" for a contiguous run of orders, else the list.
fn describe_orders(orders: &[usize]) -> String {
    match (orders.first(), orders.last()) {
        (Some(a), Some(b)) if b - a + 1 == orders.len() && a != b => format!("{a} to {b}"),
        _ => orders
            .iter()
            .map(|n| n.to_string())
            .collect::<Vec<_>>()
            .join(", "),
    }
}

/// The loads of a run as the .mess names them ("BC, PES (FONC_MULT F)").
fn describe_loads(run: &RunData) -> String {
    if run.loads.is_empty() {
        return "(none)".into();
    }
    run.loads
        .iter()
        .zip(&run.load_mults)
        .map(|(l, m)| match m {
            Some(f) => format!("{l} (FONC_MULT {f})"),
            None => l.clone(),
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// FORC_NODA and REAC_NODA of the steps `orders`, computed with the loads
/// and the mass of `run`.
#[allow(clippy::too_many_arguments)]
fn forces_of_run(
    study: &Study,
    args: &Args,
    name: &str,
    md: &mut ModelData,
    occs: &[Occurrence],
    run: &RunData,
    is_elas: bool,
    options: &[&str],
    evol: &mut crate::result::EvolNoli,
    orders: &[usize],
) -> Result<(), crate::diag::Diagnostic> {
    // The run's PESANTEUR: the lumped mass times g with MASS_DIAG='OUI'.
    md.lumped_gravity = run.mass_diag;
    let loads = loads_of(study, args, "EXCIT", &run.loads)?;
    let refs: Vec<&MechLoad> = loads.iter().collect();
    // A STAT_NON_LINE result has no ACCE: no M.a term, and no density is
    // needed (REAC_NODA = FORC_NODA - F_ext).
    let inertia = evol
        .steps
        .iter()
        .filter(|s| orders.contains(&s.nume_ordre))
        .any(|s| s.nodal.contains_key("ACCE"));
    let (mut asm, _) = nonlinear::discretize_for(
        &md.mesh,
        &md.model,
        &md.matfield,
        &md.materials,
        occs,
        &refs,
        inertia,
    )
    .map_err(|e| prepare_error(args, e))?;
    // A result of an explicit run with MASS_DIAG='OUI': M·a with the run's
    // lumped (HRZ) mass, so that REAC_NODA is that run's residual (zero at
    // free nodes, the support and contact forces elsewhere) and not the
    // consistent mass's, which would leave spurious forces at free nodes.
    if run.mass_diag && inertia {
        let rho = nonlinear::explicit::cell_densities(&md.model, &md.matfield, &md.materials, occs)
            .map_err(|e| prepare_error(args, nonlinear::PrepareError::Behaviour(e)))?;
        nonlinear::explicit::Explicit::new(
            &mut asm,
            &rho,
            crate::time::explicit::ExplicitScheme::DiffCent,
            true,
        )
        .map_err(|m| args.error("RESULTAT", m))?;
        asm.set_conjugate_forces(false);
    }
    let dofs: Vec<String> = md.model.dofs.iter().map(|d| d.name().to_string()).collect();
    let nfull = asm.numbering.nfull();
    // F_ext of each load and its FONC_MULT, evaluated at each step below.
    let mut parts = Vec::new();
    for (load, mult) in loads.iter().zip(&run.load_mults) {
        let forces = md
            .load_forces(load)
            .map_err(|m| args.error("RESULTAT", m))?;
        let f = match mult {
            None => None,
            Some(m) => Some(
                super::dyna_non_line::multiplier(study, m)
                    .map_err(|e| args.error("EXCIT", format!("FONC_MULT of the loads: {e}")))?,
            ),
        };
        parts.push((forces, f));
    }
    let mults: Vec<_> = parts.iter().map(|p| p.1.clone()).collect();
    let functions = super::dyna_non_line::function_parts(md, &loads, &mults, &asm.numbering)
        .map_err(|(_, m)| args.error("EXCIT", m))?;
    let history = crate::nonlinear::loads::LoadHistory::new(parts)
        .with_functions(functions)
        .with_fields(super::dyna_non_line::field_parts(md, &loads, &mults));
    let mut fext = vec![0.0; asm.numbering.nfull()];
    let mut fint = vec![0.0; nfull];
    let mut ma = vec![0.0; nfull];
    let mut scratch = asm.initial_states();
    // A linear result (MECA_STATIQUE): its internal forces are K u with
    // the element matrices it was solved with (for MECA_HEXS8 te0392's,
    // whose hourglass forces SIEF_ELGA does not hold), so that REAC_NODA
    // is zero at free nodes and the supports' reaction elsewhere.
    let linear = if is_elas {
        Some(
            nonlinear::linear::element_stiffnesses(&asm, crate::element::hexs8::Variant::current())
                .map_err(|f| {
                    args.error(
                        "RESULTAT",
                        format!(
                            "cell {}: {}",
                            super::post_args::cell_name(f.cell),
                            f.failure
                        ),
                    )
                })?,
        )
    } else {
        None
    };
    // The laws read at their stored state, for steps without VARI_ELGA
    // (None when a finite-strain law is among them).
    let stored_laws: Option<Vec<nonlinear::CellLaw>> =
        asm.laws.iter().map(|l| l.stored_stress()).collect();
    for step in evol.steps.iter_mut() {
        if !orders.contains(&step.nume_ordre) {
            continue;
        }
        let (nume, excluded) = (step.nume_ordre, step.excluded.clone());
        let missing = |f: &str| {
            args.error(
                "RESULTAT",
                format!(
                    "NUME_ORDRE {nume} of {name} has no {f} field{}",
                    crate::result::exclusion_note(&excluded, f)
                ),
            )
        };
        let u = fields::from_nodal(
            &asm,
            &dofs,
            step.nodal.get("DEPL").ok_or_else(|| missing("DEPL"))?,
        );
        if let Some(ks) = &linear {
            nonlinear::linear::linear_forces(&asm, ks, &u, &mut fint);
        } else {
            // Without VARI_ELGA (left out by ARCHIVAGE/CHAM_EXCLU) the
            // forces come from the stored stresses alone, as code_aster's
            // ccfnrn builds them (SIEF_ELGA, DEPL): the small-strain laws
            // are read at their stored state. The finite-strain laws need
            // their internal variables (SIMO_MIEHE's elastic left
            // Cauchy-Green tensor, GDEF_LOG's stresses): an error.
            let vari = step.gauss.get("VARI_ELGA");
            let stored = match vari {
                Some(_) => None,
                None => Some(stored_laws.clone().ok_or_else(|| {
                    args.error(
                        "RESULTAT",
                        format!(
                            "NUME_ORDRE {nume} of {name} has no VARI_ELGA field{}; \
                             not implemented yet: internal forces of a finite-strain \
                             law (SIMO_MIEHE, GDEF_LOG) without its internal variables",
                            crate::result::exclusion_note(&excluded, "VARI_ELGA")
                        ),
                    )
                })?),
            };
            let points = fields::states_from_fields(
                &asm,
                step.gauss
                    .get("SIEF_ELGA")
                    .ok_or_else(|| missing("SIEF_ELGA"))?,
                vari,
            )
            .map_err(|m| args.error("RESULTAT", m))?;
            let saved = stored.map(|laws| std::mem::replace(&mut asm.laws, laws));
            let computed = asm.compute(
                &u,
                &u,
                &points,
                &mut scratch,
                // Zero time: the stored state is evaluated, not advanced.
                0.0,
                TangentKind::None,
                &mut fint,
                None,
            );
            if let Some(laws) = saved {
                asm.laws = laws;
            }
            computed.map_err(|f| {
                args.error(
                    "RESULTAT",
                    format!(
                        "NUME_ORDRE {}: cell {}: {}",
                        step.nume_ordre,
                        f.cell + 1,
                        f.failure
                    ),
                )
            })?;
        }
        if options.contains(&"FORC_NODA") {
            step.nodal
                .insert("FORC_NODA".into(), fields::nodal(&asm, &dofs, &fint));
        }
        if options.contains(&"REAC_NODA") {
            history.at(step.inst, &mut fext).map_err(|m| {
                args.error("RESULTAT", format!("NUME_ORDRE {}: {m}", step.nume_ordre))
            })?;
            // A dynamic step whose ACCE CHAM_EXCLU took out has no M·a:
            // an error, not the reaction without inertia.
            if excluded.iter().any(|f| f == "ACCE") {
                return Err(missing("ACCE"));
            }
            let a = step
                .nodal
                .get("ACCE")
                .map(|f| fields::from_nodal(&asm, &dofs, f))
                .unwrap_or_else(|| vec![0.0; nfull]);
            asm.mass_mul(&a, &mut ma);
            let reac: Vec<f64> = (0..nfull).map(|i| fint[i] - fext[i] + ma[i]).collect();
            step.nodal
                .insert("REAC_NODA".into(), fields::nodal(&asm, &dofs, &reac));
        }
    }
    Ok(())
}

/// The NUME_ORDRE of the steps the command's access keywords select
/// (every stored step without them).
fn selected_steps(
    study: &Study,
    args: &Args,
    evol: &crate::result::EvolNoli,
) -> Result<Vec<usize>, crate::diag::Diagnostic> {
    let relative = args.text("CRITERE").unwrap_or("RELATIF") == "RELATIF";
    let precision = args.real("PRECISION").unwrap_or(1e-6);
    let mut selected: Vec<usize> = Vec::new();
    let mut pick = |acc: Access| -> Result<(), String> {
        let s = evol.find(acc)?;
        selected.push(s.nume_ordre);
        Ok(())
    };
    if let Some((key, indices)) = super::post_args::nume_ordre_selection(study, args)? {
        for k in indices {
            pick(Access::NumeOrdre(k.max(0) as usize)).map_err(|m| args.error(key, m))?;
        }
    } else if args.has("INST") || args.has("LIST_INST") {
        let insts = if let Some(l) = args.concept("LIST_INST") {
            match study.concepts.data(l) {
                Some(ConceptData::ListReal(v)) => v.clone(),
                _ => return Err(args.error("LIST_INST", format!("the list {l} holds no data"))),
            }
        } else {
            args.reals("INST")
        };
        for t in insts {
            pick(Access::Inst {
                inst: t,
                precision,
                relative,
            })
            .map_err(|m| args.error("INST", m))?;
        }
    } else {
        selected = evol.steps.iter().map(|s| s.nume_ordre).collect();
    }
    Ok(selected)
}

/// The options computed from the Gauss fields and the displacement, at
/// the selected steps, on the selected cells.
///
/// CONTRAINTE: SIEF_ELNO and SIGM_ELNO extrapolated from SIEF_ELGA cell by
/// cell (`result::elno`), SIEF_NOEU and SIGM_NOEU their mean at each node
/// over the elements holding it. SIGM_* are the stress components
/// (SIXX..SIYZ) alone, SIEF_* every component of SIEF_ELGA (with the
/// hourglass stresses FSTAB* of HEXS8 models). SIEF_ELGA holds the Cauchy
/// stress whatever the law and the kinematics, so SIGM = SIEF on those
/// components, and SIGM_ELGA is SIEF_ELGA without FSTAB*.
///
/// DEFORMATION (`element::strain`): EPSI_ELGA, EPSG_ELGA, EPSL_ELGA from
/// DEPL at the SIEF_ELGA points, their *_ELNO extrapolated and *_NOEU
/// averaged as SIEF's.
///
/// CRITERES (`result::criteria`): SIEQ_ELGA from SIEF_ELGA at each point;
/// SIEQ_ELNO from SIGM_ELNO, the stress extrapolated first and the
/// criteria taken at the nodes, and SIEQ_NOEU the mean of SIEQ_ELNO at
/// each node. That is code_aster's order: its option SIEQ_ELNO reads
/// SIGM_ELNO (`RESU!SIGM_ELNO!N`, catalogue `Options/sieq_elno.py`), and
/// every *_NOEU option is the average of the *_ELNO field (`ccchno`,
/// `cescns` with 'A'). The criteria are not linear, so extrapolating
/// SIEQ_ELGA would differ wherever the stress varies in a cell. EPEQ_*
/// likewise from EPSI_ELGA and EPSI_ELNO (its EPEQ_ELNO reads
/// PDEFORR of EPSI_ELNO).
///
/// VARI_INTERNE: VARI_ELNO extrapolated from VARI_ELGA like SIEF_ELNO,
/// VARI_NOEU its mean at each node; components V1..Vn as VARI_ELGA.
///
/// TOUT/GROUP_MA/MAILLE: the fields exist on the selected cells only
/// (the Gauss fields read are cut to them first), so a *_NOEU value is the
/// mean over the selected cells holding the node, as code_aster's
/// averaging over the cells of the field's ligrel.
fn element_fields(
    study: &Study,
    args: &Args,
    name: &str,
    evol: &mut crate::result::EvolNoli,
    selected: &[usize],
) -> Result<(), crate::diag::Diagnostic> {
    let stress_opts = args.texts("CONTRAINTE");
    let crit_opts = args.texts("CRITERES");
    let vari_opts = args.texts("VARI_INTERNE");
    let strain_opts = args.texts("DEFORMATION");
    let energy_opts = args.texts("ENERGIE");
    if stress_opts.is_empty()
        && crit_opts.is_empty()
        && vari_opts.is_empty()
        && strain_opts.is_empty()
        && energy_opts.is_empty()
    {
        return Ok(());
    }
    let model_name = args.concept("MODELE").unwrap_or(&evol.model).to_string();
    let model = match study.concepts.data(&model_name) {
        Some(ConceptData::Model(m)) => m,
        _ => {
            return Err(args.error(
                "RESULTAT",
                format!(
                    "the result {name} does not say which model it was computed with: give MODELE"
                ),
            ))
        }
    };
    let mesh = super::model_args::mesh_of_model(study, args, "RESULTAT", model)?;
    let cells: Vec<bool> = if ["TOUT", "GROUP_MA", "MAILLE"].iter().any(|k| args.has(k)) {
        let mut mask = vec![false; mesh.ncells()];
        for c in super::model_args::select_cells(mesh, args)? {
            mask[c] = true;
        }
        if !(0..mesh.ncells())
            .any(|c| mask[c] && matches!(model.cells.get(c), Some(CellRole::Element(_))))
        {
            let key = ["GROUP_MA", "MAILLE", "TOUT"]
                .into_iter()
                .find(|k| args.has(k))
                .unwrap_or("GROUP_MA");
            return Err(args.error(
                key,
                format!(
                    "{} holds no cell of an element of the model {model_name}",
                    super::model_args::selection_label(args)
                ),
            ));
        }
        mask
    } else {
        vec![true; mesh.ncells()]
    };
    let elastic = if energy_opts.is_empty() {
        Vec::new()
    } else {
        elastic_constants(
            study,
            args,
            "ENERGIE",
            ElasticUse::StoredEnergy,
            evol,
            mesh,
            model,
            &cells,
        )?
    };
    let wants_epsp = strain_opts.iter().any(|o| o.starts_with("EPSP"));
    let elastic_small = if wants_epsp {
        elastic_constants(
            study,
            args,
            "DEFORMATION",
            ElasticUse::PlasticStrain,
            evol,
            mesh,
            model,
            &cells,
        )?
    } else {
        Vec::new()
    };
    // C_PLAN: EPZZ comes from σ_zz = 0 with each cell's ELAS ν
    // (element::strain::plane_stress_zz).
    let plane_stress = model
        .element_cells()
        .any(|(_, s)| s.formulation == crate::model::spec::Formulation::PlaneStress);
    let plane_nu: Vec<Option<f64>> = if plane_stress
        && (!strain_opts.is_empty() || crit_opts.iter().any(|o| o.starts_with("EPEQ")))
    {
        elastic_constants(
            study,
            args,
            "DEFORMATION",
            ElasticUse::StrainOfDepl,
            evol,
            mesh,
            model,
            &cells,
        )?
        .into_iter()
        .map(|c| match c {
            Some(CellEnergy::Small { nu, .. } | CellEnergy::SimoMiehe { nu, .. }) => Some(nu),
            None => None,
        })
        .collect()
    } else {
        Vec::new()
    };
    let restrict = |f: &GaussField| f.restricted(&cells);
    let noeu = |f: &GaussField| crate::result::elno::noeu(f, mesh);
    for step in evol.steps.iter_mut() {
        if !selected.contains(&step.nume_ordre) {
            continue;
        }
        let nume = step.nume_ordre;
        let gauss_of = |key: &str, field: &str| {
            step.gauss.get(field).map(restrict).ok_or_else(|| {
                args.error(
                    key,
                    format!(
                        "NUME_ORDRE {nume} of {name} has no {field} field to compute {} from{}",
                        args.texts(key).join(", "),
                        step.exclusion_note(field)
                    ),
                )
            })
        };
        let located =
            |key: &'static str| move |m: String| args.error(key, format!("NUME_ORDRE {nume}: {m}"));
        let elno_of = |f: &GaussField, keep: &[usize], key: &'static str| {
            crate::result::elno::elno(f, mesh, model, keep).map_err(located(key))
        };
        // computed from the borrowed fields, stored after
        let mut nodal_out: Vec<(String, NodalField)> = Vec::new();
        let mut elno_out: Vec<(String, GaussField)> = Vec::new();
        let mut gauss_out: Vec<(String, GaussField)> = Vec::new();
        let wants = |opts: &[&str], prefix: &str, loc: &str| {
            opts.contains(&format!("{prefix}_{loc}").as_str())
        };
        if !stress_opts.is_empty() || crit_opts.iter().any(|o| o.starts_with("SIEQ")) {
            let key = if stress_opts.is_empty() {
                "CRITERES"
            } else {
                "CONTRAINTE"
            };
            let sief = gauss_of(key, "SIEF_ELGA")?;
            let all: Vec<usize> = (0..sief.ncmp()).collect();
            let stress: Vec<usize> = (0..sief.ncmp())
                .filter(|&k| sief.components[k].starts_with("SI"))
                .collect();
            if stress_opts.contains(&"SIGM_ELGA") {
                gauss_out.push(("SIGM_ELGA".into(), select(&sief, &stress)));
            }
            if crit_opts.contains(&"SIEQ_ELGA") {
                let q = crate::result::criteria::sieq(&sief).map_err(located("CRITERES"))?;
                gauss_out.push(("SIEQ_ELGA".into(), q));
            }
            let sieq_nodes = wants(&crit_opts, "SIEQ", "ELNO") || wants(&crit_opts, "SIEQ", "NOEU");
            for (prefix, keep) in [("SIEF", &all), ("SIGM", &stress)] {
                let wanted =
                    wants(&stress_opts, prefix, "ELNO") || wants(&stress_opts, prefix, "NOEU");
                let for_sieq = prefix == "SIGM" && sieq_nodes;
                if !wanted && !for_sieq {
                    continue;
                }
                let elno = elno_of(&sief, keep, key)?;
                if for_sieq {
                    let q = crate::result::criteria::sieq(&elno).map_err(located("CRITERES"))?;
                    if wants(&crit_opts, "SIEQ", "NOEU") {
                        nodal_out.push(("SIEQ_NOEU".into(), noeu(&q)));
                    }
                    if wants(&crit_opts, "SIEQ", "ELNO") {
                        elno_out.push(("SIEQ_ELNO".into(), q));
                    }
                }
                if wants(&stress_opts, prefix, "NOEU") {
                    nodal_out.push((format!("{prefix}_NOEU"), noeu(&elno)));
                }
                if wants(&stress_opts, prefix, "ELNO") {
                    elno_out.push((format!("{prefix}_ELNO"), elno));
                }
            }
        }
        let epeq = crit_opts.iter().any(|o| o.starts_with("EPEQ"));
        for prefix in ["EPSI", "EPSG", "EPSL"] {
            let for_epeq = prefix == "EPSI" && epeq;
            if !strain_opts.iter().any(|o| o.starts_with(prefix)) && !for_epeq {
                continue;
            }
            let key = if for_epeq && !strain_opts.iter().any(|o| o.starts_with(prefix)) {
                "CRITERES"
            } else {
                "DEFORMATION"
            };
            let depl = step.nodal.get("DEPL").ok_or_else(|| {
                args.error(
                    key,
                    format!(
                        "NUME_ORDRE {nume} of {name} has no DEPL field to compute {prefix} from{}",
                        step.exclusion_note("DEPL")
                    ),
                )
            })?;
            let measure = crate::element::strain::Measure::of_prefix(prefix)
                .expect("the three strain prefixes have a measure");
            if plane_stress && measure == crate::element::strain::Measure::Logarithmic {
                return Err(args.not_implemented(
                    key,
                    "EPSL_* on a C_PLAN model: its EPZZ would need the logarithmic strain of \
                     σ_zz = 0, not built; EPSI_* and EPSG_* are",
                ));
            }
            let mut gauss =
                crate::element::strain::strain_field(measure, mesh, model, depl, &cells)
                    .map_err(located(key))?;
            if plane_stress {
                crate::element::strain::plane_stress_zz(&mut gauss, model, &plane_nu)
                    .map_err(located(key))?;
            }
            let all: Vec<usize> = (0..gauss.ncmp()).collect();
            if for_epeq && wants(&crit_opts, "EPEQ", "ELGA") {
                let q = crate::result::criteria::epeq(&gauss).map_err(located("CRITERES"))?;
                gauss_out.push(("EPEQ_ELGA".into(), q));
            }
            let epeq_nodes = for_epeq
                && (wants(&crit_opts, "EPEQ", "ELNO") || wants(&crit_opts, "EPEQ", "NOEU"));
            if wants(&strain_opts, prefix, "ELNO")
                || wants(&strain_opts, prefix, "NOEU")
                || epeq_nodes
            {
                let elno = elno_of(&gauss, &all, key)?;
                if epeq_nodes {
                    let q = crate::result::criteria::epeq(&elno).map_err(located("CRITERES"))?;
                    if wants(&crit_opts, "EPEQ", "NOEU") {
                        nodal_out.push(("EPEQ_NOEU".into(), noeu(&q)));
                    }
                    if wants(&crit_opts, "EPEQ", "ELNO") {
                        elno_out.push(("EPEQ_ELNO".into(), q));
                    }
                }
                if wants(&strain_opts, prefix, "NOEU") {
                    nodal_out.push((format!("{prefix}_NOEU"), noeu(&elno)));
                }
                if wants(&strain_opts, prefix, "ELNO") {
                    elno_out.push((format!("{prefix}_ELNO"), elno));
                }
            }
            if wants(&strain_opts, prefix, "ELGA") {
                gauss_out.push((format!("{prefix}_ELGA"), gauss));
            }
        }
        // An option family's ELGA field, with its ELNO extrapolation and
        // NOEU mean when asked.
        let mut family_fields = |opts: &[&str],
                                 prefix: &str,
                                 key: &'static str,
                                 g: GaussField|
         -> Result<(), crate::diag::Diagnostic> {
            if wants(opts, prefix, "ELNO") || wants(opts, prefix, "NOEU") {
                let all: Vec<usize> = (0..g.ncmp()).collect();
                let elno = elno_of(&g, &all, key)?;
                if wants(opts, prefix, "NOEU") {
                    nodal_out.push((format!("{prefix}_NOEU"), noeu(&elno)));
                }
                if wants(opts, prefix, "ELNO") {
                    elno_out.push((format!("{prefix}_ELNO"), elno));
                }
            }
            if wants(opts, prefix, "ELGA") {
                gauss_out.push((format!("{prefix}_ELGA"), g));
            }
            Ok(())
        };
        if wants_epsp {
            let depl = step.nodal.get("DEPL").ok_or_else(|| {
                args.error(
                    "DEFORMATION",
                    format!(
                        "NUME_ORDRE {nume} of {name} has no DEPL field to compute EPSP from{}",
                        step.exclusion_note("DEPL")
                    ),
                )
            })?;
            let mut eps = crate::element::strain::strain_field(
                crate::element::strain::Measure::of_prefix("EPSI").expect("EPSI has a measure"),
                mesh,
                model,
                depl,
                &cells,
            )
            .map_err(located("DEFORMATION"))?;
            if plane_stress {
                crate::element::strain::plane_stress_zz(&mut eps, model, &plane_nu)
                    .map_err(located("DEFORMATION"))?;
            }
            let sief = gauss_of("DEFORMATION", "SIEF_ELGA")?;
            let p = crate::result::energy::epsp(&eps, &sief, &elastic_small)
                .map_err(located("DEFORMATION"))?;
            family_fields(&strain_opts, "EPSP", "DEFORMATION", p)?;
        }
        if !energy_opts.is_empty() {
            let w = enel_of_step(args, "ENERGIE", name, step, mesh, model, &cells, &elastic)?;
            family_fields(&energy_opts, "ENEL", "ENERGIE", w)?;
        }
        if !vari_opts.is_empty() {
            let vari = gauss_of("VARI_INTERNE", "VARI_ELGA")?;
            let all: Vec<usize> = (0..vari.ncmp()).collect();
            let elno = elno_of(&vari, &all, "VARI_INTERNE")?;
            if vari_opts.contains(&"VARI_NOEU") {
                nodal_out.push(("VARI_NOEU".into(), noeu(&elno)));
            }
            if vari_opts.contains(&"VARI_ELNO") {
                elno_out.push(("VARI_ELNO".into(), elno));
            }
        }
        for (n, f) in nodal_out {
            step.nodal.insert(n, f);
        }
        for (n, f) in elno_out {
            step.elno.insert(n, f);
        }
        for (n, f) in gauss_out {
            step.gauss.insert(n, f);
        }
    }
    Ok(())
}

/// How ENEL_* takes the energy of each selected element cell (its ELAS E
/// and ν): code_aster's `enelpg` under PETIT and PETIT_REAC (½ σ:S:σ) and
/// for VMIS_ISOT_* in SIMO_MIEHE (the stored energy, from J and b̄ᵉ; both
/// laws share the variables of `law::simo_miehe`).
/// A cell computed in GDEF_LOG, whose energy code_aster takes from its
/// own internal variables (the stress T of the log formalism, which this
/// law does not keep), is refused.
/// What the elastic constants of [`elastic_constants`] are for: which
/// kinematics each use can take.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElasticUse {
    /// The stored elastic energy of the stress (CALC_CHAMP ENERGIE,
    /// POST_ELEM ENER_ELAS, the balance's split): PETIT, PETIT_REAC, and
    /// VMIS_ISOT_* in SIMO_MIEHE.
    StoredEnergy,
    /// The plastic strain ε − S:σ (CALC_CHAMP EPSP_*): PETIT, PETIT_REAC.
    PlasticStrain,
    /// The elastic energy of the small strain of DEPL (POST_ELEM ENER_POT),
    /// whatever the law and the kinematics of the computation.
    StrainOfDepl,
}

#[allow(clippy::too_many_arguments)]
pub fn elastic_constants(
    study: &Study,
    args: &Args,
    key: &str,
    usage: ElasticUse,
    evol: &crate::result::EvolNoli,
    mesh: &crate::mesh::Mesh,
    model: &crate::model::Model,
    cells: &[bool],
) -> Result<Vec<Option<CellEnergy>>, crate::diag::Diagnostic> {
    let mat_name = args.concept("CHAM_MATER").unwrap_or(&evol.cham_mater);
    let matfield = match study.concepts.data(mat_name) {
        Some(ConceptData::MaterialField(m)) => m,
        _ => {
            return Err(args.error(
                key,
                format!(
                    "no material field for the elastic energy: the result does not name one{}; give CHAM_MATER",
                    if mat_name.is_empty() { String::new() } else { format!(" that holds data ({mat_name})") }
                ),
            ))
        }
    };
    let mut out = vec![None; mesh.ncells()];
    for c in 0..mesh.ncells() {
        if !cells[c] || !matches!(model.cells.get(c), Some(CellRole::Element(_))) {
            continue;
        }
        let cell = || super::post_args::cell_name(c);
        let mut simo_miehe = false;
        if let Some(Some((rel, def))) = evol.comportement.get(c) {
            let energy = usage == ElasticUse::StoredEnergy;
            simo_miehe = energy && def == "SIMO_MIEHE";
            if usage != ElasticUse::StrainOfDepl
                && def != "PETIT"
                && def != "PETIT_REAC"
                && !(simo_miehe && rel.starts_with("VMIS_ISOT"))
            {
                return Err(args.not_implemented(
                    key,
                    &format!(
                        "{} of cell {} computed with RELATION='{rel}', DEFORMATION='{def}' (PETIT, PETIT_REAC{})",
                        if energy { "the elastic energy" } else { "EPSP" },
                        cell(),
                        if energy { ", and VMIS_ISOT_LINE/VMIS_ISOT_TRAC/VMIS_ISOT_PUIS in SIMO_MIEHE" } else { "" }
                    ),
                ));
            }
        }
        let name = matfield
            .cell_material
            .get(c)
            .cloned()
            .flatten()
            .ok_or_else(|| {
                args.error(
                    key,
                    format!("cell {} has no material in {mat_name}", cell()),
                )
            })?;
        let mat = match study.concepts.data(&name) {
            Some(ConceptData::Material(m)) => m,
            _ => return Err(args.error(key, format!("the material {name} holds no data"))),
        };
        match (mat.get("ELAS", "E"), mat.get("ELAS", "NU")) {
            (Some(e), Some(nu)) if simo_miehe => {
                out[c] = Some(CellEnergy::SimoMiehe {
                    e,
                    nu,
                    be: simo_miehe_be(),
                })
            }
            (Some(e), Some(nu)) => out[c] = Some(CellEnergy::Small { e, nu }),
            _ => {
                return Err(args.error(
                    key,
                    format!(
                        "the material {name} of cell {} has no ELAS E and NU",
                        cell()
                    ),
                ))
            }
        }
    }
    Ok(out)
}

/// The ENEL_ELGA field of one step on the cells `cells` (the density
/// TOTALE of `result::energy::enel` at the SIEF_ELGA points), from the
/// per-cell laws of [`elastic_constants`]: CALC_CHAMP's ENERGIE and
/// POST_ELEM's ENER_ELAS both take it from here. Errors name `key`.
#[allow(clippy::too_many_arguments)]
pub fn enel_of_step(
    args: &Args,
    key: &'static str,
    name: &str,
    step: &crate::result::Step,
    mesh: &crate::mesh::Mesh,
    model: &crate::model::Model,
    cells: &[bool],
    elastic: &[Option<CellEnergy>],
) -> Result<GaussField, crate::diag::Diagnostic> {
    let nume = step.nume_ordre;
    let located = |m: String| args.error(key, format!("NUME_ORDRE {nume}: {m}"));
    let gauss_of = |field: &str| {
        step.gauss
            .get(field)
            .map(|f| f.restricted(cells))
            .ok_or_else(|| {
                args.error(
                    key,
                    format!(
                        "NUME_ORDRE {nume} of {name} has no {field} field for the elastic energy{}",
                        step.exclusion_note(field)
                    ),
                )
            })
    };
    let sief = gauss_of("SIEF_ELGA")?;
    let finite = elastic
        .iter()
        .any(|l| matches!(l, Some(CellEnergy::SimoMiehe { .. })));
    let (jac, vari) = if finite {
        let depl = step.nodal.get("DEPL").ok_or_else(|| {
            args.error(
                key,
                format!("NUME_ORDRE {nume} of {name} has no DEPL field for the SIMO_MIEHE energy"),
            )
        })?;
        let jac =
            crate::element::strain::jacobian_field(mesh, model, depl, cells).map_err(located)?;
        (Some(jac), Some(gauss_of("VARI_ELGA")?))
    } else {
        (None, None)
    };
    crate::result::energy::enel(&sief, jac.as_ref(), vari.as_ref(), elastic).map_err(located)
}

/// The VARI_ELGA columns of b̄ᵉ_xx − 1, b̄ᵉ_yy − 1, b̄ᵉ_zz − 1 of
/// VMIS_ISOT_LINE, VMIS_ISOT_TRAC and VMIS_ISOT_PUIS in SIMO_MIEHE, from the law's
/// variable names.
fn simo_miehe_be() -> [usize; 3] {
    let names = crate::law::simo_miehe::METADATA.internal_variables;
    let at = |n: &str| names.iter().position(|v| *v == n).unwrap_or(usize::MAX);
    [at("BE_XX"), at("BE_YY"), at("BE_ZZ")]
}

/// The components `keep` (by index) of a Gauss field, same cells and
/// points.
fn select(f: &crate::result::GaussField, keep: &[usize]) -> crate::result::GaussField {
    let nc = f.ncmp();
    let values = f
        .values
        .chunks(nc.max(1))
        .flat_map(|row| keep.iter().map(move |&k| row[k]))
        .collect();
    crate::result::GaussField {
        components: keep.iter().map(|&k| f.components[k].clone()).collect(),
        offsets: f
            .offsets
            .iter()
            .map(|&o| o.checked_div(nc).unwrap_or(0) * keep.len())
            .collect(),
        values,
    }
}
