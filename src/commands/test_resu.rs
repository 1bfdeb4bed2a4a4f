//! TEST_RESU: checks values of results against recorded and reference values.

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let (refe_kws, refe_rules) = c_test_reference(true, false);
    let mut resu = vec![
        concept("RESULTAT", &[C::EvolNoli]).required().kw(),
        int("NUME_ORDRE").doc("stored index tested").kw(),
        real("INST")
            .doc("instant tested, found with TOLE_MACHINE(2) and CRITERE(2)")
            .kw(),
        text("PARA")
            .doc("test a result parameter instead of a field")
            .kw(),
        text("NOM_CHAM").into(NOM_CHAM_RESU).kw(),
        text("NOM_CMP").kw(),
        text("NOM_VARI").doc("internal variable by name").kw(),
        text("GROUP_MA").kw(),
        text("MAILLE").hidden().kw(),
        text("NOEUD").many().hidden().kw(),
        text("GROUP_NO")
            .many()
            .doc("must hold exactly one node")
            .kw(),
        int("POINT").doc("Gauss point of an ELGA field").kw(),
        int("SOUS_POINT").kw(),
    ];
    resu.extend(refe_kws);
    let mut rules = vec![
        un_parmi(&["NUME_ORDRE", "INST"]),
        un_parmi(&["NOM_CHAM", "PARA"]),
        present_absent(
            "PARA",
            &[
                "MAILLE", "GROUP_MA", "NOEUD", "GROUP_NO", "POINT", "NOM_CMP", "NOM_VARI",
            ],
        ),
        exclus(&["NOEUD", "GROUP_NO", "POINT"]),
        exclus(&["MAILLE", "GROUP_MA"]),
        exclus(&["NOM_CMP", "NOM_VARI"]),
    ];
    rules.extend(refe_rules);

    let (refe_kws, refe_rules) = c_test_reference(false, false);
    let mut cham_no = vec![
        concept("CHAM_GD", &[C::ChamNo]).required().kw(),
        text("NOEUD").hidden().kw(),
        text("GROUP_NO").doc("must hold exactly one node").kw(),
        text("NOM_CMP").kw(),
    ];
    cham_no.extend(refe_kws);
    let mut cham_no_rules = vec![
        exclus(&["NOEUD", "GROUP_NO"]),
        present_present("NOEUD", &["NOM_CMP"]),
        present_present("GROUP_NO", &["NOM_CMP"]),
    ];
    cham_no_rules.extend(refe_rules);

    let spec = command(
        "TEST_RESU",
        Produces::Nothing,
        vec![
            fact("RESU", resu)
                .many()
                .rules(rules)
                .doc("one value of a result field at one node, instant and component")
                .kw(),
            fact("CHAM_NO", cham_no)
                .many()
                .rules(cham_no_rules)
                .doc("one value of a nodal field")
                .kw(),
        ],
    )
    .rules(vec![au_moins_un(&["RESU", "CHAM_NO"])])
    .doc("Tests computed values: non-regression against VALE_CALC, and against VALE_REFE when REFERENCE is given; prints OK/NOOK/SKIP lines.");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}
