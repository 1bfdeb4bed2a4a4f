//! Unilateral linear conditions (`DEFI_CONTACT` with
//! `FORMULATION='LIAISON_UNIL'`): one inequality Σ_k a_k(t) u_k ≤ c(t, X)
//! per (zone, node), no pairing, fixed coefficients
//! (shared/docs/notes/liaison-unil.md, semantics.md §6.5).
//!
//! This module is pure algebra on the equations of the linear system: the
//! definition ([`UnilDef`]), its evaluation at an instant ([`Row`]), the
//! primal active-set method of code_aster's `algocu` ([`active_set`]) and
//! the penalised force ([`penalty`]). The Newton loop drives them through
//! `nonlinear::unilateral`.

/// COEF_MULT or COEF_IMPO: a tabulated or constant function (one
/// parameter), or a FORMULE (evaluated by parameter name); shared with
/// AFFE_CHAR_MECA_F's function-valued loads.
pub use crate::post::formula::Coef;

/// `ALGO_CONT` of the zones (the same in every zone).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum UnilAlgo {
    /// `'CONTRAINTE'`: exact conditions by the active set on the Schur
    /// complement.
    ActiveSet,
    /// `'PENALISATION'`: force COEF_PENA × violation and its tangent.
    Penalty,
}

/// One `ZONE` occurrence, resolved on the mesh and the model.
#[derive(Debug, Clone, PartialEq)]
pub struct UnilZone {
    /// Nodes of the zone, ascending, duplicates and SANS_GROUP_NO removed.
    pub nodes: Vec<usize>,
    /// (component index in the node's dofs, COEF_MULT), NOM_CMP order.
    pub components: Vec<(usize, Coef)>,
    pub coef_impo: Coef,
    /// COEF_PENA (PENALISATION only).
    pub coef_pena: Option<f64>,
}

/// One link: a (zone, node) pair. A node in two zones gives two
/// independent links, as in code_aster.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnilLink {
    pub zone: usize,
    pub node: usize,
    /// Initial coordinates of the node (COEF_IMPO may depend on them).
    pub coords: [f64; 3],
}

/// A checked LIAISON_UNIL definition.
#[derive(Debug, Clone, PartialEq)]
pub struct UnilDef {
    pub algo: UnilAlgo,
    pub zones: Vec<UnilZone>,
    /// Zones in keyword order, nodes ascending in each.
    pub links: Vec<UnilLink>,
}

/// Link i at one instant: A_i on the equations and c_i.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// (equation, coefficient).
    pub entries: Vec<(usize, f64)>,
    pub c: f64,
}

impl Row {
    pub fn dot(&self, x: &[f64]) -> f64 {
        self.entries.iter().map(|&(e, a)| a * x[e]).sum()
    }

    /// y += s Aᵀ.
    pub fn add_transpose(&self, s: f64, y: &mut [f64]) {
        for &(e, a) in &self.entries {
            y[e] += s * a;
        }
    }
}

/// COEF_MULT takes INST only (code_aster evaluates it with that single
/// parameter: a function of X fails).
pub fn eval_coef_mult(f: &Coef, inst: f64) -> Result<f64, String> {
    let f = match f {
        Coef::Function(f) => f,
        Coef::Formula(g) => return g.eval(&[("INST", inst)]),
    };
    match f.para.as_str() {
        "TOUTPARA" | "INST" => f.eval(inst),
        other => Err(format!(
            "COEF_MULT is evaluated with the parameter INST only; the function of {other} cannot be evaluated"
        )),
    }
}

/// COEF_IMPO takes INST and the initial X, Y, Z of the node.
pub fn eval_coef_impo(f: &Coef, inst: f64, x: [f64; 3]) -> Result<f64, String> {
    crate::post::formula::eval_inst_xyz(f, inst, x, "COEF_IMPO")
}

impl UnilDef {
    /// Whether some link's COEF_IMPO or COEF_MULT is a function of INST:
    /// the conditions then move (a rising floor), and the obstacle does
    /// work on the model that the balance counts in TRAV_LIAI, with no
    /// error of the scheme in it.
    pub fn moves_with_time(&self) -> bool {
        self.zones.iter().any(|z| {
            z.coef_impo.depends_on("INST") || z.components.iter().any(|(_, c)| c.depends_on("INST"))
        })
    }

