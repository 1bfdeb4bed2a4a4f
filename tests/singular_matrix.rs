//! A singular stiffness stops the run as code_aster's direct solvers stop
//! it (SOLVEUR NPREC, STOP_SINGULIER; `solver::SingularityCheck`): the
//! HEXS20 column of tests/studies/hexs20_bending.comm, exact with two
//! cells across, has an unheld zero-energy mode with one cell across.

use std::path::{Path, PathBuf};

mod common;

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/studies")
}

/// hexs20_bending.comm with every (from, to) replaced once (each must
/// occur), run from a scratch directory with the .export's paths made
/// absolute.
fn variant(tag: &str, edits: &[(&str, &str)]) -> common::Run {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("singular_matrix");
    std::fs::create_dir_all(&tmp).unwrap();
    let mut comm = std::fs::read_to_string(dir().join("hexs20_bending.comm")).unwrap();
    for (from, to) in edits {
        assert!(comm.contains(from), "{tag}: {from}");
        comm = comm.replacen(from, to, 1);
    }
    std::fs::write(tmp.join(format!("{tag}.comm")), comm).unwrap();
    let export: String = std::fs::read_to_string(dir().join("hexs20_bending.export"))
        .unwrap()
        .lines()
        .map(|l| {
            let mut w: Vec<String> = l.split_whitespace().map(String::from).collect();
            w[2] = dir().join(&w[2]).display().to_string();
            w.join(" ") + "\n"
        })
        .collect();
    std::fs::write(tmp.join(format!("{tag}.export")), export).unwrap();
    common::run_study(tmp.join(format!("{tag}.comm")).to_str().unwrap(), tag)
}

const ONE_CELL: (&str, &str) = ("UNITE=21", "UNITE=20");

/// Two cells across: the quadratic field is reproduced (DX = -5e-3 to
/// 1e-6 relative, by the command file) in both commands,
/// and the check (NPREC 8) lets the legitimate matrix through.
#[test]
fn supported_column_is_exact() {
    let run = common::run_study("tests/studies/hexs20_bending.comm", "hexs20_bending");
    common::assert_all_ok(&run, "hexs20_bending.resu");
    let mess = run.file("hexs20_bending.mess");
    assert!(
        mess.contains("NPREC and STOP_SINGULIER are honoured"),
        "{mess}"
    );
    assert!(!mess.contains("alarm: the matrix is singular"), "{mess}");
}

/// One cell across: STAT_NON_LINE stops at its first step with the dof
/// where the decimals were lost and the likely causes, located at the
/// command, and keeps what was archived (the initial state).
#[test]
fn spurious_mode_stops_stat_non_line() {
    let run = variant("one_cell", &[ONE_CELL]);
    assert_eq!(run.code, 1, "{}", run.term);
    let t = &run.term;
    for part in [
        "error: STAT_NON_LINE",
        "the matrix is singular: ",
        "decimals lost at the pivot of node N",
        "(SOLVEUR NPREC = 8, STOP_SINGULIER='OUI')",
        "zero-energy (spurious) mode of under-integrated elements",
        "a perfectly plastic structure at its limit load",
        "one_cell.comm:26:1",
        "are kept in the result",
    ] {
        assert!(t.contains(part), "{part}:\n{t}");
    }
    // The pivot lost far more than 8 decimals: a true singularity (the
    // round-off of a 1e5 stiffness), not a borderline one.
    let lost: f64 = t
        .split("the matrix is singular: ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|d| d.parse().ok())
        .expect("a number of decimals");
    assert!(lost > 12.0, "{lost}");
    assert!(!t.contains("MECA_STATIQUE"), "{t}");
}

/// STOP_SINGULIER='NON' goes on (the alarm in the .mess names the dof);
/// MECA_STATIQUE, with MULT_FRONT's default, stops at its own line.
#[test]
fn stop_singulier_non_goes_on_with_an_alarm() {
    let run = variant(
        "one_cell_non",
        &[
            ONE_CELL,
            (
                "SOLVEUR=_F(METHODE='MUMPS')",
                "SOLVEUR=_F(METHODE='MUMPS', STOP_SINGULIER='NON')",
            ),
        ],
    );
    assert_eq!(run.code, 1, "{}", run.term);
    let mess = run.file("one_cell_non.mess");
    let alarm = mess
        .lines()
        .find(|l| l.contains("alarm: the matrix is singular or nearly"))
        .unwrap_or_else(|| panic!("{mess}"));
    assert!(
        alarm.contains("decimals lost at the pivot of node N")
            && alarm.contains("STOP_SINGULIER='NON'"),
        "{alarm}"
    );
    assert!(mess.contains("STAT_NON_LINE done"), "{mess}");
    let t = &run.term;
    assert!(t.contains("error: MECA_STATIQUE"), "{t}");
    assert!(t.contains("one_cell_non.comm:29:"), "{t}");
    assert!(t.contains("decimals lost at the pivot of node N"), "{t}");
}

/// NPREC < 0 turns the test off for MUMPS (no alarm, the run goes on) but
/// not for MULT_FRONT, which reads |NPREC| (code_aster's U4.50.01).
#[test]
fn negative_nprec_is_read_as_each_method_reads_it() {
    let run = variant(
        "one_cell_nprec",
        &[
            ONE_CELL,
            (
                "SOLVEUR=_F(METHODE='MUMPS')",
                "SOLVEUR=_F(METHODE='MUMPS', NPREC=-1)",
            ),
            (
                "SOLVEUR=_F(METHODE='MULT_FRONT')",
                "SOLVEUR=_F(METHODE='MULT_FRONT', NPREC=-8)",
            ),
        ],
    );
    let mess = run.file("one_cell_nprec.mess");
    assert!(mess.contains("STAT_NON_LINE done"), "{mess}");
    assert!(!mess.contains("alarm: the matrix is singular"), "{mess}");
    assert!(run.term.contains("error: MECA_STATIQUE"), "{}", run.term);
    assert!(run.term.contains("(SOLVEUR NPREC = 8,"), "{}", run.term);
}

/// A DEFI_LIST_INST whose ERREUR rule cuts the step: the singular step is
/// cut as the rule says (cutting cannot cure it), then the run stops.
#[test]
fn singular_step_is_cut_as_the_time_list_says() {
    let run = variant(
        "one_cell_cut",
        &[
            ONE_CELL,
            (
                "CM = AFFE_MATERIAU",
                "DL = DEFI_LIST_INST(DEFI_LIST=_F(LIST_INST=LI), ECHEC=_F(EVENEMENT='ERREUR', \
                 ACTION='DECOUPE', SUBD_METHODE='MANUEL', SUBD_PAS=2, SUBD_NIVEAU=3))\nCM = AFFE_MATERIAU",
            ),
            ("INCREMENT=_F(LIST_INST=LI)", "INCREMENT=_F(LIST_INST=DL)"),
        ],
    );
    assert_eq!(run.code, 1, "{}", run.term);
    let mess = run.file("one_cell_cut.mess");
    let failures = mess
        .lines()
        .filter(|l| l.contains("step failure") && l.contains("decimals lost"))
        .count();
    assert!(failures >= 2, "{failures}:\n{mess}");
    assert!(run.term.contains("error: STAT_NON_LINE"), "{}", run.term);
    assert!(run.term.contains("are kept in the result"), "{}", run.term);
}
