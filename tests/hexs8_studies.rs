//! Studies of 3D_SI (MECA_HEXS8 on HEXA8, MECA_HEXS20 on HEXA20) and 3D
//! beside it, written the way a user would, each against an independent
//! reference (one-dimensional wave theory, the uniaxial plastic answer,
//! beam theory, rigid-body mechanics with Coulomb friction), plus mixed
//! meshes (the AFFE override rule of semantics.md §3.2) and bad input.
//! The command files are in tests/studies/hexs8_*.comm; their meshes are
//! built here and committed (regenerate with
//! `UPDATE_MESHES=1 cargo test --test hexs8_studies meshes`).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use aster::mesh::ops::jacobian_dets;
use aster::mesh::{Cell, CellType, Mesh};
mod common;
use common::printed_table;

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/studies")
}

/// Runs the study, asserts every check OK, returns its .resu.
fn run_study(name: &str) -> String {
    let run = common::run_study(
        &format!("tests/studies/{name}.comm"),
        &format!("hexs8_{name}"),
    );
    common::assert_all_ok(&run, &format!("{name}.resu"))
}

/// How the hexahedra of a box are cut.
#[derive(Clone, Copy, PartialEq)]
enum Fill {
    Hexa,
    /// Each hexahedron cut in two prisms along the diagonal of its x-y face.
    Prisms,
}