    /// The rows of every link at instant `t`, on the equations `eq` (full
    /// dof → equation, `None` for a dof without equation) of a numbering
    /// with `ndpn` components per node. A component imposed by DDL_IMPO
    /// (`imposed` gives its value) is not an unknown: its term a·u_imposed
    /// moves to the right-hand side. This is what code_aster's dualised
    /// DDL_IMPO amounts to: its column C⁻¹Aᵀ is zero on that dof, and the
    /// gap c − A·u counts the imposed value. A row left empty is inert
    /// while its gap is ≥ 0; violated, it is singular (MECANONLINE9_6)
    /// alone and dropped into the zero set next to other active links, as
    /// there (the run's alarm lists it).
    pub fn rows(
        &self,
        t: f64,
        ndpn: usize,
        eq: impl Fn(usize) -> Option<usize>,
        imposed: impl Fn(usize) -> Option<f64>,
    ) -> Result<Vec<Row>, String> {
        self.links
            .iter()
            .map(|l| {
                let z = &self.zones[l.zone];
                let mut entries = Vec::with_capacity(z.components.len());
                let mut shift = 0.0;
                for (k, f) in &z.components {
                    let a = eval_coef_mult(f, t)
                        .map_err(|e| format!("ZONE {}, COEF_MULT: {e}", l.zone + 1))?;
                    let full = l.node * ndpn + k;
                    match (eq(full), imposed(full)) {
                        (Some(e), _) => entries.push((e, a)),
                        (None, Some(u)) => shift += a * u,
                        (None, None) => {
                            return Err(format!(
                                "the unilateral condition at node N{} acts on a component without degree of freedom in the model",
                                l.node + 1
                            ))
                        }
                    }
                }
                // COEF_IMPO depends on the node (X, Y, Z): a failure names
                // it, as the failed evaluation may hold for that node only
                // (a DEFI_FONCTION of Y whose domain misses the top nodes).
                let c = eval_coef_impo(&z.coef_impo, t, l.coords)
                    .map_err(|e| {
                        format!(
                            "ZONE {}, COEF_IMPO at node N{} (X = {}, Y = {}, Z = {}): {e}",
                            l.zone + 1,
                            l.node + 1,
                            l.coords[0],
                            l.coords[1],
                            l.coords[2]
                        )
                    })?
                    - shift;
                Ok(Row { entries, c })
            })
            .collect()
    }
}

/// Why the active set failed (code_aster's codes 1 and 2, events
/// ERRE_CTD1 / ERRE_CTD2: the step may be cut).
#[derive(Debug, Clone, PartialEq)]
pub enum ActiveSetFailure {
    /// More than 2L + 1 passes without convergence (MECANONLINE9_5).
    Cycling { passes: usize, links: usize },
    /// The Schur complement of the active links is singular (MECANONLINE9_6).
    Singular { link: usize },
    /// A solve with the iteration matrix failed.
    Solve(String),
}

impl std::fmt::Display for ActiveSetFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ActiveSetFailure::Cycling { passes, links } => write!(
                f,
                "the active-set method of LIAISON_UNIL did not converge in {passes} passes (limit 2 x {links} links + 1): the active set cycles (failure in the discrete contact treatment, MECANONLINE9_5)"
            ),
            ActiveSetFailure::Singular { link } => write!(
                f,
                "the contact matrix of LIAISON_UNIL is singular at link {} (redundant or blocked conditions, MECANONLINE9_6)",
                link + 1
            ),
            ActiveSetFailure::Solve(m) => write!(f, "LIAISON_UNIL: solve with the iteration matrix: {m}"),
        }
    }
}

/// What a converged active-set call found.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ActiveSetResult {
    /// Non-converging passes (code_aster's counter at convergence).
    pub passes: usize,
    /// Active links in the order of J and their multipliers (≥ 0).
    pub active: Vec<usize>,
    pub mu: Vec<f64>,
}

/// Absolute threshold of the step-length test (code_aster's r8prem).
const EPS: f64 = f64::EPSILON;

/// code_aster's `algocu`: given the unconstrained increment δ⁰ = C⁻¹r
/// (`delta` on entry) and the pseudo-gaps `gaps` = c − A u, finds the
/// increment δ and multipliers μ ≥ 0 with C δ + Aᵀμ = r, g − Aδ ≥ 0,
/// μ·(g − Aδ) = 0, by the primal active-set method on the Schur
/// complement A_J C⁻¹ A_Jᵀ (notation of liaison-unil.md §4). `solve`
/// solves with the factorised C in place (one factorisation, one solve per
/// link that enters the set). `zero_set` marks links once dropped for a
/// zero row of the Schur complement: they are kept out of the step-length
/// test for the rest of the run, as code_aster never resets that set.
///
/// On success `delta` holds δ and `gaps` the gaps at u + δ.
pub fn active_set(
    rows: &[Row],
    gaps: &mut [f64],
    delta: &mut [f64],
    solve: &mut dyn FnMut(&mut [f64]) -> Result<(), String>,
    zero_set: &mut [bool],
) -> Result<ActiveSetResult, ActiveSetFailure> {
    active_set_with_equalities(rows, 0, gaps, delta, solve, zero_set)
}

