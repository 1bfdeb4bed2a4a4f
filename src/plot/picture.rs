//! The picture of one instant: the deformed mesh filled by a field, over
//! the initial shape in grey, with a colour bar.
//!
//! Cell fields colour each polygon flat; nodal fields are interpolated
//! linearly over small triangles (a fan from the polygon's centroid, each
//! fan triangle cut in [`SUBDIV`]² pieces coloured at their centroid), so a
//! smooth field looks smooth without a shading backend. Drawn with plotters'
//! bitmap backend in pixel coordinates: the mesh keeps its true aspect
//! ratio, which a chart's axes would not guarantee.

use std::path::Path;

use plotters::prelude::*;

use super::data::{unit_of, Component, FieldChoice, ResultData};
use super::geometry::{self, Face, Plane};
use crate::sweep::plot::{ensure_font, tick_label, FONT};

/// A field whose values differ by at most this fraction of their largest
/// magnitude is drawn as uniform: a rigid translation's |DEPL| varies by
/// ~1e-15 relative from round-off alone, which the colour scale would
/// otherwise stretch into a patchwork. A billionth of a field's magnitude
/// is far below what a colour can show, and far above f64 round-off.
pub const UNIFORM_RTOL: f64 = 1e-9;
/// Number of intervals of the colour bar (labels: one more).
const BAR_STEPS: usize = 5;

/// Pieces per side of each fan triangle when interpolating a nodal field.
const SUBDIV: usize = 3;
/// Colour of the initial shape.
pub const INITIAL_GREY: RGBColor = RGBColor(214, 214, 214);
/// Colour of a cell without a value (NaN: a field absent on that cell).
pub const NO_VALUE_GREY: RGBColor = RGBColor(160, 160, 160);
const EDGE: RGBColor = RGBColor(60, 60, 60);

/// What to draw; `None` means the default documented on `aster plot`.
#[derive(Debug, Clone)]
pub struct PictureOptions {
    /// Field name and component (or NORM).
    pub field: Option<(String, String)>,
    pub inst: Option<f64>,
    pub deform: Option<f64>,
    pub plane: Option<Plane>,
    /// Image size in pixels.
    pub size: (u32, u32),
}

impl Default for PictureOptions {
    fn default() -> Self {
        PictureOptions {
            field: None,
            inst: None,
            deform: None,
            plane: None,
            size: (1000, 800),
        }
    }
}

/// What was drawn and where: enough to find a point of the model in the
/// image (tests read pixels through it).
#[derive(Debug, Clone)]
pub struct Rendered {
    pub field: String,
    pub component: String,
    pub time: f64,
    /// The values at the two ends of the colour bar.
    pub range: (f64, f64),
    pub deform: f64,
    pub plane: Plane,
    /// Pixels per model length unit (mm).
    pub pixels_per_unit: f64,
    /// Model point (horizontal, vertical) drawn at pixel `origin_px`.
    origin: [f64; 2],
    origin_px: (f64, f64),
    /// The part of the image the mesh is drawn in: (left, top, right, bottom).
    pub mesh_area: (i32, i32, i32, i32),
    /// Polygons painted (cells, or skin faces in 3D).
    pub faces: usize,
    /// The value of a field drawn as uniform (its range is round-off of its
    /// magnitude, see [`UNIFORM_RTOL`]): one colour, one label.
    pub uniform: Option<f64>,
    /// The labels of the colour bar, bottom to top.
    pub bar_labels: Vec<String>,
}

impl Rendered {
    /// Pixel (column, row) of a model point.
    pub fn to_pixel(&self, p: [f64; 3]) -> (f64, f64) {
        let q = self.plane.project(p);
        (
            self.origin_px.0 + self.pixels_per_unit * (q[0] - self.origin[0]),
            self.origin_px.1 - self.pixels_per_unit * (q[1] - self.origin[1]),
        )
    }
}

