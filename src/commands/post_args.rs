//! What the post-processing commands share: fetching results, fields,
//! tables and functions from the study, naming nodes and cells the way
//! code_aster does, resolving GROUP_NO / NOEUD / GROUP_MA / MAILLE, and
//! selecting stored steps (TOUT_ORDRE, NUME_ORDRE, INST, LIST_INST with
//! CRITERE / PRECISION).
//!
//! Node and cell names: aster meshes carry no names, so entities are
//! named with code_aster's defaults for meshes built without names, `N1`,
//! `N2`... and `M1`, `M2`... (1-based, in mesh order). NOEUD='N12' and
//! MAILLE='M3' are read back the same way.

use crate::catalog::args::Args;
use crate::concepts::ConceptData;
use crate::diag::{closest, Diagnostic};
use crate::mesh::Mesh;
use crate::post::function::{Extrapolation, Function, Interp};
use crate::post::table::{CritComp, Filter, FilterValues, Table, TableError};
use crate::post::test_report::{
    occurrence_checks, CheckLine, Critere, RefKind, Reference, TestSpec, Value as TestValue,
};
use crate::result::{Access, EvolNoli, GaussField, NodalField, Step};
use crate::study::Study;

/// code_aster's default name of node `i` (0-based index): `N<i+1>`.
pub fn node_name(i: usize) -> String {
    format!("N{}", i + 1)
}

/// code_aster's default name of cell `i` (0-based index): `M<i+1>`.
pub fn cell_name(i: usize) -> String {
    format!("M{}", i + 1)
}

/// Reads `N12` (or `M12`) back to its 0-based index, if it names one of
/// `count` entities.
fn parse_name(name: &str, prefix: char, count: usize) -> Option<usize> {
    let digits = name.trim().strip_prefix(prefix)?;
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) || digits.starts_with('0') {
        return None;
    }
    let k: usize = digits.parse().ok()?;
    (1..=count).contains(&k).then(|| k - 1)
}

/// A result name padded with `_` to 8 characters, as code_aster prefixes
/// MED field names (`RESU` -> `RESU____`).
pub fn pad8(name: &str) -> String {
    format!("{name:_<8}")
}

/// Logs an alarm in code_aster's `<A> <COMMAND> <ID> text` shape.
pub fn alarm(study: &mut Study, command: &str, id: &str, text: &str) {
    if id.is_empty() {
        study.log(format!("<A> <{command}> {text}"));
    } else {
        study.log(format!("<A> <{command}> <{id}> {text}"));
    }
}

/// Logs an alarm about aster's own limits (see [`Study::log_limitation`]).
pub fn limitation(study: &mut Study, command: &str, text: &str) {
    study.log_limitation(format!("<A> <{command}> {text}"));
}

fn no_data(args: &Args, key: &str, name: &str, what: &str) -> Diagnostic {
    args.error(
        key,
        format!("{name} holds no {what} (its command did not run or produced something else)"),
    )
}

/// The concept named under `key` with its data viewed as `T` by `view`,
/// and its name: one lookup for every kind of concept the post-processing
/// commands read, so that their messages are the same. `expected` ends the
/// message of a missing concept, `holds` that of a concept of another kind.
fn concept_as<'s, T: ?Sized>(
    study: &'s Study,
    args: &Args,
    key: &str,
    (expected, holds): (&str, &str),
    view: impl Fn(&'s ConceptData) -> Option<&'s T>,
) -> Result<(&'s str, &'s T), Diagnostic> {
    let name = args.concept(key).ok_or_else(|| args.error(key, expected))?;
    study
        .concepts
        .get(name)
        .and_then(|c| view(&c.data).map(|d| (c.name.as_str(), d)))
        .ok_or_else(|| no_data(args, key, name, holds))
}

/// The transient result named under `key`, with its name.
pub fn result_of<'s>(
    study: &'s Study,
    args: &Args,
    key: &str,
) -> Result<(&'s str, &'s EvolNoli), Diagnostic> {
    let what = ("a result concept is expected", "result data");
    concept_as(study, args, key, what, |d| match d {
        ConceptData::Result(r) => Some(&**r),
        _ => None,
    })
}

