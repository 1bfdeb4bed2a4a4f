//! Continuous contact in the Newton loop (`FORMULATION='CONTINUE'`): the
//! contact pressure `LAGS_C` and the friction semi-multiplier `LAGS_F1`
//! of every slave node are unknowns of the linear system, numbered after
//! the displacement equations, and the contact statuses, the friction
//! phases and the pairing are all updated inside the Newton iterations
//! (code_aster's generalised Newton, docs/contact.md §9).
//!
//! Step by step (contact-continue.md §7): the multipliers restart from 0
//! at every step (they are totals held in the increment); the prediction
//! uses the statuses of the last converged step; every later iteration
//! re-pairs on the current geometry (`ALGO_RESO_GEOM='NEWTON'`), evaluates
//! the statuses from the current λ and gap, then computes the residual and
//! the tangent with them. A step converges when the displacement residual
//! criteria hold **and** no status changed at that iteration **and** the
//! last correction of `LAGS_C` satisfies `RESI_FROT`.

use super::cycling::{Cycling, Observation, CYCLING_ITERATIONS};
use super::dofs::{DofNumbering, NONE};
use super::newton::ContactIteration;
use crate::contact::continuous::{
    contact_status, evaluate_point, nodal_weights, phase, ContactInit, ContinuousDef, Phase,
    PointInput, Resolution,
};
use crate::contact::continuous3d::{
    evaluate_point3, phase3, tangents_from_normal, PointInput3, PointOutput3,
};
use crate::contact::{pair, ContactDef, ContactState, Link, LinkState, LinkStatus, Pairing};
use crate::mesh::Mesh;
use crate::result::NodalField;

/// One contact point: a slave node of a zone and its weight ω.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    pub zone: usize,
    pub node: usize,
    pub omega: f64,
}

/// The continuous contact term of one DYNA_NON_LINE computation.
pub struct ContinuousContact {
    pub def: ContactDef,
    pub cdef: ContinuousDef,
    mesh: Mesh,
    ndpn: usize,
    pub points: Vec<Point>,
    /// Per (zone, slave node) of a point: the number of slave cells of
    /// the zone holding the node, i.e. how many times code_aster's
    /// `mmmres` visits it per step (the percussion's increment).
    visits: std::collections::HashMap<(usize, usize), usize>,
    /// Unknowns per point: 1 (`LAGS_C`), or with friction 2 in 2D
    /// (+ `LAGS_F1`) and 3 in 3D (+ `LAGS_F1`, `LAGS_F2`).
    stride: usize,
    neq: usize,
    /// Current multipliers (point-major).
    pub lam: Vec<f64>,
    /// Their values at the last committed step (for DEPL).
    pub committed_lam: Vec<f64>,
    pub status: Vec<bool>,
    committed_status: Vec<bool>,
    /// λ_s, the friction threshold used while λ is exactly 0.
    lam_s: Vec<f64>,
    committed_lam_s: Vec<f64>,
    /// No status evaluation yet in this step (the prediction).
    first: bool,
    /// A status changed at the last evaluation.
    pub changed: bool,
    /// Status evaluations of the contact fixed point in this step.
    fixed_point_loops: usize,
    /// The last one changed a status (not yet seen by an iteration).
    fixed_point_changed: bool,
    /// Threshold updates of the friction fixed point in this step
    /// (`ALGO_RESO_FROT='POINT_FIXE'`).
    pub friction_loops: usize,
    /// LAGS_C per point at the previous threshold update (0 at the step
    /// start, code_aster's `.DEPF`): the friction fixed point's reference.
    friction_ref: Vec<f64>,
    /// Largest |δλ| (LAGS_C) of the last correction.
    last_dlam: f64,
    u_start: Vec<[f64; 3]>,
    pairing: Pairing,
    /// The displacement (per node) the pairing was made at.
    u_paired: Vec<[f64; 3]>,
    /// Largest move of a point between the last two pairings (POINT_FIXE).
    geom_move: f64,
    /// Largest master edge (`arete_max`), the RESI_GEOM denominator.
    a_max: f64,
    /// The cycling detectors (`ADAPTATION='CYCLAGE'`).
    pub cycling: Cycling,
    /// λ per point at the last status evaluation of the step (None before
    /// the first): the cycling treatment's pressure residual.
    eval_lam: Vec<Option<f64>>,
    entries: Vec<(usize, usize)>,
    /// Whether each full dof is an equation (not imposed).
    free: Vec<bool>,
    residual: Vec<f64>,
    pub trial: ContactState,
    pub committed: ContactState,
}

/// (node, C_a) of a contact point: the slave with 1, then the master
/// nodes with minus their shape values (the gap's coefficients).
fn point_nodes(slave: usize, link: &Link) -> Vec<(usize, f64)> {
    std::iter::once((slave, 1.0))
        .chain(
            link.master_nodes
                .iter()
                .zip(&link.shape)
                .map(|(&n, &m)| (n, -m)),
        )
        .collect()
}

fn per_node(ndpn: usize, u: &[f64]) -> Vec<[f64; 3]> {
    u.chunks(ndpn)
        .map(|c| {
            let mut v = [0.0; 3];
            v[..ndpn].copy_from_slice(c);
            v
        })
        .collect()
}

