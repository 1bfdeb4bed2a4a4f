//! `aster sweep`: the convergence, stability and hard-case studies of
//! SDNV103 modelling B (docs/performance.md).
//!
//! Each sweep builds variants of B ([`case::CaseSpec`]), runs them
//! in-process one after the other, and writes into the output directory a
//! Markdown fragment, PNG plots and a CSV of the raw numbers; the fragment
//! is also spliced into docs/performance.md between its markers, so one
//! command regenerates a whole section.
//!
//! A sweep never stops on a bad case: a step that does not converge after
//! its cuts, a study error, a NaN or even an engine panic becomes a row
//! that says so. Runs are ordered from the cheapest, and a run predicted
//! (from the ones already done) or measured to exceed the per-run budget
//! is reported as skipped, so a sweep on a slow build ends in bounded time.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Duration;

pub mod case;
pub mod plot;
pub mod richardson;

use case::{CaseResult, CaseSpec, Scheme, TimeList};
use plot::{Figure, Series, Style};
use richardson::{extrapolate, power_law};

/// Public reference at 80 us (Stainier & Ponthot 1994, mean of 5 codes).
pub const REF_B1_DX: f64 = 3.87;
pub const REF_A2_DY: f64 = -13.46;

/// Which sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SweepKind {
    Convergence,
    Stability,
    HardCases,
}

impl SweepKind {
    /// The name used on the command line, in file names and in markers.
    pub fn name(self) -> &'static str {
        match self {
            SweepKind::Convergence => "convergence",
            SweepKind::Stability => "stability",
            SweepKind::HardCases => "hard-cases",
        }
    }
    fn file_stem(self) -> &'static str {
        match self {
            SweepKind::Convergence => "convergence",
            SweepKind::Stability => "stability",
            SweepKind::HardCases => "hard_cases",
        }
    }
}

/// Options of `aster sweep`.
#[derive(Debug, Clone)]
pub struct SweepOptions {
    /// Where the fragments, CSVs and PNGs go.
    pub out: PathBuf,
    /// The small version: 2x8 and 5x20 meshes, steps of 2 and 1 us.
    pub quick: bool,
    /// Longest acceptable run, seconds.
    pub budget: f64,
    /// The Markdown document whose section is replaced (between
    /// `<!-- sweep:NAME -->` and `<!-- /sweep:NAME -->`); None: none.
    pub doc: Option<PathBuf>,
    /// Where the cases' meshes, command files and logs go; None: a
    /// directory under the system temp dir, removed at the end.
    pub work: Option<PathBuf>,
}

/// What a sweep produced.
#[derive(Debug, Clone)]
pub struct SweepReport {
    pub results: Vec<CaseResult>,
    /// The Markdown fragment.
    pub markdown: String,
    /// Files written.
    pub files: Vec<PathBuf>,
}

/// Runs cases under the budget, learning the cost per step as it goes.
pub struct Runner {
    work: PathBuf,
    budget: f64,
    /// (estimated unknowns, wall seconds per step of the time list) of the
    /// runs so far: per step of the list, not per converged step, so the
    /// cuts a case needs are part of its cost.
    costs: Vec<(f64, f64)>,
    /// A run exceeded the budget: its thread still computes, so no other
    /// run is started (their timings would be meaningless anyway).
    timed_out: bool,
}

impl Runner {
    pub fn new(work: PathBuf, budget: f64) -> Runner {
        Runner {
            work,
            budget,
            costs: Vec::new(),
            timed_out: false,
        }
    }

    /// Predicted wall time of a case from the runs so far: a power law of
    /// the unknowns fitted on them (linear through one run), times steps.
    pub fn predict(&self, spec: &CaseSpec) -> Option<f64> {
        let n = estimated_unknowns(spec.n1, spec.n2);
        let per_step = match power_law(&self.costs) {
            // The slope clamped to [1, 3]: a sparse direct solve is no
            // cheaper than linear and, in 2D, no worse than cubic; noise
            // on small runs must not predict absurd costs.
            // Through the latest run, with the fitted (clamped) slope.
            Some((_, b)) => {
                let (x, y) = self.costs.last()?;
                y * (n / x).powf(b.clamp(1.0, 3.0))
            }
            None => {
                let &(n0, c0) = self.costs.last()?;
                c0 * n / n0
            }
        };
        Some(per_step * spec.time.steps() as f64)
    }

    /// Runs a case, or reports why it is not run.
    pub fn run(&mut self, spec: &CaseSpec, log: &mut dyn FnMut(&str)) -> CaseResult {
        if self.timed_out {
            let r = CaseResult::skipped(
                spec,
                "an earlier run exceeded the budget and still holds a core".into(),
            );
            log(&format!("  {:<48} skipped (after a timeout)", spec.slug()));
            return r;
        }
        if let Some(p) = self.predict(spec) {
            if p > self.budget {
                log(&format!(
                    "  {:<48} skipped: predicted {p:.0} s > budget {:.0} s",
                    spec.slug(),
                    self.budget
                ));
                return CaseResult::skipped(
                    spec,
                    format!(
                        "predicted {p:.0} s from the runs so far, over the {:.0} s budget",
                        self.budget
                    ),
                );
            }
        }
        let r = case::run_case(spec, &self.work, Duration::from_secs_f64(self.budget));
        if matches!(&r.outcome, case::Outcome::Skipped(_)) {
            self.timed_out = true;
        }
        if r.usable() {
            self.costs.push((
                estimated_unknowns(spec.n1, spec.n2),
                r.wall / spec.time.steps() as f64,
            ));
        }
        log(&format!(
            "  {:<48} {:>8.1} s  {}",
            spec.slug(),
            r.wall,
            r.what_happened()
        ));
        r
    }
}

