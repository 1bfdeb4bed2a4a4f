//! Axisymmetric QUAD8 (AXIS / AXIS_SI): patch test on a distorted patch
//! touching the axis, resultant forces against hand-computed tractions,
//! stiffness against finite differences, mass against the exact integral.

use std::collections::HashMap;

use aster::element::axis::{
    internal_forces, mass, AxisModelisation, ElemVec, ElementFailure, PointState, NODES,
};
use aster::law::elas::Elas;
use aster::law::vmis_isot_line::VmisIsotLine;
use aster::law::{EcroLineParams, ElasParams, SmallStrainBehaviour, TangentKind, Vec6};
use aster::mesh::quadrature::rule;
use aster::mesh::CellType;

const MODELS: [AxisModelisation; 2] = [AxisModelisation::Axis, AxisModelisation::AxisSi];

/// QUAD8 with straight edges: mid nodes at edge midpoints, MED order.
fn quad8(c: [[f64; 2]; 4]) -> [[f64; 2]; NODES] {
    let mid = |a: [f64; 2], b: [f64; 2]| [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
    [
        c[0],
        c[1],
        c[2],
        c[3],
        mid(c[0], c[1]),
        mid(c[1], c[2]),
        mid(c[2], c[3]),
        mid(c[3], c[0]),
    ]
}

/// A 2×2 patch on [0,2]×[0,2] (r, z) with the centre vertex moved.
fn patch() -> Vec<[[f64; 2]; NODES]> {
    let p = |i: usize, j: usize| {
        if (i, j) == (1, 1) {
            [1.15, 0.85]
        } else {
            [i as f64, j as f64]
        }
    };
    let mut cells = Vec::new();
    for i in 0..2 {
        for j in 0..2 {
            cells.push(quad8([p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)]));
        }
    }
    cells
}

fn key(x: [f64; 2]) -> (i64, i64) {
    ((x[0] * 1e9).round() as i64, (x[1] * 1e9).round() as i64)
}

fn elas() -> Elas {
    Elas::new(ElasParams::new(117_000.0, 0.35, Some(8.93e-9)).unwrap())
}

fn virgin(law: &dyn SmallStrainBehaviour, n: usize) -> Vec<PointState> {
    vec![
        PointState {
            stress: Vec6::zeros(),
            internal: law.initial_internal(),
        };
        n
    ]
}

#[test]
fn patch_test_uniform_strain_on_distorted_patch() {
    let (a, b) = (1e-4, -2e-4);
    let law = elas();
    let sigma = law.stiffness() * Vec6::new(a, b, a, 0.0, 0.0, 0.0);
    for model in MODELS {
        let npg = rule(CellType::Quad8, model.rigi()).unwrap().len();
        let mut global: HashMap<(i64, i64), ([f64; 2], [f64; 2])> = HashMap::new();
        for cell in patch() {
            let mut du = ElemVec::zeros();
            for (k, x) in cell.iter().enumerate() {
                du[2 * k] = a * x[0];
                du[2 * k + 1] = b * x[1];
            }
            let out = internal_forces(
                model,
                &cell,
                &du,
                &virgin(&law, npg),
                &law,
                0.0,
                TangentKind::Consistent,
            )
            .unwrap();
            for st in &out.states {
                assert!(
                    (st.stress - sigma).norm() < 1e-10 * sigma.norm(),
                    "{model:?}"
                );
            }
            // Linear element: K u = f.
            let ku = out.stiffness.unwrap() * du;
            assert!((ku - out.forces).norm() < 1e-10 * out.forces.norm());
            for (k, x) in cell.iter().enumerate() {
                let e = global.entry(key(*x)).or_insert((*x, [0.0; 2]));
                e.1[0] += out.forces[2 * k];
                e.1[1] += out.forces[2 * k + 1];
            }
        }
        assert_eq!(global.len(), 21);
        let scale = sigma.norm();
        let (mut top, mut bottom, mut outer) = (0.0, 0.0, 0.0);
        for (x, f) in global.values() {
            let boundary_z = x[1] == 0.0 || x[1] == 2.0;
            let outer_r = x[0] == 2.0;
            if !boundary_z && !outer_r {
                // interior nodes and nodes on the axis: no force
                assert!(
                    f[0].abs() < 1e-12 * scale && f[1].abs() < 1e-12 * scale,
                    "{model:?} {x:?}: {f:?}"
                );
            }
            if x[1] == 2.0 {
                top += f[1];
            }
            if x[1] == 0.0 {
                bottom += f[1];
            }
            if outer_r {
                outer += f[0];
            }
        }
        // Per radian: top face ∫₀² σ_zz r dr = 2σ_zz; outer face ∫₀² σ_rr R dz = 4σ_rr.
        assert!(
            (top - 2.0 * sigma[1]).abs() < 1e-12 * scale,
            "{model:?} top {top}"
        );
        assert!((bottom + 2.0 * sigma[1]).abs() < 1e-12 * scale);
        assert!(
            (outer - 4.0 * sigma[0]).abs() < 1e-12 * scale,
            "{model:?} outer {outer}"
        );
    }
}

