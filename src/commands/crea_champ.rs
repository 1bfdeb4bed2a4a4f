//! CREA_CHAMP: creates a nodal field, by assigned values (AFFE) or as a
//! copy of a result's field at one instant (EXTR).

use super::blocks::*;
use super::mesh_args::mesh_of;
use super::model_args::{mesh_of_model, model_of, select_cells, select_nodes};
use super::post_args::{inst_access, is_gauss_name, result_of, step_gauss, step_nodal};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;
use crate::concepts::{ChamElem, ConceptData, ElemQuantity};
use crate::diag::{closest, Diagnostic};
use crate::model::{Dof, Model};
use crate::result::Access;
use crate::result::{GaussField, NodalField};
use crate::study::Study;

pub fn def() -> CommandDef {
    let mut extr = vec![
        concept("RESULTAT", RESULTS)
            .required()
            .doc("result to extract from")
            .kw(),
        text("NOM_CHAM").required().into(NOM_CHAM_RESU).kw(),
        int("NUME_ORDRE").doc("stored index extracted").kw(),
        real("INST")
            .doc("instant extracted, found within CRITERE/PRECISION")
            .kw(),
    ];
    extr.extend(critere_precision(1e-6));
    let spec = command(
        "CREA_CHAMP",
        Produces::ByText(
            "TYPE_CHAM",
            &[("ELGA_", C::ChamElem), ("CART_", C::Carte)],
            C::ChamNo,
        ),
        vec![
            text("TYPE_CHAM")
                .required()
                .into(TYPE_CHAM)
                .doc("location and quantity of the field: AFFE builds NOEU_DEPL_R, and on a MODELE the fields at Gauss points ELGA_SIEF_R (SIXX...) and ELGA_VARI_R (V1, V2...) that ETAT_INIT SIGM and VARI take, and CART_SIEF_R (a value per cell, on a MAILLAGE or a MODELE) for SIGM; EXTR copies a nodal field of a result (NOEU_*) or its SIEF_ELGA / VARI_ELGA (ELGA_SIEF_R / ELGA_VARI_R); ELGA_EPSI_R and the ELNO_* fields are not built yet")
                .kw(),
            text("OPERATION")
                .required()
                .into(&["AFFE", "EXTR"])
                .doc("assign values, or extract a field from a result")
                .kw(),
            block(
                "b_affe",
                eq("OPERATION", "AFFE"),
                vec![
                    concept("MAILLAGE", &[C::Maillage]).kw(),
                    concept("MODELE", &[C::Modele])
                        .doc("model: its dofs (including contact LAGS_C, LAGS_F1) define the allowed components")
                        .kw(),
                    fact(
                        "AFFE",
                        vec![
                            tout(),
                            group_ma(),
                            maille(),
                            group_no(),
                            noeud(),
                            text("NOM_CMP").required().many().doc("components").kw(),
                            real("VALE")
                                .many()
                                .doc("values, one per NOM_CMP")
                                .kw(),
                            int("VALE_I").many().kw(),
                            concept("VALE_F", &[C::Fonction]).many().kw(),
                        ],
                    )
                    .required()
                    .many()
                    .rules(vec![
                        au_moins_un(&["TOUT", "GROUP_MA", "MAILLE", "GROUP_NO", "NOEUD"]),
                        un_parmi(&["VALE", "VALE_I", "VALE_F"]),
                    ])
                    .doc("applied in order, later occurrences overwrite earlier ones; unassigned components are absent")
                    .kw(),
                ],
            )
            .rules(vec![un_parmi(&["MAILLAGE", "MODELE"])])
            .kw(),
            block(
                "b_prol_zero",
                is_in(
                    "TYPE_CHAM",
                    &[
                        "ELGA_SIEF_R",
                        "ELGA_VARI_R",
                        "ELGA_EPSI_R",
                        "ELNO_SIEF_R",
                        "ELNO_VARI_R",
                        "ELNO_EPSI_R",
                    ],
                ),
                vec![oui_non("PROL_ZERO", "NON")
                    .doc("'OUI': the components of the field that no AFFE occurrence assigns are 0 on every element of the MODELE (code_aster's cham_elem prolonged by zero); 'NON' leaves them absent, which ETAT_INIT reads as 0 too (as it reads MECA_HEXS8's FSTAB hourglass stresses, which the field does not carry)")
                    .kw()],
            )
            .kw(),
            block("b_extr", eq("OPERATION", "EXTR"), extr)
                .rules(vec![un_parmi(&["NUME_ORDRE", "INST"])])
                .kw(),
            info(),
            titre(),
        ],
    )
    .doc("Creates a nodal field (cham_no) or a field at Gauss points (cham_elem, TYPE_CHAM='ELGA_SIEF_R' / 'ELGA_VARI_R'): assigned values (AFFE), e.g. an initial velocity or an initial stress for ETAT_INIT, or a copy of a result's field at one instant (EXTR), e.g. for TEST_RESU CHAM_NO or to start another computation from its SIEF_ELGA.");
    CommandDef { spec, exec }
}

