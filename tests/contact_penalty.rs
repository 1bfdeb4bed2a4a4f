//! Penalised contact and Coulomb friction at fixed pairing: the tangent
//! against central finite differences of the residual, the penalty and
//! Coulomb laws, and a block pressed on a plane solved by a small Newton
//! loop written here (references: P/E_N, T/E_T, μP).

use aster::contact::{
    evaluate, pair, ContactDef, ContactState, ContactZone, Contribution, Coulomb, IterationInput,
    LinkStatus, Pairing, ReacGeom,
};
use aster::mesh::{Cell, CellType, Mesh};

/// A mesh made of one master cell (nodes 0..k) and one slave node (k).
fn one_cell(kind: CellType, master: &[[f64; 3]], slave: [f64; 3]) -> Mesh {
    let mut coords = master.to_vec();
    coords.push(slave);
    let dim = if kind.dim() == 1 { 2 } else { 3 };
    let mut m = Mesh {
        name: "M".into(),
        dim,
        coords,
        cells: vec![Cell {
            kind,
            nodes: (0..master.len()).collect(),
        }],
        ..Mesh::default()
    };
    m.cell_groups.insert("MAIT".into(), vec![0]);
    m
}

fn def(mesh: &Mesh, e_n: f64, friction: Option<Coulomb>) -> ContactDef {
    ContactDef {
        dim: mesh.dim,
        friction: friction.is_some(),
        reac_geom: ReacGeom::Sans,
        algo: aster::contact::DiscreteAlgo::Penalty,
        ties: Vec::new(),
        continuous: None,
        zones: vec![ContactZone {
            master_group: "MAIT".into(),
            slave_group: "ESCL".into(),
            master_cells: vec![0],
            slave_nodes: vec![mesh.nnodes() - 1],
            e_n,
            friction,
            tole_proj_ext: Some(0.5),
            dist_appa: None,
            user_gap: Default::default(),
        }],
    }
}

fn coulomb(mu: f64, e_t: f64, coef: f64) -> Option<Coulomb> {
    Some(Coulomb {
        mu,
        e_t,
        coef_matr_frot: coef,
    })
}

/// Dense residual and tangent with every dof free (dof = node·dim + c).
fn dense(c: &Contribution, ndof: usize) -> (Vec<f64>, Vec<Vec<f64>>) {
    let mut r = vec![0.0; ndof];
    let mut k = vec![vec![0.0; ndof]; ndof];
    for &(i, v) in &c.residual {
        r[i] += v;
    }
    for &(i, j, v) in &c.tangent {
        k[i][j] += v;
    }
    (r, k)
}

struct Case {
    def: ContactDef,
    pairing: Pairing,
    nnodes: usize,
    u_start: Vec<[f64; 3]>,
}

impl Case {
    fn eval(
        &self,
        u: &[[f64; 3]],
        resi: f64,
        sym: bool,
    ) -> (Vec<f64>, Vec<Vec<f64>>, ContactState) {
        let dim = self.def.dim;
        let input = IterationInput {
            u,
            u_start: &self.u_start,
            resi_glob_rela: resi,
            symmetrise: sym,
        };
        let (c, s) = evaluate(&self.def, &self.pairing, &input, |n, k| Some(n * dim + k));
        let (r, k) = dense(&c, self.nnodes * dim);
        (r, k, s)
    }

    /// max |K − ∂r/∂u (central differences)| / max |K|.
    fn fd_error(&self, u: &[[f64; 3]], resi: f64) -> f64 {
        let dim = self.def.dim;
        let (_, k, _) = self.eval(u, resi, false);
        let kmax = k.iter().flatten().fold(0.0f64, |a, &b| a.max(b.abs()));
        assert!(kmax > 0.0);
        let h = 1e-7;
        let mut err = 0.0f64;
        for n in 0..self.nnodes {
            for c in 0..dim {
                let mut up = u.to_vec();
                let mut um = u.to_vec();
                up[n][c] += h;
                um[n][c] -= h;
                let (rp, _, _) = self.eval(&up, resi, false);
                let (rm, _, _) = self.eval(&um, resi, false);
                let j = n * dim + c;
                for i in 0..rp.len() {
                    let d = (rp[i] - rm[i]) / (2.0 * h);
                    err = err.max((d - k[i][j]).abs());
                }
            }
        }
        err / kmax
    }
}

