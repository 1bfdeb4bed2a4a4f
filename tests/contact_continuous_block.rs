//! Continuous contact (FORMULATION='CONTINUE') of an elastic block pressed
//! on a rigid plane, solved statically (the engine driven step by step
//! with a negligible density, so that Newmark's inertia is ~1e-20 of the
//! loads) under loads applied as consistent nodal forces.
//!
//! The block is an axisymmetric ring (AXIS, r in [1, 3], y in [0, 2],
//! 2 x 2 QUAD8, NU = 0) on the flat top face of a fixed foundation, the
//! slave face its bottom (two SEG3). A uniform pressure p on its top face
//! gives the uniform uniaxial stress sigma_yy = -p, which QUAD8 represent
//! exactly, so the contact pressure is exactly p at every slave node:
//! LAGS_C = -p to round-off, with zero gap (the augmented Lagrangian has
//! no penalty: the answer does not depend on COEF_CONT). The reference is
//! independent of the contact code: the pressure loads are integrated
//! here by Gauss quadrature; the contact weights are the code's nodal
//! rule.
//!
//! Friction (COULOMB mu): a uniform outward radial traction t on the
//! slave face itself is balanced node by node by the friction while the
//! block sticks, so the stress state is unchanged and the semi-multiplier
//! is |LAGS_F1| = t / (mu p) < 1, exactly; once t > mu p no stick
//! solution exists, every slave node slides (|LAGS_F1| = 1) and the ring
//! expands radially, held by its hoop stiffness (a static equilibrium
//! exists, so the quasi-static ramp stays meaningful).
#![allow(clippy::needless_range_loop)]

mod dynamics_support;

use aster::contact::ContactDef;
use aster::mesh::ops::{orie_peau, OrieDim};
use aster::mesh::{Cell, CellType, Mesh};
use aster::model::{MaterialField, MechLoad};
use aster::nonlinear::{
    discretize, initial_state, ConvergenceSettings, DiscreteContact, Engine, NewtonSettings,
    Occurrence,
};
use aster::time::Scheme;
use dynamics_support::*;

const P: f64 = 1.0;
const MU: f64 = 0.25;
const E: f64 = 1000.0;

/// The ring (cells 0..4, group VOL), its top face TOP, its bottom face
/// SZZ, and one foundation QUAD8 below y = 0 whose top edge is RIGID.
fn block_mesh() -> Mesh {
    let rs = [1.0, 1.5, 2.0, 2.5, 3.0];
    let ys = [0.0, 0.5, 1.0, 1.5, 2.0];
    let mut coords = Vec::new();
    let mut id = [[usize::MAX; 5]; 5];
    for (i, &r) in rs.iter().enumerate() {
        for (j, &y) in ys.iter().enumerate() {
            if i % 2 == 1 && j % 2 == 1 {
                continue; // serendipity: no centre node
            }
            id[i][j] = coords.len();
            coords.push([r, y, 0.0]);
        }
    }
    let mut cells = Vec::new();
    for ci in 0..2 {
        for cj in 0..2 {
            let (i, j) = (2 * ci, 2 * cj);
            cells.push(Cell {
                kind: CellType::Quad8,
                nodes: vec![
                    id[i][j],
                    id[i + 2][j],
                    id[i + 2][j + 2],
                    id[i][j + 2],
                    id[i + 1][j],
                    id[i + 2][j + 1],
                    id[i + 1][j + 2],
                    id[i][j + 1],
                ],
            });
        }
    }
    // Faces (SEG3: ends, then middle).
    let mut szz = Vec::new();
    let mut top = Vec::new();
    for ci in 0..2 {
        let i = 2 * ci;
        szz.push(cells.len());
        cells.push(Cell {
            kind: CellType::Seg3,
            nodes: vec![id[i][0], id[i + 2][0], id[i + 1][0]],
        });
        top.push(cells.len());
        cells.push(Cell {
            kind: CellType::Seg3,
            nodes: vec![id[i][4], id[i + 2][4], id[i + 1][4]],
        });
    }
    // Foundation r in [0, 4], y in [-1, 0]; its own nodes.
    let f0 = coords.len();
    for p in [
        [0.0, -1.0],
        [4.0, -1.0],
        [4.0, 0.0],
        [0.0, 0.0],
        [2.0, -1.0],
        [4.0, -0.5],
        [2.0, 0.0],
        [0.0, -0.5],
    ] {
        coords.push([p[0], p[1], 0.0]);
    }
    let found = cells.len();
    cells.push(Cell {
        kind: CellType::Quad8,
        nodes: (f0..f0 + 8).collect(),
    });
    let rigid = cells.len();
    cells.push(Cell {
        kind: CellType::Seg3,
        nodes: vec![f0 + 3, f0 + 2, f0 + 6],
    });
    let mut mesh = Mesh {
        name: "MAIL".into(),
        dim: 2,
        coords,
        cells,
        ..Default::default()
    };
    mesh.cell_groups.insert("VOL".into(), vec![0, 1, 2, 3]);
    mesh.cell_groups.insert("SZZ".into(), szz);
    mesh.cell_groups.insert("TOP".into(), top);
    mesh.cell_groups.insert("VOL_RIG".into(), vec![found]);
    mesh.cell_groups.insert("RIGID".into(), vec![rigid]);
    orie_peau(&mut mesh, OrieDim::D2, &["SZZ", "RIGID"], None).unwrap();
    mesh
}

