//! POST_ELEM, CREA_TABLE and DETRUIRE: the verification studies of
//! tests/verification/ (every value against a closed form written in the
//! study) and the located errors of bad input.

mod common;

use std::path::Path;

/// Runs a study of tests/verification/ and asserts every check OK.
fn study(name: &str) -> String {
    let run = common::run_study(
        &format!("tests/verification/{name}.comm"),
        &format!("post_elem_{name}"),
    );
    common::assert_all_ok(&run, &format!("{name}.resu"))
}

/// Runs a command file given as text; returns (exit code, terminal).
fn run_text(tag: &str, body: &str) -> (i32, String) {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("post_elem_src_{tag}"));
    std::fs::create_dir_all(&dir).unwrap();
    let comm = dir.join(format!("{tag}.comm"));
    std::fs::write(&comm, body).unwrap();
    let mesh = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/verification/block.mmed");
    std::fs::write(
        dir.join(format!("{tag}.export")),
        format!("F mmed {} D 20\n", mesh.display()),
    )
    .unwrap();
    let run = common::run_study(comm.to_str().unwrap(), &format!("post_elem_run_{tag}"));
    (run.code, run.term)
}

/// MASS_INER of boxes of HEXA8, of the AXIS bar (full body) and of the
/// linear 3D quarter bar against closed forms to 1e-10.
#[test]
fn mass_iner_matches_closed_forms() {
    let resu = study("post_elem_mass");
    assert!(resu.contains("UNION_GROUP_MA"), "{resu}");
}

/// ENER_CIN in free flight (both mass options, AXIS per radian and 3D)
/// and ENER_ELAS, ENER_POT of a uniaxially stressed column (HEXA8 and
/// HEXS8).
#[test]
fn kinetic_and_elastic_energies_match_closed_forms() {
    study("post_elem_energy");
}

/// CREA_TABLE (lists, NUME_LIGN, a function) read by TEST_TABLE,
/// CALC_TABLE and IMPR_TABLE; DETRUIRE then a new definition.
#[test]
fn crea_table_and_detruire() {
    study("crea_table");
}

/// A destroyed name used again is an error of the checker, located at
/// the use, before anything runs (the table before it is not even made);
/// a list still holding it is refused too.
#[test]
fn destroyed_names_are_refused_before_the_run() {
    let (code, term) = run_text(
        "reuse",
        "DEBUT()\nT = CREA_TABLE(LISTE=_F(PARA='A', LISTE_I=(1, 2)))\nL = [T]\nDETRUIRE(NOM=T)\nIMPR_TABLE(TABLE=T)\nIMPR_TABLE(TABLE=L[0])\nFIN()\n",
    );
    assert_eq!(code, 1, "{term}");
    assert!(term.contains("name 'T' is not defined"), "{term}");
    assert!(term.contains("reuse.comm:5:"), "{term}");
    assert!(term.contains("destroyed by DETRUIRE"), "{term}");
    assert!(term.contains("reuse.comm:6:"), "{term}");
    assert!(
        !term.contains("CREA_TABLE done"),
        "the checker must stop it before the run:\n{term}"
    );
}

#[test]
fn crea_table_bad_lists_are_located() {
    let cases = [
        (
            "T = CREA_TABLE(LISTE=(_F(PARA='A', LISTE_I=(1, 2)), _F(PARA='B', LISTE_R=(1., 2., 3.))))",
            "B has 3 values where A has 2",
        ),
        (
            "T = CREA_TABLE(LISTE=_F(PARA='A', LISTE_I=(1, 2), NUME_LIGN=3))",
            "NUME_LIGN gives 1 lines for the 2 values",
        ),
        (
            "T = CREA_TABLE(LISTE=_F(PARA='A', LISTE_K='TOO_LONG_TEXT'))",
            "longer than the 8 characters",
        ),
        (
            "T = CREA_TABLE(LISTE=(_F(PARA='A', LISTE_I=1), _F(PARA='A', LISTE_I=2)))",
            "already has a column named 'A'",
        ),
        (
            "T = CREA_TABLE(LISTE=_F(PARA='A', LISTE_I=1), TYPE_TABLE='TABLE_FONCTION')",
            "not implemented yet: CREA_TABLE/TYPE_TABLE",
        ),
    ];
    for (k, (line, expected)) in cases.iter().enumerate() {
        let (code, term) = run_text(&format!("crea{k}"), &format!("DEBUT()\n{line}\nFIN()\n"));
        assert_eq!(code, 1, "{line}\n{term}");
        assert!(term.contains(expected), "{line}\n{term}");
        assert!(term.contains(&format!("crea{k}.comm:2:")), "{line}\n{term}");
        assert!(term.contains("CREA_TABLE"), "{line}\n{term}");
    }
}