/// Components of code_aster's DEPL_R quantity that a nodal field of aster
/// may carry: displacements and rotations, and the contact unknowns of the
/// continuous formulation (LAGS_C, LAGS_F1, LAGS_F2), which sdnv103f sets
/// in its initial velocity. The other DEPL_R components (pressures,
/// temperatures of coupled elements...) are outside aster's scope.
pub const DEPL_R: &[&str] = &[
    "DX", "DY", "DZ", "DRX", "DRY", "DRZ", "LAGS_C", "LAGS_F1", "LAGS_F2",
];

/// TYPE_CHAM values of the catalogue: the nodal ones that EXTR copies
/// (and AFFE builds, NOEU_DEPL_R), and code_aster's fields by element,
/// which are refused at run time as not built yet.
const TYPE_CHAM: &[&str] = &[
    "NOEU_DEPL_R",
    "NOEU_SIEF_R",
    "NOEU_EPSI_R",
    "NOEU_VAR2_R",
    "NOEU_INFC_R",
    "NOEU_ENER_R",
    "ELGA_SIEF_R",
    "ELGA_VARI_R",
    "ELGA_EPSI_R",
    "ELNO_SIEF_R",
    "ELNO_VARI_R",
    "ELNO_EPSI_R",
    "CART_SIEF_R",
];

/// The TYPE_CHAM of a result's nodal field (code_aster's quantities:
/// FORC_NODA and REAC_NODA are DEPL_R, the stresses and their
/// equivalents SIEF_R, the strains and theirs EPSI_R, the internal
/// variables at nodes VAR2_R, the discrete contact's CONT_NOEU INFC_R,
/// the elastic energy ENER_R).
pub fn nodal_type_cham(nom_cham: &str) -> Option<&'static str> {
    Some(match nom_cham {
        "DEPL" | "VITE" | "ACCE" | "FORC_NODA" | "REAC_NODA" => "NOEU_DEPL_R",
        "SIEF_NOEU" | "SIGM_NOEU" | "SIEQ_NOEU" => "NOEU_SIEF_R",
        "EPSI_NOEU" | "EPSG_NOEU" | "EPSL_NOEU" | "EPEQ_NOEU" => "NOEU_EPSI_R",
        "VARI_NOEU" => "NOEU_VAR2_R",
        "CONT_NOEU" => "NOEU_INFC_R",
        "ENEL_NOEU" => "NOEU_ENER_R",
        _ => return None,
    })
}

fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    let type_cham = args.text("TYPE_CHAM").unwrap_or_default();
    if type_cham == "CART_SIEF_R" {
        return match args.text("OPERATION") {
            Some("AFFE") => affe_elga(study, args, ElemQuantity::Sief, true, result),
            _ => Err(args.error(
                "OPERATION",
                "a CART_SIEF_R field is built by OPERATION='AFFE' (a result stores its stresses at the Gauss points: EXTR them as TYPE_CHAM='ELGA_SIEF_R')",
            )),
        };
    }
    if let Some(q) = elga_quantity(type_cham) {
        return match args.text("OPERATION") {
            Some("AFFE") => affe_elga(study, args, q, false, result),
            _ => extr_elga(study, args, q, result),
        };
    }
    if !type_cham.starts_with("NOEU_") {
        return Err(args.not_implemented(
            "TYPE_CHAM",
            "ELGA_EPSI_R and the fields at element nodes (ELNO_*); CREA_CHAMP builds nodal fields (AFFE of NOEU_DEPL_R, EXTR of NOEU_DEPL_R, NOEU_SIEF_R, NOEU_EPSI_R, NOEU_VAR2_R, NOEU_INFC_R, NOEU_ENER_R) and the Gauss-point fields ELGA_SIEF_R and ELGA_VARI_R (AFFE on a MODELE, EXTR of SIEF_ELGA / VARI_ELGA)",
        ));
    }
    match args.text("OPERATION") {
        Some("AFFE") if type_cham != "NOEU_DEPL_R" => Err(args.not_implemented(
            "TYPE_CHAM",
            "OPERATION='AFFE' of a nodal field other than NOEU_DEPL_R",
        )),
        Some("AFFE") => affe(study, args, result),
        _ => extr(study, args, type_cham, result),
    }
}

/// The quantity of a TYPE_CHAM at Gauss points that CREA_CHAMP builds.
fn elga_quantity(type_cham: &str) -> Option<ElemQuantity> {
    match type_cham {
        "ELGA_SIEF_R" => Some(ElemQuantity::Sief),
        "ELGA_VARI_R" => Some(ElemQuantity::Vari),
        _ => None,
    }
}

/// The stress components of the elements of a model, in SIEF_ELGA order:
/// (SIXX, SIYY, SIZZ, SIXY) in AXIS and D_PLAN, with SIXZ, SIYZ in 3D.
pub fn model_sief_components(model: &Model) -> Vec<String> {
    let plane = model
        .element_cells()
        .next()
        .is_some_and(|(_, s)| s.formulation != crate::model::spec::Formulation::Solid3d);
    let all = ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"];
    all[..if plane { 4 } else { 6 }]
        .iter()
        .map(|s| s.to_string())
        .collect()
}

