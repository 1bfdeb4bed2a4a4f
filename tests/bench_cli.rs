//! `aster bench` through the built binary, on the contact landing
//! verification study (2 x 8 QUAD8, penalised contact, IMPR_TABLE): every
//! phase is exercised. The JSON report is parsed by an independent parser
//! written here, the phase times are checked against the wall time of
//! each run, and the counters against the step summary `aster run` writes
//! in the .mess file of the same study.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

/// A parsed JSON value (only what the check needs).
#[derive(Debug, Clone, PartialEq)]
enum Json {
    Null,
    Bool(bool),
    Num(f64),
    Str(String),
    Arr(Vec<Json>),
    Obj(BTreeMap<String, Json>),
}

impl Json {
    fn get(&self, key: &str) -> &Json {
        match self {
            Json::Obj(m) => m
                .get(key)
                .unwrap_or_else(|| panic!("no key '{key}' in {self:?}")),
            _ => panic!("not an object: {self:?}"),
        }
    }
    fn num(&self) -> f64 {
        match self {
            Json::Num(x) => *x,
            _ => panic!("not a number: {self:?}"),
        }
    }
    fn arr(&self) -> &[Json] {
        match self {
            Json::Arr(v) => v,
            _ => panic!("not an array: {self:?}"),
        }
    }
}

/// A strict recursive-descent JSON parser (RFC 8259 grammar, no
/// extensions: no trailing commas, no NaN, no comments).
struct Parser<'a> {
    s: &'a [u8],
    i: usize,
}

