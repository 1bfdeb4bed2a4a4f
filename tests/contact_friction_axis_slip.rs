//! The Newton cycle of discrete penalised contact with Coulomb friction
//! (probe h20_axis_slip_newton_cycle: a HEXA20 block sliding along a
//! tangent of its QUAD8 face, period-3 open/contact cycle of whole node
//! rows): `nonlinear::contact::newton_cycle` recognises a repeated
//! iterate and names the switching slave nodes, so the step fails at once
//! (DECOUPE cuts it) instead of after ITER_GLOB_MAXI; it never fires on a
//! converging sequence.

mod common;

use aster::contact::LinkStatus::{self, Open, Slip, Stick};
use aster::nonlinear::contact::{newton_cycle, LinkIterate};

type Iterate = (f64, Vec<LinkIterate>);

/// An evaluation of links on slave nodes 8, 9, ...; a sliding link slips
/// along +tau1.
fn it(resi: f64, statuses: &[LinkStatus]) -> Iterate {
    (
        resi,
        statuses
            .iter()
            .copied()
            .enumerate()
            .map(|(i, s)| (8 + i, s, [if s == Slip { 1 } else { 0 }, 0]))
            .collect(),
    )
}

/// The probe's period: rows open and close with RESI 0.97, 0.94, 0.146.
fn period() -> Vec<Iterate> {
    vec![
        it(0.9721, &[Open, Open, Slip, Slip]),
        it(0.9448, &[Open, Open, Open, Slip]),
        it(0.1458, &[Slip, Slip, Slip, Open]),
    ]
}

#[test]
fn a_period_three_contact_cycle_is_named_after_three_periods() {
    let mut h: Vec<Iterate> = vec![it(f64::INFINITY, &[Slip; 4]), it(0.5, &[Slip; 4])];
    for _ in 0..2 {
        h.extend(period());
    }
    assert!(newton_cycle(&h).is_none(), "two periods are not enough");
    h.extend(period());
    let m = newton_cycle(&h).expect("three periods: a cycle");
    assert!(m.contains("period 3"), "{m}");
    assert!(m.contains("between contact and open"), "{m}");
    // Slave nodes 8..11 are N9..N12; every one of them switches.
    for n in [
        "N9 (0 -> 0 -> 2+)",
        "N10",
        "N11 (2+ -> 0 -> 2+)",
        "N12 (2+ -> 2+ -> 0)",
    ] {
        assert!(m.contains(n), "{n} missing: {m}");
    }
    assert!(m.contains("DECOUPE"), "{m}");
}

#[test]
fn a_stick_slip_two_cycle_is_named() {
    let mut h = Vec::new();
    for _ in 0..3 {
        h.push(it(1.0, &[Open, Slip]));
        h.push(it(2.4404e-3, &[Stick, Slip]));
    }
    let m = newton_cycle(&h).expect("a cycle");
    assert!(
        m.contains("period 2") && m.contains("1 slave node(s)"),
        "{m}"
    );
    assert!(m.contains("N9 (0 -> 1)"), "{m}");
}

/// Every link sliding, first one way then the other, with the same
/// residual: the status alone does not change, the slip direction does.
#[test]
fn a_slip_direction_two_cycle_is_named() {
    let flip = |resi: f64, sign: i8| -> Iterate {
        (resi, vec![(0, Slip, [sign, 0]), (4, Slip, [sign, -1])])
    };
    let mut h = vec![it(f64::INFINITY, &[Open, Open])];
    for _ in 0..3 {
        h.push(flip(0.5207, 1));
        h.push(flip(0.5207, -1));
    }
    let m = newton_cycle(&h).expect("a cycle");
    assert!(
        m.contains("period 2") && m.contains("between slip directions"),
        "{m}"
    );
    assert!(
        m.contains("N1 (2+ -> 2-)") && m.contains("N5 (2+- -> 2--)"),
        "{m}"
    );
    // The same residuals with one slip direction throughout converge to a
    // fixed point, not a cycle.
    let h: Vec<Iterate> = (0..8).map(|_| flip(0.5207, 1)).collect();
    assert!(newton_cycle(&h).is_none());
}