/// OPERATION='AFFE' of ELGA_SIEF_R / ELGA_VARI_R on a MODELE (code_aster's
/// cham_elem of CREA_CHAMP): every point of each selected element gets
/// the values, occurrences in order, later ones overwriting earlier ones;
/// a value never assigned stays absent (NaN), which ETAT_INIT reads as 0.
/// The points are those of the element's SIEF_ELGA (its RIGI family,
/// HEXS8's one centre point), so the field matches the state of a
/// STAT_NON_LINE / DYNA_NON_LINE on this model point for point.
///
/// `cart`: TYPE_CHAM='CART_SIEF_R', one value per cell (one point), on a
/// MAILLAGE (every cell, the six stress components) or a MODELE (its
/// elements, their components).
fn affe_elga(
    study: &mut Study,
    args: &Args,
    q: ElemQuantity,
    cart: bool,
    result: Option<&str>,
) -> ExecResult {
    let tc = if cart { "CART_SIEF_R" } else { q.type_cham() };
    if !args.has("MODELE") && !cart {
        return Err(args.error(
            "MAILLAGE",
            format!("a field at Gauss points ({tc}) is built on the elements of a model: give MODELE instead of MAILLAGE"),
        ));
    }
    let (name, m) = if args.has("MODELE") {
        let (name, m) = model_of(study, args, "MODELE")?;
        (name.to_string(), Some(m.clone()))
    } else {
        (String::new(), None)
    };
    let (mesh, mesh_name) = match &m {
        Some(m) => (mesh_of_model(study, args, "MODELE", m)?, m.mesh.clone()),
        None => (
            mesh_of(study, args, "MAILLAGE")?,
            args.concept("MAILLAGE").unwrap_or_default().to_string(),
        ),
    };
    let allowed = match &m {
        Some(m) => model_sief_components(m),
        None => ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"]
            .iter()
            .map(|s| s.to_string())
            .collect(),
    };
    let occs = args.facts("AFFE");
    let mut nvar = 0usize;
    for occ in occs {
        if let Some(k) = ["GROUP_NO", "NOEUD"].into_iter().find(|k| occ.has(k)) {
            return Err(occ.error(
                k,
                format!("a field at Gauss points ({tc}) is assigned on cells: use TOUT, GROUP_MA or MAILLE"),
            ));
        }
        if !occ.has("VALE") {
            let key = if occ.has("VALE_F") {
                "VALE_F"
            } else {
                "VALE_I"
            };
            return Err(occ.error(
                key,
                format!("a field of type {tc} takes real values: use VALE"),
            ));
        }
        let cmps = occ.texts("NOM_CMP");
        let vale = occ.reals("VALE");
        if cmps.len() != vale.len() {
            return Err(occ.error(
                "VALE",
                format!(
                    "NOM_CMP gives {} component(s) and VALE {} value(s): they must have the same length",
                    cmps.len(),
                    vale.len()
                ),
            ));
        }
        for (i, c) in cmps.iter().enumerate() {
            if cmps[..i].contains(c) {
                return Err(occ.error(
                    "NOM_CMP",
                    format!("the component {c} is given twice in NOM_CMP"),
                ));
            }
            match q {
                ElemQuantity::Sief if !allowed.iter().any(|a| a == c) => {
                    let all = ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"];
                    let why = if all.contains(c) {
                        format!("the elements of the model {name} (a plane or axisymmetric model) have no stress component {c}")
                    } else {
                        format!("{c} is not a stress component of the elements of the model {name}")
                    };
                    let mut d = occ.error("NOM_CMP", format!("{why}: their components are {}", allowed.join(", ")));
                    d.suggestion = closest(c, &allowed.iter().map(String::as_str).collect::<Vec<_>>());
                    return Err(d);
                }
                ElemQuantity::Vari => match crate::result::vari_index(c) {
                    Some(k) => nvar = nvar.max(k),
                    None => {
                        return Err(occ.error(
                            "NOM_CMP",
                            format!("{c} is not a component of the quantity VARI_R, whose components are V1, V2, ... (the internal variables in the order of the law)"),
                        ))
                    }
                },
                _ => {}
            }
        }
    }
    let components: Vec<String> = match q {
        ElemQuantity::Sief => allowed,
        ElemQuantity::Vari => (1..=nvar).map(|k| format!("V{k}")).collect(),
    };
    let ncmp = components.len();
    let ncells = mesh.ncells();
    let mut npg = vec![0usize; ncells];
    match &m {
        Some(m) => {
            for (c, spec) in m.element_cells() {
                if c < ncells {
                    npg[c] = if cart {
                        1
                    } else {
                        crate::element::output_points(spec)
                    };
                }
            }
        }
        None => npg.iter_mut().for_each(|n| *n = 1),
    }
    let mut offsets = Vec::with_capacity(ncells + 1);
    let mut total = 0;
    for &n in &npg {
        offsets.push(total);
        total += n * ncmp;
    }
    offsets.push(total);
    let mut field = GaussField {
        components,
        offsets,
        values: vec![f64::NAN; total],
    };
    let mut lines = Vec::new();
    for (k, occ) in occs.iter().enumerate() {
        let cells = select_cells(mesh, occ)?;
        let idx: Vec<usize> = occ
            .texts("NOM_CMP")
            .iter()
            .map(|c| field.components.iter().position(|x| x == c).unwrap_or(0))
            .collect();
        let vale = occ.reals("VALE");
        let mut touched = 0;
        for &c in &cells {
            if npg[c] == 0 {
                continue;
            }
            touched += 1;
            let base = field.offsets[c];
            for p in 0..npg[c] {
                for (&i, &v) in idx.iter().zip(&vale) {
                    field.values[base + p * ncmp + i] = v;
                }
            }
        }
        lines.push(format!(
            "      AFFE {}: {touched} cells, {}",
            k + 1,
            occ.texts("NOM_CMP")
                .iter()
                .zip(&vale)
                .map(|(c, v)| format!("{c}={v}"))
                .collect::<Vec<_>>()
                .join(" ")
        ));
    }
    if args.text("PROL_ZERO") == Some("OUI") {
        for v in field.values.iter_mut().filter(|v| v.is_nan()) {
            *v = 0.0;
        }
    }
    let absent = field.values.iter().filter(|v| v.is_nan()).count();
    let nelem = npg.iter().filter(|&&n| n > 0).count();
    study.log(format!(
        "    field {} ({tc}) on {}: components {}, {nelem} cells, {} points, {absent} absent (point, component) values (read as 0 by ETAT_INIT)",
        result.unwrap_or("(unnamed)"),
        if name.is_empty() { format!("mesh {mesh_name}") } else { format!("model {name}") },
        field.components.join(" "),
        npg.iter().sum::<usize>()
    ));
    for l in lines {
        study.log(l);
    }
    Ok(Some(ConceptData::ElemField(Box::new(ChamElem {
        mesh: mesh_name,
        model: name,
        quantity: q,
        by_cell: cart,
        field,
    }))))
}

