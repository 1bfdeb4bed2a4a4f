//! Modellings B and D of SDNV103 run to FIN with every check OK, and their
//! POST_RELEVE_T tables (as IMPR_TABLE prints them) are snapshotted so that
//! any change in the numbers shows up in review.

mod common;

fn run(m: &str) -> String {
    let run = common::run_study(&format!("comm/sdnv103{m}.comm"), &format!("sdnv103{m}_run"));
    let resu = common::assert_all_ok(&run, &format!("sdnv103{m}.resu"));
    let lines: Vec<&str> = resu.lines().collect();
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
