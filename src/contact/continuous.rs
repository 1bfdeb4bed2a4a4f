//! Continuous contact (`FORMULATION='CONTINUE'`, `ALGO_CONT='STANDARD'`):
//! the augmented-Lagrangian contact and Coulomb friction of code_aster's
//! continuous method at one contact point, as pure functions
//! (docs/contact.md §9, shared/docs/notes/contact-continue.md §4-§6).
//!
//! The unknowns of a point are the displacements of its slave node and
//! of the master nodes of its projection, the contact pressure λ
//! (`LAGS_C`, ≤ 0 in compression, a nominal pressure) and in 2D the
//! friction semi-multiplier Λ (`LAGS_F1`, |Λ| < 1 stick, = 1 slip). With
//! `INTEGRATION='AUTO'` on SEG2/SEG3 (TRIA3/QUAD4 in 3D) slave cells the points are the slave
//! nodes, so a point couples only its own node's multipliers; the points
//! of one node in two cells see the same λ, d and slip and are merged
//! here into one point whose weight is the sum of theirs.
//!
//! Everything is expressed on the jump [u] = u_slave − Σ_j M_j u_j: the
//! residual of a slave dof is the point's force vector `f`, the one of
//! master node j is −M_j f, and the derivatives scale the same way.

use crate::mesh::vec3::{dot, sub};
use crate::mesh::{CellType, Mesh};

/// `ALGO_RESO_CONT` / `ALGO_RESO_FROT` / `ALGO_RESO_GEOM`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Resolution {
    /// Inside the Newton iterations (generalised Newton).
    Newton,
    /// Fixed-point loops around Newton.
    PointFixe,
}

/// `CONTACT_INIT`: the contact status of the points at the first step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactInit {
    /// In contact when the gap is closed up to 1e-6 of the smallest edge.
    Interpenetre,
    Oui,
    Non,
}

/// The continuous parameters of one `ZONE`.
#[derive(Debug, Clone, PartialEq)]
pub struct ContinuousZone {
    /// Slave cells (SEG2/SEG3 in 2D, TRIA3/QUAD4 in 3D): their nodes are the contact points.
    pub slave_cells: Vec<usize>,
    /// `COEF_CONT` ρ_n (N/mm³).
    pub coef_cont: f64,
    /// `COEF_FROT` ρ_t (1/mm).
    pub coef_frot: f64,
    /// `COULOMB` μ when the definition has `FROTTEMENT='COULOMB'`.
    pub mu: Option<f64>,
    /// `SEUIL_INIT`: the friction threshold pressure of the first step
    /// (None: the initial `LAGS_C`).
    pub seuil_init: Option<f64>,
    pub contact_init: ContactInit,
    /// `ADAPTATION='CYCLAGE'` (the default): cycling detection and
    /// treatment (nonlinear::cycling); 'NON': none.
    pub cyclage: bool,
}

/// The top-level continuous keywords.
#[derive(Debug, Clone, PartialEq)]
pub struct ContinuousDef {
    pub algo_reso_cont: Resolution,
    pub algo_reso_frot: Resolution,
    pub algo_reso_geom: Resolution,
    /// `RESI_GEOM` (largest move of a point between two pairings over the
    /// largest master edge) for the geometric fixed point.
    pub resi_geom: f64,
    /// `RESI_FROT`: largest change of `LAGS_C` in an iteration over the
    /// largest `LAGS_C` (the last iterations must also satisfy it).
    pub resi_frot: f64,
    /// `ITER_CONT_MAXI`: status evaluations of the contact fixed point
    /// (`ALGO_RESO_CONT='POINT_FIXE'`) allowed in a step.
    pub iter_cont_maxi: usize,
    /// `ITER_FROT_MAXI`: threshold updates of the friction fixed point
    /// (`ALGO_RESO_FROT='POINT_FIXE'`) allowed in a step.
    pub iter_frot_maxi: usize,
    /// One per zone of the definition, same order.
    pub zones: Vec<ContinuousZone>,
}

