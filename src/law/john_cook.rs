//! `VMIS_JOHN_COOK`: von Mises plasticity with Johnson–Cook isotropic
//! hardening, small strains (code_aster `lc0054` → `nmtevp`, flow stress
//! `eccook`, residual `nmcri9`; formula-level reading in
//! shared/docs/notes/john-cook-gdef-log.md, Part A).
//!
//! Flow stress, p = p_n + Δp, ṗ = Δp/Δt:
//!   R = (A + B pⁿ) · [1 + C ln(ṗ/ε̇₀)]   (rate factor only when ṗ > ε̇₀)
//! The rate term never softens: below EPSP0 the factor is 1 (code_aster's
//! convention). For p ≤ 1e-9 the flow stress is A + B·(1e-9)ⁿ with no
//! rate factor, which keeps R′ finite at p = 0 (so first yield is at
//! A + 0.47 MPa for copper, not A). No TEMP field exists in aster, so the
//! thermal factor (1 − θᵐ) is always 1, as in code_aster without TEMP.
//!
//! Return mapping: the radial return of VMIS_ISOT_LINE, but the consistency
//! equation f(Δp) = R(p_n, Δp, Δt) + 3μΔp − σ_eq^tr = 0 is non-linear in
//! Δp and is solved by a bracketed scalar method ([`super::root1d`],
//! ALGO_INTE), after code_aster's pre-bracketing (halving Δp₀ =
//! (σ_eq^tr − R_chk)/3μ). The elastic check uses R at (p_n + Δp_{n−1},
//! previous rate), read from V3/V4, as code_aster does.
//!
//! Internal variables (code_aster's names and meanings):
//! V1 EPSPEQ cumulated plastic strain p; V2 INDIPLAS number of scalar
//! solver iterations of a plastic step (0 when elastic; "plastic" means
//! V2 ≥ 0.5); V3 DEPSPEQ Δp of the step; V4 DINSTM Δt of the step; V5
//! DDISSM dissipated power 0.9·σ_eq·Δp/Δt (Taylor–Quinney 0.9; the
//! thermo-elastic part is 0 without TEMP).
//!
//! A step whose root cannot be bracketed or found within ITER_INTE_MAXI
//! iterations is an integration failure ("not converged"): the element
//! reports it and DEFI_LIST_INST cuts the step. A plastic step with Δt ≤ 0
//! is refused (the rate ṗ = Δp/Δt is undefined; code_aster gives NaN).

use super::root1d::{bracket_outward, solve, RootMethod};
use super::voigt::{deviator, deviatoric_projector, double_dot, one_one, trace};
use super::{
    check_small_strain_input, ElasParams, IntegrationFailure, InternalVars, LawMetadata,
    MaterialError, Regime, SmallStrainBehaviour, SmallStrainInput, SmallStrainOutput,
    StrainMeasure, TangentKind, Vec6,
};

pub static METADATA: LawMetadata = LawMetadata {
    name: "VMIS_JOHN_COOK",
    internal_variables: &["EPSPEQ", "INDIPLAS", "DEPSPEQ", "DINSTM", "DDISSM"],
    strain_measures: &[
        StrainMeasure::Petit,
        StrainMeasure::PetitReac,
        StrainMeasure::GrotGdep,
        StrainMeasure::GdefLog,
    ],
    tensor_variables: &[],
};

/// The plastic strain below which the flow stress is frozen (`eccook`).
pub const P_MIN: f64 = 1e-9;

/// The `ECRO_COOK` block, absent optional values already defaulted
/// (C = 0, EPSP0 = 1, M_PUIS = 0, TROOM = −1, TMELT = 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EcroCookParams {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub n: f64,
    pub m: f64,
    pub epsp0: f64,
    pub troom: f64,
    pub tmelt: f64,
}

impl EcroCookParams {
    /// Checks what DEFI_MATERIAU's catalogue checks (A, B, N_PUIS, C,
    /// M_PUIS ≥ 0, EPSP0 > 0) for values built outside a command file.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        a: f64,
        b: f64,
        c: f64,
        n: f64,
        m: f64,
        epsp0: f64,
        troom: f64,
        tmelt: f64,
    ) -> Result<EcroCookParams, MaterialError> {
        for (keyword, v) in [
            ("ECRO_COOK/A", a),
            ("ECRO_COOK/B", b),
            ("ECRO_COOK/C", c),
            ("ECRO_COOK/N_PUIS", n),
            ("ECRO_COOK/M_PUIS", m),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(MaterialError {
                    keyword,
                    message: format!("must be finite and >= 0, got {v}"),
                });
            }
        }
        if !(epsp0.is_finite() && epsp0 > 0.0) {
            return Err(MaterialError {
                keyword: "ECRO_COOK/EPSP0",
                message: format!("must be finite and > 0, got {epsp0}"),
            });
        }
        if !(troom.is_finite() && tmelt.is_finite()) {
            return Err(MaterialError {
                keyword: "ECRO_COOK/TROOM",
                message: "TROOM and TMELT must be finite".into(),
            });
        }
        Ok(EcroCookParams {
            a,
            b,
            c,
            n,
            m,
            epsp0,
            troom,
            tmelt,
        })
    }
}

