//! code_aster input about fields that aster used to refuse (probe
//! defects crea_champ_extr, archivage_cham_exclu,
//! post_releve_moyenne_invariant): CREA_CHAMP OPERATION='EXTR' tested by
//! TEST_RESU CHAM_NO, ARCHIVAGE/CHAM_EXCLU, and the message of POST_RELEVE_T
//! INVARIANT. Whole studies run as `aster run` does.
//!
//! The model: a bar of 4 HEXA8 cells of 1 x 1 x 1 mm along z (z = 0 to 4),
//! E = 1000 MPa, NU = 0. Two hand-solvable cases:
//!
//! - statics: BOT (z = 0) held, a pressure p = 2 MPa along +z on TOP
//!   ramped by f(t) = t: with NU = 0 the stress is uniaxial and uniform,
//!   SIZZ = p t, exactly represented by HEXA8, so DZ(z, t) = p t z / E
//!   (0.004 at the top at t = 0.5, at mid-height at t = 1), DX = DY = 0,
//!   and the reactions on BOT sum to -p t A = -2 at t = 1 (A = 1 mm²);
//! - dynamics: the free bar under gravity g = 1000 mm/s² along -z
//!   (PESANTEUR, no support): a rigid translation with a = -g at every
//!   node, which NEWMARK (average acceleration) integrates exactly:
//!   VZ = -g t, DZ = -g t²/2 (-20 and -0.2 at t = 0.02, -40 and -0.8 at
//!   t = 0.04).

mod common;

use aster::mesh::{CellType, Mesh};
use std::path::{Path, PathBuf};

/// The bar: cells VOL (HEXA8), TOP and BOT (QUAD4); node groups PTOP
/// (the top node at x = y = 0), PMID (the node x = y = 0, z = 2), NBOT.
fn bar_mesh() -> Mesh {
    let nz = 4;
    let mut coords = Vec::new();
    // Node (i, j, k) at (x, y, z) = (i, j, k), i, j in 0..2.
    let id = |i: usize, j: usize, k: usize| 4 * k + 2 * j + i;
    for k in 0..=nz {
        for j in 0..2 {
            for i in 0..2 {
                coords.push([i as f64, j as f64, k as f64]);
            }
        }
    }
    let mut m = Mesh {
        name: "BAR".into(),
        dim: 3,
        coords,
        ..Mesh::default()
    };
    let add = common::add_cell;
    // MED order: the bottom face turns clockwise seen from the top.
    let face = |k: usize| vec![id(0, 0, k), id(0, 1, k), id(1, 1, k), id(1, 0, k)];
    for k in 0..nz {
        let mut nodes = face(k);
        nodes.extend(face(k + 1));
        add(&mut m, "VOL", CellType::Hexa8, nodes);
    }
    add(&mut m, "BOT", CellType::Quad4, face(0));
    add(&mut m, "TOP", CellType::Quad4, face(nz));
    m.node_groups.insert("PTOP".into(), vec![id(0, 0, nz)]);
    m.node_groups.insert("PMID".into(), vec![id(0, 0, 2)]);
    m.node_groups.insert("NBOT".into(), face(0));
    m
}

const HEAD: &str = "DEBUT()
MA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'))
";

/// The static study up to the result R (with REAC_NODA and SIEF_NOEU).
const STATIC: &str = "MAT = DEFI_MATERIAU(ELAS=_F(E=1000., NU=0.))
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))
CHF = AFFE_CHAR_MECA(MODELE=MO, FORCE_FACE=_F(GROUP_MA='TOP', FZ=2.))
FIX = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_MA='BOT', DX=0., DY=0., DZ=0.))
RAMPE = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0., 1., 1.))
L = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=4))
R = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=CHF, FONC_MULT=RAMPE), _F(CHARGE=FIX)),
                  COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=L))
R = CALC_CHAMP(reuse=R, RESULTAT=R, FORCE='REAC_NODA', CONTRAINTE='SIEF_NOEU')
";

/// The free fall up to the result R, archived every 2 steps of 4 without
/// ACCE (`archivage` replaces the ARCHIVAGE keyword).
fn free_fall(archivage: &str) -> String {
    format!(
        "MAT = DEFI_MATERIAU(ELAS=_F(E=1000., NU=0., RHO=1.E-6))
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))
G = AFFE_CHAR_MECA(MODELE=MO, PESANTEUR=_F(GRAVITE=1000., DIRECTION=(0., 0., -1.)))
L = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=0.04, NOMBRE=4))
R = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=G),
                  COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=L),
                  SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'),
                  {archivage})
