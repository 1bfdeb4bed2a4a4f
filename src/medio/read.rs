//! MED mesh reader (MED 3.x and 4.x layouts, unstructured meshes).
//!
//! Everything read from the file is checked before it is used as an index,
//! so a damaged file yields a [`MedError`] naming what is wrong, never a
//! panic or an out-of-range cell.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use hdf5::{File, Group};
use indexmap::IndexMap;

use super::h5util::{self, Ctx};
use super::{MedError, MedErrorKind};
use crate::mesh::{Cell, CellType, Mesh};

/// Names of the meshes of a MED file, in HDF5 name order (the order
/// `read_mesh(path, None)` picks from).
pub fn mesh_names(path: &Path) -> Result<Vec<String>, MedError> {
    let file = h5util::open_read(path)?;
    let ctx = Ctx { path };
    check_version(ctx, &file)?;
    let ens = ens_maa(ctx, &file)?;
    h5util::child_groups(ctx, &ens, "/ENS_MAA")
}

/// Reads mesh `name` (or the first mesh when `None`) of a MED 3.x/4.x file.
///
/// Cells come type by type in increasing MED type code (PO1, SE2, SE3, TR3,
/// QU4, TR6, QU8, TE4, PE6, HE8, P15, H20), in file order within a type:
/// the numbering code_aster gives them (M1, M2...). Groups are listed in
/// alphabetical order, their members in increasing index order; a group
/// carried only by families without members is kept, empty.
pub fn read_mesh(path: &Path, name: Option<&str>) -> Result<Mesh, MedError> {
    read_mesh_with_notes(path, name).map(|(mesh, _)| mesh)
}

/// [`read_mesh`] with what the file holds that the mesh cannot show: node
/// and cell family numbers that /FAS does not describe (each put its
/// entities in no group). LIRE_MAILLAGE turns these into alarms.
pub fn read_mesh_with_notes(
    path: &Path,
    name: Option<&str>,
) -> Result<(Mesh, Vec<UndescribedFamily>), MedError> {
    let file = h5util::open_read(path)?;
    read_mesh_notes_from(Ctx { path }, &file, name)
}

/// Entities whose family number /FAS/<mesh> does not describe: libmed
/// reads them, their group membership is lost (they belong to no group).
#[derive(Debug, Clone, PartialEq)]
pub struct UndescribedFamily {
    /// Cells (true) or nodes.
    pub cells: bool,
    pub family: i64,
    pub count: usize,
    /// The first such entity, 0-based (code_aster's M or N + 1).
    pub first: usize,
}

pub(crate) fn check_version(ctx: Ctx, file: &File) -> Result<(), MedError> {
    // Files without INFOS_GENERALES exist (hand-made); only a stated
    // version outside 3.x/4.x is refused, because 2.x has another tree.
    if let Ok(info) = file.group("INFOS_GENERALES") {
        if let Some(maj) = h5util::opt_int_attr(ctx, &info, "MAJ", "/INFOS_GENERALES")? {
            if !(3..=4).contains(&maj) {
                let min = h5util::opt_int_attr(ctx, &info, "MIN", "/INFOS_GENERALES")?.unwrap_or(0);
                return Err(ctx.err(MedErrorKind::Unsupported(format!(
                    "MED file format {maj}.{min}; only MED 3.x and 4.x files are read"
                ))));
            }
        }
    }
    Ok(())
}

pub(crate) fn ens_maa(ctx: Ctx, file: &File) -> Result<Group, MedError> {
    file.group("ENS_MAA").map_err(|_| {
        let top = file.member_names().unwrap_or_default();
        ctx.err(MedErrorKind::NotMed(format!(
            "no /ENS_MAA group (top-level objects: {})",
            if top.is_empty() {
                "none".to_string()
            } else {
                top.join(", ")
            }
        )))
    })
}

/// Resolves the mesh name asked for, or the first one.
pub(crate) fn pick_mesh(ctx: Ctx, file: &File, name: Option<&str>) -> Result<String, MedError> {
    let ens = ens_maa(ctx, file)?;
    let names = h5util::child_groups(ctx, &ens, "/ENS_MAA")?;
    match name {
        None => names
            .into_iter()
            .next()
            .ok_or_else(|| ctx.err(MedErrorKind::NoMesh)),
        Some(n) => {
            if names.iter().any(|m| m == n) {
                Ok(n.to_string())
            } else {
                Err(ctx.err(MedErrorKind::MeshNotFound {
                    wanted: n.to_string(),
                    available: names,
                }))
            }
        }
    }
}

