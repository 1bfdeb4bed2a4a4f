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
//! so TETRA4, PENTA6 and HEXA8 are permuted into MED order, and so are the
//! mid-edge nodes of the quadratic 3D cells (TETRA10, PENTA15, HEXA20),
//! which code_aster lists edge by edge in the order of its reference cells
//! (`elrfno.F90`: T10, P15, H20).

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

/// `p` with MED node i = the cell's node p[i] as code_aster lists it
/// (empty: the same order). The 3D cells turn the other way in MED. For
/// HEXA20 code_aster lists the mid-edge nodes of the base, then of the
/// vertical edges, then of the top (MED: base, top, vertical): found by
/// the probe h_mail of 2026-11-28 on the geometry of all 14 HEXA20 cells
/// of code_aster's test meshes at hand (sslv07a, hsnv120a, hplv101b),
/// whose sslv07a converted so reproduced 12 of code_aster's values.
/// PENTA15 and TETRA10 (probe11, 2026-11-28): code_aster's reference cells
/// (`elrfno.F90`, P15 and T10) put the mid-edge nodes of the PENTA15 on the
/// base edges 1-2, 2-3, 3-1, then the vertical ones 1-4, 2-5, 3-6, then the
/// top 4-5, 5-6, 6-4 (MED: base, top, vertical), and those of the TETRA10
/// on 1-2, 2-3, 3-1, 1-4, 2-4, 3-4 (MED's list, on MED's own corners):
/// with the corners turned as the linear cells', each MED mid node is the
/// code_aster node of the same edge. These are the inverses of
/// `mesh::ops::med_to_aster`, checked by a test below and, on meshes of
/// both kinds, by tests/verification/mail_quadratic_3d.comm.
fn to_med(t: CellType) -> &'static [usize] {
    match t {
        CellType::Tetra4 => &[0, 2, 1, 3],
        CellType::Penta6 => &[0, 2, 1, 3, 5, 4],
        CellType::Hexa8 => &[0, 3, 2, 1, 4, 7, 6, 5],
        CellType::Hexa20 => &[
            0, 3, 2, 1, 4, 7, 6, 5, 11, 10, 9, 8, 19, 18, 17, 16, 12, 15, 14, 13,
        ],
        CellType::Tetra10 => &[0, 2, 1, 3, 6, 5, 4, 7, 9, 8],
        CellType::Penta15 => &[0, 2, 1, 3, 5, 4, 8, 7, 6, 14, 13, 12, 9, 11, 10],
        _ => &[],
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
            // `M2 = N0 N1` (comp005b.mail) and `NOM = G` read as their
            // names.
            .split(|c: char| c.is_whitespace() || c == ',' || c == '=')
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
        // Records may wrap, so the short one cannot be told for sure: the
        // first line that starts a record with fewer fields than a record
        // and is not continued by a line of the missing count.
        let mut count = 0;
        let mut suspect = None;
        for (i, (l, t)) in body.iter().enumerate() {
            let continued = body
                .get(i + 1)
                .is_some_and(|(_, n)| (t.len() + n.len()).is_multiple_of(arity));
            if suspect.is_none() && count % arity == 0 && t.len() < arity && !continued {
                suspect = Some((*l, t.len()));
            }
            count += t.len();
        }
        let (line, n) =
            suspect.unwrap_or((toks[toks.len() - toks.len() % arity].0, toks.len() % arity));
        return Err(err(
            line,
            format!(
                "a record of {what} has {arity} fields (a name and {}); this one has {n} (the sub-file holds {} fields, not a multiple of {arity})",
                arity - 1,
                toks.len()
            ),
        ));
    }
    Ok(toks
        .chunks(arity)
        .map(|c| (c[0].0, c.iter().map(|x| x.1).collect()))
        .collect())
}

fn number(tok: &str, line: usize) -> Result<f64, MailError> {
    let x = tok
        .replace(['D', 'd'], "e")
        .parse::<f64>()
        .map_err(|_| err(line, format!("'{tok}' is not a number")))?;
    if x.is_finite() {
        Ok(x)
    } else {
        Err(err(
            line,
            format!("the coordinate '{tok}' is not a finite number"),
        ))
    }
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
                let group = if header.len() == 2 && header[0].eq_ignore_ascii_case("NOM") {
                    header[1].to_string()
                } else if header.is_empty() {
                    if members.is_empty() {
                        return Err(err(line, format!("{key} without a group name")));
                    }
                    members.remove(0).1
                } else {
                    return Err(err(
                        line,
                        format!(
                            "unexpected '{}' after {key} (expected NOM=<group name> or nothing)",
                            header.join(" ")
                        ),
                    ));
                };
                pending.push((line, nodes, group, members));
            }
            "COOR_1D" => {
                return Err(err(
                    line,
                    "not implemented yet: COOR_1D (aster reads 2D and 3D meshes)",
                ))
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
                let perm = to_med(t);
                if t.dim() == 3 && dim == Some(2) {
                    return Err(err(
                        line,
                        format!("{other} cells in a mesh of COOR_2D: a volume cell needs COOR_3D"),
                    ));
                }
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
                            med[i] = listed[p];
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
    if coords.is_empty() {
        return Err(err(
            text.lines().count(),
            "the file holds no node (no COOR_2D or COOR_3D sub-file)",
        ));
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
        let Some((first, i)) = index
            .iter()
            .filter(|(n, &i)| **n != format!("{prefix}{}", i + 1))
            .map(|(n, &i)| (n, i))
            .min_by_key(|(_, i)| *i)
        else {
            continue;
        };
        // A name of the form N<k> / M<k> that is not the k-th: NOEUD= and
        // MAILLE= with that name reach another node or cell.
        let clash = index
            .iter()
            .filter_map(|(n, &i)| {
                let k: usize = n.strip_prefix(prefix)?.parse().ok()?;
                (k >= 1 && k - 1 != i).then_some((n, i))
            })
            .min_by_key(|(_, i)| *i);
        let mut a = format!(
            "the {what} names of the file are not kept: a {what} is {prefix}<k>, the k-th of the file, in NOEUD=/MAILLE= and in messages (the file's {first} is {prefix}{}); groups keep their members",
            i + 1
        );
        if let Some((n, j)) = clash {
            a.push_str(&format!(
                "; CAUTION: the file's own {n} is {prefix}{} here, so {n} in a command is another {what} than the file's: address it by a group",
                j + 1
            ));
        }
        alarms.push(a);
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
