//! Continuous contact (FORMULATION='CONTINUE') in 3D: an elastic block
//! (HEXA8, 3D model, NU = 0) pressed on a rigid plane, solved statically
//! (the engine driven step by step with a negligible density) under loads
//! applied as consistent nodal forces integrated here by Gauss quadrature,
//! independently of the contact code.
//!
//! The block is [0, 2] x [0, 2] x [0, H], 2 x 2 x 1 HEXA8; its bottom face
//! (four QUAD4, SZZ) is the slave; the master is the top face of a fixed
//! foundation turned by BETA about z (the pairing on a turned cell; the
//! tangents are code_aster's, rebuilt from the normal: tau1 = e_y,
//! tau2 = -e_x, oblique to the diagonal loads). The
//! block's top face carries a uniform pressure p and is held laterally
//! (DX = DY = 0), which removes the rigid-body modes without stressing the
//! block (NU = 0: sigma_zz = -p is uniform, HEXA8 represent it exactly).
//!
//! - Frictionless: LAGS_C = -p exactly at every slave node (nodal QUAD4
//!   weights are the consistent load of a uniform pressure), zero gap.
//! - Friction: a uniform traction q along the block's diagonal, on the
//!   slave face itself, is balanced node by node by friction while the
//!   block sticks: (LAGS_F1, LAGS_F2) = q/(mu p) in the tangent basis,
//!   exactly. Beyond q = mu p every node slides: |(LAGS_F1, LAGS_F2)| = 1
//!   along the node's slip (Coulomb's law), the block being sheared
//!   against its held top. The diagonal is a symmetry plane of the whole
//!   problem, so the total friction force is along the load, exactly.
#![allow(clippy::needless_range_loop)]

mod dynamics_support;

use aster::contact::{ContactDef, LinkState};
use aster::mesh::ops::{orie_peau, OrieDim};
use aster::mesh::shape::{eval, reference_nodes};
use aster::mesh::{Cell, CellType, Mesh};
use aster::model::{Dof, MaterialField, MechLoad};
use aster::nonlinear::{
    discretize, initial_state, ConvergenceSettings, DiscreteContact, Engine, NewtonSettings,
    Occurrence,
};
use aster::result::NodalField;
use aster::time::Scheme;
use dynamics_support::*;

const P: f64 = 1.0;
const MU: f64 = 0.25;
const E: f64 = 1000.0;
const H: f64 = 0.5;
/// Turn of the master plane about z (degrees).
const BETA: f64 = 20.0;

fn block_mesh() -> Mesh {
    let mut coords = Vec::new();
    let mut id = [[[0usize; 2]; 3]; 3];
    for k in 0..2 {
        for j in 0..3 {
            for i in 0..3 {
                id[i][j][k] = coords.len();
                coords.push([i as f64, j as f64, k as f64 * H]);
            }
        }
    }
    let mut cells = Vec::new();
    // HEXA8 in MED order, built from the reference coordinates.
    for ci in 0..2 {
        for cj in 0..2 {
            let nodes = reference_nodes(CellType::Hexa8)
                .iter()
                .map(|x| {
                    let a = |v: f64| usize::from(v > 0.0);
                    id[ci + a(x[0])][cj + a(x[1])][a(x[2])]
                })
                .collect();
            cells.push(Cell {
                kind: CellType::Hexa8,
                nodes,
            });
        }
    }
    let quad = |k: usize, ci: usize, cj: usize| -> Vec<usize> {
        reference_nodes(CellType::Quad4)
            .iter()
            .map(|x| id[ci + usize::from(x[0] > 0.0)][cj + usize::from(x[1] > 0.0)][k])
            .collect()
    };
    let (mut szz, mut top) = (Vec::new(), Vec::new());
    for ci in 0..2 {
        for cj in 0..2 {
            szz.push(cells.len());
            cells.push(Cell {
                kind: CellType::Quad4,
                nodes: quad(0, ci, cj),
            });
            top.push(cells.len());
            cells.push(Cell {
                kind: CellType::Quad4,
                nodes: quad(1, ci, cj),
            });
        }
    }
    // Foundation: a HEXA8 below z = 0, turned by BETA about (1, 1).
    let (s, c) = BETA.to_radians().sin_cos();
    let f0 = coords.len();
    let mut fid = std::collections::HashMap::new();
    for x in reference_nodes(CellType::Hexa8) {
        let (a, b) = (2.5 * x[0], 2.5 * x[1]);
        fid.insert([x[0] as i32, x[1] as i32, x[2] as i32], coords.len());
        coords.push([1.0 + c * a - s * b, 1.0 + s * a + c * b, 0.5 * (x[2] - 1.0)]);
    }
    let found = cells.len();
    cells.push(Cell {
        kind: CellType::Hexa8,
        nodes: (f0..f0 + 8).collect(),
    });
    let rigid = cells.len();
    cells.push(Cell {
        kind: CellType::Quad4,
        nodes: reference_nodes(CellType::Quad4)
            .iter()
            .map(|x| fid[&[x[0] as i32, x[1] as i32, 1]])
            .collect(),
    });
    let mut mesh = Mesh {
        name: "MAIL".into(),
        dim: 3,
        coords,
        cells,
        ..Default::default()
    };
    mesh.cell_groups.insert("VOL".into(), vec![0, 1, 2, 3]);
    mesh.cell_groups.insert("SZZ".into(), szz);
    mesh.cell_groups.insert("TOP".into(), top);
    mesh.cell_groups.insert("VOL_RIG".into(), vec![found]);
    mesh.cell_groups.insert("RIGID".into(), vec![rigid]);
    orie_peau(&mut mesh, OrieDim::D3, &["SZZ", "RIGID"], None).unwrap();
    mesh
}

