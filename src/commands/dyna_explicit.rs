//! DYNA_NON_LINE with an explicit scheme (SCHEMA='DIFF_CENT' | 'TCHAMWA'):
//! the keywords turned into the engine's input (`nonlinear::explicit`),
//! code_aster's checks of the explicit path (notes/explicit.md §2, §9) and
//! the CFL check of the time list.

use super::dyna_non_line::{
    archive_of, etat_init, observations_of, prepare_error, result_of_run, result_to_fill,
    time_range, ModelData,
};
use super::ExecResult;
use crate::catalog::args::Args;
use crate::concepts::ConceptData;
use crate::diag::Diagnostic;
use crate::model::MechLoad;
use crate::nonlinear::explicit::{self, Explicit, ExplicitConstraint, ExplicitSettings};
use crate::nonlinear::explicit_contact::{
    mid_nodes_free_on_a_held_edge, Enforcement, ExplicitContact,
};
use crate::nonlinear::explicit_unilateral::ExplicitUnilateral;
use crate::nonlinear::{
    self, dyna, ConvergenceSettings, Engine, NewtonSettings, Occurrence, PrepareError, TimeLoop,
};
use crate::study::Study;
use crate::time::explicit::ExplicitScheme;
use crate::time::list::Action;
use crate::time::Scheme;

/// What the implicit and explicit paths share, built by `dyna_non_line`.
pub(crate) struct Prepared {
    pub scheme: ExplicitScheme,
    /// Rayleigh damping of the materials (AMOR_ALPHA, AMOR_BETA).
    pub damping: Option<nonlinear::damping::Rayleigh>,
    pub md: ModelData,
    pub occs: Vec<Occurrence>,
    pub loads: Vec<MechLoad>,
    pub load_names: Vec<String>,
    pub load_mults: Vec<Option<String>>,
    pub asm: nonlinear::Assembler,
    pub notes: Vec<String>,
    pub model_name: String,
    pub mat_name: String,
}

/// Steps between two estimates of the critical step on the current
/// geometry (the mesh deforms little in so many explicit steps).
const RECHECK_STEPS: usize = 25;

