//! `aster plot`: pictures of MED results checked pixel by pixel on tiny
//! generated results whose shape and values are known, a 3D quarter bar,
//! a result written by SALOME, and the errors of bad input.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::{Mutex, MutexGuard};

use aster::medio::{write_result_fields, ElemField, FieldStep, NodalField};
use aster::mesh::taylor::{generate, TaylorKind, TaylorParams};
use aster::mesh::{Cell, CellType, Mesh};
use aster::plot::history::history_points;
use aster::plot::{colour_at, draw_result, HistorySpec, PictureOptions, Plane, ResultData};
use indexmap::IndexMap;

/// HDF5 opens files without close-on-exec: a child started while another
/// test has a MED file open would inherit its lock (docs/post.md, testing
/// note). The tests take turns.
fn turn() -> MutexGuard<'static, ()> {
    static LOCK: Mutex<()> = Mutex::new(());
    LOCK.lock().unwrap_or_else(|e| e.into_inner())
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("aster_plot_{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

/// Decoded PNG: (width, height, RGB rows).
fn read_png(path: &Path) -> (u32, u32, Vec<[u8; 3]>) {
    let dec = png::Decoder::new(std::fs::File::open(path).unwrap());
    let mut reader = dec.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    let ch = info.color_type.samples();
    assert!(ch >= 3, "colour PNG expected, got {:?}", info.color_type);
    let px = buf[..info.buffer_size()]
        .chunks_exact(ch)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    (info.width, info.height, px)
}

/// A pixel of the colour map, not white, black or grey (text, edges, the
/// initial shape): its channels differ by more than any grey's.
fn coloured(p: [u8; 3]) -> bool {
    let max = p.iter().max().unwrap();
    let min = p.iter().min().unwrap();
    max - min > 90
}

/// Three QUAD4 cells in a row, 1 x 1 mm each; node 7 (3, 1) is group P1.
/// Two instants: 0 (at rest) and 1e-5 s, where DX = 0.5 x, DY = 0.2 y and
/// V1 of VARI_ELGA is 1, 2, 4 in the three cells.
const V1: [f64; 3] = [1.0, 2.0, 4.0];

fn row_mesh() -> Mesh {
    let mut coords = Vec::new();
    for y in [0.0, 1.0] {
        for x in [0.0, 1.0, 2.0, 3.0] {
            coords.push([x, y, 0.0]);
        }
    }
    let cells = (0..3)
        .map(|i| Cell {
            kind: CellType::Quad4,
            nodes: vec![i, i + 1, i + 5, i + 4],
        })
        .collect();
    let mut node_groups = IndexMap::new();
    node_groups.insert("P1".to_string(), vec![7]);
    node_groups.insert("BOTTOM".to_string(), vec![0, 1, 2, 3]);
    Mesh {
        name: "ROW".into(),
        dim: 2,
        coords,
        cells,
        cell_groups: IndexMap::new(),
        node_groups,
    }
}

fn row_displacement(p: [f64; 3]) -> [f64; 2] {
    [0.5 * p[0], 0.2 * p[1]]
}

fn write_row_result(path: &Path) -> Mesh {
    let mesh = row_mesh();
    let depl: Vec<f64> = mesh
        .coords
        .iter()
        .flat_map(|&p| row_displacement(p))
        .collect();
    let nodal = vec![NodalField {
        name: "RESU____DEPL".into(),
        components: vec!["DX".into(), "DY".into()],
        steps: vec![
            FieldStep {
                numdt: 0,
                time: 0.0,
                values: vec![0.0; depl.len()],
            },
            FieldStep {
                numdt: 1,
                time: 1e-5,
                values: depl,
            },
        ],
    }];
    let cells = vec![ElemField {
        name: "RESU____VARI_ELGA".into(),
        components: vec!["V1".into(), "V2".into()],
        steps: vec![
            FieldStep {
                numdt: 0,
                time: 0.0,
                values: vec![0.0; 6],
            },
            FieldStep {
                numdt: 1,
                time: 1e-5,
                values: V1.iter().flat_map(|&v| [v, 0.0]).collect(),
            },
        ],
    }];
    write_result_fields(path, &mesh, &nodal, &cells).unwrap();
    mesh
}

fn moved(p: [f64; 3]) -> [f64; 3] {
    let d = row_displacement(p);
    [p[0] + d[0], p[1] + d[1], p[2]]
}

#[test]
fn coloured_pixels_lie_in_the_deformed_shape_and_beyond_the_initial_one() {
    let _turn = turn();
    let rmed = tmp("row.rmed");
    let mesh = write_row_result(&rmed);
    let data = ResultData::read(&rmed, None).unwrap();
    let png = tmp("row.png");
    let r = draw_result(&data, &PictureOptions::default(), &png).unwrap();
    assert_eq!(r.component, "V1");
    assert!(r.field.ends_with("VARI_ELGA"));
    assert_eq!(r.time, 1e-5);
    assert_eq!(r.range, (1.0, 4.0));
    assert_eq!(r.faces, 3);

    let (w, h, px) = read_png(&png);
    assert_eq!((w, h), (1000, 800));
    // Pixel boxes of both shapes (model y up, image rows down).
    let bbox = |f: &dyn Fn([f64; 3]) -> [f64; 3]| {
        let pts: Vec<(f64, f64)> = mesh.coords.iter().map(|&p| r.to_pixel(f(p))).collect();
        let x0 = pts.iter().map(|p| p.0).fold(f64::INFINITY, f64::min);
        let x1 = pts.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max);
        let y0 = pts.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        let y1 = pts.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
        (x0, y0, x1, y1)
    };
    let def = bbox(&moved);
    let init = bbox(&|p| p);
    assert!(def.2 - init.2 > 100.0, "the mesh moved right by 1.5 mm");
    let (a0, a1, a2, a3) = r.mesh_area;
    let (mut n, mut beyond) = (0, 0);
    for y in a1..a3 {
        for x in a0..a2 {
            let p = px[(y as u32 * w + x as u32) as usize];
            if !coloured(p) {
                continue;
            }
            n += 1;
            let (xf, yf) = (f64::from(x), f64::from(y));
            assert!(
                xf >= def.0 - 1.5 && xf <= def.2 + 1.5 && yf >= def.1 - 1.5 && yf <= def.3 + 1.5,
                "coloured pixel ({x}, {y}) outside the deformed box {def:?}"
            );
            if xf > init.2 + 2.0 || yf < init.1 - 2.0 {
                beyond += 1;
            }
        }
    }
    // The deformed cells cover 4.5 x 1.2 mm at r.pixels_per_unit.
    let full = 4.5 * 1.2 * r.pixels_per_unit * r.pixels_per_unit;
    assert!(f64::from(n) > 0.95 * full, "{n} coloured pixels of {full}");
    assert!(
        beyond > 1000,
        "{beyond} coloured pixels beyond the initial shape"
    );
    // The colour bar, right of the mesh: low values at the bottom.
    let bar: Vec<[u8; 3]> = (a1..a3)
        .map(|y| px[(y as u32 * w + w - 155) as usize])
        .filter(|&p| coloured(p))
        .collect();
    assert!(bar.len() > 400, "colour bar of {} pixels", bar.len());
    // Its end rows (under the frame: one pixel in) hold the map's ends.
    let close = |p: [u8; 3], t: f64| {
        let c = colour_at(t);
        (0..3).all(|k| (i32::from(p[k]) - i32::from([c.0, c.1, c.2][k])).abs() <= 2)
    };
    assert!(close(bar[bar.len() - 1], 0.0), "{:?}", bar[bar.len() - 1]);
    assert!(close(bar[0], 1.0), "{:?}", bar[0]);
}

