//! Conversions between the engine's full vectors / Gauss-point states and
//! the result's fields (DEPL, VITE, ACCE, SIEF_ELGA, VARI_ELGA).

use super::assembly::Assembler;
use crate::element::{hexs8, Kinematics, PointState};
use crate::law::InternalVars;
use crate::model::spec::Formulation;
use crate::result::{GaussField, NodalField};

/// Which of the state's rows are the Gauss points a user addresses
/// (EVAL_ELGA and POINT of SUIVI_DDL and OBSERVATION), cell by cell: a
/// HEXS8 cell stores its centre point and then 12 rows of hourglass
/// stresses, which are not points: [`gauss`] shows them as the FSTAB
/// components of the one point, and so does this view.
#[derive(Debug, Clone)]
pub struct GaussRows {
    offsets: Vec<usize>,
    hexs8: Vec<bool>,
}

impl GaussRows {
    pub fn of(asm: &Assembler) -> Self {
        let offsets = asm.cell_state_offsets.clone();
        let mut hexs8 = vec![false; offsets.len().saturating_sub(1)];
        for e in &asm.elements {
            hexs8[e.cell] = e.spec.is_hexs8();
        }
        GaussRows { offsets, hexs8 }
    }

    pub fn ncells(&self) -> usize {
        self.hexs8.len()
    }

    /// The number of Gauss points of cell `c` (0 outside the model).
    pub fn npoints(&self, c: usize) -> usize {
        let n = self.offsets[c + 1] - self.offsets[c];
        if self.hexs8[c] {
            n.min(1)
        } else {
            n
        }
    }

    /// SIEF_ELGA component `k` (in [`sief_components`] order) at point `p`
    /// (0-based) of cell `c`.
    pub fn stress(&self, points: &[PointState], c: usize, p: usize, k: usize) -> f64 {
        let (a, b) = (self.offsets[c], self.offsets[c + 1]);
        if k < 6 {
            points[a + p].stress[k]
        } else if self.hexs8[c] {
            hexs8::hourglass_stresses(&points[a..b])[k - 6]
        } else {
            0.0
        }
    }

    /// VARI_ELGA component `k` at point `p` of cell `c` (0 beyond the
    /// cell's own internal variables, as [`gauss`] pads them).
    pub fn internal(&self, points: &[PointState], c: usize, p: usize, k: usize) -> f64 {
        let st = &points[self.offsets[c] + p];
        st.internal.as_slice().get(k).copied().unwrap_or(0.0)
    }
}

/// Nodal field of a full vector: components = the model's dofs, nodes of
/// no element absent.
pub fn nodal(asm: &Assembler, names: &[String], v: &[f64]) -> NodalField {
    let nb = &asm.numbering;
    let mut f = NodalField::absent(names.to_vec(), nb.nnodes);
    for n in 0..nb.nnodes {
        if nb.active_node[n] {
            for c in 0..nb.ndpn {
                f.set(n, c, v[n * nb.ndpn + c]);
            }
        }
    }
    f
}

/// Reads a nodal field into a full vector; absent pairs (and components
/// the model does not have) read as 0 (semantics.md §13 trap 17).
pub fn from_nodal(asm: &Assembler, names: &[String], field: &NodalField) -> Vec<f64> {
    let nb = &asm.numbering;
    let mut out = vec![0.0; nb.nfull()];
    let idx: Vec<Option<usize>> = names.iter().map(|n| field.component_index(n)).collect();
    for n in 0..nb.nnodes.min(field.nnodes()) {
        if !nb.active_node[n] {
            continue;
        }
        for (c, k) in idx.iter().enumerate() {
            if let Some(k) = k {
                let v = field.values[n * field.ncmp() + k];
                if !v.is_nan() {
                    out[n * nb.ndpn + c] = v;
                }
            }
        }
    }
    out
}

/// SIEF_ELGA component names: 4 in AXIS and D_PLAN, 6 in 3D (semantics.md §10),
/// plus FSTAB1..FSTAB72 when the model has HEXS8 elements (their
/// hourglass stresses; other cells read 0 there).
pub fn sief_components(asm: &Assembler) -> Vec<String> {
    let plane = asm
        .elements
        .first()
        .is_some_and(|e| e.spec.formulation != Formulation::Solid3d);
    let all = ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"];
    let n = if plane { 4 } else { 6 };
    let mut out: Vec<String> = all[..n].iter().map(|s| s.to_string()).collect();
    if has_hexs8(asm) {
        out.extend((1..=hexs8::NQ).map(|k| format!("FSTAB{k}")));
    }
    out
}

