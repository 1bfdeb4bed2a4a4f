//! code_aster's own mesh format (`LIRE_MAILLAGE(FORMAT='ASTER')`, the
//! `.mail` files of its test base and of older studies).
//!
//! A file is a sequence of sub-files, each opened by a keyword line and
//! closed by `FINSF`, the whole ended by `FIN`; `%` starts a comment:
//! - `TITRE`: free text;
//! - `COOR_2D` / `COOR_3D`: one node per line, its name then its
//!   coordinates (Fortran `D` exponents allowed);
//! - a cell type (`SEG2`, `QUAD8`, `HEXA8`...): one cell per line, its name
//!   then the names of its nodes;
//! - `GROUP_NO` / `GROUP_MA`: one group, its name (first token, or
//!   `NOM=` on the keyword line) then the names of its members, over as
//!   many lines as needed.
//!
//! Nodes and cells are numbered in the order of the file, as code_aster
//! numbers them, so `N<k>` / `M<k>` in messages are the k-th of the file.
//! The names themselves are only used to resolve the connectivity and the
//! groups: the mesh keeps no names (NOEUD= / MAILLE= of a command address
//! N<k> / M<k>, as for a MED file without names).
//!
//! Node order: code_aster's numbering of a cell is MED's for 1D and 2D
//! cells and VTK's for the linear 3D ones (docs/mesh.md "Cell node order"),
//! so TETRA4, PENTA6 and HEXA8 are permuted into MED order. For the
//! quadratic 3D cells (TETRA10, PENTA15, HEXA20) the correspondence of the
//! mid-edge nodes is not established here: they are refused as not
//! implemented rather than read in a possibly wrong order.

use std::collections::HashMap;

use indexmap::IndexMap;

use super::{Cell, CellType, Mesh};

/// Why a `.mail` file cannot be read: the line (1-based) and what.
#[derive(Debug, Clone, PartialEq)]
pub struct MailError {
    pub line: usize,
    pub message: String,
}

impl std::fmt::Display for MailError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

fn err(line: usize, message: impl Into<String>) -> MailError {
    MailError {
        line,
        message: message.into(),
    }
}

/// For each node of a cell as code_aster lists it, its MED index (the
/// linear 3D cells turn the other way in MED: `vtk_permutation`).
fn to_med(t: CellType) -> Option<&'static [usize]> {
    match t {
        CellType::Tetra4 => Some(&[0, 2, 1, 3]),
        CellType::Penta6 => Some(&[0, 2, 1, 3, 5, 4]),
        CellType::Hexa8 => Some(&[0, 3, 2, 1, 4, 7, 6, 5]),
        CellType::Tetra10 | CellType::Penta15 | CellType::Hexa20 => None,
        _ => Some(&[]),
    }
}

/// The code_aster cell types of the format that aster has no element for.
const OTHER_TYPES: &[&str] = &[
    "SEG4", "TRIA7", "QUAD9", "PENTA18", "HEXA27", "PYRAM5", "PYRAM13",
];

/// The lines of a file without comments, with their 1-based numbers.
fn lines(text: &str) -> impl Iterator<Item = (usize, Vec<&str>)> {
    text.lines().enumerate().filter_map(|(i, l)| {
        let l = l.split('%').next().unwrap_or("");
        let toks: Vec<&str> = l
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|t| !t.is_empty())
            .collect();
        (!toks.is_empty()).then_some((i + 1, toks))
    })
}

