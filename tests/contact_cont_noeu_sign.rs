//! The sign of CONT_NOEU's force vectors and its percussions, on whole
//! studies whose directions are known by hand (docs/contact.md §4).
//!
//! code_aster prints in RNX.., RTAX.., RTGX.., RX.. the contact term on the
//! internal-force side of the slave node's equilibrium, i.e. **minus the
//! force exerted on the slave node** (the force the slave exerts on the
//! master): `cfresu` projects the vector `AFMU` (penalised) or `ATMU`
//! (`CONTRAINTE`) of the slave's dofs, both added to the internal forces in
//! the equilibrium residual (`nmequi`), whose slave entries are λ·n_in with
//! λ ≥ 0 and n_in the master's inward normal (`cfcpes`, `cfcoef`,
//! `cfnewj`); `mmmres` (FORMULATION='CONTINUE') prints the nodal vectors
//! `CNELTC`/`CNELTF` of the contact elements, added to `CNFINT` (`nmasco`).
//! A block pressed down onto a foundation below it therefore has RNY < 0,
//! and a block pulled along +x and held by friction RTAX > 0.
//!
//! The percussion: `cfresu` (DISCRETE) zeroes it before adding R·dt, so I
//! is R·dt of the step; `mmmres` (CONTINUE) accumulates it from step to
//! step, adding R·dt once per contact point of the node, i.e. once per
//! slave cell holding it (INTEGRATION='AUTO': the points are the cells'
//! nodes).
//!
//! The model: a D_PLAN block [0, 4] x [0, 2] (4 x 2 QUAD4, E = 1000,
//! NU = 0) on a fixed foundation [-1, 5] x [-1, 0] (6 x 1 QUAD4); slave
//! face the block's bottom (4 SEG2 of length 1: the two end nodes belong to
//! one slave cell, the three inner ones to two), master the foundation's
//! top. Loads on the block's top, ramped from 0 at t = 0 to 1 at t = 1 over
//! two steps (dt = 0.5): a pressure P = 10 (total 4 P = 40 downwards) and,
//! with friction, a traction Q = 1 along +x (total 4 Q = 4), nothing else
//! holding the block along x, so that friction alone carries it (it sticks:
//! Q = 0.1 P < mu P, mu = 0.5). Static equilibrium of the block: the
//! contact forces on the slave nodes sum to (-4 Q, +4 P), so the printed
//! sums are RNY = -4 P, RTAX = +4 Q, RX = 4 Q, RY = -4 P.

mod common;

use std::collections::HashMap;

const P: f64 = 10.0;
const Q: f64 = 1.0;

const CMPS: [&str; 17] = [
    "CONT", "JEU", "RN", "RNX", "RNY", "RTAX", "RTAY", "RTGX", "RTGY", "RX", "RY", "R", "I", "IX",
    "IY", "GLIX", "GLI",
];

