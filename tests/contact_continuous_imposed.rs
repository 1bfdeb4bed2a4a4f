//! Continuous contact (FORMULATION='CONTINUE') under imposed displacements
//! and in dynamics, whole studies run as `aster run` does (probe s8g,
//! defects D2 and D3).
//!
//! The model: a D_PLAN block [0, 4] x [0, 2] (4 x 2 QUAD4, E = 1000,
//! NU = 0) resting with gap 0 on a fixed foundation [-1, 5] x [-1, 0]
//! (6 x 1 QUAD4, every node held); slave face the block's bottom (4 SEG2),
//! master the foundation's top (6 SEG2). The foundation's top is y = 0 and
//! it does not move, so the gap of a slave node is its DY, whatever the
//! method: JEU = DY, and "no penetration" is DY >= 0.
//!
//! With NU = 0 the stress of a block squeezed between its top and the
//! foundation is uniaxial and uniform, sigma_yy = E eps_yy, exactly
//! represented by QUAD4: the continuous method's LAGS_C (the nominal
//! contact pressure, < 0 in compression) is sigma_yy at every slave node,
//! and RN = -LAGS_C times the node's share of the face (1/2 at the ends of
//! the face, 1 inside: SEG2 cells of length 1), so the RN of the five
//! slave nodes sum to -4 LAGS_C.

mod common;

use std::collections::HashMap;

const E: f64 = 1000.0;

/// Runs the study whose body (after the mesh, model, material and contact
/// definitions) is `body`, in the scratch directory `tag`; returns the
/// run and its .resu.
fn run(tag: &str, body: &str) -> (common::Run, String) {
    let (dir, med) = common::scratch_mesh(tag, &common::block_on_foundation());
    let comm = format!(
        "DEBUT()\n\
         MA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
         MA = MODI_MAILLAGE(reuse=MA, MAILLAGE=MA, ORIE_PEAU_2D=_F(GROUP_MA=('ESCL', 'MAIT', 'HAUT')))\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\n\
         CO = DEFI_CONTACT(MODELE=MO, FORMULATION='CONTINUE', ZONE=_F(GROUP_MA_MAIT='MAIT', GROUP_MA_ESCL='ESCL'))\n\
         {body}\n\
         T = POST_RELEVE_T(ACTION=(\
         _F(INTITULE='D', GROUP_NO='NESCL', RESULTAT=R, NOM_CHAM='DEPL', NOM_CMP=('DX', 'DY', 'LAGS_C'), TOUT_ORDRE='OUI', OPERATION='EXTRACTION'), \
         _F(INTITULE='C', GROUP_NO='NESCL', RESULTAT=R, NOM_CHAM='CONT_NOEU', NOM_CMP=('CONT', 'JEU', 'RN'), TOUT_ORDRE='OUI', OPERATION='EXTRACTION')))\n\
         IMPR_TABLE(TABLE=T, FORMAT_R='E24.16')\n\
         FIN()\n"
    );
    let (r, resu) = common::run_generated(&dir, tag, &comm, &med);
    (r, resu)
}

/// The printed table T as (instant, node) -> (displacement row, contact
/// row), over every archived instant.
type Rows = HashMap<(String, String), (HashMap<String, String>, HashMap<String, String>)>;

fn rows(resu: &str) -> Rows {
    let mut out: Rows = HashMap::new();
    for r in common::printed_table(resu, "T") {
        let key = (r["INST"].clone(), r["NOEUD"].clone());
        let e = out.entry(key).or_default();
        if r["INTITULE"] == "D" {
            e.0 = r;
        } else {
            e.1 = r;
        }
    }
    out
}

fn num(row: &HashMap<String, String>, k: &str) -> f64 {
    row[k]
        .parse()
        .unwrap_or_else(|_| panic!("{k} = {} is not a number", row[k]))
}