/// Options not built stop with "not implemented yet" at their keyword;
/// an energy without a result is an error naming the option.
#[test]
fn post_elem_refusals_are_located() {
    let head = "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n";
    let (code, term) = run_text(
        "pot",
        &format!("{head}MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'))\nT = POST_ELEM(MODELE=MO, ENER_TOTALE=_F(TOUT='OUI'))\nFIN()\n"),
    );
    assert_eq!(code, 1, "{term}");
    assert!(
        term.contains("not implemented yet: POST_ELEM/ENER_TOTALE"),
        "{term}"
    );
    assert!(term.contains("pot.comm:4:"), "{term}");
    let (code, term) = run_text(
        "cin",
        &format!("{head}MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'))\nT = POST_ELEM(MODELE=MO, ENER_CIN=_F(TOUT='OUI'))\nFIN()\n"),
    );
    assert_eq!(code, 1, "{term}");
    assert!(term.contains("ENER_CIN needs RESULTAT"), "{term}");
    assert!(term.contains("cin.comm:4:"), "{term}");
}

/// INTEGRALE of SIEF_ELGA / VARI_ELGA: uniform SIZZ of a column in
/// tension (INTE = sigma V, MOYE = sigma, a GROUP_MA subset, the union
/// of two groups, TYPE_MAILLE), a linear SIZZ in HEXA20 (integral =
/// (lambda + 2 mu) K x_G V) and AXIS per radian (VOL = R^2 L / 2), to
/// 1e-10. POST_ELEM refused INTEGRALE until 2026-11-28.
#[test]
fn integrale_matches_closed_forms() {
    let resu = study("post_elem_integrale");
    assert!(resu.contains("UNION_GROUP_MA"), "{resu}");
    assert!(resu.contains("MOYE_SIZZ"), "{resu}");
}

/// INTEGRALE's refusals name the keyword and the line: a nodal field
/// (code_aster integrates it through ELNO, not built here), a component
/// the field lacks, a field the result lacks, a TYPE_MAILLE that keeps
/// no cell.
#[test]
fn integrale_refusals_are_located() {
    let head = "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
        MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=_F(GROUP_MA='BLOC'))\n\
        MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(GROUP_MA='BLOC', PHENOMENE='MECANIQUE', MODELISATION='3D'))\n\
        AC = DEFI_MATERIAU(ELAS=_F(E=2.E5, NU=0.3))\n\
        CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=AC))\n\
        CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='BLOC', DX=0., DY=0., DZ=0.))\n\
        LI = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=1))\n\
        R = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH), INCREMENT=_F(LIST_INST=LI))\n";
    let cases = [
        (
            "INTEGRALE=_F(TOUT='OUI', NOM_CHAM='DEPL', NOM_CMP='DX')",
            "not implemented yet: POST_ELEM/INTEGRALE/NOM_CHAM",
        ),
        (
            "INTEGRALE=_F(TOUT='OUI', NOM_CHAM='SIEF_ELGA', NOM_CMP='SIRR')",
            "SIEF_ELGA has no component SIRR",
        ),
        (
            "INTEGRALE=_F(TOUT='OUI', NOM_CHAM='EPSI_ELGA', NOM_CMP='EPXX')",
            "has no field EPSI_ELGA",
        ),
        (
            "INTEGRALE=_F(GROUP_MA='BLOC', TYPE_MAILLE='2D', NOM_CHAM='SIEF_ELGA', NOM_CMP='SIXX')",
            "no cell of dimension 2D",
        ),
    ];
    for (k, (occ, expected)) in cases.iter().enumerate() {
        let (code, term) = run_text(
            &format!("integ{k}"),
            &format!("{head}T = POST_ELEM(RESULTAT=R, {occ})\nFIN()\n"),
        );
        assert_eq!(code, 1, "{occ}\n{term}");
        assert!(term.contains(expected), "{occ}\n{term}");
        assert!(
            term.contains(&format!("integ{k}.comm:10:")),
            "{occ}\n{term}"
        );
    }
}
