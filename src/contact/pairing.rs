//! Master/slave pairing (`APPARIEMENT='MAIT_ESCL'`): each slave node is
//! projected orthogonally on the closest master cell of the current
//! geometry, and the projection is frozen in a [`Link`] until the next
//! pairing.
//!
//! Conventions (semantics.md §6.2, code_aster's `mmnorm`): the normal is
//! the master's **inward** normal n_in, built from the master cell's
//! tangents t_a = ∂x/∂ξ_a at the projection: n_in = (−t_y, t_x) in 2D and
//! t2 × t1 in 3D. With skins oriented outward (`ORIE_PEAU`), it points into
//! the master body, and the gap g = (x_proj − x_slave)·n_in is > 0 when the
//! slave node is outside the master body, < 0 when it has penetrated.

use super::ContactDef;
use crate::mesh::shape;
use crate::mesh::vec3::{add, cross, dot, norm, scale, sub};
use crate::mesh::{CellType, Mesh};

/// An orthogonal projection of a point on one master cell.
#[derive(Debug, Clone, PartialEq)]
pub struct Projection {
    /// Parametric coordinates (the second is 0 on a segment).
    pub xi: [f64; 2],
    /// The projected point x(ξ).
    pub point: [f64; 3],
    /// Master shape functions at ξ, in the cell's (MED) node order: the
    /// weights that carry a slave force to the master nodes.
    pub shape: Vec<f64>,
    /// Unit inward master normal n_in at ξ.
    pub normal: [f64; 3],
    /// Orthonormal tangent basis: τ1 = t1/|t1|; in 3D τ2 = τ1 × n_in, so
    /// that (τ1, τ2, −n_in) is right-handed. Unused entries are 0.
    pub tangents: [[f64; 3]; 2],
    /// Gap (x(ξ) − p)·n_in: > 0 when p is outside the master body.
    pub gap: f64,
    /// Euclidean distance |x(ξ) − p|.
    pub distance: f64,
    /// How far ξ lies outside the reference cell, in parametric units
    /// (0 inside), compared with TOLE_PROJ_EXT.
    pub outside: f64,
}

/// One pairing of a slave node with a master cell, frozen within an
/// iteration: the gap and the slip are linear in the displacements with
/// these coefficients ("fixed pairing", as code_aster's discrete method).
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    /// Index of the zone in [`ContactDef::zones`].
    pub zone: usize,
    /// The slave node.
    pub slave: usize,
    pub master_cell: usize,
    /// The master cell's nodes, in MED order (aligned with `shape`).
    pub master_nodes: Vec<usize>,
    pub xi: [f64; 2],
    /// Master shape functions at ξ.
    pub shape: Vec<f64>,
    /// Unit inward master normal n_in.
    pub normal: [f64; 3],
    /// Tangent basis (1 vector in 2D, 2 in 3D; unused entries 0).
    pub tangents: [[f64; 3]; 2],
    /// Number of tangents: dim − 1.
    pub ntangents: usize,
    /// Projection point at pairing (the `PROJ_*` components of CONT_NOEU).
    pub proj: [f64; 3],
    /// Gap at pairing, less the zone's DIST_MAIT + DIST_ESCL.
    pub gap: f64,
    /// Gap of the frozen link at zero displacement:
    /// n_in·(Σ N_j X_j − X_s) with X the initial coordinates, so that the
    /// gap for displacements u is `gap_ref + n_in·(Σ N_j u_j − u_s)`
    /// (less DIST_MAIT + DIST_ESCL, as `gap`).
    pub gap_ref: f64,
}

/// The result of one pairing: one link per paired slave node and zone.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Pairing {
    pub dim: usize,
    pub links: Vec<Link>,
    /// (zone, slave node) that found no master cell within TOLE_PROJ_EXT
    /// (or DIST_APPA): `CONT = −1`, no force.
    pub unpaired: Vec<(usize, usize)>,
}