/// The nodal field (cham_no) named under `key`, with its name.
pub fn cham_no_of<'s>(
    study: &'s Study,
    args: &Args,
    key: &str,
) -> Result<(&'s str, &'s NodalField), Diagnostic> {
    let what = ("a field concept is expected", "nodal field");
    concept_as(study, args, key, what, |d| match d {
        ConceptData::Field(f) => Some(&f.field),
        _ => None,
    })
}

/// The table named under `key`, with its name.
pub fn table_of<'s>(
    study: &'s Study,
    args: &Args,
    key: &str,
) -> Result<(&'s str, &'s Table), Diagnostic> {
    let what = ("a table concept is expected", "table");
    concept_as(study, args, key, what, |d| match d {
        ConceptData::Table(t) => Some(&**t),
        _ => None,
    })
}

/// The function named under `key`, with its name.
pub fn function_of<'s>(
    study: &'s Study,
    args: &Args,
    key: &str,
) -> Result<(&'s str, &'s Function), Diagnostic> {
    let name = args
        .concept(key)
        .ok_or_else(|| args.error(key, "a function concept is expected"))?;
    function_named(study, args, key, name)
}

/// The function `name`, one of the values of `key` (ENVELOPPE's FONCTION
/// list), with its name.
pub fn function_named<'s>(
    study: &'s Study,
    args: &Args,
    key: &str,
    name: &str,
) -> Result<(&'s str, &'s Function), Diagnostic> {
    study
        .concepts
        .get(name)
        .and_then(|c| match &c.data {
            ConceptData::Function(f) => Some((c.name.as_str(), &**f)),
            _ => None,
        })
        .ok_or_else(|| no_data(args, key, name, "function"))
}

/// The mesh concept called `name`.
pub fn mesh_named<'s>(study: &'s Study, name: &str) -> Option<&'s Mesh> {
    match study.concepts.data(name) {
        Some(ConceptData::Mesh(m)) => Some(m),
        _ => None,
    }
}

/// The mesh a result lives on.
pub fn mesh_of_result<'s>(
    study: &'s Study,
    args: &Args,
    key: &str,
    result_name: &str,
    result: &EvolNoli,
) -> Result<&'s Mesh, Diagnostic> {
    mesh_named(study, &result.mesh).ok_or_else(|| {
        args.error(
            key,
            format!(
                "the mesh '{}' of result {result_name} is not available in this study",
                result.mesh
            ),
        )
    })
}

/// The mesh of a nodal field (cham_no).
///
/// A [`NodalField`] does not record its mesh, so it is found among the
/// mesh concepts: those with the field's node count that have every group
/// in `groups`. Several candidates are accepted only when they agree on
/// coordinates and on those groups (the same mesh modified in place, or a
/// copy); otherwise the field is ambiguous and this is an error.
pub fn mesh_for_field<'s>(
    study: &'s Study,
    args: &Args,
    key: &str,
    field_name: &str,
    field: &NodalField,
    groups: &[&str],
) -> Result<&'s Mesh, Diagnostic> {
    let n = field.nnodes();
    let sized: Vec<(&str, &Mesh)> = study
        .concepts
        .iter()
        .filter_map(|c| match &c.data {
            ConceptData::Mesh(m) if m.nnodes() == n => Some((c.name.as_str(), &**m)),
            _ => None,
        })
        .collect();
    if sized.is_empty() {
        return Err(args.error(
            key,
            format!("no mesh of this study has the {n} nodes of field {field_name}"),
        ));
    }
    let fit: Vec<&(&str, &Mesh)> = sized
        .iter()
        .filter(|(_, m)| groups.iter().all(|g| m.node_groups.contains_key(*g)))
        .collect();
    let Some(last) = fit.last() else {
        let names: Vec<&str> = sized.iter().map(|(n, _)| *n).collect();
        return Err(args.error(
            key,
            format!(
                "no mesh with the {n} nodes of field {field_name} ({}) has the node group(s) {}",
                names.join(", "),
                groups.join(", ")
            ),
        ));
    };
    let same = fit.iter().all(|(_, m)| {
        m.coords == last.1.coords
            && groups
                .iter()
                .all(|g| m.node_groups.get(*g) == last.1.node_groups.get(*g))
    });
    if !same {
        let names: Vec<&str> = fit.iter().map(|(n, _)| *n).collect();
        return Err(args.error(
            key,
            format!(
                "field {field_name} could lie on several different meshes ({}): a cham_no \
                 does not record its mesh in aster, so it cannot be told which",
                names.join(", ")
            ),
        ));
    }
    Ok(last.1)
}

