//! MED mesh writer.
//!
//! The file is stamped MED 4.0.0: MED 4.1 tools (code_aster, SALOME,
//! Debian's mdump) read it, medcoupling and meshio too, and unlike a 4.1
//! stamp it needs no HDF5 bitfield attributes on fields (which the safe
//! `hdf5` binding cannot create). Only the attributes those readers need
//! are written (see `docs/mesh.md`).

use std::collections::HashMap;
use std::path::Path;

use hdf5::{File, Group};
use indexmap::IndexMap;

use super::h5util::{self, Ctx};
use super::{MedError, MedErrorKind};
use crate::mesh::{CellType, Mesh};

/// Profile name meaning "every entity" in MED.
pub(crate) const NO_PROFILE: &str = "MED_NO_PROFILE_INTERNAL";
/// Name of the single computing step of a mesh: "%020d%020d" of (-1, -1).
pub(crate) const MESH_STEP: &str = "-0000000000000000001-0000000000000000001";

/// Longest names MED stores: mesh and field names 64, group names 80.
pub(crate) const MAX_MESH_NAME: usize = 64;
const MAX_GROUP_NAME: usize = 80;

/// Writes `mesh` to a new MED file (replacing any file at `path`).
///
/// Cells are stored by type in increasing MED type code, in mesh order
/// within a type, so a mesh whose cells are already sorted that way (all
/// meshes from [`super::read_mesh`]) is read back identically; otherwise
/// the cells come back renumbered, groups following them. Groups become
/// families, one per distinct set of groups (numbered 1, 2... for nodes and
/// -1, -2... for cells in order of first use); an empty group gets a family
/// of its own that no entity uses, so it survives a round trip.
pub fn write_mesh(path: &Path, mesh: &Mesh) -> Result<(), MedError> {
    let ctx = Ctx { path };
    validate_mesh(ctx, mesh)?;
    let file = create_file(ctx)?;
    write_mesh_into(ctx, &file, mesh)?;
    file.close().map_err(|e| ctx.h5("closing the file", e))
}

pub(crate) fn invalid(ctx: Ctx, msg: impl Into<String>) -> MedError {
    ctx.err(MedErrorKind::InvalidInput(msg.into()))
}

pub(crate) fn check_name(ctx: Ctx, what: &str, name: &str, max: usize) -> Result<(), MedError> {
    if name.is_empty() {
        return Err(invalid(ctx, format!("{what} name is empty")));
    }
    if !name.is_ascii() || name.contains('\0') {
        return Err(invalid(
            ctx,
            format!("{what} name '{name}' must be ASCII without NUL"),
        ));
    }
    if name.len() > max {
        return Err(invalid(
            ctx,
            format!(
                "{what} name '{name}' has {} characters, MED allows {max}",
                name.len()
            ),
        ));
    }
    Ok(())
}

/// Everything that would produce an unreadable or lossy file is refused
/// before the file is touched.
pub(crate) fn validate_mesh(ctx: Ctx, mesh: &Mesh) -> Result<(), MedError> {
    check_name(ctx, "mesh", &mesh.name, MAX_MESH_NAME)?;
    if !(1..=3).contains(&mesh.dim) {
        return Err(invalid(
            ctx,
            format!("mesh space dimension {} (expected 1, 2 or 3)", mesh.dim),
        ));
    }
    let nn = mesh.nnodes();
    for (i, p) in mesh.coords.iter().enumerate() {
        if p[mesh.dim..].iter().any(|&c| c != 0.0) {
            return Err(invalid(
                ctx,
                format!(
                    "node {} has a non-zero coordinate beyond the space dimension {}: {p:?}",
                    i + 1,
                    mesh.dim
                ),
            ));
        }
    }
    for (c, cell) in mesh.cells.iter().enumerate() {
        if cell.nodes.len() != cell.kind.nnodes() {
            return Err(invalid(
                ctx,
                format!(
                    "cell {} ({}) has {} nodes, expected {}",
                    c + 1,
                    cell.kind.aster_name(),
                    cell.nodes.len(),
                    cell.kind.nnodes()
                ),
            ));
        }
        if let Some(&n) = cell.nodes.iter().find(|&&n| n >= nn) {
            return Err(invalid(
                ctx,
                format!(
                    "cell {} refers to node index {n}, mesh has {nn} nodes",
                    c + 1
                ),
            ));
        }
        if cell.kind.dim() > mesh.dim {
            return Err(invalid(
                ctx,
                format!(
                    "cell {} is a {}D {} in a {}D space",
                    c + 1,
                    cell.kind.dim(),
                    cell.kind.aster_name(),
                    mesh.dim
                ),
            ));
        }
    }
    for (what, groups, n) in [
        ("cell", &mesh.cell_groups, mesh.ncells()),
        ("node", &mesh.node_groups, nn),
    ] {
        for (g, members) in groups {
            check_name(ctx, &format!("{what} group"), g, MAX_GROUP_NAME)?;
            if g.trim_end() != g {
                return Err(invalid(
                    ctx,
                    format!("{what} group name '{g}' ends with blanks, MED would lose them"),
                ));
            }
            if let Some(&i) = members.iter().find(|&&i| i >= n) {
                return Err(invalid(
                    ctx,
                    format!("{what} group '{g}' refers to index {i}, mesh has {n} {what}s"),
                ));
            }
        }
    }
    Ok(())
}

