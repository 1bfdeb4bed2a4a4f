//! POST_ELEM: global quantities of the model or of parts of it, as a
//! table: MASS_INER (mass, centre of gravity, inertia), ENER_CIN (kinetic
//! energy of VITE), ENER_ELAS (elastic strain energy of the stress),
//! ENER_POT and INTEGRALE (integral and mean of ELGA field components).
//!
//! Why: users check the mass of their model, and follow energies over a
//! dynamic study, with POST_ELEM and TEST_TABLE. The columns and rows are
//! code_aster's (`pemain`, `peecin`): LIEU is the mesh name with ENTITE
//! 'TOUT', the group name with ENTITE 'GROUP_MA' (MASS_INER adds a row
//! UNION_GROUP_MA for several groups), the cell name with 'MAILLE'.
//!
//! The integrals use the points and measures of the elements
//! (`element::mechanics::point_measures`: the mass family for MASS_INER,
//! the SIEF_ELGA points for ENER_ELAS) and the element mass matrix for
//! ENER_CIN, so that the numbers are those of the dynamics. AXIS: MASSE
//! and the inertias are those of the full body of revolution (2π, code_aster's
//! `te0285`), ENER_CIN and ENER_ELAS are per radian like the mass matrix
//! and the forces (`te0082`); docs/post.md.

use super::blocks::*;
use super::calc_champ::{elastic_constants, enel_of_step, ElasticUse};
use super::model_args::select_cells;
use super::post_args::{cell_name, concept_title, select_steps, table_error};
use super::{CommandDef, ExecResult};
use crate::catalog::args::Args;
use crate::catalog::schema::*;
use crate::concepts::{ConceptData, ConceptType as C};
use crate::diag::Diagnostic;
use crate::mesh::Mesh;
use crate::model::spec::Formulation;
use crate::model::{CellRole, MaterialField, Model};
use crate::post::post_elem::{mass_properties, mass_properties_axis, percent};
use crate::post::table::{Cell, ColumnType, Table};
use crate::result::energy::CellEnergy;
use crate::result::EvolNoli;
use crate::study::Study;

/// The options of code_aster's catalogue this command declares; the
/// first four and INTEGRALE run.
const OPTIONS: &[&str] = &[
    "MASS_INER",
    "ENER_CIN",
    "ENER_ELAS",
    "ENER_POT",
    "ENER_TOTALE",
    "ENER_DISS",
    "TRAV_EXT",
    "INTEGRALE",
    "MINMAX",
];

