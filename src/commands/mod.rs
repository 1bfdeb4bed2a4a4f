//! The command registry: one file per command, holding its catalogue
//! declaration (as data, see [`crate::catalog::schema`]) and its executor.
//!
//! Adding a command means adding one file here and one line in [`all`].

use crate::catalog::args::Args;
use crate::catalog::schema::CommandSpec;
use crate::concepts::ConceptData;
use crate::diag::Diagnostic;
use crate::run::Study;

pub mod blocks;

/// What an executor returns: the data of the produced concept (None for a
/// procedure such as TEST_RESU).
pub type ExecResult = Result<Option<ConceptData>, Diagnostic>;

/// Executes a checked command. `result` is the name the result is bound to
/// (for `reuse=`, the concept being modified, still in the table).
pub type ExecFn = fn(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult;

pub struct CommandDef {
    pub spec: CommandSpec,
    pub exec: ExecFn,
}

/// The executor of commands whose engine is not built yet.
pub fn not_implemented(_study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    Err(args.not_implemented("", ""))
}

/// Every command of the catalogue, in alphabetical order.
pub fn all() -> Vec<CommandDef> {
    vec![]
}

/// Looks a command up by name.
pub fn find(name: &str) -> Option<CommandDef> {
    all().into_iter().find(|c| c.spec.name == name)
}

/// The names of all commands (for "did you mean").
pub fn names() -> Vec<&'static str> {
    all().iter().map(|c| c.spec.name).collect()
}