/// [`active_set`] where the first `equalities` rows are equalities
/// (A_i·u = c_i): always in the set, their multipliers of either sign,
/// never removed nor tested by the step length. The discrete contact's
/// ties of QUAD8 mid-side nodes (code_aster's `cacoeq` relations, which
/// its `algoco` carries as links always active) are such rows. With no
/// equality it is code_aster's `algocu` pass for pass.
pub fn active_set_with_equalities(
    rows: &[Row],
    equalities: usize,
    gaps: &mut [f64],
    delta: &mut [f64],
    solve: &mut dyn FnMut(&mut [f64]) -> Result<(), String>,
    zero_set: &mut [bool],
) -> Result<ActiveSetResult, ActiveSetFailure> {
    let nl = rows.len();
    let n = delta.len();
    let d0 = delta.to_vec();
    let a_d0: Vec<f64> = rows.iter().map(|r| r.dot(&d0)).collect();
    // Initial set: the equalities, then the links δ⁰ violates
    // (strictly), increasing order.
    let mut set: Vec<usize> = (0..nl)
        .filter(|&i| (i < equalities && !zero_set[i]) || gaps[i] - a_d0[i] < 0.0)
        .collect();
    let mut columns: Vec<Option<Vec<f64>>> = vec![None; nl];
    let mut v = vec![0.0; n];
    let mut d = vec![0.0; n];
    let mut mu: Vec<f64> = Vec::new();
    let mut h_max: f64 = 0.0;
    // Rows of the Schur complement from this position of J on are new.
    let mut first_new = 0usize;
    let mut passes = 0usize;
    loop {
        let mut dropped = false;
        if set.is_empty() {
            mu.clear();
            for k in 0..n {
                d[k] = d0[k] - v[k];
            }
        } else {
            for &j in &set {
                if columns[j].is_none() {
                    let mut w = vec![0.0; n];
                    rows[j].add_transpose(1.0, &mut w);
                    solve(&mut w).map_err(ActiveSetFailure::Solve)?;
                    columns[j] = Some(w);
                }
            }
            let m = set.len();
            // S = A_J C⁻¹ A_Jᵀ (code_aster factorises H = −S).
            let mut s = vec![0.0; m * m];
            for l in 0..m {
                for c in 0..=l {
                    let w = columns[set[c]].as_ref().expect("computed above");
                    let h = rows[set[l]].dot(w);
                    s[l * m + c] = h;
                    s[c * m + l] = h;
                    if l >= first_new {
                        h_max = h_max.max(h.abs());
                    }
                }
            }
            // Zero-row test on the new rows: the first row negligible
            // against the largest entry leaves J for the zero set.
            if let Some(l) =
                (first_new..m).find(|&l| (0..=l).all(|c| s[l * m + c].abs() < 1e-8 * h_max))
            {
                let link = set.remove(l);
                zero_set[link] = true;
                first_new = l;
                dropped = true;
            }
            if !dropped {
                first_new = m;
                let rhs: Vec<f64> = set.iter().map(|&j| a_d0[j] - gaps[j]).collect();
                mu = ldlt_solve(&mut s, m, &rhs)
                    .map_err(|l| ActiveSetFailure::Singular { link: set[l] })?;
                for k in 0..n {
                    d[k] = d0[k] - v[k];
                }
                for (p, &j) in set.iter().enumerate() {
                    let w = columns[j].as_ref().expect("computed above");
                    for k in 0..n {
                        d[k] -= mu[p] * w[k];
                    }
                }
            }
        }
        if !dropped {
            // Step length: the first inactive link the direction reaches.
            let mut rho = 1.0;
            let mut entering = None;
            if set.len() < nl {
                let mut best = f64::INFINITY;
                for i in equalities..nl {
                    if zero_set[i] || set.contains(&i) {
                        continue;
                    }
                    let alpha = rows[i].dot(&d);
                    if alpha > EPS {
                        let ratio = (gaps[i] - rows[i].dot(&v)) / alpha;
                        if ratio < best {
                            best = ratio;
                            entering = Some(i);
                        }
                    }
                }
                if entering.is_some() {
                    rho = best;
                }
            }
            let step = rho.min(1.0);
            for k in 0..n {
                v[k] += step * d[k];
            }
            if rho < 1.0 {
                set.push(entering.expect("rho < 1 has a minimiser"));
            } else if set.is_empty() {
                break;
            } else {
                let Some((p, &m)) = mu
                    .iter()
                    .enumerate()
                    .filter(|&(p, _)| set[p] >= equalities)
                    .min_by(|a, b| a.1.total_cmp(b.1))
                else {
                    break;
                };
                if m >= 0.0 {
                    break;
                }
                set.remove(p);
                mu.remove(p);
                first_new = first_new.min(p);
            }
        }
        passes += 1;
        if passes > 2 * nl + 1 {
            return Err(ActiveSetFailure::Cycling { passes, links: nl });
        }
    }
    for (i, r) in rows.iter().enumerate() {
        gaps[i] -= r.dot(&v);
    }
    delta.copy_from_slice(&v);
    Ok(ActiveSetResult {
        passes,
        active: set,
        mu,
    })
}

