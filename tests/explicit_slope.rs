//! Contact on an inclined plane in explicit dynamics (probe explp,
//! 2026-11-28): the 3D block on its foundation of the contact tests
//! (`common::block_on_foundation_3d`), rotated by 30 degrees about y, so
//! that the contact normal n = (sin 30, 0, cos 30) lies along no axis;
//! gravity stays along −z. Against rigid-body mechanics:
//!
//! - a block touching the plane (to the rounding of the rotated
//!   coordinates) does not penetrate it: no initial-penetration alarm, in
//!   explicit and in implicit runs (it said "4 slave node(s) penetrate
//!   the master at the initial state (deepest 1.7742e-16)" here, 6 nodes
//!   and 2.0717e-16 on the probe's mesh), while a block put 1e-3 into the
//!   plane still gets it;
//! - with Coulomb friction the block slides down at g (sin − μ cos) from
//!   rest (μ = 0.2 < tan 30) and, started down the slope at V0 with
//!   μ = 0.8 > tan 30, stops after V0² / (2 g (μ cos − sin)) and stays;
//!   the energy table holds TRAV_EXT = m g d sin, DISS_FROT = μ m g cos d,
//!   ENER_CIN = ½ m v² − ½ m V0²;
//! - frictionless, a block thrown obliquely at the plane exchanges
//!   momentum along n only.

mod common;

use std::f64::consts::PI;

const TH: f64 = PI / 6.0;

/// The block [0, 2]² × [0, 1] on the foundation [−1, 3]² × [−1, 0]
/// (common::block_on_foundation_3d), rotated by 30 degrees about y:
/// (x, y, z) → (x cos + z sin, y, −x sin + z cos), the plane z = 0 becoming
/// the slope going down along +x. Node group HAUT_C: the block's top
/// centre (1, 1, 1) before the rotation.
fn slope_mesh() -> aster::mesh::Mesh {
    let mut m = common::block_on_foundation_3d();
    let top = m
        .coords
        .iter()
        .position(|p| *p == [1.0, 1.0, 1.0])
        .expect("top centre node");
    m.node_groups.insert("HAUT_C".into(), vec![top]);
    let (c, s) = (TH.cos(), TH.sin());
    for p in &mut m.coords {
        *p = [p[0] * c + p[2] * s, p[1], -p[0] * s + p[2] * c];
    }
    m
}

/// The commands before the runs: the skins oriented outward, the model, the steel (stiffness damping
/// AMOR_ALPHA when `damped`: it takes out the elastic vibration a sudden
/// weight and a sliding stop excite, which an undamped block keeps and
/// which ratchets it down the slope), the held foundation, the weight
/// (g = 1e6 along −z).
fn prelude(damped: bool) -> String {
    let amor = if damped { ", AMOR_ALPHA=1.E-7" } else { "" };
    format!(
        "DEBUT()
MAIL = LIRE_MAILLAGE(FORMAT='MED')
MAIL = MODI_MAILLAGE(reuse=MAIL, MAILLAGE=MAIL, ORIE_PEAU_3D=_F(GROUP_MA=('ESCL', 'MAIT')))
MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'))
ACIER = DEFI_MATERIAU(ELAS=_F(E=2.E5, NU=0.3, RHO=7.8E-9{amor}))
CHMAT = AFFE_MATERIAU(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', MATER=ACIER))
FIXE = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_NO='SOCLE', DX=0., DY=0., DZ=0.))
PES = AFFE_CHAR_MECA(MODELE=MO, PESANTEUR=_F(GRAVITE=1.E6, DIRECTION=(0., 0., -1.), GROUP_MA='BLOC'))
"
    )
}

fn initial_alarms(mess: &str) -> Vec<&str> {
    mess.lines()
        .filter(|l| l.contains("penetrate the master at the initial state"))
        .collect()
}