/// Runs a STAT_NON_LINE of the block with the DEFI_CONTACT `contact`,
/// the extra loads `loads` (besides the foundation held), the STAT_NON_LINE
/// keywords `extra`, and returns the printed CONT_NOEU rows of the slave
/// nodes at t = 0.5 and t = 1, sorted by x.
fn run(tag: &str, contact: &str, loads: &str, extra: &str) -> [Vec<HashMap<String, String>>; 2] {
    let (dir, med) = common::scratch_mesh(tag, &common::block_on_foundation());
    let cmps = CMPS.map(|c| format!("'{c}'")).join(", ");
    let comm = format!(
        "DEBUT()\n\
         MA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
         MA = MODI_MAILLAGE(reuse=MA, MAILLAGE=MA, ORIE_PEAU_2D=_F(GROUP_MA=('ESCL', 'MAIT', 'HAUT')))\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\n\
         MAT = DEFI_MATERIAU(ELAS=_F(E=1000., NU=0.))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
         FIX = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='SOCLE', DX=0., DY=0.))\n\
         DEPL0 = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='AFFE', MODELE=MO, \
         AFFE=_F(GROUP_MA='BLOC', NOM_CMP='DY', VALE=-1.E-6))\n\
         CO = {contact}\n\
         {loads}\n\
         RAMPE = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0., 1., 1.))\n\
         LI = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=2))\n\
         R = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=(_F(CHARGE=FIX), _F(CHARGE=CH, FONC_MULT=RAMPE)), \
         CONTACT=CO, COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=LI), \
         CONVERGENCE=_F(RESI_GLOB_RELA=1.E-10, ITER_GLOB_MAXI=30){extra})\n\
         T = POST_RELEVE_T(ACTION=_F(INTITULE='C', GROUP_NO='NESCL', RESULTAT=R, NOM_CHAM='CONT_NOEU', \
         NOM_CMP=({cmps}), INST=(0.5, 1.), OPERATION='EXTRACTION'))\n\
         IMPR_TABLE(TABLE=T, FORMAT_R='E24.16')\n\
         FIN()\n"
    );
    let (_, resu) = common::run_generated(&dir, tag, &comm, &med);
    let rows = common::printed_table(&resu, "T");
    let at = |t: f64| {
        let mut v: Vec<HashMap<String, String>> = rows
            .iter()
            .filter(|r| (num(r, "INST") - t).abs() <= 1e-9)
            .cloned()
            .collect();
        v.sort_by(|a, b| num(a, "COOR_X").total_cmp(&num(b, "COOR_X")));
        assert_eq!(v.len(), 5, "{tag}: the 5 slave nodes at {t}");
        v
    };
    [at(0.5), at(1.0)]
}

fn num(row: &HashMap<String, String>, k: &str) -> f64 {
    row[k]
        .parse()
        .unwrap_or_else(|_| panic!("{k} = {} is not a number", row[k]))
}

fn sum(rows: &[HashMap<String, String>], k: &str) -> f64 {
    rows.iter().map(|r| num(r, k)).sum()
}

/// Slave cells holding the node of x = `x` (0 to 4): 1 at the face's
/// ends, 2 inside.
fn visits(x: f64) -> f64 {
    if x == 0.0 || x == 4.0 {
        1.0
    } else {
        2.0
    }
}

/// At both instants (load factor t): every slave node closed, its normal
/// vector printed into the foundation (RNX = 0, RNY = -RN < 0), the sums
/// RNY = -`load` t and RY = -`load` t (and, `with_friction`, RTAX = RX =
/// 4 Q t, every node's RTAX > 0, RTG* = 0), R* = RN* + RT*.
fn check_forces(
    rows: &[Vec<HashMap<String, String>>; 2],
    load: f64,
    cont: f64,
    with_friction: bool,
    tag: &str,
) {
    for (k, t) in [(0, 0.5), (1, 1.0)] {
        let face = &rows[k];
        for r in face {
            let at = format!("{tag}: node {} at t = {t}", r["NOEUD"]);
            assert_eq!(num(r, "CONT"), cont, "{at}");
            let (rn, rnx, rny) = (num(r, "RN"), num(r, "RNX"), num(r, "RNY"));
            assert!(rn > 0.0, "{at}: RN {rn}");
            assert!(rnx.abs() <= 1e-9 * rn, "{at}: RNX {rnx}");
            assert!((rny + rn).abs() <= 1e-9 * rn, "{at}: RNY {rny}, RN {rn}");
            let rtx = num(r, "RTAX") + num(r, "RTGX");
            let rty = num(r, "RTAY") + num(r, "RTGY");
            assert!((num(r, "RX") - (rnx + rtx)).abs() <= 1e-9 * rn, "{at}");
            assert!((num(r, "RY") - (rny + rty)).abs() <= 1e-9 * rn, "{at}");
            if with_friction {
                assert!(num(r, "RTAX") > 0.0, "{at}: RTAX {}", r["RTAX"]);
                assert_eq!(num(r, "RTGX"), 0.0, "{at}");
            } else {
                assert_eq!((num(r, "RTAX"), num(r, "RTGX")), (0.0, 0.0), "{at}");
            }
        }
        let tol = 1e-7 * P;
        assert!(
            (sum(face, "RNY") + load * t).abs() <= tol,
            "{tag}: sum RNY {} at {t}",
            sum(face, "RNY")
        );
        assert!(
            (sum(face, "RY") + load * t).abs() <= tol,
            "{tag}: sum RY {} at {t}",
            sum(face, "RY")
        );
        let q = if with_friction { 4.0 * Q * t } else { 0.0 };
        assert!(
            (sum(face, "RTAX") - q).abs() <= tol,
            "{tag}: sum RTAX {} at {t}",
            sum(face, "RTAX")
        );
        assert!(
            (sum(face, "RX") - q).abs() <= tol,
            "{tag}: sum RX {} at {t}",
            sum(face, "RX")
        );
    }
}