fn has_hexs8(asm: &Assembler) -> bool {
    asm.elements.iter().any(|e| e.spec.is_hexs8())
}

/// SIEF_ELGA and VARI_ELGA of the Gauss-point states. VARI_ELGA has as
/// many components as the largest law; cells of a law with fewer
/// variables are padded with 0. A HEXS8 cell shows one point: its centre
/// stress followed by its 72 hourglass stresses.
pub fn gauss(asm: &Assembler, ncells: usize, points: &[PointState]) -> (GaussField, GaussField) {
    let sief_cmp = sief_components(asm);
    let nvari = asm.nvari_of_cell(ncells);
    let nv = nvari.iter().copied().max().unwrap_or(0);
    let vari_cmp: Vec<String> = (1..=nv).map(|k| format!("V{k}")).collect();
    let ns = sief_cmp.len();
    let nstress = ns.min(6);
    let mut sief = GaussField {
        components: sief_cmp,
        offsets: Vec::with_capacity(ncells + 1),
        values: Vec::with_capacity(points.len() * ns),
    };
    let mut vari = GaussField {
        components: vari_cmp,
        offsets: Vec::with_capacity(ncells + 1),
        values: Vec::with_capacity(points.len() * nv),
    };
    let mut hexs8_cell = vec![false; ncells];
    for e in &asm.elements {
        hexs8_cell[e.cell] = e.spec.is_hexs8();
    }
    for c in 0..ncells {
        sief.offsets.push(sief.values.len());
        vari.offsets.push(vari.values.len());
        let (a, b) = (asm.cell_state_offsets[c], asm.cell_state_offsets[c + 1]);
        let rows = &points[a..b];
        let shown = if hexs8_cell[c] { &rows[..1] } else { rows };
        for p in shown {
            sief.values
                .extend_from_slice(&p.stress.as_slice()[..nstress]);
            if hexs8_cell[c] {
                sief.values
                    .extend_from_slice(&hexs8::hourglass_stresses(rows));
            } else {
                sief.values.extend(std::iter::repeat_n(0.0, ns - nstress));
            }
            let iv = p.internal.as_slice();
            vari.values
                .extend((0..nv).map(|k| iv.get(k).copied().unwrap_or(0.0)));
        }
    }
    sief.offsets.push(sief.values.len());
    vari.offsets.push(vari.values.len());
    (sief, vari)
}

/// Gauss-point states from stored SIEF_ELGA and VARI_ELGA (a continued
/// computation must restart from exactly the stored state, HEXS8's
/// hourglass stresses included).
pub fn states_from_gauss(
    asm: &Assembler,
    sief: &GaussField,
    vari: &GaussField,
) -> Result<Vec<PointState>, String> {
    states_from_fields(asm, sief, Some(vari))
}

