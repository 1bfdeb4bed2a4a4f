//! Result fields in MED files: nodal fields (DEPL, VITE, ACCE...) and
//! cell-constant fields, at several time steps.
//!
//! In the file a field is `/CHA/<name>` with one child per step, named
//! "%020d%020d" of (numdt, numit); each step holds one group per entity
//! kind: `NOE` for nodal values, `MAI.<TYP>` for values on cells of one
//! type, `NOE.<TYP>` for values per element node. Inside, a profile group
//! (`MED_NO_PROFILE_INTERNAL` = every entity) holds `CO`, the values
//! component-major. Gauss-point fields (SIEF_ELGA, VARI_ELGA) are
//! `MAI.<TYP>` groups with `@GAU` naming a localization in `/GAUSS` and
//! `@NGA` points per cell. [`read_elem_fields`] skips them;
//! [`read_cell_mean_fields`] reads them, and per-element-node values
//! (`NOE.<TYP>`, ELNO), as their mean over each cell, which needs no
//! `/GAUSS` tree: a picture coloured per cell is all it serves.

use std::path::Path;

use hdf5::{File, Group};

use super::h5util::{self, Ctx};
use super::read::{mesh_step, pick_mesh, read_mesh_from};
use super::write::{self, check_name, create_file, invalid, write_mesh_into, NO_PROFILE};
use super::{MedError, MedErrorKind};
use crate::mesh::{CellType, Mesh};

/// Component names hold at most 16 characters in MED.
const MAX_COMPONENT: usize = 16;
/// MED type code of float64 values (`@TYP` of a field).
const MED_FLOAT64: i64 = 6;

/// A field with values at the nodes, at several steps. code_aster names a
/// result field `<result name padded with '_' to 8><field>`, e.g.
/// `RESU____DEPL`; the caller passes that full name.
#[derive(Debug, Clone, PartialEq)]
pub struct NodalField {
    pub name: String,
    pub components: Vec<String>,
    pub steps: Vec<FieldStep>,
}

/// A field with one value per cell (and component), at several steps.
/// `values` of a step are `ncells * ncomp`, cell-major, in mesh cell order;
/// cells a file gives no value (field defined on some cell types only)
/// read as NaN.
#[derive(Debug, Clone, PartialEq)]
pub struct ElemField {
    pub name: String,
    pub components: Vec<String>,
    pub steps: Vec<FieldStep>,
}

/// One step of a field: code_aster's NUME_ORDRE as `numdt`, INST as `time`.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldStep {
    pub numdt: i32,
    pub time: f64,
    /// `nentities * ncomp` values, entity-major (all components of the
    /// first node or cell, then the next).
    pub values: Vec<f64>,
}

/// Where a field lives, with what the writer and reader need to lay out
/// its values.
enum Support<'a> {
    Nodes(usize),
    /// Cells, grouped as stored: per type, the mesh indices of its cells.
    Cells(&'a [(CellType, Vec<usize>)]),
    /// Cells as above, and blocks with several values per cell (Gauss
    /// points, element nodes) reduced to their mean per cell.
    CellMeans(&'a [(CellType, Vec<usize>)]),
}

impl Support<'_> {
    fn count(&self) -> usize {
        match self {
            Support::Nodes(n) => *n,
            Support::Cells(b) | Support::CellMeans(b) => b.iter().map(|(_, ids)| ids.len()).sum(),
        }
    }
    fn what(&self) -> &'static str {
        match self {
            Support::Nodes(_) => "nodes",
            Support::Cells(_) | Support::CellMeans(_) => "cells",
        }
    }
    fn averages(&self) -> bool {
        matches!(self, Support::CellMeans(_))
    }
}

/// Writes `mesh` and its nodal fields at every step to a new MED file, so
/// that ParaView or SALOME play the steps as an animation.
pub fn write_result(path: &Path, mesh: &Mesh, fields: &[NodalField]) -> Result<(), MedError> {
    write_result_fields(path, mesh, fields, &[])
}