/// The slave face's state at instant `t` (as printed): LAGS_C, DY, JEU,
/// CONT, RN per node, with node x.
fn face_at(rows: &Rows, t: f64) -> Vec<HashMap<String, String>> {
    let mut out: Vec<HashMap<String, String>> = rows
        .iter()
        .filter(|((inst, _), _)| {
            (inst.parse::<f64>().unwrap() - t).abs() <= 1e-9 * t.abs().max(1.0)
        })
        // The two rows of a node, without the other's absent cells ("-").
        .map(|(_, (d, c))| {
            d.iter()
                .chain(c.iter())
                .filter(|(_, v)| v.as_str() != "-")
                .map(|(k, v)| (k.clone(), v.clone()))
                .collect()
        })
        .collect();
    out.sort_by(|a, b| num(a, "COOR_X").total_cmp(&num(b, "COOR_X")));
    assert_eq!(out.len(), 5, "the 5 slave nodes at {t}");
    out
}

/// Checks the squeezed block at instant `t` against the uniaxial
/// solution: LAGS_C = sigma_yy = `sigma` at every slave node, no
/// penetration and no gap (DY = JEU = 0), CONT = 2 (closed, frictionless),
/// sum RN = -4 sigma, and DX = `dx` (the block's rigid shift along x).
fn check_squeezed(rows: &Rows, t: f64, sigma: f64, dx: f64, tag: &str) {
    let face = face_at(rows, t);
    let mut sum_rn = 0.0;
    for n in &face {
        let at = format!("{tag}: node {} at t = {t}", n["NOEUD"]);
        let lags = num(n, "LAGS_C");
        assert!(
            (lags - sigma).abs() <= 1e-9 * sigma.abs(),
            "{at}: LAGS_C {lags} vs {sigma}"
        );
        assert!(num(n, "DY").abs() <= 1e-12, "{at}: DY {}", n["DY"]);
        assert!(num(n, "JEU").abs() <= 1e-12, "{at}: JEU {}", n["JEU"]);
        assert!(
            (num(n, "DX") - dx).abs() <= 1e-9 * dx.abs().max(1e-3),
            "{at}: DX {} vs {dx}",
            n["DX"]
        );
        assert_eq!(num(n, "CONT"), 2.0, "{at}");
        sum_rn += num(n, "RN");
    }
    assert!(
        (sum_rn + 4.0 * sigma).abs() <= 1e-9 * sigma.abs(),
        "{tag}: sum RN {sum_rn} at {t}"
    );
}

const PUSHED: &str = "\
MAT = DEFI_MATERIAU(ELAS=_F(E=1000., NU=0., RHO=1.E-12))
CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))
CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO='SOCLE', DX=0., DY=0.), _F(GROUP_NO='GAUCHE', DX=0.), \
_F(GROUP_NO='TOP', DY=-0.01)))
RAMPE = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0., 1., 1.))
LI = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=2))
";

/// D2: the block's top pushed down by a DDL_IMPO DY = -0.01 t over two
/// steps, STAT_NON_LINE. Bottom held by the contact: eps_yy = -0.005 t,
/// LAGS_C = -5 t. Before the fix the first step's contact saw the gap of
/// the step's start (the imposed increment, carried into the block by the
/// prediction, was invisible to it): LAGS_C = 0 with the block 0.005 inside
/// the foundation, and RESI_GLOB_RELA stalled at 1.5 (nothing carried the
/// load); the second step stopped on "right-hand side of length 22 for a
/// matrix of order 27" (the prediction's right-hand side missed the
/// multipliers).
#[test]
fn block_pushed_by_an_imposed_displacement_statics() {
    let body = format!(
        "{PUSHED}R = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH, FONC_MULT=RAMPE), CONTACT=CO, \
         COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=LI), \
         CONVERGENCE=_F(RESI_GLOB_RELA=1.E-10, ITER_GLOB_MAXI=20))"
    );
    let (_, resu) = run("imposed_stat", &body);
    let rows = rows(&resu);
    for t in [0.5, 1.0] {
        check_squeezed(&rows, t, -E * 0.005 * t, 0.0, "STAT_NON_LINE");
    }
}

