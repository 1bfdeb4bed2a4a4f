//! The continuous contact point in 3D (`FORMULATION='CONTINUE'` on a 3D
//! model): the same augmented-Lagrangian contact and Coulomb friction as
//! [`super::continuous::evaluate_point`], with two tangents τ1, τ2 and a
//! friction semi-multiplier Λ = (`LAGS_F1`, `LAGS_F2`) in their basis
//! (contact-continue.md §2, §4.2).
//!
//! A separate function rather than a generalisation of the 2D one: the 2D
//! path stays bit-identical (SDNV103 F's snapshot), and in 3D the slip
//! direction s = r/|r| of a point is a vector whose derivative
//! (I − s sᵀ)/|r| enters the tangent; in 2D that block vanishes
//! identically (s = ±1). With it the tangent is the exact derivative of the
//! residual at frozen pairing, except the friction rows' derivative with
//! respect to λ, left out as in 2D and in code_aster: its factor (the stick
//! slip g, the slip residual Λ − s) vanishes at the solution, so the
//! convergence stays quadratic near it, and with it the 3D block's slip
//! step went back and forth between stick and slip (8 iterations against
//! 4, tests/contact_continuous_block3d.rs).

use super::continuous::{normal_terms, Phase};

/// What a 3D point needs at one evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointInput3 {
    pub omega: f64,
    pub rho_n: f64,
    pub rho_t: f64,
    /// μ, None for a frictionless zone.
    pub mu: Option<f64>,
    /// The contact status s_p in force for this evaluation.
    pub status: bool,
    /// λ (`LAGS_C`).
    pub lambda: f64,
    /// λ_s, the threshold used when λ is exactly 0 or frozen.
    pub lambda_s: f64,
    /// `ALGO_RESO_FROT='POINT_FIXE'`: the threshold is λ_s even if λ ≠ 0.
    pub threshold_frozen: bool,
    /// Λ = (`LAGS_F1`, `LAGS_F2`) along (τ1, τ2).
    pub lambda_t: [f64; 2],
    /// Penetration d (> 0 penetrating).
    pub d: f64,
    /// Slip since the start of the step along τ1 and τ2.
    pub g_t: [f64; 2],
    /// Unit inward master normal n.
    pub normal: [f64; 3],
    /// Unit tangents τ1, τ2.
    pub tangents: [[f64; 3]; 2],
    /// Per tangent τ_k: every displacement the slip along τ_k depends on
    /// is imposed (each component of τ_k is 0 or an imposed dof at every
    /// node of the point), so the friction equation along τ_k has no
    /// displacement to act on: Λ_k is driven to 0 and the friction works
    /// along the other tangent only. Both: no friction at all. A symmetry
    /// plane Y0 (DY = 0) under a slave face z = const locks τ1 = e_y; the
    /// row of `LAGS_F1` was empty there and the tangent singular (probe
    /// s8g D4).
    pub slip_locked: [bool; 2],
}

/// Residual and derivatives of a 3D point, with respect to the jump [u]
/// (3), λ and Λ (2). `f` is the residual of the slave displacement (the
/// force on the slave node is −f).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PointOutput3 {
    pub f: [f64; 3],
    pub r_c: f64,
    pub r_f: [f64; 2],
    /// ∂f_i/∂[u]_j.
    pub df_du: [[f64; 3]; 3],
    pub df_dc: [f64; 3],
    /// ∂f_i/∂Λ_k.
    pub df_df: [[f64; 2]; 3],
    pub dc_du: [f64; 3],
    pub dc_dc: f64,
    /// ∂r_f,k/∂[u]_j.
    pub dfr_du: [[f64; 3]; 2],
    /// ∂r_f,k/∂Λ_l.
    pub dfr_df: [[f64; 2]; 2],
    /// Normal part of `f` (force on slave = −f_n).
    pub f_n: [f64; 3],
    /// Tangential components along τ1, τ2 (force on slave = −Σ f_t,k τ_k).
    pub f_t: [f64; 2],
}