impl Parser<'_> {
    fn parse(text: &str) -> Result<Json, String> {
        let mut p = Parser {
            s: text.as_bytes(),
            i: 0,
        };
        let v = p.value()?;
        p.ws();
        if p.i != p.s.len() {
            return Err(format!("trailing text at byte {}", p.i));
        }
        Ok(v)
    }
    fn ws(&mut self) {
        while self.i < self.s.len() && matches!(self.s[self.i], b' ' | b'\n' | b'\r' | b'\t') {
            self.i += 1;
        }
    }
    fn eat(&mut self, c: u8) -> Result<(), String> {
        self.ws();
        if self.s.get(self.i) == Some(&c) {
            self.i += 1;
            Ok(())
        } else {
            Err(format!("expected '{}' at byte {}", c as char, self.i))
        }
    }
    fn lit(&mut self, word: &str, v: Json) -> Result<Json, String> {
        if self.s[self.i..].starts_with(word.as_bytes()) {
            self.i += word.len();
            Ok(v)
        } else {
            Err(format!("bad literal at byte {}", self.i))
        }
    }
    fn value(&mut self) -> Result<Json, String> {
        self.ws();
        match self.s.get(self.i) {
            Some(b'{') => {
                self.i += 1;
                let mut m = BTreeMap::new();
                self.ws();
                if self.s.get(self.i) == Some(&b'}') {
                    self.i += 1;
                    return Ok(Json::Obj(m));
                }
                loop {
                    self.ws();
                    let k = self.string()?;
                    self.eat(b':')?;
                    let v = self.value()?;
                    if m.insert(k.clone(), v).is_some() {
                        return Err(format!("duplicate key '{k}'"));
                    }
                    self.ws();
                    match self.s.get(self.i) {
                        Some(b',') => self.i += 1,
                        Some(b'}') => {
                            self.i += 1;
                            return Ok(Json::Obj(m));
                        }
                        _ => return Err(format!("expected ',' or '}}' at byte {}", self.i)),
                    }
                }
            }
            Some(b'[') => {
                self.i += 1;
                let mut v = Vec::new();
                self.ws();
                if self.s.get(self.i) == Some(&b']') {
                    self.i += 1;
                    return Ok(Json::Arr(v));
                }
                loop {
                    v.push(self.value()?);
                    self.ws();
                    match self.s.get(self.i) {
                        Some(b',') => self.i += 1,
                        Some(b']') => {
                            self.i += 1;
                            return Ok(Json::Arr(v));
                        }
                        _ => return Err(format!("expected ',' or ']' at byte {}", self.i)),
                    }
                }
            }
            Some(b'"') => self.string().map(Json::Str),
            Some(b't') => self.lit("true", Json::Bool(true)),
            Some(b'f') => self.lit("false", Json::Bool(false)),
            Some(b'n') => self.lit("null", Json::Null),
            Some(c) if *c == b'-' || c.is_ascii_digit() => self.number(),
            _ => Err(format!("unexpected input at byte {}", self.i)),
        }
    }
    fn number(&mut self) -> Result<Json, String> {
        let start = self.i;
        let digits = |p: &mut Self| {
            let s = p.i;
            while p.i < p.s.len() && p.s[p.i].is_ascii_digit() {
                p.i += 1;
            }
            p.i > s
        };
        if self.s[self.i] == b'-' {
            self.i += 1;
        }
        if self.s.get(self.i) == Some(&b'0') {
            self.i += 1;
        } else if !digits(self) {
            return Err(format!("bad number at byte {start}"));
        }
        if self.s.get(self.i) == Some(&b'.') {
            self.i += 1;
            if !digits(self) {
                return Err(format!("bad fraction at byte {start}"));
            }
        }
        if matches!(self.s.get(self.i), Some(b'e' | b'E')) {
            self.i += 1;
            if matches!(self.s.get(self.i), Some(b'+' | b'-')) {
                self.i += 1;
            }
            if !digits(self) {
                return Err(format!("bad exponent at byte {start}"));
            }
        }
        let text = std::str::from_utf8(&self.s[start..self.i]).unwrap();
        text.parse().map(Json::Num).map_err(|e| format!("{e}"))
    }
    fn string(&mut self) -> Result<String, String> {
        if self.s.get(self.i) != Some(&b'"') {
            return Err(format!("expected a string at byte {}", self.i));
        }
        self.i += 1;
        let mut out = Vec::new();
        while let Some(&c) = self.s.get(self.i) {
            self.i += 1;
            match c {
                b'"' => return String::from_utf8(out).map_err(|e| e.to_string()),
                b'\\' => {
                    let e = *self.s.get(self.i).ok_or("unterminated escape")?;
                    self.i += 1;
                    match e {
                        b'"' | b'\\' | b'/' => out.push(e),
                        b'n' => out.push(b'\n'),
                        b't' => out.push(b'\t'),
                        b'r' => out.push(b'\r'),
                        b'b' => out.push(8),
                        b'f' => out.push(12),
                        b'u' => {
                            let hex = std::str::from_utf8(&self.s[self.i..self.i + 4])
                                .map_err(|e| e.to_string())?;
                            let code = u32::from_str_radix(hex, 16).map_err(|e| e.to_string())?;
                            let ch = char::from_u32(code).ok_or("bad \\u escape")?;
                            out.extend_from_slice(ch.to_string().as_bytes());
                            self.i += 4;
                        }
                        _ => return Err(format!("bad escape at byte {}", self.i)),
                    }
                }
                c if c < 0x20 => return Err(format!("raw control character at byte {}", self.i)),
                c => out.push(c),
            }
        }
        Err("unterminated string".into())
    }
}

