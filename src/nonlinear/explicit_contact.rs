//! Contact in explicit dynamics, an aster extension: code_aster refuses
//! DEFI_CONTACT with DIFF_CENT/TCHAMWA (MECANONLINE5_22). Node-to-surface
//! contact of the slave nodes against a master surface, in the discrete
//! formulation's pairing (`contact::pair`, master/slave, inward normal n,
//! gap g = g_ref + n·(Σ N_j u_j − u_s) > 0 when open). The master is
//! either held fixed by DDL_IMPO on all its dofs (a rigid obstacle, as the
//! Taylor bar's foundation), or deformable with the penalty only.
//!
//! Two enforcements (notes/explicit.md §10):
//! - ALGO_CONT='PENALISATION': the force E_N⟨−g⟩ at u_{n+1} enters the
//!   right-hand side of a_{n+1}; friction is the elastic predictor and
//!   return to the Coulomb disc on the history of the tangential force
//!   (f_T ← f_T − E_T Δu_T, capped at μ f_N; LS-DYNA's penalty friction):
//!   in explicit a step is tiny, so the implicit discrete method's
//!   per-step E_T·slip would make friction a viscosity.
//! - ALGO_CONT='CONTRAINTE': kinematic, predictor-corrector (Taylor &
//!   Flanagan's PRONTO, the defence-node correction against a rigid
//!   master): after a_{n+1} is known, the next predicted position of each
//!   slave node is computed; a node predicted inside the master gets the
//!   acceleration correction δa that puts it exactly on the surface
//!   (n·δu = g̃), with the force m δa (momentum exchanged = impulse, no
//!   tension by construction); Coulomb friction then removes the
//!   predicted tangential motion up to μ|f_N| (a radial return in
//!   velocity). The node-by-node constraints are decoupled because the
//!   mass is lumped and the master immobile, so no iteration is needed.
//!
//! A deformable master (some master dof free): the penalty only. The force
//! f of a link acts on the slave node and −N_j f on each master node j
//! (N_j the master shape functions at the projection, as the implicit
//! discrete method distributes it), the friction force included, its slip
//! being the relative one. The contact forces are then internal: the
//! momentum of the bodies is conserved by them to round-off, TRAV_LIAI
//! (the trapezoid of the full force vector on Δu) is their work on both
//! sides, DISS_FROT the friction's on the relative slip. The kinematic
//! correction is refused there: with a moving master the links share
//! master nodes, and putting every slave node back on a surface that
//! moves with the correction is a coupled solve, not node by node.

use std::collections::HashMap;

use super::dofs::{DofNumbering, NONE};
use super::explicit::ExplicitConstraint;
use crate::contact::{pair, ContactDef, Pairing};
use crate::mesh::CellType;
use crate::mesh::Mesh;
use crate::time::Kinematics as Motion;

/// How the non-penetration is enforced.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Enforcement {
    /// ALGO_CONT='PENALISATION'.
    Penalty,
    /// ALGO_CONT='CONTRAINTE': kinematic correction.
    Kinematic,
}

