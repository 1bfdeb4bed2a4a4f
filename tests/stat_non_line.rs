//! STAT_NON_LINE (quasi-static nonlinear analysis on DYNA_NON_LINE's
//! implicit engine without inertia): studies written as a code_aster user
//! would, each against an independent reference, and bad input that must
//! stop with a located error. The command files are tests/studies/stat_*.comm.

use std::path::{Path, PathBuf};

mod common;

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/studies")
}

/// Runs tests/studies/<name>.comm, asserts every check OK, snapshots its
/// tables and test report and returns the .resu.
fn run_study(name: &str) -> String {
    run_study_mess(name).0
}

/// [`run_study`], with the .mess.
fn run_study_mess(name: &str) -> (String, String) {
    let run = common::run_study(&format!("tests/studies/{name}.comm"), name);
    let resu = common::assert_all_ok(&run, &format!("{name}.resu"));
    // Every table and check of the file (the dated header lines aside).
    let tables: Vec<&str> = resu
        .lines()
        .filter(|l| !l.starts_with("#ASTER"))
        .map(|l| l.trim_end())
        .collect();
    insta::assert_snapshot!(name, tables.join("\n"));
    let mess = run.file(&format!("{name}.mess"));
    (resu, mess)
}

/// [`common::run_variant`] on tests/studies: exit code and terminal.
fn run_variant(study: &str, tag: &str, from: &str, to: &str) -> (i32, String) {
    let run = common::run_variant(&dir(), "stat_non_line_bad", study, tag, from, to);
    (run.code, run.term)
}

/// Each variant stops with exit 1, no panic, and a message holding every
/// part (command, keyword, line).
fn expect_errors(study: &str, cases: &[(&str, &str, &str, &[&str])]) {
    for &(tag, from, to, want) in cases {
        let (code, term) = run_variant(study, tag, from, to);
        assert_eq!(code, 1, "{tag}: {term}");
        assert!(!term.contains("panicked"), "{tag}: {term}");
        for w in want {
            assert!(term.contains(w), "{tag}: {w}\n{term}");
        }
    }
}

/// The cantilever of hexs8_cantilever.comm computed by STAT_NON_LINE
/// (stat_cantilever.comm): the end reaction against beam theory (10 %)
/// and against DYNA_NON_LINE's quasi-static run of the same model (1e-6),
/// HEXS20 and HEXS8 with 2 cells across; the material has no RHO.
#[test]
fn cantilever_matches_beam_theory_and_the_quasi_static_dynamics() {
    let resu = run_study("stat_cantilever");
    let t2 = common::printed_table(&resu, "FT2");
    let s2 = common::printed_table(&resu, "FS2");
    let value = |rows: &[std::collections::HashMap<String, String>]| -> f64 {
        rows[0]["DX"].parse().unwrap()
    };
    let (e, nu, l, h, b, d) = (2e5, 0.3, 20.0, 2.0, 2.0, 0.01);
    let g = e / (2.0 * (1.0 + nu));
    let i = b * h * h * h / 12.0;
    let p = d / (l * l * l / (3.0 * e * i) + l / (5.0 / 6.0 * g * b * h));
    for v in [value(&t2), value(&s2)] {
        assert!((v - p).abs() < 0.10 * p, "{v} against {p}");
    }
}

