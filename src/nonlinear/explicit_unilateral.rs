//! LIAISON_UNIL in explicit dynamics, an aster extension: code_aster
//! refuses DEFI_CONTACT(FORMULATION='LIAISON_UNIL') with DIFF_CENT and
//! TCHAMWA (MECANONLINE5_23). The links A_i·u ≤ c_i are those of the
//! implicit term (`contact::unilateral::UnilDef::rows`: coefficients at
//! the instant the state belongs to, DDL_IMPO components moved to c), and
//! the two enforcements plug into the explicit loop where the discrete
//! contact's do (`nonlinear::explicit_contact`, notes/explicit.md §10):
//! - ALGO_CONT='CONTRAINTE': kinematic. After a_{n+1} is known, the next
//!   predicted position u + Δt v + c Δt² a of each node is tested against
//!   its links at t_{n+2}; a node that would violate one gets the
//!   acceleration correction δa of least kinetic-energy change (the
//!   M-metric projection, `contact::unilateral::node_projection`) that
//!   satisfies all its links with multipliers ≥ 0, and the force M δa
//!   (momentum exchanged = impulse). Every link involves the components
//!   of one node and the mass is lumped, so the nodes are independent:
//!   a few links per node, solved exactly, no global iteration. This is
//!   the explicit counterpart of the implicit active set.
//! - ALGO_CONT='PENALISATION': the force E·max(0, −g)·A_iᵀ at u_{n+1}
//!   (g = c − A u, coefficients at t_{n+1}) enters the right-hand side of
//!   a_{n+1}, and the stiffness E A_iᵀA_i adds to ω² of the stable step.
//!
//! No CONT_NOEU, as the implicit LIAISON_UNIL; the reactions are read as
//! REAC_NODA, and their work is TRAV_LIAI of the energy balance.

use super::dofs::{DofNumbering, NONE};
use super::explicit::ExplicitConstraint;
use super::unilateral::imposed_value;
use crate::contact::unilateral::{
    eval_coef_mult, node_projection, penalty, Row, UnilAlgo, UnilDef,
};
use crate::result::ContactHistory;
use crate::time::Kinematics as Motion;

pub struct ExplicitUnilateral {
    pub def: UnilDef,
    ndpn: usize,
    /// The links' rows at `rows_t` (on the equations).
    rows: Vec<Row>,
    rows_t: Option<f64>,
    /// The links of each node: (node, link indices), nodes ascending.
    by_node: Vec<(usize, Vec<usize>)>,
    /// The largest |COEF_MULT| of each (zone, component) over the
    /// instants of the run (the penalty's stiffness in the step bound).
    coef_max: Vec<Vec<f64>>,
    force: Vec<f64>,
    /// The forces of the last committed state (a failed step overwrites
    /// `force` before the archive of the state it started from).
    force_prev: Vec<f64>,
    body_force: [f64; 3],
    body_force_prev: [f64; 3],
    pub impulse: [f64; 3],
    /// Largest violation seen at an evaluated state (penalty).
    pub max_penetration: f64,
    /// Largest number of links active (kinematic: corrected nodes'
    /// active links; penalty: violated links) at a state.
    pub max_active: usize,
    /// Node corrections made (kinematic).
    pub corrections: usize,
}

