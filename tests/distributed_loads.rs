//! AFFE_CHAR_MECA FORCE_FACE, FORCE_ARETE, FORCE_CONTOUR and FORCE_INTERNE
//! verified through whole studies: every node of the mesh is held by
//! DDL_IMPO, so the support reactions (CALC_CHAMP REAC_NODA) are exactly
//! minus the applied nodal forces, and their POST_RELEVE_T RESULTANTE
//! must equal the force density times the measure of the loaded cells,
//! computed here from the node coordinates alone (polygon areas, segment
//! lengths, frustum and prism volumes, the ∫ r ds and ∫∫ r dA of AXIS).
//!
//! The meshes are built here: in 3D a frustum of a square pyramid
//! (HEXA8, and HEXA20 with its mid-nodes moved along the edges, off the
//! middle: non-affine cells with flat trapezoidal faces) and an oblique
//! prism (PENTA6, PENTA15 with moved mid-nodes); in AXIS a trapezoid
//! (QUAD4, QUAD8 with moved mid-nodes) with an oblique edge. The Gauss
//! families integrate these shapes exactly, so the measure is reproduced
//! to round-off: the tolerance is 1e-10 relative.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use aster::mesh::shape::reference_nodes;
use aster::mesh::{Cell, CellType, Mesh};
mod common;

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: V3) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// Mid-node position on the straight edge a-b, off the middle by an
/// amount that changes from edge to edge (the cells stay valid for
/// |shift| < 1/4).
fn mid(a: V3, b: V3, k: usize) -> V3 {
    let t = 0.5 + [0.09, -0.07, 0.0, 0.12, -0.1][k % 5];
    [0, 1, 2].map(|i| a[i] + t * (b[i] - a[i]))
}

/// Adds a cell of `kind` whose vertices are `x(reference vertex)` and
/// whose mid-nodes sit on the straight edges (moved off the middle).
/// Returns the cell's node numbers in MED order.
fn add_cell(mesh: &mut Mesh, kind: CellType, x: &dyn Fn(V3) -> V3) -> Vec<usize> {
    let refs = reference_nodes(kind);
    let nv = kind.nvertices();
    let mut nodes = Vec::new();
    for r in &refs[..nv] {
        nodes.push(mesh.coords.len());
        mesh.coords.push(x(*r));
    }
    for (k, &(a, b)) in kind.mid_edges().iter().enumerate() {
        nodes.push(mesh.coords.len());
        let p = mid(mesh.coords[nodes[a]], mesh.coords[nodes[b]], k);
        mesh.coords.push(p);
    }
    mesh.cells.push(Cell {
        kind,
        nodes: nodes.clone(),
    });
    nodes
}

/// The mid-node of the volume cell `cell` on its edge (a, b) (local
/// vertex numbers).
fn mid_of(kind: CellType, cell: &[usize], a: usize, b: usize) -> usize {
    let k = kind
        .mid_edges()
        .iter()
        .position(|&(p, q)| (p, q) == (a, b) || (p, q) == (b, a))
        .unwrap();
    cell[kind.nvertices() + k]
}

/// A skin cell on the local vertices `verts` (cyclic order) of the
/// volume cell `cell`, with the volume's mid-nodes if it is quadratic.
fn add_skin(mesh: &mut Mesh, vol: CellType, cell: &[usize], verts: &[usize]) -> usize {
    let quadratic = vol.is_quadratic();
    let kind = match (verts.len(), quadratic) {
        (2, false) => CellType::Seg2,
        (2, true) => CellType::Seg3,
        (3, false) => CellType::Tria3,
        (3, true) => CellType::Tria6,
        (4, false) => CellType::Quad4,
        _ => CellType::Quad8,
    };
    let mut nodes: Vec<usize> = verts.iter().map(|&v| cell[v]).collect();
    if quadratic {
        let n = verts.len();
        let sides = if n == 2 { 1 } else { n };
        for k in 0..sides {
            nodes.push(mid_of(vol, cell, verts[k], verts[(k + 1) % n]));
        }
    }
    mesh.cells.push(Cell { kind, nodes });
    mesh.cells.len() - 1
}