/// Consistent nodal forces of a uniform traction `t` on the QUAD4 of
/// `group` (2 x 2 Gauss, exact on these flat parallelograms), added to
/// `f` (full, 3 dofs per node).
fn traction(mesh: &Mesh, group: &str, t: [f64; 3], f: &mut [f64]) {
    if t == [0.0; 3] {
        return;
    }
    let g = 1.0 / 3.0f64.sqrt();
    for &c in &mesh.cell_groups[group] {
        let n = &mesh.cells[c].nodes;
        for (xi, eta) in [(-g, -g), (g, -g), (g, g), (-g, g)] {
            let ev = eval(CellType::Quad4, [xi, eta, 0.0]);
            let (mut a1, mut a2) = ([0.0; 3], [0.0; 3]);
            for (k, d) in ev.dn().iter().enumerate() {
                for i in 0..3 {
                    a1[i] += d[0] * mesh.coords[n[k]][i];
                    a2[i] += d[1] * mesh.coords[n[k]][i];
                }
            }
            let cr = [
                a1[1] * a2[2] - a1[2] * a2[1],
                a1[2] * a2[0] - a1[0] * a2[2],
                a1[0] * a2[1] - a1[1] * a2[0],
            ];
            let jac = (cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]).sqrt();
            for k in 0..4 {
                for d in 0..3 {
                    f[3 * n[k] + d] += t[d] * ev.n()[k] * jac;
                }
            }
        }
    }
}

/// One converged load step.
#[derive(Debug)]
struct StepOut {
    q: f64,
    /// Per slave node: (node, LAGS_C, (LAGS_F1, LAGS_F2), its link state).
    points: Vec<(usize, f64, [f64; 2], LinkState)>,
    /// RESI_GLOB_MAXI of each Newton iteration of the step.
    residuals: Vec<f64>,
    /// CONT_NOEU of the step.
    cont: NodalField,
    /// A DEPL field (DX, DY, DZ absent) extended with the multipliers.
    depl: NodalField,
}

/// The load direction: the block's diagonal.
fn load_dir() -> [f64; 3] {
    let r = 0.5f64.sqrt();
    [r, r, 0.0]
}

/// Applies P on TOP, then the tractions `ramp` along the diagonal on SZZ,
/// one step each; `formulation` is the DEFI_CONTACT text of the zone.
fn run(contact_text: &str, friction: bool, ramp: &[f64]) -> Vec<StepOut> {
    run_on(block_mesh(), contact_text, friction, ramp)
}

/// The block with its slave face made of TRIA3: each bottom QUAD4 split
/// along its (0,0)-(1,1) diagonal direction.
fn block_mesh_tria3() -> Mesh {
    let mut mesh = block_mesh();
    let mut szz = Vec::new();
    for &c in &mesh.cell_groups["SZZ"].clone() {
        let n = mesh.cells[c].nodes.clone();
        // The quad's corner nearest the origin and its opposite.
        let key = |k: usize| mesh.coords[n[k]][0] + mesh.coords[n[k]][1];
        let a = (0..4).min_by(|&i, &j| key(i).total_cmp(&key(j))).unwrap();
        let (b, c2, d) = ((a + 1) % 4, (a + 2) % 4, (a + 3) % 4);
        for tri in [[n[a], n[b], n[c2]], [n[a], n[c2], n[d]]] {
            szz.push(mesh.cells.len());
            mesh.cells.push(Cell {
                kind: CellType::Tria3,
                nodes: tri.to_vec(),
            });
        }
    }
    mesh.cell_groups.insert("SZZ".into(), szz);
    orie_peau(&mut mesh, OrieDim::D3, &["SZZ"], None).unwrap();
    mesh
}

