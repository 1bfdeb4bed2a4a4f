//! Implicit time integration: the Newmark family and HHT, in code_aster's
//! displacement formulation.
//!
//! All schemes are parameter sets of one implementation, as in MFEM's
//! generalized-alpha family:
//! - NEWMARK(BETA, GAMMA): equilibrium at t_{n+1};
//! - HHT with MODI_EQUI='NON': Newmark with beta = (1-alpha)^2/4 and
//!   gamma = 1/2 - alpha, equilibrium still at t_{n+1} (dissipative,
//!   first-order accurate);
//! - HHT with MODI_EQUI='OUI': the true Hilber-Hughes-Taylor alpha-method,
//!   with the same beta and gamma and the equilibrium
//!   M a_{n+1} + (1+alpha)(F_int - F_ext)_{n+1} - alpha (F_int - F_ext)_n = 0,
//!   which code_aster divides by (1+alpha) (semantics.md section 8.1).
//!
//! Unknown of the Newton iterations: the displacement increment; velocity
//! and acceleration follow from the Newmark relations. code_aster's
//! FORMULATION='ACCELERATION' takes the acceleration increment instead:
//! its iteration matrix is the displacement one times beta dt^2 and its
//! increments are the same ones scaled (ndnpas: coerig = beta dt^2,
//! coemas = 1), so the Newton iterations are the same; only its
//! predictor differs (a0 = a_n), which [`Predictor`] carries.
//!
//! STAT_NON_LINE runs the same engine with [`Scheme::quasi_static`]: no
//! inertia, time a pseudo-time, velocity and acceleration held at zero.

pub mod explicit;
pub mod list;

/// The parameters of a scheme, as the engine uses them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scheme {
    pub beta: f64,
    pub gamma: f64,
    /// HHT alpha (<= 0); 0 for Newmark.
    pub alpha: f64,
    /// True for the full HHT equilibrium (MODI_EQUI='OUI').
    pub hht_full: bool,
    /// False for STAT_NON_LINE: the inertia is removed (no mass in the
    /// matrix or the residual, v = a = 0), the rest of the engine is the
    /// same.
    pub inertia: bool,
    /// The prediction of the step, from SCHEMA_TEMPS/FORMULATION.
    pub predictor: Predictor,
}

/// The predictor of an implicit step (code_aster's `ndnpas`, coefd,
/// coefv, coefa).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Predictor {
    /// FORMULATION='DEPLACEMENT': u0 = u_n.
    #[default]
    Displacement,
    /// FORMULATION='ACCELERATION': a0 = a_n, u0 = u_n + dt v_n + dt^2/2 a_n,
    /// v0 = v_n + dt a_n (the Newmark relations with a0 = a_n, for
    /// NEWMARK and HHT alike: code_aster's eps + beta = 1/2 for both).
    Acceleration,
}

/// Kinematic state of all dofs at one instant.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Kinematics {
    pub u: Vec<f64>,
    pub v: Vec<f64>,
    pub a: Vec<f64>,
}

impl Scheme {
    pub fn newmark(beta: f64, gamma: f64) -> Result<Scheme, String> {
        if beta <= 0.0 || !beta.is_finite() {
            return Err(format!("BETA must be > 0 (implicit Newmark), found {beta}"));
        }
        if !gamma.is_finite() || gamma <= 0.0 {
            return Err(format!("GAMMA must be > 0, found {gamma}"));
        }
        Ok(Scheme {
            beta,
            gamma,
            alpha: 0.0,
            hht_full: false,
            inertia: true,
            predictor: Predictor::Displacement,
        })
    }

    /// The quasi-static "scheme" of STAT_NON_LINE: equilibrium
    /// F_int(u) = F_ext(t) at each instant, t a pseudo-time.
    pub fn quasi_static() -> Scheme {
        Scheme {
            beta: 0.25,
            gamma: 0.5,
            alpha: 0.0,
            hht_full: false,
            inertia: false,
            predictor: Predictor::Displacement,
        }
    }