/// The computing-step group of a mesh. A plain mesh has one, named after
/// (-1, -1); with several, the first in name order is the initial state.
pub(crate) fn mesh_step(ctx: Ctx, file: &File, mesh: &str) -> Result<(Group, Group), MedError> {
    let what = format!("/ENS_MAA/{mesh}");
    let mg = file
        .group(&format!("ENS_MAA/{mesh}"))
        .map_err(|e| ctx.h5(&what, e))?;
    let steps = h5util::child_groups(ctx, &mg, &what)?;
    let first = steps.first().ok_or_else(|| {
        ctx.inconsistent(format!(
            "mesh '{mesh}' has no computing-step group (MED 3/4 layout expected)"
        ))
    })?;
    let sg = mg.group(first).map_err(|e| ctx.h5(&what, e))?;
    Ok((mg, sg))
}

/// Number of nodes of a mesh, from its coordinates dataset.
pub(crate) fn node_count(ctx: Ctx, file: &File, mesh: &str) -> Result<usize, MedError> {
    let (mg, sg) = mesh_step(ctx, file, mesh)?;
    let esp = space_dim(ctx, &mg, mesh)?;
    let coo = sg
        .dataset("NOE/COO")
        .map_err(|_| ctx.inconsistent(format!("mesh '{mesh}': no NOE/COO dataset")))?;
    let size = coo.size();
    if !size.is_multiple_of(esp) {
        return Err(ctx.inconsistent(format!(
            "mesh '{mesh}': NOE/COO has {size} values, not a multiple of the space dimension {esp}"
        )));
    }
    Ok(size / esp)
}

fn space_dim(ctx: Ctx, mg: &Group, mesh: &str) -> Result<usize, MedError> {
    let what = format!("mesh '{mesh}'");
    let esp = match h5util::opt_int_attr(ctx, mg, "ESP", &what)? {
        Some(e) => e,
        None => h5util::int_attr(ctx, mg, "DIM", &what)?,
    };
    if !(1..=3).contains(&esp) {
        return Err(ctx.inconsistent(format!(
            "{what}: space dimension @ESP = {esp}, expected 1, 2 or 3"
        )));
    }
    Ok(esp as usize)
}

pub(crate) fn read_mesh_from(ctx: Ctx, file: &File, name: Option<&str>) -> Result<Mesh, MedError> {
    read_mesh_notes_from(ctx, file, name).map(|(mesh, _)| mesh)
}