"
    )
}

const EXCLU: &str = "ARCHIVAGE=_F(PAS_ARCH=2, CHAM_EXCLU=('ACCE',))";

/// The outcome of a study: exit code, terminal, .resu, .mess.
struct Out {
    code: i32,
    term: String,
    resu: String,
    mess: String,
}

/// Writes `HEAD + body + FIN()` as `<tag>.comm` beside the bar mesh and
/// runs it; returns the whole text run and its outcome.
fn run(tag: &str, body: &str) -> (String, Out) {
    let dir: PathBuf = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{tag}_src"));
    std::fs::create_dir_all(&dir).unwrap();
    let med = dir.join("bar.mmed");
    aster::medio::write_mesh(&med, &bar_mesh()).unwrap();
    let comm = format!("{HEAD}{body}FIN()\n");
    std::fs::write(dir.join(format!("{tag}.comm")), &comm).unwrap();
    std::fs::write(
        dir.join(format!("{tag}.export")),
        format!("F mmed {} D 20\n", med.display()),
    )
    .unwrap();
    let r = common::run_study(dir.join(format!("{tag}.comm")).to_str().unwrap(), tag);
    let out = Out {
        code: r.code,
        term: r.term.clone(),
        resu: r.file(&format!("{tag}.resu")),
        mess: r.file(&format!("{tag}.mess")),
    };
    (comm, out)
}

/// The run ended with every check OK (at least `n` OK lines, no NOOK or
/// SKIP).
fn assert_ok(tag: &str, out: &Out, n: usize) {
    assert_eq!(out.code, 0, "{tag}: {}\n{}", out.term, out.resu);
    let ok = out.resu.lines().filter(|l| l.starts_with(" OK ")).count();
    assert!(ok >= n, "{tag}: {ok} OK lines, {n} expected:\n{}", out.resu);
    assert!(
        !out.resu
            .lines()
            .any(|l| l.starts_with("NOOK") || l.starts_with("SKIP")),
        "{tag}:\n{}",
        out.resu
    );
}

/// The run stopped on an error about `path` (COMMAND/KEYWORD...) located
/// at the line of `at` in `comm`, whose text holds every one of `words`.
fn assert_error(tag: &str, comm: &str, out: &Out, path: &str, words: &[&str], at: &str) {
    assert_eq!(out.code, 1, "{tag} should fail:\n{}", out.term);
    let e = &out.term;
    assert!(e.contains(path), "{tag}: expected {path} in:\n{e}");
    for w in words {
        assert!(e.contains(w), "{tag}: expected '{w}' in:\n{e}");
    }
    let line = comm
        .lines()
        .position(|l| l.contains(at))
        .unwrap_or_else(|| panic!("{tag}: '{at}' is not in the study"))
        + 1;
    let loc = format!("{tag}.comm:{line}:");
    assert!(e.contains(&loc), "{tag}: expected location {loc} in:\n{e}");
    // The .resu ends with the error too, as code_aster's.
    assert!(out.resu.contains(&loc), "{tag}: .resu:\n{}", out.resu);
}

// ---------------------------------------------------------------------------
// CREA_CHAMP OPERATION='EXTR' + TEST_RESU CHAM_NO

#[test]
fn crea_champ_extr_copies_the_result_field_at_inst_or_nume_ordre() {
    let body = format!(
        "{STATIC}U05 = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='EXTR', RESULTAT=R, NOM_CHAM='DEPL', INST=0.5)
U4 = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='EXTR', RESULTAT=R, NOM_CHAM='DEPL', NUME_ORDRE=4)
RN = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='EXTR', RESULTAT=R, NOM_CHAM='REAC_NODA', INST=1.)
SN = CREA_CHAMP(TYPE_CHAM='NOEU_SIEF_R', OPERATION='EXTR', RESULTAT=R, NOM_CHAM='SIEF_NOEU',
                INST=0.7505, CRITERE='ABSOLU', PRECISION=1.E-3)
