//! Penalised contact and penalised Coulomb friction of the discrete method
//! (semantics.md §6.3), at fixed pairing.
//!
//! For a link with inward normal n, tangents τ_k and master weights N_j,
//! the gap and the slip are linear in the nodal displacements:
//!
//! - g(u) = g_ref + n·(Σ_j N_j u_j − u_s)            (B_n = ∂g/∂u)
//! - g_t,k(u) = τ_k·(Δu_s − Σ_j N_j Δu_j), Δu = u − u_start of the step
//!   (B_t,k = ∂g_t,k/∂u), i.e. slave minus master.
//!
//! Active if g < 0; λ_n = E_N·(−g) ≥ 0. Friction threshold λ_f = μ·λ_n:
//! stick if |g_t| ≤ λ_f/E_T with F_t = E_T·g_t, slip otherwise with
//! F_t = λ_f·g_t/|g_t|.
//!
//! **Sign convention of the output.** The vector returned is what is
//! *added to F_int* in R = F_int − F_ext + r_c: r_c = −λ_n·B_n + Σ_k F_t,k·B_t,k,
//! the gradient of the penalty energy. On the slave node that is
//! r_s = λ_n·n_in + F_t,k·τ_k: the force the contact exerts *on* the slave
//! node is −r_s (pushed out of the master, against the slip); the master
//! nodes receive the opposite, weighted by N_j. The tangent is ∂r_c/∂u.

use super::cont_noeu::{ContactState, LinkState, LinkStatus};
use super::pairing::{Link, Pairing};
use super::ContactDef;
use crate::mesh::vec3::dot;

/// RESI_GLOB_RELA above which the slip part of the friction tangent is
/// weighted by COEF_MATR_FROT (code_aster's `cffpm2`).
pub const RESI_COEF_MATR_FROT: f64 = 1e-3;

/// What one Newton iteration gives the contact library.
#[derive(Debug, Clone, Copy)]
pub struct IterationInput<'a> {
    /// Current displacements, one per mesh node (3 components, z = 0 in 2D).
    pub u: &'a [[f64; 3]],
    /// Displacements at the start of the time step (the origin of the slip).
    pub u_start: &'a [[f64; 3]],
    /// The current RESI_GLOB_RELA of the Newton loop: while ≥ 1e-3 the
    /// slip tangent is multiplied by COEF_MATR_FROT.
    pub resi_glob_rela: f64,
    /// Return ½(K + Kᵀ) instead of K: discrete contact makes code_aster
    /// symmetrise the whole stiffness (MATR_RIGI_SYME implied, semantics.md
    /// §13 item 18), and symmetrising the sum equals summing the
    /// symmetrised parts.
    pub symmetrise: bool,
}

/// The contact contribution of one iteration.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Contribution {
    /// (dof, value) added to F_int in the residual, free dofs only;
    /// a dof may appear several times (sum them).
    pub residual: Vec<(usize, f64)>,
    /// (row dof, column dof, value) of ∂r_c/∂u, free dofs only, repeated
    /// entries to be summed.
    pub tangent: Vec<(usize, usize, f64)>,
    /// The same vector r_c per node (all components, whether the dofs are
    /// free or imposed), repeated nodes to be summed: with the opposite
    /// sign it is the contact force on each node, which enters the
    /// reactions and the RESI_GLOB_RELA denominator.
    pub nodal: Vec<(usize, [f64; 3])>,
}

/// Evaluates every link of `pairing` at the displacements of `input`.
///
/// `dof(node, component)` gives the equation number of a displacement
/// component (0 = DX, 1 = DY, 2 = DZ), or None for a dof that is imposed
/// or eliminated: its rows and columns are dropped from `residual` and
/// `tangent` but still appear in `nodal`.
///
/// The state returned has no percussion yet: see
/// [`ContactState::accumulate_percussion`], called once per converged step.
///
/// # Panics
/// If a displacement slice does not cover the nodes of a link (a caller bug).
pub fn evaluate<F>(
    def: &ContactDef,
    pairing: &Pairing,
    input: &IterationInput,
    dof: F,
) -> (Contribution, ContactState)
where
    F: Fn(usize, usize) -> Option<usize>,
{
    evaluate_armed(def, pairing, input, None, dof)
}