/// Pairs every slave node of every zone on the current geometry
/// `mesh.coords + u` (u: one displacement per node, 3 components, z = 0
/// in 2D).
///
/// Every master cell of the zone is tried (the sdnv103 master is one cell;
/// the cost is slaves × masters projections) and the nearest projection
/// within TOLE_PROJ_EXT wins; on a tie (a node above the common edge of
/// two cells) the projection least outside its cell wins.
///
/// # Panics
/// If `u` does not have one entry per mesh node (a caller bug).
pub fn pair(def: &ContactDef, mesh: &Mesh, u: &[[f64; 3]]) -> Pairing {
    assert_eq!(u.len(), mesh.nnodes(), "one displacement per mesh node");
    let cur = |n: usize| add(mesh.coords[n], u[n]);
    let mut out = Pairing {
        dim: def.dim,
        ..Pairing::default()
    };
    for (iz, zone) in def.zones.iter().enumerate() {
        // Current coordinates of each master cell, computed once.
        let masters: Vec<(usize, Vec<[f64; 3]>)> = zone
            .master_cells
            .iter()
            .map(|&c| (c, mesh.cells[c].nodes.iter().map(|&n| cur(n)).collect()))
            .collect();
        for &s in &zone.slave_nodes {
            let p = cur(s);
            let mut best: Option<(usize, Projection)> = None;
            for (c, xs) in &masters {
                let Some(pr) = project(mesh.cells[*c].kind, xs, p, def.dim) else {
                    continue;
                };
                if zone.tole_proj_ext.is_some_and(|t| pr.outside > t) {
                    continue;
                }
                let better = match &best {
                    None => true,
                    Some((_, b)) => {
                        let tie = 1e-10 * (1.0 + b.distance.max(pr.distance));
                        if (pr.distance - b.distance).abs() <= tie {
                            pr.outside < b.outside
                        } else {
                            pr.distance < b.distance
                        }
                    }
                };
                if better {
                    best = Some((*c, pr));
                }
            }
            let best = best.filter(|(_, pr)| zone.dist_appa.is_none_or(|d| pr.distance <= d));
            let Some((c, pr)) = best else {
                out.unpaired.push((iz, s));
                continue;
            };
            let nodes = mesh.cells[c].nodes.clone();
            let mut x_ref = [0.0; 3];
            for (j, &n) in nodes.iter().enumerate() {
                x_ref = add(x_ref, scale(pr.shape[j], mesh.coords[n]));
            }
            // DIST_MAIT + DIST_ESCL: the link closes that much earlier.
            let user = zone.user_gap.get(&s).copied().unwrap_or(0.0);
            let gap_ref = dot(pr.normal, sub(x_ref, mesh.coords[s])) - user;
            out.links.push(Link {
                zone: iz,
                slave: s,
                master_cell: c,
                master_nodes: nodes,
                xi: pr.xi,
                shape: pr.shape,
                normal: pr.normal,
                tangents: pr.tangents,
                ntangents: def.dim - 1,
                proj: pr.point,
                gap: pr.gap - user,
                gap_ref,
            });
        }
    }
    out
}

/// Largest number of Newton iterations of a projection.
const MAX_NEWTON: usize = 50;
/// Convergence on the parametric correction.
const XI_TOL: f64 = 1e-12;
/// Step for the second derivatives of the geometric map. The maps of the
/// supported cells are at most quadratic in each parametric variable, so
/// the central difference of their first derivatives is exact whatever the
/// step; a large step keeps rounding small.
const FD_STEP: f64 = 1e-2;

/// Projects `p` orthogonally on a master cell whose current node
/// coordinates are `xs` (MED order), by Newton's method on
/// min ½|x(ξ) − p|² over the unbounded parametrisation. `dim` is the model
/// dimension (2: SEG2/SEG3 in the x-y plane; 3: TRIA3/TRIA6/QUAD4/QUAD8).
///
/// Returns None for a cell type that is not a contact surface of that
/// dimension, a degenerate cell, or when Newton does not converge.
pub fn project(kind: CellType, xs: &[[f64; 3]], p: [f64; 3], dim: usize) -> Option<Projection> {
    let pdim = kind.dim();
    let ok = super::is_contact_surface(kind, dim);
    if !ok || xs.len() != kind.nnodes() {
        return None;
    }
    // x(ξ) and the covariant tangents; the shape functions themselves
    // are taken once, at the projection (no allocation per evaluation:
    // the explicit loop pairs at every step).
    let geo = |xi: [f64; 2]| -> ([f64; 3], [[f64; 3]; 2]) {
        let sh = shape::eval(kind, [xi[0], xi[1], 0.0]);
        let mut x = [0.0; 3];
        let mut t = [[0.0; 3]; 2];
        for (i, xi_node) in xs.iter().enumerate() {
            x = add(x, scale(sh.n()[i], *xi_node));
            for (a, ta) in t.iter_mut().enumerate().take(pdim) {
                *ta = add(*ta, scale(sh.dn()[i][a], *xi_node));
            }
        }
        (x, t)
    };
    // Newton from the cell's centre; a symmetric start can converge to a
    // stationary point that is not the closest (p on the axis of a curved
    // cell), so the vertices are tried as starts too in that case.
    let centre = match kind {
        CellType::Tria3 | CellType::Tria6 => [1.0 / 3.0, 1.0 / 3.0],
        _ => [0.0, 0.0],
    };
    let mut best: Option<([f64; 2], f64)> = None;
    let mut consider = |xi: [f64; 2]| {
        let d = norm(sub(geo(xi).0, p));
        if best.is_none_or(|(_, bd)| d < bd) {
            best = Some((xi, d));
        }
    };
    match newton(&geo, p, pdim, centre) {
        Some((xi, true)) => consider(xi),
        other => {
            if let Some((xi, _)) = other {
                consider(xi);
            }
            for v in &shape::reference_nodes(kind)[..kind.nvertices()] {
                if let Some((xi, _)) = newton(&geo, p, pdim, [v[0], v[1]]) {
                    consider(xi);
                }
            }
        }
    }
    let (xi, _) = best?;
    let (x, t) = geo(xi);
    let n = shape::eval(kind, [xi[0], xi[1], 0.0]).n().to_vec();
    let (normal, tangents) = basis(t, pdim)?;
    let d = sub(x, p);
    let outside = match kind {
        CellType::Seg2 | CellType::Seg3 => (xi[0].abs() - 1.0).max(0.0),
        CellType::Quad4 | CellType::Quad8 => (xi[0].abs() - 1.0).max(xi[1].abs() - 1.0).max(0.0),
        _ => (-xi[0]).max(-xi[1]).max(xi[0] + xi[1] - 1.0).max(0.0),
    };
    Some(Projection {
        xi,
        point: x,
        shape: n,
        normal,
        tangents,
        gap: dot(d, normal),
        distance: norm(d),
        outside,
    })
}

