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
    /// AFFE_CHAR_CINE: imposed displacements eliminated from the system
    /// in code_aster; EXCIT takes it where it takes a char_meca.
    CharCineMeca,
    CharContact,
    Listr8,
    /// DEFI_LIST_ENTI: a strictly increasing list of integers (LIST_ORDRE).
    Listis,
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
    /// A field by element (CREA_CHAMP TYPE_CHAM='ELGA_*'): SIGM and VARI
    /// of ETAT_INIT take it.
    ChamElem,
    /// A field constant by cell (CREA_CHAMP TYPE_CHAM='CART_*'): SIGM of
    /// ETAT_INIT takes it, converted to the Gauss points.
    Carte,
}

impl ConceptType {
    /// Every type: DETRUIRE takes a concept of any of them (code_aster's
    /// `assd`).
    pub const ALL: &'static [ConceptType] = &[
        ConceptType::Maillage,
        ConceptType::Modele,
        ConceptType::Mater,
        ConceptType::ChamMater,
        ConceptType::CharMeca,
        ConceptType::CharCineMeca,
        ConceptType::CharContact,
        ConceptType::Listr8,
        ConceptType::ListInst,
        ConceptType::Fonction,
        ConceptType::Formule,
        ConceptType::ChamNo,
        ConceptType::EvolNoli,
        ConceptType::EvolElas,
        ConceptType::CaraElem,
        ConceptType::Table,
        ConceptType::Listis,
        ConceptType::ChamElem,
        ConceptType::Carte,
    ];

    /// The place of a type in [`ConceptType::ALL`]. The match has no
    /// wildcard, so a new type does not compile until it is placed here
    /// and in `ALL` (a test checks the two agree).
    pub fn rank(self) -> usize {
        match self {
            ConceptType::Maillage => 0,
            ConceptType::Modele => 1,
            ConceptType::Mater => 2,
            ConceptType::ChamMater => 3,
            ConceptType::CharMeca => 4,
            ConceptType::CharCineMeca => 5,
            ConceptType::CharContact => 6,
            ConceptType::Listr8 => 7,
            ConceptType::ListInst => 8,
            ConceptType::Fonction => 9,
            ConceptType::Formule => 10,
            ConceptType::ChamNo => 11,
            ConceptType::EvolNoli => 12,
            ConceptType::EvolElas => 13,
            ConceptType::CaraElem => 14,
            ConceptType::Table => 15,
            ConceptType::Listis => 16,
            ConceptType::ChamElem => 17,
            ConceptType::Carte => 18,
        }
    }

    pub fn aster_name(self) -> &'static str {
        match self {
            ConceptType::Maillage => "maillage_sdaster",
            ConceptType::Modele => "modele_sdaster",
            ConceptType::Mater => "mater_sdaster",
            ConceptType::ChamMater => "cham_mater",
            ConceptType::CharMeca => "char_meca",
            ConceptType::CharCineMeca => "char_cine_meca",
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
            ConceptType::Listis => "listis_sdaster",
            ConceptType::ChamElem => "cham_elem",
            ConceptType::Carte => "carte_sdaster",
        }
    }
}

impl std::fmt::Display for ConceptType {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.aster_name())
    }
}

#[cfg(test)]
mod tests {
    use super::ConceptType;

    #[test]
    fn all_lists_every_type_at_its_rank() {
        for (k, t) in ConceptType::ALL.iter().enumerate() {
            assert_eq!(t.rank(), k, "{t}");
        }
    }
}
