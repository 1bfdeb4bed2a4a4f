//! Files written by aster read by independent readers: medcoupling (which
//! uses libmed, like code_aster and SALOME), meshio and mdump, through
//! tests/med_interop.py. The expected content goes to a JSON sidecar. When
//! no reader is installed the test says so and passes.

#[path = "med_common.rs"]
mod common;

use std::fmt::Write;
use std::path::Path;
use std::process::Command;

use aster::medio::{read_mesh, write_result_fields, ElemField, FieldStep, NodalField};
use aster::mesh::Mesh;
use common::{all_types_mesh, scratch};

const MESH2D: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/med/mesh2d_quad8.med"
);
const SCRIPT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/med_interop.py");

fn num(v: f64) -> String {
    // Debug gives the shortest round-trip form; JSON accepts it as is.
    format!("{v:?}")
}

fn json_str(s: &str) -> String {
    format!("\"{}\"", s.replace('\\', "\\\\").replace('"', "\\\""))
}

fn json_list<T>(v: &[T], f: impl Fn(&T) -> String) -> String {
    format!("[{}]", v.iter().map(f).collect::<Vec<_>>().join(","))
}

fn json_fields(fields: &[(&str, &[String], &[FieldStep])]) -> String {
    json_list(fields, |(name, comps, steps)| {
        format!(
            "{{\"name\":{},\"components\":{},\"steps\":{}}}",
            json_str(name),
            json_list(comps, |c| json_str(c)),
            json_list(steps, |s| format!(
                "{{\"numdt\":{},\"time\":{},\"values\":{}}}",
                s.numdt,
                num(s.time),
                json_list(&s.values, |v| num(*v))
            ))
        )
    })
}

fn sidecar_entry(path: &Path, m: &Mesh, nodal: &[NodalField], cells: &[ElemField]) -> String {
    let mut s = String::new();
    let mdim = m.cells.iter().map(|c| c.kind.dim()).max().unwrap_or(0);
    let _ = write!(
        s,
        "{{\"path\":{},\"mesh\":{},\"dim\":{},\"mesh_dim\":{mdim},",
        json_str(&path.display().to_string()),
        json_str(&m.name),
        m.dim
    );
    let _ = write!(
        s,
        "\"coords\":{},",
        json_list(&m.coords, |p| json_list(&p[..m.dim], |x| num(*x)))
    );
    let _ = write!(
        s,
        "\"cell_types\":{},\"cells\":{},",
        json_list(&m.cells, |c| json_str(c.kind.med_name())),
        json_list(&m.cells, |c| json_list(&c.nodes, |n| n.to_string()))
    );
    for (key, groups) in [
        ("cell_groups", &m.cell_groups),
        ("node_groups", &m.node_groups),
    ] {
        let body: Vec<String> = groups
            .iter()
            .map(|(g, v)| format!("{}:{}", json_str(g), json_list(v, |i| i.to_string())))
            .collect();
        let _ = write!(s, "\"{key}\":{{{}}},", body.join(","));
    }
    let nf: Vec<_> = nodal
        .iter()
        .map(|f| (f.name.as_str(), f.components.as_slice(), f.steps.as_slice()))
        .collect();
    let cf: Vec<_> = cells
        .iter()
        .map(|f| (f.name.as_str(), f.components.as_slice(), f.steps.as_slice()))
        .collect();
    let _ = write!(
        s,
        "\"nodal_fields\":{},\"cell_fields\":{}}}",
        json_fields(&nf),
        json_fields(&cf)
    );
    s
}

fn python_reader() -> Option<String> {
    for module in ["medcoupling", "meshio"] {
        let ok = Command::new("python3")
            .args(["-c", &format!("import {module}")])
            .output()
            .map(|o| o.status.success())
            .unwrap_or(false);
        if ok {
            return Some(module.to_string());
        }
    }
    None
}

fn depl(m: &Mesh, steps: &[(i32, f64)]) -> NodalField {
    NodalField {
        name: "RESU____DEPL".into(),
        components: vec!["DX".into(), "DY".into()],
        steps: steps
            .iter()
            .map(|&(numdt, t)| FieldStep {
                numdt,
                time: t,
                values: m
                    .coords
                    .iter()
                    .flat_map(|p| [1e-3 * t * p[0], -2e-3 * t * p[1] + 1e-4 * f64::from(numdt)])
                    .collect(),
            })
            .collect(),
    }
}

#[test]
fn independent_readers_agree() {
    let Some(reader) = python_reader() else {
        println!(
            "skipped: neither medcoupling nor meshio is installed for python3 \
             (pip install medcoupling meshio) - MED interoperability not checked"
        );
        return;
    };
    let mut entries = Vec::new();

    // every cell type, groups incl. empty ones, nodal + cell fields
    let m = all_types_mesh();
    let nodal = vec![depl(&m, &[(0, 0.0), (1, 2.5e-6), (2, 5e-6)])];
    let cells = vec![ElemField {
        name: "RESU____EPSP".into(),
        components: vec!["V1".into()],
        steps: vec![FieldStep {
            numdt: 2,
            time: 5e-6,
            values: (0..m.ncells()).map(|c| c as f64 + 0.25).collect(),
        }],
    }];
    let p = scratch("interop_all.med");
    write_result_fields(&p, &m, &nodal, &cells).unwrap();
    entries.push(sidecar_entry(&p, &m, &nodal, &cells));

    // the 2D fixture written back by us, with the fixture's DEPL formula
    let m2 = read_mesh(Path::new(MESH2D), None).unwrap();
    let nodal2 = vec![depl(&m2, &[(1, 0.5), (2, 1.0), (3, 2.0)])];
    let p2 = scratch("interop_2d.med");
    write_result_fields(&p2, &m2, &nodal2, &[]).unwrap();
    entries.push(sidecar_entry(&p2, &m2, &nodal2, &[]));

    let json = scratch("interop.json");
    std::fs::write(&json, format!("{{\"files\":[{}]}}", entries.join(","))).unwrap();
    let out = Command::new("python3")
        .arg(SCRIPT)
        .arg(&json)
        .output()
        .expect("run python3");
    let text = String::from_utf8_lossy(&out.stdout);
    println!(
        "python readers (first found: {reader}):\n{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "MED interop check failed:\n{text}");
    assert!(text.contains(&format!("OK   {reader}")), "{text}");
}