/// D2 in DYNA_NON_LINE (Newmark), the same push: with RHO = 1e-12 the
/// inertia is ~1e-14 of the stiffness forces, so the static answer holds.
/// Before the fix Newton stalled from the first step.
#[test]
fn block_pushed_by_an_imposed_displacement_dynamics() {
    let body = format!(
        "{PUSHED}R = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH, FONC_MULT=RAMPE), CONTACT=CO, \
         SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'), \
         COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=LI), \
         CONVERGENCE=_F(RESI_GLOB_RELA=1.E-8, ITER_GLOB_MAXI=20))"
    );
    let (_, resu) = run("imposed_dyna", &body);
    let rows = rows(&resu);
    for t in [0.5, 1.0] {
        check_squeezed(&rows, t, -E * 0.005 * t, 0.0, "DYNA_NON_LINE");
    }
}

/// A block held along y by the contact alone (pressed by p = 10) and
/// moved along x by a DDL_IMPO DX = 0.01 t on its left edge, frictionless,
/// STAT_NON_LINE: it slides rigidly, DX = 0.01 t at every node, with the
/// pressure unchanged, LAGS_C = -p. Before the fix the prediction of the
/// imposed increment solved the displacement equations without the
/// contact: nothing held the block along y there, and the first step
/// stopped on a singular matrix.
#[test]
fn block_held_by_the_contact_alone_moved_by_an_imposed_displacement() {
    let body = "\
MAT = DEFI_MATERIAU(ELAS=_F(E=1000., NU=0.))
CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))
PR = AFFE_CHAR_MECA(MODELE=MO, PRES_REP=_F(GROUP_MA='HAUT', PRES=10.))
CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO='SOCLE', DX=0., DY=0.), _F(GROUP_NO='GAUCHE', DX=0.01)))
RAMPE = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0., 1., 1.))
LI = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=2))
R = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=(_F(CHARGE=CH, FONC_MULT=RAMPE), _F(CHARGE=PR)), CONTACT=CO,
                  COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=LI),
                  CONVERGENCE=_F(RESI_GLOB_MAXI=1.E-9, ITER_GLOB_MAXI=20))";
    let (_, resu) = run("imposed_slide", body);
    let rows = rows(&resu);
    for t in [0.5, 1.0] {
        check_squeezed(&rows, t, -10.0, 0.01 * t, "slide");
    }
}