/// DISCRETE: I = R·dt, IX = RX·dt, IY = RY·dt of the step, at both
/// instants (dt = 0.5).
fn check_step_percussion(rows: &[Vec<HashMap<String, String>>; 2], tag: &str) {
    for face in rows {
        for r in face {
            let at = format!("{tag}: node {} at t = {}", r["NOEUD"], r["INST"]);
            for (i, f) in [("I", "R"), ("IX", "RX"), ("IY", "RY")] {
                let want = 0.5 * num(r, f);
                assert!(
                    (num(r, i) - want).abs() <= 1e-12 * num(r, "R"),
                    "{at}: {i} {} vs {f}·dt {want}",
                    r[i]
                );
            }
        }
    }
}

/// CONTINUE: I = visits·R·dt at t = 0.5, I(1) = I(0.5) + visits·R(1)·dt,
/// and the same for IX, IY with RX, RY.
fn check_accumulated_percussion(rows: &[Vec<HashMap<String, String>>; 2], tag: &str) {
    for (a, b) in rows[0].iter().zip(&rows[1]) {
        assert_eq!(a["NOEUD"], b["NOEUD"]);
        let m = visits(num(a, "COOR_X"));
        let at = format!("{tag}: node {} (visited {m} times per step)", a["NOEUD"]);
        for (i, f) in [("I", "R"), ("IX", "RX"), ("IY", "RY")] {
            let first = m * 0.5 * num(a, f);
            let second = first + m * 0.5 * num(b, f);
            let tol = 1e-12 * num(b, "R");
            assert!(
                (num(a, i) - first).abs() <= tol,
                "{at}: {i} {} at 0.5 vs {first}",
                a[i]
            );
            assert!(
                (num(b, i) - second).abs() <= tol,
                "{at}: {i} {} at 1 vs {second}",
                b[i]
            );
        }
    }
}

const PRESSURE: &str = "CH = AFFE_CHAR_MECA(MODELE=MO, PRES_REP=_F(GROUP_MA='HAUT', PRES=10.), \
                        DDL_IMPO=_F(GROUP_NO='GAUCHE', DX=0.))";
const PRESSURE_AND_PULL: &str =
    "CH = AFFE_CHAR_MECA(MODELE=MO, PRES_REP=_F(GROUP_MA='HAUT', PRES=10.), \
                                 FORCE_CONTOUR=_F(GROUP_MA='HAUT', FX=1.))";
/// The discrete studies start with the block 1e-6 inside the foundation (a
/// rigid shift, no strain): a penalised link is active only with a
/// negative gap, so from gap 0 the prediction would leave the block free.
const SHIFTED: &str = ", ETAT_INIT=_F(DEPL=DEPL0)";

