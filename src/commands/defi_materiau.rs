//! DEFI_MATERIAU: material parameters, by behaviour block.

use indexmap::IndexMap;

use super::blocks::*;
use super::model_args::real_text;
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::diag::Diagnostic;
use crate::law::vmis_isot_trac::TractionCurve;
use crate::model::{Material, MaterialCurve};
use crate::study::Study;

pub fn def() -> CommandDef {
    let spec = command(
        "DEFI_MATERIAU",
        Produces::Concept(C::Mater),
        vec![
            fact(
                "ELAS",
                vec![
                    real("E").required().min_val(0.0).doc("Young's modulus").kw(),
                    real("NU")
                        .required()
                        .min_val(-1.0)
                        .max_val(0.5)
                        .doc("Poisson's ratio")
                        .kw(),
                    real("RHO").doc("density, needed for the mass matrix").kw(),
                    real("ALPHA").doc("thermal expansion coefficient").kw(),
                    real("AMOR_ALPHA")
                        .doc("Rayleigh damping coefficient on the stiffness")
                        .kw(),
                    real("AMOR_BETA")
                        .doc("Rayleigh damping coefficient on the mass")
                        .kw(),
                    real("AMOR_HYST").kw(),
                    real("LONG_CARA").kw(),
                    real("COEF_AMOR").default(r(1.0)).kw(),
                ],
            )
            .doc("isotropic linear elasticity")
            .kw(),
            fact(
                "ECRO_LINE",
                vec![
                    real("D_SIGM_EPSI")
                        .required()
                        .doc("tangent slope E_T of the uniaxial curve (not the plastic modulus: H = E.E_T/(E-E_T))")
                        .kw(),
                    real("SY").required().doc("yield stress").kw(),
                    real("SIGM_LIM").kw(),
                    real("EPSI_LIM").kw(),
                ],
            )
            .doc("linear hardening: isotropic (VMIS_ISOT_LINE) or kinematic (VMIS_CINE_LINE, Prager's C = 2/3.E.E_T/(E-E_T))")
            .kw(),
            fact(
                "ECRO_PUIS",
                vec![
                    real("SY").required().doc("yield stress").kw(),
                    real("A_PUIS")
                        .required()
                        .min_val(0.0)
                        .doc("A of R(p) = SY (1 + (E p/(A SY))^(1/N)), E of ELAS; must be > 0")
                        .kw(),
                    real("N_PUIS")
                        .required()
                        .min_val(1e-6)
                        .doc("hardening exponent N of R(p) = SY (1 + (E p/(A SY))^(1/N))")
                        .kw(),
                ],
            )
            .doc("isotropic hardening by a power law (VMIS_ISOT_PUIS)")
            .kw(),
            fact(
                "TRACTION",
                vec![concept("SIGM", &[C::Fonction])
                    .required()
                    .doc("uniaxial traction curve σ(ε), NOM_PARA='EPSI': the first point is the elastic limit and sets the law's Young's modulus SIGM/EPSI; PROL_DROITE says what lies past the last point")
                    .kw()],
            )
            .doc("isotropic hardening by a traction curve (VMIS_ISOT_TRAC)")
            .kw(),
            fact(
                "ECRO_COOK",
                vec![
                    real("A").required().min_val(0.0).doc("initial yield stress").kw(),
                    real("B").required().min_val(0.0).doc("hardening modulus").kw(),
                    real("C").min_val(0.0).doc("strain-rate coefficient").kw(),
                    real("N_PUIS").required().min_val(0.0).doc("hardening exponent").kw(),
                    real("M_PUIS").min_val(0.0).doc("thermal softening exponent").kw(),
                    real("EPSP0")
                        .min_val(1e-6)
                        .doc("reference strain rate; the rate term acts only above it")
                        .kw(),
                    real("TROOM").min_val(0.0).doc("room temperature").kw(),
                    real("TMELT").min_val(0.0).doc("melting temperature").kw(),
                ],
            )
            .rules(vec![
                ensemble(&["C", "EPSP0"]),
                ensemble(&["M_PUIS", "TROOM", "TMELT"]),
            ])
            .doc("Johnson-Cook hardening (VMIS_JOHN_COOK); no thermal softening without a temperature field")
            .kw(),
            titre(),
            info(),
        ],
    )
    .rules(vec![
        au_moins_un(&["ELAS", "ECRO_LINE", "ECRO_COOK", "TRACTION", "ECRO_PUIS"]),
        exclus(&["ECRO_LINE", "ECRO_COOK"]),
    ])
    .doc("Defines a material: one factor keyword per behaviour ingredient.");
    CommandDef { spec, exec }
}

/// The blocks aster keeps, in the order they are stored.
const BLOCKS: [&str; 4] = ["ELAS", "ECRO_LINE", "ECRO_COOK", "ECRO_PUIS"];

/// The values VMIS_JOHN_COOK uses for the optional ECRO_COOK parameters
/// when they are absent (code_aster's `nmtevp`): no rate term (C = 0,
/// EPSP0 = 1) and no thermal softening (TROOM = -1 switches it off). They
/// are stored so that the law never has to know them.
const ECRO_COOK_ABSENT: [(&str, f64); 5] = [
    ("C", 0.0),
    ("EPSP0", 1.0),
    ("M_PUIS", 0.0),
    ("TROOM", -1.0),
    ("TMELT", 1.0),
];

