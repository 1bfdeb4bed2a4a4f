//! The COMPORTEMENT field: which law and strain measure each cell uses,
//! and the law objects built from the cell's material.
//!
//! code_aster builds a "carte" from the occurrences: a later occurrence
//! overrides earlier ones on common cells, and model cells that no
//! occurrence covers get ELAS/PETIT with an alarm (semantics.md §4.2).
//! Law/strain compatibility follows the law declarations: SIMO_MIEHE is
//! refused for ELAS (no finite-strain elastic law of that kind exists in
//! code_aster), VMIS_JOHN_COOK and VMIS_CINE_LINE (not in their lists),
//! and VMIS_ISOT_LINE, _TRAC and _PUIS with SIMO_MIEHE switch to the
//! multiplicative law (VMIS2ISOT_LINE in code_aster).

use indexmap::IndexMap;

use crate::element::{Kinematics, LawRef};
use crate::law::elas::Elas;
use crate::law::gdef_log::{
    CineLineLog, GdefLog, IsotLineLog, IsotPuisLog, IsotTracLog, JohnCookLog,
};
use crate::law::john_cook::{EcroCookParams, LocalControls, VmisJohnCook};
use crate::law::root1d::RootMethod;
use crate::law::simo_miehe::{Hardening, SimoMiehe};
use crate::law::vmis_cine_line::VmisCineLine;
use crate::law::vmis_isot_line::VmisIsotLine;
use crate::law::vmis_isot_puis::{PowerHardening, VmisIsotPuis};
use crate::law::vmis_isot_trac::{TractionCurve, VmisIsotTrac};
use crate::law::{
    EcroLineParams, ElasParams, FailureKind, IntegrationFailure, InternalVars, LawMetadata, Regime,
    SmallStrainBehaviour, SmallStrainInput, SmallStrainOutput, StrainMeasure, TangentKind,
};
use crate::model::{CellRole, Material, MaterialField, Model};

/// A law instance, built once per (material, relation, kinematics); a
/// handful per computation, so the size of the variants does not matter.
#[derive(Debug, Clone)]
#[allow(clippy::large_enum_variant)]
pub enum CellLaw {
    Elas(Elas),
    VmisIsotLine(VmisIsotLine),
    VmisIsotTrac(VmisIsotTrac),
    VmisIsotPuis(VmisIsotPuis),
    VmisCineLine(VmisCineLine),
    SimoMiehe(SimoMiehe),
    JohnCook(VmisJohnCook),
    IsotLineLog(IsotLineLog),
    IsotTracLog(IsotTracLog),
    IsotPuisLog(IsotPuisLog),
    CineLineLog(CineLineLog),
    JohnCookLog(JohnCookLog),
    /// A small-strain law read at its stored state ([`StoredStress`]).
    Stored(StoredStress),
}

/// A small-strain law evaluated at a stored state: it returns σ_n and the
/// internal variables it is given, whatever the strain increment, so that
/// an element's internal forces are those of the stored stresses (Bᵀσ,
/// and for HEXS8 the stored hourglass stresses FSTAB). CALC_CHAMP's
/// FORC_NODA / REAC_NODA use it for a step whose VARI_ELGA was not
/// archived (ARCHIVAGE/CHAM_EXCLU): code_aster's `ccfnrn` builds the nodal
/// forces from SIEF_ELGA, STRX_ELGA and DEPL only, never from VARI_ELGA.
/// With VARI_ELGA at hand the law itself is evaluated at zero increment,
/// which returns the same stresses. Forces only: a nonzero strain
/// increment is an error.
#[derive(Clone)]
pub struct StoredStress {
    law: std::sync::Arc<dyn SmallStrainBehaviour>,
}

impl std::fmt::Debug for StoredStress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "StoredStress({})", self.law.metadata().name)
    }
}

