//! The meshes of the SDNV103 Taylor bar, rebuilt from the geometry
//! (docs/sdnv103.md §3, docs/mesh-generator.md).
//!
//! The structured constructions are the ones whose node counts match the
//! reference meshes (359/29 nodes axisymmetric, 2849/73 quarter): serendipity
//! cells (no face or volume centre nodes) and, in 3D, the nodes on the axis
//! shared by all the angular sectors, so the cells touching the axis are
//! wedges. Every cell is written in MED's node order, which for volume cells
//! is the mirror of code_aster's reference elements (see
//! [`super::ops::med_to_aster`]); skin cells are left in the orientation a
//! mesher would give them (SZZ with normal +z, into the bar) and are
//! oriented by `MODI_MAILLAGE/ORIE_PEAU` as the command files do.

use indexmap::IndexMap;

use super::ops;
use super::vec3::{dot, sub};
use super::{Cell, CellType, Mesh};

/// Bar radius (mm).
pub const RADIUS: f64 = 3.2;
/// Bar length (mm).
pub const LENGTH: f64 = 32.4;
/// Height of the bar's bottom face above the foundation (mm).
pub const GAP: f64 = 2.27;

/// Which of the three SDNV103 meshes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TaylorKind {
    /// 2D axisymmetric, x = radius, y = height: QUAD8 (QUAD4 if linear).
    Axis,
    /// 3D quarter cylinder, z = height: HEXA20 + PENTA15 (HEXA8 + PENTA6).
    Quarter,
    /// 3D full cylinder in TETRA4.
    Tetra,
}

/// Generator parameters.
///
/// Axis: `n1` cells across the radius, `n2` along the bar, `n3` unused.
/// Quarter: `n1` radial, `n2` axial, `n3` angular cells over 90 degrees.
/// Tetra: `n1` rings of triangles in the cross-section (ring j has 6j
/// nodes), `n2` layers along the bar, `n3` unused; always linear.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TaylorParams {
    pub kind: TaylorKind,
    pub n1: usize,
    pub n2: usize,
    pub n3: usize,
    /// The linear version, i.e. CREA_MAILLAGE QUAD_LINE of the quadratic one.
    pub linear: bool,
}

impl TaylorParams {
    /// The mesh of an SDNV103 modelling, 'A' to 'K' (no 'C').
    pub fn for_modelling(letter: char) -> Option<TaylorParams> {
        let p = |kind, n1, n2, n3, linear| TaylorParams {
            kind,
            n1,
            n2,
            n3,
            linear,
        };
        Some(match letter.to_ascii_uppercase() {
            'A' | 'G' => p(TaylorKind::Quarter, 5, 20, 6, false),
            'J' => p(TaylorKind::Quarter, 5, 20, 6, true),
            'H' | 'I' => p(TaylorKind::Quarter, 2, 2, 2, false),
            'B' => p(TaylorKind::Axis, 5, 20, 0, false),
            'D' | 'F' => p(TaylorKind::Axis, 2, 2, 0, false),
            'E' | 'K' => p(TaylorKind::Tetra, 3, 34, 0, true),
            _ => return None,
        })
    }
}

/// Above this many cells the request is surely a typo; refusing it avoids
/// an allocation failure (which would abort rather than report).
const MAX_CELLS: usize = 1_000_000;

/// Builds the mesh. Errors name the bad parameter.
pub fn generate(p: &TaylorParams) -> Result<Mesh, String> {
    let need = |v: usize, name: &str| {
        if v == 0 {
            Err(format!("{name} must be at least 1 for a {:?} mesh", p.kind))
        } else {
            Ok(())
        }
    };
    need(p.n1, "n1")?;
    need(p.n2, "n2")?;
    let ncells = match p.kind {
        TaylorKind::Axis => p.n1.checked_mul(p.n2),
        TaylorKind::Quarter => {
            need(p.n3, "n3")?;
            p.n1.checked_mul(p.n2).and_then(|v| v.checked_mul(p.n3))
        }
        TaylorKind::Tetra => {
            p.n1.checked_mul(p.n1)
                .and_then(|v| v.checked_mul(18))
                .and_then(|v| v.checked_mul(p.n2))
        }
    };
    match ncells {
        Some(n) if n <= MAX_CELLS => {}
        _ => {
            return Err(format!(
                "{:?} mesh with n1={}, n2={}, n3={} would have more than {MAX_CELLS} cells",
                p.kind, p.n1, p.n2, p.n3
            ))
        }
    }
    let mesh = match p.kind {
        TaylorKind::Axis => axis(p.n1, p.n2),
        TaylorKind::Quarter => quarter(p.n1, p.n2, p.n3),
        TaylorKind::Tetra => return Ok(tetra(p.n1, p.n2)),
    };
    if p.linear {
        ops::quad_line(&mesh, None).map_err(String::from)
    } else {
        Ok(mesh)
    }
}

/// `value * i / n` with the end points exact, so that the planes the
/// command files select (z = 2.27, x = 3.2...) hold their nodes exactly.
fn frac(value: f64, i: usize, n: usize) -> f64 {
    if i == n {
        value
    } else {
        value * (i as f64 / n as f64)
    }
}

/// (cos, sin) of `k/n` of a quarter turn, exact at 0 and 90 degrees.
fn quarter_turn(k: usize, n: usize) -> (f64, f64) {
    if k == 0 {
        (1.0, 0.0)
    } else if k == n {
        (0.0, 1.0)
    } else {
        let a = std::f64::consts::FRAC_PI_2 * (k as f64 / n as f64);
        (a.cos(), a.sin())
    }
}

