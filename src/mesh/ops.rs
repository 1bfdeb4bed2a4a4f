//! Mesh operations with code_aster's semantics (docs/semantics.md §2):
//! node groups of `DEFI_GROUP`/`CREA_GROUP_NO`, skin orientation of
//! `MODI_MAILLAGE`/`ORIE_PEAU_2D|3D`, linearisation of
//! `CREA_MAILLAGE`/`QUAD_LINE`, and the geometric checks (Jacobian signs,
//! measures) that tell whether a cell is valid for code_aster.
//!
//! The functions never print: what code_aster would print as an alarm or an
//! information line is returned in a [`Report`] so that the command layer
//! writes it to the message file in its own format. Fatal conditions are a
//! [`MeshError`]; where code_aster has a message id for the condition it is
//! kept in `id`, otherwise the id starts with `ASTER_RS_` (ours).

use std::fmt;

use super::quadrature::{self, Fpg, QuadRule};
use super::shape;
use super::vec3::{cross, dot, sub};
use super::{Cell, CellType, Mesh};

/// A non-fatal condition code_aster reports as an alarm (`<A>`).
#[derive(Debug, Clone, PartialEq)]
pub struct MeshAlarm {
    pub id: &'static str,
    pub text: String,
}

/// A fatal condition (`<F>`/`<E>`): the command fails, the mesh is unchanged.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshError {
    pub id: &'static str,
    pub text: String,
}

impl MeshError {
    fn new(id: &'static str, text: impl Into<String>) -> MeshError {
        MeshError {
            id,
            text: text.into(),
        }
    }
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.id, self.text)
    }
}

impl std::error::Error for MeshError {}

impl From<MeshError> for String {
    fn from(e: MeshError) -> String {
        e.to_string()
    }
}

/// What an operation has to say besides its result.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Report {
    pub alarms: Vec<MeshAlarm>,
    /// Lines code_aster prints at INFO=1 (e.g. per-group orientation counts).
    pub infos: Vec<String>,
    /// Names of the groups created, in creation order.
    pub created: Vec<String>,
}

impl Report {
    fn alarm(&mut self, id: &'static str, text: String) {
        self.alarms.push(MeshAlarm { id, text });
    }
}

// ---------------------------------------------------------------------------
// DEFI_GROUP / CREA_GROUP_NO
// ---------------------------------------------------------------------------

/// `CRIT_NOEUD` of `CREA_GROUP_NO=_F(GROUP_MA=...)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CritNoeud {
    #[default]
    Tous,
    Sommet,
    Milieu,
    Centre,
}

/// Local node indices (0-based) a criterion selects in a cell. None of the
/// cell types aster supports has a face or volume centre node, so `Centre`
/// selects nothing, like `Milieu` on a linear cell.
fn selected_local_nodes(kind: CellType, crit: CritNoeud) -> std::ops::Range<usize> {
    match crit {
        CritNoeud::Tous => 0..kind.nnodes(),
        CritNoeud::Sommet => 0..kind.nvertices(),
        CritNoeud::Milieu => kind.nvertices()..kind.nnodes(),
        CritNoeud::Centre => 0..0,
    }
}

fn cell_group<'m>(mesh: &'m Mesh, name: &str) -> Result<&'m Vec<usize>, MeshError> {
    mesh.cell_groups.get(name).ok_or_else(|| {
        MeshError::new(
            "ELEMENTS_62",
            format!(
                "the cell group {name} is not in the mesh {}",
                mesh_label(mesh)
            ),
        )
    })
}

fn node_group<'m>(mesh: &'m Mesh, name: &str) -> Result<&'m Vec<usize>, MeshError> {
    mesh.node_groups.get(name).ok_or_else(|| {
        MeshError::new(
            "ASTER_RS_GROUP_NO_UNKNOWN",
            format!(
                "the node group {name} is not in the mesh {}",
                mesh_label(mesh)
            ),
        )
    })
}

fn mesh_label(mesh: &Mesh) -> &str {
    if mesh.name.is_empty() {
        "(unnamed)"
    } else {
        &mesh.name
    }
}

/// Nodes of some cells meeting a criterion, ascending and without
/// duplicates, as `gmgnre` stores them.
fn nodes_of_cells_crit(mesh: &Mesh, cells: &[usize], crit: CritNoeud) -> Vec<usize> {
    let mut seen = vec![false; mesh.nnodes()];
    for &c in cells {
        let cell = &mesh.cells[c];
        for k in selected_local_nodes(cell.kind, crit) {
            seen[cell.nodes[k]] = true;
        }
    }
    seen.iter()
        .enumerate()
        .filter_map(|(i, &s)| s.then_some(i))
        .collect()
}

/// Adds a node group the way `addGrpNo` does: an existing name is an alarm
/// and the old group is kept; an empty list still creates the group.
fn add_node_group(mesh: &mut Mesh, report: &mut Report, name: &str, nodes: Vec<usize>) {
    if mesh.node_groups.contains_key(name) {
        report.alarm(
            "MODELISA7_9",
            format!("the node group {name} already exists: it is not modified"),
        );
        return;
    }
    mesh.node_groups.insert(name.to_string(), nodes);
    report.created.push(name.to_string());
}

/// `CREA_GROUP_NO=_F(TOUT_GROUP_MA='OUI')`: one node group per cell group,
/// same name, all nodes.
pub fn crea_group_no_tout_group_ma(mesh: &mut Mesh) -> Report {
    let mut report = Report::default();
    let groups: Vec<(String, Vec<usize>)> = mesh
        .cell_groups
        .iter()
        .map(|(n, c)| (n.clone(), c.clone()))
        .collect();
    for (name, cells) in groups {
        let nodes = nodes_of_cells_crit(mesh, &cells, CritNoeud::Tous);
        add_node_group(mesh, &mut report, &name, nodes);
    }
    report
}

/// `CREA_GROUP_NO=_F(GROUP_MA=groups, [NOM=names], CRIT_NOEUD=crit)`.
///
/// An empty selection (MILIEU on linear cells) still creates the group, as
/// code_aster does; the trap is that the group exists but holds nothing.
pub fn crea_group_no_from_group_ma<S: AsRef<str>>(
    mesh: &mut Mesh,
    groups: &[S],
    names: Option<&[S]>,
    crit: CritNoeud,
) -> Result<Report, MeshError> {
    if let Some(names) = names {
        if names.len() != groups.len() {
            return Err(MeshError::new(
                "MODELISA7_8",
                format!(
                    "NOM must have as many names as GROUP_MA ({} names for {} groups)",
                    names.len(),
                    groups.len()
                ),
            ));
        }
    }
    // All groups are checked before any is created: code_aster raises the
    // error for every missing group before building anything.
    let mut missing = Vec::new();
    for g in groups {
        if !mesh.cell_groups.contains_key(g.as_ref()) {
            missing.push(g.as_ref().to_string());
        }
    }
    if !missing.is_empty() {
        return Err(MeshError::new(
            "ELEMENTS_62",
            format!(
                "cell group(s) not in the mesh {}: {}",
                mesh_label(mesh),
                missing.join(", ")
            ),
        ));
    }
    let mut report = Report::default();
    for (i, g) in groups.iter().enumerate() {
        let cells = cell_group(mesh, g.as_ref())?.clone();
        let nodes = nodes_of_cells_crit(mesh, &cells, crit);
        let name = match names {
            Some(n) => n[i].as_ref(),
            None => g.as_ref(),
        };
        add_node_group(mesh, &mut report, name, nodes);
    }
    Ok(report)
}

/// Set operations of `CREA_GROUP_NO` (`UNION`, `INTERSEC`, `DIFFE`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GroupSetOp {
    /// First group's nodes, then the new nodes of each next group in order.
    Union,
    /// Nodes of the first group found in every other, first group's order.
    Intersec,
    /// First group minus each next group, first group's order.
    Diffe,
}

fn check_new_name(mesh: &Mesh, name: &str) -> Result<(), MeshError> {
    if mesh.node_groups.contains_key(name) {
        return Err(MeshError::new(
            "SOUSTRUC_37",
            format!("the node group {name} already exists"),
        ));
    }
    Ok(())
}

/// Creates `name` from a non-empty result, else reports SOUSTRUC_38 and
/// creates nothing (any later use of the name then fails).
fn add_nonempty(mesh: &mut Mesh, report: &mut Report, name: &str, nodes: Vec<usize>) {
    if nodes.is_empty() {
        report.alarm(
            "SOUSTRUC_38",
            format!("the node group {name} would be empty: it is not created"),
        );
    } else {
        mesh.node_groups.insert(name.to_string(), nodes);
        report.created.push(name.to_string());
    }
}

/// `CREA_GROUP_NO=_F(UNION|INTERSEC|DIFFE=groups, NOM=name)`.
pub fn crea_group_no_set<S: AsRef<str>>(
    mesh: &mut Mesh,
    op: GroupSetOp,
    groups: &[S],
    name: &str,
) -> Result<Report, MeshError> {
    check_new_name(mesh, name)?;
    let Some(first) = groups.first() else {
        return Err(MeshError::new(
            "ASTER_RS_EMPTY_LIST",
            "the list of node groups is empty",
        ));
    };
    let mut current = node_group(mesh, first.as_ref())?.clone();
    for g in &groups[1..] {
        let other = node_group(mesh, g.as_ref())?;
        let mut in_other = vec![false; mesh.nnodes()];
        for &n in other {
            in_other[n] = true;
        }
        match op {
            GroupSetOp::Union => {
                let mut in_cur = vec![false; mesh.nnodes()];
                for &n in &current {
                    in_cur[n] = true;
                }
                for &n in other {
                    if !in_cur[n] {
                        in_cur[n] = true;
                        current.push(n);
                    }
                }
            }
            GroupSetOp::Intersec => current.retain(|&n| in_other[n]),
            GroupSetOp::Diffe => current.retain(|&n| !in_other[n]),
        }
    }
    let mut report = Report::default();
    add_nonempty(mesh, &mut report, name, current);
    Ok(report)
}