impl SmallStrainBehaviour for StoredStress {
    fn metadata(&self) -> &'static LawMetadata {
        self.law.metadata()
    }
    fn initial_internal(&self) -> InternalVars {
        self.law.initial_internal()
    }
    fn elastic_params(&self) -> Option<ElasParams> {
        self.law.elastic_params()
    }
    fn integrate(&self, input: &SmallStrainInput) -> Result<SmallStrainOutput, IntegrationFailure> {
        let refuse = |message: String| IntegrationFailure {
            kind: FailureKind::InvalidInput,
            dt_factor: 1.0,
            message,
        };
        if input.strain_increment.iter().any(|d| *d != 0.0) {
            return Err(refuse(format!(
                "{} read at its stored state takes no strain increment",
                self.law.metadata().name
            )));
        }
        let internal = InternalVars::from_slice(input.internal)
            .ok_or_else(|| refuse("too many internal variables".into()))?;
        // HEXS8 asks for a tangent even for its forces (its hourglass
        // stresses move by the tangent times their strain increment, zero
        // here): Hooke's, from the law's elastic constants.
        let tangent = match input.tangent {
            TangentKind::None => None,
            _ => Some(
                *Elas::new(self.law.elastic_params().ok_or_else(|| {
                    refuse(format!(
                        "{} has no elastic constants",
                        self.law.metadata().name
                    ))
                })?)
                .stiffness(),
            ),
        };
        Ok(SmallStrainOutput {
            stress: input.stress,
            internal,
            tangent,
            regime: Regime::Elastic,
        })
    }
}

impl CellLaw {
    /// The law read at its stored state ([`StoredStress`]), for the
    /// small-strain laws; `None` for the finite-strain ones (SIMO_MIEHE,
    /// GDEF_LOG), whose internal forces need their internal variables.
    pub fn stored_stress(&self) -> Option<CellLaw> {
        let law: std::sync::Arc<dyn SmallStrainBehaviour> = match self {
            CellLaw::Elas(l) => std::sync::Arc::new(*l),
            CellLaw::VmisIsotLine(l) => std::sync::Arc::new(*l),
            CellLaw::VmisIsotTrac(l) => std::sync::Arc::new(l.clone()),
            CellLaw::VmisIsotPuis(l) => std::sync::Arc::new(*l),
            CellLaw::VmisCineLine(l) => std::sync::Arc::new(*l),
            CellLaw::JohnCook(l) => std::sync::Arc::new(*l),
            CellLaw::Stored(l) => return Some(CellLaw::Stored(l.clone())),
            CellLaw::SimoMiehe(_)
            | CellLaw::IsotLineLog(_)
            | CellLaw::IsotTracLog(_)
            | CellLaw::IsotPuisLog(_)
            | CellLaw::CineLineLog(_)
            | CellLaw::JohnCookLog(_) => return None,
        };
        Some(CellLaw::Stored(StoredStress { law }))
    }

    pub fn law_ref(&self) -> LawRef<'_> {
        match self {
            CellLaw::Elas(l) => LawRef::Small(l),
            CellLaw::VmisIsotLine(l) => LawRef::Small(l),
            CellLaw::VmisIsotTrac(l) => LawRef::Small(l),
            CellLaw::VmisIsotPuis(l) => LawRef::Small(l),
            CellLaw::VmisCineLine(l) => LawRef::Small(l),
            CellLaw::SimoMiehe(l) => LawRef::SimoMiehe(l),
            CellLaw::JohnCook(l) => LawRef::Small(l),
            CellLaw::IsotLineLog(l) => LawRef::GdefLog(l),
            CellLaw::IsotTracLog(l) => LawRef::GdefLog(l),
            CellLaw::IsotPuisLog(l) => LawRef::GdefLog(l),
            CellLaw::CineLineLog(l) => LawRef::GdefLog(l),
            CellLaw::JohnCookLog(l) => LawRef::GdefLog(l),
            CellLaw::Stored(l) => LawRef::Small(l),
        }
    }
    /// Number of internal variables (the length of VARI_ELGA for the cell).
    pub fn nvari(&self) -> usize {
        self.law_ref().initial_internal().as_slice().len()
    }
}

/// One COMPORTEMENT occurrence, already resolved to cells.
#[derive(Debug, Clone, PartialEq)]
pub struct Occurrence {
    /// `None` for TOUT='OUI' (or no location at all).
    pub cells: Option<Vec<usize>>,
    pub relation: String,
    pub deformation: String,
    /// ALGO_INTE, ITER_INTE_MAXI, RESI_INTE_RELA (laws that iterate).
    pub controls: Controls,
}