TEST_RESU(CHAM_NO=(
    _F(CHAM_GD=U05, GROUP_NO='PTOP', NOM_CMP='DZ', VALE_CALC=0.004, REFERENCE='ANALYTIQUE', VALE_REFE=0.004, PRECISION=1.E-9),
    _F(CHAM_GD=U4, NOEUD='N9', NOM_CMP='DZ', VALE_CALC=0.004, REFERENCE='ANALYTIQUE', VALE_REFE=0.004, PRECISION=1.E-9),
    _F(CHAM_GD=U4, GROUP_NO='PTOP', NOM_CMP='DZ', VALE_CALC=0.008, REFERENCE='ANALYTIQUE', VALE_REFE=0.008, PRECISION=1.E-9),
    _F(CHAM_GD=U4, NOM_CMP='DZ', TYPE_TEST='MAX', VALE_CALC=0.008, REFERENCE='ANALYTIQUE', VALE_REFE=0.008, PRECISION=1.E-9),
    _F(CHAM_GD=U4, NOM_CMP='DX', TYPE_TEST='SOMM_ABS', VALE_CALC=0., CRITERE='ABSOLU', ORDRE_GRANDEUR=1.E-3),
    _F(CHAM_GD=RN, NOM_CMP='DZ', TYPE_TEST='SOMM', VALE_CALC=-2., REFERENCE='ANALYTIQUE', VALE_REFE=-2., PRECISION=1.E-9),
    _F(CHAM_GD=SN, NOM_CMP='SIZZ', TYPE_TEST='MAX', VALE_CALC=1.5, REFERENCE='ANALYTIQUE', VALE_REFE=1.5, PRECISION=1.E-9),
    _F(CHAM_GD=SN, NOM_CMP='SIZZ', TYPE_TEST='MIN', VALE_CALC=1.5, REFERENCE='ANALYTIQUE', VALE_REFE=1.5, PRECISION=1.E-9),
))
"
    );
    let (_, out) = run("extr_static", &body);
    assert_ok("extr_static", &out, 15);
    // N9 is the node (0, 0, 2): PMID.
    assert_eq!(bar_mesh().node_groups["PMID"], vec![8]);
    assert!(
        out.mess
            .contains("field U05 (NOEU_DEPL_R) = DEPL of R at NUME_ORDRE 2 (INST 5e-1)"),
        "{}",
        out.mess
    );
    assert!(
        out.mess
            .contains("field SN (NOEU_SIEF_R) = SIEF_NOEU of R at NUME_ORDRE 3"),
        "{}",
        out.mess
    );
    // The report block names the field tested.
    assert!(out.resu.contains("---- CHAM_NO"), "{}", out.resu);
}

#[test]
fn crea_champ_extr_of_velocity_and_acceleration() {
    let body = format!(
        "{}V1 = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='EXTR', RESULTAT=R, NOM_CHAM='VITE', NUME_ORDRE=2)
A4 = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='EXTR', RESULTAT=R, NOM_CHAM='ACCE', INST=0.04)
U4 = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='EXTR', RESULTAT=R, NOM_CHAM='DEPL', INST=0.04)
TEST_RESU(CHAM_NO=(
    _F(CHAM_GD=V1, GROUP_NO='PTOP', NOM_CMP='DZ', VALE_CALC=-20., REFERENCE='ANALYTIQUE', VALE_REFE=-20., PRECISION=1.E-9),
    _F(CHAM_GD=A4, NOM_CMP='DZ', TYPE_TEST='MIN', VALE_CALC=-1000., REFERENCE='ANALYTIQUE', VALE_REFE=-1000., PRECISION=1.E-9),
    _F(CHAM_GD=A4, NOM_CMP='DZ', TYPE_TEST='MAX', VALE_CALC=-1000., REFERENCE='ANALYTIQUE', VALE_REFE=-1000., PRECISION=1.E-9),
    _F(CHAM_GD=U4, GROUP_NO='PMID', NOM_CMP='DZ', VALE_CALC=-0.8, REFERENCE='ANALYTIQUE', VALE_REFE=-0.8, PRECISION=1.E-9),
))
",
        free_fall("")
    );
    let (_, out) = run("extr_dyna", &body);
    assert_ok("extr_dyna", &out, 8);
}