/// A curved SEG3 master ordered right to left, so that its outward normal
/// is ≈ +y (the master body below), and a slave node above its middle.
fn case_2d(friction: Option<Coulomb>) -> (Case, Vec<[f64; 3]>) {
    let master = [[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.05, 0.0]];
    let m = one_cell(CellType::Seg3, &master, [0.2, 0.3, 0.0]);
    let d = def(&m, 1000.0, friction);
    let p = pair(&d, &m, &vec![[0.0; 3]; m.nnodes()]);
    assert_eq!(p.links.len(), 1);
    assert!(
        p.links[0].normal[1] < -0.99,
        "n_in points down into the body"
    );
    let mut u_start = vec![[0.0; 3]; m.nnodes()];
    u_start[0] = [0.01, -0.002, 0.0];
    u_start[2] = [0.003, 0.001, 0.0];
    // Current: master moved a little, slave pushed below the surface.
    let mut u = u_start.clone();
    u[1] = [-0.004, 0.003, 0.0];
    u[3] = [0.0, -0.31, 0.0];
    (
        Case {
            def: d,
            pairing: p,
            nnodes: m.nnodes(),
            u_start,
        },
        u,
    )
}

fn quad8_master() -> Vec<[f64; 3]> {
    let z = |x: f64, y: f64| 0.05 * (1.0 - x * x) + 0.02 * y;
    let pts = [
        (-1.0, -1.0),
        (1.0, -1.0),
        (1.0, 1.0),
        (-1.0, 1.0),
        (0.0, -1.0),
        (1.0, 0.0),
        (0.0, 1.0),
        (-1.0, 0.0),
    ];
    pts.iter().map(|&(x, y)| [x, y, z(x, y)]).collect()
}

fn case_3d(friction: Option<Coulomb>) -> (Case, Vec<[f64; 3]>) {
    let m = one_cell(CellType::Quad8, &quad8_master(), [0.1, 0.2, 0.4]);
    let d = def(&m, 1000.0, friction);
    let p = pair(&d, &m, &vec![[0.0; 3]; m.nnodes()]);
    assert_eq!(p.links.len(), 1);
    let u_start = vec![[0.0; 3]; m.nnodes()];
    let mut u = u_start.clone();
    u[5] = [0.002, -0.001, 0.003];
    u[8] = [0.0, 0.0, -0.45];
    (
        Case {
            def: d,
            pairing: p,
            nnodes: m.nnodes(),
            u_start,
        },
        u,
    )
}

fn status(c: &Case, u: &[[f64; 3]]) -> LinkStatus {
    c.eval(u, 0.0, false).2.links[0].status
}

#[test]
fn frictionless_tangent_is_the_derivative() {
    let (c, u) = case_2d(None);
    assert_eq!(status(&c, &u), LinkStatus::Slip);
    assert!(c.fd_error(&u, 0.0) < 1e-6);
    let (c, u) = case_3d(None);
    assert!(c.fd_error(&u, 0.0) < 1e-6);
}

#[test]
fn stick_tangent_is_the_derivative() {
    // λ_n ≈ 1000·0.06 = 60, μλ_n/E_T ≈ 0.3·60/100 = 0.18 ≫ slip (~0.005).
    let (c, mut u) = case_2d(coulomb(0.3, 100.0, 0.0));
    u[3][0] = 0.005;
    assert_eq!(status(&c, &u), LinkStatus::Stick);
    assert!(c.fd_error(&u, 1.0) < 1e-6);
    let (c, mut u) = case_3d(coulomb(0.3, 100.0, 0.0));
    u[8][0] = 0.004;
    u[8][1] = -0.003;
    assert_eq!(status(&c, &u), LinkStatus::Stick);
    assert!(c.fd_error(&u, 1.0) < 1e-6);
}