/// [`write_result`] plus cell-constant fields.
pub fn write_result_fields(
    path: &Path,
    mesh: &Mesh,
    nodal: &[NodalField],
    cells: &[ElemField],
) -> Result<(), MedError> {
    let ctx = Ctx { path };
    write::validate_mesh(ctx, mesh)?;
    let all: Vec<(&str, &[String], &[FieldStep], bool)> = nodal
        .iter()
        .map(|f| {
            (
                f.name.as_str(),
                f.components.as_slice(),
                f.steps.as_slice(),
                true,
            )
        })
        .chain(cells.iter().map(|f| {
            (
                f.name.as_str(),
                f.components.as_slice(),
                f.steps.as_slice(),
                false,
            )
        }))
        .collect();
    for (i, (name, comps, steps, is_nodal)) in all.iter().enumerate() {
        let n = if *is_nodal {
            mesh.nnodes()
        } else {
            mesh.ncells()
        };
        validate_field(ctx, name, comps, steps, n)?;
        if all[..i].iter().any(|f| f.0 == *name) {
            return Err(invalid(ctx, format!("two fields are named '{name}'")));
        }
    }
    let file = create_file(ctx)?;
    let blocks = write_mesh_into(ctx, &file, mesh)?;
    if !all.is_empty() {
        let cha = h5util::group(ctx, &file, "CHA")?;
        for (name, comps, steps, is_nodal) in all {
            let support = if is_nodal {
                Support::Nodes(mesh.nnodes())
            } else {
                Support::Cells(&blocks)
            };
            write_field(ctx, &cha, &mesh.name, name, comps, steps, &support)?;
        }
    }
    file.close().map_err(|e| ctx.h5("closing the file", e))
}

fn validate_field(
    ctx: Ctx,
    name: &str,
    comps: &[String],
    steps: &[FieldStep],
    n: usize,
) -> Result<(), MedError> {
    check_name(ctx, "field", name, write::MAX_MESH_NAME)?;
    if comps.is_empty() {
        return Err(invalid(ctx, format!("field '{name}' has no component")));
    }
    for c in comps {
        check_name(ctx, &format!("field '{name}' component"), c, MAX_COMPONENT)?;
    }
    for (k, s) in steps.iter().enumerate() {
        if s.values.len() != n * comps.len() {
            return Err(invalid(
                ctx,
                format!(
                    "field '{name}' step numdt={} has {} values, expected {n} x {} components = {}",
                    s.numdt,
                    s.values.len(),
                    comps.len(),
                    n * comps.len()
                ),
            ));
        }
        if steps[..k].iter().any(|o| o.numdt == s.numdt) {
            return Err(invalid(
                ctx,
                format!("field '{name}' has two steps with numdt={}", s.numdt),
            ));
        }
    }
    Ok(())
}

fn step_name(numdt: i64, numit: i64) -> String {
    format!("{numdt:020}{numit:020}")
}

fn write_field(
    ctx: Ctx,
    cha: &Group,
    mesh_name: &str,
    name: &str,
    comps: &[String],
    steps: &[FieldStep],
    support: &Support,
) -> Result<(), MedError> {
    let nco = comps.len();
    let fg = h5util::ordered_group(ctx, cha, name)?;
    h5util::put_str(ctx, &fg, "MAI", mesh_name)?;
    h5util::put_int(ctx, &fg, "TYP", MED_FLOAT64)?;
    h5util::put_int(ctx, &fg, "NCO", nco as i64)?;
    let names: String = comps.iter().map(|c| h5util::pad(c, 16)).collect();
    h5util::put_str(ctx, &fg, "NOM", &names)?;
    h5util::put_str(ctx, &fg, "UNI", &" ".repeat(16 * nco))?;
    h5util::put_str(ctx, &fg, "UNT", "")?;
    // Cells of a type where the field is absent at every step (NaN: the
    // skin cells of a Gauss field's mean per cell, which have no point)
    // get no block, as code_aster writes a field only where it is
    // defined, rather than a block of NaN.
    let defined = |ids: &[usize]| {
        steps.iter().any(|s| {
            ids.iter()
                .any(|&i| s.values[i * nco..(i + 1) * nco].iter().any(|v| !v.is_nan()))
        })
    };
    for s in steps {
        let sg = h5util::group(ctx, &fg, &step_name(i64::from(s.numdt), -1))?;
        h5util::put_int(ctx, &sg, "NDT", i64::from(s.numdt))?;
        h5util::put_int(ctx, &sg, "NOR", -1)?;
        h5util::put_f64(ctx, &sg, "PDT", s.time)?;
        h5util::put_int(ctx, &sg, "RDT", -1)?;
        h5util::put_int(ctx, &sg, "ROR", -1)?;
        match support {
            Support::Nodes(n) => {
                let ids: Vec<usize> = (0..*n).collect();
                write_block(ctx, &sg, "NOE", &ids, &s.values, nco)?;
            }
            Support::Cells(blocks) | Support::CellMeans(blocks) => {
                for (t, ids) in blocks.iter().filter(|(_, ids)| defined(ids)) {
                    write_block(
                        ctx,
                        &sg,
                        &format!("MAI.{}", t.med_name()),
                        ids,
                        &s.values,
                        nco,
                    )?;
                }
            }
        }
    }
    Ok(())
}