/// About the number of equations of the axisymmetric Taylor case: two
/// dofs per node of the serendipity grid, the foundation being fixed.
pub fn estimated_unknowns(n1: usize, n2: usize) -> f64 {
    let nodes = (2 * n1 + 1) * (2 * n2 + 1) - n1 * n2;
    2.0 * nodes as f64
}

/// Runs a sweep and writes its outputs.
pub fn run_sweep(
    kind: SweepKind,
    opts: &SweepOptions,
    log: &mut dyn FnMut(&str),
) -> Result<SweepReport, String> {
    std::fs::create_dir_all(&opts.out)
        .map_err(|e| format!("cannot create '{}': {e}", opts.out.display()))?;
    let (work, temporary) = match &opts.work {
        Some(w) => (w.clone(), false),
        None => (
            std::env::temp_dir().join(format!(
                "aster-sweep-{}-{}",
                kind.file_stem(),
                std::process::id()
            )),
            true,
        ),
    };
    let mut runner = Runner::new(work.clone(), opts.budget);
    log(&format!(
        "aster sweep {}{}: cases in {}, budget {:.0} s per run",
        kind.name(),
        if opts.quick { " --quick" } else { "" },
        work.display(),
        opts.budget
    ));
    let mut report = match kind {
        SweepKind::Convergence => convergence(opts, &mut runner, log)?,
        SweepKind::Stability => stability(opts, &mut runner, log)?,
        SweepKind::HardCases => hard_cases(opts, &mut runner, log)?,
    };
    let header = provenance(kind, opts);
    report.markdown = format!("{header}{}", report.markdown);
    let frag = opts.out.join(format!("{}.md", kind.file_stem()));
    write(&frag, &report.markdown)?;
    report.files.push(frag);
    if let Some(doc) = &opts.doc {
        if splice_doc(doc, kind, &report.markdown)? {
            log(&format!(
                "updated the {} section of {}",
                kind.name(),
                doc.display()
            ));
        } else {
            log(&format!(
                "{} has no <!-- sweep:{} --> markers: the section was not spliced",
                doc.display(),
                kind.name()
            ));
        }
    }
    if temporary && !runner.timed_out {
        let _ = std::fs::remove_dir_all(&work);
    }
    Ok(report)
}

fn write(path: &Path, text: &str) -> Result<(), String> {
    std::fs::write(path, text).map_err(|e| format!("cannot write '{}': {e}", path.display()))
}

/// Replaces the text between the markers of `kind` in `doc`; false if the
/// markers are not there.
pub fn splice_doc(doc: &Path, kind: SweepKind, fragment: &str) -> Result<bool, String> {
    let Ok(text) = std::fs::read_to_string(doc) else {
        return Ok(false);
    };
    let open = format!("<!-- sweep:{} -->", kind.name());
    let close = format!("<!-- /sweep:{} -->", kind.name());
    let (Some(a), Some(b)) = (text.find(&open), text.find(&close)) else {
        return Ok(false);
    };
    if b < a {
        return Ok(false);
    }
    let new = format!(
        "{}{open}\n{}\n{}",
        &text[..a],
        fragment.trim_end(),
        &text[b..]
    );
    write(doc, &new)?;
    Ok(true)
}

/// The "generated by" line: command, date, commit, build.
fn provenance(kind: SweepKind, opts: &SweepOptions) -> String {
    let git = |args: &[&str]| {
        std::process::Command::new("git")
            .args(args)
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    let commit = git(&["rev-parse", "--short", "HEAD"]).unwrap_or_else(|| "unknown".into());
    let dirty =
        git(&["status", "--porcelain", "--untracked-files=no"]).is_some_and(|s| !s.is_empty());
    format!(
        "_Generated by `aster sweep {}{}` on {} (UTC) at commit {}{}, {} build, budget {:.0} s per run._\n\n",
        kind.name(),
        if opts.quick { " --quick" } else { "" },
        utc_date(),
        commit,
        if dirty { " with local changes" } else { "" },
        if cfg!(debug_assertions) { "debug" } else { "release" },
        opts.budget
    )
}

/// Today's date, from the system clock (days since 1970 to the civil
/// calendar, Howard Hinnant's algorithm).
fn utc_date() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs() as i64)
        .unwrap_or(0);
    civil(secs)
}

/// "YYYY-MM-DD hh:mm" of a Unix time.
fn civil(secs: i64) -> String {
    let z = secs.div_euclid(86_400) + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    let hm = secs.rem_euclid(86_400);
    format!(
        "{y:04}-{m:02}-{d:02} {:02}:{:02}",
        hm / 3600,
        hm % 3600 / 60
    )
}

/// A value for a table: blank when absent, "NaN" when not a number.
fn fmt_opt(v: Option<f64>, digits: usize) -> String {
    match v {
        None => "—".into(),
        Some(x) if x.is_nan() => "NaN".into(),
        Some(x) => format!("{x:.digits$}"),
    }
}

/// Wall time, blank for a run that was not started.
fn fmt_wall(r: &CaseResult) -> String {
    if r.wall > 0.0 {
        format!("{:.1}", r.wall)
    } else {
        "—".into()
    }
}

fn fmt_count(v: Option<usize>) -> String {
    v.map_or("—".into(), |x| x.to_string())
}

fn rel(a: Option<f64>, b: f64) -> Option<f64> {
    a.map(|a| (a - b).abs() / b.abs())
}

fn pct(v: Option<f64>) -> String {
    match v {
        None => "—".into(),
        Some(x) if x.is_nan() => "NaN".into(),
        Some(x) => format!("{:.2} %", 100.0 * x),
    }
}

/// Escapes a message for a Markdown table cell.
fn cell(s: &str) -> String {
    let s = s.replace('|', "\\|").replace('\n', " ");
    if s.chars().count() > 220 {
        format!("{}…", s.chars().take(220).collect::<String>())
    } else {
        s
    }
}

