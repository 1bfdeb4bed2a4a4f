//! MECA_STATIQUE: linear elastic statics.
//!
//! Why its own command and engine path: users verify a model linearly
//! (patch tests, cantilevers, self-weight) with MECA_STATIQUE, whose
//! result (evol_elas) is K u = F at each instant with code_aster's linear
//! element matrices (RIGI_MECA). The preparation is STAT_NON_LINE's (the
//! model data, the loads and their FONC_MULT, the numbering with
//! Dirichlet elimination, the rigid-mode check); the solve is
//! `nonlinear::linear`, because MECA_HEXS8's linear matrix (te0392) is not
//! the tangent of its nonlinear element.

use super::blocks::*;
use super::dyna_non_line::{
    cell_comportement, load_history, loads_of, model_data, prepare_error, ModelData,
};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::{ConceptData, ConceptType as C};
use crate::diag::Diagnostic;
use crate::element::hexs8::Variant;
use crate::model::MechLoad;
use crate::nonlinear::linear::{LinearError, LinearStatics};
use crate::nonlinear::{self, fields, Occurrence};
use crate::result::{EvolNoli, Step};
use crate::study::Study;

/// The largest relative residual |K u − F| / max(|F|, |K u|) accepted
/// from the direct solve: far above round-off on any study this engine
/// runs (1e-13 to 1e-15), far below what a user would read.
const MAX_RESIDUAL: f64 = 1e-8;

pub fn def() -> CommandDef {
    let spec = command(
        "MECA_STATIQUE",
        Produces::Concept(C::EvolElas),
        vec![
            concept("RESULTAT", &[C::EvolElas])
                .doc("the result completed in place (reuse=): instants already stored are not computed again")
                .kw(),
            concept("MODELE", &[C::Modele]).required().kw(),
            concept("CHAM_MATER", &[C::ChamMater])
                .doc("material field: ELAS (E, NU; RHO for PESANTEUR) of every element")
                .kw(),
            concept("CARA_ELEM", &[C::CaraElem])
                .doc("structural elements (not implemented yet)")
                .kw(),
            titre(),
            fact(
                "EXCIT",
                vec![
                    concept("CHARGE", &[C::CharMeca, C::CharCineMeca]).required().kw(),
                    concept("FONC_MULT", &[C::Fonction, C::Formule])
                        .doc("multiplier of the load, a function (or FORMULE) of INST evaluated at each instant")
                        .kw(),
                    text("TYPE_CHARGE")
                        .into(&["FIXE_CSTE"])
                        .default(t("FIXE_CSTE"))
                        .kw(),
                ],
            )
            .many()
            .required()
            .doc("loads and boundary conditions")
            .kw(),
            real("INST")
                .doc("the instant of a single computation (absent: 0)")
                .kw(),
            concept("LIST_INST", &[C::Listr8])
                .doc("the instants computed, NUME_ORDRE 1, 2, ... in the list's order")
                .kw(),
            real("INST_FIN")
                .doc("the instants of LIST_INST after it are not computed")
                .kw(),
            text("OPTION")
                .into(&["SIEF_ELGA", "SANS"])
                .default(t("SIEF_ELGA"))
                .doc("SIEF_ELGA: the stress at the Gauss points is stored with DEPL; SANS: DEPL only")
                .kw(),
            c_solveur(),
            info(),
        ],
    )
    .reentrant(Reentrant::Optional("RESULTAT"))
    .rules(vec![exclus(&["INST", "LIST_INST"])])
    .doc("Solves linear elastic statics K u = F at each instant (evol_elas): code_aster's linear element matrices (RIGI_MECA), the loads with their FONC_MULT at the instant.");
    CommandDef { spec, exec }
}

fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    if args.given("CARA_ELEM") {
        return Err(args.not_implemented(
            "CARA_ELEM",
            "structural elements (beams, plates, discrete elements); the continuum elements of the model need CHAM_MATER only",
        ));
    }
    let model_name = args.concept("MODELE").unwrap_or("").to_string();
    let Some(mat_name) = args.concept("CHAM_MATER").map(str::to_string) else {
        return Err(args.error(
            "CHAM_MATER",
            "CHAM_MATER is needed: the elements of the model take E and NU from their material's ELAS",
        ));
    };
    let md = model_data(
        study,
        args,
        ("MODELE", &model_name),
        ("CHAM_MATER", &mat_name),
    )?;
    check_elastic(args, &md, &mat_name)?;
    let mut load_names = Vec::new();
    let mut load_mults = Vec::new();
    for ex in args.facts("EXCIT") {
        load_names.push(ex.concept("CHARGE").unwrap_or("").to_string());
        load_mults.push(ex.concept("FONC_MULT").map(str::to_string));
    }
    let loads = loads_of(study, args, "EXCIT", &load_names)?;
    let instants = instants_of(study, args)?;
    // Linear elasticity everywhere, whatever else the materials hold.
    let occs = vec![Occurrence {
        cells: None,
        relation: "ELAS".into(),
        deformation: "PETIT".into(),
        controls: Default::default(),
    }];
    let refs: Vec<&MechLoad> = loads.iter().collect();
    let (asm, _) = nonlinear::discretize_for(
        &md.mesh,
        &md.model,
        &md.matfield,
        &md.materials,
        &occs,
        &refs,
        false,
    )
    .map_err(|e| match e {
        nonlinear::PrepareError::Behaviour(b) => args.error("CHAM_MATER", b.message),
        other => prepare_error(args, other),
    })?;
    let free = nonlinear::rigid::unheld_modes(&md.mesh, &md.model, &asm.numbering);
    if !free.is_empty() {
        return Err(args.error(
            "EXCIT",
            format!(
                "the stiffness is singular: the rigid-body mode(s) {} of the model are held by no DDL_IMPO of the loads (a static equilibrium needs supports); add the missing DDL_IMPO",
                free.iter().map(|m| format!("({m})")).collect::<Vec<_>>().join(", ")
            ),
        ));
    }
    let all_instants: Vec<f64> = instants.iter().map(|&(_, t)| t).collect();
    let history = load_history(
        args,
        &md,
        &loads,
        &load_mults,
        study,
        &all_instants,
        &asm.numbering,
    )?;
    let mut evol = match result.and_then(|r| study.concepts.data(r)) {
        Some(ConceptData::Result(r)) if args.concept("RESULTAT").is_some() => (**r).clone(),
        _ => EvolNoli::default(),
    };
    evol.mesh = md.model.mesh.clone();
    evol.model = model_name;
    evol.cham_mater = mat_name;
    evol.start_run(crate::result::RunData {
        loads: load_names,
        load_mults,
        mass_diag: false,
    });
    evol.comportement = cell_comportement(&md.model, &occs);

    let engine_error = |e: LinearError| match e {
        LinearError::Cell(c) => args.error(
            "MODELE",
            format!(
                "cell {}: {}",
                super::post_args::cell_name(c.cell),
                c.failure
            ),
        ),
        other => args.error("EXCIT", other.to_string()),
    };
    let mut linear = LinearStatics::new(asm, Variant::current()).map_err(engine_error)?;
    let dofs: Vec<String> = md.model.dofs.iter().map(|d| d.name().to_string()).collect();
    let ncells = md.mesh.ncells();
    let with_stress = args.text("OPTION").unwrap_or("SIEF_ELGA") == "SIEF_ELGA";
    // With reuse=, the NUME_ORDRE already stored are kept (mestat).
    let todo: Vec<(usize, f64)> = instants
        .iter()
        .copied()
        .filter(|&(nume, _)| !evol.steps.iter().any(|s| s.nume_ordre == nume))
        .collect();
    study.log(format!(
        "  MECA_STATIQUE: {} equations ({} imposed dofs), {} elements, {} instant(s) to compute of {} from {:e} to {:e}",
        linear.asm.numbering.neq(),
        linear.asm.numbering.imposed.len(),
        linear.asm.elements.len(),
        todo.len(),
        instants.len(),
        all_instants[0],
        all_instants[all_instants.len() - 1]
    ));
    if args.has("SOLVEUR") {
        study.log(format!("  {}", super::blocks::SOLVEUR_NOTE));
    }
    linear.check = super::blocks::singularity_check(args);
    let mut fext = vec![0.0; linear.asm.numbering.nfull()];
    for &(nume, t) in &todo {
        let at = |m: String| args.error("EXCIT", format!("INST = {t:e}: {m}"));
        history.at(t, &mut fext).map_err(at)?;
        history
            .set_imposed(t, &mut linear.asm.numbering.imposed)
            .map_err(at)?;
        let sol = linear.solve(&fext).map_err(engine_error)?;
        if sol.residual > MAX_RESIDUAL {
            return Err(args.error(
                "EXCIT",
                format!(
                    "INST = {t:e}: the solution leaves a relative residual |K u - F| / |F| = {:.3e} (more than {MAX_RESIDUAL:e}): the stiffness is nearly singular (a mechanism, or elements of very different stiffness)",
                    sol.residual
                ),
            ));
        }
        study.log(format!(
            "  NUME_ORDRE {nume}, INST = {t:e}: relative residual |K u - F| / |F| = {:.3e}",
            sol.residual
        ));
        let mut step = Step {
            nume_ordre: nume,
            inst: t,
            run: evol.current_run(),
            ..Step::default()
        };
        step.nodal
            .insert("DEPL".into(), fields::nodal(&linear.asm, &dofs, &sol.u));
        if with_stress {
            let states = linear.stresses(&sol.u).map_err(engine_error)?;
            let (sief, _) = fields::gauss(&linear.asm, ncells, &states);
            step.gauss.insert("SIEF_ELGA".into(), sief);
        }
        evol.steps.push(step);
    }
    if let Some(alarm) = linear.tolerated_singularity() {
        study.log(format!("  {alarm}"));
    }
    evol.steps.sort_by_key(|s| s.nume_ordre);
    Ok(Some(ConceptData::Result(Box::new(evol))))
}

