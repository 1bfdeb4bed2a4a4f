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
//!
//! Under SIMO_MIEHE (VMIS_ISOT_LINE, VMIS_ISOT_TRAC, VMIS_ISOT_PUIS) `enelpg` takes the stored energy of
//! the model instead, W = K/2 (½(J² − 1) − ln J) + μ/2 (tr b̄ᵉ − 3), per
//! unit initial volume, K = E/(3(1 − 2ν)), μ = E/(2(1 + ν)), J = det F
//! and b̄ᵉ the isochoric elastic left Cauchy-Green tensor the law keeps in
//! its internal variables (here V3..V5 hold its diagonal minus 1).

use super::GaussField;

/// W of the stress `s` = (XX, YY, ZZ, XY, XZ, YZ) for Young's modulus `e`
/// and Poisson's ratio `nu`.
pub fn elastic_energy_density(s: [f64; 6], e: f64, nu: f64) -> f64 {
    let [xx, yy, zz, xy, xz, yz] = s;
    let tr = xx + yy + zz;
    let ss = xx * xx + yy * yy + zz * zz + 2.0 * (xy * xy + xz * xz + yz * yz);
    ((1.0 + nu) * ss - nu * tr * tr) / (2.0 * e)
}

/// W = ½ ε:C:ε of the linearised strain `eps` = (XX, YY, ZZ, XY, XZ, YZ),
/// tensor shears, for the isotropic ELAS (E, ν): λ/2 (tr ε)² + μ ε:ε.
/// POST_ELEM's ENER_POT (code_aster's EPOT_ELEM, the displacement's
/// energy in the elastic stiffness).
pub fn strain_energy_density(eps: [f64; 6], e: f64, nu: f64) -> f64 {
    let [xx, yy, zz, xy, xz, yz] = eps;
    let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mu = e / (2.0 * (1.0 + nu));
    let tr = xx + yy + zz;
    let ee = xx * xx + yy * yy + zz * zz + 2.0 * (xy * xy + xz * xz + yz * yz);
    0.5 * lambda * tr * tr + mu * ee
}

/// W of SIMO_MIEHE for J = det F and tr b̄ᵉ.
pub fn simo_miehe_energy_density(j: f64, tr_be_bar: f64, e: f64, nu: f64) -> f64 {
    let k = e / (3.0 * (1.0 - 2.0 * nu));
    let mu = e / (2.0 * (1.0 + nu));
    0.5 * k * (0.5 * (j * j - 1.0) - j.ln()) + 0.5 * mu * (tr_be_bar - 3.0)
}

/// How the energy of a cell is taken: its ELAS (E, ν) and the kinematics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CellEnergy {
    /// PETIT, PETIT_REAC: ½ σ:S:σ.
    Small { e: f64, nu: f64 },
    /// SIMO_MIEHE: the stored energy, from J and the internal variables
    /// `be` (the columns of b̄ᵉ_xx − 1, b̄ᵉ_yy − 1, b̄ᵉ_zz − 1 in VARI_ELGA).
    SimoMiehe { e: f64, nu: f64, be: [usize; 3] },
}