/// The weight ω of every contact point (slave node) of `cells`, ascending
/// node order: Σ over the cells of the node of w_p J_p (times r_p in
/// AXIS), with the nodal rules of `INTEGRATION='AUTO'` (SEG2: 1, 1; SEG3:
/// 1/3, 1/3, 4/3) on the **initial** geometry (`mmmjac`). A point on the
/// axis (r = 0) gets r = 1e-7 as in code_aster (alarm `CONTACT2_14`).
pub fn nodal_weights(
    mesh: &Mesh,
    cells: &[usize],
    axis: bool,
) -> Result<Vec<(usize, f64)>, String> {
    let mut w: std::collections::BTreeMap<usize, f64> = Default::default();
    for &c in cells {
        let cell = &mesh.cells[c];
        let x: Vec<[f64; 3]> = cell.nodes.iter().map(|&n| mesh.coords[n]).collect();
        if matches!(cell.kind, CellType::Tria3 | CellType::Quad4) {
            face_nodal_weights(cell.kind, &cell.nodes, &x, &mut w);
            continue;
        }
        // (parametric coordinate, weight) of each node, MED order.
        let rule: &[(f64, f64)] = match cell.kind {
            CellType::Seg2 => &[(-1.0, 1.0), (1.0, 1.0)],
            CellType::Seg3 => &[(-1.0, 1.0 / 3.0), (1.0, 1.0 / 3.0), (0.0, 4.0 / 3.0)],
            CellType::Tria6 | CellType::Quad8 => {
                return Err(format!(
                    "not implemented yet: continuous contact on {} slave cells (INTEGRATION='AUTO' puts the contact points of a quadratic face at Gauss or Simpson points, not at its nodes; only TRIA3/QUAD4 slave faces in 3D)",
                    cell.kind.aster_name()
                ))
            }
            other => {
                return Err(format!(
                "not implemented yet: continuous contact on {} slave cells (only SEG2/SEG3 in 2D, TRIA3/QUAD4 in 3D)",
                other.aster_name()
            ))
            }
        };
        for (k, &(xi, wk)) in rule.iter().enumerate() {
            let dn: Vec<f64> = match cell.kind {
                CellType::Seg2 => vec![-0.5, 0.5],
                _ => vec![xi - 0.5, xi + 0.5, -2.0 * xi],
            };
            let mut t = [0.0; 3];
            for (d, p) in dn.iter().zip(&x) {
                for i in 0..3 {
                    t[i] += d * p[i];
                }
            }
            let mut j = dot(t, t).sqrt();
            if axis {
                let r = x[k][0].abs();
                j *= if r == 0.0 { 1e-7 } else { r };
            }
            *w.entry(cell.nodes[k]).or_insert(0.0) += wk * j;
        }
    }
    Ok(w.into_iter().collect())
}

/// The nodal rule of a linear face in 3D (`INTEGRATION='AUTO'`): TRIA3
/// 1/6 and QUAD4 1 at each vertex, times the area element |a1 × a2| of
/// the initial geometry at the vertex, so a flat face's weights are A/3
/// (TRIA3) and, on a parallelogram, A/4 (QUAD4): the consistent load of a
/// uniform pressure.
fn face_nodal_weights(
    kind: CellType,
    nodes: &[usize],
    x: &[[f64; 3]],
    w: &mut std::collections::BTreeMap<usize, f64>,
) {
    let wk = crate::mesh::shape::reference_measure(kind) / nodes.len() as f64;
    for (k, xi) in crate::mesh::shape::reference_nodes(kind).iter().enumerate() {
        let ev = crate::mesh::shape::eval(kind, *xi);
        let (mut a1, mut a2) = ([0.0; 3], [0.0; 3]);
        for (d, p) in ev.dn().iter().zip(x) {
            for i in 0..3 {
                a1[i] += d[0] * p[i];
                a2[i] += d[1] * p[i];
            }
        }
        let j = crate::mesh::vec3::norm(crate::mesh::vec3::cross(a1, a2));
        *w.entry(nodes[k]).or_insert(0.0) += wk * j;
    }
}

/// `mmstac`: a point is in contact iff the augmented multiplier
/// λ − ρ_n d is negative (strictly); d > 0 is a penetration.
pub fn contact_status(lambda: f64, d: f64, rho_n: f64) -> bool {
    lambda - rho_n * d < 0.0
}

/// The phase of a point (`mmmpha`), for CONT_NOEU and the tests.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Not in contact: λ and Λ are driven to 0.
    Sans,
    /// In contact, frictionless zone.
    Cont,
    /// In contact, friction zone, threshold λ̂ exactly 0: no friction.
    Ncon,
    /// Stick: |Λ + ρ_t g_t| ≤ 1.
    Adhe,
    /// Slip.
    Glis,
}