/// The tangents of the continuous method, rebuilt from the inward normal
/// n as code_aster does (`mmmron`, note §2.3): τ1 is the normalised
/// (−n_y/n_x, 1, 0) if n_x ≠ 0, else (1, −n_x/n_y, 0) if n_y ≠ 0, else
/// (0, 1, −n_y/n_z); τ2 = τ1 × n (so that (τ1, τ2, −n) is right-handed,
/// as the pairing's basis). They fix the meaning of `LAGS_F1`/`LAGS_F2`
/// whatever the master cell's node order: on a plane z = const with the
/// master below, τ1 = e_y and τ2 = −e_x.
pub fn tangents_from_normal(n: [f64; 3]) -> [[f64; 3]; 2] {
    use crate::mesh::vec3::{cross, norm, scale};
    let eps = f64::EPSILON;
    let t = if n[0].abs() > eps {
        [-n[1] / n[0], 1.0, 0.0]
    } else if n[1].abs() > eps {
        [1.0, -n[0] / n[1], 0.0]
    } else {
        [0.0, 1.0, -n[1] / n[2]]
    };
    let t1 = scale(1.0 / norm(t), t);
    let t2 = cross(t1, n);
    [t1, scale(1.0 / norm(t2), t2)]
}

/// λ̂ and ∂λ̂/∂λ (`mmlagc`).
fn threshold(p: &PointInput3) -> (f64, f64) {
    if p.lambda != 0.0 && !p.threshold_frozen {
        (p.lambda, 1.0)
    } else {
        (p.lambda_s, 0.0)
    }
}

/// r = Λ + ρ_t g, 0 along a locked tangent (no friction there).
fn aug(p: &PointInput3) -> [f64; 2] {
    let r = |k: usize| {
        if p.slip_locked[k] {
            0.0
        } else {
            p.lambda_t[k] + p.rho_t * p.g_t[k]
        }
    };
    [r(0), r(1)]
}

/// The phase of a 3D point: stick while |Λ + ρ_t g| ≤ 1.
pub fn phase3(p: &PointInput3) -> Phase {
    if !p.status {
        return Phase::Sans;
    }
    if p.mu.is_none() {
        return Phase::Cont;
    }
    if threshold(p).0 == 0.0 {
        return Phase::Ncon;
    }
    let r = aug(p);
    if (r[0] * r[0] + r[1] * r[1]).sqrt() <= 1.0 {
        Phase::Adhe
    } else {
        Phase::Glis
    }
}