    /// HHT with code_aster's `ALPHA` and `MODI_EQUI`. code_aster refuses
    /// only α = −1 (the equation is divided by 1 + α) and checks no range
    /// (semantics.md §8.1): α outside [−1, 0] is accepted, with the alarm
    /// of [`Scheme::hht_alarm`].
    pub fn hht(alpha: f64, modi_equi: bool) -> Result<Scheme, String> {
        if !alpha.is_finite() {
            return Err(format!("ALPHA must be a finite number, found {alpha}"));
        }
        if alpha == -1.0 {
            return Err(
                "ALPHA = -1 is refused for HHT, as in code_aster: the equilibrium is divided by 1 + ALPHA"
                    .to_string(),
            );
        }
        Ok(Scheme {
            beta: (1.0 - alpha).powi(2) / 4.0,
            gamma: 0.5 - alpha,
            alpha,
            hht_full: modi_equi,
            inertia: true,
            predictor: Predictor::Displacement,
        })
    }

    /// The alarm of an HHT α that code_aster accepts without a check but
    /// that is not the dissipative HHT: α > 0 gives γ = ½ − α < ½, a
    /// negative numerical damping that makes the response grow (the
    /// Newmark family is unstable for γ < ½); α < −1 makes 1 + α
    /// negative, which with MODI_EQUI='OUI' changes the sign of the
    /// inertia and damping weights 1/(1 + α) (no longer an equation of
    /// motion), and with 'NON' is a stable Newmark with γ = ½ − α > 3/2,
    /// first-order and damping far more than any HHT. `None` for NEWMARK
    /// and α in ]−1, 0].
    pub fn hht_alarm(&self) -> Option<String> {
        let a = self.alpha;
        if a > 0.0 {
            Some(format!(
                "alarm: HHT with ALPHA = {a} > 0 (code_aster does no range check): outside the dissipative range [-1/3, 0], GAMMA = 1/2 - ALPHA = {} < 1/2 gives a negative numerical damping, so the response grows step after step instead of being damped (an unstable scheme, not HHT's)",
                self.gamma
            ))
        } else if a < -1.0 {
            Some(if self.hht_full {
                format!(
                    "alarm: HHT with ALPHA = {a} < -1 (code_aster does no range check): 1 + ALPHA < 0 turns the inertia weight 1/(1 + ALPHA) of MODI_EQUI='OUI' negative: the equation solved is no longer one of motion"
                )
            } else {
                format!(
                    "alarm: HHT with ALPHA = {a} < -1 (code_aster does no range check): with MODI_EQUI='NON' this is Newmark with BETA = {}, GAMMA = {} > 3/2, stable but first-order and far more dissipative than any HHT",
                    self.beta, self.gamma
                )
            })
        } else {
            None
        }
    }

    /// Weight w_i of the inertia M a_{n+1} in the residual
    /// w_i M a_{n+1} + (F_int - F_ext)_{n+1} + w_p (F_int - F_ext)_n:
    /// 1/(1+alpha) for full HHT (code_aster divides its equation by 1+alpha,
    /// so the current forces keep weight 1), 1 otherwise.
    pub fn inertia_weight(&self) -> f64 {
        if !self.inertia {
            0.0
        } else if self.hht_full {
            1.0 / (1.0 + self.alpha)
        } else {
            1.0
        }
    }

    /// Weight w_p of the previous step's (F_int - F_ext) in the residual:
    /// -alpha/(1+alpha) for full HHT, 0 otherwise.
    pub fn previous_weight(&self) -> f64 {
        if self.hht_full {
            -self.alpha / (1.0 + self.alpha)
        } else {
            0.0
        }
    }

    /// Coefficient of the mass matrix in the iteration matrix
    /// K_T + c_m M: 1/(beta dt^2), divided by 1+alpha for full HHT.
    pub fn mass_coefficient(&self, dt: f64) -> f64 {
        self.inertia_weight() / (self.beta * dt * dt)
    }

    /// Coefficient of the damping matrix in the iteration matrix.
    pub fn damping_coefficient(&self, dt: f64) -> f64 {
        self.inertia_weight() * self.gamma / (self.beta * dt)
    }

