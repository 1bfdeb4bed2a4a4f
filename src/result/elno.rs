//! Element fields at nodes, from Gauss-point fields: CALC_CHAMP's
//! SIEF_ELNO/SIGM_ELNO (per element, at its nodes) and SIEF_NOEU/SIGM_NOEU
//! (per node, the average over the elements sharing it).
//!
//! The extrapolation follows code_aster's rule for its Gauss-to-node
//! matrices [mem: `inmat4`/`inmat5` of the element reference catalogue;
//! not checked against its source]: one Gauss point gives its value to
//! every node (TRIA3, TETRA4 and the under-integrated HEXS8); otherwise the
//! vertex values are the least-squares fit, through the Gauss values, of
//! the shape functions of the linear cell on the same vertices (exact
//! interpolation when there are as many points as vertices, QUAD4 FPG4,
//! HEXA8 FPG8, PENTA6 FPG6, and the 2×2 MEAXQS8), and a mid-side node
//! takes the mean of the two vertices of its edge. A field linear in the
//! reference coordinates is therefore reproduced exactly at every node,
//! on quadratic cells too.

use indexmap::IndexMap;
use nalgebra::DMatrix;

use super::{GaussField, NodalField};
use crate::mesh::quadrature::{rule, Fpg};
use crate::mesh::shape::eval;
use crate::mesh::{CellType, Mesh};
use crate::model::{CellRole, Model};

/// The Gauss-to-node matrix of `cell` with the family `fpg`, row-major
/// (`nnodes × npg`): node values = M · point values.
pub fn gauss_to_nodes(cell: CellType, fpg: Fpg) -> Result<DMatrix<f64>, String> {
    let q = rule(cell, fpg)
        .ok_or_else(|| format!("{} has no Gauss family {fpg:?}", cell.aster_name()))?;
    Ok(from_points(cell, &q.points))
}

fn from_points(cell: CellType, points: &[[f64; 3]]) -> DMatrix<f64> {
    let nno = cell.nnodes();
    let npg = points.len();
    if npg == 1 {
        return DMatrix::from_element(nno, 1, 1.0);
    }
    let lin = cell.linear();
    let nv = lin.nnodes();
    // P[g, a] = N_a(ξ_g) of the linear cell
    let mut p = DMatrix::zeros(npg, nv);
    for (g, xi) in points.iter().enumerate() {
        let s = eval(lin, *xi);
        for a in 0..nv {
            p[(g, a)] = s.n()[a];
        }
    }
    let ptp = p.transpose() * &p;
    let fit = ptp
        .lu()
        .solve(&p.transpose())
        // a family with fewer independent points than vertices: the mean
        .unwrap_or_else(|| DMatrix::from_element(nv, npg, 1.0 / npg as f64));
    let mut m = DMatrix::zeros(nno, npg);
    for a in 0..nv {
        m.set_row(a, &fit.row(a));
    }
    for (k, &(a, b)) in cell.mid_edges().iter().enumerate() {
        let row = (fit.row(a) + fit.row(b)) * 0.5;
        m.set_row(nv + k, &row);
    }
    m
}

/// The ELNO field of the Gauss field `gauss` (components `keep` of it, by
/// index): for each element cell of `model`, its nodes in MED order, each
/// with the components extrapolated from the cell's points. Cells without
/// an element have no values. A HEXS8 cell shows one point (its centre
/// stress and hourglass stresses) whose value goes to every node.
pub fn elno(
    gauss: &GaussField,
    mesh: &Mesh,
    model: &Model,
    keep: &[usize],
) -> Result<GaussField, String> {
    let ncmp = gauss.ncmp();
    let mut cache: IndexMap<(CellType, Fpg, usize), DMatrix<f64>> = IndexMap::new();
    let mut out = GaussField {
        components: keep.iter().map(|&k| gauss.components[k].clone()).collect(),
        offsets: Vec::with_capacity(mesh.ncells() + 1),
        values: Vec::new(),
    };
    for c in 0..mesh.ncells() {
        out.offsets.push(out.values.len());
        let Some(CellRole::Element(spec)) = model.cells.get(c) else {
            continue;
        };
        if c + 1 >= gauss.offsets.len() {
            return Err(format!("the Gauss field has no cell {}", c + 1));
        }
        let npg = gauss.npg(c);
        if npg == 0 {
            continue;
        }
        let m = match cache.entry((spec.cell, spec.rigi, npg)) {
            indexmap::map::Entry::Occupied(e) => e.into_mut(),
            indexmap::map::Entry::Vacant(e) => {
                let m = if npg == 1 {
                    DMatrix::from_element(spec.cell.nnodes(), 1, 1.0)
                } else {
                    let m = gauss_to_nodes(spec.cell, spec.rigi)?;
                    if m.ncols() != npg {
                        return Err(format!(
                            "cell {} ({}) has {npg} points in the field, its family {:?} has {}",
                            c + 1,
                            spec.name,
                            spec.rigi,
                            m.ncols()
                        ));
                    }
                    m
                };
                e.insert(m)
            }
        };
        let vals = gauss.cell(c);
        for a in 0..m.nrows() {
            for &k in keep {
                let mut v = 0.0;
                for g in 0..npg {
                    v += m[(a, g)] * vals[g * ncmp + k];
                }
                out.values.push(v);
            }
        }
    }
    out.offsets.push(out.values.len());
    Ok(out)
}