/// The colour map, blue (low) through cyan, green, yellow to red (high),
/// the fringe colours of impact codes; `t` in [0, 1] (clamped).
pub fn colour_at(t: f64) -> RGBColor {
    const STOPS: [(f64, [f64; 3]); 5] = [
        (0.0, [20.0, 40.0, 200.0]),
        (0.25, [0.0, 170.0, 240.0]),
        (0.5, [40.0, 190.0, 60.0]),
        (0.75, [245.0, 210.0, 0.0]),
        (1.0, [215.0, 25.0, 25.0]),
    ];
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let k = STOPS
        .windows(2)
        .position(|w| t <= w[1].0)
        .unwrap_or(STOPS.len() - 2);
    let (t0, a) = STOPS[k];
    let (t1, b) = STOPS[k + 1];
    let s = (t - t0) / (t1 - t0);
    let c = |i: usize| (a[i] + s * (b[i] - a[i])).round() as u8;
    RGBColor(c(0), c(1), c(2))
}

/// The labels of `steps + 1` evenly spaced values from `lo` to `hi`, with
/// the fewest significant digits (3 at least) that tell each one from its
/// neighbours: a narrow range around a large value (0.0040000 to
/// 0.0040004) needs more than the 3 digits that would print "0.004" six
/// times. A value that is round-off of zero (|v| below 1e-12 of the
/// range's magnitude) is labelled 0.
pub fn bar_labels(lo: f64, hi: f64, steps: usize) -> Vec<String> {
    let magnitude = lo.abs().max(hi.abs());
    let values: Vec<f64> = (0..=steps)
        .map(|k| {
            let v = lo + (hi - lo) * k as f64 / steps.max(1) as f64;
            if v.abs() <= 1e-12 * magnitude {
                0.0
            } else {
                v
            }
        })
        .collect();
    let mut labels = Vec::new();
    for digits in 3..=17 {
        labels = values.iter().map(|&v| significant(v, digits)).collect();
        if labels.windows(2).all(|w| w[0] != w[1]) {
            break;
        }
    }
    labels
}

/// `x` with `digits` significant digits, trailing zeros dropped; fixed
/// notation from 1e-3 to 1e4, else scientific. With 3 digits this is the
/// sweep plots' tick label.
pub fn significant(x: f64, digits: usize) -> String {
    if digits <= 3 {
        return tick_label(x, false);
    }
    if x == 0.0 || !x.is_finite() {
        return if x == 0.0 { "0".into() } else { format!("{x}") };
    }
    let trim = |s: &str| {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    };
    if x.abs() >= 1e4 || x.abs() < 1e-3 {
        let s = format!("{x:.prec$e}", prec = digits - 1);
        let (mantissa, exp) = s.split_once('e').unwrap_or((s.as_str(), "0"));
        return format!("{}e{exp}", trim(mantissa));
    }
    let decimals = (digits as i32 - 1 - x.abs().log10().floor() as i32).max(0) as usize;
    trim(&format!("{x:.decimals$}"))
}

/// The field's code_aster name without the 8-character result prefix
/// (`RESU____VARI_ELGA`, `RESU_MANDEPL` -> `VARI_ELGA`, `DEPL`).
fn short_name(name: &str) -> &str {
    let n = name.trim_end();
    if n.len() <= 8 || !n.is_char_boundary(8) {
        return n;
    }
    let rest = &n[8..];
    let known = ["DEPL", "VITE", "ACCE"].contains(&rest)
        || ["_ELGA", "_ELNO", "_NOEU", "_ELEM", "_NODA"]
            .iter()
            .any(|s| rest.ends_with(s));
    if known {
        rest
    } else {
        n
    }
}

