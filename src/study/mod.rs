//! The execution context of a study, below the commands that act on it.
//!
//! A study owns the concept table, the logical units (unit 20 -> mesh
//! file...), the message log (.mess) and the result file (.resu, unit 8),
//! and the count of OK/NOOK checks that decides the exit code.

use std::collections::BTreeMap;
use std::path::PathBuf;

use crate::concepts::Concepts;
pub use crate::post::test_report::TestCounts;

/// Logical units: code_aster's numbered files (fort.N).
#[derive(Debug, Clone, Default)]
pub struct Units {
    pub map: BTreeMap<i64, PathBuf>,
}

impl Units {
    pub fn path(&self, unit: i64) -> Option<&PathBuf> {
        self.map.get(&unit)
    }
}

/// The state of a running study.
#[derive(Debug, Default)]
pub struct Study {
    pub concepts: Concepts,
    pub units: Units,
    /// Directory where output files (.mess, .resu, unit files) are written.
    pub out_dir: PathBuf,
    /// Base name of the study (`sdnv103b` for `sdnv103b.comm`).
    pub stem: String,
    /// Text of the message file, flushed at the end and on error.
    pub mess: String,
    /// Text of the result file (unit 8).
    pub resu: String,
    /// Text written to other logical units (IMPR_TABLE UNITE=..., etc.).
    pub unit_text: BTreeMap<i64, String>,
    pub tests: TestCounts,
    /// Echo progress lines to the terminal.
    pub verbose: bool,
    /// DEBUT(ERREUR=_F(ALARME='EXCEPTION')): alarms are errors, except
    /// those whose id is listed (IGNORE_ALARM).
    pub alarm_exception: Option<Vec<String>>,
    /// The first alarm logged under `alarm_exception`, which the runner
    /// turns into the error of the command that raised it.
    pub raised_alarm: Option<String>,
    /// What each IMPR_RESU(FORMAT='MED') wrote, per logical unit: a later
    /// IMPR_RESU on the same unit adds its fields to these and writes the
    /// file again, as code_aster adds them to the open file.
    pub med_files: BTreeMap<i64, MedWritten>,
}

/// The content of a MED file written by IMPR_RESU.
#[derive(Debug, Clone)]
pub struct MedWritten {
    pub mesh: crate::mesh::Mesh,
    pub nodal: Vec<crate::medio::NodalField>,
    pub cells: Vec<crate::medio::ElemField>,
}

impl Study {
    /// Appends a line to the message file (and echoes it when verbose).
    pub fn log(&mut self, line: impl AsRef<str>) {
        self.write_line(line.as_ref(), true);
    }

    /// An alarm about what aster itself does not do yet, which code_aster
    /// would not raise: logged like the others, but never an error under
    /// DEBUT(ERREUR=_F(ALARME='EXCEPTION')), so a code_aster test file does
    /// not fail on aster's own limits.
    pub fn log_limitation(&mut self, line: impl AsRef<str>) {
        self.write_line(line.as_ref(), false);
    }

    fn write_line(&mut self, line: &str, alarm_check: bool) {
        if self.verbose {
            eprintln!("{line}");
        }
        self.mess.push_str(line);
        self.mess.push('\n');
        // Every alarm goes through here as a line `<A> <COMMAND> [<ID>] text`,
        // so this one place sees them all.
        if let (true, Some(ignored), None) =
            (alarm_check, &self.alarm_exception, &self.raised_alarm)
        {
            if let Some(rest) = line.strip_prefix("<A> ") {
                let id = rest
                    .split_once("> <")
                    .and_then(|(_, r)| r.split_once('>'))
                    .map(|(id, _)| id);
                if !id.is_some_and(|id| ignored.iter().any(|i| i == id)) {
                    self.raised_alarm = Some(line.to_string());
                }
            }
        }
    }

    /// What a `print(...)` of the command file writes: its text as is
    /// (Python's `end` included), in the .mess, which is code_aster's
    /// standard output.
    pub fn print(&mut self, text: &str) {
        if self.verbose {
            eprint!("{text}");
        }
        self.mess.push_str(text);
    }

    /// Appends text to a logical unit; unit 8 is the .resu file.
    pub fn write_unit(&mut self, unit: i64, text: &str) {
        if unit == 8 {
            self.resu.push_str(text);
        } else {
            self.unit_text.entry(unit).or_default().push_str(text);
        }
    }

    /// The path of a logical unit: mapped by the .export or `--unit`, else
    /// `fort.N` in the output directory, as code_aster names them.
    pub fn unit_path(&self, unit: i64) -> PathBuf {
        self.units
            .path(unit)
            .cloned()
            .unwrap_or_else(|| self.out_dir.join(format!("fort.{unit}")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn alarms_raise_under_alarme_exception_unless_ignored() {
        let mut s = Study {
            alarm_exception: Some(vec!["MODELE1_3".into()]),
            ..Study::default()
        };
        s.log("<A> <AFFE_MODELE> <MODELE1_3> the mesh is not in z = 0");
        s.log("a line that is not an alarm");
        assert_eq!(s.raised_alarm, None);
        s.log("<A> <DEFI_GROUP> the cell group G to delete does not exist");
        s.log("<A> <AFFE_MODELE> <MODELE1_7> second");
        assert_eq!(
            s.raised_alarm.as_deref(),
            Some("<A> <DEFI_GROUP> the cell group G to delete does not exist")
        );
        // aster's own limits never raise.
        let mut s = Study {
            alarm_exception: Some(Vec::new()),
            ..Study::default()
        };
        s.log_limitation("<A> <IMPR_RESU> the MED writer cannot store Gauss points yet");
        assert_eq!(s.raised_alarm, None);
        assert!(s.mess.contains("cannot store Gauss points"));
        // Without ALARME='EXCEPTION' nothing is raised.
        let mut s = Study::default();
        s.log("<A> <DEFI_GROUP> the cell group G to delete does not exist");
        assert_eq!(s.raised_alarm, None);
    }
}