/// OPERATION='EXTR' of a result's SIEF_ELGA (ELGA_SIEF_R) or VARI_ELGA
/// (ELGA_VARI_R) at one step: a copy, on the result's model, that
/// ETAT_INIT SIGM / VARI read back point for point.
fn extr_elga(study: &mut Study, args: &Args, q: ElemQuantity, result: Option<&str>) -> ExecResult {
    let tc = q.type_cham();
    let (rname, res) = result_of(study, args, "RESULTAT")?;
    let nom_cham = args.text("NOM_CHAM").unwrap_or_default();
    let expected = match nom_cham {
        "SIEF_ELGA" => ElemQuantity::Sief,
        "VARI_ELGA" => ElemQuantity::Vari,
        _ => {
            return Err(args.error(
                "NOM_CHAM",
                format!(
                    "EXTR of a field of type {tc} copies {}; {nom_cham} is not one",
                    match q {
                        ElemQuantity::Sief => "SIEF_ELGA",
                        ElemQuantity::Vari => "VARI_ELGA",
                    }
                ),
            ))
        }
    };
    if expected != q {
        return Err(args.error(
            "TYPE_CHAM",
            format!(
                "{nom_cham} is a field of type {}, not {tc}: give TYPE_CHAM='{}'",
                expected.type_cham(),
                expected.type_cham()
            ),
        ));
    }
    let (step, key) = match args.int("NUME_ORDRE") {
        Some(n) => {
            let n = usize::try_from(n)
                .map_err(|_| args.error("NUME_ORDRE", format!("NUME_ORDRE {n} is negative")))?;
            (res.find(Access::NumeOrdre(n)), "NUME_ORDRE")
        }
        None => {
            let t = args
                .real("INST")
                .ok_or_else(|| args.error("INST", "NUME_ORDRE or INST is needed"))?;
            (res.find(inst_access(args, t, 1e-6)), "INST")
        }
    };
    let step = step.map_err(|e| args.error(key, format!("result {rname}: {e}")))?;
    let field = step_gauss(step, nom_cham, args, "NOM_CHAM", rname)?.clone();
    let line = format!(
        "    field {} ({tc}) = {nom_cham} of {rname} at NUME_ORDRE {} (INST {:e}) on model {}: components {}",
        result.unwrap_or("(unnamed)"),
        step.nume_ordre,
        step.inst,
        res.model,
        field.components.join(" "),
    );
    let data = ChamElem {
        mesh: res.mesh.clone(),
        model: res.model.clone(),
        quantity: q,
        by_cell: false,
        field,
    };
    study.log(line);
    Ok(Some(ConceptData::ElemField(Box::new(data))))
}