/// A box [0, a] × [0, b] × [0, c] of n[0] × n[1] × n[2] cells, quadratic
/// (HEXA20 / PENTA15 and QUAD8 faces; QUAD_LINE gives the linear mesh).
/// `fill(i)` says how the cells of column i (along x) are cut, so that
/// hexahedra and prisms meet on quadrilateral faces (a conforming mesh).
/// Cell groups: VOL (all volume cells), HEXA / PENTA (by kind), XMIN ...
/// ZMAX (boundary faces, normals pointing out of the box: triangles on the
/// ends of the prisms).
fn box_mesh(n: [usize; 3], size: [f64; 3], fill: &dyn Fn(usize) -> Fill) -> Mesh {
    let id = |i: usize, j: usize, k: usize| (k * (n[1] + 1) + j) * (n[0] + 1) + i;
    let mut coords = Vec::new();
    for k in 0..=n[2] {
        for j in 0..=n[1] {
            for i in 0..=n[0] {
                coords.push([
                    size[0] * i as f64 / n[0] as f64,
                    size[1] * j as f64 / n[1] as f64,
                    size[2] * k as f64 / n[2] as f64,
                ]);
            }
        }
    }
    let mut mesh = Mesh {
        name: "BOITE".into(),
        dim: 3,
        coords,
        ..Mesh::default()
    };
    let mut vol = Vec::new();
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                let b = [
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                ];
                let t = b.map(|v| v + (n[0] + 1) * (n[1] + 1));
                match fill(i) {
                    // MED order whose code_aster numbering has ξ along x,
                    // η along y, ζ along z (the other orders of the same
                    // box change MECA_HEXS8's answers, see `swapped`)
                    Fill::Hexa => vol.push(oriented(
                        &mesh,
                        CellType::Hexa8,
                        vec![b[2], b[1], b[0], b[3], t[2], t[1], t[0], t[3]],
                    )),
                    Fill::Prisms => {
                        for tri in [[0, 1, 2], [0, 2, 3]] {
                            let mut nodes: Vec<usize> = tri.iter().map(|&m| b[m]).collect();
                            nodes.extend(tri.iter().map(|&m| t[m]));
                            vol.push(oriented(&mesh, CellType::Penta6, nodes));
                        }
                    }
                }
            }
        }
    }
    // boundary faces: the quadrilaterals of the grid on the six planes
    let mut faces: Vec<(&str, Vec<usize>)> = Vec::new();
    for (axis, name0, name1) in [
        (0, "XMIN", "XMAX"),
        (1, "YMIN", "YMAX"),
        (2, "ZMIN", "ZMAX"),
    ] {
        let (p, q) = ((axis + 1) % 3, (axis + 2) % 3);
        for (side, name) in [(0, name0), (n[axis], name1)] {
            for a in 0..n[p] {
                for c in 0..n[q] {
                    let node = |da: usize, dc: usize| {
                        let mut g = [0; 3];
                        g[axis] = side;
                        g[p] = a + da;
                        g[q] = c + dc;
                        id(g[0], g[1], g[2])
                    };
                    let quad = vec![node(0, 0), node(1, 0), node(1, 1), node(0, 1)];
                    // the ends of a prism column are its triangles, cut
                    // along the same diagonal (grid corners (i, j) and
                    // (i + 1, j + 1)) as the volume cells
                    let column = if axis == 2 { a } else { usize::MAX };
                    let pieces = if column != usize::MAX && fill(column) == Fill::Prisms {
                        vec![
                            vec![quad[0], quad[1], quad[2]],
                            vec![quad[0], quad[2], quad[3]],
                        ]
                    } else {
                        vec![quad]
                    };
                    for mut f in pieces {
                        // outward: (x2 - x1) × (x3 - x1) along ±axis
                        let x = |m: usize| mesh.coords[f[m]];
                        let normal = cross(sub(x(1), x(0)), sub(x(2), x(0)))[axis];
                        if (normal > 0.0) != (side > 0) {
                            f.reverse();
                        }
                        faces.push((name, f));
                    }
                }
            }
        }
    }
    // quadratic: one mid-node per edge, shared
    let mut mids: HashMap<(usize, usize), usize> = HashMap::new();
    let mut quadratic = |mesh: &mut Mesh, kind: CellType, mut nodes: Vec<usize>| {
        let q = match kind {
            CellType::Hexa8 => CellType::Hexa20,
            CellType::Penta6 => CellType::Penta15,
            CellType::Tria3 => CellType::Tria6,
            _ => CellType::Quad8,
        };
        for &(a, b) in q.mid_edges() {
            let (na, nb) = (nodes[a], nodes[b]);
            let key = (na.min(nb), na.max(nb));
            let m = *mids.entry(key).or_insert_with(|| {
                let (pa, pb) = (mesh.coords[na], mesh.coords[nb]);
                mesh.coords.push([
                    0.5 * (pa[0] + pb[0]),
                    0.5 * (pa[1] + pb[1]),
                    0.5 * (pa[2] + pb[2]),
                ]);
                mesh.coords.len() - 1
            });
            nodes.push(m);
        }
        mesh.cells.push(Cell { kind: q, nodes });
        mesh.cells.len() - 1
    };
    let mut groups: Vec<(String, Vec<usize>)> = Vec::new();
    let (mut all, mut hexa, mut penta) = (Vec::new(), Vec::new(), Vec::new());
    for c in vol {
        let kind = c.kind;
        let i = quadratic(&mut mesh, kind, c.nodes);
        all.push(i);
        if kind == CellType::Hexa8 {
            hexa.push(i)
        } else {
            penta.push(i)
        }
    }
    groups.push(("VOL".into(), all));
    if !hexa.is_empty() {
        groups.push(("HEXA".into(), hexa));
    }
    if !penta.is_empty() {
        groups.push(("PENTA".into(), penta));
    }
    for (name, f) in faces {
        let kind = if f.len() == 3 {
            CellType::Tria3
        } else {
            CellType::Quad4
        };
        let i = quadratic(&mut mesh, kind, f);
        match groups.iter_mut().find(|(g, _)| g == name) {
            Some((_, cells)) => cells.push(i),
            None => groups.push((name.into(), vec![i])),
        }
    }
    for (g, cells) in groups {
        mesh.cell_groups.insert(g, cells);
    }
    for c in &mesh.cells {
        if let Some(d) = jacobian_dets(&mesh, c) {
            assert!(d.iter().all(|&v| v > 0.0), "{:?} {d:?}", c.kind);
        }
    }
    mesh
}

