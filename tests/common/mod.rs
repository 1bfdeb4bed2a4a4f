//! Running a command file from a test, as `aster run` does.
//! (Each test binary uses a different subset of these helpers.)
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use aster::run::driver::{run_file, RunOptions};

/// The outcome of a run: exit code, what the terminal showed, and the
/// scratch directory holding .mess, .resu and the result files.
pub struct Run {
    pub code: i32,
    pub term: String,
    pub out: PathBuf,
}

impl Run {
    /// The text of an output file of the run (empty if absent).
    pub fn file(&self, name: &str) -> String {
        std::fs::read_to_string(self.out.join(name)).unwrap_or_default()
    }
}

/// Runs `comm` (relative to the crate root) with its .export, writing into a
/// scratch directory named `tag`; IMPR_RESU's unit 80 also goes there, so
/// that tests never write into the source tree or share a file.
pub fn run_study(comm: &str, tag: &str) -> Run {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(tag);
    let _ = std::fs::remove_dir_all(&out);
    let mut term = Vec::new();
    let code = run_file(
        &RunOptions {
            comm: root.join(comm),
            out_dir: Some(out.clone()),
            units: vec![(80, out.join("resu.rmed"))],
            ..RunOptions::default()
        },
        &mut term,
    );
    Run {
        code,
        term: String::from_utf8(term).expect("UTF-8 output"),
        out,
    }
}

/// Asserts the run ended with exit 0, at least one OK and no NOOK or SKIP
/// line in its .resu; returns the .resu.
pub fn assert_all_ok(run: &Run, resu: &str) -> String {
    let text = run.file(resu);
    assert_eq!(run.code, 0, "{}:\n{}\n{text}", resu, run.term);
    let lines: Vec<&str> = text.lines().collect();
    assert!(
        lines.iter().any(|l| l.starts_with(" OK ")),
        "no check ran:\n{text}"
    );
    assert!(
        !lines
            .iter()
            .any(|l| l.starts_with("NOOK") || l.starts_with("SKIP")),
        "{text}"
    );
    text
}

/// The rows of the table `name` as IMPR_TABLE printed it in `resu`
/// (column name -> cell text), in order.
pub fn printed_table(resu: &str, name: &str) -> Vec<std::collections::HashMap<String, String>> {
    let mut lines = resu.lines();
    let tag = format!("CONCEPT {name} ");
    lines
        .by_ref()
        .find(|l| l.starts_with('#') && l.contains(&tag))
        .unwrap_or_else(|| panic!("no table {name} printed"));
    let header: Vec<String> = lines
        .by_ref()
        .find(|l| !l.starts_with('#'))
        .unwrap()
        .split_whitespace()
        .map(String::from)
        .collect();
    lines
        .take_while(|l| !l.trim().is_empty())
        .map(|l| {
            header
                .iter()
                .cloned()
                .zip(l.split_whitespace().map(String::from))
                .collect()
        })
        .collect()
}

/// Runs `<dir>/<study>.comm` with the first `from` replaced by `to` (which
/// must occur), under the study's .export with its paths made absolute,
/// the variant written to the scratch directory `scratch`: the bad-input
/// tests change one line of a working study.
pub fn run_variant(dir: &Path, scratch: &str, study: &str, tag: &str, from: &str, to: &str) -> Run {
    run_variant_edits(dir, scratch, study, tag, &[(from, to)])
}

/// [`run_variant`] with several (from, to) edits, applied in order, each
/// to its first occurrence.
pub fn run_variant_edits(
    dir: &Path,
    scratch: &str,
    study: &str,
    tag: &str,
    edits: &[(&str, &str)],
) -> Run {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join(scratch);
    std::fs::create_dir_all(&tmp).unwrap();
    let mut comm = std::fs::read_to_string(dir.join(format!("{study}.comm"))).unwrap();
    for (from, to) in edits {
        assert!(comm.contains(from), "{tag}: {from}");
        comm = comm.replacen(from, to, 1);
    }
    std::fs::write(tmp.join(format!("{tag}.comm")), comm).unwrap();
    let export = std::fs::read_to_string(dir.join(format!("{study}.export"))).unwrap();
    let export: String = export
        .lines()
        .map(|l| {
            let mut w: Vec<String> = l.split_whitespace().map(String::from).collect();
            if w.len() >= 3 {
                w[2] = dir.join(&w[2]).display().to_string();
            }
            w.join(" ") + "\n"
        })
        .collect();
    std::fs::write(tmp.join(format!("{tag}.export")), export).unwrap();
    run_study(tmp.join(format!("{tag}.comm")).to_str().unwrap(), tag)
}

/// The numbers in parentheses after `tag` on each line of `mess` that has
/// it (the explicit runs' momentum and impulse lines of the .mess).
pub fn tuples(mess: &str, tag: &str) -> Vec<Vec<f64>> {
    mess.lines()
        .filter_map(|l| l.find(tag).map(|k| &l[k + tag.len()..]))
        .map(|rest| {
            let a = rest.find('(').unwrap();
            let b = rest.find(')').unwrap();
            rest[a + 1..b]
                .split(',')
                .map(|x| x.trim().parse::<f64>().unwrap())
                .collect()
        })
        .collect()
}
