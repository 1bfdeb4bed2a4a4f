//! AFFE_CHAR_MECA_F: mechanical loads whose values are functions
//! (DEFI_CONSTANTE, DEFI_FONCTION, FORMULE) of the instant and of the
//! node's initial coordinates, code_aster's `affe_char_meca_f.py`. The
//! concept is a char_meca like AFFE_CHAR_MECA's, so EXCIT (with FONC_MULT
//! multiplying the values) and CALC_CHAMP take it; the engine evaluates
//! the functions at each step's end instant (`nonlinear::loads`).

use super::affe_char_meca::{
    distributed_cells, face_impo_selection, force_components, pressure_cells, DISTRIBUTED_KINDS,
};
use super::blocks::*;
use super::model_args::{load_model, select_nodes, selection_label, LoadModel};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::diag::Diagnostic;
use crate::model::{
    Dof, FieldDensity, FieldFunction, FunctionTarget, ImposedDof, MechLoad, NodalFunction,
};
use crate::post::formula::{Coef, NODE_PARAMS};
use crate::study::Study;

/// A keyword whose value is a function of INST, X, Y, Z.
fn function(name: &'static str, doc: &'static str) -> Keyword {
    concept(name, &[C::Fonction, C::Formule]).doc(doc).kw()
}

/// Keywords of code_aster's catalogue that are declared (so that a
/// command file using them reads) and refused when given.
const NOT_BUILT: &[&str] = &["LIAISON_DDL", "LIAISON_OBLIQUE"];

/// The keywords of distributed loads, whose values are functions of INST
/// and of the position of the Gauss point.
const DISTRIBUTED: &[&str] = &[
    "PRES_REP",
    "FORCE_FACE",
    "FORCE_ARETE",
    "FORCE_CONTOUR",
    "FORCE_INTERNE",
];

/// A distributed-load keyword: a cell selection and function components.
fn field_fact(name: &'static str, cmps: &[&'static str], doc: &'static str) -> Keyword {
    let mut kws = vec![tout(), group_ma(), maille()];
    for &c in cmps {
        kws.push(match c {
            "MX" | "MY" | "MZ" | "CISA_2D" => concept(c, &[C::Fonction, C::Formule]).kw(),
            "PRES" => function(
                c,
                "pressure (MPa) against the normal of the skin cell: a function of INST and the Gauss point's initial X, Y, Z",
            ),
            _ => function(
                c,
                "component of the force density: a function of INST and the Gauss point's initial X, Y, Z",
            ),
        });
    }
    fact(name, kws)
        .many()
        .rules(vec![
            au_moins_un(&["TOUT", "GROUP_MA", "MAILLE"]),
            au_moins_un(cmps),
        ])
        .doc(doc)
        .kw()
}

