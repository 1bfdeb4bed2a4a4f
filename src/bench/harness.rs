//! `aster bench STUDY.comm`: runs a study several times in this process
//! and reports the wall time, the time per phase, the Newton and step
//! counts and the peak memory, as a table and as JSON so that runs of
//! different versions can be compared.
//!
//! Each run goes through [`driver::run_file`], exactly as `aster run`
//! (same .export and `--unit` resolution), with every output file sent
//! to a temporary directory so that benchmarking leaves the study's
//! directory untouched (kept, and named, when a run fails or its checks
//! do, so that its .mess can be read).

use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use super::json;
use crate::profile::{Counter, Phase, Profile, GLOBAL};
use crate::run::driver::{self, RunOptions, EXIT_OK, EXIT_USAGE};

/// Options of `aster bench`.
#[derive(Debug, Clone)]
pub struct BenchOptions {
    /// The study and its units, as for `aster run` (`out_dir` and
    /// `verbose` are ignored: outputs go to a temporary directory).
    pub run: RunOptions,
    /// How many times the study is run.
    pub runs: usize,
    /// Where to write the JSON report.
    pub json: Option<PathBuf>,
    /// Size of the rayon thread pool (None: rayon's default).
    pub threads: Option<usize>,
}

/// The measurements of one run.
#[derive(Debug, Clone, Copy)]
struct RunSample {
    wall: f64,
    profile: Profile,
    /// VmHWM after the run, in bytes.
    peak: Option<u64>,
}

/// A table row: a per-run quantity in seconds.
struct Row {
    key: &'static str,
    label: &'static str,
    per_run: Vec<f64>,
    calls: Option<Vec<u64>>,
}