/// One entity block of a step: values of entities `ids` (indices into the
/// entity-major `values`), stored component-major.
fn write_block(
    ctx: Ctx,
    sg: &Group,
    entity: &str,
    ids: &[usize],
    values: &[f64],
    nco: usize,
) -> Result<(), MedError> {
    let eg = h5util::group(ctx, sg, entity)?;
    h5util::put_str(ctx, &eg, "PFL", NO_PROFILE)?;
    h5util::put_str(ctx, &eg, "GAU", "")?;
    let pg = h5util::group(ctx, &eg, NO_PROFILE)?;
    h5util::put_int(ctx, &pg, "NBR", ids.len() as i64)?;
    h5util::put_int(ctx, &pg, "NGA", 1)?;
    h5util::put_str(ctx, &pg, "GAU", "")?;
    let mut co = Vec::with_capacity(ids.len() * nco);
    for k in 0..nco {
        co.extend(ids.iter().map(|&i| values[i * nco + k]));
    }
    h5util::put_f64s(ctx, &pg, "CO", &co)?;
    Ok(())
}

// ---------------------------------------------------------------- reading

/// Reads every nodal field defined on mesh `mesh_name` (first mesh when
/// `None`), fields in name order, steps in (numdt, numit) order. Steps that
/// carry no nodal values are left out; fields with none at all (cell or
/// Gauss-point fields) are not returned.
pub fn read_nodal_fields(
    path: &Path,
    mesh_name: Option<&str>,
) -> Result<Vec<NodalField>, MedError> {
    let ctx = Ctx { path };
    let file = h5util::open_read(path)?;
    super::read::check_version(ctx, &file)?;
    let mname = pick_mesh(ctx, &file, mesh_name)?;
    let nn = super::read::node_count(ctx, &file, &mname)?;
    Ok(read_fields(ctx, &file, &mname, &Support::Nodes(nn))?
        .into_iter()
        .map(|(name, components, steps)| NodalField {
            name,
            components,
            steps,
        })
        .collect())
}

/// Reads every cell-constant field (`MAI.<TYP>` values without Gauss
/// points) on mesh `mesh_name` (first mesh when `None`), values in the cell
/// order of [`super::read_mesh`].
pub fn read_elem_fields(path: &Path, mesh_name: Option<&str>) -> Result<Vec<ElemField>, MedError> {
    read_cell_fields(path, mesh_name, false)
}

/// Every field with values on cells, one value per cell and component:
/// cell-constant fields as they are, Gauss-point fields (SIEF_ELGA,
/// VARI_ELGA as code_aster writes them) and per-element-node fields as
/// the mean over each cell's points (NaN values left out of the mean).
/// That is what a picture coloured per cell shows; the Gauss point
/// positions (`/GAUSS`) are not needed for it and not read.
pub fn read_cell_mean_fields(
    path: &Path,
    mesh_name: Option<&str>,
) -> Result<Vec<ElemField>, MedError> {
    read_cell_fields(path, mesh_name, true)
}

/// The fields on cells, with Gauss-point and element-node values either
/// left out (`means` false) or averaged per cell (`means` true).
fn read_cell_fields(
    path: &Path,
    mesh_name: Option<&str>,
    means: bool,
) -> Result<Vec<ElemField>, MedError> {
    let ctx = Ctx { path };
    let file = h5util::open_read(path)?;
    let mesh = read_mesh_from(ctx, &file, mesh_name)?;
    let blocks = write::type_blocks(&mesh);
    let support = if means {
        Support::CellMeans(&blocks)
    } else {
        Support::Cells(&blocks)
    };
    Ok(read_fields(ctx, &file, &mesh.name, &support)?
        .into_iter()
        .map(|(name, components, steps)| ElemField {
            name,
            components,
            steps,
        })
        .collect())
}

