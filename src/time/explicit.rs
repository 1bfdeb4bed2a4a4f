//! Building blocks of explicit dynamics (DIFF_CENT, TCHAMWA): the two
//! schemes' coefficients, the lumped mass and a sound critical step. The
//! time loop that uses them is `nonlinear::explicit`.
//!
//! Lumped mass: HRZ diagonal scaling (Hinton, Rock & Zienkiewicz 1976).
//! Why not row sums: on quadratic elements the rows of the consistent mass
//! of the corner nodes sum to a negative number (QUAD8: −1/12 of the
//! element mass at each corner, HEXA20: −1/8), and a negative or zero mass
//! makes the central-difference update meaningless. HRZ keeps the diagonal
//! of the consistent mass, which is positive for any element (m_aa =
//! ∫ρN_a² dV > 0), and scales it per direction so that the element's total
//! mass is preserved: m_a = M_aa · M_e / Σ_b M_bb. The total mass, hence
//! the rigid-body momentum, is exact.
//!
//! Critical step: code_aster's estimate d_min/(2 c_bar) (notes/explicit.md
//! §7) lets through steps about twice the true limit on quadratic elements.
//! The bound used here is the element eigenvalue inequality (Irons; Hughes
//! 1987 §9.3): the largest eigenvalue of the assembled M⁻¹K with the
//! assembled lumped mass is at most the largest over the elements of the
//! element M_e⁻¹K_e, so Δt_crit = 2/ω_max,e is a lower bound of the true
//! central-difference limit on every mesh. ω_max,e comes from power
//! iteration on the symmetric D^{-1/2} K_e D^{-1/2} (D the lumped diagonal).

use nalgebra::{DMatrix, DVector, SymmetricEigen};

/// An explicit scheme of code_aster's acceleration formulation
/// (notes/explicit.md §3): both predict u_{n+1} = u_n + Δt v_n + c Δt² a_n
/// and solve M a_{n+1} = r(u_{n+1}).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ExplicitScheme {
    /// DIFF_CENT: c = ½, v* = v_n + ½Δt a_n, then v_{n+1} = v* + ½Δt a_{n+1}
    /// (Newmark β = 0, γ = ½: the leapfrog scheme).
    DiffCent,
    /// TCHAMWA(PHI): c = φ, v_{n+1} = v_n + Δt a_n, no velocity correction
    /// (a_{n+1} first enters v_{n+2}); first order and dissipative for φ > 1.
    Tchamwa { phi: f64 },
}

impl ExplicitScheme {
    /// c of the displacement predictor u_n + Δt v_n + c Δt² a_n.
    pub fn displacement_coefficient(&self) -> f64 {
        match self {
            ExplicitScheme::DiffCent => 0.5,
            ExplicitScheme::Tchamwa { phi } => *phi,
        }
    }

    /// The weight w of the step's end in the velocity update
    /// v_{n+1} − v_n = Δt((1 − w) a_n + w a_{n+1}): ½ for DIFF_CENT, 0 for
    /// TCHAMWA (a_{n+1} first enters v_{n+2}). The impulse of a force over
    /// a step is Δt((1 − w) f_n + w f_{n+1}), so that it equals the
    /// momentum the force changes.
    pub fn end_weight(&self) -> f64 {
        match self {
            ExplicitScheme::DiffCent => 0.5,
            ExplicitScheme::Tchamwa { .. } => 0.0,
        }
    }

    /// The factor f of the critical step f·2/ω_max. For DIFF_CENT 1. For
    /// TCHAMWA the exact single-dof limit Ω ≤ 2/√(2φ−1) (notes/explicit.md
    /// §3.2, the amplification matrix [[1−φΩ², 1], [−Ω², 1]]); code_aster
    /// divides by φ instead, which is more conservative but not the limit.
    /// None for φ < 1: the scheme is unstable at every step (the
    /// determinant 1 − (φ−1)Ω² exceeds 1).
    pub fn stability_factor(&self) -> Option<f64> {
        match self {
            ExplicitScheme::DiffCent => Some(1.0),
            ExplicitScheme::Tchamwa { phi } if *phi >= 1.0 => Some(1.0 / (2.0 * phi - 1.0).sqrt()),
            ExplicitScheme::Tchamwa { .. } => None,
        }
    }

