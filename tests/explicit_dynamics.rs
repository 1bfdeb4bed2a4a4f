//! The explicit loop of DYNA_NON_LINE (DIFF_CENT, TCHAMWA) against
//! independent references: the CFL check of the time list (STOP_CFL), and
//! the measured stability limit of the loop on a small clamped mesh
//! against the element bound and the true limit 2/ω_max of the assembled
//! lumped system (a dense eigenvalue computation, independent of the
//! element inequality the bound rests on).

mod common;
mod dynamics_support;

use aster::law::TangentKind;
use aster::mesh::Mesh;
use aster::model::{Dof, MaterialField, Model};
use aster::nonlinear::explicit::Explicit;
use aster::nonlinear::{Controls, Occurrence};
use aster::post::table::Cell;
use aster::solver::SparseMatrix;
use aster::time::explicit::ExplicitScheme;
use dynamics_support::*;
use nalgebra::{DMatrix, SymmetricEigen};

const E: f64 = 117_000.0;
const NU: f64 = 0.35;
const RHO: f64 = 8.93e-9;

/// The .mess says which mass an explicit run uses, in the words of the
/// command file: MASS_DIAG='NON' given is not "MASS_DIAG absent"; the
/// lumped mass of D_PLAN elements is announced as an aster extension
/// (code_aster's 2D continuum elements have no diagonal mass, CALCUL_38),
/// as AXIS's was (tests/verification/dplan_wave_explicit.comm and two
/// variants of it).
#[test]
fn mess_names_the_mass_as_the_command_file_gives_it() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/verification");
    let note = "the lumped mass of D_PLAN elements is an aster extension: code_aster's 2D continuum elements have no diagonal mass (CALCUL_38)";
    let run = |tag: &str, to: &str| {
        let r = common::run_variant(
            &dir,
            "mass_messages",
            "dplan_wave_explicit",
            tag,
            "MASS_DIAG='OUI',",
            to,
        );
        r.file(&format!("{tag}.mess"))
    };
    let lumped = run("mass_oui", "MASS_DIAG='OUI',");
    assert!(lumped.contains(note), "{lumped}");
    let non = run("mass_non", "MASS_DIAG='NON',");
    assert!(
        non.contains("MASS_DIAG='NON': the consistent mass is used"),
        "{non}"
    );
    assert!(
        !non.contains("MASS_DIAG absent") && !non.contains(note),
        "{non}"
    );
    let absent = run("mass_absent", "");
    assert!(
        absent.contains("MASS_DIAG absent: the consistent mass is used"),
        "{absent}"
    );
}

/// A 1 x 4 QUAD8 Taylor bar, bottom held in DY, axis in DX; one node of
/// the top given a velocity (a rough field: it excites the highest modes).
fn setup() -> (Mesh, Model, Vec<aster::model::ImposedDof>, usize) {
    let mesh = taylor_axis(1, 4);
    let bar = mesh.cell_groups["VOL"].clone();
    let mo = model(&mesh, "AXIS", &bar);
    let nodes = mesh.nodes_of_cells(&bar);
    let ymin = nodes
        .iter()
        .map(|&n| mesh.coords[n][1])
        .fold(f64::INFINITY, f64::min);
    let ymax = nodes
        .iter()
        .map(|&n| mesh.coords[n][1])
        .fold(f64::NEG_INFINITY, f64::max);
    let bottom: Vec<usize> = nodes
        .iter()
        .copied()
        .filter(|&n| (mesh.coords[n][1] - ymin).abs() < 1e-9)
        .collect();
    let axis: Vec<usize> = nodes
        .iter()
        .copied()
        .filter(|&n| mesh.coords[n][0].abs() < 1e-9)
        .collect();
    let top = nodes
        .iter()
        .copied()
        .find(|&n| (mesh.coords[n][1] - ymax).abs() < 1e-9 && mesh.coords[n][0] > 1.0)
        .unwrap();
    let mut imp = imposed(&bottom, Dof::Dy, 0.0);
    imp.extend(imposed(&axis, Dof::Dx, 0.0));
    (mesh, mo, imp, top)
}

/// The lumped system of `setup` on its free dofs: the element bound of
/// the critical step, the lumped masses of the free dofs (full indices in
/// `free`), and the eigen-decomposition of M^{-1/2} K M^{-1/2} (ω², and
/// the mass-normalised modes in columns).
struct Lumped {
    bound: f64,
    free: Vec<usize>,
    mass: Vec<f64>,
    eig: SymmetricEigen<f64, nalgebra::Dyn>,
}