/// The local-integration keywords of an occurrence as given (`None` when
/// absent), checked against the law when the field is built.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Controls {
    pub algo_inte: Option<String>,
    pub iter_inte_maxi: Option<i64>,
    pub resi_inte_rela: Option<f64>,
}

/// The behaviour of one model cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellBehaviour {
    pub kinematics: Kinematics,
    /// Index into [`BehaviourField::laws`].
    pub law: usize,
    /// Density of the cell's material (the mass matrix needs it).
    pub rho: f64,
}

/// The behaviour of every cell (None outside the model's elements).
#[derive(Debug, Clone)]
pub struct BehaviourField {
    pub cells: Vec<Option<CellBehaviour>>,
    pub laws: Vec<CellLaw>,
    /// Alarms for the message file (uncovered cells...).
    pub alarms: Vec<String>,
}

/// Why the field cannot be built; `occurrence` (0-based) and `keyword`
/// locate the COMPORTEMENT entry at fault when there is one.
#[derive(Debug, Clone, PartialEq)]
pub struct BehaviourError {
    pub occurrence: Option<usize>,
    pub keyword: &'static str,
    pub message: String,
    /// True for valid input that aster does not implement yet.
    pub not_implemented: bool,
}

fn err(occ: Option<usize>, keyword: &'static str, message: String) -> BehaviourError {
    BehaviourError {
        occurrence: occ,
        keyword,
        message,
        not_implemented: false,
    }
}

/// Builds the behaviour field. `materials` maps material concept names to
/// their data (those named by the material field).
pub fn build(
    model: &Model,
    matfield: &MaterialField,
    materials: &IndexMap<String, Material>,
    occurrences: &[Occurrence],
) -> Result<BehaviourField, BehaviourError> {
    build_for(model, matfield, materials, occurrences, true)
}

/// [`build`] for a dynamic (`inertia`: ELAS/RHO is compulsory) or a
/// quasi-static computation (the density of the mass is 0, RHO unread).
pub fn build_for(
    model: &Model,
    matfield: &MaterialField,
    materials: &IndexMap<String, Material>,
    occurrences: &[Occurrence],
    inertia: bool,
) -> Result<BehaviourField, BehaviourError> {
    let ncells = model.cells.len();
    // Which occurrence covers each cell (later wins); None = default.
    let mut chosen: Vec<Option<usize>> = vec![None; ncells];
    for (k, occ) in occurrences.iter().enumerate() {
        match &occ.cells {
            None => chosen.iter_mut().for_each(|c| *c = Some(k)),
            Some(cells) => {
                for &c in cells {
                    if c < ncells {
                        chosen[c] = Some(k);
                    }
                }
            }
        }
    }
    let mut out = BehaviourField {
        cells: vec![None; ncells],
        laws: Vec::new(),
        alarms: Vec::new(),
    };
    let mut law_index: IndexMap<(String, String, Kinematics, Option<usize>), usize> =
        IndexMap::new();
    let mut uncovered = 0usize;
    for (cell, role) in model.cells.iter().enumerate() {
        let CellRole::Element(spec) = role else {
            continue;
        };
        let (relation, deformation, occ) = match chosen[cell] {
            Some(k) => (
                occurrences[k].relation.as_str(),
                occurrences[k].deformation.as_str(),
                Some(k),
            ),
            None => {
                uncovered += 1;
                ("ELAS", "PETIT", None)
            }
        };
        let kinematics = kinematics_of(relation, deformation, occ)?;
        if spec.formulation == crate::model::spec::Formulation::PlaneStress
            && !matches!(kinematics, Kinematics::Petit | Kinematics::PetitReac)
        {
            // law::plane_stress solves σ_zz = 0 for the small-strain
            // contract; the finite-strain laws take F, whose F_zz would
            // be the unknown of another Newton, not built.
            return Err(BehaviourError {
                not_implemented: true,
                ..err(
                    occ,
                    "DEFORMATION",
                    format!(
                        "not implemented yet: COMPORTEMENT/DEFORMATION='{deformation}' on the plane-stress element {} \
                         of cell M{} (AFFE_MODELE MODELISATION='C_PLAN'/'C_PLAN_SI'): aster builds \
                         C_PLAN with DEFORMATION='PETIT' and 'PETIT_REAC'; use one of them, or D_PLAN or 3D \
                         for finite strains",
                        spec.name,
                        cell + 1
                    ),
                )
            });
        }
        let mat_name = matfield
            .cell_material
            .get(cell)
            .and_then(|m| m.as_deref())
            .ok_or_else(|| {
                err(
                    None,
                    "",
                    format!(
                        "cell M{} of the model has no material in the CHAM_MATER",
                        cell + 1
                    ),
                )
            })?;
        let mat = materials.get(mat_name).ok_or_else(|| {
            err(
                None,
                "",
                format!("the material {mat_name} of the CHAM_MATER has no data"),
            )
        })?;
        let key = (mat_name.to_string(), relation.to_string(), kinematics, occ);
        let law = match law_index.get(&key) {
            Some(&i) => i,
            None => {
                let controls = match occ {
                    Some(k) => local_controls(relation, &occurrences[k].controls, occ)?,
                    None => LocalControls::default(),
                };
                let l = make_law(mat_name, mat, relation, kinematics, controls, occ)?;
                out.laws.push(l);
                law_index.insert(key, out.laws.len() - 1);
                out.laws.len() - 1
            }
        };
        let rho = if !inertia {
            Some(0.0)
        } else {
            mat.get("ELAS", "RHO")
        }
        .ok_or_else(|| {
            err(
                occ,
                "",
                format!("material {mat_name}: ELAS/RHO is needed by the mass matrix of a dynamic computation"),
            )
        })?;
        out.cells[cell] = Some(CellBehaviour {
            kinematics,
            law,
            rho,
        });
    }
    if uncovered > 0 {
        out.alarms.push(format!(
            "alarm: {uncovered} cells of the model are not covered by COMPORTEMENT; they get RELATION='ELAS', DEFORMATION='PETIT'"
        ));
    }
    Ok(out)
}

