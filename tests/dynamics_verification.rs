//! Verification of the DYNA_NON_LINE engine (no contact) against
//! independent references: exact kinematics, closed-form wave solutions,
//! energy balances, patch tests and the equivalence of cut and uncut
//! steps. docs/dynamics.md §6 lists the measured numbers.
#![allow(clippy::needless_range_loop)]

mod dynamics_support;

use aster::mesh::{Cell, CellType, Mesh};
use aster::model::Dof;
use aster::study::Study;
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

const V0: f64 = -227000.0;
const E_CU: f64 = 117000.0;
const RHO_CU: f64 = 8.93e-9;

/// Bar cells, bar nodes and the nodes of a cell group of a Taylor mesh.
fn bar(mesh: &Mesh) -> (Vec<usize>, Vec<usize>) {
    let vol = mesh.cell_groups["VOL"].clone();
    let nodes = mesh.nodes_of_cells(&vol);
    (vol, nodes)
}

fn group_nodes(mesh: &Mesh, g: &str) -> Vec<usize> {
    mesh.nodes_of_cells(&mesh.cell_groups[g])
}

fn dyna_text(comportement: &str, schema: &str, extra: &str) -> String {
    format!(
        "RESU = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT,
    COMPORTEMENT=_F({comportement}, TOUT='OUI'),
    ETAT_INIT=_F(VITE=V0),
    INCREMENT=_F(LIST_INST=L_INST),
    SCHEMA_TEMPS=_F({schema}, FORMULATION='DEPLACEMENT'){extra})"
    )
}

/// (1) Free flight of the SDNV103 D/F bar (no load, foundation left out of
/// the model): DY = v (t − t0) at every step and node, VY = v, a = 0, for
/// NEWMARK and both HHT variants, with the finite-strain plastic law.
#[test]
fn free_flight_is_exact_translation() {
    for schema in [
        "SCHEMA='NEWMARK'",
        "SCHEMA='HHT', ALPHA=-0.6, MODI_EQUI='NON'",
        "SCHEMA='HHT', ALPHA=-0.3, MODI_EQUI='OUI'",
    ] {
        let mesh = aster::medio::read_mesh(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("med/sdnv103d.mmed"),
            None,
        )
        .unwrap();
        let (vol, nodes) = bar(&mesh);
        let mo = model(&mesh, "AXIS", &vol);
        let v = velocity(mesh.nnodes(), &nodes, V0);
        let t = linspace(-1e-5, 0.0, 10);
        let mut st = study(
            mesh,
            mo,
            material(E_CU, 0.35, RHO_CU, Some((400.0, 100.0))),
            vec![],
            Some(v),
            t.clone(),
            None,
        );
        let text = dyna_text(
            "RELATION='VMIS_ISOT_LINE', DEFORMATION='SIMO_MIEHE'",
            schema,
            "",
        );
        exec(
            &mut st,
            "DYNA_NON_LINE",
            &args_of(&text, "DYNA_NON_LINE", 0),
            "RESU",
        )
        .unwrap();
        let r = result(&st, "RESU");
        assert_eq!(r.steps.len(), 11, "{schema}");
        for (k, s) in r.steps.iter().enumerate() {
            assert_eq!(s.inst, t[k]);
            let expect = V0 * (s.inst - t[0]);
            for &n in &nodes {
                let dy = s.nodal["DEPL"].get(n, "DY").unwrap();
                assert!(
                    (dy - expect).abs() <= 1e-10 * expect.abs().max(1e-300),
                    "{schema} step {k}: {dy} vs {expect}"
                );
                assert!(s.nodal["DEPL"].get(n, "DX").unwrap().abs() < 1e-12);
                let vy = s.nodal["VITE"].get(n, "DY").unwrap();
                assert!((vy - V0).abs() <= 1e-10 * V0.abs(), "{schema}: VY {vy}");
                let ay = s.nodal["ACCE"].get(n, "DY").unwrap();
                // |v|/dt ≈ 2e11: a must vanish to round-off of that scale.
                assert!(ay.abs() <= 1e-6 * V0.abs() / 1e-6, "{schema}: ACCE {ay}");
            }
        }
        // Nodes outside the model (the foundation) are absent.
        let rig = match st.concepts.data("MAIL") {
            Some(aster::concepts::ConceptData::Mesh(m)) => {
                m.nodes_of_cells(&m.cell_groups["VOL_RIG"])
            }
            _ => unreachable!(),
        };
        assert!(r.steps[1].nodal["DEPL"].get(rig[0], "DY").is_none());
    }
}

