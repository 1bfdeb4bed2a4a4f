//! Verification of discrete penalised contact inside DYNA_NON_LINE
//! (docs/contact.md §8): an elastic Taylor bar (AXIS, 2 × 8 QUAD8) landing
//! flat on the rigid foundation, with and without Coulomb friction.
//!
//! References are independent of the contact code: the momentum balance of
//! the bar (the consistent mass times the velocities, against the time
//! integral of the contact forces), the penalty law read back node by node,
//! the Coulomb bound, and the scaling of the penetration with E_N.
#![allow(clippy::needless_range_loop)]

mod dynamics_support;

use aster::concepts::{ConceptData, ConceptType};
use aster::mesh::ops::{orie_peau, OrieDim};
use aster::mesh::Mesh;
use aster::model::{Dof, MaterialField, MechLoad};
use aster::nonlinear::{discretize, Occurrence};
use aster::result::{EvolNoli, NodalField};
use dynamics_support::*;

const E: f64 = 117000.0;
const RHO: f64 = 8.93e-9;
/// Landing velocity (mm/s): 10 m/s keeps the copper elastic (ρ c V ≈ 323 MPa
/// is below nothing here: the law is ELAS).
const V: f64 = -1.0e4;
const DT: f64 = 2e-7;
const T_END: f64 = 3.0e-5;
/// A dissipative Newmark (γ > ½, β = (γ + ½)²/4): the penalty springs
/// (E_N/m far above 1/Δt²) ring undamped with the trapezoidal rule, and
/// their on/off switching then feeds energy into the bar.
const GAMMA: f64 = 0.6;
const BETA: f64 = 0.3025;

struct Run {
    mesh: Mesh,
    result: EvolNoli,
    /// Consistent mass on full dofs (per radian, as the element forces).
    mass: aster::solver::SparseMatrix,
    slaves: Vec<usize>,
}

/// The bar of the Taylor mesh (its foundation left out of the model: the
/// master RIGID does not move), gap 2.27 closed at t = 0 by the flight
/// from t0 = 2.27/V; `friction` = (COULOMB, E_T); an initial radial
/// velocity k·r on top of V.
fn landing(nu: f64, e_n: f64, friction: Option<(f64, f64)>, k_radial: f64) -> Run {
    let mut mesh = taylor_axis(2, 8);
    orie_peau(&mut mesh, OrieDim::D2, &["SZZ", "RIGID"], None).unwrap();
    let vol = mesh.cell_groups["VOL"].clone();
    let bar_nodes = mesh.nodes_of_cells(&vol);
    let axe = mesh.nodes_of_cells(&mesh.cell_groups["AXE"]);
    let slaves = mesh.nodes_of_cells(&mesh.cell_groups["SZZ"]);
    let mo = model(&mesh, "AXIS", &vol);
    let mut v0 = NodalField::absent(vec!["DX".into(), "DY".into()], mesh.nnodes());
    for &n in &bar_nodes {
        v0.set(n, 0, k_radial * mesh.coords[n][0]);
        v0.set(n, 1, V);
    }
    let t0 = 2.27 / V;
    let mut t = vec![t0, -DT];
    let nsteps = ((T_END + DT) / DT).round() as usize;
    for k in 1..nsteps {
        t.push(-DT + k as f64 * DT);
    }
    let mat = material(E, nu, RHO, None);
    let mut st = study(
        mesh.clone(),
        mo.clone(),
        mat.clone(),
        imposed(&axe, Dof::Dx, 0.0),
        Some(v0),
        t,
        None,
    );
    let frot = match friction {
        Some((mu, e_t)) => format!(
            "FROTTEMENT='COULOMB', ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ', \
             ALGO_CONT='PENALISATION', E_N={e_n:e}, ALGO_FROT='PENALISATION', E_T={e_t:e}, \
             COULOMB={mu}, COEF_MATR_FROT=0.4)"
        ),
        // E_N = 0: the catalogue default ALGO_CONT='CONTRAINTE' (active set).
        None if e_n == 0.0 => "ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ')".to_string(),
        None => format!(
            "ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ', ALGO_CONT='PENALISATION', E_N={e_n:e})"
        ),
    };
    let text = format!(
        "CONT = DEFI_CONTACT(MODELE=MO, FORMULATION='DISCRETE', REAC_GEOM='CONTROLE', NB_ITER_GEOM=2, {frot})
RESU = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOQ), CONTACT=CONT,
    COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'),
    ETAT_INIT=_F(VITE=V0),
    INCREMENT=_F(LIST_INST=L_INST),
    SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', BETA={BETA}, GAMMA={GAMMA}, FORMULATION='DEPLACEMENT'),
    CONVERGENCE=_F(RESI_GLOB_RELA=1.E-8, ITER_GLOB_MAXI=30))"
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
            relation: "ELAS".into(),
            deformation: "PETIT".into(),
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
    Run {
        mesh,
        result,
        mass: asm.mass_full,
        slaves,
    }
}

