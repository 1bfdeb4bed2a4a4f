//! MED files (HDF5) in and out: meshes, groups and result fields.
//!
//! MED is the mesh and result format of code_aster and SALOME: an HDF5 file
//! with a fixed tree (`/ENS_MAA` meshes, `/FAS` families, `/CHA` fields).
//! The subset read and written here, and the choices made where the format
//! leaves freedom, are described in `docs/mesh.md`.
//!
//! Cells are kept in MED node order inside [`Mesh`](crate::mesh::Mesh); [`vtk_permutation`]
//! converts to VTK at the border. Cells read from a file are numbered type by
//! type in increasing MED type code (SE3 before QU8 before HE8...), within a
//! type in file order, which is how code_aster numbers them (M1, M2, ...).

mod field;
mod h5util;
mod info;
mod read;
mod vtk;
mod write;

use std::fmt;
use std::path::{Path, PathBuf};

pub use field::{
    read_cell_mean_fields, read_elem_fields, read_nodal_fields, write_result, write_result_fields,
    ElemField, FieldStep, NodalField,
};
pub use info::mesh_info;
pub use read::{mesh_names, read_mesh, read_mesh_with_notes, UndescribedFamily};
pub use vtk::{vtk_cell_type, vtk_permutation};
pub use write::write_mesh;

/// What went wrong with a MED file; always paired with the file path in
/// [`MedError`], so a message can be shown to a user as it is.
#[derive(Debug, Clone, PartialEq)]
pub enum MedErrorKind {
    /// The file could not be opened, read or written at the OS level.
    Io(String),
    /// No HDF5 signature: not a MED file at all (or a text file renamed).
    NotHdf5,
    /// HDF5 signature present but the file ends before its stated end.
    Truncated(String),
    /// A valid HDF5 file that does not have the MED tree (no `/ENS_MAA`).
    NotMed(String),
    /// The file has `/ENS_MAA` but no mesh in it.
    NoMesh,
    /// The mesh asked for is absent; the names present are listed.
    MeshNotFound {
        wanted: String,
        available: Vec<String>,
    },
    /// A `MAI/<TYP>` group whose type this reader does not know.
    UnknownCellType(String),
    /// Sizes or numbers that contradict each other (dataset lengths,
    /// node numbers out of range, values per step...).
    Inconsistent(String),
    /// Valid MED, but outside the supported subset (structured mesh,
    /// profiles, MED 2.x...).
    Unsupported(String),
    /// The data given to a writer cannot be represented in MED.
    InvalidInput(String),
    /// Any other HDF5 failure, with what was being done.
    Hdf5(String),
}

/// Error of the MED reader/writer: the file and what is wrong with it.
#[derive(Debug, Clone, PartialEq)]
pub struct MedError {
    pub path: PathBuf,
    pub kind: MedErrorKind,
}

impl MedError {
    pub(crate) fn new(path: &Path, kind: MedErrorKind) -> MedError {
        MedError {
            path: path.to_path_buf(),
            kind,
        }
    }
}

impl fmt::Display for MedError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = self.path.display();
        match &self.kind {
            MedErrorKind::Io(m) => write!(f, "{p}: {m}"),
            MedErrorKind::NotHdf5 => write!(
                f,
                "{p}: not an HDF5 file (no HDF5 signature), so not a MED file"
            ),
            MedErrorKind::Truncated(m) => write!(
                f,
                "{p}: truncated file (HDF5 says the file is shorter than it should be): {m}"
            ),
            MedErrorKind::NotMed(m) => write!(f, "{p}: HDF5 file but not a MED file: {m}"),
            MedErrorKind::NoMesh => write!(f, "{p}: MED file without any mesh in /ENS_MAA"),
            MedErrorKind::MeshNotFound { wanted, available } => write!(
                f,
                "{p}: no mesh named '{wanted}' in this MED file; meshes present: {}",
                if available.is_empty() {
                    "(none)".to_string()
                } else {
                    available
                        .iter()
                        .map(|n| format!("'{n}'"))
                        .collect::<Vec<_>>()
                        .join(", ")
                }
            ),
            MedErrorKind::UnknownCellType(t) => write!(
                f,
                "{p}: unknown or unsupported cell type '{t}' (supported: {})",
                crate::mesh::CellType::ALL
                    .iter()
                    .map(|t| t.med_name())
                    .collect::<Vec<_>>()
                    .join(" ")
            ),
            MedErrorKind::Inconsistent(m) => write!(f, "{p}: inconsistent MED data: {m}"),
            MedErrorKind::Unsupported(m) => write!(f, "{p}: unsupported MED content: {m}"),
            MedErrorKind::InvalidInput(m) => write!(f, "{p}: cannot write: {m}"),
            MedErrorKind::Hdf5(m) => write!(f, "{p}: HDF5 error: {m}"),
        }
    }
}

impl std::error::Error for MedError {}