fn kinematics_of(
    relation: &str,
    deformation: &str,
    occ: Option<usize>,
) -> Result<Kinematics, BehaviourError> {
    let measure = StrainMeasure::from_aster_name(deformation).ok_or_else(|| {
        err(
            occ,
            "DEFORMATION",
            format!("unknown DEFORMATION '{deformation}'"),
        )
    })?;
    match relation {
        "ELAS" | "VMIS_ISOT_LINE" | "VMIS_ISOT_TRAC" | "VMIS_ISOT_PUIS" | "VMIS_CINE_LINE"
        | "VMIS_JOHN_COOK" => {}
        other => return Err(err(occ, "RELATION", format!("unknown RELATION '{other}'"))),
    }
    if relation == "ELAS" && matches!(measure, StrainMeasure::SimoMiehe | StrainMeasure::GdefLog) {
        return Err(err(
            occ,
            "DEFORMATION",
            format!(
                "RELATION='ELAS' does not accept DEFORMATION='{deformation}' (allowed: PETIT, PETIT_REAC, GROT_GDEP), as in code_aster"
            ),
        ));
    }
    if relation == "VMIS_JOHN_COOK" && measure == StrainMeasure::SimoMiehe {
        return Err(err(
            occ,
            "DEFORMATION",
            "RELATION='VMIS_JOHN_COOK' does not accept DEFORMATION='SIMO_MIEHE' (allowed: PETIT, PETIT_REAC, GROT_GDEP, GDEF_LOG), as in code_aster: use GDEF_LOG for finite strains".into(),
        ));
    }
    if relation == "VMIS_CINE_LINE" && measure == StrainMeasure::SimoMiehe {
        return Err(err(
            occ,
            "DEFORMATION",
            "RELATION='VMIS_CINE_LINE' does not accept DEFORMATION='SIMO_MIEHE' (allowed: PETIT, PETIT_REAC, GROT_GDEP, GDEF_LOG), as in code_aster: use GDEF_LOG for finite strains".into(),
        ));
    }
    Ok(Kinematics::from_strain_measure(measure))
}