/// DISCRETE, penalised, Coulomb friction (stick): RNY < 0 at every slave
/// node (into the foundation), RTAX > 0 (along the pull), the sums of
/// the block's equilibrium, I = R·dt of the step.
#[test]
fn discrete_penalised_block_pressed_and_pulled() {
    let rows = run(
        "sign_disc_pena",
        "DEFI_CONTACT(MODELE=MO, FORMULATION='DISCRETE', FROTTEMENT='COULOMB', \
         ZONE=_F(GROUP_MA_MAIT='MAIT', GROUP_MA_ESCL='ESCL', ALGO_CONT='PENALISATION', E_N=1.E4, \
         ALGO_FROT='PENALISATION', E_T=1.E3, COULOMB=0.5))",
        PRESSURE_AND_PULL,
        SHIFTED,
    );
    check_forces(&rows, 4.0 * P, 1.0, true, "DISCRETE penalised");
    check_step_percussion(&rows, "DISCRETE penalised");
}

/// DISCRETE, ALGO_CONT='CONTRAINTE' (the default, frictionless): the
/// active set corrects the increment and adds no stiffness, so in statics
/// the block must be held without it: its top is pushed down by a DDL_IMPO
/// DY = -0.01 t (left edge held along x), squeezing it against the
/// foundation, sigma_yy = E (-0.01 t / 2) = -5 t, a total of 20 t on the
/// face. RNY < 0, sum RNY = -20 t, I = R·dt.
#[test]
fn discrete_contrainte_block_squeezed() {
    let rows = run(
        "sign_disc_cont",
        "DEFI_CONTACT(MODELE=MO, FORMULATION='DISCRETE', ZONE=_F(GROUP_MA_MAIT='MAIT', GROUP_MA_ESCL='ESCL'))",
        "CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO='GAUCHE', DX=0.), _F(GROUP_NO='TOP', DY=-0.01)))",
        "",
    );
    check_forces(&rows, 20.0, 2.0, false, "DISCRETE CONTRAINTE");
    check_step_percussion(&rows, "DISCRETE CONTRAINTE");
}

/// CONTINUE, Coulomb friction (stick): the same signs and sums; the
/// percussion accumulates, once per slave cell of the node per step.
#[test]
fn continuous_block_pressed_and_pulled() {
    let rows = run(
        "sign_cont_frot",
        "DEFI_CONTACT(MODELE=MO, FORMULATION='CONTINUE', FROTTEMENT='COULOMB', \
         ZONE=_F(GROUP_MA_MAIT='MAIT', GROUP_MA_ESCL='ESCL', COULOMB=0.5, SEUIL_INIT=5.))",
        PRESSURE_AND_PULL,
        "",
    );
    check_forces(&rows, 4.0 * P, 1.0, true, "CONTINUE");
    check_accumulated_percussion(&rows, "CONTINUE");
}

/// CONTINUE frictionless, block held along x: RN* exactly -P times the
/// node's share of the face (1/2 at the ends, 1 inside), pointing into
/// the foundation, and the accumulated percussion.
#[test]
fn continuous_block_pressed() {
    let rows = run(
        "sign_cont",
        "DEFI_CONTACT(MODELE=MO, FORMULATION='CONTINUE', ZONE=_F(GROUP_MA_MAIT='MAIT', GROUP_MA_ESCL='ESCL'))",
        PRESSURE,
        "",
    );
    check_forces(&rows, 4.0 * P, 2.0, false, "CONTINUE frictionless");
    for (k, t) in [(0, 0.5), (1, 1.0)] {
        for r in &rows[k] {
            let share = visits(num(r, "COOR_X")) / 2.0;
            let want = -P * t * share;
            assert!(
                (num(r, "RNY") - want).abs() <= 1e-9 * P,
                "node {} at {t}: RNY {} vs {want}",
                r["NOEUD"],
                r["RNY"]
            );
        }
    }
    check_accumulated_percussion(&rows, "CONTINUE frictionless");
}
