//! The contact forces that CONT_NOEU reports are (minus) the forces that
//! stop the bar: on the SDNV103 D impact (the 2 × 2 axisymmetric Taylor
//! bar, copper VMIS_ISOT_LINE in SIMO_MIEHE, discrete penalised contact
//! E_N = 1e10 with Coulomb 0.25, Newmark β = 0.49, γ = 0.9, D's time list
//! to 2e-5), the time integral of Σ RY over the slave nodes, with the
//! weights of Newmark's velocity update, equals minus the change of the
//! bar's axial momentum Σ (M v)_y (consistent mass, per radian): CONT_NOEU
//! prints, as code_aster, the contact term on the internal-force side of
//! the slave nodes' equilibrium, minus the force on them (docs/contact.md
//! §4), so RY < 0 on the bar's foot landing on the wall below it.
//!
//! Why it holds exactly: the bar's internal forces sum to zero in y
//! (translation invariance), no load acts on it and no dof of it is
//! imposed in y, so Σ_i (M a)_y,i = −Σ RY at every converged instant, up
//! to the Newton residual; Newmark's v_{n+1} = v_n + Δt[(1 − γ) a_n + γ
//! a_{n+1}] then carries it to the momentum. The reference (mass and
//! velocities) never goes through the contact code, and the check reads
//! the reported field, so a wrong RN/R definition (a share, a sign, a
//! weighting, a field taken at another moment) breaks it.
#![allow(clippy::needless_range_loop)]

mod dynamics_support;

use aster::concepts::{ConceptData, ConceptType};
use aster::mesh::ops::{orie_peau, OrieDim};
use aster::model::{Dof, MaterialField, MechLoad};
use aster::nonlinear::{discretize, Occurrence};
use aster::result::NodalField;
use dynamics_support::*;

const V: f64 = -227000.0;
const GAMMA: f64 = 0.9;
const BETA: f64 = 0.49;
const RESI: f64 = 1e-10;

#[test]
fn contact_impulse_equals_the_bar_momentum_change() {
    impulse_against_momentum(
        "FORMULATION='DISCRETE', REAC_GEOM='CONTROLE', NB_ITER_GEOM=2,
    FROTTEMENT='COULOMB', ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ', APPARIEMENT='MAIT_ESCL',
    ALGO_CONT='PENALISATION', E_N=1.E10, ALGO_FROT='PENALISATION', E_T=1.E5, COULOMB=0.25,
    COEF_MATR_FROT=0.4)",
    );
}