/// ALGO_INTE, ITER_INTE_MAXI and RESI_INTE_RELA checked against the law:
/// the scalar methods belong to VMIS_JOHN_COOK; the closed-form laws
/// accept only ANALYTIQUE (code_aster's law declarations).
fn local_controls(
    relation: &str,
    c: &Controls,
    occ: Option<usize>,
) -> Result<LocalControls, BehaviourError> {
    let mut out = LocalControls::default();
    if let Some(a) = &c.algo_inte {
        let allowed: &[&str] = match relation {
            "VMIS_JOHN_COOK" => &["BRENT", "DEKKER", "SECANTE"],
            "VMIS_ISOT_PUIS" => &["DEKKER"],
            _ => &["ANALYTIQUE"],
        };
        if !allowed.contains(&a.as_str()) {
            return Err(err(
                occ,
                "ALGO_INTE",
                format!(
                    "RELATION='{relation}' does not accept ALGO_INTE='{a}' (valid: {})",
                    allowed.join(", ")
                ),
            ));
        }
        if let Some(m) = RootMethod::from_aster_name(a) {
            out.method = m;
        }
    }
    if let Some(n) = c.iter_inte_maxi {
        if n < 1 {
            return Err(err(
                occ,
                "ITER_INTE_MAXI",
                format!("ITER_INTE_MAXI must be >= 1, got {n}"),
            ));
        }
        out.iter_maxi = n as usize;
    }
    if let Some(r) = c.resi_inte_rela {
        if !(r.is_finite() && r > 0.0) {
            return Err(err(
                occ,
                "RESI_INTE_RELA",
                format!("RESI_INTE_RELA must be > 0, got {r}"),
            ));
        }
        out.resi_rela = r;
    }
    Ok(out)
}

fn make_law(
    name: &str,
    mat: &Material,
    relation: &str,
    kin: Kinematics,
    controls: LocalControls,
    occ: Option<usize>,
) -> Result<CellLaw, BehaviourError> {
    let need = |block: &str, p: &str| {
        mat.get(block, p).ok_or_else(|| {
            err(
                occ,
                "RELATION",
                format!("material {name}: {block}/{p} is needed by RELATION='{relation}'"),
            )
        })
    };
    let bad = |e: crate::law::MaterialError| {
        err(
            occ,
            "RELATION",
            format!("material {name}: {}: {}", e.keyword, e.message),
        )
    };
    let elas = ElasParams::new(
        need("ELAS", "E")?,
        need("ELAS", "NU")?,
        mat.get("ELAS", "RHO"),
    )
    .map_err(bad)?;
    if relation == "ELAS" {
        return Ok(CellLaw::Elas(Elas::new(elas)));
    }
    if relation == "VMIS_JOHN_COOK" {
        let opt = |p: &str, default: f64| mat.get("ECRO_COOK", p).unwrap_or(default);
        let ecro = EcroCookParams::new(
            need("ECRO_COOK", "A")?,
            need("ECRO_COOK", "B")?,
            opt("C", 0.0),
            need("ECRO_COOK", "N_PUIS")?,
            opt("M_PUIS", 0.0),
            opt("EPSP0", 1.0),
            opt("TROOM", -1.0),
            opt("TMELT", 1.0),
        )
        .map_err(bad)?;
        let law = VmisJohnCook::new(elas, ecro, controls);
        return Ok(match kin {
            Kinematics::GdefLog => CellLaw::JohnCookLog(GdefLog::new(law)),
            _ => CellLaw::JohnCook(law),
        });
    }
    if relation == "VMIS_ISOT_TRAC" {
        let c = mat.curve("TRACTION", "SIGM").ok_or_else(|| {
            err(
                occ,
                "RELATION",
                format!("material {name}: TRACTION/SIGM is needed by RELATION='{relation}'"),
            )
        })?;
        let curve = TractionCurve::new(&c.abscissas, &c.ordinates, c.right).map_err(bad)?;
        let law = VmisIsotTrac::new(curve.clone(), elas.nu, elas.rho).map_err(bad)?;
        return Ok(match kin {
            Kinematics::SimoMiehe => CellLaw::SimoMiehe(SimoMiehe::with_curve(law.elas, curve)),
            Kinematics::GdefLog => CellLaw::IsotTracLog(GdefLog::new(law)),
            _ => CellLaw::VmisIsotTrac(law),
        });
    }
    if relation == "VMIS_ISOT_PUIS" {
        let hardening = PowerHardening::new(
            elas.e,
            need("ECRO_PUIS", "SY")?,
            need("ECRO_PUIS", "A_PUIS")?,
            need("ECRO_PUIS", "N_PUIS")?,
            controls,
        )
        .map_err(bad)?;
        return Ok(match kin {
            Kinematics::SimoMiehe => {
                CellLaw::SimoMiehe(SimoMiehe::with_hardening(elas, Hardening::Power(hardening)))
            }
            Kinematics::GdefLog => {
                CellLaw::IsotPuisLog(GdefLog::new(VmisIsotPuis::new(elas, hardening)))
            }
            _ => CellLaw::VmisIsotPuis(VmisIsotPuis::new(elas, hardening)),
        });
    }
    let ecro = EcroLineParams::new(
        &elas,
        need("ECRO_LINE", "SY")?,
        need("ECRO_LINE", "D_SIGM_EPSI")?,
    )
    .map_err(bad)?;
    if relation == "VMIS_CINE_LINE" {
        let law = VmisCineLine::new(elas, ecro);
        return Ok(match kin {
            Kinematics::GdefLog => CellLaw::CineLineLog(GdefLog::new(law)),
            _ => CellLaw::VmisCineLine(law),
        });
    }
    Ok(match kin {
        Kinematics::SimoMiehe => CellLaw::SimoMiehe(SimoMiehe::new(elas, ecro)),
        Kinematics::GdefLog => CellLaw::IsotLineLog(GdefLog::new(VmisIsotLine::new(elas, ecro))),
        _ => CellLaw::VmisIsotLine(VmisIsotLine::new(elas, ecro)),
    })
}