    /// The predictor of code_aster's displacement formulation (ndnpas):
    /// u0 = u_n, v0 = (1 - gamma/beta) v_n + (1 - gamma/(2 beta)) dt a_n,
    /// a0 = -v_n/(beta dt) + (1 - 1/(2 beta)) a_n.
    /// Quasi-static: u0 = u_n, v0 = a0 = 0.
    /// With [`Predictor::Acceleration`]: a0 = a_n, v0 = v_n + dt a_n,
    /// u0 = u_n + dt v_n + dt^2/2 a_n.
    pub fn predict(&self, dt: f64, prev: &Kinematics, next: &mut Kinematics) {
        let (b, g) = (self.beta, self.gamma);
        next.u.clone_from(&prev.u);
        next.v.resize(prev.v.len(), 0.0);
        next.a.resize(prev.a.len(), 0.0);
        if !self.inertia {
            next.v.iter_mut().for_each(|v| *v = 0.0);
            next.a.iter_mut().for_each(|v| *v = 0.0);
            return;
        }
        if self.predictor == Predictor::Acceleration {
            for i in 0..prev.u.len() {
                let (vn, an) = (prev.v[i], prev.a[i]);
                next.u[i] = prev.u[i] + dt * vn + 0.5 * dt * dt * an;
                next.v[i] = vn + dt * an;
                next.a[i] = an;
            }
            return;
        }
        for i in 0..prev.u.len() {
            let (vn, an) = (prev.v[i], prev.a[i]);
            next.v[i] = (1.0 - g / b) * vn + (1.0 - g / (2.0 * b)) * dt * an;
            next.a[i] = -vn / (b * dt) + (1.0 - 1.0 / (2.0 * b)) * an;
        }
    }