/// The nodes designated by GROUP_NO and NOEUD at this level, in the order
/// written (groups in their own order), without duplicates.
pub fn nodes_of(mesh: &Mesh, args: &Args) -> Result<Vec<usize>, Diagnostic> {
    let mut out: Vec<usize> = Vec::new();
    let mut seen = vec![false; mesh.nnodes()];
    let mut push = |i: usize, out: &mut Vec<usize>| {
        if !seen[i] {
            seen[i] = true;
            out.push(i);
        }
    };
    for g in args.texts("GROUP_NO") {
        let Some(nodes) = mesh.node_groups.get(g) else {
            let known: Vec<&str> = mesh.node_groups.keys().map(String::as_str).collect();
            let mut d = args.error("GROUP_NO", format!("the mesh has no node group '{g}'"));
            d.suggestion = closest(g, &known);
            d.choices = known.iter().map(|s| s.to_string()).collect();
            return Err(d);
        };
        for &i in nodes {
            push(i, &mut out);
        }
    }
    for name in args.texts("NOEUD") {
        push(node_by_name(mesh, args, "NOEUD", name)?, &mut out);
    }
    Ok(out)
}

/// The node called `name` (`N12`), read under keyword `key` (NOEUD,
/// SANS_NOEUD...); an unknown name is an error naming the valid range.
pub fn node_by_name(mesh: &Mesh, args: &Args, key: &str, name: &str) -> Result<usize, Diagnostic> {
    entity_by_name(args, key, name, 'N', mesh.nnodes(), "node")
}

/// The cell called `name` (`M3`), read under keyword `key` (MAILLE,
/// SANS_MAILLE...); an unknown name is an error naming the valid range.
pub fn cell_by_name(mesh: &Mesh, args: &Args, key: &str, name: &str) -> Result<usize, Diagnostic> {
    entity_by_name(args, key, name, 'M', mesh.ncells(), "cell")
}

/// Entity `name` among `count` named `<prefix>1..<prefix><count>`, the
/// only names aster meshes give.
fn entity_by_name(
    args: &Args,
    key: &str,
    name: &str,
    prefix: char,
    count: usize,
    what: &str,
) -> Result<usize, Diagnostic> {
    parse_name(name, prefix, count).ok_or_else(|| {
        args.error(
            key,
            format!(
                "'{name}' is not a {what} of the mesh: {what}s are named {prefix}1 to \
                 {prefix}{count} (aster meshes have no {what} names)"
            ),
        )
    })
}

/// The single node of GROUP_NO / NOEUD (TEST_RESU): more or fewer is an
/// error, as code_aster's `utnono` makes it fatal. Returns the node and
/// the header column (`GROUP_NO` or `NOEUD`, with the value written).
pub fn single_node(mesh: &Mesh, args: &Args) -> Result<(usize, &'static str, String), Diagnostic> {
    let nodes = nodes_of(mesh, args)?;
    let (key, label) = if args.has("GROUP_NO") {
        ("GROUP_NO", args.texts("GROUP_NO").join(" "))
    } else {
        ("NOEUD", args.texts("NOEUD").join(" "))
    };
    match nodes.as_slice() {
        [one] => Ok((*one, key, label)),
        [] => Err(args.error(
            key,
            format!("{key} {label} holds no node: exactly one is needed"),
        )),
        many => Err(args.error(
            key,
            format!(
                "{key} {label} holds {} nodes ({}{}): exactly one is needed",
                many.len(),
                many.iter()
                    .take(5)
                    .map(|&i| node_name(i))
                    .collect::<Vec<_>>()
                    .join(", "),
                if many.len() > 5 { ", ..." } else { "" }
            ),
        )),
    }
}