fn csv_field(s: &str) -> String {
    format!("\"{}\"", s.replace('"', "\"\"").replace('\n', " "))
}

fn csv_opt(v: Option<f64>) -> String {
    v.map_or(String::new(), |x| format!("{x:e}"))
}

/// The raw numbers of every case, one line each.
fn results_csv(results: &[CaseResult], osc: bool) -> String {
    let mut s = String::from(
        "n1,n2,time_list,e_n,scheme,outcome,unknowns,steps,newton_iterations,cuts,wall_s,loop_s,last_inst,b1_dx,a2_dy",
    );
    if osc {
        s.push_str(",vy_rms_osc,vy_max_osc,vy_max_abs");
    }
    s.push_str(",detail\n");
    for r in results {
        let sp = &r.spec;
        let _ = write!(
            s,
            "{},{},{},{:e},{},{},{},{},{},{},{:.3},{},{},{},{}",
            sp.n1,
            sp.n2,
            csv_field(&sp.time.label()),
            sp.e_n,
            csv_field(&sp.scheme.label()),
            r.outcome.short(),
            r.unknowns.map_or(String::new(), |x| x.to_string()),
            r.steps.map_or(String::new(), |x| x.to_string()),
            r.newton_iterations.map_or(String::new(), |x| x.to_string()),
            r.cuts.map_or(String::new(), |x| x.to_string()),
            r.wall,
            csv_opt(r.loop_wall),
            csv_opt(r.last_inst),
            csv_opt(r.b1_dx),
            csv_opt(r.a2_dy),
        );
        if osc {
            let o = oscillation(&r.a1_vy);
            let _ = write!(
                s,
                ",{},{},{}",
                csv_opt(o.map(|o| o.rms)),
                csv_opt(o.map(|o| o.max_dev)),
                csv_opt(o.map(|o| o.max_abs))
            );
        }
        let _ = writeln!(s, ",{}", csv_field(r.outcome.detail()));
    }
    s
}

// ------------------------------------------------------------------ convergence

/// SUBD_NIVEAU of the convergence runs. With B's default 3 a step can only
/// be cut down to dt/16, and on the 10 x 40 and 20 x 80 meshes Newton fails
/// at that level on the first contact steps (the edge node's contact
/// status flips from one iteration to the next); six levels (dt/1024) let
/// those runs through. It is a step-control setting only, the model is B's.
pub const CONVERGENCE_SUBD_NIVEAU: u32 = 6;

/// Meshes (n1, n2) and steps of the convergence sweep.
pub fn convergence_cases(quick: bool) -> Vec<CaseSpec> {
    let (meshes, dts): (&[(usize, usize)], &[f64]) = if quick {
        (&[(2, 8), (5, 20)], &[2e-6, 1e-6])
    } else {
        (
            &[(2, 8), (5, 20), (10, 40), (20, 80), (40, 160)],
            &[2e-6, 1e-6, 5e-7, 2.5e-7],
        )
    };
    let mut cases: Vec<CaseSpec> = meshes
        .iter()
        .flat_map(|&(n1, n2)| {
            dts.iter().map(move |&dt| CaseSpec {
                n1,
                n2,
                time: TimeList::Uniform { dt },
                subd_niveau: CONVERGENCE_SUBD_NIVEAU,
                ..CaseSpec::b()
            })
        })
        .collect();
    // Cheapest first, so the budget prediction learns before the big ones.
    cases.sort_by(|a, b| {
        let cost = |c: &CaseSpec| estimated_unknowns(c.n1, c.n2) * c.time.steps() as f64;
        cost(a).total_cmp(&cost(b))
    });
    cases
}

fn dt_of(spec: &CaseSpec) -> f64 {
    match spec.time {
        TimeList::Uniform { dt } => dt,
        TimeList::B => 5e-7,
    }
}

/// The analysis of a convergence sweep.
#[derive(Debug, Clone)]
pub struct ConvergenceAnalysis {
    /// Index of the finest usable run (finest mesh, then finest step).
    pub finest: Option<usize>,
    /// Richardson in the mesh size h = 1/n1 at `mesh_dt`, per quantity
    /// (B1 DX, A2 DY).
    pub mesh_dt: Option<f64>,
    pub mesh: [Result<richardson::Richardson, richardson::NotApplicable>; 2],
    /// Richardson in dt at the mesh `dt_mesh` (n1, n2).
    pub dt_mesh: Option<(usize, usize)>,
    pub dt: [Result<richardson::Richardson, richardson::NotApplicable>; 2],
    /// Wall time per step = a * unknowns^b.
    pub cost_law: Option<(f64, f64)>,
}

