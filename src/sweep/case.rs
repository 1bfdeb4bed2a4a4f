//! One sweep case: a variant of SDNV103 B (mesh, time steps, penalty, time
//! scheme), written out as a MED mesh and a command file, run in-process
//! through the study runner, and reduced to the few numbers the sweeps
//! compare.
//!
//! The values are read from the study's concepts (the result `RESU` and the
//! mesh `MAIL`), not from printed tables, so a change of print format cannot
//! silently change a sweep; the step statistics (unknowns, Newton
//! iterations, cuts) only exist in the message log and are parsed from it.

use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use crate::commands;
use crate::concepts::ConceptData;
use crate::diag::Source;
use crate::mesh::taylor::{generate, TaylorKind, TaylorParams};
use crate::run::driver::parse_and_check;
use crate::study::Study;

/// The command-file template, derived from comm/sdnv103b.comm.
const TEMPLATE: &str = include_str!("taylor_b.comm.in");

/// Time at which B1 DX and A2 DY are compared (the end of B).
pub const T_END: f64 = 8.0e-5;

/// The time scheme of DYNA_NON_LINE/SCHEMA_TEMPS.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scheme {
    Newmark { beta: f64, gamma: f64 },
    Hht { alpha: f64, modi_equi: bool },
}

impl Scheme {
    /// B's dissipative Newmark.
    pub const B: Scheme = Scheme::Newmark {
        beta: 0.49,
        gamma: 0.9,
    };
    /// The average-acceleration (trapezoidal) rule: no numerical damping.
    pub const TRAPEZOIDAL: Scheme = Scheme::Newmark {
        beta: 0.25,
        gamma: 0.5,
    };

    pub fn label(&self) -> String {
        match *self {
            Scheme::Newmark { beta, gamma } => format!("NEWMARK {beta}/{gamma}"),
            Scheme::Hht { alpha, modi_equi } => format!(
                "HHT {alpha} MODI_EQUI '{}'",
                if modi_equi { "OUI" } else { "NON" }
            ),
        }
    }

    fn keywords(&self) -> String {
        match *self {
            Scheme::Newmark { beta, gamma } => format!(
                "SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT', BETA={}, GAMMA={}",
                num(beta),
                num(gamma)
            ),
            Scheme::Hht { alpha, modi_equi } => format!(
                "SCHEMA='HHT', FORMULATION='DEPLACEMENT', ALPHA={}, MODI_EQUI='{}'",
                num(alpha),
                if modi_equi { "OUI" } else { "NON" }
            ),
        }
    }
}

/// The time list after the free flight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TimeList {
    /// B's own list: 4 steps from -1e-7 to 1e-6, then 158 steps of 5e-7.
    B,
    /// Steps of `dt` from the first contact (t = 0) to 80 us.
    Uniform { dt: f64 },
}

impl TimeList {
    /// Number of steps of the list (both lists start with one step of free
    /// flight from -1e-5 to -1e-7).
    pub fn steps(&self) -> usize {
        match *self {
            TimeList::B => 1 + 4 + 158,
            TimeList::Uniform { dt } => 2 + uniform_count(dt),
        }
    }

    pub fn label(&self) -> String {
        match *self {
            TimeList::B => "B's list".into(),
            TimeList::Uniform { dt } => format!("{} us", dt * 1e6),
        }
    }
}

fn uniform_count(dt: f64) -> usize {
    (T_END / dt).round().max(1.0) as usize
}

/// A case of a sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct CaseSpec {
    /// Cells across the radius.
    pub n1: usize,
    /// Cells along the bar.
    pub n2: usize,
    pub time: TimeList,
    /// Normal contact penalty DEFI_CONTACT/ZONE/E_N.
    pub e_n: f64,
    pub scheme: Scheme,
    /// DEFI_LIST_INST/ECHEC/SUBD_NIVEAU of the ERREUR event (cuts by 4):
    /// B leaves code_aster's default 3, which allows sub-steps down to
    /// dt/16 only; the convergence sweep raises it (docs/performance.md).
    pub subd_niveau: u32,
}