fn lumped_system(mesh: &Mesh, mo: &Model, imp: &[aster::model::ImposedDof]) -> Lumped {
    let mut materials = indexmap::IndexMap::new();
    materials.insert("MAT".to_string(), material(E, NU, RHO, None));
    let matfield = MaterialField {
        mesh: "MAIL".into(),
        cell_material: vec![Some("MAT".into()); mesh.ncells()],
    };
    let occs = vec![Occurrence {
        cells: None,
        relation: "ELAS".into(),
        deformation: "PETIT".into(),
        controls: Controls::default(),
    }];
    let load = aster::model::MechLoad {
        model: "MO".into(),
        imposed: imp.to_vec(),
        gravity: None,
        nodal_forces: Vec::new(),
        pressures: Vec::new(),
        distributed: Vec::new(),
        functions: Vec::new(),
        fields: Vec::new(),
    };
    let (mut asm, _) =
        aster::nonlinear::discretize(mesh, mo, &matfield, &materials, &occs, &[&load]).unwrap();
    let rho = aster::nonlinear::explicit::cell_densities(mo, &matfield, &materials, &occs).unwrap();
    let mut ex = Explicit::new(&mut asm, &rho, ExplicitScheme::DiffCent, true).unwrap();
    let n = asm.numbering.nfull();
    let u = vec![0.0; n];
    let pts = asm.initial_states();
    let bound = ex.step_bound(&asm, &u, &pts, 0.0).unwrap().dt;
    let mut k = SparseMatrix::zeros(asm.pattern.clone());
    let mut fint = vec![0.0; n];
    let mut out = pts.clone();
    asm.compute(
        &u,
        &u,
        &pts,
        &mut out,
        0.0,
        TangentKind::Elastic,
        &mut fint,
        Some(&mut k),
    )
    .unwrap();
    let free = asm.numbering.free.clone();
    let neq = free.len();
    let mass: Vec<f64> = free.iter().map(|&f| ex.mass[f]).collect();
    let s: Vec<f64> = mass.iter().map(|m| 1.0 / m.sqrt()).collect();
    let a = DMatrix::from_fn(neq, neq, |i, j| {
        0.5 * s[i] * (k.get(i, j) + k.get(j, i)) * s[j]
    });
    Lumped {
        bound,
        free,
        mass,
        eig: SymmetricEigen::new(a),
    }
}

/// (element bound, true limit 2/ω_max of the assembled lumped system).
fn limits(mesh: &Mesh, mo: &Model, imp: &[aster::model::ImposedDof]) -> (f64, f64) {
    let l = lumped_system(mesh, mo, imp);
    (l.bound, 2.0 / l.eig.eigenvalues.max().sqrt())
}

/// `setup`'s bar with its rough initial velocity (V0) on the manual list
/// `instants` (L_INST) and, given, the time list `list` (LI).
fn bar_study(instants: Vec<f64>, list: Option<aster::time::list::TimeList>) -> aster::study::Study {
    let (mesh, mo, imp, top) = setup();
    let nn = mesh.nnodes();
    study(
        mesh,
        mo,
        material(E, NU, RHO, None),
        imp,
        Some(velocity(nn, &[top], 1000.0)),
        instants,
        list,
    )
}

/// The energy history of a run of `steps` steps of `dt` from the rough
/// initial velocity of `setup`: the total energy (ENER_CIN + ENER_TOT)
/// over the initial kinetic energy at each archived instant (every
/// `pas_arch` steps).
fn energy_history(
    dt: f64,
    steps: usize,
    pas_arch: usize,
    stop_cfl: &str,
    schema: &str,
) -> Result<Vec<f64>, String> {
    let mut st = bar_study(linspace(0.0, dt * steps as f64, steps), None);
    let text = format!(
        "RESU = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOQ), MASS_DIAG='OUI',
    COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), ETAT_INIT=_F(VITE=V0),
    INCREMENT=_F(LIST_INST=L_INST), ARCHIVAGE=_F(PAS_ARCH={pas_arch}),
    SCHEMA_TEMPS=_F(SCHEMA='{schema}', FORMULATION='ACCELERATION', STOP_CFL='{stop_cfl}'))"
    );
    let args = args_of(&text, "DYNA_NON_LINE", 0);
    exec(&mut st, "DYNA_NON_LINE", &args, "RESU")?;
    Ok(total_energy(&mut st))
}