/// Finds the finest run, extrapolates in h and in dt, fits the cost law.
pub fn analyse_convergence(results: &[CaseResult]) -> ConvergenceAnalysis {
    let usable: Vec<(usize, &CaseResult)> = results
        .iter()
        .enumerate()
        .filter(|(_, r)| r.usable())
        .collect();
    let finest = usable
        .iter()
        .max_by(|a, b| {
            (a.1.spec.n1)
                .cmp(&b.1.spec.n1)
                .then(dt_of(&b.1.spec).total_cmp(&dt_of(&a.1.spec)))
        })
        .map(|x| x.0);
    let value =
        |r: &CaseResult, q: usize| if q == 0 { r.b1_dx } else { r.a2_dy }.unwrap_or(f64::NAN);
    // The finest dt with three usable meshes (else the finest dt at all).
    let mut dts: Vec<f64> = usable.iter().map(|(_, r)| dt_of(&r.spec)).collect();
    dts.sort_by(f64::total_cmp);
    dts.dedup();
    let meshes_at = |dt: f64| usable.iter().filter(|(_, r)| dt_of(&r.spec) == dt).count();
    let mesh_dt = dts
        .iter()
        .copied()
        .find(|&dt| meshes_at(dt) >= 3)
        .or_else(|| dts.first().copied());
    // (x, quantity q) over the usable runs that `keep` selects.
    let series = |keep: &dyn Fn(&CaseResult) -> bool,
                  x: fn(&CaseResult) -> f64,
                  q: usize|
     -> Vec<(f64, f64)> {
        usable
            .iter()
            .filter(|(_, r)| keep(r))
            .map(|(_, r)| (x(r), value(r, q)))
            .collect()
    };
    let mesh_series = |q: usize| {
        series(
            &|r| Some(dt_of(&r.spec)) == mesh_dt,
            |r| 1.0 / r.spec.n1 as f64,
            q,
        )
    };
    let mut ns: Vec<(usize, usize)> = usable.iter().map(|(_, r)| (r.spec.n1, r.spec.n2)).collect();
    ns.sort();
    ns.dedup();
    let dts_at = |m: (usize, usize)| {
        usable
            .iter()
            .filter(|(_, r)| (r.spec.n1, r.spec.n2) == m)
            .count()
    };
    let dt_mesh = ns
        .iter()
        .rev()
        .copied()
        .find(|&m| dts_at(m) >= 3)
        .or_else(|| ns.last().copied());
    let dt_series = |q: usize| {
        series(
            &|r| Some((r.spec.n1, r.spec.n2)) == dt_mesh,
            |r| dt_of(&r.spec) * 1e6,
            q,
        )
    };
    let costs: Vec<(f64, f64)> = results
        .iter()
        .filter_map(|r| Some((r.unknowns? as f64, r.wall_per_step()?)))
        .collect();
    ConvergenceAnalysis {
        finest,
        mesh_dt,
        mesh: [extrapolate(&mesh_series(0)), extrapolate(&mesh_series(1))],
        dt_mesh,
        dt: [extrapolate(&dt_series(0)), extrapolate(&dt_series(1))],
        cost_law: power_law(&costs),
    }
}