/// What belongs to dynamics is refused where it is written; a model whose
/// supports leave a rigid-body mode free is refused before the first step,
/// naming the mode and the missing DDL_IMPO; the fields a quasi-static
/// result does not hold are named when asked for.
#[test]
fn bad_input_is_a_located_error() {
    let stat = "RS2 = STAT_NON_LINE(MODELE=MOS2, CHAM_MATER=CMS2,";
    expect_errors(
        "stat_cantilever",
        &[
            (
                "schema_temps",
                stat,
                "RS2 = STAT_NON_LINE(MODELE=MOS2, CHAM_MATER=CMS2, SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'),",
                &["STAT_NON_LINE", "SCHEMA_TEMPS", ":68:"],
            ),
            (
                "mass_diag",
                stat,
                "RS2 = STAT_NON_LINE(MODELE=MOS2, CHAM_MATER=CMS2, MASS_DIAG='OUI',",
                &["STAT_NON_LINE", "MASS_DIAG", ":68:"],
            ),
            (
                "free_rigid_mode",
                "CLS2 = AFFE_CHAR_MECA(MODELE=MOS2, DDL_IMPO=_F(GROUP_NO='ZMIN', DX=0., DY=0., DZ=0.))",
                "CLS2 = AFFE_CHAR_MECA(MODELE=MOS2, DDL_IMPO=_F(GROUP_NO='ZMIN', DX=0., DZ=0.))",
                &["STAT_NON_LINE", "EXCIT", "translation DY", "DDL_IMPO", ":69:"],
            ),
            (
                "suivi_vite",
                stat,
                "RS2 = STAT_NON_LINE(MODELE=MOS2, CHAM_MATER=CMS2, SUIVI_DDL=_F(NOM_CHAM='VITE', NOM_CMP='DX', GROUP_NO='ZMAX'),",
                &["STAT_NON_LINE/SUIVI_DDL/NOM_CHAM", "VITE", ":68:"],
            ),
            (
                "vite_recu_fonction",
                "IMPR_TABLE(TABLE=FS2)",
                "IMPR_TABLE(TABLE=FS2)\nFV = RECU_FONCTION(RESULTAT=RS2, NOM_CHAM='VITE', NOM_CMP='DX', GROUP_NO='ZMAX')",
                &["RECU_FONCTION/NOM_CHAM", "result RS2 has no nodal field VITE"],
            ),
            (
                "pilotage",
                stat,
                "RS2 = STAT_NON_LINE(MODELE=MOS2, CHAM_MATER=CMS2, PILOTAGE=_F(TYPE='DDL_IMPO'),",
                &["STAT_NON_LINE", "PILOTAGE", "not implemented yet"],
            ),
            (
                "rech_lineaire",
                stat,
                "RS2 = STAT_NON_LINE(MODELE=MOS2, CHAM_MATER=CMS2, RECH_LINEAIRE=_F(),",
                &["STAT_NON_LINE", "RECH_LINEAIRE", "not implemented yet"],
            ),
            (
                "vite_asked",
                "NOM_CHAM='REAC_NODA', RESULTANTE='DX', INST=2.,\n                              OPERATION='EXTRACTION'))\nIMPR_TABLE(TABLE=FS2)",
                "NOM_CHAM='VITE', RESULTANTE='DX', INST=2.,\n                              OPERATION='EXTRACTION'))\nIMPR_TABLE(TABLE=FS2)",
                &["POST_RELEVE_T", "VITE", "RS2"],
            ),
        ],
    );
}

/// LIAISON_UNIL under STAT_NON_LINE (stat_unil.comm), the static cases of
/// liaison-unil.md §9.2 on a bar acting as the spring K = E A / L: force
/// and floor with CONTRAINTE (the floor reached exactly, reactions F − K H
/// and K H) and PENALISATION (u = (F − E h)/(k + E) per link), and a floor
/// rising with INST (free, then DZ = W t − H0 with its reaction K (W t −
/// H0)); all checked to 1e-9 or better in the file.
#[test]
fn unilateral_links_hold_the_static_references() {
    run_study("stat_unil");
}

/// The bilinear uniaxial curve of VMIS_ISOT_LINE under an imposed
/// displacement ramp and an elastic unloading (stat_plastic_bar.comm):
/// SIZZ = SY + ET (e − SY/E), p = (e − SY/E)/(1 + H/E), unloading
/// elastic with p frozen, REAC_NODA = 4 SIZZ; 3D HEXA8 and 3D_SI HEXS8
/// (loading only), both with the default NEWTON (REAC_ITER = 1).
#[test]
fn plastic_bar_follows_the_bilinear_curve() {
    run_study("stat_plastic_bar");
}

/// The distorted patch of stat_patch_hexs8.comm: the cube [0, 3]³ cut in
/// 3 × 3 × 3 HEXA8, every node moved by a fixed offset (multiples of
/// 0.05, at most 0.25) along each axis where it is not on the boundary,
/// so that faces stay plane and every cell is distorted. Node groups: Bk
/// for the k-th boundary node, Ik for the k-th interior one (in node
/// order); cell groups VOL and C1, C14 (the centre), C27.
fn patch_mesh() -> aster::mesh::Mesh {
    use aster::mesh::{Cell, CellType, Mesh};
    let n = 3usize;
    let id = |i: usize, j: usize, k: usize| (k * (n + 1) + j) * (n + 1) + i;
    let mut mesh = Mesh {
        name: "PATCH".into(),
        dim: 3,
        ..Mesh::default()
    };
    let (mut border, mut inner) = (Vec::new(), Vec::new());
    for k in 0..=n {
        for j in 0..=n {
            for i in 0..=n {
                let node = id(i, j, k);
                let g = [i, j, k];
                let mut x = [0.0; 3];
                for d in 0..3 {
                    x[d] = g[d] as f64;
                    if g[d] != 0 && g[d] != n {
                        let m = ((node * (3 + 2 * d) + 5 * d) % 11) as f64 - 5.0;
                        x[d] += m * 0.05;
                    }
                }
                mesh.coords.push(x);
                if g.iter().all(|&c| c != 0 && c != n) {
                    inner.push(node);
                } else {
                    border.push(node);
                }
            }
        }
    }
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let b = [
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                ];
                let t = b.map(|v| v + (n + 1) * (n + 1));
                mesh.cells.push(Cell {
                    kind: CellType::Hexa8,
                    nodes: vec![b[2], b[1], b[0], b[3], t[2], t[1], t[0], t[3]],
                });
            }
        }
    }
    for (k, &node) in border.iter().enumerate() {
        mesh.node_groups.insert(format!("B{}", k + 1), vec![node]);
    }
    for (k, &node) in inner.iter().enumerate() {
        mesh.node_groups.insert(format!("I{}", k + 1), vec![node]);
    }
    mesh.cell_groups
        .insert("VOL".into(), (0..mesh.cells.len()).collect());
    for c in [1usize, 14, 27] {
        mesh.cell_groups.insert(format!("C{c}"), vec![c - 1]);
    }
    mesh
}

