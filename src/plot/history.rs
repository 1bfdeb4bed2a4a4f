//! Curves over time at one-node groups (A1, B1, A2... in SDNV103), read
//! from every step of a nodal field of the result file, drawn with the
//! sweeps' plotter.

use std::path::Path;

use super::data::{unit_of, ResultData};
use crate::sweep::plot::{draw, Figure, Series, Style};

/// One curve: `GROUP_NO:FIELD:COMPONENT`, e.g. `A1:DEPL:DY`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct HistorySpec {
    pub group: String,
    pub field: String,
    pub component: String,
}

impl HistorySpec {
    pub fn parse(s: &str) -> Result<HistorySpec, String> {
        let parts: Vec<&str> = s.split(':').map(str::trim).collect();
        match parts.as_slice() {
            [g, f, c] if !g.is_empty() && !f.is_empty() && !c.is_empty() => Ok(HistorySpec {
                group: g.to_string(),
                field: f.to_string(),
                component: c.to_string(),
            }),
            _ => Err(format!(
                "--history '{s}': expected GROUP_NO:FIELD:COMPONENT, e.g. A1:DEPL:DY"
            )),
        }
    }
}

/// The (time, value) points of one curve.
pub fn history_points(data: &ResultData, spec: &HistorySpec) -> Result<Vec<(f64, f64)>, String> {
    let mesh = &data.mesh;
    let nodes = mesh.node_groups.get(&spec.group).ok_or_else(|| {
        let ones: Vec<&str> = mesh
            .node_groups
            .iter()
            .filter(|(_, n)| n.len() == 1)
            .map(|(g, _)| g.as_str())
            .collect();
        format!(
            "no node group '{}' in mesh '{}'; its one-node groups: {}",
            spec.group,
            mesh.name,
            if ones.is_empty() {
                "(none)".to_string()
            } else {
                ones.join(" ")
            }
        )
    })?;
    if nodes.len() != 1 {
        return Err(format!(
            "node group '{}' holds {} nodes: a history curve is drawn at a one-node group",
            spec.group,
            nodes.len()
        ));
    }
    let node = nodes[0];
    let field = data.field(&spec.field)?;
    if !field.is_nodal() {
        return Err(format!(
            "field {} has values per cell: history curves are drawn for nodal fields (DEPL, VITE...)",
            field.name()
        ));
    }
    let c = field.component(&spec.component)?;
    Ok((0..field.steps().len())
        .map(|k| (field.steps()[k].time, field.scalar(k, c)[node]))
        .collect())
}

/// Draws the curves of `specs` into `out` (PNG); returns the number of
/// points drawn.
pub fn draw_history(data: &ResultData, specs: &[HistorySpec], out: &Path) -> Result<usize, String> {
    let mut series = Vec::new();
    for s in specs {
        let points = history_points(data, s)?;
        let unit = unit_of(&s.field);
        series.push(Series {
            label: format!(
                "{} {} {}{}",
                s.group,
                s.field,
                s.component,
                if unit.is_empty() {
                    String::new()
                } else {
                    format!(" ({unit})")
                }
            ),
            points,
            style: Style::Line,
        });
    }
    let units: Vec<&str> = specs.iter().map(|s| unit_of(&s.field)).collect();
    let fields: Vec<String> = specs.iter().map(|s| s.field.to_ascii_uppercase()).collect();
    let y_label = if fields.iter().all(|f| *f == fields[0]) {
        if units[0].is_empty() {
            fields[0].clone()
        } else {
            format!("{} ({})", fields[0], units[0])
        }
    } else if units.iter().all(|u| *u == units[0]) && !units[0].is_empty() {
        format!("value ({})", units[0])
    } else {
        "value (mm, s, N, MPa)".to_string()
    };
    let n = series.iter().map(|s| s.points.len()).sum();
    let fig = Figure {
        title: format!(
            "{}: {}",
            data.path
                .file_name()
                .map(|s| s.to_string_lossy().to_string())
                .unwrap_or_default(),
            specs
                .iter()
                .map(|s| format!("{} {} {}", s.group, s.field, s.component))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        x_label: "time (s)".into(),
        y_label,
        log_x: false,
        log_y: false,
        series,
        annotations: Vec::new(),
        y_range: None,
    };
    draw(&fig, out, (1000, 650))?;
    Ok(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specs_parse_and_refuse() {
        assert_eq!(
            HistorySpec::parse("A1:DEPL:DY").unwrap(),
            HistorySpec {
                group: "A1".into(),
                field: "DEPL".into(),
                component: "DY".into()
            }
        );
        assert!(HistorySpec::parse("A1:DEPL").is_err());
        assert!(HistorySpec::parse("A1::DY").is_err());
    }
}