fn convergence(
    opts: &SweepOptions,
    runner: &mut Runner,
    log: &mut dyn FnMut(&str),
) -> Result<SweepReport, String> {
    let results: Vec<CaseResult> = convergence_cases(opts.quick)
        .iter()
        .map(|c| runner.run(c, log))
        .collect();
    let an = analyse_convergence(&results);
    let mut files = Vec::new();
    let csv = opts.out.join("convergence.csv");
    write(&csv, &results_csv(&results, false))?;
    files.push(csv);

    let fin = an.finest.map(|i| &results[i]);
    let (fdx, fdy) = fin.map_or((None, None), |f| (f.b1_dx, f.a2_dy));
    let err_finest = |r: &CaseResult| -> Option<f64> {
        let (a, b) = (rel(r.b1_dx, fdx?)?, rel(r.a2_dy, fdy?)?);
        Some(a.max(b))
    };
    let mut md = String::new();
    let _ = writeln!(
        md,
        "Uniform steps of dt from the first contact (after B's free-flight step to -1e-7), \
         B's model otherwise (E_N 1e10, NEWMARK 0.49/0.9); a failed step may be cut by 4 \
         down to SUBD_NIVEAU = {CONVERGENCE_SUBD_NIVEAU} (B: 3). Errors are relative, the larger \
         of B1 DX and A2 DY; the finest run is {}.\n",
        fin.map_or("none (no run reached 80 us)".into(), |f| format!(
            "{} x {} at dt = {} us",
            f.spec.n1,
            f.spec.n2,
            dt_of(&f.spec) * 1e6
        ))
    );
    md.push_str("| n1 x n2 | dt (us) | unknowns | steps | Newton its | cuts | wall (s) | B1 DX | A2 DY | err vs finest | err vs reference (DX, DY) | outcome |\n");
    md.push_str("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    // Runs went cheapest first; the table reads by mesh, then step.
    let mut shown: Vec<&CaseResult> = results.iter().collect();
    shown.sort_by(|a, b| {
        (a.spec.n1, a.spec.n2)
            .cmp(&(b.spec.n1, b.spec.n2))
            .then(dt_of(&b.spec).total_cmp(&dt_of(&a.spec)))
    });
    for r in shown {
        let _ = writeln!(
            md,
            "| {} x {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {}, {} | {} |",
            r.spec.n1,
            r.spec.n2,
            dt_of(&r.spec) * 1e6,
            fmt_count(r.unknowns),
            fmt_count(r.steps),
            fmt_count(r.newton_iterations),
            fmt_count(r.cuts),
            fmt_wall(r),
            fmt_opt(r.b1_dx, 4),
            fmt_opt(r.a2_dy, 4),
            if r.usable() {
                pct(err_finest(r))
            } else {
                "—".into()
            },
            pct(rel(r.b1_dx, REF_B1_DX)),
            pct(rel(r.a2_dy, REF_A2_DY)),
            cell(&r.what_happened()),
        );
    }
    md.push('\n');
    // Converged values.
    let names = ["B1 DX", "A2 DY"];
    let refs = [REF_B1_DX, REF_A2_DY];
    let finest_vals = [fdx, fdy];
    md.push_str("Richardson extrapolation (three finest points; observed order p; error bar = |finest − extrapolated|):\n\n");
    md.push_str("| quantity | finest | in h = 1/n1 | in dt | finest ± error bar | reference |\n|---|---|---|---|---|---|\n");
    for q in 0..2 {
        let show = |r: &Result<richardson::Richardson, richardson::NotApplicable>| match r {
            Ok(x) => format!("{:.4} (p = {:.2})", x.value, x.order),
            Err(e) => format!("n/a: {e}"),
        };
        // Richardson's bar where it applies, else the spread of the three
        // finest solutions (a cruder bar, flagged as such).
        let part = |r: &Result<richardson::Richardson, richardson::NotApplicable>| match r {
            Ok(x) => Some((x.error_bar, true)),
            Err(richardson::NotApplicable::NotMonotone { spread })
            | Err(richardson::NotApplicable::OrderOutOfRange { spread, .. }) => {
                Some((*spread, false))
            }
            Err(richardson::NotApplicable::TooFew(_)) => None,
        };
        let parts: Vec<(f64, bool)> = [part(&an.mesh[q]), part(&an.dt[q])]
            .into_iter()
            .flatten()
            .collect();
        let bar = (!parts.is_empty()).then(|| {
            (
                parts.iter().map(|p| p.0).sum::<f64>(),
                parts.iter().all(|p| p.1),
                parts.len(),
            )
        });
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} |",
            names[q],
            fmt_opt(finest_vals[q], 4),
            show(&an.mesh[q]),
            show(&an.dt[q]),
            match (finest_vals[q], bar) {
                (Some(v), Some((b, rich, n))) => format!(
                    "**{v:.3} ± {b:.3}**{}{}",
                    if rich {
                        ""
                    } else {
                        " (spread where Richardson does not apply)"
                    },
                    if n < 2 { " (one direction only)" } else { "" }
                ),
                (Some(v), None) => format!("{v:.3} (no error bar: too few runs)"),
                _ => "—".into(),
            },
            refs[q]
        );
    }
    let _ = writeln!(
        md,
        "\nThe extrapolation in h uses the runs at dt = {} us, the one in dt the {} mesh; \
         the error bar of the finest value adds the two.\n",
        an.mesh_dt.map_or("—".into(), |d| format!("{}", d * 1e6)),
        an.dt_mesh.map_or("—".into(), |(a, b)| format!("{a} x {b}"))
    );

    // Plots.
    let mut plots_ok = true;
    let mut by_dt: Vec<f64> = results.iter().map(|r| dt_of(&r.spec)).collect();
    by_dt.sort_by(|a, b| b.total_cmp(a));
    by_dt.dedup();
    let err_fig = Figure {
        title: "Taylor bar B: error against wall time".into(),
        x_label: "wall time of the run (s)".into(),
        y_label: "relative error vs the finest run".into(),
        log_x: true,
        log_y: true,
        series: by_dt
            .iter()
            .map(|&dt| Series {
                label: format!("dt = {} us", dt * 1e6),
                points: results
                    .iter()
                    .filter(|r| dt_of(&r.spec) == dt && r.usable())
                    .filter_map(|r| Some((r.wall, err_finest(r)?)))
                    .collect(),
                style: Style::Points,
            })
            .collect(),
        annotations: results
            .iter()
            .filter(|r| r.usable())
            .filter_map(|r| {
                Some((
                    (r.wall, err_finest(r)?),
                    format!("{}x{}", r.spec.n1, r.spec.n2),
                ))
            })
            .collect(),
        y_range: None,
    };
    let costs: Vec<(f64, f64)> = results
        .iter()
        .filter_map(|r| Some((r.unknowns? as f64, r.wall_per_step()?)))
        .collect();
    let mut cost_series = vec![Series {
        label: "runs".into(),
        points: costs.clone(),
        style: Style::Points,
    }];
    if let Some((a, b)) = an.cost_law {
        let (lo, hi) = costs.iter().fold((f64::INFINITY, 0.0_f64), |(l, h), p| {
            (l.min(p.0), h.max(p.0))
        });
        cost_series.push(Series {
            label: format!("fit: {a:.2e} N^{b:.2}"),
            points: vec![(lo, a * lo.powf(b)), (hi, a * hi.powf(b))],
            style: Style::Thin,
        });
    }
    let cost_fig = Figure {
        title: "Taylor bar B: cost of a time step".into(),
        x_label: "unknowns N".into(),
        y_label: "wall time per step (s)".into(),
        log_x: true,
        log_y: true,
        series: cost_series,
        annotations: Vec::new(),
        y_range: None,
    };
    if draw_figures(
        &[
            (&err_fig, "convergence_error_vs_wall.png"),
            (&cost_fig, "convergence_wall_per_step.png"),
        ],
        &opts.out,
        (900, 620),
        &mut files,
        log,
    )
    .is_some()
    {
        plots_ok = false;
    }
    let rel_out = image_prefix(opts);
    let _ = writeln!(
        md,
        "Wall time per step against unknowns, log-log; least-squares slope {}:\n\n\
         ![wall time per step against unknowns]({rel_out}convergence_wall_per_step.png)\n\n\
         Error against wall time (each point a mesh/step pair):\n\n\
         ![error against wall time]({rel_out}convergence_error_vs_wall.png)\n\n\
         Raw numbers: [convergence.csv]({rel_out}convergence.csv).{}",
        an.cost_law
            .map_or("— (fewer than two sizes)".into(), |(_, b)| format!(
                "**{b:.2}**"
            )),
        if plots_ok {
            ""
        } else {
            " (the plots could not be drawn: see the sweep's log)"
        }
    );
    Ok(SweepReport {
        results,
        markdown: md,
        files,
    })
}

/// How the fragment refers to the output directory: relative to the
/// document when the output is next to it.
fn image_prefix(opts: &SweepOptions) -> String {
    let doc_dir = opts
        .doc
        .as_ref()
        .and_then(|d| d.parent())
        .map(Path::to_path_buf)
        .unwrap_or_else(|| opts.out.parent().map(Path::to_path_buf).unwrap_or_default());
    match opts.out.strip_prefix(&doc_dir) {
        Ok(rel) if !rel.as_os_str().is_empty() => format!("{}/", rel.display()),
        Ok(_) => String::new(),
        Err(_) => format!("{}/", opts.out.display()),
    }
}

