//! CALC_CHAMP: derived fields of a result (stresses at nodes, nodal forces...).

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let mut kws = vec![
        concept("RESULTAT", &[C::EvolNoli])
            .required()
            .doc("result to enrich (also the reused concept)")
            .kw(),
        concept("MODELE", &[C::Modele])
            .doc("absent: the result's")
            .kw(),
        concept("CHAM_MATER", &[C::ChamMater]).kw(),
        fact(
            "EXCIT",
            vec![
                concept("CHARGE", &[C::CharMeca]).required().kw(),
                concept("FONC_MULT", &[C::Fonction]).kw(),
                text("TYPE_CHARGE")
                    .into(&["FIXE_CSTE", "SUIV", "DIDI"])
                    .default(t("FIXE_CSTE"))
                    .kw(),
            ],
        )
        .many()
        .doc("loads for REAC_NODA; absent: those stored in the result")
        .kw(),
        text("TOUT_ORDRE").into(&["OUI"]).kw(),
        int("NUME_ORDRE").many().kw(),
        real("INST").many().kw(),
        concept("LIST_INST", &[C::Listr8]).kw(),
    ];
    kws.extend(critere_precision(1e-6));
    kws.extend([
        tout(),
        group_ma(),
        maille(),
        text("CONTRAINTE")
            .many()
            .into(&["SIEF_ELNO", "SIGM_ELNO", "SIEF_NOEU", "SIGM_NOEU", "SIGM_ELGA"])
            .doc("stress fields")
            .kw(),
        text("DEFORMATION")
            .many()
            .into(&["EPSI_ELGA", "EPSI_ELNO", "EPSI_NOEU", "EPSL_ELGA", "EPSL_ELNO", "EPSL_NOEU"])
            .doc("strain fields")
            .kw(),
        text("CRITERES")
            .many()
            .into(&["SIEQ_ELGA", "SIEQ_ELNO", "SIEQ_NOEU", "EPEQ_ELGA", "EPEQ_ELNO", "EPEQ_NOEU"])
            .doc("equivalent stresses and strains")
            .kw(),
        text("VARI_INTERNE")
            .many()
            .into(&["VARI_ELNO", "VARI_NOEU"])
            .doc("internal variables at nodes")
            .kw(),
        text("ENERGIE")
            .many()
            .into(&["ENEL_ELGA", "ENEL_ELNO", "ENEL_NOEU", "ETOT_ELGA", "ETOT_ELNO", "ETOT_NOEU"])
            .kw(),
        text("FORCE")
            .many()
            .into(&["FORC_NODA", "REAC_NODA"])
            .doc("FORC_NODA: internal nodal forces; REAC_NODA: minus applied loads, plus M.a, i.e. support and contact reactions")
            .kw(),
        info(),
        titre(),
    ]);
    let spec = command("CALC_CHAMP", Produces::Concept(C::EvolNoli), kws)
        .reentrant(Reentrant::Optional("RESULTAT"))
        .rules(vec![
            exclus(&["TOUT_ORDRE", "NUME_ORDRE", "INST", "LIST_INST"]),
            exclus(&["TOUT", "GROUP_MA", "MAILLE"]),
        ])
        .doc("Adds derived fields to a result, at all stored indices unless restricted.");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}