/// The total energy of RESU at each archived instant over the initial
/// kinetic energy EK0: 1 + (ENER_CIN + ENER_TOT) / EK0 from its PARA_CALC
/// (ENER_CIN is the change of the kinetic energy since the start, as
/// code_aster's), EK0 from POST_ELEM ENER_CIN with the run's lumped mass.
fn total_energy(st: &mut aster::study::Study) -> Vec<f64> {
    // RESU is declared for the checker only; the study holds the run's.
    let text =
        "RESU = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOQ), MASS_DIAG='OUI',
    COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=L_INST),
    SCHEMA_TEMPS=_F(SCHEMA='DIFF_CENT', FORMULATION='ACCELERATION'))
EK = POST_ELEM(RESULTAT=RESU, NUME_ORDRE=0, ENER_CIN=_F(TOUT='OUI', OPTION='MASS_MECA_DIAG'))";
    let reg = aster::commands::all();
    let def = reg.iter().find(|d| d.spec.name == "POST_ELEM").unwrap();
    let e0 = match (def.exec)(st, &args_of(text, "POST_ELEM", 0), Some("EK")) {
        Ok(Some(aster::concepts::ConceptData::Table(t))) => t
            .cell(0, "TOTALE")
            .and_then(Cell::as_f64)
            .expect("POST_ELEM's TOTALE"),
        _ => panic!("POST_ELEM ENER_CIN of RESU"),
    };
    let t = &result(st, "RESU").tables["PARA_CALC"];
    let col = |name: &str| -> Vec<f64> {
        let k = t.columns.iter().position(|c| c == name).unwrap();
        t.rows
            .iter()
            .map(|row| match &row[k] {
                Some(Cell::Real(x)) => *x,
                _ => f64::NAN,
            })
            .collect()
    };
    let (ek, ei) = (col("ENER_CIN"), col("ENER_TOT"));
    assert_eq!(ek[0], 0.0);
    ek.iter()
        .zip(&ei)
        .map(|(a, b)| 1.0 + (a + b) / e0)
        .collect()
}

/// The worst relative change of the total energy over a run.
fn run_with(dt: f64, steps: usize, stop_cfl: &str, schema: &str) -> Result<f64, String> {
    let h = energy_history(dt, steps, steps / 10, stop_cfl, schema)?;
    Ok(h.iter().map(|e| (e - 1.0).abs()).fold(0.0, f64::max))
}

/// The element bound lies below the true limit of the assembled system
/// (the element eigenvalue inequality), the loop is stable at the bound
/// and just below the true limit (total energy kept to a few percent over
/// many steps), and unstable just above it (energy grows without bound:
/// the run stops once the scheme has created a hundred times the energy
/// it was given).
#[test]
fn measured_stability_limit_lies_above_the_element_bound() {
    let (mesh, mo, imp, _) = setup();
    let (bound, exact) = limits(&mesh, &mo, &imp);
    println!("element bound {bound:e}, true limit {exact:e}");
    assert!(bound <= exact, "bound {bound} above the true limit {exact}");
    assert!(bound > 0.5 * exact, "bound {bound} far below {exact}");
    let drift = run_with(0.99999 * bound, 20_000, "OUI", "DIFF_CENT").unwrap();
    assert!(drift < 0.05, "at the bound: energy drift {drift}");
    let drift = run_with(0.98 * exact, 5_000, "NON", "DIFF_CENT").unwrap();
    assert!(drift < 0.2, "just below the limit: energy drift {drift}");
    let m = run_with(1.02 * exact, 5_000, "NON", "DIFF_CENT").unwrap_err();
    assert!(m.contains("the explicit scheme is unstable"), "{m}");
}

/// A run far above the stability limit (STOP_CFL='NON') stops as unstable
/// (long before any value overflows) with the last state archived, and its
/// message counts the steps the result really keeps and names the last
/// instant stored.
#[test]
fn unstable_run_stops_and_says_what_the_result_keeps() {
    let (mesh, mo, imp, _) = setup();
    let (_, exact) = limits(&mesh, &mo, &imp);
    let dt = 3.0 * exact;
    let steps = 2000;
    let mut st = bar_study(linspace(0.0, dt * steps as f64, steps), None);
    let text =
        "RESU = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOQ), MASS_DIAG='OUI',
    COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), ETAT_INIT=_F(VITE=V0),
    INCREMENT=_F(LIST_INST=L_INST), ARCHIVAGE=_F(PAS_ARCH=1000),
    SCHEMA_TEMPS=_F(SCHEMA='DIFF_CENT', FORMULATION='ACCELERATION', STOP_CFL='NON'))";
    let args = args_of(text, "DYNA_NON_LINE", 0);
    let m = exec(&mut st, "DYNA_NON_LINE", &args, "RESU").unwrap_err();
    assert!(m.contains("the explicit scheme is unstable"), "{m}");
    let r = result(&st, "RESU");
    // Stopped within a few tens of steps of a growth of about 3 per step
    // (3 times the limit), every stored value finite and far from 1e300.
    assert!(r.steps.iter().all(|s| s.inst < 100.0 * dt), "{m}");
    let last = r.steps.last().unwrap().inst;
    assert!(last > 0.0, "the last converged state is archived: {last}");
    let said = format!(
        "The {} steps archived so far (last instant {last:e})",
        r.steps.len()
    );
    assert!(m.contains(&said), "{m}\nexpected: {said}");
}

