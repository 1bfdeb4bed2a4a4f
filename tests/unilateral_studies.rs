//! LIAISON_UNIL written wrong, as a user could: each variant of the AXIS
//! drop study (tests/verification/unil_axis_drop.comm) must stop with exit
//! code 1 and an error that names the command, the keyword and the line
//! and column in the file — never a panic, never a silent run.

use std::path::{Path, PathBuf};

mod common;

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/verification")
}

/// Runs each variant (tag, text replaced, replacement, message parts) and
/// asserts it stops with exit 1, no panic, and a message holding every part.
fn expect_errors(cases: &[(&str, &str, &str, &[&str])]) {
    for &(tag, from, to, want) in cases {
        let run = run_variant(tag, from, to);
        assert_eq!(run.code, 1, "{tag}: {}", run.term);
        assert!(!run.term.contains("panicked"), "{tag}: {}", run.term);
        for w in want {
            assert!(run.term.contains(w), "{tag}: {w}\n{}", run.term);
        }
    }
}

/// Runs `comm` with `from` replaced by `to` (which must occur) as
/// `<tag>.comm` on the study's mesh.
fn run_variant(tag: &str, from: &str, to: &str) -> common::Run {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("unil_studies_bad");
    std::fs::create_dir_all(&tmp).unwrap();
    let comm = std::fs::read_to_string(dir().join("unil_axis_drop.comm")).unwrap();
    assert!(comm.contains(from), "{tag}: {from}");
    let text = comm.replacen(from, to, 1);
    std::fs::write(tmp.join(format!("{tag}.comm")), text).unwrap();
    std::fs::write(
        tmp.join(format!("{tag}.export")),
        format!("F mmed {} D 20\n", dir().join("unil_axis.mmed").display()),
    )
    .unwrap();
    common::run_study(
        tmp.join(format!("{tag}.comm")).to_str().unwrap(),
        &format!("unil_bad_{tag}"),
    )
}

const FLOOR: &str = "ZONE=_F(GROUP_MA='SZZ', NOM_CMP='DY', COEF_MULT=MUN, COEF_IMPO=FH))\nPLAF";

