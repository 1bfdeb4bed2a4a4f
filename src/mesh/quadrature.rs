//! Gauss rules on the reference cells, named and ordered as code_aster's
//! `elraga.F90` names and orders them (FPG1, FPG4, FPG9, FPG27, ...), so that
//! point k here is point k of SIEF_ELGA/VARI_ELGA there.
//!
//! Abscissae and weights are computed from closed forms (√(3/5), ...) rather
//! than copied as 15-digit decimals: exactness tests then hold to round-off.
//! Coordinates are in the reference frames of [`super::shape`].

use crate::mesh::CellType;

/// code_aster's Gauss family names used by the mechanical elements.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Fpg {
    Fpg1,
    Fpg2,
    Fpg3,
    Fpg4,
    Fpg5,
    Fpg6,
    Fpg7,
    Fpg8,
    Fpg9,
    Fpg15,
    Fpg21,
    Fpg27,
}

impl Fpg {
    pub const ALL: [Fpg; 12] = [
        Fpg::Fpg1,
        Fpg::Fpg2,
        Fpg::Fpg3,
        Fpg::Fpg4,
        Fpg::Fpg5,
        Fpg::Fpg6,
        Fpg::Fpg7,
        Fpg::Fpg8,
        Fpg::Fpg9,
        Fpg::Fpg15,
        Fpg::Fpg21,
        Fpg::Fpg27,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Fpg::Fpg1 => "FPG1",
            Fpg::Fpg2 => "FPG2",
            Fpg::Fpg3 => "FPG3",
            Fpg::Fpg4 => "FPG4",
            Fpg::Fpg5 => "FPG5",
            Fpg::Fpg6 => "FPG6",
            Fpg::Fpg7 => "FPG7",
            Fpg::Fpg8 => "FPG8",
            Fpg::Fpg9 => "FPG9",
            Fpg::Fpg15 => "FPG15",
            Fpg::Fpg21 => "FPG21",
            Fpg::Fpg27 => "FPG27",
        }
    }

    pub fn from_name(name: &str) -> Option<Fpg> {
        Fpg::ALL.into_iter().find(|f| f.name() == name)
    }
}

/// Polynomial degree integrated exactly. Prisms integrate the triangle
/// (ξ₂, ξ₃) and the axis ξ₁ to different degrees, hence two numbers; for
/// other cells both are the total degree.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Exactness {
    /// Total degree in the cross-section (all coordinates for non-prisms).
    pub section: u32,
    /// Degree along the prism axis ξ₁ (equal to `section` for non-prisms).
    pub axis: u32,
}

/// A quadrature rule: points in reference coordinates and weights.
#[derive(Debug, Clone, PartialEq)]
pub struct QuadRule {
    pub fpg: Fpg,
    pub points: Vec<[f64; 3]>,
    pub weights: Vec<f64>,
    pub exactness: Exactness,
}

impl QuadRule {
    pub fn len(&self) -> usize {
        self.weights.len()
    }
    pub fn is_empty(&self) -> bool {
        self.weights.is_empty()
    }
}

/// The families this module provides for a cell, in increasing size.
pub fn families(cell: CellType) -> &'static [Fpg] {
    use Fpg::*;
    match cell {
        CellType::Poi1 => &[Fpg1],
        CellType::Seg2 | CellType::Seg3 => &[Fpg1, Fpg2, Fpg3],
        CellType::Tria3 | CellType::Tria6 => &[Fpg1, Fpg3, Fpg4, Fpg6, Fpg7],
        CellType::Quad4 | CellType::Quad8 => &[Fpg1, Fpg4, Fpg9],
        CellType::Tetra4 | CellType::Tetra10 => &[Fpg1, Fpg4, Fpg5, Fpg15],
        CellType::Penta6 | CellType::Penta15 => &[Fpg1, Fpg6, Fpg8, Fpg21],
        CellType::Hexa8 | CellType::Hexa20 => &[Fpg1, Fpg8, Fpg27],
    }
}

/// The rule `fpg` on `cell`, or `None` when code_aster has no such family
/// for that cell (the caller turns this into a diagnostic).
pub fn rule(cell: CellType, fpg: Fpg) -> Option<QuadRule> {
    if !families(cell).contains(&fpg) {
        return None;
    }
    let (points, weights, exactness) = match cell {
        CellType::Poi1 => (vec![[0.0; 3]], vec![1.0], exact(99)),
        CellType::Seg2 | CellType::Seg3 => segment(fpg),
        CellType::Quad4 | CellType::Quad8 => quadrangle(fpg),
        CellType::Hexa8 | CellType::Hexa20 => hexahedron(fpg),
        CellType::Tria3 | CellType::Tria6 => {
            let (p, w, d) = triangle(fpg);
            (p.iter().map(|q| [q[0], q[1], 0.0]).collect(), w, exact(d))
        }
        CellType::Tetra4 | CellType::Tetra10 => tetrahedron(fpg),
        CellType::Penta6 | CellType::Penta15 => prism(fpg),
    };
    Some(QuadRule {
        fpg,
        points,
        weights,
        exactness,
    })
}