/// The cell with its nodes turned so that its Jacobian is positive
/// (MED's 3D cells turn the other way from code_aster's).
fn oriented(mesh: &Mesh, kind: CellType, nodes: Vec<usize>) -> Cell {
    let cell = Cell { kind, nodes };
    if jacobian_dets(mesh, &cell).unwrap().iter().all(|&d| d > 0.0) {
        return cell;
    }
    // mirror: reverse each of the two horizontal faces
    let h = cell.nodes.len() / 2;
    let mut nodes: Vec<usize> = cell.nodes[..h].iter().rev().copied().collect();
    nodes.extend(cell.nodes[h..].iter().rev());
    let cell = Cell { kind, nodes };
    assert!(jacobian_dets(mesh, &cell).unwrap().iter().all(|&d| d > 0.0));
    cell
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Adds a node group of the nodes at `p` (exactly one must be there).
fn point(mesh: &mut Mesh, name: &str, p: [f64; 3]) {
    let nodes: Vec<usize> = (0..mesh.nnodes())
        .filter(|&i| (0..3).all(|d| (mesh.coords[i][d] - p[d]).abs() < 1e-9))
        .collect();
    assert_eq!(nodes.len(), 1, "{name}");
    mesh.node_groups.insert(name.into(), nodes);
}

/// Adds a cell group of the one volume cell whose vertex centroid is
/// nearest to `p`.
fn cell_at(mesh: &mut Mesh, name: &str, p: [f64; 3]) {
    let dist = |c: &Cell| {
        let nv = c.kind.nvertices();
        let mut g = [0.0; 3];
        for &n in &c.nodes[..nv] {
            for (gd, xd) in g.iter_mut().zip(mesh.coords[n]) {
                *gd += xd / nv as f64;
            }
        }
        (0..3).map(|d| (g[d] - p[d]).powi(2)).sum::<f64>()
    };
    let best = (0..mesh.ncells())
        .filter(|&c| mesh.cells[c].kind.dim() == 3)
        .min_by(|&a, &b| dist(&mesh.cells[a]).total_cmp(&dist(&mesh.cells[b])))
        .unwrap();
    mesh.cell_groups.insert(name.into(), vec![best]);
}

/// The same mesh with every hexahedron numbered from another corner (a
/// quarter turn about ζ): code_aster's numbering then has ξ along y and η
/// along x. The cells are the same; MECA_HEXS8 is not, because its
/// hourglass shear rules are written in global axes (note §4.7, §14.1).
fn swapped(mut mesh: Mesh) -> Mesh {
    let perm = [3, 0, 1, 2, 7, 4, 5, 6];
    let edges = CellType::Hexa20.mid_edges();
    for c in mesh.cells.iter_mut().filter(|c| c.kind == CellType::Hexa20) {
        let old = c.nodes.clone();
        let key = |a: usize, b: usize| (a.min(b), a.max(b));
        let mid: HashMap<(usize, usize), usize> = edges
            .iter()
            .enumerate()
            .map(|(e, &(a, b))| (key(old[a], old[b]), old[8 + e]))
            .collect();
        let mut nodes: Vec<usize> = perm.iter().map(|&p| old[p]).collect();
        for &(a, b) in edges {
            let m = mid[&key(nodes[a], nodes[b])];
            nodes.push(m);
        }
        c.nodes = nodes;
    }
    for c in &mesh.cells {
        if let Some(d) = jacobian_dets(&mesh, c) {
            assert!(d.iter().all(|&v| v > 0.0));
        }
    }
    mesh
}

/// The meshes of the studies: file name and mesh.
fn meshes() -> Vec<(&'static str, Mesh)> {
    let mut out = Vec::new();
    // bars along z, section 2 × 2, for waves and bending: thickness
    // (x) split in 1, 2 and 4 cells, length 20 in 10 cells
    for nx in [1, 2, 4] {
        let mut m = box_mesh([nx, 1, 10], [2.0, 2.0, 20.0], &|_| Fill::Hexa);
        point(&mut m, "TIP", [0.0, 0.0, 20.0]);
        point(&mut m, "MID", [0.0, 0.0, 10.0]);
        cell_at(&mut m, "BAS", [0.1, 0.1, 0.1]);
        out.push((
            ["hexs8_beam1.mmed", "hexs8_beam2.mmed", "hexs8_beam4.mmed"][nx / 2],
            m,
        ));
    }
    let swap: Vec<Mesh> = out[1..].iter().map(|(_, m)| swapped(m.clone())).collect();
    let mut swap = swap.into_iter();
    out.push(("hexs8_beam2_swapped.mmed", swap.next().unwrap()));
    out.push(("hexs8_beam4_swapped.mmed", swap.next().unwrap()));
    // the long bar: 1 × 1 × 40 cells, length 80
    let mut m = box_mesh([1, 1, 40], [2.0, 2.0, 80.0], &|_| Fill::Hexa);
    point(&mut m, "TIP", [0.0, 0.0, 80.0]);
    point(&mut m, "MID", [0.0, 0.0, 40.0]);
    cell_at(&mut m, "BAS", [0.1, 0.1, 0.1]);
    out.push(("hexs8_bar40.mmed", m));
    // mixed: 2 × 2 × 4, the column x < 1 hexahedra, the column x > 1
    // prisms (they meet on the quadrilaterals of the plane x = 1)
    let mut m = box_mesh([2, 2, 4], [2.0, 2.0, 4.0], &|i| {
        if i < 1 {
            Fill::Hexa
        } else {
            Fill::Prisms
        }
    });
    point(&mut m, "TOP_C", [1.0, 1.0, 4.0]);
    point(&mut m, "MID_C", [1.0, 1.0, 2.0]);
    point(&mut m, "ORIG", [0.0, 0.0, 0.0]);
    cell_at(&mut m, "BAS", [0.1, 0.1, 0.1]);
    cell_at(&mut m, "HAUT", [1.9, 0.1, 3.9]);
    out.push(("hexs8_mixed.mmed", m));
    out
}

/// The committed meshes are the ones built above.
#[test]
fn meshes_are_committed() {
    for (file, mesh) in meshes() {
        let path = dir().join(file);
        if std::env::var_os("UPDATE_MESHES").is_some() {
            aster::medio::write_mesh(&path, &mesh).unwrap();
        }
        let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("regen_{file}"));
        aster::medio::write_mesh(&tmp, &mesh).unwrap();
        let committed = aster::medio::read_mesh(&path, None).unwrap();
        assert_eq!(
            committed,
            aster::medio::read_mesh(&tmp, None).unwrap(),
            "{file}"
        );
    }
}

