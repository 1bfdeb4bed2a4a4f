//! What `aster check` and `aster run` do, as library functions so that
//! tests drive them without spawning the binary.
//!
//! Exit codes: 0 success, 1 a study error (syntax, check, execution, or
//! any NOOK test), 2 a usage error (unreadable file, bad option), 128 + the
//! signal's number for a run stopped by SIGINT (130) or SIGTERM (143).

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::catalog::checker::{check_program, CheckedProgram};
use crate::commands::{self, CommandDef};
use crate::diag::{Diagnostic, Severity, Source};
use crate::lang::parser::parse;
use crate::run::export::{parse_export, ExportFile};
use crate::study::Study;

pub const EXIT_OK: i32 = 0;
pub const EXIT_STUDY: i32 = 1;
pub const EXIT_USAGE: i32 = 2;

/// Parses and checks a source. Errors are rendered into `messages`.
pub fn parse_and_check(
    src: &Source,
    registry: &[CommandDef],
    messages: &mut String,
) -> Option<CheckedProgram> {
    let program = match parse(src) {
        Ok(p) => p,
        Err(d) => {
            messages.push_str(&d.render(Some(src)));
            return None;
        }
    };
    match check_program(&program, registry) {
        Ok(c) => {
            for w in &c.warnings {
                messages.push_str(&w.render(Some(src)));
            }
            Some(c)
        }
        Err(ds) => {
            let nerr = ds.iter().filter(|d| d.severity == Severity::Error).count();
            for d in &ds {
                messages.push_str(&d.render(Some(src)));
                messages.push('\n');
            }
            messages.push_str(&format!(
                "{}: {nerr} error{} found, nothing was run\n",
                src.name,
                if nerr == 1 { "" } else { "s" }
            ));
            None
        }
    }
}

/// `aster check FILE`: parse and check without executing.
pub fn check_file(path: &Path, out: &mut dyn Write) -> i32 {
    let src = match read_source(path) {
        Ok(s) => s,
        Err((code, d)) => {
            let _ = write!(out, "{}", d.render(None));
            return code;
        }
    };
    let registry = commands::all();
    let mut messages = String::new();
    let checked = parse_and_check(&src, &registry, &mut messages);
    let _ = write!(out, "{messages}");
    match checked {
        Some(c) => {
            let _ = writeln!(
                out,
                "{}: OK, {} commands checked",
                src.name,
                c.commands.len()
            );
            EXIT_OK
        }
        None => EXIT_STUDY,
    }
}

/// Reads a command file; a missing or unreadable file is a usage error,
/// a binary or non-UTF-8 one a study error.
fn read_source(path: &Path) -> Result<Source, (i32, Diagnostic)> {
    if !path.is_file() {
        return Err((
            EXIT_USAGE,
            Diagnostic::error(format!(
                "command file '{}' does not exist or is not a file",
                path.display()
            )),
        ));
    }
    Source::read(path).map_err(|d| (EXIT_STUDY, d))
}

/// Options of `aster run`.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    pub comm: PathBuf,
    /// `--unit N=PATH` mappings; they override the .export.
    pub units: Vec<(i64, PathBuf)>,
    /// An explicit .export file; by default `<study>.export` next to the study.
    pub export: Option<PathBuf>,
    /// Where .mess, .resu and unit files go; by default next to the study.
    pub out_dir: Option<PathBuf>,
    /// Echo the message log to the terminal.
    pub verbose: bool,
}

/// The `F` lines of the study's .export: `opts.export`, else
/// `<study>.export` next to the study if there is one (else none).
/// `aster run` and `aster bench` resolve units through this one function so
/// that a study benchmarks exactly as it runs. The error is the rendered
/// message (a usage error).
pub fn export_files(opts: &RunOptions) -> Result<Vec<ExportFile>, String> {
    let stem = opts
        .comm
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "study".into());
    let study_dir = opts.comm.parent().unwrap_or(Path::new(""));
    let export = opts
        .export
        .clone()
        .or_else(|| Some(study_dir.join(format!("{stem}.export"))).filter(|p| p.is_file()));
    let Some(e) = export else {
        return Ok(Vec::new());
    };
    let text = std::fs::read_to_string(&e)
        .map_err(|err| format!("error: cannot read export file '{}': {err}\n", e.display()))?;
    let base = e.parent().map(Path::to_path_buf).unwrap_or_default();
    parse_export(&text, &base, &e.display().to_string()).map_err(|d| d.render(None))
}