/// (2) Elastic wave in a rod (NU = 0, ELAS PETIT, 1 × 100 QUAD8 of the
/// bar's section), bottom held (DY = 0 on SZZ), the rest at v = −227 m/s:
/// behind the front σ_yy = ρ c v with c = √(E/ρ) (one-dimensional wave,
/// exact for ν = 0), and the free top's velocity reverses (−v → +v) when
/// the front reaches it at L/c (not 2L/c: the reflection at the free end
/// is what reverses it).
#[test]
fn elastic_wave_in_a_rod() {
    let mesh = taylor_axis(1, 100);
    let (vol, nodes) = bar(&mesh);
    let held = group_nodes(&mesh, "SZZ");
    let moving: Vec<usize> = nodes
        .iter()
        .copied()
        .filter(|n| !held.contains(n))
        .collect();
    let top = mesh.node_groups["A2"][0];
    let mo = model(&mesh, "AXIS", &vol);
    let v = velocity(mesh.nnodes(), &moving, V0);
    let c = (E_CU / RHO_CU).sqrt();
    let l = aster::mesh::taylor::LENGTH;
    let dt = 2.5e-8;
    let n = (1.3 * l / c / dt).ceil() as usize;
    let t = linspace(0.0, n as f64 * dt, n);
    let coords = mesh.coords.clone();
    let cells = mesh.cells.clone();
    let mut st = study(
        mesh,
        mo,
        material(E_CU, 0.0, RHO_CU, None),
        imposed(&held, Dof::Dy, 0.0),
        Some(v),
        t.clone(),
        None,
    );
    let text = dyna_text(
        "RELATION='ELAS'",
        "SCHEMA='NEWMARK'",
        ", EXCIT=_F(CHARGE=BLOQ)",
    );
    exec(
        &mut st,
        "DYNA_NON_LINE",
        &args_of(&text, "DYNA_NON_LINE", 0),
        "RESU",
    )
    .unwrap();
    let r = result(&st, "RESU");
    // Stress behind the front at t ≈ L/(2c): mean SIYY over the cells
    // between 10 % and 80 % of the distance travelled by the front.
    let k = ((0.5 * l / c) / dt).round() as usize;
    let s = &r.steps[k];
    let front = c * s.inst;
    let y0 = aster::mesh::taylor::GAP;
    let sief = &s.gauss["SIEF_ELGA"];
    let (mut sum, mut cnt) = (0.0, 0);
    for &cell in &vol {
        let yc: f64 = cells[cell].nodes.iter().map(|&n| coords[n][1]).sum::<f64>() / 8.0 - y0;
        if yc > 0.1 * front && yc < 0.8 * front {
            for p in 0..sief.npg(cell) {
                sum += sief.cell(cell)[p * 4 + 1];
                cnt += 1;
            }
        }
    }
    let sigma = sum / cnt as f64;
    let expect = RHO_CU * c * V0;
    let rel = (sigma - expect).abs() / expect.abs();
    eprintln!("wave: sigma_yy behind the front {sigma:.1} vs rho c v {expect:.1} ({rel:.2e})");
    assert!(rel < 0.02, "{sigma} vs {expect}");
    // Top velocity reversal: the zero crossing of VY, interpolated
    // linearly between the two steps around it.
    let vy = |k: usize| r.steps[k].nodal["VITE"].get(top, "DY").unwrap();
    let k_rev = (1..r.steps.len())
        .find(|&k| vy(k) > 0.0)
        .expect("the top velocity reverses");
    let (t0, t1) = (r.steps[k_rev - 1].inst, r.steps[k_rev].inst);
    let t_rev = t0 + (t1 - t0) * (-vy(k_rev - 1)) / (vy(k_rev) - vy(k_rev - 1));
    eprintln!(
        "wave: top velocity reverses at {t_rev:e}, L/c = {:e}",
        l / c
    );
    // The trapezoidal rule's dispersion delays the smeared front by about
    // 1.7 steps here: 1 % of L/c bounds it.
    assert!(
        (t_rev - l / c).abs() <= 0.01 * l / c,
        "{t_rev} vs {}",
        l / c
    );
}

