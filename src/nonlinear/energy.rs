//! The energy balance of a DYNA_NON_LINE run, step after step.
//!
//! Why: an impact computation can look right and still create or destroy
//! energy (a penalty that is too soft, a step too long, numerical damping
//! of the scheme). The balance says how much, in the units of the problem,
//! at every archived instant.
//!
//! The works are accumulated over the converged steps with the trapezoidal
//! rule of code_aster's `nmener` (notes/explicit.md §8): for a force f,
//! W += Δu·(f_n + f_{n+1})/2. The kinetic energy is ½ v·M v (the mass of
//! the run, on every dof). With the forces on the F_int side of the
//! equilibrium M a + F_int + C = F_ext + λ (C the contact forces, λ the
//! support reactions at imposed dofs):
//!
//! - `ENER_TOT` = ∫ F_int·du: the internal energy (elastic energy plus
//!   plastic work; DYNA_NON_LINE's command splits it after the run from
//!   the archived stresses, columns ENER_ELAS and TRAV_PLAS, where the
//!   laws allow: `commands::dyna_non_line::split_internal_energy`);
//! - `TRAV_EXT` = ∫ (F_ext + λ)·du: work of the loads and of the supports
//!   (zero for constant imposed values);
//! - `TRAV_LIAI` = ∫ C·du: energy absorbed by the contact (penalty energy
//!   while in contact, plus friction);
//! - `DISS_FROT` (aster extension): friction dissipation, the trapezoidal
//!   work of the friction forces on the step slips, −Δs·(f_n + f_{n+1})/2
//!   summed over the contact links (a link new in the step has f_n = 0);
//!   it is part of TRAV_LIAI. (With the end-of-step force alone, the first
//!   sliding step alone overcounts by ½ μ N V Δt: 0.8 % in
//!   tests/verification/energy_friction.comm.)
//! - `TRAV_AMOR` = ∫ C_R v·du: the work of Rayleigh damping (C_R = AMOR_ALPHA
//!   K + AMOR_BETA M, nonlinear::damping), the energy it dissipated;
//! - `ENER_CIN` = ½ v·M v − ½ v₀·M v₀: the change of the kinetic energy
//!   since the start, as code_aster's `enerca` cumulates it (the increments
//!   v̄·M·Δv of every step, whose sum is that difference for a constant
//!   symmetric M), not the kinetic energy itself: a bar launched at
//!   3200 N mm that has slowed to 2934.38 shows −265.62 (code_aster's
//!   sdnv100a);
//! - `DISS_SCH` = TRAV_EXT − ENER_CIN − ENER_TOT − TRAV_AMOR − TRAV_LIAI:
//!   the balance error, energy the time scheme dissipated (or created).
//!
//! Every column is cumulated from the call's initial state, plus the
//! values that state holds in the PARA_CALC table of the ETAT_INIT
//! EVOL_NOLI result when it has one ([`EnergyStart`], code_aster's
//! `nonlinDSEnergyInitValues`): a chain of calls continues one balance.
//!
//! For the trapezoidal rule (Newmark β = 1/4, γ = 1/2) on a linear problem
//! the identity is exact, so DISS_SCH measures only the solver tolerances;
//! numerical damping (γ > 1/2, HHT) shows in it as a positive dissipation.

use std::collections::HashMap;

use super::contact::DiscreteContact;
use super::newton::Engine;
use super::result_table::ContinuedTable;
use crate::post::table::{Cell, ColumnType, Table};

/// Name of the table in the result, as code_aster's RECU_TABLE(NOM_TABLE=).
pub const TABLE_NAME: &str = "PARA_CALC";

/// Column names of the values of [`EnergyBalance::values`], in its order
/// (code_aster's PARA_CALC energy columns, plus DISS_FROT).
pub const COLUMNS: [&str; 7] = [
    "TRAV_EXT",
    "ENER_CIN",
    "ENER_TOT",
    "TRAV_AMOR",
    "TRAV_LIAI",
    "DISS_FROT",
    "DISS_SCH",
];

/// The table's columns in its order: code_aster's (`nonlinDSEnergyCreate`:
/// NUME_REUSE, INST, TRAV_EXT, ENER_CIN, ENER_TOT, TRAV_AMOR, TRAV_LIAI,
/// DISS_SCH), then aster's: NUME_ORDRE, the archived step of the row (a
/// call's rows are found by NUME_REUSE, a step's by NUME_ORDRE or INST),
/// and DISS_FROT (ENER_ELAS and TRAV_PLAS are added after the run).
const TABLE_COLUMNS: [(&str, ColumnType); 10] = [
    (super::result_table::NUME_REUSE, ColumnType::Int),
    ("INST", ColumnType::Real),
    ("TRAV_EXT", ColumnType::Real),
    ("ENER_CIN", ColumnType::Real),
    ("ENER_TOT", ColumnType::Real),
    ("TRAV_AMOR", ColumnType::Real),
    ("TRAV_LIAI", ColumnType::Real),
    ("DISS_SCH", ColumnType::Real),
    ("NUME_ORDRE", ColumnType::Int),
    ("DISS_FROT", ColumnType::Real),
];