#[test]
fn crea_champ_extr_bad_input_is_located() {
    let cases: [(&str, &str, &str, &[&str]); 4] = [
        // An instant not stored: the stored ones are named.
        (
            "extr_no_inst",
            "X = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='EXTR', RESULTAT=R, NOM_CHAM='DEPL', INST=0.3)\n",
            "CREA_CHAMP/INST",
            &[
                "no stored instant matches INST=3e-1",
                "stored instants: 0e0, 2.5e-1, 5e-1, 7.5e-1, 1e0",
            ],
        ),
        // The quantity of the field is not TYPE_CHAM's.
        (
            "extr_type",
            "X = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='EXTR', RESULTAT=R, NOM_CHAM='SIEF_NOEU', NUME_ORDRE=1)\n",
            "CREA_CHAMP/TYPE_CHAM",
            &["SIEF_NOEU is a field of type NOEU_SIEF_R, not NOEU_DEPL_R"],
        ),
        // A field at element nodes (ELGA_SIEF_R / ELGA_VARI_R are built
        // since ETAT_INIT SIGM / VARI: tests/etat_init_fields.rs).
        (
            "extr_elno",
            "X = CREA_CHAMP(TYPE_CHAM='ELNO_SIEF_R', OPERATION='EXTR', RESULTAT=R, NOM_CHAM='SIEF_ELNO', NUME_ORDRE=1)\n",
            "CREA_CHAMP/TYPE_CHAM",
            &["not implemented yet", "fields at element nodes (ELNO_*)", "NOEU_DEPL_R, NOEU_SIEF_R", "ELGA_SIEF_R and ELGA_VARI_R"],
        ),
        // A field the result does not hold at that step.
        (
            "extr_absent",
            "X = CREA_CHAMP(TYPE_CHAM='NOEU_EPSI_R', OPERATION='EXTR', RESULTAT=R, NOM_CHAM='EPSI_NOEU', NUME_ORDRE=1)\n",
            "CREA_CHAMP/NOM_CHAM",
            &["result R has no nodal field EPSI_NOEU at NUME_ORDRE 1", "REAC_NODA"],
        ),
    ];
    for (tag, line, path, words) in cases {
        let (comm, out) = run(tag, &format!("{STATIC}{line}"));
        assert_error(tag, &comm, &out, path, words, "X = CREA_CHAMP");
    }
    // NUME_ORDRE and INST together, or neither: the catalogue's UN_PARMI
    // (the file is refused before anything runs).
    for (tag, access) in [("extr_both", "NUME_ORDRE=1, INST=0.25"), ("extr_none", "")] {
        let (_, out) = run(
            tag,
            &format!("{STATIC}X = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='EXTR', RESULTAT=R, NOM_CHAM='DEPL', {access})\n"),
        );
        assert_eq!(out.code, 1, "{tag}: {}", out.term);
        assert!(
            out.term.contains("NUME_ORDRE") && out.term.contains("INST"),
            "{tag}: {}",
            out.term
        );
        assert!(!out.mess.contains("STAT_NON_LINE done"), "{tag} ran");
    }
}

// ---------------------------------------------------------------------------
// ARCHIVAGE/CHAM_EXCLU

/// PAS_ARCH=2 of 4 steps: NUME_ORDRE 0 (t = 0), 1 (t = 0.02), 2 (t =
/// 0.04, the last: every field). ACCE is absent from the first two,
/// VITE and DEPL are there with their hand values.
#[test]
fn cham_exclu_leaves_the_field_out_but_at_the_last_instant() {
    let body = format!(
        "{}TEST_RESU(RESU=(
    _F(RESULTAT=R, INST=0.02, NOM_CHAM='VITE', GROUP_NO='PTOP', NOM_CMP='DZ', VALE_CALC=-20., REFERENCE='ANALYTIQUE', VALE_REFE=-20., PRECISION=1.E-9),
    _F(RESULTAT=R, INST=0.02, NOM_CHAM='DEPL', GROUP_NO='PTOP', NOM_CMP='DZ', VALE_CALC=-0.2, REFERENCE='ANALYTIQUE', VALE_REFE=-0.2, PRECISION=1.E-9),
    _F(RESULTAT=R, NUME_ORDRE=2, NOM_CHAM='ACCE', GROUP_NO='PTOP', NOM_CMP='DZ', VALE_CALC=-1000., REFERENCE='ANALYTIQUE', VALE_REFE=-1000., PRECISION=1.E-9),
    _F(RESULTAT=R, NUME_ORDRE=2, NOM_CHAM='VITE', GROUP_NO='PTOP', NOM_CMP='DZ', VALE_CALC=-40., REFERENCE='ANALYTIQUE', VALE_REFE=-40., PRECISION=1.E-9),
))
",
        free_fall(EXCLU)
    );
    let (_, out) = run("exclu_ok", &body);
    assert_ok("exclu_ok", &out, 8);
    assert!(out.mess.contains("3 archived"), "{}", out.mess);
}