/// The impact phase of a landing: the steps of the first and last contact,
/// the axial momentum before and after, the impulse of the contact forces
/// and the contact duration.
#[derive(Debug)]
#[allow(dead_code)]
struct Rebound {
    first: usize,
    last: usize,
    p_before: f64,
    p_after: f64,
    impulse: f64,
    duration: f64,
}

impl Run {
    /// Checks the elastic 1D bar's impact (frictionless landing flat, NU =
    /// 0): free flight exact before it, the impulse of the contact forces
    /// equal to the change of momentum within 2 % (Newmark integrates the
    /// momentum balance with the weights of its velocity update), contact
    /// for 2L/c within 10 %, and about the opposite momentum after it.
    fn rebound(&self) -> Rebound {
        let steps = self.result.steps.len();
        // Step 1 is the end of the free flight (t = −DT): open, gap V·DT.
        assert!(!self.in_contact(1));
        let first = (1..steps)
            .find(|&s| self.in_contact(s))
            .expect("the bar lands");
        let last = (first..steps)
            .rev()
            .find(|&s| self.in_contact(s))
            .expect("contact");
        assert!(last + 5 < steps, "the bar must have left before the end");
        let p_before = self.momentum_y(first - 1);
        let p_after = self.momentum_y(last + 1);
        let p0 = RHO * V * 3.2 * 3.2 / 2.0 * 32.4;
        assert!(
            (p_before - p0).abs() < 1e-9 * p0.abs(),
            "{p_before} vs {p0}"
        );
        assert!(p_after > 0.0, "rebound: momentum {p_after} after contact");
        // Impulse of the contact forces (minus RY on the slave nodes, per
        // radian: CONT_NOEU prints minus the force on the slave, as
        // code_aster, docs/contact.md §4), with the weights of Newmark's
        // velocity update v_{n+1} = v_n + Δt[(1 − γ) a_n + γ a_{n+1}].
        let mut impulse = 0.0;
        for s in first..=last + 1 {
            let dt = self.result.steps[s].inst - self.result.steps[s - 1].inst;
            impulse -= dt * (GAMMA * self.total(s, "RY") + (1.0 - GAMMA) * self.total(s - 1, "RY"));
        }
        let dp = p_after - p_before;
        assert!(
            (impulse - dp).abs() <= 0.02 * dp.abs(),
            "impulse {impulse} vs momentum change {dp}"
        );
        // An elastic 1D bar leaves with the opposite velocity after 2L/c.
        let two_l_c = 2.0 * 32.4 / (E / RHO).sqrt();
        let duration = self.result.steps[last + 1].inst - self.result.steps[first - 1].inst;
        assert!(
            (duration - two_l_c).abs() < 0.1 * two_l_c,
            "contact duration {duration} vs 2L/c = {two_l_c}"
        );
        assert!(
            (p_after + p_before).abs() < 0.1 * p_before.abs(),
            "rebound momentum {p_after} vs {}",
            -p_before
        );
        Rebound {
            first,
            last,
            p_before,
            p_after,
            impulse,
            duration,
        }
    }

    fn cont(&self, step: usize, node: usize, cmp: &str) -> f64 {
        self.result.steps[step].nodal["CONT_NOEU"]
            .get(node, cmp)
            .unwrap_or_else(|| panic!("CONT_NOEU {cmp} absent at node {}", node + 1))
    }
    /// Axial momentum per radian: Σ (M v)_y.
    fn momentum_y(&self, step: usize) -> f64 {
        let vite = &self.result.steps[step].nodal["VITE"];
        let n = self.mesh.nnodes();
        let mut v = vec![0.0; 2 * n];
        for node in 0..n {
            v[2 * node] = vite.get(node, "DX").filter(|x| !x.is_nan()).unwrap_or(0.0);
            v[2 * node + 1] = vite.get(node, "DY").filter(|x| !x.is_nan()).unwrap_or(0.0);
        }
        let mut mv = vec![0.0; 2 * n];
        self.mass.mul_vec(&v, &mut mv);
        (0..n).map(|i| mv[2 * i + 1]).sum()
    }
    fn total(&self, step: usize, cmp: &str) -> f64 {
        self.slaves.iter().map(|&n| self.cont(step, n, cmp)).sum()
    }
    fn in_contact(&self, step: usize) -> bool {
        self.slaves
            .iter()
            .any(|&n| self.cont(step, n, "CONT") > 0.0)
    }
    /// ∫ Σ_nodes (−JEU) dt over the closed nodes.
    fn integrated_penetration(&self) -> f64 {
        let mut acc = 0.0;
        for s in 1..self.result.steps.len() {
            let dt = self.result.steps[s].inst - self.result.steps[s - 1].inst;
            for &n in &self.slaves {
                if self.cont(s, n, "CONT") > 0.0 {
                    acc -= dt * self.cont(s, n, "JEU");
                }
            }
        }
        acc
    }
    fn max_penetration(&self) -> f64 {
        let mut m: f64 = 0.0;
        for s in 0..self.result.steps.len() {
            for &n in &self.slaves {
                m = m.max(-self.cont(s, n, "JEU"));
            }
        }
        m
    }
}