#[test]
fn the_json_parser_of_this_test_rejects_invalid_json() {
    assert!(Parser::parse(r#"{"a": [1, -2.5e3, "x\n", null, true]}"#).is_ok());
    for bad in [
        "{\"a\": 1,}",
        "[1 2]",
        "{\"a\": NaN}",
        "{\"a\": 01}",
        "{'a': 1}",
        "[1.]",
        "{\"a\": 1} x",
    ] {
        assert!(Parser::parse(bad).is_err(), "{bad}");
    }
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// The totals `aster run` logs at the end of DYNA_NON_LINE:
/// "  N steps (C cuts), M Newton iterations, ...".
fn mess_totals(mess: &str) -> (u64, u64, u64) {
    let line = mess
        .lines()
        .find(|l| l.contains(" steps (") && l.contains(" Newton iterations"))
        .unwrap_or_else(|| panic!("no step summary in:\n{mess}"));
    let nums: Vec<u64> = line
        .split(|c: char| !c.is_ascii_digit())
        .filter(|s| !s.is_empty())
        .take(3)
        .map(|s| s.parse().unwrap())
        .collect();
    (nums[0], nums[1], nums[2])
}

#[test]
fn bench_reports_phases_that_fit_in_the_wall_time_and_the_run_counters() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let study_dir = root.join("tests/verification");
    let comm = study_dir.join("contact_landing.comm");
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("bench_cli");
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).unwrap();
    let json_path = tmp.join("bench.json");
    let before = files_in(&study_dir);

    let out = Command::new(env!("CARGO_BIN_EXE_aster"))
        .args([
            "bench",
            comm.to_str().unwrap(),
            "--runs",
            "2",
            "--threads",
            "1",
        ])
        .arg("--json")
        .arg(&json_path)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for row in [
        "element integration + assembly, excl. law",
        "law integration",
        "factorization + solve",
        "contact pairing + terms",
        "output (IMPR_*",
        "other",
        "wall time: median",
        "Newton iterations",
        "step cuts",
        "peak memory",
    ] {
        assert!(stdout.contains(row), "no '{row}' in:\n{stdout}");
    }
    assert!(
        stdout.contains("  run  1:") && stdout.contains("  run  2:"),
        "{stdout}"
    );
    // The study's directory is left as it was (outputs went elsewhere).
    assert_eq!(files_in(&study_dir), before);

    let text = std::fs::read_to_string(&json_path).unwrap();
    let j = Parser::parse(&text).unwrap_or_else(|e| panic!("{e}:\n{text}"));
    assert_eq!(j.get("checks_failed"), &Json::Bool(false));
    assert!(!stdout.contains("CHECKS FAILED"), "{stdout}");
    assert_eq!(j.get("runs").num(), 2.0);
    assert_eq!(j.get("threads").num(), 1.0);
    let walls: Vec<f64> = j
        .get("wall_s")
        .get("per_run")
        .arr()
        .iter()
        .map(Json::num)
        .collect();
    assert_eq!(walls.len(), 2);
    let phases = j.get("phases");
    let per_run = |key: &str| -> Vec<f64> {
        phases
            .get(key)
            .get("per_run_s")
            .arr()
            .iter()
            .map(Json::num)
            .collect()
    };
    for (r, &wall) in walls.iter().enumerate() {
        let t = |k: &str| per_run(k)[r];
        for k in [
            "element_assembly",
            "element_assembly_inclusive",
            "law_integration",
            "factor_solve",
            "contact",
            "output",
            "other",
        ] {
            assert!(t(k) >= 0.0, "run {r}: {k} = {} < 0\n{text}", t(k));
        }
        // Every phase this study goes through was timed.
        for k in ["law_integration", "factor_solve", "contact", "output"] {
            assert!(t(k) > 0.0, "run {r}: {k} not timed\n{text}");
        }
        // The phases on the main thread are disjoint: they fit in the run.
        let sum = t("element_assembly_inclusive") + t("factor_solve") + t("contact") + t("output");
        assert!(sum <= wall, "run {r}: phases {sum} s > wall {wall} s");
        // One thread: the law integrations lie inside the element loops.
        assert!(
            t("law_integration") <= t("element_assembly_inclusive"),
            "{text}"
        );
    }

    // The counters equal the totals `aster run` logs for the same study.
    let run_dir = tmp.join("run");
    let status = Command::new(env!("CARGO_BIN_EXE_aster"))
        .args(["run", comm.to_str().unwrap(), "--quiet", "--out"])
        .arg(&run_dir)
        .output()
        .unwrap();
    assert!(status.status.success());
    let mess = std::fs::read_to_string(run_dir.join("contact_landing.mess")).unwrap();
    let (steps, cuts, newton) = mess_totals(&mess);
    assert!(
        steps > 100 && newton >= steps,
        "{steps} steps, {newton} iterations"
    );
    let counters = j.get("counters_per_run");
    for (key, expected) in [
        ("steps", steps),
        ("step_cuts", cuts),
        ("newton_iterations", newton),
    ] {
        for v in counters.get(key).arr() {
            assert_eq!(v.num(), expected as f64, "{key}\n{text}");
        }
    }
    // At least one pairing per step (REAC_GEOM='CONTROLE' pairs at the
    // start of every step), plus the initial one.
    for v in counters.get("contact_pairings").arr() {
        assert!(v.num() > steps as f64, "{text}");
    }
    let peak = j.get("peak_memory").get("bytes").num();
    assert!(peak > 1e6, "peak memory {peak} bytes");
}

#[test]
fn bench_fails_when_the_study_fails() {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("bench_cli_bad");
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).unwrap();
    let comm = tmp.join("bad.comm");
    std::fs::write(&comm, "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED'\nFIN()\n").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_aster"))
        .args(["bench", comm.to_str().unwrap(), "--runs", "2"])
        .env("TMPDIR", &tmp)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(stdout.contains("run 1 failed"), "{stdout}");
    assert!(!stdout.contains("wall time: median"), "{stdout}");
}