/// With the default COEF_MATR_FROT = 0 and a large residual the slip
/// tangent is code_aster's MAF1 alone (`cffpm1`), the secant of the slip
/// law at fixed λ_n, K_f = (λ_f/|g_t|) Σ_k B_t,kᵀB_t,k: K_f·(u − u_start)
/// equals the friction residual exactly.
#[test]
fn slip_tangent_with_coef_matr_frot_0_is_the_secant() {
    let check = |cf: &Case, c0: &Case, u: &[[f64; 3]], resi: f64| {
        let dim = cf.def.dim;
        let (rf, kf, s) = cf.eval(u, resi, false);
        assert_eq!(s.links[0].status, LinkStatus::Slip);
        let (r0, k0, _) = c0.eval(u, resi, false);
        let du: Vec<f64> = (0..cf.nnodes)
            .flat_map(|n| (0..dim).map(move |c| (n, c)))
            .map(|(n, c)| u[n][c] - cf.u_start[n][c])
            .collect();
        let scale = rf
            .iter()
            .zip(&r0)
            .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
        assert!(scale > 0.0);
        for i in 0..rf.len() {
            let kdu: f64 = (0..du.len()).map(|j| (kf[i][j] - k0[i][j]) * du[j]).sum();
            assert!(
                (kdu - (rf[i] - r0[i])).abs() <= 1e-9 * scale,
                "row {i}: K_f du {kdu} vs r_f {}",
                rf[i] - r0[i]
            );
        }
    };
    let (cf, mut u) = case_2d(coulomb(0.3, 1000.0, 0.0));
    u[3][0] = 0.08;
    let (c0, _) = case_2d(None);
    check(&cf, &c0, &u, 1.0);
    // 3D: two tangents.
    let (cf, mut u) = case_3d(coulomb(0.3, 1000.0, 0.0));
    u[8][0] = 0.05;
    u[8][1] = 0.07;
    let (c0, _) = case_3d(None);
    check(&cf, &c0, &u, 1.0);
    // The secant is not ∂r/∂u.
    assert!(cf.fd_error(&u, 1.0) > 1e-2, "{}", cf.fd_error(&u, 1.0));
}

/// The full slip tangent (COEF_MATR_FROT = 1, or any coefficient once
/// RESI_GLOB_RELA < 1e-3) is the derivative of the friction force at fixed
/// normal force: (λ_f/|g_t|)(Σ_k B_t,k B_t,kᵀ − b_e b_eᵀ), b_e = Σ_k e_k B_t,k.
/// The full derivative adds the normal-tangential coupling
/// C = −μ E_N b_e B_nᵀ (λ_f = μ E_N (−g)), which code_aster leaves out and
/// so do we; this test rebuilds C from the link's normal, tangents and
/// master weights and checks K + C against central differences of the
/// whole contact residual, in 2D (one tangent, where the slip part of K is
/// 0) and in 3D on a curved QUAD8 with a slip along both tangents.
#[test]
fn slip_tangent_is_the_derivative_at_fixed_normal_force() {
    let check = |c: &Case, u: &[[f64; 3]], resi: f64, mu: f64, e_n: f64| {
        let dim = c.def.dim;
        let (_, k, s) = c.eval(u, resi, false);
        let st = &s.links[0];
        assert_eq!(st.status, LinkStatus::Slip);
        let link = &c.pairing.links[0];
        let nloc = c.nnodes * dim;
        // Local dof of (node, component) is node·dim + c here: the slave
        // is the last node, the master nodes are 0..k in order.
        let mut bn = vec![0.0; nloc];
        let mut be = vec![0.0; nloc];
        let g = (0..st.ntangents)
            .map(|q| st.slip[q] * st.slip[q])
            .sum::<f64>()
            .sqrt();
        for cc in 0..dim {
            bn[link.slave * dim + cc] -= link.normal[cc];
            for q in 0..st.ntangents {
                be[link.slave * dim + cc] += st.slip[q] / g * link.tangents[q][cc];
            }
            for (j, &n) in link.master_nodes.iter().enumerate() {
                bn[n * dim + cc] += link.shape[j] * link.normal[cc];
                for q in 0..st.ntangents {
                    be[n * dim + cc] -= link.shape[j] * st.slip[q] / g * link.tangents[q][cc];
                }
            }
        }
        let kmax = k.iter().flatten().fold(0.0f64, |a, &b| a.max(b.abs()));
        let h = 1e-7;
        let mut err = 0.0f64;
        for j in 0..nloc {
            let (n, cc) = (j / dim, j % dim);
            let mut up = u.to_vec();
            let mut um = u.to_vec();
            up[n][cc] += h;
            um[n][cc] -= h;
            let (rp, _, sp) = c.eval(&up, resi, false);
            let (rm, _, sm) = c.eval(&um, resi, false);
            assert_eq!(sp.links[0].status, LinkStatus::Slip);
            assert_eq!(sm.links[0].status, LinkStatus::Slip);
            for i in 0..nloc {
                let d = (rp[i] - rm[i]) / (2.0 * h);
                let coupling = -mu * e_n * be[i] * bn[j];
                err = err.max((d - k[i][j] - coupling).abs());
            }
        }
        assert!(
            err < 1e-6 * kmax,
            "max |FD − K − C| = {err:e}, max |K| = {kmax:e}"
        );
        // Without the coupling the difference is not round-off: the test
        // sees the term it adds.
        let cmax = (0..nloc)
            .flat_map(|i| (0..nloc).map(move |j| (i, j)))
            .fold(0.0f64, |a, (i, j)| a.max((mu * e_n * be[i] * bn[j]).abs()));
        assert!(cmax > 1e-3 * kmax);
    };
    let (c, mut u) = case_2d(coulomb(0.3, 1000.0, 1.0));
    u[3][0] = 0.08;
    check(&c, &u, 1.0, 0.3, 1000.0);
    let (c, mut u) = case_3d(coulomb(0.3, 1000.0, 1.0));
    u[8][0] = 0.05;
    u[8][1] = 0.07;
    check(&c, &u, 1.0, 0.3, 1000.0);
    // Any COEF_MATR_FROT once RESI_GLOB_RELA < 1e-3.
    let (c, _) = case_3d(coulomb(0.3, 1000.0, 0.4));
    check(&c, &u, 1e-4, 0.3, 1000.0);
    // A slip along τ2 mostly, with the master moving too.
    let (c, mut u) = case_3d(coulomb(0.3, 1000.0, 1.0));
    u[8][0] = -0.01;
    u[8][1] = 0.09;
    u[2] = [0.004, -0.003, 0.001];
    check(&c, &u, 1e-4, 0.3, 1000.0);
}