/// STOP_CFL='OUI' (the default): a list step above the bound is an error
/// naming the step, the critical step and the cell; 'NON' runs it with an
/// alarm.
#[test]
fn cfl_check_of_the_time_list() {
    let (mesh, mo, imp, _) = setup();
    let (bound, _) = limits(&mesh, &mo, &imp);
    let err = run_with(1.01 * bound, 10, "OUI", "DIFF_CENT").unwrap_err();
    assert!(
        err.contains("step 1 of the time list")
            && err.contains("exceeds the critical step")
            && err.contains("DYNAMIQUE_2")
            && err.contains("of cell"),
        "{err}"
    );
    let crit = format!("{:.6e}", bound);
    assert!(err.contains(&crit), "{err} should name {crit}");
    assert!(run_with(1.01 * bound, 10, "NON", "DIFF_CENT").is_ok());
    // TCHAMWA (PHI = 1.05): the bound is multiplied by 1/sqrt(2 PHI - 1).
    let err = run_with(bound, 10, "OUI", "TCHAMWA").unwrap_err();
    assert!(err.contains("DYNAMIQUE_2"), "{err}");
    assert!(run_with(0.95 * bound, 10, "OUI", "TCHAMWA").is_ok());
}

/// TCHAMWA (PHI = 1.05) dissipates: at the same step the total energy
/// decreases where DIFF_CENT keeps it, the dissipation concentrated in the
/// highest modes (the single-dof spectral radius is sqrt(1 - (PHI-1) W^2)).
#[test]
fn tchamwa_dissipates_the_high_modes() {
    let (mesh, mo, imp, _) = setup();
    let (bound, _) = limits(&mesh, &mo, &imp);
    let dt = 0.9 * bound;
    let drift_dc = run_with(dt, 4_000, "OUI", "DIFF_CENT").unwrap();
    let drift_tc = run_with(dt, 4_000, "OUI", "TCHAMWA").unwrap();
    println!("energy change: DIFF_CENT {drift_dc}, TCHAMWA {drift_tc}");
    assert!(drift_dc < 0.05);
    assert!(drift_tc > 0.2, "TCHAMWA kept the energy: {drift_tc}");
}

/// Below the critical step the loop is stable for 1e5 steps: the total
/// energy of the free vibration (DIFF_CENT, a rough initial velocity that
/// excites every mode, 0.9 of the element bound) stays within a few
/// percent of the initial one, and its excursion in the second half of the
/// run is no larger than in the first (no growth: an unstable mode would
/// grow geometrically). TCHAMWA at its own allowed step never exceeds the
/// initial energy and loses almost all of it (the rough field is mostly
/// high modes).
#[test]
fn stable_for_1e5_steps_below_the_critical_step() {
    let (mesh, mo, imp, _) = setup();
    let (bound, _) = limits(&mesh, &mo, &imp);
    let dt = 0.9 * bound;
    let h = energy_history(dt, 100_000, 100, "OUI", "DIFF_CENT").unwrap();
    assert_eq!(h.len(), 1001);
    let dev = |s: &[f64]| s.iter().map(|e| (e - 1.0).abs()).fold(0.0, f64::max);
    let (first, second) = (dev(&h[..500]), dev(&h[500..]));
    println!(
        "DIFF_CENT, 1e5 steps: energy excursion {first:e} (first half), {second:e} (second half)"
    );
    assert!(first < 0.05 && second < 0.05, "{first} {second}");
    assert!(second < 1.2 * first, "energy grows: {first} then {second}");
    let h = energy_history(dt / 1.1f64.sqrt(), 100_000, 100, "OUI", "TCHAMWA").unwrap();
    let last = *h.last().unwrap();
    println!("TCHAMWA, 1e5 steps: final energy {last:e} of the initial");
    // The archived energy uses TCHAMWA's lagging velocity, so it is not
    // monotone step to step; it never exceeds the initial one and decays.
    assert!(h.iter().all(|&e| (0.0..=1.0 + 1e-9).contains(&e)), "{h:?}");
    assert!(last < 0.05, "TCHAMWA kept {last} of the energy");
}