impl CaseSpec {
    /// Modelling B itself (5 x 20, B's list, E_N 1e10, Newmark 0.49/0.9).
    pub fn b() -> CaseSpec {
        CaseSpec {
            n1: 5,
            n2: 20,
            time: TimeList::B,
            e_n: 1e10,
            scheme: Scheme::B,
            subd_niveau: 3,
        }
    }

    /// A file-name friendly identifier.
    pub fn slug(&self) -> String {
        let t = match self.time {
            TimeList::B => "listB".to_string(),
            TimeList::Uniform { dt } => format!("dt{}ns", (dt * 1e9).round() as i64),
        };
        let s = match self.scheme {
            Scheme::Newmark { beta, gamma } => format!("nm{beta}_{gamma}"),
            Scheme::Hht { alpha, modi_equi } => {
                format!("hht{alpha}{}", if modi_equi { "oui" } else { "non" })
            }
        };
        let cut = if self.subd_niveau == 3 {
            String::new()
        } else {
            format!("_subd{}", self.subd_niveau)
        };
        format!("b_{}x{}_{t}_en{:e}_{s}{cut}", self.n1, self.n2, self.e_n).replace(['.', '-'], "p")
    }

    /// The command file of the case; `mesh_note` names the mesh in its
    /// header comment.
    pub fn comm_text(&self) -> String {
        let (intervals, note, arch_debut, arch_n) = match self.time {
            TimeList::B => (
                "_F(JUSQU_A=-1.E-7, NOMBRE=1),\n                                    \
                 _F(JUSQU_A=1.E-6, NOMBRE=4),\n                                    \
                 _F(JUSQU_A=8.E-5, NOMBRE=158),"
                    .to_string(),
                "B's time list: one step of free flight to -1e-7, 4 steps across the impact, then 5e-7 steps; archived every 5e-7 from 1e-6".to_string(),
                "1.E-6".to_string(),
                158,
            ),
            TimeList::Uniform { dt } => {
                let n = uniform_count(dt);
                (
                    format!(
                        "_F(JUSQU_A=-1.E-7, NOMBRE=1),\n                                    \
                         _F(JUSQU_A=0., NOMBRE=1),\n                                    \
                         _F(JUSQU_A=8.E-5, NOMBRE={n}),"
                    ),
                    format!(
                        "one step of free flight to -1e-7, one to the first contact at 0, then {n} steps of {} s; archived at every step from the first contact",
                        num(T_END / n as f64)
                    ),
                    num(T_END / n as f64),
                    n - 1,
                )
            }
        };
        TEMPLATE
            .replace(
                "@MESH@",
                &format!("Taylor axis {} x {} QUAD8", self.n1, self.n2),
            )
            .replace("@E_N@", &num(self.e_n))
            .replace("@TIME_NOTE@", &note)
            .replace("@INTERVALLES@", &intervals)
            .replace("@ARCH_DEBUT@", &arch_debut)
            .replace("@ARCH_NOMBRE@", &arch_n.max(1).to_string())
            .replace("@SCHEMA_TEMPS@", &self.scheme.keywords())
            .replace("@SUBD_NIVEAU@", &self.subd_niveau.to_string())
    }

    /// Writes `<slug>.comm` and `<slug>.mmed` into `dir`; returns the
    /// command file's path and the mesh's.
    pub fn write(&self, dir: &Path) -> Result<(PathBuf, PathBuf), String> {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create '{}': {e}", dir.display()))?;
        let mesh = generate(&TaylorParams {
            kind: TaylorKind::Axis,
            n1: self.n1,
            n2: self.n2,
            n3: 0,
            linear: false,
        })?;
        let slug = self.slug();
        let mesh_path = dir.join(format!("{slug}.mmed"));
        crate::medio::write_mesh(&mesh_path, &mesh).map_err(|e| e.to_string())?;
        let comm_path = dir.join(format!("{slug}.comm"));
        std::fs::write(&comm_path, self.comm_text())
            .map_err(|e| format!("cannot write '{}': {e}", comm_path.display()))?;
        Ok((comm_path, mesh_path))
    }
}