/// COMPORTEMENT's local integration keywords.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalControls {
    /// ALGO_INTE (BRENT when absent: the first listed for the law).
    pub method: RootMethod,
    /// ITER_INTE_MAXI (default 20).
    pub iter_maxi: usize,
    /// RESI_INTE_RELA (default 1e-6): the tolerance on |f| is this times
    /// the flow stress at the first estimate Δp₀.
    pub resi_rela: f64,
}

impl Default for LocalControls {
    fn default() -> Self {
        LocalControls {
            method: RootMethod::Brent,
            iter_maxi: 20,
            resi_rela: 1e-6,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VmisJohnCook {
    pub elas: ElasParams,
    pub ecro: EcroCookParams,
    pub controls: LocalControls,
    mu: f64,
    bulk: f64,
}

impl VmisJohnCook {
    pub fn new(elas: ElasParams, ecro: EcroCookParams, controls: LocalControls) -> VmisJohnCook {
        VmisJohnCook {
            elas,
            ecro,
            controls,
            mu: elas.mu(),
            bulk: elas.bulk(),
        }
    }

    /// Static hardening A + B pⁿ (p > 1e-9).
    pub fn static_flow_stress(&self, p: f64) -> f64 {
        self.ecro.a + self.ecro.b * p.max(P_MIN).powf(self.ecro.n)
    }

    /// Flow stress R and R′ = ∂R/∂Δp at p_n + Δp with rate Δp/Δt
    /// (code_aster's `eccook`, without the thermal factor: no TEMP).
    pub fn flow_stress(&self, p_n: f64, dp: f64, dt: f64) -> (f64, f64) {
        let EcroCookParams { a, b, c, n, .. } = self.ecro;
        let p = p_n + dp;
        if p <= P_MIN {
            let r = a + b * P_MIN.powf(n);
            return (r, n * b * P_MIN.powf(n - 1.0));
        }
        let r0 = a + b * p.powf(n);
        let r0p = n * b * p.powf(n - 1.0);
        let rate = if dt > 0.0 { dp / dt } else { 0.0 };
        if rate > self.ecro.epsp0 {
            let l = (rate / self.ecro.epsp0).ln();
            (r0 * (1.0 + c * l), r0p * (1.0 + c * l) + c * r0 / dp)
        } else {
            (r0, r0p)
        }
    }

    /// The elastic-check threshold: R at p_n + Δp_{n−1} with the previous
    /// step's rate (V3/V4), as `nmtevp` evaluates it.
    fn check_threshold(&self, internal: &[f64]) -> (f64, f64) {
        self.flow_stress(internal[0], internal[2], internal[3])
    }

    fn failure(&self, message: impl std::fmt::Display) -> IntegrationFailure {
        IntegrationFailure::not_converged(METADATA.name, message)
    }

    /// Δp and the iteration count of a plastic step (code_aster's
    /// pre-bracketing, then the chosen scalar method).
    fn solve_dp(
        &self,
        p_n: f64,
        q_tr: f64,
        r_chk: f64,
        dt: f64,
    ) -> Result<(f64, usize), IntegrationFailure> {
        let mu3 = 3.0 * self.mu;
        let ctl = self.controls;
        let mut f = |dp: f64| self.flow_stress(p_n, dp, dt).0 + mu3 * dp - q_tr;
        let dp0 = (q_tr - r_chk) / mu3;
        let sigma_y0 = self.flow_stress(p_n, dp0, dt).0;
        let tol = ctl.resi_rela * sigma_y0;
        if sigma_y0.abs() <= tol {
            return Ok((dp0, 1));
        }
        // Halve Δp₀ until the residual changes sign (or is small enough).
        let mut dp_max = dp0;
        for i in 1..=ctl.iter_maxi {
            let trial = dp0 / 2f64.powi(i as i32);
            let ft = f(trial);
            if !ft.is_finite() {
                return Err(self.failure(format!("non-finite residual at dp = {trial:e}")));
            }
            dp_max = trial;
            if ft.abs() <= tol {
                return Ok((trial, i));
            }
            if ft < 0.0 {
                dp_max = 2.0 * trial;
                break;
            }
        }
        let bracket =
            bracket_outward(&mut f, 0.0, dp_max, ctl.iter_maxi).map_err(|e| self.failure(e))?;
        let root = solve(ctl.method, &mut f, bracket, tol, ctl.iter_maxi).map_err(|e| {
            self.failure(format!(
                "{e} in {} iterations (ALGO_INTE='{}', ITER_INTE_MAXI)",
                ctl.iter_maxi,
                ctl.method.aster_name()
            ))
        })?;
        if root.x.is_nan() || root.x < 0.0 {
            return Err(self.failure(format!("negative plastic increment {:e}", root.x)));
        }
        Ok((root.x, root.iterations.max(1)))
    }
}

impl SmallStrainBehaviour for VmisJohnCook {
    fn metadata(&self) -> &'static LawMetadata {
        &METADATA
    }

    /// HEXS8's hourglass projection reads ν (element::hexs8).
    fn elastic_params(&self) -> Option<ElasParams> {
        Some(self.elas)
    }

    fn integrate(&self, input: &SmallStrainInput) -> Result<SmallStrainOutput, IntegrationFailure> {
        check_small_strain_input(&METADATA, input)?;
        let v = input.internal;
        if v[0] < 0.0 || v[2] < 0.0 || v[3] < 0.0 {
            return Err(IntegrationFailure::invalid(
                METADATA.name,
                format!(
                    "invalid internal variables V1 = {}, V3 = {}, V4 = {}",
                    v[0], v[2], v[3]
                ),
            ));
        }
        let (mu, k) = (self.mu, self.bulk);
        let dt = input.dt;
        let de = input.strain_increment;
        let dev_de = deviatoric_projector() * de;
        let s_tr = deviator(&input.stress) + dev_de * (2.0 * mu);
        let sigma_m = trace(&input.stress) / 3.0 + k * trace(&de);
        let hydro = Vec6::new(sigma_m, sigma_m, sigma_m, 0.0, 0.0, 0.0);
        let q_tr = (1.5 * double_dot(&s_tr, &s_tr)).sqrt();
        let p_n = v[0];
        let (r_chk, _) = self.check_threshold(v);
        let mut internal = InternalVars::zeros(METADATA.internal_variables.len());
        let elastic_d = one_one() * k + deviatoric_projector() * (2.0 * mu);
        // Δt = 0 is an evaluation of the state, not a step: the limit of
        // the update as Δt → 0 is elastic (the rate factor, hence R, grows
        // without bound for any Δp > 0), which is what is returned. code_aster
        // gives NaN there (note A.3); the zero-increment evaluations of a
        // restart and of CALC_CHAMP FORC_NODA rely on this.
        if q_tr - r_chk <= 0.0 || dt == 0.0 {
            let iv = internal.as_mut_slice();
            iv[0] = p_n;
            iv[3] = dt;
            return Ok(SmallStrainOutput {
                stress: s_tr + hydro,
                internal,
                tangent: match input.tangent {
                    TangentKind::None => None,
                    _ => Some(elastic_d),
                },
                regime: Regime::Elastic,
            });
        }
        let (dp, iterations) = self.solve_dp(p_n, q_tr, r_chk, dt)?;
        let (r, rp) = self.flow_stress(p_n, dp, dt);
        let theta = r / (r + 3.0 * mu * dp);
        let s = s_tr * theta;
        let q = (1.5 * double_dot(&s, &s)).sqrt();
        {
            let iv = internal.as_mut_slice();
            iv[0] = p_n + dp;
            iv[1] = iterations as f64;
            iv[2] = dp;
            iv[3] = dt;
            iv[4] = 0.9 * q * dp / dt;
        }
        let tangent = match input.tangent {
            TangentKind::None => None,
            TangentKind::Elastic => Some(elastic_d),
            TangentKind::Consistent => {
                // code_aster applies the plastic branch when s:Δe ≥ 0
                // (loading); otherwise the secant-elastic part alone.
                let loading = double_dot(&s, &dev_de) >= 0.0;
                let norm = double_dot(&s_tr, &s_tr).sqrt();
                let mut d = one_one() * k + deviatoric_projector() * (2.0 * mu * theta);
                if loading && norm > 0.0 {
                    // D = K 1⊗1 + 2μθ I_dev − 2μθ̄ n⊗n with
                    // θ̄ = 3μ/(3μ + R′) − 3μΔp/(R + 3μΔp): the exact
                    // derivative of the update, rate term included in R′.
                    let n = s_tr / norm;
                    let theta_bar = 3.0 * mu / (3.0 * mu + rp) - (1.0 - theta);
                    d -= n * n.transpose() * (2.0 * mu * theta_bar);
                }
                Some(d)
            }
        };
        Ok(SmallStrainOutput {
            stress: s + hydro,
            internal,
            tangent,
            regime: Regime::Plastic,
        })
    }
}