/// Consistent nodal forces (per radian) of a uniform traction `t` (force
/// per area, a vector in (r, y)) on the SEG3 cells of `group`, integrated
/// by 3-point Gauss (exact: N_i r is cubic), added to `f` (full, 2 dofs
/// per node).
fn traction(mesh: &Mesh, group: &str, t: [f64; 2], f: &mut [f64]) {
    let g = (0.6f64).sqrt();
    for &c in &mesh.cell_groups[group] {
        let n = &mesh.cells[c].nodes;
        let (a, b, m) = (mesh.coords[n[0]], mesh.coords[n[1]], mesh.coords[n[2]]);
        for (xi, w) in [(-g, 5.0 / 9.0), (0.0, 8.0 / 9.0), (g, 5.0 / 9.0)] {
            let shape = [0.5 * xi * (xi - 1.0), 0.5 * xi * (xi + 1.0), 1.0 - xi * xi];
            let dshape = [xi - 0.5, xi + 0.5, -2.0 * xi];
            let (mut r, mut tr, mut ty) = (0.0, 0.0, 0.0);
            for (k, x) in [a, b, m].iter().enumerate() {
                r += shape[k] * x[0];
                tr += dshape[k] * x[0];
                ty += dshape[k] * x[1];
            }
            let jac = (tr * tr + ty * ty).sqrt();
            for k in 0..3 {
                for d in 0..2 {
                    f[2 * n[k] + d] += t[d] * shape[k] * r * jac * w;
                }
            }
        }
    }
}

/// What one converged load step left at the slave nodes.
#[derive(Debug)]
struct StepOut {
    t_load: f64,
    /// Per slave node: (node, LAGS_C, LAGS_F1, gap, slip in the step).
    points: Vec<(usize, f64, f64, f64, f64)>,
    iterations: usize,
    /// Threshold updates of the friction fixed point (0 with NEWTON).
    friction_loops: usize,
}

/// Applies the pressure P on TOP, then the radial tractions `ramp` on
/// SZZ one step each (P kept), solving each step to equilibrium.
fn run(coef_cont: f64, friction: bool, ramp: &[f64]) -> Vec<StepOut> {
    let extra = if friction {
        "ALGO_RESO_FROT='NEWTON',"
    } else {
        ""
    };
    run_with(coef_cont, friction, ramp, extra).unwrap_or_else(|(k, e)| panic!("load step {k}: {e}"))
}