/// The spectral radius of the recurrence q_{n+1} = T q_n − D q_{n−1}:
/// the largest modulus of the roots of λ² − Tλ + D.
fn radius(t: f64, d: f64) -> f64 {
    let disc = t * t - 4.0 * d;
    if disc < 0.0 {
        d.sqrt()
    } else {
        (t.abs() + disc.sqrt()) / 2.0
    }
}

/// The modal displacements q_n (every step) of a free vibration started
/// with the mass-normalised mode `k` of the lumped system as initial
/// velocity, and the largest relative part of u outside the mode.
fn modal_history(l: &Lumped, k: usize, dt: f64, steps: usize, schema: &str) -> (Vec<f64>, f64) {
    let (mesh, mo, imp, _) = setup();
    let nn = mesh.nnodes();
    let x = l.eig.eigenvectors.column(k);
    let phi: Vec<f64> = (0..l.free.len()).map(|i| x[i] / l.mass[i].sqrt()).collect();
    let mut vite = aster::result::NodalField::absent(vec!["DX".into(), "DY".into()], nn);
    for &f in &l.free {
        vite.set(f / 2, 0, 0.0);
        vite.set(f / 2, 1, 0.0);
    }
    for (i, &f) in l.free.iter().enumerate() {
        vite.set(f / 2, f % 2, 1000.0 * phi[i]);
    }
    let mut st = study(
        mesh,
        mo,
        material(E, NU, RHO, None),
        imp,
        Some(vite),
        linspace(0.0, dt * steps as f64, steps),
        None,
    );
    let text = format!(
        "RESU = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOQ), MASS_DIAG='OUI',
    COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), ETAT_INIT=_F(VITE=V0),
    INCREMENT=_F(LIST_INST=L_INST), ARCHIVAGE=_F(PAS_ARCH=1),
    SCHEMA_TEMPS=_F({schema}, FORMULATION='ACCELERATION'))"
    );
    let args = args_of(&text, "DYNA_NON_LINE", 0);
    exec(&mut st, "DYNA_NON_LINE", &args, "RESU").unwrap();
    let r = result(&st, "RESU");
    assert_eq!(r.steps.len(), steps + 1);
    let mut out = 0.0f64;
    let q = r
        .steps
        .iter()
        .map(|s| {
            let d = &s.nodal["DEPL"];
            let u: Vec<f64> = l
                .free
                .iter()
                .map(|&f| d.get(f / 2, if f % 2 == 0 { "DX" } else { "DY" }).unwrap())
                .collect();
            let q: f64 = (0..u.len()).map(|i| l.mass[i] * phi[i] * u[i]).sum();
            let norm = u.iter().map(|v| v * v).sum::<f64>().sqrt();
            let rest = (0..u.len())
                .map(|i| (u[i] - q * phi[i]).powi(2))
                .sum::<f64>()
                .sqrt();
            if norm > 0.0 {
                out = out.max(rest / norm);
            }
            q
        })
        .collect();
    (q, out)
}

/// Least-squares (T, D) of q_{n+1} = T q_n − D q_{n−1} over the history.
fn fit_recurrence(q: &[f64]) -> (f64, f64) {
    let (mut a11, mut a12, mut a22, mut b1, mut b2) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for w in q.windows(3) {
        let (x1, x2, y) = (w[1], -w[0], w[2]);
        a11 += x1 * x1;
        a12 += x1 * x2;
        a22 += x2 * x2;
        b1 += x1 * y;
        b2 += x2 * y;
    }
    let det = a11 * a22 - a12 * a12;
    ((b1 * a22 - b2 * a12) / det, (a11 * b2 - a12 * b1) / det)
}