/// The anelastic strain EPSP = ε − S:σ at each point of the cells `laws`
/// gives small-strain constants for (other cells have no point): `eps`
/// the strain of DEPL (EPXX.. with tensor shears, EPSI_ELGA) at the points
/// of the stress `sief` (SIXX.. by name), S the isotropic ELAS compliance
/// ε_ii = ((1 + ν) σ_ii − ν tr σ)/E, ε_ij = (1 + ν) σ_ij/E. code_aster's
/// EPSP_ELGA, without command variables (no thermal strain exists here):
/// for a von Mises law, the plastic strain.
pub fn epsp(
    eps: &GaussField,
    sief: &GaussField,
    laws: &[Option<CellEnergy>],
) -> Result<GaussField, String> {
    let stress = ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"];
    let strain = ["EPXX", "EPYY", "EPZZ", "EPXY", "EPXZ", "EPYZ"];
    let s_idx: Vec<Option<usize>> = stress
        .iter()
        .map(|n| sief.components.iter().position(|c| c == n))
        .collect();
    let e_idx: Vec<Option<usize>> = eps
        .components
        .iter()
        .map(|c| strain.iter().position(|n| n == c))
        .collect();
    let (ns, ne) = (sief.ncmp().max(1), eps.ncmp().max(1));
    let mut out = GaussField {
        components: eps.components.clone(),
        offsets: Vec::with_capacity(eps.offsets.len()),
        values: Vec::new(),
    };
    for c in 0..eps.offsets.len().saturating_sub(1) {
        out.offsets.push(out.values.len());
        let (e, nu) = match laws.get(c) {
            Some(Some(CellEnergy::Small { e, nu })) => (*e, *nu),
            Some(Some(CellEnergy::SimoMiehe { .. })) => {
                return Err(format!(
                    "cell M{}: EPSP under SIMO_MIEHE is not computed",
                    c + 1
                ))
            }
            _ => continue,
        };
        let (es, ss) = (eps.cell(c), sief.cell(c));
        if es.len() / ne != ss.len() / ns {
            return Err(format!(
                "cell M{}: {} strain points for {} stress points",
                c + 1,
                es.len() / ne,
                ss.len() / ns
            ));
        }
        for (er, sr) in es.chunks(ne).zip(ss.chunks(ns)) {
            let mut s = [0.0; 6];
            for (k, i) in s_idx.iter().enumerate() {
                if let Some(i) = i {
                    s[k] = sr[*i];
                }
            }
            let tr = s[0] + s[1] + s[2];
            for (v, k) in er.iter().zip(&e_idx) {
                let elastic = match k {
                    Some(k @ 0..=2) => ((1.0 + nu) * s[*k] - nu * tr) / e,
                    Some(k) => (1.0 + nu) * s[*k] / e,
                    None => 0.0,
                };
                out.values.push(v - elastic);
            }
        }
    }
    out.offsets.push(out.values.len());
    Ok(out)
}

/// The ENEL field: one component TOTALE at each point of the cells
/// `laws` gives a [`CellEnergy`] for (other cells have no point), from
/// the stress `sief` (components SIXX.. by name) or, for SIMO_MIEHE, from
/// `jac` (one component, det F at the same points) and `vari`.
pub fn enel(
    sief: &GaussField,
    jac: Option<&GaussField>,
    vari: Option<&GaussField>,
    laws: &[Option<CellEnergy>],
) -> Result<GaussField, String> {
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
        let (e, nu) = match laws.get(c) {
            Some(Some(CellEnergy::Small { e, nu })) => (e, nu),
            Some(Some(CellEnergy::SimoMiehe { e, nu, be })) => {
                let (Some(jac), Some(vari)) = (jac, vari) else {
                    return Err(format!(
                        "cell M{}: no J or VARI_ELGA for its SIMO_MIEHE energy",
                        c + 1
                    ));
                };
                let nv = vari.ncmp();
                let (js, vs) = (jac.cell(c), vari.cell(c));
                if nv == 0 || vs.len() != js.len() * nv || be.iter().any(|&k| k >= nv) {
                    return Err(format!(
                        "cell M{}: VARI_ELGA has {} values for {} points, not the law's b̄ᵉ",
                        c + 1,
                        vs.len(),
                        js.len()
                    ));
                }
                for (g, j) in js.iter().enumerate() {
                    let row = &vs[g * nv..(g + 1) * nv];
                    let tr = 3.0 + row[be[0]] + row[be[1]] + row[be[2]];
                    out.values.push(simo_miehe_energy_density(*j, tr, *e, *nu));
                }
                continue;
            }
            _ => continue,
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

    /// The strain of a uniaxial stress σ (ε = σ/E, −ν σ/E twice) stores
    /// σ²/(2E), as ½ σ:S:σ says.
    #[test]
    fn strain_energy_of_uniaxial_stress() {
        let (e, nu, s) = (2.0e5, 0.3, 300.0);
        let eps = [-nu * s / e, -nu * s / e, s / e, 0.0, 0.0, 0.0];
        let w = strain_energy_density(eps, e, nu);
        assert!((w - s * s / (2.0 * e)).abs() < 1e-14 * w);
    }

    /// No deformation, no energy; a pure volume change J stores only the
    /// volumetric part, whose second derivative at J = 1 is K.
    #[test]
    fn simo_miehe_energy_volumetric_part() {
        let (e, nu) = (2.0e5, 0.3);
        assert_eq!(simo_miehe_energy_density(1.0, 3.0, e, nu), 0.0);
        let k = e / (3.0 * (1.0 - 2.0 * nu));
        let h = 1e-4;
        let d2 = (simo_miehe_energy_density(1.0 + h, 3.0, e, nu)
            + simo_miehe_energy_density(1.0 - h, 3.0, e, nu))
            / (h * h);
        assert!((d2 - k).abs() < 1e-6 * k, "{d2} vs {k}");
    }
}