#[test]
fn coef_matr_frot_weights_the_slip_tangent_while_the_residual_is_large() {
    let build = |coef: f64| {
        let (c, mut u) = case_3d(coulomb(0.3, 1000.0, coef));
        u[8][0] = 0.05;
        u[8][1] = 0.07;
        (c, u)
    };
    let (c0, u) = build(0.0);
    let (c1, _) = build(1.0);
    let (c4, _) = build(0.4);
    let (_, k0, _) = c0.eval(&u, 0.5, false);
    let (_, k1, _) = c1.eval(&u, 0.5, false);
    let (r4, k4, _) = c4.eval(&u, 0.5, false);
    let (r1, _, _) = c1.eval(&u, 0.5, false);
    // The residual does not depend on COEF_MATR_FROT; the tangent is the
    // secant (w = 0) plus 0.4 times the correction −(λ_f/|g_t|) b_e b_eᵀ.
    assert_eq!(r4, r1);
    let mut slip_part = 0.0f64;
    for i in 0..k0.len() {
        for j in 0..k0.len() {
            let expect = k0[i][j] + 0.4 * (k1[i][j] - k0[i][j]);
            assert!((k4[i][j] - expect).abs() < 1e-9 * (1.0 + expect.abs()));
            slip_part = slip_part.max((k1[i][j] - k0[i][j]).abs());
        }
    }
    assert!(slip_part > 1.0, "the slip tangent is not negligible here");
    // Once RESI_GLOB_RELA < 1e-3 the full tangent is used whatever the coef.
    let (_, k0_small, _) = c0.eval(&u, 1e-4, false);
    assert_eq!(k0_small, k1);
    // Symmetrised: ½(K + Kᵀ).
    let (_, ks, _) = c1.eval(&u, 0.5, true);
    for i in 0..k1.len() {
        for j in 0..k1.len() {
            assert!(
                (ks[i][j] - 0.5 * (k1[i][j] + k1[j][i])).abs() < 1e-12 * (1.0 + k1[i][j].abs())
            );
            assert_eq!(ks[i][j], ks[j][i]);
        }
    }
}