/// The records of a sub-file of fixed arity (a node: its name and its
/// coordinates; a cell: its name and its nodes), which may run over
/// several lines (code_aster's own files wrap the eighth node of a HEXA8);
/// each record with the line it starts on.
fn records<'a>(
    body: &[(usize, Vec<&'a str>)],
    arity: usize,
    what: &str,
) -> Result<Vec<(usize, Vec<&'a str>)>, MailError> {
    let toks: Vec<(usize, &str)> = body
        .iter()
        .flat_map(|(l, t)| t.iter().map(move |s| (*l, *s)))
        .collect();
    if !toks.len().is_multiple_of(arity) {
        let start = toks.len() - toks.len() % arity;
        return Err(err(
            toks[start].0,
            format!(
                "a record of {what} has {arity} fields (a name and {}), the last one has {}",
                arity - 1,
                toks.len() - start
            ),
        ));
    }
    Ok(toks
        .chunks(arity)
        .map(|c| (c[0].0, c.iter().map(|x| x.1).collect()))
        .collect())
}

fn number(tok: &str, line: usize) -> Result<f64, MailError> {
    tok.replace(['D', 'd'], "e")
        .parse::<f64>()
        .map_err(|_| err(line, format!("'{tok}' is not a number")))
}

/// A group as read (its keyword's line, nodes or cells, its name, its
/// members with their lines), resolved once the whole file is read.
type PendingGroup = (usize, bool, String, Vec<(usize, String)>);

/// Reads the text of a `.mail` file into a mesh named `name`, with the
/// alarms for the .mess (names that N<k> / M<k> will not find).
pub fn parse(text: &str, name: &str) -> Result<(Mesh, Vec<String>), MailError> {
    let mut node_index: HashMap<String, usize> = HashMap::new();
    let mut cell_index: HashMap<String, usize> = HashMap::new();
    let mut coords: Vec<[f64; 3]> = Vec::new();
    let mut cells: Vec<Cell> = Vec::new();
    let mut cell_groups: IndexMap<String, Vec<usize>> = IndexMap::new();
    let mut node_groups: IndexMap<String, Vec<usize>> = IndexMap::new();
    // Groups are resolved at the end: a group may name cells or nodes
    // defined further down the file.
    let mut pending: Vec<PendingGroup> = Vec::new();
    let mut dim: Option<usize> = None;
    let mut it = lines(text).peekable();
    let mut ended = false;
    while let Some((line, toks)) = it.next() {
        let key = toks[0].to_ascii_uppercase();
        if key == "FIN" {
            ended = true;
            break;
        }
        // The body of the sub-file, up to its FINSF.
        let mut body: Vec<(usize, Vec<&str>)> = Vec::new();
        let mut closed = false;
        for (l, t) in it.by_ref() {
            if t[0].eq_ignore_ascii_case("FINSF") {
                closed = true;
                break;
            }
            body.push((l, t));
        }
        if !closed {
            return Err(err(
                line,
                format!("the sub-file {key} is not closed by FINSF"),
            ));
        }
        match key.as_str() {
            "TITRE" => {}
            "COOR_2D" | "COOR_3D" => {
                let d = if key == "COOR_2D" { 2 } else { 3 };
                if dim.is_some_and(|x| x != d) {
                    return Err(err(line, "COOR_2D and COOR_3D in one mesh"));
                }
                dim = Some(d);
                for (l, t) in records(&body, d + 1, &key)? {
                    let mut x = [0.0; 3];
                    for k in 0..d {
                        x[k] = number(t[k + 1], l)?;
                    }
                    if node_index.insert(t[0].to_string(), coords.len()).is_some() {
                        return Err(err(l, format!("node {} is defined twice", t[0])));
                    }
                    coords.push(x);
                }
            }
            "GROUP_NO" | "GROUP_MA" => {
                let nodes = key == "GROUP_NO";
                // NOM=NAME (or NOM = NAME) on the keyword line, else the
                // first token of the body.
                let header: Vec<&str> = toks[1..].to_vec();
                let mut members: Vec<(usize, String)> = Vec::new();
                for (l, t) in &body {
                    members.extend(t.iter().map(|s| (*l, s.to_string())));
                }
                let named = header.join(" ").replace(' ', "");
                let group = if let Some(n) = named.strip_prefix("NOM=") {
                    n.to_string()
                } else if header.is_empty() {
                    if members.is_empty() {
                        return Err(err(line, format!("{key} without a group name")));
                    }
                    members.remove(0).1
                } else {
                    return Err(err(
                        line,
                        format!(
                            "unexpected '{}' after {key} (expected NOM=<group> or nothing)",
                            header.join(" ")
                        ),
                    ));
                };
                pending.push((line, nodes, group, members));
            }
            other => {
                let t = CellType::ALL.into_iter().find(|t| t.aster_name() == other);
                let Some(t) = t else {
                    return Err(if OTHER_TYPES.contains(&other) {
                        err(line, format!("not implemented yet: cells of type {other} (aster has no element on them)"))
                    } else {
                        err(
                            line,
                            format!(
                                "unknown sub-file {other}: expected TITRE, COOR_2D, COOR_3D, GROUP_NO, GROUP_MA or a cell type ({})",
                                CellType::ALL.map(|t| t.aster_name()).join(", ")
                            ),
                        )
                    });
                };
                let Some(perm) = to_med(t) else {
                    return Err(err(
                        line,
                        format!("not implemented yet: {other} cells in FORMAT='ASTER' (the order of their mid-edge nodes against MED's is not established); convert the mesh to MED"),
                    ));
                };
                let n = t.nnodes();
                for (l, tk) in records(&body, n + 1, other)? {
                    let mut listed = Vec::with_capacity(n);
                    for s in &tk[1..] {
                        match node_index.get(*s) {
                            Some(&i) => listed.push(i),
                            None => {
                                return Err(err(
                                    l,
                                    format!("cell {} names the node {s}, which no COOR_ sub-file before it defines", tk[0]),
                                ))
                            }
                        }
                    }
                    let nodes = if perm.is_empty() {
                        listed
                    } else {
                        let mut med = vec![0; n];
                        for (i, &p) in perm.iter().enumerate() {
                            med[p] = listed[i];
                        }
                        med
                    };
                    if cell_index.insert(tk[0].to_string(), cells.len()).is_some() {
                        return Err(err(l, format!("cell {} is defined twice", tk[0])));
                    }
                    cells.push(Cell { kind: t, nodes });
                }
            }
        }
    }
    if !ended {
        return Err(err(text.lines().count(), "the file does not end with FIN"));
    }
    for (line, nodes, group, members) in pending {
        let (index, what, out) = if nodes {
            (&node_index, "node", &mut node_groups)
        } else {
            (&cell_index, "cell", &mut cell_groups)
        };
        let mut ids: Vec<usize> = Vec::with_capacity(members.len());
        let mut seen = std::collections::HashSet::new();
        for (l, m) in members {
            match index.get(&m) {
                Some(&i) => {
                    if seen.insert(i) {
                        ids.push(i)
                    }
                }
                None => {
                    return Err(err(
                        l,
                        format!(
                            "group {group} names the {what} {m}, which the file does not define"
                        ),
                    ))
                }
            }
        }
        if !nodes {
            ids.sort_unstable();
        }
        if out.insert(group.clone(), ids).is_some() {
            return Err(err(
                line,
                format!("the {what} group {group} is defined twice"),
            ));
        }
    }
    let mut alarms = Vec::new();
    for (what, prefix, index) in [("node", 'N', &node_index), ("cell", 'M', &cell_index)] {
        let mut other: Vec<(&String, usize)> = index
            .iter()
            .filter(|(n, &i)| **n != format!("{prefix}{}", i + 1))
            .map(|(n, &i)| (n, i))
            .collect();
        if let Some(&(first, i)) = other.iter().min_by_key(|(_, i)| *i) {
            other.clear();
            alarms.push(format!(
                "the {what} names of the file are not kept: a {what} is {prefix}<k>, the k-th of the file, in NOEUD=/MAILLE= and in messages (the file's {first} is {prefix}{}); groups keep their members",
                i + 1
            ));
        }
    }
    let mesh = Mesh {
        name: name.to_string(),
        dim: dim.unwrap_or(3),
        coords,
        cells,
        cell_groups,
        node_groups,
    };
    Ok((mesh, alarms))
}