#[test]
fn each_cell_centre_has_the_colour_of_its_value() {
    let _turn = turn();
    let rmed = tmp("row_centres.rmed");
    let mesh = write_row_result(&rmed);
    let data = ResultData::read(&rmed, None).unwrap();
    let png = tmp("row_centres.png");
    let r = draw_result(&data, &PictureOptions::default(), &png).unwrap();
    let (w, _, px) = read_png(&png);
    for (c, v) in mesh.cells.iter().zip(V1) {
        let mut centre = [0.0; 3];
        for &n in &c.nodes {
            let q = moved(mesh.coords[n]);
            for k in 0..3 {
                centre[k] += q[k] / 4.0;
            }
        }
        let (x, y) = r.to_pixel(centre);
        let got = px[(y.round() as u32 * w + x.round() as u32) as usize];
        let want = colour_at((v - r.range.0) / (r.range.1 - r.range.0));
        assert_eq!(got, [want.0, want.1, want.2], "cell with V1 = {v}");
    }
}

#[test]
fn a_nodal_field_is_interpolated_and_an_earlier_instant_drawn() {
    let _turn = turn();
    let rmed = tmp("row_nodal.rmed");
    let mesh = write_row_result(&rmed);
    let data = ResultData::read(&rmed, None).unwrap();
    let png = tmp("row_nodal.png");
    let opts = PictureOptions {
        field: Some(("DEPL".into(), "DX".into())),
        ..PictureOptions::default()
    };
    let r = draw_result(&data, &opts, &png).unwrap();
    assert_eq!(r.range, (0.0, 1.5));
    let (w, _, px) = read_png(&png);
    // DX = 0.5 x is linear: the interpolated colour at a point of the
    // middle cell is the map at its initial x / 3 (to the step of a
    // SUBDIV piece: 1/6 of the cell's width at most).
    let p0 = [1.5, 0.5, 0.0];
    let (x, y) = r.to_pixel(moved(p0));
    let got = px[(y.round() as u32 * w + x.round() as u32) as usize];
    let near = |t: f64| {
        let c = colour_at(t);
        (i32::from(got[0]) - i32::from(c.0)).abs()
            + (i32::from(got[1]) - i32::from(c.1)).abs()
            + (i32::from(got[2]) - i32::from(c.2)).abs()
    };
    let best = (0..=1000)
        .map(|k| (f64::from(k) / 1000.0, near(f64::from(k) / 1000.0)))
        .min_by_key(|(_, d)| *d)
        .unwrap();
    assert!(best.1 <= 4, "pixel {got:?} is not a colour of the map");
    assert!(
        (best.0 - 0.5).abs() <= 0.1,
        "value {} at x = 1.5 mm, expected 0.5",
        best.0
    );

    // At instant 0 nothing has moved: the initial shape is drawn.
    let at0 = PictureOptions {
        inst: Some(0.0),
        ..PictureOptions::default()
    };
    let r0 = draw_result(&data, &at0, &png).unwrap();
    assert_eq!(r0.time, 0.0);
    assert!(r0.range.0 < 0.0 && r0.range.1 > 0.0, "V1 = 0 everywhere");
    let (w, _, px) = read_png(&png);
    let at = |p: [f64; 3]| {
        let (x, y) = r0.to_pixel(p);
        px[(y.round() as u32 * w + x.round() as u32) as usize]
    };
    assert!(coloured(at([2.95, 0.5, 0.0])));
    assert!(!coloured(at([3.05, 0.5, 0.0])));
    assert_eq!(mesh.coords[3], [3.0, 0.0, 0.0]);
}