    /// Applies a displacement correction du: u += du, v += gamma/(beta dt) du,
    /// a += 1/(beta dt^2) du (quasi-static: u alone moves).
    pub fn correct(&self, dt: f64, du: &[f64], k: &mut Kinematics) {
        if !self.inertia {
            for (u, d) in k.u.iter_mut().zip(du) {
                *u += d;
            }
            return;
        }
        let cv = self.gamma / (self.beta * dt);
        let ca = 1.0 / (self.beta * dt * dt);
        for i in 0..du.len() {
            k.u[i] += du[i];
            k.v[i] += cv * du[i];
            k.a[i] += ca * du[i];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Integrates m a + k u = 0 from (u0, v0) over `steps` of `dt` with the
    /// same predictor/corrector and residual weights the engine uses, one
    /// linear Newton iteration per step (exact for a linear problem).
    fn sdof(
        s: &Scheme,
        m: f64,
        k: f64,
        u0: f64,
        v0: f64,
        dt: f64,
        steps: usize,
    ) -> Vec<(f64, f64)> {
        let mut prev = Kinematics {
            u: vec![u0],
            v: vec![v0],
            a: vec![-k * u0 / m],
        };
        let mut out = vec![(u0, v0)];
        for _ in 0..steps {
            let mut next = Kinematics::default();
            s.predict(dt, &prev, &mut next);
            // Residual as the engine writes it:
            // w_i M a_{n+1} + F_int(u_{n+1}) + w_p F_int(u_n), no external force.
            let resid = |kin: &Kinematics| {
                s.inertia_weight() * m * kin.a[0]
                    + k * kin.u[0]
                    + s.previous_weight() * k * prev.u[0]
            };
            let r = resid(&next);
            let kt = k + s.mass_coefficient(dt) * m;
            let du = -r / kt;
            s.correct(dt, &[du], &mut next);
            let scale = k * (u0.abs() + next.u[0].abs()) + m * next.a[0].abs() + 1.0;
            assert!(resid(&next).abs() < 1e-9 * scale);
            out.push((next.u[0], next.v[0]));
            prev = next;
        }
        out
    }

    fn energy(m: f64, k: f64, (u, v): (f64, f64)) -> f64 {
        0.5 * m * v * v + 0.5 * k * u * u
    }

    #[test]
    fn average_acceleration_conserves_energy_exactly() {
        let (m, k) = (1.0, (2.0 * std::f64::consts::PI).powi(2));
        let s = Scheme::newmark(0.25, 0.5).unwrap();
        let h = sdof(&s, m, k, 1.0, 0.0, 0.01, 1000);
        let e0 = energy(m, k, h[0]);
        for st in &h {
            assert!((energy(m, k, *st) - e0).abs() <= 1e-12 * e0);
        }
    }

    #[test]
    fn dissipative_schemes_lose_energy_monotonically() {
        let (m, k) = (1.0, (2.0 * std::f64::consts::PI).powi(2));
        for s in [
            Scheme::newmark(0.49, 0.9).unwrap(),
            Scheme::hht(-0.6, false).unwrap(),
            Scheme::hht(-0.1, true).unwrap(),
        ] {
            let h = sdof(&s, m, k, 1.0, 0.0, 0.05, 200);
            let e: Vec<f64> = h.iter().map(|x| energy(m, k, *x)).collect();
            assert!(
                e.last().unwrap() < &(0.99 * e[0]),
                "{s:?} did not dissipate"
            );
            // The plain energy may wobble within a period (the schemes
            // conserve a modified energy that includes the acceleration),
            // but sampled once per period it decreases monotonically.
            let per_period: Vec<f64> = e.iter().step_by(20).copied().collect();
            for w in per_period.windows(2) {
                assert!(w[1] < w[0], "{s:?}: {per_period:?}");
            }
        }
    }

    /// FORMULATION='ACCELERATION' changes the predictor only: the
    /// predicted state satisfies the Newmark relations with a0 = a_n, and
    /// on a linear oscillator (one exact Newton iteration per step) both
    /// formulations give the same trajectory to round-off, for Newmark
    /// and both HHT variants.
    #[test]
    fn acceleration_formulation_predicts_differently_and_converges_alike() {
        let (m, k) = (1.0, (2.0 * std::f64::consts::PI).powi(2));
        for s in [
            Scheme::newmark(0.49, 0.9).unwrap(),
            Scheme::hht(-0.6, false).unwrap(),
            Scheme::hht(-0.1, true).unwrap(),
        ] {
            let a = Scheme {
                predictor: Predictor::Acceleration,
                ..s
            };
            let prev = Kinematics {
                u: vec![0.3],
                v: vec![-2.0],
                a: vec![5.0],
            };
            let (mut pd, mut pa) = (Kinematics::default(), Kinematics::default());
            let dt = 0.01;
            s.predict(dt, &prev, &mut pd);
            a.predict(dt, &prev, &mut pa);
            assert_eq!(pd.u[0], 0.3);
            assert!((pa.u[0] - (0.3 - 2.0 * dt + 0.5 * dt * dt * 5.0)).abs() < 1e-15);
            assert!((pa.v[0] - (-2.0 + dt * 5.0)).abs() < 1e-15);
            assert_eq!(pa.a[0], 5.0);
            // Both predicted states lie on the Newmark manifold of prev.
            for p in [&pd, &pa] {
                let u = prev.u[0]
                    + dt * prev.v[0]
                    + dt * dt * ((0.5 - s.beta) * prev.a[0] + s.beta * p.a[0]);
                let v = prev.v[0] + dt * ((1.0 - s.gamma) * prev.a[0] + s.gamma * p.a[0]);
                assert!((p.u[0] - u).abs() < 1e-14 && (p.v[0] - v).abs() < 1e-12);
            }
            let hd = sdof(&s, m, k, 1.0, 0.0, 0.05, 200);
            let ha = sdof(&a, m, k, 1.0, 0.0, 0.05, 200);
            for (x, y) in hd.iter().zip(&ha) {
                assert!(
                    (x.0 - y.0).abs() < 1e-12 && (x.1 - y.1).abs() < 1e-11,
                    "{s:?}"
                );
            }
        }
    }

    /// Error at t = 1 against the exact solution u = cos(w t) in the energy
    /// norm (which sees the phase error at first order): the observed order
    /// is 2 for gamma = 1/2 and for full HHT, 1 for HHT with MODI_EQUI='NON'.
    #[test]
    fn orders_of_accuracy() {
        let w = 2.0 * std::f64::consts::PI;
        let (m, k) = (1.0, w * w);
        let err = |s: &Scheme, n: usize| {
            let h = sdof(s, m, k, 1.0, 0.0, 1.0 / n as f64, n);
            let (u, v) = h[n];
            ((u - 1.0).powi(2) + (v / w).powi(2)).sqrt()
        };
        let order = |s: &Scheme| (err(s, 400) / err(s, 800)).log2();
        let p = order(&Scheme::newmark(0.25, 0.5).unwrap());
        assert!((p - 2.0).abs() < 0.05, "Newmark order {p}");
        let p = order(&Scheme::hht(-0.1, true).unwrap());
        assert!((p - 2.0).abs() < 0.1, "HHT full order {p}");
        let p = order(&Scheme::hht(-0.3, false).unwrap());
        assert!((p - 1.0).abs() < 0.1, "HHT 'NON' order {p}");
    }

    /// Spectral radius at very high frequency (w dt = 1e4, the contact
    /// and smallest-element modes of an impact) measured by stepping the
    /// engine's scheme, against the roots of HHT's characteristic equation
    /// as w dt -> infinity: (1+a)/(1-a) (double) and the spurious root
    /// -a/(1+a). The latter exceeds 1 for a < -1/2: full HHT with
    /// ALPHA = -0.6 (MODI_EQUI='OUI', modelling G) amplifies the highest
    /// modes by 1.5 per step, which is why the classical range is
    /// [-1/3, 0]; with MODI_EQUI='NON' the same ALPHA is a stable Newmark.
    #[test]
    fn hht_high_frequency_spectral_radius() {
        let (m, k, dt) = (1.0, 1e8, 1.0);
        let growth = |s: &Scheme| {
            let h = sdof(s, m, k, 1.0, 0.0, dt, 300);
            let norm = |i: usize| energy(m, k, h[i]).sqrt();
            (norm(300) / norm(200)).powf(1.0 / 100.0)
        };
        for alpha in [-0.1, -0.3, -0.45, -0.6] {
            let rho = growth(&Scheme::hht(alpha, true).unwrap());
            let expected = ((1.0 + alpha) / (1.0 - alpha)).max(-alpha / (1.0 + alpha));
            assert!(
                (rho - expected).abs() < 1e-2 * expected,
                "alpha {alpha}: measured {rho}, expected {expected}"
            );
        }
        assert!(growth(&Scheme::hht(-0.6, true).unwrap()) > 1.4);
        assert!(growth(&Scheme::hht(-0.6, false).unwrap()) < 1.0);
    }

    /// ALPHA outside ]-1, 0] (accepted by code_aster, with an alarm here):
    /// the measured growth per step of the undamped SDOF at w dt = 0.5
    /// against the spectral radius of Newmark's amplification,
    /// sqrt(1 - (gamma - 1/2) W^2/(1 + beta W^2)) when its roots are
    /// complex: 1.02376 for ALPHA = 0.2 (gamma = 0.3: it grows), 0.85460
    /// for ALPHA = -1.5 with MODI_EQUI='NON' (beta = 1.5625, gamma = 2).
    #[test]
    fn hht_alpha_outside_the_range_is_an_alarm() {
        assert!(Scheme::hht(-1.0, true).is_err() && Scheme::hht(-1.0, false).is_err());
        assert!(Scheme::hht(f64::NAN, true).is_err());
        let (m, k, dt) = (1.0, 1.0, 0.5);
        let growth = |s: &Scheme| {
            let h = sdof(s, m, k, 1.0, 0.0, dt, 400);
            let norm = |i: usize| energy(m, k, h[i]).sqrt();
            (norm(400) / norm(200)).powf(1.0 / 200.0)
        };
        let radius = |s: &Scheme| {
            let w2 = 0.25;
            (1.0 - (s.gamma - 0.5) * w2 / (1.0 + s.beta * w2)).sqrt()
        };
        let up = Scheme::hht(0.2, false).unwrap();
        let down = Scheme::hht(-1.5, false).unwrap();
        for (s, want) in [(&up, 1.02376), (&down, 0.85460)] {
            assert!((radius(s) - want).abs() < 1e-5, "{}", radius(s));
            let g = growth(s);
            assert!(
                (g - want).abs() < 1e-2 * want,
                "measured {g}, expected {want}"
            );
        }
        assert!(growth(&Scheme::hht(0.2, true).unwrap()) > 1.0);
        assert!(up.hht_alarm().unwrap().contains("grows"));
        assert!(Scheme::hht(0.2, true)
            .unwrap()
            .hht_alarm()
            .unwrap()
            .contains("grows"));
        assert!(down.hht_alarm().unwrap().contains("GAMMA = 2 > 3/2"));
        assert!(Scheme::hht(-1.5, true)
            .unwrap()
            .hht_alarm()
            .unwrap()
            .contains("negative"));
        for s in [
            Scheme::hht(-0.6, true).unwrap(),
            Scheme::hht(0.0, false).unwrap(),
            Scheme::newmark(0.25, 0.5).unwrap(),
        ] {
            assert!(s.hht_alarm().is_none());
        }
    }

    #[test]
    fn hht_coefficients_match_code_aster() {
        let s = Scheme::hht(-0.6, false).unwrap();
        assert!((s.beta - 0.64).abs() < 1e-15 && (s.gamma - 1.1).abs() < 1e-15);
        assert!(Scheme::hht(-1.0, true).is_err());
        assert!(Scheme::newmark(0.0, 0.5).is_err());
    }
}