/// The area of the planar polygon through `verts` (cyclic).
fn polygon_area(mesh: &Mesh, cell: &[usize], verts: &[usize]) -> f64 {
    let x = |k: usize| mesh.coords[cell[verts[k]]];
    let mut s = [0.0; 3];
    for k in 1..verts.len() - 1 {
        let c = cross(sub(x(k), x(0)), sub(x(k + 1), x(0)));
        s = [0, 1, 2].map(|i| s[i] + c[i]);
    }
    0.5 * norm(s)
}

/// The local vertices of the faces of a HEXA8/PENTA6 in MED order, each
/// in cyclic order (for the area and the skin cell).
fn hexa_faces() -> Vec<Vec<usize>> {
    vec![
        vec![0, 1, 2, 3],
        vec![4, 5, 6, 7],
        vec![0, 1, 5, 4],
        vec![1, 2, 6, 5],
    ]
}

/// What the 3D mesh holds, with the measures computed from its nodes.
struct Mesh3d {
    mesh: Mesh,
    /// group name -> measure (area, length or volume) of its cells
    measure: HashMap<&'static str, f64>,
}

/// The 3D mesh: a frustum of a pyramid as one HEXA8 and one HEXA20 (side
/// 2 at the bottom, 1.2 at the top, height 1.5, the top moved sideways by
/// (0.3, −0.2)), an oblique prism as one PENTA6 and one PENTA15. Groups:
/// H8, H20, P6, P15 (the volumes), Q4, Q8 (four faces of each hexa), T3,
/// T6 (both ends of each prism), S2, S3 (three edges of each hexa), ALL
/// (every node).
fn mesh3d() -> Mesh3d {
    let mut mesh = Mesh {
        name: "LOADS3D".into(),
        dim: 3,
        ..Mesh::default()
    };
    let mut measure = HashMap::new();
    let (a, b, h, off) = (2.0, 1.2, 1.5, [0.3, -0.2]);
    let frustum = move |x0: f64| {
        move |r: V3| {
            let s = (r[2] + 1.0) / 2.0;
            let size = a + (b - a) * s;
            [
                x0 + off[0] * s + size * r[0] / 2.0,
                off[1] * s + size * r[1] / 2.0,
                h * s,
            ]
        }
    };
    let m = [[1.1, 0.3, -0.2], [0.1, 0.9, 0.4], [0.2, -0.3, 1.6]];
    let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    let prism = move |x0: f64| {
        move |r: V3| {
            let mut x = [x0, 0.0, 0.0];
            for k in 0..3 {
                for l in 0..3 {
                    x[k] += m[k][l] * r[l];
                }
            }
            x
        }
    };
    let vol_frustum = h / 3.0 * (a * a + b * b + a * b);
    for (kind, x0, vname, fname, ename) in [
        (CellType::Hexa8, 0.0, "H8", "Q4", "S2"),
        (CellType::Hexa20, 10.0, "H20", "Q8", "S3"),
    ] {
        let c = add_cell(&mut mesh, kind, &frustum(x0));
        mesh.cell_groups
            .insert(vname.into(), vec![mesh.ncells() - 1]);
        measure.insert(vname, vol_frustum);
        let mut faces = Vec::new();
        let mut area = 0.0;
        for f in hexa_faces() {
            faces.push(add_skin(&mut mesh, kind, &c, &f));
            area += polygon_area(&mesh, &c, &f);
        }
        mesh.cell_groups.insert(fname.into(), faces);
        measure.insert(fname, area);
        let mut edges = Vec::new();
        let mut length = 0.0;
        for (p, q) in [(0, 1), (1, 5), (6, 7)] {
            edges.push(add_skin(&mut mesh, kind, &c, &[p, q]));
            length += norm(sub(mesh.coords[c[q]], mesh.coords[c[p]]));
        }
        mesh.cell_groups.insert(ename.into(), edges);
        measure.insert(ename, length);
    }
    for (kind, x0, vname, fname) in [
        (CellType::Penta6, 20.0, "P6", "T3"),
        (CellType::Penta15, 30.0, "P15", "T6"),
    ] {
        let c = add_cell(&mut mesh, kind, &prism(x0));
        mesh.cell_groups
            .insert(vname.into(), vec![mesh.ncells() - 1]);
        // the reference prism has volume 1
        measure.insert(vname, det.abs());
        let mut faces = Vec::new();
        let mut area = 0.0;
        for f in [[0, 1, 2], [3, 4, 5]] {
            faces.push(add_skin(&mut mesh, kind, &c, &f));
            area += polygon_area(&mesh, &c, &f);
        }
        mesh.cell_groups.insert(fname.into(), faces);
        measure.insert(fname, area);
    }
    mesh.node_groups
        .insert("ALL".into(), (0..mesh.nnodes()).collect());
    Mesh3d { mesh, measure }
}

