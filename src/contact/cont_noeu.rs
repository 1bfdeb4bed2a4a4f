//! The state of every contact link after an iteration or a step, the
//! `CONT_NOEU` field built from it (semantics.md §6.6, code_aster's
//! `cfresu` and `mmmres`), and the contact inputs of DEFI_LIST_INST's
//! events.
//!
//! Signs (docs/contact.md §4): [`LinkState::normal_force`],
//! [`LinkState::friction_force`] and [`LinkState::reaction`] are the
//! forces exerted **on** the slave node (the physics: energy, momentum);
//! the vectors `CONT_NOEU` prints (RN*, RTA*, RTG*, R*, and the
//! percussions IX, IY, IZ) are their opposites, the contact term on the
//! internal-force side of the slave's equilibrium, which is what
//! code_aster prints ([`LinkState::printed_normal`]).

use std::collections::HashMap;

use crate::mesh::vec3::{add, norm, scale};
use crate::result::NodalField;

/// The 30 components of `CONT_NOEU` (quantity INFC_R), in code_aster's order.
pub const CONT_NOEU_COMPONENTS: [&str; 30] = [
    "CONT", "JEU", "RN", "RNX", "RNY", "RNZ", "GLIX", "GLIY", "GLI", "RTAX", "RTAY", "RTAZ",
    "RTGX", "RTGY", "RTGZ", "RX", "RY", "RZ", "R", "HN", "I", "IX", "IY", "IZ", "PT_X", "PT_Y",
    "PT_Z", "PROJ_X", "PROJ_Y", "PROJ_Z",
];

/// Below this total reaction the percussion restarts from 0 (`cfresu`,
/// `mmmres`).
pub const PERCUSSION_RESET: f64 = 1e-6;

/// Status of a link, with code_aster's `CONT` codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LinkStatus {
    /// No master cell within TOLE_PROJ_EXT / DIST_APPA (−1).
    Unpaired,
    /// Gap ≥ 0, no force (0).
    Open,
    /// In contact and sticking (1).
    Stick,
    /// In contact and sliding, or in contact without friction (2).
    Slip,
}

impl LinkStatus {
    /// The `CONT` value.
    pub fn code(self) -> f64 {
        match self {
            LinkStatus::Unpaired => -1.0,
            LinkStatus::Open => 0.0,
            LinkStatus::Stick => 1.0,
            LinkStatus::Slip => 2.0,
        }
    }
    pub fn in_contact(self) -> bool {
        matches!(self, LinkStatus::Stick | LinkStatus::Slip)
    }
}

/// One link at given displacements.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkState {
    pub zone: usize,
    pub slave: usize,
    pub status: LinkStatus,
    /// Current gap g (fixed pairing): > 0 open, < 0 penetration.
    pub gap: f64,
    /// Normal force λ_n = E_N·(−g) ≥ 0 (0 when open).
    pub lambda_n: f64,
    /// Unit inward master normal n_in.
    pub normal: [f64; 3],
    pub tangents: [[f64; 3]; 2],
    pub ntangents: usize,
    /// The zone has Coulomb friction (GLI* are reported only then).
    pub frictional: bool,
    /// Slave-minus-master tangential displacement since the start of the
    /// step, along τ1, τ2.
    pub slip: [f64; 2],
    /// Friction force components F_t along τ1, τ2 (as in the residual:
    /// the force on the slave node is −F_t, against the slip).
    pub friction: [f64; 2],
    /// Projection point at pairing.
    pub proj: [f64; 3],
    /// Percussion (I, IX, IY, IZ) as `CONT_NOEU` prints it: R·dt of the
    /// printed reaction [`LinkState::printed_reaction`], see
    /// [`ContactState::step_percussion`] (discrete) and
    /// [`ContactState::accumulate_percussion`] (continuous).
    pub percussion: [f64; 4],
}