/// Kinetic + strain energy of every archived step of an ELAS PETIT run:
/// ½ vᵀMv with the engine's mass, ½ uᵀ FORC_NODA (FORC_NODA = K u for
/// linear elasticity) from CALC_CHAMP.
fn energies(st: &mut Study) -> Vec<f64> {
    let args = args_of(
        &format!(
            "{NEWMARK_ELAS}\nRESU = CALC_CHAMP(reuse=RESU, RESULTAT=RESU, FORCE=('FORC_NODA',))"
        ),
        "CALC_CHAMP",
        0,
    );
    exec(st, "CALC_CHAMP", &args, "RESU").unwrap();
    let (mesh, mo, mat) = match (
        st.concepts.data("MAIL"),
        st.concepts.data("MO"),
        st.concepts.data("MAT"),
    ) {
        (
            Some(aster::concepts::ConceptData::Mesh(a)),
            Some(aster::concepts::ConceptData::Model(b)),
            Some(aster::concepts::ConceptData::Material(c)),
        ) => (a.clone(), b.clone(), c.clone()),
        _ => unreachable!(),
    };
    let mut mats = indexmap::IndexMap::new();
    mats.insert("MAT".to_string(), (*mat).clone());
    let mf = aster::model::MaterialField {
        mesh: "MAIL".into(),
        cell_material: vec![Some("MAT".into()); mesh.ncells()],
    };
    let (asm, _) = aster::nonlinear::discretize(&mesh, &mo, &mf, &mats, &[], &[]).unwrap();
    let names = vec!["DX".to_string(), "DY".to_string()];
    let r = result(st, "RESU");
    r.steps
        .iter()
        .map(|s| {
            let u = aster::nonlinear::fields::from_nodal(&asm, &names, &s.nodal["DEPL"]);
            let v = aster::nonlinear::fields::from_nodal(&asm, &names, &s.nodal["VITE"]);
            let f = aster::nonlinear::fields::from_nodal(&asm, &names, &s.nodal["FORC_NODA"]);
            let mut mv = vec![0.0; v.len()];
            asm.mass_mul(&v, &mut mv);
            let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
            0.5 * dot(&v, &mv) + 0.5 * dot(&u, &f)
        })
        .collect()
}

/// (3) Energy: a free elastic bar (1 × 8 QUAD8, ν = 0.3) released with
/// the velocity of its first free-free mode, v_y = V cos(π ξ). The average
/// acceleration rule conserves ½vᵀMv + ½uᵀKu exactly for a linear system
/// (1000 steps, 20 periods); HHT and NEWMARK(0.49, 0.9) dissipate it
/// (sampled once per period, it decreases).
#[test]
fn energy_is_conserved_by_average_acceleration_and_dissipated_otherwise() {
    let c = (E_CU / RHO_CU).sqrt();
    let l = aster::mesh::taylor::LENGTH;
    let period = 2.0 * l / c;
    for (schema, steps, conserve) in [
        ("SCHEMA='NEWMARK'", 1000, true),
        ("SCHEMA='NEWMARK', BETA=0.49, GAMMA=0.9", 250, false),
        ("SCHEMA='HHT', ALPHA=-0.3", 250, false),
        ("SCHEMA='HHT', ALPHA=-0.6, MODI_EQUI='NON'", 250, false),
    ] {
        let mesh = taylor_axis(1, 8);
        let (vol, nodes) = bar(&mesh);
        let mo = model(&mesh, "AXIS", &vol);
        let mut v = velocity(mesh.nnodes(), &nodes, 0.0);
        for &n in &nodes {
            let xi = (mesh.coords[n][1] - aster::mesh::taylor::GAP) / l;
            v.set(n, 1, 1000.0 * (std::f64::consts::PI * xi).cos());
        }
        let dt = period / 50.0;
        let t = linspace(0.0, steps as f64 * dt, steps);
        let mut st = study(
            mesh,
            mo,
            material(E_CU, 0.3, RHO_CU, None),
            vec![],
            Some(v),
            t,
            None,
        );
        let text = dyna_text(
            "RELATION='ELAS'",
            schema,
            ", CONVERGENCE=_F(RESI_GLOB_RELA=1e-10)",
        );
        exec(
            &mut st,
            "DYNA_NON_LINE",
            &args_of(&text, "DYNA_NON_LINE", 0),
            "RESU",
        )
        .unwrap();
        let e = energies(&mut st);
        let e0 = e[0];
        if conserve {
            let worst = e.iter().map(|x| (x - e0).abs() / e0).fold(0.0, f64::max);
            eprintln!("energy {schema}: worst relative drift {worst:.2e} over {steps} steps");
            assert!(worst < 1e-6, "{worst}");
        } else {
            let per: Vec<f64> = e.iter().step_by(50).copied().collect();
            eprintln!(
                "energy {schema}: per period {:?}",
                per.iter().map(|x| x / e0).collect::<Vec<_>>()
            );
            for w in per.windows(2) {
                assert!(w[1] < w[0], "{schema}: {per:?}");
            }
            assert!(*per.last().unwrap() < 0.999 * e0, "{schema}: {per:?}");
        }
    }
}