/// `aster bench`: returns the exit code (that of the first failing run,
/// if any). A run that reaches the end of the study but has NOOK checks is
/// still measured: the table is printed, followed by a line saying the
/// checks failed, and the exit code is that of `aster run` (1).
pub fn bench(opts: &BenchOptions, out: &mut dyn Write) -> i32 {
    if opts.runs == 0 {
        let _ = writeln!(out, "error: --runs must be at least 1");
        return EXIT_USAGE;
    }
    if let Some(path) = &opts.json {
        if let Err(message) = json_target_ok(path) {
            let _ = writeln!(out, "error: --json: {message}");
            return EXIT_USAGE;
        }
    }
    let files = match driver::export_files(&opts.run) {
        Ok(f) => f,
        Err(message) => {
            let _ = write!(out, "{message}");
            return EXIT_USAGE;
        }
    };
    let tmp = std::env::temp_dir().join(format!("aster-bench-{}", std::process::id()));
    if let Err(e) = std::fs::create_dir_all(&tmp) {
        let _ = writeln!(out, "error: cannot create '{}': {e}", tmp.display());
        return EXIT_USAGE;
    }
    // Result files of the .export are redirected to the temporary
    // directory (a data+result file is copied there first); explicit
    // --unit mappings come last and win, as in `aster run`.
    let mut units = Vec::new();
    for f in files.iter().filter(|f| f.result) {
        let name = f
            .path
            .file_name()
            .map(|n| n.to_os_string())
            .unwrap_or_else(|| format!("fort.{}", f.unit).into());
        let to = tmp.join(name);
        if f.data && f.path.is_file() {
            if let Err(e) = std::fs::copy(&f.path, &to) {
                let _ = writeln!(out, "error: cannot copy '{}': {e}", f.path.display());
                let _ = std::fs::remove_dir_all(&tmp);
                return EXIT_USAGE;
            }
        }
        units.push((f.unit, to));
    }
    units.extend(opts.run.units.iter().cloned());
    let run_opts = RunOptions {
        units,
        out_dir: Some(tmp.clone()),
        verbose: false,
        ..opts.run.clone()
    };
    let pool = match rayon::ThreadPoolBuilder::new()
        .num_threads(opts.threads.unwrap_or(0))
        .build()
    {
        Ok(p) => p,
        Err(e) => {
            let _ = writeln!(out, "error: cannot start the thread pool: {e}");
            let _ = std::fs::remove_dir_all(&tmp);
            return EXIT_USAGE;
        }
    };
    let threads = pool.current_num_threads();
    let study = opts.run.comm.display().to_string();
    let _ = writeln!(
        out,
        "aster bench {study}: {} run{}, {threads} thread{}",
        opts.runs,
        if opts.runs == 1 { "" } else { "s" },
        if threads == 1 { "" } else { "s" }
    );
    let mut samples = Vec::with_capacity(opts.runs);
    let mut peak_reset = true;
    // (run number, NOOK count, exit code) of the runs whose checks failed.
    let mut nook_runs: Vec<(usize, usize, i32)> = Vec::new();
    for i in 0..opts.runs {
        peak_reset &= reset_peak_memory();
        let mut log = Vec::new();
        GLOBAL.reset();
        GLOBAL.set_enabled(true);
        let t0 = Instant::now();
        let outcome = pool.install(|| driver::run_file_outcome(&run_opts, &mut log));
        let wall = t0.elapsed().as_secs_f64();
        GLOBAL.set_enabled(false);
        let profile = GLOBAL.snapshot();
        let code = outcome.code;
        let checks_only = outcome.completed && outcome.nook > 0;
        if code != EXIT_OK && !checks_only {
            let _ = out.write_all(&log);
            let _ = writeln!(out, "run {} failed (exit code {code})", i + 1);
            keep_outputs(&tmp, i + 1, out);
            return code;
        }
        if checks_only {
            nook_runs.push((i + 1, outcome.nook, code));
        }
        let _ = writeln!(
            out,
            "  run {:>2}: {wall:>9.3} s{}",
            i + 1,
            if checks_only {
                format!(" (checks failed: {} NOOK)", outcome.nook)
            } else {
                String::new()
            }
        );
        let _ = out.flush();
        samples.push(RunSample {
            wall,
            profile,
            peak: peak_memory(),
        });
    }
    // The outputs are kept when checks failed (said after that line).
    if nook_runs.is_empty() {
        let _ = std::fs::remove_dir_all(&tmp);
    }

    let report = Report {
        study,
        threads,
        nook: nook_runs.iter().map(|r| r.1).collect(),
        peak_reset,
        rows: rows(&samples),
        samples,
    };
    let _ = write!(out, "{}", report.table());
    if let Some(path) = &opts.json {
        if let Err(e) = std::fs::write(path, report.json()) {
            let _ = writeln!(out, "error: cannot write '{}': {e}", path.display());
            if !nook_runs.is_empty() {
                keep_outputs(&tmp, opts.runs, out);
            }
            return EXIT_USAGE;
        }
        let _ = writeln!(out, "JSON report written to {}", path.display());
    }
    if let Some(&(_, nook, code)) = nook_runs.first() {
        let runs: Vec<String> = nook_runs.iter().map(|r| r.0.to_string()).collect();
        let _ = writeln!(
            out,
            "CHECKS FAILED: {nook} NOOK test{} (run{} {}); the study ran to its end and the \
times above are measured, but its results do not pass its checks",
            if nook == 1 { "" } else { "s" },
            if runs.len() == 1 { "" } else { "s" },
            runs.join(", ")
        );
        keep_outputs(&tmp, opts.runs, out);
        return code;
    }
    EXIT_OK
}

/// Where `--json` will write: checked before the runs, so that a path
/// that cannot be written is a usage error at once rather than after
/// minutes of measurement. The file itself is written at the end.
fn json_target_ok(path: &std::path::Path) -> Result<(), String> {
    if path.is_dir() {
        return Err(format!("'{}' is a directory, not a file", path.display()));
    }
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => std::path::Path::new("."),
    };
    if !parent.is_dir() {
        return Err(format!(
            "cannot write '{}': the directory '{}' does not exist",
            path.display(),
            parent.display()
        ));
    }
    Ok(())
}