type Rule = (Vec<[f64; 3]>, Vec<f64>, Exactness);

fn exact(d: u32) -> Exactness {
    Exactness {
        section: d,
        axis: d,
    }
}

/// Gauss-Legendre points and weights on [-1, 1] in code_aster's order for
/// products (ascending abscissae).
fn gauss_line(n: usize) -> (Vec<f64>, Vec<f64>) {
    match n {
        1 => (vec![0.0], vec![2.0]),
        2 => {
            let a = (1.0f64 / 3.0).sqrt();
            (vec![-a, a], vec![1.0, 1.0])
        }
        3 => {
            let a = 0.6f64.sqrt();
            (vec![-a, 0.0, a], vec![5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0])
        }
        _ => unreachable!("only 1 to 3 point lines are used"),
    }
}

fn segment(fpg: Fpg) -> Rule {
    match fpg {
        Fpg::Fpg1 => (vec![[0.0; 3]], vec![2.0], exact(1)),
        Fpg::Fpg2 => {
            // elraga lists +1/√3 first for segments.
            let a = (1.0f64 / 3.0).sqrt();
            (
                vec![[a, 0.0, 0.0], [-a, 0.0, 0.0]],
                vec![1.0, 1.0],
                exact(3),
            )
        }
        _ => {
            let (x, w) = gauss_line(3);
            (x.iter().map(|&a| [a, 0.0, 0.0]).collect(), w, exact(5))
        }
    }
}

fn quadrangle(fpg: Fpg) -> Rule {
    match fpg {
        Fpg::Fpg1 => (vec![[0.0; 3]], vec![4.0], exact(1)),
        Fpg::Fpg4 => {
            let a = (1.0f64 / 3.0).sqrt();
            let p = [[-a, -a], [a, -a], [a, a], [-a, a]];
            (
                p.iter().map(|q| [q[0], q[1], 0.0]).collect(),
                vec![1.0; 4],
                exact(3),
            )
        }
        _ => {
            // FPG9 order: the 4 corner points counter-clockwise, the 4 edge
            // points (edges 1-2, 2-3, 3-4, 4-1), then the centre.
            let a = 0.6f64.sqrt();
            let p = [
                [-a, -a],
                [a, -a],
                [a, a],
                [-a, a],
                [0.0, -a],
                [a, 0.0],
                [0.0, a],
                [-a, 0.0],
                [0.0, 0.0],
            ];
            let (c, e, m) = (25.0 / 81.0, 40.0 / 81.0, 64.0 / 81.0);
            let w = vec![c, c, c, c, e, e, e, e, m];
            (p.iter().map(|q| [q[0], q[1], 0.0]).collect(), w, exact(5))
        }
    }
}

fn hexahedron(fpg: Fpg) -> Rule {
    let (n, d) = match fpg {
        Fpg::Fpg1 => (1, 1),
        Fpg::Fpg8 => (2, 3),
        _ => (3, 5),
    };
    let (x, w) = gauss_line(n);
    let mut pts = Vec::new();
    let mut wts = Vec::new();
    // ξ₁ slowest, ξ₃ fastest, as elraga loops.
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                pts.push([x[i], x[j], x[k]]);
                wts.push(w[i] * w[j] * w[k]);
            }
        }
    }
    (pts, wts, exact(d))
}

/// Triangle rules on {ξ,η ≥ 0, ξ+η ≤ 1}: points (ξ, η), weights, degree.
fn triangle(fpg: Fpg) -> (Vec<[f64; 2]>, Vec<f64>, u32) {
    match fpg {
        Fpg::Fpg1 => (vec![[1.0 / 3.0, 1.0 / 3.0]], vec![0.5], 1),
        Fpg::Fpg3 => (
            vec![
                [1.0 / 6.0, 1.0 / 6.0],
                [2.0 / 3.0, 1.0 / 6.0],
                [1.0 / 6.0, 2.0 / 3.0],
            ],
            vec![1.0 / 6.0; 3],
            2,
        ),
        Fpg::Fpg4 => (
            vec![[0.2, 0.2], [0.6, 0.2], [0.2, 0.6], [1.0 / 3.0, 1.0 / 3.0]],
            vec![25.0 / 96.0, 25.0 / 96.0, 25.0 / 96.0, -27.0 / 96.0],
            3,
        ),
        Fpg::Fpg6 => {
            // Strang-Fix / Dunavant degree-4 rule; the abscissae are roots of
            // a cubic and have no short closed form, so 20 digits are given.
            let a = 0.445_948_490_915_964_9;
            let b = 0.091_576_213_509_770_74;
            let wa = 0.223_381_589_678_011_47 / 2.0;
            let wb = 0.109_951_743_655_321_87 / 2.0;
            (
                vec![
                    [b, b],
                    [1.0 - 2.0 * b, b],
                    [b, 1.0 - 2.0 * b],
                    [a, 1.0 - 2.0 * a],
                    [a, a],
                    [1.0 - 2.0 * a, a],
                ],
                vec![wb, wb, wb, wa, wa, wa],
                4,
            )
        }
        _ => {
            let (p, w) = hammer7();
            (p, w, 5)
        }
    }
}

