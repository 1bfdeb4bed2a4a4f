//! DETRUIRE: removes concepts from the study.
//!
//! Why: a study that loops over cases, or frees a large result before
//! the next computation, destroys a concept to define the name again.
//! code_aster's current catalogue takes `NOM=(...)`; its older one
//! `CONCEPT=_F(NOM=(...))` (and `OBJET` for JEVEUX objects, which aster
//! does not have). The declaration is marked [`CommandSpec::destroys`]:
//! the checker forgets the names when it meets the command, so that a
//! later use is an error located there, before anything runs, and a new
//! definition of the name is an ordinary one.

use super::blocks::*;
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;
use crate::study::Study;

pub fn def() -> CommandDef {
    let any = || {
        concept("NOM", C::ALL)
            .many()
            .doc("the concepts to destroy, of any type")
    };
    let spec = command(
        "DETRUIRE",
        Produces::Nothing,
        vec![
            any().kw(),
            fact("CONCEPT", vec![any().required().kw()])
                .many()
                .doc("older form of NOM")
                .kw(),
            fact(
                "OBJET",
                vec![
                    text("CLASSE").into(&["G", "V", "L"]).default(t("G")).kw(),
                    text("CHAINE").required().many().kw(),
                    int("POSITION").many().kw(),
                ],
            )
            .many()
            .doc("JEVEUX objects by name: not implemented (aster has no JEVEUX)")
            .kw(),
            oui_non("ALARME", "OUI").kw(),
            int("INFO").into_ints(&[1, 2]).default(i(1)).kw(),
        ],
    )
    .rules(vec![un_parmi(&["NOM", "CONCEPT", "OBJET"])])
    .destroys()
    .doc("Destroys concepts: their names can be defined again, and a use before that is an error.");
    CommandDef { spec, exec }
}

fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    if args.has("OBJET") {
        return Err(args.not_implemented("OBJET", "aster has no JEVEUX objects"));
    }
    let mut names: Vec<String> = args.concepts("NOM").iter().map(|s| s.to_string()).collect();
    for occ in args.facts("CONCEPT") {
        names.extend(occ.concepts("NOM").iter().map(|s| s.to_string()));
    }
    for name in names {
        if study.concepts.remove(&name).is_some() {
            study.log(format!("DETRUIRE: the concept {name} is destroyed"));
        }
    }
    Ok(None)
}