/// [`evaluate`] with code_aster's friction flag: `armed[slave]` false
/// makes an active link frictionless in this evaluation. code_aster's
/// `cffpfo` gives a link its friction coefficient only if the link was in
/// contact at the previous contact call (the flag that `cffpm2` sets for
/// an active link and clears for an open one): a link that closes, or
/// closes again, carries no friction until the next call. Without the
/// flag a closing link sticks at once with E_T times its slip since the
/// start of the step, which includes its motion while it was open: in an
/// iterate that overshoots, a large spurious force (B at 1.55e-5 s: up to
/// 4.2e3 N against 100 to 400 N). Such a link is reported sticking, with
/// no friction force. None: every link armed.
pub fn evaluate_armed<F>(
    def: &ContactDef,
    pairing: &Pairing,
    input: &IterationInput,
    armed: Option<&[bool]>,
    dof: F,
) -> (Contribution, ContactState)
where
    F: Fn(usize, usize) -> Option<usize>,
{
    let dim = def.dim;
    let mut out = Contribution::default();
    let mut state = ContactState {
        dim,
        links: Vec::with_capacity(pairing.links.len()),
        unpaired: pairing.unpaired.clone(),
    };
    for link in &pairing.links {
        let zone = &def.zones[link.zone];
        let local = LinkCalc::new(link, dim, input);
        let armed_link = armed.is_none_or(|a| a.get(link.slave).copied().unwrap_or(false));
        let friction = zone.friction.as_ref().filter(|_| armed_link);
        let (mut ls, r, k) = local.forces(link, zone.e_n, friction, input);
        if zone.friction.is_some() && !armed_link && ls.status != LinkStatus::Open {
            ls.status = LinkStatus::Stick;
            ls.frictional = true;
        }
        let active = ls.status != LinkStatus::Open;
        state.links.push(ls);
        if !active {
            continue;
        }
        // Scatter: local index i = node slot * dim + component.
        let nodes: Vec<usize> = std::iter::once(link.slave)
            .chain(link.master_nodes.iter().copied())
            .collect();
        let dofs: Vec<Option<usize>> = nodes
            .iter()
            .flat_map(|&n| (0..dim).map(move |c| (n, c)))
            .map(|(n, c)| dof(n, c))
            .collect();
        for (slot, &n) in nodes.iter().enumerate() {
            let mut v = [0.0; 3];
            v[..dim].copy_from_slice(&r[slot * dim..(slot + 1) * dim]);
            out.nodal.push((n, v));
        }
        for (i, di) in dofs.iter().enumerate() {
            let Some(di) = *di else { continue };
            out.residual.push((di, r[i]));
            for (j, dj) in dofs.iter().enumerate() {
                let Some(dj) = *dj else { continue };
                let v = if input.symmetrise {
                    0.5 * (k[i][j] + k[j][i])
                } else {
                    k[i][j]
                };
                if v != 0.0 {
                    out.tangent.push((di, dj, v));
                }
            }
        }
    }
    (out, state)
}

/// The linear maps of one link: B_n and B_t,k over the local dofs
/// (slave then master nodes, `dim` components each), with the current gap
/// and slip.
struct LinkCalc {
    bn: Vec<f64>,
    bt: Vec<Vec<f64>>,
    gap: f64,
    slip: [f64; 2],
}

impl LinkCalc {
    fn new(link: &Link, dim: usize, input: &IterationInput) -> LinkCalc {
        let nloc = (1 + link.master_nodes.len()) * dim;
        let mut bn = vec![0.0; nloc];
        let mut bt = vec![vec![0.0; nloc]; link.ntangents];
        for c in 0..dim {
            bn[c] = -link.normal[c];
            for (k, b) in bt.iter_mut().enumerate() {
                b[c] = link.tangents[k][c];
            }
        }
        for (j, &w) in link.shape.iter().enumerate() {
            for c in 0..dim {
                let i = (1 + j) * dim + c;
                bn[i] = w * link.normal[c];
                for (k, b) in bt.iter_mut().enumerate() {
                    b[i] = -w * link.tangents[k][c];
                }
            }
        }
        let mut gap = link.gap_ref;
        let mut slip = [0.0; 2];
        let nodes = std::iter::once(link.slave).chain(link.master_nodes.iter().copied());
        for (slot, n) in nodes.enumerate() {
            for c in 0..dim {
                let i = slot * dim + c;
                gap += bn[i] * input.u[n][c];
                let du = input.u[n][c] - input.u_start[n][c];
                for (k, b) in bt.iter().enumerate() {
                    slip[k] += b[i] * du;
                }
            }
        }
        LinkCalc { bn, bt, gap, slip }
    }