impl LinkState {
    /// Normal contact force exerted on the slave node: λ_n·n_out
    /// (CONT_NOEU prints its opposite, [`LinkState::printed_normal`]).
    pub fn normal_force(&self) -> [f64; 3] {
        scale(-self.lambda_n, self.normal)
    }
    /// Friction force exerted on the slave node: −Σ F_t,k τ_k.
    pub fn friction_force(&self) -> [f64; 3] {
        let mut f = [0.0; 3];
        for k in 0..self.ntangents {
            f = add(f, scale(-self.friction[k], self.tangents[k]));
        }
        f
    }
    /// Total contact force on the slave node.
    pub fn reaction(&self) -> [f64; 3] {
        add(self.normal_force(), self.friction_force())
    }
    /// RNX, RNY, RNZ as code_aster prints them: λ_n·n_in, the normal
    /// contact term on the internal-force side of the slave node's
    /// equilibrium, i.e. minus the force on the slave node (the force the
    /// slave node exerts on the master). code_aster's `cfresu` projects on
    /// the normal the vector `AFMU` (penalised) or `ATMU` (`CONTRAINTE`),
    /// both added to the internal forces (`nmequi`), whose slave entries
    /// are λ·n_in (`cfcpes`, `cfcoef`, `cfnewj`); `mmmres` prints the
    /// contact elements' nodal vector `CNELTC`, added to `CNFINT`
    /// (`nmasco`, `nmaint`). A block pressed down on a foundation below it
    /// has RNY < 0.
    pub fn printed_normal(&self) -> [f64; 3] {
        scale(-1.0, self.normal_force())
    }
    /// RTA* (sticking) or RTG* (sliding) as code_aster prints them: Σ F_t,k
    /// τ_k, minus the friction force on the slave node (`cfresb` on
    /// `AFMU`, `mmmres` on `CNELTF`): along the slip.
    pub fn printed_friction(&self) -> [f64; 3] {
        scale(-1.0, self.friction_force())
    }
    /// RX, RY, RZ as code_aster prints them: RN* + RT*, minus the total
    /// contact force on the slave node.
    pub fn printed_reaction(&self) -> [f64; 3] {
        add(self.printed_normal(), self.printed_friction())
    }
}

/// All links of a pairing at given displacements.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ContactState {
    pub dim: usize,
    pub links: Vec<LinkState>,
    /// (zone, slave node) left unpaired.
    pub unpaired: Vec<(usize, usize)>,
}

impl ContactState {
    /// The link of a slave node in a zone.
    pub fn link(&self, zone: usize, slave: usize) -> Option<&LinkState> {
        self.links
            .iter()
            .find(|l| l.zone == zone && l.slave == slave)
    }

    /// The percussion of a converged step of length `dt` as code_aster's
    /// discrete post-treatment (`cfresu`) computes it: the stored
    /// percussion of every link is first set to 0, then R·dt is added, so
    /// I = R·dt and (IX, IY, IZ) = (RX, RY, RZ)·dt **of this step only**
    /// (0 when R ≤ 1e-6), with the printed reaction
    /// ([`LinkState::printed_reaction`]). For `FORMULATION='DISCRETE'`
    /// (penalised and `CONTRAINTE`).
    pub fn step_percussion(&mut self, dt: f64) {
        for l in &mut self.links {
            let rv = l.printed_reaction();
            let r = norm(rv);
            l.percussion = if r <= PERCUSSION_RESET {
                [0.0; 4]
            } else {
                [r * dt, rv[0] * dt, rv[1] * dt, rv[2] * dt]
            };
        }
    }

    /// The percussion of a converged step of length `dt` as code_aster's
    /// continuous post-treatment (`mmmres`) computes it: the percussion
    /// field is not reset from one step to the next ("on ne remet pas à
    /// zéro d'un pas à l'autre"), and each contact point adds R·dt to the
    /// value stored at its slave node. With `INTEGRATION='AUTO'` the
    /// contact points are the nodes of each slave cell, so a node shared by
    /// `visits(zone, node)` slave cells of its zone is visited that many
    /// times per step: I = I_prev + visits·R·dt (and IX, IY, IZ likewise
    /// with the printed reaction), I_prev being the value of the same
    /// (zone, slave node) in `prev` (the previous converged step, None at
    /// the first). Whenever R ≤ 1e-6 the percussion restarts at 0.
    pub fn accumulate_percussion(
        &mut self,
        prev: Option<&ContactState>,
        dt: f64,
        visits: impl Fn(usize, usize) -> usize,
    ) {
        let old: HashMap<(usize, usize), [f64; 4]> = prev
            .map(|p| {
                p.links
                    .iter()
                    .map(|l| ((l.zone, l.slave), l.percussion))
                    .collect()
            })
            .unwrap_or_default();
        for l in &mut self.links {
            let rv = l.printed_reaction();
            let r = norm(rv);
            if r <= PERCUSSION_RESET {
                l.percussion = [0.0; 4];
                continue;
            }
            let m = visits(l.zone, l.slave) as f64 * dt;
            let p = old.get(&(l.zone, l.slave)).copied().unwrap_or([0.0; 4]);
            l.percussion = [
                p[0] + r * m,
                p[1] + rv[0] * m,
                p[2] + rv[1] * m,
                p[3] + rv[2] * m,
            ];
        }
    }