/// `CREA_GROUP_NO=_F(DIFFE=groups, NOM=name)`.
pub fn crea_group_no_diffe<S: AsRef<str>>(
    mesh: &mut Mesh,
    groups: &[S],
    name: &str,
) -> Result<Report, MeshError> {
    crea_group_no_set(mesh, GroupSetOp::Diffe, groups, name)
}

/// Normal of `OPTION='PLAN'`: `VECT_NORMALE` or `ANGL_NAUT` (degrees).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PlaneNormal<'a> {
    Vect(&'a [f64]),
    AnglNaut(&'a [f64]),
}

/// True when every node has the same z: code_aster's "Z_CST" test, which
/// decides whether a mesh is treated as 2D by PLAN and ORIE_PEAU.
pub fn is_z_constant(mesh: &Mesh) -> bool {
    match mesh.coords.first() {
        None => true,
        Some(p0) => mesh.coords.iter().all(|p| p[2] == p0[2]),
    }
}

/// `CREA_GROUP_NO=_F(OPTION='PLAN', NOM, POINT, VECT_NORMALE|ANGL_NAUT,
/// PRECISION)`: every node of the mesh whose distance to the plane (a line
/// in 2D) is at most `precision`, an absolute distance.
pub fn crea_group_no_plan(
    mesh: &mut Mesh,
    name: &str,
    point: &[f64],
    normal: PlaneNormal<'_>,
    precision: f64,
) -> Result<Report, MeshError> {
    check_new_name(mesh, name)?;
    // NaN must fail too, hence the explicit test.
    if precision.is_nan() || precision <= 0.0 {
        return Err(MeshError::new(
            "ASTER_RS_PRECISION",
            format!("PRECISION must be > 0 (got {precision})"),
        ));
    }
    let dim = if is_z_constant(mesh) { 2 } else { 3 };
    if point.len() != dim {
        return Err(MeshError::new(
            "ASTER_RS_PLAN_DIM",
            format!(
                "POINT must have {dim} components for this {dim}D mesh (got {})",
                point.len()
            ),
        ));
    }
    let n: [f64; 3] = match normal {
        PlaneNormal::Vect(v) => {
            if v.len() != dim {
                return Err(MeshError::new(
                    "ASTER_RS_PLAN_DIM",
                    format!(
                        "VECT_NORMALE must have {dim} components for this {dim}D mesh (got {})",
                        v.len()
                    ),
                ));
            }
            [v[0], v[1], if dim == 3 { v[2] } else { 0.0 }]
        }
        PlaneNormal::AnglNaut(a) => {
            let need = if dim == 2 { 1 } else { 2 };
            if a.len() < need {
                return Err(MeshError::new(
                    "ASTER_RS_PLAN_DIM",
                    format!(
                        "ANGL_NAUT needs {need} angle(s) for this {dim}D mesh (got {})",
                        a.len()
                    ),
                ));
            }
            let al = a[0].to_radians();
            if dim == 2 {
                [al.cos(), al.sin(), 0.0]
            } else {
                let be = a[1].to_radians();
                [al.cos() * be.cos(), al.sin() * be.cos(), -be.sin()]
            }
        }
    };
    let norm = super::vec3::norm(n);
    if norm.is_nan() || norm <= 0.0 || !norm.is_finite() {
        return Err(MeshError::new(
            "ASTER_RS_PLAN_NORMAL",
            "the normal vector is zero",
        ));
    }
    let n = [n[0] / norm, n[1] / norm, n[2] / norm];
    let x0 = [point[0], point[1], if dim == 3 { point[2] } else { 0.0 }];
    let nodes: Vec<usize> = mesh
        .coords
        .iter()
        .enumerate()
        .filter(|(_, p)| {
            let mut d = (p[0] - x0[0]) * n[0] + (p[1] - x0[1]) * n[1];
            if dim == 3 {
                d += (p[2] - x0[2]) * n[2];
            }
            d.abs() <= precision
        })
        .map(|(i, _)| i)
        .collect();
    let mut report = Report::default();
    add_nonempty(mesh, &mut report, name, nodes);
    Ok(report)
}

/// Envelope of `OPTION='ENV_SPHERE'` or `'ENV_CYLINDRE'` (code_aster's
/// `cgnoes`, `cgnoec`): the nodes whose distance to the centre (to the axis)
/// is RAYON within PRECISION, `|d - RAYON| <= PRECISION`. The envelope is a
/// shell, not a ball: a node at the centre is selected only when RAYON is
/// within PRECISION of 0, which code_aster's RAYON > 0 allows for a small
/// RAYON (how a point is picked by its coordinates).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Envelope<'a> {
    Sphere,
    /// The cylinder's axis through the centre: `VECT_NORMALE` (3
    /// components) or `ANGL_NAUT` (2 angles in degrees).
    Cylinder(PlaneNormal<'a>),
}

/// `CREA_GROUP_NO=_F(OPTION='ENV_SPHERE'|'ENV_CYLINDRE', NOM, POINT, RAYON,
/// PRECISION, ...)`, see [`Envelope`]. As code_aster: RAYON and PRECISION
/// must be > 0 (MODELISA3_83/91, 75/89); the cylinder needs a 3D mesh
/// (MODELISA3_84); the centre has as many components as the mesh has
/// dimensions (2 when every z is equal, code_aster's Z_CST).
pub fn crea_group_no_envelope(
    mesh: &mut Mesh,
    name: &str,
    centre: &[f64],
    envelope: Envelope<'_>,
    radius: f64,
    precision: f64,
) -> Result<Report, MeshError> {
    check_new_name(mesh, name)?;
    // NaN is not finite: it fails too.
    if !radius.is_finite() || radius <= 0.0 {
        return Err(MeshError::new(
            "MODELISA3_83",
            format!("RAYON must be > 0 (got {radius})"),
        ));
    }
    if !precision.is_finite() || precision <= 0.0 {
        return Err(MeshError::new(
            "MODELISA3_91",
            format!("PRECISION must be > 0 (got {precision})"),
        ));
    }
    let dim = if is_z_constant(mesh) { 2 } else { 3 };
    if matches!(envelope, Envelope::Cylinder(_)) && dim != 3 {
        return Err(MeshError::new(
            "MODELISA3_84",
            "OPTION='ENV_CYLINDRE' needs a 3D mesh (every node of this one has the same z)",
        ));
    }
    if centre.len() != dim {
        return Err(MeshError::new(
            "ASTER_RS_PLAN_DIM",
            format!(
                "the centre must have {dim} components for this {dim}D mesh (got {})",
                centre.len()
            ),
        ));
    }
    let x0 = [centre[0], centre[1], if dim == 3 { centre[2] } else { 0.0 }];
    let axis = match envelope {
        Envelope::Sphere => None,
        Envelope::Cylinder(normal) => {
            let a = match normal {
                PlaneNormal::Vect(v) if v.len() == 3 => [v[0], v[1], v[2]],
                PlaneNormal::Vect(v) => {
                    return Err(MeshError::new(
                        "MODELISA3_86",
                        format!("VECT_NORMALE must have 3 components (got {})", v.len()),
                    ))
                }
                PlaneNormal::AnglNaut(a) if a.len() == 2 => {
                    let (al, be) = (a[0].to_radians(), a[1].to_radians());
                    [al.cos() * be.cos(), al.sin() * be.cos(), -be.sin()]
                }
                PlaneNormal::AnglNaut(a) => {
                    return Err(MeshError::new(
                        "MODELISA3_87",
                        format!("ANGL_NAUT must have 2 angles (got {})", a.len()),
                    ))
                }
            };
            let norm = super::vec3::norm(a);
            if !norm.is_finite() || norm <= 0.0 {
                return Err(MeshError::new(
                    "MODELISA3_79",
                    "the axis vector of the cylinder is zero",
                ));
            }
            Some([a[0] / norm, a[1] / norm, a[2] / norm])
        }
    };
    let nodes: Vec<usize> = mesh
        .coords
        .iter()
        .enumerate()
        .filter(|(_, p)| {
            let r = [
                p[0] - x0[0],
                p[1] - x0[1],
                if dim == 3 { p[2] - x0[2] } else { 0.0 },
            ];
            let r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
            let d = match axis {
                None => r2.sqrt(),
                // Distance to the axis: the part of r across it.
                Some(a) => {
                    let along = r[0] * a[0] + r[1] * a[1] + r[2] * a[2];
                    (r2 - along * along).max(0.0).sqrt()
                }
            };
            (d - radius).abs() <= precision
        })
        .map(|(i, _)| i)
        .collect();
    let mut report = Report::default();
    add_nonempty(mesh, &mut report, name, nodes);
    Ok(report)
}

/// `CREA_GROUP_NO=_F(OPTION='SEGM_DROI_ORDO', NOM, GROUP_NO|NOEUD,
/// GROUP_NO_ORIG, GROUP_NO_EXTR, PRECISION, CRITERE)` (code_aster's
/// `cgnoso`/`oreino`): the nodes given, ordered by their projection on the
/// segment from `orig` to `extr`. Nothing is selected: every node must lie
/// on the segment, within PRECISION of its line (ABSOLU: the distance;
/// RELATIF: the distance over the segment's length) and between its ends,
/// and no two may project to the same point; code_aster stops on any of
/// these (its alarms SOUSTRUC_22, 86 and 23, then the assertion on their
/// count), and so does this, naming the first offending node.
pub fn crea_group_no_segm_droi_ordo(
    mesh: &mut Mesh,
    name: &str,
    nodes: &[usize],
    (orig, extr): (usize, usize),
    precision: f64,
    relative: bool,
) -> Result<Report, MeshError> {
    check_new_name(mesh, name)?;
    if nodes.is_empty() {
        return Err(MeshError::new("MODELISA3_99", "there is no node to order"));
    }
    let a = mesh.coords[orig];
    let b = mesh.coords[extr];
    let ab = sub(b, a);
    let ab2 = dot(ab, ab);
    if ab2 == 0.0 {
        return Err(MeshError::new(
            "SOUSTRUC_20",
            format!(
                "the origin N{} and the end N{} of the segment are at the same point",
                orig + 1,
                extr + 1
            ),
        ));
    }
    let mut seen = vec![false; mesh.nnodes()];
    let mut keyed: Vec<(f64, usize)> = Vec::with_capacity(nodes.len());
    for &n in nodes {
        if std::mem::replace(&mut seen[n], true) {
            continue;
        }
        let am = sub(mesh.coords[n], a);
        let c = dot(am, ab) / ab2;
        let off = sub(am, [c * ab[0], c * ab[1], c * ab[2]]);
        let dist = dot(off, off).sqrt();
        let measured = if relative { dist / ab2.sqrt() } else { dist };
        if measured > precision || measured.is_nan() {
            return Err(MeshError::new(
                "SOUSTRUC_22",
                format!(
                    "node N{} is {dist:e} from the line of the segment, more than PRECISION = {precision:e} ({})",
                    n + 1,
                    if relative { "RELATIF: over the segment's length" } else { "ABSOLU" }
                ),
            ));
        }
        if (c < 0.0 || dot(am, am) > ab2) && (dot(am, am) - ab2) / ab2 > f64::EPSILON {
            return Err(MeshError::new(
                "SOUSTRUC_86",
                format!(
                    "node N{} projects outside the segment (abscissa {c:e} of its length)",
                    n + 1
                ),
            ));
        }
        keyed.push((c, n));
    }
    // Stable, as code_aster's bubble sort.
    keyed.sort_by(|x, y| x.0.total_cmp(&y.0));
    if let Some(w) = keyed.windows(2).find(|w| w[0].0 == w[1].0) {
        return Err(MeshError::new(
            "SOUSTRUC_23",
            format!(
                "nodes N{} and N{} have the same projection on the segment",
                w[0].1 + 1,
                w[1].1 + 1
            ),
        ));
    }
    let mut report = Report::default();
    add_nonempty(
        mesh,
        &mut report,
        name,
        keyed.into_iter().map(|(_, n)| n).collect(),
    );
    Ok(report)
}

/// `CREA_GROUP_NO=_F(NOEUD=nodes, NOM=name)`: the nodes in the order
/// written, each once.
pub fn crea_group_no_nodes(
    mesh: &mut Mesh,
    nodes: &[usize],
    name: &str,
) -> Result<Report, MeshError> {
    check_new_name(mesh, name)?;
    let mut seen = vec![false; mesh.nnodes()];
    let nodes: Vec<usize> = nodes
        .iter()
        .copied()
        .filter(|&n| !std::mem::replace(&mut seen[n], true))
        .collect();
    let mut report = Report::default();
    add_nonempty(mesh, &mut report, name, nodes);
    Ok(report)
}

/// Which cells `TYPE_MAILLE` keeps in `CREA_GROUP_MA`: `TOUT`, a
/// dimension (`1D`, `2D`, `3D`) or one cell type (`HEXA8`...).
pub fn cell_type_filter(mesh: &Mesh, cells: &mut Vec<usize>, type_maille: &str) {
    let keep = |k: CellType| match type_maille {
        "TOUT" => true,
        "1D" => k.dim() == 1,
        "2D" => k.dim() == 2,
        "3D" => k.dim() == 3,
        other => k.aster_name() == other,
    };
    cells.retain(|&c| keep(mesh.cells[c].kind));
}

/// `CREA_GROUP_MA=_F(INTERSEC|DIFFE=groups)`: the cells of the first group
/// found in every other (INTERSEC) or in none of the others (DIFFE),
/// sorted as every cell group.
pub fn cell_group_set<S: AsRef<str>>(
    mesh: &Mesh,
    op: GroupSetOp,
    groups: &[S],
) -> Result<Vec<usize>, MeshError> {
    let Some(first) = groups.first() else {
        return Err(MeshError::new(
            "ASTER_RS_EMPTY_LIST",
            "the list of cell groups is empty",
        ));
    };
    let mut current = cell_group(mesh, first.as_ref())?.clone();
    for g in &groups[1..] {
        let mut in_other = vec![false; mesh.ncells()];
        for &c in cell_group(mesh, g.as_ref())? {
            in_other[c] = true;
        }
        match op {
            GroupSetOp::Union => {
                for (c, &inside) in in_other.iter().enumerate() {
                    if inside && !current.contains(&c) {
                        current.push(c);
                    }
                }
            }
            GroupSetOp::Intersec => current.retain(|&c| in_other[c]),
            GroupSetOp::Diffe => current.retain(|&c| !in_other[c]),
        }
    }
    current.sort_unstable();
    current.dedup();
    Ok(current)
}

/// `CREA_GROUP_MA=_F(UNION=groups, NOM=name)`: the first group's cells,
/// then the new cells of each next group, kept sorted as every cell group.
/// An existing name or an empty result follow the node-group rules.
pub fn crea_group_ma_union<S: AsRef<str>>(
    mesh: &mut Mesh,
    groups: &[S],
    name: &str,
) -> Result<Report, MeshError> {
    if mesh.cell_groups.contains_key(name) {
        return Err(MeshError::new(
            "SOUSTRUC_37",
            format!("the cell group {name} already exists"),
        ));
    }
    let mut seen = vec![false; mesh.ncells()];
    for g in groups {
        for &c in cell_group(mesh, g.as_ref())? {
            seen[c] = true;
        }
    }
    let cells: Vec<usize> = seen
        .iter()
        .enumerate()
        .filter_map(|(i, &s)| s.then_some(i))
        .collect();
    let mut report = Report::default();
    if cells.is_empty() {
        report.alarm(
            "SOUSTRUC_38",
            format!("the cell group {name} would be empty: it is not created"),
        );
    } else {
        mesh.cell_groups.insert(name.to_string(), cells);
        report.created.push(name.to_string());
    }
    Ok(report)
}

// ---------------------------------------------------------------------------
// MODI_MAILLAGE / ORIE_PEAU_2D, ORIE_PEAU_3D
// ---------------------------------------------------------------------------

/// Which keyword: `ORIE_PEAU_2D` (SEG skins) or `ORIE_PEAU_3D` (TRIA/QUAD).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OrieDim {
    D2,
    D3,
}