impl ExplicitUnilateral {
    /// `instants`: the list's step ends, over which the coefficients'
    /// largest magnitudes are taken for the step bound (a COEF_MULT of
    /// INST that peaks between two instants of the list is taken at the
    /// instants only: the bound is that of the list's sampling).
    pub fn new(
        def: UnilDef,
        numbering: &DofNumbering,
        instants: &[f64],
    ) -> Result<ExplicitUnilateral, String> {
        let mut by_node: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
        for (i, l) in def.links.iter().enumerate() {
            by_node.entry(l.node).or_default().push(i);
        }
        let mut coef_max = Vec::with_capacity(def.zones.len());
        for (z, zone) in def.zones.iter().enumerate() {
            let mut per = Vec::with_capacity(zone.components.len());
            for (_, f) in &zone.components {
                let mut m: f64 = 0.0;
                for &t in instants {
                    let a = eval_coef_mult(f, t).map_err(|e| {
                        format!(
                            "LIAISON_UNIL at INST = {t:e}: ZONE {}, COEF_MULT: {e}",
                            z + 1
                        )
                    })?;
                    m = m.max(a.abs());
                }
                per.push(m);
            }
            coef_max.push(per);
        }
        Ok(ExplicitUnilateral {
            def,
            ndpn: numbering.ndpn,
            rows: Vec::new(),
            rows_t: None,
            by_node: by_node.into_iter().collect(),
            coef_max,
            force: vec![0.0; numbering.nfull()],
            force_prev: vec![0.0; numbering.nfull()],
            body_force: [0.0; 3],
            body_force_prev: [0.0; 3],
            impulse: [0.0; 3],
            max_penetration: 0.0,
            max_active: 0,
            corrections: 0,
        })
    }

    /// The rows at `t` (kept while `t` does not change).
    fn rows_at(&mut self, numbering: &DofNumbering, t: f64) -> Result<(), String> {
        if self.rows_t == Some(t) {
            return Ok(());
        }
        let eq = |f: usize| (numbering.eq[f] != NONE).then(|| numbering.eq[f]);
        self.rows = self
            .def
            .rows(t, self.ndpn, eq, imposed_value(numbering))
            .map_err(|e| format!("LIAISON_UNIL at INST = {t:e}: {e}"))?;
        self.rows_t = Some(t);
        Ok(())
    }

    /// c_i − A_i·x for the full vector `x`.
    fn gap(&self, numbering: &DofNumbering, i: usize, x: &[f64]) -> f64 {
        let r = &self.rows[i];
        r.c - r
            .entries
            .iter()
            .map(|&(e, a)| a * x[numbering.free[e]])
            .sum::<f64>()
    }
}

impl ExplicitConstraint for ExplicitUnilateral {
    fn kinematic(&self) -> bool {
        self.def.algo == UnilAlgo::ActiveSet
    }

    /// E Σ_k a_k²/m_k summed over the links of a node, the largest over the
    /// nodes: the exact k/m of a single link (rank one), and an upper bound
    /// of the largest eigenvalue of M^{-1/2} K M^{-1/2} for several links
    /// on one node (the trace of a sum of rank-one terms), so the step
    /// stays stable.
    fn penalty_omega2(&self, mass: &[f64]) -> f64 {
        if self.kinematic() {
            return 0.0;
        }
        let nd = self.ndpn;
        let mut w2: f64 = 0.0;
        for (node, links) in &self.by_node {
            let mut sum = 0.0;
            for &i in links {
                let z = self.def.links[i].zone;
                let zone = &self.def.zones[z];
                let e = zone.coef_pena.unwrap_or(0.0);
                for (k, &(c, _)) in zone.components.iter().enumerate() {
                    let m = mass[node * nd + c];
                    if m > 0.0 {
                        sum += e * self.coef_max[z][k].powi(2) / m;
                    }
                }
            }
            w2 = w2.max(sum);
        }
        w2
    }

    /// The kinematic correction evaluates its rows at the instant it
    /// predicts (`correct`'s t_next): once the initial state's rows exist
    /// (for its violation check), the loop's preparation at the step end
    /// would only evaluate them for nothing.
    fn prepare(&mut self, numbering: &DofNumbering, _u: &[f64], t: f64) -> Result<(), String> {
        let _contact = crate::profile::span(crate::profile::Phase::Contact);
        if self.kinematic() && self.rows_t.is_some() {
            return Ok(());
        }
        self.rows_at(numbering, t)
    }

    fn penetrations(&self, numbering: &DofNumbering, u: &[f64]) -> (usize, f64) {
        let mut count = 0;
        let mut deepest: f64 = 0.0;
        for i in 0..self.rows.len() {
            let g = self.gap(numbering, i, u);
            if g < 0.0 {
                count += 1;
                deepest = deepest.max(-g);
            }
        }
        (count, deepest)
    }

