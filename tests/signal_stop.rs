//! A run stopped by SIGTERM or SIGINT keeps its work (issue 16): the
//! `aster` binary runs SDNV103 B, the test waits until DYNA_NON_LINE has
//! computed and archived several instants, sends the signal, and reads the
//! MED result written on the way out.
//!
//! Progress is read from the run's terminal echo (stderr, one line per
//! step), not from a fixed sleep, so the test does not depend on the speed
//! of the machine; the timeouts only catch a hung run.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use aster::medio::read_nodal_fields;

/// The end of the time list of sdnv103b.comm (T_FIN).
const T_FIN: f64 = 8e-5;
/// Its first instant (DEBUT of L_INST).
const T_START: f64 = -1e-5;

/// The instant of a step line of the DYNA_NON_LINE log
/// (`  <step>  <INST>  <dt>  <iter> ...`), None for any other line.
fn step_instant(line: &str) -> Option<f64> {
    let mut words = line.split_whitespace();
    words.next()?.parse::<usize>().ok()?;
    let t = words.next()?.parse::<f64>().ok()?;
    words.next()?.parse::<f64>().ok()?;
    words.next()?.parse::<usize>().ok()?;
    Some(t)
}

struct Stopped {
    code: Option<i32>,
    /// The instant of the last step line seen before the signal was sent.
    seen: f64,
    out: PathBuf,
    stdout: String,
}

/// Runs sdnv103b.comm into a scratch directory, sends `signal` once a step
/// has reached `after` (in seconds of the study), and waits for the end.
fn run_and_stop(signal: i32, after: f64, tag: &str) -> Stopped {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(tag);
    let _ = std::fs::remove_dir_all(&out);
    std::fs::create_dir_all(&out).expect("scratch directory");
    let mut child = Command::new(env!("CARGO_BIN_EXE_aster"))
        .arg("run")
        .arg(root.join("comm/sdnv103b.comm"))
        .arg("--out")
        .arg(&out)
        .arg("--unit")
        .arg(format!("80={}", out.join("resu.rmed").display()))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the aster binary starts");
    let stderr = child.stderr.take().expect("piped stderr");
    let stdout = child.stdout.take().expect("piped stdout");
    let (tx, rx) = mpsc::channel::<String>();
    // Both pipes are drained to the end so that the child never blocks.
    let err_reader = std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            let _ = tx.send(line);
        }
    });
    let out_reader = std::thread::spawn(move || {
        let mut text = String::new();
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            text.push_str(&line);
            text.push('\n');
        }
        text
    });

    let deadline = Instant::now() + Duration::from_secs(900);
    let mut seen = f64::NEG_INFINITY;
    while seen < after {
        let left = deadline.saturating_duration_since(Instant::now());
        match rx.recv_timeout(left) {
            Ok(line) => {
                if let Some(t) = step_instant(&line) {
                    seen = t;
                }
            }
            Err(e) => {
                let _ = child.kill();
                panic!("the run ended or hung before reaching t = {after:e} ({e:?}); last step at t = {seen:e}");
            }
        }
    }
    let pid = child.id() as libc::pid_t;
    // SAFETY: kill() on our own child's pid, which has not been waited for.
    let rc = unsafe { libc::kill(pid, signal) };
    assert_eq!(rc, 0, "kill({pid}, {signal}) failed");

    let deadline = Instant::now() + Duration::from_secs(300);
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait for the child") {
            break status;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            panic!("the run did not stop within 300 s of the signal");
        }
        // Drain stderr meanwhile (the reader thread does the reading).
        while rx.try_recv().is_ok() {}
        std::thread::sleep(Duration::from_millis(50));
    };
    err_reader.join().expect("stderr reader");
    let stdout = out_reader.join().expect("stdout reader");
    Stopped {
        code: status.code(),
        seen,
        out,
        stdout,
    }
}