/// Result of an orientation: counts over all the groups treated.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct OrieReport {
    pub reoriented: usize,
    /// Skin cells with no support cell: left as they were.
    pub not_processed: usize,
    pub report: Report,
}

/// Connectivity permutation that reverses a skin cell while keeping every
/// mid-node on its edge: new local node i is old local node `p[i]`.
fn reverse_permutation(kind: CellType) -> Option<&'static [usize]> {
    match kind {
        CellType::Seg2 => Some(&[1, 0]),
        CellType::Seg3 => Some(&[1, 0, 2]),
        CellType::Tria3 => Some(&[2, 1, 0]),
        CellType::Tria6 => Some(&[2, 1, 0, 4, 3, 5]),
        CellType::Quad4 => Some(&[3, 2, 1, 0]),
        CellType::Quad8 => Some(&[3, 2, 1, 0, 6, 5, 4, 7]),
        _ => None,
    }
}

fn vertex_centroid(mesh: &Mesh, cell: &Cell) -> [f64; 3] {
    let nv = cell.kind.nvertices();
    let mut c = [0.0; 3];
    for &n in &cell.nodes[..nv] {
        for (k, ck) in c.iter_mut().enumerate() {
            *ck += mesh.coords[n][k];
        }
    }
    c.map(|v| v / nv as f64)
}

/// Normal used by orilma's test only (not normalised): 3D from the first
/// three nodes, 2D the first edge turned by -90 degrees.
fn skin_normal(mesh: &Mesh, cell: &Cell, dim: OrieDim) -> [f64; 3] {
    let x = |k: usize| mesh.coords[cell.nodes[k]];
    match dim {
        OrieDim::D3 => cross(sub(x(1), x(0)), sub(x(2), x(0))),
        OrieDim::D2 => {
            let t = sub(x(1), x(0));
            [t[1], -t[0], 0.0]
        }
    }
}

/// For each node, the cells of dimension `dim` holding it (only those
/// flagged in `allowed` when given): the candidate supports of skin cells.
fn support_cells_by_node(mesh: &Mesh, dim: usize, allowed: Option<&[bool]>) -> Vec<Vec<usize>> {
    let mut cells_of_node: Vec<Vec<usize>> = vec![Vec::new(); mesh.nnodes()];
    for (ci, cell) in mesh.cells.iter().enumerate() {
        if cell.kind.dim() != dim || allowed.is_some_and(|a| !a[ci]) {
            continue;
        }
        for &n in &cell.nodes {
            if cells_of_node[n].last() != Some(&ci) {
                cells_of_node[n].push(ci);
            }
        }
    }
    cells_of_node
}

/// The cells that hold every node of the skin cell `skin`.
fn supports_of(mesh: &Mesh, cells_of_node: &[Vec<usize>], skin: &Cell) -> Vec<usize> {
    cells_of_node[skin.nodes[0]]
        .iter()
        .copied()
        .filter(|&s| skin.nodes.iter().all(|n| mesh.cells[s].nodes.contains(n)))
        .collect()
}

/// orilma's test: the normal of `skin` points into its support cell.
fn points_into(mesh: &Mesh, skin: &Cell, support: usize, dim: OrieDim) -> bool {
    let n = skin_normal(mesh, skin, dim);
    let xs = vertex_centroid(mesh, &mesh.cells[support]);
    let xk = vertex_centroid(mesh, skin);
    dot(sub(xs, xk), n) > 0.0
}

