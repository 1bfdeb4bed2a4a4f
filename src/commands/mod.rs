//! The command registry: one file per command, holding its catalogue
//! declaration (as data, see [`crate::catalog::schema`]) and its executor.
//!
//! Adding a command means adding one file here and one line in [`all`].

// Executors return `Result<_, Diagnostic>`; a diagnostic is large (notes,
// choices, spans) but built only on the error path, so boxing it would cost
// every caller for nothing.
#![allow(clippy::result_large_err)]

use crate::catalog::args::Args;
use crate::catalog::schema::CommandSpec;
use crate::concepts::ConceptData;
use crate::diag::Diagnostic;
use crate::study::Study;

pub mod affe_char_cine;
pub mod affe_char_meca;
pub mod affe_char_meca_f;
pub mod affe_materiau;
pub mod affe_modele;
pub mod blocks;
pub mod calc_champ;
pub mod calc_fonction;
pub mod calc_table;
pub mod contact_def;
pub mod crea_champ;
pub mod crea_maillage;
pub mod crea_table;
pub mod debut;
pub mod defi_constante;
pub mod defi_contact;
pub mod defi_fichier;
pub mod defi_fonction;
pub mod defi_group;
pub mod defi_list_enti;
pub mod defi_list_inst;
pub mod defi_list_reel;
pub mod defi_materiau;
pub mod detruire;
pub mod dyna_explicit;
pub mod dyna_non_line;
pub mod fin;
pub mod formule;
pub mod impr_fonction;
pub mod impr_resu;
pub mod impr_table;
pub mod liaison_unil;
pub mod lire_maillage;
pub mod meca_statique;
pub mod mesh_args;
pub mod model_args;
pub mod modi_maillage;
pub mod post_args;
pub mod post_elem;
pub mod post_releve_t;
pub mod recu_fonction;
pub mod recu_table;
pub mod stat_non_line;
pub mod test_fonction;
pub mod test_resu;
pub mod test_table;

/// What an executor returns: the data of the produced concept (None for a
/// procedure such as TEST_RESU).
pub type ExecResult = Result<Option<ConceptData>, Diagnostic>;

/// Executes a checked command. `result` is the name the result is bound to
/// (for `reuse=`, the concept being modified, still in the table; without
/// it a concept of that name may still be in the table too, the one the
/// new result replaces: `args.reuse` says which case it is).
pub type ExecFn = fn(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult;

pub struct CommandDef {
    pub spec: CommandSpec,
    pub exec: ExecFn,
}

impl AsRef<CommandSpec> for CommandDef {
    fn as_ref(&self) -> &CommandSpec {
        &self.spec
    }
}

/// The executor of commands whose engine is not built yet.
pub fn not_implemented(_study: &mut Study, args: &Args, _result: Option<&str>) -> ExecResult {
    Err(args.not_implemented("", ""))
}

/// Every command of the catalogue, in alphabetical order.
pub fn all() -> Vec<CommandDef> {
    vec![
        affe_char_cine::def(),
        affe_char_cine::def_f(),
        affe_char_meca::def(),
        affe_char_meca_f::def(),
        affe_materiau::def(),
        affe_modele::def(),
        calc_champ::def(),
        calc_fonction::def(),
        calc_table::def(),
        crea_champ::def(),
        crea_maillage::def(),
        crea_table::def(),
        debut::def(),
        defi_constante::def(),
        defi_contact::def(),
        defi_fichier::def(),
        defi_fonction::def(),
        defi_group::def(),
        defi_list_enti::def(),
        defi_list_inst::def(),
        defi_list_reel::def(),
        defi_materiau::def(),
        detruire::def(),
        dyna_non_line::def(),
        fin::def(),
        formule::def(),
        impr_fonction::def(),
        impr_resu::def(),
        impr_table::def(),
        lire_maillage::def(),
        meca_statique::def(),
        modi_maillage::def(),
        post_elem::def(),
        post_releve_t::def(),
        recu_fonction::def(),
        recu_table::def(),
        stat_non_line::def(),
        test_fonction::def(),
        test_resu::def(),
        test_table::def(),
    ]
}

/// Looks a command up by name.
pub fn find(name: &str) -> Option<CommandDef> {
    all().into_iter().find(|c| c.spec.name == name)
}

/// The names of all commands (for "did you mean").
pub fn names() -> Vec<&'static str> {
    all().iter().map(|c| c.spec.name).collect()
}
