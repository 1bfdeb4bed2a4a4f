//! LIAISON_UNIL in explicit dynamics (an aster extension: code_aster stops
//! with MECANONLINE5_23), beyond the TEST_RESU of the three studies
//! tests/verification/explicit_unil_*.comm: the momentum exchanged against
//! the impulse of the reactions (two sums the engine makes independently,
//! Σ M v over the model and the trapezoidal time integral of the link
//! forces), every row of the energy balance, the critical step of the
//! penalty computed by hand, and the errors of what cannot work.

use std::path::{Path, PathBuf};

mod common;
use common::tuples;

const IMPULSE: &str = "impulse of the contact reactions on the bodies ";
const MOMENTUM: &str = "momentum of the model (M v): change over the run ";

/// The landing bar on a LIAISON_UNIL floor (explicit_unil_landing.comm):
/// runs RES_U (kinematic), RES_UP (penalty), RES_K and RES_P (the discrete
/// contact on the same plane), RES_UT (kinematic, TCHAMWA), in that order.
#[test]
fn landing_bar_on_a_unilateral_floor() {
    let run = common::run_study(
        "tests/verification/explicit_unil_landing.comm",
        "explicit_unil_landing",
    );
    let resu = common::assert_all_ok(&run, "explicit_unil_landing.resu");
    let mess = run.file("explicit_unil_landing.mess");
    assert_eq!(
        mess.matches("LIAISON_UNIL in explicit dynamics is an aster extension (code_aster stops with MECANONLINE5_23)")
            .count(),
        3,
        "{mess}"
    );
    let impulse = tuples(&mess, IMPULSE);
    let momentum = tuples(&mess, MOMENTUM);
    assert_eq!((impulse.len(), momentum.len()), (5, 5), "{mess}");
    // p0 = rho R^2/2 L |V0| per radian.
    let p0 = 8.93e-9 * 3.2 * 3.2 / 2.0 * 32.4 * 1.0e4;
    for (k, (i, m)) in impulse.iter().zip(&momentum).enumerate() {
        // No external force: the momentum exchanged is the impulse of the
        // reactions (the brief asks 1 %; the sums agree to round-off).
        assert!(
            (i[1] - m[1]).abs() <= 1e-9 * i[1].abs(),
            "run {k}: impulse {} against momentum change {}",
            i[1],
            m[1]
        );
        // The bar rebounds: the momentum reversed, less the impact's loss.
        let ratio = i[1] / p0;
        assert!((1.85..=2.0).contains(&ratio), "run {k}: {ratio}");
    }
    // The same plane by two implementations: the kinematic enforcements
    // exchange the same momentum, the penalties too (E_N = COEF_PENA).
    assert!((impulse[0][1] - impulse[2][1]).abs() <= 1e-12 * impulse[2][1]);
    assert!((impulse[1][1] - impulse[3][1]).abs() <= 1e-12 * impulse[3][1]);
    // Every row of both DIFF_CENT balances: |DISS_SCH| < 1 % of EK0.
    let ek0 = 74.068992;
    let mut rows = 0;
    for table in ["EN_U", "EN_UP"] {
        for r in common::printed_table(&resu, table) {
            let diss: f64 = r["DISS_SCH"].parse().unwrap();
            assert!(diss.abs() < 0.01 * ek0, "{table}: {r:?}");
            rows += 1;
        }
    }
    assert!(rows >= 60, "{rows} rows");
    // The kinematic impact's loss (notes/explicit.md §10.1): at the
    // first touch the bottom-edge nodes are stopped, a perfectly plastic
    // nodal impact of their lumped mass, and TRAV_LIAI is then 1/2 m V0^2
    // of that layer: 10/36 of a QUAD8 row's mass in plane (HRZ: 1/36 per
    // corner, 8/36 per mid-side node), 1/8 of the bar, so 3.5 % of EK0
    // (3.6 % with AXIS's weight r), then little more.
    let en_u = common::printed_table(&resu, "EN_U");
    let touch: f64 = en_u[1]["TRAV_LIAI"].parse().unwrap();
    let last: f64 = en_u[en_u.len() - 1]["TRAV_LIAI"].parse().unwrap();
    assert!(
        (0.030..0.040).contains(&(touch / ek0)),
        "first touch {touch}"
    );
    assert!(last >= touch && last < 1.05 * touch, "{touch} -> {last}");
}