/// A real number as the command language reads it (always with a `.` or
/// an exponent, so it is never taken for an integer).
fn num(v: f64) -> String {
    // 12 significant digits: 8e-5 / 40 prints as 2e-6, not 2.0000000000000003e-6.
    let v: f64 = format!("{v:.11e}").parse().unwrap_or(v);
    let s = format!("{v:e}");
    if s.contains('.') || s.contains('e') {
        s
    } else {
        format!("{s}.")
    }
}

/// How a case ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// Ran to 80 us.
    Completed,
    /// The study stopped with an error (DYNA_NON_LINE stopped after its
    /// cuts, a check error...): the engine's message.
    Stopped(String),
    /// The engine panicked: a bug, reported instead of crashing the sweep.
    Panicked(String),
    /// Not run: the predicted or the measured time exceeds the budget.
    Skipped(String),
    /// The case could not be built (mesh, files).
    Failed(String),
}

impl Outcome {
    pub fn short(&self) -> &'static str {
        match self {
            Outcome::Completed => "completed",
            Outcome::Stopped(_) => "stopped",
            Outcome::Panicked(_) => "panicked",
            Outcome::Skipped(_) => "skipped",
            Outcome::Failed(_) => "failed",
        }
    }

    pub fn detail(&self) -> &str {
        match self {
            Outcome::Completed => "",
            Outcome::Stopped(s)
            | Outcome::Panicked(s)
            | Outcome::Skipped(s)
            | Outcome::Failed(s) => s,
        }
    }
}

/// What a case produced.
#[derive(Debug, Clone, PartialEq)]
pub struct CaseResult {
    pub spec: CaseSpec,
    pub outcome: Outcome,
    /// Equations of DYNA_NON_LINE (free dofs).
    pub unknowns: Option<usize>,
    /// Converged steps (sub-steps of cut steps included).
    pub steps: Option<usize>,
    pub newton_iterations: Option<usize>,
    pub cuts: Option<usize>,
    /// Wall time of the whole study (mesh reading to FIN), seconds.
    pub wall: f64,
    /// Wall time of the DYNA_NON_LINE time loop, seconds.
    pub loop_wall: Option<f64>,
    /// Last instant the computation reached.
    pub last_inst: Option<f64>,
    /// B1 DX and A2 DY at 80 us; None if the run did not get there. A NaN
    /// is kept as NaN, and reported as such.
    pub b1_dx: Option<f64>,
    pub a2_dy: Option<f64>,
    /// (INST, VY of A1) at every archived instant from the first contact.
    pub a1_vy: Vec<(f64, f64)>,
}

impl CaseResult {
    fn empty(spec: &CaseSpec, outcome: Outcome) -> CaseResult {
        CaseResult {
            spec: spec.clone(),
            outcome,
            unknowns: None,
            steps: None,
            newton_iterations: None,
            cuts: None,
            wall: 0.0,
            loop_wall: None,
            last_inst: None,
            b1_dx: None,
            a2_dy: None,
            a1_vy: Vec::new(),
        }
    }

    /// A skipped case.
    pub fn skipped(spec: &CaseSpec, why: String) -> CaseResult {
        CaseResult::empty(spec, Outcome::Skipped(why))
    }

    /// Wall time of the time loop per converged step.
    pub fn wall_per_step(&self) -> Option<f64> {
        match (self.loop_wall, self.steps) {
            (Some(w), Some(s)) if s > 0 => Some(w / s as f64),
            _ => None,
        }
    }

    /// True when the run reached 80 us with finite values.
    pub fn usable(&self) -> bool {
        self.outcome == Outcome::Completed
            && self.b1_dx.is_some_and(f64::is_finite)
            && self.a2_dy.is_some_and(f64::is_finite)
    }

