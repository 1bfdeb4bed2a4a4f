//! Elastic energy density (CALC_CHAMP ENERGIE ENEL_ELGA, ENEL_ELNO,
//! ENEL_NOEU) from the stress.
//!
//! code_aster's `enelpg` under a small-strain kinematics (DEFORMATION
//! PETIT, PETIT_REAC) takes W = ½ σ : S : σ at each point, S the
//! compliance of the isotropic ELAS block, so that W is the energy of the
//! elastic part of the strain whatever the law (elastic or plastic);
//! component TOTALE (located components EENEISO of ENER_R). For an
//! isotropic material, with the tensor shears,
//! W = [(1 + ν) σ:σ − ν (tr σ)²] / (2E). Plane models read σ_xz = σ_yz =
//! 0 and keep the out-of-plane σ_zz.

use super::GaussField;

/// W of the stress `s` = (XX, YY, ZZ, XY, XZ, YZ) for Young's modulus `e`
/// and Poisson's ratio `nu`.
pub fn elastic_energy_density(s: [f64; 6], e: f64, nu: f64) -> f64 {
    let [xx, yy, zz, xy, xz, yz] = s;
    let tr = xx + yy + zz;
    let ss = xx * xx + yy * yy + zz * zz + 2.0 * (xy * xy + xz * xz + yz * yz);
    ((1.0 + nu) * ss - nu * tr * tr) / (2.0 * e)
}

/// The ENEL field of the stress field `sief` (components SIXX.. by name):
/// one component TOTALE at each point of the cells `elastic` gives
/// (E, ν) for; other cells have no point.
pub fn enel(sief: &GaussField, elastic: &[Option<(f64, f64)>]) -> Result<GaussField, String> {
    let names = ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"];
    let idx: Vec<Option<usize>> = names
        .iter()
        .map(|n| sief.components.iter().position(|c| c == n))
        .collect();
    if let Some(k) = idx[..4].iter().position(Option::is_none) {
        return Err(format!(
            "the stress field has no {} component (components: {})",
            names[k],
            sief.components.join(", ")
        ));
    }
    let nc = sief.ncmp();
    let mut out = GaussField {
        components: vec!["TOTALE".to_string()],
        offsets: Vec::with_capacity(sief.offsets.len()),
        values: Vec::new(),
    };
    for c in 0..sief.offsets.len().saturating_sub(1) {
        out.offsets.push(out.values.len());
        let Some(Some((e, nu))) = elastic.get(c) else {
            continue;
        };
        for row in sief.cell(c).chunks(nc.max(1)) {
            let mut s = [0.0; 6];
            for (k, i) in idx.iter().enumerate() {
                if let Some(i) = i {
                    s[k] = row[*i];
                }
            }
            out.values.push(if s.iter().any(|v| v.is_nan()) {
                f64::NAN
            } else {
                elastic_energy_density(s, *e, *nu)
            });
        }
    }
    out.offsets.push(out.values.len());
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uniaxial σ: W = σ²/(2E); pure shear τ: W = τ²/(2G).
    #[test]
    fn uniaxial_and_shear_energies() {
        let (e, nu) = (2.0e5, 0.3);
        let w = elastic_energy_density([0.0, 0.0, 300.0, 0.0, 0.0, 0.0], e, nu);
        assert!((w - 300.0 * 300.0 / (2.0 * e)).abs() < 1e-15 * w);
        let g = e / (2.0 * (1.0 + nu));
        let w = elastic_energy_density([0.0, 0.0, 0.0, 0.0, 50.0, 0.0], e, nu);
        assert!((w - 50.0 * 50.0 / (2.0 * g)).abs() < 1e-15 * w);
    }
}