/// A node against a sloped wall and a second wall (explicit_unil_corner
/// .comm): the momentum it loses, (−1, 0, 0) by hand, is the impulse of
/// the two links' reactions.
#[test]
fn corner_node_momentum_is_the_impulse() {
    let run = common::run_study(
        "tests/verification/explicit_unil_corner.comm",
        "explicit_unil_corner",
    );
    common::assert_all_ok(&run, "explicit_unil_corner.resu");
    let mess = run.file("explicit_unil_corner.mess");
    let i = &tuples(&mess, IMPULSE)[0];
    let m = &tuples(&mess, MOMENTUM)[0];
    for k in 0..3 {
        let want = if k == 0 { -1.0 } else { 0.0 };
        assert!((i[k] - want).abs() < 1e-12, "{i:?}");
        assert!((m[k] - want).abs() < 1e-12, "{m:?}");
    }
}

/// The penalty's critical step on one node (explicit_unil_penalty.comm):
/// 2 / sqrt(a^2 E / m) = 0.2 s for DIFF_CENT, times 1/sqrt(2 PHI − 1) for
/// TCHAMWA (0.18257 s), the alarm of a step cut by more than 10, and the
/// CFL alarm naming the penalty.
#[test]
fn penalty_step_is_the_hand_computed_one() {
    let run = common::run_study(
        "tests/verification/explicit_unil_penalty.comm",
        "explicit_unil_penalty",
    );
    common::assert_all_ok(&run, "explicit_unil_penalty.resu");
    let mess = run.file("explicit_unil_penalty.mess");
    let steps: Vec<f64> = mess
        .lines()
        .filter_map(|l| l.split_once(": critical step "))
        .map(|(_, r)| r.split_whitespace().next().unwrap().parse().unwrap())
        .collect();
    let m: f64 = 4.0 * 2.0 / 8.0;
    let dc = 2.0 / (4.0 * 25.0 / m).sqrt();
    let tw = dc / (2.0f64 * 1.1 - 1.0).sqrt();
    assert_eq!(steps.len(), 3, "{mess}");
    for (got, want) in steps.iter().zip([dc, tw, dc]) {
        // The .mess prints 7 digits.
        assert!((got - want).abs() <= 1e-6 * want, "{got} vs {want}");
    }
    assert_eq!(
        mess.matches("alarm: the contact penalty shrinks the stable step by more than 10 times")
            .count(),
        3
    );
    assert!(
        mess.contains("exceeds the critical step 2.000000e-1 set by the contact penalty")
            && mess.contains("STOP_CFL='NON'"),
        "{mess}"
    );
}

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/verification")
}

/// Runs explicit_unil_corner.comm with `from` replaced by `to`.
fn run_variant(tag: &str, from: &str, to: &str) -> common::Run {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("explicit_unil_bad");
    std::fs::create_dir_all(&tmp).unwrap();
    let comm = std::fs::read_to_string(dir().join("explicit_unil_corner.comm")).unwrap();
    assert!(comm.contains(from), "{tag}: {from}");
    std::fs::write(tmp.join(format!("{tag}.comm")), comm.replacen(from, to, 1)).unwrap();
    std::fs::write(
        tmp.join(format!("{tag}.export")),
        format!("F mmed {} D 20\n", dir().join("block.mmed").display()),
    )
    .unwrap();
    common::run_study(
        tmp.join(format!("{tag}.comm")).to_str().unwrap(),
        &format!("explicit_unil_bad_{tag}"),
    )
}

/// What cannot run stops with exit 1 and a message that says why, never a
/// panic: contradictory links on one node (no correction satisfies both),
/// a COEF_IMPO undefined at a step end of the list, the consistent mass.
#[test]
fn what_cannot_run_is_a_located_error() {
    let cases: [(&str, &str, &str, &[&str]); 3] = [
        (
            "contradictory",
            "_F(GROUP_NO='HAUT_C', NOM_CMP='DY', COEF_MULT=MUN, COEF_IMPO=D)",
            "_F(GROUP_NO='HAUT_C', NOM_CMP=('DX', 'DY'), COEF_MULT=(MUN, MUN), COEF_IMPO=MUN)",
            &[
                "DYNA_NON_LINE",
                "LIAISON_UNIL at INST = 1e0: the links of node N",
                "cannot all be satisfied",
                "MECANONLINE9_6",
            ],
        ),
        (
            "domain",
            "UN = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 1., 8., 1.))",
            "UN = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 1., 4., 1.))",
            &[
                "DYNA_NON_LINE/CONTACT",
                "LIAISON_UNIL at INST = 8e0: ZONE 1, COEF_MULT",
                // The function by its concept's name, not TOUTRESU.
                "COEF_MULT: UN(INST=",
                "domain.comm:",
            ],
        ),
        (
            "consistent",
            "                    MASS_DIAG='OUI',\n",
            "",
            &[
                "DYNA_NON_LINE/CONTACT",
                "consistent mass",
                "MASS_DIAG='OUI'",
            ],
        ),
    ];
    for (tag, from, to, want) in cases {
        let run = run_variant(tag, from, to);
        assert_eq!(run.code, 1, "{tag}: {}", run.term);
        assert!(!run.term.contains("panicked"), "{tag}: {}", run.term);
        for w in want {
            assert!(run.term.contains(w), "{tag}: {w}\n{}", run.term);
        }
    }
}