    /// One line saying what happened, for tables.
    pub fn what_happened(&self) -> String {
        let nan = self.b1_dx.is_some_and(f64::is_nan)
            || self.a2_dy.is_some_and(f64::is_nan)
            || self.a1_vy.iter().any(|(_, v)| v.is_nan());
        let mut s = match &self.outcome {
            Outcome::Completed => match self.cuts {
                Some(0) | None => "converged".to_string(),
                Some(c) => format!("converged, {c} cut{}", if c == 1 { "" } else { "s" }),
            },
            Outcome::Stopped(m) => format!(
                "stopped at t = {}: {}",
                self.last_inst
                    .map_or("?".into(), |t| format!("{:.3} us", t * 1e6)),
                short_reason(m)
            ),
            o => format!("{}: {}", o.short(), o.detail()),
        };
        if nan {
            s.push_str(" (NaN in the result)");
        }
        s
    }
}

/// The engine's stop message without what the table already says (the
/// step's instants, the residual history, the archived steps); the CSV
/// keeps it whole.
pub fn short_reason(m: &str) -> String {
    let mut s = m.trim();
    if s.starts_with("DYNA_NON_LINE stopped at the step from") {
        if let Some(i) = s.find(": ") {
            s = &s[i + 2..];
        }
    }
    let mut s = s.to_string();
    if let Some(a) = s.find("; residual history") {
        let b = s[a + 2..].find("; ").map_or(s.len(), |b| a + 2 + b);
        s.replace_range(a..b, "");
    }
    if let Some(a) = s.find(" The ") {
        if s[a..].contains("kept in the result") {
            s.truncate(a);
        }
    }
    s.trim_end_matches('.').to_string()
}

/// Runs a case in `dir`, in-process, in a worker thread so that a run
/// longer than `timeout` is reported instead of waited for. A run that
/// times out keeps its thread busy until the process exits (the engine has
/// no cancellation point); the caller must not start more runs after it.
pub fn run_case(spec: &CaseSpec, dir: &Path, timeout: Duration) -> CaseResult {
    let (comm, mesh) = match spec.write(dir) {
        Ok(p) => p,
        Err(e) => return CaseResult::empty(spec, Outcome::Failed(e)),
    };
    let (tx, rx) = mpsc::channel();
    let spec2 = spec.clone();
    let out_dir = dir.to_path_buf();
    let started = Instant::now();
    let spawned = std::thread::Builder::new()
        .name(format!("sweep {}", spec.slug()))
        .spawn(move || {
            let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                run_in_process(&spec2, &comm, &mesh, &out_dir)
            }));
            let _ = tx.send(r);
        });
    if let Err(e) = spawned {
        return CaseResult::empty(spec, Outcome::Failed(format!("cannot start a thread: {e}")));
    }
    match rx.recv_timeout(timeout) {
        Ok(Ok(mut r)) => {
            r.wall = started.elapsed().as_secs_f64();
            r
        }
        Ok(Err(payload)) => {
            let msg = payload
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "(no message)".into());
            let mut r = CaseResult::empty(spec, Outcome::Panicked(msg));
            r.wall = started.elapsed().as_secs_f64();
            r
        }
        Err(_) => {
            let mut r = CaseResult::empty(
                spec,
                Outcome::Skipped(format!(
                    "timed out: still running after the {:.0} s budget",
                    timeout.as_secs_f64()
                )),
            );
            r.wall = started.elapsed().as_secs_f64();
            r
        }
    }
}