/// Hammer's 7-point degree-5 rule (Radon), closed forms with √15.
fn hammer7() -> (Vec<[f64; 2]>, Vec<f64>) {
    let r = 15.0f64.sqrt();
    let a = (6.0 + r) / 21.0; // 0.4701...
    let b = (6.0 - r) / 21.0; // 0.1012...
    let wa = (155.0 + r) / 2400.0;
    let wb = (155.0 - r) / 2400.0;
    let t = 1.0 / 3.0;
    (
        vec![
            [t, t],
            [a, a],
            [1.0 - 2.0 * a, a],
            [a, 1.0 - 2.0 * a],
            [b, b],
            [1.0 - 2.0 * b, b],
            [b, 1.0 - 2.0 * b],
        ],
        vec![9.0 / 80.0, wa, wa, wa, wb, wb, wb],
    )
}

fn tetrahedron(fpg: Fpg) -> Rule {
    match fpg {
        Fpg::Fpg1 => (vec![[0.25; 3]], vec![1.0 / 6.0], exact(1)),
        Fpg::Fpg4 => {
            let r5 = 5.0f64.sqrt();
            let a = (5.0 - r5) / 20.0;
            let b = (5.0 + 3.0 * r5) / 20.0;
            (
                vec![[a, a, a], [a, a, b], [a, b, a], [b, a, a]],
                vec![1.0 / 24.0; 4],
                exact(2),
            )
        }
        Fpg::Fpg5 => {
            let (a, b, c) = (0.25, 1.0 / 6.0, 0.5);
            (
                vec![[a, a, a], [b, b, b], [b, b, c], [b, c, b], [c, b, b]],
                vec![-2.0 / 15.0, 3.0 / 40.0, 3.0 / 40.0, 3.0 / 40.0, 3.0 / 40.0],
                exact(3),
            )
        }
        _ => {
            let r = 15.0f64.sqrt();
            let a1 = (7.0 + r) / 34.0;
            let b1 = (13.0 - 3.0 * r) / 34.0;
            let w1 = (2665.0 - 14.0 * r) / 226_800.0;
            let a2 = (7.0 - r) / 34.0;
            let b2 = (13.0 + 3.0 * r) / 34.0;
            let w2 = (2665.0 + 14.0 * r) / 226_800.0;
            let c = (5.0 - r) / 20.0;
            let d = (5.0 + r) / 20.0;
            let w3 = 5.0 / 567.0;
            let mut p = vec![[0.25; 3]];
            let mut w = vec![8.0 / 405.0];
            for (a, b, wt) in [(a1, b1, w1), (a2, b2, w2)] {
                p.extend([[a, a, a], [a, a, b], [a, b, a], [b, a, a]]);
                w.extend([wt; 4]);
            }
            p.extend([
                [c, c, d],
                [c, d, c],
                [d, c, c],
                [c, d, d],
                [d, c, d],
                [d, d, c],
            ]);
            w.extend([w3; 6]);
            (p, w, exact(5))
        }
    }
}

/// Prism rules: a triangle rule in (ξ₂, ξ₃) times a Gauss line along ξ₁,
/// with ξ₁ the slow index as in elraga.
fn prism(fpg: Fpg) -> Rule {
    let (tri, line, ex): (Vec<[f64; 2]>, usize, Exactness) = match fpg {
        Fpg::Fpg1 => {
            return (vec![[0.0, 1.0 / 3.0, 1.0 / 3.0]], vec![1.0], exact(1));
        }
        // FPG6: the 3 mid-edge points of the triangle (degree 2) x 2 Gauss.
        Fpg::Fpg6 => (
            vec![[0.5, 0.5], [0.0, 0.5], [0.5, 0.0]],
            2,
            Exactness {
                section: 2,
                axis: 3,
            },
        ),
        Fpg::Fpg8 => (
            vec![[1.0 / 3.0, 1.0 / 3.0], [0.6, 0.2], [0.2, 0.6], [0.2, 0.2]],
            2,
            Exactness {
                section: 3,
                axis: 3,
            },
        ),
        _ => (hammer7().0, 3, exact(5)),
    };
    let tw: Vec<f64> = match fpg {
        Fpg::Fpg6 => vec![1.0 / 6.0; 3],
        Fpg::Fpg8 => vec![-27.0 / 96.0, 25.0 / 96.0, 25.0 / 96.0, 25.0 / 96.0],
        _ => hammer7().1,
    };
    let (x, w) = gauss_line(line);
    let mut pts = Vec::new();
    let mut wts = Vec::new();
    for i in 0..line {
        for (t, tw) in tri.iter().zip(&tw) {
            pts.push([x[i], t[0], t[1]]);
            wts.push(w[i] * tw);
        }
    }
    (pts, wts, ex)
}