/// The energies a call starts from: the row of its initial state in the
/// PARA_CALC table of the ETAT_INIT EVOL_NOLI result (code_aster's
/// `nonlinDSEnergyInitValues` reads that table at the initial instant and
/// adds each column to the new call's totals), zero for a run that starts
/// from fields or from rest.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EnergyStart {
    /// The values of [`COLUMNS`], in its order.
    pub values: [f64; 7],
    /// TRAV_PLAS of that row, when the call that wrote it could split
    /// ENER_TOT (`commands::dyna_non_line::split_internal_energy`).
    pub trav_plas: Option<f64>,
}

impl EnergyStart {
    /// The start of a call continuing the step `nume_ordre` (instant `inst`)
    /// of a result whose energy table is `table`: the row of that
    /// NUME_ORDRE, or, in a table without one, the row at `inst` (relative
    /// precision 1e-6). None when no row matches (code_aster then starts
    /// from zero, which the caller says in the .mess).
    pub fn from_table(table: &Table, nume_ordre: usize, inst: f64) -> Option<EnergyStart> {
        let value = |row: usize, name: &str| table.cell(row, name).and_then(Cell::as_f64);
        let matches = |row: usize| match value(row, "NUME_ORDRE") {
            Some(n) => n as usize == nume_ordre,
            None => value(row, "INST")
                .is_some_and(|t| (t - inst).abs() <= 1e-6 * inst.abs().max(f64::MIN_POSITIVE)),
        };
        let row = (0..table.n_rows()).rev().find(|&r| matches(r))?;
        let mut values = [0.0; 7];
        for (v, name) in values.iter_mut().zip(COLUMNS) {
            *v = value(row, name).unwrap_or(0.0);
        }
        Some(EnergyStart {
            values,
            trav_plas: value(row, "TRAV_PLAS"),
        })
    }
}

/// What [`EnergyBalance::given`] is, for the messages that quote it.
pub const GIVEN_MEANING: &str = "the largest of the kinetic energy at the start, |TRAV_EXT| and the internal energy of the initial state, 1/2 sum |u0 F_int0|";

/// Running totals and the forces of the last committed step.
#[derive(Debug, Clone)]
pub struct EnergyBalance {
    /// The kinetic energy ½ v·M v at the call's start and now (absolute:
    /// the column ENER_CIN is their difference).
    pub kinetic0: f64,
    pub kinetic: f64,
    /// ½ Σ |u₀ᵢ F_int,0,ᵢ| of the call's initial state: the scale of the
    /// internal energy it already holds (a preloaded or prestressed
    /// state), which no column of the balance counts.
    pub stored0: f64,
    /// The table's values at the call's start.
    start: EnergyStart,
    pub internal: f64,
    pub external: f64,
    pub contact: f64,
    pub friction: f64,
    /// TRAV_AMOR.
    pub damping: f64,
    u: Vec<f64>,
    fint: Vec<f64>,
    fext: Vec<f64>,
    cforce: Vec<f64>,
    /// The damping force of the committed state.
    dforce: Vec<f64>,
    work: Vec<f64>,
    /// Friction force on the slave node of each (zone, slave) link at the
    /// end of the last step.
    friction_prev: HashMap<(usize, usize), [f64; 3]>,
    /// Archived rows of this call (NUME_ORDRE, INST, the seven values).
    pub rows: Vec<(usize, f64, [f64; 7])>,
    /// The result's table as this call found it (the rows of the calls
    /// it continues), which its rows are appended to.
    previous: ContinuedTable,
}