/// Mid-node position, in half-step grid coordinates, of two corners.
fn mid(a: (usize, usize), b: (usize, usize)) -> (usize, usize) {
    ((a.0 + b.0) / 2, (a.1 + b.1) / 2)
}

/// A QUAD8 from its 4 corners in half-step coordinates: corners, then the
/// mid-nodes of edges 1-2, 2-3, 3-4, 4-1.
fn quad8_local(q: [(usize, usize); 4]) -> [(usize, usize); 8] {
    [
        q[0],
        q[1],
        q[2],
        q[3],
        mid(q[0], q[1]),
        mid(q[1], q[2]),
        mid(q[2], q[3]),
        mid(q[3], q[0]),
    ]
}

fn group(range: std::ops::Range<usize>) -> Vec<usize> {
    range.collect()
}

fn axis(n1: usize, n2: usize) -> Mesh {
    let (ni, nj) = (2 * n1 + 1, 2 * n2 + 1);
    let mut id = vec![usize::MAX; ni * nj];
    let mut coords = Vec::new();
    for jj in 0..nj {
        for ii in 0..ni {
            if ii % 2 == 1 && jj % 2 == 1 {
                continue;
            }
            id[jj * ni + ii] = coords.len();
            coords.push([
                frac(RADIUS, ii, 2 * n1),
                GAP + frac(LENGTH, jj, 2 * n2),
                0.0,
            ]);
        }
    }
    let node = |(ii, jj): (usize, usize)| id[jj * ni + ii];
    let mut cells = Vec::new();
    for j in 0..n2 {
        for i in 0..n1 {
            let (a, b) = (2 * i, 2 * j);
            let q = quad8_local([(a, b), (a + 2, b), (a + 2, b + 2), (a, b + 2)]);
            cells.push(Cell {
                kind: CellType::Quad8,
                nodes: q.iter().map(|&p| node(p)).collect(),
            });
        }
    }
    let nvol = cells.len();
    // Foundation [0, 20] x [-1, 0]: its own nodes, nothing shared with the bar.
    let f0 = coords.len();
    coords.extend([
        [0.0, -1.0, 0.0],
        [20.0, -1.0, 0.0],
        [20.0, 0.0, 0.0],
        [0.0, 0.0, 0.0],
        [10.0, -1.0, 0.0],
        [20.0, -0.5, 0.0],
        [10.0, 0.0, 0.0],
        [0.0, -0.5, 0.0],
    ]);
    cells.push(Cell {
        kind: CellType::Quad8,
        nodes: (f0..f0 + 8).collect(),
    });
    let seg3 = |a: (usize, usize), b: (usize, usize)| Cell {
        kind: CellType::Seg3,
        nodes: vec![node(a), node(b), node(mid(a, b))],
    };
    let szz0 = cells.len();
    for i in 0..n1 {
        cells.push(seg3((2 * i, 0), (2 * i + 2, 0)));
    }
    let axe0 = cells.len();
    for j in 0..n2 {
        cells.push(seg3((0, 2 * j), (0, 2 * j + 2)));
    }
    let rigid0 = cells.len();
    cells.push(Cell {
        kind: CellType::Seg3,
        nodes: vec![f0 + 3, f0 + 2, f0 + 6],
    });
    let mut cell_groups = IndexMap::new();
    cell_groups.insert("VOL".to_string(), group(0..nvol));
    cell_groups.insert("VOL_RIG".to_string(), group(nvol..nvol + 1));
    cell_groups.insert("SZZ".to_string(), group(szz0..axe0));
    cell_groups.insert("AXE".to_string(), group(axe0..rigid0));
    cell_groups.insert("RIGID".to_string(), group(rigid0..rigid0 + 1));
    let mut node_groups = IndexMap::new();
    node_groups.insert("A1".to_string(), vec![node((0, 0))]);
    node_groups.insert("B1".to_string(), vec![node((2 * n1, 0))]);
    node_groups.insert("A2".to_string(), vec![node((0, 2 * n2))]);
    node_groups.insert("B2".to_string(), vec![node((2 * n1, 2 * n2))]);
    Mesh {
        name: "TAYLOR_AXIS".to_string(),
        dim: 2,
        coords,
        cells,
        cell_groups,
        node_groups,
    }
}