/// TCHAMWA damps the highest mode as documented (notes/explicit.md §3.2:
/// amplification matrix [[1−φΩ², 1], [−Ω², 1]] in (u, Δt v), trace
/// 2 − φΩ², determinant 1 − (φ−1)Ω², spectral radius √(1 − (φ−1)Ω²)
/// while Ω < 2/φ) and DIFF_CENT does not (determinant 1, radius 1). The
/// run starts in one mode of the assembled lumped system, stays in it
/// (linear elasticity), and the per-step recurrence of its modal
/// displacement is fitted from the archived fields: the measured trace,
/// determinant and radius are the loop's own, compared with the scheme's
/// algebra at Ω = ω Δt. The lowest mode shows the damping is concentrated
/// at the top of the spectrum (1 − ρ ≈ (φ−1)Ω²/2).
#[test]
fn tchamwa_damps_the_highest_mode_as_documented() {
    let (mesh, mo, imp, _) = setup();
    let l = lumped_system(&mesh, &mo, &imp);
    // The step allowed for PHI = 1.1, used for every scheme.
    let dt = 0.9 * l.bound / (2.0 * 1.1 - 1.0f64).sqrt();
    let ev = &l.eig.eigenvalues;
    let top = ev.imax();
    let low = ev.imin();
    for (k, which) in [(top, "highest"), (low, "lowest")] {
        let omega = ev[k].sqrt() * dt;
        for (schema, phi) in [
            ("SCHEMA='DIFF_CENT'", None),
            ("SCHEMA='TCHAMWA', PHI=1.05", Some(1.05)),
            ("SCHEMA='TCHAMWA', PHI=1.1", Some(1.1)),
        ] {
            let (q, out) = modal_history(&l, k, dt, 200, schema);
            let (t, d) = fit_recurrence(&q);
            let (t0, d0) = match phi {
                None => (2.0 - omega * omega, 1.0),
                Some(p) => (2.0 - p * omega * omega, 1.0 - (p - 1.0) * omega * omega),
            };
            let (rho, rho0) = (radius(t, d), radius(t0, d0));
            println!(
                "{which} mode, Omega {omega:.4}, {schema}: trace {t:.8} ({t0:.8}), det {d:.8} ({d0:.8}), radius {rho:.8} (analytic {rho0:.8}), amplitude after 200 steps {:.4e}, off-mode {out:.1e}",
                (q[199].abs().max(q[200].abs())) / q[1].abs()
            );
            assert!(out < 1e-6, "the run left the mode: {out}");
            assert!((t - t0).abs() < 1e-7, "trace {t} against {t0}");
            assert!((d - d0).abs() < 1e-7, "determinant {d} against {d0}");
            assert!((rho - rho0).abs() < 1e-7, "radius {rho} against {rho0}");
            if phi.is_none() {
                assert!((rho - 1.0).abs() < 1e-7, "DIFF_CENT damps: {rho}");
            }
        }
    }
}

/// `setup`'s bar under DIFF_CENT and the lumped mass, on the manual list
/// `instants` (L_INST) or, given, on the time list `list` (LI): the study
/// after the run.
fn run_bar(instants: Vec<f64>, list: Option<aster::time::list::TimeList>) -> aster::study::Study {
    let name = if list.is_some() { "LI" } else { "L_INST" };
    let mut st = bar_study(instants, list);
    let text = format!(
        "RESU = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOQ), MASS_DIAG='OUI',
    COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), ETAT_INIT=_F(VITE=V0),
    INCREMENT=_F(LIST_INST={name}),
    SCHEMA_TEMPS=_F(SCHEMA='DIFF_CENT', FORMULATION='ACCELERATION'))"
    );
    let args = args_of(&text, "DYNA_NON_LINE", 0);
    exec(&mut st, "DYNA_NON_LINE", &args, "RESU").unwrap();
    st
}

/// One AUTO run on `setup`'s bar (DEFI_LIST_INST METHODE='AUTO' over
/// `instants`, PAS_MAXI and NB_PAS_MAXI if given, every list instant
/// archived): the study, and the number of steps its .mess reports.
fn auto_run(
    instants: Vec<f64>,
    pas_maxi: Option<f64>,
    nb_pas_maxi: Option<usize>,
) -> (aster::study::Study, usize) {
    let mut list = aster::time::list::TimeList::plain(instants.clone());
    list.auto = true;
    list.pas_maxi = pas_maxi;
    if let Some(n) = nb_pas_maxi {
        list.nb_pas_maxi = n;
    }
    let st = run_bar(instants, Some(list));
    assert!(
        st.mess.contains("METHODE='AUTO' in explicit dynamics"),
        "{}",
        st.mess
    );
    let steps: usize = st
        .mess
        .lines()
        .find_map(|l| l.trim().split_once(" explicit steps"))
        .and_then(|(n, _)| n.parse().ok())
        .unwrap_or_else(|| panic!("no step count in\n{}", st.mess));
    (st, steps)
}

/// The archived instants of RESU.
fn instants_of(st: &aster::study::Study) -> Vec<f64> {
    result(st, "RESU").steps.iter().map(|s| s.inst).collect()
}

/// DY of node `n` at the last archived instant of RESU.
fn last_dy(st: &aster::study::Study, n: usize) -> f64 {
    let r = result(st, "RESU");
    r.steps.last().unwrap().nodal["DEPL"].get(n, "DY").unwrap()
}

