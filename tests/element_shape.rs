//! Property tests of the reference shape functions and Gauss rules, run
//! over every cell type. References are mathematical identities (partition
//! of unity, Kronecker property, polynomial reproduction, exact integrals of
//! monomials), not values computed by the code under test.

use aster::mesh::quadrature::{families, rule, Fpg};
use aster::mesh::shape::{eval, med_to_aster, reference_measure, reference_nodes};
use aster::mesh::CellType;

const CELLS: [CellType; 12] = [
    CellType::Seg2,
    CellType::Seg3,
    CellType::Tria3,
    CellType::Tria6,
    CellType::Quad4,
    CellType::Quad8,
    CellType::Tetra4,
    CellType::Tetra10,
    CellType::Penta6,
    CellType::Penta15,
    CellType::Hexa8,
    CellType::Hexa20,
];

/// Deterministic interior sample points (a small LCG keeps the test free of
/// any dependency and reproducible).
fn sample_points(cell: CellType, n: usize) -> Vec<[f64; 3]> {
    let mut s: u64 = 0x2545_F491_4F6C_DD1D;
    let mut next = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 11) as f64) / ((1u64 << 53) as f64)
    };
    let mut pts = Vec::new();
    while pts.len() < n {
        let u = [next(), next(), next()];
        let p = match cell {
            CellType::Seg2 | CellType::Seg3 => [2.0 * u[0] - 1.0, 0.0, 0.0],
            CellType::Quad4 | CellType::Quad8 => [2.0 * u[0] - 1.0, 2.0 * u[1] - 1.0, 0.0],
            CellType::Hexa8 | CellType::Hexa20 => {
                [2.0 * u[0] - 1.0, 2.0 * u[1] - 1.0, 2.0 * u[2] - 1.0]
            }
            CellType::Tria3 | CellType::Tria6 => {
                if u[0] + u[1] > 1.0 {
                    continue;
                }
                [u[0], u[1], 0.0]
            }
            CellType::Tetra4 | CellType::Tetra10 => {
                if u[0] + u[1] + u[2] > 1.0 {
                    continue;
                }
                u
            }
            _ => {
                if u[1] + u[2] > 1.0 {
                    continue;
                }
                [2.0 * u[0] - 1.0, u[1], u[2]]
            }
        };
        pts.push(p);
    }
    pts
}

#[test]
fn partition_of_unity_and_zero_derivative_sum() {
    for cell in CELLS {
        for p in sample_points(cell, 20) {
            let s = eval(cell, p);
            let sum: f64 = s.n().iter().sum();
            assert!((sum - 1.0).abs() < 1e-14, "{cell:?} at {p:?}: ΣN = {sum}");
            for k in 0..3 {
                let d: f64 = s.dn().iter().map(|g| g[k]).sum();
                assert!(d.abs() < 1e-13, "{cell:?} at {p:?}: Σ∂N/∂ξ{k} = {d}");
            }
        }
    }
}

#[test]
fn kronecker_delta_at_nodes() {
    for cell in CELLS {
        let nodes = reference_nodes(cell);
        assert_eq!(nodes.len(), cell.nnodes(), "{cell:?}");
        for (j, x) in nodes.iter().enumerate() {
            let s = eval(cell, *x);
            for (i, ni) in s.n().iter().enumerate() {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((ni - want).abs() < 1e-14, "{cell:?}: N{i}(node {j}) = {ni}");
            }
        }
    }
}

#[test]
fn derivatives_match_finite_differences() {
    let h = 1e-6;
    for cell in CELLS {
        for p in sample_points(cell, 10) {
            let s = eval(cell, p);
            for k in 0..cell.dim() {
                let mut pp = p;
                let mut pm = p;
                pp[k] += h;
                pm[k] -= h;
                let (sp, sm) = (eval(cell, pp), eval(cell, pm));
                for i in 0..cell.nnodes() {
                    let fd = (sp.n()[i] - sm.n()[i]) / (2.0 * h);
                    let an = s.dn()[i][k];
                    assert!(
                        (fd - an).abs() < 1e-8,
                        "{cell:?} N{i} ∂ξ{k}: {an} vs fd {fd}"
                    );
                }
            }
        }
    }
}