fn quarter(n1: usize, n2: usize, n3: usize) -> Mesh {
    let (ni, nj, nk) = (2 * n1 + 1, 2 * n2 + 1, 2 * n3 + 1);
    let idx = |ii: usize, jj: usize, kk: usize| (jj * ni + ii) * nk + kk;
    let mut id = vec![usize::MAX; ni * nj * nk];
    let mut coords = Vec::new();
    for jj in 0..nj {
        let z = GAP + frac(LENGTH, jj, 2 * n2);
        for ii in 0..ni {
            let r = frac(RADIUS, ii, 2 * n1);
            for kk in 0..nk {
                // One node per height on the axis; elsewhere serendipity:
                // corners and edge mid-nodes have at most one odd index.
                let odd = ii % 2 + jj % 2 + kk % 2;
                if (ii == 0 && kk > 0) || odd > 1 {
                    continue;
                }
                let (c, s) = quarter_turn(kk, 2 * n3);
                id[idx(ii, jj, kk)] = coords.len();
                coords.push([r * c, r * s, z]);
            }
        }
    }
    let node = |ii: usize, jj: usize, kk: usize| {
        if ii == 0 {
            id[idx(0, jj, 0)]
        } else {
            id[idx(ii, jj, kk)]
        }
    };
    let mut cells = Vec::new();
    // Bottom face corners in (radial, angular) half steps, in MED's order
    // for the volume cell: clockwise seen from above (from the top face).
    let q = [(0, 0), (0, 2), (2, 2), (2, 0)];
    for j in 0..n2 {
        for i in 0..n1 {
            for k in 0..n3 {
                let c =
                    |(di, dk): (usize, usize), dj: usize| node(2 * i + di, 2 * j + dj, 2 * k + dk);
                let mut h = Vec::with_capacity(20);
                h.extend(q.iter().map(|&p| c(p, 0)));
                h.extend(q.iter().map(|&p| c(p, 2)));
                for dj in [0, 2] {
                    h.extend((0..4).map(|m| c(mid(q[m], q[(m + 1) % 4]), dj)));
                }
                h.extend(q.iter().map(|&p| c(p, 1)));
                if i == 0 {
                    // Corners 1 and 2 of the hexahedron are both on the axis:
                    // keep the wedge's nodes, in PENTA15 order.
                    const WEDGE: [usize; 15] =
                        [0, 2, 3, 4, 6, 7, 9, 10, 11, 13, 14, 15, 16, 18, 19];
                    cells.push(Cell {
                        kind: CellType::Penta15,
                        nodes: WEDGE.iter().map(|&m| h[m]).collect(),
                    });
                } else {
                    cells.push(Cell {
                        kind: CellType::Hexa20,
                        nodes: h,
                    });
                }
            }
        }
    }
    let nvol = cells.len();
    let f0 = coords.len();
    coords.extend([
        [0.0, 0.0, -2.0],
        [0.0, 20.0, -2.0],
        [20.0, 20.0, -2.0],
        [20.0, 0.0, -2.0],
        [0.0, 0.0, 0.0],
        [0.0, 20.0, 0.0],
        [20.0, 20.0, 0.0],
        [20.0, 0.0, 0.0],
    ]);
    cells.push(Cell {
        kind: CellType::Hexa8,
        nodes: (f0..f0 + 8).collect(),
    });
    // SZZ: counter-clockwise seen from above (normal +z, into the bar).
    let szz0 = cells.len();
    for i in 0..n1 {
        for k in 0..n3 {
            let (a, b) = (2 * i, 2 * k);
            let l = quad8_local([(a, b), (a + 2, b), (a + 2, b + 2), (a, b + 2)]);
            let all: Vec<usize> = l.iter().map(|&(ii, kk)| node(ii, 0, kk)).collect();
            cells.push(if i == 0 {
                // Corners 1 and 4 are the axis node: a TRIA6.
                Cell {
                    kind: CellType::Tria6,
                    nodes: vec![all[0], all[1], all[2], all[4], all[5], all[6]],
                }
            } else {
                Cell {
                    kind: CellType::Quad8,
                    nodes: all,
                }
            });
        }
    }
    // Symmetry faces in (radial, axial) half steps.
    let side = |cells: &mut Vec<Cell>, kk: usize| {
        for j in 0..n2 {
            for i in 0..n1 {
                let (a, b) = (2 * i, 2 * j);
                let l = quad8_local([(a, b), (a + 2, b), (a + 2, b + 2), (a, b + 2)]);
                cells.push(Cell {
                    kind: CellType::Quad8,
                    nodes: l.iter().map(|&(ii, jj)| node(ii, jj, kk)).collect(),
                });
            }
        }
    };
    let sxx0 = cells.len();
    side(&mut cells, 2 * n3);
    let syy0 = cells.len();
    side(&mut cells, 0);
    let rigid0 = cells.len();
    cells.push(Cell {
        kind: CellType::Quad4,
        nodes: vec![f0 + 4, f0 + 7, f0 + 6, f0 + 5],
    });
    let mut cell_groups = IndexMap::new();
    cell_groups.insert("VOL".to_string(), group(0..nvol));
    cell_groups.insert("VOL_RIG".to_string(), group(nvol..nvol + 1));
    cell_groups.insert("SZZ".to_string(), group(szz0..sxx0));
    cell_groups.insert("SXX".to_string(), group(sxx0..syy0));
    cell_groups.insert("SYY".to_string(), group(syy0..rigid0));
    cell_groups.insert("RIGID".to_string(), group(rigid0..rigid0 + 1));
    let mut node_groups = IndexMap::new();
    node_groups.insert("A1".to_string(), vec![node(0, 0, 0)]);
    node_groups.insert("B1".to_string(), vec![node(2 * n1, 0, 0)]);
    node_groups.insert("A2".to_string(), vec![node(0, 2 * n2, 0)]);
    node_groups.insert("B2".to_string(), vec![node(2 * n1, 2 * n2, 0)]);
    Mesh {
        name: "TAYLOR_QUARTER".to_string(),
        dim: 3,
        coords,
        cells,
        cell_groups,
        node_groups,
    }
}

