//! The study runner: executes a checked command file in order.
//!
//! A study owns the concept table, the logical units (unit 20 -> mesh
//! file...), the message log (.mess) and the result file (.resu, unit 8),
//! and the count of OK/NOOK checks that decides the exit code.

use std::collections::BTreeMap;
use std::path::PathBuf;

use crate::bench::{self, Phase};
use crate::catalog::checker::CheckedProgram;
use crate::commands::CommandDef;
use crate::concepts::{Concept, ConceptData, Concepts};
use crate::diag::Diagnostic;

pub mod driver;
pub mod export;

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

/// Counts of the test report.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct TestCounts {
    pub ok: usize,
    pub nook: usize,
    pub skip: usize,
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
}

impl Study {
    /// Appends a line to the message file (and echoes it when verbose).
    pub fn log(&mut self, line: impl AsRef<str>) {
        let line = line.as_ref();
        if self.verbose {
            eprintln!("{line}");
        }
        self.mess.push_str(line);
        self.mess.push('\n');
    }

    /// Appends text to a logical unit; unit 8 is the .resu file.
    pub fn write_unit(&mut self, unit: i64, text: &str) {
        if unit == 8 {
            self.resu.push_str(text);
        } else {
            self.unit_text.entry(unit).or_default().push_str(text);
        }
    }
}

impl Study {
    /// Runs the commands in order. Stops at the first error, which is
    /// returned; everything produced before it stays in the study (and the
    /// caller writes the .mess/.resu files in both cases).
    pub fn execute(
        &mut self,
        program: &CheckedProgram,
        registry: &[CommandDef],
        source: &crate::diag::Source,
    ) -> Result<(), Diagnostic> {
        for c in &program.commands {
            let (line, _) = source.line_col(c.span.start);
            let def = &registry[c.def];
            let target = c.result.as_ref().map(|t| t.name.as_str());
            self.log(format!(
                "# ---- {}{} (line {line})",
                target.map(|t| format!("{t} = ")).unwrap_or_default(),
                c.name,
            ));
            let started = std::time::Instant::now();
            let _output = bench::span_if(c.name.starts_with("IMPR_"), Phase::Output);
            let data = (def.exec)(self, &c.args, target)?;
            self.log(format!(
                "#      {} done in {:.3} s",
                c.name,
                started.elapsed().as_secs_f64()
            ));
            if let (Some(t), Some(ty)) = (&c.result, c.produces) {
                self.concepts.insert(Concept {
                    name: t.name.clone(),
                    ty,
                    defined_at: t.span,
                    command: c.name.clone(),
                    data: data.unwrap_or(ConceptData::Unevaluated),
                });
            }
            if c.name == "FIN" {
                break;
            }
        }
        Ok(())
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