#[test]
fn a_quarter_bar_gives_a_picture_in_its_symmetry_plane() {
    let _turn = turn();
    let mesh = generate(&TaylorParams {
        kind: TaylorKind::Quarter,
        n1: 2,
        n2: 4,
        n3: 2,
        linear: false,
    })
    .unwrap();
    // Shortened along z, bulged radially near the bottom; V1 grows to the foot.
    let zmax = mesh.coords.iter().map(|p| p[2]).fold(f64::MIN, f64::max);
    let depl: Vec<f64> = mesh
        .coords
        .iter()
        .flat_map(|p| {
            let f = 1.0 - p[2] / zmax;
            [0.3 * f * p[0], 0.3 * f * p[1], -0.1 * p[2]]
        })
        .collect();
    let v1: Vec<f64> = mesh
        .cells
        .iter()
        .map(|c| {
            let z = c.nodes.iter().map(|&n| mesh.coords[n][2]).sum::<f64>() / c.nodes.len() as f64;
            1.0 - z / zmax
        })
        .collect();
    let rmed = tmp("quarter.rmed");
    write_result_fields(
        &rmed,
        &mesh,
        &[NodalField {
            name: "RESU____DEPL".into(),
            components: vec!["DX".into(), "DY".into(), "DZ".into()],
            steps: vec![FieldStep {
                numdt: 1,
                time: 8e-5,
                values: depl,
            }],
        }],
        &[ElemField {
            name: "RESU____VARI_ELGA".into(),
            components: vec!["V1".into()],
            steps: vec![FieldStep {
                numdt: 1,
                time: 8e-5,
                values: v1,
            }],
        }],
    )
    .unwrap();
    let data = ResultData::read(&rmed, None).unwrap();
    let png = tmp("quarter.png");
    let r = draw_result(&data, &PictureOptions::default(), &png).unwrap();
    assert_eq!(r.plane, Plane::Xz);
    assert!(r.faces > 0);
    let (w, _, px) = read_png(&png);
    let (a0, a1, a2, a3) = r.mesh_area;
    let n = (a1..a3)
        .flat_map(|y| (a0..a2).map(move |x| (x, y)))
        .filter(|&(x, y)| coloured(px[(y as u32 * w + x as u32) as usize]))
        .count();
    // The section seen is about radius x height of the deformed bar.
    let section = 3.2 * 1.15 * 0.9 * zmax * r.pixels_per_unit * r.pixels_per_unit;
    assert!(
        n as f64 > 0.5 * section,
        "{n} coloured pixels, section {section}"
    );
}