impl ContinuousContact {
    /// The term at the initial state `u0` (full). `axis`: the points'
    /// weights carry r (AXIS). Errors: what is not implemented.
    pub fn new(
        def: ContactDef,
        cdef: ContinuousDef,
        mesh: &Mesh,
        numbering: &DofNumbering,
        u0: &[f64],
        axis: bool,
    ) -> Result<Self, String> {
        let mut points = Vec::new();
        for (iz, z) in cdef.zones.iter().enumerate() {
            let slaves = &def.zones[iz].slave_nodes;
            for (node, omega) in nodal_weights(mesh, &z.slave_cells, axis)? {
                if slaves.binary_search(&node).is_ok() || slaves.contains(&node) {
                    points.push(Point {
                        zone: iz,
                        node,
                        omega,
                    });
                }
            }
        }
        let mut visits: std::collections::HashMap<(usize, usize), usize> = Default::default();
        for (iz, z) in cdef.zones.iter().enumerate() {
            for &c in &z.slave_cells {
                for &n in &mesh.cells[c].nodes {
                    *visits.entry((iz, n)).or_insert(0) += 1;
                }
            }
        }
        visits.retain(|&(iz, n), _| points.iter().any(|p| p.zone == iz && p.node == n));
        let friction = cdef.zones.iter().any(|z| z.mu.is_some());
        // LAGS_C, then LAGS_F1 (and LAGS_F2 in 3D) with friction.
        let stride = if friction { def.dim } else { 1 };
        let nx = points.len() * stride;
        let neq = numbering.neq();
        let ndpn = numbering.ndpn;
        // Every possible coupling: a point with every master node of its
        // zone (the pairing may move between master cells within a step).
        let mut entries = Vec::new();
        for (i, p) in points.iter().enumerate() {
            let mut eqs: Vec<usize> = Vec::new();
            let mut nodes = vec![p.node];
            for &c in &def.zones[p.zone].master_cells {
                nodes.extend(mesh.cells[c].nodes.iter().copied());
            }
            for n in nodes {
                for c in 0..def.dim.min(ndpn) {
                    let e = numbering.eq[n * ndpn + c];
                    if e != NONE {
                        eqs.push(e);
                    }
                }
            }
            for k in 0..stride {
                eqs.push(neq + i * stride + k);
            }
            eqs.sort_unstable();
            eqs.dedup();
            for &a in &eqs {
                for &b in &eqs {
                    entries.push((a, b));
                }
            }
        }
        entries.sort_unstable();
        entries.dedup();
        let mut a_max: f64 = 0.0;
        let mut a_min = f64::INFINITY;
        let mut h_mesh = f64::INFINITY;
        for z in &def.zones {
            for &c in &z.master_cells {
                let ns = &mesh.cells[c].nodes;
                let e = crate::mesh::vec3::norm(crate::mesh::vec3::sub(
                    mesh.coords[ns[1]],
                    mesh.coords[ns[0]],
                ));
                a_max = a_max.max(e);
                if e > 0.0 {
                    a_min = a_min.min(e);
                }
            }
        }
        for cell in &mesh.cells {
            let ns = &cell.nodes;
            for k in 0..ns.len().min(2) {
                let e = crate::mesh::vec3::norm(crate::mesh::vec3::sub(
                    mesh.coords[ns[(k + 1) % ns.len()]],
                    mesh.coords[ns[k]],
                ));
                if e > 0.0 {
                    h_mesh = h_mesh.min(e);
                }
            }
        }
        let un = per_node(ndpn, u0);
        let pairing = pair(&def, mesh, &un);
        let np = points.len();
        let mut c = ContinuousContact {
            def,
            cdef,
            mesh: mesh.clone(),
            ndpn,
            points,
            visits,
            stride,
            neq,
            lam: vec![0.0; nx],
            committed_lam: vec![0.0; nx],
            status: vec![false; np],
            committed_status: vec![false; np],
            lam_s: vec![0.0; np],
            committed_lam_s: vec![0.0; np],
            first: true,
            changed: false,
            last_dlam: 0.0,
            fixed_point_loops: 0,
            fixed_point_changed: false,
            friction_loops: 0,
            friction_ref: vec![0.0; np],
            u_paired: un.clone(),
            u_start: un,
            pairing,
            geom_move: 0.0,
            a_max: if a_max > 0.0 { a_max } else { 1.0 },
            cycling: Cycling::new(np, if a_min.is_finite() { a_min } else { 1.0 }),
            eval_lam: vec![None; np],
            entries,
            free: numbering.eq.iter().map(|&e| e != NONE).collect(),
            residual: vec![0.0; nx],
            trial: ContactState::default(),
            committed: ContactState::default(),
        };
        // CONTACT_INIT and SEUIL_INIT (mmopti, first step only).
        let links = c.links();
        for (i, p) in c.points.iter().enumerate() {
            let z = &c.cdef.zones[p.zone];
            c.status[i] = match (z.contact_init, links[i]) {
                (_, None) => false,
                (ContactInit::Oui, _) => true,
                (ContactInit::Non, _) => false,
                (ContactInit::Interpenetre, Some(l)) => -c.pairing.links[l].gap >= -1e-6 * h_mesh,
            };
            c.lam_s[i] = z.seuil_init.map_or(0.0, |s| -s.abs());
        }
        c.committed_status = c.status.clone();
        c.committed_lam_s = c.lam_s.clone();
        let u = c.u_start.clone();
        let st = c.state(&u, None);
        c.trial = st.clone();
        c.committed = st;
        Ok(c)
    }