// ------------------------------------------------------------------ stability

/// The oscillation of a velocity history after the impact transient.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Oscillation {
    /// RMS of v minus its 5 us centred moving mean, over 10..80 us.
    pub rms: f64,
    /// Largest |v minus its moving mean| over 10..80 us.
    pub max_dev: f64,
    /// Largest |v| over 10..80 us.
    pub max_abs: f64,
}

/// Measures the oscillation of (t, v) samples over 10..80 us. The history
/// is resampled every 0.1 us by linear interpolation, so lists of any step
/// give comparable numbers. None without samples over that range or with
/// a non-finite sample.
pub fn oscillation(samples: &[(f64, f64)]) -> Option<Oscillation> {
    let (t0, t1, h, half) = (1.0e-5, case::T_END, 1.0e-7, 2.5e-6);
    let pts: Vec<(f64, f64)> = samples.to_vec();
    if pts.len() < 2
        || pts.iter().any(|p| !p.1.is_finite())
        || pts[0].0 > t0 + 1e-12
        || pts[pts.len() - 1].0 < t1 - 1e-12
    {
        return None;
    }
    let interp = |t: f64| -> f64 {
        let k = pts.partition_point(|p| p.0 < t).clamp(1, pts.len() - 1);
        let (a, b) = (pts[k - 1], pts[k]);
        if b.0 == a.0 {
            b.1
        } else {
            a.1 + (b.1 - a.1) * (t - a.0) / (b.0 - a.0)
        }
    };
    let n = ((t1 - t0) / h).round() as usize;
    let grid: Vec<f64> = (0..=n).map(|i| interp(t0 + i as f64 * h)).collect();
    let w = (half / h).round() as usize;
    let mut sum2 = 0.0;
    let mut max_dev = 0.0_f64;
    let mut max_abs = 0.0_f64;
    for i in 0..=n {
        let (lo, hi) = (i.saturating_sub(w), (i + w).min(n));
        let mean = grid[lo..=hi].iter().sum::<f64>() / (hi - lo + 1) as f64;
        let d = grid[i] - mean;
        sum2 += d * d;
        max_dev = max_dev.max(d.abs());
        max_abs = max_abs.max(grid[i].abs());
    }
    Some(Oscillation {
        rms: (sum2 / (n + 1) as f64).sqrt(),
        max_dev,
        max_abs,
    })
}

/// The four schemes of the seed's section 3.5 comparison.
pub fn stability_schemes() -> [Scheme; 4] {
    [
        Scheme::TRAPEZOIDAL,
        Scheme::B,
        Scheme::Hht {
            alpha: -0.6,
            modi_equi: false,
        },
        Scheme::Hht {
            alpha: -0.6,
            modi_equi: true,
        },
    ]
}

fn stability(
    opts: &SweepOptions,
    runner: &mut Runner,
    log: &mut dyn FnMut(&str),
) -> Result<SweepReport, String> {
    let (n1, n2) = if opts.quick { (2, 8) } else { (5, 20) };
    let results: Vec<CaseResult> = stability_schemes()
        .iter()
        .map(|&scheme| {
            runner.run(
                &CaseSpec {
                    n1,
                    n2,
                    scheme,
                    ..CaseSpec::b()
                },
                log,
            )
        })
        .collect();
    let mut files = Vec::new();
    let csv = opts.out.join("stability.csv");
    write(&csv, &results_csv(&results, true))?;
    files.push(csv);
    let mut hist = String::from("scheme,inst,a1_vy\n");
    for r in &results {
        for (t, v) in &r.a1_vy {
            let _ = writeln!(hist, "{},{t:e},{v:e}", csv_field(&r.spec.scheme.label()));
        }
    }
    let hcsv = opts.out.join("stability_a1_vy.csv");
    write(&hcsv, &hist)?;
    files.push(hcsv);
    let fig = Figure {
        title: format!("Taylor bar B ({n1} x {n2}): velocity VY of A1, centre of the impact face"),
        x_label: "time (us)".into(),
        y_label: "VY of A1 (mm/s)".into(),
        log_x: false,
        log_y: false,
        series: results
            .iter()
            .map(|r| Series {
                label: r.spec.scheme.label(),
                points: r.a1_vy.iter().map(|&(t, v)| (t * 1e6, v)).collect(),
                style: Style::Line,
            })
            .collect(),
        annotations: Vec::new(),
        y_range: None,
    };
    // The undamped scheme rings orders of magnitude above the others: a
    // second plot zooms on the dissipative ones (the others clamped).
    let zoom = results
        .iter()
        .filter(|r| r.spec.scheme != Scheme::TRAPEZOIDAL && r.usable())
        .flat_map(|r| r.a1_vy.iter().map(|p| p.1.abs()))
        .filter(|v| v.is_finite())
        .fold(0.0_f64, f64::max);
    let zoom_fig = Figure {
        title: format!(
            "VY of A1 ({n1} x {n2}), zoom on the completed dissipative schemes (others clamped)"
        ),
        y_range: (zoom > 0.0).then_some((-1.2 * zoom, 1.2 * zoom)),
        ..fig.clone()
    };
    let plot_note = draw_figures(
        &[
            (&fig, "stability_a1_vy.png"),
            (&zoom_fig, "stability_a1_vy_zoom.png"),
        ],
        &opts.out,
        (1000, 620),
        &mut files,
        log,
    )
    .map_or(String::new(), |e| {
        format!(" (the plots could not be drawn: {e})")
    });
    let mut md = String::new();
    let _ = writeln!(
        md,
        "Mesh {n1} x {n2}, B's time list and penalty; only the time scheme changes. \
         The oscillation is measured on VY of A1 over 10..80 us, resampled every 0.1 us: \
         RMS and largest deviation from its centred 5 us moving mean, and the largest |VY|.\n"
    );
    md.push_str("| scheme | outcome | steps | Newton its | cuts | wall (s) | B1 DX | A2 DY | RMS osc. (mm/s) | max osc. (mm/s) | max \\|VY\\| (mm/s) |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for r in &results {
        let o = oscillation(&r.a1_vy);
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.spec.scheme.label(),
            cell(&r.what_happened()),
            fmt_count(r.steps),
            fmt_count(r.newton_iterations),
            fmt_count(r.cuts),
            fmt_wall(r),
            fmt_opt(r.b1_dx, 4),
            fmt_opt(r.a2_dy, 4),
            fmt_opt(o.map(|o| o.rms), 0),
            fmt_opt(o.map(|o| o.max_dev), 0),
            fmt_opt(o.map(|o| o.max_abs), 0),
        );
    }
    let p = image_prefix(opts);
    let _ = writeln!(
        md,
        "\n![VY of A1 for four time schemes]({p}stability_a1_vy.png){plot_note}\n\n\
         ![the same, zoomed on the dissipative schemes]({p}stability_a1_vy_zoom.png)\n\n\
         Raw numbers: [stability.csv]({p}stability.csv), histories [stability_a1_vy.csv]({p}stability_a1_vy.csv)."
    );
    Ok(SweepReport {
        results,
        markdown: md,
        files,
    })
}

