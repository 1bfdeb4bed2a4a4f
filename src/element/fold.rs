//! Folding of a deformed cell where its Gauss points do not look.
//!
//! The elements check det F > 0 at their Gauss points only (as code_aster
//! does). An under-integrated element (AXIS_SI's QUAD8 on 2 x 2 points,
//! HEXS8 on one) can fold in an hourglass or a heavy distortion while
//! every Gauss point stays positive: the mesh tangles, nodes pass through
//! each other and the run goes on without a word (a Taylor bar at twice
//! SDNV103's speed in AXIS_SI threw a face node 90 mm up the axis). This
//! check reads the Jacobian at the cell's nodes, in the deformed
//! configuration against the initial one: det J(x) / det J(X) at a node is
//! det F there, and a value ≤ 0 means the cell has folded at that node.
//! Only for the kinematics that follow the geometry (PETIT_REAC and the
//! finite-strain ones); under PETIT the displacement is a small-strain
//! quantity and a "folded" deformed mesh means nothing.

use crate::mesh::{shape, CellType};

/// The most nodes a cell type has (HEXA27).
const MAX_NODES: usize = 27;

/// The reference derivatives of a cell type's shape functions at each of
/// its nodes (node-major: `dn[p * nn + a]` is ∂N_a/∂ξ at node p).
#[derive(Debug, Clone)]
pub struct NodeDerivatives {
    pub kind: CellType,
    nn: usize,
    dim: usize,
    dn: Vec<[f64; 3]>,
}

impl NodeDerivatives {
    pub fn new(kind: CellType) -> NodeDerivatives {
        let refs = shape::reference_nodes(kind);
        let nn = kind.nnodes();
        assert!(nn <= MAX_NODES, "{kind:?} has {nn} nodes");
        let mut dn = Vec::with_capacity(nn * nn);
        for &xi in &refs[..nn] {
            dn.extend_from_slice(shape::eval(kind, xi).dn());
        }
        NodeDerivatives {
            kind,
            nn,
            dim: kind.dim(),
            dn,
        }
    }

    /// det J at node `p` of the cell whose node a is at `x(a)`; 2D cells
    /// use x and y (a flat mesh, AXIS or plane strain).
    pub fn det(&self, p: usize, x: impl Fn(usize) -> [f64; 3]) -> f64 {
        let dn = &self.dn[p * self.nn..(p + 1) * self.nn];
        let mut j = [[0.0; 3]; 3];
        for (a, d) in dn.iter().enumerate() {
            let xa = x(a);
            for k in 0..self.dim {
                for l in 0..self.dim {
                    j[k][l] += xa[k] * d[l];
                }
            }
        }
        if self.dim == 2 {
            j[0][0] * j[1][1] - j[0][1] * j[1][0]
        } else {
            j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
                - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
                + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0])
        }
    }

    pub fn nnodes(&self) -> usize {
        self.nn
    }
}

/// The initial det J at each node of a cell (`coords` in the cell's node
/// order); a node where it is not positive is never checked (a curved
/// quadratic cell may have a zero Jacobian at a vertex and still be
/// valid at its Gauss points).
pub fn initial_dets(nd: &NodeDerivatives, coords: &[[f64; 3]]) -> Vec<f64> {
    (0..nd.nn).map(|p| nd.det(p, |a| coords[a])).collect()
}

/// The node of the cell where det F = det J(x) / det J(X) is smallest
/// among those where it is not positive (against a positive initial
/// det J), with that value; None when the cell is not folded.
/// `disp(a, k)` is component k of node a's displacement.
pub fn deepest_fold(
    nd: &NodeDerivatives,
    coords: &[[f64; 3]],
    j0: &[f64],
    disp: impl Fn(usize, usize) -> f64,
) -> Option<(usize, f64)> {
    let dim = nd.dim;
    // The deformed nodes, gathered once for all the node checks.
    let mut x = [[0.0; 3]; MAX_NODES];
    for (a, xa) in x.iter_mut().enumerate().take(nd.nn) {
        *xa = coords[a];
        for (k, xk) in xa.iter_mut().enumerate().take(dim) {
            *xk += disp(a, k);
        }
    }
    let mut deepest: Option<(usize, f64)> = None;
    for p in 0..nd.nn {
        if j0[p] <= 0.0 {
            continue;
        }
        let ratio = nd.det(p, |a| x[a]) / j0[p];
        // NaN (a non-finite motion) counts as the deepest.
        let ratio = if ratio.is_nan() {
            f64::NEG_INFINITY
        } else {
            ratio
        };
        if ratio <= 0.0 && deepest.is_none_or(|(_, m)| ratio < m) {
            deepest = Some((p, ratio));
        }
    }
    deepest
}