    /// Number of extra unknowns (multipliers).
    pub fn extra_unknowns(&self) -> usize {
        self.lam.len()
    }

    /// The index in `pairing.links` of each point's link.
    fn links(&self) -> Vec<Option<usize>> {
        let mut by: std::collections::HashMap<(usize, usize), usize> = Default::default();
        for (k, l) in self.pairing.links.iter().enumerate() {
            by.insert((l.zone, l.slave), k);
        }
        self.points
            .iter()
            .map(|p| by.get(&(p.zone, p.node)).copied())
            .collect()
    }

    fn repair(&mut self, u: &[[f64; 3]]) {
        let old: Vec<(usize, usize, [f64; 3])> = self
            .pairing
            .links
            .iter()
            .map(|l| (l.zone, l.slave, l.proj))
            .collect();
        self.pairing = pair(&self.def, &self.mesh, u);
        self.u_paired = u.to_vec();
        // Move of the projections (RESI_GEOM of the fixed point).
        let mut mv: f64 = 0.0;
        for l in &self.pairing.links {
            if let Some((_, _, p)) = old.iter().find(|o| o.0 == l.zone && o.1 == l.slave) {
                mv = mv.max(crate::mesh::vec3::norm(crate::mesh::vec3::sub(l.proj, *p)));
            }
        }
        self.geom_move = mv / self.a_max;
    }

    /// The gap of `link` at displacement `u` (per node): the pairing's gap
    /// plus the change of n·(Σ M_j u_j − u_s) since the pairing, the
    /// projection ξ and the normal frozen (code_aster's gap with a fixed
    /// pairing, the discrete method's `link_gap`). Until 2026-11-28 the
    /// pairing's gap itself was used, as if the gap did not depend on the
    /// displacement between two pairings: with `ALGO_RESO_GEOM=
    /// 'POINT_FIXE'` (the default) every Newton iterate of a step was
    /// judged by the gap of the step's start, and so was the first iterate
    /// after a prediction that moves the nodes (an imposed displacement):
    /// probe s8g's D2 and D3. Written as a difference so that at the
    /// pairing's own displacement it is the pairing's gap bit for bit.
    fn gap(&self, link: &Link, u: &[[f64; 3]]) -> f64 {
        use crate::mesh::vec3::{dot, sub};
        let n = link.normal;
        let mut g = link.gap - dot(n, sub(u[link.slave], self.u_paired[link.slave]));
        for (m, &j) in link.shape.iter().zip(&link.master_nodes) {
            g += m * dot(n, sub(u[j], self.u_paired[j]));
        }
        g
    }

    /// The input of point i at displacement `u` (per node); `free(n, c)`
    /// tells whether dof c of node n is an equation.
    fn input(
        &self,
        i: usize,
        link: &Link,
        u: &[[f64; 3]],
        free: &dyn Fn(usize, usize) -> bool,
    ) -> PointInput {
        let p = self.points[i];
        let z = &self.cdef.zones[p.zone];
        let du = |n: usize| crate::mesh::vec3::sub(u[n], self.u_start[n]);
        let mut jump = du(p.node);
        for (m, &n) in link.shape.iter().zip(&link.master_nodes) {
            jump = crate::mesh::vec3::sub(jump, crate::mesh::vec3::scale(*m, du(n)));
        }
        let tangent = link.tangents[0];
        let slip_locked = std::iter::once(p.node)
            .chain(link.master_nodes.iter().copied())
            .all(|n| (0..self.def.dim).all(|c| tangent[c] == 0.0 || !free(n, c)));
        PointInput {
            slip_locked,
            threshold_frozen: self.friction_fixed_point(),
            omega: p.omega,
            rho_n: z.coef_cont,
            rho_t: z.coef_frot,
            mu: z.mu,
            status: self.status[i],
            lambda: self.lam[i * self.stride],
            lambda_s: self.lam_s[i],
            lambda_t: if self.stride == 2 {
                self.lam[i * self.stride + 1]
            } else {
                0.0
            },
            d: -self.gap(link, u),
            g_t: crate::mesh::vec3::dot(tangent, jump),
            normal: link.normal,
            tangent,
        }
    }