pub(crate) fn exec(
    study: &mut Study,
    args: &Args,
    result: Option<&str>,
    p: Prepared,
) -> ExecResult {
    let Prepared {
        scheme,
        damping,
        mut md,
        occs,
        loads,
        load_names,
        load_mults,
        mut asm,
        mut notes,
        model_name,
        mat_name,
    } = p;
    let st = args
        .fact("SCHEMA_TEMPS")
        .ok_or_else(|| args.error("SCHEMA_TEMPS", "SCHEMA_TEMPS is compulsory"))?;
    let stop_cfl = st.text("STOP_CFL").unwrap_or("OUI") == "OUI";
    let lumped = args.text("MASS_DIAG") == Some("OUI");
    md.lumped_gravity = lumped;
    if let Some(o) = args.fact("NEWTON") {
        let matrice = o.text("MATRICE").unwrap_or("TANGENTE");
        let prediction = o.text("PREDICTION").unwrap_or(matrice);
        if prediction != "TANGENTE" {
            return Err(o.error(
                "PREDICTION",
                format!("an explicit scheme needs the prediction 'TANGENTE', here '{prediction}' (MATRICE gives PREDICTION its default) (MECANONLINE5_1)"),
            ));
        }
    }
    if args.given("CONVERGENCE") || args.given("NEWTON") || args.given("RECH_LINEAIRE") {
        notes.push("CONVERGENCE, NEWTON and RECH_LINEAIRE have no effect with an explicit scheme: every step is converged by definition (as code_aster)".into());
    }
    if scheme.stability_factor().is_none() {
        let m = format!(
            "TCHAMWA with PHI = {} < 1 is unstable for every step (the amplification matrix has determinant 1 - (PHI-1) (w dt)^2 > 1)",
            scheme.displacement_coefficient()
        );
        if stop_cfl {
            return Err(st.error("PHI", m));
        }
        notes.push(format!("alarm: {m}"));
    }
    if lumped {
        notes.push("MASS_DIAG='OUI': lumped mass by HRZ diagonal scaling (Hinton, Rock & Zienkiewicz: the consistent diagonal scaled to keep each element's mass, positive on quadratic elements; code_aster's MASS_MECA_EXPLI recipe); each step is a division, no factorisation".into());
        if loads.iter().any(|l| l.gravity.is_some()) {
            notes.push("PESANTEUR with the lumped mass is the lumped mass times g at each node (f_i = m_i g, the lumped counterpart of the consistent load M (g at every node)), so that a free body falls at exactly g on every element; an aster departure: code_aster keeps the consistent load (integral of rho g N), which on quadratic or distorted cells does not match the lumped mass (HEXA20 corners loaded upwards). The other loads (FORCE_*, PRES_REP) stay consistent".into());
        }
        // code_aster's 2D continuum elements (meca_axis, meca_d_plan,
        // meca_c_plan and their _SI variants) declare no diagonal mass.
        use crate::model::spec::Formulation;
        let two_d: Vec<&str> = [
            (Formulation::Axis, "AXIS (HRZ with the weight r)"),
            (Formulation::PlaneStrain, "D_PLAN"),
            (Formulation::PlaneStress, "C_PLAN"),
        ]
        .into_iter()
        .filter(|(f, _)| md.model.element_cells().any(|(_, s)| s.formulation == *f))
        .map(|(_, name)| name)
        .collect();
        if !two_d.is_empty() {
            notes.push(format!("the lumped mass of {} elements is an aster extension: code_aster's 2D continuum elements have no diagonal mass (CALCUL_38)", two_d.join(" and ")));
        }
        if md.model.element_cells().any(|(_, s)| s.is_hexs8()) {
            notes.push("the lumped mass of HEXS8 (3D_SI HEXA8) cells is an aster extension: code_aster's MECA_HEXS8 declares no MASS_MECA_EXPLI".into());
        }
    } else {
        notes.push(format!(
            "{}: the consistent mass is used, factorised once and solved at every step, as code_aster does; MASS_DIAG='OUI' gives the lumped mass (no solve)",
            if args.given("MASS_DIAG") {
                "MASS_DIAG='NON'"
            } else {
                "MASS_DIAG absent"
            }
        ));
    }
    let mut unil_def = None;
    let contact_def = match args.concept("CONTACT") {
        None => None,
        Some(name) => {
            let Some(ConceptData::Contact(cargs)) = study.concepts.data(name) else {
                return Err(args.error(
                    "CONTACT",
                    format!("the contact {name} holds no data (its command did not run)"),
                ));
            };
            if !lumped {
                return Err(args.not_implemented(
                    "CONTACT",
                    "contact in explicit dynamics with the consistent mass (give MASS_DIAG='OUI')",
                ));
            }
            if cargs.text("FORMULATION") == Some("LIAISON_UNIL") {
                if let Some(m) = cargs.concept("MODELE").filter(|m| *m != model_name) {
                    return Err(args.error(
                        "CONTACT",
                        format!(
                            "the contact {name} is defined on the model {m}, not on {model_name}"
                        ),
                    ));
                }
                let def =
                    crate::commands::liaison_unil::unil_def(study, cargs, &md.mesh, &md.model)?;
                let algo = def.algo;
                notes.push(format!(
                    "LIAISON_UNIL in explicit dynamics is an aster extension (code_aster stops with MECANONLINE5_23): {} link(s) in {} zone(s), {}",
                    def.links.len(),
                    def.zones.len(),
                    match algo {
                        crate::contact::unilateral::UnilAlgo::ActiveSet => "ALGO_CONT='CONTRAINTE' enforced kinematically (each node's links by the correction of least kinetic-energy change, momentum-conserving)",
                        crate::contact::unilateral::UnilAlgo::Penalty => "ALGO_CONT='PENALISATION' (penalty force; its stiffness enters the stable step)",
                    }
                ));
                unil_def = Some(def);
                None
            } else {
                let (mut def, enf) =
                    crate::contact::ContactDef::explicit_from_args(cargs, &md.mesh)?;
                super::contact_def::set_user_gaps(study, cargs, &mut def, &md.mesh)?;
                notes.push(format!(
                "contact in explicit dynamics is an aster extension (code_aster stops with MECANONLINE5_22): {} against a fixed master (or, penalised, a deformable one)",
                match enf {
                    Enforcement::Kinematic => "ALGO_CONT='CONTRAINTE' enforced kinematically (predictor-corrector, momentum-conserving)",
                    Enforcement::Penalty => "ALGO_CONT='PENALISATION' (penalty force; its stiffness enters the stable step)",
                }
            ));
                Some((def, enf))
            }
        }
    };
    let archive = archive_of(study, args)?;
    let dof_names: Vec<String> = md.model.dofs.iter().map(|d| d.name().to_string()).collect();
    let observations = observations_of(study, &md.mesh, &md.model, args, true)?;
    let init = etat_init(study, args, &asm, &dof_names, &model_name, &md.model.mesh)?;
    let (list, instants) = time_range(study, args, init.t0)?;
    let auto = super::dyna_non_line::growth_of(&list);
    if list.on_error() != &Action::Arret || list.rules.len() > 1 {
        notes.push("the time list's events and actions are not used in explicit: a failure stops the run (the sub-steps come from the critical step)".into());
    }
    let rho = explicit::cell_densities(&md.model, &md.matfield, &md.materials, &occs)
        .map_err(|e| prepare_error(args, PrepareError::Behaviour(e)))?;
    let tl = TimeLoop {
        instants,
        on_error: Action::Arret,
        archive,
        cham_exclu: super::dyna_non_line::cham_exclu_of(args)?,
        newton_table: false,
        suivi: super::dyna_non_line::suivi_of(&md.mesh, &md.model, args, true)?,
        observations,
        progress: false,
        dof_names,
        ncells: md.mesh.ncells(),
        events: dyna::ContactEvents::default(),
        deltas: Vec::new(),
        event_actions: Vec::new(),
        growth: None,
        adaptation: Vec::new(),
        subd_niveau: None,
        hint: None,
        // The explicit loop finds a non-finite motion itself (no solve).
        load_peaks: Vec::new(),
        energy_start: init.energy_start,
    };
    let mut evol = result_to_fill(
        study,
        args.reuse.as_deref(),
        &md.model,
        &model_name,
        &mat_name,
        crate::result::RunData {
            loads: load_names.clone(),
            load_mults: load_mults.clone(),
            mass_diag: lumped,
        },
        &occs,
    );

    let has_acce = init.a.is_some();
    let mut state = nonlinear::initial_state(&asm, tl.instants[0], init.u, init.v, init.a);
    super::dyna_non_line::start_comp_elas(args, init.stressed, &mut asm, &mut state, &mut notes)?;
    notes.extend(init.energy_note.clone());
    if let Some(pts) = init.points {
        state.points = pts;
    }
    // The Newmark parameters of the engine are unused: the explicit loop
    // drives the engine's states and assembler itself.
    let unused = Scheme::newmark(0.25, 0.5).map_err(|m| args.error("SCHEMA_TEMPS", m))?;
    let mut engine = Engine::new(
        asm,
        unused,
        NewtonSettings::default(),
        ConvergenceSettings::default(),
        state,
    );
    super::dyna_non_line::set_loads(
        args,
        &md,
        &loads,
        &load_mults,
        study,
        &tl.instants,
        &mut engine,
    )?;
    let mut ex = Explicit::new(&mut engine.asm, &rho, scheme, lumped)
        .map_err(|m| args.error("MODELE", m))?;
    // Set before `initialize`, which computes C v₀ for the initial
    // acceleration with the mass of the run (the lumped one with MASS_DIAG).
    engine.damping = damping;
    ex.damping = damping;
    let clamped = ex.impose_initial(&mut engine);
    if clamped > 0 {
        notes.push(format!(
            "{clamped} imposed dof(s) with a constant value had an initial velocity: the imposed displacement holds them (v = 0 there from the start; code_aster imposes the acceleration and would let them drift)"
        ));
    }
    engine
        .initialize(false)
        .map_err(|f| args.error("", format!("initial state: {f}")))?;
    // After `initialize`, which computes the initial internal forces.
    if lumped && init.stressed && loads.iter().any(|l| l.gravity.is_some()) {
        if let Some(m) =
            lumped_gravity_imbalance(args, &mut md, &loads, &load_mults, study, &tl, &engine)?
        {
            notes.push(m);
        }
    }
    let mut contact: Option<Box<dyn ExplicitConstraint>> = match contact_def {
        None => None,
        Some((def, enf)) => {
            let c = ExplicitContact::new(
                def,
                enf,
                &md.mesh,
                &engine.asm.numbering,
                &ex.mass,
                &engine.committed.motion.u,
            )
            .map_err(|m| args.error("CONTACT", m))?;
            if c.kinematic() {
                let free = mid_nodes_free_on_a_held_edge(&c.def, &md.mesh, &engine.asm.numbering);
                if !free.is_empty() {
                    notes.push(untied_alarm(&free));
                }
            }
            Some(Box::new(c))
        }
    };
    if let Some(def) = unil_def {
        // Coefficients that cannot be evaluated at the list's step ends are
        // refused before the first step, as in implicit (the conditions are
        // evaluated at the step ends only, the initial state's at the first
        // step's). A sub-step end before the first instant of the list
        // outside a function's domain stops the run with the same message.
        let nb = &engine.asm.numbering;
        let eq = |f: usize| (nb.eq[f] != nonlinear::dofs::NONE).then(|| nb.eq[f]);
        let imposed = nonlinear::unilateral::imposed_value(nb);
        let span = [
            tl.instants[1.min(tl.instants.len() - 1)],
            tl.instants[tl.instants.len() - 1],
        ];
        for &t in &span {
            def.rows(t, nb.ndpn, eq, &imposed)
                .map_err(|m| args.error("CONTACT", format!("LIAISON_UNIL at INST = {t:e}: {m}")))?;
        }
        let u = ExplicitUnilateral::new(def, nb, &tl.instants[1.min(tl.instants.len() - 1)..])
            .map_err(|m| args.error("CONTACT", m))?;
        contact = Some(Box::new(u));
    }
    let w2c = contact.as_ref().map_or(0.0, |c| c.penalty_omega2(&ex.mass));
    let bound = ex
        .step_bound(
            &engine.asm,
            &engine.committed.motion.u,
            &engine.committed.points,
            w2c,
        )
        .map_err(|f| {
            args.error(
                "",
                format!(
                    "critical step: cell {}: {}",
                    crate::nonlinear::cell_label(&md.mesh, &md.model, f.cell),
                    f.failure
                ),
            )
        })?;
    notes.push(format!(
        "{}: critical step {:.6e} s (element eigenvalue bound 2/w_max{}{}, largest w at cell {}{}){}",
        scheme.name(),
        bound.dt,
        match scheme {
            ExplicitScheme::DiffCent => String::new(),
            ExplicitScheme::Tchamwa { phi } =>
                format!(" times 1/sqrt(2 PHI - 1) = {:.4}, PHI = {phi}", scheme.stability_factor().unwrap_or(0.0)),
        },
        match damping {
            Some(_) => format!(
                " times sqrt(1 + xi^2) - xi = {:.4} for the Rayleigh damping ratio xi = (AMOR_ALPHA w + AMOR_BETA / w)/2 of w_max (code_aster does not reduce it)",
                bound.damping_factor
            ),
            None => String::new(),
        },
        crate::nonlinear::cell_label(&md.mesh, &md.model, bound.cell),
        match bound.held_cells {
            0 => String::new(),
            n => format!(
                "; {n} cell(s) whose every dof is imposed left out: they carry no free motion to be unstable"
            ),
        },
        if w2c > 0.0 {
            format!(
                "; without the contact penalty {:.6e} s: the penalty stiffness on the lightest slave node lowers it by a factor {:.3}",
                bound.dt_elements,
                bound.dt_elements / bound.dt
            )
        } else {
            String::new()
        }
    ));
    if w2c > 0.0 && bound.dt < bound.dt_elements / 10.0 {
        notes.push(format!(
            "alarm: the contact penalty shrinks the stable step by more than 10 times: {:.6e} s instead of {:.6e} s (lower E_N/E_T, or use ALGO_CONT='CONTRAINTE')",
            bound.dt, bound.dt_elements
        ));
    }
    // The largest step the run takes: the bound itself with AUTO (or
    // PAS_MAXI), else the list's largest step, cut to the bound with
    // STOP_CFL='OUI'.
    let largest = match &auto {
        Some(g) => g.pas_maxi.map_or(bound.dt, |m| m.min(bound.dt)),
        None => tl
            .instants
            .windows(2)
            .map(|w| w[1] - w[0])
            .map(|dt| if stop_cfl { dt.min(bound.dt) } else { dt })
            .fold(0.0, f64::max),
    };
    if let Some(m) = explicit::penalty_step_alarm(
        w2c,
        &bound,
        largest,
        scheme.stability_factor().unwrap_or(1.0),
    ) {
        notes.push(m);
    }
    if let Some(g) = &auto {
        notes.push(format!(
            "METHODE='AUTO' in explicit dynamics (an aster extension): the list's instants are the instants to reach, and each step is the current critical step bound{} (at most {} times the previous one), cut into equal steps to land on each instant; the bound is re-estimated on the current geometry during the run",
            g.pas_maxi.map_or(String::new(), |m| format!(" or PAS_MAXI = {m:e} if smaller")),
            g.factor
        ));
    }
    if let Some((k, t, dt)) =
        explicit::first_step_above(&tl.instants, bound.dt).filter(|_| auto.is_none())
    {
        // A list code_aster would accept can stop here because of the
        // damping's reduction: the message says so.
        let damped = if bound.damping_factor < 1.0 {
            format!(
                "; Rayleigh damping lowers the bound by sqrt(1 + xi^2) - xi = {:.4} (undamped {:.6e}; code_aster does not reduce it)",
                bound.damping_factor,
                bound.dt / bound.damping_factor
            )
        } else {
            String::new()
        };
        let m = if bound.dt < bound.dt_elements {
            format!(
                "step {k} of the time list (from t = {t:e}, dt = {dt:.6e}) exceeds the critical step {:.6e} set by the contact penalty (the elements' alone: {:.6e} at cell {}) (DYNAMIQUE_2)",
                bound.dt,
                bound.dt_elements,
                crate::nonlinear::cell_label(&md.mesh, &md.model, bound.cell)
            )
        } else {
            format!(
                "step {k} of the time list (from t = {t:e}, dt = {dt:.6e}) exceeds the critical step {:.6e} of cell {} (DYNAMIQUE_2)",
                bound.dt,
                crate::nonlinear::cell_label(&md.mesh, &md.model, bound.cell)
            )
        } + &damped;
        if stop_cfl {
            let inc = args.fact("INCREMENT").unwrap_or(args);
            return Err(inc
                .error("LIST_INST", m)
                .note("STOP_CFL='NON' runs it anyway with an alarm"));
        }
        notes.push(format!(
            "alarm: {m}; STOP_CFL='NON': the list is followed as given"
        ));
    }
    let settings = ExplicitSettings {
        stop_cfl,
        recheck: if stop_cfl || auto.is_some() {
            RECHECK_STEPS
        } else {
            0
        },
        auto,
    };
    for n in &notes {
        study.log(format!("  {n}"));
    }
    study.log(format!(
        "  DYNA_NON_LINE ({}): {} equations ({} imposed dofs), {} elements; {} steps of the list from {:e} to {:e}",
        scheme.name(),
        engine.asm.numbering.neq(),
        engine.asm.numbering.imposed.len(),
        engine.asm.elements.len(),
        tl.instants.len() - 1,
        tl.instants[0],
        tl.instants[tl.instants.len() - 1]
    ));
    let verbose = study.verbose;
    let mess = &mut study.mess;
    let mut log = |line: &str| {
        if verbose {
            eprintln!("{line}");
        }
        mess.push_str(line);
        mess.push('\n');
    };
    let outcome = explicit::run(
        &mut engine,
        &mut ex,
        contact.as_deref_mut(),
        &tl,
        &settings,
        has_acce,
        init.contact.as_ref(),
        &mut evol,
        &mut log,
    );
    result_of_run(study, args, result, evol, init.energy_start, outcome)
}

