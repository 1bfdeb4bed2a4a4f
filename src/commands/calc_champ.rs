//! CALC_CHAMP: derived fields of a result (stresses at nodes, nodal forces...).

use super::blocks::*;
use super::dyna_non_line::{loads_of, model_data, prepare_error};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::{ConceptData, ConceptType as C};
use crate::law::TangentKind;
use crate::model::MechLoad;
use crate::nonlinear::{self, fields, Occurrence};
use crate::result::Access;
use crate::study::Study;

pub fn def() -> CommandDef {
    let mut kws = vec![
        concept("RESULTAT", &[C::EvolNoli])
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
                concept("CHARGE", &[C::CharMeca]).required().kw(),
                concept("FONC_MULT", &[C::Fonction]).kw(),
                text("TYPE_CHARGE")
                    .into(&["FIXE_CSTE", "SUIV", "DIDI"])
                    .default(t("FIXE_CSTE"))
                    .kw(),
            ],
        )
        .many()
        .doc("loads for REAC_NODA; absent: those stored in the result")
        .kw(),
        text("TOUT_ORDRE").into(&["OUI"]).kw(),
        int("NUME_ORDRE").many().kw(),
        real("INST").many().kw(),
        concept("LIST_INST", &[C::Listr8]).kw(),
    ];
    kws.extend(critere_precision(1e-6));
    kws.extend([
        tout(),
        group_ma(),
        maille(),
        text("CONTRAINTE")
            .many()
            .into(&["SIEF_ELNO", "SIGM_ELNO", "SIEF_NOEU", "SIGM_NOEU", "SIGM_ELGA"])
            .doc("stress fields: *_ELNO extrapolated from SIEF_ELGA cell by cell, *_NOEU their mean over the cells at each node; SIGM_* the stress components SIXX..SIYZ only (SIGM_ELGA: those of SIEF_ELGA)")
            .kw(),
        text("DEFORMATION")
            .many()
            .into(&["EPSI_ELGA", "EPSI_ELNO", "EPSI_NOEU", "EPSL_ELGA", "EPSL_ELNO", "EPSL_NOEU"])
            .doc("strain fields (not implemented)")
            .kw(),
        text("CRITERES")
            .many()
            .into(&["SIEQ_ELGA", "SIEQ_ELNO", "SIEQ_NOEU", "EPEQ_ELGA", "EPEQ_ELNO", "EPEQ_NOEU"])
            .doc("equivalent stresses VMIS, TRESCA, PRIN_1..3, VMIS_SG, VECT_1_X..VECT_3_Z, TRSIG, TRIAX: SIEQ_ELGA of SIEF_ELGA, SIEQ_ELNO of SIGM_ELNO, SIEQ_NOEU the mean of SIEQ_ELNO at each node (EPEQ_* not implemented)")
            .kw(),
        text("VARI_INTERNE")
            .many()
            .into(&["VARI_ELNO", "VARI_NOEU"])
            .doc("internal variables V1..Vn at nodes: VARI_ELNO extrapolated from VARI_ELGA cell by cell, VARI_NOEU its mean at each node")
            .kw(),
        text("ENERGIE")
            .many()
            .into(&["ENEL_ELGA", "ENEL_ELNO", "ENEL_NOEU", "ETOT_ELGA", "ETOT_ELNO", "ETOT_NOEU"])
            .kw(),
        text("FORCE")
            .many()
            .into(&["FORC_NODA", "REAC_NODA"])
            .doc("FORC_NODA: internal nodal forces; REAC_NODA: minus applied loads, plus M.a, i.e. support and contact reactions")
            .kw(),
        info(),
        titre(),
    ]);
    let spec = command("CALC_CHAMP", Produces::Concept(C::EvolNoli), kws)
        .reentrant(Reentrant::Optional("RESULTAT"))
        .rules(vec![
            exclus(&["TOUT_ORDRE", "NUME_ORDRE", "INST", "LIST_INST"]),
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
/// F_ext + M·ACCE, F_ext being the PESANTEUR of the result's loads (the
/// only load with an F_ext), so at free nodes it is the dynamic residual
/// (≈ 0, without contact forces) and at supports the support reaction.
fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    let name = args.concept("RESULTAT").unwrap_or("").to_string();
    let mut evol = match study.concepts.data(&name) {
        Some(ConceptData::Result(r)) => (**r).clone(),
        _ => return Err(args.error("RESULTAT", format!("the result {name} holds no data"))),
    };
    for key in ["DEFORMATION", "ENERGIE"] {
        if args.has(key) {
            return Err(args.not_implemented(key, ""));
        }
    }
    if let Some(e) = args
        .texts("CRITERES")
        .iter()
        .find(|c| c.starts_with("EPEQ"))
    {
        return Err(args.not_implemented(
            "CRITERES",
            &format!("{e} (no strain field is built yet); SIEQ_ELGA, SIEQ_ELNO and SIEQ_NOEU are computed"),
        ));
    }
    for key in ["TOUT", "GROUP_MA", "MAILLE"] {
        if args.given(key) {
            return Err(args.not_implemented(key, "the whole model is always used"));
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
    let md = model_data(
        study,
        args,
        ("MODELE", &model_name),
        ("CHAM_MATER", &mat_name),
    )?;
    let (load_names, load_mults): (Vec<String>, Vec<Option<String>>) = if args.has("EXCIT") {
        for ex in args.facts("EXCIT") {
            if ex.text("TYPE_CHARGE").unwrap_or("FIXE_CSTE") != "FIXE_CSTE" {
                return Err(ex.not_implemented("TYPE_CHARGE", "only FIXE_CSTE loads"));
            }
        }
        args.facts("EXCIT")
            .iter()
            .map(|e| {
                (
                    e.concept("CHARGE").unwrap_or("").to_string(),
                    e.concept("FONC_MULT").map(str::to_string),
                )
            })
            .unzip()
    } else {
        let mut mults = evol.load_mults.clone();
        mults.resize(evol.loads.len(), None);
        (evol.loads.clone(), mults)
    };
    let loads = loads_of(study, args, "EXCIT", &load_names)?;
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
    let refs: Vec<&MechLoad> = loads.iter().collect();
    // A STAT_NON_LINE result has no ACCE: no M.a term, and no density is
    // needed (REAC_NODA = FORC_NODA - F_ext).
    let inertia = evol.steps.iter().any(|s| s.nodal.contains_key("ACCE"));
    let (mut asm, _) = nonlinear::discretize_for(
        &md.mesh,
        &md.model,
        &md.matfield,
        &md.materials,
        &occs,
        &refs,
        inertia,
    )
    .map_err(|e| prepare_error(args, e))?;
    // A result of an explicit run with MASS_DIAG='OUI': M·a with the run's
    // lumped (HRZ) mass, so that REAC_NODA is that run's residual (zero at
    // free nodes, the support and contact forces elsewhere) and not the
    // consistent mass's, which would leave spurious forces at free nodes.
    if evol.mass_diag {
        let rho =
            nonlinear::explicit::cell_densities(&md.model, &md.matfield, &md.materials, &occs)
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
    for (load, mult) in loads.iter().zip(&load_mults) {
        let forces = md
            .load_forces(load)
            .map_err(|m| args.error("RESULTAT", m))?;
        let f = match mult {
            None => None,
            Some(m) => match study.concepts.data(m) {
                Some(ConceptData::Function(f)) => Some((**f).clone()),
                _ => {
                    return Err(args.error(
                        "EXCIT",
                        format!("the FONC_MULT {m} of the loads holds no function"),
                    ))
                }
            },
        };
        parts.push((forces, f));
    }
    let mults: Vec<_> = parts.iter().map(|p| p.1.clone()).collect();
    let functions = super::dyna_non_line::function_parts(&md, &loads, &mults, &asm.numbering)
        .map_err(|(_, m)| args.error("EXCIT", m))?;
    let history = crate::nonlinear::loads::LoadHistory::new(parts).with_functions(functions);
    let mut fext = vec![0.0; asm.numbering.nfull()];
    let mut fint = vec![0.0; nfull];
    let mut ma = vec![0.0; nfull];
    let mut scratch = asm.initial_states();
    for step in evol.steps.iter_mut() {
        if !selected.contains(&step.nume_ordre) {
            continue;
        }
        let missing = |f: &str| {
            args.error(
                "RESULTAT",
                format!("NUME_ORDRE {} of {name} has no {f} field", step.nume_ordre),
            )
        };
        let u = fields::from_nodal(
            &asm,
            &dofs,
            step.nodal.get("DEPL").ok_or_else(|| missing("DEPL"))?,
        );
        let points = fields::states_from_gauss(
            &asm,
            step.gauss
                .get("SIEF_ELGA")
                .ok_or_else(|| missing("SIEF_ELGA"))?,
            step.gauss
                .get("VARI_ELGA")
                .ok_or_else(|| missing("VARI_ELGA"))?,
        )
        .map_err(|m| args.error("RESULTAT", m))?;
        asm.compute(
            &u,
            &u,
            &points,
            &mut scratch,
            // Zero time: the stored state is evaluated, not advanced.
            0.0,
            TangentKind::None,
            &mut fint,
            None,
        )
        .map_err(|f| {
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
        if options.contains(&"FORC_NODA") {
            step.nodal
                .insert("FORC_NODA".into(), fields::nodal(&asm, &dofs, &fint));
        }
        if options.contains(&"REAC_NODA") {
            history.at(step.inst, &mut fext).map_err(|m| {
                args.error("RESULTAT", format!("NUME_ORDRE {}: {m}", step.nume_ordre))
            })?;
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
    Ok(Some(ConceptData::Result(Box::new(evol))))
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
    if args.has("NUME_ORDRE") {
        for k in args.ints("NUME_ORDRE") {
            pick(Access::NumeOrdre(k.max(0) as usize)).map_err(|m| args.error("NUME_ORDRE", m))?;
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

/// The options computed from the Gauss fields, at the selected steps.
///
/// CONTRAINTE: SIEF_ELNO and SIGM_ELNO extrapolated from SIEF_ELGA cell by
/// cell (`result::elno`), SIEF_NOEU and SIGM_NOEU their mean at each node
/// over the elements holding it. SIGM_* are the stress components
/// (SIXX..SIYZ) alone, SIEF_* every component of SIEF_ELGA (with the
/// hourglass stresses FSTAB* of HEXS8 models). SIEF_ELGA holds the Cauchy
/// stress whatever the law and the kinematics, so SIGM = SIEF on those
/// components, and SIGM_ELGA is SIEF_ELGA without FSTAB*.
///
/// CRITERES (`result::criteria`): SIEQ_ELGA from SIEF_ELGA at each point;
/// SIEQ_ELNO from SIGM_ELNO, the stress extrapolated first and the
/// criteria taken at the nodes, and SIEQ_NOEU the mean of SIEQ_ELNO at
/// each node. That is code_aster's order: its option SIEQ_ELNO reads
/// SIGM_ELNO (`RESU!SIGM_ELNO!N`, catalogue `Options/sieq_elno.py`), and
/// every *_NOEU option is the average of the *_ELNO field (`ccchno`,
/// `cescns` with 'A'). The criteria are not linear, so extrapolating
/// SIEQ_ELGA would differ wherever the stress varies in a cell.
///
/// VARI_INTERNE: VARI_ELNO extrapolated from VARI_ELGA like SIEF_ELNO,
/// VARI_NOEU its mean at each node; components V1..Vn as VARI_ELGA.
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
    let at_nodes = stress_opts
        .iter()
        .chain(&crit_opts)
        .chain(&vari_opts)
        .any(|o| !o.ends_with("_ELGA"));
    if stress_opts.is_empty() && crit_opts.is_empty() && vari_opts.is_empty() {
        return Ok(());
    }
    // the model and its mesh, for the extrapolation to the nodes only
    let geometry = if at_nodes {
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
        Some((mesh, model))
    } else {
        None
    };
    for step in evol.steps.iter_mut() {
        if !selected.contains(&step.nume_ordre) {
            continue;
        }
        let nume = step.nume_ordre;
        let gauss_of = |key: &str, field: &str| {
            step.gauss.get(field).ok_or_else(|| {
                args.error(
                    key,
                    format!(
                        "NUME_ORDRE {nume} of {name} has no {field} field to compute {} from",
                        args.texts(key).join(", ")
                    ),
                )
            })
        };
        let no_model = || {
            args.error(
                "RESULTAT",
                format!("no model to extrapolate {name} to the nodes"),
            )
        };
        let located =
            |key: &'static str| move |m: String| args.error(key, format!("NUME_ORDRE {nume}: {m}"));
        // computed from the borrowed Gauss fields, stored after
        let mut nodal_out = Vec::new();
        let mut elno_out = Vec::new();
        let mut gauss_out = Vec::new();
        if !stress_opts.is_empty() || !crit_opts.is_empty() {
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
                gauss_out.push(("SIGM_ELGA", select(sief, &stress)));
            }
            if crit_opts.contains(&"SIEQ_ELGA") {
                let q = crate::result::criteria::sieq(sief).map_err(located("CRITERES"))?;
                gauss_out.push(("SIEQ_ELGA", q));
            }
            let sieq_nodes = crit_opts
                .iter()
                .any(|o| o.starts_with("SIEQ_") && o != &"SIEQ_ELGA");
            for (elno_name, noeu_name, keep) in [
                ("SIEF_ELNO", "SIEF_NOEU", &all),
                ("SIGM_ELNO", "SIGM_NOEU", &stress),
            ] {
                let wanted = stress_opts.contains(&elno_name) || stress_opts.contains(&noeu_name);
                let for_sieq = elno_name == "SIGM_ELNO" && sieq_nodes;
                if !wanted && !for_sieq {
                    continue;
                }
                let (mesh, model) = geometry.ok_or_else(no_model)?;
                let elno =
                    crate::result::elno::elno(sief, mesh, model, keep).map_err(located(key))?;
                if for_sieq {
                    let q = crate::result::criteria::sieq(&elno).map_err(located("CRITERES"))?;
                    if crit_opts.contains(&"SIEQ_NOEU") {
                        nodal_out.push(("SIEQ_NOEU", crate::result::elno::noeu(&q, mesh)));
                    }
                    if crit_opts.contains(&"SIEQ_ELNO") {
                        elno_out.push(("SIEQ_ELNO", q));
                    }
                }
                if stress_opts.contains(&noeu_name) {
                    nodal_out.push((noeu_name, crate::result::elno::noeu(&elno, mesh)));
                }
                if stress_opts.contains(&elno_name) {
                    elno_out.push((elno_name, elno));
                }
            }
        }
        if !vari_opts.is_empty() {
            let vari = gauss_of("VARI_INTERNE", "VARI_ELGA")?;
            let (mesh, model) = geometry.ok_or_else(no_model)?;
            let all: Vec<usize> = (0..vari.ncmp()).collect();
            let elno = crate::result::elno::elno(vari, mesh, model, &all)
                .map_err(located("VARI_INTERNE"))?;
            if vari_opts.contains(&"VARI_NOEU") {
                nodal_out.push(("VARI_NOEU", crate::result::elno::noeu(&elno, mesh)));
            }
            if vari_opts.contains(&"VARI_ELNO") {
                elno_out.push(("VARI_ELNO", elno));
            }
        }
        for (n, f) in nodal_out {
            step.nodal.insert(n.to_string(), f);
        }
        for (n, f) in elno_out {
            step.elno.insert(n.to_string(), f);
        }
        for (n, f) in gauss_out {
            step.gauss.insert(n.to_string(), f);
        }
    }
    Ok(())
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