/// Solves S x = b by LDLᵀ without pivoting (S symmetric, row-major, m×m,
/// overwritten). A pivot below 1/r8gaem or a row that loses 8 digits
/// (original diagonal / pivot ≥ 1e8) is singular, as code_aster's `tldlg3`
/// decides; the error is the position of that row.
fn ldlt_solve(s: &mut [f64], m: usize, b: &[f64]) -> Result<Vec<f64>, usize> {
    let diag: Vec<f64> = (0..m).map(|i| s[i * m + i]).collect();
    for j in 0..m {
        for k in 0..j {
            let ljk = s[j * m + k];
            s[j * m + j] -= ljk * ljk * s[k * m + k];
        }
        let p = s[j * m + j];
        if p.abs() < 1.0 / f64::MAX || (diag[j] / p).abs() >= 1e8 || !p.is_finite() {
            return Err(j);
        }
        for i in j + 1..m {
            let mut x = s[i * m + j];
            for k in 0..j {
                x -= s[i * m + k] * s[j * m + k] * s[k * m + k];
            }
            s[i * m + j] = x / p;
        }
    }
    let mut x = b.to_vec();
    for i in 0..m {
        for k in 0..i {
            x[i] -= s[i * m + k] * x[k];
        }
    }
    for i in 0..m {
        x[i] /= s[i * m + i];
    }
    for i in (0..m).rev() {
        for k in i + 1..m {
            x[i] -= s[k * m + i] * x[k];
        }
    }
    Ok(x)
}

/// The penalised force of link i at displacement gaps g_i = c_i − A_i u:
/// λ_i = −E_i g_i when g_i < ε (active), 0 otherwise (code_aster's
/// `algocup`, absolute threshold ε = r8prem).
pub fn penalty(gap: f64, e: f64) -> Option<f64> {
    (gap < EPS).then(|| -e * gap)
}

/// Why one node's projection has no solution.
#[derive(Debug, Clone, PartialEq)]
pub enum NodeProjectionFailure {
    /// No correction satisfies every link of the node: contradictory
    /// links (a bound above and below with no room between), or a
    /// violated link without free component (all imposed by DDL_IMPO).
    Infeasible,
}

/// The correction x of least M-norm (½ xᵀ M x, M = diag(1/`minv`)) with
/// B x ≤ b, B the rows of one node's links on its components (`rows[i]`
/// has one coefficient per component), and the multipliers μ ≥ 0 of every
/// link (0 for the inactive ones) with M x = −Bᵀμ: the kinematic enforcement of LIAISON_UNIL in explicit
/// dynamics, where the lumped mass makes the nodes independent. Exact by
/// enumeration of the active subsets, smallest first: a node has a few
/// links and at most 3 components, and a KKT point of this strictly
/// convex problem always has a multiplier supported on linearly
/// independent rows (Carathéodory), so subsets of more rows than
/// components, or of dependent rows, are skipped. The iterative active
/// set of [`active_set`] would do, but the enumeration has no cycling
/// and no tolerance on a step length.
pub fn node_projection(
    rows: &[Vec<f64>],
    b: &[f64],
    minv: &[f64],
) -> Result<(Vec<f64>, Vec<f64>), NodeProjectionFailure> {
    let nl = rows.len();
    let d = minv.len();
    let scale_b = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let max_size = nl.min(d);
    let mut subset: Vec<usize> = Vec::with_capacity(max_size);
    for size in 0..=max_size {
        // The subsets of `size` links in lexicographic order.
        subset.clear();
        subset.extend(0..size);
        loop {
            if let Some(found) = try_subset(rows, b, minv, &subset, scale_b) {
                return Ok(found);
            }
            // Next combination.
            let mut k = size;
            let mut advanced = false;
            while k > 0 {
                k -= 1;
                if subset[k] < nl - size + k {
                    subset[k] += 1;
                    for j in k + 1..size {
                        subset[j] = subset[j - 1] + 1;
                    }
                    advanced = true;
                    break;
                }
            }
            if !advanced {
                break;
            }
        }
    }
    Err(NodeProjectionFailure::Infeasible)
}