/// The single cell of GROUP_MA / MAILLE (TEST_RESU on a Gauss field).
pub fn single_cell(mesh: &Mesh, args: &Args) -> Result<(usize, &'static str, String), Diagnostic> {
    let mut cells: Vec<usize> = Vec::new();
    let key = if args.has("GROUP_MA") {
        "GROUP_MA"
    } else {
        "MAILLE"
    };
    for g in args.texts("GROUP_MA") {
        let Some(list) = mesh.cell_groups.get(g) else {
            let known: Vec<&str> = mesh.cell_groups.keys().map(String::as_str).collect();
            let mut d = args.error("GROUP_MA", format!("the mesh has no cell group '{g}'"));
            d.suggestion = closest(g, &known);
            d.choices = known.iter().map(|s| s.to_string()).collect();
            return Err(d);
        };
        cells.extend(list);
    }
    for name in args.texts("MAILLE") {
        cells.push(parse_name(name, 'M', mesh.ncells()).ok_or_else(|| {
            args.error(
                "MAILLE",
                format!(
                    "'{name}' is not a cell of the mesh: cells are named M1 to M{}",
                    mesh.ncells()
                ),
            )
        })?);
    }
    cells.sort_unstable();
    cells.dedup();
    let label = args.texts(key).join(" ");
    match cells.as_slice() {
        [one] => Ok((*one, key, label)),
        other => Err(args.error(
            key,
            format!(
                "{key} {label} holds {} cells: exactly one is needed",
                other.len()
            ),
        )),
    }
}

/// CRITERE / PRECISION of an instant search at this level: `PRECISION`
/// relative to the instant (RELATIF) or absolute.
pub fn inst_access(args: &Args, inst: f64, default_precision: f64) -> Access {
    Access::Inst {
        inst,
        precision: args.real("PRECISION").unwrap_or(default_precision),
        relative: args.text("CRITERE").unwrap_or("RELATIF") != "ABSOLU",
    }
}

/// The stored indices asked by NUME_ORDRE or by a DEFI_LIST_ENTI list in
/// LIST_ORDRE at this level, with the keyword that gave them (for
/// messages); None when neither is given.
pub fn nume_ordre_selection(
    study: &Study,
    args: &Args,
) -> Result<Option<(&'static str, Vec<i64>)>, Diagnostic> {
    if args.has("NUME_ORDRE") {
        return Ok(Some(("NUME_ORDRE", args.ints("NUME_ORDRE"))));
    }
    let Some(name) = args.concept("LIST_ORDRE") else {
        return Ok(None);
    };
    match study.concepts.data(name) {
        Some(ConceptData::ListInt(v)) => Ok(Some(("LIST_ORDRE", v.clone()))),
        _ => Err(no_data(args, "LIST_ORDRE", name, "list of integers")),
    }
}

/// The steps selected by TOUT_ORDRE / NUME_ORDRE / LIST_ORDRE / INST / LIST_INST at this
/// level, in the order asked; all stored steps when none is given. An
/// index or instant that is not stored is an error naming the keyword (the
/// message gives the nearest stored instant).
pub fn select_steps<'r>(
    study: &Study,
    result: &'r EvolNoli,
    args: &Args,
) -> Result<Vec<&'r Step>, Diagnostic> {
    if let Some((key, indices)) = nume_ordre_selection(study, args)? {
        return indices
            .into_iter()
            .map(|n| {
                let n = usize::try_from(n)
                    .map_err(|_| args.error(key, format!("NUME_ORDRE {n} is negative")))?;
                result
                    .find(Access::NumeOrdre(n))
                    .map_err(|e| args.error(key, e))
            })
            .collect();
    }
    let (key, instants) = if args.has("INST") {
        ("INST", args.reals("INST"))
    } else if args.has("LIST_INST") {
        let name = args.concept("LIST_INST").unwrap_or_default();
        match study.concepts.data(name) {
            Some(ConceptData::ListReal(v)) => ("LIST_INST", v.clone()),
            _ => return Err(no_data(args, "LIST_INST", name, "list of reals")),
        }
    } else {
        return Ok(result.steps.iter().collect());
    };
    instants
        .into_iter()
        .map(|t| {
            result
                .find(inst_access(args, t, 1e-6))
                .map_err(|e| args.error(key, e))
        })
        .collect()
}