/// The AXIS mesh: the trapezoid with vertices (1, 0), (3, 0), (2.6, 2),
/// (1.4, 1.5) as one QUAD4 and (shifted up by 5) one QUAD8 with moved
/// mid-nodes; groups A4, A8 (the cells), E2, E3 (the bottom, oblique
/// right and top edges of each), ALL. Measures per radian: ∫ r ds on the
/// edges, ∫∫ r dA on the cells; with the suffix _P (D_PLAN, per unit
/// thickness) the lengths and areas.
fn mesh_axis() -> (Mesh, HashMap<&'static str, f64>) {
    let mut mesh = Mesh {
        name: "LOADSAX".into(),
        dim: 2,
        ..Mesh::default()
    };
    let mut measure = HashMap::new();
    let verts = [[1.0, 0.0], [3.0, 0.0], [2.6, 2.0], [1.4, 1.5]];
    for (kind, z0, cname, ename) in [
        (CellType::Quad4, 0.0, "A4", "E2"),
        (CellType::Quad8, 5.0, "A8", "E3"),
    ] {
        // bilinear map of the reference square onto the trapezoid
        let x = move |r: V3| {
            let n = [
                (1.0 - r[0]) * (1.0 - r[1]) / 4.0,
                (1.0 + r[0]) * (1.0 - r[1]) / 4.0,
                (1.0 + r[0]) * (1.0 + r[1]) / 4.0,
                (1.0 - r[0]) * (1.0 + r[1]) / 4.0,
            ];
            let mut p = [0.0, z0, 0.0];
            for k in 0..4 {
                p[0] += n[k] * verts[k][0];
                p[1] += n[k] * verts[k][1];
            }
            p
        };
        let c = add_cell(&mut mesh, kind, &x);
        mesh.cell_groups
            .insert(cname.into(), vec![mesh.ncells() - 1]);
        // ∫∫ r dA over a polygon: (1/6) Σ (r_i + r_j)(r_i z_j − r_j z_i)
        let mut rda = 0.0;
        for k in 0..4 {
            let (p, q) = (mesh.coords[c[k]], mesh.coords[c[(k + 1) % 4]]);
            rda += (p[0] + q[0]) * (p[0] * q[1] - q[0] * p[1]) / 6.0;
        }
        measure.insert(cname, rda);
        measure.insert(
            if z0 == 0.0 { "A4_P" } else { "A8_P" },
            polygon_area(&mesh, &c, &[0, 1, 2, 3]),
        );
        let mut edges = Vec::new();
        let mut rds = 0.0;
        let mut length = 0.0;
        for (p, q) in [(0, 1), (1, 2), (2, 3)] {
            edges.push(add_skin(&mut mesh, kind, &c, &[p, q]));
            let (xp, xq) = (mesh.coords[c[p]], mesh.coords[c[q]]);
            rds += norm(sub(xq, xp)) * (xp[0] + xq[0]) / 2.0;
            length += norm(sub(xq, xp));
        }
        mesh.cell_groups.insert(ename.into(), edges);
        measure.insert(ename, rds);
        measure.insert(if z0 == 0.0 { "E2_P" } else { "E3_P" }, length);
    }
    mesh.node_groups
        .insert("ALL".into(), (0..mesh.nnodes()).collect());
    (mesh, measure)
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A study on `mesh` (written next to it) with every node held and the
/// load `load` (the keywords of an AFFE_CHAR_MECA after MODELE=MO) in a
/// one-step DYNA_NON_LINE; prints the table T of the REAC_NODA
/// resultant and, with `per_node`, the table TN of the reactions node by
/// node. Returns the run.
fn held_study(
    tag: &str,
    mesh: &Mesh,
    modelisation: &str,
    load: &str,
    per_node: bool,
) -> common::Run {
    let dir = scratch(tag);
    let med = dir.join("mesh.mmed");
    aster::medio::write_mesh(&med, mesh).unwrap();
    let (dofs, cmps) = if modelisation != "3D" {
        ("DX=0., DY=0.", "('DX', 'DY')")
    } else {
        ("DX=0., DY=0., DZ=0.", "('DX', 'DY', 'DZ')")
    };
    let per_node = if per_node {
        format!(
            "TN = POST_RELEVE_T(ACTION=_F(INTITULE='N', RESULTAT=R, NOM_CHAM='REAC_NODA', \
             GROUP_NO='ALL', NOM_CMP={cmps}, OPERATION='EXTRACTION', INST=1.E-3))\n\
             IMPR_TABLE(TABLE=TN, FORMAT_R='E24.16')\n"
        )
    } else {
        String::new()
    };
    let comm = format!(
        "DEBUT()\n\
         RHO = 7.8E-9\n\
         MAIL = LIRE_MAILLAGE(FORMAT='MED')\n\
         MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', \
         MODELISATION='{modelisation}'))\n\
         MAT = DEFI_MATERIAU(ELAS=_F(E=2.E5, NU=0.3, RHO=RHO))\n\
         CHMAT = AFFE_MATERIAU(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
         BLOQ = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(TOUT='OUI', {dofs}))\n\
         CH = AFFE_CHAR_MECA(MODELE=MO, {load})\n\
         L1 = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1.E-3, NOMBRE=1))\n\
         R = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=(_F(CHARGE=BLOQ), _F(CHARGE=CH)),\n\
             COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'), INCREMENT=_F(LIST_INST=L1),\n\
             SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'))\n\
         R = CALC_CHAMP(reuse=R, RESULTAT=R, FORCE='REAC_NODA')\n\
         T = POST_RELEVE_T(ACTION=_F(INTITULE='R', RESULTAT=R, NOM_CHAM='REAC_NODA', \
         GROUP_NO='ALL', RESULTANTE={cmps}, OPERATION='EXTRACTION', INST=1.E-3))\n\
         IMPR_TABLE(TABLE=T, FORMAT_R='E24.16')\n\
         {per_node}\
         FIN()\n"
    );
    std::fs::write(dir.join("study.comm"), comm).unwrap();
    std::fs::write(
        dir.join("study.export"),
        format!("F mmed {} D 20\n", med.display()),
    )
    .unwrap();
    common::run_study(
        dir.join("study.comm").to_str().unwrap(),
        &format!("{tag}_out"),
    )
}

