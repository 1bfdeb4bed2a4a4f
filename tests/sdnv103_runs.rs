//! Modellings B and D of SDNV103 run to FIN with every check OK, and their
//! POST_RELEVE_T tables (as IMPR_TABLE prints them) are snapshotted so that
//! any change in the numbers shows up in review.

use std::path::Path;

use aster::run::driver::{run_file, RunOptions};

fn run(m: &str) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("sdnv103{m}_run"));
    let mut term = Vec::new();
    let code = run_file(
        &RunOptions {
            comm: root.join(format!("comm/sdnv103{m}.comm")),
            out_dir: Some(out.clone()),
            // result files of IMPR_RESU go to this test's own directory
            units: vec![(80, out.join("resu.rmed"))],
            ..RunOptions::default()
        },
        &mut term,
    );
    let term = String::from_utf8(term).unwrap();
    let resu = std::fs::read_to_string(out.join(format!("sdnv103{m}.resu"))).unwrap();
    assert_eq!(code, 0, "sdnv103{m}:\n{term}\n{resu}");
    let lines: Vec<&str> = resu.lines().collect();
    assert!(lines.iter().any(|l| l.starts_with(" OK ")), "{resu}");
    assert!(
        !lines
            .iter()
            .any(|l| l.starts_with("NOOK") || l.starts_with("SKIP")),
        "{resu}"
    );
    // The tables: everything before the first test block, without the
    // title line that holds the date of the run.
    lines
        .iter()
        .take_while(|l| !l.starts_with(" ---- ") && !l.starts_with("-----"))
        .filter(|l| !l.starts_with("#ASTER"))
        .map(|l| l.trim_end())
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn sdnv103d_tables() {
    insta::assert_snapshot!(run("d"));
}

/// About 20 s in the optimised test profile.
#[test]
fn sdnv103b_tables() {
    insta::assert_snapshot!(run("b"));
}