/// The axial wave (tests/studies/hexs8_wave.comm): HEXS8, HEXS20, 3D
/// HEXA8 and HEXA20 against one-dimensional wave theory; and, the motion being
/// quadratic in z per cell, where the 2x2x2 rule of HEXS20 integrates the
/// stiffness exactly, HEXS20 and the full HEXA20 give the same tip
/// history (printed to 6 digits: within 1e-5 of the amplitude).
#[test]
fn axial_wave_in_a_bar() {
    let resu = run_study("hexs8_wave");
    let reduced = printed_table(&resu, "TIP20S");
    let full = printed_table(&resu, "TIP20F");
    assert_eq!(reduced.len(), 241);
    assert_eq!(full.len(), 241);
    let amplitude = 1000.0 * 20.0 / (2.0e5f64 / 7.8e-9).sqrt();
    for (r, f) in reduced.iter().zip(&full) {
        let (a, b): (f64, f64) = (r["DZ"].parse().unwrap(), f["DZ"].parse().unwrap());
        assert!((a - b).abs() <= 1e-5 * amplitude, "{} {a} {b}", r["INST"]);
    }
}

/// Uniaxial plastic compression of a HEXS8 column driven by a DDL_IMPO
/// ramp (FONC_MULT), PETIT and PETIT_REAC, against the uniaxial answer of
/// linear isotropic hardening (tests/studies/hexs8_compression.comm).
#[test]
fn uniaxial_plastic_compression() {
    run_study("hexs8_compression");
}