fn run_on(mesh: Mesh, contact_text: &str, friction: bool, ramp: &[f64]) -> Vec<StepOut> {
    let vol = mesh.cell_groups["VOL"].clone();
    let mo = model(&mesh, "3D", &vol);
    let def = ContactDef::from_args(&args_of(contact_text, "DEFI_CONTACT", 0), &mesh)
        .unwrap_or_else(|d| panic!("{}", d.render(None)));
    let mut materials = indexmap::IndexMap::new();
    materials.insert("MAT".to_string(), material(E, 0.0, 1e-20, None));
    let top_nodes: Vec<usize> = {
        let mut v: Vec<usize> = mesh.cell_groups["TOP"]
            .iter()
            .flat_map(|&c| mesh.cells[c].nodes.clone())
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let mut held = imposed(&top_nodes, Dof::Dx, 0.0);
    held.extend(imposed(&top_nodes, Dof::Dy, 0.0));
    let (asm, _) = discretize(
        &mesh,
        &mo,
        &MaterialField {
            mesh: "MAIL".into(),
            cell_material: vec![Some("MAT".into()); mesh.ncells()],
        },
        &materials,
        &[Occurrence {
            cells: None,
            relation: "ELAS".into(),
            deformation: "PETIT".into(),
            controls: Default::default(),
        }],
        &[&MechLoad {
            model: "MO".into(),
            imposed: held,
            gravity: None,
            nodal_forces: Vec::new(),
            pressures: Vec::new(),
            distributed: Vec::new(),
            functions: Vec::new(),
            fields: Vec::new(),
        }],
    )
    .unwrap();
    let state = initial_state(&asm, 0.0, None, None, None);
    let nfull = asm.numbering.nfull();
    let conv = ConvergenceSettings {
        resi_glob_rela: Some(1e-13),
        resi_glob_maxi: None,
        iter_glob_maxi: 100,
        arret: true,
        ..ConvergenceSettings::default()
    };
    let mut engine = Engine::new(
        asm,
        Scheme::newmark(0.25, 0.5).unwrap(),
        NewtonSettings::default(),
        conv,
        state,
    );
    // Along z the block is held by the contact and its negligible density
    // only: before the contact acts, the matrix loses ~15 decimals in that
    // rigid mode, where code_aster's solvers stop (SOLVEUR NPREC); this
    // quasi-static construction turns the test off, as NPREC < 0 does.
    engine.lu.check.limit = None;
    engine.initialize(true).unwrap();
    let u0 = vec![0.0; nfull];
    let mut contact =
        DiscreteContact::build(def, &mesh, &engine.asm.numbering, &u0, false).unwrap();
    let mut out = Vec::new();
    let loads: Vec<f64> = std::iter::once(0.0).chain(ramp.iter().copied()).collect();
    for (k, &q) in loads.iter().enumerate() {
        let mut f = vec![0.0; nfull];
        traction(&mesh, "TOP", [0.0, 0.0, -P], &mut f);
        let d = load_dir();
        traction(&mesh, "SZZ", [q * d[0], q * d[1], 0.0], &mut f);
        engine.fext = f;
        let rep = engine
            .solve_step(1.0, Some(&mut contact), &mut |_, _| {})
            .unwrap_or_else(|e| panic!("load step {k} (q = {q}): {e}"));
        engine.commit();
        contact.commit(1.0);
        let mut pts = Vec::new();
        let links = &contact.committed.links;
        match &contact.continuous {
            Some(cc) => {
                let stride = if friction { 3 } else { 1 };
                for (i, p) in cc.points.iter().enumerate() {
                    let l = links
                        .iter()
                        .find(|l| l.slave == p.node)
                        .expect("every slave node paired");
                    let lf = if friction {
                        [
                            cc.committed_lam[i * stride + 1],
                            cc.committed_lam[i * stride + 2],
                        ]
                    } else {
                        [0.0; 2]
                    };
                    pts.push((p.node, cc.committed_lam[i * stride], lf, *l));
                }
            }
            None => {
                for l in links {
                    pts.push((l.slave, f64::NAN, [f64::NAN; 2], *l));
                }
            }
        }
        let mut depl =
            NodalField::absent(vec!["DX".into(), "DY".into(), "DZ".into()], mesh.nnodes());
        contact.extend_depl(&mut depl);
        out.push(StepOut {
            q,
            cont: contact.cont_noeu(),
            depl,
            points: pts,
            residuals: rep.history.iter().map(|h| h.resi_maxi).collect(),
        });
    }
    out
}

fn continue_text(coef_cont: f64, friction: bool) -> String {
    continue_text_with(coef_cont, friction, "")
}

fn continue_text_with(coef_cont: f64, friction: bool, extra: &str) -> String {
    let (frot, coulomb) = if friction {
        ("FROTTEMENT='COULOMB', ", format!(", COULOMB={MU}"))
    } else {
        ("", String::new())
    };
    format!(
        "CONT = DEFI_CONTACT(MODELE=MO, FORMULATION='CONTINUE', {frot}
    ALGO_RESO_CONT='NEWTON', ALGO_RESO_GEOM='NEWTON', {extra}
    ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ', COEF_CONT={coef_cont:e}{coulomb}))"
    )
}

/// LAGS_C = -p at every slave node to 1e-10, gap 0 to 1e-10, whatever
/// COEF_CONT (no penalty); the contact force of each node is its share
/// p A_node of the load (corner 1/4, edge 1/2, centre 1).
#[test]
fn pressed_block_3d_lags_c_is_minus_the_pressure() {
    let mut by_coef = Vec::new();
    for coef in [100.0, 1e4] {
        let steps = run(&continue_text(coef, false), false, &[]);
        let s = &steps[0];
        assert_eq!(s.points.len(), 9, "{s:?}");
        let mut worst: (f64, f64) = (0.0, 0.0);
        for (node, lc, _, l) in &s.points {
            let err = (lc + P).abs() / P;
            assert!(err <= 1e-10, "COEF_CONT {coef}: node {node} LAGS_C {lc:e}");
            assert!(l.gap.abs() <= 1e-10, "node {node} gap {:e}", l.gap);
            // Nodal area: 1/4 per adjacent unit face.
            let x = [node % 3, (node / 3) % 3];
            let share = x
                .iter()
                .map(|&i| if i == 1 { 1.0 } else { 0.5 })
                .product::<f64>();
            let rz = l.reaction()[2];
            assert!((rz - P * share).abs() <= 1e-10, "node {node} RZ {rz:e}");
            worst = (worst.0.max(err), worst.1.max(l.gap.abs()));
        }
        eprintln!(
            "3D COEF_CONT {coef:e}: max |LAGS_C + p|/p {:.2e}, max |gap| {:.2e} mm, residuals {:?}",
            worst.0, worst.1, s.residuals
        );
        by_coef.push(s.points.iter().map(|p| p.1).collect::<Vec<f64>>());
    }
    for (a, b) in by_coef[0].iter().zip(&by_coef[1]) {
        assert!((a - b).abs() <= 1e-12 * P, "{a:e} vs {b:e}");
    }
}

/// The load direction in the tangent basis of a link.
fn in_tangents(l: &LinkState, v: [f64; 3]) -> [f64; 2] {
    let d = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    [d(l.tangents[0], v), d(l.tangents[1], v)]
}

/// |(LAGS_F1, LAGS_F2)| = q/(mu p) < 1 along the load while q < mu p
/// (stick, no slip), = 1 along each node's slip from the first load step
/// above mu p; the total friction force is along the load.
#[test]
fn friction_3d_semi_multiplier_goes_from_stick_to_slip_at_coulomb_times_the_load() {
    let ramp: Vec<f64> = (1..=11).map(|k| 0.03 * k as f64).collect();
    let steps = run(&continue_text(100.0, true), true, &ramp);
    let mut first_slip = None;
    let d = load_dir();
    for s in &steps {
        eprintln!(
            "q = {:.2}: (LAGS_F1, LAGS_F2) {:?}, LAGS_C {:?}, residuals {:?}",
            s.q,
            s.points.iter().map(|p| p.2).collect::<Vec<_>>(),
            s.points.iter().map(|p| p.1).collect::<Vec<_>>(),
            s.residuals
        );
        assert_eq!(s.points.len(), 9);
        for (node, lc, _, l) in &s.points {
            assert!(
                l.gap.abs() <= 1e-10,
                "q {}: node {node} gap {:e}",
                s.q,
                l.gap
            );
            assert!(*lc < 0.0, "q {}: node {node} LAGS_C {lc:e}", s.q);
        }
        if s.q < MU * P {
            for (node, lc, lf, l) in &s.points {
                // code_aster's tangents from the normal −e_z (`mmmron`),
                // whatever the turn of the master cell.
                let expect = [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]];
                for k in 0..2 {
                    for i in 0..3 {
                        assert!(
                            (l.tangents[k][i] - expect[k][i]).abs() <= 1e-15,
                            "{:?}",
                            l.tangents
                        );
                    }
                }
                let e = in_tangents(l, d);
                // Oblique: both tangents carry a part of the load.
                assert!(e[0].abs() > 0.2 && e[1].abs() > 0.2, "{e:?}");
                for k in 0..2 {
                    let expected = s.q / (MU * P) * e[k];
                    assert!(
                        (lf[k] - expected).abs() <= 1e-10,
                        "stick at q {}: node {node} LAGS_F{} {:e}, expected {expected:e}",
                        s.q,
                        k + 1,
                        lf[k]
                    );
                    assert!(l.slip[k].abs() <= 1e-12, "node {node} slip {:?}", l.slip);
                }
                assert!(lf[0].hypot(lf[1]) < 1.0);
                assert!((lc + P).abs() <= 1e-10 * P, "node {node} LAGS_C {lc:e}");
            }
        } else {
            first_slip.get_or_insert(s.q);
            let mut total = [0.0; 3];
            for (node, _, lf, l) in &s.points {
                let norm = lf[0].hypot(lf[1]);
                assert!(
                    (norm - 1.0).abs() <= 1e-8,
                    "slip at q {}: node {node} |LAGS_F| {norm:e}",
                    s.q
                );
                let g = l.slip;
                let gn = g[0].hypot(g[1]);
                assert!(gn > 1e-9, "slip at q {}: node {node} slip {g:?}", s.q);
                // Coulomb's direction: Λ along the slip.
                let cross = (lf[0] * g[1] - lf[1] * g[0]) / gn;
                assert!(
                    cross.abs() <= 1e-8 && lf[0] * g[0] + lf[1] * g[1] > 0.0,
                    "node {node}: {lf:?} vs slip {g:?}"
                );
                let fr = l.friction_force();
                for i in 0..3 {
                    total[i] += fr[i];
                }
                // Nodes on the diagonal (the symmetry plane): along the load.
                if [0, 4, 8].contains(node) {
                    let e = in_tangents(l, d);
                    assert!(
                        (lf[0] * e[1] - lf[1] * e[0]).abs() <= 1e-8,
                        "node {node}: {lf:?} vs {e:?}"
                    );
                }
            }
            // The total friction force on the block opposes the load.
            let tn = total[0].hypot(total[1]);
            assert!(
                (total[0] * d[1] - total[1] * d[0]).abs() <= 1e-10 * tn,
                "{total:?}"
            );
            assert!(total[0] * d[0] + total[1] * d[1] < 0.0);
        }
    }
    let q = first_slip.expect("the ramp passes mu p");
    assert!(q > MU * P && q - 0.03 < MU * P, "slip from q = {q}");
}