#[test]
fn bad_unilateral_definitions_are_located_errors() {
    let cases: [(&str, &str, &str, &[&str]); 10] = [
        (
            // A discrete zone's keyword in a LIAISON_UNIL zone says where
            // it belongs, as a top-level one does (probe minor_messages).
            "master_in_unil_zone",
            FLOOR,
            "ZONE=_F(GROUP_MA='SZZ', NOM_CMP='DY', COEF_MULT=MUN, COEF_IMPO=FH, GROUP_MA_MAIT='SZZ'))\nPLAF",
            &[
                "DEFI_CONTACT/ZONE/GROUP_MA_MAIT",
                "keyword GROUP_MA_MAIT of ZONE is not allowed here: ZONE has it only when FORMULATION='DISCRETE'",
                "master_in_unil_zone.comm:",
            ],
        ),
        (
            "dz_in_axis",
            FLOOR,
            "ZONE=_F(GROUP_MA='SZZ', NOM_CMP='DZ', COEF_MULT=MUN, COEF_IMPO=FH))\nPLAF",
            &[
                "DEFI_CONTACT/ZONE/NOM_CMP",
                "none of NOM_CMP (DZ) is a degree of freedom of the model MO",
                "UNILATER_48",
                "expected one of: 'DX', 'DY'",
                "dz_in_axis.comm:53:",
            ],
        ),
        (
            "lengths",
            FLOOR,
            "ZONE=_F(GROUP_MA='SZZ', NOM_CMP='DY', COEF_MULT=(MUN, MUN), COEF_IMPO=FH))\nPLAF",
            &[
                "DEFI_CONTACT/ZONE/COEF_MULT",
                "NOM_CMP gives 1 component(s) and COEF_MULT 2 coefficient(s)",
                "lengths.comm:53:",
            ],
        ),
        (
            "empty",
            FLOOR,
            "ZONE=_F(GROUP_MA='SZZ', SANS_GROUP_NO='SZZ', NOM_CMP='DY', COEF_MULT=MUN, COEF_IMPO=FH))\nPLAF",
            &["DEFI_CONTACT/ZONE", "keeps no node", "UNILATER_48", "empty.comm:53:"],
        ),
        (
            "no_group",
            FLOOR,
            "ZONE=_F(GROUP_MA='SOL', NOM_CMP='DY', COEF_MULT=MUN, COEF_IMPO=FH))\nPLAF",
            &[
                "DEFI_CONTACT/ZONE/GROUP_MA",
                "has no cell group (GROUP_MA) 'SOL'",
                "no_group.comm:53:",
            ],
        ),
        (
            "real_coef",
            FLOOR,
            "ZONE=_F(GROUP_MA='SZZ', NOM_CMP='DY', COEF_MULT=-1., COEF_IMPO=FH))\nPLAF",
            &[
                "DEFI_CONTACT/ZONE/COEF_MULT",
                "expected a concept of type fonction_sdaster or formule, found the real -1.0",
                "real_coef.comm:53:",
            ],
        ),
        (
            "explicit",
            "ETAT_INIT=_F(VITE=VDOWN), INCREMENT=_F(LIST_INST=LI),\n                    SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'))\nREC",
            "ETAT_INIT=_F(VITE=VDOWN), INCREMENT=_F(LIST_INST=LI),\n                    SCHEMA_TEMPS=_F(SCHEMA='DIFF_CENT', FORMULATION='ACCELERATION'))\nREC",
            &[
                "DYNA_NON_LINE/CONTACT",
                "contact in explicit dynamics with the consistent mass (give MASS_DIAG='OUI')",
                "explicit.comm:62:",
            ],
        ),
        (
            "pena_without_coef",
            "ALGO_CONT='PENALISATION', COEF_PENA=1.E12))",
            "ALGO_CONT='PENALISATION'))",
            &["DEFI_CONTACT/ZONE/COEF_PENA", "missing compulsory keyword COEF_PENA", "pena_without_coef.comm:59:"],
        ),
        (
            "domain",
            "FH = DEFI_CONSTANTE(VALE=H)",
            "FH = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., H, 1.E-5, H))",
            &[
                "DYNA_NON_LINE/CONTACT",
                "LIAISON_UNIL at INST = 1.5e-5: ZONE 1, COEF_IMPO",
                "outside the domain [0.0, 1e-05]",
                "PROL_DROITE='EXCLU'",
                "domain.comm:62:",
            ],
        ),
        (
            "cont_noeu",
            "IMPR_TABLE(TABLE=T)",
            "TC = POST_RELEVE_T(ACTION=_F(INTITULE='C', RESULTAT=RES, NOM_CHAM='CONT_NOEU', GROUP_NO='SZZ', TOUT_CMP='OUI', OPERATION='EXTRACTION'))",
            &[
                "POST_RELEVE_T/ACTION/NOM_CHAM",
                "LIAISON_UNIL produces no CONT_NOEU, as in code_aster: the reactions are REAC_NODA of CALC_CHAMP",
                "cont_noeu.comm:",
            ],
        ),
    ];
    expect_errors(&cases);
}

/// COEF_IMPO depends on the node (its X, Y, Z): when its evaluation fails
/// at one node only, the error names that node and its coordinates
/// (probe unilp, 2026-11-28: a DEFI_FONCTION of X whose domain misses the
/// outer nodes said "FX(X=3.2) is outside the domain" without the node).
/// The tilted floor of the study, FX of X on [0, 10], is cut to
/// [0, 1.8]: the bottom node on the axis is inside, the outer one N2
/// (X = 3.2, Y = 2.27) is not.
#[test]
fn coef_impo_failing_at_one_node_names_the_node() {
    expect_errors(&[(
        "impo_x_domain",
        "FX = DEFI_FONCTION(NOM_PARA='X', VALE=(0., H, 10., H - 1.))",
        "FX = DEFI_FONCTION(NOM_PARA='X', VALE=(0., H, 1.8, H - 0.18))",
        &[
            "DYNA_NON_LINE/CONTACT",
            "ZONE 1, COEF_IMPO at node N2 (X = 3.2, Y = 2.27, Z = 0): FX(X=3.2)",
            "outside the domain [0.0, 1.8]",
            "PROL_DROITE='EXCLU'",
            "impo_x_domain.comm:",
        ],
    )]);
}