// ------------------------------------------------------------------ hard cases

/// The hard cases: (family, case).
pub fn hard_case_list(quick: bool) -> Vec<(&'static str, CaseSpec)> {
    let (n1, n2) = if quick { (2, 8) } else { (5, 20) };
    let base = CaseSpec {
        n1,
        n2,
        ..CaseSpec::b()
    };
    let exps: Vec<i32> = if quick {
        vec![5, 10, 14]
    } else {
        (5..=14).collect()
    };
    let mut v: Vec<(&'static str, CaseSpec)> = exps
        .iter()
        .map(|&e| {
            (
                "penalty E_N",
                CaseSpec {
                    e_n: 10f64.powi(e),
                    ..base.clone()
                },
            )
        })
        .collect();
    for dt in [2e-6, 4e-6] {
        v.push((
            "large steps",
            CaseSpec {
                time: TimeList::Uniform { dt },
                ..base.clone()
            },
        ));
    }
    v.push((
        "no numerical damping",
        CaseSpec {
            scheme: Scheme::TRAPEZOIDAL,
            ..base.clone()
        },
    ));
    v
}

fn hard_cases(
    opts: &SweepOptions,
    runner: &mut Runner,
    log: &mut dyn FnMut(&str),
) -> Result<SweepReport, String> {
    let list = hard_case_list(opts.quick);
    let results: Vec<CaseResult> = list.iter().map(|(_, c)| runner.run(c, log)).collect();
    let mut files = Vec::new();
    let csv = opts.out.join("hard_cases.csv");
    write(&csv, &results_csv(&results, true))?;
    files.push(csv);
    let (n1, n2) = (list[0].1.n1, list[0].1.n2);
    let mut md = String::new();
    let _ = writeln!(
        md,
        "Mesh {n1} x {n2}; B's time list, E_N 1e10 and NEWMARK 0.49/0.9 unless the row says \
         otherwise. Oscillation as in the stability table (VY of A1, 10..80 us).\n"
    );
    md.push_str("| family | E_N | time list | scheme | what happened | steps | Newton its | cuts | B1 DX | A2 DY | max osc. VY A1 (mm/s) | wall (s) |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for ((family, c), r) in list.iter().zip(&results) {
        let o = oscillation(&r.a1_vy);
        let _ = writeln!(
            md,
            "| {family} | {:.0e} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            c.e_n,
            c.time.label(),
            c.scheme.label(),
            cell(&r.what_happened()),
            fmt_count(r.steps),
            fmt_count(r.newton_iterations),
            fmt_count(r.cuts),
            fmt_opt(r.b1_dx, 4),
            fmt_opt(r.a2_dy, 4),
            fmt_opt(o.map(|o| o.max_dev), 0),
            fmt_wall(r),
        );
    }
    let p = image_prefix(opts);
    let _ = writeln!(md, "\nRaw numbers: [hard_cases.csv]({p}hard_cases.csv).");
    Ok(SweepReport {
        results,
        markdown: md,
        files,
    })
}

/// Draws each figure into `out/name`, adding the files drawn to `files`;
/// a figure that cannot be drawn is logged as a warning, not a failure of
/// the sweep. Returns the last error, if any.
fn draw_figures(
    figs: &[(&Figure, &str)],
    out: &Path,
    size: (u32, u32),
    files: &mut Vec<PathBuf>,
    log: &mut dyn FnMut(&str),
) -> Option<String> {
    let mut last = None;
    for (fig, name) in figs {
        let png = out.join(name);
        match plot::draw(fig, &png, size) {
            Ok(()) => files.push(png),
            Err(e) => {
                log(&format!("warning: {e}"));
                last = Some(e);
            }
        }
    }
    last
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Synthetic runs following exact power laws, f = f0 + C h^2 along the
    /// meshes at the finest step and g = g0 + D dt along the steps on the
    /// finest mesh: the analysis picks those two series (and not the
    /// others, which are offset) and recovers f0, g0 and the orders.
    #[test]
    fn convergence_analysis_picks_the_series_and_extrapolates() {
        let run = |n1: usize, dt: f64, dx: f64, dy: f64| {
            let mut r = CaseResult::skipped(
                &CaseSpec {
                    n1,
                    n2: 4 * n1,
                    time: TimeList::Uniform { dt },
                    ..CaseSpec::b()
                },
                String::new(),
            );
            r.outcome = case::Outcome::Completed;
            (r.b1_dx, r.a2_dy) = (Some(dx), Some(dy));
            r
        };
        let mut results = Vec::new();
        for n1 in [2, 5, 10] {
            let h = 1.0 / n1 as f64;
            for dt in [1e-6, 5e-7, 2.5e-7] {
                let us = dt * 1e6;
                // Mesh law at the finest step, step law on the finest mesh;
                // an offset elsewhere that must not enter either series.
                let off = if dt == 2.5e-7 || n1 == 10 { 0.0 } else { 0.3 };
                let step = if n1 == 10 { us - 0.25 } else { 0.0 };
                let dx = 3.0 + 2.0 * h * h + 0.5 * step;
                let dy = -12.0 - h * h - 0.2 * step;
                results.push(run(n1, dt, dx + off, dy - off));
            }
        }
        let an = analyse_convergence(&results);
        let fin = &results[an.finest.unwrap()];
        assert_eq!((fin.spec.n1, dt_of(&fin.spec)), (10, 2.5e-7));
        assert_eq!(an.mesh_dt, Some(2.5e-7));
        assert_eq!(an.dt_mesh, Some((10, 40)));
        let close = |r: &Result<richardson::Richardson, richardson::NotApplicable>,
                     value: f64,
                     order: f64| {
            let r = r.as_ref().unwrap();
            assert!((r.value - value).abs() < 1e-9, "{r:?} vs {value}");
            assert!((r.order - order).abs() < 1e-6, "{r:?} vs order {order}");
        };
        close(&an.mesh[0], 3.0, 2.0);
        close(&an.mesh[1], -12.0, 2.0);
        // On 10 x 40: 3.02 + 0.5 (dt - 0.25) -> 2.895; -12.01 - 0.2 (dt - 0.25) -> -11.96.
        close(&an.dt[0], 2.895, 1.0);
        close(&an.dt[1], -11.96, 1.0);
    }

    /// A sine of 1 mm/s amplitude and 2 us period on a constant: the
    /// centred 5 us mean of sin(wt) is sin(wt) sin(wW/2)/(wW/2), here
    /// 1/(2.5 pi) of it, so the deviation is a sine of amplitude
    /// 1 - 1/(2.5 pi) and RMS that over sqrt 2 (up to the truncated
    /// windows at the ends, 2.5 us out of 70).
    #[test]
    fn oscillation_of_a_sine_is_its_amplitude() {
        let s: Vec<(f64, f64)> = (0..=800)
            .map(|i| {
                let t = i as f64 * 1e-7;
                (t, 100.0 + (2.0 * std::f64::consts::PI * t / 2e-6).sin())
            })
            .collect();
        let o = oscillation(&s).unwrap();
        let amp = 1.0 - 1.0 / (2.5 * std::f64::consts::PI);
        assert!((o.rms - amp / 2f64.sqrt()).abs() < 0.01, "{o:?}");
        assert!(o.max_dev >= amp - 1e-9 && o.max_dev <= 1.0 + 1e-9, "{o:?}");
        assert!((o.max_abs - 101.0).abs() < 1e-9, "{o:?}");
        let flat: Vec<(f64, f64)> = s.iter().map(|&(t, _)| (t, 5.0)).collect();
        assert!(oscillation(&flat).unwrap().rms < 1e-12);
        let mut nan = s.clone();
        nan[400].1 = f64::NAN;
        assert_eq!(oscillation(&nan), None);
    }

    /// Costs linear in N (1e-4 s per unknown and step): a 40 x 160 case
    /// (39202 estimated unknowns, 42 steps of 2 us) is predicted at
    /// 164.6 s, so a 100 s budget skips it without running it.
    #[test]
    fn runner_skips_a_case_predicted_over_the_budget() {
        let mut r = Runner::new(std::env::temp_dir().join("aster-never-used"), 100.0);
        r.costs = vec![(100.0, 0.01), (1000.0, 0.1)];
        let big = CaseSpec {
            n1: 40,
            n2: 160,
            time: TimeList::Uniform { dt: 2e-6 },
            ..CaseSpec::b()
        };
        assert_eq!(estimated_unknowns(40, 160), 39202.0);
        let p = r.predict(&big).unwrap();
        assert!((p - 39202.0 * 1e-4 * 42.0).abs() < 1e-6, "{p}");
        let res = r.run(&big, &mut |_| {});
        assert!(
            matches!(&res.outcome, case::Outcome::Skipped(w) if w.contains("predicted 165 s")),
            "{:?}",
            res.outcome
        );
        assert!(!r.work.exists());
    }

    #[test]
    fn dates_follow_the_civil_calendar() {
        // `date -u -d @1700000000` and a leap day.
        assert_eq!(civil(1_700_000_000), "2023-11-14 22:13");
        assert_eq!(civil(951_782_400), "2000-02-29 00:00");
        assert_eq!(civil(0), "1970-01-01 00:00");
    }

    #[test]
    fn splice_replaces_only_the_marked_section() {
        let dir = std::env::temp_dir().join(format!("aster-splice-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let doc = dir.join("p.md");
        std::fs::write(
            &doc,
            "# P\n## Bench\nkeep\n<!-- sweep:stability -->\nold\n<!-- /sweep:stability -->\nafter\n",
        )
        .unwrap();
        assert!(splice_doc(&doc, SweepKind::Stability, "new table\n").unwrap());
        let t = std::fs::read_to_string(&doc).unwrap();
        assert_eq!(
            t,
            "# P\n## Bench\nkeep\n<!-- sweep:stability -->\nnew table\n<!-- /sweep:stability -->\nafter\n"
        );
        assert!(!splice_doc(&doc, SweepKind::Convergence, "x").unwrap());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