/// Triangles of the disc of radius 1 made of `nr` rings (ring j: 6j nodes
/// on the circle of radius j/nr), as local node triples counter-clockwise.
/// Local numbering: centre 0, then ring j from angle 0 counter-clockwise.
fn disc(nr: usize) -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
    let base = |j: usize| if j == 0 { 0 } else { 1 + 3 * j * (j - 1) };
    let mut pts = vec![[0.0, 0.0]];
    for j in 1..=nr {
        let r = frac(1.0, j, nr);
        for t in 0..6 * j {
            let a = std::f64::consts::TAU * (t as f64 / (6 * j) as f64);
            let (c, s) = if t == 0 {
                (1.0, 0.0)
            } else {
                (a.cos(), a.sin())
            };
            pts.push([r * c, r * s]);
        }
    }
    let ring = |j: usize, u: usize| {
        if j == 0 {
            0
        } else {
            base(j) + u % (6 * j)
        }
    };
    let mut tris = Vec::new();
    for j in 1..=nr {
        for s in 0..6 {
            // Zip the inner ring's j nodes of this sixth with the outer
            // ring's j + 1 nodes: 2j - 1 triangles.
            let inner = |u: usize| ring(j - 1, (j - 1) * s + u);
            let outer = |u: usize| ring(j, j * s + u);
            for u in 0..j - 1 {
                tris.push([inner(u), outer(u), outer(u + 1)]);
                tris.push([inner(u), outer(u + 1), inner(u + 1)]);
            }
            tris.push([inner(j - 1), outer(j - 1), outer(j)]);
        }
    }
    for t in &mut tris {
        let (a, b, c) = (pts[t[0]], pts[t[1]], pts[t[2]]);
        let area2 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if area2 < 0.0 {
            t.swap(1, 2);
        }
    }
    (pts, tris)
}

fn tetra(nr: usize, nz: usize) -> Mesh {
    let (pts, tris) = disc(nr);
    let np = pts.len();
    let mut coords = Vec::with_capacity(np * (nz + 1) + 8);
    for l in 0..=nz {
        let z = GAP + frac(LENGTH, l, nz);
        for p in &pts {
            coords.push([RADIUS * p[0], RADIUS * p[1], z]);
        }
    }
    let mut cells = Vec::new();
    for l in 0..nz {
        for t in &tris {
            // Each prism is cut into 3 tetrahedra with every quadrilateral
            // side split along the diagonal through its lowest-numbered
            // node: both prisms sharing a side then cut it the same way, so
            // the mesh is conforming without any bookkeeping.
            let mut b = t.map(|v| l * np + v);
            b.sort_unstable();
            let [a0, b0, c0] = b;
            let [a1, b1, c1] = b.map(|v| v + np);
            for tet in [[a0, a1, b1, c1], [a0, b0, c0, c1], [a0, b0, c1, b1]] {
                cells.push(Cell {
                    kind: CellType::Tetra4,
                    nodes: med_oriented_tetra(&coords, tet),
                });
            }
        }
    }
    let nvol = cells.len();
    let f0 = coords.len();
    coords.extend([
        [-20.0, -20.0, -2.0],
        [-20.0, 20.0, -2.0],
        [20.0, 20.0, -2.0],
        [20.0, -20.0, -2.0],
        [-20.0, -20.0, 0.0],
        [-20.0, 20.0, 0.0],
        [20.0, 20.0, 0.0],
        [20.0, -20.0, 0.0],
    ]);
    cells.push(Cell {
        kind: CellType::Hexa8,
        nodes: (f0..f0 + 8).collect(),
    });
    let szz0 = cells.len();
    for t in &tris {
        cells.push(Cell {
            kind: CellType::Tria3,
            nodes: t.to_vec(),
        });
    }
    let rigid0 = cells.len();
    cells.push(Cell {
        kind: CellType::Quad4,
        nodes: vec![f0 + 4, f0 + 7, f0 + 6, f0 + 5],
    });
    let mut cell_groups = IndexMap::new();
    cell_groups.insert("VOL".to_string(), group(0..nvol));
    cell_groups.insert("VOL_RIG".to_string(), group(nvol..nvol + 1));
    cell_groups.insert("SZZ".to_string(), group(szz0..rigid0));
    cell_groups.insert("RIGID".to_string(), group(rigid0..rigid0 + 1));
    let outer = 1 + 3 * nr * (nr - 1);
    let mut node_groups = IndexMap::new();
    // code_aster's sdnv103e/k check B1 in free flight at 2.5e-7 (DZ =
    // -227000 x 1.025e-5 = -2.32675, VZ = -227000), so in this mesh B1 is
    // the *top* outer node, far from the stop; B2 is the bottom one.
    node_groups.insert("A1".to_string(), vec![0]);
    node_groups.insert("B1".to_string(), vec![nz * np + outer]);
    node_groups.insert("A2".to_string(), vec![nz * np]);
    node_groups.insert("B2".to_string(), vec![outer]);
    Mesh {
        name: "TAYLOR_TETRA".to_string(),
        dim: 3,
        coords,
        cells,
        cell_groups,
        node_groups,
    }
}

/// MED's TETRA4 has (x2-x1)x(x3-x1) pointing away from node 4 (the mirror
/// of code_aster's reference element); swap two nodes when it does not.
fn med_oriented_tetra(coords: &[[f64; 3]], t: [usize; 4]) -> Vec<usize> {
    let x = |k: usize| coords[t[k]];
    let (u, v, w) = (sub(x(1), x(0)), sub(x(2), x(0)), sub(x(3), x(0)));
    let s = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]);
    if s > 0.0 {
        vec![t[0], t[2], t[1], t[3]]
    } else {
        t.to_vec()
    }
}

/// Shape measures of the tetrahedra of a mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TetraQuality {
    pub count: usize,
    /// Smallest and largest dihedral angles, degrees (regular: 70.53).
    pub min_dihedral_deg: f64,
    pub max_dihedral_deg: f64,
    /// Smallest and largest volumes.
    pub min_volume: f64,
    pub max_volume: f64,
}