    /// The link's state, local residual r_c and local tangent ∂r_c/∂u.
    fn forces(
        &self,
        link: &Link,
        e_n: f64,
        friction: Option<&super::Coulomb>,
        input: &IterationInput,
    ) -> (LinkState, Vec<f64>, Vec<Vec<f64>>) {
        let nloc = self.bn.len();
        let nt = self.bt.len();
        let mut r = vec![0.0; nloc];
        let mut k = vec![vec![0.0; nloc]; nloc];
        let mut ls = LinkState {
            zone: link.zone,
            slave: link.slave,
            status: LinkStatus::Open,
            gap: self.gap,
            lambda_n: 0.0,
            normal: link.normal,
            tangents: link.tangents,
            ntangents: nt,
            frictional: friction.is_some(),
            slip: self.slip,
            friction: [0.0; 2],
            proj: link.proj,
            percussion: [0.0; 4],
        };
        if self.gap >= 0.0 {
            return (ls, r, k);
        }
        let lambda = -e_n * self.gap;
        ls.lambda_n = lambda;
        for i in 0..nloc {
            r[i] -= lambda * self.bn[i];
            for j in 0..nloc {
                k[i][j] += e_n * self.bn[i] * self.bn[j];
            }
        }
        let Some(fr) = friction else {
            // Contact without friction is reported as sliding (CONT = 2).
            ls.status = LinkStatus::Slip;
            return (ls, r, k);
        };
        let gt = (0..nt)
            .map(|q| self.slip[q] * self.slip[q])
            .sum::<f64>()
            .sqrt();
        let threshold = fr.mu * lambda;
        if gt * fr.e_t <= threshold {
            ls.status = LinkStatus::Stick;
            for q in 0..nt {
                ls.friction[q] = fr.e_t * self.slip[q];
                for i in 0..nloc {
                    r[i] += ls.friction[q] * self.bt[q][i];
                    for j in 0..nloc {
                        k[i][j] += fr.e_t * self.bt[q][i] * self.bt[q][j];
                    }
                }
            }
            return (ls, r, k);
        }
        ls.status = LinkStatus::Slip;
        let e: Vec<f64> = (0..nt).map(|q| self.slip[q] / gt).collect();
        for q in 0..nt {
            ls.friction[q] = threshold * e[q];
            for i in 0..nloc {
                r[i] += ls.friction[q] * self.bt[q][i];
            }
        }
        // The slip tangent as code_aster's frogdp builds it (cffpm1: MAF1
        // with the secant coefficient λ_f/|g_t| on both tangents; cffpm2:
        // MAF2 = β²·F_f F_fᵀ with β² = 1/(λ_f |g_t|) and F_f = λ_f b_e the
        // friction force at the link's dofs):
        //     K_f = (λ_f/|g_t|)·(Σ_k B_t,k B_t,kᵀ − w b_e b_eᵀ),  b_e = Σ_k e_k B_t,k,
        // w = COEF_MATR_FROT while RESI_GLOB_RELA ≥ 1e-3, 1 below. With
        // w = 1 it is the derivative of F_t = λ_f e at fixed λ_n, i.e.
        // (λ_f/|g_t|)(I − e eᵀ) in the tangent plane (0 in 2D, where e = ±1);
        // with w = 0 it is the secant (K_f·Δu = r_f). The normal-tangential
        // coupling −μ E_N b_e B_nᵀ of the full derivative is left out, as
        // code_aster does: it is not symmetric, and with E_N ≫ E_T it made
        // Newton cycle between stick and slip on the Taylor bar
        // (docs/contact.md §3).
        let w = if input.resi_glob_rela >= RESI_COEF_MATR_FROT {
            fr.coef_matr_frot
        } else {
            1.0
        };
        let secant = threshold / gt;
        let be: Vec<f64> = (0..nloc)
            .map(|i| (0..nt).map(|q| e[q] * self.bt[q][i]).sum())
            .collect();
        for i in 0..nloc {
            for j in 0..nloc {
                let mut v = -w * be[i] * be[j];
                for q in 0..nt {
                    v += self.bt[q][i] * self.bt[q][j];
                }
                k[i][j] += secant * v;
            }
        }
        (ls, r, k)
    }
}