/// What must be on disk after a stop: the .mess saying which signal
/// stopped the run where, the .resu, the partial result as MED with every
/// archived instant up to the stop, and no IMPR_RESU output.
fn check_stopped(run: &Stopped, signal_name: &str, code: i32) {
    assert_eq!(
        run.code,
        Some(code),
        "exit code of a run stopped by {signal_name}; stdout:\n{}",
        run.stdout
    );
    let mess =
        std::fs::read_to_string(run.out.join("sdnv103b.mess")).expect("the .mess is written");
    let resu =
        std::fs::read_to_string(run.out.join("sdnv103b.resu")).expect("the .resu is written");
    assert!(
        resu.contains(&format!("DYNA_NON_LINE stopped by {signal_name} at t = ")),
        "the .resu says where the run ended:\n{resu}"
    );
    let stop = format!("DYNA_NON_LINE stopped by {signal_name} at t = ");
    let line = mess
        .lines()
        .find(|l| l.contains(&stop))
        .unwrap_or_else(|| panic!("the .mess says where the run stopped:\n{mess}"));
    assert!(line.contains("archived instants"), "{line}");
    assert!(
        mess.contains("were not run: CALC_CHAMP, IMPR_RESU, POST_RELEVE_T"),
        "the .mess lists the commands skipped:\n{mess}"
    );
    assert!(
        mess.contains(&format!(
            "the run was stopped by {signal_name}; .mess and .resu hold what was done; exit code {code}"
        )),
        "{mess}"
    );
    assert!(
        run.stdout.contains(&format!("STOPPED by {signal_name}")),
        "{}",
        run.stdout
    );
    // IMPR_RESU was skipped: unit 80 was never written.
    assert!(!run.out.join("resu.rmed").exists());

    let rmed = run.out.join("sdnv103b_RESU.rmed");
    assert!(
        mess.contains(&format!("are saved in {}", rmed.display())),
        "the .mess names the saved result:\n{mess}"
    );
    let fields = read_nodal_fields(&rmed, None).expect("the saved result reads back");
    let names: Vec<&str> = fields.iter().map(|f| f.name.as_str()).collect();
    for want in ["RESU____DEPL", "RESU____VITE"] {
        assert!(names.contains(&want), "{want} in {names:?}");
    }
    let depl = fields.iter().find(|f| f.name == "RESU____DEPL").unwrap();
    let times: Vec<f64> = depl.steps.iter().map(|s| s.time).collect();
    assert!(times.len() >= 2, "instants saved: {times:?}");
    assert_eq!(times[0], T_START, "the initial state is archived");
    assert!(times.windows(2).all(|w| w[1] > w[0]), "{times:?}");
    let last = *times.last().unwrap();
    // The run stopped after the step seen and before the end of the list.
    assert!(
        last >= run.seen && last < T_FIN,
        "last {last:e}, seen {:e}",
        run.seen
    );
    // Every instant of the archive list L_ARCH (1 us to 80 us by 1 us)
    // reached before the stop is in the file, and nothing else but the
    // initial and the last converged states.
    for k in 1..=79 {
        let t = k as f64 * 1e-6;
        if t < last * (1.0 - 1e-9) {
            assert!(
                times.iter().any(|&s| (s - t).abs() <= 1e-6 * t),
                "archived instant {t:e} missing from {times:?}"
            );
        }
    }
    let on_list = |s: f64| (s / 1e-6 - (s / 1e-6).round()).abs() < 1e-6;
    assert!(
        times[1..times.len() - 1].iter().all(|&s| on_list(s)),
        "{times:?}"
    );
    // The motion is defined at every node of the model (CONT_NOEU only on
    // the contact nodes, the others read as NaN, so it is left out).
    let motion = ["RESU____DEPL", "RESU____VITE", "RESU____ACCE"];
    for f in fields.iter().filter(|f| motion.contains(&f.name.as_str())) {
        assert_eq!(f.steps.len(), times.len(), "{} has every instant", f.name);
        for s in &f.steps {
            assert!(
                s.values.iter().all(|v| v.is_finite()),
                "{} at t = {:e} is finite",
                f.name,
                s.time
            );
        }
    }
    // The bar flies at V0 = -227000 mm/s: the velocity field is not zero.
    let vite = fields.iter().find(|f| f.name == "RESU____VITE").unwrap();
    let vmax = vite.steps[0]
        .values
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(
        (vmax - 227000.0).abs() < 1e-6 * 227000.0,
        "max |VITE| at t0 {vmax}"
    );
}

#[test]
fn sigterm_in_the_middle_of_b_keeps_the_archived_instants() {
    let run = run_and_stop(libc::SIGTERM, 1e-5, "signal_sigterm");
    check_stopped(&run, "SIGTERM", 143);
}

#[test]
fn sigint_keeps_the_archived_instants() {
    let run = run_and_stop(libc::SIGINT, 2e-6, "signal_sigint");
    check_stopped(&run, "SIGINT", 130);
}

/// A stop requested between two commands (here before the first one, in
/// this process, as the handler would record it): nothing runs, the
/// commands are listed as skipped, and the outputs are still written.
#[test]
fn a_stop_before_a_command_skips_the_rest_of_the_file() {
    use aster::run::driver::{run_file, RunOptions};
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("signal_between");
    let _ = std::fs::remove_dir_all(&out);
    let mut term = Vec::new();
    aster::interrupt::request(libc::SIGTERM);
    let code = run_file(
        &RunOptions {
            comm: root.join("tests/verification/free_flight.comm"),
            out_dir: Some(out.clone()),
            units: vec![(80, out.join("resu.rmed"))],
            ..RunOptions::default()
        },
        &mut term,
    );
    aster::interrupt::clear();
    let term = String::from_utf8(term).unwrap();
    assert_eq!(code, 143, "{term}");
    let mess = std::fs::read_to_string(out.join("free_flight.mess")).expect("the .mess");
    for want in [
        "SIGTERM received: the study stops before DEBUT (line",
        "were not run: DEBUT, LIRE_MAILLAGE, AFFE_MODELE",
        "no transient result had been computed before the stop by SIGTERM",
        "exit code 143",
    ] {
        assert!(mess.contains(want), "'{want}' in:\n{mess}");
    }
    assert!(out.join("free_flight.resu").is_file());
    assert!(term.contains("STOPPED by SIGTERM"), "{term}");
}

/// A reader that closes the pipe early (`aster doc commands | head -1`)
/// ends aster quietly by SIGPIPE, as Unix tools end: no panic, no
/// backtrace, no exit code 101. (Rust ignores SIGPIPE by default, and the
/// next `println!` used to panic on the EPIPE.)
#[test]
fn a_closed_output_pipe_ends_aster_without_a_panic() {
    use std::io::Read;
    use std::os::unix::process::ExitStatusExt;
    let mut child = Command::new(env!("CARGO_BIN_EXE_aster"))
        .args(["doc", "commands"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the aster binary starts");
    let mut first = [0u8; 16];
    child
        .stdout
        .take()
        .expect("piped stdout")
        .read_exact(&mut first)
        .expect("the catalogue starts printing");
    // The read end is dropped here: the rest of the catalogue (far more
    // than a pipe buffer) meets a closed pipe.
    let mut err = String::new();
    child
        .stderr
        .take()
        .expect("piped stderr")
        .read_to_string(&mut err)
        .expect("stderr readable");
    let status = child.wait().expect("aster ends");
    assert!(!err.contains("panicked"), "aster panicked: {err}");
    assert_eq!(status.code(), None, "ended by a signal, got {status:?}");
    assert_eq!(status.signal(), Some(libc::SIGPIPE), "{status:?}");
}