/// The generalised Newton converges quadratically on a 3D step with
/// friction that takes every node from stick (or the pressed state) to
/// slip along a direction oblique to the tangents. Measured (RESI_GLOB_MAXI,
/// N): q 0.15 -> 0.3: 3.5e-2, 2.2e-6, 1.6e-8, 1.3e-15; 0 -> 0.5: 1.8e-1,
/// 1.4e-5, 1.9e-7, 1.1e-13, 2e-16. The second iteration is slower (the
/// friction rows' λ-derivative is left out, src/contact/continuous3d.rs),
/// then the residual squares: the last residual that follows one above
/// the round-off floor (1e-12 N) is at most C = 10 /N times its square; a
/// linear rate at the step's earlier ratio (1e-2) would leave ~1e-9 N.
#[test]
fn friction_3d_slip_step_converges_quadratically() {
    for ramp in [vec![0.15, 0.3], vec![0.5], vec![0.2, 0.6]] {
        let steps = run(&continue_text(100.0, true), true, &ramp);
        let r = &steps.last().unwrap().residuals;
        eprintln!("{ramp:?}: slip step residuals {r:?}");
        assert!(r.len() <= 6, "{r:?}");
        assert!(*r.last().unwrap() <= 1e-14, "{r:?}");
        let pairs: Vec<(f64, f64)> = r
            .windows(2)
            .map(|w| (w[0], w[1]))
            .filter(|&(a, _)| a > 1e-12)
            .collect();
        let &(a, b) = pairs.last().expect("at least one pair above the floor");
        assert!(a < 1e-6 && b <= 10.0 * a * a, "{a:e} -> {b:e} in {r:?}");
        // Every node slides at the end of the step.
        for (node, _, lf, _) in &steps.last().unwrap().points {
            assert!(
                (lf[0].hypot(lf[1]) - 1.0).abs() <= 1e-8,
                "node {node} {lf:?}"
            );
        }
    }
}