/// What a point needs at one evaluation (2D: one tangent).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointInput {
    pub omega: f64,
    pub rho_n: f64,
    pub rho_t: f64,
    /// μ, None for a frictionless zone.
    pub mu: Option<f64>,
    /// The contact status s_p in force for this evaluation.
    pub status: bool,
    /// λ (`LAGS_C`).
    pub lambda: f64,
    /// λ_s, the threshold used when λ is exactly 0 (`mmlagc`).
    pub lambda_s: f64,
    /// Λ (`LAGS_F1`).
    pub lambda_t: f64,
    /// Penetration d = (x_s − x_m)·n (> 0 penetrating).
    pub d: f64,
    /// Tangential slip since the start of the step, along τ.
    pub g_t: f64,
    /// Unit inward master normal n.
    pub normal: [f64; 3],
    /// Unit tangent τ.
    pub tangent: [f64; 3],
    /// Every displacement the slip g_t depends on is imposed (a slave
    /// node on the symmetry axis of an AXIS model against a fixed
    /// master): the friction force would be undetermined (it goes into
    /// the support reaction), so Λ is driven to 0 as without contact.
    pub slip_locked: bool,
    /// `ALGO_RESO_FROT='POINT_FIXE'`: the friction threshold is λ_s,
    /// frozen during the Newton iterations, even when λ ≠ 0 (`mmlagc`).
    pub threshold_frozen: bool,
}

/// The friction threshold pressure λ̂ of a point and ∂λ̂/∂λ (`mmlagc`):
/// with Newton friction the current λ (λ_s while λ is exactly 0), with
/// the friction fixed point the frozen λ_s.
fn threshold(p: &PointInput) -> (f64, f64) {
    if p.lambda != 0.0 && !p.threshold_frozen {
        (p.lambda, 1.0)
    } else {
        (p.lambda_s, 0.0)
    }
}

/// The residual of a point and its exact derivatives at frozen pairing.
/// `f` is the residual of the slave displacement (on the F_int side of
/// R = F_int − F_ext + ...), so the force the contact exerts on the slave
/// node is −f. `df_du[i][j]` = ∂f_i/∂[u]_j.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PointOutput {
    pub f: [f64; 3],
    pub r_c: f64,
    pub r_f: f64,
    pub df_du: [[f64; 3]; 3],
    pub df_dc: [f64; 3],
    pub df_df: [f64; 3],
    pub dc_du: [f64; 3],
    pub dc_dc: f64,
    pub dc_df: f64,
    pub df_du_f: [f64; 3],
    pub dfr_dc: f64,
    pub dfr_df: f64,
    /// Force on the slave split: normal part (force on slave = −f_n) and
    /// tangential component along τ (force on slave = −f_t τ).
    pub f_n: [f64; 3],
    pub f_t: f64,
}

/// The phase of a point from its input.
pub fn phase(p: &PointInput) -> Phase {
    if !p.status {
        return Phase::Sans;
    }
    let Some(_) = p.mu else {
        return Phase::Cont;
    };
    let (lh, _) = threshold(p);
    if lh == 0.0 {
        return Phase::Ncon;
    }
    if (p.lambda_t + p.rho_t * p.g_t).abs() <= 1.0 {
        Phase::Adhe
    } else {
        Phase::Glis
    }
}

/// The contact (normal) part of a point's residual and tangent, the same
/// whatever the number of friction directions (contact-continue.md §4.2,
/// §5): closed, the augmented pressure λ − ρ_n d acts along n; open, the
/// row only drives λ to 0.
pub(crate) struct NormalTerms {
    pub f: [f64; 3],
    pub df_dc: [f64; 3],
    pub dc_du: [f64; 3],
    pub df_du: [[f64; 3]; 3],
    pub r_c: f64,
    pub dc_dc: f64,
}

pub(crate) fn normal_terms(
    status: bool,
    lambda: f64,
    rho_n: f64,
    d: f64,
    w: f64,
    n: [f64; 3],
) -> NormalTerms {
    let mut c = NormalTerms {
        f: [0.0; 3],
        df_dc: [0.0; 3],
        dc_du: [0.0; 3],
        df_du: [[0.0; 3]; 3],
        r_c: 0.0,
        dc_dc: 0.0,
    };
    if status {
        let fn_ = lambda - rho_n * d;
        for i in 0..3 {
            c.f[i] = -w * fn_ * n[i];
            c.df_dc[i] = -w * n[i];
            c.dc_du[i] = -w * n[i];
            for j in 0..3 {
                c.df_du[i][j] = rho_n * w * n[i] * n[j];
            }
        }
        c.r_c = -w * d;
    } else {
        c.r_c = -w / rho_n * lambda;
        c.dc_dc = -w / rho_n;
    }
    c
}