    /// The contact state (CONT_NOEU) at `u` with the current statuses and
    /// multipliers; `forces` receives the nodal residual when given.
    fn state(&self, u: &[[f64; 3]], mut forces: Option<&mut Vec<[f64; 3]>>) -> ContactState {
        let links = self.links();
        let mut st = ContactState {
            dim: self.def.dim,
            links: Vec::new(),
            unpaired: self.pairing.unpaired.clone(),
        };
        for (i, l) in links.iter().enumerate() {
            let Some(l) = l else { continue };
            let link = &self.pairing.links[*l];
            let inp = self.input(i, link, u, &|n, c| self.free[n * self.ndpn + c]);
            let (_, o) = evaluate_point(&inp);
            let p = self.points[i];
            if self.def.dim == 3 {
                st.links.push(self.link_state3(i, link, u));
                continue;
            }
            if let Some(fs) = forces.as_deref_mut() {
                fs[p.node] = crate::mesh::vec3::add(fs[p.node], o.f);
                for (m, &n) in link.shape.iter().zip(&link.master_nodes) {
                    fs[n] = crate::mesh::vec3::sub(fs[n], crate::mesh::vec3::scale(*m, o.f));
                }
            }
            let in_contact = self.status[i];
            let status = if !in_contact {
                LinkStatus::Open
            } else if inp.mu.is_none() || inp.lambda_t.abs() >= 0.999 {
                LinkStatus::Slip
            } else {
                LinkStatus::Stick
            };
            // The normal force on the slave node is −f_n = ω(ρ_n d − λ) n_out
            // (n_out = −n): λ_n = f_n·n ≥ 0 in contact, the discrete
            // method's convention (RN* = λ_n n_out).
            let lambda_n = crate::mesh::vec3::dot(o.f_n, link.normal);
            st.links.push(LinkState {
                zone: p.zone,
                slave: p.node,
                status,
                gap: -inp.d,
                lambda_n,
                normal: link.normal,
                tangents: link.tangents,
                ntangents: link.ntangents,
                frictional: inp.mu.is_some(),
                slip: [inp.g_t, 0.0],
                friction: [o.f_t, 0.0],
                proj: link.proj,
                percussion: [0.0; 4],
            });
        }
        st
    }

    /// The input of 3D point i (two tangents, `LAGS_F1`, `LAGS_F2`).
    fn input3(&self, i: usize, link: &Link, u: &[[f64; 3]]) -> PointInput3 {
        use crate::mesh::vec3::{dot, scale, sub};
        let p = self.points[i];
        let z = &self.cdef.zones[p.zone];
        let du = |n: usize| sub(u[n], self.u_start[n]);
        let mut jump = du(p.node);
        for (m, &n) in link.shape.iter().zip(&link.master_nodes) {
            jump = sub(jump, scale(*m, du(n)));
        }
        let t = tangents_from_normal(link.normal);
        let free = |n: usize, c: usize| self.free[n * self.ndpn + c];
        // Per tangent: the slip along τ_k moves imposed dofs only.
        let locked = |k: usize| {
            std::iter::once(p.node)
                .chain(link.master_nodes.iter().copied())
                .all(|n| (0..3).all(|c| t[k][c] == 0.0 || !free(n, c)))
        };
        let slip_locked = [locked(0), locked(1)];
        let x = i * self.stride;
        PointInput3 {
            omega: p.omega,
            rho_n: z.coef_cont,
            rho_t: z.coef_frot,
            mu: z.mu,
            status: self.status[i],
            lambda: self.lam[x],
            lambda_s: self.lam_s[i],
            threshold_frozen: self.friction_fixed_point(),
            lambda_t: if self.stride == 3 {
                [self.lam[x + 1], self.lam[x + 2]]
            } else {
                [0.0; 2]
            },
            d: -self.gap(link, u),
            g_t: [dot(t[0], jump), dot(t[1], jump)],
            normal: link.normal,
            tangents: t,
            slip_locked,
        }
    }

    /// Adds 3D point i's forces and tangent: the slave node with
    /// coefficient 1, the master nodes with −M_j, on the jump's blocks.
    #[allow(clippy::too_many_arguments)]
    fn assemble3(
        &self,
        i: usize,
        link: &Link,
        o: &PointOutput3,
        residual: &mut [f64],
        force: &mut [f64],
        matrix: Option<&mut crate::solver::SparseMatrix>,
        nb: &DofNumbering,
    ) {
        let p = self.points[i];
        let ndpn = self.ndpn;
        let xc = self.neq + i * self.stride;
        let nodes = point_nodes(p.node, link);
        for &(n, ca) in &nodes {
            for c in 0..3 {
                residual[n * ndpn + c] += ca * o.f[c];
                force[n * ndpn + c] += ca * o.f[c];
            }
        }
        let nf = self.stride - 1;
        let Some(m) = matrix else { return };
        let eq = |n: usize, c: usize| {
            let e = nb.eq[n * ndpn + c];
            (e != NONE).then_some(e)
        };
        for &(na, ca) in &nodes {
            for c in 0..3 {
                let Some(ea) = eq(na, c) else { continue };
                for &(nb_, cb) in &nodes {
                    for e in 0..3 {
                        let Some(eb) = eq(nb_, e) else { continue };
                        let v = ca * cb * o.df_du[c][e];
                        if v != 0.0 {
                            m.add(ea, eb, v);
                        }
                    }
                }
                m.add(ea, xc, ca * o.df_dc[c]);
                m.add(xc, ea, ca * o.dc_du[c]);
                for k in 0..nf {
                    m.add(ea, xc + 1 + k, ca * o.df_df[c][k]);
                    m.add(xc + 1 + k, ea, ca * o.dfr_du[k][c]);
                }
            }
        }
        m.add(xc, xc, o.dc_dc);
        for k in 0..nf {
            for l in 0..nf {
                m.add(xc + 1 + k, xc + 1 + l, o.dfr_df[k][l]);
            }
        }
    }

