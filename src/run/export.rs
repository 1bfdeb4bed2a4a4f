//! code_aster `.export` files: the map from logical units to files.
//!
//! Only the `F` lines matter here: `F <type> <path> <D|R|DR|RC...> <unit>`.
//! A `D` (data) file is read, an `R` (result) file is written. Relative
//! paths are relative to the directory of the `.export` file, so a study
//! and its export can be moved together.

use std::path::{Path, PathBuf};

use crate::diag::Diagnostic;

/// One `F` line.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportFile {
    pub kind: String,
    pub path: PathBuf,
    pub data: bool,
    pub result: bool,
    pub unit: i64,
}

/// Parses an export file's text; `base` is the directory paths are relative to.
pub fn parse_export(text: &str, base: &Path, name: &str) -> Result<Vec<ExportFile>, Diagnostic> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split_whitespace().collect();
        match fields.first() {
            Some(&"F") => {}
            // P (parameters), A (arguments), R (directories): not used here.
            Some(&("P" | "A" | "R" | "N")) => continue,
            _ => {
                return Err(Diagnostic::error(format!(
                    "{name}:{}: expected a line 'F <type> <path> <D|R> <unit>', found '{line}'",
                    i + 1
                )))
            }
        }
        if fields.len() != 5 {
            return Err(Diagnostic::error(format!(
                "{name}:{}: an F line has 5 fields 'F <type> <path> <D|R> <unit>', found {}",
                i + 1,
                fields.len()
            )));
        }
        let unit: i64 = fields[4].parse().map_err(|_| {
            Diagnostic::error(format!(
                "{name}:{}: the logical unit must be an integer, found '{}'",
                i + 1,
                fields[4]
            ))
        })?;
        let mode = fields[3];
        if !mode.chars().all(|c| matches!(c, 'D' | 'R' | 'C')) || mode.is_empty() {
            return Err(Diagnostic::error(format!(
                "{name}:{}: the mode must be D (data), R (result) or DR, found '{mode}'",
                i + 1
            )));
        }
        let p = Path::new(fields[2]);
        let path = if p.is_absolute() {
            p.to_path_buf()
        } else {
            base.join(p)
        };
        out.push(ExportFile {
            kind: fields[1].to_string(),
            path,
            data: mode.contains('D'),
            result: mode.contains('R'),
            unit,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_f_lines_relative_to_the_export() {
        let t = "P actions make_etude\nF mmed ../med/sdnv103b.mmed D 20\nF resu out.resu R 8\n";
        let f = parse_export(t, Path::new("/s/comm"), "x.export").unwrap();
        assert_eq!(f.len(), 2);
        assert_eq!(f[0].unit, 20);
        assert_eq!(f[0].path, Path::new("/s/comm/../med/sdnv103b.mmed"));
        assert!(f[0].data && !f[0].result);
        assert!(parse_export("F mmed a D x\n", Path::new("."), "e").is_err());
        assert!(parse_export("bogus\n", Path::new("."), "e").is_err());
    }
}
