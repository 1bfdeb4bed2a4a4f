//! The direction of dependencies between the top-level modules of src/
//! (docs/engine.md, "Layers"): a module may use modules of its own layer or
//! of a lower one, never of a higher one, and the modules form no cycle.
//!
//! The test reads every `crate::NAME` path of src/ (in `use` lines and in
//! inline paths such as `crate::profile::span(...)`; comments excluded) and
//! `aster::NAME` in src/main.rs, so a new import that breaks the rule
//! fails here with the file and line to change.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Layers from the top (0) to the bottom. A new top-level module must be
/// placed here (and in docs/engine.md) before the test accepts it.
const LAYERS: &[(&str, &[&str])] = &[
    ("drivers", &["main", "run", "bench", "sweep", "plot"]),
    ("commands", &["commands"]),
    (
        "language and files",
        &["catalog", "concepts", "medio", "study", "lang"],
    ),
    (
        "engine",
        &["nonlinear", "time", "solver", "contact", "element", "law"],
    ),
    (
        "data",
        &[
            "mesh",
            "model",
            "result",
            "post",
            "diag",
            "profile",
            "interrupt",
        ],
    ),
];

fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|(_, mods)| mods.contains(&module))
}

/// One reference from a file to another top-level module.
struct Edge {
    from: String,
    to: String,
    file: PathBuf,
    line: usize,
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("readable src dir") {
        let path = entry.expect("dir entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The top-level module a file of src/ belongs to (`src/mesh/ops.rs` ->
/// `mesh`, `src/main.rs` -> `main`); None for src/lib.rs.
fn module_of(src: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src).expect("file under src");
    let first = rel.components().next()?.as_os_str().to_str()?.to_string();
    let name = first.strip_suffix(".rs").unwrap_or(&first).to_string();
    (name != "lib").then_some(name)
}

/// Identifiers following `prefix` in `code` (`crate::mesh::ops` -> `mesh`;
/// `crate::{a, b::c}` -> `a`, `b`).
fn targets(code: &str, prefix: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find(prefix) {
        // Skip matches inside a longer identifier (`my_crate::`).
        let before = rest[..i].chars().next_back();
        rest = &rest[i + prefix.len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let ident = |s: &str| -> String {
            s.chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect()
        };
        if let Some(group) = rest.strip_prefix('{') {
            let end = group.find('}').unwrap_or(group.len());
            for part in group[..end].split(',') {
                let id = ident(part.trim());
                if !id.is_empty() {
                    out.push(id);
                }
            }
        } else {
            let id = ident(rest);
            if !id.is_empty() {
                out.push(id);
            }
        }
    }
    out
}

fn edges() -> Vec<Edge> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let mut edges = Vec::new();
    for file in files {
        let Some(from) = module_of(&src, &file) else {
            continue;
        };
        let text = std::fs::read_to_string(&file).expect("readable source");
        // Multi-line `use crate::{...}` groups: join each use statement.
        let mut pending: Option<(usize, String)> = None;
        for (n, raw) in text.lines().enumerate() {
            let code = raw.split("//").next().unwrap_or("");
            let (line, code) = match pending.take() {
                Some((l, mut acc)) => {
                    acc.push(' ');
                    acc.push_str(code);
                    (l, acc)
                }
                None => (n + 1, code.to_string()),
            };
            if code.contains("::{") && !code.contains('}') {
                pending = Some((line, code));
                continue;
            }
            let mut found = targets(&code, "crate::");
            if from == "main" {
                found.extend(targets(&code, "aster::"));
            }
            for to in found {
                if to != from {
                    edges.push(Edge {
                        from: from.clone(),
                        to,
                        file: file.strip_prefix(&src).unwrap().to_path_buf(),
                        line,
                    });
                }
            }
        }
    }
    edges
}

#[test]
fn no_lower_layer_imports_a_higher_one() {
    let edges = edges();
    assert!(
        edges.len() > 200,
        "the scan found only {} references: is it reading src/?",
        edges.len()
    );
    let mut errors = Vec::new();
    for e in &edges {
        let (Some(lf), Some(lt)) = (layer_of(&e.from), layer_of(&e.to)) else {
            let unknown = if layer_of(&e.from).is_none() {
                &e.from
            } else {
                &e.to
            };
            errors.push(format!(
                "src/{}:{}: module `{unknown}` is in no layer: place it in LAYERS (tests/layering.rs) and in docs/engine.md",
                e.file.display(),
                e.line
            ));
            continue;
        };
        if lt < lf {
            errors.push(format!(
                "src/{}:{}: `{}` ({}) uses `{}` ({}), a higher layer",
                e.file.display(),
                e.line,
                e.from,
                LAYERS[lf].0,
                e.to,
                LAYERS[lt].0
            ));
        }
    }
    assert!(errors.is_empty(), "{}", errors.join("\n"));
}

#[test]
fn the_modules_form_no_cycle() {
    let edges = edges();
    let mut graph: BTreeMap<&str, BTreeSet<&str>> = BTreeMap::new();
    for e in &edges {
        graph.entry(&e.from).or_default().insert(&e.to);
        graph.entry(&e.to).or_default();
    }
    // Depth-first search with colours; a grey successor closes a cycle.
    fn visit<'a>(
        n: &'a str,
        graph: &BTreeMap<&'a str, BTreeSet<&'a str>>,
        colour: &mut BTreeMap<&'a str, u8>,
        stack: &mut Vec<&'a str>,
    ) -> Option<Vec<&'a str>> {
        colour.insert(n, 1);
        stack.push(n);
        for &m in &graph[n] {
            match colour.get(m).copied().unwrap_or(0) {
                1 => {
                    let start = stack.iter().position(|&s| s == m).unwrap();
                    let mut cycle = stack[start..].to_vec();
                    cycle.push(m);
                    return Some(cycle);
                }
                0 => {
                    if let Some(c) = visit(m, graph, colour, stack) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        stack.pop();
        colour.insert(n, 2);
        None
    }
    let mut colour = BTreeMap::new();
    for &n in graph.keys() {
        if colour.get(n).copied().unwrap_or(0) == 0 {
            if let Some(cycle) = visit(n, &graph, &mut colour, &mut Vec::new()) {
                let witness: Vec<String> = cycle
                    .windows(2)
                    .map(|w| {
                        let e = edges
                            .iter()
                            .find(|e| e.from == w[0] && e.to == w[1])
                            .unwrap();
                        format!("{} -> {} (src/{}:{})", w[0], w[1], e.file.display(), e.line)
                    })
                    .collect();
                panic!("import cycle between modules:\n{}", witness.join("\n"));
            }
        }
    }
}

#[test]
fn the_scanner_reads_groups_and_inline_paths() {
    assert_eq!(
        targets("use crate::{mesh::Mesh, diag};", "crate::"),
        ["mesh", "diag"]
    );
    assert_eq!(
        targets(
            "let g = crate::profile::span(crate::profile::Phase::Output);",
            "crate::"
        ),
        ["profile", "profile"]
    );
    assert!(targets("use my_crate::x;", "crate::").is_empty());
}