/// [`states_from_gauss`] with VARI_ELGA optional: without it the internal
/// variables are those of a virgin point (for forces evaluated with the
/// laws read at their stored state, `behaviour::StoredStress`).
pub fn states_from_fields(
    asm: &Assembler,
    sief: &GaussField,
    vari: Option<&GaussField>,
) -> Result<Vec<PointState>, String> {
    let mut out = asm.initial_states();
    let ns = sief.ncmp();
    let nv = vari.map_or(0, |v| v.ncmp());
    let ncells = asm.cell_state_offsets.len() - 1;
    if sief.offsets.len() != ncells + 1 || vari.is_some_and(|v| v.offsets.len() != ncells + 1) {
        return Err("SIEF_ELGA/VARI_ELGA of the initial state are on another mesh".into());
    }
    let fstab = sief.components.iter().position(|c| c == "FSTAB1");
    let nstress = fstab.unwrap_or(ns);
    for e in &asm.elements {
        let nvar = if vari.is_some() {
            out[e.state_offset].internal.as_slice().len()
        } else {
            0
        };
        let npg = crate::element::output_points(&e.spec);
        let hex = e.spec.is_hexs8();
        if sief.npg(e.cell) != npg
            || vari.is_some_and(|v| v.npg(e.cell) != npg)
            || nv < nvar
            || nstress > 6
            || (hex && (fstab != Some(6) || ns != 6 + hexs8::NQ))
        {
            return Err(format!(
                "cell M{}: the stored SIEF_ELGA/VARI_ELGA do not match the element {} ({} points, {} variables{})",
                e.cell + 1,
                e.spec.name,
                npg,
                nvar,
                if hex { ", 78 stress components" } else { "" }
            ));
        }
        let s = sief.cell(e.cell);
        for p in 0..npg {
            let st = &mut out[e.state_offset + p];
            for k in 0..nstress {
                st.stress[k] = s[p * ns + k];
            }
            if let Some(vari) = vari {
                let v = vari.cell(e.cell);
                st.internal = InternalVars::from_slice(&v[p * nv..p * nv + nvar])
                    .ok_or_else(|| format!("cell M{}: bad internal variables", e.cell + 1))?;
            }
        }
        if hex {
            let internal = out[e.state_offset].internal;
            for k in 0..hexs8::NQ {
                let row = &mut out[e.state_offset + 1 + k / 6];
                row.stress[k % 6] = s[6 + k];
                row.internal = internal;
            }
        }
    }
    Ok(out)
}