/// How a run ended, beyond its exit code: `aster bench` still measures a
/// study that ran to its end but whose checks failed (a study on another
/// mesh, or a code_aster file whose VALE_CALC are code_aster's), while a
/// study that stopped on an error has no complete timing to report.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RunOutcome {
    /// The exit code `aster run` returns.
    pub code: i32,
    /// Every command ran (the study reached its end without an error).
    pub completed: bool,
    /// Number of NOOK checks.
    pub nook: usize,
}

/// `aster run FILE`: check then execute; writes FILE.mess and FILE.resu.
pub fn run_file(opts: &RunOptions, out: &mut dyn Write) -> i32 {
    run_file_outcome(opts, out).code
}

/// [`run_file`], telling also whether the study ran to its end and how
/// many of its checks failed.
pub fn run_file_outcome(opts: &RunOptions, out: &mut dyn Write) -> RunOutcome {
    let failed = |code| RunOutcome {
        code,
        completed: false,
        nook: 0,
    };
    let src = match read_source(&opts.comm) {
        Ok(s) => s,
        Err((code, d)) => {
            let _ = write!(out, "{}", d.render(None));
            return failed(code);
        }
    };
    let stem = opts
        .comm
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "study".into());
    let study_dir = opts
        .comm
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let out_dir = opts.out_dir.clone().unwrap_or_else(|| study_dir.clone());
    if let Err(e) = std::fs::create_dir_all(&out_dir) {
        let _ = writeln!(
            out,
            "error: cannot create output directory '{}': {e}",
            out_dir.display()
        );
        return failed(EXIT_USAGE);
    }
    let mut study = Study {
        out_dir: out_dir.clone(),
        stem: stem.clone(),
        verbose: opts.verbose,
        ..Study::default()
    };

    // Logical units: the .export first, then --unit.
    match export_files(opts) {
        Ok(files) => {
            for f in files {
                study.units.map.insert(f.unit, f.path);
            }
        }
        Err(message) => {
            let _ = write!(out, "{message}");
            return failed(EXIT_USAGE);
        }
    }
    for (u, p) in &opts.units {
        study.units.map.insert(*u, p.clone());
    }

    let registry = commands::all();
    let mut messages = String::new();
    let checked = parse_and_check(&src, &registry, &mut messages);
    let _ = write!(out, "{messages}");
    study.mess.push_str(&messages);
    let mut completed = false;
    let code = match checked {
        None => {
            // Nothing ran: the .resu says why, as the .mess does.
            study.resu.push_str(&messages);
            EXIT_STUDY
        }
        Some(program) => {
            study.log(format!(
                "aster {} — study {}",
                env!("CARGO_PKG_VERSION"),
                src.name
            ));
            for (u, p) in &study.units.map.clone() {
                study.log(format!("unit {u:>3} -> {}", p.display()));
            }
            match crate::run::execute(&mut study, &program, &registry, &src) {
                Ok(()) => {
                    completed = true;
                    if study.tests.nook > 0 {
                        EXIT_STUDY
                    } else {
                        EXIT_OK
                    }
                }
                Err(d) => {
                    let r = d.render(Some(&src));
                    let _ = write!(out, "{r}");
                    study.mess.push_str(&r);
                    let signal = crate::interrupt::requested();
                    for line in save_results(&study, signal) {
                        let _ = writeln!(out, "{line}");
                        study.mess.push_str(&line);
                        study.mess.push('\n');
                    }
                    match signal {
                        Some(s) => {
                            let code = crate::interrupt::exit_code(s);
                            let line = format!(
                                "the run was stopped by {}; .mess and .resu hold what was done; exit code {code}",
                                crate::interrupt::name(s)
                            );
                            study.log(&line);
                            // The .resu says why it ends early (its tables
                            // and tests after the stop were not produced).
                            study.resu.push_str(&format!("\n{}\n{line}\n", d.message));
                            code
                        }
                        None => {
                            // As code_aster's .resu, which receives the
                            // fatal error too: a .resu that ends without
                            // it (or is empty) reads as a study that ran.
                            study.resu.push_str(&format!(
                                "\n{r}{}\n",
                                if r.ends_with('\n') { "" } else { "\n" }
                            ));
                            EXIT_STUDY
                        }
                    }
                }
            }
        }
    };
    if let Err(e) = write_outputs(&study) {
        let _ = writeln!(out, "error: {e}");
        return failed(EXIT_STUDY);
    }
    let t = study.tests;
    if t.ok + t.nook + t.skip > 0 {
        let _ = writeln!(out, "tests: {} OK, {} NOOK, {} SKIP", t.ok, t.nook, t.skip);
    }
    let _ = writeln!(
        out,
        "{}: {} (messages in {})",
        src.name,
        match crate::interrupt::requested() {
            _ if code == EXIT_OK => "done".to_string(),
            Some(s) if code == crate::interrupt::exit_code(s) =>
                format!("STOPPED by {}", crate::interrupt::name(s)),
            _ => "FAILED".to_string(),
        },
        out_dir.join(format!("{stem}.mess")).display()
    );
    RunOutcome {
        code,
        completed,
        nook: t.nook,
    }
}