/// A COEF_PENA that is not positive is refused by DEFI_CONTACT itself,
/// before any computation uses the contact (probe of 2026-11-28: it was
/// found only when DYNA_NON_LINE built its term, after the .mess had
/// shown DEFI_CONTACT done).
#[test]
fn a_non_positive_coef_pena_stops_defi_contact() {
    for (tag, value) in [("pena_zero", "0."), ("pena_negative", "-1.E6")] {
        let run = run_variant(
            tag,
            "ALGO_CONT='PENALISATION', COEF_PENA=1.E12))",
            &format!("ALGO_CONT='PENALISATION', COEF_PENA={value}))"),
        );
        let mess = run.file(&format!("{tag}.mess"));
        assert_eq!(run.code, 1, "{tag}: {}", run.term);
        assert!(
            run.term.contains("DEFI_CONTACT/ZONE/COEF_PENA")
                && run.term.contains("COEF_PENA must be > 0"),
            "{tag}: {}",
            run.term
        );
        let last = mess.lines().rfind(|l| l.starts_with("# ---- "));
        assert!(
            last.is_some_and(|l| l.ends_with("= DEFI_CONTACT (line 58)")),
            "{tag}: the penalised DEFI_CONTACT should stop the study\n{mess}"
        );
    }
}

/// NOM_CMP naming a component the model lacks next to one it has is
/// accepted, as code_aster's creaun accepts it (the component is dropped
/// with the note UNILATER_75), and gives the same motion.
#[test]
fn absent_component_is_dropped_with_a_note() {
    let run = run_variant(
        "dy_dz",
        FLOOR,
        "ZONE=_F(GROUP_MA='SZZ', NOM_CMP=('DY', 'DZ'), COEF_MULT=(MUN, MUN), COEF_IMPO=FH))\nPLAF",
    );
    let resu = common::assert_all_ok(&run, "dy_dz.resu");
    assert!(resu.contains(" OK "));
    assert!(
        run.file("dy_dz.mess").contains(
            "zone 1: NOM_CMP DZ dropped: not a degree of freedom of the model MO (UNILATER_75)"
        ),
        "{}",
        run.file("dy_dz.mess")
    );
}

/// COEF_IMPO is evaluated at the step ends only (t+), never at the
/// initial instant: a function defined from the first step end on is
/// valid, as in code_aster.
#[test]
fn coefficients_are_evaluated_at_the_step_ends_only() {
    let run = run_variant(
        "from_first_end",
        "FH = DEFI_CONSTANTE(VALE=H)",
        "FH = DEFI_FONCTION(NOM_PARA='INST', VALE=(DT, H, 1., H))",
    );
    common::assert_all_ok(&run, "from_first_end.resu");
}