/// (1) Frictionless elastic landing (NU = 0, a 1D bar): the bar rebounds;
/// the trapezoidal time integral of the total contact force equals the
/// change of axial momentum within 2 % (Newmark γ = ½ integrates the
/// momentum balance with the trapezoidal rule, so the match is close to
/// round-off here); JEU = −RN/E_N at every closed node; once the contact
/// has opened after the impact it stays open (the bar has left).
#[test]
fn elastic_bar_lands_and_rebounds() {
    let e_n = 1e7;
    let r = landing(0.0, e_n, None, 0.0);
    let steps = r.result.steps.len();
    let impact = r.rebound();
    // Penalty law node by node, and no gap opening in the middle of the
    // contact phase while the bar is still pressing... (after `last`, open
    // for good).
    let mut closed = 0;
    for s in 0..steps {
        for &n in &r.slaves {
            let (jeu, rn) = (r.cont(s, n, "JEU"), r.cont(s, n, "RN"));
            if r.cont(s, n, "CONT") > 0.0 {
                closed += 1;
                assert!(jeu < 0.0);
                assert!(
                    (-jeu - rn / e_n).abs() <= 1e-9 * rn / e_n,
                    "node {}: JEU {jeu} RN {rn}",
                    n + 1
                );
            } else {
                assert!(jeu >= 0.0 && rn == 0.0);
            }
            if s > impact.last {
                assert!(jeu > 0.0, "the gap stays open after the rebound");
            }
        }
    }
    assert!(closed > 20);
    eprintln!(
        "landing: {impact:?}, max penetration {:.4e}",
        r.max_penetration()
    );
}

/// (1b) The same landing with ALGO_CONT='CONTRAINTE' (the active set):
/// no slave node ever goes through the foundation (JEU ≥ −1e-12 mm at
/// every step) and a closed node sits on it (|JEU| ≤ 1e-12); the impulse
/// of the multipliers equals the change of momentum within 2 %; the bar
/// leaves after about 2L/c with about the opposite momentum, as the 1D
/// elastic bar does.
#[test]
fn elastic_bar_lands_and_rebounds_on_the_active_set() {
    let r = landing(0.0, 0.0, None, 0.0);
    let steps = r.result.steps.len();
    let impact = r.rebound();
    let mut closed = 0;
    for s in 0..steps {
        for &n in &r.slaves {
            let (jeu, rn) = (r.cont(s, n, "JEU"), r.cont(s, n, "RN"));
            assert!(jeu >= -1e-12, "step {s} node {}: JEU {jeu}", n + 1);
            if r.cont(s, n, "CONT") > 0.0 {
                closed += 1;
                assert!(
                    rn > 0.0 && jeu.abs() <= 1e-12,
                    "step {s} node {}: JEU {jeu} RN {rn}",
                    n + 1
                );
            } else {
                assert_eq!(rn, 0.0);
            }
        }
    }
    assert!(closed > 20);
    eprintln!("active-set landing: {impact:?}");
}

/// (3) E_N ten times larger: the penetration ten times smaller. Measured
/// as the time integral of the summed penetration over the impact, which
/// is the total impulse over E_N: the penalty is far stiffer than the bar,
/// so the impulse (≈ twice the momentum) hardly changes with E_N.
#[test]
fn penetration_scales_with_one_over_e_n() {
    let a = landing(0.0, 1e7, None, 0.0);
    let b = landing(0.0, 1e8, None, 0.0);
    let (ia, ib) = (a.integrated_penetration(), b.integrated_penetration());
    let (ma, mb) = (a.max_penetration(), b.max_penetration());
    eprintln!(
        "penetration: integrated E_N 1e7 -> {ia:.6e}, 1e8 -> {ib:.6e}, ratio {:.4}; max {ma:.4e} / {mb:.4e}, ratio {:.4}",
        ia / ib,
        ma / mb
    );
    assert!((ia / ib - 10.0).abs() < 0.5, "ratio {}", ia / ib);
}