/// Residual and tangent of one point (contact-continue.md §4.2, §5).
///
/// The tangent is the exact derivative at frozen pairing except, as in
/// code_aster (§5 "missing", §13 V7), the derivative of the friction rows
/// with respect to λ (`dfr_dc` stays 0). That block matters: with it, a
/// slip iteration entered from a stick iterate far outside the cone
/// (|Λ| ≫ 1) moves Λ to s − (Λ − s) δλ/λ instead of exactly s, which
/// on SDNV103 F put r back inside the cone and made Newton cycle between
/// stick and slip; without it a slip iteration gives Λ = s exactly.
pub fn evaluate_point(p: &PointInput) -> (Phase, PointOutput) {
    let ph = phase(p);
    let mut o = PointOutput::default();
    let (w, n, t) = (p.omega, p.normal, p.tangent);
    let c = normal_terms(p.status, p.lambda, p.rho_n, p.d, w, n);
    (o.f, o.f_n, o.df_dc, o.dc_du, o.df_du) = (c.f, c.f, c.df_dc, c.dc_du, c.df_du);
    (o.r_c, o.dc_dc) = (c.r_c, c.dc_dc);
    if let Some(mu) = p.mu {
        // ∂λ̂/∂λ: 1 unless λ̂ is λ_s (then no K_uλ friction block, and
        // the fixed point's tangent is symmetric as code_aster's).
        let (lh, dl) = threshold(p);
        match ph {
            _ if p.slip_locked => {
                o.r_f = w * p.lambda_t;
                o.dfr_df = w;
            }
            Phase::Sans | Phase::Ncon | Phase::Cont => {
                o.r_f = w * p.lambda_t;
                o.dfr_df = w;
            }
            Phase::Adhe => {
                let r = p.lambda_t + p.rho_t * p.g_t;
                let c = -w * mu * lh;
                o.f_t = c * r;
                for i in 0..3 {
                    o.f[i] += c * r * t[i];
                    o.df_df[i] = c * t[i];
                    o.df_dc[i] += -w * mu * dl * r * t[i];
                    o.df_du_f[i] = c * t[i];
                    for j in 0..3 {
                        o.df_du[i][j] += c * p.rho_t * t[i] * t[j];
                    }
                }
                o.r_f = c * p.g_t;
            }
            Phase::Glis => {
                let r = p.lambda_t + p.rho_t * p.g_t;
                let s = r.signum();
                let c = -w * mu * lh;
                o.f_t = c * s;
                for i in 0..3 {
                    o.f[i] += c * s * t[i];
                    o.df_dc[i] += -w * mu * dl * s * t[i];
                }
                o.r_f = w * mu * lh / p.rho_t * (p.lambda_t - s);
                o.dfr_df = w * mu * lh / p.rho_t;
            }
        }
    }
    (ph, o)
}

/// Penetration of a slave point given the frozen link quantities: the
/// pairing's gap g (> 0 open) is −d.
pub fn penetration(gap: f64) -> f64 {
    -gap
}