    fn initial_penetrations(&self, numbering: &DofNumbering, u: &[f64], t0: f64) -> (usize, f64) {
        let eq = |f: usize| (numbering.eq[f] != NONE).then(|| numbering.eq[f]);
        // A coefficient undefined at t0 (a function that starts later) is
        // no initial violation: the run reports its own error where the
        // conditions are evaluated.
        let Ok(rows) = self.def.rows(t0, self.ndpn, eq, imposed_value(numbering)) else {
            return (0, 0.0);
        };
        let mut count = 0;
        let mut deepest: f64 = 0.0;
        for r in &rows {
            let au: f64 = r
                .entries
                .iter()
                .map(|&(e, a)| a * u[numbering.free[e]])
                .sum();
            let g = r.c - au;
            if g < -crate::contact::roundoff_gap(r.c.abs() + au.abs()) {
                count += 1;
                deepest = deepest.max(-g);
            }
        }
        (count, deepest)
    }

    fn moves_with_time(&self) -> bool {
        self.def.moves_with_time()
    }

    fn initial_alarm(&self, n: usize, depth: f64) -> String {
        format!(
            "  alarm: {n} LIAISON_UNIL link(s) violated at the initial state (largest c - A u = -{depth:.4e}): {}, an impulse of the initial state, not of the motion",
            if self.kinematic() {
                "the kinematic enforcement puts the nodes back on their bounds within the first step"
            } else {
                "the penalty pushes them back with COEF_PENA times the violation"
            }
        )
    }

    fn penalty(
        &mut self,
        numbering: &DofNumbering,
        _u_n: &[f64],
        u: &[f64],
        t: f64,
    ) -> Result<(), String> {
        let _contact = crate::profile::span(crate::profile::Phase::Contact);
        self.rows_at(numbering, t)?;
        self.force.iter_mut().for_each(|x| *x = 0.0);
        let mut body = [0.0; 3];
        let mut active = 0;
        let nd = self.ndpn;
        for i in 0..self.rows.len() {
            let z = self.def.links[i].zone;
            let e = self.def.zones[z].coef_pena.unwrap_or(0.0);
            let g = self.gap(numbering, i, u);
            let Some(lambda) = penalty(g, e) else {
                continue;
            };
            active += 1;
            self.max_penetration = self.max_penetration.max(-g);
            for &(eq, a) in &self.rows[i].entries {
                let f = numbering.free[eq];
                self.force[f] += lambda * a;
                body[f % nd] -= lambda * a;
            }
        }
        self.body_force = body;
        self.max_active = self.max_active.max(active);
        Ok(())
    }