/// Keeps the temporary directory of the runs after a failure or failed
/// checks, so that the .mess named by the run's last line (and the .resu
/// with its NOOK lines) can be read, and says so; the runs share the
/// directory, so it holds the last run's files. An empty one (the study
/// did not start) is removed.
fn keep_outputs(tmp: &std::path::Path, run: usize, out: &mut dyn Write) {
    let holds_files = std::fs::read_dir(tmp).is_ok_and(|mut d| d.next().is_some());
    if holds_files {
        let _ = writeln!(
            out,
            "the .mess, .resu and result files of run {run} are kept in {}; remove it when done",
            tmp.display()
        );
    } else {
        let _ = std::fs::remove_dir_all(tmp);
    }
}

/// The phase rows, per run. The element row is exclusive of the law
/// integrations nested in it; "other" is what no phase covers.
fn rows(samples: &[RunSample]) -> Vec<Row> {
    let col = |f: &dyn Fn(&RunSample) -> f64| samples.iter().map(f).collect::<Vec<f64>>();
    let calls = |p: Phase| Some(samples.iter().map(|s| s.profile.calls(p)).collect());
    let t = |s: &RunSample, p: Phase| s.profile.seconds(p);
    // Phases on the calling thread, disjoint: their sum is at most the wall time.
    let top = [
        Phase::ElementAssembly,
        Phase::FactorSolve,
        Phase::Contact,
        Phase::Output,
    ];
    vec![
        Row {
            key: "element_assembly",
            label: "element integration + assembly, excl. law [1]",
            per_run: col(&|s| t(s, Phase::ElementAssembly) - t(s, Phase::LawIntegration)),
            calls: calls(Phase::ElementAssembly),
        },
        Row {
            key: "law_integration",
            label: "law integration [1]",
            per_run: col(&|s| t(s, Phase::LawIntegration)),
            calls: calls(Phase::LawIntegration),
        },
        Row {
            key: "factor_solve",
            label: "factorization + solve",
            per_run: col(&|s| t(s, Phase::FactorSolve)),
            calls: calls(Phase::FactorSolve),
        },
        Row {
            key: "contact",
            label: "contact pairing + terms",
            per_run: col(&|s| t(s, Phase::Contact)),
            calls: calls(Phase::Contact),
        },
        Row {
            key: "output",
            label: "output (IMPR_*, .mess, .resu)",
            per_run: col(&|s| t(s, Phase::Output)),
            calls: calls(Phase::Output),
        },
        Row {
            key: "other",
            label: "other (parse, mesh, set-up, time loop, post)",
            per_run: col(&|s| s.wall - top.iter().map(|&p| t(s, p)).sum::<f64>()),
            calls: None,
        },
        Row {
            key: "element_assembly_inclusive",
            label: "element integration + assembly, incl. law",
            per_run: col(&|s| t(s, Phase::ElementAssembly)),
            calls: calls(Phase::ElementAssembly),
        },
    ]
}

struct Report {
    study: String,
    threads: usize,
    /// NOOK counts of the runs whose checks failed (empty: all passed).
    nook: Vec<usize>,
    /// VmHWM could be reset before every run (else it is the process peak).
    peak_reset: bool,
    samples: Vec<RunSample>,
    rows: Vec<Row>,
}

impl Report {
    fn walls(&self) -> Vec<f64> {
        self.samples.iter().map(|s| s.wall).collect()
    }

    fn counter(&self, c: Counter) -> Vec<u64> {
        self.samples.iter().map(|s| s.profile.counter(c)).collect()
    }

    fn peaks(&self) -> Vec<Option<u64>> {
        self.samples.iter().map(|s| s.peak).collect()
    }