/// As [`run`] with `extra` keywords of DEFI_CONTACT; a failed step gives
/// its index and message.
fn run_with(
    coef_cont: f64,
    friction: bool,
    ramp: &[f64],
    extra: &str,
) -> Result<Vec<StepOut>, (usize, String)> {
    let mesh = block_mesh();
    let vol = mesh.cell_groups["VOL"].clone();
    let mo = model(&mesh, "AXIS", &vol);
    let frot = if friction {
        "FROTTEMENT='COULOMB', ".to_string()
    } else {
        String::new()
    };
    let coulomb = if friction {
        format!(", COULOMB={MU}")
    } else {
        String::new()
    };
    let text = format!(
        "CONT = DEFI_CONTACT(MODELE=MO, FORMULATION='CONTINUE', {frot}
    ALGO_RESO_CONT='NEWTON', ALGO_RESO_GEOM='NEWTON', {extra}
    ZONE=_F(GROUP_MA_MAIT='RIGID', GROUP_MA_ESCL='SZZ', COEF_CONT={coef_cont:e}{coulomb}))"
    );
    let def = ContactDef::from_args(&args_of(&text, "DEFI_CONTACT", 0), &mesh)
        .unwrap_or_else(|d| panic!("{}", d.render(None)));
    let mut materials = indexmap::IndexMap::new();
    // A negligible density: the inertia M a is ~1e-20 of the loads.
    materials.insert("MAT".to_string(), material(E, 0.0, 1e-20, None));
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
    let state = initial_state(&asm, 0.0, None, None, None);
    let nfull = asm.numbering.nfull();
    let conv = ConvergenceSettings {
        resi_glob_rela: Some(1e-13),
        resi_glob_maxi: None,
        iter_glob_maxi: 30,
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
    engine.initialize(true).unwrap();
    let u0 = vec![0.0; nfull];
    let mut contact = DiscreteContact::build(def, &mesh, &engine.asm.numbering, &u0, true).unwrap();
    let mut out = Vec::new();
    let loads: Vec<f64> = std::iter::once(0.0).chain(ramp.iter().copied()).collect();
    for (k, &t_load) in loads.iter().enumerate() {
        let mut f = vec![0.0; nfull];
        traction(&mesh, "TOP", [0.0, -P], &mut f);
        traction(&mesh, "SZZ", [t_load, 0.0], &mut f);
        engine.fext = f;
        let rep = engine
            .solve_step(1.0, Some(&mut contact), &mut |_, _| {})
            .map_err(|e| (k, e.to_string()))?;
        engine.commit();
        contact.commit(1.0);
        let cc = contact.continuous.as_ref().unwrap();
        let stride = if friction { 2 } else { 1 };
        let mut pts = Vec::new();
        for (i, p) in cc.points.iter().enumerate() {
            let link = cc
                .committed
                .links
                .iter()
                .find(|l| l.slave == p.node)
                .expect("every slave node paired");
            pts.push((
                p.node,
                cc.committed_lam[i * stride],
                if friction {
                    cc.committed_lam[i * stride + 1]
                } else {
                    0.0
                },
                link.gap,
                link.slip[0],
            ));
        }
        out.push(StepOut {
            t_load,
            points: pts,
            iterations: rep.iterations,
            friction_loops: cc.friction_loops,
        });
    }
    Ok(out)
}

/// LAGS_C = -p at every slave node to 1e-10 relative, gap 0 to 1e-10,
/// whatever COEF_CONT (no penalty).
#[test]
fn pressed_block_lags_c_is_minus_the_pressure() {
    let mut by_coef = Vec::new();
    for coef in [100.0, 1e4] {
        let steps = run(coef, false, &[]);
        let s = &steps[0];
        by_coef.push(s.points.iter().map(|p| p.1).collect::<Vec<f64>>());
        assert_eq!(s.points.len(), 5, "{s:?}");
        let mut worst: (f64, f64) = (0.0, 0.0);
        for &(node, lc, _, gap, _) in &s.points {
            let err = (lc + P).abs() / P;
            assert!(err <= 1e-10, "COEF_CONT {coef}: node {node} LAGS_C {lc:e}");
            assert!(
                gap.abs() <= 1e-10,
                "COEF_CONT {coef}: node {node} gap {gap:e}"
            );
            worst = (worst.0.max(err), worst.1.max(gap.abs()));
        }
        eprintln!(
            "COEF_CONT {coef:e}: max |LAGS_C + p|/p {:.2e}, max |gap| {:.2e} mm, {} Newton iterations",
            worst.0, worst.1, s.iterations
        );
    }
    // No penalty: the solution does not depend on COEF_CONT.
    for (a, b) in by_coef[0].iter().zip(&by_coef[1]) {
        assert!((a - b).abs() <= 1e-12 * P, "{a:e} vs {b:e}");
    }
}

/// |LAGS_F1| = t/(mu p) < 1 while t < mu p (stick, no slip), = 1 at every
/// slave node from the first load step above mu p (slip).
#[test]
fn friction_semi_multiplier_goes_from_stick_to_slip_at_coulomb_times_the_load() {
    // mu p = 0.25: steps of 0.03, the threshold between 0.24 and 0.27.
    let ramp: Vec<f64> = (1..=11).map(|k| 0.03 * k as f64).collect();
    let steps = run(100.0, true, &ramp);
    let mut first_slip = None;
    for s in &steps {
        let lf: Vec<f64> = s.points.iter().map(|p| p.2).collect();
        eprintln!(
            "t = {:.2}: LAGS_F1 {:?}, LAGS_C {:?}, slip {:?}, {} iterations",
            s.t_load,
            lf,
            s.points.iter().map(|p| p.1).collect::<Vec<_>>(),
            s.points.iter().map(|p| p.4).collect::<Vec<_>>(),
            s.iterations
        );
        for &(node, lc, _, gap, _) in &s.points {
            assert!(
                gap.abs() <= 1e-10,
                "t {}: node {node} gap {gap:e}",
                s.t_load
            );
            assert!(lc < 0.0, "t {}: node {node} LAGS_C {lc:e}", s.t_load);
        }
        if s.t_load < MU * P {
            for &(node, lc, l, _, slip) in &s.points {
                let expected = s.t_load / (MU * P);
                assert!(
                    (l.abs() - expected).abs() <= 1e-10,
                    "stick at t {}: node {node} LAGS_F1 {l:e}, expected {expected:e}",
                    s.t_load
                );
                assert!(l.abs() < 1.0);
                assert!((lc + P).abs() <= 1e-10 * P, "node {node} LAGS_C {lc:e}");
                assert!(
                    slip.abs() <= 1e-12,
                    "stick at t {}: node {node} slip {slip:e}",
                    s.t_load
                );
            }
        } else {
            first_slip.get_or_insert(s.t_load);
            for &(node, _, l, _, slip) in &s.points {
                assert!(
                    (l.abs() - 1.0).abs() <= 1e-8,
                    "slip at t {}: node {node} LAGS_F1 {l:e}",
                    s.t_load
                );
                assert!(
                    slip.abs() > 1e-9,
                    "slip at t {}: node {node} slip {slip:e}",
                    s.t_load
                );
            }
        }
    }
    // The slip starts at the first load above mu p: within one increment.
    let t = first_slip.expect("the ramp passes mu p");
    assert!(t > MU * P && t - 0.03 < MU * P, "slip from t = {t}");
}