/// The faces meet to the rounding of the rotated coordinates (2e-16 of a
/// coordinate of 1): that is no penetration, and the alarm, which says the
/// contact will push the nodes out with an impulse the user did not
/// model, must not be given, by the explicit runs (kinematic and
/// penalised) nor by the implicit one. Before, each run gave "4 slave
/// node(s) penetrate the master at the initial state (deepest
/// 1.7742e-16)": the rounding allowance of `contact::penetrations` was
/// proportional to the gap and the displacements, both 0 here, not to the
/// coordinates the gap is computed from. A block displaced 1e-3 into the
/// plane (ETAT_INIT DEPL along −n) is still reported, with its depth.
#[test]
fn a_block_touching_a_rotated_plane_is_not_an_initial_penetration() {
    let (dir, med) = common::scratch_mesh("explicit_slope_touch", &slope_mesh());
    let (c, s) = (TH.cos(), TH.sin());
    let runs = |depl: &str| -> String {
        format!(
            "{}
CK = DEFI_CONTACT(MODELE=MO, FORMULATION='DISCRETE',
                  ZONE=_F(GROUP_MA_MAIT='MAIT', GROUP_MA_ESCL='ESCL', ALGO_CONT='CONTRAINTE'))
CP = DEFI_CONTACT(MODELE=MO, FORMULATION='DISCRETE',
                  ZONE=_F(GROUP_MA_MAIT='MAIT', GROUP_MA_ESCL='ESCL', ALGO_CONT='PENALISATION', E_N=1.E4))
U0 = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='AFFE', MODELE=MO,
                AFFE=_F(GROUP_MA='BLOC', NOM_CMP=('DX', 'DY', 'DZ'), VALE=({depl})))
L = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=4.E-7, NOMBRE=10))
RK = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, MASS_DIAG='OUI', EXCIT=(_F(CHARGE=FIXE), _F(CHARGE=PES)),
                   CONTACT=CK, COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), ETAT_INIT=_F(DEPL=U0),
                   INCREMENT=_F(LIST_INST=L), SCHEMA_TEMPS=_F(SCHEMA='DIFF_CENT', FORMULATION='ACCELERATION'))
RP = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, MASS_DIAG='OUI', EXCIT=(_F(CHARGE=FIXE), _F(CHARGE=PES)),
                   CONTACT=CP, COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), ETAT_INIT=_F(DEPL=U0),
                   INCREMENT=_F(LIST_INST=L), SCHEMA_TEMPS=_F(SCHEMA='DIFF_CENT', FORMULATION='ACCELERATION'))
LI = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1.E-6, NOMBRE=2))
RI = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=FIXE), _F(CHARGE=PES)),
                   CONTACT=CP, COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), ETAT_INIT=_F(DEPL=U0),
                   INCREMENT=_F(LIST_INST=LI), SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'))
FIN()
",
            prelude(false)
        )
    };
    let (run, _) = common::run_generated(&dir, "explicit_slope_touch", &runs("0., 0., 0."), &med);
    let mess = run.file("explicit_slope_touch.mess");
    // The three runs went through their steps.
    assert_eq!(mess.matches("explicit contact, ").count(), 2, "{mess}");
    assert!(mess.contains("RESI_GLOB_RELA"), "{mess}");
    assert_eq!(initial_alarms(&mess), Vec::<&str>::new());

    let depth = 1e-3;
    let into = format!("{}, 0., {}", -depth * s, -depth * c);
    let (run, _) = common::run_generated(&dir, "explicit_slope_inside", &runs(&into), &med);
    let mess = run.file("explicit_slope_inside.mess");
    let alarms = initial_alarms(&mess);
    assert_eq!(alarms.len(), 3, "{mess}");
    for a in alarms {
        // The 9 nodes of the block's bottom face, 1e-3 deep.
        assert!(a.contains("alarm: 9 slave node(s)"), "{a}");
        assert!(a.contains("(deepest 1.0000e-3)"), "{a}");
    }
}

/// The value of column `col` in the row of `table` (printed in `resu`) at
/// the instant `t`.
fn at(resu: &str, table: &str, t: f64, col: &str) -> f64 {
    let rows = common::printed_table(resu, table);
    let row = rows
        .iter()
        .find(|r| {
            let v: f64 = r["INST"].parse().unwrap();
            (v - t).abs() <= 1e-9 * t
        })
        .unwrap_or_else(|| panic!("{table}: no row at {t}: {rows:?}"));
    row[col].parse().unwrap()
}