/// The friction fixed point (ALGO_RESO_FROT='POINT_FIXE') in 3D reaches
/// the generalised Newton's answer, stick and slip, to the tolerance of
/// its criterion (RESI_FROT = 1e-10).
#[test]
fn friction_3d_fixed_point_reaches_the_newton_answer() {
    let ramp = [0.15, 0.3, 0.33];
    let newton = run(&continue_text(100.0, true), true, &ramp);
    let pf = run(
        &continue_text_with(
            100.0,
            true,
            "ALGO_RESO_FROT='POINT_FIXE', RESI_FROT=1.E-10, ITER_FROT_MAXI=30,",
        ),
        true,
        &ramp,
    );
    for (a, b) in pf.iter().zip(&newton) {
        eprintln!(
            "q {}: NEWTON {} iterations, POINT_FIXE {}",
            a.q,
            b.residuals.len(),
            a.residuals.len()
        );
        for (p, q) in a.points.iter().zip(&b.points) {
            assert_eq!(p.0, q.0);
            assert!(
                (p.1 - q.1).abs() <= 1e-8,
                "q {}: LAGS_C {} {}",
                a.q,
                p.1,
                q.1
            );
            for k in 0..2 {
                assert!(
                    (p.2[k] - q.2[k]).abs() <= 1e-8,
                    "q {}: LAGS_F {:?} {:?}",
                    a.q,
                    p.2,
                    q.2
                );
            }
        }
    }
}
fn discrete_text(e_n: f64) -> String {
    format!(
        "CONT = DEFI_CONTACT(MODELE=MO, FORMULATION='DISCRETE', FROTTEMENT='COULOMB',
    ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ', ALGO_CONT='PENALISATION', E_N={e_n:e},
            ALGO_FROT='PENALISATION', E_T={e_n:e}, COULOMB={MU}))"
    )
}

/// The 3D discrete penalised method (E_N = E_T) tends to the continuous
/// one as the penalty grows, at the first order of a penalty (the
/// interpenetration and the stick slip are force / E_N), on the pressed
/// state, in stick (q = 0.15) and in slip (q = 0.33, non-uniform
/// pressure): the largest difference of a nodal reaction (RX, RY, RZ)
/// over the largest reaction is divided by 10 when E_N is multiplied by
/// 10. Measured: 3.05e-3, 3.07e-4, 3.07e-5 (pressed and stick),
/// 2.31e-3, 2.32e-4, 2.32e-5 (slip) for E_N = 1e5, 1e6, 1e7 N/mm; the
/// discrete slip step takes 38 to 54 iterations, the continuous one 4.
#[test]
fn continuous_and_discrete_3d_agree_on_reactions() {
    let ramp = [0.15, 0.33];
    let cont = run(&continue_text(100.0, true), true, &ramp);
    let mut errs: Vec<Vec<f64>> = Vec::new();
    for e_n in [1e5, 1e6, 1e7] {
        let disc = run(&discrete_text(e_n), true, &ramp);
        let mut row = Vec::new();
        for (c, d) in cont.iter().zip(&disc) {
            assert_eq!(c.points.len(), d.points.len());
            let mut err: f64 = 0.0;
            let mut big: f64 = 0.0;
            for (node, _, _, lc) in &c.points {
                let ld = &d.points.iter().find(|p| p.0 == *node).unwrap().3;
                let (rc, rd) = (lc.reaction(), ld.reaction());
                for i in 0..3 {
                    err = err.max((rc[i] - rd[i]).abs());
                    big = big.max(rc[i].abs());
                }
            }
            eprintln!(
                "E_N {e_n:e} q {}: max |R_disc - R_cont| / max |R| = {:.3e} ({} iterations, continuous {})",
                c.q,
                err / big,
                d.residuals.len(),
                c.residuals.len()
            );
            row.push(err / big);
        }
        errs.push(row);
    }
    for s in 0..errs[0].len() {
        assert!(errs[2][s] <= 1e-4, "{errs:?}");
        for k in 0..2 {
            let ratio = errs[k][s] / errs[k + 1][s];
            assert!((9.0..=11.0).contains(&ratio), "{errs:?}");
        }
    }
}

