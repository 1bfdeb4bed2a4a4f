//! Large-deformation behaviour of the element interface: objectivity under
//! a 90° rigid rotation (SIMO_MIEHE exact, PETIT and PETIT_REAC spurious
//! by closed forms), uniaxial large stretch of one HEXA8/HEXA20 against a
//! law-level driver, AXIS against a 3D quarter ring, and consistent masses
//! against the exact volumes of the meshed regions.

mod element_support;

use std::f64::consts::PI;

use aster::element::{
    initial_states, internal_forces, mass, ElementResponse, Kinematics, LawRef, PointState,
};
use aster::law::elas::Elas;
use aster::law::simo_miehe::{FiniteStrainInput, SimoMiehe};
use aster::law::vmis_isot_line::VmisIsotLine;
use aster::law::voigt::{stress_to_tensor, tensor_to_strain};
use aster::law::{TangentKind, Vec6};
use aster::mesh::CellType;
use aster::model::spec::{element_spec, ElementSpec};
use element_support::*;
use nalgebra::{DMatrix, DVector, Matrix3, Rotation3, Vector3};

fn spec(m: &str, cell: CellType) -> ElementSpec {
    element_spec(m, cell).unwrap()
}

#[allow(clippy::too_many_arguments)]
fn run(
    s: &ElementSpec,
    kin: Kinematics,
    coords: &[[f64; 3]],
    u_n: &[f64],
    u: &[f64],
    states: &[PointState],
    law: LawRef,
    tangent: TangentKind,
) -> ElementResponse {
    internal_forces(s, kin, coords, u_n, u, states, law, 1e-6, tangent).unwrap()
}

/// Nodal values of x ↦ (M − 1) x.
fn motion(coords: &[[f64; 3]], m: &Matrix3<f64>) -> Vec<f64> {
    coords
        .iter()
        .flat_map(|x| {
            let v = (m - Matrix3::identity()) * Vector3::from(*x);
            [v[0], v[1], v[2]]
        })
        .collect()
}

#[test]
fn rigid_rotation_of_90_degrees() {
    let axis = Vector3::new(1.0, 1.0, 1.0).normalize();
    let rot = *Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), PI / 2.0).matrix();
    let copper = simo(copper_ecro());
    let sm = LawRef::SimoMiehe(&copper);
    for (m, cell) in [("3D", CellType::Hexa8), ("3D", CellType::Hexa20)] {
        let s = spec(m, cell);
        let x = distorted_cell(cell);
        let zero = vec![0.0; s.ndofs()];
        let u = motion(&x, &rot);

        // SIMO_MIEHE from the virgin state: no stress, no force.
        let out = run(
            &s,
            Kinematics::SimoMiehe,
            &x,
            &zero,
            &u,
            &initial_states(&s, sm),
            sm,
            TangentKind::None,
        );
        for st in &out.states {
            assert!(st.stress.norm() < 1e-12 * E, "{cell:?}: {}", st.stress);
        }
        assert!(
            out.forces.norm() < 1e-12 * E,
            "{cell:?}: {}",
            out.forces.norm()
        );

        // From a plastically stretched state: the rotation rotates σ and
        // the nodal forces exactly, and p does not change.
        let f0 = Matrix3::new(1.02, 0.004, 0.0, 0.0, 0.99, 0.003, 0.002, 0.0, 0.991);
        let u0 = motion(&x, &f0);
        let step0 = run(
            &s,
            Kinematics::SimoMiehe,
            &x,
            &zero,
            &u0,
            &initial_states(&s, sm),
            sm,
            TangentKind::None,
        );
        assert!(step0.states.iter().all(|p| p.internal.as_slice()[1] == 1.0));
        let u1 = motion(&x, &(rot * f0));
        let step1 = run(
            &s,
            Kinematics::SimoMiehe,
            &x,
            &u0,
            &u1,
            &step0.states,
            sm,
            TangentKind::None,
        );
        for (a, b) in step0.states.iter().zip(&step1.states) {
            let expected = rot * stress_to_tensor(&a.stress) * rot.transpose();
            let got = stress_to_tensor(&b.stress);
            assert!(
                (got - expected).norm() < 1e-10 * expected.norm(),
                "{cell:?}"
            );
            assert!((a.internal.as_slice()[0] - b.internal.as_slice()[0]).abs() < 1e-14);
        }
        for n in 0..s.nnodes() {
            let f0n = Vector3::from_column_slice(&step0.forces.as_slice()[3 * n..3 * n + 3]);
            let f1n = Vector3::from_column_slice(&step1.forces.as_slice()[3 * n..3 * n + 3]);
            assert!((f1n - rot * f0n).norm() < 1e-10 * step0.forces.norm());
        }

        // PETIT: ε = sym(R − 1) is not zero; σ = D ε, of the order of E.
        let elas = Elas::new(elas_params());
        let small = LawRef::Small(&elas);
        let out = run(
            &s,
            Kinematics::Petit,
            &x,
            &zero,
            &u,
            &initial_states(&s, small),
            small,
            TangentKind::None,
        );
        let spurious = elas.stiffness() * tensor_to_strain(&(rot - Matrix3::identity()));
        assert!(spurious.norm() > 0.5 * E);
        for st in &out.states {
            assert!((st.stress - spurious).norm() < 1e-12 * spurious.norm());
        }
        assert!(out.forces.norm() > 0.1 * E);
    }
}