/// The .mess that a failed run's last line names is still there when
/// `aster bench` has exited (it used to delete the directory): its path
/// is read from the output, the file holds the error, and the output says
/// the directory is kept. The run fails at run time (unit 20 is mapped to
/// no mesh), after the .mess was started.
#[test]
fn bench_keeps_the_mess_of_a_failed_run_where_it_says() {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("bench_cli_kept");
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).unwrap();
    let comm = tmp.join("nomesh.comm");
    std::fs::write(
        &comm,
        "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED')\nFIN()\n",
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_aster"))
        .args(["bench", comm.to_str().unwrap(), "--runs", "2"])
        .env("TMPDIR", &tmp)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(
        stdout.contains("run 1 failed") && !stdout.contains("run  2"),
        "{stdout}"
    );
    let named = stdout
        .lines()
        .find_map(|l| l.split("FAILED (messages in ").nth(1))
        .and_then(|rest| rest.strip_suffix(')'))
        .unwrap_or_else(|| panic!("no 'FAILED (messages in ...)' line in:\n{stdout}"));
    let mess = std::fs::read_to_string(named)
        .unwrap_or_else(|e| panic!("the .mess named, {named}, cannot be read after exit: {e}"));
    assert!(mess.contains("LIRE_MAILLAGE"), "{mess}");
    let dir = Path::new(named).parent().unwrap();
    assert!(dir.starts_with(&tmp), "{named} is not under TMPDIR");
    assert!(
        stdout.contains(&format!(
            "the .mess, .resu and result files of run 1 are kept in {}",
            dir.display()
        )),
        "{stdout}"
    );
}

/// `--json` into a directory that does not exist (or onto a directory) is
/// a usage error before any run, like the other option errors; it used to
/// be found after all the runs.
#[test]
fn bench_checks_the_json_path_before_running() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let study_dir = root.join("tests/verification");
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("bench_cli_json_path");
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).unwrap();
    for (target, expected) in [
        (tmp.join("missing/x.json"), "the directory"),
        (tmp.clone(), "is a directory"),
    ] {
        let t0 = std::time::Instant::now();
        let out = Command::new(env!("CARGO_BIN_EXE_aster"))
            .arg("bench")
            .arg(study_dir.join("contact_landing.comm"))
            .args(["--runs", "3", "--export"])
            .arg(study_dir.join("contact_landing.export"))
            .arg("--json")
            .arg(&target)
            .env("TMPDIR", &tmp)
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert_eq!(out.status.code(), Some(2), "{stdout}");
        assert!(stdout.starts_with("error: --json: "), "{stdout}");
        assert!(stdout.contains(expected), "{stdout}");
        assert!(!stdout.contains("run  1"), "a run started:\n{stdout}");
        eprintln!(
            "--json {}: refused in {:.3} s",
            target.display(),
            t0.elapsed().as_secs_f64()
        );
    }
    assert!(!tmp.join("missing").exists());
}