#[test]
fn a_result_written_by_salome_draws_its_displacement() {
    let _turn = turn();
    let f = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/med/resu2d_depl.med");
    let data = ResultData::read(&f, None).unwrap();
    let png = tmp("salome.png");
    let r = draw_result(&data, &PictureOptions::default(), &png).unwrap();
    // No VARI_ELGA there: the norm of DEPL at the last instant (t = 2).
    assert_eq!(r.field, "DEPL");
    assert_eq!(r.time, 2.0);
    assert!(r.faces == 4, "the 4 QU8 are drawn, the SE3 edges not");
}

/// Adds to a result file a Gauss-point field as code_aster writes one
/// (`MAI.QU4` block with a localization, 4 points per cell, values
/// component-major, then cell by cell, the points of a cell together):
/// SIXX, SIYY = 10 k + cell + 0.1 point, so the cell means are
/// 10 k + cell + 0.15. With `profile` (1-based cell ranks), only those
/// cells get values, through `/PROFILS/<name>/PFL`.
fn add_gauss_field(path: &Path, name: &str, profile: Option<&[i64]>) {
    use hdf5::types::VarLenAscii;
    let file = hdf5::File::open_rw(path).unwrap();
    let s = |loc: &hdf5::Location, name: &str, v: &str| {
        loc.new_attr::<VarLenAscii>()
            .create(name)
            .unwrap()
            .write_scalar(&VarLenAscii::from_ascii(v).unwrap())
            .unwrap();
    };
    let i = |loc: &hdf5::Location, name: &str, v: i64| {
        loc.new_attr::<i64>()
            .create(name)
            .unwrap()
            .write_scalar(&v)
            .unwrap();
    };
    let f = file.group("CHA").unwrap().create_group(name).unwrap();
    s(&f, "MAI", "ROW");
    i(&f, "TYP", 6);
    i(&f, "NCO", 2);
    s(&f, "NOM", &format!("{:<16}{:<16}", "SIXX", "SIYY"));
    s(&f, "UNI", &" ".repeat(32));
    s(&f, "UNT", "");
    let st = f
        .create_group("0000000000000000000100000000000000000001")
        .unwrap();
    i(&st, "NDT", 1);
    i(&st, "NOR", -1);
    st.new_attr::<f64>()
        .create("PDT")
        .unwrap()
        .write_scalar(&1e-5)
        .unwrap();
    i(&st, "RDT", -1);
    i(&st, "ROR", -1);
    let cells: Vec<i64> = profile.map_or(vec![1, 2, 3], <[i64]>::to_vec);
    let pname = match profile {
        Some(p) => {
            let pname = format!("{name}_PFL");
            let pr = match file.group("PROFILS") {
                Ok(g) => g,
                Err(_) => file.create_group("PROFILS").unwrap(),
            };
            let g = pr.create_group(&pname).unwrap();
            i(&g, "NBR", p.len() as i64);
            g.new_dataset_builder().with_data(p).create("PFL").unwrap();
            pname
        }
        None => "MED_NO_PROFILE_INTERNAL".to_string(),
    };
    let b = st.create_group("MAI.QU4").unwrap();
    s(&b, "GAU", "ROW_QU4_FPG4");
    s(&b, "PFL", &pname);
    let pg = b.create_group(&pname).unwrap();
    i(&pg, "NBR", cells.len() as i64);
    i(&pg, "NGA", 4);
    s(&pg, "GAU", "ROW_QU4_FPG4");
    let mut co = Vec::new();
    for k in 0..2 {
        for c in &cells {
            for g in 0..4 {
                co.push(10.0 * f64::from(k) + (c - 1) as f64 + 0.1 * f64::from(g));
            }
        }
    }
    pg.new_dataset_builder()
        .with_data(&co)
        .create("CO")
        .unwrap();
}

