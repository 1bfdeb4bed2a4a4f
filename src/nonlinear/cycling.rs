//! Cycling of the continuous contact's statuses (`ADAPTATION='CYCLAGE'`,
//! code_aster's `mm_cycl_detect`, `mm_cycl_d1..d4`, `mm_cycl_algo`;
//! shared/docs/notes/contact-continue.md §8): the generalised Newton can
//! alternate forever between two states of a point, and the contact
//! status criterion "no status changed" then never holds.
//!
//! Detection, at every status evaluation of a step, per contact point:
//! * contact / no contact (d1): the status returns to the value it had two
//!   evaluations before (0, 1, 0 or 1, 0, 1). code_aster encodes windows
//!   of 3 statuses and flags the code of (0, 0, 1), which the note could
//!   not reconcile with a cycle (§8); this reads the rule as "a status
//!   that comes back", which is what a cycle of any period ≥ 2 shows.
//! * stick / slip (d2): a point in contact whose friction phase returns to
//!   the one it had two evaluations before.
//! * slip reversal (d3): two successive slip evaluations whose
//!   directions differ by more than 175° (in 2D the slip direction is ±τ,
//!   so a reversal is a change of sign).
//! * flip-flop (d4): a point whose status changes while its pressure is
//!   negligible, |λ| ≤ 1e-3 a_min (the note's threshold; a_min the
//!   smallest master edge): a node grazing the master.
//!
//! Treatment (what changes the iterations; the matrix blending and the
//! coefficient search of code_aster change nothing measurable, note §8,
//! and are not reproduced):
//! * a flip-flop point's status change does not block convergence (with
//!   Newton contact from iteration 3 on and a contact cycle detected, with
//!   the contact fixed point at once) once the pressures have settled: the
//!   largest change of λ between the last two evaluations over the points
//!   in contact at both is below 1e-4 of the mean |λ| (code_aster's
//!   `resi_pressure` against `cont_pressure`);
//! * a point that still cycles after Newton iteration 9 (`it_cycl_maxi`
//!   plus 3): code_aster switches it to a soft penalised contact for the rest
//!   of the step, which changes the solution (a visible penetration) with
//!   formulas the note does not give; here the step fails with a message
//!   naming the point and the cycles, so that the ERREUR rule of
//!   DEFI_LIST_INST can cut it (the note's advice: report, not emulate).

/// The four kinds of cycle, in code_aster's order d1..d4.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CycleKind {
    ContactStatus,
    StickSlip,
    SlipReversal,
    FlipFlop,
}

impl CycleKind {
    pub const ALL: [CycleKind; 4] = [
        CycleKind::ContactStatus,
        CycleKind::StickSlip,
        CycleKind::SlipReversal,
        CycleKind::FlipFlop,
    ];

    pub fn describe(self) -> &'static str {
        match self {
            CycleKind::ContactStatus => "contact/no contact",
            CycleKind::StickSlip => "stick/slip",
            CycleKind::SlipReversal => "slip forward/backward",
            CycleKind::FlipFlop => "flip-flop at zero pressure",
        }
    }
}

/// What a status evaluation saw at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observation {
    /// The evaluated contact status.
    pub status: bool,
    /// In contact with friction: Some(true) stick, Some(false) slip.
    pub stick: Option<bool>,
    /// Unit slip direction in the tangent basis (r/|r|, 2D: (±1, 0))
    /// when slipping, else 0.
    pub slip_dir: [f64; 2],
    /// λ at the evaluation.
    pub lambda: f64,
}

#[derive(Debug, Clone, Default)]
struct History {
    /// The last observations of the step, oldest first (at most 2).
    last: Vec<Observation>,
    /// Cycles detected at this point in the step.
    found: [usize; 4],
}

/// The detectors of every contact point.
#[derive(Debug, Clone)]
pub struct Cycling {
    points: Vec<History>,
    /// λ below which a pressure is "zero" for the flip-flop detector.
    zero_pressure: f64,
    /// Cycles detected since the term was built, per kind (d1..d4).
    pub total: [usize; 4],
}

impl Cycling {
    /// Detectors for `n` points; `a_min` the smallest master edge.
    pub fn new(n: usize, a_min: f64) -> Self {
        Cycling {
            points: vec![History::default(); n],
            zero_pressure: 1e-3 * a_min,
            total: [0; 4],
        }
    }