    fn correct(
        &mut self,
        numbering: &DofNumbering,
        mass: &[f64],
        m: &mut Motion,
        dt: f64,
        kappa: f64,
        c: f64,
        t_next: f64,
    ) -> Result<(), String> {
        let _contact = crate::profile::span(crate::profile::Phase::Contact);
        self.force.iter_mut().for_each(|x| *x = 0.0);
        self.body_force = [0.0; 3];
        if dt <= 0.0 {
            return Ok(());
        }
        self.rows_at(numbering, t_next)?;
        let h = dt * kappa + c * dt * dt;
        let nd = self.ndpn;
        // The predicted displacement of the free dofs a correction reads.
        let pred = |f: usize| m.u[f] + dt * m.v[f] + c * dt * dt * m.a[f];
        let mut active = 0;
        let mut corrections = Vec::new();
        for (node, links) in &self.by_node {
            let gaps: Vec<f64> = links
                .iter()
                .map(|&i| {
                    let r = &self.rows[i];
                    r.c - r
                        .entries
                        .iter()
                        .map(|&(e, a)| a * pred(numbering.free[e]))
                        .sum::<f64>()
                })
                .collect();
            if gaps.iter().all(|&g| g >= 0.0) {
                continue;
            }
            // The node's free components, as the rows' equations give them.
            let mut dofs: Vec<usize> = links
                .iter()
                .flat_map(|&i| self.rows[i].entries.iter().map(|&(e, _)| numbering.free[e]))
                .collect();
            dofs.sort_unstable();
            dofs.dedup();
            let dense: Vec<Vec<f64>> = links
                .iter()
                .map(|&i| {
                    let mut row = vec![0.0; dofs.len()];
                    for &(e, a) in &self.rows[i].entries {
                        let k = dofs
                            .binary_search(&numbering.free[e])
                            .expect("collected above");
                        row[k] += a;
                    }
                    row
                })
                .collect();
            let b: Vec<f64> = gaps.iter().map(|g| g / h).collect();
            let minv: Vec<f64> = dofs
                .iter()
                .map(|&f| if mass[f] > 0.0 { 1.0 / mass[f] } else { 0.0 })
                .collect();
            let (da, mu) = node_projection(&dense, &b, &minv).map_err(|_| {
                let worst = links
                    .iter()
                    .zip(&gaps)
                    .min_by(|a, b| a.1.total_cmp(b.1))
                    .map(|(&i, _)| self.def.links[i].zone + 1)
                    .unwrap_or(0);
                format!(
                    "LIAISON_UNIL at INST = {t_next:e}: the links of node N{} (zone {worst} violated) cannot all be satisfied: contradictory conditions, or a violated condition on components all imposed by DDL_IMPO (the explicit counterpart of MECANONLINE9_6)",
                    node + 1
                )
            })?;
            active += mu.iter().filter(|&&x| x > 0.0).count();
            corrections.push((dofs, da));
        }
        for (dofs, da) in &corrections {
            for (&f, &d) in dofs.iter().zip(da) {
                m.a[f] += d;
                m.v[f] += kappa * d;
                let force = mass[f] * d;
                self.force[f] -= force;
                self.body_force[f % nd] += force;
            }
        }
        self.corrections += corrections.len();
        self.max_active = self.max_active.max(active);
        Ok(())
    }

    fn start(&mut self) {
        self.body_force_prev = self.body_force;
        self.force_prev.copy_from_slice(&self.force);
    }

    fn commit(&mut self, _u: &[f64], dt: f64, w: f64) {
        let _contact = crate::profile::span(crate::profile::Phase::Contact);
        for k in 0..3 {
            self.impulse[k] += dt * ((1.0 - w) * self.body_force_prev[k] + w * self.body_force[k]);
        }
        self.body_force_prev = self.body_force;
        self.force_prev.copy_from_slice(&self.force);
    }

    fn force_on_fint_side(&self) -> &[f64] {
        &self.force
    }

    fn friction_dissipation(&self) -> f64 {
        0.0
    }

    fn cont_noeu(
        &self,
        _u: &[f64],
        _u_start: &[f64],
        _dt: f64,
    ) -> Option<crate::result::NodalField> {
        None
    }

    fn cont_noeu_initial(&self) -> Option<crate::result::NodalField> {
        None
    }

    fn summary_line(&self) -> String {
        let what = if self.kinematic() {
            format!(
                "kinematic (no violation by construction): {} node corrections",
                self.corrections
            )
        } else {
            format!("penalty (largest violation {:.4e})", self.max_penetration)
        };
        format!(
            "  explicit LIAISON_UNIL, {what}, at most {} links active at once; impulse of the contact reactions on the bodies ({})",
            self.max_active,
            self.impulse[..self.ndpn.min(3)]
                .iter()
                .map(|x| format!("{x:.9e}"))
                .collect::<Vec<_>>()
                .join(", ")
        )
    }

    /// The forces of the committed state: the links are functions of the
    /// state and the instant, no friction, so this is what starts the
    /// trapezoids of a continuation's first step.
    fn history(&self) -> ContactHistory {
        ContactHistory {
            ndpn: self.ndpn,
            force: super::explicit_contact::sparse(&self.force_prev),
            body_force: self.body_force_prev,
            ..ContactHistory::default()
        }
    }

    fn restore(&mut self, h: &ContactHistory) -> Result<(), String> {
        h.check_fits(self.ndpn, self.force.len())?;
        if !h.friction.is_empty() {
            return Err("it holds friction links, which LIAISON_UNIL has not".into());
        }
        for &(f, v) in &h.force {
            self.force[f] += v;
        }
        for k in 0..3 {
            self.body_force[k] += h.body_force[k];
        }
        Ok(())
    }
}