#[test]
fn gauss_point_fields_are_drawn_as_their_mean_per_cell() {
    let _turn = turn();
    let rmed = tmp("row_gauss.rmed");
    write_row_result(&rmed);
    add_gauss_field(&rmed, "RESU____SIEF_ELGA", None);
    add_gauss_field(&rmed, "RESU____SIGM_ELGA", Some(&[1, 3]));
    // The cell-constant reader leaves Gauss fields out; the mean reader
    // gives one value per cell.
    let plain = aster::medio::read_elem_fields(&rmed, None).unwrap();
    assert!(plain.iter().all(|f| !f.name.ends_with("SIEF_ELGA")));
    let data = ResultData::read(&rmed, None).unwrap();
    let sief = data
        .cells
        .iter()
        .find(|f| f.name.ends_with("SIEF_ELGA"))
        .unwrap();
    assert_eq!(sief.components, vec!["SIXX", "SIYY"]);
    let want = [0.15, 10.15, 1.15, 11.15, 2.15, 12.15];
    for (got, want) in sief.steps[0].values.iter().zip(want) {
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
    }
    let png = tmp("row_gauss.png");
    let opts = PictureOptions {
        field: Some(("SIEF_ELGA".into(), "SIYY".into())),
        ..PictureOptions::default()
    };
    let r = draw_result(&data, &opts, &png).unwrap();
    assert!((r.range.0 - 10.15).abs() < 1e-12 && (r.range.1 - 12.15).abs() < 1e-12);

    // On a profile (cells 1 and 3): the middle cell has no value.
    let sigm = data
        .cells
        .iter()
        .find(|f| f.name.ends_with("SIGM_ELGA"))
        .unwrap();
    let v = &sigm.steps[0].values;
    for (got, want) in [(v[0], 0.15), (v[1], 10.15), (v[4], 2.15), (v[5], 12.15)] {
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
    }
    assert!(v[2].is_nan() && v[3].is_nan());
}