/// The KKT point with the links of `set` active, if it is one: S μ = −b_J
/// with S = B_J M⁻¹ B_Jᵀ nonsingular, μ ≥ 0, and every link satisfied.
fn try_subset(
    rows: &[Vec<f64>],
    b: &[f64],
    minv: &[f64],
    set: &[usize],
    scale_b: f64,
) -> Option<(Vec<f64>, Vec<f64>)> {
    let m = set.len();
    let d = minv.len();
    let mut s = vec![0.0; m * m];
    for (p, &i) in set.iter().enumerate() {
        for (q, &j) in set.iter().enumerate() {
            s[p * m + q] = (0..d).map(|k| rows[i][k] * minv[k] * rows[j][k]).sum();
        }
    }
    let rhs: Vec<f64> = set.iter().map(|&i| -b[i]).collect();
    let mu = dense_solve(&mut s, m, rhs)?;
    let mu_scale = mu.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    if mu.iter().any(|&x| x < -1e-12 * mu_scale) {
        return None;
    }
    let mut x = vec![0.0; d];
    for (p, &i) in set.iter().enumerate() {
        for k in 0..d {
            x[k] -= minv[k] * rows[i][k] * mu[p];
        }
    }
    for (i, r) in rows.iter().enumerate() {
        let bx: f64 = (0..d).map(|k| r[k] * x[k]).sum();
        let size: f64 = (0..d).map(|k| (r[k] * x[k]).abs()).sum::<f64>() + scale_b;
        if bx > b[i] + 1e-12 * size {
            return None;
        }
    }
    let mut per_link = vec![0.0; rows.len()];
    for (p, &i) in set.iter().enumerate() {
        per_link[i] = mu[p].max(0.0);
    }
    Some((x, per_link))
}

