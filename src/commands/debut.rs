//! DEBUT: opens a study.

use super::blocks::*;
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::eval::{PyVal, SpVal};
use crate::catalog::schema::*;
use crate::diag::Diagnostic;
use crate::lang::ast::Ident;
use crate::study::Study;

pub fn def() -> CommandDef {
    let spec = command(
        "DEBUT",
        Produces::Nothing,
        vec![
            text("CODE")
                .into(&["OUI", "NON"])
                .doc("'OUI' is code_aster's test mode (no effect in aster); the form of code_aster 15 and before, CODE=_F(NIV_PUB_WEB='INTERNET' or 'INTRANET'), is read as 'OUI'")
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
                        .doc("behaviour on a fatal error (aster always stops the study with a located message)")
                        .kw(),
                    text("ALARME")
                        .into(&["ALARME", "EXCEPTION"])
                        .doc("'EXCEPTION': an alarm (<A>) not listed in IGNORE_ALARM is an error that stops the study, at the end of the command that raised it (not the alarms about aster's own limits)")
                        .kw(),
                ],
            )
            .doc("behaviour on errors and alarms")
            .kw(),
            text("IGNORE_ALARM")
                .many()
                .doc("alarm ids not to turn into errors under ERREUR=_F(ALARME='EXCEPTION')")
                .kw(),
            text("LANG").doc("language of the messages").kw(),
            text("PAR_LOT")
                .into(&["OUI", "NON"])
                .doc("code_aster 14 and before: 'NON' ran the file's Python between the commands, so that it could read their results; accepted and without effect: aster evaluates the Python first, as with 'OUI', and the .mess says so for 'NON'")
                .kw(),
            info(),
        ],
    )
    .compat(compat_code)
    .doc("Opens a study; must be the first command of a command file.");
    CommandDef { spec, exec }
}

/// code_aster 16 made CODE a text ('OUI'); its compat_syntax reads the
/// older factor form `CODE=_F(NIV_PUB_WEB=...)` as 'OUI'. The older form
/// is still checked as its catalogue declared it, so a typo in it is not
/// silently accepted.
// The type of every compat hook (which may add or drop keywords).
#[allow(clippy::ptr_arg)]
fn compat_code(given: &mut Vec<(Ident, SpVal)>) -> Vec<Diagnostic> {
    let mut errors = Vec::new();
    let Some((_, value)) = given.iter_mut().find(|(k, _)| k.name == "CODE") else {
        return errors;
    };
    let PyVal::Fact(_, items) = &value.v else {
        return errors;
    };
    let err = |msg: String, at| {
        Diagnostic::error(msg)
            .at(at)
            .in_command("DEBUT")
            .keyword("CODE")
            .note("code_aster 16 and later write CODE='OUI'; the older CODE=_F(NIV_PUB_WEB='INTERNET') is read the same")
    };
    let mut niv = false;
    for (k, v) in items {
        if k.name != "NIV_PUB_WEB" {
            errors.push(err(
                format!("unknown keyword {} in CODE=_F(...)", k.name),
                k.span,
            ));
            continue;
        }
        niv = true;
        match &v.v {
            PyVal::Str(s) if s == "INTERNET" || s == "INTRANET" => {}
            PyVal::Poison => {}
            other => errors.push(err(
                format!(
                    "CODE/NIV_PUB_WEB takes 'INTERNET' or 'INTRANET', not {}",
                    other.describe()
                ),
                v.span,
            )),
        }
    }
    if !niv {
        errors.push(err(
            "CODE=_F(...) needs NIV_PUB_WEB='INTERNET' or 'INTRANET'".into(),
            value.span,
        ));
    }
    if errors.is_empty() {
        value.v = PyVal::Str("OUI".into());
    } else {
        // Reported here: the checker must not report the factor again.
        value.v = PyVal::Poison;
    }
    errors
}

/// Records how alarms are treated; the runner opened the study already.
fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    if args.text("PAR_LOT") == Some("NON") {
        study.log("  PAR_LOT='NON' (code_aster 14 and before) has no effect: aster evaluates the file's Python before running any command, so the Python cannot read a command's result (EXTR_TABLE, getValues...), as under PAR_LOT='OUI'");
    }
    let exception = args
        .fact("ERREUR")
        .and_then(|e| e.text("ALARME"))
        .is_some_and(|a| a == "EXCEPTION");
    if exception {
        study.alarm_exception = Some(
            args.texts("IGNORE_ALARM")
                .into_iter()
                .map(str::to_string)
                .collect(),
        );
    }
    Ok(None)
}