/// Tangential slip since the start of the step along τ: τ·(Δu_s − Σ M_j Δu_j).
pub fn slip(tangent: [f64; 3], du_slave: [f64; 3], du_master: &[[f64; 3]], shape: &[f64]) -> f64 {
    let mut jump = du_slave;
    for (m, du) in shape.iter().zip(du_master) {
        jump = sub(jump, [m * du[0], m * du[1], m * du[2]]);
    }
    dot(tangent, jump)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn base() -> PointInput {
        PointInput {
            omega: 2.5,
            rho_n: 100.0,
            rho_t: 100.0,
            mu: Some(0.25),
            status: true,
            lambda: -3.0,
            lambda_s: -3.0,
            lambda_t: 0.3,
            d: 1e-3,
            g_t: 2e-3,
            normal: [0.0, -1.0, 0.0],
            tangent: [-1.0, 0.0, 0.0],
            slip_locked: false,
            threshold_frozen: false,
        }
    }

    /// AXIS SEG3 weights times a uniform pressure are the consistent
    /// load: L a/6, L b/6 and 2 L r_mid/3 for a straight edge from r = a to
    /// r = b (note §12.2), summing to ∫ r ds; a node shared by two cells
    /// gets both shares; a node on the axis gets 1e-7 instead of r = 0.
    #[test]
    fn axis_seg3_weights_are_the_consistent_load() {
        use crate::mesh::{Cell, Mesh};
        let mesh = Mesh {
            dim: 2,
            coords: vec![
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [5.0, 0.0, 0.0],
                [3.5, 0.0, 0.0],
            ],
            cells: vec![
                Cell {
                    kind: CellType::Seg3,
                    nodes: vec![0, 1, 2],
                },
                Cell {
                    kind: CellType::Seg3,
                    nodes: vec![1, 3, 4],
                },
            ],
            ..Mesh::default()
        };
        let w = nodal_weights(&mesh, &[0, 1], true).unwrap();
        let (l1, l2) = (2.0, 3.0);
        let expect = [
            (0, l1 / 6.0 * 1e-7),
            (1, l1 * 2.0 / 6.0 + l2 * 2.0 / 6.0),
            (2, 2.0 * l1 * 1.0 / 3.0),
            (3, l2 * 5.0 / 6.0),
            (4, 2.0 * l2 * 3.5 / 3.0),
        ];
        for ((n, v), (m, e)) in w.iter().zip(expect) {
            assert_eq!(*n, m);
            assert!((v - e).abs() < 1e-14 * e.max(1.0), "node {n}: {v} vs {e}");
        }
        // ∫ r ds over [0, 5] = 12.5 (the axis node's 1e-7 share aside).
        let total: f64 = w.iter().map(|(_, v)| v).sum();
        assert!((total - 12.5).abs() < 1e-6);
        // Plane weights: L/6, L/6, 2L/3 per cell.
        let w = nodal_weights(&mesh, &[0], false).unwrap();
        assert_eq!(w, vec![(0, 1.0 / 3.0), (1, 1.0 / 3.0), (2, 4.0 / 3.0)]);
    }

    #[test]
    fn status_examples_of_the_note() {
        assert!(contact_status(0.0, 1e-9, 100.0));
        assert!(!contact_status(0.0, 0.0, 100.0));
        assert!(contact_status(-1.0, -0.005, 100.0));
        assert!(!contact_status(-1.0, -0.02, 100.0));
    }

    /// Central differences of the residual in [u] (through d and g_t), λ
    /// and Λ reproduce every block of the tangent, in stick and in slip.
    #[test]
    fn tangent_is_the_derivative_of_the_residual() {
        for (lt, gt) in [(0.3, 2e-3), (0.9, 5e-3), (-0.95, -4e-3)] {
            let mut p0 = base();
            p0.lambda_t = lt;
            p0.g_t = gt;
            let (ph, o) = evaluate_point(&p0);
            let h = 1e-7;
            // [u] along each axis changes d by n_j h and g_t by τ_j h.
            for j in 0..2 {
                let mut pp = p0;
                let mut pm = p0;
                pp.d += p0.normal[j] * h;
                pm.d -= p0.normal[j] * h;
                pp.g_t += p0.tangent[j] * h;
                pm.g_t -= p0.tangent[j] * h;
                let (a, op) = evaluate_point(&pp);
                let (b, om) = evaluate_point(&pm);
                assert_eq!((a, b), (ph, ph));
                for i in 0..2 {
                    let fd = (op.f[i] - om.f[i]) / (2.0 * h);
                    assert!(
                        (fd - o.df_du[i][j]).abs() < 1e-6,
                        "{ph:?} df_du {i}{j}: {fd} vs {}",
                        o.df_du[i][j]
                    );
                }
                let fd = (op.r_c - om.r_c) / (2.0 * h);
                assert!((fd - o.dc_du[j]).abs() < 1e-6);
                let fd = (op.r_f - om.r_f) / (2.0 * h);
                assert!(
                    (fd - o.df_du_f[j]).abs() < 1e-6,
                    "{ph:?} dfr_du {j}: {fd} vs {}",
                    o.df_du_f[j]
                );
            }
            let mut pp = p0;
            let mut pm = p0;
            pp.lambda += h;
            pm.lambda -= h;
            let (_, op) = evaluate_point(&pp);
            let (_, om) = evaluate_point(&pm);
            for i in 0..2 {
                assert!(((op.f[i] - om.f[i]) / (2.0 * h) - o.df_dc[i]).abs() < 1e-6);
            }
            assert!(((op.r_c - om.r_c) / (2.0 * h) - o.dc_dc).abs() < 1e-6);
            // code_aster's missing block: left out on purpose.
            assert_eq!(o.dfr_dc, 0.0);
            let mut pp = p0;
            let mut pm = p0;
            pp.lambda_t += h;
            pm.lambda_t -= h;
            let (_, op) = evaluate_point(&pp);
            let (_, om) = evaluate_point(&pm);
            for i in 0..2 {
                assert!(((op.f[i] - om.f[i]) / (2.0 * h) - o.df_df[i]).abs() < 1e-6);
            }
            assert!(((op.r_c - om.r_c) / (2.0 * h) - o.dc_df).abs() < 1e-6);
            assert!(((op.r_f - om.r_f) / (2.0 * h) - o.dfr_df).abs() < 1e-6);
        }
    }

    #[test]
    fn phases() {
        let mut p = base();
        assert_eq!(phase(&p), Phase::Adhe);
        p.lambda_t = 0.9;
        p.g_t = 5e-3;
        assert_eq!(phase(&p), Phase::Glis);
        p.lambda = 0.0;
        p.lambda_s = 0.0;
        assert_eq!(phase(&p), Phase::Ncon);
        p.status = false;
        assert_eq!(phase(&p), Phase::Sans);
        p.status = true;
        p.mu = None;
        assert_eq!(phase(&p), Phase::Cont);
    }

    /// The friction fixed point (`ALGO_RESO_FROT='POINT_FIXE'`): the
    /// threshold is the frozen λ_s whatever λ, so the friction force does
    /// not depend on λ (no K_uλ friction block) and the tangent is still
    /// the derivative of the residual.
    #[test]
    fn frozen_threshold_is_lambda_s() {
        for (lt, gt) in [(0.3, 2e-3), (0.9, 5e-3)] {
            let mut p = base();
            p.threshold_frozen = true;
            p.lambda_s = -2.0;
            p.lambda_t = lt;
            p.g_t = gt;
            let (ph, o) = evaluate_point(&p);
            let mut q = p;
            q.lambda = p.lambda_s;
            q.threshold_frozen = false;
            let (qh, oq) = evaluate_point(&q);
            assert_eq!(ph, qh);
            // Same friction force as Newton friction at λ = λ_s.
            assert!((o.f_t - oq.f_t).abs() < 1e-14, "{ph:?}");
            let h = 1e-7;
            let mut pp = p;
            let mut pm = p;
            pp.lambda += h;
            pm.lambda -= h;
            let (_, op) = evaluate_point(&pp);
            let (_, om) = evaluate_point(&pm);
            for i in 0..2 {
                let fd = (op.f[i] - om.f[i]) / (2.0 * h);
                assert!((fd - o.df_dc[i]).abs() < 1e-6, "{ph:?} {fd} {}", o.df_dc[i]);
                // Only the contact part: −ω n.
                assert!((o.df_dc[i] + p.omega * p.normal[i]).abs() < 1e-14);
            }
            assert_eq!((op.r_f - om.r_f) / (2.0 * h), 0.0);
        }
        // λ_s = 0: no friction (NCON) even though λ ≠ 0.
        let mut p = base();
        p.threshold_frozen = true;
        p.lambda_s = 0.0;
        assert_eq!(phase(&p), Phase::Ncon);
    }

    /// Slip: the tangential force on the slave is μ|λ|ω against the slip,
    /// and the friction equation makes Λ = sign(r).
    #[test]
    fn slip_force_is_the_coulomb_bound() {
        let mut p = base();
        p.lambda_t = 1.0;
        p.g_t = 5e-3;
        p.d = 0.0;
        let (ph, o) = evaluate_point(&p);
        assert_eq!(ph, Phase::Glis);
        // force on the slave = −f_t τ, τ = −e_x, slip along τ > 0: the
        // force must point along −τ = +e_x with magnitude μ|λ|ω.
        let fx = -o.f_t * p.tangent[0];
        assert!((fx - 0.25 * 3.0 * 2.5).abs() < 1e-12);
        assert!(o.r_f.abs() < 1e-15);
    }
}