/// Parses, checks and executes the command file with unit 20 on the mesh,
/// as `aster run` does, keeping the study to read its concepts.
fn run_in_process(spec: &CaseSpec, comm: &Path, mesh: &Path, out_dir: &Path) -> CaseResult {
    let src = match Source::read(comm) {
        Ok(s) => s,
        Err(d) => return CaseResult::empty(spec, Outcome::Failed(d.message)),
    };
    let mut study = Study {
        out_dir: out_dir.to_path_buf(),
        stem: spec.slug(),
        ..Study::default()
    };
    study.units.map.insert(20, mesh.to_path_buf());
    let registry = commands::all();
    let mut messages = String::new();
    let Some(program) = parse_and_check(&src, &registry, &mut messages) else {
        return CaseResult::empty(
            spec,
            Outcome::Failed(format!("the generated command file is invalid: {messages}")),
        );
    };
    let outcome = match crate::run::execute(&mut study, &program, &registry, &src) {
        Ok(()) => Outcome::Completed,
        Err(d) => Outcome::Stopped(d.message),
    };
    // The log stays next to the case for whoever wants the details.
    let _ = std::fs::write(out_dir.join(format!("{}.mess", study.stem)), &study.mess);
    let _ = std::fs::write(out_dir.join(format!("{}.resu", study.stem)), &study.resu);
    let mut r = CaseResult::empty(spec, outcome);
    let stats = LogStats::parse(&study.mess);
    r.unknowns = stats.unknowns;
    r.steps = Some(stats.steps);
    r.newton_iterations = Some(stats.newton_iterations);
    r.cuts = Some(stats.cuts);
    r.loop_wall = stats.loop_seconds;
    read_values(&study, &mut r);
    r
}

/// Fills the values of `r` from the study's RESU and MAIL concepts.
fn read_values(study: &Study, r: &mut CaseResult) {
    let Some(ConceptData::Result(res)) = study.concepts.data("RESU") else {
        return;
    };
    let Some(ConceptData::Mesh(mesh)) = study.concepts.data("MAIL") else {
        return;
    };
    let node = |g: &str| mesh.node_groups.get(g).and_then(|v| v.first().copied());
    r.last_inst = res.steps.last().map(|s| s.inst);
    if let Some(end) = res
        .steps
        .iter()
        .find(|s| (s.inst - T_END).abs() <= 1e-6 * T_END)
    {
        if let Some(depl) = end.nodal.get("DEPL") {
            let value = |n: Option<usize>, c: &str| {
                let n = n?;
                let i = depl.component_index(c)?;
                depl.values.get(n * depl.ncmp() + i).copied()
            };
            r.b1_dx = value(node("B1"), "DX");
            r.a2_dy = value(node("A2"), "DY");
        }
    }
    if let Some(a1) = node("A1") {
        for s in &res.steps {
            if s.inst < -1e-12 {
                continue;
            }
            if let Some(v) = s.nodal.get("VITE") {
                if let Some(i) = v.component_index("DY") {
                    if let Some(&x) = v.values.get(a1 * v.ncmp() + i) {
                        r.a1_vy.push((s.inst, x));
                    }
                }
            }
        }
    }
}

/// Step statistics of DYNA_NON_LINE read from the message log.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LogStats {
    pub unknowns: Option<usize>,
    pub steps: usize,
    pub newton_iterations: usize,
    pub cuts: usize,
    pub loop_seconds: Option<f64>,
}