#[test]
fn penalty_and_coulomb_cone() {
    // Flat QUAD4 master z = 0 (outward +z), slave pushed to z = −0.02.
    let master = [
        [-1.0, -1.0, 0.0],
        [1.0, -1.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
    ];
    let m = one_cell(CellType::Quad4, &master, [0.1, 0.1, 0.5]);
    let (e_n, e_t, mu) = (2.0e4, 3.0e3, 0.25);
    let d = def(&m, e_n, coulomb(mu, e_t, 0.0));
    let p = pair(&d, &m, &[[0.0; 3]; 5]);
    let u_start = vec![[0.0; 3]; 5];
    let state = |slip: [f64; 2]| {
        let mut u = vec![[0.0; 3]; 5];
        u[4] = [slip[0], slip[1], -0.52];
        let input = IterationInput {
            u: &u,
            u_start: &u_start,
            resi_glob_rela: 1.0,
            symmetrise: false,
        };
        evaluate(&d, &p, &input, |n, c| Some(3 * n + c)).1.links[0]
    };
    // Penalty: F_n = E_N × penetration.
    let s = state([0.0, 0.0]);
    assert!((s.gap + 0.02).abs() < 1e-14);
    assert!((s.lambda_n - e_n * 0.02).abs() < 1e-9);
    assert!(
        (s.normal_force()[2] - e_n * 0.02).abs() < 1e-9,
        "pushed up, out of the master"
    );
    // Stick: F_t = E_T g_t (threshold μλ_n/E_T = 0.25·400/3000 = 0.0333).
    let s = state([0.01, -0.02]);
    assert_eq!(s.status, LinkStatus::Stick);
    let (gx, gy) = (s.slip[0], s.slip[1]);
    assert!(
        ((gx * gx + gy * gy).sqrt() - (0.01f64.powi(2) + 0.02f64.powi(2)).sqrt()).abs() < 1e-14
    );
    assert!((s.friction[0] - e_t * gx).abs() < 1e-9 && (s.friction[1] - e_t * gy).abs() < 1e-9);
    // Slip: |F_t| = μ F_n exactly, along the slip.
    let s = state([0.06, 0.08]);
    assert_eq!(s.status, LinkStatus::Slip);
    let ft = (s.friction[0].powi(2) + s.friction[1].powi(2)).sqrt();
    assert!((ft - mu * s.lambda_n).abs() < 1e-12 * ft);
    let g = (s.slip[0].powi(2) + s.slip[1].powi(2)).sqrt();
    assert!((s.friction[0] / ft - s.slip[0] / g).abs() < 1e-14);
    // The force on the slave opposes its motion (+x, +y here).
    let f = s.friction_force();
    assert!(f[0] < 0.0 && f[1] < 0.0);
    let fn_ = (f[0].powi(2) + f[1].powi(2) + f[2].powi(2)).sqrt();
    assert!((fn_ - mu * e_n * 0.02).abs() < 1e-9);
    // Open: no force at all.
    let mut u = vec![[0.0; 3]; 5];
    u[4][2] = -0.4;
    let input = IterationInput {
        u: &u,
        u_start: &u_start,
        resi_glob_rela: 1.0,
        symmetrise: false,
    };
    let (c, st) = evaluate(&d, &p, &input, |n, c| Some(3 * n + c));
    assert_eq!(st.links[0].status, LinkStatus::Open);
    assert!((st.links[0].gap - 0.1).abs() < 1e-14);
    assert!(c.residual.is_empty() && c.tangent.is_empty() && c.nodal.is_empty());
}

/// The block: master SEG2 from (10,0) to (−10,0) (outward normal +y, the
/// foundation below), fixed; one slave node at the origin, free in x and
/// y, loaded by F_ext = (T, −P) and tied to the ground by a horizontal
/// spring k_s. Newton on R = r_c + k_s·u_x e_x − F_ext with the library's
/// tangent; returns the converged slave displacement and state.
fn block(p_load: f64, t_load: f64, k_s: f64) -> ([f64; 3], ContactState, Contribution) {
    let master = [[10.0, 0.0, 0.0], [-10.0, 0.0, 0.0]];
    let m = one_cell(CellType::Seg2, &master, [0.0, 0.0, 0.0]);
    let d = def(&m, 1.0e4, coulomb(0.25, 1.0e3, 0.4));
    let p = pair(&d, &m, &[[0.0; 3]; 3]);
    assert!((p.links[0].normal[1] + 1.0).abs() < 1e-15);
    let u_start = vec![[0.0; 3]; 3];
    let dof = |n: usize, c: usize| (n == 2 && c < 2).then_some(c);
    let mut u = vec![[0.0; 3]; 3];
    u[2][1] = -1e-3;
    let mut resi = 1.0;
    // The secant slip tangent converges linearly (about ½ per iteration
    // here), hence more iterations than a consistent tangent would need.
    for _ in 0..200 {
        let input = IterationInput {
            u: &u,
            u_start: &u_start,
            resi_glob_rela: resi,
            symmetrise: false,
        };
        let (c, s) = evaluate(&d, &p, &input, dof);
        let mut r = [k_s * u[2][0] - t_load, p_load];
        let mut k = [[k_s, 0.0], [0.0, 0.0]];
        for &(i, v) in &c.residual {
            r[i] += v;
        }
        for &(i, j, v) in &c.tangent {
            k[i][j] += v;
        }
        resi = (r[0].hypot(r[1])) / p_load.hypot(t_load);
        if resi < 1e-13 {
            return (u[2], s, c);
        }
        let det = k[0][0] * k[1][1] - k[0][1] * k[1][0];
        u[2][0] -= (k[1][1] * r[0] - k[0][1] * r[1]) / det;
        u[2][1] -= (k[0][0] * r[1] - k[1][0] * r[0]) / det;
    }
    panic!("Newton did not converge (RESI {resi:e})");
}

#[test]
fn block_on_plane_penetration_is_p_over_e_n() {
    let (u, s, c) = block(100.0, 0.0, 0.0);
    assert!((-u[1] - 100.0 / 1.0e4).abs() < 1e-14, "{}", u[1]);
    let l = &s.links[0];
    assert!((l.lambda_n - 100.0).abs() < 1e-10);
    assert_eq!(l.status, LinkStatus::Stick);
    // The imposed master nodes receive the opposite force (reactions):
    // the nodal vector sums to zero and the masters carry −r_slave.
    let mut sum = [0.0; 3];
    let mut master = [0.0; 3];
    for &(n, v) in &c.nodal {
        for k in 0..3 {
            sum[k] += v[k];
            if n != 2 {
                master[k] += v[k];
            }
        }
    }
    assert!(sum.iter().all(|v| v.abs() < 1e-10));
    // r on the slave is λ_n n_in = −100 e_y, so the masters get +100 e_y
    // in the residual, i.e. the foundation is pushed down by 100.
    assert!((master[1] - 100.0).abs() < 1e-10);
}

#[test]
fn block_sticks_below_the_cone() {
    // T = 10 < μP = 25: stick with slip T/E_T.
    let (u, s, _) = block(100.0, 10.0, 0.0);
    let l = &s.links[0];
    assert_eq!(l.status, LinkStatus::Stick);
    assert!((u[0] - 10.0 / 1.0e3).abs() < 1e-14, "{}", u[0]);
    assert!((l.slip[0].abs() - 0.01).abs() < 1e-14);
    assert!((l.friction_force()[0] + 10.0).abs() < 1e-10);
}

#[test]
fn block_slides_above_the_cone() {
    // T = 50 > μP = 25 with a horizontal spring k_s = 100: the block slides
    // until the spring takes the rest, u_x = (T − μP)/k_s = 0.25.
    let (u, s, _) = block(100.0, 50.0, 100.0);
    let l = &s.links[0];
    assert_eq!(l.status, LinkStatus::Slip);
    assert!((u[0] - 0.25).abs() < 1e-12, "{}", u[0]);
    let f = l.friction_force();
    assert!((f[0] + 25.0).abs() < 1e-10, "{f:?}");
    assert!((f[0].abs() - 0.25 * l.lambda_n).abs() < 1e-10);
    assert!((l.lambda_n - 100.0).abs() < 1e-10);
    // Below the cone, with the same spring, it would stick: u_x = T/(E_T + k_s).
    let (u, s, _) = block(100.0, 20.0, 100.0);
    assert_eq!(s.links[0].status, LinkStatus::Stick);
    assert!((u[0] - 20.0 / 1100.0).abs() < 1e-14);
}
