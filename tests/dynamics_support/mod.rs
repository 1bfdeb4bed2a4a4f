//! Shared set-up of the dynamics tests: the concepts a DYNA_NON_LINE call
//! consumes are built directly (mesh, model, material, loads, fields, time
//! lists) and inserted in a Study; the DYNA_NON_LINE / CALC_CHAMP keywords
//! come from a real command text, parsed and checked, so the executors see
//! exactly what a .comm file gives them.
#![allow(dead_code)]

use indexmap::IndexMap;

use aster::catalog::args::Args;
use aster::catalog::checker::check_program;
use aster::commands::{all, CommandDef};
use aster::concepts::{Concept, ConceptData, ConceptType};
use aster::diag::{Source, Span};
use aster::mesh::taylor::{generate, TaylorKind, TaylorParams};
use aster::mesh::Mesh;
use aster::model::spec::element_spec;
use aster::model::{CellRole, Dof, ImposedDof, Material, MaterialField, MechLoad, Model};
use aster::result::{EvolNoli, NodalField};
use aster::study::Study;
use aster::time::list::TimeList;

/// Concepts declared (for the checker) before the command under test.
pub const PREAMBLE: &str = "
DEBUT()
MAIL = LIRE_MAILLAGE(FORMAT='MED')
MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='AXIS'))
MAT = DEFI_MATERIAU(ELAS=_F(E=1., NU=0., RHO=1.))
CHMAT = AFFE_MATERIAU(MAILLAGE=MAIL, AFFE=_F(TOUT='OUI', MATER=MAT))
BLOQ = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(TOUT='OUI', DX=0.))
V0 = CREA_CHAMP(TYPE_CHAM='NOEU_DEPL_R', OPERATION='AFFE', MODELE=MO, AFFE=_F(TOUT='OUI', NOM_CMP='DX', VALE=0.))
L_INST = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=1))
L_ARCH = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=1))
LI = DEFI_LIST_INST(DEFI_LIST=_F(LIST_INST=L_INST))
";

fn registry() -> Vec<CommandDef> {
    all()
}

/// The checked arguments of the `nth` command named `name` in
/// PREAMBLE + `text` + FIN().
pub fn args_of(text: &str, name: &str, nth: usize) -> Args {
    let full = format!("{PREAMBLE}\n{text}\nFIN()\n");
    let src = Source::new("test.comm", full);
    let prog =
        aster::lang::parser::parse(&src).unwrap_or_else(|d| panic!("{}", d.render(Some(&src))));
    let reg = registry();
    let checked = check_program(&prog, &reg).unwrap_or_else(|ds| {
        panic!(
            "{}",
            ds.iter()
                .map(|d| d.render(Some(&src)))
                .collect::<Vec<_>>()
                .join("\n")
        )
    });
    checked
        .commands
        .iter()
        .filter(|c| c.name == name)
        .nth(nth)
        .unwrap_or_else(|| panic!("no {name} in the text"))
        .args
        .clone()
}

/// Runs an executor of the registry on `args`.
pub fn exec(study: &mut Study, command: &str, args: &Args, result: &str) -> Result<(), String> {
    let reg = registry();
    let def = reg.iter().find(|d| d.spec.name == command).unwrap();
    match (def.exec)(study, args, Some(result)) {
        Ok(Some(data)) => {
            insert(study, result, ConceptType::EvolNoli, data);
            Ok(())
        }
        Ok(None) => Ok(()),
        Err(d) => Err(d.render(None)),
    }
}

pub fn insert(study: &mut Study, name: &str, ty: ConceptType, data: ConceptData) {
    study.concepts.insert(Concept {
        name: name.into(),
        ty,
        defined_at: Span::new(0, 0),
        command: "TEST".into(),
        data,
    });
}

pub fn result<'a>(study: &'a Study, name: &str) -> &'a EvolNoli {
    match study.concepts.data(name) {
        Some(ConceptData::Result(r)) => r,
        _ => panic!("{name} is not a result"),
    }
}

/// A material with ELAS (and ECRO_LINE if `ecro` is given).
pub fn material(e: f64, nu: f64, rho: f64, ecro: Option<(f64, f64)>) -> Material {
    let mut m = Material::default();
    let mut el = IndexMap::new();
    el.insert("E".to_string(), e);
    el.insert("NU".to_string(), nu);
    el.insert("RHO".to_string(), rho);
    m.blocks.insert("ELAS".into(), el);
    if let Some((sy, et)) = ecro {
        let mut ec = IndexMap::new();
        ec.insert("SY".to_string(), sy);
        ec.insert("D_SIGM_EPSI".to_string(), et);
        m.blocks.insert("ECRO_LINE".into(), ec);
    }
    m
}