/// The mid-side nodes of the slave cells that are free along a component
/// in which both vertices of their edge are imposed, as (node, component),
/// ascending. code_aster's ALGO_CONT='CONTRAINTE' ties the mid-side nodes
/// of QUAD8 slave cells to their vertices (u_mid = (u_v1 + u_v2)/2,
/// `cacoeq`), so a command file written for it leaves them out of its
/// DDL_IMPO (SDNV103 A's group MILIEU: SXX1 = SXX - MILIEU) to avoid a
/// double condition, and the tie keeps them on the plane. The kinematic
/// contact here ties nothing: such a node is free to leave the plane its
/// edge is held in, and the quarter of A is then not a symmetric quarter
/// (its edge radius off by up to a third, docs/performance.md, "The 3D
/// quarter against the axisymmetric bar"). Every quadratic slave cell is
/// looked at, not QUAD8 only: a free mid-side node on a symmetry plane is
/// wrong whichever cell carries it.
pub fn mid_nodes_free_on_a_held_edge(
    def: &ContactDef,
    mesh: &Mesh,
    numbering: &DofNumbering,
) -> Vec<(usize, usize)> {
    let nd = numbering.ndpn;
    let dim = def.dim.min(nd);
    let held = |n: usize, k: usize| numbering.eq[n * nd + k] == NONE;
    let mut out = Vec::new();
    for z in &def.zones {
        let Some(cells) = mesh.cell_groups.get(&z.slave_group) else {
            continue;
        };
        for &c in cells {
            let cell = &mesh.cells[c];
            let kind: CellType = cell.kind;
            let nv = kind.nvertices();
            for (j, &(a, b)) in kind.mid_edges().iter().enumerate() {
                let m = cell.nodes[nv + j];
                if z.slave_nodes.binary_search(&m).is_err() {
                    continue;
                }
                let (va, vb) = (cell.nodes[a], cell.nodes[b]);
                for k in 0..dim {
                    if held(va, k) && held(vb, k) && !held(m, k) {
                        out.push((m, k));
                    }
                }
            }
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

pub struct ExplicitContact {
    pub def: ContactDef,
    pub enforcement: Enforcement,
    mesh: Mesh,
    ndpn: usize,
    dim: usize,
    pairing: Pairing,
    /// Tangential force on the slave node of each (zone, slave) link at
    /// the last state, and at the state before.
    ft: HashMap<(usize, usize), [f64; 3]>,
    ft_prev: HashMap<(usize, usize), [f64; 3]>,
    /// Contact forces of the last state on the F_int side (the opposite of
    /// the force on the nodes), full vector.
    pub force_on_fint_side: Vec<f64>,
    /// The same of the last committed state (a failed step overwrites the
    /// one above before the archive of the state it started from).
    force_prev: Vec<f64>,
    /// Sum of the contact forces on the slave nodes of the last state and
    /// of the state before.
    body_force: [f64; 3],
    body_force_prev: [f64; 3],
    /// Full displacement of the last committed state.
    u_prev: Vec<f64>,
    /// Each node's displacement as `pair` reads it (reused).
    node_u: Vec<[f64; 3]>,
    /// Impulse of the contact reactions on the bodies since the start.
    pub impulse: [f64; 3],
    /// Work dissipated by friction since the start.
    pub friction_dissipation: f64,
    /// Largest penetration seen at an evaluated state (penalty).
    pub max_penetration: f64,
    /// Largest number of links in contact at a state.
    pub max_active: usize,
    active: usize,
    pub pairings: usize,
    /// Some master node has a free dof (penalty only).
    deformable: bool,
    /// Per zone: the largest inverse lumped mass over the free master dofs
    /// (0 for a held master) times the largest Σ N_j² of its master cells,
    /// the master side of the stable step's penalty term.
    master_inv_mass: Vec<f64>,
    /// The master nodes and shape functions of each frictional link of
    /// the last state and of the state before (deformable master only):
    /// the master side of the friction work.
    ft_master: HashMap<(usize, usize), (Vec<usize>, Vec<f64>)>,
    ft_master_prev: HashMap<(usize, usize), (Vec<usize>, Vec<f64>)>,
}

/// The supremum of Σ N_j² over the reference cell of a master surface:
/// 1 for the linear cells (N_j ≥ 0 with Σ N_j = 1) and for SEG3 and TRIA6
/// (reached at the vertices), 1.25 for QUAD8 (at the centre, where the
/// corner functions are −1/4 and the mid-side ones 1/2). The unit test
/// below samples each cell against these values.
fn shape_square_sum_bound(kind: CellType) -> f64 {
    match kind {
        CellType::Quad8 => 1.25,
        _ => 1.0,
    }
}

impl ExplicitContact {
    /// A master with a free dof is deformable: the penalty handles it, the
    /// kinematic correction does not (see the module doc). `mass` is the
    /// lumped mass of each full dof (for the master side of the stable
    /// step); a held master node, or a zero mass, adds nothing there.
    pub fn new(
        def: ContactDef,
        enforcement: Enforcement,
        mesh: &Mesh,
        numbering: &DofNumbering,
        mass: &[f64],
        u0: &[f64],
    ) -> Result<ExplicitContact, String> {
        let ndpn = numbering.ndpn;
        let mut deformable = false;
        let mut master_inv_mass = Vec::with_capacity(def.zones.len());
        for z in &def.zones {
            let mut inv: f64 = 0.0;
            let mut kappa: f64 = 0.0;
            for &c in &z.master_cells {
                kappa = kappa.max(shape_square_sum_bound(mesh.cells[c].kind));
                for &n in &mesh.cells[c].nodes {
                    for k in 0..ndpn {
                        let f = n * ndpn + k;
                        if numbering.eq[f] == NONE {
                            continue;
                        }
                        if enforcement == Enforcement::Kinematic {
                            return Err(format!(
                                "not implemented yet: explicit contact with ALGO_CONT='CONTRAINTE' against a deformable master surface: node N{} of the master group {} has free dofs (the kinematic correction against a moving master is a coupled solve); use ALGO_CONT='PENALISATION', or hold the master by DDL_IMPO on all its dofs (a rigid obstacle)",
                                n + 1,
                                z.master_group
                            ));
                        }
                        deformable = true;
                        if mass.get(f).is_some_and(|&m| m > 0.0) {
                            inv = inv.max(1.0 / mass[f]);
                        }
                    }
                }
            }
            master_inv_mass.push(kappa * inv);
        }
        let nfull = numbering.nfull();
        Ok(ExplicitContact {
            dim: def.dim.min(ndpn),
            def,
            enforcement,
            mesh: mesh.clone(),
            ndpn,
            pairing: Pairing::default(),
            ft: HashMap::new(),
            ft_prev: HashMap::new(),
            force_on_fint_side: vec![0.0; nfull],
            force_prev: vec![0.0; nfull],
            body_force: [0.0; 3],
            body_force_prev: [0.0; 3],
            u_prev: u0.to_vec(),
            node_u: Vec::new(),
            impulse: [0.0; 3],
            friction_dissipation: 0.0,
            max_penetration: 0.0,
            max_active: 0,
            active: 0,
            pairings: 0,
            deformable,
            master_inv_mass,
            ft_master: HashMap::new(),
            ft_master_prev: HashMap::new(),
        })
    }

    /// Some master node has a free dof.
    pub fn deformable(&self) -> bool {
        self.deformable
    }

    pub fn kinematic(&self) -> bool {
        self.enforcement == Enforcement::Kinematic
    }

    /// Pairs the slave nodes on the geometry of `u` (full).
    pub fn pair(&mut self, numbering: &DofNumbering, u: &[f64]) {
        let nd = numbering.ndpn;
        // The nodes' displacements in a buffer kept across the steps.
        let mut un = std::mem::take(&mut self.node_u);
        un.clear();
        un.extend(u.chunks(nd).map(|c| {
            let mut v = [0.0; 3];
            v[..nd].copy_from_slice(c);
            v
        }));
        self.pairing = pair(&self.def, &self.mesh, &un);
        self.node_u = un;
        self.pairings += 1;
        crate::profile::count(crate::profile::Counter::Pairings, 1);
    }

    /// The paired slave nodes that penetrate their master at the state `u`
    /// (the last pairing's links): how many, and the deepest penetration.
    pub fn penetrations(&self, u: &[f64]) -> (usize, f64) {
        crate::contact::penetrations(&self.pairing, |n| self.node_u(u, n))
    }

    /// The largest ω² of the penalty springs (0 for the kinematic
    /// enforcement): what the contact adds to ω². Against a held master a
    /// slave node's spring is k/m_s. Against a deformable master a link is
    /// a spring between the slave node and the point Σ N_j u_j: its ω² is
    /// the two-body k (1/m_s + Σ N_j²/m_j), bounded before any pairing by
    /// k/m_s + k κ max_j 1/m_j (κ = sup Σ N_j² of the zone's master cells,
    /// max_j over its free master dofs), whichever slave node and master
    /// point the pairing brings together. It is the bound of one link in
    /// isolation, as the rigid case's: a master node pressed by several
    /// slave nodes at once (a slave mesh finer than the master's) carries
    /// their springs together, up to that many times stiffer. The master
    /// term is added only when the master is deformable, so that the
    /// held-master estimate is the same number as before, to the bit.
    pub fn penalty_omega2(&self, mass: &[f64]) -> f64 {
        if self.kinematic() {
            return 0.0;
        }
        let mut w2: f64 = 0.0;
        for (z, s) in self.def.slave_nodes() {
            let zone = &self.def.zones[z];
            let k = zone.e_n.max(zone.friction.map_or(0.0, |f| f.e_t));
            let m = (0..self.ndpn)
                .map(|c| mass[s * self.ndpn + c])
                .fold(0.0, f64::max);
            if m > 0.0 {
                let master = self.master_inv_mass[z];
                w2 = w2.max(if master > 0.0 {
                    k / m + k * master
                } else {
                    k / m
                });
            }
        }
        w2
    }

    fn node_u(&self, u: &[f64], n: usize) -> [f64; 3] {
        let mut v = [0.0; 3];
        for (c, x) in v.iter_mut().enumerate().take(self.dim) {
            *x = u[n * self.ndpn + c];
        }
        v
    }

    /// The penalty forces at `u` (the step's end), the step starting at
    /// `u_n`: into [`ExplicitContact::force_on_fint_side`].
    pub fn penalty_forces(&mut self, _numbering: &DofNumbering, u_n: &[f64], u: &[f64]) {
        self.force_on_fint_side.iter_mut().for_each(|x| *x = 0.0);
        let mut ft_new = HashMap::new();
        let mut ft_master = HashMap::new();
        let mut body = [0.0; 3];
        let mut active = 0;
        let links = std::mem::take(&mut self.pairing.links);
        for l in &links {
            let zone = &self.def.zones[l.zone];
            let us = self.node_u(u, l.slave);
            let us_n = self.node_u(u_n, l.slave);
            let mut um = [0.0; 3];
            let mut dum = [0.0; 3];
            for (j, &mn) in l.master_nodes.iter().enumerate() {
                let (a, b) = (self.node_u(u, mn), self.node_u(u_n, mn));
                for c in 0..3 {
                    um[c] += l.shape[j] * a[c];
                    dum[c] += l.shape[j] * (a[c] - b[c]);
                }
            }
            let n = l.normal;
            let g = l.gap_ref + (0..3).map(|c| n[c] * (um[c] - us[c])).sum::<f64>();
            if g >= 0.0 {
                continue;
            }
            active += 1;
            self.max_penetration = self.max_penetration.max(-g);
            let fnorm = zone.e_n * (-g);
            let mut f = [0.0; 3];
            for c in 0..3 {
                f[c] = -fnorm * n[c];
            }
            if let Some(cf) = zone.friction {
                let mut d = [0.0; 3];
                for c in 0..3 {
                    d[c] = (us[c] - us_n[c]) - dum[c];
                }
                let dn: f64 = (0..3).map(|c| d[c] * n[c]).sum();
                let old = self.ft.get(&(l.zone, l.slave)).copied().unwrap_or([0.0; 3]);
                let on: f64 = (0..3).map(|c| old[c] * n[c]).sum();
                let mut tr = [0.0; 3];
                for c in 0..3 {
                    tr[c] = (old[c] - on * n[c]) - cf.e_t * (d[c] - dn * n[c]);
                }
                let norm = tr.iter().map(|x| x * x).sum::<f64>().sqrt();
                let cap = cf.mu * fnorm;
                if norm > cap && norm > 0.0 {
                    for x in tr.iter_mut() {
                        *x *= cap / norm;
                    }
                }
                for c in 0..3 {
                    f[c] += tr[c];
                }
                ft_new.insert((l.zone, l.slave), tr);
                if self.deformable {
                    ft_master.insert((l.zone, l.slave), (l.master_nodes.clone(), l.shape.clone()));
                }
            }
            for c in 0..self.dim {
                self.force_on_fint_side[l.slave * self.ndpn + c] -= f[c];
                body[c] += f[c];
                for (j, &mn) in l.master_nodes.iter().enumerate() {
                    self.force_on_fint_side[mn * self.ndpn + c] += l.shape[j] * f[c];
                }
            }
        }
        self.pairing.links = links;
        self.active = active;
        self.max_active = self.max_active.max(active);
        self.ft = ft_new;
        self.ft_master = ft_master;
        self.body_force = body;
    }

    /// The kinematic correction of the state `m` (its a, and v by
    /// `kappa`·δa) so that the next predicted positions u + dt v + c dt² a
    /// of the slave nodes do not penetrate, with Coulomb friction;
    /// `mass` the lumped mass of each full dof.
    pub fn kinematic_correction(
        &mut self,
        numbering: &DofNumbering,
        mass: &[f64],
        m: &mut Motion,
        dt: f64,
        kappa: f64,
        c: f64,
    ) {
        self.force_on_fint_side.iter_mut().for_each(|x| *x = 0.0);
        self.body_force = [0.0; 3];
        self.ft.clear();
        self.active = 0;
        if dt <= 0.0 {
            return;
        }
        let h = dt * kappa + c * dt * dt;
        let nd = self.ndpn;
        let dim = self.dim;
        let links = std::mem::take(&mut self.pairing.links);
        for l in &links {
            let s = l.slave;
            let free: [bool; 3] =
                std::array::from_fn(|k| k < dim && numbering.eq[s * nd + k] != NONE);
            let Some(first) = (0..dim).find(|&k| free[k]) else {
                continue;
            };
            let mass_s = mass[s * nd + first];
            if mass_s <= 0.0 {
                continue;
            }
            let mut pred = [0.0; 3];
            let mut now = [0.0; 3];
            for k in 0..dim {
                let f = s * nd + k;
                now[k] = m.u[f];
                pred[k] = if free[k] {
                    m.u[f] + dt * m.v[f] + c * dt * dt * m.a[f]
                } else {
                    m.u[f]
                };
            }
            let mut um = [0.0; 3];
            for (j, &mn) in l.master_nodes.iter().enumerate() {
                let a = self.node_u(&m.u, mn);
                for k in 0..3 {
                    um[k] += l.shape[j] * a[k];
                }
            }
            let n = l.normal;
            let g = l.gap_ref + (0..3).map(|k| n[k] * (um[k] - pred[k])).sum::<f64>();
            if g >= 0.0 {
                continue;
            }
            let mut nf = [0.0; 3];
            for k in 0..dim {
                if free[k] {
                    nf[k] = n[k];
                }
            }
            let nn: f64 = nf.iter().map(|x| x * x).sum();
            if nn < 1e-12 {
                continue;
            }
            self.active += 1;
            let mut da = [0.0; 3];
            for k in 0..3 {
                da[k] = g * nf[k] / nn / h;
            }
            let fnorm = mass_s * da.iter().map(|x| x * x).sum::<f64>().sqrt();
            if let Some(cf) = self.def.zones[l.zone].friction {
                // Predicted tangential motion over the step once the
                // normal correction is applied.
                let mut w = [0.0; 3];
                for k in 0..dim {
                    w[k] = (pred[k] + h * da[k] - now[k]) / dt;
                }
                let wn: f64 = (0..3).map(|k| w[k] * n[k]).sum();
                let mut stop = [0.0; 3];
                for k in 0..dim {
                    if free[k] {
                        stop[k] = -(w[k] - wn * n[k]) * dt / h;
                    }
                }
                let need = mass_s * stop.iter().map(|x| x * x).sum::<f64>().sqrt();
                let cap = cf.mu * fnorm;
                let scale = if need > cap && need > 0.0 {
                    cap / need
                } else {
                    1.0
                };
                let mut ftv = [0.0; 3];
                for k in 0..3 {
                    da[k] += scale * stop[k];
                    ftv[k] = mass_s * scale * stop[k];
                }
                self.ft.insert((l.zone, s), ftv);
            }
            for k in 0..dim {
                if !free[k] {
                    continue;
                }
                let f = s * nd + k;
                m.a[f] += da[k];
                m.v[f] += kappa * da[k];
                let force = mass[f] * da[k];
                self.force_on_fint_side[f] -= force;
                self.body_force[k] += force;
            }
        }
        self.pairing.links = links;
        self.max_active = self.max_active.max(self.active);
    }

    /// The initial state's contact forces (its kinematic correction, or
    /// the penalty at u_0) become the start of the first step's trapezoid:
    /// without this the impulse and the friction dissipation of a run
    /// whose bodies touch at the initial state miss the first half step
    /// (measured: the impulse of tests/verification/explicit_oblique_impact
    /// was short of Σ M Δv by the contact layer's normal momentum).
    pub fn start(&mut self) {
        self.force_prev.copy_from_slice(&self.force_on_fint_side);
        self.body_force_prev = self.body_force;
        self.ft_prev = self.ft.clone();
        self.ft_master_prev = self.ft_master.clone();
    }

    /// After the step of length `dt` ending at the committed `u`: the
    /// impulse of the reactions (with the weight `w` of the step's end
    /// that the scheme's velocity update gives: the trapezoid for
    /// DIFF_CENT, the step's start for TCHAMWA, so that the impulse is the
    /// momentum exchanged) and the friction dissipation (the trapezoid of the
    /// friction forces on the step's slip, the rule of TRAV_LIAI, so that
    /// DISS_FROT is the tangential part of TRAV_LIAI for both enforcements;
    /// with the kinematic correction of the step's start alone, DISS_FROT
    /// of the oblique-impact block exceeded TRAV_LIAI by a third: the
    /// initial state's correction acts over half a step only). Against a
    /// deformable master the friction force f of a link also does the work
    /// −f·Σ N_j Δu_j on the master nodes (each state's force with its own
    /// link's N_j), so that DISS_FROT is the work on the relative slip.
    /// The impulse is that of the forces on the slave nodes: against a
    /// held master the momentum the bodies exchange with the obstacle;
    /// against a deformable one the momentum the slave side receives from
    /// the master side (which receives its opposite: the total is
    /// conserved).
    pub fn commit(&mut self, u: &[f64], dt: f64, w: f64) {
        for k in 0..3 {
            self.impulse[k] += dt * ((1.0 - w) * self.body_force_prev[k] + w * self.body_force[k]);
        }
        let nd = self.ndpn;
        let keys: std::collections::BTreeSet<(usize, usize)> =
            self.ft.keys().chain(self.ft_prev.keys()).copied().collect();
        for key in keys {
            let s = key.1;
            let old = self.ft_prev.get(&key).copied().unwrap_or([0.0; 3]);
            let new = self.ft.get(&key).copied().unwrap_or([0.0; 3]);
            for k in 0..self.dim {
                let d = u[s * nd + k] - self.u_prev[s * nd + k];
                let f = 0.5 * (old[k] + new[k]);
                self.friction_dissipation -= f * d;
            }
            if self.deformable {
                // The master side: −f · Σ N_j Δu_j for each state's force.
                for (force, links) in [(old, &self.ft_master_prev), (new, &self.ft_master)] {
                    let Some((nodes, shape)) = links.get(&key) else {
                        continue;
                    };
                    for (&mn, &nj) in nodes.iter().zip(shape) {
                        for k in 0..self.dim {
                            let d = u[mn * nd + k] - self.u_prev[mn * nd + k];
                            self.friction_dissipation += 0.5 * force[k] * nj * d;
                        }
                    }
                }
            }
        }
        self.ft_prev = self.ft.clone();
        self.ft_master_prev = self.ft_master.clone();
        self.body_force_prev = self.body_force;
        self.force_prev.copy_from_slice(&self.force_on_fint_side);
        self.u_prev.copy_from_slice(u);
    }

    /// The committed state's history (`ExplicitConstraint::history`).
    pub fn history(&self) -> crate::result::ContactHistory {
        let mut friction: Vec<_> = self.ft_prev.iter().map(|(&k, &f)| (k, f)).collect();
        friction.sort_unstable_by_key(|&(k, _)| k);
        let mut friction_master: Vec<_> = self
            .ft_master_prev
            .iter()
            .map(|(&k, (n, s))| (k, n.clone(), s.clone()))
            .collect();
        friction_master.sort_unstable_by_key(|x| x.0);
        crate::result::ContactHistory {
            ndpn: self.ndpn,
            force: sparse(&self.force_prev),
            body_force: self.body_force_prev,
            friction,
            friction_master,
        }
    }

    /// Takes an archived history at the initial state of a continuation
    /// (`ExplicitConstraint::restore`): its forces add to the current ones
    /// (zero, or a kinematic correction of that state), its friction
    /// forces become the links' history. Checked whole before anything is
    /// taken.
    pub fn restore(&mut self, h: &crate::result::ContactHistory) -> Result<(), String> {
        h.check_fits(self.ndpn, self.force_on_fint_side.len())?;
        let keys = h
            .friction
            .iter()
            .map(|x| x.0)
            .chain(h.friction_master.iter().map(|x| x.0));
        for (z, s) in keys {
            let fits = self
                .def
                .zones
                .get(z)
                .is_some_and(|zone| zone.slave_nodes.binary_search(&s).is_ok());
            if !fits {
                return Err(format!(
                    "its friction link of zone {} at node N{} is not a slave node of this contact's zone {}",
                    z + 1,
                    s + 1,
                    z + 1
                ));
            }
        }
        let nnodes = self.mesh.nnodes();
        if let Some(&n) = h
            .friction_master
            .iter()
            .flat_map(|x| &x.1)
            .find(|&&n| n >= nnodes)
        {
            return Err(format!(
                "its master node N{} is not a node of this mesh",
                n + 1
            ));
        }
        for &(f, v) in &h.force {
            self.force_on_fint_side[f] += v;
        }
        for k in 0..3 {
            self.body_force[k] += h.body_force[k];
        }
        for &(key, f) in &h.friction {
            let e = self.ft.entry(key).or_insert([0.0; 3]);
            for k in 0..3 {
                e[k] += f[k];
            }
        }
        for (key, nodes, shape) in &h.friction_master {
            self.ft_master.insert(*key, (nodes.clone(), shape.clone()));
        }
        Ok(())
    }

    /// `CONT_NOEU` of the committed state `u`, reached by a step of `dt`
    /// from `u_start`, an aster extension as the explicit contact itself,
    /// so that a study's post-processing (JEU, RN, R of POST_RELEVE_T,
    /// IMPR_RESU) runs unchanged on an explicit result. The components
    /// are the implicit discrete contact's (docs/contact.md §4, code_aster's
    /// `cfresu`), read from the last contact forces
    /// ([`ExplicitContact::force_on_fint_side`]: the penalty at `u`, or the
    /// kinematic correction of the state before the next step): JEU the
    /// gap at `u` for every paired slave node; λ_n = −f·n_in and the
    /// friction components −f·τ_k of the force f on the slave node; CONT 2
    /// (sliding, or frictionless) when the tangential force reaches μλ_n
    /// within 1e-9, else 1; GLIX/GLIY the slave's tangential displacement
    /// over the step, relative to the master point Σ N_j u_j when the
    /// master is deformable (a held master does not move). RN*, RT*, R*
    /// and IX.. are printed as code_aster prints them, minus the forces on
    /// the slave node (`LinkState::printed_normal`). The percussion I is
    /// R·dt of the last step, which is what code_aster's `cfresu` stores
    /// (as the implicit discrete formulation); steps are tiny here, so I
    /// is small.
    pub fn cont_noeu(&self, u: &[f64], u_start: &[f64], dt: f64) -> crate::result::NodalField {
        use crate::contact::{ContactState, LinkState, LinkStatus};
        let nd = self.ndpn;
        let mut state = ContactState {
            dim: self.def.dim,
            links: Vec::with_capacity(self.pairing.links.len()),
            unpaired: self.pairing.unpaired.clone(),
        };
        for l in &self.pairing.links {
            let s = l.slave;
            let us = self.node_u(u, s);
            let mut um = [0.0; 3];
            for (j, &mn) in l.master_nodes.iter().enumerate() {
                let a = self.node_u(u, mn);
                for k in 0..3 {
                    um[k] += l.shape[j] * a[k];
                }
            }
            let n = l.normal;
            let gap = l.gap_ref + (0..3).map(|k| n[k] * (um[k] - us[k])).sum::<f64>();
            // The force on the slave node.
            let mut f = [0.0; 3];
            for (k, x) in f.iter_mut().enumerate().take(self.dim) {
                *x = -self.force_on_fint_side[s * nd + k];
            }
            let dot = |a: &[f64; 3], b: &[f64; 3]| (0..3).map(|k| a[k] * b[k]).sum::<f64>();
            let lambda_n = -dot(&f, &n);
            let mut friction = [0.0; 2];
            for (k, t) in l.tangents.iter().enumerate().take(l.ntangents) {
                friction[k] = -dot(&f, t);
            }
            let mut slip = [0.0; 2];
            let mut d = {
                let (a, b) = (self.node_u(u, s), self.node_u(u_start, s));
                [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
            };
            if self.deformable {
                for (j, &mn) in l.master_nodes.iter().enumerate() {
                    let (a, b) = (self.node_u(u, mn), self.node_u(u_start, mn));
                    for k in 0..3 {
                        d[k] -= l.shape[j] * (a[k] - b[k]);
                    }
                }
            }
            for (k, t) in l.tangents.iter().enumerate().take(l.ntangents) {
                slip[k] = dot(&d, t);
            }
            let coulomb = self.def.zones[l.zone].friction;
            let status = if lambda_n > 0.0 {
                let ft = (friction[0] * friction[0] + friction[1] * friction[1]).sqrt();
                match coulomb {
                    Some(c) if ft < c.mu * lambda_n * (1.0 - 1e-9) => LinkStatus::Stick,
                    _ => LinkStatus::Slip,
                }
            } else {
                LinkStatus::Open
            };
            let mut link = LinkState {
                zone: l.zone,
                slave: s,
                status,
                gap,
                lambda_n: lambda_n.max(0.0),
                normal: n,
                tangents: l.tangents,
                ntangents: l.ntangents,
                frictional: coulomb.is_some(),
                slip,
                friction,
                proj: l.proj,
                percussion: [0.0; 4],
            };
            if status.in_contact() {
                let r = link.printed_reaction();
                let rn = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
                link.percussion = [rn * dt, r[0] * dt, r[1] * dt, r[2] * dt];
            } else {
                link.friction = [0.0; 2];
            }
            state.links.push(link);
        }
        state.cont_noeu(self.mesh.nnodes())
    }

    /// `CONT_NOEU` of the initial state: zeros on the slave nodes, as
    /// code_aster's `cfmxr0` creates it and the implicit loop stores it.
    pub fn cont_noeu_initial(&self) -> crate::result::NodalField {
        let state = crate::contact::ContactState {
            dim: self.def.dim,
            links: Vec::new(),
            unpaired: self
                .def
                .zones
                .iter()
                .enumerate()
                .flat_map(|(z, zone)| zone.slave_nodes.iter().map(move |&n| (z, n)))
                .collect(),
        };
        state.cont_noeu_initial(self.mesh.nnodes())
    }

    /// The .mess line of the end of the run.
    pub fn summary_line(&self) -> String {
        let what = match self.enforcement {
            Enforcement::Penalty => {
                format!("penalty (largest penetration {:.4e})", self.max_penetration)
            }
            Enforcement::Kinematic => "kinematic (no penetration by construction)".to_string(),
        };
        let impulse = if self.deformable {
            "impulse of the contact forces on the slave side (the master side takes its opposite)"
        } else {
            "impulse of the contact reactions on the bodies"
        };
        format!(
            "  explicit contact, {what}{}: {} pairings, at most {} slave nodes in contact at once; {impulse} ({})",
            if self.deformable {
                ", deformable master"
            } else {
                ""
            },
            self.pairings,
            self.max_active,
            self.impulse[..self.dim]
                .iter()
                .map(|x| format!("{x:.9e}"))
                .collect::<Vec<_>>()
                .join(", ")
        )
    }
}

/// The explicit loop's view of the discrete contact: the pairing is the
/// preparation; the instants are not needed (the gaps depend on the
/// geometry only, the master's included).
impl ExplicitConstraint for ExplicitContact {
    fn kinematic(&self) -> bool {
        ExplicitContact::kinematic(self)
    }

    fn penalty_omega2(&self, mass: &[f64]) -> f64 {
        ExplicitContact::penalty_omega2(self, mass)
    }

    fn prepare(&mut self, numbering: &DofNumbering, u: &[f64], _t: f64) -> Result<(), String> {
        let _contact = crate::profile::span(crate::profile::Phase::Contact);
        self.pair(numbering, u);
        Ok(())
    }

    fn penetrations(&self, _numbering: &DofNumbering, u: &[f64]) -> (usize, f64) {
        ExplicitContact::penetrations(self, u)
    }

    fn initial_alarm(&self, n: usize, depth: f64) -> String {
        let how = if self.kinematic() {
            "kinematic: onto the surface within one step"
        } else {
            "penalty: a force E_N times the depth"
        };
        format!(
            "  {}",
            crate::contact::initial_penetration_alarm(n, depth, how)
        )
    }

    fn penalty(
        &mut self,
        numbering: &DofNumbering,
        u_n: &[f64],
        u: &[f64],
        _t: f64,
    ) -> Result<(), String> {
        let _contact = crate::profile::span(crate::profile::Phase::Contact);
        self.penalty_forces(numbering, u_n, u);
        Ok(())
    }

    #[allow(clippy::too_many_arguments)]
    fn correct(
        &mut self,
        numbering: &DofNumbering,
        mass: &[f64],
        m: &mut Motion,
        dt: f64,
        kappa: f64,
        c: f64,
        _t_next: f64,
    ) -> Result<(), String> {
        let _contact = crate::profile::span(crate::profile::Phase::Contact);
        self.kinematic_correction(numbering, mass, m, dt, kappa, c);
        Ok(())
    }

    fn start(&mut self) {
        ExplicitContact::start(self)
    }

    fn commit(&mut self, u: &[f64], dt: f64, w: f64) {
        let _contact = crate::profile::span(crate::profile::Phase::Contact);
        ExplicitContact::commit(self, u, dt, w)
    }

    fn force_on_fint_side(&self) -> &[f64] {
        &self.force_on_fint_side
    }

    fn friction_dissipation(&self) -> f64 {
        self.friction_dissipation
    }

    fn cont_noeu(&self, u: &[f64], u_start: &[f64], dt: f64) -> Option<crate::result::NodalField> {
        Some(ExplicitContact::cont_noeu(self, u, u_start, dt))
    }

    fn cont_noeu_initial(&self) -> Option<crate::result::NodalField> {
        Some(ExplicitContact::cont_noeu_initial(self))
    }

    fn summary_line(&self) -> String {
        ExplicitContact::summary_line(self)
    }

    fn history(&self) -> crate::result::ContactHistory {
        ExplicitContact::history(self)
    }

    fn restore(&mut self, h: &crate::result::ContactHistory) -> Result<(), String> {
        ExplicitContact::restore(self, h)
    }
}

/// The nonzero entries of a full vector, as (dof, value).
pub(super) fn sparse(v: &[f64]) -> Vec<(usize, f64)> {
    v.iter()
        .enumerate()
        .filter(|&(_, &x)| x != 0.0)
        .map(|(f, &x)| (f, x))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shape;

    /// Σ N_j² sampled on a fine grid of each master cell's reference
    /// element never exceeds the bound the stable step uses, and reaches
    /// it (so the bound is not loose).
    #[test]
    fn shape_square_sum_bound_is_the_supremum() {
        for kind in [
            CellType::Seg2,
            CellType::Seg3,
            CellType::Tria3,
            CellType::Tria6,
            CellType::Quad4,
            CellType::Quad8,
        ] {
            let bound = shape_square_sum_bound(kind);
            let m = 200;
            let mut top: f64 = 0.0;
            for i in 0..=m {
                for j in 0..=m {
                    let (a, b) = (i as f64 / m as f64, j as f64 / m as f64);
                    let xi = match kind {
                        CellType::Seg2 | CellType::Seg3 => {
                            if j > 0 {
                                continue;
                            }
                            [2.0 * a - 1.0, 0.0, 0.0]
                        }
                        CellType::Tria3 | CellType::Tria6 => {
                            if a + b > 1.0 {
                                continue;
                            }
                            [a, b, 0.0]
                        }
                        _ => [2.0 * a - 1.0, 2.0 * b - 1.0, 0.0],
                    };
                    let s: f64 = shape::eval(kind, xi).n().iter().map(|x| x * x).sum();
                    top = top.max(s);
                }
            }
            assert!(top <= bound * (1.0 + 1e-12), "{kind:?}: {top} > {bound}");
            assert!(top >= bound * (1.0 - 1e-12), "{kind:?}: {top} < {bound}");
        }
    }
}