/// DEFI_LIST_INST METHODE='AUTO' in explicit (an aster extension): the
/// list's instants are reached exactly, and in between the steps are the
/// critical step bound itself, cut into equal steps to land on each
/// instant: ceil(span / bound) steps per span, ceil(span / PAS_MAXI) with a
/// smaller PAS_MAXI. The run equals a manual list of those equal steps
/// (the same scheme and steps, to the round-off of the instants) and is
/// stable at the bound (the total energy kept over 20000 steps).
#[test]
fn auto_time_list_steps_at_the_critical_step_and_lands_on_the_instants() {
    let (mesh, mo, imp, top) = setup();
    let (bound, _) = limits(&mesh, &mo, &imp);
    let (t1, t2) = (50.5 * bound, 100.0 * bound);
    let (st, steps) = auto_run(vec![0.0, t1, t2], None, None);
    assert_eq!(steps, 51 + 50, "steps of the bound: 51 to {t1:e}, 50 more");
    assert_eq!(
        instants_of(&st),
        vec![0.0, t1, t2],
        "list instants, exactly"
    );
    let dy = last_dy(&st, top);
    // The same run on a manual list of the same equal steps.
    let mut manual = linspace(0.0, t1, 51);
    manual.extend(linspace(t1, t2, 50).into_iter().skip(1));
    let st = run_bar(manual, None);
    let dy_manual = last_dy(&st, top);
    println!("top DY: AUTO {dy:e}, manual {dy_manual:e}");
    assert!(
        (dy - dy_manual).abs() <= 1e-9 * dy_manual.abs(),
        "AUTO {dy} against the manual list {dy_manual}"
    );
    // PAS_MAXI below the bound caps the step.
    let (st, steps) = auto_run(vec![0.0, t1, t2], Some(bound / 3.0), None);
    assert_eq!(
        steps,
        152 + 149,
        "ceil(151.5) + ceil(148.5) steps of PAS_MAXI"
    );
    assert_eq!(instants_of(&st), vec![0.0, t1, t2]);
    // Stable at the bound: 20000 steps of it, the total energy of the
    // rough initial velocity (all modes excited) archived every 2000.
    let list: Vec<f64> = (0..=10).map(|k| 2000.0 * k as f64 * bound).collect();
    let (mut st, steps) = auto_run(list, None, None);
    assert!((20_000..=20_010).contains(&steps), "{steps} steps");
    let h = total_energy(&mut st);
    assert_eq!(h.len(), 11);
    let drift = h.iter().map(|e| (e - 1.0).abs()).fold(0.0, f64::max);
    println!("AUTO at the bound, 20000 steps: energy drift {drift:e}");
    assert!(drift < 0.05, "energy drift {drift}");
}

/// NB_PAS_MAXI ends a METHODE='AUTO' computation after that many steps,
/// as at the list's last instant (code_aster's ADAPTATION_13, an
/// information): the state of the last step is archived, the run ends
/// without error, and the .mess says so.
#[test]
fn nb_pas_maxi_ends_an_auto_run() {
    let (mesh, mo, imp, _) = setup();
    let (bound, _) = limits(&mesh, &mo, &imp);
    let list = vec![0.0, 50.5 * bound, 100.0 * bound];
    let (st, steps) = auto_run(list, None, Some(60));
    assert_eq!(steps, 60);
    assert!(
        st.mess.contains("NB_PAS_MAXI = 60 steps reached"),
        "{}",
        st.mess
    );
    let insts = instants_of(&st);
    assert_eq!(
        insts.len(),
        3,
        "t = 0, the list instant 50.5 bounds, the 60th step"
    );
    // 51 steps to 50.5 bounds, then 9 of the 50 equal steps to 100.
    let t60 = 50.5 * bound + 9.0 * (49.5 * bound / 50.0);
    assert!(
        (insts[2] - t60).abs() <= 1e-9 * t60,
        "last archived {:e}, expected {t60:e}",
        insts[2]
    );
}