    /// The step starts: the histories restart (the statuses of a new step
    /// are not a continuation of the last one's iterations).
    pub fn begin_step(&mut self) {
        for h in &mut self.points {
            h.last.clear();
            h.found = [0; 4];
        }
    }

    /// Records the evaluation `o` of point `i` (its status before was
    /// `prev_status`); returns the cycles it shows.
    pub fn observe(&mut self, i: usize, prev_status: bool, o: Observation) -> [bool; 4] {
        let h = &mut self.points[i];
        let mut hit = [false; 4];
        if let [a, b] = h.last[..] {
            hit[0] = o.status != b.status && o.status == a.status;
            if let (Some(x), Some(y), Some(z)) = (a.stick, b.stick, o.stick) {
                hit[1] = z != y && z == x;
            }
        }
        if let Some(b) = h.last.last() {
            // Both slipping and more than 175° apart.
            let c = b.slip_dir[0] * o.slip_dir[0] + b.slip_dir[1] * o.slip_dir[1];
            hit[2] = c < (175f64).to_radians().cos();
        }
        hit[3] = o.status != prev_status && o.lambda.abs() <= self.zero_pressure;
        for k in 0..4 {
            if hit[k] {
                h.found[k] += 1;
                self.total[k] += 1;
            }
        }
        if h.last.len() == 2 {
            h.last.remove(0);
        }
        h.last.push(o);
        hit
    }

    /// Cycles detected at point `i` in this step, per kind.
    pub fn found(&self, i: usize) -> [usize; 4] {
        self.points[i].found
    }

    /// "contact/no contact ×2, stick/slip ×1" for a message.
    pub fn summary(counts: [usize; 4]) -> String {
        CycleKind::ALL
            .iter()
            .zip(counts)
            .filter(|(_, n)| *n > 0)
            .map(|(k, n)| format!("{} ×{n}", k.describe()))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// Newton iterations after which a point still cycling is given up on
/// (code_aster's `it_cycl_maxi` + 3, note §8).
pub const CYCLING_ITERATIONS: usize = 9;

#[cfg(test)]
mod tests {
    use super::*;

    fn obs(status: bool, stick: Option<bool>, slip_sign: f64, lambda: f64) -> Observation {
        Observation {
            status,
            stick,
            slip_dir: [slip_sign, 0.0],
            lambda,
        }
    }

    #[test]
    fn a_status_that_comes_back_is_a_contact_cycle() {
        let mut c = Cycling::new(1, 20.0);
        let seq = [true, false, true, true, false, true];
        let mut prev = false;
        let mut hits = Vec::new();
        for s in seq {
            hits.push(c.observe(0, prev, obs(s, None, 0.0, -1.0))[0]);
            prev = s;
        }
        assert_eq!(hits, [false, false, true, false, false, true]);
        assert_eq!(c.found(0)[0], 2);
        c.begin_step();
        assert_eq!(c.found(0), [0; 4]);
        assert_eq!(c.total[0], 2);
    }

    #[test]
    fn stick_slip_reversal_and_flip_flop() {
        let mut c = Cycling::new(1, 20.0);
        let h1 = c.observe(0, true, obs(true, Some(true), 0.0, -1.0));
        let h2 = c.observe(0, true, obs(true, Some(false), 1.0, -1.0));
        let h3 = c.observe(0, true, obs(true, Some(true), 0.0, -1.0));
        assert_eq!((h1[1], h2[1], h3[1]), (false, false, true));
        let h4 = c.observe(0, true, obs(true, Some(false), -1.0, -1.0));
        assert!(!h4[2], "a stick evaluation between: no reversal");
        let h5 = c.observe(0, true, obs(true, Some(false), 1.0, -1.0));
        assert!(h5[2]);
        // A change at |λ| ≤ 1e-3 a_min = 0.02 is a flip-flop, not above.
        assert!(c.observe(0, true, obs(false, None, 0.0, 0.01))[3]);
        assert!(!c.observe(0, false, obs(true, None, 0.0, -0.5))[3]);
        assert!(!c.observe(0, true, obs(true, None, 0.0, 0.0))[3]);
        assert_eq!(
            Cycling::summary(c.found(0)),
            "contact/no contact ×1, stick/slip ×2, slip forward/backward ×1, flip-flop at zero pressure ×1"
        );
    }
}