/// Interpolates the nodal values of `f` and checks value and gradient
/// against `f` and `grad` at interior points.
fn check_reproduction(
    cell: CellType,
    f: &dyn Fn([f64; 3]) -> f64,
    grad: &dyn Fn([f64; 3]) -> [f64; 3],
    what: &str,
) {
    let nodal: Vec<f64> = reference_nodes(cell).iter().map(|x| f(*x)).collect();
    for p in sample_points(cell, 15) {
        let s = eval(cell, p);
        let v: f64 = s.n().iter().zip(&nodal).map(|(n, u)| n * u).sum();
        assert!((v - f(p)).abs() < 1e-13, "{cell:?} {what}: {v} vs {}", f(p));
        let g = grad(p);
        for k in 0..cell.dim() {
            let gk: f64 = s.dn().iter().zip(&nodal).map(|(d, u)| d[k] * u).sum();
            assert!(
                (gk - g[k]).abs() < 1e-12,
                "{cell:?} {what} ∂{k}: {gk} vs {}",
                g[k]
            );
        }
    }
}

#[test]
fn linear_fields_are_reproduced() {
    let c = [0.3, -1.7, 0.9, 2.2];
    for cell in CELLS {
        let d = cell.dim();
        let f = |x: [f64; 3]| c[0] + (0..d).map(|k| c[k + 1] * x[k]).sum::<f64>();
        let g = |_: [f64; 3]| [c[1], c[2], c[3]];
        check_reproduction(cell, &f, &g, "linear");
    }
}

#[test]
fn complete_quadratic_fields_are_reproduced_by_quadratic_cells() {
    // Full quadratic q(x) = Σ a_kl x_k x_l + linear part; every quadratic
    // cell here (SEG3, TRIA6, QUAD8, TETRA10, PENTA15, HEXA20) contains P2.
    let a = [[0.7, -0.4, 0.25], [-0.4, 1.3, 0.6], [0.25, 0.6, -0.9]];
    let b = [0.5, -0.2, 1.1];
    for cell in CELLS.into_iter().filter(|c| c.is_quadratic()) {
        let d = cell.dim();
        let f = |x: [f64; 3]| {
            let mut v = 0.1;
            for k in 0..d {
                v += b[k] * x[k];
                for l in 0..d {
                    v += a[k][l] * x[k] * x[l];
                }
            }
            v
        };
        let g = |x: [f64; 3]| {
            let mut g = [0.0; 3];
            for k in 0..d {
                g[k] = b[k] + 2.0 * (0..d).map(|l| a[k][l] * x[l]).sum::<f64>();
            }
            g
        };
        check_reproduction(cell, &f, &g, "quadratic");
    }
}

#[test]
fn med_order_is_the_mirror_of_code_aster_order_for_3d_cells() {
    for cell in CELLS {
        let p = med_to_aster(cell);
        let mut sorted = p.clone();
        sorted.sort();
        assert_eq!(sorted, (0..cell.nnodes()).collect::<Vec<_>>());
        let moved = p.iter().enumerate().any(|(i, &j)| i != j);
        assert_eq!(moved, cell.dim() == 3, "{cell:?}");
    }
    // code_aster's HEXA20 node 13 (elrfno) is the vertical edge 1-5 at (-1,-1,0).
    let p = med_to_aster(CellType::Hexa20);
    assert_eq!(reference_nodes(CellType::Hexa20)[p[12]], [-1.0, -1.0, 0.0]);
    // code_aster's PENTA15 node 10 is the vertical edge 1-4 at (0,1,0).
    let p = med_to_aster(CellType::Penta15);
    assert_eq!(reference_nodes(CellType::Penta15)[p[9]], [0.0, 1.0, 0.0]);
    // code_aster's TETRA4 node 2 is at (0,0,1); in MED order it is node 3.
    assert_eq!(reference_nodes(CellType::Tetra4)[2], [0.0, 0.0, 1.0]);
    // TETRA10: code_aster's node 5 (edge 1-2) is MED's node 7 (edge 3-1 of
    // MED's vertices, code_aster's vertices 1 and 2 being MED's 1 and 3);
    // every mid-node sits at the middle of its MED edge.
    let p = med_to_aster(CellType::Tetra10);
    assert_eq!(p[4], 6);
    let r = reference_nodes(CellType::Tetra10);
    for (k, &(a, b)) in CellType::Tetra10.mid_edges().iter().enumerate() {
        let mid: [f64; 3] = std::array::from_fn(|i| 0.5 * (r[a][i] + r[b][i]));
        assert_eq!(r[4 + k], mid, "mid-node {k}");
    }
}

fn factorial(n: u32) -> f64 {
    (1..=n).map(f64::from).product()
}

