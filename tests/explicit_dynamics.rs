//! The explicit loop of DYNA_NON_LINE (DIFF_CENT, TCHAMWA) against
//! independent references: the CFL check of the time list (STOP_CFL), and
//! the measured stability limit of the loop on a small clamped mesh
//! against the element bound and the true limit 2/ω_max of the assembled
//! lumped system (a dense eigenvalue computation, independent of the
//! element inequality the bound rests on).

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

/// (element bound, true limit 2/ω_max of the assembled lumped system).
fn limits(mesh: &Mesh, mo: &Model, imp: &[aster::model::ImposedDof]) -> (f64, f64) {
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
    let s: Vec<f64> = free.iter().map(|&f| 1.0 / ex.mass[f].sqrt()).collect();
    let a = DMatrix::from_fn(neq, neq, |i, j| {
        0.5 * s[i] * (k.get(i, j) + k.get(j, i)) * s[j]
    });
    let w2 = SymmetricEigen::new(a).eigenvalues.max();
    (bound, 2.0 / w2.sqrt())
}

fn run_with(dt: f64, steps: usize, stop_cfl: &str, schema: &str) -> Result<(f64, f64), String> {
    let (mesh, mo, imp, top) = setup();
    let nn = mesh.nnodes();
    let vite = velocity(nn, &[top], 1000.0);
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
    INCREMENT=_F(LIST_INST=L_INST), ARCHIVAGE=_F(PAS_ARCH={}),
    SCHEMA_TEMPS=_F(SCHEMA='{schema}', FORMULATION='ACCELERATION', STOP_CFL='{stop_cfl}'))",
        steps / 10
    );
    let args = args_of(&text, "DYNA_NON_LINE", 0);
    exec(&mut st, "DYNA_NON_LINE", &args, "RESU")?;
    let r = result(&st, "RESU");
    let t = &r.tables["PARA_CALC"];
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
    let e0 = ek[0];
    let worst = ek
        .iter()
        .zip(&ei)
        .map(|(a, b)| ((a + b) / e0 - 1.0).abs())
        .fold(0.0, f64::max);
    Ok((e0, worst))
}

/// The element bound lies below the true limit of the assembled system
/// (the element eigenvalue inequality), the loop is stable at the bound
/// and just below the true limit (total energy kept to a few percent over
/// many steps), and unstable just above it (energy grows without bound,
/// the run stops on non-finite values or ends with an energy many times
/// the initial one).
#[test]
fn measured_stability_limit_lies_above_the_element_bound() {
    let (mesh, mo, imp, _) = setup();
    let (bound, exact) = limits(&mesh, &mo, &imp);
    println!("element bound {bound:e}, true limit {exact:e}");
    assert!(bound <= exact, "bound {bound} above the true limit {exact}");
    assert!(bound > 0.5 * exact, "bound {bound} far below {exact}");
    let (_, drift) = run_with(0.99999 * bound, 20_000, "OUI", "DIFF_CENT").unwrap();
    assert!(drift < 0.05, "at the bound: energy drift {drift}");
    let (_, drift) = run_with(0.98 * exact, 5_000, "NON", "DIFF_CENT").unwrap();
    assert!(drift < 0.2, "just below the limit: energy drift {drift}");
    match run_with(1.02 * exact, 5_000, "NON", "DIFF_CENT") {
        Err(m) => assert!(m.contains("not finite"), "{m}"),
        Ok((_, drift)) => assert!(drift > 1e3, "above the limit: energy drift {drift}"),
    }
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
    let (_, drift_dc) = run_with(dt, 4_000, "OUI", "DIFF_CENT").unwrap();
    let (_, drift_tc) = run_with(dt, 4_000, "OUI", "TCHAMWA").unwrap();
    println!("energy change: DIFF_CENT {drift_dc}, TCHAMWA {drift_tc}");
    assert!(drift_dc < 0.05);
    assert!(drift_tc > 0.2, "TCHAMWA kept the energy: {drift_tc}");
}