/// The friction fixed point (ALGO_RESO_FROT='POINT_FIXE': the threshold
/// frozen during Newton, updated until LAGS_C moves by less than
/// RESI_FROT) reaches the generalised Newton's answer over the whole
/// stick -> slip ramp: LAGS_C, LAGS_F1 and the slip agree to the
/// tolerance of its criterion at every slave node and every step.
#[test]
fn friction_fixed_point_reaches_the_newton_answer() {
    let ramp: Vec<f64> = (1..=11).map(|k| 0.03 * k as f64).collect();
    let newton = run(100.0, true, &ramp);
    let pf = run_with(
        100.0,
        true,
        &ramp,
        "ALGO_RESO_FROT='POINT_FIXE', RESI_FROT=1.E-10, ITER_FROT_MAXI=30,",
    )
    .unwrap_or_else(|(k, e)| panic!("load step {k}: {e}"));
    let (mut it_n, mut it_p, mut loops) = (0, 0, 0);
    for (a, b) in pf.iter().zip(&newton) {
        it_n += b.iterations;
        it_p += a.iterations;
        loops += a.friction_loops;
        eprintln!(
            "t = {:.2}: NEWTON {} iterations, POINT_FIXE {} iterations in {} threshold updates",
            a.t_load, b.iterations, a.iterations, a.friction_loops
        );
        // Pressure on: at least two updates (the first compares with the
        // LAGS_C = 0 of the step start).
        assert!(a.friction_loops >= 2, "{a:?}");
        for (p, q) in a.points.iter().zip(&b.points) {
            assert_eq!(p.0, q.0);
            assert!(
                (p.1 - q.1).abs() <= 1e-8,
                "t {}: LAGS_C {p:?} {q:?}",
                a.t_load
            );
            assert!(
                (p.2 - q.2).abs() <= 1e-8,
                "t {}: LAGS_F1 {p:?} {q:?}",
                a.t_load
            );
            assert!(
                (p.3 - q.3).abs() <= 1e-12,
                "t {}: gap {p:?} {q:?}",
                a.t_load
            );
            assert!(
                (p.4 - q.4).abs() <= 1e-8 * q.4.abs().max(1e-6),
                "t {}: slip {p:?} {q:?}",
                a.t_load
            );
        }
    }
    eprintln!("total: NEWTON {it_n} iterations, POINT_FIXE {it_p} in {loops} threshold updates");
}

/// A slip step needs several threshold updates (the sliding face's
/// pressure depends on its friction); with ITER_FROT_MAXI = 2 the fixed
/// point stops there with a message naming the keyword, the criterion
/// and the node where LAGS_C still moves. The stick steps before it
/// (pressure independent of the friction) converge in 2 updates.
#[test]
fn friction_fixed_point_stops_at_iter_frot_maxi() {
    let ramp = [0.12, 0.3];
    let err = run_with(
        100.0,
        true,
        &ramp,
        "ALGO_RESO_FROT='POINT_FIXE', RESI_FROT=1.E-6, ITER_FROT_MAXI=2,",
    )
    .expect_err("the slip step cannot converge in 2 updates");
    eprintln!("{err:?}");
    assert_eq!(err.0, 2, "the slip step fails, not the stick ones");
    assert!(
        err.1.contains("ALGO_RESO_FROT='POINT_FIXE'")
            && err.1.contains("ITER_FROT_MAXI = 2")
            && err.1.contains("at node N")
            && err.1.contains("RESI_FROT"),
        "{}",
        err.1
    );
}