#[test]
fn converging_or_static_sequences_are_not_cycles() {
    // Same statuses, decreasing residual: Newton converging.
    let h: Vec<Iterate> = (0..12)
        .map(|k| it(0.5f64.powi(k), &[Slip, Slip, Open]))
        .collect();
    assert!(newton_cycle(&h).is_none());
    // Statuses cycling but residuals still moving (beyond 1e-6).
    let mut h = Vec::new();
    for k in 0..4 {
        let f = 1.0 - 1e-3 * k as f64;
        h.push(it(0.9 * f, &[Open, Slip]));
        h.push(it(0.1 * f, &[Slip, Slip]));
    }
    assert!(newton_cycle(&h).is_none());
    // A repeated residual with no status switching is not a contact cycle.
    let h: Vec<Iterate> = (0..12)
        .map(|k| it(if k % 2 == 0 { 0.3 } else { 0.2 }, &[Slip, Slip]))
        .collect();
    assert!(newton_cycle(&h).is_none());
    // The prediction's RESI is +inf: never equal to anything.
    let h: Vec<Iterate> = (0..9).map(|_| it(f64::INFINITY, &[Open, Slip])).collect();
    assert!(newton_cycle(&h).is_none());
}

/// The probe's study end to end: the 2 x 2 x 1 block of
/// `common::block_on_foundation_3d` made quadratic (CREA_MAILLAGE
/// LINE_QUAD: HEXA20, QUAD8 faces), under 3D (full integration), slides
/// along x on its held foundation under gravity tilted by tan(theta) = 0.5,
/// discrete penalised contact with Coulomb 0.25. Newton cycles at some
/// steps (rows of the QUAD8 face open and close in turn); the detector
/// fails those steps at once and DECOUPE cuts them, and the slide is the
/// analytic one: a = g (sin(theta) - mu cos(theta)), DX(T) = a T^2 / 2 at
/// the top centre, sum RN = m g cos(theta).
#[test]
fn hexa20_block_sliding_along_an_axis_reaches_the_analytic_slide() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("h20_axis_slip_src");
    std::fs::create_dir_all(&dir).unwrap();
    let mut mesh = common::block_on_foundation_3d();
    let top = mesh
        .coords
        .iter()
        .position(|c| *c == [1.0, 1.0, 1.0])
        .unwrap();
    mesh.node_groups.insert("HAUT_C".into(), vec![top]);
    let med = dir.join("mesh.mmed");
    aster::medio::write_mesh(&med, &mesh).unwrap();
    let (rho, g, mu, tan, t_fin): (f64, f64, f64, f64, f64) = (7.8e-9, 1e6, 0.25, 0.5, 1e-3);
    let (c, s) = (
        1.0 / (1.0 + tan * tan).sqrt(),
        tan / (1.0 + tan * tan).sqrt(),
    );
    let n = rho * 4.0 * g * c;
    let dx = 0.5 * g * (s - mu * c) * t_fin * t_fin;
    let comm = format!(
        "DEBUT()\n\
         MA0 = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
         MA = CREA_MAILLAGE(MAILLAGE=MA0, LINE_QUAD=_F(TOUT='OUI'))\n\
         MA = MODI_MAILLAGE(reuse=MA, MAILLAGE=MA, ORIE_PEAU_3D=_F(GROUP_MA=('ESCL', 'MAIT')))\n\
         MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=_F(NOM='NESCL20', GROUP_MA='ESCL'))\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'))\n\
         ACIER = DEFI_MATERIAU(ELAS=_F(E=2.E5, NU=0.3, RHO={rho}))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=ACIER))\n\
         FIXE = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(GROUP_MA='FOND', DX=0., DY=0., DZ=0.))\n\
         PES = AFFE_CHAR_MECA(MODELE=MO, PESANTEUR=_F(GRAVITE={g}, DIRECTION=({tan}, 0., -1.), GROUP_MA='BLOC'))\n\
         CONT = DEFI_CONTACT(MODELE=MO, FORMULATION='DISCRETE', FROTTEMENT='COULOMB',\n\
             REAC_GEOM='CONTROLE', NB_ITER_GEOM=2,\n\
             ZONE=_F(GROUP_MA_MAIT='MAIT', GROUP_MA_ESCL='ESCL', ALGO_CONT='PENALISATION', E_N=1.E4,\n\
                     ALGO_FROT='PENALISATION', E_T=1.E5, COULOMB={mu}))\n\
         L = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A={t_fin}, NOMBRE=100))\n\
         DL = DEFI_LIST_INST(DEFI_LIST=_F(LIST_INST=L), ECHEC=_F(EVENEMENT='ERREUR', ACTION='DECOUPE',\n\
             SUBD_METHODE='MANUEL', SUBD_PAS=2, SUBD_NIVEAU=6))\n\
         R = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=(_F(CHARGE=FIXE), _F(CHARGE=PES)), CONTACT=CONT,\n\
             COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=DL),\n\
             SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', BETA=0.3025, GAMMA=0.6, FORMULATION='DEPLACEMENT'),\n\
             CONVERGENCE=_F(RESI_GLOB_RELA=1.E-8, ITER_GLOB_MAXI=100))\n\
         T = POST_RELEVE_T(ACTION=_F(INTITULE='C', GROUP_NO='NESCL20', RESULTAT=R, INST={t_fin},\n\
             NOM_CHAM='CONT_NOEU', NOM_CMP=('CONT', 'RN'), OPERATION='EXTRACTION'))\n\
         TEST_TABLE(TABLE=T, NOM_PARA='RN', TYPE_TEST='SOMM', VALE_CALC={n:.15e}, REFERENCE='ANALYTIQUE',\n\
             VALE_REFE={n:.15e}, PRECISION=1.E-4)\n\
         TEST_RESU(RESU=_F(RESULTAT=R, INST={t_fin}, NOM_CHAM='DEPL', NOM_CMP='DX', GROUP_NO='HAUT_C',\n\
             VALE_CALC={dx:.15e}, REFERENCE='ANALYTIQUE', VALE_REFE={dx:.15e}, PRECISION=1.E-4))\n\
         FIN()\n"
    );
    let (r, _) = common::run_generated(&dir, "h20_axis_slip", &comm, &med);
    common::assert_all_ok(&r, "h20_axis_slip.resu");
    // With code_aster's friction flag (a link closing in an iterate gets
    // its friction from the next one) the rows no longer rock: the slide
    // needs no cut (before the flag: 28 cuts, each a period-3 cycle).
    let mess = r.file("h20_axis_slip.mess");
    assert!(
        mess.contains("100 steps (0 cuts)"),
        "the slide needed cuts again\n{mess}"
    );
}