    /// The CONT_NOEU state of 3D point i: slip and friction force along
    /// τ1 and τ2; sliding when |Λ| ≥ 0.999 (code_aster's `CONT` = 2).
    fn link_state3(&self, i: usize, link: &Link, u: &[[f64; 3]]) -> LinkState {
        let inp = self.input3(i, link, u);
        let (_, o) = evaluate_point3(&inp);
        let lt = inp.lambda_t;
        let status = if !self.status[i] {
            LinkStatus::Open
        } else if inp.mu.is_none() || (lt[0] * lt[0] + lt[1] * lt[1]).sqrt() >= 0.999 {
            LinkStatus::Slip
        } else {
            LinkStatus::Stick
        };
        LinkState {
            zone: self.points[i].zone,
            slave: self.points[i].node,
            status,
            gap: -inp.d,
            lambda_n: crate::mesh::vec3::dot(o.f_n, link.normal),
            normal: link.normal,
            tangents: inp.tangents,
            ntangents: link.ntangents,
            frictional: inp.mu.is_some(),
            slip: inp.g_t,
            friction: o.f_t,
            proj: link.proj,
            percussion: [0.0; 4],
        }
    }

    /// Before the iterations of a step from `u_start` (full).
    pub fn begin_step(&mut self, u_start: &[f64]) {
        self.u_start = per_node(self.ndpn, u_start);
        self.lam.iter_mut().for_each(|v| *v = 0.0);
        self.status.clone_from(&self.committed_status);
        self.lam_s.clone_from(&self.committed_lam_s);
        self.first = true;
        self.changed = false;
        self.last_dlam = 0.0;
        self.fixed_point_loops = 0;
        self.fixed_point_changed = false;
        self.friction_loops = 0;
        self.friction_ref.iter_mut().for_each(|v| *v = 0.0);
        self.cycling.begin_step();
        self.eval_lam.iter_mut().for_each(|v| *v = None);
        let u = self.u_start.clone();
        self.repair(&u);
    }

    pub fn pattern_entries(&self) -> &[(usize, usize)] {
        &self.entries
    }

    /// The residual of the multiplier equations of the last evaluation.
    pub fn extra_residual(&self) -> &[f64] {
        &self.residual
    }

    /// Adds the contact forces and tangent at the current iterate.
    pub fn add(&mut self, it: ContactIteration) -> Result<(), String> {
        let nb = it.numbering;
        if nb.neq() != self.neq {
            return Err("the numbering changed under the continuous contact".into());
        }
        let u = per_node(self.ndpn, it.u);
        if !self.first && self.cdef.algo_reso_geom == Resolution::Newton {
            self.repair(&u);
        }
        // A status changed by the contact fixed point is a change of this
        // iteration: at least one solve with it before convergence.
        self.changed = std::mem::take(&mut self.fixed_point_changed);
        if !self.first && self.cdef.algo_reso_cont == Resolution::Newton {
            self.changed |= self.update_statuses(&u, Some(it.iteration))?;
        }
        self.first = false;
        let mut extra = std::mem::take(&mut self.residual);
        self.assemble(nb, &u, it.residual, it.force, &mut extra, it.matrix);
        self.residual = extra;
        self.trial = self.state(&u, None);
        Ok(())
    }

    /// Its part of the prediction of a step whose imposed values move
    /// (code_aster's prediction solves for the multipliers with the
    /// displacements, note §7.2): the tangent at the step's start (its
    /// statuses, λ = 0: called after [`Self::begin_step`]) into `matrix`,
    /// and −(r(u_start + du) − r(u_start)) into `rhs`, the change of the
    /// residual of every equation, free displacements then multipliers,
    /// under the imposed increment `du` (full) at that frozen state and
    /// pairing: its linear part, exactly so for the normal terms. A slave
    /// or master node moved by a DDL_IMPO thus enters the prediction
    /// through its gap, and a structure held by the contact alone is not
    /// singular there.
    pub fn imposed_increment(
        &self,
        nb: &DofNumbering,
        u_start: &[f64],
        du: &[f64],
        matrix: &mut crate::solver::SparseMatrix,
        rhs: &mut [f64],
    ) {
        let nfull = u_start.len();
        let nx = self.lam.len();
        let moved: Vec<f64> = u_start.iter().zip(du).map(|(a, b)| a + b).collect();
        let (mut r0, mut r1, mut f) = (vec![0.0; nfull], vec![0.0; nfull], vec![0.0; nfull]);
        let (mut x0, mut x1) = (vec![0.0; nx], vec![0.0; nx]);
        let u0 = per_node(self.ndpn, u_start);
        self.assemble(nb, &u0, &mut r0, &mut f, &mut x0, Some(matrix));
        let u1 = per_node(self.ndpn, &moved);
        self.assemble(nb, &u1, &mut r1, &mut f, &mut x1, None);
        for (e, &df) in nb.free.iter().enumerate() {
            rhs[e] -= r1[df] - r0[df];
        }
        for k in 0..nx {
            rhs[self.neq + k] -= x1[k] - x0[k];
        }
    }

