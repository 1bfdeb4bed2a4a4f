//! FIN: closes a study.

use super::blocks::*;
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::study::Study;

pub fn def() -> CommandDef {
    let spec = command(
        "FIN",
        Produces::Nothing,
        vec![
            oui_non("FORMAT_HDF", "NON")
                .doc("save the database in HDF format")
                .kw(),
            oui_non("RETASSAGE", "NON").kw(),
            oui_non("INFO_RESU", "OUI")
                .doc("print the contents of the results at the end")
                .kw(),
            oui_non("PROC0", "OUI").kw(),
        ],
    )
    .doc("Closes the study; the runner then flushes the message and result files.");
    CommandDef { spec, exec }
}

/// Ends the .resu with the count of TEST_RESU / TEST_TABLE lines (an
/// aster extension, docs/testing-report.md §3) when the study tested
/// something; the runner then flushes the files.
fn exec(study: &mut Study, _args: &Args, _result: Option<&str>) -> ExecResult {
    let t = study.tests;
    if t.ok + t.nook + t.skip > 0 {
        let text = crate::post::test_report::summary(&t);
        study.write_unit(8, &text);
    }
    Ok(None)
}