/// Dihedral angles and volumes over the TETRA4 cells; None if there are none.
pub fn tetra_quality(mesh: &Mesh) -> Option<TetraQuality> {
    let mut q = TetraQuality {
        count: 0,
        min_dihedral_deg: f64::INFINITY,
        max_dihedral_deg: 0.0,
        min_volume: f64::INFINITY,
        max_volume: 0.0,
    };
    for cell in mesh.cells.iter().filter(|c| c.kind == CellType::Tetra4) {
        q.count += 1;
        let x: Vec<[f64; 3]> = cell.nodes.iter().map(|&n| mesh.coords[n]).collect();
        let vol = ops::cell_measure(mesh, cell);
        q.min_volume = q.min_volume.min(vol);
        q.max_volume = q.max_volume.max(vol);
        for (i, j, k, l) in [
            (0, 1, 2, 3),
            (0, 2, 1, 3),
            (0, 3, 1, 2),
            (1, 2, 0, 3),
            (1, 3, 0, 2),
            (2, 3, 0, 1),
        ] {
            // Angle between the two faces through edge ij: the angle of
            // the other two vertices projected on the plane normal to ij.
            let e = sub(x[j], x[i]);
            let e2 = dot(e, e);
            let proj = |p: [f64; 3]| {
                let v = sub(p, x[i]);
                let t = dot(v, e) / e2;
                [v[0] - t * e[0], v[1] - t * e[1], v[2] - t * e[2]]
            };
            let (u, v) = (proj(x[k]), proj(x[l]));
            let c = dot(u, v) / (dot(u, u) * dot(v, v)).sqrt();
            let a = c.clamp(-1.0, 1.0).acos().to_degrees();
            q.min_dihedral_deg = q.min_dihedral_deg.min(a);
            q.max_dihedral_deg = q.max_dihedral_deg.max(a);
        }
    }
    (q.count > 0).then_some(q)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;
    use std::f64::consts::PI;

    fn gen(letter: char) -> Mesh {
        generate(&TaylorParams::for_modelling(letter).unwrap()).unwrap()
    }

    fn count(m: &Mesh, t: CellType) -> usize {
        m.cells.iter().filter(|c| c.kind == t).count()
    }

    fn group_types(m: &Mesh, g: &str) -> Vec<(CellType, usize)> {
        let mut v: Vec<(CellType, usize)> = Vec::new();
        for &c in &m.cell_groups[g] {
            let k = m.cells[c].kind;
            match v.iter_mut().find(|(t, _)| *t == k) {
                Some(e) => e.1 += 1,
                None => v.push((k, 1)),
            }
        }
        v.sort();
        v
    }

    // Reference counts: the first two lines of each test are the figures
    // of docs/sdnv103.md §3; the others are closed forms of the
    // construction (serendipity grid, one node per height on the axis).

    #[test]
    fn axis_counts_match_the_reference_meshes() {
        let b = gen('B');
        assert_eq!(b.nnodes(), 359);
        assert_eq!(count(&b, CellType::Quad8), 101);
        assert_eq!(count(&b, CellType::Seg3), 5 + 20 + 1);
        let d = gen('D');
        assert_eq!(d.nnodes(), 29);
        assert_eq!(count(&d, CellType::Quad8), 5);
        assert_eq!(gen('F'), d);
        for (m, n1, n2) in [(&b, 5, 20), (&d, 2, 2)] {
            assert_eq!(m.dim, 2);
            assert_eq!(m.cell_groups["VOL"].len(), n1 * n2);
            assert_eq!(group_types(m, "VOL_RIG"), vec![(CellType::Quad8, 1)]);
            assert_eq!(group_types(m, "SZZ"), vec![(CellType::Seg3, n1)]);
            assert_eq!(group_types(m, "AXE"), vec![(CellType::Seg3, n2)]);
            assert_eq!(group_types(m, "RIGID"), vec![(CellType::Seg3, 1)]);
            let names: Vec<&str> = m.cell_groups.keys().map(|s| s.as_str()).collect();
            assert_eq!(names, ["VOL", "VOL_RIG", "SZZ", "AXE", "RIGID"]);
        }
    }

    #[test]
    fn quarter_counts_match_the_reference_meshes() {
        let a = gen('A');
        assert_eq!(a.nnodes(), 2849);
        assert_eq!(count(&a, CellType::Hexa20), 480);
        assert_eq!(count(&a, CellType::Penta15), 120);
        let h = gen('H');
        assert_eq!(h.nnodes(), 73);
        assert_eq!(count(&h, CellType::Hexa20), 4);
        assert_eq!(count(&h, CellType::Penta15), 4);
        assert_eq!(gen('G'), a);
        assert_eq!(gen('I'), h);
        for (m, n1, n2, n3) in [(&a, 5, 20, 6), (&h, 2, 2, 2)] {
            assert_eq!(m.dim, 3);
            assert_eq!(
                group_types(m, "SZZ"),
                vec![(CellType::Tria6, n3), (CellType::Quad8, (n1 - 1) * n3)]
            );
            assert_eq!(group_types(m, "SXX"), vec![(CellType::Quad8, n1 * n2)]);
            assert_eq!(group_types(m, "SYY"), vec![(CellType::Quad8, n1 * n2)]);
            assert_eq!(group_types(m, "RIGID"), vec![(CellType::Quad4, 1)]);
            assert_eq!(group_types(m, "VOL_RIG"), vec![(CellType::Hexa8, 1)]);
            assert_eq!(
                group_types(m, "VOL"),
                vec![
                    (CellType::Penta15, n2 * n3),
                    (CellType::Hexa20, (n1 - 1) * n2 * n3)
                ]
            );
        }
    }

    #[test]
    fn linear_quarter_is_the_vertex_mesh() {
        let j = gen('J');
        // Vertices: n1 (n2+1)(n3+1) off the axis, n2+1 on it, 8 below.
        assert_eq!(j.nnodes(), 5 * 21 * 7 + 21 + 8);
        assert_eq!(count(&j, CellType::Hexa8), 480 + 1);
        assert_eq!(count(&j, CellType::Penta6), 120);
        assert_eq!(count(&j, CellType::Quad4), 24 + 100 + 100 + 1);
        assert_eq!(count(&j, CellType::Tria3), 6);
        assert!(j.cells.iter().all(|c| !c.kind.is_quadratic()));
        let lin_axis = generate(&TaylorParams {
            linear: true,
            ..TaylorParams::for_modelling('B').unwrap()
        })
        .unwrap();
        assert_eq!(lin_axis.nnodes(), 6 * 21 + 4);
        assert_eq!(count(&lin_axis, CellType::Quad4), 101);
        assert_eq!(count(&lin_axis, CellType::Seg2), 26);
    }

    #[test]
    fn tetra_mesh_size_and_groups() {
        let e = gen('E');
        // 3 rings: 37 nodes and 54 triangles per section, 35 sections.
        assert_eq!(e.nnodes(), 37 * 35 + 8);
        assert_eq!(count(&e, CellType::Tetra4), 54 * 3 * 34);
        assert_eq!(group_types(&e, "SZZ"), vec![(CellType::Tria3, 54)]);
        assert_eq!(group_types(&e, "RIGID"), vec![(CellType::Quad4, 1)]);
        assert_eq!(group_types(&e, "VOL_RIG"), vec![(CellType::Hexa8, 1)]);
        assert_eq!(gen('K'), e);
        // "About 1300 nodes and 5500 tetrahedra" (sdnv103.md §3).
        assert!((1250..1350).contains(&e.nnodes()));
        assert!((5300..5700).contains(&count(&e, CellType::Tetra4)));
    }

    #[test]
    fn points_are_single_nodes_at_their_coordinates() {
        let top = GAP + LENGTH;
        for l in ['A', 'B', 'D', 'E', 'H', 'J'] {
            let m = gen(l);
            let want: [(&str, [f64; 3]); 4] = [
                ("A1", [0.0, GAP, 0.0]),
                ("B1", [RADIUS, GAP, 0.0]),
                ("A2", [0.0, top, 0.0]),
                ("B2", [RADIUS, top, 0.0]),
            ];
            for (g, mut x) in want {
                // The tetra mesh swaps B1 and B2 (see `tetra`).
                if l == 'E' && g.starts_with('B') {
                    x[1] = if g == "B1" { top } else { GAP };
                }
                if m.dim == 3 {
                    x = [x[0], 0.0, x[1]];
                }
                let nodes = &m.node_groups[g];
                assert_eq!(nodes.len(), 1, "{l} {g}");
                let p = m.coords[nodes[0]];
                for k in 0..3 {
                    assert!((p[k] - x[k]).abs() < 1e-12, "{l} {g} {p:?} vs {x:?}");
                }
            }
        }
    }

    #[test]
    fn no_duplicate_nodes() {
        for l in ['A', 'B', 'D', 'E', 'H', 'J'] {
            let m = gen(l);
            let mut order: Vec<usize> = (0..m.nnodes()).collect();
            order.sort_by(|&a, &b| m.coords[a][0].total_cmp(&m.coords[b][0]));
            // Sweep in x: only pairs closer than the tolerance in x can be
            // closer in space.
            let mut min_d = f64::INFINITY;
            for (i, &a) in order.iter().enumerate() {
                for &b in &order[i + 1..] {
                    if m.coords[b][0] - m.coords[a][0] > 1e-6 {
                        break;
                    }
                    let d: f64 = (0..3)
                        .map(|k| (m.coords[a][k] - m.coords[b][k]).powi(2))
                        .sum::<f64>()
                        .sqrt();
                    min_d = min_d.min(d);
                }
            }
            assert!(min_d > 1e-9, "{l}: two nodes {min_d} apart");
            // Every node is used by a cell.
            let all: Vec<usize> = (0..m.ncells()).collect();
            assert_eq!(m.nodes_of_cells(&all).len(), m.nnodes(), "{l}");
        }
    }

    #[test]
    fn every_cell_has_a_positive_jacobian() {
        for l in ['A', 'B', 'D', 'E', 'H', 'J'] {
            let m = gen(l);
            let mut checked = 0;
            for c in &m.cells {
                if let Some(d) = ops::jacobian_dets(&m, c) {
                    checked += 1;
                    let min = d.iter().copied().fold(f64::INFINITY, f64::min);
                    assert!(min > 0.0, "{l}: {:?} {:?} det {min}", c.kind, c.nodes);
                }
            }
            let vols = m.cell_groups["VOL"].len() + m.cell_groups["VOL_RIG"].len();
            assert_eq!(
                checked, vols,
                "{l}: every volume (2D: surface) cell checked"
            );
        }
    }

    /// Relative 1e-9: the quadrature is exact for these cells, what is
    /// left is rounding and the 1e-10 of the finite-difference derivatives.
    fn assert_close(a: f64, b: f64) {
        assert!((a - b).abs() <= 1e-9 * b.abs(), "{a} vs {b}");
    }

    fn group_measure(m: &Mesh, g: &str) -> f64 {
        m.cell_groups[g]
            .iter()
            .map(|&c| ops::cell_measure(m, &m.cells[c]))
            .sum()
    }

    #[test]
    fn axis_area_and_swept_volume_are_exact() {
        for l in ['B', 'D'] {
            let m = gen(l);
            let area = group_measure(&m, "VOL");
            assert!((area - RADIUS * LENGTH).abs() < 1e-9 * area, "{l} {area}");
            let swept: f64 = m.cell_groups["VOL"]
                .iter()
                .map(|&c| 2.0 * PI * ops::cell_first_moment_x(&m, &m.cells[c]).unwrap())
                .sum();
            let exact = PI * RADIUS * RADIUS * LENGTH;
            assert!((swept - exact).abs() < 1e-9 * exact, "{l} {swept} {exact}");
            assert_close(group_measure(&m, "VOL_RIG"), 20.0);
            assert_close(group_measure(&m, "SZZ"), RADIUS);
            assert_close(group_measure(&m, "AXE"), LENGTH);
        }
    }

    /// Area of the quarter disc of radius 1 as the quarter mesh sees it:
    /// per sector of angle d, the triangle (0, P0, P1) plus the parabolic
    /// segment through the three arc nodes, 4/3 of the triangle
    /// (P0, Pmid, P1) by Archimedes.
    fn quadratic_quarter_disc(n3: usize) -> f64 {
        let d = PI / 2.0 / n3 as f64;
        let h = d / 2.0;
        n3 as f64 * (0.5 * d.sin() + 4.0 / 3.0 * h.sin() * (1.0 - h.cos()))
    }

    #[test]
    fn quarter_volume_is_the_exact_volume_of_its_geometry() {
        for (l, n3) in [('A', 6), ('H', 2)] {
            let m = gen(l);
            let v = group_measure(&m, "VOL");
            // The map is r(xi) c(eta) z(zeta), r and z linear and c the
            // quadratic arc, so det J is a polynomial the 3x3x3 Gauss rule
            // integrates exactly: only rounding is left.
            let discrete = RADIUS * RADIUS * LENGTH * quadratic_quarter_disc(n3);
            assert!((v - discrete).abs() < 1e-9 * v, "{l}: {v} vs {discrete}");
            // And against the true quarter cylinder: the parabolic arc
            // deviates from the circle by O(d^4): relative volume error
            // 1.0e-5 for n3 = 6 and 7.8e-4 for n3 = 2.
            let exact = PI * RADIUS * RADIUS * LENGTH / 4.0;
            let bound = if n3 == 6 { 1.5e-5 } else { 1e-3 };
            assert!((v - exact).abs() < bound * exact, "{l}: {v} vs {exact}");
            assert_close(group_measure(&m, "VOL_RIG"), 800.0);
            assert_close(group_measure(&m, "RIGID"), 400.0);
            let szz = group_measure(&m, "SZZ");
            let face = RADIUS * RADIUS * quadratic_quarter_disc(n3);
            assert!((szz - face).abs() < 1e-9 * face, "{l} SZZ {szz} vs {face}");
            for g in ["SXX", "SYY"] {
                assert_close(group_measure(&m, g), RADIUS * LENGTH);
            }
        }
    }

    #[test]
    fn tetra_volume_is_the_inscribed_prism() {
        let m = gen('E');
        let v = group_measure(&m, "VOL");
        // 18 boundary nodes on the circle: a regular 18-gon times L.
        let polygon = 0.5 * 18.0 * RADIUS * RADIUS * (2.0 * PI / 18.0).sin();
        assert!((v - polygon * LENGTH).abs() < 1e-9 * v, "{v}");
        // The 18-gon misses 2% of the disc: (1 - sin(20deg)/(20deg)).
        let cyl = PI * RADIUS * RADIUS * LENGTH;
        assert!(((cyl - v) / cyl - 0.0202).abs() < 1e-3);
        assert_close(group_measure(&m, "VOL_RIG"), 3200.0);
        assert_close(group_measure(&m, "SZZ"), polygon);
    }

    #[test]
    fn tetra_quality_has_no_slivers() {
        let q = tetra_quality(&gen('E')).unwrap();
        assert_eq!(q.count, 5508);
        // Measured: 34.7 and 119.9 degrees, volumes 0.156 to 0.205.
        assert!(q.min_dihedral_deg > 30.0, "{q:?}");
        assert!(q.max_dihedral_deg < 125.0, "{q:?}");
        assert!(
            q.min_volume > 0.0 && q.max_volume / q.min_volume < 1.5,
            "{q:?}"
        );
    }

    /// Faces of the volume cells as sorted vertex sets, with how many
    /// cells hold each.
    fn face_counts(m: &Mesh, cells: &[usize]) -> HashMap<Vec<usize>, usize> {
        let mut faces = HashMap::new();
        for &c in cells {
            let cell = &m.cells[c];
            let local: &[&[usize]] = match cell.kind {
                CellType::Tetra4 => &[&[0, 1, 2], &[0, 1, 3], &[0, 2, 3], &[1, 2, 3]],
                CellType::Penta6 | CellType::Penta15 => &[
                    &[0, 1, 2],
                    &[3, 4, 5],
                    &[0, 1, 4, 3],
                    &[1, 2, 5, 4],
                    &[2, 0, 3, 5],
                ],
                _ => &[
                    &[0, 1, 2, 3],
                    &[4, 5, 6, 7],
                    &[0, 1, 5, 4],
                    &[1, 2, 6, 5],
                    &[2, 3, 7, 6],
                    &[3, 0, 4, 7],
                ],
            };
            for f in local {
                let mut key: Vec<usize> = f.iter().map(|&k| cell.nodes[k]).collect();
                key.sort_unstable();
                *faces.entry(key).or_insert(0) += 1;
            }
        }
        faces
    }

    #[test]
    fn volume_meshes_are_conforming_and_skins_are_faces() {
        // (mesh, skin groups, boundary faces of VOL)
        let cases = [
            ('A', vec!["SZZ", "SXX", "SYY"], 2 * 30 + 2 * 100 + 20 * 6),
            ('H', vec!["SZZ", "SXX", "SYY"], 2 * 4 + 2 * 4 + 2 * 2),
            ('J', vec!["SZZ", "SXX", "SYY"], 2 * 30 + 2 * 100 + 20 * 6),
            ('E', vec!["SZZ"], 2 * 54 + 18 * 2 * 34),
        ];
        for (l, skins, nboundary) in cases {
            let m = gen(l);
            let faces = face_counts(&m, &m.cell_groups["VOL"]);
            assert!(faces.values().all(|&n| n <= 2), "{l}: a face in 3 cells");
            let boundary = faces.values().filter(|&&n| n == 1).count();
            assert_eq!(boundary, nboundary, "{l}");
            for g in skins {
                for &c in &m.cell_groups[g] {
                    let cell = &m.cells[c];
                    let mut key = cell.nodes[..cell.kind.nvertices()].to_vec();
                    key.sort_unstable();
                    assert_eq!(faces.get(&key), Some(&1), "{l} {g}: not a boundary face");
                }
            }
        }
    }

    #[test]
    fn skin_groups_lie_on_their_planes() {
        // (mesh, group, coordinate index, value)
        let z = |l: char| if l == 'B' || l == 'D' { 1 } else { 2 };
        for l in ['A', 'B', 'D', 'E', 'H', 'J'] {
            let m = gen(l);
            let mut planes = vec![("SZZ", z(l), GAP), ("RIGID", z(l), 0.0)];
            if m.cell_groups.contains_key("AXE") {
                planes.push(("AXE", 0, 0.0));
            }
            if m.cell_groups.contains_key("SXX") {
                planes.push(("SXX", 0, 0.0));
                planes.push(("SYY", 1, 0.0));
            }
            for (g, k, v) in planes {
                for n in m.nodes_of_cells(&m.cell_groups[g]) {
                    assert!((m.coords[n][k] - v).abs() < 1e-12, "{l} {g} node {n}");
                }
            }
            // The bar stays in its box, the foundation below 0.
            for n in m.nodes_of_cells(&m.cell_groups["VOL"]) {
                let p = m.coords[n];
                let h = p[z(l)];
                assert!((GAP - 1e-12..=GAP + LENGTH + 1e-12).contains(&h));
                let r = if m.dim == 2 { p[0] } else { p[0].hypot(p[1]) };
                assert!(r <= RADIUS + 1e-12, "{l} node {n} r={r}");
            }
            for n in m.nodes_of_cells(&m.cell_groups["VOL_RIG"]) {
                assert!(m.coords[n][z(l)] <= 0.0);
            }
        }
    }

    /// MED order (docs/sdnv103 brief): each mid-node sits on the edge
    /// between the two vertices listed for it, i.e. equidistant from them
    /// (straight edges and circular arcs alike) and closer than they are to
    /// each other.
    #[test]
    fn mid_nodes_follow_med_edge_order() {
        let edges = |k: CellType| k.mid_edges();
        for l in ['A', 'B', 'H'] {
            let m = gen(l);
            let dist = |a: usize, b: usize| -> f64 {
                (0..3)
                    .map(|k| (m.coords[a][k] - m.coords[b][k]).powi(2))
                    .sum::<f64>()
                    .sqrt()
            };
            for c in &m.cells {
                let nv = c.kind.nvertices();
                for (e, &(i, j)) in edges(c.kind).iter().enumerate() {
                    let (a, b, mn) = (c.nodes[i], c.nodes[j], c.nodes[nv + e]);
                    let (da, db) = (dist(mn, a), dist(mn, b));
                    assert!((da - db).abs() < 1e-9, "{l} {:?} edge {e}", c.kind);
                    assert!(da < dist(a, b), "{l} {:?} edge {e}", c.kind);
                }
            }
        }
    }

    #[test]
    fn bad_parameters_are_errors() {
        let base = TaylorParams::for_modelling('A').unwrap();
        for p in [
            TaylorParams { n1: 0, ..base },
            TaylorParams { n2: 0, ..base },
            TaylorParams { n3: 0, ..base },
            TaylorParams {
                n1: 1_000_000,
                n2: 1_000_000,
                ..base
            },
            TaylorParams {
                kind: TaylorKind::Tetra,
                n1: 0,
                ..base
            },
            TaylorParams {
                kind: TaylorKind::Axis,
                n2: usize::MAX,
                ..base
            },
        ] {
            assert!(generate(&p).is_err(), "{p:?}");
        }
        // n3 is not used by the 2D mesh: 0 is fine there.
        let axis = TaylorParams {
            kind: TaylorKind::Axis,
            n3: 0,
            ..base
        };
        assert!(generate(&axis).is_ok());
        assert_eq!(TaylorParams::for_modelling('C'), None);
    }
}
