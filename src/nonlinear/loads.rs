//! External forces that vary in time: each load's vector (PESANTEUR,
//! FORCE_NODALE and PRES_REP, `element::body_force::load_forces`) times its EXCIT
//! FONC_MULT evaluated at the instant, summed (code_aster's dead loads
//! "FIXE_CSTE" with a multiplier function). The engine asks for F_ext at
//! the instants it needs: the end of the step, and for HHT's previous-step
//! weight the start of it.

use crate::post::function::Function;

/// The loads of a run as (forces, multiplier): a `None` multiplier is 1.
#[derive(Debug, Clone, Default)]
pub struct LoadHistory {
    parts: Vec<(Vec<f64>, Option<Function>)>,
}

impl LoadHistory {
    pub fn new(parts: Vec<(Vec<f64>, Option<Function>)>) -> LoadHistory {
        LoadHistory { parts }
    }

    /// Whether some load has a multiplier (otherwise F_ext is constant and
    /// set once).
    pub fn varies(&self) -> bool {
        self.parts.iter().any(|(_, f)| f.is_some())
    }

    /// F_ext(t) into `out` (full vector). A multiplier that cannot be
    /// evaluated at `t` (outside its abscissas with PROL 'EXCLU') gives
    /// an error naming the instant.
    pub fn at(&self, t: f64, out: &mut [f64]) -> Result<(), String> {
        out.iter_mut().for_each(|v| *v = 0.0);
        for (forces, mult) in &self.parts {
            let m = match mult {
                None => 1.0,
                Some(f) => f
                    .eval(t)
                    .map_err(|e| format!("FONC_MULT at INST = {t:e}: {e}"))?,
            };
            if m == 0.0 {
                continue;
            }
            for (o, &f) in out.iter_mut().zip(forces) {
                *o += m * f;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forces_are_scaled_by_their_multiplier_and_summed() {
        let ramp = Function::new("INST", "TOUTRESU", vec![0.0, 2.0], vec![0.0, 4.0]).unwrap();
        let h = LoadHistory::new(vec![(vec![1.0, 0.0], Some(ramp)), (vec![0.0, 3.0], None)]);
        assert!(h.varies());
        let mut out = vec![9.0; 2];
        h.at(0.5, &mut out).unwrap();
        assert_eq!(out, vec![1.0, 3.0]);
        let e = h.at(3.0, &mut out).unwrap_err();
        assert!(e.contains("FONC_MULT at INST = 3e0"), "{e}");
        assert!(!LoadHistory::new(vec![(vec![1.0], None)]).varies());
    }
}
