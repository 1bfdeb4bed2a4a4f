//! Concepts: the named, typed results that commands produce and consume.
//!
//! A command file binds names to concepts (`MAIL = LIRE_MAILLAGE(...)`).
//! The checker only needs their types; the runner also keeps their data.
//! Type names follow code_aster's (`maillage_sdaster`, `evol_noli`, ...)
//! so that messages read as a code_aster user expects.

use indexmap::IndexMap;

use crate::diag::Span;

/// Moved to the catalogue, whose checker types keywords with it; the
/// path here stays for code written before the move.
pub use crate::catalog::concept_type::ConceptType;

/// The data of a concept once its command has run. Variants are added as
/// engines are built; a concept produced by `aster check` has no data.
#[derive(Debug, Clone, Default)]
pub enum ConceptData {
    /// Produced by the checker only (no execution).
    #[default]
    Unevaluated,
    Mesh(Box<crate::mesh::Mesh>),
    /// A list of reals (DEFI_LIST_REEL).
    ListReal(Vec<f64>),
    /// A strictly increasing list of integers (DEFI_LIST_ENTI).
    ListInt(Vec<i64>),
    Table(Box<crate::post::table::Table>),
    Model(Box<crate::model::Model>),
    Material(Box<crate::model::Material>),
    MaterialField(Box<crate::model::MaterialField>),
    MechLoad(Box<crate::model::MechLoad>),
    /// DEFI_LIST_INST.
    TimeList(Box<crate::time::list::TimeList>),
    /// A nodal field (CREA_CHAMP).
    Field(Box<ChamNo>),
    /// A field by element at Gauss points (CREA_CHAMP ELGA_SIEF_R,
    /// ELGA_VARI_R).
    ElemField(Box<ChamElem>),
    /// A transient result (DYNA_NON_LINE).
    Result(Box<crate::result::EvolNoli>),
    /// A tabulated or constant function (RECU_FONCTION, DEFI_CONSTANTE).
    Function(Box<crate::post::function::Function>),
    /// FORMULE.
    Formula(Box<crate::post::formula::Formula>),
    /// DEFI_CONTACT: kept as checked keywords until the contact engine
    /// turns them into its own data.
    Contact(Box<crate::catalog::args::Args>),
}

/// A nodal field concept (CREA_CHAMP): its values and the mesh they are
/// numbered on. The mesh is kept because the values are by node index: a
/// field of another mesh given to a model would be read on the wrong nodes,
/// silently, so its users check it.
#[derive(Debug, Clone, PartialEq)]
pub struct ChamNo {
    /// The mesh concept (that of the model for CREA_CHAMP MODELE=).
    pub mesh: String,
    pub field: crate::result::NodalField,
}

/// The quantity of a field by element: stresses (SIEF_R, components
/// SIXX...) or internal variables (VARI_R, components V1, V2...).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElemQuantity {
    Sief,
    Vari,
}

impl ElemQuantity {
    /// code_aster's TYPE_CHAM of the field.
    pub fn type_cham(self) -> &'static str {
        match self {
            ElemQuantity::Sief => "ELGA_SIEF_R",
            ElemQuantity::Vari => "ELGA_VARI_R",
        }
    }
}

/// A field by element at Gauss points (cham_elem, CREA_CHAMP): values
/// per cell and point of the model's elements (the family of SIEF_ELGA:
/// [`crate::element::output_points`]); a value never assigned is NaN
/// and reads as 0 in ETAT_INIT. The model is kept because the points are
/// those of its elements: ETAT_INIT refuses a field of another model.
#[derive(Debug, Clone, PartialEq)]
pub struct ChamElem {
    pub mesh: String,
    pub model: String,
    pub quantity: ElemQuantity,
    /// A CART (TYPE_CHAM='CART_SIEF_R'): one point per cell, on a mesh
    /// (`model` empty) or a model; ETAT_INIT gives its values to every
    /// Gauss point of the cell (code_aster's nmetcv, ETATINIT_51).
    pub by_cell: bool,
    pub field: crate::result::GaussField,
}

#[derive(Debug, Clone)]
pub struct Concept {
    pub name: String,
    pub ty: ConceptType,
    /// Where the concept was (last) produced.
    pub defined_at: Span,
    /// The command that produced it.
    pub command: String,
    pub data: ConceptData,
}

/// The table of concepts of a study, in creation order.
#[derive(Debug, Clone, Default)]
pub struct Concepts {
    table: IndexMap<String, Concept>,
}

impl Concepts {
    pub fn new() -> Self {
        Self::default()
    }
    pub fn get(&self, name: &str) -> Option<&Concept> {
        self.table.get(name)
    }
    /// The data of a concept (None if unknown or not computed).
    pub fn data(&self, name: &str) -> Option<&ConceptData> {
        self.table.get(name).map(|c| &c.data)
    }
    pub fn get_mut(&mut self, name: &str) -> Option<&mut Concept> {
        self.table.get_mut(name)
    }
    /// Binds (or, with `reuse=`, rebinds) a name.
    pub fn insert(&mut self, concept: Concept) {
        self.table.insert(concept.name.clone(), concept);
    }
    pub fn remove(&mut self, name: &str) -> Option<Concept> {
        self.table.shift_remove(name)
    }
    pub fn iter(&self) -> impl Iterator<Item = &Concept> {
        self.table.values()
    }
    pub fn len(&self) -> usize {
        self.table.len()
    }
    pub fn is_empty(&self) -> bool {
        self.table.is_empty()
    }
}
