//! The element library and the mesh generator agree on cell orientation:
//! every volume cell of every generated SDNV103 mesh (and every surface
//! cell of the axisymmetric ones) has a positive Jacobian determinant at
//! every Gauss point of every rule the element tables use. A mismatch of
//! node-order conventions (MED's 3D cells are the mirror of code_aster's
//! reference elements) would show up here as negative volumes.

#![allow(clippy::needless_range_loop)]

use aster::mesh::taylor::{generate, TaylorParams};
use aster::mesh::{quadrature, shape};
use aster::mesh::{CellType, Mesh};

fn det_j(mesh: &Mesh, nodes: &[usize], kind: CellType, xi: [f64; 3]) -> f64 {
    let s = shape::eval(kind, xi);
    let dim = kind.dim();
    let mut j = [[0.0f64; 3]; 3];
    for (a, &n) in nodes.iter().enumerate() {
        let x = mesh.coords[n];
        for r in 0..dim {
            for c in 0..dim {
                j[r][c] += x[r] * s.dn()[a][c];
            }
        }
    }
    match dim {
        2 => j[0][0] * j[1][1] - j[0][1] * j[1][0],
        3 => {
            j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
                - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
                + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0])
        }
        _ => unreachable!(),
    }
}

#[test]
fn generated_cells_have_positive_jacobians_with_the_element_library() {
    for m in ['A', 'B', 'D', 'E', 'H', 'J'] {
        let p = TaylorParams::for_modelling(m).expect("known modelling");
        let mesh = generate(&p).expect("mesh generated");
        let mut checked = 0;
        for (ci, cell) in mesh.cells.iter().enumerate() {
            if cell.kind.dim() != mesh.dim {
                continue;
            }
            for &fpg in quadrature::families(cell.kind) {
                let rule = quadrature::rule(cell.kind, fpg).expect("rule exists");
                for xi in &rule.points {
                    let d = det_j(&mesh, &cell.nodes, cell.kind, *xi);
                    assert!(
                        d > 0.0,
                        "modelling {m}: cell {ci} ({}) has det J = {d} at {xi:?} ({})",
                        cell.kind.aster_name(),
                        fpg.name()
                    );
                }
            }
            checked += 1;
        }
        assert!(checked > 0, "modelling {m}: no cell checked");
    }
}