pub fn def() -> CommandDef {
    let mut ddl = ddl_selection();
    for &c in CMP_DEPL {
        ddl.push(function(
            c,
            "imposed value of this component: a function of INST and the node's initial X, Y, Z",
        ));
    }
    let forces = ["FX", "FY", "FZ"];
    let mut nodal = vec![group_no(), noeud()];
    for c in forces {
        nodal.push(function(
            c,
            "force along this axis on each node: a function of INST, X, Y, Z",
        ));
    }
    for c in ["MX", "MY", "MZ"] {
        nodal.push(concept(c, &[C::Fonction, C::Formule]).kw());
    }
    nodal.push(concept("ANGL_NAUT", &[C::Fonction, C::Formule]).many().kw());
    let spec = command(
        "AFFE_CHAR_MECA_F",
        Produces::Concept(C::CharMeca),
        vec![
            concept("MODELE", &[C::Modele]).required().kw(),
            imposed_dofs(
                "DDL_IMPO",
                ddl,
                CMP_DEPL,
                "imposed dofs whose values are functions of INST and of the node's initial X, Y, Z, evaluated at each step's end instant; GROUP_MA means all nodes of those cells; a node given again by a later occurrence keeps the later function of that component",
            )
            .kw(),
            fact("FORCE_NODALE", nodal)
                .many()
                .rules(vec![
                    au_moins_un(&["GROUP_NO", "NOEUD"]),
                    au_moins_un(&["FX", "FY", "FZ", "MX", "MY", "MZ"]),
                ])
                .doc("force on each node of the selection, global frame, a function of INST and the node's initial X, Y, Z evaluated at each step's end instant; a node given again keeps the later function of that component")
                .kw(),
            field_fact(
                "PRES_REP",
                &["PRES", "CISA_2D"],
                "pressure on the skin cells of the selection (SEG in AXIS, per radian; TRIA/QUAD in 3D), as AFFE_CHAR_MECA's PRES_REP but a function of INST and of the Gauss point's initial X, Y, Z, evaluated at each instant the engine needs",
            ),
            field_fact(
                "FORCE_FACE",
                &["FX", "FY", "FZ"],
                "force per unit area on the TRIA/QUAD skin cells of a 3D model, as AFFE_CHAR_MECA's FORCE_FACE but each component a function of INST and of the Gauss point's initial X, Y, Z",
            ),
            field_fact(
                "FORCE_ARETE",
                &["FX", "FY", "FZ", "MX", "MY", "MZ"],
                "force per unit length on the SEG cells of a 3D model, each component a function of INST, X, Y, Z",
            ),
            field_fact(
                "FORCE_CONTOUR",
                &["FX", "FY", "FZ", "MX", "MY", "MZ"],
                "force per unit length on the SEG edges of a 2D model (per radian in AXIS), each component a function of INST, X, Y, Z",
            ),
            field_fact(
                "FORCE_INTERNE",
                &["FX", "FY", "FZ"],
                "force per unit volume on the volume elements of the selection (per radian in AXIS), each component a function of INST, X, Y, Z",
            ),
            fact(
                "FACE_IMPO",
                [face_impo_selection(), vec![
                    function("DX", "imposed value of this component on every node of the cells: a function of INST and the node's initial X, Y, Z"),
                    function("DY", "imposed value of this component on every node of the cells: a function of INST and the node's initial X, Y, Z"),
                    function("DZ", "imposed value of this component on every node of the cells: a function of INST and the node's initial X, Y, Z"),
                    concept("DNOR", &[C::Fonction, C::Formule]).kw(),
                    concept("DTAN", &[C::Fonction, C::Formule]).kw(),
                ]]
                .concat(),
            )
            .many()
            .rules(vec![
                au_moins_un(&["GROUP_MA", "MAILLE"]),
                au_moins_un(&["DX", "DY", "DZ", "DNOR", "DTAN"]),
            ])
            .doc("imposed dofs on the nodes of the cells of the selection (less SANS_*), as DDL_IMPO with GROUP_MA: DX, DY, DZ functions of INST and the node's initial X, Y, Z; DNOR and DTAN are not implemented here")
            .kw(),
            fact(
                "LIAISON_DDL",
                vec![
                    group_no(),
                    noeud(),
                    text("DDL").many().kw(),
                    real("COEF_MULT").many().kw(),
                    concept("COEF_IMPO", &[C::Fonction, C::Formule]).kw(),
                ],
            )
            .many()
            .doc("not implemented yet")
            .kw(),
            fact(
                "LIAISON_OBLIQUE",
                vec![
                    group_no(),
                    noeud(),
                    real("ANGL_NAUT").many().kw(),
                    concept("DX", &[C::Fonction, C::Formule]).kw(),
                    concept("DY", &[C::Fonction, C::Formule]).kw(),
                    concept("DZ", &[C::Fonction, C::Formule]).kw(),
                ],
            )
            .many()
            .doc("not implemented yet")
            .kw(),
            oui_non("VERI_NORM", "OUI")
                .doc("check the orientation of skin cells carrying loads")
                .kw(),
            oui_non("DOUBLE_LAGRANGE", "OUI")
                .doc("two Lagrange multipliers per constraint")
                .kw(),
            info(),
        ],
    )
    .rules(vec![au_moins_un(
        &[["DDL_IMPO", "FACE_IMPO", "FORCE_NODALE"].as_slice(), DISTRIBUTED, NOT_BUILT].concat(),
    )])
    .doc("Defines mechanical boundary conditions and loads whose values are functions of time (INST) and of the nodes' initial coordinates (X, Y, Z).");
    CommandDef { spec, exec }
}

/// The function concept `name` given to `key`, checked to depend on
/// INST, X, Y, Z only (the parameters the engine evaluates it with).
fn coef_of(study: &Study, occ: &Args, key: &str, name: &str) -> Result<Coef, Diagnostic> {
    let coef = match study.concepts.data(name) {
        Some(ConceptData::Function(f)) => Coef::Function((**f).clone()),
        Some(ConceptData::Formula(f)) => Coef::Formula((**f).clone()),
        _ => {
            return Err(occ.error(
                key,
                format!("{name} holds no function (its command did not run)"),
            ))
        }
    };
    if let Some(p) = coef.unknown_param(&NODE_PARAMS) {
        return Err(occ.error(
            key,
            format!(
                "{name} is a function of {p}: AFFE_CHAR_MECA_F evaluates its functions with INST and the node's initial X, Y, Z only"
            ),
        ));
    }
    Ok(coef)
}