    fn peak_scope(&self) -> &'static str {
        if self.peak_reset {
            "peak resident set of the process during each run: VmHWM, reset before each run"
        } else {
            "peak resident set of the process since it started: VmHWM, which could not be reset between runs"
        }
    }

    fn law_note(&self) -> String {
        if self.threads == 1 {
            "law integration is nested in element integration; the element row is its time \
minus the law time (one thread: the split is exact up to the clock overhead)"
                .into()
        } else {
            format!(
                "law integration is nested in element integration, which runs in {} threads: the law \
row is CPU time summed over threads, the element row its wall time minus that (it can come out \
too small, even negative); use --threads 1 for an exact split",
                self.threads
            )
        }
    }

    fn table(&self) -> String {
        let walls = self.walls();
        let wall = median(&walls);
        let (min, max) = min_max(&walls);
        let mut t = String::new();
        t.push_str(&format!(
            "\nwall time: median {wall:.3} s, min {min:.3} s, max {max:.3} s\n\n"
        ));
        t.push_str(&format!(
            "{:<46} {:>10} {:>7} {:>10}\n",
            "phase (median over runs)", "time [s]", "share", "calls/run"
        ));
        for r in &self.rows {
            if r.key == "element_assembly_inclusive" {
                continue;
            }
            let m = median(&r.per_run);
            let calls = r
                .calls
                .as_ref()
                .map(|c| median_u(c).to_string())
                .unwrap_or_default();
            let line = format!(
                "{:<46} {:>10.3} {:>6.1}% {:>10}",
                r.label,
                m,
                share(m, wall),
                calls
            );
            t.push_str(line.trim_end());
            t.push('\n');
        }
        t.push_str(&format!(
            "{:<46} {:>10.3} {:>6.1}%\n\n",
            "wall time", wall, 100.0
        ));
        let counters = [
            ("Newton iterations", Counter::NewtonIterations),
            ("time steps", Counter::Steps),
            ("step cuts", Counter::StepCuts),
            ("contact pairings", Counter::Pairings),
        ];
        for (label, c) in counters {
            let v = self.counter(c);
            let (lo, hi) = (v.iter().min().copied(), v.iter().max().copied());
            let text = match (lo, hi) {
                (Some(a), Some(b)) if a != b => format!("{} (varies: {a} to {b})", median_u(&v)),
                _ => median_u(&v).to_string(),
            };
            t.push_str(&format!("{label:<20} {text}\n"));
        }
        let peak = self.peaks().into_iter().flatten().max();
        t.push_str(&format!(
            "{:<20} {} ({})\n",
            "peak memory",
            peak.map_or("n/a".into(), |b| format!(
                "{:.1} MiB",
                b as f64 / (1024.0 * 1024.0)
            )),
            self.peak_scope()
        ));
        t.push_str(&format!(
            "\nEach row is the median over runs of that row's per-run time, so rows need not add up \
exactly to the wall time.\n[1] {}.\n",
            self.law_note()
        ));
        t
    }

    fn json(&self) -> String {
        let walls = self.walls();
        let wall = median(&walls);
        let (min, max) = min_max(&walls);
        let mut phases = Vec::new();
        for r in &self.rows {
            let m = median(&r.per_run);
            let mut fields = vec![
                format!("\"median_s\": {}", json::number(ns(m))),
                format!(
                    "\"share\": {}",
                    json::number((share(m, wall) * 10.0).round() / 1000.0)
                ),
                format!(
                    "\"per_run_s\": {}",
                    json::numbers(&r.per_run.iter().map(|&x| ns(x)).collect::<Vec<_>>())
                ),
            ];
            if let Some(c) = &r.calls {
                fields.push(format!("\"calls_per_run\": {}", median_u(c)));
            }
            phases.push(format!(
                "    {}: {{{}}}",
                json::string(r.key),
                fields.join(", ")
            ));
        }
        let mut counters = Vec::new();
        let mut counters_per_run = Vec::new();
        for c in Counter::ALL {
            let v = self.counter(c);
            counters.push(format!("    {}: {}", json::string(c.key()), median_u(&v)));
            let items: Vec<String> = v.iter().map(u64::to_string).collect();
            counters_per_run.push(format!(
                "    {}: [{}]",
                json::string(c.key()),
                items.join(", ")
            ));
        }
        let peaks: Vec<String> = self
            .peaks()
            .iter()
            .map(|p| p.map_or("null".into(), |b| b.to_string()))
            .collect();
        let peak = self.peaks().into_iter().flatten().max();
        let notes = [
            self.law_note(),
            "element_assembly is exclusive of law_integration; element_assembly_inclusive is the \
wall time of element integration and assembly"
                .to_string(),
            "other = wall time minus element_assembly_inclusive, factor_solve, contact and output"
                .to_string(),
        ];
        let notes: Vec<String> = notes.iter().map(|n| json::string(n)).collect();
        format!(
            "{{\n  \"study\": {},\n  \"aster_version\": {},\n  \"runs\": {},\n  \"threads\": {},\n  \
\"wall_s\": {{\"median\": {}, \"min\": {}, \"max\": {}, \"per_run\": {}}},\n  \
\"phases\": {{\n{}\n  }},\n  \"counters\": {{\n{}\n  }},\n  \"counters_per_run\": {{\n{}\n  }},\n  \
\"peak_memory\": {{\"bytes\": {}, \"per_run_bytes\": [{}], \"scope\": {}}},\n  \
\"checks_failed\": {},\n  \"nook\": {},\n  \"notes\": [{}]\n}}\n",
            json::string(&self.study),
            json::string(env!("CARGO_PKG_VERSION")),
            self.samples.len(),
            self.threads,
            json::number(ns(wall)),
            json::number(ns(min)),
            json::number(ns(max)),
            json::numbers(&walls.iter().map(|&x| ns(x)).collect::<Vec<_>>()),
            phases.join(",\n"),
            counters.join(",\n"),
            counters_per_run.join(",\n"),
            peak.map_or("null".into(), |b| b.to_string()),
            peaks.join(", "),
            json::string(self.peak_scope()),
            !self.nook.is_empty(),
            self.nook.iter().max().copied().unwrap_or(0),
            notes.join(", ")
        )
    }
}