    /// code_aster's name of the scheme.
    pub fn name(&self) -> &'static str {
        match self {
            ExplicitScheme::DiffCent => "DIFF_CENT",
            ExplicitScheme::Tchamwa { .. } => "TCHAMWA",
        }
    }
}

/// The factor √(1 + ξ²) − ξ by which a viscous damping ratio ξ of the
/// mode ω lowers its critical step 2/ω (Belytschko, Liu and Moran, Box
/// 6.1). Exact for DIFF_CENT with the damping force at the predicted
/// v_{n+½} = v_n + ½Δt a_n, code_aster's v*; on the safe side for TCHAMWA
/// with its factor 1/√(2φ−1) (`damped_critical_step_against_the_amplification_matrix`).
/// For Rayleigh damping ξ = (α ω + β/ω)/2, and the step limit
/// 2/(√(ω² + (ωξ)²) + ωξ) decreases with ω, so the elements' upper bound
/// of ω keeps the bound a bound.
pub fn damped_step_factor(xi: f64) -> f64 {
    (1.0 + xi * xi).sqrt() - xi
}

/// The largest ω² of K x = ω² M x for a symmetric positive definite
/// element mass `m` (consistent) and a stiffness `k` (symmetrised here:
/// a finite-strain tangent may be slightly unsymmetric), by the
/// symmetric eigenvalues of L⁻¹ K L⁻ᵀ with M = L Lᵀ. None when M is not
/// positive definite.
pub fn max_eigenvalue_consistent(k: &DMatrix<f64>, m: &DMatrix<f64>) -> Option<f64> {
    let l = m.clone().cholesky()?.l();
    let ks = (k + k.transpose()) * 0.5;
    let linv = l.clone().try_inverse()?;
    let a = &linv * ks * linv.transpose();
    let a = (&a + a.transpose()) * 0.5;
    Some(SymmetricEigen::new(a).eigenvalues.max().max(0.0))
}

/// An upper estimate of the largest eigenvalue of the symmetric `a` by
/// power iteration from `x` (the top eigenvector of a nearby matrix: the
/// run's previous estimate, updated in place): the Rayleigh quotient ρ plus
/// the residual norm |a x − ρ x| (|x| = 1), which bounds the distance from
/// ρ to an eigenvalue, so ρ + |r| is at or above the top eigenvalue once x
/// is nearest the top eigenvector, as it is from a warm start. Falls back
/// to the full symmetric eigen-decomposition when the iteration does not
/// settle to `tol` in 50 steps.
pub fn max_eigenvalue_warm(a: &DMatrix<f64>, x: &mut DVector<f64>, tol: f64) -> f64 {
    let n = a.nrows();
    if x.len() != n || x.norm() == 0.0 {
        *x = DVector::from_element(n, 1.0);
    }
    let mut y = DVector::zeros(n);
    for _ in 0..50 {
        let nx = x.norm();
        *x /= nx;
        a.mul_to(x, &mut y);
        let rho = x.dot(&y);
        let r = (&y - &*x * rho).norm();
        if rho > 0.0 && r <= tol * rho {
            return rho + r;
        }
        std::mem::swap(x, &mut y);
    }
    let (top, v) = top_eigenpair(a);
    *x = v;
    top
}

/// The matrix D^{-1/2} K D^{-1/2} (symmetrised) whose eigenvalues are the
/// ω² of K x = ω² D x.
pub fn scaled_lumped(k: &DMatrix<f64>, lumped: &[f64]) -> DMatrix<f64> {
    let n = k.nrows();
    let s: Vec<f64> = lumped.iter().map(|m| 1.0 / m.sqrt()).collect();
    DMatrix::from_fn(n, n, |i, j| 0.5 * s[i] * (k[(i, j)] + k[(j, i)]) * s[j])
}