    /// The contact residual at `u` (per node) with the current statuses,
    /// multipliers and pairing: the nodal forces are added to `residual`
    /// and `force` (full), the multiplier equations' residual written to
    /// `extra`, and the tangent added to `matrix` when given. Changes
    /// nothing in the term.
    fn assemble(
        &self,
        nb: &DofNumbering,
        u: &[[f64; 3]],
        residual: &mut [f64],
        force: &mut [f64],
        extra: &mut [f64],
        mut matrix: Option<&mut crate::solver::SparseMatrix>,
    ) {
        let links = self.links();
        let ndpn = self.ndpn;
        let dim = self.def.dim;
        let eq = |n: usize, c: usize| {
            let e = nb.eq[n * ndpn + c];
            (e != NONE).then_some(e)
        };
        for (i, l) in links.iter().enumerate() {
            let p = self.points[i];
            let xc = self.neq + i * self.stride;
            let xf = xc + 1;
            let Some(l) = l else {
                // Unpaired: the point is excluded, λ and Λ driven to 0.
                let z = &self.cdef.zones[p.zone];
                extra[i * self.stride] = -p.omega / z.coef_cont * self.lam[i * self.stride];
                if let Some(m) = matrix.as_deref_mut() {
                    m.add(xc, xc, -p.omega / z.coef_cont);
                }
                for k in 1..self.stride {
                    extra[i * self.stride + k] = p.omega * self.lam[i * self.stride + k];
                    if let Some(m) = matrix.as_deref_mut() {
                        m.add(xc + k, xc + k, p.omega);
                    }
                }
                continue;
            };
            let link = &self.pairing.links[*l];
            if dim == 3 {
                let inp = self.input3(i, link, u);
                let (_, o) = evaluate_point3(&inp);
                self.assemble3(i, link, &o, residual, force, matrix.as_deref_mut(), nb);
                extra[i * self.stride] = o.r_c;
                for k in 1..self.stride {
                    extra[i * self.stride + k] = o.r_f[k - 1];
                }
                continue;
            }
            let inp = self.input(i, link, u, &|n, c| self.free[n * self.ndpn + c]);
            let (_, o) = evaluate_point(&inp);
            let nodes = point_nodes(p.node, link);
            for &(n, ca) in &nodes {
                for c in 0..dim {
                    let f = n * ndpn + c;
                    residual[f] += ca * o.f[c];
                    force[f] += ca * o.f[c];
                }
            }
            extra[i * self.stride] = o.r_c;
            if self.stride == 2 {
                extra[i * self.stride + 1] = o.r_f;
            }
            let Some(m) = matrix.as_deref_mut() else {
                continue;
            };
            for &(na, ca) in &nodes {
                for c in 0..dim {
                    let Some(ea) = eq(na, c) else { continue };
                    for &(nb_, cb) in &nodes {
                        for e in 0..dim {
                            let Some(eb) = eq(nb_, e) else { continue };
                            let v = ca * cb * o.df_du[c][e];
                            if v != 0.0 {
                                m.add(ea, eb, v);
                            }
                        }
                    }
                    m.add(ea, xc, ca * o.df_dc[c]);
                    m.add(xc, ea, ca * o.dc_du[c]);
                    if self.stride == 2 {
                        m.add(ea, xf, ca * o.df_df[c]);
                        m.add(xf, ea, ca * o.df_du_f[c]);
                    }
                }
            }
            m.add(xc, xc, o.dc_dc);
            if self.stride == 2 {
                m.add(xc, xf, o.dc_df);
                m.add(xf, xc, o.dfr_dc);
                m.add(xf, xf, o.dfr_df);
            }
        }
    }

    /// Applies the solved correction of the multipliers.
    pub fn apply_extra(&mut self, dx: &[f64]) {
        let mut m: f64 = 0.0;
        for (i, (l, d)) in self.lam.iter_mut().zip(dx).enumerate() {
            *l += d;
            if i % self.stride == 0 {
                m = m.max(d.abs());
            }
        }
        self.last_dlam = m;
    }

    /// RESI_FROT's quantity: the last change of LAGS_C, relative to the
    /// largest |LAGS_C| when that exceeds 1 (`mmmcrf`).
    pub fn resi_frot(&self) -> f64 {
        let lmax = self
            .lam
            .iter()
            .step_by(self.stride)
            .fold(0.0f64, |a, v| a.max(v.abs()));
        if lmax > 1.0 {
            self.last_dlam / lmax
        } else {
            self.last_dlam
        }
    }

    /// No status changed at the last evaluation and RESI_FROT holds (with
    /// Newton friction: with the friction fixed point RESI_FROT is the
    /// criterion of its outer loop, `mmconv` computes none in Newton).
    pub fn settled(&self) -> bool {
        !self.changed && (self.friction_fixed_point() || self.resi_frot() <= self.cdef.resi_frot)
    }

