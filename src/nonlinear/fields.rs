//! Conversions between the engine's full vectors / Gauss-point states and
//! the result's fields (DEPL, VITE, ACCE, SIEF_ELGA, VARI_ELGA).

use super::assembly::Assembler;
use crate::element::{Formulation, PointState};
use crate::law::InternalVars;
use crate::result::{GaussField, NodalField};

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

/// SIEF_ELGA component names: 4 in AXIS, 6 in 3D (semantics.md §10).
pub fn sief_components(asm: &Assembler) -> Vec<String> {
    let axis = asm
        .elements
        .first()
        .is_some_and(|e| e.spec.formulation == Formulation::Axis);
    let all = ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ"];
    let n = if axis { 4 } else { 6 };
    all[..n].iter().map(|s| s.to_string()).collect()
}

/// SIEF_ELGA and VARI_ELGA of the Gauss-point states. VARI_ELGA has as
/// many components as the largest law; cells of a law with fewer
/// variables are padded with 0.
pub fn gauss(asm: &Assembler, ncells: usize, points: &[PointState]) -> (GaussField, GaussField) {
    let sief_cmp = sief_components(asm);
    let nvari = asm.nvari_of_cell(ncells);
    let nv = nvari.iter().copied().max().unwrap_or(0);
    let vari_cmp: Vec<String> = (1..=nv).map(|k| format!("V{k}")).collect();
    let ns = sief_cmp.len();
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
    for c in 0..ncells {
        sief.offsets.push(sief.values.len());
        vari.offsets.push(vari.values.len());
        let (a, b) = (asm.cell_state_offsets[c], asm.cell_state_offsets[c + 1]);
        for p in &points[a..b] {
            sief.values.extend_from_slice(&p.stress.as_slice()[..ns]);
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
/// computation must restart from exactly the stored state).
pub fn states_from_gauss(
    asm: &Assembler,
    sief: &GaussField,
    vari: &GaussField,
) -> Result<Vec<PointState>, String> {
    let mut out = asm.initial_states();
    let ns = sief.ncmp();
    let nv = vari.ncmp();
    let ncells = asm.cell_state_offsets.len() - 1;
    if sief.offsets.len() != ncells + 1 || vari.offsets.len() != ncells + 1 {
        return Err("SIEF_ELGA/VARI_ELGA of the initial state are on another mesh".into());
    }
    for e in &asm.elements {
        let nvar = out[e.state_offset].internal.as_slice().len();
        if sief.npg(e.cell) != e.npg || vari.npg(e.cell) != e.npg || nv < nvar || ns > 6 {
            return Err(format!(
                "cell {}: the stored SIEF_ELGA/VARI_ELGA do not match the element {} ({} points, {} variables)",
                e.cell + 1,
                e.spec.name,
                e.npg,
                nvar
            ));
        }
        let (s, v) = (sief.cell(e.cell), vari.cell(e.cell));
        for p in 0..e.npg {
            let st = &mut out[e.state_offset + p];
            for k in 0..ns {
                st.stress[k] = s[p * ns + k];
            }
            st.internal = InternalVars::from_slice(&v[p * nv..p * nv + nvar])
                .ok_or_else(|| format!("cell {}: bad internal variables", e.cell + 1))?;
        }
    }
    Ok(out)
}