/// The largest ω² of K x = ω² D x for the diagonal D = diag(`lumped`), by
/// the symmetric eigenvalues of D^{-1/2} K D^{-1/2} (a direct method: the
/// power iteration of [`max_eigenvalue`] converges slowly when the top two
/// modes are close, and the run re-estimates the step many times).
pub fn max_eigenvalue_lumped(k: &DMatrix<f64>, lumped: &[f64]) -> f64 {
    let n = k.nrows();
    let s: Vec<f64> = lumped.iter().map(|m| 1.0 / m.sqrt()).collect();
    let a = DMatrix::from_fn(n, n, |i, j| 0.5 * s[i] * (k[(i, j)] + k[(j, i)]) * s[j]);
    SymmetricEigen::new(a).eigenvalues.max().max(0.0)
}

/// The largest eigenvalue of the symmetric `a` and its unit eigenvector,
/// by the full decomposition: the vector is the warm start of the run's
/// later estimates ([`max_eigenvalue_warm`]). A warm start that is another
/// mode's eigenvector stays on that mode (the top one is absent from it
/// in exact arithmetic, and the residual test passes at once), so the
/// start must be the top mode itself: power iteration from a fixed vector
/// may converge to a lower mode when the fixed vector is orthogonal to the
/// top one (it is, on PENTA15 cells made by LINE_QUAD: the run then took
/// steps 1.28 times its own bound and blew up).
pub fn top_eigenpair(a: &DMatrix<f64>) -> (f64, DVector<f64>) {
    let e = SymmetricEigen::new(a.clone());
    let (k, top) = e
        .eigenvalues
        .iter()
        .enumerate()
        .fold(
            (0, f64::NEG_INFINITY),
            |acc, (i, &v)| if v > acc.1 { (i, v) } else { acc },
        );
    (top.max(0.0), e.eigenvectors.column(k).into_owned())
}

/// The range of the kinetic energy a node of mass m leaves with, over the
/// energy it arrives with, when it bounces off a penalty spring k alone
/// under central differences at `wdt` = ω dt, ω² = k/m (`wdt` < 2): the
/// force is switched on at the first step end that penetrates, at a
/// depth anywhere in (0, v dt], and off at the first that does not. The
/// range over that entry depth (1000 depths) is the energy a penalised
/// contact can create or destroy at one closing: exactly 1 at ω dt = 1
/// (u = p, 1, 1 − p, −p, then speed 1), within ±1 % at ω dt = 0.2, ±4.5 %
/// at 0.5, 0.49 to 2.06 at 1.56 (tests in this module).
pub fn penalty_rebound_range(wdt: f64) -> (f64, f64) {
    let w2 = wdt * wdt;
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for i in 1..=1000 {
        // Penetration u (dt = 1, inbound speed 1): u_0 ≤ 0 < u_1 = p.
        let p = i as f64 / 1000.0;
        let (mut a, mut b) = (p - 1.0, p);
        for _ in 0..10_000 {
            let c = 2.0 * b - a - w2 * b.max(0.0);
            a = b;
            b = c;
            if a < 0.0 && b < a {
                break;
            }
        }
        let ratio = (b - a) * (b - a);
        lo = lo.min(ratio);
        hi = hi.max(ratio);
    }
    (lo, hi)
}

/// HRZ lumped mass of an element (`element::mechanics::hrz_lumped`, next
/// to the consistent mass, where PESANTEUR's lumped load reads it too).
pub use crate::element::mechanics::hrz_lumped;

/// The largest ω² of K_e x = ω² D x (D = diag(`lumped`), K_e symmetric
/// positive semi-definite) by power iteration on D^{-1/2} K_e D^{-1/2},
/// to a relative tolerance `tol`.
pub fn max_eigenvalue(k: &DMatrix<f64>, lumped: &[f64], tol: f64) -> f64 {
    let n = k.nrows();
    let s: Vec<f64> = lumped.iter().map(|m| 1.0 / m.sqrt()).collect();
    let a = DMatrix::from_fn(n, n, |i, j| s[i] * k[(i, j)] * s[j]);
    // A start vector with every component nonzero and alternating signs:
    // the highest mode of a mesh alternates.
    let mut x = DVector::from_fn(
        n,
        |i, _| if i % 2 == 0 { 1.0 } else { -1.3 } + 0.01 * i as f64,
    );
    let mut lambda = 0.0;
    for _ in 0..10_000 {
        let y = &a * &x;
        let norm = y.norm();
        if norm == 0.0 {
            return 0.0;
        }
        let next = x.dot(&y) / x.dot(&x);
        x = y / norm;
        if (next - lambda).abs() <= tol * next.abs() {
            return next;
        }
        lambda = next;
    }
    lambda
}