/// Nodal field `nom_cham` of a step; its absence is an error on `key`
/// listing the fields the step holds.
pub fn step_nodal<'r>(
    step: &'r Step,
    nom_cham: &str,
    args: &Args,
    key: &str,
    result_name: &str,
) -> Result<&'r NodalField, Diagnostic> {
    step.nodal.get(nom_cham).ok_or_else(|| {
        args.error(
            key,
            format!(
                "result {result_name} has no nodal field {nom_cham} at NUME_ORDRE {} (INST {}){}{}{}",
                step.nume_ordre,
                crate::post::test_report::py_repr(step.inst),
                step.exclusion_note(nom_cham),
                fields_held(step),
                if nom_cham == "CONT_NOEU" {
                    " (CONT_NOEU exists only for a computation with DEFI_CONTACT DISCRETE or CONTINUE; LIAISON_UNIL produces no CONT_NOEU, as in code_aster: the reactions are REAC_NODA of CALC_CHAMP)"
                } else {
                    ""
                }
            ),
        )
    })
}

/// Gauss field `nom_cham` of a step, as [`step_nodal`].
pub fn step_gauss<'r>(
    step: &'r Step,
    nom_cham: &str,
    args: &Args,
    key: &str,
    result_name: &str,
) -> Result<&'r GaussField, Diagnostic> {
    step.gauss.get(nom_cham).ok_or_else(|| {
        args.error(
            key,
            format!(
                "result {result_name} has no Gauss-point field {nom_cham} at NUME_ORDRE {} (INST {}){}{}",
                step.nume_ordre,
                crate::post::test_report::py_repr(step.inst),
                step.exclusion_note(nom_cham),
                fields_held(step)
            ),
        )
    })
}

/// Field by element at nodes `nom_cham` of a step (CALC_CHAMP's
/// SIEF_ELNO, EPSI_ELNO, VARI_ELNO...), as [`step_nodal`].
pub fn step_elno<'r>(
    step: &'r Step,
    nom_cham: &str,
    args: &Args,
    key: &str,
    result_name: &str,
) -> Result<&'r GaussField, Diagnostic> {
    step.elno.get(nom_cham).ok_or_else(|| {
        args.error(
            key,
            format!(
                "result {result_name} has no field {nom_cham} at NUME_ORDRE {} (INST {}): compute it with CALC_CHAMP{}{}",
                step.nume_ordre,
                crate::post::test_report::py_repr(step.inst),
                step.exclusion_note(nom_cham),
                fields_held(step)
            ),
        )
    })
}

fn fields_held(step: &Step) -> String {
    let names: Vec<&str> = step
        .nodal
        .keys()
        .chain(step.gauss.keys())
        .chain(step.elno.keys())
        .map(String::as_str)
        .collect();
    if names.is_empty() {
        "; this step holds no field".to_string()
    } else {
        format!("; this step holds {}", names.join(", "))
    }
}

/// Whether a field name is one of the Gauss-point fields (`*_ELGA`).
pub fn is_gauss_name(nom_cham: &str) -> bool {
    nom_cham.ends_with("_ELGA")
}

/// The index of component `cmp` in `components`, or an error on `key`
/// listing them.
pub fn component_index(
    components: &[String],
    cmp: &str,
    args: &Args,
    key: &str,
    field: &str,
) -> Result<usize, Diagnostic> {
    components.iter().position(|c| c == cmp).ok_or_else(|| {
        let mut d = args.error(
            key,
            format!(
                "field {field} has no component {cmp} (components: {})",
                components.join(", ")
            ),
        );
        d.suggestion = closest(cmp, components);
        d
    })
}

/// A table error as a diagnostic on the keyword it names (or `key`).
pub fn table_error(args: &Args, key: &str, e: TableError) -> Diagnostic {
    let kw = e.keyword.clone().unwrap_or_else(|| key.to_string());
    // `FILTRE/VALE_I` names a keyword inside an occurrence: point at the
    // factor keyword, whose path is known here.
    let top = kw.split('/').next().unwrap_or(key).to_string();
    let mut d = args.error(&top, e.message);
    if kw != top {
        d = d.note(format!("keyword {kw}"));
    }
    d
}

/// code_aster's automatic title of a produced concept (`ASTER <version>
/// CONCEPT <name> CALCULE LE <date> A <time> DE TYPE <type>`), with the
/// current date and time (UTC).
pub fn concept_title(name: &str, ty: &str) -> Vec<String> {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    let (y, m, d) = civil_from_days((secs / 86_400) as i64);
    let s = secs % 86_400;
    crate::post::table::default_title(
        env!("CARGO_PKG_VERSION"),
        name,
        &format!("{m:02}/{d:02}/{y:04}"),
        &format!("{:02}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60),
        ty,
    )
}

/// Gregorian date of a day count since 1970-01-01 (H. Hinnant's
/// days-to-civil algorithm).
fn civil_from_days(z: i64) -> (i64, u32, u32) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let y = yoe + era * 400 + i64::from(m <= 2);
    (y, m, d)
}

