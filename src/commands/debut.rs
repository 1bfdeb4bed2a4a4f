//! DEBUT: opens a study.

use super::blocks::*;
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::study::Study;

pub fn def() -> CommandDef {
    let spec = command(
        "DEBUT",
        Produces::Nothing,
        vec![
            fact(
                "CODE",
                vec![text("NIV_PUB_WEB")
                    .into(&["INTERNET", "INTRANET"])
                    .doc("'INTERNET' turns on test mode")
                    .kw()],
            )
            .doc("test-mode settings of code_aster's own test cases")
            .kw(),
            fact(
                "DEBUG",
                vec![
                    text("JXVERI").into(&["OUI", "NON"]).kw(),
                    text("SDVERI")
                        .into(&["OUI", "NON"])
                        .doc("check data structures after each command")
                        .kw(),
                    text("JEVEUX").into(&["OUI", "NON"]).kw(),
                    text("HIST_ETAPE").into(&["OUI", "NON"]).kw(),
                ],
            )
            .doc("debugging checks")
            .kw(),
            fact(
                "ERREUR",
                vec![
                    text("ERREUR_F")
                        .into(&["ABORT", "EXCEPTION"])
                        .doc("behaviour on a fatal error")
                        .kw(),
                    text("ALARME").into(&["ALARME", "EXCEPTION"]).kw(),
                ],
            )
            .kw(),
            text("IGNORE_ALARM")
                .many()
                .doc("alarm ids not to print")
                .kw(),
            text("LANG").doc("language of the messages").kw(),
            info(),
        ],
    )
    .doc("Opens a study; must be the first command of a command file.");
    CommandDef { spec, exec }
}

/// Nothing to do: the runner has already opened the study.
fn exec(_study: &mut Study, _args: &Args, _result: Option<&str>) -> ExecResult {
    Ok(None)
}
