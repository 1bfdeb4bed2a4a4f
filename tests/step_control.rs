//! Step control of DEFI_LIST_INST (semantics.md §7.2, §8.5; docs/dynamics.md
//! §2): the subdivision level shared by all the events, no level under
//! METHODE='AUTO' (PAS_MINI and SUBD_PAS_MINI bound the cuts instead),
//! CONVERGENCE ARRET='NON' only after the ERREUR action failed, and
//! the ADAPTATION rules of METHODE='AUTO'. The studies are in tests/verification/,
//! each with its hand derivation in its header.

mod common;

/// The instant after "last instant " in the stop message.
fn last_instant(term: &str) -> f64 {
    term.split("last instant ")
        .nth(1)
        .and_then(|r| r.split(')').next())
        .and_then(|x| x.parse().ok())
        .unwrap_or_else(|| panic!("no last instant in\n{term}"))
}

/// ERREUR SUBD_NIVEAU=2 beside a DELTA_GRANDEUR rule with SUBD_NIVEAU=4
/// on a plastic collapse (limit at t = 2/3): the ERREUR cuts go to level 4
/// and the run stops after 0.665625, counted by hand in the header (it
/// stopped at 0.65, level 2, with each rule's own level).
#[test]
fn subd_niveau_is_the_largest_over_the_events() {
    let run = common::run_study(
        "tests/verification/step_subd_niveau_shared.comm",
        "step_subd_niveau_shared",
    );
    assert_eq!(run.code, 1, "{}", run.term);
    let mess = run.file("step_subd_niveau_shared.mess");
    assert!(mess.contains("sub-steps of 1.563e-3 (level 4)"), "{mess}");
    assert!(
        run.term
            .contains("maximum subdivision level SUBD_NIVEAU = 4 (the largest over"),
        "{}",
        run.term
    );
    let t = last_instant(&run.term);
    assert!((t - 0.665625).abs() < 1e-12, "last instant {t}");
}

/// The reverse: DELTA_GRANDEUR SUBD_NIVEAU=2 beside ERREUR 6. The uniaxial
/// hardening cube needs level 4 to keep dp under VALE_REF; it completes with
/// the closed form (sigma = 280, p = 3.6e-3 at t = 1; it stopped at t = 0).
#[test]
fn delta_grandeur_cuts_to_the_shared_level() {
    let run = common::run_study(
        "tests/verification/step_subd_niveau_shared_dg.comm",
        "step_subd_niveau_shared_dg",
    );
    common::assert_all_ok(&run, "step_subd_niveau_shared_dg.resu");
    let mess = run.file("step_subd_niveau_shared_dg.mess");
    assert!(mess.contains("(level 4)"), "{mess}");
}

/// METHODE='AUTO' has no subdivision level (code_aster's dinins returns 1):
/// the collapse is cut past SUBD_NIVEAU = 3 until the step chosen after a
/// success falls below PAS_MINI = 1e-4 (ADAPTATION_11), within 1e-4 of the
/// limit instant 2/3 (it stopped on "SUBD_NIVEAU = 3").
#[test]
fn auto_list_has_no_level_and_stops_at_pas_mini() {
    let run = common::run_study(
        "tests/verification/step_auto_pas_mini.comm",
        "step_auto_pas_mini",
    );
    assert_eq!(run.code, 1, "{}", run.term);
    assert!(!run.term.contains("SUBD_NIVEAU"), "{}", run.term);
    assert!(
        run.term
            .contains("is below PAS_MINI = 1e-4 (code_aster ADAPTATION_11)"),
        "{}",
        run.term
    );
    let mess = run.file("step_auto_pas_mini.mess");
    assert!(mess.contains("(level 4)"), "{mess}");
    let t = last_instant(&run.term);
    assert!(t < 2.0 / 3.0 && 2.0 / 3.0 - t < 1e-4, "last instant {t}");
}

/// ARRET='NON' with ERREUR DECOUPE (SUBD_PAS 2, SUBD_NIVEAU 2): the step
/// [0, 1] is cut first; [0, 0.5] is elastic and converges (DZ = -7.5e-4);
/// [0.5, 1] at the last level is accepted unconverged, the Newton iterate
/// of the header (it was accepted at once, with no instant 0.5).
#[test]
fn arret_non_accepts_only_when_the_cut_fails() {
    let run = common::run_study(
        "tests/verification/step_arret_non_cuts.comm",
        "step_arret_non_cuts",
    );
    common::assert_all_ok(&run, "step_arret_non_cuts.resu");
    let mess = run.file("step_arret_non_cuts.mess");
    assert!(mess.contains("2 steps (1 cuts)"), "{mess}");
    assert!(
        mess.contains("accepted (ARRET='NON') because the ERREUR action failed"),
        "{mess}"
    );
}