/// The test keywords of a TEST_RESU / TEST_TABLE occurrence: VALE_CALC
/// (`_I`, `_K`), TOLE_MACHINE(1) and CRITERE(1) (1e-6 and RELATIF when
/// absent), REFERENCE with VALE_REFE and PRECISION, ORDRE_GRANDEUR,
/// VALE_ABS and LEGENDE.
pub fn test_spec(occ: &Args) -> Result<TestSpec, Diagnostic> {
    let vale_calc: Vec<TestValue> = if occ.has("VALE_CALC_I") {
        occ.ints("VALE_CALC_I")
            .into_iter()
            .map(TestValue::Int)
            .collect()
    } else if occ.has("VALE_CALC_K") {
        occ.texts("VALE_CALC_K")
            .into_iter()
            .map(|s| TestValue::Text(s.to_string()))
            .collect()
    } else {
        occ.reals("VALE_CALC")
            .into_iter()
            .map(TestValue::Real)
            .collect()
    };
    let mut spec = TestSpec::new(vale_calc);
    spec.legend = occ.text("LEGENDE").map(str::to_string);
    if let Some(t) = occ.reals("TOLE_MACHINE").first() {
        spec.tole_machine = *t;
    }
    if let Some(c) = occ.texts("CRITERE").first() {
        spec.critere = Critere::parse(c)
            .ok_or_else(|| occ.error("CRITERE", format!("unknown CRITERE '{c}'")))?;
    }
    spec.ordre_grandeur = occ.real("ORDRE_GRANDEUR");
    spec.vale_abs = occ.text("VALE_ABS") == Some("OUI");
    if let Some(kind) = occ.text("REFERENCE") {
        let kind = RefKind::parse(kind)
            .ok_or_else(|| occ.error("REFERENCE", format!("unknown REFERENCE '{kind}'")))?;
        let values: Vec<TestValue> = if occ.has("VALE_REFE_I") {
            occ.ints("VALE_REFE_I")
                .into_iter()
                .map(TestValue::Int)
                .collect()
        } else if occ.has("VALE_REFE_K") {
            occ.texts("VALE_REFE_K")
                .into_iter()
                .map(|s| TestValue::Text(s.to_string()))
                .collect()
        } else {
            occ.reals("VALE_REFE")
                .into_iter()
                .map(TestValue::Real)
                .collect()
        };
        let mut r = Reference::new(kind, values);
        if let Some(p) = occ.real("PRECISION") {
            r.precision = p;
        }
        spec.reference = Some(r);
    }
    Ok(spec)
}

/// Runs the checks of one occurrence on `computed`; a bad tolerance, or
/// VALE_CALC of the wrong type, is an error on the VALE_CALC keyword
/// given, a VALE_REFE of the wrong type (VALE_CALC being right or absent)
/// on the VALE_REFE keyword given: the message names the keyword the
/// value must be given with.
pub fn run_checks(
    occ: &Args,
    spec: &TestSpec,
    computed: &TestValue,
) -> Result<Vec<CheckLine>, Diagnostic> {
    occurrence_checks(spec, computed).map_err(|e| {
        let calc_fits = spec.vale_calc.iter().all(|v| v.same_type(computed));
        let refe_fits = spec
            .reference
            .as_ref()
            .is_none_or(|r| r.values.iter().all(|v| v.same_type(computed)));
        let family = if calc_fits && !refe_fits {
            "VALE_REFE"
        } else {
            "VALE_CALC"
        };
        let key = ["_I", "_K", ""]
            .into_iter()
            .map(|s| format!("{family}{s}"))
            .find(|k| occ.has(k))
            .unwrap_or_else(|| family.to_string());
        occ.error(&key, e)
    })
}