/// The nodes of `entries` already given the same (target, dof) lose
/// `nodes`: the later occurrence wins.
fn take_nodes(entries: &mut [NodalFunction], target: FunctionTarget, dof: Dof, nodes: &[usize]) {
    let mut mask = std::collections::HashSet::new();
    mask.extend(nodes.iter().copied());
    for e in entries
        .iter_mut()
        .filter(|e| e.target == target && e.dof == dof)
    {
        e.nodes.retain(|n| !mask.contains(n));
    }
}

fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    for &key in NOT_BUILT {
        if let Some(occ) = args.facts(key).first() {
            return Err(
                occ.not_implemented("", "AFFE_CHAR_MECA_F builds DDL_IMPO, FACE_IMPO, FORCE_NODALE, PRES_REP, FORCE_FACE, FORCE_ARETE, FORCE_CONTOUR and FORCE_INTERNE")
            );
        }
    }
    function_load(
        study,
        args,
        result,
        &[
            ("DDL_IMPO", FunctionTarget::Imposed, CMP_DEPL),
            (
                "FACE_IMPO",
                FunctionTarget::Imposed,
                &["DX", "DY", "DZ"][..],
            ),
            (
                "FORCE_NODALE",
                FunctionTarget::Force,
                &["FX", "FY", "FZ"][..],
            ),
        ],
    )
}

/// The nodal keywords of `sources` (keyword, what its values are, the
/// components it takes) and the distributed ones, as functions of INST,
/// X, Y, Z: AFFE_CHAR_MECA_F's and AFFE_CHAR_CINE_F's (MECA_IMPO).
pub(super) fn function_load(
    study: &mut Study,
    args: &Args,
    result: Option<&str>,
    sources: &[(&str, FunctionTarget, &[&str])],
) -> ExecResult {
    let LoadModel {
        name: model_name,
        model,
        mesh,
        in_model,
        nodes: model_nodes,
        dof_names,
    } = load_model(study, args)?;
    let mut functions: Vec<NodalFunction> = Vec::new();
    let mut lines = Vec::new();
    for &(key, target, cmps) in sources {
        for (k, occ) in args.facts(key).iter().enumerate() {
            if target == FunctionTarget::Force {
                for m in ["MX", "MY", "MZ"] {
                    if occ.has(m) {
                        return Err(occ.not_implemented(
                            m,
                            "nodal moments (no element of aster has rotational dofs)",
                        ));
                    }
                }
                if occ.has("ANGL_NAUT") {
                    return Err(
                        occ.not_implemented("ANGL_NAUT", "forces are given in the global frame")
                    );
                }
            }
            if key == "FACE_IMPO" {
                for c in ["DNOR", "DTAN"] {
                    if occ.has(c) {
                        return Err(occ.not_implemented(
                            c,
                            &format!("{c} as a function in AFFE_CHAR_MECA_F (FACE_IMPO takes DX, DY, DZ here; AFFE_CHAR_MECA takes a constant DNOR on faces along an axis)"),
                        ));
                    }
                }
            }
            let mut given: Vec<(Dof, &str, Coef)> = Vec::new();
            for &c in cmps {
                let Some(name) = occ.concept(c) else { continue };
                let dof = match target {
                    FunctionTarget::Imposed => Dof::from_name(c),
                    FunctionTarget::Force => Dof::from_name(&format!("D{}", &c[1..])),
                };
                let Some(dof) = dof.filter(|d| model.has_dof(*d)) else {
                    return Err(occ.error(
                        c,
                        format!(
                            "{c} is not a component of the model {model_name}, whose nodes carry {dof_names}"
                        ),
                    ));
                };
                given.push((dof, name, coef_of(study, occ, c, name)?));
            }
            let tout: &[usize] = match target {
                FunctionTarget::Imposed => &model_nodes,
                FunctionTarget::Force => &[],
            };
            let nodes = select_nodes(mesh, occ, tout)?;
            if let Some(&n0) = nodes.iter().find(|&&n| !in_model[n]) {
                return Err(occ.error(
                    "",
                    format!(
                        "node N{} of {} belongs to no cell of the model {model_name}: it carries no degree of freedom",
                        n0 + 1,
                        selection_label(occ)
                    ),
                ));
            }
            if nodes.is_empty() {
                lines.push(format!(
                    "<A> <{}> occurrence {} of {key} selects no node",
                    occ.command,
                    k + 1
                ));
            }
            lines.push(format!(
                "      {key} {}: {} nodes of {}, {}",
                k + 1,
                nodes.len(),
                selection_label(occ),
                given
                    .iter()
                    .map(|(d, n, _)| match target {
                        FunctionTarget::Imposed => format!("{}={n}", d.name()),
                        FunctionTarget::Force => format!("F{}={n}", &d.name()[1..]),
                    })
                    .collect::<Vec<_>>()
                    .join(" ")
            ));
            for (dof, name, coef) in given {
                take_nodes(&mut functions, target, dof, &nodes);
                functions.push(NodalFunction {
                    target,
                    dof,
                    name: name.to_string(),
                    coef,
                    nodes: nodes.clone(),
                });
            }
        }
    }
    functions.retain(|f| !f.nodes.is_empty());
    let imposed: Vec<ImposedDof> = functions
        .iter()
        .filter(|f| f.target == FunctionTarget::Imposed)
        .flat_map(|f| {
            f.nodes.iter().map(|&node| ImposedDof {
                node,
                dof: f.dof,
                value: 0.0,
            })
        })
        .collect();
    let fields = fields_of(study, args, mesh, &model, &model_name, &mut lines)?;
    study.log(format!(
        "    load {} on model {model_name}: {} imposed dofs, functions of INST, X, Y, Z",
        result.unwrap_or("(unnamed)"),
        imposed.len()
    ));
    for l in lines {
        study.log(l);
    }
    Ok(Some(ConceptData::MechLoad(Box::new(MechLoad {
        model: model_name,
        imposed,
        gravity: None,
        nodal_forces: Vec::new(),
        pressures: Vec::new(),
        distributed: Vec::new(),
        functions,
        fields,
    }))))
}