/// The committed patch mesh is the one built above (regenerate with
/// `UPDATE_MESHES=1 cargo test --test stat_non_line patch_mesh`), every
/// cell distorted but with positive Jacobians.
#[test]
fn patch_mesh_is_committed() {
    let mesh = patch_mesh();
    for cell in &mesh.cells {
        let dets = aster::mesh::ops::jacobian_dets(&mesh, cell).unwrap();
        assert!(dets.iter().all(|&d| d > 0.0), "{dets:?}");
    }
    let path = dir().join("stat_patch.mmed");
    if std::env::var_os("UPDATE_MESHES").is_some() {
        aster::medio::write_mesh(&path, &mesh).unwrap();
    }
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("regen_stat_patch.mmed");
    aster::medio::write_mesh(&tmp, &mesh).unwrap();
    assert_eq!(
        aster::medio::read_mesh(&path, None).unwrap(),
        aster::medio::read_mesh(&tmp, None).unwrap()
    );
}

/// The patch test of MECA_HEXS8 on the distorted mesh above
/// (stat_patch_hexs8.comm): a linear field imposed on the 56 boundary
/// nodes is reproduced at the 8 free interior nodes, the stress is the
/// uniform LAMBDA tr(eps) I + 2 MU eps and the hourglass stresses are 0,
/// in one Newton iteration; checked in the file to 1e-9 (displacements)
/// and 1e-8 (stresses), measured at 2e-15 relative.
#[test]
fn hexs8_passes_the_patch_test_on_a_distorted_mesh() {
    run_study("stat_patch_hexs8");
}

/// Step cutting, continuation and hand-over (stat_continuation.comm): the
/// ECHEC rule DELTA_GRANDEUR on VARI_ELGA V1 (VALE_REF 5e-4) redoes every
/// plastic step (Δp = 9.9e-4) in 4 sub-steps; the run stopped at t = 5 and continued
/// with reuse= and ETAT_INIT EVOL_NOLI, then DYNA_NON_LINE started from the
/// static state at t = 10 keeps the bar at rest: every value on the
/// bilinear curve (1e-9, the unloaded stress 1e-8).
#[test]
fn steps_are_cut_and_a_static_result_is_continued() {
    let (_, mess) = run_study_mess("stat_continuation");
    expect_errors(
        "stat_continuation",
        &[(
            "acce_asked",
            "FIN()",
            "TEST_RESU(RESU=_F(RESULTAT=R, INST=2., NOM_CHAM='ACCE', NOM_CMP='DX', GROUP_NO='TIP', VALE_CALC=0.))\nFIN()",
            &["TEST_RESU/RESU/NOM_CHAM", "result R has no nodal field ACCE"],
        ), (
            "delta_cmp",
            "NOM_CHAM='VARI_ELGA', NOM_CMP='V1',",
            "NOM_CHAM='VARI_ELGA', NOM_CMP='VX1',",
            &["STAT_NON_LINE/INCREMENT", "DELTA_GRANDEUR", "no component 'VX1'", "delta_cmp.comm:68:19"],
        )],
    );
    assert_eq!(
        mess.matches("DELTA_GRANDEUR: the increment of VARI_ELGA V1 reaches 9.900000e-4 > VALE_REF = 5e-4; cut into 4 sub-steps").count(),
        9,
        "{mess}"
    );
    assert_eq!(mess.matches("STAT_NON_LINE done").count(), 2, "{mess}");
    assert!(mess.contains("DYNA_NON_LINE done"), "{mess}");
    // the continuation starts where the first run stopped
    assert!(mess.contains("steps from 5e0 to 1.2e1"), "{mess}");
}

