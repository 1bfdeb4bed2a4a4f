//! Orthogonal projection of a point on master cells of every supported
//! type, against distances computed independently (plane equations, and
//! for curved cells a minimisation written here on the analytic surface
//! the quadratic cell reproduces exactly).

use aster::contact::project;
use aster::mesh::CellType;

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Root of a continuous function on [a, b] with a sign change, by bisection.
fn bisect(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let fa = f(a);
    assert!(fa * f(b) < 0.0, "no sign change");
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if (f(m) < 0.0) == (fa < 0.0) {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

#[test]
fn seg2_distance_gap_sign_and_outside_measure() {
    // Segment from (0,0) to (4,0): t = +x, n_in = (−t_y, t_x) = +y, so the
    // master body lies above (y > 0) and a point above has a negative gap.
    let xs = [[0.0, 0.0, 0.0], [4.0, 0.0, 0.0]];
    let p = project(CellType::Seg2, &xs, [1.0, 2.0, 0.0], 2).unwrap();
    assert!((p.xi[0] + 0.5).abs() < 1e-14);
    assert!((p.distance - 2.0).abs() < 1e-14);
    assert!((p.gap + 2.0).abs() < 1e-14);
    assert_eq!(p.normal, [0.0, 1.0, 0.0]);
    assert!((p.shape[0] - 0.75).abs() < 1e-14 && (p.shape[1] - 0.25).abs() < 1e-14);
    let below = project(CellType::Seg2, &xs, [3.0, -0.5, 0.0], 2).unwrap();
    assert!((below.gap - 0.5).abs() < 1e-14);
    // Beyond the end: ξ = 1.25, i.e. 0.25 outside in parametric units.
    let out = project(CellType::Seg2, &xs, [4.5, 1.0, 0.0], 2).unwrap();
    assert!((out.outside - 0.25).abs() < 1e-13);
    assert!((out.distance - 1.0).abs() < 1e-13);
}

#[test]
fn seg3_curved_parabola() {
    // Nodes (−1,1), (1,1), mid (0,0): x = ξ, y = ξ², exactly the parabola
    // y = x². Closest point to (0.5, 2): root of 4x³ − 6x − 1 = 0 near 1.3.
    let xs = [[-1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 0.0]];
    let q = [0.5, 2.0, 0.0];
    let x = bisect(|x| 2.0 * (x - 0.5) + 4.0 * x * (x * x - 2.0), 1.0, 1.6);
    let reference = dist([x, x * x, 0.0], q);
    let p = project(CellType::Seg3, &xs, q, 2).unwrap();
    assert!(
        (p.distance - reference).abs() < 1e-12,
        "{} vs {reference}",
        p.distance
    );
    assert!((p.xi[0] - x).abs() < 1e-10);
    // Tangent (1, 2x) normalised, n_in = (−2x, 1)/√(1+4x²): the gap is
    // negative because q lies on the side n_in points to (above).
    assert!(p.gap < 0.0 && (p.gap.abs() - reference).abs() < 1e-12);
    // On the symmetry axis the centre is a distance maximum: the closest
    // points are x = ±√(h − ½), at distance √(h − ¼).
    let h = 2.0;
    let s = project(CellType::Seg3, &xs, [0.0, h, 0.0], 2).unwrap();
    assert!(
        (s.distance - (h - 0.25_f64).sqrt()).abs() < 1e-12,
        "{}",
        s.distance
    );
    assert!((s.xi[0].abs() - (h - 0.5_f64).sqrt()).abs() < 1e-10);
}

#[test]
fn quad4_tilted_plane() {
    // A general quadrilateral in the plane z = 0.2x + 0.1y + 1.
    let z = |x: f64, y: f64| 0.2 * x + 0.1 * y + 1.0;
    let c = [(0.0, 0.0), (2.0, 0.0), (2.5, 2.0), (0.0, 1.5)];
    let xs: Vec<[f64; 3]> = c.iter().map(|&(x, y)| [x, y, z(x, y)]).collect();
    let q = [1.0, 0.8, 3.0];
    let p = project(CellType::Quad4, &xs, q, 3).unwrap();
    let reference = (q[2] - z(q[0], q[1])) / (1.0f64 + 0.04 + 0.01).sqrt();
    assert!((p.distance - reference.abs()).abs() < 1e-12);
    assert_eq!(p.outside, 0.0);
    // Counter-clockwise seen from +z: outward normal up, n_in down, q
    // above the plane, so the gap is positive (open).
    assert!((p.gap - reference).abs() < 1e-12);
    assert!(p.normal[2] < 0.0);
    // The projection lies in the plane and q − x is along the normal.
    assert!((p.point[2] - z(p.point[0], p.point[1])).abs() < 1e-12);
    let s: f64 = p.shape.iter().sum();
    assert!((s - 1.0).abs() < 1e-14);
}

#[test]
fn quad8_curved_cylinder() {
    // Nodes on z = 1 − 0.3x² (x ∈ [−1, 1]), straight along y ∈ [0, 2]:
    // the serendipity map reproduces this parabolic cylinder exactly, so
    // the distance reduces to the 2D distance to the parabola.
    let zf = |x: f64| 1.0 - 0.3 * x * x;
    let pts = [
        (-1.0, 0.0),
        (1.0, 0.0),
        (1.0, 2.0),
        (-1.0, 2.0),
        (0.0, 0.0),
        (1.0, 1.0),
        (0.0, 2.0),
        (-1.0, 1.0),
    ];
    let xs: Vec<[f64; 3]> = pts.iter().map(|&(x, y)| [x, y, zf(x)]).collect();
    let q = [0.4, 1.3, 2.0];
    let x = bisect(
        |x| 2.0 * (x - q[0]) + 2.0 * (zf(x) - q[2]) * (-0.6 * x),
        0.0,
        1.0,
    );
    let reference = ((x - q[0]).powi(2) + (zf(x) - q[2]).powi(2)).sqrt();
    let p = project(CellType::Quad8, &xs, q, 3).unwrap();
    assert!(
        (p.distance - reference).abs() < 1e-12,
        "{} vs {reference}",
        p.distance
    );
    assert!((p.point[1] - q[1]).abs() < 1e-12);
    assert!((p.point[0] - x).abs() < 1e-10);
}

#[test]
fn tria3_plane_inside_and_outside() {
    let xs = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let p = project(CellType::Tria3, &xs, [0.2, 0.3, 0.7], 3).unwrap();
    assert!((p.distance - 0.7).abs() < 1e-14);
    assert!((p.gap - 0.7).abs() < 1e-14);
    assert_eq!(p.normal, [0.0, 0.0, -1.0]);
    assert!((p.xi[0] - 0.2).abs() < 1e-14 && (p.xi[1] - 0.3).abs() < 1e-14);
    // Outside the hypotenuse: ξ + η − 1 = 0.3.
    let o = project(CellType::Tria3, &xs, [1.2, 0.1, -0.5], 3).unwrap();
    assert!((o.outside - 0.3).abs() < 1e-13);
    assert!((o.gap + 0.5).abs() < 1e-14);
}

#[test]
fn tria6_curved_paraboloid() {
    // Corners on z = x² + y², mid-nodes at the edge midpoints lifted to
    // the surface: the quadratic triangle is exactly that paraboloid.
    let f = |x: f64, y: f64| x * x + y * y;
    let pts = [
        (0.0, 0.0),
        (1.0, 0.0),
        (0.0, 1.0),
        (0.5, 0.0),
        (0.5, 0.5),
        (0.0, 0.5),
    ];
    let xs: Vec<[f64; 3]> = pts.iter().map(|&(x, y)| [x, y, f(x, y)]).collect();
    let q = [0.3, 0.2, 1.0];
    // Reference: Newton on the analytic squared distance
    // D(x,y) = (x−qx)² + (y−qy)² + (x²+y²−qz)², from the best grid point.
    let d = |x: f64, y: f64| (x - q[0]).powi(2) + (y - q[1]).powi(2) + (f(x, y) - q[2]).powi(2);
    let (mut x, mut y) = (0.0, 0.0);
    for i in 0..=100 {
        for j in 0..=100 {
            let (a, b) = (i as f64 / 100.0, j as f64 / 100.0);
            if d(a, b) < d(x, y) {
                (x, y) = (a, b);
            }
        }
    }
    for _ in 0..50 {
        let w = f(x, y) - q[2];
        let gx = 2.0 * (x - q[0]) + 4.0 * x * w;
        let gy = 2.0 * (y - q[1]) + 4.0 * y * w;
        let hxx = 2.0 + 8.0 * x * x + 4.0 * w;
        let hyy = 2.0 + 8.0 * y * y + 4.0 * w;
        let hxy = 8.0 * x * y;
        let det = hxx * hyy - hxy * hxy;
        x -= (hyy * gx - hxy * gy) / det;
        y -= (hxx * gy - hxy * gx) / det;
    }
    let reference = d(x, y).sqrt();
    let p = project(CellType::Tria6, &xs, q, 3).unwrap();
    assert!(
        (p.distance - reference).abs() < 1e-12,
        "{} vs {reference}",
        p.distance
    );
    assert!((p.point[0] - x).abs() < 1e-9 && (p.point[1] - y).abs() < 1e-9);
    // The surface's outward side (t1 × t2) is up, q is above: open.
    assert!(p.gap > 0.0);
}

#[test]
fn wrong_cell_for_the_dimension_is_refused() {
    let xs = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
    assert!(project(CellType::Seg2, &xs, [0.0, 1.0, 0.0], 3).is_none());
    let t = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    assert!(project(CellType::Tria3, &t, [0.0, 1.0, 0.0], 2).is_none());
    // Degenerate cell (both nodes at the same place).
    let d = [[1.0, 1.0, 0.0], [1.0, 1.0, 0.0]];
    assert!(project(CellType::Seg2, &d, [0.0, 1.0, 0.0], 2).is_none());
}