fn read_mesh_notes_from(
    ctx: Ctx,
    file: &File,
    name: Option<&str>,
) -> Result<(Mesh, Vec<UndescribedFamily>), MedError> {
    check_version(ctx, file)?;
    let mname = pick_mesh(ctx, file, name)?;
    let what = format!("mesh '{mname}'");
    let (mg, sg) = mesh_step(ctx, file, &mname)?;
    if let Some(t) = h5util::opt_int_attr(ctx, &mg, "TYP", &what)? {
        if t != 0 {
            return Err(ctx.err(MedErrorKind::Unsupported(format!(
                "{what} is a structured mesh (@TYP = {t}); only unstructured meshes are read"
            ))));
        }
    }
    let esp = space_dim(ctx, &mg, &mname)?;

    // Nodes: component-major coordinates x1..xn, y1..yn, z1..zn.
    let coo = sg
        .dataset("NOE/COO")
        .map_err(|_| ctx.inconsistent(format!("{what}: no NOE/COO dataset (node coordinates)")))?;
    let xyz = h5util::read_f64s(ctx, &coo, &format!("{what}: NOE/COO"))?;
    if !xyz.len().is_multiple_of(esp) {
        return Err(ctx.inconsistent(format!(
            "{what}: NOE/COO has {} values, not a multiple of the space dimension {esp}",
            xyz.len()
        )));
    }
    let nn = xyz.len() / esp;
    if let Some(nbr) = h5util::opt_int_attr(ctx, &coo, "NBR", &format!("{what}: NOE/COO"))? {
        if nbr != nn as i64 {
            return Err(ctx.inconsistent(format!(
                "{what}: NOE/COO@NBR says {nbr} nodes but the dataset holds {nn} (x{esp} values)"
            )));
        }
    }
    let coords: Vec<[f64; 3]> = (0..nn)
        .map(|i| {
            let mut p = [0.0; 3];
            for (k, c) in p.iter_mut().enumerate().take(esp) {
                *c = xyz[k * nn + i];
            }
            p
        })
        .collect();
    let node_fam = read_fam(ctx, &sg, "NOE/FAM", nn, &format!("{what}: NOE/FAM"))?;

    // Cells, one group per type, taken in increasing type code.
    let mut blocks: Vec<(CellType, Vec<Vec<usize>>, Vec<i64>)> = Vec::new();
    if let Ok(mai) = sg.group("MAI") {
        for tname in h5util::child_groups(ctx, &mai, &format!("{what}: MAI"))? {
            let t = CellType::from_med_name(&tname)
                .ok_or_else(|| ctx.err(MedErrorKind::UnknownCellType(tname.clone())))?;
            let tw = format!("{what}: MAI/{tname}");
            let tg = mai.group(&tname).map_err(|e| ctx.h5(&tw, e))?;
            if let Some(geo) = h5util::opt_int_attr(ctx, &tg, "GEO", &tw)? {
                if geo != i64::from(t.med_code()) {
                    return Err(ctx.inconsistent(format!(
                        "{tw}: @GEO = {geo} but {tname} has code {}",
                        t.med_code()
                    )));
                }
            }
            if let Some(pfl) = h5util::has_attr(&tg, "PFL")
                .then(|| h5util::str_attr(ctx, &tg, "PFL", &tw))
                .transpose()?
            {
                let pfl = pfl.trim();
                if !pfl.is_empty() && pfl != "MED_NO_PROFILE_INTERNAL" {
                    return Err(ctx.err(MedErrorKind::Unsupported(format!(
                        "{tw}: connectivity with profile '{pfl}'"
                    ))));
                }
            }
            let nod = tg
                .dataset("NOD")
                .map_err(|_| ctx.inconsistent(format!("{tw}: no NOD dataset (connectivity)")))?;
            let conn = h5util::read_ints(ctx, &nod, &format!("{tw}/NOD"))?;
            let npc = t.nnodes();
            if !conn.len().is_multiple_of(npc) {
                return Err(ctx.inconsistent(format!(
                    "{tw}/NOD has {} node numbers, not a multiple of {npc} nodes per {tname}",
                    conn.len()
                )));
            }
            let nc = conn.len() / npc;
            if let Some(nbr) = h5util::opt_int_attr(ctx, &nod, "NBR", &format!("{tw}/NOD"))? {
                if nbr != nc as i64 {
                    return Err(ctx.inconsistent(format!(
                        "{tw}/NOD@NBR says {nbr} cells but the dataset holds {nc} cells of {npc} nodes"
                    )));
                }
            }
            let mut cells = Vec::with_capacity(nc);
            for c in 0..nc {
                let mut nodes = Vec::with_capacity(npc);
                for k in 0..npc {
                    // node-rank-major: node k of every cell, then node k+1
                    let v = conn[k * nc + c];
                    if v < 1 || v > nn as i64 {
                        return Err(ctx.inconsistent(format!(
                            "{tw}/NOD: cell {} refers to node {v}, outside 1..{nn}",
                            c + 1
                        )));
                    }
                    nodes.push((v - 1) as usize);
                }
                cells.push(nodes);
            }
            let fam = read_fam(ctx, &tg, "FAM", nc, &format!("{tw}/FAM"))?;
            blocks.push((t, cells, fam));
        }
    }
    blocks.sort_by_key(|b| b.0.med_code());

    let mut cells = Vec::new();
    let mut cell_fam = Vec::new();
    for (t, conn, fam) in blocks {
        for nodes in conn {
            cells.push(Cell { kind: t, nodes });
        }
        cell_fam.extend(fam);
    }

    // Families -> groups.
    let (node_fams, cell_fams) = read_families(ctx, file, &mname)?;
    let node_groups = groups_from_families(&node_fam, &node_fams);
    let cell_groups = groups_from_families(&cell_fam, &cell_fams);
    let mut notes = undescribed(&node_fam, &node_fams, false);
    notes.extend(undescribed(&cell_fam, &cell_fams, true));

    Ok((
        Mesh {
            name: mname,
            dim: esp,
            coords,
            cells,
            cell_groups,
            node_groups,
        },
        notes,
    ))
}

