//! Running the ten SDNV103 studies: every command before the first one
//! whose engine is not built yet runs (the mesh commands in particular),
//! and the run stops on a clear "not implemented yet" error, exit code 1,
//! with the .mess and .resu files written.

use std::path::Path;

use aster::run::driver::{run_file, RunOptions};

#[test]
fn mesh_commands_of_every_study_run() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for m in ["a", "b", "d", "e", "f", "g", "h", "i", "j", "k"] {
        let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("study_{m}"));
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
        let mess = std::fs::read_to_string(out.join(format!("sdnv103{m}.mess"))).unwrap();
        assert!(out.join(format!("sdnv103{m}.resu")).is_file());
        let comm = std::fs::read_to_string(root.join(format!("comm/sdnv103{m}.comm"))).unwrap();
        for cmd in [
            "LIRE_MAILLAGE",
            "DEFI_GROUP",
            "MODI_MAILLAGE",
            "CREA_MAILLAGE",
        ] {
            let written = comm.matches(&format!("{cmd}(")).count();
            let done = mess.matches(&format!("{cmd} done")).count();
            assert_eq!(
                written, done,
                "study {m}: {cmd} written {written} times, ran {done}:\n{mess}"
            );
        }
        if code != 0 {
            assert_eq!(code, 1);
            assert!(
                term.contains("not implemented yet"),
                "study {m} failed otherwise:\n{term}"
            );
        }
    }
}

/// B and D without their contact definition run to FIN (issue: the engine
/// without contact handles the whole study).
#[test]
fn b_and_d_without_contact_run_to_the_end() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for m in ["b", "d"] {
        let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("sans_contact_{m}"));
        let mut term = Vec::new();
        let code = run_file(
            &RunOptions {
                comm: root.join(format!("tests/studies/sdnv103{m}_sans_contact.comm")),
                out_dir: Some(out.clone()),
                ..RunOptions::default()
            },
            &mut term,
        );
        let term = String::from_utf8(term).unwrap();
        assert_eq!(code, 0, "{m}:\n{term}");
        let mess =
            std::fs::read_to_string(out.join(format!("sdnv103{m}_sans_contact.mess"))).unwrap();
        assert!(
            mess.contains("DYNA_NON_LINE done") && mess.contains("FIN done"),
            "{mess}"
        );
    }
}

/// A run that stops on a failed step reports the instant and the rule, and
/// saves what it computed before in a MED file next to the .mess.
#[test]
fn a_stopped_run_keeps_its_results_on_disk() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("stop_plain_list");
    let _ = std::fs::remove_dir_all(&out);
    let mut term = Vec::new();
    let code = run_file(
        &RunOptions {
            comm: root.join("tests/studies/stop_plain_list.comm"),
            out_dir: Some(out.clone()),
            // result files of IMPR_RESU go to this test's own directory
            units: vec![(80, out.join("resu.rmed"))],
            ..RunOptions::default()
        },
        &mut term,
    );
    let term = String::from_utf8(term).unwrap();
    assert_eq!(code, 1, "{term}");
    assert!(
        term.contains("DYNA_NON_LINE") && term.contains("ARRET"),
        "{term}"
    );
    assert!(term.contains("stop_plain_list.comm:13:1"), "{term}");
    let file = out.join("stop_plain_list_RESU.rmed");
    assert!(term.contains("saved in"), "{term}");
    let fields = aster::medio::read_nodal_fields(&file, None).unwrap();
    let depl = fields
        .iter()
        .find(|f| f.name == "RESU____DEPL")
        .expect("DEPL saved");
    assert!(!depl.steps.is_empty());
}