/// (2) Coulomb friction 0.25: with a fast radial spreading (k·r, 1e5 mm/s
/// at the edge) the slave nodes slide and every sliding node carries a
/// friction force 0.25 × RN against its slip (RTGX, minus that force as
/// code_aster prints it, along the slip); with a slow one (10 mm/s, NU = 0) and COULOMB = 1
/// the friction needed stays below the bound and every closed node sticks.
#[test]
fn coulomb_friction_slides_at_the_bound_and_sticks_below_it() {
    let mu = 0.25;
    let fast = landing(0.3, 1e7, Some((mu, 1e5)), 1e5 / 3.2);
    let rigid = &fast.mesh.cells[fast.mesh.cell_groups["RIGID"][0]].nodes;
    let tau_x = (fast.mesh.coords[rigid[1]][0] - fast.mesh.coords[rigid[0]][0]).signum();
    let mut sliding = 0;
    for s in 0..fast.result.steps.len() {
        for &n in &fast.slaves {
            if fast.cont(s, n, "CONT") == 2.0 {
                sliding += 1;
                let rn = fast.cont(s, n, "RN");
                let rt = fast.cont(s, n, "RTGX");
                assert!(
                    (rt.abs() - mu * rn).abs() <= 1e-9 * rn,
                    "node {} step {s}: |RTGX| {rt} vs 0.25 RN {}",
                    n + 1,
                    mu * rn
                );
                // GLIX is the slip along τ1, the RIGID cell's direction:
                // the force on the node (x), −RTGX, opposes the slip
                // τ1x·GLIX.
                let slip_x = tau_x * fast.cont(s, n, "GLIX");
                assert!(
                    -rt * slip_x < 0.0,
                    "friction against the slip: RTGX {rt} (printed), slip {slip_x}"
                );
            }
        }
    }
    assert!(sliding > 10, "{sliding} sliding (node, step) pairs");
    // The landing itself loads the face tangentially (the nodal forces of
    // serendipity cells differ between corner and mid nodes, so the face
    // shears): about 0.3 RN at the edge. With COULOMB = 1 that load is
    // below the bound.
    let mu_stick = 1.0;
    let slow = landing(0.0, 1e7, Some((mu_stick, 1e5)), 10.0 / 3.2);
    // A node that touches at t = 0 with a round-off penetration (JEU ≈
    // −1e-12, RN ≈ 1e-5 N) has no friction capacity and slides: the claim
    // is about nodes that carry a real normal force (above 5 % of the peak
    // nodal force; near release a node with a few N slides, as it should).
    let peak = (0..slow.result.steps.len())
        .flat_map(|s| slow.slaves.iter().map(move |&n| (s, n)))
        .map(|(s, n)| slow.cont(s, n, "RN"))
        .fold(0.0, f64::max);
    let mut sticking = 0;
    for s in 0..slow.result.steps.len() {
        for &n in &slow.slaves {
            let c = slow.cont(s, n, "CONT");
            if c > 0.0 && slow.cont(s, n, "RN") > 0.05 * peak {
                assert_eq!(
                    c,
                    1.0,
                    "node {} step {s} slides: RN {} GLIX {} JEU {}",
                    n + 1,
                    slow.cont(s, n, "RN"),
                    slow.cont(s, n, "GLIX"),
                    slow.cont(s, n, "JEU")
                );
                sticking += 1;
                assert!(slow.cont(s, n, "RTAX").abs() <= mu_stick * slow.cont(s, n, "RN"));
            }
        }
    }
    assert!(sticking > 10);
    eprintln!("friction: {sliding} sliding pairs (fast), {sticking} sticking pairs (slow)");
}

/// The command-file version of (1): tests/verification/contact_landing.comm
/// (free flight exact, no force once the bar has left) runs to FIN with
/// every check OK.
#[test]
fn landing_study_runs_with_every_check_ok() {
    use aster::run::driver::{run_file, RunOptions};
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("contact_landing");
    let mut term = Vec::new();
    let code = run_file(
        &RunOptions {
            comm: root.join("tests/verification/contact_landing.comm"),
            out_dir: Some(out.clone()),
            ..RunOptions::default()
        },
        &mut term,
    );
    let term = String::from_utf8(term).unwrap();
    let resu = std::fs::read_to_string(out.join("contact_landing.resu")).unwrap();
    assert_eq!(code, 0, "{term}");
    assert!(!resu.lines().any(|l| l.starts_with("NOOK")), "{resu}");
    assert_eq!(
        resu.lines().filter(|l| l.starts_with(" OK ")).count(),
        6,
        "{resu}"
    );
}