/// Residual and tangent of one 3D point.
pub fn evaluate_point3(p: &PointInput3) -> (Phase, PointOutput3) {
    let ph = phase3(p);
    let mut o = PointOutput3::default();
    let (w, n, t) = (p.omega, p.normal, p.tangents);
    let c = normal_terms(p.status, p.lambda, p.rho_n, p.d, w, n);
    (o.f, o.f_n, o.df_dc, o.dc_du, o.df_du) = (c.f, c.f, c.df_dc, c.dc_du, c.df_du);
    (o.r_c, o.dc_dc) = (c.r_c, c.dc_dc);
    let Some(mu) = p.mu else {
        return (ph, o);
    };
    let (lh, dl) = threshold(p);
    let free_lambda = |o: &mut PointOutput3| {
        for k in 0..2 {
            o.r_f[k] = w * p.lambda_t[k];
            o.dfr_df[k][k] = w;
        }
    };
    if p.slip_locked == [true, true] {
        free_lambda(&mut o);
        return (ph, o);
    }
    if let Some(k) = (0..2).find(|&k| p.slip_locked[k]) {
        // One tangent locked: the point with that tangent (and its Λ_k
        // and slip) removed is a friction point along the other tangent
        // alone; then Λ_k's own equation ω Λ_k = 0 is put back.
        let mut q = *p;
        q.slip_locked = [false; 2];
        q.tangents[k] = [0.0; 3];
        q.g_t[k] = 0.0;
        q.lambda_t[k] = 0.0;
        let (_, mut o) = evaluate_point3(&q);
        o.r_f[k] = w * p.lambda_t[k];
        o.dfr_du[k] = [0.0; 3];
        o.dfr_df[k] = [0.0; 2];
        o.dfr_df[k][k] = w;
        o.dfr_df[1 - k][k] = 0.0;
        for i in 0..3 {
            o.df_df[i][k] = 0.0;
        }
        return (ph, o);
    }
    let r = aug(p);
    let c = -w * mu * lh;
    match ph {
        Phase::Sans | Phase::Ncon | Phase::Cont => free_lambda(&mut o),
        Phase::Adhe => {
            o.f_t = [c * r[0], c * r[1]];
            for i in 0..3 {
                let rt = r[0] * t[0][i] + r[1] * t[1][i];
                o.f[i] += c * rt;
                o.df_dc[i] += -w * mu * dl * rt;
                for k in 0..2 {
                    o.df_df[i][k] = c * t[k][i];
                }
                for j in 0..3 {
                    o.df_du[i][j] += c * p.rho_t * (t[0][i] * t[0][j] + t[1][i] * t[1][j]);
                }
            }
            for k in 0..2 {
                o.r_f[k] = c * p.g_t[k];
                for j in 0..3 {
                    o.dfr_du[k][j] = c * t[k][j];
                }
            }
        }
        Phase::Glis => {
            let nr = (r[0] * r[0] + r[1] * r[1]).sqrt();
            let s = [r[0] / nr, r[1] / nr];
            // ∂s/∂r = (I − s sᵀ)/|r|.
            let mut ds = [[0.0; 2]; 2];
            for k in 0..2 {
                for l in 0..2 {
                    let id = if k == l { 1.0 } else { 0.0 };
                    ds[k][l] = (id - s[k] * s[l]) / nr;
                }
            }
            // τ_l[i] ∂s_l/∂r_k: the tangential direction's derivative.
            let mut tds = [[0.0; 2]; 3];
            for i in 0..3 {
                for k in 0..2 {
                    tds[i][k] = t[0][i] * ds[0][k] + t[1][i] * ds[1][k];
                }
            }
            o.f_t = [c * s[0], c * s[1]];
            for i in 0..3 {
                let st = s[0] * t[0][i] + s[1] * t[1][i];
                o.f[i] += c * st;
                o.df_dc[i] += -w * mu * dl * st;
                for k in 0..2 {
                    o.df_df[i][k] = c * tds[i][k];
                }
                for j in 0..3 {
                    o.df_du[i][j] += c * p.rho_t * (tds[i][0] * t[0][j] + tds[i][1] * t[1][j]);
                }
            }
            let a = w * mu * lh / p.rho_t;
            for k in 0..2 {
                o.r_f[k] = a * (p.lambda_t[k] - s[k]);
                for l in 0..2 {
                    let id = if k == l { 1.0 } else { 0.0 };
                    o.dfr_df[k][l] = a * (id - ds[k][l]);
                }
                for j in 0..3 {
                    o.dfr_du[k][j] = -a * p.rho_t * (ds[k][0] * t[0][j] + ds[k][1] * t[1][j]);
                }
            }
        }
    }
    (ph, o)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::continuous::{evaluate_point, PointInput};

    /// A tilted normal and an orthonormal tangent pair.
    fn base() -> PointInput3 {
        let s = 0.6f64;
        let c = 0.8f64;
        PointInput3 {
            omega: 1.7,
            rho_n: 100.0,
            rho_t: 100.0,
            mu: Some(0.3),
            status: true,
            lambda: -2.0,
            lambda_s: -2.0,
            threshold_frozen: false,
            lambda_t: [0.2, -0.3],
            d: 1e-3,
            g_t: [1e-3, 2e-3],
            normal: [0.0, s, -c],
            tangents: [[1.0, 0.0, 0.0], [0.0, c, s]],
            slip_locked: [false; 2],
        }
    }

    /// Central differences of the residual in [u] (through d and g),
    /// λ and Λ reproduce every block of the tangent, in stick and in slip
    /// (slip directions oblique to both tangents), frictionless too; and
    /// so with one tangent locked (a symmetry plane, probe s8g D4).
    #[test]
    fn tangent_is_the_derivative_of_the_residual() {
        let cases: [(Option<f64>, [f64; 2], [f64; 2]); 4] = [
            (Some(0.3), [0.2, -0.3], [1e-3, 2e-3]),
            (Some(0.3), [0.7, 0.6], [4e-3, -3e-3]),
            (Some(0.3), [-0.9, 0.5], [-5e-3, 1e-3]),
            (None, [0.0, 0.0], [1e-3, 2e-3]),
        ];
        let mut phases = Vec::new();
        for lock in [[false, false], [true, false], [false, true]] {
            for (mu, lt, gt) in cases {
                let mut p0 = base();
                p0.slip_locked = lock;
                p0.mu = mu;
                p0.lambda_t = lt;
                p0.g_t = gt;
                let (ph, o) = evaluate_point3(&p0);
                if lock == [false, false] {
                    phases.push(ph);
                } else if let Some(k) = (0..2).find(|&k| lock[k]).filter(|_| mu.is_some()) {
                    // A locked Λ_k: driven to 0 by ω Λ_k, pushes on nothing.
                    assert_eq!(o.r_f[k], p0.omega * lt[k]);
                    assert_eq!(o.f_t[k], 0.0);
                    for i in 0..3 {
                        assert_eq!(o.df_df[i][k], 0.0);
                    }
                }
                let h = 1e-7;
                let tol = 1e-6;
                for j in 0..3 {
                    let mut pp = p0;
                    let mut pm = p0;
                    pp.d += p0.normal[j] * h;
                    pm.d -= p0.normal[j] * h;
                    for k in 0..2 {
                        pp.g_t[k] += p0.tangents[k][j] * h;
                        pm.g_t[k] -= p0.tangents[k][j] * h;
                    }
                    let (a, op) = evaluate_point3(&pp);
                    let (b, om) = evaluate_point3(&pm);
                    assert_eq!((a, b), (ph, ph));
                    for i in 0..3 {
                        let fd = (op.f[i] - om.f[i]) / (2.0 * h);
                        assert!(
                            (fd - o.df_du[i][j]).abs() < tol,
                            "{ph:?} df_du {i}{j}: {fd} vs {}",
                            o.df_du[i][j]
                        );
                    }
                    let fd = (op.r_c - om.r_c) / (2.0 * h);
                    assert!((fd - o.dc_du[j]).abs() < tol);
                    for k in 0..2 {
                        let fd = (op.r_f[k] - om.r_f[k]) / (2.0 * h);
                        assert!(
                            (fd - o.dfr_du[k][j]).abs() < tol,
                            "{ph:?} dfr_du {k}{j}: {fd} vs {}",
                            o.dfr_du[k][j]
                        );
                    }
                }
                let mut pp = p0;
                let mut pm = p0;
                pp.lambda += h;
                pm.lambda -= h;
                pp.lambda_s += h;
                pm.lambda_s -= h;
                let (_, op) = evaluate_point3(&pp);
                let (_, om) = evaluate_point3(&pm);
                for i in 0..3 {
                    let fd = (op.f[i] - om.f[i]) / (2.0 * h);
                    assert!(
                        (fd - o.df_dc[i]).abs() < tol,
                        "{ph:?} df_dc {i}: {fd} vs {}",
                        o.df_dc[i]
                    );
                }
                assert!(((op.r_c - om.r_c) / (2.0 * h) - o.dc_dc).abs() < tol);
                for l in 0..2 {
                    let mut pp = p0;
                    let mut pm = p0;
                    pp.lambda_t[l] += h;
                    pm.lambda_t[l] -= h;
                    let (_, op) = evaluate_point3(&pp);
                    let (_, om) = evaluate_point3(&pm);
                    for i in 0..3 {
                        let fd = (op.f[i] - om.f[i]) / (2.0 * h);
                        assert!(
                            (fd - o.df_df[i][l]).abs() < tol,
                            "{ph:?} df_df {i}{l}: {fd} vs {}",
                            o.df_df[i][l]
                        );
                    }
                    for k in 0..2 {
                        let fd = (op.r_f[k] - om.r_f[k]) / (2.0 * h);
                        assert!(
                            (fd - o.dfr_df[k][l]).abs() < tol,
                            "{ph:?} dfr_df {k}{l}: {fd} vs {}",
                            o.dfr_df[k][l]
                        );
                    }
                }
            }
        }
        assert_eq!(
            phases,
            vec![Phase::Adhe, Phase::Glis, Phase::Glis, Phase::Cont]
        );
    }

    /// Slip: the tangential force on the slave has the Coulomb magnitude
    /// μ|λ|ω, along −s, and Λ = s zeroes the friction residual.
    #[test]
    fn slip_force_is_the_coulomb_bound_along_the_slip() {
        let mut p = base();
        p.g_t = [3e-3, 4e-3];
        p.lambda_t = [0.6, 0.8];
        let (ph, o) = evaluate_point3(&p);
        assert_eq!(ph, Phase::Glis);
        let ft = (o.f_t[0] * o.f_t[0] + o.f_t[1] * o.f_t[1]).sqrt();
        assert!((ft - 0.3 * 2.0 * 1.7).abs() < 1e-12);
        // Force on the slave −f_t is against the slip (g along +(3, 4)).
        assert!(-o.f_t[0] * 3.0 - o.f_t[1] * 4.0 < 0.0);
        assert!((-o.f_t[0] * 4.0 + o.f_t[1] * 3.0).abs() < 1e-12);
        assert!(o.r_f[0].abs() < 1e-15 && o.r_f[1].abs() < 1e-15);
    }

    /// With the slip along τ1 only, the 3D point is the 2D point: same
    /// force, same residuals, same blocks along τ1.
    #[test]
    fn reduces_to_the_2d_point_along_one_tangent() {
        for (lt, gt) in [(0.3, 2e-3), (0.9, 5e-3), (-0.95, -4e-3)] {
            let mut p = base();
            p.lambda_t = [lt, 0.0];
            p.g_t = [gt, 0.0];
            let (ph, o) = evaluate_point3(&p);
            let q = PointInput {
                omega: p.omega,
                rho_n: p.rho_n,
                rho_t: p.rho_t,
                mu: p.mu,
                status: p.status,
                lambda: p.lambda,
                lambda_s: p.lambda_s,
                lambda_t: lt,
                d: p.d,
                g_t: gt,
                normal: p.normal,
                tangent: p.tangents[0],
                slip_locked: false,
                threshold_frozen: false,
            };
            let (qh, oq) = evaluate_point(&q);
            assert_eq!(ph, qh);
            for i in 0..3 {
                assert!((o.f[i] - oq.f[i]).abs() < 1e-14);
                assert!((o.df_dc[i] - oq.df_dc[i]).abs() < 1e-14);
                assert!((o.df_df[i][0] - oq.df_df[i]).abs() < 1e-14);
            }
            assert!((o.r_f[0] - oq.r_f).abs() < 1e-14);
            assert!((o.r_c - oq.r_c).abs() < 1e-14);
            assert!((o.f_t[0] - oq.f_t).abs() < 1e-14);
        }
    }

    /// code_aster's rule: the Taylor bar's foundation (n = −e_z) gives
    /// τ1 = e_y, τ2 = −e_x (note §2.3); a tilted normal an orthonormal
    /// basis with τ2 = τ1 × n.
    #[test]
    fn tangents_follow_code_aster_rule() {
        let t = tangents_from_normal([0.0, 0.0, -1.0]);
        assert_eq!(t, [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]]);
        for n in [[0.6, 0.0, -0.8], [0.0, 0.6, 0.8], [0.48, 0.6, -0.64]] {
            let t = tangents_from_normal(n);
            let d = crate::mesh::vec3::dot;
            for k in 0..2 {
                assert!((d(t[k], t[k]) - 1.0).abs() < 1e-15);
                assert!(d(t[k], n).abs() < 1e-15);
            }
            assert!(d(t[0], t[1]).abs() < 1e-15);
            let c = crate::mesh::vec3::cross(t[0], n);
            for i in 0..3 {
                assert!((c[i] - t[1][i]).abs() < 1e-15);
            }
        }
    }

    /// The 3D nodal rule: A/4 per vertex on a QUAD4 parallelogram (here
    /// tilted out of every coordinate plane), A/3 on a TRIA3.
    #[test]
    fn linear_face_weights_are_the_consistent_load() {
        use crate::contact::continuous::nodal_weights;
        use crate::mesh::{Cell, CellType, Mesh};
        let mesh = Mesh {
            dim: 3,
            coords: vec![
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [3.0, 1.0, 1.0],
                [1.0, 1.0, 1.0],
                [0.0, 3.0, 0.0],
            ],
            cells: vec![
                Cell {
                    kind: CellType::Quad4,
                    nodes: vec![0, 1, 2, 3],
                },
                Cell {
                    kind: CellType::Tria3,
                    nodes: vec![0, 1, 4],
                },
                Cell {
                    kind: CellType::Quad8,
                    nodes: vec![0, 1, 2, 3, 4, 4, 4, 4],
                },
            ],
            ..Mesh::default()
        };
        let w = nodal_weights(&mesh, &[0], false).unwrap();
        let a = 2.0 * 2.0f64.sqrt();
        for (_, v) in &w {
            assert!((v - a / 4.0).abs() < 1e-14, "{w:?}");
        }
        let w = nodal_weights(&mesh, &[1], false).unwrap();
        assert_eq!(w.len(), 3);
        for (_, v) in &w {
            assert!((v - 1.0).abs() < 1e-14, "{w:?}");
        }
        let e = nodal_weights(&mesh, &[2], false).unwrap_err();
        assert!(
            e.starts_with("not implemented yet") && e.contains("QUAD8"),
            "{e}"
        );
    }
}