/// Draws the picture of `data` into `out` (PNG).
pub fn draw_result(
    data: &ResultData,
    opts: &PictureOptions,
    out: &Path,
) -> Result<Rendered, String> {
    let (field, comp): (FieldChoice, Component) = match &opts.field {
        Some((name, c)) => {
            let f = data.field(name)?;
            let c = f.component(c)?;
            (f, c)
        }
        None => data.default_field()?,
    };
    let step = field.step_at(opts.inst)?;
    let time = field.steps()[step].time;
    let values = field.scalar(step, comp);

    let mesh = &data.mesh;
    let depl = data.displacement();
    let scale = match (opts.deform, depl) {
        (Some(s), Some(_)) => s,
        (Some(_), None) => {
            return Err(format!(
                "--deform needs the displacement (DEPL) and the file has none; {}",
                data.holds()
            ))
        }
        (None, Some(_)) => 1.0,
        (None, None) => 0.0,
    };
    let moved = match depl {
        Some(d) if scale != 0.0 => {
            let dc = FieldChoice::Nodal(d);
            let k = dc
                .step_at(Some(time))
                .map_err(|e| format!("the displacement is needed at the instant drawn: {e}"))?;
            geometry::deformed(&mesh.coords, &d.steps[k].values, &d.components, scale)
        }
        _ => mesh.coords.clone(),
    };

    let volume = geometry::is_volume(mesh);
    let plane = match (volume, opts.plane) {
        (true, p) => p.unwrap_or(Plane::Xz),
        (false, None | Some(Plane::Xy)) => Plane::Xy,
        (false, Some(p)) => {
            return Err(format!(
                "the mesh is plane (no volume cell): it is drawn in its own xy plane, \
                 --plane {} applies to 3D meshes",
                p.name()
            ))
        }
    };
    let mut initial = geometry::faces(mesh);
    if initial.is_empty() {
        return Err(format!(
            "nothing to draw: mesh '{}' has no surface or volume cell",
            mesh.name
        ));
    }
    let mut faces = initial.clone();
    geometry::painter_order(&mut initial, &mesh.coords, plane);
    geometry::painter_order(&mut faces, &moved, plane);

    // The colour range over what is drawn.
    let shown = |f: &Face| -> Vec<f64> {
        if field.is_nodal() {
            f.nodes.iter().map(|&n| values[n]).collect()
        } else {
            vec![values[f.cell]]
        }
    };
    let (lo, hi) = faces
        .iter()
        .flat_map(shown)
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if lo > hi {
        return Err(format!(
            "field {} {} has no value on the drawn cells at instant {time:e}",
            field.name(),
            field.component_name(comp)
        ));
    }
    let uniform = (hi - lo <= UNIFORM_RTOL * lo.abs().max(hi.abs())).then_some(0.5 * (lo + hi));
    let (lo, hi) = match uniform {
        None => (lo, hi),
        Some(m) => {
            let pad = 1e-3 * m.abs().max(1e-12);
            (m - pad, m + pad)
        }
    };
    let labels = match uniform {
        None => bar_labels(lo, hi, BAR_STEPS),
        Some(m) => vec![significant(m, 10)],
    };

    // Placement: the union of both shapes, fitted with its aspect ratio.
    let (w, h) = opts.size;
    if w < 300 || h < 200 {
        return Err(format!(
            "picture of {w} x {h} pixels is too small (300 x 200 at least)"
        ));
    }
    let area = (20, 78, w as i32 - 200, h as i32 - 44);
    let mut bb = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for (set, coords) in [(&initial, &mesh.coords), (&faces, &moved)] {
        for f in set.iter() {
            for &n in &f.nodes {
                let q = plane.project(coords[n]);
                bb = [
                    bb[0].min(q[0]),
                    bb[1].min(q[1]),
                    bb[2].max(q[0]),
                    bb[3].max(q[1]),
                ];
            }
        }
    }
    let span = ((bb[2] - bb[0]).max(1e-12), (bb[3] - bb[1]).max(1e-12));
    let aw = f64::from(area.2 - area.0);
    let ah = f64::from(area.3 - area.1);
    let ppu = (aw / span.0).min(ah / span.1);
    let origin = [bb[0], bb[1]];
    let origin_px = (
        f64::from(area.0) + 0.5 * (aw - ppu * span.0),
        f64::from(area.3) - 0.5 * (ah - ppu * span.1),
    );
    let rendered = Rendered {
        field: field.name().to_string(),
        component: field.component_name(comp),
        time,
        range: (lo, hi),
        deform: scale,
        plane,
        pixels_per_unit: ppu,
        origin,
        origin_px,
        mesh_area: area,
        faces: faces.len(),
        uniform,
        bar_labels: labels,
    };
    let px = |p: [f64; 3]| {
        let (x, y) = rendered.to_pixel(p);
        (x.round() as i32, y.round() as i32)
    };
    // A uniform field is the middle colour everywhere, whatever its noise.
    let norm = |v: f64| {
        if uniform.is_some() {
            0.5
        } else {
            (v - lo) / (hi - lo)
        }
    };

    ensure_font()?;
    let err = |e: &dyn std::fmt::Display| format!("picture '{}': {e}", out.display());
    let root = BitMapBackend::new(out, (w, h)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;

    // The initial shape, flat grey.
    for f in &initial {
        let pts: Vec<(i32, i32)> = f.nodes.iter().map(|&n| px(mesh.coords[n])).collect();
        root.draw(&Polygon::new(pts.clone(), INITIAL_GREY.filled()))
            .map_err(|e| err(&e))?;
        let mut ring = pts;
        ring.push(ring[0]);
        root.draw(&PathElement::new(ring, RGBColor(175, 175, 175)))
            .map_err(|e| err(&e))?;
    }
    // The deformed shape, coloured.
    for f in &faces {
        let pts: Vec<(i32, i32)> = f.nodes.iter().map(|&n| px(moved[n])).collect();
        if field.is_nodal() {
            let vals: Vec<f64> = f.nodes.iter().map(|&n| values[n]).collect();
            let corners: Vec<[f64; 3]> = f.nodes.iter().map(|&n| moved[n]).collect();
            for (tri, v) in fan_pieces(&corners, &vals) {
                let c = if v.is_finite() {
                    colour_at(norm(v))
                } else {
                    NO_VALUE_GREY
                };
                let tp: Vec<(i32, i32)> = tri.iter().map(|&p| px(p)).collect();
                root.draw(&Polygon::new(tp, c.filled()))
                    .map_err(|e| err(&e))?;
            }
        } else {
            let v = values[f.cell];
            let c = if v.is_finite() {
                colour_at(norm(v))
            } else {
                NO_VALUE_GREY
            };
            root.draw(&Polygon::new(pts.clone(), c.filled()))
                .map_err(|e| err(&e))?;
        }
        let mut ring = pts;
        ring.push(ring[0]);
        root.draw(&PathElement::new(ring, EDGE.mix(0.55)))
            .map_err(|e| err(&e))?;
    }

    // Titles.
    let name = short_name(field.name());
    let unit = unit_of(field.name());
    let unit_txt = if unit.is_empty() {
        String::new()
    } else {
        format!(" ({unit})")
    };
    let title = format!(
        "{name} {}{}  at t = {}",
        rendered.component,
        if field.is_nodal() { "" } else { " per cell" },
        time_text(time)
    );
    let (hx, vy) = plane.axis_names();
    let sub = format!(
        "{}  -  mesh {}, {}  -  {}",
        data.path
            .file_name()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or_default(),
        mesh.name,
        if scale == 0.0 {
            "initial shape (no displacement in the file)".to_string()
        } else if scale == 1.0 {
            "true deformed shape".to_string()
        } else {
            format!("displacement x {}", tick_label(scale, false))
        },
        if volume {
            format!("skin seen in the {hx}{vy} plane ({hx} right, {vy} up), initial shape in grey")
        } else {
            format!("{hx} right, {vy} up, initial shape in grey")
        }
    );
    root.draw(&Text::new(
        title,
        (20, 14),
        (FONT, 24).into_font().color(&BLACK),
    ))
    .map_err(|e| err(&e))?;
    root.draw(&Text::new(
        sub,
        (20, 46),
        (FONT, 14).into_font().color(&BLACK),
    ))
    .map_err(|e| err(&e))?;

    // Colour bar.
    let (bx0, bx1) = (w as i32 - 170, w as i32 - 140);
    let (by0, by1) = (area.1 + 30, area.3 - 10);
    for y in by0..=by1 {
        let t = f64::from(by1 - y) / f64::from(by1 - by0);
        let c = colour_at(if uniform.is_some() { 0.5 } else { t });
        for x in bx0..=bx1 {
            root.draw_pixel((x, y), &c).map_err(|e| err(&e))?;
        }
    }
    root.draw(&Rectangle::new([(bx0, by0), (bx1, by1)], BLACK))
        .map_err(|e| err(&e))?;
    let nl = rendered.bar_labels.len();
    for (k, label) in rendered.bar_labels.iter().enumerate() {
        // One label (uniform) sits at the middle, several span the bar.
        let t = if nl == 1 {
            0.5
        } else {
            k as f64 / (nl - 1) as f64
        };
        let y = by1 - (f64::from(by1 - by0) * t).round() as i32;
        root.draw(&PathElement::new(vec![(bx1, y), (bx1 + 5, y)], BLACK))
            .map_err(|e| err(&e))?;
        root.draw(&Text::new(
            label.as_str(),
            (bx1 + 9, y - 8),
            (FONT, 15).into_font().color(&BLACK),
        ))
        .map_err(|e| err(&e))?;
    }
    if uniform.is_some() {
        let y = (by0 + by1) / 2;
        root.draw(&Text::new(
            "(uniform)",
            (bx1 + 9, y + 10),
            (FONT, 15).into_font().color(&BLACK),
        ))
        .map_err(|e| err(&e))?;
    }
    root.draw(&Text::new(
        format!("{name} {}{unit_txt}", rendered.component),
        (bx0 - 20, by0 - 26),
        (FONT, 15).into_font().color(&BLACK),
    ))
    .map_err(|e| err(&e))?;

    // Length scale: a round length near a quarter of the drawing's width.
    let target = 0.25 * span.0.max(span.1);
    let mag = 10f64.powf(target.log10().floor());
    let len = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .rfind(|l| *l <= target)
        .unwrap_or(mag);
    let (sx, sy) = (area.0 + 10, h as i32 - 20);
    let sl = (len * ppu).round() as i32;
    root.draw(&PathElement::new(
        vec![(sx, sy), (sx + sl, sy)],
        BLACK.stroke_width(3),
    ))
    .map_err(|e| err(&e))?;
    root.draw(&Text::new(
        format!("{} mm", tick_label(len, false)),
        (sx + sl + 8, sy - 9),
        (FONT, 14).into_font().color(&BLACK),
    ))
    .map_err(|e| err(&e))?;

    root.present().map_err(|e| err(&e))?;
    Ok(rendered)
}

/// An instant as text, in seconds with the microsecond shown when small.
fn time_text(t: f64) -> String {
    if t != 0.0 && t.abs() < 1e-2 {
        format!("{} us ({t:e} s)", tick_label(t * 1e6, false))
    } else {
        format!("{} s", tick_label(t, false))
    }
}

/// The small triangles of a polygon with values at its corners, each with
/// the linearly interpolated value at its centroid: a fan from the
/// polygon's centroid (value: the corners' mean), each fan triangle cut
/// in SUBDIV² pieces.
fn fan_pieces(corners: &[[f64; 3]], vals: &[f64]) -> Vec<([[f64; 3]; 3], f64)> {
    let n = corners.len() as f64;
    let mut c = [0.0; 3];
    for p in corners {
        for k in 0..3 {
            c[k] += p[k] / n;
        }
    }
    let vc = vals.iter().sum::<f64>() / n;
    let mut out = Vec::new();
    let s = SUBDIV as f64;
    for i in 0..corners.len() {
        let j = (i + 1) % corners.len();
        let (a, b) = (corners[i], corners[j]);
        let (va, vb) = (vals[i], vals[j]);
        // Barycentric grid on (centroid, a, b).
        let at = |u: f64, v: f64| -> ([f64; 3], f64) {
            let w = 1.0 - u - v;
            let mut p = [0.0; 3];
            for k in 0..3 {
                p[k] = w * c[k] + u * a[k] + v * b[k];
            }
            (p, w * vc + u * va + v * vb)
        };
        for r in 0..SUBDIV {
            for q in 0..SUBDIV - r {
                let (u0, v0) = (r as f64 / s, q as f64 / s);
                let d = 1.0 / s;
                let tris = [
                    [(u0, v0), (u0 + d, v0), (u0, v0 + d)],
                    [(u0 + d, v0), (u0 + d, v0 + d), (u0, v0 + d)],
                ];
                for (k, t) in tris.iter().enumerate() {
                    if k == 1 && r + q + 1 >= SUBDIV {
                        continue;
                    }
                    let pts = [at(t[0].0, t[0].1), at(t[1].0, t[1].1), at(t[2].0, t[2].1)];
                    let (gu, gv) = (
                        (t[0].0 + t[1].0 + t[2].0) / 3.0,
                        (t[0].1 + t[1].1 + t[2].1) / 3.0,
                    );
                    out.push(([pts[0].0, pts[1].0, pts[2].0], at(gu, gv).1));
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_map_ends_and_middle() {
        assert_eq!(colour_at(0.0), RGBColor(20, 40, 200));
        assert_eq!(colour_at(1.0), RGBColor(215, 25, 25));
        assert_eq!(colour_at(0.5), RGBColor(40, 190, 60));
        assert_eq!(colour_at(2.0), colour_at(1.0));
    }

    #[test]
    fn bar_labels_have_the_digits_that_tell_them_apart() {
        // A wide range keeps the 3-digit labels.
        assert_eq!(
            bar_labels(0.0, 1.5, 5),
            ["0", "0.3", "0.6", "0.9", "1.2", "1.5"]
        );
        // q14: 0.004 to 0.004 (1 + 1e-6): six distinct labels, each within
        // a tenth of a step of its value.
        let (lo, hi) = (3.99992152e-3, 3.99992152e-3 * (1.0 + 1e-6));
        let labels = bar_labels(lo, hi, 5);
        for (k, l) in labels.iter().enumerate() {
            let v = lo + (hi - lo) * k as f64 / 5.0;
            let back: f64 = l.parse().unwrap();
            assert!((back - v).abs() <= 0.1 * (hi - lo) / 5.0, "{l} for {v}");
        }
        assert!(labels.windows(2).all(|w| w[0] != w[1]), "{labels:?}");
        // A zero crossed by the range is 0, not its round-off 5.55e-17.
        let (lo, hi) = (std::hint::black_box(-0.412), 0.618);
        assert!(lo + (hi - lo) * 2.0 / 5.0 != 0.0);
        assert_eq!(bar_labels(-0.412, 0.618, 5)[2], "0");
        // Large and small magnitudes in scientific notation.
        assert_eq!(significant(123456.0, 5), "1.2346e5");
        assert_eq!(significant(1.5e-7, 6), "1.5e-7");
        assert_eq!(significant(0.00399992152, 10), "0.00399992152");
    }

    #[test]
    fn fan_pieces_cover_the_polygon_with_interpolated_values() {
        // Unit square, value = x: every piece's value is its centroid's x.
        let sq = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let vals = [0.0, 1.0, 1.0, 0.0];
        let pieces = fan_pieces(&sq, &vals);
        assert_eq!(pieces.len(), 4 * SUBDIV * SUBDIV);
        let mut area = 0.0;
        for (t, v) in &pieces {
            let cx = (t[0][0] + t[1][0] + t[2][0]) / 3.0;
            assert!((v - cx).abs() < 1e-12, "{v} vs {cx}");
            area += 0.5
                * ((t[1][0] - t[0][0]) * (t[2][1] - t[0][1])
                    - (t[2][0] - t[0][0]) * (t[1][1] - t[0][1]))
                    .abs();
        }
        assert!((area - 1.0).abs() < 1e-12);
    }
}
