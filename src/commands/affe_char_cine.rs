//! AFFE_CHAR_CINE: imposed displacements as a kinematic load
//! (char_cine_meca), which code_aster eliminates from the system instead
//! of dualising them with Lagrange multipliers as AFFE_CHAR_MECA's
//! DDL_IMPO does. The solution is the same, reactions included
//! (REAC_NODA is the residual at the held dofs either way), and aster
//! holds imposed dofs one way only, so MECA_IMPO gives the data of a
//! DDL_IMPO: the concept type differs, for the checker, not the engine.
//! AFFE_CHAR_CINE_F likewise gives AFFE_CHAR_MECA_F's DDL_IMPO, values
//! functions of INST and of the node's initial X, Y, Z.

use super::affe_char_meca::ddl_impo;
use super::affe_char_meca_f::function_load;
use super::blocks::*;
use super::model_args::load_model;
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::ConceptData;
use crate::concepts::ConceptType as C;
use crate::model::{FunctionTarget, MechLoad};
use crate::study::Study;

pub fn def() -> CommandDef {
    let mut impo = vec![tout(), group_ma(), maille(), group_no(), noeud()];
    for &c in CMP_DEPL {
        impo.push(real(c).doc("imposed value of this component").kw());
    }
    let spec = command(
        "AFFE_CHAR_CINE",
        Produces::Concept(C::CharCineMeca),
        vec![
            concept("MODELE", &[C::Modele]).required().kw(),
            imposed_dofs(
                "MECA_IMPO",
                impo,
                CMP_DEPL,
                "imposed displacements, eliminated from the system; GROUP_MA means all nodes of those cells",
            )
            .kw(),
            concept("EVOL_IMPO", &[C::EvolNoli, C::EvolElas])
                .doc("displacements imposed from a result: not implemented yet")
                .kw(),
            info(),
        ],
    )
    .rules(vec![un_parmi(&["MECA_IMPO", "EVOL_IMPO"])])
    .doc("Defines imposed displacements as a kinematic load (char_cine_meca), taken by EXCIT like a char_meca.");
    CommandDef { spec, exec }
}

fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    if args.has("EVOL_IMPO") {
        return Err(args.not_implemented("EVOL_IMPO", ""));
    }
    let lm = load_model(study, args)?;
    let mut lines = Vec::new();
    let imposed = ddl_impo(args, "MECA_IMPO", &lm, &mut lines)?;
    let model_name = lm.name;
    study.log(format!(
        "    kinematic load {} on model {}: {} imposed dofs (eliminated in code_aster, held the same way as DDL_IMPO here)",
        result.unwrap_or("(unnamed)"),
        model_name,
        imposed.len()
    ));
    for l in lines {
        study.log(l);
    }
    Ok(Some(ConceptData::MechLoad(Box::new(MechLoad {
        model: model_name,
        imposed,
        ..MechLoad::default()
    }))))
}

pub fn def_f() -> CommandDef {
    let mut impo = vec![tout(), group_ma(), maille(), group_no(), noeud()];
    for &c in CMP_DEPL {
        impo.push(
            concept(c, &[C::Fonction, C::Formule])
                .doc("imposed value of this component: a function of INST and the node's initial X, Y, Z")
                .kw(),
        );
    }
    let spec = command(
        "AFFE_CHAR_CINE_F",
        Produces::Concept(C::CharCineMeca),
        vec![
            concept("MODELE", &[C::Modele]).required().kw(),
            imposed_dofs(
                "MECA_IMPO",
                impo,
                CMP_DEPL,
                "imposed displacements, functions of INST and of the node's initial X, Y, Z evaluated at each step's end instant, eliminated from the system; GROUP_MA means all nodes of those cells; a node given again keeps the later function of that component",
            )
            .required()
            .kw(),
            info(),
        ],
    )
    .doc("Defines imposed displacements given as functions (of INST, X, Y, Z) as a kinematic load (char_cine_meca), taken by EXCIT like a char_meca.");
    CommandDef { spec, exec: exec_f }
}

fn exec_f(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    function_load(
        study,
        args,
        result,
        &[("MECA_IMPO", FunctionTarget::Imposed, CMP_DEPL)],
    )
}
