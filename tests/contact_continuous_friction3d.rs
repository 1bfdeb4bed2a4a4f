//! Continuous contact with Coulomb friction in 3D (FORMULATION='CONTINUE',
//! FROTTEMENT='COULOMB'), whole studies run as `aster run` does (probe
//! s8g, defect D4): a block whose tangential motion along x is held by
//! friction alone, with a symmetry plane Y0 (DY = 0) on the slave face.
//!
//! The model: a 3D block [0, 2] x [0, 2] x [0, 1] (2 x 2 x 1 HEXA8,
//! E = 1000, NU = 0) resting with gap 0 on a fixed foundation
//! [-1, 3] x [-1, 3] x [-1, 0] (one HEXA8, every node held); slave the
//! block's bottom (4 QUAD4), master the foundation's top (one QUAD4).
//! A pressure p = 10 on the block's top (PRES_REP, ramped on [0, 1]),
//! then a uniform traction q = 1 along x on the same face (FORCE_FACE,
//! ramped on [1, 2]); the block's nodes on y = 0 have DY = 0 (the plane of
//! the pull is a symmetry plane), nothing else holds the block.
//!
//! Hand references (contact-continue.md §9): SEUIL_INIT = p gives the
//! threshold lambda_s = -p at the first prediction, so every slave node is
//! in stick in both tangent directions from the start; q = 1 < mu p = 5,
//! so the block sticks: CONT = 1 and GLI = 0 at every slave node; the
//! friction carries the pull, sum RTAX = q A = 4, sum RTAY = 0 (A = 4);
//! vertical equilibrium gives sum RNZ = -p A = -40 (the pull's moment only
//! redistributes the pressure). CONT_NOEU prints, as code_aster, minus
//! the forces on the slave nodes (docs/contact.md §4): RNZ into the
//! foundation, RTAX along the pull.
//!
//! On Y0 the tangent tau1 = e_y (code_aster's rule for a normal along z)
//! moves only the imposed DY: the friction equation of LAGS_F1 there had
//! no displacement to act on, and the first prediction stopped with
//! "singular matrix ... at unknown 0" before the fix.
#![allow(clippy::needless_range_loop)]

mod common;

/// Runs the stick study with the friction options `frot` (extra
/// DEFI_CONTACT keywords); returns the printed CONT_NOEU rows of the 9
/// slave nodes at t = 2.
fn run_stick(tag: &str, frot: &str) -> Vec<std::collections::HashMap<String, String>> {
    let (dir, med) = common::scratch_mesh(tag, &common::block_on_foundation_3d());
    let comm = format!(
        "DEBUT()\n\
         MA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
         MA = MODI_MAILLAGE(reuse=MA, MAILLAGE=MA, ORIE_PEAU_3D=_F(GROUP_MA=('ESCL', 'MAIT', 'HAUT')))\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'))\n\
         MAT = DEFI_MATERIAU(ELAS=_F(E=1000., NU=0.))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
         PR = AFFE_CHAR_MECA(MODELE=MO, PRES_REP=_F(GROUP_MA='HAUT', PRES=10.))\n\
         FIX = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO='SOCLE', DX=0., DY=0., DZ=0.), _F(GROUP_NO='Y0', DY=0.)))\n\
         TR = AFFE_CHAR_MECA(MODELE=MO, FORCE_FACE=_F(GROUP_MA='HAUT', FX=1.))\n\
         CO = DEFI_CONTACT(MODELE=MO, FORMULATION='CONTINUE', FROTTEMENT='COULOMB', {frot}\n\
             ZONE=_F(GROUP_MA_MAIT='MAIT', GROUP_MA_ESCL='ESCL', COULOMB=0.5, COEF_CONT=1.E3, COEF_FROT=1.E3, SEUIL_INIT=10.))\n\
         FP = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0., 1., 1., 2., 1.))\n\
         FQ = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0., 1., 0., 2., 1.))\n\
         L = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=(_F(JUSQU_A=1., NOMBRE=2), _F(JUSQU_A=2., NOMBRE=2)))\n\
         R = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CM, CONTACT=CO,\n\
             EXCIT=(_F(CHARGE=PR, FONC_MULT=FP), _F(CHARGE=FIX), _F(CHARGE=TR, FONC_MULT=FQ)),\n\
             COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=L),\n\
             CONVERGENCE=_F(RESI_GLOB_RELA=1.E-10, ITER_GLOB_MAXI=30))\n\
         T = POST_RELEVE_T(ACTION=_F(INTITULE='C', GROUP_NO='NESCL', RESULTAT=R, NOM_CHAM='CONT_NOEU',\n\
             NOM_CMP=('CONT', 'JEU', 'RNZ', 'GLI', 'RTAX', 'RTAY'), INST=2., OPERATION='EXTRACTION'))\n\
         IMPR_TABLE(TABLE=T, FORMAT_R='E24.16')\n\
         FIN()\n"
    );
    let (_, resu) = common::run_generated(&dir, tag, &comm, &med);
    let rows = common::printed_table(&resu, "T");
    assert_eq!(rows.len(), 9, "{tag}: the 9 slave nodes\n{resu}");
    rows
}

fn num(row: &std::collections::HashMap<String, String>, k: &str) -> f64 {
    row[k]
        .parse()
        .unwrap_or_else(|_| panic!("{k} = {} is not a number", row[k]))
}

/// Every node sticks, the friction carries the pull (sum RTAX = 4,
/// sum RTAY = 0) and the pressure the load (sum RNZ = -40), to round-off
/// (1e-9 relative: the system is solved to RESI_GLOB_RELA = 1e-10 and the
/// stick is exact, linear elasticity in a fixed contact state).
fn check_stick(rows: &[std::collections::HashMap<String, String>], tag: &str) {
    let (mut rtax, mut rtay, mut rnz) = (0.0, 0.0, 0.0);
    for r in rows {
        assert_eq!(num(r, "CONT"), 1.0, "{tag}: stick at {}", r["NOEUD"]);
        assert!(num(r, "GLI").abs() < 1e-10, "{tag}: GLI at {}", r["NOEUD"]);
        assert!(num(r, "JEU").abs() < 1e-10, "{tag}: JEU at {}", r["NOEUD"]);
        rtax += num(r, "RTAX");
        rtay += num(r, "RTAY");
        rnz += num(r, "RNZ");
    }
    assert!(
        (rtax - 4.0).abs() < 4e-9,
        "{tag}: sum RTAX = {rtax}, 4 expected"
    );
    assert!(rtay.abs() < 1e-9, "{tag}: sum RTAY = {rtay}, 0 expected");
    assert!(
        (rnz + 40.0).abs() < 4e-8,
        "{tag}: sum RNZ = {rnz}, -40 expected"
    );
}

#[test]
fn block_held_by_friction_alone_with_a_symmetry_plane_sticks_point_fixe() {
    let rows = run_stick("fr3d_pf", "ALGO_RESO_FROT='POINT_FIXE',");
    check_stick(&rows, "POINT_FIXE");
}

#[test]
fn block_held_by_friction_alone_with_a_symmetry_plane_sticks_newton() {
    let rows = run_stick("fr3d_nt", "");
    check_stick(&rows, "NEWTON");
}