type RawField = (String, Vec<String>, Vec<FieldStep>);

fn read_fields(
    ctx: Ctx,
    file: &File,
    mesh: &str,
    support: &Support,
) -> Result<Vec<RawField>, MedError> {
    // Make sure the mesh itself is there before looking at its fields.
    mesh_step(ctx, file, mesh)?;
    let Ok(cha) = file.group("CHA") else {
        return Ok(Vec::new());
    };
    let mut out = Vec::new();
    for fname in h5util::child_groups(ctx, &cha, "/CHA")? {
        let fw = format!("field '{fname}'");
        let fg = cha.group(&fname).map_err(|e| ctx.h5(&fw, e))?;
        let on = h5util::str_attr(ctx, &fg, "MAI", &fw)?;
        if on.trim_end() != mesh {
            continue;
        }
        let nco = h5util::int_attr(ctx, &fg, "NCO", &fw)?;
        if !(1..=10_000).contains(&nco) {
            return Err(ctx.inconsistent(format!("{fw}: @NCO = {nco} components")));
        }
        let nco = nco as usize;
        let names = h5util::str_attr(ctx, &fg, "NOM", &fw)?;
        let mut comps = h5util::split_fixed(&names, MAX_COMPONENT);
        if comps.len() < nco {
            return Err(ctx.inconsistent(format!(
                "{fw}: @NOM names {} components but @NCO says {nco}",
                comps.len()
            )));
        }
        comps.truncate(nco);
        let mut steps: Vec<(i64, FieldStep)> = Vec::new();
        for sname in h5util::child_groups(ctx, &fg, &fw)? {
            let sw = format!("{fw} step '{sname}'");
            let sg = fg.group(&sname).map_err(|e| ctx.h5(&sw, e))?;
            let ndt = h5util::int_attr(ctx, &sg, "NDT", &sw)?;
            let nor = h5util::opt_int_attr(ctx, &sg, "NOR", &sw)?.unwrap_or(-1);
            let time = h5util::f64_attr(ctx, &sg, "PDT", &sw)?;
            let numdt = i32::try_from(ndt)
                .map_err(|_| ctx.inconsistent(format!("{sw}: @NDT = {ndt} out of range")))?;
            if let Some(values) = read_step_values(ctx, &sg, &sw, support, nco)? {
                steps.push((
                    nor,
                    FieldStep {
                        numdt,
                        time,
                        values,
                    },
                ));
            }
        }
        if steps.is_empty() {
            continue;
        }
        steps.sort_by_key(|(nor, s)| (s.numdt, *nor));
        out.push((fname, comps, steps.into_iter().map(|(_, s)| s).collect()));
    }
    Ok(out)
}

/// Values of one step on `support`, entity-major, or None when the step
/// has no values of that kind.
fn read_step_values(
    ctx: Ctx,
    sg: &Group,
    sw: &str,
    support: &Support,
    nco: usize,
) -> Result<Option<Vec<f64>>, MedError> {
    let n = support.count();
    match support {
        Support::Nodes(_) => {
            let Ok(eg) = sg.group("NOE") else {
                return Ok(None);
            };
            let ids: Vec<usize> = (0..n).collect();
            let mut values = vec![f64::NAN; n * nco];
            if !read_block(
                ctx,
                &eg,
                &format!("{sw} NOE"),
                &ids,
                &mut values,
                nco,
                support,
            )? {
                return Ok(None);
            }
            Ok(Some(values))
        }
        Support::Cells(blocks) | Support::CellMeans(blocks) => {
            let mut values = vec![f64::NAN; n * nco];
            let mut any = false;
            for ename in h5util::child_groups(ctx, sg, sw)? {
                let tname = match ename.strip_prefix("MAI.") {
                    Some(t) => t,
                    None if support.averages() => match ename.strip_prefix("NOE.") {
                        Some(t) => t,
                        None => continue,
                    },
                    None => continue,
                };
                let ew = format!("{sw} {ename}");
                let t = CellType::from_med_name(tname)
                    .ok_or_else(|| ctx.err(MedErrorKind::UnknownCellType(tname.to_string())))?;
                let ids: &[usize] = blocks
                    .iter()
                    .find(|(bt, _)| *bt == t)
                    .map(|(_, ids)| ids.as_slice())
                    .ok_or_else(|| {
                        ctx.inconsistent(format!(
                            "{ew}: values on {tname} cells, the mesh has none"
                        ))
                    })?;
                let eg = sg.group(&ename).map_err(|e| ctx.h5(&ew, e))?;
                any |= read_block(ctx, &eg, &ew, ids, &mut values, nco, support)?;
            }
            Ok(any.then_some(values))
        }
    }
}