pub(crate) fn create_file(ctx: Ctx) -> Result<File, MedError> {
    let file = File::create(ctx.path)
        .map_err(|e| ctx.err(MedErrorKind::Io(format!("cannot create the file: {e}"))))?;
    let info = h5util::group(ctx, &file, "INFOS_GENERALES")?;
    h5util::put_int(ctx, &info, "MAJ", 4)?;
    h5util::put_int(ctx, &info, "MIN", 0)?;
    h5util::put_int(ctx, &info, "REL", 0)?;
    Ok(file)
}

/// Mesh cell indices of each type present, in the order they are stored.
pub(crate) fn type_blocks(mesh: &Mesh) -> Vec<(CellType, Vec<usize>)> {
    let mut types: Vec<CellType> = CellType::ALL.to_vec();
    types.sort_by_key(|t| t.med_code());
    types
        .into_iter()
        .map(|t| {
            let ids: Vec<usize> = (0..mesh.ncells())
                .filter(|&c| mesh.cells[c].kind == t)
                .collect();
            (t, ids)
        })
        .filter(|(_, ids)| !ids.is_empty())
        .collect()
}

/// One family per distinct set of groups: family number of each entity
/// and, per family, its number and group names (in mesh group order).
/// `sign` is +1 for nodes, -1 for cells.
fn families(
    n: usize,
    groups: &IndexMap<String, Vec<usize>>,
    sign: i64,
) -> (Vec<i64>, Vec<(i64, Vec<String>)>) {
    let mut sets: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (gi, (_, members)) in groups.iter().enumerate() {
        for &i in members {
            if sets[i].last() != Some(&gi) {
                sets[i].push(gi);
            }
        }
    }
    let mut number_of: HashMap<Vec<usize>, i64> = HashMap::new();
    let mut fams: Vec<(i64, Vec<String>)> = Vec::new();
    let mut fam = vec![0i64; n];
    for (i, set) in sets.into_iter().enumerate() {
        if set.is_empty() {
            continue;
        }
        let next = sign * (fams.len() as i64 + 1);
        let num = *number_of.entry(set.clone()).or_insert_with(|| {
            let names = set
                .iter()
                .filter_map(|&g| groups.get_index(g).map(|(k, _)| k.clone()))
                .collect();
            fams.push((next, names));
            next
        });
        fam[i] = num;
    }
    // Empty groups: a family of their own, used by no entity.
    for (g, members) in groups {
        if members.is_empty() {
            let next = sign * (fams.len() as i64 + 1);
            fams.push((next, vec![g.clone()]));
        }
    }
    (fam, fams)
}

fn family_name(num: i64, groups: &[String]) -> String {
    let mut s = format!("FAM_{num}");
    for g in groups {
        s.push('_');
        s.push_str(g);
    }
    // MED family names hold 64 characters; the number keeps them unique.
    s.chars().take(64).collect()
}