/// A skin cell whose normal points into the body (DEFI_CONTACT VERI_NORM).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct InwardSkin {
    pub cell: usize,
    /// The volume (or surface) cell it lies on.
    pub support: usize,
}

/// The cells of `cells` whose normal, computed as ORIE_PEAU does, points
/// into the one cell they lie on: segments of a flat mesh on its surface
/// cells, faces of a 3D mesh on its volume cells. A cell lying on no
/// cell or between two has no outside and is not reported; nor are cells
/// of another dimension.
pub fn inward_skin_cells(mesh: &Mesh, cells: &[usize]) -> Vec<InwardSkin> {
    let (dim, skin_dim) = if is_z_constant(mesh) {
        (OrieDim::D2, 1)
    } else {
        (OrieDim::D3, 2)
    };
    let cells_of_node = support_cells_by_node(mesh, skin_dim + 1, None);
    cells
        .iter()
        .filter(|&&c| mesh.cells[c].kind.dim() == skin_dim)
        .filter_map(|&c| {
            let skin = &mesh.cells[c];
            match supports_of(mesh, &cells_of_node, skin).as_slice() {
                [s] if points_into(mesh, skin, *s, dim) => Some(InwardSkin {
                    cell: c,
                    support: *s,
                }),
                _ => None,
            }
        })
        .collect()
}

/// `MODI_MAILLAGE(ORIE_PEAU_2D|ORIE_PEAU_3D=_F(GROUP_MA=groups,
/// [GROUP_MA_SURF|GROUP_MA_VOLU=support_groups]))`: renumbers the skin
/// cells whose normal points into their support cell.
///
/// A skin cell lying between two support cells (an internal face) is an
/// error unless the support groups leave only one: its outside is undefined.
pub fn orie_peau<S: AsRef<str>>(
    mesh: &mut Mesh,
    dim: OrieDim,
    groups: &[S],
    support_groups: Option<&[S]>,
) -> Result<OrieReport, MeshError> {
    let flat = is_z_constant(mesh);
    match dim {
        OrieDim::D2 if !flat => {
            return Err(MeshError::new(
                "MODELISA5_95",
                "ORIE_PEAU_2D needs a 2D mesh (all nodes with the same z)",
            ))
        }
        OrieDim::D3 if flat => {
            return Err(MeshError::new(
                "ASTER_RS_ORIE_PEAU_3D_FLAT",
                "ORIE_PEAU_3D needs a 3D mesh, this one is flat (all nodes with the same z)",
            ))
        }
        _ => {}
    }
    let skin_dim = match dim {
        OrieDim::D2 => 1,
        OrieDim::D3 => 2,
    };
    // Check every group and every cell type before touching anything.
    let mut skin_cells = Vec::new();
    for g in groups {
        let cells = cell_group(mesh, g.as_ref())?;
        for &c in cells {
            let k = mesh.cells[c].kind;
            if k.dim() != skin_dim || reverse_permutation(k).is_none() {
                return Err(MeshError::new(
                    "ASTER_RS_ORIE_PEAU_TYPE",
                    format!(
                        "group {}: cell {} is a {}; {} accepts only {} cells",
                        g.as_ref(),
                        c + 1,
                        k.aster_name(),
                        if skin_dim == 1 {
                            "ORIE_PEAU_2D"
                        } else {
                            "ORIE_PEAU_3D"
                        },
                        if skin_dim == 1 {
                            "SEG2/SEG3"
                        } else {
                            "TRIA3/TRIA6/QUAD4/QUAD8"
                        }
                    ),
                ));
            }
        }
        skin_cells.push((g.as_ref().to_string(), cells.clone()));
    }
    let mut allowed: Option<Vec<bool>> = None;
    if let Some(sup) = support_groups {
        let mut a = vec![false; mesh.ncells()];
        for g in sup {
            for &c in cell_group(mesh, g.as_ref())? {
                a[c] = true;
            }
        }
        allowed = Some(a);
    }
    let cells_of_node = support_cells_by_node(mesh, skin_dim + 1, allowed.as_deref());
    // Cells are turned as they are met (a cell listed in two groups must
    // not be turned twice); an error later puts them all back.
    let original = mesh.cells.clone();
    let mut out = OrieReport::default();
    for (gname, cells) in skin_cells {
        let mut reoriented = 0;
        let mut not_processed = 0;
        for c in cells {
            let skin = mesh.cells[c].clone();
            let supports = supports_of(mesh, &cells_of_node, &skin);
            let support = match supports.as_slice() {
                [] => {
                    not_processed += 1;
                    continue;
                }
                [s] => *s,
                [s1, s2, ..] => {
                    mesh.cells = original;
                    return Err(MeshError::new(
                        "ASTER_RS_ORIE_PEAU_INTERNAL",
                        format!(
                            "group {gname}: cell {} lies between cells {} and {}, \
                             restrict the supports with {}",
                            c + 1,
                            s1 + 1,
                            s2 + 1,
                            if skin_dim == 1 {
                                "GROUP_MA_SURF"
                            } else {
                                "GROUP_MA_VOLU"
                            }
                        ),
                    ));
                }
            };
            if points_into(mesh, &skin, support, dim) {
                let p = reverse_permutation(skin.kind).expect("checked above");
                mesh.cells[c].nodes = p.iter().map(|&k| skin.nodes[k]).collect();
                reoriented += 1;
            }
        }
        let total = mesh.cell_groups[&gname].len();
        out.report.infos.push(format!(
            "TRAITEMENT DU GROUP_MA: {gname} DE {total} MAILLES"
        ));
        out.report
            .infos
            .push(format!("{reoriented} MAILLE(S) ONT ETE ORIENTEE(S)"));
        if not_processed > 0 {
            out.report.infos.push(format!(
                "{not_processed} MAILLE(S) N'ONT PAS ETE TRAITEE(S)"
            ));
        }
        out.reoriented += reoriented;
        out.not_processed += not_processed;
    }
    Ok(out)
}

// ---------------------------------------------------------------------------
// CREA_MAILLAGE / QUAD_LINE
// ---------------------------------------------------------------------------

/// Which cells a CREA_MAILLAGE occurrence selects: all for `None`; an
/// index beyond the mesh is an error.
fn selection_mask(mesh: &Mesh, cells: Option<&[usize]>) -> Result<Vec<bool>, MeshError> {
    let mut selected = vec![cells.is_none(); mesh.ncells()];
    for &c in cells.unwrap_or_default() {
        if c >= mesh.ncells() {
            return Err(MeshError::new(
                "ASTER_RS_CELL_INDEX",
                format!(
                    "cell {} does not exist (the mesh has {})",
                    c + 1,
                    mesh.ncells()
                ),
            ));
        }
        selected[c] = true;
    }
    Ok(selected)
}

/// `CREA_MAILLAGE(MAILLAGE=mesh, QUAD_LINE=_F(TOUT='OUI' | GROUP_MA=...))`:
/// a new mesh where the selected quadratic cells (all cells when `cells` is
/// None) become linear. Cell indices and cell groups are unchanged; nodes
/// used by no cell any more after the conversion are removed only if they
/// were mid-nodes of a converted cell, the others are renumbered compactly
/// in their old order; node groups keep their surviving nodes and a node
/// group left empty is dropped.
pub fn quad_line(mesh: &Mesh, cells: Option<&[usize]>) -> Result<Mesh, MeshError> {
    let selected = selection_mask(mesh, cells)?;
    let convert: Vec<bool> = mesh
        .cells
        .iter()
        .zip(&selected)
        .map(|(c, &s)| s && c.kind.is_quadratic())
        .collect();
    if !convert.iter().any(|&b| b) {
        return Err(MeshError::new(
            "MODELISA3_8",
            "QUAD_LINE: no quadratic cell in the selection",
        ));
    }
    let mut used = vec![false; mesh.nnodes()];
    let mut mid_of_converted = vec![false; mesh.nnodes()];
    for (cell, &conv) in mesh.cells.iter().zip(&convert) {
        let keep = if conv {
            cell.kind.nvertices()
        } else {
            cell.nodes.len()
        };
        for &n in &cell.nodes[..keep] {
            used[n] = true;
        }
        if conv {
            for &n in &cell.nodes[keep..] {
                mid_of_converted[n] = true;
            }
        }
    }
    let mut new_index = vec![usize::MAX; mesh.nnodes()];
    let mut coords = Vec::with_capacity(mesh.nnodes());
    for (i, p) in mesh.coords.iter().enumerate() {
        if used[i] || !mid_of_converted[i] {
            new_index[i] = coords.len();
            coords.push(*p);
        }
    }
    if coords.len() == mesh.nnodes() {
        return Err(MeshError::new(
            "MODELISA4_3",
            "QUAD_LINE: no node can be removed (every mid-node is used by a cell left quadratic)",
        ));
    }
    let new_cells = mesh
        .cells
        .iter()
        .zip(&convert)
        .map(|(cell, &conv)| {
            let (kind, nn) = if conv {
                (cell.kind.linear(), cell.kind.nvertices())
            } else {
                (cell.kind, cell.nodes.len())
            };
            Cell {
                kind,
                nodes: cell.nodes[..nn].iter().map(|&n| new_index[n]).collect(),
            }
        })
        .collect();
    let mut node_groups = indexmap::IndexMap::new();
    for (name, nodes) in &mesh.node_groups {
        let kept: Vec<usize> = nodes
            .iter()
            .filter(|&&n| new_index[n] != usize::MAX)
            .map(|&n| new_index[n])
            .collect();
        if !kept.is_empty() {
            node_groups.insert(name.clone(), kept);
        }
    }
    Ok(Mesh {
        name: mesh.name.clone(),
        dim: mesh.dim,
        coords,
        cells: new_cells,
        cell_groups: mesh.cell_groups.clone(),
        node_groups,
    })
}