#[test]
fn petit_reac_accumulates_spurious_strain_and_does_not_rotate_stress() {
    // N steps of a rotation θ about z on x = R_k X: Δu = (1 − R(dθ)ᵀ) x,
    // so Δε = (1 − cos dθ)(1, 1, 0) each step, and the stress at the
    // start is never rotated: σ_N = σ_0 + N (1 − cos(θ/N)) D (1, 1, 0, 0, 0, 0).
    let elas = Elas::new(elas_params());
    let law = LawRef::Small(&elas);
    let sigma0 = Vec6::new(100.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for cell in [CellType::Hexa8, CellType::Hexa20] {
        let s = spec("3D", cell);
        let x = distorted_cell(cell);
        for n in [1usize, 10, 40] {
            let mut states: Vec<PointState> = initial_states(&s, law)
                .into_iter()
                .map(|p| PointState {
                    stress: sigma0,
                    ..p
                })
                .collect();
            let mut u = vec![0.0; s.ndofs()];
            for k in 1..=n {
                let r =
                    Rotation3::from_axis_angle(&Vector3::z_axis(), PI / 2.0 * k as f64 / n as f64);
                let u1 = motion(&x, r.matrix());
                states = run(
                    &s,
                    Kinematics::PetitReac,
                    &x,
                    &u,
                    &u1,
                    &states,
                    law,
                    TangentKind::None,
                )
                .states;
                u = u1;
            }
            let acc = n as f64 * (1.0 - (PI / 2.0 / n as f64).cos());
            let expected = sigma0 + elas.stiffness() * Vec6::new(acc, acc, 0.0, 0.0, 0.0, 0.0);
            for st in &states {
                assert!(
                    (st.stress - expected).norm() < 1e-9 * expected.norm(),
                    "{cell:?} N={n}: {} vs {expected}",
                    st.stress
                );
            }
        }
    }
}

/// Law-level uniaxial stress driver (no element): F = diag(λ, λt, λt), λt
/// from τ_yy = 0 by Newton on ∂τ/∂F, over `n` equal stretch steps.
/// Returns (p, Cauchy σ_xx, τ_xx, λt).
fn law_uniaxial(law: &SimoMiehe, lambda: f64, n: usize) -> (f64, f64, f64, f64) {
    let mut f = Matrix3::identity();
    let mut v = law.initial_internal();
    let mut res = (0.0, 0.0, 0.0, 1.0);
    for i in 1..=n {
        let l = 1.0 + (lambda - 1.0) * i as f64 / n as f64;
        let mut lt: f64 = f[(1, 1)];
        let mut done = false;
        for _ in 0..40 {
            let f1 = Matrix3::from_diagonal(&Vector3::new(l, lt, lt));
            let o = law
                .integrate(&FiniteStrainInput {
                    f_n: f,
                    f_np1: f1,
                    internal: v.as_slice(),
                    dt: 1e-6,
                    tangent: TangentKind::Consistent,
                })
                .unwrap();
            if o.kirchhoff[(1, 1)].abs() < 1e-10 {
                f = f1;
                v = o.internal;
                res = (v.as_slice()[0], o.cauchy[(0, 0)], o.kirchhoff[(0, 0)], lt);
                done = true;
                break;
            }
            let d = o.dtau_df.unwrap();
            lt -= o.kirchhoff[(1, 1)] / (d[(4, 4)] + d[(4, 8)]);
        }
        assert!(done, "law-level lateral Newton did not converge");
    }
    res
}

#[test]
fn uniaxial_large_stretch_of_one_element_matches_the_law_level_driver() {
    let law = simo(copper_ecro());
    let sm = LawRef::SimoMiehe(&law);
    let (lambda, nsteps) = (1.5, 100);
    let (p_ref, sxx_ref, tau_ref, lt_ref) = law_uniaxial(&law, lambda, nsteps);
    // The continuum value of the previous helper's reference ODE is
    // 0.4030060; 100 steps are first-order accurate to about 2e-3.
    assert!((p_ref - 0.4030060).abs() < 5e-3 * p_ref, "p {p_ref}");
    for (m, cell) in [
        ("3D", CellType::Hexa8),
        ("3D", CellType::Hexa20),
        ("3D_SI", CellType::Hexa20),
    ] {
        let s = spec(m, cell);
        let x = complete(cell, &unit_vertices(cell));
        let ndof = s.ndofs();
        // Symmetry planes x = 0, y = 0, z = 0; u_x imposed on x = 1;
        // faces y = 1 and z = 1 free.
        let mut fixed = vec![false; ndof];
        for (a, p) in x.iter().enumerate() {
            for i in 0..3 {
                fixed[3 * a + i] = p[i] == 0.0 || (i == 0 && p[0] == 1.0);
            }
        }
        let free: Vec<usize> = (0..ndof).filter(|&k| !fixed[k]).collect();
        let mut u = vec![0.0; ndof];
        let mut states = initial_states(&s, sm);
        let mut last = None;
        for step in 1..=nsteps {
            let l = 1.0 + (lambda - 1.0) * step as f64 / nsteps as f64;
            let mut u1 = u.clone();
            for (a, p) in x.iter().enumerate() {
                if p[0] == 1.0 {
                    u1[3 * a] = l - 1.0;
                }
            }
            let mut converged = None;
            for _ in 0..30 {
                let out = run(
                    &s,
                    Kinematics::SimoMiehe,
                    &x,
                    &u,
                    &u1,
                    &states,
                    sm,
                    TangentKind::Consistent,
                );
                let r = DVector::from_iterator(free.len(), free.iter().map(|&k| out.forces[k]));
                if r.norm() < 1e-10 * out.forces.norm() {
                    converged = Some(out);
                    break;
                }
                let k = out.stiffness.as_ref().unwrap();
                let kff = DMatrix::from_fn(free.len(), free.len(), |i, j| k[(free[i], free[j])]);
                let du = kff.lu().solve(&(-r)).expect("regular free-free stiffness");
                for (i, &kk) in free.iter().enumerate() {
                    u1[kk] += du[i];
                }
            }
            let out = converged.expect("element Newton converged");
            states = out.states.clone();
            u = u1;
            last = Some(out);
        }
        let out = last.unwrap();
        for st in &states {
            let p = st.internal.as_slice()[0];
            assert!(
                (p - p_ref).abs() < 1e-8 * p_ref,
                "{m} {cell:?}: p {p} vs {p_ref}"
            );
            assert!((st.stress[0] - sxx_ref).abs() < 1e-8 * sxx_ref);
            for k in 1..6 {
                assert!(
                    st.stress[k].abs() < 1e-8 * sxx_ref,
                    "{m} {cell:?}: {}",
                    st.stress
                );
            }
        }
        let (mut reaction, mut lateral) = (0.0, None);
        for (a, p) in x.iter().enumerate() {
            if p[0] == 1.0 {
                reaction += out.forces[3 * a];
            }
            if *p == [1.0, 1.0, 1.0] {
                lateral = Some((u[3 * a + 1], u[3 * a + 2]));
            }
        }
        let (uy, uz) = lateral.unwrap();
        assert!((uy - (lt_ref - 1.0)).abs() < 1e-9 && (uz - (lt_ref - 1.0)).abs() < 1e-9);
        // Reaction on the unit reference face: P_xx = τ_xx / λ.
        assert!(
            (reaction - tau_ref / lambda).abs() < 1e-8 * tau_ref,
            "{m} {cell:?}: {reaction} vs {}",
            tau_ref / lambda
        );
    }
}

const RI: f64 = 1.0;
const RO: f64 = 2.0;
const HEIGHT: f64 = 0.5;
const SECTORS: usize = 4;

/// A quarter ring RI ≤ r ≤ RO, 0 ≤ θ ≤ π/2, 0 ≤ z ≤ HEIGHT: 2 cells
/// radially, SECTORS in θ, 1 in z, every node on its exact (r, θ, z).
fn quarter_ring(cell: CellType) -> TestMesh {
    let mut lists = Vec::new();
    for i in 0..2 {
        for j in 0..SECTORS {
            lists.extend(fill_cube(cell, [i as f64, j as f64, 0.0]));
        }
    }
    let dth = PI / 2.0 / SECTORS as f64;
    build(cell, &lists, |p| {
        let (r, th) = (RI + 0.5 * (RO - RI) * p[0], dth * p[1]);
        [r * th.cos(), r * th.sin(), HEIGHT * p[2]]
    })
}

/// Volume of the region a quarter-ring mesh covers (independent of the
/// element code). Radial edges are straight; an arc through three nodes
/// on the circle (quadratic cells) is a parabola, whose segment over its
/// chord is ⅔·chord·sagitta (Archimedes); linear cells have the chords.
fn meshed_ring_volume(quadratic: bool) -> f64 {
    let dth = PI / 2.0 / SECTORS as f64;
    let d2 = RO * RO - RI * RI;
    let trapezoid = 0.5 * d2 * dth.sin();
    let segments = if quadratic {
        (4.0 / 3.0) * (dth / 2.0).sin() * (1.0 - (dth / 2.0).cos()) * d2
    } else {
        0.0
    };
    SECTORS as f64 * (trapezoid + segments) * HEIGHT
}

fn exact_ring_volume() -> f64 {
    PI / 4.0 * (RO * RO - RI * RI) * HEIGHT
}

/// The (r, z) section [RI, RO] × [0, HEIGHT] in 2 × 1 cells (triangles:
/// each rectangle split in two).
fn axis_section(cell: CellType) -> TestMesh {
    let mut lists = Vec::new();
    for i in 0..2 {
        let (r0, r1) = (RI + 0.5 * i as f64, RI + 0.5 * (i + 1) as f64);
        let quad = vec![
            [r0, 0.0, 0.0],
            [r1, 0.0, 0.0],
            [r1, HEIGHT, 0.0],
            [r0, HEIGHT, 0.0],
        ];
        if linear_of(cell) == CellType::Quad4 {
            lists.push(orient(cell, quad));
        } else {
            lists.push(orient(cell, vec![quad[0], quad[1], quad[2]]));
            lists.push(orient(cell, vec![quad[0], quad[2], quad[3]]));
        }
    }
    build(cell, &lists, |p| p)
}

/// Runs one step from the virgin state on every cell; returns all point
/// stresses and Σ f·u.
fn one_step(
    mesh: &TestMesh,
    s: &ElementSpec,
    kin: Kinematics,
    law: LawRef,
    u: &[f64],
) -> (Vec<Vec6>, f64) {
    let d = s.formulation.dofs_per_node();
    let mut stresses = Vec::new();
    let mut work = 0.0;
    for c in 0..mesh.cells.len() {
        let ue = mesh.gather(c, u, d);
        let out = run(
            s,
            kin,
            &mesh.cell_coords(c),
            &vec![0.0; ue.len()],
            &ue,
            &initial_states(s, law),
            law,
            TangentKind::None,
        );
        work += out.forces.iter().zip(&ue).map(|(f, v)| f * v).sum::<f64>();
        stresses.extend(out.states.iter().map(|p| p.stress));
    }
    (stresses, work)
}

#[test]
fn axisymmetric_and_3d_quarter_ring_agree_under_radial_expansion() {
    let elas = Elas::new(elas_params());
    let vmis = VmisIsotLine::new(elas_params(), copper_ecro());
    let copper = simo(copper_ecro());
    let ring = quarter_ring(CellType::Hexa20);
    // The circle's discretisation: ≈ −5e-5 for 4 quadratic sectors.
    let geo = meshed_ring_volume(true) / exact_ring_volume();
    assert!(
        (geo - 1.0).abs() < 1e-4 && (geo - 1.0).abs() > 1e-6,
        "{geo}"
    );
    let cases: [(Kinematics, LawRef, f64); 4] = [
        (Kinematics::Petit, LawRef::Small(&elas), 1e-3),
        (Kinematics::Petit, LawRef::Small(&vmis), 2e-2),
        (Kinematics::PetitReac, LawRef::Small(&vmis), 2e-2),
        (Kinematics::SimoMiehe, LawRef::SimoMiehe(&copper), 0.2),
    ];
    for (model3d, model2d) in [("3D", "AXIS"), ("3D_SI", "AXIS_SI")] {
        for (kin, law, a) in cases {
            let u3: Vec<f64> = ring
                .nodes
                .iter()
                .flat_map(|x| [a * x[0], a * x[1], 0.0])
                .collect();
            let (s3, w3) = one_step(&ring, &spec(model3d, CellType::Hexa20), kin, law, &u3);
            let section = axis_section(CellType::Quad8);
            let u2: Vec<f64> = section.nodes.iter().flat_map(|x| [a * x[0], 0.0]).collect();
            let (s2, w2) = one_step(&section, &spec(model2d, CellType::Quad8), kin, law, &u2);
            // u is linear in X, so every point of both meshes carries the
            // exact uniform stress: 3D (xx, yy, zz) = AXIS (rr, θθ, zz).
            let r = s2[0];
            let scale = r.norm();
            assert!(
                r[0] > 0.0 && (r[0] - r[2]).abs() < 1e-10 * scale,
                "σ_rr = σ_θθ"
            );
            for t in &s2 {
                assert!((t - r).norm() < 1e-10 * scale);
            }
            let expected = Vec6::new(r[0], r[2], r[1], 0.0, 0.0, 0.0);
            for t in &s3 {
                assert!(
                    (t - expected).norm() < 1e-10 * scale,
                    "{model3d} {kin:?}: {t} vs {expected}"
                );
            }
            // Σ f·u = ∫ S : ∇u is the stress work over the meshed volume:
            // the 3D/AXIS ratio is exactly the circle's volume error.
            let ratio = w3 / (w2 * PI / 2.0);
            assert!(
                (ratio - geo).abs() < 1e-10,
                "{model3d} {kin:?}: {ratio} vs {geo}"
            );
        }
    }
}

fn total_mass(mesh: &TestMesh, s: &ElementSpec, rho: f64) -> [f64; 3] {
    let d = s.formulation.dofs_per_node();
    let mut tot = [0.0; 3];
    for c in 0..mesh.cells.len() {
        let m = mass(s, &mesh.cell_coords(c), rho).unwrap();
        assert!((&m - m.transpose()).norm() < 1e-15 * m.norm());
        for a in 0..s.nnodes() {
            for b in 0..s.nnodes() {
                for i in 0..d {
                    tot[i] += m[(a * d + i, b * d + i)];
                    for j in 0..d {
                        if i != j {
                            assert_eq!(m[(a * d + i, b * d + j)], 0.0);
                        }
                    }
                }
            }
        }
    }
    tot
}

#[test]
fn total_mass_of_quarter_rings_is_rho_times_meshed_volume() {
    let rho = 8.93e-9;
    for (m, cell) in [
        ("3D", CellType::Hexa20),
        ("3D_SI", CellType::Hexa20),
        ("3D", CellType::Penta15),
        ("3D", CellType::Hexa8),
        ("3D", CellType::Penta6),
        ("3D", CellType::Tetra4),
    ] {
        let v = meshed_ring_volume(cell.nnodes() > cell.nvertices());
        let tot = total_mass(&quarter_ring(cell), &spec(m, cell), rho);
        for t in tot {
            assert!(
                (t - rho * v).abs() < 1e-12 * rho * v,
                "{m} {cell:?}: {t} vs {}",
                rho * v
            );
        }
    }
    // Quadratic rings approach the exact ring to the circle's error.
    let v = meshed_ring_volume(true);
    assert!((v / exact_ring_volume() - 1.0).abs() < 1e-4);
}

#[test]
fn axis_mass_is_per_radian() {
    let rho = 8.93e-9;
    // ρ ∫∫ r dr dz = ρ H (RO² − RI²)/2, a quarter ring's mass / (π/2).
    let per_radian = rho * HEIGHT * (RO * RO - RI * RI) / 2.0;
    for (m, cell) in [
        ("AXIS", CellType::Quad8),
        ("AXIS_SI", CellType::Quad8),
        ("AXIS", CellType::Quad4),
        ("AXIS", CellType::Tria6),
        ("AXIS", CellType::Tria3),
    ] {
        let tot = total_mass(&axis_section(cell), &spec(m, cell), rho);
        for t in &tot[..2] {
            assert!(
                (t - per_radian).abs() < 1e-13 * per_radian,
                "{m} {cell:?}: {t}"
            );
        }
        assert!((per_radian * PI / 2.0 - rho * exact_ring_volume()).abs() < 1e-15 * per_radian);
    }
}

/// The explicit step's evaluation (`conjugate_forces`: no tangent, the
/// forces through τF⁻ᵀ, F_n of the previous evaluation kept) on a
/// plastic SIMO_MIEHE step of AXIS_SI QUAD8 and 3D_SI HEXA20: a second
/// step from a buffer that computed the first equals the same step from a
/// fresh buffer to the bit (the kept F_n, det F_n and F_n⁻¹ are the
/// recomputed ones), its states equal the per-dof evaluation's to the bit
/// and its forces within round-off.
#[test]
fn explicit_evaluation_keeps_f_n_to_the_bit() {
    use aster::element::{internal_forces_into, ElementBuffers};
    let copper = simo(soft_ecro());
    let law = LawRef::SimoMiehe(&copper);
    for (m, cell) in [("AXIS_SI", CellType::Quad8), ("3D_SI", CellType::Hexa20)] {
        let s = spec(m, cell);
        let x = distorted_cell(cell);
        let d = s.ndofs() / x.len();
        let field = |scale: f64| -> Vec<f64> {
            (0..s.ndofs())
                .map(|k| scale * (0.02 * ((k % d) as f64 + 1.0) * (0.7 * k as f64).sin()))
                .collect()
        };
        let (u0, u1, u2) = (vec![0.0; s.ndofs()], field(1.0), field(1.6));
        let virgin = initial_states(&s, law);
        let first = run(
            &s,
            Kinematics::SimoMiehe,
            &x,
            &u0,
            &u1,
            &virgin,
            law,
            TangentKind::None,
        );
        assert!(first.states.iter().all(|p| p.internal.as_slice()[1] == 1.0));
        let eval = |buf: &mut ElementBuffers, u_n: &[f64], u: &[f64], st: &[PointState]| {
            internal_forces_into(
                &s,
                Kinematics::SimoMiehe,
                &x,
                u_n,
                u,
                st,
                law,
                1e-6,
                TangentKind::None,
                buf,
            )
            .unwrap();
        };
        let mut kept = ElementBuffers::default();
        kept.conjugate_forces = true;
        eval(&mut kept, &u0, &u1, &virgin);
        assert_eq!(kept.states, first.states, "{m}");
        eval(&mut kept, &u1, &u2, &first.states);
        let mut fresh = ElementBuffers::default();
        fresh.conjugate_forces = true;
        eval(&mut fresh, &u1, &u2, &first.states);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&kept.forces), bits(&fresh.forces), "{m}");
        assert_eq!(kept.states, fresh.states, "{m}");
        let per_dof = run(
            &s,
            Kinematics::SimoMiehe,
            &x,
            &u1,
            &u2,
            &first.states,
            law,
            TangentKind::None,
        );
        assert_eq!(kept.states, per_dof.states, "{m}");
        let scale = per_dof.forces.amax();
        assert!(scale > 0.0);
        for (a, b) in kept.forces.iter().zip(per_dof.forces.iter()) {
            assert!((a - b).abs() <= 1e-12 * scale, "{m}: {a} against {b}");
        }
    }
}