/// The row mesh translated rigidly by DX = A (1 + noise(x)), DY = 0, one
/// instant: |DEPL| is A up to `noise`.
const A: f64 = 3.99992152e-3;

fn write_translation(path: &Path, noise: &dyn Fn(f64) -> f64) -> Mesh {
    let mesh = row_mesh();
    let depl: Vec<f64> = mesh
        .coords
        .iter()
        .flat_map(|p| [A * (1.0 + noise(p[0])), 0.0])
        .collect();
    let nodal = vec![NodalField {
        name: "RESU____DEPL".into(),
        components: vec!["DX".into(), "DY".into()],
        steps: vec![FieldStep {
            numdt: 1,
            time: 1e-5,
            values: depl,
        }],
    }];
    write_result_fields(path, &mesh, &nodal, &[]).unwrap();
    mesh
}

/// The coloured pixels inside the drawing area (the colour bar is outside).
fn mesh_colours(r: &aster::plot::Rendered, png: &Path) -> Vec<[u8; 3]> {
    let (w, _, px) = read_png(png);
    let (l, t, rr, b) = r.mesh_area;
    let mut out = Vec::new();
    for y in t..b {
        for x in l..rr {
            let p = px[(y as u32 * w + x as u32) as usize];
            if coloured(p) {
                out.push(p);
            }
        }
    }
    out
}

/// A field whose range is round-off of its magnitude (q14: a rigid
/// translation, |DEPL| = 3.99992152e-3 to 1e-15 relative) is drawn in one
/// colour, the bar's single label giving the value; a narrow but real
/// range (1e-6 relative) keeps the colour scale, its six labels distinct
/// and each within a tenth of a step of the value it marks.
#[test]
fn a_uniform_field_is_one_colour_and_a_narrow_range_has_distinct_labels() {
    let _turn = turn();
    let rmed = tmp("uniform.rmed");
    // Round-off: +-2 ulp alternating along x.
    write_translation(&rmed, &|x| if (x as i64) % 2 == 0 { 4e-16 } else { -4e-16 });
    let data = ResultData::read(&rmed, None).unwrap();
    let png = tmp("uniform.png");
    let r = draw_result(&data, &PictureOptions::default(), &png).unwrap();
    assert_eq!(r.component, "|DX,DY|");
    let v = r.uniform.expect("drawn as uniform");
    assert!((v - A).abs() <= 1e-14 * A, "{v}");
    assert_eq!(r.bar_labels, ["0.00399992152"]);
    let colours = mesh_colours(&r, &png);
    let mid = colour_at(0.5);
    assert!(colours.len() > 10_000, "{} coloured pixels", colours.len());
    assert!(
        colours.iter().all(|&p| p == [mid.0, mid.1, mid.2]),
        "{} pixels of {} are not the middle colour",
        colours
            .iter()
            .filter(|&&p| p != [mid.0, mid.1, mid.2])
            .count(),
        colours.len()
    );

    // 1e-6 relative along x: a real gradient, drawn as one.
    let rmed = tmp("narrow.rmed");
    write_translation(&rmed, &|x| 1e-6 * x / 3.0);
    let data = ResultData::read(&rmed, None).unwrap();
    let png = tmp("narrow.png");
    let r = draw_result(&data, &PictureOptions::default(), &png).unwrap();
    assert!(r.uniform.is_none());
    let (lo, hi) = r.range;
    assert!((lo - A).abs() <= 1e-15 && (hi - A * (1.0 + 1e-6)).abs() <= 1e-15);
    assert_eq!(r.bar_labels.len(), 6);
    for (k, l) in r.bar_labels.iter().enumerate() {
        assert!(k == 0 || r.bar_labels[k - 1] != *l, "{:?}", r.bar_labels);
        let at = lo + (hi - lo) * k as f64 / 5.0;
        let back: f64 = l.parse().unwrap();
        assert!((back - at).abs() <= 0.1 * (hi - lo) / 5.0, "{l} for {at}");
    }
    let colours = mesh_colours(&r, &png);
    let blue = colour_at(0.0);
    let red = colour_at(1.0);
    let near = |p: [u8; 3], c: plotters::style::RGBColor| {
        (i32::from(p[0]) - i32::from(c.0)).abs()
            + (i32::from(p[1]) - i32::from(c.1)).abs()
            + (i32::from(p[2]) - i32::from(c.2)).abs()
            <= 60
    };
    assert!(colours.iter().any(|&p| near(p, blue)) && colours.iter().any(|&p| near(p, red)));
}