/// The plastic rod of the cutting tests: 1 × 10 QUAD8, bottom held,
/// VMIS_ISOT_LINE PETIT (σ = ρcv ≈ 7300 ≫ SY = 400: every step yields).
fn plastic_rod(instants: Vec<f64>, list: Option<aster::time::list::TimeList>) -> Study {
    let mesh = taylor_axis(1, 10);
    let (vol, nodes) = bar(&mesh);
    let held = group_nodes(&mesh, "SZZ");
    let moving: Vec<usize> = nodes
        .iter()
        .copied()
        .filter(|n| !held.contains(n))
        .collect();
    let mo = model(&mesh, "AXIS", &vol);
    let v = velocity(mesh.nnodes(), &moving, V0);
    study(
        mesh,
        mo,
        material(E_CU, 0.35, RHO_CU, Some((400.0, 100.0))),
        imposed(&held, Dof::Dy, 0.0),
        Some(v),
        instants,
        list,
    )
}

/// (5) Step cutting. With the elastic Newton matrix the iteration count
/// grows with the plastic increment; an ITER_GLOB_MAXI that the steps of
/// dt meet and the steps of 4·dt do not (both measured first) makes every
/// big step fail; DECOUPE MANUEL (SUBD_PAS = 4) redoes them as 4 steps of dt, so
/// the result equals the run made with steps of dt from the start (the
/// rolled-back state must be exact). With a plain list the same failure
/// stops the run: the error says where and why, and the partial result
/// keeps the steps computed before.
#[test]
fn failed_steps_are_cut_or_stop_with_the_partial_result() {
    use aster::time::list::{Action, Subdivision, TimeList};
    let dt = 2e-8;
    let fine = linspace(0.0, 16.0 * dt, 16);
    let coarse = linspace(0.0, 16.0 * dt, 4);
    let text = |list: &str, iters: usize| {
        format!(
            "RESU = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOQ),
    COMPORTEMENT=_F(RELATION='VMIS_ISOT_LINE', TOUT='OUI'),
    ETAT_INIT=_F(VITE=V0), INCREMENT=_F(LIST_INST={list}),
    SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'),
    NEWTON=_F(MATRICE='ELASTIQUE'),
    CONVERGENCE=_F(RESI_GLOB_RELA=1e-8, ITER_GLOB_MAXI={iters}))"
        )
    };
    // Reference: small steps, plenty of iterations.
    let mut reference = plastic_rod(fine.clone(), None);
    exec(
        &mut reference,
        "DYNA_NON_LINE",
        &args_of(&text("L_INST", 20), "DYNA_NON_LINE", 0),
        "RESU",
    )
    .unwrap();
    // Find the iteration budget that the small steps meet and the big
    // ones do not, from the logs of two runs.
    let max_iters = |mess: &str| -> usize {
        mess.lines()
            .filter_map(|l| {
                let w: Vec<&str> = l.split_whitespace().collect();
                (w.len() >= 7 && w[0].parse::<usize>().is_ok())
                    .then(|| w[3].parse::<usize>().ok())
                    .flatten()
            })
            .max()
            .unwrap()
    };
    let small = max_iters(&reference.mess);
    let mut big = plastic_rod(coarse.clone(), None);
    exec(
        &mut big,
        "DYNA_NON_LINE",
        &args_of(&text("L_INST", 20), "DYNA_NON_LINE", 0),
        "RESU",
    )
    .unwrap();
    let min_big = big
        .mess
        .lines()
        .filter_map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            (w.len() >= 7 && w[0].parse::<usize>().is_ok())
                .then(|| w[3].parse::<usize>().ok())
                .flatten()
        })
        .min()
        .unwrap();
    eprintln!("cutting: small steps need at most {small} iterations, big steps at least {min_big}");
    assert!(
        min_big > small,
        "no iteration budget separates the step sizes"
    );
    let rule = TimeList {
        rules: vec![aster::time::list::FailureRule {
            event: aster::time::list::Event::Erreur,
            action: Action::Decoupe(Subdivision::Manuel {
                subd_pas: 4,
                subd_niveau: 2,
                subd_pas_mini: 1e-15,
            }),
        }],
        ..TimeList::plain(coarse.clone())
    };
    let mut cut = plastic_rod(coarse.clone(), Some(rule));
    exec(
        &mut cut,
        "DYNA_NON_LINE",
        &args_of(&text("LI", small), "DYNA_NON_LINE", 0),
        "RESU",
    )
    .unwrap();
    assert_eq!(
        cut.mess.matches("is cut into 4 sub-steps").count(),
        4,
        "{}",
        cut.mess
    );
    let (rc, rr) = (result(&cut, "RESU"), result(&reference, "RESU"));
    // Sub-steps are computed instants and archived (PAS_ARCH = 1).
    assert_eq!(rc.steps.len(), rr.steps.len());
    let mut worst: f64 = 0.0;
    for (a, b) in rc.steps.iter().zip(&rr.steps) {
        assert!((a.inst - b.inst).abs() < 1e-20);
        for f in ["DEPL", "VITE"] {
            let (x, y) = (&a.nodal[f].values, &b.nodal[f].values);
            let scale = y
                .iter()
                .filter(|v| !v.is_nan())
                .fold(0.0f64, |m, v| m.max(v.abs()));
            for (p, q) in x.iter().zip(y) {
                if !q.is_nan() {
                    worst = worst.max((p - q).abs() / scale.max(1e-300));
                }
            }
        }
        let (x, y) = (&a.gauss["VARI_ELGA"].values, &b.gauss["VARI_ELGA"].values);
        for (p, q) in x.iter().zip(y) {
            assert!((p - q).abs() <= 1e-8 * q.abs().max(1e-6));
        }
    }
    eprintln!("cutting: cut run vs small steps, worst relative difference {worst:.2e}");
    assert!(worst < 1e-8, "{worst}");
    let p_max = rr.steps.last().unwrap().gauss["VARI_ELGA"]
        .values
        .iter()
        .copied()
        .fold(0.0, f64::max);
    assert!(p_max > 1e-4, "the steps are plastic: p = {p_max}");

    // Plain list: ERREUR -> ARRET, the partial result is kept.
    let mut stop = plastic_rod(coarse.clone(), None);
    let err = exec(
        &mut stop,
        "DYNA_NON_LINE",
        &args_of(&text("L_INST", small), "DYNA_NON_LINE", 0),
        "RESU",
    )
    .unwrap_err();
    assert!(
        err.contains("DYNA_NON_LINE stopped at the step from t = 0e0"),
        "{err}"
    );
    assert!(err.contains("Newton did not converge"), "{err}");
    let partial = result(&stop, "RESU");
    assert_eq!(
        partial.steps.len(),
        1,
        "only the initial state was computed"
    );
    assert_eq!(partial.steps[0].inst, 0.0);
}