/// The penalised sleeve of tests/verification/contact_friction_continue.comm
/// (STICK_D: held on its mandrel by friction, tan = 0.15 < mu N / W) with
/// COEF_MATR_FROT = 1: the 2D slip matrix MAF1 - MAF2 is then zero, the
/// links close without friction in the first corrected iterate (the
/// friction flag), slide by 7e-6 mm (the stick cone is 5e-8 mm) and Newton,
/// with no tangential stiffness but the inertia, throws the sleeve from
/// one slip direction to the other (RESI_GLOB_RELA 0.5207 for ever). The
/// detector names it at the 13th iteration instead of the 100th. The study
/// itself runs with the default COEF_MATR_FROT = 0 (the secant matrix),
/// which converges.
#[test]
fn a_sleeve_thrown_between_slip_directions_is_named() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/verification");
    let study = std::fs::read_to_string(root.join("contact_friction_continue.comm")).unwrap();
    let head = study.split("STICK = DYNA_NON_LINE").next().unwrap();
    let head = head.replace(
        "ALGO_FROT='PENALISATION', E_T=E_T, COULOMB=MU)",
        "ALGO_FROT='PENALISATION', E_T=E_T, COULOMB=MU, COEF_MATR_FROT=1.)",
    );
    assert!(
        head.contains("COEF_MATR_FROT=1."),
        "the study's CONTD changed"
    );
    let comm = format!(
        "{head}\
         STICK_D = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=FIXE), _F(CHARGE=PES1)),\n\
             CONTACT=CONTD, COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=L_INST),\n\
             SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', BETA=0.3025, GAMMA=0.6, FORMULATION='DEPLACEMENT'),\n\
             CONVERGENCE=_F(RESI_GLOB_RELA=1.E-8, ITER_GLOB_MAXI=100))\n\
         FIN()\n"
    );
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("sleeve_matr_frot_1_src");
    std::fs::create_dir_all(&dir).unwrap();
    let r = common::run_generated_any(&dir, "sleeve1", &comm, &root.join("sleeve.mmed"));
    let mess = r.file("sleeve1.mess");
    assert_ne!(r.code, 0, "the step converged\n{mess}");
    assert!(
        mess.contains("Newton cycles with period 2")
            && mess.contains("between slip directions")
            && mess.contains("N1 (2"),
        "{mess}"
    );
}