pub fn def() -> CommandDef {
    let part = |extra: Vec<Keyword>| {
        let mut k = vec![tout(), group_ma(), maille()];
        k.extend(extra);
        k
    };
    let sel = || un_parmi(&["TOUT", "GROUP_MA", "MAILLE"]);
    let plain = |name: &'static str, doc: &'static str| {
        fact(name, part(vec![]))
            .rules(vec![sel()])
            .many()
            .doc(doc)
            .kw()
    };
    let mut keywords = vec![
        fact(
            "MASS_INER",
            part(vec![real("ORIG_INER")
                .count(3, 3)
                .doc("point P of the inertia IX_P.. (columns X_P..IYZ_P)")
                .kw()]),
        )
        .rules(vec![sel()])
        .many()
        .doc("mass MASSE, centre of gravity CDG_X/Y/Z and inertia IX_G..IYZ_G about it")
        .kw(),
        fact(
            "ENER_CIN",
            part(vec![text("OPTION")
                .into(&["MASS_MECA", "MASS_MECA_DIAG"])
                .default(t("MASS_MECA"))
                .doc("consistent or lumped (HRZ) mass; the first occurrence's is used, as code_aster")
                .kw()]),
        )
        .rules(vec![sel()])
        .many()
        .doc("kinetic energy ½ Vᵀ M V of VITE: TOTALE and POUR_CENT of the whole")
        .kw(),
        plain(
            "ENER_ELAS",
            "elastic strain energy: the ENEL_ELGA density integrated (TOTALE)",
        ),
        plain(
            "ENER_POT",
            "potential energy ½ ε(u):C:ε(u) of DEPL in the elastic stiffness: TOTALE and POUR_CENT",
        ),
        plain("ENER_TOTALE", "not implemented"),
        plain("ENER_DISS", "not implemented"),
        fact("TRAV_EXT", vec![]).doc("not implemented").kw(),
        fact(
            "INTEGRALE",
            part(vec![
                text("NOM_CHAM")
                    .doc("the field of RESULTAT: an ELGA field (SIEF_ELGA, VARI_ELGA, EPSI_ELGA...)")
                    .kw(),
                text("NOM_CMP").many().doc("its components: one INTE_ and one MOYE_ column each").kw(),
                text("TYPE_MAILLE")
                    .into(&["1D", "2D", "3D"])
                    .doc("only the cells of this topological dimension")
                    .kw(),
                text("DEJA_INTEGRE")
                    .into(&["OUI", "NON"])
                    .doc("for ELEM fields, which are not built")
                    .kw(),
            ]),
        )
        .rules(vec![sel()])
        .many()
        .doc("integral ∫ f dV (INTE_<cmp>), mean (MOYE_<cmp>) and measure VOL of an ELGA field at its points (peeint/peecal)")
        .kw(),
        fact(
            "MINMAX",
            part(vec![text("NOM_CHAM").kw(), text("NOM_CMP").many().kw()]),
        )
        .many()
        .doc("not implemented")
        .kw(),
        concept("MODELE", &[C::Modele])
            .doc("the model (default: the result's)")
            .kw(),
        concept("CHAM_MATER", &[C::ChamMater])
            .doc("the material field (default: the result's)")
            .kw(),
        concept("CHARGE", &[C::CharMeca, C::CharCineMeca])
            .many()
            .doc("read by code_aster for a few options; unused here")
            .kw(),
        concept("RESULTAT", RESULTS)
            .doc("the result, evol_noli or evol_elas (the energies need it)")
            .kw(),
        concept("CHAM_GD", &[C::ChamNo])
            .doc("a field instead of a result: not implemented")
            .kw(),
        text("GEOMETRIE")
            .into(&["INITIALE", "DEFORMEE"])
            .default(t("INITIALE"))
            .doc("MASS_INER on the initial geometry (DEFORMEE is not implemented)")
            .kw(),
        text("TOUT_ORDRE").into(&["OUI"]).kw(),
        int("NUME_ORDRE").many().kw(),
        concept("LIST_ORDRE", &[C::Listis]).doc("stored indices of a DEFI_LIST_ENTI list").kw(),
        real("INST").many().kw(),
        concept("LIST_INST", &[C::Listr8]).kw(),
    ];
    keywords.extend(critere_precision(1e-6));
    keywords.push(titre());
    let spec = command("POST_ELEM", Produces::Concept(C::Table), keywords)
        .rules(vec![
            un_parmi(OPTIONS),
            exclus(&["TOUT_ORDRE", "NUME_ORDRE", "LIST_ORDRE", "INST", "LIST_INST"]),
            exclus(&["CHAM_GD", "RESULTAT"]),
        ])
        .doc("Global quantities as a table: MASS_INER (mass, centre of gravity, inertia), ENER_CIN (kinetic energy), ENER_POT (potential energy of DEPL), ENER_ELAS (elastic strain energy of the stress), INTEGRALE (integral and mean of ELGA field components).");
    CommandDef { spec, exec }
}

/// What the options work on: the model, its mesh and material field,
/// and the result when one is given.
struct Context<'s> {
    mesh_name: String,
    mesh: &'s Mesh,
    model: &'s Model,
    matfield: &'s MaterialField,
    result: Option<(&'s str, &'s EvolNoli)>,
}

fn exec(study: &mut Study, args: &Args, result: Option<&str>) -> ExecResult {
    let option = OPTIONS
        .iter()
        .copied()
        .find(|o| args.has(o))
        .unwrap_or("MASS_INER");
    if !matches!(
        option,
        "MASS_INER" | "ENER_CIN" | "ENER_ELAS" | "ENER_POT" | "INTEGRALE"
    ) {
        return Err(args.not_implemented(option, ""));
    }
    if args.has("CHAM_GD") {
        return Err(args.not_implemented("CHAM_GD", "give RESULTAT"));
    }
    if args.text("GEOMETRIE") == Some("DEFORMEE") {
        return Err(args.not_implemented("GEOMETRIE", "GEOMETRIE='DEFORMEE'"));
    }
    let ctx = context(study, args, option)?;
    let mut table = match option {
        "MASS_INER" => mass_iner(study, args, &ctx)?,
        "ENER_CIN" => ener_cin(study, args, &ctx)?,
        "ENER_POT" => ener_pot(study, args, &ctx)?,
        "INTEGRALE" => integrale(study, args, &ctx)?,
        _ => ener_elas(study, args, &ctx)?,
    };
    table.title = if args.has("TITRE") {
        args.texts("TITRE").iter().map(|s| s.to_string()).collect()
    } else {
        concept_title(result.unwrap_or(""), "table_sdaster")
    };
    Ok(Some(ConceptData::Table(Box::new(table))))
}

