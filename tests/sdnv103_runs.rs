//! Every study of comm/ that runs to FIN is run whole here, with every check
//! OK (no NOOK, no SKIP), and its POST_RELEVE_T tables (as IMPR_TABLE
//! prints them) are snapshotted so that any change in the numbers shows up
//! in review. A study that stops on a `not implemented yet` error is listed
//! in [`NOT_RUNNING_YET`]; a test checks that it still stops there, so that
//! whoever makes it run moves it from that list to the `studies!` block.

mod common;

/// The studies that stop today on a `not implemented yet` error (the
/// engine lacks a feature they use). Making one run: remove it from this
/// list and add its line to the `studies!` block below.
const NOT_RUNNING_YET: &[&str] = &["a", "e", "f", "g", "j", "k"];

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

/// One test per running study (`name => modelling letter`), and the list
/// of them.
macro_rules! studies {
    ($($name:ident => $m:literal),* $(,)?) => {
        const RUNNING: &[&str] = &[$($m),*];
        $(
            #[test]
            fn $name() {
                insta::assert_snapshot!(run($m));
            }
        )*
    };
}

// B: about 20 s in the optimised test profile.
studies! {
    sdnv103b_tables => "b",
    sdnv103d_tables => "d",
    sdnv103h_tables => "h",
    sdnv103i_tables => "i",
}

/// Every command file of comm/ is either run above or listed as not
/// running yet, never both.
#[test]
fn every_comm_study_is_run_or_listed() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("comm");
    let mut found: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| {
            let name = e.unwrap().file_name().into_string().unwrap();
            name.strip_prefix("sdnv103")?
                .strip_suffix(".comm")
                .map(str::to_string)
        })
        .collect();
    found.sort();
    for m in &found {
        let run = RUNNING.contains(&m.as_str());
        let not = NOT_RUNNING_YET.contains(&m.as_str());
        assert!(
            run ^ not,
            "comm/sdnv103{m}.comm must be in exactly one of studies! (runs) and NOT_RUNNING_YET (running: {run}, listed: {not})"
        );
    }
    for m in RUNNING.iter().chain(NOT_RUNNING_YET) {
        assert!(found.iter().any(|f| f == m), "no comm/sdnv103{m}.comm");
    }
}

/// The studies listed as not running yet still stop on a clear
/// `not implemented yet` error before FIN. When one runs to FIN, this
/// fails: move it to the `studies!` block.
#[test]
fn studies_not_running_yet_stop_on_a_missing_feature() {
    for m in NOT_RUNNING_YET {
        let run = common::run_study(
            &format!("comm/sdnv103{m}.comm"),
            &format!("sdnv103{m}_stop"),
        );
        let mess = run.file(&format!("sdnv103{m}.mess"));
        assert!(
            run.code == 1 && run.term.contains("not implemented yet") && !mess.contains("FIN done"),
            "study {m} no longer stops on a missing feature (exit {}): move it from NOT_RUNNING_YET to studies! in tests/sdnv103_runs.rs\n{}",
            run.code,
            run.term
        );
    }
}
