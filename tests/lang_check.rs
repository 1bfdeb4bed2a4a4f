//! The checker against its corpora: every malformed file in
//! `tests/lang/err/check_*.comm` gives exactly one error, whose rendered
//! message is snapshotted; every well-formed file in `tests/lang/ok/` and
//! every study in `comm/` checks clean.

use std::path::Path;

use aster::commands;
use aster::diag::{Severity, Source};
use aster::run::driver::parse_and_check;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Reads a corpus file the way `aster check` does, with a stable name.
fn load(path: &Path) -> Result<Source, String> {
    let rel = path.strip_prefix(root()).unwrap_or(path);
    let bytes = std::fs::read(path).expect("corpus file readable");
    Source::from_bytes(rel.display().to_string(), bytes).map_err(|d| d.render(None))
}

/// Renders what `aster check` prints, and counts the errors.
fn check(path: &Path) -> (String, usize) {
    let src = match load(path) {
        Ok(s) => s,
        Err(msg) => return (msg, 1),
    };
    let program = match aster::lang::parser::parse(&src) {
        Ok(p) => p,
        Err(d) => return (d.render(Some(&src)), 1),
    };
    match aster::catalog::checker::check_program(&program, &commands::all()) {
        Ok(_) => (String::new(), 0),
        Err(ds) => {
            let n = ds.iter().filter(|d| d.severity == Severity::Error).count();
            let text: Vec<String> = ds.iter().map(|d| d.render(Some(&src))).collect();
            (text.join("\n"), n)
        }
    }
}

#[test]
fn malformed_files_give_one_clear_error_each() {
    insta::glob!("lang/err/check_*.comm", |path| {
        let (text, n) = check(path);
        assert_eq!(
            n,
            1,
            "{} must give exactly one error:\n{text}",
            path.display()
        );
        insta::assert_snapshot!(text);
    });
}

#[test]
fn well_formed_files_check_clean() {
    insta::glob!("lang/ok/*.comm", |path| {
        let (text, n) = check(path);
        assert_eq!(n, 0, "{}:\n{text}", path.display());
    });
}

#[test]
fn the_ten_sdnv103_studies_check_clean() {
    let mut seen = 0;
    for m in ["a", "b", "d", "e", "f", "g", "h", "i", "j", "k"] {
        let p = root().join(format!("comm/sdnv103{m}.comm"));
        let src = load(&p).unwrap();
        let mut messages = String::new();
        let ok = parse_and_check(&src, &commands::all(), &mut messages);
        assert!(ok.is_some(), "{}:\n{messages}", p.display());
        seen += 1;
    }
    assert_eq!(seen, 10);
}

#[test]
fn cli_exit_codes() {
    let exe = env!("CARGO_BIN_EXE_aster");
    let run = |args: &[&str]| {
        std::process::Command::new(exe)
            .args(args)
            .current_dir(root())
            .output()
            .expect("aster runs")
    };
    let ok = run(&["check", "comm/sdnv103b.comm"]);
    assert_eq!(
        ok.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&ok.stdout)
    );
    let bad = run(&["check", "tests/lang/err/check_bad_into.comm"]);
    assert_eq!(bad.status.code(), Some(1));
    let out = String::from_utf8_lossy(&bad.stdout);
    assert!(out.contains("tests/lang/err/check_bad_into.comm:"), "{out}");
    assert!(out.contains("did you mean 'NEWMARK'"), "{out}");
    let missing = run(&["check", "no/such/file.comm"]);
    assert_eq!(missing.status.code(), Some(2));
    let usage = run(&["frobnicate"]);
    assert_eq!(usage.status.code(), Some(2));
    let help = run(&["run", "--help"]);
    assert_eq!(help.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&help.stdout).contains("--unit"));
}