#[test]
fn a_field_cham_exclu_left_out_is_a_located_error() {
    let cases: [(&str, &str, &str, &str, &[&str]); 5] = [
        (
            "exclu_test_resu",
            "TEST_RESU(RESU=_F(RESULTAT=R, INST=0.02, NOM_CHAM='ACCE', GROUP_NO='PTOP', NOM_CMP='DZ', VALE_CALC=-1000.))\n",
            "TEST_RESU",
            "TEST_RESU/RESU/NOM_CHAM",
            &["no nodal field ACCE at NUME_ORDRE 1", "excluded from this instant by ARCHIVAGE/CHAM_EXCLU"],
        ),
        (
            "exclu_initial",
            "T = POST_RELEVE_T(ACTION=_F(INTITULE='A', GROUP_NO='PTOP', RESULTAT=R, NOM_CHAM='ACCE', NOM_CMP='DZ', INST=0., OPERATION='EXTRACTION'))\n",
            "T = POST_RELEVE_T",
            "POST_RELEVE_T/ACTION/NOM_CHAM",
            &["no nodal field ACCE at NUME_ORDRE 0", "CHAM_EXCLU"],
        ),
        (
            "exclu_reac",
            "R = CALC_CHAMP(reuse=R, RESULTAT=R, FORCE='REAC_NODA')\n",
            "R = CALC_CHAMP",
            "CALC_CHAMP/RESULTAT",
            &["NUME_ORDRE 0 of R has no ACCE field", "CHAM_EXCLU"],
        ),
        (
            "exclu_extr",
            "X = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='EXTR', RESULTAT=R, NOM_CHAM='ACCE', INST=0.02)\n",
            "X = CREA_CHAMP",
            "CREA_CHAMP/NOM_CHAM",
            &["no nodal field ACCE at NUME_ORDRE 1", "CHAM_EXCLU", "this step holds DEPL, VITE"],
        ),
        (
            "exclu_continue",
            "R2 = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=G), ETAT_INIT=_F(EVOL_NOLI=R, NUME_ORDRE=1),\n                   COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=L, INST_FIN=0.04),\n                   SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'), ARCHIVAGE=_F(CHAM_EXCLU=('VITE',)))\nR3 = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=G), ETAT_INIT=_F(EVOL_NOLI=R2, INST=0.03),\n                   COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=L, INST_FIN=0.04),\n                   SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'))\n",
            "R3 = DYNA_NON_LINE",
            "DYNA_NON_LINE/ETAT_INIT/EVOL_NOLI",
            &["(INST 3e-2) of R2 has no VITE", "continue from the last instant of that call"],
        ),
    ];
    for (tag, line, at, path, words) in cases {
        let (comm, out) = run(tag, &format!("{}{line}", free_fall(EXCLU)));
        assert_error(tag, &comm, &out, path, words, at);
    }
}

#[test]
fn cham_exclu_names_a_field_the_command_archives() {
    let (comm, out) = run(
        "exclu_name",
        &free_fall("ARCHIVAGE=_F(PAS_ARCH=2, CHAM_EXCLU=('ACCEL',))"),
    );
    assert_error(
        "exclu_name",
        &comm,
        &out,
        "DYNA_NON_LINE/ARCHIVAGE/CHAM_EXCLU",
        &[
            "ACCEL is not a field this command archives",
            "did you mean 'ACCE'",
        ],
        "ARCHIVAGE=_F(PAS_ARCH=2",
    );
}

// ---------------------------------------------------------------------------
// POST_RELEVE_T INVARIANT

#[test]
fn post_releve_invariant_says_what_is_not_built() {
    let (comm, out) = run(
        "releve_invariant",
        &format!("{STATIC}T1 = POST_RELEVE_T(ACTION=_F(INTITULE='INV', GROUP_NO='PTOP', RESULTAT=R, INST=1., NOM_CHAM='SIEF_NOEU', INVARIANT='OUI', OPERATION='EXTRACTION'))\n"),
    );
    assert_error(
        "releve_invariant",
        &comm,
        &out,
        "POST_RELEVE_T/ACTION/INVARIANT",
        &[
            "not implemented yet",
            "INVARIANT='OUI' (the invariants VMIS, TRESCA, TRACE, DETER of a tensor field) is not built",
            "SIEQ_NOEU",
        ],
        "T1 = POST_RELEVE_T",
    );
    assert!(!out.term.contains("only nodal extraction"), "{}", out.term);
}