/// Every material of an element cell has ELAS E and NU: MECA_STATIQUE is
/// linear elastic whatever relation the material also describes.
fn check_elastic(args: &Args, md: &ModelData, mat_name: &str) -> Result<(), Diagnostic> {
    for (name, mat) in &md.materials {
        let used = md.model.element_cells().any(|(c, _)| {
            md.matfield.cell_material.get(c).and_then(|m| m.as_deref()) == Some(name.as_str())
        });
        if !used {
            continue;
        }
        let missing: Vec<&str> = ["E", "NU"]
            .into_iter()
            .filter(|p| mat.get("ELAS", p).is_none())
            .collect();
        if !missing.is_empty() {
            return Err(args.error(
                "CHAM_MATER",
                format!(
                    "the material {name} of {mat_name} has no ELAS {}: MECA_STATIQUE is linear elastic and reads E and NU of ELAS (DEFI_MATERIAU ELAS=_F(E=..., NU=...))",
                    missing.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

/// (NUME_ORDRE, INST) of the instants to compute: LIST_INST's (1-based
/// positions, those after INST_FIN left out), or INST (default 0) as
/// NUME_ORDRE 1.
fn instants_of(study: &Study, args: &Args) -> Result<Vec<(usize, f64)>, Diagnostic> {
    let list = match args.concept("LIST_INST") {
        Some(name) => match study.concepts.data(name) {
            Some(ConceptData::ListReal(v)) => v.clone(),
            _ => return Err(args.error("LIST_INST", format!("the list {name} holds no data"))),
        },
        None => vec![args.real("INST").unwrap_or(0.0)],
    };
    if list.is_empty() {
        return Err(args.error("LIST_INST", "the list of instants is empty"));
    }
    if let Some(t) = list.iter().find(|t| !t.is_finite()) {
        return Err(args.error("LIST_INST", format!("the instant {t} is not finite")));
    }
    let fin = args.real("INST_FIN").unwrap_or(f64::INFINITY);
    let out: Vec<(usize, f64)> = list
        .iter()
        .enumerate()
        .filter(|(_, &t)| t <= fin)
        .map(|(k, &t)| (k + 1, t))
        .collect();
    if out.is_empty() {
        return Err(args.error(
            "INST_FIN",
            format!(
                "INST_FIN = {fin:e} is before the first instant {:e}: nothing to compute",
                list[0]
            ),
        ));
    }
    Ok(out)
}
