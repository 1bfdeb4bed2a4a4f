//! The types of concepts, as the command language knows them: the checker
//! types keywords and results with them before anything runs, so they
//! belong to the catalogue; [`crate::concepts`] holds the data.

/// The type of a concept, as code_aster names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ConceptType {
    Maillage,
    Modele,
    Mater,
    ChamMater,
    CharMeca,
    CharContact,
    Listr8,
    ListInst,
    Fonction,
    /// FORMULE: a function given by an expression.
    Formule,
    ChamNo,
    EvolNoli,
    /// A linear static result (MECA_STATIQUE): the same data as
    /// evol_noli, read by the same post-processing commands.
    EvolElas,
    /// AFFE_CARA_ELEM's element characteristics: no command produces it
    /// yet; MECA_STATIQUE declares the keyword to refuse it clearly.
    CaraElem,
    Table,
}

impl ConceptType {
    pub fn aster_name(self) -> &'static str {
        match self {
            ConceptType::Maillage => "maillage_sdaster",
            ConceptType::Modele => "modele_sdaster",
            ConceptType::Mater => "mater_sdaster",
            ConceptType::ChamMater => "cham_mater",
            ConceptType::CharMeca => "char_meca",
            ConceptType::CharContact => "char_contact",
            ConceptType::Listr8 => "listr8_sdaster",
            ConceptType::ListInst => "list_inst",
            ConceptType::Fonction => "fonction_sdaster",
            ConceptType::Formule => "formule",
            ConceptType::ChamNo => "cham_no_sdaster",
            ConceptType::EvolNoli => "evol_noli",
            ConceptType::EvolElas => "evol_elas",
            ConceptType::CaraElem => "cara_elem",
            ConceptType::Table => "table_sdaster",
        }
    }
}

impl std::fmt::Display for ConceptType {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.aster_name())
    }
}