/// The same node in two zones, both links violated in one step: the
/// Schur complement is singular (MECANONLINE9_6, as code_aster's code 2),
/// DEFI_LIST_INST cuts the step, and in the sub-steps the node meets its
/// stricter wall first: DX + DY of A1 is 2 sqrt(2) to 1e-12 when held and
/// never above (tests/studies/unil_two_zones_cut.comm).
#[test]
fn same_node_in_two_zones_cut_then_held_on_the_stricter_wall() {
    let run = common::run_study(
        "tests/studies/unil_two_zones_cut.comm",
        "unil_two_zones_cut",
    );
    assert_eq!(run.code, 0, "{}", run.term);
    let mess = run.file("unil_two_zones_cut.mess");
    for what in [
        "step failure from t = 9e-6 to 1.2e-5",
        "singular at link 8",
        "zone 2 of LIAISON_UNIL, node N1 at (0, 0, 2.27)",
        "MECANONLINE9_6",
        "the step is cut into 4 sub-steps",
    ] {
        assert!(mess.contains(what), "{what}\n{mess}");
    }
    let resu = run.file("unil_two_zones_cut.resu");
    let c2 = 2.0 * 2f64.sqrt();
    let rows: Vec<(f64, f64)> = resu
        .lines()
        .skip_while(|l| !l.starts_with("INST"))
        .skip(1)
        .map_while(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .filter_map(|x| x.parse().ok())
                .collect();
            (v.len() == 3).then(|| (v[0], v[1] + v[2]))
        })
        .collect();
    assert_eq!(rows.len(), 9, "{resu}");
    for &(t, s) in &rows {
        assert!(s <= c2 + 1e-12, "t = {t}: DX + DY = {s} beyond {c2}");
    }
    let held: Vec<f64> = rows
        .iter()
        .filter(|r| (r.1 - c2).abs() <= 1e-12)
        .map(|r| r.0)
        .collect();
    assert_eq!(held, vec![9e-6, 9.75e-6], "{rows:?}");
}