#[cfg(test)]
mod tests {
    use super::*;

    const QUAD8: [[f64; 3]; 8] = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.5, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 0.5, 0.0],
    ];

    #[test]
    fn a_uniform_stretch_has_its_det_f_at_every_node() {
        let nd = NodeDerivatives::new(CellType::Quad8);
        let j0 = initial_dets(&nd, &QUAD8);
        // x = 1.5 X, y = 0.5 Y: det F = 0.75 everywhere, no fold.
        let u = |a: usize, k: usize| {
            if k == 0 {
                0.5 * QUAD8[a][0]
            } else {
                -0.5 * QUAD8[a][1]
            }
        };
        assert!(deepest_fold(&nd, &QUAD8, &j0, u).is_none());
        for p in 0..8 {
            let d = nd.det(p, |a| [1.5 * QUAD8[a][0], 0.5 * QUAD8[a][1], 0.0]);
            assert!((d / j0[p] - 0.75).abs() < 1e-14, "node {p}: {}", d / j0[p]);
        }
    }

    /// The spurious mode of the QUAD8 on 2 x 2 points, u = c ξ(η² − 1/3),
    /// v = −c η(ξ² − 1/3) on the reference square (in the serendipity
    /// space, so the nodes carry it exactly): at the Gauss points ±1/√3
    /// its strain is 0 and det F = 1 + 4c²ξ²η² > 0, while at the mid-side
    /// nodes (±1, 0) det F = (1 − c/3)(1 − 2c/3), −1/9 for c = 2: a fold
    /// the Gauss points do not see.
    #[test]
    fn an_hourglass_that_the_gauss_points_miss_is_a_fold_at_a_node() {
        let x: Vec<[f64; 3]> = shape::reference_nodes(CellType::Quad8)[..8].to_vec();
        let nd = NodeDerivatives::new(CellType::Quad8);
        let j0 = initial_dets(&nd, &x);
        let c = 2.0;
        let mode = |p: [f64; 3], k: usize| {
            if k == 0 {
                c * p[0] * (p[1] * p[1] - 1.0 / 3.0)
            } else {
                -c * p[1] * (p[0] * p[0] - 1.0 / 3.0)
            }
        };
        let u = |a: usize, k: usize| mode(x[a], k);
        let g = 1.0 / 3f64.sqrt();
        for xi in [[-g, -g, 0.0], [g, -g, 0.0], [g, g, 0.0], [-g, g, 0.0]] {
            let ev = shape::eval(CellType::Quad8, xi);
            let mut f = [[1.0, 0.0], [0.0, 1.0]];
            for (a, d) in ev.dn().iter().enumerate() {
                for (k, row) in f.iter_mut().enumerate() {
                    for (l, fkl) in row.iter_mut().enumerate() {
                        // x = ξ on the reference square: ∂/∂x = ∂/∂ξ.
                        *fkl += u(a, k) * d[l];
                    }
                }
            }
            let det = f[0][0] * f[1][1] - f[0][1] * f[1][0];
            let expect = 1.0 + 4.0 * c * c * xi[0] * xi[0] * xi[1] * xi[1];
            assert!(
                (det - expect).abs() < 1e-12,
                "{xi:?}: {det} against {expect}"
            );
        }
        let (p, ratio) = deepest_fold(&nd, &x, &j0, u).expect("a fold");
        assert_eq!(x[p], [1.0, 0.0, 0.0], "node {p}");
        assert!((ratio + 1.0 / 9.0).abs() < 1e-12, "{ratio}");
    }

    #[test]
    fn a_hexa8_squashed_flat_through_a_node_is_a_fold() {
        let x: Vec<[f64; 3]> = shape::reference_nodes(CellType::Hexa8)[..8].to_vec();
        let nd = NodeDerivatives::new(CellType::Hexa8);
        let j0 = initial_dets(&nd, &x);
        assert!(j0.iter().all(|&j| j > 0.0), "{j0:?}");
        // Node 0 pushed through the opposite face of its corner.
        let u = |a: usize, k: usize| if a == 0 && k == 2 { 2.5 } else { 0.0 };
        let (p, ratio) = deepest_fold(&nd, &x, &j0, u).expect("a fold");
        assert_eq!(p, 0, "{ratio}");
        assert!(ratio < 0.0);
    }
}