/// Overwrites the Gauss-point states `points` with the fields of
/// ETAT_INIT SIGM (stresses) and VARI (internal variables), as code_aster
/// reads them field by field after EVOL_NOLI's (nmdoet: nmetl1 then
/// nmetl2), so a field given replaces the result's. The fields are those
/// of CREA_CHAMP on the model (one row of values per point of the
/// element's SIEF_ELGA family); a component not given, or a value never
/// assigned (NaN), is 0. A HEXS8 element takes SIXX...SIYZ at its centre
/// point and its hourglass stresses from FSTAB1..FSTAB72 (0 when absent).
/// The error names the keyword and the cell (code_aster names, M7).
pub fn apply_initial_fields(
    asm: &Assembler,
    points: &mut [PointState],
    sigm: Option<&GaussField>,
    vari: Option<&GaussField>,
) -> Result<(), (&'static str, String)> {
    const STRESS: [&str; 6] = ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"];
    let ncells = asm.cell_state_offsets.len() - 1;
    for (key, f) in [("SIGM", sigm), ("VARI", vari)] {
        if let Some(f) = f {
            if f.offsets.len() != ncells + 1 {
                return Err((
                    key,
                    format!(
                        "the field has {} cells, the mesh of the model {ncells}: it was built on another mesh",
                        f.offsets.len().saturating_sub(1)
                    ),
                ));
            }
        }
    }
    let read = |f: &GaussField, c: usize, p: usize, k: usize| {
        let v = f.cell(c)[p * f.ncmp() + k];
        if v.is_nan() {
            0.0
        } else {
            v
        }
    };
    for e in &asm.elements {
        let c = e.cell;
        let npg = crate::element::output_points(&e.spec);
        let hex = e.spec.is_hexs8();
        let rows = asm.cell_state_offsets[c + 1] - asm.cell_state_offsets[c];
        let base = e.state_offset;
        for (key, f) in [("SIGM", sigm), ("VARI", vari)] {
            if let Some(f) = f {
                if f.npg(c) != npg {
                    return Err((
                        key,
                        format!(
                            "cell M{}: the field has {} Gauss point(s) there, the element {} has {npg}: build the field by CREA_CHAMP on the model of the computation (AFFE with MODELE, or EXTR of a result of this model)",
                            c + 1,
                            f.npg(c),
                            e.spec.name
                        ),
                    ));
                }
            }
        }
        if let Some(f) = sigm {
            // SIMO_MIEHE and GDEF_LOG start a step from their internal
            // variables (b̄e, and the logarithmic stress T in V3..V8), not
            // from SIEF: a stress written there alone would vanish at the
            // first step without a word (probe sigmp: a released D_PLAN
            // bar kept DX = 0). Without VARI (which holds that state, as
            // an EXTR of both fields of such a result gives it) it is
            // refused until it is converted into the law's state.
            if matches!(e.kin, Kinematics::SimoMiehe | Kinematics::GdefLog)
                && vari.is_none()
                && (0..npg).any(|p| (0..f.ncmp()).any(|k| read(f, c, p, k) != 0.0))
            {
                return Err((
                    "SIGM",
                    format!(
                        "not implemented yet: cell M{} has DEFORMATION='{}', whose law starts each step from its internal variables, not from the stress: an initial stress given by SIGM would be lost; use DEFORMATION='PETIT', 'PETIT_REAC' or 'GROT_GDEP', or give the law's state with VARI too (GDEF_LOG: the logarithmic stress T in V3..V8; an EXTR of SIEF_ELGA and VARI_ELGA of such a result gives both)",
                        c + 1,
                        e.kin.strain_measure().aster_name()
                    ),
                ));
            }
            let mut map: Vec<(usize, usize, usize)> = Vec::new(); // (field cmp, row, stress index)
            let plane = e.spec.formulation != Formulation::Solid3d;
            for (k, name) in f.components.iter().enumerate() {
                if let Some(i) = STRESS.iter().position(|s| s == name) {
                    // A CART on the mesh carries SIXZ, SIYZ: a plane
                    // element has none, so they must be 0 there.
                    if plane && i >= 4 {
                        if (0..npg).any(|p| read(f, c, p, k) != 0.0) {
                            return Err((
                                "SIGM",
                                format!(
                                    "cell M{}: the element {} (plane or axisymmetric) has no stress component {name}, which the field gives there",
                                    c + 1,
                                    e.spec.name
                                ),
                            ));
                        }
                        continue;
                    }
                    map.push((k, 0, i));
                } else if let Some(j) = name
                    .strip_prefix("FSTAB")
                    .and_then(|d| d.parse::<usize>().ok())
                    .filter(|j| (1..=hexs8::NQ).contains(j))
                {
                    if hex {
                        map.push((k, 1 + (j - 1) / 6, (j - 1) % 6));
                    }
                } else {
                    return Err((
                        "SIGM",
                        format!("the component {name} is not a stress component (SIXX, SIYY, SIZZ, SIXY, SIXZ, SIYZ)"),
                    ));
                }
            }
            for p in 0..npg {
                let shown = if hex { 0..rows } else { p..p + 1 };
                for r in shown {
                    points[base + r].stress = Default::default();
                }
                for &(k, row, i) in &map {
                    let r = if hex { row } else { p };
                    points[base + r].stress[i] = read(f, c, p, k);
                }
            }
        }
        if let Some(f) = vari {
            let nvar = points[base].internal.as_slice().len();
            let given: Vec<Option<usize>> = f
                .components
                .iter()
                .map(|n| crate::result::vari_index(n))
                .collect();
            if let Some(k) = given.iter().position(Option::is_none) {
                return Err((
                    "VARI",
                    format!(
                        "the component {} is not an internal variable (V1, V2, ...)",
                        f.components[k]
                    ),
                ));
            }
            let nfield = given.iter().flatten().copied().max().unwrap_or(0);
            // Components beyond the law's count are accepted when they hold
            // nothing there (0 or absent): a VARI_ELGA of a model mixing laws
            // is padded so to its largest count.
            let extra = (0..npg).any(|p| {
                given
                    .iter()
                    .enumerate()
                    .any(|(k, &j)| j.is_some_and(|j| j > nvar) && read(f, c, p, k) != 0.0)
            });
            if nfield < nvar || extra {
                return Err((
                    "VARI",
                    format!(
                        "cell M{}: the field gives {nfield} internal variable(s), the law of the element {} has {nvar}: give V1 to V{nvar} (code_aster refuses a VARI field whose count differs from the law's)",
                        c + 1,
                        e.spec.name
                    ),
                ));
            }
            for p in 0..npg {
                let mut v = vec![0.0; nvar];
                for (k, j) in given.iter().enumerate() {
                    if let Some(j) = j.filter(|&j| j <= nvar) {
                        v[j - 1] = read(f, c, p, k);
                    }
                }
                let iv = InternalVars::from_slice(&v)
                    .ok_or_else(|| ("VARI", format!("cell M{}: bad internal variables", c + 1)))?;
                if hex {
                    for r in 0..rows {
                        points[base + r].internal = iv;
                    }
                } else {
                    points[base + p].internal = iv;
                }
            }
        }
    }
    Ok(())
}