/// OPERATION='EXTR' from RESULTAT: a copy of the nodal field NOM_CHAM of
/// the step that NUME_ORDRE or INST (within CRITERE/PRECISION) designates,
/// on the result's mesh. The field keeps the result's components and its
/// absent pairs (a CONT_NOEU outside the contact zones stays absent).
fn extr(study: &mut Study, args: &Args, type_cham: &str, result: Option<&str>) -> ExecResult {
    let (rname, res) = result_of(study, args, "RESULTAT")?;
    let nom_cham = args.text("NOM_CHAM").unwrap_or_default();
    let Some(expected) = nodal_type_cham(nom_cham) else {
        let what = if is_gauss_name(nom_cham) || nom_cham.ends_with("_ELNO") {
            "a field by element"
        } else {
            "not a nodal field"
        };
        return Err(args.not_implemented(
            "NOM_CHAM",
            &format!(
                "EXTR of {nom_cham} ({what}); EXTR copies the nodal fields DEPL, VITE, ACCE, FORC_NODA, REAC_NODA (NOEU_DEPL_R), SIEF_NOEU, SIGM_NOEU, SIEQ_NOEU (NOEU_SIEF_R), EPSI_NOEU, EPSG_NOEU, EPSL_NOEU, EPEQ_NOEU (NOEU_EPSI_R), VARI_NOEU (NOEU_VAR2_R), CONT_NOEU (NOEU_INFC_R), ENEL_NOEU (NOEU_ENER_R)"
            ),
        ));
    };
    if expected != type_cham {
        return Err(args.error(
            "TYPE_CHAM",
            format!("{nom_cham} is a field of type {expected}, not {type_cham}: give TYPE_CHAM='{expected}'"),
        ));
    }
    let (step, key) = match args.int("NUME_ORDRE") {
        Some(n) => {
            let n = usize::try_from(n)
                .map_err(|_| args.error("NUME_ORDRE", format!("NUME_ORDRE {n} is negative")))?;
            (res.find(Access::NumeOrdre(n)), "NUME_ORDRE")
        }
        None => {
            let t = args
                .real("INST")
                .ok_or_else(|| args.error("INST", "NUME_ORDRE or INST is needed"))?;
            (res.find(inst_access(args, t, 1e-6)), "INST")
        }
    };
    let step = step.map_err(|e| args.error(key, format!("result {rname}: {e}")))?;
    let field = step_nodal(step, nom_cham, args, "NOM_CHAM", rname)?.clone();
    let absent = field.values.iter().filter(|v| v.is_nan()).count();
    let line = format!(
        "    field {} ({type_cham}) = {nom_cham} of {rname} at NUME_ORDRE {} (INST {:e}): components {}, {} nodes, {absent} absent (node, component) pairs",
        result.unwrap_or("(unnamed)"),
        step.nume_ordre,
        step.inst,
        field.components.join(" "),
        field.nnodes()
    );
    let mesh = res.mesh.clone();
    study.log(line);
    Ok(Some(ConceptData::Field(Box::new(
        crate::concepts::ChamNo { mesh, field },
    ))))
}