    /// The largest penetration −g over the links with g ≤ 0 (0 if none):
    /// the INTERPENETRATION event fires when it exceeds PENE_MAXI.
    pub fn max_interpenetration(&self) -> f64 {
        self.links
            .iter()
            .filter(|l| l.gap <= 0.0)
            .map(|l| -l.gap)
            .fold(0.0, f64::max)
    }

    /// `CONT_NOEU` before any step: the 30 components on every slave node,
    /// all 0, absent elsewhere. code_aster creates its contact field this
    /// way when the computation starts (`cfmxr0`) and fills it only in the
    /// post-treatment of a converged step (`cfresu`), so the initial
    /// instant (NUME_ORDRE 0) stores zeros, not the initial gaps: a
    /// minimum of JEU over a computation (SDNV103 I) includes that 0.
    pub fn cont_noeu_initial(&self, mesh_nnodes: usize) -> NodalField {
        let mut f = NodalField::absent(
            CONT_NOEU_COMPONENTS.iter().map(|s| s.to_string()).collect(),
            mesh_nnodes,
        );
        let slaves = self
            .links
            .iter()
            .map(|l| l.slave)
            .chain(self.unpaired.iter().map(|&(_, n)| n));
        for n in slaves {
            for c in 0..CONT_NOEU_COMPONENTS.len() {
                f.set(n, c, 0.0);
            }
        }
        f
    }

    /// `CONT_NOEU`: the 30 components on every slave node, absent
    /// elsewhere. As code_aster's discrete post-treatment:
    /// - every slave node starts with all components 0;
    /// - JEU is written for every paired link, in contact or not;
    /// - the other components only for links in contact;
    /// - an unpaired slave node has CONT = −1;
    /// - RN*, RTA* (stick) or RTG* (slip) are minus the forces exerted on
    ///   the slave node, as code_aster prints them
    ///   ([`LinkState::printed_normal`]), R* their sum, PT_* = 0, PROJ_*
    ///   the projection at pairing; HN (wear) is 0.
    ///
    /// A slave node in two zones shows the last zone's link.
    pub fn cont_noeu(&self, mesh_nnodes: usize) -> NodalField {
        let mut f = NodalField::absent(
            CONT_NOEU_COMPONENTS.iter().map(|s| s.to_string()).collect(),
            mesh_nnodes,
        );
        let ncmp = CONT_NOEU_COMPONENTS.len();
        let zero = |f: &mut NodalField, n: usize| {
            for c in 0..ncmp {
                f.set(n, c, 0.0);
            }
        };
        for &(_, n) in &self.unpaired {
            zero(&mut f, n);
            f.set(n, 0, LinkStatus::Unpaired.code());
        }
        for l in &self.links {
            let n = l.slave;
            zero(&mut f, n);
            f.set(n, 1, l.gap);
            if !l.status.in_contact() {
                continue;
            }
            let rn = l.printed_normal();
            let rt = l.printed_friction();
            let r = l.printed_reaction();
            let gli = (l.slip[0] * l.slip[0] + l.slip[1] * l.slip[1]).sqrt();
            let mut v = [0.0; 30];
            v[0] = l.status.code();
            v[1] = l.gap;
            v[2] = norm(rn);
            v[3..6].copy_from_slice(&rn);
            if l.frictional {
                v[6] = l.slip[0];
                v[7] = l.slip[1];
                v[8] = gli;
            }
            match l.status {
                LinkStatus::Stick => v[9..12].copy_from_slice(&rt),
                _ => v[12..15].copy_from_slice(&rt),
            }
            v[15..18].copy_from_slice(&r);
            v[18] = norm(r);
            v[19] = 0.0;
            v[20..24].copy_from_slice(&l.percussion);
            v[27..30].copy_from_slice(&l.proj);
            for (c, x) in v.iter().enumerate() {
                f.set(n, c, *x);
            }
        }
        f
    }
}

/// For each link of `new` (same order), whether it is in contact at the
/// start (in `prev`, the state at the end of the previous step) or at the
/// end of the converged step: code_aster's COLLISION event starts a
/// collision on such a link **if its collision is not already running**,
/// a flag (with the collision's end time t + SUBD_DUREE) that the time
/// stepper keeps.
pub fn collision_started(prev: &ContactState, new: &ContactState) -> Vec<bool> {
    let before: HashMap<(usize, usize), bool> = prev
        .links
        .iter()
        .map(|l| ((l.zone, l.slave), l.status.in_contact()))
        .collect();
    new.links
        .iter()
        .map(|l| l.status.in_contact() || before.get(&(l.zone, l.slave)).copied().unwrap_or(false))
        .collect()
}