/// After a failure or a stop by `signal`, writes every transient result
/// computed so far (its nodal fields, and its Gauss-point fields as cell
/// means as IMPR_RESU writes them, at every archived step) to
/// `<study>_<RESULT>.rmed`, so that nothing computed is lost (the stresses
/// and internal variables at the failure included); returns the lines to
/// report.
fn save_results(study: &Study, signal: Option<i32>) -> Vec<String> {
    let cause = match signal {
        Some(s) => format!("the stop by {}", crate::interrupt::name(s)),
        None => "the error".to_string(),
    };
    use crate::concepts::ConceptData;
    let mut lines = Vec::new();
    for c in study.concepts.iter() {
        let ConceptData::Result(res) = &c.data else {
            continue;
        };
        let Some(ConceptData::Mesh(mesh)) = study.concepts.data(&res.mesh) else {
            continue;
        };
        let mut fields: Vec<crate::medio::NodalField> = Vec::new();
        let mut cells: Vec<crate::medio::ElemField> = Vec::new();
        for step in &res.steps {
            let at = |values| crate::medio::FieldStep {
                numdt: step.nume_ordre as i32,
                time: step.inst,
                values,
            };
            for (name, f) in &step.nodal {
                let full = format!("{:_<8}{name}", c.name);
                let idx = match fields.iter().position(|x| x.name == full) {
                    Some(i) => i,
                    None => {
                        fields.push(crate::medio::NodalField {
                            name: full,
                            components: f.components.clone(),
                            steps: Vec::new(),
                        });
                        fields.len() - 1
                    }
                };
                fields[idx].steps.push(at(f.values.clone()));
            }
            for (name, f) in &step.gauss {
                // A field on another mesh or whose components changed
                // between steps has no place in one MED field: left out.
                if f.offsets.len() != mesh.ncells() + 1 {
                    continue;
                }
                let full = format!("{:_<8}{name}", c.name);
                let idx = match cells.iter().position(|x| x.name == full) {
                    Some(i) if cells[i].components == f.components => i,
                    Some(_) => continue,
                    None => {
                        cells.push(crate::medio::ElemField {
                            name: full,
                            components: f.components.clone(),
                            steps: Vec::new(),
                        });
                        cells.len() - 1
                    }
                };
                cells[idx].steps.push(at(f.cell_means(mesh.ncells())));
            }
        }
        let path = study
            .out_dir
            .join(format!("{}_{}.rmed", study.stem, c.name));
        match crate::medio::write_result_fields(&path, mesh, &fields, &cells) {
            Ok(()) => {
                let gauss: Vec<&str> = cells
                    .iter()
                    .map(|f| f.name[8.min(f.name.len())..].trim_start_matches('_'))
                    .collect();
                lines.push(format!(
                    "the {} archived steps of {} are saved in {}{}",
                    res.steps.len(),
                    c.name,
                    path.display(),
                    if gauss.is_empty() {
                        String::new()
                    } else {
                        format!(" ({} as their mean per cell)", gauss.join(", "))
                    }
                ))
            }
            Err(e) => lines.push(format!("could not save the result {}: {e}", c.name)),
        }
    }
    if lines.is_empty() {
        lines.push(format!(
            "no transient result had been computed before {cause}"
        ));
    }
    lines
}

/// Writes .mess, .resu and the text of other logical units.
fn write_outputs(study: &Study) -> Result<(), String> {
    let _output = crate::profile::span(crate::profile::Phase::Output);
    let w = |p: PathBuf, text: &str| {
        std::fs::write(&p, text).map_err(|e| format!("cannot write '{}': {e}", p.display()))
    };
    w(
        study.out_dir.join(format!("{}.mess", study.stem)),
        &study.mess,
    )?;
    w(
        study.out_dir.join(format!("{}.resu", study.stem)),
        &study.resu,
    )?;
    for (u, text) in &study.unit_text {
        w(study.unit_path(*u), text)?;
    }
    Ok(())
}