/// A study that runs to its end but whose checks fail (here the landing
/// study with its free-flight reference moved by 50 %, so that the check
/// fails honestly) is still measured: the table is printed, a line says
/// the checks failed, the JSON says so, and the exit code is `aster run`'s.
#[test]
fn bench_measures_a_study_whose_checks_fail_and_says_so() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let study_dir = root.join("tests/verification");
    let text = std::fs::read_to_string(study_dir.join("contact_landing.comm")).unwrap();
    let wrong = text.replace("VALE_REFE=2.E-3", "VALE_REFE=3.E-3");
    assert_ne!(wrong, text);
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("bench_cli_nook");
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).unwrap();
    let comm = tmp.join("landing_nook.comm");
    std::fs::write(&comm, wrong).unwrap();
    let json_path = tmp.join("bench.json");
    let out = Command::new(env!("CARGO_BIN_EXE_aster"))
        .args(["bench", comm.to_str().unwrap(), "--runs", "2"])
        .arg("--export")
        .arg(study_dir.join("contact_landing.export"))
        .arg("--json")
        .arg(&json_path)
        .env("TMPDIR", &tmp)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(stdout.contains("wall time: median"), "{stdout}");
    assert!(stdout.contains("Newton iterations"), "{stdout}");
    assert!(stdout.contains("(checks failed: 1 NOOK)"), "{stdout}");
    assert!(
        stdout.contains("CHECKS FAILED: 1 NOOK test (runs 1, 2)"),
        "{stdout}"
    );
    let j = Parser::parse(&std::fs::read_to_string(&json_path).unwrap()).unwrap();
    assert_eq!(j.get("checks_failed"), &Json::Bool(true));
    assert_eq!(j.get("nook").num(), 1.0);
    // The last run's .resu, with its NOOK line, is kept and named.
    let kept = stdout
        .lines()
        .find_map(|l| l.strip_prefix("the .mess, .resu and result files of run 2 are kept in "))
        .and_then(|l| l.strip_suffix("; remove it when done"))
        .unwrap_or_else(|| panic!("no 'kept in' line in:\n{stdout}"));
    let resu = std::fs::read_to_string(Path::new(kept).join("landing_nook.resu")).unwrap();
    assert!(resu.contains("NOOK"), "{resu}");
}

/// The explicit contact (DEFI_CONTACT discrete, and LIAISON_UNIL) is
/// timed in the "contact pairing + terms" row, as the implicit one: its
/// pairing, penalty forces, kinematic correction and commit at every
/// step. Before, the row said 0.000 s and 0 calls next to "contact
/// pairings 75002" (probe explp, a block sliding on a slope), the
/// contact's time counted in "other".
#[test]
fn bench_times_the_explicit_contact() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let study_dir = root.join("tests/verification");
    for study in ["explicit_landing", "explicit_unil_landing"] {
        let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("bench_cli_{study}"));
        let _ = std::fs::remove_dir_all(&tmp);
        std::fs::create_dir_all(&tmp).unwrap();
        let json_path = tmp.join("bench.json");
        let out = Command::new(env!("CARGO_BIN_EXE_aster"))
            .arg("bench")
            .arg(study_dir.join(format!("{study}.comm")))
            .args(["--runs", "1", "--threads", "1", "--json"])
            .arg(&json_path)
            .env("TMPDIR", &tmp)
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{study}: {stdout}");
        let text = std::fs::read_to_string(&json_path).unwrap();
        let j = Parser::parse(&text).unwrap_or_else(|e| panic!("{e}:\n{text}"));
        let steps = j.get("counters_per_run").get("steps").arr()[0].num();
        assert!(steps > 1000.0, "{study}: {steps} steps\n{text}");
        let contact = j.get("phases").get("contact");
        let time = contact.get("per_run_s").arr()[0].num();
        let calls = contact.get("calls_per_run").num();
        assert!(time > 0.0, "{study}: contact not timed\n{text}");
        // At least one call (the kinematic correction, or the penalty
        // forces) per explicit step of each run.
        assert!(
            calls >= steps,
            "{study}: {calls} calls for {steps} steps\n{text}"
        );
        // The phases stay disjoint: they fit in the wall time.
        let t = |k: &str| j.get("phases").get(k).get("per_run_s").arr()[0].num();
        let wall = j.get("wall_s").get("per_run").arr()[0].num();
        let sum = t("element_assembly_inclusive") + t("factor_solve") + t("contact") + t("output");
        assert!(
            sum <= wall,
            "{study}: phases {sum} s > wall {wall} s\n{text}"
        );
    }
}
