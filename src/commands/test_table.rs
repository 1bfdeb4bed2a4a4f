//! TEST_TABLE: checks one cell (or an aggregate) of a table.

use super::blocks::*;
use super::{not_implemented, CommandDef};
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

pub fn def() -> CommandDef {
    let (refe_kws, refe_rules) = c_test_reference(false, true);
    let mut kws = vec![
        concept("TABLE", &[C::Table]).required().kw(),
        c_filtre(),
        text("NOM_PARA")
            .required()
            .doc("column tested; without TYPE_TEST exactly one row must remain after filtering")
            .kw(),
        info(),
    ];
    kws.extend(refe_kws);
    let spec = command("TEST_TABLE", Produces::Nothing, kws)
        .rules(refe_rules)
        .doc("Tests a value of a table against VALE_CALC (non-regression) and VALE_REFE.");
    CommandDef {
        spec,
        exec: not_implemented,
    }
}