/// The resultant of the reactions (DX, DY[, DZ]) of a held study.
fn resultant(run: &common::Run, ncmp: usize) -> Vec<f64> {
    assert_eq!(run.code, 0, "{}", run.term);
    let resu = run.file("study.resu");
    let rows = common::printed_table(&resu, "T");
    assert_eq!(rows.len(), 1, "{resu}");
    ["DX", "DY", "DZ"][..ncmp]
        .iter()
        .map(|c| rows[0][*c].parse().unwrap())
        .collect()
}

fn assert_resultant(what: &str, got: &[f64], density: &[f64], measure: f64) {
    let scale = measure * density.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (i, (&g, &f)) in got.iter().zip(density).enumerate() {
        // the reactions balance the load: minus the force
        let expect = -f * measure;
        assert!(
            (g - expect).abs() <= 1e-10 * scale,
            "{what} component {i}: reaction {g:e}, expected {expect:e} (measure {measure})"
        );
    }
}

const F3: [f64; 3] = [1.7, -2.3, 0.6];

/// FORCE_FACE on QUAD4, QUAD8, TRIA3 and TRIA6 faces: the resultant is
/// the density times the area.
#[test]
fn force_face_resultant_is_density_times_area() {
    let m = mesh3d();
    for g in ["Q4", "Q8", "T3", "T6"] {
        let run = held_study(
            &format!("dl_face_{g}"),
            &m.mesh,
            "3D",
            &format!(
                "FORCE_FACE=_F(GROUP_MA='{g}', FX={}, FY={}, FZ={})",
                F3[0], F3[1], F3[2]
            ),
            false,
        );
        assert_resultant(g, &resultant(&run, 3), &F3, m.measure[g]);
    }
}