/// Coulomb's law on the slope, kinematic and penalised, DIFF_CENT with the
/// lumped mass and stiffness damping. ACC: μ = 0.2, from rest; DEC:
/// μ = 0.8, V0 = 300 mm/s down the slope, stopping at 1.556e-3 s.
/// Measured, through IMPR_TABLE's six digits: every value of the
/// kinematic run within 6e-6 (the printing), the penalised run's too but
/// its stop: 4.4e-3 long, DISS_FROT 2.6e-3 (the normal penalty lets the
/// block bounce on its springs, their mean force m g cos: the stop falls
/// at a phase of the bounce). Tolerances: 1e-4 (six printed digits, the
/// block's elastic settling, about 1e-7 of a distance, and the first
/// steps' transient), and
/// 1e-2 for the penalised stop (the bounce).
#[test]
fn a_block_slides_down_a_slope_at_the_coulomb_rate() {
    let (dir, med) = common::scratch_mesh("explicit_slope_slide", &slope_mesh());
    let mut comm = prelude(true);
    comm.push_str(
        "VITINI = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='AFFE', MODELE=MO,
                    AFFE=_F(GROUP_MA='BLOC', NOM_CMP=('DX', 'DY', 'DZ'), VALE=(259.8076211353316, 0., -150.)))
L1 = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1.E-3, NOMBRE=25000))
L2 = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=2.E-3, NOMBRE=50000))
LA = DEFI_LIST_REEL(VALE=(1.E-3, 2.E-3))
",
    );
    for (algo, name, law) in [
        ("K", "CONTRAINTE", ""),
        ("P", "PENALISATION", "E_N=1.E4, ALGO_FROT='PENALISATION', "),
    ] {
        for (case, mu, list, init) in [
            ("A", "0.2", "L1", ""),
            ("D", "0.8", "L2", "ETAT_INIT=_F(VITE=VITINI), "),
        ] {
            comm.push_str(&format!(
                "C{case}{algo} = DEFI_CONTACT(MODELE=MO, FORMULATION='DISCRETE', FROTTEMENT='COULOMB',
    ZONE=_F(GROUP_MA_MAIT='MAIT', GROUP_MA_ESCL='ESCL', ALGO_CONT='{name}', {law}COULOMB={mu}, E_T=1.E5))
R{case}{algo} = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, MASS_DIAG='OUI',
    EXCIT=(_F(CHARGE=FIXE), _F(CHARGE=PES)), CONTACT=C{case}{algo}, {init}
    COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST={list}),
    ARCHIVAGE=_F(LIST_INST=LA), SCHEMA_TEMPS=_F(SCHEMA='DIFF_CENT', FORMULATION='ACCELERATION'))
E{case}{algo} = RECU_TABLE(CO=R{case}{algo}, NOM_TABLE='PARA_CALC')
IMPR_TABLE(TABLE=E{case}{algo})
U{case}{algo} = POST_RELEVE_T(ACTION=_F(INTITULE='U', RESULTAT=R{case}{algo}, NOM_CHAM='DEPL',
    GROUP_NO='HAUT_C', NOM_CMP=('DX', 'DY', 'DZ'), OPERATION='EXTRACTION'))
IMPR_TABLE(TABLE=U{case}{algo})
"
            ));
        }
    }
    comm.push_str("FIN()\n");
    let (_, resu) = common::run_generated(&dir, "explicit_slope_slide", &comm, &med);

    let (c, s) = (TH.cos(), TH.sin());
    let (g, m, v0) = (1e6, 7.8e-9 * 4.0, 300.0);
    let close = |what: &str, got: f64, want: f64, tol: f64| {
        assert!(
            (got - want).abs() <= tol * want.abs(),
            "{what}: {got} against {want} (relative {:.2e}, tolerance {tol:.0e})",
            (got - want) / want
        );
    };
    for (algo, stop_tol) in [("K", 1e-4), ("P", 1e-2)] {
        // From rest, mu = 0.2.
        let t = 1e-3;
        let a = g * (s - 0.2 * c);
        let d = 0.5 * a * t * t;
        let ua = format!("UA{algo}");
        let ea = format!("EA{algo}");
        close(&format!("{ua} DX"), at(&resu, &ua, t, "DX"), d * c, 1e-4);
        close(&format!("{ua} DZ"), at(&resu, &ua, t, "DZ"), -d * s, 1e-4);
        assert!(at(&resu, &ua, t, "DY").abs() < 1e-9 * d, "{ua} DY");
        close(
            &format!("{ea} TRAV_EXT"),
            at(&resu, &ea, t, "TRAV_EXT"),
            m * g * d * s,
            1e-4,
        );
        close(
            &format!("{ea} ENER_CIN"),
            at(&resu, &ea, t, "ENER_CIN"),
            0.5 * m * (a * t).powi(2),
            1e-4,
        );
        close(
            &format!("{ea} DISS_FROT"),
            at(&resu, &ea, t, "DISS_FROT"),
            0.2 * m * g * c * d,
            1e-4,
        );
        // Down the slope at V0, mu = 0.8: stopped and at rest at 2e-3 s.
        let t = 2e-3;
        let a = g * (0.8 * c - s);
        let d = v0 * v0 / (2.0 * a);
        let ud = format!("UD{algo}");
        let ed = format!("ED{algo}");
        close(
            &format!("{ud} DX"),
            at(&resu, &ud, t, "DX"),
            d * c,
            stop_tol,
        );
        close(
            &format!("{ud} DZ"),
            at(&resu, &ud, t, "DZ"),
            -d * s,
            stop_tol,
        );
        close(
            &format!("{ed} ENER_CIN"),
            at(&resu, &ed, t, "ENER_CIN"),
            -0.5 * m * v0 * v0,
            1e-4,
        );
        close(
            &format!("{ed} TRAV_EXT"),
            at(&resu, &ed, t, "TRAV_EXT"),
            m * g * d * s,
            stop_tol,
        );
        close(
            &format!("{ed} DISS_FROT"),
            at(&resu, &ed, t, "DISS_FROT"),
            0.8 * m * g * c * d,
            stop_tol,
        );
    }
}