/// A traction-compression cycle on distorted HEXS8 cells numbered from 4
/// corners (tests/studies/hexs8_cine_cycle.comm, mesh hexs8_cube2.mail):
/// VMIS_ISOT_LINE, VMIS_CINE_LINE and VMIS_ISOT_TRAC against the 1D
/// return-mapping closed forms, and the back stress XCINXX..XCINYZ of
/// VMIS_CINE_LINE in global axes, (2/3) H ε_p (1, −½, −½, 0, 0, 0), in
/// every cell. It was reported in each element's own frame (the frame the
/// published variant integrates the law in): XCINXX and XCINYY swapped on
/// the cells with ξ along y, shears up to 0.24 (36 NOOK before the fix).
#[test]
fn kinematic_back_stress_is_in_global_axes() {
    let resu = run_study("hexs8_cine_cycle");
    assert_eq!(resu.matches("OK   ANALYTIQUE").count(), 53, "{resu}");
}

/// One box element on pure hourglass patterns (tests/studies/
/// hexs8_hourglass_modes.comm): the nodal forces of the bending pattern
/// u_x = κxy and of the shear-type pattern u_x = q·h1 against the closed
/// forms of the assumed-strain operator on a box, with the stored Q
/// (FSTAB7, 19, 38, 51), in STAT_NON_LINE (ADS, Voigt D) and MECA_STATIQUE
/// (te0392, ASQBI); a zero centre stress and ENER_ELAS.
#[test]
fn hourglass_patterns_give_the_closed_form_forces() {
    let resu = run_study("hexs8_hourglass_modes");
    assert_eq!(resu.matches("OK   ANALYTIQUE").count(), 13, "{resu}");
}

/// A free box set moving in the twist hourglass pattern (tests/studies/
/// hexs8_twist_mode.comm), an eigenvector of the stiffness and of both
/// masses on a box: the discrete solutions of DIFF_CENT (lumped and
/// consistent mass), NEWMARK, and NEWMARK with Rayleigh damping
/// (AMOR_ALPHA), and ENER_CIN with the consistent mass.
#[test]
fn twist_hourglass_mode_vibrates_at_its_frequency() {
    let resu = run_study("hexs8_twist_mode");
    assert_eq!(resu.matches("OK   ANALYTIQUE").count(), 8, "{resu}");
}

/// SUIVI_DDL, OBSERVATION and DELTA_GRANDEUR read a HEXS8 cell's one
/// Gauss point, not the hourglass-stress rows stored after it
/// (tests/studies/hexs8_observe.comm: the MAX, MIN and POINT=1 of SIZZ
/// over a uniaxially compressed column against the uniaxial answer).
#[test]
fn observation_reads_the_one_gauss_point_of_hexs8() {
    let resu = run_study("hexs8_observe");
    assert_eq!(resu.matches("OK   ANALYTIQUE").count(), 3, "{resu}");
}

/// Bending of a cantilever driven by a DDL_IMPO ramp at its end
/// (tests/studies/hexs8_cantilever.comm): HEXS20 and HEXS8 (2 and 4
/// across) against beam theory in the command file; here, from the
/// printed tables: one layer of HEXS8 (ADS) below 0.6 of the beam force;
/// the same HEXS8 meshes with every cell numbered from another corner
/// (ξ along y) give the aligned forces to 1e-9 (the element works in its
/// own frame; with its shear rules in global axes it locked, +31 %); the
/// full 2x2x2 HEXA8 more than 30 % above the beam with 1, 2 and 4 cells
/// across (shear locking).
#[test]
fn cantilever_bending() {
    let resu = run_study("hexs8_cantilever");
    let (e, nu, l, h, b) = (2.0e5, 0.3, 20.0, 2.0, 2.0);
    let g = e / (2.0 * (1.0 + nu));
    let i = b * h * h * h / 12.0;
    let beam = 0.01 / (l * l * l / (3.0 * e * i) + l / (5.0 / 6.0 * g * b * h));
    for t in [1, 2, 4] {
        let rows = printed_table(&resu, &format!("FH{t}"));
        let p: f64 = rows[0]["DX"].parse().unwrap();
        assert!(p > 1.3 * beam, "HEXA8, {t} across: {p} against {beam}");
    }
    let force = |name: &str| -> f64 { printed_table(&resu, name)[0]["DX"].parse().unwrap() };
    let one = force("FS1");
    assert!(one < 0.6 * beam, "HEXS8, 1 across: {one} against {beam}");
    for t in [2, 4] {
        let (p, q) = (force(&format!("FW{t}")), force(&format!("FS{t}")));
        assert!(
            (p - q).abs() < 1e-9 * q,
            "HEXS8 renumbered, {t} across: {p} against {q} aligned"
        );
    }
}