/// The entities of `ids` that profile `name` selects.
fn profile_entities(
    ctx: Ctx,
    eg: &Group,
    ew: &str,
    name: &str,
    ids: &[usize],
) -> Result<Vec<usize>, MedError> {
    let what = format!("{ew}: profile '{name}'");
    let file = eg.file().map_err(|e| ctx.h5(&what, e))?;
    let ds = file
        .group("PROFILS")
        .and_then(|g| g.group(name))
        .and_then(|g| g.dataset("PFL"))
        .map_err(|_| ctx.inconsistent(format!("{what}: no /PROFILS/{name}/PFL")))?;
    h5util::read_ints(ctx, &ds, &what)?
        .into_iter()
        .map(|r| {
            usize::try_from(r)
                .ok()
                .filter(|&r| (1..=ids.len()).contains(&r))
                .map(|r| ids[r - 1])
                .ok_or_else(|| {
                    ctx.inconsistent(format!("{what}: entity rank {r} outside 1..{}", ids.len()))
                })
        })
        .collect()
}

/// Reads one entity block into `values` at entities `ids`. Returns false
/// for blocks of another kind (Gauss points, several values per entity)
/// unless `support` averages them: MED stores those component-major, then
/// entity by entity, the points of one entity together.
fn read_block(
    ctx: Ctx,
    eg: &Group,
    ew: &str,
    ids: &[usize],
    values: &mut [f64],
    nco: usize,
    support: &Support,
) -> Result<bool, MedError> {
    let gau = if h5util::has_attr(eg, "GAU") {
        h5util::str_attr(ctx, eg, "GAU", ew)?
    } else {
        String::new()
    };
    if !gau.trim().is_empty() && !support.averages() {
        return Ok(false);
    }
    let pfl = h5util::str_attr(ctx, eg, "PFL", ew)?;
    let pfl = pfl.trim_end();
    // A profile restricts the values to some entities of the block:
    // `/PROFILS/<name>/PFL` holds their 1-based ranks in it; the others
    // keep NaN.
    let (pname, profiled);
    let ids: &[usize] = if pfl == NO_PROFILE || pfl.is_empty() {
        pname = NO_PROFILE;
        ids
    } else {
        pname = pfl;
        profiled = profile_entities(ctx, eg, ew, pfl, ids)?;
        &profiled
    };
    let pg = eg
        .group(pname)
        .map_err(|_| ctx.inconsistent(format!("{ew}: no '{pname}' group")))?;
    let nga = h5util::opt_int_attr(ctx, &pg, "NGA", ew)?.unwrap_or(1);
    if nga != 1 && !support.averages() {
        return Ok(false);
    }
    if !(1..=1000).contains(&nga) {
        return Err(ctx.inconsistent(format!("{ew}: @NGA = {nga} values per entity")));
    }
    let nga = nga as usize;
    let nbr = h5util::int_attr(ctx, &pg, "NBR", ew)?;
    if nbr != ids.len() as i64 {
        return Err(ctx.inconsistent(format!(
            "{ew}: @NBR = {nbr} values per component, the mesh has {} {}",
            ids.len(),
            support.what()
        )));
    }
    let co = pg
        .dataset("CO")
        .map_err(|_| ctx.inconsistent(format!("{ew}: no CO dataset")))?;
    let co = h5util::read_f64s(ctx, &co, &format!("{ew}/CO"))?;
    if co.len() != ids.len() * nga * nco {
        return Err(ctx.inconsistent(format!(
            "{ew}/CO has {} values, expected {} entities x {nga} points x {nco} components",
            co.len(),
            ids.len()
        )));
    }
    let m = ids.len();
    for k in 0..nco {
        for (j, &i) in ids.iter().enumerate() {
            let at = (k * m + j) * nga;
            let (sum, count) = co[at..at + nga]
                .iter()
                .filter(|v| !v.is_nan())
                .fold((0.0, 0usize), |(s, c), v| (s + v, c + 1));
            values[i * nco + k] = if count > 0 {
                sum / count as f64
            } else {
                f64::NAN
            };
        }
    }
    Ok(true)
}