/// The slave nodes of `pairing` that penetrate their master at the
/// displacements `u` (of each node): how many, and the deepest
/// penetration (0 when none). The explicit and the implicit runs check
/// their initial state with it, so that both say the same of a body that
/// starts inside another (the implicit run said nothing and stopped on an
/// inverted cell, probe s7b D6). The gap is summed as the explicit loop
/// always did, component by component, so its alarm is unchanged to the
/// bit.
///
/// The rounding allowance counts the coordinates too: `gap_ref` is
/// n·(Σ N_j X_j − X_s), a difference of coordinates, so a slave face
/// that lies on its master carries a gap of the order of ε |X| (the
/// projection point `proj` gives |X| to within the displacements). An
/// allowance from the gap and the displacements alone is 0 at an initial
/// state at rest, and every face not aligned with the axes was reported
/// as penetrating (a block on a plane at 30 degrees: "6 slave node(s)
/// ... deepest 2.0717e-16", probe explp, tests/explicit_slope.rs).
pub fn penetrations(pairing: &Pairing, u: impl Fn(usize) -> [f64; 3]) -> (usize, f64) {
    let mut count = 0;
    let mut deepest: f64 = 0.0;
    for l in &pairing.links {
        let us = u(l.slave);
        let mut um = [0.0; 3];
        for (j, &mn) in l.master_nodes.iter().enumerate() {
            let a = u(mn);
            for c in 0..3 {
                um[c] += l.shape[j] * a[c];
            }
        }
        let moved: f64 = (0..3).map(|c| l.normal[c] * (um[c] - us[c])).sum();
        let g = l.gap_ref + moved;
        let scale = l.gap_ref.abs()
            + (0..3)
                .map(|c| {
                    (l.normal[c] * um[c]).abs()
                        + (l.normal[c] * us[c]).abs()
                        + 2.0 * (l.normal[c] * l.proj[c]).abs()
                })
                .sum::<f64>();
        if g < -roundoff_gap(scale) {
            count += 1;
            deepest = deepest.max(-g);
        }
    }
    (count, deepest)
}

/// The rounding of a gap summed from terms of total magnitude `scale`:
/// a state computed to lie on a surface (a sticking node of an explicit
/// run, restarted) ends within a few ulps of it on either side, and the
/// initial-state alarm must not call that a penetration (probe
/// roundoff_penetration_alarm: "deepest 4.4409e-16" for 2.27 − 2.27).
pub fn roundoff_gap(scale: f64) -> f64 {
    16.0 * f64::EPSILON * scale
}

/// The alarm of `n` slave nodes penetrating their master at the initial
/// state, the deepest by `depth`; `how` says how the enforcement pushes
/// them out.
pub fn initial_penetration_alarm(n: usize, depth: f64, how: &str) -> String {
    format!(
        "alarm: {n} slave node(s) penetrate the master at the initial state (deepest {depth:.4e}): \
         the contact pushes them out in the first step ({how}), an impulse of the initial state, \
         not of the motion"
    )
}

/// Gap of a link at displacements `u` (fixed pairing): what
/// [`evaluate`] uses, exposed for the geometric-update criterion and tests.
pub fn link_gap(link: &Link, u: &[[f64; 3]]) -> f64 {
    let mut g = link.gap_ref - dot(link.normal, u[link.slave]);
    for (j, &n) in link.master_nodes.iter().enumerate() {
        g += link.shape[j] * dot(link.normal, u[n]);
    }
    g
}

/// The active-set form of a link (ALGO_CONT='CONTRAINTE'): g(u) ≥ 0 is
/// A·u ≤ g_ref with A = −B_n, the coefficients returned per (node,
/// component), slave then master nodes, whether the dof is free or
/// imposed (the caller splits them). A multiplier μ ≥ 0 on it is the
/// force μ·Aᵀ on the F_int side, which is the penalised r_c = −λ_n·B_n
/// with λ_n = μ: both methods report the same CONT_NOEU quantities.
pub fn link_constraint(link: &Link, dim: usize) -> Vec<((usize, usize), f64)> {
    let mut out = Vec::with_capacity((1 + link.master_nodes.len()) * dim);
    for c in 0..dim {
        out.push(((link.slave, c), link.normal[c]));
    }
    for (j, &n) in link.master_nodes.iter().enumerate() {
        for c in 0..dim {
            out.push(((n, c), -link.shape[j] * link.normal[c]));
        }
    }
    out
}