/// CREA_MAILLAGE/LINE_QUAD: a copy of `mesh` where every selected linear
/// cell (all when `cells` is `None`) becomes its quadratic counterpart, a
/// node being added at the middle of each edge of those cells, shared by
/// the cells around the edge (straight edges: the mid-node is the midpoint
/// of its two vertices). Existing nodes keep their indices and the new
/// ones follow, in the order the edges are met; cell and node groups are
/// kept as they are (as code_aster: the new nodes join no group, a
/// CREA_GROUP_NO after the command puts them in).
pub fn line_quad(mesh: &Mesh, cells: Option<&[usize]>) -> Result<Mesh, MeshError> {
    let selected = selection_mask(mesh, cells)?;
    if !mesh
        .cells
        .iter()
        .zip(&selected)
        .any(|(c, &s)| s && c.kind.quadratic().is_some())
    {
        return Err(MeshError::new(
            "MODELISA3_8",
            "LINE_QUAD: no linear cell with edges in the selection",
        ));
    }
    let mut coords = mesh.coords.clone();
    let mut mid: std::collections::HashMap<(usize, usize), usize> = Default::default();
    let mut new_cells = Vec::with_capacity(mesh.ncells());
    for (cell, &sel) in mesh.cells.iter().zip(&selected) {
        let Some(kind) = cell.kind.quadratic().filter(|_| sel) else {
            new_cells.push(cell.clone());
            continue;
        };
        let mut nodes = cell.nodes.clone();
        for &(a, b) in kind.mid_edges() {
            let (na, nb) = (cell.nodes[a], cell.nodes[b]);
            let key = (na.min(nb), na.max(nb));
            let n = *mid.entry(key).or_insert_with(|| {
                let (pa, pb) = (mesh.coords[na], mesh.coords[nb]);
                coords.push([
                    0.5 * (pa[0] + pb[0]),
                    0.5 * (pa[1] + pb[1]),
                    0.5 * (pa[2] + pb[2]),
                ]);
                coords.len() - 1
            });
            nodes.push(n);
        }
        new_cells.push(Cell { kind, nodes });
    }
    Ok(Mesh {
        name: mesh.name.clone(),
        dim: mesh.dim,
        coords,
        cells: new_cells,
        cell_groups: mesh.cell_groups.clone(),
        node_groups: mesh.node_groups.clone(),
    })
}

// ---------------------------------------------------------------------------
// Geometry: code_aster's reference elements
// ---------------------------------------------------------------------------

/// For each node of code_aster's internal numbering, its index in MED's
/// (the `numnoa` table of code_aster's MED reader, 0-based). MED numbers the
/// 3D cells in the mirror order of code_aster's reference elements, so a
/// cell is valid for code_aster when, read through this table, its
/// Jacobian is positive on code_aster's reference element.
pub fn med_to_aster(kind: CellType) -> &'static [usize] {
    const ID: [usize; 20] = [
        0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19,
    ];
    match kind {
        CellType::Tetra4 => &[0, 2, 1, 3],
        CellType::Tetra10 => &[0, 2, 1, 3, 6, 5, 4, 7, 9, 8],
        CellType::Penta6 => &[0, 2, 1, 3, 5, 4],
        CellType::Penta15 => &[0, 2, 1, 3, 5, 4, 8, 7, 6, 12, 14, 13, 11, 10, 9],
        CellType::Hexa8 => &[0, 3, 2, 1, 4, 7, 6, 5],
        CellType::Hexa20 => &[
            0, 3, 2, 1, 4, 7, 6, 5, 11, 10, 9, 8, 16, 19, 18, 17, 15, 14, 13, 12,
        ],
        k => &ID[..k.nnodes()],
    }
}

/// The Gauss rule of the mesh checks: code_aster's FPG family of the cell
/// that integrates the geometry of a straight or curved cell exactly
/// (degree 5 per direction on segments, quadrangles and hexahedra, 2 on
/// triangles and tetrahedra, 5 x 5 on prisms).
fn check_rule(kind: CellType) -> QuadRule {
    let fpg = match kind {
        CellType::Poi1 => Fpg::Fpg1,
        CellType::Seg2 | CellType::Seg3 | CellType::Tria3 | CellType::Tria6 => Fpg::Fpg3,
        CellType::Quad4 | CellType::Quad8 => Fpg::Fpg9,
        CellType::Tetra4 | CellType::Tetra10 => Fpg::Fpg4,
        CellType::Penta6 | CellType::Penta15 => Fpg::Fpg21,
        CellType::Hexa8 | CellType::Hexa20 => Fpg::Fpg27,
    };
    quadrature::rule(kind, fpg).expect("every cell type has its check family")
}

/// The number of points of the check rule of `kind` (for messages).
pub fn check_point_count(kind: CellType) -> usize {
    check_rule(kind).points.len()
}

/// Integration points of the check rule with their weights.
fn check_points(kind: CellType) -> impl Iterator<Item = ([f64; 3], f64)> {
    let r = check_rule(kind);
    r.points.into_iter().zip(r.weights)
}

/// Columns dx/dxi_a of the Jacobian at `xi` on code_aster's reference
/// element (the shape functions of [`super::shape`] take the MED node order).
fn jacobian_columns(mesh: &Mesh, cell: &Cell, xi: [f64; 3]) -> Vec<[f64; 3]> {
    let ev = shape::eval(cell.kind, xi);
    (0..cell.kind.dim())
        .map(|a| {
            let mut col = [0.0; 3];
            for (&n, dj) in cell.nodes.iter().zip(ev.dn()) {
                let p = mesh.coords[n];
                for k in 0..3 {
                    col[k] += p[k] * dj[a];
                }
            }
            col
        })
        .collect()
}

/// Jacobian determinant of a cell at its vertices and quadrature points,
/// on code_aster's reference element: a volume cell is valid when all are
/// positive, a 2D cell of a flat mesh when all are positive (nodes turning
/// counter-clockwise in the x-y plane). None for cells where a sign has no
/// meaning (points, segments, faces of a 3D mesh).
pub fn jacobian_dets(mesh: &Mesh, cell: &Cell) -> Option<Vec<f64>> {
    let kind = cell.kind;
    let planar = kind.dim() == 2 && is_z_constant(mesh);
    if kind.dim() != 3 && !planar {
        return None;
    }
    let refs = shape::reference_nodes(kind);
    let points = refs[..kind.nvertices()]
        .iter()
        .copied()
        .chain(check_points(kind).map(|(p, _)| p));
    Some(
        points
            .map(|xi| {
                let c = jacobian_columns(mesh, cell, xi);
                if kind.dim() == 3 {
                    dot(c[0], cross(c[1], c[2]))
                } else {
                    c[0][0] * c[1][1] - c[0][1] * c[1][0]
                }
            })
            .collect(),
    )
}

/// The relative volume below which a cell counts as degenerate (see
/// [`degeneracy`]).
///
/// Why 1e-12: det J is computed from coordinate differences whose
/// rounding is about 1e-16 of the cell's size (coordinates are taken from
/// the cell's first node), so a cell of zero volume comes out at
/// |det J|·V_ref/h^d of 1e-16 to 1e-14, not 0 (probe s7b 05b: a flat
/// HEXA8 passed the sign check that way). A valid but thin cell with a
/// ratio of 1e-12 (a sliver 1e-12 as high as it is wide) would make a
/// stiffness that loses 12 decimals, beyond SOLVEUR's NPREC = 8 refusal,
/// and a stable explicit step 1e-12 of its neighbours': nothing a
/// computation can use, where slivers of 1e-6 (and of 1e-9, refused by
/// NPREC only) keep their own messages.
pub const DEGENERATE_RATIO: f64 = 1e-12;

/// How far a volume cell (or a 2D cell, by its area) is from having no
/// volume: the smallest |det J| over the quadrature points of its check
/// rule, times the reference element's measure, over h^d with h the
/// largest extent of its bounding box and d its dimension (1 for a
/// rectangular box with equal sides, e.g. a cube, and for a 2 x 1 x 1
/// box 2/8). Returns (point index, that ratio, h); None for points and
/// segments.
pub fn degeneracy(mesh: &Mesh, cell: &Cell) -> Option<(usize, f64, f64)> {
    let kind = cell.kind;
    let d = kind.dim();
    if d < 2 {
        return None;
    }
    let origin = mesh.coords[*cell.nodes.first()?];
    let local: Vec<[f64; 3]> = cell
        .nodes
        .iter()
        .map(|&n| sub(mesh.coords[n], origin))
        .collect();
    let mut h = 0.0f64;
    for k in 0..3 {
        let (lo, hi) = local
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p[k]), hi.max(p[k]))
            });
        h = h.max(hi - lo);
    }
    let rule = check_rule(kind);
    let reference: f64 = rule.weights.iter().sum();
    let scale = h.powi(d as i32);
    let mut worst: Option<(usize, f64)> = None;
    for (p, xi) in rule.points.iter().enumerate() {
        let ev = shape::eval(kind, *xi);
        let mut col = [[0.0; 3]; 3];
        for (x, dn) in local.iter().zip(ev.dn()) {
            for (a, c) in col.iter_mut().enumerate().take(d) {
                for k in 0..3 {
                    c[k] += x[k] * dn[a];
                }
            }
        }
        let det = if d == 3 {
            dot(col[0], cross(col[1], col[2])).abs()
        } else {
            let n = cross(col[0], col[1]);
            dot(n, n).sqrt()
        };
        let ratio = det * reference / scale;
        let ratio = if ratio.is_nan() { 0.0 } else { ratio };
        if worst.is_none_or(|(_, w)| ratio < w) {
            worst = Some((p, ratio));
        }
    }
    worst.map(|(p, r)| (p, r, h))
}