/// The nonzero family numbers of `fam` absent from `fams`, with how many
/// entities carry each and the first one, by family number.
fn undescribed(fam: &[i64], fams: &Families, cells: bool) -> Vec<UndescribedFamily> {
    let mut out: BTreeMap<i64, UndescribedFamily> = BTreeMap::new();
    for (i, &f) in fam.iter().enumerate() {
        if f == 0 || fams.contains_key(&f) {
            continue;
        }
        out.entry(f)
            .or_insert(UndescribedFamily {
                cells,
                family: f,
                count: 0,
                first: i,
            })
            .count += 1;
    }
    out.into_values().collect()
}

/// Family numbers of `n` entities; absent dataset = all in family 0.
fn read_fam(ctx: Ctx, g: &Group, name: &str, n: usize, what: &str) -> Result<Vec<i64>, MedError> {
    match g.dataset(name) {
        Err(_) => Ok(vec![0; n]),
        Ok(ds) => {
            let v = h5util::read_ints(ctx, &ds, what)?;
            if v.len() != n {
                return Err(ctx.inconsistent(format!(
                    "{what} has {} family numbers for {n} entities",
                    v.len()
                )));
            }
            Ok(v)
        }
    }
}

type Families = HashMap<i64, Vec<String>>;

/// Node and cell families of a mesh: family number -> group names.
fn read_families(ctx: Ctx, file: &File, mesh: &str) -> Result<(Families, Families), MedError> {
    let mut out = (Families::new(), Families::new());
    let Ok(fas) = file.group(&format!("FAS/{mesh}")) else {
        return Ok(out);
    };
    for (kind, map) in [("NOEUD", &mut out.0), ("ELEME", &mut out.1)] {
        let Ok(kg) = fas.group(kind) else { continue };
        let kw = format!("/FAS/{mesh}/{kind}");
        for fname in h5util::child_groups(ctx, &kg, &kw)? {
            let fw = format!("{kw}/{fname}");
            let fg = kg.group(&fname).map_err(|e| ctx.h5(&fw, e))?;
            let num = h5util::int_attr(ctx, &fg, "NUM", &fw)?;
            // Described, even without groups.
            map.entry(num).or_default();
            // A family without GRO is legal (medcoupling writes such).
            let Ok(gro) = fg.group("GRO") else { continue };
            let Ok(nom) = gro.dataset("NOM") else {
                continue;
            };
            let names = h5util::read_names80(ctx, &nom, &format!("{fw}/GRO/NOM"))?;
            if let Some(nbr) = h5util::opt_int_attr(ctx, &gro, "NBR", &format!("{fw}/GRO"))? {
                if nbr != names.len() as i64 {
                    return Err(ctx.inconsistent(format!(
                        "{fw}/GRO@NBR says {nbr} groups but NOM holds {}",
                        names.len()
                    )));
                }
            }
            map.entry(num)
                .or_default()
                .extend(names.into_iter().filter(|n| !n.is_empty()));
        }
    }
    Ok(out)
}

/// Group -> sorted members, groups in alphabetical order. Family numbers
/// not described in /FAS put their entities in no group, as libmed does.
fn groups_from_families(fam: &[i64], fams: &Families) -> IndexMap<String, Vec<usize>> {
    let mut groups: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for names in fams.values() {
        for g in names {
            groups.entry(g.clone()).or_default();
        }
    }
    for (i, f) in fam.iter().enumerate() {
        if *f == 0 {
            continue;
        }
        if let Some(names) = fams.get(f) {
            for g in names {
                if let Some(v) = groups.get_mut(g) {
                    if v.last() != Some(&i) {
                        v.push(i);
                    }
                }
            }
        }
    }
    groups.into_iter().collect()
}