/// PRES_REP, FORCE_FACE, FORCE_ARETE, FORCE_CONTOUR, FORCE_INTERNE: the
/// cells of each occurrence as AFFE_CHAR_MECA selects them (the same
/// rules and messages), the values functions of INST, X, Y, Z. A cell
/// given again by a later occurrence of the same keyword keeps the later
/// functions.
fn fields_of(
    study: &Study,
    args: &Args,
    mesh: &crate::mesh::Mesh,
    model: &crate::model::Model,
    model_name: &str,
    lines: &mut Vec<String>,
) -> Result<Vec<FieldFunction>, Diagnostic> {
    let mut out: Vec<FieldFunction> = Vec::new();
    let mut push = |out: &mut Vec<FieldFunction>, f: FieldFunction, k: usize, occ: &Args| {
        let key = f.keyword();
        for earlier in out.iter_mut().filter(|e| e.keyword() == key) {
            earlier.cells.retain(|c| !f.cells.contains(c));
        }
        lines.push(format!(
            "      {key} {}: {} on {} cells of {}",
            k + 1,
            f.names,
            f.cells.len(),
            selection_label(occ)
        ));
        out.push(f);
    };
    for (k, occ) in args.facts("PRES_REP").iter().enumerate() {
        if occ.has("CISA_2D") {
            return Err(occ.not_implemented("CISA_2D", "only a normal pressure PRES"));
        }
        let Some(name) = occ.concept("PRES") else {
            return Err(occ.error("PRES", "PRES is needed (CISA_2D is not implemented)"));
        };
        let coef = coef_of(study, occ, "PRES", name)?;
        let cells = pressure_cells(args, occ, k, mesh, model, model_name)?;
        let f = FieldFunction {
            density: FieldDensity::Pressure(coef),
            names: format!("PRES = {name}"),
            cells,
        };
        push(&mut out, f, k, occ);
    }
    for kind in DISTRIBUTED_KINDS {
        for (k, occ) in args.facts(kind.keyword()).iter().enumerate() {
            let mut coefs: [Option<Coef>; 3] = [None, None, None];
            let mut names = Vec::new();
            for (i, c) in force_components(occ, kind, model, model_name)? {
                let Some(name) = occ.concept(c) else { continue };
                coefs[i] = Some(coef_of(study, occ, c, name)?);
                names.push(format!("{c} = {name}"));
            }
            let cells = distributed_cells(occ, kind, mesh, model, model_name)?;
            let f = FieldFunction {
                density: FieldDensity::Force(kind, Box::new(coefs)),
                names: names.join(" "),
                cells,
            };
            push(&mut out, f, k, occ);
        }
    }
    out.retain(|f| !f.cells.is_empty());
    Ok(out)
}