/// Length, area or volume of a cell by quadrature of |det J| (or of the
/// norm of the tangent / surface element for cells embedded in space).
pub fn cell_measure(mesh: &Mesh, cell: &Cell) -> f64 {
    let kind = cell.kind;
    check_points(kind)
        .map(|(xi, w)| {
            let c = jacobian_columns(mesh, cell, xi);
            let j = match kind.dim() {
                0 => 1.0,
                1 => dot(c[0], c[0]).sqrt(),
                2 => {
                    let n = cross(c[0], c[1]);
                    dot(n, n).sqrt()
                }
                _ => dot(c[0], cross(c[1], c[2])).abs(),
            };
            w * j
        })
        .sum()
}

/// Integral of the radius x over a 2D cell of a flat mesh, by quadrature:
/// times 2 pi it is the volume the cell sweeps in an axisymmetric model.
/// None for cells that are not 2D.
pub fn cell_first_moment_x(mesh: &Mesh, cell: &Cell) -> Option<f64> {
    if cell.kind.dim() != 2 {
        return None;
    }
    let m = check_points(cell.kind)
        .map(|(xi, w)| {
            let c = jacobian_columns(mesh, cell, xi);
            let ev = shape::eval(cell.kind, xi);
            let x: f64 = ev
                .n()
                .iter()
                .zip(&cell.nodes)
                .map(|(nj, &n)| nj * mesh.coords[n][0])
                .sum();
            w * x * (c[0][0] * c[1][1] - c[0][1] * c[1][0]).abs()
        })
        .sum();
    Some(m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::taylor::{generate, TaylorParams, GAP};

    fn gen(letter: char) -> Mesh {
        generate(&TaylorParams::for_modelling(letter).unwrap()).unwrap()
    }

    fn find_node(m: &Mesh, x: [f64; 3]) -> usize {
        (0..m.nnodes())
            .find(|&n| (0..3).all(|k| (m.coords[n][k] - x[k]).abs() < 1e-9))
            .unwrap()
    }

    // ---- geometry conventions -------------------------------------------

    /// Builds a one-cell mesh whose nodes are code_aster's reference
    /// element read into MED order: the map is the identity, det J = 1.
    fn reference_cell_in_med_order(kind: CellType) -> Mesh {
        let coords = shape::reference_nodes(kind).to_vec();
        Mesh {
            dim: if kind.dim() == 3 { 3 } else { 2 },
            coords,
            cells: vec![Cell {
                kind,
                nodes: (0..kind.nnodes()).collect(),
            }],
            ..Mesh::default()
        }
    }

    #[test]
    fn reference_cells_map_with_unit_jacobian() {
        for kind in CellType::ALL {
            if kind.dim() < 2 {
                continue;
            }
            let m = reference_cell_in_med_order(kind);
            let d = jacobian_dets(&m, &m.cells[0]).unwrap();
            for v in d {
                assert!((v - 1.0).abs() < 1e-9, "{kind:?}: det {v}");
            }
            // Partition of unity: the reference measures.
            let want = match kind {
                CellType::Tria3 | CellType::Tria6 => 0.5,
                CellType::Quad4 | CellType::Quad8 => 4.0,
                CellType::Tetra4 | CellType::Tetra10 => 1.0 / 6.0,
                CellType::Penta6 | CellType::Penta15 => 1.0,
                _ => 8.0,
            };
            let got = cell_measure(&m, &m.cells[0]);
            assert!((got - want).abs() < 1e-9, "{kind:?}: {got}");
        }
    }

    /// The MED edge lists of the brief, checked against code_aster's
    /// reference element read through `med_to_aster`.
    #[test]
    fn med_to_aster_matches_the_med_edge_lists() {
        let hexa20: &[(usize, usize)] = &[
            (0, 1),
            (1, 2),
            (2, 3),
            (3, 0),
            (4, 5),
            (5, 6),
            (6, 7),
            (7, 4),
            (0, 4),
            (1, 5),
            (2, 6),
            (3, 7),
        ];
        let penta15: &[(usize, usize)] = &[
            (0, 1),
            (1, 2),
            (2, 0),
            (3, 4),
            (4, 5),
            (5, 3),
            (0, 3),
            (1, 4),
            (2, 5),
        ];
        for (kind, edges) in [(CellType::Hexa20, hexa20), (CellType::Penta15, penta15)] {
            let m = reference_cell_in_med_order(kind);
            let nv = kind.nvertices();
            for (e, &(a, b)) in edges.iter().enumerate() {
                for k in 0..3 {
                    let mid = 0.5 * (m.coords[a][k] + m.coords[b][k]);
                    assert!((m.coords[nv + e][k] - mid).abs() < 1e-15, "{kind:?} {e}");
                }
            }
        }
    }

    /// The convention, stated on a unit cube: in MED order the bottom face
    /// 1-2-3-4 turns clockwise seen from the top face 5-8.
    #[test]
    fn med_hexa_bottom_face_turns_clockwise_from_the_top() {
        let cube = |bottom: [[f64; 2]; 4]| {
            let mut coords = Vec::new();
            for z in [0.0, 1.0] {
                coords.extend(bottom.iter().map(|p| [p[0], p[1], z]));
            }
            Mesh {
                dim: 3,
                coords,
                cells: vec![Cell {
                    kind: CellType::Hexa8,
                    nodes: (0..8).collect(),
                }],
                ..Mesh::default()
            }
        };
        let med = cube([[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]]);
        let ccw = cube([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
        let d_med = jacobian_dets(&med, &med.cells[0]).unwrap();
        let d_ccw = jacobian_dets(&ccw, &ccw.cells[0]).unwrap();
        // det J of the cube [0,1]^3 on [-1,1]^3 is 1/8.
        assert!(d_med.iter().all(|&d| (d - 0.125).abs() < 1e-9));
        assert!(d_ccw.iter().all(|&d| (d + 0.125).abs() < 1e-9));
        assert!((cell_measure(&med, &med.cells[0]) - 1.0).abs() < 1e-9);
    }

    // ---- DEFI_GROUP -----------------------------------------------------

    #[test]
    fn tout_group_ma_creates_one_node_group_per_cell_group() {
        let mut m = gen('B');
        let r = crea_group_no_tout_group_ma(&mut m);
        assert!(r.alarms.is_empty());
        assert_eq!(r.created, ["VOL", "VOL_RIG", "SZZ", "AXE", "RIGID"]);
        // Serendipity grid 11 x 41 minus 100 centres; foundation 8; SZZ 11
        // nodes on y = 2.27; AXE 41 on x = 0; RIGID 3.
        for (g, n) in [
            ("VOL", 351),
            ("VOL_RIG", 8),
            ("SZZ", 11),
            ("AXE", 41),
            ("RIGID", 3),
        ] {
            let nodes = &m.node_groups[g];
            assert_eq!(nodes.len(), n, "{g}");
            assert!(nodes.windows(2).all(|w| w[0] < w[1]), "{g} ascending");
        }
        // A second time: every name exists, alarm and no change.
        let before = m.clone();
        let r = crea_group_no_tout_group_ma(&mut m);
        assert_eq!(r.alarms.len(), 5);
        assert!(r.alarms.iter().all(|a| a.id == "MODELISA7_9"));
        assert!(r.created.is_empty());
        assert_eq!(m, before);
    }

    #[test]
    fn crit_noeud_selects_vertices_or_mid_nodes() {
        let mut m = gen('A');
        // SZZ of the 5/20/6 quarter: radial mids 5 x 7, arc mids 5 x 6;
        // vertices 5 x 7 plus the axis node.
        crea_group_no_from_group_ma(&mut m, &["SZZ"], Some(&["MILIEU"]), CritNoeud::Milieu)
            .unwrap();
        crea_group_no_from_group_ma(&mut m, &["SZZ"], Some(&["SOMMET"]), CritNoeud::Sommet)
            .unwrap();
        crea_group_no_from_group_ma(&mut m, &["SZZ"], None, CritNoeud::Tous).unwrap();
        let r = crea_group_no_from_group_ma(&mut m, &["SZZ"], Some(&["CENTRE"]), CritNoeud::Centre)
            .unwrap();
        assert_eq!(m.node_groups["MILIEU"].len(), 35 + 30);
        assert_eq!(m.node_groups["SOMMET"].len(), 35 + 1);
        assert_eq!(m.node_groups["SZZ"].len(), 101);
        // No centre nodes in these cell types: created, but empty.
        assert_eq!(r.created, ["CENTRE"]);
        assert!(m.node_groups["CENTRE"].is_empty());
        // MILIEU and SOMMET partition SZZ.
        let mut both = m.node_groups["MILIEU"].clone();
        both.extend(&m.node_groups["SOMMET"]);
        both.sort_unstable();
        assert_eq!(both, m.node_groups["SZZ"]);
    }

    #[test]
    fn milieu_on_linear_cells_creates_an_empty_group() {
        let mut m = gen('J');
        let r = crea_group_no_from_group_ma(&mut m, &["SZZ"], Some(&["MILIEU"]), CritNoeud::Milieu)
            .unwrap();
        assert!(r.alarms.is_empty());
        assert_eq!(m.node_groups.get("MILIEU"), Some(&Vec::new()));
        // ... so SXX minus MILIEU is all of SXX.
        crea_group_no_from_group_ma(&mut m, &["SXX"], None, CritNoeud::Tous).unwrap();
        crea_group_no_diffe(&mut m, &["SXX", "MILIEU"], "SXX1").unwrap();
        assert_eq!(m.node_groups["SXX1"], m.node_groups["SXX"]);
    }

    #[test]
    fn group_ma_errors_and_existing_names() {
        let mut m = gen('B');
        let e = crea_group_no_from_group_ma(&mut m, &["SZZ", "AXE"], Some(&["X"]), CritNoeud::Tous)
            .unwrap_err();
        assert_eq!(e.id, "MODELISA7_8");
        let e = crea_group_no_from_group_ma(&mut m, &["SZZ", "NOPE"], None, CritNoeud::Tous)
            .unwrap_err();
        assert_eq!(e.id, "ELEMENTS_62");
        assert!(e.text.contains("NOPE"));
        assert!(
            !m.node_groups.contains_key("SZZ"),
            "nothing created on error"
        );
        // A1 exists: alarm, the old one-node group stays.
        let a1 = m.node_groups["A1"].clone();
        let r =
            crea_group_no_from_group_ma(&mut m, &["SZZ"], Some(&["A1"]), CritNoeud::Tous).unwrap();
        assert_eq!(r.alarms[0].id, "MODELISA7_9");
        assert_eq!(m.node_groups["A1"], a1);
    }

    #[test]
    fn diffe_keeps_the_first_group_order_and_never_creates_empty_groups() {
        let mut m = gen('A');
        crea_group_no_tout_group_ma(&mut m);
        crea_group_no_from_group_ma(&mut m, &["SZZ"], Some(&["MILIEU"]), CritNoeud::Milieu)
            .unwrap();
        crea_group_no_diffe(&mut m, &["SXX", "MILIEU"], "SXX1").unwrap();
        crea_group_no_diffe(&mut m, &["SYY", "MILIEU"], "SYY1").unwrap();
        // SXX holds the 2D grid's 351 nodes; 5 radial mids of its bottom
        // edge are MILIEU nodes.
        assert_eq!(m.node_groups["SXX"].len(), 351);
        assert_eq!(m.node_groups["SXX1"].len(), 346);
        assert_eq!(m.node_groups["SYY1"].len(), 346);
        let sxx = &m.node_groups["SXX"];
        let expected: Vec<usize> = sxx
            .iter()
            .copied()
            .filter(|n| !m.node_groups["MILIEU"].contains(n))
            .collect();
        assert_eq!(m.node_groups["SXX1"], expected);
        // Empty difference: alarm, no group, and later use fails.
        let before = m.node_groups.len();
        let r = crea_group_no_diffe(&mut m, &["A1", "SZZ"], "EMPTY").unwrap();
        assert_eq!(r.alarms[0].id, "SOUSTRUC_38");
        assert_eq!(m.node_groups.len(), before);
        let e = crea_group_no_diffe(&mut m, &["EMPTY", "A1"], "X").unwrap_err();
        assert_eq!(e.id, "ASTER_RS_GROUP_NO_UNKNOWN");
        // Existing NOM is fatal.
        let e = crea_group_no_diffe(&mut m, &["SXX", "MILIEU"], "SXX1").unwrap_err();
        assert_eq!(e.id, "SOUSTRUC_37");
    }

    #[test]
    fn union_and_intersection_orders() {
        let mut m = gen('D');
        crea_group_no_tout_group_ma(&mut m);
        crea_group_no_set(&mut m, GroupSetOp::Union, &["B1", "A1", "B1"], "U").unwrap();
        let (a1, b1) = (m.node_groups["A1"][0], m.node_groups["B1"][0]);
        assert_eq!(m.node_groups["U"], [b1, a1]);
        crea_group_no_set(&mut m, GroupSetOp::Intersec, &["SZZ", "AXE"], "I").unwrap();
        assert_eq!(m.node_groups["I"], [a1]);
        let r = crea_group_no_set(&mut m, GroupSetOp::Intersec, &["RIGID", "VOL"], "J").unwrap();
        assert_eq!(r.alarms[0].id, "SOUSTRUC_38");
        assert!(!m.node_groups.contains_key("J"));
    }

    #[test]
    fn plan_uses_an_absolute_distance_over_all_nodes() {
        // CYLBAS of modellings E and K.
        let mut e = gen('E');
        crea_group_no_plan(
            &mut e,
            "CYLBAS",
            &[0.0, 0.0, GAP],
            PlaneNormal::Vect(&[0.0, 0.0, 1.0]),
            1e-3,
        )
        .unwrap();
        let cylbas = &e.node_groups["CYLBAS"];
        assert_eq!(cylbas.len(), 37);
        assert!(cylbas.iter().all(|&n| (e.coords[n][2] - GAP).abs() < 1e-12));
        assert!(cylbas.windows(2).all(|w| w[0] < w[1]));
        // The same plane by nautical angles (a = 0, b = -90 deg gives +z).
        crea_group_no_plan(
            &mut e,
            "CYLBAS2",
            &[0.0, 0.0, GAP],
            PlaneNormal::AnglNaut(&[0.0, -90.0]),
            1e-3,
        )
        .unwrap();
        assert_eq!(e.node_groups["CYLBAS2"], e.node_groups["CYLBAS"]);

        // 2D: the line x = 0.3 with PRECISION 0.35 catches the columns at
        // x = 0, 0.32, 0.64 of the bar (41 + 21 + 41) and the three
        // foundation nodes at x = 0: a distance, not a cell criterion.
        let mut b = gen('B');
        crea_group_no_plan(
            &mut b,
            "COL",
            &[0.3, 0.0],
            PlaneNormal::Vect(&[2.0, 0.0]),
            0.35,
        )
        .unwrap();
        assert_eq!(b.node_groups["COL"].len(), 41 + 21 + 41 + 3);
        // 2D with ANGL_NAUT: a = 90 deg gives the normal +y: line y = 0.
        crea_group_no_plan(
            &mut b,
            "Y0",
            &[5.0, 0.0],
            PlaneNormal::AnglNaut(&[90.0]),
            1e-6,
        )
        .unwrap();
        assert_eq!(b.node_groups["Y0"].len(), 3);
    }

    #[test]
    fn plan_errors_and_empty_result() {
        let mut b = gen('B');
        let cases: [(&[f64], PlaneNormal, f64); 5] = [
            (&[0.0, 0.0, 0.0], PlaneNormal::Vect(&[0.0, 1.0]), 1e-3),
            (&[0.0, 0.0], PlaneNormal::Vect(&[0.0, 1.0, 0.0]), 1e-3),
            (&[0.0, 0.0], PlaneNormal::Vect(&[0.0, 0.0]), 1e-3),
            (&[0.0, 0.0], PlaneNormal::Vect(&[0.0, 1.0]), 0.0),
            (&[0.0, 0.0], PlaneNormal::AnglNaut(&[]), 1e-3),
        ];
        for (pt, n, prec) in cases {
            assert!(crea_group_no_plan(&mut b, "P", pt, n, prec).is_err());
        }
        let r = crea_group_no_plan(
            &mut b,
            "P",
            &[0.0, 100.0],
            PlaneNormal::Vect(&[0.0, 1.0]),
            1.0,
        )
        .unwrap();
        assert_eq!(r.alarms[0].id, "SOUSTRUC_38");
        assert!(!b.node_groups.contains_key("P"));
        let e = crea_group_no_plan(
            &mut b,
            "A1",
            &[0.0, 0.0],
            PlaneNormal::Vect(&[0.0, 1.0]),
            1.0,
        )
        .unwrap_err();
        assert_eq!(e.id, "SOUSTRUC_37");
    }

    #[test]
    fn group_ma_union() {
        let mut m = gen('B');
        crea_group_ma_union(&mut m, &["RIGID", "SZZ"], "CONTACT").unwrap();
        let mut want = m.cell_groups["SZZ"].clone();
        want.extend(&m.cell_groups["RIGID"]);
        assert_eq!(m.cell_groups["CONTACT"], want);
        assert_eq!(
            crea_group_ma_union(&mut m, &["SZZ"], "VOL").unwrap_err().id,
            "SOUSTRUC_37"
        );
    }

    // ---- ORIE_PEAU ------------------------------------------------------

    /// Outward normal of every cell of a group, as unit vectors.
    fn normals(m: &Mesh, g: &str, dim: OrieDim) -> Vec<[f64; 3]> {
        m.cell_groups[g]
            .iter()
            .map(|&c| {
                let n = skin_normal(m, &m.cells[c], dim);
                let l = dot(n, n).sqrt();
                n.map(|v| v / l)
            })
            .collect()
    }

    fn all_along(ns: &[[f64; 3]], want: [f64; 3]) -> bool {
        ns.iter().all(|n| (dot(*n, want) - 1.0).abs() < 1e-12)
    }

    #[test]
    fn orie_peau_2d_turns_normals_out_of_the_bar_and_the_block() {
        for l in ['B', 'D'] {
            let mut m = gen(l);
            let r = orie_peau(&mut m, OrieDim::D2, &["SZZ", "AXE", "RIGID"], None).unwrap();
            // As generated, SZZ already points out (-y), AXE (+x) and
            // RIGID (-y) point in.
            let n2 = if l == 'B' { 20 } else { 2 };
            assert_eq!(r.reoriented, n2 + 1, "{l}");
            assert_eq!(r.not_processed, 0);
            assert!(all_along(
                &normals(&m, "SZZ", OrieDim::D2),
                [0.0, -1.0, 0.0]
            ));
            assert!(all_along(
                &normals(&m, "AXE", OrieDim::D2),
                [-1.0, 0.0, 0.0]
            ));
            assert!(all_along(
                &normals(&m, "RIGID", OrieDim::D2),
                [0.0, 1.0, 0.0]
            ));
            // Mid-node kept last, still between the two ends.
            for &c in &m.cell_groups["AXE"] {
                let nd = &m.cells[c].nodes;
                let y = |k: usize| m.coords[nd[k]][1];
                assert!(y(0) > y(1) && (y(2) - 0.5 * (y(0) + y(1))).abs() < 1e-12);
            }
            let again = orie_peau(&mut m, OrieDim::D2, &["SZZ", "AXE", "RIGID"], None).unwrap();
            assert_eq!(again.reoriented, 0);
        }
    }

    #[test]
    fn orie_peau_3d_on_the_quarter_and_tetra_meshes() {
        let mut a = gen('A');
        let r = orie_peau(&mut a, OrieDim::D3, &["SZZ", "RIGID", "SXX", "SYY"], None).unwrap();
        // SZZ generated with +z (in), SXX with +x (in); RIGID and SYY out.
        assert_eq!(r.reoriented, 30 + 100);
        assert_eq!(r.not_processed, 0);
        assert!(all_along(
            &normals(&a, "SZZ", OrieDim::D3),
            [0.0, 0.0, -1.0]
        ));
        assert!(all_along(
            &normals(&a, "RIGID", OrieDim::D3),
            [0.0, 0.0, 1.0]
        ));
        assert!(all_along(
            &normals(&a, "SXX", OrieDim::D3),
            [-1.0, 0.0, 0.0]
        ));
        assert!(all_along(
            &normals(&a, "SYY", OrieDim::D3),
            [0.0, -1.0, 0.0]
        ));
        assert_eq!(
            r.report.infos[0],
            "TRAITEMENT DU GROUP_MA: SZZ DE 30 MAILLES"
        );
        assert_eq!(r.report.infos[1], "30 MAILLE(S) ONT ETE ORIENTEE(S)");
        // Reversed QUAD8/TRIA6 keep each mid-node between its two vertices.
        for &c in &a.cell_groups["SZZ"] {
            let cell = &a.cells[c];
            let nv = cell.kind.nvertices();
            for e in 0..nv {
                let (p, q) = (cell.nodes[e], cell.nodes[(e + 1) % nv]);
                let mnode = cell.nodes[nv + e];
                let d = |u: usize, v: usize| {
                    let w = sub(a.coords[u], a.coords[v]);
                    dot(w, w).sqrt()
                };
                assert!((d(mnode, p) - d(mnode, q)).abs() < 1e-9);
            }
        }
        let mut e = gen('E');
        let r = orie_peau(&mut e, OrieDim::D3, &["SZZ", "RIGID"], None).unwrap();
        assert_eq!(r.reoriented, 54);
        assert!(all_along(
            &normals(&e, "SZZ", OrieDim::D3),
            [0.0, 0.0, -1.0]
        ));
        assert!(all_along(
            &normals(&e, "RIGID", OrieDim::D3),
            [0.0, 0.0, 1.0]
        ));
    }

    #[test]
    fn orie_peau_support_restriction_and_unsupported_cells() {
        let mut a = gen('H');
        // Supports restricted to the block: no SZZ cell has one.
        let r = orie_peau(&mut a, OrieDim::D3, &["SZZ"], Some(&["VOL_RIG"])).unwrap();
        assert_eq!((r.reoriented, r.not_processed), (0, 4));
        assert_eq!(r.report.infos[2], "4 MAILLE(S) N'ONT PAS ETE TRAITEE(S)");
        let r = orie_peau(&mut a, OrieDim::D3, &["SZZ"], Some(&["VOL"])).unwrap();
        assert_eq!((r.reoriented, r.not_processed), (4, 0));
    }

    #[test]
    fn orie_peau_errors() {
        let mut b = gen('D');
        let mut a = gen('H');
        assert_eq!(
            orie_peau(&mut a, OrieDim::D2, &["SZZ"], None)
                .unwrap_err()
                .id,
            "MODELISA5_95"
        );
        assert!(orie_peau(&mut b, OrieDim::D3, &["SZZ"], None).is_err());
        // A volume group is not a skin; mixing types is refused too.
        assert!(orie_peau(&mut a, OrieDim::D3, &["VOL"], None).is_err());
        assert!(orie_peau(&mut b, OrieDim::D2, &["VOL"], None).is_err());
        assert!(orie_peau(&mut b, OrieDim::D2, &["NOPE"], None).is_err());
        // An internal edge (between the first two cells) has no outside.
        let p = [
            find_node(&b, [1.6, GAP, 0.0]),
            find_node(&b, [1.6, GAP + 16.2, 0.0]),
            find_node(&b, [1.6, GAP + 8.1, 0.0]),
        ];
        b.cells.push(Cell {
            kind: CellType::Seg3,
            nodes: p.to_vec(),
        });
        b.cell_groups.insert("INNER".into(), vec![b.ncells() - 1]);
        let before = b.clone();
        // AXE would be turned, but INNER fails: nothing changes.
        let e = orie_peau(&mut b, OrieDim::D2, &["AXE", "INNER"], None).unwrap_err();
        assert!(e.text.contains("lies between"));
        assert_eq!(b, before);
        // A cell listed twice is turned once.
        let r = orie_peau(&mut b, OrieDim::D2, &["AXE", "AXE"], None).unwrap();
        assert_eq!(r.reoriented, 2);
        assert!(all_along(
            &normals(&b, "AXE", OrieDim::D2),
            [-1.0, 0.0, 0.0]
        ));
    }

    // ---- QUAD_LINE ------------------------------------------------------

    /// LINE_QUAD then QUAD_LINE gives the mesh back; the mid-nodes of the
    /// E mesh are one per edge (shared by the tetrahedra around it), at
    /// the middle of their edge.
    #[test]
    fn line_quad_adds_one_node_per_edge() {
        let e = gen('E');
        let q = line_quad(&e, None).unwrap();
        let mut edges = std::collections::BTreeSet::new();
        for c in &e.cells {
            if let Some(k) = c.kind.quadratic() {
                for &(a, b) in k.mid_edges() {
                    let (na, nb) = (c.nodes[a], c.nodes[b]);
                    edges.insert((na.min(nb), na.max(nb)));
                }
            }
        }
        assert_eq!(q.nnodes(), e.nnodes() + edges.len());
        for (old, new) in e.cells.iter().zip(&q.cells) {
            let kind = old.kind.quadratic().unwrap_or(old.kind);
            assert_eq!(new.kind, kind);
            assert_eq!(new.nodes[..old.nodes.len()], old.nodes[..]);
            for (k, &(a, b)) in kind.mid_edges().iter().enumerate() {
                let (pa, pb, m) = (
                    q.coords[new.nodes[a]],
                    q.coords[new.nodes[b]],
                    q.coords[new.nodes[old.nodes.len() + k]],
                );
                for i in 0..3 {
                    assert_eq!(m[i], 0.5 * (pa[i] + pb[i]));
                }
            }
        }
        assert_eq!(q.cell_groups, e.cell_groups);
        let back = quad_line(&q, None).unwrap();
        assert_eq!(back.coords, e.coords);
        assert_eq!(back.cells, e.cells);
        // Nothing linear left to convert is an error, as in code_aster.
        assert_eq!(line_quad(&q, None).unwrap_err().id, "MODELISA3_8");
    }

    #[test]
    fn quad_line_of_the_a_mesh() {
        let mut a = gen('A');
        crea_group_no_tout_group_ma(&mut a);
        crea_group_no_from_group_ma(&mut a, &["SZZ"], Some(&["MILIEU"]), CritNoeud::Milieu)
            .unwrap();
        let j = quad_line(&a, None).unwrap();
        let counts = j.count_by_type();
        assert_eq!(
            counts,
            [
                (CellType::Tria3, 6),
                (CellType::Quad4, 225),
                (CellType::Penta6, 120),
                (CellType::Hexa8, 481)
            ]
        );
        // Vertices only: 5 x 21 x 7 off the axis, 21 on it, 8 below.
        assert_eq!(j.nnodes(), 764);
        // Same cells in the same places, vertices in the same order.
        assert_eq!(j.cell_groups, a.cell_groups);
        for (old, new) in a.cells.iter().zip(&j.cells) {
            for k in 0..old.kind.nvertices() {
                assert_eq!(a.coords[old.nodes[k]], j.coords[new.nodes[k]]);
            }
        }
        // Surviving nodes keep their relative order.
        let mut last = None;
        for p in &j.coords {
            let i = find_node(&a, *p);
            assert!(last < Some(i));
            last = Some(i);
        }
        // Node groups: MILIEU is left empty, so it is gone; SZZ keeps its
        // 36 vertices; points survive.
        assert!(!j.node_groups.contains_key("MILIEU"));
        assert_eq!(j.node_groups["SZZ"].len(), 36);
        for g in ["A1", "B1", "A2", "B2"] {
            let (o, n) = (a.node_groups[g][0], j.node_groups[g][0]);
            assert_eq!(a.coords[o], j.coords[n]);
        }
        // And it is what the generator's linear flag gives.
        assert_eq!(j.cells, gen('J').cells);
        assert_eq!(j.coords, gen('J').coords);
    }

    #[test]
    fn quad_line_keeps_mid_nodes_still_used_by_quadratic_cells() {
        let b = gen('B');
        // The block alone: its 4 mid-nodes go, except (10, 0) which the
        // RIGID SEG3, left quadratic, still uses.
        let lin = quad_line(&b, Some(&b.cell_groups["VOL_RIG"])).unwrap();
        assert_eq!(lin.nnodes(), 359 - 3);
        assert_eq!(lin.cells[b.cell_groups["VOL_RIG"][0]].kind, CellType::Quad4);
        assert_eq!(lin.cells[b.cell_groups["RIGID"][0]].kind, CellType::Seg3);
        // SZZ alone: its mid-nodes belong to QUAD8 cells left quadratic.
        let e = quad_line(&b, Some(&b.cell_groups["SZZ"])).unwrap_err();
        assert_eq!(e.id, "MODELISA4_3");
        // Nothing quadratic.
        assert_eq!(quad_line(&gen('E'), None).unwrap_err().id, "MODELISA3_8");
        assert_eq!(
            quad_line(&b, Some(&b.cell_groups["VOL_RIG"][..0]))
                .unwrap_err()
                .id,
            "MODELISA3_8"
        );
        assert!(quad_line(&b, Some(&[100_000])).is_err());
    }
}