/// Stores the blocks with their given and defaulted reals, then checks
/// what code_aster checks before any computation can use the material.
fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    let mut mat = Material::default();
    let mut notes = Vec::new();
    for block in BLOCKS {
        let Some(occ) = args.fact(block) else {
            continue;
        };
        let mut params = IndexMap::new();
        for (key, _) in &occ.entries {
            if let Some(v) = occ.real(key) {
                params.insert(key.clone(), v);
            }
        }
        if block == "ECRO_COOK" {
            for (key, v) in ECRO_COOK_ABSENT {
                params.entry(key.to_string()).or_insert(v);
            }
        }
        mat.blocks.insert(block.to_string(), params);
    }
    if let Some(occ) = args.fact("TRACTION") {
        let curve = traction_curve(study, occ)?;
        notes.push(format!(
            "      TRACTION: {} points, Young's modulus of VMIS_ISOT_TRAC SIGM/EPSI of the first point = {}, yield stress {}",
            curve.abscissas.len(),
            curve.ordinates[0] / curve.abscissas[0],
            curve.ordinates[0]
        ));
        mat.curves.insert("TRACTION/SIGM".to_string(), curve);
        mat.blocks.insert("TRACTION".to_string(), IndexMap::new());
    }
    for block in ["ECRO_LINE", "ECRO_COOK", "TRACTION", "ECRO_PUIS"] {
        if mat.blocks.contains_key(block) && !mat.blocks.contains_key("ELAS") {
            return Err(args.error(
                block,
                format!("{block} needs ELAS in the same material: the plasticity laws read E and NU from it"),
            ));
        }
    }
    // The catalogue bounds NU to [-1, 0.5] as code_aster's does; the two
    // ends are limits, not materials: NU = 0.5 makes the bulk modulus
    // E/(3(1 - 2 NU)) infinite and NU = -1 the shear modulus E/(2(1 + NU)),
    // and either turns the elastic matrix into inf/NaN at the first step.
    if let Some(nu) = mat.get("ELAS", "NU") {
        if nu >= 0.5 || nu <= -1.0 {
            let occ = args.fact("ELAS").unwrap_or(args);
            let why = if nu >= 0.5 {
                "NU = 0.5 is the incompressible limit: the bulk modulus E/(3(1 - 2 NU)) is infinite, \
                 which the displacement elements cannot represent; give NU < 0.5 (0.499 for a nearly \
                 incompressible material)"
            } else {
                "NU = -1 makes the shear modulus E/(2(1 + NU)) infinite; give -1 < NU < 0.5"
            };
            return Err(occ.error("NU", format!("{why} (NU = {nu})")));
        }
    }
    if let (Some(e), Some(c)) = (mat.get("ELAS", "E"), mat.curve("TRACTION", "SIGM")) {
        let ec = c.ordinates[0] / c.abscissas[0];
        if ((ec - e) / e).abs() > 1e-3 {
            notes.push(format!(
                "      alarm: ELAS/E = {e} but the first point of TRACTION/SIGM gives E = {ec}: \
                 VMIS_ISOT_TRAC uses the latter (as code_aster's rctrac), ELAS/E serves the other laws"
            ));
        }
    }
    if let (Some(e), Some(et)) = (mat.get("ELAS", "E"), mat.get("ECRO_LINE", "D_SIGM_EPSI")) {
        if et >= e {
            let occ = args.fact("ECRO_LINE").unwrap_or(args);
            return Err(occ.error(
                "D_SIGM_EPSI",
                format!(
                    "the tangent slope D_SIGM_EPSI = {et} must be smaller than Young's modulus E = {e} (COMPOR1_54)"
                ),
            ));
        }
        notes.push(format!(
            "      ECRO_LINE: hardening modulus H = E.D_SIGM_EPSI/(E - D_SIGM_EPSI) = {}",
            e * et / (e - et)
        ));
    }
    if let (Some(e), Some(occ)) = (mat.get("ELAS", "E"), args.fact("ECRO_PUIS")) {
        let get = |p| mat.get("ECRO_PUIS", p).unwrap_or(f64::NAN);
        let law = crate::law::vmis_isot_puis::PowerHardening::new(
            e,
            get("SY"),
            get("A_PUIS"),
            get("N_PUIS"),
            Default::default(),
        );
        if let Err(why) = law {
            let key = why.keyword.rsplit('/').next().unwrap_or("SY");
            return Err(occ.error(key, why.message));
        }
    }
    study.log(format!(
        "    material {}: {}",
        result.unwrap_or("(unnamed)"),
        mat.blocks
            .iter()
            .map(|(b, p)| format!(
                "{b}({})",
                p.iter()
                    .map(|(k, v)| format!("{k}={}", real_text(*v)))
                    .collect::<Vec<_>>()
                    .join(", ")
            ))
            .collect::<Vec<_>>()
            .join(" ")
    ));
    for n in notes {
        study.log(n);
    }
    Ok(Some(ConceptData::Material(Box::new(mat))))
}

/// TRACTION/SIGM: a tabulated function of EPSI that makes a valid R(p)
/// (checked here so that the error names DEFI_MATERIAU, not the first
/// step); a constant function is refused as by code_aster (MODELISA6_88).
fn traction_curve(study: &Study, occ: &Args) -> Result<MaterialCurve, Diagnostic> {
    let name = occ.concept("SIGM").unwrap_or("");
    let Some(ConceptData::Function(f)) = study.concepts.data(name) else {
        return Err(occ.error(
            "SIGM",
            format!("{name} holds no function (its command did not run)"),
        ));
    };
    if f.para != "EPSI" {
        return Err(occ.error(
            "SIGM",
            format!(
                "the traction curve {name} must be a function of NOM_PARA='EPSI' (the strain), not '{}'",
                f.para
            ),
        ));
    }
    TractionCurve::new(&f.abscissas, &f.ordinates, f.right)
        .map_err(|e| occ.error("SIGM", format!("{name}: {}", e.message)))?;
    Ok(MaterialCurve {
        abscissas: f.abscissas.clone(),
        ordinates: f.ordinates.clone(),
        right: f.right,
    })
}