/// FORCE_ARETE on SEG2 and SEG3 edges of a 3D model: density times length.
#[test]
fn force_arete_resultant_is_density_times_length() {
    let m = mesh3d();
    for g in ["S2", "S3"] {
        let run = held_study(
            &format!("dl_arete_{g}"),
            &m.mesh,
            "3D",
            &format!(
                "FORCE_ARETE=_F(GROUP_MA='{g}', FX={}, FY={}, FZ={})",
                F3[0], F3[1], F3[2]
            ),
            false,
        );
        assert_resultant(g, &resultant(&run, 3), &F3, m.measure[g]);
    }
}

/// FORCE_INTERNE on HEXA8, HEXA20, PENTA6 and PENTA15: density times
/// volume.
#[test]
fn force_interne_resultant_is_density_times_volume() {
    let m = mesh3d();
    for g in ["H8", "H20", "P6", "P15"] {
        let run = held_study(
            &format!("dl_interne_{g}"),
            &m.mesh,
            "3D",
            &format!(
                "FORCE_INTERNE=_F(GROUP_MA='{g}', FX={}, FY={}, FZ={})",
                F3[0], F3[1], F3[2]
            ),
            false,
        );
        assert_resultant(g, &resultant(&run, 3), &F3, m.measure[g]);
    }
}

/// FORCE_CONTOUR in AXIS on SEG2 and SEG3 edges (one oblique): per
/// radian, the density times ∫ r ds; FORCE_INTERNE in AXIS: the density
/// times ∫∫ r dA. In D_PLAN (per unit thickness) the length and the area.
#[test]
fn axis_force_contour_and_interne_are_per_radian() {
    let (mesh, measure) = mesh_axis();
    let f = [2.5, -1.5];
    for (modelisation, suffix) in [("AXIS", ""), ("D_PLAN", "_P")] {
        for (g, key) in [
            ("E2", "FORCE_CONTOUR"),
            ("E3", "FORCE_CONTOUR"),
            ("A4", "FORCE_INTERNE"),
            ("A8", "FORCE_INTERNE"),
        ] {
            let run = held_study(
                &format!("dl_{modelisation}_{g}"),
                &mesh,
                modelisation,
                &format!("{key}=_F(GROUP_MA='{g}', FX={}, FY={})", f[0], f[1]),
                false,
            );
            let m = measure[format!("{g}{suffix}").as_str()];
            assert_resultant(g, &resultant(&run, 2), &f, m);
        }
    }
}

/// The reactions node by node (node name -> components).
fn reactions(run: &common::Run, cmps: &[&str]) -> HashMap<String, Vec<f64>> {
    assert_eq!(run.code, 0, "{}", run.term);
    let resu = run.file("study.resu");
    common::printed_table(&resu, "TN")
        .into_iter()
        .map(|r| {
            (
                r["NOEUD"].clone(),
                cmps.iter().map(|c| r[*c].parse().unwrap()).collect(),
            )
        })
        .collect()
}

