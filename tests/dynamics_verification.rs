//! Verification of the DYNA_NON_LINE engine (no contact) against
//! independent references: exact kinematics, closed-form wave solutions,
//! energy balances, patch tests and the equivalence of cut and uncut
//! steps. docs/dynamics.md §6 lists the measured numbers.
#![allow(clippy::needless_range_loop)]

mod dynamics_support;

use aster::mesh::{Cell, CellType, Mesh};
use aster::model::Dof;
use dynamics_support::*;

/// A 2×2 QUAD8 patch of [0,2]² touching the axis, with the middle corner
/// moved to (1.15, 0.9) and straight edges (mid-nodes at edge midpoints).
fn distorted_patch() -> (Mesh, Vec<usize>) {
    let corner = |i: usize, j: usize| -> [f64; 3] {
        if (i, j) == (1, 1) {
            [1.15, 0.9, 0.0]
        } else {
            [i as f64, j as f64, 0.0]
        }
    };
    let mut coords = Vec::new();
    let mut cid = [[0usize; 3]; 3];
    for j in 0..3 {
        for i in 0..3 {
            cid[i][j] = coords.len();
            coords.push(corner(i, j));
        }
    }
    let mut mids = std::collections::HashMap::new();
    let mut mid = |a: usize, b: usize, coords: &mut Vec<[f64; 3]>| -> usize {
        let key = (a.min(b), a.max(b));
        *mids.entry(key).or_insert_with(|| {
            let (p, q) = (coords[a], coords[b]);
            coords.push([(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0, 0.0]);
            coords.len() - 1
        })
    };
    let mut cells = Vec::new();
    for j in 0..2 {
        for i in 0..2 {
            let c = [cid[i][j], cid[i + 1][j], cid[i + 1][j + 1], cid[i][j + 1]];
            let m: Vec<usize> = (0..4)
                .map(|k| mid(c[k], c[(k + 1) % 4], &mut coords))
                .collect();
            let mut nodes = c.to_vec();
            nodes.extend(m);
            cells.push(Cell {
                kind: CellType::Quad8,
                nodes,
            });
        }
    }
    let boundary: Vec<usize> = (0..coords.len())
        .filter(|&n| {
            let [x, y, _] = coords[n];
            x == 0.0 || x == 2.0 || y == 0.0 || y == 2.0
        })
        .collect();
    let mesh = Mesh {
        dim: 2,
        coords,
        cells,
        ..Mesh::default()
    };
    (mesh, boundary)
}

const NEWMARK_ELAS: &str = "
RESU = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOQ),
    COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'),
    INCREMENT=_F(LIST_INST=L_INST),
    SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'))
";

/// (4) Uniform strain u_r = a r, u_z = b z imposed on the boundary of a
/// distorted patch, interior nodes free, inertia negligible (RHO = 1e-12,
/// one step of 1 s): the solver must reproduce the linear field at the
/// interior nodes and σ = D(a, b, a, 0) at every Gauss point, for AXIS
/// (FPG9) and AXIS_SI (FPG4).
#[test]
fn patch_test_uniform_strain_through_the_assembled_solver() {
    let (a, b) = (1e-3, -2e-3);
    let (e, nu) = (1000.0, 0.3);
    for modelisation in ["AXIS", "AXIS_SI"] {
        let (mesh, boundary) = distorted_patch();
        let cells: Vec<usize> = (0..mesh.ncells()).collect();
        let mo = model(&mesh, modelisation, &cells);
        let mut imp = Vec::new();
        for &n in &boundary {
            let [r, z, _] = mesh.coords[n];
            imp.push(aster::model::ImposedDof {
                node: n,
                dof: Dof::Dx,
                value: a * r,
            });
            imp.push(aster::model::ImposedDof {
                node: n,
                dof: Dof::Dy,
                value: b * z,
            });
        }
        let coords = mesh.coords.clone();
        let mut st = study(
            mesh,
            mo,
            material(e, nu, 1e-12, None),
            imp,
            None,
            vec![0.0, 1.0],
            None,
        );
        let args = args_of(NEWMARK_ELAS, "DYNA_NON_LINE", 0);
        exec(&mut st, "DYNA_NON_LINE", &args, "RESU").unwrap();
        let r = result(&st, "RESU");
        assert_eq!(r.steps.len(), 2);
        let last = &r.steps[1];
        let depl = &last.nodal["DEPL"];
        for (n, c) in coords.iter().enumerate() {
            let (ux, uy) = (depl.get(n, "DX").unwrap(), depl.get(n, "DY").unwrap());
            assert!(
                (ux - a * c[0]).abs() < 1e-12,
                "{modelisation} node {n}: DX {ux}"
            );
            assert!(
                (uy - b * c[1]).abs() < 1e-12,
                "{modelisation} node {n}: DY {uy}"
            );
        }
        let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let mu = e / (2.0 * (1.0 + nu));
        let tr = 2.0 * a + b;
        let expect = [
            lambda * tr + 2.0 * mu * a,
            lambda * tr + 2.0 * mu * b,
            lambda * tr + 2.0 * mu * a,
            0.0,
        ];
        let sief = &last.gauss["SIEF_ELGA"];
        assert_eq!(sief.components, ["SIXX", "SIYY", "SIZZ", "SIXY"]);
        let npg = if modelisation == "AXIS" { 9 } else { 4 };
        for c in 0..4 {
            assert_eq!(sief.npg(c), npg);
            for p in 0..npg {
                for k in 0..4 {
                    let v = sief.cell(c)[p * 4 + k];
                    assert!(
                        (v - expect[k]).abs() < 1e-10 * expect[0].abs(),
                        "{modelisation} cell {c} point {p} cmp {k}: {v} vs {}",
                        expect[k]
                    );
                }
            }
        }
    }
}