/// SDNV103 E's physics explicitly (tests/verification/sdnv103e_explicit
/// .comm): its TEST_RESU check the free flight of A2 and B1 and A1 on the
/// stop against the analytic values; here, the momentum the stop takes
/// out of the bar is the impulse of its reactions, along Z only.
#[test]
fn sdnv103e_explicit_momentum_is_the_impulse() {
    let run = common::run_study(
        "tests/verification/sdnv103e_explicit.comm",
        "sdnv103e_explicit",
    );
    common::assert_all_ok(&run, "sdnv103e_explicit.resu");
    let mess = run.file("sdnv103e_explicit.mess");
    let i = &tuples(&mess, IMPULSE)[0];
    let m = &tuples(&mess, MOMENTUM)[0];
    assert!(
        i[2] > 0.0 && (i[2] - m[2]).abs() <= 1e-9 * i[2],
        "{i:?} {m:?}"
    );
    assert!(
        i[0] == 0.0 && i[1] == 0.0 && m[0].abs() < 1e-12 * i[2],
        "{i:?} {m:?}"
    );
}

/// A floor that rises into a cube (tests/verification/unil_rising_floor.comm,
/// its TEST_RESU the hand values): under DIFF_CENT and TCHAMWA the printed
/// impulse of the reactions is the momentum the cube gains, m W (TCHAMWA
/// updates v with the step's start acceleration, so its impulse weighs the
/// step's start force; it printed the trapezoid, 4.09e-4); and the floor's
/// motion is neither an initial violation (explicit) nor energy created by
/// the scheme (implicit NEWMARK): no alarm says so.
#[test]
fn a_rising_floor_gives_its_impulse_and_no_false_alarm() {
    let run = common::run_study(
        "tests/verification/unil_rising_floor.comm",
        "unil_rising_floor",
    );
    common::assert_all_ok(&run, "unil_rising_floor.resu");
    let mess = run.file("unil_rising_floor.mess");
    let impulse = tuples(&mess, IMPULSE);
    let momentum = tuples(&mess, MOMENTUM);
    assert_eq!((impulse.len(), momentum.len()), (2, 2), "{mess}");
    let mw = 7.8e-9 * 1000.0 * 100.0;
    for (k, (i, m)) in impulse.iter().zip(&momentum).enumerate() {
        assert!((i[2] - mw).abs() <= 1e-12 * mw, "run {k}: impulse {}", i[2]);
        assert!(
            (m[2] - mw).abs() <= 1e-12 * mw,
            "run {k}: momentum {}",
            m[2]
        );
    }
    assert!(!mess.contains("violated at the initial state"), "{mess}");
    assert!(!mess.contains("more energy than it absorbed"), "{mess}");
}

/// RECH_LINEAIRE, written by a user who converts an implicit file, has no
/// effect in explicit (code_aster accepts it there; notes/explicit.md §2):
/// the run goes on with the note that says so (probe
/// rech_lineaire_explicit: it stopped as not implemented).
#[test]
fn line_search_is_accepted_without_effect_in_explicit() {
    let run = run_variant(
        "rech",
        "SCHEMA_TEMPS=_F(SCHEMA='DIFF_CENT'",
        "RECH_LINEAIRE=_F(), SCHEMA_TEMPS=_F(SCHEMA='DIFF_CENT'",
    );
    assert_eq!(run.code, 0, "{}", run.term);
    let mess = run.file("rech.mess");
    assert!(
        mess.contains(
            "CONVERGENCE, NEWTON and RECH_LINEAIRE have no effect with an explicit scheme"
        ),
        "{mess}"
    );
}

/// Without CONVERGENCE, NEWTON or RECH_LINEAIRE in the command file the
/// note is not given (probe15: it was given in every explicit run, the
/// catalogue's defaults filling CONVERGENCE and NEWTON).
#[test]
fn no_note_on_convergence_keywords_the_file_does_not_write() {
    let run = run_variant(
        "plain",
        "SCHEMA_TEMPS=_F(SCHEMA='DIFF_CENT'",
        "SCHEMA_TEMPS=_F(SCHEMA='DIFF_CENT'",
    );
    assert_eq!(run.code, 0, "{}", run.term);
    let mess = run.file("plain.mess");
    assert!(
        !mess.contains("have no effect with an explicit scheme"),
        "{mess}"
    );
}