/// Mixed meshes (tests/studies/hexs8_mixed.comm): HEXS8 + PENTA6 and
/// HEXS20 + PENTA15 under 3D then 3D_SI reproduce the homogeneous
/// uniaxial state to round-off (in the command file), and the AFFE rule
/// of semantics.md §3.2 as the message file lists the elements: 3D then
/// 3D_SI gives MECA_HEXS8 and MECA_PENTA6; 3D_SI then 3D gives MECA_HEXA8
/// everywhere; 3D_SI alone leaves the 16 prisms out (MODELE1_70).
#[test]
fn mixed_meshes() {
    let run = common::run_study("tests/studies/hexs8_mixed.comm", "hexs8_hexs8_mixed");
    common::assert_all_ok(&run, "hexs8_mixed.resu");
    let mess = run.file("hexs8_mixed.mess");
    let table = |model: &str| -> Vec<String> {
        let tag = format!("model {model} on mesh");
        mess.lines()
            .skip_while(|l| !l.contains(&tag))
            .skip(2)
            .take_while(|l| !l.starts_with('<') && !l.starts_with('#'))
            .map(|l| l.split_whitespace().collect::<Vec<_>>().join(" "))
            .collect()
    };
    let mol = table("MOL");
    assert!(
        mol.contains(&"3D_SI MECA_HEXS8 HEXA8 8".to_string()),
        "{mol:?}"
    );
    assert!(
        mol.contains(&"3D MECA_PENTA6 PENTA6 16".to_string()),
        "{mol:?}"
    );
    let moq = table("MOQ");
    assert!(
        moq.contains(&"3D_SI MECA_HEXS20 HEXA20 8".to_string()),
        "{moq:?}"
    );
    assert!(
        moq.contains(&"3D MECA_PENTA15 PENTA15 16".to_string()),
        "{moq:?}"
    );
    let mos = table("MOS");
    assert!(
        mos.contains(&"3D MECA_HEXA8 HEXA8 8".to_string()),
        "{mos:?}"
    );
    assert!(mos.iter().all(|l| !l.contains("HEXS8")), "{mos:?}");
    let moh = table("MOH");
    assert!(
        moh.contains(&"3D_SI MECA_HEXS8 HEXA8 8".to_string()),
        "{moh:?}"
    );
    assert!(moh.iter().all(|l| !l.contains("PENTA")), "{moh:?}");
    assert!(mess.contains("of the 68 cells, 68 selected, 52 assigned"));
    assert!(
        mess.contains("<MODELE1_70> after occurrence 1 of AFFE (MODELISATION='3D_SI'), 16 cell(s)")
    );
}

/// Runs `text` (a variant of a study) with the study's units; returns
/// the exit code and what the terminal showed.
fn run_variant(tag: &str, text: &str, units: Vec<(i64, PathBuf)>) -> (i32, String) {
    use aster::run::driver::{run_file, RunOptions};
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("hexs8_bad_{tag}"));
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).unwrap();
    let comm = tmp.join("bad.comm");
    std::fs::write(&comm, text).unwrap();
    let mut term = Vec::new();
    let code = run_file(
        &RunOptions {
            comm,
            units,
            out_dir: Some(tmp),
            ..RunOptions::default()
        },
        &mut term,
    );
    (code, String::from_utf8(term).unwrap())
}