fn context<'s>(study: &'s Study, args: &Args, option: &str) -> Result<Context<'s>, Diagnostic> {
    let evol = match args.concept("RESULTAT") {
        Some(_) => Some(super::post_args::result_of(study, args, "RESULTAT")?),
        None if option != "MASS_INER" => {
            return Err(args.error(
                option,
                format!("{option} needs RESULTAT (the fields it integrates)"),
            ))
        }
        None => None,
    };
    let pick = |key: &str, from_result: Option<&'s str>| -> Result<&'s str, Diagnostic> {
        match (args.concept(key), from_result.filter(|s| !s.is_empty())) {
            (Some(n), _) => Ok(study
                .concepts
                .get(n)
                .map(|c| c.name.as_str())
                .unwrap_or_default()),
            (None, Some(n)) => Ok(n),
            (None, None) => Err(args.error(key, format!("{key} is needed: no result names one"))),
        }
    };
    let model_name = pick("MODELE", evol.map(|(_, r)| r.model.as_str()))?;
    let model = match study.concepts.data(model_name) {
        Some(ConceptData::Model(m)) => m,
        _ => return Err(args.error("MODELE", format!("the model {model_name} holds no data"))),
    };
    let mat_name = pick("CHAM_MATER", evol.map(|(_, r)| r.cham_mater.as_str()))?;
    let matfield = match study.concepts.data(mat_name) {
        Some(ConceptData::MaterialField(m)) => m,
        _ => {
            return Err(args.error(
                "CHAM_MATER",
                format!("the material field {mat_name} holds no data"),
            ))
        }
    };
    let key = if args.has("MODELE") {
        "MODELE"
    } else {
        "RESULTAT"
    };
    let mesh = super::model_args::mesh_of_model(study, args, key, model)?;
    Ok(Context {
        mesh_name: model.mesh.clone(),
        mesh,
        model,
        matfield,
        result: evol,
    })
}