/// A model of `modelisation` on the cells of `cells` (others not in it).
pub fn model(mesh: &Mesh, modelisation: &str, cells: &[usize]) -> Model {
    let dofs = if modelisation.starts_with("AXIS") {
        vec![Dof::Dx, Dof::Dy]
    } else {
        vec![Dof::Dx, Dof::Dy, Dof::Dz]
    };
    let mut roles = vec![CellRole::None; mesh.ncells()];
    for &c in cells {
        if let Some(s) = element_spec(modelisation, mesh.cells[c].kind) {
            roles[c] = CellRole::Element(s);
        }
    }
    Model {
        mesh: "MAIL".into(),
        dofs,
        cells: roles,
    }
}

/// Inserts mesh, model, material, material field, load, initial velocity
/// and time lists under the preamble's names.
#[allow(clippy::too_many_arguments)]
pub fn study(
    mesh: Mesh,
    model: Model,
    mat: Material,
    imposed: Vec<ImposedDof>,
    vite: Option<NodalField>,
    instants: Vec<f64>,
    list_inst: Option<TimeList>,
) -> Study {
    let mut s = Study::default();
    let n = mesh.ncells();
    insert(
        &mut s,
        "MAT",
        ConceptType::Mater,
        ConceptData::Material(Box::new(mat)),
    );
    insert(
        &mut s,
        "CHMAT",
        ConceptType::ChamMater,
        ConceptData::MaterialField(Box::new(MaterialField {
            mesh: "MAIL".into(),
            cell_material: vec![Some("MAT".into()); n],
        })),
    );
    insert(
        &mut s,
        "MAIL",
        ConceptType::Maillage,
        ConceptData::Mesh(Box::new(mesh)),
    );
    insert(
        &mut s,
        "MO",
        ConceptType::Modele,
        ConceptData::Model(Box::new(model)),
    );
    insert(
        &mut s,
        "BLOQ",
        ConceptType::CharMeca,
        ConceptData::MechLoad(Box::new(MechLoad {
            model: "MO".into(),
            imposed,
            gravity: None,
            nodal_forces: Vec::new(),
            pressures: Vec::new(),
            distributed: Vec::new(),
            functions: Vec::new(),
            fields: Vec::new(),
        })),
    );
    if let Some(v) = vite {
        insert(
            &mut s,
            "V0",
            ConceptType::ChamNo,
            ConceptData::Field(Box::new(aster::concepts::ChamNo {
                mesh: "MAIL".into(),
                field: v,
            })),
        );
    }
    insert(
        &mut s,
        "L_INST",
        ConceptType::Listr8,
        ConceptData::ListReal(instants),
    );
    if let Some(l) = list_inst {
        insert(
            &mut s,
            "LI",
            ConceptType::ListInst,
            ConceptData::TimeList(Box::new(l)),
        );
    }
    s
}

/// The axisymmetric Taylor mesh generator (bar cells first, then the
/// foundation).
pub fn taylor_axis(n1: usize, n2: usize) -> Mesh {
    generate(&TaylorParams {
        kind: TaylorKind::Axis,
        n1,
        n2,
        n3: 0,
        linear: false,
    })
    .unwrap()
}

/// A velocity field: (vx, vy) on `nodes`, other pairs absent.
pub fn velocity(nnodes: usize, nodes: &[usize], vy: f64) -> NodalField {
    let mut f = NodalField::absent(vec!["DX".into(), "DY".into()], nnodes);
    for &n in nodes {
        f.set(n, 0, 0.0);
        f.set(n, 1, vy);
    }
    f
}

/// Equally spaced instants.
pub fn linspace(t0: f64, t1: f64, n: usize) -> Vec<f64> {
    (0..=n)
        .map(|k| {
            if k == n {
                t1
            } else {
                t0 + (t1 - t0) * k as f64 / n as f64
            }
        })
        .collect()
}

pub fn imposed(nodes: &[usize], dof: Dof, value: f64) -> Vec<ImposedDof> {
    nodes
        .iter()
        .map(|&node| ImposedDof { node, dof, value })
        .collect()
}