/// Gaussian elimination with partial pivoting of a small dense system
/// (row-major, overwritten); None when a pivot falls below 1e-12 of the
/// largest diagonal entry (dependent links).
fn dense_solve(s: &mut [f64], m: usize, mut x: Vec<f64>) -> Option<Vec<f64>> {
    let big = (0..m).fold(0.0f64, |a, i| a.max(s[i * m + i].abs()));
    for c in 0..m {
        let p = (c..m).max_by(|&i, &j| s[i * m + c].abs().total_cmp(&s[j * m + c].abs()))?;
        let pivot = s[p * m + c].abs();
        // NaN fails too.
        if pivot.is_nan() || pivot <= 1e-12 * big {
            return None;
        }
        if p != c {
            for k in 0..m {
                s.swap(p * m + k, c * m + k);
            }
            x.swap(p, c);
        }
        for r in c + 1..m {
            let f = s[r * m + c] / s[c * m + c];
            for k in c..m {
                s[r * m + k] -= f * s[c * m + k];
            }
            x[r] -= f * x[c];
        }
    }
    for c in (0..m).rev() {
        for k in c + 1..m {
            x[c] -= s[c * m + k] * x[k];
        }
        x[c] /= s[c * m + c];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::post::formula::Formula;
    use crate::post::function::Function;

    /// Dense 2×2 SPD solver for the algebraic cases of liaison-unil.md §9.1.
    fn solver(c: [[f64; 2]; 2]) -> impl FnMut(&mut [f64]) -> Result<(), String> {
        move |b: &mut [f64]| {
            let det = c[0][0] * c[1][1] - c[0][1] * c[1][0];
            let x0 = (c[1][1] * b[0] - c[0][1] * b[1]) / det;
            let x1 = (c[0][0] * b[1] - c[1][0] * b[0]) / det;
            b[0] = x0;
            b[1] = x1;
            Ok(())
        }
    }

    fn floors() -> Vec<Row> {
        vec![
            Row {
                entries: vec![(0, -1.0)],
                c: 0.0,
            },
            Row {
                entries: vec![(1, -1.0)],
                c: 0.0,
            },
        ]
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * (1.0 + b.abs())
    }

    /// §9.1 (a): link 2 enters through a step length ρ = 0.2 < 1.
    #[test]
    fn addition_through_step_length() {
        let c = [[2.0, 1.0], [1.0, 2.0]];
        let mut solve = solver(c);
        let mut delta = vec![-3.0, -1.0];
        solve(&mut delta).unwrap();
        assert!(close(delta[0], -5.0 / 3.0) && close(delta[1], 1.0 / 3.0));
        let mut gaps = vec![0.0, 0.1];
        let mut zero = vec![false; 2];
        let r = active_set(&floors(), &mut gaps, &mut delta, &mut solve, &mut zero).unwrap();
        assert_eq!(r.active, vec![0, 1]);
        assert!(close(r.mu[0], 2.9) && close(r.mu[1], 0.8), "{r:?}");
        assert!(close(delta[0], 0.0) && close(delta[1], -0.1), "{delta:?}");
        assert!(gaps.iter().all(|g| g.abs() < 1e-14));
        assert_eq!(r.passes, 1);
    }

    /// §9.1 (b): link 2 leaves because its multiplier is negative.
    #[test]
    fn removal_through_negative_multiplier() {
        let c = [[2.0, -1.0], [-1.0, 1.0]];
        let mut solve = solver(c);
        let mut delta = vec![-3.0, 0.0];
        solve(&mut delta).unwrap();
        assert!(close(delta[0], -3.0) && close(delta[1], -3.0));
        let mut gaps = vec![1.0, 2.0];
        let mut zero = vec![false; 2];
        let r = active_set(&floors(), &mut gaps, &mut delta, &mut solve, &mut zero).unwrap();
        assert_eq!(r.active, vec![0]);
        assert!(close(r.mu[0], 2.0));
        assert!(close(delta[0], -1.0) && close(delta[1], -1.0), "{delta:?}");
        assert!(close(gaps[0], 0.0) && close(gaps[1], 1.0));
        assert_eq!(r.passes, 1);
    }

    /// Two identical active links make the Schur complement singular.
    #[test]
    fn duplicate_links_are_singular() {
        let rows = vec![
            Row {
                entries: vec![(0, -1.0)],
                c: 0.0,
            },
            Row {
                entries: vec![(0, -1.0)],
                c: 0.0,
            },
        ];
        let mut solve = solver([[1.0, 0.0], [0.0, 1.0]]);
        let mut delta = vec![-1.0, 0.0];
        let mut gaps = vec![0.0, 0.0];
        let mut zero = vec![false; 2];
        let r = active_set(&rows, &mut gaps, &mut delta, &mut solve, &mut zero);
        assert_eq!(r, Err(ActiveSetFailure::Singular { link: 1 }));
    }

    /// No violated link: δ⁰ is returned untouched in zero passes.
    #[test]
    fn free_increment_is_kept() {
        let mut solve = solver([[1.0, 0.0], [0.0, 1.0]]);
        let mut delta = vec![0.5, 0.25];
        let mut gaps = vec![0.0, 0.0];
        let mut zero = vec![false; 2];
        let r = active_set(&floors(), &mut gaps, &mut delta, &mut solve, &mut zero).unwrap();
        assert_eq!((r.passes, r.active.len()), (0, 0));
        assert_eq!(delta, vec![0.5, 0.25]);
        assert_eq!(gaps, vec![0.5, 0.25]);
    }

    /// The cycling guard. With a symmetric positive definite C the method
    /// is a primal active set of a strictly convex QP and terminates; an
    /// indefinite C (never produced by the elements here, hence this
    /// algebraic case) makes the only link's multiplier negative whenever
    /// it is active, while the step length brings it back each time: the
    /// (2L + 2)-th pass is the failure, with code_aster's message.
    #[test]
    fn cycling_stops_at_the_pass_limit() {
        let mut solve = solver([[-1.0, 0.5], [0.5, 2.0]]);
        let mut delta = vec![-1.0, -1.0];
        let mut gaps = vec![0.0];
        let mut zero = vec![false];
        let rows = vec![floors().remove(0)];
        let r = active_set(&rows, &mut gaps, &mut delta, &mut solve, &mut zero);
        assert_eq!(
            r,
            Err(ActiveSetFailure::Cycling {
                passes: 4,
                links: 1
            })
        );
        let msg = r.unwrap_err().to_string();
        assert!(msg.contains("did not converge in 4 passes") && msg.contains("MECANONLINE9_5"));
        // The increment and the gaps are left as they were.
        assert_eq!((delta, gaps), (vec![-1.0, -1.0], vec![0.0]));
    }

    /// A component imposed by DDL_IMPO leaves the unknowns: its term
    /// moves to c. A link left without unknown is inert while its gap is
    /// non-negative, and singular (code 2) once violated alone, as with
    /// code_aster's dualised DDL_IMPO (liaison-unil.md §8); next to other
    /// active links its zero row drops it into the zero set.
    #[test]
    fn imposed_components_move_to_the_right_hand_side() {
        let c = Function::constant(1.0, "TOUTRESU");
        let def = UnilDef {
            algo: UnilAlgo::ActiveSet,
            zones: vec![UnilZone {
                nodes: vec![0, 1],
                components: vec![
                    (0, Function::constant(2.0, "TOUTRESU").into()),
                    (1, Function::constant(-1.0, "TOUTRESU").into()),
                ],
                coef_impo: c.into(),
                coef_pena: None,
            }],
            links: vec![
                UnilLink {
                    zone: 0,
                    node: 0,
                    coords: [0.0; 3],
                },
                UnilLink {
                    zone: 0,
                    node: 1,
                    coords: [0.0; 3],
                },
            ],
        };
        // Node 0: DX free (equation 0), DY imposed to 0.25. Node 1: both
        // imposed (DX = 1, DY = 0.5).
        let eq = |f: usize| (f == 0).then_some(0);
        let imposed = |f: usize| match f {
            1 => Some(0.25),
            2 => Some(1.0),
            3 => Some(0.5),
            _ => None,
        };
        let rows = def.rows(0.0, 2, eq, imposed).unwrap();
        assert_eq!(rows[0].entries, vec![(0, 2.0)]);
        assert!(close(rows[0].c, 1.0 + 0.25));
        assert!(rows[1].entries.is_empty());
        assert!(close(rows[1].c, 1.0 - 2.0 + 0.5));
        // A dof neither free nor imposed has no meaning here.
        assert!(def.rows(0.0, 2, |_| None, |_| None).is_err());
        // The empty row: inert with g = 0.5 >= 0 ...
        let mut solve = solver([[1.0, 0.0], [0.0, 1.0]]);
        let empty = vec![Row {
            entries: vec![],
            c: 0.5,
        }];
        let mut delta = vec![-1.0, 0.0];
        let (mut gaps, mut zero) = (vec![0.5], vec![false]);
        let r = active_set(&empty, &mut gaps, &mut delta, &mut solve, &mut zero).unwrap();
        assert!(r.active.is_empty());
        assert_eq!(delta, vec![-1.0, 0.0]);
        // ... singular with g < 0.
        let (mut gaps, mut zero) = (vec![-0.5], vec![false]);
        let r = active_set(&empty, &mut gaps, &mut delta, &mut solve, &mut zero);
        assert_eq!(r, Err(ActiveSetFailure::Singular { link: 0 }));
        // ... and next to an active link (-DX <= 0, which δ⁰ = (-1, 0)
        // violates), a zero row: dropped into the zero set, the other
        // link enforced exactly (μ = 1, DX = 0), the empty one left
        // violated (code_aster's cupivo).
        let rows = vec![
            Row {
                entries: vec![(0, -1.0)],
                c: 0.0,
            },
            Row {
                entries: vec![],
                c: -0.5,
            },
        ];
        let mut delta = vec![-1.0, 0.0];
        let (mut gaps, mut zero) = (vec![0.0, -0.5], vec![false, false]);
        let r = active_set(&rows, &mut gaps, &mut delta, &mut solve, &mut zero).unwrap();
        assert_eq!(zero, vec![false, true]);
        assert_eq!(r.active, vec![0]);
        assert!(close(r.mu[0], 1.0));
        assert!(delta[0].abs() < 1e-15 && delta[1] == 0.0, "{delta:?}");
        assert!(gaps[1] < 0.0);
    }

    #[test]
    fn penalty_force_is_active_only_on_violation() {
        assert_eq!(penalty(1e-3, 1e6), None);
        assert_eq!(penalty(-1e-3, 1e6), Some(1e3));
    }

    #[test]
    fn coefficient_parameters() {
        let fx: Coef = Function::new("X", "TOUTRESU", vec![0.0, 1.0], vec![0.0, 2.0])
            .unwrap()
            .into();
        assert!(eval_coef_mult(&fx, 0.5).is_err());
        assert_eq!(eval_coef_impo(&fx, 9.0, [0.5, 0.0, 0.0]).unwrap(), 1.0);
        let k: Coef = Function::constant(-1.0, "TOUTRESU").into();
        assert_eq!(eval_coef_mult(&k, 3.0).unwrap(), -1.0);
        // A FORMULE is evaluated by parameter name: COEF_IMPO with INST and
        // the initial X, Y, Z, COEF_MULT with INST only.
        let params = ["INST".to_string(), "Y".to_string(), "Z".to_string()];
        use crate::post::formula::{Node, Op};
        let p = |i| Box::new(Node::Param(i));
        let k = |x| Box::new(Node::Num(x));
        let node = Node::Bin(
            Op::Add,
            p(0),
            Box::new(Node::Bin(
                Op::Add,
                Box::new(Node::Bin(Op::Mul, k(10.0), p(1))),
                Box::new(Node::Bin(Op::Mul, k(100.0), p(2))),
            )),
        );
        let g = Coef::Formula(Formula {
            params: params.to_vec(),
            text: "INST + 10 * Y + 100 * Z".into(),
            node,
            callees: Vec::new(),
        });
        assert_eq!(eval_coef_impo(&g, 1.0, [5.0, 2.0, 3.0]).unwrap(), 321.0);
        let e = eval_coef_mult(&g, 1.0).unwrap_err();
        assert!(e.contains("needs Y"), "{e}");
    }

    /// One link: the correction moves the node onto the link along
    /// M⁻¹aᵀ, μ = −b / (a M⁻¹ aᵀ).
    #[test]
    fn node_projection_single_link() {
        // -x1 <= -2 (x1 >= 2), masses 1 and 4.
        let (x, mu) = node_projection(&[vec![-1.0, 0.0]], &[-2.0], &[1.0, 0.25]).unwrap();
        assert!(close(x[0], 2.0) && close(x[1], 0.0), "{x:?}");
        assert!(close(mu[0], 2.0));
        // Satisfied: no correction.
        let (x, mu) = node_projection(&[vec![-1.0, 0.0]], &[1.0], &[1.0, 1.0]).unwrap();
        assert_eq!((x, mu), (vec![0.0, 0.0], vec![0.0]));
    }

    /// A corner against two walls (x ≥ 1, y ≥ 1 from x = y = 0, unequal
    /// masses): both links active, μ = the masses times the moves. A
    /// sloped wall x + y ≤ −1 with unit masses: the projection is along
    /// (1, 1)/2, x = y = −1/2, μ = 1/2. With a second, inactive wall
    /// y ≤ 5 beside it, the same answer (its multiplier 0); with the
    /// wall x ≥ 0 added the node slides along it to (0, −1): μ_slope = 1
    /// (M x = −μ (1, 1) − ν (−1, 0) gives y = −μ = −1), ν = 1.
    #[test]
    fn node_projection_two_links_by_hand() {
        let minv = [1.0 / 2.0, 1.0 / 3.0];
        let rows = [vec![-1.0, 0.0], vec![0.0, -1.0]];
        let (x, mu) = node_projection(&rows, &[-1.0, -1.0], &minv).unwrap();
        assert!(close(x[0], 1.0) && close(x[1], 1.0), "{x:?}");
        assert!(close(mu[0], 2.0) && close(mu[1], 3.0), "{mu:?}");
        let (x, mu) = node_projection(&[vec![1.0, 1.0]], &[-1.0], &[1.0, 1.0]).unwrap();
        assert!(close(x[0], -0.5) && close(x[1], -0.5) && close(mu[0], 0.5));
        let rows = [vec![1.0, 1.0], vec![0.0, 1.0]];
        let (x, mu) = node_projection(&rows, &[-1.0, 5.0], &[1.0, 1.0]).unwrap();
        assert!(close(x[0], -0.5) && close(x[1], -0.5) && mu[1] == 0.0);
        let rows = [vec![1.0, 1.0], vec![-1.0, 0.0]];
        let (x, mu) = node_projection(&rows, &[-1.0, 0.0], &[1.0, 1.0]).unwrap();
        assert!(close(x[0], 0.0) && close(x[1], -1.0), "{x:?}");
        assert!(close(mu[0], 1.0) && close(mu[1], 1.0), "{mu:?}");
    }

    /// Contradictory links (x ≤ −1 and x ≥ 0) and a violated link without
    /// component have no solution: an error, not a wrong correction.
    #[test]
    fn node_projection_infeasible() {
        let rows = [vec![1.0], vec![-1.0]];
        assert_eq!(
            node_projection(&rows, &[-1.0, 0.0], &[1.0]),
            Err(NodeProjectionFailure::Infeasible)
        );
        assert_eq!(
            node_projection(&[vec![0.0]], &[-1.0], &[1.0]),
            Err(NodeProjectionFailure::Infeasible)
        );
        // Duplicate links: the pair is dependent, one of them suffices.
        let rows = [vec![-1.0], vec![-1.0]];
        let (x, _) = node_projection(&rows, &[-1.0, -1.0], &[1.0]).unwrap();
        assert!(close(x[0], 1.0));
    }
}
