//! What a result file holds, and the lookups a picture needs: a field by
//! the name the user knows (`VARI_ELGA`, not `RESU____VARI_ELGA`), one of
//! its components, one of its instants. Every failed lookup says what the
//! file does hold, since the file may come from another program whose
//! naming the user cannot guess.

use std::path::{Path, PathBuf};

use crate::medio::{self, ElemField, FieldStep, NodalField};
use crate::mesh::Mesh;

/// The mesh and every field of a MED result file. Element fields are held
/// as one value per cell (Gauss points and element nodes averaged).
#[derive(Debug, Clone)]
pub struct ResultData {
    pub path: PathBuf,
    pub mesh: Mesh,
    pub nodal: Vec<NodalField>,
    pub cells: Vec<ElemField>,
}

/// A field found in the file.
#[derive(Debug, Clone, Copy)]
pub enum FieldChoice<'a> {
    Nodal(&'a NodalField),
    Cell(&'a ElemField),
}

/// Which scalar of a field: one component, or the Euclidean norm of all
/// of them (the displacement magnitude).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Component {
    Index(usize),
    Norm,
}

/// The name accepted for [`Component::Norm`] on the command line.
pub const NORM: &str = "NORM";

impl<'a> FieldChoice<'a> {
    pub fn name(&self) -> &'a str {
        match self {
            FieldChoice::Nodal(f) => &f.name,
            FieldChoice::Cell(f) => &f.name,
        }
    }
    pub fn components(&self) -> &'a [String] {
        match self {
            FieldChoice::Nodal(f) => &f.components,
            FieldChoice::Cell(f) => &f.components,
        }
    }
    pub fn steps(&self) -> &'a [FieldStep] {
        match self {
            FieldChoice::Nodal(f) => &f.steps,
            FieldChoice::Cell(f) => &f.steps,
        }
    }
    pub fn is_nodal(&self) -> bool {
        matches!(self, FieldChoice::Nodal(_))
    }

    /// The component named `name` (case-insensitive), or [`NORM`].
    pub fn component(&self, name: &str) -> Result<Component, String> {
        if name.eq_ignore_ascii_case(NORM) {
            return Ok(Component::Norm);
        }
        self.components()
            .iter()
            .position(|c| c.eq_ignore_ascii_case(name))
            .map(Component::Index)
            .ok_or_else(|| {
                format!(
                    "field {} has no component '{name}'; its components: {} (or {NORM}, \
                     the norm of them all)",
                    self.name(),
                    self.components().join(" ")
                )
            })
    }

    /// Display name of a component.
    pub fn component_name(&self, c: Component) -> String {
        match c {
            Component::Index(k) => self.components()[k].clone(),
            Component::Norm => format!("|{}|", self.components().join(",")),
        }
    }

    /// The values of component `c` at step `step`, one per node or cell.
    pub fn scalar(&self, step: usize, c: Component) -> Vec<f64> {
        let nc = self.components().len();
        let v = &self.steps()[step].values;
        v.chunks_exact(nc)
            .map(|e| match c {
                Component::Index(k) => e[k],
                Component::Norm => e.iter().map(|x| x * x).sum::<f64>().sqrt(),
            })
            .collect()
    }

    /// The step at instant `inst` (the last step when None), matched to a
    /// relative 1e-6 of the largest instant, as code_aster's CRITERE
    /// RELATIF does.
    pub fn step_at(&self, inst: Option<f64>) -> Result<usize, String> {
        let steps = self.steps();
        let Some(t) = inst else {
            return Ok(steps.len() - 1);
        };
        let scale = steps.iter().fold(t.abs(), |m, s| m.max(s.time.abs()));
        let tol = 1e-6 * scale + 1e-300;
        steps
            .iter()
            .position(|s| (s.time - t).abs() <= tol)
            .ok_or_else(|| {
                format!(
                    "no instant {t:e} in field {}; its instants: {}",
                    self.name(),
                    instants_text(steps)
                )
            })
    }
}

/// The instants of a list of steps, shortened when long.
pub fn instants_text(steps: &[FieldStep]) -> String {
    let t: Vec<String> = steps.iter().map(|s| format!("{:e}", s.time)).collect();
    if t.len() <= 12 {
        t.join(" ")
    } else {
        format!(
            "{} ... {} ({} instants)",
            t[..6].join(" "),
            t[t.len() - 3..].join(" "),
            t.len()
        )
    }
}

/// True when a file field name is the field the user named: the same
/// name, or code_aster's `<result padded to 8 with '_'><field>`.
fn name_matches(file_name: &str, wanted: &str) -> bool {
    let f = file_name.trim_end();
    f.eq_ignore_ascii_case(wanted)
        || (f.len() == wanted.len() + 8
            && f.is_char_boundary(8)
            && f[8..].eq_ignore_ascii_case(wanted))
}