/// Discrete penalised contact under STAT_NON_LINE (stat_contact.comm): a
/// block resting under its weight, held sideways by frictionless walls:
/// sum RN = m g, summed penetration m g / E_N for two E_N, REAC_NODA
/// summed = m g, to 1e-9 (measured 3e-15). Started at rest (gap 0, no
/// link active, the vertical translation held by nothing), the run stops
/// on its step and says which rigid-body mode only the contact could
/// hold; the alarm is logged before the first step.
///
/// The contact surfaces need not be in the model (code_aster's zzzz237a
/// models only its two blocks): with AFFE_MODELE on the volumes alone the
/// same checks pass; their nodes move with the volumes under them.
#[test]
fn discrete_contact_carries_the_weight_statically() {
    let (resu, mess) = run_study_mess("stat_contact");
    let volumes = common::run_variant(
        &dir(),
        "stat_non_line_ok",
        "stat_contact",
        "surfaces_outside_model",
        "AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'))",
        "AFFE=_F(GROUP_MA=('BLOC', 'SOCLE'), PHENOMENE='MECANIQUE', MODELISATION='3D'))",
    );
    let volumes = common::assert_all_ok(&volumes, "surfaces_outside_model.resu");
    let checks = |r: &str| -> Vec<String> {
        r.lines()
            .filter(|l| l.contains("ANALYTIQUE"))
            .map(String::from)
            .collect()
    };
    assert_eq!(checks(&volumes), checks(&resu));
    assert!(
        mess.contains("alarm: the rigid-body mode(s) (translation DZ of the part BLOC) are held by no DDL_IMPO, only by the contact"),
        "{mess}"
    );
    expect_errors(
        "stat_contact",
        &[(
            "contact_from_rest",
            "CONTACT=CONT1, ETAT_INIT=_F(DEPL=DEPL0),",
            "CONTACT=CONT1,",
            &[
                "STAT_NON_LINE stopped at the step",
                "translation DZ of the part BLOC",
                "add the missing DDL_IMPO",
                ":60:",
            ],
        )],
    );
}

/// DISCRETE (penalised) and CONTINUE contact under STAT_NON_LINE in AXIS
/// (stat_contact_continue.comm): a ring resting under its weight on a
/// fixed foundation, held axially by the contact alone: sum RN = W for
/// all three runs, sum(-JEU) = W / E_N for the penalised ones, JEU = 0 and
/// LAGS_C = −RHO g H at every slave node for the continuous one (measured
/// 3e-14 and 1.3e-14 relative; the file's tolerances are the dynamic
/// study's).
#[test]
fn discrete_and_continuous_contact_hold_a_ring_statically() {
    run_study("stat_contact_continue");
}

/// Penalised Coulomb friction in STAT_NON_LINE (stat_friction_pull.comm):
/// a block pressed on its foundation by ETAT_INIT and pulled along x to
/// 0.15 of its weight sticks, sum RN = m g and sum RTAX = 0.15 m g to
/// 1e-9. Pulled to 0.4 (COULOMB 0.25) it has no static equilibrium: the
/// run stops, and the message says so besides the DDL_IMPO hint.
#[test]
fn friction_holds_a_pulled_block_and_a_pull_beyond_it_is_explained() {
    run_study("stat_friction_pull");
    expect_errors(
        "stat_friction_pull",
        &[(
            "pull_beyond_mu",
            "PULL = 0.15",
            "PULL = 0.4",
            &[
                "STAT_NON_LINE stopped",
                "Newton did not converge",
                "a tangential load larger than the friction can hold (COULOMB times the normal force) has no static equilibrium either",
                "pull_beyond_mu.comm:44:1",
            ],
        )],
    );
}

/// POST_RELEVE_T keeps the first 16 characters of a longer INTITULE, as
/// code_aster's K16 column does (its own zzzz237a titles a table 'Forces
/// nodales ABCD'), and says so in the .mess instead of stopping the study.
#[test]
fn a_long_intitule_is_cut_to_16_characters() {
    let run = common::run_variant(
        &dir(),
        "stat_non_line_ok",
        "stat_contact",
        "long_intitule",
        "INTITULE='EN1'",
        "INTITULE='Forces contact EN1'",
    );
    let resu = common::assert_all_ok(&run, "long_intitule.resu");
    assert!(resu.contains("Forces contact E "), "{resu}");
    assert!(!resu.contains("Forces contact EN1"), "{resu}");
    let mess = run.file("long_intitule.mess");
    assert!(
        mess.contains("INTITULE 'Forces contact EN1' is kept as 'Forces contact E' (16 characters"),
        "{mess}"
    );
}