fn aster(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_aster"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn bad_input_gives_a_clear_error_and_exit_code_1() {
    let _turn = turn();
    let text = tmp("not_med.rmed");
    std::fs::write(&text, "DEBUT()\nFIN()\n").unwrap();
    let (code, _, err) = aster(&["plot", text.to_str().unwrap()]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("not an HDF5 file"), "{err}");

    let rmed = tmp("row_bad.rmed");
    write_row_result(&rmed);
    let r = rmed.to_str().unwrap();
    let (code, _, err) = aster(&["plot", r, "--field", "SIEF_ELGA:SIXX"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("no field 'SIEF_ELGA'"), "{err}");
    assert!(
        err.contains("RESU____DEPL: at nodes, components DX DY"),
        "{err}"
    );
    assert!(
        err.contains("RESU____VARI_ELGA: per cell, components V1 V2"),
        "{err}"
    );

    let (code, _, err) = aster(&["plot", r, "--field", "DEPL:DZ"]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("no component 'DZ'") && err.contains("DX DY"),
        "{err}"
    );

    let (code, _, err) = aster(&["plot", r, "--inst", "5e-6"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("no instant 5e-6"), "{err}");
    assert!(
        err.contains("0e0 1e-5"),
        "the instants of the file are listed: {err}"
    );

    let (code, _, err) = aster(&["plot", r, "--history", "BOTTOM:DEPL:DX"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("holds 4 nodes"), "{err}");
}

#[test]
fn the_command_writes_the_picture_where_asked() {
    let _turn = turn();
    let rmed = tmp("row_cli.rmed");
    write_row_result(&rmed);
    let png = tmp("row_cli.png");
    let (code, out, err) = aster(&[
        "plot",
        rmed.to_str().unwrap(),
        "--deform",
        "2",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("V1"), "{out}");
    let (w, h, _) = read_png(&png);
    assert_eq!((w, h), (1000, 800));
}

#[test]
fn history_curves_follow_the_node_of_the_group() {
    let _turn = turn();
    let rmed = tmp("row_hist.rmed");
    let mesh = write_row_result(&rmed);
    let data = ResultData::read(&rmed, None).unwrap();
    let spec = HistorySpec::parse("P1:DEPL:DX").unwrap();
    let pts = history_points(&data, &spec).unwrap();
    let dx = row_displacement(mesh.coords[7])[0];
    assert_eq!(pts, vec![(0.0, 0.0), (1e-5, dx)]);

    let png = tmp("row_hist.png");
    let (code, out, err) = aster(&[
        "plot",
        rmed.to_str().unwrap(),
        "--history",
        "P1:DEPL:DX",
        "--history",
        "P1:DEPL:DY",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("2 curves, 4 points"), "{out}");
    let (w, h, px) = read_png(&png);
    assert_eq!((w, h), (1000, 650));
    assert!(px.iter().any(|&p| coloured(p)), "the curves are drawn");
}