/// OPERATION='AFFE' (code_aster's `cnoaff`): the components are the union
/// of all NOM_CMP in order of first appearance; occurrences are applied in
/// order, later ones overwriting earlier ones node by node and component
/// by component; a pair never assigned stays absent (NaN), which is not
/// zero: ETAT_INIT reads it as 0 but a field operation must not.
fn affe(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    let (support, model, mesh, mesh_name) = if args.has("MODELE") {
        let (name, m) = model_of(study, args, "MODELE")?;
        let mesh = mesh_of_model(study, args, "MODELE", m)?;
        let mesh_name = m.mesh.clone();
        (
            format!("model {name}"),
            Some((name, m.clone())),
            mesh,
            mesh_name,
        )
    } else {
        let name = args.concept("MAILLAGE").unwrap_or_default();
        (
            format!("mesh {name}"),
            None,
            mesh_of(study, args, "MAILLAGE")?,
            name.to_string(),
        )
    };
    let occs = args.facts("AFFE");
    let mut components: Vec<String> = Vec::new();
    for occ in occs {
        if !occ.has("VALE") {
            let key = if occ.has("VALE_F") {
                "VALE_F"
            } else {
                "VALE_I"
            };
            return Err(occ.error(
                key,
                "a field of type NOEU_DEPL_R takes real values: use VALE",
            ));
        }
        let cmps = occ.texts("NOM_CMP");
        let vale = occ.reals("VALE");
        if cmps.len() != vale.len() {
            return Err(occ.error(
                "VALE",
                format!(
                    "NOM_CMP gives {} component(s) and VALE {} value(s): they must have the same length",
                    cmps.len(),
                    vale.len()
                ),
            ));
        }
        for (i, c) in cmps.iter().enumerate() {
            check_component(occ, c, model.as_ref())?;
            if cmps[..i].contains(c) {
                return Err(occ.error(
                    "NOM_CMP",
                    format!("the component {c} is given twice in NOM_CMP"),
                ));
            }
            if !components.iter().any(|x| x == c) {
                components.push(c.to_string());
            }
        }
    }
    let tout: Vec<usize> = match &model {
        Some((_, m)) => {
            let mask = m.node_mask(mesh);
            (0..mesh.nnodes()).filter(|&n| mask[n]).collect()
        }
        None => (0..mesh.nnodes()).collect(),
    };
    let mut field = NodalField::absent(components, mesh.nnodes());
    let mut lines = Vec::new();
    for (k, occ) in occs.iter().enumerate() {
        let nodes = select_nodes(mesh, occ, &tout)?;
        let cmps = occ.texts("NOM_CMP");
        let vale = occ.reals("VALE");
        let idx: Vec<usize> = cmps
            .iter()
            .filter_map(|c| field.component_index(c))
            .collect();
        for &n in &nodes {
            for (&c, &v) in idx.iter().zip(&vale) {
                field.set(n, c, v);
            }
        }
        lines.push(format!(
            "      AFFE {}: {} nodes, {}",
            k + 1,
            nodes.len(),
            cmps.iter()
                .zip(&vale)
                .map(|(c, v)| format!("{c}={v}"))
                .collect::<Vec<_>>()
                .join(" ")
        ));
    }
    let absent = field.values.iter().filter(|v| v.is_nan()).count();
    let header = format!(
        "    field {} (NOEU_DEPL_R) on {support}: components {}, {} nodes, {absent} absent (node, component) pairs",
        result.unwrap_or("(unnamed)"),
        field.components.join(" "),
        mesh.nnodes()
    );
    study.log(header);
    for l in lines {
        study.log(l);
    }
    Ok(Some(ConceptData::Field(Box::new(
        crate::concepts::ChamNo {
            mesh: mesh_name,
            field,
        },
    ))))
}

/// A component must belong to DEPL_R; on a model, a displacement or
/// rotation must also be one of its dofs (DZ on an AXIS model is an error).
/// The contact multipliers are accepted on any model: they are unknowns
/// DEFI_CONTACT adds later, not dofs of the model itself.
fn check_component(occ: &Args, c: &str, model: Option<&(String, Model)>) -> Result<(), Diagnostic> {
    if !DEPL_R.contains(&c) {
        let mut d = occ.error(
            "NOM_CMP",
            format!("{c} is not a component of the quantity DEPL_R"),
        );
        d.suggestion = closest(c, DEPL_R);
        d.choices = DEPL_R.iter().map(|s| s.to_string()).collect();
        return Err(d);
    }
    if let Some((name, m)) = model {
        let is_lagrange = c.starts_with("LAGS_");
        if !is_lagrange && !Dof::from_name(c).is_some_and(|d| m.has_dof(d)) {
            return Err(occ.error(
                "NOM_CMP",
                format!(
                    "{c} is not a degree of freedom of the model {name}, whose nodes carry {}",
                    m.dofs
                        .iter()
                        .map(|d| d.name())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ));
        }
    }
    Ok(())
}