    /// `ALGO_RESO_FROT='POINT_FIXE'` with friction: the threshold λ_s is
    /// frozen during the Newton iterations and updated by an outer loop.
    fn friction_fixed_point(&self) -> bool {
        self.stride >= 2 && self.cdef.algo_reso_frot == Resolution::PointFixe
    }

    /// One update of the friction fixed point after Newton converged
    /// (`nmctcf`): λ_s := λ (`mmreas`), then the criterion of `mmmcri_frot`,
    /// max |λ − λ_ref| / max |λ| over the LAGS_C of the points (0 when
    /// every λ is 0), λ_ref being λ at the previous update (0 at the
    /// first). Converged when it is below RESI_FROT; otherwise λ_ref := λ
    /// and the Newton iterations go on with the new threshold, unless
    /// this was update ITER_FROT_MAXI (the step fails, `ERRE_CTCF`).
    fn friction_update(&mut self) -> Result<bool, String> {
        self.friction_loops += 1;
        let (mut dmax, mut lmax, mut at) = (0.0f64, 0.0f64, None);
        for i in 0..self.points.len() {
            let l = self.lam[i * self.stride];
            let d = (l - self.friction_ref[i]).abs();
            if d > dmax {
                dmax = d;
                at = Some(i);
            }
            lmax = lmax.max(l.abs());
            self.lam_s[i] = l;
        }
        let crit = if lmax > 0.0 { dmax / lmax } else { 0.0 };
        if crit < self.cdef.resi_frot {
            return Ok(true);
        }
        if self.friction_loops >= self.cdef.iter_frot_maxi {
            let node = at.map_or(String::new(), |i| {
                format!(" at node N{}", self.points[i].node + 1)
            });
            return Err(format!(
                "the friction fixed point (ALGO_RESO_FROT='POINT_FIXE') did not converge in ITER_FROT_MAXI = {} threshold updates: LAGS_C still changed by {crit:.3e} of its largest value{node} (RESI_FROT = {:e})",
                self.friction_loops, self.cdef.resi_frot
            ));
        }
        for i in 0..self.points.len() {
            self.friction_ref[i] = self.lam[i * self.stride];
        }
        Ok(false)
    }

    /// The statuses from the current λ and gaps (`mmstac`) at `u`; λ_s :=
    /// λ with Newton friction (the friction fixed point freezes it).
    /// Returns whether a change blocks convergence. `iteration`: the
    /// Newton iteration of an evaluation inside Newton, None for the
    /// contact fixed point's. With `ADAPTATION='CYCLAGE'` the cycling
    /// detectors see every evaluation, a flip-flop's change does not block
    /// convergence once the pressures have settled, and a point still
    /// cycling after iteration 9 fails the step (module `cycling`).
    fn update_statuses(
        &mut self,
        u: &[[f64; 3]],
        iteration: Option<usize>,
    ) -> Result<bool, String> {
        let links = self.links();
        let np = self.points.len();
        let mut new = vec![false; np];
        for (i, l) in links.iter().enumerate() {
            let z = &self.cdef.zones[self.points[i].zone];
            let lam = self.lam[i * self.stride];
            new[i] = match l {
                Some(l) => contact_status(lam, -self.gap(&self.pairing.links[*l], u), z.coef_cont),
                None => false,
            };
        }
        // The pressures have settled (`resi_pressure` < 1e-4
        // `cont_pressure`): the largest change of λ since the last
        // evaluation over the points in contact at both, against the mean
        // |λ| of the points in contact.
        let (mut resi, mut sum) = (0.0f64, 0.0f64);
        for i in 0..np {
            let lam = self.lam[i * self.stride];
            if new[i] {
                sum += lam;
                if self.status[i] {
                    if let Some(prev) = self.eval_lam[i] {
                        resi = resi.max((lam - prev).abs());
                    }
                }
            }
        }
        let settled_pressure = resi < 1e-4 * sum.abs() / np.max(1) as f64;
        let mut changed = false;
        for (i, l) in links.iter().enumerate() {
            let p = self.points[i];
            let lam = self.lam[i * self.stride];
            let s = new[i];
            let mut counts = s != self.status[i];
            if self.cdef.zones[p.zone].cyclage {
                // The friction phase the point would have with its new
                // status, and its slip direction (r/|r| in the tangent basis).
                let (mut stick, mut slip_dir) = (None, [0.0; 2]);
                if let (true, Some(l)) = (s, l) {
                    let link = &self.pairing.links[*l];
                    let (ph, r) = if self.def.dim == 3 {
                        let mut inp = self.input3(i, link, u);
                        inp.status = true;
                        let r = [
                            inp.lambda_t[0] + inp.rho_t * inp.g_t[0],
                            inp.lambda_t[1] + inp.rho_t * inp.g_t[1],
                        ];
                        (phase3(&inp), r)
                    } else {
                        let mut inp = self.input(i, link, u, &|n, c| self.free[n * self.ndpn + c]);
                        inp.status = true;
                        (phase(&inp), [inp.lambda_t + inp.rho_t * inp.g_t, 0.0])
                    };
                    match ph {
                        Phase::Adhe => stick = Some(true),
                        Phase::Glis => {
                            stick = Some(false);
                            let n = (r[0] * r[0] + r[1] * r[1]).sqrt();
                            slip_dir = [r[0] / n, r[1] / n];
                        }
                        _ => {}
                    }
                }
                let hit = self.cycling.observe(
                    i,
                    self.status[i],
                    Observation {
                        status: s,
                        stick,
                        slip_dir,
                        lambda: lam,
                    },
                );
                let cycled = self.cycling.found(i)[0] > 0;
                let flip_flop_treated = match iteration {
                    None => hit[3],
                    Some(k) => k >= 3 && hit[3] && cycled,
                };
                if counts && flip_flop_treated && settled_pressure {
                    counts = false;
                }
                if let Some(k) = iteration {
                    if counts && cycled && k > CYCLING_ITERATIONS {
                        return Err(format!(
                            "contact cycling (ADAPTATION='CYCLAGE'): the contact status of slave node N{} still changes at Newton iteration {k} (cycles detected in this step: {}); code_aster would switch this point to a penalised contact for the rest of the step, which is not reproduced: the step fails (the ERREUR rule of DEFI_LIST_INST may cut it)",
                            p.node + 1,
                            Cycling::summary(self.cycling.found(i))
                        ));
                    }
                }
            }
            changed |= counts;
            self.status[i] = s;
            self.eval_lam[i] = Some(lam);
            if !self.friction_fixed_point() {
                self.lam_s[i] = lam;
            }
        }
        Ok(changed)
    }