impl EnergyBalance {
    /// The balance at the engine's committed (initial, initialized) state:
    /// every column holds there the value `start` gives (zero for a fresh
    /// run). `previous` is the result's PARA_CALC table, if it has one:
    /// this call's rows go after its rows.
    pub fn new(engine: &Engine, previous: Option<&Table>, start: EnergyStart) -> EnergyBalance {
        let n = engine.committed.motion.u.len();
        let mut e = EnergyBalance {
            kinetic0: 0.0,
            kinetic: 0.0,
            stored0: 0.0,
            start,
            internal: 0.0,
            external: 0.0,
            contact: 0.0,
            friction: 0.0,
            damping: 0.0,
            u: engine.committed.motion.u.clone(),
            fint: engine.committed.fint.clone(),
            fext: vec![0.0; n],
            cforce: vec![0.0; n],
            dforce: engine.damping_force().to_vec(),
            work: vec![0.0; n],
            friction_prev: HashMap::new(),
            rows: Vec::new(),
            previous: ContinuedTable::new(previous, "energy balance", &TABLE_COLUMNS),
        };
        e.kinetic = e.kinetic_of(engine);
        e.kinetic0 = e.kinetic;
        e.stored0 = 0.5
            * e.u
                .iter()
                .zip(&e.fint)
                .map(|(u, f)| (u * f).abs())
                .sum::<f64>();
        // The initial support reactions: those of the initial equilibrium
        // (no contact force is known before the first step).
        e.external_forces(engine, false);
        e
    }

    fn kinetic_of(&mut self, engine: &Engine) -> f64 {
        let v = &engine.committed.motion.v;
        engine.asm.mass_mul(v, &mut self.work);
        0.5 * v.iter().zip(&self.work).map(|(a, b)| a * b).sum::<f64>()
    }

    /// F_ext + λ of the committed state into `self.fext`, λ = M a + C_R v
    /// + F_int + C − F_ext at the imposed dofs (0 elsewhere).
    fn external_forces(&mut self, engine: &Engine, with_contact: bool) {
        let st = &engine.committed;
        engine.asm.mass_mul(&st.motion.a, &mut self.work);
        self.fext.copy_from_slice(&engine.fext);
        let c = engine.contact_force();
        let d = engine.damping_force();
        for &(f, _) in &engine.asm.numbering.imposed {
            let cf = if with_contact { c[f] } else { 0.0 };
            self.fext[f] = self.work[f] + d[f] + st.fint[f] + cf;
        }
    }

    /// Adds the works of the step just committed (`engine.committed` is
    /// its end; the engine's last evaluation is that state's).
    pub fn step(&mut self, engine: &Engine, contact: Option<&DiscreteContact>, has_term: bool) {
        let st = &engine.committed;
        let u = &st.motion.u;
        let c = engine.contact_force();
        let old_fext = std::mem::take(&mut self.fext);
        self.fext = vec![0.0; old_fext.len()];
        self.external_forces(engine, has_term);
        let d = engine.damping_force();
        let (mut wi, mut we, mut wc, mut wd) = (0.0, 0.0, 0.0, 0.0);
        for f in 0..u.len() {
            let du = u[f] - self.u[f];
            if du == 0.0 {
                continue;
            }
            wi += 0.5 * du * (self.fint[f] + st.fint[f]);
            wd += 0.5 * du * (self.dforce[f] + d[f]);
            we += 0.5 * du * (old_fext[f] + self.fext[f]);
            if has_term {
                wc += 0.5 * du * (self.cforce[f] + c[f]);
            }
        }
        self.internal += wi;
        self.damping += wd;
        self.external += we;
        self.contact += wc;
        if let Some(dc) = contact {
            let mut now = HashMap::new();
            for l in dc.committed.links.iter().filter(|l| l.frictional) {
                let f = l.friction_force();
                let prev = self
                    .friction_prev
                    .get(&(l.zone, l.slave))
                    .copied()
                    .unwrap_or([0.0; 3]);
                for k in 0..l.ntangents {
                    let t = l.tangents[k];
                    let fk = (0..3).map(|i| (f[i] + prev[i]) * t[i]).sum::<f64>();
                    self.friction -= 0.5 * fk * l.slip[k];
                }
                now.insert((l.zone, l.slave), f);
            }
            self.friction_prev = now;
        }
        self.u.copy_from_slice(u);
        self.fint.copy_from_slice(&st.fint);
        self.dforce.copy_from_slice(d);
        if has_term {
            self.cforce.copy_from_slice(c);
        }
        self.kinetic = self.kinetic_of(engine);
    }

    /// The energy given to the model in this call, the scale of the
    /// balance's alarms ([`GIVEN_MEANING`]): the largest of the kinetic
    /// energy at the start, |TRAV_EXT| of the call and the internal energy
    /// the initial state holds (`stored0`). Without the last, a model
    /// preloaded at rest (STAT_NON_LINE under gravity continued by an
    /// explicit DYNA_NON_LINE under the same gravity) had a "given" energy
    /// of round-off (TRAV_EXT 4.8e-35 N mm) and the round-off of its
    /// balance (5.5e-32) stopped the run as unstable at its 11th step
    /// (probe15 p9).
    pub fn given(&self) -> f64 {
        self.kinetic0.max(self.external.abs()).max(self.stored0)
    }