/// The same balance with the continuous formulation (SDNV103 F's contact
/// keywords on D's study): RY of CONT_NOEU is minus the force the
/// multipliers exert on the bar, as the discrete formulation's. It caught
/// the two formulations printing RN* with opposite signs (the continuous
/// one was aligned on the discrete one's then-convention on 2026-11-25;
/// both follow code_aster's since).
#[test]
fn continuous_contact_impulse_equals_the_bar_momentum_change() {
    impulse_against_momentum(
        "FORMULATION='CONTINUE', FROTTEMENT='COULOMB', ALGO_RESO_CONT='NEWTON',
    ALGO_RESO_FROT='NEWTON', ALGO_RESO_GEOM='NEWTON',
    ZONE=_F(APPARIEMENT='MAIT_ESCL', GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ', COULOMB=0.25)",
    );
}

/// Runs D's study with the DEFI_CONTACT keywords `contact` and checks
/// the impulse of Σ RY against the momentum change.
fn impulse_against_momentum(contact: &str) {
    let mut mesh = taylor_axis(2, 2);
    orie_peau(&mut mesh, OrieDim::D2, &["SZZ", "RIGID"], None).unwrap();
    let vol = mesh.cell_groups["VOL"].clone();
    let bar_nodes = mesh.nodes_of_cells(&vol);
    let axe = mesh.nodes_of_cells(&mesh.cell_groups["AXE"]);
    let slaves = mesh.nodes_of_cells(&mesh.cell_groups["SZZ"]);
    let mo = model(&mesh, "AXIS", &vol);
    let mut v0 = NodalField::absent(vec!["DX".into(), "DY".into()], mesh.nnodes());
    for &n in &bar_nodes {
        v0.set(n, 0, 0.0);
        v0.set(n, 1, V);
    }
    // D's list: -1e-5, 1 step to -1e-7, 4 to 1e-6, then steps of 0.5e-6
    // (158 to 8e-5 in D's file), here to 2e-5.
    let mut t = vec![-1e-5, -1e-7];
    for k in 1..=4 {
        t.push(-1e-7 + k as f64 * (1e-6 + 1e-7) / 4.0);
    }
    for k in 1..=38 {
        t.push(1e-6 + k as f64 * 0.5e-6);
    }
    let mat = material(117000.0, 0.35, 8.93e-9, Some((400.0, 100.0)));
    let mut st = study(
        mesh.clone(),
        mo.clone(),
        mat.clone(),
        imposed(&axe, Dof::Dx, 0.0),
        Some(v0),
        t,
        None,
    );
    let text = format!(
        "CONT = DEFI_CONTACT(MODELE=MO, {contact})
RESU = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOQ), CONTACT=CONT,
    COMPORTEMENT=_F(RELATION='VMIS_ISOT_LINE', DEFORMATION='SIMO_MIEHE', TOUT='OUI'),
    ETAT_INIT=_F(VITE=V0),
    INCREMENT=_F(LIST_INST=L_INST),
    SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', BETA={BETA}, GAMMA={GAMMA}, FORMULATION='DEPLACEMENT'),
    NEWTON=_F(MATRICE='TANGENTE', REAC_ITER=1),
    CONVERGENCE=_F(RESI_GLOB_RELA={RESI:e}, ITER_GLOB_MAXI=50))"
    );
    insert(
        &mut st,
        "CONT",
        ConceptType::CharContact,
        ConceptData::Contact(Box::new(args_of(&text, "DEFI_CONTACT", 0))),
    );
    exec(
        &mut st,
        "DYNA_NON_LINE",
        &args_of(&text, "DYNA_NON_LINE", 0),
        "RESU",
    )
    .unwrap();
    let result = result(&st, "RESU").clone();
    let mut materials = indexmap::IndexMap::new();
    materials.insert("MAT".to_string(), mat);
    let (asm, _) = discretize(
        &mesh,
        &mo,
        &MaterialField {
            mesh: "MAIL".into(),
            cell_material: vec![Some("MAT".into()); mesh.ncells()],
        },
        &materials,
        &[Occurrence {
            cells: None,
            relation: "VMIS_ISOT_LINE".into(),
            deformation: "SIMO_MIEHE".into(),
            controls: Default::default(),
        }],
        &[&MechLoad {
            model: "MO".into(),
            imposed: vec![],
            gravity: None,
            nodal_forces: Vec::new(),
            pressures: Vec::new(),
            distributed: Vec::new(),
            functions: Vec::new(),
            fields: Vec::new(),
        }],
    )
    .unwrap();
    let n = mesh.nnodes();
    let momentum_y = |s: usize| {
        let vite = &result.steps[s].nodal["VITE"];
        let mut v = vec![0.0; 2 * n];
        for node in 0..n {
            for (c, name) in ["DX", "DY"].iter().enumerate() {
                v[2 * node + c] = vite.get(node, name).filter(|x| !x.is_nan()).unwrap_or(0.0);
            }
        }
        let mut mv = vec![0.0; 2 * n];
        asm.mass_full.mul_vec(&v, &mut mv);
        (0..n).map(|i| mv[2 * i + 1]).sum::<f64>()
    };
    let total = |s: usize, cmp: &str| -> f64 {
        slaves
            .iter()
            .map(|&node| result.steps[s].nodal["CONT_NOEU"].get(node, cmp).unwrap())
            .sum()
    };
    let last = result.steps.len() - 1;
    assert!((result.steps[last].inst - 2e-5).abs() < 1e-15);
    let mut impulse = 0.0;
    let mut peak: f64 = 0.0;
    for s in 1..=last {
        let dt = result.steps[s].inst - result.steps[s - 1].inst;
        impulse += dt * (GAMMA * total(s, "RY") + (1.0 - GAMMA) * total(s - 1, "RY"));
        peak = peak.max(total(s, "RN"));
    }
    let (p0, p1) = (momentum_y(0), momentum_y(last));
    let dp = p1 - p0;
    let rel = (impulse + dp).abs() / dp.abs();
    eprintln!(
        "momentum: p0 {p0:.9e}, p1 {p1:.9e}, dp {dp:.9e}, contact impulse {impulse:.9e}, relative difference {rel:.2e}, peak Σ RN {peak:.4e} N/rad"
    );
    // The bar is stopped by a good part of its momentum by 2e-5 s, the
    // contact forces push it up (printed RY < 0 on the slave nodes).
    assert!(dp > 0.2 * p0.abs(), "dp {dp} of p0 {p0}");
    assert!(impulse < 0.0, "impulse {impulse}");
    // Measured: 1.1e-10 with RESI_GLOB_RELA = 1e-10 (the sum of the
    // residuals left at convergence over the 44 steps).
    assert!(
        rel < 1e-8,
        "impulse {impulse} vs minus the momentum change {dp}"
    );
}
