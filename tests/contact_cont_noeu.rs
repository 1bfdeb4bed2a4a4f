//! CONT_NOEU on a hand-made case (values computed by hand below), the
//! percussion, and the inputs of the COLLISION and INTERPENETRATION events.
//! The force vectors are printed as code_aster prints them, minus the force
//! on the slave node (docs/contact.md §4; whole studies in
//! tests/contact_cont_noeu_sign.rs).

use aster::contact::{
    collision_started, evaluate, pair, ContactDef, ContactState, ContactZone, Coulomb,
    IterationInput, LinkStatus, Pairing, ReacGeom, CONT_NOEU_COMPONENTS,
};
use aster::mesh::{Cell, CellType, Mesh};

/// Master SEG2 from (10,0) to (−10,0): outward normal +y, n_in = −y,
/// τ = −x. Slave node 2, and node 3 which belongs to nothing.
fn setup(friction: bool) -> (Mesh, ContactDef) {
    let mut m = Mesh {
        name: "M".into(),
        dim: 2,
        coords: vec![
            [10.0, 0.0, 0.0],
            [-10.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
            [5.0, 5.0, 0.0],
        ],
        cells: vec![Cell {
            kind: CellType::Seg2,
            nodes: vec![0, 1],
        }],
        ..Mesh::default()
    };
    m.cell_groups.insert("MAIT".into(), vec![0]);
    let d = ContactDef {
        dim: 2,
        friction,
        reac_geom: ReacGeom::Sans,
        algo: aster::contact::DiscreteAlgo::Penalty,
        ties: Vec::new(),
        continuous: None,
        zones: vec![ContactZone {
            master_group: "MAIT".into(),
            slave_group: "ESCL".into(),
            master_cells: vec![0],
            slave_nodes: vec![2],
            e_n: 1.0e4,
            friction: friction.then_some(Coulomb {
                mu: 0.25,
                e_t: 1.0e3,
                coef_matr_frot: 0.0,
            }),
            tole_proj_ext: Some(0.5),
            dist_appa: None,
            user_gap: Default::default(),
        }],
    };
    (m, d)
}

fn state_at(d: &ContactDef, p: &Pairing, slave: [f64; 3]) -> ContactState {
    let mut u = vec![[0.0; 3]; 4];
    u[2] = slave;
    // The step started with the slave node at x = 0.3 (pairing position).
    let mut u0 = vec![[0.0; 3]; 4];
    u0[2] = [0.3, 0.5, 0.0];
    let input = IterationInput {
        u: &u,
        u_start: &u0,
        resi_glob_rela: 0.0,
        symmetrise: false,
    };
    evaluate(d, p, &input, |n, c| (n == 2).then_some(c)).1
}

fn cmp(f: &aster::result::NodalField, node: usize, name: &str) -> f64 {
    f.get(node, name)
        .unwrap_or_else(|| panic!("{name} absent on node {node}"))
}

#[test]
fn components_and_signs_in_stick() {
    let (m, d) = setup(true);
    // Pair with the slave at (0.3, 0.5): projection (0.3, 0).
    let mut u = vec![[0.0; 3]; 4];
    u[2] = [0.3, 0.5, 0.0];
    let p = pair(&d, &m, &u);
    // Now at (0.305, −0.01): gap −0.01, λ_n = 100, slip g_t = τ·Δu = −0.005,
    // stick (|g_t| E_T = 5 ≤ μλ_n = 25), F_t = E_T g_t = −5.
    let mut s = state_at(&d, &p, [0.305, -0.01, 0.0]);
    assert_eq!(s.links[0].status, LinkStatus::Stick);
    s.step_percussion(1e-3);
    let f = s.cont_noeu(m.nnodes());
    assert_eq!(
        f.components,
        CONT_NOEU_COMPONENTS.map(String::from).to_vec()
    );
    assert_eq!(f.components.len(), 30);
    // Slave node only.
    for n in [0, 1, 3] {
        assert!(CONT_NOEU_COMPONENTS.iter().all(|c| f.get(n, c).is_none()));
    }
    let v = |c: &str| cmp(&f, 2, c);
    assert_eq!(v("CONT"), 1.0);
    assert!((v("JEU") + 0.01).abs() < 1e-15);
    // The force on the slave pushes it up (out of the foundation) and back
    // against its +x motion; CONT_NOEU prints its opposite, as code_aster
    // (docs/contact.md §4): RN* = λ_n n_in points into the foundation
    // (RNY < 0) and RT* along the motion (RTAX > 0).
    let on_slave = s.links[0].reaction();
    assert!(on_slave[0] < 0.0 && on_slave[1] > 0.0);
    assert!((v("RN") - 100.0).abs() < 1e-10);
    assert!(v("RNX").abs() < 1e-15 && (v("RNY") + 100.0).abs() < 1e-10);
    assert_eq!(v("RNZ"), 0.0);
    assert!((v("GLIX") + 0.005).abs() < 1e-15);
    assert_eq!(v("GLIY"), 0.0);
    assert!((v("GLI") - 0.005).abs() < 1e-15);
    assert!((v("RTAX") - 5.0).abs() < 1e-10 && v("RTAY").abs() < 1e-15);
    assert_eq!((v("RTGX"), v("RTGY"), v("RTGZ")), (0.0, 0.0, 0.0));
    assert!((v("RX") - 5.0).abs() < 1e-10 && (v("RY") + 100.0).abs() < 1e-10);
    assert!((v("RX") + on_slave[0]).abs() < 1e-12 && (v("RY") + on_slave[1]).abs() < 1e-12);
    let r = (100.0f64 * 100.0 + 25.0).sqrt();
    assert!((v("R") - r).abs() < 1e-10);
    assert_eq!(v("HN"), 0.0);
    assert!((v("I") - r * 1e-3).abs() < 1e-12);
    assert!((v("IX") - 5e-3).abs() < 1e-12 && (v("IY") + 0.1).abs() < 1e-12);
    assert_eq!((v("PT_X"), v("PT_Y"), v("PT_Z")), (0.0, 0.0, 0.0));
    assert!((v("PROJ_X") - 0.3).abs() < 1e-15 && v("PROJ_Y").abs() < 1e-15);
    assert_eq!(v("PROJ_Z"), 0.0);
}

#[test]
fn slip_and_frictionless_status() {
    let (m, d) = setup(true);
    let p = pair(&d, &m, &[[0.0; 3]; 4]);
    // Slip: |g_t| = 0.05 > μλ_n/E_T = 0.025; friction on RTG, |RT| = μ RN,
    // printed along the slip (+x: the opposite of the force on the slave).
    let s = state_at(&d, &p, [0.35, -0.01, 0.0]);
    let f = s.cont_noeu(4);
    assert_eq!(cmp(&f, 2, "CONT"), 2.0);
    assert!((cmp(&f, 2, "RTGX") - 25.0).abs() < 1e-10);
    assert_eq!(cmp(&f, 2, "RTAX"), 0.0);
    let r = cmp(&f, 2, "R");
    let (rn, rt) = (cmp(&f, 2, "RN"), 25.0f64);
    assert!((r - (rn * rn + rt * rt).sqrt()).abs() < 1e-10);
    // Without friction a contact link is 2 and has no slip reported.
    let (m, d) = setup(false);
    let p = pair(&d, &m, &[[0.0; 3]; 4]);
    let f = state_at(&d, &p, [0.35, -0.01, 0.0]).cont_noeu(4);
    assert_eq!(cmp(&f, 2, "CONT"), 2.0);
    assert_eq!(cmp(&f, 2, "GLI"), 0.0);
    assert!((cmp(&f, 2, "R") - 100.0).abs() < 1e-10);
    // Open: status 0, JEU still written, all forces 0.
    let f = state_at(&d, &p, [0.35, 0.2, 0.0]).cont_noeu(4);
    assert_eq!(cmp(&f, 2, "CONT"), 0.0);
    assert!((cmp(&f, 2, "JEU") - 0.2).abs() < 1e-15);
    assert_eq!(cmp(&f, 2, "R"), 0.0);
    assert_eq!(cmp(&f, 2, "PROJ_X"), 0.0);
}

#[test]
fn unpaired_slave_is_minus_one() {
    let (m, d) = setup(false);
    // Slave node moved 30 beyond the master's end: ξ far outside.
    let mut u = [[0.0; 3]; 4];
    u[2][0] = 30.0;
    let p = pair(&d, &m, &u);
    assert!(p.links.is_empty());
    let f = state_at(&d, &p, [30.0, -0.01, 0.0]).cont_noeu(4);
    assert_eq!(cmp(&f, 2, "CONT"), -1.0);
    assert_eq!(cmp(&f, 2, "JEU"), 0.0);
}

/// The discrete formulation's percussion is R·dt of the step only
/// (code_aster's `cfresu` zeroes the stored percussion of every link
/// before adding R·dt), with the printed (code_aster) sign of R*.
#[test]
fn discrete_percussion_is_the_step_impulse() {
    // Frictionless, so that R = λ_n = E_N·penetration.
    let (m, d) = setup(false);
    let p = pair(&d, &m, &[[0.0; 3]; 4]);
    let dt = 2e-4;
    let mut s1 = state_at(&d, &p, [0.0, -0.01, 0.0]);
    s1.step_percussion(dt);
    assert!((s1.links[0].percussion[0] - 100.0 * dt).abs() < 1e-15);
    // IY: RY·dt, RY = −100 (pointing into the foundation, below).
    assert!((s1.links[0].percussion[2] + 100.0 * dt).abs() < 1e-15);
    // The next step: 200·dt, not (100 + 200)·dt.
    let mut s2 = state_at(&d, &p, [0.0, -0.02, 0.0]);
    s2.step_percussion(dt);
    assert!((s2.links[0].percussion[0] - 200.0 * dt).abs() < 1e-12);
    assert!((s2.links[0].percussion[2] + 200.0 * dt).abs() < 1e-12);
    assert_eq!(s2.links[0].percussion[1], 0.0);
    let f = s2.cont_noeu(4);
    assert!((cmp(&f, 2, "I") - 200.0 * dt).abs() < 1e-12);
    assert!((cmp(&f, 2, "IY") + 200.0 * dt).abs() < 1e-12);
    // Open: R = 0, I = 0.
    let mut s3 = state_at(&d, &p, [0.0, 0.1, 0.0]);
    s3.step_percussion(dt);
    assert_eq!(s3.links[0].percussion, [0.0; 4]);
    // A vanishing but nonzero force (R = 5e-7 ≤ 1e-6) gives 0 too.
    let mut s5 = state_at(&d, &p, [0.0, -5e-11, 0.0]);
    s5.step_percussion(dt);
    assert!(s5.links[0].status.in_contact());
    assert_eq!(s5.links[0].percussion, [0.0; 4]);
}

/// The continuous formulation's percussion accumulates over the steps and
/// each step adds R·dt once per contact point at the node (code_aster's
/// `mmmres`: a node shared by two slave cells is visited twice); it
/// restarts at 0 whenever R ≤ 1e-6.
#[test]
fn continuous_percussion_accumulates_per_visit_and_resets() {
    let (m, d) = setup(false);
    let p = pair(&d, &m, &[[0.0; 3]; 4]);
    let dt = 2e-4;
    let two = |_: usize, _: usize| 2;
    let mut s1 = state_at(&d, &p, [0.0, -0.01, 0.0]);
    s1.accumulate_percussion(None, dt, two);
    assert!((s1.links[0].percussion[0] - 2.0 * 100.0 * dt).abs() < 1e-15);
    let mut s2 = state_at(&d, &p, [0.0, -0.02, 0.0]);
    s2.accumulate_percussion(Some(&s1), dt, two);
    assert!((s2.links[0].percussion[0] - 2.0 * (100.0 + 200.0) * dt).abs() < 1e-12);
    assert!((s2.links[0].percussion[2] + 2.0 * (100.0 + 200.0) * dt).abs() < 1e-12);
    // Open at the next step: R = 0 ≤ 1e-6, the percussion restarts.
    let mut s3 = state_at(&d, &p, [0.0, 0.1, 0.0]);
    s3.accumulate_percussion(Some(&s2), dt, two);
    assert_eq!(s3.links[0].percussion, [0.0; 4]);
    let mut s4 = state_at(&d, &p, [0.0, -0.01, 0.0]);
    s4.accumulate_percussion(Some(&s3), dt, |_, _| 1);
    assert!((s4.links[0].percussion[0] - 100.0 * dt).abs() < 1e-12);
    // A vanishing but nonzero force (R = 5e-7 ≤ 1e-6) also resets.
    let mut s5 = state_at(&d, &p, [0.0, -5e-11, 0.0]);
    s5.accumulate_percussion(Some(&s4), dt, two);
    assert!(s5.links[0].status.in_contact());
    assert_eq!(s5.links[0].percussion, [0.0; 4]);
}

#[test]
fn collision_and_interpenetration() {
    let (m, d) = setup(false);
    let p = pair(&d, &m, &[[0.0; 3]; 4]);
    let open = state_at(&d, &p, [0.0, 0.3, 0.0]);
    let closed = state_at(&d, &p, [0.0, -2e-5, 0.0]);
    assert_eq!(collision_started(&open, &closed), vec![true]);
    assert_eq!(collision_started(&closed, &open), vec![true]);
    assert_eq!(collision_started(&open, &open), vec![false]);
    assert_eq!(open.max_interpenetration(), 0.0);
    assert!((closed.max_interpenetration() - 2e-5).abs() < 1e-18);
    // PENE_MAXI = 1e-5 of sdnv103i would fire here.
    assert!(closed.max_interpenetration() > 1e-5);
}

/// The field of the initial instant (NUME_ORDRE 0): every component 0 on
/// the slave node, paired or not and whatever its gap, absent on the other
/// nodes (code_aster's `cfmxr0`; the minimum of JEU in SDNV103 I relies on
/// it).
#[test]
fn initial_field_is_zero_on_slave_nodes() {
    let (m, d) = setup(true);
    let p = pair(&d, &m, &[[0.0; 3]; 4]);
    for slave in [[0.0, 0.3, 0.0], [0.0, -0.01, 0.0]] {
        let s = state_at(&d, &p, slave);
        assert_ne!(s.links[0].gap, 0.0);
        let f = s.cont_noeu_initial(4);
        for name in CONT_NOEU_COMPONENTS {
            assert_eq!(f.get(2, name), Some(0.0), "{name}");
            for other in [0, 1, 3] {
                assert_eq!(f.get(other, name), None, "{name} on {other}");
            }
        }
        // The field of a converged step carries the gap.
        assert_eq!(s.cont_noeu(4).get(2, "JEU"), Some(s.links[0].gap));
    }
    // An unpaired slave node is 0 too (not −1) before the first step.
    let far = ContactState {
        dim: 2,
        links: vec![],
        unpaired: vec![(0, 2)],
    };
    let f = far.cont_noeu_initial(4);
    assert_eq!(f.get(2, "CONT"), Some(0.0));
}