/// FORMULE for COEF_IMPO and COEF_MULT (code_aster's COEF_IMPO takes
/// fonction, nappe or formule): the tilted floor H - P X as a formula of
/// X (H a variable of the command file, P=0.1 passed as a keyword), the
/// floor 2.27 as a formula of INST and Y, COEF_MULT -1 as a formula of
/// INST give the study's checks, all OK.
#[test]
fn formulas_give_the_same_floors() {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("unil_studies_formule");
    std::fs::create_dir_all(&tmp).unwrap();
    let comm = std::fs::read_to_string(dir().join("unil_axis_drop.comm")).unwrap();
    let mut text = comm.clone();
    for (from, to) in [
        (
            "FX = DEFI_FONCTION(NOM_PARA='X', VALE=(0., H, 10., H - 1.))",
            "FX = FORMULE(VALE='H - P * X', NOM_PARA='X', P=0.1)",
        ),
        (
            "FH = DEFI_CONSTANTE(VALE=H)",
            "FH = FORMULE(VALE='2.27 + 0. * INST * Y', NOM_PARA=('INST', 'Y'))",
        ),
        (
            "MUN = DEFI_CONSTANTE(VALE=-1.)",
            "MUN = FORMULE(VALE='-1. + 0. * sin(INST)', NOM_PARA='INST')",
        ),
    ] {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    std::fs::write(tmp.join("formule.comm"), text).unwrap();
    std::fs::write(
        tmp.join("formule.export"),
        format!("F mmed {} D 20\n", dir().join("unil_axis.mmed").display()),
    )
    .unwrap();
    let run = common::run_study(tmp.join("formule.comm").to_str().unwrap(), "unil_formule");
    common::assert_all_ok(&run, "formule.resu");
}

/// A FORMULE naming an undefined constant, a
/// COEF_MULT formula of X (COEF_MULT is evaluated with INST only, as in
/// code_aster), and a formula where a tabulated function is needed are
/// located errors.
#[test]
fn bad_formulas_are_located_errors() {
    let cases: [(&str, &str, &str, &[&str]); 3] = [
        (
            "formule_constant",
            "FX = DEFI_FONCTION(NOM_PARA='X', VALE=(0., H, 10., H - 1.))",
            "FX = FORMULE(VALE='H0 - 0.1 * X', NOM_PARA='X')",
            &[
                "FORMULE/VALE",
                "name 'H0' in VALE 'H0 - 0.1 * X' is neither a parameter of NOM_PARA (X)",
                "formule_constant.comm:51:",
            ],
        ),
        (
            "formule_mult_of_x",
            "MUN = DEFI_CONSTANTE(VALE=-1.)",
            "MUN = FORMULE(VALE='-1. + 0. * X', NOM_PARA='X')",
            &[
                "DYNA_NON_LINE/CONTACT",
                "ZONE 1, COEF_MULT: the formula '-1. + 0. * X' needs X, which is not among the parameters given here (INST)",
                "formule_mult_of_x.comm:62:",
            ],
        ),
        (
            "formule_elsewhere",
            "MUN = DEFI_CONSTANTE(VALE=-1.)",
            "MUN = DEFI_CONSTANTE(VALE=-1.)\nFM = FORMULE(VALE='INST', NOM_PARA='INST')\nLF = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=2))\nIMPR_FONCTION(COURBE=_F(FONCTION=FM))",
            &["IMPR_FONCTION/COURBE/FONCTION", "formule"],
        ),
    ];
    expect_errors(&cases);
}

/// What code_aster stops with DYNA_NON_LINE around LIAISON_UNIL, and what
/// aster does not build, are located errors (probes
/// unil_solveur_gcpc_accepted and coef_mass_shift_ignored: both ran
/// silently on the direct solver and the plain mass).
#[test]
fn iterative_solver_and_mass_shift_are_located_errors() {
    let schema =
        "                    SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'))\nREC";
    expect_errors(&[
        (
            "gcpc",
            schema,
            "                    SOLVEUR=_F(METHODE='GCPC'),\n                    SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'))\nREC",
            &[
                "DYNA_NON_LINE/SOLVEUR/METHODE",
                "METHODE='GCPC'",
                "MECANONLINE3_96",
                "gcpc.comm:",
            ],
        ),
        (
            "mass_shift",
            schema,
            "                    SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT', COEF_MASS_SHIFT=1.E-12))\nREC",
            &[
                "not implemented yet: DYNA_NON_LINE/SCHEMA_TEMPS/COEF_MASS_SHIFT",
                "mass_shift.comm:",
            ],
        ),
    ]);
}

/// A link on a component imposed by DDL_IMPO (the corner P0 of the floor
/// zone held at DZ = 0, tests/studies/unil_ddl_conflict.comm): once the
/// floor passes P0 its link, without unknown, is dropped from the active
/// set next to the three others (code_aster's zero-row test) and its
/// penalty has nothing to act on; the imposed DZ = 0 wins (in the command
/// file, with P3 on the floor at 0.02 to 1e-8), and each run writes the
/// alarm naming the link, its node and the largest violation, f(1) = 0.02.
#[test]
fn link_on_an_imposed_component_is_left_violated_with_an_alarm() {
    let run = common::run_study("tests/studies/unil_ddl_conflict.comm", "unil_ddl_conflict");
    common::assert_all_ok(&run, "unil_ddl_conflict.resu");
    let mess = run.file("unil_ddl_conflict.mess");
    let alarms: Vec<&str> = mess
        .lines()
        .filter(|l| l.contains("alarm: LIAISON_UNIL: 1 link(s) violated"))
        .collect();
    assert_eq!(alarms.len(), 2, "{mess}");
    for a in alarms {
        assert!(a.contains(", DZ) violated by 2.000e-2"), "{a}");
        assert!(a.contains("PIVOT NUL"), "{a}");
    }
}

/// A zone naming nodes the model does not carry: they are dropped, as
/// code_aster's elimun does, and the .mess says how many of the zone's
/// nodes were (it said only "4 nodes" for 8 given); the kept links hold
/// (tests/studies/unil_zone_outside_model.comm, DZ of PB1 = 0 at t = 1).
#[test]
fn zone_nodes_outside_the_model_are_dropped_and_counted() {
    let run = common::run_study(
        "tests/studies/unil_zone_outside_model.comm",
        "unil_zone_outside_model",
    );
    common::assert_all_ok(&run, "unil_zone_outside_model.resu");
    let mess = run.file("unil_zone_outside_model.mess");
    assert!(
        mess.contains(
            "zone 1: 4 of its 8 nodes dropped: they carry no degree of freedom of the model MO (as code_aster's elimun)"
        ),
        "{mess}"
    );
}

/// Runs tests/studies/<name>.comm and asserts every check OK (each study's
/// header gives its hand references).
fn run_ok(name: &str) {
    let run = common::run_study(&format!("tests/studies/{name}.comm"), name);
    common::assert_all_ok(&run, &format!("{name}.resu"));
}

/// STAT_NON_LINE in D_PLAN (probe unilp): a bar along n = (1, 1)/sqrt2
/// (nu = 0, uniaxial) pushed against the inclined wall DX + DY <= C by
/// GROUP_NO and by GROUP_MA of SEG2, with COEF_MULT (1, 1) and (2, 2):
/// free, then on the wall with its force F - K h along n, then pulled off
/// (free, REAC_NODA 0); penalised, per node (F/2 + a^2 E h)/(K/2 + a^2 E)
/// with a^2 = 2 and 8, the COEF_MULT scaling of the penalty (1e-10).
#[test]
fn inclined_wall_in_plane_strain_statics() {
    run_ok("unil_dplan_wall_stat");
}

/// The same in 3D with three components (probe unilp): a HEXA8 bar along
/// (1, 1, 1)/sqrt3 against DX + DY + DZ <= sqrt3 h given by GROUP_MA of a
/// QUAD4 face outside the model, NOM_CMP in two orders; active set and
/// penalty (a^2 = 3) against the closed forms.
#[test]
fn three_component_wall_in_3d_statics() {
    run_ok("unil_box_wall_3cmp");
}

/// A wall on DX whose COEF_IMPO is a FORMULE of (INST, Y) or a
/// DEFI_FONCTION of Y in D_PLAN (probe unilp): every node of the face on
/// its own wall position to 1e-12, the wall gives no DY, the supports
/// balance it.
#[test]
fn wall_position_function_of_y_in_plane_strain() {
    run_ok("unil_wall_of_y");
}

/// The floor under a QUAD8 block (GROUP_MA of SEG3: the mid-side nodes are
/// linked) pressed by DDL_IMPO (probe unilp): the floor reactions are the
/// consistent nodal forces of the uniform stress, 1/6, 2/3, 1/3 in D_PLAN
/// and 0, 1/3, 1/3, 1, 1/3 per radian in AXIS (1e-9); under full HHT
/// REAC_NODA is the force on the body, the static one.
#[test]
fn quadratic_floor_reactions_are_the_consistent_forces() {
    run_ok("unil_quad8_press");
}

/// A node in two zones at right angles pressed into their corner, a node
/// sliding along one wall, and a link on a component imposed by a ramped
/// DDL_IMPO (moved to the right-hand side at its step-end value): exact
/// displacements and reactions (probe unilp).
#[test]
fn corner_node_and_imposed_component() {
    run_ok("unil_corner_node");
}

/// Implicit (Newmark) and explicit (DIFF_CENT) dynamics of a free bar with
/// nu = 0 thrown obliquely onto an inclined wall, two zones on the same
/// nodes (probe unilp): the tangential motion stays the free one at every
/// node and instant (1e-12), the wall's REAC_NODA is along its normal, the
/// wall is reached and never passed; thrown away, exactly free.
#[test]
fn oblique_impact_on_an_inclined_wall_keeps_the_tangential_motion() {
    run_ok("unil_dplan_wall_dyn");
}

/// The work of a moving wall (PARA_CALC, probe unilp): pushing a held bar
/// quasi-statically, TRAV_LIAI = -ENER_TOT = -K (W t)^2 / 2 (the
/// trapezoidal rule is exact for a force linear in u), STAT_NON_LINE with
/// both algorithms and DYNA_NON_LINE.
#[test]
fn work_of_a_moving_wall_is_the_stored_energy() {
    run_ok("unil_wall_work");
}

/// VMIS_ISOT_LINE in C_PLAN against a wall (probe unilp): loaded onto the
/// wall past yield, unloaded off it, reloaded in compression; the uniaxial
/// closed form at every step (1e-8).
#[test]
fn plastic_bar_against_a_wall() {
    run_ok("unil_plastic_wall");
}

/// DIFF_CENT with a wall moving with INST into a held bar (probe unilp):
/// the top nodes ride on the wall at every archived instant (1e-12), the
/// wall's force is along its normal.
#[test]
fn explicit_wall_moving_with_inst() {
    run_ok("unil_explicit_moving_wall");
}