/// Seconds rounded to the nanosecond (the clock's resolution), which
/// keeps the JSON free of float noise such as 0.48836757249999607.
fn ns(seconds: f64) -> f64 {
    (seconds * 1e9).round() / 1e9
}

fn share(part: f64, whole: f64) -> f64 {
    if whole > 0.0 {
        100.0 * part / whole
    } else {
        0.0
    }
}

fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let n = s.len();
    match n {
        0 => f64::NAN,
        _ if n % 2 == 1 => s[n / 2],
        _ => 0.5 * (s[n / 2 - 1] + s[n / 2]),
    }
}

/// The median of counts, rounded down for an even number of runs.
fn median_u(v: &[u64]) -> u64 {
    let mut s = v.to_vec();
    s.sort_unstable();
    let n = s.len();
    match n {
        0 => 0,
        _ if n % 2 == 1 => s[n / 2],
        _ => (s[n / 2 - 1] + s[n / 2]) / 2,
    }
}

fn min_max(v: &[f64]) -> (f64, f64) {
    v.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        })
}

/// Resets VmHWM to the current resident set (Linux ≥ 4.0: writing 5 to
/// /proc/self/clear_refs), so that each run reports its own peak. False
/// where that is not possible.
fn reset_peak_memory() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// VmHWM (peak resident set) of this process, in bytes.
fn peak_memory() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    parse_vm_hwm(&status)
}

fn parse_vm_hwm(status: &str) -> Option<u64> {
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let mut it = line["VmHWM:".len()..].split_whitespace();
    let n: u64 = it.next()?.parse().ok()?;
    match it.next() {
        Some("kB") => Some(n * 1024),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn medians_of_odd_and_even_counts() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), 2.5);
        assert_eq!(median_u(&[5, 1, 9]), 5);
        assert_eq!(median_u(&[1, 2]), 1);
        assert_eq!(min_max(&[2.0, -1.0, 3.0]), (-1.0, 3.0));
    }

    #[test]
    fn reads_vm_hwm_in_bytes() {
        let s = "Name:\taster\nVmPeak:\t  20000 kB\nVmHWM:\t    1234 kB\nVmRSS:\t 1000 kB\n";
        assert_eq!(parse_vm_hwm(s), Some(1234 * 1024));
        assert_eq!(parse_vm_hwm("VmRSS: 1 kB\n"), None);
        // This process exists, so it has a peak on Linux.
        if cfg!(target_os = "linux") {
            assert!(peak_memory().is_some_and(|b| b > 0));
        }
    }
}