/// A planned step that does not advance the time (here a PAS_MAXI far
/// below the resolution of the instants) stops the run with a message
/// instead of looping: the initial state is kept.
#[test]
fn a_step_that_does_not_advance_the_time_stops_the_run() {
    let instants = vec![1e-3, 1e-3 + 1e-6];
    let mut list = aster::time::list::TimeList::plain(instants.clone());
    list.auto = true;
    list.pas_maxi = Some(1e-25);
    let mut st = bar_study(instants, Some(list));
    let text =
        "RESU = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOQ), MASS_DIAG='OUI',
    COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), ETAT_INIT=_F(VITE=V0, INST=1.E-3),
    INCREMENT=_F(LIST_INST=LI),
    SCHEMA_TEMPS=_F(SCHEMA='DIFF_CENT', FORMULATION='ACCELERATION'))";
    let args = args_of(text, "DYNA_NON_LINE", 0);
    let m = exec(&mut st, "DYNA_NON_LINE", &args, "RESU").unwrap_err();
    assert!(m.contains("does not advance the time"), "{m}");
    assert_eq!(instants_of(&st), vec![1e-3]);
}

/// A DDL_IMPO under a FONC_MULT (a displacement ramp) in DIFF_CENT
/// (tests/verification/explicit_imposed_ramp.comm): the driven top of a 1D
/// rod follows the ramp with VITE = -V0 (it showed 0 before), the force on
/// it is the wave's rho c V0 A, TRAV_EXT its power rho c A V0^2 times t
/// and DISS_SCH 0 (every check in the file); here also: VITE of every
/// driven node at every archived instant after the start, and the balance
/// closes at every instant within 1e-3 of the velocity jump's 1/2 m_top
/// V0^2 (which DISS_SCH held before probe15b: the trapezoid counted the
/// jump's impulse twice).
#[test]
fn imposed_displacement_ramp_drives_the_rod() {
    let run = common::run_study(
        "tests/verification/explicit_imposed_ramp.comm",
        "explicit_imposed_ramp",
    );
    let resu = common::assert_all_ok(&run, "explicit_imposed_ramp.resu");
    let m_top = 8e-9 * 3.2 * 3.2 / 2.0 * 32.4 / 20.0 / 2.0;
    let jump = 0.5 * m_top * 1000.0f64.powi(2);
    let mut rows = 0;
    for r in common::printed_table(&resu, "EN") {
        if r["NUME_ORDRE"] == "0" {
            continue;
        }
        let diss: f64 = r["DISS_SCH"].parse().unwrap();
        assert!(diss.abs() <= 1e-3 * jump, "{r:?}");
        rows += 1;
    }
    assert_eq!(rows, 10, "{resu}");
    let vite: Vec<f64> = resu
        .lines()
        .filter(|l| l.starts_with("TOPV "))
        .map(|l| l.split_whitespace().last().unwrap().parse().unwrap())
        .collect();
    assert_eq!(vite.len(), 2);
    assert!(vite.iter().all(|v| (v + 1000.0).abs() < 1e-6), "{vite:?}");
}

/// DEFI_LIST_INST METHODE='AUTO' on PENTA15 cells made by LINE_QUAD
/// (tests/verification/explicit_auto_penta15.comm): each span of the list
/// is crossed in ceil(span / bound) steps of the critical step the .mess
/// prints (3.552168e-8 s: 2816 steps to 1e-4, 2816 more to 2e-4, 1127 to
/// 2.4e-4), never in fewer (the run stepped at 4.537e-8 s, 2204 steps to
/// 1e-4, and blew up at 3.9e-5 s); the quasi-static stretch then reaches
/// E U / L = 200 to 1 % (measured 200.06, every check in the file).
#[test]
fn auto_steps_stay_at_the_printed_bound_on_line_quad_pentas() {
    let run = common::run_study(
        "tests/verification/explicit_auto_penta15.comm",
        "explicit_auto_penta15",
    );
    common::assert_all_ok(&run, "explicit_auto_penta15.resu");
    let mess = run.file("explicit_auto_penta15.mess");
    let bound: f64 = mess
        .lines()
        .find_map(|l| l.split_once("DIFF_CENT: critical step "))
        .and_then(|(_, r)| r.split_whitespace().next())
        .and_then(|x| x.parse().ok())
        .unwrap_or_else(|| panic!("no critical step in\n{mess}"));
    assert!((bound - 3.552168e-8).abs() < 1e-13, "bound {bound:e}");
    // The cumulated step count printed at each archived list instant.
    let counts: Vec<usize> = mess
        .lines()
        .filter_map(|l| l.split_once(" after ")?.1.split_once(" steps"))
        .filter_map(|(n, _)| n.trim().parse().ok())
        .collect();
    let instants = [0.0, 1e-4, 2e-4, 2.4e-4];
    let mut expected = vec![0usize];
    for w in instants.windows(2) {
        let n = ((w[1] - w[0]) / bound).ceil() as usize;
        expected.push(expected.last().unwrap() + n);
    }
    assert_eq!(counts, expected, "steps to each instant\n{mess}");
}