/// DEPL holds LAGS_C, LAGS_F1 and LAGS_F2 at the slave nodes (absent
/// elsewhere); CONT_NOEU has the discrete method's components, the force
/// vectors printed as code_aster prints them (minus the force on the slave
/// node, docs/contact.md §4): in stick CONT = 1, JEU = 0, RZ = -p A_node
/// (into the foundation), (RTAX, RTAY) = (q A_node) along the load (the
/// friction force on the node is against it), R the norm; in slip
/// CONT = 2.
#[test]
fn depl_and_cont_noeu_3d() {
    let steps = run(&continue_text(100.0, true), true, &[0.15, 0.33]);
    let d = load_dir();
    for s in &steps[1..] {
        for (node, lc, lf, _) in &s.points {
            let get = |f: &NodalField, c: &str| {
                f.get(*node, c).unwrap_or_else(|| panic!("{c} at {node}"))
            };
            assert_eq!(get(&s.depl, "LAGS_C"), *lc);
            assert_eq!(get(&s.depl, "LAGS_F1"), lf[0]);
            assert_eq!(get(&s.depl, "LAGS_F2"), lf[1]);
            let c = &s.cont;
            assert!(get(c, "JEU").abs() <= 1e-12);
            let x = [node % 3, (node / 3) % 3];
            let share = x
                .iter()
                .map(|&i| if i == 1 { 1.0 } else { 0.5 })
                .product::<f64>();
            if s.q < MU * P {
                assert_eq!(get(c, "CONT"), 1.0);
                assert!((get(c, "RZ") + P * share).abs() <= 1e-10);
                for (k, cmp) in ["RTAX", "RTAY"].iter().enumerate() {
                    assert!(
                        (get(c, cmp) - s.q * share * d[k]).abs() <= 1e-10,
                        "{cmp} at {node}"
                    );
                }
                let r = (P * P + s.q * s.q).sqrt() * share;
                assert!((get(c, "R") - r).abs() <= 1e-10);
            } else {
                assert_eq!(get(c, "CONT"), 2.0);
            }
        }
        // Not a slave node: no multiplier.
        assert_eq!(s.depl.get(9, "LAGS_C"), None);
    }
}

/// A 3D landing in CONTINUE: the block (lifted by G0, elastic, free) flies
/// obliquely at (VX, VY, VZ) onto the turned plane and bounces, with
/// Coulomb friction. The time integral of the CONT_NOEU reactions
/// (RX, RY, RZ summed over the slave nodes, with the weights of Newmark's
/// velocity update) equals minus the change of the block's momentum Σ M v
/// (CONT_NOEU prints minus the forces on the slave nodes, as code_aster),
/// computed from the consistent mass and the velocities only: no load and
/// no imposed dof act on the block, and its internal forces sum to zero.
///
/// Measured (momentum, N s): p0 = (4e-4, 2e-4, -2e-3), the impulse equals
/// the change to 4e-11 of the normal change (2e-11 for the discrete). The block leaves the plane at 3.2e-5 s
/// with p = (-1.6e-4, -1.8e-4, 2.51e-3): its centre of mass rebounds
/// faster than it came (1255 against 1000 mm/s), an energy gain (total
/// 2.52 against 1.05 mJ; the discrete method: 0.99). It is the normal
/// constraint's, not friction's: the end-of-step friction power is <= 0
/// at every node and step (asserted here), and frictionless with a 4
/// times shorter step the total reaches 4.93 (TRAV_LIAI -3.88): an exact
/// impact constraint under Newmark's trapezoidal rule, which the 2D
/// landing study shows as well (docs/contact.md §10, 3D). This test
/// judges the forces, not the energy.
#[test]
fn landing_3d_contact_impulse_equals_the_momentum_change() {
    landing(
        &format!(
            "FORMULATION='CONTINUE', FROTTEMENT='COULOMB',
    ALGO_RESO_CONT='NEWTON', ALGO_RESO_FROT='NEWTON', ALGO_RESO_GEOM='NEWTON',
    ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ', COULOMB={MU})"
        ),
        true,
    );
}

