//! DEFI_FICHIER: ties a logical unit to a named file, so that IMPR_TABLE,
//! IMPR_FONCTION, IMPR_RESU... (UNITE=N) write there instead of `fort.N`.
//!
//! code_aster's `op0026`/`ulopen`: ACTION='ASSOCIER' opens FICHIER on
//! UNITE (ACCES 'NEW' starts it empty, 'APPEND' keeps what it holds,
//! 'OLD' needs it to exist), 'LIBERER' closes the unit (here: its text is
//! written to the file at once, and a later write to the unit starts
//! again as `fort.N` unless it is associated again), 'RESERVER' keeps a
//! unit from being handed out (nothing to do here: aster hands out no
//! unit). A relative FICHIER is taken from the study's output directory,
//! where code_aster's working directory holds its `REPE_OUT`.

use super::blocks::*;
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::study::Study;

pub fn def() -> CommandDef {
    let spec = command(
        "DEFI_FICHIER",
        Produces::Nothing,
        vec![
            text("ACTION")
                .into(&["ASSOCIER", "LIBERER", "RESERVER"])
                .default(t("ASSOCIER"))
                .doc("'ASSOCIER' ties UNITE to FICHIER, 'LIBERER' closes the unit, 'RESERVER' keeps it")
                .kw(),
            int("UNITE")
                .doc("the logical unit (in aster it must be given: a unit chosen by the command and returned is not implemented)")
                .kw(),
            text("FICHIER")
                .doc("the file's path; relative paths start at the study's output directory")
                .kw(),
            text("TYPE")
                .into(&["ASCII", "BINARY", "LIBRE"])
                .default(t("ASCII"))
                .doc("the file's format (aster's units hold text)")
                .kw(),
            text("ACCES")
                .into(&["NEW", "APPEND", "OLD"])
                .default(t("NEW"))
                .doc("'NEW' starts the file empty, 'APPEND' writes after what it holds, 'OLD' needs it to exist")
                .kw(),
            info(),
        ],
    )
    .doc("Ties a logical unit to a named file (or frees it): later writes to UNITE go to FICHIER.");
    CommandDef { spec, exec }
}

fn exec(study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    let action = args.text("ACTION").unwrap_or("ASSOCIER");
    let Some(unit) = args.int("UNITE") else {
        return Err(args.not_implemented(
            "UNITE",
            "a unit chosen by DEFI_FICHIER and returned as its value: give UNITE",
        ));
    };
    if unit == 6 || unit == 8 {
        return Err(args.error(
            "UNITE",
            format!(
                "unit {unit} is the {} file of the study, which DEFI_FICHIER cannot move",
                if unit == 6 {
                    "message (.mess)"
                } else {
                    "result (.resu)"
                }
            ),
        ));
    }
    match action {
        "ASSOCIER" => {
            let Some(file) = args.text("FICHIER") else {
                return Err(args.error("FICHIER", "ACTION='ASSOCIER' needs FICHIER"));
            };
            if args.text("TYPE") == Some("BINARY") {
                return Err(args.not_implemented(
                    "TYPE",
                    "binary units (the commands of aster write text, and MED files go through IMPR_RESU's UNITE mapped by the .export)",
                ));
            }
            let path = if std::path::Path::new(file).is_absolute() {
                std::path::PathBuf::from(file)
            } else {
                study.out_dir.join(file)
            };
            if let Some(dir) = path.parent() {
                std::fs::create_dir_all(dir).map_err(|e| {
                    args.error(
                        "FICHIER",
                        format!("cannot create the directory '{}': {e}", dir.display()),
                    )
                })?;
            }
            flush(study, args, unit)?;
            let held = match args.text("ACCES").unwrap_or("NEW") {
                "NEW" => String::new(),
                access => match std::fs::read_to_string(&path) {
                    Ok(t) => t,
                    Err(_) if access == "APPEND" => String::new(),
                    Err(e) => {
                        return Err(args.error(
                            "ACCES",
                            format!(
                                "ACCES='OLD' needs the file '{}' to exist: {e}",
                                path.display()
                            ),
                        ))
                    }
                },
            };
            study.log(format!(
                "    unit {unit} -> '{}' ({})",
                path.display(),
                args.text("ACCES").unwrap_or("NEW")
            ));
            study.units.map.insert(unit, path);
            study.unit_text.insert(unit, held);
        }
        "LIBERER" => {
            flush(study, args, unit)?;
            study.units.map.remove(&unit);
            study.log(format!("    unit {unit} freed"));
        }
        _ => study.log(format!("    unit {unit} reserved")),
    }
    Ok(None)
}

/// Writes what the unit holds to its file now and empties it, as closing
/// a unit does in code_aster.
fn flush(study: &mut Study, args: &Args, unit: i64) -> Result<(), crate::diag::Diagnostic> {
    if let Some(text) = study.unit_text.remove(&unit) {
        let path = study.unit_path(unit);
        std::fs::write(&path, text).map_err(|e| {
            args.error(
                "UNITE",
                format!("cannot write unit {unit} to '{}': {e}", path.display()),
            )
        })?;
    }
    Ok(())
}