    /// After Newton converged at `u`. The contact fixed point
    /// (`ALGO_RESO_CONT='POINT_FIXE'`): the statuses, frozen during the
    /// Newton iterations, are evaluated at the converged state; if one
    /// changed, the iterations go on with the new ones (same
    /// ITER_GLOB_MAXI counter). Then the geometric fixed point
    /// (`ALGO_RESO_GEOM='POINT_FIXE'`) re-pairs until the projections stop
    /// moving.
    pub fn accept(&mut self, u: &[f64]) -> Result<bool, String> {
        let un = per_node(self.ndpn, u);
        if self.cdef.algo_reso_cont == Resolution::PointFixe {
            if self.cdef.algo_reso_geom == Resolution::Newton {
                self.repair(&un);
            }
            self.fixed_point_loops += 1;
            if self.update_statuses(&un, None)? {
                if self.fixed_point_loops >= self.cdef.iter_cont_maxi {
                    return Err(format!(
                        "the contact fixed point (ALGO_RESO_CONT='POINT_FIXE') changed statuses at each of its {} evaluations (ITER_CONT_MAXI)",
                        self.fixed_point_loops
                    ));
                }
                self.fixed_point_changed = true;
                return Ok(false);
            }
        }
        // The loops are nested as code_aster's (`nmible`, `nmtble`):
        // contact inside friction inside geometry; an outer update restarts
        // the inner counters.
        if self.friction_fixed_point() && !self.friction_update()? {
            self.fixed_point_loops = 0;
            // At least one solve with the new threshold before convergence.
            self.fixed_point_changed = true;
            return Ok(false);
        }
        if self.cdef.algo_reso_geom == Resolution::Newton {
            return Ok(true);
        }
        self.repair(&un);
        let converged = self.geom_move <= self.cdef.resi_geom;
        if !converged {
            self.fixed_point_loops = 0;
            self.friction_loops = 0;
        }
        Ok(converged)
    }

    /// Accepts the trial state of a converged step of length `dt`: the
    /// percussion accumulates over the steps, each slave node adding R·dt
    /// once per slave cell holding it, as code_aster's `mmmres`
    /// (`ContactState::accumulate_percussion`).
    pub fn commit(&mut self, dt: f64) {
        let mut st = self.trial.clone();
        let visits = &self.visits;
        st.accumulate_percussion(Some(&self.committed), dt, |z, n| {
            visits.get(&(z, n)).copied().unwrap_or(1)
        });
        self.committed = st;
        self.committed_lam.clone_from(&self.lam);
        self.committed_status.clone_from(&self.status);
        self.committed_lam_s.clone_from(&self.lam_s);
    }

    /// Adds `LAGS_C` (and `LAGS_F1`) of the committed step to a DEPL
    /// field, on the slave nodes (absent elsewhere).
    pub fn extend_depl(&self, depl: &mut NodalField) {
        let nnodes = depl.nnodes();
        let mut names = depl.components.clone();
        names.push("LAGS_C".into());
        if self.stride >= 2 {
            names.push("LAGS_F1".into());
        }
        if self.stride == 3 {
            names.push("LAGS_F2".into());
        }
        let mut f = NodalField::absent(names, nnodes);
        let old = depl.ncmp();
        for n in 0..nnodes {
            for c in 0..old {
                f.set(n, c, depl.values[n * old + c]);
            }
        }
        for (i, p) in self.points.iter().enumerate() {
            for k in 0..self.stride {
                f.set(p.node, old + k, self.committed_lam[i * self.stride + k]);
            }
        }
        *depl = f;
    }

    /// CONT_NOEU of the committed state.
    pub fn cont_noeu(&self) -> NodalField {
        self.committed.cont_noeu(self.mesh.nnodes())
    }
}