/// The same landing with the 3D discrete method (E_N = E_T = 1e5): the
/// identity holds for it too.
#[test]
fn landing_3d_discrete_contact_impulse_equals_the_momentum_change() {
    landing(
        &format!(
            "FORMULATION='DISCRETE', FROTTEMENT='COULOMB',
    ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ', ALGO_CONT='PENALISATION', E_N=1e5,
            ALGO_FROT='PENALISATION', E_T=1e5, COULOMB={MU})"
        ),
        false,
    );
}

/// `continuous`: also check the friction power at every node and step.
fn landing(contact: &str, continuous: bool) {
    use aster::concepts::{ConceptData, ConceptType};
    const G0: f64 = 1.5e-3;
    const VEL: [f64; 3] = [200.0, 100.0, -1000.0];
    const GAMMA: f64 = 0.5;
    let mut mesh = block_mesh();
    for n in 0..18 {
        mesh.coords[n][2] += G0;
    }
    let vol = mesh.cell_groups["VOL"].clone();
    let slaves: Vec<usize> = (0..9).collect();
    let mo = model(&mesh, "3D", &vol);
    let t: Vec<f64> = (0..=60).map(|k| k as f64 * 1e-6).collect();
    let mat = material(E, 0.3, 1e-6, None);
    let mut st = study(mesh.clone(), mo.clone(), mat.clone(), vec![], None, t, None);
    // The initial velocity as F builds it: CREA_CHAMP AFFE with the
    // contact unknowns on the slave face (LAGS_F2 in 3D), ignored. (The
    // preamble has a CREA_CHAMP: this one is the second.)
    let crea = format!(
        "V0 = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='AFFE', MODELE=MO,
    AFFE=(_F(GROUP_MA='VOL', NOM_CMP=('DX', 'DY', 'DZ'), VALE=({:e}, {:e}, {:e})),
          _F(GROUP_MA='SZZ', NOM_CMP=('LAGS_C', 'LAGS_F1', 'LAGS_F2'), VALE=(0., 0., 0.))))",
        VEL[0], VEL[1], VEL[2]
    );
    exec(
        &mut st,
        "CREA_CHAMP",
        &args_of(&crea, "CREA_CHAMP", 1),
        "V0",
    )
    .unwrap();
    // exec files every result as an EVOL_NOLI: file the field as a CHAM_NO.
    let ConceptData::Field(f) = st.concepts.get("V0").unwrap().data.clone() else {
        panic!("CREA_CHAMP gives a field")
    };
    assert_eq!(
        f.field.components,
        ["DX", "DY", "DZ", "LAGS_C", "LAGS_F1", "LAGS_F2"]
    );
    insert(&mut st, "V0", ConceptType::ChamNo, ConceptData::Field(f));
    let text = format!(
        "CONT = DEFI_CONTACT(MODELE=MO, {contact})
RESU = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOQ), CONTACT=CONT,
    COMPORTEMENT=_F(RELATION='ELAS', TOUT='OUI'),
    ETAT_INIT=_F(VITE=V0),
    INCREMENT=_F(LIST_INST=L_INST),
    SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', BETA=0.25, GAMMA={GAMMA}, FORMULATION='DEPLACEMENT'),
    NEWTON=_F(MATRICE='TANGENTE', REAC_ITER=1),
    CONVERGENCE=_F(RESI_GLOB_RELA=1.E-10, ITER_GLOB_MAXI=50))"
    );
    insert(
        &mut st,
        "CONT",
        ConceptType::CharContact,
        ConceptData::Contact(Box::new(args_of(&text, "DEFI_CONTACT", 0))),
    );
    exec(
        &mut st,
        "DYNA_NON_LINE",
        &args_of(&text, "DYNA_NON_LINE", 0),
        "RESU",
    )
    .unwrap();
    let result = result(&st, "RESU").clone();
    let mut materials = indexmap::IndexMap::new();
    materials.insert("MAT".to_string(), mat);
    let (asm, _) = discretize(
        &mesh,
        &mo,
        &MaterialField {
            mesh: "MAIL".into(),
            cell_material: vec![Some("MAT".into()); mesh.ncells()],
        },
        &materials,
        &[Occurrence {
            cells: None,
            relation: "ELAS".into(),
            deformation: "PETIT".into(),
            controls: Default::default(),
        }],
        &[&MechLoad {
            model: "MO".into(),
            imposed: vec![],
            gravity: None,
            nodal_forces: Vec::new(),
            pressures: Vec::new(),
            distributed: Vec::new(),
            functions: Vec::new(),
            fields: Vec::new(),
        }],
    )
    .unwrap();
    let n = mesh.nnodes();
    let momentum = |s: usize| {
        let vite = &result.steps[s].nodal["VITE"];
        let mut v = vec![0.0; 3 * n];
        for node in 0..n {
            for (c, name) in ["DX", "DY", "DZ"].iter().enumerate() {
                v[3 * node + c] = vite.get(node, name).filter(|x| !x.is_nan()).unwrap_or(0.0);
            }
        }
        let mut mv = vec![0.0; 3 * n];
        asm.mass_full.mul_vec(&v, &mut mv);
        let mut p = [0.0; 3];
        for i in 0..n {
            for c in 0..3 {
                p[c] += mv[3 * i + c];
            }
        }
        p
    };
    let total = |s: usize, cmp: &str| -> f64 {
        slaves
            .iter()
            .map(|&node| result.steps[s].nodal["CONT_NOEU"].get(node, cmp).unwrap())
            .sum()
    };
    let last = result.steps.len() - 1;
    assert!((result.steps[last].inst - 6e-5).abs() < 1e-15);
    if continuous {
        let depl = &result.steps[last].nodal["DEPL"];
        for cmp in ["LAGS_C", "LAGS_F1", "LAGS_F2"] {
            assert!(slaves.iter().all(|&n| depl.get(n, cmp).is_some()), "{cmp}");
            assert_eq!(depl.get(9, cmp), None, "{cmp} off the slave face");
        }
    }
    // Coulomb: the friction force at the end of a step does no positive
    // work on the step's slip, at every node (CONTINUE's tangents are
    // e_y, -e_x here: the slip is (-GLIY, GLIX, 0)); the force on the node
    // is minus the printed RT*.
    if continuous {
        let mut slipping = 0;
        for s in 1..=last {
            let c = &result.steps[s].nodal["CONT_NOEU"];
            for &node in &slaves {
                let g = |cmp: &str| c.get(node, cmp).unwrap();
                let f = [
                    -(g("RTAX") + g("RTGX")),
                    -(g("RTAY") + g("RTGY")),
                    -(g("RTAZ") + g("RTGZ")),
                ];
                let slip = [-g("GLIY"), g("GLIX"), 0.0];
                let power = f[0] * slip[0] + f[1] * slip[1] + f[2] * slip[2];
                let scale = f[0].hypot(f[1]) * slip[0].hypot(slip[1]);
                assert!(
                    power <= 1e-10 * scale,
                    "step {s} node {node}: friction power {power:e}"
                );
                if power < -1e-3 * scale {
                    slipping += 1;
                }
            }
        }
        assert!(slipping > 0, "no sliding node: the check saw nothing");
    }
    let mut impulse = [0.0; 3];
    let mut peak: f64 = 0.0;
    let mut first_contact = None;
    for s in 1..=last {
        let dt = result.steps[s].inst - result.steps[s - 1].inst;
        for (c, cmp) in ["RX", "RY", "RZ"].iter().enumerate() {
            impulse[c] += dt * (GAMMA * total(s, cmp) + (1.0 - GAMMA) * total(s - 1, cmp));
        }
        let rn = total(s, "RN");
        if rn > 0.0 {
            first_contact.get_or_insert(result.steps[s].inst);
        }
        peak = peak.max(rn);
    }
    let (p0, p1) = (momentum(0), momentum(last));
    let dp = [p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]];
    eprintln!(
        "3D landing: p0 {p0:?}, p1 {p1:?}, dp {dp:?}, impulse {impulse:?}, peak Σ RN {peak:.4e} N, first contact at {first_contact:?}"
    );
    // Free flight over G0 first (1.5 steps at 1000 mm/s), then the plane
    // pushes the block up: the normal momentum changes by a good part.
    assert!(
        first_contact.is_some_and(|t| t > 1.5e-6),
        "{first_contact:?}"
    );
    assert!(dp[2] > 0.5 * p0[2].abs(), "dp {dp:?} of p0 {p0:?}");
    for c in 0..3 {
        let rel = (impulse[c] + dp[c]).abs() / dp[2].abs();
        assert!(
            rel < 1e-8,
            "component {c}: impulse {} vs minus the momentum change {}",
            impulse[c],
            dp[c]
        );
    }
    // Friction took some of the tangential momentum, within Coulomb's bound.
    let dt_norm = dp[0].hypot(dp[1]);
    assert!(
        dt_norm > 0.0 && dt_norm <= MU * dp[2] * (1.0 + 1e-8),
        "{dp:?}"
    );
}

