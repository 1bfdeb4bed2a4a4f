//! The DEFI_LIST_INST events raised inside Newton's iterations
//! (docs/dynamics.md §2): RESI_MAXI (RESI_GLOB_MAXI above the event's
//! value at an iteration) and DIVE_RESI (RESI_GLOB_MAXI decreased at
//! neither of the last two iterations, code_aster's nmevdr), each treated
//! by its own ACTION. They used to be parsed and ignored.

mod common;

use std::path::Path;

/// Runs comm/<study>.comm with `from` replaced by `to` and its .export's
/// mesh paths made absolute.
fn variant(study: &str, tag: &str, edits: &[(&str, &str)]) -> common::Run {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("comm");
    common::run_variant_edits(&root, "newton_events", study, tag, edits)
}

/// D with a time list whose RESI_MAXI event (ACTION='ARRET') is far below
/// the impact step's first residual: the run stops at that step with the
/// event, the residual seen and the threshold, located at DYNA_NON_LINE,
/// and keeps the steps done before (the free flight).
#[test]
fn resi_maxi_stops_the_run_with_arret() {
    let run = variant(
        "sdnv103d",
        "resi_maxi_arret",
        &[
            (
                "RESU = DYNA_NON_LINE(",
                "DLI = DEFI_LIST_INST(DEFI_LIST=_F(LIST_INST=L_INST),\n    ECHEC=_F(EVENEMENT='RESI_MAXI', RESI_GLOB_MAXI=1.E-3, ACTION='ARRET'))\nRESU = DYNA_NON_LINE(",
            ),
            ("INCREMENT=_F(LIST_INST=L_INST,", "INCREMENT=_F(LIST_INST=DLI,"),
        ],
    );
    assert_eq!(run.code, 1, "{}", run.term);
    for want in [
        "event RESI_MAXI: RESI_GLOB_MAXI = ",
        "exceeds the event's RESI_GLOB_MAXI = 1e-3",
        "the event's ACTION is ARRET",
        "resi_maxi_arret.comm:",
        "steps of RESU are saved in",
    ] {
        assert!(run.term.contains(want), "{want}\n{}", run.term);
    }
    assert!(!run.term.contains("panicked"), "{}", run.term);
}

/// B with DIVE_RESI -> DECOUPE (SUBD_PAS = 4) beside its ERREUR rule: the
/// steps whose residual grows at two iterations in a row are cut at once
/// (instead of running to ITER_GLOB_MAXI), each cut follows the event's
/// message, and the run still ends inside the public reference band of
/// B1 DX and A2 DY (the non-regression values, recorded on another step
/// path, are not asserted here).
#[test]
fn dive_resi_cuts_diverging_steps() {
    let run = variant(
        "sdnv103b",
        "dive_resi",
        &[
            ("ECHEC=_F(EVENEMENT='ERREUR',", "ECHEC=(_F(EVENEMENT='ERREUR',"),
            (
                "SUBD_PAS=4,),)",
                "SUBD_PAS=4,),\n                                _F(EVENEMENT='DIVE_RESI', ACTION='DECOUPE', SUBD_PAS=4),),)",
            ),
        ],
    );
    let mess = run.file("dive_resi.mess");
    let events = mess.matches("event DIVE_RESI: RESI_GLOB_MAXI").count();
    assert!(events > 0, "{mess}");
    let lines: Vec<&str> = mess.lines().collect();
    for (i, l) in lines.iter().enumerate() {
        if l.contains("event DIVE_RESI") {
            assert!(
                lines[i + 1].contains("the step is cut into 4 sub-steps"),
                "{l}\n{}",
                lines[i + 1]
            );
        }
    }
    assert!(mess.contains("FIN"), "{mess}");
    let resu = run.file("dive_resi.resu");
    let external: Vec<&str> = resu
        .lines()
        .filter(|l| l.contains("SOURCE_EXTERNE"))
        .collect();
    assert_eq!(external.len(), 2, "{resu}");
    assert!(external.iter().all(|l| l.starts_with(" OK")), "{resu}");
}