/// (6) Taylor bar without contact, mesh B (med/sdnv103b.mmed, 5 × 20
/// QUAD8, AXIS_SI): the bottom face is held (DY = 0 on SZZ, a rigid wall
/// from t = 0), DX = 0 on the axis, SIMO_MIEHE VMIS_ISOT_LINE, HHT
/// (−0.6, MODI_EQUI='NON'), 8 steps of 2.5e-7. It must run to the end with
/// p = V1 > 0 at the bottom, finite fields and a decreasing kinetic
/// energy; the wall time per step is printed for docs/dynamics.md.
#[test]
fn plastic_taylor_bar_against_a_held_face() {
    let mesh = aster::medio::read_mesh(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("med/sdnv103b.mmed"),
        None,
    )
    .unwrap();
    let (vol, nodes) = bar(&mesh);
    let held = group_nodes(&mesh, "SZZ");
    let axe = group_nodes(&mesh, "AXE");
    let moving: Vec<usize> = nodes
        .iter()
        .copied()
        .filter(|n| !held.contains(n))
        .collect();
    let mo = model(&mesh, "AXIS_SI", &vol);
    let v = velocity(mesh.nnodes(), &moving, V0);
    let mut imp = imposed(&held, Dof::Dy, 0.0);
    imp.extend(imposed(&axe, Dof::Dx, 0.0));
    let bottom_cells: Vec<usize> = vol
        .iter()
        .copied()
        .filter(|&c| mesh.cells[c].nodes.iter().any(|n| held.contains(n)))
        .collect();
    let mut st = study(
        mesh,
        mo,
        material(E_CU, 0.35, RHO_CU, Some((400.0, 100.0))),
        imp,
        Some(v),
        linspace(0.0, 2e-6, 8),
        None,
    );
    let text = dyna_text(
        "RELATION='VMIS_ISOT_LINE', DEFORMATION='SIMO_MIEHE'",
        "SCHEMA='HHT', ALPHA=-0.6, MODI_EQUI='NON'",
        ", EXCIT=_F(CHARGE=BLOQ), CONVERGENCE=_F(RESI_GLOB_RELA=1e-6, ITER_GLOB_MAXI=20)",
    );
    let started = std::time::Instant::now();
    exec(
        &mut st,
        "DYNA_NON_LINE",
        &args_of(&text, "DYNA_NON_LINE", 0),
        "RESU",
    )
    .unwrap();
    let per_step = started.elapsed().as_secs_f64() / 8.0;
    let line = st
        .mess
        .lines()
        .find(|l| l.contains("Newton iterations"))
        .unwrap_or("")
        .to_string();
    eprintln!("taylor B: {per_step:.3e} s per step (with set-up); {line}");
    let r = result(&st, "RESU");
    assert_eq!(r.steps.len(), 9);
    let last = r.steps.last().unwrap();
    let vari = &last.gauss["VARI_ELGA"];
    let p_bottom = bottom_cells
        .iter()
        .flat_map(|&c| (0..vari.npg(c)).map(move |p| (c, p)))
        .map(|(c, p)| vari.cell(c)[p * vari.ncmp()])
        .fold(0.0, f64::max);
    eprintln!("taylor B: max p at the bottom {p_bottom:.4}");
    assert!(p_bottom > 0.01, "{p_bottom}");
    for s in &r.steps {
        assert!(s.nodal["DEPL"].values.iter().all(|v| !v.is_infinite()));
        assert!(s.gauss["SIEF_ELGA"].values.iter().all(|v| v.is_finite()));
    }
    // Kinetic energy ½ vᵀMv with the consistent mass. The wall is fixed
    // and the initial strain energy zero, so the kinetic energy can never
    // exceed its initial value (a stable scheme creates no energy), and
    // plastic dissipation must make it drop.
    let (mesh, mo) = match (st.concepts.data("MAIL"), st.concepts.data("MO")) {
        (
            Some(aster::concepts::ConceptData::Mesh(a)),
            Some(aster::concepts::ConceptData::Model(b)),
        ) => (a.clone(), b.clone()),
        _ => unreachable!(),
    };
    let mut mats = indexmap::IndexMap::new();
    mats.insert("MAT".to_string(), material(E_CU, 0.35, RHO_CU, None));
    let mf = aster::model::MaterialField {
        mesh: "MAIL".into(),
        cell_material: vec![Some("MAT".into()); mesh.ncells()],
    };
    let (asm, _) = aster::nonlinear::discretize(&mesh, &mo, &mf, &mats, &[], &[]).unwrap();
    let names = vec!["DX".to_string(), "DY".to_string()];
    let ke: Vec<f64> = r
        .steps
        .iter()
        .map(|s| {
            let v = aster::nonlinear::fields::from_nodal(&asm, &names, &s.nodal["VITE"]);
            let mut mv = vec![0.0; v.len()];
            asm.mass_mul(&v, &mut mv);
            0.5 * v.iter().zip(&mv).map(|(a, b)| a * b).sum::<f64>()
        })
        .collect();
    eprintln!(
        "taylor B: kinetic energy / initial {:?}",
        ke.iter().map(|k| k / ke[0]).collect::<Vec<_>>()
    );
    for (k, e) in ke.iter().enumerate() {
        assert!(*e <= ke[0] * (1.0 + 1e-12), "step {k}: {ke:?}");
    }
    assert!(*ke.last().unwrap() < 0.99 * ke[0], "{ke:?}");
}