/// TRIA3 slave faces: the nodal weights are then A/3 per triangle, not
/// the quadrilateral's A/4, so LAGS_C is not uniform, but every node's
/// contact force ω LAGS_C is its share of the load (the HEXA8's bottom
/// reactions under the uniform stress -p: p A/4 per adjacent unit
/// square), with zero gap.
#[test]
fn pressed_block_3d_on_tria3_slave_faces() {
    let mesh = block_mesh_tria3();
    let steps = run_on(mesh, &continue_text(100.0, false), false, &[]);
    let s = &steps[0];
    assert_eq!(s.points.len(), 9);
    let mut lcs = Vec::new();
    for (node, lc, _, l) in &s.points {
        assert!(l.gap.abs() <= 1e-10, "node {node} gap {:e}", l.gap);
        let x = [node % 3, (node / 3) % 3];
        let share = x
            .iter()
            .map(|&i| if i == 1 { 1.0 } else { 0.5 })
            .product::<f64>();
        let rz = l.reaction()[2];
        assert!((rz - P * share).abs() <= 1e-10, "node {node} RZ {rz:e}");
        assert!(*lc < 0.0);
        lcs.push(*lc);
    }
    eprintln!("TRIA3 slave faces: LAGS_C {lcs:?}");
    // Not uniform: the triangle weights differ from the quad shares.
    let (lo, hi) = lcs
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
    assert!(hi - lo > 0.1 * P);
}