/// Bad input on 3D_SI studies stops with a located error, never a panic:
/// the DDL_IMPO of nodes that only prisms hold when 3D_SI alone leaves
/// the prisms out; SIMO_MIEHE and GDEF_LOG on HEXS8 (ELEMENTSSI_1);
/// RELATION='ELAS' on HEXS8 with PETIT and a DEPL-only ETAT_INIT
/// (ELEMENTSSI_3, the message saying which ETAT_INIT counts); a NOM_VARI
/// the law does not have; 3D_SI on a 2D mesh, on faces only and on
/// TETRA4 (MODELE1_6, saying why).
#[test]
fn bad_input_is_located() {
    let mixed = std::fs::read_to_string(dir().join("hexs8_mixed.comm")).unwrap();
    let unit = vec![(20, dir().join("hexs8_mixed.mmed"))];
    let only_si = mixed.replacen(
        "AFFE=(_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'),\n                         _F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D_SI')))",
        "AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D_SI'))",
        1,
    );
    assert_ne!(only_si, mixed);
    let (code, term) = run_variant("holes", &only_si, unit.clone());
    assert_eq!(code, 1, "{term}");
    assert!(term.contains("DYNA_NON_LINE/EXCIT"), "{term}");
    assert!(
        term.contains("the node belongs to no element of the model"),
        "{term}"
    );
    assert!(term.contains("bad.comm:"), "{term}");
    for measure in ["SIMO_MIEHE", "GDEF_LOG"] {
        let text = mixed.replacen(
            "COMPORTEMENT=_F(RELATION='VMIS_ISOT_LINE', TOUT='OUI')",
            &format!(
                "COMPORTEMENT=_F(RELATION='VMIS_ISOT_LINE', DEFORMATION='{measure}', TOUT='OUI')"
            ),
            1,
        );
        assert_ne!(text, mixed);
        let (code, term) = run_variant(measure, &text, unit.clone());
        assert_eq!(code, 1, "{term}");
        assert!(term.contains("DYNA_NON_LINE/COMPORTEMENT"), "{term}");
        assert!(term.contains("ELEMENTSSI_1"), "{term}");
        assert!(term.contains(measure), "{term}");
    }
    let text = mixed.replacen(
        "COMPORTEMENT=_F(RELATION='VMIS_ISOT_LINE', TOUT='OUI'),",
        "COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), ETAT_INIT=_F(DEPL=U0),",
        1,
    );
    let text = text.replacen(
        "RL = DYNA_NON_LINE(",
        "U0 = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='AFFE', MODELE=MOL,\n                 AFFE=_F(TOUT='OUI', NOM_CMP=('DX', 'DY', 'DZ'), VALE=(0., 0., 0.)))\nRL = DYNA_NON_LINE(",
        1,
    );
    let (code, term) = run_variant("elas", &text, unit.clone());
    assert_eq!(code, 1, "{term}");
    assert!(term.contains("ELEMENTSSI_3"), "{term}");
    assert!(term.contains("ETAT_INIT with EVOL_NOLI"), "{term}");
    let comp = std::fs::read_to_string(dir().join("hexs8_compression.comm")).unwrap();
    let text = comp.replacen(
        "NOM_VARI='EPSPEQ', GROUP_MA",
        "NOM_VARI='EPSEQ', GROUP_MA",
        1,
    );
    assert_ne!(text, comp);
    let (code, term) = run_variant(
        "nom_vari",
        &text,
        vec![(20, dir().join("hexs8_beam1.mmed"))],
    );
    assert_eq!(code, 1, "{term}");
    assert!(term.contains("TEST_RESU/RESU/NOM_VARI"), "{term}");
    assert!(term.contains("its variables: EPSPEQ, INDIPLAS"), "{term}");
    let two_d = "DEBUT()\nMAIL = LIRE_MAILLAGE(FORMAT='MED')\nMO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D_SI'))\nFIN()\n";
    let b = Path::new(env!("CARGO_MANIFEST_DIR")).join("med/sdnv103b.mmed");
    let (code, term) = run_variant("two_d", two_d, vec![(20, b)]);
    assert_eq!(code, 1, "{term}");
    assert!(term.contains("AFFE_MODELE/AFFE"), "{term}");
    assert!(term.contains("MODELE1_6"), "{term}");
    assert!(term.contains("bad.comm:3:"), "{term}");
    // 3D_SI on a group of QUAD4 faces only, the HEXA8 cells left out: the
    // message said the HEXA8 cells were of no type 3D_SI has an element on
    // while listing HEXA8 among them (probe hexp); it says the selection
    // holds no volume cell.
    let faces = "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='ASTER')\nMO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(GROUP_MA='XMAX', PHENOMENE='MECANIQUE', MODELISATION='3D_SI'))\nFIN()\n";
    let cube = vec![(20, dir().join("hexs8_cube2.mail"))];
    let (code, term) = run_variant("faces", faces, cube);
    assert_eq!(code, 1, "{term}");
    assert!(term.contains("bad.comm:3:"), "{term}");
    assert!(
        term.contains(
            "the AFFE occurrences select no cell of dimension 3, only 4 QUAD4 (the mesh MA has 8 HEXA8)"
        ),
        "{term}"
    );
    assert!(!term.contains("are of no type"), "{term}");
    // 3D_SI on TETRA4 cells (3D_SI has no element there): says so.
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("hexs8_tetra4.mail");
    std::fs::write(
        &tmp,
        "COOR_3D\nN1 0 0 0\nN2 1 0 0\nN3 1 1 0\nN4 0 1 0\nN5 0 0 1\nN6 1 0 1\nN7 1 1 1\nN8 0 1 1\nFINSF\n\
         TETRA4\nM1 N1 N2 N4 N5\nM2 N2 N3 N4 N7\nM3 N2 N5 N6 N7\nM4 N4 N5 N7 N8\nM5 N2 N4 N5 N7\nFINSF\nFIN\n",
    )
    .unwrap();
    let tetra = faces.replace("GROUP_MA='XMAX'", "TOUT='OUI'");
    let (code, term) = run_variant("tetra4", &tetra, vec![(20, tmp)]);
    assert_eq!(code, 1, "{term}");
    assert!(term.contains("bad.comm:3:"), "{term}");
    assert!(
        term.contains("the AFFE occurrences select 5 TETRA4, and the modelisations define elements only on other types (3D_SI on TETRA10, HEXA8, HEXA20) (MODELE1_6)"),
        "{term}"
    );
}

