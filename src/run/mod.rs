//! The study runner: executes a checked command file in order, each
//! command acting on the study's context ([`crate::study::Study`]).

use crate::catalog::checker::CheckedProgram;
use crate::commands::CommandDef;
use crate::concepts::{Concept, ConceptData};
use crate::diag::Diagnostic;
use crate::interrupt;
use crate::profile::{self, Phase};
use crate::study::Study;

pub mod driver;
pub mod export;

/// Runs the commands in order. Stops at the first error, which is
/// returned; everything produced before it stays in the study (and the
/// caller writes the .mess/.resu files in both cases). A stop requested by
/// a signal ([`crate::interrupt`]) ends the run before the next command,
/// or inside DYNA_NON_LINE between steps; the error then lists the
/// commands skipped.
pub fn execute(
    study: &mut Study,
    program: &CheckedProgram,
    registry: &[CommandDef],
    source: &crate::diag::Source,
) -> Result<(), Diagnostic> {
    let mut prints = program.prints.iter().peekable();
    for (i, c) in program.commands.iter().enumerate() {
        while let Some((_, text)) = prints.next_if(|(at, _)| *at <= i) {
            study.print(text);
        }
        let (line, _) = source.line_col(c.span.start);
        if let Some(signal) = interrupt::requested() {
            return Err(Diagnostic::error(format!(
                "{} received: the study stops before {} (line {line})",
                interrupt::name(signal),
                c.name
            ))
            .at(c.span)
            .note(skipped(program, i)));
        }
        let def = &registry[c.def];
        let target = c.result.as_ref().map(|t| t.name.as_str());
        study.log(format!(
            "# ---- {}{} (line {line})",
            target.map(|t| format!("{t} = ")).unwrap_or_default(),
            c.name,
        ));
        let started = std::time::Instant::now();
        let _output = profile::span_if(c.name.starts_with("IMPR_"), Phase::Output);
        let data = (def.exec)(study, &c.args, target).map_err(|d| {
            if interrupt::requested().is_some() {
                d.note(skipped(program, i + 1))
            } else {
                d
            }
        })?;
        if let Some(alarm) = study.raised_alarm.take() {
            return Err(Diagnostic::error(format!(
                "{} raised an alarm, an error under DEBUT(ERREUR=_F(ALARME='EXCEPTION')): {alarm}",
                c.name
            ))
            .at(c.span)
            .note("list its id in DEBUT(IGNORE_ALARM=...) to let it pass, or remove ERREUR=_F(ALARME='EXCEPTION'); code_aster stops at the alarm itself, aster at the end of the command that raised it"));
        }
        study.log(format!(
            "#      {} done in {:.3} s",
            c.name,
            started.elapsed().as_secs_f64()
        ));
        if let (Some(t), Some(ty)) = (&c.result, c.produces) {
            study.concepts.insert(Concept {
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
    for (at, text) in prints {
        if *at >= program.commands.len() {
            study.print(text);
        }
    }
    Ok(())
}

/// The commands from index `from` on, which a stop leaves unrun.
fn skipped(program: &CheckedProgram, from: usize) -> String {
    let rest = &program.commands[from.min(program.commands.len())..];
    if rest.is_empty() {
        return "no command was left to run".into();
    }
    // Runs of one command (the TEST_TABLE of a study) are counted.
    let mut names: Vec<(&str, usize)> = Vec::new();
    for c in rest {
        match names.last_mut() {
            Some((n, k)) if *n == c.name => *k += 1,
            _ => names.push((&c.name, 1)),
        }
    }
    let names: Vec<String> = names
        .iter()
        .map(|&(n, k)| {
            if k == 1 {
                n.to_string()
            } else {
                format!("{n} (x{k})")
            }
        })
        .collect();
    format!(
        "the {} command{} left {} not run: {}",
        rest.len(),
        if rest.len() == 1 { "" } else { "s" },
        if rest.len() == 1 { "was" } else { "were" },
        names.join(", ")
    )
}