/// Newton's method on min ½|x(ξ) − p|² from `start`: the converged ξ and
/// whether it is a strict local minimum (positive definite Hessian).
fn newton<G>(geo: &G, p: [f64; 3], pdim: usize, start: [f64; 2]) -> Option<([f64; 2], bool)>
where
    G: Fn([f64; 2]) -> ([f64; 3], [[f64; 3]; 2]),
{
    let mut xi = start;
    for _ in 0..MAX_NEWTON {
        let (x, t) = geo(xi);
        let r = sub(x, p);
        let mut grad = [0.0; 2];
        let mut h = [[0.0; 2]; 2];
        for a in 0..pdim {
            grad[a] = dot(t[a], r);
            for b in 0..pdim {
                h[a][b] = dot(t[a], t[b]);
            }
        }
        // Full Newton adds r·∂²x/∂ξa∂ξb; fall back to Gauss-Newton when
        // that makes the matrix indefinite (p far on the concave side).
        let mut full = h;
        for b in 0..pdim {
            let mut xp = xi;
            let mut xm = xi;
            xp[b] += FD_STEP;
            xm[b] -= FD_STEP;
            let (_, tp) = geo(xp);
            let (_, tm) = geo(xm);
            for a in 0..pdim {
                let d2 = scale(0.5 / FD_STEP, sub(tp[a], tm[a]));
                full[a][b] += dot(r, d2);
            }
        }
        let exact = solve(&full, &grad, pdim);
        let minimum = exact.is_some();
        let step = exact.or_else(|| solve(&h, &grad, pdim))?;
        // Limit a step to the size of the reference cell so that a poor
        // start cannot throw ξ far along a curved extension.
        let len = (step[0] * step[0] + step[1] * step[1]).sqrt();
        let f = if len > 1.0 { 1.0 / len } else { 1.0 };
        xi[0] -= f * step[0];
        xi[1] -= f * step[1];
        if !(xi[0].is_finite() && xi[1].is_finite()) {
            return None;
        }
        if len < XI_TOL {
            return Some((xi, minimum));
        }
    }
    None
}

/// The inward normal and orthonormal tangents from the covariant tangents
/// (None for a degenerate cell).
fn basis(t: [[f64; 3]; 2], pdim: usize) -> Option<([f64; 3], [[f64; 3]; 2])> {
    let l1 = norm(t[0]);
    if l1 == 0.0 || !l1.is_finite() {
        return None;
    }
    let tau1 = scale(1.0 / l1, t[0]);
    if pdim == 1 {
        return Some(([-tau1[1], tau1[0], 0.0], [tau1, [0.0; 3]]));
    }
    let n = cross(t[1], t[0]);
    let ln = norm(n);
    if ln == 0.0 || !ln.is_finite() {
        return None;
    }
    let n = scale(1.0 / ln, n);
    Some((n, [tau1, cross(tau1, n)]))
}

/// Solves the 1×1 or 2×2 system `m·x = b` when `m` is positive definite.
fn solve(m: &[[f64; 2]; 2], b: &[f64; 2], n: usize) -> Option<[f64; 2]> {
    if n == 1 {
        return (m[0][0] > 0.0).then(|| [b[0] / m[0][0], 0.0]);
    }
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    if !(m[0][0] > 0.0 && det > 1e-14 * (m[0][0] * m[1][1]).abs()) {
        return None;
    }
    Some([
        (m[1][1] * b[0] - m[0][1] * b[1]) / det,
        (m[0][0] * b[1] - m[1][0] * b[0]) / det,
    ])
}