impl LogStats {
    /// Reads the DYNA_NON_LINE lines of a .mess text: the "N equations"
    /// line, the step lines (step number, instant, dt, iterations...), the
    /// cut notices, and the closing summary "S steps (C cuts), I Newton
    /// iterations, A archived, W s" when the loop completed.
    pub fn parse(mess: &str) -> LogStats {
        let mut st = LogStats::default();
        let mut summary: Option<(usize, usize, usize, f64)> = None;
        for line in mess.lines() {
            let t = line.trim();
            if let Some(rest) = t.strip_prefix("DYNA_NON_LINE: ") {
                st.unknowns = rest.split_whitespace().next().and_then(|w| w.parse().ok());
                continue;
            }
            if t.starts_with("the step is cut into") {
                st.cuts += 1;
                continue;
            }
            if t.contains(" redone: ") && t.starts_with("step from") {
                st.cuts += 1;
                continue;
            }
            let w: Vec<&str> = t.split_whitespace().collect();
            if w.len() >= 9
                && w[1] == "steps"
                && w[3] == "cuts),"
                && w[5] == "Newton"
                && w[6].starts_with("iterations")
            {
                let secs = w
                    .iter()
                    .position(|x| *x == "s")
                    .and_then(|i| w[i - 1].parse().ok())
                    .unwrap_or(f64::NAN);
                if let (Ok(s), Some(Ok(c)), Ok(i)) = (
                    w[0].parse(),
                    w[2].strip_prefix('(').map(str::parse),
                    w[4].parse(),
                ) {
                    summary = Some((s, c, i, secs));
                }
                continue;
            }
            // A step line: number, instant, dt, iterations, residuals...
            if w.len() >= 4 {
                if let (Ok(_), Ok(_), Ok(_), Ok(it)) = (
                    w[0].parse::<usize>(),
                    w[1].parse::<f64>(),
                    w[2].parse::<f64>(),
                    w[3].parse::<usize>(),
                ) {
                    st.steps += 1;
                    st.newton_iterations += it;
                }
            }
        }
        if let Some((s, c, i, secs)) = summary {
            st.steps = s;
            st.cuts = c;
            st.newton_iterations = i;
            st.loop_seconds = secs.is_finite().then_some(secs);
        }
        st
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_stats_read_the_summary_and_the_step_lines() {
        let mess = "  DYNA_NON_LINE: 712 equations (6 imposed dofs), 101 elements\n\
                    \x20      1  -1.000000e-7   9.900e-6     2      1.0e-9        1.0e-3      1\n\
                    \x20      2   1.000000e-6   1.100e-6     5      1.0e-9        1.0e-3      1\n\
                    \x20 step failure from t = 1e-6 to 2e-6 (dt = 1e-6, level 1): x\n\
                    \x20 the step is cut into 4 sub-steps of 2.5e-7 (level 2)\n";
        let st = LogStats::parse(mess);
        assert_eq!(st.unknowns, Some(712));
        assert_eq!((st.steps, st.newton_iterations, st.cuts), (2, 7, 1));
        assert_eq!(st.loop_seconds, None);
        let done = format!(
            "{mess}  163 steps (2 cuts), 650 Newton iterations, 81 archived, 19.500 s (1.196e-1 s per step)\n"
        );
        let st = LogStats::parse(&done);
        assert_eq!((st.steps, st.newton_iterations, st.cuts), (163, 650, 2));
        assert_eq!(st.loop_seconds, Some(19.5));
    }

    #[test]
    fn stop_reasons_are_shortened_to_the_cause() {
        let m = "DYNA_NON_LINE stopped at the step from t = 7.5e-5 to t = 7.503e-5: Newton did not converge in 20 iterations; residual history (RESI_GLOB_RELA / RESI_GLOB_MAXI): [1] 3.5e-4 / 5.7e0 [2] 1.3e-6 / 2.1e-2; the step is already at the maximum subdivision level SUBD_NIVEAU = 3. The 150 steps archived so far (last instant 7.5e-5) are kept in the result.";
        assert_eq!(
            short_reason(m),
            "Newton did not converge in 20 iterations; the step is already at the maximum subdivision level SUBD_NIVEAU = 3"
        );
        assert_eq!(short_reason("study error"), "study error");
    }

    #[test]
    fn uniform_lists_count_their_steps() {
        assert_eq!(TimeList::Uniform { dt: 2e-6 }.steps(), 42);
        assert_eq!(TimeList::Uniform { dt: 2.5e-7 }.steps(), 322);
        assert_eq!(TimeList::B.steps(), 163);
        let text = CaseSpec {
            time: TimeList::Uniform { dt: 2e-6 },
            ..CaseSpec::b()
        }
        .comm_text();
        assert!(text.contains("_F(JUSQU_A=8.E-5, NOMBRE=40)"), "{text}");
        assert!(text.contains("DEBUT=2e-6"), "{text}");
        assert!(text.contains("SUBD_NIVEAU=3,"), "{text}");
        assert!(!text.contains('@'), "{text}");
    }
}