/// Central-difference critical step of one element, 2/ω_max (∞ for an
/// element without stiffness).
pub fn critical_step(k: &DMatrix<f64>, lumped: &[f64]) -> f64 {
    let w2 = max_eigenvalue(k, lumped, 1e-10);
    if w2 > 0.0 {
        2.0 / w2.sqrt()
    } else {
        f64::INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The single-node rebound off a penalty spring against the same
    /// recurrence in numpy (u_{n+1} = 2u_n − u_{n−1} − (ω dt)² max(u_n, 0), 1000 entry
    /// depths: 0.9913 .. 1.0088 at ω dt = 0.2, 0.9570 .. 1.0449 at 0.5,
    /// 0.4874 .. 2.0552 at 1.56) and the hand value at ω dt = 1 (the
    /// penetrations p, 1, 1 − p, −p: out at the speed it came in).
    #[test]
    fn penalty_rebound_range_against_the_recurrence() {
        let (lo, hi) = penalty_rebound_range(1.0);
        assert!(
            (lo - 1.0).abs() < 1e-12 && (hi - 1.0).abs() < 1e-12,
            "{lo} {hi}"
        );
        for (wdt, lo0, hi0) in [
            (0.2, 0.9913, 1.0088),
            (0.5, 0.9570, 1.0449),
            (1.56, 0.4874, 2.0552),
        ] {
            let (lo, hi) = penalty_rebound_range(wdt);
            assert!(
                (lo - lo0).abs() < 2e-3 && (hi - hi0).abs() < 2e-3,
                "{wdt}: {lo} {hi}"
            );
        }
    }
    /// The 1-dof step m a + c v* + k u = 0 of each scheme as the explicit
    /// loop takes it (u predicted, a solved with the damping force of the
    /// predicted velocity v*, then v), written out on (u, v, a): its
    /// spectral radius is at most 1 at the damped bound (DIFF_CENT: and
    /// above 1 just past it, the bound is the limit) for ξ from 0 to 2.
    #[test]
    fn damped_critical_step_against_the_amplification_matrix() {
        let radius = |scheme: ExplicitScheme, xi: f64, h: f64| {
            let (w, m) = (1.0, 1.0);
            let (k, c) = (w * w * m, 2.0 * xi * w * m);
            let mut a = nalgebra::Matrix3::<f64>::zeros();
            for j in 0..3 {
                let mut s = [0.0; 3];
                s[j] = 1.0;
                let [u0, v0, a0] = s;
                let p = scheme.displacement_coefficient();
                let u1 = u0 + h * v0 + p * h * h * a0;
                let (vs, after) = match scheme {
                    ExplicitScheme::DiffCent => (v0 + 0.5 * h * a0, 0.5 * h),
                    ExplicitScheme::Tchamwa { .. } => (v0 + h * a0, 0.0),
                };
                let a1 = -(c * vs + k * u1) / m;
                let col = [u1, vs + after * a1, a1];
                for i in 0..3 {
                    a[(i, j)] = col[i];
                }
            }
            a.complex_eigenvalues()
                .iter()
                .map(|z| z.norm())
                .fold(0.0, f64::max)
        };
        for xi in [0.0, 0.05, 0.2, 0.5, 1.0, 2.0] {
            for scheme in [
                ExplicitScheme::DiffCent,
                ExplicitScheme::Tchamwa { phi: 1.05 },
                ExplicitScheme::Tchamwa { phi: 1.3 },
            ] {
                let bound = scheme.stability_factor().unwrap() * 2.0 * damped_step_factor(xi);
                let r = radius(scheme, xi, bound * (1.0 - 1e-7));
                assert!(r <= 1.0 + 1e-9, "{scheme:?} xi {xi}: {r} at the bound");
                if scheme == ExplicitScheme::DiffCent {
                    let r = radius(scheme, xi, bound * (1.0 + 1e-4));
                    assert!(r > 1.0 + 1e-6, "xi {xi}: {r} past the bound");
                }
            }
        }
    }

    use crate::element::mechanics::mass;
    use crate::mesh::CellType;
    use crate::model::spec::element_spec;

    /// 2-node bar, stiffness EA/L, lumped ρAL/2: ω_max = 2c/L, Δt = L/c.
    #[test]
    fn two_node_bar_critical_step_is_l_over_c() {
        let (e, rho, a, l) = (2.0e5, 7.8e-9, 3.0, 0.5);
        let k = DMatrix::from_row_slice(2, 2, &[1.0, -1.0, -1.0, 1.0]) * (e * a / l);
        let mc = DMatrix::from_row_slice(2, 2, &[2.0, 1.0, 1.0, 2.0]) * (rho * a * l / 6.0);
        let m = hrz_lumped(&mc, 1).unwrap();
        assert!((m[0] - rho * a * l / 2.0).abs() < 1e-12 * rho * a * l);
        let dt = critical_step(&k, &m);
        let c = (e / rho).sqrt();
        assert!((dt - l / c).abs() < 1e-9 * l / c, "{dt} vs {}", l / c);
    }

    /// 3-node bar: HRZ gives (1/6, 2/3, 1/6)·ρAL and the limit is exactly
    /// L/(c√6) (notes/explicit.md §7).
    #[test]
    fn three_node_bar_hrz_masses_and_critical_step() {
        let (e, rho, a, l) = (1.0, 1.0, 1.0, 1.0);
        let k = DMatrix::from_row_slice(3, 3, &[7.0, -8.0, 1.0, -8.0, 16.0, -8.0, 1.0, -8.0, 7.0])
            * (e * a / (3.0 * l));
        let mc = DMatrix::from_row_slice(3, 3, &[4.0, 2.0, -1.0, 2.0, 16.0, 2.0, -1.0, 2.0, 4.0])
            * (rho * a * l / 30.0);
        let m = hrz_lumped(&mc, 1).unwrap();
        for (got, want) in m.iter().zip([1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0]) {
            assert!((got - want).abs() < 1e-14, "{m:?}");
        }
        let dt = critical_step(&k, &m);
        let want = l / (e / rho).sqrt() / 6f64.sqrt();
        assert!((dt - want).abs() < 1e-8 * want, "{dt} vs {want}");
    }

    /// AXIS QUAD8 far from the axis (r in [1000, 1002], so nearly a
    /// plane element): the consistent mass's corner rows sum to about
    /// −1/12 of the element mass (row-sum lumping would give negative
    /// masses); HRZ is positive everywhere, keeps the element mass
    /// ρ·A·r_c (per radian) exactly in each direction, and gives the
    /// classical QUAD8 HRZ split (Hinton, Rock & Zienkiewicz), corners
    /// 3/76 and mid-sides 16/76.
    #[test]
    fn quad8_hrz_is_positive_where_row_sums_are_negative() {
        let spec = element_spec("AXIS", CellType::Quad8).unwrap();
        let r0 = 1000.0;
        let coords = [
            [r0, 0.0, 0.0],
            [r0 + 2.0, 0.0, 0.0],
            [r0 + 2.0, 1.0, 0.0],
            [r0, 1.0, 0.0],
            [r0 + 1.0, 0.0, 0.0],
            [r0 + 2.0, 0.5, 0.0],
            [r0 + 1.0, 1.0, 0.0],
            [r0, 0.5, 0.0],
        ];
        let rho = 3.0;
        let me = rho * 2.0 * (r0 + 1.0);
        let mc = mass(&spec, &coords, rho).unwrap();
        let row0: f64 = (0..mc.ncols()).map(|j| mc[(0, j)]).sum();
        assert!((row0 / me + 1.0 / 12.0).abs() < 1e-3, "{}", row0 / me);
        let m = hrz_lumped(&mc, 2).unwrap();
        assert!(m.iter().all(|&x| x > 0.0), "{m:?}");
        for i in 0..2 {
            let total: f64 = m.iter().skip(i).step_by(2).sum();
            assert!((total - me).abs() < 1e-10 * me, "{total} vs {me}");
        }
        assert!((m[0] / me - 3.0 / 76.0).abs() < 1e-3, "{m:?}");
        assert!((m[8] / me - 16.0 / 76.0).abs() < 1e-3, "{m:?}");
    }
}