    /// The energy the model holds beyond what it was given in this call:
    /// ENER_CIN + ENER_TOT + TRAV_AMOR − TRAV_EXT of the call, that is
    /// −(DISS_SCH + TRAV_LIAI).
    pub fn surplus(&self) -> f64 {
        self.kinetic - self.kinetic0 + self.internal + self.damping - self.external
    }

    /// The contact (or the unilateral links) has created energy: its work
    /// is below −1 % of [`EnergyBalance::given`] **and** the model holds
    /// more than 1 % of it beyond what it was given. TRAV_LIAI alone is not
    /// enough: its trapezoidal rule charges a link that opens with half
    /// its last reaction over the step's separation, so a dissipative
    /// scheme shows TRAV_LIAI below zero while the energy of the model
    /// only falls (SDNV103 E: TRAV_LIAI −2.55e3 at 1e-7 s for a total
    /// energy 1.2e3 below the initial one, the difference in DISS_SCH).
    pub fn contact_created_energy(&self) -> bool {
        let given = self.given();
        given > 0.0 && self.contact < -0.01 * given && self.surplus() > 0.01 * given
    }

    /// The values that are not finite, named (`ENER_CIN = inf, ...`), if
    /// any: the motion has grown past what double precision can square
    /// (½ v·M v, F·Δu) even where the motion itself is still finite.
    pub fn not_finite(&self) -> Option<String> {
        let v = self.values();
        let bad: Vec<String> = COLUMNS
            .iter()
            .zip(v)
            .filter(|(_, x)| !x.is_finite())
            .map(|(name, x)| format!("{name} = {x}"))
            .collect();
        (!bad.is_empty()).then(|| bad.join(", "))
    }

    /// The columns' values of this call alone (from its initial state).
    pub fn own_values(&self) -> [f64; 7] {
        let kinetic = self.kinetic - self.kinetic0;
        let error = self.external - kinetic - self.internal - self.damping - self.contact;
        [
            self.external,
            kinetic,
            self.internal,
            self.damping,
            self.contact,
            self.friction,
            error,
        ]
    }

    /// The columns' values as the table holds them: this call's plus its
    /// start's.
    pub fn values(&self) -> [f64; 7] {
        let mut v = self.own_values();
        for (x, s) in v.iter_mut().zip(self.start.values) {
            *x += s;
        }
        v
    }

    /// Records an archived instant; returns the .mess line.
    pub fn archive(&mut self, nume_ordre: usize, t: f64) -> String {
        let v = self.values();
        self.rows.push((nume_ordre, t, v));
        // TRAV_AMOR only where Rayleigh damping exists.
        let amor = if v[3] != 0.0 {
            format!("  TRAV_AMOR {:.6e}", v[3])
        } else {
            String::new()
        };
        // DISS_SCH relative to the energy given: the call's initial
        // kinetic energy, or the external work for a run that starts at
        // rest (a ratio to a zero kinetic energy printed 0 whatever
        // DISS_SCH was).
        let ratio = if self.kinetic0 > 0.0 {
            format!(
                " ({:.3e} of the initial kinetic energy)",
                v[6] / self.kinetic0
            )
        } else if v[0] != 0.0 {
            format!(" ({:.3e} of |TRAV_EXT|)", v[6] / v[0].abs())
        } else {
            String::new()
        };
        format!(
            "  energy at t = {t:e}: ENER_CIN {:.6e}  ENER_TOT {:.6e}  TRAV_EXT {:.6e}{amor}  TRAV_LIAI {:.6e}  DISS_FROT {:.6e}  DISS_SCH {:.6e}{ratio}  kinetic energy {:.6e}",
            v[1],
            v[2],
            v[0],
            v[4],
            v[5],
            v[6],
            self.kinetic,
        )
    }

    /// The result's table: the previous calls' rows (kept, code_aster's
    /// `nmarpc` appends) then this call's, tagged with its NUME_REUSE. A
    /// new table is titled `title`.
    pub fn table(&self, title: &str) -> Table {
        let mut t = self.previous.table.clone();
        if t.n_rows() == 0 {
            t.title = vec![title.to_string()];
        }
        let reuse = self.previous.nume_reuse;
        for (n, inst, v) in &self.rows {
            let mut cells = vec![
                (super::result_table::NUME_REUSE, Cell::Int(reuse)),
                ("INST", Cell::Real(*inst)),
                ("NUME_ORDRE", Cell::Int(*n as i64)),
            ];
            cells.extend(COLUMNS.iter().zip(v).map(|(&c, &x)| (c, Cell::Real(x))));
            // Every column exists with the type of its value.
            let _ = t.add_row(&cells);
        }
        t
    }

    /// This call's NUME_REUSE in the table.
    pub fn nume_reuse(&self) -> i64 {
        self.previous.nume_reuse
    }
}