/// ADAPTATION EVENEMENT='AUCUN' keeps the step: 10 steps of 0.01 on the
/// one-dof bar, u(0.1) by the Newmark recurrence (the step was doubled,
/// u(0.1) = -0.197).
#[test]
fn adaptation_aucun_keeps_the_step() {
    let run = common::run_study("tests/verification/step_auto_aucun.comm", "step_auto_aucun");
    common::assert_all_ok(&run, "step_auto_aucun.resu");
    let mess = run.file("step_auto_aucun.mess");
    assert!(mess.contains("  10 steps (0 cuts)"), "{mess}");
    assert!(mess.contains("EVENEMENT='AUCUN'"), "{mess}");
}

/// Runs tests/verification/<base>.comm with `edits` (from, to) applied,
/// from a scratch copy whose .export names the mesh by its absolute path.
fn variant(base: &str, tag: &str, edits: &[(&str, &str)]) -> common::Run {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/verification");
    common::run_variant_edits(&root, "step_control_variants", base, tag, edits)
}

/// ERREUR ACTION='ITER_SUPPL' is refused by its keyword path and the list's
/// name, located in the file (it printed `IterSuppl { pcent_iter_plus: ..`).
#[test]
fn iter_suppl_is_refused_by_its_keyword() {
    let run = variant(
        "step_subd_niveau_shared",
        "step_iter_suppl",
        &[(
            "ACTION='DECOUPE', SUBD_METHODE='MANUEL', SUBD_PAS=4, SUBD_NIVEAU=2",
            "ACTION='ITER_SUPPL', PCENT_ITER_PLUS=50, SUBD_METHODE='MANUEL', SUBD_PAS=4, SUBD_NIVEAU=2",
        )],
    );
    assert_eq!(run.code, 1, "{}", run.term);
    for want in [
        "not implemented yet: STAT_NON_LINE/INCREMENT",
        "DEFI_LIST_INST/ECHEC/ACTION='ITER_SUPPL' of the ERREUR event of the time list LI",
        "step_iter_suppl.comm:",
    ] {
        assert!(run.term.contains(want), "{want}\n{}", run.term);
    }
    assert!(!run.term.contains("IterSuppl"), "{}", run.term);
    assert!(!run.term.contains("panicked"), "{}", run.term);
}

/// METHODE='AUTO' follows code_aster's ADAPTATION rules (nmadat, diadap,
/// nmcadt, nmevdt): the default SEUIL occurrence (the step doubles after
/// every second convergence), ITER_NEWTON, the smallest of two proposals,
/// DELTA_GRANDEUR and PAS_MAXI, with dt⁻ not taking the length of a step
/// shortened to reach an instant of the list; every instant counted by
/// hand in the study's header (DELTA_GRANDEUR was replaced by doubling,
/// the thresholds ignored).
#[test]
fn adaptation_rules_choose_the_instants_as_code_aster() {
    let run = common::run_study(
        "tests/verification/step_adapt_rules.comm",
        "step_adapt_rules",
    );
    common::assert_all_ok(&run, "step_adapt_rules.resu");
    let mess = run.file("step_adapt_rules.mess");
    assert!(
        mess.contains("2 times the last step (FIXE), each time 2 Newton convergences at an iteration <= 5 have been counted (SEUIL)"),
        "{mess}"
    );
}

/// MODE_CALCUL_TPLUS='IMPLEX' is refused where the list is used (code_aster
/// allows it only with STAT_NON_LINE METHODE='IMPLEX'); a DELTA_GRANDEUR
/// adaptation on a component the model lacks names it, an internal
/// variable no behaviour has too (it never acted, silently).
#[test]
fn adaptation_modes_aster_lacks_are_located_errors() {
    for (tag, to, want) in [
        (
            "step_tplus_implex",
            "    ADAPTATION=_F(EVENEMENT='TOUT_INST', MODE_CALCUL_TPLUS='IMPLEX')",
            "MODE_CALCUL_TPLUS='IMPLEX'",
        ),
        (
            "step_tplus_dg_cmp",
            "    ADAPTATION=_F(EVENEMENT='TOUT_INST', MODE_CALCUL_TPLUS='DELTA_GRANDEUR', VALE_REF=0.05, NOM_CHAM='DEPL', NOM_CMP='DRZ')",
            "ADAPTATION MODE_CALCUL_TPLUS='DELTA_GRANDEUR': the field DEPL has no component 'DRZ'",
        ),
        // An internal variable no behaviour has (ELAS has one, V1, always
        // 0): the rule would never act.
        (
            "step_tplus_dg_vari",
            "    ADAPTATION=_F(EVENEMENT='TOUT_INST', MODE_CALCUL_TPLUS='DELTA_GRANDEUR', VALE_REF=0.05, NOM_CHAM='VARI_ELGA', NOM_CMP='V5')",
            "VARI_ELGA 'V5': the behaviours of the model have at most 1 internal variable(s) (V1 to V1)",
        ),
    ] {
        let run = variant(
            "step_auto_aucun",
            tag,
            &[("    ADAPTATION=_F(EVENEMENT='AUCUN')", to)],
        );
        assert_eq!(run.code, 1, "{tag}: {}", run.term);
        assert!(run.term.contains(want), "{tag}: {}", run.term);
        assert!(run.term.contains(&format!("{tag}.comm:")), "{}", run.term);
        assert!(!run.term.contains("panicked"), "{}", run.term);
    }
}