/// tests/verification/contact_friction.comm in 3D_SI (tests/studies/
/// hexs8_contact.comm): a HEXS8 block on the QUAD4 top face of a fixed
/// HEXS8 slab, penalised discrete contact with Coulomb friction: sticking
/// (the contact carries m g cos θ and the friction m g sin θ), sliding at
/// g (sin θ − μ cos θ), and braking from V0 to rest after V0²/(2 μ g).
#[test]
fn block_on_a_slab_with_coulomb_friction() {
    run_study("hexs8_contact");
}

/// A DDL_IMPO under FONC_MULT in dynamics (tests/studies/
/// hexs8_base_motion.comm): the base of a HEXS8 bar driven at V0, Newmark
/// and DIFF_CENT, against one-dimensional wave theory (the tip at rest
/// until L/c, then at 2 V0).
#[test]
fn base_driven_at_constant_velocity() {
    run_study("hexs8_base_motion");
}

/// tests/verification/contact_penalty.comm in 3D_SI (tests/studies/
/// hexs8_contact_penalty.comm): the HEXS8 block at rest on the HEXS8 slab,
/// penalised contact: the contact carries m g and the summed penetration
/// is m g / E_N for E_N = 1e4 and 1e5.
#[test]
fn penetration_is_the_weight_over_the_penalty() {
    run_study("hexs8_contact_penalty");
}

/// 3D_SI impact (tests/studies/hexs8_impact.comm): the HEXS8 block
/// dropped at V0 on the HEXS8 slab with a soft penalty bounces as a rigid
/// mass on 9 springs: the deepest penetration V0/ω, and it leaves at +V0.
#[test]
fn block_bounces_on_the_penalty() {
    run_study("hexs8_impact");
}