impl ResultData {
    /// Reads the mesh (`mesh` or the file's first) and all its fields.
    pub fn read(path: &Path, mesh: Option<&str>) -> Result<ResultData, String> {
        let m = medio::read_mesh(path, mesh).map_err(|e| e.to_string())?;
        let nodal = medio::read_nodal_fields(path, Some(&m.name)).map_err(|e| e.to_string())?;
        let cells = medio::read_cell_mean_fields(path, Some(&m.name)).map_err(|e| e.to_string())?;
        Ok(ResultData {
            path: path.to_path_buf(),
            mesh: m,
            nodal,
            cells,
        })
    }

    fn all(&self) -> impl Iterator<Item = FieldChoice<'_>> {
        self.nodal
            .iter()
            .map(FieldChoice::Nodal)
            .chain(self.cells.iter().map(FieldChoice::Cell))
    }

    /// A description of every field of the file, one per line, for error
    /// messages.
    pub fn holds(&self) -> String {
        let mut s = format!(
            "{} holds mesh '{}' ({} nodes, {} cells)",
            self.path.display(),
            self.mesh.name,
            self.mesh.nnodes(),
            self.mesh.ncells()
        );
        if self.nodal.is_empty() && self.cells.is_empty() {
            s.push_str(" and no field");
        }
        for f in self.all() {
            s.push_str(&format!(
                "\n  {}: {}, components {}, instants {}",
                f.name(),
                if f.is_nodal() { "at nodes" } else { "per cell" },
                f.components().join(" "),
                instants_text(f.steps())
            ));
        }
        s
    }

    /// The field named `name` (see [`name_matches`]); an error lists the
    /// fields of the file when there is none, or the candidates when the
    /// name is ambiguous.
    pub fn field(&self, name: &str) -> Result<FieldChoice<'_>, String> {
        let found: Vec<FieldChoice> = self
            .all()
            .filter(|f| f.name().trim_end().eq_ignore_ascii_case(name))
            .collect();
        let found = if found.is_empty() {
            self.all()
                .filter(|f| name_matches(f.name(), name))
                .collect()
        } else {
            found
        };
        match found.len() {
            1 => Ok(found[0]),
            0 => Err(format!("no field '{name}' in the file; {}", self.holds())),
            _ => Err(format!(
                "several fields match '{name}': {}; give the full name",
                found
                    .iter()
                    .map(|f| f.name().to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
        }
    }

    /// The displacement field (named DEPL), if any.
    pub fn displacement(&self) -> Option<&NodalField> {
        self.nodal.iter().find(|f| name_matches(&f.name, "DEPL"))
    }

    /// The default field and component of a picture: the cumulated plastic
    /// strain (V1 of VARI_ELGA) when the file has it, else the norm of the
    /// displacement.
    pub fn default_field(&self) -> Result<(FieldChoice<'_>, Component), String> {
        if let Some(f) = self
            .cells
            .iter()
            .find(|f| name_matches(&f.name, "VARI_ELGA"))
        {
            let f = FieldChoice::Cell(f);
            if let Ok(c) = f.component("V1") {
                return Ok((f, c));
            }
        }
        if let Some(d) = self.displacement() {
            return Ok((FieldChoice::Nodal(d), Component::Norm));
        }
        Err(format!(
            "neither VARI_ELGA nor DEPL in the file: choose a field with --field NAME:COMPONENT; {}",
            self.holds()
        ))
    }
}

/// Unit of a field in the study's units (mm, s, N, MPa), from its
/// code_aster name; empty when unknown or dimensionless.
pub fn unit_of(field: &str) -> &'static str {
    let f = field.trim_end().to_ascii_uppercase();
    let ends = |s: &str| f.ends_with(s);
    if ends("DEPL") {
        "mm"
    } else if ends("VITE") {
        "mm/s"
    } else if ends("ACCE") {
        "mm/s²"
    } else if ends("FORC_NODA") || ends("REAC_NODA") {
        "N"
    } else if ends("SIEF_ELGA") || ends("SIGM_ELNO") || ends("SIEF_ELNO") || ends("SIGM_NOEU") {
        "MPa"
    } else {
        ""
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn aster_field_names_match_the_short_name() {
        assert!(name_matches("RESU____VARI_ELGA", "VARI_ELGA"));
        assert!(name_matches("DEPL", "depl"));
        assert!(!name_matches("RESU____DEPL", "VITE"));
        assert!(!name_matches("XDEPL", "DEPL"));
    }
}