/// The NOEU field of an ELNO field: at each node, the mean of the values
/// the cells holding it give there; nodes of no such cell are absent.
pub fn noeu(elno: &GaussField, mesh: &Mesh) -> NodalField {
    let n = elno.ncmp();
    let mut sum = vec![0.0; mesh.nnodes() * n];
    let mut count = vec![0usize; mesh.nnodes()];
    for (c, cell) in mesh.cells.iter().enumerate() {
        if elno.npg(c) != cell.nodes.len() {
            continue;
        }
        let vals = elno.cell(c);
        for (a, &node) in cell.nodes.iter().enumerate() {
            count[node] += 1;
            for k in 0..n {
                sum[node * n + k] += vals[a * n + k];
            }
        }
    }
    let mut f = NodalField::absent(elno.components.clone(), mesh.nnodes());
    for (node, &cnt) in count.iter().enumerate() {
        if cnt > 0 {
            for k in 0..n {
                f.set(node, k, sum[node * n + k] / cnt as f64);
            }
        }
    }
    f
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shape::reference_nodes;

    /// Extrapolates g(ξ) sampled at the points of `fpg` and compares with
    /// g at every node.
    fn reproduces(cell: CellType, fpg: Fpg, g: &dyn Fn([f64; 3]) -> f64) {
        let q = rule(cell, fpg).unwrap();
        let m = gauss_to_nodes(cell, fpg).unwrap();
        let at_points: Vec<f64> = q.points.iter().map(|p| g(*p)).collect();
        for (a, x) in reference_nodes(cell).iter().enumerate() {
            let v: f64 = (0..q.points.len()).map(|k| m[(a, k)] * at_points[k]).sum();
            assert!(
                (v - g(*x)).abs() < 1e-12,
                "{cell:?} {fpg:?} node {a}: {v} vs {}",
                g(*x)
            );
        }
    }

    #[test]
    fn linear_fields_are_extrapolated_exactly() {
        let lin = |x: [f64; 3]| 2.0 + 0.7 * x[0] - 1.3 * x[1] + 0.4 * x[2];
        for (cell, fpg) in [
            (CellType::Quad4, Fpg::Fpg4),
            (CellType::Quad8, Fpg::Fpg9),
            (CellType::Quad8, Fpg::Fpg4),
            (CellType::Hexa8, Fpg::Fpg8),
            (CellType::Hexa20, Fpg::Fpg27),
            (CellType::Penta6, Fpg::Fpg6),
            (CellType::Penta15, Fpg::Fpg21),
            (CellType::Tria6, Fpg::Fpg3),
            (CellType::Tetra10, Fpg::Fpg4),
            (CellType::Tetra10, Fpg::Fpg5),
            (CellType::Tetra10, Fpg::Fpg15),
        ] {
            reproduces(cell, fpg, &lin);
        }
    }

    /// With as many points as vertices the extrapolation interpolates: a
    /// bilinear field on QUAD4 comes back exactly (ξη is a QUAD4 function).
    #[test]
    fn quad4_interpolates_its_bilinear_field() {
        reproduces(CellType::Quad4, Fpg::Fpg4, &|x| 1.0 + x[0] * x[1]);
    }

    #[test]
    fn one_point_goes_to_every_node() {
        let m = gauss_to_nodes(CellType::Tetra4, Fpg::Fpg1).unwrap();
        assert_eq!(m.shape(), (4, 1));
        assert!(m.iter().all(|&v| v == 1.0));
    }
}