/// FORCE_INTERNE = ρ g d gives the nodal forces of PESANTEUR with the
/// same ρ, g, d, node by node, on every volume cell type (3D and AXIS).
#[test]
fn force_interne_equals_pesanteur() {
    let g = 9.81e3;
    let d = [0.6, -0.8, 0.0];
    let m = mesh3d();
    let (max, _) = mesh_axis();
    for (tag, mesh, modelisation, cmps) in [
        ("3d", &m.mesh, "3D", &["DX", "DY", "DZ"][..]),
        ("axis", &max, "AXIS", &["DX", "DY"][..]),
        ("dplan", &max, "D_PLAN", &["DX", "DY"][..]),
    ] {
        let interne = if modelisation != "3D" {
            format!(
                "FORCE_INTERNE=_F(TOUT='OUI', FX=RHO * {g} * {}, FY=RHO * {g} * {})",
                d[0], d[1]
            )
        } else {
            format!(
                "FORCE_INTERNE=_F(TOUT='OUI', FX=RHO * {g} * {}, FY=RHO * {g} * {}, FZ=0.)",
                d[0], d[1]
            )
        };
        let a = reactions(
            &held_study(&format!("dl_fi_{tag}"), mesh, modelisation, &interne, true),
            cmps,
        );
        let b = reactions(
            &held_study(
                &format!("dl_pes_{tag}"),
                mesh,
                modelisation,
                &format!(
                    "PESANTEUR=_F(GRAVITE={g}, DIRECTION=({}, {}, {}))",
                    d[0], d[1], d[2]
                ),
                true,
            ),
            cmps,
        );
        assert_eq!(a.len(), mesh.nnodes());
        let scale = b.values().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(scale > 0.0);
        for (node, fa) in &a {
            for (x, y) in fa.iter().zip(&b[node]) {
                assert!(
                    (x - y).abs() <= 1e-13 * scale,
                    "{tag} {node}: {fa:?} vs {:?}",
                    b[node]
                );
            }
        }
    }
}

/// The errors: FORCE_FACE on an AXIS model, FORCE_CONTOUR on a 3D one,
/// FZ in AXIS, a selection with no cell of the kind, a moment.
#[test]
fn bad_distributed_loads_are_located_errors() {
    let m = mesh3d();
    let (max, _) = mesh_axis();
    for (tag, mesh, modelisation, load, place, what) in [
        (
            "face_axis",
            &max,
            "AXIS",
            "FORCE_FACE=_F(GROUP_MA='E2', FX=1.)",
            "AFFE_CHAR_MECA/FORCE_FACE",
            "on a 2D model, FORCE_CONTOUR loads the SEG2/SEG3 edges",
        ),
        (
            "contour_3d",
            &m.mesh,
            "3D",
            "FORCE_CONTOUR=_F(GROUP_MA='S2', FX=1.)",
            "AFFE_CHAR_MECA/FORCE_CONTOUR",
            "FORCE_ARETE the SEG2/SEG3 edges",
        ),
        (
            "fz_axis",
            &max,
            "AXIS",
            "FORCE_CONTOUR=_F(GROUP_MA='E2', FZ=1.)",
            "AFFE_CHAR_MECA/FORCE_CONTOUR/FZ",
            "(valid: FX, FY)",
        ),
        (
            "face_on_volume",
            &m.mesh,
            "3D",
            "FORCE_FACE=_F(GROUP_MA='H8', FX=1.)",
            "AFFE_CHAR_MECA/FORCE_FACE",
            "has no cell that FORCE_FACE loads",
        ),
        (
            "moment",
            &m.mesh,
            "3D",
            "FORCE_ARETE=_F(GROUP_MA='S2', MX=1.)",
            "not implemented yet",
            "MX",
        ),
    ] {
        let run = held_study(&format!("dl_bad_{tag}"), mesh, modelisation, load, false);
        assert_eq!(run.code, 1, "{tag}: {}", run.term);
        assert!(run.term.contains(place), "{tag}: {}", run.term);
        assert!(run.term.contains(what), "{tag}: {}", run.term);
        assert!(run.term.contains("study.comm:8:"), "{tag}: {}", run.term);
    }
}