/// Exact integral of x^a y^b z^c over the reference cell.
fn monomial_integral(cell: CellType, e: [u32; 3]) -> f64 {
    let line = |a: u32| {
        if a % 2 == 1 {
            0.0
        } else {
            2.0 / f64::from(a + 1)
        }
    };
    let simplex2 = |a: u32, b: u32| factorial(a) * factorial(b) / factorial(a + b + 2);
    match cell {
        CellType::Seg2 | CellType::Seg3 => line(e[0]),
        CellType::Quad4 | CellType::Quad8 => line(e[0]) * line(e[1]),
        CellType::Hexa8 | CellType::Hexa20 => line(e[0]) * line(e[1]) * line(e[2]),
        CellType::Tria3 | CellType::Tria6 => simplex2(e[0], e[1]),
        CellType::Tetra4 | CellType::Tetra10 => {
            factorial(e[0]) * factorial(e[1]) * factorial(e[2]) / factorial(e[0] + e[1] + e[2] + 3)
        }
        _ => line(e[0]) * simplex2(e[1], e[2]),
    }
}

#[test]
fn weights_sum_to_reference_measure() {
    for cell in CELLS {
        for &fpg in families(cell) {
            let r = rule(cell, fpg).unwrap();
            let s: f64 = r.weights.iter().sum();
            assert!(
                (s - reference_measure(cell)).abs() < 1e-14,
                "{cell:?} {}",
                fpg.name()
            );
            assert_eq!(r.points.len(), r.weights.len());
        }
    }
}

#[test]
fn rules_integrate_monomials_of_their_degree_exactly() {
    for cell in CELLS {
        let d = cell.dim() as u32;
        let prism = matches!(cell, CellType::Penta6 | CellType::Penta15);
        for &fpg in families(cell) {
            let r = rule(cell, fpg).unwrap();
            let ex = r.exactness;
            for a in 0..=ex.axis.max(ex.section) {
                for b in 0..=ex.section {
                    for c in 0..=ex.section {
                        let e = [a, if d >= 2 { b } else { 0 }, if d >= 3 { c } else { 0 }];
                        if (d < 2 && b > 0) || (d < 3 && c > 0) {
                            continue;
                        }
                        let ok = if prism {
                            e[0] <= ex.axis && e[1] + e[2] <= ex.section
                        } else {
                            e.iter().sum::<u32>() <= ex.section
                        };
                        if !ok {
                            continue;
                        }
                        let q: f64 = r
                            .points
                            .iter()
                            .zip(&r.weights)
                            .map(|(p, w)| {
                                w * p[0].powi(e[0] as i32)
                                    * p[1].powi(e[1] as i32)
                                    * p[2].powi(e[2] as i32)
                            })
                            .sum();
                        let want = monomial_integral(cell, e);
                        assert!(
                            (q - want).abs() < 1e-14,
                            "{cell:?} {} x^{e:?}: {q} vs {want}",
                            fpg.name()
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn rules_are_not_exact_beyond_their_degree() {
    // Guards the exactness test itself: one degree more must fail for
    // Gauss-Legendre products (x^(2n) on n points).
    let r = rule(CellType::Hexa20, Fpg::Fpg8).unwrap();
    let q: f64 = r
        .points
        .iter()
        .zip(&r.weights)
        .map(|(p, w)| w * p[0].powi(4))
        .sum();
    assert!((q - monomial_integral(CellType::Hexa20, [4, 0, 0])).abs() > 1e-3);
}

#[test]
fn code_aster_point_counts_and_names() {
    let cases = [
        (CellType::Quad8, "FPG9", 9),
        (CellType::Quad8, "FPG4", 4),
        (CellType::Hexa20, "FPG27", 27),
        (CellType::Hexa20, "FPG8", 8),
        (CellType::Hexa8, "FPG1", 1),
        (CellType::Penta15, "FPG21", 21),
        (CellType::Penta6, "FPG6", 6),
        (CellType::Tria6, "FPG6", 6),
        (CellType::Tetra4, "FPG4", 4),
    ];
    for (cell, name, n) in cases {
        let r = rule(cell, Fpg::from_name(name).unwrap()).unwrap();
        assert_eq!(r.len(), n, "{cell:?} {name}");
    }
    assert!(rule(CellType::Hexa20, Fpg::Fpg21).is_none());
    // First point of QUAD FPG9 is (-√0.6, -√0.6) with weight 25/81.
    let r = rule(CellType::Quad8, Fpg::Fpg9).unwrap();
    assert!((r.points[0][0] + 0.774596669241483).abs() < 1e-14);
    assert!((r.weights[8] - 64.0 / 81.0).abs() < 1e-15);
}