/// code_aster's limits of MECA_HEXS8 (te0407, shared/docs/notes/hexs8.md
/// §12), checked before anything is computed so that the message names
/// the COMPORTEMENT occurrence: a law of type COMP_ELAS is refused
/// (ELEMENTSSI_3; RELATION='ELAS' is of that type unless
/// DEFORMATION='PETIT_REAC' or an initial state is given), and so is any
/// strain measure but PETIT and PETIT_REAC (ELEMENTSSI_1).
/// `initial_state` is true when ETAT_INIT gives SIGM or EVOL_NOLI.
pub fn check_hexs8(
    model: &Model,
    occurrences: &[Occurrence],
    initial_state: bool,
) -> Result<(), BehaviourError> {
    let ncells = model.cells.len();
    let mut chosen: Vec<Option<usize>> = vec![None; ncells];
    for (k, occ) in occurrences.iter().enumerate() {
        match &occ.cells {
            None => chosen.iter_mut().for_each(|c| *c = Some(k)),
            Some(cells) => {
                for &c in cells.iter().filter(|&&c| c < ncells) {
                    chosen[c] = Some(k);
                }
            }
        }
    }
    for (cell, role) in model.cells.iter().enumerate() {
        let CellRole::Element(spec) = role else {
            continue;
        };
        if !spec.is_hexs8() {
            continue;
        }
        let occ = chosen[cell];
        let (relation, deformation) = match occ {
            Some(k) => (
                occurrences[k].relation.as_str(),
                occurrences[k].deformation.as_str(),
            ),
            None => ("ELAS", "PETIT"),
        };
        if relation == "ELAS" && deformation != "PETIT_REAC" && !initial_state {
            return Err(err(
                occ,
                "RELATION",
                format!(
                    "cell M{}: the element MECA_HEXS8 (3D_SI on HEXA8) refuses RELATION='ELAS' with \
                     DEFORMATION='{deformation}' (ELEMENTSSI_3): a law written in the reference \
                     configuration cannot drive its incremental hourglass stresses; use \
                     DEFORMATION='PETIT_REAC', an initial state (ETAT_INIT with EVOL_NOLI \
                     or SIGM; DEPL or VITE alone do not count), or an incremental law such as VMIS_ISOT_LINE with a large SY{}",
                    cell + 1,
                    if occ.is_none() {
                        " (this cell is not covered by COMPORTEMENT and got ELAS/PETIT by default)"
                    } else {
                        ""
                    }
                ),
            ));
        }
        if !matches!(deformation, "PETIT" | "PETIT_REAC") {
            return Err(err(
                occ,
                "DEFORMATION",
                format!(
                    "cell M{}: the element MECA_HEXS8 (3D_SI on HEXA8) accepts only \
                     DEFORMATION='PETIT' or 'PETIT_REAC', not '{deformation}' (ELEMENTSSI_1)",
                    cell + 1
                ),
            ));
        }
    }
    Ok(())
}