/// One row's part of the model: (LIEU, ENTITE, cells).
type Part = (String, &'static str, Vec<usize>);

/// The parts of one occurrence, as code_aster writes them: (LIEU, ENTITE,
/// cells). TOUT: the mesh; GROUP_MA: one per group (and, for MASS_INER,
/// their union when there are several); MAILLE: one per cell.
fn parts(ctx: &Context, occ: &Args, union: bool) -> Result<Vec<Part>, Diagnostic> {
    let mut out = Vec::new();
    if occ.has("TOUT") {
        out.push((ctx.mesh_name.clone(), "TOUT", select_cells(ctx.mesh, occ)?));
    }
    if occ.has("GROUP_MA") {
        select_cells(ctx.mesh, occ)?; // checks the groups exist
        let groups = occ.texts("GROUP_MA");
        for g in &groups {
            out.push((g.to_string(), "GROUP_MA", ctx.mesh.cell_groups[*g].clone()));
        }
        if union && groups.len() > 1 {
            let mut all: Vec<usize> = groups
                .iter()
                .flat_map(|g| ctx.mesh.cell_groups[*g].iter().copied())
                .collect();
            all.sort_unstable();
            all.dedup();
            out.push(("UNION_GROUP_MA".into(), "GROUP_MA", all));
        }
    }
    if occ.has("MAILLE") {
        for name in occ.texts("MAILLE") {
            let c = super::post_args::cell_by_name(ctx.mesh, occ, "MAILLE", name)?;
            out.push((cell_name(c), "MAILLE", vec![c]));
        }
    }
    // A part of skin cells only counts 0 (code_aster's boundary elements
    // have no mass nor energy); a part outside the model is an error.
    for (lieu, _, cells) in &out {
        if !cells
            .iter()
            .any(|&c| !matches!(ctx.model.cells.get(c), None | Some(CellRole::None)))
        {
            let key = ["GROUP_MA", "MAILLE", "TOUT"]
                .into_iter()
                .find(|k| occ.has(k))
                .unwrap_or("TOUT");
            return Err(occ.error(key, format!("{lieu} holds no cell of the model")));
        }
    }
    Ok(out)
}

fn new_table(args: &Args, leading: &[(&str, ColumnType)]) -> Result<Table, Diagnostic> {
    let mut t = Table::new();
    for (n, ty) in leading {
        t.add_column(n, *ty).map_err(|e| table_error(args, "", e))?;
    }
    Ok(t)
}

fn cell_coords(mesh: &Mesh, c: usize) -> Vec<[f64; 3]> {
    mesh.cells[c]
        .nodes
        .iter()
        .map(|&n| mesh.coords[n])
        .collect()
}

/// ELAS/RHO of the material of cell `c`.
fn density(
    study: &Study,
    ctx: &Context,
    occ: &Args,
    key: &str,
    c: usize,
) -> Result<f64, Diagnostic> {
    let name = ctx
        .matfield
        .cell_material
        .get(c)
        .cloned()
        .flatten()
        .ok_or_else(|| occ.error(key, format!("cell {} has no material", cell_name(c))))?;
    let rho = match study.concepts.data(&name) {
        Some(ConceptData::Material(m)) => m.get("ELAS", "RHO"),
        _ => return Err(occ.error(key, format!("the material {name} holds no data"))),
    };
    match rho {
        Some(r) if r.is_finite() && r > 0.0 => Ok(r),
        other => Err(occ.error(
            key,
            format!(
                "the material {name} of cell {} needs ELAS/RHO > 0 for the mass{}",
                cell_name(c),
                other.map(|r| format!(" (RHO = {r:e})")).unwrap_or_default()
            ),
        )),
    }
}

fn mass_iner(study: &Study, args: &Args, ctx: &Context) -> Result<Table, Diagnostic> {
    let occs = args.facts("MASS_INER");
    let with_p = occs.iter().any(|o| o.has("ORIG_INER"));
    let mut leading = vec![
        ("LIEU", ColumnType::Text(24)),
        ("ENTITE", ColumnType::Text(8)),
    ];
    let names = [
        "MASSE", "CDG_X", "CDG_Y", "CDG_Z", "IX_G", "IY_G", "IZ_G", "IXY_G", "IXZ_G", "IYZ_G",
    ];
    let p_names = [
        "X_P", "Y_P", "Z_P", "IX_P", "IY_P", "IZ_P", "IXY_P", "IXZ_P", "IYZ_P",
    ];
    leading.extend(names.iter().map(|n| (*n, ColumnType::Real)));
    if with_p {
        leading.extend(p_names.iter().map(|n| (*n, ColumnType::Real)));
    }
    let mut table = new_table(args, &leading)?;
    let axis = ctx.model.formulation() == Some(Formulation::Axis);
    for occ in occs {
        for (lieu, entite, cells) in parts(ctx, occ, true)? {
            let mut points = Vec::new();
            for &c in &cells {
                let Some(CellRole::Element(spec)) = ctx.model.cells.get(c) else {
                    continue;
                };
                let rho = density(study, ctx, occ, "", c)?;
                let pts = crate::element::mechanics::point_measures(
                    spec,
                    &cell_coords(ctx.mesh, c),
                    spec.mass,
                )
                .map_err(|m| occ.error("", format!("cell {}: {m}", cell_name(c))))?;
                points.extend(pts.into_iter().map(|(x, dv)| (x, rho * dv)));
            }
            let p = if axis {
                mass_properties_axis(&points)
            } else {
                mass_properties(&points)
            };
            let mut row: Vec<Option<Cell>> =
                vec![Some(Cell::Text(lieu)), Some(Cell::Text(entite.into()))];
            row.extend(p.columns().iter().map(|(_, v)| Some(Cell::Real(*v))));
            if with_p {
                let o = occ.reals("ORIG_INER");
                if o.len() == 3 {
                    let [gx, gy, gz] = [p.cdg[0] - o[0], p.cdg[1] - o[1], p.cdg[2] - o[2]];
                    let m = p.mass;
                    row.extend(
                        [
                            o[0],
                            o[1],
                            o[2],
                            p.ix + m * (gy * gy + gz * gz),
                            p.iy + m * (gx * gx + gz * gz),
                            p.iz + m * (gx * gx + gy * gy),
                            p.ixy + m * gx * gy,
                            p.ixz + m * gx * gz,
                            p.iyz + m * gy * gz,
                        ]
                        .map(|v| Some(Cell::Real(v))),
                    );
                } else {
                    row.extend(std::iter::repeat_n(None, p_names.len()));
                }
            }
            table
                .push_row(row)
                .map_err(|e| table_error(args, "MASS_INER", e))?;
        }
    }
    Ok(table)
}

/// The leading columns of the energies of a result (`peecin`).
fn energy_table(args: &Args, with_percent: bool) -> Result<Table, Diagnostic> {
    let mut leading = vec![
        ("NUME_ORDRE", ColumnType::Int),
        ("INST", ColumnType::Real),
        ("LIEU", ColumnType::Text(24)),
        ("ENTITE", ColumnType::Text(8)),
        ("TOTALE", ColumnType::Real),
    ];
    if with_percent {
        leading.push(("POUR_CENT", ColumnType::Real));
    }
    new_table(args, &leading)
}

/// Adds the rows of every occurrence of `key` for one step, from the
/// energy of each cell (`per_cell`, 0 outside the elements).
fn energy_rows(
    table: &mut Table,
    args: &Args,
    ctx: &Context,
    key: &str,
    step: &crate::result::Step,
    per_cell: &[f64],
    with_percent: bool,
) -> Result<(), Diagnostic> {
    let total: f64 = per_cell.iter().sum();
    for occ in args.facts(key) {
        for (lieu, entite, cells) in parts(ctx, occ, false)? {
            let part: f64 = cells.iter().map(|&c| per_cell[c]).sum();
            let mut row = vec![
                Some(Cell::Int(step.nume_ordre as i64)),
                Some(Cell::Real(step.inst)),
                Some(Cell::Text(lieu)),
                Some(Cell::Text(entite.into())),
                Some(Cell::Real(part)),
            ];
            if with_percent {
                let pc = if entite == "TOUT" {
                    100.0
                } else {
                    percent(part, total)
                };
                row.push(Some(Cell::Real(pc)));
            }
            table.push_row(row).map_err(|e| table_error(args, key, e))?;
        }
    }
    Ok(())
}

/// ½ V_eᵀ M_e V_e of each element, with the consistent mass of its MASS
/// family or its HRZ lumped mass (MASS_MECA_DIAG: the explicit schemes'
/// lumped mass, `time::explicit::hrz_lumped`); POUR_CENT of the whole
/// model's energy (`peecin`, `peenca`).
fn ener_cin(study: &Study, args: &Args, ctx: &Context) -> Result<Table, Diagnostic> {
    let (name, evol) = ctx.result.expect("ENER_CIN has a result");
    let first = args.fact("ENER_CIN").expect("ENER_CIN is given");
    let lumped = first.text("OPTION") == Some("MASS_MECA_DIAG");
    let mut table = energy_table(args, true)?;
    let dofs: Vec<&str> = ctx.model.dofs.iter().map(|d| d.name()).collect();
    // element masses, once: they do not change with the step
    let mut masses: Vec<Option<nalgebra::DMatrix<f64>>> = vec![None; ctx.mesh.ncells()];
    let mut lumps: Vec<Option<Vec<f64>>> = vec![None; ctx.mesh.ncells()];
    for (c, spec) in ctx.model.element_cells() {
        let rho = density(study, ctx, first, "", c)?;
        let m = crate::element::mechanics::mass(spec, &cell_coords(ctx.mesh, c), rho)
            .map_err(|e| first.error("", format!("cell {}: {e}", cell_name(c))))?;
        if lumped {
            let d = spec.formulation.dofs_per_node();
            lumps[c] = Some(crate::time::explicit::hrz_lumped(&m, d).ok_or_else(|| {
                first.error(
                    "OPTION",
                    format!(
                        "cell {}: no lumped mass (a degenerate element)",
                        cell_name(c)
                    ),
                )
            })?);
        } else {
            masses[c] = Some(m);
        }
    }
    for step in select_steps(study, evol, args)? {
        let vite = step.nodal.get("VITE").ok_or_else(|| {
            args.error(
                "RESULTAT",
                format!(
                    "NUME_ORDRE {} of {name} has no VITE field{}",
                    step.nume_ordre,
                    if step.excluded.iter().any(|f| f == "VITE") {
                        step.exclusion_note("VITE")
                    } else {
                        " (a quasi-static result has no kinetic energy)".to_string()
                    }
                ),
            )
        })?;
        let mut per_cell = vec![0.0; ctx.mesh.ncells()];
        for (c, spec) in ctx.model.element_cells() {
            let mut v = Vec::with_capacity(spec.ndofs());
            for &n in &ctx.mesh.cells[c].nodes {
                for d in &dofs {
                    v.push(vite.get(n, d).unwrap_or(0.0));
                }
            }
            per_cell[c] = match (&masses[c], &lumps[c]) {
                (Some(m), _) => {
                    let v = nalgebra::DVector::from_vec(v);
                    0.5 * v.dot(&(m * &v))
                }
                (None, Some(l)) => 0.5 * l.iter().zip(&v).map(|(m, v)| m * v * v).sum::<f64>(),
                _ => 0.0,
            };
        }
        energy_rows(&mut table, args, ctx, "ENER_CIN", step, &per_cell, true)?;
    }
    Ok(table)
}

/// ∫ W dV of each element: W the elastic energy density of CALC_CHAMP's
/// ENEL_ELGA (`result::energy`: ½ σ:S:σ under PETIT and PETIT_REAC, the
/// stored energy per unit initial volume under SIMO_MIEHE), at the
/// SIEF_ELGA points, with their measure on the initial geometry.
fn ener_elas(study: &Study, args: &Args, ctx: &Context) -> Result<Table, Diagnostic> {
    let (name, evol) = ctx.result.expect("ENER_ELAS has a result");
    let mut table = energy_table(args, false)?;
    let mut mask = vec![false; ctx.mesh.ncells()];
    for occ in args.facts("ENER_ELAS") {
        for (_, _, cells) in parts(ctx, occ, false)? {
            for c in cells {
                mask[c] = true;
            }
        }
    }
    let elastic = elastic_constants(
        study,
        args,
        "ENER_ELAS",
        ElasticUse::StoredEnergy,
        evol,
        ctx.mesh,
        ctx.model,
        &mask,
    )?;
    let measures = point_weights(args, ctx.mesh, ctx.model, "ENER_ELAS", &mask)?;
    for step in select_steps(study, evol, args)? {
        let w = enel_of_step(
            args,
            "ENER_ELAS",
            name,
            step,
            ctx.mesh,
            ctx.model,
            &mask,
            &elastic,
        )?;
        let per_cell = integrate(args, "ENER_ELAS", step, &w, &measures)?;
        energy_rows(&mut table, args, ctx, "ENER_ELAS", step, &per_cell, false)?;
    }
    Ok(table)
}

/// The elastic strain energy of the whole model (ENER_ELAS over every
/// element) at each step of the result `name`, as (NUME_ORDRE, energy):
/// the split of DYNA_NON_LINE's energy balance (PARA_CALC) takes it from
/// here, so that both give the same number. Errors name `key`.
pub(super) fn total_elastic_energy(
    study: &Study,
    args: &Args,
    key: &'static str,
    name: &str,
    evol: &EvolNoli,
    mesh: &Mesh,
    model: &Model,
) -> Result<Vec<(usize, f64)>, Diagnostic> {
    let mask: Vec<bool> = (0..mesh.ncells())
        .map(|c| matches!(model.cells.get(c), Some(CellRole::Element(_))))
        .collect();
    let elastic = elastic_constants(
        study,
        args,
        key,
        ElasticUse::StoredEnergy,
        evol,
        mesh,
        model,
        &mask,
    )?;
    let measures = point_weights(args, mesh, model, key, &mask)?;
    evol.steps
        .iter()
        .map(|step| {
            let w = enel_of_step(args, key, name, step, mesh, model, &mask, &elastic)?;
            let per_cell = integrate(args, key, step, &w, &measures)?;
            Ok((step.nume_ordre, per_cell.iter().sum()))
        })
        .collect()
}

/// The measures dV of the SIEF_ELGA points of the cells of `mask`
/// (empty for the others), on the initial geometry.
fn point_weights(
    args: &Args,
    mesh: &Mesh,
    model: &Model,
    key: &str,
    mask: &[bool],
) -> Result<Vec<Vec<f64>>, Diagnostic> {
    let mut measures: Vec<Vec<f64>> = vec![Vec::new(); mesh.ncells()];
    for (c, spec) in model.element_cells() {
        if mask[c] {
            measures[c] =
                crate::element::mechanics::point_measures(spec, &cell_coords(mesh, c), spec.rigi)
                    .map_err(|m| args.error(key, format!("cell {}: {m}", cell_name(c))))?
                    .into_iter()
                    .map(|(_, dv)| dv)
                    .collect();
        }
    }
    Ok(measures)
}

/// Σ W dV of each cell, from a one-component density at the SIEF_ELGA
/// points and their measures.
fn integrate(
    args: &Args,
    key: &str,
    step: &crate::result::Step,
    w: &crate::result::GaussField,
    measures: &[Vec<f64>],
) -> Result<Vec<f64>, Diagnostic> {
    let mut per_cell = vec![0.0; measures.len()];
    for (c, dv) in measures.iter().enumerate() {
        if dv.is_empty() {
            continue;
        }
        let vals = w.cell(c);
        if vals.len() != dv.len() {
            return Err(args.error(
                key,
                format!(
                    "NUME_ORDRE {}: cell {} has {} energy values for {} points",
                    step.nume_ordre,
                    cell_name(c),
                    vals.len(),
                    dv.len()
                ),
            ));
        }
        per_cell[c] = vals.iter().zip(dv).map(|(w, v)| w * v).sum();
    }
    Ok(per_cell)
}

/// ½ ε(u):C:ε(u) of each element (code_aster's EPOT_ELEM: the linearised
/// strain of DEPL on the initial geometry in the elastic stiffness of
/// ELAS, whatever the law and the kinematics of the computation), at the
/// SIEF_ELGA points; POUR_CENT of the whole model's (`peepot`).
fn ener_pot(study: &Study, args: &Args, ctx: &Context) -> Result<Table, Diagnostic> {
    let (name, evol) = ctx.result.expect("ENER_POT has a result");
    let mut table = energy_table(args, true)?;
    let mask: Vec<bool> = ctx
        .model
        .cells
        .iter()
        .map(|r| matches!(r, CellRole::Element(_)))
        .collect();
    let elastic = elastic_constants(
        study,
        args,
        "ENER_POT",
        ElasticUse::StrainOfDepl,
        evol,
        ctx.mesh,
        ctx.model,
        &mask,
    )?;
    let measures = point_weights(args, ctx.mesh, ctx.model, "ENER_POT", &mask)?;
    let plane_nu: Vec<Option<f64>> = elastic
        .iter()
        .map(|c| match c {
            Some(CellEnergy::Small { nu, .. } | CellEnergy::SimoMiehe { nu, .. }) => Some(*nu),
            None => None,
        })
        .collect();
    for step in select_steps(study, evol, args)? {
        let nume = step.nume_ordre;
        let depl = step.nodal.get("DEPL").ok_or_else(|| {
            args.error(
                "ENER_POT",
                format!(
                    "NUME_ORDRE {nume} of {name} has no DEPL field{}",
                    step.exclusion_note("DEPL")
                ),
            )
        })?;
        let mut eps = crate::element::strain::strain_field(
            crate::element::strain::Measure::Linear,
            ctx.mesh,
            ctx.model,
            depl,
            &mask,
        )
        .map_err(|m| args.error("ENER_POT", format!("NUME_ORDRE {nume}: {m}")))?;
        // C_PLAN: the ε_zz of σ_zz = 0 (epsvmc), without which ½ ε:C:ε
        // would be the plane-strain energy (hplv101a: 0.673 for 0.549).
        crate::element::strain::plane_stress_zz(&mut eps, ctx.model, &plane_nu)
            .map_err(|m| args.error("ENER_POT", format!("NUME_ORDRE {nume}: {m}")))?;
        let nc = eps.ncmp();
        let mut w = crate::result::GaussField {
            components: vec!["TOTALE".into()],
            offsets: Vec::with_capacity(eps.offsets.len()),
            values: Vec::new(),
        };
        for c in 0..eps.offsets.len().saturating_sub(1) {
            w.offsets.push(w.values.len());
            let (e, nu) = match elastic.get(c) {
                Some(Some(CellEnergy::Small { e, nu } | CellEnergy::SimoMiehe { e, nu, .. })) => {
                    (*e, *nu)
                }
                _ => continue,
            };
            for row in eps.cell(c).chunks(nc.max(1)) {
                let mut t = [0.0; 6];
                t[..nc].copy_from_slice(row);
                w.values
                    .push(crate::result::energy::strain_energy_density(t, e, nu));
            }
        }
        w.offsets.push(w.values.len());
        let per_cell = integrate(args, "ENER_POT", step, &w, &measures)?;
        energy_rows(&mut table, args, ctx, "ENER_POT", step, &per_cell, true)?;
    }
    Ok(table)
}

/// INTEGRALE (code_aster's `peeint` / `peecal`): for each occurrence,
/// each selected step and each part (TOUT, then each group of GROUP_MA
/// and their UNION_GROUP_MA when there are several, or each cell of
/// MAILLE), the row NOM_CHAM, NUME_ORDRE, INST, VOL, the part's column
/// (TOUT / GROUP_MA / MAILLE) and, per component of NOM_CMP, INTE_<cmp> =
/// Σ f dV over the points of the field and MOYE_<cmp> = INTE / VOL, with
/// VOL = Σ dV over those same points. dV is the measure of the point
/// (weight × Jacobian on the initial geometry; × r under AXIS, so that
/// the integral is per radian as code_aster's COOR_ELGA weight). Only
/// ELGA fields at the SIEF_ELGA points are built: code_aster also
/// integrates nodal fields (turned into ELNO) and ELEM fields, refused
/// here with a message.
fn integrale(study: &Study, args: &Args, ctx: &Context) -> Result<Table, Diagnostic> {
    let (name, evol) = ctx.result.expect("INTEGRALE has a result");
    let mut table = new_table(
        args,
        &[
            ("NOM_CHAM", ColumnType::Text(16)),
            ("NUME_ORDRE", ColumnType::Int),
            ("INST", ColumnType::Real),
            ("VOL", ColumnType::Real),
        ],
    )?;
    let steps = select_steps(study, evol, args)?;
    for occ in args.facts("INTEGRALE") {
        let Some(field) = occ.text("NOM_CHAM") else {
            return Err(occ.error(
                "INTEGRALE",
                "NOM_CHAM is needed with RESULTAT: the field to integrate",
            ));
        };
        let cmps = occ.texts("NOM_CMP");
        if cmps.is_empty() {
            return Err(occ.error(
                "INTEGRALE",
                "NOM_CMP is needed: the components to integrate (NOM_VARI is not built)",
            ));
        }
        if occ.has("DEJA_INTEGRE") {
            return Err(occ.not_implemented(
                "DEJA_INTEGRE",
                "it is for ELEM fields, which are not built; give an ELGA field",
            ));
        }
        let dim = match occ.text("TYPE_MAILLE") {
            Some("1D") => Some(1),
            Some("2D") => Some(2),
            Some("3D") => Some(3),
            _ => None,
        };
        let mut parts = parts(ctx, occ, true)?;
        if let Some(d) = dim {
            for (_, _, cells) in &mut parts {
                cells.retain(|&c| ctx.mesh.cells[c].kind.dim() == d);
            }
            if parts.iter().all(|(_, _, cells)| cells.is_empty()) {
                return Err(occ.error(
                    "TYPE_MAILLE",
                    format!(
                        "no cell of dimension {} in the cells given",
                        occ.text("TYPE_MAILLE").unwrap_or_default()
                    ),
                ));
            }
        }
        let mut mask = vec![false; ctx.mesh.ncells()];
        for (_, _, cells) in &parts {
            for &c in cells {
                mask[c] = true;
            }
        }
        let measures = point_weights(args, ctx.mesh, ctx.model, "INTEGRALE", &mask)?;
        for step in &steps {
            let nume = step.nume_ordre;
            let values = match step.gauss.get(field) {
                Some(g) => g,
                None if step.nodal.contains_key(field) || step.elno.contains_key(field) => {
                    return Err(occ.not_implemented(
                        "NOM_CHAM",
                        &format!(
                            "INTEGRALE of the field {field}, not at Gauss points: only ELGA fields (SIEF_ELGA, VARI_ELGA, EPSI_ELGA... of CALC_CHAMP) are integrated"
                        ),
                    ))
                }
                None => {
                    return Err(occ.error(
                        "NOM_CHAM",
                        format!(
                            "NUME_ORDRE {nume} of {name} has no field {field}{} (fields: {})",
                            step.exclusion_note(field),
                            step.gauss
                                .keys()
                                .chain(step.nodal.keys())
                                .chain(step.elno.keys())
                                .map(|s| s.as_str())
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    ))
                }
            };
            let idx: Vec<usize> = cmps
                .iter()
                .map(|c| {
                    values
                        .components
                        .iter()
                        .position(|k| k == c)
                        .ok_or_else(|| {
                            occ.error(
                                "NOM_CMP",
                                format!(
                                    "{field} has no component {c} (components: {})",
                                    values.components.join(", ")
                                ),
                            )
                        })
                })
                .collect::<Result<_, _>>()?;
            let nc = values.ncmp().max(1);
            for (lieu, entite, cells) in &parts {
                let (mut vol, mut inte) = (0.0, vec![0.0; idx.len()]);
                let mut seen = false;
                for &c in cells {
                    let dv = &measures[c];
                    let vals = values.cell(c);
                    if dv.is_empty() || vals.is_empty() {
                        continue; // no element, or no value of the field there
                    }
                    if vals.len() != dv.len() * nc {
                        return Err(occ.error(
                            "NOM_CHAM",
                            format!(
                                "NUME_ORDRE {nume}: cell {} has {} points of {field} where its SIEF_ELGA family has {}: only fields at those points are integrated",
                                cell_name(c),
                                vals.len() / nc,
                                dv.len()
                            ),
                        ));
                    }
                    seen = true;
                    for (p, w) in dv.iter().enumerate() {
                        vol += w;
                        for (k, &i) in idx.iter().enumerate() {
                            inte[k] += vals[p * nc + i] * w;
                        }
                    }
                }
                if !seen {
                    return Err(occ.error(
                        "NOM_CHAM",
                        format!(
                            "NUME_ORDRE {nume}: {field} has no value on {lieu}: nothing to integrate"
                        ),
                    ));
                }
                let mut row: Vec<(&str, Cell)> = vec![
                    ("NOM_CHAM", Cell::Text(field.to_string())),
                    ("NUME_ORDRE", Cell::Int(nume as i64)),
                    ("INST", Cell::Real(step.inst)),
                    ("VOL", Cell::Real(vol)),
                    // code_aster's row of TOUT reads TOUT in the column TOUT
                    (
                        entite,
                        Cell::Text(if *entite == "TOUT" {
                            "TOUT".into()
                        } else {
                            lieu.clone()
                        }),
                    ),
                ];
                let names: Vec<(String, String)> = cmps
                    .iter()
                    .map(|c| (format!("INTE_{c}"), format!("MOYE_{c}")))
                    .collect();
                for (k, (i, _)) in names.iter().enumerate() {
                    row.push((i, Cell::Real(inte[k])));
                }
                for (k, (_, m)) in names.iter().enumerate() {
                    row.push((m, Cell::Real(inte[k] / vol)));
                }
                table
                    .add_row(&row)
                    .map_err(|e| table_error(args, "INTEGRALE", e))?;
            }
        }
    }
    Ok(table)
}