#[test]
fn stiffness_equals_finite_differences_of_internal_forces_when_plastic() {
    let el = ElasParams::new(200_000.0, 0.3, None).unwrap();
    let law = VmisIsotLine::new(el, EcroLineParams::new(&el, 250.0, 20_000.0).unwrap());
    let cell = quad8([[1.0, 0.0], [2.2, 0.1], [2.0, 1.3], [0.9, 1.0]]);
    for model in MODELS {
        let npg = rule(CellType::Quad8, model.rigi()).unwrap().len();
        let mut u1 = ElemVec::zeros();
        for (k, x) in cell.iter().enumerate() {
            u1[2 * k] = 4e-3 * x[0] + 1e-3 * x[1] * x[1];
            u1[2 * k + 1] = -3e-3 * x[1] + 2e-3 * x[0];
        }
        let s1 = internal_forces(
            model,
            &cell,
            &u1,
            &virgin(&law, npg),
            &law,
            0.0,
            TangentKind::None,
        )
        .unwrap()
        .states;
        let du = u1 * 0.3;
        let out =
            internal_forces(model, &cell, &du, &s1, &law, 0.0, TangentKind::Consistent).unwrap();
        assert!(
            out.states.iter().all(|s| s.internal.as_slice()[1] == 1.0),
            "all points plastic"
        );
        let k = out.stiffness.unwrap();
        let h = 1e-9;
        let mut err: f64 = 0.0;
        for j in 0..16 {
            let mut p = du;
            let mut m = du;
            p[j] += h;
            m[j] -= h;
            let fp = internal_forces(model, &cell, &p, &s1, &law, 0.0, TangentKind::None)
                .unwrap()
                .forces;
            let fm = internal_forces(model, &cell, &m, &s1, &law, 0.0, TangentKind::None)
                .unwrap()
                .forces;
            let col = (fp - fm) / (2.0 * h);
            err = err.max((col - k.column(j)).norm());
        }
        assert!(err < 1e-6 * k.norm(), "{model:?}: {err} vs {}", k.norm());
    }
}

#[test]
fn consistent_mass_integrates_rho_r_over_the_patch() {
    let rho = 8.93e-9;
    let mut total_r = 0.0;
    let mut total_z = 0.0;
    for cell in patch() {
        let m = mass(AxisModelisation::AxisSi, &cell, rho).unwrap();
        assert!((m - m.transpose()).norm() < 1e-14 * m.norm());
        for a in 0..NODES {
            for b in 0..NODES {
                total_r += m[(2 * a, 2 * b)];
                total_z += m[(2 * a + 1, 2 * b + 1)];
                assert_eq!(m[(2 * a, 2 * b + 1)], 0.0);
            }
        }
    }
    // ρ ∫₀² ∫₀² r dr dz = 4ρ per radian.
    assert!((total_r - 4.0 * rho).abs() < 1e-13 * rho);
    assert!((total_z - 4.0 * rho).abs() < 1e-13 * rho);
}

#[test]
fn inverted_cells_and_cells_across_the_axis_are_errors() {
    let law = elas();
    let flipped = quad8([[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]]);
    let err = internal_forces(
        AxisModelisation::Axis,
        &flipped,
        &ElemVec::zeros(),
        &virgin(&law, 9),
        &law,
        0.0,
        TangentKind::None,
    )
    .unwrap_err();
    assert!(matches!(err, ElementFailure::BadGeometry { .. }), "{err:?}");
    let across = quad8([[-1.0, 0.0], [1.0, 0.0], [1.0, 1.0], [-1.0, 1.0]]);
    let err = mass(AxisModelisation::Axis, &across, 1.0).unwrap_err();
    assert!(matches!(err, ElementFailure::BadGeometry { .. }));
    // Wrong number of states is refused too.
    let ok = quad8([[1.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0]]);
    assert!(matches!(
        internal_forces(
            AxisModelisation::AxisSi,
            &ok,
            &ElemVec::zeros(),
            &virgin(&law, 9),
            &law,
            0.0,
            TangentKind::None
        ),
        Err(ElementFailure::StateCount {
            expected: 4,
            got: 9
        })
    ));
}