/// D3: the block pressed by a pressure ramped from 0 to 10 over 1e-3 s,
/// DYNA_NON_LINE (Newmark 0.3025/0.6, RHO 1e-6, DT 1e-5), ten steps. The
/// slave nodes bounce off after the first step and come back. At every
/// instant: no penetration (DY >= 0), JEU = DY (the current gap), an open
/// node (CONT = 0) has JEU >= 0 and LAGS_C = 0, a closed one (CONT = 2)
/// JEU = 0 and LAGS_C <= 0. Before the fix the contact judged every
/// Newton iterate of a step by the gap of the step's start (the pairing's,
/// frozen with ALGO_RESO_GEOM='POINT_FIXE', the default): steps 4 to 8
/// converged in one iteration with the nodes open while they went through
/// the foundation (DY = -6.23e-5 at 8e-5, CONT_NOEU said JEU = +1.55e-5,
/// the step's start), and the step after could not converge.
#[test]
fn a_returning_node_does_not_penetrate_in_dynamics() {
    let body = "\
MAT = DEFI_MATERIAU(ELAS=_F(E=1000., NU=0., RHO=1.E-6))
CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))
PR = AFFE_CHAR_MECA(MODELE=MO, PRES_REP=_F(GROUP_MA='HAUT', PRES=10.))
FIX = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO='SOCLE', DX=0., DY=0.), _F(GROUP_NO='GAUCHE', DX=0.)))
FP = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0., 1.E-3, 1.))
LD = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1.E-4, NOMBRE=10))
R = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CM, CONTACT=CO, EXCIT=(_F(CHARGE=PR, FONC_MULT=FP), _F(CHARGE=FIX)),
                  COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=LD),
                  SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', BETA=0.3025, GAMMA=0.6, FORMULATION='DEPLACEMENT'),
                  CONVERGENCE=_F(RESI_GLOB_RELA=1.E-8, ITER_GLOB_MAXI=30))";
    let (_, resu) = run("dyna_return", body);
    let rows = rows(&resu);
    let (mut open, mut closed, mut left) = (0, 0, 0.0f64);
    for k in 1..=10 {
        let t = k as f64 * 1e-5;
        for n in face_at(&rows, t) {
            let at = format!("node {} at t = {t:e}", n["NOEUD"]);
            let (dy, jeu, lags) = (num(&n, "DY"), num(&n, "JEU"), num(&n, "LAGS_C"));
            assert!(dy >= -1e-12, "{at}: DY = {dy:e}, inside the foundation");
            assert!(
                (jeu - dy).abs() <= 1e-12,
                "{at}: JEU = {jeu:e}, DY = {dy:e}"
            );
            match num(&n, "CONT") as i32 {
                0 => {
                    open += 1;
                    left = left.max(dy);
                    assert!(lags == 0.0, "{at}: open with LAGS_C = {lags:e}");
                }
                2 => {
                    closed += 1;
                    assert!(
                        jeu.abs() <= 1e-12 && lags <= 0.0,
                        "{at}: JEU {jeu:e} LAGS_C {lags:e}"
                    );
                }
                c => panic!("{at}: CONT = {c}"),
            }
        }
    }
    // The bounce happens: some nodes leave the foundation (by 1e-5 mm and
    // more) and some come back, the case of the defect.
    assert!(
        open > 0 && closed > 5 && left > 1e-5,
        "{open} open, {closed} closed, {left:e}"
    );
}

/// The block starting 1e-6 inside the foundation (ETAT_INIT DEPL, a rigid
/// shift) and pressed by p = 10, STAT_NON_LINE: the contact pushes it out
/// in the first step, LAGS_C = -p, DY = JEU = 0 at the slave nodes. Before
/// the fix Newton stalled (the contact saw the gap of the pairing, frozen
/// at the start of the step, so its residual never followed the
/// correction; tests/studies/stat_contact_continue.comm had noted it).
#[test]
fn a_block_starting_inside_the_foundation_is_pushed_out() {
    let body = "\
MAT = DEFI_MATERIAU(ELAS=_F(E=1000., NU=0.))
CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))
PR = AFFE_CHAR_MECA(MODELE=MO, PRES_REP=_F(GROUP_MA='HAUT', PRES=10.))
FIX = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO='SOCLE', DX=0., DY=0.), _F(GROUP_NO='GAUCHE', DX=0.)))
DEPL0 = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='AFFE', MODELE=MO, AFFE=_F(GROUP_MA='BLOC', NOM_CMP='DY', VALE=-1.E-6))
LI = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=2))
R = STAT_NON_LINE(ETAT_INIT=_F(DEPL=DEPL0), MODELE=MO, CHAM_MATER=CM, EXCIT=(_F(CHARGE=PR), _F(CHARGE=FIX)), CONTACT=CO,
                  COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=LI),
                  CONVERGENCE=_F(RESI_GLOB_RELA=1.E-10, ITER_GLOB_MAXI=20))";
    let (_, resu) = run("inside_start", body);
    let rows = rows(&resu);
    for t in [0.5, 1.0] {
        check_squeezed(&rows, t, -10.0, 0.0, "started inside");
    }
}