/// The alarm for slave mid-side nodes left free where both vertices of
/// their edge are held (`mid_nodes_free_on_a_held_edge`).
fn untied_alarm(free: &[(usize, usize)]) -> String {
    const CMP: [&str; 3] = ["DX", "DY", "DZ"];
    let mut listed: Vec<String> = free
        .iter()
        .take(10)
        .map(|&(n, k)| format!("N{} {}", n + 1, CMP[k]))
        .collect();
    if free.len() > 10 {
        listed.push(format!("and {} more", free.len() - 10));
    }
    format!(
        "alarm: {} mid-side slave node component(s) are free although both vertices of their edge are imposed ({}): code_aster's ALGO_CONT='CONTRAINTE' ties the mid-side nodes of QUAD8 slave cells to their vertices, which is why a command file may leave them out of its DDL_IMPO (SDNV103 A's group MILIEU); aster's kinematic contact ties nothing, so these nodes can leave the plane their edge is held in. Impose the same components on them (in A: the symmetry conditions on all of SXX and SYY; docs/performance.md, \"The 3D quarter against the axisymmetric bar\")",
        free.len(),
        listed.join(", ")
    )
}

/// An alarm for an explicit run with the lumped mass that starts from a
/// stressed state (ETAT_INIT with EVOL_NOLI or SIGM) under PESANTEUR: the
/// run applies the gravity as the lumped mass times g (aster, so that a
/// free body falls at exactly g), code_aster and every implicit command
/// as the consistent load ∫ρgN. On quadratic or distorted cells the two
/// differ, so a state balanced under the consistent load (a STAT_NON_LINE
/// preload) starts out of balance by the difference and vibrates about
/// its equilibrium (probe15: a 2 x 2 x 6 HEXA20 column preloaded by
/// gravity, its top 5.4 % off the static deflection after 2e-5 s, 4.8
/// mm/s). None when they agree (regular HEXA8, TETRA4, PENTA6...).
fn lumped_gravity_imbalance(
    args: &Args,
    md: &mut ModelData,
    loads: &[MechLoad],
    mults: &[Option<String>],
    study: &Study,
    tl: &TimeLoop,
    engine: &Engine,
) -> Result<Option<String>, Diagnostic> {
    md.lumped_gravity = false;
    let history = super::dyna_non_line::load_history(
        args,
        md,
        loads,
        mults,
        study,
        &tl.instants,
        &engine.asm.numbering,
    );
    md.lumped_gravity = true;
    let mut consistent = vec![0.0; engine.fext.len()];
    history?
        .at(tl.instants[0], &mut consistent)
        .map_err(|m| args.error("EXCIT", m))?;
    let scale = consistent.iter().fold(0.0_f64, |a, f| a.max(f.abs()));
    // A state without internal forces (a free fall continued) is balanced
    // under neither load: nothing to warn about.
    let fint0 = engine
        .committed
        .fint
        .iter()
        .fold(0.0_f64, |a, f| a.max(f.abs()));
    if fint0 <= 1e-6 * scale {
        return Ok(None);
    }
    let (worst, n) = engine
        .fext
        .iter()
        .zip(&consistent)
        .map(|(l, c)| (l - c).abs())
        .fold((0.0_f64, 0_usize), |(w, n), d| {
            (w.max(d), n + usize::from(d > 1e-9 * scale))
        });
    Ok((scale > 0.0 && worst > 1e-9 * scale).then(|| {
        format!(
            "alarm: the initial state carries stresses and PESANTEUR is applied as the lumped mass times g (aster: a free body then falls at exactly g), where code_aster and the implicit commands apply the consistent load (integral of rho g N); on {n} dof(s) they differ, by up to {:.3} % of the largest nodal gravity force (quadratic or distorted cells): a state balanced under the consistent load (a STAT_NON_LINE preload) starts out of balance by that difference and vibrates about its equilibrium; MASS_DIAG absent (the consistent mass) keeps the consistent load",
            100.0 * worst / scale
        )
    }))
}