/// Writes an occurrence's block to the .resu, counts its lines and logs
/// its alarms (with the location of the occurrence in the message file).
pub fn report_checks(study: &mut Study, occ: &Args, block: &str, lines: &[CheckLine]) {
    study.write_unit(8, block);
    crate::post::test_report::tally(&mut study.tests, lines);
    for l in lines {
        for a in &l.alarms {
            alarm(study, &occ.command, a.id, &a.text);
        }
    }
    let statuses: Vec<String> = lines
        .iter()
        .map(|l| format!("{} {}", l.kind.as_str(), l.status.as_str().trim()))
        .collect();
    study.log(format!("    {}: {}", occ.key_path(""), statuses.join(", ")));
}

/// The NOM_PARA, NOM_RESU, INTERPOL and PROL_GAUCHE/PROL_DROITE keywords
/// that RECU_FONCTION and CALC_FONCTION apply to the function they
/// produce, when given (one INTERPOL value holds for both axes).
pub fn function_overrides(args: &Args, f: &mut Function) -> Result<(), Diagnostic> {
    if let Some(p) = args.text("NOM_PARA") {
        f.para = p.to_string();
    }
    if let Some(r) = args.text("NOM_RESU") {
        f.resu = r.to_string();
    }
    let interp = args.texts("INTERPOL");
    if !interp.is_empty() {
        let one = |s: &str| match s {
            "LIN" => Ok(Interp::Lin),
            "LOG" => Ok(Interp::Log),
            other => Err(args.not_implemented("INTERPOL", &format!("INTERPOL='{other}'"))),
        };
        let x = one(interp[0])?;
        let y = one(interp.get(1).copied().unwrap_or(interp[0]))?;
        f.interpolation = (x, y);
    }
    for (key, side) in [("PROL_GAUCHE", &mut f.left), ("PROL_DROITE", &mut f.right)] {
        if let Some(p) = args.text(key) {
            *side = Extrapolation::parse(p)
                .ok_or_else(|| args.error(key, format!("unknown extension '{p}'")))?;
        }
    }
    Ok(())
}

/// The FILTRE occurrences of a command (TEST_TABLE, IMPR_TABLE,
/// RECU_FONCTION), with their defaults.
pub fn filters_of(args: &Args) -> Result<Vec<Filter>, Diagnostic> {
    args.facts("FILTRE").iter().map(filter_of).collect()
}

/// One filter from the keywords of `f` (a FILTRE occurrence, or CALC_TABLE's
/// ACTION occurrence with OPERATION='FILTRE', which holds the same ones).
pub fn filter_of(f: &Args) -> Result<Filter, Diagnostic> {
    let crit = f.text("CRIT_COMP").unwrap_or("EQ");
    let crit_comp = CritComp::parse(crit)
        .ok_or_else(|| f.error("CRIT_COMP", format!("unknown CRIT_COMP '{crit}'")))?;
    let values = if f.has("VALE") {
        FilterValues::Real(f.reals("VALE"))
    } else if f.has("VALE_I") {
        FilterValues::Int(f.ints("VALE_I"))
    } else if f.has("VALE_K") {
        FilterValues::Text(f.texts("VALE_K").iter().map(|s| s.to_string()).collect())
    } else {
        FilterValues::None
    };
    let mut filter = Filter::new(f.text("NOM_PARA").unwrap_or_default(), crit_comp, values);
    if f.text("CRITERE") == Some("ABSOLU") {
        filter.critere = Critere::Absolu;
    }
    if let Some(p) = f.real("PRECISION") {
        filter.precision = p;
    }
    Ok(filter)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_read_back() {
        assert_eq!(node_name(0), "N1");
        assert_eq!(parse_name("N12", 'N', 12), Some(11));
        assert_eq!(parse_name("N13", 'N', 12), None);
        assert_eq!(parse_name("N0", 'N', 12), None);
        assert_eq!(parse_name("N01", 'N', 12), None);
        assert_eq!(parse_name("M3", 'N', 12), None);
        assert_eq!(pad8("RESU"), "RESU____");
        assert_eq!(pad8("RESULTAT"), "RESULTAT");
    }

    #[test]
    fn dates_from_day_counts() {
        assert_eq!(civil_from_days(0), (1970, 1, 1));
        // 2020-11-09, the date of the code_aster commit the docs cite.
        assert_eq!(civil_from_days(18_575), (2020, 11, 9));
        assert_eq!(civil_from_days(11_016), (2000, 2, 29));
    }
}