/// Frictionless, a block thrown at the slope with V = 500 s − 200 n (s the
/// slope's direction down, n its normal): the contact forces lie along n,
/// so the momentum the model gains over the run (Σ M v, printed in the
/// .mess with the impulse of the reactions) has no component along s nor
/// y, while its normal component reverses the block's (the rebound).
/// Measured from the .mess (10 digits): s·ΔP / |ΔP| 2e-11 (kinematic),
/// 7e-11 (penalised); n·ΔP 1.31 p0 and 2.00 p0 (p0 = m VN).
#[test]
fn a_block_thrown_at_a_slope_exchanges_momentum_along_its_normal_only() {
    let (dir, med) = common::scratch_mesh("explicit_slope_throw", &slope_mesh());
    let (c, s) = (TH.cos(), TH.sin());
    let (vt, vn) = (500.0, 200.0);
    let v = [vt * c - vn * s, 0.0, -vt * s - vn * c];
    let comm = format!(
        "{}
CK = DEFI_CONTACT(MODELE=MO, FORMULATION='DISCRETE',
                  ZONE=_F(GROUP_MA_MAIT='MAIT', GROUP_MA_ESCL='ESCL', ALGO_CONT='CONTRAINTE'))
CP = DEFI_CONTACT(MODELE=MO, FORMULATION='DISCRETE',
                  ZONE=_F(GROUP_MA_MAIT='MAIT', GROUP_MA_ESCL='ESCL', ALGO_CONT='PENALISATION', E_N=1.E4))
V0 = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='AFFE', MODELE=MO,
                AFFE=_F(GROUP_MA='BLOC', NOM_CMP=('DX', 'DY', 'DZ'), VALE=({:?}, 0., {:?})))
L = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=4.E-6, NOMBRE=200))
RK = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, MASS_DIAG='OUI', EXCIT=_F(CHARGE=FIXE),
                   CONTACT=CK, COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), ETAT_INIT=_F(VITE=V0),
                   INCREMENT=_F(LIST_INST=L), SCHEMA_TEMPS=_F(SCHEMA='DIFF_CENT', FORMULATION='ACCELERATION'))
RP = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, MASS_DIAG='OUI', EXCIT=_F(CHARGE=FIXE),
                   CONTACT=CP, COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), ETAT_INIT=_F(VITE=V0),
                   INCREMENT=_F(LIST_INST=L), SCHEMA_TEMPS=_F(SCHEMA='DIFF_CENT', FORMULATION='ACCELERATION'))
FIN()
",
        prelude(false),
        v[0],
        v[2]
    );
    let (run, _) = common::run_generated(&dir, "explicit_slope_throw", &comm, &med);
    let mess = run.file("explicit_slope_throw.mess");
    let momentum = common::tuples(&mess, "momentum of the model (M v): change over the run ");
    let impulse = common::tuples(&mess, "impulse of the contact reactions on the bodies ");
    assert_eq!(momentum.len(), 2, "{mess}");
    assert_eq!(impulse.len(), 2, "{mess}");
    let p0 = 7.8e-9 * 4.0 * vn;
    for (k, (dp, imp)) in momentum.iter().zip(&impulse).enumerate() {
        let norm = (dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2]).sqrt();
        let along_s = dp[0] * c - dp[2] * s;
        let along_n = dp[0] * s + dp[2] * c;
        assert!(along_s.abs() <= 1e-9 * norm, "run {k}: {dp:?}");
        assert!(dp[1].abs() <= 1e-9 * norm, "run {k}: {dp:?}");
        // The block left the plane: its normal momentum reversed (the
        // kinematic impact of the bottom nodes is perfectly plastic, the
        // penalty nearly elastic).
        assert!(
            along_n > p0 && along_n < 2.1 * p0,
            "run {k}: n.dP = {along_n}, p0 = {p0}"
        );
        for i in 0..3 {
            assert!(
                (dp[i] - imp[i]).abs() <= 1e-9 * norm,
                "run {k}: {dp:?} {imp:?}"
            );
        }
    }
}
