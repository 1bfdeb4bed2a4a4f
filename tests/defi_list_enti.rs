//! DEFI_LIST_ENTI (code_aster's op0022, OPERATION='DEFI') and LIST_ORDRE
//! in the post-processing commands: the list built by VALE or by
//! intervals, its errors, and a LIST_ORDRE selection that gives exactly
//! the rows of the same NUME_ORDRE selection.

mod common;

/// A STAT_NON_LINE of the block of `common::block_on_foundation` (held at
/// its bottom, its top pressed by PRES = 10 t over 4 steps: NUME_ORDRE
/// 0..4 at t = 0, 0.25, ..., 1), then `post`; returns the run's .resu and
/// exit code.
fn run(tag: &str, post: &str) -> (i32, String, String) {
    let (dir, med) = common::scratch_mesh(tag, &common::block_on_foundation());
    let comm = format!(
        "DEBUT()\n\
         MA = LIRE_MAILLAGE(FORMAT='MED', UNITE=20)\n\
         MA = MODI_MAILLAGE(reuse=MA, MAILLAGE=MA, ORIE_PEAU_2D=_F(GROUP_MA=('HAUT',)))\n\
         MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='D_PLAN'))\n\
         MAT = DEFI_MATERIAU(ELAS=_F(E=1000., NU=0.))\n\
         CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
         FIX = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO='SOCLE', DX=0., DY=0.), _F(GROUP_MA='ESCL', DX=0., DY=0.)))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, PRES_REP=_F(GROUP_MA='HAUT', PRES=10.))\n\
         RAMPE = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0., 1., 1.))\n\
         LI = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=4))\n\
         R = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=(_F(CHARGE=FIX), _F(CHARGE=CH, FONC_MULT=RAMPE)), \
         COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=LI))\n\
         {post}\n\
         FIN()\n"
    );
    let r = common::run_generated_any(&dir, tag, &comm, &med);
    let resu = r.file(&format!("{tag}.resu"));
    let mess = r.file(&format!("{tag}.mess"));
    (r.code, resu, mess)
}

fn column(resu: &str, table: &str, key: &str) -> Vec<String> {
    common::printed_table(resu, table)
        .iter()
        .map(|r| r[key].clone())
        .collect()
}

/// VALE, DEBUT with PAS and with NOMBRE give the same indices; the tables
/// of POST_RELEVE_T with LIST_ORDRE equal those with NUME_ORDRE, row for
/// row; CALC_CHAMP and RECU_FONCTION take LIST_ORDRE too.
#[test]
fn list_ordre_selects_the_same_steps_as_nume_ordre() {
    let post = "L1 = DEFI_LIST_ENTI(VALE=(0, 2, 4))\n\
         L2 = DEFI_LIST_ENTI(DEBUT=0, INTERVALLE=_F(JUSQU_A=4, PAS=2))\n\
         L3 = DEFI_LIST_ENTI(OPERATION='DEFI', DEBUT=0, INTERVALLE=(_F(JUSQU_A=2, NOMBRE=1), _F(JUSQU_A=4, NOMBRE=1)))\n\
         R = CALC_CHAMP(reuse=R, RESULTAT=R, LIST_ORDRE=L3, FORCE='REAC_NODA')\n\
         TN = POST_RELEVE_T(ACTION=_F(INTITULE='T', GROUP_NO='TOP', RESULTAT=R, NOM_CHAM='DEPL', NOM_CMP='DY', NUME_ORDRE=(0, 2, 4), OPERATION='EXTRACTION'))\n\
         T1 = POST_RELEVE_T(ACTION=_F(INTITULE='T', GROUP_NO='TOP', RESULTAT=R, NOM_CHAM='DEPL', NOM_CMP='DY', LIST_ORDRE=L1, OPERATION='EXTRACTION'))\n\
         T2 = POST_RELEVE_T(ACTION=_F(INTITULE='T', GROUP_NO='TOP', RESULTAT=R, NOM_CHAM='DEPL', NOM_CMP='DY', LIST_ORDRE=L2, OPERATION='EXTRACTION'))\n\
         TR = POST_RELEVE_T(ACTION=_F(INTITULE='R', GROUP_NO='NESCL', RESULTAT=R, NOM_CHAM='REAC_NODA', NOM_CMP='DY', LIST_ORDRE=L3, OPERATION='EXTRACTION'))\n\
         F = RECU_FONCTION(RESULTAT=R, NOM_CHAM='DEPL', NOM_CMP='DY', GROUP_NO='TOP', LIST_ORDRE=L2)\n\
         IMPR_TABLE(TABLE=TN, FORMAT_R='E24.16')\n\
         IMPR_TABLE(TABLE=T1, FORMAT_R='E24.16')\n\
         IMPR_TABLE(TABLE=T2, FORMAT_R='E24.16')\n\
         IMPR_TABLE(TABLE=TR, FORMAT_R='E24.16')\n\
         IMPR_FONCTION(FORMAT='TABLEAU', COURBE=_F(FONCTION=F), UNITE=8)\n";
    let (code, resu, mess) = run("listenti_ok", post);
    assert_eq!(code, 0, "{mess}\n{resu}");
    let rows = common::printed_table(&resu, "TN");
    assert_eq!(rows.len(), 3 * 5, "5 TOP nodes at 3 indices:\n{resu}");
    for t in ["T1", "T2"] {
        assert_eq!(common::printed_table(&resu, t), rows, "{t} against TN");
    }
    let mut orders = column(&resu, "T1", "NUME_ORDRE");
    orders.dedup();
    assert_eq!(orders, ["0", "2", "4"]);
    // REAC_NODA of the held bottom balances the pressure on the top,
    // 10 t over a width 4 (t = 0.5, 1 at indices 2, 4).
    let rows = common::printed_table(&resu, "TR");
    let sum_at = |n: &str| -> f64 {
        rows.iter()
            .filter(|r| r["NUME_ORDRE"] == n)
            .map(|r| r["DY"].parse::<f64>().unwrap())
            .sum()
    };
    assert_eq!(rows.len(), 3 * 5, "5 bottom nodes at 3 indices:\n{resu}");
    for (n, t) in [("0", 0.0), ("2", 0.5), ("4", 1.0)] {
        let s = sum_at(n);
        assert!(
            (s - 40.0 * t).abs() <= 1e-9 * 40.0,
            "sum RY {s} at t = {t}\n{resu}"
        );
    }
}

