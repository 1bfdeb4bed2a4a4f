//! Rigid-body modes that the imposed dofs leave free.
//!
//! Why: without inertia (STAT_NON_LINE) the stiffness alone must hold the
//! structure. A rigid-body mode that no DDL_IMPO touches makes it singular
//! in exact arithmetic, but in floating point the factorization usually
//! finds a tiny pivot instead of a zero one and returns a huge, finite,
//! arbitrary rigid motion. So the modes are checked before the first step,
//! where the missing condition can still be named.
//!
//! A mode combination r is free when r vanishes at every imposed dof: the
//! null space of the Gram matrix G_kl = Σ_imposed r_k r_l of the rigid
//! modes (6 in 3D: 3 translations, 3 rotations about the centroid; 3 in
//! plane strain: DX, DY and the rotation about z; 1 in AXIS: the axial
//! translation DY, a radial one strains the hoop).

use super::dofs::DofNumbering;
use crate::mesh::Mesh;
use crate::model::spec::Formulation;
use crate::model::Model;

/// The rigid-body modes of the model not held by its imposed dofs, each
/// described in words ("translation DX", "rotation about Z + translation
/// DY"); empty when every mode is held. Each connected part of the mesh
/// (cells sharing nodes) has its own modes: a block resting on a clamped
/// base is free even though the base is held; with several parts the
/// words name the part by its cell groups.
pub fn unheld_modes(mesh: &Mesh, model: &Model, nb: &DofNumbering) -> Vec<String> {
    // Connected parts by union-find over the element cells' nodes.
    let mut parent: Vec<usize> = (0..nb.nnodes).collect();
    fn root(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for (c, _) in model.element_cells() {
        let nodes = &mesh.cells[c].nodes;
        for w in nodes.windows(2) {
            let (a, b) = (root(&mut parent, w[0]), root(&mut parent, w[1]));
            if a != b {
                parent[a] = b;
            }
        }
    }
    let mut parts: indexmap::IndexMap<usize, (Vec<usize>, Vec<usize>)> = indexmap::IndexMap::new();
    for (c, _) in model.element_cells() {
        let r = root(&mut parent, mesh.cells[c].nodes[0]);
        parts.entry(r).or_default().1.push(c);
    }
    for n in (0..nb.nnodes).filter(|&n| nb.active_node[n]) {
        let r = root(&mut parent, n);
        if let Some(p) = parts.get_mut(&r) {
            p.0.push(n);
        }
    }
    let several = parts.len() > 1;
    let mut out = Vec::new();
    for (r, (nodes, cells)) in &parts {
        let imposed: Vec<usize> = nb
            .imposed
            .iter()
            .map(|&(f, _)| f)
            .filter(|&f| root(&mut parent, f / nb.ndpn) == *r)
            .collect();
        for mode in part_modes(mesh, model, nb.ndpn, nodes, &imposed) {
            if several {
                let groups = mesh.groups_containing(cells);
                let name = if groups.is_empty() {
                    format!("cells M{}..", cells[0] + 1)
                } else {
                    groups.join(", ")
                };
                out.push(format!("{mode} of the part {name}"));
            } else {
                out.push(mode);
            }
        }
    }
    out
}

/// The free modes of one connected part: `active` its nodes, `imposed`
/// its imposed dofs (full indices).
fn part_modes(
    mesh: &Mesh,
    model: &Model,
    ndpn: usize,
    active: &[usize],
    imposed: &[usize],
) -> Vec<String> {
    let axis = model
        .element_cells()
        .any(|(_, s)| s.formulation == Formulation::Axis);
    let plane = model.element_cells().any(|(_, s)| s.formulation.is_plane());
    if active.is_empty() {
        return Vec::new();
    }
    const ALL: [&str; 6] = [
        "translation DX",
        "translation DY",
        "translation DZ",
        "rotation about X",
        "rotation about Y",
        "rotation about Z",
    ];
    // The modes of the formulation, as indices into ALL.
    let ids: Vec<usize> = if axis {
        vec![1]
    } else if plane || ndpn == 2 {
        vec![0, 1, 5]
    } else {
        (0..6).collect()
    };
    let names: Vec<&str> = ids.iter().map(|&k| ALL[k]).collect();
    let m = names.len();
    // Centroid and size: the rotations are scaled to O(1) on the model.
    let mut c = [0.0; 3];
    for &n in active {
        for (ci, xi) in c.iter_mut().zip(mesh.coords[n]) {
            *ci += xi / active.len() as f64;
        }
    }
    let size = active
        .iter()
        .map(|&n| {
            let x = mesh.coords[n];
            ((x[0] - c[0]).powi(2) + (x[1] - c[1]).powi(2) + (x[2] - c[2]).powi(2)).sqrt()
        })
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let mode_value = |j: usize, node: usize, comp: usize| -> f64 {
        let k = ids[j];
        let x = mesh.coords[node];
        let r = [
            (x[0] - c[0]) / size,
            (x[1] - c[1]) / size,
            (x[2] - c[2]) / size,
        ];
        match (k, comp) {
            (0..=2, _) => f64::from(u8::from(k == comp)),
            // e_k x r
            (3, 1) => -r[2],
            (3, 2) => r[1],
            (4, 0) => r[2],
            (4, 2) => -r[0],
            (5, 0) => -r[1],
            (5, 1) => r[0],
            _ => 0.0,
        }
    };
    let mut g = vec![vec![0.0; m]; m];
    for &f in imposed {
        let (node, comp) = (f / ndpn, f % ndpn);
        let v: Vec<f64> = (0..m).map(|k| mode_value(k, node, comp)).collect();
        for k in 0..m {
            for l in 0..m {
                g[k][l] += v[k] * v[l];
            }
        }
    }
    let (values, vectors) = jacobi_eigen(g);
    let mut out = Vec::new();
    for (j, &lambda) in values.iter().enumerate() {
        // One imposed dof at unit distance contributes O(1): a mode held
        // by anything meaningful is far above this.
        if lambda > 1e-9 {
            continue;
        }
        let v: Vec<f64> = (0..m).map(|k| vectors[k][j]).collect();
        let big = v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let parts: Vec<&str> = (0..m)
            .filter(|&k| v[k].abs() >= 0.3 * big)
            .map(|k| names[k])
            .collect();
        out.push(parts.join(" + "));
    }
    out
}

/// Eigenvalues and eigenvectors (columns) of a small symmetric matrix by
/// cyclic Jacobi rotations.
fn jacobi_eigen(mut a: Vec<Vec<f64>>) -> (Vec<f64>, Vec<Vec<f64>>) {
    let n = a.len();
    let mut v = vec![vec![0.0; n]; n];
    for (i, row) in v.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for _sweep in 0..100 {
        let off: f64 = (0..n)
            .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i][j] * a[i][j])
            .sum();
        let diag: f64 = (0..n).map(|i| a[i][i] * a[i][i]).sum();
        if off <= 1e-30 * diag.max(f64::MIN_POSITIVE) {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                if a[p][q] == 0.0 {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let cs = 1.0 / (t * t + 1.0).sqrt();
                let sn = t * cs;
                for k in 0..n {
                    let (akp, akq) = (a[k][p], a[k][q]);
                    a[k][p] = cs * akp - sn * akq;
                    a[k][q] = sn * akp + cs * akq;
                }
                for k in 0..n {
                    let (apk, aqk) = (a[p][k], a[q][k]);
                    a[p][k] = cs * apk - sn * aqk;
                    a[q][k] = sn * apk + cs * aqk;
                }
                for row in v.iter_mut() {
                    let (vp, vq) = (row[p], row[q]);
                    row[p] = cs * vp - sn * vq;
                    row[q] = sn * vp + cs * vq;
                }
            }
        }
    }
    ((0..n).map(|i| a[i][i]).collect(), v)
}

#[cfg(test)]
mod tests {
    use super::jacobi_eigen;

    #[test]
    fn jacobi_finds_the_null_vector() {
        // [[1,1],[1,1]]: eigenvalues 0 and 2, null vector (1,-1)/sqrt2.
        let (vals, vecs) = jacobi_eigen(vec![vec![1.0, 1.0], vec![1.0, 1.0]]);
        let j = if vals[0] < vals[1] { 0 } else { 1 };
        assert!(vals[j].abs() < 1e-14 && (vals[1 - j] - 2.0).abs() < 1e-14);
        assert!((vecs[0][j] + vecs[1][j]).abs() < 1e-14);
    }
}