/// Writes the mesh tree (`/ENS_MAA/<mesh>` and `/FAS/<mesh>`) into an open
/// file; returns the stored cell order per type (for cell fields).
pub(crate) fn write_mesh_into(
    ctx: Ctx,
    file: &File,
    mesh: &Mesh,
) -> Result<Vec<(CellType, Vec<usize>)>, MedError> {
    let esp = mesh.dim;
    let mdim = mesh.cells.iter().map(|c| c.kind.dim()).max().unwrap_or(esp);
    let ens = match file.group("ENS_MAA") {
        Ok(g) => g,
        Err(_) => h5util::group(ctx, file, "ENS_MAA")?,
    };
    let mg = h5util::group(ctx, &ens, &mesh.name)?;
    h5util::put_int(ctx, &mg, "DIM", mdim as i64)?;
    h5util::put_int(ctx, &mg, "ESP", esp as i64)?;
    h5util::put_int(ctx, &mg, "TYP", 0)?; // unstructured
    h5util::put_int(ctx, &mg, "SRT", 0)?;
    h5util::put_int(ctx, &mg, "REP", 0)?; // cartesian
    h5util::put_int(ctx, &mg, "NXT", -1)?;
    h5util::put_int(ctx, &mg, "NXI", -1)?;
    h5util::put_str(ctx, &mg, "DES", "written by aster")?;
    let axes: String = ["X", "Y", "Z"][..esp]
        .iter()
        .map(|a| h5util::pad(a, 16))
        .collect();
    h5util::put_str(ctx, &mg, "NOM", &axes)?;
    h5util::put_str(ctx, &mg, "UNI", &" ".repeat(16 * esp))?;
    h5util::put_str(ctx, &mg, "UNT", "")?;

    let sg = h5util::group(ctx, &mg, MESH_STEP)?;
    for (k, v) in [
        ("NDT", -1),
        ("NOR", -1),
        ("NXT", -1),
        ("NXI", -1),
        ("PVT", -1),
        ("PVI", -1),
        ("CGT", 1),
    ] {
        h5util::put_int(ctx, &sg, k, v)?;
    }
    h5util::put_f64(ctx, &sg, "PDT", 0.0)?;

    let nn = mesh.nnodes();
    let noe = h5util::group(ctx, &sg, "NOE")?;
    h5util::put_int(ctx, &noe, "CGT", 1)?;
    h5util::put_int(ctx, &noe, "CGS", 1)?;
    h5util::put_str(ctx, &noe, "PFL", NO_PROFILE)?;
    let mut xyz = Vec::with_capacity(nn * esp);
    for k in 0..esp {
        xyz.extend(mesh.coords.iter().map(|p| p[k]));
    }
    let coo = h5util::put_f64s(ctx, &noe, "COO", &xyz)?;
    h5util::put_int(ctx, &coo, "NBR", nn as i64)?;
    h5util::put_int(ctx, &coo, "CGT", 1)?;
    let (node_fam, node_fams) = families(nn, &mesh.node_groups, 1);
    let fam = h5util::put_i64s(ctx, &noe, "FAM", &node_fam)?;
    h5util::put_int(ctx, &fam, "NBR", nn as i64)?;
    h5util::put_int(ctx, &fam, "CGT", 1)?;

    let (cell_fam, cell_fams) = families(mesh.ncells(), &mesh.cell_groups, -1);
    let blocks = type_blocks(mesh);
    let mai = h5util::group(ctx, &sg, "MAI")?;
    h5util::put_int(ctx, &mai, "CGT", 1)?;
    for (t, ids) in &blocks {
        let tg = h5util::group(ctx, &mai, t.med_name())?;
        h5util::put_int(ctx, &tg, "GEO", i64::from(t.med_code()))?;
        h5util::put_int(ctx, &tg, "CGT", 1)?;
        h5util::put_int(ctx, &tg, "CGS", 1)?;
        h5util::put_str(ctx, &tg, "PFL", NO_PROFILE)?;
        let nc = ids.len();
        let npc = t.nnodes();
        let mut conn = vec![0i64; nc * npc];
        for (j, &c) in ids.iter().enumerate() {
            for (k, &n) in mesh.cells[c].nodes.iter().enumerate() {
                conn[k * nc + j] = n as i64 + 1; // node-rank-major, 1-based
            }
        }
        let nod = h5util::put_i64s(ctx, &tg, "NOD", &conn)?;
        h5util::put_int(ctx, &nod, "NBR", nc as i64)?;
        h5util::put_int(ctx, &nod, "CGT", 1)?;
        let f: Vec<i64> = ids.iter().map(|&c| cell_fam[c]).collect();
        let fd = h5util::put_i64s(ctx, &tg, "FAM", &f)?;
        h5util::put_int(ctx, &fd, "NBR", nc as i64)?;
        h5util::put_int(ctx, &fd, "CGT", 1)?;
    }

    let fas_root = match file.group("FAS") {
        Ok(g) => g,
        Err(_) => h5util::group(ctx, file, "FAS")?,
    };
    let fas = h5util::group(ctx, &fas_root, &mesh.name)?;
    let zero = h5util::ordered_group(ctx, &fas, "FAMILLE_ZERO")?;
    h5util::put_int(ctx, &zero, "NUM", 0)?;
    write_families(ctx, &fas, "NOEUD", &node_fams)?;
    write_families(ctx, &fas, "ELEME", &cell_fams)?;
    Ok(blocks)
}

fn write_families(
    ctx: Ctx,
    fas: &Group,
    kind: &str,
    fams: &[(i64, Vec<String>)],
) -> Result<(), MedError> {
    let kg = h5util::ordered_group(ctx, fas, kind)?;
    for (num, groups) in fams {
        let fg = h5util::group(ctx, &kg, &family_name(*num, groups))?;
        h5util::put_int(ctx, &fg, "NUM", *num)?;
        let gro = h5util::group(ctx, &fg, "GRO")?;
        h5util::put_int(ctx, &gro, "NBR", groups.len() as i64)?;
        let names: Vec<&str> = groups.iter().map(String::as_str).collect();
        h5util::put_names80(ctx, &gro, "NOM", &names)?;
    }
    Ok(())
}