#[test]
fn bad_lists_are_located_errors() {
    for (tag, post, needles) in [
        (
            "listenti_vale",
            "L = DEFI_LIST_ENTI(VALE=(1, 3, 3))",
            &["DEFI_LIST_ENTI", "VALE", "strictly increasing", "value 3 (3) follows 3"][..],
        ),
        (
            "listenti_pas",
            "L = DEFI_LIST_ENTI(DEBUT=1, INTERVALLE=_F(JUSQU_A=8, PAS=2))",
            &["INTERVALLE", "PAS = 2 does not divide the interval [1, 8]"][..],
        ),
        (
            "listenti_nombre",
            "L = DEFI_LIST_ENTI(DEBUT=0, INTERVALLE=(_F(JUSQU_A=4, NOMBRE=2), _F(JUSQU_A=9, NOMBRE=2)))",
            &["NOMBRE = 2 does not divide the interval [4, 9] of INTERVALLE occurrence 2"][..],
        ),
        (
            "listenti_back",
            "L = DEFI_LIST_ENTI(DEBUT=5, INTERVALLE=_F(JUSQU_A=5, PAS=1))",
            &["JUSQU_A = 5 must be greater than the previous value 5"][..],
        ),
        (
            "listenti_extr",
            "L = DEFI_LIST_ENTI(OPERATION='NUME_ORDRE', RESULTAT=R, PARAMETRE='INST', INTERV_R=(0., 1.))",
            &["not implemented yet: DEFI_LIST_ENTI/OPERATION"][..],
        ),
        (
            "listenti_absent",
            "L = DEFI_LIST_ENTI(VALE=(1, 7))\n\
             T = POST_RELEVE_T(ACTION=_F(INTITULE='T', GROUP_NO='TOP', RESULTAT=R, NOM_CHAM='DEPL', NOM_CMP='DY', LIST_ORDRE=L, OPERATION='EXTRACTION'))",
            &["POST_RELEVE_T", "LIST_ORDRE", "7"][..],
        ),
    ] {
        let (code, resu, mess) = run(tag, post);
        assert_ne!(code, 0, "{tag}: ran\n{resu}");
        for n in needles {
            assert!(mess.contains(n), "{tag}: '{n}' missing\n{mess}");
        }
        assert!(!mess.contains("panicked"), "{tag}\n{mess}");
    }
}
